//! G22/G23, the stored stroke check 2 (Syntec's "second software stroke limit", spec 1.16,
//! manual 000 L1149-1219): a zone of machine X, Y and Z that the tool must not enter (or, as the
//! machine says, not leave), switched on by G22 and off by G23, on top of the travel limits
//! (crate::checks, stroke limit 1).
//!
//! `G22 X_ Y_ Z_ I_ J_ K_` gives the limits in machine coordinates, X with I, Y with J, Z with K,
//! either of a pair the larger (L1194); an axis the block does not name takes the machine file's
//! `[stroke_check]` (the control's Pr2501-Pr2540), and a pair of equal values, or a parameter
//! pair whose maximum is not above its minimum, leaves the axis unprotected (L1195-1201, L1216). One
//! of a pair alone is COR-109. `forbidden` (Pr2542) says whether the inside or the outside of the
//! range is forbidden; `on_at_power_on` (Pr3838) whether the run starts in G22.
//!
//! Every move the blocks release while the check is on is checked along its path (lines and
//! rapids exactly, arcs through chords of a degree, whose sag is under 2e-4 of the radius): the
//! first that would enter the forbidden zone is left out and stops the program with V078 at its
//! block (the spec infers FANUC's check before the motion; the manual gives no alarm number). A
//! G22 takes effect from the block after it (L1215) and reset does not cancel it (L1214).

use super::decode::Command;
use super::exec::Executor;
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::machine::Axis;
use crate::motion::{Item, Move, Segment};
use crate::source::Span;
use serde::Deserialize;

/// Which side of the range is forbidden (Pr2542).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Forbidden {
    /// The tool must stay out of the range.
    #[default]
    Inside,
    /// The tool must stay inside the range.
    Outside,
}

/// One limit per axis of X, Y, Z, machine coordinates, mm; an axis left out is not protected.
#[derive(Clone, Copy, Debug, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AxisLimits {
    /// X, mm.
    pub x: Option<f64>,
    /// Y, mm.
    pub y: Option<f64>,
    /// Z, mm.
    pub z: Option<f64>,
}

impl AxisLimits {
    fn get(&self, i: usize) -> Option<f64> {
        [self.x, self.y, self.z][i]
    }
}

/// The machine file's `[stroke_check]`: the control's parameters of stored stroke check 2.
#[derive(Clone, Copy, Debug, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StrokeCheckConfig {
    /// The negative limits (Pr2501-Pr2540).
    #[serde(default)]
    pub min: AxisLimits,
    /// The positive limits.
    #[serde(default)]
    pub max: AxisLimits,
    /// Which side is forbidden (Pr2542).
    #[serde(default)]
    pub forbidden: Forbidden,
    /// The run starts in G22 (Pr3838).
    #[serde(default)]
    pub on_at_power_on: bool,
}

/// The zone in force: per axis the range, infinite for an axis not protected.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct StrokeZone {
    low: [f64; 3],
    high: [f64; 3],
    forbidden: Forbidden,
}

impl StrokeZone {
    /// The zone of the parameters alone (a bare `G22`, or the power-on state).
    pub(crate) fn from_parameters(config: &StrokeCheckConfig) -> StrokeZone {
        let mut zone = StrokeZone {
            low: [f64::NEG_INFINITY; 3],
            high: [f64::INFINITY; 3],
            forbidden: config.forbidden,
        };
        for i in 0..3 {
            if let (Some(low), Some(high)) = (config.min.get(i), config.max.get(i)) {
                if high > low {
                    (zone.low[i], zone.high[i]) = (low, high);
                }
            }
        }
        zone
    }

    /// The share of the way from `a` to `b` where the segment enters the forbidden zone (0
    /// when it starts there).
    fn entry(&self, a: [f64; 3], b: [f64; 3]) -> Option<f64> {
        match self.forbidden {
            Forbidden::Inside => crate::probe::box_entry(a, b, self.low, self.high),
            // The range is convex: a segment leaves it only if one of its ends is out.
            Forbidden::Outside => [(0.0, a), (1.0, b)]
                .into_iter()
                .find(|(_, p)| !(0..3).all(|i| self.low[i] <= p[i] && p[i] <= self.high[i]))
                .map(|(t, _)| t),
        }
    }

    /// Whether a move enters the zone along its path.
    fn entered_by(&self, segment: &Segment) -> bool {
        match segment.kind.path() {
            Some((motion, None)) => self.entry(motion.from.xyz(), motion.to.xyz()).is_some(),
            Some((motion, Some(arc))) => {
                let sweep = arc.sweep(motion);
                let points = arc_chords(motion, arc.center.xyz(), arc.direction, arc.plane, sweep);
                points.windows(2).any(|w| self.entry(w[0], w[1]).is_some())
            }
            None => false,
        }
    }
}

/// The chord ends of an arc, one a degree (at most 3600), start and end included.
fn arc_chords(
    motion: &Move,
    center: [f64; 3],
    direction: crate::motion::ArcDirection,
    plane: crate::motion::Plane,
    sweep: f64,
) -> Vec<[f64; 3]> {
    let (a, b, n) = plane.axes();
    let start = motion.from.xyz();
    let radius = (start[a] - center[a]).hypot(start[b] - center[b]);
    let start_angle = (start[b] - center[b]).atan2(start[a] - center[a]);
    let sign = match direction {
        crate::motion::ArcDirection::CounterClockwise => 1.0,
        crate::motion::ArcDirection::Clockwise => -1.0,
    };
    let steps = (sweep.to_degrees().ceil() as usize).clamp(1, 3600);
    let rise = motion.to.0[n] - start[n];
    (0..=steps)
        .map(|k| {
            let s = k as f64 / steps as f64;
            let angle = start_angle + sign * sweep * s;
            let mut p = start;
            p[a] = center[a] + radius * angle.cos();
            p[b] = center[b] + radius * angle.sin();
            p[n] = start[n] + rise * s;
            p
        })
        .collect()
}

/// G22: the zone of the block's pairs and the parameters, in force from the next block.
///
/// # Errors
/// [`AlarmCode::StrokeCheck`] (COR-109) for a limit without its pair.
pub(crate) fn g22(exec: &mut Executor, cmd: &Command, span: Span) -> Result<(), Alarm> {
    let config = exec.kernel.setup.machine().stroke_check;
    let mut zone = StrokeZone::from_parameters(&config);
    for (i, pair) in [b'I', b'J', b'K'].into_iter().enumerate() {
        let axis = [Axis::X, Axis::Y, Axis::Z][i];
        match (cmd.axis(axis.index()), cmd.word(pair)) {
            (Some(positive), Some(negative)) => {
                let (p, q) = (exec.length(&positive), exec.length(&negative));
                (zone.low[i], zone.high[i]) = if p == q {
                    (f64::NEG_INFINITY, f64::INFINITY)
                } else {
                    (p.min(q), p.max(q))
                };
            }
            (None, None) => {}
            (Some(one), None) | (None, Some(one)) => {
                return Err(Alarm::error(
                    AlarmCode::StrokeCheck,
                    one.span,
                    "G22 needs both limits of an axis: X with I, Y with J, Z with K",
                )
                .with_label(span, "stored stroke check 2")
                .with_help("Syntec alarm COR-109: G22 command error, activation failed"));
            }
        }
    }
    exec.stroke_zone = Some(zone);
    Ok(())
}

/// G23: the check off.
pub(crate) fn g23(exec: &mut Executor) {
    exec.stroke_zone = None;
}

/// Checks the moves released from `from` on in `out`; the first that enters the zone is left
/// out with what follows it, and its alarm comes back.
///
/// # Errors
/// [`AlarmCode::StrokeCheck`] for a move into the forbidden zone.
pub(crate) fn check_released(
    zone: &StrokeZone,
    out: &mut Output,
    from: usize,
) -> Result<(), Alarm> {
    let start = from.min(out.items.len());
    let found = out.items[start..]
        .iter()
        .position(|item| matches!(item, Ok(Item::Segment(segment)) if zone.entered_by(segment)));
    let Some(offset) = found else {
        return Ok(());
    };
    let index = start + offset;
    let span = crate::motion::segment_of(&out.items[index]).map(|s| s.span);
    out.items.truncate(index);
    if out.held.is_some_and(|held| held > index) {
        out.held = Some(index);
    }
    let side = match zone.forbidden {
        Forbidden::Inside => "enters",
        Forbidden::Outside => "leaves",
    };
    Err(Alarm::error(
        AlarmCode::StrokeCheck,
        span.unwrap_or_default(),
        format!("the move {side} the range of stored stroke check 2 (G22)"),
    ))
}
