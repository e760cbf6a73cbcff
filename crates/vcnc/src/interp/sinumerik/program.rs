//! The texts a SINUMERIK run reads: the main program and the subprograms it calls.
//!
//! A main program read from its file streams: its lines are read from the file as they run and
//! forgotten, so a program of any length runs in the same memory. Only a program that goes
//! anywhere but to its next line (a jump, a loop, a control structure, a part repetition) needs
//! its lines again: the front end then asks for its whole text (read again from the file, as
//! the ISO front end does for its jumps) and the program is held whole from there on, with the
//! start of every line. Subprograms and texts given in memory are held whole from the start.
//!
//! A streamed main program is read and parsed on the interpreter's thread as it runs, or on a
//! thread of its own a few hundred lines ahead ([`BackgroundParser`](crate::syntax::blocks::BackgroundParser)): each line then comes
//! with its block, which [`Program::take_line`] hands over.
//!
//! Never: read a program's file twice unless it jumps, or load a subprogram before it is
//! called.

use crate::source::{FileId, Span};
use crate::syntax::blocks::{BlockSource, ProgramLines};
use crate::syntax::sinumerik::{Block, SinumerikParser};
use std::io::{self, Read};
use std::sync::Arc;

/// One program's text and its lines.
pub(super) struct Program {
    /// The file its spans carry.
    pub(super) file: FileId,
    /// The program's name, upper case, without its extension (`L100`, `CHAMFER`; the main
    /// program's name is empty).
    pub(super) name: Box<str>,
    text: Text,
}

/// Where a program's lines are.
enum Text {
    /// The whole text, and the byte offset of every line's start and one past the text's end.
    Whole { text: Arc<[u8]>, starts: Vec<u32> },
    /// Read line by line; only the line read last is at hand.
    Streamed(Box<Streamed>),
}

/// A text read line by line.
struct Streamed {
    lines: ProgramLines<SinumerikParser>,
    /// The line read last (0-based; `None` before the first).
    index: Option<usize>,
    /// The reader came to its end after line `index`.
    ended: bool,
}

/// One line of a program: where it is, and its bytes (without the line end).
#[derive(Clone, Copy)]
pub(super) struct Line<'a> {
    /// 1-based line number.
    pub(super) number: u32,
    /// The byte offset of its start in the file.
    pub(super) base: u32,
    pub(super) bytes: &'a [u8],
}

/// What [`Program::fetch`] found.
#[derive(Debug, PartialEq, Eq)]
pub(super) enum Fetched {
    /// The line is at hand for [`Program::line`] (or the text ends before it).
    Ready,
    /// The line is not the next one of a streamed text: the whole text is needed.
    NeedsWhole,
}

impl Program {
    /// The program `text` of `file`, named `name`.
    pub(super) fn new(file: FileId, name: &str, text: Arc<[u8]>) -> Program {
        Program {
            file,
            name: name.to_ascii_uppercase().into(),
            text: whole(text),
        }
    }

    /// The main program of `file`, read from `reader` line by line as it runs; parsed on a
    /// thread of its own, ahead of the interpreter, when `ahead` says how many bytes it holds
    /// (about; 0 when unknown).
    pub(super) fn streamed(
        file: FileId,
        reader: Box<dyn Read + Send>,
        ahead: Option<u64>,
    ) -> Program {
        let lines = ProgramLines::new(reader, SinumerikParser::new(file), ahead);
        Program {
            file,
            name: "".into(),
            text: Text::Streamed(Box::new(Streamed {
                lines,
                index: None,
                ended: false,
            })),
        }
    }

    /// True when the whole text is at hand (any line can be had).
    pub(super) fn is_whole(&self) -> bool {
        matches!(self.text, Text::Whole { .. })
    }

    /// The whole `text` of a streamed program, from now on.
    pub(super) fn make_whole(&mut self, text: Arc<[u8]>) {
        self.text = whole(text);
    }

    /// Makes line `index` (0-based) at hand: a streamed text reads its next line; any other line
    /// of a streamed text needs the whole text.
    ///
    /// # Errors
    /// The reader's.
    pub(super) fn fetch(&mut self, index: usize) -> io::Result<Fetched> {
        let Text::Streamed(stream) = &mut self.text else {
            return Ok(Fetched::Ready);
        };
        let next = stream.index.map_or(0, |i| i + 1);
        if stream.index == Some(index) || (stream.ended && index == next) {
            return Ok(Fetched::Ready);
        }
        if index != next {
            return Ok(Fetched::NeedsWhole);
        }
        match stream.lines.advance()? {
            true => stream.index = Some(index),
            false => stream.ended = true,
        }
        Ok(Fetched::Ready)
    }

    /// Line `index` (at hand: [`Program::fetch`]), as [`Program::line`] gives it, with its block
    /// in `block` when it was parsed ahead (true; `block`'s room goes to the line).
    pub(super) fn take_line(
        &mut self,
        index: usize,
        block: &mut Box<Block>,
    ) -> Option<(Line<'_>, bool)> {
        let streamed = matches!(&self.text, Text::Streamed(s) if s.index == Some(index));
        if !streamed {
            return Some((self.line(index)?, false));
        }
        let Text::Streamed(stream) = &mut self.text else {
            return None;
        };
        let line = stream.lines.line_mut()?;
        std::mem::swap(&mut line.block, block);
        let line = Line {
            number: index as u32 + 1,
            base: line.base,
            bytes: &line.text,
        };
        Some((line, true))
    }

    /// The number of lines (of a streamed text: the lines read so far).
    pub(super) fn lines(&self) -> usize {
        match &self.text {
            Text::Whole { starts, .. } => starts.len() - 1,
            Text::Streamed(stream) => stream.index.map_or(0, |i| i + 1),
        }
    }

    /// Line `index` (0-based), without its line end; None past the last (and, for a streamed
    /// text, for any line but the one [`Program::fetch`] read last).
    pub(super) fn line(&self, index: usize) -> Option<Line<'_>> {
        let (text, starts) = match &self.text {
            Text::Whole { text, starts } => (text, starts),
            Text::Streamed(stream) if stream.index == Some(index) => {
                let line = stream.lines.line()?;
                return Some(Line {
                    number: index as u32 + 1,
                    base: line.base,
                    bytes: &line.text,
                });
            }
            Text::Streamed(_) => return None,
        };
        let start = *starts.get(index)? as usize;
        let end = *starts.get(index + 1)? as usize;
        let mut bytes = &text[start..end];
        while let [rest @ .., b'\n' | b'\r'] = bytes {
            bytes = rest;
        }
        Some(Line {
            number: index as u32 + 1,
            base: start as u32,
            bytes,
        })
    }

    /// The span of line `index`'s text.
    pub(super) fn line_span(&self, index: usize) -> Span {
        match self.line(index) {
            Some(line) => Span::new(
                self.file,
                line.number,
                line.base..line.base + line.bytes.len() as u32,
            ),
            None => Span::new(self.file, index as u32 + 1, 0..0),
        }
    }
}

/// `text` held whole, with its lines found.
fn whole(text: Arc<[u8]>) -> Text {
    let mut starts = Vec::with_capacity(text.len() / 24 + 2);
    starts.push(0);
    starts.extend(
        text.iter()
            .enumerate()
            .filter(|&(_, &b)| b == b'\n')
            .map(|(i, _)| i as u32 + 1),
    );
    if starts.last() != Some(&(text.len() as u32)) {
        starts.push(text.len() as u32);
    }
    Text::Whole { text, starts }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_are_found_without_their_ends() {
        let program = Program::new(FileId(0), "main", Arc::from(&b"G0 X1\r\n\nG1 X2"[..]));
        assert_eq!(program.lines(), 3);
        assert_eq!(program.line(0).unwrap().bytes, b"G0 X1");
        assert_eq!(program.line(1).unwrap().bytes, b"");
        let last = program.line(2).unwrap();
        assert_eq!((last.number, last.base, last.bytes), (3, 8, &b"G1 X2"[..]));
        assert!(program.line(3).is_none());
    }

    #[test]
    fn a_streamed_text_reads_its_lines_in_order_with_their_offsets() {
        let text = b"G0 X1\r\n\nG1 X2";
        let mut program = Program::streamed(FileId(0), Box::new(io::Cursor::new(&text[..])), None);
        assert!(!program.is_whole());
        let mut seen = Vec::new();
        for index in 0.. {
            assert_eq!(program.fetch(index).unwrap(), Fetched::Ready);
            let Some(line) = program.line(index) else {
                break;
            };
            seen.push((line.number, line.base, line.bytes.to_vec()));
            // The same line again is still at hand; a line before it is not.
            assert_eq!(program.fetch(index).unwrap(), Fetched::Ready);
            if index > 0 {
                assert_eq!(program.fetch(index - 1).unwrap(), Fetched::NeedsWhole);
            }
        }
        // The same lines and offsets as the text held whole (line 3 starts at byte 8).
        let whole = Program::new(FileId(0), "", Arc::from(&text[..]));
        let expected: Vec<_> = (0..whole.lines())
            .map(|i| whole.line(i).unwrap())
            .map(|l| (l.number, l.base, l.bytes.to_vec()))
            .collect();
        assert_eq!(seen, expected);
        assert_eq!(program.line_span(2), whole.line_span(2));
        // Past the end: a line two ahead is not the next one.
        assert_eq!(program.fetch(5).unwrap(), Fetched::NeedsWhole);
        program.make_whole(Arc::from(&text[..]));
        assert!(program.is_whole());
        assert_eq!(program.line(0).unwrap().bytes, b"G0 X1");
    }

    /// Every line of `program` as its place, its text and its block (taken where the line
    /// came with one, parsed from its text where not).
    fn read_all(mut program: Program) -> Vec<(u32, u32, Vec<u8>, Box<Block>)> {
        let mut lines = Vec::new();
        for index in 0.. {
            assert_eq!(program.fetch(index).unwrap(), Fetched::Ready);
            let mut block = Box::<Block>::default();
            let Some((line, parsed)) = program.take_line(index, &mut block) else {
                break;
            };
            let (number, base, bytes) = (line.number, line.base, line.bytes.to_vec());
            if crate::syntax::sinumerik::is_header(&bytes) {
                // A header is no block: nothing to compare.
                block = Box::default();
            } else if !parsed {
                // As the interpreter reads a line (plain ones kept decoded).
                crate::syntax::sinumerik::parse_line_into(
                    &bytes,
                    FileId(0),
                    number,
                    base,
                    &mut block,
                );
            }
            lines.push((number, base, bytes, block));
        }
        lines
    }

    #[test]
    fn lines_parsed_ahead_are_the_lines_read_in_line_and_held_whole() {
        let mut text = String::from("%_N_PART_MPF\r\nDEF REAL F1=2\n\n");
        for i in 0..3000 {
            text.push_str(&format!("N{i} G1 X{i}.5 Y-{i} CR=-1.5 F=F1 ; c\r\n"));
        }
        text.push_str("/1 X1 Y\nIF R1==1 GOTOF A\nM30");
        let bytes = text.into_bytes();
        let reader = || -> Box<dyn Read + Send> { Box::new(io::Cursor::new(bytes.clone())) };
        let whole = read_all(Program::new(FileId(0), "", Arc::from(&bytes[..])));
        assert_eq!(whole.len(), 3006);
        for ahead in [None, Some(0), Some(bytes.len() as u64), Some(1 << 30)] {
            let streamed = read_all(Program::streamed(FileId(0), reader(), ahead));
            assert!(streamed == whole, "parsed ahead: {ahead:?}");
        }
    }
}
