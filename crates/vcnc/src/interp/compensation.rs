//! G40/G41/G42 in the executor: when compensation starts, changes and ends; the geometry and the
//! look-ahead are in `comp/`.

use super::comp::geometry::{Side, V2};
use super::comp::Compensator;
use super::corner_override::CornerStage;
use super::decode::Command;
use super::exec::Executor;
use super::frames::Frames;
use super::modal::{FeedMode, MotionMode};
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::motion::{MachinePos, Move, Plane, SegmentKind};
use crate::profile::{GCode, Group, Profile};

/// Before the block's motion: D, G41/G42/G40 of the block, and the codes that cancel
/// compensation for one block.
///
/// # Errors
/// G41/G42 in a G02/G03 block (FANUC alarm 034); a D number out of range; interference where a
/// pending element has to end.
pub(crate) fn before_motion(
    exec: &mut Executor,
    cmd: &Command,
    out: &mut Output,
) -> Result<(), Alarm> {
    if !out.compensating() && cmd.word(b'D').is_none() && cmd.group(Group::CutterComp).is_none() {
        // Most blocks: nothing about compensation.
        return Ok(());
    }
    // In a G12/G13 block D is the circle's own offset, not the cutter compensation's.
    let circle = cmd
        .group(Group::NonModal)
        .is_some_and(|g| matches!(g.code, GCode::CircleCutting(_)));
    let d = cmd.word(b'D').filter(|_| !circle);
    let number = match d {
        Some(d) => Some((d, 'D')),
        None if h_names_radius_offset(exec.kernel.setup.profile(), cmd) => {
            cmd.h().map(|h| (h, 'H'))
        }
        None => None,
    };
    if let Some((word, letter)) = number {
        exec.kernel
            .tools
            .select_radius(exec.kernel.setup.offset_number(word, letter)?);
        if let Some(comp) = out.compensation_mut() {
            let left = comp.left();
            change(exec, comp, left);
        }
    }
    if let Some(comp) = out.compensation_mut() {
        if comp.reversed() != reversed(&exec.kernel.frames, exec.modal.plane) {
            // G51.1 or G50.1 (or a negative G51 factor) in offset mode: while one plane axis is
            // mirrored G41 and G42 act the other way (spec 1.29), so the side changes from the
            // next element on, as if the mirror had come before G41/G42.
            let left = comp.left();
            change(exec, comp, left);
        }
    }
    if out.compensating() {
        if let Some(g) = cmd.group(Group::NonModal) {
            let keeps = g.code == GCode::MachineCoordinates
                && exec
                    .kernel
                    .setup
                    .profile()
                    .compensation
                    .g53_keeps_radius_compensation;
            if !keeps
                && matches!(
                    g.code,
                    GCode::ReferenceReturn
                        | GCode::ReturnFromReference
                        | GCode::NthReferenceReturn
                        | GCode::MachineCoordinates
                        | GCode::SetCoordinates
                        | GCode::PresetCoordinates
                        | GCode::LocalCoordinates
                )
            {
                // Cancelled for this block, resumed with the next (spec A.22 rule 4).
                out.suspend_compensation()?;
            }
        }
    }
    refuse_plane_change(exec, cmd, out)?;
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
            let left = g.code == GCode::CutterCompLeft;
            let setting = setting(exec, left);
            match out.compensation_mut() {
                None => {
                    let (a, b, _) = exec.modal.plane.axes();
                    let mut comp = Compensator::new(
                        setting,
                        (a, b),
                        &exec.kernel.position,
                        left,
                        exec.kernel
                            .setup
                            .profile()
                            .compensation
                            .cutter_comp_look_ahead,
                    );
                    comp.set_reversed(reversed(&exec.kernel.frames, exec.modal.plane));
                    out.start_compensation(comp);
                    if let Some(corner) = exec.kernel.setup.profile().compensation.corner_override {
                        out.start_corner_override(CornerStage::new(corner, (a, b), setting));
                    }
                }
                Some(comp) => change(exec, comp, left),
            }
        }
        GCode::CutterCompCancel => {
            if let Some(comp) = out.compensation_mut() {
                if matches!(exec.modal.motion, MotionMode::Arc(_))
                    && (cmd.has_axis_words() || cmd.has_center_words())
                {
                    // The cancel block ends on the programmed point: an arc to it from the offset
                    // point would not be an arc (spec A.22 rule 5; Syntec L1740).
                    return Err(Alarm::error(
                        AlarmCode::CutterCompensation,
                        g.span,
                        "cutter compensation ends only in a G00 or G01 block",
                    )
                    .with_help("cancel it in a straight move after the arc (FANUC alarm 034)"));
                }
                comp.cancel();
            }
        }
        _ => {}
    }
    Ok(())
}

/// G17/G18/G19 to another plane while compensating: the offset vector lies in the old plane
/// (FANUC alarm 037). A G40 block may change it: it ends the offset.
fn refuse_plane_change(exec: &Executor, cmd: &Command, out: &Output) -> Result<(), Alarm> {
    let (Some(g), Some(comp)) = (cmd.group(Group::Plane), out.compensation()) else {
        return Ok(());
    };
    let cancelling = cmd
        .group(Group::CutterComp)
        .is_some_and(|c| c.code == GCode::CutterCompCancel);
    let (a, b, _) = exec.modal.plane.axes();
    if cancelling || comp.axes() == (a, b) {
        return Ok(());
    }
    Err(Alarm::error(
        AlarmCode::CutterCompensation,
        g.span,
        "the plane cannot change while cutter compensation is on",
    )
    .with_help("cancel the compensation with G40 first (FANUC alarm 037)"))
}

/// True when the block's H word is the radius offset number (`G42 H19`, the old FANUC 0M
/// form) rather than a length offset number.
pub(crate) fn h_names_radius_offset(profile: &Profile, cmd: &Command) -> bool {
    profile.compensation.radius_offset_by_h
        && cmd.word(b'D').is_none()
        && cmd
            .group(Group::CutterComp)
            .is_some_and(|g| g.code != GCode::CutterCompCancel)
        && cmd.group(Group::LengthComp).is_none()
}

/// G41 (`left`) or G42, the D number in force or the mirroring changed in offset mode: the
/// side and radius for the next element.
fn change(exec: &Executor, comp: &mut Compensator, left: bool) {
    comp.change(setting(exec, left), left);
    comp.set_reversed(reversed(&exec.kernel.frames, exec.modal.plane));
}

/// True when exactly one axis of the plane is mirrored (G51.1, or G51 with a negative factor).
fn reversed(frames: &Frames, plane: Plane) -> bool {
    let (a, b, _) = plane.axes();
    frames.scaling().is_some_and(|s| s.reverses((a, b)))
}

/// The side and radius of G41 (`left`) or G42 with the D number in force: a negative offset
/// and a mirrored plane axis (spec 1.29) each swap the side.
fn setting(exec: &Executor, left: bool) -> (Side, f64) {
    let offset = exec.kernel.tools.radius_offset();
    let offset = if exec
        .kernel
        .setup
        .profile()
        .compensation
        .radius_offsets_are_diameters
    {
        offset / 2.0
    } else {
        offset
    };
    let side = Side::of(left, offset);
    let side = if reversed(&exec.kernel.frames, exec.modal.plane) {
        match side {
            Side::Left => Side::Right,
            Side::Right => Side::Left,
        }
    } else {
        side
    };
    (side, offset.abs())
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
    if !out.compensation().is_some_and(Compensator::is_cancelling) {
        return Ok(());
    }
    let Some(mut comp) = out.take_compensation() else {
        return Ok(());
    };
    out.finish_compensation(&mut comp)?;
    let (a, b) = comp.axes();
    let tool = comp.tool();
    let here = V2::new(exec.kernel.position[a], exec.kernel.position[b]);
    if tool.distance(here) < 1e-9 {
        return Ok(());
    }
    let mut from = exec.kernel.position;
    from[a] = tool.x;
    from[b] = tool.y;
    let motion = Move {
        from: MachinePos(from),
        to: MachinePos(exec.kernel.position),
        path_mode: exec.modal.path_mode,
        exact_stop: exec.modal.exact_stop_once(cmd),
        smoothing: exec.modal.smoothing_for_motion(),
        frame: exec.kernel.frame_in_force(out),
        offset: exec.kernel.frames.offset_at(&exec.kernel.position),
    };
    let kind = match exec.modal.motion {
        MotionMode::Rapid => SegmentKind::Rapid {
            motion,
            per_axis: exec.kernel.setup.profile().motion.rapid_path
                == crate::profile::RapidPath::PerAxis,
        },
        _ => {
            let feed = exec.cutting_feed(cmd)?;
            if exec.modal.feed_mode == FeedMode::InverseTime {
                exec.kernel.feed = None;
            }
            SegmentKind::Line { motion, feed }
        }
    };
    out.push(cmd, kind);
    Ok(())
}
