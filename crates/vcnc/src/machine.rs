//! The machine: axes, reference points, offsets and the controller profile, from a TOML file.
//!
//! [`Machine::default`] is the embedded generic 3-axis vertical machining centre
//! (`default_machine.toml`), so every command works with no file at all. A machine file names
//! its controller profile and may override any profile field, in the profile's own tables
//! (`[profile_overrides.motion]`, ...: see [`Profile::with_overrides`]).

pub use crate::axis::{Axis, AxisKind, AxisLayout, AxisName, AXES};
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

/// A position given per axis name in a machine file (`{ x = 1.0, u = 2.0 }`); missing axes are
/// zero.
pub type AxisValues = BTreeMap<String, f64>;

/// The position array of `values`, by the names of `layout`.
fn position_array(
    table: &str,
    values: &AxisValues,
    layout: &AxisLayout,
    axes: &[Option<AxisConfig>; AXES],
) -> Result<[f64; AXES], MachineError> {
    let mut array = [0.0; AXES];
    for (name, value) in values {
        let axis = layout
            .by_name(name)
            .filter(|a| a.is_geometry() || axes[a.index()].is_some())
            .ok_or_else(|| {
                MachineError::Invalid(format!(
                    "{table}.{name}: the machine has no axis `{name}` (its axes are the tables under [axes])"
                ))
            })?;
        array[axis.index()] = *value;
    }
    Ok(array)
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
    /// Each axis's table: an [`AxisConfig`] and its `kind`, read apart (see [`read_axes`]).
    axes: BTreeMap<String, toml::Table>,
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
    #[serde(default)]
    kinematics: Option<crate::kinematics::KinematicsFile>,
    #[serde(default)]
    probe: crate::probe::ProbeConfig,
    #[serde(default)]
    stroke_check: crate::interp::StrokeCheckConfig,
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
    /// The axes' names and kinds, by slot (X Y Z and A B C unless the file names others).
    pub layout: AxisLayout,
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
    /// How the rotary axes carry the tool and the part (`[kinematics]`), on a 5-axis machine.
    pub kinematics: Option<crate::kinematics::Kinematics>,
    /// What a probe and the tool setter touch (`[probe]`).
    pub probe: crate::probe::ProbeConfig,
    /// The stored stroke check 2's parameters (`[stroke_check]`, G22).
    pub stroke_check: crate::interp::StrokeCheckConfig,
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
        let (axes, layout) = read_axes(&file.axes)?;
        file.check_ranges(&profile).map_err(MachineError::Invalid)?;
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
            let table = format!("reference_points.{key}");
            reference_points[n - 1] = position_array(&table, values, &layout, &axes)?;
        }
        let mut work_offsets = BTreeMap::new();
        for (key, values) in &file.work_offsets {
            let id = WorkOffsetId::parse(key).ok_or_else(|| {
                MachineError::Invalid(format!(
                    "work offset `{key}`: expected G54..G59, G54.1 Pn or external"
                ))
            })?;
            let table = format!("work_offsets.{key}");
            work_offsets.insert(id, position_array(&table, values, &layout, &axes)?);
        }
        let tool_offsets = file
            .tool_offsets
            .into_iter()
            .map(|t| (t.number, t))
            .collect();
        let planner = file.planner.resolve().map_err(MachineError::Invalid)?;
        let limits = |axis: Axis| axes[axis.index()].as_ref().map(|a| (a.min, a.max));
        let kinematics = file
            .kinematics
            .map(|k| k.resolve(&layout, limits))
            .transpose()
            .map_err(MachineError::Invalid)?;
        file.probe.check().map_err(MachineError::Invalid)?;
        Ok(Machine {
            name: file.name,
            profile,
            start: position_array("start", &file.start, &layout, &axes)?,
            axes,
            layout,
            reference_points,
            work_offsets,
            tool_offsets,
            tools: file.tools,
            tool_shapes: crate::tool_geometry::ToolShapes::from_entries(file.tool_shapes)
                .map_err(MachineError::Invalid)?,
            spindle: file.spindle,
            planner,
            kinematics,
            probe: file.probe,
            stroke_check: file.stroke_check,
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

    /// Adds an axis after X Y Z named `name` (`"U"`, `"C1"`), with the kind its name gives
    /// unless `kind` says otherwise, as a table `[axes.NAME]` of the machine file would: A, B
    /// and C take their own slots, other names the first free one. Returns its slot.
    ///
    /// # Errors
    /// A name that is no axis name, one the machine has already, or no free slot.
    pub fn add_axis(
        &mut self,
        name: &str,
        kind: Option<AxisKind>,
        config: AxisConfig,
    ) -> Result<Axis, MachineError> {
        let name = AxisName::new(name).ok_or_else(|| {
            MachineError::Invalid(format!(
                "`{name}` is no axis name (1 to 8 letters, digits or `_`, starting with a letter)"
            ))
        })?;
        if ["X", "Y", "Z"].contains(&name.as_str()) {
            return Err(MachineError::Invalid(format!(
                "{name} is a geometry axis; set `axes[{}]`",
                name.as_str()
            )));
        }
        check_axis(name.as_str(), &config).map_err(MachineError::Invalid)?;
        let mut axes = MachineAxes {
            axes: self.axes.clone(),
            layout: self.layout,
        };
        let axis = axes.add(name, kind, config)?;
        (self.axes, self.layout) = (axes.axes, axes.layout);
        Ok(axis)
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
            for (name, value) in values {
                position(&format!("{table}.{name}"), *value)?;
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

/// The axes of the `[axes]` tables, in their slots, and the layout that names them: x y z are
/// the geometry axes; a b c keep the slots they have always had (4th to 6th), other names take
/// the free ones of those in alphabetical order. `kind = "linear" | "rotary"` in an axis's table
/// overrides the kind its name gives (rotary for A, B, C and names starting so).
fn read_axes(
    tables: &BTreeMap<String, toml::Table>,
) -> Result<([Option<AxisConfig>; AXES], AxisLayout), MachineError> {
    let invalid = |message: String| MachineError::Invalid(message);
    let mut axes: [Option<AxisConfig>; AXES] = Default::default();
    let layout = AxisLayout::default();
    let mut named = Vec::new();
    for (key, table) in tables {
        let mut table = table.clone();
        let kind = match table.remove("kind") {
            None => None,
            Some(toml::Value::String(kind)) if kind == "linear" => Some(AxisKind::Linear),
            Some(toml::Value::String(kind)) if kind == "rotary" => Some(AxisKind::Rotary),
            Some(other) => {
                return Err(invalid(format!(
                    "axes.{key}.kind = {other}: expected \"linear\" or \"rotary\""
                )))
            }
        };
        let config = AxisConfig::deserialize(table)
            .map_err(|error| invalid(format!("axes.{key}: {}", error.message())))?;
        check_axis(key, &config).map_err(invalid)?;
        let name = AxisName::new(key).ok_or_else(|| {
            invalid(format!(
                "axes.{key}: an axis name is 1 to 8 letters, digits or `_`, starting with a letter"
            ))
        })?;
        let geometry = ["X", "Y", "Z"].iter().position(|g| *g == name.as_str());
        match geometry {
            Some(_) if kind == Some(AxisKind::Rotary) => {
                return Err(invalid(format!("axes.{key}: X, Y and Z are linear axes")))
            }
            Some(i) => axes[i] = Some(config),
            None => named.push((name, kind, config)),
        }
    }
    // A, B and C first into their own slots, then the other names into the free ones.
    named.sort_by_key(|(name, _, _)| own_slot(name).is_none());
    let mut machine_axes = MachineAxes { axes, layout };
    for (name, kind, config) in named {
        machine_axes.add(name, kind, config)?;
    }
    let MachineAxes { axes, layout } = machine_axes;
    Ok((axes, layout))
}

/// The slot an axis of this name always takes: A, B and C the 4th to 6th.
fn own_slot(name: &AxisName) -> Option<usize> {
    match name.as_str() {
        "A" => Some(Axis::A.index()),
        "B" => Some(Axis::B.index()),
        "C" => Some(Axis::C.index()),
        _ => None,
    }
}

/// A machine's axes and their layout, while axes are added.
struct MachineAxes {
    axes: [Option<AxisConfig>; AXES],
    layout: AxisLayout,
}

impl MachineAxes {
    /// Adds an axis after X Y Z: in its own slot (A B C) or the first free one.
    fn add(
        &mut self,
        name: AxisName,
        kind: Option<AxisKind>,
        config: AxisConfig,
    ) -> Result<Axis, MachineError> {
        let invalid = |message: String| MachineError::Invalid(message);
        let table = format!("axes.{}", name.as_str().to_ascii_lowercase());
        // Other single letters are addresses (I J K R F ...); names of several characters are
        // SINUMERIK's (C1, SP2), which ISO programs cannot address.
        if name
            .single_letter()
            .is_some_and(|l| !b"ABCUVW".contains(&l))
        {
            return Err(invalid(format!(
                "{table}: {name} is an address, not an axis; an axis of one letter is A, B, C, U, V or W"
            )));
        }
        if (3..AXES).any(|i| self.axes[i].is_some() && self.layout.name(Axis::ALL[i]) == name) {
            return Err(invalid(format!(
                "{table}: the machine has this axis already"
            )));
        }
        let slot = match own_slot(&name) {
            Some(slot) if self.axes[slot].is_none() => slot,
            Some(slot) => {
                return Err(invalid(format!(
                    "{table}: {name} takes the axis slot {} that {} has",
                    slot + 1,
                    self.layout.name(Axis::ALL[slot])
                )))
            }
            None => (3..AXES).find(|&i| self.axes[i].is_none()).ok_or_else(|| {
                invalid(format!(
                    "{table}: vcnc's machines have at most {} axes besides X Y Z",
                    AXES - 3
                ))
            })?,
        };
        let axis = Axis::ALL[slot];
        let kind = kind.unwrap_or_else(|| AxisLayout::default_kind(&name));
        self.layout = self.layout.with(axis, name, kind);
        self.axes[slot] = Some(config);
        Ok(axis)
    }
}

/// An axis's numbers are ones a machine could have (see [`MachineFile::check_ranges`]).
fn check_axis(key: &str, axis: &AxisConfig) -> Result<(), String> {
    use Lower::{Above, AtLeast};
    let key = |name: &str| format!("axes.{key}.{name}");
    let position =
        |key: &str, value: f64| check_range(key, value, AtLeast(-MAX_POSITION), MAX_POSITION);
    position(&key("min"), axis.min)?;
    position(&key("max"), axis.max)?;
    check_range(&key("rapid"), axis.rapid, Above(0.0), MAX_RATE)?;
    check_range(&key("max_feed"), axis.max_feed, Above(0.0), MAX_RATE)?;
    check_range(&key("acceleration"), axis.acceleration, Above(0.0), 1e6)?;
    check_range(&key("jerk"), axis.jerk, Above(0.0), f64::INFINITY)?;
    if axis.min > axis.max {
        return Err(format!(
            "{}: min = {} is above max = {}",
            key("min"),
            axis.min,
            axis.max
        ));
    }
    Ok(())
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
    fn a_kinematics_table_names_rotary_axes_the_machine_has() {
        let axes = "[axes.b]\nmin = -120.0\nmax = 120.0\nrapid = 9000.0\nmax_feed = 5000.0\n\n\
                    [axes.c]\nmin = -1e5\nmax = 1e5\nrapid = 9000.0\nmax_feed = 5000.0\n\n";
        let table = "[kinematics]\ntype = \"table_table\"\nrotary = [\n\
                     { axis = \"b\", direction = [0.0, 2.0, 0.0] },\n\
                     { axis = \"c\", direction = [0.0, 0.0, 1.0], center = [1.0, 2.0, 3.0] },\n]\n";
        let text = DEFAULT_MACHINE_TOML.replace("[start]", &format!("{axes}{table}\n[start]"));
        let machine = Machine::from_toml(&text).expect("valid");
        let kinematics = machine.kinematics.expect("read");
        assert_eq!(kinematics.rotary_axes(), [Axis::B, Axis::C]);
        assert_eq!(kinematics.joints[0].direction, [0.0, 1.0, 0.0]);
        assert_eq!(kinematics.joints[0].limits, (-120.0, 120.0));
        let missing = text.replace("axis = \"b\"", "axis = \"a\"");
        let error = Machine::from_toml(&missing).unwrap_err().to_string();
        assert!(error.contains("no rotary axis"), "{error}");
    }

    #[test]
    fn a_four_axis_kinematics_table_has_one_rotary_axis() {
        let axes = "[axes.a]\nmin = -120.0\nmax = 120.0\nrapid = 9000.0\nmax_feed = 5000.0\n\n";
        let table = "[kinematics]\ntype = \"table\"\nrotary = [\n\
                     { axis = \"a\", direction = [1.0, 0.0, 0.0], center = [0.0, 0.0, -50.0] },\n]\n";
        let text = DEFAULT_MACHINE_TOML.replace("[start]", &format!("{axes}{table}\n[start]"));
        let machine = Machine::from_toml(&text).expect("valid");
        let kinematics = machine.kinematics.expect("read");
        assert_eq!(kinematics.rotary_axes(), [Axis::A]);
        let two = text.replace("type = \"table\"", "type = \"table_table\"");
        let error = Machine::from_toml(&two).unwrap_err().to_string();
        assert!(error.contains("expects 2 rotary axes, found 1"), "{error}");
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
        assert_eq!(machine.planner.look_ahead, 52);
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
        assert!(
            error.contains("axes.q: Q is an address, not an axis"),
            "{error}"
        );
        let text = DEFAULT_MACHINE_TOML.replace("[axes.z]", "[axes.\"1a\"]");
        let error = Machine::from_toml(&text).unwrap_err().to_string();
        assert!(error.contains("an axis name is 1 to 8 letters"), "{error}");
    }

    /// The default machine's X table with another name, and `extra` lines in it.
    fn axis_table(name: &str, extra: &str) -> String {
        format!("\n[axes.{name}]\nmin = -100.0\nmax = 100.0\nrapid = 5000.0\nmax_feed = 2000.0\n{extra}")
    }

    #[test]
    fn axes_named_u_v_w_are_linear_and_take_the_free_slots() {
        let text = format!(
            "{DEFAULT_MACHINE_TOML}{}{}{}",
            axis_table("w", ""),
            axis_table("c", ""),
            axis_table("u", "")
        )
        .replace("[start]\nx = 0.0", "[start]\nu = 12.5\nx = 0.0");
        let machine = Machine::from_toml(&text).unwrap();
        let layout = &machine.layout;
        // C keeps its own slot; U and W take the free ones in alphabetical order.
        assert_eq!(layout.by_name("C"), Some(Axis::C));
        assert_eq!(layout.by_name("u"), Some(Axis::A));
        assert_eq!(layout.by_name("W"), Some(Axis::B));
        assert!(!layout.is_rotary(Axis::A) && !layout.is_rotary(Axis::B));
        assert!(layout.is_rotary(Axis::C));
        assert_eq!(machine.start[Axis::A.index()], 12.5);
        assert!(machine.has_axis(Axis::A) && machine.has_axis(Axis::B));
    }

    #[test]
    fn an_axis_kind_and_sinumerik_names_come_from_the_file() {
        let text = format!(
            "{DEFAULT_MACHINE_TOML}{}{}",
            axis_table("c1", ""),
            axis_table("v", "kind = \"rotary\"\n")
        );
        let machine = Machine::from_toml(&text).unwrap();
        let c1 = machine.layout.by_name("C1").unwrap();
        let v = machine.layout.by_name("V").unwrap();
        assert!(machine.layout.is_rotary(c1) && machine.layout.is_rotary(v));
        let bad = format!(
            "{DEFAULT_MACHINE_TOML}{}",
            axis_table("u", "kind = \"round\"\n")
        );
        let error = Machine::from_toml(&bad).unwrap_err().to_string();
        assert!(
            error.contains("expected \"linear\" or \"rotary\""),
            "{error}"
        );
        let bad = DEFAULT_MACHINE_TOML.replace("[axes.z]", "[axes.z]\nkind = \"rotary\"");
        let error = Machine::from_toml(&bad).unwrap_err().to_string();
        assert!(error.contains("X, Y and Z are linear"), "{error}");
    }

    #[test]
    fn at_most_three_axes_besides_xyz_and_positions_name_present_axes() {
        let four: String = ["a", "b", "c", "u"]
            .iter()
            .map(|n| axis_table(n, ""))
            .collect();
        let error = Machine::from_toml(&format!("{DEFAULT_MACHINE_TOML}{four}"))
            .unwrap_err()
            .to_string();
        assert!(error.contains("at most 3 axes besides X Y Z"), "{error}");
        let text = DEFAULT_MACHINE_TOML.replace("[start]\nx = 0.0", "[start]\nu = 1.0\nx = 0.0");
        let error = Machine::from_toml(&text).unwrap_err().to_string();
        assert!(
            error.contains("start.u: the machine has no axis `u`"),
            "{error}"
        );
    }

    #[test]
    fn add_axis_places_axes_as_the_file_would() {
        let mut machine = Machine::default();
        let config = machine.axes[0].clone().unwrap();
        assert_eq!(
            machine.add_axis("u", None, config.clone()).unwrap(),
            Axis::A
        );
        assert_eq!(
            machine.add_axis("C", None, config.clone()).unwrap(),
            Axis::C
        );
        let error = machine
            .add_axis("A", None, config.clone())
            .unwrap_err()
            .to_string();
        assert!(
            error.contains("A takes the axis slot 4 that U has"),
            "{error}"
        );
        let error = machine
            .add_axis("U", None, config.clone())
            .unwrap_err()
            .to_string();
        assert!(error.contains("has this axis already"), "{error}");
        assert!(machine.add_axis("X", None, config).is_err());
    }
}
