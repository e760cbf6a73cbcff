//! The common SINUMERIK line read by a short path: what a CAM post writes block after block,
//! `N170 G1 X54.808 Y30.491 Z-1.288 F=FEED1` or `N160 G2 X51.4 Y26.2 CR=-11.7 F=FEED2`.
//!
//! A block number, then words that are a letter and a constant (`X-1.5`, `G1`) or `CR=` and `F=`
//! with a number or a variable's name (`CR=-11.7`, `F=FEED1`), then the end or a `;` comment.
//! Anything else (a blank inside a word, a skip level, a label, a keyword, an operator, a call,
//! an index, a string, another name) gives the line up, and `block.rs` reads it the general way.
//!
//! Such a line is kept decoded ([`PlainWords`]: a few numbers, nothing to allocate or drop),
//! and the interpreter runs the common ones from it directly; [`PlainWords::to_words`] makes the
//! words the general reader makes of the line, to the bit (a differential test in `block.rs`).
//!
//! The parser thread reads the common line from the text at hand ([`read_plain_in`]), before it
//! is cut out, and finds its end on the way, as the ISO reader does: no search for the `\n`
//! first, and the numbers read from windows (`decimal.rs`). A line it cannot end there goes to
//! the line reader, and is read the same way ([`read_plain`]): a differential test in
//! `block.rs` and one over the line sources in `lines.rs` check it.
//!
//! Never: raise an alarm (a line that would is given up) or read past the line (from the text
//! at hand: past its `\n`, but for a number's window, which only looks).

use super::block::{Address, Block, Value, Word};
use super::expr::{Expr, ExprKind, UnaryOp};
use crate::source::{FileId, Span};
use crate::syntax::decimal::{self, Decimal};
use crate::syntax::lines::memchr_newline;
use crate::syntax::Number;

/// A plain line's words, decoded.
#[derive(Clone, Debug, Default)]
pub struct PlainWords {
    words: [PlainWord; PlainWords::MAX],
    len: u8,
    /// The variable's name of the last `F=NAME` word read, upper case: kept from line to line,
    /// so that a program's lines with the same feed do not make its name again.
    name: Option<Address>,
    /// This line has an `F=NAME` word (its name is `name`).
    has_name: bool,
    /// The bytes of `name` as written, when it has eight or fewer, as one number (zero past
    /// its end; see [`short_name_key`]); zero for none.
    name_key: u64,
    file: FileId,
    line: u32,
    base: u32,
}

/// One word of a plain line.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlainWord {
    /// What it says.
    pub kind: PlainKind,
    /// Its bytes in the line.
    start: u16,
    end: u16,
}

/// The words a plain line holds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PlainKind {
    /// A letter, upper case, and the constant written against it (`X-1.5`, `G1`).
    Letter(u8, Number),
    /// `CR=` and a number, with whether it was written negated (`CR=-11.7`).
    Radius(f64, bool),
    /// `F=` and a number, with whether it was written negated.
    Feed(f64, bool),
    /// `F=` and a variable's name ([`PlainWords::feed_name`]).
    FeedName,
}

impl Default for PlainWord {
    fn default() -> PlainWord {
        PlainWord {
            kind: PlainKind::FeedName,
            start: 0,
            end: 0,
        }
    }
}

/// Equal when they hold the same words: the slots past them keep an earlier line's.
impl PartialEq for PlainWords {
    fn eq(&self, other: &PlainWords) -> bool {
        self.words() == other.words()
            && self.feed_name() == other.feed_name()
            && (self.file, self.line, self.base) == (other.file, other.line, other.base)
    }
}

impl PlainWords {
    /// The most words a plain line holds (a CAM line has up to about six).
    pub const MAX: usize = 8;

    /// The words, in their order.
    pub fn words(&self) -> &[PlainWord] {
        &self.words[..usize::from(self.len)]
    }

    /// The variable's name of the `F=NAME` word, upper case.
    pub fn feed_name(&self) -> Option<&str> {
        self.name.as_deref().filter(|_| self.has_name)
    }

    /// Where `word` was written.
    pub fn span(&self, word: &PlainWord) -> Span {
        self.span_of(usize::from(word.start), usize::from(word.end))
    }

    fn span_of(&self, start: usize, end: usize) -> Span {
        // The offsets fit in 16 bits (the reader gives longer lines up).
        let at = |i: usize| self.base.saturating_add(i as u32);
        Span::new(self.file, self.line, at(start)..at(end))
    }

    /// Appends the words the general reader makes of the line.
    pub fn to_words(&self, out: &mut Vec<Word>) {
        for word in self.words() {
            let (start, end) = (usize::from(word.start), usize::from(word.end));
            let span = self.span_of(start, end);
            let (address, value) = match word.kind {
                PlainKind::Letter(letter, number) => {
                    (Address::of_letter(letter), Value::Constant(number))
                }
                PlainKind::Radius(value, negated) => (
                    Address::new("CR"),
                    Value::Expression(self.number(start + 3, end, value, negated)),
                ),
                PlainKind::Feed(value, negated) => (
                    Address::of_letter(b'F'),
                    Value::Expression(self.number(start + 2, end, value, negated)),
                ),
                PlainKind::FeedName => {
                    let name = self.feed_name().unwrap_or_default();
                    let expr = Expr {
                        kind: ExprKind::Name(name.into()),
                        span: self.span_of(start + 2, end),
                    };
                    (Address::of_letter(b'F'), Value::Expression(expr))
                }
            };
            out.push(Word {
                address,
                value,
                span,
            });
        }
    }

    /// The expression of a number from `from` to `end`, negated by a `-` at `from`.
    fn number(&self, from: usize, end: usize, value: f64, negated: bool) -> Expr {
        if !negated {
            return Expr {
                kind: ExprKind::Number(value),
                span: self.span_of(from, end),
            };
        }
        let operand = Expr {
            kind: ExprKind::Number(value),
            span: self.span_of(from + 1, end),
        };
        Expr {
            kind: ExprKind::Unary(UnaryOp::Minus, Box::new(operand)),
            span: self.span_of(from, end),
        }
    }

    fn push(&mut self, kind: PlainKind, start: usize, end: usize) -> Option<()> {
        let slot = self.words.get_mut(usize::from(self.len))?;
        // The readers give up a line longer than u16::MAX bytes: no offset is cut.
        debug_assert!(start <= end && end <= usize::from(u16::MAX));
        *slot = PlainWord {
            kind,
            start: start as u16,
            end: end as u16,
        };
        self.len += 1;
        Some(())
    }
}

/// The longest line read from the text at hand ([`read_plain_in`]): a CAM line is far shorter.
/// The cut keeps the line inside what the line sources have searched for lone `\r`s ahead of the
/// reading (lines.rs: 4096 bytes), and its offsets in 16 bits; a longer line is read the usual
/// way.
const MAX_AT_HAND: usize = 512;

/// A plain line read from the text at hand.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct AtHand {
    /// The line's length without its line end (`\n` or `\r\n`).
    pub(super) length: usize,
    /// How many bytes of the text at hand follow the line's `\n`.
    pub(super) after: usize,
}

/// Reads line `text` (line `line` of `file`, at byte `base`) into `block.plain` if it is a
/// plain one, with the block number in `block.number`; false, and `block` to be emptied, if not.
pub(super) fn read_plain(
    text: &[u8],
    file: FileId,
    line: u32,
    base: u32,
    block: &mut Block,
) -> bool {
    text.len() <= usize::from(u16::MAX)
        && read_words::<false>(text, file, line, base, block).is_some()
}

/// Reads the first line of `unread` (the text at hand from a line's start on, line ends
/// included) as [`read_plain`] reads the line without its line end, and finds its end on the
/// way: the line's length and what follows its `\n`. None (and `block` to be emptied) when the
/// line is not plain, when its `\n` is not at hand or not within [`MAX_AT_HAND`] bytes, when it
/// has a `\r` elsewhere than before its `\n`, or when a number is too close to the end of the
/// text at hand for its window: the line is then read the usual way.
#[inline(always)]
pub(super) fn read_plain_in(
    unread: &[u8],
    file: FileId,
    line: u32,
    base: u32,
    block: &mut Block,
) -> Option<AtHand> {
    let text = unread.get(..MAX_AT_HAND).unwrap_or(unread);
    let rest = read_words::<true>(text, file, line, base, block)?;
    // The words end at the line end, or at a comment that runs to it.
    let (length, newline) = match rest {
        [b'\n', ..] => (text.len() - rest.len(), text.len() - rest.len()),
        [b'\r', ..] => (text.len() - rest.len(), text.len() - rest.len() + 1),
        _ => comment_end(text, text.len() - rest.len())?,
    };
    Some(AtHand {
        length,
        after: unread.len() - newline - 1,
    })
}

/// The length of a line whose words end at a `;` comment at `comment` in `text`, and the place
/// of its `\n`; None when the `\n` is not in `text`.
#[cold]
fn comment_end(text: &[u8], comment: usize) -> Option<(usize, usize)> {
    let newline = comment + memchr_newline(&text[comment..])?;
    // What the line sources hand out: the line without the `\r` of a `\r\n`.
    let length = match text[..newline] {
        [.., b'\r'] => newline - 1,
        _ => newline,
    };
    // Another `\r` in the comment is a lone one, which ends the line (lines.rs `normalize`):
    // the text in memory may not have been searched for it yet this far.
    if text[comment..length].contains(&b'\r') {
        return None;
    }
    Some((length, newline))
}

/// The reader of both: the words of `text` into `block` up to the line's end, and the bytes
/// from there on: nothing or a `;` comment, and when `AT_HAND` (`text` runs on past the line)
/// a `\n` or `\r\n` as well, or a `;` comment that runs to one. None when the line is not plain.
#[inline(always)]
fn read_words<'a, const AT_HAND: bool>(
    text: &'a [u8],
    file: FileId,
    line: u32,
    base: u32,
    block: &mut Block,
) -> Option<&'a [u8]> {
    // The line is read as a shrinking slice, by patterns, not through the scanner's general
    // steps: a long CAM program's parsing is mostly this loop. A word's place in the line is
    // the line's length less the length of what is left.
    let at = |rest: &[u8]| text.len() - rest.len();
    let mut rest = skip_blanks::<AT_HAND>(text);
    match rest {
        [b'N' | b'n', after @ ..] => match block_number(after) {
            Some((Some(number), after_number)) => {
                block.number = Some(number);
                rest = skip_blanks::<AT_HAND>(after_number);
            }
            // `N` and a letter: a name (`NOT`, a label), read as a word.
            Some((None, _)) => {}
            None => return None,
        },
        [b'/' | b':', ..] => return None,
        _ => {}
    }
    let plain = block.plain.get_or_insert_with(PlainWords::default);
    plain.len = 0;
    plain.has_name = false;
    plain.file = file;
    plain.line = line;
    plain.base = base;
    // Anything but a letter ends the words; what may end them is checked below.
    while let [letter, after @ ..] = rest {
        // An ASCII letter and its capital differ in bit 5 alone: one mask tests for a letter
        // and gives the capital.
        let capital = letter & !0x20;
        if !capital.is_ascii_uppercase() {
            break;
        }
        let start = at(rest);
        let after_word = match after {
            // `CR=..`, or `F=FEED1`: a letter as a name.
            [b, ..] if is(*b, NAME_START) || *b == b'=' => named::<AT_HAND>(text, start, plain)?,
            _ => letter_constant::<AT_HAND>(capital, after, start, plain)?,
        };
        // What follows a word: blanks, then the end, a comment or the next word's letter. An
        // operator going on with the word's value (`CR=5 DIV 2`) is a name of two letters or
        // more, which [`named`] gives up as it is neither `CR` nor `F`.
        rest = skip_blanks::<AT_HAND>(after_word);
    }
    match rest {
        [] if !AT_HAND => {}
        [b';', ..] => {}
        // Read from the text at hand, blanks leave out `\n` and `\r`: a `\r` is the line end's
        // (lone ones are made `\n`s before, lines.rs `normalize`), or the line is the line
        // reader's.
        [b'\n', ..] | [b'\r', b'\n', ..] if AT_HAND => {}
        _ => return None,
    }
    // A line without words (a comment, a number alone) is no block to run.
    if plain.len == 0 {
        block.plain = None;
    }
    Some(rest)
}

/// What the reader asks of a byte, a bit a question, answered by one load from [`CLASSES`].
type Class = u8;

/// A byte that separates words (scan.rs `is_blank`).
const BLANK: Class = 1;

/// A [`BLANK`] that is no line end (`\n`, `\r`): the blanks of the text at hand.
const BLANK_AT_HAND: Class = 2;

/// A letter or `_`: what a name starts with.
const NAME_START: Class = 4;

/// A letter some operator starts with ([`is_operator`]).
const OPERATOR_START: Class = 8;

/// A letter, a digit or `_`: what a name goes on with.
const NAME: Class = 16;

/// The classes of every byte.
const CLASSES: [Class; 256] = classes();

const fn classes() -> [Class; 256] {
    let mut table = [0; 256];
    let mut index = 0;
    while index < table.len() {
        let byte = index as u8;
        let mut class = 0;
        // scan.rs `is_blank`, which is no const fn (a test checks that they agree).
        if byte == b' ' || byte == b'&' || byte < 0x20 || byte == 0x7f {
            class |= BLANK;
            if byte != b'\n' && byte != b'\r' {
                class |= BLANK_AT_HAND;
            }
        }
        if byte.is_ascii_alphabetic() || byte == b'_' {
            class |= NAME_START | NAME;
        }
        if byte.is_ascii_digit() {
            class |= NAME;
        }
        if matches!(
            byte.to_ascii_uppercase(),
            b'O' | b'X' | b'A' | b'B' | b'D' | b'M' | b'N'
        ) {
            class |= OPERATOR_START;
        }
        table[index] = class;
        index += 1;
    }
    table
}

/// True when `byte` is of class `class`.
#[inline(always)]
fn is(byte: u8, class: Class) -> bool {
    CLASSES[usize::from(byte)] & class != 0
}

/// True for the bytes that separate words, but for `\n` and `\r` when `AT_HAND`: then they
/// end the line.
#[inline(always)]
fn is_blank_in<const AT_HAND: bool>(byte: u8) -> bool {
    is(byte, if AT_HAND { BLANK_AT_HAND } else { BLANK })
}

/// `bytes` from its first byte that is not a blank (see [`is_blank_in`]).
#[inline(always)]
fn skip_blanks<const AT_HAND: bool>(bytes: &[u8]) -> &[u8] {
    // One space is what usually stands between two words: stepping over it first spares the
    // common case the loop.
    let bytes = match bytes {
        [b' ', rest @ ..] => rest,
        _ => bytes,
    };
    match bytes {
        [first, ..] if is_blank_in::<AT_HAND>(*first) => skip_blank_run::<AT_HAND>(bytes),
        _ => bytes,
    }
}

/// `bytes` from its first byte that is not a blank, for any run of blanks.
fn skip_blank_run<const AT_HAND: bool>(mut bytes: &[u8]) -> &[u8] {
    while let [first, rest @ ..] = bytes {
        if !is_blank_in::<AT_HAND>(*first) {
            break;
        }
        bytes = rest;
    }
    bytes
}

/// The most digits of a block number read here: 999,999,999 fits in u32 whatever the digits,
/// so they need no checked arithmetic. A longer one (leading zeros, or too large: an alarm) is
/// the general reader's.
const MAX_NUMBER_DIGITS: usize = 9;

/// The digits of a block number after `N`: the number (None when no digit follows: a name) and
/// the bytes after it; None for what the general reader must see: `N` with `=`, more than
/// [`MAX_NUMBER_DIGITS`] digits.
#[inline(always)]
fn block_number(bytes: &[u8]) -> Option<(Option<u32>, &[u8])> {
    // Nearly always eight bytes follow `N` (the text at hand runs on): read them at once.
    if let Some((number, digits)) = bytes.first_chunk::<8>().and_then(|e| leading_digits(*e)) {
        let rest = &bytes[digits..];
        return match rest {
            _ if digits == 0 => Some((None, bytes)),
            [b'=', ..] => None,
            _ => Some((Some(number), rest)),
        };
    }
    let mut number = 0u32;
    let mut rest = bytes;
    while let [digit @ b'0'..=b'9', after @ ..] = rest {
        // Wrapping: a number of more digits than fit is refused below.
        number = number
            .wrapping_mul(10)
            .wrapping_add(u32::from(digit - b'0'));
        rest = after;
    }
    match bytes.len() - rest.len() {
        0 => Some((None, bytes)),
        digits if digits > MAX_NUMBER_DIGITS => None,
        _ if rest.first() == Some(&b'=') => None,
        _ => Some((Some(number), rest)),
    }
}

/// The value of the digits at the start of `bytes` and how many there are, all eight bytes read
/// at once; None when all eight are digits (the number may go on).
#[inline(always)]
fn leading_digits(bytes: [u8; 8]) -> Option<(u32, usize)> {
    const ONES: u64 = 0x0101_0101_0101_0101;
    const HIGHS: u64 = 0x8080_8080_8080_8080;
    // The first byte is the lowest. A digit less `0` is its value; any other byte has its high
    // bit set after subtracting `0` (below `0`: it wraps) or after adding 0x46 (above `9`: it
    // passes 0x7f). Digits neither borrow nor carry, so no byte before the first other one
    // is touched by one.
    let word = u64::from_le_bytes(bytes);
    let values = word.wrapping_sub(u64::from(b'0') * ONES);
    let others = (values | word.wrapping_add(0x46 * ONES)) & HIGHS;
    let digits = (others.trailing_zeros() / 8) as usize;
    if digits == 0 || digits == 8 {
        return (digits == 0).then_some((0, 0));
    }
    // The digits moved to the top bytes, zeros before them: the value of the eight bytes as
    // digits, the lowest byte first. Pairs of bytes make two-digit numbers, pairs of those
    // four-digit ones, then the eight-digit one, each step one multiplication that adds the
    // higher part of each pair, scaled, to the lower.
    let top = values << (64 - 8 * digits);
    let pairs = (top.wrapping_mul(1 + (10 << 8)) >> 8) & 0x00FF_00FF_00FF_00FF;
    let fours = (pairs.wrapping_mul(1 + (100 << 16)) >> 16) & 0x0000_FFFF_0000_FFFF;
    let seven = fours.wrapping_mul(1 + (10_000 << 32)) >> 32;
    // At most seven digits: below 10^7, which fits.
    Some((seven as u32, digits))
}

/// The end of the letters, digits and `_` from `at`.
fn name_end(text: &[u8], mut at: usize) -> usize {
    while text.get(at).is_some_and(|b| is(*b, NAME)) {
        at += 1;
    }
    at
}

/// The first `length` bytes of `bytes`, a name, as one number with zeros after them, when the
/// name has at most eight bytes and eight are at hand. No byte of a name is zero: two names
/// have the same key when they are written the same.
#[inline(always)]
fn short_name_key(bytes: &[u8], length: usize) -> Option<u64> {
    let eight = u64::from_le_bytes(*bytes.first_chunk::<8>()?);
    match length {
        1..=7 => Some(eight & (u64::MAX >> (64 - 8 * length))),
        8 => Some(eight),
        _ => None,
    }
}

/// The names that are operators between two values.
#[inline(always)]
fn is_operator(name: &[u8]) -> bool {
    const OPERATORS: [&[u8]; 10] = [
        b"OR", b"XOR", b"AND", b"B_OR", b"B_XOR", b"B_AND", b"DIV", b"MOD", b"NOT", b"B_NOT",
    ];
    // Most names start with a letter no operator starts with (`FEED1`): one test for those.
    name.first().is_some_and(|first| is(*first, OPERATOR_START))
        && (2..=5).contains(&name.len())
        && OPERATORS.iter().any(|op| name.eq_ignore_ascii_case(op))
}

/// A letter (`letter`, upper case) and a constant written against it (`X-1.5`, `G1`, `Y.5`),
/// `after` the bytes after the letter, not a numeric extension (`R10=`, `X1=`: then the word's
/// end is no plain one and the line is given up); the word kept in `plain`, the bytes after it.
#[inline(always)]
fn letter_constant<'a, const AT_HAND: bool>(
    letter: u8,
    after: &'a [u8],
    start: usize,
    plain: &mut PlainWords,
) -> Option<&'a [u8]> {
    let (negative, unsigned) = match after {
        [b'-', rest @ ..] => (true, rest),
        [b'+', rest @ ..] => (false, rest),
        _ => (false, after),
    };
    let (decimal, rest) = unsigned_decimal::<AT_HAND>(unsigned)?;
    let number = decimal.number(negative);
    // The word's end: the letter's place, the letter, and what was read after it.
    let end = start + 1 + after.len() - rest.len();
    plain.push(PlainKind::Letter(letter, number), start, end)?;
    Some(rest)
}

/// The decimal constant at the start of `bytes` (digits, or a point and digits), as the ISO
/// reader's short path reads it: the decimal and the bytes after it. None for anything else,
/// and for more than 15 digits, which the general reader must read. Read from windows when
/// `AT_HAND` (None as well when `bytes` is shorter than a window). An `EX` exponent after the
/// digits (`1.5EX3`) is the general reader's too, and needs no test here: its `E` is read next
/// as a word's letter followed by a name's byte, and [`named`] gives up any name but `CR` and
/// `F`.
#[inline(always)]
fn unsigned_decimal<const AT_HAND: bool>(bytes: &[u8]) -> Option<(Decimal, &[u8])> {
    if AT_HAND {
        decimal::windowed_decimal(bytes)
    } else {
        decimal::unsigned_decimal(bytes)
    }
}

/// `CR=` or `F=` and a number, a negated number or (after `F=`) a variable's name (`CR=-11.7`,
/// `F=FEED1`); the word kept in `plain`, the bytes after it. Any other name is the general
/// reader's.
fn named<'a, const AT_HAND: bool>(
    text: &'a [u8],
    start: usize,
    plain: &mut PlainWords,
) -> Option<&'a [u8]> {
    // `CR=` or `F=`, not `==` (which compares); a blank before `=`, any other name and the
    // forms with `(` or `[` are the general reader's.
    let (radius, from) = match &text[start..] {
        [b'C' | b'c', b'R' | b'r', b'=', after @ ..] if after.first() != Some(&b'=') => {
            (true, start + 3)
        }
        [b'F' | b'f', b'=', after @ ..] if after.first() != Some(&b'=') => (false, start + 2),
        _ => return None,
    };
    match text.get(from) {
        Some(b'-') => {
            let (decimal, rest) = unsigned_decimal::<AT_HAND>(&text[from + 1..])?;
            let value = decimal.number(false).value;
            let end = text.len() - rest.len();
            let kind = if radius {
                PlainKind::Radius(value, true)
            } else {
                PlainKind::Feed(value, true)
            };
            plain.push(kind, start, end)?;
            Some(rest)
        }
        Some(b) if b.is_ascii_alphabetic() || *b == b'_' => {
            // An R parameter's name ends at its digits (`R1X2`), and NOT and B_NOT are
            // operators: the general reader's; a radius from a variable too.
            let r_parameter =
                b.eq_ignore_ascii_case(&b'R') && text.get(from + 1).is_some_and(u8::is_ascii_digit);
            let end = name_end(text, from + 1);
            let variable = &text[from..end];
            if radius || r_parameter || is_operator(variable) || plain.has_name {
                return None;
            }
            // A call or indices follow the name (`(` after blanks, `[` against it).
            let after = &text[end..];
            if skip_blanks::<AT_HAND>(after).first() == Some(&b'(') || after.first() == Some(&b'[')
            {
                return None;
            }
            // Written as the last line's name, the name is made once for both.
            let key = short_name_key(&text[from..], variable.len()).unwrap_or(0);
            if key == 0 || key != plain.name_key {
                plain.name = Some(Address::upper(variable));
                plain.name_key = key;
            }
            plain.has_name = true;
            plain.push(PlainKind::FeedName, start, end)?;
            Some(after)
        }
        _ => {
            let (decimal, rest) = unsigned_decimal::<AT_HAND>(&text[from..])?;
            let value = decimal.number(false).value;
            let end = text.len() - rest.len();
            let kind = if radius {
                PlainKind::Radius(value, false)
            } else {
                PlainKind::Feed(value, false)
            };
            plain.push(kind, start, end)?;
            Some(rest)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::sinumerik::scan::is_blank;

    #[test]
    fn the_byte_classes_are_the_scanners_and_the_operators() {
        for byte in 0..=u8::MAX {
            assert_eq!(is(byte, BLANK), is_blank(byte), "{byte:#x}");
            let line_end = matches!(byte, b'\n' | b'\r');
            assert_eq!(is(byte, BLANK_AT_HAND), is_blank(byte) && !line_end);
            assert_eq!(
                is(byte, NAME_START),
                byte.is_ascii_alphabetic() || byte == b'_'
            );
            assert_eq!(is(byte, NAME), byte.is_ascii_alphanumeric() || byte == b'_');
        }
        // Every operator starts with a byte of the class, and its second byte is a name's: after
        // a word, it is read as a name, and given up.
        for operator in [
            "OR", "XOR", "AND", "B_OR", "B_XOR", "B_AND", "DIV", "MOD", "NOT", "B_NOT",
        ] {
            for name in [operator.to_string(), operator.to_lowercase()] {
                let bytes = name.as_bytes();
                assert!(
                    is(bytes[0], OPERATOR_START) && is(bytes[1], NAME_START),
                    "{name}"
                );
                assert!(is_operator(bytes), "{name}");
            }
        }
    }

    #[test]
    fn a_feed_name_read_line_after_line_is_each_lines_own() {
        let mut block = Block::default();
        let next = "\nN20 G1 X10.5 Y-2.25 Z0.125 F=FEED2 ; long enough for the numbers' windows";
        for (line, name) in [
            ("N10 G1 X1 F=FEED1", Some("FEED1")),
            ("N10 G1 X1 F=FEED1", Some("FEED1")),
            ("N10 G1 X1 F=feed1", Some("FEED1")),
            ("N10 G1 X1 F=FEED10", Some("FEED10")),
            ("N10 G1 X1", None),
            ("N10 G1 X1 F=FEED1", Some("FEED1")),
            (
                "N10 G1 X1 F=A_FEED_OF_MORE_THAN_8",
                Some("A_FEED_OF_MORE_THAN_8"),
            ),
            (
                "N10 G1 X1 F=A_FEED_OF_MORE_THAN_9",
                Some("A_FEED_OF_MORE_THAN_9"),
            ),
            ("N10 G1 X1 F=FEED_TWO", Some("FEED_TWO")),
            ("N10 G1 X1 F=FEED_TWO", Some("FEED_TWO")),
            ("N10 G1 X1 F=F", Some("F")),
        ] {
            // From the text at hand, where the key is made, and from the line alone.
            let unread = format!("{line}{next}");
            assert!(read_plain_in(unread.as_bytes(), FileId(0), 1, 0, &mut block).is_some());
            let at_hand = block.plain.as_ref().and_then(PlainWords::feed_name);
            assert_eq!(at_hand, name, "{line}");
            assert!(read_plain(line.as_bytes(), FileId(0), 1, 0, &mut block));
            let alone = block.plain.as_ref().and_then(PlainWords::feed_name);
            assert_eq!(alone, name, "{line}");
        }
    }

    proptest::proptest! {
        #[test]
        fn eight_bytes_at_once_give_the_digits_one_by_one_give(
            bytes in proptest::array::uniform8(proptest::prop_oneof![
                proptest::sample::select(b"0123456789/:.-Nn ".to_vec()),
                proptest::num::u8::ANY,
            ]),
        ) {
            let digits = bytes.iter().take_while(|b| b.is_ascii_digit()).count();
            let value = bytes[..digits]
                .iter()
                .fold(0u32, |n, d| n * 10 + u32::from(d - b'0'));
            let expected = (digits < 8).then_some((value, digits));
            proptest::prop_assert_eq!(leading_digits(bytes), expected, "{:?}", bytes);
        }
    }
}
