//! Motion cut into straight machine pieces that follow a path within a tolerance: what the
//! output stages that map finished motion non-linearly share (G12.1 polar coordinate
//! interpolation, `polar_interpolation.rs`; the 5-axis kinematic transform, `tool_center.rs`;
//! G07.1 and G07 through [`PieceQueue`]).
//!
//! A stage describes its map by [`PieceMap`]: the machine position of a point of the path, and
//! how far a machine position puts the tool from a point of the path. [`cut`] halves a segment
//! until the straight machine move between two piece ends stays within the tolerance of the
//! path, judged at a quarter, half and three quarters of each piece, and writes the pieces as
//! moves of the segment's own kind, each timed by its share of the contour.

use crate::machine::AXES;
use crate::motion::{Feed, MachinePos, Move, PathMode, Segment, SegmentKind, StreamItem};
use crate::profile::Profile;

/// Halvings of a segment at most: a piece is never shorter than 2^-30 of its segment.
const MAX_DEPTH: u32 = 30;
/// Halvings per segment at most, so that a tolerance finer than the arithmetic can follow (far
/// from the centre at huge coordinates) cannot make pieces without end.
const MAX_SPLITS: u32 = 1 << 16;

/// How a stage maps the path's points to machine positions.
pub(crate) trait PieceMap {
    /// The machine position of the path point `p` (`offset`: machine minus program coordinates
    /// along the segment), next to the machine position `previous` (for angles kept continuous).
    fn to_machine(
        &self,
        p: &[f64; AXES],
        offset: &[f64; AXES],
        previous: &[f64; AXES],
    ) -> [f64; AXES];

    /// How far, mm, the machine position `machine` puts the tool from the path point `p`.
    fn deviation(&self, machine: &[f64; AXES], offset: &[f64; AXES], p: &[f64; AXES]) -> f64;
}

/// A Cartesian segment as a function of t in [0, 1].
pub(crate) enum Path {
    Straight {
        from: [f64; AXES],
        to: [f64; AXES],
    },
    /// An arc in the plane axes, the other axes straight (a helix).
    Arc {
        from: [f64; AXES],
        to: [f64; AXES],
        axes: (usize, usize),
        center: (f64, f64),
        start_angle: f64,
        /// Radians, negative clockwise.
        sweep: f64,
        /// Start and end radius (they may differ by the arc tolerance).
        radius: (f64, f64),
    },
}

impl Path {
    pub(crate) fn of(segment: &Segment) -> Option<Path> {
        let (motion, arc) = segment.kind.path()?;
        let (from, to) = (motion.from.0, motion.to.0);
        let Some(arc) = arc else {
            return Some(Path::Straight { from, to });
        };
        let (a, b, _) = arc.plane.axes();
        let center = (arc.center.0[a], arc.center.0[b]);
        let start = (from[a] - center.0, from[b] - center.1);
        let end = (to[a] - center.0, to[b] - center.1);
        Some(Path::Arc {
            from,
            to,
            axes: (a, b),
            center,
            start_angle: start.1.atan2(start.0),
            sweep: arc.signed_sweep(motion),
            radius: (start.0.hypot(start.1), end.0.hypot(end.1)),
        })
    }

    /// The point at `t`: exactly the start at 0 and the end at 1.
    pub(crate) fn at(&self, t: f64) -> [f64; AXES] {
        let (from, to) = match self {
            Path::Straight { from, to } | Path::Arc { from, to, .. } => (from, to),
        };
        if t <= 0.0 {
            return *from;
        }
        if t >= 1.0 {
            return *to;
        }
        let mut p = lerp(from, to, t);
        if let Path::Arc {
            axes: (a, b),
            center,
            start_angle,
            sweep,
            radius,
            ..
        } = self
        {
            let r = radius.0 + (radius.1 - radius.0) * t;
            let (sin, cos) = (start_angle + sweep * t).sin_cos();
            p[*a] = center.0 + r * cos;
            p[*b] = center.1 + r * sin;
        }
        p
    }
}

pub(crate) fn lerp(from: &[f64; AXES], to: &[f64; AXES], t: f64) -> [f64; AXES] {
    std::array::from_fn(|i| from[i] + (to[i] - from[i]) * t)
}

/// Moves what a stage's input queue has released (the items before `held`, all of them when
/// nothing is held) into `items`, each motion cut into pieces through `map` from `last` (updated
/// to where the last piece ends); the hold then starts at the front of what stays.
pub(crate) fn settle(
    (staged, held): (&mut Vec<StreamItem>, &mut Option<usize>),
    map: &impl PieceMap,
    (last, tolerance): (&mut [f64; AXES], f64),
    items: &mut Vec<StreamItem>,
) {
    let ready = held.unwrap_or(staged.len());
    if ready == 0 {
        return;
    }
    for item in staged.drain(..ready) {
        match item {
            Ok(crate::motion::Item::Segment(segment)) if segment.motion().is_some() => {
                *last = cut(map, &segment, *last, tolerance, items);
            }
            other => items.push(other),
        }
    }
    if let Some(held) = held.as_mut() {
        *held = 0;
    }
}

/// The input queue of a stage that cuts motion through a [`PieceMap`] and nothing else (G07.1,
/// G07), with where its last piece ended.
#[derive(Clone, Debug)]
pub(crate) struct PieceQueue<M> {
    /// Items as the stage's input gives them.
    pub(crate) staged: Vec<StreamItem>,
    /// Items from this index on wait for compensation to know where a move ends.
    pub(crate) held: Option<usize>,
    /// The machine position where the last piece ended.
    pub(crate) last: [f64; AXES],
    /// Largest distance between a piece and the path, mm.
    pub(crate) tolerance: f64,
    pub(crate) map: M,
}

impl<M: PieceMap> PieceQueue<M> {
    /// An empty queue whose first piece starts at the machine position `last`, the pieces
    /// within the profile's `polar_interpolation_tolerance`.
    pub(crate) fn new(map: M, last: [f64; AXES], profile: &Profile) -> PieceQueue<M> {
        PieceQueue {
            staged: Vec::new(),
            held: None,
            last,
            tolerance: profile.motion.polar_interpolation_tolerance,
            map,
        }
    }

    /// Converts the items released and appends them to `items`.
    pub(crate) fn settle(&mut self, items: &mut Vec<StreamItem>) {
        settle(
            (&mut self.staged, &mut self.held),
            &self.map,
            (&mut self.last, self.tolerance),
            items,
        );
    }

    /// The stage ends: everything staged is converted. Returns where the last piece ended.
    pub(crate) fn flush(&mut self, items: &mut Vec<StreamItem>) -> [f64; AXES] {
        self.held = None;
        self.settle(items);
        self.last
    }
}

/// One piece's end and where it ends on its segment.
struct PieceEnd {
    t: f64,
    machine: [f64; AXES],
}

/// Appends the pieces of `segment` (in the stage's input coordinates) to `items`, the first
/// starting at the machine position `start`; returns where the last one ends.
pub(crate) fn cut(
    map: &impl PieceMap,
    segment: &Segment,
    start: [f64; AXES],
    tolerance: f64,
    items: &mut Vec<StreamItem>,
) -> [f64; AXES] {
    let (Some(path), Some(motion)) = (Path::of(segment), segment.motion()) else {
        items.push(Ok((*segment).into()));
        return start;
    };
    let motion = *motion;
    // The contour's length on the part: the control keeps F along it.
    let contour = segment.length();
    let mut cut = Cut {
        map,
        tolerance,
        path: &path,
        offset: motion.offset,
        splits: MAX_SPLITS,
        ends: Vec::new(),
    };
    cut.refine((0.0, start), 1.0, 0);
    let ends = cut.ends;
    let count = ends.len();
    let mut from = (0.0, start);
    for (i, end) in ends.into_iter().enumerate() {
        // The block's exact stop (G09, G61) is at its end, not between its pieces.
        let last = i + 1 == count;
        let piece = Move {
            from: MachinePos(from.1),
            to: MachinePos(end.machine),
            exact_stop: motion.exact_stop && last,
            path_mode: match motion.path_mode {
                PathMode::ExactStop if !last => PathMode::Continuous,
                mode => mode,
            },
            ..motion
        };
        let kind = match segment.kind {
            SegmentKind::Rapid { .. } => SegmentKind::Rapid {
                motion: piece,
                per_axis: false,
            },
            SegmentKind::Line { feed, .. } | SegmentKind::Arc { feed, .. } => SegmentKind::Line {
                motion: piece,
                feed: piece_feed(feed, end.t - from.0, contour),
            },
            other => other,
        };
        items.push(Ok(Segment { kind, ..*segment }.into()));
        from = (end.t, end.machine);
    }
    from.1
}

/// One segment being cut into pieces.
struct Cut<'a, M> {
    map: &'a M,
    /// Largest deviation of a piece from the path, mm.
    tolerance: f64,
    path: &'a Path,
    /// Machine minus program coordinates along the segment.
    offset: [f64; AXES],
    /// Halvings left.
    splits: u32,
    ends: Vec<PieceEnd>,
}

impl<M: PieceMap> Cut<'_, M> {
    /// Cuts the path from `start` (its parameter and machine position) to `t1` into pieces
    /// within the tolerance, appending their ends; returns the last end.
    fn refine(&mut self, start: (f64, [f64; AXES]), t1: f64, depth: u32) -> [f64; AXES] {
        let (t0, from) = start;
        let end = self.map.to_machine(&self.path.at(t1), &self.offset, &from);
        if depth >= MAX_DEPTH || self.splits == 0 || self.within((t0, &from), (t1, &end)) {
            self.ends.push(PieceEnd {
                t: t1,
                machine: end,
            });
            return end;
        }
        self.splits -= 1;
        let middle = (t0 + t1) / 2.0;
        let reached = self.refine(start, middle, depth + 1);
        self.refine((middle, reached), t1, depth + 1)
    }

    /// True when the straight machine move between two points of the path stays within the
    /// tolerance of it, judged at a quarter, half and three quarters of the move (against the
    /// path at the same fraction of its parameter, which is stricter than the distance to it).
    fn within(&self, (t0, from): (f64, &[f64; AXES]), (t1, to): (f64, &[f64; AXES])) -> bool {
        [0.25, 0.5, 0.75].iter().all(|&s| {
            let machine = lerp(from, to, s);
            let p = self.path.at(t0 + (t1 - t0) * s);
            self.map.deviation(&machine, &self.offset, &p) <= self.tolerance
        })
    }
}

/// The feed of a piece covering `share` of its block, whose contour on the part is `length` mm
/// long. The control keeps F along the contour while the piece moves the machine's axes: the piece gets the
/// time its share of the contour takes at F, as an inverse-time feed, so that the planner (which
/// measures X Y Z travel) times it as the control moves it. G93's block time is shared out the
/// same way; a G95 feed without a spindle speed stays as it is (the planner's rule for it).
fn piece_feed(feed: Feed, share: f64, length: f64) -> Feed {
    if share <= 0.0 {
        return feed;
    }
    match feed {
        Feed::InverseTime(f) => Feed::InverseTime(f / share),
        _ => match feed.mm_per_min(length) {
            Some(f) if f > 0.0 && length > 0.0 => Feed::InverseTime(f / (share * length)),
            _ => feed,
        },
    }
}
