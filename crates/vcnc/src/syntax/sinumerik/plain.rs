//! The common SINUMERIK line read by a short path: what a CAM post writes block after block,
//! `N170 G1 X54.808 Y30.491 Z-1.288 F=FEED1` or `N160 G2 X51.4 Y26.2 CR=-11.7 F=FEED2`.
//!
//! A block number, then words that are a letter and a constant (`X-1.5`, `G1`) or a name, `=`
//! and a number or a variable's name (`CR=-11.7`, `F=FEED1`), then the end or a `;` comment.
//! Anything else (a blank inside a word, a skip level, a label, a keyword, an operator, a call,
//! an index, a string) gives the line up, and `block.rs` reads it the general way. What this
//! path reads is to the bit what the general one reads (a differential test in `block.rs`).
//!
//! Never: raise an alarm (a line that would is given up) or read past the line.

use super::block::{Address, Block, Value, Word};
use super::expr::{upper, Expr, ExprKind, UnaryOp};
use super::scan::{is_blank, Scanner, POWERS_OF_TEN};
use crate::syntax::Number;

/// Reads `scanner`'s line into `block` (emptied) if it is a plain one; false, and `block`
/// holding some of its words, if it is not.
pub(super) fn read_plain(scanner: &mut Scanner<'_>, block: &mut Block) -> bool {
    // The line is read by index over its bytes, not through the scanner's general steps: a
    // long CAM program's parsing is mostly this loop.
    let text = scanner.text();
    let mut at = skip_blanks(text, 0);
    let Some(after_number) = block_number(text, at, block) else {
        return false;
    };
    at = after_number;
    loop {
        at = skip_blanks(text, at);
        let start = at;
        // Each word is made in its place in the block: a word is large, and moved through an
        // Option it was copied twice.
        let end = match text.get(at) {
            None | Some(b';') => return true,
            Some(b) if b.is_ascii_alphabetic() => {
                let after = text.get(start + 1).copied();
                if after.is_some_and(|b| b.is_ascii_alphabetic() || b == b'_' || b == b'=') {
                    // `CR=..`, or `F=FEED1`: a letter as a name.
                    named(scanner, text, start, &mut block.words)
                } else {
                    letter_constant(scanner, text, start, &mut block.words)
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
/// the word pushed onto `words`, the position after it.
fn letter_constant(
    scanner: &Scanner<'_>,
    text: &[u8],
    start: usize,
    words: &mut Vec<Word>,
) -> Option<usize> {
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
    words.push(Word {
        address: Address::of_letter(letter),
        value: Value::Constant(Number {
            value: if negative { -value } else { value },
            decimal_point,
            negative,
        }),
        span: scanner.span(start..end),
    });
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

/// A name, `=` and a number, a negated number or a variable's name (`CR=-11.7`, `F=FEED1`);
/// the word pushed onto `words`, the position after it.
fn named(scanner: &Scanner<'_>, text: &[u8], start: usize, words: &mut Vec<Word>) -> Option<usize> {
    let name_end = name_end(text, start + 1);
    // `==` compares; a blank before `=` and the forms with `(` or `[` are the general reader's.
    if text.get(name_end) != Some(&b'=') || text.get(name_end + 1) == Some(&b'=') {
        return None;
    }
    let address = Address::upper(&text[start..name_end]);
    let (value, end) = value(scanner, text, name_end + 1)?;
    words.push(Word {
        address,
        value: Value::Expression(value),
        span: scanner.span(start..end),
    });
    Some(end)
}

/// The value after `=` at `start`: a number, `-` and a number, or a name without indices or
/// arguments; the expression and the position after it.
fn value(scanner: &Scanner<'_>, text: &[u8], start: usize) -> Option<(Expr, usize)> {
    match text.get(start) {
        Some(b'-') => {
            let from = start + 1;
            let (value, _, end) = number(text, from)?;
            let operand = Expr {
                kind: ExprKind::Number(value),
                span: scanner.span(from..end),
            };
            let negated = Expr {
                kind: ExprKind::Unary(UnaryOp::Minus, Box::new(operand)),
                span: scanner.span(start..end),
            };
            Some((negated, end))
        }
        Some(b) if b.is_ascii_alphabetic() || *b == b'_' => {
            // An R parameter's name ends at its digits (`R1X2`), and NOT and B_NOT are
            // operators: the general reader's.
            let r_parameter = b.eq_ignore_ascii_case(&b'R')
                && text.get(start + 1).is_some_and(u8::is_ascii_digit);
            let end = name_end(text, start + 1);
            let name = &text[start..end];
            if r_parameter || is_operator(name) {
                return None;
            }
            // A call or indices follow the name (`(` after blanks, `[` against it).
            if text.get(skip_blanks(text, end)) == Some(&b'(') || text.get(end) == Some(&b'[') {
                return None;
            }
            let name = Expr {
                kind: ExprKind::Name(upper(name)),
                span: scanner.span(start..end),
            };
            Some((name, end))
        }
        _ => {
            let (value, _, end) = number(text, start)?;
            let number = Expr {
                kind: ExprKind::Number(value),
                span: scanner.span(start..end),
            };
            Some((number, end))
        }
    }
}
