//! Hand-checked cutter compensation cases (issue #5, acceptance 3): each a short program with
//! offset D1 = 5 mm and the tool-centre points worked out by hand beside it, FANUC rules (spec
//! iso-fanuc0m-mitsubishi.md A.22, iso-syntec-milling.md 1.24): type A start-up and cancel
//! (perpendicular to the next / last element), inner corners at the intersection of the
//! compensated paths, outer corners of 90 degrees or more at the intersection of the compensated
//! paths, sharper outer corners by two extension points a radius beyond each element.
//! Values with decimals: 5/sqrt(2) = 3.5355. With the cases of `compensation.rs` (12) and the
//! geometry unit tests (the FANUC 0M worked example, four start-ups, corner classes) there are
//! more than 40.

use crate::common::check_on;
use vcnc::machine::ToolOffset;
use vcnc::Machine;

fn machine(radius: f64) -> Machine {
    let mut machine = Machine::default();
    machine.tool_offsets.insert(
        1,
        ToolOffset {
            number: 1,
            radius,
            ..ToolOffset::default()
        },
    );
    machine
}

/// Runs one case with D1 = `radius`: the program then M30; the expected trace then `end M30`
/// unless the case ends in an alarm.
#[track_caller]
fn case(radius: f64, program: &str, expected: &str) {
    let program: Vec<&str> = program.lines().map(str::trim).collect();
    let mut expected: Vec<&str> = expected.lines().map(str::trim).collect();
    if !expected.last().is_some_and(|l| l.starts_with("alarm")) {
        expected.push("end M30");
    }
    check_on(
        &machine(radius),
        &format!("{}\nM30", program.join("\n")),
        &expected.join("\n"),
    );
}

/// One path with G41 and with G42 (`{code}` in `program`): the expected traces of each.
#[track_caller]
fn both_sides(program: &str, left: &str, right: &str) {
    case(5.0, &program.replace("{code}", "G41"), left);
    case(5.0, &program.replace("{code}", "G42"), right);
}

/// The corner cases share this contour: along +X from the origin to X50, then a second line.
#[test]
fn line_line_inner_corner_of_90_degrees() {
    // G41 turning left: the compensated lines y=5 and x=45 meet at (45,5). The same contour
    // programmed in G91 gives the same path.
    let absolute = "G0 X-10. Y0\nG1 G41 X0 Y0 D1 F100.\nX50.\nY50.\nG40 X50. Y60.";
    let incremental = "G0 X-10. Y0\nG91 G1 G41 X10. Y0 D1 F100.\nX50.\nY50.\nG40 X0 Y10.";
    for program in [absolute, incremental] {
        case(
            5.0,
            program,
            "rapid X-10 Y0 Z0
             line X0 Y5 Z0 F100
             line X45 Y5 Z0 F100
             line X45 Y50 Z0 F100
             line X50 Y60 Z0 F100",
        );
    }
}

#[test]
fn line_line_outer_corner_of_90_degrees() {
    // G42 turning left: the compensated lines y=-5 and x=55 meet at (55,-5). G41 with a
    // negative offset is the same.
    for (code, radius) in [("G42", 5.0), ("G41", -5.0)] {
        case(
            radius,
            &format!(
                "G0 X-10. Y0
                 G1 {code} X0 Y0 D1 F100.
                 X50.
                 Y50.
                 G40 X50. Y60."
            ),
            "rapid X-10 Y0 Z0
             line X0 Y-5 Z0 F100
             line X55 Y-5 Z0 F100
             line X55 Y50 Z0 F100
             line X50 Y60 Z0 F100",
        );
    }
}

#[test]
fn corners_of_135_degrees() {
    // G41 turning left by 135 degrees: y=5 meets the second line's compensated path (through
    // (46.4645,-3.5355) along (-1,1)) at x = 46.4645 - 8.5355 = 37.9289.
    // G42 turning left by 135 degrees: the first line runs on a radius to (55,-5); the second
    // line's compensated path, extended a radius back from its start (53.5355,3.5355), begins
    // at (57.0711,0); a straight move joins the two. It ends perpendicular at
    // (0,50) + (3.5355,3.5355).
    both_sides(
        "G0 X-10. Y0
         G1 {code} X0 Y0 D1 F100.
         X50.
         X0 Y50.
         G40 X-10. Y60.",
        "rapid X-10 Y0 Z0
         line X0 Y5 Z0 F100
         line X37.9289 Y5 Z0 F100
         line X-3.5355 Y46.4645 Z0 F100
         line X-10 Y60 Z0 F100",
        "rapid X-10 Y0 Z0
         line X0 Y-5 Z0 F100
         line X55 Y-5 Z0 F100
         line X57.0711 Y0 Z0 F100
         line X3.5355 Y53.5355 Z0 F100
         line X-10 Y60 Z0 F100",
    );
}

#[test]
fn corners_of_45_degrees() {
    // G41 turning right by 45 degrees: y=5 meets the line through (53.5355,3.5355) along
    // (1,-1) at x = 53.5355 - 1.4645 = 52.0711.
    // G42 turning right by 45 degrees: y=-5 meets the line through (46.4645,-3.5355) along
    // (1,-1) at x = 47.9289.
    both_sides(
        "G0 X-10. Y0
         G1 {code} X0 Y0 D1 F100.
         X50.
         X100. Y-50.
         G40 X110. Y-50.",
        "rapid X-10 Y0 Z0
         line X0 Y5 Z0 F100
         line X52.0711 Y5 Z0 F100
         line X103.5355 Y-46.4645 Z0 F100
         line X110 Y-50 Z0 F100",
        "rapid X-10 Y0 Z0
         line X0 Y-5 Z0 F100
         line X47.9289 Y-5 Z0 F100
         line X96.4645 Y-53.5355 Z0 F100
         line X110 Y-50 Z0 F100",
    );
}

#[test]
fn a_straight_continuation_is_no_corner() {
    // Two collinear lines: the tool runs straight through (50,5).
    case(
        5.0,
        "G0 X-10. Y0
         G1 G41 X0 Y0 D1 F100.
         X50.
         X100.
         G40 X110.",
        "rapid X-10 Y0 Z0
         line X0 Y5 Z0 F100
         line X50 Y5 Z0 F100
         line X100 Y5 Z0 F100
         line X110 Y0 Z0 F100",
    );
}

#[test]
fn a_line_into_a_tangent_arc() {
    // G41 on a counter-clockwise R10 arc: the tool is inside, the compensated arc has R5.
    // G42 on the same arc: the tool is outside, the compensated arc has R15.
    both_sides(
        "G0 X-10. Y0
         G1 {code} X0 Y0 D1 F100.
         X50.
         G3 X60. Y10. R10.
         G1 G40 X70. Y10.",
        "rapid X-10 Y0 Z0
         line X0 Y5 Z0 F100
         line X50 Y5 Z0 F100
         arc ccw xy X55 Y10 Z0 C(50,10,0) F100
         line X70 Y10 Z0 F100",
        "rapid X-10 Y0 Z0
         line X0 Y-5 Z0 F100
         line X50 Y-5 Z0 F100
         arc ccw xy X65 Y10 Z0 C(50,10,0) F100
         line X70 Y10 Z0 F100",
    );
}

#[test]
fn line_arc_inner_corner() {
    // A clockwise R10 arc about (60,0) leaving (50,0) upwards, G41: the tool is outside the arc
    // (R15) and inside the corner; y=5 meets the R15 circle at x = 60 - sqrt(200) = 45.8579.
    case(
        5.0,
        "G0 X-10. Y0
         G1 G41 X0 Y0 D1 F100.
         X50.
         G2 X70. Y0 R10.
         G1 G40 X70. Y-10.",
        "rapid X-10 Y0 Z0
         line X0 Y5 Z0 F100
         line X45.8579 Y5 Z0 F100
         arc cw xy X75 Y0 Z0 C(60,0,0) F100
         line X70 Y-10 Z0 F100",
    );
}

#[test]
fn arc_line_inner_corner() {
    // A clockwise R10 arc from (0,0) to (20,0) about (10,0) with G42: the tool is inside it
    // (R5). The arc ends heading -Y into a line (tangent: no corner), which turns right to -X
    // at (20,-50): an inner corner, at (15,-45).
    case(
        5.0,
        "G0 X-10. Y0
         G1 G42 X0 Y0 D1 F100.
         G2 X20. Y0 R10.
         G1 Y-50.
         X-30.
         G40 X-40.",
        "rapid X-10 Y0 Z0
         line X5 Y0 Z0 F100
         arc cw xy X15 Y0 Z0 C(10,0,0) F100
         line X15 Y-45 Z0 F100
         line X-30 Y-45 Z0 F100
         line X-40 Y-50 Z0 F100",
    );
}

#[test]
fn a_full_circle_with_a_start_up_from_its_centre() {
    // The FANUC 0M manual's hole (O4949, 001:L1242-1285): G42 start-up from the centre to
    // (15,0), perpendicular to the clockwise circle's start: (10,0); the circle of R10; the
    // cancel from its end back to the centre.
    case(
        5.0,
        "G1 G42 X15. D1 F100.
         G2 I-15.
         G0 G40 X0 Y0",
        "line X10 Y0 Z0 F100
         arc cw xy X10 Y0 Z0 C(0,0,0) F100
         rapid X0 Y0 Z0",
    );
}

/// Start-up and cancel round the inside of a corner (the material angle at the corner 180
/// degrees or more) end perpendicular to the next and to the last element as everywhere else:
/// the FANUC 0M manual says the start-up vector is always perpendicular to the next path
/// (001:L970, spec A.22 rule 6), and its example 1 starts up at such a corner (B, start-up
/// (-5,0)); the spec reads the cancel the same way ("cancel at an inside corner leaves the
/// vector perpendicular to the last offset block"). The intersection of the paths, which a
/// corner in offset mode takes, is not used: the start-up and the cancel block are not
/// compensated themselves.
#[test]
fn start_up_and_cancel_inside_a_line_line_corner_are_perpendicular() {
    // G41: the start-up along +X turns left into +Y (inner), the cancel along -X turns left
    // again (inner). Start-up end (0,0) + 5 * (-1,0); the last line ends at (0,50) + 5 * (-1,0).
    // The intersections would have been (-5,5) and (-5,45).
    // G42, the same contour mirrored across the X axis: both turns go right, towards the tool;
    // the normal on the right of -Y is -X, so the points mirror too.
    for (code, y) in [("G41", "50"), ("G42", "-50")] {
        case(
            5.0,
            &format!("G0 X-20. Y0\nG1 {code} X0 Y0 D1 F100.\nY{y}.\nG40 X-20."),
            &format!(
                "rapid X-20 Y0 Z0
                 line X-5 Y0 Z0 F100
                 line X-5 Y{y} Z0 F100
                 line X-20 Y{y} Z0 F100"
            ),
        );
    }
}

#[test]
fn start_up_inside_a_hexagon_vertex_lands_half_a_radius_from_the_closing_edge() {
    // The corner of corpus boreyko_O00100 (G41, a start-up along +X into a hexagon's vertex,
    // the next edge turning left by 120 degrees towards (-25,43.3013), direction
    // (-0.5,0.86603)). Start-up end: 5 * (-0.86603,-0.5) = (-4.3301,-2.5). The edge that closes
    // the hexagon at this vertex arrives along (0.5,0.86603), its tool side normal
    // (-0.86603,0.5): the start-up point is 5 * (0.75 - 0.25) = 2.5 from it, half a radius,
    // as on the control. The edge ends at (-25,43.3013) + (-4.3301,-2.5) and the cancel along
    // -X turns left again (inner): perpendicular, then the G40 move.
    case(
        5.0,
        "G0 X-20. Y0
         G1 G41 X0 Y0 D1 F100.
         X-25. Y43.3013
         G40 X-45.",
        "rapid X-20 Y0 Z0
         line X-4.3301 Y-2.5 Z0 F100
         line X-29.3301 Y40.8013 Z0 F100
         line X-45 Y43.3013 Z0 F100",
    );
}

#[test]
fn start_up_into_an_arc_and_cancel_from_it_inside_the_corner_are_perpendicular() {
    // G41: the start-up along (1,1) turns left by 45 degrees into a counter-clockwise R40 arc
    // about (-40,0), whose start tangent is +Y. Start-up end: the radius towards the centre,
    // (-5,0); the tool is inside the arc, R35, which ends at (-40,35). The arc ends heading -X
    // and the cancel runs -Y (a left turn, inner): the arc's end stays perpendicular, (-40,35).
    // G42, mirrored across the X axis: the start-up along (1,-1) turns right into a clockwise
    // arc starting along -Y; the cancel turns right again. The same points with Y negated.
    for (code, arc, minus, plus) in [("G41", "G3", "-", ""), ("G42", "G2", "", "-")] {
        case(
            5.0,
            &format!(
                "G0 X-20. Y{minus}20.
                 G1 {code} X0 Y0 D1 F100.
                 {arc} X-40. Y{plus}40. I-40. J0
                 G1 G40 X-40. Y{plus}10."
            ),
            &format!(
                "rapid X-20 Y{minus}20 Z0
                 line X-5 Y0 Z0 F100
                 arc {} xy X-40 Y{plus}35 Z0 C(-40,0,0) F100
                 line X-40 Y{plus}10 Z0 F100",
                if arc == "G3" { "ccw" } else { "cw" }
            ),
        );
    }
}

#[test]
fn a_rapid_start_up_and_cancel() {
    case(
        5.0,
        "G0 X-10. Y0
         G0 G41 X0 Y0 D1
         G1 X50. F100.
         G0 G40 X60.",
        "rapid X-10 Y0 Z0
         rapid X0 Y5 Z0
         line X50 Y5 Z0 F100
         rapid X60 Y0 Z0",
    );
}

#[test]
fn in_the_zx_plane_left_of_plus_z_is_plus_x() {
    // G18, seen from +Y with Z to the right and X up: travelling +Z, the tool on the left is at
    // X+5.
    case(
        5.0,
        "G18 G0 X0 Z-10.
         G1 G41 X0 Z0 D1 F100.
         Z50.
         G40 Z60.",
        "rapid X0 Y0 Z-10
         line X5 Y0 Z0 F100
         line X5 Y0 Z50 F100
         line X0 Y0 Z60 F100",
    );
}

#[test]
fn in_the_yz_plane_left_of_plus_y_is_plus_z() {
    case(
        5.0,
        "G19 G0 Y-10. Z0
         G1 G41 Y0 Z0 D1 F100.
         Y50.
         G40 Y60.",
        "rapid X0 Y-10 Z0
         line X0 Y0 Z5 F100
         line X0 Y50 Z5 F100
         line X0 Y60 Z0 F100",
    );
}

#[test]
fn compensation_after_rotation_follows_the_rotated_contour() {
    // The inner-corner case turned 90 degrees about the origin: the tool-centre points turn
    // with it, (45,5) -> (-5,45).
    case(
        5.0,
        "G68 X0 Y0 R90.
         G0 X-10. Y0
         G1 G41 X0 Y0 D1 F100.
         X50.
         Y50.
         G40 X50. Y60.",
        "rapid X0 Y-10 Z0
         line X-5 Y0 Z0 F100
         line X-5 Y45 Z0 F100
         line X-50 Y45 Z0 F100
         line X-60 Y50 Z0 F100",
    );
}

#[test]
fn a_mirrored_axis_swaps_g41_and_g42() {
    // The inner-corner case mirrored in X (G51.1 X0): the path is its mirror image, G41 acts
    // as G42, and the corner point (45,5) mirrors to (-45,5).
    case(
        5.0,
        "G51.1 X0
         G0 X-10. Y0
         G1 G41 X0 Y0 D1 F100.
         X50.
         Y50.
         G40 X50. Y60.",
        "rapid X10 Y0 Z0
         line X0 Y5 Z0 F100
         line X-45 Y5 Z0 F100
         line X-45 Y50 Z0 F100
         line X-50 Y60 Z0 F100",
    );
}

#[test]
fn a_mirror_commanded_in_offset_mode_swaps_g41_and_g42_from_there_on() {
    // The rule is a state (spec 1.29: while one plane axis is mirrored G41 and G42 act the
    // other way), so G51.1 after G41 gives what G51.1 before it gives. Program path (0,0) ->
    // (-10,0) -> (-50,0) -> (-50,50), mirrored about X0: (10,0) -> (50,0) -> (50,50), G41
    // acting as G42, on the right. Start-up end (10,0) + 5 * (0,-1); the corner turns left,
    // away from the tool: y=-5 meets x=55 at (55,-5); the last line ends perpendicular at
    // (55,50), then G40 to (50,60). The mirror image of the unmirrored path's (-55,-5).
    for first in ["G41 D1\nG51.1 X0", "G51.1 X0\nG41 D1"] {
        case(
            5.0,
            &format!("{first}\nG1 X-10. Y0 F100.\nX-50.\nY50.\nG40 X-50. Y60."),
            "line X10 Y-5 Z0 F100
             line X55 Y-5 Z0 F100
             line X55 Y50 Z0 F100
             line X50 Y60 Z0 F100",
        );
    }
}

#[test]
fn an_inner_corner_on_a_step_shorter_than_the_radius_is_interference() {
    // A 3 mm step between two lines, G41 inside the first corner: the compensated lines y=5
    // and x=45 meet beyond the step's end. The control stops before the first line moves.
    case(
        5.0,
        "G0 X-10. Y0
         G1 G41 X0 Y0 D1 F100.
         X50.
         Y3.
         X100.
         G40 X110.",
        "rapid X-10 Y0 Z0
         line X0 Y5 Z0 F100
         alarm cutter_compensation line 4",
    );
}

#[test]
fn an_inner_arc_exactly_the_tool_radius_alarms() {
    // G41 inside a counter-clockwise R5 arc with a R5 tool: the compensated arc has no radius.
    case(
        5.0,
        "G0 X-10. Y0
         G1 G41 X0 Y0 D1 F100.
         X50.
         G3 X55. Y5. R5.
         G1 G40 X60.",
        "rapid X-10 Y0 Z0
         line X0 Y5 Z0 F100
         alarm cutter_compensation line 4",
    );
}

#[test]
fn an_event_between_two_elements_waits_for_the_corner() {
    // M08 between the two lines: the coolant comes on after the first line, which is written
    // only once the corner is known.
    case(
        5.0,
        "G0 X-10. Y0
         G1 G41 X0 Y0 D1 F100.
         X50.
         M08
         Y50.
         G40 X50. Y60.",
        "rapid X-10 Y0 Z0
         line X0 Y5 Z0 F100
         line X45 Y5 Z0 F100
         coolant on
         line X45 Y50 Z0 F100
         line X50 Y60 Z0 F100",
    );
}
