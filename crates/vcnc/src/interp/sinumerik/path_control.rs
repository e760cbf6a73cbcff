//! SINUMERIK's continuous-path rounding (group 10 beside G60 and G64): G641 by distance (ADIS,
//! ADISPOS) and G642-G645 within a tolerance (CYCLE832's, else the machine file's
//! `planner.rounding_tolerance`), carried to the planner as the corner smoothing of every move
//! (docs/SINUMERIK.md 4.4). The exact-stop side (G60, G9) stays the block's path mode.

use crate::motion::Smoothing;
use crate::plan::PlannerConfig;

/// How a continuous path rounds its corners.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Rounding {
    /// G64: no rounding; the planner slows at a corner as its `corner_tolerance` allows.
    None,
    /// G641: rounding by distance, ADIS for path blocks, ADISPOS for G0.
    Distance,
    /// G642, G643, G644, G645 (the number less 640): rounding within the tolerance. The planner
    /// times all four alike (a choice, docs/SINUMERIK.md 4.4).
    Tolerance(u8),
}

/// The rounding in force and its parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct PathControl {
    pub(super) rounding: Rounding,
    /// ADIS, mm: 0 (the power-on value) rounds nothing (seed 002 L8334-8391).
    pub(super) adis: f64,
    /// ADISPOS, mm, for G0 blocks.
    pub(super) adispos: f64,
    /// CYCLE832's tolerance, mm; none: the machine file's.
    pub(super) tolerance: Option<f64>,
}

impl Default for PathControl {
    fn default() -> PathControl {
        PathControl {
            rounding: Rounding::None,
            adis: 0.0,
            adispos: 0.0,
            tolerance: None,
        }
    }
}

impl PathControl {
    /// The smoothing a move gets (a rapid when `rapid`) under `config`.
    pub(super) fn smoothing(&self, rapid: bool, config: &PlannerConfig) -> Option<Smoothing> {
        match self.rounding {
            Rounding::None => None,
            Rounding::Distance => {
                let distance = if rapid { self.adispos } else { self.adis };
                // ADIS=0 behaves as G64 (seed 002 L8102-8424).
                (distance > 0.0).then(|| Smoothing::distance(distance))
            }
            Rounding::Tolerance(_) => Some(Smoothing::from_mm(
                self.tolerance.unwrap_or(config.rounding_tolerance),
            )),
        }
    }

    /// Group 10's value in `$P_GG`/`$AC_GG` with G60 off: G64 2, G641 3 ... G645 7.
    pub(super) fn group_value(&self) -> i32 {
        match self.rounding {
            Rounding::None => 2,
            Rounding::Distance => 3,
            Rounding::Tolerance(n) => 2 + i32::from(n),
        }
    }
}

/// `ADIS=` or `ADISPOS=`: the modal rounding distance of G641, in the unit in force.
pub(super) fn distance(
    front: &mut super::Sinumerik,
    kernel: &crate::interp::kernel::Kernel,
    word: &crate::syntax::sinumerik::Word,
) -> Result<(), crate::alarm::Alarm> {
    let value = super::block::number(front, kernel, word)? * super::motion::unit(front);
    if !(0.0..=Smoothing::MAX_MM).contains(&value) {
        return Err(crate::alarm::Alarm::error(
            crate::alarm::AlarmCode::ValueOutOfRange,
            word.span,
            format!(
                "{} = {value} mm: a rounding distance is 0 to {} mm",
                word.address,
                Smoothing::MAX_MM
            ),
        ));
    }
    if word.address.as_ref() == "ADIS" {
        front.modal.path_control.adis = value;
    } else {
        front.modal.path_control.adispos = value;
    }
    Ok(())
}

/// The named machining types of CYCLE832 (`CYCLE832(0.01, _FINISH)`, `CYCLE832(0, _OFF)`), which
/// the cycles' definitions give the control (**inferred** values: the units digit the cycle
/// reads, docs/SINUMERIK.md 12).
pub(super) fn constant(name: &str) -> Option<super::value::Value> {
    let kind = match name {
        "_OFF" => 0,
        "_FINISH" => 1,
        "_SEMIFIN" => 2,
        "_ROUGH" => 3,
        _ => return None,
    };
    Some(super::value::Value::Int(kind))
}
