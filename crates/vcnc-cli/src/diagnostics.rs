//! Alarms for people (rustc-style, with the source line and the word underlined) and for
//! machines (JSON).

use codespan_reporting::diagnostic::{Diagnostic, Label, Severity as CsSeverity};
use codespan_reporting::files::SimpleFiles;
use codespan_reporting::term::termcolor::{ColorChoice, StandardStream};
use codespan_reporting::term::{self, Config};
use serde_json::{json, Value};
use std::collections::HashMap;
use std::io::IsTerminal;
use vcnc::pipeline::ProgramFiles;
use vcnc::source::line_column;
use vcnc::{Alarm, FileId, Severity};

/// The text of a program for showing its lines: bytes that are not UTF-8 (Latin-1 comments)
/// become `?`, one byte each, so byte offsets stay right.
pub(crate) fn display_text(bytes: &[u8]) -> String {
    let mut out = String::with_capacity(bytes.len());
    let mut rest = bytes;
    loop {
        match std::str::from_utf8(rest) {
            Ok(valid) => {
                out.push_str(valid);
                return out;
            }
            Err(error) => {
                let (valid, after) = rest.split_at(error.valid_up_to());
                out.push_str(std::str::from_utf8(valid).unwrap_or_default());
                let bad = error.error_len().unwrap_or(after.len());
                out.extend(std::iter::repeat_n('?', bad));
                rest = &after[bad..];
            }
        }
    }
}

/// Prints alarms of one program to stderr like rustc prints errors; an alarm in a called
/// program shows that program's line.
pub(crate) fn print_human(files: &ProgramFiles, alarms: &[Alarm]) {
    if alarms.is_empty() {
        return;
    }
    let mut sources = SimpleFiles::new();
    let mut ids: HashMap<FileId, (usize, usize)> = HashMap::new();
    let mut id_of = |file: FileId| {
        *ids.entry(file).or_insert_with(|| {
            let path = files.path(file);
            let bytes = std::fs::read(&path).unwrap_or_default();
            let len = bytes.len();
            (
                sources.add(path.display().to_string(), display_text(&bytes)),
                len,
            )
        })
    };
    let diagnostics: Vec<_> = alarms.iter().map(|a| to_codespan(a, &mut id_of)).collect();
    let color = if std::env::var_os("NO_COLOR").is_none() && std::io::stderr().is_terminal() {
        ColorChoice::Auto
    } else {
        ColorChoice::Never
    };
    let writer = StandardStream::stderr(color);
    let config = Config::default();
    for diagnostic in &diagnostics {
        let _ = term::emit(&mut writer.lock(), &config, &sources, diagnostic);
    }
}

fn to_codespan(
    alarm: &Alarm,
    id_of: &mut impl FnMut(FileId) -> (usize, usize),
) -> Diagnostic<usize> {
    let severity = match alarm.severity {
        Severity::Error => CsSeverity::Error,
        Severity::Warning => CsSeverity::Warning,
    };
    let mut place = |span: vcnc::Span| {
        let (id, len) = id_of(span.file);
        let start = (span.start as usize).min(len);
        (id, start..(span.end as usize).clamp(start, len))
    };
    let mut labels = Vec::new();
    if let Some(span) = alarm.span {
        let (id, range) = place(span);
        labels.push(Label::primary(id, range));
    }
    for label in &alarm.labels {
        let (id, range) = place(label.span);
        labels.push(Label::secondary(id, range).with_message(label.message.clone()));
    }
    let mut diagnostic = Diagnostic::new(severity)
        .with_code(alarm.code.code())
        .with_message(alarm.message.clone())
        .with_labels(labels);
    if let Some(help) = &alarm.help {
        diagnostic = diagnostic.with_notes(vec![format!("help: {help}")]);
    }
    diagnostic
}

/// One alarm as a JSON object: file, line, column, code, id, severity, message, help.
/// `texts` keeps the files read so far.
pub(crate) fn to_json(
    files: &ProgramFiles,
    texts: &mut HashMap<FileId, Vec<u8>>,
    alarm: &Alarm,
) -> Value {
    let file = alarm.span.map_or(FileId(0), |s| s.file);
    let path = files.path(file);
    let (line, column) = match alarm.span {
        Some(span) => {
            let text = texts
                .entry(file)
                .or_insert_with(|| std::fs::read(&path).unwrap_or_default());
            let at = line_column(text, span.start);
            (Some(at.line), Some(at.column))
        }
        None => (None, None),
    };
    json!({
        "file": path.display().to_string(),
        "line": line,
        "column": column,
        "code": alarm.code.code(),
        "id": alarm.code.id(),
        "severity": alarm.severity.as_str(),
        "message": alarm.message,
        "help": alarm.help,
    })
}
