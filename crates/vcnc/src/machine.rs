//! The machine: axes, reference points, offsets and the controller profile, from a TOML file.
//!
//! [`Machine::default`] is the embedded generic 3-axis vertical machining centre
//! (`default_machine.toml`), so every command works with no file at all. A machine file names
//! its controller profile and may override any profile field, in the profile's own tables
//! (`[profile_overrides.motion]`, ...: see [`Profile::with_overrides`]).

pub use crate::axis::{Axis, AXES};
use crate::plan::{PlannerConfig, PlannerFile};
use crate::profile::{check_range, Lower, Profile, ProfileName};
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

/// One cutting edge of a tool in the tool table of a SINUMERIK machine (`[[tools]]`): the tool
/// is named by its number T and, optionally, by a name (`T="PF60"`); D is its edge (offset)
/// number, 1 to 12 on the control.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ToolEdge {
    /// The tool number (T).
    pub t: u32,
    /// The tool's name, if programs select it by name.
    #[serde(default)]
    pub name: Option<String>,
    /// The edge number (D), 1 when not given.
    #[serde(default = "first_edge")]
    pub d: u32,
    /// The tool type ($TC_DP1): 100-199 milling, 200-299 drills; 120 (end mill) when not given.
    #[serde(default = "end_mill", rename = "type")]
    pub tool_type: u32,
    /// Length 1 (along the tool axis), mm.
    #[serde(default)]
    pub length: f64,
    /// Lengths 2 and 3 (along the plane's other axes), mm.
    #[serde(default)]
    pub length2: f64,
    /// Length 3, mm.
    #[serde(default)]
    pub length3: f64,
    /// The edge radius, mm.
    #[serde(default)]
    pub radius: f64,
    /// The number of teeth ($TC_DPNT), for a feed per tooth (FZ).
    #[serde(default)]
    pub teeth: Option<u32>,
}

fn first_edge() -> u32 {
    1
}

fn end_mill() -> u32 {
    120
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
    /// How many spindles the machine has (1 to 5), numbered from 1 (the master spindle, which
    /// S and M3 address); SINUMERIK programs address the others as `S2=`, `M2=3`, `SPOS[2]=`.
    #[serde(default = "one_spindle")]
    pub count: u32,
}

fn one_spindle() -> u32 {
    1
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
    #[serde(default)]
    tools: Vec<ToolEdge>,
    #[serde(default)]
    tool_shapes: Vec<crate::tool_geometry::ToolShapeEntry>,
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
    /// SINUMERIK's settable frames beyond G54..G57: G500 (0, zero unless set) and G505..G599
    /// (5..99), `$P_UIFR[n]`.
    Settable(u32),
}

impl WorkOffsetId {
    /// Reads a key of the `[work_offsets]` table: `external`, `G54`, `G59.3`, `G54.1 P7`.
    pub fn parse(key: &str) -> Option<WorkOffsetId> {
        let key = key.trim().to_ascii_uppercase();
        if key == "EXTERNAL" || key == "EXT" {
            return Some(WorkOffsetId::External);
        }
        if let Some(n) = key
            .strip_prefix("G5")
            .filter(|n| n.len() == 2)
            .and_then(|n| n.parse::<u32>().ok())
            .filter(|&n| n == 0 || (5..=99).contains(&n))
        {
            return Some(WorkOffsetId::Settable(n));
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
            WorkOffsetId::Settable(n) => format!("G5{n:02}"),
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
    /// The tool table of a SINUMERIK machine: tools by number and name, with their edges.
    pub tools: Vec<ToolEdge>,
    /// The tools' shapes (`[[tool_shapes]]`), by tool number: what a tool change carries.
    pub tool_shapes: crate::tool_geometry::ToolShapes,
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
        profile.check_ranges().map_err(MachineError::Invalid)?;
        file.check_ranges(&profile).map_err(MachineError::Invalid)?;
        let mut axes: [Option<AxisConfig>; AXES] = Default::default();
        for (letter, config) in file.axes {
            let axis = single_letter(&letter)
                .and_then(Axis::from_letter)
                .ok_or_else(|| {
                    MachineError::Invalid(format!("unknown axis `{letter}` (expected x y z a b c)"))
                })?;
            if config.min > config.max {
                return Err(MachineError::Invalid(format!(
                    "axes.{letter}: min = {} is above max = {}",
                    config.min, config.max
                )));
            }
            axes[axis.index()] = Some(config);
        }
        let count = profile.coordinates.reference_points.max(1) as usize;
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
            tools: file.tools,
            tool_shapes: crate::tool_geometry::ToolShapes::from_entries(file.tool_shapes)
                .map_err(MachineError::Invalid)?,
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
        self.profile.check_ranges().map_err(MachineError::Invalid)?;
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

/// The largest coordinate or offset a machine file may give, mm: a kilometre, far past any
/// machine, and small enough that sums and squares of positions stay exact enough.
const MAX_POSITION: f64 = 1e6;

/// The fastest rate a machine file may give, mm/min (or deg/min).
const MAX_RATE: f64 = 1e7;

impl MachineFile {
    /// Every number of the file is one a machine could have: rates and limits positive (so that
    /// the planner never divides by zero or meets a NaN; jerk may be `inf`, no limit), positions
    /// and offsets finite, offset numbers among the profile's.
    fn check_ranges(&self, profile: &Profile) -> Result<(), String> {
        use Lower::{Above, AtLeast};
        let position =
            |key: &str, value: f64| check_range(key, value, AtLeast(-MAX_POSITION), MAX_POSITION);
        for (letter, axis) in &self.axes {
            let key = |name: &str| format!("axes.{letter}.{name}");
            position(&key("min"), axis.min)?;
            position(&key("max"), axis.max)?;
            check_range(&key("rapid"), axis.rapid, Above(0.0), MAX_RATE)?;
            check_range(&key("max_feed"), axis.max_feed, Above(0.0), MAX_RATE)?;
            check_range(&key("acceleration"), axis.acceleration, Above(0.0), 1e6)?;
            check_range(&key("jerk"), axis.jerk, Above(0.0), f64::INFINITY)?;
        }
        let tables = [("start".to_string(), &self.start)]
            .into_iter()
            .chain(
                self.reference_points
                    .iter()
                    .map(|(k, v)| (format!("reference_points.{k}"), v)),
            )
            .chain(
                self.work_offsets
                    .iter()
                    .map(|(k, v)| (format!("work_offsets.{k}"), v)),
            );
        for (table, values) in tables {
            for (letter, value) in ["x", "y", "z", "a", "b", "c"].iter().zip(values.to_array()) {
                position(&format!("{table}.{letter}"), value)?;
            }
        }
        for tool in &self.tool_offsets {
            let number = tool.number;
            let key = |name: &str| format!("tool_offsets (number {number}).{name}");
            let most = f64::from(profile.compensation.max_offset_number);
            check_range(&key("number"), f64::from(number), AtLeast(1.0), most)?;
            position(&key("length"), tool.length)?;
            position(&key("length_wear"), tool.length_wear)?;
            position(&key("radius"), tool.radius)?;
            position(&key("radius_wear"), tool.radius_wear)?;
        }
        check_range("spindle.max_rpm", self.spindle.max_rpm, Above(0.0), 1e6)?;
        // A channel has at most five spindles (PGsl 6.1, L1845).
        check_range(
            "spindle.count",
            f64::from(self.spindle.count),
            AtLeast(1.0),
            5.0,
        )
    }
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
    fn every_number_of_the_machine_file_has_its_range_checked() {
        let cases = [
            (
                "max_rpm = 12000.0",
                "max_rpm = -5",
                "spindle.max_rpm = -5: expected more than 0, up to 1000000",
            ),
            (
                "rapid = 24000.0",
                "rapid = 0",
                "axes.z.rapid = 0: expected more than 0, up to 10000000",
            ),
            (
                "jerk = 50000.0\n\n[axes.y]",
                "jerk = -1\n\n[axes.y]",
                "axes.x.jerk = -1: expected more than 0 (inf for no limit)",
            ),
            (
                "min = -1000.0",
                "min = nan",
                "axes.x.min = NaN: expected -1000000 or more, up to 1000000",
            ),
            (
                "1 = { x = 0.0,",
                "1 = { x = 1e300,",
                "reference_points.1.x = 1e300: expected -1000000 or more, up to 1000000",
            ),
            (
                "number = 1\n",
                "number = 0\n",
                "tool_offsets (number 0).number = 0: expected 1 or more, up to 400",
            ),
        ];
        for (from, to, expected) in cases {
            assert!(DEFAULT_MACHINE_TOML.contains(from), "{from}");
            let text = DEFAULT_MACHINE_TOML.replacen(from, to, 1);
            let error = Machine::from_toml(&text).unwrap_err().to_string();
            assert_eq!(error, format!("machine file: {expected}"));
        }
        let text = format!(
            "{DEFAULT_MACHINE_TOML}\n[profile_overrides.compensation]\nmax_offset_number = 0\n"
        );
        let error = Machine::from_toml(&text).unwrap_err().to_string();
        assert!(
            error.contains("profile_overrides.compensation.max_offset_number = 0"),
            "{error}"
        );
    }

    #[test]
    fn profile_overrides_go_in_the_profiles_tables() {
        let text = format!(
            "{DEFAULT_MACHINE_TOML}\n[profile_overrides.motion]\nrapid_path = \"per_axis\"\n"
        );
        let machine = Machine::from_toml(&text).unwrap();
        assert_eq!(
            machine.profile.motion.rapid_path,
            crate::profile::RapidPath::PerAxis
        );
        // The machine keeps its overrides under another profile.
        let machine = machine.with_profile(ProfileName::Syntec).unwrap();
        assert_eq!(
            machine.profile.motion.rapid_path,
            crate::profile::RapidPath::PerAxis
        );
        assert_eq!(machine.profile.motion.default_feed, Some(1000.0));
        // The flat form of older machine files is refused with the table to write it in.
        let text =
            format!("{DEFAULT_MACHINE_TOML}\n[profile_overrides]\nrapid_path = \"per_axis\"\n");
        let error = Machine::from_toml(&text).unwrap_err().to_string();
        assert!(
            error.contains("write `rapid_path = ...` under [profile_overrides.motion]"),
            "{error}"
        );
    }

    #[test]
    fn a_bad_axis_letter_is_reported() {
        let text = DEFAULT_MACHINE_TOML.replace("[axes.z]", "[axes.q]");
        let error = Machine::from_toml(&text).unwrap_err().to_string();
        assert!(error.contains("unknown axis `q`"), "{error}");
    }
}
