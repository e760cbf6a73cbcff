//! The tokens of one SINUMERIK line: names, numbers, strings and symbols, each with its span.
//!
//! Blanks, tabs, `&` and other non-printable characters separate tokens (manual 3.2). Numbers
//! are decimal with an optional `EX` exponent (`1.5EX3`), or `'H..'` hexadecimal and `'B..'`
//! binary constants. A name is a letter, `_` or `$` followed by letters, digits and `_`; case is
//! the block parser's and the interpreter's business. The scanner never reads past its line and
//! never panics.

use crate::alarm::{Alarm, AlarmCode};
use crate::source::{FileId, Span};
use std::ops::Range;

/// A token; names and strings as byte ranges of the line.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Token {
    /// A number's value.
    Number(f64),
    /// A string's text, without its quotes.
    Text(Range<usize>),
    /// A name.
    Name(Range<usize>),
    /// An operator or punctuation.
    Symbol(&'static str),
}

/// The symbols, two-character ones first.
const SYMBOLS: [&str; 18] = [
    "==", "<>", "<=", ">=", "<<", "<", ">", "=", "+", "-", "*", "/", "(", ")", "[", "]", ",", ":",
];

/// A cursor over one line.
pub(super) struct Scanner<'a> {
    text: &'a [u8],
    pos: usize,
    file: FileId,
    line: u32,
    /// Byte offset of the line in its file.
    base: u32,
}

impl<'a> Scanner<'a> {
    /// A scanner at the start of `text`, line `line` of `file` at byte `base`.
    pub(super) fn new(text: &'a [u8], file: FileId, line: u32, base: u32) -> Scanner<'a> {
        Scanner {
            text,
            pos: 0,
            file,
            line,
            base,
        }
    }

    /// The line.
    pub(super) fn text(&self) -> &'a [u8] {
        self.text
    }

    /// The position, to come back to.
    pub(super) fn mark(&self) -> usize {
        self.pos
    }

    /// Back to a position [`Scanner::mark`] gave.
    pub(super) fn reset(&mut self, mark: usize) {
        self.pos = mark;
    }

    /// The span of bytes `range` of the line.
    pub(super) fn span(&self, range: Range<usize>) -> Span {
        let at = |i: usize| {
            self.base
                .saturating_add(u32::try_from(i).unwrap_or(u32::MAX))
        };
        Span::new(self.file, self.line, at(range.start)..at(range.end))
    }

    /// The span of the next byte (empty at the end of the line).
    pub(super) fn here(&self) -> Span {
        self.span(self.pos..(self.pos + 1).min(self.text.len()))
    }

    /// The next byte, blanks not skipped.
    pub(super) fn peek_byte(&self) -> Option<u8> {
        self.text.get(self.pos).copied()
    }

    /// Moves over one byte.
    pub(super) fn bump(&mut self) {
        self.pos = (self.pos + 1).min(self.text.len());
    }

    /// Moves over blanks.
    pub(super) fn skip_blanks(&mut self) {
        while self.peek_byte().is_some_and(is_blank) {
            self.pos += 1;
        }
    }

    /// Moves over blanks and an `=` that is not `==`, if one comes, and says so; the position
    /// stays where it was otherwise.
    pub(super) fn take_equals(&mut self) -> bool {
        let mark = self.pos;
        self.skip_blanks();
        let rest = &self.text[self.pos..];
        if rest.starts_with(b"=") && !rest.starts_with(b"==") {
            self.pos += 1;
            return true;
        }
        self.pos = mark;
        false
    }

    /// Moves over a `-` or `+` if one comes; true for `-`.
    pub(super) fn take_sign(&mut self) -> bool {
        match self.peek_byte() {
            Some(b'-') => {
                self.bump();
                true
            }
            Some(b'+') => {
                self.bump();
                false
            }
            _ => false,
        }
    }

    /// True at the end of the line or at its comment.
    pub(super) fn at_end(&mut self) -> bool {
        self.skip_blanks();
        matches!(self.peek_byte(), None | Some(b';'))
    }

    /// Reads a run of digits and the bytes of a name after the first: letters, digits, `_`.
    pub(super) fn name_rest(&mut self) {
        while self
            .peek_byte()
            .is_some_and(|b| b.is_ascii_alphanumeric() || b == b'_')
        {
            self.pos += 1;
        }
    }

    /// Reads a run of letters and `_` (no digits).
    pub(super) fn letters(&mut self) {
        while self
            .peek_byte()
            .is_some_and(|b| b.is_ascii_alphabetic() || b == b'_')
        {
            self.pos += 1;
        }
    }

    /// The next token and its span, blanks skipped; `None` at the end of the line or at a
    /// comment (which is not consumed).
    ///
    /// # Errors
    /// [`AlarmCode::UnexpectedCharacter`] for a byte no token starts with,
    /// [`AlarmCode::BadNumber`] for a malformed constant, [`AlarmCode::MacroSyntax`] for a string
    /// without its closing quote.
    pub(super) fn next_token(&mut self) -> Result<Option<(Token, Span)>, Alarm> {
        if self.at_end() {
            return Ok(None);
        }
        let start = self.pos;
        let Some(byte) = self.peek_byte() else {
            return Ok(None);
        };
        let token = if byte.is_ascii_digit()
            || (byte == b'.' && self.text.get(start + 1).is_some_and(u8::is_ascii_digit))
        {
            Token::Number(self.decimal()?)
        } else if byte == b'\'' {
            Token::Number(self.based()?)
        } else if byte == b'"' {
            self.pos += 1;
            let from = self.pos;
            while self.peek_byte().is_some_and(|b| b != b'"') {
                self.pos += 1;
            }
            if self.peek_byte().is_none() {
                return Err(Alarm::error(
                    AlarmCode::MacroSyntax,
                    self.span(start..self.pos),
                    "the string has no closing `\"`",
                )
                .with_help("a string ends on its own line"));
            }
            let text = from..self.pos;
            self.pos += 1;
            Token::Text(text)
        } else if byte.is_ascii_alphabetic() || byte == b'_' || byte == b'$' {
            self.pos += 1;
            if byte.eq_ignore_ascii_case(&b'R')
                && self.peek_byte().is_some_and(|b| b.is_ascii_digit())
            {
                // An R parameter ends at its digits: `X=R24Y=R25` is R24, then the word Y.
                self.digits();
            } else {
                self.name_rest();
            }
            Token::Name(start..self.pos)
        } else if let Some(symbol) = SYMBOLS
            .iter()
            .find(|s| self.text[start..].starts_with(s.as_bytes()))
        {
            self.pos += symbol.len();
            Token::Symbol(symbol)
        } else {
            return Err(unexpected(self.span(start..start + 1), byte));
        };
        Ok(Some((token, self.span(start..self.pos))))
    }

    /// A decimal number at the position: digits, a point, digits, and `EX` with a signed
    /// exponent.
    ///
    /// # Errors
    /// [`AlarmCode::BadNumber`] for `EX` without digits or a value beyond f64.
    pub(super) fn decimal(&mut self) -> Result<f64, Alarm> {
        let start = self.pos;
        // Digits, a point and digits, read in one pass; the value of a short number is made on
        // the way (see `short_decimal`), a long one is left to the standard parser.
        let text = self.text;
        let mut whole = 0u64;
        let mut at = digits_onto(text, start, &mut whole);
        let (mut decimals, point) = (0, text.get(at) == Some(&b'.'));
        if point {
            at += 1;
            let from = at;
            at = digits_onto(text, at, &mut whole);
            decimals = at - from;
        }
        let digits = at - start - usize::from(point);
        self.pos = at;
        let mantissa = match digits {
            1..=15 => whole as f64 / POWERS_OF_TEN[decimals],
            _ => parse_f64(&self.text[start..self.pos]),
        };
        let ex = self.text[self.pos..].get(..2);
        if ex.is_some_and(|ex| ex.eq_ignore_ascii_case(b"EX")) {
            self.pos += 2;
            let negative = match self.peek_byte() {
                Some(b'-') => {
                    self.pos += 1;
                    true
                }
                Some(b'+') => {
                    self.pos += 1;
                    false
                }
                _ => false,
            };
            let from = self.pos;
            self.digits();
            if from == self.pos || self.pos - from > 3 {
                return Err(bad_number(
                    self.span(start..self.pos),
                    "an exponent (EX) needs one to three digits",
                ));
            }
            let exponent = parse_f64(&self.text[from..self.pos]);
            let exponent = if negative { -exponent } else { exponent };
            return self.finite(mantissa * 10f64.powf(exponent), start);
        }
        self.finite(mantissa, start)
    }

    /// `value`, or the alarm of a number (from `start` to here) beyond f64: the span is made
    /// only then.
    fn finite(&self, value: f64, start: usize) -> Result<f64, Alarm> {
        if value.is_finite() {
            Ok(value)
        } else {
            Err(bad_number(
                self.span(start..self.pos),
                "the number is beyond the control's range",
            ))
        }
    }

    /// `'H1F'` or `'B1011'`.
    fn based(&mut self) -> Result<f64, Alarm> {
        let start = self.pos;
        self.pos += 1;
        let radix = match self.peek_byte().map(|b| b.to_ascii_uppercase()) {
            Some(b'H') => 16,
            Some(b'B') => 2,
            _ => {
                return Err(bad_number(
                    self.span(start..self.pos),
                    "a constant in quotes is 'H..' (hexadecimal) or 'B..' (binary)",
                ))
            }
        };
        self.pos += 1;
        let from = self.pos;
        while self.peek_byte().is_some_and(|b| b.is_ascii_alphanumeric()) {
            self.pos += 1;
        }
        let digits = &self.text[from..self.pos];
        let closed = self.peek_byte() == Some(b'\'');
        if closed {
            self.pos += 1;
        }
        let value = std::str::from_utf8(digits)
            .ok()
            .filter(|_| closed && !digits.is_empty())
            .and_then(|d| u32::from_str_radix(d, radix).ok());
        match value {
            Some(v) => Ok(f64::from(v)),
            None => Err(bad_number(
                self.span(start..self.pos),
                "not a hexadecimal or binary constant that fits 32 bits",
            )),
        }
    }

    fn digits(&mut self) {
        while self.peek_byte().is_some_and(|b| b.is_ascii_digit()) {
            self.pos += 1;
        }
    }
}

/// Reads the digits of `text` from `at` on into `whole` (wrapping: a long number is read again
/// by the standard parser); the position after them.
fn digits_onto(text: &[u8], mut at: usize, whole: &mut u64) -> usize {
    while let Some(digit) = text
        .get(at)
        .map(|b| b.wrapping_sub(b'0'))
        .filter(|d| *d < 10)
    {
        *whole = whole.wrapping_mul(10).wrapping_add(u64::from(digit));
        at += 1;
    }
    at
}

/// Separators: blank, tab, `&`, and characters that do not print (manual 3.2).
pub(super) fn is_blank(byte: u8) -> bool {
    byte == b' ' || byte == b'&' || byte < 0x20 || byte == 0x7f
}

/// The value of a run of digits with at most one point (always valid when it reaches here).
fn parse_f64(text: &[u8]) -> f64 {
    if let Some(value) = short_decimal(text) {
        return value;
    }
    std::str::from_utf8(text)
        .ok()
        .and_then(|t| t.parse::<f64>().ok())
        .unwrap_or(0.0)
}

/// The value of digits with at most one point and at most 15 digits in all, worked out
/// exactly: the digits make a whole number below 2^53 and the point divides it by a power of
/// ten up to 10^15, both exact in an f64, so their quotient is the correctly rounded value, the
/// one `str::parse` gives. None for anything longer (then `str::parse` reads it).
fn short_decimal(text: &[u8]) -> Option<f64> {
    let mut whole: u64 = 0;
    let mut digits = 0usize;
    let mut decimals = None;
    for &b in text {
        match b {
            b'0'..=b'9' => {
                whole = whole * 10 + u64::from(b - b'0');
                digits += 1;
                if let Some(d) = decimals.as_mut() {
                    *d += 1;
                }
            }
            b'.' if decimals.is_none() => decimals = Some(0usize),
            _ => return None,
        }
        if digits > 15 {
            return None;
        }
    }
    if digits == 0 {
        return None;
    }
    Some(whole as f64 / POWERS_OF_TEN[decimals.unwrap_or(0)])
}

/// The powers of ten an f64 holds exactly, up to the most decimals of a short number.
pub(super) const POWERS_OF_TEN: [f64; 16] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
];

fn bad_number(span: Span, message: &str) -> Alarm {
    Alarm::error(AlarmCode::BadNumber, span, message)
}

/// The alarm of a byte that starts no token.
pub(super) fn unexpected(span: Span, byte: u8) -> Alarm {
    let shown = if byte.is_ascii_graphic() {
        format!("`{}`", byte as char)
    } else {
        format!("byte 0x{byte:02x}")
    };
    Alarm::error(
        AlarmCode::UnexpectedCharacter,
        span,
        format!("unexpected {shown} in a SINUMERIK block"),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_decimals_read_as_the_standard_parser_reads_them() {
        // The exact quotient rounds once, as the standard parser does: compare bit for bit over
        // every shape of a short number, and a few that stay with the standard parser.
        let mut texts: Vec<String> = [
            "0",
            "0.",
            ".5",
            "12.345",
            "0.1",
            "0.3",
            "123456789012345",
            "9007199254740993",
            "1.0000000000000001",
            "00000000000000000001.5",
        ]
        .iter()
        .map(|t| t.to_string())
        .collect();
        let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
        for _ in 0..20_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let digits = (x % 15 + 1) as usize;
            let text: String = (0..digits)
                .map(|i| char::from(b'0' + ((x >> (i * 3)) % 10) as u8))
                .collect();
            let point = ((x >> 50) as usize) % (digits + 1);
            texts.push(format!("{}.{}", &text[..point], &text[point..]));
        }
        for text in texts {
            let expected: f64 = text.parse().unwrap();
            assert_eq!(
                parse_f64(text.as_bytes()).to_bits(),
                expected.to_bits(),
                "{text}"
            );
        }
        assert_eq!(short_decimal(b"9007199254740993"), None);
        assert_eq!(short_decimal(b"1.2.3"), None);
        assert_eq!(short_decimal(b"."), None);
    }
}
