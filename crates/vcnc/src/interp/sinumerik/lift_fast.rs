//! Fast retraction (PGsl 9.14, L6594-6747): LFON and LFOF, the retraction's length DILF=, its
//! plane LFTXT, LFWP or LFPOS and direction ALF=, and the absolute retraction positions POLF[axis]=
//! of the axes POLFMASK and POLFMLIN enable.
//!
//! The control retracts only on an NC stop, a reset or a fast input during G33, which a
//! simulation of the program never raises: the words are read and checked, their state is noted
//! once, and the program moves as written (issue 20's "accepted as state").
//!
//! Never: take a word the control refuses (ALF= outside 0 to 8 or not whole, a negative DILF=, an
//! axis the machine lacks).

use super::block::Words;
use super::predefined::{note_state, written};
use super::Sinumerik;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::kernel::Kernel;
use crate::syntax::sinumerik::{Value, Word};

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
