//! Syntec's interrupt-type subprogram (issue #3): `M96 P_` arms it, `M97` disarms it, and the
//! signal (C49 on the machine) comes during the block an option names. Expected moves are worked
//! out by hand from spec/iso-syntec-milling.md §2 item 11 (seed L4954-5043): the interrupt program
//! starts in the modes of the interruption point, a plain `M99` brings the tool back there and
//! runs the interrupted block again, `M99 P_` / `M99 Q_` go on at a sequence number / line of the
//! main program, and the signal is ignored (with a warning) where the control ignores it.

use crate::common;

use crate::common::Run;
use vcnc::interp::{InterruptAt, MemoryLibrary};
use vcnc::syntax::lines::ReaderLines;
use vcnc::{
    interpret_str, AlarmCode, FileId, Interpreter, Machine, Options, ProfileName, SegmentKind,
};

/// The Syntec machine, with a C axis for G12.1.
fn syntec() -> Machine {
    common::with_c_axis(ProfileName::Syntec)
}

/// The manual's interrupt program O1111 (seed L5031-5043): saves the motion and distance
/// modes, rapids to Z100, restores the modes, stops, returns.
const O1111: &str = "%@MACRO\n#30 := #1000;\n#31 := #1004;\nG00 Z100.;\nG#30 G#31;\nM00;\nM99;\n";

/// The manual's main program (seed L5009-5029): the 10 mm square; line 3 is `G01 X10.`, line 4
/// `Y10.`.
const MAIN: &str = "M96 P1111\nG00 X0 Y0 Z0\nG01 X10. F500\nY10.\nX0\nY0\nM97\nM30\n";

fn library(programs: &[(u32, &str)]) -> MemoryLibrary {
    let mut library = MemoryLibrary::new();
    for (i, (number, text)) in programs.iter().enumerate() {
        library.insert(*number, FileId(i as u32 + 1), text);
    }
    library
}

/// Runs `program` on the Syntec machine with the signal at `at` and the programs of `programs`.
fn run(program: &str, at: &[InterruptAt], programs: &[(u32, &str)]) -> Run {
    let options = Options {
        interrupts: at.to_vec(),
        ..Options::default()
    };
    let interpreter =
        interpret_str(program, &syntec(), options).with_library(Box::new(library(programs)));
    common::collect(interpreter)
}

/// Each move as its kind and end point (machine X, Y, Z, rounded to 1e-4), in order.
fn moves(run: &Run) -> Vec<(&'static str, [f64; 3])> {
    assert!(run.error().is_none(), "{:?}", run.error());
    let ends = common::variables::move_ends(&run.segments);
    let kinds = run.segments.iter().filter_map(|s| match s.kind {
        SegmentKind::Rapid { .. } => Some("rapid"),
        SegmentKind::Line { .. } => Some("line"),
        SegmentKind::Arc { .. } => Some("arc"),
        _ => None,
    });
    kinds.zip(ends).collect()
}

fn line(n: u32) -> InterruptAt {
    InterruptAt::Line(n)
}

const R: &str = "rapid";
const L: &str = "line";

/// Asserts the moves of `main` with the signal at line `at` and `o2000` as program O2000.
#[track_caller]
fn check(main: &str, at: u32, o2000: &str, expected: &[(&str, [f64; 3])]) {
    assert_eq!(moves(&run(main, &[line(at)], &[(2000, o2000)])), expected);
}

/// The warnings of a run with this code.
fn ignored(run: &Run) -> Vec<(u32, String)> {
    run.alarms
        .iter()
        .filter(|a| a.code == AlarmCode::InterruptIgnored)
        .map(|a| (a.span.map_or(0, |s| s.line), a.message.clone()))
        .collect()
}

#[test]
fn without_the_signal_the_manuals_main_program_cuts_its_square() {
    let run = run(MAIN, &[], &[(1111, O1111)]);
    assert_eq!(
        moves(&run),
        [
            ("line", [10.0, 0.0, 0.0]),
            ("line", [10.0, 10.0, 0.0]),
            ("line", [0.0, 10.0, 0.0]),
            ("line", [0.0, 0.0, 0.0]),
        ]
    );
    assert!(ignored(&run).is_empty());
}

#[test]
fn the_signal_runs_the_interrupt_program_and_the_interrupted_block_again() {
    let run = run(MAIN, &[line(4)], &[(1111, O1111)]);
    assert_eq!(
        moves(&run),
        [
            ("line", [10.0, 0.0, 0.0]),
            // O1111: up to the tool-check point, M00, back to the interruption point.
            ("rapid", [10.0, 0.0, 100.0]),
            ("rapid", [10.0, 0.0, 0.0]),
            // `Y10.` again, in G01: O1111 restored the mode it saved.
            ("line", [10.0, 10.0, 0.0]),
            ("line", [0.0, 10.0, 0.0]),
            ("line", [0.0, 0.0, 0.0]),
        ]
    );
    let stops = run
        .segments
        .iter()
        .filter(|s| matches!(s.kind, SegmentKind::Stop { .. }))
        .count();
    assert_eq!(stops, 1, "O1111's M00");
}

#[test]
fn a_sequence_number_names_the_interrupted_block() {
    let main = "M96 P1111\nG00 X0 Y0 Z0\nN10 G01 X10. F500\nN20 Y10.\nN30 X0\nM30\n";
    let run = run(main, &[InterruptAt::Sequence(20)], &[(1111, O1111)]);
    assert_eq!(
        moves(&run)[1..4],
        [
            ("rapid", [10.0, 0.0, 100.0]),
            ("rapid", [10.0, 0.0, 0.0]),
            ("line", [10.0, 10.0, 0.0]),
        ]
    );
}

#[test]
fn the_interrupt_program_starts_in_the_modes_of_the_interruption_point() {
    // Interrupted during `G00 X50.`: the interrupt program starts in G00 (seed L4976-4978);
    // in G91 its `Z5.` is an increment.
    check(
        "M96 P2000\nG91 G00 X50.\nM30\n",
        2,
        "X-5.\nZ5.\nM99\n",
        &[
            (R, [-5.0, 0.0, 0.0]),
            (R, [-5.0, 0.0, 5.0]),
            (R, [0.0, 0.0, 0.0]),
            (R, [50.0, 0.0, 0.0]),
        ],
    );
}

#[test]
fn modes_the_interrupt_program_changes_stay_for_the_block_run_again() {
    // Without the manual's mode backup, the interrupted `G01 ... Y10.` block runs again in G00
    // (the block is read afresh: seed L4979-4985).
    check(
        "M96 P2000\nG01 X10. F500\nY10.\nM30\n",
        3,
        "G00 Z50.\nM99\n",
        &[
            (L, [10.0, 0.0, 0.0]),
            (R, [10.0, 0.0, 50.0]),
            (R, [10.0, 0.0, 0.0]),
            (R, [10.0, 10.0, 0.0]),
        ],
    );
}

#[test]
fn in_g91_the_block_run_again_moves_from_the_interruption_point() {
    // The manual's `G00 Z100.` from Z0 (seed L4980-4985): vcnc interrupts before the block
    // moves, so the interruption point is Z0 and G91 Z100. ends at Z100 (the control, stopped
    // at Z35, would end at Z135).
    check(
        "M96 P2000\nG91 G00 Z100.\nM30\n",
        2,
        "G91 G00 Z20.\nM99\n",
        &[
            (R, [0.0, 0.0, 20.0]),
            (R, [0.0, 0.0, 0.0]),
            (R, [0.0, 0.0, 100.0]),
        ],
    );
}

#[test]
fn m99_p_goes_on_at_a_sequence_number_of_the_main_program() {
    // N20 is abandoned, N30 runs from where the interrupt program left the tool (in G00).
    check(
        "M96 P2000\nN10 G01 X10. F500\nN20 Y10.\nN30 X20.\nM30\n",
        3,
        "G00 Z50.\nM99 P30\n",
        &[
            (L, [10.0, 0.0, 0.0]),
            (R, [10.0, 0.0, 50.0]),
            (R, [20.0, 0.0, 50.0]),
        ],
    );
}

#[test]
fn m99_q_goes_on_at_a_line_of_the_main_program() {
    check(
        "M96 P2000\nG01 X10. F500\nY10.\nX20.\nY20.\nM30\n",
        3,
        "G00 Z50.\nG01\nM99 Q5\n",
        &[
            (L, [10.0, 0.0, 0.0]),
            (R, [10.0, 0.0, 50.0]),
            (L, [10.0, 20.0, 50.0]),
        ],
    );
}

#[test]
fn m99_q_beyond_the_main_program_is_an_alarm_at_the_m99() {
    let run = run(
        "M96 P4000\nG01 X10. F500\nM30\n",
        &[line(2)],
        &[(4000, "M99 Q40\n")],
    );
    let error = run.error().expect("no line 40");
    assert_eq!(error.code, AlarmCode::SequenceNotFound);
    assert_eq!(error.span.map(|s| (s.file, s.line)), Some((FileId(1), 1)));
}

#[test]
fn a_missing_interrupt_program_is_an_alarm_at_m96() {
    let run = run("M96 P5555\nG01 X10. F500\nM30\n", &[line(2)], &[]);
    let error = run.error().expect("O5555 is nowhere");
    assert_eq!(error.code, AlarmCode::ProgramNotFound);
    assert_eq!(error.span.map(|s| s.line), Some(1));
    assert_eq!(error.labels[0].span.line, 2, "the interrupted block");
    assert!(
        moves(&Run {
            segments: run.segments.clone(),
            alarms: Vec::new()
        })
        .is_empty(),
        "the interrupted block never runs"
    );
}

#[test]
fn the_signal_is_ignored_without_m96_and_after_m97() {
    let o1 = "G00 Z50.\nM99\n";
    let program = "G01 X10. F500\nM96 P1\nM97\nY10.\nM30\n";
    let run = run(program, &[line(1), line(4)], &[(1, o1)]);
    assert_eq!(
        moves(&run),
        [("line", [10.0, 0.0, 0.0]), ("line", [10.0, 10.0, 0.0])]
    );
    let warnings = ignored(&run);
    assert_eq!(warnings.len(), 2, "{warnings:?}");
    assert_eq!(warnings[0].0, 1);
    assert_eq!(warnings[1].0, 4);
    assert!(warnings[1].1.contains("M96"), "{}", warnings[1].1);
}

#[test]
fn the_signal_is_ignored_in_the_modes_the_manual_lists() {
    let o1 = "G00 Z50.\nM99\n";
    let cases = [
        ("G41 D0 G01 X10. F500\nY10.\nG40 X20.\n", "G41/G42"),
        ("G16 G01 X10. Y0 F500\nX10. Y90.\nG15\n", "G16"),
        ("G51 X0 Y0 P2\nG01 X10. F500\nG50\n", "G51"),
        ("G51.1 X0\nG01 X10. F500\nG50.1 X0\n", "G51.1"),
        ("G12.1\nG01 X10. F500\nG13.1\n", "G12.1"),
        ("G05 P10000\nG01 X10. F500\nG05 P0\n", "G05"),
        ("G05.1 Q1 E0.01\nG01 X10. F500\nG05.1 Q0\n", "G05.1"),
    ];
    for (body, mode) in cases {
        let program = format!("M96 P1\n{body}M30\n");
        let run = run(&program, &[line(3)], &[(1, o1)]);
        assert!(run.error().is_none(), "{mode}: {:?}", run.error());
        let warnings = ignored(&run);
        assert_eq!(warnings.len(), 1, "{mode}: {warnings:?}");
        assert_eq!(warnings[0].0, 3, "{mode}");
        assert!(warnings[0].1.contains(mode), "{mode}: {}", warnings[0].1);
        assert!(
            !moves(&run).iter().any(|(_, p)| p[2] == 50.0),
            "{mode}: the interrupt program ran"
        );
    }
}

#[test]
fn the_signal_is_ignored_inside_a_subprogram() {
    // Line 5 is O0200's `X20.`, in the same file after M30.
    let program = "M96 P1\nM98 P200\nM30\nO0200\nX20.\nM99\n";
    let run = run(program, &[line(5)], &[(1, "G00 Z50.\nM99\n")]);
    assert_eq!(moves(&run), [("rapid", [20.0, 0.0, 0.0])]);
    let warnings = ignored(&run);
    assert_eq!(warnings.len(), 1);
    assert!(warnings[0].1.contains("subprogram"), "{}", warnings[0].1);
}

#[test]
fn each_signal_comes_once_even_when_a_loop_runs_the_block_again() {
    check(
        "M96 P2000\n#1 = 0\nWHILE [#1 LT 3] DO1\nG00 X#1\n#1 = #1 + 1\nEND1\nM30\n",
        4,
        "G91 G00 Z1.\nG90\nM99\n",
        &[
            (R, [0.0, 0.0, 1.0]),
            (R, [0.0, 0.0, 0.0]),
            (R, [1.0, 0.0, 0.0]),
            (R, [2.0, 0.0, 0.0]),
        ],
    );
}

#[test]
fn two_signals_interrupt_two_blocks() {
    let o1 = "G91 G00 Z1.\nG90\nM99\n";
    let program = "M96 P1\nG00 X1.\nX2.\nX3.\nM30\n";
    let run = run(program, &[line(2), InterruptAt::Line(4)], &[(1, o1)]);
    let zs = moves(&run).iter().filter(|(_, p)| p[2] == 1.0).count();
    assert_eq!(zs, 2);
}

#[test]
fn a_streamed_main_program_is_loaded_when_the_signal_comes() {
    // The interrupted block must run again, so the main program is held in memory from the
    // signal on (as a jump does); the stream gives its text through the library.
    struct WithMain(MemoryLibrary, &'static str);
    impl vcnc::interp::ProgramLibrary for WithMain {
        fn find(
            &mut self,
            number: u32,
        ) -> Result<Option<vcnc::interp::ProgramText>, vcnc::interp::LookupError> {
            self.0.find(number)
        }
        fn main_text(&mut self) -> Option<std::sync::Arc<[u8]>> {
            Some(std::sync::Arc::from(self.1.as_bytes()))
        }
    }
    let options = Options {
        interrupts: vec![line(4)],
        ..Options::default()
    };
    let interpreter = Interpreter::new(
        ReaderLines::new(MAIN.as_bytes()),
        FileId(0),
        &syntec(),
        options,
    )
    .with_library(Box::new(WithMain(library(&[(1111, O1111)]), MAIN)));
    let streamed = common::collect(interpreter);
    let in_memory = run(MAIN, &[line(4)], &[(1111, O1111)]);
    assert_eq!(moves(&streamed), moves(&in_memory));
}
