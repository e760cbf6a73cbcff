//! A main program that jumps, held as an index into its file instead of as parsed text: memory
//! stays flat however long the program is, and a loop costs the parsing of its own lines.
//!
//! The first jump (GOTO, WHILE, M99 P, M97) or call (M98, G65) of a streamed main program makes
//! one pass over the file ([`IndexedFile::scan`]), reading it line by line and keeping, for every
//! [`CHUNK_LINES`] lines, a chunk: the byte offset where it starts, the lowest and highest
//! sequence number its lines start blocks with, and which loop numbers its WHILE/DO and END
//! statements use. Only lines that hold an `N`, `W` or `D` are parsed in that pass (a CAM line
//! has none); the rest are only counted. The same pass notes the `O1234` / `:1234` headers of the
//! programs that follow the main program, so a call finds them without the file's text. The pass
//! runs once, when it is needed, and not as the stream goes: a program without jumps pays nothing,
//! and the stream's hot path is left as it is.
//!
//! After that, the program's lines are read again from the file (a seek) a chunk at a time and
//! parsed with the same reader the stream uses; the last [`CACHED_CHUNKS`] chunks used stay parsed,
//! so the body of a loop stays in memory while it loops. A GOTO looks only at the chunks whose
//! sequence number range holds its target, and the places of a target once found are remembered
//! (up to [`REMEMBERED_LABELS`] numbers); the END of a loop is searched only in the chunks that
//! use its number. The answers are those of [`super::programs::StoredProgram`], which holds the
//! whole program parsed (the differential tests compare the two).
//!
//! What it must never do: hold the file's text, or a parsed block per line of the file. A main
//! program that cannot be read again from any place (a pipe), or whose text the block source
//! holds already, is loaded whole as before (`StoredProgram`); so is a Syntec `%@MACRO` main
//! program (they are small, and their statements need the whole text's structure).

use super::programs::{header_number, sequence_number, starts_code, LoopEnd, Position};
use crate::source::FileId;
use crate::syntax::iso::{parse_line, LineBlocks, SyntaxOptions};
use crate::syntax::lines::{
    memchr_newline, normalize, normalize_read, Line, LineSource, TextLines,
};
use crate::syntax::{Block, Statement};
use std::collections::HashMap;
use std::fs::File;
use std::io::{self, Read, Seek, SeekFrom};
use std::sync::{Arc, Mutex, MutexGuard};

/// Lines per chunk: the unit of the index, of reading again and of the cache.
pub(crate) const CHUNK_LINES: usize = 64;

/// Chunks kept parsed: 1,024 lines, under a megabyte at a few hundred bytes a block.
pub(crate) const CACHED_CHUNKS: usize = 16;

/// Sequence numbers whose places are remembered once searched: a GOTO in a loop searches once.
const REMEMBERED_LABELS: usize = 1024;

#[cfg(test)]
thread_local! {
    /// Chunks kept parsed by the files this thread indexes, instead of [`CACHED_CHUNKS`]: the
    /// tests run whole programs with a tiny cache.
    static TEST_CACHE_BOUND: std::cell::Cell<Option<usize>> = const { std::cell::Cell::new(None) };
}

/// How many chunks stay parsed.
fn cache_bound() -> usize {
    #[cfg(test)]
    if let Some(bound) = TEST_CACHE_BOUND.with(std::cell::Cell::get) {
        return bound;
    }
    CACHED_CHUNKS
}

/// Where the file's bytes are read again from.
#[derive(Debug)]
pub(crate) enum Bytes {
    /// A file that can be read from any place.
    File(File),
    /// Text in memory (the tests).
    #[cfg_attr(not(test), allow(dead_code))]
    Memory(Arc<[u8]>),
}

impl Bytes {
    /// The bytes `start..end`.
    fn read(&mut self, start: u64, end: u64) -> io::Result<Vec<u8>> {
        match self {
            Bytes::File(file) => {
                file.seek(SeekFrom::Start(start))?;
                let mut bytes = Vec::new();
                file.take(end.saturating_sub(start))
                    .read_to_end(&mut bytes)?;
                normalize(&mut bytes, start == 0);
                Ok(bytes)
            }
            Bytes::Memory(text) => {
                let end = usize::try_from(end).unwrap_or(usize::MAX).min(text.len());
                let start = usize::try_from(start).unwrap_or(usize::MAX).min(end);
                let mut bytes = text[start..end].to_vec();
                normalize(&mut bytes, start == 0);
                Ok(bytes)
            }
        }
    }
}

/// What the index keeps of a chunk of lines.
#[derive(Clone, Copy, Debug)]
struct Chunk {
    /// The byte offset of its first line.
    offset: u64,
    /// The lowest and the highest sequence number its blocks start with (low > high: none).
    low: u32,
    high: u32,
    /// Bit `n % 64` is set when a WHILE/DO or END of loop `n` is in it.
    loops: u64,
}

impl Chunk {
    fn at(offset: u64) -> Chunk {
        Chunk {
            offset,
            low: u32::MAX,
            high: 0,
            loops: 0,
        }
    }

    /// Notes the sequence numbers and loops of a line's blocks.
    fn note(&mut self, blocks: &[Block]) {
        for block in blocks {
            if let Some(n) = sequence_number(block) {
                self.low = self.low.min(n);
                self.high = self.high.max(n);
            }
            for statement in &block.statements {
                if let Statement::While { label, .. } | Statement::End { label, .. } = *statement {
                    self.loops |= loop_bit(label);
                }
            }
        }
    }

    fn may_hold_label(&self, n: u32) -> bool {
        (self.low..=self.high).contains(&n)
    }
}

/// Calls `each` with every line `reader` reads, its `\n` included (the last line may have none),
/// read through one buffer in large blocks.
fn for_each_line(mut reader: impl Read, mut each: impl FnMut(&[u8])) -> io::Result<()> {
    let mut buffer = vec![0u8; 1 << 20];
    // `buffer[start..searched]` is known to hold no `\n`; `buffer[0]` is at `offset` in the file.
    let (mut start, mut searched, mut end) = (0usize, 0usize, 0usize);
    let mut offset = 0u64;
    loop {
        if let Some(i) = memchr_newline(&buffer[searched..end]) {
            each(&buffer[start..=searched + i]);
            start = searched + i + 1;
            searched = start;
            continue;
        }
        buffer.copy_within(start..end, 0);
        offset += start as u64;
        end -= start;
        start = 0;
        // The last byte may be a `\r` that the read turns into a line end.
        searched = end.saturating_sub(1);
        if end == buffer.len() {
            buffer.resize(end * 2, 0);
        }
        let read = match reader.read(&mut buffer[end..]) {
            Err(error) if error.kind() == io::ErrorKind::Interrupted => continue,
            read => read?,
        };
        if read == 0 {
            if end > 0 {
                each(&buffer[..end]);
            }
            return Ok(());
        }
        normalize_read(&mut buffer, end, end + read, offset);
        end += read;
    }
}

fn loop_bit(label: u32) -> u64 {
    1 << (label % 64)
}

/// Lines of the main program, parsed: chunk `first / CHUNK_LINES`.
#[derive(Debug)]
pub(crate) struct ParsedChunk {
    first: usize,
    lines: Vec<LineBlocks>,
}

impl ParsedChunk {
    /// The blocks of line `line` (an index in the program), if this chunk has it.
    #[inline]
    pub(crate) fn line(&self, line: usize) -> Option<&[Block]> {
        self.lines
            .get(line.checked_sub(self.first)?)
            .map(LineBlocks::as_slice)
    }
}

/// What changes as the program runs: the bytes' reader and what was parsed and searched.
#[derive(Debug)]
struct Cache {
    bytes: Bytes,
    /// (chunk, last use, lines): at most `bound` of them.
    chunks: Vec<(usize, u64, Arc<ParsedChunk>)>,
    bound: usize,
    clock: u64,
    labels: HashMap<u32, Arc<[Position]>>,
}

/// A file whose main program runs from an index (see the module doc).
#[derive(Debug)]
pub(crate) struct IndexedFile {
    file: FileId,
    syntax: SyntaxOptions,
    /// (program number, byte offset, line number) of each program header of the file.
    headers: Vec<(u32, u64, u32)>,
    /// The file's length, bytes.
    length: u64,
    /// Where the main program ends, bytes, and its number of lines.
    main_end: u64,
    lines: usize,
    chunks: Vec<Chunk>,
    cache: Mutex<Cache>,
}

impl IndexedFile {
    /// Indexes the text `reader` reads (file `file`); `bytes` reads it again later.
    ///
    /// # Errors
    /// Whatever reading reports.
    pub(crate) fn scan(
        reader: impl Read,
        bytes: Bytes,
        file: FileId,
        syntax: SyntaxOptions,
    ) -> io::Result<IndexedFile> {
        let mut blocks = LineBlocks::new();
        let mut chunks = Vec::new();
        let mut headers = Vec::new();
        let mut runs_before_header = false;
        let (mut offset, mut number) = (0u64, 0u32);
        for_each_line(reader, |raw| {
            let index = number as usize;
            number = number.saturating_add(1);
            if index.is_multiple_of(CHUNK_LINES) {
                chunks.push(Chunk::at(offset));
            }
            let line = raw.strip_suffix(b"\n").unwrap_or(raw);
            if let Some(n) = header_number(line, &syntax) {
                headers.push((n, offset, number));
            } else if headers.is_empty() && starts_code(line) {
                runs_before_header = true;
            }
            // Without an early exit the test runs on whole vectors of bytes.
            let may_matter = line.iter().fold(false, |found, &b| {
                found | matches!(b | 0x20, b'n' | b'w' | b'd')
            });
            if may_matter {
                let line = Line {
                    text: line.strip_suffix(b"\r").unwrap_or(line),
                    offset: u32::try_from(offset).unwrap_or(u32::MAX),
                    number,
                };
                parse_line(line, file, &syntax, &mut blocks);
                let chunk = chunks.last_mut().expect("pushed at the chunk's first line");
                chunk.note(blocks.as_slice());
            }
            offset += raw.len() as u64;
        })?;
        // As `main_program_end`: the main program ends at the second header, or at the first
        // when something runs before it (the first is then a subprogram's).
        let end_header = if runs_before_header {
            headers.first()
        } else {
            headers.get(1)
        };
        let (main_end, lines) = match end_header {
            Some(&(_, at, line)) => (at, line as usize - 1),
            None => (offset, number as usize),
        };
        Ok(IndexedFile {
            file,
            syntax,
            headers,
            length: offset,
            main_end,
            lines,
            chunks,
            cache: Mutex::new(Cache {
                bytes,
                chunks: Vec::new(),
                bound: cache_bound(),
                clock: 0,
                labels: HashMap::new(),
            }),
        })
    }

    /// Sets how many chunks stay parsed (the tests make it tiny).
    #[cfg(test)]
    pub(crate) fn keep_chunks(&self, bound: usize) {
        self.lock().bound = bound.max(1);
    }

    fn lock(&self) -> MutexGuard<'_, Cache> {
        // A panic while the lock was held left nothing half-done that matters: the cache is
        // only a cache.
        self.cache
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    }

    /// The main program's number of lines.
    pub(crate) fn lines(&self) -> usize {
        self.lines
    }

    /// The chunk that holds line `line` of the main program, parsed; `None` past its end.
    ///
    /// # Errors
    /// Reading the file again failed.
    pub(crate) fn chunk_of(&self, line: usize) -> io::Result<Option<Arc<ParsedChunk>>> {
        if line >= self.lines {
            return Ok(None);
        }
        self.chunk(line / CHUNK_LINES).map(Some)
    }

    fn chunk(&self, index: usize) -> io::Result<Arc<ParsedChunk>> {
        let mut cache = self.lock();
        cache.clock += 1;
        let clock = cache.clock;
        if let Some(entry) = cache.chunks.iter_mut().find(|e| e.0 == index) {
            entry.1 = clock;
            return Ok(Arc::clone(&entry.2));
        }
        let start = self.chunks[index].offset;
        let end = self
            .chunks
            .get(index + 1)
            .map_or(self.main_end, |c| c.offset)
            .min(self.main_end);
        let bytes = cache.bytes.read(start, end)?;
        let first = index * CHUNK_LINES;
        let base = usize::try_from(start).unwrap_or(usize::MAX);
        let mut source = TextLines::piece(&bytes, base, first as u32 + 1);
        let mut lines = Vec::with_capacity(CHUNK_LINES);
        while let Some(line) = source.next_line()? {
            let mut blocks = LineBlocks::new();
            parse_line(line, self.file, &self.syntax, &mut blocks);
            lines.push(blocks);
        }
        let parsed = Arc::new(ParsedChunk { first, lines });
        if cache.chunks.len() >= cache.bound {
            let oldest = (0..cache.chunks.len())
                .min_by_key(|&i| cache.chunks[i].1)
                .expect("the cache is not empty");
            cache.chunks.swap_remove(oldest);
        }
        cache.chunks.push((index, clock, Arc::clone(&parsed)));
        Ok(parsed)
    }

    /// Every place of sequence number `n` in the main program, in order.
    fn label_places(&self, n: u32) -> io::Result<Arc<[Position]>> {
        if let Some(places) = self.lock().labels.get(&n) {
            return Ok(Arc::clone(places));
        }
        let mut places = Vec::new();
        for (index, _) in self
            .chunks
            .iter()
            .enumerate()
            .filter(|(_, c)| c.may_hold_label(n))
        {
            let chunk = self.chunk(index)?;
            for (i, blocks) in chunk.lines.iter().enumerate() {
                for (b, block) in blocks.as_slice().iter().enumerate() {
                    if sequence_number(block) == Some(n) {
                        places.push((chunk.first + i, b));
                    }
                }
            }
        }
        let places: Arc<[Position]> = places.into();
        let mut cache = self.lock();
        if cache.labels.len() >= REMEMBERED_LABELS {
            cache.labels.clear();
        }
        cache.labels.insert(n, Arc::clone(&places));
        Ok(places)
    }

    /// The block with sequence number `n`: the first after `from` if there is one, else the
    /// first in the program (as [`super::programs::StoredProgram::find_label`]).
    ///
    /// # Errors
    /// Reading the file again failed.
    pub(crate) fn find_label(
        &self,
        n: u32,
        from: Option<Position>,
    ) -> io::Result<Option<Position>> {
        let places = self.label_places(n)?;
        let after = from.and_then(|from| places.iter().find(|&&p| p > from));
        Ok(after.or(places.first()).copied())
    }

    /// Where loop `label`'s END is, for the WHILE at `from` (as
    /// [`super::programs::StoredProgram::find_loop_end`]).
    ///
    /// # Errors
    /// Reading the file again failed.
    pub(crate) fn find_loop_end(&self, from: Position, label: u32) -> io::Result<Option<Position>> {
        let mut search = LoopEnd::new(label);
        let bit = loop_bit(label);
        for index in from.0 / CHUNK_LINES..self.chunks.len() {
            if self.chunks[index].loops & bit == 0 {
                continue;
            }
            let chunk = self.chunk(index)?;
            for (i, blocks) in chunk.lines.iter().enumerate() {
                let l = chunk.first + i;
                for (b, block) in blocks.as_slice().iter().enumerate() {
                    if (l, b) > from && search.is_end(block) {
                        return Ok(Some((l, b)));
                    }
                }
            }
        }
        Ok(None)
    }

    /// The text of the program whose header says `number`: (text, its byte offset in the file,
    /// its first line's number). The first such header counts, as in a file held whole.
    ///
    /// # Errors
    /// Reading the file again failed.
    pub(crate) fn program_text(&self, number: u32) -> io::Result<Option<(Vec<u8>, u64, u32)>> {
        let extent = super::programs::program_extent(&self.headers, number, self.length);
        let Some((start, line, end)) = extent else {
            return Ok(None);
        };
        let text = self.lock().bytes.read(start, end)?;
        Ok(Some((text, start, line)))
    }

    /// The main program's text, whole: for a main program that must run from memory after all
    /// (a Syntec `%@MACRO` program).
    ///
    /// # Errors
    /// Reading the file again failed.
    pub(crate) fn main_text(&self) -> io::Result<Vec<u8>> {
        self.lock().bytes.read(0, self.main_end)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::interp::macros::programs::StoredProgram;

    fn indexed(text: &str) -> IndexedFile {
        let bytes = Bytes::Memory(Arc::from(text.as_bytes()));
        IndexedFile::scan(text.as_bytes(), bytes, FileId(0), SyntaxOptions::default())
            .expect("memory reads")
    }

    fn stored(text: &str) -> StoredProgram {
        let syntax = SyntaxOptions::default();
        let headers = super::super::programs::program_headers(text.as_bytes(), &syntax);
        let end = super::super::programs::main_program_end(text.as_bytes(), &headers);
        StoredProgram::parse(text.as_bytes(), (0, 1, end), FileId(0), &syntax, None)
    }

    /// Every line of the index, by its chunks, as text.
    fn all_lines(index: &IndexedFile) -> Vec<String> {
        (0..index.lines())
            .map(|l| {
                let chunk = index.chunk_of(l).unwrap().unwrap();
                format!("{:?}", chunk.line(l).unwrap())
            })
            .collect()
    }

    /// A program with labels, loops and programs after its end, 300 lines and more.
    fn program() -> String {
        let mut text = String::from("%\nO0001 (MAIN)\n#1=0\n");
        for i in 0..300 {
            match i % 50 {
                0 => text.push_str(&format!("N{} WHILE[#1LT2]DO{}\n", i + 10, 1 + i / 50)),
                7 => text.push_str(&format!("END{}\n", 1 + i / 50)),
                9 => text.push_str(&format!("N{} G1 X{i}. ; N5 G0 Y1.\n", i + 10)),
                _ => text.push_str(&format!("G1 X{i}. Y1.\r\n")),
            }
        }
        text.push_str("N5 GOTO 10\nM30\nO2000\nN5 G1 X1.\nM99\n:3000\nM99");
        text
    }

    #[test]
    fn the_index_gives_the_lines_labels_and_loop_ends_of_the_whole_parse() {
        let text = program();
        let index = indexed(&text);
        let whole = stored(&text);
        let expected: Vec<String> = (0..)
            .map_while(|l| whole.line(l).map(|b| format!("{b:?}")))
            .collect();
        assert_eq!(index.lines(), expected.len());
        assert_eq!(all_lines(&index), expected);
        for n in [1, 5, 10, 19, 60, 69, 309, 400] {
            for from in [
                None,
                Some((0, 0)),
                Some((100, 0)),
                Some((300, 1)),
                Some((310, 0)),
            ] {
                assert_eq!(
                    index.find_label(n, from).unwrap(),
                    whole.find_label(n, from),
                    "N{n} from {from:?}"
                );
            }
        }
        for at in [(3, 0), (53, 0), (103, 0), (10, 0)] {
            for label in 1..8 {
                assert_eq!(
                    index.find_loop_end(at, label).unwrap(),
                    whole.find_loop_end(at, label),
                    "DO{label} at {at:?}"
                );
            }
        }
        let (sub, base, line) = index.program_text(2000).unwrap().unwrap();
        assert!(sub.starts_with(b"O2000\n") && sub.ends_with(b"M99\n"));
        assert_eq!(
            (&text.as_bytes()[base as usize..][..5], line),
            (&b"O2000"[..], 306)
        );
        assert!(index.program_text(3000).unwrap().is_some());
        assert!(index.program_text(1).unwrap().is_some());
        assert!(index.program_text(4).unwrap().is_none());
    }

    #[test]
    fn a_tiny_cache_evicts_and_parses_again_to_the_same_lines() {
        let text = program();
        let roomy = indexed(&text);
        let tiny = indexed(&text);
        tiny.keep_chunks(1);
        let expected = all_lines(&roomy);
        // Forward, backward and forward again over every chunk boundary.
        assert_eq!(all_lines(&tiny), expected);
        let backward: Vec<String> = (0..tiny.lines())
            .rev()
            .map(|l| format!("{:?}", tiny.chunk_of(l).unwrap().unwrap().line(l).unwrap()))
            .collect();
        assert!(backward.iter().rev().eq(expected.iter()));
        assert!(tiny.lock().chunks.len() <= 1);
        assert_eq!(tiny.find_label(10, Some((200, 0))).unwrap(), Some((3, 0)));
        assert_eq!(tiny.find_loop_end((103, 0), 3).unwrap(), Some((110, 0)));
    }

    #[test]
    fn a_run_that_jumps_over_evicted_chunks_gives_the_stream_of_the_whole_text() {
        use crate::interp::{DirectoryLibrary, Interpreter, Options};
        use crate::syntax::lines::ReaderLines;
        use crate::Machine;
        // Backward from far down, forward over thousands of lines, a loop longer than the cache.
        let mut text = String::from("G90 G01 F1000.\n#1=0\nN10 #1=#1+1\n");
        let moves = |from: usize, lines: usize| -> String {
            (from..from + lines)
                .map(|i| format!("G01 X{}. Y{}.\n", i % 97, i % 13))
                .collect()
        };
        text.push_str(&moves(0, 300));
        text.push_str("IF[#1LT3]GOTO10\nWHILE[#1LT5]DO1\n");
        text.push_str(&moves(1000, 200));
        text.push_str("#1=#1+1\nEND1\nIF[#1GT4]GOTO40\n");
        text.push_str(&moves(2000, 400));
        text.push_str("N40 M97 P10\nM30\n");
        let path = std::env::temp_dir().join(format!("vcnc-indexed-{}.nc", std::process::id()));
        std::fs::write(&path, &text).unwrap();
        let machine = Machine::default();
        let describe = |items: &mut dyn Iterator<Item = crate::StreamItem>| {
            items.map(|item| format!("{item:?}")).collect::<Vec<_>>()
        };
        let whole = describe(&mut crate::interpret_str(
            &text,
            &machine,
            Options::default(),
        ));
        for bound in [1, 2] {
            TEST_CACHE_BOUND.with(|b| b.set(Some(bound)));
            let lines = ReaderLines::new(std::fs::File::open(&path).unwrap());
            let library = DirectoryLibrary::new(Some(path.clone()), Vec::new(), 1);
            let mut run = Interpreter::new(lines, FileId(0), &machine, Options::default())
                .with_library(Box::new(library));
            assert_eq!(describe(&mut run), whole, "{bound} chunks kept");
        }
        TEST_CACHE_BOUND.with(|b| b.set(None));
        let _ = std::fs::remove_file(&path);
        assert!(whole.len() > 3 * 300 + 2 * 200, "the loops ran");
    }

    #[test]
    fn lines_cut_by_reads_and_longer_than_the_buffer_come_whole() {
        use crate::syntax::lines::tests::Trickle;
        let mut text = b"G1 X1.\r\n\nN10 G1 Y2.\n".to_vec();
        text.extend(std::iter::repeat_n(b'X', 3 << 20));
        text.extend_from_slice(b"\nM30");
        let expected: Vec<&[u8]> = text.split_inclusive(|&b| b == b'\n').collect();
        for chunk in [1, 3, 1 << 16] {
            let mut lines = Vec::new();
            let reader = Trickle { data: &text, chunk };
            for_each_line(reader, |line| lines.push(line.to_vec())).unwrap();
            assert_eq!(lines, expected, "reads of {chunk} bytes");
        }
    }

    #[test]
    fn something_that_runs_before_the_first_header_makes_it_a_subprograms() {
        let text = "G1 X1.\nM30\nO2000\nG1 X2.\nM99\n";
        let index = indexed(text);
        assert_eq!(index.lines(), 2);
        let text = "%\n(T)\nO1\nG1 X1.\nM30\nO2000\nM99\n";
        assert_eq!(indexed(text).lines(), 5);
        let text = "G1 X1.\nM30";
        assert_eq!(indexed(text).lines(), 2);
    }
}
