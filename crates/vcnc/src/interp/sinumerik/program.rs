//! The texts a SINUMERIK run reads: the main program and the subprograms it calls, each held
//! whole with the start of every line, so that a jump, a loop or a part repetition can go to any
//! block. Lines are found once, when a text is loaded; blocks are read where they run.
//!
//! Never: read a program's file twice, or load a subprogram before it is called.

use crate::source::{FileId, Span};
use std::sync::Arc;

/// One program's text and its lines.
pub(super) struct Program {
    /// The file its spans carry.
    pub(super) file: FileId,
    /// The program's name, upper case, without its extension (`L100`, `CHAMFER`; the main
    /// program's name is empty).
    pub(super) name: Box<str>,
    text: Arc<[u8]>,
    /// The byte offset of every line's start, and one past the text's end.
    starts: Vec<u32>,
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

impl Program {
    /// The program `text` of `file`, named `name`.
    pub(super) fn new(file: FileId, name: &str, text: Arc<[u8]>) -> Program {
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
        Program {
            file,
            name: name.to_ascii_uppercase().into(),
            text,
            starts,
        }
    }

    /// The number of lines.
    pub(super) fn lines(&self) -> usize {
        self.starts.len() - 1
    }

    /// Line `index` (0-based), without its line end; None past the last.
    pub(super) fn line(&self, index: usize) -> Option<Line<'_>> {
        let start = *self.starts.get(index)? as usize;
        let end = *self.starts.get(index + 1)? as usize;
        let mut bytes = &self.text[start..end];
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
}
