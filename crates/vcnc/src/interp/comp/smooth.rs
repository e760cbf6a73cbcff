//! SINUMERIK's smooth approach (SAR: G147, G247, G347 with G340/G341, DISR, DISCL, FAD;
//! sinumerik-part-b.md 2.4.1, seed 002 L7398-7672): the moves that take the tool centre from
//! where it stands onto the start of the compensated contour, tangent to it.
//!
//! The compensator calls [`approach_moves`] for its start-up block once the first element of
//! the contour is known (its start tangent decides the approach); everything here is built
//! from the start-up block's segment, in machine coordinates. The moves (P0 to P4):
//! - P0 -> P1 at rapid parallel to the plane, over the approach contour's start P3;
//! - P1 -> P2 at rapid along the plane's normal to the clearance DISCL above the contour;
//! - G341: P2 -> P3 on down at FAD, then the approach contour P3 -> P4 in the plane at F;
//! - G340: the approach contour from P2 to P4 in space (an oblique line or a helix) at FAD, or
//!   F without it.
//!
//! The approach contour: a straight line along the first element's tangent, the tool radius
//! plus DISR long (G147); a quarter (G247) or half circle (G347) of radius DISR for the tool
//! centre, on the tool's side (G140), tangent to the contour at its start.

use super::geometry::{Side, V2};
use crate::machine::AXES;
use crate::motion::{ArcDirection, Feed, MachinePos, Plane, Segment, SegmentKind};

/// The approach contour's shape.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Shape {
    /// G147.
    Line,
    /// G247.
    QuarterCircle,
    /// G347.
    HalfCircle,
}

/// Where the clearance plane P2 lies along the plane's normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Clearance {
    /// DISCL=d: d above the contour's level, towards the start.
    Above(f64),
    /// DISCL=AC(..): at this machine coordinate.
    At(f64),
}

/// A smooth approach, as the SAR block programs it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Approach {
    pub(crate) shape: Shape,
    /// G341: infeed first, then the approach in the plane; G340 (false): in space.
    pub(crate) in_plane: bool,
    /// DISR: the line's length beyond the tool's edge, or the circle's radius for the centre.
    pub(crate) distance: f64,
    pub(crate) clearance: Clearance,
    /// FAD: the feed of the slow infeed.
    pub(crate) slow: Option<Feed>,
    /// F: the feed of the approach contour.
    pub(crate) feed: Feed,
    /// Rapids per axis (the profile's rapid path).
    pub(crate) per_axis: bool,
}

/// The approach contour in the plane: its start P3 and, for a circle, its centre and direction.
fn contour(
    approach: &Approach,
    p4: V2,
    tangent: V2,
    side: Side,
    radius: f64,
) -> (V2, Option<(V2, bool)>) {
    let ccw = side == Side::Left;
    let centre = p4 + side.normal(tangent) * approach.distance;
    match approach.shape {
        // Only a positive tool radius lengthens the line (L7526-7530).
        Shape::Line => (p4 - tangent * (approach.distance + radius.max(0.0)), None),
        Shape::QuarterCircle => (centre - tangent * approach.distance, Some((centre, ccw))),
        Shape::HalfCircle => (
            centre + side.normal(tangent) * approach.distance,
            Some((centre, ccw)),
        ),
    }
}

/// The moves of the approach for the start-up block `segment` (from P0 to the programmed P4),
/// ending at `p4`, the compensated contour start, tangent to `tangent`, the first element's
/// direction there. `axes` are the plane's first two axes, `plane` the plane.
pub(crate) fn approach_moves(
    approach: &Approach,
    segment: &Segment,
    (p4, tangent): (V2, V2),
    (side, radius): (Side, f64),
    plane: Plane,
) -> Vec<Segment> {
    let Some(motion) = segment.motion() else {
        return vec![*segment];
    };
    let (a, b, normal) = plane.axes();
    let (p3, circle) = contour(approach, p4, tangent, side, radius);
    let from = motion.from.0;
    let level = motion.to.0[normal];
    let clearance = match approach.clearance {
        Clearance::Above(d) => {
            let up = if from[normal] < level { -1.0 } else { 1.0 };
            level + up * d
        }
        Clearance::At(z) => z,
    };
    let point = |plane_point: V2, height: f64| {
        let mut p = motion.to.0;
        p[a] = plane_point.x;
        p[b] = plane_point.y;
        p[normal] = height;
        p
    };
    let mut p1 = from;
    (p1[a], p1[b]) = (p3.x, p3.y);
    let p2 = point(p3, clearance);
    let end = point(p4, level);
    let slow = approach.slow.unwrap_or(approach.feed);
    let mut moves = Vec::new();
    let mut here = from;
    let mut push = |to: [f64; AXES], kind: Kind| {
        if (0..AXES).all(|i| (to[i] - here[i]).abs() < 1e-9) {
            return;
        }
        let mut m = *motion;
        m.from = MachinePos(here);
        m.to = MachinePos(to);
        let kind = match kind {
            Kind::Rapid => SegmentKind::Rapid {
                motion: m,
                per_axis: approach.per_axis,
            },
            Kind::Line(feed) => SegmentKind::Line { motion: m, feed },
            Kind::Arc(feed, (centre, ccw)) => {
                let mut c = here;
                (c[a], c[b]) = (centre.x, centre.y);
                SegmentKind::Arc {
                    motion: m,
                    center: MachinePos(c),
                    direction: if ccw {
                        ArcDirection::CounterClockwise
                    } else {
                        ArcDirection::Clockwise
                    },
                    plane,
                    extra_turns: 0,
                    feed,
                }
            }
        };
        moves.push(Segment { kind, ..*segment });
        here = to;
    };
    push(p1, Kind::Rapid);
    push(p2, Kind::Rapid);
    let last_feed = if approach.in_plane {
        push(point(p3, level), Kind::Line(slow));
        approach.feed
    } else {
        slow
    };
    match circle {
        Some(circle) => push(end, Kind::Arc(last_feed, circle)),
        None => push(end, Kind::Line(last_feed)),
    }
    moves
}

enum Kind {
    Rapid,
    Line(Feed),
    Arc(Feed, (V2, bool)),
}

#[cfg(test)]
mod tests {
    use super::*;

    /// b/54's line (seed 002 L7572-7597): P4 (40,-3) after compensation, direction +X, tool
    /// radius 7, DISR 13: P3 is 20 back, (20,-3).
    #[test]
    fn the_line_is_the_radius_and_disr_long() {
        let approach = Approach {
            shape: Shape::Line,
            in_plane: false,
            distance: 13.0,
            clearance: Clearance::Above(3.0),
            slow: None,
            feed: Feed::PerMinute(1000.0),
            per_axis: false,
        };
        let (p3, circle) = contour(
            &approach,
            V2::new(40.0, -3.0),
            V2::new(1.0, 0.0),
            Side::Left,
            7.0,
        );
        assert_eq!((p3, circle), (V2::new(20.0, -3.0), None));
    }

    /// b/53's quarter circle (seed 002 L7458-7503): P4 (30,5), direction +X, tool left, DISR
    /// 10: centre (30,15), start (20,15), counter-clockwise.
    #[test]
    fn the_quarter_circle_is_tangent_on_the_tools_side() {
        let approach = Approach {
            shape: Shape::QuarterCircle,
            in_plane: true,
            distance: 10.0,
            clearance: Clearance::At(7.0),
            slow: None,
            feed: Feed::PerMinute(1500.0),
            per_axis: false,
        };
        let (p3, circle) = contour(
            &approach,
            V2::new(30.0, 5.0),
            V2::new(1.0, 0.0),
            Side::Left,
            15.0,
        );
        assert_eq!(p3, V2::new(20.0, 15.0));
        assert_eq!(circle, Some((V2::new(30.0, 15.0), true)));
    }
}
