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
//!
//! A corner blend's arc with an acceleration of its own (LinuxCNC's habits) takes a slot of its
//! own between the two motions it joins, planned like any motion; it is no item of the stream,
//! so its time goes to the motion after it ([`Slot::Blend`]).

use super::config::{LookAheadRelease, PlannerConfig};
use super::corner::Junction;
use super::corner::{junction, Handover, Handovers};
use super::limits::MotionLimits;
use super::speed_profile::{reachable_speed_up_to, PathLimits, SpeedProfile};
use super::{greater, lesser};

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
#[derive(Clone, Copy, Debug)]
pub(crate) enum Slot {
    /// A motion being planned.
    Motion(Planned),
    /// A corner blend's arc planned as a motion of its own: no item of the stream, its time
    /// goes to the motion after it.
    Blend(Planned),
    /// An item whose duration is known when it enters: an event, an alarm, a motion of zero
    /// length.
    Fixed(f64),
}

/// The window: a ring of slots whose length is a power of two, so that a slot's place is its
/// index masked, with no division and no wrap test (a `VecDeque` of any capacity needs one).
/// The window is the `len` slots from `head` on, oldest first. The ring doubles if a consumer
/// leaves final slots in it while more arrive; otherwise it holds a window and a slot or two.
pub(crate) struct Window {
    ring: Vec<Slot>,
    /// The ring's place of the first slot in the window.
    head: usize,
    /// Slots in the window.
    len: usize,
    capacity: usize,
    /// Slots at the front whose speeds are final.
    ready: usize,
    /// Speed at the start of the first motion in the window (the last one that left ends there).
    start_speed: f64,
    /// How the last motion that entered ends, for the junction with the next (none after a
    /// stop), and how the entering one does.
    handovers: Handovers,
    /// `PlannerConfig::min_segment_seconds`, for the motion before a stop.
    min_segment_seconds: f64,
    /// `PlannerConfig::last_stop_length_share`, for the motion before a stop.
    last_stop_length_share: f64,
    /// Each motion leaves as soon as the window holds `capacity` motions of positive length
    /// (`LookAheadRelease::Each`), instead of the first half when it holds `capacity` slots.
    release_each: bool,
    /// Motions of positive length in the window that are not final yet, with `release_each`.
    live: usize,
}

impl Window {
    pub(crate) fn new(config: &PlannerConfig) -> Window {
        let capacity = config.look_ahead.max(2);
        Window {
            ring: vec![Slot::Fixed(0.0); (capacity + 1).next_power_of_two()],
            head: 0,
            len: 0,
            capacity,
            ready: 0,
            start_speed: 0.0,
            handovers: Handovers::new(),
            min_segment_seconds: config.min_segment_seconds,
            last_stop_length_share: config.last_stop_length_share,
            release_each: config.look_ahead_release == LookAheadRelease::Each,
            live: 0,
        }
    }

    /// The ring's place of the window's slot `index`.
    #[inline(always)]
    fn place(&self, index: usize) -> usize {
        (self.head + index) & (self.ring.len() - 1)
    }

    /// The window's slots, oldest first, as the two pieces of the ring they take.
    #[inline(always)]
    fn pieces(&mut self) -> (&mut [Slot], &mut [Slot]) {
        let end = self.head + self.len;
        let size = self.ring.len();
        if end <= size {
            (&mut self.ring[self.head..end], &mut [])
        } else {
            let (wrapped, first) = self.ring.split_at_mut(self.head);
            (first, &mut wrapped[..end - size])
        }
    }

    #[inline(always)]
    fn push_slot(&mut self, slot: Slot) {
        if self.len == self.ring.len() {
            self.grow();
        }
        let place = self.place(self.len);
        if let Some(free) = self.ring.get_mut(place) {
            *free = slot;
        }
        self.len += 1;
    }

    /// Doubles the ring, its window first.
    #[cold]
    fn grow(&mut self) {
        let size = 2 * self.ring.len();
        let (first, second) = self.pieces();
        let mut ring = Vec::with_capacity(size);
        ring.extend_from_slice(first);
        ring.extend_from_slice(second);
        ring.resize(size, Slot::Fixed(0.0));
        self.ring = ring;
        self.head = 0;
    }

    /// Whether a final slot is ready.
    #[inline(always)]
    pub(crate) fn has_ready(&self) -> bool {
        self.ready > 0
    }

    /// A final slot, if one is ready.
    #[inline(always)]
    pub(crate) fn pop_ready(&mut self) -> Option<&Slot> {
        if self.ready == 0 {
            return None;
        }
        let place = self.head;
        self.head = self.place(1);
        self.ready -= 1;
        self.len -= 1;
        let slot = self.ring.get(place)?;
        if let Slot::Motion(planned) | Slot::Blend(planned) = slot {
            self.start_speed = planned.exit;
        }
        Some(slot)
    }

    /// Adds an item that takes no time and does not interrupt the motion (an alarm, a motion
    /// of zero length).
    pub(crate) fn push_timeless(&mut self) {
        self.push_slot(Slot::Fixed(0.0));
        self.release_if_full();
    }

    /// Adds an event that takes `seconds`: the machine comes to rest before it, so the window
    /// is planned to a stop, and the event is final at once.
    pub(crate) fn push_event(&mut self, seconds: f64) {
        self.stop();
        self.push_slot(Slot::Fixed(seconds));
        self.ready += 1;
    }

    /// Where the next motion's handover to the motion after it is made, before
    /// [`Window::push_motion`] adds the motion.
    #[inline(always)]
    pub(crate) fn entering_handover(&mut self) -> &mut Handover {
        self.handovers.entering_mut()
    }

    /// Adds a motion of positive length with its limits and its start tangent, its handover
    /// to the next motion made in [`Window::entering_handover`]; `per_axis_seconds` is the
    /// duration of a rapid with each axis at its own rate.
    #[inline(always)]
    pub(crate) fn push_motion(
        &mut self,
        mut limits: MotionLimits,
        start: &[f64; 3],
        per_axis_seconds: Option<f64>,
        config: &PlannerConfig,
    ) {
        let mut max_entry = 0.0;
        let mut lead_in = 0.0;
        if let (Some(prev), handover) = self.handovers.pair() {
            let junction = junction(prev, handover, start, config);
            if junction.arc_acceleration > 0.0 && junction.arc > 0.0 {
                let prev = *prev;
                let arc_cruise = self.push_blend(&prev, &junction, limits.path.jerk, config);
                limits.length = greater(0.0, limits.length - junction.leg);
                max_entry = lesser(arc_cruise, limits.cruise);
                return self.push_planned(limits, max_entry, 0.0, per_axis_seconds);
            }
            let mut prev_cruise = prev.cruise;
            limits.length = greater(0.0, limits.length - junction.leg);
            lead_in = junction.arc;
            // A factor of 1 scales nothing: only a stop at a corner or a kink scales the
            // acceleration.
            let factor = if junction.corner_stop {
                config.stop_acceleration_factor
            } else {
                junction.kink_factor
            };
            limits.scale_acceleration(factor);
            if let Some(prev) = self.last_planned() {
                prev.limits.length = greater(0.0, prev.limits.length - junction.leg);
                prev.limits.scale_acceleration(factor);
                prev_cruise = lesser(prev_cruise, prev.cap_trimmed(config.min_segment_seconds));
            }
            max_entry = lesser(lesser(prev_cruise, junction.speed), limits.cruise);
        }
        self.push_planned(limits, max_entry, lead_in, per_axis_seconds);
    }

    #[inline(always)]
    fn push_planned(
        &mut self,
        limits: MotionLimits,
        max_entry: f64,
        lead_in: f64,
        per_axis_seconds: Option<f64>,
    ) {
        self.handovers.enter();
        self.live += 1;
        self.push_slot(Slot::Motion(Planned {
            limits,
            lead_in,
            max_entry,
            backward: f64::NAN,
            entry: 0.0,
            exit: 0.0,
            per_axis_seconds,
        }));
        self.release_if_full();
    }

    /// Puts the blend arc of `junction` after the last motion (`prev` its handover), which
    /// gives up the arc's leg; the arc's cruise speed, which caps the next motion's entry. What
    /// the arc leaves of a straight move that the blend speed crosses in less than
    /// `PlannerConfig::blend_consume_seconds` runs as part of the arc (LinuxCNC's
    /// `blendCheckConsume`): at the arc's speed and acceleration.
    #[cold]
    fn push_blend(
        &mut self,
        prev: &Handover,
        junction: &Junction,
        jerk: f64,
        config: &PlannerConfig,
    ) -> f64 {
        let mut length = junction.arc;
        let mut prev_cruise = prev.cruise;
        if let Some(last) = self.last_planned() {
            last.limits.length = greater(0.0, last.limits.length - junction.leg);
            let rest = last.limits.length;
            if prev.straight && rest < config.blend_consume_seconds * junction.speed {
                length += rest;
                last.limits.length = 0.0;
                // LinuxCNC takes the consumed line out of its queue.
                self.live = self.live.saturating_sub(1);
            } else {
                prev_cruise = lesser(prev_cruise, last.cap_trimmed(config.min_segment_seconds));
            }
        }
        // The least time per segment holds for the arc as for any segment.
        let mut cruise = junction.speed;
        if config.min_segment_seconds > 0.0 {
            cruise = lesser(cruise, length / config.min_segment_seconds);
        }
        let acceleration = junction.arc_acceleration;
        let limits = MotionLimits {
            length,
            cruise,
            path: PathLimits { acceleration, jerk },
            unblended_acceleration: acceleration,
            feed_unknown: false,
            acceleration_scale: 1.0,
        };
        self.live += 1;
        self.push_slot(Slot::Blend(Planned {
            limits,
            lead_in: 0.0,
            max_entry: lesser(prev_cruise, cruise),
            backward: f64::NAN,
            entry: 0.0,
            exit: 0.0,
            per_axis_seconds: None,
        }));
        cruise
    }

    #[inline(always)]
    fn last_planned(&mut self) -> Option<&mut Planned> {
        // Almost always the last slot; a search only behind an alarm or a zero-length motion.
        let last = self.place(self.len.checked_sub(1)?);
        if let Some(Slot::Motion(_)) = self.ring.get(last) {
            return self.ring.get_mut(last).and_then(Slot::planned);
        }
        let (first, second) = self.pieces();
        second
            .iter_mut()
            .rev()
            .chain(first.iter_mut().rev())
            .find_map(Slot::planned)
    }

    /// The motion comes to rest here (an event, or the end of the stream): everything in the
    /// window becomes final. The last motion did not blend into another, so it gets the
    /// unblended acceleration.
    pub(crate) fn stop(&mut self) {
        let (least, share) = (self.min_segment_seconds, self.last_stop_length_share);
        if let Some(last) = self.last_planned() {
            last.limits.path.acceleration = last.limits.unblended_acceleration;
            last.cap_trimmed(least);
            if share < 1.0 {
                let room = 2.0 * last.limits.path.acceleration * share * last.limits.length;
                last.max_entry = lesser(last.max_entry, room.sqrt());
            }
        }
        self.plan(self.len);
        self.handovers.stop();
    }

    #[inline(always)]
    fn release_if_full(&mut self) {
        if self.release_each {
            if self.live >= self.capacity && self.ready == 0 {
                self.release_first_motion();
            }
        } else if self.len >= self.capacity && self.ready == 0 {
            self.plan(self.len / 2);
        }
    }

    /// Plans the window and makes final everything up to its first motion of positive length.
    #[cold]
    fn release_first_motion(&mut self) {
        let (first, second) = self.pieces();
        let index = first
            .iter_mut()
            .chain(second.iter_mut())
            .position(|slot| slot.planned().is_some_and(|p| p.limits.length > 0.0));
        if let Some(index) = index {
            self.live -= 1;
            self.plan(index + 1);
        }
    }

    /// Plans the window and makes its first `release` slots final.
    fn plan(&mut self, release: usize) {
        self.backward_pass();
        self.forward_pass(release);
        self.ready = release;
        if release == self.len {
            self.live = 0;
        }
    }

    /// The highest entry speed of each motion from which the machine can still stop at the
    /// window's end. A motion's value depends only on the next one's, so once a value comes out
    /// as it was in the previous round, every earlier one would too and the pass ends there:
    /// at a corner that limits the speed, usually a few motions back.
    fn backward_pass(&mut self) {
        let mut next_entry = 0.0;
        let (first, second) = self.pieces();
        let slots = second.iter_mut().rev().chain(first.iter_mut().rev());
        for planned in slots.filter_map(Slot::planned) {
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
        let start_speed = self.start_speed;
        let (first, second) = self.pieces();
        for (index, slot) in first.iter_mut().chain(second.iter_mut()).enumerate() {
            let Some(planned) = slot.planned() else {
                continue;
            };
            // The first motion continues from a motion that has already left: its entry is fixed.
            planned.entry = match previous.take() {
                None => start_speed,
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

impl Planned {
    /// Once its blends have cut it, a motion runs at no more than the least time per segment
    /// allows over what is left (LinuxCNC caps a segment's speed by its length when it plans
    /// it, after the blends: tp.c `tpComputeOptimalVelocity`), entry included; a motion the
    /// blends left nothing of takes no time and caps nothing. Its cruise speed.
    #[inline(always)]
    fn cap_trimmed(&mut self, least_seconds: f64) -> f64 {
        let limits = &mut self.limits;
        if least_seconds > 0.0 && limits.length > 0.0 {
            limits.cruise = lesser(limits.cruise, limits.length / least_seconds);
            self.max_entry = lesser(self.max_entry, limits.cruise);
        }
        limits.cruise
    }
}

impl Slot {
    #[inline(always)]
    fn planned(&mut self) -> Option<&mut Planned> {
        match self {
            Slot::Motion(planned) | Slot::Blend(planned) => Some(planned),
            Slot::Fixed(_) => None,
        }
    }
}

/// The timed result of a planned motion: its profile (None for a per-axis rapid) and duration.
#[inline(always)]
pub(crate) fn time_motion(planned: &Planned) -> (Option<SpeedProfile>, f64) {
    if let Some(seconds) = planned.per_axis_seconds {
        return (None, seconds);
    }
    let limits = &planned.limits;
    let profile = SpeedProfile::new(
        limits.length,
        planned.entry,
        planned.exit,
        limits.cruise,
        limits.path,
    )
    .with_lead_in(planned.lead_in);
    (Some(profile), profile.duration())
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn fixed_seconds(slot: &Slot) -> Option<f64> {
        match slot {
            Slot::Fixed(seconds) => Some(*seconds),
            Slot::Motion(_) | Slot::Blend(_) => None,
        }
    }

    proptest! {
        /// The ring gives the slots back in the order they came, across its wrap and while it
        /// grows (a consumer that takes nothing for a while).
        #[test]
        fn slots_leave_the_ring_in_the_order_they_came(
            takes in proptest::collection::vec(0_usize..40, 1..60),
        ) {
            let mut window = Window::new(&PlannerConfig {
                look_ahead: 4,
                ..PlannerConfig::default()
            });
            let (mut pushed, mut popped) = (0_u32, 0_u32);
            for take in takes {
                // Events are final at once; a few between each round of taking.
                for _ in 0..(take % 7 + 1) {
                    window.push_event(f64::from(pushed));
                    pushed += 1;
                }
                for _ in 0..take {
                    let Some(slot) = window.pop_ready() else { break };
                    prop_assert_eq!(fixed_seconds(slot), Some(f64::from(popped)));
                    popped += 1;
                }
            }
            while let Some(slot) = window.pop_ready() {
                prop_assert_eq!(fixed_seconds(slot), Some(f64::from(popped)));
                popped += 1;
            }
            prop_assert_eq!(popped, pushed);
        }
    }
}
