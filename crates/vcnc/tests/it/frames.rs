//! The coordinate chain: work offsets, G10, G92, G92.1, G52, G53, tool length, reference returns.

use crate::common::{check, check_on, check_with};
use vcnc::machine::{ToolOffset, WorkOffsetId};
use vcnc::{Machine, ProfileName};

fn machine_with_tools() -> Machine {
    let mut machine = Machine::default();
    machine.tool_offsets.insert(
        1,
        ToolOffset {
            number: 1,
            length: 100.0,
            ..ToolOffset::default()
        },
    );
    machine.tool_offsets.insert(
        2,
        ToolOffset {
            number: 2,
            length: 50.0,
            length_wear: -0.5,
            ..ToolOffset::default()
        },
    );
    machine.work_offsets.insert(
        WorkOffsetId::Standard(2),
        [-300.0, -200.0, -400.0, 0.0, 0.0, 0.0],
    );
    machine.reference_points[1] = [-10.0, -20.0, -30.0, 0.0, 0.0, 0.0];
    machine
}

#[test]
fn work_offsets_set_by_g10_l2_move_the_program_zero() {
    check(
        "G10 L2 P2 X100. Y50. Z-10.\nG55 G0 X0 Y0 Z0\nG54 X0 Y0 Z0\nM30",
        "
        rapid X100 Y50 Z-10
        rapid X0 Y0 Z0
        end M30",
    );
}

#[test]
fn g10_in_g91_adds_to_the_stored_offset() {
    check(
        "G10 L2 P1 X10.\nG91 G10 L2 P1 X5.\nG90 G0 X0\nM30",
        "
        rapid X15 Y0 Z0
        end M30",
    );
}

#[test]
fn external_offset_p0_shifts_every_work_system() {
    check(
        "G10 L2 P0 X-50.\nG10 L2 P2 X100.\nG55 G0 X0\nG54 X0\nM30",
        "
        rapid X50 Y0 Z0
        rapid X-50 Y0 Z0
        end M30",
    );
}

#[test]
fn g54_1_selects_the_extended_offsets_set_by_g10_l20() {
    check(
        "G10 L20 P7 X11. Y22.\nG54.1 P7 G0 X0 Y0\nM30",
        "
        rapid X11 Y22 Z0
        end M30",
    );
    check("G54.1 P49\nM30", "alarm work_offset_out_of_range line 1");
}

#[test]
fn syntec_g59_1_to_g59_9_are_work_systems_7_to_15() {
    check_with(
        ProfileName::Syntec,
        "G10 L2 P15 X5.\nG59.9 G0 X0\nM30",
        "
        rapid X5 Y0 Z0
        end M30",
    );
}

#[test]
fn g92_makes_the_current_position_read_as_programmed() {
    // spec/iso-syntec-milling.md 1.54: after G92 X5 Y10 Z15 at X20 Y15 Z20 the offsets are 15, 5, 5.
    check(
        "G1 X20. Y15. Z20. F1000.\nG92 X5. Y10. Z15.\nG1 X25. Y25. Z35.\nM30",
        "
        line X20 Y15 Z20 F1000
        line X40 Y30 Z40 F1000
        end M30",
    );
}

#[test]
fn g92_1_cancels_the_g92_shift() {
    check(
        "G0 X20.\nG92 X0\nG0 X10.\nG92.1 X0\nG0 X10.\nM30",
        "
        rapid X20 Y0 Z0
        rapid X30 Y0 Z0
        rapid X10 Y0 Z0
        end M30",
    );
}

#[test]
fn g52_shifts_the_program_zero_inside_the_work_system_until_cancelled() {
    check(
        "G52 X30. Y30.\nG0 X0 Y0\nG91 X20.\nG90 G52 X0 Y0\nG0 X0 Y0\nM30",
        "
        rapid X30 Y30 Z0
        rapid X50 Y30 Z0
        rapid X0 Y0 Z0
        end M30",
    );
}

#[test]
fn g53_moves_in_machine_coordinates_for_one_block() {
    // spec/iso-syntec-milling.md 1.31, example 44.
    check("G92 X-200. Y-100.\nG54 G90 G0 X100. Y200.\nG53 X300. Y100.\nX300. Y0\nG52 X300. Y200.\nX0 Y0\nM30", "
        rapid X300 Y300 Z0
        rapid X300 Y100 Z0
        rapid X500 Y100 Z0
        rapid X500 Y300 Z0
        end M30");
}

#[test]
fn g43_adds_the_length_offset_and_g49_takes_it_away() {
    check_on(
        &machine_with_tools(),
        "G43 H1 G0 Z10.\nG1 Z0 F100.\nG49 G0 Z10.\nM30",
        "
        rapid X0 Y0 Z110
        line X0 Y0 Z100 F100
        rapid X0 Y0 Z10
        end M30",
    );
}

#[test]
fn g43_without_a_z_word_moves_z_by_the_offset_at_once() {
    check_on(
        &machine_with_tools(),
        "G0 Z10.\nG43 H2\nG49\nM30",
        "
        rapid X0 Y0 Z10
        rapid X0 Y0 Z59.5
        rapid X0 Y0 Z10
        end M30",
    );
}

#[test]
fn g44_subtracts_the_offset() {
    check_on(
        &machine_with_tools(),
        "G44 H1 G0 Z10.\nM30",
        "
        rapid X0 Y0 Z-90
        end M30",
    );
}

#[test]
fn a_g10_tool_offset_is_used_by_the_next_g43() {
    check(
        "G10 L10 P5 R25.\nG10 L11 P5 R-1.\nG43 H5 G0 Z0\nM30",
        "
        rapid X0 Y0 Z24
        end M30",
    );
}

#[test]
fn g28_goes_through_the_intermediate_point_then_to_the_reference_point() {
    check(
        "G0 X10. Y10. Z10.\nG91 G28 Z0\nG90 G28 X50. Y0\nM30",
        "
        rapid X10 Y10 Z10
        rapid X10 Y10 Z0
        rapid X50 Y0 Z0
        rapid X0 Y0 Z0
        end M30",
    );
}

#[test]
fn g29_returns_through_the_intermediate_point_to_the_target() {
    check(
        "G0 X10. Y10. Z10.\nG28 Z50.\nG29 Z5.\nM30",
        "
        rapid X10 Y10 Z10
        rapid X10 Y10 Z50
        rapid X10 Y10 Z0
        rapid X10 Y10 Z50
        rapid X10 Y10 Z5
        end M30",
    );
    check("G29 X0\nM30", "alarm no_intermediate_point line 1");
}

#[test]
fn g30_goes_to_the_second_reference_point_by_default() {
    check_on(
        &machine_with_tools(),
        "G0 X5.\nG91 G30 X0 Y0 Z0\nG30 P5 Z0\nM30",
        "
        rapid X5 Y0 Z0
        rapid X-10 Y-20 Z-30
        alarm reference_point_out_of_range line 3",
    );
}

#[test]
fn g28_without_axes_homes_every_axis_on_haas_and_nothing_on_fanuc() {
    check_with(
        ProfileName::Haas,
        "G0 X5. Y5. Z5.\nG28\nM30",
        "
        rapid X5 Y5 Z5
        rapid X0 Y0 Z0
        end M30",
    );
    check(
        "G0 X5.\nG28\nM30",
        "
        rapid X5 Y0 Z0
        end M30
        alarm word_not_allowed line 2",
    );
}

#[test]
fn a_g53_retract_ignores_the_tool_length() {
    check_on(
        &machine_with_tools(),
        "G43 H1 G0 Z10.\nG53 Z0\nG0 Z20.\nM30",
        "
        rapid X0 Y0 Z110
        rapid X0 Y0 Z0
        rapid X0 Y0 Z120
        end M30",
    );
}

#[test]
fn work_offset_from_the_machine_file_applies() {
    check_on(
        &machine_with_tools(),
        "G55 G0 X0 Y0 Z0\nM30",
        "
        rapid X-300 Y-200 Z-400
        end M30",
    );
}
