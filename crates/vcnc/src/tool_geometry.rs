//! Tools with geometry: the machine file's `[[tool_shapes]]` table, read into [`ToolShapes`],
//! and the shape of a tool as a simulator or a plot needs it ([`ToolShape::height_at`]).
//!
//! One entry per tool number (T): the end that cuts (flat, ball, bull nose, drill, chamfer or
//! engraving V), its diameter, the flute length, the shank and a holder as a stack of
//! cylinders and cones. The interpreter puts the entry of the tool it changes to on the tool
//! change ([`crate::SegmentKind::ToolChange`]); this module never looks at a program.

use crate::motion::{Holder, HolderSection, ToolShape, ToolTip, HOLDER_SECTIONS};
use crate::profile::{check_range, Lower};
use serde::Deserialize;
use std::collections::BTreeMap;

/// The tool table's shapes, by tool number.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ToolShapes(BTreeMap<u32, ToolShape>);

impl ToolShapes {
    /// The shape of tool `tool`, if the table describes it.
    pub fn get(&self, tool: u32) -> Option<ToolShape> {
        self.0.get(&tool).copied()
    }

    /// How many tools the table describes.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// True when the table describes no tool.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// The table of the machine file's entries, each checked.
    ///
    /// # Errors
    /// A message naming the entry and the field when an entry does not describe a tool (a
    /// size out of range, a field of another kind of tool, the same number twice).
    pub(crate) fn from_entries(entries: Vec<ToolShapeEntry>) -> Result<ToolShapes, String> {
        let mut shapes = BTreeMap::new();
        for entry in entries {
            let t = entry.t;
            let shape = entry.shape()?;
            if shapes.insert(t, shape).is_some() {
                return Err(format!("tool_shapes (t {t}): tool {t} is described twice"));
            }
        }
        Ok(ToolShapes(shapes))
    }
}

/// The kinds of tool the table knows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub(crate) enum ToolKind {
    Flat,
    Ball,
    BullNose,
    Drill,
    Chamfer,
    Engraving,
}

/// One section of a holder as written: `{ length, diameter }` for a cylinder,
/// `{ length, bottom_diameter, top_diameter }` for a cone.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SectionEntry {
    length: f64,
    #[serde(default)]
    diameter: Option<f64>,
    #[serde(default)]
    bottom_diameter: Option<f64>,
    #[serde(default)]
    top_diameter: Option<f64>,
}

/// One entry of `[[tool_shapes]]` as written.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ToolShapeEntry {
    t: u32,
    #[serde(rename = "type")]
    kind: ToolKind,
    diameter: f64,
    #[serde(default)]
    corner_radius: Option<f64>,
    #[serde(default)]
    point_angle: Option<f64>,
    #[serde(default)]
    angle: Option<f64>,
    #[serde(default)]
    tip_diameter: Option<f64>,
    #[serde(default)]
    cutting_length: Option<f64>,
    #[serde(default)]
    shank_diameter: Option<f64>,
    #[serde(default)]
    stickout: Option<f64>,
    #[serde(default)]
    center_cutting: Option<bool>,
    #[serde(default)]
    holder: Vec<SectionEntry>,
}

/// The largest size a tool table takes, mm: far beyond any tool.
const MAX_SIZE: f64 = 10_000.0;

impl ToolShapeEntry {
    fn shape(&self) -> Result<ToolShape, String> {
        let t = self.t;
        let key = |name: &str| format!("tool_shapes (t {t}).{name}");
        let size =
            |name: &str, value: f64| check_range(&key(name), value, Lower::Above(0.0), MAX_SIZE);
        size("diameter", self.diameter)?;
        self.only_for_its_kind(&key)?;
        let tip = self.tip(&key)?;
        // Flutes of no given length cut up to the holder.
        let cutting_length = self
            .cutting_length
            .or(self.stickout)
            .unwrap_or(f64::INFINITY);
        if let Some(length) = self.cutting_length {
            size("cutting_length", length)?;
        }
        let shank_diameter = self.shank_diameter.unwrap_or(self.diameter);
        size("shank_diameter", shank_diameter)?;
        let holder = self.holder(&key)?;
        let stickout = match (self.stickout, holder.sections().is_empty()) {
            (Some(stickout), _) => {
                size("stickout", stickout)?;
                if stickout < cutting_length {
                    return Err(format!(
                        "{}: {stickout} is shorter than cutting_length = {cutting_length}",
                        key("stickout")
                    ));
                }
                stickout
            }
            (None, true) => f64::INFINITY,
            (None, false) => {
                return Err(format!(
                    "{}: a tool with a holder needs its stickout (tip to holder face, mm)",
                    key("stickout")
                ))
            }
        };
        Ok(ToolShape {
            tip,
            diameter: self.diameter,
            cutting_length,
            shank_diameter,
            stickout,
            holder,
            center_cutting: self.center_cutting.unwrap_or(true),
        })
    }

    /// The fields of one kind of tool are refused on the others, so a typo cannot pass as a
    /// tool of another shape.
    fn only_for_its_kind(&self, key: &impl Fn(&str) -> String) -> Result<(), String> {
        use ToolKind::*;
        let fields = [
            (
                "corner_radius",
                self.corner_radius.is_some(),
                &[BullNose][..],
            ),
            ("point_angle", self.point_angle.is_some(), &[Drill][..]),
            ("angle", self.angle.is_some(), &[Chamfer, Engraving][..]),
            (
                "tip_diameter",
                self.tip_diameter.is_some(),
                &[Chamfer, Engraving][..],
            ),
            (
                "center_cutting",
                self.center_cutting.is_some(),
                &[Flat, BullNose][..],
            ),
        ];
        for (name, given, kinds) in fields {
            if given && !kinds.contains(&self.kind) {
                return Err(format!(
                    "{}: not a field of a {:?} tool",
                    key(name),
                    self.kind
                ));
            }
        }
        Ok(())
    }

    fn tip(&self, key: &impl Fn(&str) -> String) -> Result<ToolTip, String> {
        let radius = self.diameter / 2.0;
        let angle = |name: &str, value: Option<f64>| {
            let value = value.ok_or_else(|| format!("{}: missing", key(name)))?;
            check_range(&key(name), value, Lower::Above(0.0), 179.0).map(|()| value)
        };
        Ok(match self.kind {
            ToolKind::Flat => ToolTip::Flat,
            ToolKind::Ball => ToolTip::Ball,
            ToolKind::BullNose => {
                let corner_radius = self
                    .corner_radius
                    .ok_or_else(|| format!("{}: missing", key("corner_radius")))?;
                check_range(
                    &key("corner_radius"),
                    corner_radius,
                    Lower::Above(0.0),
                    radius,
                )?;
                ToolTip::BullNose { corner_radius }
            }
            ToolKind::Drill => ToolTip::Drill {
                point_angle: angle("point_angle", self.point_angle)?,
            },
            ToolKind::Chamfer | ToolKind::Engraving => {
                let tip_diameter = self.tip_diameter.unwrap_or(0.0);
                check_range(
                    &key("tip_diameter"),
                    tip_diameter,
                    Lower::AtLeast(0.0),
                    self.diameter,
                )?;
                ToolTip::Cone {
                    angle: angle("angle", self.angle)?,
                    tip_diameter,
                }
            }
        })
    }

    fn holder(&self, key: &impl Fn(&str) -> String) -> Result<Holder, String> {
        let mut sections = Vec::with_capacity(self.holder.len());
        for (i, entry) in self.holder.iter().enumerate() {
            let key = |name: &str| key(&format!("holder[{i}].{name}"));
            check_range(&key("length"), entry.length, Lower::Above(0.0), MAX_SIZE)?;
            let (bottom, top) = match (entry.diameter, entry.bottom_diameter, entry.top_diameter) {
                (Some(d), None, None) => (d, d),
                (None, Some(bottom), Some(top)) => (bottom, top),
                _ => {
                    return Err(format!(
                        "{}: give `diameter` (a cylinder) or `bottom_diameter` and \
                         `top_diameter` (a cone)",
                        key("diameter")
                    ))
                }
            };
            check_range(&key("bottom_diameter"), bottom, Lower::Above(0.0), MAX_SIZE)?;
            check_range(&key("top_diameter"), top, Lower::Above(0.0), MAX_SIZE)?;
            sections.push(HolderSection {
                length: entry.length,
                bottom_diameter: bottom,
                top_diameter: top,
            });
        }
        Holder::new(&sections).ok_or_else(|| {
            format!(
                "{}: {} sections, at most {HOLDER_SECTIONS}",
                key("holder"),
                sections.len()
            )
        })
    }
}

impl ToolShape {
    /// A flat end mill of this radius that cuts along its whole length (what a tool without
    /// geometry is taken for).
    pub fn flat(radius: f64) -> ToolShape {
        ToolShape {
            tip: ToolTip::Flat,
            diameter: 2.0 * radius,
            cutting_length: f64::INFINITY,
            shank_diameter: 2.0 * radius,
            stickout: f64::INFINITY,
            holder: Holder::default(),
            center_cutting: true,
        }
    }

    /// The cutting radius, mm.
    pub fn radius(&self) -> f64 {
        self.diameter / 2.0
    }

    /// The height of the tool's cutting surface above its tip at `r` mm from its axis; `None`
    /// beyond the radius. The profile is convex and rises with `r`, which the simulator's
    /// search along a sloped move relies on.
    pub fn height_at(&self, r: f64) -> Option<f64> {
        let radius = self.radius();
        if r > radius {
            return None;
        }
        Some(match self.tip {
            ToolTip::Flat => 0.0,
            ToolTip::Ball => radius - (radius * radius - r * r).max(0.0).sqrt(),
            ToolTip::BullNose { corner_radius } => {
                let flat = radius - corner_radius;
                if r <= flat {
                    0.0
                } else {
                    let d = r - flat;
                    corner_radius - (corner_radius * corner_radius - d * d).max(0.0).sqrt()
                }
            }
            ToolTip::Drill { point_angle } => r / (point_angle.to_radians() / 2.0).tan(),
            ToolTip::Cone {
                angle,
                tip_diameter,
            } => (r - tip_diameter / 2.0).max(0.0) / (angle.to_radians() / 2.0).tan(),
        })
    }

    /// The height above the tip where the cutting profile reaches full diameter: the length of
    /// the point of a drill or a V, the radius of a ball.
    pub fn tip_height(&self) -> f64 {
        self.height_at(self.radius()).unwrap_or(0.0)
    }

    /// A word for people: `flat 10 mm`, `ball 6 mm`, `drill 8.5 mm 118°`.
    pub fn describe(&self) -> String {
        let d = self.diameter;
        match self.tip {
            ToolTip::Flat => format!("flat {d} mm"),
            ToolTip::Ball => format!("ball {d} mm"),
            ToolTip::BullNose { corner_radius } => format!("bull nose {d} mm r{corner_radius}"),
            ToolTip::Drill { point_angle } => format!("drill {d} mm {point_angle}°"),
            ToolTip::Cone { angle, .. } => format!("V {d} mm {angle}°"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Result<ToolShapes, String> {
        #[derive(Deserialize)]
        struct File {
            tool_shapes: Vec<ToolShapeEntry>,
        }
        let file: File = toml::from_str(text).map_err(|e| e.to_string())?;
        ToolShapes::from_entries(file.tool_shapes)
    }

    #[test]
    fn every_kind_of_tool_reads_with_its_own_fields() {
        let shapes = read(
            r#"
            [[tool_shapes]]
            t = 1
            type = "flat"
            diameter = 10.0
            cutting_length = 20.0
            center_cutting = false
            [[tool_shapes]]
            t = 2
            type = "ball"
            diameter = 6.0
            [[tool_shapes]]
            t = 3
            type = "bull_nose"
            diameter = 12.0
            corner_radius = 1.0
            [[tool_shapes]]
            t = 4
            type = "drill"
            diameter = 8.5
            point_angle = 118.0
            [[tool_shapes]]
            t = 5
            type = "engraving"
            diameter = 6.0
            angle = 60.0
            tip_diameter = 0.2
            stickout = 30.0
            holder = [{ length = 20.0, diameter = 25.0 }, { length = 15.0, bottom_diameter = 25.0, top_diameter = 40.0 }]
            "#,
        )
        .unwrap();
        assert_eq!(shapes.len(), 5);
        let flat = shapes.get(1).unwrap();
        assert!(!flat.center_cutting);
        assert_eq!(flat.cutting_length, 20.0);
        assert_eq!(flat.shank_diameter, 10.0);
        assert_eq!(
            shapes.get(3).unwrap().tip,
            ToolTip::BullNose { corner_radius: 1.0 }
        );
        let v = shapes.get(5).unwrap();
        assert_eq!(v.holder.sections().len(), 2);
        assert_eq!(v.holder.sections()[1].top_diameter, 40.0);
        assert_eq!(v.stickout, 30.0);
        assert_eq!(shapes.get(6), None);
    }

    #[test]
    fn profiles_rise_from_the_tip_as_their_shape_says() {
        let ball = ToolShape {
            tip: ToolTip::Ball,
            ..ToolShape::flat(3.0)
        };
        // A ball of radius 3: at r = 3 the surface is a radius above the tip.
        assert_eq!(ball.height_at(0.0), Some(0.0));
        assert!((ball.height_at(3.0).unwrap() - 3.0).abs() < 1e-12);
        assert_eq!(ball.height_at(3.1), None);
        // A 90° drill rises as fast as it widens: at r = 2, 2 above the tip.
        let drill = ToolShape {
            tip: ToolTip::Drill { point_angle: 90.0 },
            ..ToolShape::flat(4.0)
        };
        assert!((drill.height_at(2.0).unwrap() - 2.0).abs() < 1e-12);
        // A bull nose of radius 5 and corner 1 is flat out to r = 4.
        let bull = ToolShape {
            tip: ToolTip::BullNose { corner_radius: 1.0 },
            ..ToolShape::flat(5.0)
        };
        assert_eq!(bull.height_at(4.0), Some(0.0));
        assert!((bull.height_at(5.0).unwrap() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn bad_entries_are_refused_with_the_field_named() {
        let cases = [
            ("t = 1\ntype = \"flat\"\ndiameter = 0.0", "tool_shapes (t 1).diameter = 0"),
            (
                "t = 2\ntype = \"ball\"\ndiameter = 6.0\npoint_angle = 118.0",
                "tool_shapes (t 2).point_angle: not a field",
            ),
            (
                "t = 3\ntype = \"bull_nose\"\ndiameter = 6.0\ncorner_radius = 4.0",
                "tool_shapes (t 3).corner_radius = 4",
            ),
            (
                "t = 4\ntype = \"flat\"\ndiameter = 6.0\nholder = [{ length = 5.0, diameter = 20.0 }]",
                "tool_shapes (t 4).stickout: a tool with a holder",
            ),
            ("t = 5\ntype = \"drill\"\ndiameter = 6.0", "tool_shapes (t 5).point_angle: missing"),
        ];
        for (entry, expected) in cases {
            let error = read(&format!("[[tool_shapes]]\n{entry}")).unwrap_err();
            assert!(error.starts_with(expected), "{entry}: {error}");
        }
        let twice = "[[tool_shapes]]\nt = 1\ntype = \"flat\"\ndiameter = 6.0\n";
        let error = read(&format!("{twice}{twice}")).unwrap_err();
        assert!(error.contains("described twice"), "{error}");
    }
}
