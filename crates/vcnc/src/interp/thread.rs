//! G33 thread cutting (Syntec spec 1.21, FANUC 0M A.30, Mitsubishi B.10): a straight move whose
//! feed is tied to the spindle, one lead per revolution, as a boring bar cuts an internal thread.
//!
//! F is the lead (mm or inch per revolution, like a length); on the Mitsubishi profile E may give
//! threads per inch instead (lead 25.4 / E mm). The axes move at lead x S. The control cuts the
//! thread with the feed override locked at 100 % and brings the axes to rest at the end of the
//! pass, as in G63 tapping mode (FANUC 0M A.30/A.31): the move carries the tapping path mode,
//! which the planner times that way. Q (Mitsubishi's start angle) changes neither path nor time.

use super::decode::Command;
use super::exec::Executor;
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::machine::AXES;
use crate::motion::{Feed, PathMode, SegmentKind};

/// Runs a G33 move to `target` (machine coordinates).
///
/// # Errors
/// No lead (F or E), G33 in cutter compensation, a position out of range.
pub(crate) fn g33(
    exec: &mut Executor,
    cmd: &Command,
    target: [f64; AXES],
    out: &mut Output,
) -> Result<(), Alarm> {
    if out.compensating() {
        return Err(Alarm::not_supported(
            cmd.span,
            "thread cutting (G33) under cutter compensation",
            None,
        ));
    }
    let lead = match cmd
        .word(b'E')
        .filter(|_| exec.kernel.setup.profile().motion.thread_e_per_inch)
    {
        Some(e) if e.number.value > 0.0 => 25.4 / e.number.value,
        Some(e) => {
            return Err(Alarm::error(
                AlarmCode::ValueOutOfRange,
                e.span,
                "E of a thread is its number of threads per inch: more than 0",
            ))
        }
        None => match exec.kernel.feed {
            Some(f) if f > 0.0 => f,
            _ => {
                return Err(Alarm::error(
                    AlarmCode::NoFeedRate,
                    cmd.span,
                    "thread cutting (G33) without a lead: give it in F",
                ))
            }
        },
    };
    if super::kernel::same_place(&target, &exec.kernel.position) {
        return Ok(());
    }
    let feed = Feed::PerRevolution {
        per_revolution: lead,
        rpm: (exec.kernel.spindle.speed() > 0.0).then_some(exec.kernel.spindle.speed()),
    };
    let mut motion = exec.move_to(target, cmd, out)?;
    motion.path_mode = PathMode::Tapping;
    motion.smoothing = None;
    out.push(cmd, SegmentKind::Line { motion, feed });
    Ok(())
}
