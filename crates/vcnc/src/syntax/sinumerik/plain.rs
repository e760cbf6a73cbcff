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
use super::scan::{is_blank, Scanner};
use crate::syntax::Number;

/// Reads `scanner`'s line into `block` (emptied) if it is a plain one; false, and `block`
/// holding some of its words, if it is not.
pub(super) fn read_plain(scanner: &mut Scanner<'_>, block: &mut Block) -> bool {
    skip_blanks(scanner);
    if !block_number(scanner, block) {
        return false;
    }
    loop {
        skip_blanks(scanner);
        let start = scanner.mark();
        let word = match scanner.peek_byte() {
            None | Some(b';') => return true,
            Some(b) if b.is_ascii_alphabetic() => {
                let after = scanner.text().get(start + 1).copied();
                if after.is_some_and(|b| b.is_ascii_alphabetic() || b == b'_') {
                    named(scanner, start)
                } else if after == Some(b'=') {
                    // `F=FEED1`: a letter as a name.
                    named(scanner, start)
                } else {
                    letter_constant(scanner, start)
                }
            }
            Some(_) => return false,
        };
        let Some(word) = word else {
            return false;
        };
        if !ends_word(scanner) {
            return false;
        }
        block.words.push(word);
    }
}

fn skip_blanks(scanner: &mut Scanner<'_>) {
    while scanner.peek_byte().is_some_and(is_blank) {
        scanner.bump();
    }
}

/// `N123` (or none) at the position; false for what the general reader must see: a skip level,
/// a main block `:`, `N` with `=`.
fn block_number(scanner: &mut Scanner<'_>, block: &mut Block) -> bool {
    match scanner.peek_byte() {
        Some(b'N' | b'n') => {}
        Some(b'/' | b':') => return false,
        _ => return true,
    }
    let start = scanner.mark();
    scanner.bump();
    let mut number = 0u32;
    while let Some(digit) = scanner.peek_byte().filter(u8::is_ascii_digit) {
        let Some(n) = number
            .checked_mul(10)
            .and_then(|n| n.checked_add(u32::from(digit - b'0')))
        else {
            return false;
        };
        number = n;
        scanner.bump();
    }
    if scanner.mark() == start + 1 {
        // `N` and a letter: a name (`NOT`, a label), read as a word.
        scanner.reset(start);
        return true;
    }
    if scanner.peek_byte() == Some(b'=') {
        return false;
    }
    block.number = Some(number);
    true
}

/// After a word: blanks, then the end, a comment or the next word's letter, which must not
/// be an operator that would go on with the word's expression (`CR=5 DIV 2`).
fn ends_word(scanner: &mut Scanner<'_>) -> bool {
    let text = scanner.text();
    let mut at = scanner.mark();
    while text.get(at).copied().is_some_and(is_blank) {
        at += 1;
    }
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
            let end = at
                + text[at..]
                    .iter()
                    .take_while(|b| b.is_ascii_alphanumeric() || **b == b'_')
                    .count();
            !is_operator(&text[at..end])
        }
        Some(_) => false,
    }
}

/// The names that are operators between two values.
fn is_operator(name: &[u8]) -> bool {
    const OPERATORS: [&[u8]; 10] = [
        b"OR", b"XOR", b"AND", b"B_OR", b"B_XOR", b"B_AND", b"DIV", b"MOD", b"NOT", b"B_NOT",
    ];
    (2..=5).contains(&name.len()) && OPERATORS.iter().any(|op| name.eq_ignore_ascii_case(op))
}

/// A letter and a constant written against it (`X-1.5`, `G1`, `Y.5`), not a numeric
/// extension (`R10=`, `X1=`: then the word's end is no plain one and the line is given up).
fn letter_constant(scanner: &mut Scanner<'_>, start: usize) -> Option<Word> {
    let letter = scanner.text()[start].to_ascii_uppercase();
    scanner.bump();
    let negative = scanner.take_sign();
    let number_start = scanner.mark();
    let value = number(scanner)?;
    let decimal_point = scanner.text()[number_start..scanner.mark()].contains(&b'.');
    Some(Word {
        address: Address::of_letter(letter),
        value: Value::Constant(Number {
            value: if negative { -value } else { value },
            decimal_point,
            negative,
        }),
        span: scanner.span(start..scanner.mark()),
    })
}

/// A decimal constant at the position (digits, or a point and digits); None for anything else
/// or a constant the general reader would refuse.
fn number(scanner: &mut Scanner<'_>) -> Option<f64> {
    let text = scanner.text();
    let at = scanner.mark();
    let starts = match text.get(at) {
        Some(b) if b.is_ascii_digit() => true,
        Some(b'.') => text.get(at + 1).is_some_and(u8::is_ascii_digit),
        _ => false,
    };
    if !starts {
        return None;
    }
    scanner.decimal().ok()
}

/// A name, `=` and a number, a negated number or a variable's name (`CR=-11.7`, `F=FEED1`).
fn named(scanner: &mut Scanner<'_>, start: usize) -> Option<Word> {
    scanner.name_rest();
    let name_end = scanner.mark();
    let text = scanner.text();
    // `==` compares; a blank before `=` and the forms with `(` or `[` are the general reader's.
    if text.get(name_end) != Some(&b'=') || text.get(name_end + 1) == Some(&b'=') {
        return None;
    }
    let address = Address::upper(&text[start..name_end]);
    scanner.bump();
    let value = value(scanner)?;
    Some(Word {
        address,
        value: Value::Expression(value),
        span: scanner.span(start..scanner.mark()),
    })
}

/// The value after `=`: a number, `-` and a number, or a name without indices or arguments.
fn value(scanner: &mut Scanner<'_>) -> Option<Expr> {
    let start = scanner.mark();
    let text = scanner.text();
    match text.get(start) {
        Some(b'-') => {
            scanner.bump();
            let from = scanner.mark();
            let value = number(scanner)?;
            let operand = Expr {
                kind: ExprKind::Number(value),
                span: scanner.span(from..scanner.mark()),
            };
            Some(Expr {
                kind: ExprKind::Unary(UnaryOp::Minus, Box::new(operand)),
                span: scanner.span(start..scanner.mark()),
            })
        }
        Some(b) if b.is_ascii_alphabetic() || *b == b'_' => {
            // An R parameter's name ends at its digits (`R1X2`), and NOT and B_NOT are
            // operators: the general reader's.
            let r_parameter = b.eq_ignore_ascii_case(&b'R')
                && text.get(start + 1).is_some_and(u8::is_ascii_digit);
            scanner.bump();
            scanner.name_rest();
            let name = &text[start..scanner.mark()];
            if r_parameter || is_operator(name) {
                return None;
            }
            // A call or indices follow the name (`(` after blanks, `[` against it).
            let mut after = scanner.mark();
            while text.get(after).copied().is_some_and(is_blank) {
                after += 1;
            }
            if text.get(after) == Some(&b'(') || text.get(scanner.mark()) == Some(&b'[') {
                return None;
            }
            Some(Expr {
                kind: ExprKind::Name(upper(name)),
                span: scanner.span(start..scanner.mark()),
            })
        }
        _ => {
            let value = number(scanner)?;
            Some(Expr {
                kind: ExprKind::Number(value),
                span: scanner.span(start..scanner.mark()),
            })
        }
    }
}
