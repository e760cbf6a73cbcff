//! G07 hypothetical axis interpolation (issue 23): an axis made hypothetical takes part in the
//! interpolation without moving, so a helix traces a sine on the remaining axes. Not in the three
//! ISO manuals: the FANUC 15i/16i-M descriptions ("4.7 Hypothetical axis interpolation (G07)":
//! `G07 α0` sets, `G07 α1` cancels; X hypothetical in a helix gives Y = r sin(2 pi Z / l)) and
//! the Mitsubishi M700V programming manual 6.16 (the feed distributed as for a real axis,
//! values other than 0 cancel). Each case worked by hand in its comment.

use vcnc::motion::Feed;
use vcnc::{Machine, ProfileName, Segment, SegmentKind};

fn machine(profile: ProfileName) -> Machine {
    Machine::default().with_profile(profile).unwrap()
}

/// The segments of `program` on `profile`, which must run without an error.
fn segments(profile: ProfileName, program: &str) -> Vec<Segment> {
    let run = crate::common::run(
        program.as_bytes(),
        &machine(profile),
        vcnc::Options::default(),
    );
    if let Some(alarm) = run.error() {
        panic!("{alarm:?}\n{program}");
    }
    run.segments
}

/// The X Y Z machine positions where each feed move ends (every program here starts with the
/// tool at the origin, where `G00 X0 Y0 Z0` makes no move).
fn ends(segments: &[Segment]) -> Vec<[f64; 3]> {
    segments
        .iter()
        .filter(|s| matches!(s.kind, SegmentKind::Line { .. }))
        .filter_map(|s| s.motion())
        .map(|m| [m.to.0[0], m.to.0[1], m.to.0[2]])
        .collect()
}

/// The id of the first alarm `program` raises on `profile`.
fn first_alarm(profile: ProfileName, program: &str) -> String {
    let run = crate::common::run(
        program.as_bytes(),
        &machine(profile),
        vcnc::Options::default(),
    );
    run.alarms
        .first()
        .map_or_else(String::new, |a| a.code.id().to_string())
}

/// The minutes a feed move takes, from its inverse-time feed.
fn minutes(segment: &Segment) -> Option<f64> {
    match segment.kind {
        SegmentKind::Line {
            feed: Feed::InverseTime(per_minute),
            ..
        } => Some(1.0 / per_minute),
        _ => None,
    }
}

/// FANUC's sine interpolation: X hypothetical, a full CCW circle of radius 10 about (-10, 0) in
/// G17 from X0 Y0 with Z rising 40 mm. The program's X = -10 + 10 cos(t), Y = 10 sin(t), Z = 40
/// t / (2 pi), so the machine traces Y = 10 sin(2 pi Z / 40) with X standing at 0.
const SINE: &str =
    "G90 G17 G54 G00 X0 Y0 Z0\nG07 X0\nG03 X0 Y0 Z40. I-10. F100.\nG07 X1\nG01 Y5.\nM30\n";

fn sine(z: f64) -> f64 {
    10.0 * (2.0 * std::f64::consts::PI * z / 40.0).sin()
}

#[test]
fn a_helix_with_a_hypothetical_axis_traces_a_sine() {
    let segments = segments(ProfileName::Fanuc, SINE);
    let ends = ends(&segments);
    // The pieces of the helix, then the G01 after G07 X1.
    let pieces = &ends[..ends.len() - 1];
    assert!(pieces.len() > 16, "{} pieces", pieces.len());
    let mut from = [0.0; 3];
    for end in pieces {
        assert!(end[0].abs() < 1e-9, "X moved: {end:?}");
        assert!((end[1] - sine(end[2])).abs() < 1e-9, "{end:?} off the sine");
        // Z is linear along the helix, so the piece's middle is at the same parameter as the
        // curve's point of the same Z: the chord stays within the tolerance (0.001 mm) there.
        let middle = [(from[1] + end[1]) / 2.0, (from[2] + end[2]) / 2.0];
        assert!(
            (middle[0] - sine(middle[1])).abs() <= 0.001 + 1e-9,
            "{from:?} -> {end:?}"
        );
        from = *end;
    }
    // The pieces are halvings of the helix, each at most a quarter of it: a quarter turn (Z 10)
    // is the sine's top, half a turn (Z 20) its zero, three quarters (Z 30) its bottom.
    for point in [[10.0, 10.0], [20.0, 0.0], [30.0, -10.0], [40.0, 0.0]] {
        assert!(
            pieces
                .iter()
                .any(|e| (e[2] - point[0]).abs() < 1e-9 && (e[1] - point[1]).abs() < 1e-9),
            "no piece ends at Z{} Y{}",
            point[0],
            point[1]
        );
    }
}

#[test]
fn the_helix_takes_the_time_of_the_whole_helix_at_f() {
    // The feed is distributed as if X moved (Mitsubishi 6.16 precaution 4): the helix is
    // sqrt((2 pi 10)^2 + 40^2) = sqrt(3947.84 + 1600) = 74.4838 mm long, 0.744838 min at F100.
    let segments = segments(ProfileName::Fanuc, SINE);
    let total: f64 = segments.iter().filter_map(minutes).sum();
    assert!((total - 0.744838).abs() < 1e-5, "{total} min");
}

#[test]
fn the_axis_is_real_again_where_it_stands() {
    // After G07 X1 the G01 Y5. moves Y alone: X is where the machine held it, 0.
    let ends = ends(&segments(ProfileName::Fanuc, SINE));
    let last = ends.last().unwrap();
    assert!(
        last[0].abs() < 1e-9 && (last[1] - 5.0).abs() < 1e-9 && (last[2] - 40.0).abs() < 1e-9,
        "{last:?}"
    );
}

#[test]
fn mitsubishi_manual_example_gives_the_sine_on_x_z() {
    // Mitsubishi M700V 6.16's example without its P2 (two more turns): Y hypothetical, a CW
    // circle about (0, -10) from X0 Y0: X = 10 sin(t), Y = -10 + 10 cos(t), Z = 40 t / (2 pi),
    // so X = 10 sin(2 pi Z / 40) "on the X-Z plane" with Y standing.
    let program = "G90 G17 G54 G00 X0 Y0 Z0\nN01 G07 Y0\nN02 G17 G02 X0. Y0. Z40. I0. J-10. F50\nN03 G07 Y1\nM30\n";
    let ends = ends(&segments(ProfileName::Mitsubishi, program));
    assert!(ends.len() > 16, "{} pieces", ends.len());
    for end in &ends {
        assert!(end[1].abs() < 1e-9, "Y moved: {end:?}");
        assert!((end[0] - sine(end[2])).abs() < 1e-9, "{end:?} off the sine");
    }
    assert!(ends
        .iter()
        .any(|e| (e[2] - 10.0).abs() < 1e-9 && (e[0] - 10.0).abs() < 1e-9));
}

#[test]
fn a_line_keeps_the_time_of_its_programmed_length() {
    // G07 Z0, then a line to X30 Y40 Z120 from the origin: Z stands, X and Y move, and the move
    // takes sqrt(30^2 + 40^2 + 120^2) = sqrt(16900) = 130 mm at F100 = 1.3 min.
    let program = "G90 G17 G54 G00 X0 Y0 Z0\nG07 Z0\nG01 X30. Y40. Z120. F100.\nG07 Z1\nM30\n";
    let segments = segments(ProfileName::Fanuc, program);
    let ends = ends(&segments);
    assert_eq!(ends, [[30.0, 40.0, 0.0]]);
    let total: f64 = segments.iter().filter_map(minutes).sum();
    assert!((total - 1.3).abs() < 1e-9, "{total} min");
}

#[test]
fn a_value_other_than_zero_makes_the_axis_real() {
    // Mitsubishi 6.16 detail 4: G07 Y2 cancels like G07 Y1, so G01 Y10. moves Y.
    let program = "G90 G17 G54 G00 X0 Y0 Z0\nG07 Y0\nG07 Y2\nG01 Y10. F100.\nM30\n";
    let ends = ends(&segments(ProfileName::Mitsubishi, program));
    assert_eq!(ends.last().unwrap(), &[0.0, 10.0, 0.0]);
}

#[test]
fn g07_is_absent_where_the_control_lacks_it() {
    // Not in the Syntec (000), FANUC 0M (001) or Haas code tables.
    for profile in [ProfileName::Syntec, ProfileName::Fanuc0m, ProfileName::Haas] {
        assert_eq!(
            first_alarm(profile, "G07 X0\nM30\n"),
            "unknown_g_code",
            "{profile:?}"
        );
    }
}

#[test]
fn g07_is_refused_under_compensation_and_other_modes_under_g07() {
    let mut with_radius = machine(ProfileName::Fanuc);
    with_radius.tool_offsets.insert(
        1,
        vcnc::machine::ToolOffset {
            number: 1,
            radius: 5.0,
            ..Default::default()
        },
    );
    let run = crate::common::run(
        b"G90 G17 G00 X0 Y0\nG41 G01 X10. D1 F100.\nG07 Y0\nM30\n",
        &with_radius,
        vcnc::Options::default(),
    );
    assert_eq!(run.error().map(|a| a.code.id()), Some("word_not_allowed"));
    assert_eq!(
        first_alarm(ProfileName::Fanuc, "G07 Y0\nG12.1\nM30\n"),
        "word_not_allowed"
    );
    assert_eq!(
        first_alarm(ProfileName::Fanuc, "G07\nM30\n"),
        "word_not_allowed"
    );
}
