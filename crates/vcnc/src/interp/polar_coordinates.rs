//! G16/G15: polar coordinate command (spec iso-syntec-milling.md 1.14).
//!
//! In G16 the first axis word of the selected plane is a radius and the second an angle in
//! degrees, counter-clockwise positive, about the pole: the program origin. A word left out keeps
//! its polar value (not its Cartesian one). G91 as the profile says (`polar_increments`): on
//! Syntec radius and angle add to the previous point's; on a FANUC a radius in G91 is measured
//! from the current position, which becomes the pole, and an angle adds to the previous one.
//! Other words (I J K, R, the third axis) are not converted.

use super::decode::Command;
use super::exec::Executor;
use super::modal::DistanceMode;
use crate::machine::Axis;
use crate::profile::PolarIncrements;

/// The radius and angle (degrees) of the last polar point, and the pole they are measured from:
/// the plane's two coordinates of the current position where a FANUC's G91 put it, else (None)
/// the program origin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PolarPoint {
    pub(crate) radius: f64,
    pub(crate) degrees: f64,
    pub(crate) pole: Option<(f64, f64)>,
}

/// G16: polar mode on, starting from the polar values of the current position.
pub(crate) fn g16(exec: &mut Executor) {
    let (a, b, _) = exec.modal.plane.axes();
    let here = exec.kernel.program_position();
    exec.polar = Some(PolarPoint {
        radius: here[a].hypot(here[b]),
        degrees: here[b].atan2(here[a]).to_degrees(),
        pole: None,
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
    let rule = exec.kernel.setup.profile().coordinates.polar_increments;
    Some(match (exec.modal.distance, rule) {
        (DistanceMode::Absolute, _) => PolarPoint {
            radius: radius.unwrap_or(previous.radius),
            degrees: degrees.unwrap_or(previous.degrees),
            // A radius in G90 is measured from the program origin; a block without one keeps
            // the pole its radius was measured from.
            pole: radius.map_or(previous.pole, |_| None),
        },
        (DistanceMode::Incremental, PolarIncrements::AddToPreviousPoint) => PolarPoint {
            radius: previous.radius + radius.unwrap_or(0.0),
            degrees: previous.degrees + degrees.unwrap_or(0.0),
            pole: previous.pole,
        },
        (DistanceMode::Incremental, PolarIncrements::PoleAtCurrentPosition) => {
            let here = exec.kernel.program_position();
            PolarPoint {
                radius: radius.unwrap_or(previous.radius),
                degrees: previous.degrees + degrees.unwrap_or(0.0),
                pole: radius.map_or(previous.pole, |_| Some((here[a], here[b]))),
            }
        }
    })
}

/// The Cartesian coordinates of the plane's two axes for a polar point.
pub(crate) fn cartesian(point: PolarPoint) -> (f64, f64) {
    let (sin, cos) = super::frames::sin_cos_degrees(point.degrees);
    let (x, y) = (point.radius * cos, point.radius * sin);
    match point.pole {
        Some((a, b)) => (a + x, b + y),
        None => (x, y),
    }
}
