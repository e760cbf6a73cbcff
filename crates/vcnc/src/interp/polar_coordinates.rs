//! G16/G15: polar coordinate command (spec iso-syntec-milling.md 1.14).
//!
//! In G16 the first axis word of the selected plane is a radius and the second an angle in
//! degrees, counter-clockwise positive, about the program origin. A word left out keeps its polar
//! value (not its Cartesian one). In G91 radius and angle add to the previous point's. Other
//! words (I J K, R, the third axis) are not converted.

use super::decode::Command;
use super::exec::Executor;
use super::modal::DistanceMode;
use crate::machine::Axis;

/// The radius and angle (degrees) of the last polar point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PolarPoint {
    pub(crate) radius: f64,
    pub(crate) degrees: f64,
}

/// G16: polar mode on, starting from the polar values of the current position.
pub(crate) fn g16(exec: &mut Executor) {
    let (a, b, _) = exec.modal.plane.axes();
    let here = exec.kernel.program_position();
    exec.polar = Some(PolarPoint {
        radius: here[a].hypot(here[b]),
        degrees: here[b].atan2(here[a]).to_degrees(),
    });
}

/// G15: polar mode off.
pub(crate) fn g15(polar: &mut Option<PolarPoint>) {
    *polar = None;
}

/// The polar point a block in G16 programs, when it has a word of the plane: the radius from the
/// plane's first axis word, the angle from the second's, the others kept.
#[inline(always)]
pub(crate) fn point(exec: &Executor, cmd: &Command) -> Option<PolarPoint> {
    // Out of G16, the common case, this is one test in the caller.
    let previous = exec.polar?;
    point_from(exec, cmd, previous)
}

/// [`point`] in G16, from the previous polar point.
#[inline(never)]
fn point_from(exec: &Executor, cmd: &Command, previous: PolarPoint) -> Option<PolarPoint> {
    let (a, b, _) = exec.modal.plane.axes();
    let radius_word = cmd.axis(a);
    let angle_word = cmd.axis(b);
    if radius_word.is_none() && angle_word.is_none() {
        return None;
    }
    let radius = radius_word.map(|v| exec.axis_value(Axis::ALL[a], &v));
    // An angle, whatever the plane's axis is.
    let degrees = angle_word.map(|v| exec.kernel.setup.angle(&v));
    Some(match exec.modal.distance {
        DistanceMode::Absolute => PolarPoint {
            radius: radius.unwrap_or(previous.radius),
            degrees: degrees.unwrap_or(previous.degrees),
        },
        DistanceMode::Incremental => PolarPoint {
            radius: previous.radius + radius.unwrap_or(0.0),
            degrees: previous.degrees + degrees.unwrap_or(0.0),
        },
    })
}

/// The Cartesian coordinates of the plane's two axes for a polar point.
pub(crate) fn cartesian(point: PolarPoint) -> (f64, f64) {
    let (sin, cos) = super::frames::sin_cos_degrees(point.degrees);
    (point.radius * cos, point.radius * sin)
}
