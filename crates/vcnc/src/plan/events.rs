//! How long the events of the stream take: dwells, tool changes, the spindle.
//!
//! Motion is at rest during every event (the look-ahead stops before it). The spindle's times
//! depend on what it was doing, so the clock keeps its state: starting a stopped spindle costs
//! the start time, reversing it a stop and a start, a new speed in the same direction nothing.

use super::config::PlannerConfig;
use crate::motion::{SegmentKind, SpindleState};

/// The state the event times depend on.
#[derive(Clone, Copy, Debug)]
pub(crate) struct EventClock {
    spindle: SpindleState,
}

impl Default for EventClock {
    fn default() -> EventClock {
        EventClock {
            spindle: SpindleState::Stopped,
        }
    }
}

impl EventClock {
    /// Seconds the event takes.
    pub(crate) fn seconds(&mut self, kind: &SegmentKind, config: &PlannerConfig) -> f64 {
        match *kind {
            SegmentKind::Dwell { seconds } if seconds.is_finite() => seconds.max(0.0),
            SegmentKind::ToolChange { .. } => config.tool_change_seconds,
            SegmentKind::Spindle { state, .. } => self.spindle_seconds(state, config),
            _ => 0.0,
        }
    }

    fn spindle_seconds(&mut self, state: SpindleState, config: &PlannerConfig) -> f64 {
        use SpindleState::{Clockwise, CounterClockwise, Oriented, Stopped};
        let before = std::mem::replace(&mut self.spindle, state);
        let running = |s: SpindleState| matches!(s, Clockwise | CounterClockwise);
        match state {
            Stopped if running(before) => config.spindle_stop_seconds,
            Stopped => 0.0,
            Oriented => {
                let stop = if running(before) {
                    config.spindle_stop_seconds
                } else {
                    0.0
                };
                stop + config.spindle_orientation_seconds
            }
            _ if before == state => 0.0,
            _ if running(before) => config.spindle_stop_seconds + config.spindle_start_seconds,
            _ => config.spindle_start_seconds,
        }
    }
}
