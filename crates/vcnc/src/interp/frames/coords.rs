//! One-shot coordinate codes: G92, G92.1, G52, G53.

use super::Rotation;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::decode::Command;
use crate::interp::exec::Executor;
use crate::interp::modal::DistanceMode;
use crate::interp::Output;
use crate::machine::{Axis, AXES};
use crate::profile::Group;

/// G92: the current position gets the programmed coordinates (named axes only); the shift moves
/// every work coordinate system (spec 1.54, L4477-4497). FANUC cancels the G52 local offset of the
/// named axes at the same time. `G92 S_` alone is the spindle speed clamp for G96.
///
/// # Errors
/// None yet; fallible like every one-shot code.
pub(crate) fn g92(exec: &mut Executor, cmd: &Command) -> Result<bool, Alarm> {
    let program = exec.kernel.program_position();
    for axis in Axis::ALL {
        let Some(value) = &cmd.axis(axis.index()) else {
            continue;
        };
        let i = axis.index();
        let wanted = exec.axis_value(axis, value);
        let g92 = exec.kernel.frames.g92(i) + exec.kernel.frames.local(i) + (program[i] - wanted);
        exec.kernel.frames.set_g92(i, g92);
        exec.kernel.frames.set_local(i, 0.0);
    }
    Ok(true)
}

/// G92.1 (FANUC): the work coordinate system preset — the G92 and G52 shifts of the named axes
/// (all axes when none is named) are cancelled. Syntec's G92.1 with K and R (a preset with
/// rotation, spec 1.55) is a coordinate transformation of issue 5.
///
/// # Errors
/// Not supported yet for Syntec's rotated form; an axis value other than 0.
pub(crate) fn g92_1(exec: &mut Executor, cmd: &Command) -> Result<bool, Alarm> {
    if cmd.r().is_some() || cmd.center(2).is_some() {
        return preset_with_rotation(exec, cmd);
    }
    let named = cmd.has_axis_words();
    for axis in Axis::ALL {
        let i = axis.index();
        match &cmd.axis(i) {
            Some(value) if value.number.value != 0.0 => {
                return Err(Alarm::error(
                    AlarmCode::ValueOutOfRange,
                    value.span,
                    "G92.1 presets to zero: write the axis with 0",
                ));
            }
            Some(_) => {}
            None if named => continue,
            None => {}
        }
        exec.kernel.frames.set_g92(i, 0.0);
        exec.kernel.frames.set_local(i, 0.0);
    }
    Ok(true)
}

/// G52: the local coordinate system's origin, in the work coordinate system, for the named axes
/// (absolute whatever G90/G91 says; `G52 X0 Y0 Z0` cancels it; spec 1.30).
///
/// # Errors
/// None yet.
pub(crate) fn g52(exec: &mut Executor, cmd: &Command) -> Result<bool, Alarm> {
    for axis in Axis::ALL {
        if let Some(value) = &cmd.axis(axis.index()) {
            let local = exec.axis_value(axis, value);
            exec.kernel.frames.set_local(axis.index(), local);
        }
    }
    Ok(true)
}

/// G53: a rapid to machine coordinates for the named axes, one block only (spec 1.31). The tool
/// length vector is not applied (a retract with `G53 Z0` reaches machine Z0 with any tool). In G91
/// G53 is an ordinary incremental move (Syntec, spec 1.31), so the block's motion runs instead.
///
/// # Errors
/// None yet.
pub(crate) fn g53(exec: &mut Executor, cmd: &Command, out: &mut Output) -> Result<bool, Alarm> {
    if exec.modal.distance == DistanceMode::Incremental {
        return Ok(false);
    }
    let mut target: [f64; AXES] = exec.kernel.position;
    for axis in Axis::ALL {
        if let Some(value) = &cmd.axis(axis.index()) {
            target[axis.index()] = exec.axis_value(axis, value);
        }
    }
    if cmd.axis(Axis::Z.index()).is_some() {
        exec.kernel.frames.set_length_vector(0.0);
    }
    exec.rapid_to(target, cmd, out)?;
    Ok(true)
}

/// Syntec's G92.1 X Y K1. R (spec 1.55): the program origin moves to (X, Y) of the present
/// program system (the G92 shift) and the program's X-Y plane turns by R degrees about it:
/// machine = work offset + (X, Y) + Rot(R) p.
///
/// # Errors
/// On profiles without it, with K other than 1 (the only axis the manual shows), or when the
/// system is already shifted by G92, G52 or turned.
fn preset_with_rotation(exec: &mut Executor, cmd: &Command) -> Result<bool, Alarm> {
    let span = cmd.group(Group::NonModal).map_or(cmd.span, |g| g.span);
    if !exec.kernel.setup.profile().coordinates.g92_1_rotation {
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            span,
            "G92.1 takes no K or R on this control",
        ));
    }
    let k = cmd.center(2).map(|k| k.number.value);
    if k.is_some_and(|k| k != 1.0) {
        return Err(Alarm::not_supported(
            span,
            "G92.1 with K other than 1 (rotation about Z)",
            Some(5),
        ));
    }
    let shifted =
        (0..2).any(|i| exec.kernel.frames.g92(i) != 0.0 || exec.kernel.frames.local(i) != 0.0);
    if shifted || exec.kernel.frames.rotated() {
        return Err(Alarm::not_supported(
            span,
            "G92.1 with R on a system already shifted by G92/G52 or turned",
            Some(5),
        ));
    }
    for axis in [Axis::X, Axis::Y] {
        let i = axis.index();
        if let Some(value) = cmd.axis(i) {
            let v = exec.axis_value(axis, &value);
            exec.kernel.frames.set_g92(i, v);
        }
    }
    let degrees = cmd.r().map_or(0.0, |r| exec.kernel.setup.angle(&r));
    exec.kernel
        .frames
        .set_preset_rotation((degrees != 0.0).then(|| Rotation::new((0, 1), (0.0, 0.0), degrees)));
    Ok(true)
}
