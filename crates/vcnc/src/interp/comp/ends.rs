//! The compensator's SINUMERIK ends of a contour: where the first or last element is too short
//! for the tool (G461, G462: `extension.rs`), the smooth retraction (G148, G248, G348:
//! `smooth.rs`) and the KONTC/KONTT curves (`polynomial.rs`), as moves in the compensator's
//! queue. Methods of [`Compensator`]; its look-ahead and corners stay in `mod.rs`.

use super::geometry::{Element, V2};
use super::{
    extension, motion_mut, plane_point, polynomial, segment_mut, set_plane, smooth, with_motion,
    Compensator, Pending,
};
use crate::alarm::Alarm;
use crate::machine::AXES;
use crate::motion::{MachinePos, Segment, SegmentKind, StreamItem};

impl Compensator {
    /// G461/G462 at the approach: the contour's first element is skipped, and the start-up
    /// block, held before it, ends at `point` instead, where the next element starts.
    pub(super) fn skip_first(
        &mut self,
        pending: Pending,
        point: V2,
        items: &mut Vec<StreamItem>,
        held: &mut Option<usize>,
    ) {
        let at = held.take().unwrap_or(items.len());
        for later in items[at..].iter_mut() {
            if let Some(motion) = segment_mut(later).and_then(motion_mut) {
                for p in [&mut motion.from.0, &mut motion.to.0] {
                    let here = plane_point(p, self.axes);
                    if here == pending.start || here == pending.provisional {
                        set_plane(p, self.axes, point);
                    }
                }
            }
        }
        if let Some(skipped) = self.skipped(pending.segment, point) {
            items.insert((at + pending.place).min(items.len()), Ok(skipped.into()));
        }
        self.tool = point;
    }

    /// A skipped element's move, standing at `point` in the plane: what it moves of the other
    /// axes, or nothing.
    fn skipped(&self, mut segment: Segment, point: V2) -> Option<Segment> {
        let motion = motion_mut(&mut segment)?;
        set_plane(&mut motion.from.0, self.axes, point);
        set_plane(&mut motion.to.0, self.axes, point);
        if motion.from == motion.to {
            return None;
        }
        let motion = *motion;
        segment.kind = match segment.kind {
            SegmentKind::Arc { feed, .. } => SegmentKind::Line { motion, feed },
            kind => kind,
        };
        Some(segment)
    }

    /// G461/G462 at the retraction: the element kept in doubt ends the contour. The pending
    /// element ends where the doubtful one, produced beyond its end, meets it, and the doubtful
    /// one is skipped. Without a G40 block, or without such a point, its alarm.
    ///
    /// # Errors
    /// The kept alarm (SINUMERIK 10751); interference of the pending element.
    pub(super) fn resolve_doubt(
        &mut self,
        items: &mut Vec<StreamItem>,
        held: &mut Option<usize>,
    ) -> Result<(), Alarm> {
        let Some(doubt) = self.doubt.take() else {
            return Ok(());
        };
        let point = match &self.pending {
            Some(pending) if self.cancelling => extension::extended_end(
                self.rules.extension,
                &pending.element,
                &doubt.element,
                (self.side, self.radius),
            ),
            _ => None,
        };
        let (Some(point), Some(pending)) = (point, self.pending.take()) else {
            return Err(doubt.alarm);
        };
        let hold = held.unwrap_or(items.len());
        let before = items.len();
        self.emit(pending, point, items, held)?;
        if let Some(skipped) = self.skipped(doubt.segment, point) {
            let place = (hold + doubt.place + items.len() - before).min(items.len());
            items.insert(place, Ok(skipped.into()));
        }
        Ok(())
    }

    /// The cancelling block's smooth retraction: the last element ends perpendicular to itself
    /// (P4), and the block's `segment` (from there to its programmed end P0, at the contour's
    /// level) becomes the retraction's moves. Without a segment (a block that moved nothing),
    /// nothing but the end.
    ///
    /// # Errors
    /// Interference at the last element's end.
    pub(super) fn retract_smoothly(
        &mut self,
        retraction: &smooth::Approach,
        segment: Option<Segment>,
        items: &mut Vec<StreamItem>,
        held: &mut Option<usize>,
    ) -> Result<(), Alarm> {
        let last = self.pending.as_ref().map(|pending| {
            let feed = match pending.segment.kind {
                SegmentKind::Line { feed, .. } | SegmentKind::Arc { feed, .. } => Some(feed),
                _ => None,
            };
            (pending.element.end_tangent(), feed)
        });
        self.finish(items, held)?;
        let Some(mut segment) = segment else {
            return Ok(());
        };
        let Some(motion) = motion_mut(&mut segment) else {
            return Ok(());
        };
        set_plane(&mut motion.from.0, self.axes, self.tool);
        let end = plane_point(&motion.to.0, self.axes);
        // Without a last element (G461/G462 skipped it, or none came), straight to P0.
        let moves = match last {
            Some((tangent, feed)) => smooth::retraction_moves(
                retraction,
                &segment,
                (self.tool, tangent),
                (self.side, self.radius),
                self.plane(),
                feed,
            ),
            None => vec![segment],
        };
        items.extend(moves.into_iter().map(|s| Ok(s.into())));
        self.tool = end;
        Ok(())
    }

    /// The cancelling block under KONTC or KONTT: the last element ends perpendicular to
    /// itself, and the block leaves it on the polynomial to its programmed end.
    ///
    /// # Errors
    /// Interference at the last element's end.
    pub(super) fn retract_on_curve(
        &mut self,
        continuity: polynomial::Continuity,
        mut segment: Segment,
        items: &mut Vec<StreamItem>,
        held: &mut Option<usize>,
    ) -> Result<(), Alarm> {
        let last = self.pending.as_ref().map(|pending| {
            let setting = (self.side, self.radius);
            let element = pending.element;
            let curvature = match element {
                // The compensated arc's curvature is the same all along.
                Element::Arc { .. } => polynomial::curvature(&element, setting),
                Element::Line { .. } => 0.0,
            };
            (element.end_tangent(), curvature)
        });
        self.finish(items, held)?;
        let Some(motion) = motion_mut(&mut segment) else {
            return Ok(());
        };
        set_plane(&mut motion.from.0, self.axes, self.tool);
        self.tool = plane_point(&motion.to.0, self.axes);
        let moves = match last {
            Some(leaving) => curve_pieces(&segment, |ends| {
                polynomial::retraction(continuity, ends, self.axes, leaving)
            }),
            None => vec![segment],
        };
        items.extend(moves.into_iter().map(|s| Ok(s.into())));
        Ok(())
    }
}

/// The straight pieces of a curve that replaces `segment`, from its start to its end: `points`
/// gives their ends from the segment's two ends.
pub(super) fn curve_pieces(
    segment: &Segment,
    points: impl FnOnce(([f64; AXES], [f64; AXES])) -> Vec<[f64; AXES]>,
) -> Vec<Segment> {
    let Some(motion) = segment.motion() else {
        return vec![*segment];
    };
    let mut here = motion.from.0;
    points((motion.from.0, motion.to.0))
        .into_iter()
        .map(|to| {
            let mut piece = *motion;
            piece.from = MachinePos(here);
            piece.to = MachinePos(to);
            here = to;
            let kind = match segment.kind {
                SegmentKind::Arc { feed, .. } => SegmentKind::Line {
                    motion: piece,
                    feed,
                },
                kind => with_motion(kind, piece),
            };
            Segment { kind, ..*segment }
        })
        .collect()
}
