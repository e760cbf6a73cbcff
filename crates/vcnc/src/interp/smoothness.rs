//! The accuracy settings that map onto the smoothing tolerance the planner already carries
//! (interp/smoothing.rs): Haas G187 and Syntec G120.1.
//!
//! Haas G187 `[P_] [E_]` sets the smoothness level (P1 rough, P2 medium, P3 finish, over the
//! machine's setting 191) and the largest corner rounding (E, over setting 85); a bare G187
//! goes back to the settings. vcnc has no numbers for the levels: E becomes the corner tolerance
//! of every motion after it, as G05.1's E does; P alone keeps the tolerance in force, with a note;
//! a bare G187 switches the tolerance off (the machine file's `corner_tolerance` again).
//!
//! Syntec G120.1 (the code list, 000 L94-140: "multiple machining-condition sets") has no
//! syntax in the manual; the documented way to choose a set is G62/G64 Pn (spec 1.34), sets
//! kept on the control's screen. vcnc accepts it, notes that the set's values are the
//! control's own, and keeps the planner's settings.

use super::decode::{Command, GWord};
use super::exec::Executor;
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::motion::Smoothing;
use crate::profile::GCode;

/// Runs G187 or G120.1.
///
/// # Errors
/// [`AlarmCode::SmoothingCommand`] for a level other than P1-P3 or an E not above zero.
pub(crate) fn run(
    exec: &mut Executor,
    cmd: &Command,
    g: GWord,
    out: &mut Output,
) -> Result<(), Alarm> {
    match g.code {
        GCode::SmoothnessSetting => g187(exec, cmd, g, out),
        _ => {
            out.push_warning(note(
                g,
                "G120.1 selects a machining-condition set of the control's screen: vcnc keeps the machine file's planner settings",
            ));
            Ok(())
        }
    }
}

fn g187(exec: &mut Executor, cmd: &Command, g: GWord, out: &mut Output) -> Result<(), Alarm> {
    let level = cmd.p();
    if let Some(p) = level {
        if !matches!(p.number.whole(), Some(1..=3)) {
            return Err(Alarm::error(
                AlarmCode::SmoothingCommand,
                p.span,
                "G187 takes P1 (rough), P2 (medium) or P3 (finish)",
            ));
        }
    }
    match (cmd.word(b'E'), level) {
        (Some(e), _) => {
            let mm = exec.length(&e);
            if !(mm > 0.0 && mm.is_finite()) {
                return Err(Alarm::error(
                    AlarmCode::SmoothingCommand,
                    e.span,
                    "G187's E (the corner rounding) must be above zero",
                ));
            }
            exec.modal.smoothing.path = Some(Smoothing::from_mm(mm));
        }
        (None, Some(_)) => out.push_warning(note(
            g,
            "G187 P sets a smoothness level whose numbers are the machine's: the tolerance in force stays",
        )),
        (None, None) => exec.modal.smoothing.path = None,
    }
    Ok(())
}

fn note(g: GWord, message: &str) -> Alarm {
    Alarm::warning(AlarmCode::KeptAsState, g.span, message.to_string())
}
