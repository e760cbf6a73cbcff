//! SINUMERIK's extended approach and retraction strategies (G460, G461, G462; sinumerik-part-b.md
//! 2.4.2, seed 002 L7674-7794): where the first or last element of an open contour is too short
//! for the tool, so that its compensated element has no intersection with its neighbour's.
//!
//! G460 keeps the collision alarm (10751). G461 produces the element by a circle of the tool
//! radius about its uncompensated end (the start for the approach) and G462 by its compensated
//! tangent there; the point where the produced piece meets the neighbour's compensated element
//! becomes the neighbour's end (the start-up block's end at the approach) and the element itself
//! is skipped: the circle and the line serve the intersection only, they are never travelled
//! (seed 002 L7746-7749).
//!
//! Plane geometry only, in the coordinates of `geometry`; the compensator decides when to ask.

use super::geometry::{intersections, nearest, Element, Side, EPSILON, V2};

/// What the compensation does where an open contour's first or last element has no
/// intersection with its neighbour (SINUMERIK group 48).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Extension {
    /// G460 (and every ISO control): the collision alarm.
    None,
    /// G461: a circle of the tool radius about the element's uncompensated end.
    Circle,
    /// G462: the compensated element's tangent, produced beyond its end.
    Line,
}

/// The approach: where the start-up block ends when the contour's `first` element, produced
/// backwards from its start, meets the compensated `next` element; `None` without such a point.
pub(crate) fn extended_start(
    extension: Extension,
    first: &Element,
    next: &Element,
    (side, r): (Side, f64),
) -> Option<V2> {
    let compensated = first.offset(side, r).ok()?;
    let produced = match extension {
        Extension::None => return None,
        Extension::Circle => Produced::Circle(first.start()),
        Extension::Line => Produced::Ray(compensated.start(), -first.start_tangent()),
    };
    meeting(produced, next, (side, r), first.end())
}

/// The retraction: where the compensated `previous` element ends when the contour's `last`
/// element, produced beyond its end, meets it; `None` without such a point.
pub(crate) fn extended_end(
    extension: Extension,
    previous: &Element,
    last: &Element,
    (side, r): (Side, f64),
) -> Option<V2> {
    let compensated = last.offset(side, r).ok()?;
    let produced = match extension {
        Extension::None => return None,
        Extension::Circle => Produced::Circle(last.end()),
        Extension::Line => Produced::Ray(compensated.end(), last.end_tangent()),
    };
    meeting(produced, previous, (side, r), last.start())
}

/// The piece an element is produced by: a circle of the tool radius about a point, or a ray
/// from a point along a direction.
enum Produced {
    Circle(V2),
    Ray(V2, V2),
}

/// Where `produced` meets `neighbour` compensated, on the compensated element, nearest the
/// programmed `joint` of the two elements.
fn meeting(
    produced: Produced,
    neighbour: &Element,
    (side, r): (Side, f64),
    joint: V2,
) -> Option<V2> {
    let compensated = neighbour.offset(side, r).ok()?;
    let points = match produced {
        Produced::Circle(center) => {
            let on = center + V2::new(r, 0.0);
            let circle = Element::Arc {
                start: on,
                end: on,
                center,
                ccw: true,
            };
            intersections(&circle, &compensated)
        }
        Produced::Ray(from, along) => {
            let line = Element::Line {
                start: from,
                end: from + along,
            };
            intersections(&line, &compensated)
                .into_iter()
                .filter(|&p| (p - from).dot(along) >= -EPSILON)
                .collect()
        }
    };
    nearest(
        points
            .into_iter()
            .filter(|&p| compensated.spans(p))
            .collect(),
        joint,
    )
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

    /// b/56 (seed 002 L7712-7718), G42 r 20: N10 runs -X at Y0 (compensated Y20), N20 +Y from
    /// (0,0) to (0,10) (compensated X20). G461: the circle of 20 about N20's end (0,10) meets
    /// Y20 at X = sqrt(20^2 - 10^2) = 17.3205; G462: N20's compensated line produced, X20,
    /// meets it at (20,20).
    #[test]
    fn the_retraction_of_the_manuals_g460_example_by_circle_and_by_line() {
        let previous = line(p(110.0, 0.0), p(0.0, 0.0));
        let last = line(p(0.0, 0.0), p(0.0, 10.0));
        let setting = (Side::Right, 20.0);
        let circle = extended_end(Extension::Circle, &previous, &last, setting).unwrap();
        assert!(circle.distance(p(300f64.sqrt(), 20.0)) < 1e-9, "{circle:?}");
        let ray = extended_end(Extension::Line, &previous, &last, setting).unwrap();
        assert!(ray.distance(p(20.0, 20.0)) < 1e-9, "{ray:?}");
        assert_eq!(
            extended_end(Extension::None, &previous, &last, setting),
            None
        );
    }

    /// b/57 (seed 002 L7720-7730), G42 r 10: N60 runs -Y from (50,5) to (50,0) (compensated
    /// X40), N70 -X from (50,0) to (30,0) (compensated Y10). G461: the circle of 10 about N60's
    /// start (50,5) meets Y10 at X = 50 - sqrt(10^2 - 5^2) = 41.3397; G462: X40 produced back
    /// (+Y) meets it at (40,10).
    #[test]
    fn the_approach_of_the_manuals_g461_example_by_circle_and_by_line() {
        let first = line(p(50.0, 5.0), p(50.0, 0.0));
        let next = line(p(50.0, 0.0), p(30.0, 0.0));
        let setting = (Side::Right, 10.0);
        let circle = extended_start(Extension::Circle, &first, &next, setting).unwrap();
        assert!(
            circle.distance(p(50.0 - 75f64.sqrt(), 10.0)) < 1e-9,
            "{circle:?}"
        );
        let ray = extended_start(Extension::Line, &first, &next, setting).unwrap();
        assert!(ray.distance(p(40.0, 10.0)) < 1e-9, "{ray:?}");
    }
}
