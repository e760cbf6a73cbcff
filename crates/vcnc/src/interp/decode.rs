//! Decoding: the words of one block sorted into what the control reads from them.
//!
//! [`decode`] checks what can be checked without state (unknown G codes, two codes of one group,
//! an address written twice, a decimal point where none is allowed) and returns a [`Command`]:
//! the G codes by group, the axis words, the other addresses. Values stay as written; the
//! executor converts them with the units in force.

use crate::alarm::{Alarm, AlarmCode};
use crate::machine::Axis;
use crate::profile::{
    classify_g, classify_m, g_name, not_supported_description, GCode, GLookup, Group, MCode,
    MLookup, Profile, SameGroupRule,
};
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

/// The block, sorted. Storage is compact (indexes into two short lists) because a command is
/// cleared and refilled for every block: clearing costs a few dozen bytes, not kilobytes.
#[derive(Clone, Debug, Default)]
pub(crate) struct Command {
    pub(crate) span: Span,
    pub(crate) sequence: Option<u32>,
    /// G09 in the block.
    pub(crate) exact_stop_once: bool,
    /// Syntec's `F2=`: a canned cycle's retract feed.
    pub(crate) retract_feed: Option<Value>,
    /// Per address letter A-Z: 1 + index into `values`, 0 when absent (G, M and N are kept apart).
    letters: [u8; 26],
    /// Bit i set when the axis word of axis index i is present.
    axis_mask: u8,
    values: Vec<Value>,
    /// Per group slot: 1 + index into `g_words`, 0 when absent (the last code written wins).
    groups: [u8; GROUP_SLOTS],
    g_words: Vec<GWord>,
    m: Vec<Value>,
    /// Warnings found while decoding (the block still runs).
    pub(crate) warnings: Vec<Alarm>,
    /// A subprogram call, return or interrupt code (M98, M99, M97, M198, M96): the macro
    /// layer runs it after the block's other words.
    pub(crate) subprogram: Option<(MCode, Value)>,
    /// G65 or G66: the block is a macro call; the words from this index on are its arguments
    /// and were not decoded.
    pub(crate) macro_call: Option<(GWord, usize)>,
}

impl Command {
    /// The G code of a group, if the block has one.
    pub(crate) fn group(&self, group: Group) -> Option<GWord> {
        match self.groups[group_slot(group)] {
            0 => None,
            i => Some(self.g_words[usize::from(i) - 1]),
        }
    }

    /// Every G code of the block in force, one per group, in the order written.
    pub(crate) fn g_codes(&self) -> impl Iterator<Item = GWord> + '_ {
        // A code overridden by a later one of its group is not in force.
        self.g_words
            .iter()
            .enumerate()
            .filter(|(i, g)| usize::from(self.groups[group_slot(g.code.group())]) == i + 1)
            .map(|(_, g)| *g)
    }

    /// The value of an address letter (`b'R'`), if the block has it.
    pub(crate) fn word(&self, letter: u8) -> Option<Value> {
        match self
            .letters
            .get(usize::from(letter.wrapping_sub(b'A')))
            .copied()
            .unwrap_or(0)
        {
            0 => None,
            i => Some(self.values[usize::from(i) - 1]),
        }
    }

    /// The axis word of axis index `i` (X Y Z A B C).
    pub(crate) fn axis(&self, i: usize) -> Option<Value> {
        self.word(b"XYZABC"[i])
    }

    /// The centre word I, J or K for axis index 0, 1 or 2.
    pub(crate) fn center(&self, i: usize) -> Option<Value> {
        self.word(b"IJK"[i])
    }

    pub(crate) fn r(&self) -> Option<Value> {
        self.word(b'R')
    }
    pub(crate) fn f(&self) -> Option<Value> {
        self.word(b'F')
    }
    pub(crate) fn s(&self) -> Option<Value> {
        self.word(b'S')
    }
    pub(crate) fn t(&self) -> Option<Value> {
        self.word(b'T')
    }
    pub(crate) fn h(&self) -> Option<Value> {
        self.word(b'H')
    }
    pub(crate) fn p(&self) -> Option<Value> {
        self.word(b'P')
    }
    pub(crate) fn l(&self) -> Option<Value> {
        self.word(b'L')
    }

    /// The M codes in the order written.
    pub(crate) fn m_codes(&self) -> &[Value] {
        &self.m
    }

    /// Removes M02 or M30 from the block and returns it (a subprogram returns instead).
    pub(crate) fn take_program_end(&mut self) -> Option<Value> {
        let i = self
            .m
            .iter()
            .position(|m| matches!(m.number.whole(), Some(2 | 30)))?;
        Some(self.m.remove(i))
    }

    /// An empty command standing for the block at `span`.
    pub(crate) fn at(span: Span) -> Command {
        Command {
            span,
            ..Command::default()
        }
    }

    /// True when any axis word is present.
    pub(crate) fn has_axis_words(&self) -> bool {
        self.axis_mask != 0
    }

    /// The axes whose words are present, in axis order.
    pub(crate) fn axes_present(&self) -> impl Iterator<Item = Axis> + '_ {
        // The set bits of the mask, lowest first: no test for the absent axes.
        let mut mask = self.axis_mask;
        std::iter::from_fn(move || {
            let index = mask.trailing_zeros() as usize;
            mask &= mask.wrapping_sub(1);
            Axis::ALL.get(index).copied()
        })
    }

    /// Moves the word of axis `from`, if any, to the slot of axis `to`, which must be empty: in
    /// G12.1 the rotary axis's address names the plane's hypothetical second axis.
    pub(crate) fn move_axis_word(&mut self, from: Axis, to: Axis) {
        let slot = |axis: Axis| usize::from(axis.letter() - b'A');
        let (from, to) = (slot(from), slot(to));
        if self.letters[from] != 0 {
            self.letters[to] = std::mem::take(&mut self.letters[from]);
            self.axis_mask = (self.axis_mask & !AXIS_BIT[from]) | AXIS_BIT[to];
        }
    }

    /// True when S, T or an M code is present: the block has auxiliary functions to run.
    pub(crate) fn has_auxiliary_words(&self) -> bool {
        !self.m.is_empty() || self.s().is_some() || self.t().is_some()
    }

    /// True when I, J, K or R is present.
    pub(crate) fn has_center_words(&self) -> bool {
        (0..3).any(|i| self.center(i).is_some()) || self.r().is_some()
    }

    /// Clears the command for reuse, keeping its allocations.
    pub(crate) fn clear(&mut self) {
        self.span = Span::default();
        self.sequence = None;
        self.exact_stop_once = false;
        self.retract_feed = None;
        self.letters = [0; 26];
        self.axis_mask = 0;
        self.values.clear();
        self.groups = [0; GROUP_SLOTS];
        self.g_words.clear();
        self.m.clear();
        self.warnings.clear();
        self.subprogram = None;
        self.macro_call = None;
    }

    /// Records the value of an address letter.
    ///
    /// # Errors
    /// [`AlarmCode::DuplicateAddress`] when the letter was already written in the block.
    fn set(&mut self, word: &Word, value: Value) -> Result<(), Alarm> {
        let slot = usize::from(word.letter - b'A');
        if self.letters[slot] != 0 {
            let previous = self.values[usize::from(self.letters[slot]) - 1];
            return Err(Alarm::error(
                AlarmCode::DuplicateAddress,
                word.span,
                format!("address {} appears twice in the block", word.letter as char),
            )
            .with_label(previous.span, "first written here"));
        }
        self.values.push(value);
        self.letters[slot] = u8::try_from(self.values.len()).unwrap_or(u8::MAX);
        self.axis_mask |= AXIS_BIT[slot];
        Ok(())
    }
}

/// The axis-mask bit of each address letter A-Z (0 for letters that are not axes): a table, not
/// a `match`, because this runs for every word.
const AXIS_BIT: [u8; 26] = {
    let mut bits = [0u8; 26];
    let mut i = 0;
    while i < Axis::ALL.len() {
        let axis = Axis::ALL[i];
        bits[(axis.letter() - b'A') as usize] = 1 << axis.index();
        i += 1;
    }
    bits
};

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
    machine_axes: &[bool; crate::machine::AXES],
    out: &mut Command,
) -> Result<(), Alarm> {
    out.clear();
    out.span = block.span;
    for (order, word) in block.words.iter().enumerate() {
        if word.number.value.abs() > profile.max_word_value {
            return Err(Alarm::error(
                AlarmCode::ValueOutOfRange,
                word.span,
                format!(
                    "{} is out of range: the control reads values up to {}",
                    word.letter as char, profile.max_word_value
                ),
            ));
        }
        let value = Value {
            number: word.number,
            span: word.span,
            order,
        };
        // Axis words and G codes are most of every program: test for them before the `match`,
        // whose jump table mispredicts when letters alternate word after word.
        let slot = usize::from(word.letter.wrapping_sub(b'A'));
        if AXIS_BIT.get(slot).is_some_and(|bit| *bit != 0) {
            let index = AXIS_BIT[slot].trailing_zeros() as usize;
            if !machine_axes[index] {
                return Err(Alarm::error(
                    AlarmCode::AxisNotOnMachine,
                    word.span,
                    format!("the machine has no {} axis", word.letter as char),
                )
                .with_help(
                    "add the axis to the machine file (`[axes.a]` ...) or remove the word",
                ));
            }
            out.set(word, value)?;
            continue;
        }
        if word.letter == b'G' {
            decode_g(word, order, profile, out)?;
            if let Some(call) = out
                .group(Group::NonModal)
                .filter(|g| g.code == GCode::MacroCall)
            {
                out.macro_call = Some((call, order + 1));
                break;
            }
            if let Some(call) = out
                .group(Group::ModalMacro)
                .filter(|g| g.code == GCode::ModalMacroCall && g.order == order)
            {
                out.macro_call = Some((call, order + 1));
                break;
            }
            continue;
        }
        match word.letter {
            b'M' => {
                whole(word)?;
                if let MLookup::Known(code) = classify_m(word.number.value as u32, profile) {
                    if code.is_subprogram_flow() {
                        if let Some((_, first)) = out.subprogram {
                            return Err(Alarm::error(
                                AlarmCode::WordNotAllowed,
                                word.span,
                                "two subprogram codes in one block",
                            )
                            .with_label(first.span, "the first one"));
                        }
                        out.subprogram = Some((code, value));
                        continue;
                    }
                }
                if out.m.len() >= profile.m_codes_per_block as usize && !out.m.is_empty() {
                    let dropped = out.m.remove(0);
                    out.warnings.push(
                        Alarm::warning(
                            AlarmCode::WordNotAllowed,
                            dropped.span,
                            format!(
                                "this control runs {} M code(s) per block: this one is ignored",
                                profile.m_codes_per_block
                            ),
                        )
                        .with_label(word.span, "the later M code that runs"),
                    );
                }
                out.m.push(value);
            }
            b'N' => {
                whole(word)?;
                out.sequence = u32::try_from(word.number.value as i64).ok();
            }
            b'O' => {
                whole(word)?;
                out.set(word, value)?;
            }
            b'I' => out.set(word, value)?,
            b'J' => out.set(word, value)?,
            b'K' => out.set(word, value)?,
            b'R' => out.set(word, value)?,
            b'F' if word.index == 0 => out.set(word, value)?,
            b'S' if word.index == 0 => out.set(word, value)?,
            b'T' => {
                whole(word)?;
                out.set(word, value)?;
            }
            b'H' => {
                whole(word)?;
                out.set(word, value)?;
            }
            b'D' => {
                whole(word)?;
                out.set(word, value)?;
            }
            b'P' => out.set(word, value)?,
            b'Q' => out.set(word, value)?,
            // Syntec's threads per inch of a tapping cycle.
            b'E' => out.set(word, value)?,
            b'L' => {
                whole(word)?;
                out.set(word, value)?;
            }
            b'F' if word.index == 2 => out.retract_feed = Some(value),
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
                return Err(Alarm::not_supported(
                    word.span,
                    &format!("address {}", other as char),
                    None,
                ));
            }
        }
    }
    Ok(())
}

fn decode_g(word: &Word, order: usize, profile: &Profile, out: &mut Command) -> Result<(), Alarm> {
    let Some(tenths) = word.number.tenths().filter(|t| *t >= 0) else {
        return Err(Alarm::error(
            AlarmCode::UnknownGCode,
            word.span,
            format!("G{} is not a G code", word.number.value),
        ));
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
                format!(
                    "{} does not exist on the {} profile",
                    g_name(tenths),
                    profile.name
                ),
            ))
        }
    };
    if code == GCode::ExactStopOnce {
        out.exact_stop_once = true;
        return Ok(());
    }
    let slot = group_slot(code.group());
    let new = GWord {
        code,
        span: word.span,
        order,
    };
    if let Some(previous) = out.group(code.group()) {
        if previous.code != code {
            let message = format!(
                "two G codes of one modal group in a block: {} wins",
                g_name(tenths)
            );
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
    out.g_words.push(new);
    out.groups[slot] = u8::try_from(out.g_words.len()).unwrap_or(u8::MAX);
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
