//! Evaluating expressions: the postfix code of a block run on a small stack.
//!
//! Values are `Option<f64>`: `None` is the vacant value of `#0` and of variables never set.
//! FANUC's rules for it: a vacant operand counts as 0 in arithmetic and functions, and in GT,
//! GE, LT and LE; EQ and NE tell vacant from 0. A lone variable keeps its vacancy (`#2 = #1`
//! leaves #2 vacant when #1 is, and `X#1` is then omitted), and so does its negation.
//!
//! A Syntec `%@MACRO` program types its numbers: one written without a decimal point is a Long
//! (`Op::Long`), and two Longs divide to a whole number (`1/2` is 0). A value read from a
//! variable is a real (the local variables are Double: syntec-macro handbook 02-variables 2.1;
//! the public variables `@n` keep the type written, which vcnc does not track).

use super::MacroValue;
use crate::alarm::{Alarm, AlarmCode};
use crate::source::Span;
use crate::syntax::expr::{BinaryOp, Expr, Function, Function2, Instruction, Op};

/// Reads variables for the evaluator.
pub(crate) trait VariableReader {
    /// The value of `#number`, or an alarm for a variable that does not exist.
    fn read(&mut self, number: u32, span: Span) -> Result<MacroValue, Alarm>;

    /// The value of Syntec's public variable `@number`.
    fn read_public(&mut self, number: u32, span: Span) -> Result<MacroValue, Alarm>;
}

/// Room for operands: FANUC nests brackets five deep, so real expressions need a handful.
const STACK: usize = 32;

/// Evaluates `expr` of `code`.
///
/// # Errors
/// Unknown variables, arithmetic without a value (division by zero, SQRT of a negative ...).
pub(crate) fn evaluate(
    expr: Expr,
    code: &[Instruction],
    variables: &mut dyn VariableReader,
) -> Result<MacroValue, Alarm> {
    let code = expr.of(code);
    // A lone variable (the most common expression) needs no stack.
    if let [Instruction {
        op: Op::Variable(n),
        span,
    }] = code
    {
        return variables.read(*n, *span);
    }
    run(code, variables).map_err(|alarm| with_values(alarm, code, variables))
}

/// Labels `alarm` with the values of the variables `code` reads (`#1 = 0` under the `#1` of
/// `#2 = 10 / #1`): the alarm says which operation failed, the values say why. Read again
/// only here, when the evaluation failed; an alarm about a variable itself is left as it is.
fn with_values(
    mut alarm: Alarm,
    code: &[Instruction],
    variables: &mut dyn VariableReader,
) -> Alarm {
    /// A few are enough to see why; a long expression would bury the alarm.
    const MOST: usize = 6;
    if alarm.code == AlarmCode::BadVariable {
        return alarm;
    }
    let mut shown: Vec<(u8, u32)> = Vec::new();
    for instruction in code {
        let (sigil, number) = match instruction.op {
            Op::Variable(n) => (b'#', n),
            Op::Public(n) => (b'@', n),
            _ => continue,
        };
        if shown.len() == MOST || shown.contains(&(sigil, number)) {
            continue;
        }
        shown.push((sigil, number));
        let value = match sigil {
            b'#' => variables.read(number, instruction.span),
            _ => variables.read_public(number, instruction.span),
        };
        let sigil = sigil as char;
        let text = match value {
            Ok(Some(v)) => format!("{sigil}{number} = {v}"),
            Ok(None) => format!("{sigil}{number} is vacant"),
            Err(_) => continue,
        };
        alarm = alarm.with_label(instruction.span, text);
    }
    alarm
}

/// The evaluation proper: the postfix code on a stack.
fn run(code: &[Instruction], variables: &mut dyn VariableReader) -> Result<MacroValue, Alarm> {
    let mut stack = [None; STACK];
    // Whether each operand is a Syntec Long; only `Op::Long` and arithmetic between two Longs
    // make one.
    let mut long = [false; STACK];
    let mut depth = 0usize;
    for instruction in code {
        let span = instruction.span;
        let mut is_long = false;
        let value = match instruction.op {
            Op::Number(n) => Some(n),
            Op::Long(n) => {
                is_long = true;
                Some(n)
            }
            Op::Variable(n) => variables.read(n, span)?,
            Op::Indirect => {
                depth -= 1;
                let number = variable_number(stack[depth], span)?;
                variables.read(number, span)?
            }
            Op::Negate => {
                depth -= 1;
                is_long = long[depth];
                stack[depth].map(|v| -v)
            }
            Op::Binary(op) => {
                depth -= 2;
                let (a, b) = (stack[depth], stack[depth + 1]);
                is_long = long[depth] && long[depth + 1] && op.is_arithmetic();
                match op {
                    BinaryOp::Divide if is_long => whole_quotient(a, b, span)?,
                    _ => binary(op, a, b, span)?,
                }
            }
            Op::Function(f) => {
                depth -= 1;
                Some(function(f, stack[depth].unwrap_or(0.0), span)?)
            }
            Op::Atan2 => {
                depth -= 2;
                let y = stack[depth].unwrap_or(0.0);
                let x = stack[depth + 1].unwrap_or(0.0);
                Some(atan2_degrees(y, x, span)?)
            }
            Op::Power => {
                depth -= 2;
                let base = stack[depth].unwrap_or(0.0);
                let exponent = stack[depth + 1].unwrap_or(0.0);
                Some(finite(base.powf(exponent), span, "POW")?)
            }
            Op::Function2(f) => {
                depth -= 2;
                let a = stack[depth].unwrap_or(0.0);
                let b = stack[depth + 1].unwrap_or(0.0);
                Some(function2(f, a, b, span)?)
            }
            Op::Public(n) => variables.read_public(n, span)?,
            Op::PublicIndirect => {
                depth -= 1;
                let number = variable_number(stack[depth], span)?;
                variables.read_public(number, span)?
            }
        };
        if depth >= STACK {
            return Err(Alarm::error(
                AlarmCode::MacroSyntax,
                span,
                "expression too complex to evaluate",
            ));
        }
        stack[depth] = value;
        long[depth] = is_long;
        depth += 1;
    }
    Ok(if depth == 1 { stack[0] } else { None })
}

/// A computed variable number (`#[#1+2]`): rounded to a whole number as FANUC does.
///
/// # Errors
/// A vacant, negative or huge number.
pub(crate) fn variable_number(value: MacroValue, span: Span) -> Result<u32, Alarm> {
    let Some(v) = value else {
        return Err(Alarm::error(
            AlarmCode::BadVariable,
            span,
            "a variable number cannot be vacant",
        ));
    };
    let rounded = round_half_away(v);
    if !(0.0..=99_999_999.0).contains(&rounded) {
        return Err(Alarm::error(
            AlarmCode::BadVariable,
            span,
            format!("#{rounded} is not a variable number"),
        ));
    }
    Ok(rounded as u32)
}

/// Truth of a condition: non-zero is true, vacant is false.
pub(crate) fn is_true(value: MacroValue) -> bool {
    value.is_some_and(|v| v != 0.0)
}

fn binary(op: BinaryOp, a: MacroValue, b: MacroValue, span: Span) -> Result<MacroValue, Alarm> {
    let truth = |t: bool| Some(if t { 1.0 } else { 0.0 });
    // EQ and NE compare vacancy too: #0 EQ 0 is false, #0 EQ #0 is true.
    match op {
        BinaryOp::Equal => return Ok(truth(equal(a, b))),
        BinaryOp::NotEqual => return Ok(truth(!equal(a, b))),
        _ => {}
    }
    let (x, y) = (a.unwrap_or(0.0), b.unwrap_or(0.0));
    Ok(match op {
        BinaryOp::Add => Some(x + y),
        BinaryOp::Subtract => Some(x - y),
        BinaryOp::Multiply => Some(finite(x * y, span, "the product")?),
        BinaryOp::Divide => {
            if y == 0.0 {
                return Err(Alarm::error(
                    AlarmCode::MacroArithmetic,
                    span,
                    "division by zero",
                ));
            }
            Some(finite(x / y, span, "the quotient")?)
        }
        BinaryOp::Modulo => {
            if y == 0.0 {
                return Err(Alarm::error(
                    AlarmCode::MacroArithmetic,
                    span,
                    "MOD by zero",
                ));
            }
            // The remainder takes the sign of the dividend, as FANUC's MOD does.
            Some(x % y)
        }
        BinaryOp::And => Some(bitwise(x, y, span, |p, q| p & q)?),
        BinaryOp::Or => Some(bitwise(x, y, span, |p, q| p | q)?),
        BinaryOp::Xor => Some(bitwise(x, y, span, |p, q| p ^ q)?),
        BinaryOp::Greater => truth(x > y),
        BinaryOp::GreaterOrEqual => truth(x >= y),
        BinaryOp::Less => truth(x < y),
        BinaryOp::LessOrEqual => truth(x <= y),
        BinaryOp::Equal | BinaryOp::NotEqual => unreachable!("handled above"),
    })
}

/// Two Syntec Longs divided: the quotient's fraction dropped, toward zero (`7/2` is 3, `-7/2`
/// is -3). The handbook (02-variables 3.4) gives the rule, not the direction for negative
/// numbers: vcnc takes C's, in which the control is written.
fn whole_quotient(a: MacroValue, b: MacroValue, span: Span) -> Result<MacroValue, Alarm> {
    Ok(binary(BinaryOp::Divide, a, b, span)?.map(f64::trunc))
}

/// EQ: both vacant, or both set and equal. The controls compare with a small tolerance (they
/// hold about 15 significant digits); 1e-12 relative keeps `0.1+0.2 EQ 0.3` true.
pub(crate) fn equal(a: MacroValue, b: MacroValue) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(x), Some(y)) => (x - y).abs() <= 1e-12 * x.abs().max(y.abs()).max(1.0),
        _ => false,
    }
}

/// AND, OR, XOR on whole numbers (conditions are 0 and 1, so they act as logic).
fn bitwise(x: f64, y: f64, span: Span, f: impl Fn(i64, i64) -> i64) -> Result<f64, Alarm> {
    let whole = |v: f64| {
        let r = round_half_away(v);
        if (v - r).abs() > 1e-9 || r.abs() > 9.0e15 {
            Err(Alarm::error(
                AlarmCode::MacroArithmetic,
                span,
                format!("AND, OR and XOR take whole numbers, not {v}"),
            ))
        } else {
            Ok(r as i64)
        }
    };
    Ok(f(whole(x)?, whole(y)?) as f64)
}

fn finite(v: f64, span: Span, what: &str) -> Result<f64, Alarm> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Alarm::error(
            AlarmCode::MacroArithmetic,
            span,
            format!("{what} is too large"),
        ))
    }
}

/// Rounds halves away from zero (ROUND, and the rounding of variable numbers).
pub(crate) fn round_half_away(v: f64) -> f64 {
    v.round()
}

fn function(f: Function, x: f64, span: Span) -> Result<f64, Alarm> {
    let domain = |ok: bool, what: &str| {
        if ok {
            Ok(())
        } else {
            Err(Alarm::error(
                AlarmCode::MacroArithmetic,
                span,
                format!("{what} of {x} has no value"),
            ))
        }
    };
    Ok(match f {
        Function::Sin => crate::interp::frames::sin_cos_degrees(x).0,
        Function::Cos => crate::interp::frames::sin_cos_degrees(x).1,
        Function::Tan => {
            let (s, c) = crate::interp::frames::sin_cos_degrees(x);
            domain(c != 0.0, "TAN")?;
            s / c
        }
        Function::Asin => {
            domain((-1.0..=1.0).contains(&x), "ASIN")?;
            x.asin().to_degrees()
        }
        Function::Acos => {
            domain((-1.0..=1.0).contains(&x), "ACOS")?;
            x.acos().to_degrees()
        }
        Function::Atan => x.atan().to_degrees(),
        Function::Sqrt => {
            domain(x >= 0.0, "SQRT")?;
            x.sqrt()
        }
        Function::Abs => x.abs(),
        Function::Round => round_half_away(x),
        Function::Fix => x.trunc(),
        Function::Fup => {
            let t = x.trunc();
            if t == x {
                t
            } else {
                t + x.signum()
            }
        }
        Function::Ln => {
            domain(x > 0.0, "LN")?;
            x.ln()
        }
        Function::Exp => finite(x.exp(), span, "EXP")?,
        Function::Bin => {
            domain(x >= 0.0 && x.fract() == 0.0 && x < 1e15, "BIN")?;
            from_bcd(x as u64, span)? as f64
        }
        Function::Bcd => {
            domain(x >= 0.0 && x.fract() == 0.0 && x < 1e15, "BCD")?;
            to_bcd(x as u64) as f64
        }
        Function::Ceil => x.ceil(),
        Function::Floor => x.floor(),
        Function::Sign => {
            if x == 0.0 {
                0.0
            } else {
                x.signum()
            }
        }
        Function::Not => {
            if x == 0.0 {
                1.0
            } else {
                0.0
            }
        }
    })
}

/// MAX, MIN and ATAN2 of Syntec macro programs.
fn function2(f: Function2, a: f64, b: f64, span: Span) -> Result<f64, Alarm> {
    Ok(match f {
        Function2::Max => a.max(b),
        Function2::Min => a.min(b),
        Function2::Atan2 => {
            if a == 0.0 && b == 0.0 {
                return Err(Alarm::error(
                    AlarmCode::MacroArithmetic,
                    span,
                    "ATAN2 of 0 and 0 has no value",
                ));
            }
            a.atan2(b).to_degrees()
        }
    })
}

/// ATAN[y]/[x] in degrees, 0 to 360 as FANUC gives it (parameter NAT off).
fn atan2_degrees(y: f64, x: f64, span: Span) -> Result<f64, Alarm> {
    if x == 0.0 && y == 0.0 {
        return Err(Alarm::error(
            AlarmCode::MacroArithmetic,
            span,
            "ATAN of 0/0 has no value",
        ));
    }
    let degrees = y.atan2(x).to_degrees();
    Ok(if degrees < 0.0 {
        degrees + 360.0
    } else {
        degrees
    })
}

fn to_bcd(mut v: u64) -> u64 {
    let mut out = 0u64;
    let mut shift = 0;
    while v > 0 && shift < 64 {
        out |= (v % 10) << shift;
        v /= 10;
        shift += 4;
    }
    out
}

fn from_bcd(mut v: u64, span: Span) -> Result<u64, Alarm> {
    let mut out = 0u64;
    let mut scale = 1u64;
    while v > 0 {
        let digit = v & 0xF;
        if digit > 9 {
            return Err(Alarm::error(
                AlarmCode::MacroArithmetic,
                span,
                "BIN: the value is not binary-coded decimal",
            ));
        }
        out += digit * scale;
        scale = scale.saturating_mul(10);
        v >>= 4;
    }
    Ok(out)
}
