//! Every real program of ../shared/corpus runs to its end, or stops with an alarm that names what
//! vcnc does not support yet; SINUMERIK programs get one clear "not supported yet" alarm. Never a
//! panic, never a hang. The counts are printed (`cargo test --test corpus -- --nocapture`).

mod common;

use common::corpus::machine_for;
use std::collections::BTreeMap;
use vcnc::motion::SegmentKind;
use vcnc::syntax::{detect_dialect, Dialect};
use vcnc::{AlarmCode, Options};

#[derive(Default, Debug)]
struct Counts {
    ran_to_end: usize,
    not_supported_yet: BTreeMap<String, usize>,
    dialect: usize,
}

#[test]
fn every_corpus_program_runs_or_names_what_is_missing() {
    let corpus = common::shared_dir().join("corpus");
    let mut counts = Counts::default();
    let mut failures = Vec::new();
    let mut total = 0;
    for folder in ["fanuc", "large", "sinumerik"] {
        let mut files: Vec<_> = std::fs::read_dir(corpus.join(folder))
            .unwrap()
            .map(|e| e.unwrap().path())
            .collect();
        files.sort();
        for path in files {
            total += 1;
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            let text = std::fs::read(&path).unwrap();
            let machine = machine_for(&name);
            let options = Options {
                dialect: detect_dialect(&name, &text),
                ..Options::default()
            };
            let run = common::run(&text, &machine, options.clone());
            let ended = run
                .segments
                .iter()
                .any(|s| matches!(s.kind, SegmentKind::End { .. }));
            match run.error() {
                None if ended => counts.ran_to_end += 1,
                None => failures.push(format!("{folder}/{name}: no end and no alarm")),
                Some(alarm) if alarm.code == AlarmCode::DialectNotSupported => {
                    if folder != "sinumerik" {
                        failures.push(format!("{folder}/{name}: taken for SINUMERIK"));
                    }
                    counts.dialect += 1;
                }
                Some(alarm) if alarm.code == AlarmCode::NotSupportedYet => {
                    *counts
                        .not_supported_yet
                        .entry(alarm.message.clone())
                        .or_default() += 1;
                }
                Some(alarm) => failures.push(format!(
                    "{folder}/{name}:{}: {alarm}",
                    alarm.span.map_or(0, |s| s.line)
                )),
            }
            if folder == "sinumerik" && options.dialect != Dialect::Sinumerik {
                failures.push(format!("{folder}/{name}: not recognised as SINUMERIK"));
            }
        }
    }
    println!("corpus: {total} programs");
    println!("  ran to their end: {}", counts.ran_to_end);
    println!("  SINUMERIK, not supported yet: {}", counts.dialect);
    for (message, n) in &counts.not_supported_yet {
        println!("  stopped, {message}: {n}");
    }
    assert!(
        failures.is_empty(),
        "corpus programs with unexpected results:\n{}",
        failures.join("\n")
    );
    assert_eq!(total, 48, "the corpus has 48 programs (MANIFEST.md)");
}
