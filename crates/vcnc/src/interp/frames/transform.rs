//! The frames of the coordinate chain: what one frame does to a point, and how it is undone.
//!
//! A frame is a [`Transform`] in a [`FrameSlot`]: a scaling or mirror about a centre, or a
//! rotation about a centre in the plane of any two axes (translations that follow the chain are
//! added into one shift, `mod.rs`). The ISO codes fill three slots (G51/G51.1, G68, Syntec's
//! G92.1 R); SINUMERIK's frames (TRANS, ROT, SCALE, MIRROR in the programmable and settable
//! frames) are to be compositions of such transforms in slots of their own. Each transform is applied in the
//! form the manual writes it (`c + f (x - c)`, `c + Rot (p - c)`), not as a matrix, so that a
//! program's positions come out exactly as the control's formula gives them.

use crate::machine::AXES;

/// Where a frame sits in the chain; the chain applies its frames in this order, from the
/// program's coordinates towards the machine's.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum FrameSlot {
    /// G51 scaling or G51.1 mirror (FANUC applies them before a rotation).
    Scaling,
    /// G68 coordinate rotation.
    Rotation,
    /// Syntec's G92.1 with K R: the program system turned about its new origin, outside G68.
    PresetRotation,
}

/// One frame of the chain.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Frame {
    pub(crate) slot: FrameSlot,
    pub(crate) transform: Transform,
}

/// What a frame does to a point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Transform {
    /// `p' = c + f (p - c)` per axis; a factor of -1 mirrors the axis.
    Scale(Scaling),
    /// `p' = c + Rot (p - c)` in the rotation's plane.
    Rotate(Rotation),
}

impl Transform {
    /// Moves `point` through the frame, towards the machine.
    pub(crate) fn apply(&self, point: &mut [f64; AXES]) {
        match self {
            Transform::Scale(scaling) => {
                for ((p, c), f) in point.iter_mut().zip(scaling.center).zip(scaling.factor) {
                    *p = c + (*p - c) * f;
                }
            }
            Transform::Rotate(rotation) => rotation.turn(point, rotation.sin),
        }
    }

    /// Moves `point` back through the frame, towards the program: [`Transform::apply`] undone.
    pub(crate) fn undo(&self, point: &mut [f64; AXES]) {
        match self {
            Transform::Scale(scaling) => {
                for ((p, c), f) in point.iter_mut().zip(scaling.center).zip(scaling.factor) {
                    *p = c + (*p - c) / f;
                }
            }
            Transform::Rotate(rotation) => rotation.turn(point, -rotation.sin),
        }
    }
}

/// G51 scaling or G51.1 mirror: each axis' programmed coordinate is stretched about a centre,
/// `x' = c + f (x - c)`; a factor of 1 leaves the axis alone, -1 mirrors it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Scaling {
    /// The centre, program coordinates.
    pub(crate) center: [f64; AXES],
    /// The factor of each axis (never zero).
    pub(crate) factor: [f64; AXES],
    /// G51.1 rather than G51 (for messages).
    pub(crate) mirror: bool,
}

impl Scaling {
    /// An arc's centre offset in the plane axes `(a, b)`: each component takes its axis' sign and
    /// the larger of the two factors' sizes, so that a circle stays a circle (Syntec spec 1.28:
    /// unequal factors scale an arc by the largest one).
    pub(crate) fn arc_vector(&self, (a, b): (usize, usize), (x, y): (f64, f64)) -> (f64, f64) {
        let size = self.arc_factor((a, b));
        (
            x * size * self.factor[a].signum(),
            y * size * self.factor[b].signum(),
        )
    }

    /// How much an arc's radius grows in the plane axes `(a, b)`.
    pub(crate) fn arc_factor(&self, (a, b): (usize, usize)) -> f64 {
        self.factor[a].abs().max(self.factor[b].abs())
    }

    /// True when exactly one of the plane axes `(a, b)` is reversed: arcs turn the other way.
    pub(crate) fn reverses(&self, (a, b): (usize, usize)) -> bool {
        (self.factor[a] < 0.0) != (self.factor[b] < 0.0)
    }
}

/// The sine and cosine of an angle in degrees, exact for quarter turns: a program rotated by 90
/// degrees, or a hole at 90 degrees in polar coordinates, ends on round numbers.
pub(crate) fn sin_cos_degrees(degrees: f64) -> (f64, f64) {
    let turn = degrees.rem_euclid(360.0);
    if turn == 0.0 {
        (0.0, 1.0)
    } else if turn == 90.0 {
        (1.0, 0.0)
    } else if turn == 180.0 {
        (0.0, -1.0)
    } else if turn == 270.0 {
        (-1.0, 0.0)
    } else {
        degrees.to_radians().sin_cos()
    }
}

/// G68: a rotation of program coordinates in a plane, about a centre (spec 1.37:
/// p' = c + Rot(R) (p - c), positive angles counter-clockwise seen from the plane's normal).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Rotation {
    /// The plane's first and second axis (as `Plane::axes` orders them).
    pub(crate) axes: (usize, usize),
    /// The centre, program coordinates of the two axes.
    pub(crate) center: (f64, f64),
    /// The angle, degrees.
    pub(crate) degrees: f64,
    pub(super) cos: f64,
    pub(super) sin: f64,
}

impl Rotation {
    pub(crate) fn new(axes: (usize, usize), center: (f64, f64), degrees: f64) -> Rotation {
        let (sin, cos) = sin_cos_degrees(degrees);
        Rotation {
            axes,
            center,
            degrees,
            cos,
            sin,
        }
    }

    /// A vector (an arc's centre offset I J K) turned by the rotation.
    pub(crate) fn vector(&self, (x, y): (f64, f64)) -> (f64, f64) {
        (x * self.cos - y * self.sin, x * self.sin + y * self.cos)
    }

    /// Turns `point` about the centre; `sin` is the rotation's own for the forward turn and its
    /// negative for the inverse.
    pub(super) fn turn(&self, point: &mut [f64; AXES], sin: f64) {
        let (a, b) = self.axes;
        let (x, y) = (point[a] - self.center.0, point[b] - self.center.1);
        point[a] = self.center.0 + x * self.cos - y * sin;
        point[b] = self.center.1 + x * sin + y * self.cos;
    }
}
