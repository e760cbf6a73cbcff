//! Where a cycle works and the moves it makes: the plane, the tool's position in program
//! coordinates, and the kernel's rapids, lines, arcs and threads to the cycle's points.
//!
//! Never: move an axis outside the plane and its tool axis, or make more than [`MAX_MOVES`]
//! moves in one call (its passes together).

use super::super::Sinumerik;
use super::MAX_MOVES;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::kernel::{Kernel, Origin};
use crate::machine::AXES;
use crate::motion::{ArcDirection, PathMode, Plane, SpindleState};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

/// Where a cycle works: the plane, the tool's position in program coordinates as the cycle
/// moves it, and the block its moves belong to.
pub(super) struct Place {
    /// The plane's first and second axes and the tool axis (G17: X, Y, Z).
    pub(super) axes: (usize, usize, usize),
    pub(super) plane: Plane,
    /// The position in program coordinates.
    position: [f64; AXES],
    pub(super) origin: Origin,
    /// Whether the spindle turns clockwise (M3) when the cycle starts: climb milling depends
    /// on it.
    pub(super) clockwise: bool,
    /// The path mode of the block (G60 or continuous), restored after a tapping move.
    pub(super) path_mode: PathMode,
    /// The moves the call has made so far, its earlier passes too (at most [`MAX_MOVES`]).
    moves: Arc<AtomicU64>,
}

impl Place {
    pub(super) fn new(front: &Sinumerik, kernel: &Kernel) -> Place {
        let plane = front.modal.plane;
        Place {
            axes: plane.axes(),
            plane,
            position: front.programmed,
            // The moves belong to the block that runs the cycle (the positioning block of a
            // modal call); alarms point at the call.
            origin: Origin::at(front.last_span),
            clockwise: kernel.state().spindle.state() != SpindleState::CounterClockwise,
            path_mode: if front.modal.exact_stop {
                PathMode::ExactStop
            } else {
                PathMode::Continuous
            },
            moves: Arc::clone(&front.cycles.moves),
        }
    }

    /// The position in the plane (abscissa, ordinate).
    pub(super) fn in_plane(&self) -> (f64, f64) {
        (self.position[self.axes.0], self.position[self.axes.1])
    }

    /// The position along the tool axis.
    pub(super) fn height(&self) -> f64 {
        self.position[self.axes.2]
    }

    /// The target of a move to `point` in the plane and `height` on the tool axis (each
    /// None: stays); an alarm past [`MAX_MOVES`].
    fn target(
        &mut self,
        point: Option<(f64, f64)>,
        height: Option<f64>,
    ) -> Result<[Option<f64>; AXES], Alarm> {
        // The front end runs on one thread: the count is shared, never contended.
        let moves = self.moves.fetch_add(1, Ordering::Relaxed) + 1;
        if moves > MAX_MOVES {
            return Err(Alarm::error(
                AlarmCode::MacroLimit,
                self.origin.span,
                format!("the cycle makes more than {MAX_MOVES} moves"),
            )
            .with_help("check the cycle's steps (MID, MIDA, DXY, DP1): one is far too small"));
        }
        let (a, b, n) = self.axes;
        if let Some((x, y)) = point {
            self.position[a] = x;
            self.position[b] = y;
        }
        if let Some(h) = height {
            self.position[n] = h;
        }
        let mut target = [None; AXES];
        for i in [a, b, n] {
            target[i] = Some(self.position[i]);
        }
        Ok(target)
    }

    /// A rapid along the tool axis to `height`.
    pub(super) fn rapid_height(&mut self, kernel: &mut Kernel, height: f64) -> Result<(), Alarm> {
        let target = self.target(None, Some(height))?;
        kernel.rapid_to(target, self.origin)
    }

    /// A cutting line along the tool axis to `height` at the feed in force.
    pub(super) fn feed_height(&mut self, kernel: &mut Kernel, height: f64) -> Result<(), Alarm> {
        let target = self.target(None, Some(height))?;
        kernel.feed_to(target, self.origin)
    }

    /// A rapid in the plane to `point`.
    pub(super) fn rapid_plane(
        &mut self,
        kernel: &mut Kernel,
        point: (f64, f64),
    ) -> Result<(), Alarm> {
        let target = self.target(Some(point), None)?;
        kernel.rapid_to(target, self.origin)
    }

    /// A cutting line to `point` in the plane and `height` (None: stays) at the feed in force.
    pub(super) fn feed_to(
        &mut self,
        kernel: &mut Kernel,
        point: (f64, f64),
        height: Option<f64>,
    ) -> Result<(), Alarm> {
        let target = self.target(Some(point), height)?;
        kernel.feed_to(target, self.origin)
    }

    /// An arc in the plane to `point` about `centre` (a helix when `height` changes; `turns`
    /// full turns beyond the first when the end is the start) at the feed in force.
    pub(super) fn arc_to(
        &mut self,
        kernel: &mut Kernel,
        point: (f64, f64),
        centre: (f64, f64),
        clockwise: bool,
        height: Option<f64>,
        turns: u32,
    ) -> Result<(), Alarm> {
        let direction = if clockwise {
            ArcDirection::Clockwise
        } else {
            ArcDirection::CounterClockwise
        };
        let target = self.target(Some(point), height)?;
        super::super::motion::arc_in_frames(
            kernel,
            self.plane,
            target,
            centre,
            direction,
            turns,
            self.origin,
        )
    }

    /// A thread along the tool axis to `height`, `lead` mm per revolution.
    pub(super) fn thread_height(
        &mut self,
        kernel: &mut Kernel,
        height: f64,
        lead: f64,
    ) -> Result<(), Alarm> {
        let target = self.target(None, Some(height))?;
        kernel.thread_to(target, lead, self.origin)
    }

    /// The programmed position becomes where the cycle left the tool.
    pub(super) fn finish(self, front: &mut Sinumerik) {
        let (a, b, n) = self.axes;
        for i in [a, b, n] {
            front.programmed[i] = self.position[i];
        }
    }
}
