//! Golden traces: `vcnc trace` on a set of programs, compared line by line with the text kept in
//! `tests/golden/`. Any change of the motion stream, its times or the diagnostics shows up here
//! as a diff to review; a change that is meant is accepted by rewriting the files:
//! `VCNC_BLESS=1 cargo test -p vcnc-cli --test it golden::`.
//!
//! The programs are the bundled example and examples printed in the controllers' manuals, read
//! from `../shared/spec/examples` (or `$VCNC_SHARED/spec/examples`; each file's header names its manual and lines), chosen to
//! cover the stages of the pipeline: arcs and helices, cutter compensation, scaling, mirror,
//! rotation, polar coordinates, canned cycles and hole patterns, smoothing modes, exact stop
//! and continuous mode, subprograms and interrupts. Without `../shared` only the bundled example
//! is compared (with a notice; under CI its absence fails).

use crate::shared::shared_dir;
use std::path::{Path, PathBuf};
use std::process::Command;

/// (profile, folder the path is relative to, program path). The path goes on the command line
/// as written, so the `file` field of every record is the same on every machine.
const PROGRAMS: &[(&str, Folder, &str)] = &[
    ("fanuc", Folder::Repository, "examples/bracket.nc"),
    ("syntec", Folder::Examples, "syntec/10-helical.nc"),
    ("syntec", Folder::Examples, "syntec/14-g05-hpcc.nc"),
    (
        "syntec",
        Folder::Examples,
        "syntec/20-g16-polar-absolute.nc",
    ),
    ("syntec", Folder::Examples, "syntec/34-g41-flower-slot.nc"),
    ("syntec", Folder::Examples, "syntec/39-g51-scaling.nc"),
    ("syntec", Folder::Examples, "syntec/40-g51-unequal-arc.nc"),
    (
        "syntec",
        Folder::Examples,
        "syntec/42-g51.1-mirror-flower.nc",
    ),
    (
        "syntec",
        Folder::Examples,
        "syntec/48-g68-rotation-4-petals.nc",
    ),
    ("syntec", Folder::Examples, "syntec/55-g83-peck-drill.nc"),
    (
        "syntec",
        Folder::Examples,
        "syntec/63-g92.1-rotated-preset.nc",
    ),
    ("syntec", Folder::Examples, "syntec/67-g134-bolt-circle.nc"),
    (
        "syntec",
        Folder::Examples,
        "syntec/74-m96-interrupt-main.nc",
    ),
    (
        "fanuc0m",
        Folder::Examples,
        "fanuc0m/17-o2127-g43-g42-contour.nc",
    ),
    (
        "fanuc0m",
        Folder::Examples,
        "fanuc0m/20-o1313-g64-corners.nc",
    ),
    ("fanuc0m", Folder::Examples, "fanuc0m/23-o1616-g73-g74.nc"),
    (
        "mitsubishi",
        Folder::Examples,
        "mitsubishi/02-g01-parallelogram.nc",
    ),
];

#[derive(Clone, Copy)]
enum Folder {
    /// The repository's root.
    Repository,
    /// `../shared/spec/examples`, or `$VCNC_SHARED/spec/examples`.
    Examples,
}

/// The folder `which` names; `None` for the examples when `shared` (the reference material) is.
fn folder(which: Folder, shared: Option<&Path>) -> Option<PathBuf> {
    match which {
        Folder::Repository => Some(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")),
        Folder::Examples => shared.map(|dir| dir.join("spec/examples")),
    }
}

/// The snapshot text of one run: the command, what it wrote to standard output, and its
/// diagnostics.
fn snapshot(profile: &str, cwd: &Path, program: &str) -> String {
    let output = Command::new(env!("CARGO_BIN_EXE_vcnc"))
        .args(["trace", "--profile", profile, program])
        .current_dir(cwd)
        .env("NO_COLOR", "1")
        .output()
        .expect("vcnc runs");
    format!(
        "# vcnc trace --profile {profile} {program}\n{}# exit {}, diagnostics:\n{}",
        String::from_utf8_lossy(&output.stdout),
        output.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&output.stderr)
    )
}

fn snapshot_path(program: &str) -> PathBuf {
    let name = program.replace('/', "-").replace(".nc", ".trace");
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/golden")
        .join(name)
}

/// Where two texts first differ, with the line from each.
fn first_difference(expected: &str, actual: &str) -> String {
    let (mut e, mut a) = (expected.lines(), actual.lines());
    for number in 1.. {
        match (e.next(), a.next()) {
            (Some(x), Some(y)) if x == y => {}
            (None, None) => break,
            (x, y) => {
                return format!(
                    "line {number}\n  expected: {}\n  actual:   {}",
                    x.unwrap_or("(end)"),
                    y.unwrap_or("(end)")
                )
            }
        }
    }
    "only in line endings".to_string()
}

#[test]
fn traces_match_their_golden_files() {
    let bless = std::env::var_os("VCNC_BLESS").is_some();
    let shared = shared_dir();
    let mut failures = Vec::new();
    for &(profile, which, program) in PROGRAMS {
        let Some(cwd) = folder(which, shared.as_deref()) else {
            continue;
        };
        let actual = snapshot(profile, &cwd, program);
        let path = snapshot_path(program);
        if bless {
            std::fs::write(&path, &actual).unwrap();
            continue;
        }
        match std::fs::read_to_string(&path) {
            Ok(expected) if expected == actual => {}
            Ok(expected) => failures.push(format!(
                "{program}: differs from {} at {}",
                path.display(),
                first_difference(&expected, &actual)
            )),
            Err(e) => failures.push(format!("{program}: cannot read {}: {e}", path.display())),
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} traces changed (review, then VCNC_BLESS=1 to accept):\n{}",
        failures.len(),
        PROGRAMS.len(),
        failures.join("\n")
    );
}

#[test]
fn every_golden_file_belongs_to_a_program() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/golden");
    let known: Vec<PathBuf> = PROGRAMS.iter().map(|p| snapshot_path(p.2)).collect();
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        assert!(
            known.contains(&path),
            "stale golden file {}",
            path.display()
        );
    }
}
