//! The frames of the coordinate chain: what one frame does to a point, and how it is undone.
//!
//! A frame is a [`Transform`] in a [`FrameSlot`]: a scaling or mirror about a centre, a
//! rotation about a centre in the plane of any two axes, or a general affine map of the geometry
//! axes (translations that follow the chain are added into one shift, `mod.rs`). The ISO codes
//! fill three slots (G51/G51.1, G68, Syntec's G92.1 R) and never the affine one; SINUMERIK's
//! programmable frame (TRANS, ROT, SCALE, MIRROR, `interp/sinumerik/frame.rs`) is one [`Affine`]
//! in a slot of its own. The ISO transforms are applied in the form the manual writes them
//! (`c + f (x - c)`, `c + Rot (p - c)`), not as a matrix, so that a program's positions come out
//! exactly as the control's formula gives them; the SINUMERIK manual gives its frames as
//! components whose product is a matrix, so a matrix is their form.

use crate::machine::AXES;
use crate::motion::invert;

/// Where a frame sits in the chain; the chain applies its frames in this order, from the
/// program's coordinates towards the machine's.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum FrameSlot {
    /// SINUMERIK's programmable frame (`$P_PFRAME`): the first frame a program point meets, WCS to
    /// SZS (docs/SINUMERIK.md 5.1); the settable frame's translation is the shift after the chain.
    Programmable,
    /// SINUMERIK's swivel frame (CYCLE800, `sinumerik/cycles/swivel.rs`): a system frame, after
    /// the programmable one towards the machine.
    Swivel,
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
    /// `p' = L p + t` on X Y Z, `p' = p + t` on the other axes.
    #[cfg_attr(not(test), allow(dead_code))] // wired in by the SINUMERIK front end (issue 20)
    Affine(Affine),
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
            Transform::Affine(affine) => *point = affine.apply(point),
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
            Transform::Affine(affine) => *point = affine.undo(point),
        }
    }
}

/// A general affine map of the geometry axes X Y Z, `p' = L p + t`, with the other axes (A B C)
/// only translated: the SINUMERIK frame `parent = T + R S M p` multiplied out
/// (docs/SINUMERIK.md 5.2). Its inverse is kept beside it, since every block maps a point back.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Affine {
    /// `L`, row by row: `L[i][j]` is how much child axis `j` moves parent axis `i`.
    linear: [[f64; 3]; 3],
    /// `L` inverted.
    inverse: [[f64; 3]; 3],
    /// `t`, per axis of the machine.
    translation: [f64; AXES],
}

/// How far from zero an entry of a linear map may be and still count as zero: rounding of sines
/// and products of a few rotations stays near 1e-16 per unit; programs write no more than
/// micrometre digits, far above this.
#[cfg_attr(not(test), allow(dead_code))]
const ZERO: f64 = 1e-12;

#[cfg_attr(not(test), allow(dead_code))] // wired in by the SINUMERIK front end (issue 20)
impl Affine {
    /// The map `p' = linear p + translation`; `None` when `linear` cannot be inverted (a scale
    /// factor of zero) or holds a number that is not finite.
    pub(crate) fn new(linear: [[f64; 3]; 3], translation: [f64; AXES]) -> Option<Affine> {
        let inverse = invert(&linear)?;
        translation.iter().all(|t| t.is_finite()).then_some(Affine {
            linear,
            inverse,
            translation,
        })
    }

    /// The linear part `L`, row by row.
    pub(crate) fn linear(&self) -> &[[f64; 3]; 3] {
        &self.linear
    }

    /// The translation `t`.
    pub(crate) fn translation(&self) -> &[f64; AXES] {
        &self.translation
    }

    /// The image of `point`, towards the machine.
    pub(crate) fn apply(&self, point: &[f64; AXES]) -> [f64; AXES] {
        let mut image: [f64; AXES] = std::array::from_fn(|i| point[i] + self.translation[i]);
        let turned = multiply(&self.linear, [point[0], point[1], point[2]]);
        for (i, value) in turned.into_iter().enumerate() {
            image[i] = value + self.translation[i];
        }
        image
    }

    /// The point whose image is `image`: [`Affine::apply`] undone.
    pub(crate) fn undo(&self, image: &[f64; AXES]) -> [f64; AXES] {
        let mut point: [f64; AXES] = std::array::from_fn(|i| image[i] - self.translation[i]);
        let back = multiply(&self.inverse, [point[0], point[1], point[2]]);
        point[..3].copy_from_slice(&back);
        point
    }

    /// The linear part seen in the plane of axes `(a, b)` (first and second, as
    /// `Plane::axes` orders them): the 2x2 block `[[L_aa, L_ab], [L_ba, L_bb]]`.
    fn in_plane(&self, (a, b): (usize, usize)) -> [[f64; 2]; 2] {
        let l = &self.linear;
        [[l[a][a], l[a][b]], [l[b][a], l[b][b]]]
    }

    /// True when the map turns the plane of axes `(a, b)` over: seen from the plane's normal, a
    /// counter-clockwise arc comes out clockwise (one plane axis mirrored, or a half turn about an
    /// axis of the plane). Meaningful where [`Affine::keeps_plane`] holds.
    pub(crate) fn reverses(&self, (a, b): (usize, usize)) -> bool {
        let [[p, q], [r, s]] = self.in_plane((a, b));
        p * s - q * r < 0.0
    }

    /// True when an arc in the plane of axes `(a, b)` stays a circular arc in the same machine
    /// plane, with its helix axis along the plane's normal: the plane is mapped parallel to
    /// itself (nothing of `a` or `b` leaks into the normal axis and nothing of the normal into
    /// `a` or `b`) and scaled by the same factor in every direction (the 2x2 block is a turn,
    /// or a turn and a mirror, times one factor). A SINUMERIK front end alarms otherwise.
    pub(crate) fn keeps_plane(&self, (a, b): (usize, usize)) -> bool {
        let normal = 3 - a - b;
        let l = &self.linear;
        let size = l.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        let zero = |v: f64| v.abs() <= ZERO * size;
        // Products of two entries are compared with the square of the size.
        let zero_product = |v: f64| v.abs() <= ZERO * size * size;
        let [[p, q], [r, s]] = self.in_plane((a, b));
        // Columns (p, r) and (q, s) of equal length and at right angles: a similarity.
        let similar = zero_product(p * p + r * r - q * q - s * s) && zero_product(p * q + r * s);
        similar
            && zero(l[normal][a])
            && zero(l[normal][b])
            && zero(l[a][normal])
            && zero(l[b][normal])
    }

    /// The machine plane onto which the plane of axes `(a, b)` maps its circles as circles when
    /// the frame turns it onto another coordinate plane (`ROT Y90` takes X-Y onto Y-Z), and
    /// whether its arcs then turn the other way there (seen from that plane's normal, in its
    /// `Plane::axes` order): None where no coordinate plane takes the image whole (a tilt by
    /// other than quarter turns, uneven scaling) and where the plane stays itself
    /// ([`Affine::keeps_plane`] covers that case).
    pub(crate) fn plane_image(&self, (a, b): (usize, usize)) -> Option<((usize, usize), bool)> {
        let normal = 3 - a - b;
        let l = &self.linear;
        let size = l.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        let zero = |v: f64| v.abs() <= ZERO * size;
        // The machine axis the plane's normal goes to, alone.
        let onto = (0..3).find(|&m| !zero(l[m][normal]))?;
        if onto == normal || (0..3).any(|m| m != onto && !zero(l[m][normal])) {
            return None;
        }
        // The machine plane of that normal, in `Plane::axes` order: Y-Z for X, Z-X for Y, X-Y
        // for Z.
        let (c, d) = match onto {
            0 => (1, 2),
            1 => (2, 0),
            _ => (0, 1),
        };
        if !zero(l[onto][a]) || !zero(l[onto][b]) {
            return None;
        }
        let [[p, q], [r, s]] = [[l[c][a], l[c][b]], [l[d][a], l[d][b]]];
        let zero_product = |v: f64| v.abs() <= ZERO * size * size;
        let similar = zero_product(p * p + r * r - q * q - s * s) && zero_product(p * q + r * s);
        similar.then_some(((c, d), p * s - q * r < 0.0))
    }

    /// How much a length in the plane of axes `(a, b)` grows through the map (a radius `CR`):
    /// the length of the image of a unit vector along `a`. Meaningful where
    /// [`Affine::keeps_plane`] holds.
    pub(crate) fn plane_factor(&self, (a, b): (usize, usize)) -> f64 {
        let [[p, _], [r, _]] = self.in_plane((a, b));
        p.hypot(r)
    }
}

/// `matrix · vector`, a 3x3 matrix given row by row.
pub(crate) fn multiply(matrix: &[[f64; 3]; 3], vector: [f64; 3]) -> [f64; 3] {
    matrix.map(|row| row[0] * vector[0] + row[1] * vector[1] + row[2] * vector[2])
}

/// G51 scaling or G51.1 mirror: each axis' programmed coordinate is stretched about a centre,
/// `x' = c + f (x - c)`; a factor of 1 leaves the axis alone, -1 mirrors it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Scaling {
    /// The centre, program coordinates.
    pub(crate) center: [f64; AXES],
    /// The factor of each axis (never zero).
    pub(crate) factor: [f64; AXES],
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
