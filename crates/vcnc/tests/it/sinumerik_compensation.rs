//! SINUMERIK tool radius compensation (G40/G41/G42, NORM/KONT/KONTC/KONTT, G450/G451/DISC,
//! OFFN, SAR, G460-G462, CDON, CUTCONON): tool-centre paths worked out by hand in each test's
//! comment (docs/SINUMERIK.md 11; sinumerik-part-b.md 2, seed 002 L6949-7986). Positions are machine coordinates X Y Z; the machine is the default
//! one on the 840D profile with tool 1 (D1, length 0) of the radius each test says.

use vcnc::interp::sinumerik::run_str;
use vcnc::{Alarm, AlarmCode, Machine, Segment, SegmentKind};

use crate::common::sinumerik::{machine, mill};

/// The default machine with tool 1, edge 1, of radius `radius` (length 0).
fn with_tool(radius: f64) -> Machine {
    let mut machine = machine();
    machine.tools.push(mill(1, "MILL", 1, 0.0, radius));
    machine
}

fn stream(text: &str, machine: &Machine) -> (Vec<Segment>, Vec<Alarm>) {
    let mut segments = Vec::new();
    let mut alarms = Vec::new();
    for item in run_str(text, machine) {
        match item {
            Ok(vcnc::Item::Segment(segment)) => segments.push(segment),
            Ok(vcnc::Item::Frame(_)) => {}
            Ok(vcnc::Item::Warning(alarm)) | Err(alarm) => alarms.push(alarm),
        }
    }
    (segments, alarms)
}

/// The end points of the moves, with `A` for an arc's end.
fn ends(segments: &[Segment]) -> Vec<(char, [f64; 3])> {
    segments
        .iter()
        .filter_map(|s| {
            let m = s.motion()?;
            let kind = if matches!(s.kind, SegmentKind::Arc { .. }) {
                'A'
            } else {
                'L'
            };
            Some((kind, [m.to.0[0], m.to.0[1], m.to.0[2]]))
        })
        .collect()
}

#[track_caller]
fn assert_path(text: &str, radius: f64, expected: &[(char, [f64; 3])]) {
    let (segments, alarms) = stream(text, &with_tool(radius));
    assert!(alarms.iter().all(|a| !a.is_error()), "{text}\n{alarms:#?}");
    let got = ends(&segments);
    let same = got.len() == expected.len()
        && got
            .iter()
            .zip(expected)
            .all(|((k, g), (l, e))| k == l && g.iter().zip(e).all(|(p, q)| (p - q).abs() < 1e-4));
    assert!(same, "{text}\ngot    {got:?}\nwanted {expected:?}");
}

fn error(text: &str, radius: f64) -> Alarm {
    let (_, alarms) = stream(text, &with_tool(radius));
    alarms
        .into_iter()
        .find(Alarm::is_error)
        .unwrap_or_else(|| panic!("no error in\n{text}"))
}

const L: char = 'L';
const A: char = 'A';

/// Example 2 of 10.1 (seed 002 L6996-7007, examples/sinumerik-b/48): the clockwise contour
/// (20,20) (20,40) (40,70) (80,50) (80,20) (20,20) with G41, r 5, so every corner is outer and
/// G450 (power-on) goes round it on a circle of 5 about the corner.
/// - NORM start-up: perpendicular to N60 (up): (20,20) + 5 (-1,0) = (15,20).
/// - (20,40): N60 ends at (15,40); N70's direction (20,30)/36.0555 = (0.5547,0.8321), its
///   left normal (-0.8321,0.5547): the circle ends at (15.8397,42.7735).
/// - (40,70): N70 ends at (35.8397,72.7735); N80's direction (0.8944,-0.4472), normal
///   (0.4472,0.8944): the circle ends at (42.2361,74.4721).
/// - (80,50): N80 ends at (82.2361,54.4721); N90 down, normal (1,0): circle to (85,50).
/// - (80,20): N90 ends at (85,20); N100 to -X, normal (0,-1): circle to (80,15).
/// - N100 ends perpendicular at (20,15); N110 G40 G0 Z100 moves Z there, then the tool centre
///   goes onto the programmed (20,20) at rapid.
#[test]
fn the_manuals_contour_goes_round_its_outer_corners_on_circles() {
    let program = "N10 G0 Z100\nN20 G17 T1 M6\nN30 G0 X0 Y0 Z1 M3 S300 D1\nN40 Z-7 F500\n\
                   N50 G41 X20 Y20\nN60 Y40\nN70 X40 Y70\nN80 X80 Y50\nN90 Y20\nN100 X20\n\
                   N110 G40 G0 Z100 M30\n";
    assert_path(
        program,
        5.0,
        &[
            (L, [0.0, 0.0, 100.0]),
            (L, [0.0, 0.0, 1.0]),
            (L, [0.0, 0.0, -7.0]),
            (L, [15.0, 20.0, -7.0]),
            (L, [15.0, 40.0, -7.0]),
            (A, [15.8397, 42.7735, -7.0]),
            (L, [35.8397, 72.7735, -7.0]),
            (A, [42.2361, 74.4721, -7.0]),
            (L, [82.2361, 54.4721, -7.0]),
            (A, [85.0, 50.0, -7.0]),
            (L, [85.0, 20.0, -7.0]),
            (A, [80.0, 15.0, -7.0]),
            (L, [20.0, 15.0, -7.0]),
            (L, [20.0, 15.0, 100.0]),
            (L, [20.0, 20.0, 100.0]),
        ],
    );
}

/// The same contour under G451: the tool centre goes to where the compensated lines meet,
/// corner + r (n1 + n2) / (1 + n1.n2) with the unit left normals n1, n2 of the two lines.
/// - (20,40): n1 (-1,0), n2 (-0.83205,0.55470), n1.n2 0.83205: (15, 41.51388).
/// - (40,70): n2, n3 (0.44721,0.89443), dot 0.12404: (38.28815, 76.44610).
/// - (80,50): n3, n4 (1,0), dot 0.44721: (85, 53.09017).
/// - (80,20): n4, n5 (0,-1), dot 0: (85, 15).
#[test]
fn g451_goes_to_the_intersection_of_the_compensated_lines() {
    let program = "N10 G0 X0 Y0 Z-7 T1 M6 D1 G451\nN50 G41 X20 Y20\nN60 Y40\nN70 X40 Y70\n\
                   N80 X80 Y50\nN90 Y20\nN100 X20\nN110 G40 X0 Y0 M30\n";
    assert_path(
        program,
        5.0,
        &[
            (L, [0.0, 0.0, -7.0]),
            (L, [15.0, 20.0, -7.0]),
            (L, [15.0, 41.51388, -7.0]),
            (L, [38.28815, 76.44610, -7.0]),
            (L, [85.0, 53.09017, -7.0]),
            (L, [85.0, 15.0, -7.0]),
            (L, [20.0, 15.0, -7.0]),
            (L, [0.0, 0.0, -7.0]),
        ],
    );
}

/// A counter-clockwise rectangle with G41 keeps the tool inside: every corner is inner and
/// the tool centre stops where the compensated lines cross, r 5 in from both sides.
/// Start-up from (0,-20) to (0,0), perpendicular to N30 (+X): (0,5). Corners (35,5),
/// (35,25); N50 (-X) ends perpendicular at (0,25); the G40 block goes straight to (-20,30).
const INNER: &str = "N10 G0 X0 Y-20 Z0 T1 M6 D1\nN20 G1 G41 X0 Y0 F100\nN30 X40\nN40 Y30\n\
                     N50 X0\nN60 G40 X-20 Y30\nN70 M30\n";

const INNER_PATH: [(char, [f64; 3]); 6] = [
    ('L', [0.0, -20.0, 0.0]),
    ('L', [0.0, 5.0, 0.0]),
    ('L', [35.0, 5.0, 0.0]),
    ('L', [35.0, 25.0, 0.0]),
    ('L', [0.0, 25.0, 0.0]),
    ('L', [-20.0, 30.0, 0.0]),
];

#[test]
fn inner_corners_stop_where_the_compensated_lines_cross() {
    assert_path(INNER, 5.0, &INNER_PATH);
}

/// OFFN adds to the edge's radius (seed 002 L6958): radius 3 with OFFN=2 cuts the path of
/// radius 5.
#[test]
fn offn_adds_to_the_radius() {
    let program = INNER.replace("N20 G1", "N20 OFFN=2 G1");
    assert_path(&program, 3.0, &INNER_PATH);
}

/// A negative total radius swaps the side (seed 002 L7097): radius 2 with OFFN=-7 is -5, so
/// G42 acts as G41 with 5.
#[test]
fn a_negative_radius_swaps_the_side() {
    let program = INNER.replace("N20 G1 G41", "N20 OFFN=-7 G1 G42");
    assert_path(&program, 2.0, &INNER_PATH);
}

/// G42 (tool right) into a counter-clockwise arc: the tool is outside it, on radius 20 + 5.
/// - Start-up from (0,-10) to (0,0), perpendicular to N30 (+X) on the right: (0,-5).
/// - N30 ends at (20,-5); N40 G3 about (20,20) starts tangent to it, on radius 25 from
///   (20,-5) to (45,20) (its end (40,20) plus 5 along the radius).
/// - N50 (+Y) goes on tangent from (45,20) to (45,40), which ends perpendicular; G40 goes
///   straight to (60,50).
#[test]
fn an_arc_is_compensated_concentrically() {
    let program = "N10 G0 X0 Y-10 Z0 T1 M6 D1\nN20 G1 G42 X0 Y0 F100\nN30 X20\n\
                   N40 G3 X40 Y20 I0 J20\nN50 G1 Y40\nN60 G40 X60 Y50\nN70 M30\n";
    assert_path(
        program,
        5.0,
        &[
            (L, [0.0, -10.0, 0.0]),
            (L, [0.0, -5.0, 0.0]),
            (L, [20.0, -5.0, 0.0]),
            (A, [45.0, 20.0, 0.0]),
            (L, [45.0, 40.0, 0.0]),
            (L, [60.0, 50.0, 0.0]),
        ],
    );
}

/// The compensation plane follows G18: in Z-X (first axis Z, second X) G41 puts the tool on
/// the left looking along the path, as seen with Y pointing at the viewer. Start-up from
/// Z0 X0 to Z-10 X0, next N30 to Z-10 X20 (direction +X, which in the Z-X plane's (Z,X)
/// coordinates is (0,1)): left of (0,1) is (-1,0), Z - 5: the start-up ends at Z-15 X0.
/// N30 ends perpendicular at Z-15 X20 before the G40 block to Z-15 X30 (straight on).
#[test]
fn g18_compensates_in_z_x() {
    let program = "N10 G18 G0 X0 Y0 Z0 T1 M6 D1\nN20 G1 G41 Z-10 F100\nN30 X20\n\
                   N40 G40 X30 Z-15\nN50 M30\n";
    assert_path(
        program,
        5.0,
        &[
            (L, [0.0, 0.0, -15.0]),
            (L, [20.0, 0.0, -15.0]),
            (L, [30.0, 0.0, -15.0]),
        ],
    );
}

/// KONT from behind the contour (examples/sinumerik-b/52, seed 002 L7349-7358), r 5.
/// - Approach: from (35,0) to the start (10,10), first element up (0,1). The approach turns
///   right into it, away from the tool (G41): the tool is behind the contour, so it goes on
///   the tangent from (35,0) to the circle r 5 about (10,10): seen from the centre (35,0) is
///   at -21.8014 degrees, 26.9258 away; the tangents touch at -21.8014 +- acos(5/26.9258) =
///   -21.8014 +- 79.2983 degrees; the one that goes on clockwise is -101.0997: (9.03741,
///   5.09353). Then clockwise round to (5,10), perpendicular to the first element.
/// - (10,60): N40 ends at (5,60), circle to (10,60) + 5 (0.6,0.8) = (13,64).
/// - (50,30): N50 ends at (53,34), circle to (50,30) + 5 (0.44721,-0.89443) = (52.23607,
///   25.52786).
/// - Retract to (-20,50): N60 (direction (-0.89443,-0.44721)) turns right into it, so round
///   the end (10,10): N60 ends at (12.23607,5.52786), then clockwise to where the tangent to
///   (-20,50) leaves the circle: (-20,50) is at 126.8699 degrees, 50 away, acos(0.1) =
///   84.2608; the point is at 211.1307 degrees: (5.72005,7.41504); then straight to (-20,50).
#[test]
fn kont_goes_round_the_start_and_end_points_from_behind() {
    let program = "N10 G17 T1 D1 M6 G0 X35 Y0 Z0 F500\nN20 G1 Z-5\n\
                   N30 G41 KONT G450 X10 Y10\nN40 Y60\nN50 X50 Y30\nN60 X10 Y10\n\
                   N80 G40 X-20 Y50\nN90 G0 Y100\nN100 X200 M30\n";
    assert_path(
        program,
        5.0,
        &[
            (L, [35.0, 0.0, 0.0]),
            (L, [35.0, 0.0, -5.0]),
            (L, [9.03741, 5.09353, -5.0]),
            (A, [5.0, 10.0, -5.0]),
            (L, [5.0, 60.0, -5.0]),
            (A, [13.0, 64.0, -5.0]),
            (L, [53.0, 34.0, -5.0]),
            (A, [52.23607, 25.52786, -5.0]),
            (L, [12.23607, 5.52786, -5.0]),
            (A, [5.72005, 7.41504, -5.0]),
            (L, [-20.0, 50.0, -5.0]),
            (L, [-20.0, 100.0, -5.0]),
            (L, [200.0, 100.0, -5.0]),
        ],
    );
}

/// KONT with the tool in front of the contour is NORM: from (-10,10) on the tool's side
/// (left of the first element, +X from (0,0)) straight to (0,5).
#[test]
fn kont_from_in_front_is_norm() {
    let program = "N10 G0 X-10 Y10 Z0 T1 M6 D1\nN20 G1 G41 KONT X0 Y0 F100\nN30 X40\n\
                   N40 G40 X50 Y10\nN50 M30\n";
    assert_path(
        program,
        5.0,
        &[
            (L, [-10.0, 10.0, 0.0]),
            (L, [0.0, 5.0, 0.0]),
            (L, [40.0, 5.0, 0.0]),
            (L, [50.0, 10.0, 0.0]),
        ],
    );
}

/// A notch 4 wide for a tool of radius 5: the compensated lines of N30 and N40 meet at (15,5),
/// 1 mm beyond N40's compensated end (15,4): the tool would cut into the contour. The control
/// stops with its collision alarm (10751, seed 002 L7761) before N30 moves.
#[test]
fn a_notch_narrower_than_the_tool_alarms() {
    let alarm = error(
        "N10 G0 X-10 Y-10 Z0 T1 M6 D1\nN20 G1 G41 X0 Y0 F100\nN30 X20\nN40 Y4\nN50 X0\n\
         N60 G40 X-10 Y10\nN70 M30\n",
        5.0,
    );
    assert_eq!(alarm.code, AlarmCode::CutterCompensation);
    assert!(
        alarm.help.as_deref().is_some_and(|h| h.contains("10751")),
        "{alarm:?}"
    );
}

/// An arc of radius 3 with the tool (radius 5) inside it cannot be compensated.
#[test]
fn an_arc_smaller_than_the_tool_on_its_inside_alarms() {
    let alarm = error(
        "N10 G0 X0 Y-10 Z0 T1 M6 D1\nN20 G1 G41 X0 Y0 F100\nN30 X10\nN40 G3 X10 Y6 CR=3\n\
         N50 G1 X0\nN60 G40 X0 Y20\nN70 M30\n",
        5.0,
    );
    assert_eq!(alarm.code, AlarmCode::CutterCompensation);
    assert!(alarm.message.contains("radius 3"), "{alarm:?}");
}

/// G41 starts in a G0 or G1 block (seed 002 L6968).
#[test]
fn compensation_starts_only_in_a_straight_block() {
    let alarm = error(
        "N10 G0 X0 Y0 T1 M6 D1\nN20 G2 G41 X10 Y0 CR=5 F100\nN30 M30\n",
        5.0,
    );
    assert_eq!(alarm.code, AlarmCode::CutterCompensation);
}

/// The working plane cannot change while G41/G42 is on (sinumerik-part-b.md 2.1).
#[test]
fn the_plane_cannot_change_while_compensating() {
    let alarm = error(
        "N10 G0 X0 Y0 T1 M6 D1\nN20 G1 G41 X10 F100\nN30 G18 X20\nN40 M30\n",
        5.0,
    );
    assert_eq!(alarm.code, AlarmCode::CutterCompensation);
    assert!(alarm.message.contains("plane"), "{alarm:?}");
}

/// DISC flattens the transition circle towards the intersection (seed 002 L7300-7340): a
/// square outer corner at (10,0), tool left, r 2. The compensated ends (10,2) and (12,0); with
/// DISC=100 the curve is the two tangent lines through their meeting point (12,2), moves of
/// N40 (the block after the corner); DISC=50 leaves (10,2) on a conic whose middle is
/// (11.70711,1.70711) (0.70711 of the way from (11,1) to (12,2); the circle's is 0.41421),
/// in straight pieces; under G451 DISC does nothing. Out of 0..100 it alarms.
#[test]
fn disc_flattens_the_transition_circle() {
    let program = "N10 G0 X-10 Y0 T1 M6 D1\nN20 G1 F500 G41 DISC=100 X0 Y0\nN30 X10\nN40 Y-10\n\
                   N50 G40 X20 Y-20\nM30\n";
    let tail = [(L, [12.0, -10.0, 0.0]), (L, [20.0, -20.0, 0.0])];
    let mut expected = vec![
        (L, [-10.0, 0.0, 0.0]),
        (L, [0.0, 2.0, 0.0]),
        (L, [10.0, 2.0, 0.0]),
        (L, [12.0, 2.0, 0.0]),
        (L, [12.0, 0.0, 0.0]),
    ];
    expected.extend(tail);
    assert_path(program, 2.0, &expected);
    let (segments, _) = stream(&program.replace("DISC=100", "DISC=50"), &with_tool(2.0));
    let path = ends(&segments);
    let corner = &path[3..path.len() - 2];
    assert!(corner.len() > 8, "{corner:?}");
    assert_eq!(corner.last().unwrap().1, [12.0, 0.0, 0.0]);
    // The pieces run round the curve (their corners where its tangents meet), within 1 um:
    // one passes that near the curve's middle.
    let half = 0.5f64.sqrt();
    let middle = (11.0 + half, 1.0 + half);
    let off = corner
        .windows(2)
        .map(|w| {
            let (p, q) = ((w[0].1[0], w[0].1[1]), (w[1].1[0], w[1].1[1]));
            let d = (q.0 - p.0, q.1 - p.1);
            let t = (((middle.0 - p.0) * d.0 + (middle.1 - p.1) * d.1) / (d.0 * d.0 + d.1 * d.1))
                .clamp(0.0, 1.0);
            (middle.0 - p.0 - d.0 * t).hypot(middle.1 - p.1 - d.1 * t)
        })
        .fold(f64::INFINITY, f64::min);
    assert!(off < 1e-3, "{off} {corner:?}");
    let g451 = program.replace("G41", "G41 G451");
    let mut expected = vec![
        (L, [-10.0, 0.0, 0.0]),
        (L, [0.0, 2.0, 0.0]),
        (L, [12.0, 2.0, 0.0]),
    ];
    expected.extend(tail);
    assert_path(&g451, 2.0, &expected);
    let alarm = error("N10 DISC=150\nN20 M30\n", 5.0);
    assert_eq!(alarm.code, AlarmCode::ValueOutOfRange);
}

/// Z moves while compensating are made where the tool centre stands: a plunge between two
/// elements happens at the corner (after N30 ends at (35,5), before N50).
#[test]
fn a_plunge_between_elements_happens_at_the_corner() {
    let program = INNER.replace("N40 Y30", "N35 Z-5\nN40 Y30");
    let mut expected = INNER_PATH.to_vec();
    for point in expected.iter_mut().skip(3) {
        point.1[2] = -5.0;
    }
    expected.insert(3, ('L', [35.0, 5.0, -5.0]));
    assert_path(&program, 5.0, &expected);
}

/// MIRROR X0 swaps G41 and G42 on the machine (seed 002 L9124-9244): the mirrored rectangle is
/// still cut with the tool inside, so the path is the unmirrored one's mirror image in X.
#[test]
fn a_mirrored_contour_keeps_the_tool_on_its_side() {
    let program = INNER.replace("N10 ", "N5 MIRROR X0\nN10 ");
    let mirrored: Vec<(char, [f64; 3])> = INNER_PATH
        .iter()
        .map(|&(kind, [x, y, z])| (kind, [-x, y, z]))
        .collect();
    assert_path(&program, 5.0, &mirrored);
}

/// G41 to G42 in offset mode (allowed without G40, seed 002 L7135): the compensated lines y=5
/// and y=-5 of two collinear elements never cross, so N30 ends perpendicular at (40,5) and a
/// straight move joins N40's start perpendicular on the right, (40,-5); N40 ends
/// perpendicular at (80,-5) and G40 goes straight to (90,-10).
#[test]
fn the_side_changes_without_g40() {
    let program = "N10 G0 X0 Y-10 Z0 T1 M6 D1\nN20 G1 G41 X0 Y0 F100\nN30 X40\nN40 G42 X80\n\
                   N50 G40 X90 Y-10\nN60 M30\n";
    assert_path(
        program,
        5.0,
        &[
            (L, [0.0, -10.0, 0.0]),
            (L, [0.0, 5.0, 0.0]),
            (L, [40.0, 5.0, 0.0]),
            (L, [40.0, -5.0, 0.0]),
            (L, [80.0, -5.0, 0.0]),
            (L, [90.0, -10.0, 0.0]),
        ],
    );
}

/// KONT with G451 (examples/sinumerik-b/52's contour under G451), r 5.
/// - Approach: the tangent from (35,0) that touches the circle about (10,10) at (9.03741,
///   5.09353) (as with G450), carried on to the first compensated element X5: at
///   y = 5.09353 * (35 - 5) / (35 - 9.03741) = 5.88562.
/// - (10,60): N40's X5 meets N50's compensated line through (13,64) along (0.8,-0.6) at
///   (5,70).
/// - (50,30): n1 (0.6,0.8), n2 (0.44721,-0.89443), n1.n2 -0.44721: (50,30) + 5 (n1 + n2) /
///   (1 + n1.n2) = (59.47214,29.14590).
/// - Retract: the tangent to (-20,50) that leaves the circle about (10,10) at (5.72005,7.41504)
///   meets N60's compensated line (through (12.23607,5.52786) along (-0.89443,-0.44721)) at
///   (8.10682,3.46324); from there straight to (-20,50).
#[test]
fn kont_under_g451_goes_through_the_intersections() {
    let program = "N10 G17 T1 D1 M6 G0 X35 Y0 Z0 F500\nN20 G1 Z-5\n\
                   N30 G41 KONT G451 X10 Y10\nN40 Y60\nN50 X50 Y30\nN60 X10 Y10\n\
                   N80 G40 X-20 Y50\nN90 G0 Y100\nN100 X200 M30\n";
    assert_path(
        program,
        5.0,
        &[
            (L, [35.0, 0.0, 0.0]),
            (L, [35.0, 0.0, -5.0]),
            (L, [5.0, 5.88562, -5.0]),
            (L, [5.0, 70.0, -5.0]),
            (L, [59.47214, 29.14590, -5.0]),
            (L, [8.10682, 3.46324, -5.0]),
            (L, [-20.0, 50.0, -5.0]),
            (L, [-20.0, 100.0, -5.0]),
            (L, [200.0, 100.0, -5.0]),
        ],
    );
}

/// CUTCONON keeps the offset the tool centre has where the last compensated block ends
/// (seed 002 L7967-7985). G42, r 5, on a counter-clockwise path: the tool outside. Start-up
/// to (0,-5); N30 ends at (40,-5), the circle about (40,0) to (45,0); N40 ends perpendicular
/// at (45,30), an offset (5,0) from the programmed (40,30). N50 X0 CUTCONON runs shifted:
/// (5,30). N60 Y40 CUTCONOF is compensated again from its start (0,30) moved right of +Y:
/// (5,30), where the tool stands (no joining move), and ends perpendicular at (5,40); G40
/// goes straight to (-10,40).
#[test]
fn cutconon_shifts_the_blocks_by_the_offset_kept() {
    let program = "N10 G0 X0 Y-10 Z0 T1 M6 D1\nN20 G1 G42 X0 Y0 F100\nN30 X40\nN40 Y30\n\
                   N50 X0 CUTCONON\nN60 Y40 CUTCONOF\nN70 G40 X-10\nN80 M30\n";
    assert_path(
        program,
        5.0,
        &[
            (L, [0.0, -10.0, 0.0]),
            (L, [0.0, -5.0, 0.0]),
            (L, [40.0, -5.0, 0.0]),
            (A, [45.0, 0.0, 0.0]),
            (L, [45.0, 30.0, 0.0]),
            (L, [5.0, 30.0, 0.0]),
            (L, [5.0, 40.0, 0.0]),
            (L, [-10.0, 40.0, 0.0]),
        ],
    );
}

/// G347 with G341 (seed 002 L7398-7538), G41 r 5: P4 (30,0) compensated onto (30,5) along +X;
/// the half circle of DISR 10 for the tool centre has its centre (30,15) on the tool's side and
/// starts at (30,25). Rapid over it at Z10, down to DISCL=2 above Z0, FAD (100) down to Z0,
/// the half circle counter-clockwise to (30,5) at F300; N30 ends perpendicular at (60,5), G40
/// goes straight to (70,10). The feeds: the infeed at FAD, the circle and N30 at F.
#[test]
fn g347_approaches_on_a_half_circle_after_the_infeed() {
    let program = "N10 G0 X0 Y0 Z10 T1 M6 D1\n\
                   N20 G1 G41 G347 G341 DISR=10 DISCL=2 FAD=100 X30 Y0 Z0 F300\n\
                   N30 X60\nN40 G40 X70 Y10\nN50 M30\n";
    assert_path(
        program,
        5.0,
        &[
            (L, [0.0, 0.0, 10.0]),
            (L, [30.0, 25.0, 10.0]),
            (L, [30.0, 25.0, 2.0]),
            (L, [30.0, 25.0, 0.0]),
            (A, [30.0, 5.0, 0.0]),
            (L, [60.0, 5.0, 0.0]),
            (L, [70.0, 10.0, 0.0]),
        ],
    );
    let (segments, _) = stream(program, &with_tool(5.0));
    let feeds: Vec<Option<f64>> = segments
        .iter()
        .filter(|s| s.motion().is_some())
        .map(|s| match s.kind {
            SegmentKind::Line { feed, .. } | SegmentKind::Arc { feed, .. } => feed.mm_per_min(1.0),
            _ => None,
        })
        .collect();
    assert_eq!(
        feeds,
        [
            None,
            None,
            None,
            Some(100.0),
            Some(300.0),
            Some(300.0),
            Some(300.0)
        ]
    );
}

/// A smooth approach needs the compensation to start in its block (vcnc's choice: the other
/// cases are not run yet).
#[test]
fn a_smooth_approach_without_starting_compensation_is_not_run_yet() {
    let alarm = error(
        "N10 G0 X0 Y0 T1 M6 D1\nN20 G1 G247 DISR=5 X10 F100\nN30 M30\n",
        5.0,
    );
    assert_eq!(alarm.code, AlarmCode::NotSupportedYet);
    assert!(alarm.message.contains("G247"), "{alarm:?}");
}

/// Example 2 of 10.4.2 (seed 002 L7720-7730, examples/sinumerik-b/57), G42 r 10, G461: N60
/// (-Y from (50,5) to (50,0), compensated X40) is shorter than the tool needs before N70 (-X,
/// compensated Y10): the lines meet at (40,10), 5 beyond N60's start. G461 produces N60 back by
/// the circle of 10 about its start (50,5), which meets Y10 at X = 50 - sqrt(100 - 25) =
/// 41.33975: the approach N50 ends there and N60 is skipped. N70 ends at (30,10); the outer
/// corner at (30,0) (G450) goes round to (30,0) + 10 (-0.44721,0.89443) = (25.52786,8.94427),
/// the right normal of N80's direction (-0.89443,-0.44721); N80 ends perpendicular, at
/// (20,-5) + the same normal * 10 = (15.52786,3.94427), and N90 G40 goes to (0,0).
#[test]
fn g461_skips_a_first_element_too_short_for_the_tool() {
    let program = "N30 X0 Y0 F10000 T1 M6 D1\nN40 Y20\nN50 G42 X50 Y5 G461\nN60 Y0 F600\n\
                   N70 X30\nN80 X20 Y-5\nN90 X0 Y0 G40\nN100 M30\n";
    let tail = [
        (L, [30.0, 10.0, 0.0]),
        (A, [25.52786, 8.94427, 0.0]),
        (L, [15.52786, 3.94427, 0.0]),
        (L, [0.0, 0.0, 0.0]),
    ];
    let expected = |x: f64| {
        let mut path = vec![(L, [0.0, 20.0, 0.0]), (L, [x, 10.0, 0.0])];
        path.extend(tail);
        path
    };
    assert_path(program, 10.0, &expected(50.0 - 75f64.sqrt()));
    // G462 produces N60's compensated line X40 back (+Y) instead: it meets Y10 at (40,10).
    assert_path(&program.replace("G461", "G462"), 10.0, &expected(40.0));
    // G460 (power-on): the collision alarm (SINUMERIK 10751).
    let alarm = error(&program.replace("G461", "G460"), 10.0);
    assert_eq!(alarm.code, AlarmCode::CutterCompensation);
    assert!(alarm.help.as_deref().is_some_and(|h| h.contains("10751")));
}

/// Example 1 of 10.4.2 (seed 002 L7712-7718, examples/sinumerik-b/56), G42 r 20: N10 runs -X
/// at Y0 (compensated Y20), N20 +Y from (0,0) to (0,10) (compensated X20), their compensated
/// lines meet at (20,20), 10 beyond N20's end; N30 G40 goes to (50,50).
/// - G461: the circle of 20 about N20's end (0,10) meets Y20 at X = sqrt(400 - 100) =
///   17.32051: N10 ends there, N20 is skipped, N30 leaves from there.
/// - G462: N20's compensated line X20 produced beyond its end meets Y20 at (20,20). N20's Z
///   move (written here) is made where the tool centre stands.
#[test]
fn g461_and_g462_skip_a_last_element_too_short_for_the_tool() {
    let program = "T1 M6 D1 F1000\nG42 G461\nG1 X110 Y0\nN10 X0\nN20 Y10\nN30 G40 X50 Y50\nM30\n";
    assert_path(
        program,
        20.0,
        &[
            (L, [110.0, 20.0, 0.0]),
            (L, [300f64.sqrt(), 20.0, 0.0]),
            (L, [50.0, 50.0, 0.0]),
        ],
    );
    let program = program.replace("G461", "G462").replace("Y10", "Y10 Z-3");
    assert_path(
        &program,
        20.0,
        &[
            (L, [110.0, 20.0, 0.0]),
            (L, [20.0, 20.0, 0.0]),
            (L, [20.0, 20.0, -3.0]),
            (L, [50.0, 50.0, -3.0]),
        ],
    );
}

/// G461 helps only at the contour's ends: the same short N20 with the contour going on after
/// it (N25 +X) is the collision alarm.
#[test]
fn g461_inside_the_contour_is_still_the_collision_alarm() {
    let program =
        "T1 M6 D1 F1000\nG42 G461\nG1 X110 Y0\nN10 X0\nN20 Y10\nN25 X50\nN30 G40 X50 Y50\nM30\n";
    let alarm = error(program, 20.0);
    assert_eq!(alarm.code, AlarmCode::CutterCompensation);
    assert_eq!(alarm.span.map(|s| s.line), Some(5), "the alarm names N20");
}

/// The feeds of the moves at a feed, mm/min, in order (rapids left out).
fn feeds(segments: &[Segment]) -> Vec<f64> {
    segments
        .iter()
        .filter_map(|s| match s.kind {
            SegmentKind::Line { feed, .. } | SegmentKind::Arc { feed, .. } => match feed {
                vcnc::motion::Feed::PerMinute(f) => Some(f),
                _ => None,
            },
            _ => None,
        })
        .collect()
}

/// The manual's SAR example (seed 002 L7458-7503, examples/sinumerik-b/53): r 10 + OFFN 5 =
/// 15, tool left. Approach (G247 G341): rapid over P3 (20,15), down to DISCL=AC(7), FAD 200 to
/// Z0, the quarter circle about (30,15) to (30,5) at F1500; N40 to (40,5,2), N50 to (50,5,2)
/// (P4 of the retraction, +X). Retraction (G248 G340, DISR 5, DISCL 6): the quarter circle for
/// the tool centre leaves (50,5) along +X and turns left about (50,5) + 5 (0,1) = (50,10) to
/// (55,10), rising in space from the contour's Z2 to Z2 + 6 = Z8 (a helix) at the last block's
/// F1500; then up to N60's Z20 and across to P0 (70,0) at N60's F10000; N70 to (80,0).
#[test]
fn g248_leaves_on_a_quarter_circle_rising_to_the_clearance() {
    let program = "N10 G0 X0 Y0 Z20 D1 T1 M6 OFFN=5\n\
                   N20 G41 G247 G341 Z0 DISCL=AC(7) DISR=10 F1500 FAD=200\n\
                   N30 G1 X30 Y-10\nN40 X40 Z2\nN50 X50\n\
                   N60 G248 G340 X70 Y0 Z20 DISCL=6 DISR=5 G40 F10000\nN70 X80 Y0\nN80 M30\n";
    assert_path(
        program,
        10.0,
        &[
            (L, [0.0, 0.0, 20.0]),
            (L, [20.0, 15.0, 20.0]),
            (L, [20.0, 15.0, 7.0]),
            (L, [20.0, 15.0, 0.0]),
            (A, [30.0, 5.0, 0.0]),
            (L, [40.0, 5.0, 2.0]),
            (L, [50.0, 5.0, 2.0]),
            (A, [55.0, 10.0, 8.0]),
            (L, [55.0, 10.0, 20.0]),
            (L, [70.0, 0.0, 20.0]),
            (L, [80.0, 0.0, 20.0]),
        ],
    );
    let (segments, _) = stream(program, &with_tool(10.0));
    assert_eq!(
        feeds(&segments),
        [200.0, 1500.0, 1500.0, 1500.0, 1500.0, 10000.0, 10000.0, 10000.0]
    );
}

/// G148 with G341, r 5, tool left of N40 (+X at Y0): P4 = (30,5). The line is r + DISR = 5 +
/// 4 = 9 long along +X: P3 (39,5) at the contour's Z0, at N40's F500; up at FAD 200 to DISCL
/// 3 above Z0 (towards P0's Z10); up to Z10 and across to P0 (50,20) at N50's F2000.
#[test]
fn g148_leaves_on_a_line_then_rises_at_fad() {
    let program = "N10 G0 X-20 Y0 Z10 T1 M6 D1\nN20 G1 Z0 F500\nN30 G41 X0 Y0\nN40 X30\n\
                   N50 G40 G148 G341 X50 Y20 Z10 DISR=4 DISCL=3 FAD=200 F2000\nM30\n";
    assert_path(
        program,
        5.0,
        &[
            (L, [-20.0, 0.0, 10.0]),
            (L, [-20.0, 0.0, 0.0]),
            (L, [0.0, 5.0, 0.0]),
            (L, [30.0, 5.0, 0.0]),
            (L, [39.0, 5.0, 0.0]),
            (L, [39.0, 5.0, 3.0]),
            (L, [39.0, 5.0, 10.0]),
            (L, [50.0, 20.0, 10.0]),
        ],
    );
    let (segments, _) = stream(program, &with_tool(5.0));
    assert_eq!(
        feeds(&segments),
        [500.0, 500.0, 500.0, 500.0, 200.0, 2000.0, 2000.0]
    );
}

/// G348 with G42, r 5: N40 (+X at Y0) ends at P4 (30,-5); the half circle of DISR 6 for the
/// tool centre turns right (clockwise) about (30,-5) + 6 (0,-1) = (30,-11) to (30,-17); no
/// DISCL: the rest in the plane, straight to P0 (30,-30).
#[test]
fn g348_leaves_on_a_half_circle_to_the_tools_side() {
    let program =
        "N10 G0 X-20 Y0 T1 M6 D1\nN20 G1 F500\nN30 G42 X0 Y0\nN40 X30\nN50 G40 G348 X30 Y-30 DISR=6\nM30\n";
    assert_path(
        program,
        5.0,
        &[
            (L, [-20.0, 0.0, 0.0]),
            (L, [0.0, -5.0, 0.0]),
            (L, [30.0, -5.0, 0.0]),
            (A, [30.0, -17.0, 0.0]),
            (L, [30.0, -30.0, 0.0]),
        ],
    );
    let (segments, _) = stream(program, &with_tool(5.0));
    let centre = segments.iter().find_map(|s| match s.kind {
        SegmentKind::Arc {
            center, direction, ..
        } => Some((center.0[0], center.0[1], direction)),
        _ => None,
    });
    assert_eq!(
        centre,
        Some((30.0, -11.0, vcnc::motion::ArcDirection::Clockwise))
    );
}

/// A smooth retraction needs the G40 in its own block.
#[test]
fn a_smooth_retraction_without_g40_is_not_run_yet() {
    let program = "N10 G0 X-20 Y0 T1 M6 D1\nN20 G1 F500\nN30 G41 X0 Y0\nN40 X30\nN50 G248 X50 Y20 DISR=4\nM30\n";
    let alarm = error(program, 5.0);
    assert_eq!(alarm.code, AlarmCode::NotSupportedYet);
    assert!(alarm.message.contains("G248"), "{}", alarm.message);
}

/// The manual's KONTC example (seed 002 L7222-7229, examples/sinumerik-b/51): a full circle of
/// 70 about the origin, clockwise, tool left (outside, r 10): the tool centre runs on the
/// circle of 80, starting at (80,0) heading -Y, its curvature -1/80. The approach from
/// (0,0,60) is a curve in straight pieces (within 1 um) ending at (80,0,0) with that tangent
/// and curvature, Z coming to rest there; the circle; the retraction the same backwards, to
/// (0,0,60). KONTT meets the same point and tangent.
#[test]
fn kontc_joins_the_circle_with_its_tangent_and_curvature() {
    let program = "N10 G1 X0 Y0 Z60 T1 M6 D1 F10000\nN20 G41 KONTC X70 Y0 Z0\nN30 G2 I-70\n\
                   N40 G40 G1 X0 Y0 Z60\nN50 M30\n";
    for continuity in ["KONTC", "KONTT"] {
        let program = program.replace("KONTC", continuity);
        let (segments, alarms) = stream(&program, &with_tool(10.0));
        assert!(alarms.is_empty(), "{alarms:#?}");
        let path = ends(&segments);
        let circle = path.iter().position(|(kind, _)| *kind == A).unwrap();
        assert_eq!(path.iter().filter(|(kind, _)| *kind == A).count(), 1);
        let at = |i: usize| path[i].1;
        assert_eq!(
            at(circle),
            [80.0, 0.0, 0.0],
            "{continuity}: the full circle"
        );
        assert_eq!(
            at(circle - 1),
            [80.0, 0.0, 0.0],
            "{continuity}: the approach's end"
        );
        assert_eq!(*at(path.len() - 1).first().unwrap(), 0.0);
        assert_eq!(at(path.len() - 1), [0.0, 0.0, 60.0]);
        // The approach's last piece heads -Y (its chord turned from the tangent by half the
        // curve's turn along it), Z at rest (KONTT: Z' is 0 at the end, so the last of n
        // pieces falls 60 / n^2 there).
        let (q, r) = (at(circle - 2), at(circle - 1));
        let d = ((r[0] - q[0]), (r[1] - q[1]));
        let length = d.0.hypot(d.1);
        assert!(
            d.0.abs() / length < 1e-2 && d.1 < 0.0,
            "{continuity}: {d:?}"
        );
        assert!((r[2] - q[2]).abs() < 2e-3, "{continuity}: {q:?} {r:?}");
        let first = at(circle + 1);
        assert!(
            (first[0] - 80.0).abs() < 0.05 && first[1] < 0.0,
            "{first:?}"
        );
        // Z falls from 60 to 0 without turning back.
        assert!(path[..circle]
            .windows(2)
            .all(|w| w[1].1[2] <= w[0].1[2] + 1e-9));
    }
}

/// KONTC and KONTT replace a G1 block only (seed 002 L7207-7208).
#[test]
fn kontc_from_a_rapid_alarms() {
    let program = "N10 G0 X0 Y0 Z60 T1 M6 D1 F1000\nN20 G41 KONTC X70 Y0 Z0\nN30 G2 I-70\nM30\n";
    let alarm = error(program, 10.0);
    assert_eq!(alarm.code, AlarmCode::CutterCompensation);
    assert!(alarm.message.contains("G1"), "{}", alarm.message);
}

/// G141-G143 choose the side of the approach contour (seed 002 L7421-7432). b/55's approach
/// (G41 r 7, G247 G341, DISR 13): P4 (40,-3) heading +X. G140 and G141 take the left: the
/// quarter circle about (40,10) from (27,10), counter-clockwise. G142 takes the right: about
/// (40,-3) + 13 (0,-1) = (40,-16), from (27,-16), clockwise. G143 takes the side of the
/// tangent at P4 that P0 lies on: from (0,0) (3 above the tangent Y-3) the left; from
/// (0,-20) the right.
#[test]
fn g141_to_g143_choose_the_approach_side() {
    let program = |side: &str, start: &str| {
        format!(
            "N10 G90 G0 {start} Z20 T1 M6 D1\nN20 G41 G341 G247 {side} DISCL=AC(5) DISR=13 \
             FAD=500 X40 Y-10 Z=0 F200\nN30 X50\nM30\n"
        )
    };
    let path = |p3: (f64, f64), start: (f64, f64)| {
        vec![
            (L, [start.0, start.1, 20.0]),
            (L, [p3.0, p3.1, 20.0]),
            (L, [p3.0, p3.1, 5.0]),
            (L, [p3.0, p3.1, 0.0]),
            (A, [40.0, -3.0, 0.0]),
            (L, [50.0, -3.0, 0.0]),
        ]
    };
    let origin = "X0 Y0";
    let below = "X0 Y-20";
    assert_path(
        &program("G140", origin),
        7.0,
        &path((27.0, 10.0), (0.0, 0.0)),
    );
    assert_path(
        &program("G141", origin),
        7.0,
        &path((27.0, 10.0), (0.0, 0.0)),
    );
    assert_path(
        &program("G142", origin),
        7.0,
        &path((27.0, -16.0), (0.0, 0.0)),
    );
    assert_path(
        &program("G143", origin),
        7.0,
        &path((27.0, 10.0), (0.0, 0.0)),
    );
    assert_path(
        &program("G143", below),
        7.0,
        &path((27.0, -16.0), (0.0, -20.0)),
    );
    let (segments, _) = stream(&program("G142", origin), &with_tool(7.0));
    let arc = segments.iter().find_map(|s| match s.kind {
        SegmentKind::Arc {
            center, direction, ..
        } => Some((center.0[0], center.0[1], direction)),
        _ => None,
    });
    assert_eq!(
        arc,
        Some((40.0, -16.0, vcnc::motion::ArcDirection::Clockwise))
    );
}

/// CDON's bottleneck detection (seed 002 L7796-7852), r 3, tool left: N30 runs +X at Y0, N40
/// a major arc (292.6 degrees, radius sqrt(13) about (23,2)) round to (20,4), N50 back -X at
/// Y4. Both corners turn right, outer for the tool (transition circles), so the neighbouring
/// blocks never meet; but N50's compensated line, Y1, runs 1 from N30 two blocks back: the
/// passage is 4 wide for a tool of 6. CDON stops there with the collision alarm; CDOF
/// (power-on) checks neighbours only and runs.
#[test]
fn cdon_finds_a_bottleneck_two_blocks_back() {
    let program = "N10 G0 X-10 Y10 T1 M6 D1\nN20 G1 F500 G41 CDON X0 Y0\nN30 X20\n\
                   N40 G3 X20 Y4 I3 J2\nN50 G1 X0\nN60 G40 X-10 Y10\nM30\n";
    let alarm = error(program, 3.0);
    assert_eq!(alarm.code, AlarmCode::CutterCompensation);
    assert!(alarm.message.contains("bottleneck"), "{}", alarm.message);
    assert_eq!(alarm.span.map(|s| s.line), Some(5), "the alarm names N50");
    let (_, alarms) = stream(&program.replace("CDON", "CDOF"), &with_tool(3.0));
    assert!(alarms.iter().all(|a| !a.is_error()), "{alarms:#?}");
}

/// G462 and a smooth retraction together: b/56's N20 is skipped, N10 ends at (20,20) (see
/// g461_and_g462_skip_a_last_element_too_short_for_the_tool), and with no last element left
/// to leave tangentially the G248 block goes straight on to its end (50,50).
#[test]
fn a_smooth_retraction_after_a_skipped_last_element_goes_straight() {
    let program = "T1 M6 D1 F1000\nG42 G462\nG1 X110 Y0\nN10 X0\nN20 Y10\n\
                   N30 G40 G248 DISR=5 X50 Y50\nM30\n";
    assert_path(
        program,
        20.0,
        &[
            (L, [110.0, 20.0, 0.0]),
            (L, [20.0, 20.0, 0.0]),
            (L, [50.0, 50.0, 0.0]),
        ],
    );
}

/// A smooth retraction block that moves only the plane's normal (seed 002 L7600-7610): the
/// contour ends at P1, and as the block also deselects the compensation a move from P1 to P0,
/// the uncompensated end point, follows. r 5, tool left of N40 (+X at Y0): P4 (30,5,0); the
/// line r + DISR = 9 to P3 (39,5); G340 in space up to DISCL 3 above Z0, (39,5,3); up to N50's
/// Z10; across to P0 (30,0,10); N60 on to (40,0,10).
#[test]
fn a_smooth_retraction_moving_only_the_normal_ends_uncompensated() {
    let program = "N10 G0 X-20 Y0 Z10 T1 M6 D1\nN20 G1 Z0 F500\nN30 G41 X0 Y0\nN40 X30\n\
                   N50 G40 G148 Z10 DISR=4 DISCL=3 F2000\nN60 X40\nM30\n";
    assert_path(
        program,
        5.0,
        &[
            (L, [-20.0, 0.0, 10.0]),
            (L, [-20.0, 0.0, 0.0]),
            (L, [0.0, 5.0, 0.0]),
            (L, [30.0, 5.0, 0.0]),
            (L, [39.0, 5.0, 3.0]),
            (L, [39.0, 5.0, 10.0]),
            (L, [30.0, 0.0, 10.0]),
            (L, [40.0, 0.0, 10.0]),
        ],
    );
}
