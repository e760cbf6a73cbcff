//! The machine: axes, reference points, offsets and the controller profile, from a TOML file.
//!
//! [`Machine::default`] is the embedded generic 3-axis vertical machining centre
//! (`default_machine.toml`), so every command works with no file at all. A machine file names
//! its controller profile and may override any profile field.

pub use crate::axis::{Axis, AXES};
use crate::plan::{PlannerConfig, PlannerFile};
use crate::profile::{Profile, ProfileName};
use serde::Deserialize;
use std::collections::BTreeMap;

/// The embedded default machine file, as text (`vcnc machine` prints it).
pub const DEFAULT_MACHINE_TOML: &str = include_str!("default_machine.toml");

/// Limits and rates of one axis.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AxisConfig {
    /// Lower travel limit, machine coordinates.
    pub min: f64,
    /// Upper travel limit, machine coordinates.
    pub max: f64,
    /// Rapid rate, mm/min (deg/min).
    pub rapid: f64,
    /// Highest cutting feed, mm/min.
    pub max_feed: f64,
    /// Acceleration limit, mm/s^2.
    #[serde(default = "default_acceleration")]
    pub acceleration: f64,
    /// Jerk limit, mm/s^3.
    #[serde(default = "default_jerk")]
    pub jerk: f64,
}

fn default_acceleration() -> f64 {
    1000.0
}

fn default_jerk() -> f64 {
    f64::INFINITY
}

/// One entry of the tool offset memory.
#[derive(Clone, Debug, PartialEq, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ToolOffset {
    /// The H/D number.
    pub number: u32,
    /// Length geometry, mm.
    #[serde(default)]
    pub length: f64,
    /// Length wear, mm.
    #[serde(default)]
    pub length_wear: f64,
    /// Radius geometry, mm (a diameter on profiles that keep diameters).
    #[serde(default)]
    pub radius: f64,
    /// Radius wear, mm.
    #[serde(default)]
    pub radius_wear: f64,
}

/// A position given per axis letter in a machine file; missing axes are zero.
#[derive(Clone, Debug, PartialEq, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AxisValues {
    /// X.
    #[serde(default)]
    pub x: f64,
    /// Y.
    #[serde(default)]
    pub y: f64,
    /// Z.
    #[serde(default)]
    pub z: f64,
    /// A.
    #[serde(default)]
    pub a: f64,
    /// B.
    #[serde(default)]
    pub b: f64,
    /// C.
    #[serde(default)]
    pub c: f64,
}

impl AxisValues {
    /// As a position array.
    pub fn to_array(&self) -> [f64; AXES] {
        [self.x, self.y, self.z, self.a, self.b, self.c]
    }
}

/// The spindle.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpindleConfig {
    /// Highest speed, rpm.
    pub max_rpm: f64,
}

/// The machine file as written.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MachineFile {
    name: String,
    #[serde(default)]
    profile: ProfileName,
    #[serde(default)]
    profile_overrides: toml::Table,
    axes: BTreeMap<String, AxisConfig>,
    #[serde(default)]
    start: AxisValues,
    #[serde(default)]
    reference_points: BTreeMap<String, AxisValues>,
    #[serde(default)]
    work_offsets: BTreeMap<String, AxisValues>,
    #[serde(default)]
    tool_offsets: Vec<ToolOffset>,
    spindle: SpindleConfig,
    #[serde(default)]
    planner: PlannerFile,
}

/// Why a machine file was rejected.
#[derive(Debug, thiserror::Error)]
pub enum MachineError {
    /// Not valid TOML, or a field of the wrong type or name.
    #[error("machine file: {0}")]
    Toml(#[from] toml::de::Error),
    /// Valid TOML that does not describe a machine.
    #[error("machine file: {0}")]
    Invalid(String),
}

/// A work offset register: the 6 standard ones, the external one, and the extended ones.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum WorkOffsetId {
    /// The external (common) offset added to every work coordinate system (G10 L2 P0).
    External,
    /// G54 (1) ... G59 (6), Syntec G59.1 ... G59.9 (7 ... 15).
    Standard(u8),
    /// G54.1 Pn.
    Extended(u32),
}

impl WorkOffsetId {
    /// Reads a key of the `[work_offsets]` table: `external`, `G54`, `G59.3`, `G54.1 P7`.
    pub fn parse(key: &str) -> Option<WorkOffsetId> {
        let key = key.trim().to_ascii_uppercase();
        if key == "EXTERNAL" || key == "EXT" {
            return Some(WorkOffsetId::External);
        }
        if let Some(rest) = key.strip_prefix("G54.1") {
            let number = rest.trim().strip_prefix('P')?.trim().parse().ok()?;
            return Some(WorkOffsetId::Extended(number));
        }
        if let Some(rest) = key.strip_prefix("G59.") {
            let n: u8 = rest.parse().ok()?;
            return (1..=9)
                .contains(&n)
                .then_some(WorkOffsetId::Standard(6 + n));
        }
        let n: u8 = key.strip_prefix('G')?.parse().ok()?;
        (54..=59)
            .contains(&n)
            .then_some(WorkOffsetId::Standard(n - 53))
    }

    /// The G code that selects it, for people.
    pub fn name(self) -> String {
        match self {
            WorkOffsetId::External => "external".to_string(),
            WorkOffsetId::Standard(n @ 1..=6) => format!("G{}", 53 + n),
            WorkOffsetId::Standard(n) => format!("G59.{}", n - 6),
            WorkOffsetId::Extended(p) => format!("G54.1 P{p}"),
        }
    }
}

/// A machine: what the interpreter needs to know about the hardware and its control.
#[derive(Clone, Debug)]
pub struct Machine {
    /// A name for reports.
    pub name: String,
    /// The controller profile (built-in plus overrides).
    pub profile: Profile,
    /// Configured axes, by axis; `None` for axes the machine does not have.
    pub axes: [Option<AxisConfig>; AXES],
    /// Start position, machine coordinates.
    pub start: [f64; AXES],
    /// Reference points 1 (G28) to n (G30 Pn), machine coordinates.
    pub reference_points: Vec<[f64; AXES]>,
    /// Work offsets at the start of the run.
    pub work_offsets: BTreeMap<WorkOffsetId, [f64; AXES]>,
    /// Tool offset memory at the start of the run, by number.
    pub tool_offsets: BTreeMap<u32, ToolOffset>,
    /// The spindle.
    pub spindle: SpindleConfig,
    /// The planner's settings (`[planner]`): look-ahead, corners, event times.
    pub planner: PlannerConfig,
    profile_overrides: toml::Table,
}

impl Machine {
    /// Reads a machine file.
    ///
    /// # Errors
    /// [`MachineError`] when the text is not a valid machine file.
    pub fn from_toml(text: &str) -> Result<Machine, MachineError> {
        let file: MachineFile = toml::from_str(text)?;
        let profile = Profile::with_overrides(file.profile, &file.profile_overrides)?;
        let mut axes: [Option<AxisConfig>; AXES] = Default::default();
        for (letter, config) in file.axes {
            let axis = single_letter(&letter)
                .and_then(Axis::from_letter)
                .ok_or_else(|| {
                    MachineError::Invalid(format!("unknown axis `{letter}` (expected x y z a b c)"))
                })?;
            if config.min > config.max {
                return Err(MachineError::Invalid(format!(
                    "axis {letter}: min is above max"
                )));
            }
            check_rates(&letter, &config)?;
            axes[axis.index()] = Some(config);
        }
        let count = profile.reference_points.max(1) as usize;
        let mut reference_points = vec![[0.0; AXES]; count];
        for (key, values) in &file.reference_points {
            let n: usize = key
                .parse()
                .ok()
                .filter(|n| (1..=count).contains(n))
                .ok_or_else(|| {
                    MachineError::Invalid(format!("reference point `{key}`: expected 1 to {count}"))
                })?;
            reference_points[n - 1] = values.to_array();
        }
        let mut work_offsets = BTreeMap::new();
        for (key, values) in &file.work_offsets {
            let id = WorkOffsetId::parse(key).ok_or_else(|| {
                MachineError::Invalid(format!(
                    "work offset `{key}`: expected G54..G59, G54.1 Pn or external"
                ))
            })?;
            work_offsets.insert(id, values.to_array());
        }
        let tool_offsets = file
            .tool_offsets
            .into_iter()
            .map(|t| (t.number, t))
            .collect();
        let planner = file.planner.resolve().map_err(MachineError::Invalid)?;
        Ok(Machine {
            name: file.name,
            profile,
            axes,
            start: file.start.to_array(),
            reference_points,
            work_offsets,
            tool_offsets,
            spindle: file.spindle,
            planner,
            profile_overrides: file.profile_overrides,
        })
    }

    /// The same machine with another built-in profile (keeping the file's overrides).
    ///
    /// # Errors
    /// When the machine file's overrides do not fit the new profile.
    pub fn with_profile(mut self, name: ProfileName) -> Result<Machine, MachineError> {
        self.profile = Profile::with_overrides(name, &self.profile_overrides)?;
        Ok(self)
    }

    /// True when the machine has this axis.
    pub fn has_axis(&self, axis: Axis) -> bool {
        self.axes[axis.index()].is_some()
    }

    /// The offset of a work coordinate system (zero when not configured).
    pub fn work_offset(&self, id: WorkOffsetId) -> [f64; AXES] {
        self.work_offsets.get(&id).copied().unwrap_or([0.0; AXES])
    }
}

impl Default for Machine {
    fn default() -> Machine {
        // The embedded file is checked by a unit test, so this cannot fail at run time.
        Machine::from_toml(DEFAULT_MACHINE_TOML)
            .expect("the embedded default machine is valid (checked by tests)")
    }
}

/// Rates and limits must be positive numbers (jerk may be `inf`: no jerk limit), so that the
/// planner never divides by zero or meets a NaN.
fn check_rates(letter: &str, config: &AxisConfig) -> Result<(), MachineError> {
    for (name, value, infinite_ok) in [
        ("rapid", config.rapid, false),
        ("max_feed", config.max_feed, false),
        ("acceleration", config.acceleration, false),
        ("jerk", config.jerk, true),
    ] {
        let ok = value > 0.0 && (value.is_finite() || (infinite_ok && value == f64::INFINITY));
        if !ok {
            return Err(MachineError::Invalid(format!(
                "axis {letter}: {name} = {value}: expected a positive number"
            )));
        }
    }
    Ok(())
}

fn single_letter(text: &str) -> Option<u8> {
    match text.as_bytes() {
        [b] => Some(*b),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_machine_is_a_three_axis_fanuc_mill() {
        let machine = Machine::default();
        assert!(machine.has_axis(Axis::X) && machine.has_axis(Axis::Z));
        assert!(!machine.has_axis(Axis::A));
        assert_eq!(machine.profile.name, ProfileName::Fanuc);
        assert_eq!(machine.reference_points.len(), 4);
    }

    #[test]
    fn work_offset_keys_name_every_register() {
        assert_eq!(WorkOffsetId::parse("G54"), Some(WorkOffsetId::Standard(1)));
        assert_eq!(
            WorkOffsetId::parse("g59.9"),
            Some(WorkOffsetId::Standard(15))
        );
        assert_eq!(
            WorkOffsetId::parse("G54.1 P12"),
            Some(WorkOffsetId::Extended(12))
        );
        assert_eq!(
            WorkOffsetId::parse("external"),
            Some(WorkOffsetId::External)
        );
        assert_eq!(WorkOffsetId::parse("G60"), None);
    }

    #[test]
    fn the_default_machine_spells_out_the_default_planner() {
        let machine = Machine::default();
        // The file rounds sqrt(3)/2 to three places.
        let expected = PlannerConfig {
            normal_acceleration_share: 0.866,
            ..PlannerConfig::default()
        };
        assert_eq!(machine.planner, expected);
    }

    #[test]
    fn planner_habits_are_a_starting_point_that_fields_override() {
        let text = DEFAULT_MACHINE_TOML
            .replace("[planner]", "[planner]\nhabits = \"linuxcnc\"")
            .replace("look_ahead = 200\n", "")
            .replace("corner_tolerance = 0.02\n", "");
        let machine = Machine::from_toml(&text).unwrap();
        assert_eq!(machine.planner.look_ahead, 200);
        assert!(machine.planner.corner_tolerance.is_infinite());
        // Written in the file, so it wins over the preset's 0.5.
        assert_eq!(machine.planner.unblended_acceleration_factor, 1.0);
    }

    #[test]
    fn a_planner_value_out_of_range_is_reported() {
        let text = DEFAULT_MACHINE_TOML.replace("look_ahead = 200", "look_ahead = 1");
        let error = Machine::from_toml(&text).unwrap_err().to_string();
        assert!(error.contains("planner.look_ahead"), "{error}");
        let text = DEFAULT_MACHINE_TOML.replace("acceleration = 2000.0", "acceleration = 0.0");
        let error = Machine::from_toml(&text).unwrap_err().to_string();
        assert!(error.contains("acceleration"), "{error}");
    }

    #[test]
    fn a_bad_axis_letter_is_reported() {
        let text = DEFAULT_MACHINE_TOML.replace("[axes.z]", "[axes.q]");
        let error = Machine::from_toml(&text).unwrap_err().to_string();
        assert!(error.contains("unknown axis `q`"), "{error}");
    }
}
