//! G10: programmable data input of work offsets and tool offsets.
//!
//! `G10 L2 Pp X Y Z` sets work offset p (P0 external, P1-P6 G54-G59, Syntec P7-P15 G59.1-G59.9;
//! P omitted: the one in use), `G10 L20 Pn ...` the G54.1 Pn offsets, and the profile's tool
//! offset L numbers `G10 Lnn P<number> R<value>`. In G90 the value replaces the stored one, in G91
//! it is added (spec B.5; A.24 relies on it).

use super::decode::{Command, Value};
use super::exec::Executor;
use super::modal::DistanceMode;
use crate::alarm::{Alarm, AlarmCode};
use crate::machine::{Axis, WorkOffsetId};
use crate::profile::{Group, ToolOffsetField};

/// Runs a G10 block.
///
/// # Errors
/// [`AlarmCode::BadDataInput`] for an L the profile does not have or a missing P/R;
/// [`AlarmCode::WorkOffsetOutOfRange`] and [`AlarmCode::OffsetNumberOutOfRange`] for bad P.
pub(crate) fn g10(exec: &mut Executor, cmd: &Command) -> Result<bool, Alarm> {
    let g10_span = cmd.group(Group::NonModal).map_or(cmd.span, |g| g.span);
    let l = cmd.l().and_then(|l| l.number.whole());
    let profile = exec.kernel.setup.profile();
    if let Some(l) = l {
        if l == i64::from(profile.coordinates.g10_work_l) {
            let id = standard_offset(exec, cmd)?;
            set_work_offset(exec, cmd, id);
            return Ok(true);
        }
        if profile.coordinates.g10_extended_work_l != 0
            && l == i64::from(profile.coordinates.g10_extended_work_l)
        {
            let id = extended_offset(exec, cmd, g10_span)?;
            set_work_offset(exec, cmd, id);
            return Ok(true);
        }
    }
    let field = match l {
        Some(l) => profile
            .compensation
            .g10_tool_l
            .iter()
            .find(|t| i64::from(t.l) == l)
            .map(|t| t.field),
        None => profile.compensation.g10_tool_default,
    };
    let Some(field) = field else {
        let span = cmd.l().map_or(g10_span, |v| v.span);
        let message = match l {
            Some(l) => format!(
                "G10 L{l} is not a data input this {} control accepts",
                profile.name
            ),
            None => "G10 needs an L number".to_string(),
        };
        return Err(Alarm::error(AlarmCode::BadDataInput, span, message));
    };
    set_tool_offset(exec, cmd, field, g10_span)?;
    Ok(true)
}

fn standard_offset(exec: &Executor, cmd: &Command) -> Result<WorkOffsetId, Alarm> {
    let Some(p) = cmd.p() else {
        return Ok(exec.modal.work_offset);
    };
    let n = p.number.whole().unwrap_or(-1);
    let highest = if exec.kernel.setup.profile().coordinates.g59_x_offsets {
        15
    } else {
        6
    };
    match n {
        0 => Ok(WorkOffsetId::External),
        1.. if n <= highest => Ok(WorkOffsetId::Standard(n as u8)),
        _ => Err(Alarm::error(
            AlarmCode::WorkOffsetOutOfRange,
            p.span,
            format!(
                "G10 L{} P{n}: work offsets are P0 (external) to P{highest}",
                exec.kernel.setup.profile().coordinates.g10_work_l
            ),
        )),
    }
}

fn extended_offset(
    exec: &Executor,
    cmd: &Command,
    span: crate::source::Span,
) -> Result<WorkOffsetId, Alarm> {
    let Some(p) = cmd.p() else {
        return Ok(exec.modal.work_offset);
    };
    exec.kernel
        .setup
        .extended_offset(&p)
        .map_err(|alarm| alarm.with_label(span, "in this G10"))
}

fn set_work_offset(exec: &mut Executor, cmd: &Command, id: WorkOffsetId) {
    let current = exec.kernel.frames.work_offset(id);
    for axis in Axis::ALL {
        let Some(value) = &cmd.axis(axis.index()) else {
            continue;
        };
        let v = exec.axis_value(axis, value);
        let new = match exec.modal.distance {
            DistanceMode::Absolute => v,
            DistanceMode::Incremental => current[axis.index()] + v,
        };
        exec.kernel.frames.set_work_offset(id, axis.index(), new);
    }
}

fn set_tool_offset(
    exec: &mut Executor,
    cmd: &Command,
    field: ToolOffsetField,
    span: crate::source::Span,
) -> Result<(), Alarm> {
    let p = required(
        cmd.p(),
        span,
        "G10 for a tool offset needs P (the offset number)",
    )?;
    let r = required(cmd.r(), span, "G10 for a tool offset needs R (the value)")?;
    let n = p.number.whole().unwrap_or(-1);
    if n < 1 || n > i64::from(exec.kernel.setup.profile().compensation.max_offset_number) {
        return Err(Alarm::error(
            AlarmCode::OffsetNumberOutOfRange,
            p.span,
            format!(
                "offset number {n} is out of range 1 to {}",
                exec.kernel.setup.profile().compensation.max_offset_number
            ),
        ));
    }
    let value = exec.length(&r);
    let distance = exec.modal.distance;
    exec.kernel.tools.write(n as u32, |entry| {
        let slot = match field {
            ToolOffsetField::LengthGeometry => &mut entry.length,
            ToolOffsetField::LengthWear => &mut entry.length_wear,
            ToolOffsetField::RadiusGeometry => &mut entry.radius,
            ToolOffsetField::RadiusWear => &mut entry.radius_wear,
        };
        match distance {
            DistanceMode::Absolute => *slot = value,
            DistanceMode::Incremental => *slot += value,
        }
    });
    Ok(())
}

fn required(
    value: Option<Value>,
    span: crate::source::Span,
    message: &str,
) -> Result<Value, Alarm> {
    value.ok_or_else(|| Alarm::error(AlarmCode::BadDataInput, span, message))
}
