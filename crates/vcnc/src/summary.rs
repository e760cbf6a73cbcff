//! A consumer of the motion stream that sums up a run: path lengths, a first estimate of the
//! time (length / feed and rapid rates, before the planner exists), extents in machine and
//! program coordinates, tools used.

use crate::machine::{Machine, AXES};
use crate::motion::{
    arc_sweep, helix_length, ArcDirection, MachinePos, Move, Plane, Segment, SegmentKind,
};
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

    #[inline]
    fn add(&mut self, p: [f64; 3]) {
        for ((min, max), v) in self.min.iter_mut().zip(&mut self.max).zip(p) {
            // Plain comparisons (a NaN changes nothing): cheaper than f64::min and max.
            if v < *min {
                *min = v;
            }
            if v > *max {
                *max = v;
            }
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
    /// Where the last move ended, its offset and whether it cut.
    last_end: Option<(MachinePos, [f64; AXES], bool)>,
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
            last_end: None,
        }
    }

    /// Length / feed, rapid and dwell time together, seconds.
    pub fn estimated_seconds(&self) -> f64 {
        self.rapid_seconds + self.feed_seconds + self.dwell_seconds
    }

    /// Adds one segment.
    pub fn add(&mut self, segment: &Segment) {
        match &segment.kind {
            SegmentKind::Rapid { motion, .. } => {
                let length = motion.from.distance_xyz(&motion.to);
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
                let length = motion.from.distance_xyz(&motion.to);
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
                // The sweep once, for the length and the extremes (each takes two atan2).
                let sweep = arc_sweep(motion, center, *direction, *plane, *extra_turns);
                let length = helix_length(motion, center, *plane, sweep);
                self.feed_moves += 1;
                self.feed_length += length;
                self.time_cut(feed.mm_per_min(length), length);
                self.extend(
                    motion,
                    Some((center.xyz(), *direction, *plane, sweep)),
                    true,
                );
            }
            SegmentKind::Dwell { seconds } => self.dwell_seconds += seconds,
            SegmentKind::ToolChange { tool, .. } => {
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
        // A move starts where the last one ended (in the same program coordinates, mostly): that
        // point is in the extents already.
        let continues = self.last_end == Some((motion.from, motion.offset, cutting));
        if !continues {
            self.extend_point(motion, motion.from.xyz(), cutting);
        }
        self.extend_point(motion, motion.to.xyz(), cutting);
        self.last_end = Some((motion.to, motion.offset, cutting));
        if let Some((center, direction, plane, sweep)) = arc {
            crate::motion::for_arc_extreme_points(motion, center, direction, plane, sweep, |p| {
                self.extend_point(motion, p, cutting)
            });
        }
    }

    /// Adds a point in machine coordinates of `motion` to the extents.
    #[inline]
    fn extend_point(&mut self, motion: &Move, p: [f64; 3], cutting: bool) {
        self.machine_extents.add(p);
        let work = [
            p[0] - motion.offset[0],
            p[1] - motion.offset[1],
            p[2] - motion.offset[2],
        ];
        self.work_extents.add(work);
        if cutting {
            self.cutting_extents.add(work);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{interpret_str, Options};

    fn summary_of(program: &str) -> Summary {
        let machine = Machine::default();
        let mut summary = Summary::new(&machine);
        for item in interpret_str(program, &machine, Options::default()) {
            summary.add(&item.expect("no alarm"));
        }
        summary
    }

    #[test]
    fn extents_take_the_arc_extremes_inside_the_sweep() {
        // A half circle from (10, 0) counter-clockwise round (0, 0) to (-10, 0): it reaches
        // Y 10 at 90 degrees, never Y -10.
        let s = summary_of("G90 G17 G54 G0 X10. Y0 Z0\nG3 X-10. Y0 I-10. J0 F100.\nM30\n");
        let e = s.work_extents;
        assert!((e.max[1] - 10.0).abs() < 1e-12, "{e:?}");
        assert!(e.min[1].abs() < 1e-12, "{e:?}");
        assert!((e.min[0] + 10.0).abs() < 1e-12 && (e.max[0] - 10.0).abs() < 1e-12);
        let c = s.cutting_extents;
        assert!(
            (c.max[1] - 10.0).abs() < 1e-12 && c.min[1].abs() < 1e-12,
            "{c:?}"
        );
        assert!((s.feed_length - 10.0 * std::f64::consts::PI).abs() < 1e-9);
    }

    #[test]
    fn extents_count_the_start_of_a_cut_after_a_rapid_and_each_offset() {
        // The cut starts where the rapid ended: that point belongs to the cutting extents too.
        let s = summary_of("G90 G54 G0 X5. Y5. Z0\nG1 X6. F100.\nG52 X100.\nG1 X7.\nM30\n");
        assert_eq!(s.cutting_extents.max[0], 7.0);
        // After G52 the tool stands at X-94. of the shifted program coordinates: the last cut
        // starts there.
        assert_eq!(s.cutting_extents.min[0], -94.0);
        assert_eq!(s.work_extents.max[0], 7.0);
    }
}
