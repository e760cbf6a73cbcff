//! Program text, one line at a time.
//!
//! The interpreter streams: it reads a line, runs its blocks, and forgets it. A [`LineSource`]
//! hands out lines with their byte offset and line number, from text in memory
//! ([`TextLines`]) or from any reader ([`ReaderLines`]), so a program of any length runs in
//! constant memory. Line ends (`\n`, `\r\n`, and a lone `\r` as old Mac editors wrote) are
//! stripped; bytes are passed on as they are (comments may be Latin-1), but for the two that
//! [`normalize`] rewrites in place without moving any other byte: a UTF-8 byte-order mark at the
//! file's start and a lone `\r`. A reader that finds a line's end itself as it reads the line (the
//! ISO front end's reader of plain lines) takes the text at hand instead
//! ([`LineSource::unread`]) and then skips the line ([`LineSource::skip_line`]).

use std::borrow::Cow;
use std::io::{self, Read};

/// The UTF-8 byte-order mark some editors put at a file's start.
const BYTE_ORDER_MARK: &[u8] = b"\xEF\xBB\xBF";

/// Rewrites the two things that make the same program read differently by the editor that
/// saved it, keeping every byte where it is (spans stay file offsets): a UTF-8 byte-order mark
/// at the file's start becomes three blanks, and a `\r` not followed by `\n` (old Mac line
/// ends) becomes `\n`. `starts_file`: `bytes[0]` is the file's first byte. A `\r` at the end
/// of `bytes` is taken for a line end: nothing follows it.
pub fn normalize(bytes: &mut [u8], starts_file: bool) {
    if starts_file && bytes.starts_with(BYTE_ORDER_MARK) {
        bytes[..3].fill(b' ');
    }
    let mut from = 0;
    while let Some(i) = find_carriage_return(&bytes[from..]) {
        let at = from + i;
        if bytes.get(at + 1) != Some(&b'\n') {
            bytes[at] = b'\n';
        }
        from = at + 1;
    }
}

/// The first `\r` in `bytes`. A text with `\n` line ends has none: it is searched 32 bytes at a
/// step, four words tested at once for a byte equal to `\r` ([`find_byte`]'s test, without a
/// branch per word), and the step that has one searched again for where it is. Every buffer a
/// reader reads is searched: this is about two thirds of [`find_byte`]'s instructions.
fn find_carriage_return(bytes: &[u8]) -> Option<usize> {
    let mut steps = bytes.chunks_exact(32);
    let mut base = 0;
    for step in steps.by_ref() {
        let found = step
            .chunks_exact(8)
            .map(|word| has_byte(word, b'\r'))
            .fold(0, |found, word| found | word);
        if found != 0 {
            return find_byte(step, b'\r').map(|i| base + i);
        }
        base += 32;
    }
    find_byte(steps.remainder(), b'\r').map(|i| base + i)
}

/// Nonzero when the eight bytes `word` hold `byte` (the has-zero-byte test after an XOR), with
/// the high bit of the first such byte set.
#[inline(always)]
fn has_byte(word: &[u8], byte: u8) -> u64 {
    const ONES: u64 = 0x0101_0101_0101_0101;
    const HIGHS: u64 = 0x8080_8080_8080_8080;
    let word = u64::from_le_bytes(word.try_into().expect("chunks_exact gives 8 bytes"))
        ^ (ONES * u64::from(byte));
    word.wrapping_sub(ONES) & !word & HIGHS
}

/// True when [`normalize`] would change `bytes`.
pub fn needs_normalizing(bytes: &[u8], starts_file: bool) -> bool {
    if starts_file && bytes.starts_with(BYTE_ORDER_MARK) {
        return true;
    }
    let mut from = 0;
    while let Some(i) = find_byte(&bytes[from..], b'\r') {
        let at = from + i;
        if bytes.get(at + 1) != Some(&b'\n') {
            return true;
        }
        from = at + 1;
    }
    false
}

/// [`normalize`] for a buffer that is read in pieces: `buffer[from..to]` was just read, and
/// `buffer[0]` is at byte `offset` of the file. A `\r` at the end of what was read before is
/// looked at again now that what follows it is known; one at `to - 1` is left for the next read
/// (at the text's end, a line reader strips it as the `\r` of a line end).
pub(crate) fn normalize_read(buffer: &mut [u8], from: usize, to: usize, offset: u64) {
    let start = from.saturating_sub(1);
    let end = if buffer[..to].ends_with(b"\r") {
        to - 1
    } else {
        to
    };
    if end > start {
        // A `\r` at `end - 1` is followed by the `\r` at `end` or by nothing read: lone either way.
        normalize(&mut buffer[start..end], false);
    }
    if offset == 0 && from < BYTE_ORDER_MARK.len() && buffer[..to].starts_with(BYTE_ORDER_MARK) {
        buffer[..3].fill(b' ');
    }
}

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

/// The text at hand not yet handed out, for a reader that finds the end of a line itself (see
/// [`LineSource::unread`]).
#[derive(Clone, Copy, Debug)]
pub struct Unread<'a> {
    /// From the start of the next line to wherever the text at hand ends, which may be inside
    /// that line or several lines further, line ends included.
    pub text: &'a [u8],
    /// The byte offset in the file one past the last byte of `text`: every offset in `text` fits
    /// in u32, and is `end_offset` less the length of the text from it on.
    pub end_offset: u32,
    /// The 1-based number of the line `text` starts with.
    pub number: u32,
}

impl Unread<'_> {
    /// The byte offset in the file of the first byte of `text`.
    pub fn offset(&self) -> u32 {
        // `text` ends at `end_offset`: its length is at most that.
        self.end_offset - self.text.len() as u32
    }
}

/// Something that hands out program lines in order.
pub trait LineSource {
    /// The next line, or `None` at the end of the text.
    ///
    /// # Errors
    /// Whatever the underlying reader reports.
    fn next_line(&mut self) -> io::Result<Option<Line<'_>>>;

    /// The whole program text, when it is in memory: jumps (GOTO, WHILE) and subprograms that
    /// follow M30 in the same file need it. `None` for streamed text.
    fn text(&self) -> Option<&[u8]> {
        None
    }

    /// The text not yet handed out, as far as it is at hand: from the start of the next line to
    /// wherever the text at hand ends, which may be inside that line or several lines further,
    /// line ends included. A reader that finds the end of the line itself reads it from here,
    /// then calls [`LineSource::skip_line`]. `None` when nothing is at hand, or when the text at
    /// hand ends past 4 GiB (where offsets no longer fit in a span).
    fn unread(&self) -> Option<Unread<'_>> {
        None
    }

    /// Moves past the next line, which [`LineSource::unread`]'s text holds, its `\n` included,
    /// followed by `after` more bytes: it will not be handed out. (Counted from the end of the
    /// text, the reader of the line need not keep the length of the text through the line.)
    fn skip_line(&mut self, after: usize) {
        let _ = after;
    }
}

/// Lines of a text held in memory: borrowed as it is, or copied once and [`normalize`]d when it
/// has a byte-order mark or lone `\r` line ends. The text is searched for a lone `\r` a chunk
/// ahead of the reading, not all at once first: a separate pass over a large text read it from
/// memory twice (an eighth of the time of interpreting it).
#[derive(Clone, Debug)]
pub struct TextLines<'a> {
    text: Cow<'a, [u8]>,
    /// The file offset of `text[0]`: zero unless the text is a piece of a file read apart.
    base: usize,
    position: usize,
    number: u32,
    /// `text[..checked]` has no lone `\r` (or the text is normalized whole).
    checked: usize,
}

/// How far ahead of the reading position [`TextLines`] has looked for a lone `\r`: more than the
/// longest line the fast reader takes from the text at hand (which gives up on a longer one).
const CHECKED_AHEAD: usize = 4096;

/// How much [`TextLines`] searches at a time.
const CHECK_CHUNK: usize = 1 << 16;

impl<'a> TextLines<'a> {
    /// Lines of `text`.
    pub fn new(text: &'a [u8]) -> TextLines<'a> {
        TextLines::piece(text, 0, 1)
    }

    /// Lines of `text` from byte `offset` on, which starts line `number` (1-based): for reading
    /// one program out of a file that holds several.
    pub fn starting_at(text: &'a [u8], offset: usize, number: u32) -> TextLines<'a> {
        let mut lines = TextLines::piece(text, 0, number);
        lines.position = offset.min(lines.text.len());
        lines.check_ahead();
        lines
    }

    /// Lines of `text`, a piece of a file that starts at byte `base` of the file and at line
    /// `number` (1-based): offsets are the file's, for reading a program out of a file that is
    /// not held whole.
    pub fn piece(text: &'a [u8], base: usize, number: u32) -> TextLines<'a> {
        let mut lines = TextLines {
            text: Cow::Borrowed(text),
            base,
            position: 0,
            number: number.saturating_sub(1),
            checked: 0,
        };
        if base == 0 && text.starts_with(BYTE_ORDER_MARK) {
            lines.normalize_whole();
        }
        lines.check_ahead();
        lines
    }

    /// Copies the text and [`normalize`]s it whole.
    fn normalize_whole(&mut self) {
        let mut copy = self.text.to_vec();
        normalize(&mut copy, self.base == 0);
        self.text = Cow::Owned(copy);
        self.checked = usize::MAX;
    }

    /// Keeps the text [`CHECKED_AHEAD`] bytes past the position free of lone `\r`s, searching a
    /// chunk at a time; the first one found has the whole text normalized.
    #[inline(always)]
    fn check_ahead(&mut self) {
        if self.position + CHECKED_AHEAD > self.checked && self.checked < self.text.len() {
            self.check_until(self.position + CHECK_CHUNK);
        }
    }

    /// Searches `text[checked..to]` for a lone `\r` (one at `to - 1` judged by the byte after it),
    /// and normalizes the whole text at the first.
    #[inline(never)]
    fn check_until(&mut self, to: usize) {
        let text = &self.text[..];
        let to = to.min(text.len());
        let mut from = self.checked.min(to);
        while let Some(i) = find_byte(&text[from..to], b'\r') {
            let at = from + i;
            if text.get(at + 1) != Some(&b'\n') {
                self.normalize_whole();
                return;
            }
            from = at + 1;
        }
        self.checked = self.checked.max(to);
    }

    /// The length of the line at `start`, its `\n` included.
    fn line_length(&self, start: usize) -> usize {
        let rest = &self.text[start..];
        memchr_newline(rest).map_or(rest.len(), |i| i + 1)
    }

    /// The whole text, normalized where the reading has come to.
    pub fn text(&self) -> &[u8] {
        &self.text
    }
}

impl LineSource for TextLines<'_> {
    fn text(&self) -> Option<&[u8]> {
        // A piece of a file is not the program's whole text.
        (self.base == 0).then_some(&self.text)
    }

    fn unread(&self) -> Option<Unread<'_>> {
        Some(Unread {
            text: self.text.get(self.position..)?,
            end_offset: u32::try_from(self.base + self.text.len()).ok()?,
            number: self.number.wrapping_add(1),
        })
    }

    fn skip_line(&mut self, after: usize) {
        self.position = self.text.len() - after;
        self.number += 1;
        self.check_ahead();
    }

    fn next_line(&mut self) -> io::Result<Option<Line<'_>>> {
        if self.position >= self.text.len() {
            return Ok(None);
        }
        // The line to be cut may run past what was checked ahead: checked to its `\n` (or the
        // text's end), and cut again if that normalized the text.
        let start = self.position;
        let mut advance = self.line_length(start);
        if start + advance > self.checked {
            // The line runs past what was checked ahead: checked to its end, and cut again if
            // that normalized the text (a lone `\r` in it ends it earlier).
            self.check_until(start + advance);
            advance = self.line_length(start);
        }
        let rest = &self.text[start..];
        let line = &rest[..advance];
        let line = line.strip_suffix(b"\n").unwrap_or(line);
        self.position += advance;
        self.number += 1;
        let line = line.strip_suffix(b"\r").unwrap_or(line);
        Ok(Some(Line {
            text: line,
            offset: clamp_offset(self.base + start),
            number: self.number,
        }))
    }
}

/// Lines read from any reader through one buffer that is reused for every line: a line is
/// handed out as a slice of the buffer, never copied (a line longer than the buffer grows it).
#[derive(Debug)]
pub struct ReaderLines<R> {
    reader: R,
    buffer: Vec<u8>,
    /// The unread bytes are `buffer[start..end]`.
    start: usize,
    end: usize,
    /// File offset of `buffer[0]`: it changes only when the buffer is refilled, not per line.
    buffer_offset: u64,
    /// File offset of `buffer[end]`, when it fits in u32: the end of the unread text, known
    /// from one refill to the next (see [`LineSource::unread`]).
    end_offset: Option<u32>,
    number: u32,
    eof: bool,
}

impl<R: Read> ReaderLines<R> {
    /// Lines of `reader` (it need not be buffered: this reads in large blocks).
    pub fn new(reader: R) -> ReaderLines<R> {
        ReaderLines {
            reader,
            buffer: vec![0; 256 * 1024],
            start: 0,
            end: 0,
            buffer_offset: 0,
            end_offset: Some(0),
            number: 0,
            eof: false,
        }
    }

    /// Moves the unread bytes to the front and reads more; false when nothing more came.
    fn refill(&mut self) -> io::Result<bool> {
        if self.eof {
            return Ok(false);
        }
        self.buffer.copy_within(self.start..self.end, 0);
        self.buffer_offset += self.start as u64;
        self.end -= self.start;
        self.start = 0;
        // The end of the unread text has moved (its bytes went to the front, more may come):
        // its offset is worked out again, whatever the read gives.
        let read = self.read_more();
        self.end_offset = u32::try_from(self.buffer_offset + self.end as u64).ok();
        read
    }

    /// Reads more after `buffer[..end]`; false when nothing more came.
    fn read_more(&mut self) -> io::Result<bool> {
        if self.end == self.buffer.len() {
            let grown = self.buffer.len() * 2;
            self.buffer.resize(grown, 0);
        }
        loop {
            match self.reader.read(&mut self.buffer[self.end..]) {
                Ok(0) => {
                    self.eof = true;
                    return Ok(false);
                }
                Ok(n) => {
                    normalize_read(&mut self.buffer, self.end, self.end + n, self.buffer_offset);
                    self.end += n;
                    return Ok(true);
                }
                Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
                Err(e) => return Err(e),
            }
        }
    }
}

impl<R: Read> LineSource for ReaderLines<R> {
    // Inlined into the parsing loop, with `skip_line`: the common line is read straight from the
    // buffer, and its end found by the reader of its words.
    #[inline(always)]
    fn unread(&self) -> Option<Unread<'_>> {
        // The end's offset is kept from the last refill: nothing to add or clamp per line.
        Some(Unread {
            text: self.buffer.get(self.start..self.end)?,
            end_offset: self.end_offset?,
            number: self.number.wrapping_add(1),
        })
    }

    #[inline(always)]
    fn skip_line(&mut self, after: usize) {
        debug_assert!(after < self.end - self.start, "a line of the unread text");
        self.start = self.end - after;
        self.number += 1;
    }

    // Inlined into the parsing loop: out of line, every line paid a call and its line was
    // returned through memory.
    #[inline(always)]
    fn next_line(&mut self) -> io::Result<Option<Line<'_>>> {
        // The common case, a whole line in the buffer, stays short; reading more is out of line.
        let newline = match memchr_newline(&self.buffer[self.start..self.end]) {
            Some(i) => Some(self.start + i),
            None => self.refill_to_newline()?,
        };
        let (line_end, next) = match newline {
            Some(i) => (i, i + 1),
            None if self.start < self.end => (self.end, self.end),
            None => return Ok(None),
        };
        let line_start = self.start;
        let file_offset = self.buffer_offset + line_start as u64;
        self.start = next;
        self.number += 1;
        let line = &self.buffer[line_start..line_end];
        let line = line.strip_suffix(b"\r").unwrap_or(line);
        Ok(Some(Line {
            text: line,
            offset: clamp_offset(usize::try_from(file_offset).unwrap_or(usize::MAX)),
            number: self.number,
        }))
    }
}

impl<R: Read> ReaderLines<R> {
    /// Reads until the unread bytes hold a `\n` (its index in the buffer) or the reader ends
    /// (`None`): the unread bytes, known to hold none, are not searched again.
    #[cold]
    fn refill_to_newline(&mut self) -> io::Result<Option<usize>> {
        loop {
            // The last byte searched may be a `\r` that the read turns into a line end.
            let searched = (self.end - self.start).saturating_sub(1);
            if !self.refill()? {
                return Ok(None);
            }
            if let Some(i) = memchr_newline(&self.buffer[self.start + searched..self.end]) {
                return Ok(Some(self.start + searched + i));
            }
        }
    }
}

/// The first `\n` in `bytes`.
#[inline(always)]
pub(crate) fn memchr_newline(bytes: &[u8]) -> Option<usize> {
    find_byte(bytes, b'\n')
}

/// The first `byte` in `bytes`, eight bytes at a time: a byte equal to `byte` becomes zero after
/// the XOR, and the classic has-zero-byte test finds it without a branch per byte.
#[inline(always)]
fn find_byte(bytes: &[u8], byte: u8) -> Option<usize> {
    let mut chunks = bytes.chunks_exact(8);
    let mut base = 0;
    for chunk in chunks.by_ref() {
        let found = has_byte(chunk, byte);
        if found != 0 {
            return Some(base + (found.trailing_zeros() / 8) as usize);
        }
        base += 8;
    }
    chunks
        .remainder()
        .iter()
        .position(|&b| b == byte)
        .map(|i| base + i)
}

/// Offsets are kept in u32 (spans are small); past 4 GiB they saturate, which only blurs the
/// position shown in a diagnostic.
fn clamp_offset(offset: usize) -> u32 {
    u32::try_from(offset).unwrap_or(u32::MAX)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    fn collect(source: &mut dyn LineSource) -> Vec<(String, u32, u32)> {
        let mut lines = Vec::new();
        while let Some(line) = source.next_line().unwrap() {
            lines.push((
                String::from_utf8_lossy(line.text).into_owned(),
                line.offset,
                line.number,
            ));
        }
        lines
    }

    /// A reader that hands out at most `chunk` bytes per read, so that lines are cut where a
    /// reader's buffer ends (the line sources' and the parsers' tests).
    pub(crate) struct Trickle<'a> {
        pub(crate) data: &'a [u8],
        pub(crate) chunk: usize,
    }

    impl Read for Trickle<'_> {
        fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
            let n = self.chunk.min(buf.len()).min(self.data.len());
            buf[..n].copy_from_slice(&self.data[..n]);
            self.data = &self.data[n..];
            Ok(n)
        }
    }

    #[test]
    fn lines_longer_than_the_buffer_and_split_reads_come_out_whole() {
        let mut text = Vec::new();
        for i in 0..2000 {
            text.extend_from_slice(format!("G1 X{i}.\r\n").as_bytes());
        }
        text.extend(std::iter::repeat_n(b'X', 600 * 1024));
        text.extend_from_slice(b"\nM30");
        let a = collect(&mut TextLines::new(&text));
        let b = collect(&mut ReaderLines::new(Trickle {
            data: &text,
            chunk: 7,
        }));
        let c = collect(&mut ReaderLines::new(&text[..]));
        assert_eq!(a, b);
        assert_eq!(a, c);
        assert_eq!(a.len(), 2002);
    }

    #[test]
    fn the_word_at_a_time_newline_search_finds_the_first_newline() {
        for len in 0..40 {
            for at in 0..=len {
                let mut bytes = vec![b'x'; len];
                if at < len {
                    bytes[at] = b'\n';
                    if at + 3 < len {
                        bytes[at + 3] = b'\n';
                    }
                }
                let expected = bytes.iter().position(|&b| b == b'\n');
                assert_eq!(memchr_newline(&bytes), expected, "len {len} at {at}");
            }
        }
        assert_eq!(memchr_newline(&[0x8a, b'\n']), Some(1));
        assert_eq!(
            memchr_newline(&[0x0b, 0x8a, 0x0a, 0, 0, 0, 0, 0, 0]),
            Some(2)
        );
    }

    #[test]
    fn a_skipped_line_is_not_handed_out_and_the_next_one_keeps_its_place() {
        let text = b"G0 X1\r\nG1 Y2\nM30";
        let mut a = TextLines::new(text);
        let mut b = ReaderLines::new(Trickle {
            data: text,
            chunk: 4,
        });
        // The reader has nothing at hand before its first read.
        assert!(b.unread().is_none_or(|unread| unread.text.is_empty()));
        assert_eq!(b.next_line().unwrap().unwrap().text, b"G0 X1");
        a.next_line().unwrap();
        for source in [&mut a as &mut dyn LineSource, &mut b] {
            let unread = source.unread().unwrap();
            assert_eq!((unread.offset(), unread.number), (7, 2));
            if unread.text.starts_with(b"G1 Y2\n") {
                source.skip_line(unread.text.len() - 6);
            } else {
                // Cut short by the reader: the line is read as usual.
                source.next_line().unwrap();
            }
            let line = source.next_line().unwrap().unwrap();
            assert_eq!((line.text, line.offset, line.number), (&b"M30"[..], 13, 3));
        }
    }

    #[test]
    fn the_text_at_hand_starts_where_the_next_line_starts_across_refills() {
        let mut text = Vec::new();
        for i in 0..300 {
            text.extend_from_slice(format!("G1 X{i}.\r\n\n").as_bytes());
        }
        for chunk in [1, 3, 7, 64] {
            let mut reader = ReaderLines::new(Trickle { data: &text, chunk });
            let mut lines = TextLines::new(&text);
            loop {
                // The reader's text at hand is a part of the text's, from the same place on.
                let whole = lines.unread().expect("the whole text is at hand");
                if let Some(unread) = reader.unread().filter(|u| !u.text.is_empty()) {
                    assert_eq!(unread.offset(), whole.offset(), "chunk {chunk}");
                    assert_eq!(unread.number, whole.number, "chunk {chunk}");
                    assert!(whole.text.starts_with(unread.text), "chunk {chunk}");
                }
                let Some(line) = reader.next_line().unwrap().map(|l| (l.offset, l.number)) else {
                    break;
                };
                let expected = lines.next_line().unwrap().map(|l| (l.offset, l.number));
                assert_eq!(Some(line), expected);
            }
        }
    }

    #[test]
    fn lone_carriage_returns_are_found_across_the_pieces_searched_at_once() {
        for at in [0, 1, 1022, 1023, 1024, 1025, 2047, 2048, 2999] {
            let mut bytes = vec![b'x'; 3000];
            bytes[at] = b'\r';
            bytes[2500] = b'\r';
            bytes[2501] = b'\n';
            let mut expected = bytes.clone();
            // At the end too: nothing follows it.
            expected[at] = b'\n';
            normalize(&mut bytes, false);
            assert_eq!(bytes, expected, "{at}");
        }
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

    #[test]
    fn old_mac_line_ends_and_a_byte_order_mark_read_as_line_feeds_in_every_reader() {
        let text = b"\xEF\xBB\xBFG0 X1\rG1 Y2\r\rG2 X3\r\nM30\r";
        let expected = vec![
            ("   G0 X1".to_string(), 0, 1),
            ("G1 Y2".to_string(), 9, 2),
            ("".to_string(), 15, 3),
            ("G2 X3".to_string(), 16, 4),
            ("M30".to_string(), 23, 5),
        ];
        assert_eq!(collect(&mut TextLines::new(text)), expected);
        for chunk in 1..8 {
            let reader = Trickle { data: text, chunk };
            assert_eq!(collect(&mut ReaderLines::new(reader)), expected, "{chunk}");
        }
        // A piece of a file read apart is not its start: three bytes there are text.
        let piece = collect(&mut TextLines::piece(b"\xEF\xBB\xBFX\r", 5, 2));
        assert_eq!(piece[0].0, "\u{feff}X");
    }
}
