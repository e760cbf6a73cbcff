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
#[derive(Clone, Copy, Debug, PartialEq, Default)]
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

impl Default for GWord {
    /// A stand-in for the empty slots of [`Command`]'s groups, never read.
    fn default() -> GWord {
        GWord {
            code: GCode::Linear,
            span: Span::default(),
            order: 0,
        }
    }
}

/// Number of modal-group slots (see [`group_slot`]).
const GROUP_SLOTS: usize = 19;

/// The block, sorted. A command is cleared and refilled for every block, so what is present is
/// kept in bit masks: clearing them forgets the slots behind them, which are overwritten when a
/// later block writes them and never read before.
#[derive(Clone, Debug, Default)]
pub(crate) struct Command {
    pub(crate) span: Span,
    sequence: Option<u32>,
    /// G09 in the block.
    exact_stop_once: bool,
    /// Syntec's `F2=`: a canned cycle's retract feed.
    retract_feed: Option<Value>,
    /// Bit i set when address letter `A + i` has its value in `values[i]` (G, M and N are kept
    /// apart).
    letters: u32,
    /// The value of each address letter A-Z; only those in `letters` mean anything.
    values: [Value; 26],
    /// Bit i set when group slot i has a code of the block, in `groups[i]` (the last code of
    /// its group written: the one in force).
    group_mask: u32,
    /// The code of each group slot; only those in `group_mask` mean anything. One code per
    /// group in its slot, not a list of the codes written with an index per group: a G word
    /// costs one store, and asking for a group one load.
    groups: [GWord; GROUP_SLOTS],
    m: Vec<Value>,
    /// Warnings found while decoding (the block still runs).
    warnings: Vec<Alarm>,
    /// A subprogram call, return or interrupt code (M98, M99, M97, M198, M96): the macro
    /// layer runs it after the block's other words.
    subprogram: Option<(MCode, Value)>,
    /// The text of the first comment of a G47 block (Haas engraving).
    text: Option<Box<str>>,
    /// G65 or G66: the block is a macro call; the words from this index on are its arguments
    /// and were not decoded.
    macro_call: Option<(GWord, usize)>,
    /// True when `subprogram` or `macro_call` is set: one test after every block instead of
    /// two (see [`Command::has_calls`]).
    calls: bool,
    /// True when one of the fields that few blocks set (N, G09, `F2=`, M codes, warnings,
    /// calls) may hold something: only then does [`Command::reset`] clear them. Those fields
    /// are private and every method that writes one sets this, so no field leaks into the
    /// next block.
    rare: bool,
    /// G codes classified before, kept from block to block (not cleared): a command is decoded
    /// with one profile all its life, the executor's. A small cache indexed by the value
    /// ([`LastG::slot`]): CAM programs switch between three motion codes all along.
    last_g: [Option<LastG>; LastG::SLOTS],
}

/// A G word's value (its bits) and the code and group it is on the profile.
#[derive(Clone, Copy, Debug)]
struct LastG {
    bits: u64,
    code: GCode,
    group: Group,
}

impl LastG {
    /// Entries of the cache of classified G codes.
    const SLOTS: usize = 8;

    /// The cache entry of a G word's value: a multiplicative hash of its bits, whose top bits
    /// put G00, G01, G02 and G03 in four different entries.
    #[inline]
    fn slot(bits: u64) -> usize {
        (bits.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 61) as usize
    }
}

impl Command {
    /// The G code of a group, if the block has one.
    #[inline]
    pub(crate) fn group(&self, group: Group) -> Option<GWord> {
        let slot = group_slot(group);
        if self.group_mask & (1 << slot) == 0 {
            return None;
        }
        Some(self.groups[slot])
    }

    /// True when the block's G codes, if it has any, are all of the motion group (G00-G03,
    /// G33; G09 aside): almost every block of a CAM program.
    #[inline]
    pub(crate) fn only_motion_codes(&self) -> bool {
        self.group_mask & !(1 << group_slot(Group::Motion)) == 0
    }

    /// Every G code of the block in force, one per group, in the order written.
    pub(crate) fn g_codes(&self) -> impl Iterator<Item = &GWord> + '_ {
        // The slots in use, sorted by where their codes were written (each word has its own
        // index). The codes are lent, not copied: the executor reads one field of most.
        let mut slots = [0u8; GROUP_SLOTS];
        let mut count = 0;
        let mut mask = self.group_mask;
        while mask != 0 {
            slots[count] = mask.trailing_zeros() as u8;
            count += 1;
            mask &= mask - 1;
        }
        slots[..count].sort_unstable_by_key(|slot| self.groups[usize::from(*slot)].order);
        slots
            .into_iter()
            .take(count)
            .map(|slot| &self.groups[usize::from(slot)])
    }

    /// The value of an address letter (`b'R'`), if the block has it.
    #[inline]
    pub(crate) fn word(&self, letter: u8) -> Option<Value> {
        let slot = usize::from(letter.wrapping_sub(b'A'));
        if slot >= self.values.len() || self.letters & (1 << slot) == 0 {
            return None;
        }
        Some(self.values[slot])
    }

    /// The value of an address letter (`b'X'`), lent, if the block has it.
    #[inline]
    pub(crate) fn word_ref(&self, letter: u8) -> Option<&Value> {
        let slot = usize::from(letter.wrapping_sub(b'A'));
        if slot >= self.values.len() || self.letters & (1 << slot) == 0 {
            return None;
        }
        self.values.get(slot)
    }

    /// True when an axis word beyond X Y Z (the 4th to 6th axis) is present.
    #[inline]
    pub(crate) fn has_extra_axis_words(&self) -> bool {
        self.letters & letter_bits(b"ABC") != 0
    }

    /// The axis word of axis index `i`, whatever the machine calls the axis.
    pub(crate) fn axis(&self, i: usize) -> Option<Value> {
        self.word(SLOT_LETTERS[i])
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
    #[inline]
    pub(crate) fn has_axis_words(&self) -> bool {
        self.letters & AXIS_LETTERS != 0
    }

    /// Bit i set when the axis word of axis index i is present: X Y Z are letter bits 23 to
    /// 25, A B C letter bits 0 to 2 (computed from the letters, not kept beside them: one `or`
    /// less for every word).
    #[inline]
    fn axis_mask(&self) -> u8 {
        (((self.letters >> (b'X' - b'A')) & 0b111) | ((self.letters & 0b111) << 3)) as u8
    }

    /// The axes whose words are present, in axis order.
    pub(crate) fn axes_present(&self) -> impl Iterator<Item = Axis> + '_ {
        // The set bits of the mask, lowest first: no test for the absent axes.
        let mut mask = self.axis_mask();
        std::iter::from_fn(move || {
            let index = mask.trailing_zeros() as usize;
            mask &= mask.wrapping_sub(1);
            Axis::ALL.get(index).copied()
        })
    }

    /// The axis words present with their axes, in axis order.
    #[inline]
    pub(crate) fn axis_words(&self) -> impl Iterator<Item = (Axis, &Value)> + '_ {
        // The set bits of the mask, lowest first; each axis's slot from a table.
        let mut mask = self.axis_mask();
        std::iter::from_fn(move || {
            let index = mask.trailing_zeros() as usize;
            mask &= mask.wrapping_sub(1);
            let axis = *Axis::ALL.get(index)?;
            Some((axis, &self.values[AXIS_SLOT[index]]))
        })
    }

    /// Moves the word of axis `from`, if any, to the slot of axis `to`, which must be empty: in
    /// G12.1 the rotary axis's address names the plane's hypothetical second axis.
    pub(crate) fn move_axis_word(&mut self, from: Axis, to: Axis) {
        let (from, to) = (AXIS_SLOT[from.index()], AXIS_SLOT[to.index()]);
        if self.letters & (1 << from) != 0 {
            self.values[to] = self.values[from];
            self.letters = (self.letters & !(1 << from)) | (1 << to);
        }
    }

    /// True when S, T or an M code is present: the block has auxiliary functions to run.
    pub(crate) fn has_auxiliary_words(&self) -> bool {
        !self.m.is_empty() || self.s().is_some() || self.t().is_some()
    }

    /// True when the block has nothing but a motion, plane, distance, feed or unit code, axis
    /// words, I J K R and F (and N, G09): the words of almost every block of a CAM program, which
    /// the executor runs on a short path (`Executor::run_plain`). Any other code or word, M
    /// codes included, takes the full sequence of stages.
    #[inline]
    pub(crate) fn is_plain(&self) -> bool {
        self.group_mask & !PLAIN_GROUPS == 0
            && self.letters & !PLAIN_LETTERS == 0
            && self.m.is_empty()
            && self.retract_feed.is_none()
    }

    /// True when I, J, K or R is present.
    #[inline]
    pub(crate) fn has_center_words(&self) -> bool {
        const CENTER: u32 = 1 << (b'I' - b'A') | 1 << (b'J' - b'A') | 1 << (b'K' - b'A');
        self.letters & (CENTER | 1 << (b'R' - b'A')) != 0
    }

    /// Clears the command for reuse as the command of the block at `span`, keeping its
    /// allocations.
    #[inline]
    pub(crate) fn reset(&mut self, span: Span) {
        self.span = span;
        self.letters = 0;
        self.group_mask = 0;
        if self.rare {
            self.clear_rare();
        }
    }

    /// Clears the fields few blocks set (see `rare`).
    #[inline(never)]
    fn clear_rare(&mut self) {
        self.sequence = None;
        self.exact_stop_once = false;
        self.retract_feed = None;
        self.m.clear();
        self.warnings.clear();
        self.subprogram = None;
        self.macro_call = None;
        self.calls = false;
        self.text = None;
        self.rare = false;
    }

    /// True when the block calls or returns: a subprogram code (M98, M99 ...) or a macro call
    /// (G65, G66).
    #[inline]
    pub(crate) fn has_calls(&self) -> bool {
        self.calls
    }

    /// The block's sequence number (N), if any.
    #[inline]
    pub(crate) fn sequence(&self) -> Option<u32> {
        self.sequence
    }

    /// Sets the sequence number the block's segments carry.
    pub(crate) fn set_sequence(&mut self, sequence: Option<u32>) {
        self.sequence = sequence;
        self.rare = true;
    }

    /// G09 in the block.
    #[inline]
    pub(crate) fn exact_stop_once(&self) -> bool {
        self.exact_stop_once
    }

    /// Syntec's `F2=`: a canned cycle's retract feed.
    pub(crate) fn retract_feed(&self) -> Option<Value> {
        self.retract_feed
    }

    /// The block's subprogram call, return or interrupt code, if any.
    pub(crate) fn subprogram(&self) -> Option<(MCode, Value)> {
        self.subprogram
    }

    /// The block's G65 or G66 call and the index of its first argument word, if any.
    pub(crate) fn macro_call(&self) -> Option<(GWord, usize)> {
        self.macro_call
    }

    /// True when decoding found warnings (the block still runs).
    #[inline]
    pub(crate) fn has_warnings(&self) -> bool {
        !self.warnings.is_empty()
    }

    /// The warnings decoding found, handed out once.
    pub(crate) fn take_warnings(&mut self) -> std::vec::Drain<'_, Alarm> {
        self.warnings.drain(..)
    }

    /// Records a warning about the block.
    fn warn(&mut self, warning: Alarm) {
        self.warnings.push(warning);
        self.rare = true;
    }

    /// Records the text of the block's first comment.
    #[cold]
    fn set_text(&mut self, text: &str) {
        self.text = Some(text.into());
        self.rare = true;
    }

    /// Puts `text` in place of the comment's (Haas G47 P1: the serial number to engrave).
    pub(crate) fn replace_text(&mut self, text: &str) {
        self.set_text(text);
    }

    /// True when the block is a Haas G47 P1, serial number engraving.
    pub(crate) fn engraves_serial(&self) -> bool {
        self.group(Group::NonModal)
            .is_some_and(|g| g.code == GCode::Engrave)
            && self.p().and_then(|p| p.number.whole()) == Some(1)
    }

    /// The text of the first comment of a G47 block (Haas engraving; the macro layer puts the
    /// serial number of G47 P1 in its place).
    pub(crate) fn text(&self) -> Option<&str> {
        self.text.as_deref()
    }

    /// Records the block's G65 or G66 `call`, whose arguments are the words from `arguments` on.
    fn set_macro_call(&mut self, call: GWord, arguments: usize) {
        self.macro_call = Some((call, arguments));
        self.calls = true;
        self.rare = true;
    }

    /// Records a subprogram call, return or interrupt code of the block.
    pub(crate) fn set_subprogram(&mut self, code: MCode, value: Value) {
        self.subprogram = Some((code, value));
        self.calls = true;
        self.rare = true;
    }

    /// Records the value of an address letter.
    ///
    /// # Errors
    /// [`AlarmCode::DuplicateAddress`] when the letter was already written in the block.
    // Inlined: out of line, the value and the result went through memory for every word.
    #[inline]
    fn set(&mut self, word: &Word, value: Value) -> Result<(), Alarm> {
        let slot = usize::from(word.letter.wrapping_sub(b'A'));
        let Some(stored) = self.values.get_mut(slot) else {
            return Err(not_an_address(word));
        };
        if self.letters & (1 << slot) != 0 {
            return Err(duplicate(word, stored));
        }
        *stored = value;
        self.letters |= 1 << slot;
        Ok(())
    }

    /// Records the word of a letter of the decoder's plain letters under `letter` (its own, or
    /// the slot letter of a renamed axis), whose letter bit is `bit`; `order` is its index in
    /// the block.
    ///
    /// # Errors
    /// [`AlarmCode::DuplicateAddress`] when the letter was already written in the block.
    #[inline]
    fn set_plain(&mut self, word: &Word, letter: u8, bit: u32, order: usize) -> Result<(), Alarm> {
        let slot = usize::from(letter.wrapping_sub(b'A'));
        let Some(stored) = self.values.get_mut(slot) else {
            return Err(not_an_address(word));
        };
        if self.letters & bit != 0 {
            return Err(duplicate(word, stored));
        }
        // Built in its slot, from the word: built before, it went through the stack.
        *stored = Value {
            number: word.number,
            span: word.span,
            order,
        };
        self.letters |= bit;
        Ok(())
    }
}

/// A word whose value is beyond what the control reads.
#[cold]
fn word_out_of_range(word: &Word, profile: &Profile) -> Alarm {
    Alarm::error(
        AlarmCode::ValueOutOfRange,
        word.span,
        format!(
            "{} is out of range: the control reads values up to {}",
            word.letter as char, profile.reading.max_word_value
        ),
    )
}

/// A number written with more digits than the control reads (FANUC 0M: 7): the digits of its
/// whole part, leading zeros left out, and of its fraction up to its last non-zero digit
/// (`X1.2345678` has 8, `X0.00123` 5). Counted without text: the value shifted by the
/// decimals the limit leaves must come out whole.
///
/// # Errors
/// [`AlarmCode::ValueOutOfRange`] beyond `max`.
fn check_digits(word: &Word, max: u32) -> Result<(), Alarm> {
    let value = word.number.value.abs();
    let whole_digits = if value >= 1.0 {
        value.log10().floor() as i32 + 1
    } else {
        0
    };
    let whole_after = |decimals: i32| {
        let shifted = value * 10f64.powi(decimals);
        (shifted - shifted.round()).abs() <= 1e-12 * shifted.max(1.0)
    };
    let decimals = max as i32 - whole_digits;
    if decimals >= 0 && whole_after(decimals) {
        return Ok(());
    }
    // Past the limit (the rare case): how many digits, for the message.
    let written = whole_digits + (0..17).find(|&k| whole_after(k)).unwrap_or(17);
    Err(Alarm::error(
        AlarmCode::ValueOutOfRange,
        word.span,
        format!(
            "{} is written with {written} digits: this control reads at most {max}",
            word.letter as char
        ),
    )
    .with_help("drop the decimals beyond the control's least increment"))
}

/// An axis word for an axis the machine does not have.
#[cold]
fn axis_not_on_machine(word: &Word) -> Alarm {
    Alarm::error(
        AlarmCode::AxisNotOnMachine,
        word.span,
        format!("the machine has no {} axis", word.letter as char),
    )
    .with_help(format!(
        "add the axis to the machine file (`[axes.{}]`) or remove the word",
        word.letter.to_ascii_lowercase() as char
    ))
}

/// An address letter written twice in a block; `previous` is the first.
#[cold]
fn duplicate(word: &Word, previous: &Value) -> Alarm {
    Alarm::error(
        AlarmCode::DuplicateAddress,
        word.span,
        format!("address {} appears twice in the block", word.letter as char),
    )
    .with_label(previous.span, "first written here")
}

/// A word whose letter is no address (the front ends give only letters A to Z).
#[cold]
fn not_an_address(word: &Word) -> Alarm {
    Alarm::not_supported(word.span, &format!("address {}", word.letter as char), None)
}

impl Command {
    /// Records a G code of group slot `slot`, which wins over any earlier one of its group.
    #[inline]
    fn set_group(&mut self, slot: usize, g: GWord) {
        self.groups[slot] = g;
        self.group_mask |= 1 << slot;
    }
}

/// The letter bits of the axis letters X Y Z A B C.
const AXIS_LETTERS: u32 = letter_bits(b"XYZABC");

/// The letter bits of the address letters whose words are recorded as written whatever the
/// machine: the centre words, R, P, Q and E (their values are checked where they are used).
const UNCHECKED_LETTERS: u32 = letter_bits(b"IJKRPQE");

/// The bit of each of `letters` in a letter mask (bit i for letter `A + i`).
const fn letter_bits(letters: &[u8]) -> u32 {
    let mut bits = 0u32;
    let mut i = 0;
    while i < letters.len() {
        bits |= 1 << (letters[i] - b'A');
        i += 1;
    }
    bits
}

/// The bit of a word's address letter in a letter mask, 0 for a byte that is no letter A-Z
/// (the front ends give only letters; a stray byte takes the general path and its alarm).
#[inline]
fn letter_bit(letter: u8) -> u32 {
    LETTER_BIT[usize::from(letter)]
}

/// [`letter_bit`] of every byte: a table, one load for every word of a program.
static LETTER_BIT: [u32; 256] = {
    let mut bits = [0u32; 256];
    let mut letter = b'A';
    while letter <= b'Z' {
        bits[letter as usize] = 1 << (letter - b'A');
        letter += 1;
    }
    bits
};

/// The kernel knows an ISO block by its span, N number and F word.
impl super::kernel::BlockOrigin for Command {
    #[inline(always)]
    fn span(&self) -> Span {
        self.span
    }

    #[inline(always)]
    fn sequence(&self) -> Option<u32> {
        Command::sequence(self)
    }

    fn feed_span(&self) -> Span {
        self.f().map_or(self.span, |f| f.span)
    }
}

/// The letter a [`Command`] keeps each axis's word under, by axis index, whatever the machine
/// calls the axis: X Y Z, and A B C for the 4th to 6th axes (a machine's U in the 4th slot is
/// kept as A), so the masks and slots below hold for every machine.
const SLOT_LETTERS: &[u8; crate::machine::AXES] = b"XYZABC";

/// How [`decode`] reads a machine's axis words; computed once per machine.
#[derive(Clone, Copy, Debug)]
pub(crate) struct AxisLetters {
    /// The letters recorded with no check but the duplicate one: the machine's axes kept under
    /// their own letters and [`UNCHECKED_LETTERS`]. Most words of a program are of these
    /// letters, and one mask test sorts them out.
    plain: u32,
    /// For each letter A-Z that names an axis kept under another letter (U in the 4th slot),
    /// that letter ([`SLOT_LETTERS`]); 0 for the others.
    renamed: [u8; 26],
}

impl AxisLetters {
    /// The letters of the axes `present` (by axis index) on a machine of `layout`.
    pub(crate) fn new(
        layout: &crate::machine::AxisLayout,
        present: &[bool; crate::machine::AXES],
    ) -> AxisLetters {
        let mut letters = AxisLetters {
            plain: UNCHECKED_LETTERS,
            renamed: [0; 26],
        };
        for axis in Axis::ALL.into_iter().filter(|a| present[a.index()]) {
            let slot_letter = SLOT_LETTERS[axis.index()];
            match layout.name(axis).single_letter() {
                Some(letter) if letter == slot_letter => letters.plain |= letter_bit(letter),
                Some(letter) => letters.renamed[usize::from(letter - b'A')] = slot_letter,
                // SINUMERIK's names of several characters: not an ISO address.
                None => {}
            }
        }
        letters
    }

    /// The letter an axis word of `letter` is kept under, when `letter` names a renamed axis.
    fn renamed(&self, letter: u8) -> Option<u8> {
        let to = *self.renamed.get(usize::from(letter.wrapping_sub(b'A')))?;
        (to != 0).then_some(to)
    }
}

/// The address-letter slot of each axis, by axis index.
const AXIS_SLOT: [usize; crate::machine::AXES] = {
    let mut slots = [0; crate::machine::AXES];
    let mut i = 0;
    while i < slots.len() {
        slots[i] = (SLOT_LETTERS[i] - b'A') as usize;
        i += 1;
    }
    slots
};

/// The letter-mask bits of the words of a plain block (see [`Command::is_plain`]).
const PLAIN_LETTERS: u32 = letter_bits(b"XYZABCIJKRF");

/// The group-mask bits of the codes of a plain block (see [`Command::is_plain`]): none of them
/// is read after the modal state is set, but by the motion itself.
const PLAIN_GROUPS: u32 = (1 << group_slot(Group::Motion))
    | (1 << group_slot(Group::Plane))
    | (1 << group_slot(Group::Distance))
    | (1 << group_slot(Group::FeedMode))
    | (1 << group_slot(Group::Units));

const fn group_slot(group: Group) -> usize {
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

/// Sorts the words of `block` into `out`, reading the axis words by `axes`.
///
/// # Errors
/// The first alarm of the block: unknown or unsupported G codes, addresses written twice,
/// decimal points where none is allowed, axis words for axes the machine lacks.
pub(crate) fn decode(
    block: &Block,
    profile: &Profile,
    axes: &AxisLetters,
    out: &mut Command,
) -> Result<(), Alarm> {
    out.reset(block.span);
    for (order, word) in block.words.iter().enumerate() {
        if word.number.value.abs() > profile.reading.max_word_value {
            return Err(word_out_of_range(word, profile));
        }
        if profile.reading.max_digits != 0 {
            check_digits(word, profile.reading.max_digits)?;
        }
        // Axis words are most of every program: one mask test records them (and the other
        // letters taken as written) before the G test and the `match`, whose jump table
        // mispredicts when letters alternate word after word.
        let bit = letter_bit(word.letter);
        if bit & axes.plain != 0 {
            out.set_plain(word, word.letter, bit, order)?;
            continue;
        }
        if word.letter == b'G' {
            // G65 or G66 ends the words decoded: the rest are its arguments. Asked of the word's
            // code, not of the groups afterwards: one test.
            if let Some(call) = decode_g(word, order, profile, out)? {
                out.set_macro_call(call, order + 1);
                break;
            }
            continue;
        }
        if let Some(letter) = axes.renamed(word.letter) {
            out.set_plain(word, letter, letter_bit(letter), order)?;
            continue;
        }
        decode_other(word, order, profile, out)?;
    }
    // Only G47 reads the comment's text: a statement block's comment, kept for #3000, is not
    // copied into its command every time it runs.
    if let Some(text) = &block.message {
        if out
            .group(Group::NonModal)
            .is_some_and(|g| g.code == GCode::Engrave)
        {
            out.set_text(text);
        }
    }
    Ok(())
}

/// Decodes a word that is neither of the plain letters nor a G code: N, M, F, S, T, H, D, L, O,
/// and the alarms of letters that are no address here.
///
/// # Errors
/// The word's alarm (see [`decode`]).
// Out of line: inlined, the loop over the words kept the addresses these rare arms use in
// registers or on the stack, set up for every block.
#[inline(never)]
fn decode_other(
    word: &Word,
    order: usize,
    profile: &Profile,
    out: &mut Command,
) -> Result<(), Alarm> {
    if letter_bit(word.letter) & AXIS_LETTERS != 0 {
        return Err(axis_not_on_machine(word));
    }
    let value = Value {
        number: word.number,
        span: word.span,
        order,
    };
    match word.letter {
        b'M' => {
            out.rare = true;
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
                    out.set_subprogram(code, value);
                    return Ok(());
                }
            }
            if out.m.len() >= profile.reading.m_codes_per_block as usize && !out.m.is_empty() {
                let dropped = out.m.remove(0);
                out.warn(
                    Alarm::warning(
                        AlarmCode::WordNotAllowed,
                        dropped.span,
                        format!(
                            "this control runs {} M code(s) per block: this one is ignored",
                            profile.reading.m_codes_per_block
                        ),
                    )
                    .with_label(word.span, "the later M code that runs"),
                );
            }
            out.m.push(value);
        }
        b'N' => {
            whole(word)?;
            out.set_sequence(u32::try_from(word.number.value as i64).ok());
        }
        // Numbers that must be whole: program number, tool, offset numbers, repeat count.
        b'O' | b'T' | b'H' | b'D' | b'L' => {
            whole(word)?;
            out.set(word, value)?;
        }
        // The letters of `UNCHECKED_LETTERS` are recorded above; these arms are for a caller
        // whose plain letters leave them out. E is Syntec's threads per inch of a tapping
        // cycle.
        b'I' | b'J' | b'K' | b'R' | b'P' | b'Q' | b'E' => out.set(word, value)?,
        // `S1=` names spindle 1, the one S drives (Syntec 1.64, L4865).
        b'F' | b'S' if word.index == 0 => out.set(word, value)?,
        b'S' if word.index == 1 => out.set(word, value)?,
        b'F' if word.index == 2 => {
            out.retract_feed = Some(value);
            out.rare = true;
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
            return Err(Alarm::not_supported(
                word.span,
                &format!("address {}", other as char),
                None,
            ));
        }
    }
    Ok(())
}

/// Decodes a G word; returns it when it is a macro call (G65, G66), which ends the block's words.
fn decode_g(
    word: &Word,
    order: usize,
    profile: &Profile,
    out: &mut Command,
) -> Result<Option<GWord>, Alarm> {
    // A CAM program writes the same few motion codes block after block: the codes read are
    // remembered by their values, and a value is classified again only when its entry holds
    // another. Remembering the last one alone, every switch between G01 and G02 or G03
    // classified again.
    let bits = word.number.value.to_bits();
    let entry = out.last_g.get_mut(LastG::slot(bits));
    let (code, group) = match entry {
        Some(Some(last)) if last.bits == bits => (last.code, last.group),
        _ => {
            let code = classify_g_word(word, profile)?;
            let group = code.group();
            if let Some(entry) = out.last_g.get_mut(LastG::slot(bits)) {
                *entry = Some(LastG { bits, code, group });
            }
            (code, group)
        }
    };
    if code == GCode::ExactStopOnce {
        out.exact_stop_once = true;
        out.rare = true;
        return Ok(None);
    }
    let new = GWord {
        code,
        span: word.span,
        order,
    };
    let slot = group_slot(group);
    if out.group_mask & (1 << slot) != 0 {
        // The warning of `same_group` goes where `rare` says to look.
        out.rare = true;
        if let Some(previous) = out.group(group).filter(|previous| previous.code != code) {
            same_group(word, code, previous, group, profile, out)?;
        }
    }
    out.set_group(slot, new);
    let call = matches!(code, GCode::MacroCall | GCode::ModalMacroCall);
    Ok(call.then_some(new))
}

/// The G code of a G word on `profile`.
///
/// # Errors
/// A value that is no G code, a code this profile does not have or vcnc does not support yet.
#[inline(never)]
fn classify_g_word(word: &Word, profile: &Profile) -> Result<GCode, Alarm> {
    let Some(tenths) = word.number.tenths().filter(|t| *t >= 0) else {
        return Err(Alarm::error(
            AlarmCode::UnknownGCode,
            word.span,
            format!("G{} is not a G code", word.number.value),
        ));
    };
    match classify_g(tenths, profile) {
        GLookup::Known(code) => Ok(code),
        GLookup::NotSupported(issue) => {
            let what = match not_supported_description(tenths, profile) {
                Some(meaning) => format!("{} ({meaning})", g_name(tenths)),
                None => g_name(tenths),
            };
            Err(Alarm::not_supported(word.span, &what, issue))
        }
        GLookup::Unknown => Err(Alarm::error(
            AlarmCode::UnknownGCode,
            word.span,
            format!(
                "{} does not exist on the {} profile",
                g_name(tenths),
                profile.name
            ),
        )),
    }
}

/// A second code of one group in a block, `word` after `previous`: the later one wins with a
/// warning where the profile says so, otherwise the block is refused.
///
/// # Errors
/// [`AlarmCode::SameGroupGCodes`] where the profile refuses such blocks, and always for
/// non-modal codes.
#[cold]
fn same_group(
    word: &Word,
    code: GCode,
    previous: GWord,
    group: Group,
    profile: &Profile,
    out: &mut Command,
) -> Result<(), Alarm> {
    // Of the one-shot codes only G53 and G28 may meet: "the later one is effective"
    // (Mitsubishi 003 L79).
    let g53_g28 = profile.reading.g53_g28_later_wins
        && matches!(
            (previous.code, code),
            (GCode::MachineCoordinates, GCode::ReferenceReturn)
                | (GCode::ReferenceReturn, GCode::MachineCoordinates)
        );
    match profile.reading.same_group {
        SameGroupRule::LastWins if group != Group::NonModal || g53_g28 => {
            // The word was classified, so its value is a code in tenths.
            let name = word
                .number
                .tenths()
                .map_or_else(|| format!("G{}", word.number.value), g_name);
            let message = if group == Group::NonModal {
                format!("G53 and G28 in a block: the later one, {name}, wins")
            } else {
                format!("two G codes of one modal group in a block: {name} wins")
            };
            out.warn(
                Alarm::warning(AlarmCode::SameGroupGCodes, word.span, message)
                    .with_label(previous.span, "overridden by the later code"),
            );
            Ok(())
        }
        _ => Err(Alarm::error(
            AlarmCode::SameGroupGCodes,
            word.span,
            "two G codes of one group in a block",
        )
        .with_label(previous.span, "the other code")),
    }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::machine::{AxisLayout, Machine};
    use crate::source::FileId;
    use crate::syntax::iso::{parse_line, LineBlocks, SyntaxOptions};
    use crate::syntax::lines::Line;

    /// Decodes the one block of `text` on a machine with the axes `machine_axes`.
    fn decoded(text: &str, machine_axes: [bool; 6]) -> Result<Command, Alarm> {
        let profile = Machine::default().profile;
        let mut blocks = LineBlocks::new();
        let line = Line {
            text: text.as_bytes(),
            offset: 0,
            number: 1,
        };
        parse_line(line, FileId(0), &SyntaxOptions::default(), &mut blocks);
        let block = &blocks.as_slice()[0];
        let mut cmd = Command::default();
        decode(
            block,
            &profile,
            &AxisLetters::new(&AxisLayout::default(), &machine_axes),
            &mut cmd,
        )
        .map(|()| cmd)
    }

    /// What decoding must make of words of the letters X Y Z A B C I J K R P Q E: each
    /// letter's first value, the first alarm's code and word index.
    fn expected(
        words: &[(u8, i32)],
        machine_axes: [bool; 6],
    ) -> Result<Vec<(u8, f64)>, (AlarmCode, usize)> {
        let mut seen: Vec<(u8, f64)> = Vec::new();
        for (i, &(letter, value)) in words.iter().enumerate() {
            if let Some(axis) = AxisLayout::default().by_letter(letter) {
                if !machine_axes[axis.index()] {
                    return Err((AlarmCode::AxisNotOnMachine, i));
                }
            }
            if seen.iter().any(|(l, _)| *l == letter) {
                return Err((AlarmCode::DuplicateAddress, i));
            }
            seen.push((letter, f64::from(value)));
        }
        Ok(seen)
    }

    #[test]
    fn only_the_letters_a_to_z_have_a_letter_bit() {
        for byte in 0..=u8::MAX {
            let want = if byte.is_ascii_uppercase() {
                1 << (byte - b'A')
            } else {
                0
            };
            assert_eq!(letter_bit(byte), want, "{byte}");
        }
    }

    #[test]
    fn an_axis_the_machine_lacks_is_an_alarm_with_help() {
        let alarm = decoded("G01 X1. B2.", [true, true, true, true, false, false]).unwrap_err();
        assert_eq!(alarm.code, AlarmCode::AxisNotOnMachine);
        assert_eq!(alarm.message, "the machine has no B axis");
        assert!(alarm.help.is_some());
    }

    #[test]
    fn codes_overridden_in_their_group_are_not_in_force() {
        let cmd = decoded("G00 G01 G90 X1.", [true; 6]);
        assert!(cmd.is_ok(), "{cmd:?}");
        if let Ok(cmd) = cmd {
            let codes: Vec<GCode> = cmd.g_codes().map(|g| g.code).collect();
            assert_eq!(codes, [GCode::Linear, GCode::Absolute]);
        }
        let cmd = decoded("G01 G90 X1.", [true; 6]).unwrap();
        let codes: Vec<GCode> = cmd.g_codes().map(|g| g.code).collect();
        assert_eq!(codes, [GCode::Linear, GCode::Absolute]);
    }

    #[test]
    fn codes_in_force_come_in_the_order_written() {
        // Their groups' slots are in another order (motion, plane, distance, units).
        let cmd = decoded("G20 G90 G18 G02 G91 G17 X1.", [true; 6]).unwrap();
        let codes: Vec<GCode> = cmd.g_codes().map(|g| g.code).collect();
        assert_eq!(
            codes,
            [
                GCode::Inch,
                GCode::ArcClockwise,
                GCode::Incremental,
                GCode::PlaneXy
            ]
        );
    }

    proptest::proptest! {
        #[test]
        fn words_are_recorded_as_written_or_refused(
            words in proptest::collection::vec(
                (proptest::sample::select(b"XYZABCIJKRPQE".to_vec()), -999i32..999),
                1..8,
            ),
            machine_axes in proptest::array::uniform6(proptest::bool::ANY),
        ) {
            let text: String = words
                .iter()
                .map(|(letter, value)| format!("{}{value}. ", *letter as char))
                .collect();
            let machine_axes = [true, true, true, machine_axes[3], machine_axes[4], machine_axes[5]];
            match (decoded(&text, machine_axes), expected(&words, machine_axes)) {
                (Ok(cmd), Ok(values)) => {
                    for letter in b'A'..=b'Z' {
                        let want = values.iter().find(|(l, _)| *l == letter).map(|(_, v)| *v);
                        proptest::prop_assert_eq!(cmd.word(letter).map(|v| v.number.value), want);
                    }
                    let axes: Vec<(Axis, f64)> =
                        cmd.axis_words().map(|(axis, v)| (axis, v.number.value)).collect();
                    let want: Vec<(Axis, f64)> = Axis::ALL
                        .iter()
                        .filter_map(|axis| {
                            values.iter().find(|(l, _)| *l == SLOT_LETTERS[axis.index()]).map(|(_, v)| (*axis, *v))
                        })
                        .collect();
                    proptest::prop_assert_eq!(cmd.has_axis_words(), !want.is_empty());
                    proptest::prop_assert_eq!(cmd.axes_present().count(), want.len());
                    proptest::prop_assert_eq!(axes, want);
                }
                (Err(alarm), Err((code, index))) => {
                    proptest::prop_assert_eq!(alarm.code, code);
                    let start = text.split(' ').take(index).map(|w| w.len() + 1).sum::<usize>();
                    proptest::prop_assert_eq!(alarm.span.map(|s| s.start as usize), Some(start));
                }
                (got, want) => proptest::prop_assert!(false, "{text:?}: {got:?} against {want:?}"),
            }
        }
    }

    /// What a block's command holds that a later block could see: every field but the slots
    /// the masks say are empty.
    fn contents(cmd: &Command) -> String {
        let letters: Vec<(char, f64)> = (b'A'..=b'Z')
            .filter_map(|l| cmd.word(l).map(|v| (l as char, v.number.value)))
            .collect();
        let codes: Vec<GCode> = cmd.g_codes().map(|g| g.code).collect();
        format!(
            "{:?} {:?} {} {:?} {:?} {:?} {:?} {:?} {:?} {} {}",
            cmd.sequence,
            letters,
            cmd.exact_stop_once,
            cmd.retract_feed,
            codes,
            cmd.m_codes(),
            cmd.warnings,
            cmd.subprogram,
            cmd.macro_call,
            cmd.has_calls(),
            cmd.group_mask,
        )
    }

    #[test]
    fn a_reused_command_keeps_nothing_of_the_block_before() {
        let profile = Machine::default().profile;
        let axes = AxisLetters::new(&AxisLayout::default(), &[true; 6]);
        let mut fresh = Command::default();
        let mut reused = Command::default();
        for before in [
            "N10 G01 X1.",
            "G09 G01 X1.",
            "G00 G01 X1.",
            "M03 S100",
            "M03 M08 M05",
            "M98 P100",
            "G65 P100 A1.",
            "G04 P1",
        ] {
            for after in ["X2. Y3.", "G01 X2.", "G02 X2. R1.", "F100.", "G90 G00 Z1."] {
                let parsed = |text: &str| {
                    let mut blocks = LineBlocks::new();
                    let line = Line {
                        text: text.as_bytes(),
                        offset: 0,
                        number: 1,
                    };
                    parse_line(line, FileId(0), &SyntaxOptions::default(), &mut blocks);
                    blocks.as_slice()[0].clone()
                };
                let (before_block, after_block) = (parsed(before), parsed(after));
                decode(&before_block, &profile, &axes, &mut reused).unwrap();
                assert_ne!(contents(&reused), contents(&Command::default()), "{before}");
                decode(&after_block, &profile, &axes, &mut reused).unwrap();
                decode(&after_block, &profile, &axes, &mut fresh).unwrap();
                assert_eq!(contents(&reused), contents(&fresh), "{before} then {after}");
                fresh = Command::default();
            }
        }
    }

    #[test]
    fn the_motion_codes_take_different_entries_of_the_g_code_cache() {
        let slots: Vec<usize> = [0.0f64, 1.0, 2.0, 3.0]
            .iter()
            .map(|g| LastG::slot(g.to_bits()))
            .collect();
        for (i, a) in slots.iter().enumerate() {
            assert!(*a < LastG::SLOTS);
            assert!(slots[i + 1..].iter().all(|b| b != a), "{slots:?}");
        }
    }
}
