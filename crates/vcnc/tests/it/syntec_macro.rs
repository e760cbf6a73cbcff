//! Syntec `%@MACRO` programs (issue #3): statements ended by `;`, `//` and `(* *)` comments,
//! `:=`, `G#30`, IF/ELSEIF/ELSE/END_IF, WHILE, FOR, REPEAT ... UNTIL, EXIT, GOTO, public
//! variables `@n`, and the alarms of what is malformed or not supported. Each case is a small
//! program and the variables or moves it must leave, or the alarm (code and line) it must stop
//! with. Expected values are worked out by hand from the structured-text rules the statements
//! follow (spec/iso-syntec-milling.md §0.1.1, §2 item 11).

use crate::common;

use crate::common::Run;
use vcnc::interp::MemoryLibrary;
use vcnc::motion::SegmentKind;
use vcnc::source::line_column;
use vcnc::syntax::lines::ReaderLines;
use vcnc::{
    interpret_bytes, interpret_str, Alarm, AlarmCode, FileId, Interpreter, Machine, Options,
    ProfileName,
};

fn syntec() -> Machine {
    Machine::default()
        .with_profile(ProfileName::Syntec)
        .expect("the Syntec profile fits the default machine")
}

/// Runs `program` on the Syntec machine with `library` and `options`; the run and the variables
/// `#0`-`#999` and `@0`-`@99` at its end.
fn run_full(
    program: &str,
    library: MemoryLibrary,
    options: Options,
) -> (Run, Vec<Option<f64>>, Vec<Option<f64>>) {
    let mut interpreter =
        interpret_str(program, &syntec(), options).with_library(Box::new(library));
    let mut run = Run {
        segments: Vec::new(),
        alarms: Vec::new(),
    };
    for item in interpreter.by_ref() {
        match item {
            Ok(vcnc::Item::Segment(segment)) => run.segments.push(segment),
            Ok(vcnc::Item::Frame(_)) => {}
            Ok(vcnc::Item::Warning(alarm)) | Err(alarm) => run.alarms.push(alarm),
        }
    }
    let hash = (0..1000).map(|n| interpreter.variable(n)).collect();
    let at = (0..100).map(|n| interpreter.public_variable(n)).collect();
    (run, hash, at)
}

/// The `#` variables after `program` runs without an error.
fn vars(program: &str) -> Vec<Option<f64>> {
    let (run, values, _) = run_full(program, MemoryLibrary::new(), Options::default());
    assert!(run.error().is_none(), "{program}\n{:?}", run.error());
    values
}

/// Asserts `#` variable values after a run (`None` = vacant).
fn check(program: &str, expected: &[(usize, Option<f64>)]) {
    common::variables::assert_values(program, &vars(program), expected);
}

/// The error a run stops with.
fn error_of(program: &str, library: MemoryLibrary) -> Alarm {
    let mut options = Options::default();
    options.limits.jumps = 10_000;
    let (run, _, _) = run_full(program, library, options);
    run.error()
        .cloned()
        .unwrap_or_else(|| panic!("no alarm:\n{program}"))
}

/// The code and line of the error a run stops with.
fn alarm(program: &str) -> (AlarmCode, u32) {
    let a = error_of(program, MemoryLibrary::new());
    (a.code, a.span.map_or(0, |s| s.line))
}

/// End points (machine X, Y, Z, rounded to 1e-4) of the moves of a run without error.
fn ends(program: &str, library: MemoryLibrary) -> Vec<[f64; 3]> {
    let (run, _, _) = run_full(program, library, Options::default());
    assert!(run.error().is_none(), "{program}\n{:?}", run.error());
    common::variables::move_ends(&run.segments)
}

fn v(x: f64) -> Option<f64> {
    Some(x)
}

// Statements, expressions, comments.

#[test]
fn assignments_and_expressions_follow_structured_text_precedence() {
    check(
        "%@MACRO\n#1 := 1 + 2 * 3;\n#2 := (1 + 2) * 3;\n#3 := 2 > 1 AND 3 > 2;\n#4 := NOT 0;\n#5 := 7 MOD 4;\n#6 := 1 = 2 OR 2 <> 3;\n#7 := ABS(-2) + MAX(1, 4) + MIN(1, 4);\n#8 := CEIL(-1.5) + FLOOR(-1.5) * 10;\n#9 := ATAN2(-1, -1);\nM30;\n",
        &[
            (1, v(7.0)),
            (2, v(9.0)),
            (3, v(1.0)),
            (4, v(1.0)),
            (5, v(3.0)),
            (6, v(1.0)),
            (7, v(7.0)),
            (8, v(-21.0)),
            (9, v(-135.0)),
        ],
    );
}

#[test]
fn statements_share_lines_and_run_over_several() {
    check(
        "%@MACRO\n#1 := 1; #2 := 2; #3 := #1 +\n   #2\n   * 10;\n#4 :=\n5;\nM30;\n",
        &[(1, v(1.0)), (2, v(2.0)), (3, v(21.0)), (4, v(5.0))],
    );
}

#[test]
fn comments_of_both_kinds_are_skipped() {
    check(
        "// title line\n%@MACRO\n#1 := 1; // #1 := 2;\n(* #1 := 3;\n   #2 := 4; *) #2 := 5;\n#3 := 6; (* ; *) #4 := 7;\nM30;\n",
        &[(1, v(1.0)), (2, v(5.0)), (3, v(6.0)), (4, v(7.0))],
    );
}

#[test]
fn the_manuals_mode_backup_restores_modes_through_g_variables() {
    // spec/iso-syntec-milling.md §2 item 11 (seed L5031-5039): #1000 and #1004 hold the modes,
    // `G#30 G#31` restores them.
    let lib = {
        let mut lib = MemoryLibrary::new();
        lib.insert(
            1111,
            FileId(1),
            "%@MACRO\n#30 := #1000;   // G00/G01/G02/G03\n#31 := #1004;   // G90/G91\nG91 G00 Z10.;\nG#30 G#31;      // restore\nM99;\n",
        );
        lib
    };
    let moves = ends("G90 G01 X10. F500.\nM98 P1111\nX20.\nM30\n", lib);
    assert_eq!(
        moves,
        vec![[10.0, 0.0, 0.0], [10.0, 0.0, 10.0], [20.0, 0.0, 10.0]]
    );
}

// IF.

#[test]
fn if_runs_its_branch_only_when_the_condition_holds() {
    check(
        "%@MACRO\n#1 := 5;\nIF #1 > 3 THEN\n  #2 := 1;\nEND_IF;\nIF #1 < 3 THEN\n  #3 := 1;\nEND_IF;\nM30;\n",
        &[(2, v(1.0)), (3, None)],
    );
}

#[test]
fn else_runs_when_the_condition_fails() {
    check(
        "%@MACRO\n#1 := 1;\nIF #1 = 2 THEN #2 := 1; ELSE #2 := 2; #3 := 3; END_IF;\n#4 := 4;\nM30;\n",
        &[(2, v(2.0)), (3, v(3.0)), (4, v(4.0))],
    );
}

#[test]
fn an_elseif_chain_runs_the_first_branch_that_holds_and_only_that() {
    let program = |x: u32| {
        format!(
            "%@MACRO\n#1 := {x};\nIF #1 = 1 THEN\n  #2 := 10;\nELSEIF #1 = 2 THEN\n  #2 := 20;\nELSIF #1 >= 2 THEN\n  #2 := 30;\nELSE\n  #2 := 40;\nEND_IF;\n#3 := #2 + 1;\nM30;\n"
        )
    };
    for (x, want) in [(1, 10.0), (2, 20.0), (3, 30.0), (0, 40.0)] {
        check(&program(x), &[(2, v(want)), (3, v(want + 1.0))]);
    }
}

#[test]
fn an_if_without_else_whose_conditions_all_fail_does_nothing() {
    check(
        "%@MACRO\n#2 := 0;\nIF #1 = 1 THEN #2 := 1; ELSIF #1 = 2 THEN #2 := 2; END_IF;\nM30;\n",
        &[(2, v(0.0))],
    );
}

#[test]
fn ifs_nest() {
    check(
        "%@MACRO\n#1 := 2; #2 := 3;\nIF #1 = 2 THEN\n  IF #2 = 4 THEN\n    #3 := 1;\n  ELSE\n    IF #2 = 3 THEN #3 := 2; END_IF;\n  END_IF;\nELSE\n  #3 := 3;\nEND_IF;\nM30;\n",
        &[(3, v(2.0))],
    );
}

#[test]
fn a_vacant_argument_is_told_from_zero() {
    check(
        "%@MACRO\nIF #24 = #0 THEN #24 := 0.; END_IF;\nIF #1 = #0 THEN #2 := 1; ELSE #2 := 2; END_IF;\nM30;\n",
        &[(24, v(0.0)), (2, v(1.0))],
    );
}

// Loops.

#[test]
fn while_loops_while_the_condition_holds() {
    check(
        "%@MACRO\n#1 := 0; #2 := 0;\nWHILE #1 < 5 DO\n  #1 := #1 + 1;\n  #2 := #2 + #1;\nEND_WHILE;\nM30;\n",
        &[(1, v(5.0)), (2, v(15.0))],
    );
}

#[test]
fn a_while_whose_condition_fails_at_once_never_runs() {
    check(
        "%@MACRO\n#1 := 9;\nWHILE #1 < 5 DO\n  #2 := 1;\nENDWHILE;\n#3 := 1;\nM30;\n",
        &[(2, None), (3, v(1.0))],
    );
}

#[test]
fn for_counts_up_by_one_without_by() {
    check(
        "%@MACRO\n#2 := 0; #3 := 0;\nFOR #1 := 1 TO 4 DO\n  #2 := #2 + #1;\n  #3 := #3 + 1;\nEND_FOR;\nM30;\n",
        // The counter ends one step past the last value, as in structured text.
        &[(1, v(5.0)), (2, v(10.0)), (3, v(4.0))],
    );
}

#[test]
fn for_steps_by_any_amount_down_as_well_as_up() {
    check(
        "%@MACRO\n#2 := 0; #4 := 0;\nFOR #1 := 1 TO 10 BY 3 DO #2 := #2 + #1; END_FOR;\nFOR #3 := 10 TO 1 BY -4 DO #4 := #4 * 100 + #3; ENDFOR;\nM30;\n",
        // 1 + 4 + 7 + 10; then 10, 6, 2.
        &[(2, v(22.0)), (4, v(100_602.0)), (3, v(-2.0))],
    );
}

#[test]
fn a_for_whose_first_value_is_past_the_last_never_runs() {
    check(
        "%@MACRO\nFOR #1 := 5 TO 1 DO #2 := 1; END_FOR;\nFOR #3 := 1 TO 5 BY -1 DO #4 := 1; END_FOR;\nM30;\n",
        &[(1, v(5.0)), (2, None), (3, v(1.0)), (4, None)],
    );
}

#[test]
fn repeat_runs_at_least_once() {
    check(
        "%@MACRO\n#1 := 10;\nREPEAT\n  #1 := #1 + 1;\n  #2 := #2 + 1;\nUNTIL #1 > 3 END_REPEAT;\nM30;\n",
        &[(1, v(11.0)), (2, v(1.0))],
    );
}

#[test]
fn repeat_loops_until_its_condition_holds_with_end_repeat_on_its_own() {
    check(
        "%@MACRO\n#1 := 0;\nREPEAT\n  #1 := #1 + 2;\nUNTIL #1 >= 7;\nEND_REPEAT;\nM30;\n",
        &[(1, v(8.0))],
    );
}

#[test]
fn exit_leaves_the_innermost_loop_only() {
    check(
        "%@MACRO\n#3 := 0;\nFOR #1 := 1 TO 3 DO\n  #2 := 0;\n  WHILE 1 DO\n    #2 := #2 + 1;\n    IF #2 >= #1 THEN EXIT; END_IF;\n  END_WHILE;\n  #3 := #3 + #2;\nEND_FOR;\nREPEAT EXIT; #4 := 1; UNTIL 1 END_REPEAT;\nM30;\n",
        &[(3, v(6.0)), (4, None)],
    );
}

#[test]
fn loops_nest_inside_each_other_and_inside_ifs() {
    check(
        "%@MACRO\n#10 := 0;\nFOR #1 := 1 TO 3 DO\n  FOR #2 := 1 TO 3 DO\n    IF #1 <> #2 THEN\n      #3 := 0;\n      REPEAT #3 := #3 + 1; #10 := #10 + 1; UNTIL #3 >= #1 END_REPEAT;\n    END_IF;\n  END_FOR;\nEND_FOR;\nM30;\n",
        // Pairs (1,2) (1,3): 1 each; (2,1) (2,3): 2 each; (3,1) (3,2): 3 each.
        &[(10, v(12.0))],
    );
}

#[test]
fn goto_jumps_out_of_a_loop_to_a_label() {
    check(
        "%@MACRO\n#1 := 0;\nWHILE 1 DO\n  #1 := #1 + 1;\n  IF #1 = 4 THEN GOTO 100; END_IF;\nEND_WHILE;\n#2 := 1;\nN100;\n#3 := #1;\nM30;\n",
        &[(1, v(4.0)), (2, None), (3, v(4.0))],
    );
}

#[test]
fn goto_back_to_a_label_loops_and_a_computed_goto_takes_a_variable() {
    check(
        "%@MACRO\n#1 := 0; #5 := 20;\nN10 #1 := #1 + 1;\nIF #1 < 3 THEN GOTO N10; END_IF;\nGOTO #5;\n#2 := 1;\nN20 #3 := 1;\nM30;\n",
        &[(1, v(3.0)), (2, None), (3, v(1.0))],
    );
}

#[test]
fn public_variables_hold_values_across_programs() {
    let mut lib = MemoryLibrary::new();
    lib.insert(
        8000,
        FileId(1),
        "%@MACRO\n@1 := @1 + 5;\n@[#1 + 1] := 7;\nM99;\n",
    );
    let (run, values, at) = run_full(
        "%@MACRO\n#1 := 2;\n@1 := 1;\nM98 P8000;\nM98 P8000;\n#2 := @1 + @3;\n#3 := @0;\nM30;\n",
        lib,
        Options::default(),
    );
    assert!(run.error().is_none(), "{:?}", run.error());
    assert_eq!(
        (at[1], at[3], values[2], values[3]),
        (v(11.0), v(7.0), v(18.0), None)
    );
}

// Motion.

#[test]
fn moves_inside_loops_go_where_the_counters_say() {
    let moves = ends(
        "%@MACRO\nG90 G01 F1000.;\nFOR #1 := 1 TO 3 DO\n  X(#1 * 10.) Y-#1;\n  #2 := 0;\n  WHILE #2 < 2 DO\n    #2 := #2 + 1;\n    G91 Z-1.;\n    G90;\n  END_WHILE;\nEND_FOR;\nG00 Z0.;\nM30;\n",
        MemoryLibrary::new(),
    );
    assert_eq!(
        moves,
        vec![
            [10.0, -1.0, 0.0],
            [10.0, -1.0, -1.0],
            [10.0, -1.0, -2.0],
            [20.0, -2.0, -2.0],
            [20.0, -2.0, -3.0],
            [20.0, -2.0, -4.0],
            [30.0, -3.0, -4.0],
            [30.0, -3.0, -5.0],
            [30.0, -3.0, -6.0],
            [30.0, -3.0, 0.0],
        ]
    );
}

#[test]
fn a_macro_subprogram_with_arguments_cuts_a_square_of_their_size() {
    let mut lib = MemoryLibrary::new();
    lib.insert(
        9000,
        FileId(1),
        "%@MACRO\n// side #24, passes #17\n#30 := #1004;\nFOR #31 := 1 TO #17 DO\n  G91 G01 X#24 F500.;\n  Y#24; X-#24; Y-#24;\n  Z-1.;\nEND_FOR;\nG#30;\nM99;\n",
    );
    let moves = ends("G90 G00 X0. Y0.\nG65 P9000 X5. Q2.\nG00 X1.\nM30\n", lib);
    assert_eq!(
        moves[..5],
        [
            [5.0, 0.0, 0.0],
            [5.0, 5.0, 0.0],
            [0.0, 5.0, 0.0],
            [0.0, 0.0, 0.0],
            [0.0, 0.0, -1.0]
        ]
    );
    assert_eq!(moves[9], [0.0, 0.0, -2.0]);
    // G90 restored by `G#30`: X1. is absolute.
    assert_eq!(moves[10..], [[1.0, 0.0, -2.0]]);
}

// Alarms.

#[test]
fn statements_without_partners_stop_with_a_structure_alarm_at_their_line() {
    assert_eq!(
        alarm("%@MACRO\n#1 := 1;\nEND_IF;\nM30;\n"),
        (AlarmCode::LoopStructure, 3)
    );
    assert_eq!(
        alarm("%@MACRO\n#1 := 1;\nWHILE #1 < 3 DO\n  #1 := #1 + 1;\nM30;\n"),
        (AlarmCode::LoopStructure, 3)
    );
    assert_eq!(
        alarm("%@MACRO\nFOR #1 := 1 TO 2 DO\n  IF #1 = 1 THEN\nEND_FOR;\nM30;\n"),
        (AlarmCode::LoopStructure, 3)
    );
    assert_eq!(
        alarm("%@MACRO\nREPEAT\n  #1 := 1;\nUNTIL #1 = 1;\n#2 := 1;\nM30;\n"),
        (AlarmCode::LoopStructure, 4)
    );
    assert_eq!(
        alarm("%@MACRO\nIF 0 THEN\nELSE\nELSE\nEND_IF;\nM30;\n"),
        (AlarmCode::LoopStructure, 4)
    );
    assert_eq!(
        alarm("%@MACRO\n#1 := 2;\nEXIT;\nM30;\n"),
        (AlarmCode::LoopStructure, 3)
    );
}

#[test]
fn a_broken_structure_stops_the_run_only_where_it_is_reached() {
    let (run, _, _) = run_full(
        "%@MACRO\nG90 G00 X1.;\nX2.;\nIF #1 = 1 THEN\nX3.;\nM30;\n",
        MemoryLibrary::new(),
        Options::default(),
    );
    let moves = run
        .segments
        .iter()
        .filter(|s| matches!(s.kind, SegmentKind::Rapid { .. }))
        .count();
    assert_eq!(moves, 2);
    let error = run.error().expect("the IF has no END_IF");
    assert_eq!(
        (error.code, error.span.unwrap().line, error.message.as_str()),
        (AlarmCode::LoopStructure, 4, "IF has no END_IF")
    );
}

#[test]
fn a_loop_that_never_ends_stops_at_the_jump_limit() {
    let mut options = Options::default();
    options.limits.jumps = 1000;
    let (run, values, _) = run_full(
        "%@MACRO\n#1 := 0;\nWHILE 1 DO\n  #1 := #1 + 1;\nEND_WHILE;\nM30;\n",
        MemoryLibrary::new(),
        options.clone(),
    );
    let error = run.error().expect("the limit stops it");
    assert_eq!(
        (error.code, error.span.unwrap().line),
        (AlarmCode::MacroLimit, 5)
    );
    assert_eq!(values[1], v(1001.0));
    let (run, _, _) = run_full(
        "%@MACRO\nREPEAT\n  #1 := #1 + 1;\nUNTIL #1 < 0 END_REPEAT;\nM30;\n",
        MemoryLibrary::new(),
        options,
    );
    assert_eq!(run.error().map(|e| e.code), Some(AlarmCode::MacroLimit));
    assert_eq!(
        alarm("%@MACRO\nFOR #1 := 1 TO 2 BY 0 DO\nEND_FOR;\nM30;\n"),
        (AlarmCode::MacroLimit, 2)
    );
}

// CASE and the nesting limit.

#[test]
fn case_runs_the_branch_of_the_first_label_equal_to_the_selector() {
    // 0 and 4 take ELSE, 1 its branch, 2 and 3 share one of two statements.
    check(
        "%@MACRO\n#10 := 0;\nFOR #1 := 0 TO 4 DO\n  CASE #1 OF\n    1: #10 := #10 + 1;\n    2, 3: #10 := #10 + 10;\n       #10 := #10 + 100;\n  ELSE\n    #10 := #10 + 1000;\n  END_CASE;\nEND_FOR;\nM30;\n",
        &[(10, v(2221.0))],
    );
}

#[test]
fn case_without_a_matching_label_or_else_goes_on_after_end_case() {
    check(
        "%@MACRO\n#2 := 5;\nCASE #2 - 1 OF\n-4: #3 := 1;\n1:\n#3 := 2;\nEND_CASE;\n#4 := 7;\nM30;\n",
        &[(3, None), (4, v(7.0))],
    );
    // A vacant selector equals no label (as EQ compares): ELSE runs.
    check(
        "%@MACRO\nCASE #1 OF\n0: #3 := 1;\nELSE #3 := 2;\nEND_CASE;\nM30;\n",
        &[(3, v(2.0))],
    );
    // ENDCASE is read too, and a selector that computes to a whole number matches.
    check(
        "%@MACRO\nCASE 0.1 * 30 OF\n3: #3 := 1;\nENDCASE;\nM30;\n",
        &[(3, v(1.0))],
    );
}

#[test]
fn case_branches_hold_any_statement_and_nest() {
    check(
        "%@MACRO\n#1 := 2; #2 := 1;\nCASE #1 OF\n1: #5 := 1;\n2: IF #2 = 1 THEN\n     CASE #2 OF\n       1: #5 := 21;\n       ELSE #5 := 22;\n     END_CASE;\n   END_IF;\n   #6 := 3;\nELSE #5 := 3;\nEND_CASE;\nM30;\n",
        &[(5, v(21.0)), (6, v(3.0))],
    );
    // EXIT in a CASE leaves the loop around it.
    check(
        "%@MACRO\n#1 := 0;\nWHILE #1 < 10 DO\n#1 := #1 + 1;\nCASE #1 OF\n3: EXIT;\nEND_CASE;\nEND_WHILE;\nM30;\n",
        &[(1, v(3.0))],
    );
    let moves = ends(
        "%@MACRO\nFOR #1 := 1 TO 2 DO\nCASE #1 OF\n1: G01 X10. F100.;\n2: G01 Y10.;\nEND_CASE;\nEND_FOR;\nM30;\n",
        MemoryLibrary::new(),
    );
    assert_eq!(moves, vec![[10.0, 0.0, 0.0], [10.0, 10.0, 0.0]]);
}

#[test]
fn case_without_its_partners_stops_where_the_run_reaches_it() {
    for (program, line) in [
        ("%@MACRO\n#1 := 1;\nEND_CASE;\nM30;\n", 3),
        ("%@MACRO\n#1 := 1;\n1: #2 := 1;\nM30;\n", 3),
        ("%@MACRO\nCASE #1 OF\n1: #2 := 1;\nM30;\n", 2),
        (
            "%@MACRO\n#1 := 2;\nCASE #1 OF\nELSE #2 := 1;\n2: #2 := 2;\nEND_CASE;\nM30;\n",
            5,
        ),
        ("%@MACRO\nCASE 1 OF\n1: IF 1 THEN\nEND_CASE;\nM30;\n", 3),
    ] {
        assert_eq!(
            alarm(program),
            (AlarmCode::LoopStructure, line),
            "{program}"
        );
    }
}

#[test]
fn structured_statements_nest_ten_deep_and_no_deeper() {
    let nested = |depth: usize| {
        let mut program = String::from("%@MACRO\n");
        for _ in 0..depth {
            program.push_str("IF 1 THEN\n");
        }
        program.push_str("#1 := 1;\n");
        for _ in 0..depth {
            program.push_str("END_IF;\n");
        }
        program.push_str("M30;\n");
        program
    };
    check(&nested(10), &[(1, v(1.0))]);
    // The eleventh IF (line 12) opens one level too many.
    assert_eq!(alarm(&nested(11)), (AlarmCode::MacroLimit, 12));
    // Loops and CASE count alike.
    assert_eq!(
        alarm("%@MACRO\nWHILE 1 DO\nFOR #1 := 1 TO 2 DO\nREPEAT\nCASE 1 OF\n1: IF 1 THEN\nIF 1 THEN\nIF 1 THEN\nIF 1 THEN\nIF 1 THEN\nIF 1 THEN\nIF 1 THEN\nEND_IF;\nEND_IF;\nEND_IF;\nEND_IF;\nEND_IF;\nEND_IF;\nEND_IF;\nEND_CASE;\nUNTIL 1 END_REPEAT;\nEND_FOR;\nEND_WHILE;\nM30;\n"),
        (AlarmCode::MacroLimit, 12)
    );
}

#[test]
fn what_is_not_supported_is_an_alarm_that_names_it_at_its_line_and_column() {
    let program = "%@MACRO\n#1 := 1;\nCASE #1 OF\n  1..5: #2 := 1;\nEND_CASE;\nM30;\n";
    let a = error_of(program, MemoryLibrary::new());
    assert_eq!(a.code, AlarmCode::NotSupportedYet);
    assert_eq!(
        a.message,
        "the CASE label range `1..5` is not supported yet"
    );
    let at = line_column(program.as_bytes(), a.span.unwrap().start);
    assert_eq!((at.line, at.column), (4, 3));
    let program = "%@MACRO\n#1 := 1 + GETARG(X1);\nM30;\n";
    let a = error_of(program, MemoryLibrary::new());
    assert_eq!(
        (a.code, a.message.as_str()),
        (
            AlarmCode::NotSupportedYet,
            "the macro function `GETARG` is not supported yet"
        )
    );
    let at = line_column(program.as_bytes(), a.span.unwrap().start);
    assert_eq!((at.line, at.column), (2, 11));
}

#[test]
fn malformed_statements_are_syntax_alarms_at_their_line() {
    assert_eq!(
        alarm("%@MACRO\n#1 := 1;\nIF #1 = 1\n  #2 := 2;\nEND_IF;\nM30;\n"),
        (AlarmCode::MacroSyntax, 4)
    );
    assert_eq!(
        alarm("%@MACRO\n#1 := (1 + 2;\nM30;\n"),
        (AlarmCode::MacroSyntax, 2)
    );
    assert_eq!(
        alarm("%@MACRO\nG01 X1. (comment) F100.;\nM30;\n"),
        (AlarmCode::MacroSyntax, 2)
    );
    assert_eq!(
        alarm("%@MACRO\n@0 := 1;\nM30;\n"),
        (AlarmCode::BadVariable, 2)
    );
}

#[test]
fn alarm_stops_with_its_number_and_text_and_msg_only_tells() {
    let program = "%@MACRO\nMSG(\"check the tool\");\n#1 := 1;\nALARM(301, \"TOOL MISSING\");\n#2 := 1;\nM30;\n";
    let (run, values, _) = run_full(program, MemoryLibrary::new(), Options::default());
    let warnings: Vec<_> = run.alarms.iter().filter(|a| !a.is_error()).collect();
    assert_eq!(warnings[0].message, "message: check the tool");
    let error = run.error().expect("ALARM stops the run");
    assert_eq!(
        (error.code, error.message.as_str(), error.span.unwrap().line),
        (AlarmCode::UserAlarm, "alarm 301: TOOL MISSING", 4)
    );
    assert_eq!((values[1], values[2]), (v(1.0), None));
}

#[test]
fn wait_and_sleep_do_nothing_in_a_simulation() {
    check(
        "%@MACRO\nG01 X1. F100.;\nWAIT();\n#1 := #5001;\nSLEEP();\nM30;\n",
        &[(1, v(1.0))],
    );
}

// Plain programs.

#[test]
fn plain_fanuc_programs_are_read_as_before() {
    // `( )` is a comment, `[ ]` bracket, FANUC's precedence (AND with the products), and the
    // Syntec keywords are no statements outside a %@MACRO program.
    let machine = Machine::default();
    let program = "%\nO0001 (PLAIN)\n#1=1+2*3 (SEVEN)\n#2=[1 AND 3] + 1\nIF [#1 EQ 7] THEN #3=1\nWHILE [#2 LT 4] DO1\n#2=#2+1\nEND1\nM30\n%\n";
    let mut interpreter = interpret_str(program, &machine, Options::default());
    let errors: Vec<_> = interpreter.by_ref().filter_map(Result::err).collect();
    assert!(errors.is_empty(), "{errors:?}");
    assert_eq!(
        (1..=3).map(|n| interpreter.variable(n)).collect::<Vec<_>>(),
        vec![v(7.0), v(4.0), v(1.0)]
    );
    let run = common::run(b"G90\nEND_IF\nM30\n", &machine, Options::default());
    assert_eq!(
        run.error().map(|e| e.code),
        Some(AlarmCode::NotSupportedYet)
    );
    // A `%@MACRO` line that is not the first is no header: the program is ISO.
    let run = common::run(
        b"G90 G00 X1.\n%@MACRO\nX2.\n",
        &syntec(),
        Options::default(),
    );
    assert!(run.error().is_none(), "{:?}", run.error());
}

#[test]
fn a_macro_program_that_cannot_be_held_in_memory_says_so() {
    let text = b"%@MACRO\n#1 := 1;\nM30;\n";
    let interpreter = Interpreter::new(
        ReaderLines::new(&text[..]),
        FileId(0),
        &syntec(),
        Options::default(),
    );
    let error = interpreter
        .filter_map(Result::err)
        .find(Alarm::is_error)
        .expect("a stream cannot run a macro program");
    assert_eq!(error.code, AlarmCode::NotSupportedYet);
    assert_eq!(error.span.unwrap().line, 1);
}

// Mangled text.

#[test]
fn mangled_macro_programs_never_panic_and_every_alarm_points_inside_the_text() {
    let seeds: &[&str] = &[
        "%@MACRO\n#1 := 0;\nWHILE #1 < 3 DO\n  #1 := #1 + 1;\n  G01 X(#1 * 2.) F100.;\nEND_WHILE;\nM30;\n",
        "%@MACRO\nFOR #1 := 1 TO 3 BY 1 DO\n  IF #1 = 2 THEN EXIT; ELSIF #1 > 2 THEN #2 := 1; ELSE @3 := 2; END_IF;\nEND_FOR;\nREPEAT #4 := #4 + 1; UNTIL #4 > 2 END_REPEAT;\nGOTO 10;\nN10 M30;\n",
        "// c\n%@MACRO\n(* block\n comment *) #1 := ABS(-1) + MAX(2, 3); // line\nIF NOT (#1 = 4) THEN ALARM(1, \"X\"); END_IF;\nMSG(\"done\");\nM30;\n",
        "%@MACRO\nFOR #1 := 0 TO 3 DO\n  CASE #1 OF\n    1: G01 X(#1) F100.;\n    2, -3: IF #1 = 2 THEN EXIT; END_IF;\n  ELSE\n    #2 := #2 + 1;\n  END_CASE;\nEND_FOR;\nM30;\n",
    ];
    let mut state = 0x9e37_79b9_7f4a_7c15_u64;
    let mut random = move |below: usize| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state % below.max(1) as u64) as usize
    };
    const PIECES: &[&[u8]] = &[
        b";",
        b"(*",
        b"*)",
        b"//",
        b"\"",
        b"\n",
        b"IF ",
        b" THEN",
        b"END_IF",
        b"WHILE ",
        b" DO",
        b"END_WHILE;",
        b"FOR #1 := ",
        b" TO ",
        b" BY ",
        b"END_FOR;",
        b"REPEAT",
        b"UNTIL ",
        b"END_REPEAT",
        b"EXIT;",
        b"ELSE",
        b"ELSIF ",
        b"GOTO ",
        b"@",
        b"#",
        b"(",
        b")",
        b"[",
        b"]",
        b":=",
        b"<>",
        b"NOT",
        b"%",
        b"N1",
        b"\xff",
    ];
    let mut options = Options::default();
    options.limits.jumps = 200;
    for round in 0..600 {
        let mut text = seeds[round % seeds.len()].as_bytes().to_vec();
        for _ in 0..1 + random(4) {
            let at = random(text.len() + 1);
            match random(3) {
                0 if at < text.len() => {
                    text.remove(at);
                }
                1 => {
                    let piece = PIECES[random(PIECES.len())];
                    text.splice(at..at, piece.iter().copied());
                }
                _ => {
                    let end = (at + random(12)).min(text.len());
                    let copy = text[at..end].to_vec();
                    let to = random(text.len() + 1);
                    text.splice(to..to, copy);
                }
            }
        }
        let length = text.len() as u32;
        let mut error_seen = false;
        let limit = 64 * text.len() + 64;
        let items = interpret_bytes(&text, &syntec(), options.clone()).take(limit + 1);
        let mut count = 0;
        for item in items {
            count += 1;
            assert!(
                !error_seen,
                "an item after the error: {}",
                String::from_utf8_lossy(&text)
            );
            let span = match &item {
                Ok(vcnc::Item::Segment(segment)) => segment.span,
                // A frame names no block.
                Ok(vcnc::Item::Frame(_)) => continue,
                Ok(vcnc::Item::Warning(alarm)) => alarm.span.expect("every alarm has a span"),
                Err(alarm) => {
                    error_seen = true;
                    alarm.span.expect("every alarm has a span")
                }
            };
            assert!(
                span.start <= span.end && span.end <= length,
                "span {span} outside {length} bytes: {}",
                String::from_utf8_lossy(&text)
            );
        }
        assert!(count <= limit, "{}", String::from_utf8_lossy(&text));
    }
}
