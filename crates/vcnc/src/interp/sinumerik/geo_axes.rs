//! The geometry axes and the channel axes behind them (PGAsl GEOAX; PGsl 6.3, seed 002
//! L2286-2318): GEOAX(n, axis) makes the channel axis `axis` the n-th geometry axis, GEOAX()
//! brings back the machine data's assignment, GEOAX(0, axis) takes the axis out of the
//! geometry axes.
//!
//! The geometry axes keep their names X, Y, Z; the channel axes are the machine file's axes by
//! name (`crate::axis`), and X1, Y1, Z1 name the channel axes behind the geometry axes at
//! power-on (the machine axis names G74 reads too). vcnc keeps the assignment (the constant
//! cutting rate's reference axis and SCC read it) but moves the geometry axes only on the
//! slots of the machine file: a block that moves a geometry axis while another channel axis
//! stands behind it alarms (V020), rather than move the wrong axis.
//!
//! **Choices**: a channel axis already behind another geometry axis is not exchanged (an alarm:
//! the manual is silent on it); the assignment is checked, not its effect on frames (the
//! control resets them on an exchange).
//!
//! Never: move a geometry axis's word on an axis other than the one the program assigned.

use super::block::Words;
use super::Sinumerik;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::kernel::Kernel;
use crate::source::Span;
use crate::syntax::sinumerik::{Expr, ExprKind, Value, Word};

/// The geometry axes' names.
const NAMES: [&str; 3] = ["X", "Y", "Z"];

/// Which channel axis (a slot of the position arrays) is each geometry axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct GeometryAxes {
    slots: [Option<usize>; 3],
}

impl Default for GeometryAxes {
    fn default() -> GeometryAxes {
        GeometryAxes {
            slots: [Some(0), Some(1), Some(2)],
        }
    }
}

impl GeometryAxes {
    /// The channel axis behind geometry axis `number` (0 for the first), if one is.
    pub(super) fn slot(&self, number: usize) -> Option<usize> {
        self.slots.get(number).copied().flatten()
    }

    /// The geometry axis channel axis `slot` is now, if it is one.
    pub(super) fn number_of(&self, slot: usize) -> Option<usize> {
        self.slots.iter().position(|s| *s == Some(slot))
    }

    /// True when every geometry axis is on its own slot: the common case.
    pub(super) fn as_at_power_on(&self) -> bool {
        *self == GeometryAxes::default()
    }
}

/// The number (0 for the first) of the geometry axis named `name`.
pub(super) fn geometry_number(name: &str) -> Option<usize> {
    NAMES.iter().position(|n| *n == name)
}

/// The channel axis `name` calls: the machine's axes by name, and X1, Y1, Z1 for the channel
/// axes of the geometry axes at power-on.
pub(super) fn channel_axis(front: &Sinumerik, name: &str) -> Option<usize> {
    if let Some(slot) = front.axes.index(name) {
        return Some(slot);
    }
    let letter = name.strip_suffix('1')?;
    geometry_number(letter).filter(|&n| front.axes.index(letter) == Some(n))
}

/// The axis of `NAME[axis]` (SCC, DIAMONA ...): one axis name in the brackets, no value.
///
/// # Errors
/// Anything else after the name.
pub(super) fn bracketed_axis(word: &Word) -> Result<&str, Alarm> {
    if let Value::Indexed(indices, None) = &word.value {
        if let [index] = indices.as_slice() {
            if let ExprKind::Name(name) = &index.kind {
                return Ok(name);
            }
        }
    }
    Err(Alarm::error(
        AlarmCode::MacroSyntax,
        word.span,
        format!("{0} takes one axis name in brackets: {0}[X]", word.address),
    ))
}

/// GEOAX(n, axis, ...) and GEOAX(): true for that word, false for any other.
///
/// # Errors
/// A geometry axis number outside 0 to 3, an axis the machine lacks, a rotary axis, an axis
/// already behind another geometry axis, an odd argument list.
pub(super) fn read_word(
    front: &mut Sinumerik,
    kernel: &Kernel,
    word: &Word,
) -> Result<bool, Alarm> {
    if &*word.address != "GEOAX" {
        return Ok(false);
    }
    let arguments: Vec<&Expr> = match &word.value {
        Value::Call(arguments) => arguments.iter().flatten().collect(),
        Value::Bare => Vec::new(),
        _ => return Ok(false),
    };
    if arguments.is_empty() {
        front.geo_axes = GeometryAxes::default();
        return Ok(true);
    }
    let syntax = || {
        Alarm::error(
            AlarmCode::MacroSyntax,
            word.span,
            "GEOAX takes pairs of a geometry axis number and a channel axis: GEOAX(1, X2)",
        )
    };
    if !arguments.len().is_multiple_of(2) {
        return Err(syntax());
    }
    let mut axes = front.geo_axes;
    for pair in arguments.chunks(2) {
        let number = front.value(kernel, pair[0])?;
        let ExprKind::Name(name) = &pair[1].kind else {
            return Err(syntax());
        };
        let slot = checked_channel_axis(front, name, word)?;
        if !(0.0..=3.0).contains(&number) || number.fract() != 0.0 {
            return Err(Alarm::error(
                AlarmCode::ValueOutOfRange,
                word.span,
                format!(
                    "GEOAX({number}, {name}): the geometry axes are 1 to 3 (0 takes the axis out)"
                ),
            ));
        }
        let owner = axes.number_of(slot);
        if number == 0.0 {
            if let Some(owner) = owner {
                axes.slots[owner] = None;
            }
            continue;
        }
        let number = number as usize - 1;
        if owner.is_some_and(|owner| owner != number) {
            return Err(Alarm::error(
                AlarmCode::WordNotAllowed,
                word.span,
                format!(
                    "GEOAX: {name} is already geometry axis {}",
                    NAMES[owner.unwrap_or(0)]
                ),
            )
            .with_help("take it out first: GEOAX(0, axis), or assign another channel axis"));
        }
        axes.slots[number] = Some(slot);
    }
    front.geo_axes = axes;
    Ok(true)
}

/// The channel axis of a GEOAX argument: on the machine and linear.
fn checked_channel_axis(front: &Sinumerik, name: &str, word: &Word) -> Result<usize, Alarm> {
    let Some(slot) = channel_axis(front, name) else {
        return Err(Alarm::error(
            AlarmCode::AxisNotOnMachine,
            word.span,
            format!("GEOAX: the machine has no channel axis {name}"),
        )
        .with_help(format!(
            "add the axis to the machine file (`[axes.{}]`)",
            name.to_ascii_lowercase()
        )));
    };
    if front.axes.rotary()[slot] {
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            word.span,
            format!("GEOAX: {name} is a rotary axis; a geometry axis is linear"),
        ));
    }
    Ok(slot)
}

/// A block that moves a geometry axis whose channel axis GEOAX changed: vcnc moves the geometry
/// axes on the machine file's slots only.
///
/// # Errors
/// V020 naming GEOAX and the axis.
pub(super) fn check_block(front: &Sinumerik, words: &Words<'_>, span: Span) -> Result<(), Alarm> {
    if front.geo_axes.as_at_power_on() {
        return Ok(());
    }
    for (number, name) in NAMES.iter().enumerate() {
        if words.axes[number].is_none() || front.geo_axes.slot(number) == Some(number) {
            continue;
        }
        let behind = front
            .geo_axes
            .slot(number)
            .map_or("no channel axis".to_string(), |s| {
                format!("channel axis {}", front.axes.name(s))
            });
        return Err(Alarm::error(
            AlarmCode::NotSupportedYet,
            span,
            format!("{name} after GEOAX, which put {behind} behind it: vcnc moves the geometry axes on their own axes only"),
        )
        .with_help("GEOAX() brings back the machine's geometry axes"));
    }
    Ok(())
}
