//! Modal state and motion: numbers, units, distance modes, planes, arcs, feeds, events.

use crate::common::{check, check_with};
use vcnc::ProfileName::*;

#[test]
fn numbers_without_decimal_point_are_least_increments_on_fanuc() {
    check(
        "G0 X25. Y3000 Z5.\nG1 Z-5. F100.\nX36000 Y50.\nM30",
        "
        rapid X25 Y3 Z5
        line X25 Y3 Z-5 F100
        line X36 Y50 Z-5 F100
        end M30",
    );
}

#[test]
fn inch_programs_are_converted_to_millimetres_and_increments_are_tenths_of_a_thou() {
    check(
        "G20 G0 X1. Y10000\nG1 Z-.5 F10.\nM30",
        "
        rapid X25.4 Y25.4 Z0
        line X25.4 Y25.4 Z-12.7 F254
        end M30",
    );
}

#[test]
fn syntec_g70_is_inch_and_g71_metric() {
    check_with(
        Syntec,
        "G70 G0 X1.\nG71 X1.\nM30",
        "
        rapid X25.4 Y0 Z0
        rapid X1 Y0 Z0
        end M30",
    );
}

#[test]
fn g91_moves_relative_to_the_current_position() {
    check(
        "G91 G0 X10. Y5.\nX10.\nG90 X0.\nM30",
        "
        rapid X10 Y5 Z0
        rapid X20 Y5 Z0
        rapid X0 Y5 Z0
        end M30",
    );
}

#[test]
fn modal_motion_and_feed_carry_over_to_later_blocks() {
    check(
        "G1 X10. F300.\nY10.\nG0 Z5.\nX0\nM30",
        "
        line X10 Y0 Z0 F300
        line X10 Y10 Z0 F300
        rapid X10 Y10 Z5
        rapid X0 Y10 Z5
        end M30",
    );
}

#[test]
fn g02_with_i_j_turns_clockwise_about_the_centre() {
    check(
        "G0 X10.\nG2 X0 Y10. I-10. J0 F100.\nM30",
        "
        rapid X10 Y0 Z0
        arc cw xy X0 Y10 Z0 C(0,0,0) F100
        end M30",
    );
}

#[test]
fn full_circle_with_i_and_end_on_start() {
    check(
        "G0 X10.\nG3 I-10. F100.\nM30",
        "
        rapid X10 Y0 Z0
        arc ccw xy X10 Y0 Z0 C(0,0,0) F100
        end M30",
    );
}

#[test]
fn negative_r_takes_the_long_way_round() {
    check(
        "G0 X10.\nG3 X0 Y10. R10. F100.\nG0 X10. Y0\nG3 X0 Y10. R-10.\nM30",
        "
        rapid X10 Y0 Z0
        arc ccw xy X0 Y10 Z0 C(0,0,0) F100
        rapid X10 Y0 Z0
        arc ccw xy X0 Y10 Z0 C(10,10,0) F100
        end M30",
    );
}

#[test]
fn helical_arc_moves_the_third_axis_linearly() {
    check(
        "G0 X10.\nG17 G3 X-10. Y0 Z-5. I-10. F100.\nM30",
        "
        rapid X10 Y0 Z0
        arc ccw xy X-10 Y0 Z-5 C(0,0,0) F100
        end M30",
    );
}

#[test]
fn g18_arcs_use_k_and_i_and_g19_arcs_j_and_k() {
    check(
        "G0 Z10.\nG18 G2 X10. Z0 I0 K-10. F100.\nG19 G3 Y10. Z10. J0 K10.\nM30",
        "
        rapid X0 Y0 Z10
        arc cw zx X10 Y0 Z0 C(0,0,0) F100
        arc ccw yz X10 Y10 Z10 C(10,0,10) F100
        end M30",
    );
}

#[test]
fn i_j_k_are_incremental_even_in_g90() {
    check(
        "G90 G0 X20. Y20.\nG2 X40. Y20. I10. F100.\nM30",
        "
        rapid X20 Y20 Z0
        arc cw xy X40 Y20 Z0 C(30,20,0) F100
        end M30",
    );
}

#[test]
fn syntec_cuts_at_1000_mm_per_min_before_any_f() {
    check_with(
        Syntec,
        "G1 X10.\nM30",
        "
        line X10 Y0 Z0 F1000
        end M30",
    );
}

#[test]
fn g95_feed_is_per_revolution_with_the_spindle_speed() {
    check(
        "S1000 M3\nG95 G1 X10. F.2\nM30",
        "
        spindle Clockwise 1000
        line X10 Y0 Z0 F0.2/rev
        end M30",
    );
}

#[test]
fn g93_inverse_time_feed_needs_f_in_every_block() {
    check(
        "G93 G1 X10. F2.\nX20.\nM30",
        "
        line X10 Y0 Z0 F1/2min
        alarm no_feed_rate line 2",
    );
}

#[test]
fn tool_change_spindle_and_coolant_come_before_the_motion_and_stops_after() {
    check(
        "T1 M6\nS2000 M3 M8 G0 X10.\nM0\nM5 M9\nM1\nM30",
        "
        select T1
        change T1
        spindle Clockwise 2000
        coolant on
        rapid X10 Y0 Z0
        stop Program
        spindle Stopped 2000
        coolant off
        stop Optional
        end M30",
    );
}

#[test]
fn unknown_m_codes_pass_to_the_machine() {
    check(
        "M13\nM88\nM30",
        "
        M13
        M88
        end M30",
    );
}

#[test]
fn dwell_p_is_milliseconds_and_x_with_a_point_is_seconds() {
    check(
        "G4 P2500\nG4 X1.5\nG4 X2500\nM30",
        "
        dwell 2.5
        dwell 1.5
        dwell 2.5
        end M30",
    );
}

#[test]
fn dwell_p_with_a_fraction_is_an_alarm_on_fanuc_and_truncated_on_syntec() {
    check("G4 P2.5\nM30", "alarm decimal_point_not_allowed line 1");
    check_with(
        Syntec,
        "G4 P2.5\nM30",
        "
        dwell 0.002
        end M30",
    );
    check_with(
        Haas,
        "G4 P2.5\nM30",
        "
        dwell 2.5
        end M30",
    );
}

#[test]
fn fanuc_0m_x_written_before_g04_in_inch_mode_dwells_twenty_seconds() {
    // spec/iso-fanuc0m-mitsubishi.md A.8, seed 001 L190-202.
    check_with(
        Fanuc0m,
        "G20\nX2.0 G04\nG04 X2.0\nM30",
        "
        dwell 20
        dwell 2
        end M30",
    );
}

#[test]
fn two_motion_codes_in_a_block_the_last_wins_with_a_warning() {
    check(
        "G0 G1 X10. F100.\nM30",
        "
        line X10 Y0 Z0 F100
        end M30
        alarm same_group_g_codes line 1",
    );
}

#[test]
fn block_skip_runs_the_block_when_the_switch_is_off() {
    check(
        "/G0 X10.\nM30",
        "
        rapid X10 Y0 Z0
        end M30",
    );
}

#[test]
fn tape_marks_and_program_numbers_frame_the_program() {
    check(
        "%\nO1234 (TITLE)\nG0 X1.\n%\nG0 X2.\n",
        "
        rapid X1 Y0 Z0
        end TapeMark",
    );
}

#[test]
fn a_program_without_an_end_warns_at_its_last_block() {
    check(
        "G0 X1.\nG0 X2.",
        "
        rapid X1 Y0 Z0
        rapid X2 Y0 Z0
        end EndOfText
        alarm missing_program_end line 2",
    );
}

#[test]
fn semicolons_end_blocks_and_syntec_double_slash_comments() {
    check_with(
        Syntec,
        "G90 G00 X90.0 Y40.0; // absolute\nG01 X0; G01 Y0;\nM30;",
        "
        rapid X90 Y40 Z0
        line X0 Y40 Z0 F1000
        line X0 Y0 Z0 F1000
        end M30",
    );
}

#[test]
fn batches_give_the_same_stream_as_the_iterator() {
    let program = "G0 X1.\nG1 X2. F100.\nG4 P10\nG2 X4. R1.\nG0 G1 X5.\nM30\n";
    let machine = vcnc::Machine::default();
    let one_by_one: Vec<_> =
        vcnc::interpret_str(program, &machine, vcnc::Options::default()).collect();
    for size in [1, 2, 3, 100] {
        let mut interpreter = vcnc::interpret_str(program, &machine, vcnc::Options::default());
        let mut batched = Vec::new();
        let mut batch = Vec::new();
        while interpreter.next_batch(&mut batch, size) {
            batched.append(&mut batch);
        }
        assert_eq!(batched, one_by_one, "batch size {size}");
    }
}

#[test]
fn taking_items_one_by_one_and_in_batches_by_turns_gives_the_same_stream() {
    // A peck cycle of a thousand pecks (one block, thousands of items), then a compensated
    // contour (items held back until the next move is known), taken by `next` and
    // `next_batch` by turns: every item once, in order.
    let program = "G90 G17 G21 G94\nG00 X10. Y10. Z5.\nG83 X10. Y10. Z-100. R1. Q0.1 F200.\nG80\n\
                   G01 G41 X0 Y0 D1 F100.\nY20.\nX20.\nY0\nG40 X-5. Y-5.\nM30\n";
    let mut machine = vcnc::Machine::default();
    machine.tool_offsets.insert(
        1,
        vcnc::machine::ToolOffset {
            number: 1,
            radius: 2.0,
            ..vcnc::machine::ToolOffset::default()
        },
    );
    let one_by_one: Vec<_> =
        vcnc::interpret_str(program, &machine, vcnc::Options::default()).collect();
    assert!(one_by_one.len() > 3000, "{}", one_by_one.len());
    assert!(
        one_by_one.iter().all(Result::is_ok),
        "{:?}",
        one_by_one.last()
    );
    for (taken, size) in [(1, 1), (3, 7), (2500, 100), (3001, 2)] {
        let mut interpreter = vcnc::interpret_str(program, &machine, vcnc::Options::default());
        let mut mixed = Vec::new();
        let mut batch = Vec::new();
        loop {
            let before = mixed.len();
            mixed.extend(interpreter.by_ref().take(taken));
            let more = interpreter.next_batch(&mut batch, size);
            mixed.append(&mut batch);
            if !more && mixed.len() == before {
                break;
            }
        }
        assert_eq!(mixed, one_by_one, "{taken} items, then a batch of {size}");
    }
}

#[test]
fn fanuc_0m_runs_only_the_last_of_two_m_codes_in_a_block() {
    // spec/iso-fanuc0m-mitsubishi.md A.15, example fanuc0m/06: M03 is ignored, M08 runs.
    check_with(
        Fanuc0m,
        "S600 M03 M08\nM30",
        "
        coolant on
        end M30
        alarm word_not_allowed line 1",
    );
    check(
        "S600 M03 M08\nM30",
        "
        spindle Clockwise 600
        coolant on
        end M30",
    );
}

#[test]
fn a_tool_change_carries_the_offsets_of_the_register_numbered_like_the_tool() {
    use vcnc::motion::ToolGeometry;
    use vcnc::{Machine, Options, SegmentKind};
    let mut machine = Machine::default();
    machine.tool_offsets.insert(
        3,
        vcnc::machine::ToolOffset {
            number: 3,
            length: 120.0,
            length_wear: -0.2,
            radius: 6.0,
            radius_wear: -0.05,
        },
    );
    let changes = |machine: &Machine, program: &str| -> Vec<(u32, Option<ToolGeometry>)> {
        vcnc::interpret_str(program, machine, Options::default())
            .filter_map(|item| match item.ok()?.into_segment()?.kind {
                SegmentKind::ToolChange {
                    tool,
                    geometry,
                    shape,
                } => {
                    // No machine file has tool shapes yet.
                    assert_eq!(shape, None);
                    Some((tool, geometry))
                }
                _ => None,
            })
            .collect()
    };
    let geometry = |length: f64, radius: f64| Some(ToolGeometry { length, radius });
    assert_eq!(
        changes(&machine, "T3 M06\nT9 M06\nM30\n"),
        [(3, geometry(119.8, 5.95)), (9, None)]
    );
    // A register the program rewrote (#2203: the length geometry of H3, FANUC memory C) is read
    // as it stands at the change.
    assert_eq!(
        changes(&machine, "#2203 = 50.\nT3 M06\nM30\n"),
        [(3, geometry(50.0 - 0.2, 5.95))]
    );
}
