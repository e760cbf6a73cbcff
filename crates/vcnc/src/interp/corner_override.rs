//! G62 automatic corner override (FANUC family): at an inner corner of the tool-centre path the
//! feed is lowered over the distance Le before the corner and Ls after it, and on an arc with the
//! tool inside it the feed along the tool centre is lowered by the ratio of the radii. Spec
//! iso-fanuc0m-mitsubishi.md A.31 (001 L1533: on by itself while G41/G42 is on, on FANUC 0M);
//! the settings are the profile's `compensation.corner_override`.
//!
//! How it sits in the pipeline: [`CornerStage`] is the stage right behind cutter compensation in
//! [`super::Output`]'s chain, so that it sees the compensated path. It holds the last cutting
//! move (and what is queued behind it) until the next move shows the corner at its end; then it
//! cuts the move at Le and Ls and writes the pieces with their feed lowered, so the planner times
//! the override with no rule of its own. It exists only while compensation is on, on a profile
//! whose G62 is the corner override.
//!
//! What it must never do: move a point of the path (pieces lie on the compensated move), or
//! change anything on a corner that is not inner (outer corners, rapids, moves out of the plane).

use super::comp::geometry::{turn, Element, Side, Turn, V2};
use super::pieces::Path;
use crate::motion::{
    ArcDirection, Feed, Item, MachinePos, Move, PathMode, Segment, SegmentKind, StreamItem,
};
use crate::profile::CornerOverride;

/// Pieces shorter than this, mm, are not cut off: the move keeps its feed there.
const SHORTEST_PIECE: f64 = 1e-6;

/// The stage between cutter compensation and the next stage (or the output queue) while
/// compensation is on.
#[derive(Clone, Debug)]
pub(crate) struct CornerStage {
    /// Compensated items, as compensation releases them.
    pub(crate) staged: Vec<StreamItem>,
    /// Items from this index on wait for compensation to know where a move ends.
    pub(crate) held: Option<usize>,
    settings: CornerOverride,
    /// The compensation plane's axes.
    axes: (usize, usize),
    /// The tool's side and radius, as compensation last had them.
    side: Side,
    radius: f64,
    /// The cutting move waiting for the corner at its end, with the items queued behind it.
    waiting: Vec<StreamItem>,
    /// The length at the start of the waiting move that the corner before it overrides (Ls).
    head: f64,
    /// The waiting move is the start-up block: the corner at its end is not overridden (FANUC:
    /// the override is off where the block before the corner is the start-up block).
    waiting_is_start_up: bool,
    /// No move has come yet: the next is the start-up block.
    before_start_up: bool,
}

impl CornerStage {
    /// The stage for compensation on `side` by `radius` in the plane `axes`.
    pub(crate) fn new(
        settings: CornerOverride,
        axes: (usize, usize),
        (side, radius): (Side, f64),
    ) -> CornerStage {
        CornerStage {
            staged: Vec::new(),
            held: None,
            settings,
            axes,
            side,
            radius: radius.abs(),
            waiting: Vec::new(),
            head: 0.0,
            waiting_is_start_up: false,
            before_start_up: true,
        }
    }

    /// The tool's side and radius now (G41/G42 or D changed in offset mode).
    pub(crate) fn set_offset(&mut self, (side, radius): (Side, f64)) {
        self.side = side;
        self.radius = radius.abs();
    }

    /// Passes on what compensation has released, holding the last cutting move back.
    pub(crate) fn settle(&mut self, items: &mut Vec<StreamItem>) {
        let ready = self.held.unwrap_or(self.staged.len());
        if ready == 0 {
            return;
        }
        let released: Vec<StreamItem> = self.staged.drain(..ready).collect();
        for item in released {
            self.take(item, items);
        }
        if let Some(held) = self.held.as_mut() {
            *held = 0;
        }
    }

    /// Compensation ends (or the run stops): everything is passed on, the last move with no
    /// corner after it.
    pub(crate) fn flush(mut self, items: &mut Vec<StreamItem>) {
        self.held = None;
        self.settle(items);
        self.release(None, items);
    }

    /// One released item.
    fn take(&mut self, item: StreamItem, items: &mut Vec<StreamItem>) {
        let segment = match &item {
            Ok(Item::Segment(segment)) if segment.motion().is_some() => segment,
            _ => {
                match self.waiting.is_empty() {
                    true => items.push(item),
                    false => self.waiting.push(item),
                }
                return;
            }
        };
        let start_up = std::mem::take(&mut self.before_start_up);
        let Some(element) = self.cutting_element(segment) else {
            // A rapid or a move out of the plane: no corner across it.
            self.release(None, items);
            items.push(item);
            return;
        };
        self.release(Some((segment, &element)), items);
        self.waiting.push(item);
        self.waiting_is_start_up = start_up;
    }

    /// Writes out the waiting move and what queued behind it; `next` is the move after it (with
    /// its element in the plane), when it makes a corner with it.
    fn release(&mut self, next: Option<(&Segment, &Element)>, items: &mut Vec<StreamItem>) {
        let mut waiting = std::mem::take(&mut self.waiting).into_iter();
        let Some(first) = waiting.next() else {
            self.head = 0.0;
            return;
        };
        let (tail, head) = match (next, &first) {
            (Some((next, next_element)), Ok(Item::Segment(segment))) => {
                self.corner(segment, next, next_element)
            }
            _ => (0.0, 0.0),
        };
        match first {
            Ok(Item::Segment(segment)) => self.write(&segment, tail, items),
            other => items.push(other),
        }
        items.extend(waiting);
        self.head = head;
    }

    /// Le and Ls at the corner between `segment` and `next`: both 0 unless the corner is an
    /// inner corner the override applies to.
    fn corner(&self, segment: &Segment, next: &Segment, next_element: &Element) -> (f64, f64) {
        let Some(element) = self.cutting_element(segment) else {
            return (0.0, 0.0);
        };
        if self.waiting_is_start_up || !self.applies(segment) && !self.applies(next) {
            return (0.0, 0.0);
        }
        let (ta, tb) = (element.end_tangent(), next_element.start_tangent());
        if turn(ta, tb, self.side) != Turn::Inner {
            return (0.0, 0.0);
        }
        // The inner angle of the corner is what the path's turn leaves of a straight line;
        // FANUC overrides corners from 2 degrees up to its parameter 1711.
        let inner = 180.0 - ta.cross(tb).atan2(ta.dot(tb)).abs().to_degrees();
        if (2.0..=self.settings.inner_angle).contains(&inner) {
            (self.settings.before_corner, self.settings.after_corner)
        } else {
            (0.0, 0.0)
        }
    }

    /// Whether the override is in force for `segment`: always with compensation on, where the
    /// profile says so (G61 and G63 of the same group still cancel it), or in G62.
    fn applies(&self, segment: &Segment) -> bool {
        let Some(motion) = segment.motion() else {
            return false;
        };
        match motion.path_mode {
            PathMode::CornerOverride => true,
            PathMode::Continuous => self.settings.with_compensation,
            PathMode::ExactStop | PathMode::Tapping => false,
        }
    }

    /// The element in the plane of a cutting move (a line or arc moving in the plane), with a
    /// tool radius to override for.
    fn cutting_element(&self, segment: &Segment) -> Option<Element> {
        if self.radius <= 0.0 {
            return None;
        }
        let at = |p: &MachinePos| V2::new(p.0[self.axes.0], p.0[self.axes.1]);
        match &segment.kind {
            SegmentKind::Line { motion, .. } => {
                let (start, end) = (at(&motion.from), at(&motion.to));
                (start.distance(end) > SHORTEST_PIECE).then_some(Element::Line { start, end })
            }
            SegmentKind::Arc {
                motion,
                center,
                direction,
                plane,
                ..
            } => {
                let (a, b, _) = plane.axes();
                ((a, b) == self.axes).then(|| Element::Arc {
                    start: at(&motion.from),
                    end: at(&motion.to),
                    center: at(center),
                    ccw: *direction == ArcDirection::CounterClockwise,
                })
            }
            _ => None,
        }
    }

    /// The factor of an arc's feed with the tool inside it: the tool centre's radius over the
    /// programmed one (the programmed path keeps F), at least the profile's minimum.
    fn arc_factor(&self, segment: &Segment) -> f64 {
        let element = match self.cutting_element(segment) {
            Some(element @ Element::Arc { ccw, .. }) if self.applies(segment) => {
                // The tool is inside an arc when the centre is on its side: left of a G03.
                let inside = ccw == (self.side == Side::Left);
                if !inside {
                    return 1.0;
                }
                element
            }
            _ => return 1.0,
        };
        let centre_radius = element.radius().unwrap_or(0.0);
        let programmed = centre_radius + self.radius;
        let floor = self.settings.inner_arc_min_percent / 100.0;
        (centre_radius / programmed).max(floor).min(1.0)
    }

    /// Writes `segment` cut where the override starts and ends: its first `self.head` mm and its
    /// last `tail` mm at the corner override.
    fn write(&self, segment: &Segment, tail: f64, items: &mut Vec<StreamItem>) {
        let arc = self.arc_factor(segment);
        let length = segment.length();
        let whole_turns =
            matches!(segment.kind, SegmentKind::Arc { extra_turns, .. } if extra_turns > 0);
        if (self.head <= 0.0 && tail <= 0.0 && arc == 1.0) || length <= SHORTEST_PIECE {
            items.push(Ok((*segment).into()));
            return;
        }
        let slow = arc * self.settings.override_percent / 100.0;
        if whole_turns {
            // A circle of several turns is not cut: its feed is lowered as a whole.
            let factor = if self.head > 0.0 || tail > 0.0 {
                slow
            } else {
                arc
            };
            items.push(Ok(piece(segment, (0.0, 1.0), factor, length).into()));
            return;
        }
        let start = self.head.min(length);
        let end = (length - tail).max(start);
        let mut cuts: Vec<(f64, f64, f64)> = Vec::with_capacity(3);
        for (from, to, factor) in [(0.0, start, slow), (start, end, arc), (end, length, slow)] {
            if to - from <= SHORTEST_PIECE {
                continue;
            }
            match cuts.last_mut() {
                Some(last) if last.2 == factor => last.1 = to,
                _ => cuts.push((from, to, factor)),
            }
        }
        if let Some(last) = cuts.last_mut() {
            last.1 = length;
        }
        if let Some(first) = cuts.first_mut() {
            first.0 = 0.0;
        }
        for (from, to, factor) in cuts {
            items.push(Ok(piece(
                segment,
                (from / length, to / length),
                factor,
                length,
            )
            .into()));
        }
    }
}

/// The part of `segment` (a line or arc of `length` mm) from parameter `t.0` to `t.1`, its feed
/// times `factor`.
fn piece(segment: &Segment, (t0, t1): (f64, f64), factor: f64, length: f64) -> Segment {
    let mut piece = *segment;
    let Some(path) = Path::of(segment) else {
        return piece;
    };
    let last = t1 >= 1.0;
    let share = t1 - t0;
    let cut = |motion: &mut Move| {
        motion.from = MachinePos(path.at(t0));
        motion.to = MachinePos(path.at(t1));
        // The block's exact stop is at its end, not between its pieces.
        motion.exact_stop &= last;
    };
    match &mut piece.kind {
        SegmentKind::Line { motion, feed } | SegmentKind::Arc { motion, feed, .. } => {
            cut(motion);
            *feed = scaled(*feed, factor, share, length);
        }
        _ => {}
    }
    piece
}

/// A feed times `factor` for a piece that is `share` of its block: G93's block time is shared
/// out by length, so the piece's own inverse time is the block's over its share.
fn scaled(feed: Feed, factor: f64, share: f64, length: f64) -> Feed {
    match feed {
        Feed::PerMinute(f) => Feed::PerMinute(f * factor),
        Feed::PerRevolution {
            per_revolution,
            rpm,
        } => Feed::PerRevolution {
            per_revolution: per_revolution * factor,
            rpm,
        },
        Feed::InverseTime(f) if share > 0.0 && length > 0.0 => {
            Feed::InverseTime(f * factor / share)
        }
        other => other,
    }
}
