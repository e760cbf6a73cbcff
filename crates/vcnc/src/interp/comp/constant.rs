//! SINUMERIK's CUTCONON and CUTCONOF (sinumerik-part-b.md 2.7, seed 002 L7930-7986): the
//! compensation kept constant over blocks that run as programmed, shifted by the offset the
//! tool centre had where the last compensated element ended, and its return. Methods of
//! [`Compensator`].

use super::geometry::{self, Element, Link, Side, V2};
use super::transition::Approach;
use super::{motion_mut, plane_point, set_plane, Compensator};
use crate::alarm::Alarm;
use crate::machine::AXES;
use crate::motion::{Segment, SegmentKind, StreamItem};

impl Compensator {
    /// A move under CUTCONON: as programmed, shifted by the offset kept.
    pub(super) fn push_shifted(
        &mut self,
        mut segment: Segment,
        shift: V2,
        items: &mut Vec<StreamItem>,
    ) {
        if let Some(element) = self.element(&segment) {
            self.suppressed = Some(element);
            self.moved = true;
            self.idle_blocks = 0;
        }
        let axes = self.axes;
        let moved = |point: &mut [f64; AXES]| {
            let p = plane_point(point, axes) + shift;
            set_plane(point, axes, p);
        };
        if let SegmentKind::Arc { center, .. } = &mut segment.kind {
            moved(&mut center.0);
        }
        if let Some(motion) = motion_mut(&mut segment) {
            moved(&mut motion.from.0);
            moved(&mut motion.to.0);
            self.tool = plane_point(&motion.to.0, axes);
        }
        items.push(Ok(segment.into()));
    }

    /// How the tool centre goes from where it stands to `start`, the compensated start of
    /// `element`, after an end perpendicular to the last element: straight, or after CUTCONON
    /// with KONT round an outer corner on the circle about it (seed 002 L7960-7985).
    pub(super) fn rejoin(&mut self, element: &Element, start: V2) -> Link {
        let Some(last) = self.suppressed.take() else {
            return Link::Line(start);
        };
        let corner = element.start();
        let outer = matches!(
            geometry::turn(last.end_tangent(), element.start_tangent(), self.side),
            geometry::Turn::Outer | geometry::Turn::SharpOuter
        );
        if self.rules.approach == Approach::AroundPoint
            && outer
            && (self.tool.distance(corner) - self.radius).abs() < 1e-6
        {
            Link::Arc {
                to: start,
                center: corner,
                ccw: self.side == Side::Right,
            }
        } else {
            Link::Line(start)
        }
    }

    /// CUTCONON: the pending element ends perpendicular to itself, and the moves from here on
    /// go as programmed, shifted by the tool centre's offset there from `programmed`, the
    /// programmed point (plane axes).
    ///
    /// # Errors
    /// Interference at the pending element's end.
    pub(crate) fn keep_constant(
        &mut self,
        programmed: V2,
        items: &mut Vec<StreamItem>,
        held: &mut Option<usize>,
    ) -> Result<(), Alarm> {
        self.finish(items, held)?;
        self.constant = Some(self.tool - programmed);
        Ok(())
    }

    /// CUTCONOF: the next element is compensated again, joined from the shifted position.
    pub(crate) fn release_constant(&mut self) {
        self.constant = None;
    }
}
