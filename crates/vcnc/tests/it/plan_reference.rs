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

/// The worst error of each kind: a change that makes a kind's worst program worse fails; one
/// that makes it better lowers its line here. Kinds not listed are within 2 % (drilling; zigzags
/// and pockets since their programs carry their own `G64 P`). On 2026-11-28, before LinuxCNC's
/// blend arcs were modelled as segments of their own, chords were off by up to +334 % and rapid
/// tours by -17.7 %. Left: `chords_02` (0.1 mm chords of a circle at F6000), where LinuxCNC's
/// speed wanders between 49 mm/s (0.1 mm in two of its 1.02 ms segment cycles) and 95 mm/s
/// (its per-cycle trace) while vcnc holds 98 mm/s; chains of arcs at F4800, where vcnc is up
/// to 3.5 % faster (next to a G2/G3 LinuxCNC's blend arcs mostly give up for parabolic blends,
/// which vcnc does not model); one rapid tour 2.6 % faster.
const RANDOM_WORST_TODAY: &[(&str, f64)] =
    &[("arcs", 0.0350), ("chords", 0.3279), ("rapids", 0.0258)];

#[test]
fn the_random_programs_of_each_kind_get_no_worse() {
    let comparisons = compare_random();
    assert!(
        comparisons.len() >= 120,
        "only {} random programs recorded",
        comparisons.len()
    );
    let kinds = random_by_kind(&comparisons);
    let report = readme_random_table(&kinds);
    // Every program, for `--nocapture`.
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
    println!("{report}");
    for k in &kinds {
        let today = RANDOM_WORST_TODAY
            .iter()
            .find(|(kind, _)| *kind == k.kind)
            .map_or(TOLERANCE, |(_, worst)| worst.max(TOLERANCE));
        assert!(
            k.worst.0.abs() <= today + 0.002,
            "{}: {} is {:+.2} % off LinuxCNC, more than today's worst {:.2} %\n{report}",
            k.kind,
            k.worst.1,
            100.0 * k.worst.0,
            100.0 * today
        );
    }
}

/// Issue 24, acceptance 1: every random program within 2 % of LinuxCNC.
#[test]
#[ignore = "issue 24: the planner misses LinuxCNC by more than 2 % on some random programs (RANDOM_WORST_TODAY)"]
fn every_random_program_is_timed_within_two_percent_of_linuxcnc() {
    let comparisons = compare_random();
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
