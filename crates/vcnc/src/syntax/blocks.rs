//! Where the interpreter gets its blocks: a [`BlockSource`] hands them out one line at a time.
//!
//! [`ParsedLines`] reads and parses on demand, on the caller's thread. [`BackgroundParser`] reads
//! and parses on a thread of its own, a few hundred lines ahead, so that a consumer with a second
//! core spends its time interpreting; both give the same blocks (checked by the tests). What a
//! line parses into is the front end's: a [`LineParser`] says it (the ISO front end's blocks by
//! default; the SINUMERIK front end has its own, in `syntax::sinumerik`).

use super::iso::{parse_line, parse_plain_line_in, LineBlocks, SyntaxOptions};
use super::lines::{LineSource, ReaderLines};
use super::Block;
use crate::source::FileId;
use std::io::{self, Read};
use std::sync::mpsc::{sync_channel, Receiver, SyncSender};
use std::thread::JoinHandle;

/// Blocks of a program, one line's worth at a time.
pub trait BlockSource {
    /// Moves to the next line; false at the end of the text.
    ///
    /// # Errors
    /// Whatever reading the text reports.
    fn advance(&mut self) -> io::Result<bool>;

    /// The blocks of the current line (empty before the first `advance`).
    fn blocks(&self) -> &[Block];

    /// The whole program text, when it is in memory (see [`LineSource::text`]).
    fn text(&self) -> Option<&[u8]> {
        None
    }
}

/// Lines from a [`LineSource`], parsed as they are asked for.
#[derive(Debug)]
pub struct ParsedLines<L> {
    lines: L,
    file: FileId,
    syntax: SyntaxOptions,
    blocks: LineBlocks,
}

impl<L: LineSource> ParsedLines<L> {
    /// Parses the lines of `lines` (file `file`) with the character rules `syntax`.
    pub fn new(lines: L, file: FileId, syntax: SyntaxOptions) -> ParsedLines<L> {
        ParsedLines {
            lines,
            file,
            syntax,
            blocks: LineBlocks::new(),
        }
    }
}

impl<L: LineSource> BlockSource for ParsedLines<L> {
    fn advance(&mut self) -> io::Result<bool> {
        read_next_line(&mut self.lines, self.file, &self.syntax, &mut self.blocks)
    }

    fn blocks(&self) -> &[Block] {
        self.blocks.as_slice()
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
const POOL: usize = 4;

/// What the parser thread sends: a batch of parsed lines, or the error that stopped it.
type Batch<T> = io::Result<Vec<T>>;

/// Lines read and parsed on a background thread, by the ISO front end's parser unless `P` says
/// another.
pub struct BackgroundParser<P: LineParser = IsoParser> {
    batches: Receiver<Batch<P::Line>>,
    recycle: SyncSender<Vec<P::Line>>,
    batch: Vec<P::Line>,
    index: usize,
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
            ended: false,
            thread: Some(thread),
        }
    }

    /// Moves to the next line; false at the end of the text.
    ///
    /// # Errors
    /// Whatever reading the text reported on the parser's thread.
    pub fn next_line(&mut self) -> io::Result<bool> {
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
                    let _ = self.recycle.try_send(done);
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

    /// The current line: None before the first [`BackgroundParser::next_line`]; after the
    /// end of the text, still the last line.
    pub fn line(&self) -> Option<&P::Line> {
        self.batch.get(self.index)
    }

    /// The current line, to take parts of it: it goes back to the parser thread with its batch,
    /// to be read into again.
    pub fn line_mut(&mut self) -> Option<&mut P::Line> {
        self.batch.get_mut(self.index)
    }
}

impl BlockSource for BackgroundParser<IsoParser> {
    fn advance(&mut self) -> io::Result<bool> {
        self.next_line()
    }

    fn blocks(&self) -> &[Block] {
        match self.line() {
            Some(line) if !self.ended => line.as_slice(),
            _ => &[],
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

    fn collect(source: &mut dyn BlockSource) -> Vec<Vec<Block>> {
        let mut lines = Vec::new();
        while source.advance().unwrap() {
            lines.push(source.blocks().to_vec());
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
        let read = |source: &mut dyn BlockSource| format!("{:?}", collect(source));
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
        assert_eq!(lines.blocks()[0].span.end, 26);
        assert!(lines.advance().unwrap());
        assert_eq!(lines.blocks()[0].span.end, 26 + 2 + 29);
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
