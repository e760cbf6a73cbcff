//! Arc geometry: the centre of a G02/G03 from I J K or from R, checked as the control checks it.

use crate::alarm::{Alarm, AlarmCode};
use crate::motion::{ArcDirection, Plane};
use crate::source::Span;

/// How the arc was programmed, in machine mm.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum ArcSpec {
    /// Centre offsets from the start along the plane's first and second axes.
    Center { offset: (f64, f64), span: Span },
    /// Signed radius: negative for more than 180 degrees.
    Radius { radius: f64, span: Span },
}

/// The centre of an arc in the plane's (first, second) coordinates.
///
/// `start` and `end` are the plane coordinates of the arc's ends; `tolerance` is the largest
/// accepted difference between start and end radius (FANUC parameter 3410).
///
/// # Errors
/// [`AlarmCode::ArcEndNotOnCircle`] when the end is not on the circle of the centre form,
/// [`AlarmCode::ArcRadiusTooSmall`] when R is shorter than half the chord.
pub(crate) fn arc_center(
    start: (f64, f64),
    end: (f64, f64),
    spec: ArcSpec,
    direction: ArcDirection,
    tolerance: f64,
) -> Result<(f64, f64), Alarm> {
    let (clean, span) = match spec {
        ArcSpec::Center { offset, span } => (CleanSpec::Center(offset), span),
        ArcSpec::Radius { radius, span } => (CleanSpec::Radius(radius), span),
    };
    clean_arc_center(start, end, clean, direction, tolerance)
        .ok_or_else(|| refused_arc(start, end, clean, span, tolerance))
}

/// The alarm of an arc [`clean_arc_center`] refuses, its tests asked again in the same order.
#[cold]
fn refused_arc(
    start: (f64, f64),
    end: (f64, f64),
    spec: CleanSpec,
    span: Span,
    tolerance: f64,
) -> Alarm {
    match spec {
        CleanSpec::Center(offset) => {
            if offset == (0.0, 0.0) {
                return Alarm::error(
                    AlarmCode::ArcWithoutCenter,
                    span,
                    "arc centre is on its start point",
                );
            }
            let (_, r_start, r_end) = centre_form(start, end, offset);
            Alarm::error(
                AlarmCode::ArcEndNotOnCircle,
                span,
                format!(
                    "arc end point is not on the circle: radius {:.4} at the start, {:.4} at the end",
                    r_start, r_end
                ),
            )
            .with_help(format!(
                "the control accepts a difference of {tolerance} mm (FANUC alarm 020)"
            ))
        }
        CleanSpec::Radius(radius) => {
            let (chord, _) = radius_form(start, end, radius);
            if chord == 0.0 {
                return Alarm::error(
                    AlarmCode::ArcRadiusTooSmall,
                    span,
                    "an R arc needs an end point different from its start",
                )
                .with_help("program a full circle with I, J or K");
            }
            let (r, half) = (radius.abs(), chord / 2.0);
            Alarm::error(
                AlarmCode::ArcRadiusTooSmall,
                span,
                format!("R{r:.4} is smaller than half the distance to the end point ({half:.4})"),
            )
        }
    }
}

/// The centre of an arc the control takes, `None` where it refuses the arc: [`arc_center`]
/// without the alarm, which the common arc's path (`circular::plain_arc`) then asks of it. One
/// computation for both paths, so the same bits.
#[inline]
pub(crate) fn clean_arc_center(
    start: (f64, f64),
    end: (f64, f64),
    spec: CleanSpec,
    direction: ArcDirection,
    tolerance: f64,
) -> Option<(f64, f64)> {
    match spec {
        CleanSpec::Center(offset) => {
            let (center, r_start, r_end) = centre_form(start, end, offset);
            // The tests of `arc_center`, so that a NaN radius passes as it does there.
            if offset == (0.0, 0.0) || (r_end - r_start).abs() > tolerance {
                return None;
            }
            Some(center)
        }
        CleanSpec::Radius(radius) => {
            let (chord, h2) = radius_form(start, end, radius);
            if chord == 0.0 {
                return None;
            }
            let h2 = short_radius_settled(chord, h2, radius, tolerance)?;
            Some(radius_centre(start, end, chord, h2, radius, direction))
        }
    }
}

/// How the common arc was programmed: [`ArcSpec`] without the span its alarms would need.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum CleanSpec {
    /// Centre offsets from the start along the plane's first and second axes.
    Center((f64, f64)),
    /// Signed radius: negative for more than 180 degrees.
    Radius(f64),
}

/// The centre of the centre form, and its radius at the start and at the end.
#[inline]
fn centre_form(start: (f64, f64), end: (f64, f64), offset: (f64, f64)) -> ((f64, f64), f64, f64) {
    let center = (start.0 + offset.0, start.1 + offset.1);
    let r_start = length_of(offset);
    let r_end = length_of((end.0 - center.0, end.1 - center.1));
    (center, r_start, r_end)
}

/// The chord of an R arc and the square of the centre's distance from the chord's middle
/// (negative when R is shorter than half the chord).
#[inline]
fn radius_form(start: (f64, f64), end: (f64, f64), radius: f64) -> (f64, f64) {
    let (dx, dy) = (end.0 - start.0, end.1 - start.1);
    let chord = dx.hypot(dy);
    let r = radius.abs();
    let half = chord / 2.0;
    (chord, r * r - half * half)
}

/// `h2` of an R arc (see [`radius_form`]) as the centre is computed from it: a radius short by
/// rounding only (R written to fewer decimals than the end point) is taken as a half circle, as
/// the controls do within their tolerance; `None` when R is shorter than that.
#[inline]
fn short_radius_settled(chord: f64, h2: f64, radius: f64, tolerance: f64) -> Option<f64> {
    if h2 >= 0.0 || h2.is_nan() {
        return Some(h2);
    }
    if chord / 2.0 - radius.abs() > tolerance {
        return None;
    }
    Some(0.0)
}

/// The centre of an R arc from its chord and `h2` (see [`radius_form`], not negative).
#[inline]
fn radius_centre(
    start: (f64, f64),
    end: (f64, f64),
    chord: f64,
    h2: f64,
    radius: f64,
    direction: ArcDirection,
) -> (f64, f64) {
    let (dx, dy) = (end.0 - start.0, end.1 - start.1);
    let h = h2.sqrt();
    let mid = (start.0 + dx / 2.0, start.1 + dy / 2.0);
    // Unit normal to the chord, to the left of the travel direction.
    let left = (-dy / chord, dx / chord);
    // Counter-clockwise arcs of less than 180 degrees have their centre on the left.
    let mut side = match direction {
        ArcDirection::CounterClockwise => 1.0,
        ArcDirection::Clockwise => -1.0,
    };
    if radius < 0.0 {
        side = -side;
    }
    (mid.0 + side * h * left.0, mid.1 + side * h * left.1)
}

/// The length of a vector in the plane, for the radius check of the centre form: the square
/// root of the sum of squares, not `hypot`, which costs several times more. The check compares
/// two radii with a tolerance of micrometres: a difference of a few units in the last place
/// does not matter there (and positions stay far below where the squares would overflow).
#[allow(clippy::imprecise_flops)]
#[inline]
fn length_of((x, y): (f64, f64)) -> f64 {
    (x * x + y * y).sqrt()
}

/// Plane coordinates (first, second) of a position.
pub(crate) fn in_plane(plane: Plane, p: &[f64]) -> (f64, f64) {
    let (a, b, _) = plane.axes();
    (p[a], p[b])
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const SPAN: Span = Span {
        file: crate::source::FileId(0),
        start: 0,
        end: 0,
        line: 1,
    };

    fn radius(r: f64) -> ArcSpec {
        ArcSpec::Radius {
            radius: r,
            span: SPAN,
        }
    }

    #[test]
    fn positive_r_is_the_short_way_and_negative_r_the_long_way() {
        let ccw = ArcDirection::CounterClockwise;
        let c = arc_center((10.0, 0.0), (0.0, 10.0), radius(10.0), ccw, 0.01).unwrap();
        assert!((c.0).abs() < 1e-12 && (c.1).abs() < 1e-12);
        let c = arc_center((10.0, 0.0), (0.0, 10.0), radius(-10.0), ccw, 0.01).unwrap();
        assert!((c.0 - 10.0).abs() < 1e-12 && (c.1 - 10.0).abs() < 1e-12);
    }

    #[test]
    fn mitsubishi_r_example_centre_matches_the_manual() {
        // spec/iso-fanuc0m-mitsubishi.md B.3: from X30 Y10 to X5 Y25 with R20.616 the centre is
        // X9.9997 Y4.9994.
        let c = arc_center(
            (30.0, 10.0),
            (5.0, 25.0),
            radius(20.616),
            ArcDirection::CounterClockwise,
            0.01,
        )
        .unwrap();
        assert!(
            (c.0 - 9.9997).abs() < 1e-3 && (c.1 - 4.9994).abs() < 1e-3,
            "{c:?}"
        );
    }

    #[test]
    fn end_point_off_the_circle_is_alarm_020() {
        let spec = ArcSpec::Center {
            offset: (10.0, 0.0),
            span: SPAN,
        };
        let error = arc_center(
            (0.0, 0.0),
            (10.0, 10.5),
            spec,
            ArcDirection::Clockwise,
            0.01,
        )
        .unwrap_err();
        assert_eq!(error.code, AlarmCode::ArcEndNotOnCircle);
    }

    #[test]
    fn only_a_centre_offset_of_zero_is_on_the_start_point() {
        let center = |offset| ArcSpec::Center { offset, span: SPAN };
        let cw = ArcDirection::Clockwise;
        let error = arc_center((1.0, 1.0), (1.0, 1.0), center((0.0, -0.0)), cw, 0.01);
        assert_eq!(error.unwrap_err().code, AlarmCode::ArcWithoutCenter);
        // The squares of this offset are below what a double holds: its length is not zero.
        let tiny = arc_center((0.0, 0.0), (0.0, 0.0), center((1e-170, 0.0)), cw, 0.01);
        assert!(tiny.is_ok(), "{tiny:?}");
    }

    proptest! {
        #[test]
        fn the_centre_form_accepts_what_the_exact_radii_accept(
            sx in -500.0..500.0f64, sy in -500.0..500.0f64,
            ox in -50.0..50.0f64, oy in -50.0..50.0f64,
            turn in 0.0..6.3f64, stretch in -0.02..0.02f64,
        ) {
            let tolerance = 0.01;
            let radius = ox.hypot(oy);
            prop_assume!(radius > 1e-3);
            let center = (sx + ox, sy + oy);
            let end_radius = radius + stretch;
            let end = (center.0 + end_radius * turn.cos(), center.1 + end_radius * turn.sin());
            let exact = ((end.0 - center.0).hypot(end.1 - center.1) - radius).abs();
            // Within a nanometre of the tolerance the two may round differently.
            prop_assume!((exact - tolerance).abs() > 1e-9);
            let spec = ArcSpec::Center { offset: (ox, oy), span: SPAN };
            let got = arc_center((sx, sy), end, spec, ArcDirection::Clockwise, tolerance);
            prop_assert_eq!(got.is_ok(), exact <= tolerance, "{:?}", got);
        }
    }

    #[test]
    fn radius_too_small_is_an_alarm() {
        let error = arc_center(
            (0.0, 0.0),
            (30.0, 0.0),
            radius(10.0),
            ArcDirection::Clockwise,
            0.01,
        )
        .unwrap_err();
        assert_eq!(error.code, AlarmCode::ArcRadiusTooSmall);
    }

    proptest! {
        #[test]
        fn r_arc_centres_are_at_r_from_both_ends(
            sx in -500.0..500.0f64, sy in -500.0..500.0f64,
            ex in -500.0..500.0f64, ey in -500.0..500.0f64,
            extra in 0.0..300.0f64, long in any::<bool>(), cw in any::<bool>(),
        ) {
            let chord = (ex - sx).hypot(ey - sy);
            prop_assume!(chord > 1e-3);
            let r = chord / 2.0 + extra;
            let r = if long { -r } else { r };
            let direction = if cw { ArcDirection::Clockwise } else { ArcDirection::CounterClockwise };
            let c = arc_center((sx, sy), (ex, ey), radius(r), direction, 0.01).unwrap();
            let r_start = (sx - c.0).hypot(sy - c.1);
            let r_end = (ex - c.0).hypot(ey - c.1);
            prop_assert!((r_start - r.abs()).abs() < 1e-6 * r.abs().max(1.0));
            prop_assert!((r_end - r.abs()).abs() < 1e-6 * r.abs().max(1.0));
            // The swept angle is at most 180 degrees for positive R, at least 180 for negative R.
            let a0 = (sy - c.1).atan2(sx - c.0);
            let a1 = (ey - c.1).atan2(ex - c.0);
            let mut sweep = if cw { a0 - a1 } else { a1 - a0 };
            while sweep <= 0.0 { sweep += std::f64::consts::TAU; }
            let pi = std::f64::consts::PI;
            if long { prop_assert!(sweep >= pi - 1e-6); } else { prop_assert!(sweep <= pi + 1e-6); }
        }
    }
    /// The centre [`clean_arc_center`] gives, bit for bit, and whether it gives one, against
    /// [`arc_center`].
    fn assert_clean_centre_agrees(
        start: (f64, f64),
        end: (f64, f64),
        spec: ArcSpec,
        direction: ArcDirection,
        tolerance: f64,
    ) -> Result<(), TestCaseError> {
        let clean = match spec {
            ArcSpec::Center { offset, .. } => CleanSpec::Center(offset),
            ArcSpec::Radius { radius, .. } => CleanSpec::Radius(radius),
        };
        let general = arc_center(start, end, spec, direction, tolerance);
        let fast = clean_arc_center(start, end, clean, direction, tolerance);
        let bits = |(x, y): (f64, f64)| (x.to_bits(), y.to_bits());
        prop_assert_eq!(
            fast.map(bits),
            general.ok().map(bits),
            "{:?} {:?} {:?}",
            start,
            end,
            spec
        );
        Ok(())
    }

    proptest! {
        #[test]
        fn the_clean_centre_is_the_general_one_to_the_bit(
            sx in -500.0..500.0f64, sy in -500.0..500.0f64,
            ox in -50.0..50.0f64, oy in -50.0..50.0f64,
            turn in 0.0..6.3f64, stretch in -0.02..0.02f64,
            r_extra in prop_oneof![-0.03..0.0f64, 0.0..30.0f64], long in any::<bool>(), cw in any::<bool>(),
            zero in 0..8u8,
        ) {
            let direction = if cw { ArcDirection::Clockwise } else { ArcDirection::CounterClockwise };
            // Now and then an offset or a chord of zero, where both refuse the arc.
            let (ox, oy) = if zero == 0 { (0.0, 0.0) } else { (ox, oy) };
            let radius = ox.hypot(oy);
            let center = (sx + ox, sy + oy);
            let end = (
                center.0 + (radius + stretch) * turn.cos(),
                center.1 + (radius + stretch) * turn.sin(),
            );
            let spec = ArcSpec::Center { offset: (ox, oy), span: SPAN };
            assert_clean_centre_agrees((sx, sy), end, spec, direction, 0.01)?;
            // R from half the chord on: radii short by less and by more than the tolerance,
            // half circles, and every other arc.
            let end = if zero == 1 { (sx, sy) } else { end };
            let half = (end.0 - sx).hypot(end.1 - sy) / 2.0;
            let r = half + r_extra;
            let spec = ArcSpec::Radius { radius: if long { -r } else { r }, span: SPAN };
            assert_clean_centre_agrees((sx, sy), end, spec, direction, 0.01)?;
            let spec = ArcSpec::Radius { radius: half, span: SPAN };
            assert_clean_centre_agrees((sx, sy), end, spec, direction, 0.01)?;
        }
    }
}
