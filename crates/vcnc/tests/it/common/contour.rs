//! Generated contours for the transform tests: lines and I J arcs from the origin, written
//! with every point passed through a map (a rotation, mirror or scaling done by hand, or none).

use proptest::prelude::*;
use vcnc::{Machine, Options, SegmentKind};

/// A step of a generated contour: a line, or an I J arc whose end is on its circle.
#[derive(Clone, Debug)]
pub enum Step {
    Line(f64, f64),
    Arc {
        ccw: bool,
        center: (f64, f64),
        angle: f64,
    },
}

pub fn step() -> impl Strategy<Value = Step> {
    prop_oneof![
        (-100.0f64..100.0, -100.0f64..100.0).prop_map(|(x, y)| Step::Line(x, y)),
        (
            proptest::bool::ANY,
            -50.0f64..50.0,
            -50.0f64..50.0,
            0.3f64..2.5
        )
            .prop_map(|(ccw, dx, dy, angle)| Step::Arc {
                ccw,
                center: (dx, dy),
                angle
            }),
    ]
}

/// The program of `steps` from `start` (machine), each point through `map`, arcs' directions
/// swapped when `swap`; `header` goes after the first rapid.
pub fn program(
    steps: &[Step],
    map: &dyn Fn(f64, f64) -> (f64, f64),
    swap: bool,
    start: (f64, f64),
    header: &str,
) -> String {
    let mut text = format!(
        "G90 G17 G0 X{:.9} Y{:.9}\n{header}G1 F500.\n",
        start.0, start.1
    );
    let (mut x, mut y) = (0.0f64, 0.0f64);
    for step in steps {
        match *step {
            Step::Line(nx, ny) => {
                let (tx, ty) = map(nx, ny);
                text.push_str(&format!("G1 X{tx:.9} Y{ty:.9}\n"));
                (x, y) = (nx, ny);
            }
            Step::Arc { ccw, center, angle } => {
                let (cx, cy) = (x + center.0, y + center.1);
                let from = (y - cy).atan2(x - cx);
                let radius = (x - cx).hypot(y - cy);
                let to = if ccw { from + angle } else { from - angle };
                let (nx, ny) = (cx + radius * to.cos(), cy + radius * to.sin());
                let (tx, ty) = map(nx, ny);
                let (sx, sy) = map(x, y);
                let (tcx, tcy) = map(cx, cy);
                let g = if ccw != swap { 3 } else { 2 };
                text.push_str(&format!(
                    "G{g} X{tx:.9} Y{ty:.9} I{:.9} J{:.9}\n",
                    tcx - sx,
                    tcy - sy
                ));
                (x, y) = (nx, ny);
            }
        }
    }
    text.push_str("M30\n");
    text
}

/// Every motion's end point, arc centre and direction, machine X Y, of `text` on `machine`; the
/// program must run without alarms.
pub fn path(text: &str, machine: &Machine) -> Vec<(f64, f64, &'static str)> {
    let result = super::run(text.as_bytes(), machine, Options::default());
    assert!(result.alarms.is_empty(), "{:?}\n{text}", result.alarms);
    let mut points = Vec::new();
    for segment in &result.segments {
        if let Some(motion) = segment.motion() {
            points.push((motion.to.0[0], motion.to.0[1], "end"));
        }
        if let SegmentKind::Arc {
            center, direction, ..
        } = segment.kind
        {
            points.push((center.0[0], center.0[1], direction.as_str()));
        }
    }
    points
}

/// Asserts two paths from [`path`] equal within 1e-6 mm, arc directions included.
pub fn assert_same_path(
    a: &[(f64, f64, &str)],
    b: &[(f64, f64, &str)],
) -> Result<(), TestCaseError> {
    prop_assert_eq!(a.len(), b.len());
    for (p, q) in a.iter().zip(b) {
        prop_assert!(
            (p.0 - q.0).abs() < 1e-6 && (p.1 - q.1).abs() < 1e-6,
            "{:?} {:?}",
            p,
            q
        );
        prop_assert_eq!(p.2, q.2);
    }
    Ok(())
}

/// Runs `steps` with the transform codes of `header` and, separately, transformed by hand with
/// `by_hand` (arcs' directions swapped when `swap`), and asserts the same machine path. Both
/// start where the transformed program's origin is.
pub fn assert_coded_is_by_hand(
    steps: &[Step],
    by_hand: &dyn Fn(f64, f64) -> (f64, f64),
    swap: bool,
    header: &str,
    machine: &Machine,
) -> Result<(), TestCaseError> {
    let start = by_hand(0.0, 0.0);
    let coded = program(steps, &|x, y| (x, y), false, start, header);
    let manual = program(steps, by_hand, swap, start, "");
    assert_same_path(&path(&coded, machine), &path(&manual, machine))
}
