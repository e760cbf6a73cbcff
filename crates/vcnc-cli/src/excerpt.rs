//! The lines of a program a diagnostic shows, made safe and small for a terminal: control
//! characters escaped (`\x1b`), a long line cut to a window around the alarm's column.
//!
//! A line is read from its file a few kilobytes around the alarm, never whole: a 50 MB line
//! costs a scan for its start (to count the column) and no more memory than the window.
//! Nothing here may hold or render a whole line or file.

use codespan_reporting::files::{Error as FilesError, Files};
use std::io::{self, Read, Seek, SeekFrom};
use std::ops::Range;
use vcnc::Span;

/// `text` with every control character but tab shown escaped (`\x1b`, `\u{85}`).
pub(crate) fn escape(text: &str) -> String {
    if !text.chars().any(needs_escape) {
        return text.to_string();
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        push_char(&mut out, c);
    }
    out
}

fn needs_escape(c: char) -> bool {
    c != '\t' && c.is_control()
}

fn push_char(out: &mut String, c: char) {
    if !needs_escape(c) {
        out.push(c);
    } else if (c as u32) < 0x80 {
        out.push_str(&format!("\\x{:02x}", c as u32));
    } else {
        out.push_str(&format!("\\u{{{:x}}}", c as u32));
    }
}

/// How far around an alarm's start a file is read, in bytes.
const REACH: u64 = 4096;
/// A line up to this many bytes is shown whole; a longer one as a window: about [`CONTEXT`]
/// bytes before and after the words an alarm points at, and at most [`WORDS`] of the words.
const WHOLE_LINE: usize = 240;
const CONTEXT: usize = 80;
const WORDS: usize = 160;

/// The bytes of a file around an alarm's start, and where its line begins and ends in them.
pub(crate) struct Region {
    bytes: Vec<u8>,
    /// Where `bytes` start in the file.
    at: u64,
    /// The span's start, in `bytes`.
    start: usize,
    /// The line's first byte in `bytes`, or `None` when the line begins before them; then
    /// `columns_before` counts its characters before them.
    first: Option<usize>,
    columns_before: usize,
    /// The line's end (before `\r\n` or `\n`) in `bytes`, or `None` when it goes on after them.
    last: Option<usize>,
}

impl Region {
    /// The region of a file that cannot be read any more: an empty line.
    pub(crate) fn empty() -> Region {
        Region {
            bytes: Vec::new(),
            at: 0,
            start: 0,
            first: Some(0),
            columns_before: 0,
            last: Some(0),
        }
    }

    /// The region of `file` around byte `offset`.
    pub(crate) fn read(file: &mut (impl Read + Seek), offset: u32) -> io::Result<Region> {
        let len = file.seek(SeekFrom::End(0))?;
        let start = u64::from(offset).min(len);
        let at = start.saturating_sub(REACH);
        let mut bytes = Vec::new();
        file.seek(SeekFrom::Start(at))?;
        file.by_ref()
            .take((start + REACH).min(len) - at)
            .read_to_end(&mut bytes)?;
        // Lines end as the interpreter reads them: old Mac `\r`s too, a byte-order mark blank.
        vcnc::syntax::lines::normalize(&mut bytes, at == 0);
        let start = ((start - at) as usize).min(bytes.len());
        let first = match bytes[..start].iter().rposition(|&b| b == b'\n') {
            Some(i) => Some(i + 1),
            None if at == 0 => Some(0),
            None => None,
        };
        let columns_before = match first {
            Some(_) => 0,
            None => columns_back_to_line_start(file, at)?,
        };
        let last = bytes[start..]
            .iter()
            .position(|&b| b == b'\n')
            .map(|i| start + i)
            .or((at + bytes.len() as u64 == len).then_some(bytes.len()))
            .map(|end| {
                if end > start && bytes[end - 1] == b'\r' {
                    end - 1
                } else {
                    end
                }
            });
        Ok(Region {
            bytes,
            at,
            start,
            first,
            columns_before,
            last,
        })
    }

    /// The 1-based column of the span's start, in characters (a byte that is not UTF-8
    /// counts as one).
    pub(crate) fn column(&self) -> u32 {
        self.column_at(self.start) as u32
    }

    /// The 1-based column of byte `at` of the region.
    fn column_at(&self, at: usize) -> usize {
        let first = self.first.unwrap_or(0);
        self.columns_before + characters(&self.bytes[first..at.max(first)]) + 1
    }
}

fn characters(bytes: &[u8]) -> usize {
    bytes.iter().filter(|&&b| (b & 0xC0) != 0x80).count()
}

/// The characters between the start of the line and byte `at` of `file`, read back in chunks.
fn columns_back_to_line_start(file: &mut (impl Read + Seek), mut at: u64) -> io::Result<usize> {
    let mut chunk = vec![0; 1 << 16];
    let mut columns = 0;
    while at > 0 {
        let size = (chunk.len() as u64).min(at);
        at -= size;
        file.seek(SeekFrom::Start(at))?;
        let chunk = &mut chunk[..size as usize];
        file.read_exact(chunk)?;
        match chunk.iter().rposition(|&b| b == b'\n') {
            Some(i) => return Ok(columns + characters(&chunk[i + 1..])),
            None => columns += characters(chunk),
        }
    }
    Ok(columns)
}

/// The lines one diagnostic shows, each cut to a window and escaped, as codespan's files.
#[derive(Default)]
pub(crate) struct Excerpts {
    files: Vec<Excerpt>,
}

/// The lines of one file that a diagnostic shows.
struct Excerpt {
    name: String,
    source: String,
    lines: Vec<ExcerptLine>,
}

/// One line of an excerpt: where it is in the excerpt's source, its number in the file, and
/// for each character shown (an escaped character shows as several) its column and offset in
/// the file, then the end's.
struct ExcerptLine {
    range: Range<usize>,
    number: usize,
    columns: Vec<Shown>,
}

/// A character shown: where in the excerpt, its column and its offset in the file.
#[derive(Clone, Copy)]
struct Shown {
    at: usize,
    column: usize,
    offset: u64,
}

impl Excerpts {
    /// Adds a file named `name` (escaped already); returns its id.
    pub(crate) fn add_file(&mut self, name: String) -> usize {
        self.files.push(Excerpt {
            name,
            source: String::new(),
            lines: Vec::new(),
        });
        self.files.len() - 1
    }

    /// Adds to file `id` the window of `region` around `span` (which starts on line
    /// `span.line`), and returns the span's range in the file's excerpt. A span that goes on
    /// past its line's end is cut there.
    pub(crate) fn add_line(&mut self, id: usize, region: &Region, span: Span) -> Range<usize> {
        self.files[id].add(region, span)
    }
}

impl Excerpt {
    fn add(&mut self, region: &Region, span: Span) -> Range<usize> {
        if let Some(range) = self.on_a_line_shown(span) {
            return range;
        }
        let bytes = &region.bytes;
        let start = region.start;
        let first = region.first.unwrap_or(0);
        let last = region.last.unwrap_or(bytes.len()).max(start);
        let end = (start + span.len() as usize).clamp(start, last);
        // The window in bytes, not characters: a few characters fewer on UTF-8 text is no loss.
        let whole = region.first.is_some() && region.last.is_some() && last - first <= WHOLE_LINE;
        let (from, to) = if whole {
            (first, last)
        } else {
            (
                char_boundary(bytes, start.saturating_sub(CONTEXT).max(first)),
                char_boundary(bytes, (end.min(start + WORDS) + CONTEXT).min(last)),
            )
        };
        let end = end.min(to);
        let line_begin = self.source.len();
        if from > first || region.first.is_none() {
            self.source.push('…');
        }
        let mut column = region.column_at(from);
        let mut columns = Vec::new();
        let (mut range_start, mut range_end) = (None, None);
        let mut at = from;
        while at < to {
            if at >= start && range_start.is_none() {
                range_start = Some(self.source.len());
            }
            if at >= end && range_end.is_none() {
                range_end = Some(self.source.len());
            }
            let (c, len) = decode(&bytes[at..to]);
            columns.push(Shown {
                at: self.source.len(),
                column,
                offset: region.at + at as u64,
            });
            push_char(&mut self.source, c);
            column += 1;
            at += len;
        }
        let range_start = range_start.unwrap_or(self.source.len());
        let range_end = range_end.unwrap_or(self.source.len()).max(range_start);
        if to < last || region.last.is_none() {
            self.source.push('…');
        }
        columns.push(Shown {
            at: self.source.len(),
            column,
            offset: region.at + to as u64,
        });
        self.lines.push(ExcerptLine {
            range: line_begin..self.source.len(),
            number: span.line as usize,
            columns,
        });
        self.source.push('\n');
        range_start..range_end
    }

    /// The range of `span` in a line shown already (a second label on a line), when the line's
    /// window holds its start.
    fn on_a_line_shown(&self, span: Span) -> Option<Range<usize>> {
        let (start, end) = (u64::from(span.start), u64::from(span.end));
        let line = self.lines.iter().find(|line| {
            let (first, last) = (line.columns[0].offset, line.columns[line.columns.len() - 1]);
            line.number == span.line as usize && first <= start && start < last.offset
        })?;
        let at = |offset: u64| {
            line.columns
                .iter()
                .find(|shown| shown.offset >= offset)
                .or(line.columns.last())
                .map_or(0, |shown| shown.at)
        };
        Some(at(start)..at(end).max(at(start)))
    }

    fn line(&self, byte: usize) -> usize {
        self.lines
            .iter()
            .rposition(|l| l.range.start <= byte)
            .unwrap_or(0)
    }
}

/// `at` moved back to the start of the character it is in.
fn char_boundary(bytes: &[u8], mut at: usize) -> usize {
    let floor = at.saturating_sub(3);
    while at > floor && at < bytes.len() && (bytes[at] & 0xC0) == 0x80 {
        at -= 1;
    }
    at
}

/// The first character of `bytes` and its length; a byte that is not UTF-8 is `?`.
fn decode(bytes: &[u8]) -> (char, usize) {
    let len = match bytes[0] {
        b if b < 0x80 => 1,
        b if b >= 0xF0 => 4,
        b if b >= 0xE0 => 3,
        b if b >= 0xC0 => 2,
        _ => 1,
    }
    .min(bytes.len());
    match std::str::from_utf8(&bytes[..len]) {
        Ok(s) => (s.chars().next().unwrap_or('?'), len),
        Err(_) => ('?', 1),
    }
}

impl<'a> Files<'a> for Excerpts {
    type FileId = usize;
    type Name = &'a str;
    type Source = &'a str;

    fn name(&'a self, id: usize) -> Result<&'a str, FilesError> {
        Ok(&self.get(id)?.name)
    }

    fn source(&'a self, id: usize) -> Result<&'a str, FilesError> {
        Ok(&self.get(id)?.source)
    }

    fn line_index(&'a self, id: usize, byte_index: usize) -> Result<usize, FilesError> {
        Ok(self.get(id)?.line(byte_index))
    }

    fn line_number(&'a self, id: usize, line_index: usize) -> Result<usize, FilesError> {
        Ok(self.excerpt_line(id, line_index)?.number)
    }

    fn column_number(
        &'a self,
        id: usize,
        line_index: usize,
        byte_index: usize,
    ) -> Result<usize, FilesError> {
        let line = self.excerpt_line(id, line_index)?;
        Ok(line
            .columns
            .iter()
            .rev()
            .find(|shown| shown.at <= byte_index)
            .map_or(1, |shown| shown.column))
    }

    fn line_range(&'a self, id: usize, line_index: usize) -> Result<Range<usize>, FilesError> {
        let excerpt = self.get(id)?;
        match excerpt.lines.get(line_index) {
            Some(line) => Ok(line.range.start..line.range.end + 1),
            // codespan asks for the line after the last one; it is empty.
            None => Ok(excerpt.source.len()..excerpt.source.len()),
        }
    }
}

impl Excerpts {
    fn get(&self, id: usize) -> Result<&Excerpt, FilesError> {
        self.files.get(id).ok_or(FilesError::FileMissing)
    }

    fn excerpt_line(&self, id: usize, line_index: usize) -> Result<&ExcerptLine, FilesError> {
        let excerpt = self.get(id)?;
        excerpt
            .lines
            .get(line_index)
            .or(excerpt.lines.last())
            .ok_or(FilesError::LineTooLarge {
                given: line_index,
                max: excerpt.lines.len(),
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use vcnc::FileId;

    /// The excerpt of `span` in `text`, its range, and the column of the range's start.
    fn excerpt_of(text: &[u8], span: Span) -> (String, Range<usize>, usize) {
        let region = Region::read(&mut io::Cursor::new(text), span.start).unwrap();
        let mut excerpts = Excerpts::default();
        let id = excerpts.add_file(String::new());
        let range = excerpts.add_line(id, &region, span);
        let column = excerpts.column_number(id, 0, range.start).unwrap();
        assert_eq!(column, region.column() as usize);
        (excerpts.files[id].source.clone(), range, column)
    }

    #[test]
    fn control_bytes_are_shown_escaped() {
        assert_eq!(
            escape("a\u{1b}[2Jb\0\tc\u{85}"),
            "a\\x1b[2Jb\\x00\tc\\u{85}"
        );
        let text = b"G0\nG1 X\x1b[31m1.\r\n";
        let (source, range, column) = excerpt_of(text, Span::new(FileId(0), 2, 7..8));
        assert_eq!(source, "G1 X\\x1b[31m1.\n");
        assert_eq!(&source[range], "\\x1b");
        assert_eq!(column, 5);
    }

    #[test]
    fn a_long_line_is_shown_as_a_window_around_the_words() {
        let mut text = "é".repeat(500_000).into_bytes();
        text[500_000..500_003].copy_from_slice(b"G99");
        let (source, range, column) = excerpt_of(&text, Span::new(FileId(0), 1, 500_000..500_003));
        assert!(source.len() < 400, "{} bytes", source.len());
        assert_eq!(&source[range], "G99");
        assert!(
            source.starts_with('…') && source.ends_with("…\n"),
            "{source}"
        );
        assert_eq!(column, 250_001);
    }

    #[test]
    fn two_labels_on_one_line_share_it() {
        let text = b"S600 M03 M08;\n";
        let mut excerpts = Excerpts::default();
        let id = excerpts.add_file(String::new());
        let mut add = |range: Range<u32>| {
            let span = Span::new(FileId(0), 1, range.clone());
            let region = Region::read(&mut io::Cursor::new(text), range.start).unwrap();
            excerpts.add_line(id, &region, span)
        };
        assert_eq!((add(5..8), add(9..12)), (5..8, 9..12));
        assert_eq!(excerpts.files[id].source, "S600 M03 M08;\n");
    }

    #[test]
    fn a_short_line_is_shown_whole() {
        let text = b"G0 X1.\nG1 X2. (a comment that goes on for a while)\nM30\n";
        let (source, range, column) = excerpt_of(text, Span::new(FileId(0), 2, 7..9));
        assert_eq!(source, "G1 X2. (a comment that goes on for a while)\n");
        assert_eq!(&source[range], "G1");
        assert_eq!(column, 1);
    }
}
