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

/// The side the approach or retraction contour lies on (group 43).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Direction {
    /// G140: the compensation's side.
    Compensation,
    /// G141: from (or to) the left of the contour.
    Left,
    /// G142: from (or to) the right.
    Right,
    /// G143: the side of the contour's tangent at P4 that P0 lies on.
    Tangent,
}

/// A smooth approach, as the SAR block programs it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Approach {
    pub(crate) shape: Shape,
    pub(crate) direction: Direction,
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

impl Approach {
    /// The side the contour lies on for a tool on `side`, P0 lying at `away` from P4, where
    /// the contour's tangent is `tangent` (the manual: G140-G143, seed 002 L7421-7432).
    fn side(&self, side: Side, (away, tangent): (V2, V2)) -> Side {
        match self.direction {
            Direction::Compensation => side,
            Direction::Left => Side::Left,
            Direction::Right => Side::Right,
            Direction::Tangent if tangent.cross(away) >= 0.0 => Side::Left,
            Direction::Tangent => Side::Right,
        }
    }
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
    let from = motion.from.0;
    let side = approach.side(side, (V2::new(from[a], from[b]) - p4, tangent));
    let (p3, circle) = contour(approach, p4, tangent, side, radius);
    let level = motion.to.0[normal];
    let clearance = clearance(approach.clearance, level, from[normal]);
    let mut moves = Moves::new(segment, plane, approach.per_axis);
    let mut p1 = from;
    set(&mut p1, plane, p3, None);
    let end = moves.point(p4, level);
    let slow = approach.slow.unwrap_or(approach.feed);
    moves.to(p1, Kind::Rapid);
    moves.to(moves.point(p3, clearance), Kind::Rapid);
    let last_feed = if approach.in_plane {
        moves.to(moves.point(p3, level), Kind::Line(slow));
        approach.feed
    } else {
        slow
    };
    match circle {
        Some(circle) => moves.to(end, Kind::Arc(last_feed, circle)),
        None => moves.to(end, Kind::Line(last_feed)),
    }
    moves.done
}

/// The moves of the smooth retraction (G148, G248, G348) of the cancelling block `segment`,
/// from the last element's compensated end `p4` (where the segment starts, at the contour's
/// level), leaving it tangent to `tangent`, to the segment's end P0: the retraction contour to
/// P3 at `contour_feed` (the last element's: the roles of the feeds reverse, seed 002
/// L7621-7646), in space up to the clearance P2 (G340) or in the plane and then up at FAD
/// (G341); then along the plane's normal to P0's level (P1) and across to P0 as the block moves
/// (its G0, or its F).
pub(crate) fn retraction_moves(
    retraction: &Approach,
    segment: &Segment,
    (p4, tangent): (V2, V2),
    (side, radius): (Side, f64),
    plane: Plane,
    contour_feed: Option<Feed>,
) -> Vec<Segment> {
    let Some(motion) = segment.motion() else {
        return vec![*segment];
    };
    let (a, b, normal) = plane.axes();
    let side = retraction.side(
        side,
        (V2::new(motion.to.0[a], motion.to.0[b]) - p4, tangent),
    );
    let (p3, circle) = contour(retraction, p4, -tangent, side.other(), radius);
    // Travelled the other way: the circle turns the way the approach's would, seen backwards.
    let circle = circle.map(|(centre, ccw)| (centre, !ccw));
    let level = motion.from.0[normal];
    let p0 = motion.to.0;
    let clearance = clearance(retraction.clearance, level, p0[normal]);
    let mut moves = Moves::new(segment, plane, retraction.per_axis);
    let contour_end = if retraction.in_plane {
        moves.point(p3, level)
    } else {
        moves.point(p3, clearance)
    };
    let contour_kind = |circle: Option<(V2, bool)>| match (circle, contour_feed) {
        (Some(circle), feed) => Kind::Arc(feed.unwrap_or(retraction.feed), circle),
        (None, Some(feed)) => Kind::Line(feed),
        (None, None) => Kind::Rapid,
    };
    moves.to(contour_end, contour_kind(circle));
    if retraction.in_plane {
        let slow = retraction.slow.or(contour_feed);
        moves.to(
            moves.point(p3, clearance),
            slow.map_or(Kind::Rapid, Kind::Line),
        );
    }
    let last = match segment.kind {
        SegmentKind::Rapid { .. } => Kind::Rapid,
        _ => Kind::Line(retraction.feed),
    };
    moves.to(moves.point(p3, p0[normal]), last);
    moves.to(p0, last);
    moves.done
}

/// Where P2 lies along the plane's normal: DISCL above the contour's `level`, towards `away`
/// (the far end's level), or at its absolute position.
fn clearance(clearance: Clearance, level: f64, away: f64) -> f64 {
    match clearance {
        Clearance::Above(d) => {
            let up = if away < level { -1.0 } else { 1.0 };
            level + up * d
        }
        Clearance::At(z) => z,
    }
}

/// `p`'s plane coordinates set to `point`, and its normal coordinate to `height` if given.
fn set(p: &mut [f64; AXES], plane: Plane, point: V2, height: Option<f64>) {
    let (a, b, normal) = plane.axes();
    (p[a], p[b]) = (point.x, point.y);
    if let Some(height) = height {
        p[normal] = height;
    }
}

/// The moves of an approach or retraction, each one of the block's segment.
struct Moves<'a> {
    segment: &'a Segment,
    plane: Plane,
    per_axis: bool,
    here: [f64; AXES],
    done: Vec<Segment>,
}

impl<'a> Moves<'a> {
    fn new(segment: &'a Segment, plane: Plane, per_axis: bool) -> Self {
        let here = segment.motion().map_or([0.0; AXES], |m| m.from.0);
        Moves {
            segment,
            plane,
            per_axis,
            here,
            done: Vec::new(),
        }
    }

    /// The segment's end with the plane point `point` at `height` along the normal.
    fn point(&self, point: V2, height: f64) -> [f64; AXES] {
        let mut p = self.segment.motion().map_or(self.here, |m| m.to.0);
        set(&mut p, self.plane, point, Some(height));
        p
    }

    /// A move from where the last one ended to `to`; none of no length.
    fn to(&mut self, to: [f64; AXES], kind: Kind) {
        let Some(motion) = self.segment.motion() else {
            return;
        };
        if (0..AXES).all(|i| (to[i] - self.here[i]).abs() < 1e-9) {
            return;
        }
        let mut m = *motion;
        m.from = MachinePos(self.here);
        m.to = MachinePos(to);
        let kind = match kind {
            Kind::Rapid => SegmentKind::Rapid {
                motion: m,
                per_axis: self.per_axis,
            },
            Kind::Line(feed) => SegmentKind::Line { motion: m, feed },
            Kind::Arc(feed, (centre, ccw)) => {
                let mut c = self.here;
                set(&mut c, self.plane, centre, None);
                SegmentKind::Arc {
                    motion: m,
                    center: MachinePos(c),
                    direction: if ccw {
                        ArcDirection::CounterClockwise
                    } else {
                        ArcDirection::Clockwise
                    },
                    plane: self.plane,
                    extra_turns: 0,
                    feed,
                }
            }
        };
        self.done.push(Segment {
            kind,
            ..*self.segment
        });
        self.here = to;
    }
}

#[derive(Clone, Copy)]
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
            direction: Direction::Compensation,
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
            direction: Direction::Compensation,
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
