//! G31, the skip function (Syntec spec 1.20, manual 000:L1353-1419): a cutting move toward the
//! end point that a skip signal (a touch probe, a tool setter) ends where it comes; the control
//! records that position and the next block starts from it.
//!
//! The signal comes from the machine file's touch targets (`[probe]`, crate::probe): the move
//! stops where the tool's tip first touches one, and that point is the recorded skip position
//! (FANUC #5061-#5066, in program coordinates). When the machine describes no target, the signal
//! never comes: the block runs to its end point like G01 (what the spec infers for a block
//! without the signal) and that end point is recorded; a probing macro then sees "no contact".
//! When targets are described and the move touches none, the same, with a warning: the program
//! expected a touch. The control brings the axes to rest at the end of the block: the move has an
//! exact stop.
//!
//! Q (Syntec's choice of PLC signal, Q101-Q132) selects nothing here.

use super::decode::Command;
use super::exec::Executor;
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::machine::AXES;
use crate::probe::Signal;

/// Runs a G31 block.
///
/// # Errors
/// G31 in cutter compensation (FANUC alarm 035), no feed, a position out of range.
pub(crate) fn g31(exec: &mut Executor, cmd: &Command, out: &mut Output) -> Result<(), Alarm> {
    let span = cmd
        .group(crate::profile::Group::NonModal)
        .map_or(cmd.span, |g| g.span);
    if out.compensating() {
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            span,
            "G31 (skip) in cutter compensation: cancel it with G40 first",
        )
        .with_help("FANUC alarm 035: skip cutting cannot be commanded in cutter compensation"));
    }
    let target = exec.block_target(cmd, false, out)?;
    let touched = skip_to(exec, target, cmd, Signal::Skip, out)?;
    if touched.is_none() && exec.probe.has_targets() {
        out.push_warning(Alarm::warning(
            AlarmCode::Probing,
            span,
            "G31 touched none of the machine file's probe targets: the block ran to its end point",
        ));
    }
    exec.skip_position = exec.kernel.program_position();
    Ok(())
}

/// A cutting move toward `target` (machine coordinates) at the feed in force that stops where
/// `signal` comes, with an exact stop; the machine position of the touch, if one came.
///
/// # Errors
/// No feed in force, a position beyond the control's range.
pub(crate) fn skip_to(
    exec: &mut Executor,
    target: [f64; AXES],
    cmd: &Command,
    signal: Signal,
    out: &mut Output,
) -> Result<Option<[f64; AXES]>, Alarm> {
    let from = exec.kernel.position;
    let tool = exec.kernel.tools.in_spindle();
    let Some(t) = exec.probe.first_touch(&from, &target, tool, signal) else {
        exec.feed_to(target, cmd, true, out)?;
        return Ok(None);
    };
    let mut stop = from;
    for (s, (a, b)) in stop.iter_mut().zip(from.iter().zip(&target)) {
        *s = a + t * (b - a);
    }
    exec.feed_to(stop, cmd, true, out)?;
    Ok(Some(stop))
}
