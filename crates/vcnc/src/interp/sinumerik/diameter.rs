//! Diameter programming (PGsl 8.3.6 and 8.3.7, seed 002 L4504-4764): a lathe's transverse axis,
//! and any other axis given it, programmed in diameter while the control moves it in radius.
//!
//! The channel's mode (group 29: DIAMOF, the power-on state, DIAMON, DIAM90) acts on the
//! transverse axis (MD20100 `$MC_DIAMETER_AX_DEF`; vcnc's is the first geometry axis, X, the
//! turning convention of PGsl 8.4, L4765-4791). DIAMONA[ax], DIAM90A[ax] and DIAMOFA[ax] give an
//! axis a mode of its own; DIAMCHANA[ax] and DIAMCHAN give the channel's back. DAC, DIC, RAC and
//! RIC give one value its dimension for its word only. [`convert`] runs once per block, after
//! its G functions took effect and before its end point is worked out: every value the mode
//! makes a diameter is halved there, so the programmed position and the motion stay radii.
//!
//! Which values (L4527-4541, L4556-4564): DIAMON halves absolute and incremental values, DIAM90
//! absolute ones only, DIAMOF none; I, J, K are diameters only when written with AC (an
//! incremental centre is always a radius); CIP's intermediate point is a position like the end
//! point (a choice: the manual's list names "end positions" without it). **Choices**: the
//! frame instructions (TRANS X..), G25/G26 with axes and the polar words keep their values as
//! written (the manual's list of diameter values, L4552-4568, does not name them); MD30460,
//! which admits an axis to axis-specific diameter programming, is not modelled: any linear axis
//! is admitted, a rotary one alarms (L4606-4610: "a rotary axis cannot be a transverse axis").
//! DIAMCYCOF and DIACYCOFA[ax] are accepted and change nothing: the cycles vcnc runs compute in
//! radius anyway, and the blocks keep the mode in force (L4543-4545). `$P_EP` and `$AA_IW` read
//! a diameter axis's work position as a diameter (L4547-4549); `$AA_IM`, the machine's, stays
//! a radius.
//!
//! Never: halve a value twice (a DAC/RAC word is out of the mode's reach), or halve a rotary
//! axis.

use super::block::{AxisValue, Words};
use super::Sinumerik;
use crate::alarm::{Alarm, AlarmCode};
use crate::machine::AXES;
use crate::source::Span;
use crate::syntax::sinumerik::Word;

/// How an axis's values are read: the members of group 29 and their axis-specific forms.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Dimension {
    /// DIAMOF, DIAMOFA: radius, absolute and incremental.
    Radius,
    /// DIAMON, DIAMONA: diameter, absolute and incremental.
    Diameter,
    /// DIAM90, DIAM90A: diameter when absolute, radius when incremental.
    DiameterAbsolute,
}

impl Dimension {
    /// True when a value written `absolute` (or incrementally) is a diameter.
    fn halves(self, absolute: bool) -> bool {
        match self {
            Dimension::Radius => false,
            Dimension::Diameter => true,
            Dimension::DiameterAbsolute => absolute,
        }
    }
}

/// The diameter commands.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Command {
    /// DIAMOF, DIAMON, DIAM90: the channel's mode.
    Channel(Dimension),
    /// DIAMCHAN: every axis with a mode of its own takes the channel's again.
    AllToChannel,
    /// DIAMCYCOF, DIACYCOFA[ax]: radius inside cycles.
    CyclesInRadius,
    /// DIAMONA, DIAM90A, DIAMOFA: an axis's own mode (needs `[axis]`).
    Axis(Dimension),
    /// DIAMCHANA[ax]: the axis takes the channel's mode.
    AxisToChannel,
}

/// The command a name is, if any.
pub(super) fn command(name: &str) -> Option<Command> {
    Some(match name {
        "DIAMOF" => Command::Channel(Dimension::Radius),
        "DIAMON" => Command::Channel(Dimension::Diameter),
        "DIAM90" => Command::Channel(Dimension::DiameterAbsolute),
        "DIAMCHAN" => Command::AllToChannel,
        "DIAMCYCOF" | "DIACYCOFA" => Command::CyclesInRadius,
        "DIAMOFA" => Command::Axis(Dimension::Radius),
        "DIAMONA" => Command::Axis(Dimension::Diameter),
        "DIAM90A" => Command::Axis(Dimension::DiameterAbsolute),
        "DIAMCHANA" => Command::AxisToChannel,
        _ => return None,
    })
}

/// What an axis follows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum AxisMode {
    /// The channel's mode (the transverse axis, and axes given it by DIAMCHANA).
    Channel,
    /// A mode of its own.
    Own(Dimension),
}

/// The diameter programming in force.
#[derive(Clone, Copy, Debug)]
pub(super) struct Diameter {
    channel: Dimension,
    /// The member of group 29 last programmed, as `$P_GG[29]` reads it: DIAMOF 1, DIAMON 2,
    /// DIAM90 3, DIAMCYCOF 4 (sinumerik-tables.md, group 29).
    member: i32,
    axes: [AxisMode; AXES],
    /// Axes an axis-specific command named: those DIAMCHAN gives the channel's mode.
    admitted: [bool; AXES],
}

/// The transverse axis of MD20100: the first geometry axis.
const TRANSVERSE: usize = 0;

impl Default for Diameter {
    fn default() -> Diameter {
        let mut axes = [AxisMode::Own(Dimension::Radius); AXES];
        axes[TRANSVERSE] = AxisMode::Channel;
        Diameter {
            channel: Dimension::Radius,
            member: 1,
            axes,
            admitted: [false; AXES],
        }
    }
}

impl Diameter {
    /// How the values of axis `axis` are read now.
    pub(super) fn dimension(&self, axis: usize) -> Dimension {
        match self.axes[axis] {
            AxisMode::Channel => self.channel,
            AxisMode::Own(dimension) => dimension,
        }
    }

    /// The factor of the work position's readout (`$P_EP`, `$AA_IW`): 2 while the axis is
    /// programmed in diameter, DIAM90 included (L4547-4549, L4740-4744).
    pub(super) fn readout(&self, axis: usize) -> f64 {
        match self.dimension(axis) {
            Dimension::Radius => 1.0,
            Dimension::Diameter | Dimension::DiameterAbsolute => 2.0,
        }
    }

    /// The member of group 29 in force (`$P_GG[29]`).
    pub(super) fn group_member(&self) -> i32 {
        self.member
    }

    /// A command of the channel (no axis).
    fn apply(&mut self, command: Command, span: Span) -> Result<(), Alarm> {
        match command {
            Command::Channel(dimension) => {
                self.channel = dimension;
                self.member = match dimension {
                    Dimension::Radius => 1,
                    Dimension::Diameter => 2,
                    Dimension::DiameterAbsolute => 3,
                };
            }
            Command::AllToChannel => {
                for (mode, admitted) in self.axes.iter_mut().zip(self.admitted) {
                    if admitted {
                        *mode = AxisMode::Channel;
                    }
                }
            }
            Command::CyclesInRadius => self.member = 4,
            Command::Axis(_) | Command::AxisToChannel => {
                return Err(Alarm::error(
                    AlarmCode::MissingValue,
                    span,
                    "an axis-specific diameter command names its axis: DIAMONA[X]",
                ))
            }
        }
        Ok(())
    }

    /// A command for axis `axis`.
    fn apply_to_axis(&mut self, command: Command, axis: usize) {
        self.admitted[axis] = true;
        match command {
            Command::Axis(dimension) => self.axes[axis] = AxisMode::Own(dimension),
            Command::AxisToChannel => self.axes[axis] = AxisMode::Channel,
            _ => {}
        }
    }
}

/// DIAMON, DIAMOF, DIAM90, DIAMCHAN, DIAMCYCOF as a block's G function.
///
/// # Errors
/// An axis-specific command without its axis.
pub(super) fn apply(front: &mut Sinumerik, command: Command, span: Span) -> Result<(), Alarm> {
    front.diameter.apply(command, span)
}

/// `DIAMONA[Y]`, `DIAM90A[X]`, `DIAMOFA[Y]`, `DIACYCOFA[X]`, `DIAMCHANA[Y]`: false for other
/// words.
///
/// # Errors
/// Anything but one axis in the brackets, an axis the machine lacks, a rotary axis.
pub(super) fn axis_word(front: &mut Sinumerik, word: &Word) -> Result<bool, Alarm> {
    // The channel's commands (DIAMON ...) take no axis: `DIAMON[X]` is an unknown word.
    let command = match (command(&word.address), &*word.address) {
        (Some(command @ (Command::Axis(_) | Command::AxisToChannel)), _) => command,
        (Some(command), "DIACYCOFA") => command,
        _ => return Ok(false),
    };
    let name = super::geo_axes::bracketed_axis(word)?;
    let Some(axis) = front.axes.index(name) else {
        return Err(Alarm::error(
            AlarmCode::AxisNotOnMachine,
            word.span,
            format!("{}[{name}]: the machine has no axis {name}", word.address),
        ));
    };
    if front.axes.rotary()[axis] {
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            word.span,
            format!(
                "{}[{name}]: a rotary axis cannot be programmed in diameter",
                word.address
            ),
        )
        .with_help("name a linear axis (the manual, L4606-4610)"));
    }
    front.diameter.apply_to_axis(command, axis);
    Ok(true)
}

/// The form of a value written `AC(..)`, `IC(..)`, `DAC(..)` ...: absolute (true) or
/// incremental, and for DAC/DIC/RAC/RIC whether it is a diameter; None for any other name.
/// DC, ACP and ACN position a rotary axis absolutely by the shortest way or in a direction;
/// vcnc's rotary axes do not roll over, so they are absolute (a choice).
pub(super) fn value_form(name: &str) -> Option<(bool, Option<bool>)> {
    Some(match name {
        "AC" | "DC" | "ACP" | "ACN" => (true, None),
        "IC" => (false, None),
        "DAC" => (true, Some(true)),
        "DIC" => (false, Some(true)),
        "RAC" => (true, Some(false)),
        "RIC" => (false, Some(false)),
        _ => return None,
    })
}

/// No axis is programmed in diameter (DIAMOF, no DIAMONA): only DAC and DIC make a value a
/// diameter.
pub(super) fn is_off(front: &Sinumerik) -> bool {
    front.diameter.channel == Dimension::Radius && !front.diameter.admitted.contains(&true)
}

/// The block's axis, centre and intermediate-point values in radius: each value the diameter
/// programming in force (or its own DAC/DIC) makes a diameter halved. Runs after the block's G
/// functions (G90/G91, DIAMON in the block act on its values).
pub(super) fn convert(front: &Sinumerik, words: &mut Words<'_>) {
    let common = is_off(front);
    let written = |v: &Option<AxisValue>| v.is_some_and(|v| v.diameter == Some(true));
    if common
        && !words.axes.iter().any(written)
        && !words.centre.iter().chain(&words.via).any(written)
        && !words
            .positioning
            .iter()
            .any(|(_, v)| v.diameter == Some(true))
    {
        // Nothing is a diameter: the common block of a mill.
        return;
    }
    let absolute = front.modal.absolute;
    let diameter = &front.diameter;
    let rotary = front.axes.rotary();
    let halve = |value: &mut AxisValue, axis: usize, centre: bool| {
        let is_diameter = match value.diameter {
            Some(written) => written,
            // An incremental centre is always a radius (L4563-4564).
            None if centre => value.absolute == Some(true) && diameter.dimension(axis).halves(true),
            None => diameter
                .dimension(axis)
                .halves(value.absolute.unwrap_or(absolute)),
        };
        if is_diameter && !rotary[axis] {
            value.value /= 2.0;
        }
    };
    for (axis, value) in words.axes.iter_mut().enumerate() {
        if let Some(value) = value {
            halve(value, axis, false);
        }
    }
    for (axis, value) in words.centre.iter_mut().enumerate() {
        if let Some(value) = value {
            halve(value, axis, true);
        }
    }
    for (axis, value) in words.via.iter_mut().enumerate() {
        if let Some(value) = value {
            halve(value, axis, false);
        }
    }
    for (axis, value) in words.positioning.iter_mut() {
        halve(value, *axis, false);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn diamon_halves_both_dimensions_and_diam90_only_absolute_ones() {
        // The table of L4527-4541.
        assert!(Dimension::Diameter.halves(true) && Dimension::Diameter.halves(false));
        assert!(Dimension::DiameterAbsolute.halves(true));
        assert!(!Dimension::DiameterAbsolute.halves(false));
        assert!(!Dimension::Radius.halves(true) && !Dimension::Radius.halves(false));
    }

    #[test]
    fn an_axis_of_its_own_follows_the_channel_again_after_diamchan() {
        let span = Span::new(crate::source::FileId(0), 1, 0..0);
        let mut diameter = Diameter::default();
        diameter.apply_to_axis(Command::Axis(Dimension::Diameter), 1);
        diameter
            .apply(Command::Channel(Dimension::Radius), span)
            .unwrap();
        assert_eq!(diameter.dimension(0), Dimension::Radius);
        assert_eq!(diameter.dimension(1), Dimension::Diameter);
        diameter.apply(Command::AllToChannel, span).unwrap();
        assert_eq!(diameter.dimension(1), Dimension::Radius);
        diameter
            .apply(Command::Channel(Dimension::DiameterAbsolute), span)
            .unwrap();
        assert_eq!(diameter.dimension(1), Dimension::DiameterAbsolute);
        // Z was never named: radius whatever the channel says.
        assert_eq!(diameter.dimension(2), Dimension::Radius);
        assert!(diameter.apply(Command::AxisToChannel, span).is_err());
    }
}
