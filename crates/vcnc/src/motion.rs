//! The canonical motion stream: what the interpreter yields.
//!
//! Every [`Segment`] is in machine coordinates (mm, degrees) and carries the [`Span`] of the block
//! it comes from. Consumers (trace output, planner, checks, simulation) need nothing else: no
//! segment refers back to syntax, modal state or the profile.

use crate::axis::AXES;
use crate::source::Span;

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
/// G08 P1): the control may leave the programmed path by up to this much to keep its speed
/// through the corners. Kept in whole micrometres, so that it fits beside the path mode and
/// costs a motion no space.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Smoothing(std::num::NonZeroU16);

impl Smoothing {
    /// The tolerance `mm`, rounded to a micrometre and kept within 1 um to 65 mm.
    pub fn from_mm(mm: f64) -> Smoothing {
        let micrometres = (mm * 1000.0).round().clamp(1.0, f64::from(u16::MAX));
        Smoothing(
            std::num::NonZeroU16::new(micrometres as u16).unwrap_or(std::num::NonZeroU16::MIN),
        )
    }

    /// The tolerance, mm.
    pub fn mm(self) -> f64 {
        f64::from(self.0.get()) / 1000.0
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
    /// Machine minus program coordinates at the end of the move (work offset, G92, G52 and tool
    /// length together): `to - offset` is the end point in the program's coordinates.
    pub offset: [f64; AXES],
}

impl Move {
    /// The end point in program (work) coordinates.
    pub fn work_to(&self) -> [f64; AXES] {
        std::array::from_fn(|i| self.to.0[i] - self.offset[i])
    }
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
        /// usual setup, H and D equal to T); None when that register was never set.
        geometry: Option<ToolGeometry>,
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

/// One item of the motion stream.
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
        match &self.kind {
            SegmentKind::Rapid { motion, .. } | SegmentKind::Line { motion, .. } => {
                motion.from.distance_xyz(&motion.to)
            }
            SegmentKind::Arc {
                motion,
                center,
                direction,
                plane,
                extra_turns,
                ..
            } => arc_length(motion, center, *direction, *plane, *extra_turns),
            _ => 0.0,
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
