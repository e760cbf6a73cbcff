//! Cutter radius compensation (G40/G41/G42) through the interpreter: the FANUC 0M manual's
//! worked example and start-ups (spec iso-fanuc0m-mitsubishi.md A.22), blocks without motion in
//! the plane, alarms, and a property: a compensated pocket keeps the tool radius from its walls.

use crate::common::{check_on, shared_dir};
use vcnc::machine::ToolOffset;
use vcnc::{Machine, ProfileName};

fn machine_with_radius(number: u32, radius: f64) -> Machine {
    let mut machine = Machine::default();
    set_offset(&mut machine, number, 0.0, radius);
    machine
}

/// Sets offset `number` to a length and a radius.
fn set_offset(machine: &mut Machine, number: u32, length: f64, radius: f64) {
    machine.tool_offsets.insert(
        number,
        ToolOffset {
            number,
            length,
            radius,
            ..ToolOffset::default()
        },
    );
}

/// Example 1 (001:L971-1000, file examples/fanuc0m/16-g41-g40-example1-frag.nc), D12 = 5: the
/// tool-centre points the spec works out, and at I (an outer corner of 77.47 degrees) the two
/// extension points of a sharp corner, the second one a move of the next block.
#[test]
fn fanuc_0m_example_1() {
    check_on(
        &machine_with_radius(12, 5.0),
        "G90 G00 X-20. Y-20.
         G01 G41 X0 Y0 D12 F80.
         Y35.
         X20.
         G03 X25. Y60. R65.
         G02 X65. R-25.
         G03 X70. Y35. R65.
         G01 X90.
         Y0.
         X45. Y10.
         X0 Y0
         X-20. Y-20.
         G40
         M30",
        "
        rapid X-20 Y-20 Z0
        line X-5 Y0 Z0 F80
        line X-5 Y40 Z0 F80
        line X16.5685 Y40 Z0 F80
        arc ccw xy X19.9799 Y58.4472 Z0 C(-40,60,0) F80
        arc cw xy X70.0201 Y58.4472 Z0 C(45,75,0) F80
        arc ccw xy X73.4315 Y40 Z0 C(130,60,0) F80
        line X95 Y40 Z0 F80
        line X95 Y-5 Z0 F80
        line X93.7963 Y-5.9656 Z0 F80
        line X45 Y4.878 Z0 F80
        line X2.506 Y-4.5651 Z0 F80
        line X-16.4645 Y-23.5355 Z0 F80
        line X-20 Y-20 Z0 F80
        end M30",
    );
}

/// Start-up (a) of the manual (001:L885-902, file examples/fanuc0m/12-g42-start-a-frag.nc),
/// D11 = 4, with a Z move and a coolant code between two elements: two blocks without motion in
/// the plane, so the arc ends perpendicular to itself (look-ahead of two blocks).
#[test]
fn g42_start_up_and_blocks_without_motion_in_the_plane() {
    check_on(
        &machine_with_radius(11, 4.0),
        "G90 G00 X110. Y-20.
         G01 G42 X92. Y0 D11 F80.
         Y52.
         G03 X84. Y60. R8.
         G01 Z-1.
         M08
         X0
         Y0
         G40 X-20.
         M30",
        "
        rapid X110 Y-20 Z0
        line X96 Y0 Z0 F80
        line X96 Y52 Z0 F80
        arc ccw xy X84 Y64 Z0 C(84,52,0) F80
        line X84 Y64 Z-1 F80
        coolant on
        line X-4 Y64 Z-1 F80
        line X-4 Y0 Z-1 F80
        line X-20 Y0 Z-1 F80
        end M30",
    );
}

/// One block without motion in the plane: the corner is still known, and the Z move is made at
/// the corner point (outer corners of 90 degrees: the offset lines' intersection).
#[test]
fn a_z_move_between_two_elements_is_made_at_the_corner() {
    check_on(
        &machine_with_radius(1, 5.0),
        "G0 X-10. Y-10.
         G1 G41 X0 Y0 D1 F100.
         Y50.
         Z-1.
         X50.
         Y0
         X0
         G40 X-10. Y-10.
         M30",
        "
        rapid X-10 Y-10 Z0
        line X-5 Y0 Z0 F100
        line X-5 Y55 Z0 F100
        line X-5 Y55 Z-1 F100
        line X55 Y55 Z-1 F100
        line X55 Y-5 Z-1 F100
        line X0 Y-5 Z-1 F100
        line X-10 Y-10 Z-1 F100
        end M30",
    );
}

#[test]
fn compensation_cannot_start_in_an_arc_and_an_arc_smaller_than_the_tool_alarms() {
    let machine = machine_with_radius(1, 5.0);
    check_on(
        &machine,
        "G1 X10. F100.\nG02 G41 X20. R5. D1\nM30",
        "
        line X10 Y0 Z0 F100
        alarm cutter_compensation line 2",
    );
    // G41 on a counter-clockwise arc of radius 3 with a tool of radius 5: the tool is inside.
    check_on(
        &machine,
        "G1 G41 X10. Y0 D1 F100.\nG3 X10. Y6. R3.\nM30",
        "alarm cutter_compensation line 2",
    );
}

/// A groove narrower than the tool: the compensated bottom of the groove would run backwards
/// between its two inner corners. The control stops before that block (FANUC alarm 041); the
/// moves before it are made.
#[test]
fn a_groove_narrower_than_the_tool_is_interference() {
    check_on(
        &machine_with_radius(1, 5.0),
        "G0 X0 Y30.
         G1 G41 X0 Y20. D1 F100.
         Y0
         X6.
         Y20.
         G40 Y30.
         M30",
        "
        rapid X0 Y30 Z0
        line X5 Y20 Z0 F100
        line X5 Y5 Z0 F100
        alarm cutter_compensation line 4",
    );
}

/// The FANUC 0M manual's contour example O2127 (001:L1125-1237, spec A.23, file
/// examples/fanuc0m/17-o2127-g43-g42-contour.nc): G42 with D11 = 5 round lines and arcs given
/// partly in G91, the tool-centre points the example's header works out. At the 90-degree outer
/// corner after the R12 arc the arc's circle is extended to meet the next path at (25.101, 37);
/// the last element ends perpendicular because `G00 Z20.` has no motion in the plane; the lone
/// `G40` moves the tool back onto the programmed point. The R12 arc has the tool inside it:
/// FANUC 0M's automatic G62 (001 L1533) feeds its tool centre (radius 7) at 100 * 7 / 12.
#[test]
fn fanuc_0m_contour_example_o2127() {
    let Some(shared) = shared_dir() else {
        return;
    };
    let path = shared.join("spec/examples/fanuc0m/17-o2127-g43-g42-contour.nc");
    let text = std::fs::read_to_string(&path).expect("the example is in ../shared");
    let mut machine = machine_with_radius(11, 5.0)
        .with_profile(ProfileName::Fanuc0m)
        .unwrap();
    set_offset(&mut machine, 1, -395.452, 0.0);
    check_on(
        &machine,
        &text,
        "
        spindle Clockwise 800
        coolant on
        rapid X-20 Y-20 Z0
        rapid X-20 Y-20 Z-390.452
        line X-20 Y-20 Z-400.452 F60
        line X12 Y7 Z-400.452 F100
        line X52 Y7 Z-400.452 F100
        arc ccw xy X77 Y32 Z-400.452 C(52,32,-400.452) F100
        arc ccw xy X37 Y32 Z-400.452 C(57,32,-400.452) F100
        arc cw xy X25.101 Y37 Z-400.452 C(30,32,-400.452) F58.3333
        line X7 Y37 Z-400.452 F100
        line X7 Y0 Z-400.452 F100
        rapid X7 Y0 Z-375.452
        rapid X12 Y0 Z-375.452
        rapid X12 Y0 Z0
        rapid X0 Y0 Z0
        end M30",
    );
}

/// G41 to G42 in offset mode: the compensated paths of the two elements do not cross, so the
/// first ends perpendicular to itself on the left and a straight move goes to the start of the
/// second on the right; then an inner corner on the new side.
#[test]
fn changing_from_g41_to_g42_in_offset_mode() {
    check_on(
        &machine_with_radius(1, 5.0),
        "G0 X-10. Y0
         G1 G41 X0 Y0 D1 F100.
         X50.
         G42 Y50.
         X100.
         G40 X110.
         M30",
        "
        rapid X-10 Y0 Z0
        line X0 Y5 Z0 F100
        line X50 Y5 Z0 F100
        line X55 Y0 Z0 F100
        line X55 Y45 Z0 F100
        line X100 Y45 Z0 F100
        line X110 Y50 Z0 F100
        end M30",
    );
}

/// A new D in offset mode: the corner at the start of its block is made with the old radius,
/// the corner at its end with the new one, so the block's tool-centre path slants.
#[test]
fn changing_d_in_offset_mode() {
    let mut machine = machine_with_radius(1, 5.0);
    set_offset(&mut machine, 2, 0.0, 2.0);
    check_on(
        &machine,
        "G0 X-10. Y0
         G1 G41 X0 Y0 D1 F100.
         X50.
         Y50. D2
         X0
         G40 X-10.
         M30",
        "
        rapid X-10 Y0 Z0
        line X0 Y5 Z0 F100
        line X45 Y5 Z0 F100
        line X48 Y48 Z0 F100
        line X0 Y48 Z0 F100
        line X-10 Y50 Z0 F100
        end M30",
    );
    // In an arc block the path would change its radius along the arc: refused.
    check_on(
        &machine,
        "G1 G41 X0 Y0 D1 F100.\nX50.\nG3 X60. Y10. R10. D2\nM30",
        "alarm not_supported_yet line 3",
    );
}

/// G28 in offset mode (spec A.22 rule 4): the last element ends perpendicular, the return goes
/// from the tool centre through the intermediate point without compensation, and compensation
/// starts up again with the next motion in the plane. G09 is allowed while compensating.
#[test]
fn g28_cancels_compensation_for_its_block() {
    check_on(
        &machine_with_radius(1, 5.0),
        "G0 X-10. Y0
         G1 G41 X0 Y0 D1 F100.
         G09 X50.
         G28 X60. Y10.
         G1 X0 Y20.
         X20.
         G40 X30.
         M30",
        "
        rapid X-10 Y0 Z0
        line X0 Y5 Z0 F100
        line X50 Y5 Z0 F100
        rapid X60 Y10 Z0
        rapid X0 Y0 Z0
        line X0 Y25 Z0 F100
        line X20 Y25 Z0 F100
        line X30 Y20 Z0 F100
        end M30",
    );
}

/// The old FANUC 0M form `G42 H19` (corpus gcodeworkshop_FANUC0M_0097.nc): on the fanuc0m
/// profile the H of a G41/G42 block without D is the radius offset number, and the length
/// offset in force (H3) stays.
#[test]
fn fanuc_0m_h_form_names_the_radius_offset() {
    let mut machine = machine_with_radius(19, 5.0)
        .with_profile(ProfileName::Fanuc0m)
        .unwrap();
    set_offset(&mut machine, 3, 10.0, 0.0);
    check_on(
        &machine,
        "G0 X-10. Y0\nG43 H3 Z5.\nG1 G42 H19 X0 Y0 F100.\nX50.\nG40 X60.\nM30",
        "
        rapid X-10 Y0 Z0
        rapid X-10 Y0 Z15
        line X0 Y-5 Z15 F100
        line X50 Y-5 Z15 F100
        line X60 Y0 Z15 F100
        end M30",
    );
}

/// Haas keeps cutter diameters in its offset table: D1 = 10 compensates by 5.
#[test]
fn haas_offsets_are_diameters() {
    check_on(
        &machine_with_radius(1, 10.0)
            .with_profile(ProfileName::Haas)
            .unwrap(),
        "G0 X-10. Y0\nG1 G41 X0 Y0 D1 F100.\nX50.\nG40 X60.\nM30",
        "
        rapid X-10 Y0 Z0
        line X0 Y5 Z0 F100
        line X50 Y5 Z0 F100
        line X60 Y0 Z0 F100
        end M30",
    );
}

/// The look-ahead is a profile setting: with one block, a lone Z move already ends the element
/// perpendicular to itself, and the next element is reached by a straight move to its start.
#[test]
fn the_look_ahead_is_a_profile_setting() {
    let mut machine = machine_with_radius(1, 5.0);
    machine.profile.compensation.cutter_comp_look_ahead = 1;
    check_on(
        &machine,
        "G0 X-10. Y-10.
         G1 G41 X0 Y0 D1 F100.
         Y50.
         Z-1.
         X50.
         G40 X60.
         M30",
        "
        rapid X-10 Y-10 Z0
        line X-5 Y0 Z0 F100
        line X-5 Y50 Z0 F100
        line X-5 Y50 Z-1 F100
        line X0 Y55 Z-1 F100
        line X50 Y55 Z-1 F100
        line X60 Y50 Z-1 F100
        end M30",
    );
}

/// Runs a manual example from ../shared/spec/examples on `machine`.
#[track_caller]
fn check_example(file: &str, machine: &Machine, expected: &str) {
    let Some(shared) = shared_dir() else {
        return;
    };
    let path = shared.join("spec/examples").join(file);
    let text = std::fs::read_to_string(&path).expect("the example is in ../shared");
    check_on(machine, &text, expected);
}

/// The Syntec manual's flower slot (000:L1753-1807, spec 1.24, file
/// examples/syntec/34-g41-flower-slot.nc), D01 = 5 as the header suggests: nine arcs, G41, every
/// corner an outer one where the compensated circles meet (R10 arcs with the tool inside: R5;
/// R15 arcs with the tool outside: R20). The corner points were worked out separately by
/// intersecting the compensated circles, e.g. B': circles about (-0.1658,33.9986) R5 and about
/// (18,18) R20 meet at (4.7250,32.9591).
#[test]
fn syntec_flower_slot_example_34() {
    let machine = machine_with_radius(1, 5.0)
        .with_profile(ProfileName::Syntec)
        .unwrap();
    check_example(
        "syntec/34-g41-flower-slot.nc",
        &machine,
        "
        select T1
        spindle Clockwise 1000
        rapid X0 Y0 Z10
        coolant on
        line X0 Y0 Z-10 F600
        line X-0.0829 Y28.9993 Z-10 F600
        arc ccw xy X4.725 Y32.9591 Z-10 C(-0.1658,33.9986,-10) F600
        arc cw xy X33.0471 Y4.8249 Z-10 C(18,18,-10) F600
        arc ccw xy X33.0471 Y-4.8249 Z-10 C(34.3589,0,-10) F600
        arc cw xy X4.8249 Y-33.0471 Z-10 C(18,-18,-10) F600
        arc ccw xy X-4.8249 Y-33.0471 Z-10 C(0,-34.3589,-10) F600
        arc cw xy X-33.0471 Y-4.8249 Z-10 C(-18,-18,-10) F600
        arc ccw xy X-33.0471 Y4.8249 Z-10 C(-34.3589,0,-10) F600
        arc cw xy X-4.725 Y32.9591 Z-10 C(-18,18,-10) F600
        arc ccw xy X0.0829 Y28.9993 Z-10 C(0.1658,33.9986,-10) F600
        rapid X0.0829 Y28.9993 Z10
        rapid X0 Y0 Z10
        coolant off
        spindle Stopped 1000
        end M30",
    );
}

/// The Syntec manual's contour (000:L1854-1880, spec 1.25, file
/// examples/syntec/35-g43-g42-contour.nc), D01 = 10 and H01 = -10: G42 starts in a block
/// without motion; the start-up rapid is followed by two blocks without motion in the plane
/// (the G43 Z move and the plunge), so it ends perpendicular to itself at
/// (10,5) + 10 (0.4472,-0.8944); the first cut goes from there to A' (10,-5). Outer corners:
/// (120,-5); x=120 meets the 45-degree side's path through (117.0711,92.0711) at y=89.1421;
/// that meets y=115 at x=94.1421; y=115 meets the R30 circle about (10,105) at x=38.2843; the
/// circle meets x=0 at y=76.7157. The last side ends perpendicular at (0,5); G40 G49 moves
/// back onto A and lifts by the length offset.
#[test]
fn syntec_contour_example_35() {
    let mut machine = machine_with_radius(1, 10.0)
        .with_profile(ProfileName::Syntec)
        .unwrap();
    set_offset(&mut machine, 1, -10.0, 10.0);
    check_example(
        "syntec/35-g43-g42-contour.nc",
        &machine,
        "
        select T1
        spindle Clockwise 1000
        rapid X14.4721 Y-3.9443 Z15
        rapid X14.4721 Y-3.9443 Z5
        line X14.4721 Y-3.9443 Z-20 F1000
        line X10 Y-5 Z-20 F1000
        line X120 Y-5 Z-20 F1000
        line X120 Y89.1421 Z-20 F1000
        line X94.1421 Y115 Z-20 F1000
        line X38.2843 Y115 Z-20 F1000
        arc cw xy X0 Y76.7157 Z-20 C(10,105,-20) F1000
        line X0 Y5 Z-20 F1000
        rapid X0 Y5 Z5
        rapid X0 Y5 Z15
        rapid X10 Y5 Z15
        spindle Stopped 1000
        end M30",
    );
}
