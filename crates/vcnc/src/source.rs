//! Source files and positions in them.
//!
//! A [`Span`] names a byte range of one file and the 1-based line it starts on. Everything the
//! interpreter produces (segments, alarms) carries the span of the words it came from, so a
//! consumer can always point back at the program text. Columns are not stored: they are computed
//! from the line's text only when a diagnostic is rendered.

use std::fmt;

/// Identifies one file among those an interpreter reads (the main program and, later, subprograms).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
pub struct FileId(pub u32);

/// A byte range in one file, with the 1-based number of the line it starts on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Span {
    /// The file the range belongs to.
    pub file: FileId,
    /// 1-based line number of `start`.
    // Next to `file`: the words of a line share both, and a reader copies the two at once.
    pub line: u32,
    /// Byte offset of the first byte.
    pub start: u32,
    /// Byte offset one past the last byte.
    pub end: u32,
}

impl Span {
    /// The bytes `range` (start to one past the end) on `line` of `file`.
    pub fn new(file: FileId, line: u32, range: std::ops::Range<u32>) -> Span {
        Span {
            file,
            line,
            start: range.start,
            end: range.end,
        }
    }

    /// The smallest span covering `self` and `other` (which must be in the same file).
    pub fn to(self, other: Span) -> Span {
        Span {
            file: self.file,
            start: self.start.min(other.start),
            end: self.end.max(other.end),
            line: self.line.min(other.line),
        }
    }

    /// Length in bytes.
    pub fn len(&self) -> u32 {
        self.end.saturating_sub(self.start)
    }

    /// True when the span covers no byte.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

impl fmt::Display for Span {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}..{} (line {})", self.start, self.end, self.line)
    }
}

/// A 1-based line and column, as shown to people.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LineColumn {
    /// 1-based line number.
    pub line: u32,
    /// 1-based column, counted in characters of the line's text.
    pub column: u32,
}

/// True when byte `i` of `text` ends a line: a `\n`, or a `\r` not followed by one (old Mac
/// line ends, which the line readers take for line ends too).
fn ends_line(text: &[u8], i: usize) -> bool {
    match text[i] {
        b'\n' => true,
        b'\r' => text.get(i + 1) != Some(&b'\n'),
        _ => false,
    }
}

/// The 1-based line and column of byte `offset` in `text`.
///
/// Bytes that are not valid UTF-8 (Latin-1 comments) count as one column each; a byte-order mark
/// at the file's start counts as none.
pub fn line_column(text: &[u8], offset: u32) -> LineColumn {
    let offset = (offset as usize).min(text.len());
    let breaks = (0..offset).filter(|&i| ends_line(text, i));
    let (count, last) = breaks.fold((0u32, None), |(n, _), i| (n + 1, Some(i)));
    let line_start = last.map_or(0, |i| i + 1);
    let mut before = &text[line_start..offset];
    if line_start == 0 {
        before = before.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(before);
    }
    let column = before.iter().filter(|&&b| (b & 0xC0) != 0x80).count() as u32 + 1;
    LineColumn {
        line: count + 1,
        column,
    }
}

/// The text of the line containing byte `offset`, without its line end.
pub fn line_text(text: &[u8], offset: u32) -> &[u8] {
    let offset = (offset as usize).min(text.len());
    let start = (0..offset)
        .rev()
        .find(|&i| ends_line(text, i))
        .map_or(0, |i| i + 1);
    let end = (offset..text.len())
        .find(|&i| ends_line(text, i))
        .unwrap_or(text.len());
    let line = &text[start..end];
    let line = line.strip_suffix(b"\r").unwrap_or(line);
    if start == 0 {
        return line.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(line);
    }
    line
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_and_column_count_from_one() {
        let text = b"G0 X1\r\nG1 Y2\n";
        assert_eq!(line_column(text, 0), LineColumn { line: 1, column: 1 });
        assert_eq!(line_column(text, 10), LineColumn { line: 2, column: 4 });
        assert_eq!(line_text(text, 10), b"G1 Y2");
        assert_eq!(line_text(text, 2), b"G0 X1");
    }

    #[test]
    fn lone_carriage_returns_end_lines_and_a_byte_order_mark_takes_no_column() {
        let text = b"\xEF\xBB\xBFG0 X1\rG1 Y2\r\nM30";
        assert_eq!(line_column(text, 3), LineColumn { line: 1, column: 1 });
        assert_eq!(line_column(text, 12), LineColumn { line: 2, column: 4 });
        assert_eq!(line_column(text, 16), LineColumn { line: 3, column: 1 });
        assert_eq!(line_text(text, 12), b"G1 Y2");
        assert_eq!(line_text(text, 4), b"G0 X1");
    }
}
