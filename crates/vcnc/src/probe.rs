//! The virtual probe: what a skip signal can touch on this machine. The machine file's `[probe]`
//! describes the touch targets (a tool setter at a machine position, part or fixture surfaces as
//! planes or boxes) and the defaults of Syntec's automatic tool length measurement (the
//! control's Pr4055-Pr4059). The interpreter asks `Probe::first_touch` where a move of the
//! tool's tip first meets a target: G31 stops there (interp/skip.rs), G37 and G37.1 measure
//! against the tool setter alone (interp/tool_measurement.rs).
//!
//! The tool is its tip, a point: the control point less the tool's own length along Z (the
//! machine file's `[[tool_offsets]]` entry of the tool's number, geometry plus wear, as the
//! tool was set up before the program ran; what the program writes to the registers later does
//! not change the tool). A probe's stylus radius is left to its calibration, as on the machine.
//! Targets are solid: a move that starts inside one touches at its start (the manual: a signal
//! already on stops the block at once, Syntec spec 1.20).

use crate::machine::{ToolOffset, AXES};
use serde::Deserialize;
use std::collections::BTreeMap;

/// A point of the machine file: x, y, z in machine coordinates, mm.
#[derive(Clone, Copy, Debug, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Point {
    /// X, mm.
    #[serde(default)]
    pub x: f64,
    /// Y, mm.
    #[serde(default)]
    pub y: f64,
    /// Z, mm.
    #[serde(default)]
    pub z: f64,
}

impl Point {
    fn array(self) -> [f64; 3] {
        [self.x, self.y, self.z]
    }
}

/// The tool setter: the centre of its top face, where the tool's tip touches it, and the face's
/// radius.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ToolSetter {
    /// X of the face's centre, machine coordinates, mm.
    pub x: f64,
    /// Y of the face's centre, machine coordinates, mm.
    pub y: f64,
    /// Z of the face, machine coordinates of the tip that touches it, mm.
    pub z: f64,
    /// Radius of the face, mm.
    #[serde(default = "default_setter_radius")]
    pub radius: f64,
}

fn default_setter_radius() -> f64 {
    10.0
}

/// A surface: the material is on the side the normal points away from.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlaneTarget {
    /// A point of the plane, machine coordinates.
    pub point: Point,
    /// The outward normal (need not be of unit length).
    pub normal: Point,
}

/// A solid box, its faces along the machine's axes.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxTarget {
    /// The corner of the smallest coordinates, machine coordinates.
    pub min: Point,
    /// The corner of the largest coordinates.
    pub max: Point,
}

/// The defaults of G37/G37.1 where the block leaves a word out (Syntec spec 1.22, 1.23; the
/// control's parameters, whose values the manual does not give: these are vcnc's).
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeasurementDefaults {
    /// R, the measuring distance above Z, mm (Pr4055).
    #[serde(default = "default_measuring_distance")]
    pub measuring_distance: f64,
    /// D, the allowed trigger distance either side of Z, mm (Pr4056).
    #[serde(default = "default_allowed_distance")]
    pub allowed_distance: f64,
    /// F, the measuring feed, mm/min (Pr4057).
    #[serde(default = "default_measuring_feed")]
    pub feed: f64,
    /// P, the reference point to go to first; none unless 1 to 4 (Pr4058).
    #[serde(default)]
    pub reference_point: u32,
    /// G37.1's Z, machine coordinates, mm, when the block has none (Pr4059).
    #[serde(default)]
    pub position: Option<f64>,
}

fn default_measuring_distance() -> f64 {
    10.0
}

fn default_allowed_distance() -> f64 {
    5.0
}

fn default_measuring_feed() -> f64 {
    100.0
}

impl Default for MeasurementDefaults {
    fn default() -> MeasurementDefaults {
        MeasurementDefaults {
            measuring_distance: default_measuring_distance(),
            allowed_distance: default_allowed_distance(),
            feed: default_measuring_feed(),
            reference_point: 0,
            position: None,
        }
    }
}

/// The machine file's `[probe]`.
#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProbeConfig {
    /// The tool setter G37/G37.1 measure against (and G31 touches).
    #[serde(default)]
    pub tool_setter: Option<ToolSetter>,
    /// Surfaces G31 touches.
    #[serde(default)]
    pub planes: Vec<PlaneTarget>,
    /// Boxes G31 touches.
    #[serde(default)]
    pub boxes: Vec<BoxTarget>,
    /// G37/G37.1 defaults.
    #[serde(default)]
    pub measurement: MeasurementDefaults,
}

impl ProbeConfig {
    /// Every number is one a machine could have.
    ///
    /// # Errors
    /// The first field that is not finite, a zero normal, a box whose corners are swapped, a
    /// negative radius or distance, a feed not above zero.
    pub fn check(&self) -> Result<(), String> {
        let finite = |p: &Point| p.array().iter().all(|v| v.is_finite());
        if let Some(s) = &self.tool_setter {
            let valid = [s.x, s.y, s.z, s.radius].iter().all(|v| v.is_finite()) && s.radius >= 0.0;
            if !valid {
                return Err("probe.tool_setter: x, y, z finite and radius >= 0".to_string());
            }
        }
        for p in &self.planes {
            if !finite(&p.point) || !finite(&p.normal) || p.normal.array() == [0.0; 3] {
                return Err("probe.planes: a point and a normal that is not zero".to_string());
            }
        }
        for b in &self.boxes {
            let (min, max) = (b.min.array(), b.max.array());
            if !finite(&b.min) || !finite(&b.max) || (0..3).any(|i| min[i] > max[i]) {
                return Err("probe.boxes: min at most max on every axis".to_string());
            }
        }
        let m = &self.measurement;
        let distances = [m.measuring_distance, m.allowed_distance];
        let valid = distances.iter().all(|d| d.is_finite() && *d >= 0.0)
            && m.feed.is_finite()
            && m.feed > 0.0;
        if !valid {
            return Err("probe.measurement: distances >= 0 and a feed above 0".to_string());
        }
        Ok(())
    }
}

/// Which targets a signal comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Signal {
    /// G31's skip signal: every target.
    Skip,
    /// The tool setter's signal (G37, G37.1).
    ToolSetter,
}

/// The targets and the tools' own lengths, for the run.
#[derive(Clone, Debug, Default)]
pub(crate) struct Probe {
    config: ProbeConfig,
    /// Each tool's length by tool number, from the machine file's registers.
    lengths: BTreeMap<u32, f64>,
}

impl Probe {
    /// The probe of a machine: its `[probe]` and the lengths of its tools.
    pub(crate) fn new(config: &ProbeConfig, offsets: &BTreeMap<u32, ToolOffset>) -> Probe {
        Probe {
            config: config.clone(),
            lengths: offsets
                .iter()
                .map(|(n, t)| (*n, t.length + t.length_wear))
                .collect(),
        }
    }

    /// Whether the machine file describes anything G31 could touch.
    pub(crate) fn has_targets(&self) -> bool {
        self.config.tool_setter.is_some()
            || !self.config.planes.is_empty()
            || !self.config.boxes.is_empty()
    }

    /// The tool setter, if the machine has one.
    pub(crate) fn tool_setter(&self) -> Option<ToolSetter> {
        self.config.tool_setter
    }

    /// The G37/G37.1 defaults.
    pub(crate) fn measurement(&self) -> MeasurementDefaults {
        self.config.measurement
    }

    /// The length of tool `tool` (0 for a tool the machine file does not list).
    pub(crate) fn tool_length(&self, tool: u32) -> f64 {
        self.lengths.get(&tool).copied().unwrap_or(0.0)
    }

    /// Where, as a share 0..=1 of the move, the tip of tool `tool` moving with the control
    /// point from `from` to `to` (machine coordinates) first touches a target of `signal`.
    pub(crate) fn first_touch(
        &self,
        from: &[f64; AXES],
        to: &[f64; AXES],
        tool: u32,
        signal: Signal,
    ) -> Option<f64> {
        let length = self.tool_length(tool);
        let tip = |p: &[f64; AXES]| [p[0], p[1], p[2] - length];
        let (a, b) = (tip(from), tip(to));
        let setter = self.config.tool_setter.map(|s| {
            // The setter as a post below its face: the tip touches the face or its side.
            let r = s.radius;
            (
                [s.x - r, s.y - r, f64::NEG_INFINITY],
                [s.x + r, s.y + r, s.z],
            )
        });
        let boxes = self
            .config
            .boxes
            .iter()
            .map(|b| (b.min.array(), b.max.array()));
        let mut touches: Vec<f64> = match signal {
            Signal::ToolSetter => setter
                .iter()
                .filter_map(|(lo, hi)| box_entry(a, b, *lo, *hi))
                .collect(),
            Signal::Skip => setter
                .into_iter()
                .chain(boxes)
                .filter_map(|(lo, hi)| box_entry(a, b, lo, hi))
                .chain(
                    self.config
                        .planes
                        .iter()
                        .filter_map(|p| plane_entry(a, b, p.point.array(), p.normal.array())),
                )
                .collect(),
        };
        touches.sort_by(f64::total_cmp);
        touches.first().copied()
    }
}

/// Where the segment `a`-`b` enters the solid behind a plane (0 when it starts there).
fn plane_entry(a: [f64; 3], b: [f64; 3], point: [f64; 3], normal: [f64; 3]) -> Option<f64> {
    let side = |p: [f64; 3]| (0..3).map(|i| (p[i] - point[i]) * normal[i]).sum::<f64>();
    let (sa, sb) = (side(a), side(b));
    if sa <= 0.0 {
        Some(0.0)
    } else if sb <= 0.0 {
        Some(sa / (sa - sb))
    } else {
        None
    }
}

/// Where the segment `a`-`b` enters the box `lo`-`hi` (0 when it starts inside): the slabs'
/// entries and exits, Kay and Kajiya's test.
pub(crate) fn box_entry(a: [f64; 3], b: [f64; 3], lo: [f64; 3], hi: [f64; 3]) -> Option<f64> {
    let (mut enter, mut exit) = (0.0_f64, 1.0_f64);
    for i in 0..3 {
        let d = b[i] - a[i];
        if d == 0.0 {
            if a[i] < lo[i] || a[i] > hi[i] {
                return None;
            }
            continue;
        }
        let (t0, t1) = ((lo[i] - a[i]) / d, (hi[i] - a[i]) / d);
        enter = enter.max(t0.min(t1));
        exit = exit.min(t0.max(t1));
        if enter > exit {
            return None;
        }
    }
    Some(enter)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_move_down_onto_a_plane_touches_it_where_the_tip_meets_it() {
        // Tip 100 below the control point; the plane z = -50: the control point at z = 50,
        // a quarter of the way from z = 60 to z = 20.
        let probe = Probe {
            config: ProbeConfig {
                planes: vec![PlaneTarget {
                    point: Point {
                        x: 0.0,
                        y: 0.0,
                        z: -50.0,
                    },
                    normal: Point {
                        x: 0.0,
                        y: 0.0,
                        z: 1.0,
                    },
                }],
                ..ProbeConfig::default()
            },
            lengths: [(1, 100.0)].into_iter().collect(),
        };
        let from = [0.0, 0.0, 60.0, 0.0, 0.0, 0.0];
        let to = [0.0, 0.0, 20.0, 0.0, 0.0, 0.0];
        assert_eq!(probe.first_touch(&from, &to, 1, Signal::Skip), Some(0.25));
        assert_eq!(probe.first_touch(&from, &to, 0, Signal::Skip), None);
        assert_eq!(probe.first_touch(&from, &to, 1, Signal::ToolSetter), None);
    }

    #[test]
    fn a_move_beside_a_box_misses_it_and_one_through_it_enters_at_its_face() {
        let (lo, hi) = ([0.0, 0.0, 0.0], [10.0, 10.0, 10.0]);
        assert_eq!(
            box_entry([-5.0, 20.0, 5.0], [15.0, 20.0, 5.0], lo, hi),
            None
        );
        assert_eq!(
            box_entry([-10.0, 5.0, 5.0], [10.0, 5.0, 5.0], lo, hi),
            Some(0.5)
        );
        assert_eq!(
            box_entry([5.0, 5.0, 5.0], [50.0, 5.0, 5.0], lo, hi),
            Some(0.0)
        );
    }
}
