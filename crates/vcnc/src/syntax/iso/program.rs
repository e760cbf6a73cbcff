//! A whole program held in memory, read into lines of blocks: an ISO program line by line, a
//! Syntec `%@MACRO` program statement by statement.
//!
//! A Syntec control reads a file whose first line is `%@MACRO` as a macro program
//! (spec/iso-syntec-milling.md §0.1.1, seed L5031-5039): statements end with `;` wherever the
//! line ends, `IF ... THEN`, `WHILE ... DO`, `FOR ... DO`, `ELSE` and `REPEAT` need none, several
//! statements may share a line and one may run over several lines (a line without `;` goes on
//! with the next; a CASE label such as `2, 3:` is a statement of its own), comments are
//! `// ...` to the line end and `(* ... *)` over any number of
//! lines, and `( )` are brackets. [`parse_program`] cuts such a text into statements and reads
//! each with the ISO reader in its macro format; a statement's block is kept with the line it
//! starts on, so a block's place is still (line, block) as in an ISO program, and a block's span
//! covers its statement, lines and all.
//!
//! Only the text after the header is read this way: the lines before it (blank lines, comments,
//! `%`, an `O1234` program number) are ISO lines. A program whose first line is anything else is
//! an ISO program, whatever it holds: `%@MACRO` further down is not a header.

use super::parser::structured::is_case_label_list;
use super::parser::{is_macro_header, parse_macro_statement};
use super::structure::Structure;
use super::{parse_line, LineBlocks, SyntaxOptions};
use crate::alarm::{Alarm, AlarmCode};
use crate::source::{FileId, Span};
use crate::syntax::lines::{LineSource, TextLines};

/// A program's blocks, by line.
#[derive(Debug)]
pub struct ProgramBlocks {
    /// One entry per line of the program text, from its first line: the blocks that start on
    /// that line.
    pub lines: Vec<LineBlocks>,
    /// For a `%@MACRO` program, which statements belong together (IF with its ELSE and END_IF,
    /// loops with their ends); `None` for an ISO program.
    pub structure: Option<Structure>,
}

/// Reads the program in `text` from byte `offset`, which starts line `line` (1-based), to the end
/// of `text`; spans name `file`.
pub fn parse_program(
    text: &[u8],
    offset: usize,
    line: u32,
    file: FileId,
    options: &SyntaxOptions,
) -> ProgramBlocks {
    let offset = offset.min(text.len());
    read_program(text, Piece { offset, base: 0 }, line, file, options)
}

/// Reads the program in `text`, a piece of a file that starts at byte `base` of the file and at
/// line `line` (1-based): spans are the file's. For a program read out of a file that is not
/// held whole.
pub fn parse_program_piece(
    text: &[u8],
    base: usize,
    line: u32,
    file: FileId,
    options: &SyntaxOptions,
) -> ProgramBlocks {
    read_program(text, Piece { offset: 0, base }, line, file, options)
}

/// Where a program starts in the text it is read from (`offset`), and where that text starts in
/// its file (`base`).
#[derive(Clone, Copy)]
struct Piece {
    offset: usize,
    base: usize,
}

fn read_program(
    text: &[u8],
    Piece { offset, base }: Piece,
    line: u32,
    file: FileId,
    options: &SyntaxOptions,
) -> ProgramBlocks {
    let header = macro_header(&text[offset..]);
    let iso_end = header.map_or(text.len(), |h| offset + h.body);
    // `//` comments before the header are what made it the first line that counts.
    let preamble = SyntaxOptions {
        slash_slash_comments: options.slash_slash_comments || header.is_some(),
        ..*options
    };
    let mut source = TextLines::piece(&text[offset..iso_end], base + offset, line);
    let mut lines = Vec::new();
    while let Ok(Some(line)) = source.next_line() {
        let mut blocks = LineBlocks::new();
        parse_line(line, file, &preamble, &mut blocks);
        lines.push(blocks);
    }
    let Some(header) = header else {
        return ProgramBlocks {
            lines,
            structure: None,
        };
    };
    let first_line = line.saturating_add(header.line as u32 + 1);
    let mut cutter = Cutter::new(text, iso_end, first_line, file, options);
    cutter.base = base;
    cutter.run();
    lines.extend(cutter.lines);
    let structure = Some(Structure::scan(&lines));
    ProgramBlocks { lines, structure }
}

/// Where the `%@MACRO` header of a program text is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Header {
    /// Its line index (0 for the text's first line).
    line: usize,
    /// The byte where the macro program's body starts (the line after the header).
    body: usize,
}

/// The header, when the first line of `text` that is not blank, a comment, `%` or a program
/// number is `%@MACRO`.
fn macro_header(text: &[u8]) -> Option<Header> {
    let mut start = 0;
    for (index, line) in text.split(|&b| b == b'\n').enumerate() {
        let body = (start + line.len() + 1).min(text.len());
        let content = line.trim_ascii();
        start += line.len() + 1;
        if is_macro_header(content) {
            return Some(Header { line: index, body });
        }
        let skipped = content.is_empty()
            || content.starts_with(b"//")
            || content.starts_with(b"(")
            || content == b"%"
            || (content.len() > 1
                && matches!(content[0], b'O' | b'o')
                && content[1].is_ascii_digit());
        if !skipped {
            return None;
        }
    }
    None
}

/// Keywords that end a statement without `;`.
const OPENERS: &[&[u8]] = &[b"THEN", b"DO", b"ELSE", b"REPEAT", b"OF"];

/// Keywords that make a statement of their own, ended by the line end when `;` is missing.
const CLOSERS: &[&[u8]] = &[
    b"END_IF",
    b"ENDIF",
    b"END_WHILE",
    b"ENDWHILE",
    b"END_FOR",
    b"ENDFOR",
    b"END_REPEAT",
    b"ENDREPEAT",
    b"END_CASE",
    b"ENDCASE",
    b"EXIT",
];

/// Cuts a macro program's body into statements and reads each.
struct Cutter<'t, 'o> {
    text: &'t [u8],
    /// The file offset of `text[0]` (spans are the file's).
    base: usize,
    /// The next byte to look at.
    pos: usize,
    /// Line index (in `lines`) and number of the byte at `pos`.
    line_index: usize,
    line_number: u32,
    file: FileId,
    options: &'o SyntaxOptions,
    /// The statement being gathered: where it starts (byte, line index, line number) and its
    /// bytes so far, comments blanked out (one byte for each byte of the text).
    start: Option<(usize, usize, u32)>,
    statement: Vec<u8>,
    lines: Vec<LineBlocks>,
}

impl<'t, 'o> Cutter<'t, 'o> {
    fn new(
        text: &'t [u8],
        body: usize,
        line_number: u32,
        file: FileId,
        options: &'o SyntaxOptions,
    ) -> Cutter<'t, 'o> {
        let line_count = text[body..].split(|&b| b == b'\n').count();
        Cutter {
            text,
            base: 0,
            pos: body,
            line_index: 0,
            line_number,
            file,
            options,
            start: None,
            statement: Vec::new(),
            lines: (0..line_count).map(|_| LineBlocks::new()).collect(),
        }
    }

    fn run(&mut self) {
        while let Some(&byte) = self.text.get(self.pos) {
            let next = self.text.get(self.pos + 1).copied();
            match (byte, next) {
                (b'/', Some(b'/')) => self.line_comment(),
                (b'(', Some(b'*')) => self.block_comment(),
                (b'"', _) => self.quoted(),
                (b';', _) => {
                    self.finish();
                    self.pos += 1;
                }
                (b':', next) if next != Some(b'=') && is_case_label_list(&self.statement) => {
                    // `2, 3:` labels the statements after it: a statement of its own.
                    self.take(1);
                    self.finish();
                }
                (b'\n', _) => self.line_end(),
                (b' ' | b'\t' | b'\r' | b'\x0c' | b'\x0b' | 0, _) => self.blank(1),
                (b, _) if b.is_ascii_alphabetic() || b == b'_' => self.word(),
                _ => self.take(1),
            }
        }
        self.finish();
    }

    /// Adds `length` bytes of the text to the statement (starting one if none is open).
    fn take(&mut self, length: usize) {
        if self.start.is_none() {
            self.start = Some((self.pos, self.line_index, self.line_number));
        }
        let end = (self.pos + length).min(self.text.len());
        self.statement.extend_from_slice(&self.text[self.pos..end]);
        self.pos = end;
    }

    /// Skips `length` bytes that are not part of the statement's words (blanks, comments): a
    /// statement keeps a blank in their place, line ends as they are.
    fn blank(&mut self, length: usize) {
        let end = (self.pos + length).min(self.text.len());
        for &b in &self.text[self.pos..end] {
            if b == b'\n' {
                self.line_index += 1;
                self.line_number = self.line_number.saturating_add(1);
            }
            if self.start.is_some() {
                self.statement.push(if b == b'\n' { b'\n' } else { b' ' });
            }
        }
        self.pos = end;
    }

    fn line_comment(&mut self) {
        let length = self.text[self.pos..]
            .iter()
            .position(|&b| b == b'\n')
            .unwrap_or(self.text.len() - self.pos);
        self.blank(length);
    }

    fn block_comment(&mut self) {
        let open = self.pos;
        match self.text[open + 2..].windows(2).position(|w| w == b"*)") {
            Some(length) => self.blank(length + 4),
            None => {
                let (line_index, line_number) = (self.line_index, self.line_number);
                self.blank(self.text.len() - open);
                let at = |p: usize| u32::try_from(self.base + p).unwrap_or(u32::MAX);
                let span = Span::new(self.file, line_number, at(open)..at(open + 2));
                let alarm = Alarm::warning(
                    AlarmCode::UnclosedComment,
                    span,
                    "comment `(*` is not closed: the rest of the program is comment",
                )
                .with_help("close it with `*)`");
                if let Some(line) = self.lines.get_mut(line_index) {
                    line.push().alarms.push(alarm);
                }
            }
        }
    }

    /// `"text"` up to its closing quote or the line end, kept as it is (a `;` or `//` inside
    /// does not end anything).
    fn quoted(&mut self) {
        let rest = &self.text[self.pos + 1..];
        let length = rest
            .iter()
            .position(|&b| b == b'"' || b == b'\n')
            .map_or(rest.len(), |i| if rest[i] == b'"' { i + 1 } else { i });
        self.take(length + 1);
    }

    /// A run of letters: THEN, DO, ELSE, REPEAT and OF end the statement after them.
    fn word(&mut self) {
        let rest = &self.text[self.pos..];
        let length = rest
            .iter()
            .take_while(|b| b.is_ascii_alphabetic() || **b == b'_')
            .count();
        let word = &rest[..length];
        let followed_by_digit = rest.get(length).is_some_and(u8::is_ascii_digit);
        self.take(length);
        if !followed_by_digit && OPENERS.iter().any(|k| word.eq_ignore_ascii_case(k)) {
            self.finish();
        }
    }

    /// A line end goes on with the statement, unless the statement is complete without `;`
    /// (a lone END_IF, EXIT ..., a sequence number alone, a `%` line).
    fn line_end(&mut self) {
        let content = self.statement.trim_ascii();
        let label = content.len() > 1
            && matches!(content[0], b'N' | b'n')
            && content[1..].iter().all(u8::is_ascii_digit);
        let complete = label
            || content.first() == Some(&b'%')
            || CLOSERS.iter().any(|k| content.eq_ignore_ascii_case(k));
        if complete {
            self.finish();
        }
        self.blank(1);
    }

    /// Reads the statement gathered so far into the blocks of the line it starts on.
    fn finish(&mut self) {
        let Some((start, line_index, line_number)) = self.start.take() else {
            return;
        };
        let offset = u32::try_from(self.base + start).unwrap_or(u32::MAX);
        if let Some(line) = self.lines.get_mut(line_index) {
            parse_macro_statement(
                &self.statement,
                offset,
                line_number,
                self.file,
                self.options,
                line,
            );
        }
        self.statement.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::iso::parser::describe_block as describe;

    fn read(text: &str) -> ProgramBlocks {
        parse_program(text.as_bytes(), 0, 1, FileId(0), &SyntaxOptions::default())
    }

    /// Each line that starts blocks: `n: block || block`.
    fn lines(text: &str) -> Vec<String> {
        read(text)
            .lines
            .iter()
            .enumerate()
            .filter(|(_, l)| !l.as_slice().is_empty())
            .map(|(i, l)| {
                let blocks: Vec<String> = l.as_slice().iter().map(describe).collect();
                format!("{}: {}", i + 1, blocks.join(" || "))
            })
            .collect()
    }

    #[test]
    fn statements_end_at_semicolons_and_after_then_do_else_repeat() {
        assert_eq!(
            lines("%@MACRO\n#1 := 1; #2 := 2;\nIF #1 = 1 THEN #3 := 3; ELSE #3 := 4; END_IF;\nREPEAT #1 := #1 + 1; UNTIL #1 > 3 END_REPEAT;\n"),
            vec![
                "1: MacroHeader",
                "2: #[1] = 1 || #[2] = 2",
                "3: if #1 1 Equal then || #[3] = 3 || else || #[3] = 4 || end_if",
                "4: repeat || #[1] = #1 1 Add || until #1 3 Greater | end_repeat",
            ]
        );
    }

    #[test]
    fn a_line_without_semicolon_goes_on_with_the_next() {
        let program =
            read("%@MACRO\n#1 := 1 +\n  2;\nG01 X1.\n  Y2.;\nEND_IF\nG00 Z5.;\nN10\nIF 1 THEN\n");
        let blocks: Vec<String> = program
            .lines
            .iter()
            .flat_map(|l| l.as_slice().iter().map(describe))
            .collect();
        assert_eq!(
            blocks,
            vec![
                "MacroHeader",
                "#[1] = 1 2 Add",
                "G1 | X1 | Y2",
                "end_if",
                "G0 | Z5",
                "N10",
                "if 1 then"
            ]
        );
        let statement = &program.lines[1].as_slice()[0];
        assert_eq!(
            (
                statement.span.line,
                statement.span.start,
                statement.span.end
            ),
            (2, 8, 21)
        );
        let y = program.lines[3].as_slice()[0].words[2].span;
        assert_eq!((y.line, y.start), (5, 33));
    }

    #[test]
    fn comments_are_skipped_and_parentheses_bracket() {
        assert_eq!(
            lines("// title\n%@MACRO\n#1 := 2; // a note; with a semicolon\n(* a block ;\n comment *) #2 := (#1 + 1) * 2;\n"),
            vec![
                "2: MacroHeader",
                "3: #[1] = 2",
                "5: #[2] = #1 1 Add 2 Multiply"
            ]
        );
        let unclosed = lines("%@MACRO\n#1 := 2;\n(* never closed\n#2 := 3;\n");
        assert_eq!(
            unclosed,
            vec![
                "1: MacroHeader",
                "2: #[1] = 2",
                "3: alarm 17: comment `(*` is not closed: the rest of the program is comment"
            ]
        );
    }

    #[test]
    fn an_alarm_in_a_long_statement_names_its_own_line() {
        let program = read("%@MACRO\n#1 := 1 +\n\n  ];\n");
        let alarm = &program.lines[1].as_slice()[0].alarms[0];
        assert_eq!(alarm.span.unwrap().line, 4);
    }

    #[test]
    fn only_a_first_line_header_makes_a_macro_program() {
        assert!(read("%@MACRO\nM30;\n").structure.is_some());
        assert!(read("\n// note\nO0100 (SUB)\n%@macro\nM99;\n")
            .structure
            .is_some());
        assert!(read("G0 X1.\n%@MACRO\nM30\n").structure.is_none());
        assert!(read("%@MACROS\nM30\n").structure.is_none());
        // The lines before the body stay ISO lines: `( )` is a comment there.
        assert_eq!(
            lines("O0100 (SUB)\n%@MACRO\nIF #1 = 0 THEN\n  #1 := 1;\nEND_IF;\nM99;\n"),
            vec![
                "1: O100",
                "2: MacroHeader",
                "3: if #1 0 Equal then",
                "4: #[1] = 1",
                "5: end_if",
                "6: M99"
            ]
        );
    }

    #[test]
    fn a_percent_line_ends_the_program_text() {
        assert_eq!(
            lines("%@MACRO\nG01 X1.;\n%\n"),
            vec!["1: MacroHeader", "2: G1 | X1", "3: TapeMark"]
        );
    }
}
