//! A consumer of the motion stream that sums up a run: path lengths, a first estimate of the
//! time (length / feed and rapid rates, before the planner exists), extents in machine and
//! program coordinates, tools used.

use crate::machine::{Machine, AXES};
use crate::motion::{arc_sweep, ArcDirection, Move, Plane, Segment, SegmentKind};
use std::collections::BTreeSet;

/// An axis-aligned box over X Y Z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Extents {
    /// Lowest X Y Z.
    pub min: [f64; 3],
    /// Highest X Y Z.
    pub max: [f64; 3],
}

impl Extents {
    fn empty() -> Extents {
        Extents {
            min: [f64::INFINITY; 3],
            max: [f64::NEG_INFINITY; 3],
        }
    }

    fn add(&mut self, p: [f64; 3]) {
        for ((min, max), v) in self.min.iter_mut().zip(&mut self.max).zip(p) {
            *min = min.min(v);
            *max = max.max(v);
        }
    }

    /// True when no point was added.
    pub fn is_empty(&self) -> bool {
        self.min[0] > self.max[0]
    }
}

/// Totals of a run.
#[derive(Clone, Debug)]
pub struct Summary {
    /// Rapid moves.
    pub rapid_moves: u64,
    /// Cutting moves (lines and arcs).
    pub feed_moves: u64,
    /// Rapid path length, mm.
    pub rapid_length: f64,
    /// Cutting path length, mm.
    pub feed_length: f64,
    /// Rapid time at the machine's rapid rates, seconds.
    pub rapid_seconds: f64,
    /// Cutting time at the programmed feeds, seconds.
    pub feed_seconds: f64,
    /// Dwell time, seconds.
    pub dwell_seconds: f64,
    /// Cutting moves whose feed is unknown (G95 without spindle speed): not in `feed_seconds`.
    pub untimed_moves: u64,
    /// Extents of all motion, machine coordinates.
    pub machine_extents: Extents,
    /// Extents of all motion, program coordinates.
    pub work_extents: Extents,
    /// Extents of cutting motion only, program coordinates.
    pub cutting_extents: Extents,
    /// Tools put in the spindle (M06).
    pub tools: BTreeSet<u32>,
    /// Tool changes.
    pub tool_changes: u64,
    rapid_rates: [f64; AXES],
}

impl Summary {
    /// An empty summary for a run on `machine`.
    pub fn new(machine: &Machine) -> Summary {
        let rapid_rates =
            std::array::from_fn(|i| machine.axes[i].as_ref().map_or(f64::INFINITY, |a| a.rapid));
        Summary {
            rapid_moves: 0,
            feed_moves: 0,
            rapid_length: 0.0,
            feed_length: 0.0,
            rapid_seconds: 0.0,
            feed_seconds: 0.0,
            dwell_seconds: 0.0,
            untimed_moves: 0,
            machine_extents: Extents::empty(),
            work_extents: Extents::empty(),
            cutting_extents: Extents::empty(),
            tools: BTreeSet::new(),
            tool_changes: 0,
            rapid_rates,
        }
    }

    /// Length / feed, rapid and dwell time together, seconds.
    pub fn estimated_seconds(&self) -> f64 {
        self.rapid_seconds + self.feed_seconds + self.dwell_seconds
    }

    /// Adds one segment.
    pub fn add(&mut self, segment: &Segment) {
        let length = segment.length();
        match &segment.kind {
            SegmentKind::Rapid { motion, .. } => {
                self.rapid_moves += 1;
                self.rapid_length += length;
                // Each axis at most at its rapid rate: the slowest axis sets the time, whether the
                // axes interpolate or not.
                let minutes = (0..AXES)
                    .map(|i| (motion.to.0[i] - motion.from.0[i]).abs() / self.rapid_rates[i])
                    .fold(0.0, f64::max);
                self.rapid_seconds += minutes * 60.0;
                self.extend(motion, None, false);
            }
            SegmentKind::Line { motion, feed } => {
                self.feed_moves += 1;
                self.feed_length += length;
                self.time_cut(feed.mm_per_min(length), length);
                self.extend(motion, None, true);
            }
            SegmentKind::Arc {
                motion,
                feed,
                center,
                direction,
                plane,
                extra_turns,
            } => {
                self.feed_moves += 1;
                self.feed_length += length;
                self.time_cut(feed.mm_per_min(length), length);
                let sweep = arc_sweep(motion, center, *direction, *plane, *extra_turns);
                self.extend(
                    motion,
                    Some((center.xyz(), *direction, *plane, sweep)),
                    true,
                );
            }
            SegmentKind::Dwell { seconds } => self.dwell_seconds += seconds,
            SegmentKind::ToolChange { tool } => {
                self.tool_changes += 1;
                self.tools.insert(*tool);
            }
            _ => {}
        }
    }

    fn time_cut(&mut self, mm_per_min: Option<f64>, length: f64) {
        match mm_per_min {
            Some(f) if f > 0.0 => self.feed_seconds += length / f * 60.0,
            _ => self.untimed_moves += 1,
        }
    }

    fn extend(
        &mut self,
        motion: &Move,
        arc: Option<([f64; 3], ArcDirection, Plane, f64)>,
        cutting: bool,
    ) {
        let offset = [motion.offset[0], motion.offset[1], motion.offset[2]];
        let mut points = vec![motion.from.xyz(), motion.to.xyz()];
        if let Some((center, direction, plane, sweep)) = arc {
            points.extend(arc_extreme_points(motion, center, direction, plane, sweep));
        }
        for p in points {
            self.machine_extents.add(p);
            let work = [p[0] - offset[0], p[1] - offset[1], p[2] - offset[2]];
            self.work_extents.add(work);
            if cutting {
                self.cutting_extents.add(work);
            }
        }
    }
}

/// The points where an arc reaches its extremes along the plane's axes (0, 90, 180, 270 degrees),
/// when they lie inside its sweep. The normal axis is taken at the start (helix ends are added
/// by the caller).
fn arc_extreme_points(
    motion: &Move,
    center: [f64; 3],
    direction: ArcDirection,
    plane: Plane,
    sweep: f64,
) -> Vec<[f64; 3]> {
    let (a, b, _) = plane.axes();
    let start = motion.from.xyz();
    let radius = (start[a] - center[a]).hypot(start[b] - center[b]);
    let start_angle = (start[b] - center[b]).atan2(start[a] - center[a]);
    let mut points = Vec::new();
    for quadrant in 0..4 {
        let angle = f64::from(quadrant) * std::f64::consts::FRAC_PI_2;
        let mut delta = match direction {
            ArcDirection::CounterClockwise => angle - start_angle,
            ArcDirection::Clockwise => start_angle - angle,
        };
        delta = delta.rem_euclid(std::f64::consts::TAU);
        if delta <= sweep {
            let mut p = start;
            p[a] = center[a] + radius * angle.cos();
            p[b] = center[b] + radius * angle.sin();
            points.push(p);
        }
    }
    points
}
