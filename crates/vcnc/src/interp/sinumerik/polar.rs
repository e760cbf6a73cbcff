//! Polar coordinates of the SINUMERIK front end: the pole of G110/G111/G112 and the end points
//! of `AP= RP=` blocks, with the angle and radius the control stores between blocks
//! (docs/SINUMERIK.md 6.5; PGsl 9.3, L4873-5002).
//!
//! [`Polar`] holds the pole (work coordinates, X Y Z) and the stored AP and RP; the front end
//! owns one, feeds it the words as written (AC/IC and G90/G91 already told apart, inch already
//! converted) and gets plane coordinates back. It never moves anything and never reads a block.
//! Invariants: the stored radius is positive when present; a new pole or a plane change clears
//! what is stored.
#![cfg_attr(not(test), allow(dead_code))] // wired in by the front end (issue 20)

use super::arcs::Point3;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::comp::geometry::V2;
use crate::interp::modal::DistanceMode;
use crate::motion::Plane;
use crate::source::Span;

/// Radii below this are zero, in mm: far below the control's least increment.
const EPSILON: f64 = 1e-9;

/// An `AP=` or `RP=` value as written.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum PolarValue {
    /// `AP=18`: absolute or incremental as G90/G91 say (for AP; RP is always absolute).
    Plain(f64),
    /// `AP=AC(18)`.
    Absolute(f64),
    /// `AP=IC(72)`: added to the stored value.
    Incremental(f64),
}

/// What a pole instruction measures from (PGsl 9.3.1, L4883-4890).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum PoleReference {
    /// G110: the last programmed point, work coordinates.
    LastPoint(Point3),
    /// G111: the zero of the work coordinate system.
    WorkZero,
    /// G112: the pole in force.
    LastPole,
}

/// How a pole instruction gives the pole, from its reference; G90/G91 do not apply (L4880).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum PoleDefinition {
    /// `X.. Y.. Z..`: the offsets from the reference written; an axis not written keeps the
    /// reference's value.
    Cartesian([Option<f64>; 3]),
    /// `AP=.. RP=..` in the working plane, degrees and mm.
    Polar { angle: f64, radius: f64 },
}

/// The kind of move a polar end point is for: a circle about the pole needs a radius.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum PolarMove {
    /// G0 or G1.
    Line,
    /// G2 or G3: the pole is the centre (PGsl 9.6.5).
    Circle,
}

/// A block with polar end coordinates, as the front end has read it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PolarBlock {
    pub(crate) plane: Plane,
    /// Where the move starts, work coordinates (X, Y, Z).
    pub(crate) start: Point3,
    /// `AP=`, if written.
    pub(crate) angle: Option<PolarValue>,
    /// `RP=`, if written.
    pub(crate) radius: Option<PolarValue>,
    /// G90 or G91 in force.
    pub(crate) distance: DistanceMode,
    pub(crate) motion: PolarMove,
    /// The block, for alarms.
    pub(crate) span: Span,
}

/// The pole and the stored polar angle and radius.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub(crate) struct Polar {
    /// Work coordinates (X, Y, Z). Kept as numbers: a later frame change does not move it
    /// (docs/SINUMERIK.md 6.5, choice).
    pole: Point3,
    /// The last AP, degrees.
    angle: Option<f64>,
    /// The last RP, mm, positive.
    radius: Option<f64>,
}

impl Polar {
    /// No pole programmed: the work zero is the pole (L4917), nothing stored.
    pub(crate) fn new() -> Polar {
        Polar::default()
    }

    /// The pole, work coordinates (X, Y, Z).
    pub(crate) fn pole(&self) -> Point3 {
        self.pole
    }

    /// The pole in `plane`'s (abscissa, ordinate).
    pub(crate) fn pole_in(&self, plane: Plane) -> V2 {
        in_plane(plane, self.pole)
    }

    /// G110/G111/G112: a new pole, in force until the program ends (L4911-4913). It clears the
    /// stored angle and radius (docs/SINUMERIK.md 6.5).
    pub(crate) fn set_pole(
        &mut self,
        reference: PoleReference,
        definition: PoleDefinition,
        plane: Plane,
    ) {
        let base = match reference {
            PoleReference::LastPoint(point) => point,
            PoleReference::WorkZero => [0.0; 3],
            PoleReference::LastPole => self.pole,
        };
        let mut pole = base;
        match definition {
            PoleDefinition::Cartesian(offsets) => {
                for (axis, offset) in offsets.into_iter().enumerate() {
                    pole[axis] += offset.unwrap_or(0.0);
                }
            }
            PoleDefinition::Polar { angle, radius } => {
                let (a, b, _) = plane.axes();
                let (sin, cos) = angle.to_radians().sin_cos();
                pole[a] += radius * cos;
                pole[b] += radius * sin;
            }
        }
        *self = Polar {
            pole,
            angle: None,
            radius: None,
        };
    }

    /// G17/G18/G19 changed the plane: the stored angle and radius belong to the old one
    /// (L4939-4940).
    pub(crate) fn plane_changed(&mut self) {
        self.angle = None;
        self.radius = None;
    }

    /// The end point in the block's plane of a block with `AP=`/`RP=` (either may be missing):
    /// `pole + RP (cos AP, sin AP)`,
    /// AP counter-clockwise from the abscissa (PGsl 9.3.2, L4925-5002). Stores the AP and RP
    /// used.
    ///
    /// - AP: under G91 or `IC` added to the stored angle (ex. b-02 N50, N70); `AC` and G90
    ///   plain values replace it. Missing, the stored angle; with none stored, the angle of the
    ///   start seen from the pole (choice, the manual gives this rule for RP only).
    /// - RP: absolute even under G91; `IC` adds to the stored radius (choice: the text calls RP
    ///   always absolute, the address table gives it IC). Missing, or written as 0, the stored
    ///   radius; with none stored, the distance from the pole to the start, which is then
    ///   stored (L4963-4968).
    /// - A radius of 0 from that rule: a line goes to the pole and nothing is stored
    ///   (L4973-4977); a circle raises the alarm (14095, L4969).
    ///
    /// # Errors
    /// [`AlarmCode::ArcRadiusTooSmall`] for a circle of radius 0 (Siemens alarm 14095),
    /// [`AlarmCode::ValueOutOfRange`] for a negative radius.
    pub(crate) fn end_point(&mut self, block: &PolarBlock) -> Result<V2, Alarm> {
        let span = block.span;
        let pole = self.pole_in(block.plane);
        let from_pole = in_plane(block.plane, block.start) - pole;
        let angle = self.angle_for(block.angle, from_pole, block.distance);
        let radius = self.radius_for(block.radius, from_pole);
        if radius < 0.0 {
            return Err(Alarm::error(
                AlarmCode::ValueOutOfRange,
                span,
                format!("RP={radius} is negative: a polar radius is a length"),
            ));
        }
        self.angle = Some(angle);
        if radius < EPSILON {
            return match block.motion {
                PolarMove::Line => Ok(pole),
                PolarMove::Circle => Err(Alarm::error(
                    AlarmCode::ArcRadiusTooSmall,
                    span,
                    "the polar circle has radius 0: the start point is on the pole",
                )
                .with_help(
                    "program RP=, or a pole away from the start point (Siemens alarm 14095)",
                )),
            };
        }
        self.radius = Some(radius);
        let (sin, cos) = angle.to_radians().sin_cos();
        Ok(pole + V2::new(cos, sin) * radius)
    }

    /// The polar angle of a block, degrees.
    fn angle_for(&self, word: Option<PolarValue>, from_pole: V2, distance: DistanceMode) -> f64 {
        let stored = || {
            self.angle
                .unwrap_or_else(|| from_pole.y.atan2(from_pole.x).to_degrees())
        };
        match word {
            None => stored(),
            Some(PolarValue::Absolute(angle)) => angle,
            Some(PolarValue::Incremental(step)) => stored() + step,
            Some(PolarValue::Plain(value)) => match distance {
                DistanceMode::Absolute => value,
                DistanceMode::Incremental => stored() + value,
            },
        }
    }

    /// The polar radius of a block, mm (negative when programmed so, 0 when there is none).
    fn radius_for(&self, word: Option<PolarValue>, from_pole: V2) -> f64 {
        let stored = self.radius.unwrap_or_else(|| from_pole.length());
        match word {
            Some(PolarValue::Incremental(step)) => stored + step,
            Some(PolarValue::Plain(radius) | PolarValue::Absolute(radius)) if radius != 0.0 => {
                radius
            }
            _ => stored,
        }
    }
}

/// `point`'s (abscissa, ordinate) in `plane`.
fn in_plane(plane: Plane, point: Point3) -> V2 {
    let (a, b, _) = plane.axes();
    V2::new(point[a], point[b])
}

#[cfg(test)]
mod tests {
    use super::super::arcs::tests::{assert_near, SPAN};
    use super::*;

    const G90: DistanceMode = DistanceMode::Absolute;
    const G91: DistanceMode = DistanceMode::Incremental;

    /// A block of the words (AP, RP).
    fn block(
        plane: Plane,
        start: Point3,
        (angle, radius): (Option<PolarValue>, Option<PolarValue>),
        distance: DistanceMode,
        motion: PolarMove,
    ) -> PolarBlock {
        PolarBlock {
            plane,
            start,
            angle,
            radius,
            distance,
            motion,
            span: SPAN,
        }
    }

    /// A line end point in G17 from `start` (X, Y; Z 0).
    fn line_end(
        polar: &mut Polar,
        start: (f64, f64),
        words: (Option<PolarValue>, Option<PolarValue>),
        distance: DistanceMode,
    ) -> Result<V2, Alarm> {
        let start = [start.0, start.1, 0.0];
        polar.end_point(&block(Plane::Xy, start, words, distance, PolarMove::Line))
    }

    #[test]
    fn hole_pattern_of_example_b02_steps_72_degrees() {
        // sinumerik-b/02-polar-hole-pattern.mpf: G111 X43 Y38; G0 RP=30 AP=18; G91 AP=72;
        // AP=IC(72) three times: X71.5317 Y47.2705, X43 Y68, X14.4683 Y47.2705, X25.3664
        // Y13.7295, X60.6336 Y13.7295.
        let mut polar = Polar::new();
        polar.set_pole(
            PoleReference::WorkZero,
            PoleDefinition::Cartesian([Some(43.0), Some(38.0), None]),
            Plane::Xy,
        );
        let words = (Some(PolarValue::Plain(18.0)), Some(PolarValue::Plain(30.0)));
        let mut at = line_end(&mut polar, (0.0, 0.0), words, G90).unwrap();
        assert_near(at, (71.5317, 47.2705), 1e-4);
        let steps = [
            (PolarValue::Plain(72.0), (43.0, 68.0)),
            (PolarValue::Incremental(72.0), (14.4683, 47.2705)),
            (PolarValue::Incremental(72.0), (25.3664, 13.7295)),
            (PolarValue::Incremental(72.0), (60.6336, 13.7295)),
        ];
        for (angle, want) in steps {
            at = line_end(&mut polar, (at.x, at.y), (Some(angle), None), G91).unwrap();
            assert_near(at, want, 1e-4);
        }
    }

    #[test]
    fn polar_circle_of_example_b18_ends_where_the_header_says() {
        // sinumerik-b/18-circle-polar-milling.mpf: G0 X67.5 Y80.211; G111 X50 Y50;
        // G3 RP=34.913 AP=200.052 ends at X17.2034 Y38.0293.
        let mut polar = Polar::new();
        polar.set_pole(
            PoleReference::WorkZero,
            PoleDefinition::Cartesian([Some(50.0), Some(50.0), None]),
            Plane::Xy,
        );
        let words = (
            Some(PolarValue::Plain(200.052)),
            Some(PolarValue::Plain(34.913)),
        );
        let end = polar.end_point(&block(
            Plane::Xy,
            [67.5, 80.211, 0.0],
            words,
            G90,
            PolarMove::Circle,
        ));
        assert_near(end.unwrap(), (17.2034, 38.0293), 1e-4);
    }

    #[test]
    fn poles_refer_to_the_last_point_the_work_zero_or_the_last_pole() {
        let mut polar = Polar::new();
        // G110 X10 from the last point (5, 5, 2): pole (15, 5, 2).
        polar.set_pole(
            PoleReference::LastPoint([5.0, 5.0, 2.0]),
            PoleDefinition::Cartesian([Some(10.0), None, None]),
            Plane::Xy,
        );
        assert_eq!(polar.pole(), [15.0, 5.0, 2.0]);
        // G112 AP=90 RP=4: 4 along +Y from the last pole: (15, 9, 2).
        polar.set_pole(
            PoleReference::LastPole,
            PoleDefinition::Polar {
                angle: 90.0,
                radius: 4.0,
            },
            Plane::Xy,
        );
        let pole = polar.pole();
        assert!((pole[0] - 15.0).abs() < 1e-12 && (pole[1] - 9.0).abs() < 1e-12);
        assert_eq!(pole[2], 2.0);
        // G18 G112 AP=0 RP=3: along the abscissa Z.
        polar.set_pole(
            PoleReference::LastPole,
            PoleDefinition::Polar {
                angle: 0.0,
                radius: 3.0,
            },
            Plane::Zx,
        );
        let pole = polar.pole();
        assert!((pole[2] - 5.0).abs() < 1e-12 && (pole[1] - 9.0).abs() < 1e-12);
        // G111 X1: from the work zero, the other axes at 0.
        polar.set_pole(
            PoleReference::WorkZero,
            PoleDefinition::Cartesian([Some(1.0), None, None]),
            Plane::Xy,
        );
        assert_eq!(polar.pole(), [1.0, 0.0, 0.0]);
    }

    #[test]
    fn without_rp_the_radius_is_the_start_distance_and_stays_stored() {
        // No pole: the work zero. From (3, 4), AP=90 alone: the radius is 5 (3-4-5 triangle)
        // and the end (0, 5); then AP=180 from there keeps RP 5: (-5, 0).
        let mut polar = Polar::new();
        let end = line_end(
            &mut polar,
            (3.0, 4.0),
            (Some(PolarValue::Plain(90.0)), None),
            G90,
        );
        assert_near(end.unwrap(), (0.0, 5.0), 1e-12);
        let end = line_end(
            &mut polar,
            (7.0, 7.0),
            (Some(PolarValue::Plain(180.0)), None),
            G90,
        );
        assert_near(end.unwrap(), (-5.0, 0.0), 1e-12);
        // RP=IC(2) adds to the stored 5; no AP: the stored 180 degrees.
        let end = line_end(
            &mut polar,
            (0.0, 0.0),
            (None, Some(PolarValue::Incremental(2.0))),
            G91,
        );
        assert_near(end.unwrap(), (-7.0, 0.0), 1e-12);
        // RP under G91 stays absolute (choice, docs/SINUMERIK.md 6.5).
        let end = line_end(
            &mut polar,
            (0.0, 0.0),
            (None, Some(PolarValue::Plain(2.0))),
            G91,
        );
        assert_near(end.unwrap(), (-2.0, 0.0), 1e-12);
    }

    #[test]
    fn without_a_stored_angle_ap_ic_adds_to_the_start_angle() {
        // Pole (0,0), start (10, 0) at 0 degrees: AP=IC(30) with RP=10 ends at 30 degrees,
        // (8.6603, 5). AP=AC(90) replaces it under G91: (0, 10).
        let mut polar = Polar::new();
        let words = (
            Some(PolarValue::Incremental(30.0)),
            Some(PolarValue::Plain(10.0)),
        );
        let end = line_end(&mut polar, (10.0, 0.0), words, G90);
        assert_near(end.unwrap(), (8.660_254_037_844_386, 5.0), 1e-12);
        let end = line_end(
            &mut polar,
            (0.0, 0.0),
            (Some(PolarValue::Absolute(90.0)), None),
            G91,
        );
        assert_near(end.unwrap(), (0.0, 10.0), 1e-12);
    }

    #[test]
    fn a_new_pole_or_plane_clears_the_stored_values() {
        let mut polar = Polar::new();
        let words = (Some(PolarValue::Plain(0.0)), Some(PolarValue::Plain(10.0)));
        line_end(&mut polar, (0.0, 0.0), words, G90).unwrap();
        // After a plane change, AP alone measures the radius from the start again: from (0, 2)
        // to 0 degrees at radius 2.
        polar.plane_changed();
        let end = line_end(
            &mut polar,
            (0.0, 2.0),
            (Some(PolarValue::Plain(0.0)), None),
            G90,
        );
        assert_near(end.unwrap(), (2.0, 0.0), 1e-12);
        // A new pole at (1, 0): RP=3 alone takes the start's angle seen from it, 90 degrees
        // from (1, 1): (1, 3).
        polar.set_pole(
            PoleReference::WorkZero,
            PoleDefinition::Cartesian([Some(1.0), None, None]),
            Plane::Xy,
        );
        let end = line_end(
            &mut polar,
            (1.0, 1.0),
            (None, Some(PolarValue::Plain(3.0))),
            G90,
        );
        assert_near(end.unwrap(), (1.0, 3.0), 1e-12);
    }

    #[test]
    fn a_start_on_the_pole_gives_no_circle_but_a_line_to_the_pole() {
        // L4969-4977: no radius stored and the start on the pole.
        let mut polar = Polar::new();
        let words = (Some(PolarValue::Plain(45.0)), None);
        let circle = polar.end_point(&block(Plane::Xy, [0.0; 3], words, G90, PolarMove::Circle));
        assert_eq!(circle.unwrap_err().code, AlarmCode::ArcRadiusTooSmall);
        let line = line_end(&mut polar, (0.0, 0.0), words, G90);
        assert_near(line.unwrap(), (0.0, 0.0), 0.0);
        let negative = line_end(
            &mut polar,
            (1.0, 0.0),
            (None, Some(PolarValue::Plain(-1.0))),
            G90,
        );
        assert_eq!(negative.unwrap_err().code, AlarmCode::ValueOutOfRange);
    }

    #[test]
    fn g18_angles_start_at_z_towards_x() {
        // The form of sinumerik-b/19-circle-polar-turning.mpf with X as a plain coordinate (the
        // example's X is a diameter): G18 G111 X33.33 Z-54.25, RP=30
        // AP=142.326: AP from the abscissa Z. By hand: Z = -54.25 + 30 cos 142.326 = -77.9950,
        // X = 33.33 + 30 sin 142.326 = 51.6650.
        let mut polar = Polar::new();
        polar.set_pole(
            PoleReference::WorkZero,
            PoleDefinition::Cartesian([Some(33.33), None, Some(-54.25)]),
            Plane::Zx,
        );
        let words = (
            Some(PolarValue::Plain(142.326)),
            Some(PolarValue::Plain(30.0)),
        );
        let end = polar.end_point(&block(
            Plane::Zx,
            [40.0, 0.0, -25.0],
            words,
            G90,
            PolarMove::Circle,
        ));
        assert_near(end.unwrap(), (-77.9950, 51.6650), 1e-4);
    }
}
