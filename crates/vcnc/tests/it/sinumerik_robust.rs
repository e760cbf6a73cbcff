//! Robustness of the SINUMERIK front end: whatever bytes a program holds, the run ends without a
//! panic or a hang, and every alarm points inside the text with a one-line message and a help
//! line. The same properties as `mangled.rs` (and the fuzz target `interpret_sinumerik` in
//! `fuzz/`), over SINUMERIK text: truncations and seeded mutations of the manual's examples and
//! the corpus, random bytes, huge numbers, deep expressions and nesting, unterminated structures
//! and recursion; then the findings of the fuzz target, one test each.
//!
//! Both SINUMERIK profiles run every input, on a machine with rotary A, B and C axes: the 840D
//! with a program library that answers every call with the input itself (calls and recursion
//! run), the 828D without one (a call alarms). The iteration limit is small, as in the fuzz
//! target, so that a loop that never ends stops fast.

use crate::common;
use crate::mangled::{check_alarm, check_segment, mutate, shown, XorShift};

use proptest::prelude::*;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use vcnc::interp::sinumerik::Sinumerik;
use vcnc::interp::{DirectoryLibrary, Kernel, LookupError, ProgramLibrary, ProgramText, Run};
use vcnc::{Alarm, AlarmCode, Axis, FileId, Item, Machine, ProfileName};

/// Lines a run may read before it stops with the limit alarm (the fuzz target's value).
const ITERATIONS: u64 = 20_000;

/// Items a run may yield per line read: a line yields a handful (its warnings, a tool change, a
/// spindle event, a few segments); the bound is loose, it catches streams that do not end.
const ITEMS_PER_ITERATION: usize = 50;

/// Both SINUMERIK profiles on the default machine with rotary A, B and C axes and a small
/// iteration limit.
fn machines() -> Vec<(ProfileName, Machine)> {
    ProfileName::SINUMERIK
        .iter()
        .map(|&p| {
            let mut machine = common::with_c_axis(p);
            for axis in [Axis::A, Axis::B] {
                machine.axes[axis.index()] = machine.axes[Axis::C.index()].clone();
            }
            machine.profile.sinumerik.as_mut().unwrap().iteration_limit = ITERATIONS;
            (p, machine)
        })
        .collect()
}

/// Every called program is the input itself, in file 0 (its spans are the input's).
struct Itself(Arc<[u8]>);

impl ProgramLibrary for Itself {
    fn find(&mut self, _number: u32) -> Result<Option<ProgramText>, LookupError> {
        Ok(Some(ProgramText {
            file: FileId(0),
            text: self.0.clone(),
        }))
    }

    fn find_named(&mut self, _name: &str) -> Result<Option<ProgramText>, LookupError> {
        self.find(0)
    }
}

/// Words of a help line that belong to ISO programs only: an alarm of the SINUMERIK front end
/// whose help names one of them fell back to its code's ISO help.
const ISO_ONLY: &[&str] = &[
    "#3000",
    "( ) comment",
    "MACROS.md",
    "G01",
    "M99",
    "--max-jumps",
    "DOn",
    "(R)",
];

/// The help line of `alarm` is there, one line, and in SINUMERIK's terms.
fn check_help(alarm: &Alarm) -> Result<(), String> {
    let help = alarm.help_line();
    if help.trim().is_empty() || help.contains('\n') {
        return Err(format!("alarm without a one-line help line: {alarm:?}"));
    }
    if let Some(word) = ISO_ONLY.iter().find(|w| help.contains(*w)) {
        return Err(format!("help line naming ISO syntax ({word}): {alarm:?}"));
    }
    Ok(())
}

/// Runs `front_end` and checks the properties for a text of `len` bytes whose spans are all in
/// file 0; gives the alarms.
fn check_run(front_end: Sinumerik, machine: &Machine, len: u32) -> Result<Vec<Alarm>, String> {
    let limit = ITEMS_PER_ITERATION * ITERATIONS as usize;
    let mut alarms = Vec::new();
    let mut error: Option<Alarm> = None;
    for (count, item) in Run::new(front_end, Kernel::new(machine)).enumerate() {
        if count >= limit {
            return Err(format!("the run did not end within {limit} items"));
        }
        if let Some(error) = &error {
            return Err(format!("{item:?} came after the error alarm {error:?}"));
        }
        match item {
            Ok(vcnc::Item::Segment(segment)) => check_segment(&segment, len)?,
            Ok(vcnc::Item::Frame(_)) => {}
            Ok(vcnc::Item::Warning(alarm)) | Err(alarm) => {
                check_alarm(&alarm, len)?;
                check_help(&alarm)?;
                if alarm.is_error() {
                    error = Some(alarm.clone());
                }
                alarms.push(alarm);
            }
        }
    }
    Ok(alarms)
}

/// Checks `text` on both profiles (the 840D calling the text itself); a panic is caught so that
/// the failure names the input. Gives the alarms of both runs.
fn check_everywhere(text: &[u8]) -> Result<Vec<Alarm>, String> {
    let len = u32::try_from(text.len()).map_err(|_| "input over 4 GiB".to_string())?;
    let shared: Arc<[u8]> = Arc::from(text);
    let mut alarms = Vec::new();
    for (index, (profile, machine)) in machines().iter().enumerate() {
        let mut front_end = Sinumerik::new(shared.clone(), FileId(0), machine);
        if index == 0 {
            front_end = front_end.with_library(Box::new(Itself(shared.clone())));
        }
        let result = catch_unwind(AssertUnwindSafe(|| check_run(front_end, machine, len)))
            .unwrap_or_else(|panic| {
                let message = panic
                    .downcast_ref::<String>()
                    .map(String::as_str)
                    .or_else(|| panic.downcast_ref::<&str>().copied())
                    .unwrap_or("(no message)");
                Err(format!("panic: {message}"))
            });
        match result {
            Ok(found) => alarms.extend(found),
            Err(e) => {
                return Err(format!(
                    "{}: {e}\n  input: `{}`",
                    profile.as_str(),
                    shown(text)
                ))
            }
        }
    }
    Ok(alarms)
}

/// Checks every input and lists all failures at once.
fn check_all(inputs: &[Vec<u8>]) {
    let failures: Vec<String> = inputs
        .iter()
        .filter_map(|text| check_everywhere(text).err())
        .collect();
    assert!(
        failures.is_empty(),
        "{} of {} inputs broke a property:\n{}",
        failures.len(),
        inputs.len(),
        failures.join("\n")
    );
}

/// Asserts that `text` keeps every property and stops with an error alarm on both profiles;
/// gives the alarms.
#[track_caller]
fn check_stops(text: &str) -> Vec<Alarm> {
    let alarms = check_everywhere(text.as_bytes()).unwrap_or_else(|e| panic!("{e}"));
    let errors = alarms.iter().filter(|a| a.is_error()).count();
    assert_eq!(
        errors,
        2,
        "`{}` stops on both profiles: {alarms:?}",
        shown(text.as_bytes())
    );
    alarms
}

fn b(text: &str) -> Vec<u8> {
    text.as_bytes().to_vec()
}

/// The manual's example programs and the corpus, sorted by path.
fn shared_files(shared: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for folder in [
        "spec/examples/sinumerik-a",
        "spec/examples/sinumerik-b",
        "corpus/sinumerik",
    ] {
        let mut entries: Vec<_> = std::fs::read_dir(shared.join(folder))
            .unwrap_or_else(|e| panic!("{folder}: {e}"))
            .map(|e| e.expect("a folder entry").path())
            .filter(|p| p.extension().is_none_or(|e| e != "md"))
            .collect();
        entries.sort();
        files.extend(entries);
    }
    files
}

// ---------------------------------------------------------------------------------------------
// Fixed nasty programs.

/// Numbers too large for f64, and finite numbers whose sums, products and squares overflow.
fn huge_numbers() -> Vec<Vec<u8>> {
    let nines = "9".repeat(400);
    let big = format!("1{}.", "0".repeat(308));
    let mut out = vec![
        format!("X{nines}\n"),
        format!("G1 X{nines} F100\n"),
        format!("R1={nines}\nG0 X=R1\n"),
        format!("G91 G0 X{big}\nX{big}\n"),
        "R1=1E308 R2=R1*10\nG0 X=R2\n".into(),
        "R1=1E300*1E300\nG0 X=R1\n".into(),
        "R1=-1E308-1E308\nG0 Y=R1\n".into(),
        "R1=1/0\n".into(),
        "R1=0/0\nG0 X=R1\n".into(),
        "R1=SQRT(-1)\nG0 X=R1\n".into(),
        "R1=LN(0)\nG0 X=R1\n".into(),
        "R1=EXP(1000)\nG0 X=R1\n".into(),
        "R1=POT(1E200)\nG0 X=R1\n".into(),
        "R1=TRUNC(1E300) R2=ROUND(1E300)\nG0 X=R2\n".into(),
        "R1=1E308 G0 X=R1*R1\n".into(),
        "G2 X10 Y0 CR=1E200 F100\n".into(),
        "G2 X1E200 Y0 CR=1 F100\n".into(),
        "G3 X10 Y0 AR=1E300 F100\n".into(),
        "G2 X10 Y0 I=AC(1E300) J=AC(-1E300) F100\n".into(),
        "G2 X10 Y10 I1E300 J1E300 TURN=1E9 F100\n".into(),
        "G2 X10 Y10 I5 TURN=99999999 F100\n".into(),
        "CIP X10 Y10 I1=1E300 J1=1E-300 F100\n".into(),
        "G111 X0 Y0\nG1 AP=1E300 RP=1E300 F100\n".into(),
        "G110 X1E300 Y1E300\nG0 RP=1E300 AP=45\n".into(),
        "TRANS X1E308\nATRANS X1E308\nG0 X0\n".into(),
        "SCALE X1E200\nASCALE X1E200\nG0 X1\n".into(),
        "ROT RPL=1E300\nG0 X1 Y1\n".into(),
        "AROT Z=1E308\nG0 X1\n".into(),
        "G1 X10 F1E300\nG1 X20 F1E-300\n".into(),
        "G1 X10 F0\n".into(),
        "G94 G1 X10 F-1\n".into(),
        "G95 S1E300 M3 F1E300\nG1 X10\n".into(),
        "G96 S1E300 LIMS=1E300 M3\nG1 X10 F1\n".into(),
        "G4 F1E300\nG4 S1E300\nG4 F-1\n".into(),
        "S1E300 M3\nSVC=1E300\n".into(),
        "T1 D1 G1 X10 F100 FZ=1E300\n".into(),
        "G1 X10 Y10 RND=1E300 F100\nX20 Y0\n".into(),
        "G1 X10 Y10 CHF=1E300 F100\nX20 Y0\n".into(),
        "G1 ANG=1E300 X10 F100\nANG=1E-300 X20 Y1E300\n".into(),
        "G0 A1E300 B-1E300 C1E300\n".into(),
        "R99999999=1\nR-1=1\nR1E300=1\n".into(),
        "DEF REAL A1[1E300]\nDEF INT B1[99999,99999,99999]\n".into(),
        "DEF INT I1=2147483647 I1=I1+1\nG0 X=I1\n".into(),
        "FOR R1=0 TO 1E300\nENDFOR\n".into(),
        "N99999999999999999999 G0 X1\n".into(),
        "L99999999999999999999 P99999999999\n".into(),
        "SPOS=1E300\nM19\n".into(),
        "G25 S1E300 G26 S-1E300\n".into(),
        "OVR=1E300\nG1 X1 F100\n".into(),
    ];
    out.push(format!("R1={}\nG0 X=R1\n", "9".repeat(5000)));
    out.into_iter().map(|s| s.into_bytes()).collect()
}

/// Expressions and structures nested or repeated far beyond any program.
fn deep() -> Vec<Vec<u8>> {
    let mut out = Vec::new();
    for depth in [100, 1000, 20_000] {
        out.push(format!(
            "R1={}1{}\nG0 X=R1\n",
            "(".repeat(depth),
            ")".repeat(depth)
        ));
        out.push(format!("R1={}1\n", "-".repeat(depth)));
        out.push(format!("R1={}1\n", "NOT ".repeat(depth)));
        out.push(format!("R1=1{}\n", "+1".repeat(depth)));
        out.push(format!("R1={}1\n", "SIN(".repeat(depth)));
        out.push(format!("IF {}1\nENDIF\n", "(".repeat(depth)));
        // Structures nest 2,000 deep at most here: their scans are linear in the program, and a
        // deeper nest only costs the debug build time (the expressions above go the whole way).
        let depth = depth.min(2000);
        out.push("IF 1==1\n".repeat(depth) + &"ENDIF\n".repeat(depth));
        out.push("WHILE 1\n".repeat(depth));
        out.push("ENDWHILE\n".repeat(depth));
        out.push("FOR R1=1 TO 2\n".repeat(depth) + &"ENDFOR\n".repeat(depth));
        out.push("REPEAT\n".repeat(depth) + &"UNTIL 1\n".repeat(depth));
        out.push("LOOP\n".repeat(depth) + "M30\n");
        out.push(format!("G0 X{}\n", "=".repeat(depth)));
        out.push(format!("MSG(\"{}\")\n", "x".repeat(depth)));
        out.push(format!("DEF INT A[{}]\n", "1,".repeat(depth)));
    }
    out.into_iter().map(|s| s.into_bytes()).collect()
}

/// Structures opened and never closed, closed and never opened, or crossing each other.
fn unterminated() -> Vec<Vec<u8>> {
    [
        "IF 1\nG0 X1\n",
        "IF 0\nG0 X1\n",
        "IF 1==1\nELSE\n",
        "ELSE\nENDIF\n",
        "ENDIF\n",
        "WHILE 1\nG0 X1\n",
        "WHILE 0\nG0 X1\n",
        "ENDWHILE\n",
        "FOR R1=0 TO 10\nG0 X=R1\n",
        "ENDFOR\n",
        "REPEAT\nG0 X1\n",
        "UNTIL 1\n",
        "LOOP\nG0 X1\n",
        "ENDLOOP\n",
        "CASE R1 OF 1 GOTOF A DEFAULT GOTOF B\n",
        "GOTOF NOWHERE\n",
        "GOTOB NOWHERE\n",
        "GOTO NOWHERE\n",
        "GOTOC NOWHERE\nG0 X1\nM30\n",
        "A: A: GOTOB A\n",
        "L1: GOTOF L1\n",
        "IF 1\nWHILE 1\nENDIF\nENDWHILE\n",
        "FOR R1=0 TO 2\nREPEAT\nENDFOR\nUNTIL 1\n",
        "PROC SUB(REAL A\nG0 X=A\n",
        "PROC SUB(VAR REAL A)\nRET\n",
        "PROC\n",
        "RET\n",
        "RET\nRET\nM17\n",
        "M17\n",
        "MSG(\"unterminated\n",
        "MSG(\"a\"\n",
        "G0 X=(1+2\n",
        "R1=SIN(\n",
        "DEF\n",
        "DEF INT\n",
        "DEF INT A[\n",
        "DEF STRING[ S\n",
        "DEF REAL A=\n",
        "R1=\n",
        "X=\n",
        "X=AC(\n",
        "X=IC(1\n",
        "T=\"\n",
        "T=\"MILL\n",
        "SETAL(\n",
        "SETAL(65000)\n",
        "MCALL\n",
        "MCALL SUB\nG0 X1\nG0 X2\n",
        "SAVE\n",
        "EXTERN SUB(\n",
        "$P_UIFR[\n",
        "$P_UIFR[1]=CTRANS(X,\n",
        "$TC_DP1[1,1]=\n",
        "$AA_IM[X\n",
        ";comment without end\n(not a comment\n",
        "%_N_UNTERMINATED",
        "%",
        "G0 X1 ;",
        "N",
        "/",
        "/9",
        ":",
        "\"",
        "[",
        "]",
        "=",
        "(",
        ")",
        "'H",
        "'B102",
        "TRANS X\n",
        "ROT RPL=\n",
        "G1 RND=\n",
        "G2 CR=\n",
        "G2 X10\n",
        "G2 X10 CR=1 F100\n",
        "G2 X0 Y0 CR=5 F100\n",
        "G112 AP=10\n",
        "TURN=-1\n",
        "CIP X1 Y1 F100\n",
        "G1 ANG=45 F100\nG1 ANG=45\nM30\n",
        "G1 X10 CHR=2 F100\n",
        "G1 X10 RND=2 F100\nM30\n",
    ]
    .iter()
    .map(|s| b(s))
    .collect()
}

/// Calls that recurse: the 840D's library answers every call with the input itself.
fn recursion() -> Vec<Vec<u8>> {
    [
        "SUB\n",
        "L1\n",
        "L1 P3\nM30\n",
        "CALL \"SUB\"\n",
        "SUB P99999\n",
        "MCALL SUB\nG0 X1\n",
        "PROC SUB\nSUB\nRET\n",
        "PROC SUB(REAL A)\nSUB(A+1)\nRET\n",
        "PROC SUB(VAR REAL A)\nSUB(A)\nM17\n",
        "G0 X1\nSUB\nG0 X2\nM30\n",
        "R1=R1+1\nIF R1<5 GOTOF END\nSUB\nEND:\nM17\n",
        "LOOP\nSUB\nENDLOOP\n",
        "WHILE 1\nL2 P2\nENDWHILE\n",
        "A: GOTOB A\n",
        "A: G0 X1\nGOTOB A\n",
        "B: GOTOF B\n",
        "LOOP\nENDLOOP\n",
        "WHILE 1\nENDWHILE\n",
        "REPEAT\nUNTIL 0\n",
        "FOR R1=0 TO 1E9\nENDFOR\n",
        "REPEAT\nG0 X1\nUNTIL 0\n",
    ]
    .iter()
    .map(|s| b(s))
    .collect()
}

#[test]
fn huge_numbers_end_with_an_alarm_or_finite_segments() {
    check_all(&huge_numbers());
}

#[test]
fn deep_expressions_and_nesting_end_without_overflowing_the_stack() {
    check_all(&deep());
}

#[test]
fn unterminated_and_unmatched_structures_end_with_spans_inside_the_text() {
    check_all(&unterminated());
}

#[test]
fn recursive_calls_and_endless_loops_stop_at_a_limit() {
    check_all(&recursion());
    // Each of these never ends on a control: here it stops with an error on both profiles.
    for text in ["LOOP\nENDLOOP\n", "A: GOTOB A\n", "WHILE 1\nENDWHILE\n"] {
        check_stops(text);
    }
}

#[test]
fn every_byte_alone_and_after_each_letter_ends() {
    let mut inputs: Vec<Vec<u8>> = (0..=255u8).map(|c| vec![c]).collect();
    for letter in b'A'..=b'Z' {
        for c in b" !\"#$%&'()*+,-./0123456789:;<=>?@[\\]^_`{|}~\t\r\n\x00\xff" {
            inputs.push(vec![letter, *c]);
            inputs.push(vec![letter, b'=', *c]);
        }
    }
    check_all(&inputs);
}

// ---------------------------------------------------------------------------------------------
// The manual's examples and the corpus: as they are, cut short, and mutated.

/// Cut points per file: the text cut after this many eighths of its length, and at a random
/// byte (mid-word, mid-string, mid-structure).
const CUTS: usize = 8;

/// Mutations per file (about 190 files, two profiles).
const MUTANTS_PER_FILE: usize = 12;

#[test]
fn truncations_of_the_examples_and_the_corpus_end_with_spans_inside_the_text() {
    let Some(shared) = common::shared::shared_dir() else {
        return;
    };
    let mut rng = XorShift(0x5eed_5157_0000_0001);
    let mut inputs = Vec::new();
    for path in shared_files(&shared) {
        let text = std::fs::read(&path).unwrap();
        let text = &text[..text.len().min(16 * 1024)];
        for eighth in 1..CUTS {
            inputs.push(text[..text.len() * eighth / CUTS].to_vec());
        }
        inputs.push(text[..rng.below(text.len() + 1)].to_vec());
    }
    check_all(&inputs);
}

#[test]
fn seeded_mutations_of_the_examples_and_the_corpus_end_with_spans_inside_the_text() {
    let Some(shared) = common::shared::shared_dir() else {
        return;
    };
    let files: Vec<Vec<u8>> = shared_files(&shared)
        .iter()
        .map(|p| {
            let text = std::fs::read(p).unwrap();
            text[..text.len().min(16 * 1024)].to_vec()
        })
        .collect();
    let mut rng = XorShift(0x5eed_5157_0000_0002);
    let mut inputs = Vec::new();
    for (i, text) in files.iter().enumerate() {
        let other = &files[(i * 7 + 3) % files.len()];
        for _ in 0..MUTANTS_PER_FILE {
            inputs.push(mutate(text, other, &mut rng));
        }
    }
    check_all(&inputs);
}

/// Every alarm the front end raises on the manual's examples and the corpus, run as they are
/// from their folder (so that the corpus's subprograms are found where they are), has a span
/// and a one-line help line saying what to do.
#[test]
fn every_alarm_on_the_examples_and_the_corpus_has_a_span_and_a_help_line() {
    let Some(shared) = common::shared::shared_dir() else {
        return;
    };
    let (_, machine) = machines().swap_remove(0);
    let mut failures = Vec::new();
    let mut alarms_seen = 0;
    for path in shared_files(&shared) {
        let text = std::fs::read(&path).unwrap();
        let folder = path.parent().unwrap().to_path_buf();
        let library = DirectoryLibrary::new(Some(path.clone()), vec![folder], 1);
        let front_end = Sinumerik::new(text, FileId(0), &machine).with_library(Box::new(library));
        for item in Run::new(front_end, Kernel::new(&machine)).take(10_000_000) {
            let Err(alarm) = item else { continue };
            alarms_seen += 1;
            let name = path.file_name().unwrap().to_string_lossy();
            if alarm.span.is_none() {
                failures.push(format!("{name}: alarm without a span: {alarm:?}"));
            }
            if let Err(e) = check_help(&alarm) {
                failures.push(format!("{name}: {e}"));
            }
        }
    }
    assert!(
        alarms_seen > 50,
        "only {alarms_seen} alarms: are the examples there?"
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

// ---------------------------------------------------------------------------------------------
// Random input.

/// Text made of SINUMERIK's words, keywords and punctuation.
fn sinumerik_like() -> impl Strategy<Value = Vec<u8>> {
    let piece = prop::sample::select(vec![
        "G0 ",
        "G1 ",
        "G2 ",
        "G3 ",
        "CIP ",
        "G17 ",
        "G18 ",
        "G19 ",
        "G90 ",
        "G91 ",
        "G111 ",
        "G112 ",
        "G110 ",
        "X",
        "Y",
        "Z",
        "A",
        "B",
        "C",
        "I",
        "J",
        "K",
        "I1=",
        "J1=",
        "CR=",
        "AR=",
        "AP=",
        "RP=",
        "TURN=",
        "RND=",
        "CHF=",
        "ANG=",
        "F",
        "S",
        "T",
        "D",
        "M3 ",
        "M6 ",
        "M30 ",
        "R1",
        "R2",
        "=",
        "==",
        "<",
        "+",
        "-",
        "*",
        "/",
        "(",
        ")",
        "[",
        "]",
        ",",
        "\"",
        "1",
        "0",
        "2.5",
        "-7",
        "1E300",
        "AC(",
        "IC(",
        "SIN(",
        "SQRT(",
        "IF ",
        "ELSE",
        "ENDIF",
        "WHILE ",
        "ENDWHILE",
        "FOR ",
        " TO ",
        "ENDFOR",
        "REPEAT",
        "UNTIL ",
        "LOOP",
        "ENDLOOP",
        "GOTOF ",
        "GOTOB ",
        "L1: ",
        "L1",
        "DEF INT ",
        "DEF REAL ",
        "PROC ",
        "RET",
        "SUB",
        " P2",
        "TRANS ",
        "ATRANS ",
        "ROT ",
        "AROT ",
        "SCALE ",
        "MIRROR ",
        "RPL=",
        "G54 ",
        "G500 ",
        "G53 ",
        "; ",
        "MSG(",
        "$P_UIFR[1]",
        "$AA_IM[X]",
        "\n",
        "\n",
        "\n",
        " ",
    ]);
    prop::collection::vec(piece, 0..60).prop_map(|pieces| pieces.concat().into_bytes())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn random_bytes_through_the_sinumerik_front_end_end(text in prop::collection::vec(any::<u8>(), 0..300)) {
        if let Err(e) = check_everywhere(&text) {
            prop_assert!(false, "{}", e);
        }
    }

    #[test]
    fn random_sinumerik_like_text_ends_with_spans_inside_the_text(text in sinumerik_like()) {
        if let Err(e) = check_everywhere(&text) {
            prop_assert!(false, "{}", e);
        }
    }
}

/// Alarms whose code's own help names ISO syntax get one in SINUMERIK's terms.
#[test]
fn alarms_whose_code_helps_in_iso_terms_get_a_sinumerik_help_line() {
    let deep = format!("R1={}1\n", "(".repeat(100));
    let cases = [
        ("G0 X1 * \n", "`;`"),
        ("SETAL(65000)\n", "SETAL"),
        (deep.as_str(), "docs/SINUMERIK.md"),
        ("G2 X10 Y0 CR=1 F100\n", "CR="),
        ("G1 X10\n", "G1/G2/G3"),
        ("LOOP\nENDLOOP\n", "iteration_limit"),
    ];
    for (text, expected) in cases {
        let alarms = check_stops(text);
        let error = alarms.iter().find(|a| a.is_error()).unwrap();
        assert!(
            error.help_line().contains(expected),
            "`{}`: help `{}` names {expected}",
            text.escape_debug(),
            error.help_line()
        );
    }
}

/// Findings of the fuzz target (2026-11-29): a cycle called as G41 starts (the cycles run with
/// G40), and a compensated start-up block whose next corner cannot be made (a chamfer inside an
/// offset larger than it): each stops with its alarm, and nothing is left half-held (a debug
/// assertion of the compensator fired on the program's end).
#[test]
fn fuzz_findings_of_the_compensator_stop_with_their_alarm() {
    for (text, code) in [
        ("OFFN=20G41HOLES2(,,5,,,6)", AlarmCode::CutterCompensation),
        (
            "OFFN=5G41Y1F4\nX10CHF=2\nY12",
            AlarmCode::CutterCompensation,
        ),
        (
            "N0X0Y0OFFN=5\nG41 F1X20CHF=3\nY30CHF=3\nX40n",
            AlarmCode::CutterCompensation,
        ),
    ] {
        // The 840D's library answers HOLES2 with the input itself: that run stops at the depth.
        let alarms = check_stops(text);
        assert!(
            alarms.iter().any(|a| a.is_error() && a.code == code),
            "`{}`: {alarms:?}",
            text.escape_debug()
        );
    }
}

/// The moves `text` makes on the default machine (840D) and the error that stops it.
fn moves_and_stop(text: &str) -> (usize, Alarm) {
    let items: Vec<_> = vcnc::interp::sinumerik::run_str(text, &Machine::default()).collect();
    let moves = items
        .iter()
        .filter(|item| matches!(item, Ok(Item::Segment(s)) if s.motion().is_some()))
        .count();
    let last = items
        .last()
        .expect("an item")
        .clone()
        .expect_err("an error ends the run");
    (moves, last)
}

/// A fuzz finding (2026-11-29): an ISO section (G291) whose GOTO loops for ever made its moves
/// within the G291 block, all held in memory until the section ended (24 GB, then the kernel's
/// OOM killer); the section now stops with V086 past 100,000 moves.
#[test]
fn an_iso_section_that_loops_stops_at_its_limit_of_moves() {
    let text = "N10 G1 X0 Y0 F100\nN20 G291\nN30 G1 X1\nN40 X0\nN50 GOTO 30\n";
    let (moves, last) = moves_and_stop(text);
    assert_eq!(last.code, AlarmCode::MacroLimit, "{last:?}");
    assert!(last.message.contains("100000 moves"), "{}", last.message);
    assert_eq!(last.span.unwrap().line, 2, "at the G291 block");
    // The moves before the limit come out, as the control would have made them.
    assert_eq!(moves, 100_000);
}

/// A fuzz finding (2026-11-29): a hole circle of 8551 holes called with 290 passes made 2.5
/// million moves from one line; the limit of a cycle call's moves (2,000,000, docs/SINUMERIK.md
/// 12) holds for its passes together.
#[test]
fn a_cycle_calls_passes_share_its_limit_of_moves() {
    // A pass is a rapid to each hole (the call gives no drilling cycle): 290 x 8551 moves.
    let (moves, last) = moves_and_stop("P290 HOLES2(0,0,80,0,1,8551)");
    assert_eq!(last.code, AlarmCode::MacroLimit, "{last:?}");
    assert!(last.message.contains("2000000 moves"), "{}", last.message);
    assert_eq!(moves, 2_000_000);
}
