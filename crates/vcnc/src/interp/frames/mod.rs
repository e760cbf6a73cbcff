//! The coordinate chain: from program coordinates to machine coordinates.
//!
//! machine = chain(program) + G52 local + G92 shift + work offset (G54 ...) + external offset
//!           + tool length vector (Z only)
//!
//! The chain is a list of general frames ([`transform::Frame`]) applied in slot order: first
//! SINUMERIK's programmable frame (an affine map of X Y Z, never set by the ISO codes), then for
//! the ISO codes scaling or mirror (G51, G51.1: stretching the programmed coordinates of some axes
//! about a centre), then the G68 rotation (about a centre in the plane selected when it was
//! programmed), then Syntec's rotated preset (G92.1 with K R). The FANUC family applies them in
//! that order (spec/iso-syntec-milling.md 0.1.3, seed L4493-4497). What follows the chain is a
//! translation only, so its parts are added into one shift when one of them changes.
//!
//! G16's polar coordinates are not a frame: they say how a block's words name a point, which then
//! goes through the chain (`polar_coordinates.rs`). G12.1 maps X-C motion after the chain
//! (`polar_interpolation.rs`).
//!
//! The tool length vector is the offset actually applied to the machine position; it follows the
//! modal G43/G44 value only when a block moves Z or changes the compensation, and a reference
//! return on Z clears it (FANUC, spec A.26).
//!
//! The consumers of the stream see the whole map (`motion::WorkTransform`, [`Frames::new_frame`]):
//! every change that moves something marks the map new, and the next move tells the stream of
//! it first (`KernelState::move_to`), so the map is multiplied out once per change, never per
//! move.
//!
//! The codes that set the frames live beside this file: `scaling.rs` (G51, G51.1, G50, G50.1),
//! `rotation.rs` (G68, G69) and `coords.rs` (G92, G92.1, G52, G53).

pub(crate) mod coords;
pub(crate) mod rotation;
pub(crate) mod scaling;
mod transform;

pub(crate) use transform::{
    multiply, sin_cos_degrees, Affine, Frame, FrameSlot, Rotation, Scaling, Transform,
};

use crate::machine::{Machine, WorkOffsetId, AXES};
use crate::motion::{ArcDirection, FrameId, WorkFrame, WorkTransform};
use std::collections::BTreeMap;

/// The coordinate chain and the offsets that move the program's zero.
#[derive(Clone, Debug)]
pub(crate) struct Frames {
    /// The frames in force, in slot order (none: program and machine axes are parallel).
    chain: Vec<Frame>,
    work_offsets: BTreeMap<WorkOffsetId, [f64; AXES]>,
    /// The G92 shift.
    g92: [f64; AXES],
    /// The G52 local offset.
    local: [f64; AXES],
    /// The tool length offset applied to the Z position now.
    length_vector: f64,
    /// The tool length along X and Y: SINUMERIK's lengths by plane (G18, G19, TOFF), zero on
    /// the ISO side.
    lateral_length: [f64; 2],
    /// The work coordinate system in use (kept equal to the modal state's by the executor).
    active: WorkOffsetId,
    /// Work + external + G92 + G52 of `active`: every block needs it and it changes only when an
    /// offset does, so it is recomputed then.
    shift: [f64; AXES],
    /// `shift` plus the length vector on Z: every move records it.
    offset: [f64; AXES],
    /// The id of the frame moves are made in (the last one the stream was told of).
    id: FrameId,
    /// The map has changed since the stream was last told of it (true at power-on: the first
    /// move tells it).
    changed: bool,
    /// The id the next frame gets.
    next_id: u32,
}

impl Frames {
    /// True when a rotation turns the program's plane (G68 or Syntec's rotated G92.1). The
    /// ISO codes ask it; SINUMERIK's programmable frame is not counted (its front end asks the
    /// frame itself, `ProgrammableFrame::has_rotation`).
    pub(crate) fn rotated(&self) -> bool {
        self.rotation().is_some() || self.preset_rotation().is_some()
    }

    pub(crate) fn new(machine: &Machine) -> Frames {
        let mut frames = Frames {
            work_offsets: machine.work_offsets.clone(),
            g92: [0.0; AXES],
            local: [0.0; AXES],
            length_vector: 0.0,
            lateral_length: [0.0; 2],
            active: WorkOffsetId::Standard(1),
            shift: [0.0; AXES],
            offset: [0.0; AXES],
            chain: Vec::new(),
            id: FrameId(0),
            changed: true,
            next_id: 0,
        };
        frames.recompute();
        frames
    }

    /// True when the program system is scaled, mirrored or turned (G51, G51.1, G68, Syntec's
    /// rotated G92.1).
    #[inline(always)]
    pub(crate) fn transformed(&self) -> bool {
        !self.chain.is_empty()
    }

    /// The frame in `slot`, if one is set.
    pub(crate) fn frame(&self, slot: FrameSlot) -> Option<&Transform> {
        self.chain
            .iter()
            .find(|frame| frame.slot == slot)
            .map(|frame| &frame.transform)
    }

    /// Sets the frame in `slot`, or clears it (`None`); the chain stays in slot order.
    pub(crate) fn set_frame(&mut self, slot: FrameSlot, transform: Option<Transform>) {
        self.changed = true;
        self.chain.retain(|frame| frame.slot != slot);
        if let Some(transform) = transform {
            let at = self.chain.partition_point(|frame| frame.slot < slot);
            self.chain.insert(at, Frame { slot, transform });
        }
    }

    /// The rotation in `slot`, if that slot holds one.
    fn rotation_in(&self, slot: FrameSlot) -> Option<&Rotation> {
        match self.frame(slot) {
            Some(Transform::Rotate(rotation)) => Some(rotation),
            _ => None,
        }
    }

    /// G68's rotation, while it is on.
    pub(crate) fn rotation(&self) -> Option<&Rotation> {
        self.rotation_in(FrameSlot::Rotation)
    }

    /// Syntec's rotated G92.1, while it is on.
    pub(crate) fn preset_rotation(&self) -> Option<&Rotation> {
        self.rotation_in(FrameSlot::PresetRotation)
    }

    /// G51 or G51.1, while it is on.
    pub(crate) fn scaling(&self) -> Option<&Scaling> {
        match self.frame(FrameSlot::Scaling) {
            Some(Transform::Scale(scaling)) => Some(scaling),
            _ => None,
        }
    }

    /// SINUMERIK's programmable frame, while one is set.
    pub(crate) fn programmable(&self) -> Option<&Affine> {
        match self.frame(FrameSlot::Programmable) {
            Some(Transform::Affine(affine)) => Some(affine),
            _ => None,
        }
    }

    /// True when the chain turns the plane of axes `(a, b)` over, so that arcs (and G41/G42)
    /// swap: a mirror of one plane axis (or a negative factor), or a programmable frame that
    /// turns the plane over; two such frames cancel.
    pub(crate) fn reverses_plane(&self, (a, b): (usize, usize)) -> bool {
        let scaled = self.scaling().is_some_and(|s| s.reverses((a, b)));
        let framed = self.programmable().is_some_and(|f| f.reverses((a, b)));
        scaled != framed
    }

    /// The direction on the machine of an arc programmed `direction` in the plane of axes
    /// `(a, b)`: reversed where [`Frames::reverses_plane`] says so.
    pub(crate) fn arc_direction(
        &self,
        (a, b): (usize, usize),
        direction: ArcDirection,
    ) -> ArcDirection {
        if self.reverses_plane((a, b)) {
            direction.reversed()
        } else {
            direction
        }
    }

    /// Sets SINUMERIK's programmable frame, or clears it (`None`, also for the identity, so that
    /// a program without frames keeps the chain's fast path). It changes the chain only, not
    /// the position (docs/SINUMERIK.md 6.4 rule 1).
    #[cfg_attr(not(test), allow(dead_code))] // wired in by the SINUMERIK front end (issue 20)
    pub(crate) fn set_programmable(&mut self, frame: Option<Affine>) {
        self.set_frame(FrameSlot::Programmable, frame.map(Transform::Affine));
    }

    /// SINUMERIK's swivel frame (CYCLE800), while one is set.
    pub(crate) fn swivel(&self) -> Option<&Affine> {
        match self.frame(FrameSlot::Swivel) {
            Some(Transform::Affine(affine)) => Some(affine),
            _ => None,
        }
    }

    /// Sets or ends SINUMERIK's swivel frame.
    pub(crate) fn set_swivel(&mut self, frame: Option<Affine>) {
        self.set_frame(FrameSlot::Swivel, frame.map(Transform::Affine));
    }

    /// True when every general affine frame of the chain (SINUMERIK's programmable and swivel
    /// frames) keeps an arc in the plane of axes `(a, b)` a machine arc ([`Affine::keeps_plane`]).
    pub(crate) fn affine_frames_keep_plane(&self, (a, b): (usize, usize)) -> bool {
        [self.programmable(), self.swivel()]
            .into_iter()
            .flatten()
            .all(|f| f.keeps_plane((a, b)))
    }

    /// Sets or ends G68's rotation.
    pub(crate) fn set_rotation(&mut self, rotation: Option<Rotation>) {
        self.set_frame(FrameSlot::Rotation, rotation.map(Transform::Rotate));
    }

    /// Sets or ends Syntec's rotated G92.1.
    pub(crate) fn set_preset_rotation(&mut self, rotation: Option<Rotation>) {
        self.set_frame(FrameSlot::PresetRotation, rotation.map(Transform::Rotate));
    }

    /// Sets or ends G51 or G51.1.
    pub(crate) fn set_scaling(&mut self, scaling: Option<Scaling>) {
        self.set_frame(FrameSlot::Scaling, scaling.map(Transform::Scale));
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
        let before = self.offset;
        self.shift = std::array::from_fn(|i| work[i] + external[i] + self.g92[i] + self.local[i]);
        self.shift[0] += self.lateral_length[0];
        self.shift[1] += self.lateral_length[1];
        self.offset = self.shift;
        self.offset[2] += self.length_vector;
        // A write to a register not in use (G10 L2 P2 under G54) moves nothing.
        self.changed |= self.offset != before;
    }

    /// The tool length offset applied to the Z position now.
    pub(crate) fn length_vector(&self) -> f64 {
        self.length_vector
    }

    /// Applies a tool length offset to the Z position.
    #[inline(always)]
    pub(crate) fn set_length_vector(&mut self, length: f64) {
        // Compared by value, so -0 and 0 are one frame (no NaN gets here: positions are checked).
        self.changed |= length != self.length_vector;
        self.length_vector = length;
        self.offset[2] = self.shift[2] + length;
    }

    /// The tool length along X and Y (SINUMERIK's length by plane); the Z part is
    /// [`Frames::set_length_vector`]'s.
    pub(crate) fn set_lateral_length(&mut self, length: [f64; 2]) {
        if length != self.lateral_length {
            self.lateral_length = length;
            self.recompute();
        }
    }

    /// The tool length along X and Y.
    pub(crate) fn lateral_length(&self) -> [f64; 2] {
        self.lateral_length
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

    /// The id of the frame moves are made in.
    #[inline(always)]
    pub(crate) fn id(&self) -> FrameId {
        self.id
    }

    /// True when the map changed since the stream was last told of it: the next move is made
    /// in a new frame, whose event ([`Frames::new_frame`]) goes first.
    #[inline(always)]
    pub(crate) fn is_new(&self) -> bool {
        self.changed
    }

    /// The map now as a new frame with the next id, for the stream's event.
    pub(crate) fn new_frame(&mut self) -> WorkFrame {
        self.id = FrameId(self.next_id);
        self.next_id = self.next_id.wrapping_add(1);
        self.changed = false;
        WorkFrame {
            id: self.id,
            transform: self.work_transform(),
            tool_length: [
                self.lateral_length[0],
                self.lateral_length[1],
                self.length_vector,
            ],
        }
    }

    /// The whole map from program to machine coordinates now: the chain multiplied out, then
    /// the shift and the tool length vector.
    pub(crate) fn work_transform(&self) -> WorkTransform {
        if self.chain.is_empty() {
            // Exactly the offset every move records: program = machine - offset.
            return WorkTransform::translation(self.offset);
        }
        // The chain is affine (each frame is): the origin's image is the translation, and the
        // unit vectors' images less it are the columns of the linear part.
        let origin = self.to_machine(&[0.0; AXES], self.length_vector);
        let image = |axis: usize| {
            let mut unit = [0.0; AXES];
            unit[axis] = 1.0;
            let moved = self.to_machine(&unit, self.length_vector);
            std::array::from_fn::<f64, AXES, _>(|i| moved[i] - origin[i])
        };
        let columns: [[f64; AXES]; 3] = std::array::from_fn(image);
        WorkTransform {
            linear: std::array::from_fn(|i| std::array::from_fn(|j| columns[j][i])),
            rotary: std::array::from_fn(|i| image(3 + i)[3 + i]),
            translation: origin,
        }
    }

    /// Machine minus program coordinates now: the shift and the applied tool length vector.
    #[inline(always)]
    pub(crate) fn offset(&self) -> [f64; AXES] {
        self.offset
    }

    /// Machine minus program coordinates at the machine position `at`: the plain offset, or,
    /// when the program system is scaled or turned, the difference at that point.
    // Inlined, with the scaled or turned case out of line: every move asks.
    #[inline(always)]
    pub(crate) fn offset_at(&self, at: &[f64; AXES]) -> [f64; AXES] {
        if self.chain.is_empty() {
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
        if self.chain.is_empty() {
            return program;
        }
        self.unturn(program)
    }

    /// The program coordinates of a point already shifted back: the chain undone, last frame
    /// first.
    #[inline(never)]
    fn unturn(&self, mut program: [f64; AXES]) -> [f64; AXES] {
        for frame in self.chain.iter().rev() {
            frame.transform.undo(&mut program);
        }
        program
    }

    /// Machine coordinates of a program position, with tool length vector `length`.
    #[inline(always)]
    pub(crate) fn to_machine(&self, program: &[f64; AXES], length: f64) -> [f64; AXES] {
        // The point is shifted where it is: a copy of it for a common exit cost every block six
        // moves.
        if self.chain.is_empty() {
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

    /// A program position through the chain, before the shift.
    #[inline(never)]
    fn turn(&self, program: &[f64; AXES]) -> [f64; AXES] {
        let mut turned = *program;
        for frame in &self.chain {
            frame.transform.apply(&mut turned);
        }
        turned
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn frames() -> Frames {
        Frames::new(&Machine::default())
    }

    fn scaling(factor: [f64; AXES]) -> Scaling {
        Scaling {
            center: [1.0, 2.0, 0.0, 0.0, 0.0, 0.0],
            factor,
        }
    }

    #[test]
    fn frames_apply_in_slot_order_whatever_order_they_were_set_in() {
        let mut early = frames();
        early.set_scaling(Some(scaling([2.0; AXES])));
        early.set_rotation(Some(Rotation::new((0, 1), (0.0, 0.0), 90.0)));
        let mut late = frames();
        late.set_rotation(Some(Rotation::new((0, 1), (0.0, 0.0), 90.0)));
        late.set_scaling(Some(scaling([2.0; AXES])));
        let point = [3.0, 1.0, 0.0, 0.0, 0.0, 0.0];
        // Scaled about (1, 2) first: (5, 0); then turned a quarter: (0, 5).
        let expected = [0.0, 5.0, 0.0, 0.0, 0.0, 0.0];
        assert_eq!(early.to_machine(&point, 0.0), expected);
        assert_eq!(late.to_machine(&point, 0.0), expected);
    }

    #[test]
    fn clearing_every_frame_leaves_a_plain_translation() {
        let mut chain = frames();
        chain.set_rotation(Some(Rotation::new((1, 2), (0.0, 0.0), 30.0)));
        chain.set_scaling(Some(scaling([-1.0; AXES])));
        assert!(chain.transformed() && chain.rotated());
        chain.set_rotation(None);
        chain.set_scaling(None);
        assert!(!chain.transformed());
        assert_eq!(chain.frame(FrameSlot::Scaling), None);
    }

    /// An affine map: a quarter turn about Z, X scaled by `factor`, then moved by `shift` (and
    /// A by 5).
    fn affine(factor: f64, shift: [f64; 3]) -> Affine {
        let linear = [[0.0, -1.0, 0.0], [factor, 0.0, 0.0], [0.0, 0.0, 1.0]];
        let [x, y, z] = shift;
        Affine::new(linear, [x, y, z, 5.0, 0.0, 0.0]).expect("a regular matrix")
    }

    #[test]
    fn the_programmable_frame_comes_first_in_the_chain() {
        let mut chain = frames();
        chain.set_scaling(Some(scaling([2.0; AXES])));
        chain.set_programmable(Some(affine(1.0, [1.0, 0.0, 0.0])));
        assert!(matches!(
            chain.frame(FrameSlot::Programmable),
            Some(Transform::Affine(_))
        ));
        assert!(chain.programmable().is_some() && chain.transformed() && !chain.rotated());
        let point = [3.0, 0.0, 0.0, 1.0, 0.0, 0.0];
        // The affine map first: (3, 0) turned a quarter is (0, 3), moved to (1, 3); then scaled
        // by 2 about (1, 2): (1, 4). A moves by 5 to 6, then is scaled about 0 to 12.
        let expected = [1.0, 4.0, 0.0, 12.0, 0.0, 0.0];
        assert_eq!(chain.to_machine(&point, 0.0), expected);
        chain.set_programmable(None);
        assert!(chain.programmable().is_none());
        assert_eq!(
            chain.frame(FrameSlot::Scaling),
            Some(&Transform::Scale(scaling([2.0; AXES])))
        );
    }

    #[test]
    fn an_affine_map_is_kept_with_its_parts() {
        let map = affine(2.0, [1.0, 2.0, 3.0]);
        assert_eq!(map.linear()[1], [2.0, 0.0, 0.0]);
        assert_eq!(map.translation(), &[1.0, 2.0, 3.0, 5.0, 0.0, 0.0]);
        assert_eq!(
            map.apply(&[1.0, 1.0, 1.0, 1.0, 1.0, 1.0]),
            [0.0, 4.0, 4.0, 6.0, 1.0, 1.0]
        );
        // A zero row, or a number that is not one, cannot be undone.
        let flat = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 0.0]];
        assert_eq!(Affine::new(flat, [0.0; AXES]), None);
        let mut huge = flat;
        huge[2][2] = f64::INFINITY;
        assert_eq!(Affine::new(huge, [0.0; AXES]), None);
        assert_eq!(
            Affine::new(*affine(1.0, [0.0; 3]).linear(), [f64::NAN; AXES]),
            None
        );
    }

    #[test]
    fn arcs_reverse_when_one_frame_turns_the_plane_over() {
        let xy = (0, 1);
        let cw = ArcDirection::Clockwise;
        let mut chain = frames();
        // A quarter turn with X stretched keeps the orientation of XY.
        chain.set_programmable(Some(affine(2.0, [0.0; 3])));
        assert_eq!(chain.arc_direction(xy, cw), cw);
        // Y mirrored in the affine map: reversed; with G51.1 X as well: the two cancel.
        let mirror = [[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0]];
        chain.set_programmable(Affine::new(mirror, [0.0; AXES]));
        assert_eq!(chain.arc_direction(xy, cw), cw.reversed());
        assert!(chain.reverses_plane(xy) && !chain.reverses_plane((2, 0)));
        chain.set_scaling(Some(scaling([-1.0, 1.0, 1.0, 1.0, 1.0, 1.0])));
        assert_eq!(chain.arc_direction(xy, cw), cw);
        assert!(!chain.reverses_plane(xy));
    }

    #[test]
    fn an_affine_map_keeps_a_plane_only_when_it_stays_parallel_and_even() {
        let (xy, zx, yz) = ((0, 1), (2, 0), (1, 2));
        // A quarter turn about Z with X stretched: XY is distorted, YZ and ZX are not kept
        // parallel (X goes to Y).
        let map = affine(2.0, [0.0; 3]);
        assert!(!map.keeps_plane(xy) && !map.keeps_plane(yz) && !map.keeps_plane(zx));
        let even = affine(1.0, [7.0, 8.0, 9.0]);
        assert!(even.keeps_plane(xy) && !even.keeps_plane(zx));
        assert_eq!(even.plane_factor(xy), 1.0);
        // A shear of Z into X: XY keeps its shape but a helix would lean.
        let shear = [[1.0, 0.0, 0.5], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        assert!(!Affine::new(shear, [0.0; AXES]).unwrap().keeps_plane(xy));
        // Mirrored and scaled by 3 evenly in ZX: kept, factor 3, reversed.
        let mirrored = [[-3.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 3.0]];
        let mirrored = Affine::new(mirrored, [0.0; AXES]).unwrap();
        assert!(mirrored.keeps_plane(zx) && mirrored.reverses(zx));
        assert_eq!(mirrored.plane_factor(zx), 3.0);
        // Large factors keep their planes despite the rounding of their products: a turn by 30
        // degrees with both factors a million.
        let (sin, cos) = sin_cos_degrees(30.0);
        let big = 1.0e6;
        let turned = [
            [big * cos, -big * sin, 0.0],
            [big * sin, big * cos, 0.0],
            [0.0, 0.0, 1.0],
        ];
        let turned = Affine::new(turned, [0.0; AXES]).unwrap();
        assert!(turned.keeps_plane(xy));
        assert!((turned.plane_factor(xy) - big).abs() < 1e-6);
    }

    #[test]
    fn a_quarter_turn_puts_a_plane_onto_another_machine_plane() {
        let (xy, yz) = ((0, 1), (1, 2));
        // ROT Y90: x' = z, z' = -x. X-Y goes onto Y-Z, its normal Z onto X; in Y-Z's order the
        // block (L_yx, L_yy; L_zx, L_zy) = (0, 1; -1, 0) has determinant 1: the same turn.
        let rot_y90 = [[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]];
        let rot_y90 = Affine::new(rot_y90, [0.0; AXES]).unwrap();
        assert!(!rot_y90.keeps_plane(xy));
        assert_eq!(rot_y90.plane_image(xy), Some((yz, false)));
        // Y-Z goes onto X-Y: Y stays, Z goes to X; (L_xy, L_xz; L_yy, L_yz) = (0, 1; 1, 0):
        // mirrored.
        assert_eq!(rot_y90.plane_image(yz), Some((xy, true)));
        // A plane kept is not "turned onto another"; a tilt by 30 degrees has no image plane.
        assert_eq!(affine(1.0, [0.0; 3]).plane_image(xy), None);
        let (sin, cos) = sin_cos_degrees(30.0);
        let tilt = [[cos, 0.0, sin], [0.0, 1.0, 0.0], [-sin, 0.0, cos]];
        assert_eq!(
            Affine::new(tilt, [0.0; AXES]).unwrap().plane_image(xy),
            None
        );
    }

    #[test]
    fn a_new_frame_is_told_once_and_only_when_the_map_changed() {
        let mut chain = frames();
        // Power-on: the first move tells frame 0.
        assert!(chain.is_new());
        assert_eq!(chain.new_frame().id, FrameId(0));
        assert!(!chain.is_new());
        // A register not in use, the length vector it already has: nothing moved.
        chain.set_work_offset(WorkOffsetId::Standard(2), 0, 100.0);
        chain.set_length_vector(0.0);
        assert!(!chain.is_new());
        chain.set_length_vector(25.0);
        assert!(chain.is_new());
        let frame = chain.new_frame();
        assert_eq!(
            (frame.id, frame.tool_length),
            (FrameId(1), [0.0, 0.0, 25.0])
        );
        assert_eq!(frame.transform.translation[2], 25.0);
        chain.set_rotation(Some(Rotation::new((0, 1), (0.0, 0.0), 90.0)));
        assert_eq!(chain.new_frame().id, FrameId(2));
    }

    /// True for a map whose determinant is far from zero: a nearly singular map loses a
    /// point's digits on the way back.
    fn well_conditioned(map: Option<&Affine>) -> bool {
        map.is_some_and(|m| {
            let l = m.linear();
            let determinant = l[0][0] * (l[1][1] * l[2][2] - l[1][2] * l[2][1])
                - l[0][1] * (l[1][0] * l[2][2] - l[1][2] * l[2][0])
                + l[0][2] * (l[1][0] * l[2][1] - l[1][1] * l[2][0]);
            determinant.abs() > 0.1
        })
    }

    proptest! {
        #[test]
        fn the_whole_map_of_a_frame_is_the_chain_multiplied_out(
            point in prop::array::uniform6(-500.0f64..500.0),
            linear in prop::array::uniform3(prop::array::uniform3(-3.0f64..3.0)),
            factor in prop::array::uniform6(prop_oneof![0.1f64..4.0, -4.0f64..-0.1]),
            degrees in -720.0f64..720.0,
            plane in 0usize..3,
            shift in prop::array::uniform6(-100.0f64..100.0),
            length in -50.0f64..50.0,
        ) {
            let map = Affine::new(linear, shift);
            prop_assume!(well_conditioned(map.as_ref()));
            let mut chain = frames();
            chain.set_programmable(map);
            chain.set_scaling(Some(scaling(factor)));
            let axes = [(0, 1), (2, 0), (1, 2)][plane];
            chain.set_rotation(Some(Rotation::new(axes, (10.0, -20.0), degrees)));
            chain.set_g92(0, shift[0]);
            chain.set_length_vector(length);
            let whole = chain.new_frame().transform;
            let machine = chain.to_machine(&point, length);
            let through = whole.to_machine(&point);
            for (m, t) in machine.iter().zip(through) {
                prop_assert!((m - t).abs() < 1e-7, "{machine:?} {through:?}");
            }
            // And back: the consumer's map of machine coordinates to the program's.
            let program = chain.to_program(&machine);
            let back = whole.program_map().to_program([machine[0], machine[1], machine[2]]);
            for (p, b) in program.iter().zip(back) {
                prop_assert!((p - b).abs() < 1e-6, "{program:?} {back:?}");
            }
        }

        #[test]
        fn a_point_through_a_chain_with_an_affine_map_and_back_is_where_it_started(
            point in prop::array::uniform6(-500.0f64..500.0),
            linear in prop::array::uniform3(prop::array::uniform3(-3.0f64..3.0)),
            translation in prop::array::uniform6(-100.0f64..100.0),
            factor in prop::array::uniform6(prop_oneof![0.1f64..4.0, -4.0f64..-0.1]),
            degrees in -720.0f64..720.0,
            length in -50.0f64..50.0,
        ) {
            let map = Affine::new(linear, translation);
            prop_assume!(well_conditioned(map.as_ref()));
            let mut chain = frames();
            chain.set_programmable(map);
            chain.set_scaling(Some(scaling(factor)));
            chain.set_rotation(Some(Rotation::new((1, 2), (10.0, -20.0), degrees)));
            chain.set_work_offset(WorkOffsetId::Standard(1), 0, 100.0);
            let machine = chain.to_machine(&point, length);
            chain.set_length_vector(length);
            let back = chain.to_program(&machine);
            for (p, b) in point.iter().zip(back) {
                prop_assert!((p - b).abs() < 1e-7, "{point:?} came back as {back:?}");
            }
        }

        #[test]
        fn a_point_through_the_chain_and_back_is_where_it_started(
            point in prop::array::uniform6(-500.0f64..500.0),
            factor in prop::array::uniform6(prop_oneof![0.1f64..4.0, -4.0f64..-0.1]),
            degrees in -720.0f64..720.0,
            preset in -90.0f64..90.0,
            plane in 0usize..3,
            shift in prop::array::uniform6(-100.0f64..100.0),
            length in -50.0f64..50.0,
        ) {
            let axes = [(0, 1), (2, 0), (1, 2)][plane];
            let mut chain = frames();
            chain.set_preset_rotation(Some(Rotation::new((0, 1), (4.0, -3.0), preset)));
            chain.set_scaling(Some(scaling(factor)));
            chain.set_rotation(Some(Rotation::new(axes, (10.0, -20.0), degrees)));
            for (axis, value) in shift.iter().enumerate() {
                chain.set_g92(axis, *value);
            }
            let machine = chain.to_machine(&point, length);
            chain.set_length_vector(length);
            let back = chain.to_program(&machine);
            for (p, b) in point.iter().zip(back) {
                prop_assert!((p - b).abs() < 1e-9, "{point:?} came back as {back:?}");
            }
            let offset = chain.offset_at(&machine);
            for i in 0..AXES {
                prop_assert!((machine[i] - offset[i] - point[i]).abs() < 1e-9);
            }
        }
    }
}
