//! F S T M and G04: the functions that are events rather than geometry.
//!
//! Spindle, coolant and tool-change M codes run before the block's motion; M00, M01, M02 and M30
//! after it. M codes the profile does not know are passed on to the machine as auxiliary events,
//! as a real control passes them to its PLC.

use super::decode::{Command, Value};
use super::exec::{end_program, stop, Executor, Flow};
use super::modal::{SpindleMode, Units};
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::machine::Axis;
use crate::motion::{EndKind, SegmentKind, SpindleState, StopKind};
use crate::profile::{classify_m, DwellP, MCode, MLookup, Profile};

/// S and T.
///
/// # Errors
/// A negative S.
pub(crate) fn speed_and_tool(
    exec: &mut Executor,
    cmd: &Command,
    out: &mut Output,
) -> Result<(), Alarm> {
    if let Some(s) = cmd.s() {
        if s.number.value < 0.0 {
            return Err(Alarm::error(
                AlarmCode::ValueOutOfRange,
                s.span,
                "spindle speed cannot be negative",
            ));
        }
        let g92 = cmd
            .group(crate::profile::Group::NonModal)
            .is_some_and(|g| g.code == crate::profile::GCode::SetCoordinates);
        if g92 {
            // `G92 S`: the clamp of constant surface speed, not a speed (Syntec 1.58, L4618).
            exec.kernel.spindle.set_clamp(s.number.value);
        } else {
            let speed = match exec.modal.spindle_mode {
                SpindleMode::Rpm => Some(s.number.value),
                SpindleMode::SurfaceSpeed => surface_speed_rpm(exec, cmd, s, out)?,
            };
            if let Some(speed) = speed {
                exec.kernel.spindle.set_speed(speed);
                let running = exec.kernel.spindle.running();
                let starts_here = cmd
                    .m_codes()
                    .iter()
                    .any(|m| matches!(m.number.value as u32, 3 | 4));
                if running && !starts_here {
                    out.push(cmd, exec.kernel.spindle.event());
                }
            }
        }
    }
    if let Some(t) = cmd.t() {
        exec.kernel.tools.select(t.number.value as u32);
        out.push(
            cmd,
            SegmentKind::ToolSelect {
                tool: exec.kernel.tools.selected(),
            },
        );
    }
    Ok(())
}

/// G96's S, a surface speed (m/min, or ft/min under G20), as the spindle speed that gives it on
/// the cutter: N = 1000 V / (pi D) with D the diameter of the radius register in force (the
/// block's D first), clamped by `G92 S` and the machine's top speed (Syntec 1.58, L4597-4628; a
/// mill's diameter is the cutter's, as the manual's example reads it). None, with a warning,
/// when the register gives no diameter.
///
/// # Errors
/// A D number out of range.
fn surface_speed_rpm(
    exec: &Executor,
    cmd: &Command,
    s: Value,
    out: &mut Output,
) -> Result<Option<f64>, Alarm> {
    let number = match cmd.word(b'D') {
        Some(d) => exec.kernel.setup.offset_number(d, 'D')?,
        None => exec.kernel.tools.radius_number(),
    };
    let register = exec.kernel.tools.radius(number);
    let profile = exec.kernel.setup.profile();
    let diameter_mm = if profile.compensation.radius_offsets_are_diameters {
        register
    } else {
        2.0 * register
    }
    .abs()
        * exec.modal.units.to_mm();
    if diameter_mm <= 0.0 {
        out.push_warning(
            Alarm::warning(
                AlarmCode::ValueOutOfRange,
                s.span,
                format!("G96 S{}: no cutter diameter (D{number} holds no radius), so no spindle speed follows from the surface speed", s.number.value),
            )
            .with_help("select the tool's radius register (D) before G96 S, or program G97 S in rpm"),
        );
        return Ok(None);
    }
    // m/min over mm, or ft/min (304.8 mm a foot) under G20.
    let per_minute_mm = match exec.modal.units {
        Units::Millimetres => 1000.0,
        Units::Inches => 304.8,
    } * s.number.value;
    let rpm = per_minute_mm / (std::f64::consts::PI * diameter_mm);
    let top = exec.kernel.setup.machine().spindle.max_rpm;
    Ok(Some(
        rpm.min(exec.kernel.spindle.clamp().unwrap_or(top)).min(top),
    ))
}

/// M codes that act before the motion of the block.
///
/// # Errors
/// Subprogram calls and returns (issue 3).
pub(crate) fn before_motion(
    exec: &mut Executor,
    cmd: &Command,
    out: &mut Output,
) -> Result<(), Alarm> {
    for m in cmd.m_codes() {
        let code = m.number.value as u32;
        let kind = match classify_m(code, exec.kernel.setup.profile()) {
            MLookup::NotSupported(issue) => {
                return Err(Alarm::not_supported(
                    m.span,
                    &format!("M{code:02} (subprogram call or return)"),
                    issue,
                ));
            }
            MLookup::Machine => SegmentKind::Auxiliary { code },
            MLookup::Known(known) => match known {
                MCode::ProgramStop
                | MCode::OptionalStop
                | MCode::ProgramEnd
                | MCode::ProgramEndRewind => continue,
                // Calls and returns: the macro layer runs them after the block.
                MCode::SubprogramCall
                | MCode::SubprogramReturn
                | MCode::ExternalSubprogramCall
                | MCode::LocalSubprogramCall
                | MCode::InterruptOn
                | MCode::InterruptOff => continue,
                MCode::SpindleClockwise => exec.kernel.spindle.turn(SpindleState::Clockwise),
                MCode::SpindleCounterClockwise => {
                    exec.kernel.spindle.turn(SpindleState::CounterClockwise)
                }
                MCode::SpindleStop => exec.kernel.spindle.turn(SpindleState::Stopped),
                MCode::SpindleOrientation => exec.kernel.spindle.turn(SpindleState::Oriented),
                MCode::ToolChange => {
                    let tool = exec.kernel.tools.change();
                    let diameters = exec
                        .kernel
                        .setup
                        .profile()
                        .compensation
                        .radius_offsets_are_diameters;
                    SegmentKind::ToolChange {
                        tool,
                        geometry: exec.kernel.tools.geometry(tool, diameters),
                        shape: exec.kernel.setup.machine().tool_shapes.get(tool),
                    }
                }
                MCode::CoolantOn => SegmentKind::Coolant { on: true },
                MCode::CoolantOff => SegmentKind::Coolant { on: false },
            },
        };
        out.push(cmd, kind);
    }
    Ok(())
}

/// M00, M01, M02, M30 after the motion.
///
/// # Errors
/// None yet.
pub(crate) fn after_motion(
    profile: &Profile,
    cmd: &Command,
    out: &mut Output,
) -> Result<Flow, Alarm> {
    for m in cmd.m_codes() {
        match classify_m(m.number.value as u32, profile) {
            MLookup::Known(MCode::ProgramStop) => stop(cmd, StopKind::Program, out),
            MLookup::Known(MCode::OptionalStop) => stop(cmd, StopKind::Optional, out),
            MLookup::Known(MCode::ProgramEnd) => return Ok(end_program(cmd, EndKind::M02, out)),
            MLookup::Known(MCode::ProgramEndRewind) => {
                return Ok(end_program(cmd, EndKind::M30, out))
            }
            _ => {}
        }
    }
    Ok(Flow::Next)
}

/// G04: dwell for P (milliseconds, or as the profile reads it) or X (seconds with a decimal
/// point, milliseconds without).
///
/// # Errors
/// A decimal point in P where the control forbids it; a negative time.
pub(crate) fn dwell(
    exec: &mut Executor,
    cmd: &Command,
    g04_order: usize,
    out: &mut Output,
) -> Result<(), Alarm> {
    let seconds = if let Some(p) = cmd.p() {
        p_seconds(exec.kernel.setup.profile().dwell.dwell_p, p)?
    } else if let Some(x) = cmd.axis(Axis::X.index()) {
        let n = x.number;
        if exec
            .kernel
            .setup
            .profile()
            .dwell
            .dwell_x_before_g04_is_increments
            && x.order < g04_order
            && n.decimal_point
        {
            // FANUC 0M (spec A.8): the X word was converted as a distance before G04 was read, so
            // its count of least increments becomes milliseconds.
            let increment = match exec.modal.units {
                Units::Millimetres => exec.kernel.setup.profile().units.increment_mm,
                Units::Inches => exec.kernel.setup.profile().units.increment_inch,
            };
            (n.value / increment).round() / 1000.0
        } else if n.decimal_point {
            n.value
        } else {
            n.value / 1000.0
        }
    } else {
        0.0
    };
    if seconds < 0.0 {
        return Err(Alarm::error(
            AlarmCode::BadDwell,
            cmd.span,
            "dwell time cannot be negative",
        ));
    }
    // G04 is a block of its own on the controls: its other axis words move nothing. Said, not
    // dropped quietly (`G01 X10. Y0. F100. G04 P1000`).
    let x_is_time = cmd.p().is_none();
    if let Some((_, value)) = cmd
        .axis_words()
        .find(|(axis, _)| !(x_is_time && *axis == Axis::X))
    {
        out.push_warning(
            Alarm::warning(
                AlarmCode::WordNotAllowed,
                value.span,
                "the axis words of a G04 block move nothing: the block only dwells",
            )
            .with_help("move in a block of its own, before or after the dwell"),
        );
    }
    out.push(cmd, SegmentKind::Dwell { seconds });
    Ok(())
}

/// A dwell's P in seconds, read as `rule` says.
///
/// # Errors
/// A fraction where the control takes whole milliseconds.
pub(crate) fn p_seconds(rule: DwellP, p: Value) -> Result<f64, Alarm> {
    let n = p.number;
    Ok(match rule {
        DwellP::MillisecondsStrict if n.decimal_point && n.value.fract() != 0.0 => {
            return Err(Alarm::error(
                AlarmCode::DecimalPointNotAllowed,
                p.span,
                "P is a whole number of milliseconds",
            )
            .with_help("write P1500 for 1.5 s"));
        }
        DwellP::MillisecondsStrict => n.value / 1000.0,
        DwellP::MillisecondsTruncated => n.value.trunc() / 1000.0,
        DwellP::SecondsWithPoint if n.decimal_point => n.value,
        DwellP::SecondsWithPoint => n.value / 1000.0,
    })
}
