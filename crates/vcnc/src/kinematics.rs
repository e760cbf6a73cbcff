//! A 5-axis machine's kinematics: where the tool tip is and how the tool points, in the
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
//! direction that cannot be reached into their alarm). Table-table (A-C, B-C), head-head and
//! head-table machines with two rotary axes are what the machine file describes.

use crate::axis::{Axis, AxisLayout, AXES};
use serde::Deserialize;

/// A vector or point of X Y Z.
pub type Vec3 = [f64; 3];

/// Where the two rotary axes are.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum KinematicsKind {
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

/// A machine's kinematics: two rotary axes, where they sit and how the tool points at zero.
#[derive(Clone, Debug, PartialEq)]
pub struct Kinematics {
    /// Head or table axes.
    pub kind: KinematicsKind,
    /// The rotary axes from the machine's base outwards (the first carries the second; on a
    /// head-table machine the head's first).
    pub joints: [RotaryJoint; 2],
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
        let [first, second] = <[RotaryFile; 2]>::try_from(self.rotary).map_err(|rotary| {
            format!(
                "kinematics.rotary: expected two rotary axes, found {}",
                rotary.len()
            )
        })?;
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
        let joints = [joint(first)?, joint(second)?];
        if joints[0].axis == joints[1].axis {
            return Err("kinematics.rotary: the two rotary axes must differ".into());
        }
        if norm(cross(joints[0].direction, joints[1].direction)) < 1e-6 {
            return Err("kinematics.rotary: the two axes must not be parallel".into());
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

impl Kinematics {
    /// The two rotary axes, from the base outwards.
    pub fn rotary_axes(&self) -> [Axis; 2] {
        self.joints.map(|j| j.axis)
    }

    /// Which joints sit in the head (the others carry the part).
    fn in_head(&self) -> [bool; 2] {
        match self.kind {
            KinematicsKind::TableTable => [false, false],
            KinematicsKind::HeadHead => [true, true],
            KinematicsKind::HeadTable => [true, false],
        }
    }

    /// The angles of the two rotary axes in `joints`, degrees.
    fn angles(&self, joints: &[f64; AXES]) -> [f64; 2] {
        self.joints.map(|j| joints[j.axis.index()])
    }

    /// The tip's offset from the control point and the tool axis in machine coordinates, for a
    /// tool `length` long (from the tip to the control point along the tool) and the head at
    /// `angles`: the head's axes applied from the tool outwards.
    fn head(&self, angles: [f64; 2], length: f64) -> (Vec3, Vec3) {
        let mut tip = scale(self.tool_axis, -length);
        let mut axis = self.tool_axis;
        for (i, joint) in self.joints.iter().enumerate().rev() {
            if self.in_head()[i] {
                tip = turn_about(tip, joint.center, joint.direction, angles[i]);
                axis = rotate(axis, joint.direction, angles[i]);
            }
        }
        (tip, axis)
    }

    /// Where the table's axes at `angles` carry a workpiece point (or, `about_centre` false, a
    /// direction): from the part towards the base.
    fn table_to_machine(&self, mut p: Vec3, angles: [f64; 2], about_centre: bool) -> Vec3 {
        for (i, joint) in self.joints.iter().enumerate().rev() {
            if !self.in_head()[i] {
                p = match about_centre {
                    true => turn_about(p, joint.center, joint.direction, angles[i]),
                    false => rotate(p, joint.direction, angles[i]),
                };
            }
        }
        p
    }

    /// [`Kinematics::table_to_machine`] undone: a machine point (or direction) in the part.
    fn machine_to_table(&self, mut p: Vec3, angles: [f64; 2], about_centre: bool) -> Vec3 {
        for (i, joint) in self.joints.iter().enumerate() {
            if !self.in_head()[i] {
                p = match about_centre {
                    true => turn_about(p, joint.center, joint.direction, -angles[i]),
                    false => rotate(p, joint.direction, -angles[i]),
                };
            }
        }
        p
    }

    /// The forward transform: the tool tip and axis in the workpiece for the machine at
    /// `joints`, with a tool `length` long.
    pub fn forward(&self, joints: &[f64; AXES], length: f64) -> ToolPose {
        let angles = self.angles(joints);
        let (offset, axis) = self.head(angles, length);
        let control = [joints[0], joints[1], joints[2]];
        ToolPose {
            tip: self.machine_to_table(add(control, offset), angles, true),
            axis: self.machine_to_table(axis, angles, false),
        }
    }

    /// The inverse for a given orientation: the machine position that puts a tool `length` long
    /// with its tip at `tip` (workpiece coordinates), the rotary axes at their angles in
    /// `joints` (whose other axes are kept).
    pub fn joints_for_tip(&self, tip: Vec3, joints: &[f64; AXES], length: f64) -> [f64; AXES] {
        let angles = self.angles(joints);
        let (offset, _) = self.head(angles, length);
        let control = sub(self.table_to_machine(tip, angles, true), offset);
        let mut out = *joints;
        out[..3].copy_from_slice(&control);
        out
    }

    /// The inverse for a tool direction: the angles of the two rotary axes that point the tool
    /// along `direction` (workpiece coordinates), chosen by [`Kinematics::solution`] among the
    /// solutions within the axes' limits, next to `current`. `None` when no position of the
    /// axes gives that direction.
    pub fn angles_for(&self, direction: Vec3, current: [f64; 2]) -> Option<[f64; 2]> {
        let direction = unit(direction)?;
        // The chain as two turns of the tool axis: direction = R_outer(φo) R_inner(φi) k0. A table
        // axis turns the tool (seen from the part) by minus its angle, the base's last.
        let ([outer, inner], signs) = match self.kind {
            KinematicsKind::TableTable => ([1, 0], [-1.0, -1.0]),
            KinematicsKind::HeadHead => ([0, 1], [1.0, 1.0]),
            KinematicsKind::HeadTable => ([1, 0], [-1.0, 1.0]),
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
        let mut out = [0.0; 2];
        for i in 0..2 {
            let (min, max) = self.joints[i].limits;
            let near = current[i] + wrap(raw[i] - current[i]);
            // The nearest equivalent first, then a turn either way if the limits refuse it.
            out[i] = [near, near - 360.0, near + 360.0]
                .into_iter()
                .filter(|a| (min - 1e-9..=max + 1e-9).contains(a))
                .min_by(|x, y| (x - current[i]).abs().total_cmp(&(y - current[i]).abs()))?;
        }
        Some(out)
    }
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

fn unit(v: Vec3) -> Option<Vec3> {
    let n = norm(v);
    (n.is_finite() && n > DEGENERATE).then(|| scale(v, 1.0 / n))
}

fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(v: Vec3) -> f64 {
    dot(v, v).sqrt()
}

fn add(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn sub(a: Vec3, b: Vec3) -> Vec3 {
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
            joints: joints.map(|(axis, direction, center)| RotaryJoint {
                axis,
                direction,
                center,
                limits: FREE,
            }),
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
}
