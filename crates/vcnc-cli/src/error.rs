//! What stops a command outside the program itself: a file that cannot be read, a machine or
//! state file that is not valid, an option out of range, output that cannot be written. The
//! program's own alarms are diagnostics, never these. Each ends the command with exit code 2.

use std::path::PathBuf;

/// A command's error, with what the user needs to fix it.
#[derive(Debug, thiserror::Error)]
pub(crate) enum CliError {
    /// The machine file cannot be read.
    #[error("cannot read machine file {}: {source}", path.display())]
    ReadMachine {
        path: PathBuf,
        source: std::io::Error,
    },
    /// The machine file, or the profile asked for, does not make a machine.
    #[error("{}{source}", path.as_ref().map_or(String::new(), |p| format!("{}: ", p.display())))]
    Machine {
        path: Option<PathBuf>,
        source: vcnc::machine::MachineError,
    },
    /// An option's value is out of its range.
    #[error("{option} {value}: {expected}")]
    Option {
        option: &'static str,
        value: String,
        expected: &'static str,
    },
    /// The state file cannot be read.
    #[error("cannot read state file {}: {source}", path.display())]
    ReadState {
        path: PathBuf,
        source: std::io::Error,
    },
    /// The state file is not TOML.
    #[error("state file {}: {source}", path.display())]
    StateSyntax {
        path: PathBuf,
        source: toml::de::Error,
    },
    /// The state file holds something that is not a numbered variable, or cannot be saved to.
    #[error("state file {}: {problem}", path.display())]
    StateContent { path: PathBuf, problem: String },
    /// The state file cannot be saved: the persistent variables of the run are lost.
    #[error("cannot save state file {}: {source}", path.display())]
    SaveState {
        path: PathBuf,
        source: std::io::Error,
    },
    /// A pipe or standard input that gave nothing.
    #[error("{}: nothing to read (an empty pipe: did the command writing it fail?)", .0.display())]
    EmptyStream(PathBuf),
    /// `-` named twice.
    #[error("standard input (`-`) can be read once")]
    StdinTwice,
    /// A directory where a program file was expected.
    #[error("{} is a directory (check takes directories; run and trace take one program file)", .0.display())]
    Directory(PathBuf),
    /// The program cannot be opened.
    #[error(transparent)]
    Open(#[from] vcnc::pipeline::OpenError),
    /// The output cannot be written (a full disk, a closed file); a reader that went away
    /// (`| head`) is not an error.
    #[error("cannot write the output: {0}")]
    Output(std::io::Error),
}
