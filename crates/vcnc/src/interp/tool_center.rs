//! G43.4 tool centre point control (RTCP) and the kinematic transform it shares with G53.1:
//! programmed X Y Z are the tool tip in the work coordinates, A B C the rotary axes' positions,
//! and the machine's joints move so that the tip follows the programmed path. Spec
//! iso-syntec-milling.md 1.26 (seed 000 L1884-1936).
//!
//! How it sits in the pipeline (as G12.1 does, `polar_interpolation.rs`):
//!
//! - While the transform is on, the executor works in tip coordinates: its position is the
//!   tool tip in the workpiece (machine coordinates with the table at zero) plus the tool length
//!   vector, as if the rotary axes were all at zero, so G43's arithmetic (`length.rs`) and the
//!   frames apply unchanged. The rotary slots hold the joint angles.
//! - [`KinematicStage`] sits in the output queue behind the other stages. Each motion it
//!   receives is cut into straight joint moves whose ends put the tip on the path and which,
//!   seen at the tip, stay within the machine's `smoothing_tolerance` of it
//!   (`pieces.rs`); the rotary axes run linearly along the block, so the tool axis at each
//!   point is the one the programmed angles give there. The tool length comes from the frames
//!   that pass through the stage (`WorkFrame::tool_length`).
//! - G49 (or G43/G44, the same group) ends it unless G53.1 keeps it on, G69 ends G53.1's; the
//!   executor then holds the joints again. SINUMERIK's CYCLE800 keeps it on as G53.1 does
//!   (`sinumerik/cycles/swivel.rs`), until CYCLE800().
//!
//! Restrictions the manual lists and vcnc alarms: no G41/G42 with it (rule 1), a positive tool
//! length (rule 3); a machine file without `[kinematics]` cannot run it.
//!
//! G43.5 (FANUC Series 30i, tool centre point control type 2; profile
//! `motion.tool_center_point_type2`) is the same transform, but a G00/G01 block gives the tool
//! direction at its end by I J K in the program system instead of the rotary positions: the
//! control solves the angles ([`tool_direction`]). FANUC's rules kept: I J K all left out keep
//! the direction, one or two left out are 0, a block of I J K alone turns the tool about its
//! tip; I J K in the G43.5 block itself only on a machine whose rotary axes are all in the head
//! (FANUC PS5421). The solution rule: of the angles that give the direction, the ones reached
//! with the least rotary travel from where the axes are, each angle taken whole turns to the
//! nearest (FANUC: a shortcut move, never more than 180 degrees), whatever the machine file's
//! `solution` (which is G53.1's); a tie goes to the first of the two. Choices: the rotary axes
//! run linearly along the block as under G43.4 (the tool direction between the ends is the
//! joints'); rotary axis words with I J K, G02/G03 with I J K and Q (the tool's inclination)
//! are refused.

use super::decode::Command;
use super::exec::Executor;
use super::kernel::KernelState;
use super::pieces::{self, PieceMap};
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::kinematics::{Kinematics, Solution};
use crate::machine::AXES;
use crate::motion::{Item, StreamItem};
use crate::profile::{GCode, Group};
use crate::source::Span;

/// What keeps the kinematic transform on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Keeper {
    /// G43.4 until G49.
    CenterPoint,
    /// G53.1 until G69, SINUMERIK's CYCLE800 until CYCLE800().
    ToolAxis,
}

/// The stage between the other stages and the output queue while the transform is on.
#[derive(Clone, Debug)]
pub(crate) struct KinematicStage {
    /// Items in tip coordinates, as the executor queues them.
    pub(crate) staged: Vec<StreamItem>,
    /// Items from this index on wait for an earlier stage.
    pub(crate) held: Option<usize>,
    map: TipMap,
    /// The joints where the last piece ended.
    last: [f64; AXES],
    /// Largest distance of the tip from the path between piece ends, mm.
    tolerance: f64,
    center_point: bool,
    tool_axis: bool,
    /// G43.5: blocks give the tool direction by I J K.
    by_direction: bool,
}

/// Tip coordinates to joints.
#[derive(Clone, Debug)]
struct TipMap {
    kinematics: Kinematics,
    /// The tool length vector in force (tip to control point with the rotary axes at zero).
    length: [f64; 3],
}

impl TipMap {
    /// The tool's length along its axis.
    fn tool_length(&self) -> f64 {
        let k = self.kinematics.tool_axis;
        self.length[0] * k[0] + self.length[1] * k[1] + self.length[2] * k[2]
    }

    /// The tip coordinates (tip plus length vector, rotary angles) of the joints `joints`.
    fn tip_coordinates(&self, joints: &[f64; AXES]) -> [f64; AXES] {
        let pose = self.kinematics.forward(joints, self.tool_length());
        let mut out = *joints;
        for ((o, tip), length) in out.iter_mut().zip(pose.tip).zip(self.length) {
            *o = tip + length;
        }
        out
    }
}

impl PieceMap for TipMap {
    fn to_machine(&self, p: &[f64; AXES], _: &[f64; AXES], _: &[f64; AXES]) -> [f64; AXES] {
        let tip = std::array::from_fn(|i| p[i] - self.length[i]);
        self.kinematics.joints_for_tip(tip, p, self.tool_length())
    }

    fn deviation(&self, machine: &[f64; AXES], _: &[f64; AXES], p: &[f64; AXES]) -> f64 {
        let tip = self.kinematics.forward(machine, self.tool_length()).tip;
        let d: [f64; 3] = std::array::from_fn(|i| tip[i] - (p[i] - self.length[i]));
        d[0].hypot(d[1]).hypot(d[2])
    }
}

impl KinematicStage {
    /// Converts the items the stages before have released and appends them to `items`.
    pub(crate) fn settle(&mut self, items: &mut Vec<StreamItem>) {
        let ready = self.held.unwrap_or(self.staged.len());
        for item in self.staged.drain(..ready) {
            match item {
                Ok(Item::Segment(segment)) if segment.motion().is_some() => {
                    self.last = pieces::cut(&self.map, &segment, self.last, self.tolerance, items);
                }
                Ok(Item::Frame(frame)) => {
                    self.map.length = frame.tool_length;
                    items.push(Ok(Item::Frame(frame)));
                }
                other => items.push(other),
            }
        }
        if let Some(held) = self.held.as_mut() {
            *held = 0;
        }
    }

    /// The transform ends: everything staged is converted. Returns the joints where the last
    /// piece ended.
    pub(crate) fn flush(mut self, items: &mut Vec<StreamItem>) -> [f64; AXES] {
        self.held = None;
        self.settle(items);
        self.last
    }

    /// Whether `keeper` keeps the transform on.
    pub(crate) fn kept_by(&self, keeper: Keeper) -> bool {
        match keeper {
            Keeper::CenterPoint => self.center_point,
            Keeper::ToolAxis => self.tool_axis,
        }
    }

    /// `keeper` keeps the transform on from now.
    pub(crate) fn keep(&mut self, keeper: Keeper) {
        match keeper {
            Keeper::CenterPoint => self.center_point = true,
            Keeper::ToolAxis => self.tool_axis = true,
        }
    }

    /// `keeper` lets go; true when nothing keeps the transform on any more.
    fn release(&mut self, keeper: Keeper) -> bool {
        match keeper {
            Keeper::CenterPoint => self.center_point = false,
            Keeper::ToolAxis => self.tool_axis = false,
        }
        !self.center_point && !self.tool_axis
    }
}

/// The machine's kinematics, or the alarm for `what` (a 5-axis code, at `span`) on a machine
/// without them.
///
/// # Errors
/// [`AlarmCode::FiveAxis`] when the machine file has no `[kinematics]`.
pub(crate) fn kinematics(state: &KernelState, span: Span, what: &str) -> Result<Kinematics, Alarm> {
    state.setup.machine().kinematics.clone().ok_or_else(|| {
        Alarm::error(
            AlarmCode::FiveAxis,
            span,
            format!("{what} needs the machine's kinematics: the machine file has none"),
        )
        .with_help("describe the rotary axes in the machine file's [kinematics] table (docs/KINEMATICS.md)")
    })
}

/// The kinematic transform on for `keeper` (started if it was off): the executor's position
/// becomes the tip coordinates of the joints.
///
/// # Errors
/// [`AlarmCode::FiveAxis`] on a machine without kinematics.
pub(crate) fn start(
    state: &mut KernelState,
    (span, what): (Span, &str),
    keeper: Keeper,
    out: &mut Output,
) -> Result<(), Alarm> {
    if let Some(stage) = out.kinematics_mut() {
        stage.keep(keeper);
        return Ok(());
    }
    let kinematics = kinematics(state, span, what)?;
    let frames = &state.frames;
    let [x, y] = frames.lateral_length();
    let map = TipMap {
        kinematics,
        length: [x, y, frames.length_vector()],
    };
    let joints = state.position;
    state.position = map.tip_coordinates(&joints);
    let mut stage = KinematicStage {
        staged: Vec::new(),
        held: None,
        map,
        last: joints,
        tolerance: state.setup.machine().planner.smoothing_tolerance,
        center_point: false,
        tool_axis: false,
        by_direction: false,
    };
    stage.keep(keeper);
    out.start_kinematics(stage);
    Ok(())
}

/// `keeper` lets the transform go; when nothing keeps it on, it ends and the executor holds the
/// joints where its last piece ended.
pub(crate) fn release(state: &mut KernelState, keeper: Keeper, out: &mut Output) {
    let ended = out
        .kinematics_mut()
        .is_some_and(|stage| stage.release(keeper));
    if ended {
        if let Some(joints) = out.end_kinematics() {
            state.position = joints;
        }
    }
}

/// G43.4, or another code of its group, in a block (after its H is selected).
///
/// # Errors
/// G43.4 with cutter compensation on (spec 1.26 rule 1), with a negative tool length (rule 3), or
/// on a machine without kinematics.
pub(crate) fn switch(exec: &mut Executor, cmd: &Command, out: &mut Output) -> Result<(), Alarm> {
    let Some(g) = cmd.group(Group::LengthComp) else {
        return Ok(());
    };
    let name = match g.code {
        GCode::ToolCenterPoint => "G43.4",
        GCode::ToolCenterPointType2 => "G43.5",
        _ => {
            release(&mut exec.kernel, Keeper::CenterPoint, out);
            return Ok(());
        }
    };
    if out.compensating() {
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            g.span,
            format!("{name} cannot be commanded while cutter compensation (G41/G42) is on"),
        )
        .with_help("cancel compensation with G40 first: the two cannot be used together"));
    }
    if exec.active_length() < 0.0 {
        return Err(Alarm::error(
            AlarmCode::FiveAxis,
            g.span,
            format!(
                "{name} with a negative tool length ({})",
                exec.active_length()
            ),
        )
        .with_help("tool centre point control needs a positive tool length (spec 1.26 rule 3)"));
    }
    let by_direction = g.code == GCode::ToolCenterPointType2;
    if by_direction {
        refuse_type2_words(exec, cmd, g.span)?;
    }
    start(&mut exec.kernel, (g.span, name), Keeper::CenterPoint, out)?;
    if let Some(stage) = out.kinematics_mut() {
        stage.by_direction = by_direction;
    }
    Ok(())
}

/// The words G43.5's own block may not have: Q (the tool's inclination, not simulated) and,
/// on a machine with a table axis, I J K (FANUC PS5421).
fn refuse_type2_words(exec: &Executor, cmd: &Command, span: Span) -> Result<(), Alarm> {
    if let Some(q) = cmd.word(b'Q') {
        return Err(Alarm::error(
            AlarmCode::NotSupportedYet,
            q.span,
            "G43.5 Q (the tool's inclination towards the direction of motion) is not simulated",
        )
        .with_help("give the inclined tool direction by I J K in the motion blocks instead"));
    }
    let kinematics = kinematics(&exec.kernel, span, "G43.5")?;
    if cmd.has_center_words() && !kinematics.all_in_head() {
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            span,
            "PS5421: I J K in the G43.5 block on a machine whose table turns",
        )
        .with_help("give the tool direction in the motion blocks after G43.5 (FANUC: only a head-only machine takes it in the G43.5 block)"));
    }
    Ok(())
}

/// G43.5's motion block: the rotary angles of `target` solved for the tool direction its I J K
/// give (program system), when the transform is on by G43.5 and the block has them.
///
/// # Errors
/// [`AlarmCode::WordNotAllowed`] for rotary axis words beside I J K, or I J K in a G02/G03;
/// [`AlarmCode::FiveAxis`] for a zero direction or one the rotary axes cannot reach.
// Inlined into the short path of a CAM line, which pays for the one test of I J K.
#[inline(always)]
pub(crate) fn tool_direction(
    exec: &Executor,
    cmd: &Command,
    target: [f64; AXES],
    out: &Output,
) -> Result<[f64; AXES], Alarm> {
    if !cmd.has_center_words() {
        return Ok(target);
    }
    solve_direction(exec, cmd, target, out)
}

/// [`tool_direction`] for a block with I J K.
#[inline(never)]
fn solve_direction(
    exec: &Executor,
    cmd: &Command,
    target: [f64; AXES],
    out: &Output,
) -> Result<[f64; AXES], Alarm> {
    if !out.kinematics().is_some_and(|stage| stage.by_direction) {
        return Ok(target);
    }
    let span = cmd.span;
    let refuse = |message: &str, help: &str| {
        Err(
            Alarm::error(AlarmCode::WordNotAllowed, span, message.to_string())
                .with_help(help.to_string()),
        )
    };
    if matches!(exec.modal.motion, super::modal::MotionMode::Arc(_)) {
        return refuse(
            "I J K in a G02/G03 under G43.5: they give the tool direction, not the centre",
            "give the arc by R (FANUC: only R in tool centre point control type 2)",
        );
    }
    if cmd.has_extra_axis_words() {
        return refuse(
            "rotary axis words beside I J K under G43.5",
            "give the tool direction by I J K alone: the control solves the rotary axes",
        );
    }
    let ijk: [f64; 3] = std::array::from_fn(|i| cmd.center(i).map_or(0.0, |v| v.number.value));
    let direction = program_direction(exec, ijk);
    let mut kinematics = kinematics(&exec.kernel, span, "G43.5")?;
    kinematics.solution = Solution::Shortest;
    kinematics.orient(direction, &target).ok_or_else(|| {
        Alarm::error(
            AlarmCode::FiveAxis,
            span,
            format!(
                "G43.5: the rotary axes cannot point the tool along I{} J{} K{}",
                ijk[0], ijk[1], ijk[2]
            ),
        )
        .with_help("the direction is zero or beyond the rotary axes' reach and travel")
    })
}

/// A direction of the program system in the workpiece: through the frames (G68, G68.2), as the
/// difference of two points they carry.
fn program_direction(exec: &Executor, ijk: [f64; 3]) -> [f64; 3] {
    let frames = &exec.kernel.frames;
    let from = exec.kernel.program_position();
    let mut ahead = from;
    for (p, d) in ahead.iter_mut().zip(ijk) {
        *p += d;
    }
    let length = frames.length_vector();
    let (a, b) = (
        frames.to_machine(&from, length),
        frames.to_machine(&ahead, length),
    );
    std::array::from_fn(|i| b[i] - a[i])
}

/// G41/G42 while G43.4 is on: refused (spec 1.26 rule 1).
///
/// # Errors
/// [`AlarmCode::WordNotAllowed`] for a G41 or G42 in the mode.
pub(crate) fn refuse_compensation(cmd: &Command, out: &mut Output) -> Result<(), Alarm> {
    let on = out
        .kinematics_mut()
        .is_some_and(|stage| stage.kept_by(Keeper::CenterPoint));
    match cmd.group(Group::CutterComp) {
        Some(g) if on && g.code != GCode::CutterCompCancel => Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            g.span,
            format!(
                "{} cannot be commanded while tool centre point control (G43.4) is on",
                g.code.description()
            ),
        )
        .with_help("cancel G43.4 with G49 first: the two cannot be used together")),
        _ => Ok(()),
    }
}

/// G05 P10000 (high-speed high-precision mode) turned on while G43.4 is on: Syntec's alarm
/// COR-140 (spec 1.26 rule 5).
///
/// # Errors
/// [`AlarmCode::SmoothingCommand`] for the G05 that turned the mode on in the RTCP mode.
pub(crate) fn refuse_high_speed(
    exec: &Executor,
    cmd: &Command,
    out: &mut Output,
) -> Result<(), Alarm> {
    let on = out
        .kinematics_mut()
        .is_some_and(|stage| stage.kept_by(Keeper::CenterPoint));
    match cmd.group(Group::NonModal) {
        Some(g)
            if on
                && g.code == GCode::HighSpeedMode
                && exec.modal.smoothing.high_speed.is_some() =>
        {
            Err(Alarm::error(
                AlarmCode::SmoothingCommand,
                g.span,
                "COR-140: G05 high-precision cutting mode is prohibited in G43.4 (tool centre point control)",
            )
            .with_help("cancel G43.4 with G49 before G05 P10000 (Syntec spec 1.26 rule 5)"))
        }
        _ => Ok(()),
    }
}
