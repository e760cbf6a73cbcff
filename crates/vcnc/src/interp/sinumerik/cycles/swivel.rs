//! CYCLE800, the swivel cycle of 3+2 machining: it turns the working plane (a swivel frame in
//! the chain, after the programmable frame, as the control's system frame for swivelling is)
//! and, on a machine with kinematics (the machine file's `[kinematics]` is its swivel data
//! record), turns the rotary axes so that the tool stands along the new Z; the moves after it go
//! through the kinematics (`interp/tool_center.rs`) until CYCLE800() resets the swivel.
//!
//! Parameters, by position (the SINUMERIK cycles manual's list, as the corpus programs write
//! it: `CYCLE800(4,"TC1",200000,57,0,0,50,-15,0,0,50,51.76,0,1,,1)`): 0 `_FR` retract, 1 `_TC`
//! swivel data record, 2 `_ST` (units digit 1: additive to the swivel in force), 3 `_MODE`, 4-6
//! `_X0 _Y0 _Z0` the reference point, 7-9 `_A _B _C` the angles, 10-12 `_X1 _Y1 _Z1` the zero
//! point after the turn, 13 `_DIR` (which rotary solution: +1, -1; 0 turns the plane only),
//! 14 `_FR_I`, 15 `_DMODE`.
//!
//! `_MODE`'s bits 6-7 give how the angles read: 0 axis by axis (bits 0-5, two per turn, name the
//! axes in order: 1 X, 2 Y, 3 Z; 57 is X, Y, Z), 1 (64) solid angles, 2 (128) projection angles,
//! 3 (192) the rotary axes' positions directly (not run yet). The manual's text for these is
//! not among vcnc's sources (spec sinumerik-tables.md lists CYCLE800 only): the readings below
//! are vcnc's choices, each marked, and docs/DEVIATIONS.md lists them.
//!
//! Never: leave the programmed position stale after the frame changes (it is read back from the
//! machine position in the new frame).

use super::super::Sinumerik;
use super::params::Params;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::frames::{multiply, Affine};
use crate::interp::kernel::{Kernel, Origin};
use crate::interp::tool_center::{self, Keeper};
use crate::kinematics::{successive_turns, Solution, Vec3};
use crate::machine::AXES;

const X: Vec3 = [1.0, 0.0, 0.0];
const Y: Vec3 = [0.0, 1.0, 0.0];
const Z: Vec3 = [0.0, 0.0, 1.0];

/// CYCLE800 with `params`: the swivel set (or reset), the rotary axes turned.
///
/// # Errors
/// [`AlarmCode::FiveAxis`] for a turn on a machine without kinematics or one its axes cannot
/// reach; [`AlarmCode::NotSupportedYet`] for `_MODE` 192 (rotary positions given directly).
pub(super) fn run(front: &mut Sinumerik, kernel: &mut Kernel, p: &Params) -> Result<(), Alarm> {
    let angles = [7, 8, 9].map(|i| p.or_zero(i));
    let before = [4, 5, 6].map(|i| p.length_or_zero(i));
    let after = [10, 11, 12].map(|i| p.length_or_zero(i));
    let additive = p.or_zero(2).rem_euclid(10.0) == 1.0;
    if angles == [0.0; 3] && before == [0.0; 3] && after == [0.0; 3] && !additive {
        reset(front, kernel);
        return Ok(());
    }
    let rotation = rotation(p.or_zero(3) as i64, angles, p)?;
    // Choice: the reference point shifts the origin before the turn and the zero point after
    // it shifts again in the turned system (TRANS, AROT, ATRANS): work = P0 + R (P1 + p).
    let turned_after = multiply(&rotation, after);
    let translation: [f64; AXES] = std::array::from_fn(|i| {
        if i < 3 {
            before[i] + turned_after[i]
        } else {
            0.0
        }
    });
    let mut frame = Affine::new(rotation, translation)
        .ok_or_else(|| params_alarm(p, "the swivel's angles or offsets are not finite"))?;
    if additive {
        if let Some(old) = kernel.state().frames.swivel() {
            frame = compose(old, &frame)
                .ok_or_else(|| params_alarm(p, "the additive swivel cannot be composed"))?;
        }
    }
    let direction = p.or_zero(13);
    let normal = {
        let l = frame.linear();
        [l[0][2], l[1][2], l[2][2]]
    };
    kernel.state_mut().frames.set_swivel(Some(frame));
    if direction != 0.0 && normal != Z {
        let solution = if direction > 0.0 {
            Solution::FirstPositive
        } else {
            Solution::FirstNegative
        };
        turn_rotary_axes(kernel, p, normal, solution)?;
    }
    front.programmed = kernel.program_position();
    Ok(())
}

/// CYCLE800(): no swivel frame, and the kinematic transform it kept on ends; the rotary axes
/// stay where they are.
fn reset(front: &mut Sinumerik, kernel: &mut Kernel) {
    let (state, out) = kernel.state_and_output();
    state.frames.set_swivel(None);
    tool_center::release(state, Keeper::ToolAxis, out);
    front.programmed = kernel.program_position();
}

/// The rotary axes turned so that the tool stands along `normal` (a rapid; with the transform
/// already on, the tip stays put), then the transform on.
fn turn_rotary_axes(
    kernel: &mut Kernel,
    p: &Params,
    normal: Vec3,
    solution: Solution,
) -> Result<(), Alarm> {
    let mut kinematics = tool_center::kinematics(kernel.state(), p.span, "CYCLE800")?;
    // Choice: _DIR +1 / -1 takes the solution whose first rotary axis turns the plus / minus
    // way (the swivel data record's reference axis is the machine file's first rotary axis).
    kinematics.solution = solution;
    let target = kinematics
        .orient(normal, &kernel.position().0)
        .ok_or_else(|| {
            Alarm::error(
                AlarmCode::FiveAxis,
                p.span,
                format!(
                    "CYCLE800: the rotary axes cannot point the tool along ({:.6}, {:.6}, {:.6})",
                    normal[0], normal[1], normal[2]
                ),
            )
            .with_help("check the angles against the rotary axes' travel in the machine file")
        })?;
    kernel.rapid_to_machine(target, Origin::at(p.span))?;
    let (state, out) = kernel.state_and_output();
    tool_center::start(state, (p.span, "CYCLE800"), Keeper::ToolAxis, out)
}

/// The turn `_MODE` and the angles describe.
fn rotation(mode: i64, angles: [f64; 3], p: &Params) -> Result<[[f64; 3]; 3], Alarm> {
    let [a, b, c] = angles;
    match mode >> 6 {
        // Axis by axis: each turn about an axis of the system the turns before left.
        0 => Ok(successive_turns(&order(mode).zip_angles(angles))),
        // Choice: solid angles turn about Z by _A, then about the new Y by _B, then about the
        // newest Z by _C.
        1 => Ok(successive_turns(&[(Z, a), (Y, b), (Z, c)])),
        // Projection angles: the second turn is the one whose trace in the plane of the first
        // axis and the tool axis makes the angle _B: tan b' = tan b cos a (the plane's normal
        // after turns a and b' is (sin b', -sin a cos b', cos a cos b') for X then Y).
        2 => {
            let b = (b.to_radians().tan() * a.to_radians().cos())
                .atan()
                .to_degrees();
            Ok(successive_turns(&order(mode).zip_angles([a, b, c])))
        }
        _ => Err(Alarm::not_supported(
            p.span,
            "CYCLE800 with _MODE 192 (the rotary axes' positions given directly)",
            Some(22),
        )),
    }
}

/// The axes of the three turns `_MODE`'s bits 0-5 name (two bits each: 1 X, 2 Y, 3 Z); X, Y, Z
/// when they name none.
fn order(mode: i64) -> [Vec3; 3] {
    let axis = |k: i64| match (mode >> (2 * k)) & 3 {
        1 => Some(X),
        2 => Some(Y),
        3 => Some(Z),
        _ => None,
    };
    match [axis(0), axis(1), axis(2)] {
        [Some(first), Some(second), Some(third)] => [first, second, third],
        _ => [X, Y, Z],
    }
}

/// Pairs three axes with three angles.
trait ZipAngles {
    fn zip_angles(self, angles: [f64; 3]) -> [(Vec3, f64); 3];
}

impl ZipAngles for [Vec3; 3] {
    fn zip_angles(self, angles: [f64; 3]) -> [(Vec3, f64); 3] {
        [0, 1, 2].map(|i| (self[i], angles[i]))
    }
}

/// `outer` after `inner`: the map `p -> outer(inner(p))`.
fn compose(outer: &Affine, inner: &Affine) -> Option<Affine> {
    let (l1, l2) = (outer.linear(), inner.linear());
    let linear =
        std::array::from_fn(|r| std::array::from_fn(|c| (0..3).map(|k| l1[r][k] * l2[k][c]).sum()));
    let t2 = inner.translation();
    let moved = multiply(l1, [t2[0], t2[1], t2[2]]);
    let t1 = outer.translation();
    let translation = std::array::from_fn(|i| {
        if i < 3 {
            moved[i] + t1[i]
        } else {
            t1[i] + t2[i]
        }
    });
    Affine::new(linear, translation)
}

fn params_alarm(p: &Params, message: &str) -> Alarm {
    Alarm::error(
        AlarmCode::CycleParameter,
        p.span,
        format!("CYCLE800: {message}"),
    )
}
