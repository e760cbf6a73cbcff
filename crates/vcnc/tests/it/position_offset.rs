//! G45/G46/G47/G48 tool position offset (spec iso-syntec-milling.md 1.27): the Syntec manual's
//! example, the signed-zero table, and the alarms.

use crate::common::{check_on, shared_dir};
use vcnc::machine::ToolOffset;
use vcnc::{Machine, ProfileName};

/// A Syntec machine with D1 = `d`.
fn machine(d: f64) -> Machine {
    let mut machine = Machine::default()
        .with_profile(ProfileName::Syntec)
        .unwrap();
    machine.tool_offsets.insert(
        1,
        ToolOffset {
            number: 1,
            radius: d,
            ..ToolOffset::default()
        },
    );
    machine
}

/// The manual's example (000:L2031-2100, file examples/syntec/38-g45-g48-tool-offset.nc) with
/// D01 = 10: the header's point list 70,40 - 140,40 - 140,80 - 160,80 - 160,40 - 200,40 -
/// 240,80 (arc about 200,80, radius 30 + d) - 240,110 - 230,110 - 210,130 (arc about 230,130,
/// radius 30 - d) - 210,140 - 70,140 - 70,40. The last block `G46 G00 X80.0 Y-50.0` in G91
/// from 70,40 goes to 140,0 by the rule (X 80 - d, Y -50 + d); the header's "0,0" would need
/// a sign the manual's table lost.
#[test]
fn syntec_example_38() {
    let Some(shared) = shared_dir() else {
        return;
    };
    let text =
        std::fs::read_to_string(shared.join("spec/examples/syntec/38-g45-g48-tool-offset.nc"))
            .unwrap();
    check_on(
        &machine(10.0),
        &text,
        "
        rapid X70 Y40 Z0
        line X140 Y40 Z0 F120
        line X140 Y80 Z0 F120
        line X160 Y80 Z0 F120
        line X160 Y40 Z0 F120
        line X200 Y40 Z0 F120
        arc ccw xy X240 Y80 Z0 C(200,80,0) F120
        line X240 Y110 Z0 F120
        line X230 Y110 Z0 F120
        arc cw xy X210 Y130 Z0 C(230,130,0) F120
        line X210 Y140 Z0 F120
        line X70 Y140 Z0 F120
        line X70 Y40 Z0 F120
        rapid X140 Y0 Z0
        end EndOfText
        alarm missing_program_end line 27",
    );
}

/// The manual's table (spec 1.27, D1 = 10): in G91 a zero word moves by the offset in the
/// direction of its sign; in G90 a word that does not move the axis gets no offset. One block
/// only: the next move is not offset.
#[test]
fn a_zero_word_takes_the_direction_of_its_sign_in_g91_only() {
    for (block, y) in [
        ("G91 G45 Y0 D1", 10),
        ("G91 G45 Y-0 D1", -10),
        ("G91 G46 Y0 D1", -10),
        ("G91 G46 Y-0 D1", 10),
        ("G90 G45 Y0 D1", 0),
        ("G90 G46 Y-0 D1", 0),
    ] {
        let expected = if y == 0 {
            "line X20 Y0 Z0 F100\nend M30".to_string()
        } else {
            format!("line X0 Y{y} Z0 F100\nline X20 Y{y} Z0 F100\nend M30")
        };
        check_on(
            &machine(10.0),
            &format!("G1 F100.\n{block}\nG90 X20.\nM30"),
            &expected,
        );
    }
}

#[test]
fn g47_and_g48_offset_twice_in_g90_and_a_negative_value_reverses() {
    check_on(
        &machine(-2.0),
        "G90 G1 G47 X50. D1 F100.\nG48 Y30.\nM30",
        "
        line X46 Y0 Z0 F100
        line X46 Y34 Z0 F100
        end M30",
    );
}

#[test]
fn alarms_with_compensation_and_on_arcs_other_than_quarters() {
    check_on(
        &machine(5.0),
        "G1 G41 X10. D1 F100.\nG45 X20.\nM30",
        "alarm position_offset line 2",
    );
    check_on(
        &machine(5.0),
        "G1 X10. F100.\nG45 G3 X20. Y10. R10.\nM30",
        "
        line X10 Y0 Z0 F100
        alarm position_offset line 2",
    );
    // A half circle.
    check_on(
        &machine(5.0),
        "G1 X10. F100.\nG45 G3 X30. I10.\nM30",
        "
        line X10 Y0 Z0 F100
        alarm position_offset line 2",
    );
}
