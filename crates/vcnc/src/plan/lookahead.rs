//! The look-ahead window: the planner's only buffer, and the passes that set entry speeds.
//!
//! Motions enter at the back with the highest speed their junction with the previous motion
//! allows. When the window is full, a backward pass (assuming the machine must be able to stop
//! at the window's end) and a forward pass (from the speed already fixed at the window's front)
//! give every motion the highest entry speed that is reachable both ways; the first half is then
//! final and leaves the window. Before an event (which stops the motion) and at the end of the
//! stream the window ends in a real stop and all of it leaves.
//!
//! Why half: a motion that leaves has been planned with at least half a window of look-ahead
//! behind it. The forward pass runs over the released half only, and the backward pass stops
//! where its values stop changing, so the work per segment stays small and constant. Why the front speed never has to drop: the stop assumed at the old
//! window end is the tightest condition there is, so a longer window only allows more.
//!
//! Alarms and zero-length motions sit in the window in stream order and take no time; they do
//! not break a chain of motions.

use super::config::PlannerConfig;
use super::corner::{junction, Handover};
use super::limits::{MotionLimits, Tangents};
use super::profile::{reachable_speed_up_to, Profile};
use super::{greater, lesser};
use crate::motion::{Move, Segment};
use std::collections::VecDeque;

/// A motion's place in the plan.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Planned {
    pub(crate) limits: MotionLimits,
    /// The blend arc from the previous motion, passed at the entry speed before the segment's
    /// own (shortened) path, mm.
    pub(crate) lead_in: f64,
    /// Highest entry speed the junction with the previous motion allows.
    max_entry: f64,
    /// Highest entry speed that can still stop at the window's end (NaN until first planned).
    backward: f64,
    /// Planned entry and exit speeds, mm/s.
    pub(crate) entry: f64,
    pub(crate) exit: f64,
    /// The duration of a rapid with each axis at its own rate, which the path speeds do not
    /// time (they only make its neighbours stop).
    pub(crate) per_axis_seconds: Option<f64>,
}

/// One item of the window. The window holds only what timing needs: the segments themselves
/// stay with the caller, in the same order (see [`super::Timeline`]), so that a slot is small
/// to move and a segment is never copied for planning.
pub(crate) enum Slot {
    /// A motion being planned.
    Motion(Planned),
    /// An item whose duration is known when it enters: an event, an alarm, a motion of zero
    /// length.
    Fixed(f64),
}
pub(crate) struct Window {
    slots: VecDeque<Slot>,
    capacity: usize,
    /// Slots at the front whose speeds are final.
    ready: usize,
    /// Speed at the start of the first motion in the window (the last one that left ends there).
    start_speed: f64,
    /// How the last motion that entered ends, for the junction with the next; None after a stop.
    last: Option<Handover>,
}

impl Window {
    pub(crate) fn new(capacity: usize) -> Window {
        let capacity = capacity.max(2);
        Window {
            slots: VecDeque::with_capacity(capacity + 1),
            capacity,
            ready: 0,
            start_speed: 0.0,
            last: None,
        }
    }

    /// A final slot, if one is ready.
    pub(crate) fn pop_ready(&mut self) -> Option<Slot> {
        if self.ready == 0 {
            return None;
        }
        self.ready -= 1;
        let slot = self.slots.pop_front()?;
        if let Slot::Motion(planned) = &slot {
            self.start_speed = planned.exit;
        }
        Some(slot)
    }

    /// Adds an item that takes no time and does not interrupt the motion (an alarm).
    pub(crate) fn push_timeless(&mut self) {
        self.slots.push_back(Slot::Fixed(0.0));
        self.release_if_full();
    }

    /// Adds an event that takes `seconds`: the machine comes to rest before it, so the window
    /// is planned to a stop, and the event is final at once.
    pub(crate) fn push_event(&mut self, seconds: f64) {
        self.stop();
        self.slots.push_back(Slot::Fixed(seconds));
        self.ready += 1;
    }

    /// Adds a motion with its limits (None: a motion of zero length); `per_axis_seconds` is the
    /// duration of a rapid with each axis at its own rate.
    pub(crate) fn push_motion(
        &mut self,
        segment: &Segment,
        motion: &Move,
        limits: Option<(MotionLimits, Tangents)>,
        per_axis_seconds: Option<f64>,
        config: &PlannerConfig,
    ) {
        let planned = match limits {
            Some((mut limits, tangents)) if limits.length > 0.0 => {
                let handover = Handover::new(segment, motion, &limits, tangents);
                let mut max_entry = 0.0;
                let mut lead_in = 0.0;
                if let Some(prev) = &self.last {
                    let junction = junction(prev, &handover, config);
                    max_entry = lesser(lesser(prev.cruise, junction.speed), limits.cruise);
                    limits.length = greater(0.0, limits.length - junction.leg);
                    lead_in = junction.arc;
                    let stop_factor = if junction.corner_stop {
                        config.stop_acceleration_factor
                    } else {
                        1.0
                    };
                    limits.scale_acceleration(stop_factor);
                    if let Some(prev) = self.last_planned() {
                        prev.limits.length = greater(0.0, prev.limits.length - junction.leg);
                        prev.limits.scale_acceleration(stop_factor);
                    }
                }
                self.last = Some(handover);
                Slot::Motion(Planned {
                    limits,
                    lead_in,
                    max_entry,
                    backward: f64::NAN,
                    entry: 0.0,
                    exit: 0.0,
                    per_axis_seconds,
                })
            }
            _ => Slot::Fixed(0.0),
        };
        self.slots.push_back(planned);
        self.release_if_full();
    }

    fn last_planned(&mut self) -> Option<&mut Planned> {
        // Almost always the last slot; a search only behind an alarm or a zero-length motion.
        if let Some(Slot::Motion(_)) = self.slots.back() {
            return self.slots.back_mut().and_then(Slot::planned);
        }
        self.slots.iter_mut().rev().find_map(Slot::planned)
    }

    /// The motion comes to rest here (an event, or the end of the stream): everything in the
    /// window becomes final. The last motion did not blend into another, so it gets the
    /// unblended acceleration.
    pub(crate) fn stop(&mut self) {
        if let Some(last) = self.last_planned() {
            last.limits.path.acceleration = last.limits.unblended_acceleration;
        }
        self.plan(self.slots.len());
        self.last = None;
    }

    fn release_if_full(&mut self) {
        if self.slots.len() >= self.capacity && self.ready == 0 {
            self.plan(self.slots.len() / 2);
        }
    }

    /// Plans the window and makes its first `release` slots final.
    fn plan(&mut self, release: usize) {
        self.backward_pass();
        self.forward_pass(release);
        self.ready = release;
    }

    /// The highest entry speed of each motion from which the machine can still stop at the
    /// window's end. A motion's value depends only on the next one's, so once a value comes out
    /// as it was in the previous round, every earlier one would too and the pass ends there:
    /// at a corner that limits the speed, usually a few motions back.
    fn backward_pass(&mut self) {
        let mut next_entry = 0.0;
        for planned in self.slots.iter_mut().rev().filter_map(Slot::planned) {
            let limits = &planned.limits;
            let entry =
                reachable_speed_up_to(next_entry, planned.max_entry, limits.length, limits.path);
            if entry == planned.backward {
                return;
            }
            planned.backward = entry;
            next_entry = entry;
        }
    }

    /// Entry and exit speeds from the fixed speed at the window's front, as far as the first
    /// motion after the released slots (whose entry is the last released motion's exit).
    fn forward_pass(&mut self, release: usize) {
        let mut previous: Option<&mut Planned> = None;
        for (index, slot) in self.slots.iter_mut().enumerate() {
            let Some(planned) = slot.planned() else {
                continue;
            };
            // The first motion continues from a motion that has already left: its entry is fixed.
            planned.entry = match previous.take() {
                None => self.start_speed,
                Some(previous) => {
                    let limits = &previous.limits;
                    let entry = reachable_speed_up_to(
                        previous.entry,
                        planned.backward,
                        limits.length,
                        limits.path,
                    );
                    previous.exit = entry;
                    entry
                }
            };
            if index >= release {
                return;
            }
            previous = Some(planned);
        }
        // The window ends in a stop.
        if let Some(last) = previous {
            last.exit = 0.0;
        }
    }
}

impl Slot {
    fn planned(&mut self) -> Option<&mut Planned> {
        match self {
            Slot::Motion(planned) => Some(planned),
            Slot::Fixed(_) => None,
        }
    }
}

/// The timed result of a planned motion: its profile (None for a per-axis rapid) and duration.
pub(crate) fn time_motion(planned: &Planned) -> (Option<Profile>, f64) {
    if let Some(seconds) = planned.per_axis_seconds {
        return (None, seconds);
    }
    let limits = &planned.limits;
    let profile = Profile::new(
        limits.length,
        planned.entry,
        planned.exit,
        limits.cruise,
        limits.path,
    )
    .with_lead_in(planned.lead_in);
    (Some(profile), profile.duration())
}
