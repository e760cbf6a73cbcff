//! Machine limits seen along one segment's path.
//!
//! The machine file gives per-axis limits (rates in mm/min, acceleration mm/s^2, jerk mm/s^3).
//! A segment moves several axes at once; each axis sees the path speed times its share of the
//! direction, so the path may go as fast as the tightest axis allows: v <= v_axis / |u_axis|.
//! Arcs add the centripetal acceleration v^2 / r, which takes a share of the acceleration
//! limit and leaves the rest to the tangent.
//!
//! Everything here is in mm/s, mm/s^2 and mm/s^3 (degrees for rotary axes). An axis the machine
//! does not have, or a limit that is not a positive number, limits nothing.

use super::config::PlannerConfig;
use super::speed_profile::{PathLimits, SpeedProfile};
use super::{finite, greater, lesser};
use crate::machine::{Machine, AXES};
use crate::motion::{arc_sweep, ArcDirection, Feed, MachinePos, Move, PathMode, Plane};

/// Per-axis limits of a machine, in seconds-based units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct AxisLimits {
    /// Highest cutting speed per axis, mm/s.
    pub(crate) feed: [f64; AXES],
    /// Rapid speed per axis, mm/s.
    pub(crate) rapid: [f64; AXES],
    /// Acceleration per axis, mm/s^2.
    pub(crate) acceleration: [f64; AXES],
    /// Jerk per axis, mm/s^3 (infinite: no jerk limit).
    pub(crate) jerk: [f64; AXES],
    /// Path speed cap, mm/s.
    pub(crate) path_speed: f64,
    /// One past the last axis the machine has: the axes after it never limit anything.
    pub(crate) span: usize,
    /// X, Y and Z have the same acceleration and the same jerk (as on most machines; or none
    /// of them is there): see [`AxisLimits::project_xyz`].
    uniform_xyz: bool,
    /// The reciprocals of the limits above (0 for none), so that projecting them onto a
    /// direction takes one division, not one per axis.
    inverse: Inverses,
}

#[derive(Clone, Copy, Debug, PartialEq)]
struct Inverses {
    feed: [f64; AXES],
    rapid: [f64; AXES],
    acceleration: [f64; AXES],
    jerk: [f64; AXES],
}

fn reciprocals(values: &[f64; AXES]) -> [f64; AXES] {
    values.map(|v| 1.0 / v)
}

fn positive_or_infinite(value: f64) -> f64 {
    if value > 0.0 {
        value
    } else {
        f64::INFINITY
    }
}

impl AxisLimits {
    pub(crate) fn new(machine: &Machine, config: &PlannerConfig) -> AxisLimits {
        let field = |f: fn(&crate::machine::AxisConfig) -> f64, scale: f64| {
            std::array::from_fn(|i| {
                machine.axes[i]
                    .as_ref()
                    .map_or(f64::INFINITY, |axis| positive_or_infinite(f(axis)) * scale)
            })
        };
        let span = (0..AXES)
            .rev()
            .find(|&i| machine.axes[i].is_some())
            .map_or(0, |i| i + 1);
        AxisLimits::with(
            [
                field(|a| a.max_feed, 1.0 / 60.0),
                field(|a| a.rapid, 1.0 / 60.0),
                field(|a| a.acceleration, 1.0),
                field(|a| a.jerk, 1.0),
            ],
            positive_or_infinite(config.max_path_rate) / 60.0,
            span,
        )
    }

    /// The limits of feed, rapid, acceleration and jerk per axis, with what follows from them.
    fn with(
        [feed, rapid, acceleration, jerk]: [[f64; AXES]; 4],
        path_speed: f64,
        span: usize,
    ) -> AxisLimits {
        let same_on_xyz = |values: &[f64; AXES]| values[1] == values[0] && values[2] == values[0];
        AxisLimits {
            feed,
            rapid,
            acceleration,
            jerk,
            path_speed,
            span,
            uniform_xyz: same_on_xyz(&acceleration) && same_on_xyz(&jerk),
            inverse: Inverses {
                feed: reciprocals(&feed),
                rapid: reciprocals(&rapid),
                acceleration: reciprocals(&acceleration),
                jerk: reciprocals(&jerk),
            },
        }
    }

    /// These limits with each axis's speeds, acceleration and jerk scaled by its `factors`
    /// (velocity, acceleration, jerk; SINUMERIK VELOLIMA, ACCLIMA, JERKLIMA).
    pub(crate) fn scaled(&self, factors: &[[f64; 3]; AXES]) -> AxisLimits {
        let scale =
            |values: &[f64; AXES], k: usize| std::array::from_fn(|i| values[i] * factors[i][k]);
        AxisLimits::with(
            [
                scale(&self.feed, 0),
                scale(&self.rapid, 0),
                scale(&self.acceleration, 1),
                scale(&self.jerk, 2),
            ],
            self.path_speed,
            self.span,
        )
    }
}

/// What the look-ahead needs to know of one motion.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct MotionLimits {
    /// Path length, mm (degrees for a rotary-only move).
    pub(crate) length: f64,
    /// Speed the segment would like to cruise at: programmed feed (after override) or rapid,
    /// capped by the axes, mm/s.
    pub(crate) cruise: f64,
    /// Tangential acceleration and jerk along the path.
    pub(crate) path: PathLimits,
    /// The tangential acceleration when the segment ends without blending into a next motion
    /// (see `PlannerConfig::unblended_acceleration_factor`).
    pub(crate) unblended_acceleration: f64,
    /// The feed could not be known (G95 without a spindle speed): timed at the axis limit.
    pub(crate) feed_unknown: bool,
    /// The factor the acceleration has been scaled by for its ends (1: not scaled).
    pub(crate) acceleration_scale: f64,
}

/// What the junctions with a motion's neighbours need besides its limits: the unit tangents
/// over X Y Z at its start and at its end (zero for a move without XYZ travel) and the
/// acceleration available for turning. Kept apart from [`MotionLimits`], which stays in the
/// look-ahead window for the whole passage of the motion, while this is needed only until the
/// next motion has entered.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Ends {
    pub(crate) start: [f64; 3],
    pub(crate) end: [f64; 3],
    /// Acceleration available for turning (corner blends): the lowest limit of the axes that
    /// move, mm/s^2.
    pub(crate) turning: f64,
    /// An arc's shape, for LinuxCNC's blends next to it; None for a straight move.
    pub(crate) bend: Option<Bend>,
}

/// An arc's shape as a corner blend next to it sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Bend {
    /// The unit normal of the arc's plane whose cross product with a tangent points at the
    /// centre (the plane's normal axis, negated for a clockwise arc).
    pub(crate) curl: [f64; 3],
    pub(crate) radius: f64,
    /// The angle the arc sweeps, radians.
    pub(crate) sweep: f64,
}

/// What the axes allow along a motion: the caps their limits put on the path.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Projection {
    /// Path speed the axes' rates (cutting or rapid) allow, mm/s.
    speed: f64,
    /// Path acceleration and jerk the axes allow.
    acceleration: f64,
    jerk: f64,
    /// The lowest acceleration limit among the axes with a share of the motion.
    turning: f64,
}

impl AxisLimits {
    /// The caps for a move with per-axis shares `share` (|direction component| per unit of
    /// path): for each limit, min over axes of limit / share, from the limits' reciprocals.
    /// One pass over the axes for all of them, and only over those the machine has: an axis it
    /// lacks has infinite limits (zero reciprocals) and never caps anything.
    fn project(&self, share: &[f64; AXES], rapid: bool) -> Projection {
        self.project_first(&share[..self.span], rapid)
    }

    /// [`AxisLimits::project`] over X Y Z alone, for a machine without further axes or a move
    /// that moves no other axis (an arc). The three iterations are unrolled; an axis among X Y Z
    /// that the machine lacks caps nothing, as in the general loop.
    #[inline(always)]
    fn project_xyz(&self, share: &[f64; 3], rapid: bool) -> Projection {
        if self.uniform_xyz {
            return self.project_uniform_xyz(share, rapid);
        }
        self.project_first(share, rapid)
    }

    /// [`AxisLimits::project_xyz`] on a machine whose X, Y and Z have the same acceleration and
    /// jerk. Then the largest share caps both, and gives the same caps as the general loop to
    /// the bit: a product rounded is never smaller than one of a smaller share rounded, so the
    /// largest product is that of the largest share. The turning acceleration is the axes' one,
    /// since a move with X Y Z travel has a share of at least 1/sqrt(3) on one of them.
    #[inline(always)]
    fn project_uniform_xyz(&self, share: &[f64; 3], rapid: bool) -> Projection {
        let rates = if rapid {
            &self.inverse.rapid
        } else {
            &self.inverse.feed
        };
        let mut speed = 0.0_f64;
        let mut largest = 0.0_f64;
        for (i, &s) in share.iter().enumerate() {
            let demand = s * rates[i];
            if demand > speed {
                speed = demand;
            }
            if s > largest {
                largest = s;
            }
        }
        // The general loop starts from 0 too: a share of 0 everywhere caps nothing.
        let acceleration = greater(0.0, largest * self.inverse.acceleration[0]);
        let jerk = greater(0.0, largest * self.inverse.jerk[0]);
        Projection {
            speed: 1.0 / speed,
            acceleration: 1.0 / acceleration,
            jerk: 1.0 / jerk,
            turning: if largest > 1e-12 {
                self.acceleration[0]
            } else {
                f64::INFINITY
            },
        }
    }

    /// The caps from the shares of the first `share.len()` axes (the others do not move, or the
    /// machine does not have them).
    #[inline(always)]
    fn project_first(&self, share: &[f64], rapid: bool) -> Projection {
        let rates = if rapid {
            &self.inverse.rapid
        } else {
            &self.inverse.feed
        };
        let (mut speed, mut acceleration, mut jerk) = (0.0_f64, 0.0_f64, 0.0_f64);
        let mut turning = f64::INFINITY;
        for (i, &s) in share.iter().enumerate() {
            // Plain comparisons, not f64::max: no NaN can reach here, and each is one
            // instruction.
            let demand = s * rates[i];
            if demand > speed {
                speed = demand;
            }
            let demand = s * self.inverse.acceleration[i];
            if demand > acceleration {
                acceleration = demand;
            }
            let demand = s * self.inverse.jerk[i];
            if demand > jerk {
                jerk = demand;
            }
            if s > 1e-12 && self.acceleration[i] < turning {
                turning = self.acceleration[i];
            }
        }
        Projection {
            speed: 1.0 / speed,
            acceleration: 1.0 / acceleration,
            jerk: 1.0 / jerk,
            turning,
        }
    }
}

/// Length, the axes' caps and the unit direction over X Y Z of a straight move.
#[inline(always)]
fn straight(motion: &Move, axes: &AxisLimits, rapid: bool) -> (f64, Projection, [f64; 3]) {
    let (from, to) = (&motion.from.0, &motion.to.0);
    let delta = [to[0] - from[0], to[1] - from[1], to[2] - from[2]];
    let linear = (delta[0] * delta[0] + delta[1] * delta[1] + delta[2] * delta[2]).sqrt();
    // The common case: a machine without axes after Z, and a move with X Y Z travel. Its
    // shares are the absolute values of its direction, and only X Y Z can cap it; the general
    // path below gives the same values over all six axes.
    if axes.span <= 3 && linear > 1e-9 {
        let per_length = 1.0 / linear;
        let direction = delta.map(|d| d * per_length);
        let share = direction.map(f64::abs);
        return (linear, axes.project_xyz(&share, rapid), direction);
    }
    let (length, share, direction) = straight_path(motion);
    (length, axes.project(&share, rapid), direction)
}

fn straight_path(motion: &Move) -> (f64, [f64; AXES], [f64; 3]) {
    let delta: [f64; AXES] = std::array::from_fn(|i| motion.to.0[i] - motion.from.0[i]);
    let linear = (delta[0] * delta[0] + delta[1] * delta[1] + delta[2] * delta[2]).sqrt();
    // A rotary-only move is measured in degrees (its feed is deg/min, as on the controls).
    let length = if linear > 1e-9 {
        linear
    } else {
        delta[3..].iter().map(|d| d * d).sum::<f64>().sqrt()
    };
    if length <= 1e-12 {
        return (0.0, [0.0; AXES], [0.0; 3]);
    }
    let per_length = 1.0 / length;
    let share = delta.map(|d| (d * per_length).abs());
    let direction = if linear > 1e-9 {
        [delta[0], delta[1], delta[2]].map(|d| d * per_length)
    } else {
        [0.0; 3]
    };
    (length, share, direction)
}

/// The programmed path speed, mm/s, of a cutting move, or None when it cannot be known.
#[inline(always)]
fn programmed_speed(feed: &Feed, length: f64, feed_override: f64) -> Option<f64> {
    feed.mm_per_min(length)
        .filter(|&f| f > 0.0 && finite(f))
        .map(|f| f / 60.0 * feed_override)
}

/// The path speed of the last feed per minute met, kept for the moves after it: consecutive
/// moves mostly share their feed and override, and comparing them costs less than working the
/// speed out again (a test of the feed, a division and a multiplication).
///
/// It always holds the speed [`programmed_speed`] gives for a feed per minute of `feed` under
/// `feed_override` (their bits), at first for a feed that is not a number.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FeedSpeeds {
    feed: u64,
    feed_override: u64,
    speed: Option<f64>,
}

impl Default for FeedSpeeds {
    fn default() -> FeedSpeeds {
        FeedSpeeds {
            feed: f64::NAN.to_bits(),
            feed_override: 1.0_f64.to_bits(),
            speed: programmed_speed(&Feed::PerMinute(f64::NAN), 0.0, 1.0),
        }
    }
}

impl FeedSpeeds {
    /// [`programmed_speed`], from the kept speed when the feed per minute and the override are
    /// those of last time.
    #[inline(always)]
    pub(crate) fn speed(&mut self, feed: &Feed, length: f64, feed_override: f64) -> Option<f64> {
        let Feed::PerMinute(per_minute) = *feed else {
            return programmed_speed(feed, length, feed_override);
        };
        let key = (per_minute.to_bits(), feed_override.to_bits());
        if key != (self.feed, self.feed_override) {
            *self = FeedSpeeds {
                feed: key.0,
                feed_override: key.1,
                speed: programmed_speed(feed, length, feed_override),
            };
        }
        self.speed
    }
}

impl MotionLimits {
    /// Scales the acceleration for one end: a stop (see
    /// `PlannerConfig::stop_acceleration_factor`) or a kink (`PlannerConfig::kink_ratio`). The
    /// two ends do not compound: the smaller factor holds (LinuxCNC's tc.c
    /// `tcGetOverallMaxAccel` takes the larger of the two reductions).
    pub(crate) fn scale_acceleration(&mut self, factor: f64) {
        if factor < self.acceleration_scale {
            let step = factor / self.acceleration_scale;
            self.acceleration_scale = factor;
            self.path.acceleration *= step;
            self.unblended_acceleration *= step;
        }
    }
}

/// Caps infinite limits (axes the machine does not limit) at values far beyond any machine,
/// so that the planner's arithmetic never meets inf - inf.
#[inline(always)]
fn bounded((mut limits, mut ends): (MotionLimits, Ends)) -> (MotionLimits, Ends) {
    limits.cruise = lesser(1e9, limits.cruise);
    limits.path.acceleration = lesser(1e12, limits.path.acceleration);
    limits.unblended_acceleration = lesser(1e12, limits.unblended_acceleration);
    ends.turning = lesser(1e12, ends.turning);
    (limits, ends)
}

/// The limits of a straight move, a rapid when `feed` is None.
// Inlined into the timeline's push: the limits and ends are built where they are kept instead
// of being returned through calls.
#[inline(always)]
pub(crate) fn line(
    motion: &Move,
    feed: Option<(&Feed, &mut FeedSpeeds)>,
    axes: &AxisLimits,
    config: &PlannerConfig,
    feed_override: f64,
) -> (MotionLimits, Ends) {
    bounded(unbounded_line(motion, feed, axes, config, feed_override))
}

/// [`line`] before [`bounded`]: the limits as the axes and the feed give them.
#[inline(always)]
fn unbounded_line(
    motion: &Move,
    feed: Option<(&Feed, &mut FeedSpeeds)>,
    axes: &AxisLimits,
    config: &PlannerConfig,
    feed_override: f64,
) -> (MotionLimits, Ends) {
    let (length, caps, direction) = straight(motion, axes, feed.is_none());
    let axis_speed = lesser(axes.path_speed, caps.speed);
    let programmed = feed.map(|(f, speeds)| speeds.speed(f, length, feed_override));
    let cruise = match programmed {
        Some(Some(v)) => lesser(v, axis_speed),
        _ => axis_speed,
    };
    let acceleration = caps.acceleration;
    let continuous = motion.path_mode == PathMode::Continuous && !motion.exact_stop;
    let limits = MotionLimits {
        length,
        cruise,
        path: PathLimits {
            acceleration,
            jerk: caps.jerk,
        },
        // Only a segment that could have blended is planned with the reduced acceleration.
        unblended_acceleration: if continuous {
            acceleration * config.unblended_acceleration_factor
        } else {
            acceleration
        },
        feed_unknown: matches!(programmed, Some(None)),
        acceleration_scale: 1.0,
    };
    let ends = Ends {
        start: direction,
        end: direction,
        turning: caps.turning,
        bend: None,
    };
    (limits, ends)
}

/// An arc's geometry, as [`arc`] takes it.
pub(crate) struct ArcPath<'a> {
    pub(crate) motion: &'a Move,
    pub(crate) center: &'a MachinePos,
    pub(crate) direction: ArcDirection,
    pub(crate) plane: Plane,
    pub(crate) extra_turns: u32,
    pub(crate) feed: &'a Feed,
}

/// The limits of an arc.
#[inline(always)]
pub(crate) fn arc(
    path: &ArcPath<'_>,
    speeds: &mut FeedSpeeds,
    axes: &AxisLimits,
    config: &PlannerConfig,
    feed_override: f64,
) -> (MotionLimits, Ends) {
    let ArcPath {
        motion,
        center,
        direction,
        plane,
        extra_turns,
        feed,
    } = *path;
    let (a, b, n) = plane.axes();
    // Plain square roots, not hypot: machine coordinates are far from overflow and underflow,
    // where hypot's care lies, and that care costs several times a square root.
    #[allow(clippy::imprecise_flops)]
    let norm = |x: f64, y: f64| (x * x + y * y).sqrt();
    let radius = norm(
        motion.from.0[a] - center.0[a],
        motion.from.0[b] - center.0[b],
    );
    let sweep = arc_sweep(motion, center, direction, plane, extra_turns);
    let planar = radius * sweep;
    let axial = motion.to.0[n] - motion.from.0[n];
    let length = norm(planar, axial);
    if length <= 1e-12 || radius <= 1e-12 {
        return line(motion, Some((feed, speeds)), axes, config, feed_override);
    }
    // The tangent turns through the plane, so each plane axis carries the whole planar share
    // somewhere on a long enough arc; taking it everywhere is the safe side. The plane's axes
    // are among X Y Z, and no other axis moves.
    let (p, q) = (planar / length, axial.abs() / length);
    let mut share = [0.0; 3];
    share[a] = p;
    share[b] = p;
    share[n] = q;
    let caps = axes.project_xyz(&share, false);
    // The minima and maxima below take a first value that is never NaN (the path speed and the
    // axes' limits, and what comes of them): one instruction each, see `lesser`.
    let axis_speed = lesser(axes.path_speed, caps.speed);
    let plane_acceleration = lesser(axes.acceleration[a], axes.acceleration[b]);
    // v_planar^2 / r <= share * a, with v_planar = p v.
    let centripetal_speed =
        (config.normal_acceleration_share * plane_acceleration * radius).sqrt() / p;
    let top = lesser(axis_speed, centripetal_speed);
    // The tangent keeps what the normal acceleration at the arc's top speed leaves over. The top
    // speed, not the feed, sets it, so a faster feed never makes an arc accelerate harder.
    let normal = (p * top).powi(2) / radius;
    let tangential_room = if finite(plane_acceleration) {
        greater(0.0, 1.0 - (normal / plane_acceleration).powi(2)).sqrt()
    } else {
        1.0
    };
    let programmed = speeds.speed(feed, length, feed_override);
    let cruise = programmed.map_or(top, |v| lesser(top, v));
    let sign = match direction {
        ArcDirection::CounterClockwise => 1.0,
        ArcDirection::Clockwise => -1.0,
    };
    let end = &motion.to.0;
    let (c, axes_abn) = (&center.0, (a, b, n));
    let normal_component = axial.signum() * q;
    // The start is `radius` from the centre (the floor only matters to a NaN).
    let start_tangent = arc_tangent(
        (motion.from.0[a] - c[a], motion.from.0[b] - c[b]),
        greater(1e-12, radius),
        sign,
        p,
        axes_abn,
        normal_component,
    );
    let (ra, rb) = (end[a] - c[a], end[b] - c[b]);
    let end_tangent = arc_tangent(
        (ra, rb),
        greater(1e-12, norm(ra, rb)),
        sign,
        p,
        axes_abn,
        normal_component,
    );
    let acceleration = caps.acceleration;
    let continuous = motion.path_mode == PathMode::Continuous && !motion.exact_stop;
    let unblended_share = lesser(tangential_room, config.unblended_arc_tangential_share);
    let unblended_factor = if continuous {
        config.unblended_acceleration_factor
    } else {
        1.0
    };
    let limits = MotionLimits {
        length,
        cruise,
        path: PathLimits {
            acceleration: acceleration * tangential_room,
            jerk: caps.jerk,
        },
        unblended_acceleration: acceleration * unblended_share * unblended_factor,
        feed_unknown: programmed.is_none(),
        acceleration_scale: 1.0,
    };
    let ends = Ends {
        start: start_tangent,
        end: end_tangent,
        turning: caps.turning,
        bend: Some(Bend {
            curl: {
                let mut curl = [0.0; 3];
                curl[n] = sign;
                curl
            },
            radius,
            sweep,
        }),
    };
    bounded((limits, ends))
}

/// The unit tangent of an arc at the point `(ra, rb)` from its centre in the plane of axes
/// `(a, b)`, `r` from it: the planar share `p` turned a quarter in the arc's direction (`sign`
/// 1 counter-clockwise), with `normal` on the normal axis `n`.
#[inline(always)]
fn arc_tangent(
    (ra, rb): (f64, f64),
    r: f64,
    sign: f64,
    p: f64,
    (a, b, n): (usize, usize, usize),
    normal: f64,
) -> [f64; 3] {
    let mut t = [0.0; 3];
    t[a] = -sign * rb / r * p;
    t[b] = sign * ra / r * p;
    t[n] = normal;
    t
}

/// A rapid with each axis at its own rate (a dog-leg): every axis starts and stops on its own,
/// and the move lasts as long as its slowest axis.
pub(crate) fn per_axis_rapid_seconds(motion: &Move, axes: &AxisLimits) -> f64 {
    (0..AXES)
        .map(|i| {
            let distance = (motion.to.0[i] - motion.from.0[i]).abs();
            let limits = PathLimits {
                acceleration: axes.acceleration[i],
                jerk: axes.jerk[i],
            };
            SpeedProfile::new(distance, 0.0, 0.0, axes.rapid[i], limits).duration()
        })
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn axis(rate: f64, acceleration: f64) -> crate::machine::AxisConfig {
        crate::machine::AxisConfig {
            min: -1e6,
            max: 1e6,
            rapid: rate,
            max_feed: rate,
            acceleration,
            jerk: f64::INFINITY,
        }
    }

    #[test]
    fn the_last_axis_of_the_machine_still_limits_a_move() {
        // X Y Z and C (the sixth axis): a move of C alone is capped by C's own limits, and a
        // move of X alone by X's, whatever the axes in between.
        let mut machine = Machine::default();
        machine.axes = [
            Some(axis(6000.0, 500.0)),
            Some(axis(6000.0, 500.0)),
            Some(axis(6000.0, 500.0)),
            None,
            None,
            Some(axis(1200.0, 50.0)),
        ];
        let config = PlannerConfig::default();
        let axes = AxisLimits::new(&machine, &config);
        let mut to = [0.0; AXES];
        to[5] = 90.0;
        let c_only = axes.project(&[0.0, 0.0, 0.0, 0.0, 0.0, 1.0], false);
        assert_eq!(c_only.speed, 20.0);
        assert_eq!(c_only.acceleration, 50.0);
        assert_eq!(c_only.turning, 50.0);
        let x_only = axes.project(&[1.0, 0.0, 0.0, 0.0, 0.0, 0.0], false);
        assert_eq!(x_only.speed, 100.0);
        assert_eq!(x_only.turning, 500.0);
        // Half the path on X and half on C in shares: C's cap, doubled.
        let both = axes.project(&[0.5, 0.0, 0.0, 0.0, 0.0, 0.5], false);
        assert_eq!(both.speed, 40.0);
        assert_eq!(both.turning, 50.0);
        let motion = Move {
            from: MachinePos([0.0; AXES]),
            to: MachinePos(to),
            path_mode: PathMode::Continuous,
            exact_stop: false,
            smoothing: None,
            frame: crate::motion::FrameId(0),
            offset: [0.0; AXES],
        };
        let (limits, _) = line(&motion, None, &axes, &config, 1.0);
        assert_eq!(limits.length, 90.0);
        assert_eq!(limits.path.acceleration, 50.0);
    }

    /// A machine with X Y Z of the given limits, one of them absent (`absent` 0 to 2; 3: none),
    /// and no further axes.
    fn xyz_machine(
        rates: [f64; 3],
        accelerations: [f64; 3],
        jerks: [f64; 3],
        absent: usize,
    ) -> Machine {
        let mut machine = Machine::default();
        machine.axes = std::array::from_fn(|i| {
            (i < 3 && i != absent).then(|| crate::machine::AxisConfig {
                jerk: jerks[i],
                ..axis(rates[i], accelerations[i])
            })
        });
        machine
    }

    fn projection_bits(p: &Projection) -> [u64; 4] {
        [p.speed, p.acceleration, p.jerk, p.turning].map(f64::to_bits)
    }

    fn limit() -> impl Strategy<Value = f64> {
        prop_oneof![Just(f64::INFINITY), 1.0..1e6_f64]
    }

    fn a_feed() -> impl Strategy<Value = Feed> {
        // A few feeds per minute, so that they repeat, and the other kinds between them.
        let per_minute = prop_oneof![
            Just(1500.0),
            Just(800.0),
            Just(0.0),
            Just(-5.0),
            Just(f64::NAN),
            Just(f64::INFINITY),
            1.0..1e5_f64,
        ];
        prop_oneof![
            4 => per_minute.prop_map(Feed::PerMinute),
            1 => (0.01..1.0_f64, proptest::option::of(100.0..1e4_f64)).prop_map(
                |(per_revolution, rpm)| Feed::PerRevolution { per_revolution, rpm }
            ),
            1 => (0.1..100.0_f64).prop_map(Feed::InverseTime),
        ]
    }

    proptest! {
        /// The kept speed of a feed is the speed worked out, whatever came before.
        #[test]
        fn a_kept_feed_speed_is_the_programmed_speed(
            moves in proptest::collection::vec(
                (a_feed(), 0.0..50.0_f64, prop_oneof![Just(1.0), Just(1.37), 0.1..2.0_f64]),
                1..40,
            ),
        ) {
            let mut speeds = FeedSpeeds::default();
            for (feed, length, feed_override) in moves {
                let kept = speeds.speed(&feed, length, feed_override).map(f64::to_bits);
                let worked_out = programmed_speed(&feed, length, feed_override).map(f64::to_bits);
                prop_assert_eq!(kept, worked_out);
            }
        }

        #[test]
        fn the_xyz_fast_path_gives_the_general_path_to_the_bit(
            from in proptest::array::uniform6(-500.0..500.0_f64),
            delta in proptest::array::uniform6(prop_oneof![
                Just(0.0),
                -50.0..50.0_f64,
                -1e-8..1e-8_f64,
            ]),
            rates in proptest::array::uniform3(100.0..50_000.0_f64),
            accelerations in proptest::array::uniform3(limit()),
            jerks in proptest::array::uniform3(limit()),
            absent in 0_usize..4,
            rapid in any::<bool>(),
            uniform in any::<bool>(),
        ) {
            // Half the machines have the same acceleration and jerk on X Y Z.
            let (accelerations, jerks) = if uniform {
                ([accelerations[0]; 3], [jerks[0]; 3])
            } else {
                (accelerations, jerks)
            };
            let machine = xyz_machine(rates, accelerations, jerks, absent);
            let axes = AxisLimits::new(&machine, &PlannerConfig::default());
            prop_assert!(axes.span <= 3);
            let to: [f64; AXES] = std::array::from_fn(|i| from[i] + delta[i]);
            let motion = Move {
                from: MachinePos(from),
                to: MachinePos(to),
                path_mode: PathMode::Continuous,
                exact_stop: false,
                smoothing: None,
                frame: crate::motion::FrameId(0),
                offset: [0.0; AXES],
            };
            let (length, caps, direction) = straight(&motion, &axes, rapid);
            let (general_length, share, general_direction) = straight_path(&motion);
            let general_caps = axes.project(&share, rapid);
            prop_assert_eq!(length.to_bits(), general_length.to_bits());
            prop_assert_eq!(projection_bits(&caps), projection_bits(&general_caps));
            prop_assert_eq!(direction.map(f64::to_bits), general_direction.map(f64::to_bits));
        }

        #[test]
        fn the_xyz_projection_of_an_arc_is_the_general_one_on_any_machine(
            share in proptest::array::uniform3(prop_oneof![Just(0.0), 0.0..1.0_f64]),
            rates in proptest::array::uniform3(100.0..50_000.0_f64),
            accelerations in proptest::array::uniform3(limit()),
            jerks in proptest::array::uniform3(limit()),
            absent in 0_usize..4,
            uniform in any::<bool>(),
        ) {
            let (accelerations, jerks) = if uniform {
                ([accelerations[0]; 3], [jerks[0]; 3])
            } else {
                (accelerations, jerks)
            };
            // A machine with a C axis of tight limits: it never moves in an arc, and must not cap
            // it.
            let mut machine = xyz_machine(rates, accelerations, jerks, absent);
            machine.axes[5] = Some(axis(10.0, 1.0));
            let axes = AxisLimits::new(&machine, &PlannerConfig::default());
            let mut padded = [0.0; AXES];
            padded[..3].copy_from_slice(&share);
            for rapid in [false, true] {
                prop_assert_eq!(
                    projection_bits(&axes.project_xyz(&share, rapid)),
                    projection_bits(&axes.project(&padded, rapid))
                );
            }
        }
    }
}
