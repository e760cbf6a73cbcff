//! Where the interpreter gets its blocks: a [`BlockSource`] hands them out one line at a time.
//!
//! [`ParsedLines`] reads and parses on demand, on the caller's thread. [`BackgroundParser`] reads
//! and parses on a thread of its own, a few hundred lines ahead, so that a consumer with a second
//! core spends its time interpreting; both give the same blocks (checked by the tests).

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

/// Lines per batch handed from the parser thread.
const BATCH: usize = 1024;

/// Batches in circulation between the parser thread and the interpreter.
const POOL: usize = 4;

/// What the parser thread sends: a batch of parsed lines, or the error that stopped it.
type Batch = io::Result<Vec<LineBlocks>>;

/// Lines read and parsed on a background thread.
#[derive(Debug)]
pub struct BackgroundParser {
    batches: Receiver<Batch>,
    recycle: SyncSender<Vec<LineBlocks>>,
    batch: Vec<LineBlocks>,
    index: usize,
    thread: Option<JoinHandle<()>>,
}

impl BackgroundParser {
    /// Starts reading `reader` (file `file`) on a new thread.
    pub fn spawn<R: Read + Send + 'static>(
        reader: R,
        file: FileId,
        syntax: SyntaxOptions,
    ) -> BackgroundParser {
        BackgroundParser::spawn_expecting(reader, file, syntax, 0)
    }

    /// Starts reading `reader` (file `file`), which holds about `expected_bytes` bytes, on a new
    /// thread. For a long program the buffers of the parsed lines are made at once, here on the
    /// caller's thread: made line by line on the parser's thread, they grew that thread's heap
    /// one page at a time (hundreds of system calls on a 400,000-line program). A short program
    /// gets only what it needs.
    pub fn spawn_expecting<R: Read + Send + 'static>(
        reader: R,
        file: FileId,
        syntax: SyntaxOptions,
        expected_bytes: u64,
    ) -> BackgroundParser {
        // A fixed pool of batches goes round between the two threads: the parser waits for an
        // empty one, so memory stays bounded and the parsed blocks' buffers are reused.
        let (send_batch, batches) = sync_channel::<Batch>(POOL);
        let (recycle, recycled) = sync_channel::<Vec<LineBlocks>>(POOL);
        // Lines are rarely shorter than 16 bytes in a program worth reading ahead.
        let mut made_now = usize::try_from(expected_bytes / 16).unwrap_or(usize::MAX);
        for _ in 0..POOL {
            let lines = made_now.min(BATCH);
            made_now -= lines;
            let mut batch = Vec::with_capacity(BATCH);
            batch.extend((0..lines).map(|_| LineBlocks::with_room(8)));
            let _ = recycle.try_send(batch);
        }
        let thread = std::thread::spawn(move || {
            let mut lines = ReaderLines::new(reader);
            while let Ok(mut batch) = recycled.recv() {
                let mut filled = 0;
                while filled < BATCH {
                    if batch.len() <= filled {
                        batch.push(LineBlocks::new());
                    }
                    match read_next_line(&mut lines, file, &syntax, &mut batch[filled]) {
                        Ok(true) => filled += 1,
                        Ok(false) => break,
                        Err(error) => {
                            let _ = send_batch.send(Err(error));
                            return;
                        }
                    }
                }
                batch.truncate(filled);
                let last = filled < BATCH;
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
            thread: Some(thread),
        }
    }
}

impl BlockSource for BackgroundParser {
    fn advance(&mut self) -> io::Result<bool> {
        self.index += 1;
        if self.index < self.batch.len() {
            return Ok(true);
        }
        let done = std::mem::take(&mut self.batch);
        if done.capacity() > 0 {
            let _ = self.recycle.try_send(done);
        }
        match self.batches.recv() {
            Ok(Ok(batch)) => {
                self.batch = batch;
                self.index = 0;
                Ok(!self.batch.is_empty())
            }
            Ok(Err(error)) => Err(error),
            Err(_) => Ok(false),
        }
    }

    fn blocks(&self) -> &[Block] {
        match self.batch.get(self.index) {
            Some(line) => line.as_slice(),
            None => &[],
        }
    }
}

impl Drop for BackgroundParser {
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
