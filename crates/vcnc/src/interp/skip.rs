//! G31, the skip function (Syntec spec 1.20, manual 000:L1353-1419): a cutting move toward the
//! end point that a skip signal (a touch probe, a tool setter) ends where it comes; the control
//! records that position and the next block starts from it.
//!
//! vcnc has no probe and no workpiece to touch: the signal never comes, so the block runs to
//! its end point like G01 (what the spec infers for a block without the signal) and that end
//! point is the recorded skip position (FANUC #5061-#5066, in program coordinates). A probing
//! macro then sees "no contact", as on a machine with nothing under the probe. The control
//! brings the axes to rest at the end of the block: the move has an exact stop.
//!
//! Q (Syntec's choice of PLC signal, Q101-Q132) selects nothing here.

use super::decode::Command;
use super::exec::Executor;
use super::Output;
use crate::alarm::{Alarm, AlarmCode};

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
    exec.feed_to(target, cmd, true, out)?;
    exec.skip_position = exec.kernel.program_position();
    Ok(())
}
