//! Cycle times against LinuxCNC's real trajectory planner.
//!
//! Each program in tests/data/plan/lcnc/ was run through LinuxCNC 2.9 with lcnc-time
//! (`tools/record-lcnc-time.sh`), which stored the measured time as <stem>.json. Here vcnc times
//! the same program on a machine with the same limits and the `linuxcnc` planner habits; the
//! two must agree within 2 %. LinuxCNC is not needed to run this test.

use crate::common::plan;

use std::path::{Path, PathBuf};
use vcnc::summary::Summary;
use vcnc::{interpret_str, Options};

/// The agreement the issue asks for (#6, acceptance 3).
const TOLERANCE: f64 = 0.02;

/// Programs that miss the 2 %, with the error they have today and why. Each is asserted at its
/// current error so that a change either way shows up. None today.
///
/// `23_tiny_segments_g64` (200 segments of 0.05 mm at F6000) runs at the planner's floor of
/// about one servo cycle per segment, LinuxCNC's 49.02 mm/s cap. Its first recording (0.270 s)
/// came from a run in which LinuxCNC's speed dropped to 46 mm/s on some cycles; recorded again
/// (2026-11-25, four runs alike) it holds the cap on every cycle and takes 0.263 s, which vcnc
/// meets within 1.3 %.
const KNOWN_OFF: &[(&str, f64)] = &[];

fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/plan/lcnc")
}

/// A number after `"key":` in the recorded JSON (flat, one key per line).
fn json_number(text: &str, key: &str) -> Option<f64> {
    let needle = format!("\"{key}\":");
    let rest = &text[text.find(&needle)? + needle.len()..];
    let end = rest.find([',', '\n', '}']).unwrap_or(rest.len());
    rest[..end].trim().parse().ok()
}

/// The `--vel V --acc A [--blend-tol T]` of the program's first line.
fn limits_line(program: &str) -> (f64, f64, Option<f64>) {
    let first = program.lines().next().unwrap_or("");
    let words: Vec<&str> = first
        .trim_start_matches("(limits:")
        .trim_end_matches(')')
        .split_whitespace()
        .collect();
    let value = |flag: &str| {
        words
            .windows(2)
            .find(|w| w[0] == flag)
            .and_then(|w| w[1].parse().ok())
            .unwrap_or_else(|| panic!("{flag} missing in `{first}`"))
    };
    let tolerance = words
        .windows(2)
        .find(|w| w[0] == "--blend-tol")
        .and_then(|w| w[1].parse().ok());
    (value("--vel"), value("--acc"), tolerance)
}

struct Comparison {
    stem: String,
    /// The program's second comment: what it exercises.
    what: String,
    linuxcnc: f64,
    vcnc: f64,
    /// vcnc's length / feed estimate (`Summary::estimated_seconds`).
    estimate: f64,
}

fn compare_all() -> Vec<Comparison> {
    compare_dir(&data_dir())
}

/// The random programs of `cargo xtask gen-plan-programs` (issue 24), by name.
fn compare_random() -> Vec<Comparison> {
    compare_dir(&data_dir().join("random"))
}

fn compare_dir(dir: &Path) -> Vec<Comparison> {
    let mut programs: Vec<PathBuf> = std::fs::read_dir(dir)
        .expect("the folder of reference programs exists")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "ngc"))
        .collect();
    programs.sort();
    programs
        .iter()
        .map(|path| {
            let stem = path
                .file_stem()
                .unwrap_or_default()
                .to_string_lossy()
                .into_owned();
            let program = std::fs::read_to_string(path).expect("program readable");
            let json = std::fs::read_to_string(path.with_extension("json"))
                .unwrap_or_else(|_| panic!("{stem}.json missing: run tools/record-lcnc-time.sh"));
            let linuxcnc = json_number(&json, "seconds").expect("seconds in the JSON");
            let (speed, acceleration, tolerance) = limits_line(&program);
            // lcnc-time's --vel is also [TRAJ]MAX_LINEAR_VELOCITY, the path speed cap; its
            // --blend-tol is G64 P, the planner's corner tolerance.
            let mut planner = format!("habits = \"linuxcnc\"\nmax_path_rate = {:?}", speed * 60.0);
            if let Some(tolerance) = tolerance {
                // LinuxCNC blends with a tolerance only where the program's own `G64 P` sets
                // it: lcnc-time's --blend-tol, in the startup code, never reaches its planner.
                assert!(
                    program.lines().any(|l| l.starts_with("G64 P")),
                    "{stem}: a --blend-tol needs its `G64 P` in the program"
                );
                planner += &format!("\ncorner_tolerance = {tolerance:?}");
            }
            let machine = plan::machine(&plan::Limits {
                speed,
                acceleration,
                planner: &planner,
                // LinuxCNC's G4 P is seconds; its programs write every coordinate with a point.
                profile_overrides: "dwell.dwell_p = \"seconds_with_point\"",
                ..plan::Limits::default()
            });
            // lcnc-time counts from the first motion to the end of the last one.
            let vcnc = plan::total_seconds(&program, &machine);
            let mut summary = Summary::new(&machine);
            for item in interpret_str(&program, &machine, Options::default()).flatten() {
                summary.add_item(&item);
            }
            let what = program
                .lines()
                .nth(1)
                .unwrap_or("")
                .trim_matches(|c| c == '(' || c == ')')
                .to_string();
            Comparison {
                stem,
                what,
                linuxcnc,
                vcnc,
                estimate: summary.estimated_seconds(),
            }
        })
        .collect()
}

#[test]
fn every_reference_program_is_timed_within_two_percent_of_linuxcnc() {
    let comparisons = compare_all();
    assert!(
        comparisons.len() >= 20,
        "only {} reference programs",
        comparisons.len()
    );
    let mut report = String::new();
    let mut failed = 0;
    for c in &comparisons {
        let error = (c.vcnc - c.linuxcnc) / c.linuxcnc;
        let known = KNOWN_OFF.iter().find(|(stem, _)| *stem == c.stem);
        let ok = match known {
            Some((_, today)) => (error - today).abs() <= 0.002,
            None => error.abs() <= TOLERANCE,
        };
        let mark = match (ok, known) {
            (true, None) => "",
            (true, Some(_)) => "  (known, see KNOWN_OFF)",
            (false, _) => "  <-- off",
        };
        failed += usize::from(!ok);
        report.push_str(&format!(
            "{:<28} linuxcnc {:>8.3} s  vcnc {:>8.3} s  {:>+6.2} %{mark}\n",
            c.stem,
            c.linuxcnc,
            c.vcnc,
            100.0 * error
        ));
    }
    println!("{report}");
    assert_eq!(
        failed, 0,
        "{failed} program(s) off by more than 2 %:\n{report}"
    );
}

/// The README's table of the reference programs.
fn readme_table(comparisons: &[Comparison]) -> String {
    let mut table = String::from(
        "| program | what it exercises | LinuxCNC s | vcnc s | vcnc - LinuxCNC | length / feed s |\n\
         |---|---|---:|---:|---:|---:|\n",
    );
    for c in comparisons {
        table += &format!(
            "| `{}` | {} | {:.3} | {:.3} | {:+.2} % | {:.3} |\n",
            c.stem,
            c.what,
            c.linuxcnc,
            c.vcnc,
            100.0 * (c.vcnc - c.linuxcnc) / c.linuxcnc,
            c.estimate
        );
    }
    table
}

#[test]
fn the_readme_table_of_reference_times_is_up_to_date() {
    let readme_path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../README.md");
    let readme = std::fs::read_to_string(&readme_path).expect("README.md");
    let (begin, end) = (
        "<!-- plan-reference:begin -->\n",
        "<!-- plan-reference:end -->",
    );
    let start = readme
        .find(begin)
        .expect("README has the plan-reference markers")
        + begin.len();
    let stop = readme[start..].find(end).expect("end marker") + start;
    let expected = readme_table(&compare_all());
    assert!(
        readme[start..stop] == expected,
        "README.md's reference table is stale; replace it with:\n{expected}"
    );
}

/// One kind of random program: how far vcnc is from LinuxCNC over its programs.
struct KindSummary {
    kind: String,
    count: usize,
    /// The largest error, signed, and the program it is in.
    worst: (f64, String),
    /// The median of the absolute errors.
    median: f64,
}

/// The random programs' errors by kind (the part of the name before `_`).
fn random_by_kind(comparisons: &[Comparison]) -> Vec<KindSummary> {
    let mut kinds: Vec<KindSummary> = Vec::new();
    let mut errors: std::collections::BTreeMap<String, Vec<(f64, String)>> =
        std::collections::BTreeMap::new();
    for c in comparisons {
        let kind = c.stem.split('_').next().unwrap_or(&c.stem).to_string();
        let error = (c.vcnc - c.linuxcnc) / c.linuxcnc;
        errors
            .entry(kind)
            .or_default()
            .push((error, c.stem.clone()));
    }
    for (kind, mut list) in errors {
        let worst = list
            .iter()
            .max_by(|a, b| a.0.abs().total_cmp(&b.0.abs()))
            .cloned()
            .expect("a kind has programs");
        list.sort_by(|a, b| a.0.abs().total_cmp(&b.0.abs()));
        let middle = list.len() / 2;
        let median = if list.len() % 2 == 1 {
            list[middle].0.abs()
        } else {
            (list[middle - 1].0.abs() + list[middle].0.abs()) / 2.0
        };
        kinds.push(KindSummary {
            kind,
            count: list.len(),
            worst,
            median,
        });
    }
    kinds
}

/// Issue 24, acceptance 1: every random program within 2 % of LinuxCNC (120 programs, 20 of
/// each kind). What it took, each a setting of the `linuxcnc` habits (default_machine.toml):
/// blend arcs as segments of their own; near-tangent kinks passed at speed (chords_02, whose
/// rounded coordinates put the kink right at LinuxCNC's ratio, was 32.8 % fast without them);
/// the least time per segment over what the blends leave; a look-ahead of 50 segments past
/// each (chords_03); blend arcs bounded by the arcs next to them (arc chains, 3.5 % fast
/// before); the last segment entered as if a blend could still take half of it; a stop where
/// the path turns back within 2 degrees (rapids_14, 2.6 % fast before).
#[test]
fn every_random_program_is_timed_within_two_percent_of_linuxcnc() {
    let comparisons = compare_random();
    assert!(
        comparisons.len() >= 120,
        "only {} random programs recorded",
        comparisons.len()
    );
    // Every program and the table by kind, for `--nocapture`.
    for c in &comparisons {
        let error = (c.vcnc - c.linuxcnc) / c.linuxcnc;
        println!(
            "{:<12} linuxcnc {:>8.3} s  vcnc {:>8.3} s  {:>+7.2} %  {}",
            c.stem,
            c.linuxcnc,
            c.vcnc,
            100.0 * error,
            c.what
        );
    }
    println!("{}", readme_random_table(&random_by_kind(&comparisons)));
    let off: Vec<String> = comparisons
        .iter()
        .filter(|c| ((c.vcnc - c.linuxcnc) / c.linuxcnc).abs() > TOLERANCE)
        .map(|c| {
            format!(
                "{}: linuxcnc {:.3} s, vcnc {:.3} s",
                c.stem, c.linuxcnc, c.vcnc
            )
        })
        .collect();
    assert!(off.is_empty(), "{} off:\n{}", off.len(), off.join("\n"));
}

/// The README's table of the random programs by kind.
fn readme_random_table(kinds: &[KindSummary]) -> String {
    let mut table = String::from(
        "| kind | programs | worst vcnc - LinuxCNC | median abs error |\n|---|---:|---:|---:|\n",
    );
    for k in kinds {
        table += &format!(
            "| `{}` | {} | {:+.2} % (`{}`) | {:.2} % |\n",
            k.kind,
            k.count,
            100.0 * k.worst.0,
            k.worst.1,
            100.0 * k.median
        );
    }
    table
}

#[test]
fn the_readme_table_of_random_programs_is_up_to_date() {
    let readme_path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../README.md");
    let readme = std::fs::read_to_string(&readme_path).expect("README.md");
    let (begin, end) = ("<!-- plan-random:begin -->\n", "<!-- plan-random:end -->");
    let start = readme
        .find(begin)
        .expect("README has the plan-random markers")
        + begin.len();
    let stop = readme[start..].find(end).expect("end marker") + start;
    let expected = readme_random_table(&random_by_kind(&compare_random()));
    assert!(
        readme[start..stop] == expected,
        "README.md's table of random programs is stale; replace it with:\n{expected}"
    );
}

/// A SINUMERIK machine with the limits of the reference programs (100 mm/s, 1000 mm/s^2 on
/// every axis) and `planner` lines.
fn sinumerik_machine(planner: &str) -> vcnc::Machine {
    let mut text =
        String::from("name = \"test\"\nprofile = \"sinumerik\"\n[spindle]\nmax_rpm = 10000.0\n");
    for axis in ["x", "y", "z"] {
        text.push_str(&format!(
            "[axes.{axis}]\nmin = -5000.0\nmax = 5000.0\nrapid = 6000.0\nmax_feed = 6000.0\nacceleration = 1000.0\n"
        ));
    }
    text.push_str(&format!("[planner]\n{planner}\n"));
    vcnc::Machine::from_toml(&text).unwrap_or_else(|e| panic!("test machine: {e}\n{text}"))
}

/// The time of SINUMERIK program `text` on `machine`, from the first motion to the end.
fn sinumerik_seconds(text: &str, machine: &vcnc::Machine) -> f64 {
    let run = vcnc::interp::sinumerik::run_str(text, machine);
    let mut end = 0.0;
    for item in vcnc::plan::Planner::new(run, machine, vcnc::plan::PlanOptions::default()) {
        let item = item.unwrap_or_else(|alarm| panic!("alarm: {alarm:?}\n{text}"));
        if let Some(timed) = item.segment() {
            end = timed.t + timed.dt;
        }
    }
    end
}

/// The part of `sinumerik/g642_part.ngc` (its G0 and G1 lines) as a SINUMERIK program whose
/// path control is set by `setup`.
fn sinumerik_part(setup: &str) -> String {
    let ngc = std::fs::read_to_string(data_dir().join("sinumerik/g642_part.ngc"))
        .expect("the path-control part is readable");
    let moves: Vec<&str> = ngc
        .lines()
        .filter(|l| l.starts_with("G0 ") || l.starts_with("G1 "))
        .collect();
    format!("G90 G17 G71\n{setup}\n{}\nM30\n", moves.join("\n"))
}

/// Issue 22, acceptance 5: the path-control modes on one part (16 corners, most of them right
/// angles, at F3000) on the vcnc habits, ordered as they must be: an exact stop at every block
/// end is slowest; G64 slows at each corner within the machine's 0.02 mm; rounding within a
/// wider tolerance is faster, the wider the faster (CYCLE832's 0.05 mm, then G642's machine
/// tolerance of 0.1 mm); G641 with ADIS=0.5 rounds a right angle with a 0.5 mm radius (the leg
/// is the radius at 90 degrees), more than G642's 0.1 mm allows (0.1 * cos45 / (1 - cos45) =
/// 0.24 mm). ADIS=0 is G64 (seed 002 L8102-8424) and G9 on every block is G60.
#[test]
fn the_path_control_modes_order_the_time_of_a_part() {
    let machine = sinumerik_machine("");
    let time = |setup: &str| sinumerik_seconds(&sinumerik_part(setup), &machine);
    let g60 = time("G60 G601");
    let g64 = time("G64");
    let cycle832 = time("CYCLE832(0.05,1,1)");
    let g642 = time("G642");
    let g641 = time("G641 ADIS=0.5 ADISPOS=0.5");
    println!("G60 {g60:.4} G64 {g64:.4} CYCLE832 {cycle832:.4} G642 {g642:.4} G641 {g641:.4}");
    assert!(g60 > g64 + 0.01, "G60 {g60} against G64 {g64}");
    assert!(
        g64 > cycle832 + 0.01,
        "G64 {g64} against CYCLE832 {cycle832}"
    );
    assert!(
        cycle832 > g642 + 0.01,
        "CYCLE832 {cycle832} against G642 {g642}"
    );
    assert!(g642 > g641 + 0.01, "G642 {g642} against G641 {g641}");
    assert_eq!(time("G641 ADIS=0"), g64);
    assert_eq!(time("G643"), g642);
    // CYCLE832() and a machining type of 0 deselect: G64 with the machine's tolerance.
    assert_eq!(time("G642\nCYCLE832()"), g64);
    assert_eq!(time("CYCLE832(0.05,1,1)\nCYCLE832(0.05,0,1)"), g64);
    assert_eq!(time("CYCLE832(0.05,_OFF,1)\nCYCLE832(0,_OFF)"), g64);
    assert_eq!(time("CYCLE832(0.05,_FINISH)"), cycle832);
    assert_eq!(time("CYCLE832(0.05,_ROUGH,1)"), cycle832);
    let every_block: String = sinumerik_part("G64")
        .lines()
        .map(|l| {
            if l.starts_with("G1 ") {
                format!("{l} G9\n")
            } else {
                format!("{l}\n")
            }
        })
        .collect();
    let g9 = sinumerik_seconds(&every_block, &machine);
    // The first feed's start after the rapid stops either way; every G1 ends with a stop.
    assert!((g9 - g60).abs() < 1e-9, "G9 {g9} against G60 {g60}");
}

/// Issue 22, acceptance 5: G642 with CYCLE832's tolerance of 0.05 mm on the `linuxcnc` habits
/// is LinuxCNC's `G64 P0.05 Q0` (sinumerik/g642_part.ngc, recorded with
/// tools/record-lcnc-time.sh `sinumerik/g642_part`): within the 2 % of the other programs.
#[test]
fn g642_with_a_tolerance_is_timed_as_linuxcnc_times_g64_p() {
    let json = std::fs::read_to_string(data_dir().join("sinumerik/g642_part.json"))
        .expect("sinumerik/g642_part.json is recorded");
    let linuxcnc = json_number(&json, "seconds").expect("seconds in the JSON");
    let machine = sinumerik_machine("habits = \"linuxcnc\"\nmax_path_rate = 6000.0");
    let vcnc = sinumerik_seconds(&sinumerik_part("CYCLE832(0.05,1,1)"), &machine);
    let error = (vcnc - linuxcnc) / linuxcnc;
    println!(
        "linuxcnc {linuxcnc:.3} s, vcnc {vcnc:.3} s, {:+.2} %",
        100.0 * error
    );
    assert!(
        error.abs() <= TOLERANCE,
        "linuxcnc {linuxcnc} s, vcnc {vcnc} s"
    );
}

/// Path-control parameters outside what the control takes are alarms naming the cause: a
/// negative rounding distance, a machining type of CYCLE832 beyond 3 (units digit) or not
/// whole, a tolerance beyond what a motion keeps.
#[test]
fn path_control_parameters_out_of_range_are_alarms() {
    let machine = sinumerik_machine("");
    for (text, code, says) in [
        (
            "G641 ADIS=-1\nM30\n",
            vcnc::AlarmCode::ValueOutOfRange,
            "ADIS",
        ),
        (
            "ADISPOS=40\nM30\n",
            vcnc::AlarmCode::ValueOutOfRange,
            "ADISPOS",
        ),
        (
            "CYCLE832(0.01,4,1)\nM30\n",
            vcnc::AlarmCode::CycleParameter,
            "61002",
        ),
        (
            "CYCLE832(0.01,1.5,1)\nM30\n",
            vcnc::AlarmCode::CycleParameter,
            "61002",
        ),
        (
            "CYCLE832(50,1,1)\nM30\n",
            vcnc::AlarmCode::ValueOutOfRange,
            "CYCLE832",
        ),
    ] {
        let alarm = vcnc::interp::sinumerik::run_str(text, &machine)
            .find_map(Result::err)
            .unwrap_or_else(|| panic!("no alarm in\n{text}"));
        assert_eq!(alarm.code, code, "{text}");
        assert!(alarm.message.contains(says), "{text}: {}", alarm.message);
    }
}
