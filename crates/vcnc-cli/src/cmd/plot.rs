//! `vcnc plot`: the toolpath drawn to scale, as SVG or PNG (by the output's extension).

use super::{Outcome, SetupError};
use crate::diagnostics::{Output, Texts};
use crate::program::{open_planned, Planned, Source};
use crate::progress::Progress;
use crate::setup::MachineArgs;
use clap::{Args as ClapArgs, ValueEnum};
use std::path::{Path, PathBuf};
use vcnc::plan::Timing;
use vcnc::plot::{Toolpath, View};
use vcnc::{Alarm, AlarmCode, Item};

/// Where the drawing is seen from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum ViewArg {
    /// Looking down Z.
    Top,
    /// Looking along +Y (X right, Z up).
    Front,
    /// Looking along -X (Y right, Z up).
    Side,
    /// Isometric.
    Iso,
}

impl ViewArg {
    pub(crate) fn view(self) -> View {
        match self {
            ViewArg::Top => View::Top,
            ViewArg::Front => View::Front,
            ViewArg::Side => View::Side,
            ViewArg::Iso => View::Iso,
        }
    }
}

/// `vcnc plot` arguments.
#[derive(ClapArgs, Debug)]
pub(crate) struct Args {
    /// The program.
    program: PathBuf,
    /// The drawing: FILE.svg or FILE.png.
    #[arg(short, long, value_name = "FILE")]
    output: PathBuf,
    /// The view.
    #[arg(long, value_enum, default_value = "top")]
    view: ViewArg,
    /// Width of the drawing, pixels.
    #[arg(long, default_value_t = 1200)]
    width: u32,
    #[command(flatten)]
    machine: MachineArgs,
}

pub(crate) fn run(args: &Args) -> Result<Outcome, SetupError> {
    args.machine.check()?;
    let png = is_png(&args.output)?;
    let source = Source::read(&args.program)?;
    let mut path = Toolpath::new();
    path.per_axis_rapids(&args.machine.machine()?);
    let (texts, mut alarms) = each_item(&source, &args.machine, |item, _| path.add(item))?;
    if let Some((why, span, count)) = path.unfollowed() {
        alarms.push(Alarm::warning(
            AlarmCode::NotSimulated,
            span,
            format!(
                "{count} move(s) not drawn, from this block on: {}",
                why.describe()
            ),
        ));
    }
    let bytes = if png {
        path.to_png(args.view.view(), args.width)
    } else {
        path.to_svg(args.view.view(), args.width).into_bytes()
    };
    std::fs::write(&args.output, bytes).map_err(SetupError::Output)?;
    crate::diagnostics::print_human(&texts, &alarms, Output::Stderr);
    Ok(outcome(&alarms))
}

/// True for a `.png` output, false for `.svg`; anything else is refused.
pub(super) fn is_png(output: &Path) -> Result<bool, SetupError> {
    match output.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("png") => Ok(true),
        Some(e) if e.eq_ignore_ascii_case("svg") => Ok(false),
        _ => Err(SetupError::Option {
            option: "--output",
            value: output.display().to_string(),
            expected: "a file name ending in .svg or .png",
        }),
    }
}

/// Clean unless an alarm is an error.
pub(super) fn outcome(alarms: &[Alarm]) -> Outcome {
    if alarms.iter().any(Alarm::is_error) {
        Outcome::Alarm
    } else {
        Outcome::Clean
    }
}

/// Runs `source` through the library pipeline with the planner, giving every item that is not
/// the stopping alarm to `each` with its timing; returns the texts for diagnostics and the
/// run's warnings and alarm. A progress line shows on a terminal.
pub(super) fn each_item(
    source: &Source,
    setup: &MachineArgs,
    mut each: impl FnMut(&Item, &Timing),
) -> Result<(Texts, Vec<Alarm>), SetupError> {
    let Planned {
        plan_options,
        mut stream,
    } = open_planned(source, setup, false)?;
    let texts = crate::program::files(&stream, source);
    let mut alarms = Vec::new();
    let name = source.name().display().to_string();
    let mut progress = Progress::on_stderr(&name, true);
    stream.for_each_timed(plan_options, |items, timings| {
        for (item, timing) in items.iter().zip(timings) {
            match item {
                Ok(item) => {
                    if let Item::Segment(segment) = item {
                        progress.segment(segment.span.line);
                    }
                    if let Item::Warning(alarm) = item {
                        alarms.push(alarm.clone());
                    }
                    each(item, timing);
                }
                Err(alarm) => alarms.push(alarm.clone()),
            }
        }
        true
    });
    progress.finish();
    let (_, saved) = crate::program::finish(stream, setup);
    saved?;
    Ok((texts, alarms))
}
