//! The closed paths the milling cycles clear a level with, in a cycle's own coordinates: circles,
//! rectangles with round corners (a slot is one whose corners are half its width), and the
//! round-ended ring sectors of a circumferential slot.
//!
//! Every ring is built counter-clockwise from and back to its first point; [`oriented`] turns
//! it round for clockwise milling. Each arc says its own direction within the ring, since a
//! ring sector goes back along its inner arc the other way about the centre.
//!
//! Never: let a ring leave the outline it was made for (the rings of an outline are its inward
//! offsets, their corners the outline's corner less the offset).

/// A piece of a ring: a line or an arc to a point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Piece {
    Line((f64, f64)),
    Arc {
        to: (f64, f64),
        centre: (f64, f64),
        ccw: bool,
    },
}

impl Piece {
    fn end(&self) -> (f64, f64) {
        match *self {
            Piece::Line(to) | Piece::Arc { to, .. } => to,
        }
    }
}

/// `ring` for milling `clockwise` (as built, or the other way round).
pub(super) fn oriented(ring: &[Piece], clockwise: bool) -> Vec<Piece> {
    if !clockwise || ring.is_empty() {
        return ring.to_vec();
    }
    let ends: Vec<_> = ring.iter().map(Piece::end).collect();
    let mut reversed = vec![Piece::Line(ends[0])];
    for k in (1..ring.len()).rev() {
        let to = ends[k - 1];
        reversed.push(match ring[k] {
            Piece::Line(_) => Piece::Line(to),
            Piece::Arc { centre, ccw, .. } => Piece::Arc {
                to,
                centre,
                ccw: !ccw,
            },
        });
    }
    reversed
}

/// `count` steps shared out evenly up to `outer`, at most `step` each: the offsets of the rings.
pub(super) fn steps(outer: f64, step: f64) -> Vec<f64> {
    if outer <= 0.0 {
        return Vec::new();
    }
    let count = super::divisions(outer, step);
    (1..=count)
        .map(|k| outer * k as f64 / count as f64)
        .collect()
}

/// A full circle of `radius` about the centre, from and back to (radius, 0), in two halves.
pub(super) fn circle(radius: f64) -> Vec<Piece> {
    if radius <= 0.0 {
        return Vec::new();
    }
    let centre = (0.0, 0.0);
    vec![
        Piece::Line((radius, 0.0)),
        Piece::Arc {
            to: (-radius, 0.0),
            centre,
            ccw: true,
        },
        Piece::Arc {
            to: (radius, 0.0),
            centre,
            ccw: true,
        },
    ]
}

/// The circles that clear a disc of radius `outer`, inside out.
pub(super) fn circles(outer: f64, step: f64) -> Vec<Vec<Piece>> {
    steps(outer, step).into_iter().map(circle).collect()
}

/// A rectangle of half sizes `a` × `b` about the centre with corners of radius `corner`, from
/// and back to the middle of its right side (a, 0).
pub(super) fn rectangle(a: f64, b: f64, corner: f64) -> Vec<Piece> {
    let c = corner.min(a).min(b).max(0.0);
    let mut pieces = vec![Piece::Line((a, 0.0)), Piece::Line((a, b - c))];
    let corners = [
        ((a - c, b), (a - c, b - c), (-a + c, b)),
        ((-a, b - c), (-a + c, b - c), (-a, -b + c)),
        ((-a + c, -b), (-a + c, -b + c), (a - c, -b)),
        ((a, -b + c), (a - c, -b + c), (a, 0.0)),
    ];
    for (to, centre, next) in corners {
        if c > 0.0 {
            pieces.push(Piece::Arc {
                to,
                centre,
                ccw: true,
            });
        }
        pieces.push(Piece::Line(next));
    }
    pieces
}

/// The rectangles that clear a rectangle of half sizes `a` × `b` with corners of radius
/// `corner`, inside out: inward offsets by equal steps of at most `step` until the smaller side
/// closes (the innermost a line or a point), each with the corner less its offset.
pub(super) fn rectangles(a: f64, b: f64, corner: f64, step: f64) -> Vec<Vec<Piece>> {
    let inner = a.min(b);
    let count = if inner > 0.0 {
        super::divisions(inner, step)
    } else {
        0
    };
    (0..=count)
        .rev()
        .map(|k| {
            let d = if count == 0 {
                0.0
            } else {
                inner * k as f64 / count as f64
            };
            rectangle(a - d, b - d, (corner - d).max(0.0))
        })
        .collect()
}

/// The point at `radius` and `degrees` about the centre.
pub(super) fn polar(radius: f64, degrees: f64) -> (f64, f64) {
    let (sin, cos) = degrees.to_radians().sin_cos();
    (radius * cos, radius * sin)
}

/// A ring sector about the centre: `offset` either side of the arc of `radius` from `from` to
/// `to` degrees (counter-clockwise), with round ends; from and back to its outer start.
pub(super) fn sector(radius: f64, from: f64, to: f64, offset: f64) -> Vec<Piece> {
    let centre = (0.0, 0.0);
    let (outer, inner) = (radius + offset, radius - offset);
    let mut pieces = vec![
        Piece::Line(polar(outer, from)),
        Piece::Arc {
            to: polar(outer, to),
            centre,
            ccw: true,
        },
    ];
    if offset > 0.0 {
        pieces.push(Piece::Arc {
            to: polar(inner, to),
            centre: polar(radius, to),
            ccw: true,
        });
    }
    pieces.push(Piece::Arc {
        to: polar(inner, from),
        centre,
        ccw: false,
    });
    if offset > 0.0 {
        pieces.push(Piece::Arc {
            to: polar(outer, from),
            centre: polar(radius, from),
            ccw: true,
        });
    }
    pieces
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_are_shared_out_evenly_up_to_the_outline() {
        assert_eq!(steps(10.0, 5.0), vec![5.0, 10.0]);
        assert_eq!(steps(11.0, 5.0), vec![11.0 / 3.0, 22.0 / 3.0, 11.0]);
        assert!(steps(0.0, 5.0).is_empty());
    }

    #[test]
    fn a_rectangle_goes_round_and_back_both_ways() {
        let ccw = rectangle(10.0, 5.0, 2.0);
        assert_eq!(ccw.first(), Some(&Piece::Line((10.0, 0.0))));
        assert_eq!(ccw.last(), Some(&Piece::Line((10.0, 0.0))));
        // The way up the right side, then four arcs and four lines.
        assert_eq!(ccw.len(), 10);
        let cw = oriented(&ccw, true);
        assert_eq!(cw.len(), 10);
        // Clockwise, the way from the right side's middle goes down first, and the arcs turn
        // the other way.
        assert_eq!(cw[1], Piece::Line((10.0, -3.0)));
        assert!(matches!(cw[2], Piece::Arc { ccw: false, .. }));
        assert_eq!(cw.last(), Some(&Piece::Line((10.0, 0.0))));
    }

    #[test]
    fn inner_rectangles_keep_inside_the_round_corners() {
        // Half sizes 10 × 6 with corners of 4, steps of at most 2: offsets 6, 4, 2, 0; the
        // ring at offset 2 has corners of 2 about the same centres (8 - 2, 4 - 2).
        let rings = rectangles(10.0, 6.0, 4.0, 2.0);
        assert_eq!(rings.len(), 4);
        assert_eq!(rings[0][0], Piece::Line((4.0, 0.0)));
        assert!(rings[2].contains(&Piece::Arc {
            to: (6.0, 4.0),
            centre: (6.0, 2.0),
            ccw: true
        }));
    }

    #[test]
    fn a_sector_comes_back_along_its_inner_arc_the_other_way() {
        let ring = sector(20.0, 0.0, 90.0, 2.0);
        assert_eq!(ring.len(), 5);
        assert!(matches!(ring[3], Piece::Arc { ccw: false, .. }));
        let end = ring.last().map(Piece::end).unwrap();
        assert!((end.0 - 22.0).abs() < 1e-9 && end.1.abs() < 1e-9);
    }
}
