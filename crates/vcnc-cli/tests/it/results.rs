//! Runs that used to end "ok" with a wrong or empty result (issue 19): each now ends with a
//! warning that says why, or with the right result.

use crate::cli::{temp_program, vcnc};

/// Standard output and standard error of `vcnc ARGS`, which must end with exit code 0.
fn ok(args: &[&str]) -> (String, String) {
    let out = vcnc(args);
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    (String::from_utf8(out.stdout).unwrap(), stderr)
}

/// A Haas program: its thread milling is the local subprogram N15, after M30.
const HAAS_LOCAL_CALL: &str = "O20\nG90 G21 G17 G54\nT1 M06\nM97 P15\nG0 Z100.\nM30\n\
N15 M03 S2000\nG0 X0. Y0. Z5.\nG1 Z-5. F300.\nG3 I5. J0.\nG0 Z5.\nM99\n";

#[test]
fn a_haas_local_call_on_the_default_profile_names_the_haas_profile() {
    let path = temp_program("local_call.nc", HAAS_LOCAL_CALL);
    let (stdout, stderr) = ok(&["run", &path]);
    assert!(stdout.contains("1 warning(s)"), "{stdout}");
    assert!(stderr.contains("warning[V100]"), "{stderr}");
    assert!(
        stderr.contains("looks written for the haas profile, not fanuc"),
        "{stderr}"
    );
    assert!(stderr.contains("`M97 P15` (line 4) calls N15"), "{stderr}");
    assert!(stderr.contains("--profile haas"), "{stderr}");
    // With the profile it names, the local subprogram cuts, and nothing is to be said.
    let (stdout, stderr) = ok(&["run", "--profile", "haas", &path]);
    assert!(!stderr.contains("V100"), "{stderr}");
    assert!(
        stdout.contains("cutting                 2 moves"),
        "{stdout}"
    );
    // `check` reports on standard output.
    let (stdout, _) = ok(&["check", &path]);
    assert!(stdout.contains("warning[V100]"), "{stdout}");
}

#[test]
fn a_system_variable_of_another_profile_names_that_profile() {
    let path = temp_program("haas_timer.nc", "#100 = #3020\nG0 X1.\nM30\n");
    let out = vcnc(&["check", &path]);
    // `check` reports on standard output.
    let stderr = String::from_utf8(out.stdout).unwrap();
    assert_eq!(
        out.status.code(),
        Some(1),
        "the variable is still an alarm: {stderr}"
    );
    assert!(stderr.contains("error[V082]"), "{stderr}");
    assert!(
        stderr.contains("#3020 (line 1) is a variable of haas, not of fanuc"),
        "{stderr}"
    );
}

#[test]
fn whole_units_without_decimal_points_are_warned_once_with_the_fix() {
    let path = temp_program(
        "whole_units.nc",
        "G90 G21 G17\nS1000 M3\nG0 X10 Y10\nZ5\nG1 Z-2 F100\nX60\nY40\nG0 Z5\nM30\n",
    );
    let (_, stderr) = ok(&["run", &path]);
    assert_eq!(stderr.matches("warning[V101]").count(), 1, "{stderr}");
    assert!(stderr.contains("`X10` has no decimal point"), "{stderr}");
    assert!(stderr.contains("0.0100 mm"), "{stderr}");
    assert!(
        stderr.contains("decimal_less = \"whole_units\""),
        "{stderr}"
    );
    // The machine file setting it names reads the program as meant, without a warning.
    let machine = temp_program(
        "whole_units.toml",
        &format!(
            "{}\n[profile_overrides.units]\ndecimal_less = \"whole_units\"\n",
            String::from_utf8(vcnc(&["machine"]).stdout).unwrap()
        ),
    );
    let out = vcnc(&["run", "--format", "json", "--machine", &machine, &path]);
    let value: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(value["alarms"].as_array().unwrap().len(), 0, "{value}");
    assert_eq!(value["extents"]["cutting"]["max"][0], 60.0, "{value}");
}

#[test]
fn a_program_written_in_increments_gets_no_warning() {
    let path = temp_program(
        "increments.nc",
        "G90 G21 G17\nS1000 M3\nG0 X10000 Y10000\nZ5000\nG1 Z-2000 F100\nX60000\nG4 X500\nM30\n",
    );
    let (_, stderr) = ok(&["run", &path]);
    assert!(!stderr.contains("V10"), "{stderr}");
}

#[test]
fn the_slowest_blocks_name_their_file_line_and_text() {
    let path = temp_program(
        "slow.nc",
        "G90 G21 G17\nS1000 M3\nG1 X100. F100.\nX110.\nM30\n",
    );
    let (stdout, _) = ok(&["run", &path]);
    let line = stdout
        .lines()
        .find(|l| l.starts_with("  slowest blocks"))
        .unwrap_or_else(|| panic!("{stdout}"));
    assert!(line.contains("slow.nc:3  G1 X100. F100."), "{stdout}");
    let (json, _) = ok(&["run", "--format", "json", &path]);
    let value: serde_json::Value = serde_json::from_str(&json).unwrap();
    let slowest = &value["time"]["slowest_blocks"][0];
    assert_eq!(slowest["file"], "slow.nc", "{slowest}");
    assert_eq!(slowest["line"], 3, "{slowest}");
    assert_eq!(slowest["text"], "G1 X100. F100.", "{slowest}");
}

#[test]
fn an_inch_program_shows_its_extents_in_inches_with_mm_beside() {
    let path = temp_program(
        "inch.nc",
        "G90 G20 G17\nS1000 M3\nG0 X0 Y0\nG1 X2. Y-0.5 F10.\nM30\n",
    );
    let (stdout, _) = ok(&["run", &path]);
    assert!(
        stdout.contains("extents cutting   X 0.0000 .. 2.0000  Y -0.5000 .. 0.0000  Z 0.0000 .. 0.0000 in\n                    X 0.000 .. 50.800  Y -12.700 .. 0.000  Z 0.000 .. 0.000 mm"),
        "{stdout}"
    );
    let (json, _) = ok(&["run", "--format", "json", &path]);
    let value: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(value["extents"]["program_unit"], "in", "{value}");
    // A metric program says its unit too.
    let (stdout, _) = ok(&[
        "run",
        &temp_program("mm.nc", "G21 S1000 M3\nG1 X2. F10.\nM30\n"),
    ]);
    assert!(stdout.contains("Z 0.000 .. 0.000 mm\n"), "{stdout}");
}

#[test]
fn cutting_with_the_spindle_stopped_and_too_fast_is_warned() {
    let stopped = temp_program("no_spindle.nc", "G90 G21\nG1 X10. F100.\nM30\n");
    let (stdout, stderr) = ok(&["run", &stopped]);
    assert!(stdout.contains("1 warning(s)"), "{stdout}");
    assert!(
        stderr.contains("warning[V102]: cutting with the spindle stopped"),
        "{stderr}"
    );
    assert!(stderr.contains("no_spindle.nc:2:1"), "{stderr}");
    let fast = temp_program("fast.nc", "G90 G21\nS30000 M3\nG1 X10. F100.\nM30\n");
    let (_, stderr) = ok(&["run", &fast]);
    assert!(
        stderr.contains(
            "warning[V103]: the spindle speed is above the machine's maximum of 12000 rpm"
        ),
        "{stderr}"
    );
}

#[test]
fn an_inch_program_without_g20_on_a_metric_profile_is_warned() {
    let path = temp_program(
        "inch_shop.nc",
        "O10020\n(T 1 = 1IN FACE MILL)\nS5000 M3\nG0 X-1.5 Y.51\nG1 Z-.1 F20.\nX3.51\nM30\n",
    );
    let (_, stderr) = ok(&["run", "--profile", "haas", &path]);
    assert!(stderr.contains("warning[V104]"), "{stderr}");
    assert!(stderr.contains("(`1IN`)"), "{stderr}");
    assert!(stderr.contains("add G20"), "{stderr}");
}
