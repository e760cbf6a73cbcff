//! A SINUMERIK program's lines read and parsed as they come: the [`LineParser`] that
//! [`BackgroundParser`](crate::syntax::blocks::BackgroundParser) runs on a thread of its own, a
//! few hundred lines ahead of the interpreter (the SINUMERIK front end reads and parses a block
//! in about as many instructions as it runs it: on a second core the two overlap).
//!
//! Each line keeps its text and place beside its block, so that the interpreter sees exactly
//! what it would have read itself. Never: skip or join lines (line numbers are the program's).

use super::block::{parse_line_into, Block};
use crate::source::FileId;
use crate::syntax::blocks::LineParser;
use crate::syntax::lines::LineSource;
use std::io;

/// One line of a SINUMERIK program, read and parsed.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ParsedLine {
    /// 1-based line number.
    pub number: u32,
    /// The byte offset of its start in the file.
    pub base: u32,
    /// Its text, without the line end.
    pub text: Vec<u8>,
    /// Its block; empty for a `%_N_..._MPF` header line, which is no block. Boxed, so that
    /// handing it over moves a pointer, not the block.
    pub block: Box<Block>,
}

/// Reads the lines of a SINUMERIK program file into [`ParsedLine`]s.
#[derive(Clone, Copy, Debug)]
pub struct SinumerikParser {
    file: FileId,
    /// Lines read so far.
    read: u32,
}

impl SinumerikParser {
    /// The lines of file `file`, from its first.
    pub fn new(file: FileId) -> SinumerikParser {
        SinumerikParser { file, read: 0 }
    }
}

/// True when the line is a `%_N_PART_MPF` header (or `%` alone): it names the file for the
/// control's file system and is no block (docs/SINUMERIK.md 2.1).
pub fn is_header(text: &[u8]) -> bool {
    text.trim_ascii_start().starts_with(b"%")
}

impl LineParser for SinumerikParser {
    type Line = ParsedLine;

    // A parsed line is about 500 bytes with its words: a quarter of the ISO front end's batch
    // keeps the pool at about 2 MB, and a hand-over every 256 lines costs nothing measurable.
    const BATCH: usize = 256;

    fn empty_line(&self) -> ParsedLine {
        ParsedLine {
            text: Vec::with_capacity(48),
            block: Box::new(Block {
                // A CAM line has up to about eight words.
                words: Vec::with_capacity(8),
                ..Block::default()
            }),
            ..ParsedLine::default()
        }
    }

    fn read_line<L: LineSource>(
        &mut self,
        lines: &mut L,
        out: &mut ParsedLine,
    ) -> io::Result<bool> {
        // At the end, the last line stays in `out`, at hand as it was.
        let Some(line) = lines.next_line()? else {
            return Ok(false);
        };
        self.read += 1;
        out.number = self.read;
        out.base = line.offset;
        out.text.clear();
        out.text.extend_from_slice(line.text);
        if is_header(&out.text) {
            parse_line_into(b"", self.file, out.number, out.base, &mut out.block);
        } else {
            parse_line_into(&out.text, self.file, out.number, out.base, &mut out.block);
        }
        Ok(true)
    }
}
