//! Haas G12/G13 circular pocket milling (the Yasnac-style cycle of the Haas mill manual): from
//! the pocket's centre, circles of growing radius in the cutting direction, each reached by a
//! half circle outwards, the tool centre one cutter radius inside each (the cycle implies G42 for
//! G12, G41 for G13), and a half circle back to the centre.
//!
//! `G12 X_ Y_ Z_ I_ K_ Q_ L_ D_ F_`: X Y the centre (rapid there first), Z the depth (in G91 an
//! increment, repeated L times), I the first circle's radius (the finish one without K), K the
//! finish radius, Q the step between circles (with K), D the cutter's radius register. Where the
//! Haas manual does not say (docs/DEVIATIONS.md): the plunge is at F at the centre, the step out
//! to the next circle is a half circle like the first, and the tool stays at the centre at depth.

use super::circle_cutting::Circles;
use super::decode::{Command, Value};
use super::exec::Executor;
use super::modal::DistanceMode;
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::machine::Axis;
use crate::motion::{ArcDirection, Plane, SegmentKind};

/// Most circles one block may cut (a Q far smaller than K would mean millions of moves).
const MOST_CIRCLES: f64 = 10_000.0;

/// Runs a Haas G12 (clockwise) or G13 block.
///
/// # Errors
/// No I, K without Q, a first circle not larger than the cutter or beyond K, a D out of range,
/// no feed.
pub(crate) fn run(
    exec: &mut Executor,
    cmd: &Command,
    direction: ArcDirection,
    out: &mut Output,
) -> Result<(), Alarm> {
    let refuse = |span, message: &str| Alarm::error(AlarmCode::CircleCutting, span, message);
    let i = cmd.word(b'I').ok_or_else(|| {
        refuse(
            cmd.span,
            "circular pocket milling needs I, the first circle's radius",
        )
    })?;
    let cutter = cutter_radius(exec, cmd)?;
    let first = exec.length(&i).abs();
    let finish = match (cmd.word(b'K'), cmd.word(b'Q')) {
        (Some(k), Some(q)) => Some((exec.length(&k).abs(), exec.length(&q).abs(), k)),
        (Some(k), None) => return Err(refuse(k.span, "K needs Q, the step from circle to circle")),
        (None, _) => None,
    };
    if first <= cutter {
        return Err(refuse(
            i.span,
            &format!(
                "the first circle's radius {first:.4} is not larger than the cutter's {cutter:.4}"
            ),
        ));
    }
    let mut radii = vec![first - cutter];
    if let Some((k, q, k_word)) = finish {
        if k < first || q <= 0.0 || (k - first) / q > MOST_CIRCLES {
            return Err(refuse(
                k_word.span,
                "K must be at least I, and Q a step that reaches it in at most 10,000 circles",
            ));
        }
        let mut r = first;
        while r + q < k - 1e-9 {
            r += q;
            radii.push(r - cutter);
        }
        radii.push(k - cutter);
    }
    let feed = exec.cutting_feed(cmd)?;
    let loops = loop_count(cmd)?;
    if exec.modal.plane != Plane::Xy {
        return Err(refuse(
            cmd.span,
            "circular pocket milling cuts in the X-Y plane (G17)",
        ));
    }
    // The centre: X Y of the block at rapid, then each pass's depth at feed.
    let mut centre = exec.kernel.program_position();
    let incremental = exec.modal.distance == DistanceMode::Incremental;
    for axis in [Axis::X, Axis::Y] {
        if let Some(v) = cmd.axis(axis.index()) {
            let v = exec.length(&v);
            centre[axis.index()] = if incremental {
                centre[axis.index()] + v
            } else {
                v
            };
        }
    }
    if centre != exec.kernel.program_position() {
        let to = exec.machine_target(&centre, false);
        exec.rapid_to(to, cmd, out)?;
    }
    let z = cmd.axis(Axis::Z.index()).map(|v| exec.length(&v));
    for _ in 0..loops {
        if let Some(z) = z {
            centre[2] = if incremental { centre[2] + z } else { z };
            let to = exec.machine_target(&centre, true);
            let motion = exec.move_to(to, cmd, out)?;
            out.push(cmd, SegmentKind::Line { motion, feed });
        }
        let circles = Circles {
            centre,
            plane: Plane::Xy,
            direction,
            feed,
        };
        let mut from = 0.0;
        for &r in &radii {
            // A half circle out from radius `from` to `r`, then the whole circle.
            circles.arc(exec, cmd, (r, (from + r) / 2.0), out)?;
            circles.arc(exec, cmd, (r, 0.0), out)?;
            from = r;
        }
        circles.arc(exec, cmd, (0.0, from / 2.0), out)?;
    }
    Ok(())
}

/// The cutter's radius: the block's D register, or the one in force (a diameter on profiles
/// that keep diameters); D0 cuts on the centreline.
fn cutter_radius(exec: &Executor, cmd: &Command) -> Result<f64, Alarm> {
    let register = match cmd.word(b'D') {
        Some(d) => exec
            .kernel
            .tools
            .radius(exec.kernel.setup.offset_number(d, 'D')?),
        None => exec.kernel.tools.radius_offset(),
    };
    let profile = exec.kernel.setup.profile();
    let radius = if profile.compensation.radius_offsets_are_diameters {
        register / 2.0
    } else {
        register
    };
    Ok(radius.abs() * exec.modal.units.to_mm())
}

/// L, the passes (1 without it).
fn loop_count(cmd: &Command) -> Result<u32, Alarm> {
    let Some(l) = cmd.l() else { return Ok(1) };
    match l.number.whole() {
        Some(n @ 1..=9999) => Ok(n as u32),
        _ => Err(bad_loops(l)),
    }
}

fn bad_loops(l: Value) -> Alarm {
    Alarm::error(
        AlarmCode::CircleCutting,
        l.span,
        "L, the passes, is a whole number from 1 to 9999",
    )
}
