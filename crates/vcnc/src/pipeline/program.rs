//! Opening a program: where its text comes from (a file, a reader, text in memory), its
//! dialect, where its blocks are parsed, and the programs it can call.
//!
//! The program library of a run is made in one place, [`library`]: the directories the caller
//! names, then the program file's own directory, and the main program's whole text for its
//! jumps. This module starts no interpreter: `threads.rs` does.

use super::Parsing;
use crate::interp::sinumerik::Sinumerik;
use crate::interp::{
    DirectoryLibrary, Interpreter, LoadedFiles, LookupError, Options, ProgramLibrary, ProgramText,
};
use crate::machine::Machine;
use crate::profile::ProfileName;
use crate::source::FileId;
use crate::syntax::blocks::{IsoParser, ProgramLines};
use crate::syntax::iso::SyntaxOptions;
use crate::syntax::{detect_dialect, Dialect};
use std::fs::File;
use std::io::{self, Read};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Why a program could not be opened.
#[derive(Debug, thiserror::Error)]
pub enum OpenError {
    /// The program file cannot be opened.
    #[error("cannot open {}: {source}", path.display())]
    Open {
        /// The program file.
        path: PathBuf,
        /// What the system said.
        source: io::Error,
    },
    /// The program's first lines cannot be read (to know its dialect).
    #[error("cannot read {}: {source}", path.display())]
    Read {
        /// The program file, or the name given to the reader.
        path: PathBuf,
        /// What the system said.
        source: io::Error,
    },
}

/// A program's ISO blocks, parsed where [`Parsing`] says.
pub(crate) type IsoProgramLines = ProgramLines<IsoParser>;

/// The ISO blocks of `reader`'s text (about `length` bytes, 0 when unknown), parsed where
/// `parsing` says.
pub(crate) fn iso_program_lines(
    reader: Box<dyn Read + Send>,
    length: u64,
    syntax: SyntaxOptions,
    parsing: Parsing,
) -> IsoProgramLines {
    let ahead = match parsing {
        Parsing::Ahead => Some(length),
        Parsing::InLine | Parsing::AheadWhenHeavy => None,
    };
    ProgramLines::new(reader, IsoParser::new(FileId(0), syntax), ahead)
}

/// The interpreter of a pipeline's program.
pub(crate) type ProgramInterpreter = Interpreter<IsoProgramLines>;

/// The files a run reads: the main program (file 0) and the programs it calls, for the
/// consumer's diagnostics.
#[derive(Debug, Clone)]
pub struct ProgramFiles {
    main: PathBuf,
    loaded: LoadedFiles,
}

impl ProgramFiles {
    /// The main program `main` and the files a library reads into `loaded`.
    pub(crate) fn new(main: PathBuf, loaded: LoadedFiles) -> ProgramFiles {
        ProgramFiles { main, loaded }
    }

    /// The path of file `file` (the main program's name for a file the run has not read).
    pub fn path(&self, file: FileId) -> PathBuf {
        if file == FileId(0) {
            return self.main.clone();
        }
        self.loaded
            .lock()
            .ok()
            .and_then(|l| l.iter().find(|(id, _)| *id == file).map(|(_, p)| p.clone()))
            .unwrap_or_else(|| self.main.clone())
    }
}

/// Where the main program's whole text can be had again, for its jumps.
pub(crate) enum MainText {
    /// Read again from its file.
    File(PathBuf),
    /// Held in memory.
    Memory(Arc<[u8]>),
    /// Nowhere: the text came from a reader.
    None,
}

/// A program opened and its dialect known, ready for its interpreter.
pub(crate) struct Opened {
    /// Where its whole text can be had again.
    pub(crate) main: MainText,
    /// Its name in diagnostics.
    pub(crate) name: PathBuf,
    pub(crate) reader: Box<dyn Read + Send>,
    /// About how many bytes it has (0 when unknown).
    pub(crate) length: u64,
    pub(crate) dialect: Dialect,
}

impl Opened {
    /// Its interpreter on `machine`, parsed as `parsing` says, calling programs from
    /// `directories` (and its own); with the files it will read.
    pub(crate) fn interpreter(
        self,
        machine: &Machine,
        options: Options,
        parsing: Parsing,
        directories: &[PathBuf],
    ) -> (ProgramInterpreter, ProgramFiles) {
        let syntax = machine.profile.syntax();
        let blocks = iso_program_lines(self.reader, self.length, syntax, parsing);
        let (library, loaded) = library(self.main, directories);
        let files = ProgramFiles::new(self.name, loaded);
        let interpreter =
            Interpreter::from_blocks(blocks, FileId(0), machine, options).with_library(library);
        (interpreter, files)
    }
}

impl Opened {
    /// True when the program runs on the SINUMERIK front end: written in the SINUMERIK language,
    /// or run on a SINUMERIK profile.
    pub(crate) fn is_sinumerik(&self, machine: &Machine) -> bool {
        self.dialect == Dialect::Sinumerik || machine.profile.name.is_sinumerik()
    }

    /// Its SINUMERIK front end on `machine` (a SINUMERIK profile: the machine's own, or the 840D
    /// when the machine is an ISO one), calling programs from `directories` (and its own
    /// directory); with the machine it runs on and the files it will read.
    pub(crate) fn sinumerik(
        mut self,
        machine: &Machine,
        options: &Options,
        parsing: Parsing,
        directories: &[PathBuf],
    ) -> (Sinumerik, Machine, ProgramFiles) {
        let machine = if machine.profile.name.is_sinumerik() {
            machine.clone()
        } else {
            machine
                .clone()
                .with_profile(ProfileName::Sinumerik)
                .unwrap_or_else(|_| machine.clone())
        };
        // A program in a file streams (its file is read again if it jumps); a text given whole
        // or read from a reader, which cannot be read again, is held whole.
        let streams = matches!(self.main, MainText::File(_));
        let mut text = Vec::new();
        if !streams {
            text.reserve(self.length as usize);
            // A read error mid-way runs what was read: the front end's end-of-text alarm says
            // the program ends without M30.
            let _ = self.reader.read_to_end(&mut text);
        }
        let (library, loaded) = library(self.main, directories);
        let files = ProgramFiles::new(self.name, loaded);
        let front_end = if !streams {
            Sinumerik::new(text, FileId(0), &machine)
        } else if parsing == Parsing::InLine {
            Sinumerik::streamed(self.reader, FileId(0), &machine)
        } else {
            Sinumerik::streamed_ahead(self.reader, self.length, FileId(0), &machine)
        };
        let mut front_end = front_end.with_library(library);
        for (switch, &on) in options.block_skip.iter().enumerate() {
            // Switch 1 is `/` and `/0` as well as `/1` (the ISO panel has switches 1 to 9).
            if switch == 0 {
                front_end = front_end.with_skip_level(0, on);
            }
            front_end = front_end.with_skip_level(switch as u8 + 1, on);
        }
        (front_end, machine, files)
    }
}

/// The programs a run can call: from `directories`, then from the main program file's own
/// directory; and the main program's whole text for its jumps. Called files get ids from 1 on.
pub(crate) fn library(
    main: MainText,
    directories: &[PathBuf],
) -> (Box<dyn ProgramLibrary>, LoadedFiles) {
    let mut directories = directories.to_vec();
    let (file, text) = match main {
        MainText::File(path) => {
            if let Some(own) = path.parent() {
                let own = if own.as_os_str().is_empty() {
                    PathBuf::from(".")
                } else {
                    own.to_path_buf()
                };
                directories.push(own);
            }
            (Some(path), None)
        }
        MainText::Memory(text) => (None, Some(text)),
        MainText::None => (None, None),
    };
    let library = DirectoryLibrary::new(file, directories, 1);
    let loaded = library.loaded_files();
    let library: Box<dyn ProgramLibrary> = match text {
        Some(text) => Box::new(WithMainText { text, library }),
        None => Box::new(library),
    };
    (library, loaded)
}

/// A directory library for a main program held in memory.
struct WithMainText {
    text: Arc<[u8]>,
    library: DirectoryLibrary,
}

impl ProgramLibrary for WithMainText {
    fn find(&mut self, number: u32) -> Result<Option<ProgramText>, LookupError> {
        self.library.find(number)
    }

    fn find_named(&mut self, name: &str) -> Result<Option<ProgramText>, LookupError> {
        self.library.find_named(name)
    }

    fn main_text(&mut self) -> Option<Arc<[u8]>> {
        Some(Arc::clone(&self.text))
    }
}

/// How much of a program's start is read to tell its dialect.
const HEAD: u64 = 4096;

/// A program file, opened.
pub(crate) enum OpenedFile {
    /// A regular file: its first bytes, and the file again at its start.
    Regular { head: Vec<u8>, file: File },
    /// A pipe, a FIFO or a terminal, read once and whole: it cannot be read again for its
    /// head, nor for a jump back.
    Stream(Vec<u8>),
}

/// Opens the file at `path`: a regular file with its first bytes, anything else read whole.
pub(crate) fn open_file(path: &Path) -> Result<OpenedFile, OpenError> {
    let open = || {
        File::open(path).map_err(|source| OpenError::Open {
            path: path.to_path_buf(),
            source,
        })
    };
    let read_error = |source| OpenError::Read {
        path: path.to_path_buf(),
        source,
    };
    let mut file = open()?;
    if !file.metadata().is_ok_and(|m| m.is_file()) {
        let mut text = Vec::new();
        file.read_to_end(&mut text).map_err(read_error)?;
        return Ok(OpenedFile::Stream(text));
    }
    let mut head = Vec::with_capacity(HEAD as usize);
    file.take(HEAD).read_to_end(&mut head).map_err(read_error)?;
    // Opened again rather than rewound: the program's reader then starts as a fresh file.
    Ok(OpenedFile::Regular {
        head,
        file: open()?,
    })
}

/// Reads the first bytes of `reader` (named `name`), and gives them back in front of the rest.
pub(crate) fn read_head(
    reader: impl Read + Send + 'static,
    name: &Path,
) -> Result<(Vec<u8>, Box<dyn Read + Send>), OpenError> {
    let mut head = Vec::with_capacity(HEAD as usize);
    let mut reader = reader;
    reader
        .by_ref()
        .take(HEAD)
        .read_to_end(&mut head)
        .map_err(|source| OpenError::Read {
            path: name.to_path_buf(),
            source,
        })?;
    let again = io::Cursor::new(head.clone());
    Ok((head, Box::new(again.chain(reader))))
}

/// The dialect of the program `name` whose text starts with `head`.
pub(crate) fn dialect(name: &Path, head: &[u8]) -> Dialect {
    let name = name
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    detect_dialect(&name, head)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::motion::Item;

    /// The end points of a run's moves, or its alarm codes.
    fn moves(stream: super::super::Stream) -> Vec<String> {
        stream
            .map(|item| match item {
                Ok(Item::Segment(segment)) => segment
                    .motion()
                    .map_or_else(String::new, |m| format!("{:?}", m.to)),
                Ok(Item::Frame(_)) => String::new(),
                Ok(Item::Warning(alarm)) | Err(alarm) => format!("{:?}", alarm.code),
            })
            .filter(|s| !s.is_empty())
            .collect()
    }

    #[test]
    fn a_sinumerik_file_that_jumps_runs_as_its_text_held_whole() {
        // The file streams until the WHILE: from there the front end reads the file whole
        // again. The moves (X0 Y0 is where the run starts: no move): X1, X2, X3 in the loop (R1 = 1, 2, 3); X10 then X11 by the
        // GOTOB back to LOOP2 (R2 = 0, 1); Y5 and two repetitions of it, incremental (Y10,
        // Y15); X20.
        let text = "DEF REAL FEED=500\nN10 G1 X0 Y0 F=FEED\nR1=0\nWHILE R1<3\nR1=R1+1\nG1 X=R1\nENDWHILE\n\
                    R2=0\nLOOP2: G1 X=10+R2\nR2=R2+1\nIF R2<2 GOTOB LOOP2\nMARK: G91 Y5\nREPEATB MARK P=2\nG90 X20\nM30\n";
        let dir = std::env::temp_dir().join(format!("vcnc-stream-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("JUMPS.MPF");
        std::fs::write(&path, text).unwrap();
        let machine = Machine::default();
        let from_file = moves(crate::Pipeline::new(&machine).open_path(&path).unwrap());
        let whole = moves(crate::Pipeline::new(&machine).open_text(text, "JUMPS.MPF"));
        std::fs::remove_dir_all(&dir).ok();
        assert_eq!(from_file, whole);
        // 3 (the loop) + 2 (X10, X11) + 3 (Y5, Y10, Y15) + 1 (X20).
        assert_eq!(from_file.len(), 9, "{from_file:?}");
        assert!(
            from_file[8].starts_with("MachinePos([20.0, 15.0,"),
            "{from_file:?}"
        );
    }

    #[test]
    fn a_reader_gives_its_head_back_in_front_of_the_rest() {
        let text: Vec<u8> = (0..10_000u32).map(|i| (i % 251) as u8).collect();
        let (head, mut reader) = read_head(io::Cursor::new(text.clone()), Path::new("p")).unwrap();
        assert_eq!(head, &text[..4096]);
        let mut again = Vec::new();
        reader.read_to_end(&mut again).unwrap();
        assert_eq!(again, text);
    }

    #[test]
    fn a_missing_file_names_itself_in_the_error() {
        let path = Path::new("/nonexistent/vcnc/part.nc");
        let Err(error) = open_file(path) else {
            panic!("opened")
        };
        assert!(matches!(error, OpenError::Open { .. }));
        assert!(
            error
                .to_string()
                .starts_with("cannot open /nonexistent/vcnc/part.nc: "),
            "{error}"
        );
    }

    #[test]
    fn the_dialect_comes_from_the_name_and_the_head() {
        assert_eq!(
            dialect(Path::new("dir/PART.MPF"), b"G1 X1"),
            Dialect::Sinumerik
        );
        assert_eq!(dialect(Path::new("part.nc"), b"G1 X1"), Dialect::Iso);
    }
}
