//! The plane geometry of cutter radius compensation (G41/G42): where the tool centre goes for a
//! programmed contour of lines and arcs, one corner at a time.
//!
//! Everything here is in the coordinates of the compensation plane (first and second axis of
//! G17/G18/G19, as [`crate::motion::Plane::axes`] orders them), in mm. The executor feeds the
//! programmed elements in and turns the results back into moves.
//!
//! The rules, FANUC type (spec/iso-fanuc0m-mitsubishi.md A.22, spec/iso-syntec-milling.md 1.24):
//!
//! - A compensated line is the programmed line moved sideways by the radius; a compensated arc
//!   is concentric with the programmed one, its radius larger by the tool radius when the tool
//!   is outside the arc (G41 with G02, G42 with G03) and smaller when inside.
//! - Start-up (type A): the start-up block ends at the programmed end point plus the radius
//!   perpendicular to the next element's start. Cancel and a block followed by no motion in the
//!   plane: the vector at the end of the block is perpendicular to the block's own end. Both
//!   hold round the inside of a corner too, where a corner in offset mode would take the
//!   intersection: the FANUC 0M manual has the start-up vector always perpendicular to the next
//!   path (seed 001 L970), and its example 1 starts up so at an inner corner.
//! - An inner corner: the tool centre stops where the two compensated elements intersect.
//! - An outer corner whose angle on the material side is 90 degrees or more: the tool centre
//!   goes to the intersection of the tangent lines at the ends of the two compensated elements
//!   (for two lines, where the compensated lines meet).
//! - A sharper outer corner: each compensated element is extended by the radius along its
//!   tangent and the two extension ends are joined by a straight move.

use std::ops::{Add, Mul, Neg, Sub};

/// Lengths below this are zero, in mm: far below a control's least increment.
pub(crate) const EPSILON: f64 = 1e-9;

/// How far beyond an element's end a corner point may lie and still count as on the element,
/// mm. Programs written to 0.0001 inch have arcs whose ends are that far apart from where the
/// next arc starts (corpus ramos_O1006); a control does not call that interference.
const SPAN_TOLERANCE: f64 = 0.005;

/// A point or vector in the compensation plane.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub(crate) struct V2 {
    pub(crate) x: f64,
    pub(crate) y: f64,
}

impl V2 {
    pub(crate) const fn new(x: f64, y: f64) -> V2 {
        V2 { x, y }
    }

    pub(crate) fn dot(self, other: V2) -> f64 {
        self.x * other.x + self.y * other.y
    }

    /// The z component of the cross product: positive when `other` turns left from `self`.
    pub(crate) fn cross(self, other: V2) -> f64 {
        self.x * other.y - self.y * other.x
    }

    pub(crate) fn length(self) -> f64 {
        self.x.hypot(self.y)
    }

    /// The vector turned a quarter turn counter-clockwise.
    pub(crate) fn left(self) -> V2 {
        V2::new(-self.y, self.x)
    }

    /// The unit vector in this direction (zero stays zero).
    pub(crate) fn unit(self) -> V2 {
        let length = self.length();
        if length < EPSILON {
            V2::default()
        } else {
            self * (1.0 / length)
        }
    }

    pub(crate) fn distance(self, other: V2) -> f64 {
        (other - self).length()
    }
}

impl Add for V2 {
    type Output = V2;
    fn add(self, other: V2) -> V2 {
        V2::new(self.x + other.x, self.y + other.y)
    }
}

impl Sub for V2 {
    type Output = V2;
    fn sub(self, other: V2) -> V2 {
        V2::new(self.x - other.x, self.y - other.y)
    }
}

impl Mul<f64> for V2 {
    type Output = V2;
    fn mul(self, factor: f64) -> V2 {
        V2::new(self.x * factor, self.y * factor)
    }
}

impl Neg for V2 {
    type Output = V2;
    fn neg(self) -> V2 {
        V2::new(-self.x, -self.y)
    }
}

/// The side of the contour the tool is on, looking along the direction of travel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Side {
    /// G41 (or G42 with a negative offset).
    Left,
    /// G42 (or G41 with a negative offset).
    Right,
}

impl Side {
    /// The side for a G41/G42 code and the sign of the offset value: a negative radius swaps it.
    pub(crate) fn of(left: bool, radius: f64) -> Side {
        if left == (radius >= 0.0) {
            Side::Left
        } else {
            Side::Right
        }
    }

    /// The side opposite.
    pub(crate) fn other(self) -> Side {
        match self {
            Side::Left => Side::Right,
            Side::Right => Side::Left,
        }
    }

    /// The unit normal on this side of a travel direction `tangent` (a unit vector).
    pub(crate) fn normal(self, tangent: V2) -> V2 {
        match self {
            Side::Left => tangent.left(),
            Side::Right => -tangent.left(),
        }
    }

    /// +1 for left, -1 for right: a turn is towards the tool when `sign * cross > 0`.
    fn sign(self) -> f64 {
        match self {
            Side::Left => 1.0,
            Side::Right => -1.0,
        }
    }
}

/// A programmed or compensated element of the contour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Element {
    Line {
        start: V2,
        end: V2,
    },
    /// An arc from `start` to `end` about `center`; `ccw` for G03. Start and end at the same
    /// point is a full circle.
    Arc {
        start: V2,
        end: V2,
        center: V2,
        ccw: bool,
    },
}

/// Why a compensated path cannot be made.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum GeometryError {
    /// An arc with the tool inside it and a radius not larger than the tool's (FANUC alarm 033 or
    /// 041 family): the compensated arc would vanish or turn inside out.
    ArcSmallerThanTool { arc_radius: f64, tool_radius: f64 },
    /// The two compensated elements of an inner corner do not meet: the tool would gouge the
    /// contour (FANUC alarm 041, interference).
    NoIntersection,
    /// The compensated elements of an inner corner meet beyond the end of one of them: the
    /// element is shorter than the tool needs, and following it would cut into the contour
    /// (FANUC alarm 041, interference).
    Interference,
    /// An element of no length where a direction is needed.
    ZeroLength,
    /// The compensated element comes within the tool radius of a programmed element before its
    /// neighbour (SINUMERIK's bottleneck detection, CDON).
    Bottleneck,
}

impl Element {
    pub(crate) fn start(&self) -> V2 {
        match *self {
            Element::Line { start, .. } | Element::Arc { start, .. } => start,
        }
    }

    pub(crate) fn end(&self) -> V2 {
        match *self {
            Element::Line { end, .. } | Element::Arc { end, .. } => end,
        }
    }

    /// The unit direction of travel at a point of the element (for an arc, any point on it).
    fn tangent_at(&self, point: V2) -> V2 {
        match *self {
            Element::Line { start, end } => (end - start).unit(),
            Element::Arc { center, ccw, .. } => {
                let radial = (point - center).unit();
                if ccw {
                    radial.left()
                } else {
                    -radial.left()
                }
            }
        }
    }

    /// The unit direction of travel where the element starts.
    pub(crate) fn start_tangent(&self) -> V2 {
        self.tangent_at(self.start())
    }

    /// The unit direction of travel where the element ends.
    pub(crate) fn end_tangent(&self) -> V2 {
        self.tangent_at(self.end())
    }

    /// The radius of an arc (at its start), `None` for a line.
    pub(crate) fn radius(&self) -> Option<f64> {
        match *self {
            Element::Line { .. } => None,
            Element::Arc { start, center, .. } => Some(start.distance(center)),
        }
    }

    /// The radius the compensated arc has: larger by `r` when the tool is outside.
    fn offset_radius(&self, side: Side, r: f64) -> Option<f64> {
        let Element::Arc { ccw, .. } = *self else {
            return None;
        };
        let radius = self.radius()?;
        // Travelling counter-clockwise, the left side is the inside of the arc.
        let inside = ccw == (side == Side::Left);
        Some(if inside { radius - r } else { radius + r })
    }

    /// The tool-centre element: the element moved sideways by `r`, ends on the normals of the
    /// programmed ends. Corners then trim or join these.
    ///
    /// # Errors
    /// [`GeometryError::ArcSmallerThanTool`] for an arc the tool does not fit inside.
    pub(crate) fn offset(&self, side: Side, r: f64) -> Result<Element, GeometryError> {
        match *self {
            Element::Line { start, end } => {
                let tangent = (end - start).unit();
                if tangent == V2::default() {
                    return Err(GeometryError::ZeroLength);
                }
                let shift = side.normal(tangent) * r;
                Ok(Element::Line {
                    start: start + shift,
                    end: end + shift,
                })
            }
            Element::Arc {
                start,
                end,
                center,
                ccw,
            } => {
                let radius = start.distance(center);
                let new_radius = self.offset_radius(side, r).unwrap_or(radius);
                if new_radius <= EPSILON {
                    return Err(GeometryError::ArcSmallerThanTool {
                        arc_radius: radius,
                        tool_radius: r,
                    });
                }
                let scale = |p: V2| center + (p - center).unit() * new_radius;
                Ok(Element::Arc {
                    start: scale(start),
                    end: scale(end),
                    center,
                    ccw,
                })
            }
        }
    }

    /// True when `point` (on the element's line or circle) lies between its ends, or at most
    /// [`SPAN_TOLERANCE`] beyond one.
    pub(crate) fn spans(&self, point: V2) -> bool {
        match *self {
            Element::Line { start, end } => {
                let d = end - start;
                let length = d.length();
                let t = (point - start).dot(d) / (length * length);
                let margin = SPAN_TOLERANCE / length;
                (-margin..=1.0 + margin).contains(&t)
            }
            Element::Arc { start, center, .. } => {
                let tau = std::f64::consts::TAU;
                let tolerance = SPAN_TOLERANCE / start.distance(center).max(EPSILON);
                let along = self.angle_along(point);
                along <= self.sweep() + tolerance || tau - along < tolerance
            }
        }
    }

    /// The distance from `point` to the element, exactly: a point whose nearest point on an
    /// arc's circle lies beyond the arc's ends is measured to the nearer end. (`spans` would
    /// not do: a point 0.005 mm beyond an end counts as on the element there.)
    pub(crate) fn distance(&self, point: V2) -> f64 {
        match *self {
            Element::Line { start, end } => {
                let d = end - start;
                let t = ((point - start).dot(d) / d.dot(d)).clamp(0.0, 1.0);
                point.distance(start + d * t)
            }
            Element::Arc {
                start, end, center, ..
            } => {
                if self.angle_along(point) <= self.sweep() {
                    (point.distance(center) - start.distance(center)).abs()
                } else {
                    point.distance(start).min(point.distance(end))
                }
            }
        }
    }

    /// The angle an arc turns from its start to `point`'s direction from its centre, in its
    /// own direction, in [0, tau); 0 for a line.
    pub(crate) fn angle_along(&self, point: V2) -> f64 {
        let Element::Arc {
            start, center, ccw, ..
        } = *self
        else {
            return 0.0;
        };
        let angle = |v: V2| v.y.atan2(v.x);
        let tau = std::f64::consts::TAU;
        let turned = (angle(point - center) - angle(start - center)).rem_euclid(tau);
        if ccw {
            turned
        } else {
            (tau - turned).rem_euclid(tau)
        }
    }

    /// The angle an arc sweeps (tau for a full circle); 0 for a line.
    pub(crate) fn sweep(&self) -> f64 {
        match *self {
            Element::Line { .. } => 0.0,
            Element::Arc { start, end, .. } if start.distance(end) < EPSILON => {
                std::f64::consts::TAU
            }
            Element::Arc { end, .. } => self.angle_along(end),
        }
    }
}

/// The tool-centre path through the corner where element `a` ends and element `b` starts.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Corner {
    /// Where the compensated `a` ends.
    pub(crate) a_end: V2,
    /// Moves after `a_end`, in order; the last one ends where the compensated `b` starts.
    /// Empty when `b` starts at `a_end`.
    pub(crate) links: Vec<Link>,
}

/// A move of the tool centre that joins two compensated elements.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Link {
    /// A straight move to the point (FANUC's outer corners).
    Line(V2),
    /// An arc to `to` about `center` (SINUMERIK's transition circle about the programmed
    /// corner); `ccw` for counter-clockwise.
    Arc { to: V2, center: V2, ccw: bool },
}

impl Link {
    /// Where the move ends.
    pub(crate) fn to(self) -> V2 {
        match self {
            Link::Line(to) | Link::Arc { to, .. } => to,
        }
    }
}

impl Corner {
    /// Where the compensated `b` starts.
    #[cfg(test)]
    pub(crate) fn b_start(&self) -> V2 {
        self.links.last().map_or(self.a_end, |link| link.to())
    }
}

/// How the path turns at a corner, seen from the tool's side.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Turn {
    /// The elements continue in the same direction (tangent).
    Straight,
    /// The path turns towards the tool: the compensated elements cross.
    Inner,
    /// The path turns away from the tool by at most 90 degrees (material angle 90 to 180).
    Outer,
    /// The path turns away from the tool by more than 90 degrees (material angle below 90).
    SharpOuter,
}

/// The turn from direction `ta` into direction `tb` (unit vectors) for a tool on `side`.
pub(crate) fn turn(ta: V2, tb: V2, side: Side) -> Turn {
    let cross = ta.cross(tb);
    let dot = ta.dot(tb);
    if cross.abs() < 1e-9 && dot > 0.0 {
        Turn::Straight
    } else if side.sign() * cross > 1e-9 {
        Turn::Inner
    } else if dot >= -1e-12 {
        Turn::Outer
    } else {
        Turn::SharpOuter
    }
}

/// The corner between the programmed elements `a` and `b` (`a` ends where `b` starts), with the
/// tool on `side` at radius `r`.
///
/// # Errors
/// [`GeometryError::NoIntersection`] when an inner corner's compensated elements do not meet,
/// [`GeometryError::Interference`] when they meet beyond the end of one of them (checked against
/// the whole compensated elements: the executor also checks against the previous corner), and
/// the errors of [`Element::offset`].
pub(crate) fn corner(
    a: &Element,
    b: &Element,
    side: Side,
    r: f64,
) -> Result<Corner, GeometryError> {
    let oa = a.offset(side, r)?;
    let ob = b.offset(side, r)?;
    let ta = a.end_tangent();
    let tb = b.start_tangent();
    let pa = oa.end();
    let pb = ob.start();
    match turn(ta, tb, side) {
        Turn::Straight => Ok(Corner {
            a_end: pa,
            links: if pa.distance(pb) > EPSILON {
                vec![Link::Line(pb)]
            } else {
                Vec::new()
            },
        }),
        Turn::Inner => {
            let point =
                nearest(intersections(&oa, &ob), a.end()).ok_or(GeometryError::NoIntersection)?;
            if !oa.spans(point) || !ob.spans(point) {
                return Err(GeometryError::Interference);
            }
            Ok(Corner {
                a_end: point,
                links: Vec::new(),
            })
        }
        Turn::Outer => match nearest(intersections(&oa, &ob), a.end()) {
            // The compensated paths meet (an arc's path taken as its whole circle): the tool
            // centre goes there, as the FANUC 0M manual's example shows at an arc-line corner.
            Some(point) if !matches!((a, b), (Element::Line { .. }, Element::Line { .. })) => {
                Ok(Corner {
                    a_end: point,
                    links: Vec::new(),
                })
            }
            _ => {
                // The tangent lines at the compensated ends meet at q.
                let q = line_intersection(pa, ta, pb, tb).unwrap_or(pa);
                Ok(outer_corner(a, b, pa, pb, &[q]))
            }
        },
        Turn::SharpOuter => {
            let qa = pa + ta * r;
            let qb = pb - tb * r;
            Ok(outer_corner(a, b, pa, pb, &[qa, qb]))
        }
    }
}

/// The corner where the side changes (G41 <-> G42 in offset mode): `a` compensated with `old`,
/// `b` with `new`. The tool centre goes to where the two compensated paths cross, if they do
/// within both elements; otherwise to the end of `a` perpendicular to it, then straight to the
/// start of `b` perpendicular to it.
///
/// # Errors
/// The errors of [`Element::offset`].
pub(crate) fn side_change(
    a: &Element,
    b: &Element,
    old: (Side, f64),
    new: (Side, f64),
) -> Result<Corner, GeometryError> {
    let oa = a.offset(old.0, old.1)?;
    let ob = b.offset(new.0, new.1)?;
    let crossing = intersections(&oa, &ob)
        .into_iter()
        .filter(|&p| oa.spans(p) && ob.spans(p));
    Ok(match nearest(crossing.collect(), a.end()) {
        Some(point) => Corner {
            a_end: point,
            links: Vec::new(),
        },
        None => Corner {
            a_end: perpendicular_end(a, old.0, old.1),
            links: vec![Link::Line(start_up_end(b, new.0, new.1))],
        },
    })
}

/// An outer corner through the points `via`: a compensated line runs on to the first of them, a
/// compensated arc ends on its normal and a straight move joins it; the same at `b`'s side.
fn outer_corner(a: &Element, b: &Element, pa: V2, pb: V2, via: &[V2]) -> Corner {
    let a_is_line = matches!(a, Element::Line { .. });
    let b_is_line = matches!(b, Element::Line { .. });
    let (a_end, rest) = if a_is_line {
        (via[0], &via[1..])
    } else {
        (pa, via)
    };
    let mut links: Vec<V2> = rest.to_vec();
    if !b_is_line {
        links.push(pb);
    }
    links.dedup_by(|p, q| p.distance(*q) < EPSILON);
    if links.first().is_some_and(|p| p.distance(a_end) < EPSILON) {
        links.remove(0);
    }
    Corner {
        a_end,
        links: links.into_iter().map(Link::Line).collect(),
    }
}

/// The point of `points` nearest `to`.
pub(crate) fn nearest(points: Vec<V2>, to: V2) -> Option<V2> {
    points
        .into_iter()
        .min_by(|p, q| p.distance(to).total_cmp(&q.distance(to)))
}

/// Where the lines through `p` along `u` and through `q` along `v` meet; `None` when parallel.
fn line_intersection(p: V2, u: V2, q: V2, v: V2) -> Option<V2> {
    let denominator = u.cross(v);
    if denominator.abs() < 1e-12 {
        return None;
    }
    let t = (q - p).cross(v) / denominator;
    Some(p + u * t)
}

/// The points where two compensated elements meet, taking lines as infinite and arcs as full
/// circles (the corner picks the one nearest the programmed corner).
pub(crate) fn intersections(a: &Element, b: &Element) -> Vec<V2> {
    match (*a, *b) {
        (Element::Line { start: p, end: p2 }, Element::Line { start: q, end: q2 }) => {
            line_intersection(p, (p2 - p).unit(), q, (q2 - q).unit())
                .into_iter()
                .collect()
        }
        (Element::Line { start, end }, Element::Arc { .. }) => {
            let (center, radius) = circle(b);
            line_circle(start, (end - start).unit(), center, radius)
        }
        (Element::Arc { .. }, Element::Line { start, end }) => {
            let (center, radius) = circle(a);
            line_circle(start, (end - start).unit(), center, radius)
        }
        (Element::Arc { .. }, Element::Arc { .. }) => {
            let (c1, r1) = circle(a);
            let (c2, r2) = circle(b);
            circle_circle(c1, r1, c2, r2)
        }
    }
}

fn circle(element: &Element) -> (V2, f64) {
    match *element {
        Element::Arc { start, center, .. } => (center, start.distance(center)),
        Element::Line { start, .. } => (start, 0.0),
    }
}

/// Where the line through `p` along the unit vector `u` meets the circle.
fn line_circle(p: V2, u: V2, center: V2, radius: f64) -> Vec<V2> {
    // |p + t u - c|^2 = r^2  =>  t^2 + 2 t (u.(p-c)) + |p-c|^2 - r^2 = 0
    let d = p - center;
    let b = u.dot(d);
    let c = d.dot(d) - radius * radius;
    let discriminant = b * b - c;
    if discriminant < -1e-9 {
        return Vec::new();
    }
    let root = discriminant.max(0.0).sqrt();
    vec![p + u * (-b - root), p + u * (-b + root)]
}

/// Where two circles meet.
fn circle_circle(c1: V2, r1: f64, c2: V2, r2: f64) -> Vec<V2> {
    let between = c2 - c1;
    let d = between.length();
    if d < EPSILON || d > r1 + r2 + 1e-9 || d < (r1 - r2).abs() - 1e-9 {
        return Vec::new();
    }
    // Distance from c1 to the chord through both points, and half the chord.
    let along = (d * d + r1 * r1 - r2 * r2) / (2.0 * d);
    let half = (r1 * r1 - along * along).max(0.0).sqrt();
    let axis = between * (1.0 / d);
    let foot = c1 + axis * along;
    vec![foot + axis.left() * half, foot - axis.left() * half]
}

/// The start-up (type A): where the start-up block's tool centre ends, the programmed end point
/// of the block moved by `r` perpendicular to the start of the next element.
pub(crate) fn start_up_end(next: &Element, side: Side, r: f64) -> V2 {
    next.start() + side.normal(next.start_tangent()) * r
}

/// The end of the last compensated element before a cancel, or before blocks with no motion in
/// the plane: perpendicular to the element's own end.
pub(crate) fn perpendicular_end(last: &Element, side: Side, r: f64) -> V2 {
    last.end() + side.normal(last.end_tangent()) * r
}

/// FANUC's interference check on a compensated element once both its corners are known: the
/// tool centre, going from `start` to `end`, would travel against the programmed element (a
/// line's direction turned by more than 90 degrees, an arc's swept angle changed by more than
/// 180 degrees). Following it would cut into the contour.
pub(crate) fn interferes(programmed: &Element, start: V2, end: V2) -> bool {
    match *programmed {
        Element::Line { start: p, end: q } => (end - start).dot(q - p) < -EPSILON,
        Element::Arc {
            start: p,
            end: q,
            center,
            ccw,
        } => {
            let tau = std::f64::consts::TAU;
            let sweep = |from: V2, to: V2| {
                let (a, b) = (from - center, to - center);
                let ccw_angle = (b.y.atan2(b.x) - a.y.atan2(a.x)).rem_euclid(tau);
                if ccw {
                    ccw_angle
                } else {
                    (tau - ccw_angle).rem_euclid(tau)
                }
            };
            let pi = std::f64::consts::PI;
            let programmed = if p.distance(q) < 1e-7 {
                tau
            } else {
                sweep(p, q)
            };
            // Ends that meet: a full circle if the programmed arc is nearly full, else nothing.
            let compensated = if start.distance(end) < 1e-7 {
                if programmed > pi {
                    tau
                } else {
                    0.0
                }
            } else {
                sweep(start, end)
            };
            (compensated - programmed).abs() > pi
        }
    }
}

#[cfg(test)]
pub(super) mod tests;
