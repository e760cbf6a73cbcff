//! Syntec spiral and conical interpolation (G02/G03 with L, spec 1.6): the pieces follow an
//! Archimedean spiral about the I J K centre, the turns are counted as the manual counts them,
//! and bad words alarm. The manual's two examples are asserted in seed_examples.toml.

use crate::common::run;
use proptest::prelude::*;
use std::f64::consts::TAU;
use vcnc::motion::Feed;
use vcnc::{AlarmCode, Machine, Options, ProfileName, SegmentKind};

fn syntec() -> Machine {
    Machine::default()
        .with_profile(ProfileName::Syntec)
        .unwrap()
}

/// The end points of the cutting pieces, in the XY plane and Z.
fn pieces(program: &str) -> Vec<[f64; 3]> {
    let run = run(program.as_bytes(), &syntec(), Options::default());
    assert!(run.error().is_none(), "{:?}", run.error());
    run.segments
        .iter()
        .filter_map(|s| match &s.kind {
            SegmentKind::Line { motion, .. } => Some(motion.to.xyz()),
            _ => None,
        })
        .collect()
}

/// Angle swept about `centre` from `start` through `points`, signed (counterclockwise
/// positive), and the radius of each point.
fn unwrap_angles(centre: (f64, f64), start: [f64; 3], points: &[[f64; 3]]) -> Vec<(f64, f64)> {
    let angle = |p: &[f64; 3]| (p[1] - centre.1).atan2(p[0] - centre.0);
    let mut previous = angle(&start);
    let mut swept = 0.0;
    points
        .iter()
        .map(|p| {
            let a = angle(p);
            let mut step = a - previous;
            if step > TAU / 2.0 {
                step -= TAU;
            } else if step < -TAU / 2.0 {
                step += TAU;
            }
            swept += step;
            previous = a;
            (swept, (p[0] - centre.0).hypot(p[1] - centre.1))
        })
        .collect()
}

#[test]
fn l_counts_the_turns_with_the_incomplete_one() {
    // From 50,0 about the origin to 0,20 counterclockwise: a quarter turn with L1, one and a
    // quarter with L2, two and a quarter with L3.
    for (l, turns) in [(1, 0.25), (2, 1.25), (3, 2.25)] {
        let points = pieces(&format!(
            "G90 G17 F600\nG00 X50. Y0\nG03 X0 Y20. I-50. L{l}\nM30\n"
        ));
        let swept = unwrap_angles((0.0, 0.0), [50.0, 0.0, 0.0], &points);
        let (angle, radius) = *swept.last().unwrap();
        assert!((angle - turns * TAU).abs() < 1e-9, "L{l}: {angle}");
        assert!((radius - 20.0).abs() < 1e-9, "L{l}: {radius}");
        assert_eq!(points.last().unwrap(), &[0.0, 20.0, 0.0]);
    }
}

#[test]
fn an_end_on_the_start_angle_is_whole_turns() {
    // The end is straight inwards from the start: L2 makes two whole turns, clockwise.
    let points = pieces("G90 G17 F600\nG00 X30. Y0\nG02 X10. I-30. L2\nM30\n");
    let swept = unwrap_angles((0.0, 0.0), [30.0, 0.0, 0.0], &points);
    let (angle, radius) = *swept.last().unwrap();
    assert!((angle + 2.0 * TAU).abs() < 1e-9, "{angle}");
    assert!((radius - 10.0).abs() < 1e-9);
}

#[test]
fn a_cone_in_g18_moves_y_with_the_angle() {
    // G18: the plane is Z-X, centre from K and I; Y is the axis along the cone.
    let points = pieces("G90 G18 F600\nG00 X0 Z40.\nG02 X0 Z10. Y30. K-40. L2\nM30\n");
    let end = points.last().unwrap();
    assert_eq!(end, &[0.0, 30.0, 10.0]);
    // Y grows linearly along the pieces' angles: halfway through the sweep, halfway up.
    let half = points.len() / 2;
    assert!((points[half][1] - 15.0).abs() < 0.1, "{:?}", points[half]);
}

#[test]
fn inverse_time_spreads_the_block_time_over_the_pieces() {
    let run = run(
        b"G90 G17 G94 F600\nG00 X50. Y0\nG93\nG02 X0 Y-20. I-50. L2 F2.\nG94\nM30\n",
        &syntec(),
        Options::default(),
    );
    assert!(run.error().is_none(), "{:?}", run.error());
    let minutes: f64 = run
        .segments
        .iter()
        .filter_map(|s| match &s.kind {
            SegmentKind::Line {
                feed: Feed::InverseTime(f),
                ..
            } => Some(1.0 / f),
            _ => None,
        })
        .sum();
    // F2. in G93: the block takes half a minute, whatever it is cut into.
    assert!((minutes - 0.5).abs() < 1e-12, "{minutes}");
}

#[test]
fn bad_turns_and_centres_alarm() {
    let cases = [
        ("G02 X-10. I-20. L0", AlarmCode::WordNotAllowed),
        ("G02 X-10. I-20. L2.5", AlarmCode::DecimalPointNotAllowed),
        ("G02 X-10. I-20. L10000", AlarmCode::WordNotAllowed),
        ("G02 X-10. R15. L2", AlarmCode::WordNotAllowed),
        ("G02 X-10. L2", AlarmCode::ArcWithoutCenter),
        ("G02 X-10. I0 J0 L2", AlarmCode::ArcWithoutCenter),
    ];
    for (block, code) in cases {
        let program = format!("G90 G17 F600\nG00 X20. Y0\n{block}\nM30\n");
        let run = run(program.as_bytes(), &syntec(), Options::default());
        let alarm = run.error().unwrap_or_else(|| panic!("{block}: no alarm"));
        assert_eq!(alarm.code, code, "{block}: {alarm:?}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Every piece ends on the Archimedean spiral (radius linear in the angle swept), the
    /// chord between two pieces stays within the tolerance of the curve, and the last piece
    /// ends on the programmed end point.
    #[test]
    fn pieces_follow_the_archimedean_spiral(
        r0 in 1.0..80.0_f64,
        start_angle in 0.0..TAU,
        end_radius in 0.5..80.0_f64,
        end_angle in 0.0..TAU,
        turns in 1u32..4,
        ccw in any::<bool>(),
    ) {
        let (cx, cy) = (10.0, -5.0);
        let start = [cx + r0 * start_angle.cos(), cy + r0 * start_angle.sin(), 0.0];
        let end = [cx + end_radius * end_angle.cos(), cy + end_radius * end_angle.sin()];
        let program = format!(
            "G90 G17 F600\nG00 X{:.6} Y{:.6}\nG0{} X{:.6} Y{:.6} I{:.6} J{:.6} L{turns}\nM30\n",
            start[0], start[1], if ccw { 3 } else { 2 },
            end[0], end[1], cx - start[0], cy - start[1],
        );
        let points = pieces(&program);
        // The start as the control reads it (six decimals).
        let start = [(start[0] * 1e6).round() / 1e6, (start[1] * 1e6).round() / 1e6, 0.0];
        let r0 = (start[0] - cx).hypot(start[1] - cy);
        let swept = unwrap_angles((cx, cy), start, &points);
        let (total, r1) = *swept.last().unwrap();
        let sign = if ccw { 1.0 } else { -1.0 };
        prop_assert!(sign * total > (turns as f64 - 1.0) * TAU - 1e-9);
        prop_assert!(sign * total <= turns as f64 * TAU + 1e-9);
        let last = points.last().unwrap();
        prop_assert!((last[0] - (end[0] * 1e6).round() / 1e6).abs() < 1e-9);
        prop_assert!((last[1] - (end[1] * 1e6).round() / 1e6).abs() < 1e-9);
        let mut previous = (start, 0.0);
        for (point, (angle, radius)) in points.iter().zip(&swept) {
            let expected = r0 + (r1 - r0) * angle / total;
            prop_assert!((radius - expected).abs() < 1e-6, "radius {radius}, expected {expected}");
            // The curve at the middle angle against the chord's midpoint.
            let middle_angle = (previous.1 + angle) / 2.0;
            let middle_radius = r0 + (r1 - r0) * middle_angle / total;
            let start_angle = (start[1] - cy).atan2(start[0] - cx);
            let curve = (
                cx + middle_radius * (start_angle + middle_angle).cos(),
                cy + middle_radius * (start_angle + middle_angle).sin(),
            );
            let chord = ((previous.0[0] + point[0]) / 2.0, (previous.0[1] + point[1]) / 2.0);
            let deviation = (curve.0 - chord.0).hypot(curve.1 - chord.1);
            prop_assert!(deviation <= 0.0011, "chord {deviation} mm off the curve");
            previous = (*point, *angle);
        }
    }
}
