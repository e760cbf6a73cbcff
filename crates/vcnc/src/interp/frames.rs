//! The coordinate chain: from program coordinates to machine coordinates.
//!
//! machine = preset rotation(rotation(scaling(program))) + local (G52) + G92 shift + work offset
//! (G54 ...), the preset rotation being Syntec's G92.1 with K R
//!           + external offset + tool length vector (Z only)
//!
//! Scaling (G51) or the programmable mirror (G51.1, a scaling by -1) stretches the programmed
//! coordinates of some axes about a centre; the rotation (G68) then turns them about a centre in
//! the plane that was selected when it was programmed; everything else is a translation. The
//! FANUC family applies them in that order: mirror or scaling, then rotation.
//!
//! (spec/iso-syntec-milling.md 0.1.3, seed L4493-4497.) The tool length vector is the offset
//! actually applied to the machine position; it follows the modal G43/G44 value only when a block
//! moves Z or changes the compensation, and a reference return on Z clears it (FANUC, spec A.26).

use crate::machine::{Machine, WorkOffsetId, AXES};
use std::collections::BTreeMap;

/// Offsets that move the program's zero.
#[derive(Clone, Debug)]
pub(crate) struct Frames {
    work_offsets: BTreeMap<WorkOffsetId, [f64; AXES]>,
    /// The G92 shift.
    g92: [f64; AXES],
    /// The G52 local offset.
    local: [f64; AXES],
    /// The tool length offset applied to the Z position now.
    length_vector: f64,
    /// The work coordinate system in use (kept equal to the modal state's by the executor).
    active: WorkOffsetId,
    /// Work + external + G92 + G52 of `active`: every block needs it and it changes only when an
    /// offset does, so it is recomputed then.
    shift: [f64; AXES],
    /// [`Frames::offset`], kept: every move records it, and it changes only with the shift and
    /// the length vector.
    offset: [f64; AXES],
    /// G68, while it is on.
    rotation: Option<Rotation>,
    /// Syntec's G92.1 with K R: the program system turned about its new origin, outside G68.
    preset_rotation: Option<Rotation>,
    /// G51 or G51.1, while it is on.
    scaling: Option<Scaling>,
    /// True when one of the three above is on: every block converts points between program
    /// and machine coordinates, and asked of the three, each conversion tested two words.
    transformed: bool,
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
    cos: f64,
    sin: f64,
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
    fn turn(&self, point: &mut [f64; AXES], sin: f64) {
        let (a, b) = self.axes;
        let (x, y) = (point[a] - self.center.0, point[b] - self.center.1);
        point[a] = self.center.0 + x * self.cos - y * sin;
        point[b] = self.center.1 + x * sin + y * self.cos;
    }
}

impl Frames {
    /// True when a rotation turns the program's plane (G68 or Syntec's rotated G92.1).
    pub(crate) fn rotated(&self) -> bool {
        self.rotation.is_some() || self.preset_rotation.is_some()
    }

    pub(crate) fn new(machine: &Machine) -> Frames {
        let mut frames = Frames {
            work_offsets: machine.work_offsets.clone(),
            g92: [0.0; AXES],
            local: [0.0; AXES],
            length_vector: 0.0,
            active: WorkOffsetId::Standard(1),
            shift: [0.0; AXES],
            offset: [0.0; AXES],
            rotation: None,
            preset_rotation: None,
            scaling: None,
            transformed: false,
        };
        frames.recompute();
        frames
    }

    /// True when the program system is scaled, mirrored or turned (G51, G51.1, G68, Syntec's
    /// rotated G92.1).
    #[inline(always)]
    pub(crate) fn transformed(&self) -> bool {
        self.transformed
    }

    /// G68's rotation, while it is on.
    pub(crate) fn rotation(&self) -> Option<&Rotation> {
        self.rotation.as_ref()
    }

    /// Syntec's rotated G92.1, while it is on.
    pub(crate) fn preset_rotation(&self) -> Option<&Rotation> {
        self.preset_rotation.as_ref()
    }

    /// G51 or G51.1, while it is on.
    pub(crate) fn scaling(&self) -> Option<&Scaling> {
        self.scaling.as_ref()
    }

    /// Sets or ends G68's rotation.
    pub(crate) fn set_rotation(&mut self, rotation: Option<Rotation>) {
        self.rotation = rotation;
        self.note_transforms();
    }

    /// Sets or ends Syntec's rotated G92.1.
    pub(crate) fn set_preset_rotation(&mut self, rotation: Option<Rotation>) {
        self.preset_rotation = rotation;
        self.note_transforms();
    }

    /// Sets or ends G51 or G51.1.
    pub(crate) fn set_scaling(&mut self, scaling: Option<Scaling>) {
        self.scaling = scaling;
        self.note_transforms();
    }

    fn note_transforms(&mut self) {
        self.transformed = self.scaling.is_some() || self.rotated();
    }

    /// Selects the work coordinate system in use.
    pub(crate) fn select(&mut self, active: WorkOffsetId) {
        if active != self.active {
            self.active = active;
            self.recompute();
        }
    }

    fn recompute(&mut self) {
        let work = self.work_offset(self.active);
        let external = self.work_offset(WorkOffsetId::External);
        self.shift = std::array::from_fn(|i| work[i] + external[i] + self.g92[i] + self.local[i]);
        self.offset = self.shift;
        self.offset[2] += self.length_vector;
    }

    /// The tool length offset applied to the Z position now.
    pub(crate) fn length_vector(&self) -> f64 {
        self.length_vector
    }

    /// Applies a tool length offset to the Z position.
    #[inline(always)]
    pub(crate) fn set_length_vector(&mut self, length: f64) {
        self.length_vector = length;
        self.offset[2] = self.shift[2] + length;
    }

    /// The value of a work offset register.
    pub(crate) fn work_offset(&self, id: WorkOffsetId) -> [f64; AXES] {
        self.work_offsets.get(&id).copied().unwrap_or([0.0; AXES])
    }

    /// Sets one axis of a work offset register.
    pub(crate) fn set_work_offset(&mut self, id: WorkOffsetId, axis: usize, value: f64) {
        self.work_offsets.entry(id).or_insert([0.0; AXES])[axis] = value;
        self.recompute();
    }

    /// The G92 shift of an axis.
    pub(crate) fn g92(&self, axis: usize) -> f64 {
        self.g92[axis]
    }

    /// Sets the G92 shift of an axis.
    pub(crate) fn set_g92(&mut self, axis: usize, value: f64) {
        self.g92[axis] = value;
        self.recompute();
    }

    /// The G52 local offset of an axis.
    pub(crate) fn local(&self, axis: usize) -> f64 {
        self.local[axis]
    }

    /// Sets the G52 local offset of an axis.
    pub(crate) fn set_local(&mut self, axis: usize, value: f64) {
        self.local[axis] = value;
        self.recompute();
    }

    /// Machine minus program coordinates now: the shift and the applied tool length vector.
    #[inline(always)]
    pub(crate) fn offset(&self) -> [f64; AXES] {
        debug_assert_eq!(
            self.offset[2].to_bits(),
            (self.shift[2] + self.length_vector).to_bits()
        );
        self.offset
    }

    /// Machine minus program coordinates at the machine position `at`: the plain offset, or,
    /// when the program system is scaled or turned, the difference at that point.
    // Inlined, with the scaled or turned case out of line: every move asks.
    #[inline(always)]
    pub(crate) fn offset_at(&self, at: &[f64; AXES]) -> [f64; AXES] {
        if !self.transformed {
            return self.offset();
        }
        self.transformed_offset_at(at)
    }

    /// [`Frames::offset_at`] when the program system is scaled or turned.
    #[inline(never)]
    fn transformed_offset_at(&self, at: &[f64; AXES]) -> [f64; AXES] {
        let program = self.to_program(at);
        std::array::from_fn(|i| at[i] - program[i])
    }

    /// Program coordinates of a machine position, with the applied tool length vector.
    // Inlined for the common case, a translation only: every block asks.
    #[inline(always)]
    pub(crate) fn to_program(&self, machine: &[f64; AXES]) -> [f64; AXES] {
        let shift = &self.shift;
        let mut program: [f64; AXES] = std::array::from_fn(|i| machine[i] - shift[i]);
        program[2] -= self.length_vector;
        if !self.transformed {
            return program;
        }
        self.unturn(program)
    }

    /// The program coordinates of a point already shifted back: the rotations and the scaling
    /// undone.
    #[inline(never)]
    fn unturn(&self, mut program: [f64; AXES]) -> [f64; AXES] {
        if let Some(rotation) = &self.preset_rotation {
            rotation.turn(&mut program, -rotation.sin);
        }
        if let Some(rotation) = &self.rotation {
            rotation.turn(&mut program, -rotation.sin);
        }
        if let Some(scaling) = &self.scaling {
            for ((p, c), f) in program.iter_mut().zip(scaling.center).zip(scaling.factor) {
                *p = c + (*p - c) / f;
            }
        }
        program
    }

    /// Machine coordinates of a program position, with tool length vector `length`.
    #[inline(always)]
    pub(crate) fn to_machine(&self, program: &[f64; AXES], length: f64) -> [f64; AXES] {
        // The point is shifted where it is: a copy of it for a common exit cost every block six
        // moves.
        if !self.transformed {
            return self.shifted(program, length);
        }
        self.shifted(&self.turn(program), length)
    }

    /// Machine coordinates of a point already scaled and turned, with tool length vector
    /// `length`.
    #[inline(always)]
    fn shifted(&self, turned: &[f64; AXES], length: f64) -> [f64; AXES] {
        let shift = &self.shift;
        let mut machine: [f64; AXES] = std::array::from_fn(|i| turned[i] + shift[i]);
        machine[2] += length;
        machine
    }

    /// A program position scaled and turned, before the shift.
    #[inline(never)]
    fn turn(&self, program: &[f64; AXES]) -> [f64; AXES] {
        let mut turned = *program;
        if let Some(scaling) = &self.scaling {
            for ((p, c), f) in turned.iter_mut().zip(scaling.center).zip(scaling.factor) {
                *p = c + (*p - c) * f;
            }
        }
        if let Some(rotation) = &self.rotation {
            rotation.turn(&mut turned, rotation.sin);
        }
        if let Some(rotation) = &self.preset_rotation {
            rotation.turn(&mut turned, rotation.sin);
        }
        turned
    }
}
