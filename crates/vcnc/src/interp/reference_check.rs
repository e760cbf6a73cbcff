//! G27, the reference position return check (FANUC 0M, spec iso-fanuc0m-mitsubishi.md A.25,
//! manual 001 L1286-1306): the tool moves at rapid to the point the block names (G90 or G91,
//! through the frames and the tool length in force, like G00), then every axis the block names
//! must stand on reference point 1; one that does not stops the program with alarm PS 092.
//!
//! The manual asks for G40 and G49 before G27. Under cutter compensation vcnc refuses the block
//! (the compensated rapid would not be the point named); a length offset in force is applied,
//! and the check then fails as on the control, the point reached being off by the offset.
//! "At the reference position" is within a thousandth of a millimetre, the 0M's least increment
//! (A.25's expected result: compare with a tolerance of one least increment).

use super::decode::Command;
use super::exec::Executor;
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::source::Span;

/// One least increment of the FANUC 0M, mm.
const IN_POSITION: f64 = 0.001;

/// Runs a G27 block.
///
/// # Errors
/// [`AlarmCode::ReferenceCheck`] under cutter compensation or for an axis away from the
/// reference point after the rapid; the rapid's alarms.
pub(crate) fn g27(
    exec: &mut Executor,
    cmd: &Command,
    span: Span,
    out: &mut Output,
) -> Result<(), Alarm> {
    if out.compensating() {
        return Err(Alarm::error(
            AlarmCode::ReferenceCheck,
            span,
            "G27 in cutter compensation: cancel it with G40 first",
        ));
    }
    let target = exec.block_target(cmd, false, out)?;
    exec.rapid_to(target, cmd, out)?;
    let reference = exec.kernel.setup.machine().reference_points[0];
    let away: Vec<String> = cmd
        .axes_present()
        .filter(|axis| {
            let i = axis.index();
            (exec.kernel.position[i] - reference[i]).abs() > IN_POSITION
        })
        .map(|axis| {
            exec.kernel
                .setup
                .machine()
                .layout
                .name(axis)
                .as_str()
                .to_string()
        })
        .collect();
    if away.is_empty() {
        return Ok(());
    }
    Err(Alarm::error(
        AlarmCode::ReferenceCheck,
        span,
        format!(
            "G27: {} not at the reference position (FANUC alarm PS 092)",
            away.join(", ")
        ),
    )
    .with_help("the point of G27 is the reference point in program coordinates, offsets cancelled"))
}
