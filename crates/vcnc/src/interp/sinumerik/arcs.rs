//! The arcs of the SINUMERIK front end, as pure geometry: the centre of a G2/G3 from `CR=`, the
//! centre or the end from `AR=`, the tangential arc `CT`, the circle through an intermediate
//! point `CIP`, and the extra turns of `TURN=` (docs/SINUMERIK.md 6.3; spec
//! sinumerik-part-b.md 1.6-1.7, PGsl 9.6-9.7, L5182-5716).
//!
//! Points are in the plane's (abscissa, ordinate) coordinates as [`Plane::axes`] orders them
//! (G18: Z then X), except CIP, whose points are (X, Y, Z) work coordinates. The front end turns
//! the words into these numbers (AC/IC, G90/G91, inch) before it calls; the results go to the
//! kernel as an ordinary arc. Nothing here reads a word or keeps state, and bad data never
//! panics: it is an [`Alarm`] at the span the caller gives.
#![cfg_attr(not(test), allow(dead_code))] // wired in by the front end (issue 20)

use crate::alarm::{Alarm, AlarmCode};
use crate::interp::arc::{arc_center, ArcSpec};
use crate::interp::comp::geometry::V2;
use crate::motion::{ArcDirection, Plane};
use crate::source::Span;

/// Lengths below this are zero, in mm: far below the control's least increment.
const EPSILON: f64 = 1e-9;

/// Out of its working plane by less than this (mm at the circle's rim), a CIP circle counts as
/// in the plane: the points are written to 0.001 mm, their own error is far larger.
const PLANE_TOLERANCE: f64 = 1e-6;

/// The centre of `G2/G3 X.. Y.. CR=radius` (PGsl 9.6.3, L5356-5411): a positive radius takes
/// the arc of 180 degrees or less, a negative one the longer arc. `tolerance` is the profile's
/// arc tolerance: a radius short of half the chord by no more than that is a half circle.
///
/// # Errors
/// [`AlarmCode::ArcRadiusTooSmall`] when `CR=0`, when the end is on the start (a full circle
/// cannot be programmed with CR, L5380) or when the radius is shorter than half the chord.
pub(crate) fn centre_from_radius(
    start: V2,
    end: V2,
    radius: f64,
    direction: ArcDirection,
    tolerance: f64,
    span: Span,
) -> Result<V2, Alarm> {
    if radius == 0.0 {
        return Err(Alarm::error(
            AlarmCode::ArcRadiusTooSmall,
            span,
            "CR=0 gives no circle",
        ));
    }
    let spec = ArcSpec::Radius { radius, span };
    match arc_center(
        (start.x, start.y),
        (end.x, end.y),
        spec,
        direction,
        tolerance,
    ) {
        Ok((x, y)) => Ok(V2::new(x, y)),
        // The ISO alarm speaks of R; say CR= here, with the same code.
        Err(_) if start.distance(end) < EPSILON => Err(Alarm::error(
            AlarmCode::ArcRadiusTooSmall,
            span,
            "a CR= arc needs an end point different from its start",
        )
        .with_help("program a full circle with its centre (I, J, K) and no CR=")),
        Err(_) => Err(Alarm::error(
            AlarmCode::ArcRadiusTooSmall,
            span,
            format!(
                "CR={:.4} is smaller than half the distance to the end point ({:.4})",
                radius.abs(),
                start.distance(end) / 2.0
            ),
        )),
    }
}

/// The centre of `G2/G3 X.. Y.. AR=opening` (PGsl 9.6.4, L5413-5464): on the chord's
/// perpendicular bisector, `(chord / 2) / tan(AR / 2)` from its middle, on the left of the
/// chord for G3 under 180 degrees (the tangent's sign moves it across beyond 180).
///
/// # Errors
/// [`AlarmCode::ValueOutOfRange`] for an opening outside 0-360 degrees (both excluded: a full
/// circle cannot be programmed with AR, L5425), [`AlarmCode::ArcRadiusTooSmall`] when the end
/// is on the start.
pub(crate) fn centre_from_opening(
    start: V2,
    end: V2,
    opening: f64,
    direction: ArcDirection,
    span: Span,
) -> Result<V2, Alarm> {
    check_opening(opening, span)?;
    let chord = end - start;
    let length = chord.length();
    if length < EPSILON {
        return Err(Alarm::error(
            AlarmCode::ArcRadiusTooSmall,
            span,
            "an AR= arc with an end point needs an end point different from its start",
        )
        .with_help("program a full circle with its centre (I, J, K) and no AR="));
    }
    let from_middle = (length / 2.0) / (opening.to_radians() / 2.0).tan();
    let middle = start + chord * 0.5;
    Ok(middle + chord.unit().left() * (from_middle * ccw_sign(direction)))
}

/// The end of `G2/G3 I.. J.. AR=opening` (PGsl 9.6.4): the start turned about the centre by
/// the opening, counter-clockwise for G3.
///
/// # Errors
/// [`AlarmCode::ValueOutOfRange`] for an opening outside 0-360 degrees,
/// [`AlarmCode::ArcWithoutCenter`] when the centre is on the start.
pub(crate) fn end_from_opening(
    start: V2,
    centre: V2,
    opening: f64,
    direction: ArcDirection,
    span: Span,
) -> Result<V2, Alarm> {
    check_opening(opening, span)?;
    if start.distance(centre) < EPSILON {
        return Err(Alarm::error(
            AlarmCode::ArcWithoutCenter,
            span,
            "the arc's centre is on its start point",
        ));
    }
    Ok(turned(
        start,
        centre,
        opening.to_radians() * ccw_sign(direction),
    ))
}

/// `point` turned about `centre` by `angle` radians, counter-clockwise when positive.
pub(super) fn turned(point: V2, centre: V2, angle: f64) -> V2 {
    let (sin, cos) = angle.sin_cos();
    let radial = point - centre;
    centre
        + V2::new(
            radial.x * cos - radial.y * sin,
            radial.x * sin + radial.y * cos,
        )
}

/// `AR=` takes an opening of more than 0 and less than 360 degrees.
fn check_opening(opening: f64, span: Span) -> Result<(), Alarm> {
    if opening > 0.0 && opening < 360.0 {
        return Ok(());
    }
    Err(Alarm::error(
        AlarmCode::ValueOutOfRange,
        span,
        format!("AR={opening} is not an opening angle between 0 and 360 degrees"),
    )
    .with_help("a full circle is programmed with its centre (I, J, K) and no AR="))
}

/// +1 for G3, -1 for G2: counter-clockwise angles are positive.
fn ccw_sign(direction: ArcDirection) -> f64 {
    match direction {
        ArcDirection::CounterClockwise => 1.0,
        ArcDirection::Clockwise => -1.0,
    }
}

/// What `CT` makes from its start, end and the direction it must leave the start in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Tangential {
    /// The end is ahead on the tangent: a straight line (L5585-5590: a circle of infinite
    /// radius; TURN must then be 0, which the caller checks).
    Line,
    /// An arc about `centre`.
    Arc { centre: V2, direction: ArcDirection },
}

/// The arc of `CT X.. Y..` (PGsl 9.6.7, L5566-5645): through the start and the end, leaving the
/// start along `tangent`, the direction in which the previous element with motion ended
/// (`Element::end_tangent` of comp's geometry, or a line's direction; a direction out of the
/// plane is given as its projection, L5591). With `n` the tangent turned left and `d` the
/// chord, the centre is `start + n * |d|^2 / (2 n.d)`: counter-clockwise when positive.
///
/// # Errors
/// [`AlarmCode::ArcWithoutCenter`] when there is no direction to be tangent to (no previous
/// motion in the plane) or when the end lies behind the start on the tangent (no circle is
/// tangent there), [`AlarmCode::ArcRadiusTooSmall`] when the end is on the start.
pub(crate) fn tangential_arc(
    start: V2,
    end: V2,
    tangent: V2,
    span: Span,
) -> Result<Tangential, Alarm> {
    let tangent = tangent.unit();
    if tangent == V2::default() {
        return Err(Alarm::error(
            AlarmCode::ArcWithoutCenter,
            span,
            "CT has no previous motion in the plane to be tangent to",
        )
        .with_help("program the arc's centre (I, J, K) or radius (CR=) instead of CT"));
    }
    let chord = end - start;
    let length = chord.length();
    if length < EPSILON {
        return Err(Alarm::error(
            AlarmCode::ArcRadiusTooSmall,
            span,
            "a CT arc needs an end point different from its start",
        ));
    }
    let normal = tangent.left();
    let across = normal.dot(chord);
    // Relative to the chord: an end this close to the tangent is on it (the radius would be a
    // billion chords).
    if across.abs() <= EPSILON * length {
        if tangent.dot(chord) > 0.0 {
            return Ok(Tangential::Line);
        }
        return Err(Alarm::error(
            AlarmCode::ArcWithoutCenter,
            span,
            "the CT end point lies behind the start on the tangent: no circle fits",
        ));
    }
    let signed_radius = chord.dot(chord) / (2.0 * across);
    let direction = if signed_radius > 0.0 {
        ArcDirection::CounterClockwise
    } else {
        ArcDirection::Clockwise
    };
    Ok(Tangential::Arc {
        centre: start + normal * signed_radius,
        direction,
    })
}

/// The extra full turns of `TURN=n` (PGsl 9.7, L5647-5716): a whole number from 0 to 999.
///
/// # Errors
/// [`AlarmCode::ValueOutOfRange`] otherwise.
pub(crate) fn extra_turns(turn: f64, span: Span) -> Result<u32, Alarm> {
    if turn.fract() == 0.0 && (0.0..=999.0).contains(&turn) {
        // A whole number in 0..=999 converts exactly.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        return Ok(turn as u32);
    }
    Err(Alarm::error(
        AlarmCode::ValueOutOfRange,
        span,
        format!("TURN={turn} is not a number of turns from 0 to 999"),
    ))
}

/// A point or vector in work coordinates (X, Y, Z).
pub(crate) type Point3 = [f64; 3];

/// The circle of a `CIP` block: through the start, the intermediate point and the end, in
/// that order, in whatever plane they lie (PGsl 9.6.6, L5506-5565).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SpaceCircle {
    /// The centre, work coordinates.
    pub(crate) centre: Point3,
    pub(crate) radius: f64,
    /// The unit normal of the circle's plane about which the travel is counter-clockwise
    /// (right-hand rule).
    pub(crate) normal: Point3,
    /// The angle travelled from the start to the end, radians, in (0, 2 pi).
    pub(crate) sweep: f64,
}

impl SpaceCircle {
    /// The direction of the arc when it lies in `plane` (or one parallel to it): then it is an
    /// ordinary G2/G3 about `centre`. `None` when the circle is inclined to the plane.
    pub(crate) fn direction_in(&self, plane: Plane) -> Option<ArcDirection> {
        let (_, _, axis) = plane.axes();
        let along = self.normal[axis];
        // How far the rim leaves the plane: the normal's part in the plane times the radius.
        let off = (1.0 - along * along).max(0.0).sqrt() * self.radius;
        if off > PLANE_TOLERANCE {
            return None;
        }
        Some(if along > 0.0 {
            ArcDirection::CounterClockwise
        } else {
            ArcDirection::Clockwise
        })
    }

    /// The plane of G17/G18/G19 the circle lies in, with its direction there, if any: the
    /// manual lets a CIP circle lie outside the selected plane (L5343-5346).
    pub(crate) fn machine_plane(&self) -> Option<(Plane, ArcDirection)> {
        [Plane::Xy, Plane::Zx, Plane::Yz]
            .into_iter()
            .find_map(|plane| Some((plane, self.direction_in(plane)?)))
    }

    /// The angle between the circle's plane and `plane`, degrees (0 to 90).
    pub(crate) fn tilt(&self, plane: Plane) -> f64 {
        let (_, _, axis) = plane.axes();
        self.normal[axis].abs().min(1.0).acos().to_degrees()
    }

    /// The alarm for a caller that moves only on arcs in a plane of G17/G18/G19: this circle
    /// lies in none of them (docs/SINUMERIK.md, open question 1).
    pub(crate) fn inclined_alarm(&self, plane: Plane, span: Span) -> Alarm {
        Alarm::error(
            AlarmCode::NotSupportedYet,
            span,
            format!(
                "a CIP circle inclined by {:.3} degrees to the working plane is not supported yet",
                self.tilt(plane)
            ),
        )
        .with_help("program the arc in a plane of G17, G18 or G19, or as straight moves")
    }
}

/// The circle of `CIP` through `start`, `via` and `end` (work coordinates), travelled in that
/// order. Its centre is the circumcentre: with `a = via - start`, `b = end - start`, it is
/// `start + ((|a|^2 b - |b|^2 a) x (a x b)) / (2 |a x b|^2)`.
///
/// # Errors
/// [`AlarmCode::ArcWithoutCenter`] when the three points lie on one line or two of them
/// coincide: they define no circle.
pub(crate) fn circle_through(
    start: Point3,
    via: Point3,
    end: Point3,
    span: Span,
) -> Result<SpaceCircle, Alarm> {
    let a = sub(via, start);
    let b = sub(end, start);
    let normal = cross(a, b);
    let area = norm(normal);
    // Relative to the sides: collinear within rounding, or a side of no length.
    if area <= EPSILON * norm(a) * norm(b) || area == 0.0 {
        return Err(Alarm::error(
            AlarmCode::ArcWithoutCenter,
            span,
            "the CIP start, intermediate and end points lie on one line: they define no circle",
        )
        .with_help("move the intermediate point (I1, J1, K1) off the line from start to end"));
    }
    let numerator = cross(sub(scale(b, dot(a, a)), scale(a, dot(b, b))), normal);
    let to_centre = scale(numerator, 1.0 / (2.0 * area * area));
    let centre = add(start, to_centre);
    let radius = norm(to_centre);
    let normal = scale(normal, 1.0 / area);
    // The angle of the end in the circle's own axes: u towards the start, w = normal x u.
    let u = scale(sub(start, centre), 1.0 / radius);
    let w = cross(normal, u);
    let e = sub(end, centre);
    let sweep = dot(e, w).atan2(dot(e, u)).rem_euclid(std::f64::consts::TAU);
    Ok(SpaceCircle {
        centre,
        radius,
        normal,
        sweep,
    })
}

fn sub(p: Point3, q: Point3) -> Point3 {
    [p[0] - q[0], p[1] - q[1], p[2] - q[2]]
}

fn add(p: Point3, q: Point3) -> Point3 {
    [p[0] + q[0], p[1] + q[1], p[2] + q[2]]
}

fn scale(p: Point3, factor: f64) -> Point3 {
    [p[0] * factor, p[1] * factor, p[2] * factor]
}

fn dot(p: Point3, q: Point3) -> f64 {
    p[0] * q[0] + p[1] * q[1] + p[2] * q[2]
}

fn cross(p: Point3, q: Point3) -> Point3 {
    [
        p[1] * q[2] - p[2] * q[1],
        p[2] * q[0] - p[0] * q[2],
        p[0] * q[1] - p[1] * q[0],
    ]
}

fn norm(p: Point3) -> f64 {
    p[0].hypot(p[1]).hypot(p[2])
}

/// Most straight pieces one circle in no machine plane is cut into (as the ISO spiral's): at 1 µm
/// a circle of about 2 km radius; beyond, the block alarms rather than leave the tolerance.
const MOST_CHORDS: f64 = 100_000.0;

/// How many chords within `tolerance` of a circle of `radius` a `sweep` (radians, either sign)
/// takes.
///
/// # Errors
/// More than [`MOST_CHORDS`], at `span`.
pub(crate) fn chord_count(
    sweep: f64,
    radius: f64,
    tolerance: f64,
    span: Span,
) -> Result<usize, Alarm> {
    // Chords of at most `tolerance` from the circle: 2 r (1 - cos(step / 2)) <= tolerance.
    let step = 2.0
        * (1.0 - tolerance / radius.max(EPSILON))
            .clamp(-1.0, 1.0)
            .acos();
    let pieces = (sweep.abs() / step.max(1e-9)).ceil();
    if pieces > MOST_CHORDS || pieces.is_nan() {
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            span,
            format!(
                "this circle (radius {radius:.3} mm) in no machine plane would take {pieces} \
                 straight pieces within {tolerance} mm; vcnc stops at {MOST_CHORDS} a block"
            ),
        )
        .with_help("check the circle's points: a radius of kilometres is a typing error"));
    }
    Ok((pieces as usize).max(1))
}

/// The points of an arc (or helix) in its own plane's coordinates, for a frame that tilts that
/// plane out of G17/G18/G19: straight pieces whose chords stay within `tolerance` of the
/// circle. The radius runs linearly from the start's to the end's (the end is reached exactly)
/// and the third axis linearly from `height.0` to `height.1`; `turns` full turns come beyond
/// the first, an end on the start is a full circle.
#[allow(clippy::too_many_arguments)] // the arc's words, its tolerance and where to alarm
pub(crate) fn helix_points(
    start: V2,
    centre: V2,
    end: V2,
    height: (f64, f64),
    direction: ArcDirection,
    turns: u32,
    tolerance: f64,
    span: Span,
) -> Result<Vec<(V2, f64)>, Alarm> {
    let (r0, r1) = ((start - centre).length(), (end - centre).length());
    let a0 = (start.y - centre.y).atan2(start.x - centre.x);
    let a1 = (end.y - centre.y).atan2(end.x - centre.x);
    let tau = std::f64::consts::TAU;
    let mut sweep = match direction {
        ArcDirection::CounterClockwise => (a1 - a0).rem_euclid(tau),
        ArcDirection::Clockwise => -(a0 - a1).rem_euclid(tau),
    };
    if (end - start).length() <= EPSILON * r0.max(1.0) {
        sweep = if direction == ArcDirection::Clockwise {
            -tau
        } else {
            tau
        };
    }
    sweep += f64::from(turns) * tau * sweep.signum();
    let pieces = chord_count(sweep, r0.max(r1), tolerance, span)?;
    Ok((1..=pieces)
        .map(|k| {
            if k == pieces {
                return (end, height.1);
            }
            let t = k as f64 / pieces as f64;
            let (sin, cos) = (a0 + sweep * t).sin_cos();
            let r = r0 + (r1 - r0) * t;
            let point = V2::new(centre.x + r * cos, centre.y + r * sin);
            (point, height.0 + (height.1 - height.0) * t)
        })
        .collect())
}

#[cfg(test)]
pub(super) mod tests {
    //! Also the helpers of the polar and contour tests.
    use super::*;
    use crate::interp::comp::geometry::Element;

    pub(in crate::interp::sinumerik) const SPAN: Span = Span {
        file: crate::source::FileId(0),
        start: 0,
        end: 0,
        line: 1,
    };
    const CW: ArcDirection = ArcDirection::Clockwise;
    const CCW: ArcDirection = ArcDirection::CounterClockwise;

    pub(in crate::interp::sinumerik) fn p(x: f64, y: f64) -> V2 {
        V2::new(x, y)
    }

    pub(in crate::interp::sinumerik) fn assert_near(got: V2, want: (f64, f64), tolerance: f64) {
        assert!(
            (got.x - want.0).abs() <= tolerance && (got.y - want.1).abs() <= tolerance,
            "got {got:?}, want {want:?}"
        );
    }

    fn assert_near3(got: Point3, want: Point3, tolerance: f64) {
        assert!(
            (0..3).all(|i| (got[i] - want[i]).abs() <= tolerance),
            "got {got:?}, want {want:?}"
        );
    }

    #[test]
    fn cr_example_b14_has_its_centre_where_the_header_says() {
        // Example sinumerik-b/14-circle-cr-milling.mpf: G3 from X67.5 Y80.511 to X17.203
        // Y38.029 with CR=34.913, centre X49.857 Y50.384.
        let c = centre_from_radius(p(67.5, 80.511), p(17.203, 38.029), 34.913, CCW, 0.01, SPAN);
        assert_near(c.unwrap(), (49.857, 50.384), 1e-3);
    }

    #[test]
    fn negative_cr_takes_the_long_way_as_in_example_b08() {
        // Example sinumerik-b/08-circle-forms-milling.mpf: G2 X115 Y113.3 CR=-50 from X133
        // Y44.48, centre X90.002 Y69.998 (269 degrees clockwise).
        let c = centre_from_radius(p(133.0, 44.48), p(115.0, 113.3), -50.0, CW, 0.01, SPAN);
        assert_near(c.unwrap(), (90.002, 69.998), 1e-3);
    }

    #[test]
    fn cr_shorter_than_half_the_chord_or_zero_is_an_alarm() {
        // The chord from X0 to X30 needs CR of at least 15.
        let short = centre_from_radius(p(0.0, 0.0), p(30.0, 0.0), 10.0, CW, 0.01, SPAN);
        assert_eq!(short.unwrap_err().code, AlarmCode::ArcRadiusTooSmall);
        let zero = centre_from_radius(p(0.0, 0.0), p(30.0, 0.0), 0.0, CW, 0.01, SPAN);
        assert_eq!(zero.unwrap_err().code, AlarmCode::ArcRadiusTooSmall);
        let full = centre_from_radius(p(5.0, 5.0), p(5.0, 5.0), 10.0, CW, 0.01, SPAN);
        assert_eq!(full.unwrap_err().code, AlarmCode::ArcRadiusTooSmall);
    }

    #[test]
    fn ar_with_end_point_finds_the_centres_of_examples_b16_and_b08() {
        // sinumerik-b/16-circle-ar-milling.mpf: G3 X17.203 Y38.029 AR=140.134 from X67.5
        // Y80.211, centre X50 Y50 (the end is written to 0.001, so the centre to about that).
        let c = centre_from_opening(p(67.5, 80.211), p(17.203, 38.029), 140.134, CCW, SPAN);
        assert_near(c.unwrap(), (50.0, 50.0), 2e-3);
        // sinumerik-b/08: G2 AR=269.31 X115 Y113.3 from X133 Y44.48, centre X90 Y70. AR is
        // written to 0.01 degree: 0.005 degree is 4.4 um on the radius of 50, and the centre
        // comes out at X90.0019 Y69.9977.
        let c = centre_from_opening(p(133.0, 44.48), p(115.0, 113.3), 269.31, CW, SPAN);
        assert_near(c.unwrap(), (90.0, 70.0), 3e-3);
    }

    #[test]
    fn ar_of_a_half_circle_has_its_centre_in_the_chord_middle() {
        // By hand: from (0,0) to (20,0), 180 degrees either way, the centre is (10,0).
        for direction in [CW, CCW] {
            let c = centre_from_opening(p(0.0, 0.0), p(20.0, 0.0), 180.0, direction, SPAN);
            assert_near(c.unwrap(), (10.0, 0.0), 1e-12);
        }
        // A quarter circle counter-clockwise from (10,0) to (0,10) turns about (0,0): the
        // centre is on the left of the chord, half the chord (7.0711) over tan(45) from the middle.
        let c = centre_from_opening(p(10.0, 0.0), p(0.0, 10.0), 90.0, CCW, SPAN);
        assert_near(c.unwrap(), (0.0, 0.0), 1e-12);
    }

    #[test]
    fn ar_with_centre_gives_the_end_points_of_examples_b16_and_b08() {
        // sinumerik-b/16: G3 I-17.5 J-30.211 AR=140.134 from X67.5 Y80.211 ends at X17.203
        // Y38.029. (The header's X17.2034 Y38.0293 takes the radius 34.913 of the polar form,
        // example b-18; the start is 34.9135 from the centre, which gives X17.20287 Y38.02908.)
        let end = end_from_opening(p(67.5, 80.211), p(50.0, 50.0), 140.134, CCW, SPAN).unwrap();
        assert_near(end, (17.203, 38.029), 5e-4);
        assert_near(end, (17.20287, 38.02908), 1e-5);
        // sinumerik-b/08: G2 AR=269.31 I-43 J25.52 from X133 Y44.48 ends near X115 Y113.3, the
        // end the other forms write. By hand: the start is 50.0027 from the centre at -30.6886
        // degrees; turned 269.31 clockwise it is at 60.0014 degrees: X115.0003 Y113.3042. (The
        // header's X114.999 Y113.302 takes the radius as 50.)
        let end = end_from_opening(p(133.0, 44.48), p(90.0, 70.0), 269.31, CW, SPAN).unwrap();
        assert_near(end, (115.0, 113.3), 5e-3);
        assert_near(end, (115.0003, 113.3042), 1e-4);
    }

    #[test]
    fn ar_outside_0_to_360_or_on_the_start_is_an_alarm() {
        for opening in [0.0, 360.0, -90.0, 400.0, f64::NAN] {
            let end = end_from_opening(p(10.0, 0.0), p(0.0, 0.0), opening, CW, SPAN);
            assert_eq!(
                end.unwrap_err().code,
                AlarmCode::ValueOutOfRange,
                "{opening}"
            );
        }
        let end = end_from_opening(p(10.0, 0.0), p(10.0, 0.0), 90.0, CW, SPAN);
        assert_eq!(end.unwrap_err().code, AlarmCode::ArcWithoutCenter);
        let centre = centre_from_opening(p(1.0, 1.0), p(1.0, 1.0), 90.0, CW, SPAN);
        assert_eq!(centre.unwrap_err().code, AlarmCode::ArcRadiusTooSmall);
    }

    #[test]
    fn ct_arcs_of_example_b22_follow_each_other() {
        // sinumerik-b/22-ct-milling.mpf: line (0,0)->(30,30); CT X50 Y15 is clockwise about
        // (38.9286, 21.0714): n = (-1,1)/sqrt2, d = (20,-15), r = 625 / (2 n.d) = -12.6269.
        let line = Element::Line {
            start: p(0.0, 0.0),
            end: p(30.0, 30.0),
        };
        let first = tangential_arc(p(30.0, 30.0), p(50.0, 15.0), line.end_tangent(), SPAN);
        let Ok(Tangential::Arc { centre, direction }) = first else {
            panic!("{first:?}")
        };
        assert_near(centre, (38.9286, 21.0714), 1e-4);
        assert_eq!(direction, CW);
        // N40 X60 Y-5, still CT: counter-clockwise about (61.9231, 8.4615).
        let arc = Element::Arc {
            start: p(30.0, 30.0),
            end: p(50.0, 15.0),
            center: centre,
            ccw: false,
        };
        let second = tangential_arc(p(50.0, 15.0), p(60.0, -5.0), arc.end_tangent(), SPAN);
        let Ok(Tangential::Arc { centre, direction }) = second else {
            panic!("{second:?}")
        };
        assert_near(centre, (61.9231, 8.4615), 1e-4);
        assert_eq!(direction, CCW);
    }

    #[test]
    fn ct_in_g18_of_example_b23_is_clockwise() {
        // sinumerik-b/23-ct-turning.mpf in (Z, X): line (0, 23.293) -> (-30, 40), CT to
        // (-42, 58.146): centre (-18.504, 60.643), clockwise.
        let tangent = p(-30.0, 40.0 - 23.293);
        let arc = tangential_arc(p(-30.0, 40.0), p(-42.0, 58.146), tangent, SPAN);
        let Ok(Tangential::Arc { centre, direction }) = arc else {
            panic!("{arc:?}")
        };
        assert_near(centre, (-18.504, 60.643), 1e-3);
        assert_eq!(direction, CW);
    }

    #[test]
    fn ct_along_its_tangent_is_a_line_and_behind_it_an_alarm() {
        // L5585-5590: the end on the extension of the start tangent gives a straight line.
        let ahead = tangential_arc(p(0.0, 0.0), p(10.0, 10.0), p(1.0, 1.0), SPAN);
        assert_eq!(ahead, Ok(Tangential::Line));
        let behind = tangential_arc(p(0.0, 0.0), p(-10.0, -10.0), p(1.0, 1.0), SPAN);
        assert_eq!(behind.unwrap_err().code, AlarmCode::ArcWithoutCenter);
        let no_direction = tangential_arc(p(0.0, 0.0), p(5.0, 0.0), V2::default(), SPAN);
        assert_eq!(no_direction.unwrap_err().code, AlarmCode::ArcWithoutCenter);
        let no_chord = tangential_arc(p(1.0, 0.0), p(1.0, 0.0), p(1.0, 0.0), SPAN);
        assert_eq!(no_chord.unwrap_err().code, AlarmCode::ArcRadiusTooSmall);
    }

    /// The CIP circle through `points` (start, intermediate, end), checked against a manual's
    /// centre, radius and swept degrees as its header writes them (to 0.001 mm, 0.01 degree).
    fn assert_manual_circle(
        points: [Point3; 3],
        centre: Point3,
        (radius, sweep): (f64, f64),
    ) -> SpaceCircle {
        let circle = circle_through(points[0], points[1], points[2], SPAN).unwrap();
        assert_near3(circle.centre, centre, 1e-3);
        assert!((circle.radius - radius).abs() < 1e-3, "{circle:?}");
        assert!(
            (circle.sweep.to_degrees() - sweep).abs() < 1e-2,
            "{circle:?}"
        );
        circle
    }

    #[test]
    fn cip_example_b20_is_an_inclined_clockwise_circle() {
        // sinumerik-b/20-cip-milling.mpf: start X130 Y60 Z-2, intermediate X44.65 Y24.65 Z-6,
        // end X80 Y120 Z-10: centre X77.287 Y66.8418 Z-6.4802, R53.344, 265.23 degrees,
        // clockwise seen from +Z.
        let circle = assert_manual_circle(
            [
                [130.0, 60.0, -2.0],
                [44.65, 24.65, -6.0],
                [80.0, 120.0, -10.0],
            ],
            [77.287, 66.8418, -6.4802],
            (53.344, 265.23),
        );
        assert!(circle.normal[2] < 0.0);
        assert_eq!(circle.direction_in(Plane::Xy), None);
        assert_eq!(circle.machine_plane(), None);
        let alarm = circle.inclined_alarm(Plane::Xy, SPAN);
        assert_eq!(alarm.code, AlarmCode::NotSupportedYet);
        assert!(circle.tilt(Plane::Xy) > 1.0, "{}", circle.tilt(Plane::Xy));
    }

    #[test]
    fn cip_alternative_of_example_b08_matches_its_header() {
        // sinumerik-b/08: start X133 Y44.48 Z-5, intermediate X47.65 Y9.13 Z-6, end X80 Y120
        // Z-10: centre X76.1957 Y60.9748 Z-7.4636, R59.202, 257.41 degrees.
        assert_manual_circle(
            [
                [133.0, 44.48, -5.0],
                [47.65, 9.13, -6.0],
                [80.0, 120.0, -10.0],
            ],
            [76.1957, 60.9748, -7.4636],
            (59.202, 257.41),
        );
    }

    #[test]
    fn cip_in_a_machine_plane_is_an_ordinary_arc() {
        // By hand: (10,0,5) -> (0,10,5) -> (-10,0,5) is the upper half of the circle of radius
        // 10 about (0,0,5), counter-clockwise seen from +Z, 180 degrees.
        let circle =
            circle_through([10.0, 0.0, 5.0], [0.0, 10.0, 5.0], [-10.0, 0.0, 5.0], SPAN).unwrap();
        assert_near3(circle.centre, [0.0, 0.0, 5.0], 1e-12);
        assert!((circle.radius - 10.0).abs() < 1e-12);
        assert!((circle.sweep - std::f64::consts::PI).abs() < 1e-12);
        assert_eq!(circle.direction_in(Plane::Xy), Some(CCW));
        assert_eq!(circle.direction_in(Plane::Zx), None);
        // In the Z-X plane (abscissa Z, ordinate X, seen from +Y): X10 Z0 -> X0 Z10 -> X-10 Z0
        // goes from 90 through 0 to -90 degrees: clockwise.
        let circle =
            circle_through([10.0, 2.0, 0.0], [0.0, 2.0, 10.0], [-10.0, 2.0, 0.0], SPAN).unwrap();
        assert_eq!(circle.machine_plane(), Some((Plane::Zx, CW)));
        assert_eq!(circle.direction_in(Plane::Xy), None);
        assert!((circle.tilt(Plane::Xy) - 90.0).abs() < 1e-9);
    }

    #[test]
    fn cip_on_one_line_or_with_coincident_points_is_an_alarm() {
        let line = circle_through([0.0, 0.0, 0.0], [1.0, 1.0, 1.0], [3.0, 3.0, 3.0], SPAN);
        assert_eq!(line.unwrap_err().code, AlarmCode::ArcWithoutCenter);
        let same = circle_through([0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [3.0, 1.0, 0.0], SPAN);
        assert_eq!(same.unwrap_err().code, AlarmCode::ArcWithoutCenter);
        let closed = circle_through([0.0, 0.0, 0.0], [3.0, 1.0, 0.0], [0.0, 0.0, 0.0], SPAN);
        assert_eq!(closed.unwrap_err().code, AlarmCode::ArcWithoutCenter);
    }

    #[test]
    fn turn_is_a_whole_number_up_to_999() {
        // sinumerik-b/24-helix-turn.mpf: TURN=2, two extra full circles.
        assert_eq!(extra_turns(2.0, SPAN), Ok(2));
        assert_eq!(extra_turns(0.0, SPAN), Ok(0));
        assert_eq!(extra_turns(999.0, SPAN), Ok(999));
        for bad in [1.5, -1.0, 1000.0, f64::NAN, f64::INFINITY] {
            assert_eq!(
                extra_turns(bad, SPAN).unwrap_err().code,
                AlarmCode::ValueOutOfRange,
                "{bad}"
            );
        }
    }

    proptest::proptest! {
        #[test]
        fn ct_arcs_pass_through_both_ends_leaving_along_the_tangent(
            sx in -100.0..100.0f64, sy in -100.0..100.0f64,
            ex in -100.0..100.0f64, ey in -100.0..100.0f64,
            heading in 0.0..std::f64::consts::TAU,
        ) {
            let (start, end) = (p(sx, sy), p(ex, ey));
            proptest::prop_assume!(start.distance(end) > 1e-3);
            let tangent = p(heading.cos(), heading.sin());
            let Ok(Tangential::Arc { centre, direction }) =
                tangential_arc(start, end, tangent, SPAN)
            else {
                return Ok(());
            };
            let radius = start.distance(centre);
            proptest::prop_assert!((end.distance(centre) - radius).abs() < 1e-6 * radius.max(1.0));
            let arc = Element::Arc { start, end, center: centre, ccw: direction == CCW };
            proptest::prop_assert!(arc.start_tangent().distance(tangent) < 1e-6);
        }

        #[test]
        fn ar_arcs_sweep_their_opening_between_their_ends(
            sx in -100.0..100.0f64, sy in -100.0..100.0f64,
            ex in -100.0..100.0f64, ey in -100.0..100.0f64,
            opening in 0.5..359.5f64, ccw in proptest::bool::ANY,
        ) {
            let (start, end) = (p(sx, sy), p(ex, ey));
            proptest::prop_assume!(start.distance(end) > 1e-3);
            let direction = if ccw { CCW } else { CW };
            let centre = centre_from_opening(start, end, opening, direction, SPAN).unwrap();
            let radius = start.distance(centre);
            proptest::prop_assert!((end.distance(centre) - radius).abs() < 1e-6 * radius.max(1.0));
            // The centre form of the same arc ends where the end point form started from.
            let back = end_from_opening(start, centre, opening, direction, SPAN).unwrap();
            proptest::prop_assert!(back.distance(end) < 1e-6 * radius.max(1.0), "{back:?}");
        }

        #[test]
        fn cip_circles_pass_through_their_three_points_in_order(
            centre in proptest::array::uniform3(-100.0..100.0f64),
            radius in 1.0..100.0f64,
            tilt in 0.0..3.1f64, spin in 0.0..std::f64::consts::TAU,
            angles in proptest::array::uniform3(0.0..std::f64::consts::TAU),
        ) {
            // A circle of `radius` about `centre` in a plane tilted by `tilt` about an axis
            // turned by `spin`; three points on it at `angles`, taken in increasing angle.
            let mut a = angles;
            a.sort_by(f64::total_cmp);
            proptest::prop_assume!(a[1] - a[0] > 0.05 && a[2] - a[1] > 0.05 && a[2] - a[0] < 6.2);
            let u = [spin.cos(), spin.sin(), 0.0];
            let w = [-spin.sin() * tilt.cos(), spin.cos() * tilt.cos(), tilt.sin()];
            let point = |t: f64| add(centre, add(scale(u, radius * t.cos()), scale(w, radius * t.sin())));
            let circle = circle_through(point(a[0]), point(a[1]), point(a[2]), SPAN).unwrap();
            assert_near3(circle.centre, centre, 1e-6 * radius);
            proptest::prop_assert!((circle.radius - radius).abs() < 1e-6 * radius);
            proptest::prop_assert!((circle.sweep - (a[2] - a[0])).abs() < 1e-6);
            proptest::prop_assert!(dot(circle.normal, cross(u, w)) > 0.999_999);
        }
    }

    #[test]
    fn a_circle_of_kilometres_in_no_machine_plane_alarms() {
        // At 1 µm, a quarter circle of 1 km (1e6 mm) radius takes chords of
        // 2 acos(1 - 1e-9) = 8.944e-5 rad: (pi / 2) / 8.944e-5 = 17,562.4, so 17,563; half a
        // circle of 1000 km takes about 1.1 million: too many.
        let (half, quarter) = (std::f64::consts::PI, std::f64::consts::FRAC_PI_2);
        assert_eq!(chord_count(quarter, 1.0e6, 0.001, SPAN).unwrap(), 17_563);
        let alarm = chord_count(half, 1.0e9, 0.001, SPAN).unwrap_err();
        assert_eq!(alarm.code, AlarmCode::WordNotAllowed);
    }

    #[test]
    fn a_quarter_helix_in_pieces_stays_on_its_circle_and_climbs_evenly() {
        // Quarter circle of radius 10 about the origin, (10,0) to (0,10) counter-clockwise,
        // climbing 0 to 5: every point at radius 10, the height proportional to the angle,
        // the last point exactly the end, chords within 1 µm.
        let points = helix_points(
            V2::new(10.0, 0.0),
            V2::new(0.0, 0.0),
            V2::new(0.0, 10.0),
            (0.0, 5.0),
            ArcDirection::CounterClockwise,
            0,
            0.001,
            SPAN,
        )
        .unwrap();
        let step = 2.0 * (1.0f64 - 0.001 / 10.0).acos();
        assert_eq!(
            points.len(),
            (std::f64::consts::FRAC_PI_2 / step).ceil() as usize
        );
        for &(p, h) in &points {
            assert!((p.length() - 10.0).abs() < 1e-9, "{p:?}");
            let angle = p.y.atan2(p.x);
            assert!((h - 5.0 * angle / std::f64::consts::FRAC_PI_2).abs() < 1e-9);
        }
        assert_eq!(points.last().copied(), Some((V2::new(0.0, 10.0), 5.0)));
    }

    #[test]
    fn a_clockwise_full_circle_with_a_turn_goes_round_twice_the_other_way() {
        // End on the start, G2, TURN=1: two turns clockwise, so the first piece goes to negative
        // y from (10,0), and the points pass (0,-10) twice.
        let points = helix_points(
            V2::new(10.0, 0.0),
            V2::new(0.0, 0.0),
            V2::new(10.0, 0.0),
            (0.0, 0.0),
            ArcDirection::Clockwise,
            1,
            0.01,
            SPAN,
        )
        .unwrap();
        assert!(points[0].0.y < 0.0);
        let near_bottom = points
            .windows(2)
            .filter(|w| w[0].0.x > 0.0 && w[1].0.x <= 0.0 && w[1].0.y < 0.0)
            .count();
        assert_eq!(near_bottom, 2);
    }
}
