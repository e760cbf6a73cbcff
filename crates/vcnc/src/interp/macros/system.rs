//! System variables: the control's state seen as numbered variables (#2001 tool offsets,
//! #4001 modal codes, #5001 positions, #5221 work offsets, #3000 alarms ...).
//!
//! Numbers follow the FANUC Custom Macro B manuals, which Syntec, Mitsubishi and Haas follow
//! for the common ones; where a control differs the profile says so (`tool_offset_variables`,
//! Syntec's #1000-range modal variables, Haas's timers and tool-life counters). A number no
//! control here defines is an alarm, never a silent zero. Lengths are read and written in the
//! program's units (mm or inch), as the control shows them.

use super::MacroValue;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::exec::Executor;
use crate::interp::modal::{
    CycleReturn, DistanceMode, FeedMode, LengthComp, MotionMode, SpindleMode, Units,
};
use crate::interp::Output;
use crate::machine::{Axis, WorkOffsetId, AXES};
use crate::motion::{ArcDirection, PathMode, Plane};
use crate::profile::{CycleKind, RotaryRollover, ToolOffsetVariables};
use crate::source::Span;

/// What writing a system variable asks of the interpreter besides storing a value.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum WriteEffect {
    /// Nothing more.
    None,
    /// `#3000 = n (MESSAGE)`: stop with alarm 3000 + n.
    Alarm(f64),
    /// `#3006 = n (MESSAGE)`: stop, show the message, go on at cycle start.
    Stop,
}

/// Clocks and counters the program can read and set (#3001, #3002, #3901, #3902).
#[derive(Clone, Debug, Default)]
pub(crate) struct Counters {
    /// #3001, milliseconds.
    pub(crate) clock_ms: f64,
    /// #3002, hours.
    pub(crate) clock_hours: f64,
    /// #3901.
    pub(crate) parts_done: f64,
    /// #3902.
    pub(crate) parts_required: f64,
    /// #3003, #3004 (single block and feed hold suppression): stored, no effect on a simulation.
    pub(crate) controls: [f64; 2],
}

fn unknown(number: u32, span: Span) -> Alarm {
    Alarm::error(
        AlarmCode::BadVariable,
        span,
        format!("#{number} is not a variable of this control"),
    )
    .with_help("locals are #1-#33, commons #100-#499 and #500-#999 (Syntec: locals #1-#400, persistent #401-#999); see the system variable list in docs/MACROS.md")
}

/// The axis index of `number - base` when it is 0..AXES.
fn axis_of(number: u32, base: u32) -> Option<usize> {
    number
        .checked_sub(base)
        .map(|i| i as usize)
        .filter(|&i| i < AXES)
}

/// The work offset register and axis of a work offset variable number.
fn work_offset_of(number: u32, profile_g54_1: u32) -> Option<(WorkOffsetId, usize)> {
    let register = |first: u32, count: u32| -> Option<(u32, usize)> {
        let i = number.checked_sub(first)?;
        let (register, axis) = (i / 20, (i % 20) as usize);
        (register < count && axis < AXES).then_some((register, axis))
    };
    if let Some((k, axis)) = register(5201, 7) {
        let id = if k == 0 {
            WorkOffsetId::External
        } else {
            WorkOffsetId::Standard(k as u8)
        };
        return Some((id, axis));
    }
    for (first, count) in [(7001, 48), (14001, 300)] {
        if let Some((p, axis)) = register(first, count.min(profile_g54_1)) {
            return Some((WorkOffsetId::Extended(p + 1), axis));
        }
    }
    None
}

/// Which field of the tool offset memory a number names: (offset number, field).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum ToolField {
    Length,
    LengthWear,
    Radius,
    RadiusWear,
}

fn tool_field_of(number: u32, layout: ToolOffsetVariables) -> Option<(u32, ToolField)> {
    use ToolField::*;
    let bank = |first: u32, count: u32, field: ToolField| {
        number
            .checked_sub(first)
            .filter(|i| *i < count)
            .map(|i| (i + 1, field))
    };
    match layout {
        // FANUC memory C: wear before geometry; #10001+ for up to 400 offsets.
        ToolOffsetVariables::FanucC => bank(2001, 200, LengthWear)
            .or_else(|| bank(2201, 200, Length))
            .or_else(|| bank(2401, 200, RadiusWear))
            .or_else(|| bank(2601, 200, Radius))
            .or_else(|| bank(10001, 400, LengthWear))
            .or_else(|| bank(11001, 400, Length))
            .or_else(|| bank(12001, 400, RadiusWear))
            .or_else(|| bank(13001, 400, Radius)),
        // Haas: geometry before wear, diameters for D.
        ToolOffsetVariables::Haas => bank(2001, 200, Length)
            .or_else(|| bank(2201, 200, LengthWear))
            .or_else(|| bank(2401, 200, Radius))
            .or_else(|| bank(2601, 200, RadiusWear)),
    }
}

/// Reads system variable `number`.
///
/// # Errors
/// A number this control does not have, or one that can only be written (#3000, #3006).
pub(crate) fn read(
    exec: &Executor,
    out: &Output,
    counters: &Counters,
    number: u32,
    span: Span,
) -> Result<MacroValue, Alarm> {
    let profile = exec.kernel.setup.profile();
    let to_units = 1.0 / exec.modal.units.to_mm();
    let length = |mm: f64| Some(mm * to_units);
    if let Some((n, field)) = tool_field_of(number, profile.macros.tool_offset_variables) {
        let offset = exec.kernel.tools.get(n).cloned().unwrap_or_default();
        let mm = match field {
            ToolField::Length => offset.length,
            ToolField::LengthWear => offset.length_wear,
            ToolField::Radius => offset.radius,
            ToolField::RadiusWear => offset.radius_wear,
        };
        return Ok(length(mm));
    }
    if let Some((id, axis)) = work_offset_of(number, profile.coordinates.g54_1_count) {
        return Ok(length(exec.kernel.frames.work_offset(id)[axis]));
    }
    if profile.macros.syntec_system_variables {
        match number {
            1000 => return Ok(Some(motion_code(exec.modal.motion) / 10.0)),
            1004 => return Ok(Some(distance_code(exec.modal.distance) / 10.0)),
            1901..=1916 => {
                return Ok(
                    axis_of(number, 1901).map_or(Some(0.0), |a| length(exec.kernel.frames.g92(a)))
                )
            }
            1930 => {
                return Ok(Some(
                    exec.kernel
                        .frames
                        .preset_rotation()
                        .map_or(0.0, |r| r.degrees),
                ))
            }
            _ => {}
        }
    }
    if profile.macros.haas_system_variables {
        match number {
            // Power-on, cycle-start, feed, part timers (seconds): the simulation has no clock.
            3020..=3025 => return Ok(Some(0.0)),
            3026 => return Ok(Some(f64::from(exec.kernel.tools.in_spindle()))),
            3027 => return Ok(Some(exec.kernel.spindle.speed())),
            // Tool-life counters and timers, per tool.
            5401..=5800 => return Ok(Some(0.0)),
            _ => {}
        }
    }
    let modal = |n: u32| modal_code(exec, out, n).map(Some);
    Ok(match number {
        3000 | 3006 => {
            return Err(Alarm::error(
                AlarmCode::BadVariable,
                span,
                format!("#{number} can only be written"),
            ))
        }
        3001 => Some(counters.clock_ms),
        3002 => Some(counters.clock_hours),
        3003 | 3004 => Some(counters.controls[(number - 3003) as usize]),
        // Date and time: fixed, so that runs are repeatable (docs/DEVIATIONS.md).
        3011 => Some(20_000_101.0),
        3012 => Some(0.0),
        3901 => Some(counters.parts_done),
        3902 => Some(counters.parts_required),
        4001..=4022 => match modal(number - 4000) {
            Some(v) => v,
            None => return Err(unknown(number, span)),
        },
        4102..=4130 => match letter_value(exec, number - 4100) {
            Some(v) => v,
            None => return Err(unknown(number, span)),
        },
        4201..=4222 if profile.macros.haas_system_variables => match modal(number - 4200) {
            Some(v) => v,
            None => return Err(unknown(number, span)),
        },
        4302..=4330 if profile.macros.haas_system_variables => {
            match letter_value(exec, number - 4300) {
                Some(v) => v,
                None => return Err(unknown(number, span)),
            }
        }
        5001..=5006 => {
            let program = exec.kernel.program_position();
            axis_of(number, 5001).and_then(|a| position(exec, a, program[a]))
        }
        5021..=5026 => {
            axis_of(number, 5021).and_then(|a| position(exec, a, exec.kernel.position[a]))
        }
        5041..=5046 => {
            let program = exec.kernel.program_position();
            axis_of(number, 5041).and_then(|a| position(exec, a, program[a]))
        }
        5061..=5066 => axis_of(number, 5061).and_then(|a| position(exec, a, exec.skip_position[a])),
        // Servo deviations: no servo lag.
        5101..=5106 => Some(0.0),
        5081..=5086 => {
            let a = axis_of(number, 5081).unwrap_or(0);
            if a == 2 {
                length(exec.kernel.frames.length_vector())
            } else {
                Some(0.0)
            }
        }
        _ => return Err(unknown(number, span)),
    })
}

/// Axis `a` of a position as a program reads it: a length in the program's unit, a rotary
/// axis in degrees, within one turn (0 to 360) when the machine rolls its rotary axes over.
/// FANUC rounds the absolute and machine coordinates of a roll-over axis to one rotation
/// (B-63534EN 20.2.1, its example: `G90 A-150.` from 0 reads 210); the motion stream keeps the
/// continuous position, which is what the axis travelled.
fn position(exec: &Executor, a: usize, value: f64) -> MacroValue {
    let setup = &exec.kernel.setup;
    if !setup.machine().layout.is_rotary(Axis::ALL[a]) {
        return Some(value / exec.modal.units.to_mm());
    }
    if setup.profile().motion.rotary_rollover == RotaryRollover::Off {
        return Some(value);
    }
    let turn = value.rem_euclid(360.0);
    // A hair below a whole turn (a position of -1e-13) is the turn's start.
    Some(if 360.0 - turn < 1e-9 { 0.0 } else { turn })
}

/// Writes system variable `number`.
///
/// # Errors
/// A number this control does not have or does not let a program write.
pub(crate) fn write(
    exec: &mut Executor,
    counters: &mut Counters,
    number: u32,
    value: MacroValue,
    span: Span,
) -> Result<WriteEffect, Alarm> {
    let mm = value.unwrap_or(0.0) * exec.modal.units.to_mm();
    if let Some((n, field)) = tool_field_of(
        number,
        exec.kernel.setup.profile().macros.tool_offset_variables,
    ) {
        exec.kernel.tools.write(n, |offset| match field {
            ToolField::Length => offset.length = mm,
            ToolField::LengthWear => offset.length_wear = mm,
            ToolField::Radius => offset.radius = mm,
            ToolField::RadiusWear => offset.radius_wear = mm,
        });
        return Ok(WriteEffect::None);
    }
    if let Some((id, axis)) =
        work_offset_of(number, exec.kernel.setup.profile().coordinates.g54_1_count)
    {
        exec.kernel.frames.set_work_offset(id, axis, mm);
        return Ok(WriteEffect::None);
    }
    let v = value.unwrap_or(0.0);
    match number {
        3000 => Ok(WriteEffect::Alarm(v)),
        3006 => Ok(WriteEffect::Stop),
        3001 => {
            counters.clock_ms = v;
            Ok(WriteEffect::None)
        }
        3002 => {
            counters.clock_hours = v;
            Ok(WriteEffect::None)
        }
        3003 | 3004 => {
            counters.controls[(number - 3003) as usize] = v;
            Ok(WriteEffect::None)
        }
        3901 => {
            counters.parts_done = v;
            Ok(WriteEffect::None)
        }
        3902 => {
            counters.parts_required = v;
            Ok(WriteEffect::None)
        }
        _ => Err(Alarm::error(
            AlarmCode::BadVariable,
            span,
            format!("#{number} cannot be written by a program"),
        )),
    }
}

/// G codes in tenths of the motion and distance groups.
fn motion_code(mode: MotionMode) -> f64 {
    match mode {
        MotionMode::Rapid => 0.0,
        MotionMode::Linear => 10.0,
        MotionMode::Arc(ArcDirection::Clockwise) => 20.0,
        MotionMode::Arc(ArcDirection::CounterClockwise) => 30.0,
        MotionMode::Thread => 330.0,
    }
}

fn distance_code(mode: DistanceMode) -> f64 {
    match mode {
        DistanceMode::Absolute => 900.0,
        DistanceMode::Incremental => 910.0,
    }
}

/// The G code in force in FANUC's modal group `group` (#4001 is group 1), as a number.
fn modal_code(exec: &Executor, out: &Output, group: u32) -> Option<f64> {
    let m = &exec.modal;
    let tenths = match group {
        1 => match &exec.cycle {
            Some(cycle) => cycle_code(cycle.kind()),
            None => motion_code(m.motion),
        },
        2 => match m.plane {
            Plane::Xy => 170.0,
            Plane::Zx => 180.0,
            Plane::Yz => 190.0,
        },
        3 => distance_code(m.distance),
        4 => 230.0,
        5 => match m.feed_mode {
            FeedMode::InverseTime => 930.0,
            FeedMode::PerMinute => 940.0,
            FeedMode::PerRevolution => 950.0,
        },
        6 => match m.units {
            Units::Inches => 200.0,
            Units::Millimetres => 210.0,
        },
        7 => match out.compensation() {
            None => 400.0,
            Some(comp) if comp.left() => 410.0,
            Some(_) => 420.0,
        },
        8 => match m.length_comp {
            LengthComp::Plus => 430.0,
            LengthComp::Minus => 440.0,
            LengthComp::CenterPoint => 434.0,
            LengthComp::Off => 490.0,
        },
        9 => exec.cycle.as_ref().map_or(800.0, |c| cycle_code(c.kind())),
        10 => match m.cycle_return {
            CycleReturn::InitialLevel => 980.0,
            CycleReturn::RLevel => 990.0,
        },
        11 => {
            if exec.scaling.scaling_on() {
                510.0
            } else {
                500.0
            }
        }
        12 => 670.0,
        13 => match m.spindle_mode {
            SpindleMode::SurfaceSpeed => 960.0,
            SpindleMode::Rpm => 970.0,
        },
        14 => match m.work_offset {
            WorkOffsetId::Standard(n) => 530.0 + 10.0 * f64::from(n),
            WorkOffsetId::Extended(_) => 541.0,
            // ISO programs select neither: the external offset and SINUMERIK's G500 are no
            // work system of their own.
            WorkOffsetId::External | WorkOffsetId::Settable(_) => 540.0,
        },
        15 => match m.path_mode {
            PathMode::ExactStop => 610.0,
            PathMode::CornerOverride => 620.0,
            PathMode::Tapping => 630.0,
            PathMode::Continuous => 640.0,
        },
        16 => {
            if exec.kernel.frames.rotation().is_some() {
                680.0
            } else {
                690.0
            }
        }
        17 => {
            if exec.polar.is_some() {
                160.0
            } else {
                150.0
            }
        }
        // FANUC's group 21 is G12.1/G13.1 (polar coordinate interpolation), G13.1 at power-on;
        // a control without the function has nothing in it.
        21 if exec.kernel.setup.profile().motion.polar_interpolation => {
            if out.polar_interpolating() {
                121.0
            } else {
                131.0
            }
        }
        18..=22 => return Some(0.0),
        _ => return None,
    };
    Some(tenths / 10.0)
}

fn cycle_code(kind: CycleKind) -> f64 {
    match kind {
        CycleKind::HighSpeedPeck => 730.0,
        CycleKind::LeftHandTap => 740.0,
        CycleKind::FineBoring => 760.0,
        CycleKind::Drill => 810.0,
        CycleKind::DrillDwell => 820.0,
        CycleKind::Peck => 830.0,
        CycleKind::Tap => 840.0,
        CycleKind::Bore => 850.0,
        CycleKind::BoreSpindleStop => 860.0,
        CycleKind::BackBore => 870.0,
        CycleKind::BoreManualRetract => 880.0,
        CycleKind::BoreDwell => 890.0,
    }
}

/// #4102 (B) ... #4130 (P): the last value of an address (`letter` is 2 for B ... 30 for P).
fn letter_value(exec: &Executor, letter: u32) -> Option<MacroValue> {
    Some(match letter {
        // B, E, M, N, O: not kept by vcnc's executor; FANUC gives the last one read.
        2 | 8 | 13 | 14 | 15 => Some(0.0),
        7 => Some(f64::from(exec.kernel.tools.radius_number())),
        9 => Some(exec.kernel.feed.unwrap_or(0.0) / exec.modal.units.to_mm()),
        11 => Some(f64::from(exec.kernel.tools.length_number())),
        19 => Some(exec.kernel.spindle.speed()),
        20 => Some(f64::from(exec.kernel.tools.selected())),
        30 => match exec.modal.work_offset {
            WorkOffsetId::Extended(p) => Some(f64::from(p)),
            _ => Some(0.0),
        },
        _ => return None,
    })
}
