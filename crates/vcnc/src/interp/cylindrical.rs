//! G07.1 cylindrical interpolation (FANUC family, Mitsubishi): `G07.1 C r` makes the rotary
//! axis C programmable as a length along the surface of a cylinder of radius r, so that a slot
//! or contour wrapped round the cylinder is programmed on the unrolled surface, with lines,
//! arcs and cutter compensation; `G07.1 C0` ends it. None of the three ISO manuals has the code:
//! vcnc follows the FANUC and Mitsubishi controls that have it (docs/DEVIATIONS.md).
//!
//! How it sits in the pipeline (built like G12.1's `polar_interpolation.rs`):
//!
//! - While the mode is on, [`prepare`] reads the rotary axis word of each block as a length and
//!   carries it in the slot of a linear axis the surface does not use (C, which turns about Z:
//!   the Y slot, plane G19 of Y and Z, so Z and C span the surface; A about X: Y, G17; B about
//!   Y: X, G17). The executor, its arcs and cutter compensation run unchanged in that plane; the
//!   machine's own axis in that slot stays where it was (a word for it is refused).
//! - [`CylindricalStage`] sits after compensation. Each released segment is cut into straight
//!   pieces of the linear axis and the rotary axis (`pieces.rs`): C degrees = length * 180 /
//!   (pi r) from the program zero of C. A straight line stays one piece; an arc of the surface
//!   becomes pieces within the profile's `polar_interpolation_tolerance`. Each piece gets the time
//!   its share of the contour on the surface takes at F (the control keeps F along the surface).
//! - `G07.1 C0` puts the machine position back in the executor and restores the plane.
//!
//! What it must never do: cost anything when the mode is off (the queue asks for the stage only
//! when it exists).

use super::decode::{Command, GWord};
use super::exec::Executor;
use super::pieces::{PieceMap, PieceQueue};
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::machine::{Axis, AXES};
use crate::motion::{Plane, StreamItem};
use crate::profile::GCode;

/// The codes the mode allows: those of G12.1's mode (motion and the modes that do not move the
/// coordinate system) but positioning, which FANUC refuses in the mode, and G12.1/G13.1.
fn allowed_in_mode(code: GCode) -> bool {
    match code {
        GCode::Rapid | GCode::PolarInterpolation | GCode::PolarInterpolationCancel => false,
        _ => super::polar_interpolation::allowed_in_mode(code),
    }
}

/// The slot that carries the surface length of the rotary axis `letter`, and the plane the
/// surface is programmed in.
fn carrier(letter: u8) -> Option<(Axis, Plane)> {
    match letter {
        b'A' => Some((Axis::Y, Plane::Xy)),
        b'B' => Some((Axis::X, Plane::Xy)),
        b'C' => Some((Axis::Y, Plane::Yz)),
        _ => None,
    }
}

/// Before a block in the mode: refuses the codes the mode does not allow and reads the rotary
/// axis word as the surface length.
///
/// # Errors
/// [`AlarmCode::WordNotAllowed`] for G00 or a code that changes the coordinate system, or a
/// word for the axis whose slot carries the surface length.
pub(crate) fn prepare(cmd: &mut Command, out: &Output) -> Result<(), Alarm> {
    let Some((rotary, carried)) = out.cylindrical_axes() else {
        return Ok(());
    };
    if cmd
        .g_codes()
        .any(|g| g.code == GCode::CylindricalInterpolation)
    {
        // G07.1 C0: its word is the radius, read by `switch`.
        return Ok(());
    }
    if let Some(g) = cmd.g_codes().find(|g| !allowed_in_mode(g.code)) {
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            g.span,
            format!(
                "{} cannot be commanded during cylindrical interpolation (G07.1)",
                g.code.description()
            ),
        )
        .with_help("cut with G01, G02 or G03; cancel the mode with G07.1 C0 first"));
    }
    if let Some(word) = cmd.axis(carried.index()) {
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            word.span,
            "this axis cannot be commanded during cylindrical interpolation (G07.1)",
        )
        .with_help("its slot carries the rotary axis on the surface; cancel with G07.1 C0"));
    }
    cmd.move_axis_word(rotary, carried);
    Ok(())
}

/// G07.1 (`g`) in a block: `G07.1 C r` starts the mode on the rotary axis named, `G07.1 C0`
/// ends it.
///
/// # Errors
/// Cutter compensation on, no rotary axis word (or more than one axis word), a rotary axis the
/// surface cannot be mapped for, or another transform in force.
pub(crate) fn switch(
    exec: &mut Executor,
    cmd: &Command,
    g: GWord,
    out: &mut Output,
) -> Result<(), Alarm> {
    if out.compensating() {
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            g.span,
            "G07.1 cannot be commanded while cutter compensation (G41/G42) is on",
        )
        .with_help("start and cancel compensation inside the mode (G40 before G07.1 C0)"));
    }
    let layout = &exec.kernel.setup.machine().layout;
    let mut words = cmd.axes_present();
    let (Some(axis), None) = (words.next(), words.next()) else {
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            g.span,
            "G07.1 takes one word: the rotary axis with the cylinder's radius (G07.1 C50.)",
        ));
    };
    let value = cmd
        .axis(axis.index())
        .expect("axes_present names a word of the block");
    let letter = layout.letter(axis);
    let carried = carrier(letter).filter(|_| layout.is_rotary(axis));
    let Some((carried, plane)) = carried.filter(|(c, _)| exec.kernel.setup.has_axis(*c)) else {
        return Err(Alarm::error(
            AlarmCode::AxisNotOnMachine,
            value.span,
            format!(
                "G07.1 needs a rotary axis A, B or C and the linear axis across it: {} is not one",
                char::from(letter)
            ),
        )
        .with_help("name the rotary axis with the cylinder's radius, e.g. G07.1 C50. on a machine whose C is rotary (`[axes.c] kind = \"rotary\"`)"));
    };
    let radius = exec.length(&value);
    match (out.cylindrical_axes(), radius) {
        (Some(_), r) if r != 0.0 => Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            g.span,
            "G07.1 while cylindrical interpolation is already on",
        )
        .with_help("cancel it with G07.1 C0 first")),
        (Some(_), _) => {
            cancel(exec, out);
            Ok(())
        }
        (None, r) if r > 0.0 => start(exec, (axis, carried, plane), r, g, out),
        (None, r) if r < 0.0 => Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            value.span,
            format!("G07.1's cylinder radius must be positive, not {r}"),
        )),
        // G07.1 C0 with the mode off changes nothing.
        (None, _) => Ok(()),
    }
}

/// The mode starts: the executor's position in the carrying slot becomes the surface length of
/// the rotary axis from its program zero.
fn start(
    exec: &mut Executor,
    (rotary, carried, plane): (Axis, Axis, Plane),
    radius: f64,
    g: GWord,
    out: &mut Output,
) -> Result<(), Alarm> {
    if out.polar_interpolating() || exec.kernel.frames.rotated() || exec.cycle.is_some() {
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            g.span,
            "G07.1 cannot be commanded while polar interpolation, a rotation or a canned cycle is on",
        )
        .with_help("cancel it (G13.1, G69, G80) before G07.1"));
    }
    let machine = exec.kernel.position;
    let offset = exec.kernel.frames.offset();
    let map = SurfaceMap {
        rotary: rotary.index(),
        carried: carried.index(),
        radius,
        machine_carried: machine[carried.index()],
    };
    exec.kernel.position[map.carried] =
        map.length(machine[map.rotary] - offset[map.rotary]) + offset[map.carried];
    let plane = std::mem::replace(&mut exec.modal.plane, plane);
    out.start_cylindrical_interpolation(CylindricalStage {
        pieces: PieceQueue::new(map, machine, exec.kernel.setup.profile()),
        plane,
    });
    Ok(())
}

/// `G07.1 C0`: the machine position back in the executor, the plane before G07.1 restored.
fn cancel(exec: &mut Executor, out: &mut Output) {
    if let Some((plane, machine)) = out.end_cylindrical_interpolation() {
        exec.kernel.position = machine;
        exec.modal.plane = plane;
    }
}

/// The stage between cutter compensation and the output queue while G07.1 is on.
#[derive(Clone, Debug)]
pub(crate) struct CylindricalStage {
    /// Surface items, as the executor and compensation queue them, and the map that cuts them.
    pub(crate) pieces: PieceQueue<SurfaceMap>,
    /// The plane before G07.1.
    plane: Plane,
}

impl CylindricalStage {
    /// The rotary axis and the slot that carries its surface length.
    pub(crate) fn axes(&self) -> (Axis, Axis) {
        let map = &self.pieces.map;
        (Axis::ALL[map.rotary], Axis::ALL[map.carried])
    }

    /// Converts the items compensation has released and appends them to `items`.
    pub(crate) fn settle(&mut self, items: &mut Vec<StreamItem>) {
        self.pieces.settle(items);
    }

    /// The mode ends: everything staged is converted. Returns the plane before G07.1 and the
    /// machine position where the last piece ended.
    pub(crate) fn flush(mut self, items: &mut Vec<StreamItem>) -> (Plane, [f64; AXES]) {
        let last = self.pieces.flush(items);
        (self.plane, last)
    }
}

/// The unrolled surface to the machine's axes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SurfaceMap {
    /// The rotary axis's slot.
    rotary: usize,
    /// The slot that carries the surface length while the mode is on.
    carried: usize,
    /// The cylinder's radius, mm.
    radius: f64,
    /// The machine's own position of the carrying axis, which the mode does not move.
    machine_carried: f64,
}

impl SurfaceMap {
    /// The surface length of `degrees` of the rotary axis.
    fn length(&self, degrees: f64) -> f64 {
        degrees.to_radians() * self.radius
    }

    /// The degrees of the rotary axis for `length` mm on the surface.
    fn degrees(&self, length: f64) -> f64 {
        (length / self.radius).to_degrees()
    }
}

impl PieceMap for SurfaceMap {
    /// The machine position of the surface point `p`: the rotary axis at its angle, the
    /// carrying axis where the machine has it.
    fn to_machine(
        &self,
        p: &[f64; AXES],
        offset: &[f64; AXES],
        _previous: &[f64; AXES],
    ) -> [f64; AXES] {
        let mut machine = *p;
        machine[self.rotary] =
            self.degrees(p[self.carried] - offset[self.carried]) + offset[self.rotary];
        machine[self.carried] = self.machine_carried;
        machine
    }

    /// The distance on the surface between the point a machine position puts the tool at and
    /// `p`.
    fn deviation(&self, machine: &[f64; AXES], offset: &[f64; AXES], p: &[f64; AXES]) -> f64 {
        let along = self.length(machine[self.rotary] - offset[self.rotary]) + offset[self.carried];
        let mut squares = (along - p[self.carried]).powi(2);
        for axis in 0..3 {
            if axis != self.carried {
                squares += (machine[axis] - p[axis]).powi(2);
            }
        }
        squares.sqrt()
    }
}
