//! The planner's settings: the `[planner]` table of a machine file.
//!
//! Each setting models one thing a control does, so that a user whose machine takes longer than
//! vcnc says can calibrate against measured times. `habits = "linuxcnc"` starts from the values
//! that reproduce LinuxCNC 2.9's trajectory planner (see ../shared/tools/lcnc-time/README.md);
//! any field written beside it still wins. Values are checked when the file is read, so the
//! planner can rely on them being finite and in range.

use serde::Deserialize;

/// Planner settings, resolved (preset plus the fields written in the machine file).
#[derive(Clone, Debug, PartialEq)]
pub struct PlannerConfig {
    /// Segments in the look-ahead window (at least 2): the planner's only buffer.
    pub look_ahead: usize,
    /// Whether the window releases its first half when full, or each motion as soon as
    /// `look_ahead` - 1 motions follow it (LinuxCNC's optimizer plans each new segment back
    /// over a fixed depth, and a segment beyond it keeps its speeds).
    pub look_ahead_release: LookAheadRelease,
    /// Largest distance, mm, by which a blended corner in continuous mode (G64) may cut inside
    /// the programmed corner; infinite when only segment lengths bound the blend.
    pub corner_tolerance: f64,
    /// Largest distance, mm, by which a corner may be cut in a high-speed or smoothing mode
    /// whose code gives no tolerance (Syntec G05 without E, its "TOL" parameter; FANUC G05.1 Q1
    /// and G08 P1); a tolerance the program gives (E) wins.
    pub smoothing_tolerance: f64,
    /// Largest distance, mm, by which SINUMERIK's G642-G645 may round a corner when no CYCLE832
    /// gives a tolerance: the axis tolerance of its machine data (MD33100 $MA_COMPRESS_POS_TOL,
    /// seed 002 L8267-8270), one value for every axis.
    pub rounding_tolerance: f64,
    /// SINUMERIK G641's rounding distance (ADIS, ADISPOS) is cut to this share of the shorter
    /// of the two blocks (seed 002 L8102-8424: "reduced automatically to max. 36 %").
    pub rounding_distance_share: f64,
    /// Share of a segment's length, at each end, that a corner blend may use.
    pub blend_length_share: f64,
    /// The corner tolerance is at most this share of the shorter of the two segments' lengths
    /// (LinuxCNC: 0.25, in plain G64 and under `G64 P` alike); infinite: no such bound.
    pub corner_tolerance_length_share: f64,
    /// Share of the turning acceleration that a corner blend's arc may use along its path, to
    /// speed up or slow down on it (LinuxCNC: 0.5, its blend arcs being segments of their own).
    /// 0: the arc is passed at the junction speed, as a lead-in of the next motion.
    pub blend_arc_tangential_share: f64,
    /// How large a corner blend's arc is drawn.
    pub blend_radius: BlendRadius,
    /// With `blend_arc_tangential_share`, corners next to a G2/G3 get a blend arc of their own
    /// too, bounded as LinuxCNC bounds it by the arcs' sweeps and sides (blendmath.c); without,
    /// they are blended as vcnc's habits blend them.
    pub blend_next_to_arcs: bool,
    /// The acceleration a corner blend may turn with.
    pub blend_turning: BlendTurning,
    /// What is left of a line between two blends, when the blend speed crosses it in less than
    /// this, s, is run as part of the blend arc after it (LinuxCNC: 4 servo cycles, its
    /// `ARC_BLEND_GAP_CYCLES`); 0: never.
    pub blend_consume_seconds: f64,
    /// Share of the acceleration limit given to the normal (centripetal) acceleration on arcs and
    /// corner blends; the tangential acceleration keeps sqrt(1 - share^2) of the limit at the
    /// arc's highest speed.
    pub normal_acceleration_share: f64,
    /// The acceleration of a continuous-mode segment that ends without a blend into the next
    /// motion (before an event or the program end) is multiplied by this (LinuxCNC: 0.5).
    pub unblended_acceleration_factor: f64,
    /// The last motion before a stop enters no faster than it can stop from within this share
    /// of its length (LinuxCNC: 0.5; its optimizer plans the newest segment as if a blend might
    /// still take half of it, tp.c `tpCalculateOptimizationInitialVel`, and the program's end
    /// or a wait leaves it so).
    pub last_stop_length_share: f64,
    /// The largest share of the acceleration limit an arc may use tangentially when it ends
    /// without a next motion (LinuxCNC: 0.5, the share it gives an arc before it knows the next
    /// move); 1 leaves arcs to the normal-share rule alone.
    pub unblended_arc_tangential_share: f64,
    /// The acceleration of both motions at a corner where the machine stops (exact stop, or a
    /// corner too sharp to blend) is multiplied by this (LinuxCNC: 0.9, measured with
    /// lcnc-time; it matches its `ARC_BLEND_KINK_RATIO` of 0.1).
    pub stop_acceleration_factor: f64,
    /// The machine stops, without scaling either move's acceleration, where the path turns back
    /// to within this angle, degrees (LinuxCNC: 2, tp.c `tpSetupTangent`'s sharp corner); 0:
    /// only an exact reversal stops.
    pub reversal_stop_degrees: f64,
    /// Exact stop (G61) keeps moving through tangent block ends (LinuxCNC's "exact path"),
    /// instead of stopping at every block end.
    pub exact_stop_passes_tangents: bool,
    /// A stop between a rapid and a cutting move even in continuous mode.
    pub stop_between_rapid_and_feed: bool,
    /// Least time per segment, s: caps the speed on very short segments, and on what the
    /// blends leave of a segment (LinuxCNC: 1.02 servo cycles, on a segment's length when it is
    /// planned, after its blends).
    pub min_segment_seconds: f64,
    /// The trajectory's cycle, s (LinuxCNC: its servo period, 0.001): a direction change
    /// within one cycle is what [`PlannerConfig::kink_ratio`] weighs.
    pub cycle_seconds: f64,
    /// A corner whose direction change, made within one cycle at the slower segment's speed
    /// (plus the acceleration of the next), asks no axis for more than this share of its
    /// acceleration limit is passed as a tangent, both segments keeping 1 minus that share of
    /// their acceleration; at a sharper corner the same pass at the speed that asks for
    /// exactly this share competes with the blend arc, and the faster wins, the segments then
    /// keeping 1 minus this share (LinuxCNC: `ARC_BLEND_KINK_RATIO` 0.1, tp.c
    /// `tpSetupTangent` and `tpChooseBestBlend`). 0: never.
    pub kink_ratio: f64,
    /// Highest path speed, mm/min, whatever the axes allow (LinuxCNC's
    /// `[TRAJ]MAX_LINEAR_VELOCITY`); infinite when only the axes limit it.
    pub max_path_rate: f64,
    /// Seconds for a tool change (M06).
    pub tool_change_seconds: f64,
    /// Seconds for the spindle to start (M03/M04 from standstill).
    pub spindle_start_seconds: f64,
    /// Seconds for the spindle to stop (M05).
    pub spindle_stop_seconds: f64,
    /// Seconds for a spindle orientation (M19).
    pub spindle_orientation_seconds: f64,
}

/// When a motion leaves the look-ahead window with its speeds final.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LookAheadRelease {
    /// The first half of the window when it is full: every motion planned with at least half a
    /// window after it.
    Half,
    /// Each motion (of positive length) when the window's motions fill it: every motion planned
    /// with the same number of motions after it (LinuxCNC: `ARC_BLEND_OPTIMIZATION_DEPTH` 50,
    /// tp.c `tpRunOptimization`, a window of 52 with the motion itself and the newest, which it
    /// plans as a stop).
    Each,
}

/// How large a corner blend's arc is drawn (within the tolerance and the segments' lengths).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BlendRadius {
    /// The smallest arc that carries the junction speed: it cuts as little corner as it can.
    Least,
    /// LinuxCNC's: at least the arc a parabolic blend of the same corner would run along for
    /// as long, at half the acceleration, up to the largest the corner allows. On short
    /// segments that is much larger than the least arc: less path, more of it on the arc.
    ParabolicTime,
}

/// The acceleration available to a corner blend for turning.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BlendTurning {
    /// The lowest acceleration limit among the axes that move.
    LowestAxis,
    /// The largest acceleration in every direction of the plane of the two moves that no axis
    /// exceeds, for axes as strong as the weakest one that moves (LinuxCNC's circle inscribed
    /// in the plane's cut through the box of axis limits): above the lowest limit in a plane
    /// oblique to the axes.
    InPlane,
}

/// A named set of starting values for [`PlannerConfig`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PlannerHabits {
    /// vcnc's model of a FANUC-style control.
    Vcnc,
    /// LinuxCNC 2.9's trajectory planner.
    Linuxcnc,
}

impl Default for PlannerConfig {
    fn default() -> PlannerConfig {
        PlannerConfig::with_habits(PlannerHabits::Vcnc)
    }
}

impl PlannerConfig {
    /// The starting values of a set of habits.
    pub fn with_habits(habits: PlannerHabits) -> PlannerConfig {
        match habits {
            PlannerHabits::Vcnc => PlannerConfig {
                look_ahead: 200,
                look_ahead_release: LookAheadRelease::Half,
                corner_tolerance: 0.02,
                smoothing_tolerance: 0.01,
                rounding_tolerance: 0.1,
                rounding_distance_share: 0.36,
                blend_length_share: 0.5,
                corner_tolerance_length_share: f64::INFINITY,
                blend_arc_tangential_share: 0.0,
                blend_radius: BlendRadius::Least,
                blend_next_to_arcs: false,
                blend_turning: BlendTurning::LowestAxis,
                blend_consume_seconds: 0.0,
                normal_acceleration_share: NORMAL_SHARE,
                unblended_acceleration_factor: 1.0,
                unblended_arc_tangential_share: 1.0,
                last_stop_length_share: 1.0,
                stop_acceleration_factor: 1.0,
                reversal_stop_degrees: 0.0,
                exact_stop_passes_tangents: false,
                stop_between_rapid_and_feed: true,
                min_segment_seconds: 0.0,
                cycle_seconds: 0.001,
                kink_ratio: 0.0,
                max_path_rate: f64::INFINITY,
                tool_change_seconds: 4.0,
                spindle_start_seconds: 1.0,
                spindle_stop_seconds: 1.0,
                spindle_orientation_seconds: 1.0,
            },
            // LinuxCNC's planner as lcnc-time's README describes it: plain G64 has no tolerance
            // but a quarter of the segments' lengths, blends may use half of each segment and
            // are arcs of their own with half the acceleration along them (tc.c, blendmath.c),
            // arcs keep half the acceleration tangentially, spindle and tool change are instant
            // in its simulated machine. Besides (tp.c): near-tangent kinks pass at speed, a
            // segment's speed is capped over what its blends leave of it, each segment is planned
            // with 50 after it, blends next to arcs are bounded by the arcs, the last segment is
            // entered as if a blend could still take half of it, near reversals stop.
            PlannerHabits::Linuxcnc => PlannerConfig {
                look_ahead: 52,
                look_ahead_release: LookAheadRelease::Each,
                corner_tolerance: f64::INFINITY,
                smoothing_tolerance: 0.01,
                rounding_tolerance: 0.1,
                rounding_distance_share: 0.36,
                blend_length_share: 0.5,
                corner_tolerance_length_share: 0.25,
                blend_arc_tangential_share: 0.5,
                blend_radius: BlendRadius::ParabolicTime,
                blend_next_to_arcs: true,
                blend_turning: BlendTurning::InPlane,
                blend_consume_seconds: 0.004,
                normal_acceleration_share: NORMAL_SHARE,
                unblended_acceleration_factor: 0.5,
                unblended_arc_tangential_share: 0.5,
                last_stop_length_share: 0.5,
                stop_acceleration_factor: 0.9,
                reversal_stop_degrees: 2.0,
                exact_stop_passes_tangents: true,
                stop_between_rapid_and_feed: true,
                min_segment_seconds: 0.00102,
                cycle_seconds: 0.001,
                kink_ratio: 0.1,
                max_path_rate: f64::INFINITY,
                tool_change_seconds: 0.0,
                spindle_start_seconds: 0.0,
                spindle_stop_seconds: 0.0,
                spindle_orientation_seconds: 0.0,
            },
        }
    }
}

/// sqrt(3)/2: the normal share that leaves half the acceleration for the tangent.
const NORMAL_SHARE: f64 = 0.866_025_403_784_438_6;

/// The `[planner]` table as written: every field optional.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct PlannerFile {
    habits: Option<PlannerHabits>,
    look_ahead: Option<usize>,
    look_ahead_release: Option<LookAheadRelease>,
    corner_tolerance: Option<f64>,
    smoothing_tolerance: Option<f64>,
    rounding_tolerance: Option<f64>,
    rounding_distance_share: Option<f64>,
    blend_length_share: Option<f64>,
    corner_tolerance_length_share: Option<f64>,
    blend_arc_tangential_share: Option<f64>,
    blend_radius: Option<BlendRadius>,
    blend_next_to_arcs: Option<bool>,
    blend_turning: Option<BlendTurning>,
    blend_consume_seconds: Option<f64>,
    normal_acceleration_share: Option<f64>,
    unblended_acceleration_factor: Option<f64>,
    unblended_arc_tangential_share: Option<f64>,
    last_stop_length_share: Option<f64>,
    stop_acceleration_factor: Option<f64>,
    reversal_stop_degrees: Option<f64>,
    exact_stop_passes_tangents: Option<bool>,
    stop_between_rapid_and_feed: Option<bool>,
    min_segment_seconds: Option<f64>,
    cycle_seconds: Option<f64>,
    kink_ratio: Option<f64>,
    max_path_rate: Option<f64>,
    tool_change_seconds: Option<f64>,
    spindle_start_seconds: Option<f64>,
    spindle_stop_seconds: Option<f64>,
    spindle_orientation_seconds: Option<f64>,
}

impl PlannerFile {
    /// The resolved settings, or a sentence saying which value is out of range.
    pub(crate) fn resolve(&self) -> Result<PlannerConfig, String> {
        let mut c = PlannerConfig::with_habits(self.habits.unwrap_or(PlannerHabits::Vcnc));
        set(&mut c.look_ahead, self.look_ahead);
        set(&mut c.look_ahead_release, self.look_ahead_release);
        set(&mut c.corner_tolerance, self.corner_tolerance);
        set(&mut c.smoothing_tolerance, self.smoothing_tolerance);
        set(&mut c.rounding_tolerance, self.rounding_tolerance);
        set(&mut c.rounding_distance_share, self.rounding_distance_share);
        set(&mut c.blend_length_share, self.blend_length_share);
        set(
            &mut c.corner_tolerance_length_share,
            self.corner_tolerance_length_share,
        );
        set(
            &mut c.blend_arc_tangential_share,
            self.blend_arc_tangential_share,
        );
        set(&mut c.blend_radius, self.blend_radius);
        set(&mut c.blend_next_to_arcs, self.blend_next_to_arcs);
        set(&mut c.blend_turning, self.blend_turning);
        set(&mut c.blend_consume_seconds, self.blend_consume_seconds);
        set(
            &mut c.normal_acceleration_share,
            self.normal_acceleration_share,
        );
        set(
            &mut c.unblended_acceleration_factor,
            self.unblended_acceleration_factor,
        );
        set(
            &mut c.unblended_arc_tangential_share,
            self.unblended_arc_tangential_share,
        );
        set(&mut c.last_stop_length_share, self.last_stop_length_share);
        set(
            &mut c.stop_acceleration_factor,
            self.stop_acceleration_factor,
        );
        set(&mut c.reversal_stop_degrees, self.reversal_stop_degrees);
        set(
            &mut c.exact_stop_passes_tangents,
            self.exact_stop_passes_tangents,
        );
        set(
            &mut c.stop_between_rapid_and_feed,
            self.stop_between_rapid_and_feed,
        );
        set(&mut c.min_segment_seconds, self.min_segment_seconds);
        set(&mut c.cycle_seconds, self.cycle_seconds);
        set(&mut c.kink_ratio, self.kink_ratio);
        set(&mut c.max_path_rate, self.max_path_rate);
        set(&mut c.tool_change_seconds, self.tool_change_seconds);
        set(&mut c.spindle_start_seconds, self.spindle_start_seconds);
        set(&mut c.spindle_stop_seconds, self.spindle_stop_seconds);
        set(
            &mut c.spindle_orientation_seconds,
            self.spindle_orientation_seconds,
        );
        c.check()?;
        Ok(c)
    }
}

fn set<T>(field: &mut T, value: Option<T>) {
    if let Some(value) = value {
        *field = value;
    }
}

impl PlannerConfig {
    fn check(&self) -> Result<(), String> {
        let within = |name: &str, value: f64, low: f64, high: f64| {
            if value.is_nan() || value < low || value > high {
                Err(format!(
                    "planner.{name} = {value}: expected {low} to {high}"
                ))
            } else {
                Ok(())
            }
        };
        if self.look_ahead < 2 || self.look_ahead > 100_000 {
            return Err(format!(
                "planner.look_ahead = {}: expected 2 to 100000",
                self.look_ahead
            ));
        }
        within(
            "corner_tolerance",
            self.corner_tolerance,
            0.0,
            f64::INFINITY,
        )?;
        // Kept in whole micrometres on every motion (crate::motion::Smoothing).
        let most = crate::motion::Smoothing::MAX_MM;
        within("smoothing_tolerance", self.smoothing_tolerance, 0.001, most)?;
        within("rounding_tolerance", self.rounding_tolerance, 0.001, most)?;
        within(
            "rounding_distance_share",
            self.rounding_distance_share,
            0.0,
            0.5,
        )?;
        within("blend_length_share", self.blend_length_share, 0.0, 0.5)?;
        within(
            "corner_tolerance_length_share",
            self.corner_tolerance_length_share,
            0.0,
            f64::INFINITY,
        )?;
        // A share of 1 would leave the arc no acceleration to turn with.
        within(
            "blend_arc_tangential_share",
            self.blend_arc_tangential_share,
            0.0,
            0.99,
        )?;
        within(
            "blend_consume_seconds",
            self.blend_consume_seconds,
            0.0,
            1.0,
        )?;
        // A share of 1 would leave no tangential acceleration at an arc's top speed.
        within(
            "normal_acceleration_share",
            self.normal_acceleration_share,
            0.01,
            0.99,
        )?;
        within(
            "unblended_acceleration_factor",
            self.unblended_acceleration_factor,
            0.01,
            1.0,
        )?;
        within(
            "unblended_arc_tangential_share",
            self.unblended_arc_tangential_share,
            0.01,
            1.0,
        )?;
        within(
            "last_stop_length_share",
            self.last_stop_length_share,
            0.01,
            1.0,
        )?;
        within(
            "stop_acceleration_factor",
            self.stop_acceleration_factor,
            0.01,
            1.0,
        )?;
        within(
            "reversal_stop_degrees",
            self.reversal_stop_degrees,
            0.0,
            90.0,
        )?;
        within("min_segment_seconds", self.min_segment_seconds, 0.0, 1.0)?;
        within("cycle_seconds", self.cycle_seconds, 1e-6, 1.0)?;
        // LinuxCNC bounds its ratio to 0.7071 (tp.c tpGetTangentKinkRatio).
        within(
            "kink_ratio",
            self.kink_ratio,
            0.0,
            std::f64::consts::FRAC_1_SQRT_2,
        )?;
        within("max_path_rate", self.max_path_rate, 1e-6, f64::INFINITY)?;
        for (name, value) in [
            ("tool_change_seconds", self.tool_change_seconds),
            ("spindle_start_seconds", self.spindle_start_seconds),
            ("spindle_stop_seconds", self.spindle_stop_seconds),
            (
                "spindle_orientation_seconds",
                self.spindle_orientation_seconds,
            ),
        ] {
            within(name, value, 0.0, 1e6)?;
        }
        Ok(())
    }
}
