//! Syntec's spiral and conical interpolation: G02/G03 with L turns (spec 1.6, manual
//! 000:L459-486).
//!
//! `G17 G02 X_ Y_ I_ J_ L_` turns about the centre start + (I, J) from the start radius to the
//! end radius: L counts the turns, an incomplete last turn counting as one, so the tool sweeps
//! (L - 1) full turns plus the angle from the start to the end in the programmed direction. The
//! radius changes linearly with the angle swept (an Archimedean spiral), and an axis of the
//! block outside the plane moves linearly with it too (conical interpolation). The manual does
//! not say how the radius changes between the two radii; linear in the angle is the reading the
//! spec infers from its examples (docs/DEVIATIONS.md).
//!
//! The control interpolates the curve in its servo cycle. vcnc gives it as straight pieces in
//! the stream, each within [`CHORD_TOLERANCE`] of the curve, so that every consumer (planner,
//! summary, trace) sees an ordinary path.

use super::decode::{Command, Value};
use super::exec::Executor;
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::machine::AXES;
use crate::motion::{ArcDirection, Feed, SegmentKind};
use crate::source::Span;
use std::f64::consts::TAU;

/// Largest distance, mm, between the spiral and the straight pieces that stand for it (vcnc's
/// choice: the control's servo cycle gives no such number).
pub(crate) const CHORD_TOLERANCE: f64 = 0.001;

/// Most pieces one spiral block may make: a bound on a huge L, like the canned cycles' bound
/// on their moves per block.
const MAX_PIECES: usize = 100_000;

/// Most turns L may ask for.
const MAX_TURNS: f64 = 9999.0;

/// The spiral of the block, from what G02/G03 worked out: the direction (after any mirror), the
/// end point in machine coordinates, and the centre as an offset from the start in the plane.
pub(crate) struct Spiral {
    pub(crate) direction: ArcDirection,
    pub(crate) target: [f64; AXES],
    pub(crate) offset: (f64, f64),
    /// The centre words, for alarms about the centre.
    pub(crate) centre_span: Span,
    pub(crate) turns: Value,
    pub(crate) feed: Feed,
}

/// Moves along the spiral from the current position.
///
/// # Errors
/// L that is not a whole number of turns from 1 to 9999, a centre on the start point, more
/// than [`MAX_PIECES`] pieces, a position out of range.
pub(crate) fn run(
    exec: &mut Executor,
    cmd: &Command,
    spiral: &Spiral,
    out: &mut Output,
) -> Result<(), Alarm> {
    let turns = spiral.turns.number.value;
    if !(1.0..=MAX_TURNS).contains(&turns) || turns.fract() != 0.0 {
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            spiral.turns.span,
            format!("L of a spiral is its number of turns, a whole number from 1 to {MAX_TURNS}"),
        )
        .with_help("an incomplete last turn counts as one: L3 for two and a half turns"));
    }
    let (a, b, _) = exec.modal.plane.axes();
    let start = exec.kernel.position;
    let centre = (start[a] + spiral.offset.0, start[b] + spiral.offset.1);
    let start_radius = spiral.offset.0.hypot(spiral.offset.1);
    if start_radius <= 1e-9 {
        return Err(Alarm::error(
            AlarmCode::ArcWithoutCenter,
            spiral.centre_span,
            "spiral centre is on its start point",
        ));
    }
    let target = spiral.target;
    let end_radius = (target[a] - centre.0).hypot(target[b] - centre.1);
    let sign = match spiral.direction {
        ArcDirection::CounterClockwise => 1.0,
        ArcDirection::Clockwise => -1.0,
    };
    let start_angle = (start[b] - centre.1).atan2(start[a] - centre.0);
    // The last turn: from the start angle to the end angle in the programmed direction, a whole
    // turn when they meet (or when the spiral ends on its centre, where no angle is defined).
    let last_turn = if end_radius <= 1e-9 {
        TAU
    } else {
        let end_angle = (target[b] - centre.1).atan2(target[a] - centre.0);
        let swept = (sign * (end_angle - start_angle)).rem_euclid(TAU);
        if swept <= 1e-12 {
            TAU
        } else {
            swept
        }
    };
    let sweep = (turns - 1.0) * TAU + last_turn;
    // A chord of angle d on a circle of radius r leaves it by r (1 - cos(d/2)). A spiral with
    // r' = dr/dphi bends like a circle of (r^2 + 2 r'^2) / sqrt(r^2 + r'^2) per unit of angle
    // (its curvature times its speed squared): the larger radius, taken at the larger r.
    let growth = (end_radius - start_radius) / sweep;
    let outer = start_radius.max(end_radius);
    let radius = (outer * outer + 2.0 * growth * growth) / outer.hypot(growth);
    let step = if CHORD_TOLERANCE >= radius {
        TAU / 4.0
    } else {
        (2.0 * (1.0 - CHORD_TOLERANCE / radius).acos()).min(TAU / 4.0)
    };
    let pieces = (sweep / step).ceil();
    if pieces > MAX_PIECES as f64 {
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            spiral.turns.span,
            format!(
                "this spiral would take {pieces} straight pieces of {CHORD_TOLERANCE} mm \
                 tolerance; vcnc stops at {MAX_PIECES} a block"
            ),
        ));
    }
    let pieces = (pieces as usize).max(1);
    let point = |k: usize| -> [f64; AXES] {
        if k == pieces {
            return target;
        }
        let share = k as f64 / pieces as f64;
        let angle = start_angle + sign * sweep * share;
        let r = start_radius + (end_radius - start_radius) * share;
        let mut p: [f64; AXES] = std::array::from_fn(|i| start[i] + (target[i] - start[i]) * share);
        p[a] = centre.0 + r * angle.cos();
        p[b] = centre.1 + r * angle.sin();
        p
    };
    // In G93 the block's F is the inverse of its whole time: each piece gets its share.
    let total = match spiral.feed {
        Feed::InverseTime(_) => (1..=pieces).fold((0.0, start), |(sum, from), k| {
            let to = point(k);
            (sum + distance(&from, &to), to)
        }),
        _ => (0.0, start),
    }
    .0;
    for k in 1..=pieces {
        let to = point(k);
        let feed = match spiral.feed {
            Feed::InverseTime(f) => {
                let length = distance(&exec.kernel.position, &to);
                if length <= 0.0 {
                    continue;
                }
                Feed::InverseTime(f * total / length)
            }
            feed => feed,
        };
        if super::kernel::same_place(&to, &exec.kernel.position) {
            continue;
        }
        let motion = exec.move_to(to, cmd, out)?;
        out.push(cmd, SegmentKind::Line { motion, feed });
    }
    Ok(())
}

/// Straight distance over X Y Z between two machine positions, mm.
fn distance(from: &[f64; AXES], to: &[f64; AXES]) -> f64 {
    (to[0] - from[0])
        .hypot(to[1] - from[1])
        .hypot(to[2] - from[2])
}
