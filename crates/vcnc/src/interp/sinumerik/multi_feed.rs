//! Several feeds in one block (PGsl 7.10, L3658-3750): `F2=` to `F7=` path feeds, `ST=` a dwell
//! and `SR=` a return path, and per axis `FMA[bit, axis]=`, `STA[axis]=`, `SRA[axis]=`, each
//! taking over when its digital input comes on during the block's motion.
//!
//! They are one-block values. vcnc simulates no digital inputs: with none on, the control
//! moves at F (or FA) as if they were not written (the manual: "the F feed stays valid while no
//! input signal is present"), so a block's words are read, checked and noted once a run, and
//! change nothing.
//!
//! Never: take a value the control refuses (a negative feed, time or path; an input bit outside
//! 2 to 7; an axis the machine lacks).

use super::block::Words;
use super::predefined::written;
use super::Sinumerik;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::kernel::Kernel;
use crate::syntax::sinumerik::{Value, Word};

/// Reads F2= to F7=, ST=, SR=, FMA[..], STA[..] and SRA[..]; false for other words. The caller has
/// made sure no variable of the program has the word's name.
pub(super) fn read_word(
    front: &mut Sinumerik,
    kernel: &Kernel,
    word: &Word,
    words: &mut Words<'_>,
) -> Result<bool, Alarm> {
    let address = &*word.address;
    let (indices, expr) = match (address, &word.value) {
        ("F2" | "F3" | "F4" | "F5" | "F6" | "F7" | "ST" | "SR", Value::Expression(expr)) => {
            (&[][..], expr)
        }
        ("FMA" | "STA" | "SRA", Value::Indexed(indices, Some(expr))) => (&indices[..], expr),
        _ => return Ok(false),
    };
    match (address, indices) {
        ("FMA", [bit, axis]) => {
            let bit = front.value(kernel, bit)?;
            if !(2.0..=7.0).contains(&bit) || bit.fract() != 0.0 {
                return Err(Alarm::error(
                    AlarmCode::ValueOutOfRange,
                    word.span,
                    format!("FMA[{bit}, ..]: the input bit of an axial feed is 2 to 7"),
                ));
            }
            super::axes::axis_of(front, kernel, axis, word)?;
        }
        ("STA" | "SRA", [axis]) => {
            super::axes::axis_of(front, kernel, axis, word)?;
        }
        ("FMA" | "STA" | "SRA", _) => {
            return Err(Alarm::error(
                AlarmCode::MacroSyntax,
                word.span,
                format!(
                    "{address} takes {}",
                    if address == "FMA" {
                        "[bit, axis]"
                    } else {
                        "[axis]"
                    }
                ),
            ));
        }
        _ => {}
    }
    let value = front.value(kernel, expr)?;
    if value.is_nan() || value < 0.0 {
        return Err(Alarm::error(
            AlarmCode::ValueOutOfRange,
            word.span,
            format!(
                "{}: a feed, dwell time or return path cannot be negative",
                written(word)
            ),
        ));
    }
    if front.noted.insert("multi-feed".to_string()) {
        words.warnings.push(Alarm::warning(
            AlarmCode::KeptAsState,
            word.span,
            format!(
                "{} takes over only when its digital input comes on during the motion; vcnc \
                 simulates no inputs, so the block moves at its F (PGsl 7.10)",
                written(word)
            ),
        ));
    }
    Ok(true)
}
