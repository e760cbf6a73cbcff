//! The subcommands, one module each.

pub(crate) mod check;
pub(crate) mod run;
pub(crate) mod trace;

/// How a command ended, for the exit code.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Outcome {
    /// No program raised an error alarm.
    Clean,
    /// At least one program stopped with an alarm.
    Alarm,
}

/// A problem that is not an alarm of a program: a missing file, a bad machine file.
pub(crate) type SetupError = crate::error::CliError;
