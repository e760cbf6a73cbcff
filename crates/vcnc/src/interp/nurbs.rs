//! G06.2 NURBS interpolation (Syntec spec 1.10, manual 000 L748-835): the blocks of a curve are
//! gathered, the curve is evaluated exactly (de Boor's algorithm on weighted points) and passed
//! on as straight chords that leave it by at most half the smoothing tolerance, each chord end on
//! the curve. The planner times them like any short lines, so the curve's time is its length
//! at the feed its limits allow.
//!
//! The blocks (L750-772): `G06.2 P_ K_ X_ Y_ Z_ R_ F_` starts the curve with its first knot and
//! control point, each following `K_ X_ Y_ Z_ R_` adds a knot and a control point, and `order`
//! blocks of K alone close it (the example: P3, three control points, six knots). P is the order
//! (2-4, default 4: L774), R the weight (0.001-1000, default 1: L780), X Y Z in G90 or G91
//! (incremental from the previous control point). The knot vector is clamped as the manual's U
//! (L802): its first and last `order` knots are equal, so the curve starts on its first control
//! point and ends on its last.
//!
//! Choices where the manual is silent: the first control point must be where the tool stands
//! (the curve starts there; elsewhere an alarm, as FANUC's G06.2 has); a block without K before
//! the curve is complete is an alarm (the curve would be lost); after the last knot the motion
//! mode in force before G06.2 goes on; G06.2 runs outside G05 as well.
//!
//! Control points are taken to machine coordinates as they are read: the frame chain is affine,
//! and a NURBS curve mapped point by point with its weights is the mapped curve.

use super::decode::Command;
use super::exec::Executor;
use super::kernel::{MoveModes, Origin};
use super::modal::DistanceMode;
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::machine::{Axis, AXES};
use crate::motion::Smoothing;
use crate::source::Span;

/// The orders the manual allows (L774).
const ORDERS: std::ops::RangeInclusive<usize> = 2..=4;

/// The order when P is not given (L774).
const DEFAULT_ORDER: usize = 4;

/// The weights the manual allows (L780).
const WEIGHTS: std::ops::RangeInclusive<f64> = 0.001..=1000.0;

/// Halvings of one knot span at most: 2^16 chords bound the work a tiny tolerance can ask for.
const MAX_DEPTH: u32 = 16;

/// The finest chord tolerance, mm: a tenth of a micrometre, below any control's resolution, so
/// that a zero tolerance in a machine file cannot ask for chords without end.
const FINEST_CHORD: f64 = 1e-4;

/// A curve being read, block by block.
#[derive(Clone, Debug)]
pub(crate) struct NurbsInput {
    origin: Origin,
    order: usize,
    order_span: Span,
    knots: Vec<f64>,
    points: Vec<[f64; 3]>,
    weights: Vec<f64>,
    /// The last control point in program coordinates, what G91 adds to.
    last_program: [f64; AXES],
}

/// A NURBS curve: order, clamped knot vector, control points and weights, as the manual's C(u).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Curve {
    order: usize,
    knots: Vec<f64>,
    /// Control points multiplied by their weights, with the weight last.
    weighted: Vec<[f64; 4]>,
}

/// Why a curve cannot be made (the message of [`AlarmCode::NurbsDefinition`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct CurveError(pub String);

impl Curve {
    /// The curve of `order` (degree + 1) over `knots` through the weighted `points`.
    ///
    /// # Errors
    /// An order outside 2-4, fewer points than the order, a number of knots other than points +
    /// order, knots that decrease or are not clamped, a weight outside 0.001-1000.
    pub(crate) fn new(
        order: usize,
        knots: &[f64],
        points: &[[f64; 3]],
        weights: &[f64],
    ) -> Result<Curve, CurveError> {
        let fail = |message: String| Err(CurveError(message));
        if !ORDERS.contains(&order) {
            return fail(format!("the NURBS order P{order} is outside P2 to P4"));
        }
        if points.len() < order {
            return fail(format!(
                "a curve of order {order} needs {order} control points at least, this one has {}",
                points.len()
            ));
        }
        if knots.len() != points.len() + order {
            return fail(format!(
                "{} control points of order {order} need {} knots, not {}",
                points.len(),
                points.len() + order,
                knots.len()
            ));
        }
        if knots.iter().any(|k| !k.is_finite()) || knots.windows(2).any(|w| w[1] < w[0]) {
            return fail("the knots must never decrease".to_string());
        }
        // The manual's U (L802): the first and the last knot `order` times each, no more, so
        // that the curve starts on its first control point and ends on its last.
        let runs: Vec<usize> = knots.chunk_by(|a, b| a == b).map(<[f64]>::len).collect();
        let ends_clamped = runs.len() >= 2 && runs[0] == order && runs[runs.len() - 1] == order;
        if !ends_clamped {
            return fail(format!(
                "the knots must start with exactly {order} equal values and end with {order} larger equal values (the manual's U)"
            ));
        }
        // An inner knot repeated `order` times breaks the curve in two (the manual is silent;
        // a tool path cannot jump): refused.
        if runs[1..runs.len() - 1].iter().any(|&run| run >= order) {
            return fail(format!(
                "an inner knot repeated {order} times breaks the curve: at most {} times",
                order - 1
            ));
        }
        if let Some(w) = weights.iter().find(|w| !WEIGHTS.contains(*w)) {
            return fail(format!("the weight R{w} is outside 0.001 to 1000"));
        }
        let weighted = points
            .iter()
            .zip(weights)
            .map(|(p, w)| [p[0] * w, p[1] * w, p[2] * w, *w])
            .collect();
        Ok(Curve {
            order,
            knots: knots.to_vec(),
            weighted,
        })
    }

    /// The parameter range, first knot to last.
    pub(crate) fn range(&self) -> (f64, f64) {
        (self.knots[0], self.knots[self.knots.len() - 1])
    }

    /// The point at parameter `u` (clamped to the range), by de Boor's algorithm on the weighted
    /// points, divided by the weight at the end.
    pub(crate) fn point(&self, u: f64) -> [f64; 3] {
        let (first, last) = self.range();
        let u = u.clamp(first, last);
        let p = self.order - 1;
        // The span k with knots[k] <= u < knots[k + 1]; at the last knot, the last span that
        // is not empty (the curve is closed at its end).
        let n = self.weighted.len();
        let k = (p..n)
            .rev()
            .find(|&k| self.knots[k] <= u && self.knots[k] < self.knots[k + 1])
            .unwrap_or(p);
        let mut d: Vec<[f64; 4]> = (0..=p).map(|j| self.weighted[j + k - p]).collect();
        for r in 1..=p {
            for j in (r..=p).rev() {
                let (a, b) = (self.knots[j + k - p], self.knots[j + 1 + k - r]);
                let alpha = if b > a { (u - a) / (b - a) } else { 0.0 };
                let previous = d[j - 1];
                for (c, before) in d[j].iter_mut().zip(previous) {
                    *c = (1.0 - alpha) * before + alpha * *c;
                }
            }
        }
        let h = d[p];
        [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
    }

    /// The parameters of chord ends that keep every chord within `tolerance` of the curve
    /// (checked at a quarter, half and three quarters of each chord's parameter interval),
    /// first and last knot included, every knot between them too.
    pub(crate) fn chord_parameters(&self, tolerance: f64) -> Vec<f64> {
        let mut out = vec![self.knots[0]];
        for w in self.knots.windows(2) {
            if w[1] > w[0] {
                self.split(w[0], w[1], tolerance, 0, &mut out);
            }
        }
        out
    }

    /// Adds the ends of the chords of `[a, b]` after `a` to `out`.
    fn split(&self, a: f64, b: f64, tolerance: f64, depth: u32, out: &mut Vec<f64>) {
        let (pa, pb) = (self.point(a), self.point(b));
        let within = [0.25, 0.5, 0.75]
            .iter()
            .all(|s| distance_to_segment(self.point(a + (b - a) * s), pa, pb) <= tolerance);
        if within || depth >= MAX_DEPTH {
            out.push(b);
        } else {
            let mid = 0.5 * (a + b);
            self.split(a, mid, tolerance, depth + 1, out);
            self.split(mid, b, tolerance, depth + 1, out);
        }
    }
}

/// The distance from `p` to the segment from `a` to `b`.
pub(crate) fn distance_to_segment(p: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let ab = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let ap = [p[0] - a[0], p[1] - a[1], p[2] - a[2]];
    let length2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
    let t = if length2 > 0.0 {
        ((ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) / length2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let d = [ap[0] - t * ab[0], ap[1] - t * ab[1], ap[2] - t * ab[2]];
    (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
}

/// Whether the block starts a curve or belongs to the one being read.
#[inline(always)]
pub(crate) fn takes(exec: &Executor, cmd: &Command) -> bool {
    exec.nurbs.is_some() || starts(cmd)
}

/// True when the block is a G06.2 block, the first of a curve.
#[inline(always)]
pub(crate) fn starts(cmd: &Command) -> bool {
    cmd.group(crate::profile::Group::Motion)
        .is_some_and(|g| g.code == crate::profile::GCode::Nurbs)
}

/// Runs a block of a NURBS curve: the G06.2 block, a control point, or a knot; the last knot
/// queues the curve's chords.
///
/// # Errors
/// [`AlarmCode::NurbsDefinition`] for a block the curve cannot take or a curve that cannot be
/// made; the feed's alarms; a position out of range.
#[cold]
pub(crate) fn block(exec: &mut Executor, cmd: &Command, out: &mut Output) -> Result<(), Alarm> {
    refuse_other_words(cmd)?;
    exec.set_feed(cmd)?;
    let k = cmd.word(b'K').ok_or_else(|| {
        let read = exec.nurbs.as_ref().map_or(0, |n| n.knots.len());
        bad(cmd.span, format!("a block of a NURBS curve without K: {read} knots were given, the curve is not complete"))
    })?;
    let mut input = match exec.nurbs.take() {
        Some(input) => input,
        None => Box::new(start(exec, cmd)?),
    };
    let has_point = cmd.has_axis_words() || cmd.r().is_some();
    if has_point {
        if input.knots.len() > input.points.len() {
            return Err(bad(
                cmd.span,
                "a control point after the knots-only blocks of a NURBS curve".to_string(),
            ));
        }
        add_point(exec, cmd, &mut input, out)?;
    } else if input.points.is_empty() {
        return Err(bad(
            cmd.span,
            "G06.2 needs the first control point (X Y Z) in its block".to_string(),
        ));
    }
    input.knots.push(k.number.value);
    if input.knots.len() < input.points.len() + input.order || has_point {
        exec.nurbs = Some(input);
        return Ok(());
    }
    run_curve(exec, &input, out)
}

/// The curve of a G06.2 block: its order, its origin.
fn start(exec: &mut Executor, cmd: &Command) -> Result<NurbsInput, Alarm> {
    let (order, order_span) = match cmd.p() {
        Some(p) if p.number.value.fract() == 0.0 && p.number.value >= 0.0 => {
            (p.number.value as usize, p.span)
        }
        Some(p) => {
            return Err(bad(
                p.span,
                "P, the NURBS order, is a whole number from 2 to 4".to_string(),
            ))
        }
        None => (DEFAULT_ORDER, cmd.span),
    };
    if !ORDERS.contains(&order) {
        return Err(bad(
            order_span,
            format!("the NURBS order P{order} is outside P2 to P4"),
        ));
    }
    // F is the curve's feed (L782); in G93 it would time each chord apart (and Syntec's
    // high-speed mode, which NURBS runs in, refuses G93: spec 1.8 restriction 14).
    if exec.modal.feed_mode == super::modal::FeedMode::InverseTime {
        return Err(bad(
            cmd.span,
            "G06.2 does not run in inverse time feed (G93)".to_string(),
        ));
    }
    Ok(NurbsInput {
        origin: Origin {
            span: cmd.span,
            sequence: cmd.sequence(),
        },
        order,
        order_span,
        knots: Vec::new(),
        points: Vec::new(),
        weights: Vec::new(),
        last_program: exec.kernel.program_position(),
    })
}

/// Reads a control point and its weight; the first must be where the tool stands.
fn add_point(
    exec: &mut Executor,
    cmd: &Command,
    input: &mut NurbsInput,
    out: &Output,
) -> Result<(), Alarm> {
    let mut program = input.last_program;
    let incremental = exec.modal.distance == DistanceMode::Incremental;
    for (i, letter) in [b'X', b'Y', b'Z'].into_iter().enumerate() {
        if let Some(value) = cmd.word_ref(letter) {
            let v = exec.length(value);
            program[i] = if incremental { program[i] + v } else { v };
        }
    }
    input.last_program = program;
    let moves_z = cmd.axis(Axis::Z.index()).is_some();
    let machine = exec.machine_target(&program, moves_z);
    let weight = cmd.r().map_or(1.0, |r| r.number.value);
    if !WEIGHTS.contains(&weight) {
        let span = cmd.r().map_or(cmd.span, |r| r.span);
        return Err(bad(
            span,
            format!("the weight R{weight} is outside 0.001 to 1000"),
        ));
    }
    if input.points.is_empty() {
        let here = exec.kernel.position;
        let away = (0..3).any(|i| (machine[i] - here[i]).abs() > 1e-6);
        if away || out.compensating() {
            return Err(bad(
                cmd.span,
                "the first control point of a NURBS curve must be where the tool stands"
                    .to_string(),
            )
            .with_help("move to the curve's start first, and cancel cutter compensation (G40)"));
        }
    }
    input.points.push([machine[0], machine[1], machine[2]]);
    input.weights.push(weight);
    Ok(())
}

/// Evaluates the curve read and queues its chords.
fn run_curve(exec: &mut Executor, input: &NurbsInput, out: &mut Output) -> Result<(), Alarm> {
    let curve =
        Curve::new(input.order, &input.knots, &input.points, &input.weights).map_err(|e| {
            bad(input.origin.span, e.0).with_label(input.order_span, "the curve starts here")
        })?;
    let tolerance = exec.modal.smoothing_for_motion().map_or(
        exec.kernel.setup.machine().planner.smoothing_tolerance,
        Smoothing::mm,
    );
    // Half the tolerance for the chords, half for the planner's blends of their corners: the
    // path stays within the tolerance of the curve.
    let half = (0.5 * tolerance).max(FINEST_CHORD);
    let modes = MoveModes {
        path_mode: exec.modal.path_mode,
        exact_stop: false,
        smoothing: Some(Smoothing::from_mm(half)),
    };
    let feed_mode = exec.modal.feed_mode;
    let mut target = exec.kernel.position;
    for u in curve.chord_parameters(half).into_iter().skip(1) {
        let p = curve.point(u);
        target[..3].copy_from_slice(&p);
        exec.kernel
            .feed_to(target, &input.origin, feed_mode, modes, out)?;
    }
    Ok(())
}

/// A NURBS block holds K, X Y Z, R, P, F and the codes of the groups that say how it reads
/// (motion, plane, distance, feed mode, units): anything else would be dropped unrun.
fn refuse_other_words(cmd: &Command) -> Result<(), Alarm> {
    use crate::profile::Group;
    let other_groups = [
        Group::NonModal,
        Group::CutterComp,
        Group::LengthComp,
        Group::Cycle,
        Group::CycleReturn,
        Group::Scaling,
        Group::ModalMacro,
        Group::SpindleMode,
        Group::WorkOffset,
        Group::PathMode,
        Group::Rotation,
        Group::Polar,
        Group::PolarInterpolation,
        Group::Mirror,
    ];
    let other_words = [b'I', b'J', b'H', b'D', b'L', b'Q', b'E']
        .iter()
        .any(|letter| cmd.word(*letter).is_some());
    if cmd.has_extra_axis_words()
        || other_words
        || cmd.has_auxiliary_words()
        || other_groups.iter().any(|g| cmd.group(*g).is_some())
    {
        return Err(bad(
            cmd.span,
            "a NURBS block takes K, X Y Z, R, P and F only (no other code, no rotary axis)"
                .to_string(),
        ));
    }
    Ok(())
}

fn bad(span: Span, message: String) -> Alarm {
    Alarm::error(AlarmCode::NurbsDefinition, span, message)
}
