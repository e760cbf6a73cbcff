//! Helpers for the planner tests: machines with given limits, and timing a program.
#![allow(dead_code, unreachable_pub)]

use vcnc::plan::{PlanOptions, Planner, TimedSegment};
use vcnc::{interpret_str, Machine, Options};

/// Limits of every axis of a test machine (mm/s, mm/s^2, mm/s^3) and extra `[planner]` lines.
pub struct Limits<'a> {
    pub speed: f64,
    pub acceleration: f64,
    pub jerk: f64,
    pub planner: &'a str,
    pub profile_overrides: &'a str,
}

impl Default for Limits<'_> {
    fn default() -> Self {
        Limits {
            speed: 100.0,
            acceleration: 1000.0,
            jerk: f64::INFINITY,
            planner: "",
            profile_overrides: "",
        }
    }
}

/// A 3-axis machine whose axes all have the same limits (rapid and feed alike).
pub fn machine(limits: &Limits) -> Machine {
    let mut text = format!(
        "name = \"test\"\nprofile = \"fanuc\"\n[spindle]\nmax_rpm = 10000.0\n[profile_overrides]\n{}\n",
        limits.profile_overrides
    );
    for axis in ["x", "y", "z"] {
        text.push_str(&format!(
            "[axes.{axis}]\nmin = -5000.0\nmax = 5000.0\nrapid = {rate:?}\nmax_feed = {rate:?}\nacceleration = {a:?}\njerk = {j}\n",
            rate = limits.speed * 60.0,
            a = limits.acceleration,
            j = if limits.jerk.is_finite() { format!("{:?}", limits.jerk) } else { "inf".to_string() },
        ));
    }
    text.push_str(&format!("[planner]\n{}\n", limits.planner));
    Machine::from_toml(&text).unwrap_or_else(|e| panic!("test machine: {e}\n{text}"))
}

/// Every timed segment of a program; panics on an alarm.
pub fn timed(program: &str, machine: &Machine, options: PlanOptions) -> Vec<TimedSegment> {
    let stream = interpret_str(program, machine, Options::default());
    Planner::new(stream, machine, options)
        .filter_map(|item| match item {
            Ok(vcnc::plan::TimedItem::Segment(timed)) => Some(timed),
            Ok(vcnc::plan::TimedItem::Frame(_)) => None,
            Ok(vcnc::plan::TimedItem::Warning(alarm)) | Err(alarm) => {
                panic!("alarm: {alarm:?}\n{program}")
            }
        })
        .collect()
}

/// The program's total time, seconds.
pub fn total_seconds(program: &str, machine: &Machine) -> f64 {
    timed(program, machine, PlanOptions::default())
        .last()
        .map_or(0.0, |s| s.t + s.dt)
}
