//! The common CAM block run from its decoded words (`syntax/sinumerik/plain.rs`): G0, G1, G2 or
//! G3 with axis words, I J K or `CR=`, and F, while nothing else is pending: no corner held or
//! programmed, no frame written, no modal call, no diameter programming, the geometry axes of
//! power-on. Most blocks of a long CAM program are such
//! blocks; running them without making their words and sorting them by name is most of the
//! SINUMERIK front end's speed (issue 20).
//!
//! It does what [`block::run`](super::block) does with such a block, in the same order, calling
//! the same parts (`motion::prepare_plain`, `spindle::program_feed`, the compensation's
//! steps); a block it does not take runs the general way, from the words the line would have
//! been read into. The traces of the manual's examples and of the corpus, compared by
//! `vcnc-cli`'s traces test, are the check that both ways agree.
//!
//! Never: change anything before it knows it takes the block.

use super::axes::Positioning;
use super::block::{feed_mode, AxisValue};
use super::gcodes::{self, Function, Motion};
use super::language::AxisLookup;
use super::motion::{self, ArcWords};
use super::{compensation, diameter, dynamics, feed_source, spindle, toolholder, Sinumerik, Step};
use crate::alarm::Alarm;
use crate::interp::kernel::{Kernel, Origin};
use crate::machine::AXES;
use crate::motion::PathMode;
use crate::source::Span;
use crate::syntax::sinumerik::{PlainKind, PlainWords};

/// A plain block's words, sorted by what they do.
#[derive(Default)]
struct Decoded {
    motion: Option<Motion>,
    axes: [Option<AxisValue>; AXES],
    arc: ArcWords,
    feed: Option<(f64, Span)>,
}

/// Runs the block of `plain` (number `number`, at `span`) if it is one this path takes; None,
/// with nothing changed, if it must run the general way.
pub(super) fn run(
    front: &mut Sinumerik,
    kernel: &mut Kernel,
    plain: &PlainWords,
    number: Option<u32>,
    span: Span,
) -> Option<Result<Step, Alarm>> {
    if !front.frame_writes.is_empty()
        || front.angle_lines.is_open()
        || front.contour.is_holding()
        || front.rounding_modal
        || front.modal_call.is_some()
        || !diameter::is_off(front)
        || !front.geo_axes.as_at_power_on()
    {
        return None;
    }
    // Filled in place: returned through an Option it was copied a block.
    let mut decoded = Decoded::default();
    if !decode(front, plain, &mut decoded) {
        return None;
    }
    let motion = decoded.motion.unwrap_or(front.modal.motion);
    if !matches!(
        motion,
        Motion::Rapid | Motion::Line | Motion::Clockwise | Motion::CounterClockwise
    ) {
        return None;
    }
    let origin = Origin {
        span,
        sequence: number,
    };
    Some(run_decoded(front, kernel, &decoded, origin))
}

/// The words of `plain` sorted into `decoded` as `block::read` sorts them; false for a word
/// that read would take another way or reject (a letter that is no axis of the machine, a G
/// function that is no motion, a feed variable that is not a number).
fn decode(front: &Sinumerik, plain: &PlainWords, decoded: &mut Decoded) -> bool {
    for word in plain.words() {
        match word.kind {
            PlainKind::Letter(letter, number) => {
                let value = AxisValue {
                    value: number.value,
                    absolute: None,
                    diameter: None,
                };
                if let Some(axis) = front.axes.by_letter(letter) {
                    decoded.axes[axis] = Some(value);
                    continue;
                }
                match letter {
                    b'I' | b'J' | b'K' => {
                        decoded.arc.centre[usize::from(letter - b'I')] = Some(value);
                    }
                    b'F' => decoded.feed = Some((number.value, plain.span(word))),
                    b'G' => {
                        let g = number.value;
                        // Whole numbers below 100 only (`g as u32` truncates; f64::fract
                        // is a call of libm's trunc).
                        let common = ((0.0..100.0).contains(&g) && f64::from(g as u32) == g)
                            .then(|| gcodes::common(g as u32))
                            .flatten();
                        // A second motion is the general way's alarm.
                        match common {
                            Some((Function::Motion(m), _)) if decoded.motion.is_none() => {
                                decoded.motion = Some(m);
                            }
                            _ => return false,
                        }
                    }
                    _ => return false,
                }
            }
            // As `block::number` reads a literal: the evaluator's INT makes -0 a 0.
            PlainKind::Radius(value, negated) => {
                if front.axes.lookup("CR") != AxisLookup::NotAnAxis {
                    return false;
                }
                let value = if negated { 0.0 - value } else { value + 0.0 };
                decoded.arc.radius = Some((value, plain.span(word)));
            }
            // An axis named F would take `F=` (as `block::read` looks axes up first).
            PlainKind::Feed(..) | PlainKind::FeedName if front.axes.by_letter(b'F').is_some() => {
                return false;
            }
            PlainKind::Feed(value, negated) => {
                let value = if negated { 0.0 - value } else { value + 0.0 };
                decoded.feed = Some((value, plain.span(word)));
            }
            PlainKind::FeedName => {
                let value = plain
                    .feed_name()
                    .filter(|name| !matches!(*name, "TRUE" | "FALSE"))
                    .and_then(|name| front.vars.scalar(name)?.as_f64());
                let Some(value) = value else {
                    return false;
                };
                decoded.feed = Some((value, plain.span(word)));
            }
        }
    }
    true
}

/// `block::run`'s steps for a plain block.
fn run_decoded(
    front: &mut Sinumerik,
    kernel: &mut Kernel,
    decoded: &Decoded,
    origin: Origin,
) -> Result<Step, Alarm> {
    if let Some(motion) = decoded.motion {
        front.modal.motion = motion;
    }
    let prepared = motion::prepare_plain(front, &decoded.axes, &decoded.arc, origin)?;
    let moved = prepared.is_some();
    if moved {
        front.idle_blocks = 0;
    } else {
        front.idle_blocks += 1;
        if front.idle_blocks > 5 {
            front.flush_contour(kernel)?;
        }
    }
    let mode = feed_mode(front.modal.feed_type);
    if let Some((f, span)) = decoded.feed {
        spindle::program_feed(front, f, span)?;
        spindle::apply_feed(front, kernel, mode);
    }
    // A plain block has no positioning axes.
    let positioning = Positioning::new();
    dynamics::before_motion(front, kernel, &decoded.axes, &positioning, origin)?;
    feed_source::before_motion(front, kernel, &positioning, origin)?;
    toolholder::before_motion(front, kernel, origin);
    let path_mode = if front.modal.exact_stop {
        PathMode::ExactStop
    } else {
        PathMode::Continuous
    };
    kernel.set_path_mode(path_mode, false);
    let rapid = front.modal.motion == Motion::Rapid;
    let planner = &kernel.state().setup.machine().planner;
    kernel.set_smoothing(front.modal.path_control.smoothing(rapid, planner));
    compensation::before_motion(front, kernel, moved, origin.span)?;
    if let Some(direct) = &prepared {
        direct.make(front, kernel)?;
    }
    compensation::after_motion(front, kernel, origin)?;
    spindle::constant_rate(front, kernel, origin);
    spindle::restore_feed(front, kernel, mode);
    Ok(Step::Next)
}
