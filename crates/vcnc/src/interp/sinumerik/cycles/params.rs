//! A standard cycle's parameters: the numbers of its call by position ([`Params`]), the planes
//! every drilling and milling cycle starts with ([`Levels`]), and the cycles' alarms.
//!
//! Never: give a left-out parameter a value other than 0 (the cycles' own default), or read
//! a length without the unit in force.

use super::super::language::Argument;
use super::super::motion::unit;
use super::super::value::Value;
use super::super::Sinumerik;
use super::{Call, MAX_DIVISIONS};
use crate::alarm::{Alarm, AlarmCode};
use crate::source::Span;

/// A cycle's alarm: the control's number first, then what is wrong.
pub(super) fn alarm(number: u32, span: Span, message: impl std::fmt::Display) -> Alarm {
    Alarm::error(
        AlarmCode::CycleParameter,
        span,
        format!("cycle alarm {number}: {message}"),
    )
}

/// Alarm 61002 "machining type defined incorrectly" for VARI `vari`, with the values the cycle
/// takes.
pub(super) fn machining_type(p: &Params, vari: i64, values: &str) -> Alarm {
    alarm(
        61002,
        p.span,
        format_args!(
            "{}: machining type defined incorrectly: VARI {vari}",
            p.name()
        ),
    )
    .with_help(format!("VARI: {values}"))
}

/// A cycle's parameters as numbers, by position (0-based), lengths in mm.
pub(super) struct Params {
    name: String,
    values: Vec<Option<f64>>,
    /// The parameters given as strings (a contour's name), by position.
    texts: Vec<(usize, String)>,
    /// The factor of lengths: 25.4 under G70/G700.
    unit: f64,
    /// The call's span: where a cycle's alarm points.
    pub(super) span: Span,
}

impl Params {
    /// The arguments of `call`, each a number or left out.
    pub(super) fn read(front: &mut Sinumerik, call: &Call) -> Result<Params, Alarm> {
        let mut values = Vec::with_capacity(call.arguments.len());
        let mut texts = Vec::new();
        for (index, argument) in call.arguments.iter().enumerate() {
            let value = match argument {
                Argument::Omitted => None,
                Argument::Value(value) => Some(value.clone()),
                Argument::Place(place) => Some(front.vars.get(place, call.span)?),
            };
            if let Some(Value::Str(text)) = &value {
                texts.push((index, text.clone()));
            }
            values.push(value.and_then(|v| v.as_f64()));
        }
        Ok(Params {
            name: call.name.clone(),
            values,
            texts,
            unit: unit(front),
            span: call.span,
        })
    }

    /// Parameter `index` as written, if given.
    pub(super) fn number(&self, index: usize) -> Option<f64> {
        self.values.get(index).copied().flatten()
    }

    /// Parameter `index`, 0 when left out (the cycles' default for a number).
    pub(super) fn or_zero(&self, index: usize) -> f64 {
        self.number(index).unwrap_or(0.0)
    }

    /// Parameter `index` as a length in mm.
    pub(super) fn length(&self, index: usize) -> Option<f64> {
        self.number(index).map(|v| v * self.unit)
    }

    /// Parameter `index` as a length in mm, 0 when left out.
    pub(super) fn length_or_zero(&self, index: usize) -> f64 {
        self.length(index).unwrap_or(0.0)
    }

    /// Parameter `index` as a string, if given as one.
    pub(super) fn text(&self, index: usize) -> Option<&str> {
        self.texts
            .iter()
            .find(|(i, _)| *i == index)
            .map(|(_, text)| text.as_str())
    }

    /// The cycle's name, for messages.
    pub(super) fn name(&self) -> &str {
        &self.name
    }
}

/// The planes of a drilling cycle along the tool axis: the retraction plane (RTP), the
/// reference plane (RFP), the safety clearance above it (SDIS) and the final depth (DP, or
/// DPR below the reference plane), read from the first five parameters every drilling and
/// milling cycle shares.
#[derive(Clone, Copy, Debug)]
pub(super) struct Levels {
    pub(super) retraction: f64,
    pub(super) reference: f64,
    /// The reference plane brought forward by the safety clearance.
    pub(super) safety: f64,
    pub(super) depth: f64,
}

impl Levels {
    /// RTP, RFP, SDIS, DP, DPR at `first..first + 5` (DPR at `relative`, when the cycle has
    /// one).
    ///
    /// The cycles manual: a relative depth DPR, when given, wins over DP. **Inferred**: the
    /// cycles drill toward the tool axis' negative side (G17: -Z), and alarm 61101 "reference
    /// plane defined incorrectly" stands for a depth not below the reference plane and for a
    /// retraction plane below it.
    pub(super) fn read(params: &Params, relative: Option<usize>) -> Result<Levels, Alarm> {
        Levels::read_from(params, 0, relative)
    }

    /// RTP, RFP, SDIS, DP at `first..first + 4` (a cycle whose first parameter is something
    /// else: CYCLE72's contour), DPR at `relative`, as [`Levels::read`].
    pub(super) fn read_from(
        params: &Params,
        first: usize,
        relative: Option<usize>,
    ) -> Result<Levels, Alarm> {
        let retraction = params.length_or_zero(first);
        let reference = params.length_or_zero(first + 1);
        let clearance = params.length_or_zero(first + 2).abs();
        let depth = match relative.and_then(|i| params.length(i)) {
            Some(below) if below != 0.0 => reference - below.abs(),
            _ => params.length_or_zero(first + 3),
        };
        if depth >= reference {
            return Err(alarm(
                61101,
                params.span,
                format_args!(
                    "{}: reference plane defined incorrectly: the depth {depth} is not below the reference plane {reference}",
                    params.name()
                ),
            )
            .with_help("give the final depth below the reference plane (DP), or the depth below it (DPR)"));
        }
        if retraction < reference {
            return Err(alarm(
                61101,
                params.span,
                format_args!(
                    "{}: reference plane defined incorrectly: the retraction plane {retraction} is below the reference plane {reference}",
                    params.name()
                ),
            )
            .with_help("the retraction plane RTP must be at or above the reference plane RFP"));
        }
        Ok(Levels {
            retraction,
            reference,
            safety: reference + clearance,
            depth,
        })
    }
}

/// Alarm V007 for a count of holes or slots beyond [`MAX_DIVISIONS`].
pub(super) fn too_many(p: &Params, count: f64, what: &str) -> Alarm {
    Alarm::error(
        AlarmCode::ValueOutOfRange,
        p.span,
        format!(
            "{}: {count} {what} is more than vcnc runs in one call ({MAX_DIVISIONS})",
            p.name()
        ),
    )
}
