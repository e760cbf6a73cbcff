//! Opening a program for a command: the machine, options, program directories and state file
//! of the command line, handed to the library's pipeline (`vcnc::pipeline`), which runs the
//! threads. This module reads a program that is not a regular file (a pipe, a FIFO, `-` for
//! standard input) into memory, keeps the machine state file (TOML) and reports what the
//! pipeline hands back; it never starts a thread or handles a batch itself.

use crate::error::CliError;
use crate::setup::MachineArgs;
use std::fs::File;
use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use vcnc::interp::PersistentVariables;
use vcnc::pipeline::{Layout, PersistentStore, Pipeline, ProgramFiles, Stream};
use vcnc::{Machine, Options};

/// The name a program read from standard input (`-`) has in diagnostics.
pub(crate) const STDIN_NAME: &str = "<stdin>";

/// Standard input can be read once: a second `-` would be an empty program.
static STDIN_READ: AtomicBool = AtomicBool::new(false);

/// A program as the command line names it: a regular file, read as the program runs, or a
/// stream (standard input, a pipe, a FIFO, a device) read whole first, since it cannot be read
/// twice and its text is needed again for jumps and diagnostics.
pub(crate) enum Source {
    File(PathBuf),
    Memory { name: PathBuf, text: Arc<[u8]> },
}

impl Source {
    /// The program `path` names (`-`: standard input).
    pub(crate) fn read(path: &Path) -> Result<Source, CliError> {
        let read_error = |source| {
            CliError::Open(vcnc::pipeline::OpenError::Read {
                path: path.to_path_buf(),
                source,
            })
        };
        if path.as_os_str() == "-" {
            if STDIN_READ.swap(true, Ordering::Relaxed) {
                return Err(CliError::StdinTwice);
            }
            let mut text = Vec::new();
            std::io::stdin()
                .lock()
                .read_to_end(&mut text)
                .map_err(read_error)?;
            return Source::memory(PathBuf::from(STDIN_NAME), text);
        }
        let metadata = std::fs::metadata(path).map_err(|source| {
            CliError::Open(vcnc::pipeline::OpenError::Open {
                path: path.to_path_buf(),
                source,
            })
        })?;
        if metadata.is_file() {
            return Ok(Source::File(path.to_path_buf()));
        }
        if metadata.is_dir() {
            return Err(CliError::Directory(path.to_path_buf()));
        }
        // Opened once: a FIFO opened a second time waits for a writer that may never come.
        let mut text = Vec::new();
        File::open(path)
            .and_then(|mut file| file.read_to_end(&mut text))
            .map_err(read_error)?;
        Source::memory(path.to_path_buf(), text)
    }

    /// A program read from a stream. Nothing at all is an error, not an empty program: the
    /// command that should have written it failed (`cat missing.nc | vcnc run -`).
    fn memory(name: PathBuf, text: Vec<u8>) -> Result<Source, CliError> {
        if text.is_empty() {
            return Err(CliError::EmptyStream(name));
        }
        Ok(Source::Memory {
            name,
            text: text.into(),
        })
    }

    /// Its name in diagnostics.
    pub(crate) fn name(&self) -> &Path {
        match self {
            Source::File(path) => path,
            Source::Memory { name, .. } => name,
        }
    }

    /// Its text when it is held in memory (the diagnostics cannot read it again).
    pub(crate) fn text(&self) -> Option<Arc<[u8]>> {
        match self {
            Source::File(_) => None,
            Source::Memory { text, .. } => Some(Arc::clone(text)),
        }
    }
}

/// Opens `source` and starts interpreting it on `machine` with `options`, its threads laid out
/// as `layout` says. Called programs come from the `--lib` directories and the program's own
/// directory; persistent variables from the state file when the command keeps one.
pub(crate) fn open(
    source: &Source,
    machine: &Machine,
    options: Options,
    setup: &MachineArgs,
    layout: Layout,
) -> Result<Stream, CliError> {
    let mut pipeline = Pipeline::new(machine)
        .options(options)
        .layout(layout)
        .library_directories(setup.lib.clone());
    if let Some(state) = setup.state_file().map(StateFile::new) {
        pipeline = pipeline.persistent(state.load()?, state);
    }
    Ok(match source {
        Source::File(path) => pipeline.open_path(path)?,
        Source::Memory { name, text } => pipeline.open_text(text, name),
    })
}

/// A program opened for a command that plans it (`run`, `trace`).
pub(crate) struct Planned {
    pub(crate) plan_options: vcnc::plan::PlanOptions,
    pub(crate) stream: Stream,
}

/// Opens `source` on the machine and with the options of `setup`, for a consumer that keeps a
/// core busy and shows how many blocks ran (`counts_blocks`) or not.
pub(crate) fn open_planned(
    source: &Source,
    setup: &MachineArgs,
    counts_blocks: bool,
) -> Result<Planned, CliError> {
    let machine = setup.machine()?;
    let options = setup.options()?;
    let plan_options = setup.plan_options()?;
    let mut layout = Layout::for_busy_consumer();
    if counts_blocks {
        layout.stopping = vcnc::pipeline::Stopping::AtTheBlock;
    }
    let stream = open(source, &machine, options, setup, layout)?;
    Ok(Planned {
        plan_options,
        stream,
    })
}

/// The files of a run and the text of those held in memory, for the diagnostics.
pub(crate) fn files(stream: &Stream, source: &Source) -> crate::diagnostics::Texts {
    let files: ProgramFiles = stream.files().clone();
    crate::diagnostics::Texts::new(files, source.text())
}

/// Ends `stream` and waits for its last save of the state file. Returns the blocks the
/// interpreter ran, and the error of a save that failed (the command's output comes first,
/// then the error ends the command).
pub(crate) fn finish(stream: Stream, setup: &MachineArgs) -> (u64, Result<(), CliError>) {
    let finished = stream.finish();
    let saved = match (finished.store_error, setup.state_file()) {
        (Some(source), Some(path)) => Err(CliError::SaveState { path, source }),
        _ => Ok(()),
    };
    (finished.blocks_executed, saved)
}

/// The machine state file: the persistent macro variables between runs.
pub(crate) struct StateFile {
    path: PathBuf,
}

impl StateFile {
    fn new(path: PathBuf) -> StateFile {
        StateFile { path }
    }

    /// The saved values (none when the file does not exist yet). A file that is read-only
    /// (the user keeps it so) or holds anything but numbered variables is an error: saving
    /// over it would lose what it holds.
    fn load(&self) -> Result<PersistentVariables, CliError> {
        let text = match std::fs::read_to_string(&self.path) {
            Ok(text) => text,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Default::default()),
            Err(source) => {
                return Err(CliError::ReadState {
                    path: self.path.clone(),
                    source,
                })
            }
        };
        let invalid = |problem: String| CliError::StateContent {
            path: self.path.clone(),
            problem,
        };
        if std::fs::metadata(&self.path).is_ok_and(|m| m.permissions().readonly()) {
            return Err(invalid(
                "the file is read-only and a run saves to it (use --no-state to run without it)"
                    .into(),
            ));
        }
        let table: toml::Table = text.parse().map_err(|source| CliError::StateSyntax {
            path: self.path.clone(),
            source,
        })?;
        let mut values = PersistentVariables::default();
        for (key, value) in &table {
            let toml::Value::Table(variables) = value else {
                return Err(invalid(format!(
                    "unknown key `{key}` (expected the table [variables])"
                )));
            };
            if key != "variables" {
                return Err(invalid(format!(
                    "unknown table [{key}] (expected [variables])"
                )));
            }
            for (name, value) in variables {
                let number = name
                    .strip_prefix('#')
                    .and_then(|n| n.parse::<u32>().ok())
                    .ok_or_else(|| {
                        invalid(format!(
                            "variable `{name}` is not a macro variable number like \"#500\""
                        ))
                    })?;
                let value = match value {
                    toml::Value::Float(f) if f.is_finite() => *f,
                    toml::Value::Integer(i) => *i as f64,
                    other => {
                        return Err(invalid(format!(
                            "variable `{name}` = {other} is not a finite number"
                        )))
                    }
                };
                values.values.insert(number, value);
            }
        }
        Ok(values)
    }
}

impl PersistentStore for StateFile {
    /// Writes the values to a temporary file beside the state file and renames it over the
    /// state file: a run that is killed leaves the old file or the new one, never half of one.
    fn save(&mut self, values: &PersistentVariables) -> std::io::Result<()> {
        let mut text = String::from(
            "# vcnc machine state: persistent macro variables (#500-#999), saved by each run.\n[variables]\n",
        );
        for (number, value) in &values.values {
            text.push_str(&format!("\"#{number}\" = {value:?}\n"));
        }
        let name = self
            .path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "state.toml".into());
        let temporary = self
            .path
            .with_file_name(format!(".{name}.{}.tmp", std::process::id()));
        {
            let mut file = File::create(&temporary)?;
            file.write_all(text.as_bytes())?;
            file.sync_all()?;
        }
        std::fs::rename(&temporary, &self.path)
    }
}
