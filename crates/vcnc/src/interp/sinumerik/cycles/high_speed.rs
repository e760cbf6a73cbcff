//! CYCLE832, the high-speed settings of the 840D's technology cycles: it selects the rounding
//! of the continuous path with its tolerance, which is what the planner times (path_control.rs).
//!
//! The parameters by position, as vcnc reads them (inferred: the manual lists the cycle by
//! name only, sinumerik-tables.md 12; docs/SINUMERIK.md 12): 0 the tolerance (_TOL, mm or
//! inch), 1 the machining type (_TOLM: its units digit 0 deselects, 1 finishing, 2 semi-
//! finishing, 3 roughing), 2 the cycle's version (_V832, not read). Every machining type
//! selects G642 with the tolerance (the control's choice of its dynamic group, DYNFINISH and
//! the like, changes no limit vcnc has); deselection, `CYCLE832()` or a type of 0, is G64
//! with the machine's tolerance again.

use super::super::path_control::Rounding;
use super::super::Sinumerik;
use super::params::{machining_type, Params};
use crate::alarm::{Alarm, AlarmCode};
use crate::motion::Smoothing;

/// Runs CYCLE832 with `p`.
pub(super) fn settings(front: &mut Sinumerik, p: &Params) -> Result<(), Alarm> {
    let kind = p.or_zero(1);
    let whole = kind.fract() == 0.0 && (0.0..=10_000.0).contains(&kind);
    let select = kind as i64 % 10;
    if !whole || select > 3 {
        return Err(machining_type(
            p,
            kind as i64,
            "0 (deselect), 1 (finishing), 2 (semi-finishing), 3 (roughing)",
        ));
    }
    let control = &mut front.modal.path_control;
    front.modal.exact_stop = false;
    if select == 0 {
        control.rounding = Rounding::None;
        control.tolerance = None;
        return Ok(());
    }
    let tolerance = p.length_or_zero(0);
    if !(0.0..=Smoothing::MAX_MM).contains(&tolerance) {
        return Err(Alarm::error(
            AlarmCode::ValueOutOfRange,
            p.span,
            format!(
                "CYCLE832: a tolerance of {tolerance} mm; it is 0 to {} mm",
                Smoothing::MAX_MM
            ),
        ));
    }
    control.rounding = Rounding::Tolerance(2);
    // A tolerance of 0 leaves the machine's (planner.rounding_tolerance).
    control.tolerance = (tolerance > 0.0).then_some(tolerance);
    Ok(())
}
