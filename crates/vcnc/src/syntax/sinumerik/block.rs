//! One SINUMERIK block: skip level, block number, label, and its words (manual 2.2).
//!
//! A word is a DIN 66025 address with a constant (`X10`, `G1`, `F 100`, `N140G0` is two), an
//! address or name with `=` and an expression (`X=10*R1`, `CR=5`, `X1=10`, `T="PF60"`), a name
//! with indices and `=` (`$P_UIFR[1]=...`), a call (`CYCLE82(2,,1)`, `MSG("...")`), or a name alone
//! (`TRANS`, `MCALL`, `RET`). After a single address letter, digits followed by `=`, `(` or `[`
//! are a numeric extension (`X1=10` is axis X1, `X110` is X at 110: manual L604-606). A control
//! structure or declaration (IF, WHILE, DEF ...) first in the block, or a jump or synchronized
//! action after its words, is read by `control.rs` into `Block::statement`. Parsing never
//! fails as a whole: a block that cannot be read carries its alarm.

use super::control::{self, Place};
use super::expr::{self, Expr};
use super::plain::{self, AtHand, PlainWords};
use super::scan::{unexpected, Scanner};
use super::statement::{Name, Spanned, Statement};
use crate::alarm::{Alarm, AlarmCode};
use crate::source::{FileId, Span};
use crate::syntax::Number;

/// A parsed block.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Block {
    /// The skip level of a `/` or `/n` in front (`/` is level 0).
    pub skip: Option<u8>,
    /// The block number of `N..` or `:..` (a main block).
    pub number: Option<u32>,
    /// A jump label ending in `:` at the start of the block.
    pub label: Option<Box<str>>,
    /// The block's words, in order; empty when the line is kept decoded in `plain`.
    pub words: Vec<Word>,
    /// A plain line's words, decoded ([`parse_line_into`]); its words are then not in `words`.
    pub plain: Option<PlainWords>,
    /// The block's statement: a control structure or declaration (IF, WHILE, DEF ...) after the
    /// number and label, or a jump or synchronized action after the words.
    pub statement: Option<Statement>,
    /// Why the block could not be read, if it could not.
    pub alarm: Option<Alarm>,
}

/// An address or name and its value.
#[derive(Clone, Debug, PartialEq)]
pub struct Word {
    /// The address or name, upper case, with its numeric extension (`X`, `X1`, `CR`, `R10`).
    pub address: Address,
    /// What it is given.
    pub value: Value,
    /// Where the word was written.
    pub span: Span,
}

/// A word's address or name, upper case, read as a `str`. An address letter is a static
/// string, and a name up to [`Address::INLINE`] bytes is held in the word itself: reading a
/// word allocates nothing for its address (a CAM program's blocks are mostly such words).
#[derive(Clone, PartialEq, Eq)]
pub struct Address(Repr);

#[derive(Clone, PartialEq, Eq)]
enum Repr {
    /// A single letter.
    Letter(&'static str),
    /// The length and the bytes, zero after the length (so that equal names compare equal).
    Inline(u8, [u8; Address::INLINE]),
    Heap(Box<str>),
}

impl Address {
    /// The longest name held in the word itself.
    pub const INLINE: usize = 22;

    /// The address `name` as it is.
    pub fn new(name: &str) -> Address {
        if let Some(letter) = letter(name.as_bytes()) {
            return letter;
        }
        match name.len() {
            len @ 0..=Address::INLINE => {
                let mut bytes = [0; Address::INLINE];
                bytes[..len].copy_from_slice(name.as_bytes());
                Address(Repr::Inline(len as u8, bytes))
            }
            _ => Address(Repr::Heap(name.into())),
        }
    }

    /// The address of the upper-case letter `letter` (any other byte as a name).
    pub(super) fn of_letter(letter: u8) -> Address {
        self::letter(&[letter]).unwrap_or_else(|| Address::upper(&[letter]))
    }

    /// The name written `bytes`, upper case (bytes that are not UTF-8 as U+FFFD).
    pub(super) fn upper(bytes: &[u8]) -> Address {
        if let [b] = bytes {
            if let Some(letter) = letter(&[b.to_ascii_uppercase()]) {
                return letter;
            }
        }
        if bytes.len() <= Address::INLINE && bytes.is_ascii() {
            let mut inline = [0; Address::INLINE];
            inline[..bytes.len()].copy_from_slice(bytes);
            inline.make_ascii_uppercase();
            return Address(Repr::Inline(bytes.len() as u8, inline));
        }
        Address(Repr::Heap(expr::upper(bytes)))
    }

    /// The letter of a single-letter address (`X`, `G`), upper case; None for a name.
    pub fn letter(&self) -> Option<u8> {
        match &self.0 {
            Repr::Letter(letter) => letter.as_bytes().first().copied(),
            _ => None,
        }
    }

    /// The address as text.
    pub fn as_str(&self) -> &str {
        match &self.0 {
            Repr::Letter(letter) => letter,
            Repr::Inline(len, bytes) => std::str::from_utf8(&bytes[..*len as usize])
                .expect("only ASCII or whole names are held inline"),
            Repr::Heap(name) => name,
        }
    }
}

/// The address of the upper-case letter `name`, if it is one.
fn letter(name: &[u8]) -> Option<Address> {
    const LETTERS: [&str; 26] = [
        "A", "B", "C", "D", "E", "F", "G", "H", "I", "J", "K", "L", "M", "N", "O", "P", "Q", "R",
        "S", "T", "U", "V", "W", "X", "Y", "Z",
    ];
    match name {
        [b @ b'A'..=b'Z'] => Some(Address(Repr::Letter(LETTERS[usize::from(b - b'A')]))),
        _ => None,
    }
}

impl std::ops::Deref for Address {
    type Target = str;

    fn deref(&self) -> &str {
        self.as_str()
    }
}

impl AsRef<str> for Address {
    fn as_ref(&self) -> &str {
        self.as_str()
    }
}

impl std::borrow::Borrow<str> for Address {
    fn borrow(&self) -> &str {
        self.as_str()
    }
}

impl From<&str> for Address {
    fn from(name: &str) -> Address {
        Address::new(name)
    }
}

impl PartialEq<str> for Address {
    fn eq(&self, other: &str) -> bool {
        self.as_str() == other
    }
}

impl PartialEq<&str> for Address {
    fn eq(&self, other: &&str) -> bool {
        self.as_str() == *other
    }
}

impl std::fmt::Display for Address {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl std::fmt::Debug for Address {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        std::fmt::Debug::fmt(self.as_str(), f)
    }
}

/// The value of a word.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// A constant after an address letter, as written (`X-12.5`, `G1`).
    Constant(Number),
    /// An expression after `=`; `AC(..)` and `IC(..)` stay calls at its top.
    Expression(Expr),
    /// `NAME[i, j]=value`, or `NAME[i]` alone (`SCC[X]`).
    Indexed(Vec<Expr>, Option<Expr>),
    /// `NAME(arguments)`: a subprogram, cycle or procedure call.
    Call(Vec<Option<Expr>>),
    /// A name alone: a keyword (`TRANS`, `MCALL`) or a subprogram called by its name.
    Bare,
}

/// Reads the block on `text`, line `line` of `file` at byte `base`.
pub fn parse_block(text: &[u8], file: FileId, line: u32, base: u32) -> Block {
    let mut block = Block {
        // A CAM block has a few words: one allocation, never grown.
        words: Vec::with_capacity(4),
        ..Block::default()
    };
    parse_block_into(text, file, line, base, &mut block);
    block
}

/// Reads the block on `text` (as [`parse_block`]) into `block`, whatever it held: its words'
/// room is kept, so that a block read into line after line does not allocate for them.
pub fn parse_block_into(text: &[u8], file: FileId, line: u32, base: u32, block: &mut Block) {
    parse_line_into(text, file, line, base, block);
    if let Some(plain) = block.plain.take() {
        plain.to_words(&mut block.words);
    }
}

/// Reads the block on `text` into `block` as [`parse_block_into`] does, but keeps a plain line
/// decoded in `block.plain` (its `words` then empty): what a program's lines are read with, for
/// the interpreter to run the common ones without making their words.
pub fn parse_line_into(text: &[u8], file: FileId, line: u32, base: u32, block: &mut Block) {
    clear(block);
    // Most lines of a long program are plain ones (plain.rs); any other is read the general
    // way from its start.
    if plain::read_plain(text, file, line, base, block) {
        return;
    }
    block.plain = None;
    block.number = None;
    read_general(text, file, line, base, block);
}

/// Reads the first line of `unread`, the text at hand from the start of line `line` of `file`
/// (at byte `base`) on, into `block` as [`parse_line_into`] reads a plain line, if it is one
/// (plain.rs [`plain::read_plain_in`]): where the line ends. None, and `block` to be read
/// into again, for any other line.
#[inline(always)]
pub(super) fn parse_plain_line_in(
    unread: &[u8],
    file: FileId,
    line: u32,
    base: u32,
    block: &mut Block,
) -> Option<AtHand> {
    clear(block);
    plain::read_plain_in(unread, file, line, base, block)
}

/// Empties `block` but for its plain words, which the reader of a plain line overwrites, and
/// its words' room.
#[inline(always)]
fn clear(block: &mut Block) {
    block.skip = None;
    block.number = None;
    block.label = None;
    block.words.clear();
    block.statement = None;
    block.alarm = None;
}

/// Reads the block on `text` into the empty `block` the general way.
fn read_general(text: &[u8], file: FileId, line: u32, base: u32, block: &mut Block) {
    let mut scanner = Scanner::new(text, file, line, base);
    if let Err(alarm) = read(&mut scanner, block) {
        block.alarm = Some(alarm);
    }
}

fn read(scanner: &mut Scanner<'_>, block: &mut Block) -> Result<(), Alarm> {
    scanner.skip_blanks();
    if scanner.peek_byte() == Some(b'/') {
        scanner.bump();
        let level = scanner.peek_byte().filter(u8::is_ascii_digit);
        if let Some(digit) = level {
            scanner.bump();
            block.skip = Some(digit - b'0');
        } else {
            block.skip = Some(0);
        }
    }
    block_number(scanner, block)?;
    if let Some(span) = label(scanner, block) {
        if block.label.as_deref() == Some("ENDLABEL") {
            // `ENDLABEL:` is a label and the end marker of REPEAT: a statement of its own.
            let keyword = Spanned {
                value: "ENDLABEL".into(),
                span,
            };
            block.statement = Some(control::read(scanner, keyword)?);
            return Ok(());
        }
    }
    while !scanner.at_end() {
        let start = scanner.mark();
        match scanner.peek_byte() {
            Some(b) if b.is_ascii_alphabetic() || b == b'_' || b == b'$' => {}
            Some(b) => return Err(unexpected(scanner.here(), b)),
            None => break,
        }
        // A single letter (`X12`, `G1`, `F=..`) is no keyword: keywords have two letters or more.
        let single = !scanner
            .text()
            .get(start + 1)
            .is_some_and(|b| b.is_ascii_alphabetic() || *b == b'_');
        if !single {
            if let Some(keyword) = statement_keyword(scanner, block.words.is_empty())? {
                let statement = control::read(scanner, keyword)?;
                block.statement = Some(statement);
                return Ok(());
            }
            scanner.reset(start);
        }
        let word = word(scanner)?;
        if scanner.mark() == start {
            // Nothing read: a guard, so that no line can loop here.
            return Err(unexpected(
                scanner.here(),
                scanner.peek_byte().unwrap_or(b' '),
            ));
        }
        block.words.push(word);
    }
    Ok(())
}

/// `N123` or `:123` at the start of the block.
fn block_number(scanner: &mut Scanner<'_>, block: &mut Block) -> Result<(), Alarm> {
    scanner.skip_blanks();
    let start = scanner.mark();
    let main = scanner.peek_byte() == Some(b':');
    let is_n = scanner
        .peek_byte()
        .is_some_and(|b| b.eq_ignore_ascii_case(&b'N'));
    if !(main || is_n) {
        return Ok(());
    }
    scanner.bump();
    let from = scanner.mark();
    while scanner.peek_byte().is_some_and(|b| b.is_ascii_digit()) {
        scanner.bump();
    }
    let digits = &scanner.text()[from..scanner.mark()];
    // `N` followed by a letter is a name (`NOT`, a label `NEXT:`), not a block number.
    if digits.is_empty() || scanner.peek_byte() == Some(b'=') {
        scanner.reset(start);
        return Ok(());
    }
    // Every block has its number: worked out here, without a string in between.
    let number = digits
        .iter()
        .try_fold(0u32, |n, &d| {
            n.checked_mul(10)?.checked_add(u32::from(d - b'0'))
        })
        .ok_or_else(|| {
            Alarm::error(
                AlarmCode::BadNumber,
                scanner.span(start..scanner.mark()),
                "the block number is too large",
            )
        })?;
    block.number = Some(number);
    Ok(())
}

/// `NAME:` at the start of the block (not `NAME:=`, and not a block number); the span of the
/// name, if there is one.
fn label(scanner: &mut Scanner<'_>, block: &mut Block) -> Option<Span> {
    scanner.skip_blanks();
    let start = scanner.mark();
    if !scanner
        .peek_byte()
        .is_some_and(|b| b.is_ascii_alphabetic() || b == b'_')
    {
        return None;
    }
    scanner.name_rest();
    let end = scanner.mark();
    if scanner.peek_byte() == Some(b':') {
        scanner.bump();
        block.label = Some(expr::upper(&scanner.text()[start..end]));
        Some(scanner.span(start..end))
    } else {
        scanner.reset(start);
        None
    }
}

/// The keyword of a statement at the position, consumed, if the rest of the block is one
/// (`first`: no word before it); an alarm for a keyword that must come first but does not.
fn statement_keyword(scanner: &mut Scanner<'_>, first: bool) -> Result<Option<Name>, Alarm> {
    let start = scanner.mark();
    scanner.name_rest();
    // `DEF` and `IF` are keywords only as written; `DEFX=1` is not a declaration.
    if matches!(scanner.peek_byte(), Some(b'=' | b'[')) {
        return Ok(None);
    }
    let written = &scanner.text()[start..scanner.mark()];
    // Most words are no keyword (an address letter and its digits, `CR`): their name is not
    // made (nor allocated) for the look-up. Keywords are two to eight letters.
    let could_be = (2..=8).contains(&written.len()) && written.iter().all(u8::is_ascii_alphabetic);
    if !could_be || control::place_of(written).is_none() {
        return Ok(None);
    }
    let name = expr::upper(written);
    let span = scanner.span(start..scanner.mark());
    match control::place(&name) {
        Some(Place::AfterWords) => {}
        Some(Place::First) if first => {}
        Some(Place::First) => {
            return Err(Alarm::error(
                AlarmCode::MacroSyntax,
                span,
                format!("{name} must begin its block"),
            )
            .with_help("put the words before it in a block of their own"))
        }
        None => return Ok(None),
    }
    Ok(Some(Spanned { value: name, span }))
}

/// One word at the position (a letter, `_` or `$` there).
fn word(scanner: &mut Scanner<'_>) -> Result<Word, Alarm> {
    let start = scanner.mark();
    if scanner.peek_byte() == Some(b'$') {
        scanner.bump();
    }
    scanner.letters();
    let letters_end = scanner.mark();
    let single_letter = letters_end - start == 1 && scanner.text()[start].is_ascii_alphabetic();
    if single_letter {
        if let Some(word) = din_word(scanner, start)? {
            return Ok(word);
        }
        scanner.reset(letters_end);
    }
    scanner.name_rest();
    let name_end = scanner.mark();
    let address = Address::upper(&scanner.text()[start..name_end]);
    named_word(scanner, address, start)
}

/// A single address letter with a constant (`X10`, `G1`, `X-5`, `F 100`), or `None` when the
/// digits after the letter are a numeric extension (`X1=`, `R10=`) or no number follows.
fn din_word(scanner: &mut Scanner<'_>, start: usize) -> Result<Option<Word>, Alarm> {
    let letter = scanner.text()[start].to_ascii_uppercase();
    let after_letter = scanner.mark();
    scanner.skip_blanks();
    let negative = scanner.take_sign();
    let number_start = scanner.mark();
    let starts_number = match scanner.peek_byte() {
        Some(b) if b.is_ascii_digit() => true,
        Some(b'.') => scanner
            .text()
            .get(number_start + 1)
            .is_some_and(u8::is_ascii_digit),
        _ => false,
    };
    if !starts_number {
        scanner.reset(after_letter);
        return Ok(None);
    }
    let value = scanner.decimal()?;
    let written = &scanner.text()[number_start..scanner.mark()];
    let decimal_point = written.contains(&b'.');
    let number_end = scanner.mark();
    // `R107 = 1`, `S1 = 60`: real programs and the manual put blanks before the `=`.
    let assigns = scanner.take_equals();
    scanner.reset(number_end);
    let extension = !negative
        && !decimal_point
        && number_start == after_letter
        && (assigns || matches!(scanner.peek_byte(), Some(b'(' | b'[')));
    if extension {
        return Ok(None);
    }
    let span = scanner.span(start..scanner.mark());
    Ok(Some(Word {
        address: Address::upper(&[letter]),
        value: Value::Constant(Number {
            value: if negative { -value } else { value },
            decimal_point,
            negative,
        }),
        span,
    }))
}

/// A name with what follows it: `=` and an expression, indices and `=`, arguments, or nothing.
fn named_word(scanner: &mut Scanner<'_>, address: Address, start: usize) -> Result<Word, Alarm> {
    // `MSG ("text")`, `SETMS (2)`: a blank may stand before the arguments.
    let name_end = scanner.mark();
    scanner.skip_blanks();
    if scanner.peek_byte() != Some(b'(') {
        scanner.reset(name_end);
    }
    let value = match scanner.peek_byte() {
        Some(b'(') => {
            scanner.bump();
            let (arguments, _) = expr::arguments(scanner, 0)?;
            Value::Call(arguments)
        }
        Some(b'[') => {
            scanner.bump();
            let (indices, _) = expr::indices(scanner, 0)?;
            // `SCC[X]`, `DIAMONA[Y]`: a keyword with an axis, no value.
            let value = match scanner.take_equals() {
                true => Some(expr::parse(scanner)?),
                false => None,
            };
            Value::Indexed(indices, value)
        }
        _ => {
            let mark = scanner.mark();
            if scanner.take_equals() {
                Value::Expression(expr::parse(scanner)?)
            } else if address.len() > 1 && lenient_constant(scanner, mark) {
                // `FZ0.03`: a multi-letter address with a constant and no `=`, as the manual's
                // own examples write it (spec part A 2.2.3 note).
                return lenient_word(scanner, &address, start);
            } else {
                scanner.reset(mark);
                Value::Bare
            }
        }
    };
    Ok(Word {
        address,
        value,
        span: scanner.span(start..scanner.mark()),
    })
}

/// True when a multi-letter name ends in digits that a decimal point continues (`FZ0.03`).
fn lenient_constant(scanner: &mut Scanner<'_>, mark: usize) -> bool {
    scanner.reset(mark);
    let text = scanner.text();
    let digits = text[..mark]
        .iter()
        .rev()
        .take_while(|b| b.is_ascii_digit())
        .count();
    digits > 0 && text.get(mark) == Some(&b'.')
}

/// The word of [`lenient_constant`]: the letters as the address, the digits and decimals as
/// its constant.
fn lenient_word(scanner: &mut Scanner<'_>, address: &str, start: usize) -> Result<Word, Alarm> {
    let letters = address.trim_end_matches(|c: char| c.is_ascii_digit()).len();
    scanner.reset(start + letters);
    let value = scanner.decimal()?;
    Ok(Word {
        address: address[..letters].into(),
        value: Value::Constant(Number {
            value,
            decimal_point: true,
            negative: false,
        }),
        span: scanner.span(start..scanner.mark()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `text` read by the short path where it takes the line, and the general way.
    fn both_ways(text: &[u8]) -> (Block, Block) {
        let mut general = Block::default();
        read_general(text, FileId(3), 7, 100, &mut general);
        // Read into a block that held another line, as the front end reads.
        let mut fast = Block::default();
        parse_line_into(b"N1 G0 X1 CR=2 F=A", FileId(3), 7, 100, &mut fast);
        parse_block_into(text, FileId(3), 7, 100, &mut fast);
        (general, fast)
    }

    /// `text` read from the text at hand, ended by `line_end` and followed by another line, as
    /// the parser thread reads it: the block and the line's length; None when the line is left
    /// to the line reader.
    fn at_hand(text: &[u8], line_end: &[u8]) -> Option<(Block, usize)> {
        let next = b"N20 G1 X10.5 Y-2.25 Z0.125 F=FEED2 ; long enough for the numbers' windows";
        let unread = [text, line_end, next].concat();
        let mut block = Block::default();
        parse_line_into(b"N1 G0 X1 CR=2 F=A", FileId(3), 7, 100, &mut block);
        let end = parse_plain_line_in(&unread, FileId(3), 7, 100, &mut block)?;
        assert_eq!(end.after, next.len(), "{}", text.escape_ascii());
        Some((block, end.length))
    }

    /// The line `text` reads from the text at hand, ended by `\n` or `\r\n`, as the line reader
    /// reads it, or is left to the line reader only when that does not take it for a plain line.
    fn assert_at_hand_reads_as_the_line(text: &[u8]) {
        let mut line = Block::default();
        parse_line_into(text, FileId(3), 7, 100, &mut line);
        let plain = plain::read_plain(text, FileId(3), 7, 100, &mut Block::default());
        for line_end in [&b"\n"[..], b"\r\n"] {
            match at_hand(text, line_end) {
                Some((block, length)) => {
                    assert!(plain, "{}", text.escape_ascii());
                    assert_eq!(block, line, "{}", text.escape_ascii());
                    assert_eq!(length, text.len(), "{}", text.escape_ascii());
                }
                None => assert!(!plain, "{}", text.escape_ascii()),
            }
        }
    }

    #[test]
    fn the_short_path_reads_cam_lines_as_the_general_way_does() {
        for line in [
            &b"N170 G1 X54.808 Y30.491 Z-1.288 F=FEED1"[..],
            b"N160 G2 X51.438 Y26.151 CR=-11.700 F=FEED2 ; arc",
            b"n10g1x.5y+2.Z-0 cr=5",
            b"G3 X1 Y2 I-0.5 J=AC(3)",
            b"",
            b"   ; comment only",
        ] {
            let (general, fast) = both_ways(line);
            assert_eq!(
                format!("{general:?}"),
                format!("{fast:?}"),
                "{}",
                line.escape_ascii()
            );
        }
        for line in [
            &b"N170 G1 X54.808 Y30.491 Z-1.288 F=FEED1"[..],
            b"N160 G2 X51.438 Y26.151 CR=-11.700 F=FEED2 ; arc",
            b"",
            b"   ; comment only",
            b"N999999999 G1 X1",
        ] {
            assert!(at_hand(line, b"\n").is_some(), "{}", line.escape_ascii());
            assert_at_hand_reads_as_the_line(line);
        }
        let mut block = Block::default();
        let line = b"N170 G1 X54.808 Y30.491 Z-1.288 F=FEED1";
        assert!(plain::read_plain(line, FileId(0), 1, 0, &mut block));
        assert_eq!(block.plain.as_ref().map(|p| p.words().len()), Some(5));
        assert_eq!(
            block.plain.as_ref().and_then(|p| p.feed_name()),
            Some("FEED1")
        );
    }

    #[test]
    fn a_line_at_hand_is_left_to_the_line_reader_where_its_end_or_a_window_is_not_at_hand() {
        let next = "N20 G1 X10.5 Y-2.25 Z0.125 F=FEED2 ; long enough for the numbers' windows\n";
        let long = format!("N10 G1 X1 ;{}\n{next}", "c".repeat(600));
        for unread in [
            "N10 G1 X1",
            "N10 G1 X1\n",
            "N10 G1 X1\r",
            &format!("N10 G1\rX1\n{next}"),
            &format!("N10 G1 X1 ; c\rc\n{next}"),
            &long,
        ] {
            let mut block = Block::default();
            let end = parse_plain_line_in(unread.as_bytes(), FileId(0), 1, 0, &mut block);
            assert_eq!(end, None, "{unread:?}");
        }
        // The long line is a plain one, read the usual way.
        let line = long.lines().next().unwrap_or_default().as_bytes();
        assert!(plain::read_plain(
            line,
            FileId(0),
            1,
            0,
            &mut Block::default()
        ));
        // A comment runs to the `\n`; the `\r` before it is the line end's.
        let unread = format!("N10 G1 X1 ; c\r\n{next}");
        let end = parse_plain_line_in(unread.as_bytes(), FileId(0), 1, 0, &mut Block::default());
        assert_eq!(
            end,
            Some(AtHand {
                length: 13,
                after: next.len()
            })
        );
    }

    proptest::proptest! {
        #[test]
        fn any_line_reads_the_same_by_the_short_path_and_the_general_way(
            pieces in proptest::collection::vec(
                proptest::sample::select(vec![
                    "N10", "N", "n5", ":5", "N4294967296", "N1=", "G1", "g2", "G", "X12.5",
                    "X-1.2", "Y+.5", "Z-0", "X1=5", "X1", "R10=2", "X1(", "X1[", "CR=11.7",
                    "CR=-3", "cr=-.5", "CR==1", "CR=", "CR=-", "CR=--1", "F=FEED1", "F=R1",
                    "F=R1X", "f=feed2", "F=A[2]", "F=SIN(1)", "F=A (1)", "F = 3", "F =3", "F= 3",
                    "CR=5 DIV 2", "AND", "OR", "B_OR", "NOT", "X", "IF", "GOTOF L1", "L1:",
                    "/", "/1", ";c", " ", "  ", "&", "	", "=", "-", "+", ".", "1", "A", "_",
                    "$P", "$P=1", "(", "[", "1EX3", "X1EX3", "X1EX", "X1.5EX-2", "EX",
                    "X99999999999999999999", "'H1F'", "\"s\"", "F='H1F'", "F=\"s\"", "X.", "X.5.",
                    "_A=1", "A_=1", "AB1=2", "ENDLABEL:", "X1e5", "\u{e9}", "F=$A", "F=_A",
                    "F=-3", "F=3.5", "CR=A", "Cr=2", "F=b_2", "N999999999", "N0000000012",
                    "N4294967295", "N12345678901", "\u{b}", "\u{7f}", "X1.23456789012345",
                ]),
                0..8,
            ),
            glue in proptest::collection::vec(proptest::sample::select(vec!["", " ", "\t"]), 8),
        ) {
            let mut line = String::new();
            for (piece, glue) in pieces.iter().zip(&glue) {
                line.push_str(piece);
                line.push_str(glue);
            }
            let (general, fast) = both_ways(line.as_bytes());
            proptest::prop_assert_eq!(format!("{:?}", general), format!("{:?}", fast), "{}", line);
            assert_at_hand_reads_as_the_line(line.as_bytes());
        }
    }
}
