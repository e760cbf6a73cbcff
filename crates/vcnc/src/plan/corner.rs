//! The speed at which one motion may hand over to the next: zero at a stop, the blend speed at
//! a corner in continuous mode, unlimited (up to both segments' speeds) on a tangent.
//!
//! Corner blending follows the deviation model: the control rounds the corner with an arc
//! tangent to both moves, as large as the corner tolerance and the segments' lengths allow, and
//! passes it at the speed whose centripetal acceleration is the normal share of the limit. For a
//! turn of angle phi, an arc of radius r tangent to both moves leaves the corner by
//! r (1 / cos(phi/2) - 1) and starts r tan(phi/2) before it, so
//! r = min(tolerance cos(phi/2) / (1 - cos(phi/2)), share * shorter length / tan(phi/2)),
//! and no larger than the segments' speed needs. The arc replaces two legs of r tan(phi/2) by
//! r phi and is passed at the junction speed: negligible at a tolerance of hundredths of a
//! millimetre, a large part of the time where blends are only bounded by the segments' lengths
//! (LinuxCNC's plain G64).
//!
//! LinuxCNC differs in ways its habits turn on one by one (see `config.rs`): its blend arc is a
//! segment of its own, along which the speed may change with part of the acceleration (so that
//! a chain of short chords, whose blends eat them whole, still speeds up); it draws the arc as
//! large as a parabolic blend of the corner would take; it bounds the tolerance by a quarter of
//! the segments' lengths; it turns with what the axes allow in the plane of the corner; and it
//! runs what a blend leaves of a short line as part of the arc after it.

use super::config::{BlendRadius, BlendTurning, PlannerConfig};
use super::limits::{Bend, Ends, MotionLimits};
use super::{finite, greater, lesser};
use crate::motion::{Move, PathMode, Smoothing};

/// Turns smaller than this (radians) are tangent: no corner at all.
const TANGENT_ANGLE: f64 = 1e-6;

/// The kind of a motion, as far as a junction is concerned.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum MotionClass {
    /// A line or an arc at a feed.
    Cutting,
    /// An interpolated rapid.
    Rapid,
    /// A rapid with each axis at its own rate: it stops at both ends.
    PerAxisRapid,
}

/// How a motion meets the next one, as far as their junction is concerned: small, because the
/// last one is kept for the next junction. (The next motion's start tangent is passed beside
/// it: a motion's start only matters to its junction with the previous one.)
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Handover {
    /// Unit tangent over X Y Z at the motion's end (zero without XYZ travel).
    end: [f64; 3],
    /// The motion's whole length, mm (before any blend shortens it).
    length: f64,
    /// Its cruise speed, mm/s.
    pub(crate) cruise: f64,
    /// Its turning acceleration (see [`Ends::turning`]), mm/s^2.
    turning: f64,
    /// Its tangential acceleration, mm/s^2.
    acceleration: f64,
    /// An arc's shape; None for a straight move.
    bend: Option<Bend>,
    class: MotionClass,
    /// A straight move (a line or a rapid), whose rest a blend may take over.
    pub(crate) straight: bool,
    /// The block asks for an exact stop at its end (G61, G63 or G09).
    exact_stop: bool,
    /// The high-speed or smoothing mode in force.
    smoothing: Option<Smoothing>,
}

impl Handover {
    #[inline]
    pub(crate) fn new(
        class: MotionClass,
        straight: bool,
        motion: &Move,
        limits: &MotionLimits,
        ends: Ends,
        config: &PlannerConfig,
    ) -> Handover {
        // LinuxCNC caps a segment's speed by one cycle over its length when it takes it in
        // (tc.c `tcClampVelocityByLength`), by a little more once its blends are known
        // (`PlannerConfig::min_segment_seconds`, in the look-ahead window).
        let cruise = if config.min_segment_seconds > 0.0 {
            lesser(limits.cruise, limits.length / config.cycle_seconds)
        } else {
            limits.cruise
        };
        Handover {
            end: ends.end,
            length: limits.length,
            cruise,
            turning: ends.turning,
            acceleration: limits.path.acceleration,
            bend: ends.bend,
            class,
            straight,
            exact_stop: motion.exact_stop
                || matches!(motion.path_mode, PathMode::ExactStop | PathMode::Tapping),
            smoothing: motion.smoothing,
        }
    }

    /// A handover that is never read: the second place of [`Handovers`] before any motion.
    const NONE: Handover = Handover {
        end: [0.0; 3],
        length: 0.0,
        cruise: 0.0,
        turning: 0.0,
        acceleration: 0.0,
        bend: None,
        class: MotionClass::Cutting,
        straight: true,
        exact_stop: false,
        smoothing: None,
    };
}

/// The handovers of the last motion that entered the look-ahead window and of the motion
/// entering it, in two places that take turns: the entering motion's is made where it stays,
/// instead of beside it and copied there once its junction is known (a copy per motion).
#[derive(Debug)]
pub(crate) struct Handovers {
    places: [Handover; 2],
    /// The place of the entering motion's handover; the other one holds the last motion's.
    entering: usize,
    /// The other place holds the last motion's handover: false at first and after a stop.
    continuing: bool,
}

impl Handovers {
    pub(crate) const fn new() -> Handovers {
        Handovers {
            places: [Handover::NONE; 2],
            entering: 0,
            continuing: false,
        }
    }

    /// The place where the entering motion's handover is made.
    #[inline(always)]
    pub(crate) fn entering_mut(&mut self) -> &mut Handover {
        &mut self.places[self.entering & 1]
    }

    /// The last motion's handover (None after a stop) and the entering motion's.
    #[inline(always)]
    pub(crate) fn pair(&self) -> (Option<&Handover>, &Handover) {
        let last = &self.places[(self.entering ^ 1) & 1];
        (
            self.continuing.then_some(last),
            &self.places[self.entering & 1],
        )
    }

    /// The entering motion has entered: its handover is the last one.
    #[inline(always)]
    pub(crate) fn enter(&mut self) {
        self.entering ^= 1;
        self.continuing = true;
    }

    /// The motion comes to rest: the next motion has no junction with the last one.
    pub(crate) fn stop(&mut self) {
        self.continuing = false;
    }
}

/// What happens where one motion hands over to the next.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Junction {
    /// Highest speed through the junction, mm/s (infinite: only the segments' own speeds).
    pub(crate) speed: f64,
    /// Path length each of the two segments gives up to the blend arc, mm.
    pub(crate) leg: f64,
    /// Length of the blend arc, mm, passed at the junction speed unless it has an acceleration
    /// of its own.
    pub(crate) arc: f64,
    /// The blend arc's tangential acceleration, mm/s^2, when it is a piece of path of its own
    /// (`PlannerConfig::blend_arc_tangential_share`); 0 when it is passed at the junction speed.
    pub(crate) arc_acceleration: f64,
    /// A stop at a corner the path could not blend (exact stop, a reversal), as opposed to a
    /// stop between kinds of motion.
    pub(crate) corner_stop: bool,
    /// The factor both motions' acceleration is scaled by where a kink is passed as a tangent
    /// (`PlannerConfig::kink_ratio`); 1: not scaled.
    pub(crate) kink_factor: f64,
}

impl Junction {
    const STOP: Junction = Junction {
        speed: 0.0,
        leg: 0.0,
        arc: 0.0,
        arc_acceleration: 0.0,
        corner_stop: false,
        kink_factor: 1.0,
    };
    const CORNER_STOP: Junction = Junction {
        corner_stop: true,
        ..Junction::STOP
    };
    const TANGENT: Junction = Junction {
        speed: f64::INFINITY,
        leg: 0.0,
        arc: 0.0,
        arc_acceleration: 0.0,
        corner_stop: false,
        kink_factor: 1.0,
    };

    /// The machine comes to rest here.
    #[cfg(test)]
    fn is_stop(&self) -> bool {
        self.speed <= 0.0
    }
}

/// The junction of `prev` and `next`, which starts along `next_start`.
// Inlined into the window's push (as it was before LinuxCNC's blend arcs grew its cold paths):
// a call costs more than most junctions.
#[inline(always)]
pub(crate) fn junction(
    prev: &Handover,
    next: &Handover,
    next_start: &[f64; 3],
    config: &PlannerConfig,
) -> Junction {
    use MotionClass::{Cutting, PerAxisRapid};
    if prev.class == PerAxisRapid || next.class == PerAxisRapid {
        return Junction::STOP;
    }
    if (prev.class == Cutting) != (next.class == Cutting) && config.stop_between_rapid_and_feed {
        return Junction::STOP;
    }
    let (u, w) = (&prev.end, next_start);
    let cos_turn = u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
    if cos_turn.is_nan() {
        return Junction::STOP;
    }
    // An exact stop that passes no tangent, where no reversal stops otherwise, stops at every
    // corner whatever its turn (the tests below would all come to that): the commonest
    // junction of a SINUMERIK program, which powers on in G60.
    if prev.exact_stop && !config.exact_stop_passes_tangents && config.reversal_stop_degrees <= 0.0
    {
        return Junction::CORNER_STOP;
    }
    let cos_turn = greater(-1.0, lesser(1.0, cos_turn));
    // LinuxCNC stops where the path nearly turns back (tp.c `tpSetupTangent`: |u + w|^2 below
    // the square of the angle), with no scaled acceleration, exact stop or not.
    if config.reversal_stop_degrees > 0.0
        && 2.0 * (1.0 + cos_turn) < config.reversal_stop_degrees.to_radians().powi(2)
    {
        return Junction::STOP;
    }
    let tangent = cos_turn >= TANGENT_ANGLE.cos();
    // LinuxCNC's kinks: 0 when vcnc's habits weigh none.
    let kink = if config.kink_ratio > 0.0 && !tangent {
        kink_scale(prev, next, u, w, config)
    } else {
        0.0
    };
    let passed = tangent || kink < config.kink_ratio;
    if prev.exact_stop && !(passed && config.exact_stop_passes_tangents) {
        return Junction::CORNER_STOP;
    }
    if tangent {
        return Junction::TANGENT;
    }
    if passed {
        return Junction {
            kink_factor: 1.0 - kink,
            ..Junction::TANGENT
        };
    }
    // A move without X Y Z travel (rotary only) has no direction: the product is 0, a right
    // angle, which blends only as much as a right angle would.
    let cos_half = (0.5 * (1.0 + cos_turn)).sqrt();
    let sin_half = (0.5 * (1.0 - cos_turn)).sqrt();
    if cos_half <= 1e-12 {
        return Junction::CORNER_STOP;
    }
    let tan_half = sin_half / cos_half;
    // A corner between two moves of a high-speed or smoothing mode is cut within that mode's
    // tolerance or rounding distance; any other within the machine's tolerance.
    let shorter = lesser(prev.length, next.length);
    let (tolerance, leg) = match (prev.smoothing, next.smoothing) {
        (Some(a), Some(b)) => smoothing_bounds(a, b, shorter, config),
        _ => (config.corner_tolerance, config.blend_length_share * shorter),
    };
    // Infinite for vcnc's habits: the tolerance stays as it is.
    let tolerance = lesser(tolerance, config.corner_tolerance_length_share * shorter);
    let by_tolerance = if finite(tolerance) {
        tolerance * cos_half / (1.0 - cos_half)
    } else {
        f64::INFINITY
    };
    let by_length = leg / tan_half;
    // The blend turns in the plane of the two moves: each axis that moves may carry the whole
    // normal acceleration somewhere on it.
    let mut acceleration = lesser(prev.turning, next.turning);
    if config.blend_turning == BlendTurning::InPlane {
        acceleration *= in_plane_factor(u, w);
    }
    let normal = config.normal_acceleration_share * acceleration;
    let turn = 2.0 * half_turn(tan_half);
    // LinuxCNC makes an arc of its own between two lines; where a G2/G3 meets the corner its
    // arc blends mostly give up (tp.c: tpCreateLineArcBlend and the like) for a parabolic one.
    if config.blend_arc_tangential_share > 0.0 && prev.straight && next.straight {
        let geometric = lesser(by_length, by_tolerance);
        let arc = blend_segment(
            prev,
            next,
            (tan_half, turn),
            geometric,
            acceleration,
            config,
        );
        return faster_than_kink(arc, prev, next, kink, config);
    }
    if config.blend_arc_tangential_share > 0.0 && config.blend_next_to_arcs {
        let corner = Corner {
            u,
            w,
            turn,
            tolerance,
            acceleration,
            kink,
        };
        if let Some(junction) = arc_blend(prev, next, &corner, config) {
            return junction;
        }
    }
    // No larger arc than the speed of the two segments needs: it would only cut more corner.
    let wanted = lesser(prev.cruise, next.cruise);
    let radius = lesser(lesser(by_length, by_tolerance), wanted * wanted / normal);
    Junction {
        speed: (normal * radius).sqrt(),
        leg: radius * tan_half,
        arc: radius * turn,
        arc_acceleration: 0.0,
        corner_stop: false,
        kink_factor: 1.0,
    }
}

/// The deviation and the leg (distance from the corner) that a corner between two smoothing
/// modes may round with, `shorter` the shorter move's length: each bound from the mode that
/// gives it, the smaller where both do (so a G0 meeting a G1 under G641 takes the smaller of
/// ADISPOS and ADIS, seed 002 L8334-8391). Out of line: most corners have no smoothing.
#[cold]
#[inline(never)]
fn smoothing_bounds(
    a: Smoothing,
    b: Smoothing,
    shorter: f64,
    config: &PlannerConfig,
) -> (f64, f64) {
    let mut bounds = [f64::INFINITY; 2];
    for s in [a, b] {
        let i = usize::from(s.is_distance());
        bounds[i] = lesser(bounds[i], s.mm());
    }
    let mut leg = config.blend_length_share * shorter;
    if finite(bounds[1]) {
        leg = lesser(
            leg,
            lesser(bounds[1], config.rounding_distance_share * shorter),
        );
    }
    (bounds[0], leg)
}

/// The junction whose blend arc is a segment of its own (LinuxCNC's, tp.c and blendmath.c):
/// its speed is capped by the arc as large as the corner allows (`geometric`, the radius) and
/// by the faster of the two moves, since each move caps the arc's ends with its own speed; its
/// radius is the least that carries that speed or, with [`BlendRadius::ParabolicTime`], the
/// one a parabolic blend at half the acceleration would run along for as long, within the
/// geometric one; along it the speed may change with the tangential share of `acceleration`.
#[cold]
#[inline(never)]
fn blend_segment(
    prev: &Handover,
    next: &Handover,
    (tan_half, turn): (f64, f64),
    geometric: f64,
    acceleration: f64,
    config: &PlannerConfig,
) -> Junction {
    let normal = config.normal_acceleration_share * acceleration;
    let wanted = greater(prev.cruise, next.cruise);
    let speed = lesser((normal * geometric).sqrt(), wanted);
    let mut radius = speed * speed / normal;
    if config.blend_radius == BlendRadius::ParabolicTime {
        // A parabolic blend at half the acceleration needs the time to change the speed
        // across the corner, or less where the legs are too short to reach it.
        let half = 0.5 * acceleration;
        let reachable = (2.0 * half * geometric * tan_half).sqrt();
        let seconds = lesser(reachable, speed) / half;
        radius = greater(radius, lesser(seconds * speed / turn, geometric));
    }
    // Never past what the corner allows (rounding in the speed's square and root).
    let radius = lesser(radius, geometric);
    Junction {
        speed,
        leg: radius * tan_half,
        arc: radius * turn,
        arc_acceleration: config.blend_arc_tangential_share * acceleration,
        corner_stop: false,
        kink_factor: 1.0,
    }
}

/// A corner next to an arc, as [`arc_blend`] takes it.
struct Corner<'a> {
    /// Unit tangents at the end of the previous motion and at the start of the next.
    u: &'a [f64; 3],
    w: &'a [f64; 3],
    /// The angle the path turns by, radians.
    turn: f64,
    /// The largest distance the blend may leave the corner by, mm.
    tolerance: f64,
    /// The acceleration the blend may turn with.
    acceleration: f64,
    /// The share of an axis's acceleration the corner's kink asks for ([`kink_scale`]).
    kink: f64,
}

/// LinuxCNC's blend arc at a corner where a G2/G3 meets a line or another arc (blendmath.c
/// `blendInit3FromLineArc`, `...ArcLine`, `...ArcArc`): an arc may give up at most a third of
/// its sweep to a blend after it (two thirds to one before it), and no more than the corner's
/// half angle where the blend lies on the arc's outer side (a convex corner), where the arc's
/// secant, not its tangent, bounds the blend: the leg is half that chord and the half angle
/// shrinks by a quarter of the sweep given up. Between two arcs a half angle below 15 degrees
/// makes no blend arc (None: the corner is blended as vcnc's habits blend it). The arc is then
/// the line-line one of that half angle and legs, a segment of its own ([`blend_segment`]),
/// or the kink where that is faster. Not modelled: LinuxCNC's checks of the fitted arc
/// (`blendArcArcPostProcess`, `checkTangentAngle`), whose failures end in a parabolic blend.
#[cold]
#[inline(never)]
fn arc_blend(
    prev: &Handover,
    next: &Handover,
    corner: &Corner<'_>,
    config: &PlannerConfig,
) -> Option<Junction> {
    use std::f64::consts::{FRAC_PI_2, PI};
    let half = FRAC_PI_2 - 0.5 * corner.turn;
    let mut theta = half;
    // What a move may give up to the blend, mm; `share` the part of an arc's sweep.
    let mut leg_of = |motion: &Handover, tangent: &[f64; 3], other: &[f64; 3], before: bool| {
        let Some(bend) = motion.bend else {
            return config.blend_length_share * motion.length;
        };
        let inward = cross(&bend.curl, tangent);
        let toward = dot(&inward, other);
        // The blend on the arc's outer side: the next move heads inward of the arc before
        // it, or the previous one comes from outward of the arc after it.
        let convex = if before { toward > 0.0 } else { toward <= 0.0 };
        let share = if before { 2.0 / 3.0 } else { 1.0 / 3.0 };
        let bound = if convex { half } else { FRAC_PI_2 };
        let phi = lesser(share * bend.sweep, bound);
        if convex {
            theta = lesser(theta, half - 0.25 * phi);
            (0.25 * phi).sin() * bend.radius
        } else {
            phi * bend.radius
        }
    };
    let first = leg_of(prev, corner.u, corner.w, true);
    let second = leg_of(next, corner.w, corner.u, false);
    let both_arcs = prev.bend.is_some() && next.bend.is_some();
    if theta <= 1e-9 || (both_arcs && theta < PI / 12.0) {
        return None;
    }
    let (sin, cos) = theta.sin_cos();
    let by_length = lesser(first, second) * sin / cos;
    let by_tolerance = if finite(corner.tolerance) {
        corner.tolerance * sin / (1.0 - sin)
    } else {
        f64::INFINITY
    };
    let arc = blend_segment(
        prev,
        next,
        (cos / sin, PI - 2.0 * theta),
        lesser(by_length, by_tolerance),
        corner.acceleration,
        config,
    );
    Some(faster_than_kink(arc, prev, next, corner.kink, config))
}

fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// LinuxCNC's measure of a kink (tp.c `tpSetupTangent`): the largest share of an axis's
/// acceleration limit that turning from `u` to `w` within one cycle asks for, at the slower
/// segment's speed plus one cycle of the next segment's acceleration; twice that next to an
/// arc, which keeps only half its acceleration for its tangent. Every axis is taken to have the
/// lower turning limit of the two motions (exact where the axes share one limit).
#[cold]
#[inline(never)]
fn kink_scale(
    prev: &Handover,
    next: &Handover,
    u: &[f64; 3],
    w: &[f64; 3],
    config: &PlannerConfig,
) -> f64 {
    let speed = lesser(prev.cruise, next.cruise);
    let instant = speed / config.cycle_seconds + next.acceleration;
    let largest = greater(
        greater((w[0] - u[0]).abs(), (w[1] - u[1]).abs()),
        (w[2] - u[2]).abs(),
    );
    let scale = instant * largest / lesser(prev.turning, next.turning);
    if prev.straight && next.straight {
        scale
    } else {
        scale / 0.5
    }
}

/// `arc`, or the corner passed as a kink where that is faster (LinuxCNC's
/// `tpChooseBestBlend`): at the speed whose kink asks for exactly `kink_ratio` (`kink` being
/// the share the segments' speed asks for), both segments keeping 1 - `kink_ratio` of their
/// acceleration. The arc's own speed is capped by one cycle along it (tc.c
/// `tcClampVelocityByLength`).
#[cold]
#[inline(never)]
fn faster_than_kink(
    arc: Junction,
    prev: &Handover,
    next: &Handover,
    kink: f64,
    config: &PlannerConfig,
) -> Junction {
    if config.kink_ratio <= 0.0 {
        return arc;
    }
    let kink_speed = lesser(prev.cruise, next.cruise) * config.kink_ratio / kink;
    let arc_speed = lesser(arc.speed, arc.arc / config.cycle_seconds);
    if kink_speed > arc_speed {
        Junction {
            speed: kink_speed,
            kink_factor: 1.0 - config.kink_ratio,
            ..Junction::TANGENT
        }
    } else {
        arc
    }
}

/// How much more than an axis's limit the path may turn with in the plane of `u` and `w`
/// (unit vectors, not parallel) when every axis has that limit: the acceleration a along a unit
/// direction d of the plane puts a d_i on axis i, and the largest d_i over the plane is
/// sqrt(1 - n_i^2), n the plane's unit normal; so a <= limit / sqrt(1 - n_i^2) for the axis
/// with the smallest n_i.
#[cold]
#[inline(never)]
fn in_plane_factor(u: &[f64; 3], w: &[f64; 3]) -> f64 {
    let n = [
        u[1] * w[2] - u[2] * w[1],
        u[2] * w[0] - u[0] * w[2],
        u[0] * w[1] - u[1] * w[0],
    ];
    let squared = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    if squared <= 1e-24 {
        return 1.0;
    }
    let smallest = lesser(lesser(n[0] * n[0], n[1] * n[1]), n[2] * n[2]) / squared;
    1.0 / greater(1e-12, 1.0 - smallest).sqrt()
}

/// The half turn angle, radians, from its tangent (finite: the half turn is below a right
/// angle here). Most corners of CAM paths turn by a few degrees: there the series of atan,
/// whose first left-out term is below 2e-11 of the angle, costs a few multiplications instead
/// of a call into libm.
#[inline]
fn half_turn(tan_half: f64) -> f64 {
    const SERIES_LIMIT: f64 = 0.2;
    if tan_half > SERIES_LIMIT {
        return tan_half.atan();
    }
    tan_half * atan_series(tan_half * tan_half)
}

/// atan t / t = 1 - t^2/3 + t^4/5 - ... + t^12/13 from `t2` = t^2, in Horner form (t^14/15 is
/// below 2e-11 for the t of [`half_turn`]), every other level negated: c - t2 x, rounded, is
/// the negative of t2 x - c rounded, so that each level is a product and a sum with a
/// constant, two instructions, instead of three with the constant loaded first. The same to
/// the bit as the plain form (see the tests).
#[inline]
fn atan_series(t2: f64) -> f64 {
    let negated_5 = t2 * (1.0 / 13.0) - 1.0 / 11.0;
    let level_4 = 1.0 / 9.0 + t2 * negated_5;
    let negated_3 = t2 * level_4 - 1.0 / 7.0;
    let level_2 = 1.0 / 5.0 + t2 * negated_3;
    let negated_1 = t2 * level_2 - 1.0 / 3.0;
    1.0 + t2 * negated_1
}

#[cfg(test)]
mod tests {
    use super::*;

    fn handover(direction: [f64; 3], exact_stop: bool) -> Handover {
        Handover {
            end: direction,
            length: 100.0,
            cruise: 100.0,
            turning: 1000.0,
            acceleration: 1000.0,
            bend: None,
            class: MotionClass::Cutting,
            straight: true,
            exact_stop,
            smoothing: None,
        }
    }

    /// The junction of a motion along `u` with one along `w`.
    fn junction(u: &Handover, w: &Handover, config: &PlannerConfig) -> Junction {
        super::junction(u, w, &w.end, config)
    }

    #[test]
    fn a_right_angle_blends_at_the_speed_of_its_tolerance_arc() {
        let config = PlannerConfig {
            corner_tolerance: 0.1,
            ..PlannerConfig::default()
        };
        let v = junction(
            &handover([1.0, 0.0, 0.0], false),
            &handover([0.0, 1.0, 0.0], false),
            &config,
        )
        .speed;
        let c = std::f64::consts::FRAC_1_SQRT_2;
        let radius = 0.1 * c / (1.0 - c);
        let expected = (config.normal_acceleration_share * 1000.0 * radius).sqrt();
        assert!((v - expected).abs() < 1e-9, "{v} {expected}");
    }

    /// SINUMERIK G641 ADIS=0.5 at a right angle: the rounding starts 0.5 mm before the corner,
    /// so its arc has the radius 0.5 / tan 45 = 0.5 mm; with 0.2 mm segments the leg is cut to
    /// 0.36 * 0.2 = 0.072 mm. A neighbour rounding within 0.2 mm gives the smaller distance.
    #[test]
    fn a_rounding_distance_bounds_the_leg_of_the_arc() {
        let config = PlannerConfig::default();
        let normal = config.normal_acceleration_share * 1000.0;
        let by = |a: Smoothing, b: Smoothing, length: f64| {
            let mut u = handover([1.0, 0.0, 0.0], false);
            let mut w = handover([0.0, 1.0, 0.0], false);
            (u.smoothing, w.smoothing) = (Some(a), Some(b));
            (u.length, w.length) = (length, length);
            junction(&u, &w, &config).speed
        };
        let adis = Smoothing::distance(0.5);
        let close = |v: f64, radius: f64| (v - (normal * radius).sqrt()).abs() < 1e-9;
        assert!(close(by(adis, adis, 100.0), 0.5));
        assert!(close(by(adis, adis, 0.2), 0.072));
        assert!(close(by(adis, Smoothing::distance(0.2), 100.0), 0.2));
        // A distance beside a tolerance: both bound the arc (0.01 mm: 0.0241 mm of radius).
        let c = std::f64::consts::FRAC_1_SQRT_2;
        assert!(close(
            by(adis, Smoothing::from_mm(0.01), 100.0),
            0.01 * c / (1.0 - c)
        ));
    }

    #[test]
    fn exact_stop_stops_even_on_a_straight_line_unless_told_otherwise() {
        let x = [1.0, 0.0, 0.0];
        let mut config = PlannerConfig::default();
        assert!(junction(&handover(x, true), &handover(x, false), &config).is_stop());
        config.exact_stop_passes_tangents = true;
        let through = junction(&handover(x, true), &handover(x, false), &config);
        assert!(through.speed.is_infinite());
    }

    #[test]
    fn the_half_turn_series_agrees_with_atan() {
        for i in 0..=2000 {
            let t = f64::from(i) * 1e-3;
            let (fast, exact) = (half_turn(t), t.atan());
            assert!(
                (fast - exact).abs() <= 1e-10 * exact.max(1e-300),
                "{t}: {fast} {exact}"
            );
        }
    }

    /// The series in the plain Horner form.
    fn plain_series(t2: f64) -> f64 {
        1.0 - t2
            * (1.0 / 3.0
                - t2 * (1.0 / 5.0
                    - t2 * (1.0 / 7.0 - t2 * (1.0 / 9.0 - t2 * (1.0 / 11.0 - t2 * (1.0 / 13.0))))))
    }

    #[test]
    fn the_series_with_negated_levels_is_the_plain_one_to_the_bit() {
        // Every t below the series' limit, 1e-7 apart, and the smallest ones.
        for i in 0..=2_000_000 {
            let t = f64::from(i) * 1e-7;
            let t2 = t * t;
            assert_eq!(atan_series(t2).to_bits(), plain_series(t2).to_bits(), "{t}");
        }
        for t in [f64::MIN_POSITIVE, 1e-300, 1e-160, 1e-20, 1e-9] {
            let t2 = t * t;
            assert_eq!(atan_series(t2).to_bits(), plain_series(t2).to_bits(), "{t}");
        }
    }

    proptest::proptest! {
        #[test]
        fn the_series_with_negated_levels_is_the_plain_one_on_any_turn(t in 0.0..0.2_f64) {
            let t2 = t * t;
            proptest::prop_assert_eq!(atan_series(t2).to_bits(), plain_series(t2).to_bits());
        }
    }

    #[test]
    fn a_corner_turns_with_more_than_an_axis_limit_only_in_a_plane_oblique_to_the_axes() {
        // In the XY plane the X and Y limits bound the turn; in the plane whose normal is
        // (1, 1, 1)/sqrt 3 every axis sees at most sqrt(2/3) of the acceleration.
        let (x, y) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        assert_eq!(in_plane_factor(&x, &y), 1.0);
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let (u, w) = ([s, -s, 0.0], [0.0, s, -s]);
        let expected = 1.0 / (2.0_f64 / 3.0).sqrt();
        assert!((in_plane_factor(&u, &w) - expected).abs() < 1e-12);
    }

    /// LinuxCNC's kinks (tp.c `tpSetupTangent`): at 100 mm/s, a 1 ms cycle and 1000 mm/s^2 a
    /// turn by `a` radians from X asks an axis for (100 / 0.001 + 1000) sin a / 1000 = 101 sin a
    /// of its limit. At a = 0.0005 that is 0.0505, below the ratio of 0.1: a tangent, both
    /// motions keeping 1 - 0.0505 of their acceleration. At a = 0.002 it is 0.202: on 100 mm
    /// lines the blend arc (100 mm/s) beats the kink speed 100 * 0.1 / 0.202 = 49.5 mm/s; on
    /// 0.01 mm chords the arc, at most 0.01 mm long, is capped at 0.01 / 0.001 = 10 mm/s by its
    /// one cycle, and the kink wins, keeping 0.9 of the acceleration.
    #[test]
    fn a_small_kink_is_passed_as_a_tangent_and_a_larger_one_where_faster_than_its_arc() {
        let config = PlannerConfig::with_habits(super::super::config::PlannerHabits::Linuxcnc);
        let x = handover([1.0, 0.0, 0.0], false);
        let turned = |a: f64, length: f64| {
            let mut w = handover([a.cos(), a.sin(), 0.0], false);
            let mut u = x;
            (u.length, w.length) = (length, length);
            junction(&u, &w, &config)
        };
        let small = turned(0.0005, 100.0);
        let share = 101.0 * 0.0005_f64.sin();
        assert!(small.speed.is_infinite() && small.leg == 0.0);
        assert!(
            (small.kink_factor - (1.0 - share)).abs() < 1e-9,
            "{small:?}"
        );
        let long = turned(0.002, 100.0);
        assert!(long.arc > 0.0 && long.kink_factor == 1.0, "{long:?}");
        let short = turned(0.002, 0.01);
        let kink_speed = 100.0 * 0.1 / (101.0 * 0.002_f64.sin());
        assert!((short.speed - kink_speed).abs() < 1e-6, "{short:?}");
        assert_eq!((short.leg, short.kink_factor), (0.0, 0.9));
    }

    /// arcs_11 (tests/data/plan/lcnc/random), lines 18-19: a G3 of R 8.58 sweeping 72.9
    /// degrees meets a G2 of R 27.5 (116 degrees) with a turn of 46.4 degrees, at 500 mm/s^2.
    /// The corner lies on the first arc's outer side: it may give up 2/3 of its sweep, at most
    /// the half angle 66.8 degrees, so 48.6 degrees, of which the blend takes half the chord,
    /// 8.58 sin(12.2 deg) = 1.81 mm, with the half angle cut by 12.2 degrees to 54.7: a radius
    /// of 1.81 tan 54.7 = 2.55 mm and a speed of sqrt(0.866 * 500 * 2.55) = 33.2 mm/s, which
    /// LinuxCNC holds for 72 cycles across that corner (lcnc-time's trace: 33.18 mm/s).
    #[test]
    fn a_blend_next_to_an_arc_is_bounded_by_the_arcs_sweep_and_side() {
        let config = PlannerConfig::with_habits(super::super::config::PlannerHabits::Linuxcnc);
        let unit = |x: f64, y: f64| {
            let n = x.hypot(y);
            [x / n, y / n, 0.0]
        };
        let bend = |sign: f64, radius: f64, from: [f64; 2], to: [f64; 2]| {
            let sweep = (from[0] * to[0] + from[1] * to[1]) / (radius * radius);
            Bend {
                curl: [0.0, 0.0, sign],
                radius,
                sweep: sweep.acos(),
            }
        };
        // Radius vectors (end or start minus centre) from the program's I J.
        let (r1_start, r1_end) = ([8.5264, 0.9686], [76.8965 - 75.3238, 8.9354 - 0.4995]);
        let (r2_start, r2_end) = ([16.1414, -22.2763], [33.648 - 60.7551, 26.523 - 31.2117]);
        let mut first = handover(unit(-r1_end[1], r1_end[0]), false);
        first.bend = Some(bend(1.0, 8.5811, r1_start, r1_end));
        let mut second = handover(unit(r2_start[1], -r2_start[0]), false);
        second.bend = Some(bend(-1.0, 27.511, r2_start, r2_end));
        for h in [&mut first, &mut second] {
            (h.straight, h.turning, h.acceleration, h.cruise) = (false, 500.0, 500.0, 80.0);
            h.length = 200.0;
        }
        let j = junction(&first, &second, &config);
        assert!((j.speed - 33.2).abs() < 0.1, "{j:?}");
        assert!(j.arc_acceleration > 0.0);
    }

    #[test]
    fn a_reversal_stops() {
        let config = PlannerConfig::default();
        let reversal = junction(
            &handover([1.0, 0.0, 0.0], false),
            &handover([-1.0, 0.0, 0.0], false),
            &config,
        );
        assert!(reversal.is_stop());
    }
}
