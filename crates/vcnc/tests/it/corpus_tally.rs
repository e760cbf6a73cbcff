//! The corpus tallied with each program's best machine (tests/it/common/corpus.rs: the profile
//! its dialect needs, and the settings its author's control evidently had): every run that ends
//! without an error must give a plausible result, not merely "ok". A program whose text cuts
//! (G01, G02, G03 or a canned cycle) cuts at least once; the program scan finds no sign that
//! it was written for another profile, for whole-unit input or in inches; the travel check
//! passes.
//!
//! `VCNC_TALLY=FILE cargo test -p vcnc --test it corpus_tally::` also writes the table
//! (program, profile, result, cutting moves, cutting extents, warnings, reason) as markdown.

use crate::common;
use crate::common::corpus::{expected_alarm, machine_for, EXPECTED_ALARMS};
use std::fmt::Write as _;
use vcnc::checks::TravelLimits;
use vcnc::motion::{EndKind, SegmentKind};
use vcnc::program_scan::ProgramScan;
use vcnc::summary::Summary;
use vcnc::syntax::{detect_dialect, Dialect};
use vcnc::{AlarmCode, Machine, Options};

/// Runs whose warning is the right result: the program itself holds the slip, and the run
/// does what the control would, saying so. (file, warning, why)
const WARNED_AS_THE_CONTROL_RUNS_IT: &[(&str, AlarmCode, &str)] = &[(
    "werocketry_fin_frames_inch.nc",
    AlarmCode::DecimalLessScale,
    "`G01 Z1` (line 419), the retract before G28, means 1 inch; a Haas reads it as 0.0001 in, as vcnc does, and the warning names it",
)];

/// One program's row of the tally.
struct Row {
    program: String,
    profile: String,
    result: String,
    cutting_moves: u64,
    extents: String,
    warnings: Vec<String>,
    reason: String,
    /// What makes the result implausible, if anything.
    wrong: Option<String>,
}

/// True when the text holds a cutting code: G01, G02, G03 or a drilling cycle (G73-G89), as
/// a word (`G1X5`, `G01 `, not `G10` or `G17`).
fn text_cuts(text: &[u8]) -> bool {
    // Padded so that a code at the very end fills a window too.
    let mut upper = text.to_ascii_uppercase();
    upper.extend_from_slice(b"   ");
    upper.windows(4).any(|w| {
        let number = |d: &[u8]| {
            let digits: Vec<u8> = d.iter().copied().take_while(u8::is_ascii_digit).collect();
            std::str::from_utf8(&digits).ok()?.parse::<u32>().ok()
        };
        w[0] == b'G'
            && w[1].is_ascii_digit()
            && number(&w[1..]).is_some_and(|n| {
                let digits = w[1..].iter().take_while(|c| c.is_ascii_digit()).count();
                // The word ends before the window does, or fills it with a third digit that is
                // no part of a cutting code anyway.
                digits < 3 && (matches!(n, 1..=3) || (73..=89).contains(&n))
            })
    })
}

fn run_one(folder: &str, path: &std::path::Path) -> Row {
    let name = path.file_name().unwrap().to_string_lossy().into_owned();
    let text = std::fs::read(path).unwrap();
    let machine: Machine = machine_for(&name);
    let options = Options {
        dialect: detect_dialect(&name, &text),
        ..Options::default()
    };
    let scan = ProgramScan::of_text(&text);
    let mut warnings: Vec<vcnc::Alarm> = if options.dialect == Dialect::Iso {
        scan.warnings(&machine)
    } else {
        Vec::new()
    };
    let stream = common::corpus::stream(path, &text, &machine, options.clone());
    let mut summary = Summary::new(&machine);
    let mut end = None;
    let mut error = None;
    for item in TravelLimits::new(stream, &machine) {
        match item {
            Ok(vcnc::Item::Segment(segment)) => {
                if let SegmentKind::End { kind } = segment.kind {
                    end = Some(kind);
                }
                summary.add(&segment);
            }
            Ok(vcnc::Item::Frame(frame)) => summary.add_frame(&frame),
            Ok(vcnc::Item::Warning(alarm)) => warnings.push(alarm),
            Err(alarm) => error = Some(alarm),
        }
    }
    warnings.extend(summary.warnings());
    let result = match (&error, end) {
        (Some(alarm), _) => format!(
            "alarm {} at line {}",
            alarm.code,
            alarm.span.map_or(0, |s| s.line)
        ),
        (None, Some(EndKind::M02)) => "ok, M02".into(),
        (None, Some(EndKind::M30)) => "ok, M30".into(),
        (None, Some(EndKind::TapeMark)) => "ok, %".into(),
        (None, Some(EndKind::M99)) => "ok, M99 (main program)".into(),
        (None, _) => "ok, end of text".into(),
    };
    let reason = reason_for(&name, error.as_ref());
    let cuts = text_cuts(&text);
    let known = |code: AlarmCode| {
        WARNED_AS_THE_CONTROL_RUNS_IT
            .iter()
            .any(|&(file, c, _)| file == name && c == code)
    };
    let codes: Vec<AlarmCode> = warnings
        .iter()
        .map(|w| w.code)
        .filter(|&c| !known(c))
        .collect();
    let wrong = if error.is_some() {
        None
    } else if cuts && summary.feed_moves == 0 {
        Some("the text cuts, the run does not".to_string())
    } else if codes.contains(&AlarmCode::WrittenForAnotherProfile) {
        Some("written for another profile than its best".to_string())
    } else if codes.contains(&AlarmCode::DecimalLessScale) {
        Some("lengths read a thousandth of their size".to_string())
    } else if codes.contains(&AlarmCode::UnitNotSelected) {
        Some("an inch program run in mm".to_string())
    } else {
        None
    };
    let extents = if summary.cutting_extents.is_empty() {
        "-".to_string()
    } else {
        summary
            .cutting_extents
            .describe(vcnc::summary::LengthUnit::Millimetre)
    };
    Row {
        program: format!("{folder}/{name}"),
        profile: machine.profile.name.as_str().to_string(),
        result,
        cutting_moves: summary.feed_moves,
        extents,
        warnings: warnings
            .iter()
            .map(|w| format!("{} line {}", w.code, w.span.map_or(0, |s| s.line)))
            .collect(),
        reason,
        wrong,
    }
}

/// Why a program ends as it does: the expected alarm's reason, or the alarm.
fn reason_for(name: &str, error: Option<&vcnc::Alarm>) -> String {
    if let Some((_, _, why)) = WARNED_AS_THE_CONTROL_RUNS_IT
        .iter()
        .find(|(file, ..)| *file == name)
    {
        return format!("runs to its end, warned: {why}");
    }
    if let Some((_, _, _, why)) = EXPECTED_ALARMS.iter().find(|(file, ..)| *file == name) {
        return format!("as the control: {why}");
    }
    match error {
        None => "runs to its end".to_string(),
        Some(alarm) => alarm.message.replace('|', "\\|"),
    }
}

#[test]
fn every_corpus_run_that_ends_ok_has_a_plausible_result() {
    let Some(shared) = common::shared_dir() else {
        return;
    };
    let corpus = shared.join("corpus");
    let mut rows = Vec::new();
    for (folder, path) in common::corpus::programs(&corpus) {
        rows.push(run_one(folder, &path));
    }
    let mut table = String::from(
        "| program | profile | result | cutting moves | cutting extents (program, mm) | warnings | reason |\n|---|---|---|---:|---|---|---|\n",
    );
    for row in &rows {
        let _ = writeln!(
            table,
            "| `{}` | {} | {} | {} | {} | {} | {} |",
            row.program,
            row.profile,
            row.result,
            row.cutting_moves,
            row.extents,
            if row.warnings.is_empty() {
                "-".to_string()
            } else {
                row.warnings.join(", ")
            },
            row.reason
        );
    }
    if let Some(path) = std::env::var_os("VCNC_TALLY") {
        std::fs::write(&path, &table).expect("the tally file can be written");
    }
    let ok = rows.iter().filter(|r| r.result.starts_with("ok")).count();
    println!("corpus tally: {} programs, {ok} ok\n{table}", rows.len());
    let wrong: Vec<String> = rows
        .iter()
        .filter_map(|r| r.wrong.as_ref().map(|w| format!("{}: {w}", r.program)))
        .collect();
    assert!(
        wrong.is_empty(),
        "runs that end ok with an implausible result:\n{}",
        wrong.join("\n")
    );
    // Every expected alarm is still the one the run stops with.
    for row in &rows {
        let name = row.program.rsplit('/').next().unwrap();
        if let Some((code, line)) = expected_alarm(name) {
            assert_eq!(
                row.result,
                format!("alarm {code} at line {line}"),
                "{}",
                row.program
            );
        }
    }
}

#[test]
fn the_cutting_codes_are_found_as_words() {
    assert!(text_cuts(b"G0 X1.\ng1x5\n"));
    assert!(text_cuts(b"G98 G83 Z-1. R1. Q1.\n"));
    assert!(text_cuts(b"G03 I1."));
    assert!(text_cuts(b"G1"));
    assert!(!text_cuts(b"G0 X1.\nG17 G10 L2 P1 X0\nG28 G91 Z0\n"));
}
