//! Hand-checked tool-centre paths from the manuals, and properties of every corner.

use super::*;
use proptest::prelude::*;

fn p(x: f64, y: f64) -> V2 {
    V2::new(x, y)
}

pub(crate) fn line(a: V2, b: V2) -> Element {
    Element::Line { start: a, end: b }
}

pub(crate) fn arc(a: V2, b: V2, center: V2, ccw: bool) -> Element {
    Element::Arc {
        start: a,
        end: b,
        center,
        ccw,
    }
}

/// The tool-centre points of a contour compensated from a type-A start-up to a perpendicular
/// end: the start-up end, every corner's points, the last end.
fn tool_path(elements: &[Element], side: Side, r: f64) -> Vec<V2> {
    let mut points = vec![start_up_end(&elements[0], side, r)];
    for pair in elements.windows(2) {
        let corner = corner(&pair[0], &pair[1], side, r).expect("the corner can be made");
        points.push(corner.a_end);
        points.extend(corner.links.iter().map(|link| link.to()));
    }
    points.push(perpendicular_end(elements.last().unwrap(), side, r));
    points
}

fn assert_path(actual: &[V2], expected: &[(f64, f64)]) {
    assert_eq!(
        actual.len(),
        expected.len(),
        "points: {actual:?}\nexpected: {expected:?}"
    );
    for (i, (a, e)) in actual.iter().zip(expected).enumerate() {
        assert!(
            (a.x - e.0).abs() < 1e-3 && (a.y - e.1).abs() < 1e-3,
            "point {i}: {a:?}, expected {e:?}\nall: {actual:?}"
        );
    }
}

/// FANUC 0M manual, Example 1 (001:L971-1000; spec A.22, file
/// examples/fanuc0m/16-g41-g40-example1-frag.nc): G41 with D12 = 5 round a part with three arcs,
/// tool-centre points as the spec works them out. At I (an outer corner of 77.47 degrees) the
/// spec gives the plain intersection and notes that the control adds points there: the two
/// extension points of a sharp outer corner are checked instead.
#[test]
fn fanuc_0m_example_1_tool_centre_points() {
    let a = p(-20.0, -20.0);
    let b = p(0.0, 0.0);
    let c = p(0.0, 35.0);
    let d = p(20.0, 35.0);
    let e = p(25.0, 60.0);
    let f = p(65.0, 60.0);
    let g = p(70.0, 35.0);
    let h = p(90.0, 35.0);
    let i = p(90.0, 0.0);
    let j = p(45.0, 10.0);
    let contour = [
        line(b, c),
        line(c, d),
        arc(d, e, p(-40.0, 60.0), true),
        arc(e, f, p(45.0, 75.0), false),
        arc(f, g, p(130.0, 60.0), true),
        line(g, h),
        line(h, i),
        line(i, j),
        line(j, b),
        line(b, a),
    ];
    let path = tool_path(&contour, Side::Left, 5.0);
    assert_path(
        &path,
        &[
            (-5.0, 0.0),
            (-5.0, 40.0),
            (16.569, 40.0),
            (19.980, 58.447),
            (70.020, 58.447),
            (73.431, 40.0),
            (95.0, 40.0),
            (95.0, -5.0),
            (93.796, -5.966),
            (45.0, 4.878),
            (2.506, -4.565),
            (-16.464, -23.536),
        ],
    );
}

/// FANUC 0M manual, the four start-ups on one part (001:L885-958; spec A.22, files
/// examples/fanuc0m/12 to 15): rectangle 0..92 x 0..60 with an R8 corner at (92,60), D11 = 4.
#[test]
fn fanuc_0m_start_up_variants() {
    let c = p(92.0, 0.0);
    let d = p(92.0, 52.0);
    let e = p(84.0, 60.0);
    let f = p(0.0, 60.0);
    let g = p(0.0, 0.0);
    let centre = p(84.0, 52.0);
    // (a) G42 from A: C -> D -> E (G03) -> F -> G -> C.
    let a = [
        line(c, d),
        arc(d, e, centre, true),
        line(e, f),
        line(f, g),
        line(g, c),
    ];
    let path = tool_path(&a, Side::Right, 4.0);
    assert_path(
        &path[..5],
        &[
            (96.0, 0.0),
            (96.0, 52.0),
            (84.0, 64.0),
            (-4.0, 64.0),
            (-4.0, -4.0),
        ],
    );
    // (b) G42 from B: F -> G -> C -> D -> E (G03) -> F.
    let b = [
        line(f, g),
        line(g, c),
        line(c, d),
        arc(d, e, centre, true),
        line(e, f),
    ];
    let path = tool_path(&b, Side::Right, 4.0);
    assert_path(
        &path[..5],
        &[
            (-4.0, 60.0),
            (-4.0, -4.0),
            (96.0, -4.0),
            (96.0, 52.0),
            (84.0, 64.0),
        ],
    );
    // (c) G41 from A: C -> G -> F -> E -> D (G02) -> C.
    let cc = [
        line(c, g),
        line(g, f),
        line(f, e),
        arc(e, d, centre, false),
        line(d, c),
    ];
    let path = tool_path(&cc, Side::Left, 4.0);
    assert_path(
        &path[..5],
        &[
            (92.0, -4.0),
            (-4.0, -4.0),
            (-4.0, 64.0),
            (84.0, 64.0),
            (96.0, 52.0),
        ],
    );
    // (d) G41 from B: F -> E -> D (G02) -> C -> G -> F.
    let dd = [
        line(f, e),
        arc(e, d, centre, false),
        line(d, c),
        line(c, g),
        line(g, f),
    ];
    let path = tool_path(&dd, Side::Left, 4.0);
    assert_path(
        &path[..5],
        &[
            (0.0, 64.0),
            (84.0, 64.0),
            (96.0, 52.0),
            (96.0, -4.0),
            (-4.0, -4.0),
        ],
    );
}

/// The compensated elements of Example 1 between their corners: each line parallel to its
/// programmed line at the radius, each arc on the circle of radius R + r or R - r, and each one
/// ending where the corner's moves begin.
#[test]
fn compensated_elements_join_their_corners() {
    let contour = [
        line(p(0.0, 0.0), p(0.0, 35.0)),
        line(p(0.0, 35.0), p(20.0, 35.0)),
        arc(p(20.0, 35.0), p(25.0, 60.0), p(-40.0, 60.0), true),
        arc(p(25.0, 60.0), p(65.0, 60.0), p(45.0, 75.0), false),
        arc(p(65.0, 60.0), p(70.0, 35.0), p(130.0, 60.0), true),
        line(p(70.0, 35.0), p(90.0, 35.0)),
    ];
    let (side, r) = (Side::Left, 5.0);
    let corners: Vec<Corner> = contour
        .windows(2)
        .map(|pair| corner(&pair[0], &pair[1], side, r).unwrap())
        .collect();
    for (i, element) in contour.iter().enumerate() {
        let start = match i {
            0 => start_up_end(element, side, r),
            _ => corners[i - 1].b_start(),
        };
        let end = corners
            .get(i)
            .map_or_else(|| perpendicular_end(element, side, r), |c| c.a_end);
        // Both corner points lie on the compensated element, which runs the programmed way.
        assert!(!interferes(element, start, end), "element {i} interferes");
        match *element {
            Element::Line { start: a, end: b } => {
                let normal = side.normal((b - a).unit());
                assert!(((start - a).dot(normal) - r).abs() < 1e-9);
                assert!(((end - a).dot(normal) - r).abs() < 1e-9);
            }
            Element::Arc { center, .. } => {
                let programmed = element.radius().unwrap();
                let radius = start.distance(center);
                assert!(((radius - programmed).abs() - r).abs() < 1e-6);
                assert!((end.distance(center) - radius).abs() < 1e-6);
            }
        }
    }
}

#[test]
fn a_negative_offset_swaps_the_side() {
    assert_eq!(Side::of(true, 5.0), Side::Left);
    assert_eq!(Side::of(true, -5.0), Side::Right);
    assert_eq!(Side::of(false, 5.0), Side::Right);
    assert_eq!(Side::of(false, -5.0), Side::Left);
}

#[test]
fn an_arc_the_tool_does_not_fit_inside_is_refused() {
    // G41 on a counter-clockwise arc: the tool is inside.
    let small = arc(p(2.0, 0.0), p(0.0, 2.0), p(0.0, 0.0), true);
    assert_eq!(
        small.offset(Side::Left, 2.0),
        Err(GeometryError::ArcSmallerThanTool {
            arc_radius: 2.0,
            tool_radius: 2.0
        })
    );
    assert!(small.offset(Side::Right, 2.0).is_ok());
    // Clockwise: the left side is outside.
    let cw = arc(p(0.0, 2.0), p(2.0, 0.0), p(0.0, 0.0), false);
    assert!(cw.offset(Side::Left, 5.0).is_ok());
    assert!(cw.offset(Side::Right, 5.0).is_err());
}

#[test]
fn corners_are_classified_from_the_tools_side() {
    let east = p(1.0, 0.0);
    let north = p(0.0, 1.0);
    let south = p(0.0, -1.0);
    let south_west = p(-1.0, -1.0).unit();
    assert_eq!(turn(east, east, Side::Left), Turn::Straight);
    assert_eq!(turn(east, north, Side::Left), Turn::Inner);
    assert_eq!(turn(east, north, Side::Right), Turn::Outer);
    assert_eq!(turn(east, south, Side::Left), Turn::Outer);
    assert_eq!(turn(east, south_west, Side::Left), Turn::SharpOuter);
    assert_eq!(turn(east, -east, Side::Left), Turn::SharpOuter);
}

/// A line that doubles back is a 180-degree outer corner: two extension points, one radius past
/// the end on each compensated line.
#[test]
fn a_reversal_goes_round_the_end() {
    let corner = corner(
        &line(p(0.0, 0.0), p(10.0, 0.0)),
        &line(p(10.0, 0.0), p(0.0, 0.0)),
        Side::Left,
        2.0,
    )
    .unwrap();
    assert_path(
        &[corner.a_end, corner.links[0].to()],
        &[(12.0, 2.0), (12.0, -2.0)],
    );
}

/// An inner corner whose compensated lines meet behind the start of the short element: the
/// nearest intersection is still found (the interference check belongs to the executor, which
/// sees whole elements).
#[test]
fn parallel_lines_in_opposite_directions_on_the_inside_do_not_meet() {
    let result = intersections(
        &line(p(0.0, 1.0), p(10.0, 1.0)),
        &line(p(10.0, 3.0), p(0.0, 3.0)),
    );
    assert!(result.is_empty());
}

/// Distance from a point to a programmed element (segment or arc piece).
pub(crate) fn distance_to(element: &Element, point: V2) -> f64 {
    element.distance(point)
}

pub(crate) fn direction() -> impl Strategy<Value = V2> {
    (0.0..std::f64::consts::TAU).prop_map(|a| V2::new(a.cos(), a.sin()))
}

pub(crate) fn side() -> impl Strategy<Value = Side> {
    prop_oneof![Just(Side::Left), Just(Side::Right)]
}

proptest! {
    /// Two lines meeting at the origin: every tool-centre point of the corner is at least the
    /// radius from both programmed lines, and an inner corner's point exactly the radius.
    #[test]
    fn line_corners_keep_the_radius(
        u in direction(),
        v in direction(),
        la in 5.0f64..100.0,
        lb in 5.0f64..100.0,
        r in 0.5f64..4.0,
        side in side(),
    ) {
        let origin = V2::default();
        let a = line(origin - u * la, origin);
        let b = line(origin, v * lb);
        prop_assume!(u.dot(v) > -0.999);
        let corner = match corner(&a, &b, side, r) {
            Ok(corner) => corner,
            Err(GeometryError::Interference) => {
                // Only an inner corner too tight for the shorter line: the point where the
                // compensated lines meet lies a radius times cot(half the angle) back.
                prop_assert_eq!(turn(u, v, side), Turn::Inner);
                let half = (-u).dot(v).clamp(-1.0, 1.0).acos() / 2.0;
                prop_assert!(r / half.tan() > la.min(lb) - 1e-6);
                return Ok(());
            }
            Err(other) => panic!("{other:?}"),
        };
        let mut points = vec![corner.a_end];
        points.extend(corner.links.iter().map(|link| link.to()));
        for point in &points {
            prop_assert!(distance_to(&a, *point) >= r - 1e-6, "{point:?} too near a");
            prop_assert!(distance_to(&b, *point) >= r - 1e-6, "{point:?} too near b");
        }
        if turn(u, v, side) == Turn::Inner {
            // Exactly the radius from both lines; measured to the lines, not the segments: a
            // point up to SPAN_TOLERANCE beyond a segment's end is taken as on it (a corner at
            // the very end of a short line), and its distance to the segment's end is larger.
            let to_line = |d: V2, p: V2| d.cross(p).abs() / d.length();
            prop_assert!(points.len() == 1);
            prop_assert!((to_line(u, corner.a_end) - r).abs() < 1e-6);
            prop_assert!((to_line(v, corner.a_end) - r).abs() < 1e-6);
        }
    }

    /// A line into an arc (and an arc into a line), tangent or not: the corner's points keep at
    /// least the radius from both programmed elements.
    #[test]
    fn line_arc_corners_keep_the_radius(
        u in direction(),
        start_angle in 0.0f64..std::f64::consts::TAU,
        sweep in 0.2f64..3.0,
        radius in 10.0f64..50.0,
        r in 0.5f64..4.0,
        ccw in proptest::bool::ANY,
        side in side(),
        line_first in proptest::bool::ANY,
    ) {
        let center = V2::new(0.0, 0.0);
        let at = |angle: f64| center + V2::new(angle.cos(), angle.sin()) * radius;
        let end_angle = if ccw { start_angle + sweep } else { start_angle - sweep };
        let the_arc = arc(at(start_angle), at(end_angle), center, ccw);
        let (a, b) = if line_first {
            let joint = the_arc.start();
            (line(joint - u * 30.0, joint), the_arc)
        } else {
            let joint = the_arc.end();
            (the_arc, line(joint, joint + u * 30.0))
        };
        let ta = a.end_tangent();
        let tb = b.start_tangent();
        prop_assume!(ta.dot(tb) > -0.999);
        let corner = match corner(&a, &b, side, r) {
            Ok(corner) => corner,
            // Too tight for the tool, or a line that never meets the compensated circle: the
            // executor alarms there.
            Err(GeometryError::NoIntersection | GeometryError::Interference) => return Ok(()),
            Err(other) => panic!("{other:?}"),
        };
        let mut points = vec![corner.a_end];
        points.extend(corner.links.iter().map(|link| link.to()));
        for point in &points {
            prop_assert!(distance_to(&a, *point) >= r - 1e-6, "{point:?} too near {a:?}");
            prop_assert!(distance_to(&b, *point) >= r - 1e-6, "{point:?} too near {b:?}");
        }
    }

    /// A convex polygon run counter-clockwise with the tool inside (G41): every corner is an
    /// inner one, and the tool-centre polygon is the programmed one shrunk by the radius (each
    /// corner point the radius from both sides).
    #[test]
    fn a_convex_pocket_shrinks_by_the_radius(
        weights in proptest::collection::vec(1.0f64..2.0, 4..9),
        turn_start in 0.0f64..std::f64::consts::TAU,
        size in 40.0f64..100.0,
        r in 0.5f64..3.0,
    ) {
        // Gaps between the vertices' angles: at most 2.51 rad (the polygon holds its centre
        // well inside), at least 0.39 rad.
        let total: f64 = weights.iter().sum();
        let mut angle = turn_start;
        let angles: Vec<f64> = weights
            .iter()
            .map(|w| {
                angle += std::f64::consts::TAU * w / total;
                angle
            })
            .collect();
        let vertices: Vec<V2> = angles.iter().map(|a| V2::new(a.cos(), a.sin()) * size).collect();
        let n = vertices.len();
        let sides: Vec<Element> = (0..n).map(|i| line(vertices[i], vertices[(i + 1) % n])).collect();
        for i in 0..n {
            let a = &sides[i];
            let b = &sides[(i + 1) % n];
            prop_assert_eq!(turn(a.end_tangent(), b.start_tangent(), Side::Left), Turn::Inner);
            let corner = corner(a, b, Side::Left, r).unwrap();
            prop_assert!(corner.links.is_empty());
            for element in [a, b] {
                let Element::Line { start, end } = *element else { unreachable!() };
                let normal = (end - start).unit().left();
                // Inside, at the radius from the side's line.
                prop_assert!(((corner.a_end - start).dot(normal) - r).abs() < 1e-6);
            }
        }
    }
}
