//! Checks over the motion stream: what the control watches while the axes move, downstream of
//! the interpreter (DESIGN: consumers).
//!
//! [`TravelLimits`] is the control's stored stroke limit 1: no axis may go beyond the machine's
//! travel, the `min` and `max` of each axis in the machine file, in machine coordinates. A
//! line or a rapid stays inside if its end does (a straight move between two points inside a
//! box stays inside it; a per-axis rapid moves each axis between its two ends too); an arc
//! also through its extremes in the plane. The first move that would leave the travel becomes
//! an [`AlarmCode::Overtravel`] alarm at its block and the stream ends there: the control stops
//! the axes at the limit (FANUC OT0500/OT0501). Checking before the move, vcnc leaves the
//! move out: the position stays at the block's start. [`TravelCheck`] is the same check for a
//! consumer that takes the stream in batches, or for the interpreter to run after every block
//! ([`ReleasedCheck`]). This module never depends on the interpreter.

use crate::alarm::{Alarm, AlarmCode};
use crate::machine::{Axis, AxisName, Machine, AXES};
use crate::motion::{
    arc_sweep, for_arc_extreme_points, ArcDirection, Item, MachinePos, Move, Plane, Segment,
    SegmentKind, StreamItem,
};

/// Slack for rounding, mm: a move ending on its limit is inside.
const SLACK: f64 = 1e-6;

/// The travel check over a stream of segments (an iterator adapter; see the module doc).
pub struct TravelLimits<I> {
    source: I,
    check: TravelCheck,
}

/// The travel check itself, for a consumer that takes the stream in batches.
#[derive(Clone, Debug)]
pub struct TravelCheck {
    limits: Limits,
    stopped: bool,
    /// The machine has X, Y and Z and no other axis: a move's other three coordinates have no
    /// travel to leave, and only three are compared.
    xyz_only: bool,
}

/// Each axis's travel with the slack added, infinite for an axis the machine does not have:
/// one comparison per axis and bound, no branch on the axes' presence in the common case.
#[derive(Clone, Copy, Debug)]
struct Limits {
    low: [f64; AXES],
    high: [f64; AXES],
    /// The axes' names, for the alarm.
    names: [AxisName; AXES],
}

impl<I> TravelLimits<I> {
    /// Checks `source` against the travel of `machine`'s axes.
    pub fn new(source: I, machine: &Machine) -> TravelLimits<I> {
        TravelLimits {
            source,
            check: TravelCheck::new(machine),
        }
    }

    /// The stream being checked.
    pub fn source(&self) -> &I {
        &self.source
    }
}

impl<I: Iterator<Item = StreamItem>> Iterator for TravelLimits<I> {
    type Item = StreamItem;

    fn next(&mut self) -> Option<Self::Item> {
        if self.check.stopped {
            return None;
        }
        let item = self.source.next()?;
        if let Ok(Item::Segment(segment)) = &item {
            let limits = &self.check.limits;
            let alarm = if self.check.xyz_only {
                limits.check::<3>(segment)
            } else {
                limits.check::<AXES>(segment)
            };
            if let Some(alarm) = alarm {
                self.check.stopped = true;
                return Some(Err(alarm));
            }
        }
        Some(item)
    }
}

impl TravelCheck {
    /// The check of `machine`'s travel.
    pub fn new(machine: &Machine) -> TravelCheck {
        TravelCheck {
            limits: Limits {
                low: std::array::from_fn(|i| {
                    machine.axes[i]
                        .as_ref()
                        .map_or(f64::NEG_INFINITY, |a| a.min - SLACK)
                }),
                high: std::array::from_fn(|i| {
                    machine.axes[i]
                        .as_ref()
                        .map_or(f64::INFINITY, |a| a.max + SLACK)
                }),
                names: Axis::ALL.map(|axis| machine.layout.name(axis)),
            },
            stopped: false,
            xyz_only: (0..AXES).all(|i| machine.axes[i].is_some() == (i < 3)),
        }
    }

    /// Checks the next batch of the stream in place: the first segment that leaves the
    /// travel is replaced by its alarm and the rest of the batch dropped. Returns false once
    /// the stream has stopped (and empties every later batch).
    pub fn check_batch(&mut self, batch: &mut Vec<StreamItem>) -> bool {
        let all = 0..batch.len();
        if self.xyz_only {
            self.check_items::<3>(batch, all)
        } else {
            self.check_items::<AXES>(batch, all)
        }
    }

    /// [`TravelCheck::check_batch`] for the items in `range` of `items` alone (the ones before
    /// it have passed; the ones after are not final yet): at the first that leaves the travel,
    /// `items` is cut and its alarm added.
    /// Only the first `N` coordinates are compared: the machine has no other axis.
    #[inline(always)]
    fn check_items<const N: usize>(
        &mut self,
        items: &mut Vec<StreamItem>,
        range: std::ops::Range<usize>,
    ) -> bool {
        if self.stopped {
            items.truncate(range.start);
            return false;
        }
        let limits = &self.limits;
        let start = range.start;
        let failed = items[range].iter().enumerate().find_map(|(i, item)| {
            // A line inside the travel, most of a stream, is recognised by its own tag, the
            // whole item's: matched through the result and then the kind, every segment paid
            // for decoding the kind's tag from the niche of the result's.
            if let Ok(Item::Segment(Segment {
                kind: SegmentKind::Line { motion, .. },
                ..
            })) = item
            {
                if limits.inside::<N>(&motion.to.0) {
                    return None;
                }
            }
            match item {
                Ok(Item::Segment(segment)) => {
                    limits.check::<N>(segment).map(|alarm| (start + i, alarm))
                }
                Ok(Item::Frame(_) | Item::Warning(_)) | Err(_) => None,
            }
        });
        if let Some((at, alarm)) = failed {
            items.truncate(at);
            items.push(Err(alarm));
            self.stopped = true;
        }
        !self.stopped
    }
}

/// A check of the stream's items as the blocks release them, made by the interpreter's caller
/// and run by the interpreter after every block
/// ([`Interpreter::next_batch_checked`](crate::Interpreter::next_batch_checked)): the check
/// belongs to the consumer's side, and the interpreter knows it only by this trait.
pub trait ReleasedCheck {
    /// Looks at the items in the range `released` of `items` (the ones before it have passed;
    /// the ones after it are held by compensation and may still change) and, to stop the
    /// program at one of them, cuts `items` there, adds its alarm and returns false.
    fn check_released(
        &mut self,
        items: &mut Vec<StreamItem>,
        released: std::ops::Range<usize>,
    ) -> bool;
}

/// The travel checked block by block as the interpreter runs (inlined into its loop).
impl ReleasedCheck for TravelCheck {
    #[inline(always)]
    fn check_released(
        &mut self,
        items: &mut Vec<StreamItem>,
        released: std::ops::Range<usize>,
    ) -> bool {
        if self.xyz_only {
            self.check_items::<3>(items, released)
        } else {
            self.check_items::<AXES>(items, released)
        }
    }
}

impl Limits {
    /// The overtravel alarm of `segment`, if it leaves the travel of its first `N` axes (the
    /// others are not the machine's).
    #[inline(always)]
    fn check<const N: usize>(&self, segment: &Segment) -> Option<Alarm> {
        // Lines first (most of a stream), then one `match` on the kind: rapids, like lines, need
        // only their end.
        if let SegmentKind::Line { motion, .. } = &segment.kind {
            if self.inside::<N>(&motion.to.0) {
                return None;
            }
            return Some(self.alarm(segment, &motion.to.0));
        }
        let (motion, arc) = match &segment.kind {
            SegmentKind::Rapid { motion, .. } | SegmentKind::Line { motion, .. } => (motion, None),
            SegmentKind::Arc {
                motion,
                center,
                direction,
                plane,
                extra_turns,
                ..
            } => (motion, Some((center, *direction, *plane, *extra_turns))),
            _ => return None,
        };
        if !self.inside::<N>(&motion.to.0) {
            return Some(self.alarm(segment, &motion.to.0));
        }
        let (center, direction, plane, extra_turns) = arc?;
        if self.circle_inside(motion, center, plane) {
            return None;
        }
        self.arc_extremes_alarm(segment, motion, center, direction, plane, extra_turns)
    }

    /// The overtravel alarm of an arc whose circle leaves the travel, if a point of the arc
    /// itself does (kept out of line: most arcs stay well inside).
    #[inline(never)]
    fn arc_extremes_alarm(
        &self,
        segment: &Segment,
        motion: &Move,
        center: &MachinePos,
        direction: ArcDirection,
        plane: Plane,
        extra_turns: u32,
    ) -> Option<Alarm> {
        let sweep = arc_sweep(motion, center, direction, plane, extra_turns);
        let mut found = None;
        for_arc_extreme_points(motion, center.xyz(), direction, plane, sweep, |p| {
            let mut point = motion.to.0;
            point[..3].copy_from_slice(&p);
            if found.is_none() && !self.inside::<AXES>(&point) {
                found = Some(self.alarm(segment, &point));
            }
        });
        found
    }

    /// True when each of the first `N` coordinates of `point` is within its axis's travel
    /// (NaN is not).
    #[inline(always)]
    fn inside<const N: usize>(&self, point: &[f64; AXES]) -> bool {
        // Every axis compared, without a branch per axis: the comparisons go two by two in
        // vector instructions, and this runs for every move of the stream.
        (0..N.min(AXES)).fold(true, |inside, i| {
            inside & (point[i] >= self.low[i]) & (point[i] <= self.high[i])
        })
    }

    /// True when the arc's whole circle lies inside the travel in its plane: then no point of
    /// it can leave, and its extremes need no angles (most arcs).
    fn circle_inside(&self, motion: &Move, center: &MachinePos, plane: Plane) -> bool {
        let (a, b, _) = plane.axes();
        // An upper bound of the radius is all this test needs: a circle found inside with it is
        // inside, and the others get the exact test of their extremes.
        let radius = radius_bound(
            motion.from.0[a] - center.0[a],
            motion.from.0[b] - center.0[b],
        );
        [a, b]
            .iter()
            .all(|&i| center.0[i] - radius >= self.low[i] && center.0[i] + radius <= self.high[i])
    }

    /// The alarm for `point`, which lies beyond the travel of one of its axes.
    #[cold]
    fn alarm(&self, segment: &Segment, point: &[f64; AXES]) -> Alarm {
        let i = (0..AXES)
            .find(|&i| point[i] < self.low[i] || point[i] > self.high[i])
            .unwrap_or(0);
        let value = point[i];
        let (side, limit) = if value > self.high[i] {
            ("+", self.high[i] - SLACK)
        } else {
            ("-", self.low[i] + SLACK)
        };
        let letter = self.names[i];
        Alarm::error(
            AlarmCode::Overtravel,
            segment.span,
            format!(
                "{side}{letter} overtravel: the move takes {letter} to {value:.3}, \
                 beyond the machine's travel limit {limit:.3} (machine coordinates)"
            ),
        )
        .with_help(format!(
            "the machine file gives the travel ([axes.{}] min and max); FANUC stops with \
             OT0500/OT0501 (stored stroke limit 1)",
            letter.as_str().to_ascii_lowercase()
        ))
    }
}

/// A number at least the length of the vector (x, y), and within a millionth of a micrometre of
/// it on a machine's scale. The square root of the sum of squares is within a few units in the
/// last place of the length (and several times cheaper than `hypot`); the factor puts it above,
/// and the tiny term covers squares too small for a double.
#[allow(clippy::imprecise_flops)]
#[inline(always)]
fn radius_bound(x: f64, y: f64) -> f64 {
    (x * x + y * y).sqrt() * (1.0 + 1e-12) + 1e-150
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{interpret_str, Options};

    fn checked(program: &str) -> Vec<StreamItem> {
        let machine = Machine::default();
        TravelLimits::new(
            interpret_str(program, &machine, Options::default()),
            &machine,
        )
        .collect()
    }

    #[test]
    fn a_move_beyond_the_travel_stops_the_stream_at_its_block() {
        // The default machine: X Y Z from -1000 to 1000.
        let items = checked("G90 G00 X900.\nG01 X1000. F1000.\nX1000.5\nX0\nM30\n");
        // The frame of the first move, the two moves, the alarm.
        assert_eq!(items.len(), 4, "{items:?}");
        assert!(matches!(items[0], Ok(Item::Frame(_))));
        assert!(items[2].is_ok(), "a move that ends on the limit is inside");
        let alarm = items[3].as_ref().unwrap_err();
        assert_eq!(alarm.code, AlarmCode::Overtravel);
        assert_eq!(alarm.span.unwrap().line, 3);
        assert!(
            alarm.message.starts_with("+X overtravel"),
            "{}",
            alarm.message
        );
    }

    #[test]
    fn an_arc_is_checked_through_its_extremes() {
        // A half circle of radius 5 about X900 Y-5 ends and stays inside; one of radius 20
        // about X990 Y0, clockwise from the top, passes X1010 on its way to the bottom.
        let inside = checked("G90 G00 X900.\nG02 X900. Y-10. J-5. F500.\nM30\n");
        assert!(inside.iter().all(Result::is_ok), "{inside:?}");
        let bulging = checked("G90 G00 X990. Y20.\nG02 X990. Y-20. J-20. F500.\nM30\n");
        let alarm = bulging.last().unwrap().as_ref().unwrap_err();
        assert_eq!(alarm.code, AlarmCode::Overtravel);
        assert_eq!(alarm.span.unwrap().line, 2);
    }

    proptest::proptest! {
        #[test]
        fn the_radius_bound_is_never_below_the_radius(
            x in -1.0e4..1.0e4f64, y in -1.0e4..1.0e4f64, scale in -200i32..200,
        ) {
            let factor = 10f64.powi(scale);
            let (x, y) = (x * factor, y * factor);
            let (bound, exact) = (radius_bound(x, y), x.hypot(y));
            proptest::prop_assert!(bound >= exact, "{x} {y}: {bound}");
            // Squares beyond what a double holds make the bound infinite: the circle then gets
            // the exact test.
            if bound.is_finite() {
                proptest::prop_assert!(bound - exact <= 2e-12 * exact + 1e-149, "{x} {y}: {bound}");
            }
        }
    }

    proptest::proptest! {
        #[test]
        fn a_checked_batch_is_the_checked_stream(
            moves in proptest::collection::vec(
                (0..3u8, -1003.0..1003.0f64, -1003.0..1003.0f64, -2.0..2.0f64),
                1..12,
            ),
        ) {
            // Lines, rapids and arcs whose ends and bulges fall on both sides of the default
            // machine's travel (-1000 to 1000 on X, Y and Z).
            let mut program = String::from("G90 G17 F1000.\n");
            for (kind, x, y, bulge) in moves {
                let code = ["G00", "G01", "G02"][usize::from(kind)];
                let radius = if kind == 2 { format!(" R{:.3}", 1500.0 + bulge) } else { String::new() };
                program.push_str(&format!("{code} X{x:.3} Y{y:.3}{radius}\n"));
            }
            program.push_str("M30\n");
            let machine = Machine::default();
            let mut batch: Vec<_> =
                interpret_str(&program, &machine, Options::default()).collect();
            let check = TravelCheck::new(&machine);
            proptest::prop_assert!(check.xyz_only);
            // The three-axis comparison the default machine gets against all six.
            let mut six_axes = TravelCheck { xyz_only: false, ..check.clone() };
            let mut compared_on_six = batch.clone();
            six_axes.check_batch(&mut compared_on_six);
            check.clone().check_batch(&mut batch);
            proptest::prop_assert_eq!(&batch, &compared_on_six, "{}", program);
            proptest::prop_assert_eq!(batch, checked(&program), "{}", program);
        }
    }

    #[test]
    fn a_rotary_axis_is_checked_on_a_machine_that_has_one() {
        // With an A axis the check compares every coordinate, not only X, Y and Z.
        let text = format!(
            "{}\n[axes.a]\nmin = -10.0\nmax = 10.0\nrapid = 3600.0\nmax_feed = 3600.0\nacceleration = 2000.0\njerk = 50000.0\n",
            crate::machine::DEFAULT_MACHINE_TOML
        );
        let machine = Machine::from_toml(&text).unwrap();
        let mut check = TravelCheck::new(&machine);
        assert!(!check.xyz_only);
        let mut batch: Vec<_> =
            interpret_str("G90 G00 A5.\nG00 A20.\nM30\n", &machine, Options::default()).collect();
        assert!(!check.check_batch(&mut batch));
        assert_eq!(batch.len(), 3, "the frame, the move, the alarm: {batch:?}");
        let alarm = batch[2].as_ref().unwrap_err();
        assert_eq!(alarm.code, AlarmCode::Overtravel);
        assert!(alarm.message.contains('A'), "{}", alarm.message);
    }

    #[test]
    fn a_batch_is_cut_at_the_first_move_beyond_the_travel() {
        let machine = Machine::default();
        let mut batch: Vec<_> = interpret_str(
            "G90 G00 Z-999.\nZ-1001.\nZ0\nM30\n",
            &machine,
            Options::default(),
        )
        .collect();
        let mut check = TravelCheck::new(&machine);
        assert!(!check.check_batch(&mut batch));
        assert_eq!(batch.len(), 3, "the frame, the move, the alarm: {batch:?}");
        assert!(batch[1].is_ok());
        assert!(batch[2]
            .as_ref()
            .unwrap_err()
            .message
            .starts_with("-Z overtravel"));
        let mut more = vec![Ok(batch[1].clone().unwrap())];
        assert!(!check.check_batch(&mut more));
        assert!(more.is_empty(), "nothing after the stop");
    }
}
