//! Revolutional feeds derived from another spindle or a rotary axis, and the handwheel's feed
//! of a positioning axis (PGsl 7.5, L3169-3311; 7.8, L3443-3593; docs/SINUMERIK.md 10.6):
//! `FPR(..)` names what G95 feeds of the path are per, `FPRAON(..)`/`FPRAOF(..)` switch a
//! positioning axis's or a spindle's FA to a feed per revolution, `FDA[ax]=` is the
//! handwheel's feed of a positioning axis for one block.
//!
//! The derived feed is the programmed feed times the source's speed (L3250-3253). A spindle's
//! speed is its programmed S; a rotary axis's is its FA (deg/min) over 360: vcnc's rotary
//! axes turn only when a block moves them, so the speed FPR reads is the one the axis moves
//! at when positioned (a choice, docs/SINUMERIK.md 10.6). The kernel makes the path's feeds
//! with the source's speed ([`Kernel::set_revolution_speed`]), so the stream's per-revolution
//! feeds carry it and the planner times them with it.
//!
//! Never: derive a feed from a spindle or an axis the machine lacks, or from a linear axis.

use super::axes::Positioning;
use super::predefined::written;
use super::Sinumerik;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::kernel::{Kernel, Origin};
use crate::machine::AXES;
use crate::syntax::sinumerik::{Expr, ExprKind, Value, Word};

/// What a feed per revolution is per.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Source {
    /// Spindle n (1 is the master spindle).
    Spindle(u32),
    /// A rotary axis, by slot.
    Axis(usize),
}

/// A spindle or an axis, as FPRAON's first argument names it.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Driven {
    Spindle(u32),
    Axis(usize),
}

/// The sources in force.
#[derive(Clone, Debug, Default)]
pub(super) struct FeedSources {
    /// FPR: the path's G95 source (None: the master spindle).
    path: Option<Source>,
    /// FPRAON: the positioning axes and spindles whose FA is per revolution, and of what.
    derived: Vec<(Driven, Source)>,
    /// The speed last given to the kernel (None: the spindle's).
    applied: Option<f64>,
    /// FDA of the block being read, and of the block running: the handwheel's feed per axis.
    handwheel_read: [Option<f64>; AXES],
    handwheel: [Option<f64>; AXES],
}

/// Reads FPR, FPRAON, FPRAOF and FDA; false for other words.
pub(super) fn read_word(
    front: &mut Sinumerik,
    kernel: &Kernel,
    word: &Word,
) -> Result<bool, Alarm> {
    match (&*word.address, &word.value) {
        ("FPR", Value::Call(arguments)) => {
            let [Some(source)] = arguments.as_slice() else {
                return Err(syntax(
                    word,
                    "FPR names one rotary axis or spindle: FPR(A), FPR(S2)",
                ));
            };
            let source = source_of(front, kernel, source, word)?;
            front.feed_sources.path = (source != Source::Spindle(1)).then_some(source);
        }
        ("FPRAON", Value::Call(arguments)) => {
            let (driven, source) = match arguments.as_slice() {
                [Some(driven)] => (driven, Source::Spindle(1)),
                [Some(driven), Some(source)] => (driven, source_of(front, kernel, source, word)?),
                _ => {
                    return Err(syntax(
                        word,
                        "FPRAON names the axis or spindle and its source: FPRAON(X), FPRAON(S1,S2)",
                    ))
                }
            };
            let driven = driven_of(front, kernel, driven, word)?;
            let sources = &mut front.feed_sources.derived;
            sources.retain(|(d, _)| *d != driven);
            sources.push((driven, source));
        }
        ("FPRAOF", Value::Call(arguments)) => {
            for argument in arguments.iter().flatten() {
                let driven = driven_of(front, kernel, argument, word)?;
                front.feed_sources.derived.retain(|(d, _)| *d != driven);
            }
        }
        ("FDA", Value::Indexed(indices, Some(expr))) => {
            let [index] = indices.as_slice() else {
                return Err(syntax(word, "FDA[axis] takes one axis"));
            };
            let axis = super::axes::axis_of(front, kernel, index, word)?;
            let feed = front.value(kernel, expr)?;
            if feed < 0.0 {
                return Err(Alarm::error(
                    AlarmCode::BadFeedRate,
                    word.span,
                    format!("{}: the handwheel's feed cannot be negative", written(word)),
                ));
            }
            front.feed_sources.handwheel_read[axis] = Some(feed);
        }
        _ => return Ok(false),
    }
    Ok(true)
}

fn syntax(word: &Word, message: &str) -> Alarm {
    Alarm::error(AlarmCode::MacroSyntax, word.span, message.to_string())
}

/// A spindle named `S<n>` or `SPI(<n>)`, if `expr` names one.
fn spindle_number(
    front: &mut Sinumerik,
    kernel: &Kernel,
    expr: &Expr,
) -> Result<Option<f64>, Alarm> {
    Ok(match &expr.kind {
        ExprKind::Name(name) if !front.is_variable(name) => name
            .strip_prefix('S')
            .filter(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
            .and_then(|n| n.parse().ok()),
        ExprKind::Call(name, arguments) if &**name == "SPI" => match arguments.as_slice() {
            [Some(n)] => Some(front.value(kernel, n)?),
            _ => None,
        },
        _ => None,
    })
}

/// FPR's and FPRAON's source: a spindle of the machine or a rotary axis.
fn source_of(
    front: &mut Sinumerik,
    kernel: &Kernel,
    expr: &Expr,
    word: &Word,
) -> Result<Source, Alarm> {
    if let Some(n) = spindle_number(front, kernel, expr)? {
        return Ok(Source::Spindle(front.spindles.check(n, word)?));
    }
    let axis = super::axes::axis_of(front, kernel, expr, word)?;
    if !front.axes.rotary()[axis] {
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            word.span,
            format!(
                "{}: a feed per revolution is derived from a rotary axis or a spindle, and {} is linear",
                word.address,
                front.axes.name(axis)
            ),
        ));
    }
    Ok(Source::Axis(axis))
}

/// FPRAON's and FPRAOF's axis or spindle.
fn driven_of(
    front: &mut Sinumerik,
    kernel: &Kernel,
    expr: &Expr,
    word: &Word,
) -> Result<Driven, Alarm> {
    if let Some(n) = spindle_number(front, kernel, expr)? {
        return Ok(Driven::Spindle(front.spindles.check(n, word)?));
    }
    Ok(Driven::Axis(super::axes::axis_of(
        front, kernel, expr, word,
    )?))
}

/// The source's speed now, rev/min (0 when it stands still or was never given a speed).
fn speed(front: &Sinumerik, kernel: &Kernel, source: Source) -> f64 {
    match source {
        Source::Spindle(1) => kernel.state().spindle.speed(),
        Source::Spindle(n) => front.spindles.programmed_speed(n),
        Source::Axis(axis) => front.axis_feeds.positioning_feed(axis).unwrap_or(0.0) / 360.0,
    }
}

/// Before the block's motion: the path's G95 feeds take the FPR source's speed as it is now,
/// and the block's FDA words come into force (the last block's go).
///
/// # Errors
/// FDA without a positioning word of its axis in the block.
#[inline]
pub(super) fn before_motion(
    front: &mut Sinumerik,
    kernel: &mut Kernel,
    positioning: &Positioning,
    origin: Origin,
) -> Result<(), Alarm> {
    let sources = &front.feed_sources;
    // The common block: no source but the master spindle, no FDA.
    // (`iter().all`: comparing with `[None; AXES]` compares each value too.)
    if sources.path.is_none()
        && sources.applied.is_none()
        && sources.handwheel_read.iter().all(Option::is_none)
        && sources.handwheel.iter().all(Option::is_none)
    {
        return Ok(());
    }
    apply(front, kernel, positioning, origin)
}

/// [`before_motion`] for a block with another feed source or FDA words.
// Out of line: the check before it is inlined into every block's step.
#[inline(never)]
fn apply(
    front: &mut Sinumerik,
    kernel: &mut Kernel,
    positioning: &Positioning,
    origin: Origin,
) -> Result<(), Alarm> {
    let sources = &mut front.feed_sources;
    sources.handwheel = std::mem::take(&mut sources.handwheel_read);
    for (axis, feed) in sources.handwheel.iter().enumerate() {
        if feed.is_some() && !positioning.iter().any(|&(a, _)| a == axis) {
            let name = front.axes.name(axis);
            return Err(Alarm::error(
                AlarmCode::WordNotAllowed,
                origin.span,
                format!("FDA[{name}] is the feed of a positioning axis: it needs POS[{name}] in its block"),
            ));
        }
    }
    let rpm = front
        .feed_sources
        .path
        .map(|source| speed(front, kernel, source));
    if rpm != front.feed_sources.applied {
        front.feed_sources.applied = rpm;
        kernel.set_revolution_speed(rpm);
    }
    Ok(())
}

/// The feed a positioning axis moves at, mm/min or deg/min: FDA of its block (the handwheel's,
/// which vcnc has not: FDA=0 moves at the axis's FA, with a note), else its FA, per
/// revolution of its source under FPRAON. None: at its rapid rate.
pub(super) fn positioning_feed(
    front: &mut Sinumerik,
    kernel: &mut Kernel,
    axis: usize,
    origin: Origin,
) -> Option<f64> {
    let fa = front.axis_feeds.positioning_feed(axis);
    match front.feed_sources.handwheel[axis] {
        Some(feed) if feed > 0.0 => return Some(feed),
        Some(_) => kernel.warn(Alarm::warning(
            AlarmCode::KeptAsState,
            origin.span,
            format!(
                "FDA[{}]=0: the operator's handwheel moves the axis towards its target; vcnc, without a handwheel, moves it there at its positioning feed",
                front.axes.name(axis)
            ),
        )),
        None => {}
    }
    let source = front
        .feed_sources
        .derived
        .iter()
        .find(|(d, _)| *d == Driven::Axis(axis))
        .map(|&(_, source)| source);
    match source {
        None => fa,
        // A stopped source gives no feed: the axis is timed at its rapid rate, as the path's
        // G95 without a speed is timed at the axes' limits.
        Some(source) => fa
            .map(|fa| fa * speed(front, kernel, source))
            .filter(|&feed| feed > 0.0),
    }
}
