//! Controller profiles: what differs between the controls vcnc imitates, as data.
//!
//! A [`Profile`] holds the parameters and rules in which the FANUC-family controls differ:
//! how numbers without a decimal point are read, which extended work offsets exist, what G10's
//! L numbers mean, the dwell rules, the power-on modal state. Code asks the profile a question;
//! it never asks which controller it is. The five built-in profiles are TOML files embedded in
//! the library (`profile/*.toml`); a machine file can override any field.

mod codes;
mod sinumerik;

pub use codes::{
    classify_g, classify_m, g_name, not_supported_description, supported_codes_markdown, CycleKind,
    GCode, GLookup, Group, MCode, MLookup, PatternKind,
};

use crate::syntax::iso::SyntaxOptions;
use serde::{Deserialize, Serialize};
pub use sinumerik::{SinumerikSettings, Variant};
use std::fmt;
use std::str::FromStr;

/// The built-in profiles.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum ProfileName {
    /// The FANUC-family common ground that CAM post-processors target (the default).
    #[default]
    Fanuc,
    /// Syntec 900M/10/20-series milling (manual seed 000).
    Syntec,
    /// FANUC 0M (manual seed 001).
    Fanuc0m,
    /// Mitsubishi M-series (manual seed 003).
    Mitsubishi,
    /// FANUC plus the habits of Haas mills seen in real programs.
    Haas,
    /// SINUMERIK 840D sl milling (manual seed 002), its own language and front end.
    Sinumerik,
    /// SINUMERIK 828D milling: the 840D language with the 828D's variant (G58/G59 as the 5th
    /// and 6th settable frames).
    Sinumerik828d,
}

impl ProfileName {
    /// Every built-in ISO profile (the FANUC family: one interpreter, one code table).
    pub const ALL: [ProfileName; 5] = [
        ProfileName::Fanuc,
        ProfileName::Syntec,
        ProfileName::Fanuc0m,
        ProfileName::Mitsubishi,
        ProfileName::Haas,
    ];

    /// The SINUMERIK profiles: programs in the SINUMERIK language.
    pub const SINUMERIK: [ProfileName; 2] = [ProfileName::Sinumerik, ProfileName::Sinumerik828d];

    /// True for the SINUMERIK profiles.
    pub fn is_sinumerik(self) -> bool {
        ProfileName::SINUMERIK.contains(&self)
    }

    /// The name used on the command line and in machine files.
    pub fn as_str(self) -> &'static str {
        match self {
            ProfileName::Fanuc => "fanuc",
            ProfileName::Syntec => "syntec",
            ProfileName::Fanuc0m => "fanuc0m",
            ProfileName::Mitsubishi => "mitsubishi",
            ProfileName::Haas => "haas",
            ProfileName::Sinumerik => "sinumerik",
            ProfileName::Sinumerik828d => "sinumerik828d",
        }
    }

    /// The embedded TOML text of the profile.
    pub fn toml(self) -> &'static str {
        match self {
            ProfileName::Fanuc => include_str!("fanuc.toml"),
            ProfileName::Syntec => include_str!("syntec.toml"),
            ProfileName::Fanuc0m => include_str!("fanuc0m.toml"),
            ProfileName::Mitsubishi => include_str!("mitsubishi.toml"),
            ProfileName::Haas => include_str!("haas.toml"),
            ProfileName::Sinumerik => include_str!("sinumerik.toml"),
            ProfileName::Sinumerik828d => include_str!("sinumerik828d.toml"),
        }
    }
}

impl fmt::Display for ProfileName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl FromStr for ProfileName {
    type Err = String;
    fn from_str(s: &str) -> Result<ProfileName, String> {
        ProfileName::ALL
            .into_iter()
            .chain(ProfileName::SINUMERIK)
            .find(|p| p.as_str().eq_ignore_ascii_case(s))
            .ok_or_else(|| format!("unknown profile `{s}` (expected one of fanuc, syntec, fanuc0m, mitsubishi, haas, sinumerik, sinumerik828d)"))
    }
}

/// How a value without a decimal point is read for length and angle words.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DecimalLess {
    /// In least input increments: `X20` is 0.020 mm (FANUC with parameter DPI = 0).
    Increments,
    /// In whole units: `X20` is 20 mm (FANUC with DPI = 1, pocket calculator input).
    WholeUnits,
}

/// How the argument letters of G65/G66 become local variables.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MacroArguments {
    /// FANUC argument specification I (A #1, B #2, C #3, I #4, J #5, K #6, D #7, E #8, F #9,
    /// H #11, M #13, Q #17, R #18, S #19, T #20, U #21, V #22, W #23, X #24, Y #25, Z #26) and
    /// II (I, J, K repeated: the n-th I is #(3n+1), J #(3n+2), K #(3n+3)).
    #[default]
    Fanuc,
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

/// Where the tool offsets are among the system variables.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ToolOffsetVariables {
    /// FANUC tool offset memory C: #2001 H wear, #2201 H geometry, #2401 D wear, #2601 D
    /// geometry (200 each; #10001/#11001/#12001/#13001 for 400).
    #[default]
    FanucC,
    /// Haas: #2001 length geometry, #2201 length wear, #2401 diameter geometry, #2601
    /// diameter wear.
    Haas,
}

/// How `P` of G04 is read.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DwellP {
    /// Milliseconds; a decimal point is an alarm (FANUC).
    MillisecondsStrict,
    /// Milliseconds; a fraction is dropped (`P2.5` is 2 ms, Syntec manual L512).
    MillisecondsTruncated,
    /// Milliseconds without a decimal point, seconds with one (Haas, Mitsubishi).
    SecondsWithPoint,
}

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

/// How G00 moves the axes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RapidPath {
    /// All axes arrive together on a straight line (Syntec Pr411 = 0).
    Linear,
    /// Each axis at its own rapid rate: a dog-leg path (FANUC's classic positioning).
    PerAxis,
}

/// What two G codes of one modal group in one block do.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SameGroupRule {
    /// The last one written is effective (FANUC); vcnc warns.
    LastWins,
    /// An alarm.
    Alarm,
}

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

/// The modal state at power-on and reset, as G codes in tenths (G17 is 170).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PowerOn {
    /// G00 or G01.
    pub motion: u32,
    /// G17, G18 or G19.
    pub plane: u32,
    /// G90 or G91.
    pub distance: u32,
    /// G20 or G21 (G70 or G71 on Syntec).
    pub units: u32,
    /// G94 or G95.
    pub feed_mode: u32,
    /// G54 ... .
    pub work_offset: u32,
    /// G61 or G64.
    pub path_mode: u32,
    /// G98 or G99.
    pub cycle_return: u32,
}

/// Everything about a controller that the interpreter asks.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Profile {
    /// Which built-in profile this is (or started from).
    pub name: ProfileName,
    /// One line for people.
    pub description: String,
    /// `;` ends a block (true) or starts a comment (false).
    pub semicolon_ends_block: bool,
    /// `//` starts a comment to the end of the line.
    pub slash_slash_comments: bool,
    /// `:1234` is a program number.
    pub colon_program_number: bool,
    /// How lengths and angles without a decimal point are read.
    pub decimal_less: DecimalLess,
    /// Least input increment in millimetre mode, mm.
    pub increment_mm: f64,
    /// Least input increment in inch mode, inch.
    pub increment_inch: f64,
    /// Least input increment of rotary axes, degrees.
    pub increment_deg: f64,
    /// How G04 P is read.
    pub dwell_p: DwellP,
    /// FANUC 0M quirk (manual 001 L190-202): an X word written before G04 in the same block was
    /// already converted as a distance, and that count of increments becomes milliseconds.
    pub dwell_x_before_g04_is_increments: bool,
    /// Syntec's G70/G71 select inch/metric (besides G20/G21).
    pub g70_g71_units: bool,
    /// Number of G54.1 Pn work offsets (0: G54.1 does not exist).
    pub g54_1_count: u32,
    /// Syntec's G59.1 ... G59.9 work offsets 7 to 15.
    pub g59_x_offsets: bool,
    /// Haas's G154 Pn selects the extended work offsets like G54.1 Pn.
    #[serde(default)]
    pub g154_extended_offsets: bool,
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
    /// The G10 L number that sets work offsets G54..G59 (P1..P6, P0 = external).
    pub g10_work_l: u32,
    /// The G10 L number that sets G54.1 work offsets (0: none).
    pub g10_extended_work_l: u32,
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
    #[serde(default = "default_true")]
    pub tool_position_offset: bool,
    /// Canned cycles drill along the axis normal to the plane (G17 Z, G18 Y, G19 X); when false,
    /// always along Z (FANUC 0M, spec A.32).
    #[serde(default = "default_true")]
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
    /// How a canned cycle's P is read; when absent, as G04's P.
    #[serde(default)]
    pub cycle_dwell_p: Option<DwellP>,
    /// Syntec's hole patterns G134, G135, G136, G137.1.
    #[serde(default)]
    pub hole_patterns: bool,
    /// Syntec's G92.1 X Y K R: a preset of the program origin with a rotation (spec 1.55);
    /// elsewhere G92.1 is FANUC's work coordinate system preset.
    #[serde(default)]
    pub g92_1_rotation: bool,
    /// M codes a block may hold; when a block has more, only the last ones run (FANUC 0M: one,
    /// spec A.15 and example fanuc0m/06).
    #[serde(default = "default_m_codes_per_block")]
    pub m_codes_per_block: u32,
    /// Largest magnitude of any value as written (`X99999999` ...): the control's digit limit.
    #[serde(default = "default_max_word_value")]
    pub max_word_value: f64,
    /// Highest H/D offset number.
    pub max_offset_number: u32,
    /// G00 path shape.
    pub rapid_path: RapidPath,
    /// Two G codes of one group in a block.
    pub same_group: SameGroupRule,
    /// Feed used when G01/G02/G03 run before any F (None: alarm, as FANUC alarm 011).
    #[serde(default)]
    pub default_feed: Option<f64>,
    /// Largest difference between start and end radius of an arc, mm (FANUC parameter 3410).
    pub arc_radius_tolerance: f64,
    /// G28 (and G30) without axis words sends every axis home (Haas); otherwise nothing moves.
    #[serde(default)]
    pub g28_without_axes_homes_all: bool,
    /// Number of reference points (G28 is 1, G30 P2..Pn).
    pub reference_points: u32,
    /// M codes that are subprogram calls and returns on this control: 98 call, 99 return,
    /// 198 external call (Syntec), 96/97 interrupt on/off (Syntec) or 97 local call (Haas, see
    /// `m97_local_subprogram`).
    pub subprogram_m_codes: Vec<u32>,
    /// M97 P calls sequence number P of the running program (Haas); otherwise M97 turns the
    /// interrupt program off (Syntec).
    #[serde(default)]
    pub m97_local_subprogram: bool,
    /// M02 and M30 in a subprogram return to the caller (Syntec, spec section 2 item 12);
    /// otherwise they end the program (FANUC).
    #[serde(default)]
    pub end_in_subprogram_returns: bool,
    /// How G65/G66 argument letters map to local variables.
    #[serde(default)]
    pub macro_arguments: MacroArguments,
    /// Which system variable numbers hold the tool offsets.
    #[serde(default)]
    pub tool_offset_variables: ToolOffsetVariables,
    /// Syntec's #1000 modal variables, #1901-#1916 G92 offsets and #1930 rotation.
    #[serde(default)]
    pub syntec_system_variables: bool,
    /// Haas's #3020-#3027 timers and spindle data, #4201+ modal data, #5401+ tool life.
    #[serde(default)]
    pub haas_system_variables: bool,
    /// Extra common variables kept between runs (Haas: #10000-#10999), first and last.
    #[serde(default)]
    pub extended_common_variables: Option<(u32, u32)>,
    /// Macro calls (G65, G66) nested at most this deep (FANUC: 4; PS0077 beyond).
    #[serde(default = "default_macro_call_depth")]
    pub macro_call_depth: u32,
    /// Subprogram and macro calls together nested at most this deep (FANUC 0i: 10).
    #[serde(default = "default_call_depth")]
    pub call_depth: u32,
    /// The loop numbers DO and END take: 1 to this (FANUC: 3).
    #[serde(default = "default_loop_numbers")]
    pub loop_numbers: u32,
    /// `M98 P50001` without L calls O0001 five times: the digits before the last four count
    /// the repeats (FANUC).
    #[serde(default)]
    pub m98_p_holds_repeats: bool,
    /// G12.1/G13.1 polar coordinate interpolation exists (FANUC family, Syntec spec 1.13,
    /// Mitsubishi); it turns the machine's C axis with X as the radius.
    #[serde(default)]
    pub polar_interpolation: bool,
    /// Largest distance, mm, between the programmed path in G12.1 and the path the straight X-C
    /// pieces that replace it trace on the part (vcnc's choice: FANUC and Syntec interpolate in
    /// their servo cycle and give no such number).
    #[serde(default = "default_polar_interpolation_tolerance")]
    pub polar_interpolation_tolerance: f64,
    /// Which high-speed and smoothing codes the control has (they change the timing, within a
    /// tolerance the path).
    #[serde(default)]
    pub smoothing_codes: SmoothingCodes,
    /// Power-on modal state.
    pub power_on: PowerOn,
    /// What a SINUMERIK machine's data decide (the SINUMERIK profiles only).
    #[serde(default)]
    pub sinumerik: Option<SinumerikSettings>,
}

fn default_macro_call_depth() -> u32 {
    4
}

fn default_call_depth() -> u32 {
    10
}

fn default_loop_numbers() -> u32 {
    3
}

fn default_peck_distance() -> f64 {
    1.0
}

fn default_polar_interpolation_tolerance() -> f64 {
    0.001
}

fn default_true() -> bool {
    true
}

fn default_cutter_comp_look_ahead() -> u32 {
    2
}

fn default_m_codes_per_block() -> u32 {
    3
}

fn default_max_word_value() -> f64 {
    // Nine digits before the point: FANUC's widest input format.
    999_999_999.0
}

impl Profile {
    /// A built-in profile.
    pub fn builtin(name: ProfileName) -> Profile {
        // The embedded profiles are tested to parse (tests below), so this cannot fail at run time.
        toml::from_str(name.toml())
            .expect("embedded profile TOML is valid (checked by the profile tests)")
    }

    /// A built-in profile with fields replaced by those in `overrides` (a TOML table).
    ///
    /// # Errors
    /// When `overrides` names a field the profile does not have, or gives it a value of the wrong type.
    pub fn with_overrides(
        name: ProfileName,
        overrides: &toml::Table,
    ) -> Result<Profile, toml::de::Error> {
        // Every run opens a machine, most without overrides: the profile is then read once,
        // not read, merged, written out and read again (half the start-up's work).
        if overrides.is_empty() {
            return Ok(Profile::builtin(name));
        }
        let mut base: toml::Table = toml::from_str(name.toml())
            .expect("embedded profile TOML is valid (checked by the profile tests)");
        for (key, value) in overrides {
            base.insert(key.clone(), value.clone());
        }
        toml::Value::Table(base).try_into()
    }

    /// Checks that every number of the profile is one a control could have, for a profile
    /// changed by a machine file's `[profile_overrides]`.
    ///
    /// # Errors
    /// A sentence naming the first field out of range, its value and the range allowed.
    pub fn check_ranges(&self) -> Result<(), String> {
        use Lower::{Above, AtLeast};
        let key = |name: &str| format!("profile_overrides.{name}");
        for (name, value, lower, upper) in [
            ("increment_mm", self.increment_mm, Above(0.0), 1.0),
            ("increment_inch", self.increment_inch, Above(0.0), 0.1),
            ("increment_deg", self.increment_deg, Above(0.0), 1.0),
            ("peck_retract", self.peck_retract, AtLeast(0.0), 1000.0),
            ("peck_clearance", self.peck_clearance, AtLeast(0.0), 1000.0),
            ("max_word_value", self.max_word_value, AtLeast(1.0), 1e15),
            (
                "arc_radius_tolerance",
                self.arc_radius_tolerance,
                Above(0.0),
                100.0,
            ),
            (
                "polar_interpolation_tolerance",
                self.polar_interpolation_tolerance,
                Above(0.0),
                10.0,
            ),
        ] {
            check_range(&key(name), value, lower, upper)?;
        }
        if let Some(feed) = self.default_feed {
            check_range(&key("default_feed"), feed, Above(0.0), 1e6)?;
        }
        for (name, value, low, high) in [
            ("g54_1_count", self.g54_1_count, 0, 300),
            ("g10_work_l", self.g10_work_l, 0, 99),
            ("g10_extended_work_l", self.g10_extended_work_l, 0, 99),
            (
                "cutter_comp_look_ahead",
                self.cutter_comp_look_ahead,
                1,
                100,
            ),
            ("m_codes_per_block", self.m_codes_per_block, 1, 16),
            ("max_offset_number", self.max_offset_number, 1, 9999),
            ("reference_points", self.reference_points, 1, 10),
            ("macro_call_depth", self.macro_call_depth, 1, 100),
            ("call_depth", self.call_depth, 1, 100),
            ("loop_numbers", self.loop_numbers, 1, 999),
        ] {
            check_range(
                &key(name),
                f64::from(value),
                AtLeast(f64::from(low)),
                f64::from(high),
            )?;
        }
        for &code in &self.subprogram_m_codes {
            check_range(
                &key("subprogram_m_codes"),
                f64::from(code),
                AtLeast(0.0),
                9999.0,
            )?;
        }
        if let Some((low, high)) = self.extended_common_variables {
            if low > high {
                return Err(format!(
                    "{} = [{low}, {high}]: expected the first number at most the second",
                    key("extended_common_variables")
                ));
            }
        }
        Ok(())
    }

    /// The character-level options of the ISO front end.
    pub fn syntax(&self) -> SyntaxOptions {
        SyntaxOptions {
            semicolon_ends_block: self.semicolon_ends_block,
            slash_slash_comments: self.slash_slash_comments,
            colon_program_number: self.colon_program_number,
        }
    }
}

/// The lower end of an allowed range.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Lower {
    /// The value must be above this (a rate or a tolerance of zero would make nothing move).
    Above(f64),
    /// The value may be this or more.
    AtLeast(f64),
}

/// `key = value` of a settings file must lie in the range `lower` to `upper` (an upper end of
/// infinity takes `inf` too); the error names the key, the value and the range.
pub(crate) fn check_range(key: &str, value: f64, lower: Lower, upper: f64) -> Result<(), String> {
    let (low_ok, low_text) = match lower {
        Lower::Above(low) => (value > low, format!("more than {low}")),
        Lower::AtLeast(low) => (value >= low, format!("{low} or more")),
    };
    let high_ok = value <= upper && (value.is_finite() || upper == f64::INFINITY);
    if low_ok && high_ok {
        return Ok(());
    }
    let range = if upper == f64::INFINITY {
        format!("{low_text} (inf for no limit)")
    } else {
        format!("{low_text}, up to {upper}")
    };
    // Huge values in exponent form, not as three hundred digits.
    let shown = if value.abs() >= 1e15 {
        format!("{value:e}")
    } else {
        value.to_string()
    };
    Err(format!("{key} = {shown}: expected {range}"))
}

impl Default for Profile {
    fn default() -> Profile {
        Profile::builtin(ProfileName::Fanuc)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_builtin_profile_parses_and_names_itself() {
        for name in ProfileName::ALL {
            let profile = Profile::builtin(name);
            assert_eq!(profile.name, name);
        }
    }

    #[test]
    fn overrides_replace_single_fields() {
        let overrides: toml::Table = toml::from_str("rapid_path = \"per_axis\"").unwrap();
        let profile = Profile::with_overrides(ProfileName::Syntec, &overrides).unwrap();
        assert_eq!(profile.rapid_path, RapidPath::PerAxis);
        assert!(profile.slash_slash_comments);
    }

    #[test]
    fn every_builtin_profile_is_in_range() {
        for name in ProfileName::ALL {
            assert_eq!(Profile::builtin(name).check_ranges(), Ok(()), "{name}");
        }
    }

    #[test]
    fn an_override_out_of_range_names_the_key_the_value_and_the_range() {
        let overrides: toml::Table = toml::from_str("increment_mm = -0.001").unwrap();
        let profile = Profile::with_overrides(ProfileName::Fanuc, &overrides).unwrap();
        assert_eq!(
            profile.check_ranges(),
            Err("profile_overrides.increment_mm = -0.001: expected more than 0, up to 1".into())
        );
        let overrides: toml::Table = toml::from_str("loop_numbers = 0").unwrap();
        let profile = Profile::with_overrides(ProfileName::Fanuc, &overrides).unwrap();
        assert_eq!(
            profile.check_ranges(),
            Err("profile_overrides.loop_numbers = 0: expected 1 or more, up to 999".into())
        );
    }

    #[test]
    fn unknown_override_fields_are_rejected() {
        let overrides: toml::Table = toml::from_str("no_such_field = 1").unwrap();
        assert!(Profile::with_overrides(ProfileName::Fanuc, &overrides).is_err());
    }
}
