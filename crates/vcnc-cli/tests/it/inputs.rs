//! Programs from pipes, FIFOs and standard input, and text that could upset a terminal or a
//! renderer (control bytes, a line of megabytes): each is read whole or alarmed, never run
//! empty, and its diagnostics stay short and printable. And the progress line a long run shows
//! on a terminal, never in a pipe.

use super::cli::{example, temp_program, vcnc};
use std::io::Write;
use std::process::{Command, Output, Stdio};

/// `vcnc args`, with `input` on its standard input (a pipe).
fn vcnc_with_input(args: &[&str], input: &[u8]) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_vcnc"))
        .args(args)
        .env("NO_COLOR", "1")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("vcnc runs");
    let mut stdin = child.stdin.take().unwrap();
    let input = input.to_vec();
    // Written on a thread: a program larger than the pipe's buffer would block both sides.
    let writer = std::thread::spawn(move || {
        let _ = stdin.write_all(&input);
    });
    let out = child.wait_with_output().expect("vcnc ends");
    writer.join().unwrap();
    out
}

fn blocks_of(out: &Output) -> u64 {
    let value: serde_json::Value = serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|_| panic!("{}", String::from_utf8_lossy(&out.stderr)));
    value["blocks"].as_u64().unwrap()
}

#[test]
fn a_program_on_standard_input_runs_whole_by_dash_and_by_dev_stdin() {
    let text = std::fs::read(example()).unwrap();
    for name in ["-", "/dev/stdin"] {
        let out = vcnc_with_input(&["run", "--format", "json", name], &text);
        assert_eq!(out.status.code(), Some(0), "{name}");
        assert_eq!(blocks_of(&out), 48, "{name}");
    }
    let out = vcnc_with_input(&["trace", "-"], &text);
    assert!(out.status.success());
    let moves = String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter(|l| l.contains("\"kind\":\"feed\""))
        .count();
    assert!(moves > 10, "{moves} cutting moves");
}

#[test]
fn an_empty_pipe_or_a_second_dash_is_an_error_not_an_empty_program() {
    let out = vcnc_with_input(&["check", "-"], b"");
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("<stdin>: nothing to read"), "{stderr}");
    let out = vcnc_with_input(&["check", "-", "-"], b"G0 X1.\nM30\n");
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("can be read once"), "{stderr}");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("2 programs: 1 ok"), "{stdout}");
}

#[test]
fn a_program_from_a_pipe_may_jump() {
    let program = b"#1=0\nWHILE [#1 LT 3] DO1\nG1 X[#1+1] F100.\n#1=#1+1\nEND1\nM30\n";
    let out = vcnc_with_input(&["run", "--format", "json", "-"], program);
    assert_eq!(out.status.code(), Some(0));
    let value: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(value["feed"]["moves"], 3, "{value}");
}

#[test]
fn a_diagnostic_of_standard_input_shows_its_line() {
    let out = vcnc_with_input(&["check", "-"], b"G0 X1.\nG1 X2.\nM30\n");
    assert_eq!(out.status.code(), Some(1));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("<stdin>:2:1"), "{stdout}");
    assert!(stdout.contains("G1 X2."), "{stdout}");
}

#[test]
fn a_fifo_is_read_once_and_whole() {
    let dir = std::env::temp_dir().join(format!("vcnc-fifo-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let fifo = dir.join("part.nc");
    let _ = std::fs::remove_file(&fifo);
    let Ok(status) = Command::new("mkfifo").arg(&fifo).status() else {
        return; // No mkfifo on this system.
    };
    assert!(status.success());
    let text = std::fs::read(example()).unwrap();
    let writer = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::write(fifo, text))
    };
    let mut child = Command::new(env!("CARGO_BIN_EXE_vcnc"))
        .args(["run", "--format", "json", &fifo.display().to_string()])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("vcnc runs");
    // Opening a FIFO a second time waits for a writer that is gone: a hang, ended here.
    let started = std::time::Instant::now();
    while child.try_wait().unwrap().is_none() {
        if started.elapsed() > std::time::Duration::from_secs(60) {
            child.kill().unwrap();
            panic!("vcnc hangs on a FIFO");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let out = child.wait_with_output().unwrap();
    writer.join().unwrap().unwrap();
    assert_eq!(out.status.code(), Some(0));
    assert_eq!(blocks_of(&out), 48);
}

#[test]
fn control_bytes_are_shown_escaped_never_raw() {
    let program = temp_program(
        "escape.nc",
        "G0 X1.\n\u{1b}[2J\u{1b}]0;title\u{7}G1 X2.\0\nM30\n",
    );
    for format in ["human", "short"] {
        let out = vcnc(&["check", "--format", format, &program]);
        assert_eq!(out.status.code(), Some(1));
        for (name, bytes) in [("stdout", &out.stdout), ("stderr", &out.stderr)] {
            let raw = bytes
                .iter()
                .find(|&&b| (b < 0x20 && b != b'\n' && b != b'\t') || b == 0x7f);
            assert_eq!(
                raw,
                None,
                "{format} {name}: {}",
                String::from_utf8_lossy(bytes)
            );
        }
    }
    let out = vcnc(&["check", &program]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("2 │ \\x1b[2J\\x1b]0;title\\x07G1 X2.\\x00"),
        "{stdout}"
    );
}

/// A line of `megabytes` MB without a newline, an unknown word near its end.
fn long_line(megabytes: usize) -> Vec<u8> {
    let mut text = b"G90 G21 G17\nG0 X1. ".to_vec();
    text.resize(megabytes * 1_000_000, b' ');
    let end = text.len() - 10;
    text[end..end + 3].copy_from_slice(b"&&&");
    text
}

/// The report on a long line shows a window of it, whatever its length.
fn assert_long_line_reported_briefly(megabytes: usize) {
    let program = temp_program(&format!("long{megabytes}.nc"), "");
    std::fs::write(&program, long_line(megabytes)).unwrap();
    let out = vcnc(&["check", &program]);
    assert_eq!(out.status.code(), Some(1));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("error[V001]"), "{stdout}");
    assert!(stdout.contains("&&&"), "{stdout}");
    assert!(
        out.stdout.len() < 2_000,
        "{} bytes of report",
        out.stdout.len()
    );
    let column = megabytes * 1_000_000 - 10 - 12 + 1;
    assert!(stdout.contains(&format!(":2:{column}")), "{stdout}");
}

#[test]
fn a_long_line_is_reported_as_a_window_around_the_alarm() {
    assert_long_line_reported_briefly(2);
}

/// The case: a 50 MB line (0.3 s in the debug build).
#[test]
fn a_50_mb_line_is_reported_as_a_window_around_the_alarm() {
    assert_long_line_reported_briefly(50);
}

/// A 50 MB line of words: refused at its 513th word, the rest never held (658 MB before).
/// Its peak memory is checked where `/usr/bin/time` is there to tell it.
#[test]
fn a_50_mb_line_of_words_is_refused_in_little_memory() {
    let program = temp_program("words50.nc", "");
    let mut text = b"G1 F100 ".to_vec();
    text.extend(b"X1. ".repeat(12_500_000));
    std::fs::write(&program, text).unwrap();
    let out = vcnc(&["check", "--format", "short", &program]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    assert!(stdout.contains("more than 512 words"), "{stdout}");
    let time = std::path::Path::new("/usr/bin/time");
    if !time.exists() {
        println!("note: /usr/bin/time is absent; the peak memory is not checked");
        return;
    }
    let measured = Command::new(time)
        .args(["-f", "%M", env!("CARGO_BIN_EXE_vcnc"), "check", &program])
        .output()
        .expect("time runs");
    let stderr = String::from_utf8_lossy(&measured.stderr);
    let kilobytes: u64 = stderr
        .lines()
        .last()
        .and_then(|l| l.trim().parse().ok())
        .unwrap_or_else(|| panic!("no peak in {stderr}"));
    assert!(kilobytes < 100_000, "{kilobytes} KB");
}

/// A loop of 200,000 moves, and progress told to show at once (a run of a second is not the
/// same on every machine).
const LONG_RUN: &str =
    "#1=0\nWHILE [#1 LT 200000] DO1\nG1 X[#1 MOD 100] F100000.\n#1=#1+1\nEND1\nM30\n";
const AFTER: (&str, &str) = ("VCNC_PROGRESS_AFTER_MS", "0");

#[test]
fn a_long_run_shows_progress_on_a_terminal_and_never_in_a_pipe() {
    let program = temp_program("long_run.nc", LONG_RUN);
    let piped = {
        let program = program.clone();
        std::thread::spawn(move || {
            Command::new(env!("CARGO_BIN_EXE_vcnc"))
                .args(["check", &program])
                .env(AFTER.0, AFTER.1)
                .output()
                .unwrap()
        })
    };
    // `script` runs the command on a terminal of its own (util-linux); without it, only the
    // pipe is checked.
    let command = format!("{} check {program}", env!("CARGO_BIN_EXE_vcnc"));
    let on_terminal = Command::new("script")
        .args(["-qec", &command, "/dev/null"])
        .env("NO_COLOR", "1")
        .env(AFTER.0, AFTER.1)
        .stdin(Stdio::null())
        .output();
    let piped = piped.join().unwrap();
    assert_eq!(piped.status.code(), Some(0));
    assert!(
        !piped.stderr.contains(&b'\r') && !piped.stdout.contains(&b'\r'),
        "{}",
        String::from_utf8_lossy(&piped.stderr)
    );
    if let Some(out) = on_terminal.ok().filter(|out| out.status.success()) {
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(text.contains("long_run.nc: line "), "{text}");
        assert!(text.contains(" segments, "), "{text}");
    }
}
