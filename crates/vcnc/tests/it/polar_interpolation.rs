//! G12.1/G13.1 polar coordinate interpolation (issue #5, spec/iso-syntec-milling.md 1.13).
//!
//! A program in G12.1 is checked against the same contour run on the X-Y plane (C written as Y):
//! every X-C piece, mapped back onto the part through x = X cos C, y = X sin C, must lie on that
//! X-Y tool-centre path, its ends exactly and its inside within the profile's tolerance.

use crate::common;

use crate::common::plane::Element;
use proptest::prelude::*;
use std::path::Path;
use vcnc::motion::Feed;
use vcnc::{AlarmCode, Machine, Options, ProfileName, Segment, SegmentKind};

/// The profile's default tolerance, mm.
const TOLERANCE: f64 = 0.001;

/// A machine of `profile` with X Y Z and a C axis turning the part.
fn machine(profile: ProfileName) -> Machine {
    common::with_c_axis(profile)
}

fn run(program: &str, machine: &Machine) -> common::Run {
    common::run(program.as_bytes(), machine, Options::default())
}

/// Runs `program` on the FANUC profile with a C axis; it must not raise an alarm.
#[track_caller]
fn run_without_alarm(program: &str) -> common::Run {
    let run = run(program, &machine(ProfileName::Fanuc));
    assert!(run.error().is_none(), "{:?}", run.error());
    run
}

/// The motion segments of `run` written by the program lines `lines` (1-based).
fn motions_of(run: &common::Run, lines: std::ops::RangeInclusive<u32>) -> Vec<Segment> {
    run.segments
        .iter()
        .filter(|s| s.motion().is_some() && lines.contains(&s.span.line))
        .copied()
        .collect()
}

/// Where a machine position (X radius, C degrees) is on the part, seen from the rotation centre.
fn on_part(p: &[f64; 6]) -> (f64, f64) {
    let (sin, cos) = p[5].to_radians().sin_cos();
    (p[0] * cos, p[0] * sin)
}

fn distance(path: &[Element], p: (f64, f64)) -> f64 {
    path.iter()
        .map(|e| e.distance(p))
        .fold(f64::INFINITY, f64::min)
}

/// Asserts that the X-C `pieces` trace `path` (X-Y) on the part: ends within `at_ends`, points
/// inside each piece (straight in X and C) within the tolerance. Returns the largest deviation
/// inside pieces.
#[track_caller]
fn assert_traces(pieces: &[Segment], path: &[Element], at_ends: f64) -> f64 {
    assert!(!pieces.is_empty(), "no X-C motion");
    let mut worst: f64 = 0.0;
    for (i, piece) in pieces.iter().enumerate() {
        let motion = piece.motion().unwrap();
        assert!(
            matches!(
                piece.kind,
                SegmentKind::Line { .. } | SegmentKind::Rapid { .. }
            ),
            "piece {i} is not straight: {piece:?}"
        );
        if i > 0 {
            assert_eq!(
                pieces[i - 1].motion().unwrap().to,
                motion.from,
                "piece {i} does not start where piece {} ended",
                i - 1
            );
        }
        for end in [&motion.from.0, &motion.to.0] {
            assert!(end.iter().all(|v| v.is_finite()));
            let d = distance(path, on_part(end));
            assert!(
                d <= at_ends,
                "piece {i} ends {d} mm off the path at X{} C{} (part {:?})",
                end[0],
                end[5],
                on_part(end)
            );
        }
        for k in 1..8 {
            let s = f64::from(k) / 8.0;
            let p: [f64; 6] =
                std::array::from_fn(|a| motion.from.0[a] + (motion.to.0[a] - motion.from.0[a]) * s);
            worst = worst.max(distance(path, on_part(&p)));
        }
    }
    assert!(
        worst <= TOLERANCE * 1.05,
        "a piece runs {worst} mm off the path (tolerance {TOLERANCE})"
    );
    worst
}

/// The X-Y tool-centre path of the X-Y version of a G12.1 program.
fn xy_path(
    program: &str,
    profile: ProfileName,
    lines: std::ops::RangeInclusive<u32>,
) -> Vec<Element> {
    let run = run(program, &Machine::default().with_profile(profile).unwrap());
    assert!(run.error().is_none(), "{:?}", run.error());
    motions_of(&run, lines)
        .iter()
        .filter_map(|s| Element::of(&s.kind))
        .collect()
}

fn last_position(run: &common::Run) -> [f64; 6] {
    run.segments
        .iter()
        .rev()
        .find_map(|s| s.motion().map(|m| m.to.0))
        .unwrap()
}

fn example(shared: &Path, name: &str) -> String {
    let path = shared.join("spec/examples/syntec").join(name);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The line (1-based) of the first line of `text` that starts with `prefix`.
fn line_of(text: &str, prefix: &str) -> u32 {
    text.lines()
        .position(|l| l.starts_with(prefix))
        .map(|i| i as u32 + 1)
        .unwrap_or_else(|| panic!("no line starts with {prefix}"))
}

/// The example with C written as Y and G12.1/G13.1 replaced by `start` and nothing: the same
/// contour on the X-Y plane, line for line.
fn as_xy(text: &str, start: &str) -> String {
    text.lines()
        .map(|line| {
            if line.starts_with("G12.1") {
                start.to_string()
            } else if line.starts_with("G13.1") {
                String::new()
            } else if line.starts_with('(') {
                line.to_string()
            } else {
                line.replace('C', "Y")
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// Runs the Syntec example `name` on a machine with C: the run, its X-C pieces from G12.1 to
/// G13.1, and the X-Y path of the same lines with G12.1 replaced by `start`.
fn run_example(
    shared: &Path,
    name: &str,
    start: &str,
) -> (common::Run, Vec<Segment>, Vec<Element>) {
    let text = example(shared, name);
    let run = run(&text, &machine(ProfileName::Syntec));
    assert!(run.error().is_none(), "{:?}", run.error());
    let lines = line_of(&text, "G12.1")..=line_of(&text, "G13.1");
    let pieces = motions_of(&run, lines.clone());
    let path = xy_path(&as_xy(&text, start), ProfileName::Syntec, lines);
    (run, pieces, path)
}

#[test]
fn syntec_example_18_runs_its_contour_on_x_and_c() {
    let Some(shared) = common::shared_dir() else {
        return;
    };
    let (run, pieces, path) = run_example(&shared, "18-g12.1-polar-interp.nc", "");
    // The contour of the header: 55,0 - 20,0 - 20,10 - arc to 10,20 - -20,20 - -20,-10 - arc to
    // -10,-20 - 20,-20 - 20,0 - 55,0 (no D: compensation by radius 0).
    let corners = [
        (110.0, 0.0),
        (55.0, 0.0),
        (20.0, 0.0),
        (20.0, 10.0),
        (10.0, 20.0),
        (-20.0, 20.0),
        (-20.0, -10.0),
        (-10.0, -20.0),
        (20.0, -20.0),
        (20.0, 0.0),
        (55.0, 0.0),
    ];
    let ends: Vec<_> = path.iter().map(Element::end).collect();
    for corner in &corners[1..] {
        assert!(
            ends.iter()
                .any(|e| (e.0 - corner.0).hypot(e.1 - corner.1) < 1e-9),
            "the X-Y run misses {corner:?}"
        );
    }
    assert_traces(&pieces, &path, 1e-9);
    let start = pieces[0].motion().unwrap().from.0;
    assert_eq!((start[0], start[5]), (110.0, 0.0));
    // Around the centre once, counter-clockwise: C ends one turn on, at 360 degrees.
    let end = last_position(&run);
    assert!(
        (end[0] - 55.0).abs() < 1e-9 && (end[5] - 360.0).abs() < 1e-9,
        "{end:?}"
    );
    // Sampled points of the contour: the arc's middle and a corner, in X and C.
    let visits = |x: f64, c: f64| {
        pieces.iter().any(|s| {
            let to = s.motion().unwrap().to.0;
            (to[0] - x).abs() < 1e-9 && (to[5] - c).abs() < 1e-9
        })
    };
    assert!(visits(20f64.hypot(20.0), 135.0), "(-20, 20)");
    assert!(
        visits(20f64.hypot(10.0), 180.0 + 10f64.atan2(20.0).to_degrees()),
        "(-20, -10)"
    );
    // Every piece takes the time its stretch of the contour takes at F100 along the part: an
    // inverse-time feed of F / length (the piece's chord on the part is its stretch of the
    // contour, to the tolerance).
    for piece in &pieces[1..] {
        if let SegmentKind::Line { feed, motion } = piece.kind {
            let Feed::InverseTime(per_minute) = feed else {
                panic!("{feed:?}")
            };
            let (a, b) = (on_part(&motion.from.0), on_part(&motion.to.0));
            let length = (b.0 - a.0).hypot(b.1 - a.1);
            let minutes = length / 100.0;
            assert!(
                (1.0 / per_minute - minutes).abs() <= 1e-3 * minutes,
                "{} min for {length} mm",
                1.0 / per_minute
            );
        }
    }
    // G13.1: the position is the machine's again; Z never moved.
    assert!(pieces.iter().all(|s| s.motion().unwrap().to.0[2] == 0.0));
}

#[test]
fn syntec_example_19_puts_the_program_zero_off_the_centre() {
    // On X-Y the eccentricity is a shift of the program zero to 50,50 from the centre.
    let Some(shared) = common::shared_dir() else {
        return;
    };
    let (run, pieces, path) = run_example(&shared, "19-g12.1-eccentric.nc", "G52 X50. Y50.");
    assert_traces(&pieces, &path, 1e-9);
    // The tool stood at X110 C0, the program point 60,-50; the contour's end 55,0 is 105,50 from
    // the centre.
    let end = last_position(&run);
    assert!((end[0] - 105f64.hypot(50.0)).abs() < 1e-9, "{end:?}");
    assert!(
        (end[5] - 50f64.atan2(105.0).to_degrees()).abs() < 1e-9,
        "{end:?}"
    );
    let corner: (f64, f64) = (10.0 + 50.0, 20.0 + 50.0);
    assert!(pieces.iter().any(|s| {
        let to = s.motion().unwrap().to.0;
        (to[0] - corner.0.hypot(corner.1)).abs() < 1e-9
            && (to[5] - corner.1.atan2(corner.0).to_degrees()).abs() < 1e-9
    }));
}

#[test]
fn cutter_compensation_offsets_the_contour_in_the_cartesian_plane() {
    let program = "G90 G94 G0 X60. C0.\nG12.1\nG42 D1 X55.\nG1 X20. F100.\nC10.\nM8\nG3 X10. C20. R10.\nG1 X-20.\nC-10.\nG3 X-10. C-20. R10.\nG1 X20.\nC0.\nG40 X55.\nG13.1\nM30";
    let mut machine = machine(ProfileName::Fanuc);
    machine.tool_offsets.insert(
        1,
        vcnc::machine::ToolOffset {
            number: 1,
            radius: 3.0,
            ..Default::default()
        },
    );
    let run = run(program, &machine);
    assert!(run.error().is_none(), "{:?}", run.error());
    let pieces = motions_of(&run, 2..=14);
    let mut xy_machine = Machine::default();
    xy_machine.tool_offsets = machine.tool_offsets.clone();
    let xy = common::run(
        as_xy(program, "").as_bytes(),
        &xy_machine,
        Options::default(),
    );
    assert!(xy.error().is_none());
    let path: Vec<_> = motions_of(&xy, 2..=14)
        .iter()
        .filter_map(|s| Element::of(&s.kind))
        .collect();
    // The compensated X-Y path goes 3 mm right of the contour: along C0 at Y3, up X20 at X23.
    let ends: Vec<_> = path.iter().map(Element::end).collect();
    for corner in [(23.0, 3.0), (23.0, 10.0)] {
        assert!(
            ends.iter()
                .any(|e| (e.0 - corner.0).hypot(e.1 - corner.1) < 1e-9),
            "{corner:?} not in {ends:?}"
        );
    }
    assert_traces(&pieces, &path, 1e-9);
    // M8 waited with compensation for the corner after C10. and stays between its moves.
    let index_of = |kind: &dyn Fn(&Segment) -> bool| run.segments.iter().position(kind).unwrap();
    let coolant = index_of(&|s| matches!(s.kind, SegmentKind::Coolant { on: true }));
    let last_c10 = run.segments.iter().rposition(|s| s.span.line == 5).unwrap();
    let first_arc = index_of(&|s| s.span.line == 7);
    assert!(last_c10 < coolant && coolant < first_arc);
}

#[test]
fn without_a_c_axis_g12_1_is_an_alarm_at_its_block() {
    let run = run("G0 X10.\nG12.1\nG1 X5. F100.\nM30", &Machine::default());
    let alarm = run.error().expect("an alarm");
    assert_eq!(alarm.code, AlarmCode::AxisNotOnMachine);
    assert_eq!(
        alarm.message,
        "G12.1 needs the C axis: the machine has none"
    );
    assert_eq!(alarm.span.unwrap().line, 2);
    assert!(run
        .segments
        .iter()
        .all(|s| s.span.line < 2 || s.motion().is_none()));
}

#[test]
fn controls_without_polar_interpolation_do_not_know_g12_1() {
    for profile in [ProfileName::Haas, ProfileName::Fanuc0m] {
        let run = run("G12.1\nM30", &machine(profile));
        assert_eq!(run.error().unwrap().code, AlarmCode::UnknownGCode);
    }
}

#[test]
fn g13_1_returns_to_motion_in_machine_x_and_c() {
    let program = "G0 X10. C90.\nG12.1\nG1 X-10. F200.\nG13.1\nG1 X30. C45.\nY5.\nM30";
    let run = run_without_alarm(program);
    // In the mode: from (0, 10) on the part to (-10, 10): X grows to 14.14, C to 135 degrees.
    let pieces = motions_of(&run, 3..=3);
    let end = pieces.last().unwrap().motion().unwrap().to.0;
    assert!((end[0] - 200f64.sqrt()).abs() < 1e-9 && (end[5] - 135.0).abs() < 1e-9);
    assert!(pieces.len() > 1);
    assert_traces(&pieces, &[Element::Line((0.0, 10.0), (-10.0, 10.0))], 1e-9);
    // After G13.1 the axes are the machine's: one straight move of X and C, then Y.
    let after = motions_of(&run, 5..=6);
    assert_eq!(after.len(), 2);
    let first = after[0].motion().unwrap();
    assert_eq!(first.from.0, end);
    assert_eq!((first.to.0[0], first.to.0[5]), (30.0, 45.0));
    assert_eq!(after[1].motion().unwrap().to.0[1], 5.0);
    assert_eq!(
        run.segments.last().unwrap().kind,
        SegmentKind::End {
            kind: vcnc::motion::EndKind::M30
        }
    );
}

#[test]
fn a_line_through_the_centre_turns_c_half_a_turn_there() {
    let program = "G0 X10. C180.\nG12.1\nG1 X10. F100.\nG13.1\nM30";
    let run = run_without_alarm(program);
    let pieces = motions_of(&run, 3..=3);
    assert!(pieces.len() < 200, "{} pieces", pieces.len());
    assert_traces(&pieces, &[Element::Line((-10.0, 0.0), (10.0, 0.0))], 1e-9);
    let end = last_position(&run);
    assert!((end[0] - 10.0).abs() < 1e-9, "{end:?}");
    assert!((end[5] - 0.0).abs() < 1e-9, "{end:?}");
    // X never goes below the centre.
    assert!(pieces.iter().all(|s| s.motion().unwrap().to.0[0] >= 0.0));
}

#[test]
fn a_line_near_the_centre_stays_within_the_tolerance() {
    let program = "G0 X10. C180.\nG12.1\nG1 C0.01 F100.\nX10.\nG13.1\nM30";
    let run = run_without_alarm(program);
    let pieces = motions_of(&run, 3..=4);
    assert!(pieces.len() < 2000, "{} pieces", pieces.len());
    assert_traces(
        &pieces,
        &[
            Element::Line((-10.0, 0.0), (-10.0, 0.01)),
            Element::Line((-10.0, 0.01), (10.0, 0.01)),
        ],
        1e-9,
    );
}

#[test]
fn codes_that_move_the_coordinate_system_are_refused_in_the_mode() {
    for (block, code) in [
        ("G54", AlarmCode::WordNotAllowed),
        ("G52 X1.", AlarmCode::WordNotAllowed),
        ("G17", AlarmCode::WordNotAllowed),
        ("G81 Z-1. R1.", AlarmCode::WordNotAllowed),
        ("G1 Y5. F100.", AlarmCode::WordNotAllowed),
        ("G41 D1 X5. F100.\nG13.1", AlarmCode::WordNotAllowed),
        ("G12.1", AlarmCode::WordNotAllowed),
    ] {
        let program = format!("G0 X10. C0.\nG12.1\n{block}\nG13.1\nM30");
        let run = run(&program, &machine(ProfileName::Fanuc));
        let alarm = run.error().unwrap_or_else(|| panic!("{block}: no alarm"));
        assert_eq!(alarm.code, code, "{block}: {alarm:?}");
    }
    let below = run("G0 X-1. C0.\nG12.1\nM30", &machine(ProfileName::Fanuc));
    assert_eq!(below.error().unwrap().code, AlarmCode::NotSupportedYet);
    let compensating = run(
        "G0 X10. C0.\nG41 D1 X5.\nG12.1\nM30",
        &machine(ProfileName::Fanuc),
    );
    assert_eq!(
        compensating.error().unwrap().message,
        "G12.1 cannot be commanded while cutter compensation (G41/G42) is on"
    );
}

#[test]
fn rotation_scaling_mirror_polar_words_and_cycles_are_refused_in_the_mode() {
    // Spec 1.13.2 rule 3 lists what the mode allows (G01-G03, G04, G40-G42, G65-G67); the
    // codes that turn these transforms on or off, and the canned cycles, are not in it.
    for block in [
        "G68 R45.",
        "G69",
        "G51 P2.",
        "G50",
        "G51.1 X0",
        "G50.1",
        "G16",
        "G15",
        "G80",
        "G83 Z-1. R1. Q1.",
    ] {
        let program = format!("G0 X10. C0.\nG12.1\n{block}\nG13.1\nM30");
        let run = run(&program, &machine(ProfileName::Fanuc));
        let alarm = run.error().unwrap_or_else(|| panic!("{block}: no alarm"));
        assert_eq!(alarm.code, AlarmCode::WordNotAllowed, "{block}: {alarm:?}");
        assert_eq!(alarm.span.unwrap().line, 3, "{block}");
        assert!(
            alarm
                .message
                .ends_with("cannot be commanded during polar coordinate interpolation (G12.1)"),
            "{block}: {}",
            alarm.message
        );
    }
}

#[test]
fn g12_1_under_rotation_scaling_mirror_polar_words_or_a_cycle_is_refused() {
    // The mode allows no transform or cycle (spec 1.13.2 rules 3 and 5): one left on from before
    // G12.1 would apply to every block of the mode, so the control refuses G12.1, at its block,
    // before anything moves in the mode, and says what to cancel.
    for (before, what, cancel) in [
        ("G68 R45.", "coordinate rotation", "G69"),
        ("G51 P2.", "scaling or mirror image", "G50"),
        ("G51.1 X0", "scaling or mirror image", "G50.1"),
        ("G16", "polar coordinate command", "G15"),
        ("G81 Z-1. R1. F100.", "a canned cycle", "G80"),
    ] {
        let program = format!("G0 X10. C0.\n{before}\nG12.1\nG1 X5. F100.\nM30");
        let run = run(&program, &machine(ProfileName::Fanuc));
        let alarm = run.error().unwrap_or_else(|| panic!("{before}: no alarm"));
        assert_eq!(alarm.code, AlarmCode::WordNotAllowed, "{before}: {alarm:?}");
        assert_eq!(alarm.span.unwrap().line, 3, "{before}");
        assert!(alarm.message.contains(what), "{before}: {}", alarm.message);
        let help = alarm.help.as_deref().unwrap_or_default();
        assert!(help.contains(cancel), "{before}: {help}");
        assert!(run.segments.iter().all(|s| s.span.line < 3));
    }
}

#[test]
fn system_variable_4021_holds_the_polar_interpolation_mode() {
    // FANUC's modal group 21 is G12.1/G13.1 (G13.1 at power-on); #4021 reads it as 12.1 or
    // 13.1. A control without the function has nothing in that group.
    let program = "#1=#4021\nG0 X10. C0.\nG12.1\n#2=#4021\nG1 X5. F100.\nG13.1\n#3=#4021\nM30";
    for (profile, expected) in [
        (ProfileName::Fanuc, [12.1, 13.1]),
        (ProfileName::Syntec, [12.1, 13.1]),
        (ProfileName::Mitsubishi, [12.1, 13.1]),
    ] {
        let values = variables(program, &machine(profile));
        assert_eq!(
            [values[1], values[2], values[3]],
            [Some(expected[1]), Some(expected[0]), Some(expected[1])],
            "{profile:?}"
        );
    }
    let values = variables("#1=#4021\nM30", &machine(ProfileName::Fanuc0m));
    assert_eq!(values[1], Some(0.0));
}

/// Variables #0-#9 after `program` ran without an alarm.
fn variables(program: &str, machine: &Machine) -> Vec<Option<f64>> {
    let mut interpreter = vcnc::interpret_str(program, machine, Options::default());
    for item in interpreter.by_ref() {
        assert!(item.is_ok(), "{item:?}");
    }
    (0..10).map(|n| interpreter.variable(n)).collect()
}

#[test]
fn incremental_c_and_a_full_circle_about_an_off_centre_point() {
    let program = "G0 X20. C0.\nG12.1\nG91 G1 C5. F100.\nG90 G2 I-5. J-5.\nG13.1\nM30";
    let run = run_without_alarm(program);
    let pieces = motions_of(&run, 3..=4);
    // The circle about (15, 0) through (20, 5), as two half circles.
    let (east, west) = ((15.0 + 50f64.sqrt(), 0.0), (15.0 - 50f64.sqrt(), 0.0));
    let half = |from, to| Element::Arc {
        from,
        to,
        center: (15.0, 0.0),
        ccw: true,
    };
    let path = [
        Element::Line((20.0, 0.0), (20.0, 5.0)),
        half(east, west),
        half(west, east),
    ];
    assert_traces(&pieces, &path, 1e-9);
    let end = last_position(&run);
    assert!((end[0] - 425f64.sqrt()).abs() < 1e-9);
}

/// One random move in the plane: a line to a point, or an arc by its centre offset, sweep and
/// direction.
#[derive(Clone, Debug)]
enum Move {
    Line(f64, f64),
    Arc {
        i: f64,
        j: f64,
        sweep: f64,
        ccw: bool,
    },
}

fn any_move() -> impl Strategy<Value = Move> {
    prop_oneof![
        (-60.0..60.0, -60.0..60.0).prop_map(|(x, y)| Move::Line(x, y)),
        (-30.0..30.0, -30.0..30.0, 0.1..6.2, any::<bool>())
            .prop_map(|(i, j, sweep, ccw)| { Move::Arc { i, j, sweep, ccw } }),
    ]
}

/// The program of `moves` from (x0, 0), in G12.1 with C (`polar`) or on X-Y.
fn random_program(x0: f64, moves: &[Move], polar: bool) -> String {
    let second = if polar { 'C' } else { 'Y' };
    let mut text = format!("G90 G0 X{x0:.6} {second}0.\n");
    text.push_str(if polar { "G12.1\n" } else { "\n" });
    text.push_str("G1 F500.\n");
    let mut here = (x0, 0.0);
    for m in moves {
        match *m {
            Move::Line(x, y) => {
                text.push_str(&format!("G1 X{x:.6} {second}{y:.6}\n"));
                here = (x, y);
            }
            Move::Arc { i, j, sweep, ccw } => {
                let center = (here.0 + i, here.1 + j);
                let start = (-j).atan2(-i);
                let end = if ccw { start + sweep } else { start - sweep };
                let r = i.hypot(j);
                let to = (center.0 + r * end.cos(), center.1 + r * end.sin());
                let g = if ccw { 3 } else { 2 };
                text.push_str(&format!(
                    "G{g} X{:.6} {second}{:.6} I{i:.6} J{j:.6}\n",
                    to.0, to.1
                ));
                here = to;
            }
        }
    }
    text.push_str(if polar { "G13.1\nM30\n" } else { "\nM30\n" });
    text
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn random_lines_and_arcs_map_back_onto_their_cartesian_path(
        x0 in 1.0..80.0f64,
        moves in prop::collection::vec(any_move(), 1..5),
    ) {
        let polar = random_program(x0, &moves, true);
        let run = run(&polar, &machine(ProfileName::Fanuc));
        prop_assert!(run.error().is_none(), "{:?}", run.error());
        let last_line = 3 + moves.len() as u32;
        let path = xy_path(&random_program(x0, &moves, false), ProfileName::Fanuc, 3..=last_line);
        let pieces = motions_of(&run, 3..=last_line);
        assert_traces(&pieces, &path, 1e-5);
        let end = last_position(&run);
        let xy_end = path.last().unwrap().end();
        let part = on_part(&end);
        prop_assert!((part.0 - xy_end.0).hypot(part.1 - xy_end.1) < 1e-6);
    }
}

#[test]
fn the_planner_times_the_contour_at_f_along_the_part() {
    // A line 40 mm long on the part, 50 mm from the centre, at F600: 4 s along the contour,
    // though X hardly moves and C turns 43.6 degrees. G61 stops at the end of the block, not
    // between its pieces. The planner still blends the pieces' junctions in X Y Z, where an X-C
    // piece is mostly standing X, and the blends take a little off each piece: 3 % short here
    // (it was 75 % short in G64 and 27 % in G61 when the pieces carried F as mm/min of X).
    let program = "G61\nG0 X50. C-21.8014\nG12.1\nG1 X50. C20. F600.\nG13.1\nM30";
    let machine = machine(ProfileName::Fanuc);
    let stream = vcnc::interpret_str(program, &machine, Options::default());
    let mut cutting = 0.0;
    for item in vcnc::plan::Planner::new(stream, &machine, vcnc::plan::PlanOptions::default()) {
        let Some(timed) = item.expect("no alarm").segment().copied() else {
            continue;
        };
        if timed.segment.span.line == 4 {
            cutting += timed.dt;
        }
    }
    let length = 20.0 + 50.0 * (21.8014_f64).to_radians().tan();
    let expected = length / 600.0 * 60.0;
    assert!(
        (cutting - expected).abs() < 0.04 * expected,
        "{cutting} s for {length} mm at F600 ({expected} s)"
    );
}
