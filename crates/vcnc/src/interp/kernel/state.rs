//! The state every dialect's executor shares, and the moves made from it.
//!
//! Position and the coordinate chain, the tool memory, feed and spindle, with the setup they
//! are read against; [`KernelState::rapid_to`], [`KernelState::feed_to`],
//! [`KernelState::queue_arc`] turn a machine target into a segment of the stream. A dialect
//! says how it wants a move made ([`MoveModes`], the feed mode); this module never reads a
//! dialect's modal state or words: a block is known by its origin ([`BlockOrigin`]).

use super::super::circular::ArcTo;
use super::super::frames::Frames;
use super::super::modal::FeedMode;
use super::super::setup::Setup;
use super::super::spindle::Spindle;
use super::super::tools::ToolMemory;
use super::super::Output;
use super::BlockOrigin;
use crate::alarm::{Alarm, AlarmCode};
use crate::machine::{Machine, AXES};
use crate::motion::{Feed, FrameId, MachinePos, Move, PathMode, Plane, SegmentKind, Smoothing};
use crate::source::Span;

/// The machine state every dialect shares.
#[derive(Clone, Debug)]
pub(crate) struct KernelState {
    /// The machine and profile, fixed for the run.
    pub(crate) setup: Setup,
    /// The coordinate chain from program to machine coordinates.
    pub(crate) frames: Frames,
    /// Machine position of every axis.
    pub(crate) position: [f64; AXES],
    /// Last programmed F, converted to mm/min, mm/rev or 1/min as the feed mode reads it.
    pub(crate) feed: Option<f64>,
    /// S and how the spindle turns.
    pub(crate) spindle: Spindle,
    /// The speed per-revolution feeds are per when it is not the spindle's (SINUMERIK FPR:
    /// another spindle or a rotary axis), rev/min; None: the spindle's.
    pub(crate) revolution_speed: Option<f64>,
    /// The tool offset registers, the H and D numbers in force, the tools selected and in use.
    pub(crate) tools: ToolMemory,
}

/// How a move is to be made, as the dialect's modal state and block say.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct MoveModes {
    /// Exact stop, continuous path or tapping.
    pub(crate) path_mode: PathMode,
    /// The axes come to rest at this move's end, whatever the path mode.
    pub(crate) exact_stop: bool,
    /// The corner tolerance of a smoothing mode in force.
    pub(crate) smoothing: Option<Smoothing>,
}

impl MoveModes {
    /// These modes, with an exact stop at the end when `exact_stop`.
    #[inline(always)]
    pub(crate) fn stopping(self, exact_stop: bool) -> MoveModes {
        MoveModes {
            exact_stop: self.exact_stop | exact_stop,
            ..self
        }
    }
}

impl KernelState {
    /// The state of `machine` at power-on, in the work system `frames` selects; the tool
    /// registers move from the machine file into the tool memory.
    pub(crate) fn new(machine: &Machine) -> KernelState {
        // The registers live in `tools` from here on: the machine's copy is the power-on state.
        let mut machine = machine.clone();
        let tool_offsets = std::mem::take(&mut machine.tool_offsets);
        let setup = Setup::new(machine);
        KernelState {
            frames: Frames::new(setup.machine()),
            position: setup.machine().start,
            feed: setup.profile().motion.default_feed,
            spindle: Spindle::new(),
            revolution_speed: None,
            tools: ToolMemory::new(tool_offsets),
            setup,
        }
    }

    /// The current position in program coordinates.
    #[inline(always)]
    pub(crate) fn program_position(&self) -> [f64; AXES] {
        self.frames.to_program(&self.position)
    }

    /// A cutting line to a machine position at the feed in force, recorded in the stream.
    ///
    /// # Errors
    /// No feed in force, a position beyond the control's range.
    #[inline(always)]
    pub(crate) fn feed_to(
        &mut self,
        to: [f64; AXES],
        block: &impl BlockOrigin,
        feed_mode: FeedMode,
        modes: MoveModes,
        out: &mut Output,
    ) -> Result<(), Alarm> {
        // A line that ends where it starts moves nothing (and needs no feed).
        if same_place(&to, &self.position) {
            return Ok(());
        }
        let feed = self.cutting_feed(feed_mode, block)?;
        let motion = self.move_to(to, block, modes, out)?;
        // Built where it is queued when no stage is on: through `Output::push` the kind was
        // built on the stack and copied over.
        match out.direct() {
            Some(items) => items.push(Ok(crate::motion::Item::Segment(crate::motion::Segment {
                kind: SegmentKind::Line { motion, feed },
                span: block.span(),
                sequence: block.sequence(),
            }))),
            None => out.push(block, SegmentKind::Line { motion, feed }),
        }
        Ok(())
    }

    /// A rapid to a machine position, recorded in the stream.
    ///
    /// # Errors
    /// [`AlarmCode::ValueOutOfRange`] for a position beyond the control's range.
    pub(crate) fn rapid_to(
        &mut self,
        to: [f64; AXES],
        block: &impl BlockOrigin,
        modes: MoveModes,
        out: &mut Output,
    ) -> Result<(), Alarm> {
        if same_place(&to, &self.position) {
            return Ok(());
        }
        let per_axis = self.setup.profile().motion.rapid_path == crate::profile::RapidPath::PerAxis;
        let motion = self.move_to(to, block, modes, out)?;
        out.push(block, SegmentKind::Rapid { motion, per_axis });
        Ok(())
    }

    /// Moves along `arc` in `plane` from the current position and queues it; the centre's
    /// coordinate off the plane is the start's.
    ///
    /// # Errors
    /// A centre or end beyond the control's range.
    pub(crate) fn queue_arc(
        &mut self,
        block: &impl BlockOrigin,
        arc: ArcTo,
        plane: Plane,
        modes: MoveModes,
        out: &mut Output,
    ) -> Result<(), Alarm> {
        let (a, b, _) = plane.axes();
        let mut center = self.position;
        (center[a], center[b]) = arc.center;
        check_position(&center, block)?;
        let motion = self.move_to(arc.target, block, modes, out)?;
        out.push_with(block, || SegmentKind::Arc {
            motion,
            center: MachinePos(center),
            direction: arc.direction,
            plane,
            extra_turns: arc.extra_turns,
            feed: arc.feed,
        });
        Ok(())
    }

    /// A [`Move`] from the current position to `to`; the position becomes `to`. When the map
    /// from program to machine coordinates changed since the last move, its
    /// [`Item::Frame`](crate::motion::Item::Frame) goes into `out` first: the caller queues the
    /// move next.
    ///
    /// # Errors
    /// [`AlarmCode::ValueOutOfRange`] for a position beyond the control's range (incremental
    /// moves and offsets add up; the control refuses what it cannot represent).
    // Inlined: the move is built where the caller puts it (in the output queue) instead of
    // being copied out of a Result several times per block.
    #[inline(always)]
    pub(crate) fn move_to(
        &mut self,
        to: [f64; AXES],
        block: &impl BlockOrigin,
        modes: MoveModes,
        out: &mut Output,
    ) -> Result<Move, Alarm> {
        check_position(&to, block)?;
        let frame = self.frame_in_force(out);
        let from = MachinePos(self.position);
        self.position = to;
        Ok(Move {
            from,
            to: MachinePos(to),
            path_mode: modes.path_mode,
            exact_stop: modes.exact_stop,
            smoothing: modes.smoothing,
            frame,
            offset: self.frames.offset_at(&to),
        })
    }

    /// The frame a move made now is in; its event goes into `out` first when it is new.
    #[inline(always)]
    pub(crate) fn frame_in_force(&mut self, out: &mut Output) -> FrameId {
        if self.frames.is_new() {
            self.queue_frame(out);
        }
        self.frames.id()
    }

    /// Tells the stream of a new frame.
    #[cold]
    #[inline(never)]
    fn queue_frame(&mut self, out: &mut Output) {
        let frame = self.frames.new_frame();
        out.push_frame(frame);
    }

    /// The feed of a cutting move in `mode`.
    ///
    /// # Errors
    /// [`AlarmCode::NoFeedRate`] when no F is in force (FANUC alarm 011).
    // Inlined: out of line, the feed came back through memory.
    #[inline(always)]
    pub(crate) fn cutting_feed(
        &self,
        mode: FeedMode,
        block: &impl BlockOrigin,
    ) -> Result<Feed, Alarm> {
        let f = match self.feed {
            Some(f) if f != 0.0 => f,
            _ => return Err(self.no_feed(mode, block)),
        };
        Ok(match mode {
            FeedMode::PerMinute => Feed::PerMinute(f),
            FeedMode::PerRevolution => {
                let rpm = self.revolution_speed.unwrap_or(self.spindle.speed());
                Feed::PerRevolution {
                    per_revolution: f,
                    rpm: (rpm > 0.0).then_some(rpm),
                }
            }
            FeedMode::InverseTime => Feed::InverseTime(f),
        })
    }

    /// The alarm of a cutting move without a feed in force, or with a zero feed.
    #[cold]
    fn no_feed(&self, mode: FeedMode, block: &impl BlockOrigin) -> Alarm {
        if self.feed.is_none() {
            let what = match mode {
                FeedMode::InverseTime => {
                    "in G93 inverse-time mode every cutting block needs its own F"
                }
                _ => "cutting move before any feed rate (F) was programmed",
            };
            return Alarm::error(AlarmCode::NoFeedRate, block.span(), what)
                .with_help("add an F word to this block or an earlier one (FANUC alarm 011)");
        }
        Alarm::error(
            AlarmCode::NoFeedRate,
            block.feed_span(),
            "feed rate is zero",
        )
    }
}

/// The largest machine coordinate vcnc accepts, mm or degrees: far beyond any machine, far
/// inside what f64 holds exactly to a micrometre.
pub(crate) const POSITION_LIMIT: f64 = 1.0e9;

/// Refuses a position no control can reach.
///
/// # Errors
/// [`AlarmCode::ValueOutOfRange`] when a coordinate is not finite or beyond [`POSITION_LIMIT`].
// Inlined, with the alarm out of line: out of line, every move paid a call.
#[inline(always)]
pub(crate) fn check_position(position: &[f64], block: &impl BlockOrigin) -> Result<(), Alarm> {
    // One test for all axes, without a branch per axis: this runs for every move.
    let within = position
        .iter()
        .fold(true, |within, v| within & (v.abs() <= POSITION_LIMIT));
    if within {
        return Ok(());
    }
    Err(out_of_range(block.span()))
}

/// The alarm of a position beyond [`POSITION_LIMIT`].
#[cold]
fn out_of_range(span: Span) -> Alarm {
    Alarm::error(
        AlarmCode::ValueOutOfRange,
        span,
        "the position is beyond the control's range",
    )
    .with_help(format!("coordinates are limited to ±{POSITION_LIMIT:e} mm"))
}

/// Two machine positions the control cannot tell apart: every axis within a millionth of the
/// finest input increment. Rotations and scaling leave rounding of about 1e-14 mm on a point the
/// program meant to repeat; a real control, counting in increments, does not move there.
// Inlined: every move asks, and out of line both positions went through memory.
#[inline(always)]
pub(crate) fn same_place(a: &[f64; AXES], b: &[f64; AXES]) -> bool {
    a.iter().zip(b).all(|(p, q)| (p - q).abs() <= 1e-10)
}
