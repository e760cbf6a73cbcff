//! The kernel a dialect drives: position and the coordinate chain, the tool offsets, feed, and
//! the moves, events and alarms that become the motion stream.
//!
//! A front end other than ISO (a SINUMERIK block sequencer, a test's toy dialect) reads its own
//! blocks, keeps its own modal state and calls the kernel for what every control shares:
//! [`Kernel::rapid_to`], [`Kernel::feed_to`], [`Kernel::arc_to`], [`Kernel::dwell`],
//! [`Kernel::end`]. Targets are program coordinates (the work system in force, through the frames
//! of the chain and the tool length); what comes out is the same [`Segment`] stream the ISO
//! interpreter yields, so the planner, the checks and every consumer take it unchanged. The
//! kernel never reads program text and knows no dialect: each operation names the block it
//! belongs to by an [`Origin`].

mod state;

pub(crate) use state::{check_position, same_place, KernelState, MoveModes};

use crate::profile::RotaryRollover;

/// How far a rotary axis at `current` degrees turns for an absolute (G90) `programmed` angle
/// under `rollover`: all the way to the angle without rollover; else to the angle modulo 360,
/// the shorter way (half a turn positively) or the way of the angle's sign (FANUC's RABx).
pub(crate) fn rollover_turn(rollover: RotaryRollover, current: f64, programmed: f64) -> f64 {
    let difference = programmed - current;
    match rollover {
        RotaryRollover::Off => difference,
        // Into (-180, 180]: a difference of exactly half a turn goes the positive way.
        RotaryRollover::Shortest => difference - 360.0 * ((difference - 180.0) / 360.0).ceil(),
        // `C-0.` is a negative zero: it turns negatively to 0, as its sign says.
        RotaryRollover::BySign if programmed.is_sign_negative() => {
            -(current - programmed.abs()).rem_euclid(360.0)
        }
        RotaryRollover::BySign => (programmed - current).rem_euclid(360.0),
    }
}

use super::arc::{arc_center, in_plane, ArcSpec};
use super::circular::ArcTo;
use super::comp::geometry::{Side, V2};
use super::comp::transition::Rules;
use super::comp::Compensator;
use super::modal::FeedMode;
use super::modal::ModalState;
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::machine::{Machine, WorkOffsetId, AXES};
use crate::motion::{
    ArcDirection, EndKind, MachinePos, PathMode, Plane, SegmentKind, SpindleState,
};
use crate::source::Span;

/// The block an operation of the kernel belongs to: its span, for alarms and for every segment
/// it makes, and its sequence number, if it has one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Origin {
    /// The block's span in the program text.
    pub span: Span,
    /// Its sequence number (`N`), if any.
    pub sequence: Option<u32>,
}

/// What the kernel knows of the block an operation belongs to: where it is, for alarms and for
/// every segment it makes, and its sequence number. A dialect's decoded block implements it,
/// and so does [`Origin`], for front ends that keep their blocks to themselves.
pub(crate) trait BlockOrigin {
    /// The block's span in the program text.
    fn span(&self) -> Span;
    /// Its sequence number, if any.
    fn sequence(&self) -> Option<u32>;
    /// Where an alarm about the feed points: the feed word, when the block has one.
    fn feed_span(&self) -> Span {
        self.span()
    }
}

impl BlockOrigin for Origin {
    #[inline(always)]
    fn span(&self) -> Span {
        self.span
    }

    #[inline(always)]
    fn sequence(&self) -> Option<u32> {
        self.sequence
    }
}

impl Origin {
    /// The block at `span`, without a sequence number.
    pub fn at(span: Span) -> Origin {
        Origin {
            span,
            sequence: None,
        }
    }
}

/// The machine state every dialect shares, and the queue of the stream it produces.
pub struct Kernel {
    state: KernelState,
    out: Output,
    /// The plane of arcs.
    plane: Plane,
    /// How [`KernelState::feed`] reads.
    feed_mode: FeedMode,
    /// How moves are made (path mode, smoothing).
    modes: MoveModes,
}

impl Kernel {
    /// The kernel of `machine` at power-on: the profile's plane, feed mode, path mode and work
    /// system, no tool length.
    pub fn new(machine: &Machine) -> Kernel {
        let mut state = KernelState::new(machine);
        let power_on = ModalState::power_on(&state.setup.profile().power_on);
        state.frames.select(power_on.work_offset);
        Kernel {
            state,
            out: Output::default(),
            plane: power_on.plane,
            feed_mode: power_on.feed_mode,
            modes: MoveModes {
                path_mode: power_on.path_mode,
                exact_stop: false,
                smoothing: power_on.smoothing_for_motion(),
            },
        }
    }

    /// The machine position now.
    pub fn position(&self) -> MachinePos {
        MachinePos(self.state.position)
    }

    /// The position now in program coordinates.
    pub fn program_position(&self) -> [f64; AXES] {
        self.state.program_position()
    }

    /// Sets the cutting feed, mm/min.
    pub fn set_feed(&mut self, mm_per_min: f64) {
        self.feed_mode = FeedMode::PerMinute;
        self.state.feed = Some(mm_per_min);
    }

    /// Machine coordinates of a program-coordinate target; axes without a value stay where they
    /// are.
    // Inlined: every move a front end makes on the kernel passes through it.
    #[inline]
    fn machine_target(&self, target: [Option<f64>; AXES]) -> [f64; AXES] {
        let here = self.state.program_position();
        let program = std::array::from_fn(|i| target[i].unwrap_or(here[i]));
        let frames = &self.state.frames;
        frames.to_machine(&program, frames.length_vector())
    }

    /// A rapid to `target` (program coordinates).
    ///
    /// # Errors
    /// [`AlarmCode::ValueOutOfRange`] for a position beyond the control's range.
    pub fn rapid_to(&mut self, target: [Option<f64>; AXES], origin: Origin) -> Result<(), Alarm> {
        let to = self.machine_target(target);
        self.state.rapid_to(to, &origin, self.modes, &mut self.out)
    }

    /// A cutting line to `target` (program coordinates) at the feed in force.
    ///
    /// # Errors
    /// [`AlarmCode::NoFeedRate`] without a feed; [`AlarmCode::ValueOutOfRange`] for a position
    /// beyond the control's range.
    pub fn feed_to(&mut self, target: [Option<f64>; AXES], origin: Origin) -> Result<(), Alarm> {
        let to = self.machine_target(target);
        let feed_mode = self.feed_mode;
        self.state
            .feed_to(to, &origin, feed_mode, self.modes, &mut self.out)
    }

    /// An arc in the plane in force (G17 at power-on) to `target` about `center`, both in
    /// program coordinates (the centre's two plane coordinates), at the feed in force; axes off
    /// the plane move with it (a helix). An end on the start is a full circle.
    ///
    /// # Errors
    /// [`AlarmCode::NoFeedRate`] without a feed; [`AlarmCode::ArcEndNotOnCircle`] when the end is
    /// not on the circle about `center`.
    pub fn arc_to(
        &mut self,
        target: [Option<f64>; AXES],
        center: (f64, f64),
        direction: ArcDirection,
        origin: Origin,
    ) -> Result<(), Alarm> {
        self.arc_in(self.plane, target, center, direction, 0, origin)
    }

    /// [`Kernel::arc_to`] in `plane` (whatever plane is in force), with `turns` full turns
    /// beyond the first (a helix of several turns).
    ///
    /// # Errors
    /// As [`Kernel::arc_to`].
    pub fn arc_in(
        &mut self,
        plane: Plane,
        target: [Option<f64>; AXES],
        center: (f64, f64),
        direction: ArcDirection,
        turns: u32,
        origin: Origin,
    ) -> Result<(), Alarm> {
        let (a, b, _) = plane.axes();
        let reversed = self.state.frames.reverses_plane((a, b));
        self.arc_onto(
            plane, plane, reversed, target, center, direction, turns, origin,
        )
    }

    /// A circular move programmed in `plane` that the frame turns onto the machine plane
    /// `onto` (SINUMERIK's ROT Y90 and the like: the frame's `plane_image`), `reversed` when it
    /// turns the other way there: an arc of the stream in that plane, its helix along that
    /// plane's normal.
    ///
    /// # Errors
    /// No feed in force, an end point off the circle.
    #[allow(clippy::too_many_arguments)] // the same words as `arc_in`, and where they land
    pub(crate) fn arc_onto(
        &mut self,
        plane: Plane,
        onto: Plane,
        reversed: bool,
        target: [Option<f64>; AXES],
        center: (f64, f64),
        direction: ArcDirection,
        turns: u32,
        origin: Origin,
    ) -> Result<(), Alarm> {
        let feed = self.state.cutting_feed(self.feed_mode, &origin)?;
        let (a, b, _) = plane.axes();
        let (c, d, _) = onto.axes();
        let direction = if reversed {
            direction.reversed()
        } else {
            direction
        };
        let frames = &self.state.frames;
        let mut center_point = self.state.program_position();
        (center_point[a], center_point[b]) = center;
        let center_machine = frames.to_machine(&center_point, frames.length_vector());
        let to = self.machine_target(target);
        let start = in_plane(onto, &self.state.position);
        let spec = ArcSpec::Center {
            offset: (center_machine[c] - start.0, center_machine[d] - start.1),
            span: origin.span,
        };
        let tolerance = self.state.setup.profile().motion.arc_radius_tolerance;
        let center = arc_center(start, in_plane(onto, &to), spec, direction, tolerance)?;
        let arc = ArcTo {
            target: to,
            center,
            direction,
            feed,
            extra_turns: turns,
        };
        let modes = self.modes;
        self.state
            .queue_arc(&origin, arc, onto, modes, &mut self.out)
    }

    /// The plane of arcs from here on.
    pub fn set_plane(&mut self, plane: Plane) {
        self.plane = plane;
    }

    /// How F reads from here on, and its value in that mode (None: no feed in force, as after
    /// a change of the feed type on SINUMERIK).
    pub fn set_feed_in(&mut self, mode: FeedMode, value: Option<f64>) {
        self.feed_mode = mode;
        self.state.feed = value;
    }

    /// The speed per-revolution feeds are per from here on, rev/min, when it is not the
    /// spindle's (SINUMERIK FPR); None: the spindle's again.
    pub(crate) fn set_revolution_speed(&mut self, rpm: Option<f64>) {
        self.state.revolution_speed = rpm;
    }

    /// How F reads now and its value: what a front end restores around a move of an earlier
    /// block's.
    pub fn feed_setting(&self) -> (FeedMode, Option<f64>) {
        (self.feed_mode, self.state.feed)
    }

    /// How the moves to come are made: path mode, and an exact stop at their end.
    pub fn set_path_mode(&mut self, path_mode: PathMode, exact_stop: bool) {
        self.modes.path_mode = path_mode;
        self.modes.exact_stop = exact_stop;
    }

    /// The corner smoothing of the moves to come (a front end's rounding modes: SINUMERIK
    /// G641-G645); none leaves the corners to the machine's `corner_tolerance`.
    pub fn set_smoothing(&mut self, smoothing: Option<crate::motion::Smoothing>) {
        self.modes.smoothing = smoothing;
    }

    /// An event of the stream (spindle, coolant, tool, stop, auxiliary function) at this
    /// place of the program. Moves, dwells and the end have their own operations.
    pub fn event(&mut self, kind: SegmentKind, origin: Origin) {
        debug_assert!(!matches!(
            kind,
            SegmentKind::Rapid { .. }
                | SegmentKind::Line { .. }
                | SegmentKind::Arc { .. }
                | SegmentKind::End { .. }
        ));
        self.out.push(&origin, kind);
    }

    /// The spindle's programmed speed and state change (either may stay): what `G95` feeds
    /// read; the spindle event says so in the stream.
    pub fn spindle(&mut self, speed: Option<f64>, state: Option<SpindleState>, origin: Origin) {
        if let Some(speed) = speed {
            self.state.spindle.set_speed(speed);
        }
        let event = match state {
            Some(state) => self.state.spindle.turn(state),
            None => self.state.spindle.event(),
        };
        self.out.push(&origin, event);
    }

    /// The settable work offset in force from here on (G54 ...); it moves nothing until the
    /// next move of each axis.
    pub fn select_work_offset(&mut self, id: WorkOffsetId) {
        self.state.frames.select(id);
    }

    /// Sets one axis of a work offset register (a program writing its settable frames).
    pub fn set_work_offset(&mut self, id: WorkOffsetId, axis: usize, value: f64) {
        self.state.frames.set_work_offset(id, axis, value);
    }

    /// The tool length applied along Z from here on (the next move of Z travels it).
    pub fn set_tool_length(&mut self, length: f64) {
        self.state.frames.set_length_vector(length);
    }

    /// The tool's offset vector along X, Y and Z from here on (a length by plane: along Y in
    /// G18); each axis's next move travels its part.
    pub fn set_tool_vector(&mut self, vector: [f64; 3]) {
        self.state.frames.set_lateral_length([vector[0], vector[1]]);
        self.state.frames.set_length_vector(vector[2]);
    }

    /// A rapid to a machine position (a frame-suppressing block: G53, SUPA).
    pub(crate) fn rapid_to_machine(
        &mut self,
        to: [f64; AXES],
        origin: Origin,
    ) -> Result<(), Alarm> {
        self.state.rapid_to(to, &origin, self.modes, &mut self.out)
    }

    /// A cutting line to a machine position (a frame-suppressing block: G53, SUPA).
    pub(crate) fn feed_to_machine(&mut self, to: [f64; AXES], origin: Origin) -> Result<(), Alarm> {
        let feed_mode = self.feed_mode;
        self.state
            .feed_to(to, &origin, feed_mode, self.modes, &mut self.out)
    }

    /// The programmable frame from here on (None: no frame); it moves nothing until the next
    /// move of each axis.
    pub(crate) fn set_programmable(&mut self, frame: Option<crate::interp::frames::Affine>) {
        self.state.frames.set_programmable(frame);
    }

    /// The kernel's machine state, for a front end's reads (frames, tools, spindle).
    pub(crate) fn state(&self) -> &KernelState {
        &self.state
    }

    /// The kernel's machine state, lent to another interpreter that runs blocks on it (the ISO
    /// blocks of a SINUMERIK program's G291 section).
    pub(crate) fn state_mut(&mut self) -> &mut KernelState {
        &mut self.state
    }

    /// The kernel's machine state and its output, for a change that starts or ends an output
    /// stage (SINUMERIK's CYCLE800 and the kinematic transform).
    pub(crate) fn state_and_output(&mut self) -> (&mut KernelState, &mut Output) {
        (&mut self.state, &mut self.out)
    }

    /// The number of items waiting to be handed out.
    pub(crate) fn waiting(&self) -> usize {
        self.out.items.len()
    }

    /// Runs `check` over the items made since `from` were waiting; when it cuts them and adds
    /// its alarm (returns false), the alarm is taken back and returned: the caller stops.
    pub(crate) fn check_waiting(
        &mut self,
        from: usize,
        check: impl FnOnce(&mut Vec<crate::motion::StreamItem>, std::ops::Range<usize>) -> bool,
    ) -> Option<Alarm> {
        let end = self.out.items.len();
        if check(&mut self.out.items, from.min(end)..end) {
            return None;
        }
        let alarm = self.out.items.pop()?.err();
        let len = self.out.items.len();
        if let Some(held) = self.out.held.as_mut() {
            *held = (*held).min(len);
        }
        alarm
    }

    /// A segment (or frame) another interpreter made on this kernel's state, into the stream.
    pub(crate) fn push_item(&mut self, item: crate::motion::Item) {
        self.out.items.push(Ok(item));
    }

    /// A thread (or a rigid tap) to `target` (program coordinates): a line whose feed is
    /// `lead` mm per spindle revolution along the path, cut at 100 % override and ending at
    /// rest, as the tapping path mode says.
    ///
    /// # Errors
    /// [`AlarmCode::ValueOutOfRange`] for a position beyond the control's range.
    pub fn thread_to(
        &mut self,
        target: [Option<f64>; AXES],
        lead: f64,
        origin: Origin,
    ) -> Result<(), Alarm> {
        let to = self.machine_target(target);
        if same_place(&to, &self.state.position) {
            return Ok(());
        }
        let speed = self.state.spindle.speed();
        let feed = crate::motion::Feed::PerRevolution {
            per_revolution: lead,
            rpm: (speed > 0.0).then_some(speed),
        };
        let modes = MoveModes {
            path_mode: PathMode::Tapping,
            exact_stop: true,
            smoothing: None,
        };
        let motion = self.state.move_to(to, &origin, modes, &mut self.out)?;
        self.out.push(&origin, SegmentKind::Line { motion, feed });
        Ok(())
    }

    /// A dwell of `seconds`.
    ///
    /// # Errors
    /// [`AlarmCode::BadDwell`] for a negative time.
    pub fn dwell(&mut self, seconds: f64, origin: Origin) -> Result<(), Alarm> {
        if seconds.is_nan() || seconds < 0.0 {
            return Err(Alarm::error(
                AlarmCode::BadDwell,
                origin.span,
                "dwell time cannot be negative",
            ));
        }
        self.out.push(&origin, SegmentKind::Dwell { seconds });
        Ok(())
    }

    /// The program ends here, as `kind` says: the end item, nothing after it.
    pub fn end(&mut self, kind: EndKind, origin: Origin) {
        self.out.push(&origin, SegmentKind::End { kind });
    }

    /// A warning (or any alarm that does not stop the program) in the stream.
    pub fn warn(&mut self, alarm: Alarm) {
        self.out.push_warning(alarm);
    }

    /// An error stops the program: the alarm is the stream's last item.
    pub(super) fn stop(&mut self, alarm: Alarm) {
        self.out.stop(alarm);
    }

    /// Moves the items that can be handed out to the end of `into`.
    pub(super) fn release(&mut self, into: &mut impl Extend<crate::motion::StreamItem>) {
        let released = self.out.releasable();
        into.extend(self.out.items.drain(..released));
        if let Some(held) = self.out.held.as_mut() {
            *held -= released;
        }
    }

    /// Nothing waits any more: the program is over.
    pub(super) fn finish(&mut self) {
        self.out.finish();
    }

    /// The queue becomes the caller's batch `out` until [`Kernel::give_back`]
    /// ([`Output::lend`]).
    pub(super) fn lend(&mut self, out: &mut Vec<crate::motion::StreamItem>) {
        self.out.lend(out);
    }

    /// Ends [`Kernel::lend`]: `out` gets what can be handed out.
    pub(super) fn give_back(&mut self, out: &mut Vec<crate::motion::StreamItem>) {
        self.out.give_back(out);
    }

    /// The queue, with how many of its first items can be handed out.
    pub(super) fn released(&mut self) -> (&mut Vec<crate::motion::StreamItem>, usize) {
        let released = self.out.releasable();
        (&mut self.out.items, released)
    }

    /// A check cut the queue ([`Output::cut_by_check`]).
    pub(super) fn cut_by_check(&mut self) {
        self.out.cut_by_check();
    }

    /// Cutter radius compensation starts in `plane`, on the side and at the radius of
    /// `setting`, from the tool's position now, under a dialect's `rules`; `left` says G41 (or
    /// its dialect's equal). `look_ahead` blocks without motion in the plane end the element
    /// pending perpendicular to itself.
    pub(crate) fn start_compensation(
        &mut self,
        setting: (Side, f64),
        plane: Plane,
        left: bool,
        rules: Rules,
        look_ahead: u32,
    ) {
        let (a, b, _) = plane.axes();
        let comp = Compensator::new(setting, (a, b), &self.state.position, left, look_ahead)
            .with_rules(rules);
        self.out.start_compensation(comp);
    }

    /// The start-up block approaches the contour smoothly (SINUMERIK's SAR).
    pub(crate) fn approach_smoothly(&mut self, approach: super::comp::smooth::Approach) {
        if let Some(comp) = self.out.compensation_mut() {
            comp.approach_smoothly(approach);
        }
    }

    /// The cutting feed in force, as the segments carry it.
    ///
    /// # Errors
    /// [`AlarmCode::NoFeedRate`] without a feed.
    pub(crate) fn cutting_feed(&self, origin: Origin) -> Result<crate::motion::Feed, Alarm> {
        self.state.cutting_feed(self.feed_mode, &origin)
    }

    /// A new side or radius while compensating: from the next element in the plane.
    pub(crate) fn change_compensation(&mut self, setting: (Side, f64), left: bool) {
        if let Some(comp) = self.out.compensation_mut() {
            comp.change(setting, left);
        }
    }

    /// New corner or approach rules while compensating.
    pub(crate) fn set_compensation_rules(&mut self, rules: Rules) {
        if let Some(comp) = self.out.compensation_mut() {
            comp.set_rules(rules);
        }
    }

    /// CUTCONON (`keep`): the moves from here on go as programmed, shifted by the offset the
    /// tool centre has where the last compensated element ends; CUTCONOF: compensated again.
    ///
    /// # Errors
    /// Interference where the last compensated element ends.
    pub(crate) fn keep_compensation_constant(&mut self, keep: bool) -> Result<(), Alarm> {
        let position = self.state.position;
        self.out.change_compensation(|comp, items, held| {
            if !keep {
                comp.release_constant();
                return Ok(());
            }
            let (a, b) = comp.axes();
            comp.keep_constant(V2::new(position[a], position[b]), items, held)
        })
    }

    /// The block being run cancels compensation: its move in the plane leaves the contour.
    pub(crate) fn cancel_compensation(&mut self) {
        if let Some(comp) = self.out.compensation_mut() {
            comp.cancel();
        }
    }

    /// After the cancelling block's motion: compensation ends, and when the block did not move
    /// in the plane the tool centre goes from where it stands onto the programmed point, at
    /// rapid (`rapid`) or at the feed in force.
    ///
    /// # Errors
    /// Interference at the pending element's end; a line without a feed.
    pub(crate) fn end_compensation(&mut self, rapid: bool, origin: Origin) -> Result<(), Alarm> {
        if !self
            .out
            .compensation()
            .is_some_and(Compensator::is_cancelling)
        {
            return Ok(());
        }
        let Some(mut comp) = self.out.take_compensation() else {
            return Ok(());
        };
        self.out.finish_compensation(&mut comp)?;
        let (a, b) = comp.axes();
        let tool = comp.tool();
        let here = self.state.position;
        if tool.distance(V2::new(here[a], here[b])) < 1e-9 {
            return Ok(());
        }
        let mut from = here;
        (from[a], from[b]) = (tool.x, tool.y);
        let motion = crate::motion::Move {
            from: MachinePos(from),
            to: MachinePos(here),
            path_mode: self.modes.path_mode,
            exact_stop: self.modes.exact_stop,
            smoothing: self.modes.smoothing,
            offset: self.state.frames.offset_at(&here),
            frame: self.state.frame_in_force(&mut self.out),
        };
        let kind = if rapid {
            let per_axis =
                self.state.setup.profile().motion.rapid_path == crate::profile::RapidPath::PerAxis;
            SegmentKind::Rapid { motion, per_axis }
        } else {
            let feed = self.state.cutting_feed(self.feed_mode, &origin)?;
            SegmentKind::Line { motion, feed }
        };
        self.out.push(&origin, kind);
        Ok(())
    }

    /// A block of the front end ends: compensation counts the blocks without motion in the
    /// plane, and a corner it could not make stops the program here.
    ///
    /// # Errors
    /// The compensation's alarm (interference, an arc smaller than the tool).
    pub(crate) fn end_block(&mut self) -> Result<(), Alarm> {
        if !self.out.compensating() && !self.out.failing() {
            return Ok(());
        }
        self.out.end_block()?;
        match self.out.take_failure() {
            Some(alarm) => Err(alarm),
            None => Ok(()),
        }
    }

    /// The feed of the moves to come, as the segments carry it.
    #[cfg(test)]
    fn feed(&self) -> Option<crate::motion::Feed> {
        let origin = Origin::at(Span::new(crate::source::FileId(0), 1, 0..1));
        self.state.cutting_feed(self.feed_mode, &origin).ok()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::source::FileId;

    fn origin() -> Origin {
        Origin::at(Span::new(FileId(0), 1, 0..1))
    }

    #[test]
    fn axes_without_a_value_stay_where_they_are() {
        let mut kernel = Kernel::new(&Machine::default());
        let start = kernel.program_position();
        kernel
            .rapid_to([Some(10.0), None, None, None, None, None], origin())
            .unwrap();
        let now = kernel.program_position();
        assert_eq!(now[0], 10.0);
        assert_eq!(now[1..], start[1..]);
    }

    #[test]
    fn a_cutting_move_needs_a_feed() {
        let mut kernel = Kernel::new(&Machine::default());
        assert_eq!(kernel.feed(), None);
        let refused = kernel.feed_to([Some(1.0), None, None, None, None, None], origin());
        assert_eq!(refused.unwrap_err().code, AlarmCode::NoFeedRate);
        kernel.set_feed(300.0);
        assert_eq!(kernel.feed(), Some(crate::motion::Feed::PerMinute(300.0)));
    }
}
