//! A SINUMERIK program's lines read and parsed as they come: the [`LineParser`] that
//! [`BackgroundParser`](crate::syntax::blocks::BackgroundParser) runs on a thread of its own, a
//! few hundred lines ahead of the interpreter (the SINUMERIK front end reads and parses a block
//! in about as many instructions as it runs it: on a second core the two overlap).
//!
//! Each line keeps its text and place beside its block, so that the interpreter sees exactly
//! what it would have read itself. A plain line is read from the text at hand and its text
//! copied after it (plain.rs); any other is cut out by the line source first. Never: skip or join lines (line numbers are the program's).

use super::block::{parse_line_into, parse_plain_line_in, Block};
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

/// The length up to which a line's text is copied as a block of that fixed size (most lines of
/// a CAM program are shorter), and the room each line's text is made with.
const SHORT_LINE: usize = 64;

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

impl SinumerikParser {
    /// Reads the next line into `out` from the text at hand when it is a plain one (the common
    /// line, read without being cut out and searched for its end first), and copies its text
    /// after it; how many bytes of the text at hand follow the line, or None to read it the
    /// usual way.
    #[inline(always)]
    fn read_plain_at_hand<L: LineSource>(
        &mut self,
        lines: &L,
        out: &mut ParsedLine,
    ) -> Option<usize> {
        let unread = lines.unread()?;
        let number = self.read + 1;
        let base = unread.offset();
        let line = parse_plain_line_in(unread.text, self.file, number, base, &mut out.block)?;
        self.read = number;
        out.number = number;
        out.base = base;
        out.text.clear();
        // A short line is copied as a block of fixed size and cut to its length: a copy the
        // compiler makes in a few moves, where one of the line's length called memcpy.
        match unread.text.first_chunk::<SHORT_LINE>() {
            Some(block) if line.length <= SHORT_LINE => {
                out.text.extend_from_slice(block);
                out.text.truncate(line.length);
            }
            _ => out.text.extend_from_slice(&unread.text[..line.length]),
        }
        Some(line.after)
    }
}

impl LineParser for SinumerikParser {
    type Line = ParsedLine;

    // A parsed line is about 500 bytes with its words: a quarter of the ISO front end's batch
    // keeps the pool at about 2 MB, and a hand-over every 256 lines costs nothing measurable.
    const BATCH: usize = 256;

    fn empty_line(&self) -> ParsedLine {
        ParsedLine {
            text: Vec::with_capacity(SHORT_LINE),
            block: Box::new(Block {
                // A CAM line has up to about eight words.
                words: Vec::with_capacity(8),
                ..Block::default()
            }),
            ..ParsedLine::default()
        }
    }

    // Inlined into the parser thread's loop: a call cost every line its registers saved and
    // restored.
    #[inline(always)]
    fn read_line<L: LineSource>(
        &mut self,
        lines: &mut L,
        out: &mut ParsedLine,
    ) -> io::Result<bool> {
        if let Some(after) = self.read_plain_at_hand(lines, out) {
            lines.skip_line(after);
            return Ok(true);
        }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::blocks::{BackgroundParser, BlockSource, ParsedLines};
    use crate::syntax::lines::tests::Trickle;
    use crate::syntax::lines::{Line, ReaderLines, TextLines};

    /// A line source that hands out lines one by one and nothing else: every line is cut out
    /// first, and none is read from the text at hand.
    struct OneByOne<L>(L);

    impl<L: LineSource> LineSource for OneByOne<L> {
        fn next_line(&mut self) -> io::Result<Option<Line<'_>>> {
            self.0.next_line()
        }
    }

    fn collect(source: &mut dyn BlockSource<Line = ParsedLine>) -> Vec<ParsedLine> {
        let mut lines = Vec::new();
        while source.advance().expect("text in memory") {
            lines.extend(source.line().cloned());
        }
        lines
    }

    /// The lines of `text` as every source gives them, the first one line by line.
    fn lines_by_every_source(text: &[u8]) -> Vec<Vec<ParsedLine>> {
        let parser = SinumerikParser::new(FileId(2));
        let trickle = |chunk| ReaderLines::new(Trickle { data: text, chunk });
        vec![
            collect(&mut ParsedLines::with_parser(
                OneByOne(TextLines::new(text)),
                parser,
            )),
            collect(&mut ParsedLines::with_parser(TextLines::new(text), parser)),
            collect(&mut ParsedLines::with_parser(
                ReaderLines::new(text),
                parser,
            )),
            collect(&mut ParsedLines::with_parser(trickle(5), parser)),
            collect(&mut ParsedLines::with_parser(trickle(64), parser)),
            collect(&mut BackgroundParser::start(
                io::Cursor::new(text.to_vec()),
                parser,
                0,
            )),
        ]
    }

    #[test]
    fn lines_read_from_the_text_at_hand_are_the_lines_handed_out_one_by_one() {
        let mut text = b"%_N_PART_MPF\r\nN10 G1 X54.808 Y30.491 Z-1.288 F=FEED1\r\n\
            N20 G2 X51.438 Y26.151 CR=-11.700 F=FEED2 ; arc \r\r\n\n \r\n\
            N30 G1\rX1\nN40 X1 ; c\nDEF REAL A=1\nN50 G1 X1&Y2\t\x0bZ3\n"
            .to_vec();
        // Lines about as long as the block a short line is copied in.
        for length in [63, 64, 65] {
            let line = format!("N80 G1 X1 ;{}\n", "c".repeat(length - 11));
            assert_eq!(line.len(), length + 1);
            text.extend_from_slice(line.as_bytes());
        }
        text.extend_from_slice(format!("N60 X1 ;{}\nN70 G1 X1", "c".repeat(600)).as_bytes());
        let sources = lines_by_every_source(&text);
        assert_eq!(sources[0].len(), 16);
        assert_eq!(sources[0][12].text.len(), 64);
        for other in &sources[1..] {
            assert_eq!(&sources[0], other);
        }
    }

    #[test]
    fn a_lone_carriage_return_in_a_comment_far_into_a_text_ends_its_line() {
        // Lines that only the line reader reads, far past what the text in memory searched for
        // lone `\r`s at first; then a comment with one, not yet searched when it is at hand.
        let mut text = "DEF REAL A\n".repeat(8_000).into_bytes();
        text.extend_from_slice(
            b"N10 G1 X1 ; c\rc\nN20 G1 X2 Y3 Z4 F=FEED1 ; long enough for windows\n",
        );
        let sources = lines_by_every_source(&text);
        assert_eq!(sources[0][8_000].text, b"N10 G1 X1 ; c");
        for other in &sources[1..] {
            assert_eq!(&sources[0], other);
        }
    }

    proptest::proptest! {
        #[test]
        fn any_text_reads_the_same_from_the_text_at_hand_and_line_by_line(
            lines in proptest::collection::vec(
                "[ \t&]{0,2}(N[0-9]{0,10} )?([GXYgxF][-+=]?[0-9]{0,3}[.]?[0-9]{0,3}[ \t\r(;=]{0,2}){0,4}(CR=-?[0-9.]{0,3}|F=FEED1|;c)?[\r]{0,2}",
                0..12,
            ),
            final_newline in proptest::bool::ANY,
        ) {
            let mut text = lines.join("\n");
            if final_newline {
                text.push('\n');
            }
            let sources = lines_by_every_source(text.as_bytes());
            for other in &sources[1..] {
                proptest::prop_assert_eq!(&sources[0], other);
            }
        }
    }
}
