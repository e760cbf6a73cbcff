//! The machine state file (persistent variables #500-#999): only `run` keeps it by default,
//! `--no-state` keeps none, and a file that cannot be trusted or saved to stops the command
//! with an error instead of being replaced or dropped.

use super::cli::{temp_program, vcnc};
use std::path::PathBuf;

/// A directory of its own for a test, with the default machine file in it.
fn machine_dir(test: &str) -> (PathBuf, String) {
    let dir = std::env::temp_dir().join(format!("vcnc-state-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let machine = dir.join("mill.toml");
    std::fs::write(&machine, vcnc(&["machine"]).stdout).unwrap();
    (dir, machine.display().to_string())
}

/// A program that counts its runs in #500 and alarms when it has run before.
const COUNTS_RUNS: &str = "#500=#500+1\nIF [#500 NE 1] THEN #3000=1(RAN BEFORE)\nM30\n";

#[test]
fn check_and_trace_leave_no_state_file_and_give_the_same_result_each_time() {
    let (dir, machine) = machine_dir("check");
    let program = temp_program("counts_check.nc", COUNTS_RUNS);
    for _ in 0..3 {
        for command in ["check", "trace"] {
            let out = vcnc(&[command, "--machine", &machine, &program]);
            assert_eq!(
                out.status.code(),
                Some(0),
                "{command}: {}",
                String::from_utf8_lossy(&out.stdout)
            );
        }
    }
    assert!(!dir.join("mill.state.toml").exists());
}

#[test]
fn run_keeps_the_state_beside_the_machine_file_unless_told_not_to() {
    let (dir, machine) = machine_dir("run");
    let program = temp_program("counts_run.nc", COUNTS_RUNS);
    for _ in 0..3 {
        let out = vcnc(&["run", "--no-state", "--machine", &machine, &program]);
        assert_eq!(out.status.code(), Some(0));
    }
    assert!(!dir.join("mill.state.toml").exists());
    assert_eq!(
        vcnc(&["run", "--machine", &machine, &program])
            .status
            .code(),
        Some(0)
    );
    assert!(dir.join("mill.state.toml").exists());
    // The second run sees the first's #500: the program's own alarm.
    assert_eq!(
        vcnc(&["run", "--machine", &machine, &program])
            .status
            .code(),
        Some(1)
    );
}

#[test]
fn a_read_only_state_file_is_an_error_and_stays_as_it_was() {
    let (dir, _) = machine_dir("readonly");
    let state = dir.join("kept.toml");
    let text = "[variables]\n\"#500\" = 41.0\n";
    std::fs::write(&state, text).unwrap();
    let mut permissions = std::fs::metadata(&state).unwrap().permissions();
    permissions.set_readonly(true);
    std::fs::set_permissions(&state, permissions).unwrap();
    let program = temp_program("counts_readonly.nc", COUNTS_RUNS);
    let out = vcnc(&["run", "--state", &state.display().to_string(), &program]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("read-only"), "{stderr}");
    assert_eq!(std::fs::read_to_string(&state).unwrap(), text);
}

#[test]
fn a_state_file_with_wrong_types_or_unknown_keys_is_an_error_and_stays_as_it_was() {
    let (dir, _) = machine_dir("malformed");
    let program = temp_program("counts_malformed.nc", COUNTS_RUNS);
    for (case, text) in [
        (
            "a string",
            "[variables]\n\"#500\" = \"abc\"\n\"#501\" = 2.0\n",
        ),
        ("a name", "[variables]\nspeed = 2.0\n"),
        ("a table", "[variables]\n\"#500\" = 1.0\n[other]\nx = 1\n"),
        ("a key", "version = 2\n[variables]\n\"#500\" = 1.0\n"),
        ("not TOML", "[variables\n"),
    ] {
        let state = dir.join("bad.toml");
        std::fs::write(&state, text).unwrap();
        let out = vcnc(&["run", "--state", &state.display().to_string(), &program]);
        assert_eq!(out.status.code(), Some(2), "{case}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains("bad.toml"), "{case}: {stderr}");
        assert_eq!(std::fs::read_to_string(&state).unwrap(), text, "{case}");
    }
}

#[test]
fn a_state_that_cannot_be_saved_is_an_error() {
    let state = std::env::temp_dir()
        .join(format!("vcnc-no-such-dir-{}", std::process::id()))
        .join("state.toml");
    let program = temp_program("counts_unsaved.nc", COUNTS_RUNS);
    let out = vcnc(&["run", "--state", &state.display().to_string(), &program]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("cannot save state file"), "{stderr}");
    // The summary is still printed before the error.
    assert!(String::from_utf8_lossy(&out.stdout).contains("ended with M30"));
}
