//! Alarms for people (rustc-style, with the source line and the word underlined), for editors
//! and grep (one line each: `file:line:col: severity[code]: message`) and for machines (JSON).
//!
//! Whatever a program holds, the terminal never gets a raw control byte from it (they are
//! shown escaped, `\x1b`), and a long line is shown as a window around its column
//! (`excerpt.rs`): rendering never costs the whole line.

use crate::excerpt::{escape, Excerpts, Region};
use codespan_reporting::diagnostic::{Diagnostic, Label, Severity as CsSeverity};
use codespan_reporting::term::termcolor::{ColorChoice, StandardStream};
use codespan_reporting::term::{self, Config};
use serde_json::{json, Value};
use std::collections::HashMap;
use std::fs::File;
use std::io::{Cursor, IsTerminal, Read, Seek, SeekFrom, Write};
use std::path::PathBuf;
use std::sync::Arc;
use vcnc::pipeline::ProgramFiles;
use vcnc::{Alarm, FileId, Severity, Span};

/// The files of a run, for the lines the diagnostics show (a program read from a pipe is held
/// in memory from the start: it cannot be read again).
pub(crate) struct Texts {
    files: ProgramFiles,
    main: Option<Arc<[u8]>>,
}

impl Texts {
    /// The files of a run; `main` is the main program's text when it is held in memory.
    pub(crate) fn new(files: ProgramFiles, main: Option<Arc<[u8]>>) -> Texts {
        Texts { files, main }
    }

    /// The name of `file` as the diagnostics show it.
    pub(crate) fn name(&self, file: FileId) -> String {
        escape(&self.path(file).display().to_string())
    }

    fn path(&self, file: FileId) -> PathBuf {
        self.files.path(file)
    }

    /// The whole text of `file` (empty when it cannot be read any more): the viewer's program panel.
    pub(crate) fn text(&self, file: FileId) -> Vec<u8> {
        match (&self.main, file) {
            (Some(text), FileId(0)) => text.to_vec(),
            _ => std::fs::read(self.path(file)).unwrap_or_default(),
        }
    }

    /// The file name of `file` (without its folders), and up to `most` bytes of its text from
    /// `span`'s start to the line's end, escaped: a block as the summary names it.
    pub(crate) fn block(&self, span: Span, most: u64) -> (String, String) {
        let path = self.path(span.file);
        let name = path.file_name().map_or_else(
            || path.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        );
        let mut bytes = Vec::new();
        let start = u64::from(span.start);
        match (&self.main, span.file) {
            (Some(text), FileId(0)) => {
                let from = (start as usize).min(text.len());
                let to = (from + most as usize).min(text.len());
                bytes.extend_from_slice(&text[from..to]);
            }
            _ => {
                if let Ok(mut file) = File::open(&path) {
                    if file.seek(SeekFrom::Start(start)).is_ok() {
                        let _ = file.take(most).read_to_end(&mut bytes);
                    }
                }
            }
        }
        let end = bytes.iter().position(|&b| b == b'\n' || b == b'\r');
        let text = String::from_utf8_lossy(&bytes[..end.unwrap_or(bytes.len())]).into_owned();
        (escape(&name), escape(text.trim_end()))
    }

    /// The bytes around `span`'s start (none when its file cannot be read any more).
    fn region(&self, span: Span) -> Region {
        let read = match (&self.main, span.file) {
            (Some(text), FileId(0)) => Region::read(&mut Cursor::new(&text[..]), span.start),
            _ => File::open(self.path(span.file))
                .and_then(|mut file| Region::read(&mut file, span.start)),
        };
        read.unwrap_or_else(|_| Region::empty())
    }
}

/// Where a diagnostic goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Output {
    Stdout,
    Stderr,
}

/// An alarm and how many identical ones it stands for (warnings repeat: the same V070 on
/// every block of a loop); the lines of the others.
pub(crate) struct Folded<'a> {
    pub(crate) alarm: &'a Alarm,
    pub(crate) lines: Vec<u32>,
}

impl Folded<'_> {
    /// How many alarms this one stands for.
    pub(crate) fn count(&self) -> usize {
        self.lines.len() + 1
    }
}

/// `alarms` with each warning that repeats an earlier one (same code, same message) folded
/// into the first; errors are never folded.
pub(crate) fn fold(alarms: &[Alarm]) -> Vec<Folded<'_>> {
    let mut folded: Vec<Folded> = Vec::new();
    let mut first: HashMap<(&str, &str), usize> = HashMap::new();
    for alarm in alarms {
        if !alarm.is_error() {
            let key = (alarm.code.code(), alarm.message.as_str());
            if let Some(&index) = first.get(&key) {
                folded[index].lines.push(alarm.span.map_or(0, |s| s.line));
                continue;
            }
            first.insert(key, folded.len());
        }
        folded.push(Folded {
            alarm,
            lines: Vec::new(),
        });
    }
    folded
}

/// How many lines of a folded warning are named.
const LINES_NAMED: usize = 5;

fn repeat_note(folded: &Folded) -> Option<String> {
    if folded.lines.is_empty() {
        return None;
    }
    let mut named: Vec<String> = folded
        .lines
        .iter()
        .take(LINES_NAMED)
        .map(u32::to_string)
        .collect();
    if folded.lines.len() > LINES_NAMED {
        named.push(format!("{} more", folded.lines.len() - LINES_NAMED));
    }
    Some(format!(
        "{} x{}: the same warning also at line{} {}",
        folded.alarm.code.code(),
        folded.count(),
        if folded.lines.len() == 1 { "" } else { "s" },
        named.join(", ")
    ))
}

/// Prints alarms of one program like rustc prints errors, identical warnings folded; an alarm
/// in a called program shows that program's line, an alarm of the whole file its name.
pub(crate) fn print_human(texts: &Texts, alarms: &[Alarm], output: Output) {
    if alarms.is_empty() {
        return;
    }
    let terminal = match output {
        Output::Stdout => std::io::stdout().is_terminal(),
        Output::Stderr => std::io::stderr().is_terminal(),
    };
    let color = if std::env::var_os("NO_COLOR").is_none() && terminal {
        ColorChoice::Auto
    } else {
        ColorChoice::Never
    };
    let writer = match output {
        Output::Stdout => StandardStream::stdout(color),
        Output::Stderr => StandardStream::stderr(color),
    };
    let config = Config::default();
    for folded in fold(alarms) {
        let (excerpts, diagnostic) = to_codespan(&folded, texts);
        let _ = term::emit(&mut writer.lock(), &config, &excerpts, &diagnostic);
    }
}

/// Prints alarms one a line, `file:line:col: severity[code]: message`, identical warnings
/// folded (`(x8)` at the end).
pub(crate) fn print_short(
    texts: &Texts,
    alarms: &[Alarm],
    out: &mut impl Write,
) -> std::io::Result<()> {
    for folded in fold(alarms) {
        let alarm = folded.alarm;
        let file = alarm.span.map_or(FileId(0), |s| s.file);
        let place = match alarm.span {
            Some(span) => {
                let column = texts.region(span).column();
                format!("{}:{}:{column}", texts.name(file), span.line)
            }
            None => texts.name(file),
        };
        let repeats = match folded.count() {
            1 => String::new(),
            n => format!(" (x{n})"),
        };
        writeln!(
            out,
            "{place}: {}[{}]: {}{repeats}",
            alarm.severity.as_str(),
            alarm.code.code(),
            escape(&alarm.message)
        )?;
    }
    Ok(())
}

/// One alarm as a JSON object: file, line, column, code, id, severity, message, help, and the
/// labels of its other places when it has any.
pub(crate) fn to_json(texts: &Texts, alarm: &Alarm) -> Value {
    let file = alarm.span.map_or(FileId(0), |s| s.file);
    let (line, column) = match alarm.span {
        Some(span) => (Some(span.line), Some(texts.region(span).column())),
        None => (None, None),
    };
    let mut value = json!({
        "file": texts.path(file).display().to_string(),
        "line": line,
        "column": column,
        "code": alarm.code.code(),
        "id": alarm.code.id(),
        "severity": alarm.severity.as_str(),
        "message": alarm.message,
        "help": alarm.help_line(),
    });
    // The other places an alarm names (the calls that led to a macro alarm, the values its
    // expression read, the first of two words): only when it has some.
    if !alarm.labels.is_empty() {
        let labels: Vec<Value> = alarm
            .labels
            .iter()
            .map(|label| {
                json!({
                    "file": texts.path(label.span.file).display().to_string(),
                    "line": label.span.line,
                    "column": texts.region(label.span).column(),
                    "message": label.message,
                })
            })
            .collect();
        value["labels"] = Value::Array(labels);
    }
    value
}

/// The diagnostic of `folded` and the excerpts of the lines it shows. An alarm without a
/// place (a whole file's) points at the start of the main program, so that it names its file.
fn to_codespan(folded: &Folded, texts: &Texts) -> (Excerpts, Diagnostic<usize>) {
    let alarm = folded.alarm;
    let severity = match alarm.severity {
        Severity::Error => CsSeverity::Error,
        Severity::Warning => CsSeverity::Warning,
    };
    let mut excerpts = Excerpts::default();
    let mut ids: Vec<FileId> = Vec::new();
    let mut place = |span: Span, excerpts: &mut Excerpts| {
        let id = match ids.iter().position(|&f| f == span.file) {
            Some(id) => id,
            None => {
                ids.push(span.file);
                excerpts.add_file(texts.name(span.file))
            }
        };
        (id, excerpts.add_line(id, &texts.region(span), span))
    };
    let mut labels = Vec::new();
    let primary = alarm.span.unwrap_or(Span::new(FileId(0), 1, 0..0));
    let (id, range) = place(primary, &mut excerpts);
    labels.push(Label::primary(id, range));
    for label in &alarm.labels {
        let (id, range) = place(label.span, &mut excerpts);
        labels.push(Label::secondary(id, range).with_message(escape(&label.message)));
    }
    let mut notes = Vec::new();
    notes.push(format!("help: {}", escape(alarm.help_line())));
    notes.extend(repeat_note(folded));
    let diagnostic = Diagnostic::new(severity)
        .with_code(alarm.code.code())
        .with_message(escape(&alarm.message))
        .with_labels(labels)
        .with_notes(notes);
    (excerpts, diagnostic)
}

#[cfg(test)]
mod tests {
    use super::*;
    use vcnc::{AlarmCode, Span};

    #[test]
    fn identical_warnings_fold_into_the_first() {
        let warning = |line| {
            Alarm::warning(
                AlarmCode::NotSupportedYet,
                Span::new(FileId(0), line, 0..1),
                "same",
            )
        };
        let alarms = vec![warning(1), warning(2), warning(3)];
        let folded = fold(&alarms);
        assert_eq!(folded.len(), 1);
        assert_eq!(folded[0].count(), 3);
        assert_eq!(folded[0].lines, vec![2, 3]);
    }
}
