//! Alarms for people (rustc-style, with the source line and the word underlined) and for
//! machines (JSON).

use codespan_reporting::diagnostic::{Diagnostic, Label, Severity as CsSeverity};
use codespan_reporting::files::SimpleFile;
use codespan_reporting::term::termcolor::{ColorChoice, StandardStream};
use codespan_reporting::term::{self, Config};
use serde_json::{json, Value};
use std::io::IsTerminal;
use std::path::Path;
use vcnc::source::line_column;
use vcnc::{Alarm, Severity};

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
                out.extend(std::iter::repeat('?').take(bad));
                rest = &after[bad..];
            }
        }
    }
}

/// Prints alarms of one program to stderr like rustc prints errors.
pub(crate) fn print_human(path: &Path, alarms: &[Alarm]) {
    if alarms.is_empty() {
        return;
    }
    let bytes = std::fs::read(path).unwrap_or_default();
    let file = SimpleFile::new(path.display().to_string(), display_text(&bytes));
    let color = if std::env::var_os("NO_COLOR").is_none() && std::io::stderr().is_terminal() {
        ColorChoice::Auto
    } else {
        ColorChoice::Never
    };
    let writer = StandardStream::stderr(color);
    let config = Config::default();
    for alarm in alarms {
        let _ = term::emit(
            &mut writer.lock(),
            &config,
            &file,
            &to_codespan(alarm, bytes.len()),
        );
    }
}

fn to_codespan(alarm: &Alarm, len: usize) -> Diagnostic<()> {
    let severity = match alarm.severity {
        Severity::Error => CsSeverity::Error,
        Severity::Warning => CsSeverity::Warning,
    };
    let range = |span: vcnc::Span| {
        let start = (span.start as usize).min(len);
        start..(span.end as usize).clamp(start, len)
    };
    let mut labels = Vec::new();
    if let Some(span) = alarm.span {
        labels.push(Label::primary((), range(span)));
    }
    for label in &alarm.labels {
        labels.push(Label::secondary((), range(label.span)).with_message(label.message.clone()));
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
pub(crate) fn to_json(path: &Path, text: &[u8], alarm: &Alarm) -> Value {
    let (line, column) = match alarm.span {
        Some(span) => {
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
