//! G28, G30 (reference point return via an intermediate point) and G29 (return from it).
//!
//! G28/G30 move at rapid to the intermediate point (program coordinates, G90 or G91) and then to
//! the reference point, only for the axes named (spec 1.17, 1.19; A.26, A.28). The intermediate
//! point is kept per axis in program coordinates for G29, so it follows a change of coordinate
//! system (A.28). Reaching the reference point on Z clears the applied tool length vector (A.26).

use super::decode::Command;
use super::exec::Executor;
use super::modal::{DistanceMode, LengthComp};
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::machine::{Axis, AXES};
use crate::profile::Group;

/// G28: return to reference point 1.
///
/// # Errors
/// None yet.
pub(crate) fn g28(exec: &mut Executor, cmd: &Command, out: &mut Output) -> Result<bool, Alarm> {
    reference_return(exec, cmd, 1, out)
}

/// G30 Pn: return to reference point n (P2 when P is omitted).
///
/// # Errors
/// [`AlarmCode::ReferencePointOutOfRange`] for a P the machine does not have (on Mitsubishi,
/// only beyond the machine's points: P0, P1 and P5 and above go to the 2nd).
pub(crate) fn g30(exec: &mut Executor, cmd: &Command, out: &mut Output) -> Result<bool, Alarm> {
    let count = exec.kernel.setup.machine().reference_points.len();
    let other_is_second = exec
        .kernel
        .setup
        .profile()
        .coordinates
        .g30_other_p_is_second;
    let n = match cmd.p() {
        None => 2,
        Some(p) if other_is_second && !matches!(p.number.whole(), Some(2..=4)) => 2,
        Some(p) => {
            let n = p.number.whole().unwrap_or(0);
            if n < 1 || n as usize > count {
                return Err(Alarm::error(
                    AlarmCode::ReferencePointOutOfRange,
                    p.span,
                    format!("G30 P{n}: the machine has reference points 1 to {count}"),
                ));
            }
            n as usize
        }
    };
    reference_return(exec, cmd, n, out)
}

fn reference_return(
    exec: &mut Executor,
    cmd: &Command,
    n: usize,
    out: &mut Output,
) -> Result<bool, Alarm> {
    let reference = exec
        .kernel
        .setup
        .machine()
        .reference_points
        .get(n - 1)
        .copied()
        .unwrap_or([0.0; AXES]);
    if !cmd.has_axis_words() {
        if exec
            .kernel
            .setup
            .profile()
            .coordinates
            .g28_without_axes_homes_all
        {
            let mut target = exec.kernel.position;
            for axis in Axis::ALL
                .into_iter()
                .filter(|a| exec.kernel.setup.machine().has_axis(*a))
            {
                target[axis.index()] = reference[axis.index()];
            }
            exec.kernel.frames.set_length_vector(0.0);
            exec.rapid_to(target, cmd, out)?;
            after_reference_return(exec, n);
        } else {
            let span = cmd.group(Group::NonModal).map_or(cmd.span, |g| g.span);
            out.push_warning(
                Alarm::warning(
                    AlarmCode::WordNotAllowed,
                    span,
                    "reference return without axis words moves no axis",
                )
                .with_help("name the axes to send home, e.g. `G91 G28 Z0`"),
            );
        }
        return Ok(true);
    }
    let intermediate = exec.target_program(cmd);
    let moves_z = cmd.axis(Axis::Z.index()).is_some();
    let via = exec.machine_target(&intermediate, moves_z);
    exec.rapid_to(via, cmd, out)?;
    let mut home = exec.kernel.position;
    for axis in Axis::ALL {
        if cmd.axis(axis.index()).is_some() {
            exec.intermediate[axis.index()] = Some(intermediate[axis.index()]);
            home[axis.index()] = reference[axis.index()];
        }
    }
    if moves_z {
        exec.kernel.frames.set_length_vector(0.0);
    }
    exec.rapid_to(home, cmd, out)?;
    after_reference_return(exec, n);
    Ok(true)
}

/// What reaching reference point 1 (G28) cancels on the profile: the G52 local system
/// (Mitsubishi 003 L75), tool length compensation (Haas).
fn after_reference_return(exec: &mut Executor, n: usize) {
    let rules = &exec.kernel.setup.profile().coordinates;
    let (local, length) = (rules.g28_cancels_local, rules.g28_cancels_length_offset);
    if n != 1 {
        return;
    }
    if local {
        for axis in 0..AXES {
            exec.kernel.frames.set_local(axis, 0.0);
        }
    }
    if length {
        exec.modal.length_comp = LengthComp::Off;
        exec.kernel.frames.set_length_vector(0.0);
    }
}

/// G29: from the reference point through the last intermediate point to the programmed point
/// (in G91 incremental from the intermediate point), named axes only.
///
/// # Errors
/// [`AlarmCode::NoIntermediatePoint`] when an axis has no intermediate point from a G28/G30.
pub(crate) fn g29(exec: &mut Executor, cmd: &Command, out: &mut Output) -> Result<bool, Alarm> {
    let mut via = exec.kernel.program_position();
    let mut target = via;
    for axis in Axis::ALL {
        let i = axis.index();
        let Some(value) = &cmd.axis(i) else { continue };
        let Some(mid) = exec.intermediate[i] else {
            return Err(Alarm::error(
                AlarmCode::NoIntermediatePoint,
                value.span,
                format!(
                    "G29 {}: no G28 or G30 has set an intermediate point for this axis",
                    exec.kernel.setup.machine().layout.letter(axis) as char
                ),
            ));
        };
        via[i] = mid;
        let v = exec.axis_value(axis, value);
        target[i] = match exec.modal.distance {
            DistanceMode::Absolute => v,
            DistanceMode::Incremental => mid + v,
        };
    }
    let moves_z = cmd.axis(Axis::Z.index()).is_some();
    let via_machine = exec.machine_target(&via, moves_z);
    exec.rapid_to(via_machine, cmd, out)?;
    let target_machine = exec.machine_target(&target, moves_z);
    exec.rapid_to(target_machine, cmd, out)?;
    Ok(true)
}
