//! The canonical motion stream: what the interpreter yields.
//!
//! The stream is a sequence of [`StreamItem`]s: `Ok` a [`Segment`] or a warning ([`Item`]),
//! `Err` the alarm that stops the run, always the last item. Every [`Segment`] is in machine
//! coordinates (mm, degrees) and carries the [`Span`] of the block it comes from. Consumers
//! (trace output, planner, checks, simulation, a viewer) need nothing else: no segment refers
//! back to syntax, modal state or the profile.
//!
//! Work coordinates: every move names the frame it was made in ([`Move::frame`]), and an
//! [`Item::Frame`], carrying the whole map from program to machine coordinates
//! ([`WorkTransform`]), comes before the first move made in a new frame. A consumer that shows
//! work coordinates keeps the last frame; one that keeps moves keeps the frames by id.

use crate::alarm::Alarm;
use crate::axis::AXES;
use crate::source::Span;

/// One item of the stream as a consumer takes it: `Ok` a segment or a warning, `Err` the alarm
/// that stops the run (always the last item). So `?`, or `collect::<Result<Vec<_>, _>>()`,
/// stops at the error and nowhere else.
pub type StreamItem = Result<Item, Alarm>;

/// What the stream carries before its end: a segment, a new frame, or a warning the run goes
/// on after.
#[derive(Clone, Debug, PartialEq)]
pub enum Item {
    /// A motion or an event.
    Segment(Segment),
    /// The map from program to machine coordinates changes: a work offset selected or
    /// written (G54..., G10 L2/L20, system variables, SINUMERIK's settable frames), G92, G52,
    /// G68, G51, G51.1, SINUMERIK's programmable frame, or the tool length vector (G43/G44/G49
    /// with another H or a register written while it is in force, a reference return that
    /// clears it, SINUMERIK's lengths as its front end applies them). It comes before the first move made in the new frame, and only then: a change
    /// no move follows is not in the stream. It takes no time. Cutter radius (D) is not part of
    /// it: the moves are the tool centre's path already.
    Frame(WorkFrame),
    /// A warning: the control would run on, the program probably does not do what was meant.
    Warning(Alarm),
}

impl Item {
    /// The segment, if this is one.
    #[inline(always)]
    pub fn segment(&self) -> Option<&Segment> {
        match self {
            Item::Segment(segment) => Some(segment),
            Item::Frame(_) | Item::Warning(_) => None,
        }
    }

    /// The warning, if this is one.
    pub fn warning(&self) -> Option<&Alarm> {
        match self {
            Item::Warning(alarm) => Some(alarm),
            Item::Segment(_) | Item::Frame(_) => None,
        }
    }

    /// The segment, if this is one, by value.
    #[inline(always)]
    pub fn into_segment(self) -> Option<Segment> {
        match self {
            Item::Segment(segment) => Some(segment),
            Item::Frame(_) | Item::Warning(_) => None,
        }
    }
}

impl From<Segment> for Item {
    #[inline(always)]
    fn from(segment: Segment) -> Item {
        Item::Segment(segment)
    }
}

/// The stream item of an alarm: a warning goes on as [`Item::Warning`], an error is the `Err`
/// that stops the run.
pub(crate) fn alarm_item(alarm: Alarm) -> StreamItem {
    if alarm.is_error() {
        Err(alarm)
    } else {
        Ok(Item::Warning(alarm))
    }
}

/// The segment of a stream item, if it is one.
#[inline(always)]
pub fn segment_of(item: &StreamItem) -> Option<&Segment> {
    match item {
        Ok(Item::Segment(segment)) => Some(segment),
        _ => None,
    }
}

/// A position in machine coordinates: X Y Z in mm, A B C in degrees.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct MachinePos(pub [f64; AXES]);

impl MachinePos {
    /// X, Y, Z.
    pub fn xyz(&self) -> [f64; 3] {
        [self.0[0], self.0[1], self.0[2]]
    }

    /// Straight-line distance to `other` over the linear axes.
    pub fn distance_xyz(&self, other: &MachinePos) -> f64 {
        let d = |i: usize| other.0[i] - self.0[i];
        (d(0) * d(0) + d(1) * d(1) + d(2) * d(2)).sqrt()
    }
}

/// The plane of an arc.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Plane {
    /// G17: X-Y, helix axis Z.
    Xy,
    /// G18: Z-X, helix axis Y.
    Zx,
    /// G19: Y-Z, helix axis X.
    Yz,
}

impl Plane {
    /// The axis indices (first, second, normal): for G18 the first axis is Z and the second X, so
    /// that counter-clockwise is seen from +Y.
    pub fn axes(self) -> (usize, usize, usize) {
        match self {
            Plane::Xy => (0, 1, 2),
            Plane::Zx => (2, 0, 1),
            Plane::Yz => (1, 2, 0),
        }
    }

    /// `xy`, `zx` or `yz`.
    pub fn as_str(self) -> &'static str {
        match self {
            Plane::Xy => "xy",
            Plane::Zx => "zx",
            Plane::Yz => "yz",
        }
    }
}

/// Direction of an arc, seen from the positive end of the plane's normal axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ArcDirection {
    /// G02.
    Clockwise,
    /// G03.
    CounterClockwise,
}

impl ArcDirection {
    /// `cw` or `ccw`.
    pub fn as_str(self) -> &'static str {
        match self {
            ArcDirection::Clockwise => "cw",
            ArcDirection::CounterClockwise => "ccw",
        }
    }

    /// The other way round.
    pub fn reversed(self) -> ArcDirection {
        match self {
            ArcDirection::Clockwise => ArcDirection::CounterClockwise,
            ArcDirection::CounterClockwise => ArcDirection::Clockwise,
        }
    }
}

/// How the feed of a cutting move was programmed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Feed {
    /// G94: mm/min along the path.
    PerMinute(f64),
    /// G95: mm per spindle revolution, with the spindle speed in rpm when one was programmed.
    PerRevolution {
        /// mm/rev.
        per_revolution: f64,
        /// Spindle speed, rpm.
        rpm: Option<f64>,
    },
    /// G93: the move takes 1/F minutes.
    InverseTime(f64),
}

impl Feed {
    /// The path speed in mm/min for a move of `length` mm, when it can be known.
    pub fn mm_per_min(&self, length: f64) -> Option<f64> {
        match *self {
            Feed::PerMinute(f) => Some(f),
            Feed::PerRevolution {
                per_revolution,
                rpm,
            } => rpm.map(|s| per_revolution * s),
            Feed::InverseTime(f) => Some(f * length),
        }
    }
}

/// The cutting mode in force for a motion (group 15 and G09), for the planner.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PathMode {
    /// G64: continuous path, corners blended.
    Continuous,
    /// G61: exact stop at every block end.
    ExactStop,
    /// G62: automatic corner override.
    CornerOverride,
    /// G63: tapping mode (no override, no blending).
    Tapping,
}

/// A high-speed or smoothing mode in force for a motion (Syntec G05 and G05.1, FANUC G05.1 Q1 and
/// G08 P1, SINUMERIK G641-G645): the control may leave the programmed path by up to this much to
/// keep its speed through the corners, or (SINUMERIK G641's ADIS) start and end its rounding up
/// to this far from the corner. Kept in whole micrometres, the top bit telling a rounding
/// distance, so that it fits beside the path mode and costs a motion no space.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Smoothing(std::num::NonZeroU16);

/// The bit of [`Smoothing`] that marks a rounding distance rather than a tolerance.
const DISTANCE_BIT: u16 = 0x8000;

impl Smoothing {
    /// The largest tolerance or distance kept, mm.
    pub const MAX_MM: f64 = 32.767;

    /// The tolerance `mm`, rounded to a micrometre and kept within 1 um to 32.767 mm.
    pub fn from_mm(mm: f64) -> Smoothing {
        let micrometres = (mm * 1000.0)
            .round()
            .clamp(1.0, f64::from(DISTANCE_BIT - 1));
        Smoothing(
            std::num::NonZeroU16::new(micrometres as u16).unwrap_or(std::num::NonZeroU16::MIN),
        )
    }

    /// A rounding that starts at most `mm` before the corner and ends at most `mm` after it
    /// (SINUMERIK G641 with ADIS or ADISPOS), kept as [`Smoothing::from_mm`] keeps a tolerance.
    pub fn distance(mm: f64) -> Smoothing {
        let bits = Smoothing::from_mm(mm).0.get() | DISTANCE_BIT;
        Smoothing(std::num::NonZeroU16::new(bits).unwrap_or(std::num::NonZeroU16::MIN))
    }

    /// True for a rounding distance ([`Smoothing::distance`]), false for a tolerance.
    pub fn is_distance(self) -> bool {
        self.0.get() & DISTANCE_BIT != 0
    }

    /// The tolerance or the distance, mm.
    pub fn mm(self) -> f64 {
        f64::from(self.0.get() & !DISTANCE_BIT) / 1000.0
    }
}

/// A motion in space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Move {
    /// Where it starts.
    pub from: MachinePos,
    /// Where it ends.
    pub to: MachinePos,
    /// The cutting mode in force.
    pub path_mode: PathMode,
    /// G09 in this block, or an exact stop the control makes anyway (e.g. before a tool change).
    pub exact_stop: bool,
    /// The high-speed or smoothing mode in force, if any (never in G61 or G63, which suspend it).
    pub smoothing: Option<Smoothing>,
    /// The frame the move was made in: the last [`Item::Frame`] before it, which has this id,
    /// carries the whole map from program to machine coordinates.
    pub frame: FrameId,
    /// Machine minus program coordinates at the end of the move (work offset, G92, G52 and tool
    /// length together): `to - offset` is the end point in the program's coordinates. It holds
    /// at the end point only: under a rotation or scaling the start, an arc's centre or a point
    /// moved by cutter compensation need the frame's [`WorkTransform`].
    pub offset: [f64; AXES],
}

impl Move {
    /// The end point in program (work) coordinates, from [`Move::offset`].
    pub fn work_to(&self) -> [f64; AXES] {
        std::array::from_fn(|i| self.to.0[i] - self.offset[i])
    }
}

/// Names a frame: the map from program to machine coordinates that a run had in force for a
/// stretch of moves. Ids count up from 0 in the order the frames came into force; a frame that
/// comes back (G69 after G68) gets a new id.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct FrameId(pub u32);

/// The whole map from program (work) coordinates to machine coordinates: `machine = linear ·
/// program + translation` on X Y Z, and `machine = factor · program + translation` on A B C.
/// It is the coordinate chain multiplied out (SINUMERIK's frames, G51/G51.1, G68, Syntec's
/// rotated G92.1), then the translations (G52, G92, the work offset, the external offset) and
/// the tool length vector.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorkTransform {
    /// X Y Z, row by row: `linear[i][j]` is how much program axis `j` moves machine axis `i`
    /// (the identity when nothing turns, scales or mirrors).
    pub linear: [[f64; 3]; 3],
    /// The factor of A B C (1, or G51's factor for the axis; -1 mirrors it).
    pub rotary: [f64; 3],
    /// Where the program's zero is on the machine, every axis.
    pub translation: [f64; AXES],
}

/// The identity of X Y Z.
const IDENTITY: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

impl WorkTransform {
    /// A translation only: machine = program + `translation`.
    pub fn translation(translation: [f64; AXES]) -> WorkTransform {
        WorkTransform {
            linear: IDENTITY,
            rotary: [1.0; 3],
            translation,
        }
    }

    /// True when the map only translates (no frame turns, scales or mirrors).
    pub fn is_translation(&self) -> bool {
        self.linear == IDENTITY && self.rotary == [1.0; 3]
    }

    /// The machine coordinates of a point in program coordinates.
    pub fn to_machine(&self, program: &[f64; AXES]) -> [f64; AXES] {
        let mut machine = [0.0; AXES];
        for (i, row) in self.linear.iter().enumerate() {
            let turned = row[0] * program[0] + row[1] * program[1] + row[2] * program[2];
            machine[i] = turned + self.translation[i];
        }
        for (i, factor) in self.rotary.iter().enumerate() {
            machine[3 + i] = factor * program[3 + i] + self.translation[3 + i];
        }
        machine
    }

    /// The map back, from machine to program coordinates; `None` when the map cannot be undone
    /// (the interpreter never makes one: a scale factor of zero is refused).
    pub fn inverse(&self) -> Option<WorkTransform> {
        let linear = invert(&self.linear)?;
        let rotary = self.rotary.map(|f| 1.0 / f);
        if rotary.iter().any(|f| !f.is_finite()) {
            return None;
        }
        // program = L⁻¹ (machine - t) = L⁻¹ machine - L⁻¹ t.
        let back = WorkTransform {
            linear,
            rotary,
            translation: [0.0; AXES],
        };
        let moved = back.to_machine(&self.translation);
        Some(WorkTransform {
            translation: moved.map(|v| -v),
            ..back
        })
    }
}

/// A frame's map back from machine to program coordinates on X Y Z, made once for the many
/// points a consumer converts: a plain subtraction when the frame only translates (the same
/// arithmetic as [`Move::work_to`]), the inverse map otherwise.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProgramMap {
    /// `machine - shift` on a translation.
    shift: [f64; 3],
    /// The inverse map, when the frame turns, scales or mirrors.
    back: Option<WorkTransform>,
}

impl ProgramMap {
    /// The map back of a frame that only translates by `offset` (a move's [`Move::offset`]).
    pub fn shift(offset: &[f64; AXES]) -> ProgramMap {
        ProgramMap {
            shift: [offset[0], offset[1], offset[2]],
            back: None,
        }
    }

    /// Program X Y Z of the machine point `machine`.
    #[inline]
    pub fn to_program(&self, machine: [f64; 3]) -> [f64; 3] {
        match &self.back {
            None => std::array::from_fn(|i| machine[i] - self.shift[i]),
            Some(back) => {
                let l = &back.linear;
                let t = &back.translation;
                std::array::from_fn(|i| {
                    l[i][0] * machine[0] + l[i][1] * machine[1] + l[i][2] * machine[2] + t[i]
                })
            }
        }
    }
}

impl WorkTransform {
    /// The map back from machine to program coordinates, for converting many points.
    pub fn program_map(&self) -> ProgramMap {
        let back = if self.is_translation() {
            None
        } else {
            self.inverse()
        };
        ProgramMap {
            shift: [
                self.translation[0],
                self.translation[1],
                self.translation[2],
            ],
            back,
        }
    }
}

/// The inverse of a 3x3 matrix (given row by row) by its adjugate, `None` when it is singular or
/// not finite.
pub(crate) fn invert(m: &[[f64; 3]; 3]) -> Option<[[f64; 3]; 3]> {
    // cofactor(i, j) of the transpose: the adjugate's entry (i, j).
    let cofactor = |i: usize, j: usize| {
        let (r0, r1) = ((j + 1) % 3, (j + 2) % 3);
        let (c0, c1) = ((i + 1) % 3, (i + 2) % 3);
        m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]
    };
    let adjugate: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| cofactor(i, j)));
    let determinant =
        m[0][0] * adjugate[0][0] + m[0][1] * adjugate[1][0] + m[0][2] * adjugate[2][0];
    if determinant == 0.0 || !determinant.is_finite() {
        return None;
    }
    let inverse = adjugate.map(|row| row.map(|v| v / determinant));
    inverse
        .iter()
        .flatten()
        .all(|v| v.is_finite())
        .then_some(inverse)
}

/// A frame coming into force: the moves that name its id are made in it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorkFrame {
    /// The frame's id, as the moves made in it carry it.
    pub id: FrameId,
    /// Program to machine coordinates, the tool length vector included.
    pub transform: WorkTransform,
    /// The tool length vector applied, machine X Y Z (Z on the ISO side; SINUMERIK's lengths
    /// by plane move X and Y too): already in `transform`'s translation; a consumer that follows
    /// the tool's tip rather than the programmed point subtracts it.
    pub tool_length: [f64; 3],
}

/// Why the program stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum StopKind {
    /// M00.
    Program,
    /// M01.
    Optional,
    /// `#3006 = n (MESSAGE)`: a stop that shows the operator a message.
    Message,
}

/// How the program ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum EndKind {
    /// M02.
    M02,
    /// M30.
    M30,
    /// A `%` tape mark after the program.
    TapeMark,
    /// The end of the text with no end code (a warning is raised too).
    EndOfText,
    /// M99 in the main program: the control starts it again until reset; vcnc stops after the
    /// passes its options allow (a warning says so).
    M99,
}

/// The spindle's state.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SpindleState {
    /// M03.
    Clockwise,
    /// M04.
    CounterClockwise,
    /// M05.
    Stopped,
    /// M19: oriented stop.
    Oriented,
}

/// A tool's offsets, geometry plus wear, mm: what a consumer that draws or simulates the tool
/// needs of it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ToolGeometry {
    /// Length offset.
    pub length: f64,
    /// Radius (half the register's value on controls that keep diameters).
    pub radius: f64,
}

/// A tool's shape, as the machine file's tool table (`[[tool_shapes]]`) describes it: the end
/// that cuts, the length of its flutes, the shank and the holder above. A tool the table does
/// not describe has none ([`SegmentKind::ToolChange`] carries `None`); a consumer takes it as a
/// flat end mill of its radius offset ([`ToolShape::flat`]). A plain value (no allocation) so
/// that a segment stays `Copy`: the holder is a short stack of fixed size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ToolShape {
    /// The end that cuts.
    pub tip: ToolTip,
    /// The cutting diameter, mm.
    pub diameter: f64,
    /// Length of the flutes from the tip, mm (infinite when the table does not say).
    pub cutting_length: f64,
    /// The shank's diameter above the flutes, mm.
    pub shank_diameter: f64,
    /// From the tip to the holder's face, mm (infinite when the tool has no holder).
    pub stickout: f64,
    /// The holder, from its face upwards.
    pub holder: Holder,
    /// False for a flat end mill whose end teeth do not reach the centre: it cannot plunge.
    pub center_cutting: bool,
}

/// The end of a tool that cuts: its profile about the tool's axis.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum ToolTip {
    /// A flat end mill.
    Flat,
    /// A ball nose end mill (the corner radius is half the diameter).
    Ball,
    /// A bull nose end mill.
    BullNose {
        /// The corner radius, mm.
        corner_radius: f64,
    },
    /// A drill.
    Drill {
        /// The included angle of the point, degrees (118 for a common twist drill).
        point_angle: f64,
    },
    /// A chamfer or engraving tool: a V.
    Cone {
        /// The included angle of the V, degrees.
        angle: f64,
        /// The diameter of the flat at its point, mm (0 for a sharp V).
        tip_diameter: f64,
    },
}

/// The most sections a holder has in a machine file.
pub const HOLDER_SECTIONS: usize = 4;

/// A tool holder: a stack of cylinders and cones from its face (the tool side) upwards.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Holder {
    sections: [HolderSection; HOLDER_SECTIONS],
    count: u8,
}

impl Holder {
    /// A holder of these sections, bottom first; `None` beyond [`HOLDER_SECTIONS`].
    pub fn new(sections: &[HolderSection]) -> Option<Holder> {
        let mut holder = Holder::default();
        for (slot, section) in holder.sections.iter_mut().zip(sections) {
            *slot = *section;
        }
        holder.count = u8::try_from(sections.len())
            .ok()
            .filter(|&n| usize::from(n) <= HOLDER_SECTIONS)?;
        Some(holder)
    }

    /// Its sections, from the face upwards (none for a tool without holder).
    pub fn sections(&self) -> &[HolderSection] {
        &self.sections[..usize::from(self.count)]
    }
}

/// One section of a holder: a cylinder, or a cone when its diameters differ.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct HolderSection {
    /// Its length along the tool axis, mm.
    pub length: f64,
    /// Its diameter at the bottom (tool side), mm.
    pub bottom_diameter: f64,
    /// Its diameter at the top, mm.
    pub top_diameter: f64,
}

/// What happened: a motion or an event.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum SegmentKind {
    /// G00 and the positioning moves of G28/G29/G30/G53.
    Rapid {
        /// The move.
        motion: Move,
        /// Each axis at its own rapid rate (dog-leg) rather than a straight line.
        per_axis: bool,
    },
    /// G01.
    Line {
        /// The move.
        motion: Move,
        /// The programmed feed.
        feed: Feed,
    },
    /// G02/G03, helical when the normal axis moves.
    Arc {
        /// The move.
        motion: Move,
        /// Centre, machine coordinates (its normal-axis value is the start's).
        center: MachinePos,
        /// Direction.
        direction: ArcDirection,
        /// Plane.
        plane: Plane,
        /// Full turns beyond the first (0 for an ordinary arc; a full circle has end = start and 0).
        extra_turns: u32,
        /// The programmed feed.
        feed: Feed,
    },
    /// G04.
    Dwell {
        /// Seconds.
        seconds: f64,
    },
    /// T: a tool is selected (prepared) for the next change.
    ToolSelect {
        /// Tool number.
        tool: u32,
    },
    /// M06: the tool change itself.
    ToolChange {
        /// The tool put in the spindle (the last T selected).
        tool: u32,
        /// Its offsets as the change found them in the register numbered like the tool (the
        /// usual setup, H and D equal to T; SINUMERIK: the tool's active edge); None when that
        /// register was never set. The length the moves are made with is the frame's
        /// ([`WorkFrame::tool_length`]): it follows G43 H, not T.
        geometry: Option<ToolGeometry>,
        /// Its shape, from the machine file's tool table (`[[tool_shapes]]`, by tool
        /// number); None for a tool the table does not describe.
        shape: Option<ToolShape>,
    },
    /// M03/M04/M05/M19 and S changes.
    Spindle {
        /// Direction or stop.
        state: SpindleState,
        /// Programmed speed, rpm (or m/min under G96).
        speed: f64,
    },
    /// M07/M08/M09.
    Coolant {
        /// On or off.
        on: bool,
    },
    /// An axis's dynamic limits from here on, as fractions of the machine file's (SINUMERIK
    /// VELOLIMA, ACCLIMA, JERKLIMA): the planner times the following motions with them. It
    /// takes no time and does not stop the motion.
    AxisLimits {
        /// The axis.
        axis: crate::axis::Axis,
        /// Of its highest speed (rapid and feed), 1 for the machine file's.
        velocity: f64,
        /// Of its acceleration.
        acceleration: f64,
        /// Of its jerk.
        jerk: f64,
    },
    /// M00/M01.
    Stop {
        /// Which stop.
        kind: StopKind,
    },
    /// Another M code, passed to the machine (PLC).
    Auxiliary {
        /// The M number.
        code: u32,
    },
    /// The end of the program.
    End {
        /// How it ended.
        kind: EndKind,
    },
}

/// A motion or an event of the stream.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    /// What happened.
    pub kind: SegmentKind,
    /// The block it comes from.
    pub span: Span,
    /// The block's sequence number (N), if it had one.
    pub sequence: Option<u32>,
}

impl Segment {
    /// The motion, for rapids, lines and arcs.
    pub fn motion(&self) -> Option<&Move> {
        match &self.kind {
            SegmentKind::Rapid { motion, .. }
            | SegmentKind::Line { motion, .. }
            | SegmentKind::Arc { motion, .. } => Some(motion),
            _ => None,
        }
    }

    /// Path length in mm (arcs along the helix), 0 for events.
    pub fn length(&self) -> f64 {
        match self.kind.path() {
            Some((motion, None)) => motion.from.distance_xyz(&motion.to),
            Some((motion, Some(arc))) => arc_length(
                motion,
                &arc.center,
                arc.direction,
                arc.plane,
                arc.extra_turns,
            ),
            None => 0.0,
        }
    }
}

/// An arc's geometry beside its move: what [`SegmentKind::path`] gives of an arc.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArcGeometry {
    /// Centre, machine coordinates (its normal-axis value is the start's).
    pub center: MachinePos,
    /// Direction.
    pub direction: ArcDirection,
    /// Plane.
    pub plane: Plane,
    /// Full turns beyond the first.
    pub extra_turns: u32,
}

impl ArcGeometry {
    /// The swept angle of the arc of `motion` in radians (positive), extra turns included.
    pub fn sweep(&self, motion: &Move) -> f64 {
        arc_sweep(
            motion,
            &self.center,
            self.direction,
            self.plane,
            self.extra_turns,
        )
    }

    /// [`ArcGeometry::sweep`] signed: positive counter-clockwise, negative clockwise.
    pub fn signed_sweep(&self, motion: &Move) -> f64 {
        let sweep = self.sweep(motion);
        match self.direction {
            ArcDirection::CounterClockwise => sweep,
            ArcDirection::Clockwise => -sweep,
        }
    }
}

impl SegmentKind {
    /// The move of a rapid, line or arc, with an arc's geometry; `None` for events. One match
    /// for the consumers that follow the path (checks, plots, simulation).
    pub fn path(&self) -> Option<(&Move, Option<ArcGeometry>)> {
        match self {
            SegmentKind::Rapid { motion, .. } | SegmentKind::Line { motion, .. } => {
                Some((motion, None))
            }
            SegmentKind::Arc {
                motion,
                center,
                direction,
                plane,
                extra_turns,
                ..
            } => Some((
                motion,
                Some(ArcGeometry {
                    center: *center,
                    direction: *direction,
                    plane: *plane,
                    extra_turns: *extra_turns,
                }),
            )),
            _ => None,
        }
    }
}

/// The swept angle of an arc in radians (positive), including extra full turns.
pub fn arc_sweep(
    motion: &Move,
    center: &MachinePos,
    direction: ArcDirection,
    plane: Plane,
    extra_turns: u32,
) -> f64 {
    let (a, b, _) = plane.axes();
    let start = (
        motion.from.0[a] - center.0[a],
        motion.from.0[b] - center.0[b],
    );
    let end = (motion.to.0[a] - center.0[a], motion.to.0[b] - center.0[b]);
    // The angle from start to end, counter-clockwise, in (-pi, pi]: one atan2 of the two
    // vectors' cross and dot products, not the difference of two (atan2 is most of an arc's
    // planning time).
    let cross = start.0 * end.1 - start.1 * end.0;
    let dot = start.0 * end.0 + start.1 * end.1;
    let turn = cross.atan2(dot);
    let mut sweep = match direction {
        ArcDirection::CounterClockwise => turn,
        ArcDirection::Clockwise => -turn,
    };
    let tau = std::f64::consts::TAU;
    if sweep < 0.0 {
        sweep += tau;
    }
    // A full circle (end on start) sweeps 2 pi, never 0.
    if sweep <= 1e-12 {
        sweep += tau;
    }
    sweep + tau * f64::from(extra_turns)
}

fn arc_length(
    motion: &Move,
    center: &MachinePos,
    direction: ArcDirection,
    plane: Plane,
    extra_turns: u32,
) -> f64 {
    let sweep = arc_sweep(motion, center, direction, plane, extra_turns);
    helix_length(motion, center, plane, sweep)
}

/// The length of an arc (along the helix) whose sweep, in radians, is known.
pub fn helix_length(motion: &Move, center: &MachinePos, plane: Plane, sweep: f64) -> f64 {
    let (a, b, n) = plane.axes();
    let radius = (motion.from.0[a] - center.0[a]).hypot(motion.from.0[b] - center.0[b]);
    let planar = radius * sweep;
    let axial = motion.to.0[n] - motion.from.0[n];
    planar.hypot(axial)
}

/// Calls `visit` with each point where an arc reaches its extremes along the plane's axes (0,
/// 90, 180, 270 degrees) that lies inside its sweep. The normal axis is taken at the start
/// (helix ends are added by the caller). A callback, not a list: the summary and the travel
/// check run once per segment of the stream and must not allocate.
pub(crate) fn for_arc_extreme_points(
    motion: &Move,
    center: [f64; 3],
    direction: ArcDirection,
    plane: Plane,
    sweep: f64,
    mut visit: impl FnMut([f64; 3]),
) {
    let (a, b, _) = plane.axes();
    let start = motion.from.xyz();
    let radius = (start[a] - center[a]).hypot(start[b] - center[b]);
    let start_angle = (start[b] - center[b]).atan2(start[a] - center[a]);
    // The four axis directions as (angle, cos, sin), exact.
    let quadrants = [
        (0.0, 1.0, 0.0),
        (1.0, 0.0, 1.0),
        (2.0, -1.0, 0.0),
        (3.0, 0.0, -1.0),
    ];
    for (quadrant, cos, sin) in quadrants {
        let angle = quadrant * std::f64::consts::FRAC_PI_2;
        let mut delta = match direction {
            ArcDirection::CounterClockwise => angle - start_angle,
            ArcDirection::Clockwise => start_angle - angle,
        };
        delta = delta.rem_euclid(std::f64::consts::TAU);
        if delta <= sweep {
            let mut p = start;
            p[a] = center[a] + radius * cos;
            p[b] = center[b] + radius * sin;
            visit(p);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_translation_is_taken_back_by_the_same_subtraction_as_the_moves_offset() {
        let offset = [0.1, -0.2, 100.3, 0.0, 0.0, 0.0];
        let map = WorkTransform::translation(offset);
        assert!(map.is_translation());
        let machine = [10.7, 3.3, 80.05];
        let motion_to = [machine[0], machine[1], machine[2], 0.0, 0.0, 0.0];
        let expected: [f64; 3] = std::array::from_fn(|i| motion_to[i] - offset[i]);
        assert_eq!(map.program_map().to_program(machine), expected);
        assert_eq!(ProgramMap::shift(&offset).to_program(machine), expected);
    }

    #[test]
    fn a_map_and_its_inverse_undo_each_other() {
        // A quarter turn about Z, X doubled, A mirrored, moved by (1, 2, 3) and A by 5:
        // program (1, 1, 1, A 1) goes to (-1 + 1, 2 + 2, 1 + 3, -1 + 5).
        let map = WorkTransform {
            linear: [[0.0, -1.0, 0.0], [2.0, 0.0, 0.0], [0.0, 0.0, 1.0]],
            rotary: [-1.0, 1.0, 1.0],
            translation: [1.0, 2.0, 3.0, 5.0, 0.0, 0.0],
        };
        let machine = map.to_machine(&[1.0, 1.0, 1.0, 1.0, 0.0, 0.0]);
        assert_eq!(machine, [0.0, 4.0, 4.0, 4.0, 0.0, 0.0]);
        let back = map.inverse().expect("a regular map");
        assert_eq!(back.to_machine(&machine), [1.0, 1.0, 1.0, 1.0, 0.0, 0.0]);
        assert_eq!(
            map.program_map().to_program([0.0, 4.0, 4.0]),
            [1.0, 1.0, 1.0]
        );
        let flat = WorkTransform {
            linear: [[1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0]],
            ..map
        };
        assert_eq!(flat.inverse(), None);
    }
}
