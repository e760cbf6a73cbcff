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
//! Never: raise an alarm (a line that would is given up) or read past the line.

use super::block::{Address, Block, Value, Word};
use super::expr::{Expr, ExprKind, UnaryOp};
use super::scan::{is_blank, POWERS_OF_TEN};
use crate::source::{FileId, Span};
use crate::syntax::Number;

/// A plain line's words, decoded.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PlainWords {
    words: [PlainWord; PlainWords::MAX],
    len: u8,
    /// The variable's name of an `F=NAME` word, upper case.
    name: Option<Address>,
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

impl PlainWords {
    /// The most words a plain line holds (a CAM line has up to about six).
    pub const MAX: usize = 8;

    /// The words, in their order.
    pub fn words(&self) -> &[PlainWord] {
        &self.words[..usize::from(self.len)]
    }

    /// The variable's name of the `F=NAME` word, upper case.
    pub fn feed_name(&self) -> Option<&str> {
        self.name.as_deref()
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
                    let name = self.name.as_deref().unwrap_or_default();
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
        *slot = PlainWord {
            kind,
            start: u16::try_from(start).ok()?,
            end: u16::try_from(end).ok()?,
        };
        self.len += 1;
        Some(())
    }
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
    // The line is read by index over its bytes, not through the scanner's general steps: a
    // long CAM program's parsing is mostly this loop.
    let mut at = skip_blanks(text, 0);
    let Some(after_number) = block_number(text, at, block) else {
        return false;
    };
    at = after_number;
    let plain = block.plain.get_or_insert_with(PlainWords::default);
    plain.len = 0;
    plain.name = None;
    plain.file = file;
    plain.line = line;
    plain.base = base;
    loop {
        at = skip_blanks(text, at);
        let start = at;
        let end = match text.get(at) {
            None | Some(b';') => {
                // A line without words (a comment, a number alone) is no block to run.
                if plain.len == 0 {
                    block.plain = None;
                }
                return true;
            }
            Some(b) if b.is_ascii_alphabetic() => {
                let after = text.get(start + 1).copied();
                if after.is_some_and(|b| b.is_ascii_alphabetic() || b == b'_' || b == b'=') {
                    // `CR=..`, or `F=FEED1`: a letter as a name.
                    named(text, start, plain)
                } else {
                    letter_constant(text, start, plain)
                }
            }
            Some(_) => return false,
        };
        let Some(end) = end else {
            return false;
        };
        if !ends_word(text, end) {
            return false;
        }
        at = end;
    }
}

/// The position after the blanks from `at`.
fn skip_blanks(text: &[u8], mut at: usize) -> usize {
    while text.get(at).copied().is_some_and(is_blank) {
        at += 1;
    }
    at
}

/// `N123` (or none) at `at`: the position after it; None for what the general reader must
/// see: a skip level, a main block `:`, `N` with `=`, a number too large.
fn block_number(text: &[u8], at: usize, block: &mut Block) -> Option<usize> {
    match text.get(at) {
        Some(b'N' | b'n') => {}
        Some(b'/' | b':') => return None,
        _ => return Some(at),
    }
    let mut end = at + 1;
    let mut number = 0u32;
    while let Some(digit) = digit(text, end) {
        number = number.checked_mul(10)?.checked_add(u32::from(digit))?;
        end += 1;
    }
    if end == at + 1 {
        // `N` and a letter: a name (`NOT`, a label), read as a word.
        return Some(at);
    }
    if text.get(end) == Some(&b'=') {
        return None;
    }
    block.number = Some(number);
    Some(end)
}

/// The digit at `at`, if there is one.
fn digit(text: &[u8], at: usize) -> Option<u8> {
    text.get(at)
        .map(|b| b.wrapping_sub(b'0'))
        .filter(|d| *d < 10)
}

/// After a word ending at `at`: blanks, then the end, a comment or the next word's letter,
/// which must not be an operator that would go on with the word's expression (`CR=5 DIV 2`).
fn ends_word(text: &[u8], at: usize) -> bool {
    let at = skip_blanks(text, at);
    match text.get(at) {
        None | Some(b';') => true,
        Some(b) if b.is_ascii_alphabetic() => {
            // Most next words are axes and feeds: no operator starts with their letter.
            if !matches!(
                b.to_ascii_uppercase(),
                b'O' | b'X' | b'A' | b'B' | b'D' | b'M' | b'N'
            ) {
                return true;
            }
            let end = name_end(text, at);
            !is_operator(&text[at..end])
        }
        Some(_) => false,
    }
}

/// The end of the letters, digits and `_` from `at`.
fn name_end(text: &[u8], mut at: usize) -> usize {
    while text
        .get(at)
        .is_some_and(|b| b.is_ascii_alphanumeric() || *b == b'_')
    {
        at += 1;
    }
    at
}

/// The names that are operators between two values.
fn is_operator(name: &[u8]) -> bool {
    const OPERATORS: [&[u8]; 10] = [
        b"OR", b"XOR", b"AND", b"B_OR", b"B_XOR", b"B_AND", b"DIV", b"MOD", b"NOT", b"B_NOT",
    ];
    (2..=5).contains(&name.len()) && OPERATORS.iter().any(|op| name.eq_ignore_ascii_case(op))
}

/// A letter and a constant written against it (`X-1.5`, `G1`, `Y.5`), not a numeric
/// extension (`R10=`, `X1=`: then the word's end is no plain one and the line is given up);
/// the word kept in `plain`, the position after it.
fn letter_constant(text: &[u8], start: usize, plain: &mut PlainWords) -> Option<usize> {
    let letter = text[start].to_ascii_uppercase();
    let mut at = start + 1;
    let negative = match text.get(at) {
        Some(b'-') => {
            at += 1;
            true
        }
        Some(b'+') => {
            at += 1;
            false
        }
        _ => false,
    };
    let (value, decimal_point, end) = number(text, at)?;
    let number = Number {
        value: if negative { -value } else { value },
        decimal_point,
        negative,
    };
    plain.push(PlainKind::Letter(letter, number), start, end)?;
    Some(end)
}

/// The decimal constant at `at` (digits, or a point and digits): its value, whether it has a
/// point, and the position after it. None for anything else, and for what the general reader
/// must read: an `EX` exponent, more than 15 digits (the value made here is then not the
/// correctly rounded one), a second point.
fn number(text: &[u8], at: usize) -> Option<(f64, bool, usize)> {
    let mut whole = 0u64;
    let mut end = at;
    while let Some(d) = digit(text, end) {
        whole = whole.wrapping_mul(10).wrapping_add(u64::from(d));
        end += 1;
    }
    let point = text.get(end) == Some(&b'.');
    let mut decimals = 0;
    if point {
        end += 1;
        let from = end;
        while let Some(d) = digit(text, end) {
            whole = whole.wrapping_mul(10).wrapping_add(u64::from(d));
            end += 1;
        }
        decimals = end - from;
    }
    let digits = end - at - usize::from(point);
    if !(1..=15).contains(&digits) {
        return None;
    }
    if text
        .get(end..end + 2)
        .is_some_and(|ex| ex.eq_ignore_ascii_case(b"EX"))
    {
        return None;
    }
    // Both exact in f64 (below 2^53 and a power of ten up to 1e15): the quotient is the
    // correctly rounded value, as the standard parser's.
    Some((whole as f64 / POWERS_OF_TEN[decimals], point, end))
}

/// `CR=` or `F=` and a number, a negated number or (after `F=`) a variable's name (`CR=-11.7`,
/// `F=FEED1`); the word kept in `plain`, the position after it. Any other name is the general
/// reader's.
fn named(text: &[u8], start: usize, plain: &mut PlainWords) -> Option<usize> {
    let equals = name_end(text, start + 1);
    // `==` compares; a blank before `=` and the forms with `(` or `[` are the general reader's.
    if text.get(equals) != Some(&b'=') || text.get(equals + 1) == Some(&b'=') {
        return None;
    }
    let name = &text[start..equals];
    let radius = name.eq_ignore_ascii_case(b"CR");
    if !radius && !name.eq_ignore_ascii_case(b"F") {
        return None;
    }
    let from = equals + 1;
    match text.get(from) {
        Some(b'-') => {
            let (value, _, end) = number(text, from + 1)?;
            let kind = if radius {
                PlainKind::Radius(value, true)
            } else {
                PlainKind::Feed(value, true)
            };
            plain.push(kind, start, end)?;
            Some(end)
        }
        Some(b) if b.is_ascii_alphabetic() || *b == b'_' => {
            // An R parameter's name ends at its digits (`R1X2`), and NOT and B_NOT are
            // operators: the general reader's; a radius from a variable too.
            let r_parameter =
                b.eq_ignore_ascii_case(&b'R') && text.get(from + 1).is_some_and(u8::is_ascii_digit);
            let end = name_end(text, from + 1);
            let variable = &text[from..end];
            if radius || r_parameter || is_operator(variable) || plain.name.is_some() {
                return None;
            }
            // A call or indices follow the name (`(` after blanks, `[` against it).
            if text.get(skip_blanks(text, end)) == Some(&b'(') || text.get(end) == Some(&b'[') {
                return None;
            }
            plain.name = Some(Address::upper(variable));
            plain.push(PlainKind::FeedName, start, end)?;
            Some(end)
        }
        _ => {
            let (value, _, end) = number(text, from)?;
            let kind = if radius {
                PlainKind::Radius(value, false)
            } else {
                PlainKind::Feed(value, false)
            };
            plain.push(kind, start, end)?;
            Some(end)
        }
    }
}
