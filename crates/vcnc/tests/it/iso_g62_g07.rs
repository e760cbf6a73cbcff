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

/// The default machine on `profile` with a rotary C axis.
fn with_c(profile: ProfileName) -> Machine {
    let mut machine = crate::common::with_c_axis(profile);
    set_radius(&mut machine, 1, 5.0);
    machine
}

/// The machine positions (X, Y, Z, C) where each motion of `program` ends.
fn ends(machine: &Machine, program: &str) -> Vec<[f64; 4]> {
    let run = crate::common::run(program.as_bytes(), machine, vcnc::Options::default());
    if let Some(alarm) = run.error() {
        panic!("{alarm:?}\n{program}");
    }
    run.segments
        .iter()
        .filter_map(|s| s.motion())
        .map(|m| {
            let p = m.to.0;
            [p[0], p[1], p[2], p[vcnc::Axis::C.index()]]
        })
        .collect()
}

fn close(a: f64, b: f64, tolerance: f64) -> bool {
    (a - b).abs() <= tolerance
}

/// Degrees of C for `length` mm on a cylinder of radius 50: length * 180 / (50 pi).
fn degrees(length: f64) -> f64 {
    length * 180.0 / (50.0 * std::f64::consts::PI)
}

#[test]
fn g07_1_turns_surface_lengths_into_degrees_of_c() {
    // A slot round a cylinder of radius 50: 39.2699 mm along the surface is 39.2699 * 180 /
    // (50 pi) = 45.000 degrees of C; the Z move goes with it in the same line. Y, the slot that
    // carries C in the mode, stays where the machine had it.
    let machine = with_c(ProfileName::Fanuc);
    let program = "G90 G54 G00 X0 Y10. Z0 C0\nG07.1 C50.\nG01 Z-5. F100.\nC39.2699\nZ-20. C78.5398\nG07.1 C0\nG00 Z50.\nM30\n";
    let ends = ends(&machine, program);
    let expected = [
        [0.0, 10.0, 0.0, 0.0],
        [0.0, 10.0, -5.0, 0.0],
        [0.0, 10.0, -5.0, 45.0],
        [0.0, 10.0, -20.0, 90.0],
        [0.0, 10.0, 50.0, 90.0],
    ];
    assert_eq!(ends.len(), expected.len(), "{ends:?}");
    for (end, want) in ends.iter().zip(expected) {
        assert!(
            end.iter().zip(want).all(|(a, b)| close(*a, b, 1e-4)),
            "{end:?} != {want:?}"
        );
    }
}

#[test]
fn a_surface_line_keeps_f_along_the_surface() {
    // `Z-20. C78.5398` from (Z -5, 39.2699 mm): 15 mm along Z and 39.2699 mm round, sqrt(15^2 +
    // 39.2699^2) = 42.0372 mm on the surface at F100: the move takes 1 / (100 / 42.0372) min.
    let machine = with_c(ProfileName::Fanuc);
    let program = "G90 G54 G00 X0 Y10. Z0 C0\nG07.1 C50.\nG01 Z-5. F100.\nC39.2699\nZ-20. C78.5398\nG07.1 C0\nM30\n";
    let run = crate::common::run(program.as_bytes(), &machine, vcnc::Options::default());
    let last_cut = run
        .segments
        .iter()
        .rev()
        .find_map(|s| match s.kind {
            vcnc::SegmentKind::Line { feed, .. } => Some(feed),
            _ => None,
        })
        .unwrap();
    let vcnc::motion::Feed::InverseTime(per_minute) = last_cut else {
        panic!("{last_cut:?}");
    };
    assert!(close(per_minute, 100.0 / 42.0372, 1e-5), "{per_minute}");
}

#[test]
fn a_surface_arc_becomes_pieces_on_its_circle() {
    // G02 of radius 10 in the Z-C surface plane (G19: C in the first axis, Z in the second),
    // from (C 0, Z 0) to (C 20, Z 0) round the centre (C 10, Z 0): every piece ends on that
    // circle (C back to mm: degrees * 50 pi / 180) within the tolerance, and the last at C =
    // degrees(20) = 22.918.
    let machine = with_c(ProfileName::Fanuc);
    let program = "G90 G54 G00 X0 Y0 Z0 C0\nG07.1 C50.\nG02 C20. Z0 R10. F200.\nG07.1 C0\nM30\n";
    let ends = ends(&machine, program);
    let cut = &ends[1..];
    assert!(cut.len() > 10, "{} pieces", cut.len());
    for end in cut {
        let c_mm = end[3] * 50.0 * std::f64::consts::PI / 180.0;
        let from_centre = (c_mm - 10.0).hypot(end[2]);
        assert!(close(from_centre, 10.0, 0.002), "{end:?}: {from_centre}");
        assert!(
            end[2] >= -1e-9,
            "G02 from C0 to C20 in G19 bulges to +Z: {end:?}"
        );
    }
    let last = cut.last().unwrap();
    assert!(close(last[3], degrees(20.0), 1e-6), "{last:?}");
}

#[test]
fn cutter_compensation_offsets_the_slot_wall_on_the_surface() {
    // G42 with a tool of radius 5 along +Z at C 0 in G19 (first axis C, second Z): travel
    // (0, 1) in (C, Z) turned clockwise, the tool's right, is (1, 0), +C, so the centre runs at C = 5 mm =
    // degrees(5) = 5.7296.
    let machine = with_c(ProfileName::Fanuc);
    let program = "G90 G54 G00 X0 Y0 Z-10. C0\nG07.1 C50.\nG01 G42 Z0 C0 D1 F100.\nZ30.\nG40 Z40. C0\nG07.1 C0\nM30\n";
    let ends = ends(&machine, program);
    let wall: Vec<_> = ends.iter().filter(|e| close(e[2], 30.0, 1e-6)).collect();
    assert_eq!(wall.len(), 1, "{ends:?}");
    assert!(close(wall[0][3], degrees(5.0), 1e-6), "{ends:?}");
}

#[test]
fn g07_1_is_refused_without_a_rotary_axis_and_absent_on_fanuc_0m() {
    let machine = on(ProfileName::Fanuc);
    let trace = trace_on(&machine, "G07.1 C50.\nM30\n");
    assert!(trace.contains("alarm"), "{trace}");
    let fanuc0m = with_c(ProfileName::Fanuc0m);
    let trace = trace_on(&fanuc0m, "G07.1 C50.\nM30\n");
    assert!(trace.contains("alarm"), "{trace}");
}

#[test]
fn g00_is_refused_in_cylindrical_interpolation() {
    let machine = with_c(ProfileName::Mitsubishi);
    let trace = trace_on(&machine, "G90 G00 Z0 C0\nG07.1 C50.\nG00 C10.\nM30\n");
    assert!(trace.contains("alarm"), "{trace}");
}

/// The C angles where each move of `program` ends, on a machine whose rotary axes roll over by
/// `rule`.
fn c_ends(rule: vcnc::profile::RotaryRollover, program: &str) -> Vec<f64> {
    let mut machine = with_c(ProfileName::Fanuc);
    machine.profile.motion.rotary_rollover = rule;
    ends(&machine, program).iter().map(|e| e[3]).collect()
}

#[test]
fn a_rollover_axis_goes_the_shorter_way_in_g90() {
    use vcnc::profile::RotaryRollover::Shortest;
    // (`G00 C0` at C0 makes no move.) From 0: C350. is 10 degrees back (-10, not +350); then C20. is 30 on (to 20); C400. is
    // 40 modulo 360, 20 on (to 40); C220. is exactly half a turn, taken positively (to 220).
    let program = "G90 G00 C0\nC350.\nC20.\nC400.\nC220.\nM30\n";
    assert_eq!(c_ends(Shortest, program), [-10.0, 20.0, 40.0, 220.0]);
}

#[test]
fn a_rollover_axis_turns_the_way_of_the_sign_and_g91_by_the_amount() {
    use vcnc::profile::RotaryRollover::{BySign, Off, Shortest};
    // By sign from 0: C-90. turns negatively to 90 (by -270, to -270 on the continuous
    // position); C45. turns positively to 45 (by +315: -270 + 315 = 45).
    let program = "G90 G00 C0\nC-90.\nC45.\nM30\n";
    assert_eq!(c_ends(BySign, program), [-270.0, 45.0]);
    // G91 moves by the amount written, past a whole turn, whatever the rule.
    let program = "G90 G00 C0\nG91 C400.\nC-30.\nM30\n";
    for rule in [Off, Shortest, BySign] {
        assert_eq!(c_ends(rule, program), [400.0, 370.0]);
    }
    // Without rollover G90 goes to the angle written.
    assert_eq!(c_ends(Off, "G90 G00 C0\nC350.\nM30\n"), [350.0]);
}

#[test]
fn a_program_ending_in_compensation_still_makes_its_last_moves() {
    // The pocket without G40: M30 ends compensation (a reset), and the corner override lets the
    // last side go (its end perpendicular at (50,5), no corner after it).
    let machine = on(ProfileName::Fanuc0m);
    let program = "G90 G17 G54\nG00 X50. Y20.\nG01 Z-1. F600.\nG41 X50. Y0 D1\nX100.\nY100.\nX0\nY0\nX50.\nM30\n";
    let trace = trace_on(&machine, program);
    assert!(
        trace.ends_with("line X7 Y5 Z-1 F300\nline X50 Y5 Z-1 F600\nend M30"),
        "{trace}"
    );
}
