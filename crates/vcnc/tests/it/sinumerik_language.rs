//! The SINUMERIK language and geometry through the whole front end (issue #20, acceptance 4):
//! each test runs a short program and asserts the machine positions of its motion stream, with
//! the numbers worked out by hand in a comment. Expressions and their precedence, jumps and
//! their search directions, loops, PROC parameters, MCALL, frames in the order of
//! docs/SINUMERIK.md 5.3, IC after a frame change (6.4), polar coordinates (6.5), contour
//! definitions, arcs, tools, the spindle and system variables. The last test is a property:
//! a random sequence of frame blocks maps a point as the components of 5.3, composed here
//! independently as 4x4 matrices, say.

use crate::common::{collect, Run};
use proptest::prelude::*;
use std::f64::consts::PI;
use vcnc::interp::sinumerik::{run_str, Sinumerik};
use vcnc::interp::{Kernel, MemoryLibrary};
use vcnc::machine::WorkOffsetId;
use vcnc::motion::{ArcDirection, SpindleState};
use vcnc::{AlarmCode, FileId, Machine, Segment, SegmentKind};

use crate::common::sinumerik::{machine, mill};

/// G54 = X100 Y50 Z0 (the numbers of docs/SINUMERIK.md 5.3), G55 = X200; tool 1 "MILL10"
/// (type 120, radius 5) with D1 L1 = 100 and D2 L1 = 50, tool 2 "DRILL8" (radius 4) D1 L1 = 80.
fn shop() -> Machine {
    let mut machine = machine();
    machine
        .work_offsets
        .insert(WorkOffsetId::Standard(1), [100.0, 50.0, 0.0, 0.0, 0.0, 0.0]);
    machine
        .work_offsets
        .insert(WorkOffsetId::Standard(2), [200.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    for (t, name, d, length, radius) in [
        (1, "MILL10", 1, 100.0, 5.0),
        (1, "MILL10", 2, 50.0, 5.0),
        (2, "DRILL8", 1, 80.0, 4.0),
    ] {
        machine.tools.push(mill(t, name, d, length, radius));
    }
    machine
}

fn run_on(text: &str, machine: &Machine) -> Run {
    collect(run_str(text, machine))
}

/// `text` with the subprograms `library` (name, text) to call.
fn run_with(text: &str, library: &[(&str, &str)]) -> Run {
    let mut programs = MemoryLibrary::new();
    for (n, (name, body)) in library.iter().enumerate() {
        programs.insert_named(name, FileId(n as u32 + 1), body);
    }
    let machine = machine();
    let front_end =
        Sinumerik::new(text.as_bytes(), FileId(0), &machine).with_library(Box::new(programs));
    collect(vcnc::interp::Run::new(front_end, Kernel::new(&machine)))
}

/// The end points of the moves, machine X Y Z.
fn ends(segments: &[Segment]) -> Vec<[f64; 3]> {
    segments
        .iter()
        .filter_map(Segment::motion)
        .map(|m| [m.to.0[0], m.to.0[1], m.to.0[2]])
        .collect()
}

/// The end points of a run that must have raised no error.
#[track_caller]
fn ends_of(run: &Run, text: &str) -> Vec<[f64; 3]> {
    assert!(run.error().is_none(), "{text}\n{:#?}", run.alarms);
    ends(&run.segments)
}

fn close(a: [f64; 3], b: [f64; 3], tolerance: f64) -> bool {
    a.iter().zip(b).all(|(p, q)| (p - q).abs() < tolerance)
}

#[track_caller]
fn assert_points(got: &[[f64; 3]], wanted: &[[f64; 3]], text: &str) {
    assert!(
        got.len() == wanted.len() && got.iter().zip(wanted).all(|(g, w)| close(*g, *w, 1e-3)),
        "{text}\ngot    {got:?}\nwanted {wanted:?}"
    );
}

/// Asserts every move end of `text` on the plain machine (no offsets).
#[track_caller]
fn assert_moves(text: &str, wanted: &[[f64; 3]]) {
    let got = ends_of(&run_on(text, &machine()), text);
    assert_points(&got, wanted, text);
}

/// Asserts every move end of `text` on [`shop`].
#[track_caller]
fn assert_shop(text: &str, wanted: &[[f64; 3]]) {
    let got = ends_of(&run_on(text, &shop()), text);
    assert_points(&got, wanted, text);
}

/// Asserts the last move end of `G54` then `text` on [`shop`] (G54 = X100 Y50).
#[track_caller]
fn assert_last(text: &str, wanted: [f64; 3]) {
    let program = format!("G54\n{text}\nM30\n");
    let got = ends_of(&run_on(&program, &shop()), &program);
    let last = *got
        .last()
        .unwrap_or_else(|| panic!("no move in\n{program}"));
    assert_points(&[last], &[wanted], &program);
}

/// The X values the moves of `text` go to (plain machine).
#[track_caller]
fn xs(text: &str) -> Vec<f64> {
    ends_of(&run_on(text, &machine()), text)
        .iter()
        .map(|p| p[0])
        .collect()
}

/// The first error of `text` on the plain machine.
#[track_caller]
fn error_code(text: &str) -> AlarmCode {
    let run = run_on(text, &machine());
    run.error()
        .unwrap_or_else(|| panic!("no error in\n{text}"))
        .code
}

/// The arcs of a stream: end, centre, direction and extra turns.
fn arcs(segments: &[Segment]) -> Vec<([f64; 3], [f64; 3], ArcDirection, u32)> {
    segments
        .iter()
        .filter_map(|s| match s.kind {
            SegmentKind::Arc {
                motion,
                center,
                direction,
                extra_turns,
                ..
            } => Some((
                [motion.to.0[0], motion.to.0[1], motion.to.0[2]],
                [center.0[0], center.0[1], center.0[2]],
                direction,
                extra_turns,
            )),
            _ => None,
        })
        .collect()
}

/// The arcs of `text` on `machine`, which must run without an error.
#[track_caller]
fn arcs_of(text: &str, machine: &Machine) -> Vec<([f64; 3], [f64; 3], ArcDirection, u32)> {
    let run = run_on(text, machine);
    assert!(run.error().is_none(), "{text}\n{:?}", run.alarms);
    arcs(&run.segments)
}

/// The spindle speeds the stream sets, in order.
fn speeds(segments: &[Segment]) -> Vec<f64> {
    segments
        .iter()
        .filter_map(|s| match s.kind {
            SegmentKind::Spindle { speed, .. } => Some(speed),
            _ => None,
        })
        .collect()
}

// ---------------------------------------------------------------------------------------------
// Expressions: precedence and types in positions.

#[test]
fn multiplication_binds_tighter_than_addition_and_minus_is_left_associative() {
    // 2+3*4 = 14; (2+3)*4 = 20; 10-4-3 = (10-4)-3 = 3.
    assert_moves("G0 X=2+3*4 Y=(2+3)*4 Z=10-4-3\nM30\n", &[[14.0, 20.0, 3.0]]);
}

#[test]
fn div_is_integer_division_slash_is_real_and_mod_the_remainder() {
    // 7 DIV 2 = 3 (integer division), 7/2 = 3.5, 7 MOD 3 = 1.
    assert_moves("G0 X=7 DIV 2 Y=7/2 Z=7 MOD 3\nM30\n", &[[3.0, 3.5, 1.0]]);
}

#[test]
fn operators_of_one_level_go_left_to_right_and_unary_minus_binds_tightest() {
    // 12/2/3 = (12/2)/3 = 2; 2*3 MOD 4 = 6 MOD 4 = 2; -2*3+10 = (-2)*3+10 = 4.
    assert_moves(
        "G0 X=12/2/3 Y=2*3 MOD 4 Z=-2*3+10\nM30\n",
        &[[2.0, 2.0, 4.0]],
    );
}

#[test]
fn arithmetic_functions_give_positions() {
    // SQRT(16) + POT(3) = 4 + 9 = 13; ABS(-2.5) = 2.5; TRUNC(2.7) = 2.
    assert_moves(
        "G0 X=SQRT(16)+POT(3) Y=ABS(-2.5) Z=TRUNC(2.7)\nM30\n",
        &[[13.0, 2.5, 2.0]],
    );
}

#[test]
fn trigonometric_functions_work_in_degrees() {
    // SIN(30)*10 = 5; COS(60)*10 = 5; ATAN2(1,1) = 45 degrees.
    assert_moves(
        "G0 X=SIN(30)*10 Y=COS(60)*10 Z=ATAN2(1,1)\nM30\n",
        &[[5.0, 5.0, 45.0]],
    );
}

#[test]
fn comparisons_are_values_and_bind_least() {
    // (3>2) + (2==2) + (1<>1) = 1 + 1 + 0 = 2; 1+1==2 is (1+1)==2, TRUE = 1.
    assert_moves(
        "R1=(3>2)+(2==2)+(1<>1)\nR2=1+1==2\nG0 X=R1 Y=R2\nM30\n",
        &[[2.0, 1.0, 0.0]],
    );
}

#[test]
fn bit_operators_bind_looser_than_addition() {
    // 5 B_AND 3 = 0b101 & 0b011 = 1; 5 B_OR 3 = 7; 5 B_XOR 3 = 6;
    // 1+5 B_AND 3 = (1+5) B_AND 3 = 6 & 3 = 2.
    assert_moves(
        "G0 X=5 B_AND 3 Y=5 B_OR 3 Z=5 B_XOR 3\nG0 X=1+5 B_AND 3\nM30\n",
        &[[1.0, 7.0, 6.0], [2.0, 7.0, 6.0]],
    );
}

#[test]
fn a_real_assigned_to_an_int_is_rounded() {
    // INT NUM = 2.5 -> 3 (rounded, not cut); NUM = 7/2 = 3.5 -> 4; NUM = 2.4 -> 2.
    assert_moves(
        "DEF INT NUM\nNUM=2.5\nG0 X=NUM\nNUM=7/2\nG0 X=NUM\nNUM=2.4\nG0 X=NUM\nM30\n",
        &[[3.0, 0.0, 0.0], [4.0, 0.0, 0.0], [2.0, 0.0, 0.0]],
    );
}

#[test]
fn conditions_in_if_compare_with_every_operator() {
    // R1 = 5: >= 5 true (X1), < 5 false, <> 4 true (X3), == 5.0 true (X4), <= 4 false.
    let text = "R1=5\nIF R1>=5\nG0 X1\nENDIF\nIF R1<5\nG0 X2\nENDIF\nIF R1<>4\nG0 X3\nENDIF\n\
                IF R1==5.0\nG0 X4\nENDIF\nIF R1<=4\nG0 X5\nENDIF\nM30\n";
    assert_eq!(xs(text), [1.0, 3.0, 4.0]);
}

#[test]
fn and_without_parentheses_is_read_inside_the_comparison() {
    // With parentheses: (R1==1) AND (R2==2) is TRUE -> X1. Without: R1==1 AND R2==2 reads
    // R1 == (1 AND R2) == 2 = (1 == TRUE) == 2 = TRUE == 2 = FALSE -> X2.
    let text = "R1=1 R2=2\nIF (R1==1) AND (R2==2)\nG0 X1\nELSE\nG0 X9\nENDIF\n\
                IF R1==1 AND R2==2\nG0 X9\nELSE\nG0 X2\nENDIF\nM30\n";
    assert_eq!(xs(text), [1.0, 2.0]);
}

#[test]
fn not_and_or_combine_truth_values() {
    // NOT 0 = TRUE; 0 OR 1 = TRUE; 1 XOR 1 = FALSE; NOT binds tighter than AND.
    let text = "R1=0\nIF NOT R1 AND (R1 OR 1)\nG0 X1\nENDIF\nIF 1 XOR 1\nG0 X9\nENDIF\nM30\n";
    assert_eq!(xs(text), [1.0]);
}

#[test]
fn a_string_is_chained_and_measured() {
    // "AB" << "CDE" = "ABCDE", 5 characters.
    assert_eq!(
        xs("DEF STRING[10] TXT\nTXT=\"AB\"<<\"CDE\"\nG0 X=STRLEN(TXT)\nM30\n"),
        [5.0]
    );
}

#[test]
fn an_array_is_filled_with_set_and_rep_and_indexed_from_zero() {
    // SET(1,2,3): AA[0]=1 AA[1]=2 AA[2]=3; REP(7) fills BB; AA[2]+BB[1] = 3 + 7 = 10.
    assert_moves(
        "DEF REAL AA[3]=SET(1,2,3)\nDEF REAL BB[2]=REP(7)\nG0 X=AA[0] Y=AA[2]+BB[1]\nM30\n",
        &[[1.0, 10.0, 0.0]],
    );
}

// ---------------------------------------------------------------------------------------------
// Jumps: directions, duplicate labels and block numbers.

#[test]
fn gotof_with_a_label_written_twice_takes_the_first_after_the_jump() {
    // The jump is on line 3: the MARK of line 1 is behind it, the MARK of line 5 the first
    // ahead, so X2 (line 4) is skipped and X3 (line 5) and X4 follow.
    let text = "MARK: G0 X1\nR1=1\nGOTOF MARK\nG0 X2\nMARK: G0 X3\nMARK: G0 X4\nM30\n";
    assert_eq!(xs(text), [1.0, 3.0, 4.0]);
}

#[test]
fn gotob_with_a_label_written_twice_takes_the_nearest_before_the_jump() {
    // TOP on lines 2 and 3 (X1, X2); the jump on line 6 goes back to the nearer one, line 3.
    // R1 = 2 - 1 = 1 after the first pass: jump (X2, X3 again); then 0: no jump.
    let text = "R1=2\nTOP: G0 X1\nTOP: G0 X2\nG0 X3\nR1=R1-1\nIF R1>0 GOTOB TOP\nM30\n";
    assert_eq!(xs(text), [1.0, 2.0, 3.0, 2.0, 3.0]);
}

#[test]
fn gotof_to_a_block_number_written_twice_takes_the_first_ahead() {
    // N20 on lines 1 and 4; from line 2 forwards the N20 of line 4 (X4), then on.
    let text = "N20 G0 X1\nGOTOF N20\nG0 X2\nN20 G0 X4\nM30\n";
    assert_eq!(xs(text), [1.0, 4.0]);
}

#[test]
fn gotob_to_a_block_number_counts_passes() {
    // N10 on line 2; R2 counts 0 -> 1 -> 2 -> 3; the jump back runs while R2 < 3: three
    // passes of X=R2*10+10 with R2 = 0, 1, 2 -> X10, X20, X30.
    let text = "R2=0\nN10 G0 X=R2*10+10\nR2=R2+1\nIF R2<3 GOTOB N10\nM30\n";
    assert_eq!(xs(text), [10.0, 20.0, 30.0]);
}

#[test]
fn goto_searches_ahead_first_and_then_back() {
    // GOTO B is found ahead (X5); R1 = 1; GOTO A is not ahead and found behind (X4, X5);
    // R1 = 2: no jump.
    let text = "R1=0\nGOTO B\nG0 X1\nA: G0 X4\nB: G0 X5\nR1=R1+1\nIF R1==1 GOTO A\nM30\n";
    assert_eq!(xs(text), [5.0, 4.0, 5.0]);
}

#[test]
fn gotoc_without_a_target_goes_on_and_goto_without_one_alarms() {
    assert_eq!(xs("GOTOC NONE\nG0 X1\nM30\n"), [1.0]);
    assert_eq!(
        error_code("GOTO NONE\nG0 X1\nM30\n"),
        AlarmCode::SequenceNotFound
    );
    assert_eq!(
        error_code("G0 X1\nN5 G0 X2\nGOTOF N5\nM30\n"),
        AlarmCode::SequenceNotFound
    );
}

#[test]
fn the_jump_acts_after_the_other_words_of_its_block() {
    // `G0 X3 GOTOF END` moves to X3 first (docs/SINUMERIK.md 3.1: the jump is the last action).
    assert_eq!(xs("G0 X3 GOTOF END\nG0 X4\nEND: M30\n"), [3.0]);
}

#[test]
fn gotos_goes_back_to_the_program_start() {
    // R1 counts the passes: the first pass sets it to 1 and jumps, the second ends.
    let text = "G0 X=R1+1\nR1=R1+1\nIF R1<2 GOTOS\nM30\n";
    assert_eq!(xs(text), [1.0, 2.0]);
}

// ---------------------------------------------------------------------------------------------
// Loops, CASE and part repetition.

#[test]
fn nested_for_loops_run_the_product_of_their_counts() {
    // 2 outer x 3 inner passes: X = 10*II + JJ for II = 1..2, JJ = 1..3.
    let text = "DEF INT II, JJ\nFOR II=1 TO 2\nFOR JJ=1 TO 3\nG0 X=10*II+JJ\nENDFOR\nENDFOR\nM30\n";
    assert_eq!(xs(text), [11.0, 12.0, 13.0, 21.0, 22.0, 23.0]);
}

#[test]
fn for_with_a_defined_int_counter_leaves_it_one_past_the_end() {
    // FOR NUM=3 TO 5: X3, X4, X5; after the loop NUM = 6.
    let text = "DEF INT NUM\nFOR NUM=3 TO 5\nG0 X=NUM\nENDFOR\nG0 X=NUM\nM30\n";
    assert_eq!(xs(text), [3.0, 4.0, 5.0, 6.0]);
}

#[test]
fn while_inside_for_tests_its_condition_each_time() {
    // For II = 1..3: R1 starts at 0 and WHILE R1 < II adds 1: II passes each -> 1 + 2 + 3 = 6
    // moves of G91 X1: the last X6.
    let text =
        "DEF INT II\nG91\nFOR II=1 TO 3\nR1=0\nWHILE R1<II\nG0 X1\nR1=R1+1\nENDWHILE\nENDFOR\nM30\n";
    let got = xs(text);
    assert_eq!(got.len(), 6);
    assert!((got[5] - 6.0).abs() < 1e-9, "{got:?}");
}

#[test]
fn repeat_until_runs_until_its_condition_is_true() {
    // R1 = 0, 1, 2 at the moves (X = R1+1); UNTIL R1>=3 ends after R1 = 3.
    let text = "R1=0\nREPEAT\nG0 X=R1+1\nR1=R1+1\nUNTIL R1>=3\nM30\n";
    assert_eq!(xs(text), [1.0, 2.0, 3.0]);
}

#[test]
fn loop_inside_while_is_left_by_a_jump() {
    // The WHILE runs twice (R2 = 0, 1); each time the LOOP runs until R1 counts to 2 more:
    // X = R1 = 1, 2 then 3, 4.
    let text = "R1=0 R2=0\nWHILE R2<2\nLOOP\nR1=R1+1\nG0 X=R1\nIF R1 MOD 2==0 GOTOF OUT\nENDLOOP\n\
                OUT: R2=R2+1\nENDWHILE\nM30\n";
    assert_eq!(xs(text), [1.0, 2.0, 3.0, 4.0]);
}

#[test]
fn case_picks_its_branch_by_value_and_default_otherwise() {
    // R1 = 3: no branch 3 -> DEFAULT (X9); R1 = 1 -> ONE (X1); R1 = 2 -> TWO (X2).
    let base = "CASE(R1) OF 1 GOTOF ONE 2 GOTOF TWO DEFAULT GOTOF OTHER\nONE: G0 X1\nGOTOF END\n\
                TWO: G0 X2\nGOTOF END\nOTHER: G0 X9\nEND: M30\n";
    assert_eq!(xs(&format!("R1=3\n{base}")), [9.0]);
    assert_eq!(xs(&format!("R1=1\n{base}")), [1.0]);
    assert_eq!(xs(&format!("R1=2\n{base}")), [2.0]);
}

#[test]
fn case_on_an_expression() {
    // R1 = 5: R1 MOD 3 = 2 -> TWO.
    let text = "R1=5\nCASE(R1 MOD 3) OF 0 GOTOF ZERO 2 GOTOF TWO\nZERO: G0 X1\nTWO: G0 X2\nM30\n";
    assert_eq!(xs(text), [2.0]);
}

#[test]
fn repeat_of_a_section_in_a_loop_uses_the_current_values() {
    // Section A..B is `G0 X=R1+1` / `R1=R1+1`; it runs once (R1 0 -> 1), then REPEAT A B P=2
    // runs it twice more: X1, X2, X3.
    let text = "R1=0\nA: G0 X=R1+1\nB: R1=R1+1\nREPEAT A B P=2\nM30\n";
    assert_eq!(xs(text), [1.0, 2.0, 3.0]);
}

#[test]
fn repeat_to_endlabel_without_p_runs_once_more() {
    // START..ENDLABEL holds one move (G91 X1); REPEAT START runs it once again: X1, X2.
    let text = "G91\nSTART: G0 X1\nENDLABEL:\nREPEAT START\nM30\n";
    assert_eq!(xs(text), [1.0, 2.0]);
}

// ---------------------------------------------------------------------------------------------
// Subprograms: PROC parameters, local variables, SAVE, MCALL.

#[test]
fn a_value_parameter_leaves_the_callers_variable_unchanged() {
    // SUB(VB) with VB = 1: PA = 1 + 10 = 11 in SUB (X11); the caller's VB is still 1 (Y1).
    let text = "DEF REAL VB=1\nSUB(VB)\nG0 Y=VB\nM30\n";
    let run = run_with(
        text,
        &[("SUB", "PROC SUB(REAL PA)\nPA=PA+10\nG0 X=PA\nRET\n")],
    );
    assert_points(
        &ends_of(&run, text),
        &[[11.0, 0.0, 0.0], [11.0, 1.0, 0.0]],
        text,
    );
}

#[test]
fn a_var_parameter_changes_the_callers_variable() {
    // SUB(VB) with VAR: PA is VB; PA = 11 changes VB: Y11.
    let text = "DEF REAL VB=1\nSUB(VB)\nG0 Y=VB\nM30\n";
    let run = run_with(
        text,
        &[("SUB", "PROC SUB(VAR REAL PA)\nPA=PA+10\nG0 X=PA\nRET\n")],
    );
    assert_points(
        &ends_of(&run, text),
        &[[11.0, 0.0, 0.0], [11.0, 11.0, 0.0]],
        text,
    );
}

#[test]
fn a_var_parameter_may_be_an_r_parameter() {
    // R5 = 2 doubled by reference in DOUBLE: X4.
    let text = "R5=2\nDOUBLE(R5)\nG0 X=R5\nM30\n";
    let run = run_with(
        text,
        &[("DOUBLE", "PROC DOUBLE(VAR REAL VAL)\nVAL=VAL*2\nRET\n")],
    );
    assert_points(&ends_of(&run, text), &[[4.0, 0.0, 0.0]], text);
}

#[test]
fn a_value_argument_may_be_an_expression_and_a_var_one_may_not() {
    // SUB(2*3): PA = 6 -> X6.
    let text = "SUB(2*3)\nM30\n";
    let run = run_with(text, &[("SUB", "PROC SUB(REAL PA)\nG0 X=PA\nRET\n")]);
    assert_points(&ends_of(&run, text), &[[6.0, 0.0, 0.0]], text);
    let run = run_with(text, &[("SUB", "PROC SUB(VAR REAL PA)\nG0 X=PA\nRET\n")]);
    assert_eq!(run.error().map(|a| a.code), Some(AlarmCode::BadVariable));
}

#[test]
fn an_array_passed_by_reference_is_written_by_the_subprogram() {
    // FILL writes VV[0] = 7 and VV[2] = VV[0] + 1 = 8 in the caller's array.
    let text = "DEF REAL VV[3]\nFILL(VV)\nG0 X=VV[0] Y=VV[2]\nM30\n";
    let run = run_with(
        text,
        &[(
            "FILL",
            "PROC FILL(VAR REAL ARR[3])\nARR[0]=7\nARR[2]=ARR[0]+1\nRET\n",
        )],
    );
    assert_points(&ends_of(&run, text), &[[7.0, 8.0, 0.0]], text);
}

#[test]
fn omitted_parameters_take_their_default() {
    // SUB(, 3): PA left out is 0, PB = 3 -> X0 Y3.
    let text = "SUB(,3)\nM30\n";
    let run = run_with(
        text,
        &[("SUB", "PROC SUB(REAL PA, REAL PB)\nG0 X=PA Y=PB\nRET\n")],
    );
    assert_points(&ends_of(&run, text), &[[0.0, 3.0, 0.0]], text);
}

#[test]
fn each_call_level_has_its_own_local_variables() {
    // OUTER's NUM = 1 and INNER's NUM = 5 are two variables: INNER moves X5, back in OUTER
    // NUM is still 1 (Y1); the main program's NUM = 9 is untouched (Z9).
    let text = "DEF INT NUM=9\nOUTER\nG0 Z=NUM\nM30\n";
    let run = run_with(
        text,
        &[
            ("OUTER", "PROC OUTER\nDEF INT NUM=1\nINNER\nG0 Y=NUM\nRET\n"),
            ("INNER", "PROC INNER\nDEF INT NUM=5\nG0 X=NUM\nRET\n"),
        ],
    );
    assert_points(
        &ends_of(&run, text),
        &[[5.0, 0.0, 0.0], [5.0, 1.0, 0.0], [5.0, 1.0, 9.0]],
        text,
    );
}

#[test]
fn a_reference_passes_down_two_levels() {
    // The main program's VB goes to OUTER as VAR OUTV, which passes it on to INNER as VAR VAL:
    // VAL = 3 -> VB = 3.
    let text = "DEF REAL VB=0\nOUTER(VB)\nG0 X=VB\nM30\n";
    let run = run_with(
        text,
        &[
            ("OUTER", "PROC OUTER(VAR REAL OUTV)\nINNER(OUTV)\nRET\n"),
            ("INNER", "PROC INNER(VAR REAL VAL)\nVAL=3\nRET\n"),
        ],
    );
    assert_points(&ends_of(&run, text), &[[3.0, 0.0, 0.0]], text);
}

#[test]
fn r_parameters_are_global_across_calls() {
    // SUB sets R7 = 4; the caller reads it.
    let text = "SUB\nG0 X=R7\nM30\n";
    let run = run_with(text, &[("SUB", "PROC SUB\nR7=4\nRET\n")]);
    assert_points(&ends_of(&run, text), &[[4.0, 0.0, 0.0]], text);
}

#[test]
fn a_recursive_proc_with_a_value_parameter_counts_down() {
    // DOWN(3): X3, DOWN(2): X2, DOWN(1): X1, DOWN(0) returns.
    let text = "DOWN(3)\nM30\n";
    let run = run_with(
        text,
        &[(
            "DOWN",
            "PROC DOWN(INT KK)\nIF KK>0\nG0 X=KK\nDOWN(KK-1)\nENDIF\nRET\n",
        )],
    );
    assert_points(
        &ends_of(&run, text),
        &[[3.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 0.0, 0.0]],
        text,
    );
}

#[test]
fn without_save_a_subprograms_g91_stays_in_force() {
    // SUB switches to G91 and moves X1 (X3); back in the main program `G0 X5` is incremental:
    // X8.
    let text = "G90 G0 X2\nSUB\nG0 X5\nM30\n";
    let run = run_with(text, &[("SUB", "PROC SUB\nG91 G0 X1\nRET\n")]);
    assert_points(
        &ends_of(&run, text),
        &[[2.0, 0.0, 0.0], [3.0, 0.0, 0.0], [8.0, 0.0, 0.0]],
        text,
    );
}

#[test]
fn save_restores_the_g_functions_at_the_return() {
    // PROC SUB SAVE: G90 comes back at the RET, so `G0 X5` goes to X5.
    let text = "G90 G0 X2\nSUB\nG0 X5\nM30\n";
    let run = run_with(text, &[("SUB", "PROC SUB SAVE\nG91 G0 X1\nRET\n")]);
    assert_points(
        &ends_of(&run, text),
        &[[2.0, 0.0, 0.0], [3.0, 0.0, 0.0], [5.0, 0.0, 0.0]],
        text,
    );
}

#[test]
fn save_restores_the_programmable_frame_at_the_return() {
    // sinumerik-part-b.md (frames, L2042): with SAVE the caller's frame comes back. SUB adds
    // ATRANS X10 and moves to its X0 (X10); after the return `G0 X0` is X0 again.
    let text = "G0 X1\nSUB\nG0 X0 Y1\nM30\n";
    let run = run_with(text, &[("SUB", "PROC SUB SAVE\nATRANS X10\nG0 X0\nRET\n")]);
    assert_points(
        &ends_of(&run, text),
        &[[1.0, 0.0, 0.0], [10.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        text,
    );
}

#[test]
fn mcall_calls_its_subprogram_after_every_block_with_motion() {
    // PGAsl, modal subprogram call: after `MCALL HOLE` each block that moves an axis is followed
    // by HOLE (down Z-5, back Z0); `R1=1` moves nothing and calls nothing; `MCALL` alone ends it.
    let text = "MCALL HOLE\nG0 X10\nR1=1\nG0 X20\nMCALL\nG0 X30\nM30\n";
    let run = run_with(text, &[("HOLE", "G1 Z-5 F100\nG0 Z0\nM17\n")]);
    assert_points(
        &ends_of(&run, text),
        &[
            [10.0, 0.0, 0.0],
            [10.0, 0.0, -5.0],
            [10.0, 0.0, 0.0],
            [20.0, 0.0, 0.0],
            [20.0, 0.0, -5.0],
            [20.0, 0.0, 0.0],
            [30.0, 0.0, 0.0],
        ],
        text,
    );
}

#[test]
fn mcall_passes_its_arguments_each_time() {
    // MCALL DRILL(3): after each move DRILL goes to Z-3 and back.
    let text = "MCALL DRILL(3)\nG0 X10\nG0 X20\nMCALL\nM30\n";
    let run = run_with(
        text,
        &[(
            "DRILL",
            "PROC DRILL(REAL DEPTH)\nG1 Z=-DEPTH F100\nG0 Z0\nRET\n",
        )],
    );
    assert_points(
        &ends_of(&run, text),
        &[
            [10.0, 0.0, 0.0],
            [10.0, 0.0, -3.0],
            [10.0, 0.0, 0.0],
            [20.0, 0.0, 0.0],
            [20.0, 0.0, -3.0],
            [20.0, 0.0, 0.0],
        ],
        text,
    );
}

#[test]
fn a_new_mcall_replaces_the_old_one() {
    // MCALL A then MCALL B: after `G0 X10` only B runs (Y1).
    let text = "MCALL PA\nMCALL PB\nG0 X10\nMCALL\nM30\n";
    let run = run_with(text, &[("PA", "G0 Z-1\nM17\n"), ("PB", "G0 Y1\nM17\n")]);
    assert_points(
        &ends_of(&run, text),
        &[[10.0, 0.0, 0.0], [10.0, 1.0, 0.0]],
        text,
    );
}

// ---------------------------------------------------------------------------------------------
// Frames through blocks (docs/SINUMERIK.md 5.3, G54 = X100 Y50).

#[test]
fn rot_then_trans_keeps_only_the_translation() {
    // Rule 2: TRANS replaces the whole frame, the rotation is gone: (10, 5) + (10, 0) -> X120
    // Y55 from machine zero with G54.
    assert_last("ROT RPL=45\nTRANS X10\nG0 X10 Y5", [120.0, 55.0, 0.0]);
}

#[test]
fn trans_then_arot_turns_about_the_translated_zero() {
    // Rule 3: zero at (10, 20); (10, 0) turned by 90 is (0, 10) -> (10, 30) -> X110 Y80.
    assert_last("TRANS X10 Y20\nAROT RPL=90\nG0 X10 Y0", [110.0, 80.0, 0.0]);
}

#[test]
fn rot_then_atrans_translates_along_the_turned_axes() {
    // Rule 4: ROT 90 turns X onto +Y; ATRANS X10 Y5 in the turned axes is (-5, 10) in the SZS;
    // G0 X0 Y0 -> X95 Y60.
    assert_last("ROT RPL=90\nATRANS X10 Y5\nG0 X0 Y0", [95.0, 60.0, 0.0]);
}

#[test]
fn trans_then_atrans_then_arot_then_atrans_chains_in_order() {
    // T = (10, 0); AROT 90; ATRANS X5 along the turned X (+Y): zero at (10, 5); G0 X1 Y0 ->
    // (1, 0) turned is (0, 1): (10, 6) -> X110 Y56.
    assert_last(
        "TRANS X10\nAROT RPL=90\nATRANS X5\nG0 X1 Y0",
        [110.0, 56.0, 0.0],
    );
}

#[test]
fn two_arots_add_their_angles() {
    // AROT 30 then AROT 60: 90 in all; (10, 0) -> (0, 10) -> X100 Y60.
    assert_last("AROT RPL=30\nAROT RPL=60\nG0 X10 Y0", [100.0, 60.0, 0.0]);
}

#[test]
fn rot_replaces_an_earlier_rot() {
    // ROT 30 then ROT 90: only 90; (10, 0) -> (0, 10).
    assert_last("ROT RPL=30\nROT RPL=90\nG0 X10 Y0", [100.0, 60.0, 0.0]);
}

#[test]
fn mirror_then_arot_turns_the_other_way_seen_from_the_workpiece() {
    // Rule 6: MIRROR X0 / AROT RPL=30 / G0 X10 Y0 -> R30 (-10, 0) = (-8.660, -5.000):
    // X91.340 Y45.
    assert_last("MIRROR X0\nAROT RPL=30\nG0 X10 Y0", [91.340, 45.0, 0.0]);
}

#[test]
fn rot_then_amirror_mirrors_the_turned_axis() {
    // ROT 90 then AMIRROR X0: M flips X before R turns: (10, 0) -> (-10, 0) -> (0, -10):
    // X100 Y40.
    assert_last("ROT RPL=90\nAMIRROR X0\nG0 X10 Y0", [100.0, 40.0, 0.0]);
}

#[test]
fn amirror_twice_switches_the_mirror_off() {
    // AMIRROR X0 toggles X twice: no mirror; X10 -> X110.
    assert_last("AMIRROR X0\nAMIRROR X0\nG0 X10 Y0", [110.0, 50.0, 0.0]);
}

#[test]
fn mirror_about_z_then_atrans_moves_down() {
    // Ex. B-68 form: TRANS Z60 / AMIRROR Z0 / ATRANS Z12: the ATRANS runs along the mirrored
    // Z: zero at Z60 - 12 = 48; G0 Z5 -> 48 - 5 = 43.
    assert_last(
        "TRANS Z60\nAMIRROR Z0\nATRANS Z12\nG0 X0 Y0 Z5",
        [100.0, 50.0, 43.0],
    );
}

#[test]
fn scale_then_atrans_scales_the_translation() {
    // Rule 7: SCALE X3 Y2 / ATRANS X10 Y10 -> zero at (30, 20); G0 X1 Y1 -> (33, 22): X133 Y72.
    assert_last("SCALE X3 Y2\nATRANS X10 Y10\nG0 X1 Y1", [133.0, 72.0, 0.0]);
}

#[test]
fn atrans_then_ascale_leaves_the_translation_unscaled() {
    // ATRANS X10 Y10 / ASCALE X3 Y2: zero stays (10, 10); (1, 1) -> (13, 12): X113 Y62.
    assert_last("ATRANS X10 Y10\nASCALE X3 Y2\nG0 X1 Y1", [113.0, 62.0, 0.0]);
}

#[test]
fn ascale_multiplies_the_factors() {
    // SCALE X2 then ASCALE X1.5: factor 3; X10 -> X30 -> X130.
    assert_last("SCALE X2\nASCALE X1.5\nG0 X10 Y0", [130.0, 50.0, 0.0]);
}

#[test]
fn scale_then_arot_turns_the_scaled_point() {
    // SCALE X2 Y2 / AROT RPL=90: (5, 0) scaled (10, 0), turned (0, 10): X100 Y60.
    assert_last("SCALE X2 Y2\nAROT RPL=90\nG0 X5 Y0", [100.0, 60.0, 0.0]);
}

#[test]
fn rot_about_x_turns_y_onto_z() {
    // ROT X90: Rx(90) (0, 10, 0) = (0, 0, 10): Z10.
    assert_last("ROT X90\nG0 X0 Y10 Z0", [100.0, 50.0, 10.0]);
}

#[test]
fn rot_about_y_turns_z_onto_x() {
    // ROT Y90: Ry(90) (0, 0, 10) = (10, 0, 0): X110.
    assert_last("ROT Y90\nG0 X0 Y0 Z10", [110.0, 50.0, 0.0]);
}

#[test]
fn arot_x_then_arot_z_turn_about_the_turned_axes() {
    // Rule 5: AROT X90 then AROT Z90: R = Rx(90) Rz(90); (10, 0, 0) -> Rz: (0, 10, 0) ->
    // Rx: (0, 0, 10): Z10.
    assert_last("AROT X90\nAROT Z90\nG0 X10 Y0 Z0", [100.0, 50.0, 10.0]);
}

#[test]
fn rpl_turns_about_the_axis_of_the_plane_in_force() {
    // G18: RPL turns about Y, from Z towards X: (X0, Z10) by 90 -> X10 Z0: X110.
    assert_last("G18\nROT RPL=90\nG0 X0 Y0 Z10", [110.0, 50.0, 0.0]);
}

#[test]
fn g58_replaces_the_coarse_part_and_keeps_the_fine_part() {
    // 5.4: TRANS X10 / ATRANS X5 (fine) / G58 X30 -> 30 + 5 = 35: G0 X0 -> X135.
    assert_last(
        "TRANS X10\nATRANS X5\nG58 X30\nG0 X0 Y0",
        [135.0, 50.0, 0.0],
    );
}

#[test]
fn g59_replaces_the_fine_part_and_keeps_the_coarse_part() {
    // TRANS X10 / ATRANS X5 / G59 X2 -> 10 + 2 = 12: X112.
    assert_last("TRANS X10\nATRANS X5\nG59 X2\nG0 X0 Y0", [112.0, 50.0, 0.0]);
}

#[test]
fn g58_keeps_the_rotation_and_translates_along_the_szs_axes() {
    // ROT RPL=90 / G58 X10: T = (10, 0) not turned; G0 X5 Y0 -> (0, 5) + (10, 0): X110 Y55.
    assert_last("ROT RPL=90\nG58 X10\nG0 X5 Y0", [110.0, 55.0, 0.0]);
}

#[test]
fn g55_keeps_the_programmable_rotation() {
    // 5.5: ROT RPL=90 stays over G55 (X200 Y0): (10, 0) -> (0, 10): X200 Y10.
    assert_shop(
        "G54\nROT RPL=90\nG55\nG0 X10 Y0\nM30\n",
        &[[200.0, 10.0, 0.0]],
    );
}

#[test]
fn g500_drops_the_settable_frame_and_keeps_trans() {
    // G54 / TRANS X10 / G500 / G0 X0 Y0 -> X10 Y0.
    assert_last("TRANS X10\nG500\nG0 X0 Y0", [10.0, 0.0, 0.0]);
}

#[test]
fn g53_skips_the_frames_for_one_block() {
    // G54 / TRANS X10: G0 X0 -> X110; G53 G0 X0 -> X0; G0 X0 -> X110 again.
    assert_shop(
        "G54\nTRANS X10\nG0 X0 Y0\nG53 G0 X0\nG0 X0\nM30\n",
        &[[110.0, 50.0, 0.0], [0.0, 50.0, 0.0], [110.0, 50.0, 0.0]],
    );
}

#[test]
fn p_pframe_reads_the_translation_back() {
    // TRANS X10 / ATRANS X5: $P_PFRAME[X,TR] = 15 -> G0 Y=15: Y15 + 50 = Y65.
    assert_last(
        "TRANS X10\nATRANS X5\nR1=$P_PFRAME[X,TR]\nTRANS\nG0 X0 Y=R1",
        [100.0, 65.0, 0.0],
    );
}

// ---------------------------------------------------------------------------------------------
// IC and G91 after a frame change (docs/SINUMERIK.md 6.4).

#[test]
fn ic_after_trans_travels_the_change_too() {
    // Rule 4 with X=IC(..): G0 X10 Y0 (X110) / TRANS X5 / G0 X=IC(1) -> p = 11, X116.
    assert_last("G0 X10 Y0\nTRANS X5\nG0 X=IC(1)", [116.0, 50.0, 0.0]);
}

#[test]
fn g91_after_atrans_with_an_axis_not_programmed() {
    // G0 X10 Y0 / ATRANS Y5 / G91 G0 X1: rule 2: Y is not programmed and keeps its place
    // (Y50); X p = 11: X111.
    assert_last("G0 X10 Y0\nATRANS Y5\nG91 G0 X1", [111.0, 50.0, 0.0]);
}

#[test]
fn ic_after_a_rotation_moves_all_geometry_axes() {
    // Rule 3 and 4: G0 X10 Y0 / ROT RPL=90 / G0 X=IC(5): p = (15, 0) -> (0, 15): X100 Y65.
    assert_last("G0 X10 Y0\nROT RPL=90\nG0 X=IC(5)", [100.0, 65.0, 0.0]);
}

#[test]
fn ic_after_a_scale_scales_the_position_not_only_the_increment() {
    // G0 X10 (X110) / SCALE X2 / G0 X=IC(1): p = 11, scaled 22: X122.
    assert_last("G0 X10 Y0\nSCALE X2\nG0 X=IC(1)", [122.0, 50.0, 0.0]);
}

#[test]
fn an_absolute_move_after_a_mirror() {
    // Rule 6: G0 X10 (X110) / MIRROR X0 / G0 X10 -> X90.
    assert_last("G0 X10 Y0\nMIRROR X0\nG0 X10", [90.0, 50.0, 0.0]);
}

#[test]
fn ac_after_a_frame_change_in_g91() {
    // G91 with X=AC(5) after TRANS X20: the WCS value 5 -> X125.
    assert_last("G0 X10 Y0\nTRANS X20\nG91 G0 X=AC(5)", [125.0, 50.0, 0.0]);
}

#[test]
fn a_settable_frame_change_then_g91_travels_the_difference() {
    // G54 X100 -> G55 X200: G54 G0 X10 (X110) / G55 / G91 G0 X1: p = 11 -> X211.
    assert_shop(
        "G54 G0 X10 Y0\nG55\nG91 G0 X1\nM30\n",
        &[[110.0, 50.0, 0.0], [211.0, 50.0, 0.0]],
    );
}

// ---------------------------------------------------------------------------------------------
// Polar coordinates (6.5).

#[test]
fn g111_sets_the_pole_from_the_wcs_zero() {
    // Pole X10 Y10; AP=90 RP=5 -> (10, 15).
    assert_moves("G111 X10 Y10\nG0 AP=90 RP=5\nM30\n", &[[10.0, 15.0, 0.0]]);
}

#[test]
fn g110_sets_the_pole_from_the_last_point() {
    // From X20 Y0: G110 X5 -> pole (25, 0); AP=180 RP=10 -> (15, 0).
    assert_moves(
        "G0 X20 Y0\nG110 X5 Y0\nG0 AP=180 RP=10\nM30\n",
        &[[20.0, 0.0, 0.0], [15.0, 0.0, 0.0]],
    );
}

#[test]
fn g112_sets_the_pole_from_the_previous_pole() {
    // G111 X10 Y10 then G112 X5: pole (15, 10); AP=0 RP=2 -> (17, 10).
    assert_moves(
        "G111 X10 Y10\nG112 X5 Y0\nG0 AP=0 RP=2\nM30\n",
        &[[17.0, 10.0, 0.0]],
    );
}

#[test]
fn a_pole_given_in_polar_form() {
    // G111 AP=90 RP=10: pole (0, 10) seen from the WCS zero; G0 AP=0 RP=3 -> (3, 10).
    assert_moves("G111 AP=90 RP=10\nG0 AP=0 RP=3\nM30\n", &[[3.0, 10.0, 0.0]]);
}

#[test]
fn ap_under_g91_adds_to_the_last_angle_and_rp_stays() {
    // Ex. B-02 form: pole (0, 0), AP=0 RP=10 -> (10, 0); G91 AP=90 -> 90, RP stays 10 -> (0, 10);
    // AP=IC(90) in G90 -> 180 -> (-10, 0).
    assert_moves(
        "G111 X0 Y0\nG0 AP=0 RP=10\nG91 AP=90\nG90 AP=IC(90)\nM30\n",
        &[[10.0, 0.0, 0.0], [0.0, 10.0, 0.0], [-10.0, 0.0, 0.0]],
    );
}

#[test]
fn without_a_stored_rp_it_is_the_distance_to_the_pole() {
    // From (30, 40) with the pole at the WCS zero: RP = 50; AP=0 -> (50, 0).
    assert_moves(
        "G0 X30 Y40\nG111 X0 Y0\nG0 AP=0\nM30\n",
        &[[30.0, 40.0, 0.0], [50.0, 0.0, 0.0]],
    );
}

#[test]
fn a_polar_block_may_carry_the_third_axis() {
    // Cylinder coordinates: AP=45 RP=sqrt(2)*10 -> (10, 10), Z-3.
    assert_moves(
        "G111 X0 Y0\nG1 AP=45 RP=14.1421356 Z-3 F100\nM30\n",
        &[[10.0, 10.0, -3.0]],
    );
}

#[test]
fn polar_in_g18_measures_the_angle_from_z() {
    // G18: abscissa Z, ordinate X; pole (Z0, X0); AP=90 RP=10 -> X10 Z0; AP=0 -> Z10.
    assert_moves(
        "G18\nG111 Z0 X0\nG0 AP=90 RP=10\nG0 AP=0\nM30\n",
        &[[10.0, 0.0, 0.0], [0.0, 0.0, 10.0]],
    );
}

#[test]
fn polar_end_points_go_through_the_frame() {
    // G54 (X100 Y50): pole (0, 0) of the WCS; AP=90 RP=10 -> WCS (0, 10) -> X100 Y60.
    assert_last("G111 X0 Y0\nG0 AP=90 RP=10", [100.0, 60.0, 0.0]);
}

#[test]
fn a_polar_arc_turns_about_the_pole() {
    // Pole (0, 0); from (10, 0) G3 AP=90: a counter-clockwise quarter about the pole to (0, 10).
    let text = "G0 X10 Y0\nG111 X0 Y0\nG3 AP=90 F100\nM30\n";
    let got = arcs_of(text, &machine());
    assert!(close(got[0].0, [0.0, 10.0, 0.0], 1e-6), "{got:?}");
    assert!(close(got[0].1, [0.0, 0.0, 0.0], 1e-6), "{got:?}");
    assert_eq!(got[0].2, ArcDirection::CounterClockwise);
}

// ---------------------------------------------------------------------------------------------
// Contour definitions: corner points worked out.

/// (0,-10) up to (0,0), along X to (20,0), up to (20,20), with the corner at (20,0) cut back 5
/// along both lines (RND=5, CHR=5 or CHF=5*sqrt(2) at this right angle).
const CUT_CORNER_AT_20_0: [[f64; 3]; 5] = [
    [0.0, -10.0, 0.0],
    [0.0, 0.0, 0.0],
    [15.0, 0.0, 0.0],
    [20.0, 5.0, 0.0],
    [20.0, 20.0, 0.0],
];

#[test]
fn rnd_between_two_lines_at_a_right_angle() {
    // (0,0) -> (20,0) RND=5 -> (20,20): the rounding touches each line 5 from the corner
    // (tan 45 * 5): line to (15, 0), arc about (15, 5) to (20, 5), line to (20, 20).
    let text = "G0 X0 Y-10\nG1 Y0 F100\nX20 RND=5\nY20\nM30\n";
    let run = run_on(text, &machine());
    let got = ends_of(&run, text);
    assert_points(&got, &CUT_CORNER_AT_20_0, text);
    let a = arcs(&run.segments);
    assert!(close(a[0].1, [15.0, 5.0, 0.0], 1e-6), "{a:?}");
    assert_eq!(a[0].2, ArcDirection::CounterClockwise);
}

#[test]
fn chf_cuts_the_corner_with_a_chamfer_of_that_length() {
    // CHF=5*sqrt(2) = 7.0711 at a right angle: the legs are 5: (15, 0) then (20, 5).
    assert_moves(
        "G0 X0 Y-10\nG1 Y0 F100\nX20 CHF=7.0710678\nY20\nM30\n",
        &CUT_CORNER_AT_20_0,
    );
}

#[test]
fn chr_gives_the_leg_length() {
    // CHR=5: legs of 5 along each line: (15, 0) then (20, 5).
    assert_moves(
        "G0 X0 Y-10\nG1 Y0 F100\nX20 CHR=5\nY20\nM30\n",
        &CUT_CORNER_AT_20_0,
    );
}

#[test]
fn chr_at_an_obtuse_corner() {
    // (0,0) -> (20,0) then to (30,10): the path turns 45 degrees. CHR=4 cuts 4 back along
    // each line: ends (16, 0) and (20 + 4 cos 45, 4 sin 45) = (22.8284, 2.8284).
    assert_moves(
        "G0 X0 Y-10\nG1 Y0 F100\nX20 CHR=4\nX30 Y10\nM30\n",
        &[
            [0.0, -10.0, 0.0],
            [0.0, 0.0, 0.0],
            [16.0, 0.0, 0.0],
            [22.828427, 2.828427, 0.0],
            [30.0, 10.0, 0.0],
        ],
    );
}

#[test]
fn rndm_rounds_every_corner_until_rndm_0() {
    // A square (0,0) (20,0) (20,20) (0,20): RNDM=2 from the block ending at (20,0), RNDM=0 in
    // the block ending at (0,20): roundings at (20,0) and (20,20) only: line to (18, 0), arc
    // to (20, 2), line to (20, 18), arc to (18, 20), line to (0, 20), then (0, 0) sharp.
    assert_moves(
        "G0 X0 Y-10\nG1 Y0 F100\nX20 RNDM=2\nY20\nX0 RNDM=0\nY0\nM30\n",
        &[
            [0.0, -10.0, 0.0],
            [0.0, 0.0, 0.0],
            [18.0, 0.0, 0.0],
            [20.0, 2.0, 0.0],
            [20.0, 18.0, 0.0],
            [18.0, 20.0, 0.0],
            [0.0, 20.0, 0.0],
            [0.0, 0.0, 0.0],
        ],
    );
}

#[test]
fn rnd_between_a_line_and_an_arc() {
    // Line (0,0) -> (20,0) with RND=2, then G2 to (30,10) about (30,0) (radius 10), which
    // leaves (20,0) going +Y: the path turns left 90 degrees. The rounding (radius 2) is on the
    // left of both: 2 above the line (y = 2) and outside the arc's circle (the arc's centre is
    // on its right), 10 + 2 = 12 from (30,0): x = 30 - sqrt(144 - 4) = 18.168. It touches the
    // line at (18.168, 0) and the arc where the line from (30,0) to its centre crosses the
    // circle: (30,0) + 10/12 (x - 30, 2) = (20.140, 1.667).
    let text = "G0 X0 Y-10\nG1 Y0 F100\nX20 RND=2\nG2 X30 Y10 I10 J0\nM30\n";
    let run = run_on(text, &machine());
    let got = ends_of(&run, text);
    let x = 30.0 - (144.0f64 - 4.0).sqrt();
    assert_points(
        &got,
        &[
            [0.0, -10.0, 0.0],
            [0.0, 0.0, 0.0],
            [x, 0.0, 0.0],
            [30.0 + 10.0 / 12.0 * (x - 30.0), 10.0 / 12.0 * 2.0, 0.0],
            [30.0, 10.0, 0.0],
        ],
        text,
    );
}

#[test]
fn ang_with_one_coordinate_fixes_the_end_on_the_line() {
    // From (0,0) at ANG=30 to X=17.3205: Y = 17.3205 tan 30 = 10.
    assert_moves(
        "G1 X17.320508 ANG=30 F100\nM30\n",
        &[[17.320508, 10.0, 0.0]],
    );
}

#[test]
fn ang_with_the_ordinate_written() {
    // From (0,0) at ANG=45 to Y=10: X = 10.
    assert_moves("G1 Y10 ANG=45 F100\nM30\n", &[[10.0, 10.0, 0.0]]);
}

#[test]
fn two_angle_lines_meet_at_their_intersection() {
    // From (0,0): ANG=0 (no end), then X20 Y10 ANG=90: the second line is X = 20 going up to
    // (20,10); the first line along X meets it at (20, 0).
    assert_moves(
        "G1 ANG=0 F100\nX20 Y10 ANG=90\nM30\n",
        &[[20.0, 0.0, 0.0], [20.0, 10.0, 0.0]],
    );
}

#[test]
fn two_angle_lines_at_45_and_135() {
    // From (0,0): ANG=45, then X20 Y0 ANG=-45 (the second line runs to (20,0) at -45):
    // intersection of y = x and y = 20 - x: (10, 10).
    assert_moves(
        "G1 ANG=45 F100\nX20 Y0 ANG=-45\nM30\n",
        &[[10.0, 10.0, 0.0], [20.0, 0.0, 0.0]],
    );
}

#[test]
fn two_angle_lines_with_a_rounding_at_their_corner() {
    // As above, with RND=2 at the end of the first line: the lines turn by 90 degrees, so the
    // tangent points are 2 tan 45 = 2 from (10,10) along each: (10 - 1.4142, 10 - 1.4142) and
    // (10 + 1.4142, 10 - 1.4142).
    let d = 2.0 / 2f64.sqrt();
    assert_moves(
        "G1 ANG=45 RND=2 F100\nX20 Y0 ANG=-45\nM30\n",
        &[
            [10.0 - d, 10.0 - d, 0.0],
            [10.0 + d, 10.0 - d, 0.0],
            [20.0, 0.0, 0.0],
        ],
    );
}

// ---------------------------------------------------------------------------------------------
// Arcs: CR, AR, CT, TURN, CIP.

#[test]
fn ar_gives_the_opening_angle_with_the_end_point() {
    // From (0,0) to (20,0) with AR=180: half circle about (10, 0).
    let text = "G0 X0 Y0\nG2 X20 Y0 AR=180 F100\nM30\n";
    let a = arcs_of(text, &machine());
    assert!(close(a[0].1, [10.0, 0.0, 0.0], 1e-6), "{a:?}");
}

#[test]
fn ar_with_the_centre_gives_the_end_point() {
    // From (10,0) about (0,0): I-10 J0 AR=90 counter-clockwise -> (0, 10).
    let text = "G0 X10 Y0\nG3 I-10 J0 AR=90 F100\nM30\n";
    let a = arcs_of(text, &machine());
    assert!(close(a[0].0, [0.0, 10.0, 0.0], 1e-6), "{a:?}");
}

#[test]
fn ar_of_90_with_the_end_puts_the_centre_at_the_square_corner() {
    // From (0,0) to (10,10), G2 AR=90: chord 14.142, radius 10; clockwise the centre is on
    // the right of the way: (10, 0).
    let text = "G0 X0 Y0\nG2 X10 Y10 AR=90 F100\nM30\n";
    let a = arcs_of(text, &machine());
    assert!(close(a[0].1, [10.0, 0.0, 0.0], 1e-6), "{a:?}");
}

#[test]
fn cr_arc_with_a_frame_translation() {
    // G54 + TRANS X10: G2 from WCS (0,0) to (20,0) CR=10 -> centre WCS (10,0) -> X120 Y50.
    let text = "G54\nTRANS X10\nG0 X0 Y0\nG2 X20 Y0 CR=10 F100\nM30\n";
    let a = arcs_of(text, &shop());
    assert!(close(a[0].1, [120.0, 50.0, 0.0], 1e-6), "{a:?}");
    assert!(close(a[0].0, [130.0, 50.0, 0.0], 1e-6), "{a:?}");
}

#[test]
fn ct_continues_tangentially_from_a_line() {
    // Line (0,0) -> (10,0) along +X; CT to (20,10): the circle tangent to +X at (10,0)
    // through (20,10) has its centre at (10, r) with (20-10)^2 + (10-r)^2 = r^2: r = 10;
    // centre (10, 10), counter-clockwise.
    let text = "G1 X0 Y0 F100\nX10\nCT X20 Y10\nM30\n";
    let a = arcs_of(text, &machine());
    assert!(close(a[0].1, [10.0, 10.0, 0.0], 1e-6), "{a:?}");
    assert_eq!(a[0].2, ArcDirection::CounterClockwise);
}

#[test]
fn cip_goes_through_its_intermediate_point() {
    // From (0,0) through (10,10) to (20,0): the circle about (10,0), radius 10, clockwise.
    let text = "G0 X0 Y0\nCIP X20 Y0 I1=10 J1=10 F100\nM30\n";
    let a = arcs_of(text, &machine());
    assert!(close(a[0].1, [10.0, 0.0, 0.0], 1e-6), "{a:?}");
    assert_eq!(a[0].2, ArcDirection::Clockwise);
}

#[test]
fn turn_adds_full_circles_to_a_helix() {
    // G3 from (10,0) to (0,10) about (0,0), Z-6, TURN=2: two extra full turns; end (0,10,-6).
    let text = "G0 X10 Y0 Z0\nG3 X0 Y10 Z-6 I-10 J0 TURN=2 F100\nM30\n";
    let a = arcs_of(text, &machine());
    assert!(close(a[0].0, [0.0, 10.0, -6.0], 1e-6), "{a:?}");
    assert_eq!(a[0].3, 2);
}

#[test]
fn a_modal_g2_with_cr_keeps_turning_the_same_way() {
    // G2 is modal: the second block `X0 Y0 CR=10` is a clockwise arc back (chord 20: centre
    // (10, 0) again).
    let text = "G0 X0 Y0\nG2 X20 Y0 CR=10 F100\nX0 Y0 CR=10\nM30\n";
    let a = arcs_of(text, &machine());
    assert_eq!(a.len(), 2);
    assert_eq!(a[1].2, ArcDirection::Clockwise);
    assert!(close(a[1].1, [10.0, 0.0, 0.0], 1e-6), "{a:?}");
}

// ---------------------------------------------------------------------------------------------
// Tools.

#[test]
fn t_by_name_selects_the_tool_and_d2_its_second_edge() {
    // T="MILL10" M6 D2: length 50: G0 Z0 -> Z50.
    assert_shop(
        "T=\"MILL10\" M6 D2\nG0 X0 Y0 Z0\nM30\n",
        &[[0.0, 0.0, 50.0]],
    );
}

#[test]
fn a_second_tool_by_name_brings_its_own_length() {
    // MILL10 D1 (100) then DRILL8 D1 (80): Z0 -> Z100, then Z0 -> Z80.
    assert_shop(
        "T=\"MILL10\" M6 D1\nG0 Z0\nT=\"DRILL8\" M6 D1\nG0 Z0\nM30\n",
        &[[0.0, 0.0, 100.0], [0.0, 0.0, 80.0]],
    );
}

#[test]
fn toffl_adds_to_the_length_along_the_planes_third_axis() {
    // PGsl 5.8: L1 = 100 + TOFFL 1 in G17 acts on Z: Z101; in G18 L1 acts on Y: Y101.
    assert_shop(
        "T1 M6 D1\nTOFFL=1\nG0 X0 Y0 Z0\nG18 G0 X0 Y0 Z0\nM30\n",
        &[[0.0, 0.0, 101.0], [0.0, 101.0, 0.0]],
    );
}

#[test]
fn toff_stays_on_its_axis_through_a_plane_change() {
    // Ex. A-18: TOFF[Z]=1: G17 Z101; G18: L1 on Y (Y100) and the TOFF still on Z (Z1).
    assert_shop(
        "T1 M6 D1\nTOFF[Z]=1\nG0 X0 Y0 Z0\nG18 G0 X0 Y0 Z0\nM30\n",
        &[[0.0, 0.0, 101.0], [0.0, 100.0, 1.0]],
    );
}

#[test]
fn d0_switches_the_length_off() {
    // D1 then D0: Z0 -> Z100 then Z0.
    assert_shop(
        "T1 M6 D1\nG0 Z0\nD0\nG0 Z0\nM30\n",
        &[[0.0, 0.0, 100.0], [0.0, 0.0, 0.0]],
    );
}

#[test]
fn p_toolno_reads_the_tool_in_the_spindle() {
    // T2 M6: $P_TOOLNO = 2: G0 X=$P_TOOLNO*10 -> X20 (with DRILL8's length 80 on Z0? Z not
    // programmed: Z stays 0).
    assert_shop("T2 M6 D0\nG0 X=$P_TOOLNO*10\nM30\n", &[[20.0, 0.0, 0.0]]);
}

// ---------------------------------------------------------------------------------------------
// Spindle.

#[test]
fn svc_gives_the_speed_at_the_tools_radius() {
    // PGsl 6.2: S = SVC * 1000 / (2 pi r): MILL10 radius 5, SVC=100 -> 3183.099 rpm.
    let run = run_on("T1 M6 D1\nSVC=100 M3\nM30\n", &shop());
    assert!(run.error().is_none(), "{:?}", run.alarms);
    let s = speeds(&run.segments);
    let wanted = 100.0 * 1000.0 / (2.0 * PI * 5.0);
    assert!((s.last().unwrap() - wanted).abs() < 1e-6, "{s:?}");
}

#[test]
fn svc_follows_a_change_of_tool() {
    // SVC=100 with MILL10 (r5, 3183.1) then DRILL8 D1 (r4): 100000 / (8 pi) = 3978.87 rpm.
    let run = run_on("T1 M6 D1\nSVC=100 M3\nT2 M6 D1\nM30\n", &shop());
    assert!(run.error().is_none(), "{:?}", run.alarms);
    let s = speeds(&run.segments);
    let wanted = 100.0 * 1000.0 / (2.0 * PI * 4.0);
    assert!((s.last().unwrap() - wanted).abs() < 1e-6, "{s:?}");
}

#[test]
fn g96_follows_x_and_lims_caps_it() {
    // G96 S100 (m/min) with LIMS=2000: at X=10 the speed would be 100000/(20 pi) = 1591.55;
    // at X=5 it would be 3183.1, capped at 2000.
    let run = run_on(
        "G0 X10\nG96 S100 LIMS=2000 M3\nG1 X5 F100\nM30\n",
        &machine(),
    );
    assert!(run.error().is_none(), "{:?}", run.alarms);
    let s = speeds(&run.segments);
    assert!(
        s.iter().any(|v| (v - 100000.0 / (20.0 * PI)).abs() < 1e-3),
        "{s:?}"
    );
    assert!((s.last().unwrap() - 2000.0).abs() < 1e-9, "{s:?}");
}

#[test]
fn g26_caps_and_g25_raises_the_programmed_speed() {
    // G26 S3000: S5000 runs at 3000; G25 S500: S100 runs at 500.
    let run = run_on("G26 S3000\nS5000 M3\nG25 S500\nS100\nM30\n", &machine());
    assert!(run.error().is_none(), "{:?}", run.alarms);
    let s = speeds(&run.segments);
    assert_eq!(s, [3000.0, 500.0]);
}

#[test]
fn m5_stops_the_spindle_and_keeps_the_speed_for_m3() {
    let run = run_on("S1200 M3\nM5\nM3\nM30\n", &machine());
    let states: Vec<_> = run
        .segments
        .iter()
        .filter_map(|s| match s.kind {
            SegmentKind::Spindle { state, speed } => Some((state, speed)),
            _ => None,
        })
        .collect();
    assert_eq!(states.first(), Some(&(SpindleState::Clockwise, 1200.0)));
    assert_eq!(states.last(), Some(&(SpindleState::Clockwise, 1200.0)));
    assert!(states.iter().any(|(s, _)| *s == SpindleState::Stopped));
}

// ---------------------------------------------------------------------------------------------
// System variables.

#[test]
fn aa_iw_reads_the_work_position_after_the_previous_move() {
    // G54 (X100): G0 X12 Y3; $AA_IW[X] = 12 (WCS, not 112): G0 Y=$AA_IW[X] -> Y12 -> Y62.
    assert_last("G0 X12 Y3\nG0 Y=$AA_IW[X]", [112.0, 62.0, 0.0]);
}

#[test]
fn aa_im_reads_the_machine_position() {
    // G54 (X100): G0 X12: $AA_IM[X] = 112: G0 Y=$AA_IM[X]-100 -> WCS Y12 -> Y62.
    assert_last("G0 X12 Y3\nG0 Y=$AA_IM[X]-100", [112.0, 62.0, 0.0]);
}

#[test]
fn p_gg_reads_the_active_member_of_a_group() {
    // The tables' member numbers: $P_GG[1] under G1 is 2 (G0 1, G1 2, G2 3 ...); $P_GG[6]
    // under G18 is 2 (G17 1); $P_GG[14] under G91 is 2 (G90 1): X2 Y2 Z2.
    assert_moves(
        "G1 F100 X1\nG18\nR1=$P_GG[1]\nR2=$P_GG[6]\nG91\nR3=$P_GG[14]\nG90 G0 X=R1 Y=R2 Z=R3\nM30\n",
        &[[1.0, 0.0, 0.0], [2.0, 2.0, 2.0]],
    );
}

// ---------------------------------------------------------------------------------------------
// More of each: functions, strings, polar after a frame, CR > 180 degrees, $P_GG of group 8.

#[test]
fn rounding_and_min_max_functions() {
    // ROUND(2.5) = 3; ROUNDUP(2.1) = 3; MINVAL(4,7) + MAXVAL(4,7) = 4 + 7 = 11.
    assert_moves(
        "G0 X=ROUND(2.5) Y=ROUNDUP(2.1) Z=MINVAL(4,7)+MAXVAL(4,7)\nM30\n",
        &[[3.0, 3.0, 11.0]],
    );
}

#[test]
fn strings_compare_in_a_condition() {
    // "AB" << "C" == "ABC" is true (X1); "AB" == "ab" is false (case counts).
    let text = "DEF STRING[8] TXT=\"AB\"\nIF TXT<<\"C\"==\"ABC\"\nG0 X1\nENDIF\n\
                IF TXT==\"ab\"\nG0 X9\nENDIF\nM30\n";
    assert_eq!(xs(text), [1.0]);
}

#[test]
fn a_pole_keeps_its_numbers_when_the_frame_changes() {
    // 6.5 (choice): G111 X10 Y0 is stored as WCS numbers; after TRANS X5 the pole is WCS
    // (10, 0) of the new frame: AP=0 RP=5 -> WCS (15, 0) -> + TRANS 5 + G54 (100, 50): X120 Y50.
    assert_last("G111 X10 Y0\nTRANS X5\nG0 AP=0 RP=5", [120.0, 50.0, 0.0]);
}

#[test]
fn rp_ic_adds_to_the_stored_radius() {
    // Pole (0,0); AP=0 RP=10 -> (10, 0); RP=IC(5) -> RP 15 at AP 0 -> (15, 0).
    assert_moves(
        "G111 X0 Y0\nG0 AP=0 RP=10\nRP=IC(5)\nM30\n",
        &[[10.0, 0.0, 0.0], [15.0, 0.0, 0.0]],
    );
}

#[test]
fn a_negative_cr_with_g3_takes_the_long_way() {
    // G3 from (0,0) to (10,0) with CR=-10: more than 180 degrees, so the centre is on the
    // right of the way (G3 with CR < 0, part-b 1.6.3): y = -sqrt(100 - 25) = -8.660.
    let a = arcs_of("G0 X0 Y0\nG3 X10 Y0 CR=-10 F100\nM30\n", &machine());
    assert!(close(a[0].1, [5.0, -8.660254, 0.0], 1e-6), "{a:?}");
    assert_eq!(a[0].2, ArcDirection::CounterClockwise);
}

#[test]
fn p_gg_of_group_8_counts_the_settable_frames() {
    // $P_GG[8]: G500 is 1, G54 is 2, G55 is 3: X=2 then X=3 (no offsets on the plain machine).
    assert_moves(
        "G54\nR1=$P_GG[8]\nG55\nR2=$P_GG[8]\nG0 X=R1 Y=R2\nM30\n",
        &[[2.0, 3.0, 0.0]],
    );
}

#[test]
fn mcall_is_not_called_by_the_blocks_of_its_own_subprogram() {
    // The moves of HOLE do not call HOLE again (no nesting of the modal call): one pass per
    // move of the main program: X10, Z-1, Z0, X20, Z-1, Z0.
    let text = "MCALL HOLE\nG0 X10\nX20\nMCALL\nM30\n";
    let run = run_with(text, &[("HOLE", "G91 G0 Z-1\nZ1\nG90\nM17\n")]);
    assert_points(
        &ends_of(&run, text),
        &[
            [10.0, 0.0, 0.0],
            [10.0, 0.0, -1.0],
            [10.0, 0.0, 0.0],
            [20.0, 0.0, 0.0],
            [20.0, 0.0, -1.0],
            [20.0, 0.0, 0.0],
        ],
        text,
    );
}

#[test]
fn atrans_after_a_mirror_runs_along_the_mirrored_axis() {
    // 5.3 rule 1 with M: MIRROR X0 / ATRANS X10: Tf = M (10, 0) = (-10, 0); G0 X0 Y0 -> X90.
    assert_last("MIRROR X0\nATRANS X10\nG0 X0 Y0", [90.0, 50.0, 0.0]);
}

#[test]
fn a_jump_out_of_a_for_loop_leaves_it_and_a_second_loop_runs() {
    // PGAsl: a jump may leave a control structure. II = 1, 2 then out; then II = 7, 8.
    let text = "DEF INT II\nFOR II=1 TO 5\nG0 X=II\nIF II==2 GOTOF OUT\nENDFOR\n\
                OUT: FOR II=7 TO 8\nG0 X=II\nENDFOR\nM30\n";
    assert_eq!(xs(text), [1.0, 2.0, 7.0, 8.0]);
}

#[test]
fn leaving_a_while_by_a_jump_fifty_times_leaves_nothing_open() {
    // Each pass enters the WHILE and jumps out of it; the abandoned structures must not count
    // against the nesting limit: 50 passes, then X50.
    let text = "R1=0\nTOP: WHILE 1\nR1=R1+1\nGOTOF OUT\nENDWHILE\nOUT: IF R1<50 GOTOB TOP\n\
                G0 X=R1\nM30\n";
    assert_eq!(xs(text), [50.0]);
}

#[test]
fn ret_from_inside_a_loop_of_a_subprogram() {
    // SUB returns from inside its FOR at KK = 2 (X1, X2); the caller's FOR goes on: SUB runs
    // for JJ = 1, 2: X1, X2, X1, X2, then Y5.
    let text = "DEF INT JJ\nFOR JJ=1 TO 2\nSUB\nENDFOR\nG0 Y5\nM30\n";
    let run = run_with(
        text,
        &[(
            "SUB",
            "PROC SUB\nDEF INT KK\nFOR KK=1 TO 5\nG0 X=KK\nIF KK==2\nRET\nENDIF\nENDFOR\nRET\n",
        )],
    );
    let got: Vec<f64> = ends_of(&run, text).iter().map(|p| p[0]).collect();
    assert_eq!(got, [1.0, 2.0, 1.0, 2.0, 2.0]);
}

#[test]
fn a_subprogram_defines_its_locals_again_on_each_call() {
    // DEF INT NUM=3 in SUB on each of two calls: no "defined twice"; X3 then (G91) X6.
    let text = "G91\nSUB\nSUB\nM30\n";
    let run = run_with(text, &[("SUB", "PROC SUB\nDEF INT NUM=3\nG0 X=NUM\nRET\n")]);
    assert_points(
        &ends_of(&run, text),
        &[[3.0, 0.0, 0.0], [6.0, 0.0, 0.0]],
        text,
    );
}

#[test]
fn case_without_a_match_or_default_goes_on_after_it() {
    // R1 = 5 matches no branch and there is no DEFAULT: the next block runs (X7).
    assert_eq!(
        xs("R1=5\nCASE(R1) OF 1 GOTOF ONE\nG0 X7\nONE: G0 X8\nM30\n"),
        [7.0, 8.0]
    );
}

#[test]
fn rpl_in_g19_turns_about_x_from_y_towards_z() {
    // G19: RPL turns about X, from Y towards Z: (Y10) by 90 -> Z10.
    assert_last("G19\nROT RPL=90\nG0 X0 Y10 Z0", [100.0, 50.0, 10.0]);
}

#[test]
fn constants_in_hex_binary_and_ex_notation() {
    // 'H10' = 16; 'B101' = 5; 1.5EX2 = 150.
    assert_moves("G0 X='H10' Y='B101' Z=1.5EX2\nM30\n", &[[16.0, 5.0, 150.0]]);
}

#[test]
fn an_r_parameter_indexed_by_an_expression() {
    // R1 = 3: R[R1+1] is R4 = 8.
    assert_moves("R1=3\nR[R1+1]=8\nG0 X=R4\nM30\n", &[[8.0, 0.0, 0.0]]);
}

#[test]
fn a_two_dimensional_array_is_indexed_row_then_column() {
    // TAB[1,2] = 5, TAB[0,1] = 2: X = 5 + 2 = 7; an unset element is 0: Y = TAB[1,0] = 0 -> Y0.
    assert_moves(
        "DEF REAL TAB[2,3]\nTAB[1,2]=5\nTAB[0,1]=2\nG0 X=TAB[1,2]+TAB[0,1] Y=TAB[1,0]+1\nM30\n",
        &[[7.0, 1.0, 0.0]],
    );
}

#[test]
fn after_g53_an_increment_starts_where_the_tool_stands() {
    // 6.4 rule 7: G54 (X100): G0 X10 -> X110; G53 G0 X0 -> X0; G91 G0 X1: p = -100 + 1 =
    // -99 in the WCS -> machine X1.
    assert_shop(
        "G54 G0 X10 Y0\nG53 G0 X0\nG91 G0 X1\nM30\n",
        &[[110.0, 50.0, 0.0], [0.0, 50.0, 0.0], [1.0, 50.0, 0.0]],
    );
}

#[test]
fn a_length_change_then_g91_travels_the_change_too() {
    // 6.4 rule 4 for the tool (SD42442 = 1): T1 D1 (L 100); G0 Z0 -> Z100; D2 (L 50);
    // G91 G0 Z1: p = 1 -> Z51.
    assert_shop(
        "T1 M6 D1\nG0 Z0\nD2\nG91 G0 Z1\nM30\n",
        &[[0.0, 0.0, 100.0], [0.0, 0.0, 51.0]],
    );
}

#[test]
fn a_rounding_under_a_rotation_is_turned_with_the_contour() {
    // ROT RPL=90: the WCS corners of the RND=5 test, (x, y) -> (-y, x): (0,-10) -> (10,0),
    // (0,0), (15,0) -> (0,15), (20,5) -> (-5,20), (20,20) -> (-20,20); plus G54 (100, 50).
    let text = "G0 X0 Y-10\nG1 Y0 F100\nX20 RND=5\nY20";
    let program = format!("G54\nROT RPL=90\n{text}\nM30\n");
    let got = ends_of(&run_on(&program, &shop()), &program);
    let wanted: Vec<[f64; 3]> = CUT_CORNER_AT_20_0
        .iter()
        .map(|p| [100.0 - p[1], 50.0 + p[0], 0.0])
        .collect();
    assert_points(&got, &wanted, &program);
}

#[test]
fn atrans_in_inches_is_converted_and_scale_is_not() {
    // 6.2: G70 converts TRANS/ATRANS values; scale factors never: ATRANS X1 (25.4 mm),
    // ASCALE X2: G0 X1 -> 25.4 + 2 * 25.4 = 76.2 mm.
    assert_moves(
        "G70\nATRANS X1\nASCALE X2\nG0 X1\nM30\n",
        &[[76.2, 0.0, 0.0]],
    );
}

#[test]
fn g110_after_a_polar_move_takes_its_end_as_the_last_point() {
    // Pole (0,0); AP=90 RP=10 -> (0,10); G110 X0 Y0: the pole is that end point; AP=0 RP=5
    // -> (5, 10).
    assert_moves(
        "G111 X0 Y0\nG0 AP=90 RP=10\nG110 X0 Y0\nG0 AP=0 RP=5\nM30\n",
        &[[0.0, 10.0, 0.0], [5.0, 10.0, 0.0]],
    );
}

#[test]
fn a_uniform_scale_scales_the_radius_of_a_cr_arc() {
    // 6.3: SCALE X2 Y2, G2 from (0,0) to (20,0) CR=10: machine chord 40, radius 20, centre
    // (20, 0) of the WCS scaled -> machine X120 Y50 with G54.
    let text = "G54\nSCALE X2 Y2\nG0 X0 Y0\nG2 X20 Y0 CR=10 F100\nM30\n";
    let a = arcs_of(text, &shop());
    assert!(close(a[0].0, [140.0, 50.0, 0.0], 1e-6), "{a:?}");
    assert!(close(a[0].1, [120.0, 50.0, 0.0], 1e-6), "{a:?}");
}

#[test]
fn a_negative_scale_factor_mirrors_the_axis() {
    // 5.3 rule 7 (choice): SCALE X-2: X5 -> -10 -> X90 with G54.
    assert_last("SCALE X-2\nG0 X5 Y0", [90.0, 50.0, 0.0]);
}

#[test]
fn trans_gives_zero_to_the_axes_it_does_not_name() {
    // Rule 1: TRANS X10 Y10 then TRANS X5: Y's translation is 0 again: X105 Y50.
    assert_last("TRANS X10 Y10\nTRANS X5\nG0 X0 Y0", [105.0, 50.0, 0.0]);
}

#[test]
fn a_frame_block_under_mcall_calls_nothing() {
    // Only blocks with motion call the modal subprogram: TRANS X5 moves nothing; the next
    // move (X0 + 5) calls it once: X5, then Z-1 and back.
    let text = "MCALL HOLE\nTRANS X5\nG0 X0\nMCALL\nM30\n";
    let run = run_with(text, &[("HOLE", "G91 G0 Z-1\nZ1\nG90\nM17\n")]);
    assert_points(
        &ends_of(&run, text),
        &[[5.0, 0.0, 0.0], [5.0, 0.0, -1.0], [5.0, 0.0, 0.0]],
        text,
    );
}

#[test]
fn a_helix_clockwise_with_turn_ends_below() {
    // G2 from (10,0) about (0,0) to (0,-10): a clockwise quarter, Z-4, TURN=1: one extra turn.
    let a = arcs_of(
        "G0 X10 Y0 Z0\nG2 X0 Y-10 Z-4 I-10 J0 TURN=1 F100\nM30\n",
        &machine(),
    );
    assert!(close(a[0].0, [0.0, -10.0, -4.0], 1e-6), "{a:?}");
    assert_eq!((a[0].2, a[0].3), (ArcDirection::Clockwise, 1));
}

// ---------------------------------------------------------------------------------------------
// The frame property (docs/SINUMERIK.md 5.3): a random sequence of frame blocks, then a G0 to
// a random point, lands where the components T + Tf + R S M p computed here put it. The
// blocks: TRANS/ATRANS, ROT/AROT RPL, SCALE/ASCALE, MIRROR/AMIRROR and G58/G59 (5.3, 5.4).

/// One frame instruction as the test writes it and applies it.
#[derive(Clone, Debug)]
enum FrameBlock {
    Trans([f64; 3]),
    Atrans([f64; 3]),
    Rot(f64),
    Arot(f64),
    Scale([f64; 3]),
    Ascale([f64; 3]),
    Mirror([bool; 3]),
    Amirror([bool; 3]),
    /// G58 / G59 (840D, 5.4): replace the coarse / fine translation, along the SZS axes.
    Coarse([f64; 3]),
    Fine([f64; 3]),
}

/// A value with three decimals, as written in the program text (so the model uses the same).
fn milli(range: std::ops::Range<f64>) -> impl Strategy<Value = f64> {
    range.prop_map(|v| (v * 1000.0).round() / 1000.0)
}

fn frame_block() -> impl Strategy<Value = FrameBlock> {
    let vector = || [milli(-50.0..50.0), milli(-50.0..50.0), milli(-50.0..50.0)];
    let factors = || [milli(0.5..2.0), milli(0.5..2.0), milli(0.5..2.0)];
    let flags = || {
        [any::<bool>(), any::<bool>(), any::<bool>()]
            .prop_filter("at least one axis", |f| f.iter().any(|b| *b))
    };
    prop_oneof![
        vector().prop_map(FrameBlock::Trans),
        vector().prop_map(FrameBlock::Atrans),
        milli(-180.0..180.0).prop_map(FrameBlock::Rot),
        milli(-180.0..180.0).prop_map(FrameBlock::Arot),
        factors().prop_map(FrameBlock::Scale),
        factors().prop_map(FrameBlock::Ascale),
        flags().prop_map(FrameBlock::Mirror),
        flags().prop_map(FrameBlock::Amirror),
        vector().prop_map(FrameBlock::Coarse),
        vector().prop_map(FrameBlock::Fine),
    ]
}

impl FrameBlock {
    fn text(&self) -> String {
        let values =
            |word: &str, v: &[f64; 3]| format!("{word} X{:.3} Y{:.3} Z{:.3}", v[0], v[1], v[2]);
        let axes = |word: &str, f: &[bool; 3]| {
            let mut text = word.to_string();
            for (flag, axis) in f.iter().zip(["X", "Y", "Z"]) {
                if *flag {
                    text.push_str(&format!(" {axis}0"));
                }
            }
            text
        };
        match self {
            FrameBlock::Trans(v) => values("TRANS", v),
            FrameBlock::Atrans(v) => values("ATRANS", v),
            FrameBlock::Rot(a) => format!("ROT RPL={a:.3}"),
            FrameBlock::Arot(a) => format!("AROT RPL={a:.3}"),
            FrameBlock::Scale(v) => values("SCALE", v),
            FrameBlock::Ascale(v) => values("ASCALE", v),
            FrameBlock::Mirror(f) => axes("MIRROR", f),
            FrameBlock::Amirror(f) => axes("AMIRROR", f),
            FrameBlock::Coarse(v) => values("G58", v),
            FrameBlock::Fine(v) => values("G59", v),
        }
    }
}

type M4 = [[f64; 4]; 4];

fn identity() -> M4 {
    let mut m = [[0.0; 4]; 4];
    for (i, row) in m.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    m
}

fn product(a: &M4, b: &M4) -> M4 {
    let mut m = [[0.0; 4]; 4];
    for (i, row) in m.iter_mut().enumerate() {
        for (j, cell) in row.iter_mut().enumerate() {
            *cell = (0..4).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    m
}

fn diagonal(d: [f64; 3]) -> M4 {
    let mut m = identity();
    for i in 0..3 {
        m[i][i] = d[i];
    }
    m
}

/// Rz(a): G17's RPL, counter-clockwise positive seen from +Z.
fn rotation_z(degrees: f64) -> M4 {
    let (s, c) = degrees.to_radians().sin_cos();
    let mut m = identity();
    m[0][0] = c;
    m[0][1] = -s;
    m[1][0] = s;
    m[1][1] = c;
    m
}

fn translation(t: [f64; 3]) -> M4 {
    let mut m = identity();
    for i in 0..3 {
        m[i][3] = t[i];
    }
    m
}

fn apply(m: &M4, p: [f64; 3]) -> [f64; 3] {
    let mut out = [0.0; 3];
    for (i, o) in out.iter_mut().enumerate() {
        *o = m[i][3] + (0..3).map(|k| m[i][k] * p[k]).sum::<f64>();
    }
    out
}

/// The programmable frame as 5.3 keeps it: coarse and fine translation, rotation (4x4 with no
/// translation), scale factors and mirror flags.
struct Components {
    coarse: [f64; 3],
    fine: [f64; 3],
    rotation: M4,
    scale: [f64; 3],
    mirror: [bool; 3],
}

impl Components {
    fn cleared() -> Components {
        Components {
            coarse: [0.0; 3],
            fine: [0.0; 3],
            rotation: identity(),
            scale: [1.0; 3],
            mirror: [false; 3],
        }
    }

    /// R S M as one matrix (mirror first, then scale, then rotate).
    fn linear(&self) -> M4 {
        let signs = self.mirror.map(|m| if m { -1.0 } else { 1.0 });
        product(
            &self.rotation,
            &product(&diagonal(self.scale), &diagonal(signs)),
        )
    }

    /// The whole frame: translation (T + Tf) after R S M.
    fn matrix(&self) -> M4 {
        let t = [0, 1, 2].map(|i| self.coarse[i] + self.fine[i]);
        product(&translation(t), &self.linear())
    }

    fn apply_block(&mut self, block: &FrameBlock) {
        match block {
            FrameBlock::Trans(t) => {
                *self = Components::cleared();
                self.coarse = *t;
            }
            FrameBlock::Atrans(t) => {
                // Tf += R S M t: the translation along the current axes.
                let along = apply(&self.linear(), *t);
                for (fine, a) in self.fine.iter_mut().zip(along) {
                    *fine += a;
                }
            }
            FrameBlock::Rot(a) => {
                *self = Components::cleared();
                self.rotation = rotation_z(*a);
            }
            FrameBlock::Arot(a) => self.rotation = product(&self.rotation, &rotation_z(*a)),
            FrameBlock::Scale(s) => {
                *self = Components::cleared();
                self.scale = *s;
            }
            FrameBlock::Ascale(s) => {
                for (scale, factor) in self.scale.iter_mut().zip(s) {
                    *scale *= factor;
                }
            }
            FrameBlock::Mirror(f) => {
                *self = Components::cleared();
                self.mirror = *f;
            }
            FrameBlock::Amirror(f) => {
                for (mirror, flag) in self.mirror.iter_mut().zip(f) {
                    *mirror ^= flag;
                }
            }
            FrameBlock::Coarse(t) => self.coarse = *t,
            FrameBlock::Fine(t) => self.fine = *t,
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn a_random_sequence_of_frame_blocks_maps_a_point_as_its_components(
        blocks in proptest::collection::vec(frame_block(), 1..7),
        point in [milli(-100.0..100.0), milli(-100.0..100.0), milli(-100.0..100.0)],
    ) {
        let mut text = String::from("G54\n");
        let mut frame = Components::cleared();
        for block in &blocks {
            text.push_str(&block.text());
            text.push('\n');
            frame.apply_block(block);
        }
        text.push_str(&format!(
            "G0 X{:.3} Y{:.3} Z{:.3}\nM30\n",
            point[0], point[1], point[2]
        ));
        // m = G54 (100, 50, 0) + P(p): the settable frame is a translation only.
        let wcs = apply(&frame.matrix(), point);
        let wanted = [wcs[0] + 100.0, wcs[1] + 50.0, wcs[2]];
        let run = run_on(&text, &shop());
        prop_assert!(run.error().is_none(), "{}\n{:?}", text, run.alarms);
        let got = ends(&run.segments);
        let last = *got.last().expect("the G0 moves");
        prop_assert!(close(last, wanted, 1e-6), "{}\ngot {:?}\nwanted {:?}", text, last, wanted);
    }
}

#[test]
fn call_runs_the_program_a_string_variable_names() {
    // PGAsl, indirect call: PROG holds "SUB1"; SUB1 moves X10 then Y5 and returns to G0 X0.
    let text = "DEF STRING[20] PROG\nPROG=\"SUB1\"\nCALL PROG\nG0 X0\nM30\n";
    let run = run_with(text, &[("SUB1", "G0 X10\nY5\nRET\n")]);
    assert_points(
        &ends_of(&run, text),
        &[[10.0, 0.0, 0.0], [10.0, 5.0, 0.0], [0.0, 5.0, 0.0]],
        text,
    );
}

#[test]
fn call_takes_a_path_of_the_controls_file_system() {
    // The name is the path's last part without `_N_` and `_SPF`: SUB1.
    let text = "CALL \"/_N_WKS_DIR/_N_PART_WPD/_N_SUB1_SPF\"\nM30\n";
    let run = run_with(text, &[("SUB1", "G0 X7\nRET\n")]);
    assert_points(&ends_of(&run, text), &[[7.0, 0.0, 0.0]], text);
}

#[test]
fn call_block_runs_the_part_between_two_labels_of_the_called_program_once() {
    // SUB1's lines FROM: (Y1) and UPTO: (Y2) run; X1 before and X3 after them do not, and the
    // call returns after UPTO to the main program's G0 Z9.
    let text = "CALL \"SUB1\" BLOCK FROM TO UPTO\nG0 Z9\nM30\n";
    let run = run_with(
        text,
        &[("SUB1", "G0 X1\nFROM: G0 Y1\nUPTO: G0 Y2\nG0 X3\nRET\n")],
    );
    assert_points(
        &ends_of(&run, text),
        &[[0.0, 1.0, 0.0], [0.0, 2.0, 0.0], [0.0, 2.0, 9.0]],
        text,
    );
}

#[test]
fn call_block_without_a_program_repeats_a_part_of_this_one() {
    // A: X1 and B: X2 run, then CALL BLOCK A TO B runs them once more after X5 (X1, X2), and the
    // program goes on after the CALL with X6.
    let text = "A: G0 X1\nB: G0 X2\nG0 X5\nCALL BLOCK A TO B\nG0 X6\nM30\n";
    assert_eq!(xs(text), vec![1.0, 2.0, 5.0, 1.0, 2.0, 6.0]);
}

#[test]
fn call_of_an_empty_name_or_a_missing_program_is_an_alarm() {
    assert_eq!(
        error_code("DEF STRING[8] PN\nCALL PN\nM30\n"),
        AlarmCode::ValueOutOfRange
    );
    assert_eq!(
        error_code("CALL \"NOWHERE\"\nM30\n"),
        AlarmCode::ProgramNotFound
    );
}

#[test]
fn a_call_without_its_program_or_with_half_a_block_part_is_a_syntax_alarm() {
    assert_eq!(error_code("CALL\nM30\n"), AlarmCode::MacroSyntax);
    assert_eq!(
        error_code("CALL \"SUB1\" BLOCK A\nM30\n"),
        AlarmCode::MacroSyntax
    );
    assert_eq!(
        error_code("CALL \"SUB1\" X10\nM30\n"),
        AlarmCode::MacroSyntax
    );
}

/// INVCCW in G18 (Z-X plane, Z the plane's first axis) with Y along: the base circle about
/// Z0 X0 of radius 5 from Z10 X0 (K-10 from the start), one half turn of the polar angle out
/// (AR=180), Y rising 8 on the way. t0 = sqrt 3 (t - atan t = 0.684853); half a turn more is
/// 3.826446, t1 = 5.207522 (5.207522 - atan 5.207522 = 5.207522 - 1.381076), distance
/// 5 sqrt(1 + t1^2) = 26.5133 on the ray opposite the start: Z-26.5133 X0 Y8. Every piece's end
/// lies at distance 5 sqrt(1 + t^2) for a t between t0 and t1, and Y rises with the pieces.
#[test]
fn an_involute_in_g18_ends_half_a_turn_out_with_the_normal_axis_along() {
    let text = "G18 G1 Z10 X0 F1000\nINVCCW K-10 I0 CR=5 AR=180 Y8\nM30\n";
    let run = run_on(text, &machine());
    let points = ends_of(&run, text);
    let last = points.last().copied().unwrap();
    assert!(close(last, [0.0, 8.0, -26.5133], 1e-3), "{last:?}");
    let mut y = 0.0;
    for p in &points[1..] {
        let distance = p[0].hypot(p[2]);
        assert!((5.0 - 1e-9..=26.514).contains(&distance), "{p:?}");
        assert!(p[1] >= y - 1e-12);
        y = p[1];
    }
    assert!(points.len() > 100, "{} pieces", points.len());
}

/// The involute's alarms (PGsl 9.8, L5765-5778): no CR=, the end point and AR= together, a
/// start inside the base circle, an end point 0.5 mm off the involute through the start; and a
/// chamfer or rounding after an involute or a CIP circle, which vcnc does not make yet.
#[test]
fn involutes_the_control_refuses_alarm() {
    for (text, code) in [
        (
            "G1 X10 F100\nINVCCW I-10 AR=90\n",
            AlarmCode::ArcWithoutCenter,
        ),
        (
            "G1 X10 F100\nINVCCW X20 I-10 CR=5 AR=90\n",
            AlarmCode::WordNotAllowed,
        ),
        (
            "G1 X3 F100\nINVCCW I-3 CR=5 AR=90\n",
            AlarmCode::ArcEndNotOnCircle,
        ),
        (
            "G1 X10 F100\nINVCCW X32.27 Y32.77 I-10 CR=5\n",
            AlarmCode::ArcEndNotOnCircle,
        ),
        // A rounding after an involute or a CIP circle, which vcnc does not make: named.
        (
            "G1 X10 F100\nINVCCW X32.77 Y32.77 I-10 CR=5 RND=2\nG1 X50\n",
            AlarmCode::NotSupportedYet,
        ),
        (
            "G1 X10 F100\nCIP X20 Y10 I1=15 J1=8 CHF=1\nG1 X50\n",
            AlarmCode::NotSupportedYet,
        ),
    ] {
        let run = run_on(text, &machine());
        assert_eq!(run.error().map(|a| a.code), Some(code), "{text}");
    }
}

/// Several feeds in one block (PGsl 7.10): F7=, F3=, ST=, SR= and FMA[3, X] act only on a
/// digital input, which a simulation never sets: the block moves at F=20 (5 mm, 15 s), a note
/// says so once; a negative value, an input bit outside 2-7 or an axis the machine lacks alarm.
#[test]
fn several_feeds_in_a_block_leave_the_move_at_its_f_and_check_their_values() {
    let text = "G0 X100\nG1 X105 F=20 F7=5 F3=2.5 ST=1.5 SR=0.5\nFMA[3, X]=1000 F2=3\nM30\n";
    let run = run_on(text, &machine());
    assert_points(
        &ends_of(&run, text),
        &[[100.0, 0.0, 0.0], [105.0, 0.0, 0.0]],
        text,
    );
    let feeds: Vec<vcnc::motion::Feed> = run
        .segments
        .iter()
        .filter_map(|s| match &s.kind {
            SegmentKind::Line { feed, .. } => Some(*feed),
            _ => None,
        })
        .collect();
    assert_eq!(feeds, [vcnc::motion::Feed::PerMinute(20.0)]);
    let notes = run
        .alarms
        .iter()
        .filter(|a| a.code == AlarmCode::KeptAsState && a.message.contains("digital input"))
        .count();
    assert_eq!(notes, 1);
    for (text, code) in [
        ("G1 X5 F100 F7=-1\n", AlarmCode::ValueOutOfRange),
        ("FMA[8, X]=100\n", AlarmCode::ValueOutOfRange),
        ("FMA[3, Q]=100\n", AlarmCode::AxisNotOnMachine),
        ("FMA[3]=100\n", AlarmCode::MacroSyntax),
    ] {
        let run = run_on(text, &machine());
        assert_eq!(run.error().map(|a| a.code), Some(code), "{text}");
    }
}

/// Fast retraction (PGsl 9.14): LFON, DILF=, LFWP, ALF=, POLF[X]=, LFPOS and POLFMASK(X) act
/// only on an NC stop or fast input during G33, which a run never raises: the thread moves as
/// written (G18, Z from 5 to -25 at lead K2). ALF= outside 0-8 or not whole, a negative DILF=
/// and POLF or POLFMASK of an axis the machine lacks alarm.
#[test]
fn fast_retraction_is_read_and_checked_and_moves_nothing() {
    let text = "G18 G0 X10 Z5 S500 M3\nPOLF[X]=IC(20) LFPOS\nPOLFMASK(X)\n\
                G33 Z-25 K2 LFON DILF=3 LFWP ALF=7\nLFOF\nM30\n";
    let run = run_on(text, &machine());
    assert_points(
        &ends_of(&run, text),
        &[[10.0, 0.0, 5.0], [10.0, 0.0, -25.0]],
        text,
    );
    for (text, code) in [
        ("ALF=9\n", AlarmCode::ValueOutOfRange),
        ("ALF=1.5\n", AlarmCode::ValueOutOfRange),
        ("DILF=-1\n", AlarmCode::ValueOutOfRange),
        ("POLF[Q]=5\n", AlarmCode::AxisNotOnMachine),
        ("POLFMASK(X, Q)\n", AlarmCode::AxisNotOnMachine),
    ] {
        let run = run_on(text, &machine());
        assert_eq!(run.error().map(|a| a.code), Some(code), "{text}");
    }
}

/// The dynamic response's machine data from the program (PGsl 14.7.3, L10640-10687): every
/// group reads the machine file's limit in the control's unit (X's 2000 mm/s^2 is 2 m/s^2, Y's
/// jerk 50000 mm/s^3 is 50 m/s^3) until the program writes it. X=R1*10 goes to X20; after
/// `$MA_MAX_AX_ACCEL[2, X]=5` group 2 reads 5 (X5) while group 0 still reads 2. A group outside
/// 0-4, an axis the machine lacks and a limit not above 0 alarm.
#[test]
fn the_dynamic_machine_data_read_the_machine_file_and_keep_what_is_written() {
    let text = "R1=$MA_MAX_AX_ACCEL[2, X]\nG1 X=R1*10 F100\n$MA_MAX_AX_ACCEL[2, X]=5\n\
                R2=$MA_MAX_AX_ACCEL[2, X]\nR3=$MA_MAX_AX_JERK[0, Y]\nR4=$MA_MAX_AX_ACCEL[0, X]\n\
                G1 X=R2 Y=R3 Z=R4\nM30\n";
    let run = run_on(text, &machine());
    assert_points(
        &ends_of(&run, text),
        &[[20.0, 0.0, 0.0], [5.0, 50.0, 2.0]],
        text,
    );
    for (text, code) in [
        ("R1=$MA_MAX_AX_ACCEL[5, X]\n", AlarmCode::BadVariable),
        ("R1=$MA_MAX_AX_ACCEL[1, Q]\n", AlarmCode::BadVariable),
        ("$MA_MAX_AX_JERK[1, X]=0\n", AlarmCode::ValueOutOfRange),
    ] {
        let run = run_on(text, &machine());
        assert_eq!(run.error().map(|a| a.code), Some(code), "{text}");
    }
}
