//! Where a front end gets its program's lines: a [`BlockSource`] hands them out one at a time,
//! each read and parsed by the front end's [`LineParser`] into the front end's own type (the
//! ISO front end's [`LineBlocks`], SINUMERIK's `ParsedLine`).
//!
//! [`ParsedLines`] reads and parses on demand, on the caller's thread. [`BackgroundParser`] reads
//! and parses on a thread of its own, a few hundred lines ahead, so that a consumer with a second
//! core spends its time interpreting; both give the same lines (checked by the tests).
//! [`ProgramLines`] is either, as the caller chooses, over a program's reader.

use super::iso::{parse_line, parse_plain_line_in, LineBlocks, SyntaxOptions};
use super::lines::{LineSource, ReaderLines};
use super::Block;
use crate::source::FileId;
use std::io::{self, Read};
use std::sync::mpsc::{sync_channel, Receiver, SyncSender};
use std::thread::JoinHandle;

/// A program's lines, read and parsed one at a time.
pub trait BlockSource {
    /// One line as the front end's parser gives it.
    type Line;

    /// Moves to the next line; false at the end of the text.
    ///
    /// # Errors
    /// Whatever reading the text reports.
    fn advance(&mut self) -> io::Result<bool>;

    /// The line read last: before the first `advance`, None or a line without blocks; after the
    /// end of the text, what the parser left there (the ISO parser: a line without blocks; SINUMERIK's: the last
    /// line, for the spans of what the end finds missing).
    fn line(&self) -> Option<&Self::Line>;

    /// The line read last, to take parts of it: it is read into again by the next `advance`.
    fn line_mut(&mut self) -> Option<&mut Self::Line>;

    /// The whole program text, when it is in memory (see [`LineSource::text`]).
    fn text(&self) -> Option<&[u8]> {
        None
    }
}

/// The blocks of the line `source` read last (none before the first line).
#[inline(always)]
pub fn line_blocks<B: BlockSource<Line = LineBlocks> + ?Sized>(source: &B) -> &[Block] {
    source.line().map_or(&[], LineBlocks::as_slice)
}

/// Lines from a [`LineSource`], parsed as they are asked for by `P` (the ISO parser unless
/// said otherwise).
#[derive(Debug)]
pub struct ParsedLines<L, P: LineParser = IsoParser> {
    lines: L,
    parser: P,
    line: P::Line,
}

impl<L: LineSource> ParsedLines<L> {
    /// Parses the lines of `lines` (file `file`) as ISO blocks with the character rules
    /// `syntax`.
    pub fn new(lines: L, file: FileId, syntax: SyntaxOptions) -> ParsedLines<L> {
        ParsedLines::with_parser(lines, IsoParser::new(file, syntax))
    }
}

impl<L: LineSource, P: LineParser> ParsedLines<L, P> {
    /// Parses the lines of `lines` with `parser`.
    pub fn with_parser(lines: L, parser: P) -> ParsedLines<L, P> {
        ParsedLines {
            line: parser.empty_line(),
            lines,
            parser,
        }
    }
}

impl<L: LineSource, P: LineParser> BlockSource for ParsedLines<L, P> {
    type Line = P::Line;

    #[inline(always)]
    fn advance(&mut self) -> io::Result<bool> {
        self.parser.read_line(&mut self.lines, &mut self.line)
    }

    #[inline(always)]
    fn line(&self) -> Option<&P::Line> {
        Some(&self.line)
    }

    fn line_mut(&mut self) -> Option<&mut P::Line> {
        Some(&mut self.line)
    }

    fn text(&self) -> Option<&[u8]> {
        self.lines.text()
    }
}

/// Reads the next line of `lines` into `out`; false (and `out` empty) at the end of the text.
///
/// The common line, a plain one, is read straight from the text at hand, its end found by the
/// reader of its words: searching for it first cost a second pass over every line.
#[inline(always)]
fn read_next_line<L: LineSource>(
    lines: &mut L,
    file: FileId,
    syntax: &SyntaxOptions,
    out: &mut LineBlocks,
) -> io::Result<bool> {
    if let Some(unread) = lines.unread() {
        if let Some(after) = parse_plain_line_in(unread, file, out) {
            lines.skip_line(after);
            return Ok(true);
        }
    }
    match lines.next_line()? {
        Some(line) => {
            parse_line(line, file, syntax, out);
            Ok(true)
        }
        None => {
            out.reset();
            Ok(false)
        }
    }
}

/// How a front end reads a program line by line: what one line is once read, and how the next
/// one is read from a [`LineSource`]. [`BackgroundParser`] runs it on a thread of its own.
pub trait LineParser: Send + 'static {
    /// One line, read and parsed; reused line after line, so that reading need not allocate.
    type Line: Send + 'static;

    /// Lines per batch handed from the parser thread (four batches go round).
    const BATCH: usize = 1024;

    /// An empty line with room for what most lines hold (made up front for the pools).
    fn empty_line(&self) -> Self::Line;

    /// Reads the next line of `lines` into `out`; false at the end of the text (`out` then
    /// holds what the parser says: no blocks for the ISO one, the last line for SINUMERIK's).
    ///
    /// # Errors
    /// Whatever reading the text reports.
    fn read_line<L: LineSource>(&mut self, lines: &mut L, out: &mut Self::Line)
        -> io::Result<bool>;
}

/// The ISO front end's lines: the blocks of each line.
#[derive(Clone, Copy, Debug)]
pub struct IsoParser {
    file: FileId,
    syntax: SyntaxOptions,
}

impl IsoParser {
    /// The lines of file `file`, read with the character rules `syntax`.
    pub fn new(file: FileId, syntax: SyntaxOptions) -> IsoParser {
        IsoParser { file, syntax }
    }
}

impl LineParser for IsoParser {
    type Line = LineBlocks;

    fn empty_line(&self) -> LineBlocks {
        LineBlocks::with_room(8)
    }

    #[inline(always)]
    fn read_line<L: LineSource>(
        &mut self,
        lines: &mut L,
        out: &mut LineBlocks,
    ) -> io::Result<bool> {
        read_next_line(lines, self.file, &self.syntax, out)
    }
}

/// Batches in circulation between the parser thread and the interpreter.
const POOL: usize = 8;

/// Read batches go back to the parser thread this many at a time: the parser, ahead, then wakes
/// once for several batches, not once a batch (every wake-up a switch of threads on two busy
/// cores).
const RETURNED_TOGETHER: usize = POOL / 2;

/// What the parser thread sends: a batch of parsed lines, or the error that stopped it.
type Batch<T> = io::Result<Vec<T>>;

/// Lines read and parsed on a background thread, by the ISO front end's parser unless `P` says
/// another.
pub struct BackgroundParser<P: LineParser = IsoParser> {
    batches: Receiver<Batch<P::Line>>,
    recycle: SyncSender<Vec<P::Line>>,
    batch: Vec<P::Line>,
    index: usize,
    /// Read batches waiting to go back together ([`RETURNED_TOGETHER`]).
    returned: Vec<Vec<P::Line>>,
    /// The parser thread came to the end of the text.
    ended: bool,
    thread: Option<JoinHandle<()>>,
}

impl BackgroundParser<IsoParser> {
    /// Starts reading `reader` (file `file`) on a new thread.
    pub fn spawn<R: Read + Send + 'static>(
        reader: R,
        file: FileId,
        syntax: SyntaxOptions,
    ) -> BackgroundParser {
        BackgroundParser::spawn_expecting(reader, file, syntax, 0)
    }

    /// Starts reading `reader` (file `file`), which holds about `expected_bytes` bytes, on a new
    /// thread (see [`BackgroundParser::start`]).
    pub fn spawn_expecting<R: Read + Send + 'static>(
        reader: R,
        file: FileId,
        syntax: SyntaxOptions,
        expected_bytes: u64,
    ) -> BackgroundParser {
        BackgroundParser::start(reader, IsoParser::new(file, syntax), expected_bytes)
    }
}

impl<P: LineParser> BackgroundParser<P> {
    /// Starts reading `reader`, which holds about `expected_bytes` bytes, with `parser` on a new
    /// thread. For a long program the buffers of the parsed lines are made at once, here on the
    /// caller's thread: made line by line on the parser's thread, they grew that thread's heap
    /// one page at a time (hundreds of system calls on a 400,000-line program). A short program
    /// gets only what it needs.
    pub fn start<R: Read + Send + 'static>(
        reader: R,
        mut parser: P,
        expected_bytes: u64,
    ) -> BackgroundParser<P> {
        // A fixed pool of batches goes round between the two threads: the parser waits for an
        // empty one, so memory stays bounded and the parsed lines' buffers are reused.
        let (send_batch, batches) = sync_channel::<Batch<P::Line>>(POOL);
        let (recycle, recycled) = sync_channel::<Vec<P::Line>>(POOL);
        // Lines are rarely shorter than 16 bytes in a program worth reading ahead.
        let mut made_now = usize::try_from(expected_bytes / 16).unwrap_or(usize::MAX);
        for _ in 0..POOL {
            let lines = made_now.min(P::BATCH);
            made_now -= lines;
            let mut batch = Vec::with_capacity(P::BATCH);
            batch.extend((0..lines).map(|_| parser.empty_line()));
            let _ = recycle.try_send(batch);
        }
        let thread = std::thread::spawn(move || {
            let mut lines = ReaderLines::new(reader);
            while let Ok(mut batch) = recycled.recv() {
                let mut filled = 0;
                while filled < P::BATCH {
                    if batch.len() <= filled {
                        batch.push(parser.empty_line());
                    }
                    match parser.read_line(&mut lines, &mut batch[filled]) {
                        Ok(true) => filled += 1,
                        Ok(false) => break,
                        Err(error) => {
                            let _ = send_batch.send(Err(error));
                            return;
                        }
                    }
                }
                batch.truncate(filled);
                let last = filled < P::BATCH;
                if (filled > 0 && send_batch.send(Ok(batch)).is_err()) || last {
                    return;
                }
            }
        });
        BackgroundParser {
            batches,
            recycle,
            batch: Vec::new(),
            index: 0,
            returned: Vec::with_capacity(RETURNED_TOGETHER),
            ended: false,
            thread: Some(thread),
        }
    }
}

impl<P: LineParser> BlockSource for BackgroundParser<P> {
    type Line = P::Line;

    fn advance(&mut self) -> io::Result<bool> {
        if self.ended {
            return Ok(false);
        }
        if self.index + 1 < self.batch.len() {
            self.index += 1;
            return Ok(true);
        }
        // The batch read last is kept until the next one comes: at the end of the text its
        // last line stays at hand.
        match self.batches.recv() {
            Ok(Ok(batch)) => {
                let done = std::mem::replace(&mut self.batch, batch);
                if done.capacity() > 0 {
                    self.returned.push(done);
                }
                if self.returned.len() >= RETURNED_TOGETHER {
                    for done in self.returned.drain(..) {
                        // The channel holds the whole pool: there is always room.
                        let _ = self.recycle.try_send(done);
                    }
                }
                self.index = 0;
                Ok(!self.batch.is_empty())
            }
            Ok(Err(error)) => Err(error),
            Err(_) => {
                self.ended = true;
                Ok(false)
            }
        }
    }

    fn line(&self) -> Option<&P::Line> {
        self.batch.get(self.index)
    }

    fn line_mut(&mut self) -> Option<&mut P::Line> {
        self.batch.get_mut(self.index)
    }
}

/// A program's lines read from its reader by `P`: here as they are asked for, or on a thread
/// of its own ahead of them.
// Made once per run: the variants' sizes do not matter.
#[allow(clippy::large_enum_variant)]
pub enum ProgramLines<P: LineParser> {
    /// On a thread of its own ([`BackgroundParser`]).
    Ahead(BackgroundParser<P>),
    /// On the caller's thread ([`ParsedLines`]).
    InLine(ParsedLines<ReaderLines<Box<dyn Read + Send>>, P>),
}

impl<P: LineParser> ProgramLines<P> {
    /// The lines of `reader` parsed by `parser`: on a thread of its own when `ahead` says
    /// about how many bytes the text holds (0 when unknown), here when it is None.
    pub fn new(reader: Box<dyn Read + Send>, parser: P, ahead: Option<u64>) -> ProgramLines<P> {
        match ahead {
            Some(bytes) => ProgramLines::Ahead(BackgroundParser::start(reader, parser, bytes)),
            None => {
                ProgramLines::InLine(ParsedLines::with_parser(ReaderLines::new(reader), parser))
            }
        }
    }
}

impl<P: LineParser> BlockSource for ProgramLines<P> {
    type Line = P::Line;

    #[inline(always)]
    fn advance(&mut self) -> io::Result<bool> {
        match self {
            ProgramLines::Ahead(lines) => lines.advance(),
            ProgramLines::InLine(lines) => lines.advance(),
        }
    }

    #[inline(always)]
    fn line(&self) -> Option<&P::Line> {
        match self {
            ProgramLines::Ahead(lines) => lines.line(),
            ProgramLines::InLine(lines) => lines.line(),
        }
    }

    fn line_mut(&mut self) -> Option<&mut P::Line> {
        match self {
            ProgramLines::Ahead(lines) => lines.line_mut(),
            ProgramLines::InLine(lines) => lines.line_mut(),
        }
    }
}

impl<P: LineParser> std::fmt::Debug for ProgramLines<P> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ProgramLines::Ahead(lines) => lines.fmt(f),
            ProgramLines::InLine(_) => f.write_str("ProgramLines::InLine"),
        }
    }
}

impl<P: LineParser> std::fmt::Debug for BackgroundParser<P> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("BackgroundParser")
            .field("lines_at_hand", &self.batch.len())
            .field("index", &self.index)
            .finish_non_exhaustive()
    }
}

impl<P: LineParser> Drop for BackgroundParser<P> {
    fn drop(&mut self) {
        // Dropping both ends makes the parser thread's next send or receive fail, so it ends.
        let (_, receiver) = sync_channel(0);
        drop(std::mem::replace(&mut self.batches, receiver));
        let (sender, _) = sync_channel(0);
        drop(std::mem::replace(&mut self.recycle, sender));
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::lines::tests::Trickle;
    use crate::syntax::lines::TextLines;

    fn collect(source: &mut dyn BlockSource<Line = LineBlocks>) -> Vec<Vec<Block>> {
        let mut lines = Vec::new();
        while source.advance().unwrap() {
            lines.push(line_blocks(source).to_vec());
        }
        lines
    }

    #[test]
    fn background_and_on_demand_parsing_give_the_same_blocks() {
        let mut text = String::new();
        for i in 0..2000 {
            text.push_str(&format!("N{i} G1 X{i}. Y-{i}.5 (C) ; G0 Z1.\n"));
        }
        text.push_str("#1=2\nM30");
        let syntax = SyntaxOptions::default();
        let a = collect(&mut ParsedLines::new(
            TextLines::new(text.as_bytes()),
            FileId(0),
            syntax,
        ));
        assert_eq!(a.len(), 2002);
        // Pools made as lines come, made up front for more lines than the text has, and made up
        // front for fewer.
        for expected_bytes in [0, 1 << 30, 10_000] {
            let b = collect(&mut BackgroundParser::spawn_expecting(
                std::io::Cursor::new(text.clone().into_bytes()),
                FileId(0),
                syntax,
                expected_bytes,
            ));
            assert_eq!(a, b, "expecting {expected_bytes} bytes");
        }
    }

    /// A line source that hands out lines one by one and nothing else: every line takes the
    /// path of [`LineSource::next_line`] and [`parse_line`].
    struct OneByOne<L>(L);

    impl<L: LineSource> LineSource for OneByOne<L> {
        fn next_line(&mut self) -> io::Result<Option<crate::syntax::lines::Line<'_>>> {
            self.0.next_line()
        }
    }

    /// The blocks of every line of `text` as text, values to the bit (`{:?}` tells -0 from 0),
    /// as each source gives them.
    fn blocks_by_every_source(text: &[u8]) -> Vec<String> {
        let read =
            |source: &mut dyn BlockSource<Line = LineBlocks>| format!("{:?}", collect(source));
        let syntax = SyntaxOptions::default();
        let file = FileId(2);
        vec![
            read(&mut ParsedLines::new(
                OneByOne(TextLines::new(text)),
                file,
                syntax,
            )),
            read(&mut ParsedLines::new(TextLines::new(text), file, syntax)),
            read(&mut ParsedLines::new(ReaderLines::new(text), file, syntax)),
            read(&mut ParsedLines::new(
                ReaderLines::new(Trickle {
                    data: text,
                    chunk: 5,
                }),
                file,
                syntax,
            )),
            read(&mut BackgroundParser::spawn(
                io::Cursor::new(text.to_vec()),
                file,
                syntax,
            )),
        ]
    }

    #[test]
    fn lines_read_from_the_text_at_hand_are_the_lines_handed_out_one_by_one() {
        let text = b"G01 X11.280 Y5.659 Z-1.464\r\nG02 X51.438 Y26.151 R11.700  \r\r\n\n \r\n\
            X1 (C)\ng1x1y2\r\n\0X1\x0bY2\x0c\nX1\rY2\nN10 G1 X+.5\n  \tG1 X1\nF2=100\nG1 X1";
        let sources = blocks_by_every_source(text);
        for other in &sources[1..] {
            assert_eq!(&sources[0], other);
        }
        // The end of a CRLF line's block is before its `\r`, as on the line handed out; a lone
        // `\r` ends a line (old Mac line ends), the next `\r\n` an empty one.
        let mut lines = ParsedLines::new(TextLines::new(text), FileId(0), SyntaxOptions::default());
        assert!(lines.advance().unwrap());
        assert_eq!(line_blocks(&lines)[0].span.end, 26);
        assert!(lines.advance().unwrap());
        assert_eq!(line_blocks(&lines)[0].span.end, 26 + 2 + 29);
    }

    proptest::proptest! {
        #[test]
        fn any_text_reads_the_same_from_the_text_at_hand_and_line_by_line(
            lines in proptest::collection::vec(
                "[ \t]{0,2}([GXYgx][-+]?[0-9]{0,3}[.]?[0-9]{0,3}[ \t\r\x00(;=]{0,2}){0,4}[\r]{0,2}",
                0..12,
            ),
            final_newline in proptest::bool::ANY,
        ) {
            let mut text = lines.join("\n");
            if final_newline {
                text.push('\n');
            }
            let sources = blocks_by_every_source(text.as_bytes());
            for other in &sources[1..] {
                proptest::prop_assert_eq!(&sources[0], other);
            }
        }
    }

    #[test]
    fn dropping_a_background_parser_early_ends_its_thread() {
        let text = "G1 X1.\n".repeat(100_000);
        let mut parser = BackgroundParser::spawn(
            std::io::Cursor::new(text.into_bytes()),
            FileId(0),
            SyntaxOptions::default(),
        );
        assert!(parser.advance().unwrap());
        drop(parser);
    }
}
