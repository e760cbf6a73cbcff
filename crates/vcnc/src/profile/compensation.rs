//! A control's tool offsets and compensation: the offset numbers, what G10's tool L numbers
//! set, radius or diameter, how G41/G42 find their offset, cutter compensation's look-ahead, and
//! the G45-G48 tool position offsets.

use serde::{Deserialize, Serialize};

/// What a G10 L number sets, for tool offsets.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ToolOffsetField {
    /// Tool length, geometry.
    LengthGeometry,
    /// Tool length, wear.
    LengthWear,
    /// Cutter radius (or diameter, per `radius_offsets_are_diameters`), geometry.
    RadiusGeometry,
    /// Cutter radius, wear.
    RadiusWear,
}

/// One G10 L number for tool offsets.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct ToolOffsetL {
    /// The L number.
    pub l: u32,
    /// What it sets.
    pub field: ToolOffsetField,
}

/// `[compensation]`: the tool offset memory and the compensations that read it (where the
/// offsets sit among the system variables is the macros' `tool_offset_variables`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompensationRules {
    /// Highest H/D offset number.
    pub max_offset_number: u32,
    /// The G10 L numbers that set tool offsets.
    pub g10_tool_l: Vec<ToolOffsetL>,
    /// A G10 tool offset block without L (`G10 P_ R_`) sets this field (FANUC 0M memory A).
    #[serde(default)]
    pub g10_tool_default: Option<ToolOffsetField>,
    /// Cutter compensation values are diameters (Haas), not radii.
    pub radius_offsets_are_diameters: bool,
    /// A G41/G42 block with H and no D takes H as its radius offset number, not as a length
    /// offset (the old FANUC 0M form, `G42 H19`, seen in the corpus).
    #[serde(default)]
    pub radius_offset_by_h: bool,
    /// Blocks in a row without motion in the compensation plane after which the last element
    /// ends perpendicular to itself (cutter compensation's look-ahead; FANUC: 2).
    #[serde(default = "default_cutter_comp_look_ahead")]
    pub cutter_comp_look_ahead: u32,
    /// G45-G48 are tool position offsets (FANUC family, Syntec, Mitsubishi); Haas has no such
    /// codes (its G47 engraves text).
    #[serde(default = "super::default_true")]
    pub tool_position_offset: bool,
    /// G43/G44 H or G49 without a Z word moves by the change of offset at rapid, as `G00 G91
    /// Z0` would (Mitsubishi 003 L65 note 1); otherwise in the motion mode in force.
    #[serde(default)]
    pub length_change_at_rapid: bool,
    /// G53 in offset mode keeps the radius compensation of the axes it moves (Mitsubishi 003
    /// L79); otherwise the block is made without it, as G28 is (FANUC family, spec A.22).
    #[serde(default)]
    pub g53_keeps_radius_compensation: bool,
    /// G62 is the automatic corner override of the FANUC family, with these settings; `None`
    /// where G62 means something else (Syntec's curved-surface cutting mode, spec 1.34) or the
    /// control has no such function.
    #[serde(default)]
    pub corner_override: Option<CornerOverride>,
}

/// `corner_override`: the inner-corner feed override of G62 (FANUC's parameters 1710-1714; the
/// FANUC 0M textbook, 001 L1533, says only that the feed is lowered at inner corners).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CornerOverride {
    /// The override is on whenever G41/G42 is, G62 programmed or not (the FANUC 0M textbook,
    /// 001 L1533); otherwise only in G62.
    pub with_compensation: bool,
    /// A corner of the tool-centre path whose inner angle is at most this, degrees, is
    /// overridden (FANUC parameter 1711, 2 to 178).
    pub inner_angle: f64,
    /// The feed at an inner corner, percent of F (FANUC parameter 1712).
    pub override_percent: f64,
    /// Le: the distance before the corner the override starts at, mm (FANUC parameter 1714).
    pub before_corner: f64,
    /// Ls: the distance after the corner it ends at, mm (FANUC parameter 1713).
    pub after_corner: f64,
    /// On an arc with the tool inside it, the feed along the tool centre is F times the tool
    /// centre's radius over the programmed radius, never below this percent of F (FANUC's inner
    /// circular cutting feed change and its parameter 1710).
    pub inner_arc_min_percent: f64,
}

fn default_cutter_comp_look_ahead() -> u32 {
    2
}
