//! Programs held in memory: the subprograms and macros a program calls, and the main program
//! itself once it jumps (GOTO, WHILE, M99).
//!
//! A control keeps its programs in memory, so a jump is a search of text it already has. vcnc
//! streams a main program that runs straight through and holds nothing of it; the first jump
//! loads it (from the block source's text, or through the [`ProgramLibrary`]) and parses it
//! once. Called programs come from the same file (programs that follow M30, each headed by
//! `O1234` or `:1234`) or from the library (a program directory). A Syntec `%@MACRO` program
//! is read statement by statement and keeps the structure of its IF and loop statements; it
//! always runs from memory (`structured.rs`). A main program read from a file that can be read
//! again from any place does not load whole: it runs from an index into the file
//! (`indexed.rs`), and the programs after its M30 are found by the index's headers.

use super::indexed::IndexedFile;
use crate::source::FileId;
use crate::syntax::iso::structure::Structure;
use crate::syntax::iso::{
    parse_program, parse_program_piece, LineBlocks, ProgramBlocks, SyntaxOptions,
};
use crate::syntax::lines::normalize;
use crate::syntax::{Block, BlockKind};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

/// The text of a program the library found.
#[derive(Clone, Debug)]
pub struct ProgramText {
    /// The file id the program's spans carry (the caller keeps the file for diagnostics).
    pub file: FileId,
    /// The text.
    pub text: Arc<[u8]>,
}

/// Why a library cannot give a program it has.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum LookupError {
    /// More than one file could be the program: their paths, in name order.
    #[error("program O{number:04} is in more than one file: {}", list(.files))]
    Ambiguous {
        /// The program number.
        number: u32,
        /// The files that hold it.
        files: Vec<PathBuf>,
    },
    /// The program's file was found and cannot be read.
    #[error("program O{number:04} is in {}, which cannot be read: {error}", .path.display())]
    Unreadable {
        /// The program number.
        number: u32,
        /// The file.
        path: PathBuf,
        /// What the system said.
        error: String,
    },
    /// A program called by name (SINUMERIK) was found and cannot be read.
    #[error("program {name} is in {}, which cannot be read: {error}", .path.display())]
    NamedUnreadable {
        /// The program's name.
        name: String,
        /// The file.
        path: PathBuf,
        /// What the system said.
        error: String,
    },
}

/// `a`, `b` and `c`.
fn list(files: &[PathBuf]) -> String {
    let names: Vec<String> = files.iter().map(|f| f.display().to_string()).collect();
    match names.split_last() {
        Some((last, [])) => last.clone(),
        Some((last, rest)) => format!("{} and {last}", rest.join(", ")),
        None => String::new(),
    }
}

/// Where the interpreter finds programs that are not in the main program's file.
pub trait ProgramLibrary: Send {
    /// Program `number` (`O1234`), if the library has it.
    ///
    /// # Errors
    /// [`LookupError`]: the program is in several files, or its file cannot be read.
    fn find(&mut self, number: u32) -> Result<Option<ProgramText>, LookupError>;

    /// The program called by `name` (SINUMERIK: `L100`, `CHAMFER`; upper case, no
    /// extension), if the library has it.
    ///
    /// # Errors
    /// [`LookupError`]: the program's file cannot be read.
    fn find_named(&mut self, name: &str) -> Result<Option<ProgramText>, LookupError> {
        let _ = name;
        Ok(None)
    }

    /// The main program's text, when the block source streams it and cannot give it whole.
    fn main_text(&mut self) -> Option<Arc<[u8]>> {
        None
    }

    /// The main program's file opened again, when it can be read from any place (a regular
    /// file, not a pipe): a main program that jumps runs from an index into it instead of
    /// from its whole text ([`ProgramLibrary::main_text`]).
    fn open_main(&mut self) -> Option<std::fs::File> {
        None
    }
}

/// Programs held in memory by number: for tests and for callers that have the text already.
#[derive(Clone, Debug, Default)]
pub struct MemoryLibrary {
    programs: HashMap<u32, ProgramText>,
    named: HashMap<String, ProgramText>,
}

impl MemoryLibrary {
    /// An empty library.
    pub fn new() -> MemoryLibrary {
        MemoryLibrary::default()
    }

    /// Adds program `number` with `text`, whose spans will carry `file`.
    pub fn insert(&mut self, number: u32, file: FileId, text: &str) {
        let mut text = text.as_bytes().to_vec();
        normalize(&mut text, true);
        self.programs.insert(
            number,
            ProgramText {
                file,
                text: Arc::from(text),
            },
        );
    }
}

impl MemoryLibrary {
    /// Adds the program called by `name` (any case; an extension such as `.SPF` is dropped)
    /// with `text`, whose spans will carry `file`.
    pub fn insert_named(&mut self, name: &str, file: FileId, text: &str) {
        self.named.insert(
            program_name(name),
            ProgramText {
                file,
                text: Arc::from(text.as_bytes()),
            },
        );
    }
}

/// A program's name as calls use it: upper case, without an extension.
fn program_name(name: &str) -> String {
    let stem = name.rsplit_once('.').map_or(name, |(stem, _)| stem);
    stem.to_ascii_uppercase()
}

impl ProgramLibrary for MemoryLibrary {
    fn find(&mut self, number: u32) -> Result<Option<ProgramText>, LookupError> {
        Ok(self.programs.get(&number).cloned())
    }

    fn find_named(&mut self, name: &str) -> Result<Option<ProgramText>, LookupError> {
        Ok(self.named.get(&program_name(name)).cloned())
    }
}

/// The files a [`DirectoryLibrary`] has read, by the file id it gave each: the caller renders
/// diagnostics in them.
pub type LoadedFiles = Arc<Mutex<Vec<(FileId, PathBuf)>>>;

/// Programs in directories: files named exactly for the number, `O1234`, `O1234.nc`, `1234.nc`
/// (any extension, any case, leading zeros or none), and files named otherwise that hold an
/// `O1234` header line; and the main program's file, indexed when it jumps or calls (read whole
/// when it is not a regular file). A name that only contains the number (`part_O1234.nc`) does
/// not count. The first directory that has the program gives it; two files of that directory
/// that could both be it are an alarm ([`LookupError::Ambiguous`]).
#[derive(Debug)]
pub struct DirectoryLibrary {
    main: Option<PathBuf>,
    directories: Vec<PathBuf>,
    /// The files that could be each program, from the first directory that has it.
    index: Option<HashMap<u32, Vec<PathBuf>>>,
    next_file: u32,
    loaded: LoadedFiles,
}

impl DirectoryLibrary {
    /// A library over `directories`; `main` is the main program's file; the files it reads get
    /// ids from `first_file` on.
    pub fn new(
        main: Option<PathBuf>,
        directories: Vec<PathBuf>,
        first_file: u32,
    ) -> DirectoryLibrary {
        DirectoryLibrary {
            main,
            directories,
            index: None,
            next_file: first_file,
            loaded: LoadedFiles::default(),
        }
    }

    /// The files read so far, shared: it fills as the program runs.
    pub fn loaded_files(&self) -> LoadedFiles {
        Arc::clone(&self.loaded)
    }

    /// The program in the file at `path`, with the next file id, recorded as loaded; `unreadable`
    /// says what a read error is.
    fn read(
        &mut self,
        path: PathBuf,
        unreadable: impl FnOnce(PathBuf, String) -> LookupError,
    ) -> Result<ProgramText, LookupError> {
        let mut text = match std::fs::read(&path) {
            Ok(text) => text,
            Err(error) => return Err(unreadable(path, error.to_string())),
        };
        normalize(&mut text, true);
        let file = FileId(self.next_file);
        self.next_file += 1;
        if let Ok(mut loaded) = self.loaded.lock() {
            loaded.push((file, path));
        }
        Ok(ProgramText {
            file,
            text: Arc::from(text),
        })
    }

    fn index(&mut self) -> &HashMap<u32, Vec<PathBuf>> {
        self.index.get_or_insert_with(|| {
            let mut index: HashMap<u32, Vec<PathBuf>> = HashMap::new();
            for directory in &self.directories {
                for (number, files) in directory_programs(directory) {
                    index.entry(number).or_insert(files);
                }
            }
            index
        })
    }
}

/// The programs of one directory: for each number, the files that could be it, in name order.
fn directory_programs(directory: &Path) -> HashMap<u32, Vec<PathBuf>> {
    let mut programs: HashMap<u32, Vec<PathBuf>> = HashMap::new();
    let Ok(entries) = std::fs::read_dir(directory) else {
        return programs;
    };
    let mut paths: Vec<PathBuf> = entries.flatten().map(|e| e.path()).collect();
    paths.sort();
    for path in paths {
        if let Some(number) = program_number_of_file(&path) {
            programs.entry(number).or_default().push(path);
            continue;
        }
        // Files named otherwise are found by the `O1234` headers in them.
        let mut numbers = header_numbers_of_file(&path);
        numbers.sort_unstable();
        numbers.dedup();
        for number in numbers {
            programs.entry(number).or_default().push(path.clone());
        }
    }
    programs
}

/// The numbers of the `O1234` header lines in the first part of the file at `path` (none when
/// it is not a regular file or cannot be read).
fn header_numbers_of_file(path: &Path) -> Vec<u32> {
    if !path.is_file() {
        return Vec::new();
    }
    let Ok(file) = std::fs::File::open(path) else {
        return Vec::new();
    };
    let mut head = Vec::new();
    if std::io::Read::read_to_end(&mut std::io::Read::take(file, HEADER_SCAN), &mut head).is_err() {
        return Vec::new();
    }
    normalize(&mut head, true);
    program_headers(&head, &SyntaxOptions::default())
        .into_iter()
        .map(|(number, _, _)| number)
        .collect()
}

/// How much of a file is searched for program headers when its name is not a program number.
const HEADER_SCAN: u64 = 1 << 20;

/// `O1234.nc`, `o0012`, `1234.NC` → the program number.
fn program_number_of_file(path: &Path) -> Option<u32> {
    if !path.is_file() {
        return None;
    }
    let stem = path.file_stem()?.to_str()?;
    let digits = stem
        .strip_prefix('O')
        .or_else(|| stem.strip_prefix('o'))
        .unwrap_or(stem);
    if digits.is_empty() || digits.len() > 8 || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    digits.parse().ok()
}

impl ProgramLibrary for DirectoryLibrary {
    fn find(&mut self, number: u32) -> Result<Option<ProgramText>, LookupError> {
        let path = match self.index().get(&number).map(Vec::as_slice) {
            None | Some([]) => return Ok(None),
            Some([path]) => path.clone(),
            Some(files) => {
                return Err(LookupError::Ambiguous {
                    number,
                    files: files.to_vec(),
                })
            }
        };
        self.read(path, |path, error| LookupError::Unreadable {
            number,
            path,
            error,
        })
        .map(Some)
    }

    fn find_named(&mut self, name: &str) -> Result<Option<ProgramText>, LookupError> {
        // SINUMERIK keeps programs as NAME.SPF or NAME.MPF (any case); the first directory that
        // has one gives it, a subprogram before a main program.
        let wanted = program_name(name);
        let found = self.directories.iter().find_map(|directory| {
            let entries = std::fs::read_dir(directory).ok()?;
            let mut matches: Vec<PathBuf> = entries
                .flatten()
                .map(|e| e.path())
                .filter(|path| {
                    path.is_file()
                        && path.file_name().and_then(|n| n.to_str()).is_some_and(|n| {
                            program_name(n) == wanted
                                && n.rsplit_once('.').is_some_and(|(_, ext)| {
                                    ext.eq_ignore_ascii_case("SPF")
                                        || ext.eq_ignore_ascii_case("MPF")
                                })
                        })
                })
                .collect();
            // SPF sorts after MPF: a subprogram named like a main program wins.
            matches.sort_by_key(|p| {
                let spf = p.extension().is_some_and(|e| e.eq_ignore_ascii_case("SPF"));
                (!spf, p.clone())
            });
            matches.into_iter().next()
        });
        let Some(path) = found else {
            return Ok(None);
        };
        self.read(path, |path, error| LookupError::NamedUnreadable {
            name: wanted,
            path,
            error,
        })
        .map(Some)
    }

    fn main_text(&mut self) -> Option<Arc<[u8]>> {
        let mut text = std::fs::read(self.main.as_ref()?).ok()?;
        normalize(&mut text, true);
        Some(Arc::from(text))
    }

    fn open_main(&mut self) -> Option<std::fs::File> {
        let file = std::fs::File::open(self.main.as_ref()?).ok()?;
        file.metadata().ok()?.is_file().then_some(file)
    }
}

/// A sequence number's place in a program: line index and block index in the line.
pub(crate) type Position = (usize, usize);

/// A program the run can jump in: parsed whole, or a main program run from an index into its
/// file (`indexed.rs`).
#[derive(Clone, Debug)]
pub(crate) enum Program {
    Stored(Arc<StoredProgram>),
    Indexed(Arc<IndexedFile>),
}

impl Program {
    /// The program number of its header, if it has one (a main program has none here).
    pub(crate) fn number(&self) -> Option<u32> {
        match self {
            Program::Stored(program) => program.number,
            Program::Indexed(_) => None,
        }
    }

    /// True when the program has line `line` (an index).
    pub(crate) fn has_line(&self, line: usize) -> bool {
        match self {
            Program::Stored(program) => program.line(line).is_some(),
            Program::Indexed(file) => line < file.lines(),
        }
    }

    /// Where the program starts again after M99: after the `%` that opens the tape, when one
    /// comes before anything else runs (read there again, it would end the program), else at
    /// its first line. Leading lines with nothing to run (blank, comments only) are looked
    /// through; the search stops at the first line that has something.
    ///
    /// # Errors
    /// Reading an indexed program's file again failed.
    pub(crate) fn start_after_tape_mark(&self) -> std::io::Result<Position> {
        let mut line = 0;
        loop {
            let blocks = match self {
                Program::Stored(program) => program.line(line).map(<[Block]>::to_vec),
                Program::Indexed(file) => file
                    .chunk_of(line)?
                    .and_then(|chunk| chunk.line(line).map(<[Block]>::to_vec)),
            };
            let Some(blocks) = blocks else {
                return Ok((0, 0));
            };
            match blocks.iter().find(|block| !block.is_empty()) {
                None => line += 1,
                Some(block) if block.kind == BlockKind::TapeMark => return Ok((line + 1, 0)),
                Some(_) => return Ok((0, 0)),
            }
        }
    }

    /// [`StoredProgram::find_label`].
    ///
    /// # Errors
    /// Reading an indexed program's file again failed.
    pub(crate) fn find_label(
        &self,
        n: u32,
        from: Option<Position>,
    ) -> std::io::Result<Option<Position>> {
        match self {
            Program::Stored(program) => Ok(program.find_label(n, from)),
            Program::Indexed(file) => file.find_label(n, from),
        }
    }

    /// [`StoredProgram::find_loop_end`].
    ///
    /// # Errors
    /// Reading an indexed program's file again failed.
    pub(crate) fn find_loop_end(
        &self,
        from: Position,
        label: u32,
    ) -> std::io::Result<Option<Position>> {
        match self {
            Program::Stored(program) => Ok(program.find_loop_end(from, label)),
            Program::Indexed(file) => file.find_loop_end(from, label),
        }
    }
}

/// One program, parsed, with its sequence numbers indexed.
#[derive(Debug)]
pub(crate) struct StoredProgram {
    /// The program number of its header, if it has one.
    pub(crate) number: Option<u32>,
    lines: Vec<LineBlocks>,
    /// (sequence number, line, block), sorted.
    labels: Vec<(u32, usize, usize)>,
    /// A Syntec `%@MACRO` program: the partners of its structured statements.
    structure: Option<Structure>,
}

impl StoredProgram {
    /// Parses the lines of `text` from byte `offset` (line `line`) up to byte `end`: an ISO
    /// program line by line, a Syntec `%@MACRO` program statement by statement.
    pub(crate) fn parse(
        text: &[u8],
        (offset, line, end): (usize, u32, usize),
        file: FileId,
        syntax: &SyntaxOptions,
        number: Option<u32>,
    ) -> StoredProgram {
        let end = end.min(text.len());
        let program = parse_program(&text[..end], offset, line, file, syntax);
        StoredProgram::from_blocks(program, number)
    }

    /// Parses `text`, a program alone, cut out of a file where it starts at byte `base` and line
    /// `line`: spans are the file's.
    pub(crate) fn parse_piece(
        text: &[u8],
        (base, line): (usize, u32),
        file: FileId,
        syntax: &SyntaxOptions,
        number: Option<u32>,
    ) -> StoredProgram {
        let program = parse_program_piece(text, base, line, file, syntax);
        StoredProgram::from_blocks(program, number)
    }

    fn from_blocks(program: ProgramBlocks, number: Option<u32>) -> StoredProgram {
        let mut labels = Vec::new();
        for (l, blocks) in program.lines.iter().enumerate() {
            for (b, block) in blocks.as_slice().iter().enumerate() {
                if let Some(n) = sequence_number(block) {
                    labels.push((n, l, b));
                }
            }
        }
        labels.sort_unstable();
        StoredProgram {
            number,
            lines: program.lines,
            labels,
            structure: program.structure,
        }
    }

    /// The partners of the structured statements, for a Syntec `%@MACRO` program.
    pub(crate) fn structure(&self) -> Option<&Structure> {
        self.structure.as_ref()
    }

    /// The block at `at`.
    pub(crate) fn block(&self, (line, block): Position) -> Option<&Block> {
        self.line(line)?.get(block)
    }

    /// The blocks of line `line`.
    #[inline]
    pub(crate) fn line(&self, line: usize) -> Option<&[Block]> {
        self.lines.get(line).map(LineBlocks::as_slice)
    }

    /// The block with sequence number `n`: the first after `from` if there is one (a GOTO
    /// searches forward first), else the first in the program.
    pub(crate) fn find_label(&self, n: u32, from: Option<Position>) -> Option<Position> {
        let first = self.labels.partition_point(|&(label, _, _)| label < n);
        let matching = self.labels[first..]
            .iter()
            .take_while(|&&(label, _, _)| label == n)
            .map(|&(_, line, block)| (line, block));
        let mut earliest = None;
        for position in matching {
            if from.is_some_and(|from| position > from) {
                return Some(position);
            }
            earliest.get_or_insert(position);
        }
        earliest
    }

    /// Where loop `label`'s END is, for the WHILE at `from`: the first END with that number
    /// after it, counting nested loops of the same number.
    pub(crate) fn find_loop_end(&self, from: Position, label: u32) -> Option<Position> {
        let mut search = LoopEnd::new(label);
        let (start_line, start_block) = from;
        for (l, line) in self.lines.iter().enumerate().skip(start_line) {
            for (b, block) in line.as_slice().iter().enumerate() {
                if l == start_line && b <= start_block {
                    continue;
                }
                if search.is_end(block) {
                    return Some((l, b));
                }
            }
        }
        None
    }
}

/// The search for the END of loop `label` over the blocks after its WHILE, in order: nested
/// loops of the same number are counted.
pub(crate) struct LoopEnd {
    label: u32,
    depth: usize,
}

impl LoopEnd {
    pub(crate) fn new(label: u32) -> LoopEnd {
        LoopEnd { label, depth: 0 }
    }

    /// True when `block`, the next block, holds the END searched for.
    pub(crate) fn is_end(&mut self, block: &Block) -> bool {
        use crate::syntax::Statement;
        for statement in &block.statements {
            match *statement {
                Statement::While { label, .. } if label == self.label => self.depth += 1,
                Statement::End { label, .. } if label == self.label => {
                    if self.depth == 0 {
                        return true;
                    }
                    self.depth -= 1;
                }
                _ => {}
            }
        }
        false
    }
}

/// The sequence number a block starts with, if any.
pub(crate) fn sequence_number(block: &Block) -> Option<u32> {
    let word = block.words.first().filter(|w| w.letter == b'N')?;
    word.number.whole().and_then(|n| u32::try_from(n).ok())
}

/// Where program `number` lies among the `headers` (number, start, line) of a text of `length`:
/// its start, its first line, and its end (the next program's header, or the end of the text).
pub(crate) fn program_extent<T: Copy>(
    headers: &[(u32, T, u32)],
    number: u32,
    length: T,
) -> Option<(T, u32, T)> {
    let i = headers.iter().position(|h| h.0 == number)?;
    let (_, start, line) = headers[i];
    Some((start, line, headers.get(i + 1).map_or(length, |h| h.1)))
}

/// Where each program of a file starts: (number, byte offset, line number) of each `O1234` or
/// `:1234` header line. Scans bytes only (a large file is not parsed for this).
pub(crate) fn program_headers(text: &[u8], syntax: &SyntaxOptions) -> Vec<(u32, usize, u32)> {
    let mut headers = Vec::new();
    let mut offset = 0usize;
    let mut line = 1u32;
    while offset < text.len() {
        let rest = &text[offset..];
        let length = rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len());
        if let Some(n) = header_number(&rest[..length], syntax) {
            headers.push((n, offset, line));
        }
        offset += length + 1;
        line = line.saturating_add(1);
    }
    headers
}

/// The program number of a header line (`O1234`, `:1234`), given without its `\n`.
pub(crate) fn header_number(line: &[u8], syntax: &SyntaxOptions) -> Option<u32> {
    let start = line
        .iter()
        .position(|b| !matches!(b, b' ' | b'\t' | b'\r'))
        .unwrap_or(line.len());
    let content = &line[start..];
    let letter = content.first().copied().unwrap_or(0);
    if !(letter == b'O' || letter == b'o' || (letter == b':' && syntax.colon_program_number)) {
        return None;
    }
    let digits = content[1..]
        .iter()
        .take_while(|b| b.is_ascii_digit())
        .count();
    if digits == 0 || digits > 8 {
        return None;
    }
    std::str::from_utf8(&content[1..1 + digits])
        .ok()
        .and_then(|d| d.parse().ok())
}

/// True when a line is more than blanks, `%` and a comment: before the first header, it makes
/// that header a subprogram's.
pub(crate) fn starts_code(line: &[u8]) -> bool {
    let first = line.iter().find(|b| !matches!(b, b' ' | b'\t' | b'\r'));
    !matches!(first, None | Some(b'%' | b'(' | b';'))
}

/// The lines of a text that are the main program: from the start to the header of the second
/// program (the first header is the main program's own when nothing runs before it).
pub(crate) fn main_program_end(text: &[u8], headers: &[(u32, usize, u32)]) -> usize {
    let Some(&(_, first, _)) = headers.first() else {
        return text.len();
    };
    // Anything but blanks, `%` and comments before the first header makes it a subprogram's.
    let runs_before = text[..first].split(|&b| b == b'\n').any(starts_code);
    if runs_before {
        first
    } else {
        headers.get(1).map_or(text.len(), |h| h.1)
    }
}
