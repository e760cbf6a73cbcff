//! The corner and approach rules a dialect chooses for cutter compensation: how the tool centre
//! goes round an outer corner (FANUC's rules, SINUMERIK's transition circle G450 or intersection
//! G451), and how it reaches and leaves the contour (straight, or round the start and end point
//! as SINUMERIK's KONT does).
//!
//! Plane geometry only, in the coordinates of `geometry`; the compensator asks these functions
//! what its [`Rules`] say and never which control it runs for. The FANUC rules stay in
//! `geometry::corner`, unchanged.
//!
//! SINUMERIK (sinumerik-part-b.md 2.2, 2.3; seed 002 L7176-7396):
//! - G450: at an outer corner the tool centre travels a circle of the tool radius about the
//!   programmed corner point, from the end normal of one element to the start normal of the next.
//! - G451: it goes to the intersection of the two compensated elements (lines taken as
//!   infinite, arcs as whole circles); where they never meet (a reversal), the circle is taken.
//! - KONT: a tool behind the contour (the approach block turning outward into the first element)
//!   goes on a straight line tangent to a circle of the tool radius about the start point, then
//!   round it (G450) or to where that line meets the first compensated element (G451); the
//!   retraction is the same in reverse. A tool in front of the contour goes as with NORM.

use super::extension::Extension;
use super::geometry::{
    intersections, nearest, perpendicular_end, start_up_end, turn, Corner, Element, GeometryError,
    Link, Side, Turn, EPSILON, V2,
};
use super::polynomial::Continuity;

/// How the tool centre goes round an outer corner.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum OuterCorner {
    /// FANUC: the tangent lines' intersection, extended ends at sharp corners (`geometry::corner`).
    Fanuc,
    /// SINUMERIK G450: a circle of the tool radius about the programmed corner.
    TransitionCircle,
    /// SINUMERIK G451: the intersection of the compensated elements.
    Intersection,
    /// SINUMERIK G450 with DISC 1 to 100: the transition circle flattened towards the
    /// intersection, a conic ([`conic_corner`]).
    Conic(u8),
}

/// How the tool reaches the contour at the start-up and leaves it at the cancel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Approach {
    /// Straight to the compensated start, perpendicular to the first element (FANUC type A,
    /// SINUMERIK NORM); straight from the perpendicular end of the last one.
    Straight,
    /// SINUMERIK KONT: round the start or end point when the tool is behind the contour.
    AroundPoint,
    /// SINUMERIK KONTT, KONTC: a polynomial joining the contour with its tangent (and
    /// curvature), `polynomial.rs`.
    Curve(Continuity),
}

/// The rules of a dialect's compensation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Rules {
    pub(crate) outer: OuterCorner,
    pub(crate) approach: Approach,
    /// Where an open contour's first or last element meets no neighbour (SINUMERIK G460-G462).
    pub(crate) extension: Extension,
    /// SINUMERIK CDON: each compensated element checked against the programmed elements
    /// before its neighbour (`bottleneck.rs`).
    pub(crate) bottleneck: bool,
    /// The help line of the interference alarm, in the control's own terms.
    pub(crate) alarm_help: &'static str,
    /// The feed of a transition circle joining moves at rapid, mm/min: the plane axes' rapid
    /// rate (a circle has a feed, a rapid has none).
    pub(crate) rapid_arc_feed: f64,
}

impl Rules {
    /// The FANUC family's rules (spec A.22, 1.24).
    pub(crate) const FANUC: Rules = Rules {
        outer: OuterCorner::Fanuc,
        approach: Approach::Straight,
        extension: Extension::None,
        bottleneck: false,
        alarm_help: "FANUC alarms 033/041: a smaller tool, a larger radius or another path",
        rapid_arc_feed: 0.0,
    };
}

/// The corner between the programmed elements `a` and `b` under `rule` (see
/// [`super::geometry::corner`] for the FANUC one and the errors).
///
/// # Errors
/// The errors of [`super::geometry::corner`].
pub(crate) fn corner(
    rule: OuterCorner,
    a: &Element,
    b: &Element,
    side: Side,
    r: f64,
) -> Result<Corner, GeometryError> {
    let outer = matches!(
        turn(a.end_tangent(), b.start_tangent(), side),
        Turn::Outer | Turn::SharpOuter
    );
    if rule == OuterCorner::Fanuc || !outer {
        return super::geometry::corner(a, b, side, r);
    }
    let oa = a.offset(side, r)?;
    let ob = b.offset(side, r)?;
    if rule == OuterCorner::Intersection {
        if let Some(point) = nearest(intersections(&oa, &ob), a.end()) {
            return Ok(Corner {
                a_end: point,
                links: Vec::new(),
            });
        }
    }
    let circle = circle_corner(oa.end(), ob.start(), a.end(), side);
    Ok(match rule {
        OuterCorner::Conic(disc) => conic_corner(
            (oa.end(), a.end_tangent()),
            (ob.start(), b.start_tangent()),
            disc,
        )
        .unwrap_or(circle),
        _ => circle,
    })
}

/// G450 with DISC (seed 002 L7300-7340: 0 the circle, 100 the intersection of the
/// equidistants, the curve in between "an ellipse, parabola or hyperbola"): the rational
/// quadratic Bezier curve from `a` to `b` (points with their directions of travel) whose
/// control point is where the two tangents meet. Its weight cos(turn / 2) is the transition
/// circle itself; vcnc's choice for DISC: the curve's middle moves DISC/100 of the way from
/// the circle's middle to the tangents' meeting point, the weight growing through 1 (the
/// parabola) towards infinity (the two tangent lines). As straight pieces within 1 um of the
/// curve; `None` where the tangents do not meet ahead (a reversal): the circle.
fn conic_corner((a, ta): (V2, V2), (b, tb): (V2, V2), disc: u8) -> Option<Corner> {
    let denominator = ta.cross(tb);
    if denominator.abs() < 1e-9 {
        return None;
    }
    let along_a = (b - a).cross(tb) / denominator;
    let q = a + ta * along_a;
    if along_a <= EPSILON || (b - q).dot(tb) <= EPSILON {
        return None;
    }
    let circle = (1.0 + ta.dot(tb)).max(0.0).sqrt() / std::f64::consts::SQRT_2;
    let middle = |w: f64| w / (1.0 + w);
    let share = f64::from(disc.min(100)) / 100.0;
    let f = middle(circle) + (1.0 - middle(circle)) * share;
    if f >= 1.0 - 1e-12 {
        return Some(Corner {
            a_end: a,
            links: vec![Link::Line(q), Link::Line(b)],
        });
    }
    let w = f / (1.0 - f);
    let at = |t: f64| {
        let (s, u) = (1.0 - t, 2.0 * w * t * (1.0 - t));
        (a * (s * s) + q * u + b * (t * t)) * (1.0 / (s * s + u + t * t))
    };
    let mut pieces = 2;
    while pieces < 4096 {
        let n = f64::from(pieces);
        let worst = (0..pieces)
            .map(|k| {
                let (t0, t1) = (f64::from(k) / n, f64::from(k + 1) / n);
                let chord = (at(t0) + at(t1)) * 0.5;
                chord.distance(at((t0 + t1) / 2.0))
            })
            .fold(0.0, f64::max);
        if worst < 1e-3 {
            break;
        }
        pieces *= 2;
    }
    // The corners of the polygon round the curve, where the tangents at the pieces' ends
    // meet: it never comes nearer the contour than the curve (chords would, by up to 1 um).
    // The tangent at t joins the two points of the last de Casteljau step.
    let tangent = |t: f64| {
        let near = (a * (1.0 - t) + q * (w * t)) * (1.0 / (1.0 - t + w * t));
        let far = (q * (w * (1.0 - t)) + b * t) * (1.0 / (w * (1.0 - t) + t));
        (near, far - near)
    };
    let mut links: Vec<Link> = (0..pieces)
        .filter_map(|k| {
            let (p, u) = tangent(f64::from(k) / f64::from(pieces));
            let (r, v) = tangent(f64::from(k + 1) / f64::from(pieces));
            let denominator = u.cross(v);
            (denominator.abs() > 1e-15)
                .then(|| Link::Line(p + u * ((r - p).cross(v) / denominator)))
        })
        .collect();
    links.push(Link::Line(b));
    Some(Corner { a_end: a, links })
}

/// The transition circle from `from` to `to` about the programmed corner `center`: it turns the
/// way the path turns at an outer corner, away from the tool's side.
fn circle_corner(from: V2, to: V2, center: V2, side: Side) -> Corner {
    Corner {
        a_end: from,
        links: if from.distance(to) > EPSILON {
            vec![Link::Arc {
                to,
                center,
                ccw: side == Side::Right,
            }]
        } else {
            Vec::new()
        },
    }
}

/// The points where lines from `p` touch the circle about `center` of radius `r`; none when
/// `p` is on or inside the circle.
fn tangent_points(p: V2, center: V2, r: f64) -> Option<[V2; 2]> {
    let d = p - center;
    let distance = d.length();
    if distance <= r + EPSILON {
        return None;
    }
    let base = d.y.atan2(d.x);
    let half = (r / distance).acos();
    let at = |angle: f64| center + V2::new(angle.cos(), angle.sin()) * r;
    Some([at(base + half), at(base - half)])
}

/// The direction of travel at `point` on a circle about `center` (not normalised).
fn circling(center: V2, point: V2, ccw: bool) -> V2 {
    let radial = point - center;
    if ccw {
        radial.left()
    } else {
        -radial.left()
    }
}

/// True when the path turns from direction `from` into `to` away from the tool: the tool goes
/// round the corner.
fn turns_outward(from: V2, to: V2, side: Side) -> bool {
    from != V2::default() && matches!(turn(from, to, side), Turn::Outer | Turn::SharpOuter)
}

/// Where a line through `p` touches the circle of radius `r` about `center`, the circle being
/// travelled the way an outer corner turns for a tool on `side`: the line arriving at it
/// (`arriving`, KONT's approach) or leaving it (the retraction) in the circle's direction.
fn touching(p: V2, center: V2, r: f64, side: Side, arriving: bool) -> Option<V2> {
    let ccw = side == Side::Right;
    tangent_points(p, center, r)?.into_iter().find(|&t| {
        let along = if arriving { t - p } else { p - t };
        along.dot(circling(center, t, ccw)) > 0.0
    })
}

/// G451's point: where the straight line `line` meets `element` compensated, nearest `near`.
fn meeting(line: Element, element: &Element, side: Side, r: f64, near: V2) -> Option<V2> {
    let compensated = element.offset(side, r).ok()?;
    nearest(intersections(&line, &compensated), near)
}

/// KONT's start-up: the start-up block from `p0` (the uncompensated point before it) into the
/// first element `next`. `None` when the tool is in front of the contour (or within a radius of
/// its start): the start-up is NORM's.
pub(crate) fn around_start(
    rule: OuterCorner,
    p0: V2,
    next: &Element,
    side: Side,
    r: f64,
) -> Option<Corner> {
    let s = next.start();
    if !turns_outward((s - p0).unit(), next.start_tangent(), side) {
        return None;
    }
    let touch = touching(p0, s, r, side, true)?;
    let on_contour = start_up_end(next, side, r);
    let line = Element::Line {
        start: p0,
        end: touch,
    };
    match rule {
        OuterCorner::Intersection => meeting(line, next, side, r, on_contour).map(|point| Corner {
            a_end: point,
            links: Vec::new(),
        }),
        _ => None,
    }
    .or_else(|| Some(circle_corner(touch, on_contour, s, side)))
}

/// KONT's retraction: from the last element `last` to the uncompensated point `p0` the cancel
/// block goes to. `None` when the tool ends in front of the contour: NORM's perpendicular end.
/// The corner's last point is where the straight move to `p0` starts.
pub(crate) fn around_end(
    rule: OuterCorner,
    last: &Element,
    p0: V2,
    side: Side,
    r: f64,
) -> Option<Corner> {
    let e = last.end();
    if !turns_outward(last.end_tangent(), (p0 - e).unit(), side) {
        return None;
    }
    let touch = touching(p0, e, r, side, false)?;
    let off_contour = perpendicular_end(last, side, r);
    let line = Element::Line {
        start: touch,
        end: p0,
    };
    match rule {
        OuterCorner::Intersection => {
            meeting(line, last, side, r, off_contour).map(|point| Corner {
                a_end: point,
                links: Vec::new(),
            })
        }
        _ => None,
    }
    .or_else(|| Some(circle_corner(off_contour, touch, e, side)))
}

#[cfg(test)]
mod tests {
    use super::super::geometry::tests::{arc, direction, distance_to, line, side};
    use super::*;
    use proptest::prelude::*;

    fn p(x: f64, y: f64) -> V2 {
        V2::new(x, y)
    }

    /// Every point of a corner's tool-centre path: its end of `a`, its links' ends, and eight
    /// points along each transition circle.
    fn corner_points(corner: &Corner) -> Vec<V2> {
        let mut points = vec![corner.a_end];
        let mut here = corner.a_end;
        for link in &corner.links {
            if let Link::Arc { to, center, ccw } = *link {
                let (from, end) = (here - center, to - center);
                let angle = |v: V2| v.y.atan2(v.x);
                let tau = std::f64::consts::TAU;
                let sweep = if ccw {
                    (angle(end) - angle(from)).rem_euclid(tau)
                } else {
                    -(angle(from) - angle(end)).rem_euclid(tau)
                };
                let radius = from.length();
                for k in 1..8 {
                    let a = angle(from) + sweep * f64::from(k) / 8.0;
                    points.push(center + V2::new(a.cos(), a.sin()) * radius);
                }
            }
            here = link.to();
            points.push(here);
        }
        points
    }

    fn rule() -> impl Strategy<Value = OuterCorner> {
        prop_oneof![
            Just(OuterCorner::TransitionCircle),
            Just(OuterCorner::Intersection),
            (1u8..=100).prop_map(OuterCorner::Conic),
        ]
    }

    proptest! {
        /// Two lines meeting at the origin under G450 or G451: every tool-centre point of the
        /// corner (along the transition circle too) is at least the radius from both lines, and
        /// the circle runs at exactly the radius about the corner.
        #[test]
        fn line_corners_keep_the_radius(
            u in direction(),
            v in direction(),
            la in 5.0f64..100.0,
            lb in 5.0f64..100.0,
            r in 0.5f64..4.0,
            side in side(),
            rule in rule(),
        ) {
            let origin = V2::default();
            let a = line(origin - u * la, origin);
            let b = line(origin, v * lb);
            let corner = match corner(rule, &a, &b, side, r) {
                Ok(corner) => corner,
                Err(GeometryError::Interference) => {
                    prop_assert_eq!(turn(u, v, side), Turn::Inner);
                    return Ok(());
                }
                Err(other) => panic!("{other:?}"),
            };
            for point in corner_points(&corner) {
                prop_assert!(distance_to(&a, point) >= r - 1e-6, "{point:?} too near a");
                prop_assert!(distance_to(&b, point) >= r - 1e-6, "{point:?} too near b");
            }
            for link in &corner.links {
                if let Link::Arc { to, center, .. } = *link {
                    prop_assert!((to.distance(center) - r).abs() < 1e-9);
                }
            }
        }

        /// A line into an arc or an arc into a line under G450 or G451: the corner's points keep
        /// at least the radius from both programmed elements.
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
            rule in rule(),
        ) {
            let at = |angle: f64| V2::new(angle.cos(), angle.sin()) * radius;
            let end_angle = if ccw { start_angle + sweep } else { start_angle - sweep };
            let the_arc = arc(at(start_angle), at(end_angle), V2::default(), ccw);
            let (a, b) = if line_first {
                let joint = the_arc.start();
                (line(joint - u * 30.0, joint), the_arc)
            } else {
                let joint = the_arc.end();
                (the_arc, line(joint, joint + u * 30.0))
            };
            let corner = match corner(rule, &a, &b, side, r) {
                Ok(corner) => corner,
                Err(GeometryError::NoIntersection | GeometryError::Interference) => return Ok(()),
                Err(other) => panic!("{other:?}"),
            };
            for point in corner_points(&corner) {
                prop_assert!(distance_to(&a, point) >= r - 1e-6, "{point:?} too near {a:?}");
                prop_assert!(distance_to(&b, point) >= r - 1e-6, "{point:?} too near {b:?}");
            }
        }
    }

    fn near(a: V2, b: (f64, f64)) -> bool {
        a.distance(p(b.0, b.1)) < 1e-9
    }

    /// A square corner turned right with the tool on the left (outside): G450 goes from
    /// (10,2) round (10,0) to (12,0), clockwise; G451 to the compensated lines' meeting point
    /// (12,2).
    #[test]
    fn an_outer_square_corner_by_circle_and_by_intersection() {
        let a = line(p(0.0, 0.0), p(10.0, 0.0));
        let b = line(p(10.0, 0.0), p(10.0, -10.0));
        let circle = corner(OuterCorner::TransitionCircle, &a, &b, Side::Left, 2.0).unwrap();
        assert!(near(circle.a_end, (10.0, 2.0)));
        assert_eq!(
            circle.links,
            vec![Link::Arc {
                to: p(12.0, 0.0),
                center: p(10.0, 0.0),
                ccw: false
            }]
        );
        let meet = corner(OuterCorner::Intersection, &a, &b, Side::Left, 2.0).unwrap();
        assert!(near(meet.a_end, (12.0, 2.0)));
        assert!(meet.links.is_empty());
    }

    /// DISC on the square corner above (tool left, r 2): the compensated ends (10,2) and
    /// (12,0), their tangents meeting at (12,2). The circle's middle is (10,0) + 2 (0.70711,
    /// 0.70711) = (11.41421,1.41421), 0.41421 of the way from the chord's middle (11,1) to
    /// (12,2); DISC=50 takes the curve's middle half of the rest further: 0.70711 of the way,
    /// (11.70711,1.70711); DISC=100 is the two tangent lines through (12,2).
    #[test]
    fn disc_flattens_the_transition_circle_towards_the_intersection() {
        let a = line(p(0.0, 0.0), p(10.0, 0.0));
        let b = line(p(10.0, 0.0), p(10.0, -10.0));
        // How far the corner's polygon passes from `point`, and how near it comes to the
        // programmed corner (10,0).
        let passes = |disc: u8, point: V2| {
            let c = corner(OuterCorner::Conic(disc), &a, &b, Side::Left, 2.0).unwrap();
            assert!(near(c.a_end, (10.0, 2.0)) && near(c.b_start(), (12.0, 0.0)));
            let mut from = c.a_end;
            let (mut off, mut nearest) = (f64::INFINITY, f64::INFINITY);
            for link in &c.links {
                let to = link.to();
                let d = to - from;
                let t = ((point - from).dot(d) / d.dot(d)).clamp(0.0, 1.0);
                off = off.min(point.distance(from + d * t));
                nearest = nearest.min(to.distance(p(10.0, 0.0)));
                from = to;
            }
            (off, nearest)
        };
        let half = 0.5f64.sqrt();
        let circle = half / (1.0 + half);
        let at = |f: f64| p(11.0 + f, 1.0 + f);
        assert!((circle - (2f64.sqrt() - 1.0)).abs() < 1e-12);
        // The polygon runs round the curve within 1 um of it, never inside the circle.
        for (disc, f) in [(1, circle + (1.0 - circle) / 100.0), (50, half), (100, 1.0)] {
            let (off, nearest) = passes(disc, at(f));
            assert!(off < 1e-3, "DISC={disc}: {off}");
            assert!(nearest >= 2.0 - 1e-12, "DISC={disc}: {nearest}");
        }
    }

    /// A reversal has no intersection: G451 takes the circle, a half turn round the corner.
    #[test]
    fn a_reversal_under_g451_takes_the_circle() {
        let a = line(p(0.0, 0.0), p(10.0, 0.0));
        let b = line(p(10.0, 0.0), p(0.0, 0.0));
        let c = corner(OuterCorner::Intersection, &a, &b, Side::Left, 2.0).unwrap();
        assert!(near(c.a_end, (10.0, 2.0)));
        assert!(near(c.links[0].to(), (10.0, -2.0)));
    }

    /// KONT from behind: contour along +X from (0,0), tool left (r 5), approach from (-20,-20).
    /// Seen from the start point, (-20,-20) lies at -135 degrees, 28.2843 away; the tangents
    /// touch at -135 +- acos(5 / 28.2843) = -135 +- 79.8179 degrees. The line that goes on
    /// clockwise round the start touches at -214.8179 (145.1821) degrees: 5 (cos, sin) =
    /// (-4.104853, 2.854853); then clockwise round to (0,5).
    #[test]
    fn kont_from_behind_goes_round_the_start_point() {
        let next = line(p(0.0, 0.0), p(50.0, 0.0));
        let c = around_start(
            OuterCorner::TransitionCircle,
            p(-20.0, -20.0),
            &next,
            Side::Left,
            5.0,
        )
        .unwrap();
        assert!(
            c.a_end.distance(p(-4.104_852_727, 2.854_852_727)) < 1e-8,
            "{c:?}"
        );
        assert!(near(c.links[0].to(), (0.0, 5.0)));
        // In front of the contour (the tool's side): NORM.
        assert!(around_start(
            OuterCorner::TransitionCircle,
            p(-20.0, 20.0),
            &next,
            Side::Left,
            5.0
        )
        .is_none());
    }
}
