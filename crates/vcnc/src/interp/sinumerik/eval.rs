#![cfg_attr(not(test), allow(dead_code))] // wired in by the front end (issue 20)
//! Evaluating SINUMERIK expressions: operators with the control's type rules, the arithmetic
//! and string functions, and assignments to R parameters and user variables.
//!
//! The tree comes from `crate::syntax::sinumerik` (its doc gives the precedence); names are
//! resolved here: TRUE, FALSE and `$PI`, the other `$` system variables (asked of the
//! [`Environment`]), R parameters and user variables ([`Variables`]), then axis names (the
//! environment knows them). The front end strips `AC(..)`/`IC(..)` and similar value functions of a word before
//! calling [`evaluate`]; a call that neither this module nor the environment knows is a
//! NotSupportedYet alarm that names it.
//!
//! Evaluation never panics and never yields NaN or an infinity: division by zero, a function
//! outside its domain, an overflow are alarms with the span of the operation. It never writes
//! a variable except through [`assign`] and [`assign_expr`].

mod functions;

use super::value::{int_of, kind_name, Value, MAX_STRING};
use super::vars::{Init, Place, Variables};
use crate::alarm::{Alarm, AlarmCode};
use crate::source::Span;
use crate::syntax::sinumerik::{BinaryOp, Expr, ExprKind, UnaryOp};
use functions::{arithmetic, exactly, missing, string_function, syntax, text_of};
use std::cmp::Ordering;

/// What the evaluator asks of the front end.
pub(crate) trait Environment {
    /// The value of system variable `name` (`$AA_IW`, `$P_TOOLNO`, with its `$`) at `indices`
    /// (evaluated: an axis index is a [`Value::Axis`], a name that is neither a variable nor an
    /// axis a [`Value::Str`] of the name, as the `TR` of `$P_UIFR[1,X,TR]`).
    ///
    /// # Errors
    /// An alarm for a variable the front end does not have or indices it does not take.
    fn system_variable(
        &mut self,
        name: &str,
        indices: &[Value],
        span: Span,
    ) -> Result<Value, Alarm>;

    /// True when `name` (upper case) is an axis of the channel (`X`, `Y`, `Z`, `A1` ...).
    fn is_axis(&self, name: &str) -> bool;

    /// A call this module does not know (`CTRANS`, `GETT`, `ISAXIS` ...): `None` when the front
    /// end does not know it either.
    fn call(
        &mut self,
        _name: &str,
        _arguments: &[Option<Value>],
        _span: Span,
    ) -> Option<Result<Value, Alarm>> {
        None
    }

    /// Writes system variable `name` at `indices` ([`assign_expr`] to a `$` name).
    ///
    /// # Errors
    /// By default every system variable is read-only here: [`AlarmCode::BadVariable`].
    fn write_system_variable(
        &mut self,
        name: &str,
        _indices: &[Value],
        _value: Value,
        span: Span,
    ) -> Result<(), Alarm> {
        Err(Alarm::error(
            AlarmCode::BadVariable,
            span,
            format!("{name} cannot be written by a program"),
        ))
    }
}

/// The tolerance of `==` and the other comparisons on REAL: relative to the larger operand
/// (**choice**: PGAsl compares REAL values with a relative tolerance of 1e-12, so that
/// `0.1+0.2==0.3` holds as on the control).
const COMPARISON_TOLERANCE: f64 = 1e-12;

/// The deepest tree evaluated: a line of thousands of `+1` parses into a deep left branch.
const MAX_DEPTH: u32 = 1024;

/// The value of `expr`.
///
/// # Errors
/// [`AlarmCode::BadVariable`] for an unknown name, [`AlarmCode::MacroArithmetic`] for
/// division by zero, domain errors, overflow and operands of the wrong type,
/// [`AlarmCode::MacroSyntax`] for a call with the wrong arguments, SET or REP outside an
/// assignment, [`AlarmCode::NotSupportedYet`] for an unknown function, the environment's alarms.
pub(crate) fn evaluate(
    expr: &Expr,
    variables: &Variables,
    env: &mut dyn Environment,
) -> Result<Value, Alarm> {
    Evaluator { variables, env }.eval(expr, 0)
}

/// `name[indices] = value` for an R parameter or a user variable, `value` converted to the
/// variable's type.
///
/// # Errors
/// The alarms of [`Variables::place`] and [`Variables::set`].
pub(crate) fn assign(
    variables: &mut Variables,
    name: &str,
    indices: &[Value],
    value: Value,
    span: Span,
) -> Result<(), Alarm> {
    let place = variables.place(name, indices, span)?;
    variables.set(&place, value, span)
}

/// The assignment `name[indices] = expr` of a block: `SET(..)` and `REP(..)` fill an array from
/// the element on (or from its start), a `$` name is written through the environment, any
/// other value is [`assign`]ed.
///
/// # Errors
/// As [`evaluate`] and [`assign`].
pub(crate) fn assign_expr(
    variables: &mut Variables,
    env: &mut dyn Environment,
    name: &str,
    indices: &[Expr],
    expr: &Expr,
    span: Span,
) -> Result<(), Alarm> {
    let indices = indices
        .iter()
        .map(|index| evaluate(index, variables, env))
        .collect::<Result<Vec<_>, _>>()?;
    if name.starts_with('$') {
        let value = evaluate(expr, variables, env)?;
        return env.write_system_variable(name, &indices, value, span);
    }
    let place = variables.place(name, &indices, span)?;
    match initialiser(expr, variables, env)? {
        Init::Set(values) => variables.set_list(&place, values, span),
        Init::Rep(value) => variables.fill(&place, value, span),
        Init::Value(value) => variables.set(&place, value, span),
        Init::Default => Ok(()),
    }
}

/// The place a call's argument names, for a `VAR` parameter ([`Variables::bind_reference`]):
/// a variable, an array, an element or an R parameter, its indices evaluated.
///
/// # Errors
/// [`AlarmCode::BadVariable`] for an argument that is not a variable (a constant, an
/// expression, a system variable); as [`Variables::place`] and [`evaluate`].
pub(crate) fn place_of(
    expr: &Expr,
    variables: &Variables,
    env: &mut dyn Environment,
) -> Result<Place, Alarm> {
    let named = match &expr.kind {
        ExprKind::Name(name) => Some((name, &[][..])),
        ExprKind::Index(name, indices) => Some((name, &indices[..])),
        _ => None,
    };
    let Some((name, indices)) = named.filter(|(name, _)| !name.starts_with('$')) else {
        return Err(Alarm::error(
            AlarmCode::BadVariable,
            expr.span,
            "a VAR parameter takes a variable, an array element or an R parameter",
        )
        .with_help("pass the value through a variable: `DEF REAL TMP=...` and the call with TMP"));
    };
    let indices = indices
        .iter()
        .map(|index| evaluate(index, variables, env))
        .collect::<Result<Vec<_>, _>>()?;
    variables.place(name, &indices, expr.span)
}

/// What a DEF's `=expr` gives ([`Variables::declare`]): `SET(a, b, ...)`, `REP(v)` or a value.
///
/// # Errors
/// As [`evaluate`]; [`AlarmCode::MacroSyntax`] for a SET or REP without values.
pub(crate) fn initialiser(
    expr: &Expr,
    variables: &Variables,
    env: &mut dyn Environment,
) -> Result<Init, Alarm> {
    let mut evaluator = Evaluator { variables, env };
    match &expr.kind {
        ExprKind::Call(name, arguments) if &**name == "SET" => {
            let values = evaluator.arguments(name, arguments, expr.span, 0)?;
            let values = values
                .into_iter()
                .enumerate()
                .map(|(n, v)| v.ok_or_else(|| missing(name, n, expr.span)))
                .collect::<Result<Vec<_>, _>>()?;
            if values.is_empty() {
                return Err(syntax(expr.span, "SET needs at least one value"));
            }
            Ok(Init::Set(values))
        }
        ExprKind::Call(name, arguments) if &**name == "REP" => {
            // REP(value, count) of later software versions is not in our manuals.
            let [value] = evaluator.fixed::<1>(name, arguments, expr.span, 0)?;
            Ok(Init::Rep(value))
        }
        _ => Ok(Init::Value(evaluator.eval(expr, 0)?)),
    }
}

struct Evaluator<'a> {
    variables: &'a Variables,
    env: &'a mut dyn Environment,
}

impl Evaluator<'_> {
    fn eval(&mut self, expr: &Expr, depth: u32) -> Result<Value, Alarm> {
        if depth > MAX_DEPTH {
            return Err(Alarm::error(
                AlarmCode::MacroLimit,
                expr.span,
                format!("the expression is deeper than {MAX_DEPTH} operations"),
            )
            .with_help("split the expression over several assignments"));
        }
        let span = expr.span;
        match &expr.kind {
            ExprKind::Number(x) => Value::number(*x, span),
            ExprKind::Text(text) => Ok(Value::Str(text.to_string())),
            ExprKind::Name(name) => self.name(name, span),
            ExprKind::Index(name, indices) if name.starts_with('$') => {
                let indices = indices
                    .iter()
                    .map(|index| self.system_index(index, depth + 1))
                    .collect::<Result<Vec<_>, _>>()?;
                let value = self.env.system_variable(name, &indices, span)?;
                checked(value, span)
            }
            ExprKind::Index(name, indices) => {
                let indices = indices
                    .iter()
                    .map(|index| self.eval(index, depth + 1))
                    .collect::<Result<Vec<_>, _>>()?;
                self.variables.read(name, &indices, span)
            }
            ExprKind::Call(name, arguments) => {
                let values = self.arguments(name, arguments, span, depth)?;
                self.call(name, values, span)
            }
            ExprKind::Unary(op, operand) => {
                let value = self.eval(operand, depth + 1)?;
                unary(*op, value, span)
            }
            ExprKind::Binary(op, left, right) => {
                let left = self.eval(left, depth + 1)?;
                let right = self.eval(right, depth + 1)?;
                binary(*op, left, right, span)
            }
        }
    }

    /// An index of a system variable: a name that is neither a variable nor an axis is passed
    /// as its text, for the front end to read (the frame components of `$P_UIFR[1,X,TR]`: TR,
    /// FI, RT, SC, MI).
    fn system_index(&mut self, index: &Expr, depth: u32) -> Result<Value, Alarm> {
        match &index.kind {
            ExprKind::Name(name)
                if !self.variables.is_defined(name)
                    && !self.env.is_axis(name)
                    && !matches!(&**name, "TRUE" | "FALSE")
                    && !name.starts_with('$') =>
            {
                Ok(Value::Str(name.to_string()))
            }
            _ => self.eval(index, depth),
        }
    }

    fn name(&mut self, name: &str, span: Span) -> Result<Value, Alarm> {
        match name {
            "TRUE" => return Ok(Value::Bool(true)),
            "FALSE" => return Ok(Value::Bool(false)),
            // The circle constant is the language's, not the machine's (PGsl 7.1 example,
            // L2476-2500: `FGREF[A]=360/(2*$PI)`).
            "$PI" => return Ok(Value::Real(std::f64::consts::PI)),
            _ => {}
        }
        if name.starts_with('$') {
            let value = self.env.system_variable(name, &[], span)?;
            return checked(value, span);
        }
        if !self.variables.is_defined(name) && self.env.is_axis(name) {
            return Ok(Value::Axis(name.to_string()));
        }
        // CYCLE832's machining types by name, where the program has no variable of that name
        // (looked up only then: the common path pays nothing).
        self.variables
            .read(name, &[], span)
            .or_else(|alarm| super::path_control::constant(name).ok_or(alarm))
    }

    fn arguments(
        &mut self,
        name: &str,
        arguments: &[Option<Expr>],
        span: Span,
        depth: u32,
    ) -> Result<Vec<Option<Value>>, Alarm> {
        // Too many arguments is the callee's alarm; this bounds the work before it.
        const MOST: usize = 64;
        if arguments.len() > MOST {
            return Err(syntax(
                span,
                format!("{name} has more than {MOST} arguments"),
            ));
        }
        arguments
            .iter()
            .map(|argument| {
                argument
                    .as_ref()
                    .map(|expr| self.eval(expr, depth + 1))
                    .transpose()
            })
            .collect()
    }

    /// Exactly `N` arguments, all given.
    fn fixed<const N: usize>(
        &mut self,
        name: &str,
        arguments: &[Option<Expr>],
        span: Span,
        depth: u32,
    ) -> Result<[Value; N], Alarm> {
        let values = self.arguments(name, arguments, span, depth)?;
        exactly::<N>(name, values, span)
    }

    fn call(&mut self, name: &str, args: Vec<Option<Value>>, span: Span) -> Result<Value, Alarm> {
        if let Some(result) = arithmetic(name, &args, span) {
            return result;
        }
        if let Some(result) = string_function(name, &args, span) {
            return result;
        }
        match name {
            "AXNAME" => {
                let [text] = exactly::<1>(name, args, span)?;
                let text = text_of(name, text, span)?.to_ascii_uppercase();
                if self.env.is_axis(&text) {
                    Ok(Value::Axis(text))
                } else {
                    Err(Alarm::error(
                        AlarmCode::AxisNotOnMachine,
                        span,
                        format!("AXNAME: \"{text}\" is not an axis of this machine"),
                    ))
                }
            }
            "SET" | "REP" => Err(syntax(
                span,
                format!("{name}(..) stands only after the `=` of an array's DEF or assignment"),
            )),
            _ => match self.env.call(name, &args, span) {
                Some(result) => result.and_then(|value| checked(value, span)),
                None => Err(Alarm::not_supported(
                    span,
                    &format!("the function {name}"),
                    None,
                )),
            },
        }
    }
}

/// A value from the environment: a REAL must be finite.
fn checked(value: Value, span: Span) -> Result<Value, Alarm> {
    match value {
        Value::Real(x) => Value::real(x, span),
        other => Ok(other),
    }
}

fn unary(op: UnaryOp, value: Value, span: Span) -> Result<Value, Alarm> {
    match op {
        UnaryOp::Minus => match value {
            Value::Int(i) => Ok(i
                .checked_neg()
                .map_or(Value::Real(-f64::from(i)), Value::Int)),
            Value::Real(x) => Ok(Value::Real(-x)),
            Value::Bool(_) | Value::Char(_) => Ok(Value::Int(-int_operand(value, "-", span)?)),
            other => Err(operand_type("-", &other, span)),
        },
        UnaryOp::Not => Ok(Value::Bool(!bool_operand(value, "NOT", span)?)),
        UnaryOp::BitNot => Ok(Value::Int(!int_operand(value, "B_NOT", span)?)),
    }
}

fn binary(op: BinaryOp, left: Value, right: Value, span: Span) -> Result<Value, Alarm> {
    use BinaryOp::*;
    match op {
        Equal | NotEqual | Less | Greater | LessEqual | GreaterEqual => {
            compare(op, &left, &right, span)
        }
        Chain => chain(left, right, span),
        Or | Xor | And => {
            let symbol = symbol(op);
            let (a, b) = (
                bool_operand(left, symbol, span)?,
                bool_operand(right, symbol, span)?,
            );
            Ok(Value::Bool(match op {
                Or => a || b,
                Xor => a != b,
                _ => a && b,
            }))
        }
        BitOr | BitXor | BitAnd => {
            let symbol = symbol(op);
            let (a, b) = (
                int_operand(left, symbol, span)?,
                int_operand(right, symbol, span)?,
            );
            Ok(Value::Int(match op {
                BitOr => a | b,
                BitXor => a ^ b,
                _ => a & b,
            }))
        }
        Add | Subtract | Multiply | Divide | IntDivide | Modulo => {
            arithmetic_op(op, left, right, span)
        }
    }
}

/// `+ - * / DIV MOD`. INT with INT stays INT where the result fits (**choice**: beyond INT's
/// range the result is the REAL, nothing is lost); `/` is always REAL (PGAsl: 3/4 = 0.75);
/// `DIV` of two INTs is INT (3 DIV 4 = 0), of a REAL the quotient truncated as a REAL;
/// `MOD` keeps the dividend's sign, and takes REALs too (**choice**: PGAsl names INT).
fn arithmetic_op(op: BinaryOp, left: Value, right: Value, span: Span) -> Result<Value, Alarm> {
    let symbol = symbol(op);
    let ints = match (&left, &right) {
        (Value::Int(_) | Value::Char(_), Value::Int(_) | Value::Char(_)) => Some((
            int_operand(left.clone(), symbol, span)?,
            int_operand(right.clone(), symbol, span)?,
        )),
        _ => None,
    };
    let a = number_operand(&left, symbol, span)?;
    let b = number_operand(&right, symbol, span)?;
    let divides = matches!(
        op,
        BinaryOp::Divide | BinaryOp::IntDivide | BinaryOp::Modulo
    );
    if divides && b == 0.0 {
        return Err(Alarm::error(
            AlarmCode::MacroArithmetic,
            span,
            format!("division by zero ({symbol})"),
        )
        .with_help("check the divisor's variables: the control stops here too"));
    }
    let whole = ints.and_then(|(i, j)| match op {
        BinaryOp::Add => i.checked_add(j),
        BinaryOp::Subtract => i.checked_sub(j),
        BinaryOp::Multiply => i.checked_mul(j),
        BinaryOp::IntDivide => i.checked_div(j),
        BinaryOp::Modulo => i.checked_rem(j),
        _ => None,
    });
    if let Some(i) = whole {
        return Ok(Value::Int(i));
    }
    let x = match op {
        BinaryOp::Add => a + b,
        BinaryOp::Subtract => a - b,
        BinaryOp::Multiply => a * b,
        BinaryOp::Divide => a / b,
        BinaryOp::IntDivide => (a / b).trunc(),
        _ => a % b,
    };
    Value::real(x, span)
}

/// The comparisons give BOOL. Numbers (INT, REAL, BOOL, CHAR) compare by value with
/// [`COMPARISON_TOLERANCE`]; strings (and a CHAR with a string) by their characters' codes;
/// axes only with `==` and `<>`.
fn compare(op: BinaryOp, left: &Value, right: &Value, span: Span) -> Result<Value, Alarm> {
    let ordering = match (left, right) {
        (Value::Str(_) | Value::Char(_), Value::Str(_)) | (Value::Str(_), Value::Char(_)) => {
            Some(left.to_text().as_bytes().cmp(right.to_text().as_bytes()))
        }
        (Value::Axis(a), Value::Axis(b)) => {
            if !matches!(op, BinaryOp::Equal | BinaryOp::NotEqual) {
                return Err(operand_type(symbol(op), left, span));
            }
            Some(if a == b {
                Ordering::Equal
            } else {
                Ordering::Less
            })
        }
        _ => match (left.as_f64(), right.as_f64()) {
            (Some(a), Some(b)) => Some(numeric_order(a, b)),
            _ => None,
        },
    };
    let Some(ordering) = ordering else {
        return Err(Alarm::error(
            AlarmCode::MacroArithmetic,
            span,
            format!(
                "{} and {} cannot be compared",
                kind_name(left.type_of()),
                kind_name(right.type_of())
            ),
        )
        .with_help("compare numbers with numbers, strings with strings, axes with axes"));
    };
    Ok(Value::Bool(match op {
        BinaryOp::Equal => ordering == Ordering::Equal,
        BinaryOp::NotEqual => ordering != Ordering::Equal,
        BinaryOp::Less => ordering == Ordering::Less,
        BinaryOp::Greater => ordering == Ordering::Greater,
        BinaryOp::LessEqual => ordering != Ordering::Greater,
        _ => ordering != Ordering::Less,
    }))
}

fn numeric_order(a: f64, b: f64) -> Ordering {
    if (a - b).abs() <= COMPARISON_TOLERANCE * a.abs().max(b.abs()) {
        Ordering::Equal
    } else if a < b {
        Ordering::Less
    } else {
        Ordering::Greater
    }
}

/// `<<`: both operands as text (INT, REAL, BOOL, CHAR, STRING: PGAsl; `"..."<<R12`, L9806).
fn chain(left: Value, right: Value, span: Span) -> Result<Value, Alarm> {
    for value in [&left, &right] {
        if matches!(value, Value::Axis(_)) {
            return Err(operand_type("<<", value, span)
                .with_help("AXSTRING(axis) gives an axis' name as a string"));
        }
    }
    let mut text = left.to_text();
    text.push_str(&right.to_text());
    if text.len() > MAX_STRING {
        return Err(Alarm::error(
            AlarmCode::MacroArithmetic,
            span,
            format!(
                "the chained string has {} characters, more than {MAX_STRING}",
                text.len()
            ),
        ));
    }
    Ok(Value::Str(text))
}

fn symbol(op: BinaryOp) -> &'static str {
    use BinaryOp::*;
    match op {
        Equal => "==",
        NotEqual => "<>",
        Less => "<",
        Greater => ">",
        LessEqual => "<=",
        GreaterEqual => ">=",
        Chain => "<<",
        Or => "OR",
        Xor => "XOR",
        And => "AND",
        BitOr => "B_OR",
        BitXor => "B_XOR",
        BitAnd => "B_AND",
        Add => "+",
        Subtract => "-",
        Multiply => "*",
        Divide => "/",
        IntDivide => "DIV",
        Modulo => "MOD",
    }
}

/// An operand of an arithmetic operator: INT, REAL, BOOL or CHAR.
fn number_operand(value: &Value, symbol: &str, span: Span) -> Result<f64, Alarm> {
    value
        .as_f64()
        .ok_or_else(|| operand_type(symbol, value, span))
}

/// An operand of a logic operator: any number (not 0 is TRUE) or BOOL (PGAsl).
fn bool_operand(value: Value, symbol: &str, span: Span) -> Result<bool, Alarm> {
    match value {
        Value::Str(_) | Value::Axis(_) => Err(operand_type(symbol, &value, span)),
        other => Ok(other.as_f64().is_some_and(|x| x != 0.0)),
    }
}

/// An operand of a bit operator: INT, CHAR, BOOL, or a REAL rounded to INT (**choice**: R
/// parameters are REAL and programs apply B_AND to them).
fn int_operand(value: Value, symbol: &str, span: Span) -> Result<i32, Alarm> {
    match value {
        Value::Int(i) => Ok(i),
        Value::Str(_) | Value::Axis(_) => Err(operand_type(symbol, &value, span)),
        other => int_of(other.as_f64().unwrap_or(0.0), span),
    }
}

fn operand_type(symbol: &str, value: &Value, span: Span) -> Alarm {
    Alarm::error(
        AlarmCode::MacroArithmetic,
        span,
        format!(
            "`{symbol}` cannot take a {} value",
            kind_name(value.type_of())
        ),
    )
    .with_help("convert the value first (NUMBER, AXSTRING, or `<<` for text)")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::interp::sinumerik::value::Type;
    use crate::source::FileId;
    use crate::syntax::sinumerik::{parse_block, Value as WordValue};

    /// Axes X, Y, Z and A1; `$AA_IW[X]` is 12.5, `$P_TOOLNO` 7, `$NAN` not a number; the
    /// front end's own function TWICE(x).
    struct Machine;

    impl Environment for Machine {
        fn system_variable(
            &mut self,
            name: &str,
            indices: &[Value],
            span: Span,
        ) -> Result<Value, Alarm> {
            match (name, indices) {
                ("$AA_IW", [Value::Axis(axis)]) if axis == "X" => Ok(Value::Real(12.5)),
                ("$P_UIFR", [Value::Int(1), Value::Axis(axis), Value::Str(part)])
                    if axis == "Y" && part == "TR" =>
                {
                    Ok(Value::Real(-4.0))
                }
                ("$P_TOOLNO", []) => Ok(Value::Int(7)),
                ("$NAN", []) => Ok(Value::Real(f64::NAN)),
                _ => Err(Alarm::error(AlarmCode::BadVariable, span, name)),
            }
        }

        fn is_axis(&self, name: &str) -> bool {
            ["X", "Y", "Z", "A1"].contains(&name)
        }

        fn call(
            &mut self,
            name: &str,
            arguments: &[Option<Value>],
            _span: Span,
        ) -> Option<Result<Value, Alarm>> {
            match (name, arguments) {
                ("TWICE", [Some(Value::Int(i))]) => Some(Ok(Value::Int(2 * i))),
                _ => None,
            }
        }
    }

    /// The expression of `R1=<text>`, read by the SINUMERIK block reader.
    fn expr(text: &str) -> Expr {
        let block = parse_block(format!("R1={text}").as_bytes(), FileId(0), 1, 0);
        assert_eq!(block.alarm, None, "{text}");
        match block.words.into_iter().next().map(|w| w.value) {
            Some(WordValue::Expression(expr)) => expr,
            other => panic!("`{text}` is no assignment: {other:?}"),
        }
    }

    fn eval_in(variables: &Variables, text: &str) -> Result<Value, Alarm> {
        evaluate(&expr(text), variables, &mut Machine)
    }

    fn eval(text: &str) -> Result<Value, Alarm> {
        eval_in(&Variables::default(), text)
    }

    fn check(text: &str, expected: Value) {
        assert_eq!(eval(text), Ok(expected), "{text}");
    }

    /// A REAL result within 1e-9 of `expected`.
    fn check_real(text: &str, expected: f64) {
        match eval(text) {
            Ok(Value::Real(x)) => assert!((x - expected).abs() < 1e-9, "{text} = {x}"),
            other => panic!("{text} gave {other:?}, not REAL {expected}"),
        }
    }

    fn alarm(text: &str) -> Alarm {
        eval(text).expect_err(text)
    }

    fn text(s: &str) -> Value {
        Value::Str(s.into())
    }

    fn span() -> Span {
        Span::new(FileId(0), 1, 0..1)
    }

    #[test]
    fn multiplication_binds_tighter_than_addition() {
        // 3*4 first: 2+12.
        check("2+3*4", Value::Int(14));
        check("(2+3)*4", Value::Int(20));
        // Left to right within a level: (10-4)-3, (2*3) MOD 4 = 6 MOD 4.
        check("10-4-3", Value::Int(3));
        check("2*3 MOD 4", Value::Int(2));
        check("-2*3", Value::Int(-6));
        check("-3+5", Value::Int(2));
    }

    #[test]
    fn division_is_always_real() {
        // PGAsl: 3/4 = 0.75 though both are INT.
        check("3/4", Value::Real(0.75));
        check("4/2", Value::Real(2.0));
    }

    #[test]
    fn div_is_integer_division_truncating_toward_zero() {
        // PGAsl: 3 DIV 4 = 0; -7/2 = -3.5 truncated to -3.
        check("3 DIV 4", Value::Int(0));
        check("-7 DIV 2", Value::Int(-3));
        check("7.5 DIV 2", Value::Real(3.0));
    }

    #[test]
    fn mod_keeps_the_dividends_sign() {
        // 3 MOD 4 = 3 (PGAsl); -7 = -2*3 - 1; 7.5 = 3*2 + 1.5.
        check("3 MOD 4", Value::Int(3));
        check("-7 MOD 3", Value::Int(-1));
        check("7.5 MOD 2", Value::Real(1.5));
    }

    #[test]
    fn int_arithmetic_beyond_the_range_becomes_real() {
        // 2000000000 + 2000000000 = 4e9 does not fit 32 bits.
        check("2000000000+2000000000", Value::Real(4.0e9));
        check("2.5*2", Value::Real(5.0));
    }

    #[test]
    fn division_by_zero_alarms() {
        for text in ["1/0", "5 DIV 0", "5 MOD 0", "1/(2-2)"] {
            let alarm = alarm(text);
            assert_eq!(alarm.code, AlarmCode::MacroArithmetic, "{text}");
            assert!(alarm.message.contains("division by zero"), "{text}");
        }
    }

    #[test]
    fn comparisons_bind_loosest_and_give_bool() {
        check("1+1==2", Value::Bool(true));
        check("3<>3", Value::Bool(false));
        check("2<3", Value::Bool(true));
        check("2>3", Value::Bool(false));
        check("3<=3", Value::Bool(true));
        check("2>=3", Value::Bool(false));
        // The tolerance: 0.1+0.2 is 0.30000000000000004 in binary.
        check("0.1+0.2==0.3", Value::Bool(true));
        check("0.1+0.2>0.3", Value::Bool(false));
    }

    #[test]
    fn unparenthesised_comparisons_with_and_compare_the_and() {
        // R1=1, R2=2. `R1==1 AND R2==2` is (R1 == (1 AND R2)) == 2: 1 AND 2 is TRUE, R1==TRUE
        // is 1==1, TRUE; TRUE==2 is 1==2, FALSE. With parentheses it is TRUE.
        let mut variables = Variables::default();
        assign(&mut variables, "R1", &[], Value::Int(1), span()).unwrap();
        assign(&mut variables, "R2", &[], Value::Int(2), span()).unwrap();
        assert_eq!(
            eval_in(&variables, "R1==1 AND R2==2"),
            Ok(Value::Bool(false))
        );
        assert_eq!(
            eval_in(&variables, "(R1==1) AND (R2==2)"),
            Ok(Value::Bool(true))
        );
    }

    #[test]
    fn logic_operators_bind_not_and_xor_or_in_that_order() {
        // AND before XOR: 1 XOR (1 AND 0) = TRUE; (1 XOR 1) AND 0 would be FALSE.
        check("1 XOR 1 AND 0", Value::Bool(true));
        // XOR before OR: 1 OR (1 XOR 1) = TRUE; (1 OR 1) XOR 1 would be FALSE.
        check("1 OR 1 XOR 1", Value::Bool(true));
        // NOT before ==: (NOT 1) == 0 is FALSE == 0.
        check("NOT 1==0", Value::Bool(true));
        check("NOT FALSE", Value::Bool(true));
        check("TRUE AND 0.5", Value::Bool(true));
    }

    #[test]
    fn bit_operators_work_on_integers_and_bind_and_xor_or() {
        // 1100 & 1010 = 1000, 1100 | 0011 = 1111, 1100 ^ 1010 = 0110.
        check("12 B_AND 10", Value::Int(8));
        check("12 B_OR 3", Value::Int(15));
        check("12 B_XOR 10", Value::Int(6));
        check("B_NOT 0", Value::Int(-1));
        // B_AND before B_OR: 4 | (2 & 1) = 4; (4 | 2) & 1 would be 0.
        check("4 B_OR 2 B_AND 1", Value::Int(4));
        // B_AND before B_XOR: 5 ^ (1 & 3) = 4; (5 ^ 1) & 3 would be 0.
        check("5 B_XOR 1 B_AND 3", Value::Int(4));
        // + before B_AND: (1+2) & 6 = 2; 1 + (2 & 6) would be 3.
        check("1+2 B_AND 6", Value::Int(2));
        // Constants of PGsl 15.6: 'H0F' = 15, 'B1010' = 10.
        check("'H0F' B_AND 'B1010'", Value::Int(10));
        // B_AND binds tighter than AND: 1 AND (2 B_AND 1) = 1 AND 0.
        check("1 AND 2 B_AND 1", Value::Bool(false));
    }

    #[test]
    fn chaining_converts_its_operands_to_text() {
        // Arithmetic binds tighter: 5*2 first.
        check("\"R12=\"<<5*2", text("R12=10"));
        check("\"A\"<<1.5<<TRUE", text("A1.5TRUE"));
        // Comparison is looser than <<: ("AB"<<"C") == "ABC".
        check("\"AB\"<<\"C\"==\"ABC\"", Value::Bool(true));
        assert!(alarm("\"A\"<<X").help.unwrap().contains("AXSTRING"));
    }

    #[test]
    fn message_of_the_manual_chains_an_r_parameter() {
        // PGsl 14.1 (L9806, example B MSG): MSG("..."<<R12) with R12 = 20.5.
        let mut variables = Variables::default();
        assign(&mut variables, "R12", &[], Value::Real(20.5), span()).unwrap();
        assert_eq!(
            eval_in(&variables, "\"check position of X axis \"<<R12"),
            Ok(text("check position of X axis 20.5"))
        );
    }

    #[test]
    fn strings_compare_by_character_codes() {
        check("\"ABC\"==\"ABC\"", Value::Bool(true));
        check("\"ABC\"<\"ABD\"", Value::Bool(true));
        check("\"ABC\"<>\"abc\"", Value::Bool(true));
        let alarm = alarm("\"1\"==1");
        assert_eq!(alarm.code, AlarmCode::MacroArithmetic);
        assert!(alarm.message.contains("cannot be compared"));
    }

    #[test]
    fn operands_of_the_wrong_type_alarm() {
        for text in [
            "\"A\"+1",
            "NOT \"A\"",
            "X+1",
            "-\"A\"",
            "\"A\" B_AND 1",
            "X AND 1",
        ] {
            let alarm = alarm(text);
            assert_eq!(alarm.code, AlarmCode::MacroArithmetic, "{text}");
        }
    }

    #[test]
    fn names_resolve_to_constants_system_variables_r_parameters_and_axes() {
        check("TRUE", Value::Bool(true));
        check("FALSE", Value::Bool(false));
        check("$AA_IW[X]+0.5", Value::Real(13.0));
        check("$P_TOOLNO", Value::Int(7));
        check("$P_UIFR[1,Y,TR]", Value::Real(-4.0));
        check("X", Value::Axis("X".into()));
        check("X==X", Value::Bool(true));
        check("X<>A1", Value::Bool(true));
        assert_eq!(alarm("X<Y").code, AlarmCode::MacroArithmetic);
        check("R99", Value::Real(0.0));
    }

    #[test]
    fn pi_is_a_constant_of_the_language() {
        // Example sinumerik-a/37-fgroup-fgref.mpf N300: 360/(2*pi) = 57.29577951 (57.296).
        check_real("360/(2*$PI)", 57.295_779_513_082_32);
    }

    #[test]
    fn r_parameters_by_number_and_by_index() {
        // R5 = 2.5, R[2+3] is R5.
        let mut variables = Variables::default();
        assign(&mut variables, "R5", &[], Value::Real(2.5), span()).unwrap();
        assert_eq!(eval_in(&variables, "R5*2"), Ok(Value::Real(5.0)));
        assert_eq!(eval_in(&variables, "R[2+3]"), Ok(Value::Real(2.5)));
        let alarm = eval_in(&variables, "R[100]").unwrap_err();
        assert_eq!(alarm.code, AlarmCode::BadVariable);
        assert!(alarm.message.contains("R0 to R99"));
    }

    #[test]
    fn the_corpus_arithmetic_of_r_parameters() {
        // dubovikov: R17=R7/(1+TRUNC(R7/R17)) with R7=10, R17=3: TRUNC(3.33)=3, 10/4 = 2.5.
        // R104=ROUNDUP (R103/(R17*(-1))) with R103=10, R17=-4: 10/4 = 2.5 rounds up to 3.
        // Those programs use R100-R109: their machines have more than the standard 100.
        let mut variables = Variables::new(200);
        assign(&mut variables, "R7", &[], Value::Int(10), span()).unwrap();
        assign(&mut variables, "R17", &[], Value::Int(3), span()).unwrap();
        assert_eq!(
            eval_in(&variables, "R7/(1+TRUNC(R7/R17))"),
            Ok(Value::Real(2.5))
        );
        assign(&mut variables, "R103", &[], Value::Int(10), span()).unwrap();
        assign(&mut variables, "R17", &[], Value::Int(-4), span()).unwrap();
        assert_eq!(
            eval_in(&variables, "ROUNDUP (R103/(R17*(-1)))"),
            Ok(Value::Real(3.0))
        );
    }

    #[test]
    fn unknown_names_alarm_with_their_span() {
        let alarm = alarm("2*UNKNOWN");
        assert_eq!(alarm.code, AlarmCode::BadVariable);
        assert!(alarm.message.contains("UNKNOWN"));
        // `R1=2*UNKNOWN`: the name is bytes 5 to 12.
        let span = alarm.span.unwrap();
        assert_eq!((span.start, span.end), (5, 12));
    }

    #[test]
    fn trigonometry_is_in_degrees() {
        check_real("SIN(30)", 0.5);
        check_real("COS(60)", 0.5);
        check_real("TAN(45)", 1.0);
        check_real("ASIN(0.5)", 30.0);
        check_real("ACOS(0.5)", 60.0);
        // ATAN2(y, x): (1, 1) is 45 degrees, (1, -1) 135, (-1, 0) -90.
        check_real("ATAN2(1,1)", 45.0);
        check_real("ATAN2(1,-1)", 135.0);
        check_real("ATAN2(-1,0)", -90.0);
        // An example of PGsl 2.2.3 (L586): X=10*(5+SIN(37.5)), sin 37.5 = 0.608761429.
        check_real("10*(5+SIN(37.5))", 56.087_614_290_087_2);
    }

    #[test]
    fn arithmetic_functions() {
        check_real("SQRT(16)", 4.0);
        check_real("ABS(-3.5)", 3.5);
        check_real("POT(3)", 9.0);
        check_real("TRUNC(-2.7)", -2.0);
        check_real("ROUND(2.5)", 3.0);
        check_real("ROUND(-2.5)", -3.0);
        check_real("ROUND(2.49)", 2.0);
        check_real("ROUNDUP(3.1)", 4.0);
        check_real("ROUNDUP(-3.1)", -3.0);
        check_real("ROUNDUP(3)", 3.0);
        check_real("LN(EXP(2))", 2.0);
        check_real("EXP(0)", 1.0);
        check_real("MINVAL(3,-1)", -1.0);
        check_real("MAXVAL(3,-1)", 3.0);
    }

    #[test]
    fn bound_clamps_to_its_range() {
        // In range: the value itself (tables §1.2); outside: the limit passed.
        check_real("BOUND(0,10,5)", 5.0);
        check_real("BOUND(0,10,12)", 10.0);
        check_real("BOUND(0,10,-2)", 0.0);
        assert_eq!(alarm("BOUND(10,0,5)").code, AlarmCode::MacroArithmetic);
    }

    #[test]
    fn functions_outside_their_domain_alarm() {
        for text in [
            "SQRT(-1)",
            "LN(0)",
            "ASIN(2)",
            "ACOS(-1.5)",
            "EXP(1000)",
            "POT(1EX200)",
        ] {
            let alarm = alarm(text);
            assert_eq!(alarm.code, AlarmCode::MacroArithmetic, "{text}");
        }
        assert!(alarm("SQRT(-1)").help.unwrap().contains("0 or more"));
    }

    #[test]
    fn functions_with_wrong_arguments_alarm() {
        for text in [
            "SIN()",
            "SIN(1,2)",
            "ATAN2(1,)",
            "STRLEN(\"A\",\"B\")",
            "SUBSTR(\"A\")",
        ] {
            assert_eq!(alarm(text).code, AlarmCode::MacroSyntax, "{text}");
        }
        assert_eq!(alarm("SIN(\"A\")").code, AlarmCode::MacroArithmetic);
        assert_eq!(alarm("STRLEN(1)").code, AlarmCode::MacroArithmetic);
    }

    #[test]
    fn unknown_functions_are_not_supported_and_named() {
        let alarm = alarm("FOO(1)");
        assert_eq!(alarm.code, AlarmCode::NotSupportedYet);
        assert!(alarm.message.contains("FOO"));
        // The environment's own function comes before the alarm.
        check("TWICE(21)", Value::Int(42));
    }

    #[test]
    fn string_length_and_searches_count_from_zero() {
        check("STRLEN(\"ABC\")", Value::Int(3));
        check("STRLEN(\"\")", Value::Int(0));
        // "ABCABC": the first C is at 2, the last at 5.
        check("INDEX(\"ABCABC\",\"C\")", Value::Int(2));
        check("RINDEX(\"ABCABC\",\"C\")", Value::Int(5));
        check("INDEX(\"ABC\",\"Z\")", Value::Int(-1));
        // F at 5, D at 3: the first of either is D.
        check("MINDEX(\"ABCDEF\",\"FD\")", Value::Int(3));
        check("MINDEX(\"ABC\",\"XY\")", Value::Int(-1));
        // A-C-K-N-O-W: NOW starts at 3.
        check("MATCH(\"ACKNOWLEDGE\",\"NOW\")", Value::Int(3));
        check("MATCH(\"ABC\",\"X\")", Value::Int(-1));
        assert_eq!(
            alarm("INDEX(\"ABC\",\"BC\")").code,
            AlarmCode::MacroArithmetic
        );
    }

    #[test]
    fn substr_takes_a_start_and_a_count() {
        // Tables §7.6, the manual's example in its German original: in "QUITTUNG: 10 bis 99"
        // index 10 is the "1" (Q=0 ... ':'=8, ' '=9), two characters give "10".
        check("SUBSTR(\"QUITTUNG: 10 bis 99\",10,2)", text("10"));
        check("SUBSTR(\"ABC\",1)", text("BC"));
        check("SUBSTR(\"ABC\",1,9)", text("BC"));
        check("SUBSTR(\"ABC\",5,2)", text(""));
        assert_eq!(
            alarm("SUBSTR(\"ABC\",-1,2)").code,
            AlarmCode::MacroArithmetic
        );
    }

    #[test]
    fn case_conversion() {
        check("TOUPPER(\"Ab1_x\")", text("AB1_X"));
        check("TOLOWER(\"Ab1_X\")", text("ab1_x"));
    }

    #[test]
    fn number_reads_the_controls_notation() {
        check("NUMBER(\"12.5\")", Value::Real(12.5));
        // -1.5EX3 = -1.5 * 10^3.
        check("NUMBER(\" -1.5EX3 \")", Value::Real(-1500.0));
        check("NUMBER(\".25\")", Value::Real(0.25));
        check("ISNUMBER(\"3\")", Value::Bool(true));
        check("ISNUMBER(\"12A\")", Value::Bool(false));
        check("ISNUMBER(\"\")", Value::Bool(false));
        check("ISNUMBER(\"1.2.3\")", Value::Bool(false));
        let alarm = alarm("NUMBER(\"12A\")");
        assert_eq!(alarm.code, AlarmCode::MacroArithmetic);
        assert!(alarm.help.unwrap().contains("ISNUMBER"));
    }

    #[test]
    fn axis_names_and_strings_convert_both_ways() {
        check("AXNAME(\"x\")", Value::Axis("X".into()));
        check("AXSTRING(A1)", text("A1"));
        check("AXSTRING(AXNAME(\"Y\"))<<\"=\"", text("Y="));
        assert_eq!(alarm("AXNAME(\"Q\")").code, AlarmCode::AxisNotOnMachine);
        assert_eq!(alarm("AXSTRING(1)").code, AlarmCode::MacroArithmetic);
    }

    #[test]
    fn set_and_rep_outside_an_assignment_alarm() {
        assert_eq!(alarm("SET(1,2)+1").code, AlarmCode::MacroSyntax);
        assert_eq!(alarm("REP(1)").code, AlarmCode::MacroSyntax);
    }

    #[test]
    fn not_a_number_never_escapes_the_environment() {
        let alarm = alarm("$NAN+1");
        assert_eq!(alarm.code, AlarmCode::MacroArithmetic);
        assert_eq!(eval("$P_UNKNOWN").unwrap_err().code, AlarmCode::BadVariable);
    }

    #[test]
    fn a_very_deep_expression_alarms_instead_of_overflowing() {
        // 3000 additions parse into a left branch 3000 deep.
        let text = format!("1{}", "+1".repeat(3000));
        let alarm = eval(&text).unwrap_err();
        assert_eq!(alarm.code, AlarmCode::MacroLimit);
        // 500 are evaluated: 1 + 500.
        let text = format!("1{}", "+1".repeat(500));
        assert_eq!(eval(&text), Ok(Value::Int(501)));
    }

    #[test]
    fn assignments_convert_to_the_declared_type() {
        let mut variables = Variables::default();
        variables
            .declare("COUNT", Type::Int, &[], Init::Default, span())
            .unwrap();
        // 7.5 rounds to 8 (REAL to INT, half away from zero).
        assign(&mut variables, "COUNT", &[], Value::Real(7.5), span()).unwrap();
        assert_eq!(eval_in(&variables, "COUNT"), Ok(Value::Int(8)));
        let alarm = assign(&mut variables, "COUNT", &[], text("A"), span()).unwrap_err();
        assert_eq!(alarm.code, AlarmCode::MacroArithmetic);
        // R parameters are REAL.
        assign(&mut variables, "R3", &[], Value::Bool(true), span()).unwrap();
        assert_eq!(eval_in(&variables, "R3"), Ok(Value::Real(1.0)));
    }

    /// Runs `NAME[i]=expr` (or `NAME=expr`) as the front end would.
    fn run_assignment(variables: &mut Variables, line: &str) -> Result<(), Alarm> {
        let block = parse_block(line.as_bytes(), FileId(0), 1, 0);
        assert_eq!(block.alarm, None, "{line}");
        let word = block.words.into_iter().next().unwrap();
        match word.value {
            WordValue::Indexed(indices, Some(value)) => assign_expr(
                variables,
                &mut Machine,
                &word.address,
                &indices,
                &value,
                word.span,
            ),
            WordValue::Expression(value) => assign_expr(
                variables,
                &mut Machine,
                &word.address,
                &[],
                &value,
                word.span,
            ),
            other => panic!("{line}: {other:?}"),
        }
    }

    #[test]
    fn assignments_with_set_and_rep_fill_from_the_element_on() {
        // DEF INT ARR[5]=REP(7); ARR[2]=SET(1,2) gives 7 7 1 2 7; ARR[3]=REP(9) 7 7 1 9 9.
        let mut variables = Variables::default();
        let init = initialiser(&expr("REP(7)"), &variables, &mut Machine).unwrap();
        variables
            .declare("ARR", Type::Int, &[Value::Int(5)], init, span())
            .unwrap();
        run_assignment(&mut variables, "ARR[2]=SET(1,2)").unwrap();
        let all = |v: &Variables| -> Vec<Value> {
            (0..5)
                .map(|i| v.read("ARR", &[Value::Int(i)], span()).unwrap())
                .collect()
        };
        let ints = |xs: [i32; 5]| xs.map(Value::Int).to_vec();
        assert_eq!(all(&variables), ints([7, 7, 1, 2, 7]));
        run_assignment(&mut variables, "ARR[3]=REP(9)").unwrap();
        assert_eq!(all(&variables), ints([7, 7, 1, 9, 9]));
        run_assignment(&mut variables, "ARR[R1+1]=ARR[0]*6").unwrap();
        assert_eq!(all(&variables), ints([7, 42, 1, 9, 9]));
        // Three values from element 3 on: only 2 remain.
        let alarm = run_assignment(&mut variables, "ARR[3]=SET(1,2,3)").unwrap_err();
        assert_eq!(alarm.code, AlarmCode::MacroArithmetic);
    }

    #[test]
    fn r_parameters_are_assigned_by_index() {
        // R1=2, then R[R1+3]=4.5 writes R5.
        let mut variables = Variables::default();
        run_assignment(&mut variables, "R1=2").unwrap();
        run_assignment(&mut variables, "R[R1+3]=4.5").unwrap();
        assert_eq!(eval_in(&variables, "R5"), Ok(Value::Real(4.5)));
    }

    #[test]
    fn var_arguments_name_places_and_nothing_else() {
        // P(ARR[R1], R7) with R1 = 1: the places of ARR[1] and R7; a constant or a sum is
        // no place.
        let mut variables = Variables::default();
        variables
            .declare("ARR", Type::Int, &[Value::Int(2)], Init::Default, span())
            .unwrap();
        run_assignment(&mut variables, "R1=1").unwrap();
        let element = place_of(&expr("ARR[R1]"), &variables, &mut Machine).unwrap();
        variables.set(&element, Value::Int(6), span()).unwrap();
        assert_eq!(eval_in(&variables, "ARR[1]"), Ok(Value::Int(6)));
        assert!(place_of(&expr("R7"), &variables, &mut Machine).is_ok());
        for text in ["5", "R1+1", "$P_TOOLNO"] {
            let alarm = place_of(&expr(text), &variables, &mut Machine).unwrap_err();
            assert_eq!(alarm.code, AlarmCode::BadVariable, "{text}");
        }
    }

    #[test]
    fn set_and_rep_need_their_values() {
        let variables = Variables::default();
        for text in ["SET()", "SET(1,,3)", "REP()", "REP(1,2)"] {
            let alarm = initialiser(&expr(text), &variables, &mut Machine).unwrap_err();
            assert_eq!(alarm.code, AlarmCode::MacroSyntax, "{text}");
        }
        assert_eq!(
            initialiser(&expr("SET(1,2)"), &variables, &mut Machine),
            Ok(Init::Set(vec![Value::Int(1), Value::Int(2)]))
        );
    }

    #[test]
    fn a_chained_string_longer_than_200_characters_alarms() {
        // 150 + 60 = 210 characters.
        let long = format!("\"{}\"<<\"{}\"", "A".repeat(150), "B".repeat(60));
        let alarm = alarm(&long);
        assert_eq!(alarm.code, AlarmCode::MacroArithmetic);
        assert!(alarm.message.contains("210 characters"));
        let fits = format!("\"{}\"<<\"{}\"", "A".repeat(150), "B".repeat(50));
        assert!(eval(&fits).is_ok());
    }

    #[test]
    fn a_call_with_too_many_arguments_alarms_before_evaluating_them() {
        let text = format!("MAXVAL({})", vec!["1"; 65].join(","));
        assert_eq!(alarm(&text).code, AlarmCode::MacroSyntax);
    }

    #[test]
    fn array_indices_are_numbers() {
        let mut variables = Variables::default();
        variables
            .declare("ARR", Type::Int, &[Value::Int(2)], Init::Default, span())
            .unwrap();
        for text in ["ARR[\"A\"]", "ARR[TRUE]", "ARR[X]"] {
            let alarm = eval_in(&variables, text).unwrap_err();
            assert_eq!(alarm.code, AlarmCode::BadVariable, "{text}");
            assert!(alarm.message.contains("an index is a number"), "{text}");
        }
        // R parameters are REAL and index arrays: R1 = 1.
        run_assignment(&mut variables, "R1=1").unwrap();
        run_assignment(&mut variables, "ARR[R1]=3").unwrap();
        assert_eq!(eval_in(&variables, "ARR[1]"), Ok(Value::Int(3)));
    }

    #[test]
    fn any_short_expression_gives_a_finite_value_or_an_alarm_with_a_span() {
        // Every sequence of four of these pieces that the reader accepts: 20^4 = 160000.
        const PIECES: [&str; 20] = [
            "1",
            "-",
            "0",
            "/",
            "R1",
            "X",
            "\"A\"",
            "(",
            ")",
            "SUBSTR(\"AB\",",
            "<<",
            "AND",
            "B_NOT ",
            " MOD ",
            " DIV ",
            "1EX300",
            "*",
            ",",
            "ARR[",
            "]",
        ];
        let mut variables = Variables::default();
        variables
            .declare("ARR", Type::Int, &[Value::Int(2)], Init::Default, span())
            .unwrap();
        let mut evaluated = 0;
        for n in 0..PIECES.len().pow(4) {
            let text: String = (0..4)
                .map(|k| PIECES[n / PIECES.len().pow(k) % PIECES.len()])
                .collect();
            let block = parse_block(format!("R1={text}").as_bytes(), FileId(0), 1, 0);
            let Some(WordValue::Expression(expr)) = block.words.first().map(|w| &w.value) else {
                continue;
            };
            evaluated += 1;
            match evaluate(expr, &variables, &mut Machine) {
                Ok(Value::Real(x)) => assert!(x.is_finite(), "{text}"),
                Ok(_) => {}
                Err(alarm) => assert!(alarm.span.is_some(), "{text}"),
            }
        }
        assert!(evaluated > 1000, "{evaluated}");
    }

    #[test]
    fn system_variables_are_read_only_unless_the_front_end_writes_them() {
        let mut variables = Variables::default();
        let alarm = run_assignment(&mut variables, "$P_TOOLNO=3").unwrap_err();
        assert_eq!(alarm.code, AlarmCode::BadVariable);
    }

    #[test]
    fn an_axis_variable_takes_an_axis_name() {
        // DEF AXIS AXIS_1=X: the initialiser evaluates X as an axis.
        let mut variables = Variables::default();
        let init = initialiser(&expr("X"), &variables, &mut Machine).unwrap();
        variables
            .declare("AXIS_1", Type::Axis, &[], init, span())
            .unwrap();
        assert_eq!(eval_in(&variables, "AXIS_1==X"), Ok(Value::Bool(true)));
        assert_eq!(eval_in(&variables, "AXSTRING(AXIS_1)"), Ok(text("X")));
        let alarm = run_assignment(&mut variables, "AXIS_1=\"Y\"").unwrap_err();
        assert!(alarm.help.unwrap().contains("AXNAME"));
    }
}
