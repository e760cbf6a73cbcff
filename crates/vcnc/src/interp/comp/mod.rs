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
pub(crate) mod geometry;

use crate::alarm::{Alarm, AlarmCode};
use crate::machine::AXES;
use crate::motion::{ArcDirection, Item, MachinePos, Segment, SegmentKind, StreamItem};
use geometry::{Element, GeometryError, Side, V2};

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
        }
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
        let Some(element) = self.element(&segment) else {
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
            self.finish(items, held)?;
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
            .map_err(|e| geometry_alarm(e, &segment))?;
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
        let start = match self.pending.take() {
            Some(pending) => {
                let (a_end, links) = self.corner(&pending, &element, &segment, setting)?;
                self.emit(pending, a_end, items, held)?;
                (self.side, self.radius) = setting;
                self.links(a_end, &links, &segment, items);
                self.tool
            }
            None if start_up => {
                (self.side, self.radius) = setting;
                self.tool
            }
            None => {
                // After an end perpendicular to the last element: straight to this one's start.
                (self.side, self.radius) = setting;
                let start = geometry::start_up_end(&element, self.side, self.radius);
                let tool = self.tool;
                self.links(tool, &[start], &segment, items);
                start
            }
        };
        let provisional = geometry::perpendicular_end(&element, self.side, self.radius);
        debug_assert!(held.is_none(), "one pending element at a time");
        *held = Some(items.len());
        self.pending = Some(Pending {
            element,
            start,
            segment,
            start_up,
            provisional,
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
    ) -> Result<(V2, Vec<V2>), Alarm> {
        if pending.start_up {
            return Ok((geometry::start_up_end(next, side, radius), Vec::new()));
        }
        let corner = if side == self.side {
            geometry::corner(&pending.element, next, self.side, self.radius)
        } else {
            geometry::side_change(
                &pending.element,
                next,
                (self.side, self.radius),
                (side, radius),
            )
        }
        .map_err(|e| geometry_alarm(e, segment))?;
        Ok((corner.a_end, corner.links))
    }

    /// Writes the pending element's compensated segment at its place in the queue, ending at
    /// `end`, and moves what was held after it from the provisional point to `end`.
    ///
    /// # Errors
    /// Interference: the compensated element would run against the programmed one.
    fn emit(
        &mut self,
        pending: Pending,
        end: V2,
        items: &mut Vec<StreamItem>,
        held: &mut Option<usize>,
    ) -> Result<(), Alarm> {
        if !pending.start_up && geometry::interferes(&pending.element, pending.start, end) {
            return Err(geometry_alarm(
                GeometryError::Interference,
                &pending.segment,
            ));
        }
        let at = held.take().unwrap_or(items.len());
        let mut segment = pending.segment;
        if let Some(motion) = motion_mut(&mut segment) {
            set_plane(&mut motion.from.0, self.axes, pending.start);
            set_plane(&mut motion.to.0, self.axes, end);
        }
        for later in items[at..].iter_mut() {
            if let Some(motion) = segment_mut(later).and_then(motion_mut) {
                for point in [&mut motion.from.0, &mut motion.to.0] {
                    if plane_point(point, self.axes) == pending.provisional {
                        set_plane(point, self.axes, end);
                    }
                }
            }
        }
        items.insert(at, Ok(segment.into()));
        self.tool = end;
        Ok(())
    }

    /// The straight moves of an outer corner, as moves of the block that turns the corner.
    fn links(&mut self, from: V2, links: &[V2], segment: &Segment, items: &mut Vec<StreamItem>) {
        let mut here = from;
        for &point in links {
            if point.distance(here) < geometry::EPSILON {
                continue;
            }
            let mut link = *segment;
            let (a, b) = self.axes;
            if let Some(motion) = motion_mut(&mut link) {
                let mut to = motion.from.0;
                to[a] = point.x;
                to[b] = point.y;
                let mut start = motion.from.0;
                start[a] = here.x;
                start[b] = here.y;
                motion.from = MachinePos(start);
                motion.to = MachinePos(to);
            }
            let link = match link.kind {
                SegmentKind::Arc { motion, feed, .. } => Segment {
                    kind: SegmentKind::Line { motion, feed },
                    ..link
                },
                _ => link,
            };
            items.push(Ok(link.into()));
            here = point;
        }
        self.tool = here;
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
        match self.pending.take() {
            Some(pending) => {
                let end = pending.provisional;
                self.emit(pending, end, items, held)
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

fn geometry_alarm(error: GeometryError, segment: &Segment) -> Alarm {
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
    };
    Alarm::error(AlarmCode::CutterCompensation, segment.span, message)
        .with_help("FANUC alarms 033/041: a smaller tool, a larger radius or another path")
}
