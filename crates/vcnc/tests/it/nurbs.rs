//! G06.2 NURBS interpolation (Syntec spec 1.10, manual 000 L748-835): the chords vcnc passes on
//! lie on and within the tolerance of the curve as the manual defines it, evaluated here on its
//! own from the manual's basis functions (L811-815), not by de Boor's algorithm the library uses;
//! the path turns smoothly; the planner times the curve as it times the same chords written as
//! G01 lines; bad curves are alarms. Example 17 is asserted in seed_examples.toml.

use crate::common::{plan::total_seconds, run};
use vcnc::{AlarmCode, Machine, Options, ProfileName, SegmentKind};

fn syntec() -> Machine {
    Machine::default()
        .with_profile(ProfileName::Syntec)
        .unwrap()
}

/// The manual's basis function N_{i,p}(u) (L811-815), 0/0 taken as 0.
fn basis(knots: &[f64], i: usize, p: usize, u: f64) -> f64 {
    if p == 0 {
        return if knots[i] <= u && u < knots[i + 1] {
            1.0
        } else {
            0.0
        };
    }
    let left = knots[i + p] - knots[i];
    let right = knots[i + p + 1] - knots[i + 1];
    let a = if left > 0.0 {
        (u - knots[i]) / left * basis(knots, i, p - 1, u)
    } else {
        0.0
    };
    let b = if right > 0.0 {
        (knots[i + p + 1] - u) / right * basis(knots, i + 1, p - 1, u)
    } else {
        0.0
    };
    a + b
}

/// The manual's C(u) (L798): the weighted sum of the control points over the sum of weights.
/// At the last knot every N_{i,0} is 0, so the curve's end is its last control point there.
fn curve(order: usize, knots: &[f64], points: &[[f64; 3]], weights: &[f64], u: f64) -> [f64; 3] {
    if u >= knots[knots.len() - 1] {
        return points[points.len() - 1];
    }
    let (mut sum, mut weight) = ([0.0; 3], 0.0);
    for (i, (p, w)) in points.iter().zip(weights).enumerate() {
        let n = basis(knots, i, order - 1, u) * w;
        weight += n;
        for c in 0..3 {
            sum[c] += n * p[c];
        }
    }
    [sum[0] / weight, sum[1] / weight, sum[2] / weight]
}

struct TestCurve {
    order: usize,
    knots: Vec<f64>,
    points: Vec<[f64; 3]>,
    weights: Vec<f64>,
}

impl TestCurve {
    /// A rational cubic over three spans in space, non-uniform knots and weights.
    fn cubic() -> TestCurve {
        TestCurve {
            order: 4,
            knots: vec![0.0, 0.0, 0.0, 0.0, 1.0, 3.0, 4.0, 4.0, 4.0, 4.0],
            points: vec![
                [0.0, 0.0, 0.0],
                [10.0, 0.0, -1.0],
                [20.0, 15.0, -2.0],
                [5.0, 25.0, -1.0],
                [-5.0, 10.0, 0.0],
                [0.0, 30.0, 1.0],
            ],
            weights: vec![1.0, 0.5, 2.0, 1.0, 0.8, 1.0],
        }
    }

    fn at(&self, u: f64) -> [f64; 3] {
        curve(self.order, &self.knots, &self.points, &self.weights, u)
    }

    /// The program: G06.2 with the first point, a block per point, `order` knot blocks.
    fn program(&self, head: &str) -> String {
        let mut text = format!("G90 G00 X0 Y0 Z0\n{head}\n");
        for (i, (p, w)) in self.points.iter().zip(&self.weights).enumerate() {
            let start = if i == 0 {
                format!("G06.2 P{} ", self.order)
            } else {
                String::new()
            };
            let feed = if i == 0 { " F3000." } else { "" };
            text += &format!(
                "{start}K{:.1} X{:.3} Y{:.3} Z{:.3} R{w}{feed}\n",
                self.knots[i], p[0], p[1], p[2]
            );
        }
        for k in &self.knots[self.points.len()..] {
            text += &format!("K{k:.1}\n");
        }
        text + "G05 P0\nM30\n"
    }

    /// Dense samples of the curve: (parameter, point).
    fn samples(&self, count: usize) -> Vec<(f64, [f64; 3])> {
        let last = self.knots[self.knots.len() - 1];
        (0..=count)
            .map(|i| {
                let u = last * i as f64 / count as f64;
                (u, self.at(u))
            })
            .collect()
    }
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The chords of the run, as (start, end) points.
fn chords(program: &str) -> Vec<([f64; 3], [f64; 3])> {
    let run = run(program.as_bytes(), &syntec(), Options::default());
    assert!(run.error().is_none(), "{:?}", run.error());
    run.segments
        .iter()
        .filter_map(|s| match &s.kind {
            SegmentKind::Line { motion, .. } => Some((
                [motion.from.0[0], motion.from.0[1], motion.from.0[2]],
                [motion.to.0[0], motion.to.0[1], motion.to.0[2]],
            )),
            _ => None,
        })
        .collect()
}

/// The parameter of the curve's point nearest `p`, from dense samples refined by bisection of
/// the distance on the neighbouring interval.
fn nearest_parameter(c: &TestCurve, samples: &[(f64, [f64; 3])], p: [f64; 3]) -> f64 {
    let (i, _) = samples
        .iter()
        .enumerate()
        .min_by(|a, b| distance(a.1 .1, p).total_cmp(&distance(b.1 .1, p)))
        .unwrap();
    let (mut lo, mut hi) = (
        samples[i.saturating_sub(1)].0,
        samples[(i + 1).min(samples.len() - 1)].0,
    );
    for _ in 0..60 {
        let (a, b) = (lo + (hi - lo) / 3.0, hi - (hi - lo) / 3.0);
        if distance(c.at(a), p) < distance(c.at(b), p) {
            hi = b;
        } else {
            lo = a;
        }
    }
    0.5 * (lo + hi)
}

#[test]
fn the_chords_end_on_the_curve_and_stay_within_half_the_tolerance() {
    // G05 P10000 without E: the machine's smoothing tolerance, 0.01 mm; the chords take half.
    let c = TestCurve::cubic();
    let chords = chords(&c.program("G05 P10000"));
    assert!(chords.len() > 20, "{} chords", chords.len());
    let samples = c.samples(20_000);
    let mut previous_u = 0.0;
    for (from, to) in &chords {
        // Each end is a point of the curve, to rounding, further along than the last one.
        let u = nearest_parameter(&c, &samples, *to);
        assert!(distance(c.at(u), *to) < 1e-6, "{to:?} off the curve");
        assert!(u > previous_u, "{u} after {previous_u}");
        // Every point of the curve between the chord's ends is within 0.005 of the chord.
        for (_, q) in samples.iter().filter(|(s, _)| *s > previous_u && *s < u) {
            let deviation = point_to_segment(*q, *from, *to);
            assert!(deviation <= 0.005 + 1e-9, "{deviation} at {q:?}");
        }
        previous_u = u;
    }
    assert_eq!(chords.last().unwrap().1, [0.0, 30.0, 1.0]);
}

fn point_to_segment(p: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let ab = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let length2 = ab.iter().map(|v| v * v).sum::<f64>();
    let t = ((0..3).map(|i| (p[i] - a[i]) * ab[i]).sum::<f64>() / length2).clamp(0.0, 1.0);
    distance(p, [a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2]])
}

/// The angle between two directions, degrees.
fn angle(a: [f64; 3], b: [f64; 3]) -> f64 {
    let dot = (0..3).map(|i| a[i] * b[i]).sum::<f64>();
    let norm = |v: [f64; 3]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    (dot / norm(a) / norm(b))
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees()
}

fn direction(from: [f64; 3], to: [f64; 3]) -> [f64; 3] {
    [to[0] - from[0], to[1] - from[1], to[2] - from[2]]
}

#[test]
fn the_path_leaves_and_ends_along_the_curve_and_turns_smoothly() {
    let c = TestCurve::cubic();
    let chords = chords(&c.program("G05 P10000"));
    // A clamped curve leaves its first point towards the second and reaches its last from the
    // one before: the end tangents. A chord of a curve whose chord error is e and radius r turns
    // from the tangent by about sqrt(8 e / r) / 2 radians; 5 degrees is far above that here.
    let first = direction(chords[0].0, chords[0].1);
    assert!(angle(first, direction(c.points[0], c.points[1])) < 5.0);
    let last = chords.last().unwrap();
    let n = c.points.len();
    assert!(
        angle(
            direction(last.0, last.1),
            direction(c.points[n - 2], c.points[n - 1])
        ) < 5.0
    );
    // Between chords the path turns by little: the curve has no corner.
    for pair in chords.windows(2) {
        let turn = angle(
            direction(pair[0].0, pair[0].1),
            direction(pair[1].0, pair[1].1),
        );
        assert!(turn < 10.0, "a corner of {turn} degrees");
    }
}

#[test]
fn the_planner_times_the_curve_as_the_same_chords_written_as_lines() {
    // The chords' ends, found on the curve evaluated here, written as G01 blocks in the same
    // high-speed mode (to 1e-4 mm): the two programs must take the same time within 2 %.
    let c = TestCurve::cubic();
    let nurbs = c.program("G05 P10000");
    let chords = chords(&nurbs);
    let samples = c.samples(20_000);
    let mut lines = String::from("G90 G00 X0 Y0 Z0\nG05 P10000\nG01 F3000.\n");
    for (_, to) in &chords {
        let p = c.at(nearest_parameter(&c, &samples, *to));
        lines += &format!("X{:.4} Y{:.4} Z{:.4}\n", p[0], p[1], p[2]);
    }
    lines += "G05 P0\nM30\n";
    let machine = syntec();
    let (curve_time, line_time) = (
        total_seconds(&nurbs, &machine),
        total_seconds(&lines, &machine),
    );
    assert!(
        (curve_time - line_time).abs() <= 0.02 * line_time,
        "NURBS {curve_time} s, lines {line_time} s"
    );
}

#[test]
fn the_planner_times_the_curve_as_fine_g01_chords_of_it() {
    // The curve as 200 G01 chords at equal steps of the parameter (under 0.5 mm each),
    // evaluated here, in the same high-speed mode: within 2 % of the NURBS. Much finer chords
    // are slower on this planner: its blends then use whole chords and leave no straight part to
    // speed up on, a limit of the planner's handling of chord chains, not of the curve.
    let c = TestCurve::cubic();
    let mut lines = String::from("G90 G00 X0 Y0 Z0\nG05 P10000\nG01 F3000.\n");
    for i in 1..=200 {
        let p = c.at(4.0 * f64::from(i) / 200.0);
        lines += &format!("X{:.4} Y{:.4} Z{:.4}\n", p[0], p[1], p[2]);
    }
    lines += "G05 P0\nM30\n";
    let machine = syntec();
    let (curve_time, line_time) = (
        total_seconds(&c.program("G05 P10000"), &machine),
        total_seconds(&lines, &machine),
    );
    assert!(
        (curve_time - line_time).abs() <= 0.02 * line_time,
        "NURBS {curve_time} s, 200 chords {line_time} s"
    );
}

#[test]
fn incremental_control_points_give_the_same_curve() {
    // G91: each control point from the one before (the manual: G90/G91 decide, L786).
    let c = TestCurve::cubic();
    let absolute = chords(&c.program("G05 P10000"));
    let mut text = String::from("G90 G00 X0 Y0 Z0\nG05 P10000\nG91\n");
    let mut previous = [0.0; 3];
    for (i, p) in c.points.iter().enumerate() {
        let head = if i == 0 { "G06.2 P4 " } else { "" };
        let feed = if i == 0 { " F3000." } else { "" };
        text += &format!(
            "{head}K{:.1} X{:.3} Y{:.3} Z{:.3} R{}{feed}\n",
            c.knots[i],
            p[0] - previous[0],
            p[1] - previous[1],
            p[2] - previous[2],
            c.weights[i]
        );
        previous = *p;
    }
    for k in &c.knots[c.points.len()..] {
        text += &format!("K{k:.1}\n");
    }
    let incremental = chords(&(text + "M30\n"));
    assert_eq!(absolute.len(), incremental.len());
    for (a, b) in absolute.iter().zip(&incremental) {
        assert!(distance(a.1, b.1) < 1e-9);
    }
}

#[test]
fn the_order_defaults_to_4_and_r_to_1() {
    // L774, L780: without P and R the curve is a non-rational cubic; four control points and
    // eight knots 0 0 0 0 1 1 1 1 make a Bezier curve: C(0.5) = (P0 + 3 P1 + 3 P2 + P3) / 8.
    let program =
        "G00 X0 Y0\nG06.2 K0 X0 Y0 F1000.\nK0 X0 Y8.\nK0 X8. Y8.\nK0 X8. Y0\nK1\nK1\nK1\nK1\nM30\n";
    let chords = chords(program);
    let middle = [(3.0 * 8.0 + 8.0) / 8.0, (3.0 * 8.0 + 3.0 * 8.0) / 8.0, 0.0];
    assert!(
        chords.iter().any(|(_, to)| distance(*to, middle) < 1e-9),
        "no chord ends at {middle:?}"
    );
    assert_eq!(chords.last().unwrap().1, [8.0, 0.0, 0.0]);
}

#[test]
fn a_rational_quadratic_with_the_middle_weight_cos_45_is_a_quarter_circle() {
    // Control points (10,0), (10,10), (0,10), weights 1, cos 45 deg, 1, knots 0 0 0 1 1 1: the
    // quarter of the circle of radius 10 about the origin, so every chord end is 10 from it.
    let program = "G90 G00 X10. Y0\nG06.2 P3 K0 X10. Y0 R1. F2000.\nK0 X10. Y10. R0.70710678\n\
                   K0 X0 Y10. R1.\nK1\nK1\nK1\nM30\n";
    let chords = chords(program);
    assert!(chords.len() > 8);
    for (_, to) in &chords {
        let radius = to[0].hypot(to[1]);
        assert!((radius - 10.0).abs() < 1e-7, "{to:?} at {radius}");
    }
}

fn alarm(program: &str) -> (AlarmCode, u32) {
    let run = run(program.as_bytes(), &syntec(), Options::default());
    let alarm = run.error().unwrap_or_else(|| panic!("no alarm: {program}"));
    (alarm.code, alarm.span.unwrap().line)
}

#[test]
fn curves_that_cannot_be_made_are_alarms() {
    let head = "G00 X0 Y0\n";
    let cases = [
        // Order 5: the manual allows 2 to 4.
        ("G06.2 P5 K0 X0 Y0 F100.\n", 2),
        // A weight out of 0.001-1000.
        ("G06.2 P2 K0 X0 Y0 F100.\nK0 X5. R0\n", 3),
        // Decreasing knots.
        ("G06.2 P2 K0 X0 Y0 F100.\nK1 X5.\nK0 X9.\nK1\nK1\n", 2),
        // Not clamped: the first two knots differ.
        ("G06.2 P2 K0 X0 Y0 F100.\nK0.5 X5.\nK1\nK1\n", 2),
        // The curve does not start where the tool stands.
        ("G06.2 P2 K0 X1. Y0 F100.\nK0 X5.\nK1\nK1\n", 2),
        // The program goes on before the last knot: the curve would be lost.
        ("G06.2 P2 K0 X0 Y0 F100.\nK0 X5.\nK1\nG01 X7.\n", 5),
        // An inner knot as often as the order: the curve would break in two.
        (
            "G06.2 P2 K0 X0 Y0 F100.\nK0 X5.\nK0.5 X5. Y5.\nK0.5 X9.\nK1\nK1\n",
            2,
        ),
        // The first knot more often than the order: the curve would not start at the tool.
        ("G06.2 P2 K0 X0 Y0 F100.\nK0 X5.\nK0 X5. Y5.\nK1\nK1\n", 2),
        // Inverse time feed would time each chord apart.
        ("G93 G06.2 P2 K0 X0 Y0 F100.\nK0 X5.\nK1\nK1\n", 2),
        // A control point after the knots-only blocks.
        (
            "G06.2 P3 K0 X0 Y0 F100.\nK0 X5.\nK0 X6. Y1.\nK1\nK1 X3.\n",
            6,
        ),
    ];
    for (body, line) in cases {
        let program = format!("{head}{body}M30\n");
        assert_eq!(
            alarm(&program),
            (AlarmCode::NurbsDefinition, line),
            "{program}"
        );
    }
}

#[test]
fn controls_without_the_high_speed_mode_have_no_g06_2() {
    let program = "G06.2 P2 K0 X0 Y0 F100.\nM30\n";
    let machine = Machine::default()
        .with_profile(ProfileName::Fanuc0m)
        .unwrap();
    let run = run(program.as_bytes(), &machine, Options::default());
    assert_eq!(run.error().map(|a| a.code), Some(AlarmCode::UnknownGCode));
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(200))]

    /// Any sequence of NURBS-like blocks either runs, with every chord end inside the box of the
    /// control points (a NURBS curve lies in the convex hull of its points), or stops with
    /// V075 (or a feed alarm), never a panic or another kind of alarm.
    #[test]
    fn any_nurbs_blocks_run_inside_the_hull_or_alarm(
        order in 0..6u32,
        points in proptest::collection::vec((-50..50i32, -50..50i32, 0..3u32), 1..7),
        knots in proptest::collection::vec(0..4u32, 0..12),
        clamped in proptest::bool::ANY,
    ) {
        // Half the cases get a clamped knot vector of the right length: curves that run.
        let order_usize = order as usize;
        let knots = if clamped && (2..=4).contains(&order_usize) && points.len() >= order_usize {
            let mut inner: Vec<u32> = (0..points.len() - order_usize)
                .map(|i| 1 + knots.get(i).copied().unwrap_or(1) % 3)
                .collect();
            inner.sort_unstable();
            let mut all = vec![0; order_usize];
            all.extend(inner);
            all.extend(vec![4; order_usize]);
            all
        } else {
            knots
        };
        let mut text = String::from("G90 G00 X0 Y0 Z0\n");
        for (i, (x, y, w)) in points.iter().enumerate() {
            let head = if i == 0 { format!("G06.2 P{order} F1000. ") } else { String::new() };
            let (x, y) = if i == 0 { (0, 0) } else { (*x, *y) };
            let k = knots.get(i).copied().unwrap_or(0);
            text += &format!("{head}K{k} X{x}. Y{y}. R{}\n", [0.5, 1.0, 2.0][*w as usize]);
        }
        for k in knots.iter().skip(points.len()) {
            text += &format!("K{k}\n");
        }
        text += "M30\n";
        let run = run(text.as_bytes(), &syntec(), Options::default());
        match run.error() {
            Some(alarm) => proptest::prop_assert!(
                matches!(alarm.code, AlarmCode::NurbsDefinition | AlarmCode::NoFeedRate),
                "{alarm:?}\n{text}"
            ),
            None => {
                let (mut low, mut high) = ([0.0f64; 2], [0.0f64; 2]);
                for (x, y, _) in points.iter().skip(1) {
                    low = [low[0].min(f64::from(*x)), low[1].min(f64::from(*y))];
                    high = [high[0].max(f64::from(*x)), high[1].max(f64::from(*y))];
                }
                for segment in &run.segments {
                    if let Some(motion) = segment.motion() {
                        let p = motion.to.0;
                        for i in 0..2 {
                            proptest::prop_assert!(
                                p[i] >= low[i] - 1e-9 && p[i] <= high[i] + 1e-9,
                                "{p:?} outside {low:?}..{high:?}\n{text}"
                            );
                        }
                    }
                }
            }
        }
    }
}
