//! SINUMERIK's working-area limitation in the basic coordinate system (PGsl 6.3, L9888-10010):
//! G25 and G26 with axis words set the lower and upper limit of each axis written, WALIMON
//! (the power-on state) and WALIMOF switch the limitation on and off.
//!
//! The manual: "all tool motions outside the area defined by G25/G26 are prohibited"; a tool
//! outside the area stops the program with an alarm. vcnc checks the moves each block makes,
//! end points and path (an arc also through its extremes: the travel check of
//! [`crate::checks`], given the area's limits), and a move leaving the area becomes the
//! control's alarm 10730 at its block, with the block's moves left out: the position stays at
//! the block's start.
//!
//! **Choices**: the limits are compared with the machine coordinates of the stream (vcnc's
//! three-axis mill has no kinematic between the basic and the machine system), and the tool's
//! radius is not added (MD21020 $MC_WORKAREA_WITH_TOOL_RADIUS is 0 by default). A limit
//! stays set when WALIMOF switches the check off, as the manual's example (L9941-9960)
//! relies on.
//!
//! Never: alarm at a move inside the area, or keep a move that leaves it.

use crate::alarm::{Alarm, AlarmCode};
use crate::checks::{ReleasedCheck, TravelCheck};
use crate::interp::kernel::Kernel;
use crate::machine::{Machine, AXES};

/// The limits G25/G26 set, and whether WALIMON is in force.
#[derive(Clone, Debug)]
pub(super) struct WorkArea {
    low: [f64; AXES],
    high: [f64; AXES],
    off: bool,
    /// The travel check of the area, built when a limit is set (None: no limit yet).
    check: Option<TravelCheck>,
}

impl Default for WorkArea {
    fn default() -> WorkArea {
        WorkArea {
            low: [f64::NEG_INFINITY; AXES],
            high: [f64::INFINITY; AXES],
            off: false,
            check: None,
        }
    }
}

impl WorkArea {
    /// G25 (`upper` false) or G26 (true) with `limits` (mm, None for an axis not written) on
    /// `machine`.
    pub(super) fn set(&mut self, upper: bool, limits: [Option<f64>; AXES], machine: &Machine) {
        let bounds = if upper { &mut self.high } else { &mut self.low };
        for (bound, limit) in bounds.iter_mut().zip(limits) {
            if let Some(limit) = limit {
                *bound = limit;
            }
        }
        // The machine's own check, given the area as its travel.
        let mut area = machine.clone();
        for (i, axis) in area.axes.iter_mut().enumerate() {
            if let Some(axis) = axis {
                axis.min = self.low[i];
                axis.max = self.high[i];
            }
        }
        self.check = Some(TravelCheck::new(&area));
    }

    /// WALIMON (`on` true) or WALIMOF.
    pub(super) fn switch(&mut self, on: bool) {
        self.off = !on;
    }

    /// The moves the kernel made since it had `from` items waiting, checked against the area:
    /// the first that leaves it is cut with the rest and becomes alarm 10730.
    pub(super) fn check(&mut self, kernel: &mut Kernel, from: usize) -> Result<(), Alarm> {
        if self.off {
            return Ok(());
        }
        let Some(check) = self.check.as_mut() else {
            return Ok(());
        };
        // A fresh copy each time: the check remembers that it stopped.
        let mut check = check.clone();
        let Some(travel) =
            kernel.check_waiting(from, |items, range| check.check_released(items, range))
        else {
            return Ok(());
        };
        // The travel check's words, told of the working area instead.
        let message = travel
            .message
            .replace(" overtravel", "")
            .replace("the machine's travel limit", "the limit G25/G26 set");
        Err(Alarm {
            code: AlarmCode::Overtravel,
            message: format!("alarm 10730 working area limitation: {message}"),
            help: Some(
                "move inside the limits of G25 and G26, or switch the limitation off with WALIMOF"
                    .into(),
            ),
            ..travel
        })
    }
}
