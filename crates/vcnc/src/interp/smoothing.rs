//! High-speed and smoothing modes: Syntec G05 (high-speed high-precision contour control) and
//! G05.1 (path smoothing), FANUC G05.1 Q1 (AI contour control) and G08 P1 (look-ahead control).
//!
//! The controls use these modes to keep their speed through the corners of dense CAM paths,
//! leaving the programmed path by at most a tolerance. vcnc keeps the programmed path (the
//! Syntec manual: "the nominal path is a valid approximation", spec 1.8) and hands the tolerance
//! to the planner on every motion ([`crate::motion::Move::smoothing`]), which blends corners
//! within it. G61 and G63 suspend the modes until G64 (spec 1.8 restriction 7, 1.9 restriction
//! 5): [`super::modal::ModalState::smoothing_for_motion`] leaves them out there.
//!
//! Syntec's words (spec 1.8, 1.9): `G05 P10000 [E_]` on, `G05 E_` on, `G05 P0` or a bare `G05`
//! off; `G05.1 Q1|Q2 E_` on, `G05.1 Q0` off, E clamped to 0.002..0.020 program units, a missing
//! or bad word COR-107, switching on in G61/G63 COR-106. FANUC's G05 P10000/P0, G05.1 Q1/Q0 and
//! G08 P1/P0 take no tolerance: the machine file's `planner.smoothing_tolerance` stands for the
//! control's own.

use super::decode::{Command, GWord, Value};
use super::exec::Executor;
use super::modal::FeedMode;
use crate::alarm::{Alarm, AlarmCode};
use crate::motion::{PathMode, Smoothing};
use crate::profile::{GCode, SmoothingCodes};

/// Syntec's range for G05.1's E, program units (spec 1.9 restriction 2): 2 to 20 thousandths.
const PATH_SMOOTHING_E: (f64, f64) = (0.002, 0.020);

/// The G05 P value that switches high-speed mode on.
const HIGH_SPEED_ON: f64 = 10000.0;

/// Switches the mode `g` names on or off as the block's words say.
///
/// # Errors
/// [`AlarmCode::SmoothingCommand`] for a missing or bad word, for switching a mode on in G61 or
/// G63, and for high-speed mode with inverse time feed.
pub(crate) fn switch(exec: &mut Executor, cmd: &Command, g: GWord) -> Result<(), Alarm> {
    let default = Smoothing::from_mm(exec.kernel.setup.machine().planner.smoothing_tolerance);
    match (g.code, exec.kernel.setup.profile().motion.smoothing_codes) {
        (GCode::HighSpeedMode, _) => {
            let e = cmd.word(b'E');
            // P defaults to 10000 when E is given, to 0 when neither is (spec 1.8).
            let on = match cmd.p() {
                Some(p) if p.number.value == HIGH_SPEED_ON => true,
                Some(p) if p.number.value == 0.0 => false,
                Some(p) => return Err(bad(p.span, "G05 takes P10000 (on) or P0 (off)")),
                None => e.is_some(),
            };
            exec.modal.smoothing.high_speed = if on {
                refuse_in_exact_stop(exec.modal.path_mode, g)?;
                if exec.modal.feed_mode == FeedMode::InverseTime {
                    return Err(bad(
                        g.span,
                        "high-speed mode (G05) does not run in inverse time feed (G93)",
                    ));
                }
                Some(match e {
                    Some(e) => Smoothing::from_mm(positive(exec.length(&e), e, "G05's E")?),
                    None => default,
                })
            } else {
                None
            };
        }
        (GCode::PathSmoothing, SmoothingCodes::Syntec) => {
            let q = cmd
                .word(b'Q')
                .ok_or_else(|| bad(g.span, "G05.1 needs Q: Q1 or Q2 (on) or Q0 (off)"))?;
            let q_value = q.number.value;
            exec.modal.smoothing.path = if q_value == 0.0 {
                None
            } else if q_value == 1.0 || q_value == 2.0 {
                refuse_in_exact_stop(exec.modal.path_mode, g)?;
                let e = cmd
                    .word(b'E')
                    .ok_or_else(|| bad(g.span, "G05.1 Q1 and Q2 need E, the tolerance"))?;
                let units = exec.modal.units.to_mm();
                let (low, high) = PATH_SMOOTHING_E;
                let tolerance =
                    positive(exec.length(&e), e, "G05.1's E")?.clamp(low * units, high * units);
                Some(Smoothing::from_mm(tolerance))
            } else {
                return Err(bad(q.span, "G05.1 takes Q0, Q1 or Q2"));
            };
        }
        (GCode::PathSmoothing, _) => {
            let q = cmd
                .word(b'Q')
                .ok_or_else(|| bad(g.span, "G05.1 needs Q: Q1 (on) or Q0 (off)"))?;
            exec.modal.smoothing.path = on_off(
                exec.modal.path_mode,
                g,
                q,
                "G05.1 takes Q1 (on) or Q0 (off)",
            )?
            .then_some(default);
        }
        (_, _) => {
            let p = cmd
                .p()
                .ok_or_else(|| bad(g.span, "G08 needs P: P1 (on) or P0 (off)"))?;
            exec.modal.smoothing.path =
                on_off(exec.modal.path_mode, g, p, "G08 takes P1 (on) or P0 (off)")?
                    .then_some(default);
        }
    }
    Ok(())
}

/// A FANUC switch word: 1 is on, 0 off.
fn on_off(path_mode: PathMode, g: GWord, word: Value, message: &str) -> Result<bool, Alarm> {
    let value = word.number.value;
    if value == 1.0 {
        refuse_in_exact_stop(path_mode, g)?;
        Ok(true)
    } else if value == 0.0 {
        Ok(false)
    } else {
        Err(bad(word.span, message))
    }
}

/// A tolerance word in mm: positive (spec 1.8 restriction 2, 1.9 restriction 3).
fn positive(mm: f64, e: Value, what: &str) -> Result<f64, Alarm> {
    if mm > 0.0 && mm.is_finite() {
        Ok(mm)
    } else {
        Err(bad(
            e.span,
            &format!("{what} (the tolerance) must be above zero"),
        ))
    }
}

/// The modes do not start in G61 or G63 (Syntec COR-106, spec 1.8 restriction 8).
fn refuse_in_exact_stop(path_mode: PathMode, g: GWord) -> Result<(), Alarm> {
    if matches!(path_mode, PathMode::ExactStop | PathMode::Tapping) {
        return Err(Alarm::error(
            AlarmCode::SmoothingCommand,
            g.span,
            "a high-speed or smoothing mode cannot start in exact stop (G61) or tapping (G63) mode",
        )
        .with_help("switch to G64 first (Syntec alarm COR-106)"));
    }
    Ok(())
}

fn bad(span: crate::Span, message: &str) -> Alarm {
    Alarm::error(AlarmCode::SmoothingCommand, span, message.to_string())
        .with_help("Syntec alarm COR-107: G5.1/G05 command format error")
}
