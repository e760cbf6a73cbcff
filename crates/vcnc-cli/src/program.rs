//! Opening a program for a command: the machine, options, program directories and state file
//! of the command line, handed to the library's pipeline (`vcnc::pipeline`), which runs the
//! threads. This module keeps the machine state file (TOML) and reports what the pipeline
//! hands back; it never starts a thread or handles a batch itself.

use crate::error::CliError;
use crate::setup::MachineArgs;
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};
use vcnc::interp::PersistentVariables;
use vcnc::pipeline::{Layout, PersistentStore, Pipeline, Stream};
use vcnc::{Machine, Options};

/// Opens `path` and starts interpreting it on `machine` with `options`, its threads laid out
/// as `layout` says. Called programs come from the `--lib` directories and the program's own
/// directory; persistent variables from the state file.
pub(crate) fn open(
    path: &Path,
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
    Ok(pipeline.open_path(path)?)
}

/// A program opened for a command that plans it (`run`, `trace`).
pub(crate) struct Planned {
    pub(crate) plan_options: vcnc::plan::PlanOptions,
    pub(crate) stream: Stream,
}

/// Opens `path` on the machine and with the options of `setup`, for a consumer that keeps a
/// core busy and shows how many blocks ran (`counts_blocks`) or not.
pub(crate) fn open_planned(
    path: &Path,
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
    let stream = open(path, &machine, options, setup, layout)?;
    Ok(Planned {
        plan_options,
        stream,
    })
}

/// Ends `stream` and waits for its last save of the state file; a save that failed is
/// reported here. Returns the blocks the interpreter ran.
pub(crate) fn finish(stream: Stream, setup: &MachineArgs) -> u64 {
    let finished = stream.finish();
    if let (Some(error), Some(path)) = (finished.store_error, setup.state_file()) {
        eprintln!("vcnc: cannot save state file {}: {error}", path.display());
    }
    finished.blocks_executed
}

/// The machine state file: the persistent macro variables between runs.
pub(crate) struct StateFile {
    path: PathBuf,
}

impl StateFile {
    fn new(path: PathBuf) -> StateFile {
        StateFile { path }
    }

    /// The saved values (none when the file does not exist yet).
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
        let table: toml::Table = text.parse().map_err(|source| CliError::StateSyntax {
            path: self.path.clone(),
            source,
        })?;
        let mut values = PersistentVariables::default();
        if let Some(toml::Value::Table(variables)) = table.get("variables") {
            for (key, value) in variables {
                let number = key.trim_start_matches('#').parse::<u32>().ok();
                let value = match value {
                    toml::Value::Float(f) => Some(*f),
                    toml::Value::Integer(i) => Some(*i as f64),
                    _ => None,
                };
                if let (Some(number), Some(value)) = (number, value) {
                    values.values.insert(number, value);
                }
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
