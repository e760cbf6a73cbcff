//! `vcnc check`'s report: on standard output, a line of totals, directories searched,
//! repeated warnings folded, the file named on every diagnostic, and the one-line format.

use super::cli::{example, vcnc};
use std::path::PathBuf;

/// A directory of its own for a test.
fn test_dir(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("vcnc-check-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

const NO_FEED: &str = "G0 X1.\nG1 X2.\nM30\n";

/// Four holes tapped with the spindle stopped: one warning, four times.
const TAPS: &str = "G90 G21 G17\nG0 X0 Y0 Z10.\nG84 Z-10. R2. F100.\nX10.\nX20.\nX30.\nG80\nM30\n";

#[test]
fn the_report_is_on_standard_output_and_ends_with_the_totals() {
    let dir = test_dir("totals");
    std::fs::write(dir.join("bad.nc"), NO_FEED).unwrap();
    std::fs::write(dir.join("PART.MPF"), "G0 X=10\nCYCLE70(10,0,2,-5)\nM30\n").unwrap();
    let out = vcnc(&[
        "check",
        &example(),
        &dir.join("bad.nc").display().to_string(),
        &dir.join("PART.MPF").display().to_string(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(
        stdout.lines().last(),
        Some("3 programs: 1 ok, 1 with alarms, 1 not supported"),
        "{stdout}"
    );
    // A program vcnc cannot read is its own error, on standard error; the others are checked.
    let out = vcnc(&["check", "/no/such/file.nc", &example()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("/no/such/file.nc"));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.ends_with("2 programs: 1 ok, 0 with alarms, 0 not supported, 1 not read\n"),
        "{stdout}"
    );
}

#[test]
fn a_directory_stands_for_the_nc_programs_under_it() {
    let dir = test_dir("directory");
    std::fs::create_dir_all(dir.join("sub/.hidden")).unwrap();
    std::fs::write(dir.join("a.nc"), NO_FEED).unwrap();
    std::fs::write(dir.join("sub/b.NGC"), "G0 X1.\nM30\n").unwrap();
    std::fs::write(dir.join("sub/O1000"), "O1000\nG0 X1.\nM30\n").unwrap();
    std::fs::write(dir.join("sub/.hidden/c.nc"), NO_FEED).unwrap();
    std::fs::write(dir.join("README"), "GNU General Public License\n").unwrap();
    std::fs::write(dir.join("notes.md"), "G0 X1.\n").unwrap();
    let out = vcnc(&["check", "--format", "short", &dir.display().to_string()]);
    assert_eq!(out.status.code(), Some(1));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("a.nc:2:1: error[V030]"), "{stdout}");
    assert!(
        stdout.ends_with("3 programs: 2 ok, 1 with alarms, 0 not supported\n"),
        "{stdout}"
    );
}

#[test]
fn repeated_identical_warnings_are_folded() {
    let dir = test_dir("fold");
    let program = dir.join("taps.nc").display().to_string();
    std::fs::write(&program, TAPS).unwrap();
    let out = vcnc(&["check", &program]);
    assert_eq!(out.status.code(), Some(0));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(
        stdout.matches("tapping without a spindle speed").count(),
        1,
        "{stdout}"
    );
    assert!(
        stdout.contains("V070 x4: the same warning also at lines 4, 5, 6"),
        "{stdout}"
    );
    let out = vcnc(&["check", "--format", "short", &program]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("taps.nc:3:1: warning[V070]: tapping without a spindle speed"),
        "{stdout}"
    );
    assert!(stdout.contains("(x4)\n"), "{stdout}");
}

#[test]
fn every_diagnostic_of_a_sinumerik_program_names_its_file_and_place() {
    let dir = test_dir("whole");
    let program = dir.join("PART.MPF").display().to_string();
    std::fs::write(&program, "G0 X=10\nN20 CYCLE70(10,0,2,-5)\nM30\n").unwrap();
    let out = vcnc(&["check", &program]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains(&format!("┌─ {program}:2:5")), "{stdout}");
    let out = vcnc(&["check", "--format", "short", &program]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.starts_with(&format!(
            "{program}:2:5: error[V020]: CYCLE70 is not run yet (planned: issue 22"
        )),
        "{stdout}"
    );
}

#[test]
fn json_reports_each_program_s_result_and_the_totals() {
    let dir = test_dir("json");
    std::fs::write(dir.join("bad.nc"), NO_FEED).unwrap();
    let out = vcnc(&[
        "check",
        "--format",
        "json",
        &dir.display().to_string(),
        &example(),
    ]);
    let value: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(value["programs"][0]["result"], "alarm");
    assert_eq!(value["programs"][1]["result"], "ok");
    assert_eq!(value["totals"]["programs"], 2);
    assert_eq!(value["totals"]["alarm"], 1);
}

/// A quoted glob (`vcnc check 'dir/*.nc'`, or a shell that does not expand it) names the
/// matching files; one that matches nothing is said, and counted as not read.
#[test]
fn a_quoted_glob_names_the_programs_it_matches() {
    let dir = std::env::temp_dir().join(format!("vcnc-glob-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for name in ["a.nc", "b.nc", "c.txt.bak"] {
        std::fs::write(dir.join(name), "G0 X1.\nM30\n").unwrap();
    }
    let pattern = dir.join("*.nc").display().to_string();
    let out = vcnc(&["check", &pattern]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{stdout}");
    assert!(
        stdout.contains("a.nc: ok") && stdout.contains("b.nc: ok"),
        "{stdout}"
    );
    assert!(!stdout.contains("c.txt.bak"), "{stdout}");
    assert!(stdout.contains("2 programs: 2 ok"), "{stdout}");
    let none = dir.join("*.xyz").display().to_string();
    let out = vcnc(&["check", &none]);
    assert_ne!(out.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&out.stderr).contains("matches no file"));
}

/// A macro alarm in JSON says how the program got there, as the terminal view does: the
/// values its expression read and the call that ran the macro, each with its place.
#[test]
fn json_alarms_carry_their_labels() {
    let dir = std::env::temp_dir().join(format!("vcnc-labels-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let program = dir.join("macro.nc");
    std::fs::write(&program, "O1\nG65 P2 A0\nM30\nO2\n#2=10/#1\nM99\n").unwrap();
    let out = vcnc(&["check", "--format", "json", &program.display().to_string()]);
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let labels = &report["programs"][0]["alarms"][0]["labels"];
    assert_eq!(labels[0]["message"], "#1 = 0", "{report:#}");
    assert_eq!(labels[0]["line"], 5, "{report:#}");
    assert_eq!(
        labels[1]["message"], "this macro call ran O0002",
        "{report:#}"
    );
    assert_eq!(labels[1]["line"], 2, "{report:#}");
}
