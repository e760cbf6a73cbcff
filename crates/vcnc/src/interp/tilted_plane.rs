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
//!
//! FANUC's Series 30i has more forms, chosen by P (profile `motion.tilted_plane_forms`; the
//! Syntec manual gives the Euler form only, so P there is refused). The seed manuals do not
//! describe them: the forms and their words follow FANUC's 30i documentation as the Mazak
//! (FANUC-compatible) and LinuxCNC tilted-work-plane documents restate it, and the choices where
//! those leave a reading open are marked below.
//!
//! - P0 (or none): the Euler angles above.
//! - P1: roll-pitch-yaw, I about X, J about Y, K about Z, turned in the order Q names (Q123, the
//!   default, X then Y then Z; any order of the three digits). Choice: each turn is about the
//!   work system's own (fixed) axes, the classic roll-pitch-yaw, so Q123 is Rz(K) Ry(J) Rx(I);
//!   one restatement multiplies the other way round (about the turned axes).
//! - P2: three points, one block each: Q1, Q2, Q3 give X Y Z. Q1 to Q2 is the feature +X, Q3
//!   lies on the +Y side of the feature XY plane. An optional Q0 block before them gives the
//!   origin (X Y Z; without it the origin is the Q1 point) and R, a turn about the feature Z.
//! - P3: two vectors: Q1 gives the origin (X Y Z), the feature X direction (I J K) and R; Q2 the
//!   feature Z direction (I J K). FANUC refuses vectors further than 5 degrees from square; the
//!   Z direction is kept and X squared to it (choice: Z is the tool's direction).
//!
//! The plane of a P2 or P3 comes into force at its last block (Q3, Q2); until then the frame in
//! force stays; G69 drops the blocks given so far. Choice: other blocks between them are not
//! refused.

use super::arc::{arc_center, in_plane, ArcSpec};
use super::decode::Command;
use super::exec::Executor;
use super::frames::{Affine, FrameSlot, Transform};
use super::tool_center::{self, Keeper};
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::kinematics::{cross, dot, norm, sub, successive_turns, unit, Vec3};
use crate::machine::AXES;
use crate::motion::{ArcDirection, Feed, Move, PathMode, SegmentKind};
use crate::profile::{GCode, Group};

/// The rotation `Rz(i) Rx(j) Rz(k)` of the Euler angles (degrees) in Syntec's Z-X-Z order,
/// row by row: each later turn is about an axis the earlier ones moved, so the matrices
/// multiply in the order written.
pub(crate) fn euler_zxz(i: f64, j: f64, k: f64) -> [[f64; 3]; 3] {
    let (x, z) = ([1.0, 0.0, 0.0], [0.0, 0.0, 1.0]);
    successive_turns(&[(z, i), (x, j), (z, k)])
}

/// The rotation of roll-pitch-yaw angles (degrees) `[about X, about Y, about Z]` turned in
/// `order` (axis indices, the first turn first), each about the fixed axes: the later turns
/// multiply from the left.
pub(crate) fn roll_pitch_yaw(order: [usize; 3], angles: [f64; 3]) -> [[f64; 3]; 3] {
    let unit = |i: usize| std::array::from_fn(|k| if k == i { 1.0 } else { 0.0 });
    // Turns about fixed axes in one order are turns about the moved axes in the other.
    let turns = order.map(|i| (unit(i), angles[i]));
    successive_turns(&[turns[2], turns[1], turns[0]])
}

/// The rotation whose columns are the feature X, Y and Z: X along `x` squared to `z`, turned
/// `turn` degrees about Z; `None` when the two are (nearly) parallel or either is zero.
fn from_x_and_z(x: Vec3, z: Vec3, turn: f64) -> Option<[[f64; 3]; 3]> {
    let z = unit(z)?;
    let along = dot(x, z);
    let x = unit(std::array::from_fn(|i| x[i] - along * z[i]))?;
    let y = cross(z, x);
    let axes = successive_turns(&[([0.0, 0.0, 1.0], turn)]);
    let columns = [x, y, z];
    // Turning the feature system about its own Z: the columns times Rz(turn).
    Some(std::array::from_fn(|row| {
        std::array::from_fn(|col| (0..3).map(|k| columns[k][row] * axes[k][col]).sum())
    }))
}

/// The block's X Y Z in work coordinates (0 for a word left out), and whether it had any.
fn work_point(exec: &Executor, cmd: &Command) -> (Vec3, bool) {
    let point = std::array::from_fn(|i| cmd.axis(i).map_or(0.0, |v| exec.length(&v)));
    (point, (0..3).any(|i| cmd.axis(i).is_some()))
}

/// G68.2: the feature coordinate system from the block (the Euler form, or FANUC's P1-P3).
///
/// # Errors
/// [`AlarmCode::ValueOutOfRange`] for a P or Q the control does not have;
/// [`AlarmCode::FiveAxis`] for points or vectors that make no plane, or a P2/P3 block out of
/// its order.
pub(crate) fn g68_2(exec: &mut Executor, cmd: &Command) -> Result<(), Alarm> {
    let form = plane_form(exec, cmd)?;
    let angle = |i: usize| cmd.center(i).map_or(0.0, |v| exec.kernel.setup.angle(&v));
    let angles = [angle(0), angle(1), angle(2)];
    let (rotation, origin) = match form {
        0 => (
            euler_zxz(angles[0], angles[1], angles[2]),
            work_point(exec, cmd).0,
        ),
        1 => (
            roll_pitch_yaw(rotation_order(cmd)?, angles),
            work_point(exec, cmd).0,
        ),
        _ => match gather(exec, cmd, form)? {
            Some(plane) => plane,
            None => return Ok(()),
        },
    };
    let origin: [f64; AXES] = std::array::from_fn(|i| origin.get(i).copied().unwrap_or(0.0));
    // A rotation matrix always inverts and the origin is a checked program value.
    let frame = Affine::new(rotation, origin).map(Transform::Affine);
    exec.kernel.frames.set_frame(FrameSlot::Rotation, frame);
    Ok(())
}

/// The form G68.2's P selects (0 without P).
fn plane_form(exec: &Executor, cmd: &Command) -> Result<u8, Alarm> {
    let Some(p) = cmd.word(b'P') else {
        return Ok(0);
    };
    let forms = exec.kernel.setup.profile().motion.tilted_plane_forms;
    let value = p.number.value;
    match value {
        0.0 => Ok(0),
        1.0 | 2.0 | 3.0 if forms => Ok(value as u8),
        _ => Err(Alarm::error(
            AlarmCode::ValueOutOfRange,
            p.span,
            format!("G68.2 P{value} is not a form of this control's tilted working plane"),
        )
        .with_help(if forms {
            "P0 Euler angles, P1 roll-pitch-yaw, P2 three points, P3 two vectors"
        } else {
            "this control's G68.2 takes the Euler angles I J K only (X Y Z I J K, no P)"
        })),
    }
}

/// P1's Q: the order of the three turns as axis indices (Q123 when Q is left out).
fn rotation_order(cmd: &Command) -> Result<[usize; 3], Alarm> {
    let Some(q) = cmd.word(b'Q') else {
        return Ok([0, 1, 2]);
    };
    let digits = q.number.value;
    let order = [100.0, 10.0, 1.0].map(|place| ((digits / place).floor() % 10.0) as usize);
    let permutation = digits.fract() == 0.0
        && (100.0..=321.0).contains(&digits)
        && order.iter().all(|d| (1..=3).contains(d))
        && order[0] != order[1]
        && order[1] != order[2]
        && order[0] != order[2];
    if !permutation {
        return Err(Alarm::error(
            AlarmCode::ValueOutOfRange,
            q.span,
            format!("G68.2 P1 Q{digits}: Q names the order of the turns about X (1), Y (2), Z (3)"),
        )
        .with_help("give the three digits once each: Q123, Q132, Q213, Q231, Q312 or Q321"));
    }
    Ok(order.map(|d| d - 1))
}

/// A feature system: its rotation (columns the feature X Y Z) and origin, work coordinates.
type Plane = ([[f64; 3]; 3], Vec3);

/// The blocks of a FANUC G68.2 P2 (three points) or P3 (two vectors) read so far.
#[derive(Clone, Debug, Default)]
pub(crate) struct PlaneParts {
    /// The form (2 or 3) the blocks so far belong to.
    form: u8,
    /// Each block by its Q: X Y Z (work coordinates, if written), I J K, R.
    parts: [Option<PlanePart>; 4],
}

/// One block of a P2/P3 definition.
#[derive(Clone, Copy, Debug)]
struct PlanePart {
    point: Option<Vec3>,
    vector: Vec3,
    turn: f64,
}

/// A P2/P3 block: kept, and at the form's last block the plane (rotation, origin).
fn gather(exec: &mut Executor, cmd: &Command, form: u8) -> Result<Option<Plane>, Alarm> {
    let span = cmd.group(Group::Rotation).map_or(cmd.span, |g| g.span);
    let last = if form == 2 { 3 } else { 2 };
    let first = if form == 2 { 0 } else { 1 };
    let q = cmd.word(b'Q').map(|q| q.number.value);
    let Some(q) = q.filter(|q| q.fract() == 0.0 && (first as f64..=last as f64).contains(q)) else {
        return Err(Alarm::error(
            AlarmCode::ValueOutOfRange,
            span,
            format!(
                "G68.2 P{form} needs Q{first} to Q{last}: which part of the plane the block gives"
            ),
        )
        .with_help(if form == 2 {
            "G68.2 P2: Q0 origin and R (optional), Q1, Q2, Q3 the three points"
        } else {
            "G68.2 P3: Q1 origin, X direction (I J K) and R; Q2 the Z direction (I J K)"
        }));
    };
    let q = q as usize;
    if exec.plane_parts.form != form {
        exec.plane_parts = PlaneParts {
            form,
            ..PlaneParts::default()
        };
    }
    let (point, written) = work_point(exec, cmd);
    // A direction's length does not matter: I J K as written, not as lengths.
    let vector = std::array::from_fn(|i| cmd.center(i).map_or(0.0, |v| v.number.value));
    let turn = cmd.r().map_or(0.0, |v| exec.kernel.setup.angle(&v));
    exec.plane_parts.parts[q] = Some(PlanePart {
        point: written.then_some(point),
        vector,
        turn,
    });
    if q != last {
        return Ok(None);
    }
    let parts = std::mem::take(&mut exec.plane_parts).parts;
    let missing = |what: &str| {
        Alarm::error(
            AlarmCode::FiveAxis,
            span,
            format!("G68.2 P{form} Q{last} without {what} before it"),
        )
        .with_help("give the plane's blocks in order, each with G68.2 and its P and Q")
    };
    let no_plane = |what: &str| {
        Alarm::error(AlarmCode::FiveAxis, span, format!("G68.2 P{form}: {what}"))
            .with_help("the blocks' points or vectors must span a plane")
    };
    if form == 2 {
        let [origin, Some(p1), Some(p2), Some(p3)] = parts else {
            return Err(missing("Q1 and Q2"));
        };
        let (p1, p2, p3) = (p1.point.unwrap_or_default(), p2.point, p3.point);
        let (p2, p3) = (p2.unwrap_or_default(), p3.unwrap_or_default());
        let x = sub(p2, p1);
        let z = cross(x, sub(p3, p1));
        // Choice: a plane of points closer than 1 µm to one line is no plane (FANUC sets a
        // limit by parameter).
        if norm(x) < 1e-3 || norm(z) < 1e-3 * norm(x) {
            return Err(no_plane("the three points lie on one line"));
        }
        let turn = origin.map_or(0.0, |o| o.turn);
        let centre = origin.and_then(|o| o.point).unwrap_or(p1);
        let rotation = from_x_and_z(x, z, turn).ok_or_else(|| no_plane("no plane"))?;
        return Ok(Some((rotation, centre)));
    }
    let [_, Some(first), Some(second), _] = parts else {
        return Err(missing("Q1"));
    };
    let (x, z) = (first.vector, second.vector);
    let (lx, lz) = (norm(x), norm(z));
    if lx < 1e-9 || lz < 1e-9 {
        return Err(no_plane("a direction is the zero vector"));
    }
    // FANUC's limit: the two directions within 5 degrees of square.
    let cos = dot(x, z) / (lx * lz);
    if cos.abs() > 5f64.to_radians().sin() {
        return Err(no_plane(&format!(
            "the X and Z directions are {:.3} degrees apart, not within 5 of square",
            cos.clamp(-1.0, 1.0).acos().to_degrees()
        )));
    }
    let rotation = from_x_and_z(x, z, first.turn).ok_or_else(|| no_plane("no plane"))?;
    Ok(Some((rotation, first.point.unwrap_or_default())))
}

/// G69: no rotation or tilted plane from here on; the tool keeps its direction, but the
/// kinematic transform G53.1 kept on ends.
pub(crate) fn g69(exec: &mut Executor, out: &mut Output) {
    super::frames::rotation::g69(&mut exec.kernel.frames);
    // A P2/P3 plane left half given is dropped with it.
    exec.plane_parts = PlaneParts::default();
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
