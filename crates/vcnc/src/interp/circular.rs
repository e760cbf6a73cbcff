//! G02/G03: circular and helical interpolation in the selected plane.

use super::arc::{arc_center, clean_arc_center, in_plane, ArcSpec, CleanSpec};
use super::decode::{Command, Value};
use super::exec::Executor;
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::machine::AXES;
use crate::motion::{ArcDirection, Feed, MachinePos, Plane, Segment, SegmentKind};

/// Moves along an arc from the current position to `target` (machine coordinates).
///
/// I J K are incremental from the start whatever G90/G91 says (spec 1.4, L297); R is negative for
/// arcs over 180 degrees; with I J K and the end on the start the arc is a full circle. Axes
/// outside the plane move linearly with the arc (helical interpolation).
///
/// # Errors
/// No feed, no centre words, an end off the circle, or R too small.
pub(crate) fn arc(
    exec: &mut Executor,
    cmd: &Command,
    direction: ArcDirection,
    target: [f64; AXES],
    out: &mut Output,
) -> Result<(), Alarm> {
    let plane = exec.modal.plane;
    let (a, b, _) = plane.axes();
    // Borrowed: a copy of the scaling (two arrays of six) would cost every arc.
    let scaling = exec.kernel.frames.scaling();
    let direction = exec.kernel.frames.arc_direction((a, b), direction);
    let position_offset = super::position_offset::factor(cmd);
    let spec = if let Some(r) = cmd.r() {
        if let Some(factor) = position_offset {
            return Err(super::position_offset::radius_refused(factor));
        }
        ArcSpec::Radius {
            radius: exec.length(&r) * scaling.map_or(1.0, |s| s.arc_factor((a, b))),
            span: r.span,
        }
    } else {
        let (ca, cb) = (cmd.center(a), cmd.center(b));
        let Some(span) = ca.or(cb).map(|v| v.span) else {
            return Err(Alarm::error(
                AlarmCode::ArcWithoutCenter,
                cmd.span,
                "circular move without R or centre words of the selected plane",
            )
            .with_help(format!(
                "in {} give {} or R",
                plane_name(plane),
                centre_letters(plane)
            )));
        };
        let mut offset = (
            ca.map_or(0.0, |v| exec.length(&v)),
            cb.map_or(0.0, |v| exec.length(&v)),
        );
        if let Some(factor) = position_offset {
            offset = super::position_offset::centre(&exec.kernel.tools, factor, offset);
        }
        if let Some(scaling) = scaling {
            offset = scaling.arc_vector((a, b), offset);
        }
        // I J K are a vector in the programmed (unrotated) coordinates.
        for rotation in [
            exec.kernel.frames.rotation(),
            exec.kernel.frames.preset_rotation(),
        ]
        .into_iter()
        .flatten()
        {
            offset = rotation.vector(offset);
        }
        ArcSpec::Center { offset, span }
    };
    let feed = exec.cutting_feed(cmd)?;
    if let (Some(turns), true) = (cmd.l(), exec.kernel.setup.profile().motion.arc_l_is_spiral) {
        return spiral(exec, cmd, spec, turns, direction, target, feed, out);
    }
    if super::tilted_plane::tilted(exec).is_some() {
        return super::tilted_plane::arc_as_chords(exec, cmd, (spec, direction, feed), target, out);
    }
    let start = in_plane(plane, &exec.kernel.position);
    let end = in_plane(plane, &target);
    if let ArcSpec::Radius { span, .. } = spec {
        if start == end {
            // An R arc ending on its start is an arc of 0 degrees: the control does not move in
            // the plane. Only the other axes (if any) move, in a straight line.
            out.push_warning(Alarm::warning(
                AlarmCode::ArcRadiusTooSmall,
                span,
                "an R arc that ends on its start point does not move (use I J K for a full circle)",
            ));
            if target != exec.kernel.position {
                let motion = exec.move_to(target, cmd, out)?;
                out.push(cmd, SegmentKind::Line { motion, feed });
            }
            return Ok(());
        }
    }
    let center_plane = arc_center(
        start,
        end,
        spec,
        direction,
        exec.kernel.setup.profile().motion.arc_radius_tolerance,
    )?;
    if let Some(factor) = position_offset {
        super::position_offset::check_quarter(factor, start, end, center_plane)?;
    }
    let arc = ArcTo {
        target,
        center: center_plane,
        direction,
        feed,
        extra_turns: 0,
    };
    let modes = exec.modal.move_modes(cmd);
    let plane = exec.modal.plane;
    exec.kernel.queue_arc(cmd, arc, plane, modes, out)
}

/// An arc in the plane in force whose centre is known, machine coordinates.
pub(crate) struct ArcTo {
    /// The end point.
    pub(crate) target: [f64; AXES],
    /// The centre's two plane coordinates.
    pub(crate) center: (f64, f64),
    pub(crate) direction: ArcDirection,
    pub(crate) feed: Feed,
    /// Full turns beyond the first (a helix of several turns: SINUMERIK's TURN=).
    pub(crate) extra_turns: u32,
}

/// G02/G03 of a plain block (`Executor::run_plain`): [`arc`] for the common arc of a CAM
/// program, in the XY plane, with a feed, in coordinates neither scaled nor turned, straight to
/// the output queue, and ending on its circle. Any other arc, and every arc with an alarm or a
/// warning, is handed to [`arc`] before anything changed. Through [`arc`], with its plane axes
/// looked up, the scaling asked and its alarms built where they are tested, an arc cost about
/// two fifths more.
///
/// # Errors
/// Those of [`arc`].
#[inline(never)]
pub(crate) fn plain_arc(
    exec: &mut Executor,
    cmd: &Command,
    direction: ArcDirection,
    out: &mut Output,
) -> Result<(), Alarm> {
    // A plain block has no G45-G48 (a non-modal code) and no L (a spiral).
    debug_assert!(cmd.is_plain());
    let target = exec.block_target(cmd, false, out)?;
    let common = exec.modal.plane == Plane::Xy
        && !exec.kernel.frames.transformed()
        && exec.kernel.feed.is_some_and(|f| f != 0.0);
    let spec = match cmd.word_ref(b'R') {
        Some(r) => Some(CleanSpec::Radius(exec.length(r))),
        None => {
            let (i, j) = (cmd.word_ref(b'I'), cmd.word_ref(b'J'));
            (i.is_some() || j.is_some()).then(|| {
                CleanSpec::Center((
                    i.map_or(0.0, |v| exec.length(v)),
                    j.map_or(0.0, |v| exec.length(v)),
                ))
            })
        }
    };
    let (Some(spec), true) = (spec, common) else {
        return arc(exec, cmd, direction, target, out);
    };
    let start = (exec.kernel.position[0], exec.kernel.position[1]);
    let end = (target[0], target[1]);
    let tolerance = exec.kernel.setup.profile().motion.arc_radius_tolerance;
    let Some((x, y)) = clean_arc_center(start, end, spec, direction, tolerance) else {
        return arc(exec, cmd, direction, target, out);
    };
    let mut center = exec.kernel.position;
    (center[0], center[1]) = (x, y);
    let feed = exec.cutting_feed(cmd)?;
    super::kernel::check_position(&center, cmd)?;
    if out.direct().is_none() {
        return arc(exec, cmd, direction, target, out);
    }
    let motion = exec.move_to(target, cmd, out)?;
    if let Some(items) = out.direct() {
        items.push(Ok(crate::motion::Item::Segment(Segment {
            kind: SegmentKind::Arc {
                motion,
                center: MachinePos(center),
                direction,
                plane: Plane::Xy,
                extra_turns: 0,
                feed,
            },
            span: cmd.span,
            sequence: cmd.sequence(),
        })));
    }
    Ok(())
}

/// G02/G03 with L on Syntec: a spiral (or, with the third axis, a cone) about the I J K centre.
#[allow(clippy::too_many_arguments)]
fn spiral(
    exec: &mut Executor,
    cmd: &Command,
    spec: ArcSpec,
    turns: Value,
    direction: ArcDirection,
    target: [f64; AXES],
    feed: Feed,
    out: &mut Output,
) -> Result<(), Alarm> {
    let ArcSpec::Center { offset, span } = spec else {
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            cmd.r().map_or(cmd.span, |r| r.span),
            "a spiral (G02/G03 with L) takes its centre from I J K, not R",
        ));
    };
    if out.direct().is_none() {
        return Err(Alarm::not_supported(
            turns.span,
            "a spiral (G02/G03 with L) under cutter compensation or G12.1",
            None,
        ));
    }
    let spiral = super::spiral::Spiral {
        direction,
        target,
        offset,
        centre_span: span,
        turns,
        feed,
    };
    super::spiral::run(exec, cmd, &spiral, out)
}

fn plane_name(plane: crate::motion::Plane) -> &'static str {
    match plane {
        crate::motion::Plane::Xy => "G17",
        crate::motion::Plane::Zx => "G18",
        crate::motion::Plane::Yz => "G19",
    }
}

fn centre_letters(plane: crate::motion::Plane) -> &'static str {
    match plane {
        crate::motion::Plane::Xy => "I and J",
        crate::motion::Plane::Zx => "K and I",
        crate::motion::Plane::Yz => "J and K",
    }
}
