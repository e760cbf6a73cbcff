//! `vcnc check`: run programs and report only their alarms and warnings, on standard output,
//! with a line of totals at the end. Errors of vcnc itself (a file it cannot read) go to
//! standard error; the other programs are still checked.
//!
//! A directory stands for the NC programs under it ([`NC_EXTENSIONS`], and files without an
//! extension whose first line looks like a program), searched recursively, in name order.

use super::{Outcome, SetupError};
use crate::diagnostics::Output;
use crate::program::Source;
use crate::progress::Progress;
use crate::setup::MachineArgs;
use clap::{Args as ClapArgs, ValueEnum};
use std::io::Write;
use std::path::{Path, PathBuf};
use vcnc::pipeline::Layout;
use vcnc::{Alarm, AlarmCode, Item};

/// Output format of the diagnostics.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum Format {
    /// For people, like rustc.
    Human,
    /// One line an alarm, `file:line:col: severity[code]: message`, for editors and grep.
    Short,
    /// One JSON document: `{"programs": [{"file", "ok", "result", "alarms": [...]}], "totals"}`.
    Json,
}

/// `vcnc check` arguments.
#[derive(ClapArgs, Debug)]
pub(crate) struct Args {
    /// The programs, or directories of programs (searched recursively for .nc .ngc .tap .cnc
    /// .txt .mpf .spf files and files without extension that start like a program; `-`:
    /// standard input). Globs are the shell's: a quoted `*.nc` is not expanded.
    #[arg(required = true)]
    programs: Vec<PathBuf>,
    /// Output format.
    #[arg(long, value_enum, default_value = "human")]
    format: Format,
    #[command(flatten)]
    machine: MachineArgs,
}

/// The extensions of NC programs a directory is searched for (compared without case).
pub(crate) const NC_EXTENSIONS: [&str; 7] = ["nc", "ngc", "tap", "cnc", "txt", "mpf", "spf"];

/// How a program's check ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Verdict {
    /// No error alarm (warnings perhaps).
    Ok,
    /// Stopped by an alarm.
    Alarm,
    /// Stopped because vcnc does not support what it uses yet (V020, V021).
    NotSupported,
    /// Could not be read.
    Unread,
}

impl Verdict {
    fn of(alarms: &[Alarm]) -> Verdict {
        match alarms.iter().find(|a| a.is_error()) {
            None => Verdict::Ok,
            Some(a)
                if matches!(
                    a.code,
                    AlarmCode::NotSupportedYet
                        | AlarmCode::DialectNotSupported
                        | AlarmCode::NotInProduct
                ) =>
            {
                Verdict::NotSupported
            }
            Some(_) => Verdict::Alarm,
        }
    }

    fn as_str(self) -> &'static str {
        match self {
            Verdict::Ok => "ok",
            Verdict::Alarm => "alarm",
            Verdict::NotSupported => "not_supported",
            Verdict::Unread => "not_read",
        }
    }
}

/// How many programs ended each way.
#[derive(Default)]
struct Totals {
    ok: usize,
    alarm: usize,
    not_supported: usize,
    unread: usize,
}

impl Totals {
    fn add(&mut self, verdict: Verdict) {
        *match verdict {
            Verdict::Ok => &mut self.ok,
            Verdict::Alarm => &mut self.alarm,
            Verdict::NotSupported => &mut self.not_supported,
            Verdict::Unread => &mut self.unread,
        } += 1;
    }

    fn programs(&self) -> usize {
        self.ok + self.alarm + self.not_supported + self.unread
    }

    /// `12 programs: 9 ok, 2 with alarms, 1 not supported` (and `, 1 not read`).
    fn line(&self) -> String {
        let n = self.programs();
        let mut line = format!(
            "{n} program{}: {} ok, {} with alarms, {} not supported",
            if n == 1 { "" } else { "s" },
            self.ok,
            self.alarm,
            self.not_supported
        );
        if self.unread > 0 {
            line.push_str(&format!(", {} not read", self.unread));
        }
        line
    }

    fn outcome(&self) -> Outcome {
        if self.unread > 0 {
            Outcome::Unread
        } else if self.alarm + self.not_supported > 0 {
            Outcome::Alarm
        } else {
            Outcome::Clean
        }
    }
}

pub(crate) fn run(args: &Args) -> Result<Outcome, SetupError> {
    args.machine.check()?;
    let machine = args.machine.machine()?;
    let options = args.machine.options()?;
    let mut totals = Totals::default();
    let mut reports = Vec::new();
    let stdout = std::io::stdout();
    for path in programs(&args.programs, &mut totals) {
        let checked = Source::read(&path).and_then(|source| {
            let mut stream = crate::program::open(
                &source,
                &machine,
                options.clone(),
                &args.machine,
                Layout::for_idle_consumer(),
            )?;
            let texts = crate::program::files(&stream, &source);
            let name = source.name().display().to_string();
            let scanning = super::run::scan_beside(&source);
            let mut progress = Progress::on_stderr(&name, args.format != Format::Json);
            let mut alarms: Vec<Alarm> = stream
                .by_ref()
                .filter_map(|item| match item {
                    Ok(Item::Segment(segment)) => {
                        progress.segment(segment.span.line);
                        None
                    }
                    Ok(Item::Frame(_)) => None,
                    Ok(Item::Warning(alarm)) | Err(alarm) => Some(alarm),
                })
                .collect();
            progress.finish();
            // What the text says of the control it was written for comes first.
            let scan = scanning.join().ok().flatten();
            alarms.splice(0..0, scan.map_or_else(Vec::new, |s| s.warnings(&machine)));
            let (_, saved) = crate::program::finish(stream, &args.machine);
            saved?;
            Ok((source, texts, alarms))
        });
        let (source, texts, alarms) = match checked {
            Ok(checked) => checked,
            Err(error) => {
                eprintln!("vcnc: {error}");
                totals.add(Verdict::Unread);
                if args.format == Format::Json {
                    reports.push(serde_json::json!({
                        "file": path.display().to_string(),
                        "ok": false,
                        "result": Verdict::Unread.as_str(),
                        "error": error.to_string(),
                        "alarms": [],
                    }));
                }
                continue;
            }
        };
        let verdict = Verdict::of(&alarms);
        totals.add(verdict);
        let written = match args.format {
            Format::Human => {
                crate::diagnostics::print_human(&texts, &alarms, Output::Stdout);
                writeln!(stdout.lock(), "{}", status(&source, verdict, &alarms))
            }
            Format::Short => crate::diagnostics::print_short(&texts, &alarms, &mut stdout.lock()),
            Format::Json => {
                let list: Vec<_> = alarms
                    .iter()
                    .map(|a| crate::diagnostics::to_json(&texts, a))
                    .collect();
                reports.push(serde_json::json!({
                    "file": source.name().display().to_string(),
                    "ok": verdict == Verdict::Ok,
                    "result": verdict.as_str(),
                    "alarms": list,
                }));
                Ok(())
            }
        };
        finish_writing(written)?;
    }
    let written = match args.format {
        Format::Json => writeln!(
            stdout.lock(),
            "{}",
            serde_json::json!({
                "programs": reports,
                "totals": {
                    "programs": totals.programs(),
                    "ok": totals.ok,
                    "alarm": totals.alarm,
                    "not_supported": totals.not_supported,
                    "not_read": totals.unread,
                },
            })
        ),
        Format::Human | Format::Short => writeln!(stdout.lock(), "{}", totals.line()),
    };
    finish_writing(written)?;
    Ok(totals.outcome())
}

/// A report that cannot be written is an error; a reader that went away (`| head`) is not.
fn finish_writing(written: std::io::Result<()>) -> Result<(), SetupError> {
    match written {
        Err(error) if error.kind() != std::io::ErrorKind::BrokenPipe => {
            Err(SetupError::Output(error))
        }
        _ => Ok(()),
    }
}

/// The line that ends a program's report: `part.nc: ok (2 warnings)`.
fn status(source: &Source, verdict: Verdict, alarms: &[Alarm]) -> String {
    let name = crate::excerpt::escape(&source.name().display().to_string());
    let warnings = alarms.iter().filter(|a| !a.is_error()).count();
    let warnings = match warnings {
        0 => String::new(),
        1 => " (1 warning)".to_string(),
        n => format!(" ({n} warnings)"),
    };
    let error = alarms.iter().find(|a| a.is_error());
    let stop = error.map_or(String::new(), |a| {
        format!(
            " {}{}",
            a.code.code(),
            a.span
                .map_or(String::new(), |s| format!(" at line {}", s.line))
        )
    });
    let verdict = match verdict {
        Verdict::Ok => "ok",
        Verdict::Alarm => "stopped by alarm",
        Verdict::NotSupported => "not supported:",
        Verdict::Unread => "not read",
    };
    format!("{name}: {verdict}{stop}{warnings}")
}

/// The programs the arguments name: files as given, directories searched. A directory that
/// cannot be read is reported and counted as a program not read.
fn programs(arguments: &[PathBuf], totals: &mut Totals) -> Vec<PathBuf> {
    let mut found = Vec::new();
    for argument in arguments {
        if argument.is_dir() {
            search(argument, &mut found, totals);
        } else if let Some(matches) = glob(argument) {
            // A quoted glob (or a shell that does not expand them): `*` and `?` in the file
            // name, matched in its folder, in name order.
            if matches.is_empty() {
                eprintln!("vcnc: {}: matches no file", argument.display());
                totals.add(Verdict::Unread);
            }
            found.extend(matches);
        } else {
            found.push(argument.clone());
        }
    }
    found
}

/// The files that `pattern` names, when it is a glob: a path that does not exist whose file
/// name holds `*` (any characters) or `?` (one character). Hidden files match only a pattern
/// that starts with `.`.
fn glob(pattern: &Path) -> Option<Vec<PathBuf>> {
    let name = pattern.file_name()?.to_string_lossy().into_owned();
    if pattern.exists() || !name.contains(['*', '?']) {
        return None;
    }
    let folder = match pattern.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let wanted: Vec<char> = name.chars().collect();
    let mut matches: Vec<PathBuf> = std::fs::read_dir(&folder)
        .map(|entries| {
            entries
                .filter_map(Result::ok)
                .filter(|e| e.path().is_file())
                .filter(|e| {
                    let file: Vec<char> = e.file_name().to_string_lossy().chars().collect();
                    (wanted.first() == Some(&'.') || file.first() != Some(&'.'))
                        && wildcard_match(&wanted, &file)
                })
                .map(|e| folder.join(e.file_name()))
                .collect()
        })
        .unwrap_or_default();
    matches.sort();
    Some(matches)
}

/// Whether `name` matches `pattern` (`*` any run of characters, `?` one character).
fn wildcard_match(pattern: &[char], name: &[char]) -> bool {
    // The classic two-pointer match with one backtrack point for the last `*`.
    let (mut p, mut n) = (0, 0);
    let mut star: Option<(usize, usize)> = None;
    while n < name.len() {
        match pattern.get(p) {
            Some('*') => {
                star = Some((p, n));
                p += 1;
            }
            Some(&c) if c == '?' || c == name[n] => {
                p += 1;
                n += 1;
            }
            _ => match star {
                Some((sp, sn)) => {
                    p = sp + 1;
                    n = sn + 1;
                    star = Some((sp, sn + 1));
                }
                None => return false,
            },
        }
    }
    pattern[p..].iter().all(|&c| c == '*')
}

/// Adds the NC programs under `directory` to `found`, in name order. Hidden entries (`.git`)
/// are skipped; links to directories are not followed (they can loop).
fn search(directory: &Path, found: &mut Vec<PathBuf>, totals: &mut Totals) {
    let entries = match std::fs::read_dir(directory) {
        Ok(entries) => entries,
        Err(error) => {
            eprintln!(
                "vcnc: cannot read directory {}: {error}",
                directory.display()
            );
            totals.add(Verdict::Unread);
            return;
        }
    };
    let mut entries: Vec<_> = entries.filter_map(Result::ok).collect();
    entries.sort_by_key(|e| e.file_name());
    for entry in entries {
        let path = entry.path();
        if entry.file_name().to_string_lossy().starts_with('.') {
            continue;
        }
        let Ok(kind) = entry.file_type() else {
            continue;
        };
        if kind.is_dir() {
            search(&path, found, totals);
        } else if is_program(&path) {
            found.push(path);
        }
    }
}

/// True for a file with an NC extension, or without extension and starting like a program.
fn is_program(path: &Path) -> bool {
    if !path.is_file() {
        return false;
    }
    match path.extension() {
        Some(extension) => {
            let extension = extension.to_string_lossy().to_ascii_lowercase();
            NC_EXTENSIONS.contains(&extension.as_str())
        }
        None => starts_like_a_program(path),
    }
}

/// True when the first line that is not blank starts as NC programs do: `%`, a program
/// number (`O1234`, `:1234`), a sequence number (`N10`), a G code (`G90`) or a comment `(`.
fn starts_like_a_program(path: &Path) -> bool {
    use std::io::Read;
    let mut head = Vec::new();
    let read = std::fs::File::open(path).and_then(|f| f.take(512).read_to_end(&mut head));
    if read.is_err() || head.contains(&0) {
        return false;
    }
    let text = String::from_utf8_lossy(&head);
    let mut chars = text.trim_start().chars();
    match (chars.next(), chars.next()) {
        (Some('%' | '('), _) => true,
        (Some('O' | 'o' | ':' | 'N' | 'n' | 'G' | 'g'), Some(c)) => c.is_ascii_digit(),
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wildcards_match_as_a_shell_does() {
        let m = |p: &str, n: &str| {
            wildcard_match(
                &p.chars().collect::<Vec<_>>(),
                &n.chars().collect::<Vec<_>>(),
            )
        };
        assert!(m("*.nc", "part.nc"));
        assert!(!m("*.nc", "part.ngc"));
        assert!(m("p?rt*", "part.nc"));
        assert!(m("*a*b*", "xaxxbx"));
        assert!(!m("*a*b", "xaxxbx"));
        assert!(m("*", ""));
        assert!(!m("?", ""));
        assert!(m("O00**1.nc", "O0001.nc"));
    }

    #[test]
    fn the_totals_line_counts_each_kind() {
        let mut totals = Totals::default();
        for verdict in [
            Verdict::Ok,
            Verdict::Ok,
            Verdict::Alarm,
            Verdict::NotSupported,
        ] {
            totals.add(verdict);
        }
        assert_eq!(
            totals.line(),
            "4 programs: 2 ok, 1 with alarms, 1 not supported"
        );
        assert_eq!(totals.outcome(), Outcome::Alarm);
        totals.add(Verdict::Unread);
        assert!(totals.line().ends_with(", 1 not read"));
        assert_eq!(totals.outcome(), Outcome::Unread);
    }
}
