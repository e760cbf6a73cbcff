//! G62 automatic corner override on the compensated path (spec iso-fanuc0m-mitsubishi.md A.31,
//! FANUC 0M textbook 001 L1533), G07.1 cylindrical interpolation and rotary rollover (issue 23):
//! each case worked by hand in its comment.

use vcnc::{Machine, ProfileName};

use crate::common::plan::{machine as planner_machine, total_seconds, Limits};
use crate::common::trace_on;

/// Writes the cutter radius of register `number`.
fn set_radius(machine: &mut Machine, number: u32, radius: f64) {
    let register = vcnc::machine::ToolOffset {
        number,
        radius,
        ..Default::default()
    };
    machine.tool_offsets.insert(number, register);
}

fn on(profile: ProfileName) -> Machine {
    let mut machine = Machine::default().with_profile(profile).unwrap();
    set_radius(&mut machine, 1, 5.0);
    machine
}

/// A square pocket 0..100 x 0..100 cut counter-clockwise with G41 and a tool of radius 5: the
/// tool centre runs the square 5..95, every corner an inner corner of 90 degrees. `mode` is the
/// group-13 code in force.
fn pocket(mode: &str) -> String {
    format!(
        "G90 G17 G54 {mode}\nG00 X50. Y20.\nG01 Z-1. F600.\nG41 X50. Y0 D1\nX100.\nY100.\nX0\nY0\nX50.\nG40 X50. Y20.\nM30\n"
    )
}

/// The pocket's trace with the override at the profile's settings (91 degrees, 50 %, Le = Ls =
/// 2 mm): each side of the tool-centre square is cut 2 mm from each corner and fed at 300 there.
/// The start-up block's end (50,5) turns inwards too, but FANUC does not override the corner
/// after a start-up block; the corner before the cancel block (G40 X50. Y20.) is inner and is
/// overridden (FANUC names only the start-up block and a block with G41/G42 after the corner).
const POCKET_OVERRIDDEN: &str = "\
rapid X50 Y20 Z0
line X50 Y20 Z-1 F600
line X50 Y5 Z-1 F600
line X93 Y5 Z-1 F600
line X95 Y5 Z-1 F300
line X95 Y7 Z-1 F300
line X95 Y93 Z-1 F600
line X95 Y95 Z-1 F300
line X93 Y95 Z-1 F300
line X7 Y95 Z-1 F600
line X5 Y95 Z-1 F300
line X5 Y93 Z-1 F300
line X5 Y7 Z-1 F600
line X5 Y5 Z-1 F300
line X7 Y5 Z-1 F300
line X48 Y5 Z-1 F600
line X50 Y5 Z-1 F300
line X50 Y7 Z-1 F300
line X50 Y20 Z-1 F600
end M30";

const POCKET_PLAIN: &str = "\
rapid X50 Y20 Z0
line X50 Y20 Z-1 F600
line X50 Y5 Z-1 F600
line X95 Y5 Z-1 F600
line X95 Y95 Z-1 F600
line X5 Y95 Z-1 F600
line X5 Y5 Z-1 F600
line X50 Y5 Z-1 F600
line X50 Y20 Z-1 F600
end M30";

#[test]
fn g62_splits_the_moves_at_inner_corners_and_halves_their_feed() {
    let machine = on(ProfileName::Fanuc);
    assert_eq!(trace_on(&machine, &pocket("G62")), POCKET_OVERRIDDEN);
}

#[test]
fn without_g62_a_fanuc_leaves_the_corners_alone() {
    let machine = on(ProfileName::Fanuc);
    assert_eq!(trace_on(&machine, &pocket("G64")), POCKET_PLAIN);
}

#[test]
fn fanuc_0m_overrides_inner_corners_whenever_compensation_is_on() {
    // 001 L1533: "when G41/G42 is started the control executes G62 by itself".
    let machine = on(ProfileName::Fanuc0m);
    assert_eq!(trace_on(&machine, &pocket("")), POCKET_OVERRIDDEN);
    // G61 of the same group cancels it: exact stops, no override.
    assert!(!trace_on(&machine, &pocket("G61")).contains("F300"));
}

#[test]
fn mitsubishi_overrides_in_g62_only_and_syntec_keeps_its_own_g62() {
    let mitsubishi = on(ProfileName::Mitsubishi);
    assert_eq!(trace_on(&mitsubishi, &pocket("")), POCKET_PLAIN);
    assert_eq!(trace_on(&mitsubishi, &pocket("G62")), POCKET_OVERRIDDEN);
    // Syntec's G62 is its curved-surface cutting mode (spec 1.34), like G64.
    let syntec = on(ProfileName::Syntec);
    assert!(!trace_on(&syntec, &pocket("G62")).contains("F300"));
}

#[test]
fn outer_corners_are_not_overridden() {
    // The same square run clockwise with G41 puts the tool outside it: every corner is outer.
    // The cancel turns inwards by 45 degrees: an inner angle of 135, above the 91 allowed.
    let machine = on(ProfileName::Fanuc);
    let program = "G90 G17 G54 G62\nG00 X-20. Y50.\nG01 Z-1. F600.\nG41 X0 Y50. D1\nY100.\nX100.\nY0\nX0\nG40 X-20. Y-20.\nM30\n";
    let trace = trace_on(&machine, program);
    assert!(!trace.contains("F300"), "{trace}");
}

#[test]
fn an_inner_arc_is_fed_by_the_ratio_of_its_radii() {
    // A G03 circle of radius 20 about (50,50) with G41: the tool (radius 5) is inside it and its
    // centre runs a circle of 15, fed at 600 * 15 / 20 = 450 so that the contour gets 600.
    let machine = on(ProfileName::Fanuc);
    let program = "G90 G17 G54 G62\nG00 X50. Y50.\nG01 Z-1. F600.\nG41 X70. Y50. D1\nG03 I-20.\nG01 G40 X50. Y50.\nM30\n";
    let trace = trace_on(&machine, program);
    assert!(trace.contains("C(50,50,-1) F450"), "{trace}");
}

#[test]
fn the_override_lengthens_the_pocket_by_the_time_worked_out() {
    // Ten stretches of 2 mm (either side of the four corners and of the corner before the
    // cancel) at 300 instead of 600 mm/min take 20 / 300 - 20 / 600 = 20 / 600 min = 2 s longer. With acceleration near infinite the
    // planner's times are length over feed, so its difference is the same within a few ms.
    let mut machine = planner_machine(&Limits {
        acceleration: 1.0e6,
        ..Limits::default()
    });
    set_radius(&mut machine, 1, 5.0);
    let plain = total_seconds(&pocket("G64"), &machine);
    let overridden = total_seconds(&pocket("G62"), &machine);
    let longer = overridden - plain;
    assert!((longer - 2.0).abs() < 0.01, "{plain} s -> {overridden} s");
}
