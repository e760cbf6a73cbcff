//! Plane geometry for checking tool-centre paths: programmed elements, the distance of a point
//! to them, and points sampled along traced moves (X-Y).

use std::f64::consts::TAU;
use vcnc::motion::ArcDirection;
use vcnc::SegmentKind;

pub type P = (f64, f64);

pub fn sub(a: P, b: P) -> P {
    (a.0 - b.0, a.1 - b.1)
}

pub fn dot(a: P, b: P) -> f64 {
    a.0 * b.0 + a.1 * b.1
}

pub fn cross(a: P, b: P) -> f64 {
    a.0 * b.1 - a.1 * b.0
}

pub fn length(a: P) -> f64 {
    a.0.hypot(a.1)
}

/// A programmed element: a line, or an arc about `center` (counter-clockwise when `ccw`).
#[derive(Clone, Copy, Debug)]
pub enum Element {
    Line(P, P),
    Arc {
        from: P,
        to: P,
        center: P,
        ccw: bool,
    },
}

impl Element {
    pub fn start(&self) -> P {
        match *self {
            Element::Line(a, _) | Element::Arc { from: a, .. } => a,
        }
    }

    pub fn end(&self) -> P {
        match *self {
            Element::Line(_, b) | Element::Arc { to: b, .. } => b,
        }
    }

    /// The distance from `p` to the element.
    pub fn distance(&self, p: P) -> f64 {
        match *self {
            Element::Line(a, b) => {
                let d = sub(b, a);
                let t = (dot(sub(p, a), d) / dot(d, d)).clamp(0.0, 1.0);
                length(sub(p, (a.0 + d.0 * t, a.1 + d.1 * t)))
            }
            Element::Arc {
                from,
                to,
                center,
                ccw,
            } => {
                let radius = length(sub(from, center));
                if on_sweep(center, from, to, ccw, p) {
                    (length(sub(p, center)) - radius).abs()
                } else {
                    length(sub(p, from)).min(length(sub(p, to)))
                }
            }
        }
    }
}

/// True when the direction of `p` from `center` lies within the arc from `from` to `to`.
pub fn on_sweep(center: P, from: P, to: P, ccw: bool, p: P) -> bool {
    let angle = |q: P| (q.1 - center.1).atan2(q.0 - center.0);
    let ccw_sweep = |a: f64, b: f64| (b - a).rem_euclid(TAU);
    let (a0, a1, a) = (angle(from), angle(to), angle(p));
    if ccw {
        ccw_sweep(a0, a) <= ccw_sweep(a0, a1)
    } else {
        ccw_sweep(a, a0) <= ccw_sweep(a1, a0)
    }
}

impl Element {
    /// The programmed element of a traced line or arc, X-Y; `None` for other segments.
    pub fn of(kind: &SegmentKind) -> Option<Element> {
        match *kind {
            SegmentKind::Line { motion, .. } | SegmentKind::Rapid { motion, .. } => {
                Some(Element::Line(
                    (motion.from.0[0], motion.from.0[1]),
                    (motion.to.0[0], motion.to.0[1]),
                ))
            }
            SegmentKind::Arc {
                motion,
                center,
                direction,
                ..
            } => Some(Element::Arc {
                from: (motion.from.0[0], motion.from.0[1]),
                to: (motion.to.0[0], motion.to.0[1]),
                center: (center.0[0], center.0[1]),
                ccw: direction == ArcDirection::CounterClockwise,
            }),
            _ => None,
        }
    }
}

/// Points along a traced move in the plane: `count` of them, ends included.
pub fn samples(kind: &SegmentKind, count: usize) -> Vec<P> {
    match *kind {
        SegmentKind::Line { motion, .. } | SegmentKind::Rapid { motion, .. } => {
            let (a, b) = (motion.from.0, motion.to.0);
            (0..=count)
                .map(|i| {
                    let t = i as f64 / count as f64;
                    (a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t)
                })
                .collect()
        }
        SegmentKind::Arc {
            motion,
            center,
            direction,
            ..
        } => {
            let c = (center.0[0], center.0[1]);
            let (a, b) = (
                (motion.from.0[0], motion.from.0[1]),
                (motion.to.0[0], motion.to.0[1]),
            );
            let radius = length(sub(a, c));
            let start = (a.1 - c.1).atan2(a.0 - c.0);
            let end = (b.1 - c.1).atan2(b.0 - c.0);
            let mut sweep = (end - start).rem_euclid(TAU);
            if direction == ArcDirection::Clockwise {
                sweep -= TAU;
            }
            if length(sub(a, b)) < 1e-9 {
                sweep = if direction == ArcDirection::Clockwise {
                    -TAU
                } else {
                    TAU
                };
            }
            (0..=count)
                .map(|i| {
                    let t = start + sweep * i as f64 / count as f64;
                    (c.0 + radius * t.cos(), c.1 + radius * t.sin())
                })
                .collect()
        }
        _ => Vec::new(),
    }
}
