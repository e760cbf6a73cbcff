//! A main program read from a file runs from an index into the file once it jumps or calls
//! (issue 18, streaming that holds with jumps and calls): these tests run programs with jumps and
//! calls both from a file (the index, read again by seeking) and from text held whole in memory
//! (`interpret_str`, which loads the whole program at its first jump), and require the same stream,
//! alarms and spans included.

use std::path::PathBuf;
use vcnc::interp::DirectoryLibrary;
use vcnc::syntax::blocks::BackgroundParser;
use vcnc::syntax::lines::ReaderLines;
use vcnc::{interpret_str, FileId, Interpreter, Machine, Options};

/// A file of the test's own under the temporary directory, removed when dropped.
struct TempProgram(PathBuf);

impl TempProgram {
    fn new(name: &str, text: &str) -> TempProgram {
        let path =
            std::env::temp_dir().join(format!("vcnc-streaming-{}-{name}.nc", std::process::id()));
        std::fs::write(&path, text).expect("the temporary directory is writable");
        TempProgram(path)
    }

    fn library(&self) -> Box<DirectoryLibrary> {
        Box::new(DirectoryLibrary::new(Some(self.0.clone()), Vec::new(), 1))
    }
}

impl Drop for TempProgram {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

/// Every item of a stream as text (`{:?}` tells -0 from 0 and shows every span).
fn describe(items: impl Iterator<Item = vcnc::StreamItem>) -> Vec<String> {
    items.map(|item| format!("{item:?}")).collect()
}

/// The stream of `text` from memory, and from a file through each kind of block source.
fn streams(name: &str, text: &str) -> (Vec<String>, Vec<Vec<String>>) {
    let machine = Machine::default();
    let whole = describe(interpret_str(text, &machine, Options::default()));
    let file = TempProgram::new(name, text);
    let open = || std::fs::File::open(&file.0).expect("just written");
    let syntax = machine.profile.syntax();
    let read = Interpreter::new(
        ReaderLines::new(open()),
        FileId(0),
        &machine,
        Options::default(),
    )
    .with_library(file.library());
    let ahead = Interpreter::from_blocks(
        BackgroundParser::spawn(open(), FileId(0), syntax),
        FileId(0),
        &machine,
        Options::default(),
    )
    .with_library(file.library());
    (whole, vec![describe(read), describe(ahead)])
}

fn check_same(name: &str, text: &str) -> Vec<String> {
    let (whole, from_files) = streams(name, text);
    for streamed in from_files {
        assert_eq!(streamed.len(), whole.len(), "{name}: items");
        for (i, (a, b)) in streamed.iter().zip(&whole).enumerate() {
            assert_eq!(a, b, "{name}: item {i}");
        }
    }
    whole
}

/// `lines` feed moves, each on a line of its own, from X`from`.
fn moves(from: usize, lines: usize) -> String {
    (from..from + lines)
        .map(|i| format!("G01 X{}. Y{}.\n", i % 97, i % 13))
        .collect()
}

#[test]
fn jumps_and_calls_from_a_file_give_the_stream_of_the_whole_text() {
    let cases = [
        (
            "while",
            "%\nO0001\nG90 G01 F1000.\n#1=0\nWHILE[#1LT3]DO1\nG01 X#1 Y1.\n#1=#1+1\nEND1\nG01 X9.\nM30\n%\n",
        ),
        (
            "goto",
            "G90 G01 F1000.\n#1=0\nN10 G01 X#1\n#1=#1+1\nIF[#1LT4]GOTO10\nGOTO30\nG01 Y9.\nN30 G01 Y2.\nM30\n",
        ),
        (
            "nested",
            "G90 G01 F1000.\n#1=0\nWHILE[#1LT2]DO1\n#2=0\nWHILE[#2LT2]DO2\nG01 X#1 Y#2\n#2=#2+1\nEND2\n#1=#1+1\nEND1\nM30\n",
        ),
        (
            "m98",
            "%\nO1000\nG90 G01 F1000.\nM98 P2000 L2\nG01 X5.\nM30\n%\nO2000\nG91 G01 X1.\nG90\nM99\n",
        ),
        (
            "g65",
            "O1000\nG90 G01 F1000.\nG65 P2001 A1.\nG01 X5.\nM30\nO2001\nG01 X#1\nG65 P2002 A[#1+1]\nM99\nO2002\nG01 Y#1\nM99\n",
        ),
        (
            "m99p",
            "O1000\nG90 G01 F1000.\nM98 P2000\nG01 X1.\nN50 G01 X2.\nM30\nO2000\nG01 Y3.\nM99 P50\n",
        ),
        (
            "m97",
            "G90 G01 F1000.\nM97 P100 L2\nG01 X9.\nM30\nN100 G91 G01 X1.\nG90\nM99\n",
        ),
        (
            "main-m99",
            "G90 G01 F1000.\n#1=[#1+1]\nG01 X#1\nM99\n",
        ),
        (
            "missing-label",
            "G90 G01 F1000.\nG01 X1.\nGOTO 77\nG01 X2.\nM30\n",
        ),
        (
            // No M30: the main program ends where the program after it starts.
            "no-end",
            "G90 G01 F1000.\n#1=0\nN10 G01 X#1\n#1=#1+1\nIF[#1LT2]GOTO10\nG01 Y1.\nO2000\nG01 X9.\nM99\n",
        ),
        (
            "missing-program",
            "G90 G01 F1000.\nM98 P4321\nM30\n",
        ),
    ];
    for (name, text) in cases {
        check_same(name, text);
    }
}

#[test]
fn jumps_over_more_lines_than_the_cache_holds_give_the_stream_of_the_whole_text() {
    // Labels on some lines, jumps back from far down and forward over thousands of lines, a loop
    // whose body is longer than the lines kept parsed, and calls of programs after M30.
    let mut text = String::from("%\nO0001\nG90 G01 F1000.\n#1=0\nN10 #1=#1+1\n");
    text.push_str(&moves(0, 1500));
    text.push_str("N20 IF[#1LT3]GOTO10\nWHILE[#1LT5]DO1\n");
    text.push_str(&moves(2000, 3000));
    text.push_str("#1=#1+1\nEND1\nIF[#1GT4]GOTO40\n");
    text.push_str(&moves(9000, 2500));
    text.push_str("N40 M98 P2000\nG65 P2001 A2.\n");
    for n in 0..200 {
        text.push_str(&format!("N{} G01 X{}.\n", 1000 + n, n % 50));
    }
    text.push_str("M30\n%\nO2000\nG01 Y1.\nM99\nO2001\nG01 X#1\nM99\n");
    let whole = check_same("long", &text);
    assert!(
        whole.len() > 3 * 1500 + 2 * 3000,
        "the loops ran: {} items, the last {:?}",
        whole.len(),
        whole.last()
    );
}

#[test]
fn a_goto_to_a_missing_sequence_number_names_the_goto_in_the_file() {
    let text = "G90 G01 F1000.\n#1=0\nN10 G01 X#1\n#1=#1+1\nIF[#1LT2]GOTO10\nGOTO 99\nM30\n";
    let machine = Machine::default();
    let file = TempProgram::new("missing", text);
    let reader = std::fs::File::open(&file.0).expect("just written");
    let last = Interpreter::new(
        ReaderLines::new(reader),
        FileId(0),
        &machine,
        Options::default(),
    )
    .with_library(file.library())
    .last()
    .expect("the program makes items");
    let alarm = last.expect_err("the run stops at the GOTO");
    let span = alarm.span.expect("the alarm has a span");
    assert_eq!(alarm.code, vcnc::AlarmCode::SequenceNotFound);
    assert_eq!((span.file, span.line), (FileId(0), 6));
    let at = text.find("GOTO 99").expect("in the text") as u32;
    assert!(span.start >= at - 1 && span.end <= at + 7, "{span:?}");
    // The same alarm as from the whole text.
    let whole = interpret_str(text, &machine, Options::default()).last();
    assert_eq!(whole, Some(Err(alarm)));
}
