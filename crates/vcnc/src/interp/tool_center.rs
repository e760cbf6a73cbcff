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

use super::decode::Command;
use super::exec::Executor;
use super::kernel::KernelState;
use super::pieces::{self, PieceMap};
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::kinematics::Kinematics;
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
    if g.code != GCode::ToolCenterPoint {
        release(&mut exec.kernel, Keeper::CenterPoint, out);
        return Ok(());
    }
    if out.compensating() {
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            g.span,
            "G43.4 cannot be commanded while cutter compensation (G41/G42) is on",
        )
        .with_help("cancel compensation with G40 first: the two cannot be used together"));
    }
    if exec.active_length() < 0.0 {
        return Err(Alarm::error(
            AlarmCode::FiveAxis,
            g.span,
            format!(
                "G43.4 with a negative tool length ({})",
                exec.active_length()
            ),
        )
        .with_help("tool centre point control needs a positive tool length (spec 1.26 rule 3)"));
    }
    start(
        &mut exec.kernel,
        (g.span, "G43.4"),
        Keeper::CenterPoint,
        out,
    )
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
