//! Where a rapid with each axis at its own rate really goes (a dog-leg, `rapid_path =
//! "per_axis"`: FANUC 0M's power-on G00, 001 A.19; "each axis independently at its own maximum
//! rate", 003): every axis runs its own speed profile from rest to rest, so the tool does not
//! follow the straight line between the ends. A consumer that draws or checks the path (the
//! trace, a plot, the simulator) asks for its corners: the machine position at each moment an
//! axis comes to rest, with the time from the start of the move. The pieces between corners
//! are chords of the path (straight where the moving axes keep their speeds).
//!
//! The planner times the whole move the same way (`limits::per_axis_rapid_seconds`), so the last
//! corner's time is the move's duration.

use super::limits::AxisLimits;
use super::{PathLimits, SpeedProfile};
use crate::machine::{Machine, AXES};
use crate::motion::{MachinePos, Move};

/// Steps of the integration of an axis's speed up to a corner: the profile is a few pieces of
/// low-degree polynomials, so this is far finer than any drawing needs.
const STEPS: usize = 256;

/// The corners of per-axis rapids on one machine.
#[derive(Clone, Debug)]
pub struct DogLeg {
    limits: AxisLimits,
}

impl DogLeg {
    /// The per-axis rapids of `machine` (its axes' rapid rates, accelerations and jerks).
    pub fn new(machine: &Machine) -> DogLeg {
        DogLeg {
            limits: AxisLimits::new(machine, &machine.planner),
        }
    }

    /// The corners of `motion` as a per-axis rapid: for each moment a moving axis comes to rest
    /// (in time order, axes stopping together giving one corner), the seconds from the move's
    /// start and the machine position then. The last corner is the move's end; a move of one
    /// axis, or of axes that all stop together, has only that one.
    pub fn corners(&self, motion: &Move) -> Vec<(f64, MachinePos)> {
        let (from, to) = (motion.from.0, motion.to.0);
        let profiles: [Option<SpeedProfile>; AXES] = std::array::from_fn(|i| {
            let distance = (to[i] - from[i]).abs();
            (distance > 0.0).then(|| {
                let limits = PathLimits {
                    acceleration: self.limits.acceleration[i],
                    jerk: self.limits.jerk[i],
                };
                SpeedProfile::new(distance, 0.0, 0.0, self.limits.rapid[i], limits)
            })
        });
        let mut stops: Vec<f64> = profiles.iter().flatten().map(|p| p.duration()).collect();
        stops.sort_by(f64::total_cmp);
        stops.dedup_by(|b, a| (*b - *a).abs() <= 1e-9 * a.max(1.0));
        let last = stops.len().saturating_sub(1);
        stops
            .iter()
            .enumerate()
            .map(|(k, &t)| {
                let position = std::array::from_fn(|i| match &profiles[i] {
                    Some(profile) if k < last && t < profile.duration() => {
                        from[i] + (to[i] - from[i]).signum() * travelled(profile, t)
                    }
                    _ => to[i],
                });
                (t, MachinePos(position))
            })
            .collect()
    }
}

/// How far `profile` has gone `t` seconds in (Simpson's rule over its speed).
fn travelled(profile: &SpeedProfile, t: f64) -> f64 {
    let h = t / STEPS as f64;
    let sum: f64 = (0..=STEPS)
        .map(|k| {
            let weight = match k {
                0 => 1.0,
                k if k == STEPS => 1.0,
                k if k % 2 == 1 => 4.0,
                _ => 2.0,
            };
            weight * profile.velocity_at(k as f64 * h)
        })
        .sum();
    (sum * h / 3.0).min(profile.length)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::motion::PathMode;

    fn rapid(from: [f64; 3], to: [f64; 3]) -> Move {
        let pad = |p: [f64; 3]| MachinePos([p[0], p[1], p[2], 0.0, 0.0, 0.0]);
        Move {
            from: pad(from),
            to: pad(to),
            path_mode: PathMode::ExactStop,
            exact_stop: false,
            smoothing: None,
            frame: Default::default(),
            offset: [0.0; AXES],
        }
    }

    /// X 100 and Y 30 at the same rate and acceleration: Y stops first, at the time its own
    /// profile takes, and X has gone as far as its profile goes in that time; X stops at the end
    /// when the planner's per-axis time says.
    #[test]
    fn the_shorter_axis_stops_first_and_the_longer_runs_on() {
        let machine = Machine::default();
        let dog_leg = DogLeg::new(&machine);
        let motion = rapid([0.0, 0.0, 0.0], [100.0, -30.0, 0.0]);
        let corners = dog_leg.corners(&motion);
        assert_eq!(corners.len(), 2);
        let limits = AxisLimits::new(&machine, &machine.planner);
        let axis = |i: usize, d: f64| {
            let path = PathLimits {
                acceleration: limits.acceleration[i],
                jerk: limits.jerk[i],
            };
            SpeedProfile::new(d, 0.0, 0.0, limits.rapid[i], path)
        };
        let (y, x) = (axis(1, 30.0), axis(0, 100.0));
        let (t, at) = corners[0];
        assert!((t - y.duration()).abs() < 1e-12);
        assert_eq!(at.0[1], -30.0);
        // Before Y stops, X has gone farther than 30 (Y slowed down, X did not) and not 100.
        assert!(at.0[0] > 30.0 && at.0[0] < 100.0, "{at:?}");
        let (t, end) = corners[1];
        assert!((t - x.duration()).abs() < 1e-12);
        assert_eq!(end, motion.to);
        assert!((t - super::super::limits::per_axis_rapid_seconds(&motion, &limits)).abs() < 1e-12);
    }

    /// Simpson's rule over a whole profile gives its length.
    #[test]
    fn the_integrated_speed_is_the_length() {
        let limits = PathLimits {
            acceleration: 2000.0,
            jerk: 50_000.0,
        };
        for length in [0.5, 7.0, 300.0] {
            let profile = SpeedProfile::new(length, 0.0, 0.0, 400.0, limits);
            let got = travelled(&profile, profile.duration() * (1.0 - 1e-12));
            assert!(
                (got - length).abs() < 1e-6 * length.max(1.0),
                "{length}: {got}"
            );
        }
    }
}
