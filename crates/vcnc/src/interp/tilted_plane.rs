//! G68.2 tilted working plane, G53.1 tool axis direction and their cancel G69. Spec
//! iso-syntec-milling.md 1.32 and 1.38 (seed 000 L2553-2632, L2994-3090).
//!
//! `G68.2 X_ Y_ Z_ I_ J_ K_` sets the feature coordinate system: its origin X Y Z in the work
//! coordinates (the distances from the G54 origin, L3017) and its orientation as Euler angles
//! I J K in the order Z, X', Z" (L3019-3027): turn about Z by I, about the new X by J, about the
//! newest Z by K. A feature point p is the work point `O + Rz(I) Rx(J) Rz(K) p`. Positive angles
//! turn right-handed (the manual's figure; the spec infers it). It is a frame of the chain in
//! G68's slot: G68.2 and G68 are one group and G69 cancels both.
//!
//! `G53.1` turns the rotary axes so that the tool stands along the feature Z axis (L2557); the
//! tool keeps that direction and later moves go through the machine's kinematics (the transform
//! of `tool_center.rs`, kept on by G53.1 until G69), so a point of the feature system is reached
//! by the tool tip under G43, whichever way the table or head has turned. G53.1 before any
//! G68.2 is refused (L3031); the manual gives no alarm number.
//!
//! A G02/G03 in the feature plane is a circle in a tilted plane, which the machine's arcs (in
//! G17/G18/G19) cannot carry: it becomes chords, computed in the feature system.

use super::arc::{arc_center, in_plane, ArcSpec};
use super::decode::Command;
use super::exec::Executor;
use super::frames::{Affine, FrameSlot, Transform};
use super::tool_center::{self, Keeper};
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::kinematics::successive_turns;
use crate::machine::{Axis, AXES};
use crate::motion::{ArcDirection, Feed, Move, PathMode, SegmentKind};
use crate::profile::{GCode, Group};

/// The rotation `Rz(i) Rx(j) Rz(k)` of the Euler angles (degrees) in Syntec's Z-X-Z order,
/// row by row: each later turn is about an axis the earlier ones moved, so the matrices
/// multiply in the order written.
pub(crate) fn euler_zxz(i: f64, j: f64, k: f64) -> [[f64; 3]; 3] {
    let (x, z) = ([1.0, 0.0, 0.0], [0.0, 0.0, 1.0]);
    successive_turns(&[(z, i), (x, j), (z, k)])
}

/// G68.2: the feature coordinate system from the block's X Y Z and I J K.
///
/// # Errors
/// None today; kept fallible like the other coordinate codes.
pub(crate) fn g68_2(exec: &mut Executor, cmd: &Command) -> Result<(), Alarm> {
    let origin: [f64; AXES] = std::array::from_fn(|i| match Axis::from_index(i) {
        Some(axis) if axis.is_geometry() => cmd.axis(i).map_or(0.0, |v| exec.axis_value(axis, &v)),
        _ => 0.0,
    });
    let angle = |i: usize| cmd.center(i).map_or(0.0, |v| exec.kernel.setup.angle(&v));
    let rotation = euler_zxz(angle(0), angle(1), angle(2));
    // A rotation matrix always inverts and the origin is a checked program value.
    let frame = Affine::new(rotation, origin).map(Transform::Affine);
    exec.kernel.frames.set_frame(FrameSlot::Rotation, frame);
    Ok(())
}

/// G69: no rotation or tilted plane from here on; the tool keeps its direction, but the
/// kinematic transform G53.1 kept on ends.
pub(crate) fn g69(exec: &mut Executor, out: &mut Output) {
    super::frames::rotation::g69(&mut exec.kernel.frames);
    tool_center::release(&mut exec.kernel, Keeper::ToolAxis, out);
}

/// The tilted plane in force, if G68.2 set one.
pub(crate) fn tilted(exec: &Executor) -> Option<Affine> {
    match exec.kernel.frames.frame(FrameSlot::Rotation) {
        Some(Transform::Affine(affine)) => Some(*affine),
        _ => None,
    }
}

/// Largest distance, mm, between an arc in a tilted plane and the chords that replace it: the
/// control interpolates the arc in its servo cycle; vcnc's choice, as SINUMERIK's tilted arcs
/// (`sinumerik/motion.rs`).
const CHORD_TOLERANCE: f64 = 0.001;

/// G02/G03 in a tilted working plane: the arc lies in the feature system's plane, which no
/// machine plane carries, so it is cut into chords within [`CHORD_TOLERANCE`] of it, computed in
/// program coordinates (the axes off the plane linear along it, a helix) and each taken through
/// the chain. The block's feed holds along the chords (an inverse-time feed is shared out).
///
/// # Errors
/// The arc's own alarms (an end off the circle, R too small); a chord beyond the control's
/// range.
pub(crate) fn arc_as_chords(
    exec: &mut Executor,
    cmd: &Command,
    (spec, direction, feed): (ArcSpec, ArcDirection, Feed),
    target: [f64; AXES],
    out: &mut Output,
) -> Result<(), Alarm> {
    let plane = exec.modal.plane;
    let (a, b, _) = plane.axes();
    let from = exec.kernel.program_position();
    let to = exec.kernel.frames.to_program(&target);
    let (start, end) = (in_plane(plane, &from), in_plane(plane, &to));
    let tolerance = exec.kernel.setup.profile().motion.arc_radius_tolerance;
    let centre = arc_center(start, end, spec, direction, tolerance)?;
    let r0 = (start.0 - centre.0).hypot(start.1 - centre.1);
    let r1 = (end.0 - centre.0).hypot(end.1 - centre.1);
    let a0 = (start.1 - centre.1).atan2(start.0 - centre.0);
    let a1 = (end.1 - centre.1).atan2(end.0 - centre.0);
    let tau = std::f64::consts::TAU;
    let mut sweep = match direction {
        ArcDirection::CounterClockwise => (a1 - a0).rem_euclid(tau),
        ArcDirection::Clockwise => -(a0 - a1).rem_euclid(tau),
    };
    // An arc by I J K ending on its start is a full circle.
    if sweep == 0.0 && matches!(spec, ArcSpec::Center { .. }) {
        sweep = if direction == ArcDirection::Clockwise {
            -tau
        } else {
            tau
        };
    }
    // Chords of at most the tolerance from the circle: 2 r (1 - cos(step / 2)) <= tolerance.
    let radius = r0.max(r1).max(CHORD_TOLERANCE);
    let step = 2.0 * (1.0 - CHORD_TOLERANCE / radius).clamp(-1.0, 1.0).acos();
    // At most a million chords: a radius far beyond any machine must not hang the run.
    let count = ((sweep.abs() / step.max(1e-6)).ceil() as usize).clamp(1, 1_000_000);
    let feed = match feed {
        Feed::InverseTime(f) => Feed::InverseTime(f * count as f64),
        other => other,
    };
    for k in 1..=count {
        let machine = if k == count {
            target
        } else {
            let t = k as f64 / count as f64;
            let mut p: [f64; AXES] = std::array::from_fn(|i| from[i] + (to[i] - from[i]) * t);
            let (sin, cos) = (a0 + sweep * t).sin_cos();
            let r = r0 + (r1 - r0) * t;
            (p[a], p[b]) = (centre.0 + r * cos, centre.1 + r * sin);
            let length = exec.kernel.frames.length_vector();
            exec.kernel.frames.to_machine(&p, length)
        };
        let last = k == count;
        // The block's exact stop (G09, G61) is at its end, not between its chords.
        let motion = exec.move_to(machine, cmd, out)?;
        let motion = Move {
            exact_stop: motion.exact_stop && last,
            path_mode: match motion.path_mode {
                PathMode::ExactStop if !last => PathMode::Continuous,
                mode => mode,
            },
            ..motion
        };
        out.push(cmd, SegmentKind::Line { motion, feed });
    }
    Ok(())
}

/// G53.1: the rotary axes turn the tool along the feature Z axis (a rapid of the rotary axes),
/// and the kinematic transform stays on until G69.
///
/// # Errors
/// [`AlarmCode::FiveAxis`] without G68.2, on a machine without kinematics, or when the rotary
/// axes cannot point the tool that way.
pub(crate) fn g53_1(exec: &mut Executor, cmd: &Command, out: &mut Output) -> Result<(), Alarm> {
    let Some(g) = cmd
        .group(Group::NonModal)
        .filter(|g| g.code == GCode::ToolAxisDirection)
    else {
        return Ok(());
    };
    let Some(plane) = tilted(exec) else {
        return Err(Alarm::error(
            AlarmCode::FiveAxis,
            g.span,
            "G53.1 without a tilted working plane",
        )
        .with_help("command G68.2 before G53.1 (Syntec spec 1.32)"));
    };
    let kinematics = tool_center::kinematics(&exec.kernel, g.span, "G53.1")?;
    let linear = plane.linear();
    let normal = [linear[0][2], linear[1][2], linear[2][2]];
    let Some(target) = kinematics.orient(normal, &exec.kernel.position) else {
        return Err(Alarm::error(
            AlarmCode::FiveAxis,
            g.span,
            format!(
                "G53.1: the rotary axes cannot point the tool along ({:.6}, {:.6}, {:.6})",
                normal[0], normal[1], normal[2]
            ),
        )
        .with_help("the direction is beyond the rotary axes' travel: check G68.2's angles and the axes' limits"));
    };
    // With the transform on, the rotary move keeps the tip where it is; off, the linear axes stay
    // and only the rotary axes turn (then the transform starts at the new angles).
    exec.rapid_to(target, cmd, out)?;
    tool_center::start(&mut exec.kernel, (g.span, "G53.1"), Keeper::ToolAxis, out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_euler_angles_turn_z_then_the_new_x_then_the_newest_z() {
        // The spec's matrix for I30 J15 K20 (iso-syntec-milling.md 1.32): R = Rz(30) Rx(15) Rz(20).
        let r = euler_zxz(30.0, 15.0, 20.0);
        let expected = [
            [0.648615, -0.750035, 0.129410],
            [0.755952, 0.615058, -0.224144],
            [0.088521, 0.243210, 0.965926],
        ];
        for (row, want) in r.iter().zip(expected) {
            for (got, want) in row.iter().zip(want) {
                assert!((got - want).abs() < 5e-7, "{r:?}");
            }
        }
        // J alone tips the plane about X: the feature Z (0, -sin J, cos J); I alone turns X to
        // (cos I, sin I, 0); K alone the same about the unturned Z.
        let j = euler_zxz(0.0, 90.0, 0.0);
        assert!((j[1][2] + 1.0).abs() < 1e-12 && j[2][2].abs() < 1e-12);
        let i = euler_zxz(90.0, 0.0, 0.0);
        assert!(i[0][0].abs() < 1e-12 && (i[1][0] - 1.0).abs() < 1e-12);
        let k = euler_zxz(0.0, 0.0, 90.0);
        assert!(k[0][0].abs() < 1e-12 && (k[1][0] - 1.0).abs() < 1e-12);
        // I and K about the same axis while J is zero: they add.
        let both = euler_zxz(10.0, 0.0, 20.0);
        let sum = euler_zxz(30.0, 0.0, 0.0);
        for (a, b) in both.iter().flatten().zip(sum.iter().flatten()) {
            assert!((a - b).abs() < 1e-12);
        }
    }
}
