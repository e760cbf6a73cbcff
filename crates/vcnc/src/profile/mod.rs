//! Controller profiles: what differs between the controls vcnc imitates, as data.
//!
//! A [`Profile`] holds the parameters and rules in which the FANUC-family controls differ:
//! how numbers without a decimal point are read, which extended work offsets exist, what G10's
//! L numbers mean, the dwell rules, the power-on modal state. Code asks the profile a question;
//! it never asks which controller it is. The rules are grouped by concern, one type and one
//! file each: [`ReadingRules`] (`reading.rs`), [`UnitRules`] (`units.rs`), [`CoordinateRules`]
//! (`coordinates.rs`), [`CompensationRules`] (`compensation.rs`), [`DwellRules`] (`dwell.rs`),
//! [`CycleRules`] (`cycles.rs`), [`MotionRules`] (`motion.rs`), [`SubprogramRules`]
//! (`subprograms.rs`), [`MacroRules`] (`macros.rs`), then [`PowerOn`] and the SINUMERIK machine
//! data ([`SinumerikSettings`], `sinumerik.rs`). The built-in profiles are TOML files embedded
//! in the library (`profile/*.toml`), one table per group; a machine file can override any
//! field under `[profile_overrides.<group>]`.

mod codes;
mod compensation;
mod coordinates;
mod cycles;
mod dwell;
mod macros;
mod motion;
mod reading;
mod sinumerik;
mod subprograms;
mod units;

pub use codes::{
    classify_g, classify_m, g_name, not_supported_description, supported_codes_markdown, CycleKind,
    GCode, GLookup, Group, MCode, MLookup, PatternKind,
};

pub use compensation::{CompensationRules, CornerOverride, ToolOffsetField, ToolOffsetL};
pub use coordinates::{CoordinateRules, PolarIncrements, ScalingAxes};
pub use cycles::{CycleRules, ShiftDirection};
pub use dwell::{DwellP, DwellRules};
pub use macros::{MacroArguments, MacroRules, ToolOffsetVariables};
pub use motion::{MotionRules, RapidPath, RotaryRollover, SmoothingCodes};
pub use reading::{ReadingRules, SameGroupRule};
pub use sinumerik::{SinumerikSettings, Variant};
pub use subprograms::SubprogramRules;
pub use units::{DecimalLess, UnitRules};

use crate::syntax::iso::SyntaxOptions;
use serde::{Deserialize, Serialize};
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

/// Everything about a controller that the interpreter asks, grouped by concern: each group is a
/// table of the profile's TOML (`[reading]`, `[units]`, ...) and a type with its own docs, and
/// each field lives in exactly one group (docs/PROFILES.md lists them).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Profile {
    /// Which built-in profile this is (or started from).
    pub name: ProfileName,
    /// One line for people.
    pub description: String,
    /// How the text becomes blocks and words.
    pub reading: ReadingRules,
    /// How numbers become lengths and angles.
    pub units: UnitRules,
    /// Work offsets, G10 for them, G92.1, and the reference points.
    pub coordinates: CoordinateRules,
    /// Tool offsets and the compensations that read them.
    pub compensation: CompensationRules,
    /// How dwell times are written (G04, and the P of canned cycles).
    pub dwell: DwellRules,
    /// The canned cycles' parameters.
    pub cycles: CycleRules,
    /// The path of each kind of move.
    pub motion: MotionRules,
    /// Subprogram calls and returns.
    pub subprograms: SubprogramRules,
    /// Macro calls, loops and system variables.
    pub macros: MacroRules,
    /// Power-on modal state.
    pub power_on: PowerOn,
    /// What a SINUMERIK machine's data decide (the SINUMERIK profiles only).
    #[serde(default)]
    pub sinumerik: Option<SinumerikSettings>,
}

/// The tables of [`Profile`] that group its ISO rules, as the TOML names them: the tables a
/// machine file's `[profile_overrides]` once held as flat keys.
const GROUPS: [&str; 9] = [
    "reading",
    "units",
    "coordinates",
    "compensation",
    "dwell",
    "cycles",
    "motion",
    "subprograms",
    "macros",
];

pub(crate) fn default_true() -> bool {
    true
}

impl Profile {
    /// A built-in profile.
    pub fn builtin(name: ProfileName) -> Profile {
        // The embedded profiles are tested to parse (tests below), so this cannot fail at run time.
        toml::from_str(name.toml())
            .expect("embedded profile TOML is valid (checked by the profile tests)")
    }

    /// A built-in profile with fields replaced by those in `overrides` (a TOML table of the
    /// profile's tables: `[profile_overrides.motion]` in a machine file gives `motion`'s fields).
    /// Tables merge field by field; any other value replaces the profile's.
    ///
    /// # Errors
    /// When `overrides` names a field the profile does not have, gives it a value of the wrong
    /// type, or names a field of a group outside its table (the flat form of machine files
    /// before the profile was grouped: the error names the table it belongs in).
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
            if let Some(group) = group_of_flat_key(key) {
                return Err(serde::de::Error::custom(format!(
                    "profile_overrides.{key}: the profile's fields are grouped by concern; \
                     write `{key} = ...` under [profile_overrides.{group}]"
                )));
            }
            merge(&mut base, key, value);
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
            (
                "units.increment_mm",
                self.units.increment_mm,
                Above(0.0),
                1.0,
            ),
            (
                "units.increment_inch",
                self.units.increment_inch,
                Above(0.0),
                0.1,
            ),
            (
                "units.increment_deg",
                self.units.increment_deg,
                Above(0.0),
                1.0,
            ),
            (
                "cycles.peck_retract",
                self.cycles.peck_retract,
                AtLeast(0.0),
                1000.0,
            ),
            (
                "cycles.peck_clearance",
                self.cycles.peck_clearance,
                AtLeast(0.0),
                1000.0,
            ),
            (
                "reading.max_word_value",
                self.reading.max_word_value,
                AtLeast(1.0),
                1e15,
            ),
            (
                "motion.arc_radius_tolerance",
                self.motion.arc_radius_tolerance,
                Above(0.0),
                100.0,
            ),
            (
                "motion.polar_interpolation_tolerance",
                self.motion.polar_interpolation_tolerance,
                Above(0.0),
                10.0,
            ),
        ] {
            check_range(&key(name), value, lower, upper)?;
        }
        if let Some(corner) = &self.compensation.corner_override {
            for (name, value, lower, upper) in [
                ("inner_angle", corner.inner_angle, AtLeast(2.0), 178.0),
                (
                    "override_percent",
                    corner.override_percent,
                    Above(0.0),
                    100.0,
                ),
                ("before_corner", corner.before_corner, AtLeast(0.0), 1000.0),
                ("after_corner", corner.after_corner, AtLeast(0.0), 1000.0),
                (
                    "inner_arc_min_percent",
                    corner.inner_arc_min_percent,
                    AtLeast(0.0),
                    100.0,
                ),
            ] {
                check_range(
                    &key(&format!("compensation.corner_override.{name}")),
                    value,
                    lower,
                    upper,
                )?;
            }
        }
        if let Some(feed) = self.motion.default_feed {
            check_range(&key("motion.default_feed"), feed, Above(0.0), 1e6)?;
        }
        let coordinates = &self.coordinates;
        for (name, value, low, high) in [
            ("coordinates.g54_1_count", coordinates.g54_1_count, 0, 300),
            ("coordinates.g10_work_l", coordinates.g10_work_l, 0, 99),
            (
                "coordinates.g10_extended_work_l",
                coordinates.g10_extended_work_l,
                0,
                99,
            ),
            (
                "coordinates.reference_points",
                coordinates.reference_points,
                1,
                10,
            ),
            (
                "compensation.cutter_comp_look_ahead",
                self.compensation.cutter_comp_look_ahead,
                1,
                100,
            ),
            (
                "compensation.max_offset_number",
                self.compensation.max_offset_number,
                1,
                9999,
            ),
            (
                "reading.m_codes_per_block",
                self.reading.m_codes_per_block,
                1,
                16,
            ),
            (
                "macros.macro_call_depth",
                self.macros.macro_call_depth,
                1,
                100,
            ),
            (
                "subprograms.call_depth",
                self.subprograms.call_depth,
                1,
                100,
            ),
            ("macros.loop_numbers", self.macros.loop_numbers, 1, 999),
            (
                "macros.last_local_variable",
                self.macros.last_local_variable,
                33,
                400,
            ),
            (
                "macros.first_persistent_variable",
                self.macros.first_persistent_variable,
                401,
                500,
            ),
        ] {
            check_range(
                &key(name),
                f64::from(value),
                AtLeast(f64::from(low)),
                f64::from(high),
            )?;
        }
        for &code in &self.subprograms.subprogram_m_codes {
            check_range(
                &key("subprograms.subprogram_m_codes"),
                f64::from(code),
                AtLeast(0.0),
                9999.0,
            )?;
        }
        if let Some((low, high)) = self.macros.extended_common_variables {
            if low > high {
                return Err(format!(
                    "{} = [{low}, {high}]: expected the first number at most the second",
                    key("macros.extended_common_variables")
                ));
            }
        }
        Ok(())
    }

    /// The character-level options of the ISO front end.
    pub fn syntax(&self) -> SyntaxOptions {
        self.reading.syntax()
    }
}

/// Puts `value` at `key` of `table`: into the table there field by field when both are tables,
/// in its place otherwise.
fn merge(table: &mut toml::Table, key: &str, value: &toml::Value) {
    match (table.get_mut(key), value) {
        (Some(toml::Value::Table(base)), toml::Value::Table(fields)) => {
            for (field, value) in fields {
                merge(base, field, value);
            }
        }
        _ => {
            table.insert(key.to_string(), value.clone());
        }
    }
}

/// The group whose field `key` is, when `key` is not a key of the profile itself: a flat key
/// of a machine file written before the profile was grouped. Every built-in profile is looked
/// at as a whole (defaults filled in), so that a field one leaves unset (`None`) is found in
/// another.
fn group_of_flat_key(key: &str) -> Option<&'static str> {
    if GROUPS.contains(&key) {
        return None;
    }
    ProfileName::ALL.into_iter().find_map(|name| {
        let table = toml::Table::try_from(Profile::builtin(name)).ok()?;
        GROUPS.into_iter().find(|group| {
            table
                .get(*group)
                .and_then(toml::Value::as_table)
                .is_some_and(|fields| fields.contains_key(key))
        })
    })
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

    fn every_builtin() -> impl Iterator<Item = ProfileName> {
        ProfileName::ALL.into_iter().chain(ProfileName::SINUMERIK)
    }

    #[test]
    fn every_builtin_profile_parses_and_names_itself() {
        for name in every_builtin() {
            let profile = Profile::builtin(name);
            assert_eq!(profile.name, name);
        }
    }

    #[test]
    fn overrides_replace_single_fields_of_a_table() {
        let overrides: toml::Table =
            toml::from_str("[motion]\nrapid_path = \"per_axis\"\n[power_on]\nunits = 200").unwrap();
        let profile = Profile::with_overrides(ProfileName::Syntec, &overrides).unwrap();
        assert_eq!(profile.motion.rapid_path, RapidPath::PerAxis);
        // The other fields of the tables named stay the profile's.
        assert_eq!(profile.motion.default_feed, Some(1000.0));
        assert_eq!(profile.power_on.units, 200);
        assert_eq!(profile.power_on.plane, 170);
        assert!(profile.reading.slash_slash_comments);
    }

    #[test]
    fn a_flat_key_of_a_group_is_refused_with_the_table_it_belongs_in() {
        // Every group field, including those left at their defaults or unset in some profiles.
        for (key, group) in [
            ("rapid_path", "motion"),
            ("decimal_less", "units"),
            ("boring_shift", "cycles"),
            ("loop_numbers", "macros"),
            ("extended_common_variables", "macros"),
            ("g10_tool_default", "compensation"),
            ("cycle_dwell_p", "dwell"),
            ("max_word_value", "reading"),
            ("call_depth", "subprograms"),
            ("g54_1_count", "coordinates"),
        ] {
            let overrides: toml::Table = toml::from_str(&format!("{key} = 1")).unwrap();
            let error = Profile::with_overrides(ProfileName::Fanuc, &overrides)
                .unwrap_err()
                .to_string();
            assert!(
                error.contains(&format!("under [profile_overrides.{group}]")),
                "{key}: {error}"
            );
        }
    }

    #[test]
    fn every_field_lives_in_one_group() {
        let mut seen = std::collections::BTreeMap::new();
        for name in every_builtin() {
            let table = toml::Table::try_from(Profile::builtin(name)).unwrap();
            for group in GROUPS {
                for key in table[group].as_table().unwrap().keys() {
                    let first = seen.entry(key.clone()).or_insert(group);
                    assert_eq!(*first, group, "{key}");
                }
            }
        }
        // Every field but name, description, power_on and sinumerik: each is set or has a
        // default in some profile, so the flat-key error finds them all.
        assert_eq!(seen.len(), 84);
    }

    #[test]
    fn docs_profiles_names_every_field_in_its_table() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/PROFILES.md");
        let docs = std::fs::read_to_string(path).unwrap();
        let table = toml::Table::try_from(Profile::builtin(ProfileName::Haas)).unwrap();
        for group in GROUPS {
            let start = docs.find(&format!("\n`[{group}]` —")).expect(group);
            let section = &docs[start + 1..];
            let section = &section[..section.find("\n`[").unwrap_or(section.len())];
            for key in table[group].as_table().unwrap().keys() {
                assert!(section.contains(&format!("`{key}`")), "{group}.{key}");
            }
        }
    }

    #[test]
    fn every_builtin_profile_is_in_range() {
        for name in every_builtin() {
            assert_eq!(Profile::builtin(name).check_ranges(), Ok(()), "{name}");
        }
    }

    #[test]
    fn an_override_out_of_range_names_the_key_the_value_and_the_range() {
        let overrides: toml::Table = toml::from_str("units.increment_mm = -0.001").unwrap();
        let profile = Profile::with_overrides(ProfileName::Fanuc, &overrides).unwrap();
        assert_eq!(
            profile.check_ranges(),
            Err(
                "profile_overrides.units.increment_mm = -0.001: expected more than 0, up to 1"
                    .into()
            )
        );
        let overrides: toml::Table = toml::from_str("macros.loop_numbers = 0").unwrap();
        let profile = Profile::with_overrides(ProfileName::Fanuc, &overrides).unwrap();
        assert_eq!(
            profile.check_ranges(),
            Err("profile_overrides.macros.loop_numbers = 0: expected 1 or more, up to 999".into())
        );
    }

    #[test]
    fn unknown_override_fields_are_rejected() {
        for text in ["no_such_field = 1", "[motion]\nno_such_field = 1"] {
            let overrides: toml::Table = toml::from_str(text).unwrap();
            assert!(Profile::with_overrides(ProfileName::Fanuc, &overrides).is_err());
        }
    }
}
