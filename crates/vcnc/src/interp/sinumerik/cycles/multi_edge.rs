//! CYCLE79, multi-edge milling: a regular polygon spigot (three edges or more) or one or two key
//! flats on a round blank, milled from outside as the spigot cycles mill theirs (`spigots.rs`:
//! rings from the blank in, level by level).
//!
//! Parameters (**inferred**: the Fundamentals manual names the cycle only, sinumerik-tables.md 5,
//! seed 002 L12258; the list is laid out as CYCLE76's, the rectangle's LENG and WID replaced by
//! the edges' number and size): CYCLE79(RTP, RFP, SDIS, DP, DPR, NUM, SWL, CRAD, PA, PO, STA, MID,
//! FAL, FALD, FFP1, FFD, CDIR, VARI, AP1). NUM edges about (PA, PO), the first edge's outward
//! normal at STA degrees; SWL above 0 the width across flats, below 0 the edge length; CRAD above
//! 0 the corners' radius, below 0 a chamfer cutting |CRAD| off each edge at each corner; AP1 the
//! blank's diameter (0: no larger than the spigot, one ring). NUM 2 is two flats SWL apart on
//! the blank, NUM 1 one flat SWL from the blank's far side; both need AP1.
//!
//! Never: feed down where the blank is, or round a corner with more than the edge has.

use super::params::too_many;
use super::rings::Piece;
use super::spigots::{mill, milling, Layout};
use super::{alarm, Params, Place, MAX_DIVISIONS};
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::kernel::Kernel;
use std::f64::consts::PI;

/// The places of the parameters after the edges' size: CYCLE76's.
const LAYOUT: Layout = Layout {
    pa: 8,
    sta: Some(10),
    mid: 11,
};

/// A piece of a convex outline, counter-clockwise from the end of the piece before: a line, or
/// an arc about a centre.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Edge {
    to: (f64, f64),
    centre: Option<(f64, f64)>,
}

/// A closed convex outline, counter-clockwise, starting at the start of a line whose middle is on
/// the positive abscissa (where the rings start and the tool comes in).
struct Outline {
    start: (f64, f64),
    edges: Vec<Edge>,
    /// How far the outline reaches along the positive abscissa.
    reach: f64,
}

/// CYCLE79 (see the module's doc).
pub(super) fn multi_edge(
    at: &mut Place,
    kernel: &mut Kernel,
    p: &Params,
    radius: Option<f64>,
) -> Result<(), Alarm> {
    let count = p.or_zero(5).round();
    if !(1.0..=MAX_DIVISIONS as f64).contains(&count) {
        return Err(edges_out_of_range(p, count));
    }
    let blank = p.length_or_zero(18).abs() / 2.0;
    let outline = match count as usize {
        n @ 1..=2 => key_flats(p, n, blank)?,
        n => polygon(p, n)?,
    };
    // The material farthest out from the outline lies where the blank passes the middle of the
    // first edge (every edge's middle is as far in).
    let extra = (blank - outline.reach).max(0.0);
    let (milling, offsets) = milling(p, at, &LAYOUT, radius, extra)?;
    let frame =
        super::pockets::Frame::new((p.length_or_zero(8), p.length_or_zero(9)), p.or_zero(10));
    let clearance = milling.levels.safety - milling.levels.reference;
    let entry = (
        outline.reach + offsets[0] + milling.tool_radius + clearance,
        0.0,
    );
    let ring = |o: f64| outline.offset(o);
    mill(at, kernel, frame, milling, &offsets, entry, ring)
}

/// NUM not a number of edges vcnc mills: V007 (**choice**: the control's own number for it is
/// not known).
fn edges_out_of_range(p: &Params, count: f64) -> Alarm {
    if count > MAX_DIVISIONS as f64 {
        return too_many(p, count, "edges");
    }
    Alarm::error(
        AlarmCode::ValueOutOfRange,
        p.span,
        format!("CYCLE79: {count} edges: NUM must be 1 or more"),
    )
    .with_help("NUM: 1 or 2 key flats on the blank AP1, 3 or more a regular polygon")
}

/// A regular polygon of `n` edges (SWL across flats or as the edge length) with its corners
/// rounded or chamfered by CRAD: alarm 61113 when a corner takes more than its edges have.
fn polygon(p: &Params, n: usize) -> Result<Outline, Alarm> {
    let half_angle = PI / n as f64;
    let size = p.length_or_zero(6);
    // The apothem: half the width across flats, or half an edge over tan(180/n degrees).
    let apothem = if size >= 0.0 {
        size / 2.0
    } else {
        -size / 2.0 / half_angle.tan()
    };
    if apothem <= 0.0 {
        return Err(size_is_zero(p));
    }
    let half_edge = apothem * half_angle.tan();
    let corner = p.length_or_zero(7);
    let too_large = if corner >= 0.0 {
        corner > apothem
    } else {
        -corner > half_edge
    };
    if too_large {
        return Err(alarm(
            61113,
            p.span,
            format_args!(
                "CYCLE79: parameter CRAD for the corner radius too large: {corner} for edges {} long",
                2.0 * half_edge
            ),
        )
        .with_help("a corner radius is at most half the width across flats, a chamfer at most half an edge"));
    }
    // The corners' centres of a rounded polygon are its vertices brought in by the radius; a
    // chamfered polygon has two corners where the plain one has one.
    let vertex = |k: usize, inset: f64| {
        let angle = (2 * k) as f64 * half_angle - half_angle;
        let r = (apothem - inset) / half_angle.cos();
        (r * angle.cos(), r * angle.sin())
    };
    let mut edges = Vec::with_capacity(4 * n);
    let start;
    if corner > 0.0 {
        let centres: Vec<_> = (0..n).map(|k| vertex(k, corner)).collect();
        let on = |k: usize, normal_k: usize| {
            let c = centres[k % n];
            let angle = (2 * normal_k) as f64 * half_angle;
            (c.0 + corner * angle.cos(), c.1 + corner * angle.sin())
        };
        start = on(0, 0);
        for k in 1..=n {
            edges.push(Edge {
                to: on(k, k - 1),
                centre: None,
            });
            edges.push(Edge {
                to: on(k, k),
                centre: Some(centres[k % n]),
            });
        }
    } else {
        let leg = -corner;
        let vertices: Vec<_> = (0..n).map(|k| vertex(k, 0.0)).collect();
        let toward = |from: (f64, f64), to: (f64, f64)| {
            let d = ((to.0 - from.0), (to.1 - from.1));
            let length = d.0.hypot(d.1);
            (from.0 + d.0 * leg / length, from.1 + d.1 * leg / length)
        };
        start = toward(vertices[0], vertices[1]);
        for k in 1..=n {
            let (before, here, after) = (vertices[k - 1], vertices[k % n], vertices[(k + 1) % n]);
            edges.push(Edge {
                to: toward(here, before),
                centre: None,
            });
            if leg > 0.0 {
                edges.push(Edge {
                    to: toward(here, after),
                    centre: None,
                });
            }
        }
    }
    Ok(Outline {
        start,
        edges,
        reach: apothem,
    })
}

/// `n` key flats (1 or 2) on the blank of radius `blank`: two SWL apart about the centre, or one
/// SWL from the blank's far side (**inferred**: the width across a single flat).
fn key_flats(p: &Params, n: usize, blank: f64) -> Result<Outline, Alarm> {
    let size = p.length_or_zero(6).abs();
    if size <= 0.0 {
        return Err(size_is_zero(p));
    }
    let flat = if n == 2 { size / 2.0 } else { size - blank };
    if blank <= 0.0 || flat.abs() >= blank {
        return Err(Alarm::error(
            AlarmCode::ValueOutOfRange,
            p.span,
            format!("CYCLE79: key flats {size} wide do not cut the blank of diameter {}", 2.0 * blank),
        )
        .with_help("NUM 1 and 2 mill flats on a round blank: give its diameter AP1, larger than the width SWL"));
    }
    let half_chord = (blank * blank - flat * flat).sqrt();
    let centre = Some((0.0, 0.0));
    let mut edges = vec![Edge {
        to: (flat, half_chord),
        centre: None,
    }];
    if n == 2 {
        edges.extend([
            Edge {
                to: (-flat, half_chord),
                centre,
            },
            Edge {
                to: (-flat, -half_chord),
                centre: None,
            },
        ]);
    }
    edges.push(Edge {
        to: (flat, -half_chord),
        centre,
    });
    Ok(Outline {
        start: (flat, -half_chord),
        edges,
        reach: flat,
    })
}

/// SWL 0: V007.
fn size_is_zero(p: &Params) -> Alarm {
    Alarm::error(
        AlarmCode::ValueOutOfRange,
        p.span,
        "CYCLE79: the width across flats or the edge length SWL is 0",
    )
    .with_help("SWL: above 0 the width across flats, below 0 the edge length")
}

impl Outline {
    /// The outline moved out by `o`: its lines moved along their normals, its arcs' radii
    /// grown, and an arc of radius `o` round each corner; from and back to the middle of the
    /// first line, as the rings of `rings.rs` go.
    fn offset(&self, o: f64) -> Vec<Piece> {
        let (first_normal, _) = self.edges[0].normals(self.start);
        let middle = along(midpoint(self.start, self.edges[0].to), first_normal, o);
        let mut pieces = Vec::with_capacity(2 * self.edges.len() + 2);
        pieces.push(Piece::Line(middle));
        let mut from = self.start;
        let mut before = first_normal;
        for (k, edge) in self.edges.iter().enumerate() {
            let (start_normal, end_normal) = edge.normals(from);
            if k > 0 {
                round_corner(&mut pieces, from, (before, start_normal), o);
            }
            let to = along(edge.to, end_normal, o);
            pieces.push(match edge.centre {
                None => Piece::Line(to),
                Some(centre) => Piece::Arc {
                    to,
                    centre,
                    ccw: true,
                },
            });
            before = end_normal;
            from = edge.to;
        }
        round_corner(&mut pieces, self.start, (before, first_normal), o);
        pieces.push(Piece::Line(middle));
        pieces
    }
}

/// The arc of radius `o` about corner `at` from the normal of the edge before to the normal of
/// the edge after; none where they meet tangentially.
fn round_corner(pieces: &mut Vec<Piece>, at: (f64, f64), (before, after): Normals, o: f64) {
    let to = along(at, after, o);
    if distance(along(at, before, o), to) > 1e-9 {
        pieces.push(Piece::Arc {
            to,
            centre: at,
            ccw: true,
        });
    }
}

/// The outward unit normals where an edge starts and ends.
type Normals = ((f64, f64), (f64, f64));

impl Edge {
    /// The outward unit normals where the edge from `from` starts and ends.
    fn normals(&self, from: (f64, f64)) -> Normals {
        match self.centre {
            None => {
                let (dx, dy) = (self.to.0 - from.0, self.to.1 - from.1);
                let length = dx.hypot(dy);
                let normal = (dy / length, -dx / length);
                (normal, normal)
            }
            Some(c) => (unit(from, c), unit(self.to, c)),
        }
    }
}

/// The unit vector from `c` to `p`.
fn unit(p: (f64, f64), c: (f64, f64)) -> (f64, f64) {
    let (dx, dy) = (p.0 - c.0, p.1 - c.1);
    let length = dx.hypot(dy);
    (dx / length, dy / length)
}

fn along(p: (f64, f64), normal: (f64, f64), o: f64) -> (f64, f64) {
    (p.0 + normal.0 * o, p.1 + normal.1 * o)
}

fn midpoint(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0)
}

fn distance(a: (f64, f64), b: (f64, f64)) -> f64 {
    (a.0 - b.0).hypot(a.1 - b.1)
}
