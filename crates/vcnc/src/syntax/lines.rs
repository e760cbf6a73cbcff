//! Program text, one line at a time.
//!
//! The interpreter streams: it reads a line, runs its blocks, and forgets it. A [`LineSource`]
//! hands out lines with their byte offset and line number, from text in memory
//! ([`TextLines`]) or from any reader ([`ReaderLines`]), so a program of any length runs in
//! constant memory. Line ends (`\n`, `\r\n`) are stripped; bytes are passed on as they are
//! (comments may be Latin-1).

use std::io::{self, BufRead};

/// One line of program text.
#[derive(Clone, Copy, Debug)]
pub struct Line<'a> {
    /// The bytes of the line without its line end.
    pub text: &'a [u8],
    /// Byte offset of the first byte in the file.
    pub offset: u32,
    /// 1-based line number.
    pub number: u32,
}

/// Something that hands out program lines in order.
pub trait LineSource {
    /// The next line, or `None` at the end of the text.
    ///
    /// # Errors
    /// Whatever the underlying reader reports.
    fn next_line(&mut self) -> io::Result<Option<Line<'_>>>;
}

/// Lines of a text held in memory.
#[derive(Clone, Debug)]
pub struct TextLines<'a> {
    text: &'a [u8],
    position: usize,
    number: u32,
}

impl<'a> TextLines<'a> {
    /// Lines of `text`.
    pub fn new(text: &'a [u8]) -> TextLines<'a> {
        TextLines { text, position: 0, number: 0 }
    }
}

impl LineSource for TextLines<'_> {
    fn next_line(&mut self) -> io::Result<Option<Line<'_>>> {
        if self.position >= self.text.len() {
            return Ok(None);
        }
        let start = self.position;
        let rest = &self.text[start..];
        let (line, advance) = match memchr_newline(rest) {
            Some(i) => (&rest[..i], i + 1),
            None => (rest, rest.len()),
        };
        self.position += advance;
        self.number += 1;
        let line = line.strip_suffix(b"\r").unwrap_or(line);
        Ok(Some(Line { text: line, offset: clamp_offset(start), number: self.number }))
    }
}

/// Lines read from a buffered reader, one buffer reused for every line.
#[derive(Debug)]
pub struct ReaderLines<R> {
    reader: R,
    buffer: Vec<u8>,
    offset: u64,
    number: u32,
}

impl<R: BufRead> ReaderLines<R> {
    /// Lines of `reader`.
    pub fn new(reader: R) -> ReaderLines<R> {
        ReaderLines { reader, buffer: Vec::with_capacity(256), offset: 0, number: 0 }
    }
}

impl<R: BufRead> LineSource for ReaderLines<R> {
    fn next_line(&mut self) -> io::Result<Option<Line<'_>>> {
        self.buffer.clear();
        let read = self.reader.read_until(b'\n', &mut self.buffer)?;
        if read == 0 {
            return Ok(None);
        }
        let start = self.offset;
        self.offset += read as u64;
        self.number += 1;
        let mut line = self.buffer.as_slice();
        line = line.strip_suffix(b"\n").unwrap_or(line);
        line = line.strip_suffix(b"\r").unwrap_or(line);
        Ok(Some(Line { text: line, offset: clamp_offset(start as usize), number: self.number }))
    }
}

fn memchr_newline(bytes: &[u8]) -> Option<usize> {
    bytes.iter().position(|&b| b == b'\n')
}

/// Offsets are kept in u32 (spans are small); past 4 GiB they saturate, which only blurs the
/// position shown in a diagnostic.
fn clamp_offset(offset: usize) -> u32 {
    u32::try_from(offset).unwrap_or(u32::MAX)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn collect(source: &mut dyn LineSource) -> Vec<(String, u32, u32)> {
        let mut lines = Vec::new();
        while let Some(line) = source.next_line().unwrap() {
            lines.push((String::from_utf8_lossy(line.text).into_owned(), line.offset, line.number));
        }
        lines
    }

    #[test]
    fn text_and_reader_lines_agree_on_crlf_and_missing_final_newline() {
        let text = b"G0 X1\r\nG1 Y2\n\nM30";
        let a = collect(&mut TextLines::new(text));
        let b = collect(&mut ReaderLines::new(&text[..]));
        assert_eq!(a, b);
        assert_eq!(a[1], ("G1 Y2".to_string(), 7, 2));
        assert_eq!(a[3], ("M30".to_string(), 14, 4));
    }
}
