//! Velocity profiles along one segment: how fast the tool goes at each instant, in closed form.
//!
//! A segment is entered at one speed, speeds up to a peak (the cruise speed when there is room),
//! and slows to its exit speed. Each change of speed is a [`Ramp`]: with a jerk limit it is the
//! S-curve of three phases (jerk up, constant acceleration, jerk down, the middle one absent when
//! the acceleration limit is not reached); with an infinite jerk it is the constant acceleration
//! of a trapezoid. A ramp begins and ends with zero acceleration, so segments join without a
//! jump in acceleration. That is conservative on chains of short segments (a real S-curve may
//! carry acceleration across a block boundary) and keeps every segment's profile independent.
//!
//! Invariants: speeds are mm/s (or deg/s), lengths mm, times s, all finite and non-negative for
//! finite non-negative input; nothing here panics or loops without bound on any input.

use super::{finite, greater, lesser};

/// The limits along the path that shape a profile: tangential acceleration and jerk.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathLimits {
    /// Tangential acceleration, mm/s^2.
    pub acceleration: f64,
    /// Jerk, mm/s^3; infinite for trapezoidal profiles.
    pub jerk: f64,
}

impl PathLimits {
    fn is_trapezoid(&self) -> bool {
        !finite(self.jerk)
    }

    /// The speed change above which an S-curve reaches full acceleration: a^2 / j.
    fn full_acceleration_change(&self) -> f64 {
        if self.is_trapezoid() {
            0.0
        } else {
            self.acceleration * self.acceleration / self.jerk
        }
    }
}

/// A change of speed from `from` to `to` that starts and ends with zero acceleration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Ramp {
    from: f64,
    to: f64,
    jerk: f64,
    /// Acceleration reached in the middle of the ramp (magnitude).
    peak_acceleration: f64,
    /// Length of each of the two jerk phases (0 for a trapezoid).
    jerk_time: f64,
    /// Length of the constant-acceleration phase.
    constant_time: f64,
}

impl Ramp {
    /// The fastest change of speed under `limits`.
    pub(crate) fn new(from: f64, to: f64, limits: PathLimits) -> Ramp {
        let change = (to - from).abs();
        let a = limits.acceleration;
        let (peak_acceleration, jerk_time, constant_time) = if change <= 0.0 || a <= 0.0 {
            (0.0, 0.0, 0.0)
        } else if limits.is_trapezoid() {
            (a, 0.0, change / a)
        } else if change >= limits.full_acceleration_change() {
            (a, a / limits.jerk, change / a - a / limits.jerk)
        } else {
            // The jerk phases meet before the acceleration limit: a triangle of acceleration.
            let peak = (change * limits.jerk).sqrt();
            (peak, peak / limits.jerk, 0.0)
        };
        Ramp {
            from,
            to,
            jerk: limits.jerk,
            peak_acceleration,
            jerk_time,
            constant_time,
        }
    }

    /// Seconds the ramp takes.
    pub(crate) fn duration(&self) -> f64 {
        2.0 * self.jerk_time + self.constant_time
    }

    /// Distance covered. The acceleration is symmetric about the ramp's middle, so the speed is
    /// point-symmetric there and the mean speed is the mean of the two ends.
    #[cfg(test)]
    pub(crate) fn distance(&self) -> f64 {
        0.5 * (self.from + self.to) * self.duration()
    }

    /// Speed `t` seconds after the ramp starts (clamped to the ramp).
    pub(crate) fn velocity_at(&self, t: f64) -> f64 {
        let sign = if self.to >= self.from { 1.0 } else { -1.0 };
        self.from + sign * self.change_at(t.clamp(0.0, self.duration()))
    }

    /// Signed acceleration `t` seconds after the ramp starts.
    pub(crate) fn acceleration_at(&self, t: f64) -> f64 {
        let sign = if self.to >= self.from { 1.0 } else { -1.0 };
        let total = self.duration();
        if !(0.0..=total).contains(&t) || total == 0.0 {
            return 0.0;
        }
        let magnitude = if t < self.jerk_time {
            self.jerk * t
        } else if t <= self.jerk_time + self.constant_time {
            self.peak_acceleration
        } else {
            self.jerk * (total - t)
        };
        sign * magnitude
    }

    /// How much the speed has changed `t` seconds in (magnitude).
    fn change_at(&self, t: f64) -> f64 {
        let (t1, t2) = (self.jerk_time, self.constant_time);
        let half_jerk = |s: f64| {
            if t1 > 0.0 {
                0.5 * self.jerk * s * s
            } else {
                0.0
            }
        };
        if t < t1 {
            half_jerk(t)
        } else if t <= t1 + t2 {
            half_jerk(t1) + self.peak_acceleration * (t - t1)
        } else {
            (self.to - self.from).abs() - half_jerk(self.duration() - t)
        }
    }
}

/// The highest speed reachable from `speed` by accelerating over `distance` (the same function
/// gives the highest speed from which `speed` can still be reached by braking over `distance`).
pub(crate) fn reachable_speed(speed: f64, distance: f64, limits: PathLimits) -> f64 {
    let (v, d, a) = (speed.max(0.0), distance.max(0.0), limits.acceleration);
    if d == 0.0 || a <= 0.0 {
        return v;
    }
    if limits.is_trapezoid() {
        return (v * v + 2.0 * a * d).sqrt();
    }
    let j = limits.jerk;
    let b = limits.full_acceleration_change();
    // Distance of the ramp that just reaches full acceleration: time 2a/j at mean speed v + b/2.
    let threshold = (2.0 * v + b) * a / j;
    if d >= threshold {
        // Full acceleration reached: (w^2 - v^2) / 2a + (a / 2j)(v + w) = d, a quadratic in w.
        let c = b * v - v * v - 2.0 * a * d;
        0.5 * (-b + (b * b - 4.0 * c).max(0.0).sqrt())
    } else {
        // Jerk phases only: w = v + s^2 with (2v + s^2) s = d sqrt(j), a depressed cubic in s.
        v + jerk_cubic_root(2.0 * v, d * j.sqrt()).powi(2)
    }
}

/// The highest speed reachable from `speed` over `distance`, but no more than `cap`. When the
/// cap can be reached (the common case: a corner or the feed limits the speed, not the room to
/// accelerate), one ramp distance settles it, without solving for the reachable speed.
pub(crate) fn reachable_speed_up_to(
    speed: f64,
    cap: f64,
    distance: f64,
    limits: PathLimits,
) -> f64 {
    if cap <= speed {
        return cap;
    }
    if ramp_distance(speed, cap, limits) <= distance {
        return cap;
    }
    lesser(cap, reachable_speed(speed, distance, limits))
}

/// Seconds of the fastest ramp between `from` and `to` (the same as [`Ramp::duration`], without
/// building the ramp).
#[inline]
fn ramp_time(from: f64, to: f64, limits: PathLimits) -> f64 {
    ramp_time_and_rate((to - from).abs(), limits).0
}

/// Seconds of the fastest ramp over a speed change of `change`, and how fast they grow with the
/// change (0 for no change; callers that want only the time leave the rate to the compiler,
/// which drops it).
#[inline]
fn ramp_time_and_rate(change: f64, limits: PathLimits) -> (f64, f64) {
    let a = limits.acceleration;
    if change <= 0.0 || a <= 0.0 {
        (0.0, 0.0)
    } else if limits.is_trapezoid() {
        (change / a, 1.0 / a)
    } else if change * limits.jerk >= a * a {
        // At least a^2 / j ([`PathLimits::full_acceleration_change`]), tested without dividing.
        (change / a + a / limits.jerk, 1.0 / a)
    } else {
        // T = 2 sqrt(change / j), whose derivative 1 / sqrt(change j) is 2 / (j T).
        let time = 2.0 * (change / limits.jerk).sqrt();
        (time, 2.0 / (limits.jerk * time))
    }
}

/// The distance of the fastest ramp between `from` and `to` (the same as [`Ramp::distance`]).
fn ramp_distance(from: f64, to: f64, limits: PathLimits) -> f64 {
    0.5 * (from + to) * ramp_time(from, to, limits)
}

/// The real root of s^3 + p s - q = 0 for p >= 0, q >= 0 (Cardano, then one Newton step for
/// the cancellation in its second term when p is large).
fn jerk_cubic_root(p: f64, q: f64) -> f64 {
    let half = 0.5 * q;
    let root = (half * half + (p / 3.0).powi(3)).sqrt();
    let c = (half + root).cbrt();
    let mut s = if c > 0.0 { c - p / (3.0 * c) } else { 0.0 };
    s = s.max(0.0);
    let slope = 3.0 * s * s + p;
    if slope > 0.0 {
        s -= (s * s * s + p * s - q) / slope;
    }
    s.max(0.0)
}

const HUGE_SPEED: f64 = 1e9;
const HUGE_ACCELERATION: f64 = 1e12;

/// The speed profile of one segment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpeedProfile {
    /// Path length, mm.
    pub length: f64,
    /// Speed at the start, mm/s.
    pub entry: f64,
    /// Highest speed on the segment, mm/s.
    pub peak: f64,
    /// Speed at the end, mm/s.
    pub exit: f64,
    /// The limits it was shaped with.
    pub limits: PathLimits,
    /// A stretch at the entry speed before the ramps (a corner blend's arc), s.
    lead_in_time: f64,
    /// Durations of the ramp up to the peak, the cruise, and the ramp down. The ramps themselves
    /// are rebuilt when a profile is sampled: a profile travels with every timed segment, so it
    /// is kept small.
    up_time: f64,
    cruise_time: f64,
    down_time: f64,
}

impl SpeedProfile {
    /// The fastest profile over `length` from `entry` to `exit` that stays under `cruise` and
    /// `limits`. The look-ahead passes only ask for feasible end speeds; a pair that is slightly
    /// out of reach (rounding) gets the closest feasible profile rather than an error.
    // Inlined: the planner's callers that only want the duration then skip building the rest;
    // the rare profile that does not reach its cruise speed is worked out in `peaked`.
    #[inline]
    pub fn new(
        length: f64,
        entry: f64,
        exit: f64,
        cruise: f64,
        limits: PathLimits,
    ) -> SpeedProfile {
        // An axis without limits gives infinite caps; huge finite ones keep the arithmetic free
        // of inf - inf and take no measurable time.
        let limits = PathLimits {
            acceleration: lesser(HUGE_ACCELERATION, limits.acceleration),
            jerk: limits.jerk,
        };
        let length = greater(0.0, length);
        let cruise = greater(greater(lesser(HUGE_SPEED, cruise), entry), exit);
        if entry == cruise && exit == cruise {
            // The commonest profile of a contour: entered and left at the cruise speed, which
            // gentle corners allow. Both ramps are empty, and the general way would find the
            // same: ramps of no time, the whole length left at the cruise speed.
            return SpeedProfile::at_cruise(length, (entry, cruise, exit), limits);
        }
        SpeedProfile::ramped(length, (entry, cruise, exit), limits)
    }

    /// [`SpeedProfile::new`] after its bounds, in general: `length` not negative, `cruise` not
    /// below `entry` and `exit`, finite limits of acceleration.
    #[inline]
    fn ramped(
        length: f64,
        (entry, cruise, exit): (f64, f64, f64),
        limits: PathLimits,
    ) -> SpeedProfile {
        // Most segments reach their cruise speed: the ramps to it settle the profile. Between
        // two stops (SINUMERIK's G60 at every corner) the ramp down mirrors the ramp up, the
        // same change of speed to the bit.
        let mut up_time = ramp_time(entry, cruise, limits);
        let mut down_time = if exit == entry {
            up_time
        } else {
            ramp_time(cruise, exit, limits)
        };
        let mut rest = length - 0.5 * ((entry + cruise) * up_time + (cruise + exit) * down_time);
        let mut peak = cruise;
        if rest < 0.0 {
            (peak, up_time, down_time, rest) = peaked(length, entry, exit, cruise, limits);
        }
        let cruise_time = if rest > 0.0 && peak > 0.0 {
            rest / peak
        } else {
            0.0
        };
        SpeedProfile {
            length,
            entry,
            peak,
            exit,
            limits,
            lead_in_time: 0.0,
            up_time,
            cruise_time,
            down_time,
        }
    }

    /// The profile of `length` entered and left at its cruise speed (`entry` and `exit` equal
    /// to `cruise`, finite): no ramps, the whole length at the cruise speed.
    #[inline]
    fn at_cruise(
        length: f64,
        (entry, cruise, exit): (f64, f64, f64),
        limits: PathLimits,
    ) -> SpeedProfile {
        let cruise_time = if length > 0.0 && cruise > 0.0 {
            length / cruise
        } else {
            0.0
        };
        SpeedProfile {
            length,
            entry,
            peak: cruise,
            exit,
            limits,
            lead_in_time: 0.0,
            up_time: 0.0,
            cruise_time,
            down_time: 0.0,
        }
    }

    /// The same profile after `distance` passed at the entry speed (a corner blend's arc). At a
    /// standstill there is no arc to pass: the distance is the ramps' business then, and the
    /// look-ahead never plans a blend at zero speed.
    #[inline]
    pub fn with_lead_in(mut self, distance: f64) -> SpeedProfile {
        if distance > 0.0 && self.entry > 1e-9 {
            self.lead_in_time = distance / self.entry;
            self.length += distance;
        }
        self
    }

    /// The same profile after `distance` passed in `seconds` before it (a corner blend's arc
    /// planned as a motion of its own, whose speeds are not kept: over it the profile gives the
    /// speed it starts with).
    #[inline]
    pub fn with_lead_in_time(mut self, distance: f64, seconds: f64) -> SpeedProfile {
        if seconds > 0.0 {
            self.lead_in_time += seconds;
            self.length += distance;
        }
        self
    }

    /// Seconds the segment takes.
    #[inline]
    pub fn duration(&self) -> f64 {
        self.lead_in_time + self.up_time + self.cruise_time + self.down_time
    }

    /// Path speed `t` seconds into the segment.
    pub fn velocity_at(&self, t: f64) -> f64 {
        if t < self.lead_in_time {
            return self.entry;
        }
        let t = t - self.lead_in_time;
        let (t_up, t_cruise) = (self.up_time, self.cruise_time);
        if t <= t_up {
            Ramp::new(self.entry, self.peak, self.limits).velocity_at(t)
        } else if t <= t_up + t_cruise {
            self.peak
        } else {
            Ramp::new(self.peak, self.exit, self.limits).velocity_at(t - t_up - t_cruise)
        }
    }

    /// Path (tangential) acceleration `t` seconds into the segment.
    pub fn acceleration_at(&self, t: f64) -> f64 {
        if t < self.lead_in_time {
            return 0.0;
        }
        let t = t - self.lead_in_time;
        let (t_up, t_cruise) = (self.up_time, self.cruise_time);
        if t <= t_up {
            Ramp::new(self.entry, self.peak, self.limits).acceleration_at(t)
        } else if t <= t_up + t_cruise {
            0.0
        } else {
            Ramp::new(self.peak, self.exit, self.limits).acceleration_at(t - t_up - t_cruise)
        }
    }
}

/// The peak speed, the durations of the ramps up to it and down from it, and the length left
/// over (not positive, but for rounding) of a profile whose ramps to its cruise speed do not fit
/// in its length.
#[cold]
#[inline(never)]
fn peaked(
    length: f64,
    entry: f64,
    exit: f64,
    cruise: f64,
    limits: PathLimits,
) -> (f64, f64, f64, f64) {
    let peak = peak_speed(length, entry, exit, cruise, limits);
    let (up_time, down_time) = (
        ramp_time(entry, peak, limits),
        ramp_time(peak, exit, limits),
    );
    let rest = length - 0.5 * ((entry + peak) * up_time + (peak + exit) * down_time);
    (peak, up_time, down_time, rest)
}

/// The peak speed of the fastest profile when the ramps up to the cruise speed and down from it
/// do not fit in the length (the caller has found that): the speed at which they meet.
fn peak_speed(length: f64, entry: f64, exit: f64, cruise: f64, limits: PathLimits) -> f64 {
    let low = entry.max(exit);
    let needed = |peak: f64| ramp_distance(entry, peak, limits) + ramp_distance(peak, exit, limits);
    if needed(low) >= length {
        return low;
    }
    let a = limits.acceleration;
    if limits.is_trapezoid() {
        // (p^2 - entry^2) / 2a + (p^2 - exit^2) / 2a = length.
        let p = (a * length + 0.5 * (entry * entry + exit * exit)).sqrt();
        return p.clamp(low, cruise);
    }
    if (entry - exit).abs() <= 1e-12 * cruise.max(1.0) {
        // Two mirror-image ramps, each over half the length.
        return reachable_speed(entry, 0.5 * length, limits).clamp(low, cruise);
    }
    // Both ramps at full acceleration: p^2 / a + (a/j) p + (a/2j)(entry + exit)
    // - (entry^2 + exit^2) / 2a - length = 0. Valid when both changes exceed a^2 / j.
    let b = limits.full_acceleration_change();
    let c = 0.5 * b * (entry + exit) - 0.5 * (entry * entry + exit * exit) - a * length;
    let p = 0.5 * (-b + (b * b - 4.0 * c).max(0.0).sqrt());
    if p - low >= b && p <= cruise {
        return p;
    }
    // One ramp jerk-limited and the other not, or both with different ends: no tidy closed form
    // for the peak. Newton's method on the distance the two ramps need, which grows with the
    // peak (each ramp's time and its rate of change stay closed-form), inside the bracket of
    // peaks too low and too high: a step that would leave it, or a slope that is not a number,
    // bisects instead. About six steps where bisection took over forty, each with two roots:
    // CAM paths of short segments with S-curves meet this case at every few corners.
    let (mut lo, mut hi) = (low, cruise);
    let mut peak = 0.5 * (lo + hi);
    for _ in 0..200 {
        let (up, up_slope) = ramp_distance_and_slope(entry, peak, limits);
        let (down, down_slope) = ramp_distance_and_slope(exit, peak, limits);
        let excess = up + down - length;
        if excess > 0.0 {
            hi = peak;
        } else {
            lo = peak;
        }
        if excess == 0.0 {
            return peak;
        }
        let newton = peak - excess / (up_slope + down_slope);
        if newton >= lo && newton <= hi {
            if (newton - peak).abs() <= 1e-13 * peak {
                return newton;
            }
            peak = newton;
        } else {
            if hi - lo <= 1e-13 * hi {
                return lo;
            }
            peak = 0.5 * (lo + hi);
        }
    }
    peak
}

/// The distance of the fastest ramp between `speed` and `peak` (not below it), and how fast
/// that distance grows with the peak: the derivative of 0.5 (speed + peak) T, T the ramp's
/// time ([`ramp_time_and_rate`]).
#[inline]
fn ramp_distance_and_slope(speed: f64, peak: f64, limits: PathLimits) -> (f64, f64) {
    let (time, rate) = ramp_time_and_rate(peak - speed, limits);
    let mean = 0.5 * (speed + peak);
    (mean * time, 0.5 * time + mean * rate)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const TRAPEZOID: PathLimits = PathLimits {
        acceleration: 1000.0,
        jerk: f64::INFINITY,
    };
    const S_CURVE: PathLimits = PathLimits {
        acceleration: 1000.0,
        jerk: 20000.0,
    };

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-9 * b.abs().max(1.0)
    }

    #[test]
    fn a_ramp_covers_its_mean_speed_times_its_duration() {
        for limits in [TRAPEZOID, S_CURVE] {
            for (from, to) in [(0.0, 100.0), (100.0, 10.0), (30.0, 31.0)] {
                let ramp = Ramp::new(from, to, limits);
                let steps = 20_000;
                let dt = ramp.duration() / f64::from(steps);
                let sum: f64 = (0..steps)
                    .map(|i| ramp.velocity_at((f64::from(i) + 0.5) * dt) * dt)
                    .sum();
                assert!((sum - ramp.distance()).abs() < 1e-6, "{from} -> {to}");
                assert!(close(ramp.velocity_at(ramp.duration()), to));
            }
        }
    }

    #[test]
    fn reachable_speed_inverts_the_ramp_distance() {
        for limits in [TRAPEZOID, S_CURVE] {
            for (from, distance) in [(0.0, 0.01), (0.0, 50.0), (40.0, 0.001), (40.0, 20.0)] {
                let w = reachable_speed(from, distance, limits);
                let ramp = Ramp::new(from, w, limits);
                assert!(close(ramp.distance(), distance), "{from} {distance} {w}");
            }
        }
    }

    #[test]
    fn an_unequal_s_curve_profile_fits_its_length() {
        for (entry, exit, length) in [(0.0, 30.0, 2.0), (50.0, 5.0, 3.0), (10.0, 12.0, 0.5)] {
            let profile = SpeedProfile::new(length, entry, exit, 1000.0, S_CURVE);
            let up = Ramp::new(entry, profile.peak, S_CURVE);
            let covered = up.distance() + Ramp::new(profile.peak, exit, S_CURVE).distance();
            assert!((covered - length).abs() < 1e-9, "{entry} {exit} {length}");
        }
    }

    #[test]
    fn a_capped_reach_is_the_cap_or_the_reachable_speed() {
        for limits in [TRAPEZOID, S_CURVE] {
            for (from, cap, distance) in [(0.0, 50.0, 0.1), (0.0, 50.0, 100.0), (30.0, 10.0, 1.0)] {
                let capped = reachable_speed_up_to(from, cap, distance, limits);
                let expected = reachable_speed(from, distance, limits).min(cap);
                assert!(close(capped, expected), "{from} {cap} {distance}");
            }
        }
    }

    #[test]
    fn the_ramp_shortcuts_agree_with_the_ramp() {
        for limits in [TRAPEZOID, S_CURVE] {
            for (from, to) in [(0.0, 100.0), (100.0, 10.0), (30.0, 31.0), (5.0, 5.0)] {
                let ramp = Ramp::new(from, to, limits);
                assert!(close(ramp_time(from, to, limits), ramp.duration()));
                assert!(close(ramp_distance(from, to, limits), ramp.distance()));
            }
        }
    }

    /// The bits of every field of a profile.
    fn profile_bits(p: &SpeedProfile) -> [u64; 10] {
        [
            p.length,
            p.entry,
            p.peak,
            p.exit,
            p.limits.acceleration,
            p.limits.jerk,
            p.lead_in_time,
            p.up_time,
            p.cruise_time,
            p.down_time,
        ]
        .map(f64::to_bits)
    }

    fn limits() -> impl Strategy<Value = PathLimits> {
        let positive = prop_oneof![Just(f64::INFINITY), 1e-3..1e7_f64, Just(0.0)];
        (positive.clone(), positive)
            .prop_map(|(acceleration, jerk)| PathLimits { acceleration, jerk })
    }

    proptest! {
        /// A profile entered and left at its cruise speed is what the ramps of the general
        /// way give, to the bit.
        #[test]
        fn a_profile_at_its_cruise_speed_is_the_general_one(
            length in prop_oneof![Just(0.0), Just(-1.0), 1e-9..1e4_f64],
            speed in prop_oneof![Just(0.0), 1e-9..1e4_f64, Just(1e9), Just(2e9)],
            limits in limits(),
        ) {
            let fast = SpeedProfile::new(length, speed, speed, speed, limits);
            let bounded = PathLimits {
                acceleration: lesser(HUGE_ACCELERATION, limits.acceleration),
                jerk: limits.jerk,
            };
            // Any speed not below zero is its own cruise speed after the bounds.
            let general = SpeedProfile::ramped(greater(0.0, length), (speed, speed, speed), bounded);
            prop_assert_eq!(profile_bits(&fast), profile_bits(&general));
        }
    }

    /// The peak by bisection to the last bit, as it was found before Newton's method.
    fn bisected_peak(length: f64, entry: f64, exit: f64, cruise: f64, limits: PathLimits) -> f64 {
        let needed =
            |peak: f64| ramp_distance(entry, peak, limits) + ramp_distance(peak, exit, limits);
        let (mut lo, mut hi) = (entry.max(exit), cruise);
        for _ in 0..2000 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if needed(mid) > length {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        lo
    }

    proptest! {
        /// Where the two ramps do not both reach full acceleration, the peak found by Newton's
        /// method is the one bisection finds, to 1e-10 of it (where the distance grows slowly
        /// with the peak, rounding alone leaves that much room), and its ramps fit the length.
        #[test]
        fn the_searched_peak_is_the_bisected_one(
            entry in 0.0..200.0_f64,
            exit in 0.0..200.0_f64,
            length in 1e-6..50.0_f64,
            acceleration in 10.0..1e5_f64,
            jerk in 100.0..1e7_f64,
        ) {
            let limits = PathLimits { acceleration, jerk };
            let cruise = 1e4;
            let needed = |peak: f64| ramp_distance(entry, peak, limits) + ramp_distance(peak, exit, limits);
            prop_assume!(needed(entry.max(exit)) < length && needed(cruise) > length);
            let found = peak_speed(length, entry, exit, cruise, limits);
            let bisected = bisected_peak(length, entry, exit, cruise, limits);
            prop_assert!((found - bisected).abs() <= 1e-10 * bisected, "{} {}", found, bisected);
            prop_assert!((needed(found) - length).abs() <= 1e-9 * length.max(1.0));
        }
    }

    #[test]
    fn a_peak_whose_ramps_meet_the_length_exactly_is_kept() {
        // Newton's method lands on a peak whose ramps cover the length to the bit: that peak is
        // the answer (an early version took the middle of the bracket there instead).
        let limits = PathLimits {
            acceleration: 71_101.332_007_420_58,
            jerk: 8_349_417.243_764_563,
        };
        let (entry, exit, length) = (
            148.601_394_216_499_64,
            101.761_413_237_097_9,
            2.418_848_705_369_914,
        );
        let peak = peak_speed(length, entry, exit, 1e4, limits);
        let bisected = bisected_peak(length, entry, exit, 1e4, limits);
        assert!(
            (peak - bisected).abs() <= 1e-10 * bisected,
            "{peak} {bisected}"
        );
    }

    #[test]
    fn a_zero_length_segment_takes_no_time() {
        let profile = SpeedProfile::new(0.0, 0.0, 0.0, 100.0, S_CURVE);
        assert_eq!(profile.duration(), 0.0);
    }
}
