//! The planner: times the motion stream the way the machine moves it.
//!
//! [`Planner`] wraps the interpreter's stream (`Result<Segment, Alarm>`) and yields every item
//! again, each segment with its start time `t` and duration `dt`. Motions get jerk-limited (or,
//! with infinite jerk, trapezoidal) speed profiles under the per-axis limits of the machine file,
//! slowed at corners in continuous mode (G64), stopped at exact stops (G61, G09, G63) and before
//! every non-motion event; events take the times the machine file gives them.
//!
//! The parts: `limits.rs` (machine limits along one segment's path), `corner.rs` (junction
//! speeds), `profile.rs` (velocity profiles in closed form), `lookahead.rs` (the window and its
//! passes), `events.rs` (time of dwells, tool changes, spindle), `config.rs` (the machine file's
//! `[planner]` table, with LinuxCNC's habits as a preset), `report.rs` (where the time goes:
//! by kind, by tool, the slowest blocks).
//!
//! Invariants: the look-ahead window is the only buffer, so memory is constant on any program
//! length; items come out in the order they came in; the same input gives the same times; no
//! input makes it panic. Alarms pass through untouched and take no time.
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
//!     let timed = item.expect("no alarm");
//!     total = timed.t + timed.dt;
//! }
//! // 100 mm at 50 mm/s, plus the ramps: more than length / feed.
//! assert!(total > 2.0);
//! ```

mod config;
mod corner;
mod events;
mod limits;
mod lookahead;
mod profile;
mod report;

pub(crate) use config::PlannerFile;
pub use config::{PlannerConfig, PlannerHabits};
pub use profile::{PathLimits, Profile};
pub use report::{BlockTime, TimeKind, TimeReport, SLOWEST};

use crate::alarm::Alarm;
use crate::machine::Machine;
use crate::motion::Segment;
use events::EventClock;
use limits::{AxisLimits, MotionLimits};
use lookahead::{time_motion, Window};

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
    pub profile: Option<Profile>,
    /// The feed could not be known (G95 without a spindle speed): timed at the axes' limit.
    pub feed_unknown: bool,
}

/// The planner over a motion stream: an iterator of timed segments and the stream's alarms.
pub struct Planner<I> {
    source: I,
    source_done: bool,
    window: Window,
    /// An event waiting until the motions before it have left.
    pending_event: Option<Segment>,
    axes: AxisLimits,
    config: PlannerConfig,
    feed_override: f64,
    events: EventClock,
    clock: f64,
}

impl<I: Iterator<Item = Result<Segment, Alarm>>> Planner<I> {
    /// A planner for `machine` over `source`.
    pub fn new(source: I, machine: &Machine, options: PlanOptions) -> Planner<I> {
        let config = machine.planner.clone();
        let feed_override = if options.feed_override > 0.0 && options.feed_override.is_finite() {
            options.feed_override
        } else {
            1.0
        };
        Planner {
            source,
            source_done: false,
            window: Window::new(config.look_ahead),
            pending_event: None,
            axes: AxisLimits::new(machine, &config),
            config,
            feed_override,
            events: EventClock::default(),
            clock: 0.0,
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

    fn pull(&mut self) {
        match self.source.next() {
            None => {
                self.source_done = true;
                self.window.stop();
            }
            Some(Err(alarm)) => self.window.push_alarm(alarm),
            Some(Ok(segment)) if segment.motion().is_some() => {
                let limits =
                    MotionLimits::of(&segment, &self.axes, &self.config, self.feed_override);
                self.window.push_motion(segment, limits, &self.config);
            }
            Some(Ok(segment)) => {
                // The machine stops before an event; the end of the program too.
                self.window.stop();
                self.pending_event = Some(segment);
            }
        }
    }

    fn timed(&mut self, segment: Segment, dt: f64, profile: Option<Profile>) -> TimedSegment {
        let t = self.clock;
        self.clock += dt;
        TimedSegment {
            segment,
            t,
            dt,
            profile,
            feed_unknown: false,
        }
    }
}

impl<I: Iterator<Item = Result<Segment, Alarm>>> Iterator for Planner<I> {
    type Item = Result<TimedSegment, Alarm>;

    fn next(&mut self) -> Option<Self::Item> {
        loop {
            if let Some(slot) = self.window.pop_ready() {
                let segment = match slot.item {
                    Ok(segment) => segment,
                    Err(alarm) => return Some(Err(*alarm)),
                };
                let Some(planned) = slot.planned else {
                    return Some(Ok(self.timed(segment, 0.0, None)));
                };
                let (profile, dt) = time_motion(&segment, &planned, &self.axes);
                let mut timed = self.timed(segment, dt, profile);
                timed.feed_unknown = planned.limits.feed_unknown;
                return Some(Ok(timed));
            }
            if let Some(event) = self.pending_event.take() {
                let dt = self.events.seconds(&event.kind, &self.config);
                return Some(Ok(self.timed(event, dt, None)));
            }
            if self.source_done {
                return None;
            }
            self.pull();
        }
    }
}
