//! SINUMERIK's programmable frame (`$P_PFRAME`): its components and the frame instructions that
//! set them (docs/SINUMERIK.md 5.2-5.4).
//!
//! The frame is kept as the components the control shows - coarse translation T, fine
//! translation Tf, rotation R, scale factors S, mirror flags M - and maps a WCS point p to the
//! SZS as `T + Tf + R·S·M·p` on X Y Z (the other axes are only translated). Each instruction
//! changes the components by the rules of 5.3 (replacing: clear everything, then set one part;
//! additive: compose in the current WCS) and 5.4 (G58/G59). [`ProgrammableFrame::to_affine`]
//! multiplies the components out for the kernel's chain (`FrameSlot::Programmable`).
//!
//! It knows nothing of blocks, words or spans: the front end reads an instruction's values and
//! turns a [`FrameError`] into an alarm. An instruction that fails leaves the frame as it was.
//! It never touches the settable or basic frames, nor the position.

#![cfg_attr(not(test), allow(dead_code))] // wired in by the front end (issue 20)

use crate::interp::frames::{multiply, sin_cos_degrees, Affine};
use crate::machine::AXES;
use crate::motion::Plane;

/// A 3x3 matrix of the geometry axes, row by row.
type Matrix = [[f64; 3]; 3];

const IDENTITY: Matrix = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// The largest translation a frame holds, mm: the kernel's position limit, so that a frame
/// that passes never makes a position the kernel could not have been given.
const TRANSLATION_LIMIT: f64 = 1.0e9;

/// The range of a scale factor's size (**choice**: the manual gives none; this keeps the
/// frame's matrix and its inverse finite, and no part is scaled a billion times).
const SCALE_LIMITS: (f64, f64) = (1.0e-9, 1.0e9);

/// How far an entry of R may be from the identity's and still count as no rotation: a turn and
/// its reverse leave about 1e-16.
const ROTATION_TOLERANCE: f64 = 1.0e-12;

/// Why a frame instruction was refused; the frame stays as it was.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum FrameError {
    /// A translation (written, or the sum an ATRANS, G58 or G59 makes) beyond ±1e9 mm or not a
    /// number, or an angle that is not a number; `axis` is the axis whose value it is.
    OutOfRange { axis: usize },
    /// A scale factor of zero, not a number, or (after ASCALE's product) outside 1e-9..1e9 in
    /// size.
    BadScaleFactor { axis: usize },
    /// ROTS/AROTS with three angles: two solid angles define a plane (PGsl 12.5, L8971-9037).
    ThreeSolidAngles,
    /// ROTS/AROTS whose two traces lie on one line (both angles ±90): no plane.
    NoSolidAnglePlane,
}

impl FrameError {
    /// The alarm's message.
    pub(crate) fn message(self) -> String {
        const NAMES: [&str; AXES] = ["X", "Y", "Z", "A", "B", "C"];
        match self {
            FrameError::OutOfRange { axis } => format!(
                "the frame's value for {} is out of range (translations are limited to ±1e9 mm)",
                NAMES[axis]
            ),
            FrameError::BadScaleFactor { axis } => format!(
                "the scale factor of {} must be non-zero, between 1e-9 and 1e9 in size",
                NAMES[axis]
            ),
            FrameError::ThreeSolidAngles => {
                "ROTS and AROTS take two solid angles, not three".to_string()
            }
            FrameError::NoSolidAnglePlane => {
                "the two solid angles define no plane (both are ±90 degrees)".to_string()
            }
        }
    }
}

/// The programmable frame, as `$P_PFRAME` holds it. The default is the identity (no frame).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ProgrammableFrame {
    /// T: TRANS and G58.
    coarse: [f64; AXES],
    /// Tf: ATRANS and G59 (kept apart as if MD24000 = 1, docs/SINUMERIK.md 5.4).
    fine: [f64; AXES],
    /// R, a rotation (orthonormal, determinant 1).
    rotation: Matrix,
    /// S, each factor positive: a negative factor is kept as its size and a mirror.
    scale: [f64; 3],
    /// M: the axes whose direction is reversed.
    mirror: [bool; 3],
}

impl Default for ProgrammableFrame {
    fn default() -> Self {
        ProgrammableFrame {
            coarse: [0.0; AXES],
            fine: [0.0; AXES],
            rotation: IDENTITY,
            scale: [1.0; 3],
            mirror: [false; 3],
        }
    }
}

impl ProgrammableFrame {
    /// No frame: `TRANS`, `ROT`, `SCALE`, `MIRROR` without axes (PGsl 12.9).
    pub(crate) fn clear(&mut self) {
        *self = ProgrammableFrame::default();
    }

    /// TRANS: the frame cleared, then the coarse translation of the named axes; the others get
    /// 0 (rule 1). TRANS clears the fine part too (**choice**, docs/SINUMERIK.md 5.4: PGsl
    /// 12.3.1 says TRANS resets every component, the table of L8709-8727 keeps the fine part).
    ///
    /// # Errors
    /// [`FrameError::OutOfRange`] for a value beyond ±1e9 mm.
    pub(crate) fn trans(&mut self, offsets: [Option<f64>; AXES]) -> Result<(), FrameError> {
        let coarse = checked_translation(offsets.map(|v| v.unwrap_or(0.0)))?;
        *self = ProgrammableFrame {
            coarse,
            ..ProgrammableFrame::default()
        };
        Ok(())
    }

    /// ATRANS: the offset along the current WCS axes added to the fine part, `Tf += R·S·M·t`
    /// (rules 1, 4, 7: after a rotation it runs along the turned axes, after a scale it is
    /// scaled); A B C are added as written.
    ///
    /// # Errors
    /// [`FrameError::OutOfRange`] when a sum leaves ±1e9 mm.
    pub(crate) fn atrans(&mut self, offsets: [Option<f64>; AXES]) -> Result<(), FrameError> {
        let offsets = offsets.map(|v| v.unwrap_or(0.0));
        let along = multiply(&self.linear(), [offsets[0], offsets[1], offsets[2]]);
        let fine =
            std::array::from_fn(|i| self.fine[i] + if i < 3 { along[i] } else { offsets[i] });
        self.fine = checked_translation(fine)?;
        Ok(())
    }

    /// G58 (840D): the coarse translation of the named axes replaced; the fine part and the other
    /// components stay (PGsl 12.3.2, L8613-8727). Along the SZS axes, not turned by R.
    ///
    /// # Errors
    /// [`FrameError::OutOfRange`] for a value beyond ±1e9 mm.
    pub(crate) fn g58(&mut self, offsets: [Option<f64>; AXES]) -> Result<(), FrameError> {
        let coarse = std::array::from_fn(|i| offsets[i].unwrap_or(self.coarse[i]));
        self.coarse = checked_translation(coarse)?;
        Ok(())
    }

    /// G59 (840D): the fine translation of the named axes replaced; the rest stays.
    ///
    /// # Errors
    /// [`FrameError::OutOfRange`] for a value beyond ±1e9 mm.
    pub(crate) fn g59(&mut self, offsets: [Option<f64>; AXES]) -> Result<(), FrameError> {
        let fine = std::array::from_fn(|i| offsets[i].unwrap_or(self.fine[i]));
        self.fine = checked_translation(fine)?;
        Ok(())
    }

    /// ROT X Y Z: the frame cleared, then `R = Rz(z)·Ry(y)·Rx(x)` whatever the order of the words
    /// (RPY, MD10600 default; rule 5); an axis not named turns by 0.
    ///
    /// # Errors
    /// [`FrameError::OutOfRange`] for an angle that is not a number.
    pub(crate) fn rot(&mut self, degrees: [Option<f64>; 3]) -> Result<(), FrameError> {
        let rotation = rpy(checked_angles(degrees)?);
        *self = ProgrammableFrame {
            rotation,
            ..ProgrammableFrame::default()
        };
        Ok(())
    }

    /// TOFRAME (`rotation_only` false): the frame cleared, then turned by `rotation`; TOROT
    /// (true): the rotation replaced, translations, scale and mirror kept (PGsl 4.8).
    ///
    /// # Errors
    /// [`FrameError::OutOfRange`] for a rotation that is not a number.
    pub(crate) fn tool_frame(
        &mut self,
        rotation: Matrix,
        rotation_only: bool,
    ) -> Result<(), FrameError> {
        if rotation.iter().flatten().any(|v| !v.is_finite()) {
            return Err(FrameError::OutOfRange { axis: 0 });
        }
        if !rotation_only {
            *self = ProgrammableFrame::default();
        }
        self.rotation = rotation;
        Ok(())
    }

    /// AROT X Y Z: `R := R·Rz(z)·Ry(y)·Rx(x)`, a turn about the current zero and the already
    /// turned axes (rules 3 and 5).
    ///
    /// # Errors
    /// [`FrameError::OutOfRange`] for an angle that is not a number.
    pub(crate) fn arot(&mut self, degrees: [Option<f64>; 3]) -> Result<(), FrameError> {
        let turn = rpy(checked_angles(degrees)?);
        self.rotation = product(&self.rotation, &turn);
        Ok(())
    }

    /// ROT RPL=a (and ROTS RPL=a): the frame cleared, then a turn about the normal of `plane`,
    /// positive from its first axis towards its second (G17 Rz, G18 Ry, G19 Rx; rule 5).
    ///
    /// # Errors
    /// [`FrameError::OutOfRange`] for an angle that is not a number.
    pub(crate) fn rot_rpl(&mut self, plane: Plane, degrees: f64) -> Result<(), FrameError> {
        let rotation = plane_turn(plane, checked_angle(degrees, plane.axes().2)?);
        *self = ProgrammableFrame {
            rotation,
            ..ProgrammableFrame::default()
        };
        Ok(())
    }

    /// AROT RPL=a (and AROTS RPL=a): `R := R·turn`, the turn of [`ProgrammableFrame::rot_rpl`].
    ///
    /// # Errors
    /// [`FrameError::OutOfRange`] for an angle that is not a number.
    pub(crate) fn arot_rpl(&mut self, plane: Plane, degrees: f64) -> Result<(), FrameError> {
        let turn = plane_turn(plane, checked_angle(degrees, plane.axes().2)?);
        self.rotation = product(&self.rotation, &turn);
        Ok(())
    }

    /// ROTS with two solid angles: the frame cleared, then the rotation whose plane they define
    /// ([`solid_angle_rotation`]; PGsl 12.5, L8971-9037). One angle alone is ROT of that axis.
    ///
    /// # Errors
    /// [`FrameError::ThreeSolidAngles`], [`FrameError::NoSolidAnglePlane`],
    /// [`FrameError::OutOfRange`] for an angle that is not a number.
    pub(crate) fn rots(&mut self, degrees: [Option<f64>; 3]) -> Result<(), FrameError> {
        let rotation = solid_angle_rotation(degrees)?;
        *self = ProgrammableFrame {
            rotation,
            ..ProgrammableFrame::default()
        };
        Ok(())
    }

    /// AROTS: `R := R·solid`, the rotation of [`ProgrammableFrame::rots`] in the current WCS.
    ///
    /// # Errors
    /// Those of [`ProgrammableFrame::rots`].
    pub(crate) fn arots(&mut self, degrees: [Option<f64>; 3]) -> Result<(), FrameError> {
        let turn = solid_angle_rotation(degrees)?;
        self.rotation = product(&self.rotation, &turn);
        Ok(())
    }

    /// SCALE X Y Z: the frame cleared, then the factors of the named axes (the others keep 1),
    /// about the SZS zero (rule 7). A negative factor scales by its size and mirrors the axis
    /// (**choice**, docs/SINUMERIK.md 5.3 rule 7).
    ///
    /// # Errors
    /// [`FrameError::BadScaleFactor`] for a factor of 0 or beyond 1e-9..1e9 in size.
    pub(crate) fn scale(&mut self, factors: [Option<f64>; 3]) -> Result<(), FrameError> {
        let mut frame = ProgrammableFrame::default();
        frame.multiply_scale(factors)?;
        *self = frame;
        Ok(())
    }

    /// ASCALE X Y Z: each named axis' factor multiplied by the new one (rule 7).
    ///
    /// # Errors
    /// [`FrameError::BadScaleFactor`] for a factor of 0, or a product beyond 1e-9..1e9 in size.
    pub(crate) fn ascale(&mut self, factors: [Option<f64>; 3]) -> Result<(), FrameError> {
        let mut frame = *self;
        frame.multiply_scale(factors)?;
        *self = frame;
        Ok(())
    }

    /// MIRROR X0 Y0 Z0: the frame cleared, then the named axes reversed; the written values are
    /// ignored (MD10612 = 0, rule 6).
    pub(crate) fn mirror(&mut self, axes: [bool; 3]) {
        *self = ProgrammableFrame {
            mirror: axes,
            ..ProgrammableFrame::default()
        };
    }

    /// AMIRROR: the named axes' mirroring toggled (rule 6).
    pub(crate) fn amirror(&mut self, axes: [bool; 3]) {
        for (flag, toggle) in self.mirror.iter_mut().zip(axes) {
            *flag ^= toggle;
        }
    }

    /// The SZS point of the WCS point `point`: `T + Tf + R·S·M·p` on X Y Z, `T + Tf + p` on the
    /// other axes.
    pub(crate) fn map(&self, point: &[f64; AXES]) -> [f64; AXES] {
        let turned = multiply(&self.linear(), [point[0], point[1], point[2]]);
        let translation = self.translation();
        std::array::from_fn(|i| translation[i] + if i < 3 { turned[i] } else { point[i] })
    }

    /// The WCS point of the SZS point `parent`: [`ProgrammableFrame::map`] undone,
    /// `p = M·S⁻¹·Rᵀ·(parent - T - Tf)` (R is a rotation, so Rᵀ undoes it).
    pub(crate) fn unmap(&self, parent: &[f64; AXES]) -> [f64; AXES] {
        let translation = self.translation();
        let moved: [f64; AXES] = std::array::from_fn(|i| parent[i] - translation[i]);
        let r = &self.rotation;
        let back: [f64; 3] =
            std::array::from_fn(|j| (0..3).map(|i| r[i][j] * moved[i]).sum::<f64>());
        std::array::from_fn(|i| {
            if i < 3 {
                back[i] / self.scale[i] * self.mirror_sign(i)
            } else {
                moved[i]
            }
        })
    }

    /// True when the frame moves nothing.
    pub(crate) fn is_identity(&self) -> bool {
        self.translation().iter().all(|&t| t == 0.0)
            && !self.has_rotation()
            && self.scale == [1.0; 3]
            && self.mirror == [false; 3]
    }

    /// True when R is not the identity (docs/SINUMERIK.md 6.4 rule 3: then a block moves every
    /// geometry axis).
    pub(crate) fn has_rotation(&self) -> bool {
        self.rotation
            .iter()
            .zip(IDENTITY)
            .flat_map(|(row, unit)| row.iter().zip(unit))
            .any(|(r, u)| (r - u).abs() > ROTATION_TOLERANCE)
    }

    /// The translation per axis, `T + Tf` (`$P_PFRAME[X,TR]` plus `[X,FI]`).
    pub(crate) fn translation(&self) -> [f64; AXES] {
        std::array::from_fn(|i| self.coarse[i] + self.fine[i])
    }

    /// The coarse translation T (`$P_PFRAME[X,TR]`).
    pub(crate) fn coarse(&self) -> [f64; AXES] {
        self.coarse
    }

    /// The fine translation Tf (`$P_PFRAME[X,FI]`).
    pub(crate) fn fine(&self) -> [f64; AXES] {
        self.fine
    }

    /// The rotation R, row by row.
    pub(crate) fn rotation(&self) -> &Matrix {
        &self.rotation
    }

    /// The rotation read back as RPY angles X Y Z, normalised as the control does: X and Z in
    /// -180..180, Y in -90..90; at Y = ±90 (where only Z - X or Z + X is defined) X reads 0
    /// (PGsl 12.4, L8962-8968: `CROT(X,10,Y,90,Z,40)` reads back `CROT(X,0,Y,90,Z,30)`).
    pub(crate) fn rpy_degrees(&self) -> [f64; 3] {
        let r = &self.rotation;
        // R = Rz(z)·Ry(y)·Rx(x): row 2 is (-sin y, cos y sin x, cos y cos x), column 0 is
        // cos y (cos z, sin z, ·).
        let y = (-r[2][0]).clamp(-1.0, 1.0).asin();
        let cos_y = r[2][1].hypot(r[2][2]);
        let (x, z) = if cos_y > 1.0e-9 {
            (r[2][1].atan2(r[2][2]), r[1][0].atan2(r[0][0]))
        } else {
            // With x = 0, row 0 column 1 is -sin z and row 1 column 1 cos z, at y = 90 and -90.
            (0.0, (-r[0][1]).atan2(r[1][1]))
        };
        [x, y, z].map(|a| {
            let degrees = a.to_degrees();
            // atan2 gives -180 for a half turn written 180; the control's range holds both.
            if degrees == -180.0 {
                180.0
            } else {
                degrees
            }
        })
    }

    /// The scale factors S (each positive; a negative factor shows as its size and a mirror).
    pub(crate) fn scale_factors(&self) -> [f64; 3] {
        self.scale
    }

    /// The mirror flags M.
    pub(crate) fn mirrored(&self) -> [bool; 3] {
        self.mirror
    }

    /// The frame multiplied out for the kernel's chain (`Frames::set_programmable`): the linear
    /// part `R·S·M` and the translation `T + Tf`; `None` for the identity, so that a program
    /// without frames keeps the chain empty.
    pub(crate) fn to_affine(self) -> Option<Affine> {
        if self.is_identity() {
            return None;
        }
        // Every instruction keeps the translations within ±1e9 mm and the factors within
        // 1e-9..1e9, so the matrix is finite and can be inverted.
        Affine::new(self.linear(), self.translation())
    }

    /// `R·S·M`.
    fn linear(&self) -> Matrix {
        let diagonal: [f64; 3] = std::array::from_fn(|j| self.scale[j] * self.mirror_sign(j));
        self.rotation
            .map(|row| std::array::from_fn(|j| row[j] * diagonal[j]))
    }

    fn mirror_sign(&self, axis: usize) -> f64 {
        if self.mirror[axis] {
            -1.0
        } else {
            1.0
        }
    }

    /// Multiplies the named axes' factors; a negative factor toggles the axis' mirror.
    fn multiply_scale(&mut self, factors: [Option<f64>; 3]) -> Result<(), FrameError> {
        let (low, high) = SCALE_LIMITS;
        for (axis, factor) in factors.into_iter().enumerate() {
            let Some(factor) = factor else { continue };
            let size = self.scale[axis] * factor.abs();
            if !(low..=high).contains(&size) {
                return Err(FrameError::BadScaleFactor { axis });
            }
            self.scale[axis] = size;
            self.mirror[axis] ^= factor < 0.0;
        }
        Ok(())
    }
}

/// The translation `values`, or the first axis beyond the limit.
fn checked_translation(values: [f64; AXES]) -> Result<[f64; AXES], FrameError> {
    match values
        .iter()
        .position(|v| v.is_nan() || v.abs() > TRANSLATION_LIMIT)
    {
        Some(axis) => Err(FrameError::OutOfRange { axis }),
        None => Ok(values),
    }
}

/// An angle that is a number, or the error naming `axis`.
fn checked_angle(degrees: f64, axis: usize) -> Result<f64, FrameError> {
    if degrees.is_finite() {
        Ok(degrees)
    } else {
        Err(FrameError::OutOfRange { axis })
    }
}

/// The angles of X Y Z, 0 where none is written.
fn checked_angles(degrees: [Option<f64>; 3]) -> Result<[f64; 3], FrameError> {
    let mut angles = [0.0; 3];
    for (axis, angle) in degrees.into_iter().enumerate() {
        if let Some(angle) = angle {
            angles[axis] = checked_angle(angle, axis)?;
        }
    }
    Ok(angles)
}

/// The turn by `degrees` about the geometry axis `axis`, right-handed (PGsl 12.4, L8881-8882).
fn axis_turn(axis: usize, degrees: f64) -> Matrix {
    let (sin, cos) = sin_cos_degrees(degrees);
    // In the plane of the two other axes taken cyclically, (a, b) -> (a cos - b sin, ...):
    // about X from Y to Z, about Y from Z to X, about Z from X to Y.
    let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
    let mut turn = IDENTITY;
    turn[a][a] = cos;
    turn[a][b] = -sin;
    turn[b][a] = sin;
    turn[b][b] = cos;
    turn
}

/// `Rz(z)·Ry(y)·Rx(x)` of the angles `[x, y, z]`.
fn rpy([x, y, z]: [f64; 3]) -> Matrix {
    product(
        &product(&axis_turn(2, z), &axis_turn(1, y)),
        &axis_turn(0, x),
    )
}

/// RPL's turn: about the normal of `plane`, from its first axis towards its second. The axes
/// of `Plane::axes` are cyclic (X Y, Z X, Y Z), so this is the right-handed turn about the
/// normal.
fn plane_turn(plane: Plane, degrees: f64) -> Matrix {
    axis_turn(plane.axes().2, degrees)
}

/// ROTS/AROTS with solid angles (PGsl 12.5, L8971-9037; docs/SINUMERIK.md 5.3 rule 5, the
/// geometry inferred in the spec's part B 4.5). For the pair X a, Y b: the new X axis is
/// `u = (cos b, 0, -sin b)`, X turned by b about Y (the plane's trace in the old Z/X plane);
/// the plane also holds `v = (0, cos a, sin a)`, Y turned by a about X; new Z = `u × v`
/// normalised, new Y = Z × X. The pairs Y Z (new Y in the old X/Y plane) and Z X (new Z in the
/// old Y/Z plane) are the same with the axes taken cyclically. The pair is named by the two
/// angles written; one angle alone is a plain turn about its axis (both readings agree).
fn solid_angle_rotation(degrees: [Option<f64>; 3]) -> Result<Matrix, FrameError> {
    let written = degrees.iter().filter(|d| d.is_some()).count();
    if written == 3 {
        return Err(FrameError::ThreeSolidAngles);
    }
    let angles = checked_angles(degrees)?;
    // The first axis of the cyclic pair: X for X Y (and for X or Y alone), Y for Y Z (and Z
    // alone), Z for Z X.
    let first = match degrees.map(|d| d.is_some()) {
        [_, true, true] | [false, false, true] => 1,
        [true, false, true] => 2,
        _ => 0,
    };
    let (second, third) = ((first + 1) % 3, (first + 2) % 3);
    let unit = |axis: usize| IDENTITY[axis];
    let u = multiply(&axis_turn(second, angles[second]), unit(first));
    let v = multiply(&axis_turn(first, angles[first]), unit(second));
    let normal = cross(u, v);
    let length = normal.iter().map(|n| n * n).sum::<f64>().sqrt();
    if length < 1.0e-9 {
        return Err(FrameError::NoSolidAnglePlane);
    }
    let new_third = normal.map(|n| n / length);
    let new_second = cross(new_third, u);
    let mut rotation = [[0.0; 3]; 3];
    for (axis, column) in [(first, u), (second, new_second), (third, new_third)] {
        for (row, value) in column.into_iter().enumerate() {
            rotation[row][axis] = value;
        }
    }
    Ok(rotation)
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn product(left: &Matrix, right: &Matrix) -> Matrix {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| left[i][k] * right[k][j]).sum()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::interp::frames::Frames;
    use crate::machine::Machine;
    use crate::motion::ArcDirection;
    use proptest::prelude::*;

    /// The settable frame of docs/SINUMERIK.md 5.3's rules: G54 = X100 Y50 Z0.
    const G54: [f64; 3] = [100.0, 50.0, 0.0];

    /// The words of an instruction, `"XYZABC"` letters with their values.
    fn words(pairs: &[(char, f64)]) -> [Option<f64>; AXES] {
        let mut values = [None; AXES];
        for &(letter, value) in pairs {
            let axis = "XYZABC".find(letter).expect("an axis letter");
            values[axis] = Some(value);
        }
        values
    }

    /// The angles or factors of X Y Z.
    fn xyz(pairs: &[(char, f64)]) -> [Option<f64>; 3] {
        let values = words(pairs);
        [values[0], values[1], values[2]]
    }

    fn frame() -> ProgrammableFrame {
        ProgrammableFrame::default()
    }

    /// Where `G0 X Y Z` goes on the machine under `frame` and G54 (no tool length).
    fn machine(frame: &ProgrammableFrame, [x, y, z]: [f64; 3]) -> [f64; 3] {
        let szs = frame.map(&[x, y, z, 0.0, 0.0, 0.0]);
        std::array::from_fn(|i| szs[i] + G54[i])
    }

    /// The SZS point of the WCS zero: where the frame puts the program's zero.
    fn zero(frame: &ProgrammableFrame) -> [f64; 3] {
        let szs = frame.map(&[0.0; AXES]);
        [szs[0], szs[1], szs[2]]
    }

    #[track_caller]
    fn assert_near(actual: [f64; 3], expected: [f64; 3], tolerance: f64) {
        for (a, e) in actual.iter().zip(expected) {
            assert!(
                (a - e).abs() <= tolerance,
                "{actual:?} is not {expected:?} (within {tolerance})"
            );
        }
    }

    /// The image of a WCS axis direction: the column of R·S·M.
    fn axis_image(frame: &ProgrammableFrame, axis: usize) -> [f64; 3] {
        let mut point = [0.0; AXES];
        point[axis] = 1.0;
        let (image, origin) = (frame.map(&point), frame.map(&[0.0; AXES]));
        std::array::from_fn(|i| image[i] - origin[i])
    }

    // Rule 1 and ex. B-60 (examples/sinumerik-b/60-trans-milling.mpf): the second TRANS
    // replaces the first: zero at G54 + (50, 10), not + (60, 20).
    #[test]
    fn a_second_trans_replaces_the_first() {
        let mut f = frame();
        f.trans(words(&[('X', 10.0), ('Y', 10.0)])).unwrap();
        assert_near(machine(&f, [0.0; 3]), [110.0, 60.0, 0.0], 1e-12);
        f.trans(words(&[('X', 50.0), ('Y', 10.0)])).unwrap();
        assert_near(machine(&f, [0.0; 3]), [150.0, 60.0, 0.0], 1e-12);
    }

    // Rule 1: TRANS X10 Y10 / ATRANS X5 / G0 X0 Y0 -> X115 Y60.
    #[test]
    fn atrans_adds_to_the_translation() {
        let mut f = frame();
        f.trans(words(&[('X', 10.0), ('Y', 10.0)])).unwrap();
        f.atrans(words(&[('X', 5.0)])).unwrap();
        assert_near(machine(&f, [0.0; 3]), [115.0, 60.0, 0.0], 1e-12);
    }

    // Rule 1: axes not named in TRANS get 0: TRANS X10 Y10 Z10 / TRANS X5 -> zero X5 Y0 Z0.
    #[test]
    fn trans_gives_zero_to_the_axes_it_does_not_name() {
        let mut f = frame();
        f.trans(words(&[('X', 10.0), ('Y', 10.0), ('Z', 10.0)]))
            .unwrap();
        f.trans(words(&[('X', 5.0)])).unwrap();
        assert_eq!(f.translation(), [5.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    }

    // Ex. B-61 (61-trans-turning.mpf): TRANS X0 Z150, then TRANS X0 Z140 "or ATRANS Z-10",
    // then Z130: both forms put the zero at Z150, Z140, Z130.
    #[test]
    fn trans_and_atrans_give_the_turning_example_zeros() {
        let (mut replacing, mut adding) = (frame(), frame());
        replacing.trans(words(&[('X', 0.0), ('Z', 150.0)])).unwrap();
        adding.trans(words(&[('X', 0.0), ('Z', 150.0)])).unwrap();
        for z in [140.0, 130.0] {
            replacing.trans(words(&[('X', 0.0), ('Z', z)])).unwrap();
            adding.atrans(words(&[('Z', -10.0)])).unwrap();
            assert_eq!(zero(&replacing), [0.0, 0.0, z]);
            assert_eq!(zero(&adding), [0.0, 0.0, z]);
        }
    }

    // Rule 2: TRANS X10 / ROT RPL=90 / G0 X10 Y0 -> X100 Y60 (the ROT deleted the translation;
    // (10, 0) turned by 90 is (0, 10)).
    #[test]
    fn rot_clears_the_translation() {
        let mut f = frame();
        f.trans(words(&[('X', 10.0)])).unwrap();
        f.rot_rpl(Plane::Xy, 90.0).unwrap();
        assert_near(machine(&f, [10.0, 0.0, 0.0]), [100.0, 60.0, 0.0], 1e-12);
    }

    // Rule 2: ROT RPL=90 / TRANS X10 / G0 X10 Y0 -> X120 Y50 (the TRANS deleted the rotation).
    #[test]
    fn trans_clears_the_rotation() {
        let mut f = frame();
        f.rot_rpl(Plane::Xy, 90.0).unwrap();
        f.trans(words(&[('X', 10.0)])).unwrap();
        assert!(!f.has_rotation());
        assert_near(machine(&f, [10.0, 0.0, 0.0]), [120.0, 50.0, 0.0], 1e-12);
    }

    // Rule 3: TRANS X10 / AROT RPL=90 / G0 X10 Y0: (10, 0) turned is (0, 10), plus the zero
    // (10, 0): X110 Y60.
    #[test]
    fn arot_turns_about_the_translated_zero() {
        let mut f = frame();
        f.trans(words(&[('X', 10.0)])).unwrap();
        f.arot_rpl(Plane::Xy, 90.0).unwrap();
        assert_near(machine(&f, [10.0, 0.0, 0.0]), [110.0, 60.0, 0.0], 1e-12);
    }

    // Ex. B-63 (63-rot-plane.mpf): N20 zero (20, 10) unturned; N40-N50 zero (55, 35) turned 45;
    // N70-N80 zero (20, 40) turned 60 (the TRANS deleted the 45); N100 G0 X100 Y100:
    // X = 20 + 100 cos 60 - 100 sin 60 = -16.603, Y = 40 + 100 sin 60 + 100 cos 60 = 176.603
    // from the G54 zero, X83.397 Y226.603 on the machine.
    #[test]
    fn the_plane_rotation_example_ends_where_the_manual_says() {
        let mut f = frame();
        f.trans(words(&[('X', 20.0), ('Y', 10.0)])).unwrap();
        assert!(!f.has_rotation());
        f.trans(words(&[('X', 55.0), ('Y', 35.0)])).unwrap();
        f.arot_rpl(Plane::Xy, 45.0).unwrap();
        assert_near(zero(&f), [55.0, 35.0, 0.0], 1e-12);
        assert_near(f.rpy_degrees(), [0.0, 0.0, 45.0], 1e-12);
        f.trans(words(&[('X', 20.0), ('Y', 40.0)])).unwrap();
        f.arot_rpl(Plane::Xy, 60.0).unwrap();
        assert_near(f.rpy_degrees(), [0.0, 0.0, 60.0], 1e-12);
        let szs = f.map(&[100.0, 100.0, 0.0, 0.0, 0.0, 0.0]);
        assert_near([szs[0], szs[1], szs[2]], [-16.603, 176.603, 0.0], 5e-4);
        assert_near(
            machine(&f, [100.0, 100.0, 0.0]),
            [83.397, 226.603, 0.0],
            5e-4,
        );
    }

    // Rule 4: ROT RPL=90 / ATRANS X10: the translation runs along the turned X, i.e. +Y:
    // G0 X0 Y0 -> X100 Y60; G0 X10 Y0 -> (0, 10) + (0, 10) -> X100 Y70.
    #[test]
    fn atrans_after_a_rotation_runs_along_the_turned_axes() {
        let mut f = frame();
        f.rot_rpl(Plane::Xy, 90.0).unwrap();
        f.atrans(words(&[('X', 10.0)])).unwrap();
        assert_near(machine(&f, [0.0; 3]), [100.0, 60.0, 0.0], 1e-12);
        assert_near(machine(&f, [10.0, 0.0, 0.0]), [100.0, 70.0, 0.0], 1e-12);
    }

    // Ex. B-64 (64-rot-spatial.mpf): TRANS X10 Y10 / ATRANS X35 / AROT Y30 / ATRANS X5: the
    // last 5 along the turned X, (cos 30, 0, -sin 30): zero at (45 + 4.330, 10, -2.5) =
    // X49.330 Y10 Z-2.5 from G54, new X axis (0.866, 0, -0.5).
    #[test]
    fn the_spatial_rotation_example_puts_the_zero_where_the_manual_says() {
        let mut f = frame();
        f.trans(words(&[('X', 10.0), ('Y', 10.0)])).unwrap();
        f.atrans(words(&[('X', 35.0)])).unwrap();
        f.arot(xyz(&[('Y', 30.0)])).unwrap();
        f.atrans(words(&[('X', 5.0)])).unwrap();
        assert_near(zero(&f), [49.330, 10.0, -2.5], 5e-4);
        let half = 3f64.sqrt() / 2.0;
        assert_near(axis_image(&f, 0), [half, 0.0, -0.5], 1e-12);
        assert_eq!(f.coarse()[..3], [10.0, 10.0, 0.0]);
    }

    // Rule 5: ROT X90 Z90 is Rz(90)·Rx(90) whatever the order of the words: (10, 0, 0) stays
    // under Rx and goes to +Y under Rz: X100 Y60 Z0.
    #[test]
    fn rot_turns_about_x_then_y_then_z() {
        let mut f = frame();
        f.rot(xyz(&[('Z', 90.0), ('X', 90.0)])).unwrap();
        assert_near(machine(&f, [10.0, 0.0, 0.0]), [100.0, 60.0, 0.0], 1e-12);
        assert_near(f.rpy_degrees(), [90.0, 0.0, 90.0], 1e-12);
    }

    // Rule 5: AROT X90 then AROT Z90 is Rx(90)·Rz(90): (10, 0, 0) -> (0, 10, 0) by Rz, then
    // -> (0, 0, 10) by Rx: X100 Y50 Z10.
    #[test]
    fn successive_arots_turn_about_the_turned_axes() {
        let mut f = frame();
        f.arot(xyz(&[('X', 90.0)])).unwrap();
        f.arot(xyz(&[('Z', 90.0)])).unwrap();
        assert_near(machine(&f, [10.0, 0.0, 0.0]), [100.0, 50.0, 10.0], 1e-12);
    }

    // Ex. B-65 (65-rot-multi-face.mpf): TRANS X100 Z-100 / AROT Y90 / AROT Z90: R = Ry(90)·Rz(90)
    // takes X to Ry(90)·Y = +Y, Y to Ry(90)·(-X) = +Z, Z to Ry(90)·Z = +X; zero (100, 0, -100).
    #[test]
    fn the_multi_face_example_turns_the_axes_onto_the_side_face() {
        let mut f = frame();
        f.trans(words(&[('X', 100.0), ('Z', -100.0)])).unwrap();
        f.arot(xyz(&[('Y', 90.0)])).unwrap();
        f.arot(xyz(&[('Z', 90.0)])).unwrap();
        assert_eq!(zero(&f), [100.0, 0.0, -100.0]);
        assert_near(axis_image(&f, 0), [0.0, 1.0, 0.0], 1e-12);
        assert_near(axis_image(&f, 1), [0.0, 0.0, 1.0], 1e-12);
        assert_near(axis_image(&f, 2), [1.0, 0.0, 0.0], 1e-12);
    }

    // Rule 5: RPL turns about the normal of the plane in force, from its first axis to its
    // second: G18 (Z, X) turns Z towards X (Ry), G19 (Y, Z) turns Y towards Z (Rx).
    #[test]
    fn rpl_turns_in_the_plane_in_force() {
        let mut f = frame();
        f.rot_rpl(Plane::Zx, 90.0).unwrap();
        assert_near(axis_image(&f, 2), [1.0, 0.0, 0.0], 1e-12);
        assert_near(f.rpy_degrees(), [0.0, 90.0, 0.0], 1e-12);
        f.rot_rpl(Plane::Yz, 90.0).unwrap();
        assert_near(axis_image(&f, 1), [0.0, 0.0, 1.0], 1e-12);
        assert_near(f.rpy_degrees(), [90.0, 0.0, 0.0], 1e-12);
    }

    // Rule 5 and PGsl 12.4, L8962-8968: CROT(X,190,Y,0,Z,-200) reads back X-170 Y0 Z160
    // (190 - 360, -200 + 360); CROT(X,10,Y,90,Z,40) reads back X0 Y90 Z30 (at Y90 only Z - X
    // is defined).
    #[test]
    fn rotations_read_back_normalised_like_the_manual() {
        let mut f = frame();
        f.rot(xyz(&[('X', 190.0), ('Y', 0.0), ('Z', -200.0)]))
            .unwrap();
        assert_near(f.rpy_degrees(), [-170.0, 0.0, 160.0], 1e-9);
        f.rot(xyz(&[('X', 10.0), ('Y', 90.0), ('Z', 40.0)]))
            .unwrap();
        assert_near(f.rpy_degrees(), [0.0, 90.0, 30.0], 1e-9);
    }

    // Rule 5, ROTS X30 Y45: u = (cos 45, 0, -sin 45) = (0.707107, 0, -0.707107),
    // v = (0, cos 30, sin 30) = (0, 0.866025, 0.5); u x v = (0.612372, -0.353553, 0.612372),
    // length sqrt(0.875) = 0.935414, new Z = (0.654654, -0.377964, 0.654654); new Y = Z x X =
    // (0.267261, 0.925820, 0.267261).
    #[test]
    fn rots_turns_onto_the_plane_of_two_solid_angles() {
        let mut f = frame();
        f.rots(xyz(&[('X', 30.0), ('Y', 45.0)])).unwrap();
        let root_half = std::f64::consts::FRAC_1_SQRT_2;
        assert_near(axis_image(&f, 0), [root_half, 0.0, -root_half], 1e-12);
        assert_near(axis_image(&f, 1), [0.267261, 0.925820, 0.267261], 1e-6);
        assert_near(axis_image(&f, 2), [0.654654, -0.377964, 0.654654], 1e-6);
    }

    // Rule 5, the cyclic pairs: ROTS Y0 Z30 puts the new Y at Rz(30)·Y = (-0.5, 0.866, 0), in
    // the old X/Y plane; ROTS Z0 X30 puts the new Z at Rx(30)·Z = (0, -0.5, 0.866), in the old
    // Y/Z plane. With the other angle 0 both are plain turns.
    #[test]
    fn rots_of_the_other_pairs_are_cyclic() {
        let half = 3f64.sqrt() / 2.0;
        let mut f = frame();
        f.rots(xyz(&[('Y', 0.0), ('Z', 30.0)])).unwrap();
        assert_near(axis_image(&f, 1), [-0.5, half, 0.0], 1e-12);
        f.rots(xyz(&[('Z', 0.0), ('X', 30.0)])).unwrap();
        assert_near(axis_image(&f, 2), [0.0, -0.5, half], 1e-12);
        // ROTS Y20 Z30: new Y = (-sin 30, cos 30, 0), the trace in the X/Y plane.
        f.rots(xyz(&[('Y', 20.0), ('Z', 30.0)])).unwrap();
        assert_near(axis_image(&f, 1), [-0.5, half, 0.0], 1e-12);
    }

    // One solid angle alone is the plain turn about its axis.
    #[test]
    fn rots_with_one_angle_is_rot() {
        for axis in 0..3 {
            let mut angles = [None; 3];
            angles[axis] = Some(25.0);
            let (mut solid, mut plain) = (frame(), frame());
            solid.rots(angles).unwrap();
            plain.rot(angles).unwrap();
            for (s, p) in solid
                .rotation()
                .iter()
                .flatten()
                .zip(plain.rotation().iter().flatten())
            {
                assert!((s - p).abs() < 1e-12, "axis {axis}");
            }
        }
    }

    // AROTS composes in the current WCS like AROT: TRANS X10 / AROTS X0 Y90 turns about Y at
    // (10, 0, 0): the point X0 Y0 Z10 goes to (10 + 10, 0, 0).
    #[test]
    fn arots_adds_to_the_frame() {
        let mut f = frame();
        f.trans(words(&[('X', 10.0)])).unwrap();
        f.arots(xyz(&[('X', 0.0), ('Y', 90.0)])).unwrap();
        assert_near(zero(&f), [10.0, 0.0, 0.0], 1e-12);
        let szs = f.map(&[0.0, 0.0, 10.0, 0.0, 0.0, 0.0]);
        assert_near([szs[0], szs[1], szs[2]], [20.0, 0.0, 0.0], 1e-12);
    }

    // Ex. B-67 (67-mirror-milling.mpf) and rule 6: MIRROR X0 / G0 X10 Y5 -> X90 Y55; AMIRROR Y0
    // -> X90 Y45; MIRROR Y0 (replacing) -> X110 Y45; MIRROR -> no frame, X110 Y55.
    #[test]
    fn the_mirror_example_puts_the_contour_in_each_quadrant() {
        let point = [10.0, 5.0, 0.0];
        let mut f = frame();
        f.mirror([true, false, false]);
        assert_near(machine(&f, point), [90.0, 55.0, 0.0], 1e-12);
        f.amirror([false, true, false]);
        assert_near(machine(&f, point), [90.0, 45.0, 0.0], 1e-12);
        f.mirror([false, true, false]);
        assert_near(machine(&f, point), [110.0, 45.0, 0.0], 1e-12);
        assert_eq!(f.mirrored(), [false, true, false]);
        f.mirror([false; 3]);
        assert!(f.is_identity());
        assert_near(machine(&f, point), [110.0, 55.0, 0.0], 1e-12);
    }

    // Ex. B-68 (68-mirror-turning.mpf) and rule 6: TRANS Z600 / AMIRROR Z0 / ATRANS Z120: the
    // 120 runs along the mirrored Z: zero at SZS Z480, and Z10 of the program is Z470.
    #[test]
    fn atrans_after_a_mirror_runs_the_other_way() {
        let mut f = frame();
        f.trans(words(&[('X', 0.0), ('Z', 140.0)])).unwrap();
        f.trans(words(&[('X', 0.0), ('Z', 600.0)])).unwrap();
        f.amirror([false, false, true]);
        f.atrans(words(&[('Z', 120.0)])).unwrap();
        assert_eq!(zero(&f), [0.0, 0.0, 480.0]);
        assert_eq!(machine(&f, [0.0, 0.0, 10.0]), [100.0, 50.0, 470.0]);
    }

    // Rule 6, the component rule: MIRROR X0 / AROT RPL=30 / G0 X10 Y0 -> R30·(-10, 0) =
    // (-8.660, -5.000) from G54: X91.340 Y45.000.
    #[test]
    fn arot_after_a_mirror_turns_the_mirrored_point() {
        let mut f = frame();
        f.mirror([true, false, false]);
        f.arot_rpl(Plane::Xy, 30.0).unwrap();
        assert_near(machine(&f, [10.0, 0.0, 0.0]), [91.340, 45.0, 0.0], 5e-4);
    }

    // Rule 7: SCALE X2 Y2 / ATRANS X10: the 10 is scaled to 20: G0 X0 Y0 -> X120 Y50,
    // G0 X5 Y5 -> (10 + 20, 10) -> X130 Y60.
    #[test]
    fn atrans_after_a_scale_is_scaled() {
        let mut f = frame();
        f.scale(xyz(&[('X', 2.0), ('Y', 2.0)])).unwrap();
        f.atrans(words(&[('X', 10.0)])).unwrap();
        assert_eq!(machine(&f, [0.0; 3]), [120.0, 50.0, 0.0]);
        assert_eq!(machine(&f, [5.0, 5.0, 0.0]), [130.0, 60.0, 0.0]);
    }

    // Rule 7: TRANS X10 / ASCALE X2 Y2 / G0 X5 Y5: scaled about the translated zero,
    // (10 + 10, 10) -> X120 Y60; Z keeps factor 1.
    #[test]
    fn ascale_scales_about_the_translated_zero() {
        let mut f = frame();
        f.trans(words(&[('X', 10.0)])).unwrap();
        f.ascale(xyz(&[('X', 2.0), ('Y', 2.0)])).unwrap();
        assert_eq!(machine(&f, [5.0, 5.0, 3.0]), [120.0, 60.0, 3.0]);
        assert_eq!(f.scale_factors(), [2.0, 2.0, 1.0]);
    }

    // Ex. B-66 (66-scale.mpf): TRANS X40 Y20 / AROT RPL=35 / ASCALE X0.7 Y0.7 / G0 X300 Y100:
    // scaled (210, 70), turned: X = 40 + 210 cos 35 - 70 sin 35 = 171.872,
    // Y = 20 + 210 sin 35 + 70 cos 35 = 197.792 from the G54 zero.
    #[test]
    fn the_scale_example_ends_where_the_manual_says() {
        let mut f = frame();
        f.trans(words(&[('X', 15.0), ('Y', 15.0)])).unwrap();
        f.trans(words(&[('X', 40.0), ('Y', 20.0)])).unwrap();
        f.arot_rpl(Plane::Xy, 35.0).unwrap();
        f.ascale(xyz(&[('X', 0.7), ('Y', 0.7)])).unwrap();
        let szs = f.map(&[300.0, 100.0, 0.0, 0.0, 0.0, 0.0]);
        assert_near([szs[0], szs[1], szs[2]], [171.872, 197.792, 0.0], 5e-4);
    }

    // Rule 7 (choice): a negative factor scales by its size and mirrors: SCALE X-2 reads back
    // factor 2 with X mirrored, and X5 goes to -10.
    #[test]
    fn a_negative_factor_scales_and_mirrors() {
        let mut f = frame();
        f.scale(xyz(&[('X', -2.0)])).unwrap();
        assert_eq!(f.scale_factors(), [2.0, 1.0, 1.0]);
        assert_eq!(f.mirrored(), [true, false, false]);
        assert_eq!(machine(&f, [5.0, 0.0, 0.0]), [90.0, 50.0, 0.0]);
        // ASCALE X-1 toggles the mirror back.
        f.ascale(xyz(&[('X', -1.0)])).unwrap();
        assert_eq!(f.mirrored(), [false; 3]);
    }

    // Ex. B-62 (62-g58-g59.mpf): TRANS X10 Y10 Z10 -> X10 Y10 Z10; ATRANS X5 Y5 -> fine X5 Y5,
    // total X15 Y15 Z10; G58 X20 -> coarse X20, total X25 Y15 Z10; G59 X10 Y10 -> fine X10 Y10,
    // total X30 Y20 Z10.
    #[test]
    fn g58_and_g59_replace_the_coarse_and_fine_parts() {
        let mut f = frame();
        f.trans(words(&[('X', 10.0), ('Y', 10.0), ('Z', 10.0)]))
            .unwrap();
        assert_eq!(zero(&f), [10.0, 10.0, 10.0]);
        f.atrans(words(&[('X', 5.0), ('Y', 5.0)])).unwrap();
        assert_eq!(zero(&f), [15.0, 15.0, 10.0]);
        assert_eq!(f.fine()[..3], [5.0, 5.0, 0.0]);
        f.g58(words(&[('X', 20.0)])).unwrap();
        assert_eq!(zero(&f), [25.0, 15.0, 10.0]);
        f.g59(words(&[('X', 10.0), ('Y', 10.0)])).unwrap();
        assert_eq!(zero(&f), [30.0, 20.0, 10.0]);
        assert_eq!(f.coarse()[..3], [20.0, 10.0, 10.0]);
        assert_eq!(f.fine()[..3], [10.0, 10.0, 0.0]);
    }

    // 5.4: G58/G59 act along the SZS axes, not turned by R: ROT RPL=90 / G58 X10 puts the zero
    // at SZS X10, where ATRANS X10 would have put it at Y10.
    #[test]
    fn g58_is_not_turned_by_the_rotation() {
        let mut f = frame();
        f.rot_rpl(Plane::Xy, 90.0).unwrap();
        f.g58(words(&[('X', 10.0)])).unwrap();
        assert_eq!(zero(&f), [10.0, 0.0, 0.0]);
        assert!(f.has_rotation());
    }

    // Rotary axes are only translated: TRANS A30 / AROT RPL=90 / ATRANS A5 -> A35 for A0.
    #[test]
    fn rotary_axes_are_only_translated() {
        let mut f = frame();
        f.trans(words(&[('A', 30.0)])).unwrap();
        f.arot_rpl(Plane::Xy, 90.0).unwrap();
        f.atrans(words(&[('A', 5.0)])).unwrap();
        assert_eq!(f.map(&[0.0; AXES])[3], 35.0);
        assert_eq!(f.unmap(&[0.0, 0.0, 0.0, 35.0, 0.0, 0.0])[3], 0.0);
    }

    // 5.3 and PGsl 12.9: the words without axes delete the whole frame.
    #[test]
    fn the_words_without_axes_clear_the_frame() {
        let mut f = frame();
        f.trans(words(&[('X', 10.0)])).unwrap();
        f.arot_rpl(Plane::Xy, 30.0).unwrap();
        f.ascale(xyz(&[('X', 2.0)])).unwrap();
        f.amirror([false, true, false]);
        assert!(!f.is_identity() && f.to_affine().is_some());
        f.rot([None; 3]).unwrap();
        assert!(f.is_identity() && f.to_affine().is_none());
        for clear in [
            |f: &mut ProgrammableFrame| f.trans([None; AXES]).unwrap(),
            |f: &mut ProgrammableFrame| f.scale([None; 3]).unwrap(),
            |f: &mut ProgrammableFrame| f.mirror([false; 3]),
            ProgrammableFrame::clear,
        ] {
            let mut g = frame();
            g.trans(words(&[('Y', 1.0)])).unwrap();
            g.amirror([true, false, false]);
            clear(&mut g);
            assert!(g.is_identity());
        }
    }

    // A turn and its reverse leave rounding in R, but no rotation.
    #[test]
    fn a_turn_and_its_reverse_is_no_rotation() {
        let mut f = frame();
        f.arot(xyz(&[('X', 33.0), ('Y', -17.0), ('Z', 71.0)]))
            .unwrap();
        f.arot(xyz(&[('X', -33.0)])).unwrap();
        f.arot(xyz(&[('Y', 17.0)])).unwrap();
        assert!(f.has_rotation());
        f.arot(xyz(&[('Z', -71.0)])).unwrap();
        assert!(!f.has_rotation() && f.is_identity());
    }

    #[test]
    fn refused_instructions_leave_the_frame_as_it_was() {
        let mut f = frame();
        f.trans(words(&[('X', 10.0)])).unwrap();
        f.ascale(xyz(&[('X', 2.0)])).unwrap();
        let before = f;
        assert_eq!(
            f.scale(xyz(&[('Y', 0.0)])),
            Err(FrameError::BadScaleFactor { axis: 1 })
        );
        assert_eq!(
            f.ascale(xyz(&[('Y', 3.0), ('Z', f64::NAN)])),
            Err(FrameError::BadScaleFactor { axis: 2 })
        );
        // 2 x 1e9 leaves the range of factors.
        assert_eq!(
            f.ascale(xyz(&[('X', 1.0e9)])),
            Err(FrameError::BadScaleFactor { axis: 0 })
        );
        assert_eq!(
            f.rots(xyz(&[('X', 1.0), ('Y', 2.0), ('Z', 3.0)])),
            Err(FrameError::ThreeSolidAngles)
        );
        assert_eq!(
            f.arots(xyz(&[('X', 90.0), ('Y', -90.0)])),
            Err(FrameError::NoSolidAnglePlane)
        );
        assert_eq!(
            f.trans(words(&[('B', 2.0e9)])),
            Err(FrameError::OutOfRange { axis: 4 })
        );
        // The ATRANS X6e8 is scaled by 2: 1.2e9 beyond the limit.
        assert_eq!(
            f.atrans(words(&[('X', 6.0e8)])),
            Err(FrameError::OutOfRange { axis: 0 })
        );
        assert_eq!(
            f.g59(words(&[('Z', f64::INFINITY)])),
            Err(FrameError::OutOfRange { axis: 2 })
        );
        assert_eq!(
            f.arot(xyz(&[('Z', f64::NAN)])),
            Err(FrameError::OutOfRange { axis: 2 })
        );
        assert_eq!(
            f.arot_rpl(Plane::Zx, f64::NAN),
            Err(FrameError::OutOfRange { axis: 1 })
        );
        assert_eq!(f, before);
        assert!(FrameError::BadScaleFactor { axis: 1 }
            .message()
            .contains("scale factor of Y"));
    }

    /// The kernel's chain with G54 at X100 Y50 Z0 and `frame` as the programmable frame.
    fn chain(frame: &ProgrammableFrame) -> Frames {
        let mut frames = Frames::new(&Machine::default());
        frames.set_programmable(frame.to_affine());
        frames
    }

    // The frame in the kernel's chain comes before the settable frame: the machine point is
    // the frame's SZS point through the chain without it (G54, external offset, length), and
    // the chain maps it back.
    #[test]
    fn the_frame_in_the_chain_comes_before_the_work_offset() {
        let mut f = frame();
        f.trans(words(&[('X', 10.0), ('A', 5.0)])).unwrap();
        f.arot_rpl(Plane::Xy, 30.0).unwrap();
        f.ascale(xyz(&[('X', -1.5), ('Y', 1.5)])).unwrap();
        let (framed, plain) = (chain(&f), chain(&frame()));
        let point = [12.0, -7.0, 3.0, 40.0, 0.0, 0.0];
        let machine = framed.to_machine(&point, 25.0);
        let expected = plain.to_machine(&f.map(&point), 25.0);
        for (m, e) in machine.iter().zip(expected) {
            assert!((m - e).abs() < 1e-12, "{machine:?} is not {expected:?}");
        }
        let mut back_chain = framed.clone();
        back_chain.set_length_vector(25.0);
        let back = back_chain.to_program(&machine);
        for (b, p) in back.iter().zip(point) {
            assert!((b - p).abs() < 1e-9, "{back:?} is not {point:?}");
        }
    }

    // Rule 6: one mirrored plane axis swaps G2 and G3; two cancel; a half turn about X turns
    // the XY plane over too (Y and Z reversed).
    #[test]
    fn a_mirrored_or_overturned_plane_reverses_arcs() {
        let xy = (0, 1);
        let direction = |f: &ProgrammableFrame| chain(f).arc_direction(xy, ArcDirection::Clockwise);
        let mut f = frame();
        f.mirror([true, false, false]);
        assert_eq!(direction(&f), ArcDirection::CounterClockwise);
        f.amirror([false, true, false]);
        assert_eq!(direction(&f), ArcDirection::Clockwise);
        f.rot(xyz(&[('X', 180.0)])).unwrap();
        assert_eq!(direction(&f), ArcDirection::CounterClockwise);
        f.rot_rpl(Plane::Xy, 123.0).unwrap();
        assert_eq!(direction(&f), ArcDirection::Clockwise);
    }

    // An arc stays a circle in a machine plane when the frame keeps its plane parallel and
    // scales it evenly: ROT RPL=30 with SCALE X2 Y2 Z5 does for G17 (factor 2) but not for G18
    // (Z5 against X2); ROT X90 takes the XY plane onto XZ; SCALE X2 Y3 distorts the circle.
    #[test]
    fn arcs_stay_circles_only_in_planes_the_frame_keeps() {
        let (xy, zx) = (Plane::Xy.axes(), Plane::Zx.axes());
        let (xy, zx) = ((xy.0, xy.1), (zx.0, zx.1));
        let mut f = frame();
        f.scale(xyz(&[('X', 2.0), ('Y', 2.0), ('Z', 5.0)])).unwrap();
        f.arot_rpl(Plane::Xy, 30.0).unwrap();
        let affine = f.to_affine().unwrap();
        assert!(affine.keeps_plane(xy) && !affine.keeps_plane(zx));
        assert!((affine.plane_factor(xy) - 2.0).abs() < 1e-12);
        f.rot(xyz(&[('X', 90.0)])).unwrap();
        let affine = f.to_affine().unwrap();
        assert!(!affine.keeps_plane(xy) && affine.keeps_plane((1, 2)));
        f.scale(xyz(&[('X', 2.0), ('Y', 3.0)])).unwrap();
        assert!(!f.to_affine().unwrap().keeps_plane(xy));
    }

    /// One frame instruction, for the property test.
    #[derive(Clone, Debug)]
    enum Instruction {
        Trans([Option<f64>; AXES]),
        Atrans([Option<f64>; AXES]),
        G58([Option<f64>; AXES]),
        G59([Option<f64>; AXES]),
        Rot([Option<f64>; 3]),
        Arot([Option<f64>; 3]),
        RotRpl(usize, f64),
        ArotRpl(usize, f64),
        /// The pair's first axis (0 X Y, 1 Y Z, 2 Z X) and its two angles.
        Rots(usize, f64, f64),
        Arots(usize, f64, f64),
        Scale([Option<f64>; 3]),
        Ascale([Option<f64>; 3]),
        Mirror([bool; 3]),
        Amirror([bool; 3]),
    }

    const PLANES: [Plane; 3] = [Plane::Xy, Plane::Zx, Plane::Yz];

    fn instruction() -> impl Strategy<Value = Instruction> {
        let offsets = prop::array::uniform6(prop::option::of(-500.0f64..500.0));
        let angles = prop::array::uniform3(prop::option::of(-400.0f64..400.0));
        let factor = prop_oneof![0.5f64..2.0, -2.0f64..-0.5];
        let factors = prop::array::uniform3(prop::option::of(factor));
        let flags = prop::array::uniform3(any::<bool>());
        let angle = -180.0f64..180.0;
        prop_oneof![
            offsets.clone().prop_map(Instruction::Trans),
            offsets.clone().prop_map(Instruction::Atrans),
            offsets.clone().prop_map(Instruction::G58),
            offsets.prop_map(Instruction::G59),
            angles.clone().prop_map(Instruction::Rot),
            angles.prop_map(Instruction::Arot),
            (0usize..3, angle.clone()).prop_map(|(p, a)| Instruction::RotRpl(p, a)),
            (0usize..3, angle.clone()).prop_map(|(p, a)| Instruction::ArotRpl(p, a)),
            (0usize..3, angle.clone(), angle.clone())
                .prop_map(|(i, a, b)| Instruction::Rots(i, a, b)),
            (0usize..3, angle.clone(), angle).prop_map(|(i, a, b)| Instruction::Arots(i, a, b)),
            factors.clone().prop_map(Instruction::Scale),
            factors.prop_map(Instruction::Ascale),
            flags.prop_map(Instruction::Mirror),
            flags.prop_map(Instruction::Amirror),
        ]
    }

    /// The angles of a solid-angle pair as ROTS takes them.
    fn pair_angles(first: usize, a: f64, b: f64) -> [Option<f64>; 3] {
        let mut angles = [None; 3];
        angles[first] = Some(a);
        angles[(first + 1) % 3] = Some(b);
        angles
    }

    /// The frame under test: `Err` when it refused the instruction.
    fn apply(frame: &mut ProgrammableFrame, instruction: &Instruction) -> Result<(), FrameError> {
        match *instruction {
            Instruction::Trans(t) => frame.trans(t),
            Instruction::Atrans(t) => frame.atrans(t),
            Instruction::G58(t) => frame.g58(t),
            Instruction::G59(t) => frame.g59(t),
            Instruction::Rot(r) => frame.rot(r),
            Instruction::Arot(r) => frame.arot(r),
            Instruction::RotRpl(p, a) => frame.rot_rpl(PLANES[p], a),
            Instruction::ArotRpl(p, a) => frame.arot_rpl(PLANES[p], a),
            Instruction::Rots(i, a, b) => frame.rots(pair_angles(i, a, b)),
            Instruction::Arots(i, a, b) => frame.arots(pair_angles(i, a, b)),
            Instruction::Scale(s) => frame.scale(s),
            Instruction::Ascale(s) => frame.ascale(s),
            Instruction::Mirror(m) => {
                frame.mirror(m);
                Ok(())
            }
            Instruction::Amirror(m) => {
                frame.amirror(m);
                Ok(())
            }
        }
    }

    /// An independent model of the frame: its components as 4x4 homogeneous matrices, composed
    /// by the rules of docs/SINUMERIK.md 5.3's last paragraph, rotations built by Rodrigues'
    /// formula about each axis, ROTS as a turn about the pair's second axis then about the
    /// turned first axis.
    mod model {
        pub(super) type H = [[f64; 4]; 4];

        pub(super) fn identity() -> H {
            std::array::from_fn(|i| std::array::from_fn(|j| if i == j { 1.0 } else { 0.0 }))
        }

        pub(super) fn product(a: &H, b: &H) -> H {
            std::array::from_fn(|i| {
                std::array::from_fn(|j| (0..4).map(|k| a[i][k] * b[k][j]).sum())
            })
        }

        pub(super) fn apply(h: &H, p: [f64; 4]) -> [f64; 4] {
            std::array::from_fn(|i| (0..4).map(|k| h[i][k] * p[k]).sum())
        }

        pub(super) fn translation(t: [f64; 3]) -> H {
            let mut h = identity();
            for i in 0..3 {
                h[i][3] = t[i];
            }
            h
        }

        pub(super) fn diagonal(d: [f64; 3]) -> H {
            let mut h = identity();
            for i in 0..3 {
                h[i][i] = d[i];
            }
            h
        }

        /// Rodrigues: `cos θ I + sin θ [k]x + (1 - cos θ) k kᵀ` about the unit axis `k`.
        pub(super) fn turn(k: [f64; 3], degrees: f64) -> H {
            let (s, c) = degrees.to_radians().sin_cos();
            let cross = [[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]];
            let mut h = identity();
            for i in 0..3 {
                for j in 0..3 {
                    let unit = if i == j { 1.0 } else { 0.0 };
                    h[i][j] = c * unit + s * cross[i][j] + (1.0 - c) * k[i] * k[j];
                }
            }
            h
        }

        pub(super) fn unit(axis: usize) -> [f64; 3] {
            std::array::from_fn(|i| if i == axis { 1.0 } else { 0.0 })
        }

        pub(super) fn rpy(angles: [f64; 3]) -> H {
            let turns = [2, 1, 0].map(|axis| turn(unit(axis), angles[axis]));
            product(&product(&turns[0], &turns[1]), &turns[2])
        }

        /// ROTS of the pair starting at `first`: for X a Y b, Ry(b)·Rx(φ) with
        /// tan φ = tan a cos b (the turned Y axis tilted until the plane holds
        /// (0, cos a, sin a)); the other pairs conjugated by the cyclic permutation.
        pub(super) fn solid(first: usize, a: f64, b: f64) -> Option<H> {
            let (sa, ca) = a.to_radians().sin_cos();
            let cb = b.to_radians().cos();
            if ca.hypot(sa * cb) < 1e-6 {
                return None;
            }
            let phi = (sa * cb).atan2(ca).to_degrees();
            let second = (first + 1) % 3;
            Some(product(&turn(unit(second), b), &turn(unit(first), phi)))
        }
    }

    /// The model's state: coarse and fine translations (all six axes) and R, S, M.
    struct Model {
        coarse: [f64; AXES],
        fine: [f64; AXES],
        r: model::H,
        s: model::H,
        m: model::H,
    }

    impl Model {
        fn new() -> Model {
            Model {
                coarse: [0.0; AXES],
                fine: [0.0; AXES],
                r: model::identity(),
                s: model::identity(),
                m: model::identity(),
            }
        }

        fn linear(&self) -> model::H {
            model::product(&model::product(&self.r, &self.s), &self.m)
        }

        /// Applies `instruction`; false when it cannot (ROTS with no plane).
        fn apply(&mut self, instruction: &Instruction) -> bool {
            let values = |t: [Option<f64>; AXES]| t.map(|v| v.unwrap_or(0.0));
            let angles = |r: [Option<f64>; 3]| r.map(|v| v.unwrap_or(0.0));
            let factors = |s: [Option<f64>; 3]| s.map(|v| v.unwrap_or(1.0));
            let flips = |m: [bool; 3]| m.map(|f| if f { -1.0 } else { 1.0 });
            let normal = |p: usize| PLANES[p].axes().2;
            match *instruction {
                Instruction::Trans(t) => {
                    *self = Model::new();
                    self.coarse = values(t);
                }
                Instruction::Atrans(t) => {
                    let t = values(t);
                    let along = model::apply(&self.linear(), [t[0], t[1], t[2], 0.0]);
                    for i in 0..AXES {
                        self.fine[i] += if i < 3 { along[i] } else { t[i] };
                    }
                }
                Instruction::G58(t) => {
                    for (c, v) in self.coarse.iter_mut().zip(t) {
                        *c = v.unwrap_or(*c);
                    }
                }
                Instruction::G59(t) => {
                    for (f, v) in self.fine.iter_mut().zip(t) {
                        *f = v.unwrap_or(*f);
                    }
                }
                Instruction::Rot(r) => {
                    *self = Model::new();
                    self.r = model::rpy(angles(r));
                }
                Instruction::Arot(r) => self.r = model::product(&self.r, &model::rpy(angles(r))),
                Instruction::RotRpl(p, a) => {
                    *self = Model::new();
                    self.r = model::turn(model::unit(normal(p)), a);
                }
                Instruction::ArotRpl(p, a) => {
                    let turn = model::turn(model::unit(normal(p)), a);
                    self.r = model::product(&self.r, &turn);
                }
                Instruction::Rots(i, a, b) => {
                    let Some(solid) = model::solid(i, a, b) else {
                        return false;
                    };
                    *self = Model::new();
                    self.r = solid;
                }
                Instruction::Arots(i, a, b) => {
                    let Some(solid) = model::solid(i, a, b) else {
                        return false;
                    };
                    self.r = model::product(&self.r, &solid);
                }
                Instruction::Scale(s) => {
                    *self = Model::new();
                    self.s = model::diagonal(factors(s));
                }
                Instruction::Ascale(s) => {
                    self.s = model::product(&self.s, &model::diagonal(factors(s)));
                }
                Instruction::Mirror(m) => {
                    *self = Model::new();
                    self.m = model::diagonal(flips(m));
                }
                Instruction::Amirror(m) => {
                    self.m = model::product(&self.m, &model::diagonal(flips(m)));
                }
            }
            true
        }

        /// `T + Tf + R·S·M·p` as one homogeneous matrix; the other axes translated.
        fn map(&self, p: &[f64; AXES]) -> [f64; AXES] {
            let t: [f64; AXES] = std::array::from_fn(|i| self.coarse[i] + self.fine[i]);
            let whole = model::product(&model::translation([t[0], t[1], t[2]]), &self.linear());
            let image = model::apply(&whole, [p[0], p[1], p[2], 1.0]);
            std::array::from_fn(|i| if i < 3 { image[i] } else { p[i] + t[i] })
        }
    }

    proptest! {
        #[test]
        fn instructions_map_points_as_the_composed_components_do(
            instructions in prop::collection::vec(instruction(), 1..12),
            points in prop::collection::vec(prop::array::uniform6(-500.0f64..500.0), 1..4),
        ) {
            let (mut frame, mut model) = (frame(), Model::new());
            for instruction in &instructions {
                let modelled = model.apply(instruction);
                let applied = apply(&mut frame, instruction);
                prop_assert_eq!(modelled, applied.is_ok(), "{:?}: {:?}", instruction, applied);
            }
            for point in &points {
                let (actual, expected) = (frame.map(point), model.map(point));
                let size = expected.iter().fold(1.0f64, |m, v| m.max(v.abs()));
                for (a, e) in actual.iter().zip(expected) {
                    prop_assert!((a - e).abs() <= 1e-9 * size, "{actual:?} is not {expected:?}");
                }
                let back = frame.unmap(&actual);
                for (b, p) in back.iter().zip(point) {
                    prop_assert!((b - p).abs() <= 1e-9 * size, "{back:?} is not {point:?}");
                }
            }
            // The chain's matrix is the same map.
            if let Some(affine) = frame.to_affine() {
                let point = points[0];
                let (chained, mapped) = (affine.apply(&point), frame.map(&point));
                for (c, m) in chained.iter().zip(mapped) {
                    prop_assert!((c - m).abs() <= 1e-9 * (1.0 + m.abs()));
                }
            } else {
                prop_assert!(frame.is_identity());
            }
        }

        #[test]
        fn rpy_angles_in_range_read_back_as_written(
            x in -179.9f64..179.9,
            y in -89.9f64..89.9,
            z in -179.9f64..179.9,
        ) {
            let mut f = frame();
            f.rot([Some(x), Some(y), Some(z)]).unwrap();
            let [rx, ry, rz] = f.rpy_degrees();
            prop_assert!((rx - x).abs() < 1e-9 && (ry - y).abs() < 1e-9 && (rz - z).abs() < 1e-9);
        }
    }
}
