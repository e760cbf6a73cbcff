//! Syntec's automatic tool length measurement: G37 (spec 1.22, manual 000 L1465-1555) and G37.1
//! (spec 1.23, L1559-1649), against the tool setter of the machine file's `[probe]`.
//!
//! G37 `Z_ [R_] [D_] [F_] [P_]` (L1489-1495): a G30-style return to reference point P (none
//! unless P, or its default, is 1-4), Z at rapid to Z + R, then Z in the manner of G31 at F to
//! Z + D (a touch there is MAR-335) and on to Z (no touch by then is MAR-336), Z in program
//! coordinates. The manual's figures are lost; vcnc's choice: Z is the lowest point of the
//! measuring travel, as MAR-330 names it ("Z-axis lowest point setting error", L1515), so the
//! window where the signal may come is Z + D down to Z (the spec infers Z + D to Z - D).
//!
//! G37.1 `[Z_] [R_] [F_] [P_] [Q_]` (L1579-1592): air blow on (M90), the return, Z at rapid to
//! Z + R, air blow off (M91), Z toward Z (machine coordinates) until the touch, back 1 mm at
//! rapid, a second touch at F50, and Z at rapid to the safe point Q (default the machine zero,
//! taken as reference point 1).
//!
//! The result (L1495, L1591): the length register of the H number in force (the manual: the
//! tool number H names, L1517) gets the measured length, the control point's Z at the touch
//! less the setter's face (so the tool of the machine file's length L touching the face
//! measures L), its wear cleared: the register then holds what was measured (vcnc's choice; the
//! manual says only that the result is filled in). The words left out take the machine file's
//! `[probe.measurement]` (the control's Pr4055-Pr4059). The feed of the touches is F, or the
//! default; a measuring feed not written in the block does not stay in force.

use super::decode::Command;
use super::exec::Executor;
use super::skip::skip_to;
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::machine::Axis;
use crate::motion::SegmentKind;
use crate::probe::{Signal, ToolSetter};
use crate::source::Span;

/// Which of the two measurements.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Measurement {
    /// G37: Z in program coordinates, one touch inside an allowed window.
    Window,
    /// G37.1: Z in machine coordinates, a fast touch and a slow one.
    TwoTouches,
}

/// The feed of G37.1's second touch, mm/min (L1587).
const SLOW_TOUCH_FEED: f64 = 50.0;

/// How far G37.1 backs off between the touches, mm (L1586).
const BACK_OFF: f64 = 1.0;

/// The air blow of G37.1 (L1581, L1584).
const AIR_BLOW_ON: u32 = 90;
const AIR_BLOW_OFF: u32 = 91;

/// Runs a G37 or G37.1 block.
///
/// # Errors
/// [`AlarmCode::Probing`] for the manual's MAR alarms and a machine without a tool setter; the
/// moves' alarms.
pub(crate) fn run(
    exec: &mut Executor,
    cmd: &Command,
    span: Span,
    kind: Measurement,
    out: &mut Output,
) -> Result<(), Alarm> {
    let setter = exec.probe.tool_setter().ok_or_else(|| {
        alarm(span, "no tool setter to measure against")
            .with_help("describe it in the machine file: [probe.tool_setter] x, y, z (its face)")
    })?;
    let h = exec.kernel.tools.length_number();
    if h == 0 {
        return Err(
            alarm(span, "no H number before the tool measurement (MAR-334)")
                .with_help("select the register to write with an H word in an earlier block"),
        );
    }
    let defaults = exec.probe.measurement();
    let z = measuring_position(exec, cmd, span, kind)?;
    let r = cmd
        .r()
        .map_or(defaults.measuring_distance, |r| exec.length(&r));
    let saved_feed = exec.kernel.feed;
    if cmd.f().is_none() {
        exec.kernel.feed = Some(defaults.feed);
    }
    if kind == Measurement::TwoTouches {
        out.push(cmd, SegmentKind::Auxiliary { code: AIR_BLOW_ON });
    }
    let p = cmd
        .p()
        .map_or(defaults.reference_point, |p| p.number.value as u32);
    return_to_reference(exec, cmd, p, out)?;
    if exec.kernel.position[Axis::Z.index()] <= z {
        return Err(alarm(
            span,
            "Z does not start above the measuring position (MAR-333)",
        ));
    }
    rapid_z(exec, cmd, z + r, out)?;
    let touch = match kind {
        Measurement::Window => window(exec, cmd, span, z, out)?,
        Measurement::TwoTouches => two_touches(exec, cmd, span, z, out)?,
    };
    write_length(exec, h, touch, setter);
    exec.kernel.feed = if cmd.f().is_some() {
        exec.kernel.feed
    } else {
        saved_feed
    };
    if kind == Measurement::TwoTouches {
        let safe = match cmd.word(b'Q') {
            Some(q) => exec.length(&q),
            None => exec.kernel.setup.machine().reference_points[0][Axis::Z.index()],
        };
        rapid_z(exec, cmd, safe, out)?;
    }
    Ok(())
}

/// The measuring position, machine Z: G37's Z in program coordinates, G37.1's in machine
/// coordinates or the machine file's default.
fn measuring_position(
    exec: &mut Executor,
    cmd: &Command,
    span: Span,
    kind: Measurement,
) -> Result<f64, Alarm> {
    let z_word = cmd.axis(Axis::Z.index());
    match (kind, z_word) {
        (Measurement::Window, Some(z)) => {
            let mut program = exec.kernel.program_position();
            program[Axis::Z.index()] = exec.length(&z);
            Ok(exec.machine_target(&program, true)[Axis::Z.index()])
        }
        (Measurement::TwoTouches, Some(z)) => Ok(exec.length(&z)),
        (Measurement::TwoTouches, None) => {
            exec.probe.measurement().position.ok_or_else(|| no_z(span))
        }
        (Measurement::Window, None) => Err(no_z(span)),
    }
}

fn no_z(span: Span) -> Alarm {
    alarm(span, "the measuring position Z is not given (MAR-330)")
}

/// The G30-style return of step 1: every axis at rapid to reference point `p`, when it is one
/// of the machine's (L1491: none otherwise).
fn return_to_reference(
    exec: &mut Executor,
    cmd: &Command,
    p: u32,
    out: &mut Output,
) -> Result<(), Alarm> {
    let points = &exec.kernel.setup.machine().reference_points;
    let Some(point) = (p as usize)
        .checked_sub(1)
        .and_then(|i| points.get(i))
        .copied()
    else {
        return Ok(());
    };
    exec.rapid_to(point, cmd, out)
}

/// Z alone at rapid to machine `z`.
fn rapid_z(exec: &mut Executor, cmd: &Command, z: f64, out: &mut Output) -> Result<(), Alarm> {
    let mut target = exec.kernel.position;
    target[Axis::Z.index()] = z;
    exec.rapid_to(target, cmd, out)
}

/// Z alone toward machine `z` until the tool setter's signal; Z of the touch, if any.
fn touch_z(
    exec: &mut Executor,
    cmd: &Command,
    z: f64,
    out: &mut Output,
) -> Result<Option<f64>, Alarm> {
    let mut target = exec.kernel.position;
    target[Axis::Z.index()] = z;
    let touch = skip_to(exec, target, cmd, Signal::ToolSetter, out)?;
    Ok(touch.map(|p| p[Axis::Z.index()]))
}

/// G37's steps 3 and 4: no touch before Z + D, a touch by Z.
fn window(
    exec: &mut Executor,
    cmd: &Command,
    span: Span,
    z: f64,
    out: &mut Output,
) -> Result<f64, Alarm> {
    let d = cmd
        .word(b'D')
        .map_or(exec.probe.measurement().allowed_distance, |d| {
            exec.length(&d)
        });
    if touch_z(exec, cmd, z + d, out)?.is_some() {
        return Err(alarm(
            span,
            "the measuring signal came before the allowed distance (MAR-335)",
        ));
    }
    touch_z(exec, cmd, z, out)?.ok_or_else(|| not_triggered(span))
}

/// G37.1's steps 5 to 7: a touch toward Z, back off, a slow touch.
fn two_touches(
    exec: &mut Executor,
    cmd: &Command,
    span: Span,
    z: f64,
    out: &mut Output,
) -> Result<f64, Alarm> {
    out.push(cmd, SegmentKind::Auxiliary { code: AIR_BLOW_OFF });
    let first = touch_z(exec, cmd, z, out)?.ok_or_else(|| not_triggered(span))?;
    rapid_z(exec, cmd, first + BACK_OFF, out)?;
    let feed = exec.kernel.feed;
    exec.kernel.feed = Some(SLOW_TOUCH_FEED);
    let second = touch_z(exec, cmd, z, out);
    exec.kernel.feed = feed;
    second?.ok_or_else(|| not_triggered(span))
}

fn not_triggered(span: Span) -> Alarm {
    alarm(
        span,
        "the tool setter's signal did not come by the end of the measuring move (MAR-336)",
    )
    .with_help("check the measuring position Z and the tool setter's place under [probe]")
}

/// Step 5: the H register in force gets the measured length, its wear cleared.
fn write_length(exec: &mut Executor, h: u32, touch: f64, setter: ToolSetter) {
    let measured = touch - setter.z;
    exec.kernel.tools.write(h, |offset| {
        offset.length = measured;
        offset.length_wear = 0.0;
    });
}

fn alarm(span: Span, message: &str) -> Alarm {
    Alarm::error(AlarmCode::Probing, span, message.to_string())
}
