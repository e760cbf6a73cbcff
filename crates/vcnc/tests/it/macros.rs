//! Custom Macro B, construct by construct (issue #3, acceptance 3): each case is a small
//! program and the values its variables must have at the end, or the alarm it must stop with.
//! Expected values are worked out by hand from the FANUC Custom Macro B rules.

use crate::common;

use vcnc::interp::MemoryLibrary;
use vcnc::motion::SegmentKind;
use vcnc::{interpret_str, AlarmCode, FileId, Machine, Options, ProfileName, Segment};

/// Runs `program` (with `library`) and returns the interpreter at its end and the stream.
fn run_with(
    program: &str,
    machine: &Machine,
    library: MemoryLibrary,
) -> (Vec<Segment>, Vec<vcnc::Alarm>, Vec<Option<f64>>) {
    let mut interpreter =
        interpret_str(program, machine, Options::default()).with_library(Box::new(library));
    let mut segments = Vec::new();
    let mut alarms = Vec::new();
    for item in interpreter.by_ref() {
        match item {
            Ok(vcnc::Item::Segment(s)) => segments.push(s),
            Ok(vcnc::Item::Frame(_)) => {}
            Ok(vcnc::Item::Warning(a)) | Err(a) => alarms.push(a),
        }
    }
    let values = (0..1000).map(|n| interpreter.variable(n)).collect();
    (segments, alarms, values)
}

/// The variables after `program` runs without error.
fn vars(program: &str) -> Vec<Option<f64>> {
    let (_, alarms, values) = run_with(program, &Machine::default(), MemoryLibrary::new());
    let errors: Vec<_> = alarms.iter().filter(|a| a.is_error()).collect();
    assert!(errors.is_empty(), "{program}\n{errors:?}");
    values
}

/// Asserts variable values after a run (`None` = vacant).
fn check(program: &str, expected: &[(usize, Option<f64>)]) {
    common::variables::assert_values(program, &vars(program), expected);
}

/// The first error's code and line.
fn alarm(program: &str) -> (AlarmCode, u32) {
    let (_, alarms, _) = run_with(program, &Machine::default(), MemoryLibrary::new());
    let a = alarms
        .into_iter()
        .find(|a| a.is_error())
        .unwrap_or_else(|| panic!("no alarm:\n{program}"));
    (a.code, a.span.map_or(0, |s| s.line))
}

/// End points (machine X, Y, Z) of the moves of a run.
fn ends(program: &str, library: MemoryLibrary) -> Vec<[f64; 3]> {
    let (segments, alarms, _) = run_with(program, &Machine::default(), library);
    let errors: Vec<_> = alarms.iter().filter(|a| a.is_error()).collect();
    assert!(errors.is_empty(), "{program}\n{errors:?}");
    common::variables::move_ends(&segments)
}

fn library(programs: &[(u32, &str)]) -> MemoryLibrary {
    let mut library = MemoryLibrary::new();
    for (i, (number, text)) in programs.iter().enumerate() {
        library.insert(*number, FileId(i as u32 + 1), text);
    }
    library
}

const S: Option<f64> = None;
fn v(x: f64) -> Option<f64> {
    Some(x)
}

// Vacant variables.

#[test]
fn a_variable_never_set_is_vacant() {
    check("#2=#1\nM30", &[(1, S), (2, S)]);
}

#[test]
fn vacant_counts_as_zero_in_arithmetic() {
    check(
        "#2=#1+5\n#3=#1*5\n#4=-#1\n#5=#0",
        &[(2, v(5.0)), (3, v(0.0)), (4, S), (5, S)],
    );
}

#[test]
fn eq_and_ne_tell_vacant_from_zero() {
    check(
        "#10=[#1 EQ #0]\n#11=[#1 EQ 0]\n#12=[#0 NE 0]\n#13=[#0 EQ #0]",
        &[(10, v(1.0)), (11, v(0.0)), (12, v(1.0)), (13, v(1.0))],
    );
}

#[test]
fn the_ordering_comparisons_take_vacant_as_zero() {
    check(
        "#10=[#1 GE 0]\n#11=[#1 LT 0]\n#12=[#1 LE 0]\n#13=[#1 GT -1]",
        &[(10, v(1.0)), (11, v(0.0)), (12, v(1.0)), (13, v(1.0))],
    );
}

#[test]
fn an_address_with_a_vacant_variable_is_left_out() {
    let moves = ends(
        "G90 G0 X1. Y2.\nG0 X5. Y#1\nG0 X#1 Y7.\nM30",
        MemoryLibrary::new(),
    );
    assert_eq!(moves[1], [5.0, 2.0, 0.0]);
    assert_eq!(moves[2], [5.0, 7.0, 0.0]);
}

#[test]
fn a_block_whose_only_axis_word_is_vacant_does_not_move() {
    let moves = ends("G90 G0 X1.\nG0 X#5\nM30", MemoryLibrary::new());
    assert_eq!(moves.len(), 1);
}

#[test]
fn writing_hash_zero_is_an_alarm() {
    assert_eq!(alarm("G0 X0\n#0=1\nM30"), (AlarmCode::BadVariable, 2));
}

#[test]
fn vacant_in_a_function_is_zero() {
    check("#2=COS[#1]\n#3=ABS[#1]", &[(2, v(1.0)), (3, v(0.0))]);
}

// Precedence and arithmetic.

#[test]
fn multiplication_binds_tighter_than_addition() {
    check(
        "#1=2+3*4\n#2=[2+3]*4\n#3=10-4-3\n#4=24/4/2",
        &[(1, v(14.0)), (2, v(20.0)), (3, v(3.0)), (4, v(3.0))],
    );
}

#[test]
fn and_is_at_the_level_of_multiplication_and_or_of_addition() {
    // 1 OR 2 AND 0 = 1 OR [2 AND 0] = 1; [1 OR 2] AND 3 = 3.
    check(
        "#1=1 OR 2 AND 0\n#2=[1 OR 2] AND 3\n#3=5 XOR 1",
        &[(1, v(1.0)), (2, v(3.0)), (3, v(4.0))],
    );
}

#[test]
fn comparisons_are_lowest() {
    check("#1=1+1 EQ 2\n#2=2*3 GT 5+0", &[(1, v(1.0)), (2, v(1.0))]);
}

#[test]
fn unary_minus_applies_to_its_operand() {
    check(
        "#1=-2*3\n#2=-[2+3]\n#3=4--2",
        &[(1, v(-6.0)), (2, v(-5.0)), (3, v(6.0))],
    );
}

#[test]
fn mod_keeps_the_sign_of_the_dividend() {
    check(
        "#1=10 MOD 3\n#2=-10 MOD 3\n#3=7.5 MOD 2",
        &[(1, v(1.0)), (2, v(-1.0)), (3, v(1.5))],
    );
}

#[test]
fn brackets_nest() {
    check("#1=[[[1+2]*[3+4]]-[5]]/2", &[(1, v(8.0))]);
}

#[test]
fn division_by_zero_is_an_alarm_on_its_line() {
    assert_eq!(alarm("#1=1\n#2=#1/0\nM30"), (AlarmCode::MacroArithmetic, 2));
}

#[test]
fn division_by_a_vacant_variable_is_division_by_zero() {
    assert_eq!(alarm("#2=5/#1\nM30"), (AlarmCode::MacroArithmetic, 1));
}

// Functions.

#[test]
fn trigonometry_is_in_degrees() {
    check(
        "#1=SIN[30]\n#2=COS[60]\n#3=TAN[45]\n#4=ASIN[0.5]\n#5=ACOS[0.5]\n#6=ATAN[1]",
        &[
            (1, v(0.5)),
            (2, v(0.5)),
            (3, v(1.0)),
            (4, v(30.0)),
            (5, v(60.0)),
            (6, v(45.0)),
        ],
    );
}

#[test]
fn atan_with_two_arguments_gives_zero_to_360() {
    check(
        "#1=ATAN[1]/[-1]\n#2=ATAN[-1,-1]\n#3=ATAN[-1]/[1]\n#4=ATAN[0,1]",
        &[(1, v(135.0)), (2, v(225.0)), (3, v(315.0)), (4, v(0.0))],
    );
}

#[test]
fn fix_truncates_toward_zero_and_fup_away_from_zero() {
    check(
        "#1=FIX[1.7]\n#2=FIX[-1.7]\n#3=FUP[1.2]\n#4=FUP[-1.2]\n#5=FUP[2]\n#6=FIX[-2]",
        &[
            (1, v(1.0)),
            (2, v(-1.0)),
            (3, v(2.0)),
            (4, v(-2.0)),
            (5, v(2.0)),
            (6, v(-2.0)),
        ],
    );
}

#[test]
fn round_takes_halves_away_from_zero() {
    check(
        "#1=ROUND[2.5]\n#2=ROUND[-2.5]\n#3=ROUND[1.4999]\n#4=ROUND[-0.4]",
        &[(1, v(3.0)), (2, v(-3.0)), (3, v(1.0)), (4, v(-0.0))],
    );
}

#[test]
fn sqrt_abs_ln_exp_pow() {
    check(
        "#1=SQRT[16]\n#2=ABS[-3]\n#3=LN[1]\n#4=EXP[0]\n#5=POW[2,10]",
        &[
            (1, v(4.0)),
            (2, v(3.0)),
            (3, v(0.0)),
            (4, v(1.0)),
            (5, v(1024.0)),
        ],
    );
}

#[test]
fn bin_and_bcd_convert_binary_coded_decimal() {
    check("#1=BCD[25]\n#2=BIN[37]", &[(1, v(37.0)), (2, v(25.0))]);
}

#[test]
fn sqrt_of_a_negative_number_is_an_alarm() {
    assert_eq!(alarm("#1=SQRT[-1]"), (AlarmCode::MacroArithmetic, 1));
}

#[test]
fn asin_beyond_one_is_an_alarm() {
    assert_eq!(alarm("#1=ASIN[2]"), (AlarmCode::MacroArithmetic, 1));
}

#[test]
fn functions_nest_inside_expressions() {
    check("#1=SQRT[ABS[-9]]+FIX[SIN[90]*2.5]", &[(1, v(5.0))]);
}

// Variables: indirect, ranges, system variables.

#[test]
fn indirect_variables_read_and_write() {
    check(
        "#1=105\n#[#1]=7\n#2=#[100+5]\n#[#1+1]=#105+1",
        &[(105, v(7.0)), (2, v(7.0)), (106, v(8.0))],
    );
}

#[test]
fn common_and_persistent_variables_are_shared_with_subprograms() {
    let lib = library(&[(10, "O10\n#100=#100+1\n#500=3\nM99")]);
    let (_, alarms, values) = run_with("#100=1\nM98 P10\nM30", &Machine::default(), lib);
    assert!(alarms.iter().all(|a| !a.is_error()), "{alarms:?}");
    assert_eq!((values[100], values[500]), (v(2.0), v(3.0)));
}

#[test]
fn an_unknown_system_variable_is_an_alarm_not_a_zero() {
    assert_eq!(alarm("#1=#9999\nM30"), (AlarmCode::BadVariable, 1));
    assert_eq!(alarm("#1=#3000\nM30"), (AlarmCode::BadVariable, 1));
}

#[test]
fn positions_are_system_variables() {
    check(
        "G90 G0 X10. Y20. Z5.\n#1=#5001\n#2=#5002\n#3=#5043\n#4=#5021",
        &[(1, v(10.0)), (2, v(20.0)), (3, v(5.0)), (4, v(10.0))],
    );
}

#[test]
fn modal_information_is_in_the_4000s() {
    check(
        "G91 G1 X1. F100.\n#1=#4001\n#2=#4003\n#3=#4002\n#4=#4006\n#5=#4014\n#6=#4109",
        &[
            (1, v(1.0)),
            (2, v(91.0)),
            (3, v(17.0)),
            (4, v(21.0)),
            (5, v(54.0)),
            (6, v(100.0)),
        ],
    );
}

#[test]
fn work_offsets_read_and_write_through_5221() {
    let moves = ends(
        "#5221=100.\n#5222=-50.\nG90 G54 G0 X0 Y0\nM30",
        MemoryLibrary::new(),
    );
    assert_eq!(moves[0], [100.0, -50.0, 0.0]);
    check("#5241=12.5\n#1=#5241", &[(1, v(12.5))]);
}

#[test]
fn extended_work_offsets_are_in_the_7000s() {
    let moves = ends(
        "#7001=5.\n#7002=6.\nG90 G54.1 P1 G0 X0 Y0\nM30",
        MemoryLibrary::new(),
    );
    assert_eq!(moves[0], [5.0, 6.0, 0.0]);
}

#[test]
fn tool_offsets_are_in_the_2000s() {
    // FANUC memory C: #2201 is H1 geometry, #2001 its wear.
    let moves = ends(
        "#2201=10.\n#2001=0.5\nG90 G43 H1 G0 Z0\nM30",
        MemoryLibrary::new(),
    );
    assert_eq!(moves[0], [0.0, 0.0, 10.5]);
}

#[test]
fn hash_3000_raises_the_programs_own_alarm_with_its_message() {
    let (_, alarms, _) = run_with(
        "G0 X1.\n#3000=12 (CHECK TOOL)\nG0 X2.\n",
        &Machine::default(),
        MemoryLibrary::new(),
    );
    let a = alarms.iter().find(|a| a.is_error()).unwrap();
    assert_eq!(a.code, AlarmCode::UserAlarm);
    assert_eq!(a.message, "alarm 3012: CHECK TOOL");
}

#[test]
fn hash_3006_stops_with_a_message_and_goes_on() {
    let (segments, alarms, _) = run_with(
        "#3006=1 (TURN PART)\nG0 X1.\nM30",
        &Machine::default(),
        MemoryLibrary::new(),
    );
    assert!(alarms.iter().all(|a| !a.is_error()));
    assert!(matches!(
        segments[0].kind,
        SegmentKind::Stop {
            kind: vcnc::motion::StopKind::Message
        }
    ));
    assert!(segments.len() >= 3);
}

#[test]
fn timers_and_parts_counters_can_be_set_and_read() {
    check("#3001=0\n#3901=5\n#1=#3901+#3001", &[(1, v(5.0))]);
}

// Control flow.

#[test]
fn goto_skips_forward() {
    check("#1=1\nGOTO 10\n#1=2\nN10 #2=3", &[(1, v(1.0)), (2, v(3.0))]);
}

#[test]
fn goto_jumps_back() {
    check("#1=0\nN5 #1=#1+1\nIF [#1 LT 5] GOTO 5\n", &[(1, v(5.0))]);
}

#[test]
fn computed_goto_takes_the_variables_value() {
    check(
        "#5=30\nGOTO #5\nN20 #1=20\nN30 #2=30",
        &[(1, S), (2, v(30.0))],
    );
    check(
        "#5=2\nGOTO [#5*10]\nN10 #1=1\nN20 #2=2",
        &[(1, S), (2, v(2.0))],
    );
}

#[test]
fn goto_searches_forward_first_then_from_the_top() {
    // Two blocks are N10: the one after the GOTO is found first.
    check(
        "N10 #1=#1+1\nIF [#1 GT 3] GOTO 99\nGOTO 10\nN10 #2=#2+1\nGOTO 10\nN99 #3=1",
        &[(1, v(4.0)), (2, v(3.0)), (3, v(1.0))],
    );
}

#[test]
fn goto_to_a_missing_number_is_an_alarm() {
    assert_eq!(
        alarm("#1=1\nGOTO 77\nM30"),
        (AlarmCode::SequenceNotFound, 2)
    );
}

#[test]
fn if_then_runs_its_assignment_only_when_true() {
    check(
        "#1=5\nIF [#1 GT 3] THEN #2=1\nIF [#1 LT 3] THEN #3=1",
        &[(2, v(1.0)), (3, S)],
    );
}

#[test]
fn if_with_and_or_of_conditions() {
    check(
        "#1=5\nIF [[#1 GT 3] AND [#1 LT 10]] THEN #2=1\nIF [[#1 LT 3] OR [#1 EQ 5]] THEN #3=1",
        &[(2, v(1.0)), (3, v(1.0))],
    );
}

#[test]
fn while_loops_until_the_condition_fails() {
    check(
        "#1=0\n#2=0\nWHILE [#1 LT 10] DO1\n#2=#2+#1\n#1=#1+1\nEND1",
        &[(1, v(10.0)), (2, v(45.0))],
    );
}

#[test]
fn a_while_that_is_false_at_once_skips_its_body() {
    check(
        "#1=10\nWHILE [#1 LT 10] DO1\n#2=1\nEND1\n#3=1",
        &[(2, S), (3, v(1.0))],
    );
}

#[test]
fn nested_while_loops_with_their_own_numbers() {
    check(
        "#1=0\n#3=0\nWHILE [#1 LT 3] DO1\n#2=0\nWHILE [#2 LT 4] DO2\n#3=#3+1\n#2=#2+1\nEND2\n#1=#1+1\nEND1",
        &[(3, v(12.0))],
    );
}

#[test]
fn three_nested_loops() {
    check(
        "#10=0\n#1=0\nWH [#1 LT 2] DO1\n#2=0\nWH [#2 LT 2] DO2\n#3=0\nWH [#3 LT 2] DO3\n#10=#10+1\n#3=#3+1\nEND3\n#2=#2+1\nEND2\n#1=#1+1\nEND1",
        &[(10, v(8.0))],
    );
}

#[test]
fn a_loop_number_can_be_used_again_after_its_end() {
    check(
        "#1=0\nWHILE [#1 LT 2] DO1\n#1=#1+1\nEND1\nWHILE [#1 LT 5] DO1\n#1=#1+1\nEND1",
        &[(1, v(5.0))],
    );
}

#[test]
fn goto_out_of_a_loop_is_allowed() {
    check(
        "#1=0\nWHILE [1 EQ 1] DO1\n#1=#1+1\nIF [#1 EQ 4] GOTO 50\nEND1\nN50 #2=#1",
        &[(2, v(4.0))],
    );
}

#[test]
fn goto_into_a_loop_ends_in_an_alarm_at_its_end() {
    assert_eq!(
        alarm("GOTO 10\nWHILE [#1 LT 3] DO1\nN10 #1=#1+1\nEND1\nM30"),
        (AlarmCode::LoopStructure, 4)
    );
}

#[test]
fn loops_inside_a_loop_body_run_with_goto_inside_them() {
    check(
        "#1=0\nWHILE [#1 LT 3] DO1\n#1=#1+1\nIF [#1 EQ 2] GOTO 20\n#5=#5+1\nN20 #6=#6+1\nEND1",
        &[(5, v(2.0)), (6, v(3.0))],
    );
}

#[test]
fn do_without_while_loops_until_a_goto_leaves() {
    check(
        "#1=0\nDO1\n#1=#1+1\nIF [#1 GE 7] GOTO 9\nEND1\nN9 #2=#1",
        &[(2, v(7.0))],
    );
}

#[test]
fn end_without_do_is_an_alarm() {
    assert_eq!(alarm("#1=1\nEND1\nM30"), (AlarmCode::LoopStructure, 2));
}

#[test]
fn overlapping_loops_are_an_alarm() {
    assert_eq!(
        alarm("WHILE [#1 LT 1] DO1\nWHILE [#2 LT 1] DO2\n#1=1\nEND1\nEND2\nM30"),
        (AlarmCode::LoopStructure, 4)
    );
}

#[test]
fn a_loop_number_beyond_three_is_an_alarm_on_fanuc() {
    assert_eq!(
        alarm("WHILE [#1 LT 1] DO4\nEND4\nM30"),
        (AlarmCode::LoopStructure, 1)
    );
}

#[test]
fn a_do_with_no_end_is_an_alarm() {
    assert_eq!(
        alarm("WHILE [#1 GT 1] DO1\n#1=1\nM30"),
        (AlarmCode::LoopStructure, 1)
    );
}

#[test]
fn an_endless_loop_stops_at_the_limit_with_an_alarm() {
    let mut options = Options::default();
    options.limits.jumps = 1000;
    let alarms: Vec<_> = interpret_str("N1 #1=#1+1\nGOTO 1\n", &Machine::default(), options)
        .filter_map(Result::err)
        .collect();
    assert_eq!(alarms.last().unwrap().code, AlarmCode::MacroLimit);
}

#[test]
fn loop_counters_drive_moves() {
    let moves = ends(
        "G90 G1 F100.\n#1=1\nWHILE [#1 LE 3] DO1\nX[#1*10] Y-#1\n#1=#1+1\nEND1\nM30",
        MemoryLibrary::new(),
    );
    assert_eq!(
        moves,
        vec![[10.0, -1.0, 0.0], [20.0, -2.0, 0.0], [30.0, -3.0, 0.0]]
    );
}

#[test]
fn g_codes_come_from_variables() {
    let moves = ends(
        "#8=1\n#9=91\nG#8 G#9 X2. F100.\nX2.\nM30",
        MemoryLibrary::new(),
    );
    assert_eq!(moves, vec![[2.0, 0.0, 0.0], [4.0, 0.0, 0.0]]);
}

#[test]
fn values_given_to_addresses_are_rounded_to_the_least_increment() {
    let moves = ends("#1=1.23456\nG90 G0 X#1\nM30", MemoryLibrary::new());
    assert_eq!(moves[0][0], 1.235);
}

#[test]
fn a_variable_in_an_address_is_read_with_a_decimal_point() {
    // X10 is 0.010 mm on the FANUC profile; #1=10 gives X10.000.
    let moves = ends("#1=10\nG90 G0 X#1\nX10\nM30", MemoryLibrary::new());
    assert_eq!(moves, vec![[10.0, 0.0, 0.0], [0.01, 0.0, 0.0]]);
}

// Calls.

#[test]
fn m98_calls_and_m99_returns_to_the_next_block() {
    let lib = library(&[(100, "O100\nG91 G1 X1. F100.\nM99")]);
    let moves = ends("G90 G0 X-1.\nM98 P100\nG90 G0 Y5.\nM30", lib);
    assert_eq!(
        moves,
        vec![[-1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 5.0, 0.0]]
    );
}

#[test]
fn m98_l_repeats_the_subprogram() {
    let lib = library(&[(100, "O100\nG91 G1 X1. F100.\nM99")]);
    let moves = ends("M98 P100 L3\nM30", lib);
    assert_eq!(moves.last().unwrap(), &[3.0, 0.0, 0.0]);
    assert_eq!(moves.len(), 3);
}

#[test]
fn fanuc_m98_p_with_more_than_four_digits_holds_the_repeats() {
    let lib = library(&[(4949, "O4949\nG91 G1 X1. F100.\nM99")]);
    let moves = ends("M98 P54949\nM30", lib);
    assert_eq!(moves.len(), 5);
}

#[test]
fn subprograms_after_m30_in_the_same_file_are_found() {
    let moves = ends(
        "%\nO1\nM98 P2\nM98 P3\nM30\nO2\nG90 G0 X2.\nM99\nO3\nG90 G0 Y3.\nM99\n%",
        MemoryLibrary::new(),
    );
    assert_eq!(moves, vec![[2.0, 0.0, 0.0], [2.0, 3.0, 0.0]]);
}

#[test]
fn m99_p_returns_to_a_sequence_number_of_the_caller() {
    let lib = library(&[(7, "O7\nM99 P50")]);
    let (_, alarms, values) = run_with("M98 P7\n#1=1\nN50 #2=2\nM30", &Machine::default(), lib);
    assert!(alarms.iter().all(|a| !a.is_error()), "{alarms:?}");
    assert_eq!((values[1], values[2]), (S, v(2.0)));
}

#[test]
fn m99_in_a_main_program_ends_the_run_with_a_warning_after_its_passes() {
    let (segments, alarms, _) =
        run_with("G0 X1.\nM99\n", &Machine::default(), MemoryLibrary::new());
    assert!(alarms
        .iter()
        .any(|a| a.code == AlarmCode::MacroLimit && !a.is_error()));
    assert!(matches!(
        segments.last().unwrap().kind,
        SegmentKind::End {
            kind: vcnc::motion::EndKind::M99
        }
    ));
    let mut options = Options::default();
    options.limits.main_program_passes = 3;
    let moves = interpret_str("G91 G0 X1.\nM99\n", &Machine::default(), options)
        .filter_map(|item| item.ok()?.into_segment())
        .filter(|s| matches!(s.kind, SegmentKind::Rapid { .. }))
        .count();
    assert_eq!(moves, 3);
}

#[test]
fn a_missing_subprogram_is_an_alarm_naming_it() {
    assert_eq!(
        alarm("G0 X1.\nM98 P4321\nM30"),
        (AlarmCode::ProgramNotFound, 2)
    );
}

#[test]
fn calls_nested_too_deep_are_an_alarm() {
    let lib = library(&[(5, "O5\nM98 P5\nM99")]);
    let (_, alarms, _) = run_with("M98 P5\nM30", &Machine::default(), lib);
    assert_eq!(alarms.last().unwrap().code, AlarmCode::MacroLimit);
}

#[test]
fn a_block_runs_its_move_before_its_call() {
    let lib = library(&[(20, "O20\n#1=#5001\nM99")]);
    let (_, _, values) = run_with("G90 G0 X7. M98 P20\nM30", &Machine::default(), lib);
    assert_eq!(values[1], v(7.0));
}

#[test]
fn g65_passes_arguments_as_local_variables_of_a_new_level() {
    let lib = library(&[(9000, "O9000\n#100=#1+#2+#24\n#101=#26\n#5=99\nM99")]);
    let (_, alarms, values) =
        run_with("#5=1\nG65 P9000 A1. B2. X3.\nM30", &Machine::default(), lib);
    assert!(alarms.iter().all(|a| !a.is_error()), "{alarms:?}");
    assert_eq!(values[100], v(6.0));
    assert_eq!(values[101], S);
    // The caller's #5 is untouched by the macro's own #5.
    assert_eq!(values[5], v(1.0));
}

#[test]
fn g65_argument_specification_one_maps_the_letters() {
    let lib = library(&[(9001, "O9001\n#100=#7\n#101=#8\n#102=#9\n#103=#11\n#104=#13\n#105=#17\n#106=#18\n#107=#19\n#108=#20\n#109=#21\n#110=#22\n#111=#23\n#112=#25\n#113=#3\n#114=#4\n#115=#5\n#116=#6\nM99")]);
    let (_, alarms, values) = run_with(
        "G65 P9001 C3. I4. J5. K6. D7. E8. F9. H11. M13. Q17. R18. S19. T20. U21. V22. W23. Y25.\nM30",
        &Machine::default(),
        lib,
    );
    assert!(alarms.iter().all(|a| !a.is_error()), "{alarms:?}");
    let got: Vec<f64> = (100..=116).map(|n| values[n].unwrap()).collect();
    assert_eq!(
        got,
        vec![7., 8., 9., 11., 13., 17., 18., 19., 20., 21., 22., 23., 25., 3., 4., 5., 6.]
    );
}

#[test]
fn g65_argument_specification_two_repeats_i_j_k() {
    let lib = library(&[(
        9002,
        "O9002\n#100=#4\n#101=#5\n#102=#6\n#103=#7\n#104=#8\n#105=#9\n#106=#10\nM99",
    )]);
    let (_, _, values) = run_with(
        "G65 P9002 A1. I2. J3. K4. I5. J6. K7. I8.\nM30",
        &Machine::default(),
        lib,
    );
    let got: Vec<Option<f64>> = (100..=106).map(|n| values[n]).collect();
    assert_eq!(got, vec![v(2.), v(3.), v(4.), v(5.), v(6.), v(7.), v(8.)]);
}

#[test]
fn mixed_argument_specifications_let_the_later_word_win() {
    // FANUC's own example: I-3. I4. D5. gives #4=-3, #7=5 (D after the second I).
    let lib = library(&[(9003, "O9003\n#100=#4\n#101=#7\nM99")]);
    let (_, _, values) = run_with(
        "G65 P9003 A1. B2. I-3. I4. D5.\nM30",
        &Machine::default(),
        lib,
    );
    assert_eq!((values[100], values[101]), (v(-3.0), v(5.0)));
}

#[test]
fn g65_arguments_without_a_decimal_point_are_in_least_increments() {
    let lib = library(&[(9004, "O9004\n#100=#24\n#101=#19\nM99")]);
    let (_, _, values) = run_with("G65 P9004 X10 S10\nM30", &Machine::default(), lib);
    assert_eq!((values[100], values[101]), (v(0.01), v(10.0)));
}

#[test]
fn g65_l_calls_the_macro_again_with_the_same_arguments() {
    let lib = library(&[(9005, "O9005\n#100=#100+#1\n#1=0\nM99")]);
    let (_, _, values) = run_with("#100=0\nG65 P9005 L4 A2.\nM30", &Machine::default(), lib);
    assert_eq!(values[100], v(8.0));
}

#[test]
fn g66_calls_the_macro_after_each_move_until_g67() {
    // The macro drills at each position the moves reach.
    let lib = library(&[(9010, "O9010\nG91 G1 Z-#26 F100.\nG0 Z#26\nG90\nM99")]);
    let moves = ends("G90 G0 X0 Y0\nG66 P9010 Z5.\nX10.\nY10.\nG67\nX0\nM30", lib);
    assert_eq!(
        moves,
        vec![
            [10.0, 0.0, 0.0],
            [10.0, 0.0, -5.0],
            [10.0, 0.0, 0.0],
            [10.0, 10.0, 0.0],
            [10.0, 10.0, -5.0],
            [10.0, 10.0, 0.0],
            [0.0, 10.0, 0.0],
        ]
    );
}

#[test]
fn g66_does_not_call_after_blocks_without_a_move() {
    let lib = library(&[(9011, "O9011\n#100=#100+1\nM99")]);
    let (_, _, values) = run_with(
        "#100=0\nG66 P9011\nF100.\nG0 X1.\nS1000\nG67\nG0 X2.\nM30",
        &Machine::default(),
        lib,
    );
    assert_eq!(values[100], v(1.0));
}

#[test]
fn haas_m97_calls_a_sequence_number_of_the_same_program() {
    let machine = Machine::default().with_profile(ProfileName::Haas).unwrap();
    let (segments, alarms, _) = run_with(
        "G90 G0 X-1.\nM97 P100 L2\nM30\nN100 G91 G0 X1.\nM99\n",
        &machine,
        MemoryLibrary::new(),
    );
    assert!(alarms.iter().all(|a| !a.is_error()), "{alarms:?}");
    let rapids = segments
        .iter()
        .filter(|s| matches!(s.kind, SegmentKind::Rapid { .. }))
        .count();
    assert_eq!(rapids, 3);
}

#[test]
fn syntec_m98_h_calls_a_label_and_m30_in_a_subprogram_returns() {
    let machine = Machine::default()
        .with_profile(ProfileName::Syntec)
        .unwrap();
    let lib = library(&[(55, "O55\n#100=#100+1\nM30")]);
    let (segments, alarms, values) = run_with(
        "#100=0\nM98 H100\nM98 P55\nM30\nN100 #101=1\nM99\n",
        &machine,
        lib,
    );
    assert!(alarms.iter().all(|a| !a.is_error()), "{alarms:?}");
    assert_eq!((values[100], values[101]), (v(1.0), v(1.0)));
    assert_eq!(
        segments
            .iter()
            .filter(|s| matches!(s.kind, SegmentKind::End { .. }))
            .count(),
        1
    );
}

#[test]
fn local_variables_of_the_caller_are_seen_by_an_m98_subprogram() {
    let lib = library(&[(30, "O30\n#2=#1*2\nM99")]);
    let (_, _, values) = run_with("#1=4\nM98 P30\nM30", &Machine::default(), lib);
    assert_eq!(values[2], v(8.0));
}

#[test]
fn loops_in_a_subprogram_called_from_a_loop() {
    let lib = library(&[(
        40,
        "O40\n#3=0\nWHILE [#3 LT 2] DO1\n#100=#100+1\n#3=#3+1\nEND1\nM99",
    )]);
    let (_, alarms, values) = run_with(
        "#100=0\n#1=0\nWHILE [#1 LT 3] DO1\nM98 P40\n#1=#1+1\nEND1\nM30",
        &Machine::default(),
        lib,
    );
    assert!(alarms.iter().all(|a| !a.is_error()), "{alarms:?}");
    assert_eq!(values[100], v(6.0));
}

#[test]
fn an_alarm_in_a_subprogram_points_into_its_file() {
    let lib = library(&[(66, "O66\nG0 X1.\n#1=1/0\nM99")]);
    let (_, alarms, _) = run_with("M98 P66\nM30", &Machine::default(), lib);
    let a = alarms.iter().find(|a| a.is_error()).unwrap();
    let span = a.span.unwrap();
    assert_eq!((span.file, span.line), (FileId(1), 3));
}

#[test]
fn macro_statements_and_words_in_one_block_run_statements_first() {
    let moves = ends("#1=3 G90 G0 X#1\nM30", MemoryLibrary::new());
    assert_eq!(moves[0], [3.0, 0.0, 0.0]);
}

#[test]
fn a_streamed_main_program_that_jumps_is_loaded_and_runs_on() {
    // Jumps and loops need the text; interpret_str gives it, so the stream turns into memory.
    let moves = ends(
        "G90 G1 F100.\n#1=0\nN10 #1=#1+1\nX#1\nIF [#1 LT 4] GOTO 10\nY1.\nM30",
        MemoryLibrary::new(),
    );
    assert_eq!(moves.len(), 5);
    assert_eq!(moves[4], [4.0, 1.0, 0.0]);
}

/// The Syntec manual's G65 and G66 examples (files 46 and 47) call O0010, which the manual does
/// not print. With a stand-in O0010 that moves by its arguments (`G91 G01 X#24 Y#25`), the calls
/// themselves are checked: G65 P10 L20 runs it 20 times with X10 Y10 (#24, #25); G66 P10 L2
/// runs it twice after each move block until G67, each time with the arguments of the G66
/// block.
#[test]
fn syntec_manual_g65_and_g66_calls_with_a_stand_in_macro() {
    let Some(shared) = common::shared_dir() else {
        return;
    };
    let example = |name: &str| {
        let path = shared.join("spec/examples/syntec").join(name);
        std::fs::read_to_string(path).expect("the example is in ../shared")
    };
    let stand_in = || {
        let mut library = MemoryLibrary::new();
        library.insert(10, FileId(7), "O0010\nG91 G01 X#24 Y#25 F100.\nM99\n");
        library
    };
    let machine = Machine::default()
        .with_profile(ProfileName::Syntec)
        .unwrap();
    let (segments, alarms, _) = run_with(&example("46-g65-macro-call.nc"), &machine, stand_in());
    assert!(alarms.iter().all(|a| !a.is_error()), "{alarms:?}");
    let expected: Vec<[f64; 3]> = (1..=20)
        .map(|k| [10.0 * f64::from(k), 10.0 * f64::from(k), 0.0])
        .collect();
    assert_eq!(common::variables::move_ends(&segments), expected);

    let (segments, alarms, _) = run_with(&example("47-g66-modal-macro.nc"), &machine, stand_in());
    assert!(alarms.iter().all(|a| !a.is_error()), "{alarms:?}");
    assert_eq!(
        common::variables::move_ends(&segments),
        [
            [20.0, 0.0, 0.0],
            [30.0, 10.0, 0.0],
            [40.0, 20.0, 0.0],
            [40.0, 40.0, 0.0],
            [50.0, 50.0, 0.0],
            [60.0, 60.0, 0.0],
        ]
    );
}
