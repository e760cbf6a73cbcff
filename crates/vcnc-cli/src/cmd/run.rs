//! `vcnc run`: run a program and print the summary a CNC programmer wants.

use super::{Outcome, SetupError};
use crate::diagnostics::{Output, Texts};
use crate::program::{open_planned, Planned, Source};
use crate::progress::Progress;
use crate::setup::MachineArgs;
use clap::{Args as ClapArgs, ValueEnum};
use serde_json::json;
use std::path::{Path, PathBuf};
use vcnc::motion::EndKind;
use vcnc::plan::{TimeKind, TimeReport};
use vcnc::program_scan::{power_on_unit, ProgramScan};
use vcnc::summary::{Extents, LengthUnit, Summary};
use vcnc::{Alarm, Item, SegmentKind};

/// Output format of the summary.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum Format {
    /// A table for people.
    Human,
    /// One JSON object per program.
    Json,
}

/// `vcnc run` arguments.
#[derive(ClapArgs, Debug)]
pub(crate) struct Args {
    /// The programs, each run on its own from a fresh start (`-`: standard input; a pipe
    /// or FIFO is read whole first).
    #[arg(required = true)]
    programs: Vec<PathBuf>,
    /// Output format.
    #[arg(long, value_enum, default_value = "human")]
    format: Format,
    #[command(flatten)]
    pub(crate) machine: MachineArgs,
}

/// `println!` into the report being built: written out whole at the end, so that a reader that
/// goes away (`| head`) ends the output quietly instead of a panic of `println!`.
macro_rules! outln {
    ($out:expr) => {
        $out.push('\n')
    };
    ($out:expr, $($arg:tt)*) => {{
        // Writing into a String cannot fail.
        let _ = std::fmt::Write::write_fmt($out, format_args!($($arg)*));
        $out.push('\n');
    }};
}

/// Writes the report to standard output; a reader that went away is no error.
fn emit(report: &str) -> Result<(), SetupError> {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    match stdout
        .write_all(report.as_bytes())
        .and_then(|()| stdout.flush())
    {
        Err(error) if error.kind() != std::io::ErrorKind::BrokenPipe => {
            Err(SetupError::Output(error))
        }
        _ => Ok(()),
    }
}

const ESTIMATE_NOTE: &str = "length / feed and rapid rates, without acceleration or corners";

const PLAN_NOTE: &str = "planned: per-axis speed, acceleration and jerk, look-ahead, corners, \
exact stops, dwell, tool change and spindle times from the machine file";

pub(crate) fn run(args: &Args) -> Result<Outcome, SetupError> {
    args.machine.check()?;
    let mut first = true;
    Ok(super::each_program(&args.programs, |path| {
        if !std::mem::take(&mut first) && args.format == Format::Human {
            emit("\n")?;
        }
        run_one(args, path)
    }))
}

fn run_one(args: &Args, path: &Path) -> Result<Outcome, SetupError> {
    let source = Source::read(path)?;
    let Planned {
        plan_options,
        mut stream,
    } = open_planned(&source, &args.machine, true)?;
    let machine = stream.machine().clone();
    let texts = crate::program::files(&stream, &source);
    let mut summary = Summary::new(&machine);
    let mut report = TimeReport::new();
    let scanning = scan_beside(&source);
    let mut alarms: Vec<Alarm> = Vec::new();
    let mut end = None;
    let name = source.name().display().to_string();
    let mut progress = Progress::on_stderr(&name, args.format == Format::Human);
    stream.for_each_timed(plan_options, |items, timings| {
        for (item, timing) in items.iter().zip(timings) {
            match item {
                Ok(Item::Segment(segment)) => {
                    progress.segment(segment.span.line);
                    if let SegmentKind::End { kind } = segment.kind {
                        end = Some(kind);
                    }
                    summary.add(segment);
                    report.add(segment, timing);
                }
                Ok(Item::Frame(frame)) => summary.add_frame(frame),
                Ok(Item::Warning(alarm)) | Err(alarm) => alarms.push(alarm.clone()),
            }
        }
        true
    });
    progress.finish();
    let (blocks, saved) = crate::program::finish(stream, &args.machine);
    // The run's own warnings go before the alarm that stopped it, if one did.
    let at = alarms
        .iter()
        .position(Alarm::is_error)
        .unwrap_or(alarms.len());
    alarms.splice(at..at, summary.warnings());
    // What the text says of the control it was written for comes first: it explains the rest.
    let scan = scanning.join().ok().flatten();
    let unit = scan.as_ref().map_or_else(
        || power_on_unit(&machine.profile),
        |s| s.program_unit(&machine.profile),
    );
    alarms.splice(0..0, scan.map_or_else(Vec::new, |s| s.warnings(&machine)));
    let error = alarms.iter().find(|a| a.is_error());
    let result = match (error, end) {
        (Some(alarm), _) => format!(
            "stopped by alarm {} at line {}",
            alarm.code,
            alarm.span.map_or(0, |s| s.line)
        ),
        (None, Some(EndKind::M02)) => "ended with M02".to_string(),
        (None, Some(EndKind::M30)) => "ended with M30".to_string(),
        (None, Some(EndKind::TapeMark)) => "ended at %".to_string(),
        (None, Some(EndKind::M99)) => {
            "ended at M99 in the main program (the control would repeat it)".to_string()
        }
        (None, _) => "ended at the end of the text (no M02/M30)".to_string(),
    };
    let warnings = alarms.iter().filter(|a| !a.is_error()).count();
    let mut out = String::new();
    match args.format {
        Format::Human => {
            print_human(
                &mut out,
                source.name(),
                &machine,
                &summary,
                (blocks, &result),
                warnings,
                unit,
            );
            print_time_human(
                &mut out,
                &report,
                &summary,
                plan_options.feed_override,
                &texts,
            );
            emit(&out)?;
            crate::diagnostics::print_human(&texts, &alarms, Output::Stderr);
        }
        Format::Json => {
            let list: Vec<_> = alarms
                .iter()
                .map(|a| crate::diagnostics::to_json(&texts, a))
                .collect();
            let value = json!({
                "file": source.name().display().to_string(),
                "machine": machine.name,
                "profile": machine.profile.name.as_str(),
                "blocks": blocks,
                "result": result,
                "ok": error.is_none(),
                "rapid": { "moves": summary.rapid_moves, "length_mm": summary.rapid_length, "seconds": summary.rapid_seconds },
                "feed": { "moves": summary.feed_moves, "length_mm": summary.feed_length, "seconds": summary.feed_seconds,
                          "untimed_moves": summary.untimed_moves },
                "dwell_seconds": summary.dwell_seconds,
                "estimated_seconds": summary.estimated_seconds(),
                "estimate_method": ESTIMATE_NOTE,
                "time": time_json(&report, plan_options.feed_override, &texts),
                "tools": summary.tools.iter().collect::<Vec<_>>(),
                "tool_changes": summary.tool_changes,
                "extents": { "program_unit": unit.as_str(), "machine": extents_json(&summary.machine_extents), "program": extents_json(&summary.work_extents),
                             "cutting": extents_json(&summary.cutting_extents) },
                "alarms": list,
            });
            outln!(&mut out, "{value:#}");
            emit(&out)?;
        }
    }
    saved?;
    Ok(if error.is_some() {
        Outcome::Alarm
    } else {
        Outcome::Clean
    })
}

/// The program scan of `path`, on a thread of its own beside the run: it reads the file once
/// more (about a fifth of a plain program's run time, here on the other core).
pub(crate) fn scan_beside(source: &Source) -> std::thread::JoinHandle<Option<ProgramScan>> {
    match source {
        Source::File(path) => {
            let path = path.clone();
            std::thread::spawn(move || ProgramScan::of_file(&path).ok().flatten())
        }
        Source::Memory { text, .. } => {
            let text = std::sync::Arc::clone(text);
            std::thread::spawn(move || Some(ProgramScan::of_text(&text)))
        }
    }
}

fn print_human(
    out: &mut String,
    name: &Path,
    machine: &vcnc::Machine,
    summary: &Summary,
    (blocks, result): (u64, &str),
    warnings: usize,
    unit: LengthUnit,
) {
    outln!(
        out,
        "{}  ({}, {} profile)",
        crate::excerpt::escape(&name.display().to_string()),
        machine.name,
        machine.profile.name
    );
    outln!(
        out,
        "  result            {result}{}",
        if warnings > 0 {
            format!(", {warnings} warning(s)")
        } else {
            String::new()
        }
    );
    outln!(out, "  blocks executed   {blocks}");
    outln!(
        out,
        "  rapid             {:>7} moves  {:>12.3} mm",
        summary.rapid_moves,
        summary.rapid_length
    );
    outln!(
        out,
        "  cutting           {:>7} moves  {:>12.3} mm",
        summary.feed_moves,
        summary.feed_length
    );
    let tools: Vec<String> = summary.tools.iter().map(|t| format!("T{t}")).collect();
    outln!(
        out,
        "  tools             {}",
        if tools.is_empty() {
            "none changed".to_string()
        } else {
            format!(
                "{} ({} change{})",
                tools.join(" "),
                summary.tool_changes,
                if summary.tool_changes == 1 { "" } else { "s" }
            )
        }
    );
    let extents = [
        ("machine", &summary.machine_extents),
        ("program", &summary.work_extents),
        ("cutting", &summary.cutting_extents),
    ];
    for (name, e) in extents {
        outln!(out, "  extents {name:<10}{}", e.describe(unit));
        // An inch program's extents in mm too, for the machine's side.
        if unit == LengthUnit::Inch && !e.is_empty() {
            outln!(out, "{:<20}{}", "", e.describe(LengthUnit::Millimetre));
        }
    }
}

/// The planned time, where it goes, and the length / feed estimate beside it.
fn print_time_human(
    out: &mut String,
    report: &TimeReport,
    summary: &Summary,
    feed_override: f64,
    files: &Texts,
) {
    let percent = if feed_override == 1.0 {
        String::new()
    } else {
        format!(", feed override {:.0} %", feed_override * 100.0)
    };
    outln!(out, "  cycle time        {}{percent}", clock(report.total));
    outln!(out, "                    {PLAN_NOTE}");
    outln!(
        out,
        "  length / feed     {}  (rapid {:.1} s, cutting {:.1} s, dwell {:.1} s: {ESTIMATE_NOTE})",
        clock(summary.estimated_seconds()),
        summary.rapid_seconds,
        summary.feed_seconds,
        summary.dwell_seconds
    );
    if summary.untimed_moves > 0 {
        outln!(out,
            "                    {} cutting moves at the axes' limit (feed per revolution without S)",
            summary.untimed_moves
        );
    }
    let kinds: Vec<String> = TimeKind::ALL
        .iter()
        .map(|k| {
            format!(
                "{} {:.1} s",
                k.as_str().replace('_', " "),
                report.seconds(*k)
            )
        })
        .collect();
    outln!(out, "  time by kind      {}", kinds.join(", "));
    let tools: Vec<String> = report
        .by_tool
        .iter()
        .map(|(tool, s)| format!("{} {s:.1} s", tool_name(*tool)))
        .collect();
    outln!(out, "  time by tool      {}", tools.join(", "));
    for (i, block) in report.slowest_blocks().iter().enumerate() {
        let label = if i == 0 { "  slowest blocks" } else { "" };
        let (file, text) = files.block(block.span, BLOCK_TEXT);
        outln!(
            out,
            "{label:<20}{:>9.3} s  {file}:{}  {text}",
            block.seconds,
            block.span.line
        );
    }
}

fn tool_name(tool: Option<u32>) -> String {
    tool.map_or_else(|| "no tool".to_string(), |t| format!("T{t}"))
}

/// How much of a slowest block's text the summary shows.
const BLOCK_TEXT: u64 = 120;

fn time_json(report: &TimeReport, feed_override: f64, files: &Texts) -> serde_json::Value {
    let by_kind: serde_json::Map<String, serde_json::Value> = TimeKind::ALL
        .iter()
        .map(|k| (k.as_str().to_string(), json!(report.seconds(*k))))
        .collect();
    let by_tool: Vec<_> = report
        .by_tool
        .iter()
        .map(|(tool, s)| json!({ "tool": tool, "seconds": s }))
        .collect();
    let slowest: Vec<_> = report
        .slowest_blocks()
        .iter()
        .map(|b| {
            let (file, text) = files.block(b.span, BLOCK_TEXT);
            json!({ "file": file, "line": b.span.line, "text": text, "seconds": b.seconds })
        })
        .collect();
    json!({
        "total_seconds": report.total,
        "method": PLAN_NOTE,
        "feed_override": feed_override,
        "by_kind": by_kind,
        "by_tool": by_tool,
        "slowest_blocks": slowest,
    })
}

fn clock(seconds: f64) -> String {
    let total = seconds.max(0.0);
    let hours = (total / 3600.0).floor();
    let minutes = ((total - hours * 3600.0) / 60.0).floor();
    let rest = total - hours * 3600.0 - minutes * 60.0;
    format!("{}:{:02}:{:04.1}", hours as u64, minutes as u64, rest)
}

fn extents_json(e: &Extents) -> serde_json::Value {
    if e.is_empty() {
        return serde_json::Value::Null;
    }
    json!({ "min": e.min, "max": e.max })
}
