//! Involute interpolation, INVCW and INVCCW (PGsl 9.8, manual L5718-5830): the path traced by
//! the end of a taut string unwound from a base circle (centre I J K from the start point, radius
//! CR=), to an end point given in the plane's axes or by the opening angle AR=.
//!
//! An involute of the base circle (centre C, radius r) is, for the roll parameter t >= 0,
//! `P(t) = C + r (cos(a + s t) + s t sin(a + s t), sin(a + s t) - s t cos(a + s t))`: at
//! distance `r sqrt(1 + t^2)` from C, at polar angle `a + s (t - atan t)`. With s = +1 the polar
//! angle grows as the string unwinds; with s = -1 it falls. Which of the two a block follows is
//! given by its direction and whether it moves away from the base circle or towards it:
//! counter-clockwise away and clockwise towards is s = +1, the other two s = -1.
//!
//! An end point that is not exactly on the involute through the start point is reached by moving
//! between the two involutes through the start and the end (the angle `a` passes from the one to
//! the other along the path), as the manual says; more than [`RADIAL_TOLERANCE`] off in the
//! radial direction is an alarm.
//!
//! Never: enter the base circle, or guess an end point: start and end outside the circle, and
//! either the end point or AR=, are alarms otherwise.

use crate::alarm::{Alarm, AlarmCode};
use crate::interp::comp::geometry::V2;
use crate::source::Span;

/// How far the programmed end point may be from the involute through the start point, radially
/// (mm): the control's machine data MD21015 INVOLUTE_RADIUS_DELTA, whose default this is.
pub(super) const RADIAL_TOLERANCE: f64 = 0.01;

/// The most straight pieces one involute block is cut into.
const MOST_PIECES: f64 = 100_000.0;

/// The involute of one block, in the plane's coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Involute {
    centre: V2,
    radius: f64,
    /// +1: the polar angle grows with the roll parameter; -1: it falls.
    sense: f64,
    /// The roll parameter and the angle `a` at the start and at the end.
    t0: f64,
    t1: f64,
    a0: f64,
    a1: f64,
}

/// How the block gives its end.
#[derive(Clone, Copy, Debug)]
pub(super) enum End {
    /// The end point in the plane.
    Point(V2),
    /// AR=, degrees: the change of the polar angle about the centre; positive away from the base
    /// circle, negative towards it.
    Opening(f64),
}

/// `t - atan t`: how far the polar angle has turned at roll parameter `t`.
fn turned(t: f64) -> f64 {
    t - t.atan()
}

/// The roll parameter of a point at `distance` from the centre of a base circle of `radius`.
fn roll(distance: f64, radius: f64) -> f64 {
    ((distance / radius).powi(2) - 1.0).max(0.0).sqrt()
}

/// The roll parameter t >= 0 with `turned(t) == target` (target >= 0), by Newton's method from
/// above (turned is convex for t > 0, so the steps fall monotonically onto the root).
fn roll_for_turn(target: f64) -> f64 {
    // turned(t) >= t - pi/2: the root is below target + pi/2.
    let mut t = target + std::f64::consts::FRAC_PI_2;
    for _ in 0..100 {
        let slope = t * t / (1.0 + t * t);
        if slope <= 0.0 {
            break;
        }
        let step = (turned(t) - target) / slope;
        t -= step;
        if step.abs() <= 1e-13 * t.max(1.0) {
            break;
        }
    }
    t.max(0.0)
}

/// `angle` brought into (-pi, pi].
fn wrapped(angle: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    let a = angle.rem_euclid(TAU);
    if a > PI {
        a - TAU
    } else {
        a
    }
}

impl Involute {
    /// The involute from `start` about the base circle (`centre`, `radius`) to `end`, turning
    /// counter-clockwise when `ccw`.
    ///
    /// # Errors
    /// A radius that is not positive, a start or end point on or inside the base circle, an
    /// opening angle that would enter it, an end point off the involute by more than
    /// [`RADIAL_TOLERANCE`] or on the start's radius, each at `span`.
    pub(super) fn new(
        start: V2,
        centre: V2,
        radius: f64,
        end: End,
        ccw: bool,
        span: Span,
    ) -> Result<Involute, Alarm> {
        if !(radius > 0.0 && radius.is_finite()) {
            return Err(Alarm::error(
                AlarmCode::ArcWithoutCenter,
                span,
                format!("an involute needs the base circle's radius CR= above 0, not {radius}"),
            ));
        }
        let inside = |point: V2, what: &str| {
            Alarm::error(
                AlarmCode::ArcEndNotOnCircle,
                span,
                format!(
                    "the involute's {what} ({:.3}, {:.3}) is not outside its base circle \
                     (centre ({:.3}, {:.3}), radius {radius:.3})",
                    point.x, point.y, centre.x, centre.y
                ),
            )
            .with_help("start and end of an involute lie outside the base circle (PGsl 9.8)")
        };
        let from_centre = start - centre;
        if from_centre.length() <= radius {
            return Err(inside(start, "start point"));
        }
        let t0 = roll(from_centre.length(), radius);
        let polar0 = from_centre.y.atan2(from_centre.x);
        let (sense, t1, a1) = match end {
            End::Point(point) => {
                let to_end = point - centre;
                let distance = to_end.length();
                if distance <= radius {
                    return Err(inside(point, "end point"));
                }
                let t1 = roll(distance, radius);
                if (t1 - t0).abs() <= 1e-12 {
                    return Err(Alarm::error(
                        AlarmCode::ArcEndNotOnCircle,
                        span,
                        "the involute's end point is as far from the base circle's centre as its \
                         start: no involute joins them",
                    ));
                }
                let away = t1 > t0;
                let sense = if ccw == away { 1.0 } else { -1.0 };
                let a0 = polar0 - sense * turned(t0);
                let polar1 = to_end.y.atan2(to_end.x);
                let a1 = a0 + wrapped(polar1 - sense * turned(t1) - a0);
                // The radius the involute through the start has where the end point lies differs
                // by the polar gap times dR/dtheta = r sqrt(1 + t^2) / t.
                let deviation = (a1 - a0).abs() * radius * (1.0 + t1 * t1).sqrt() / t1.max(1e-9);
                if deviation > RADIAL_TOLERANCE {
                    return Err(Alarm::error(
                        AlarmCode::ArcEndNotOnCircle,
                        span,
                        format!(
                            "the end point is {deviation:.4} mm off the involute through the \
                             start point (at most {RADIAL_TOLERANCE} mm)"
                        ),
                    )
                    .with_help("check the end point, the base circle's centre I J K and CR="));
                }
                (sense, t1, a1)
            }
            End::Opening(degrees) => {
                let away = degrees >= 0.0;
                let sense = if ccw == away { 1.0 } else { -1.0 };
                let turn = degrees.abs().to_radians();
                let target = if away {
                    turned(t0) + turn
                } else {
                    turned(t0) - turn
                };
                if target <= 0.0 {
                    return Err(Alarm::error(
                        AlarmCode::ArcEndNotOnCircle,
                        span,
                        format!(
                            "AR={degrees} turns the involute into its base circle: towards it, \
                             at most {:.3} degrees from this start",
                            turned(t0).to_degrees()
                        ),
                    ));
                }
                (sense, roll_for_turn(target), polar0 - sense * turned(t0))
            }
        };
        Ok(Involute {
            centre,
            radius,
            sense,
            t0,
            t1,
            a0: polar0 - sense * turned(t0),
            a1,
        })
    }

    /// The point at `u` of the way (0 the start, 1 the end).
    pub(super) fn point(&self, u: f64) -> V2 {
        let t = self.t0 + u * (self.t1 - self.t0);
        let a = self.a0 + u * (self.a1 - self.a0);
        let phase = a + self.sense * t;
        let (sin, cos) = phase.sin_cos();
        let s = self.sense;
        self.centre + V2::new(cos + s * t * sin, sin - s * t * cos) * self.radius
    }

    /// The end point.
    pub(super) fn end(&self) -> V2 {
        self.point(1.0)
    }

    /// The unit direction of travel at the end.
    pub(super) fn end_tangent(&self) -> V2 {
        // dP/dt = r t (cos(a + s t), sin(a + s t)); the path runs towards falling t when the
        // block moves towards the base circle.
        let phase = self.a1 + self.sense * self.t1;
        let along = if self.t1 > self.t0 { 1.0 } else { -1.0 };
        V2::new(phase.cos(), phase.sin()) * along
    }

    /// How many straight pieces keep the path within `tolerance` (mm).
    ///
    /// # Errors
    /// More than [`MOST_PIECES`], at `span`.
    pub(super) fn pieces(&self, tolerance: f64, span: Span) -> Result<usize, Alarm> {
        // The path's radius of curvature is r t, its direction turns by dt (and the drift of
        // `a`): a chord over a turn d at curvature radius R strays R d^2 / 8.
        let widest = self.radius * self.t0.max(self.t1);
        let turn = (self.t1 - self.t0).abs() + (self.a1 - self.a0).abs();
        let step = (8.0 * tolerance / widest.max(1e-9)).sqrt();
        let pieces = (turn / step).ceil().max(1.0);
        if pieces > MOST_PIECES || pieces.is_nan() {
            return Err(Alarm::error(
                AlarmCode::WordNotAllowed,
                span,
                format!(
                    "this involute would take {pieces} straight pieces within {tolerance} mm; \
                     vcnc stops at {MOST_PIECES} a block"
                ),
            )
            .with_help(
                "check CR= and the end point: a base circle of micrometres is a typing error",
            ));
        }
        Ok(pieces as usize)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::source::FileId;

    const SPAN: Span = Span {
        file: FileId(0),
        line: 1,
        start: 0,
        end: 0,
    };

    fn close(a: V2, b: V2, tolerance: f64) -> bool {
        (a - b).length() <= tolerance
    }

    /// Manual example 1 (b/25): base circle (0,0) r 5, from (10,0) counter-clockwise out to
    /// (32.77, 32.77). Start distance 10: t0 = sqrt(4 - 1) = sqrt 3. End distance 46.3437:
    /// t1 = sqrt((46.3437/5)^2 - 1) = 9.2147. The involute through the start reaches that
    /// distance at polar angle a0 + t1 - atan t1 with a0 = -(sqrt 3 - pi/3) = -0.68485:
    /// 9.2147 - 1.46268 - 0.68485 = 7.06717 rad = 44.915 degrees (mod 360), 0.085 degrees short
    /// of the programmed 45: 0.00148 rad * 46.3437 / 9.2147 = 0.0075 mm radially, inside 0.01.
    #[test]
    fn the_manuals_first_example_reaches_its_end_within_the_tolerance() {
        let start = V2::new(10.0, 0.0);
        let end = V2::new(32.77, 32.77);
        let inv = Involute::new(start, V2::default(), 5.0, End::Point(end), true, SPAN).unwrap();
        assert!((inv.t0 - 3f64.sqrt()).abs() < 1e-12);
        assert!((inv.t1 - 9.2147).abs() < 1e-4, "{}", inv.t1);
        assert!(close(inv.point(0.0), start, 1e-9));
        assert!(close(inv.end(), end, 1e-9));
        // Halfway in t and a, the point is at r sqrt(1 + t^2) from the centre.
        let t = (inv.t0 + inv.t1) / 2.0;
        assert!((inv.point(0.5).length() - 5.0 * (1.0 + t * t).sqrt()).abs() < 1e-9);
        // The way back (N30, clockwise towards the circle) retraces it.
        let back = Involute::new(end, V2::default(), 5.0, End::Point(start), false, SPAN).unwrap();
        assert_eq!(back.sense, 1.0);
        assert!(close(back.point(0.3), inv.point(0.7), 1e-3));
        assert!(close(back.end(), start, 1e-9));
    }

    /// Manual example 2 (b/26): from (10,0) about (0,0) r 5, AR=360 counter-clockwise away:
    /// the polar angle turns once, so t - atan t grows by 2 pi from sqrt 3 - pi/3 = 0.684853 to
    /// 6.968038: t1 = 8.42063 (8.42063 - atan 8.42063 = 8.42063 - 1.45260), at distance
    /// 5 sqrt(1 + t1^2) = 42.399 on the start's ray: (42.399, 0).
    #[test]
    fn an_opening_angle_of_a_full_turn_ends_on_the_starts_ray() {
        let inv = Involute::new(
            V2::new(10.0, 0.0),
            V2::default(),
            5.0,
            End::Opening(360.0),
            true,
            SPAN,
        )
        .unwrap();
        let end = inv.end();
        assert!(
            (end.x - 42.399).abs() < 1e-3 && end.y.abs() < 1e-9,
            "{end:?}"
        );
        // Half way round the polar angle is past 90 degrees: the path turned counter-clockwise.
        assert!(inv.point(0.5).y > 0.0);
    }

    #[test]
    fn an_end_off_the_involute_or_inside_the_circle_is_an_alarm() {
        let start = V2::new(10.0, 0.0);
        let c = V2::default();
        let off = Involute::new(start, c, 5.0, End::Point(V2::new(32.0, 33.5)), true, SPAN);
        assert_eq!(off.unwrap_err().code, AlarmCode::ArcEndNotOnCircle);
        let inside = Involute::new(start, c, 5.0, End::Point(V2::new(1.0, 1.0)), true, SPAN);
        assert_eq!(inside.unwrap_err().code, AlarmCode::ArcEndNotOnCircle);
        let from_inside = Involute::new(V2::new(2.0, 0.0), c, 5.0, End::Opening(90.0), true, SPAN);
        assert_eq!(from_inside.unwrap_err().code, AlarmCode::ArcEndNotOnCircle);
        // Towards the circle by more than the start has turned: t - atan t = 0.6849 rad = 39.2
        // degrees at the start.
        let too_far = Involute::new(start, c, 5.0, End::Opening(-40.0), true, SPAN);
        assert_eq!(too_far.unwrap_err().code, AlarmCode::ArcEndNotOnCircle);
        let fine = Involute::new(start, c, 5.0, End::Opening(-39.0), true, SPAN).unwrap();
        assert!(fine.end().length() > 5.0 && fine.end().length() < 10.0);
        let no_radius = Involute::new(start, c, 0.0, End::Opening(90.0), true, SPAN);
        assert_eq!(no_radius.unwrap_err().code, AlarmCode::ArcWithoutCenter);
    }

    proptest::proptest! {
        /// Every point of an opening-angle involute lies on the involute of the base circle
        /// through the start (distance r sqrt(1 + t^2) at polar angle a0 + s (t - atan t)), and
        /// the pieces keep the path within the tolerance at their middles.
        #[test]
        fn opening_angle_paths_stay_on_their_involute(
            r in 0.5f64..20.0,
            out in 1.05f64..6.0,
            angle0 in -3.1f64..3.1,
            degrees in -30.0f64..720.0,
            ccw: bool,
        ) {
            let start = V2::new(angle0.cos(), angle0.sin()) * (r * out);
            let Ok(inv) = Involute::new(start, V2::default(), r, End::Opening(degrees), ccw, SPAN)
            else {
                return Ok(());
            };
            for k in 0..=20 {
                let u = f64::from(k) / 20.0;
                let t = inv.t0 + u * (inv.t1 - inv.t0);
                let p = inv.point(u);
                proptest::prop_assert!((p.length() - r * (1.0 + t * t).sqrt()).abs() < 1e-9);
                let polar = inv.a0 + inv.sense * turned(t);
                proptest::prop_assert!(wrapped(p.y.atan2(p.x) - polar).abs() < 1e-9);
            }
            let pieces = inv.pieces(0.001, SPAN).unwrap();
            for k in 0..pieces {
                let (u0, u1) = (k as f64 / pieces as f64, (k + 1) as f64 / pieces as f64);
                let (p0, p1) = (inv.point(u0), inv.point(u1));
                let along = (p1 - p0).unit();
                // Points of the path inside the piece, measured square to its chord.
                for j in 1..4 {
                    let q = inv.point(u0 + (u1 - u0) * f64::from(j) / 4.0) - p0;
                    let off = (q.x * along.y - q.y * along.x).abs();
                    proptest::prop_assert!(off <= 0.0011, "piece {} of {}: {}", k, pieces, off);
                }
            }
        }
    }
}
