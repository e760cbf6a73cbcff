//! Fast retraction (PGsl 9.14, L6594-6747): LFON and LFOF, the retraction's length DILF=, its
//! plane LFTXT, LFWP or LFPOS and direction ALF=, and the absolute retraction positions POLF[axis]=
//! of the axes POLFMASK and POLFMLIN enable.
//!
//! The control retracts only on an NC stop, a reset or a fast input during G33, which a
//! simulation of the program never raises: the words are read and checked, their state is noted
//! once, and the program moves as written (issue 20's "accepted as state"). So `$AC_LIFTFAST`,
//! the flag a retraction sets for the program to test (L6703, L6715), always reads 0, and a
//! program may reset it.
//!
//! Never: take a word the control refuses (ALF= outside 0 to 8 or not whole, a negative DILF=, an
//! axis the machine lacks).

use super::block::Words;
use super::predefined::{note_state, written};
use super::Sinumerik;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::kernel::Kernel;
use crate::source::Span;
use crate::syntax::sinumerik::{Value, Word};

/// The system variable a fast retraction sets.
pub(super) const FLAG: &str = "$AC_LIFTFAST";

/// `$AC_LIFTFAST`: 0, as no retraction ever happens in a run (an interrupted thread is what makes
/// the control set it).
pub(super) fn read_flag() -> super::value::Value {
    super::value::Value::Int(0)
}

/// A write of `$AC_LIFTFAST`: the program resets it to 0 before a thread (L6703), which it is
/// already.
///
/// # Errors
/// [`AlarmCode::ValueOutOfRange`] for another value: vcnc cannot say what the program means by a
/// retraction that did not happen (**choice**: the manual writes only the reset).
pub(super) fn write_flag(value: Option<f64>, span: Span) -> Result<(), Alarm> {
    if value == Some(0.0) {
        return Ok(());
    }
    Err(Alarm::error(
        AlarmCode::ValueOutOfRange,
        span,
        format!("{FLAG} can only be reset to 0: vcnc simulates no NC stop or fast input, so no fast retraction sets it"),
    ))
}

/// Reads DILF=, ALF=, POLF[axis]=, POLFMASK(..) and POLFMLIN(..); false for other words. The caller
/// has made sure no variable of the program has the word's name.
pub(super) fn read_word(
    front: &mut Sinumerik,
    kernel: &Kernel,
    word: &Word,
    words: &mut Words<'_>,
) -> Result<bool, Alarm> {
    let address = &*word.address;
    match (address, &word.value) {
        ("DILF" | "ALF", Value::Expression(expr)) => {
            let value = front.value(kernel, expr)?;
            let refused = if address == "ALF" {
                !(0.0..=8.0).contains(&value) || value.fract() != 0.0
            } else {
                value.is_nan() || value < 0.0
            };
            if refused {
                return Err(Alarm::error(
                    AlarmCode::ValueOutOfRange,
                    word.span,
                    format!(
                        "{}: {}",
                        written(word),
                        if address == "ALF" {
                            "the retraction's direction is a whole number 0 to 8 (45 degree steps)"
                        } else {
                            "the retraction's length cannot be negative"
                        }
                    ),
                ));
            }
        }
        ("POLF", Value::Indexed(indices, Some(expr))) => {
            let [axis] = indices.as_slice() else {
                return Err(Alarm::error(
                    AlarmCode::MacroSyntax,
                    word.span,
                    "POLF[axis] takes one axis",
                ));
            };
            super::axes::axis_of(front, kernel, axis, word)?;
            // `=IC(..)` is allowed (L6660): the value is only checked to be a number.
            let inner = match &expr.kind {
                crate::syntax::sinumerik::ExprKind::Call(name, arguments)
                    if matches!(&**name, "IC" | "AC") && arguments.len() == 1 =>
                {
                    arguments[0].as_ref().unwrap_or(expr)
                }
                _ => expr,
            };
            front.value(kernel, inner)?;
        }
        ("POLFMASK" | "POLFMLIN", Value::Call(arguments)) => {
            for argument in arguments.iter().flatten() {
                super::axes::axis_of(front, kernel, argument, word)?;
            }
        }
        _ => return Ok(false),
    }
    note_state(front, address, word, &mut words.warnings);
    Ok(true)
}
