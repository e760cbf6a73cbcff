//! The predefined functions of expressions: arithmetic (tables §7.5, L19596-19627) and
//! strings (tables §7.6, L19628-19675), plus the argument checks they share with the evaluator.
//!
//! Each takes evaluated arguments and gives a value or an alarm; none panics or returns a NaN.
//! Positions in strings count bytes from 0, and -1 means "not found" (tables §7.6).

use crate::alarm::{Alarm, AlarmCode};
use crate::interp::sinumerik::value::{int_of, kind_name, Value};
use crate::source::Span;

/// The arithmetic functions (tables §7.5, L19596-19627): REAL results, angles in degrees.
pub(super) fn arithmetic(
    name: &str,
    args: &[Option<Value>],
    span: Span,
) -> Option<Result<Value, Alarm>> {
    let one =
        |f: fn(f64) -> f64| reals::<1>(name, args, span).and_then(|[x]| Value::real(f(x), span));
    let result = match name {
        "SIN" => one(|x| x.to_radians().sin()),
        "COS" => one(|x| x.to_radians().cos()),
        "TAN" => one(|x| x.to_radians().tan()),
        "ASIN" => domain(
            name,
            args,
            span,
            |x| (-1.0..=1.0).contains(&x),
            |x| x.asin().to_degrees(),
        ),
        "ACOS" => domain(
            name,
            args,
            span,
            |x| (-1.0..=1.0).contains(&x),
            |x| x.acos().to_degrees(),
        ),
        "SQRT" => domain(name, args, span, |x| x >= 0.0, f64::sqrt),
        "LN" => domain(name, args, span, |x| x > 0.0, f64::ln),
        "EXP" => one(f64::exp),
        "ABS" => one(f64::abs),
        "POT" => one(|x| x * x),
        "TRUNC" => one(f64::trunc),
        // Half away from zero, as the conversion to INT.
        "ROUND" => one(f64::round),
        // Up to the next whole number (**choice**: towards plus infinity, PGAsl's examples give
        // ROUNDUP(-3.1) = -3).
        "ROUNDUP" => one(f64::ceil),
        "ATAN2" => reals::<2>(name, args, span)
            .and_then(|[y, x]| Value::real(y.atan2(x).to_degrees(), span)),
        "MINVAL" => reals::<2>(name, args, span).and_then(|[a, b]| Value::real(a.min(b), span)),
        "MAXVAL" => reals::<2>(name, args, span).and_then(|[a, b]| Value::real(a.max(b), span)),
        "BOUND" => reals::<3>(name, args, span).and_then(|[min, max, x]| bound(min, max, x, span)),
        _ => return None,
    };
    Some(result)
}

/// BOUND(min, max, value): the value within the range, the limit it passes otherwise (tables
/// §1.2 `BOUND`: "if in range the tested value is returned"; **choice**: the limit otherwise,
/// as PGAsl).
fn bound(min: f64, max: f64, x: f64, span: Span) -> Result<Value, Alarm> {
    if min > max {
        return Err(Alarm::error(
            AlarmCode::MacroArithmetic,
            span,
            format!("BOUND: the minimum {min} is above the maximum {max}"),
        ));
    }
    Value::real(x.clamp(min, max), span)
}

/// A function of one REAL defined where `inside` holds.
fn domain(
    name: &str,
    args: &[Option<Value>],
    span: Span,
    inside: fn(f64) -> bool,
    f: fn(f64) -> f64,
) -> Result<Value, Alarm> {
    let [x] = reals::<1>(name, args, span)?;
    if !inside(x) {
        return Err(Alarm::error(
            AlarmCode::MacroArithmetic,
            span,
            format!("{name}({x}) has no value"),
        )
        .with_help(match name {
            "SQRT" => "SQRT takes a number of 0 or more",
            "LN" => "LN takes a number above 0",
            _ => "ASIN and ACOS take a number from -1 to 1",
        }));
    }
    Value::real(f(x), span)
}

/// The string functions (tables §7.6, L19628-19675); positions count from 0, -1 is "not
/// found".
pub(super) fn string_function(
    name: &str,
    args: &[Option<Value>],
    span: Span,
) -> Option<Result<Value, Alarm>> {
    let texts = |n| texts(name, args, n, span);
    let result = match name {
        "STRLEN" => texts(1).map(|t| {
            // Up to the end of string, character 0 (tables §7.6).
            let length = t[0].bytes().position(|b| b == 0).unwrap_or(t[0].len());
            Value::Int(position(Some(length)))
        }),
        "INDEX" => texts(2).and_then(|t| {
            let c = one_char(name, &t[1], span)?;
            Ok(Value::Int(position(t[0].bytes().position(|b| b == c))))
        }),
        "RINDEX" => texts(2).and_then(|t| {
            let c = one_char(name, &t[1], span)?;
            Ok(Value::Int(position(t[0].bytes().rposition(|b| b == c))))
        }),
        "MINDEX" => texts(2).map(|t| {
            let set = t[1].as_bytes();
            Value::Int(position(t[0].bytes().position(|b| set.contains(&b))))
        }),
        // MATCH: the position of a string in a string (tables §1.2 `MATCH`).
        "MATCH" => texts(2).map(|t| {
            let (haystack, needle) = (t[0].as_bytes(), t[1].as_bytes());
            let found = match needle.is_empty() {
                true => Some(0),
                false => haystack.windows(needle.len()).position(|w| w == needle),
            };
            Value::Int(position(found))
        }),
        "SUBSTR" => substr(args, span),
        "TOUPPER" => texts(1).map(|t| Value::Str(t[0].to_ascii_uppercase())),
        "TOLOWER" => texts(1).map(|t| Value::Str(t[0].to_ascii_lowercase())),
        "NUMBER" => texts(1).and_then(|t| match parse_number(&t[0]) {
            Some(x) => Value::real(x, span),
            None => Err(Alarm::error(
                AlarmCode::MacroArithmetic,
                span,
                format!("NUMBER: \"{}\" is not a number", t[0]),
            )
            .with_help("ISNUMBER(text) tells whether NUMBER can convert it")),
        }),
        "ISNUMBER" => texts(1).map(|t| Value::Bool(parse_number(&t[0]).is_some())),
        "AXSTRING" => exactly::<1>(name, args.to_vec(), span).and_then(|[axis]| match axis {
            Value::Axis(axis) => Ok(Value::Str(axis)),
            other => Err(argument_type(name, 1, "AXIS", &other, span)),
        }),
        _ => return None,
    };
    Some(result)
}

/// SUBSTR(text, start[, count]): `count` characters from position `start` (0-based), or the
/// rest without `count` (**choice**: the tables give three parameters, §7.6; positions past
/// the end give the empty string, a negative one alarms).
fn substr(args: &[Option<Value>], span: Span) -> Result<Value, Alarm> {
    const NAME: &str = "SUBSTR";
    if !(2..=3).contains(&args.len()) {
        return Err(count(NAME, "2 or 3", args.len(), span));
    }
    let text = text_of(NAME, required(NAME, args, 0, span)?, span)?;
    let whole = |n: usize| -> Result<i32, Alarm> {
        let value = required(NAME, args, n, span)?;
        let x = value
            .as_f64()
            .ok_or_else(|| argument_type(NAME, n + 1, "INT", &value, span))?;
        int_of(x, span)
    };
    let start = whole(1)?;
    let count = match args.get(2) {
        Some(_) => whole(2)?,
        None => i32::MAX,
    };
    let (Ok(start), Ok(count)) = (usize::try_from(start), usize::try_from(count)) else {
        return Err(Alarm::error(
            AlarmCode::MacroArithmetic,
            span,
            format!("SUBSTR takes a start and a count of 0 or more, not {start} and {count}"),
        ));
    };
    let bytes = text.as_bytes();
    let from = start.min(bytes.len());
    let to = from.saturating_add(count).min(bytes.len());
    Ok(Value::Str(
        String::from_utf8_lossy(&bytes[from..to]).into_owned(),
    ))
}

/// The number NUMBER reads: blanks around, a sign, digits with a point, an exponent written
/// `EX` (the control's notation, PGsl 15.6 L11480-11488; **choice**: no `E` alone).
fn parse_number(text: &str) -> Option<f64> {
    let text = text
        .trim_matches(|c| c == ' ' || c == '\t')
        .to_ascii_uppercase();
    let (mantissa, exponent) = match text.split_once("EX") {
        Some((m, e)) => (m, Some(e)),
        None => (text.as_str(), None),
    };
    let unsigned = mantissa.strip_prefix(['+', '-']).unwrap_or(mantissa);
    let digits = unsigned.bytes().filter(u8::is_ascii_digit).count();
    let points = unsigned.bytes().filter(|&b| b == b'.').count();
    if digits == 0 || points > 1 || digits + points != unsigned.len() {
        return None;
    }
    let mut x: f64 = mantissa.parse().ok()?;
    if let Some(exponent) = exponent {
        let unsigned = exponent.strip_prefix(['+', '-']).unwrap_or(exponent);
        if unsigned.is_empty()
            || unsigned.len() > 3
            || !unsigned.bytes().all(|b| b.is_ascii_digit())
        {
            return None;
        }
        let e: i32 = exponent.parse().ok()?;
        x *= 10f64.powi(e);
    }
    x.is_finite().then_some(x)
}

/// A position as INT; -1 for none.
fn position(found: Option<usize>) -> i32 {
    // Strings hold at most a line's bytes, far below INT's range.
    found.map_or(-1, |p| i32::try_from(p).unwrap_or(i32::MAX))
}

/// The `n` arguments of a string function as texts.
fn texts(name: &str, args: &[Option<Value>], n: usize, span: Span) -> Result<Vec<String>, Alarm> {
    if args.len() != n {
        return Err(count(name, &n.to_string(), args.len(), span));
    }
    (0..n)
        .map(|i| text_of(name, required(name, args, i, span)?, span))
        .collect()
}

/// A STRING argument, or a CHAR as a string of one character.
pub(super) fn text_of(name: &str, value: Value, span: Span) -> Result<String, Alarm> {
    match value {
        Value::Str(s) => Ok(s),
        Value::Char(c) => Ok(char::from(c).to_string()),
        other => Err(argument_type(name, 1, "STRING", &other, span)),
    }
}

/// The CHAR argument of INDEX and RINDEX, given as a CHAR or a string of one character.
fn one_char(name: &str, text: &str, span: Span) -> Result<u8, Alarm> {
    match text.as_bytes() {
        [c] => Ok(*c),
        _ => Err(Alarm::error(
            AlarmCode::MacroArithmetic,
            span,
            format!("{name} searches for one character, not \"{text}\""),
        )
        .with_help("MATCH searches for a string, MINDEX for any of several characters")),
    }
}

/// The `N` arguments of an arithmetic function as REALs.
fn reals<const N: usize>(
    name: &str,
    args: &[Option<Value>],
    span: Span,
) -> Result<[f64; N], Alarm> {
    let values = exactly::<N>(name, args.to_vec(), span)?;
    let mut reals = [0.0; N];
    for (n, (real, value)) in reals.iter_mut().zip(values).enumerate() {
        *real = value
            .as_f64()
            .ok_or_else(|| argument_type(name, n + 1, "REAL", &value, span))?;
    }
    Ok(reals)
}

/// Exactly `N` arguments, all given.
pub(super) fn exactly<const N: usize>(
    name: &str,
    args: Vec<Option<Value>>,
    span: Span,
) -> Result<[Value; N], Alarm> {
    if args.len() != N {
        return Err(count(name, &N.to_string(), args.len(), span));
    }
    let values = args
        .into_iter()
        .enumerate()
        .map(|(n, v)| v.ok_or_else(|| missing(name, n, span)))
        .collect::<Result<Vec<_>, _>>()?;
    values
        .try_into()
        .map_err(|_| count(name, &N.to_string(), N, span))
}

fn required(name: &str, args: &[Option<Value>], n: usize, span: Span) -> Result<Value, Alarm> {
    args.get(n)
        .cloned()
        .flatten()
        .ok_or_else(|| missing(name, n, span))
}

fn count(name: &str, wanted: &str, given: usize, span: Span) -> Alarm {
    syntax(
        span,
        format!("{name} takes {wanted} arguments, {given} given"),
    )
}

pub(super) fn missing(name: &str, n: usize, span: Span) -> Alarm {
    syntax(span, format!("{name}: argument {} is missing", n + 1))
}

fn argument_type(name: &str, n: usize, wanted: &str, value: &Value, span: Span) -> Alarm {
    Alarm::error(
        AlarmCode::MacroArithmetic,
        span,
        format!(
            "{name}: argument {n} is {}, the function takes {wanted}",
            kind_name(value.type_of())
        ),
    )
}

pub(super) fn syntax(span: Span, message: impl Into<String>) -> Alarm {
    Alarm::error(AlarmCode::MacroSyntax, span, message)
        .with_help("check the function's arguments against the manual's list (tables §7)")
}
