#![cfg_attr(not(test), allow(dead_code))] // wired in by the front end (issue 20)
//! The SINUMERIK language's values and data types, and the conversions between them.
//!
//! The types are the control's: INT, REAL, BOOL, CHAR, `STRING[n]` and AXIS (an axis name).
//! FRAME variables belong to the frame module and are not values here. A value never holds a
//! NaN or an infinity: every constructor from `f64` checks, and a conversion that cannot be made
//! is an alarm with the span of its cause, never a panic or a silent default.
//!
//! The Fundamentals manual lists the types and functions but leaves their rules to the Job
//! Planning manual (PGAsl, not one of our seeds: sinumerik-tables.md 1.1). Where it is silent,
//! the conversions follow the control's documented table as this module states it, each rule
//! marked as a choice where it is one.

use crate::alarm::{Alarm, AlarmCode};
use crate::source::Span;
use std::fmt::Write as _;

/// The longest STRING the control holds, and the length of `DEF STRING` without `[n]`
/// (**choice**: PGAsl limits `STRING[n]` to 200 characters; the Fundamentals manual is silent).
pub(crate) const MAX_STRING: usize = 200;

/// A data type of the language, as `DEF` names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Type {
    /// `INT`: a signed 32-bit integer.
    Int,
    /// `REAL`: a double.
    Real,
    /// `BOOL`: TRUE or FALSE ("TRUE/FALSE or 1/0", tables §1.2 `BOOL`).
    Bool,
    /// `CHAR`: one ASCII character, 0 to 255.
    Char,
    /// `STRING[n]`: text of at most `n` characters.
    String(usize),
    /// `AXIS`: an axis name (tables §1.2 `AXIS`).
    Axis,
}

impl Type {
    /// The type `DEF` writes as `name` (upper case); `STRING` gets its length separately
    /// ([`Type::string`]). `None` for a name that is not a type.
    pub(crate) fn from_name(name: &str) -> Option<Type> {
        Some(match name {
            "INT" => Type::Int,
            "REAL" => Type::Real,
            "BOOL" => Type::Bool,
            "CHAR" => Type::Char,
            "STRING" => Type::String(MAX_STRING),
            "AXIS" => Type::Axis,
            _ => return None,
        })
    }

    /// `STRING[length]`, checked against the control's limit.
    ///
    /// # Errors
    /// [`AlarmCode::ValueOutOfRange`] for a length of 0 or above [`MAX_STRING`].
    pub(crate) fn string(length: i64, span: Span) -> Result<Type, Alarm> {
        match usize::try_from(length) {
            Ok(n) if (1..=MAX_STRING).contains(&n) => Ok(Type::String(n)),
            _ => Err(Alarm::error(
                AlarmCode::ValueOutOfRange,
                span,
                format!("STRING[{length}] is not a length the control has: 1 to {MAX_STRING}"),
            )),
        }
    }

    /// The name `DEF` writes for it (`STRING[20]`).
    pub(crate) fn name(self) -> String {
        match self {
            Type::Int => "INT".into(),
            Type::Real => "REAL".into(),
            Type::Bool => "BOOL".into(),
            Type::Char => "CHAR".into(),
            Type::String(n) => format!("STRING[{n}]"),
            Type::Axis => "AXIS".into(),
        }
    }

    /// The value of a variable of this type that no one has set (**choice**, PGAsl's table:
    /// 0, 0.0, FALSE, character 0, the empty string, no axis).
    pub(crate) fn default_value(self) -> Value {
        match self {
            Type::Int => Value::Int(0),
            Type::Real => Value::Real(0.0),
            Type::Bool => Value::Bool(false),
            Type::Char => Value::Char(0),
            Type::String(_) => Value::Str(String::new()),
            Type::Axis => Value::Axis(String::new()),
        }
    }

    /// True when both are STRING, whatever their lengths, or the same type.
    pub(crate) fn same_kind(self, other: Type) -> bool {
        matches!((self, other), (Type::String(_), Type::String(_))) || self == other
    }
}

/// A value of the language.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Value {
    /// INT.
    Int(i32),
    /// REAL, always finite.
    Real(f64),
    /// BOOL.
    Bool(bool),
    /// CHAR.
    Char(u8),
    /// STRING.
    Str(String),
    /// AXIS: the axis name, upper case; empty for an AXIS variable never set.
    Axis(String),
}

impl Value {
    /// A REAL, or an alarm at `span` when `x` is NaN or infinite (an overflow: `EXP(1000)`).
    ///
    /// # Errors
    /// [`AlarmCode::MacroArithmetic`] when `x` is not finite.
    pub(crate) fn real(x: f64, span: Span) -> Result<Value, Alarm> {
        if x.is_finite() {
            Ok(Value::Real(x))
        } else {
            Err(Alarm::error(
                AlarmCode::MacroArithmetic,
                span,
                "the result has no value: too large, or not a number",
            )
            .with_help("check the operands of the expression: a REAL holds about ±1.8e308"))
        }
    }

    /// A number as its narrowest type: a whole number within INT's range is an INT (`5`,
    /// `'H1F'`), any other a REAL. (**Choice**: the syntax tree keeps constants as `f64`, so a
    /// written `5.0` is INT too; it only matters for `+ - *`, whose result INT or REAL holds
    /// the same number.)
    pub(crate) fn number(x: f64, span: Span) -> Result<Value, Alarm> {
        if x.fract() == 0.0 && (f64::from(i32::MIN)..=f64::from(i32::MAX)).contains(&x) {
            // The range check above makes the cast exact.
            Ok(Value::Int(x as i32))
        } else {
            Value::real(x, span)
        }
    }

    /// The value's type; a STRING reports its own length.
    pub(crate) fn type_of(&self) -> Type {
        match self {
            Value::Int(_) => Type::Int,
            Value::Real(_) => Type::Real,
            Value::Bool(_) => Type::Bool,
            Value::Char(_) => Type::Char,
            Value::Str(s) => Type::String(s.len()),
            Value::Axis(_) => Type::Axis,
        }
    }

    /// The number a numeric value holds (INT, REAL, BOOL as 0/1, CHAR as its code), or `None`
    /// for STRING and AXIS.
    pub(crate) fn as_f64(&self) -> Option<f64> {
        match *self {
            Value::Int(i) => Some(f64::from(i)),
            Value::Real(x) => Some(x),
            Value::Bool(b) => Some(if b { 1.0 } else { 0.0 }),
            Value::Char(c) => Some(f64::from(c)),
            Value::Str(_) | Value::Axis(_) => None,
        }
    }

    /// This value as type `to`, by the conversion table (PGAsl "type conversion"):
    ///
    /// | from \ to | REAL | INT | BOOL | CHAR | STRING | AXIS |
    /// |---|---|---|---|---|---|---|
    /// | REAL | yes | rounded | ≠0 | rounded, 0-255 | text | - |
    /// | INT | yes | yes | ≠0 | 0-255 | text | - |
    /// | BOOL | 1/0 | 1/0 | yes | 1/0 | TRUE/FALSE | - |
    /// | CHAR | code | code | ≠0 | yes | 1 character | - |
    /// | STRING | - | - | not empty | 1 character only | yes (length) | - |
    /// | AXIS | - | - | - | - | - | yes |
    ///
    /// REAL to INT rounds half away from zero (PGAsl: a fraction of 0.5 and more rounds up).
    /// Numbers to STRING (**choice**: PGAsl converts them for `<<`; vcnc on assignment too) are
    /// written as [`Value::to_text`] does. STRING to a number is NUMBER's work, STRING to AXIS
    /// AXNAME's, AXIS to STRING AXSTRING's: the alarm says so.
    ///
    /// # Errors
    /// [`AlarmCode::MacroArithmetic`] for a conversion the table forbids, a number out of the
    /// target's range, a string longer than `STRING[n]`.
    pub(crate) fn convert(self, to: Type, span: Span) -> Result<Value, Alarm> {
        let from = self.type_of();
        let refused = |help: &str| {
            Err(Alarm::error(
                AlarmCode::MacroArithmetic,
                span,
                format!("a {} value cannot become {}", kind_name(from), to.name()),
            )
            .with_help(help.to_string()))
        };
        match (to, self) {
            (Type::Real, Value::Str(_)) | (Type::Int, Value::Str(_)) => {
                refused("NUMBER(text) converts a string into a number")
            }
            (Type::Axis, Value::Axis(name)) => Ok(Value::Axis(name)),
            (Type::Axis, Value::Str(_)) => refused("AXNAME(text) converts a string into an axis"),
            (Type::Axis, _) => refused("an AXIS variable takes an axis name (X, Y, Z ...)"),
            (Type::String(_), Value::Axis(_)) => {
                refused("AXSTRING(axis) converts an axis into a string")
            }
            (_, Value::Axis(_)) => refused("an axis name is no number"),
            (Type::Real, value) => Ok(Value::Real(value.as_f64().unwrap_or(0.0))),
            (Type::Int, value) => int_of(value.as_f64().unwrap_or(0.0), span).map(Value::Int),
            (Type::Bool, Value::Str(s)) => Ok(Value::Bool(!s.is_empty())),
            (Type::Bool, value) => Ok(Value::Bool(value.as_f64().is_some_and(|x| x != 0.0))),
            (Type::Char, Value::Str(s)) => match s.as_bytes() {
                [c] => Ok(Value::Char(*c)),
                _ => refused("only a string of one character becomes a CHAR"),
            },
            (Type::Char, value) => char_of(value.as_f64().unwrap_or(0.0), span),
            (Type::String(n), value) => {
                let text = value.to_text();
                if text.len() > n {
                    return Err(Alarm::error(
                        AlarmCode::MacroArithmetic,
                        span,
                        format!(
                            "the string has {} characters, more than STRING[{n}] holds",
                            text.len()
                        ),
                    )
                    .with_help("declare the variable longer, or shorten the text (SUBSTR)"));
                }
                Ok(Value::Str(text))
            }
        }
    }

    /// The value as text, as `<<` chains it: INT in digits, REAL with up to ten decimals and
    /// no trailing zeros (`12.5`, `3`), BOOL as TRUE or FALSE, CHAR as its character, STRING as
    /// itself, AXIS as its name. (**Choice**: the Fundamentals manual shows only
    /// `"..."<<R12`, L9806; the format is PGAsl's as far as known.)
    pub(crate) fn to_text(&self) -> String {
        match self {
            Value::Int(i) => i.to_string(),
            Value::Real(x) => real_text(*x),
            Value::Bool(b) => if *b { "TRUE" } else { "FALSE" }.into(),
            Value::Char(c) => char::from(*c).to_string(),
            Value::Str(s) | Value::Axis(s) => s.clone(),
        }
    }
}

/// The short name of a value's kind for messages (`STRING`, not `STRING[5]`).
pub(crate) fn kind_name(ty: Type) -> &'static str {
    match ty {
        Type::Int => "INT",
        Type::Real => "REAL",
        Type::Bool => "BOOL",
        Type::Char => "CHAR",
        Type::String(_) => "STRING",
        Type::Axis => "AXIS",
    }
}

/// REAL to INT: rounded half away from zero, within INT's range.
///
/// # Errors
/// [`AlarmCode::MacroArithmetic`] for a value beyond ±2147483647.
pub(crate) fn int_of(x: f64, span: Span) -> Result<i32, Alarm> {
    let rounded = x.round();
    if (f64::from(i32::MIN)..=f64::from(i32::MAX)).contains(&rounded) {
        // Within range and whole: the cast is exact.
        Ok(rounded as i32)
    } else {
        Err(Alarm::error(
            AlarmCode::MacroArithmetic,
            span,
            format!("{} is too large for an INT", real_text(x)),
        )
        .with_help("an INT holds -2147483648 to 2147483647: use a REAL variable"))
    }
}

/// A number to CHAR: rounded, 0 to 255.
fn char_of(x: f64, span: Span) -> Result<Value, Alarm> {
    let rounded = x.round();
    if (0.0..=255.0).contains(&rounded) {
        // 0..=255 and whole: the cast is exact.
        Ok(Value::Char(rounded as u8))
    } else {
        Err(Alarm::error(
            AlarmCode::MacroArithmetic,
            span,
            format!("{} is not a character code (0 to 255)", real_text(x)),
        ))
    }
}

/// A REAL with up to ten decimals, without trailing zeros or a trailing point, `-0` as `0`.
fn real_text(x: f64) -> String {
    let mut text = String::new();
    // Writing to a String cannot fail.
    let _ = write!(text, "{x:.10}");
    if text.contains('.') {
        let kept = text.trim_end_matches('0').trim_end_matches('.').len();
        text.truncate(kept);
    }
    if text == "-0" {
        text = "0".into();
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::source::FileId;

    fn span() -> Span {
        Span::new(FileId(0), 1, 0..1)
    }

    fn convert(value: Value, to: Type) -> Result<Value, Alarm> {
        value.convert(to, span())
    }

    #[test]
    fn real_to_int_rounds_half_away_from_zero() {
        // PGAsl: a fraction of .5 and more rounds up (in magnitude).
        assert_eq!(convert(Value::Real(2.5), Type::Int), Ok(Value::Int(3)));
        assert_eq!(convert(Value::Real(2.49), Type::Int), Ok(Value::Int(2)));
        assert_eq!(convert(Value::Real(-2.5), Type::Int), Ok(Value::Int(-3)));
        assert_eq!(convert(Value::Real(-2.4), Type::Int), Ok(Value::Int(-2)));
    }

    #[test]
    fn real_to_int_beyond_the_range_alarms() {
        let alarm = convert(Value::Real(3.0e9), Type::Int).unwrap_err();
        assert_eq!(alarm.code, AlarmCode::MacroArithmetic);
        assert!(alarm.message.contains("too large for an INT"));
    }

    #[test]
    fn numbers_become_bool_when_not_zero() {
        assert_eq!(
            convert(Value::Real(0.001), Type::Bool),
            Ok(Value::Bool(true))
        );
        assert_eq!(convert(Value::Int(0), Type::Bool), Ok(Value::Bool(false)));
        assert_eq!(
            convert(Value::Char(b'A'), Type::Bool),
            Ok(Value::Bool(true))
        );
        assert_eq!(
            convert(Value::Str(String::new()), Type::Bool),
            Ok(Value::Bool(false))
        );
        assert_eq!(
            convert(Value::Str("0".into()), Type::Bool),
            Ok(Value::Bool(true))
        );
    }

    #[test]
    fn bool_and_char_become_numbers() {
        assert_eq!(convert(Value::Bool(true), Type::Real), Ok(Value::Real(1.0)));
        assert_eq!(convert(Value::Char(b'A'), Type::Int), Ok(Value::Int(65)));
        assert_eq!(convert(Value::Int(66), Type::Char), Ok(Value::Char(b'B')));
        assert!(convert(Value::Int(256), Type::Char).is_err());
        assert!(convert(Value::Int(-1), Type::Char).is_err());
    }

    #[test]
    fn numbers_become_text() {
        // Ten decimals at most, trailing zeros dropped: 1/3 = 0.3333333333.
        assert_eq!(
            convert(Value::Real(1.0 / 3.0), Type::String(20)),
            Ok(Value::Str("0.3333333333".into()))
        );
        assert_eq!(Value::Real(12.5).to_text(), "12.5");
        assert_eq!(Value::Real(3.0).to_text(), "3");
        assert_eq!(Value::Real(-0.0).to_text(), "0");
        assert_eq!(Value::Int(-42).to_text(), "-42");
        assert_eq!(Value::Bool(true).to_text(), "TRUE");
        assert_eq!(
            convert(Value::Char(b'x'), Type::String(1)),
            Ok(Value::Str("x".into()))
        );
    }

    #[test]
    fn string_to_a_number_alarms_and_names_number() {
        let alarm = convert(Value::Str("12".into()), Type::Real).unwrap_err();
        assert_eq!(alarm.code, AlarmCode::MacroArithmetic);
        assert!(alarm.help.unwrap().contains("NUMBER"));
        assert!(convert(Value::Str("12".into()), Type::Int).is_err());
    }

    #[test]
    fn string_to_char_needs_one_character() {
        assert_eq!(
            convert(Value::Str("Q".into()), Type::Char),
            Ok(Value::Char(b'Q'))
        );
        assert!(convert(Value::Str("QR".into()), Type::Char).is_err());
    }

    #[test]
    fn strings_longer_than_the_declared_length_alarm() {
        assert!(convert(Value::Str("ABCDE".into()), Type::String(5)).is_ok());
        let alarm = convert(Value::Str("ABCDEF".into()), Type::String(5)).unwrap_err();
        assert!(alarm.message.contains("STRING[5]"));
    }

    #[test]
    fn axes_convert_only_to_axes() {
        assert_eq!(
            convert(Value::Axis("X".into()), Type::Axis),
            Ok(Value::Axis("X".into()))
        );
        assert!(convert(Value::Axis("X".into()), Type::Real).is_err());
        let alarm = convert(Value::Axis("X".into()), Type::String(10)).unwrap_err();
        assert!(alarm.help.unwrap().contains("AXSTRING"));
        let alarm = convert(Value::Str("X".into()), Type::Axis).unwrap_err();
        assert!(alarm.help.unwrap().contains("AXNAME"));
        assert!(convert(Value::Int(1), Type::Axis).is_err());
    }

    #[test]
    fn type_names_and_defaults() {
        assert_eq!(Type::from_name("REAL"), Some(Type::Real));
        assert_eq!(Type::from_name("STRING"), Some(Type::String(MAX_STRING)));
        assert_eq!(Type::from_name("FRAME"), None);
        assert_eq!(Type::String(8).name(), "STRING[8]");
        assert_eq!(Type::Bool.default_value(), Value::Bool(false));
        assert_eq!(Type::Axis.default_value(), Value::Axis(String::new()));
        assert!(Type::string(0, span()).is_err());
        assert!(Type::string(201, span()).is_err());
        assert_eq!(Type::string(32, span()), Ok(Type::String(32)));
    }

    #[test]
    fn numbers_take_their_narrowest_type() {
        assert_eq!(Value::number(5.0, span()), Ok(Value::Int(5)));
        assert_eq!(Value::number(2.5, span()), Ok(Value::Real(2.5)));
        assert_eq!(Value::number(3.0e9, span()), Ok(Value::Real(3.0e9)));
        assert!(Value::real(f64::NAN, span()).is_err());
        assert!(Value::real(f64::INFINITY, span()).is_err());
    }
}
