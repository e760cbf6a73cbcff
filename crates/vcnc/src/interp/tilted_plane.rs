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

use super::decode::Command;
use super::exec::Executor;
use super::frames::{Affine, FrameSlot, Transform};
use super::tool_center::{self, Keeper};
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::kinematics::successive_turns;
use crate::machine::{Axis, AXES};
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
fn tilted(exec: &Executor) -> Option<Affine> {
    match exec.kernel.frames.frame(FrameSlot::Rotation) {
        Some(Transform::Affine(affine)) => Some(*affine),
        _ => None,
    }
}

/// G02/G03 in a tilted working plane: not run yet (the arc lies in a plane of the feature
/// system, which the machine's arcs in G17/G18/G19 cannot carry; it would need cutting into
/// lines, as SINUMERIK's tilted frames do in `sinumerik/arcs.rs`).
///
/// # Errors
/// [`AlarmCode::NotSupportedYet`] for an arc while G68.2 is on.
pub(crate) fn refuse_arc(exec: &Executor, cmd: &Command) -> Result<(), Alarm> {
    match tilted(exec) {
        Some(_) => Err(Alarm::not_supported(
            cmd.span,
            "G02/G03 in a tilted working plane (G68.2)",
            Some(23),
        )
        .with_help("program the arc as short G01 lines, or cancel G68.2 with G69 first")),
        None => Ok(()),
    }
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
    let [first, second] = kinematics.rotary_axes();
    let current = [
        exec.kernel.position[first.index()],
        exec.kernel.position[second.index()],
    ];
    let Some(angles) = kinematics.angles_for(normal, current) else {
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
    let mut target = exec.kernel.position;
    target[first.index()] = angles[0];
    target[second.index()] = angles[1];
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
