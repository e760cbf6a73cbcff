//! Where a control's coordinate systems come from: which work offsets exist (G54.1 Pn, G59.x,
//! G154), which G10 L numbers set them, Syntec's G92.1 with a rotation, and the reference
//! points of G28 and G30.

use serde::{Deserialize, Serialize};

/// `[coordinates]`: work offsets, their G10 L numbers, G92.1, and the reference points.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CoordinateRules {
    /// Number of G54.1 Pn work offsets (0: G54.1 does not exist).
    pub g54_1_count: u32,
    /// Syntec's G59.1 ... G59.9 work offsets 7 to 15.
    pub g59_x_offsets: bool,
    /// Haas's G154 Pn selects the extended work offsets like G54.1 Pn.
    #[serde(default)]
    pub g154_extended_offsets: bool,
    /// The G10 L number that sets work offsets G54..G59 (P1..P6, P0 = external).
    pub g10_work_l: u32,
    /// The G10 L number that sets G54.1 work offsets (0: none).
    pub g10_extended_work_l: u32,
    /// Syntec's G92.1 X Y K R: a preset of the program origin with a rotation (spec 1.55);
    /// elsewhere G92.1 is FANUC's work coordinate system preset.
    #[serde(default)]
    pub g92_1_rotation: bool,
    /// Number of reference points (G28 is 1, G30 P2..Pn).
    pub reference_points: u32,
    /// G28 (and G30) without axis words sends every axis home (Haas); otherwise nothing moves.
    #[serde(default)]
    pub g28_without_axes_homes_all: bool,
    /// A G30 P the control does not have (P0, P1, P5 and above) goes to the 2nd reference
    /// point (Mitsubishi, 003 L50); otherwise it is an alarm.
    #[serde(default)]
    pub g30_other_p_is_second: bool,
    /// G28 cancels the G52 local coordinate system (Mitsubishi 003 L75: reference point return
    /// cancels it).
    #[serde(default)]
    pub g28_cancels_local: bool,
    /// G28 cancels tool length compensation (G49), not only its vector until the next Z move
    /// (Haas).
    #[serde(default)]
    pub g28_cancels_length_offset: bool,
    /// How G16 reads a radius or an angle in G91.
    #[serde(default)]
    pub polar_increments: PolarIncrements,
    /// Which axes G51 scales.
    #[serde(default)]
    pub scaling_axes: ScalingAxes,
    /// G51 scaling and the G51.1 mirror can be on together (a FANUC: the mirror first); otherwise
    /// the second is an alarm (Syntec spec 1.28, 1.29).
    #[serde(default)]
    pub scaling_with_mirror: bool,
}

/// How G16 polar coordinates read G91.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PolarIncrements {
    /// Radius and angle add to the previous polar point's; the pole stays the program origin
    /// (Syntec spec 1.14, L1033).
    #[default]
    AddToPreviousPoint,
    /// A radius in G91 is measured from the current position, which becomes the pole (in G90
    /// the pole is the program origin); an angle in G91 adds to the previous one (a FANUC).
    PoleAtCurrentPosition,
}

/// The axes G51 scales.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ScalingAxes {
    /// Only the axes named in the G51 block, about the coordinates they give (Syntec spec 1.28).
    #[default]
    Named,
    /// X, Y and Z whether named or not (a FANUC's parameter SCLx set for the basic axes), each
    /// about the coordinate its word gives or the current position.
    BasicAxes,
}
