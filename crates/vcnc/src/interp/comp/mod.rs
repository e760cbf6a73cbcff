//! Cutter radius compensation (G40/G41/G42, issue #5): the look-ahead stage between the
//! executor and the output queue.
//!
//! `geometry` is the plane geometry: compensated elements, the corner rules (inner, outer, sharp
//! outer), start-up and cancel vectors and the interference check, checked against the manuals'
//! worked examples and by property tests. This module applies it to the motion stream:
//!
//! - A motion block in the plane executes at once, but its segment cannot be written until the
//!   next element in the plane is known (the corner decides where it ends). It becomes the
//!   pending element and the output queue is held from its place on: whatever the following
//!   blocks emit (events, moves of other axes) queues after it and is not handed out until the
//!   hold is resolved. Moves of other axes during the hold are made at a provisional plane
//!   position (the perpendicular end) and moved to the corner point when it is known.
//! - Resolution: the next plane motion (the corner; its extra straight moves belong to the block
//!   that turns the corner), G40 and program end (perpendicular end, then the G40 move to the
//!   programmed point), or the profile's look-ahead count of blocks in a row without plane motion (perpendicular end,
//!   as FANUC does).
//! - Start-up (type A): the start-up block ends at the next element's start moved perpendicular
//!   by the radius. G41/G42 in G02/G03 is refused by the caller (FANUC alarm 034).
//! - Alarms: an arc smaller than the tool and interference stop the control before the pending
//!   block moves; the caller drops what was held.
//!
//! A dialect's rules come as data ([`Rules`], `transition.rs`). SINUMERIK's own parts: the
//! smooth approach and retraction (`smooth.rs`), KONTC/KONTT curves (`polynomial.rs`), the
//! extension of a contour's short ends (`extension.rs`), bottleneck detection
//! (`bottleneck.rs`), and the compensator's methods for them: `ends.rs` (a contour's ends) and
//! `constant.rs` (CUTCONON).
pub(crate) mod bottleneck;
mod constant;
mod ends;
pub(crate) mod extension;
pub(crate) mod geometry;
pub(crate) mod polynomial;
pub(crate) mod smooth;
pub(crate) mod transition;

use crate::alarm::{Alarm, AlarmCode};
use crate::machine::AXES;
use crate::motion::{
    ArcDirection, Feed, Item, MachinePos, Plane, Segment, SegmentKind, StreamItem,
};
use extension::Extension;
use geometry::{Element, GeometryError, Link, Side, V2};
use transition::{Approach, Rules};

/// Cutter compensation in force: turns the programmed motion of the executor (machine
/// coordinates, the tool's programmed centre) into the tool-centre path, one corner late.
#[derive(Clone, Debug)]
pub(crate) struct Compensator {
    side: Side,
    radius: f64,
    /// The plane's first and second axis.
    axes: (usize, usize),
    /// Where the tool centre is, plane axes, when nothing is pending.
    tool: V2,
    pending: Option<Pending>,
    idle_blocks: u32,
    /// Blocks without motion in the plane after which a pending element ends perpendicular to
    /// itself (the profile's look-ahead).
    look_ahead: u32,
    /// True once the first element in the plane (the start-up) has come.
    started: bool,
    /// True when the block being executed moved in the plane.
    moved: bool,
    /// G40 in this block: the next motion goes from the tool centre to the programmed point.
    cancelling: bool,
    /// G28, G29, G30, G53 or G92 in this block: compensation is cancelled for the block and
    /// starts up again with the next motion in the plane (spec A.22 rule 4).
    suspended: bool,
    /// A change of side or radius (G41/G42 or D in offset mode), for the next element.
    next: Option<(Side, f64)>,
    /// G41 (true) or G42 in force, before the sign of the offset and mirroring decide the side.
    left: bool,
    /// One axis of the plane was mirrored when the side was last worked out.
    reversed: bool,
    /// The dialect's corner and approach rules.
    rules: Rules,
    /// SINUMERIK's CUTCONON: moves go uncompensated, shifted by this vector (the tool centre's
    /// offset where the last compensated element ended).
    constant: Option<V2>,
    /// The last element moved under CUTCONON, until the next compensated one: KONT goes round
    /// the corner between them.
    suppressed: Option<Element>,
    /// SINUMERIK's smooth approach of the start-up block, the moves before it without travel
    /// in the plane (the end of one is the approach's level), taken into it from where the first
    /// started, and the first element's start direction once known.
    smooth: Option<smooth::Approach>,
    absorbed: Option<[f64; AXES]>,
    next_tangent: Option<V2>,
    /// The first element's compensated curvature where it starts (KONTC).
    next_curvature: f64,
    /// SINUMERIK's smooth retraction of the cancelling block (G148, G248, G348), and the moves
    /// of that block along the plane's normal only, taken into it.
    retraction: Option<smooth::Approach>,
    retraction_moves: Option<Segment>,
    /// The programmed elements emitted last, the newest last (SINUMERIK CDON checks against
    /// them).
    history: Vec<Element>,
    /// SINUMERIK G461/G462: the element after the pending one, whose corner with it has no
    /// intersection, kept until the next block shows whether it ends the contour.
    doubt: Option<Doubt>,
}

/// An element whose corner with the pending one cannot be made, and the alarm it raises unless
/// the contour ends with it (`place`: its segment's place in the queue, after the hold).
#[derive(Clone, Debug)]
struct Doubt {
    element: Element,
    segment: Segment,
    alarm: Alarm,
    place: usize,
}

#[derive(Clone, Debug)]
struct Pending {
    /// The programmed element, plane axes.
    element: Element,
    /// Where its compensated element starts.
    start: V2,
    /// The programmed segment, rewritten when the pending element is resolved. Its place in the
    /// output queue is the start of the hold.
    segment: Segment,
    /// The start-up block: it ends on the next element's start-up vector.
    start_up: bool,
    /// The plane position used meanwhile by moves of other axes: the perpendicular end.
    provisional: V2,
    /// The contour's first element, the start-up block held before it (SINUMERIK G461/G462 may
    /// still move the start-up's end), and its place in the queue after the hold.
    first: bool,
    place: usize,
}

fn plane_point(p: &[f64; AXES], (a, b): (usize, usize)) -> V2 {
    V2::new(p[a], p[b])
}

fn set_plane(p: &mut [f64; AXES], (a, b): (usize, usize), v: V2) {
    p[a] = v.x;
    p[b] = v.y;
}

impl Compensator {
    /// Compensation on `side` by `radius` in the plane `axes`, from the tool position `tool`
    /// (machine coordinates), started by G41 (`left`) or G42.
    pub(crate) fn new(
        (side, radius): (Side, f64),
        axes: (usize, usize),
        tool: &[f64; AXES],
        left: bool,
        look_ahead: u32,
    ) -> Self {
        Compensator {
            side,
            radius: radius.abs(),
            axes,
            tool: plane_point(tool, axes),
            pending: None,
            idle_blocks: 0,
            look_ahead: look_ahead.max(1),
            started: false,
            moved: false,
            cancelling: false,
            suspended: false,
            next: None,
            left,
            reversed: false,
            rules: Rules::FANUC,
            constant: None,
            suppressed: None,
            smooth: None,
            absorbed: None,
            next_tangent: None,
            next_curvature: 0.0,
            retraction: None,
            retraction_moves: None,
            doubt: None,
            history: Vec::new(),
        }
    }

    /// The start-up block approaches the contour smoothly (SINUMERIK's G147, G247, G347), or
    /// the cancelling block leaves it so (G148, G248, G348).
    pub(crate) fn approach_smoothly(&mut self, approach: smooth::Approach) {
        if self.cancelling {
            self.retraction = Some(approach);
        } else {
            self.smooth = Some(approach);
        }
    }

    /// The same compensation under a dialect's `rules`.
    pub(crate) fn with_rules(mut self, rules: Rules) -> Self {
        self.rules = rules;
        self
    }

    /// The rules from here on (a change of corner or approach mode while compensating).
    pub(crate) fn set_rules(&mut self, rules: Rules) {
        self.rules = rules;
    }

    /// The plane of the compensation's axes.
    fn plane(&self) -> Plane {
        [Plane::Xy, Plane::Zx, Plane::Yz]
            .into_iter()
            .find(|plane| {
                let (a, b, _) = plane.axes();
                (a, b) == self.axes
            })
            .unwrap_or(Plane::Xy)
    }

    /// The programmed element of a motion segment in the plane, `None` for a move with no travel
    /// in the plane.
    fn element(&self, segment: &Segment) -> Option<Element> {
        let motion = segment.motion()?;
        let start = plane_point(&motion.from.0, self.axes);
        let end = plane_point(&motion.to.0, self.axes);
        match segment.kind {
            SegmentKind::Arc {
                center, direction, ..
            } => Some(Element::Arc {
                start,
                end,
                center: plane_point(&center.0, self.axes),
                ccw: direction == ArcDirection::CounterClockwise,
            }),
            _ if start.distance(end) > geometry::EPSILON => Some(Element::Line { start, end }),
            _ => None,
        }
    }

    /// Takes a segment of the executor: events and moves of other axes go to the queue as they
    /// are (moves at the tool centre's plane position); a motion in the plane resolves the
    /// pending one and becomes pending itself.
    ///
    /// # Errors
    /// The alarm of a corner that cannot be made.
    pub(crate) fn push(
        &mut self,
        segment: Segment,
        items: &mut Vec<StreamItem>,
        held: &mut Option<usize>,
    ) -> Result<(), Alarm> {
        if segment.motion().is_none() {
            items.push(Ok(segment.into()));
            return Ok(());
        }
        if self.suspended {
            // Without compensation for this block: the first move leaves from the tool centre.
            let mut segment = segment;
            if let Some(motion) = motion_mut(&mut segment) {
                set_plane(&mut motion.from.0, self.axes, self.tool);
                self.tool = plane_point(&motion.to.0, self.axes);
            }
            items.push(Ok(segment.into()));
            return Ok(());
        }
        if let Some(shift) = self.constant {
            self.push_shifted(segment, shift, items);
            return Ok(());
        }
        let Some(element) = self.element(&segment) else {
            if self.cancelling && self.retraction.is_some() {
                // The smooth retraction's block moves only along the normal: its end is P0.
                let taken = self.retraction_moves.get_or_insert(segment);
                if let (Some(all), Some(this)) = (motion_mut(taken), segment.motion()) {
                    all.to = this.to;
                }
                return Ok(());
            }
            if self.smooth.is_some() && !self.started {
                // Before a smooth approach: the move only sets the level the contour starts at.
                if let Some(motion) = segment.motion() {
                    self.absorbed.get_or_insert(motion.from.0);
                }
                return Ok(());
            }
            let mut segment = segment;
            let here = self.pending.as_ref().map_or(self.tool, |p| p.provisional);
            if let Some(motion) = motion_mut(&mut segment) {
                set_plane(&mut motion.from.0, self.axes, here);
                set_plane(&mut motion.to.0, self.axes, here);
            }
            items.push(Ok(segment.into()));
            return Ok(());
        };
        if let SegmentKind::Arc { plane, .. } = segment.kind {
            let (a, b, _) = plane.axes();
            if (a, b) != self.axes {
                return Err(Alarm::not_supported(
                    segment.span,
                    "an arc outside the plane of cutter compensation",
                    Some(5),
                ));
            }
        }
        self.idle_blocks = 0;
        self.moved = true;
        if self.cancelling {
            // The G40 block: from the tool centre to the programmed end.
            self.resolve_doubt(items, held)?;
            if let Some(retraction) = self.retraction.take() {
                return self.retract_smoothly(&retraction, Some(segment), items, held);
            }
            if let Approach::Curve(continuity) = self.rules.approach {
                return self.retract_on_curve(continuity, segment, items, held);
            }
            self.retract(&element, &segment, items, held)?;
            let mut segment = segment;
            if let Some(motion) = motion_mut(&mut segment) {
                set_plane(&mut motion.from.0, self.axes, self.tool);
            }
            self.tool = element.end();
            items.push(Ok(segment.into()));
            return Ok(());
        }
        // The side and radius for this element: a change in offset mode applies from here.
        let setting = self.next.take().unwrap_or((self.side, self.radius));
        // An element that cannot be compensated at all (an arc smaller than the tool) stops the
        // control before the block waiting for it moves.
        element
            .offset(setting.0, setting.1)
            .map_err(|e| self.alarm(e, &segment))?;
        if setting.1 != self.radius
            && self.pending.is_some()
            && matches!(element, Element::Arc { .. })
        {
            // The element would start at the old radius and end at the new one.
            return Err(Alarm::not_supported(
                segment.span,
                "changing D in an arc block while compensating",
                Some(5),
            ));
        }
        let start_up = !self.started;
        let mut segment = segment;
        if let (true, Some(from), Some(motion)) =
            (start_up, self.absorbed.take(), motion_mut(&mut segment))
        {
            motion.from = MachinePos(from);
        }
        if let Some(doubt) = self.doubt.take() {
            // The element that met no intersection does not end the contour.
            return Err(doubt.alarm);
        }
        self.next_tangent = Some(element.start_tangent());
        self.next_curvature = polynomial::curvature(&element, setting);
        let mut start_up_at = None;
        let start = match self.pending.take() {
            Some(pending) => match self.corner(&pending, &element, &segment, setting) {
                Ok((a_end, links)) => {
                    // G461/G462 may still move a start-up block of one straight move (not a
                    // smooth approach, a curve or KONT's way round the start).
                    let keep = pending.start_up
                        && self.rules.extension != Extension::None
                        && self.smooth.is_none()
                        && !matches!(self.rules.approach, Approach::Curve(_))
                        && links.is_empty();
                    let at = self.emit(pending, a_end, items, held)?;
                    start_up_at = keep.then_some(at);
                    (self.side, self.radius) = setting;
                    self.links(a_end, &links, &segment, items);
                    self.tool
                }
                Err(alarm) if self.rules.extension == Extension::None || pending.start_up => {
                    // The run stops here; the pending element stays with the items held for it.
                    self.pending = Some(pending);
                    return Err(alarm);
                }
                Err(alarm) => {
                    // The first element skipped (the approach), or else perhaps the last one
                    // (the retraction, once the next block tells).
                    let skip_to = pending.first.then(|| {
                        let rule = self.rules.extension;
                        extension::extended_start(rule, &pending.element, &element, setting)
                    });
                    if let Some(point) = skip_to.flatten() {
                        self.skip_first(pending, point, items, held);
                        (self.side, self.radius) = setting;
                        point
                    } else {
                        let place = items.len() - held.unwrap_or(items.len());
                        self.pending = Some(pending);
                        self.doubt = Some(Doubt {
                            element,
                            segment,
                            alarm,
                            place,
                        });
                        if setting != (self.side, self.radius) {
                            self.next = Some(setting);
                        }
                        return Ok(());
                    }
                }
            },
            None if start_up => {
                (self.side, self.radius) = setting;
                self.tool
            }
            None => {
                // After an end perpendicular to the last element: straight to this one's start.
                (self.side, self.radius) = setting;
                let start = geometry::start_up_end(&element, self.side, self.radius);
                let tool = self.tool;
                let link = self.rejoin(&element, start);
                self.links(tool, &[link], &segment, items);
                start
            }
        };
        let provisional = geometry::perpendicular_end(&element, self.side, self.radius);
        debug_assert!(held.is_none(), "one pending element at a time");
        // The start-up block stays held while the first element's end is unknown.
        let hold = start_up_at.unwrap_or(items.len());
        *held = Some(hold);
        self.pending = Some(Pending {
            element,
            start,
            segment,
            start_up,
            provisional,
            first: start_up_at.is_some(),
            place: items.len() - hold,
        });
        self.started = true;
        Ok(())
    }

    /// The end of the pending element and the links to the next one's start, which is
    /// compensated with `setting`. A change of radius takes effect at the end of the next
    /// element (the corner is made with the old one); a change of side at this corner.
    fn corner(
        &self,
        pending: &Pending,
        next: &Element,
        segment: &Segment,
        (side, radius): (Side, f64),
    ) -> Result<(V2, Vec<Link>), Alarm> {
        if pending.start_up {
            let around = match pending.element {
                Element::Line { start, .. } if self.rules.approach == Approach::AroundPoint => {
                    transition::around_start(self.rules.outer, start, next, side, radius)
                }
                _ => None,
            };
            return Ok(match around {
                Some(corner) => (corner.a_end, corner.links),
                None => (geometry::start_up_end(next, side, radius), Vec::new()),
            });
        }
        let corner = if side == self.side {
            transition::corner(
                self.rules.outer,
                &pending.element,
                next,
                self.side,
                self.radius,
            )
        } else {
            geometry::side_change(
                &pending.element,
                next,
                (self.side, self.radius),
                (side, radius),
            )
        }
        .map_err(|e| self.alarm(e, segment))?;
        Ok((corner.a_end, corner.links))
    }

    /// Writes the pending element's compensated segment at its place in the queue, ending at
    /// `end`, and moves what was held after it from the provisional point to `end`; returns
    /// that place.
    ///
    /// # Errors
    /// Interference: the compensated element would run against the programmed one.
    fn emit(
        &mut self,
        pending: Pending,
        end: V2,
        items: &mut Vec<StreamItem>,
        held: &mut Option<usize>,
    ) -> Result<usize, Alarm> {
        if !pending.start_up && geometry::interferes(&pending.element, pending.start, end) {
            return Err(self.alarm(GeometryError::Interference, &pending.segment));
        }
        if !pending.start_up {
            let before_neighbour = &self.history[..self.history.len().saturating_sub(1)];
            let ends = (pending.start, end);
            if self.rules.bottleneck
                && bottleneck::cuts_into(&pending.element, ends, before_neighbour, self.radius)
            {
                return Err(self.alarm(GeometryError::Bottleneck, &pending.segment));
            }
            if self.history.len() == bottleneck::CHECKED_BLOCKS {
                self.history.remove(0);
            }
            self.history.push(pending.element);
        }
        let at = held.take().map_or(items.len(), |hold| hold + pending.place);
        let mut segment = pending.segment;
        if let Some(motion) = motion_mut(&mut segment) {
            set_plane(&mut motion.from.0, self.axes, pending.start);
            set_plane(&mut motion.to.0, self.axes, end);
        }
        let smooth = self.smooth.take().filter(|_| pending.start_up);
        let segments = match (smooth, self.next_tangent, self.rules.approach) {
            (Some(approach), Some(tangent), _) => smooth::approach_moves(
                &approach,
                &segment,
                (end, tangent),
                (self.side, self.radius),
                self.plane(),
            ),
            (None, Some(tangent), Approach::Curve(continuity)) if pending.start_up => {
                let arrival = (tangent, self.next_curvature);
                ends::curve_pieces(&segment, |ends| {
                    polynomial::approach(continuity, ends, self.axes, arrival)
                })
            }
            _ => vec![segment],
        };
        for later in items[at..].iter_mut() {
            if let Some(motion) = segment_mut(later).and_then(motion_mut) {
                for point in [&mut motion.from.0, &mut motion.to.0] {
                    if plane_point(point, self.axes) == pending.provisional {
                        set_plane(point, self.axes, end);
                    }
                }
            }
        }
        items.splice(at..at, segments.into_iter().map(|s| Ok(s.into())));
        self.tool = end;
        Ok(at)
    }

    /// The moves of an outer corner, as moves of the block that turns the corner.
    fn links(&mut self, from: V2, links: &[Link], segment: &Segment, items: &mut Vec<StreamItem>) {
        let mut here = from;
        for &link in links {
            let point = link.to();
            if point.distance(here) < geometry::EPSILON {
                continue;
            }
            let mut motion = match segment.motion() {
                Some(motion) => *motion,
                None => continue,
            };
            let (mut start, mut to) = (motion.from.0, motion.from.0);
            set_plane(&mut start, self.axes, here);
            set_plane(&mut to, self.axes, point);
            motion.from = MachinePos(start);
            motion.to = MachinePos(to);
            let kind = match (link, segment.kind) {
                (Link::Arc { center, ccw, .. }, kind) => {
                    let mut centre = start;
                    set_plane(&mut centre, self.axes, center);
                    SegmentKind::Arc {
                        motion,
                        center: MachinePos(centre),
                        direction: if ccw {
                            ArcDirection::CounterClockwise
                        } else {
                            ArcDirection::Clockwise
                        },
                        plane: self.plane(),
                        extra_turns: 0,
                        feed: match kind {
                            SegmentKind::Line { feed, .. } | SegmentKind::Arc { feed, .. } => feed,
                            _ => Feed::PerMinute(self.rules.rapid_arc_feed),
                        },
                    }
                }
                (Link::Line(_), SegmentKind::Arc { feed, .. }) => {
                    SegmentKind::Line { motion, feed }
                }
                (Link::Line(_), kind) => with_motion(kind, motion),
            };
            items.push(Ok(Segment { kind, ..*segment }.into()));
            here = point;
        }
        self.tool = here;
    }

    /// The G40 block's move in the plane: the pending element ends perpendicular to itself
    /// (or round its end point, by the rules), and the block goes from there to its end.
    fn retract(
        &mut self,
        element: &Element,
        segment: &Segment,
        items: &mut Vec<StreamItem>,
        held: &mut Option<usize>,
    ) -> Result<(), Alarm> {
        let around = match &self.pending {
            Some(pending) if !pending.start_up && self.rules.approach == Approach::AroundPoint => {
                transition::around_end(
                    self.rules.outer,
                    &pending.element,
                    element.end(),
                    self.side,
                    self.radius,
                )
            }
            _ => None,
        };
        let Some(corner) = around else {
            return self.finish(items, held);
        };
        let pending = self.pending.take().expect("matched above");
        let _ = self.emit(pending, corner.a_end, items, held)?;
        let a_end = corner.a_end;
        self.links(a_end, &corner.links, segment, items);
        Ok(())
    }

    /// A block ends: past the look-ahead of blocks without motion in the plane, the pending
    /// element ends perpendicular to itself.
    ///
    /// # Errors
    /// Interference at that end.
    pub(crate) fn end_block(
        &mut self,
        items: &mut Vec<StreamItem>,
        held: &mut Option<usize>,
    ) -> Result<(), Alarm> {
        if std::mem::take(&mut self.suspended) {
            // Compensation starts up again with the next motion in the plane.
            self.started = false;
            self.moved = false;
            return Ok(());
        }
        if !std::mem::take(&mut self.moved) && self.pending.is_some() {
            self.idle_blocks += 1;
            if self.idle_blocks >= self.look_ahead {
                self.finish(items, held)?;
            }
        }
        Ok(())
    }

    /// The end of compensation or of the program: nothing stays pending.
    ///
    /// # Errors
    /// Interference at the pending element's end.
    pub(crate) fn finish(
        &mut self,
        items: &mut Vec<StreamItem>,
        held: &mut Option<usize>,
    ) -> Result<(), Alarm> {
        self.resolve_doubt(items, held)?;
        if let Some(retraction) = self.retraction.take().filter(|_| self.cancelling) {
            let moves = self.retraction_moves.take();
            return self.retract_smoothly(&retraction, moves, items, held);
        }
        match self.pending.take() {
            Some(pending) => {
                let end = pending.provisional;
                self.emit(pending, end, items, held).map(|_| ())
            }
            None => Ok(()),
        }
    }

    /// G28, G29, G30, G53 or G92 in offset mode: the pending element ends perpendicular to
    /// itself and the block's moves are made without compensation.
    ///
    /// # Errors
    /// Interference at the pending element's end.
    pub(crate) fn suspend(
        &mut self,
        items: &mut Vec<StreamItem>,
        held: &mut Option<usize>,
    ) -> Result<(), Alarm> {
        self.finish(items, held)?;
        self.suspended = true;
        Ok(())
    }

    /// G41/G42 or D in offset mode: the new side and radius apply from the next element.
    pub(crate) fn change(&mut self, setting: (Side, f64), left: bool) {
        self.left = left;
        self.next = (setting != (self.side, self.radius)).then_some(setting);
    }

    /// The tool's side and radius in force.
    pub(crate) fn offset(&self) -> (Side, f64) {
        (self.side, self.radius)
    }

    /// G41 (true) or G42 in force.
    pub(crate) fn left(&self) -> bool {
        self.left
    }

    /// True when one axis of the plane was mirrored when the side was last worked out.
    pub(crate) fn reversed(&self) -> bool {
        self.reversed
    }

    /// Records whether one axis of the plane is mirrored for the side last worked out.
    pub(crate) fn set_reversed(&mut self, reversed: bool) {
        self.reversed = reversed;
    }

    /// An alarm stops the control: the pending element never moves.
    pub(crate) fn abandon(&mut self) {
        self.pending = None;
    }

    /// The alarm of a corner or element that cannot be made, in the dialect's terms.
    fn alarm(&self, error: GeometryError, segment: &Segment) -> Alarm {
        geometry_alarm(error, segment, self.rules.alarm_help)
    }

    /// G40 in the block being executed.
    pub(crate) fn cancel(&mut self) {
        self.cancelling = true;
    }

    /// Where the tool centre is, plane axes (after `finish`).
    pub(crate) fn tool(&self) -> V2 {
        self.tool
    }

    /// The plane's first and second axis.
    pub(crate) fn axes(&self) -> (usize, usize) {
        self.axes
    }

    /// True while a G40 block is being executed.
    pub(crate) fn is_cancelling(&self) -> bool {
        self.cancelling
    }
}

/// The segment of a queued item, if it is one.
fn segment_mut(item: &mut StreamItem) -> Option<&mut Segment> {
    match item {
        Ok(Item::Segment(segment)) => Some(segment),
        _ => None,
    }
}

fn motion_mut(segment: &mut Segment) -> Option<&mut crate::motion::Move> {
    match &mut segment.kind {
        SegmentKind::Rapid { motion, .. }
        | SegmentKind::Line { motion, .. }
        | SegmentKind::Arc { motion, .. } => Some(motion),
        _ => None,
    }
}

/// The segment `kind` (a rapid or a line) moving along `motion` instead.
fn with_motion(kind: SegmentKind, motion: crate::motion::Move) -> SegmentKind {
    match kind {
        SegmentKind::Rapid { per_axis, .. } => SegmentKind::Rapid { motion, per_axis },
        SegmentKind::Line { feed, .. } => SegmentKind::Line { motion, feed },
        other => other,
    }
}

fn geometry_alarm(error: GeometryError, segment: &Segment, help: &'static str) -> Alarm {
    let message = match error {
        GeometryError::ArcSmallerThanTool {
            arc_radius,
            tool_radius,
        } => format!(
            "the arc's radius {arc_radius:.4} is not larger than the tool radius {tool_radius:.4} on its inside"
        ),
        GeometryError::NoIntersection | GeometryError::Interference => {
            "the compensated path would cut into the contour here (interference)".to_string()
        }
        GeometryError::ZeroLength => "a move of no length where compensation needs a direction".to_string(),
        GeometryError::Bottleneck => "bottleneck: the compensated path comes within the tool radius of an earlier block".to_string(),
    };
    Alarm::error(AlarmCode::CutterCompensation, segment.span, message).with_help(help)
}
