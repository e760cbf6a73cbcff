//! The manuals' example programs (../shared/spec/examples) run, and their expected positions
//! hold. The expectations are data: tests/data/seed_examples*.toml, one entry per example, written
//! from each example's header (source lines in the manual, preconditions, expected result).

use crate::common;

use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::Path;
use vcnc::interp::MemoryLibrary;
use vcnc::machine::{ToolOffset, WorkOffsetId};
use vcnc::{FileId, Machine, Options, ProfileName, SegmentKind};

/// An alarm expected at a line of the example.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct AlarmAt {
    code: String,
    line: u32,
}

#[derive(Deserialize, Debug)]
struct Table {
    example: Vec<Example>,
}

#[derive(Deserialize, Debug, Default, Clone, Copy)]
struct Point {
    x: Option<f64>,
    y: Option<f64>,
    z: Option<f64>,
    /// The rotary axis C, degrees (machines with `c_axis`).
    c: Option<f64>,
}

impl Point {
    fn axes(&self) -> [(usize, Option<f64>); 4] {
        [(0, self.x), (1, self.y), (2, self.z), (5, self.c)]
    }

    /// True when every axis the point gives is within `tolerance` of `position`.
    fn matches(&self, position: &[f64; 6], tolerance: f64) -> bool {
        self.axes()
            .iter()
            .all(|&(i, v)| v.is_none_or(|v| close(position[i], v, tolerance)))
    }
}

/// The letter of a position's axis index.
fn letter(index: usize) -> char {
    "XYZABC".as_bytes()[index] as char
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct Example {
    file: String,
    profile: ProfileName,
    source: String,
    id: Option<String>,
    start: Option<Point>,
    /// The machine has a rotary axis C (polar coordinate interpolation needs one).
    #[serde(default)]
    c_axis: bool,
    prelude: Option<String>,
    lines: Option<Vec<usize>>,
    #[serde(default)]
    tool_lengths: BTreeMap<String, f64>,
    /// Radius offsets by offset number (the D cells).
    #[serde(default)]
    tool_radii: BTreeMap<String, f64>,
    #[serde(default)]
    work_offsets: BTreeMap<String, Point>,
    #[serde(default)]
    reference_points: BTreeMap<String, Point>,
    end: Option<Point>,
    points: Option<Vec<Point>>,
    /// Positions some motions end at, in this order, other motions between them allowed: for
    /// paths the control cuts into pieces of its own (G12.1), whose count is not the manual's.
    visits: Option<Vec<Point>>,
    feed_length: Option<f64>,
    rapid_length: Option<f64>,
    dwell_seconds: Option<f64>,
    /// The speeds of the spindle events in order, rpm.
    spindle_speeds: Option<Vec<f64>>,
    tolerance: Option<f64>,
    skip: Option<String>,
    /// The alarm the real control stops the program with, after the asserted motions: code and
    /// line (`{ code = "V070", line = 32 }`).
    alarm: Option<AlarmAt>,
    /// Blocks during which the interrupt signal comes (`Options::interrupts`: `"13"` is line 13
    /// of the example file, `"N20"` a sequence number).
    #[serde(default)]
    interrupts: Vec<String>,
    /// Programs the example calls, by number: other example files.
    #[serde(default)]
    programs: BTreeMap<String, String>,
    #[allow(dead_code)]
    note: Option<String>,
}

impl Example {
    fn name(&self) -> String {
        match &self.id {
            Some(id) => format!("{} [{id}]", self.file),
            None => self.file.clone(),
        }
    }

    fn machine(&self) -> Machine {
        let mut machine = if self.c_axis {
            common::with_c_axis(self.profile)
        } else {
            Machine::default().with_profile(self.profile).unwrap()
        };
        if let Some(start) = self.start {
            for (i, v) in start.axes() {
                machine.start[i] = v.unwrap_or(0.0);
            }
        }
        for (number, length) in &self.tool_lengths {
            let number: u32 = number.parse().expect("tool_lengths keys are numbers");
            machine.tool_offsets.insert(
                number,
                ToolOffset {
                    number,
                    length: *length,
                    ..ToolOffset::default()
                },
            );
        }
        for (number, radius) in &self.tool_radii {
            let number: u32 = number.parse().expect("tool_radii keys are numbers");
            machine
                .tool_offsets
                .entry(number)
                .or_insert(ToolOffset {
                    number,
                    ..ToolOffset::default()
                })
                .radius = *radius;
        }
        for (key, offset) in &self.work_offsets {
            let id = WorkOffsetId::parse(key)
                .unwrap_or_else(|| panic!("{}: bad work offset key {key}", self.name()));
            let mut values = [0.0; 6];
            for (i, v) in offset.axes() {
                values[i] = v.unwrap_or(0.0);
            }
            machine.work_offsets.insert(id, values);
        }
        for (key, point) in &self.reference_points {
            let n: usize = key.parse().expect("reference point keys are numbers");
            for (i, v) in point.axes() {
                machine.reference_points[n - 1][i] = v.unwrap_or(0.0);
            }
        }
        machine
    }

    fn options(&self) -> Options {
        let interrupts = self.interrupts.iter().map(|at| {
            at.parse()
                .unwrap_or_else(|e| panic!("{}: interrupts: {e}", self.name()))
        });
        Options {
            interrupts: interrupts.collect(),
            ..Options::default()
        }
    }

    /// The example files it calls, as a program library.
    fn library(&self, examples_dir: &Path) -> MemoryLibrary {
        let mut library = MemoryLibrary::new();
        for (i, (number, file)) in self.programs.iter().enumerate() {
            let number: u32 = number.parse().expect("programs keys are program numbers");
            let path = examples_dir.join(file);
            let text = std::fs::read_to_string(&path)
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            library.insert(number, FileId(i as u32 + 1), &text);
        }
        library
    }

    fn program(&self, text: &str) -> String {
        let mut program = String::new();
        if let Some(prelude) = &self.prelude {
            program.push_str(prelude);
            program.push('\n');
        }
        match &self.lines {
            Some(lines) => {
                let all: Vec<&str> = text.lines().collect();
                for &n in lines {
                    program.push_str(
                        all.get(n - 1)
                            .unwrap_or_else(|| panic!("{}: no line {n}", self.name())),
                    );
                    program.push('\n');
                }
            }
            None => program.push_str(text),
        }
        program
    }
}

fn close(actual: f64, expected: f64, tolerance: f64) -> bool {
    (actual - expected).abs() <= tolerance
}

#[test]
fn manual_examples_reach_their_expected_positions() {
    let Some(shared) = common::shared_dir() else {
        return;
    };
    let examples_dir = shared.join("spec/examples");
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let mut files: Vec<_> = std::fs::read_dir(&data)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            p.file_name()
                .unwrap()
                .to_string_lossy()
                .starts_with("seed_examples")
        })
        .collect();
    files.sort();
    let mut table = Table {
        example: Vec::new(),
    };
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        let part: Table =
            toml::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        table.example.extend(part.example);
    }
    let mut failures = Vec::new();
    let mut asserted = 0;
    let mut stale_skips = Vec::new();
    for example in &table.example {
        let path = examples_dir.join(&example.file);
        let text =
            std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let program = example.program(&text);
        let run = common::run_with_library(
            program.as_bytes(),
            &example.machine(),
            example.options(),
            Box::new(example.library(&examples_dir)),
        );
        let fail = |what: String| format!("{} (manual {}): {what}", example.name(), example.source);
        if let Some(reason) = &example.skip {
            // A skipped example needs what vcnc does not have yet (a code, or a machine with more
            // axes); it must stop with an alarm, not run to a wrong end.
            if run.error().is_none() {
                stale_skips.push(format!("{} ({reason})", example.name()));
            }
            continue;
        }
        match (run.error(), &example.alarm) {
            (Some(alarm), Some(want))
                if alarm.code.code() == want.code
                    && alarm.span.map(|s| s.line) == Some(want.line) => {}
            (Some(alarm), _) => {
                failures.push(fail(format!("alarm: {alarm}")));
                continue;
            }
            (None, Some(want)) => {
                failures.push(fail(format!(
                    "no alarm; expected {} at line {}",
                    want.code, want.line
                )));
                continue;
            }
            (None, None) => {}
        }
        let tolerance = example.tolerance.unwrap_or(0.001);
        let motions: Vec<_> = run
            .segments
            .iter()
            .filter_map(|s| s.motion().map(|m| m.to.0))
            .collect();
        let last = motions
            .last()
            .copied()
            .unwrap_or_else(|| example.machine().start);
        if let Some(end) = example.end {
            asserted += 1;
            for (i, expected) in end.axes() {
                if let Some(expected) = expected {
                    if !close(last[i], expected, tolerance) {
                        failures.push(fail(format!(
                            "end {} is {:.4}, expected {expected}",
                            letter(i),
                            last[i]
                        )));
                    }
                }
            }
        }
        if let Some(points) = &example.points {
            if points.len() != motions.len() {
                failures.push(fail(format!(
                    "{} motions, expected {}: {:?}",
                    motions.len(),
                    points.len(),
                    motions
                )));
            } else {
                for (k, (point, actual)) in points.iter().zip(&motions).enumerate() {
                    for (i, expected) in point.axes() {
                        if let Some(expected) = expected {
                            if !close(actual[i], expected, tolerance) {
                                failures.push(fail(format!(
                                    "motion {} {} is {:.4}, expected {expected}",
                                    k + 1,
                                    letter(i),
                                    actual[i]
                                )));
                            }
                        }
                    }
                }
            }
        }
        if let Some(visits) = &example.visits {
            let mut next = 0;
            for (k, point) in visits.iter().enumerate() {
                match motions[next..]
                    .iter()
                    .position(|m| point.matches(m, tolerance))
                {
                    Some(i) => next += i + 1,
                    None => failures.push(fail(format!(
                        "visit {} {point:?} is not reached after visit {k}",
                        k + 1
                    ))),
                }
            }
        }
        let total = |rapid: bool| -> f64 {
            run.segments
                .iter()
                .filter(|s| {
                    matches!(s.kind, SegmentKind::Rapid { .. }) == rapid && s.motion().is_some()
                })
                .map(|s| s.length())
                .sum()
        };
        if let Some(expected) = example.feed_length {
            if !close(total(false), expected, tolerance.max(0.001)) {
                failures.push(fail(format!(
                    "feed length {:.4}, expected {expected}",
                    total(false)
                )));
            }
        }
        if let Some(expected) = example.rapid_length {
            if !close(total(true), expected, tolerance.max(0.001)) {
                failures.push(fail(format!(
                    "rapid length {:.4}, expected {expected}",
                    total(true)
                )));
            }
        }
        if let Some(expected) = example.dwell_seconds {
            let dwell: f64 = run
                .segments
                .iter()
                .map(|s| {
                    if let SegmentKind::Dwell { seconds } = s.kind {
                        seconds
                    } else {
                        0.0
                    }
                })
                .sum();
            if !close(dwell, expected, 1e-6) {
                failures.push(fail(format!("dwell {dwell} s, expected {expected}")));
            }
        }
        if let Some(expected) = &example.spindle_speeds {
            let speeds: Vec<f64> = run
                .segments
                .iter()
                .filter_map(|s| match s.kind {
                    SegmentKind::Spindle { speed, .. } => Some(speed),
                    _ => None,
                })
                .collect();
            let same = speeds.len() == expected.len()
                && speeds.iter().zip(expected).all(|(a, b)| close(*a, *b, 0.5));
            if !same {
                failures.push(fail(format!(
                    "spindle speeds {speeds:?}, expected {expected:?}"
                )));
            }
        }
    }
    println!(
        "seed examples: {} entries, {asserted} end positions asserted",
        table.example.len()
    );
    if !stale_skips.is_empty() {
        println!(
            "skipped entries that now run (remove their skip): {}",
            stale_skips.join(", ")
        );
    }
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
    assert!(
        asserted >= 20,
        "at least 20 examples must assert their end position, {asserted} do"
    );
}
