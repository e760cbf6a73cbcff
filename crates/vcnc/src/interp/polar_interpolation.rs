//! G12.1/G13.1 polar coordinate interpolation: a contour programmed in the Cartesian plane of the
//! linear axis X and a hypothetical axis C becomes motion of X (the radius) and of the rotary axis
//! C (the angle). Spec: spec/iso-syntec-milling.md 1.13 (seed 000 L894-1017); FANUC and
//! Mitsubishi M-series controls have the same codes.
//!
//! How it sits in the pipeline:
//!
//! - While the mode is on, the executor works in the Cartesian plane. [`prepare`] reads the
//!   address C of each block as a length and carries it in the Y slot of positions, and G12.1
//!   selects G17, so that lines, arcs (I J or R) and cutter compensation run unchanged in that
//!   plane. The machine's own Y stays where it was (a Y word is refused in the mode).
//! - [`PolarStage`] sits in the output queue after cutter compensation. A segment compensation
//!   has released is cut into straight pieces in machine X and C whose ends lie on the
//!   programmed (compensated) path, each short enough that the piece, seen on the part, stays
//!   within the profile's `polar_interpolation_tolerance` of that path. Nothing Cartesian
//!   leaves the stage.
//! - G13.1 puts the machine position back in the executor and restores the plane (rule 4).
//!
//! Geometry (the spec's inferred FANUC conversion): the rotation centre is the program zero of X
//! and C; G12.1's X and C put the program zero off it (eccentricity, Syntec 10.116.11 on). A
//! Cartesian point (x, c) lies at u = x + ex, v = c + ec from the centre; the machine goes to
//! X = |(u, v)| (a radius: vcnc has no diameter axes) and C = atan2(v, u) in degrees from the
//! program zero of C, kept continuous from piece to piece (no jump at ±180 degrees). At the
//! centre the angle keeps its last value; leaving it, C turns within a piece shorter than the
//! tolerance.
//!
//! The control keeps the block's feed as the speed along the contour on the part, so every piece
//! carries the time its share of the contour takes, as an inverse-time feed (G93's block time is
//! shared out the same way). Rapids are cut the same
//! way and stay rapids, on the Cartesian straight line.
//!
//! What it must never do: cost anything when the mode is off (the queue asks for the stage only
//! when it exists).

use super::decode::{Command, GWord};
use super::exec::Executor;
use super::frames::sin_cos_degrees;
use super::pieces::{self, PieceMap};
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::machine::{Axis, AXES};
use crate::motion::{Plane, StreamItem};
use crate::profile::{GCode, Group};

/// The linear axis of the plane: the radius.
const LINEAR: usize = Axis::X.index();
/// The rotary axis C, the angle.
const ROTARY_AXIS: Axis = Axis::C;
/// [`ROTARY_AXIS`]'s index.
const ROTARY: usize = ROTARY_AXIS.index();
/// The slot of positions that carries the hypothetical axis while the mode is on.
const HYPOTHETICAL: usize = Axis::Y.index();

/// Closer than this to the rotation centre, mm, a point has no angle of its own.
const CENTRE: f64 = 1e-9;

/// Before a block in the mode: refuses the codes the mode does not allow and reads the address
/// C as the hypothetical axis.
///
/// # Errors
/// [`AlarmCode::WordNotAllowed`] for a G code the mode does not allow (spec 1.13.2 rules 3-5)
/// or a Y word.
pub(crate) fn prepare(cmd: &mut Command) -> Result<(), Alarm> {
    if let Some(g) = cmd.g_codes().find(|g| !allowed_in_mode(g.code)) {
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            g.span,
            format!(
                "{} cannot be commanded during polar coordinate interpolation (G12.1)",
                g.code.description()
            ),
        )
        .with_help("cancel the mode with G13.1 first"));
    }
    if let Some(y) = cmd.axis(HYPOTHETICAL) {
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            y.span,
            "Y cannot be commanded during polar coordinate interpolation (G12.1)",
        )
        .with_help("the plane is X and C; cancel the mode with G13.1 to move Y"));
    }
    cmd.move_axis_word(ROTARY_AXIS, Axis::Y);
    Ok(())
}

/// The codes the mode allows: motion and the modes that do not move the coordinate system
/// (spec 1.13.2 rule 3 lists G01, G02, G03, G04, G40-G42, G65-G67; G00, G90/G91, the feed,
/// path and spindle modes change nothing in the plane and are accepted too).
pub(super) fn allowed_in_mode(code: GCode) -> bool {
    match code.group() {
        Group::Motion
        | Group::Distance
        | Group::FeedMode
        | Group::CutterComp
        | Group::ModalMacro
        | Group::PathMode
        | Group::SpindleMode
        | Group::CycleReturn
        | Group::PolarInterpolation => true,
        Group::NonModal => matches!(code, GCode::Dwell | GCode::ExactStopOnce | GCode::MacroCall),
        _ => false,
    }
}

/// G12.1 or G13.1 (`g`) in a block.
///
/// # Errors
/// Cutter compensation on (spec 1.13.2 rule 6), G12.1 on a machine without X or C, or with
/// words it does not take; see [`start`] and [`cancel`].
pub(crate) fn switch(
    exec: &mut Executor,
    cmd: &Command,
    g: GWord,
    out: &mut Output,
) -> Result<(), Alarm> {
    let name = match g.code {
        GCode::PolarInterpolation => "G12.1",
        _ => "G13.1",
    };
    if out.compensating() {
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            g.span,
            format!("{name} cannot be commanded while cutter compensation (G41/G42) is on"),
        )
        .with_help("cancel compensation with G40 in an earlier block"));
    }
    match g.code {
        GCode::PolarInterpolation => start(exec, cmd, g, out),
        _ => cancel(exec, cmd, out),
    }
}

/// G12.1: the executor's position becomes the Cartesian point of the tool, the plane G17.
fn start(exec: &mut Executor, cmd: &Command, g: GWord, out: &mut Output) -> Result<(), Alarm> {
    if out.polar_interpolating() {
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            g.span,
            "G12.1 while polar coordinate interpolation is already on",
        ));
    }
    let layout = &exec.kernel.setup.machine().layout;
    for (axis, letter) in [(Axis::X, 'X'), (ROTARY_AXIS, 'C')] {
        let named = layout.by_letter(letter as u8) == Some(axis)
            && layout.is_rotary(axis) == (letter == 'C');
        if !exec.kernel.setup.has_axis(axis) || !named {
            return Err(Alarm::error(
                AlarmCode::AxisNotOnMachine,
                g.span,
                format!("G12.1 needs the {letter} axis: the machine has none"),
            )
            .with_help(
                "polar coordinate interpolation moves X and turns the rotary axis C; add them to the machine file (`[axes.c]`)",
            ));
        }
    }
    if let Some(axis) = cmd
        .axes_present()
        .find(|a| *a != Axis::X && *a != ROTARY_AXIS)
    {
        let span = cmd.axis(axis.index()).map_or(g.span, |v| v.span);
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            span,
            "G12.1 takes only X and C (the program zero's offset from the rotation centre)",
        ));
    }
    refuse_transforms(exec, g)?;
    let eccentricity = (
        cmd.axis(LINEAR).map_or(0.0, |v| exec.length(&v)),
        cmd.axis(ROTARY).map_or(0.0, |v| exec.length(&v)),
    );
    let machine = exec.kernel.position;
    let offset = exec.kernel.frames.offset();
    let radius = machine[LINEAR] - offset[LINEAR];
    if radius < 0.0 {
        // The conversion keeps X at or above the centre; starting below it, the first piece
        // would swing X through the centre with C half a turn round.
        return Err(Alarm::not_supported(
            g.span,
            "G12.1 with X below the rotation centre (a negative radius)",
            None,
        )
        .with_help("position X at or above the program zero of X before G12.1"));
    }
    let (sin, cos) = sin_cos_degrees(machine[ROTARY] - offset[ROTARY]);
    exec.kernel.position[LINEAR] = radius * cos - eccentricity.0 + offset[LINEAR];
    exec.kernel.position[HYPOTHETICAL] = radius * sin - eccentricity.1 + offset[HYPOTHETICAL];
    let plane = std::mem::replace(&mut exec.modal.plane, Plane::Xy);
    out.start_polar_interpolation(PolarStage {
        staged: Vec::new(),
        held: None,
        plane,
        converter: Converter {
            eccentricity,
            machine_y: machine[HYPOTHETICAL],
            last: machine,
            tolerance: exec
                .kernel
                .setup
                .profile()
                .motion
                .polar_interpolation_tolerance,
        },
    });
    Ok(())
}

/// G12.1 while a transform or a canned cycle is in force: an alarm, as on the control. The mode
/// allows only motion, dwell, compensation and macro calls (spec 1.13.2 rule 3) and no change of
/// the coordinate system (rule 5); a rotation, scaling, mirror, G16 or cycle left on would apply
/// to every block of the mode, so the control refuses G12.1 until it is cancelled.
fn refuse_transforms(exec: &Executor, g: GWord) -> Result<(), Alarm> {
    let active = [
        (
            exec.kernel.frames.rotated(),
            "coordinate rotation (G68, G92.1 R)",
            "G69",
        ),
        (
            exec.kernel.frames.scaling().is_some(),
            "scaling or mirror image (G51, G51.1)",
            "G50 or G50.1",
        ),
        (
            exec.polar.is_some(),
            "polar coordinate command (G16)",
            "G15",
        ),
        (exec.cycle.is_some(), "a canned cycle", "G80"),
    ];
    match active.iter().find(|(on, ..)| *on) {
        Some((_, what, cancel)) => Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            g.span,
            format!("G12.1 cannot be commanded while {what} is on"),
        )
        .with_help(format!(
            "polar coordinate interpolation allows no transform or cycle: cancel it with {cancel} before G12.1"
        ))),
        None => Ok(()),
    }
}

/// G13.1: the machine position back in the executor, the plane before G12.1 restored.
fn cancel(exec: &mut Executor, cmd: &Command, out: &mut Output) -> Result<(), Alarm> {
    if let Some(axis) = cmd.axes_present().next() {
        let span = cmd.axis(axis.index()).map_or(cmd.span, |v| v.span);
        return Err(
            Alarm::error(AlarmCode::WordNotAllowed, span, "G13.1 takes no axis words")
                .with_help("move in a block of its own"),
        );
    }
    if let Some((plane, machine)) = out.end_polar_interpolation() {
        exec.kernel.position = machine;
        exec.modal.plane = plane;
    }
    Ok(())
}

/// The stage between cutter compensation and the output queue while G12.1 is on.
#[derive(Clone, Debug)]
pub(crate) struct PolarStage {
    /// Cartesian items, as the executor and compensation queue them.
    pub(crate) staged: Vec<StreamItem>,
    /// Items from this index on wait for compensation to know where a move ends.
    pub(crate) held: Option<usize>,
    /// The plane before G12.1.
    plane: Plane,
    converter: Converter,
}

impl PolarStage {
    /// Converts the items compensation has released and appends them to `items`.
    pub(crate) fn settle(&mut self, items: &mut Vec<StreamItem>) {
        let mut last = self.converter.last;
        pieces::settle(
            (&mut self.staged, &mut self.held),
            &self.converter,
            (&mut last, self.converter.tolerance),
            items,
        );
        self.converter.last = last;
    }

    /// The mode ends: everything staged is converted. Returns the plane before G12.1 and the
    /// machine position where the last piece ended.
    pub(crate) fn flush(mut self, items: &mut Vec<StreamItem>) -> (Plane, [f64; AXES]) {
        self.held = None;
        self.settle(items);
        (self.plane, self.converter.last)
    }
}

/// Cartesian points to machine X and C.
#[derive(Clone, Debug)]
struct Converter {
    /// G12.1's X and C: the program zero's offset from the rotation centre, mm.
    eccentricity: (f64, f64),
    /// The machine's Y, which the mode does not move.
    machine_y: f64,
    /// The machine position where the last piece ended (where G12.1 found the tool at first).
    last: [f64; AXES],
    /// Largest distance between a piece and the Cartesian path, mm.
    tolerance: f64,
}

/// `degrees` brought into [-180, 180).
fn wrap(degrees: f64) -> f64 {
    degrees - 360.0 * ((degrees + 180.0) / 360.0).floor()
}

impl PieceMap for Converter {
    /// The machine position of the Cartesian point `p`, its C next to the previous position's.
    fn to_machine(
        &self,
        p: &[f64; AXES],
        offset: &[f64; AXES],
        previous: &[f64; AXES],
    ) -> [f64; AXES] {
        let previous_c = previous[ROTARY];
        let u = p[LINEAR] - offset[LINEAR] + self.eccentricity.0;
        let v = p[HYPOTHETICAL] - offset[HYPOTHETICAL] + self.eccentricity.1;
        let radius = u.hypot(v);
        let mut machine = *p;
        machine[LINEAR] = offset[LINEAR] + radius;
        machine[HYPOTHETICAL] = self.machine_y;
        machine[ROTARY] = if radius > CENTRE {
            let c = v.atan2(u).to_degrees() + offset[ROTARY];
            previous_c + wrap(c - previous_c)
        } else {
            previous_c
        };
        machine
    }

    /// The distance in the plane between the Cartesian point (X and the hypothetical axis,
    /// executor coordinates) of a machine position and `p`.
    fn deviation(&self, machine: &[f64; AXES], offset: &[f64; AXES], p: &[f64; AXES]) -> f64 {
        let radius = machine[LINEAR] - offset[LINEAR];
        let (sin, cos) = (machine[ROTARY] - offset[ROTARY]).to_radians().sin_cos();
        let x = radius * cos - self.eccentricity.0 + offset[LINEAR];
        let y = radius * sin - self.eccentricity.1 + offset[HYPOTHETICAL];
        (x - p[LINEAR]).hypot(y - p[HYPOTHETICAL])
    }
}
