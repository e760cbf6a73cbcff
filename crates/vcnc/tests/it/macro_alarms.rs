//! What a macro alarm tells (issue 19): how the program got there (a label on every calling
//! block, innermost first) and the values of the variables the failing expression read; and
//! that every alarm code has a help line, none of them pointing at a file that is not there.

use vcnc::interp::MemoryLibrary;
use vcnc::{interpret_str, Alarm, AlarmCode, FileId, Interpreter, Machine, Options};

/// The first alarm of `main`, calling the programs of `library`.
fn first_alarm(main: &str, library: MemoryLibrary) -> Alarm {
    Interpreter::new(
        vcnc::syntax::lines::TextLines::new(main.as_bytes()),
        FileId(0),
        &Machine::default(),
        Options::default(),
    )
    .with_library(Box::new(library))
    .find_map(Result::err)
    .expect("the program stops with an alarm")
}

/// The labels of `alarm` as (file, line, message).
fn labels(alarm: &Alarm) -> Vec<(u32, u32, String)> {
    alarm
        .labels
        .iter()
        .map(|l| (l.span.file.0, l.span.line, l.message.clone()))
        .collect()
}

#[test]
fn a_division_by_zero_shows_the_variables_it_read() {
    let alarm = first_alarm(
        "#1 = 0\n#3 = 4\n#2 = [10 + #3] / #1 + #7\nM30\n",
        MemoryLibrary::new(),
    );
    assert_eq!(alarm.code, AlarmCode::MacroArithmetic);
    assert_eq!(alarm.message, "division by zero");
    assert_eq!(
        labels(&alarm),
        [
            (0, 3, "#3 = 4".to_string()),
            (0, 3, "#1 = 0".to_string()),
            (0, 3, "#7 is vacant".to_string())
        ]
    );
}

#[test]
fn an_alarm_in_a_called_program_shows_each_call_that_led_there() {
    let mut library = MemoryLibrary::new();
    library.insert(2000, FileId(1), "O2000\nG0 X1.\nG65 P9010 A0\nM99\n");
    library.insert(9010, FileId(2), "O9010\n#2 = SQRT[#1 - 1]\nM99\n");
    let alarm = first_alarm("G90 G0 X0 Y0\nM98 P2000\nM30\n", library);
    assert_eq!(alarm.code, AlarmCode::MacroArithmetic);
    assert_eq!(alarm.span.map(|s| (s.file.0, s.line)), Some((2, 2)));
    assert_eq!(
        labels(&alarm),
        [
            (2, 2, "#1 = 0".to_string()),
            (1, 3, "this macro call ran O9010".to_string()),
            (0, 2, "this call ran O2000".to_string()),
        ]
    );
}

#[test]
fn a_call_that_fails_inside_a_called_program_shows_the_calls_before_it() {
    let mut library = MemoryLibrary::new();
    library.insert(2000, FileId(1), "O2000\nM98 P7777\nM99\n");
    let alarm = first_alarm("M98 P2000\nM30\n", library);
    assert_eq!(alarm.code, AlarmCode::ProgramNotFound);
    assert_eq!(labels(&alarm), [(0, 1, "this call ran O2000".to_string())]);
}

#[test]
fn an_alarm_of_the_main_program_has_no_call_labels() {
    let alarm = interpret_str("#1 = 1 / 0\nM30\n", &Machine::default(), Options::default())
        .find_map(Result::err)
        .unwrap();
    assert_eq!(alarm.code, AlarmCode::MacroArithmetic);
    assert!(alarm.labels.is_empty(), "{:?}", alarm.labels);
}

#[test]
fn every_alarm_code_has_a_help_line() {
    for code in AlarmCode::ALL {
        let help = code.help();
        assert!(!help.is_empty() && !help.ends_with('.'), "{code}: {help:?}");
        assert!(!help.contains('\n'), "{code}: one line");
    }
    let alarm = Alarm::error(AlarmCode::BadDwell, vcnc::Span::default(), "x");
    assert_eq!(alarm.help_line(), AlarmCode::BadDwell.help());
    assert_eq!(alarm.with_help("own").help_line(), "own");
}

#[test]
fn no_help_or_comment_points_at_a_document_that_is_not_there() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut texts: Vec<(String, String)> = AlarmCode::ALL
        .iter()
        .map(|code| (format!("help of {code}"), code.help().to_string()))
        .collect();
    let mut folders = vec![root.join("crates")];
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(&folder).unwrap().flatten() {
            let path = entry.path();
            if path.is_dir() {
                folders.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let text = std::fs::read_to_string(&path).unwrap();
                texts.push((path.display().to_string(), text));
            }
        }
    }
    let mut missing = Vec::new();
    for (place, text) in &texts {
        for (at, _) in text.match_indices("docs/") {
            let name: String = text[at..]
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || matches!(c, '/' | '_' | '.' | '-'))
                .collect();
            let name = name.trim_end_matches('.');
            if name.ends_with(".md") && !root.join(name).is_file() {
                missing.push(format!("{place}: {name}"));
            }
        }
    }
    assert!(missing.is_empty(), "{missing:#?}");
}
