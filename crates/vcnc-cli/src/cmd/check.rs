//! `vcnc check`: run programs and report only their alarms and warnings.

use super::{Outcome, SetupError};
use crate::setup::MachineArgs;
use clap::{Args as ClapArgs, ValueEnum};
use std::path::PathBuf;
use vcnc::pipeline::Layout;
use vcnc::Alarm;

/// Output format of the diagnostics.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum Format {
    /// For people, like rustc.
    Human,
    /// One JSON document: `{"programs": [{"file", "ok", "alarms": [...]}]}`.
    Json,
}

/// `vcnc check` arguments.
#[derive(ClapArgs, Debug)]
pub(crate) struct Args {
    /// The programs.
    #[arg(required = true)]
    programs: Vec<PathBuf>,
    /// Output format.
    #[arg(long, value_enum, default_value = "human")]
    format: Format,
    #[command(flatten)]
    machine: MachineArgs,
}

pub(crate) fn run(args: &Args) -> Result<Outcome, SetupError> {
    let machine = args.machine.machine()?;
    let options = args.machine.options()?;
    let mut outcome = Outcome::Clean;
    let mut reports = Vec::new();
    for path in &args.programs {
        let mut stream = crate::program::open(
            path,
            &machine,
            options.clone(),
            &args.machine,
            Layout::for_idle_consumer(),
        )?;
        let files = stream.files().clone();
        let scanning = super::run::scan_beside(path);
        let mut alarms: Vec<Alarm> = stream.by_ref().filter_map(Result::err).collect();
        let scan = scanning.join().ok().flatten();
        alarms.splice(0..0, scan.map_or_else(Vec::new, |s| s.warnings(&machine)));
        crate::program::finish(stream, &args.machine);
        let failed = alarms.iter().any(Alarm::is_error);
        if failed {
            outcome = Outcome::Alarm;
        }
        match args.format {
            Format::Human => {
                crate::diagnostics::print_human(&files, &alarms);
                if !failed {
                    eprintln!("{}: ok{}", path.display(), warning_count(&alarms));
                }
            }
            Format::Json => {
                let mut texts = std::collections::HashMap::new();
                let list: Vec<_> = alarms
                    .iter()
                    .map(|a| crate::diagnostics::to_json(&files, &mut texts, a))
                    .collect();
                reports.push(serde_json::json!({
                    "file": path.display().to_string(),
                    "ok": !failed,
                    "alarms": list,
                }));
            }
        }
    }
    if args.format == Format::Json {
        println!("{}", serde_json::json!({ "programs": reports }));
    }
    Ok(outcome)
}

fn warning_count(alarms: &[Alarm]) -> String {
    match alarms.len() {
        0 => String::new(),
        1 => " (1 warning)".to_string(),
        n => format!(" ({n} warnings)"),
    }
}
