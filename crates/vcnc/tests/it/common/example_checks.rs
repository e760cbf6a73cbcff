//! What an example program's run is checked against: its end position, the end points of its
//! motions in order, positions it passes, its feed and rapid path lengths, feeds and dwells. Written
//! for the SINUMERIK examples (`sinumerik_examples.rs`) in the form the ISO examples use, so that
//! both tables can share it. It only compares a finished run; it never runs a program itself.

use serde::Deserialize;
use vcnc::{Segment, SegmentKind};

/// A position given per axis; axes it leaves out are not checked.
#[derive(Deserialize, Debug, Default, Clone, Copy)]
#[serde(deny_unknown_fields)]
pub struct Point {
    pub x: Option<f64>,
    pub y: Option<f64>,
    pub z: Option<f64>,
    /// The rotary axis A, degrees.
    pub a: Option<f64>,
    /// The rotary axis C, degrees.
    pub c: Option<f64>,
}

impl Point {
    /// The axes the point gives, by index into a position.
    pub fn axes(&self) -> [(usize, Option<f64>); 5] {
        [
            (0, self.x),
            (1, self.y),
            (2, self.z),
            (3, self.a),
            (5, self.c),
        ]
    }

    /// True when every axis the point gives is within `tolerance` of `position`.
    pub fn matches(&self, position: &[f64; 6], tolerance: f64) -> bool {
        self.axes()
            .iter()
            .all(|&(i, v)| v.is_none_or(|v| close(position[i], v, tolerance)))
    }
}

/// The letter of a position's axis index.
pub fn letter(index: usize) -> char {
    "XYZABC".as_bytes()[index] as char
}

pub fn close(actual: f64, expected: f64, tolerance: f64) -> bool {
    (actual - expected).abs() <= tolerance
}

/// What a run must show. Every field is optional; [`Expected::asserts`] says whether any is given.
#[derive(Deserialize, Debug, Default, Clone)]
pub struct Expected {
    /// Where the last motion ends, machine coordinates (the start when nothing moves).
    pub end: Option<Point>,
    /// The end point of every motion, in order: as many as there are motions.
    pub points: Option<Vec<Point>>,
    /// Positions some motions end at, in this order, other motions between them allowed.
    pub visits: Option<Vec<Point>>,
    /// Total length of the feed motions (lines, arcs, threads), mm.
    pub feed_length: Option<f64>,
    /// Total length of the rapid motions, mm.
    pub rapid_length: Option<f64>,
    /// Tolerance of the two lengths when it is not `tolerance` (arcs whose data the control
    /// evens out, paths it cuts into pieces).
    pub length_tolerance: Option<f64>,
    /// Path speed of every feed motion in order, mm/min.
    pub feeds: Option<Vec<f64>>,
    /// Total dwell, seconds.
    pub dwell_seconds: Option<f64>,
    /// The master spindle's speed at each of its events (S, M3, M4, M5), rpm, in order.
    pub speeds: Option<Vec<f64>>,
    /// Tolerance of positions, mm (0.001 when not given).
    pub tolerance: Option<f64>,
}

impl Expected {
    /// True when the entry checks a position or a path.
    pub fn asserts(&self) -> bool {
        self.end.is_some()
            || self.points.is_some()
            || self.visits.is_some()
            || self.feed_length.is_some()
            || self.rapid_length.is_some()
            || self.dwell_seconds.is_some()
    }

    /// What in `segments` differs from the expectation, one line each; `start` is the machine
    /// position before the first motion.
    pub fn check(&self, segments: &[Segment], start: [f64; 6]) -> Vec<String> {
        let mut failures = Vec::new();
        let tolerance = self.tolerance.unwrap_or(0.001);
        let motions: Vec<[f64; 6]> = segments
            .iter()
            .filter_map(|s| s.motion().map(|m| m.to.0))
            .collect();
        let last = motions.last().copied().unwrap_or(start);
        if let Some(end) = self.end {
            for (i, expected) in end.axes() {
                if let Some(expected) = expected {
                    if !close(last[i], expected, tolerance) {
                        failures.push(format!(
                            "end {} is {:.4}, expected {expected}",
                            letter(i),
                            last[i]
                        ));
                    }
                }
            }
        }
        if let Some(points) = &self.points {
            if points.len() != motions.len() {
                failures.push(format!(
                    "{} motions, expected {}: {:?}",
                    motions.len(),
                    points.len(),
                    motions
                ));
            } else {
                for (k, (point, actual)) in points.iter().zip(&motions).enumerate() {
                    for (i, expected) in point.axes() {
                        if let Some(expected) = expected {
                            if !close(actual[i], expected, tolerance) {
                                failures.push(format!(
                                    "motion {} {} is {:.4}, expected {expected}",
                                    k + 1,
                                    letter(i),
                                    actual[i]
                                ));
                            }
                        }
                    }
                }
            }
        }
        if let Some(visits) = &self.visits {
            let mut next = 0;
            for (k, point) in visits.iter().enumerate() {
                match motions[next..]
                    .iter()
                    .position(|m| point.matches(m, tolerance))
                {
                    Some(i) => next += i + 1,
                    None => failures.push(format!(
                        "visit {} {point:?} is not reached after visit {k}",
                        k + 1
                    )),
                }
            }
        }
        let length_tolerance = self.length_tolerance.unwrap_or(tolerance.max(0.001));
        let total = |rapid: bool| -> f64 {
            segments
                .iter()
                .filter(|s| {
                    matches!(s.kind, SegmentKind::Rapid { .. }) == rapid && s.motion().is_some()
                })
                .map(|s| s.length())
                .sum()
        };
        for (expected, rapid, what) in [
            (self.feed_length, false, "feed"),
            (self.rapid_length, true, "rapid"),
        ] {
            if let Some(expected) = expected {
                let actual = total(rapid);
                if !close(actual, expected, length_tolerance) {
                    failures.push(format!("{what} length {actual:.4}, expected {expected}"));
                }
            }
        }
        if let Some(expected) = &self.feeds {
            let actual: Vec<Option<f64>> = segments
                .iter()
                .filter_map(|s| match &s.kind {
                    SegmentKind::Line { feed, .. } | SegmentKind::Arc { feed, .. } => {
                        Some(feed.mm_per_min(s.length()))
                    }
                    _ => None,
                })
                .collect();
            if !same_values(&actual, expected) {
                failures.push(format!("feeds {actual:?}, expected {expected:?} mm/min"));
            }
        }
        if let Some(expected) = &self.speeds {
            let actual: Vec<Option<f64>> = segments
                .iter()
                .filter_map(|s| match s.kind {
                    SegmentKind::Spindle { speed, .. } => Some(Some(speed)),
                    _ => None,
                })
                .collect();
            if !same_values(&actual, expected) {
                failures.push(format!(
                    "spindle speeds {actual:?}, expected {expected:?} rpm"
                ));
            }
        }
        if let Some(expected) = self.dwell_seconds {
            let dwell: f64 = segments
                .iter()
                .map(|s| match s.kind {
                    SegmentKind::Dwell { seconds } => seconds,
                    _ => 0.0,
                })
                .sum();
            if !close(dwell, expected, 1e-6) {
                failures.push(format!("dwell {dwell} s, expected {expected}"));
            }
        }
        failures
    }
}

/// The same number of values, each within a millionth of the expected one (of 1 near 0).
fn same_values(actual: &[Option<f64>], expected: &[f64]) -> bool {
    actual.len() == expected.len()
        && actual
            .iter()
            .zip(expected)
            .all(|(a, e)| a.is_some_and(|a| close(a, *e, 1e-6 * e.abs().max(1.0))))
}
