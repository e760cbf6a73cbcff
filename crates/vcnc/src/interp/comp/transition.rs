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

use super::geometry::{
    intersections, nearest, perpendicular_end, start_up_end, turn, Corner, Element, GeometryError,
    Link, Side, Turn, EPSILON, V2,
};

/// How the tool centre goes round an outer corner.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum OuterCorner {
    /// FANUC: the tangent lines' intersection, extended ends at sharp corners (`geometry::corner`).
    Fanuc,
    /// SINUMERIK G450: a circle of the tool radius about the programmed corner.
    TransitionCircle,
    /// SINUMERIK G451: the intersection of the compensated elements.
    Intersection,
}

/// How the tool reaches the contour at the start-up and leaves it at the cancel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Approach {
    /// Straight to the compensated start, perpendicular to the first element (FANUC type A,
    /// SINUMERIK NORM); straight from the perpendicular end of the last one.
    Straight,
    /// SINUMERIK KONT: round the start or end point when the tool is behind the contour.
    AroundPoint,
}

/// The rules of a dialect's compensation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Rules {
    pub(crate) outer: OuterCorner,
    pub(crate) approach: Approach,
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
    Ok(circle_corner(oa.end(), ob.start(), a.end(), side))
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
    let approach = (s - p0).unit();
    if approach == V2::default()
        || !matches!(
            turn(approach, next.start_tangent(), side),
            Turn::Outer | Turn::SharpOuter
        )
    {
        return None;
    }
    let ccw = side == Side::Right;
    // The line arrives at the circle and goes on round it the way the corner turns.
    let touch = tangent_points(p0, s, r)?
        .into_iter()
        .find(|&t| (t - p0).dot(circling(s, t, ccw)) > 0.0)?;
    let on_contour = start_up_end(next, side, r);
    if rule == OuterCorner::Intersection {
        let line = Element::Line {
            start: p0,
            end: touch,
        };
        let compensated = next.offset(side, r).ok()?;
        if let Some(point) = nearest(intersections(&line, &compensated), on_contour) {
            return Some(Corner {
                a_end: point,
                links: Vec::new(),
            });
        }
    }
    Some(circle_corner(touch, on_contour, s, side))
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
    let leave = (p0 - e).unit();
    if leave == V2::default()
        || !matches!(
            turn(last.end_tangent(), leave, side),
            Turn::Outer | Turn::SharpOuter
        )
    {
        return None;
    }
    let ccw = side == Side::Right;
    // The circle hands over to the line where the line leaves it in its direction of travel.
    let touch = tangent_points(p0, e, r)?
        .into_iter()
        .find(|&t| (p0 - t).dot(circling(e, t, ccw)) > 0.0)?;
    let off_contour = perpendicular_end(last, side, r);
    if rule == OuterCorner::Intersection {
        let line = Element::Line {
            start: touch,
            end: p0,
        };
        let compensated = last.offset(side, r).ok()?;
        if let Some(point) = nearest(intersections(&compensated, &line), off_contour) {
            return Some(Corner {
                a_end: point,
                links: Vec::new(),
            });
        }
    }
    Some(circle_corner(off_contour, touch, e, side))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: f64, y: f64) -> V2 {
        V2::new(x, y)
    }

    fn line(a: V2, b: V2) -> Element {
        Element::Line { start: a, end: b }
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
