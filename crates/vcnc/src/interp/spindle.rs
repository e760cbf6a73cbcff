//! The spindle: its programmed speed (S) and how it turns, and the events that say so.
//!
//! A part of the executor: the stream's spindle events are made here from the state they
//! report, so an event never tells another speed or direction than the one in force.

use crate::motion::{SegmentKind, SpindleState};

/// The spindle's speed and state.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Spindle {
    /// The speed in force, rpm (under G96, the one the surface speed gives).
    speed: f64,
    state: SpindleState,
    /// The highest speed `G92 S` allows, rpm (None: the machine's).
    clamp: Option<f64>,
}

impl Spindle {
    /// At power-on: stopped, S0.
    pub(crate) fn new() -> Spindle {
        Spindle {
            speed: 0.0,
            state: SpindleState::Stopped,
            clamp: None,
        }
    }

    /// The highest speed `G92 S` allows, rpm.
    pub(crate) fn clamp(&self) -> Option<f64> {
        self.clamp
    }

    /// `G92 S`: the highest speed of constant surface speed control.
    pub(crate) fn set_clamp(&mut self, rpm: f64) {
        self.clamp = Some(rpm);
    }

    /// The speed in force, rpm.
    pub(crate) fn speed(&self) -> f64 {
        self.speed
    }

    /// How the spindle turns.
    pub(crate) fn state(&self) -> SpindleState {
        self.state
    }

    /// Whether it turns (M03 or M04).
    pub(crate) fn running(&self) -> bool {
        matches!(
            self.state,
            SpindleState::Clockwise | SpindleState::CounterClockwise
        )
    }

    /// An S word, or the speed G96 computed, rpm.
    pub(crate) fn set_speed(&mut self, speed: f64) {
        self.speed = speed;
    }

    /// The spindle turns as `state` says (M03, M04, M05, M19); the event that says so.
    pub(crate) fn turn(&mut self, state: SpindleState) -> SegmentKind {
        self.state = state;
        self.event()
    }

    /// The event of the spindle as it is.
    pub(crate) fn event(&self) -> SegmentKind {
        SegmentKind::Spindle {
            state: self.state,
            speed: self.speed,
        }
    }
}
