//! The ISO block reader: one line of bytes into blocks of words.
//!
//! The same reader reads the statements of a Syntec `%@MACRO` program (`Format::Macro`), one
//! statement at a time, as `super::program` cuts them out of the text: there `( )` are
//! brackets, not comments, and the structured statements (IF ... END_IF, WHILE, FOR, REPEAT)
//! of `structured.rs` are read.

mod macros;
mod plain;
pub(super) mod structured;

use super::LineBlocks;
use crate::alarm::{Alarm, AlarmCode};
use crate::source::{FileId, Span};
use crate::syntax::decimal::POWERS_OF_TEN;
use crate::syntax::lines::{Line, Unread};
use crate::syntax::{BlockKind, Number, Word};
use plain::{fast_number, read_plain_line, read_plain_line_in};

/// How a text is read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Format {
    /// ISO blocks: a line holds blocks ended by `;` or the line end, `( )` are comments.
    Iso,
    /// One statement of a Syntec `%@MACRO` program (its `;` and comments already removed).
    Macro,
}

/// What varies between the ISO dialects at the level of characters.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SyntaxOptions {
    /// `;` ends a block (as the manuals print the end-of-block code). When false, `;` starts a
    /// comment that runs to the end of the line.
    pub semicolon_ends_block: bool,
    /// `//` starts a comment that runs to the end of the line (Syntec).
    pub slash_slash_comments: bool,
    /// `:` at the start of a block is a program number (FANUC 0M ISO code).
    pub colon_program_number: bool,
    /// `G` with no number is G00 (Mitsubishi, 003 B.0); elsewhere it is an address without a
    /// value.
    pub bare_g_is_g00: bool,
    /// A comment ends at the first `)` (FANUC 0M); otherwise parentheses nest, so that
    /// `(A (B) C)` is one comment.
    pub comment_ends_at_first_paren: bool,
}

impl Default for SyntaxOptions {
    fn default() -> SyntaxOptions {
        SyntaxOptions {
            semicolon_ends_block: true,
            slash_slash_comments: false,
            colon_program_number: true,
            bare_g_is_g00: false,
            comment_ends_at_first_paren: false,
        }
    }
}

/// Reads the blocks of one line into `out` (which is reset first).
// Inlined into the reading loops, with the general reader out of line: the common line costs no
// call.
#[inline(always)]
pub fn parse_line(line: Line<'_>, file: FileId, options: &SyntaxOptions, out: &mut LineBlocks) {
    out.reset();
    if read_plain_line(line, file, out) {
        return;
    }
    out.reset();
    parse_any_line(line, file, options, out);
}

/// Reads the first line of `unread` (text from the start of a line on, line ends included) into
/// `out` (which is reset first) when it is a plain line whose `\n` is in `unread`, as
/// [`parse_line`] would read it: how many bytes of `unread` follow the line's `\n`. `None` leaves
/// the line to [`parse_line`] (`out` then holds nothing to keep); so does a line that ends less
/// than a few dozen bytes before the end of `unread`, and one with a `\r` elsewhere than before
/// its `\n`.
// Inlined into the reading loops: the common line is read straight from the reader's buffer,
// and its end is found on the way instead of by a search of its own.
#[inline(always)]
pub(crate) fn parse_plain_line_in(
    unread: Unread<'_>,
    file: FileId,
    out: &mut LineBlocks,
) -> Option<usize> {
    out.reset();
    read_plain_line_in(unread, file, out)
}

/// Reads the blocks of any line, character by character.
#[inline(never)]
fn parse_any_line(line: Line<'_>, file: FileId, options: &SyntaxOptions, out: &mut LineBlocks) {
    let mut reader = Reader {
        text: line.text,
        pos: 0,
        file,
        base: line.offset,
        line: line.number,
        options,
        format: Format::Iso,
        line_breaks: &[],
    };
    loop {
        reader.skip_blanks();
        if reader.at_end() {
            break;
        }
        let block = out.push();
        let ended = reader.read_block(block);
        if block.is_empty() && block.skip.is_none() && block.alarms.is_empty() {
            out.pop();
        }
        if ended == BlockEnd::Line {
            break;
        }
    }
}

#[derive(PartialEq, Eq)]
enum BlockEnd {
    /// A `;` ended the block; more may follow on the line.
    Semicolon,
    /// The line ended (or the rest of it is a comment).
    Line,
}

struct Reader<'a, 'o> {
    text: &'a [u8],
    pos: usize,
    file: FileId,
    base: u32,
    line: u32,
    options: &'o SyntaxOptions,
    format: Format,
    /// Where `text` has line ends (a macro statement may run over several lines), for the line
    /// numbers of spans; empty for one line.
    line_breaks: &'a [usize],
}

/// Where a number written with an exponent was met.
#[derive(Clone, Copy, Debug)]
enum Exponent {
    /// After the value of a word (`X1e308`).
    AfterWord,
    /// After a constant of a macro expression (`#1 = 1E308`).
    InExpression,
}

/// True when `rest`, what follows a word's number with no blank between, is written as an
/// exponent: a lower-case `e`, or `E` and a sign, then a digit (`1e308`, `1.5E-3`, as `printf`
/// writes them). A capital E and digits (`V0E41`) is the E address of a G65 argument or a
/// tapping cycle, and is left to be one.
fn looks_like_exponent(rest: &[u8]) -> bool {
    matches!(
        rest,
        [b'e', b'0'..=b'9', ..] | [b'e' | b'E', b'+' | b'-', b'0'..=b'9', ..]
    )
}

impl Reader<'_, '_> {
    /// The alarm for a number written with an exponent, from `start` (its word or constant)
    /// to the end of the exponent's digits.
    fn exponent_alarm(&mut self, block: &mut crate::syntax::Block, start: usize, at: Exponent) {
        let exponent = self.pos;
        let mut end = exponent + 1;
        if matches!(self.text.get(end), Some(b'+' | b'-')) {
            end += 1;
        }
        end += self.text[end.min(self.text.len())..]
            .iter()
            .take_while(|b| b.is_ascii_digit())
            .count();
        let end = end.min(self.text.len());
        let written = String::from_utf8_lossy(&self.text[start..end]).into_owned();
        let (code, reads_as) = match at {
            Exponent::AfterWord => (
                AlarmCode::BadNumber,
                format!(
                    "this reads as the word {} followed by the address E",
                    String::from_utf8_lossy(&self.text[start..exponent]).to_ascii_uppercase()
                ),
            ),
            Exponent::InExpression => (
                AlarmCode::MacroSyntax,
                "E cannot follow a constant inside an expression".to_string(),
            ),
        };
        block.alarms.push(
            Alarm::error(
                code,
                self.span(start, end),
                format!(
                    "`{written}`: ISO G-code has no exponent notation, and E is an address here \
                     (the thread lead or feed on FANUC, a macro argument): {reads_as}"
                ),
            )
            .with_help("write the number out with a decimal point (`X0.0015`, not `X1.5e-3`)"),
        );
    }
}

/// True when `block` has a comment and a G47 word: Haas engraves the comment's text, so it is
/// kept.
fn engraves(block: &crate::syntax::Block) -> bool {
    block.comment.is_some()
        && block
            .words
            .iter()
            .any(|w| w.letter == b'G' && w.expr.is_none() && w.number.value == 47.0)
}

#[cfg(test)]
pub(super) use macros::tests::describe as describe_block;

/// Reads one statement of a Syntec macro program into `out`: `text` is the statement as it
/// stands in the file from byte `offset` (line `line`), without its `;`, comments blanked out.
pub(crate) fn parse_macro_statement(
    text: &[u8],
    offset: u32,
    line: u32,
    file: FileId,
    options: &SyntaxOptions,
    out: &mut LineBlocks,
) {
    let line_breaks: Vec<usize> = text
        .iter()
        .enumerate()
        .filter(|(_, &b)| b == b'\n')
        .map(|(i, _)| i)
        .collect();
    let mut reader = Reader {
        text,
        pos: 0,
        file,
        base: offset,
        line,
        options,
        format: Format::Macro,
        line_breaks: &line_breaks,
    };
    reader.skip_blanks();
    if reader.at_end() {
        return;
    }
    let block = out.push();
    if !reader.read_case_label(block) {
        reader.read_block(block);
    }
    if block.is_empty() && block.skip.is_none() && block.alarms.is_empty() {
        out.pop();
    }
}

impl Reader<'_, '_> {
    fn at_end(&self) -> bool {
        self.pos >= self.text.len()
    }

    fn peek(&self) -> Option<u8> {
        self.text.get(self.pos).copied()
    }

    fn peek_at(&self, ahead: usize) -> Option<u8> {
        self.text.get(self.pos + ahead).copied()
    }

    fn span(&self, start: usize, end: usize) -> Span {
        let at = |p: usize| {
            self.base
                .saturating_add(u32::try_from(p).unwrap_or(u32::MAX))
        };
        let line = self.line + self.line_breaks.partition_point(|&b| b < start) as u32;
        Span::new(self.file, line, at(start)..at(end))
    }

    fn skip_blanks(&mut self) {
        while let Some(b) = self.peek() {
            // A line end is only ever inside a macro statement that runs over several lines.
            if matches!(b, b' ' | b'\t' | b'\x0c' | b'\x0b' | b'\r' | b'\n' | 0) {
                self.pos += 1;
            } else {
                break;
            }
        }
    }

    /// Reads one block; returns how it ended.
    fn read_block(&mut self, block: &mut crate::syntax::Block) -> BlockEnd {
        let start = self.pos;
        let end = self.read_items(block);
        let mut stop = self.pos;
        if end == BlockEnd::Semicolon {
            stop -= 1;
        }
        block.span = self.span(start, stop.max(start));
        if !block.statements.is_empty() || engraves(block) {
            if let Some(comment) = block.comment {
                let from = comment.start.saturating_sub(self.base) as usize;
                let to = (comment.end.saturating_sub(self.base) as usize).min(self.text.len());
                let text = self.text.get(from..to).unwrap_or(&[]);
                let text = text.strip_prefix(b"(").unwrap_or(text);
                let text = text.strip_suffix(b")").unwrap_or(text);
                block.message = Some(String::from_utf8_lossy(text).trim().into());
            }
        }
        end
    }

    fn read_items(&mut self, block: &mut crate::syntax::Block) -> BlockEnd {
        loop {
            self.skip_blanks();
            let Some(byte) = self.peek() else {
                return BlockEnd::Line;
            };
            if block.words.len() + block.statements.len() >= super::MAX_WORDS_PER_BLOCK {
                // A line of megabytes of words would otherwise be held word by word.
                block.alarms.push(
                    Alarm::error(
                        AlarmCode::ValueOutOfRange,
                        self.span(self.pos, self.pos + 1),
                        format!(
                            "the block has more than {} words",
                            super::MAX_WORDS_PER_BLOCK
                        ),
                    )
                    .with_help("no control takes a block this long: end blocks with a line end"),
                );
                return self.abandon(block);
            }
            let at_block_start =
                block.words.is_empty() && block.statements.is_empty() && block.skip.is_none();
            match byte {
                b';' if self.options.semicolon_ends_block => {
                    self.pos += 1;
                    return BlockEnd::Semicolon;
                }
                b';' => {
                    self.note_comment(block, self.pos, self.text.len());
                    self.pos = self.text.len();
                    return BlockEnd::Line;
                }
                b'(' if self.format == Format::Iso => self.read_comment(block),
                b'/' if self.options.slash_slash_comments && self.peek_at(1) == Some(b'/') => {
                    self.note_comment(block, self.pos, self.text.len());
                    self.pos = self.text.len();
                    return BlockEnd::Line;
                }
                b'/' if at_block_start => self.read_block_skip(block),
                b'%' if at_block_start => {
                    block.kind = if is_macro_header(&self.text[self.pos..]) {
                        BlockKind::MacroHeader
                    } else {
                        BlockKind::TapeMark
                    };
                    self.pos = self.text.len();
                    return BlockEnd::Line;
                }
                b':' if at_block_start
                    && self.options.colon_program_number
                    && self.peek_at(1) != Some(b'=') =>
                {
                    let start = self.pos;
                    self.pos += 1;
                    if !self.read_value(block, b'O', start) {
                        return self.abandon(block);
                    }
                }
                b'#' => {
                    if self.read_assignment(block).is_err() {
                        return self.abandon(block);
                    }
                }
                b'@' if self.format == Format::Macro => {
                    if self.read_assignment(block).is_err() {
                        return self.abandon(block);
                    }
                }
                b'(' => {
                    let span = self.span(self.pos, self.pos + 1);
                    block.alarms.push(
                        Alarm::error(
                            AlarmCode::MacroSyntax,
                            span,
                            "`(` where a statement or a word should start",
                        )
                        .with_help("in a %@MACRO program `( )` are brackets: comments are `// ...` or `(* ... *)`"),
                    );
                    return self.abandon(block);
                }
                b if b.is_ascii_alphabetic() => {
                    if !self.read_plain_word(block) && !self.read_word(block) {
                        return self.abandon(block);
                    }
                }
                _ => {
                    let width = char_width(&self.text[self.pos..]);
                    let span = self.span(self.pos, self.pos + width);
                    let shown = String::from_utf8_lossy(&self.text[self.pos..self.pos + width])
                        .into_owned();
                    block.alarms.push(Alarm::error(
                        AlarmCode::UnexpectedCharacter,
                        span,
                        format!(
                            "unexpected character `{}` in an ISO block",
                            shown.escape_debug()
                        ),
                    ));
                    return self.abandon(block);
                }
            }
        }
    }

    /// Skips the rest of a block that cannot be read, up to the next `;` or the line end.
    fn abandon(&mut self, _block: &mut crate::syntax::Block) -> BlockEnd {
        let mut depth = 0usize;
        while let Some(b) = self.peek() {
            self.pos += 1;
            match b {
                b'(' => depth += 1,
                b')' => depth = depth.saturating_sub(1),
                b';' if depth == 0 && self.options.semicolon_ends_block => {
                    return BlockEnd::Semicolon
                }
                _ => {}
            }
        }
        BlockEnd::Line
    }

    fn note_comment(&self, block: &mut crate::syntax::Block, start: usize, end: usize) {
        if block.comment.is_none() {
            block.comment = Some(self.span(start, end));
        }
    }

    /// `( ... )`; nested parentheses are counted so that `(A (B) C)` is one comment, unless the
    /// control ends a comment at its first `)`.
    fn read_comment(&mut self, block: &mut crate::syntax::Block) {
        let start = self.pos;
        let mut depth = 0usize;
        let nested = !self.options.comment_ends_at_first_paren;
        while let Some(b) = self.peek() {
            self.pos += 1;
            match b {
                b'(' if nested || depth == 0 => depth += 1,
                b')' => {
                    depth -= 1;
                    if depth == 0 {
                        self.note_comment(block, start, self.pos);
                        return;
                    }
                }
                _ => {}
            }
        }
        self.note_comment(block, start, self.pos);
        block.alarms.push(
            Alarm::warning(
                AlarmCode::UnclosedComment,
                self.span(start, start + 1),
                "comment is not closed before the end of the line",
            )
            .with_help("add `)`; the control takes the rest of the line as comment"),
        );
    }

    fn read_block_skip(&mut self, block: &mut crate::syntax::Block) {
        self.pos += 1;
        let mut level = 1u8;
        if let Some(d @ b'1'..=b'9') = self.peek() {
            // `/2` is block skip switch 2; a digit right after `/` belongs to the slash.
            level = d - b'0';
            self.pos += 1;
        }
        block.skip = Some(level);
    }

    /// The common word, a letter right before its number (`X-12.5`), read in one step; false
    /// (nothing consumed) for every other form, which [`Reader::read_word`] reads.
    fn read_plain_word(&mut self, block: &mut crate::syntax::Block) -> bool {
        let start = self.pos;
        let rest = &self.text[start + 1..];
        let (negative, sign) = match rest.first() {
            Some(b'-') => (true, 1),
            Some(b'+') => (false, 1),
            _ => (false, 0),
        };
        let Some((number, length)) = fast_number(&rest[sign..], negative) else {
            return false;
        };
        let end = start + 1 + sign + length;
        if self.text.get(end) == Some(&b'=') || looks_like_exponent(&self.text[end..]) {
            return false;
        }
        let letter = self.text[start].to_ascii_uppercase();
        block.words.push(Word {
            letter,
            index: 0,
            number,
            span: self.span(start, end),
            expr: None,
        });
        self.pos = end;
        true
    }

    /// An address letter and its value, or a macro statement that starts with a keyword.
    /// Returns false when the block cannot be read further.
    fn read_word(&mut self, block: &mut crate::syntax::Block) -> bool {
        let start = self.pos;
        let letter = self.text[self.pos].to_ascii_uppercase();
        let macro_format = self.format == Format::Macro;
        if self
            .peek_at(1)
            .is_some_and(|b| b.is_ascii_alphabetic() || (macro_format && b == b'_'))
        {
            let read = match self.format {
                Format::Iso => self.read_keyword_statement(block),
                Format::Macro => self.read_structured_statement(block),
            };
            if let Some(read) = read {
                return read.is_ok();
            }
            self.unknown_name(block, start);
            return false;
        }
        self.pos += 1;
        if self.expression_value_follows() {
            return self.read_expression_word(block, letter, start).is_ok();
        }
        self.read_value(block, letter, start)
    }

    /// Two letters in a row that start no statement: the alarm says what they look like.
    fn unknown_name(&mut self, block: &mut crate::syntax::Block, start: usize) {
        let end = self.text[start..]
            .iter()
            .position(|b| !(b.is_ascii_alphabetic() || *b == b'_'))
            .map_or(self.text.len(), |n| start + n);
        let name = String::from_utf8_lossy(&self.text[start..end]).to_ascii_uppercase();
        let span = self.span(start, end);
        let called = self.text[end..]
            .iter()
            .find(|b| !matches!(b, b' ' | b'\t'))
            .is_some_and(|&b| b == b'(' || b == b'[');
        block.alarms.push(match self.format {
            // IEC 61131-3 has DIV; Syntec's macro language does not (syntec-macro handbook
            // 02-variables 3.4): its `/` divides two whole numbers to a whole number.
            Format::Macro if name == "DIV" => Alarm::error(
                AlarmCode::MacroSyntax,
                span,
                "`DIV` is not an operator of a %@MACRO program",
            )
            .with_help("divide with `/`: two numbers without a decimal point give a whole quotient (`7/2` is 3), `7./2` gives 3.5"),
            Format::Macro if called => {
                Alarm::not_supported(span, &format!("the macro function `{name}`"), None)
            }
            Format::Macro => Alarm::error(
                AlarmCode::MacroSyntax,
                span,
                format!("`{name}` is not a statement of a %@MACRO program"),
            )
            .with_help("a statement is an assignment (`#1 := 2;`), a keyword statement (IF, WHILE, FOR, REPEAT, GOTO ...) or NC words (`G01 X10.;`)"),
            Format::Iso if is_macro_keyword(&name) => {
                Alarm::not_supported(span, &format!("the macro statement `{name}`"), None)
            }
            Format::Iso => Alarm::error(
                AlarmCode::UnexpectedCharacter,
                span,
                format!("`{name}` is not an ISO word"),
            )
            .with_help("an address is one letter followed by a number, e.g. `X10.`"),
        });
    }

    /// The number after an address letter (and the value of an extended address `F2=...`).
    fn read_value(&mut self, block: &mut crate::syntax::Block, letter: u8, start: usize) -> bool {
        let Some(first) = self.read_number(start, letter, block) else {
            return false;
        };
        let end = self.pos;
        if looks_like_exponent(&self.text[end..]) {
            self.exponent_alarm(block, start, Exponent::AfterWord);
            return false;
        }
        self.skip_blanks();
        let mut index = 0u8;
        let mut number = first;
        if self.peek() != Some(b'=') || self.peek_at(1) == Some(b'=') {
            self.pos = end;
        } else {
            let simple_index =
                !first.decimal_point && !first.negative && (1.0..=9.0).contains(&first.value);
            if !simple_index {
                let span = self.span(self.pos, self.pos + 1);
                block.alarms.push(Alarm::error(
                    AlarmCode::UnexpectedCharacter,
                    span,
                    "`=` after an address: only F1= to F9= style extended addresses take one",
                ));
                return false;
            }
            index = first.value as u8;
            self.pos += 1;
            let Some(value) = self.read_number(start, letter, block) else {
                return false;
            };
            number = value;
        }
        block.words.push(Word {
            letter,
            index,
            number,
            span: self.span(start, self.pos),
            expr: None,
        });
        true
    }

    /// True when the blanks at the cursor are followed by more of the same number: the controls
    /// ignore spaces anywhere in a block, so `X1 2.5` is X12.5.
    fn blank_inside_number(&self, decimal_point: bool) -> bool {
        let rest = &self.text[self.pos..];
        match rest.iter().find(|b| !matches!(b, b' ' | b'\t')) {
            Some(b'0'..=b'9') => true,
            Some(b'.') => !decimal_point,
            _ => false,
        }
    }

    /// `[+|-] digits [. digits]`, blanks allowed anywhere inside.
    fn read_number(
        &mut self,
        word_start: usize,
        letter: u8,
        block: &mut crate::syntax::Block,
    ) -> Option<Number> {
        self.skip_blanks();
        let mut negative = false;
        if let Some(sign @ (b'+' | b'-')) = self.peek() {
            negative = sign == b'-';
            self.pos += 1;
            self.skip_blanks();
        }
        if let Some((number, end)) = fast_number(&self.text[self.pos..], negative) {
            self.pos += end;
            return Some(number);
        }
        self.read_digits(word_start, letter, negative, block)
    }

    /// The digits of a number in every form: blanks inside, more than 18 digits, errors.
    fn read_digits(
        &mut self,
        word_start: usize,
        letter: u8,
        negative: bool,
        block: &mut crate::syntax::Block,
    ) -> Option<Number> {
        let digits_start = self.pos;
        let mut mantissa: u64 = 0;
        let mut significant = 0u32;
        let mut fraction_digits = 0i32;
        let mut decimal_point = false;
        let mut any_digit = false;
        let mut overflow_digits = 0i32;
        while let Some(b) = self.peek() {
            match b {
                b'0'..=b'9' => {
                    any_digit = true;
                    if significant < 18 {
                        mantissa = mantissa * 10 + u64::from(b - b'0');
                        if mantissa != 0 {
                            significant += 1;
                        }
                        if decimal_point {
                            fraction_digits += 1;
                        }
                    } else if !decimal_point {
                        overflow_digits += 1;
                    }
                }
                b'.' if !decimal_point => decimal_point = true,
                b' ' | b'\t' if self.blank_inside_number(decimal_point) => {}
                b'.' => {
                    let span = self.span(word_start, self.pos + 1);
                    block.alarms.push(Alarm::error(
                        AlarmCode::BadNumber,
                        span,
                        "number has two decimal points",
                    ));
                    return None;
                }
                _ => break,
            }
            self.pos += 1;
        }
        if !any_digit {
            if letter == b'G'
                && self.options.bare_g_is_g00
                && digits_start == self.pos
                && !decimal_point
                && !negative
            {
                return Some(Number::default());
            }
            let span = self.span(word_start, self.pos.max(word_start + 1));
            let message = if digits_start == self.pos && !decimal_point {
                format!("address {} has no value", letter as char)
            } else {
                format!("address {} has no digits", letter as char)
            };
            block
                .alarms
                .push(Alarm::error(AlarmCode::MissingValue, span, message));
            return None;
        }
        let magnitude = scale(mantissa, overflow_digits - fraction_digits);
        let value = if negative { -magnitude } else { magnitude };
        Some(Number {
            value,
            decimal_point,
            negative,
        })
    }
}

/// `mantissa * 10^exponent`, correctly rounded for the exponents a G-code number can have: the
/// powers of ten up to 10^22 are exact in f64, so one multiplication or division rounds once.
fn scale(mantissa: u64, exponent: i32) -> f64 {
    const POWERS: [f64; 23] = POWERS_OF_TEN;
    let m = mantissa as f64;
    if mantissa < (1u64 << 53) {
        let e = exponent.unsigned_abs() as usize;
        if e < POWERS.len() {
            return if exponent < 0 {
                m / POWERS[e]
            } else {
                m * POWERS[e]
            };
        }
    }
    format!("{mantissa}e{exponent}")
        .parse()
        .unwrap_or(f64::INFINITY)
}

fn char_width(bytes: &[u8]) -> usize {
    let first = bytes.first().copied().unwrap_or(0);
    let width = match first {
        0xC0..=0xDF => 2,
        0xE0..=0xEF => 3,
        0xF0..=0xF7 => 4,
        _ => 1,
    };
    if bytes.len() >= width && std::str::from_utf8(&bytes[..width]).is_ok() {
        width
    } else {
        1
    }
}

/// `%@MACRO` at the start of `rest` (any case), not followed by more of a word.
pub(super) fn is_macro_header(rest: &[u8]) -> bool {
    const HEADER: &[u8] = b"%@MACRO";
    rest.len() >= HEADER.len()
        && rest[..HEADER.len()].eq_ignore_ascii_case(HEADER)
        && !rest
            .get(HEADER.len())
            .is_some_and(|b| b.is_ascii_alphanumeric() || *b == b'_')
}

fn is_macro_keyword(word: &str) -> bool {
    const KEYWORDS: &[&str] = &[
        "IF", "THEN", "GOTO", "WHILE", "WH", "DO", "END", "EQ", "NE", "GT", "GE", "LT", "LE",
        "AND", "OR", "XOR", "MOD", "SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN", "SQRT", "SQR",
        "ABS", "ROUND", "RND", "FIX", "FUP", "LN", "EXP", "POW", "BIN", "BCD", "ELSE", "ELSIF",
        "ENDIF", "END_IF", "FOR", "TO", "BY", "REPEAT", "UNTIL", "POPEN", "PCLOS", "DPRNT",
        "BPRNT", "SETVN",
    ];
    KEYWORDS.iter().any(|k| word.starts_with(k))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::Block;

    fn parse(text: &str) -> Vec<Block> {
        parse_with(text, SyntaxOptions::default())
    }

    fn parse_with(text: &str, options: SyntaxOptions) -> Vec<Block> {
        let mut out = LineBlocks::new();
        let line = Line {
            text: text.as_bytes(),
            offset: 0,
            number: 1,
        };
        parse_line(line, FileId(0), &options, &mut out);
        out.as_slice().to_vec()
    }

    fn words(block: &Block) -> String {
        block
            .words
            .iter()
            .map(|w| {
                let index = if w.index > 0 {
                    format!("{}=", w.index)
                } else {
                    String::new()
                };
                let point = if w.number.decimal_point { "." } else { "" };
                format!("{}{index}{}{point}", w.letter as char, w.number.value)
            })
            .collect::<Vec<_>>()
            .join(" ")
    }

    #[test]
    fn words_without_spaces_are_split_at_letters() {
        let blocks = parse("G1X0.0010Y-0.0010F300");
        assert_eq!(words(&blocks[0]), "G1 X0.001. Y-0.001. F300");
    }

    #[test]
    fn semicolons_end_blocks_and_comments_are_skipped() {
        let blocks = parse("G90 G00 X90.0 (GO) Y40.0; G01 Z-5. F100;");
        assert_eq!(blocks.len(), 2);
        assert_eq!(words(&blocks[0]), "G90 G0 X90. Y40.");
        assert_eq!(words(&blocks[1]), "G1 Z-5. F100");
        assert_eq!(blocks[1].span.start, 26);
    }

    #[test]
    fn spaces_between_address_sign_and_digits_are_ignored() {
        assert_eq!(words(&parse("Y -20.")[0]), "Y-20.");
        assert_eq!(words(&parse("X 1 2 .5")[0]), "X12.5.");
    }

    #[test]
    fn nested_parentheses_stay_inside_the_comment() {
        let blocks = parse("G0 (stock is (nominally) 3/8\") X1.");
        assert_eq!(words(&blocks[0]), "G0 X1.");
        assert!(blocks[0].alarms.is_empty());
    }

    #[test]
    fn extended_addresses_take_their_index() {
        assert_eq!(words(&parse("G81 F2=1000 S1=150")[0]), "G81 F2=1000 S1=150");
    }

    #[test]
    fn slash_starts_block_skip_and_double_slash_a_syntec_comment() {
        let syntec = SyntaxOptions {
            slash_slash_comments: true,
            ..SyntaxOptions::default()
        };
        let blocks = parse_with("/2 G0 X1.; // move", syntec);
        assert_eq!(blocks.len(), 1);
        assert_eq!(blocks[0].skip, Some(2));
        assert_eq!(words(&blocks[0]), "G0 X1.");
    }

    #[test]
    fn negative_zero_keeps_its_sign() {
        let blocks = parse("Y-0");
        assert!(blocks[0].words[0].number.negative);
    }

    #[test]
    fn percent_and_colon_program_numbers() {
        assert_eq!(parse("%")[0].kind, BlockKind::TapeMark);
        assert_eq!(words(&parse(":0097")[0]), "O97");
    }

    #[test]
    fn address_without_value_is_an_alarm_with_its_span() {
        let blocks = parse("G0 X Y1.");
        let alarm = &blocks[0].alarms[0];
        assert_eq!(alarm.code, AlarmCode::MissingValue);
        assert_eq!(alarm.span.unwrap().start, 3);
    }

    #[test]
    fn numbers_round_once() {
        assert_eq!(parse("X0.1")[0].words[0].number.value, 0.1);
        assert_eq!(parse("X-1.833")[0].words[0].number.value, -1.833);
        assert_eq!(
            parse("X123456789.123456789")[0].words[0].number.value,
            123456789.12345679
        );
    }
}
