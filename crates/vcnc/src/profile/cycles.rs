//! How a control's canned cycles drill: the drilling axis, the peck distances, G76's shift, and
//! Syntec's hole patterns. (A cycle's dwell P is read by [`DwellRules`](super::DwellRules).)

use serde::{Deserialize, Serialize};

/// Where G76 shifts the tool at the hole bottom: along the plane's first or second axis.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ShiftDirection {
    /// +X in G17 (the plane's first axis, plus).
    #[default]
    PlusFirst,
    /// -X in G17.
    MinusFirst,
    /// +Y in G17.
    PlusSecond,
    /// -Y in G17.
    MinusSecond,
}

/// `[cycles]`: the canned cycles' parameters (every field has a default: FANUC's).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CycleRules {
    /// Canned cycles drill along the axis normal to the plane (G17 Z, G18 Y, G19 X); when false,
    /// always along Z (FANUC 0M, spec A.32).
    #[serde(default = "super::default_true")]
    pub cycle_plane_follows_g17: bool,
    /// G73: how far the tool backs off after each peck, mm (FANUC parameter 5114, 0M 0531,
    /// Syntec Pr4002).
    #[serde(default = "default_peck_distance")]
    pub peck_retract: f64,
    /// G83: how far above the last depth the rapid back into the hole stops, mm (FANUC 5115,
    /// Syntec Pr4002).
    #[serde(default = "default_peck_distance")]
    pub peck_clearance: f64,
    /// G76: the direction of the shift off the wall at the hole bottom (Syntec Pr4020, FANUC
    /// RD1/RD2), in the positioning plane.
    #[serde(default)]
    pub boring_shift: ShiftDirection,
    /// Syntec's hole patterns G134, G135, G136, G137.1.
    #[serde(default)]
    pub hole_patterns: bool,
    /// Syntec's fast drilling mode (parameter Pr4008 = 1): G81 retracts at its `F2=` feed
    /// (spec 1.44). Off (the normal drilling mode, every built-in profile), the retract is a
    /// rapid; a machine file turns it on.
    #[serde(default)]
    pub fast_drilling: bool,
}

fn default_peck_distance() -> f64 {
    1.0
}
