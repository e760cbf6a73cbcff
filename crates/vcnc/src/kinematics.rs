//! A 4- or 5-axis machine's kinematics: where the tool tip is and how the tool points, in the
//! workpiece, for a position of the joints (the forward transform), and the joints for a tip and
//! a tool direction (the inverse). Read from the machine file's `[kinematics]` table
//! (docs/KINEMATICS.md).
//!
//! The model: the linear axes X Y Z carry the control point (the spindle nose with the head at
//! zero, where the tool length is measured from) and any head rotary axes; the table rotary axes
//! carry the part. A head axis turns the tool about a line through a point given relative to the
//! control point (a pivot length is that point's distance along the tool axis); a table axis
//! turns the part about a line through a point given in machine coordinates. Every axis turns by
//! its angle right-handed about its `direction`; a machine whose axis turns the other way gives
//! the opposite direction. Workpiece coordinates are machine coordinates with every table axis at
//! zero, so work offsets keep their meaning.
//!
//! The transforms are pure functions of their arguments: no state, no alarms (the callers turn a
//! direction that cannot be reached into their alarm). One rotary axis on the table or in the
//! head (4-axis), and table-table (A-C, B-C), head-head and head-table machines with two rotary
//! axes are what the machine file describes.

use crate::axis::{Axis, AxisLayout, AXES};
use serde::Deserialize;

/// A vector or point of X Y Z.
pub type Vec3 = [f64; 3];

/// Where the rotary axes are.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum KinematicsKind {
    /// One rotary axis, on the table (a 4-axis machine: an A or B trunnion, or a rotary C).
    Table,
    /// One rotary axis, in the head (a 4-axis machine with a tilting head).
    Head,
    /// Both on the table: the first carries the second (a trunnion A or B carrying a rotary C).
    TableTable,
    /// Both in the head: the first carries the second (a C head carrying an A or B fork).
    HeadHead,
    /// The first in the head, the second on the table.
    HeadTable,
}

/// Which of the (usually two) joint solutions for a tool direction the control takes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Solution {
    /// The one the rotary axes reach with the least travel from where they are.
    #[default]
    Shortest,
    /// The one whose first rotary axis (the carrier) is at zero or above, shortest among them.
    FirstPositive,
    /// The one whose first rotary axis is at zero or below, shortest among them.
    FirstNegative,
}

/// A rotary axis of the kinematic chain.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RotaryJoint {
    /// The machine axis (slot of the positions) that turns it.
    pub axis: Axis,
    /// Unit vector it turns about, right-handed for positive angles, with every axis at zero.
    pub direction: Vec3,
    /// A point of its line with every axis at zero: machine coordinates for a table axis, relative
    /// to the control point for a head axis.
    pub center: Vec3,
    /// The travel the solution must stay within (the axis's limits), degrees.
    pub limits: (f64, f64),
}

/// Where the tool is in the workpiece.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ToolPose {
    /// The tool tip, workpiece coordinates (machine coordinates with the table at zero).
    pub tip: Vec3,
    /// Unit vector from the tip towards the spindle, workpiece coordinates.
    pub axis: Vec3,
}

/// A machine's kinematics: one or two rotary axes, where they sit and how the tool points at
/// zero.
#[derive(Clone, Debug, PartialEq)]
pub struct Kinematics {
    /// Head or table axes.
    pub kind: KinematicsKind,
    /// The rotary axes from the machine's base outwards (the first carries the second; on a
    /// head-table machine the head's first): as many as `kind` says.
    pub joints: Vec<RotaryJoint>,
    /// Unit vector from the tip towards the spindle with every axis at zero.
    pub tool_axis: Vec3,
    /// Which joint solution the inverse takes.
    pub solution: Solution,
}

/// The `[kinematics]` table as written.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct KinematicsFile {
    #[serde(rename = "type")]
    kind: KinematicsKind,
    rotary: Vec<RotaryFile>,
    #[serde(default = "up")]
    tool_axis: Vec3,
    #[serde(default)]
    solution: Solution,
}

/// One `rotary` entry as written.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RotaryFile {
    axis: String,
    direction: Vec3,
    #[serde(default)]
    center: Vec3,
}

fn up() -> Vec3 {
    [0.0, 0.0, 1.0]
}

/// Shorter than this, a direction has none (and two unit vectors this close to parallel are).
const DEGENERATE: f64 = 1e-9;

impl KinematicsFile {
    /// The kinematics, its axes found by name in `layout` among the rotary axes `limits` gives.
    pub(crate) fn resolve(
        self,
        layout: &AxisLayout,
        limits: impl Fn(Axis) -> Option<(f64, f64)>,
    ) -> Result<Kinematics, String> {
        let expected = self.kind.rotary_count();
        if self.rotary.len() != expected {
            return Err(format!(
                "kinematics.rotary: type `{}` expects {expected} rotary {}, found {}",
                self.kind.name(),
                if expected == 1 { "axis" } else { "axes" },
                self.rotary.len()
            ));
        }
        let joint = |entry: RotaryFile| -> Result<RotaryJoint, String> {
            let key = format!("kinematics.rotary `{}`", entry.axis);
            let (axis, limits) = layout
                .by_name(&entry.axis)
                .filter(|a| layout.is_rotary(*a))
                .and_then(|a| Some((a, limits(a)?)))
                .ok_or_else(|| format!("{key}: the machine has no rotary axis of that name"))?;
            let direction = unit(entry.direction)
                .ok_or_else(|| format!("{key}: direction must be a non-zero vector"))?;
            if entry.center.iter().any(|c| !c.is_finite() || c.abs() > 1e6) {
                return Err(format!("{key}: center must be finite, within 1e6 mm"));
            }
            Ok(RotaryJoint {
                axis,
                direction,
                center: entry.center,
                limits,
            })
        };
        let joints = self
            .rotary
            .into_iter()
            .map(joint)
            .collect::<Result<Vec<_>, _>>()?;
        if let [first, second] = joints.as_slice() {
            if first.axis == second.axis {
                return Err("kinematics.rotary: the two rotary axes must differ".into());
            }
            if norm(cross(first.direction, second.direction)) < 1e-6 {
                return Err("kinematics.rotary: the two axes must not be parallel".into());
            }
        }
        let tool_axis = unit(self.tool_axis)
            .ok_or_else(|| "kinematics.tool_axis must be a non-zero vector".to_string())?;
        Ok(Kinematics {
            kind: self.kind,
            joints,
            tool_axis,
            solution: self.solution,
        })
    }
}

impl KinematicsKind {
    /// How many rotary axes a machine of this kind has.
    pub fn rotary_count(self) -> usize {
        match self {
            KinematicsKind::Table | KinematicsKind::Head => 1,
            _ => 2,
        }
    }

    /// The name the machine file gives it.
    fn name(self) -> &'static str {
        match self {
            KinematicsKind::Table => "table",
            KinematicsKind::Head => "head",
            KinematicsKind::TableTable => "table_table",
            KinematicsKind::HeadHead => "head_head",
            KinematicsKind::HeadTable => "head_table",
        }
    }

    /// Whether the `index`th rotary axis (from the base) sits in the head; the others carry
    /// the part.
    fn in_head(self, index: usize) -> bool {
        match self {
            KinematicsKind::Table | KinematicsKind::TableTable => false,
            KinematicsKind::Head | KinematicsKind::HeadHead => true,
            KinematicsKind::HeadTable => index == 0,
        }
    }
}

impl Kinematics {
    /// The rotary axes, from the base outwards.
    pub fn rotary_axes(&self) -> Vec<Axis> {
        self.joints.iter().map(|j| j.axis).collect()
    }

    /// Whether every rotary axis sits in the head (the table does not turn).
    pub fn all_in_head(&self) -> bool {
        (0..self.joints.len()).all(|i| self.kind.in_head(i))
    }

    /// The tip's offset from the control point and the tool axis in machine coordinates, for a
    /// tool `length` long (from the tip to the control point along the tool) and the head's
    /// axes at their angles in `joints`: applied from the tool outwards.
    fn head(&self, joints: &[f64; AXES], length: f64) -> (Vec3, Vec3) {
        let mut tip = scale(self.tool_axis, -length);
        let mut axis = self.tool_axis;
        for (i, joint) in self.joints.iter().enumerate().rev() {
            if self.kind.in_head(i) {
                let angle = joints[joint.axis.index()];
                tip = turn_about(tip, joint.center, joint.direction, angle);
                axis = rotate(axis, joint.direction, angle);
            }
        }
        (tip, axis)
    }

    /// Where the table's axes at their angles in `joints` carry a workpiece point (or,
    /// `about_centre` false, a direction): from the part towards the base.
    fn table_to_machine(&self, mut p: Vec3, joints: &[f64; AXES], about_centre: bool) -> Vec3 {
        for (i, joint) in self.joints.iter().enumerate().rev() {
            if !self.kind.in_head(i) {
                let angle = joints[joint.axis.index()];
                p = match about_centre {
                    true => turn_about(p, joint.center, joint.direction, angle),
                    false => rotate(p, joint.direction, angle),
                };
            }
        }
        p
    }

    /// [`Kinematics::table_to_machine`] undone: a machine point (or direction) in the part.
    fn machine_to_table(&self, mut p: Vec3, joints: &[f64; AXES], about_centre: bool) -> Vec3 {
        for (i, joint) in self.joints.iter().enumerate() {
            if !self.kind.in_head(i) {
                let angle = joints[joint.axis.index()];
                p = match about_centre {
                    true => turn_about(p, joint.center, joint.direction, -angle),
                    false => rotate(p, joint.direction, -angle),
                };
            }
        }
        p
    }

    /// The forward transform: the tool tip and axis in the workpiece for the machine at
    /// `joints`, with a tool `length` long.
    pub fn forward(&self, joints: &[f64; AXES], length: f64) -> ToolPose {
        let (offset, axis) = self.head(joints, length);
        let control = [joints[0], joints[1], joints[2]];
        ToolPose {
            tip: self.machine_to_table(add(control, offset), joints, true),
            axis: self.machine_to_table(axis, joints, false),
        }
    }

    /// The inverse for a given orientation: the machine position that puts a tool `length` long
    /// with its tip at `tip` (workpiece coordinates), the rotary axes at their angles in
    /// `joints` (whose other axes are kept).
    pub fn joints_for_tip(&self, tip: Vec3, joints: &[f64; AXES], length: f64) -> [f64; AXES] {
        let (offset, _) = self.head(joints, length);
        let control = sub(self.table_to_machine(tip, joints, true), offset);
        let mut out = *joints;
        out[..3].copy_from_slice(&control);
        out
    }

    /// The inverse for a tool direction: `joints` with the rotary axes turned so that the tool
    /// points along `direction` (workpiece coordinates), chosen by [`Kinematics::solution`]
    /// among the solutions within the axes' limits, next to the angles `joints` holds. `None`
    /// when no position of the axes gives that direction (with one rotary axis, any direction
    /// off the cone the tool sweeps about it).
    pub fn orient(&self, direction: Vec3, joints: &[f64; AXES]) -> Option<[f64; AXES]> {
        let direction = unit(direction)?;
        let current = |i: usize| joints[self.joints[i].axis.index()];
        let angles = match self.joints.len() {
            1 => vec![self.angle_for(direction, current(0))?],
            _ => self
                .angles_for(direction, [current(0), current(1)])?
                .to_vec(),
        };
        let mut out = *joints;
        for (joint, angle) in self.joints.iter().zip(angles) {
            out[joint.axis.index()] = angle;
        }
        Some(out)
    }

    /// One rotary axis: the tool turned about it sweeps a cone, and a direction on that cone is
    /// reached by one angle (the axis's own direction by any: it stays at `current`).
    fn angle_for(&self, direction: Vec3, current: f64) -> Option<f64> {
        let joint = &self.joints[0];
        let a = joint.direction;
        // Rounding may leave a reachable direction a hair off the cone; anything more is out of
        // reach, as for two axes (`two_cone_meeting`).
        if (dot(direction, a) - dot(self.tool_axis, a)).abs() > 1e-9 {
            return None;
        }
        // A table axis turns the tool, seen from the part, by minus its angle.
        let sign = if self.kind.in_head(0) { 1.0 } else { -1.0 };
        let raw = angle_about(a, self.tool_axis, direction).map_or(current, |v| v * sign);
        nearest_turn(raw, current, joint.limits)
    }

    /// Two rotary axes: their angles for `direction`, next to `current`.
    fn angles_for(&self, direction: Vec3, current: [f64; 2]) -> Option<[f64; 2]> {
        let direction = unit(direction)?;
        // The chain as two turns of the tool axis: direction = R_outer(φo) R_inner(φi) k0. A table
        // axis turns the tool (seen from the part) by minus its angle, the base's last.
        let ([outer, inner], signs) = match self.kind {
            KinematicsKind::HeadHead => ([0, 1], [1.0, 1.0]),
            KinematicsKind::HeadTable => ([1, 0], [-1.0, 1.0]),
            _ => ([1, 0], [-1.0, -1.0]),
        };
        let (a, b) = (self.joints[outer].direction, self.joints[inner].direction);
        let mut best: Option<([f64; 2], f64)> = None;
        for z in two_cone_meeting(a, b, self.tool_axis, direction)? {
            // R_inner(φi) k0 = z, R_outer(-φo) direction = z.
            let inner_angle = angle_about(b, self.tool_axis, z).map(|v| v * signs[1]);
            let outer_angle = angle_about(a, direction, z).map(|v| -v * signs[0]);
            let mut raw = [0.0; 2];
            raw[outer] = outer_angle.unwrap_or(current[outer]);
            raw[inner] = inner_angle.unwrap_or(current[inner]);
            let Some(chosen) = self.nearest(raw, current) else {
                continue;
            };
            let travel = (chosen[0] - current[0]).abs() + (chosen[1] - current[1]).abs();
            let preferred = match self.solution {
                Solution::Shortest => true,
                Solution::FirstPositive => wrap(chosen[0]) >= -1e-9,
                Solution::FirstNegative => wrap(chosen[0]) <= 1e-9,
            };
            // A preferred solution beats any other; among equals the shorter travel wins.
            let score = travel + if preferred { 0.0 } else { 1e9 };
            if best.is_none_or(|(_, s)| score < s - 1e-9) {
                best = Some((chosen, score));
            }
        }
        best.map(|(angles, _)| angles)
    }

    /// Each angle of `raw` taken whole turns towards `current`, within its axis's limits.
    fn nearest(&self, raw: [f64; 2], current: [f64; 2]) -> Option<[f64; 2]> {
        Some([
            nearest_turn(raw[0], current[0], self.joints[0].limits)?,
            nearest_turn(raw[1], current[1], self.joints[1].limits)?,
        ])
    }
}

/// `raw` taken whole turns towards `current`, within `(min, max)`.
fn nearest_turn(raw: f64, current: f64, (min, max): (f64, f64)) -> Option<f64> {
    let near = current + wrap(raw - current);
    // The nearest equivalent first, then a turn either way if the limits refuse it.
    [near, near - 360.0, near + 360.0]
        .into_iter()
        .filter(|a| (min - 1e-9..=max + 1e-9).contains(a))
        .min_by(|x, y| (x - current).abs().total_cmp(&(y - current).abs()))
}

/// The unit vectors `z` with `z·b = k·b` and `z·a = d·a`: where the cone `k` sweeps about `b`
/// meets the cone `d` sweeps about `a` (zero, one or two of them). `a` and `b` are unit vectors,
/// not parallel. Writing `z = α a + β b + γ a×b` turns the two conditions into two linear
/// equations in α and β, and |z| = 1 gives γ.
fn two_cone_meeting(a: Vec3, b: Vec3, k: Vec3, d: Vec3) -> Option<Vec<Vec3>> {
    let ab = dot(a, b);
    let (da, kb) = (dot(d, a), dot(k, b));
    let det = ab * ab - 1.0;
    let alpha = (ab * kb - da) / det;
    let beta = (ab * da - kb) / det;
    let n = cross(a, b);
    let rest = 1.0 - alpha * alpha - beta * beta - 2.0 * alpha * beta * ab;
    let gamma_squared = rest / dot(n, n);
    // Rounding may leave a reachable direction a hair outside; anything more is out of reach.
    if gamma_squared < -1e-9 {
        return None;
    }
    let gamma = gamma_squared.max(0.0).sqrt();
    let base = add(scale(a, alpha), scale(b, beta));
    let mut out = vec![add(base, scale(n, gamma))];
    if gamma > DEGENERATE {
        out.push(add(base, scale(n, -gamma)));
    }
    Some(out)
}

/// The angle, degrees, that turns `from` into `to` about the unit vector `axis`; `None` when
/// either lies along the axis (any angle does).
fn angle_about(axis: Vec3, from: Vec3, to: Vec3) -> Option<f64> {
    let u = sub(from, scale(axis, dot(from, axis)));
    let v = sub(to, scale(axis, dot(to, axis)));
    if norm(u) < DEGENERATE || norm(v) < DEGENERATE {
        return None;
    }
    Some(dot(axis, cross(u, v)).atan2(dot(u, v)).to_degrees())
}

/// `degrees` brought into (-180, 180].
fn wrap(degrees: f64) -> f64 {
    let w = degrees - 360.0 * ((degrees + 180.0) / 360.0).floor();
    if w <= -180.0 {
        w + 360.0
    } else {
        w
    }
}

/// `v` turned by `degrees` about the unit vector `axis` (Rodrigues' formula).
pub fn rotate(v: Vec3, axis: Vec3, degrees: f64) -> Vec3 {
    let (sin, cos) = degrees.to_radians().sin_cos();
    let along = scale(axis, dot(axis, v) * (1.0 - cos));
    add(add(scale(v, cos), scale(cross(axis, v), sin)), along)
}

/// The rotation matrix (row by row) of turns made one after the other, each about an axis of
/// the system the turns before it left (`(axis, degrees)`, the axis in that turned system):
/// the product of the turns in the order given.
pub fn successive_turns(turns: &[(Vec3, f64)]) -> [[f64; 3]; 3] {
    // The images of the unit vectors are the columns; the last turn acts first on them.
    let column = |unit: Vec3| {
        turns
            .iter()
            .rev()
            .fold(unit, |v, (axis, degrees)| rotate(v, *axis, *degrees))
    };
    let columns = [
        column([1.0, 0.0, 0.0]),
        column([0.0, 1.0, 0.0]),
        column([0.0, 0.0, 1.0]),
    ];
    std::array::from_fn(|row| std::array::from_fn(|col| columns[col][row]))
}

/// `p` turned by `degrees` about the line through `center` along `axis`.
fn turn_about(p: Vec3, center: Vec3, axis: Vec3, degrees: f64) -> Vec3 {
    add(center, rotate(sub(p, center), axis, degrees))
}

pub(crate) fn unit(v: Vec3) -> Option<Vec3> {
    let n = norm(v);
    (n.is_finite() && n > DEGENERATE).then(|| scale(v, 1.0 / n))
}

pub(crate) fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(crate) fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub(crate) fn norm(v: Vec3) -> f64 {
    dot(v, v).sqrt()
}

fn add(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

pub(crate) fn sub(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn scale(v: Vec3, f: f64) -> Vec3 {
    [v[0] * f, v[1] * f, v[2] * f]
}

#[cfg(test)]
mod tests {
    use super::*;

    const FREE: (f64, f64) = (-1e5, 1e5);

    fn machine(kind: KinematicsKind, joints: [(Axis, Vec3, Vec3); 2]) -> Kinematics {
        Kinematics {
            kind,
            joints: joints
                .map(|(axis, direction, center)| RotaryJoint {
                    axis,
                    direction,
                    center,
                    limits: FREE,
                })
                .into(),
            tool_axis: [0.0, 0.0, 1.0],
            solution: Solution::Shortest,
        }
    }

    fn at(x: f64, y: f64, z: f64, b: f64, c: f64) -> [f64; AXES] {
        [x, y, z, 0.0, b, c]
    }

    fn close(a: Vec3, b: Vec3) -> bool {
        (0..3).all(|i| (a[i] - b[i]).abs() < 1e-9)
    }

    #[test]
    fn a_b_head_with_a_pivot_swings_the_tip_round_the_pivot() {
        // Head B about Y through the pivot 100 mm above the nose, C about Z above it; a 50 mm
        // tool: the tip is 150 below the pivot. At B = 90 the tool points along +X from the
        // tip (R_y(90) z = x), so the tip is 150 along -X from the pivot (0, 0, 100):
        // (-150, 0, 100) at X Y Z = 0.
        let head = machine(
            KinematicsKind::HeadHead,
            [
                (Axis::C, [0.0, 0.0, 1.0], [0.0, 0.0, 100.0]),
                (Axis::B, [0.0, 1.0, 0.0], [0.0, 0.0, 100.0]),
            ],
        );
        let pose = head.forward(&at(0.0, 0.0, 0.0, 90.0, 0.0), 50.0);
        assert!(close(pose.tip, [-150.0, 0.0, 100.0]), "{pose:?}");
        assert!(close(pose.axis, [1.0, 0.0, 0.0]), "{pose:?}");
        // C 90 then turns that about Z: the tool points along +Y, the tip at (0, -150, 100).
        let pose = head.forward(&at(0.0, 0.0, 0.0, 90.0, 90.0), 50.0);
        assert!(close(pose.tip, [0.0, -150.0, 100.0]), "{pose:?}");
    }

    #[test]
    fn a_tilting_table_carries_the_part_round_its_centre() {
        // Table B about Y through (0, 0, -100), C about Z on it through the same point. With B at
        // 90 the part is turned +90 about Y, so the machine point (0, 0, 0) (100 above the
        // centre) is the part point turned back by -90: R_y(-90) (0, 0, 100) = (-100, 0, 0),
        // about the centre: (-100, 0, -100). The tool (+Z in the machine) is -X in the part.
        let table = machine(
            KinematicsKind::TableTable,
            [
                (Axis::B, [0.0, 1.0, 0.0], [0.0, 0.0, -100.0]),
                (Axis::C, [0.0, 0.0, 1.0], [0.0, 0.0, -100.0]),
            ],
        );
        let pose = table.forward(&at(0.0, 0.0, 0.0, 90.0, 0.0), 0.0);
        assert!(close(pose.tip, [-100.0, 0.0, -100.0]), "{pose:?}");
        assert!(close(pose.axis, [-1.0, 0.0, 0.0]), "{pose:?}");
    }

    #[test]
    fn the_inverse_puts_the_tip_back_where_the_forward_found_it() {
        let kinds = [
            KinematicsKind::TableTable,
            KinematicsKind::HeadHead,
            KinematicsKind::HeadTable,
        ];
        for kind in kinds {
            let m = machine(
                kind,
                [
                    (Axis::B, [0.0, 1.0, 0.0], [10.0, -5.0, 80.0]),
                    (Axis::C, [0.0, 0.0, 1.0], [3.0, 7.0, 20.0]),
                ],
            );
            let joints = at(12.0, -30.0, 44.0, 33.0, -71.0);
            let pose = m.forward(&joints, 60.0);
            let back = m.joints_for_tip(pose.tip, &joints, 60.0);
            assert!(
                close([back[0], back[1], back[2]], [12.0, -30.0, 44.0]),
                "{kind:?}"
            );
            let angles = m.angles_for(pose.axis, [30.0, -60.0]).expect("reachable");
            let again = m.forward(&at(0.0, 0.0, 0.0, angles[0], angles[1]), 60.0);
            assert!(close(again.axis, pose.axis), "{kind:?}: {angles:?}");
        }
    }

    #[test]
    fn a_b_c_table_has_two_solutions_and_takes_the_nearer() {
        // Tool direction (1, 0, 1)/√2 in the part on a B-C table: B = -45 with C = 0 (the part
        // tipped so +X rises), or B = +45 with C = 180. From B 40, C 170 the second is nearer.
        let table = machine(
            KinematicsKind::TableTable,
            [
                (Axis::B, [0.0, 1.0, 0.0], [0.0; 3]),
                (Axis::C, [0.0, 0.0, 1.0], [0.0; 3]),
            ],
        );
        let d = [1.0, 0.0, 1.0];
        let near_zero = table.angles_for(d, [0.0, 0.0]).unwrap();
        assert!((near_zero[0] + 45.0).abs() < 1e-9 && near_zero[1].abs() < 1e-9);
        let near_other = table.angles_for(d, [40.0, 170.0]).unwrap();
        assert!((near_other[0] - 45.0).abs() < 1e-9 && (near_other[1] - 180.0).abs() < 1e-9);
    }

    #[test]
    fn a_direction_along_the_carried_axis_keeps_its_angle() {
        // Straight down the C axis: any C gives it; C stays where it is.
        let table = machine(
            KinematicsKind::TableTable,
            [
                (Axis::A, [1.0, 0.0, 0.0], [0.0; 3]),
                (Axis::C, [0.0, 0.0, 1.0], [0.0; 3]),
            ],
        );
        let angles = table.angles_for([0.0, 0.0, 1.0], [0.0, 123.0]).unwrap();
        assert!(angles[0].abs() < 1e-9 && (angles[1] - 123.0).abs() < 1e-9);
    }

    #[test]
    fn a_direction_the_axes_cannot_reach_has_no_solution() {
        // An A-C table whose A is limited to 0..90 and C held at 0 tips the part one way only:
        // the tool seen from the part is R_x(-A) z = (0, sin A, cos A), so y >= 0.
        let mut table = machine(
            KinematicsKind::TableTable,
            [
                (Axis::A, [1.0, 0.0, 0.0], [0.0; 3]),
                (Axis::C, [0.0, 0.0, 1.0], [0.0; 3]),
            ],
        );
        table.joints[0].limits = (0.0, 90.0);
        table.joints[1].limits = (0.0, 0.0);
        assert!(table.angles_for([0.0, -1.0, 1.0], [0.0, 0.0]).is_none());
        let angles = table.angles_for([0.0, 1.0, 1.0], [0.0, 0.0]).unwrap();
        assert!((angles[0] - 45.0).abs() < 1e-9 && angles[1].abs() < 1e-9);
    }

    /// A 4-axis machine: one rotary axis.
    fn one_axis(kind: KinematicsKind, axis: Axis, direction: Vec3, center: Vec3) -> Kinematics {
        Kinematics {
            kind,
            joints: vec![RotaryJoint {
                axis,
                direction,
                center,
                limits: FREE,
            }],
            tool_axis: [0.0, 0.0, 1.0],
            solution: Solution::Shortest,
        }
    }

    fn with_a(x: f64, y: f64, z: f64, a: f64) -> [f64; AXES] {
        [x, y, z, a, 0.0, 0.0]
    }

    #[test]
    fn an_a_table_alone_carries_the_part_round_its_line() {
        // A about X through (0, 0, -100) at 90: the machine point (0, 0, 0), 100 above the line,
        // is the part point turned back by -90: R_x(-90) (0, 0, 100) = (0, 100, 0), about the
        // line (0, 100, -100); the tool (+Z) is R_x(-90) z = +Y in the part.
        let table = one_axis(
            KinematicsKind::Table,
            Axis::A,
            [1.0, 0.0, 0.0],
            [0.0, 0.0, -100.0],
        );
        let pose = table.forward(&with_a(0.0, 0.0, 0.0, 90.0), 0.0);
        assert!(close(pose.tip, [0.0, 100.0, -100.0]), "{pose:?}");
        assert!(close(pose.axis, [0.0, 1.0, 0.0]), "{pose:?}");
        let back = table.joints_for_tip(pose.tip, &with_a(5.0, 5.0, 5.0, 90.0), 0.0);
        assert!(close([back[0], back[1], back[2]], [0.0; 3]), "{back:?}");
    }

    #[test]
    fn one_rotary_axis_reaches_the_directions_on_its_cone_only() {
        // The A table shows the part the tool as R_x(-A) z = (0, sin A, cos A): (0, 1, 1) is
        // A = 45, (0, -1, 1) A = -45, and anything with an X part is out of reach.
        let mut table = one_axis(KinematicsKind::Table, Axis::A, [1.0, 0.0, 0.0], [0.0; 3]);
        let at_zero = with_a(0.0, 0.0, 0.0, 0.0);
        let a = table.orient([0.0, 1.0, 1.0], &at_zero).unwrap()[3];
        assert!((a - 45.0).abs() < 1e-9, "{a}");
        let a = table.orient([0.0, -1.0, 1.0], &at_zero).unwrap()[3];
        assert!((a + 45.0).abs() < 1e-9, "{a}");
        assert!(table.orient([1.0, 0.0, 1.0], &at_zero).is_none());
        // The limits refuse -45: no other angle gives that direction.
        table.joints[0].limits = (-30.0, 120.0);
        assert!(table.orient([0.0, -1.0, 1.0], &at_zero).is_none());
        // A whole turn away is nearer from 350: 405 is the same direction as 45.
        table.joints[0].limits = FREE;
        let a = table
            .orient([0.0, 1.0, 1.0], &with_a(0.0, 0.0, 0.0, 350.0))
            .unwrap()[3];
        assert!((a - 405.0).abs() < 1e-9, "{a}");
    }

    #[test]
    fn a_rotary_table_alone_keeps_its_angle_for_the_tool_along_it() {
        // A C table turns the part about the tool: +Z in the part at any C, and C stays put.
        let table = one_axis(KinematicsKind::Table, Axis::C, [0.0, 0.0, 1.0], [0.0; 3]);
        let joints = [0.0, 0.0, 0.0, 0.0, 0.0, 123.0];
        assert_eq!(table.orient([0.0, 0.0, 2.0], &joints).unwrap()[5], 123.0);
        assert!(table.orient([0.0, 1.0, 1.0], &joints).is_none());
    }

    #[test]
    fn a_tilting_head_alone_turns_the_tool_its_own_way() {
        // B head through the pivot 100 above the nose, a 50 mm tool: at B = 90 the tool points
        // along R_y(90) z = +X from the tip, so the tip is 150 along -X from the pivot, and the
        // inverse for +X is B = 90 (a head axis turns the tool by plus its angle).
        let head = one_axis(
            KinematicsKind::Head,
            Axis::B,
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 100.0],
        );
        let pose = head.forward(&at(0.0, 0.0, 0.0, 90.0, 0.0), 50.0);
        assert!(close(pose.tip, [-150.0, 0.0, 100.0]), "{pose:?}");
        let b = head
            .orient([1.0, 0.0, 0.0], &at(0.0, 0.0, 0.0, 0.0, 0.0))
            .unwrap()[4];
        assert!((b - 90.0).abs() < 1e-9, "{b}");
    }
}
