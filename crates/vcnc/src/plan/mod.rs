//! The planner: times the motion stream the way the machine moves it.
//!
//! [`Planner`] wraps the interpreter's stream (`StreamItem`) and yields every item
//! again, each segment with its start time `t` and duration `dt`. Motions get jerk-limited (or,
//! with infinite jerk, trapezoidal) speed profiles under the per-axis limits of the machine file,
//! slowed at corners in continuous mode (G64), stopped at exact stops (G61, G09, G63) and before
//! every non-motion event; events take the times the machine file gives them.
//!
//! The parts: `limits.rs` (machine limits along one segment's path), `corner.rs` (junction
//! speeds), `speed_profile.rs` (velocity profiles in closed form), `lookahead.rs` (the window and its
//! passes), `events.rs` (time of dwells, tool changes, spindle), `config.rs` (the machine file's
//! `[planner]` table, with LinuxCNC's habits as a preset), `report.rs` (where the time goes:
//! by kind, by tool, the slowest blocks).
//!
//! Invariants: the look-ahead window is the only buffer, so memory is constant on any program
//! length; items come out in the order they came in; the same input gives the same times; no
//! input makes it panic. Alarms pass through untouched and take no time; frames are not planned
//! at all (a slot in the window would shorten the look-ahead of every motion after it).
//!
//! ```
//! use vcnc::plan::{PlanOptions, Planner};
//! use vcnc::{interpret_str, Machine, Options};
//!
//! let machine = Machine::default();
//! let program = "G90 G21 G17 G61\nG1 X100. F3000.\nM30\n";
//! let stream = interpret_str(program, &machine, Options::default());
//! let mut total = 0.0;
//! for item in Planner::new(stream, &machine, PlanOptions::default()) {
//!     // Frames and warnings take no time; the segments come with theirs.
//!     if let Some(timed) = item.expect("no alarm").segment() {
//!         total = timed.t + timed.dt;
//!     }
//! }
//! // 100 mm at 50 mm/s, plus the ramps: more than length / feed.
//! assert!(total > 2.0);
//! ```

mod config;
mod corner;
mod dog_leg;
mod events;
mod limits;
mod lookahead;
mod report;
mod speed_profile;

pub(crate) use config::PlannerFile;
pub use config::{BlendRadius, BlendTurning, PlannerConfig, PlannerHabits};
pub use dog_leg::DogLeg;
pub use report::{BlockTime, TimeKind, TimeReport, SLOWEST};
pub use speed_profile::{PathLimits, SpeedProfile};

use crate::alarm::Alarm;
use crate::machine::Machine;
use crate::motion::{Feed, Item, Move, PathMode, Segment, SegmentKind, StreamItem, WorkFrame};
use corner::{Handover, MotionClass};
use events::EventClock;
use limits::{
    arc, line, per_axis_rapid_seconds, ArcPath, AxisLimits, Ends, FeedSpeeds, MotionLimits,
};
use lookahead::{time_motion, Slot, Window};
use std::collections::VecDeque;

/// The smaller of `a` and `b`, where `a` is never NaN (`b` may be: then `a`). One instruction
/// where `f64::min` takes four, to sort out a NaN on either side; the planner's hot path takes
/// a few dozen minima a segment.
#[inline(always)]
pub(crate) fn lesser(a: f64, b: f64) -> f64 {
    if b < a {
        b
    } else {
        a
    }
}

/// The greater of `a` and `b`, where `a` is never NaN (`b` may be: then `a`); see [`lesser`].
#[inline(always)]
pub(crate) fn greater(a: f64, b: f64) -> f64 {
    if b > a {
        b
    } else {
        a
    }
}

/// `value` is neither infinite nor NaN: the same as `f64::is_finite`, in two instructions of
/// the floating-point unit. (The compiler turns `is_finite` and `abs() < INFINITY` alike into
/// about seven integer instructions on the bits.) Zero times a finite number is zero, times an
/// infinite one or NaN it is NaN.
#[inline(always)]
pub(crate) fn finite(value: f64) -> bool {
    value * 0.0 == 0.0
}

/// Choices of a planning run that are not part of the machine.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanOptions {
    /// Feed override as a fraction (1.0 is 100 %); scales programmed feeds, not rapids. The axes'
    /// limits still cap the result.
    pub feed_override: f64,
}

impl Default for PlanOptions {
    fn default() -> PlanOptions {
        PlanOptions { feed_override: 1.0 }
    }
}

/// When one item of the stream runs: what the planner adds to it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Timing {
    /// Start time, seconds from the start of the program.
    pub t: f64,
    /// Duration, seconds.
    pub dt: f64,
    /// The feed could not be known (G95 without a spindle speed): timed at the axes' limit.
    pub feed_unknown: bool,
}

/// A segment with its place in time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimedSegment {
    /// The segment as the interpreter gave it.
    pub segment: Segment,
    /// Start time, seconds from the start of the program.
    pub t: f64,
    /// Duration, seconds.
    pub dt: f64,
    /// The path speed profile of an interpolated motion (None for events, per-axis rapids and
    /// motions of zero length).
    pub profile: Option<SpeedProfile>,
    /// The feed could not be known (G95 without a spindle speed): timed at the axes' limit.
    pub feed_unknown: bool,
}

impl TimedSegment {
    /// `segment` at `timing`, with its speed profile.
    pub fn new(segment: Segment, timing: Timing, profile: Option<SpeedProfile>) -> TimedSegment {
        TimedSegment {
            segment,
            t: timing.t,
            dt: timing.dt,
            profile,
            feed_unknown: timing.feed_unknown,
        }
    }

    /// Its timing, without the segment.
    pub fn timing(&self) -> Timing {
        Timing {
            t: self.t,
            dt: self.dt,
            feed_unknown: self.feed_unknown,
        }
    }
}

/// The planner's core, apart from any stream: the items of a stream go in by reference, and
/// their timings come out in the same order once they are final (a motion's when the look-ahead
/// has passed it). The caller keeps the items meanwhile, so that planning never copies a
/// segment; [`Planner`] is this with a queue of its own, as an iterator.
///
/// ```
/// use vcnc::plan::{PlanOptions, Timeline};
/// use vcnc::{interpret_str, Machine, Options};
///
/// let machine = Machine::default();
/// let items: Vec<_> = interpret_str("G1 X100. F3000.\nM30\n", &machine, Options::default())
///     .collect();
/// let mut timeline = Timeline::new(&machine, PlanOptions::default());
/// for item in &items {
///     timeline.push_item(item);
/// }
/// timeline.finish();
/// let timings: Vec<_> = std::iter::from_fn(|| timeline.next_timing()).collect();
/// // Every item has its timing but the frame of the first move, which is not planned.
/// assert_eq!(timings.len(), items.len() - 1);
/// ```
pub struct Timeline {
    window: Window,
    axes: AxisLimits,
    /// The machine file's limits, and each axis's factors of them in force (velocity,
    /// acceleration, jerk: [`SegmentKind::AxisLimits`]); `axes` is the two together.
    machine_axes: AxisLimits,
    axis_factors: [[f64; 3]; crate::machine::AXES],
    config: PlannerConfig,
    feed_override: f64,
    events: EventClock,
    clock: f64,
    speeds: FeedSpeeds,
    /// Blend arcs that left the window before the motion after them, whose time and length go
    /// to that motion (see `Slot::Blend`).
    blend: (f64, f64),
}

impl Timeline {
    /// A timeline for `machine`.
    pub fn new(machine: &Machine, options: PlanOptions) -> Timeline {
        let config = machine.planner.clone();
        let feed_override = if options.feed_override > 0.0 && options.feed_override.is_finite() {
            options.feed_override
        } else {
            1.0
        };
        Timeline {
            window: Window::new(&config),
            axes: AxisLimits::new(machine, &config),
            machine_axes: AxisLimits::new(machine, &config),
            axis_factors: [[1.0; 3]; crate::machine::AXES],
            config,
            feed_override,
            events: EventClock::default(),
            clock: 0.0,
            speeds: FeedSpeeds::default(),
            blend: (0.0, 0.0),
        }
    }

    /// [`Timeline::push_item`] for a caller whose loop does little else (the command line's
    /// trace): the commonest item, a line, is tested first by its own pattern, one comparison
    /// of the kind, where the match takes the result, the item and the kind apart in turn. (In
    /// a loop that does more, the planner's iterator, the second copy of the line's planning
    /// costs more than it saves: the loop is no longer inlined into its caller.)
    #[inline(always)]
    pub(crate) fn push_item_line_first(&mut self, item: &StreamItem) {
        if let Ok(Item::Segment(Segment {
            kind: SegmentKind::Line { motion, feed },
            ..
        })) = item
        {
            return self.push_line(motion, feed);
        }
        self.push_item(item);
    }

    /// The next item of the stream: a segment, or an alarm.
    /// A frame ([`Item::Frame`]) gets no timing: [`Timeline::next_timing`] skips it.
    #[inline(always)]
    pub fn push_item(&mut self, item: &StreamItem) {
        match item {
            Ok(Item::Segment(segment)) => self.push(segment),
            // A warning, the error: no time, no break in the motion.
            Ok(Item::Warning(_)) | Err(_) => self.push_alarm(),
            // A frame is not planned at all (it would take a place in the look-ahead window):
            // it gets no timing, and starts when the item after it does.
            Ok(Item::Frame(_)) => {}
        }
    }

    /// The next segment of the stream.
    // One match on the kind decides everything that depends on it: the limits, the class of
    // the motion for its junctions, the per-axis time of a dog-leg rapid. Each arm enters its
    // motion itself: arms that joined first would build their limits in one place and copy
    // them on.
    #[inline(always)]
    pub fn push(&mut self, segment: &Segment) {
        let (axes, config, speeds) = (&self.axes, &self.config, &mut self.speeds);
        match &segment.kind {
            SegmentKind::Line { motion, feed } => self.push_line(motion, feed),
            SegmentKind::Arc {
                motion,
                center,
                direction,
                plane,
                extra_turns,
                feed,
            } => {
                let path = ArcPath {
                    motion,
                    center,
                    direction: *direction,
                    plane: *plane,
                    extra_turns: *extra_turns,
                    feed,
                };
                let limits = arc(&path, speeds, axes, config, self.feed_override);
                self.enter_motion(motion, limits, (MotionClass::Cutting, false, None));
            }
            SegmentKind::Rapid { motion, per_axis } => {
                let limits = line(motion, None, axes, config, 1.0);
                let kind = if *per_axis {
                    let seconds = per_axis_rapid_seconds(motion, axes);
                    (MotionClass::PerAxisRapid, true, Some(seconds))
                } else {
                    (MotionClass::Rapid, true, None)
                };
                self.enter_motion(motion, limits, kind);
            }
            SegmentKind::AxisLimits {
                axis,
                velocity,
                acceleration,
                jerk,
            } => {
                // New limits hold for the motions after them, without a stop between.
                self.axis_factors[axis.index()] = [*velocity, *acceleration, *jerk];
                self.axes = self.machine_axes.scaled(&self.axis_factors);
                self.window.push_timeless();
            }
            _ => {
                // The machine stops before an event; the end of the program too.
                let seconds = self.events.seconds(&segment.kind, &self.config);
                self.window.push_event(seconds);
            }
        }
    }

    /// A straight move at a feed.
    #[inline(always)]
    fn push_line(&mut self, motion: &Move, feed: &Feed) {
        // The control locks the override at 100 % where the feed is tied to the spindle (G63
        // tapping mode, G33 threads).
        let feed_override = if motion.path_mode == PathMode::Tapping {
            1.0
        } else {
            self.feed_override
        };
        let (axes, config, speeds) = (&self.axes, &self.config, &mut self.speeds);
        let limits = line(motion, Some((feed, speeds)), axes, config, feed_override);
        self.enter_motion(motion, limits, (MotionClass::Cutting, true, None));
    }

    /// A motion with its limits enters the window; `kind` is its class for its junctions,
    /// whether it is straight, and the time of a dog-leg rapid.
    #[inline(always)]
    fn enter_motion(
        &mut self,
        motion: &Move,
        (limits, ends): (MotionLimits, Ends),
        (class, straight, per_axis_seconds): (MotionClass, bool, Option<f64>),
    ) {
        let config = &self.config;
        if limits.length > 0.0 {
            *self.window.entering_handover() =
                Handover::new(class, straight, motion, &limits, ends, config);
            self.window
                .push_motion(limits, &ends.start, per_axis_seconds, config);
        } else {
            self.window.push_timeless();
        }
    }

    /// The next item of the stream is an alarm: it takes no time and does not interrupt the
    /// motion.
    pub fn push_alarm(&mut self) {
        self.window.push_timeless();
    }

    /// The stream has ended: the machine comes to rest after its last motion, and every timing
    /// becomes final.
    pub fn finish(&mut self) {
        self.window.stop();
    }

    /// Whether [`Timeline::next_timing`] has a timing to give.
    #[inline(always)]
    pub fn has_timing(&self) -> bool {
        self.window.has_ready()
    }

    /// The timing of the oldest item pushed whose timing has not been taken, once it is final.
    // Inlined into the caller's loop, as the push is: a call each would cost more than
    // the common path of either.
    #[inline(always)]
    pub fn next_timing(&mut self) -> Option<Timing> {
        self.next_timing_and_profile().map(|(timing, _)| timing)
    }

    /// [`Timeline::next_timing`] with the speed profile of the motion (None for events,
    /// alarms, per-axis rapids and motions of zero length).
    #[inline(always)]
    pub fn next_timing_and_profile(&mut self) -> Option<(Timing, Option<SpeedProfile>)> {
        let (dt, profile, feed_unknown) = loop {
            match self.window.pop_ready()? {
                Slot::Fixed(seconds) => break (*seconds, None, false),
                Slot::Motion(planned) => {
                    let (mut profile, mut dt) = time_motion(planned);
                    if self.blend.0 > 0.0 {
                        let (seconds, length) = std::mem::take(&mut self.blend);
                        dt += seconds;
                        profile = profile.map(|p| p.with_lead_in_time(length, seconds));
                    }
                    break (dt, profile, planned.limits.feed_unknown);
                }
                Slot::Blend(planned) => {
                    let (_, seconds) = time_motion(planned);
                    self.blend.0 += seconds;
                    self.blend.1 += planned.limits.length;
                }
            }
        };
        let t = self.clock;
        self.clock += dt;
        Some((
            Timing {
                t,
                dt,
                feed_unknown,
            },
            profile,
        ))
    }
}

/// The planner over a motion stream: an iterator of timed segments and the stream's alarms.
pub struct Planner<I> {
    source: I,
    source_done: bool,
    timeline: Timeline,
    /// The items given to the timeline whose timings are not final yet, oldest first.
    waiting: VecDeque<StreamItem>,
}

impl<I: Iterator<Item = StreamItem>> Planner<I> {
    /// A planner for `machine` over `source`.
    pub fn new(source: I, machine: &Machine, options: PlanOptions) -> Planner<I> {
        let timeline = Timeline::new(machine, options);
        Planner {
            source,
            source_done: false,
            waiting: VecDeque::with_capacity(timeline.config.look_ahead + 1),
            timeline,
        }
    }

    /// The stream being planned (e.g. to ask the interpreter how many blocks it ran).
    pub fn source(&self) -> &I {
        &self.source
    }

    /// The stream being planned, taking the planner apart.
    pub fn into_source(self) -> I {
        self.source
    }
}

/// An item of the planned stream: the stream's item, a segment with its timing.
#[derive(Clone, Debug, PartialEq)]
pub enum TimedItem {
    /// A motion or an event, timed.
    Segment(TimedSegment),
    /// A new frame (it takes no time).
    Frame(WorkFrame),
    /// A warning (it takes no time).
    Warning(Alarm),
}

impl TimedItem {
    /// The stream's item again, with the segment's timing (the default for a frame or a
    /// warning, which take no time).
    pub fn into_parts(self) -> (Item, Timing) {
        match self {
            TimedItem::Segment(timed) => (Item::Segment(timed.segment), timed.timing()),
            TimedItem::Frame(frame) => (Item::Frame(frame), Timing::default()),
            TimedItem::Warning(alarm) => (Item::Warning(alarm), Timing::default()),
        }
    }

    /// The timed segment, if this is one.
    pub fn segment(&self) -> Option<&TimedSegment> {
        match self {
            TimedItem::Segment(timed) => Some(timed),
            TimedItem::Frame(_) | TimedItem::Warning(_) => None,
        }
    }
}

impl<I: Iterator<Item = StreamItem>> Iterator for Planner<I> {
    type Item = Result<TimedItem, Alarm>;

    fn next(&mut self) -> Option<Self::Item> {
        loop {
            // A frame has no timing of its own: it goes as soon as it is first.
            if let Some(Ok(Item::Frame(frame))) = self.waiting.front() {
                let frame = *frame;
                self.waiting.pop_front();
                return Some(Ok(TimedItem::Frame(frame)));
            }
            if let Some((timing, profile)) = self.timeline.next_timing_and_profile() {
                let item = self.waiting.pop_front()?;
                return Some(item.map(|item| match item {
                    Item::Segment(segment) => {
                        TimedItem::Segment(TimedSegment::new(segment, timing, profile))
                    }
                    Item::Frame(frame) => TimedItem::Frame(frame),
                    Item::Warning(alarm) => TimedItem::Warning(alarm),
                }));
            }
            if self.source_done {
                return None;
            }
            match self.source.next() {
                None => {
                    self.source_done = true;
                    self.timeline.finish();
                }
                Some(item) => {
                    self.timeline.push_item(&item);
                    self.waiting.push_back(item);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn finite_agrees_with_is_finite_on_the_special_values() {
        let values = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            f64::MAX,
            f64::MIN,
            f64::MIN_POSITIVE,
            f64::from_bits(1),
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            -f64::NAN,
        ];
        for value in values {
            assert_eq!(finite(value), value.is_finite(), "{value}");
        }
    }

    proptest! {
        #[test]
        fn finite_agrees_with_is_finite_on_any_bits(bits in any::<u64>()) {
            let value = f64::from_bits(bits);
            prop_assert_eq!(finite(value), value.is_finite());
        }
    }
}
