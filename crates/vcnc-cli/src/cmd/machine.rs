//! `vcnc machine`: print a machine file to copy and edit: the embedded default, or the
//! `--machine` file, with the `--profile` asked for and the profile's reading of numbers
//! without a decimal point (`decimal_less`) spelled out. It never writes a file.

use super::{Outcome, SetupError};
use crate::setup::MachineChoice;
use clap::Args as ClapArgs;
use vcnc::profile::DecimalLess;

/// `vcnc machine` arguments.
#[derive(ClapArgs, Debug)]
pub(crate) struct Args {
    #[command(flatten)]
    choice: MachineChoice,
}

pub(crate) fn run(args: &Args) -> Result<Outcome, SetupError> {
    let machine = args.choice.machine()?;
    print!("{}", annotated(&args.choice.text()?, &machine));
    Ok(Outcome::Clean)
}

/// `text` with its `profile = ...` line naming `machine`'s profile, followed by a comment
/// on how the profile reads `X10`.
fn annotated(text: &str, machine: &vcnc::Machine) -> String {
    let profile = machine.profile.name.as_str();
    let (setting, reads, other, other_reads) = match machine.profile.units.decimal_less {
        DecimalLess::Increments => (
            "increments",
            "0.010 mm (0.0010 inch)",
            "whole_units",
            "10 mm",
        ),
        DecimalLess::WholeUnits => ("whole_units", "10 mm (10 inches)", "increments", "0.010 mm"),
    };
    let note = format!(
        "# Numbers without a decimal point: decimal_less = \"{setting}\" on this profile, X10 is\n\
         # {reads}; decimal_less = \"{other}\" under [profile_overrides.units] reads X10 as {other_reads}.\n"
    );
    let mut out = String::with_capacity(text.len() + note.len() + 32);
    let mut named = false;
    for line in text.lines() {
        // The note of an earlier `vcnc machine` is made again below.
        if line.starts_with("# Numbers without a decimal point:")
            || (line.contains("under [profile_overrides") && line.contains("reads X10 as"))
        {
            continue;
        }
        let key = line.split('=').next().map(str::trim);
        if !named && line.contains('=') && key == Some("profile") {
            out.push_str(&format!("profile = \"{profile}\"\n{note}"));
            named = true;
        } else {
            out.push_str(line);
            out.push('\n');
        }
    }
    if !named {
        // A machine file without a profile line takes fanuc; the line makes the choice plain.
        out = format!("profile = \"{profile}\"\n{note}{out}");
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use vcnc::machine::DEFAULT_MACHINE_TOML;
    use vcnc::{Machine, ProfileName};

    #[test]
    fn the_profile_line_names_the_profile_asked_for_and_the_file_loads_back() {
        let haas = Machine::default().with_profile(ProfileName::Haas).unwrap();
        let text = annotated(DEFAULT_MACHINE_TOML, &haas);
        assert!(text.contains("\nprofile = \"haas\"\n"), "{text}");
        assert!(text.contains("decimal_less = \"increments\""), "{text}");
        let again = Machine::from_toml(&text).unwrap();
        assert_eq!(again.profile.name, ProfileName::Haas);
        assert_eq!(annotated(&text, &again), text, "the note is not repeated");
    }
}
