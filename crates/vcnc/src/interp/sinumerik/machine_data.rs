//! Machine data of the dynamic response a part program reads and writes (PGsl 14.7.3, L10640-
//! 10687): `$MA_MAX_AX_ACCEL[n, axis]` (m/s^2) and `$MA_MAX_AX_JERK[n, axis]` (m/s^3), one
//! element per dynamic group n, 0 DYNNORM to 4 DYNFINISH.
//!
//! Every group reads the machine file's limit of the axis until the program writes it; a write
//! is kept for the program's later reads. vcnc plans with the machine file's limits in every
//! group (DYNNORM to DYNFINISH are kept as state, with their note), so a written value changes
//! no timing.
//!
//! Never: read or write a group outside 0 to 4, an axis the machine lacks, or a negative limit.

use crate::alarm::{Alarm, AlarmCode};
use crate::machine::AxisConfig;
use crate::source::Span;

/// The machine data this module holds.
const NAMES: [&str; 2] = ["$MA_MAX_AX_ACCEL", "$MA_MAX_AX_JERK"];

/// The values the program wrote: name, group, axis, value.
#[derive(Clone, Debug, Default)]
pub(super) struct MachineData {
    written: Vec<(&'static str, usize, usize, f64)>,
}

/// True for the machine data this module reads and writes.
pub(super) fn holds(name: &str) -> bool {
    NAMES.contains(&name)
}

/// The dynamic group of an index: 0 to 4.
fn group(index: Option<f64>, name: &str, span: Span) -> Result<usize, Alarm> {
    match index {
        Some(n) if (0.0..=4.0).contains(&n) && n.fract() == 0.0 => Ok(n as usize),
        _ => Err(Alarm::error(
            AlarmCode::BadVariable,
            span,
            format!("{name}[n, axis]: n is the dynamic group, 0 (DYNNORM) to 4 (DYNFINISH)"),
        )),
    }
}

impl MachineData {
    /// `name[group, axis]`: the value written, else the machine file's limit of `config` in
    /// the control's unit.
    pub(super) fn read(
        &self,
        name: &str,
        index: Option<f64>,
        axis: usize,
        config: Option<&AxisConfig>,
        span: Span,
    ) -> Result<f64, Alarm> {
        let group = group(index, name, span)?;
        if let Some(&(_, _, _, value)) = self
            .written
            .iter()
            .find(|(n, g, a, _)| *n == name && *g == group && *a == axis)
        {
            return Ok(value);
        }
        let config = config.ok_or_else(|| {
            Alarm::error(
                AlarmCode::BadVariable,
                span,
                format!("{name}: the machine has no such axis"),
            )
        })?;
        // The machine file holds mm/s^2 and mm/s^3; the machine data m/s^2 and m/s^3.
        Ok(if name == NAMES[0] {
            config.acceleration / 1000.0
        } else {
            config.jerk / 1000.0
        })
    }

    /// `name[group, axis] = value`.
    pub(super) fn write(
        &mut self,
        name: &str,
        index: Option<f64>,
        axis: usize,
        value: f64,
        span: Span,
    ) -> Result<(), Alarm> {
        let group = group(index, name, span)?;
        if value.is_nan() || value <= 0.0 {
            return Err(Alarm::error(
                AlarmCode::ValueOutOfRange,
                span,
                format!("{name}: a limit of the dynamic response is above 0, not {value}"),
            ));
        }
        let name = NAMES.into_iter().find(|n| *n == name).unwrap_or(NAMES[0]);
        self.written
            .retain(|(n, g, a, _)| !(*n == name && *g == group && *a == axis));
        self.written.push((name, group, axis, value));
        Ok(())
    }
}
