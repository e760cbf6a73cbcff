//! `cargo xtask record-lcnc [--check] [NAME ...]`: runs LinuxCNC's standalone interpreter
//! `rs274 -g` on the reference programs in crates/vcnc/tests/data/lcnc/*.ngc and stores what it
//! prints beside each program as `<stem>.canon`. The test suite reads those files; it never needs
//! LinuxCNC.
//!
//! NAME selects programs by file name or stem (`001-g0-g1-absolute` or `001-g0-g1-absolute.ngc`);
//! without names every program is recorded. `--check` records into memory only and fails when a
//! stored .canon file differs (or is missing).
//!
//! Each program runs as
//!
//! ```text
//! rs274 -t <dir>/tool.tbl -v <tmp>/rs274.var -g <dir>/<stem>.ngc
//! ```
//!
//! in a fresh temporary directory `<tmp>` that is also `HOME`, with `LC_ALL=C`. The empty parameter
//! file gives every program the same start (all work offsets and G28 home at 0, G54 active); rs274
//! writes its parameters back at the end, so reusing one file would carry G10 offsets from one
//! program into the next. `HOME` is set because rs274 keeps a tool-table memory map in
//! `$HOME/.tool.mmap`. `-t` is left out when there is no tool.tbl. A program counts as recorded
//! only when rs274 exits with status 0, prints nothing on stderr but its `executing` banner, and
//! its output ends the program (`PROGRAM_END()`): an interpreter error stops the output early.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

const INSTALL_HINT: &str =
    "install LinuxCNC's standalone interpreter with `apt-get install -y linuxcnc-uspace`";

pub(crate) fn run(args: &[String]) -> Result<(), String> {
    let mut check = false;
    let mut names = Vec::new();
    for arg in args {
        match arg.as_str() {
            "--check" => check = true,
            "-h" | "--help" => {
                println!("usage: cargo xtask record-lcnc [--check] [NAME ...]");
                return Ok(());
            }
            flag if flag.starts_with('-') => return Err(format!("unknown option `{flag}`")),
            name => names.push(name.trim_end_matches(".ngc").to_string()),
        }
    }
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../crates/vcnc/tests/data/lcnc");
    let dir = dir
        .canonicalize()
        .map_err(|e| format!("{}: {e}", dir.display()))?;
    let programs = select_programs(&dir, &names)?;
    let rs274 = find_rs274()?;
    let tool_table = Some(dir.join("tool.tbl")).filter(|p| p.is_file());

    let mut stale = Vec::new();
    for (index, program) in programs.iter().enumerate() {
        let stem = program
            .file_stem()
            .unwrap_or_default()
            .to_string_lossy()
            .into_owned();
        let output = record(&rs274, program, tool_table.as_deref(), index)?;
        let canon = program.with_extension("canon");
        let previous = std::fs::read(&canon).ok();
        let changed = previous.as_deref() != Some(output.as_bytes());
        let calls = output.lines().count();
        if check {
            if changed {
                stale.push(stem);
            }
        } else if changed {
            std::fs::write(&canon, &output).map_err(|e| format!("{}: {e}", canon.display()))?;
            let what = if previous.is_some() {
                "updated"
            } else {
                "recorded"
            };
            println!("{stem}.canon: {what} ({calls} canonical calls)");
        } else {
            println!("{stem}.canon: unchanged ({calls} canonical calls)");
        }
    }
    if !stale.is_empty() {
        return Err(format!(
            "{} .canon file(s) differ from what rs274 prints now: {} (run `cargo xtask record-lcnc`)",
            stale.len(),
            stale.join(", ")
        ));
    }
    if check {
        println!("{} .canon file(s) up to date", programs.len());
    }
    Ok(())
}

/// The .ngc files of `dir`, sorted, or only those named (every name must exist).
fn select_programs(dir: &Path, names: &[String]) -> Result<Vec<PathBuf>, String> {
    if !names.is_empty() {
        let mut programs = Vec::new();
        for name in names {
            let path = dir.join(format!("{name}.ngc"));
            if !path.is_file() {
                return Err(format!("no program {}", path.display()));
            }
            programs.push(path);
        }
        return Ok(programs);
    }
    let entries = std::fs::read_dir(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let mut programs = Vec::new();
    for entry in entries {
        let path = entry.map_err(|e| format!("{}: {e}", dir.display()))?.path();
        if path.extension().is_some_and(|e| e == "ngc") {
            programs.push(path);
        }
    }
    programs.sort();
    if programs.is_empty() {
        return Err(format!("no .ngc programs in {}", dir.display()));
    }
    Ok(programs)
}

/// `rs274` on PATH, or an error that says how to install it.
fn find_rs274() -> Result<PathBuf, String> {
    let path = std::env::var_os("PATH").unwrap_or_default();
    std::env::split_paths(&path)
        .map(|dir| dir.join("rs274"))
        .find(|candidate| candidate.is_file())
        .ok_or_else(|| format!("`rs274` was not found on PATH: {INSTALL_HINT}"))
}

/// Runs one program and returns rs274's standard output.
fn record(
    rs274: &Path,
    program: &Path,
    tool_table: Option<&Path>,
    index: usize,
) -> Result<String, String> {
    let name = program
        .file_name()
        .unwrap_or_default()
        .to_string_lossy()
        .into_owned();
    let scratch = ScratchDir::new(index)?;
    let var_file = scratch.path.join("rs274.var");
    std::fs::write(&var_file, "").map_err(|e| format!("{}: {e}", var_file.display()))?;

    let mut command = Command::new(rs274);
    if let Some(table) = tool_table {
        command.arg("-t").arg(table);
    }
    command
        .arg("-v")
        .arg(&var_file)
        .arg("-g")
        .arg(program)
        .current_dir(&scratch.path)
        .env("HOME", &scratch.path)
        .env("LC_ALL", "C")
        .stdin(Stdio::null());
    let output = command
        .output()
        .map_err(|e| format!("cannot run {}: {e} ({INSTALL_HINT})", rs274.display()))?;

    let stdout = String::from_utf8(output.stdout)
        .map_err(|_| format!("{name}: rs274 printed non-UTF-8 output"))?;
    let stderr = String::from_utf8_lossy(&output.stderr);
    let complaints: Vec<&str> = stderr
        .lines()
        .filter(|l| !l.trim().is_empty() && l.trim() != "executing")
        .collect();
    if !output.status.success() || !complaints.is_empty() {
        return Err(format!(
            "{name}: rs274 failed ({}):\n{}",
            output.status,
            if complaints.is_empty() {
                "(nothing on stderr)".to_string()
            } else {
                complaints.join("\n")
            }
        ));
    }
    if !stdout
        .lines()
        .any(|l| l.trim_end().ends_with("PROGRAM_END()"))
    {
        return Err(format!(
            "{name}: rs274's output has no PROGRAM_END(): does the program end with M2 or M30?"
        ));
    }
    Ok(stdout)
}

/// A temporary directory removed when dropped.
struct ScratchDir {
    path: PathBuf,
}

impl ScratchDir {
    fn new(index: usize) -> Result<Self, String> {
        let path =
            std::env::temp_dir().join(format!("vcnc-record-lcnc-{}-{index}", std::process::id()));
        if path.exists() {
            std::fs::remove_dir_all(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        }
        std::fs::create_dir_all(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        Ok(ScratchDir { path })
    }
}

impl Drop for ScratchDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.path);
    }
}
