//! Fuzz target: arbitrary bytes through the interpreter, the travel check and the planner (as
//! the command line runs them), on the FANUC and Syntec profiles of the default machine
//! (S-curve profiles) and of the same machine with LinuxCNC's habits (trapezoids, blending
//! rules).
//!
//! Properties (a broken one is a crash, and libFuzzer keeps the input):
//! - no panic, and the run ends (the interpreter's own bounds hold; see `interpret.rs`);
//! - every timed segment has a finite, non-negative duration and starts where the one before
//!   it ended: the clock never runs backwards or jumps;
//! - a motion's profile, when it has one, lasts as long as its segment and never exceeds the
//!   segment's cruise speed by more than rounding.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::sync::OnceLock;
use vcnc::checks::TravelLimits;
use vcnc::plan::{PlanOptions, Planner, PlannerConfig, PlannerHabits, TimedItem};
use vcnc::{interpret_bytes, Machine, Options, ProfileName};

/// Items of one run checked before the run is left: a legitimate program can be long.
const MAX_ITEMS: usize = 200_000;

/// Backward jumps a run may make (few, so that fuzzed macro loops end fast).
const JUMPS: u64 = 200;

fn machines() -> &'static [Machine] {
    static MACHINES: OnceLock<Vec<Machine>> = OnceLock::new();
    MACHINES.get_or_init(|| {
        let mut all = Vec::new();
        for profile in [ProfileName::Fanuc, ProfileName::Syntec] {
            let machine = Machine::default()
                .with_profile(profile)
                .expect("built-in profiles fit the default machine");
            let mut linuxcnc = machine.clone();
            linuxcnc.planner = PlannerConfig::with_habits(PlannerHabits::Linuxcnc);
            all.push(machine);
            all.push(linuxcnc);
        }
        all
    })
}

fuzz_target!(|data: &[u8]| {
    for machine in machines() {
        let mut options = Options::default();
        options.limits.jumps = JUMPS;
        let stream = TravelLimits::new(interpret_bytes(data, machine, options), machine);
        let mut clock = 0.0_f64;
        for item in Planner::new(stream, machine, PlanOptions::default()).take(MAX_ITEMS) {
            let Ok(TimedItem::Segment(timed)) = item else {
                continue;
            };
            assert!(
                timed.dt.is_finite() && timed.dt >= 0.0,
                "duration {} of {:?}",
                timed.dt,
                timed.segment
            );
            assert!(
                timed.t == clock,
                "segment starts at {} where the one before ended at {clock}: {:?}",
                timed.t,
                timed.segment
            );
            clock = timed.t + timed.dt;
            if let Some(profile) = timed.profile {
                let duration = profile.duration();
                assert!(
                    (duration - timed.dt).abs() <= 1e-9 * duration.max(1.0),
                    "profile lasts {duration} s, segment {} s: {:?}",
                    timed.dt,
                    timed.segment
                );
            }
        }
    }
});
