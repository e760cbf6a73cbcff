//! The dynamic limits of an axis and the electronic gear (PGsl 14.7.2, L10555-10623;
//! docs/SINUMERIK.md 10.6): `VELOLIMA[ax]=`, `ACCLIMA[ax]=`, `JERKLIMA[ax]=` correct the
//! axis's velocity, acceleration and jerk to a percentage of the machine data's (the machine
//! file's), modal; `EGON(..)` and `EGOFS(..)` switch an electronic gear coupling on and off.
//!
//! A correction goes into the stream as an `AxisLimits` event before the block's motion, and
//! the planner times the motions after it with the corrected limits. The gear is kept as
//! state: what it would move is a following axis driven by its leading axes, which vcnc's one
//! path cannot make, so a block that moves a coupled axis (the follower or one of its leaders)
//! stops with V022.
//!
//! Never: move an axis the gear would move as though it were free, or accept a correction of an
//! axis the machine lacks.

use super::axes::Positioning;
use super::block::AxisValue;
use super::predefined::written;
use super::Sinumerik;
use crate::alarm::{Alarm, AlarmCode};
use crate::axis::Axis;
use crate::interp::kernel::{Kernel, Origin};
use crate::machine::AXES;
use crate::motion::SegmentKind;
use crate::syntax::sinumerik::{Expr, ExprKind, Value, Word};

/// The range of a correction, percent. The manual gives none (L10586: "a percentage"); vcnc
/// takes above 0 up to 200 (a choice: twice the machine data is far beyond any axis).
const PERCENT_RANGE: std::ops::RangeInclusive<f64> = 1e-6..=200.0;

/// The corrections and couplings in force.
#[derive(Clone, Debug)]
pub(super) struct Dynamics {
    /// Per axis: velocity, acceleration, jerk, percent of the machine file's.
    percent: [[f64; 3]; AXES],
    /// Axes whose correction changed in the block being read, for the stream.
    changed: [bool; AXES],
    /// Per following axis: its leading axes, while EGON is in force.
    gears: [Option<[bool; AXES]>; AXES],
}

impl Default for Dynamics {
    fn default() -> Dynamics {
        Dynamics {
            percent: [[100.0; 3]; AXES],
            changed: [false; AXES],
            gears: [None; AXES],
        }
    }
}

/// Reads VELOLIMA, ACCLIMA, JERKLIMA, EGON and EGOFS; false for other words.
pub(super) fn read_word(
    front: &mut Sinumerik,
    kernel: &Kernel,
    word: &Word,
) -> Result<bool, Alarm> {
    let address = &*word.address;
    let limit = match address {
        "VELOLIMA" => 0,
        "ACCLIMA" => 1,
        "JERKLIMA" => 2,
        "EGON" | "EGOFS" => {
            let Value::Call(arguments) = &word.value else {
                return Ok(false);
            };
            return gear(front, kernel, word, arguments).map(|()| true);
        }
        _ => return Ok(false),
    };
    let Value::Indexed(indices, Some(expr)) = &word.value else {
        return Err(Alarm::error(
            AlarmCode::MacroSyntax,
            word.span,
            format!("{address} corrects one axis: {address}[AX4]=50 (percent)"),
        ));
    };
    let [index] = indices.as_slice() else {
        return Err(Alarm::error(
            AlarmCode::MacroSyntax,
            word.span,
            format!("{address}[axis] takes one axis"),
        ));
    };
    let axis = super::axes::axis_of(front, kernel, index, word)?;
    let percent = front.value(kernel, expr)?;
    if !PERCENT_RANGE.contains(&percent) {
        return Err(Alarm::error(
            AlarmCode::ValueOutOfRange,
            word.span,
            format!(
                "{}: the correction is a percentage of the machine data, above 0 up to 200, not {percent}",
                written(word)
            ),
        ));
    }
    let dynamics = &mut front.dynamics;
    dynamics.percent[axis][limit] = percent;
    dynamics.changed[axis] = true;
    Ok(true)
}

/// EGON(FA, "mode", LA1, Z1, N1, ...) couples the following axis FA to its leading axes;
/// EGOFS(FA) ends it, EGOFS(FA, LA1, ...) ends the named leaders' part.
fn gear(
    front: &mut Sinumerik,
    kernel: &Kernel,
    word: &Word,
    arguments: &[Option<Expr>],
) -> Result<(), Alarm> {
    // The block change mode ("FINE") and the gear's numerators and denominators are no axes;
    // the axes are names, or variables holding one.
    let mut axes = Vec::new();
    for argument in arguments.iter().flatten() {
        if let ExprKind::Name(name) = &argument.kind {
            if !front.is_variable(name) || is_axis_variable(front, kernel, argument) {
                axes.push(argument);
            }
        }
    }
    let mut axes = axes.into_iter();
    let Some(following) = axes.next() else {
        return Err(Alarm::error(
            AlarmCode::MacroSyntax,
            word.span,
            format!(
                "{} names the following axis first: EGON(AX4,\"FINE\",X,1,2)",
                word.address
            ),
        ));
    };
    let following = super::axes::axis_of(front, kernel, following, word)?;
    let mut leaders = [false; AXES];
    for leader in axes {
        leaders[super::axes::axis_of(front, kernel, leader, word)?] = true;
    }
    let gear = &mut front.dynamics.gears[following];
    if &*word.address == "EGON" {
        if leaders == [false; AXES] {
            return Err(Alarm::error(
                AlarmCode::MacroSyntax,
                word.span,
                "EGON names the following axis and at least one leading axis: EGON(AX4,\"FINE\",X,1,2)",
            ));
        }
        *gear = Some(leaders);
        return Ok(());
    }
    // EGOFS with leaders ends their part of the coupling; alone, all of it. The Fundamentals
    // manual shows EGON only (L10609-10617): the selective form is vcnc's reading of the
    // electronic gear's own description (a choice, docs/SINUMERIK.md 10.5).
    *gear = match *gear {
        Some(mut left) if leaders != [false; AXES] => {
            for (kept, ended) in left.iter_mut().zip(leaders) {
                *kept &= !ended;
            }
            (left != [false; AXES]).then_some(left)
        }
        _ => None,
    };
    Ok(())
}

fn is_axis_variable(front: &mut Sinumerik, kernel: &Kernel, expr: &Expr) -> bool {
    matches!(
        front.evaluate(kernel, expr),
        Ok(super::value::Value::Axis(_))
    )
}

/// Before the block's motion: the corrections it made go into the stream; a block that moves a
/// coupled axis stops with V022.
#[inline]
pub(super) fn before_motion(
    front: &mut Sinumerik,
    kernel: &mut Kernel,
    axes: &[Option<AxisValue>; AXES],
    positioning: &Positioning,
    origin: Origin,
) -> Result<(), Alarm> {
    // The common block: no correction programmed, no gear in force.
    let dynamics = &front.dynamics;
    if !dynamics.changed.contains(&true) && dynamics.gears.iter().all(Option::is_none) {
        return Ok(());
    }
    announce_and_check(front, kernel, axes, positioning, origin)
}

/// [`before_motion`] for a block with corrections to announce or an axis coupled.
// Out of line: the check before it is inlined into every block's step.
#[inline(never)]
fn announce_and_check(
    front: &mut Sinumerik,
    kernel: &mut Kernel,
    axes: &[Option<AxisValue>; AXES],
    positioning: &Positioning,
    origin: Origin,
) -> Result<(), Alarm> {
    let dynamics = &mut front.dynamics;
    if dynamics.changed != [false; AXES] {
        for axis in Axis::ALL {
            if std::mem::take(&mut dynamics.changed[axis.index()]) {
                let [velocity, acceleration, jerk] =
                    dynamics.percent[axis.index()].map(|p| p / 100.0);
                let kind = SegmentKind::AxisLimits {
                    axis,
                    velocity,
                    acceleration,
                    jerk,
                };
                kernel.event(kind, origin);
            }
        }
    }
    if front.dynamics.gears == [None; AXES] {
        return Ok(());
    }
    let moved = |axis: usize| axes[axis].is_some() || positioning.iter().any(|&(a, _)| a == axis);
    for (following, gear) in front.dynamics.gears.iter().enumerate() {
        let Some(leaders) = gear else { continue };
        let driven = moved(following) || (0..AXES).any(|a| leaders[a] && moved(a));
        if driven {
            let name = front.axes.name(following);
            return Err(Alarm::error(
                AlarmCode::NotInProduct,
                origin.span,
                format!("this block moves {name}, coupled by EGON (an electronic gear): axis couplings are outside what vcnc simulates"),
            )
            .with_help(format!("end the coupling with EGOFS({name}) before moving its axes")));
        }
    }
    Ok(())
}
