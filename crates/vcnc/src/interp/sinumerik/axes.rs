//! Axes beyond the path's geometry (PGsl 7.1, 7.2; docs/SINUMERIK.md 10): the feed group that
//! decides which axes make the path feed (FGROUP, FGREF, FL, and F of rotary axes under G700),
//! and positioning axes that move at their own feed (POS, POSA, FA, WAITP).
//!
//! The kernel's planner measures a move along X Y Z (a rotary-only move in degrees). When the
//! control measures it otherwise, [`scale_feed`] gives the kernel the feed that takes the
//! control's time over the planner's length; positioning axes make a move of their own
//! ([`position`]), after the block's path (the stream has one path).
//!
//! Never: change the feed of a move the default group measures as the planner does, or let
//! a positioning word move an axis the machine file does not declare.

use super::block::{AxisValue, Words};
use super::language::AxisLookup;
use super::motion::unit;
use super::predefined::written;
use super::Sinumerik;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::kernel::{Kernel, Origin};
use crate::interp::modal::FeedMode;
use crate::machine::AXES;
use crate::motion::{ArcDirection, Plane};
use crate::syntax::sinumerik::{Expr, ExprKind, Value, Word};

/// FGREF's value at power-on: 1 degree is 1 mm (PGsl 7.1, L2636-2655).
const DEFAULT_REFERENCE_RADIUS: f64 = 180.0 / std::f64::consts::PI;

/// The feed group and the positioning axes' feeds, modal.
#[derive(Clone, Debug, Default)]
pub(super) struct AxisFeeds {
    /// FGROUP: the axes whose travel is the path (None: the geometry axes X Y Z).
    group: Option<[bool; AXES]>,
    /// FGREF per rotary axis, mm (None: the default, 1 degree = 1 mm).
    reference_radius: [Option<f64>; AXES],
    /// FL per axis: the speed limit, mm/min or deg/min.
    limit: [Option<f64>; AXES],
    /// FA per axis: the positioning feed, mm/min or deg/min.
    positioning_feed: [Option<f64>; AXES],
}

impl AxisFeeds {
    /// FA of `axis`: its positioning feed, mm/min or deg/min.
    pub(super) fn positioning_feed(&self, axis: usize) -> Option<f64> {
        self.positioning_feed[axis]
    }
}

/// POS and POSA of a block: the axis and its value.
pub(super) type Positioning = Vec<(usize, AxisValue)>;

/// Reads FGROUP, FGREF, FL, FA, POS, POSA and WAITP; false for other words. The caller has made
/// sure no variable of the program has the word's name.
pub(super) fn read_word(
    front: &mut Sinumerik,
    kernel: &Kernel,
    word: &Word,
    words: &mut Words<'_>,
) -> Result<bool, Alarm> {
    let address = &*word.address;
    match (address, &word.value) {
        // FGROUP alone, as FGROUP(), brings back the geometry axes.
        ("FGROUP", Value::Bare) => front.axis_feeds.group = None,
        ("FGROUP", Value::Call(arguments)) => {
            let mut group = [false; AXES];
            for argument in arguments.iter().flatten() {
                group[axis_of(front, kernel, argument, word)?] = true;
            }
            // FGROUP() brings back the geometry axes (L2581-2590).
            let default = [true, true, true, false, false, false];
            front.axis_feeds.group = (group != default && group != [false; AXES]).then_some(group);
        }
        ("FGREF" | "FL" | "FA" | "POS" | "POSA", Value::Indexed(indices, Some(expr))) => {
            let [index] = indices.as_slice() else {
                return Err(Alarm::error(
                    AlarmCode::MacroSyntax,
                    word.span,
                    format!("{address}[axis] takes one axis"),
                ));
            };
            let axis = axis_of(front, kernel, index, word)?;
            let feeds = if front.modal.inch && front.modal.inch_feeds && !front.axes.rotary()[axis]
            {
                25.4
            } else {
                1.0
            };
            match address {
                // In the unit of G70/G71/G700/G710 (L2633).
                "FGREF" => {
                    let radius = front.value(kernel, expr)? * unit(front);
                    front.axis_feeds.reference_radius[axis] = Some(radius);
                }
                // In the unit of F: G700 makes it inch/min (L2592-2608).
                // Assigning the machine data's limit deselects FL (L2566-2569): the axis is
                // then limited by its own speed, as before any FL.
                "FL" if matches!(&expr.kind, ExprKind::Index(name, _) if &**name == "$MA_AX_VELO_LIMIT") =>
                {
                    front.axis_feeds.limit[axis] = None;
                }
                "FL" => {
                    let limit = positive(front.value(kernel, expr)?, word)? * feeds;
                    front.axis_feeds.limit[axis] = Some(limit);
                }
                "FA" => {
                    let feed = positive(front.value(kernel, expr)?, word)? * feeds;
                    front.axis_feeds.positioning_feed[axis] = Some(feed);
                }
                _ => words
                    .positioning
                    .push((axis, axis_value(front, kernel, expr)?)),
            }
        }
        ("WAITP", Value::Call(arguments)) => {
            // vcnc's positioning moves end before the next block starts: nothing to wait for.
            for argument in arguments.iter().flatten() {
                axis_of(front, kernel, argument, word)?;
            }
        }
        _ => return Ok(false),
    }
    Ok(true)
}

/// The axis an index or argument names, on the machine: an axis name, or an AXIS variable
/// holding one (PGsl 1.3, axis variables stand for the axis they hold).
pub(super) fn axis_of(
    front: &mut Sinumerik,
    kernel: &Kernel,
    expr: &Expr,
    word: &Word,
) -> Result<usize, Alarm> {
    let held;
    let name = match &expr.kind {
        ExprKind::Name(name) if front.is_variable(name) => {
            held = match front.evaluate(kernel, expr)? {
                super::value::Value::Axis(name) => name.to_string(),
                _ => String::from("?"),
            };
            held.as_str()
        }
        ExprKind::Name(name) => &**name,
        _ => "?",
    };
    match front.axes.lookup(name) {
        AxisLookup::Present(axis) => Ok(axis),
        AxisLookup::Absent | AxisLookup::NotAnAxis => Err(Alarm::error(
            AlarmCode::AxisNotOnMachine,
            word.span,
            format!("{}: the machine has no axis {name}", written(word)),
        )
        .with_help(format!(
            "add the axis to the machine file (`[axes.{}]`)",
            name.to_ascii_lowercase()
        ))),
    }
}

fn positive(value: f64, word: &Word) -> Result<f64, Alarm> {
    if value < 0.0 {
        return Err(Alarm::error(
            AlarmCode::BadFeedRate,
            word.span,
            format!(
                "{}: a feed or speed limit cannot be negative",
                written(word)
            ),
        ));
    }
    Ok(value)
}

/// A positioning value, with `AC(..)`, `IC(..)` (and DC, ACP, ACN: absolute, as on the path;
/// DAC, DIC, RAC, RIC: `diameter.rs`).
fn axis_value(front: &mut Sinumerik, kernel: &Kernel, expr: &Expr) -> Result<AxisValue, Alarm> {
    if let ExprKind::Call(name, args) = &expr.kind {
        let form = super::diameter::value_form(name);
        if let (Some((absolute, diameter)), [Some(arg)]) = (form, args.as_slice()) {
            return Ok(AxisValue {
                value: front.value(kernel, arg)?,
                absolute: Some(absolute),
                diameter,
            });
        }
    }
    Ok(AxisValue {
        value: front.value(kernel, expr)?,
        absolute: None,
        diameter: None,
    })
}

/// POS and POSA: the positioning axes go to their positions in one move of their own, after
/// the block's path, each at its FA (without FA at its rapid rate); the move takes as long as
/// the slowest axis needs. The block waits for it (POS) and so does POSA's (vcnc has one path:
/// the control would overlap POSA with the blocks up to WAITP; docs/SINUMERIK.md 10.2).
pub(super) fn position(
    front: &mut Sinumerik,
    kernel: &mut Kernel,
    words: &Words<'_>,
    origin: Origin,
) -> Result<(), Alarm> {
    let positioning = &words.positioning;
    if positioning.is_empty() {
        return Ok(());
    }
    // An axis is either a path axis or a positioning axis of a block (PGsl 7.2).
    if let Some(&(axis, _)) = positioning
        .iter()
        .find(|(axis, _)| words.axes[*axis].is_some())
    {
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            origin.span,
            format!(
                "{} is a path axis and a positioning axis (POS, POSA) in one block",
                front.axes.name(axis)
            ),
        )
        .with_help("move the axis either on the path or with POS/POSA"));
    }
    // A block held for its corner moves first: the positioning word ends the contour.
    front.flush_contour(kernel)?;
    let start = kernel.program_position();
    let mut target = [None; AXES];
    let mut minutes = 0.0_f64;
    let mut any_feed = false;
    for &(axis, value) in positioning {
        let scale = front.axes.scale(axis, unit(front));
        let to = if value.absolute.unwrap_or(front.modal.absolute) {
            value.value * scale
        } else {
            front.programmed[axis] + value.value * scale
        };
        front.programmed[axis] = to;
        target[axis] = Some(to);
        let rapid = kernel.state().setup.machine().axes[axis]
            .as_ref()
            .map_or(f64::INFINITY, |a| a.rapid);
        let speed = match super::feed_source::positioning_feed(front, kernel, axis, origin) {
            Some(feed) if feed > 0.0 => {
                any_feed = true;
                feed
            }
            _ => rapid,
        };
        minutes = minutes.max((to - start[axis]).abs() / speed);
    }
    if !any_feed {
        return kernel.rapid_to(target, origin);
    }
    let length = planner_length(&start, &target, None);
    if minutes <= 0.0 || length <= 0.0 {
        return Ok(());
    }
    let saved = kernel.feed_setting();
    kernel.set_feed_in(FeedMode::PerMinute, Some(length / minutes));
    let moved = kernel.feed_to(target, origin);
    kernel.set_feed_in(saved.0, saved.1);
    moved
}

/// The arc of a move, for its length in the plane.
#[derive(Clone, Copy, Debug)]
pub(super) struct ArcShape {
    pub(super) plane: Plane,
    pub(super) centre: (f64, f64),
    pub(super) direction: ArcDirection,
    pub(super) turns: u32,
}

/// The length of the arc's part in its plane and the travel of each axis (the plane's two axes
/// get the arc's length as one).
fn travels(
    start: &[f64; AXES],
    target: &[Option<f64>; AXES],
    arc: Option<ArcShape>,
) -> ([f64; AXES], Option<f64>) {
    let delta: [f64; AXES] = std::array::from_fn(|i| target[i].map_or(0.0, |t| t - start[i]));
    let Some(arc) = arc else {
        return (delta, None);
    };
    let (a, b, _) = arc.plane.axes();
    let (ca, cb) = arc.centre;
    let radius = (start[a] - ca).hypot(start[b] - cb);
    let begin = (start[b] - cb).atan2(start[a] - ca);
    let end_a = target[a].unwrap_or(start[a]);
    let end_b = target[b].unwrap_or(start[b]);
    let end = (end_b - cb).atan2(end_a - ca);
    let tau = std::f64::consts::TAU;
    let mut sweep = match arc.direction {
        ArcDirection::CounterClockwise => (end - begin).rem_euclid(tau),
        ArcDirection::Clockwise => (begin - end).rem_euclid(tau),
    };
    if sweep < 1e-9 {
        sweep = tau;
    }
    sweep += tau * f64::from(arc.turns);
    (delta, Some(radius * sweep))
}

/// The length the planner measures: along X Y Z, or in degrees when only rotary axes move.
fn planner_length(start: &[f64; AXES], target: &[Option<f64>; AXES], arc: Option<ArcShape>) -> f64 {
    let (delta, in_plane) = travels(start, target, arc);
    let linear = match (in_plane, arc) {
        (Some(s), Some(arc)) => {
            let (_, _, normal) = arc.plane.axes();
            s.hypot(delta[normal])
        }
        _ => (delta[0] * delta[0] + delta[1] * delta[1] + delta[2] * delta[2]).sqrt(),
    };
    if linear > 1e-9 {
        linear
    } else {
        delta[3..].iter().map(|d| d * d).sum::<f64>().sqrt()
    }
}

/// The feed a cutting move to `target` gets so that the planner's length takes the control's
/// time (PGsl 7.1): the path measured along the FGROUP axes (rotary ones through FGREF), F in
/// deg/min when only rotary axes of the group move with their default FGREF, and no axis
/// beyond its FL. Sets it and returns the feed to restore; None when the planner's own
/// measure is the control's.
pub(super) fn scale_feed(
    front: &Sinumerik,
    kernel: &mut Kernel,
    target: &[Option<f64>; AXES],
    arc: Option<ArcShape>,
) -> Option<(FeedMode, Option<f64>)> {
    let feeds = &front.axis_feeds;
    let inch_feeds = front.modal.inch && front.modal.inch_feeds;
    let default_group = feeds.group.is_none() && feeds.limit.iter().all(Option::is_none);
    if default_group && !inch_feeds {
        return None;
    }
    let (mode, Some(feed)) = kernel.feed_setting() else {
        return None;
    };
    if mode == FeedMode::InverseTime || feed <= 0.0 {
        return None;
    }
    let start = kernel.program_position();
    let (delta, in_plane) = travels(&start, target, arc);
    // Under G700 the default group differs from the planner's measure only for rotary axes
    // alone.
    if default_group && (in_plane.is_some() || delta[..3].iter().any(|d| d.abs() > 1e-12)) {
        return None;
    }
    let plane_axes = arc.map(|arc| {
        let (a, b, _) = arc.plane.axes();
        (a, b)
    });
    let in_arc_plane = |i: usize| plane_axes.is_some_and(|(a, b)| i == a || i == b);
    let moves = |i: usize| delta[i].abs() > 1e-12 || in_arc_plane(i);
    let group = feeds
        .group
        .unwrap_or([true, true, true, false, false, false]);
    let moving: Vec<usize> = (0..AXES).filter(|&i| moves(i) && group[i]).collect();
    let rotary = *front.axes.rotary();
    let linear_moves = moving.iter().any(|&i| !rotary[i]);
    let default_radius = |i: usize| {
        feeds.reference_radius[i]
            .is_none_or(|r| (r - DEFAULT_REFERENCE_RADIUS).abs() < 1e-6 * DEFAULT_REFERENCE_RADIUS)
    };
    // The control's path length and the factor of F to its unit.
    let (length, factor) = if moving.is_empty() {
        // No axis of the group moves: the block's axes make the path as the geometry axes
        // would (vcnc's choice; the manual is silent). F of a rotary-only move is deg/min.
        let rotary_only = (0..AXES).all(|i| rotary[i] || !moves(i));
        let planner = planner_length(&start, target, arc);
        (
            planner,
            if rotary_only && inch_feeds {
                1.0 / 25.4
            } else {
                1.0
            },
        )
    } else if !linear_moves && moving.iter().all(|&i| default_radius(i)) {
        // Only rotary axes of the group, their FGREF the default: F is deg/min (L2656-2689).
        let degrees = moving.iter().map(|&i| delta[i] * delta[i]).sum::<f64>();
        (degrees.sqrt(), if inch_feeds { 1.0 / 25.4 } else { 1.0 })
    } else {
        let mut squares = 0.0;
        if let (Some(s), true) = (in_plane, moving.iter().any(|&i| in_arc_plane(i))) {
            // One of the plane's axes in the group counts the whole arc (vcnc's choice).
            squares += s * s;
        }
        for &i in moving.iter().filter(|&&i| !in_arc_plane(i)) {
            let travel = if !rotary[i] {
                delta[i]
            } else {
                let radius = feeds.reference_radius[i].unwrap_or(DEFAULT_REFERENCE_RADIUS);
                delta[i].to_radians() * radius
            };
            squares += travel * travel;
        }
        (squares.sqrt(), 1.0)
    };
    let mut time = length / (feed * factor);
    // FL: no axis faster than its limit (per minute: under G94 only, vcnc's choice).
    if mode == FeedMode::PerMinute {
        for i in (0..AXES).filter(|&i| !in_arc_plane(i)) {
            if let Some(limit) = feeds.limit[i].filter(|l| *l > 0.0) {
                time = time.max(delta[i].abs() / limit);
            }
        }
    }
    let planner = planner_length(&start, target, arc);
    if time <= 0.0 || planner <= 0.0 || !time.is_finite() {
        return None;
    }
    let saved = kernel.feed_setting();
    kernel.set_feed_in(mode, Some(planner / time));
    Some(saved)
}
