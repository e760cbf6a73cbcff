//! The subcommands, one module each.

pub(crate) mod check;
pub(crate) mod machine;
pub(crate) mod plot;
pub(crate) mod run;
pub(crate) mod sim;
pub(crate) mod trace;
pub(crate) mod view;

use std::path::Path;

/// How a command ended, for the exit code; the worse of two outcomes is the larger.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Outcome {
    /// No program raised an error alarm.
    Clean,
    /// At least one program stopped with an alarm.
    Alarm,
    /// A program could not be read (the error is printed): the others were run.
    Unread,
}

/// A problem that is not an alarm of a program: a missing file, a bad machine file.
pub(crate) type SetupError = crate::error::CliError;

/// Runs `each` on every program in turn. A program that cannot be read or run (a missing file)
/// is reported on standard error and the others still run; the worst outcome is returned.
/// Errors that concern the whole command (the machine file, an option) must be found before.
pub(crate) fn each_program<P: AsRef<Path>>(
    programs: &[P],
    mut each: impl FnMut(&Path) -> Result<Outcome, SetupError>,
) -> Outcome {
    let mut worst = Outcome::Clean;
    for program in programs {
        let outcome = each(program.as_ref()).unwrap_or_else(|error| {
            eprintln!("vcnc: {error}");
            Outcome::Unread
        });
        worst = worst.max(outcome);
    }
    worst
}
