//! Decoding: the words of one block sorted into what the control reads from them.
//!
//! [`decode`] checks what can be checked without state (unknown G codes, two codes of one group,
//! an address written twice, a decimal point where none is allowed) and returns a [`Command`]:
//! the G codes by group, the axis words, the other addresses. Values stay as written; the
//! executor converts them with the units in force.

use crate::alarm::{Alarm, AlarmCode};
use crate::machine::{Axis, AXES};
use crate::profile::{classify_g, g_name, not_supported_description, GCode, GLookup, Group, Profile, SameGroupRule};
use crate::source::Span;
use crate::syntax::{Block, Number, Word};

/// A value as written, with where it was written and its position among the block's words.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Value {
    pub(crate) number: Number,
    pub(crate) span: Span,
    /// Index of the word in the block (word order matters for the FANUC 0M G04 quirk).
    pub(crate) order: usize,
}

/// A G code of the block.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct GWord {
    pub(crate) code: GCode,
    pub(crate) span: Span,
    pub(crate) order: usize,
}

/// Number of modal-group slots (see [`group_slot`]).
const GROUP_SLOTS: usize = 19;

/// The block, sorted.
#[derive(Clone, Debug, Default)]
pub(crate) struct Command {
    pub(crate) span: Span,
    pub(crate) sequence: Option<u32>,
    pub(crate) program_number: Option<Value>,
    /// One G code per group slot (the last one written wins).
    groups: [Option<GWord>; GROUP_SLOTS],
    /// G09 in the block.
    pub(crate) exact_stop_once: bool,
    pub(crate) axes: [Option<Value>; AXES],
    /// I, J, K.
    pub(crate) center: [Option<Value>; 3],
    pub(crate) r: Option<Value>,
    pub(crate) f: Option<Value>,
    pub(crate) s: Option<Value>,
    pub(crate) t: Option<Value>,
    pub(crate) h: Option<Value>,
    pub(crate) d: Option<Value>,
    pub(crate) p: Option<Value>,
    pub(crate) q: Option<Value>,
    pub(crate) l: Option<Value>,
    pub(crate) m: Vec<Value>,
    /// Warnings found while decoding (the block still runs).
    pub(crate) warnings: Vec<Alarm>,
}

impl Command {
    /// The G code of a group, if the block has one.
    pub(crate) fn group(&self, group: Group) -> Option<GWord> {
        self.groups[group_slot(group)]
    }

    /// Every G code of the block, one per group, in group order.
    pub(crate) fn g_codes(&self) -> impl Iterator<Item = GWord> + '_ {
        self.groups.iter().flatten().copied()
    }

    /// An empty command standing for the block at `span`.
    pub(crate) fn at(span: Span) -> Command {
        Command { span, ..Command::default() }
    }

    /// True when any axis word is present.
    pub(crate) fn has_axis_words(&self) -> bool {
        self.axes.iter().any(Option::is_some)
    }

    /// Clears the command for reuse.
    pub(crate) fn clear(&mut self) {
        let mut m = std::mem::take(&mut self.m);
        let mut warnings = std::mem::take(&mut self.warnings);
        m.clear();
        warnings.clear();
        *self = Command { m, warnings, ..Command::default() };
    }
}

fn group_slot(group: Group) -> usize {
    match group {
        Group::NonModal => 0,
        Group::Motion => 1,
        Group::Plane => 2,
        Group::Distance => 3,
        Group::FeedMode => 4,
        Group::Units => 5,
        Group::CutterComp => 6,
        Group::LengthComp => 7,
        Group::Cycle => 8,
        Group::CycleReturn => 9,
        Group::Scaling => 10,
        Group::ModalMacro => 11,
        Group::SpindleMode => 12,
        Group::WorkOffset => 13,
        Group::PathMode => 14,
        Group::Rotation => 15,
        Group::Polar => 16,
        Group::PolarInterpolation => 17,
        Group::Mirror => 18,
    }
}

/// Sorts the words of `block` into `out`.
///
/// # Errors
/// The first alarm of the block: unknown or unsupported G codes, addresses written twice,
/// decimal points where none is allowed, axis words for axes the machine lacks.
pub(crate) fn decode(
    block: &Block,
    profile: &Profile,
    has_axis: &dyn Fn(Axis) -> bool,
    out: &mut Command,
) -> Result<(), Alarm> {
    out.clear();
    out.span = block.span;
    for (order, word) in block.words.iter().enumerate() {
        let value = Value { number: word.number, span: word.span, order };
        match word.letter {
            b'G' => decode_g(word, order, profile, out)?,
            b'M' => {
                whole(word)?;
                out.m.push(value);
            }
            b'N' => {
                whole(word)?;
                out.sequence = u32::try_from(word.number.value as i64).ok();
            }
            b'O' => {
                whole(word)?;
                set_once(&mut out.program_number, value, word)?;
            }
            b'X' | b'Y' | b'Z' | b'A' | b'B' | b'C' => {
                let axis = Axis::from_letter(word.letter).expect("letter matched as an axis above");
                if !has_axis(axis) {
                    return Err(Alarm::error(
                        AlarmCode::AxisNotOnMachine,
                        word.span,
                        format!("the machine has no {} axis", word.letter as char),
                    )
                    .with_help("add the axis to the machine file (`[axes.a]` ...) or remove the word"));
                }
                set_once(&mut out.axes[axis.index()], value, word)?;
            }
            b'I' => set_once(&mut out.center[0], value, word)?,
            b'J' => set_once(&mut out.center[1], value, word)?,
            b'K' => set_once(&mut out.center[2], value, word)?,
            b'R' => set_once(&mut out.r, value, word)?,
            b'F' if word.index == 0 => set_once(&mut out.f, value, word)?,
            b'S' if word.index == 0 => set_once(&mut out.s, value, word)?,
            b'T' => {
                whole(word)?;
                set_once(&mut out.t, value, word)?;
            }
            b'H' => {
                whole(word)?;
                set_once(&mut out.h, value, word)?;
            }
            b'D' => {
                whole(word)?;
                set_once(&mut out.d, value, word)?;
            }
            b'P' => set_once(&mut out.p, value, word)?,
            b'Q' => set_once(&mut out.q, value, word)?,
            b'L' => {
                whole(word)?;
                set_once(&mut out.l, value, word)?;
            }
            b'F' | b'S' => {
                return Err(Alarm::not_supported(
                    word.span,
                    &format!("extended address {}{}=", word.letter as char, word.index),
                    if word.letter == b'F' { Some(4) } else { None },
                ));
            }
            b'U' | b'V' | b'W' => {
                return Err(Alarm::error(
                    AlarmCode::AxisNotOnMachine,
                    word.span,
                    format!("the machine has no {} axis", word.letter as char),
                ));
            }
            other => {
                return Err(Alarm::not_supported(word.span, &format!("address {}", other as char), None));
            }
        }
    }
    Ok(())
}

fn decode_g(word: &Word, order: usize, profile: &Profile, out: &mut Command) -> Result<(), Alarm> {
    let Some(tenths) = word.number.tenths().filter(|t| *t >= 0) else {
        return Err(Alarm::error(AlarmCode::UnknownGCode, word.span, format!("G{} is not a G code", word.number.value)));
    };
    let code = match classify_g(tenths, profile) {
        GLookup::Known(code) => code,
        GLookup::NotSupported(issue) => {
            let what = match not_supported_description(tenths, profile) {
                Some(meaning) => format!("{} ({meaning})", g_name(tenths)),
                None => g_name(tenths),
            };
            return Err(Alarm::not_supported(word.span, &what, issue));
        }
        GLookup::Unknown => {
            return Err(Alarm::error(
                AlarmCode::UnknownGCode,
                word.span,
                format!("{} does not exist on the {} profile", g_name(tenths), profile.name),
            ))
        }
    };
    if code == GCode::ExactStopOnce {
        out.exact_stop_once = true;
        return Ok(());
    }
    let slot = group_slot(code.group());
    let new = GWord { code, span: word.span, order };
    if let Some(previous) = out.groups[slot] {
        if previous.code != code {
            let message = format!("two G codes of one modal group in a block: {} wins", g_name(tenths));
            match profile.same_group {
                SameGroupRule::LastWins if code.group() != crate::profile::Group::NonModal => {
                    out.warnings.push(
                        Alarm::warning(AlarmCode::SameGroupGCodes, word.span, message)
                            .with_label(previous.span, "overridden by the later code"),
                    );
                }
                _ => {
                    return Err(Alarm::error(
                        AlarmCode::SameGroupGCodes,
                        word.span,
                        "two G codes of one group in a block",
                    )
                    .with_label(previous.span, "the other code"));
                }
            }
        }
    }
    out.groups[slot] = Some(new);
    Ok(())
}

fn set_once(slot: &mut Option<Value>, value: Value, word: &Word) -> Result<(), Alarm> {
    if let Some(previous) = slot {
        return Err(Alarm::error(
            AlarmCode::DuplicateAddress,
            word.span,
            format!("address {} appears twice in the block", word.letter as char),
        )
        .with_label(previous.span, "first written here"));
    }
    *slot = Some(value);
    Ok(())
}

fn whole(word: &Word) -> Result<(), Alarm> {
    if word.number.decimal_point && word.number.value.fract() != 0.0 {
        return Err(Alarm::error(
            AlarmCode::DecimalPointNotAllowed,
            word.span,
            format!("address {} takes a whole number", word.letter as char),
        ));
    }
    if word.number.value < 0.0 && word.letter != b'H' {
        return Err(Alarm::error(
            AlarmCode::ValueOutOfRange,
            word.span,
            format!("address {} cannot be negative", word.letter as char),
        ));
    }
    Ok(())
}
