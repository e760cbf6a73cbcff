//! How a control moves: G00's path, the feed before any F, arcs (the radius tolerance, Syntec's
//! spirals), threads, Mitsubishi's circle cutting, polar coordinate interpolation, and the
//! high-speed and smoothing codes.

use serde::{Deserialize, Serialize};

/// How G00 moves the axes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RapidPath {
    /// All axes arrive together on a straight line (Syntec Pr411 = 0).
    Linear,
    /// Each axis at its own rapid rate: a dog-leg path (FANUC's classic positioning).
    PerAxis,
}

/// How an absolute (G90) move of a rotary axis goes: FANUC's rollover parameters ROAx and RABx.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RotaryRollover {
    /// No rollover: the axis goes to the angle written, as a linear axis would.
    #[default]
    Off,
    /// The angle is taken modulo 360 and reached by the shorter way (ROAx = 1, RABx = 0); half
    /// a turn goes the positive way.
    Shortest,
    /// The angle is taken modulo 360 and reached turning the way of its sign (ROAx = 1,
    /// RABx = 1): `C-90.` turns negatively to 90.
    BySign,
}

/// The high-speed and smoothing codes of a control.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SmoothingCodes {
    /// None that vcnc runs.
    #[default]
    None,
    /// Syntec (spec iso-syntec-milling.md 1.8, 1.9): G05 P10000 (E optional) high-speed high-precision
    /// mode and G05.1 Q1/Q2 E path smoothing, off with G05 P0 and G05.1 Q0.
    Syntec,
    /// FANUC: G05 P10000 (high-precision contour control), G05.1 Q1 (AI contour control) and
    /// G08 P1 (look-ahead control), off with P0, Q0 and P0; none takes a tolerance.
    Fanuc,
}

/// `[motion]`: the path of each kind of move (the timing is the machine file's `[planner]`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MotionRules {
    /// G00 path shape.
    pub rapid_path: RapidPath,
    /// Feed used when G01/G02/G03 run before any F (None: alarm, as FANUC alarm 011).
    #[serde(default)]
    pub default_feed: Option<f64>,
    /// Largest difference between start and end radius of an arc, mm (FANUC parameter 3410).
    pub arc_radius_tolerance: f64,
    /// L in a G02/G03 block is the number of turns of a spiral (Syntec, spec 1.6).
    #[serde(default)]
    pub arc_l_is_spiral: bool,
    /// E in a G33 block gives threads per inch (Mitsubishi, spec B.10); elsewhere E in G33 is
    /// refused like any E outside a tapping cycle.
    #[serde(default)]
    pub thread_e_per_inch: bool,
    /// Mitsubishi's G12/G13 circle cutting exists.
    #[serde(default)]
    pub g12_g13_circle_cutting: bool,
    /// G12/G13 are Haas's circular pocket milling (I K Q L D Z F).
    #[serde(default)]
    pub g12_g13_pocket: bool,
    /// G12.1/G13.1 polar coordinate interpolation exists (FANUC family, Syntec spec 1.13,
    /// Mitsubishi); it turns the machine's C axis with X as the radius.
    #[serde(default)]
    pub polar_interpolation: bool,
    /// Largest distance, mm, between the programmed path in G12.1 and the path the straight X-C
    /// pieces that replace it trace on the part (vcnc's choice: FANUC and Syntec interpolate in
    /// their servo cycle and give no such number).
    #[serde(default = "default_polar_interpolation_tolerance")]
    pub polar_interpolation_tolerance: f64,
    /// G07.1 cylindrical interpolation exists (FANUC 0i/30i-M and Mitsubishi M70/M700, whose
    /// manuals are not among the seeds; docs/DEVIATIONS.md); it cuts on the surface of a
    /// cylinder turned by a rotary axis, within `polar_interpolation_tolerance`.
    #[serde(default)]
    pub cylindrical_interpolation: bool,
    /// G07 hypothetical axis interpolation exists (FANUC 0i/15i/16i-M and Mitsubishi M70/M700,
    /// whose manuals are not among the seeds; docs/DEVIATIONS.md): an axis made hypothetical
    /// takes part in the interpolation but does not move.
    #[serde(default)]
    pub hypothetical_axis_interpolation: bool,
    /// How G90 moves rotary axes: every rotary axis of the machine rolls over this way (G91
    /// moves by the amount written either way). No manual of the seeds sets it: a machine
    /// file does (`[profile_overrides.motion] rotary_rollover = "shortest"`).
    #[serde(default)]
    pub rotary_rollover: RotaryRollover,
    /// Which high-speed and smoothing codes the control has (they change the timing, within a
    /// tolerance the path).
    #[serde(default)]
    pub smoothing_codes: SmoothingCodes,
    /// The 5-axis codes exist: G43.4 tool centre point control, G68.2 tilted working plane and
    /// G53.1 tool axis direction (Syntec spec 1.26, 1.32, 1.38; FANUC's Series 30i); they run
    /// on a machine file with `[kinematics]`.
    #[serde(default)]
    pub five_axis: bool,
    /// G68.2's FANUC forms besides the Euler angles: P1 roll-pitch-yaw (Q the order), P2 three
    /// points, P3 two vectors (FANUC Series 30i; Syntec's manual gives the Euler form only).
    #[serde(default)]
    pub tilted_plane_forms: bool,
    /// G43.5 tool centre point control type 2: the tool direction by I J K in the program
    /// system, the rotary positions solved by the control (FANUC Series 30i; not in Syntec's
    /// manual).
    #[serde(default)]
    pub tool_center_point_type2: bool,
    /// G22/G23 stored stroke check 2, a forbidden zone switched by the program (Syntec 1.16).
    #[serde(default)]
    pub stored_stroke_check: bool,
    /// G27 reference position return check (FANUC 0M A.25).
    #[serde(default)]
    pub reference_check: bool,
    /// G37/G37.1 automatic tool length measurement against the tool setter (Syntec 1.22, 1.23).
    #[serde(default)]
    pub tool_length_measurement: bool,
    /// Haas G187 smoothness and corner rounding setting.
    #[serde(default)]
    pub smoothness_setting: bool,
    /// Syntec G120.1 machining-condition sets (listed in the code table, 000 L94-140).
    #[serde(default)]
    pub machining_condition_sets: bool,
}

fn default_polar_interpolation_tolerance() -> f64 {
    0.001
}
