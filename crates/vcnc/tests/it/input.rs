//! How the library reads programs and finds the programs they call (issue 19): the bytes editors
//! put in files (a UTF-8 byte-order mark, old Mac `\r` line ends), subprogram lookup in a
//! directory, main programs that repeat with M99, dialect detection. Each test runs the program
//! through every path that reads text: held whole, streamed from a reader, and from a file that
//! runs from an index once it jumps.

use std::path::PathBuf;
use vcnc::pipeline::{Item, Pipeline};
use vcnc::{interpret_bytes, Machine, Options};

/// A directory of the test's own under the temporary directory, removed when dropped.
struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> TempDir {
        let path = std::env::temp_dir().join(format!("vcnc-input-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&path);
        std::fs::create_dir_all(&path).expect("the temporary directory is writable");
        TempDir(path)
    }

    fn write(&self, name: &str, text: &[u8]) -> PathBuf {
        let path = self.0.join(name);
        std::fs::write(&path, text).expect("the temporary directory is writable");
        path
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// What a run did, as lines of text: each move's source line and end point, each alarm's code,
/// line and message.
fn outline(items: impl IntoIterator<Item = Item>) -> Vec<String> {
    items
        .into_iter()
        .filter_map(|item| match item {
            Ok(vcnc::Item::Frame(_)) => None,
            Ok(vcnc::Item::Segment(segment)) => segment.motion().map(|motion| {
                let [x, y, z] = motion.to.xyz();
                format!("line {}: {x:.3} {y:.3} {z:.3}", segment.span.line)
            }),
            Ok(vcnc::Item::Warning(alarm)) | Err(alarm) => Some(format!(
                "{} line {}: {}",
                alarm.code.code(),
                alarm.span.map_or(0, |s| s.line),
                alarm.message
            )),
        })
        .collect()
}

/// The outlines of `text` run held whole (by the interpreter, and by a pipeline), and from a
/// file in `dir` (streamed, then from an index into the file once it jumps).
fn outlines(dir: &TempDir, name: &str, text: &[u8], options: Options) -> [Vec<String>; 3] {
    let machine = Machine::default();
    let whole = outline(interpret_bytes(text, &machine, options.clone()));
    let held = Pipeline::new(&machine)
        .options(options.clone())
        .open_text(text, name);
    let path = dir.write(name, text);
    let file = Pipeline::new(&machine)
        .options(options)
        .open_path(&path)
        .expect("the file was just written");
    [whole, outline(held), outline(file)]
}

/// A program that jumps (WHILE), calls a subprogram after its M30 and has a comment on its first
/// line: every reader of the text meets each line end.
const JUMPS_AND_CALLS: &str = "%\n(FIRST LINE)\nO0001\nG90 G21 G17 G0 X0 Y0 Z5.\n#1 = 0\n\
WHILE [#1 LT 3] DO1\nG1 X[#1 * 10] F500.\n#1 = #1 + 1\nEND1\nM98 P1234\nG0 Z10.\nM30\n\
O1234\nG1 Y7. F300.\nM99\n%\n";

#[test]
fn a_byte_order_mark_and_old_mac_line_ends_read_as_plain_line_feeds() {
    let dir = TempDir::new("line-ends");
    let [expected, ..] = outlines(
        &dir,
        "lf.nc",
        JUMPS_AND_CALLS.as_bytes(),
        Options::default(),
    );
    assert_eq!(expected.len(), 5, "{expected:#?}");
    let variants: [(&str, Vec<u8>); 4] = [
        (
            "bom.nc",
            [b"\xEF\xBB\xBF", JUMPS_AND_CALLS.as_bytes()].concat(),
        ),
        ("cr.nc", JUMPS_AND_CALLS.replace('\n', "\r").into_bytes()),
        (
            "crlf.nc",
            JUMPS_AND_CALLS.replace('\n', "\r\n").into_bytes(),
        ),
        (
            "bom-cr.nc",
            [
                b"\xEF\xBB\xBF",
                JUMPS_AND_CALLS.replace('\n', "\r").as_bytes(),
            ]
            .concat(),
        ),
    ];
    for (name, text) in variants {
        for (path, got) in
            ["whole", "held", "file"]
                .iter()
                .zip(outlines(&dir, name, &text, Options::default()))
        {
            assert_eq!(got, expected, "{name} read {path}");
        }
    }
}

#[test]
fn old_mac_line_ends_cut_by_every_read_size_give_the_same_lines() {
    // A `\r` at the end of one read and its line's text in the next: the line reader must not
    // take the two lines for one. (A program read from a reader cannot jump.)
    let text = "\u{feff}%\rG90 G0 X1. Y2.\rG1 X3. F100.\r\rG1 Y4.\r\nG1 Z-1.\rM30\r%";
    assert!(text.starts_with('\u{feff}'));
    let machine = Machine::default();
    let expected = outline(interpret_bytes(
        text.as_bytes(),
        &machine,
        Options::default(),
    ));
    for chunk in 1..9 {
        let reader = Trickle {
            data: text.as_bytes().to_vec(),
            at: 0,
            chunk,
        };
        let stream = Pipeline::new(&machine)
            .open_reader(reader, "trickle.nc")
            .expect("a reader in memory opens");
        assert_eq!(outline(stream), expected, "reads of {chunk} bytes");
    }
    assert_eq!(
        expected,
        [
            "line 2: 1.000 2.000 0.000",
            "line 3: 3.000 2.000 0.000",
            "line 5: 3.000 4.000 0.000",
            "line 6: 3.000 4.000 -1.000"
        ]
    );
}

/// A reader that hands out at most `chunk` bytes per read.
struct Trickle {
    data: Vec<u8>,
    at: usize,
    chunk: usize,
}

impl std::io::Read for Trickle {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.chunk.min(buf.len()).min(self.data.len() - self.at);
        buf[..n].copy_from_slice(&self.data[self.at..self.at + n]);
        self.at += n;
        Ok(n)
    }
}

/// The outline of the main program `main` in `dir` (its own directory is its library).
fn run_in(dir: &TempDir, main: &str) -> Vec<String> {
    let path = dir.write("main.nc", main.as_bytes());
    let stream = Pipeline::new(&Machine::default())
        .open_path(&path)
        .expect("the file was just written");
    outline(stream)
}

const CALLS_10: &str = "%\nG90 G21 G17 G0 X0 Y0 Z5.\nM98 P[10]\nM30\n%\n";
const SUB_10: &str = "%\nO0010\nG1 X10. F300.\nM99\n%\n";

#[test]
fn a_called_program_is_found_by_its_exact_name_or_its_header_not_by_a_name_that_holds_it() {
    let dir = TempDir::new("lookup-exact");
    // Named for the number in every accepted form: found.
    for name in ["O0010.nc", "o10", "0010.NC", "10.txt"] {
        dir.write(name, b"G1 X10. F300.\nM99\n");
        let got = run_in(&dir, CALLS_10);
        assert_eq!(
            got.last().unwrap(),
            "line 1: 10.000 0.000 5.000",
            "{name}: {got:#?}"
        );
        std::fs::remove_file(dir.0.join(name)).unwrap();
    }
    // A name that only holds the number, without a header: not the program.
    dir.write("bolt_O0010_circle.nc", b"G1 X10. F300.\nM99\n");
    let got = run_in(&dir, CALLS_10);
    assert!(got.last().unwrap().starts_with("V084 line 3"), "{got:#?}");
    // Headed O0010 (the file's first program): found by its header.
    dir.write("bolt_O0010_circle.nc", SUB_10.as_bytes());
    let got = run_in(&dir, CALLS_10);
    assert_eq!(
        got.last().unwrap(),
        "line 3: 10.000 0.000 5.000",
        "{got:#?}"
    );
}

#[test]
fn two_files_that_could_be_the_called_program_are_an_alarm_naming_both() {
    let dir = TempDir::new("lookup-two");
    dir.write("bolt_circle.nc", SUB_10.as_bytes());
    dir.write("z64_bolts.nc", SUB_10.replace("X10.", "X20.").as_bytes());
    let got = run_in(&dir, CALLS_10);
    let alarm = got.last().unwrap();
    assert!(
        alarm.starts_with("V089 line 3: program O0010 is in more than one file: "),
        "{alarm}"
    );
    assert!(
        alarm.contains("bolt_circle.nc and ") && alarm.ends_with("z64_bolts.nc"),
        "{alarm}"
    );
    assert_eq!(got.len(), 2, "nothing runs of either: {got:#?}");
    // A file named for the number and one headed by it: two candidates as well.
    std::fs::remove_file(dir.0.join("z64_bolts.nc")).unwrap();
    dir.write("O10.nc", b"G1 X30. F300.\nM99\n");
    let alarm = run_in(&dir, CALLS_10).pop().unwrap();
    assert!(alarm.starts_with("V089 line 3: "), "{alarm}");
    assert!(
        alarm.contains("O10.nc") && alarm.contains("bolt_circle.nc"),
        "{alarm}"
    );
    // Two names for one number.
    std::fs::remove_file(dir.0.join("bolt_circle.nc")).unwrap();
    dir.write("O0010", b"G1 X40. F300.\nM99\n");
    let alarm = run_in(&dir, CALLS_10).pop().unwrap();
    assert!(alarm.starts_with("V089 line 3: "), "{alarm}");
}

#[test]
fn a_main_program_opened_by_a_tape_mark_repeats_from_the_block_after_it_on_m99() {
    // Read again from its first line, the `%` ended the program after one pass.
    let dir = TempDir::new("main-passes");
    let program = "%\nG90 G21 G17\nG1 X1. F100.\nG1 X0\nM99\n";
    let options = Options {
        limits: vcnc::interp::Limits {
            main_program_passes: 10,
            ..vcnc::interp::Limits::default()
        },
        ..Options::default()
    };
    for with_comment in [false, true] {
        let text = if with_comment {
            format!("\n(PASSES)\n{program}")
        } else {
            program.to_string()
        };
        for (path, got) in ["whole", "held", "file"].iter().zip(outlines(
            &dir,
            "passes.nc",
            text.as_bytes(),
            options.clone(),
        )) {
            let moves = got.iter().filter(|l| l.starts_with("line")).count();
            assert_eq!(moves, 20, "{path}: {got:#?}");
            assert!(got.last().unwrap().starts_with("V086"), "{path}: {got:#?}");
        }
    }
}

#[test]
fn a_number_with_an_exponent_says_iso_g_code_has_none() {
    let machine = Machine::default();
    let first_alarm = |text: &str| {
        outline(interpret_bytes(
            text.as_bytes(),
            &machine,
            Options::default(),
        ))
        .into_iter()
        .find(|l| l.starts_with('V'))
        .unwrap_or_default()
    };
    for (text, code, written) in [
        ("G0 X1e308\nM30\n", "V003", "`X1e308`"),
        ("G1 X1.5E-3 F100.\nM30\n", "V003", "`X1.5E-3`"),
        ("G1 Y2.E+3 F100.\nM30\n", "V003", "`Y2.E+3`"),
        ("#1=1E308\nG0 X#1\nM30\n", "V080", "`1E308`"),
        ("#1=[2.5e-3 * 2]\nM30\n", "V080", "`2.5e-3`"),
    ] {
        let alarm = first_alarm(text);
        assert!(alarm.starts_with(&format!("{code} line 1: {written}: ISO G-code has no exponent notation, and E is an address")), "{text}: {alarm}");
    }
    // E with digits after a number is the address E (a G65 argument, a tapping cycle's E).
    let alarm = first_alarm("G65 P9000 A1. V0E41\nM30\n");
    assert!(alarm.starts_with("V084"), "{alarm}");
}

/// Text in memory is searched for lone `\r` a chunk ahead of the reading, not all at once: line
/// ends of any kind, first met far into a large text or on a chunk's edge, read as the same
/// program as its LF twin.
#[test]
fn line_ends_met_late_in_a_large_text_read_as_its_lf_twin() {
    let lf: String = (0..30_000)
        .map(|i| format!("G1 X{}.{} Y{}. F500.\n", i % 97, i % 10, i % 89))
        .collect::<String>()
        + "M30\n";
    let twin = outline(interpret_bytes(
        lf.as_bytes(),
        &Machine::default(),
        Options::default(),
    ));
    let cut = lf.len() / 2;
    let second_half_cr = format!("{}{}", &lf[..cut], lf[cut..].replace('\n', "\r"));
    let crlf = lf.replace('\n', "\r\n");
    // A lone `\r` in a comment line near the end, after megabytes of LF lines.
    let late_comment = lf.replacen("M30\n", "(LAST)\rM30\n", 1);
    for (name, text) in [
        ("second half CR", second_half_cr),
        ("CRLF", crlf),
        ("late CR", late_comment),
    ] {
        let got = outline(interpret_bytes(
            text.as_bytes(),
            &Machine::default(),
            Options::default(),
        ));
        assert_eq!(got.len(), twin.len(), "{name}");
        assert!(got == twin, "{name}: another stream");
    }
}
