//! The command line on the input issue 19 is about: programs saved by other editors (a UTF-8
//! byte-order mark, old Mac line ends), a main program that repeats with M99 after a leading
//! `%`, and a machine file with a number out of range. The library's tests cover each path in
//! detail (`crates/vcnc/tests/it/input.rs`); these check what a user of `vcnc` sees.

use super::cli::vcnc;

/// Writes `text` to `name` in a directory of this test process, and gives its path.
fn temp_file(name: &str, text: &[u8]) -> String {
    let dir = std::env::temp_dir().join(format!("vcnc-cli-input-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

/// The `run --format json` report of `args`.
fn run_json(args: &[&str]) -> serde_json::Value {
    let out = vcnc(&[&["run", "--format", "json"], args].concat());
    serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
        panic!("{e}: {}", String::from_utf8_lossy(&out.stderr));
    })
}

#[test]
fn main_passes_repeat_a_program_that_starts_with_a_tape_mark() {
    let program = temp_file("passes.nc", b"%\nG90 G21 G17\nG1 X1. F100.\nG1 X0\nM99\n");
    let report = run_json(&["--main-passes", "10", &program]);
    assert_eq!(report["feed"]["moves"], 20, "{report:#}");
    assert_eq!(report["alarms"][0]["code"], "V086");
}

#[test]
fn a_byte_order_mark_and_old_mac_line_ends_run_as_the_same_program() {
    // The spindle runs: the run then has no warning that would name its file.
    let text = "%\nO0001\nG90 G0 X0 Y0 Z5. S1000 M03\nG1 X10. F300.\nY10.\nM30\n%\n";
    let plain = run_json(&[&temp_file("plain.nc", text.as_bytes())]);
    assert_eq!(plain["ok"], true, "{plain:#}");
    assert_eq!(plain["alarms"], serde_json::json!([]), "{plain:#}");
    assert_eq!(plain["feed"]["moves"], 2, "{plain:#}");
    for (name, bytes) in [
        ("bom.nc", [b"\xEF\xBB\xBF", text.as_bytes()].concat()),
        ("cr.nc", text.replace('\n', "\r").into_bytes()),
    ] {
        let report = run_json(&[&temp_file(name, &bytes)]);
        for key in ["ok", "blocks", "feed", "rapid", "alarms"] {
            assert_eq!(report[key], plain[key], "{name}: {key}");
        }
    }
}

#[test]
fn a_machine_file_number_out_of_range_is_refused_with_its_key_and_range() {
    let machine = String::from_utf8(vcnc(&["machine"]).stdout).unwrap();
    assert!(machine.contains("max_rpm = 12000.0"));
    let machine = temp_file(
        "negative-rpm.toml",
        machine
            .replace("max_rpm = 12000.0", "max_rpm = -5")
            .as_bytes(),
    );
    let program = temp_file("rpm.nc", b"G0 X1.\nM30\n");
    let out = vcnc(&["run", "--machine", &machine, &program]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(
        stderr.contains("spindle.max_rpm = -5: expected more than 0, up to 1000000"),
        "{stderr}"
    );
}
