//! Following the tool through the motion stream: each move as the path of the tool's tip in
//! part coordinates, with the tool in the spindle and its shape. The plot and the simulator
//! both take the stream through a [`ToolFollower`].
//!
//! Part coordinates are the machine coordinates of the tool's tip less the first move's work
//! offset: the program's own coordinates as long as its first frame is a translation (the usual
//! G54 and G43), and a frame that changes later (G68, G52, another work offset) moves the path
//! in them as it moves the tool on the table. The tool's tip is the machine point less the
//! frame's tool length vector. The follower never cuts or draws: it names moves it cannot
//! follow (rotary axes, a tool not along Z) and leaves the warning to its consumer.

use crate::motion::{arc_sweep, ArcDirection, Item, Plane, Segment, SegmentKind, ToolShape};
use crate::motion::{SpindleState, WorkFrame};
use crate::source::Span;

/// The tool in the spindle as the follower knows it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tool {
    /// Its number (0 before the first tool change).
    pub number: u32,
    /// Its shape: the machine file's, or a flat end mill of its radius offset.
    pub shape: ToolShape,
    /// True when the machine file's tool table describes it.
    pub described: bool,
}

/// An arc of a move, in part coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArcPath {
    /// The centre (its normal-axis value is the start's).
    pub center: [f64; 3],
    /// The plane.
    pub plane: Plane,
    /// The swept angle, radians, positive counter-clockwise in the plane.
    pub sweep: f64,
    /// The radius, mm.
    pub radius: f64,
}

/// A move of the tool's tip in part coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ToolMove {
    /// A rapid (G0) rather than a cut.
    pub rapid: bool,
    /// Where it starts.
    pub from: [f64; 3],
    /// Where it ends.
    pub to: [f64; 3],
    /// The arc it follows, if it is one.
    pub arc: Option<ArcPath>,
    /// A rapid with each axis at its own rate (dog-leg): where its axes come to rest on the way,
    /// in order, before the end.
    pub corners: [Option<[f64; 3]>; 2],
    /// The block.
    pub span: Span,
}

/// Why a move cannot be followed as a tool along Z.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Unfollowed {
    /// An axis after X Y Z moves, or stands away from 0: a rotary axis, or a linear one the
    /// machine file names (U V W, a quill), which this 3-axis follower does not place.
    RotaryAxes,
    /// The tool length vector is not along Z (a tool along X or Y).
    ToolNotAlongZ,
}

impl Unfollowed {
    /// Words for people.
    pub fn describe(self) -> &'static str {
        match self {
            Unfollowed::RotaryAxes => {
                "an axis after X Y Z (rotary, or a linear U V W) moves or stands away from 0"
            }
            Unfollowed::ToolNotAlongZ => "the tool is not along Z",
        }
    }
}

/// What one item of the stream is to a consumer that follows the tool.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Followed {
    /// A move of the tool's tip.
    Move(ToolMove),
    /// A move the follower cannot take as a tool along Z.
    Unfollowed(Unfollowed, Span),
    /// A tool change: the tool now in the spindle.
    ToolChange(Tool, Span),
    /// Anything else (a frame, an event, a warning).
    Other,
}

/// Turns stream items into tool moves in part coordinates.
#[derive(Clone, Debug, Default)]
pub struct ToolFollower {
    frame: Option<WorkFrame>,
    /// Machine tip minus part coordinates, fixed by the first move.
    shift: Option<[f64; 3]>,
    tool: Option<Tool>,
    spindle: Option<SpindleState>,
    /// The machine's per-axis rapids, when the follower knows its axes.
    dog_leg: Option<crate::plan::DogLeg>,
}

impl ToolFollower {
    /// Follows a per-axis (dog-leg) rapid of `machine` along the path its axes take, not the
    /// straight line (see `plan::DogLeg`).
    pub fn per_axis_rapids(&mut self, machine: &crate::machine::Machine) {
        self.dog_leg = Some(crate::plan::DogLeg::new(machine));
    }

    /// A follower at the start of a run.
    pub fn new() -> ToolFollower {
        ToolFollower::default()
    }

    /// The tool in the spindle: before the first change, a flat end mill of radius 0 (it cuts
    /// nothing) numbered 0.
    pub fn tool(&self) -> Tool {
        self.tool.unwrap_or(Tool {
            number: 0,
            shape: ToolShape::flat(0.0),
            described: false,
        })
    }

    /// True while the spindle turns (M03/M04).
    pub fn spindle_turning(&self) -> bool {
        matches!(
            self.spindle,
            Some(SpindleState::Clockwise | SpindleState::CounterClockwise)
        )
    }

    /// Machine coordinates minus part coordinates (of the tip), once the first move is known.
    pub fn part_shift(&self) -> Option<[f64; 3]> {
        self.shift
    }

    /// What `item` is to the tool's path.
    pub fn follow(&mut self, item: &Item) -> Followed {
        match item {
            Item::Frame(frame) => {
                self.frame = Some(*frame);
                Followed::Other
            }
            Item::Warning(_) => Followed::Other,
            Item::Segment(segment) => self.follow_segment(segment),
        }
    }

    fn follow_segment(&mut self, segment: &Segment) -> Followed {
        let span = segment.span;
        let mut dog_leg = false;
        let (motion, rapid, arc) = match &segment.kind {
            SegmentKind::Rapid { motion, per_axis } => {
                dog_leg = *per_axis;
                (motion, true, None)
            }
            SegmentKind::Line { motion, .. } => (motion, false, None),
            SegmentKind::Arc {
                motion,
                center,
                direction,
                plane,
                extra_turns,
                ..
            } => {
                let sweep = arc_sweep(motion, center, *direction, *plane, *extra_turns);
                let signed = match direction {
                    ArcDirection::CounterClockwise => sweep,
                    ArcDirection::Clockwise => -sweep,
                };
                (motion, false, Some((center.xyz(), *plane, signed)))
            }
            SegmentKind::ToolChange {
                tool,
                geometry,
                shape,
            } => {
                let radius = geometry.map_or(0.0, |g| g.radius.abs());
                let tool = Tool {
                    number: *tool,
                    shape: shape.unwrap_or(ToolShape::flat(radius)),
                    described: shape.is_some(),
                };
                self.tool = Some(tool);
                return Followed::ToolChange(tool, span);
            }
            SegmentKind::Spindle { state, .. } => {
                self.spindle = Some(*state);
                return Followed::Other;
            }
            _ => return Followed::Other,
        };
        let rotary = (3..motion.from.0.len())
            .any(|i| motion.from.0[i].abs() > 1e-9 || motion.to.0[i].abs() > 1e-9);
        if rotary {
            return Followed::Unfollowed(Unfollowed::RotaryAxes, span);
        }
        let length = self.frame.map_or([0.0; 3], |f| f.tool_length);
        if length[0].abs() > 1e-9 || length[1].abs() > 1e-9 {
            return Followed::Unfollowed(Unfollowed::ToolNotAlongZ, span);
        }
        let shift = *self.shift.get_or_insert_with(|| {
            let translation = self.frame.map_or([0.0; 6], |f| f.transform.translation);
            std::array::from_fn(|i| translation[i] - length[i])
        });
        let part =
            |p: [f64; 3]| -> [f64; 3] { std::array::from_fn(|i| p[i] - length[i] - shift[i]) };
        let from = part(motion.from.xyz());
        let to = part(motion.to.xyz());
        let arc = arc.map(|(center, plane, sweep)| {
            let center = part(center);
            let (a, b, _) = plane.axes();
            ArcPath {
                center,
                plane,
                sweep,
                radius: (from[a] - center[a]).hypot(from[b] - center[b]),
            }
        });
        let mut corners = [None; 2];
        if let (true, Some(legs)) = (dog_leg, &self.dog_leg) {
            let points = legs.corners(motion);
            let inner = &points[..points.len().saturating_sub(1)];
            for (corner, (_, at)) in corners.iter_mut().zip(inner) {
                *corner = Some(part(at.xyz()));
            }
        }
        Followed::Move(ToolMove {
            rapid,
            from,
            to,
            arc,
            corners,
            span,
        })
    }
}

impl ToolMove {
    /// Calls `visit` with the points of the move from its start (excluded) to its end, with
    /// arcs cut into chords that leave the arc by at most `tolerance` mm.
    pub fn for_each_point(&self, tolerance: f64, mut visit: impl FnMut([f64; 3])) {
        let Some(arc) = self.arc else {
            self.corners.iter().flatten().for_each(|&p| visit(p));
            visit(self.to);
            return;
        };
        let steps = arc_steps(arc.radius, arc.sweep, tolerance);
        let (a, b, n) = arc.plane.axes();
        let start = (self.from[b] - arc.center[b]).atan2(self.from[a] - arc.center[a]);
        for i in 1..steps {
            let f = i as f64 / steps as f64;
            let angle = start + arc.sweep * f;
            let mut p = [0.0; 3];
            p[a] = arc.center[a] + arc.radius * angle.cos();
            p[b] = arc.center[b] + arc.radius * angle.sin();
            p[n] = self.from[n] + (self.to[n] - self.from[n]) * f;
            visit(p);
        }
        visit(self.to);
    }
}

/// How many chords an arc needs so that none leaves it by more than `tolerance`: the sagitta
/// of a chord of angle `t` is `r (1 - cos(t / 2))`.
fn arc_steps(radius: f64, sweep: f64, tolerance: f64) -> usize {
    let tolerance = tolerance.max(1e-6);
    let step = if tolerance >= radius {
        std::f64::consts::PI
    } else {
        2.0 * (1.0 - tolerance / radius).acos()
    };
    // At least four chords per full turn, and a bound that no radius can pass.
    let steps = (sweep.abs() / step.clamp(1e-4, std::f64::consts::FRAC_PI_2)).ceil();
    (steps as usize).clamp(1, 1_000_000)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A per-axis rapid of the default machine from (0,0,0) to (100,-30,5): Z comes to rest
    /// first, then Y, then X: the points visited are the two corners, then the end.
    #[test]
    fn a_per_axis_rapid_is_followed_along_its_legs() {
        use crate::motion::{MachinePos, Move, PathMode};
        let machine = crate::machine::Machine::default();
        let motion = Move {
            from: MachinePos([0.0; 6]),
            to: MachinePos([100.0, -30.0, 5.0, 0.0, 0.0, 0.0]),
            path_mode: PathMode::ExactStop,
            exact_stop: false,
            smoothing: None,
            frame: Default::default(),
            offset: [0.0; 6],
        };
        let segment = Segment {
            kind: SegmentKind::Rapid {
                motion,
                per_axis: true,
            },
            span: Span::default(),
            sequence: None,
        };
        let mut follower = ToolFollower::new();
        follower.per_axis_rapids(&machine);
        let Followed::Move(tool_move) = follower.follow(&Item::Segment(segment)) else {
            panic!("a move");
        };
        let mut points = Vec::new();
        tool_move.for_each_point(0.01, |p| points.push(p));
        assert_eq!(points.len(), 3, "{points:?}");
        assert_eq!(points[0][2], 5.0);
        assert!(points[0][0] > 0.0 && points[0][0] < 100.0, "{points:?}");
        assert_eq!(points[1][1..], [-30.0, 5.0]);
        assert_eq!(points[2], [100.0, -30.0, 5.0]);
        // Without the machine's axes the follower takes the straight line.
        let mut straight = ToolFollower::new();
        let Followed::Move(line) = straight.follow(&Item::Segment(segment)) else {
            panic!("a move");
        };
        assert_eq!(line.corners, [None, None]);
    }

    #[test]
    fn arc_chords_stay_within_the_tolerance() {
        // r = 10, tolerance 0.01: each chord spans 2 acos(0.999) = 0.0895 rad; a half turn
        // needs ceil(pi / 0.0895) = 36.
        assert_eq!(arc_steps(10.0, std::f64::consts::PI, 0.01), 36);
        assert_eq!(arc_steps(0.001, std::f64::consts::TAU, 0.01), 4);
    }
}
