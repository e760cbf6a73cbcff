//! SINUMERIK's KONTC and KONTT (sinumerik-part-b.md 2.2, seed 002 L7176-7293): the approach
//! and retraction block replaced by a polynomial that joins the compensated contour with the
//! same tangent (KONTT) or the same tangent and curvature (KONTC), in all three axes, so that
//! an infeed along the plane's normal may run in the same block.
//!
//! The manual names the continuity, not the polynomial (the control's is its own); vcnc's
//! choice: in the plane a cubic Bezier curve from the uncompensated point P0 to the contour
//! point P4, its last control point a third of the chord back along the contour's tangent, its
//! second one half-way between P0 and that point (KONTT) or moved across the tangent until the
//! curve's curvature at P4 is the compensated contour's (KONTC); every other axis follows the
//! curve's parameter s by 1 - (1 - s)^2 (KONTT) or 1 - (1 - s)^3 (KONTC), so that it arrives
//! with no speed (and no acceleration) along the normal, as the contour runs in the plane. The
//! motion stream has lines and arcs: the curve goes out as straight pieces within 1 um of it.

use super::geometry::{Element, Side, V2};
use crate::machine::AXES;

/// What the approach curve keeps continuous where it meets the contour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Continuity {
    /// KONTT: the tangent.
    Tangent,
    /// KONTC: the tangent and the curvature.
    Curvature,
}

/// How far a straight piece may leave the curve, mm.
const CHORD_TOLERANCE: f64 = 0.001;

/// The signed curvature (positive turning left) of `element` compensated on `side` by `r`.
pub(crate) fn curvature(element: &Element, (side, r): (Side, f64)) -> f64 {
    match element.offset(side, r) {
        Ok(compensated @ Element::Arc { ccw, .. }) => {
            let radius = compensated.radius().unwrap_or(f64::INFINITY);
            if ccw {
                1.0 / radius
            } else {
                -1.0 / radius
            }
        }
        _ => 0.0,
    }
}

/// The approach from `from` to `to` (machine coordinates; the plane's axes `axes`), arriving
/// along the unit `tangent` with the signed `curvature`: the pieces' end points, `to` last.
pub(crate) fn approach(
    continuity: Continuity,
    (from, to): ([f64; AXES], [f64; AXES]),
    axes: (usize, usize),
    (tangent, curvature): (V2, f64),
) -> Vec<[f64; AXES]> {
    let (a, b) = axes;
    let p0 = V2::new(from[a], from[b]);
    let p4 = V2::new(to[a], to[b]);
    let reach = p0.distance(p4) / 3.0;
    let c2 = p4 - tangent * reach;
    let middle = p0 + (c2 - p0) * 0.5;
    let c1 = match continuity {
        Continuity::Tangent => middle,
        // The end curvature of the cubic is (2/3) ((c1 - c2) . n) / reach^2, n the tangent's
        // left normal: c1 is moved along n until it is `curvature`.
        Continuity::Curvature => {
            let normal = tangent.left();
            let across = 1.5 * curvature * reach * reach - (middle - c2).dot(normal);
            middle + normal * across
        }
    };
    let (order, bend) = match continuity {
        Continuity::Tangent => (2, 2.0),
        Continuity::Curvature => (3, 6.0),
    };
    // Uniform steps of s leave the curve by at most |B''| ds^2 / 8.
    let plane_bend = 6.0
        * (p0 - c1 * 2.0 + c2)
            .length()
            .max((c1 - c2 * 2.0 + p4).length());
    let other_bend: f64 = (0..AXES)
        .filter(|&i| i != a && i != b)
        .map(|i| (to[i] - from[i]).abs() * bend)
        .sum();
    let pieces = ((plane_bend + other_bend) / (8.0 * CHORD_TOLERANCE))
        .sqrt()
        .ceil()
        .clamp(1.0, 10_000.0) as usize;
    (1..=pieces)
        .map(|k| {
            if k == pieces {
                return to;
            }
            let s = k as f64 / pieces as f64;
            let t = 1.0 - s;
            let point = p0 * (t * t * t)
                + c1 * (3.0 * t * t * s)
                + c2 * (3.0 * t * s * s)
                + p4 * (s * s * s);
            let follow = 1.0 - t.powi(order);
            let mut p = [0.0; AXES];
            for i in 0..AXES {
                p[i] = from[i] + (to[i] - from[i]) * follow;
            }
            (p[a], p[b]) = (point.x, point.y);
            p
        })
        .collect()
}

/// The retraction from `from` (the contour's end, left along the unit `tangent` with the
/// signed `curvature`) to `to`: the approach travelled backwards.
pub(crate) fn retraction(
    continuity: Continuity,
    (from, to): ([f64; AXES], [f64; AXES]),
    axes: (usize, usize),
    (tangent, curvature): (V2, f64),
) -> Vec<[f64; AXES]> {
    let mut points = approach(continuity, (to, from), axes, (-tangent, -curvature));
    points.pop();
    points.reverse();
    points.push(to);
    points
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(x: f64, y: f64, z: f64) -> [f64; AXES] {
        let mut p = [0.0; AXES];
        (p[0], p[1], p[2]) = (x, y, z);
        p
    }

    /// The curvature of a curve through three points (signed, left positive).
    fn bend(p: [f64; AXES], q: [f64; AXES], r: [f64; AXES]) -> f64 {
        let (u, v) = (
            V2::new(q[0] - p[0], q[1] - p[1]),
            V2::new(r[0] - q[0], r[1] - q[1]),
        );
        2.0 * u.cross(v) / (u.length() * v.length() * (u + v).length())
    }

    /// b/51 (seed 002 L7222-7229): from (0,0,60) onto the tool-centre circle of radius 80
    /// about the origin, clockwise, at (80,0,0), heading -Y with curvature -1/80. KONTC ends
    /// there with that tangent and curvature and Z at rest; KONTT with the tangent only.
    #[test]
    fn kontc_meets_the_circle_with_its_tangent_and_curvature() {
        let (from, to) = (at(0.0, 0.0, 60.0), at(80.0, 0.0, 0.0));
        let arrival = (V2::new(0.0, -1.0), -1.0 / 80.0);
        let points = approach(Continuity::Curvature, (from, to), (0, 1), arrival);
        let n = points.len();
        assert!(n > 100, "{n} pieces");
        assert_eq!(points[n - 1], to);
        let (p, q, r) = (points[n - 3], points[n - 2], points[n - 1]);
        // A chord turns from the tangent by half the curve's turn along it: about 0.3 mm / 80
        // / 2 here.
        let direction = V2::new(r[0] - q[0], r[1] - q[1]).unit();
        assert!(
            direction.distance(V2::new(0.0, -1.0)) < 5e-3,
            "{direction:?}"
        );
        assert!(
            (bend(p, q, r) + 1.0 / 80.0).abs() < 1e-3,
            "{}",
            bend(p, q, r)
        );
        // 60 / n^3 over the last of n pieces.
        assert!((q[2] - r[2]).abs() < 1e-5, "Z at rest: {} {}", q[2], r[2]);
        let tangent = approach(Continuity::Tangent, (from, to), (0, 1), arrival);
        let m = tangent.len();
        let (q, r) = (tangent[m - 2], tangent[m - 1]);
        // KONTT's curvature at the end is its own: (2/3) 40 / 26.67^2 = 1/26.7 here, so the
        // last chord (0.33 mm) turns 0.0062 from the tangent.
        let direction = V2::new(r[0] - q[0], r[1] - q[1]).unit();
        assert!(
            direction.distance(V2::new(0.0, -1.0)) < 1e-2,
            "{direction:?}"
        );
    }

    /// The retraction is the approach backwards: it starts along the contour's tangent and
    /// ends at the uncompensated point.
    #[test]
    fn the_retraction_leaves_along_the_contour() {
        let (from, to) = (at(80.0, 0.0, 0.0), at(0.0, 0.0, 60.0));
        let points = retraction(
            Continuity::Curvature,
            (from, to),
            (0, 1),
            (V2::new(0.0, -1.0), -1.0 / 80.0),
        );
        assert_eq!(*points.last().unwrap(), to);
        let first = V2::new(points[0][0] - 80.0, points[0][1]).unit();
        assert!(first.distance(V2::new(0.0, -1.0)) < 1e-2, "{first:?}");
    }
}
