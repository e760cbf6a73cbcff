//! A consumer of the motion stream that sums up a run: path lengths, a first estimate of the
//! time (length / feed and rapid rates, before the planner exists), extents in machine and
//! program coordinates, tools used, and the warnings only the whole stream shows: cutting with
//! the spindle stopped, a speed above the machine's (`V102`, `V103`). It never changes the
//! stream and never stops it.

use crate::alarm::{Alarm, AlarmCode};
use crate::machine::{Machine, AXES};
use crate::motion::{
    arc_sweep, helix_length, ArcDirection, Item, MachinePos, Move, Plane, ProgramMap, Segment,
    SegmentKind, SpindleState, WorkFrame,
};
use crate::source::Span;
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

    /// The box for people, in `unit` (the extents are kept in mm):
    /// `X 0.0000 .. 2.0000  Y 0.0000 .. 1.0000  Z -0.5000 .. 0.1000 in`.
    pub fn describe(&self, unit: LengthUnit) -> String {
        if self.is_empty() {
            return "no motion".to_string();
        }
        let axes = |scale: f64, digits: usize| {
            let (min, max) = (self.min, self.max);
            format!(
                "X {:.digits$} .. {:.digits$}  Y {:.digits$} .. {:.digits$}  Z {:.digits$} .. {:.digits$}",
                min[0] / scale, max[0] / scale, min[1] / scale, max[1] / scale, min[2] / scale, max[2] / scale
            )
        };
        match unit {
            LengthUnit::Millimetre => format!("{} mm", axes(1.0, 3)),
            LengthUnit::Inch => format!("{} in", axes(25.4, 4)),
        }
    }
}

/// The unit a program is written in (G20 or G21), for showing its lengths as its author reads
/// them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LengthUnit {
    /// G21.
    #[default]
    Millimetre,
    /// G20.
    Inch,
}

impl LengthUnit {
    /// `mm` or `in`.
    pub fn as_str(self) -> &'static str {
        match self {
            LengthUnit::Millimetre => "mm",
            LengthUnit::Inch => "in",
        }
    }
}

/// The spindle as far as the stream shows it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Spindle {
    Running,
    /// At power-on, after M05 or M19.
    Stopped,
    /// After an M code that only the machine knows: many machines start the spindle with M13 or
    /// M14 (and the coolant with it), so nothing is said until M03, M04 or M05.
    Unknown,
}

/// The first place a warning applies, and how often it did.
#[derive(Clone, Copy, Debug, Default)]
struct Occurrences {
    first: Option<Span>,
    count: u64,
    /// The largest value seen (the speed, for `S` above the maximum).
    largest: f64,
}

impl Occurrences {
    fn add(&mut self, span: Span, value: f64) {
        self.first.get_or_insert(span);
        self.count += 1;
        self.largest = self.largest.max(value);
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
    /// Extents of all motion, program coordinates: X and Y in the frame in force at the first
    /// move, so that a pattern repeated under G52, G92 or G68 (a thread milled at four places,
    /// holes on a bolt circle) is measured where it is cut, not stacked on its local zero; Z
    /// in each move's own frame (its zero, tool length and rotation). Points are taken back
    /// through the whole frame ([`Item::Frame`]) when the stream's frames are added
    /// ([`Summary::add_item`]); a consumer that adds segments alone gets each move's
    /// translation ([`Move::offset`]), which is right for lines and arcs that nothing turns.
    pub work_extents: Extents,
    /// Extents of cutting motion only, program coordinates as [`Summary::work_extents`].
    pub cutting_extents: Extents,
    /// Tools put in the spindle (M06).
    pub tools: BTreeSet<u32>,
    /// Tool changes.
    pub tool_changes: u64,
    rapid_rates: [f64; AXES],
    /// The map back of the frame in force at the first move: the X and Y the program extents
    /// keep.
    first_frame: Option<ProgramMap>,
    /// The map back of the frame in force, when the stream told it.
    frame: Option<ProgramMap>,
    /// Where the last move ended, its offset and whether it cut.
    last_end: Option<(MachinePos, [f64; AXES], bool)>,
    spindle: Spindle,
    max_rpm: f64,
    cuts_with_spindle_stopped: Occurrences,
    speeds_above_maximum: Occurrences,
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
            first_frame: None,
            frame: None,
            last_end: None,
            spindle: Spindle::Stopped,
            max_rpm: machine.spindle.max_rpm,
            cuts_with_spindle_stopped: Occurrences::default(),
            speeds_above_maximum: Occurrences::default(),
        }
    }

    /// The warnings of the whole run, one per kind at its first place, with the count: cutting
    /// moves while the spindle is stopped (V102), spindle speeds above the machine's `max_rpm`
    /// (V103).
    pub fn warnings(&self) -> Vec<Alarm> {
        let mut warnings = Vec::new();
        let times = |n: u64| {
            if n == 1 {
                "once".to_string()
            } else {
                format!("{n} times")
            }
        };
        let stopped = &self.cuts_with_spindle_stopped;
        if let Some(span) = stopped.first {
            warnings.push(
                Alarm::warning(
                    AlarmCode::CuttingWithSpindleStopped,
                    span,
                    format!(
                        "cutting with the spindle stopped ({} cutting move{}): no M03 or M04 since the start or the last M05",
                        stopped.count,
                        if stopped.count == 1 { "" } else { "s" }
                    ),
                )
                .with_help("start the spindle (`S_ M03`) before the first cut"),
            );
        }
        let fast = &self.speeds_above_maximum;
        if let Some(span) = fast.first {
            warnings.push(
                Alarm::warning(
                    AlarmCode::SpindleSpeedAboveMaximum,
                    span,
                    format!(
                        "the spindle speed is above the machine's maximum of {} rpm ({}, up to S{})",
                        self.max_rpm,
                        times(fast.count),
                        fast.largest
                    ),
                )
                .with_help("the control clamps the speed or refuses it; the machine file's [spindle] max_rpm gives the maximum"),
            );
        }
        warnings
    }

    /// Length / feed, rapid and dwell time together, seconds.
    pub fn estimated_seconds(&self) -> f64 {
        self.rapid_seconds + self.feed_seconds + self.dwell_seconds
    }

    /// Adds one item of the stream: a segment, a frame (for the program extents), a warning
    /// (nothing).
    pub fn add_item(&mut self, item: &Item) {
        match item {
            Item::Segment(segment) => self.add(segment),
            Item::Frame(frame) => self.add_frame(frame),
            Item::Warning(_) => {}
        }
    }

    /// A new frame: the moves after it are made in it.
    pub fn add_frame(&mut self, frame: &WorkFrame) {
        self.frame = Some(frame.transform.program_map());
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
                self.check_spindle_cuts(segment.span);
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
                self.check_spindle_cuts(segment.span);
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
            SegmentKind::Spindle { state, speed } => {
                self.spindle = match state {
                    SpindleState::Clockwise | SpindleState::CounterClockwise => Spindle::Running,
                    SpindleState::Stopped | SpindleState::Oriented => Spindle::Stopped,
                };
                if self.spindle == Spindle::Running && *speed > self.max_rpm {
                    self.speeds_above_maximum.add(segment.span, *speed);
                }
            }
            SegmentKind::Auxiliary { .. } if self.spindle == Spindle::Stopped => {
                self.spindle = Spindle::Unknown;
            }
            _ => {}
        }
    }

    #[inline]
    fn check_spindle_cuts(&mut self, span: Span) {
        if self.spindle == Spindle::Stopped {
            self.cuts_with_spindle_stopped.add(span, 0.0);
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
        // Without the stream's frames, the move's own translation (it holds at its end point
        // only under a rotation).
        let here = self
            .frame
            .unwrap_or_else(|| ProgramMap::shift(&motion.offset));
        let first = *self.first_frame.get_or_insert(here);
        let (planar, depth) = (first.to_program(p), here.to_program(p));
        let work = [planar[0], planar[1], depth[2]];
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
            summary.add_item(&item.expect("no alarm"));
        }
        summary
    }

    fn warnings_of(program: &str) -> Vec<(AlarmCode, u32, String)> {
        summary_of(program)
            .warnings()
            .into_iter()
            .map(|a| (a.code, a.span.map_or(0, |s| s.line), a.message))
            .collect()
    }

    #[test]
    fn cutting_with_the_spindle_stopped_is_warned_once_at_the_first_cut() {
        let w = warnings_of("G90 G0 X0 Y0\nG1 X10. F100.\nX20.\nS1000 M3\nX30.\nM5\nX40.\nM30\n");
        assert_eq!(w.len(), 1, "{w:?}");
        assert_eq!((w[0].0, w[0].1), (AlarmCode::CuttingWithSpindleStopped, 2));
        assert!(w[0].2.contains("(3 cutting moves)"), "{w:?}");
        assert!(warnings_of("S1000 M3\nG1 X10. F100.\nM30\n").is_empty());
        // M13 starts the spindle on many machines: after an M code only the machine knows,
        // nothing is said.
        assert!(warnings_of("S1000 M13\nG1 X10. F100.\nM30\n").is_empty());
    }

    #[test]
    fn a_speed_above_the_machines_maximum_is_warned() {
        // The default machine turns at most 12000 rpm.
        assert_eq!(Machine::default().spindle.max_rpm, 12000.0);
        let w = warnings_of("S15000 M3\nG1 X10. F100.\nS20000\nS8000\nM30\n");
        assert_eq!(w.len(), 1, "{w:?}");
        assert_eq!((w[0].0, w[0].1), (AlarmCode::SpindleSpeedAboveMaximum, 1));
        assert!(w[0].2.contains("2 times, up to S20000"), "{w:?}");
    }

    #[test]
    fn extents_are_described_in_the_programs_unit() {
        let s = summary_of("G90 G0 X0 Y0 Z0\nG1 X25.4 Y-12.7 F100.\nM30\n");
        assert_eq!(
            s.cutting_extents.describe(LengthUnit::Inch),
            "X 0.0000 .. 1.0000  Y -0.5000 .. 0.0000  Z 0.0000 .. 0.0000 in"
        );
        assert!(s
            .cutting_extents
            .describe(LengthUnit::Millimetre)
            .ends_with("Z 0.000 .. 0.000 mm"));
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
    fn extents_count_the_start_of_a_cut_after_a_rapid() {
        // The cut starts where the rapid ended: that point belongs to the cutting extents too.
        let s = summary_of("G90 G54 G0 X5. Y5. Z0\nG1 X6. F100.\nM30\n");
        assert_eq!(s.cutting_extents.min[0], 5.0);
        assert_eq!(s.cutting_extents.max[0], 6.0);
    }

    #[test]
    fn a_pattern_repeated_under_g52_is_measured_where_it_is_cut() {
        // A circle of radius 1.6 milled about two local zeros, 97.5 mm each side of the
        // part's: the cut spans +-99.1, not +-1.6.
        let circle = "G0 X0 Y0\nG1 Z-1. F300.\nG1 X1.6\nG3 I-1.6\nG0 Z5.\n";
        let program = format!(
            "G90 G17 G54 G0 X0 Y0 Z5.\nG52 X97.5\n{circle}G52 X-97.5\n{circle}G52 X0\nM30\n"
        );
        let s = summary_of(&program);
        let c = s.cutting_extents;
        assert!(
            (c.min[0] + 99.1).abs() < 1e-9 && (c.max[0] - 99.1).abs() < 1e-9,
            "{c:?}"
        );
        assert!(
            (c.min[1] + 1.6).abs() < 1e-9 && (c.max[1] - 1.6).abs() < 1e-9,
            "{c:?}"
        );
    }

    #[test]
    fn holes_on_a_circle_turned_with_g68_are_measured_where_they_are_drilled() {
        // The same hole at X50 turned by 0, 90, 180 and 270 degrees: the holes lie on a circle
        // of radius 50, not all at X50 Y0.
        let mut program = String::from("G90 G17 G54 G0 X0 Y0 Z5.\n");
        for angle in [0, 90, 180, 270] {
            program.push_str(&format!(
                "G68 X0 Y0 R{angle}.\nG0 X50. Y0\nG1 Z-2. F100.\nG0 Z5.\nG69\n"
            ));
        }
        program.push_str("M30\n");
        let c = summary_of(&program).cutting_extents;
        for (got, want) in c.min[..2].iter().zip([-50.0, -50.0]) {
            assert!((got - want).abs() < 1e-9, "{c:?}");
        }
        for (got, want) in c.max[..2].iter().zip([50.0, 50.0]) {
            assert!((got - want).abs() < 1e-9, "{c:?}");
        }
    }
}
