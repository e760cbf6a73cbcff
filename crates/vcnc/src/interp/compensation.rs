//! G40/G41/G42 in the executor: when compensation starts, changes and ends; the geometry and the
//! look-ahead are in `comp/`.

use super::comp::geometry::{Side, V2};
use super::comp::Compensator;
use super::decode::Command;
use super::exec::Executor;
use super::modal::{FeedMode, MotionMode};
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::motion::{MachinePos, Move, SegmentKind};
use crate::profile::{GCode, Group};

/// Before the block's motion: D, and G41/G42/G40 of the block.
///
/// # Errors
/// G41/G42 in a G02/G03 block (FANUC alarm 034); a D number out of range; G41/G42 or D changed
/// while compensating (not supported yet); codes that do not work with compensation yet.
pub(crate) fn before_motion(
    exec: &mut Executor,
    cmd: &Command,
    out: &mut Output,
) -> Result<(), Alarm> {
    if let Some(d) = cmd.word(b'D') {
        let n = exec.offset_number(d, 'D')?;
        if out.comp.is_some() && n != exec.radius_offset_number {
            return Err(Alarm::not_supported(
                d.span,
                "changing D while compensating",
                Some(5),
            ));
        }
        exec.radius_offset_number = n;
    }
    if out.comp.is_some() {
        if let Some(g) = cmd.group(Group::NonModal) {
            if !matches!(g.code, GCode::Dwell | GCode::DataInput) {
                return Err(Alarm::not_supported(
                    g.span,
                    "this code while cutter compensation is on",
                    Some(5),
                ));
            }
        }
    }
    let Some(g) = cmd.group(Group::CutterComp) else {
        return Ok(());
    };
    match g.code {
        GCode::CutterCompLeft | GCode::CutterCompRight => {
            if matches!(exec.modal.motion, MotionMode::Arc(_))
                && (cmd.has_axis_words() || cmd.has_center_words())
            {
                return Err(Alarm::error(
                    AlarmCode::CutterCompensation,
                    g.span,
                    "cutter compensation starts only in a G00 or G01 block",
                )
                .with_help("start it in a straight move before the arc (FANUC alarm 034)"));
            }
            let offset = exec
                .machine
                .tool_offsets
                .get(&exec.radius_offset_number)
                .map_or(0.0, |t| t.radius + t.radius_wear);
            let mut side = Side::of(g.code == GCode::CutterCompLeft, offset);
            let (a, b, _) = exec.modal.plane.axes();
            if exec.frames.scaling.is_some_and(|s| s.reverses((a, b))) {
                // A mirrored plane axis swaps G41 and G42 (spec 1.29).
                side = match side {
                    Side::Left => Side::Right,
                    Side::Right => Side::Left,
                };
            }
            match &out.comp {
                None => {
                    out.comp = Some(Compensator::new(side, offset, (a, b), &exec.position));
                }
                Some(comp) if comp.setting() == (side, offset.abs()) => {}
                Some(_) => {
                    return Err(Alarm::not_supported(
                        g.span,
                        "changing between G41 and G42 while compensating",
                        Some(5),
                    ));
                }
            }
        }
        GCode::CutterCompCancel => {
            if let Some(comp) = out.comp.as_mut() {
                comp.cancel();
            }
        }
        _ => {}
    }
    Ok(())
}

/// After the block's motion: a G40 block ends compensation, moving the tool centre onto the
/// programmed point if the block itself did not.
///
/// # Errors
/// A cutting move without a feed rate.
pub(crate) fn after_motion(
    exec: &mut Executor,
    cmd: &Command,
    out: &mut Output,
) -> Result<(), Alarm> {
    if !out.comp.as_ref().is_some_and(Compensator::is_cancelling) {
        return Ok(());
    }
    let Some(mut comp) = out.comp.take() else {
        return Ok(());
    };
    out.finish_compensation(&mut comp)?;
    let (a, b) = comp.axes();
    let tool = comp.tool();
    let here = V2::new(exec.position[a], exec.position[b]);
    if tool.distance(here) < 1e-9 {
        return Ok(());
    }
    let mut from = exec.position;
    from[a] = tool.x;
    from[b] = tool.y;
    let motion = Move {
        from: MachinePos(from),
        to: MachinePos(exec.position),
        path_mode: exec.modal.path_mode,
        exact_stop: cmd.exact_stop_once,
        offset: exec.frames.offset(),
    };
    let kind = match exec.modal.motion {
        MotionMode::Rapid => SegmentKind::Rapid {
            motion,
            per_axis: exec.profile.rapid_path == crate::profile::RapidPath::PerAxis,
        },
        _ => {
            let feed = exec.cutting_feed(cmd)?;
            if exec.modal.feed_mode == FeedMode::InverseTime {
                exec.feed = None;
            }
            SegmentKind::Line { motion, feed }
        }
    };
    out.push(cmd, kind);
    Ok(())
}
