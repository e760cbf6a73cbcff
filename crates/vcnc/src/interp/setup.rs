//! The control's fixed setup: the machine file, the profile it names, and what is derived from
//! them once (the axes present, the letters decoding records as written, how a number without a
//! decimal point reads).
//!
//! A part of the executor with private fields: nothing changes the setup while a program runs,
//! so what is derived from it stays right by construction. It never holds run-time state.

use super::decode::{AxisLetters, Value};
use super::modal::Units;
use crate::alarm::{Alarm, AlarmCode};
use crate::machine::{Axis, Machine, WorkOffsetId, AXES};
use crate::profile::{DecimalLess, Profile};

/// The machine and profile of a run.
#[derive(Clone, Debug)]
pub(crate) struct Setup {
    profile: Profile,
    machine: Machine,
    /// Which axes the machine has, by axis index.
    axes: [bool; AXES],
    /// How decoding reads the machine's axis words.
    axis_letters: AxisLetters,
}

impl Setup {
    /// The setup of `machine` (whose tool offsets the caller has taken: the registers are
    /// run-time state, not setup).
    pub(crate) fn new(machine: Machine) -> Setup {
        let axes = std::array::from_fn(|i| machine.axes[i].is_some());
        Setup {
            profile: machine.profile.clone(),
            axis_letters: AxisLetters::new(&machine.layout, &axes),
            axes,
            machine,
        }
    }

    /// The profile of the control.
    pub(crate) fn profile(&self) -> &Profile {
        &self.profile
    }

    /// The machine file.
    pub(crate) fn machine(&self) -> &Machine {
        &self.machine
    }

    /// Whether the machine has `axis`.
    pub(crate) fn has_axis(&self, axis: Axis) -> bool {
        self.axes[axis.index()]
    }

    /// How decoding reads the machine's axis words.
    pub(crate) fn axis_letters(&self) -> &AxisLetters {
        &self.axis_letters
    }

    /// True when `axis` is rotary on this machine.
    pub(crate) fn is_rotary(&self, axis: Axis) -> bool {
        self.machine.layout.is_rotary(axis)
    }

    /// The tool offset number an H or D word gives (`letter`).
    ///
    /// # Errors
    /// [`AlarmCode::OffsetNumberOutOfRange`] for a number the control does not have.
    pub(crate) fn offset_number(&self, word: Value, letter: char) -> Result<u32, Alarm> {
        let n = word.number.whole().unwrap_or(-1);
        let max = self.profile.compensation.max_offset_number;
        if n < 0 || n > i64::from(max) {
            return Err(Alarm::error(
                AlarmCode::OffsetNumberOutOfRange,
                word.span,
                format!("{letter}{n} is out of range: this control has {letter}0 to {letter}{max}"),
            ));
        }
        Ok(n as u32)
    }

    /// The extended work offset (G54.1) numbered by `p`, as G54.1 and G10 name it.
    ///
    /// # Errors
    /// [`AlarmCode::WorkOffsetOutOfRange`] for a number the control does not have.
    pub(crate) fn extended_offset(&self, p: &Value) -> Result<WorkOffsetId, Alarm> {
        let n = p.number.whole().unwrap_or(-1);
        let count = self.profile.coordinates.g54_1_count;
        if n < 1 || n > i64::from(count) {
            return Err(Alarm::error(
                AlarmCode::WorkOffsetOutOfRange,
                p.span,
                format!("G54.1 P{n}: this control has P1 to P{count}"),
            ));
        }
        Ok(WorkOffsetId::Extended(n as u32))
    }

    /// A length word (axis, I J K, R, Q) in `units`, converted to mm with the profile's rule
    /// for numbers without a decimal point.
    pub(crate) fn length(&self, units: Units, value: &Value) -> f64 {
        let n = value.number;
        let increment = match units {
            Units::Millimetres => self.profile.units.increment_mm,
            Units::Inches => self.profile.units.increment_inch,
        };
        let raw = if !n.decimal_point && self.profile.units.decimal_less == DecimalLess::Increments
        {
            n.value * increment
        } else if self.profile.units.drop_excess_decimals {
            drop_excess_decimals(n.value, increment)
        } else {
            n.value
        };
        raw * units.to_mm()
    }

    /// An angle in degrees (a rotary axis, G68's R, G16's angle, a hole pattern's J): in least
    /// increments when written without a decimal point on profiles that read numbers so.
    pub(crate) fn angle(&self, value: &Value) -> f64 {
        let n = value.number;
        if !n.decimal_point && self.profile.units.decimal_less == DecimalLess::Increments {
            n.value * self.profile.units.increment_deg
        } else if self.profile.units.drop_excess_decimals {
            drop_excess_decimals(n.value, self.profile.units.increment_deg)
        } else {
            n.value
        }
    }
}

/// `value` cut toward zero to a whole number of `increment`s (a power of ten): `1.23456` at
/// 0.001 is 1.234. A value already on the grid stays as written (1.234 is not 1.233 for the
/// binary error of 1.234 * 1000).
fn drop_excess_decimals(value: f64, increment: f64) -> f64 {
    let per_unit = (1.0 / increment).round();
    let steps = value * per_unit;
    let nearest = steps.round();
    let whole = if (steps - nearest).abs() < 1e-6 {
        nearest
    } else {
        steps.trunc()
    };
    whole / per_unit
}
