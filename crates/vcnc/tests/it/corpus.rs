//! Every real program of ../shared/corpus runs to its end, stops with the alarm the real control
//! raises (the table in tests/it/common/corpus.rs, with the reason for each), or stops with an
//! alarm that names what vcnc does not support yet (V020) or what is outside the product
//! (V022). SINUMERIK programs run on the SINUMERIK front end (tests/it/sinumerik_corpus.rs
//! checks each one's outcome). Never a panic, never a hang. The counts are printed
//! (`cargo test -p vcnc --test it corpus::every_corpus_program -- --nocapture`).

use crate::common;

use crate::common::corpus::machine_for;
use std::collections::BTreeMap;
use vcnc::motion::SegmentKind;
use vcnc::syntax::{detect_dialect, Dialect};
use vcnc::{AlarmCode, Options};

#[derive(Default, Debug)]
struct Counts {
    ran_to_end: usize,
    expected_alarms: usize,
    not_supported_yet: BTreeMap<String, usize>,
    out_of_product: BTreeMap<String, usize>,
}

#[test]
fn every_corpus_program_runs_or_names_what_is_missing() {
    let Some(shared) = common::shared_dir() else {
        return;
    };
    let corpus = shared.join("corpus");
    let mut counts = Counts::default();
    let mut failures = Vec::new();
    let mut total = 0;
    for (folder, path) in common::corpus::programs(&corpus) {
        total += 1;
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let text = std::fs::read(&path).unwrap();
        let machine = machine_for(&name);
        let options = Options {
            dialect: detect_dialect(&name, &text),
            ..Options::default()
        };
        // Called programs: the same author's programs, as in that control's memory.
        let stream = common::corpus::stream(&path, &text, &machine, options.clone());
        let run = common::collect(stream);
        let ended = run
            .segments
            .iter()
            .any(|s| matches!(s.kind, SegmentKind::End { .. }));
        let expected = common::corpus::expected_alarm(&name);
        match run.error() {
            None if ended && expected.is_none() => counts.ran_to_end += 1,
            None if ended => failures.push(format!(
                "{folder}/{name}: ran to its end, expected {expected:?}"
            )),
            Some(alarm) if Some((alarm.code, alarm.span.map_or(0, |s| s.line))) == expected => {
                counts.expected_alarms += 1;
            }
            None => failures.push(format!("{folder}/{name}: no end and no alarm")),
            Some(alarm) if alarm.code == AlarmCode::NotInProduct => {
                *counts
                    .out_of_product
                    .entry(alarm.message.clone())
                    .or_default() += 1;
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
    println!("corpus: {total} programs");
    println!("  ran to their end: {}", counts.ran_to_end);
    println!(
        "  stopped where the control stops (tests/it/common/corpus.rs): {}",
        counts.expected_alarms
    );
    for (message, n) in &counts.not_supported_yet {
        println!("  stopped, {message}: {n}");
    }
    for (message, n) in &counts.out_of_product {
        println!("  stopped, out of the product: {message}: {n}");
    }
    assert!(
        failures.is_empty(),
        "corpus programs with unexpected results:\n{}",
        failures.join("\n")
    );
    assert_eq!(total, 48, "the corpus has 48 programs (MANIFEST.md)");
}
