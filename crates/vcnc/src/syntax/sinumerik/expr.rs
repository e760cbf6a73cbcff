//! SINUMERIK expressions: the values after `=` and the arguments of calls, as a tree.
//!
//! The operators and their precedence are the control's (loosest first): comparisons `==`
//! `<>` `<` `>` `<=` `>=`; string chaining `<<`; `OR`; `XOR`; `AND`; `B_OR`; `B_XOR`; `B_AND`;
//! `+` `-`; `*` `/` `DIV` `MOD`; then the unary `NOT` `B_NOT` `-` `+`. Comparisons bind least, so
//! `R1==1 AND R2==2` compares R1 with `1 AND R2` — as on the control, a program writes the
//! parentheses. Names, calls and indices are kept as written; what a name means (an R
//! parameter, a user variable, a system variable, a function) is the interpreter's business.
//! Parsing never panics: a malformed expression is an alarm with the span of its cause.

use super::scan::{Scanner, Token};
use crate::alarm::{Alarm, AlarmCode};
use crate::source::Span;

/// An expression with the span it was read from.
#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    /// What it is.
    pub kind: ExprKind,
    /// Where it was written.
    pub span: Span,
}

/// The forms of an expression.
#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    /// A number (`12.5`, `1.5EX3`, `'H1F'`).
    Number(f64),
    /// A string constant, without its quotes.
    Text(Box<str>),
    /// A name, upper case (`R10`, `$P_UIFR`, `LENGTH`).
    Name(Box<str>),
    /// A name with indices: `ARR[1,2]`, `$P_UIFR[1]`.
    Index(Box<str>, Vec<Expr>),
    /// A call: `SIN(30)`, `AC(10)`, `CYCLE82(2,,1)`; a left-out argument is `None`.
    Call(Box<str>, Vec<Option<Expr>>),
    /// A unary operator and its operand.
    Unary(UnaryOp, Box<Expr>),
    /// A binary operator and its operands.
    Binary(BinaryOp, Box<Expr>, Box<Expr>),
}

/// Unary operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UnaryOp {
    /// `-`.
    Minus,
    /// `NOT`.
    Not,
    /// `B_NOT`.
    BitNot,
}

/// Binary operators, loosest binding first.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinaryOp {
    /// `==`.
    Equal,
    /// `<>`.
    NotEqual,
    /// `<`.
    Less,
    /// `>`.
    Greater,
    /// `<=`.
    LessEqual,
    /// `>=`.
    GreaterEqual,
    /// `<<`: string chaining.
    Chain,
    /// `OR`.
    Or,
    /// `XOR`.
    Xor,
    /// `AND`.
    And,
    /// `B_OR`.
    BitOr,
    /// `B_XOR`.
    BitXor,
    /// `B_AND`.
    BitAnd,
    /// `+`.
    Add,
    /// `-`.
    Subtract,
    /// `*`.
    Multiply,
    /// `/`.
    Divide,
    /// `DIV`: integer division.
    IntDivide,
    /// `MOD`.
    Modulo,
}

impl BinaryOp {
    /// Binding strength: higher binds tighter.
    fn precedence(self) -> u8 {
        match self {
            BinaryOp::Equal
            | BinaryOp::NotEqual
            | BinaryOp::Less
            | BinaryOp::Greater
            | BinaryOp::LessEqual
            | BinaryOp::GreaterEqual => 1,
            BinaryOp::Chain => 2,
            BinaryOp::Or => 3,
            BinaryOp::Xor => 4,
            BinaryOp::And => 5,
            BinaryOp::BitOr => 6,
            BinaryOp::BitXor => 7,
            BinaryOp::BitAnd => 8,
            BinaryOp::Add | BinaryOp::Subtract => 9,
            BinaryOp::Multiply | BinaryOp::Divide | BinaryOp::IntDivide | BinaryOp::Modulo => 10,
        }
    }

    /// The operator a token is, if it is one.
    fn of(token: &Token, text: &[u8]) -> Option<BinaryOp> {
        Some(match token {
            Token::Symbol(symbol) => match *symbol {
                "==" => BinaryOp::Equal,
                "<>" => BinaryOp::NotEqual,
                "<" => BinaryOp::Less,
                ">" => BinaryOp::Greater,
                "<=" => BinaryOp::LessEqual,
                ">=" => BinaryOp::GreaterEqual,
                "<<" => BinaryOp::Chain,
                "+" => BinaryOp::Add,
                "-" => BinaryOp::Subtract,
                "*" => BinaryOp::Multiply,
                "/" => BinaryOp::Divide,
                _ => return None,
            },
            Token::Name(range) => {
                let name = &text[range.clone()];
                let is = |word: &str| name.eq_ignore_ascii_case(word.as_bytes());
                if is("OR") {
                    BinaryOp::Or
                } else if is("XOR") {
                    BinaryOp::Xor
                } else if is("AND") {
                    BinaryOp::And
                } else if is("B_OR") {
                    BinaryOp::BitOr
                } else if is("B_XOR") {
                    BinaryOp::BitXor
                } else if is("B_AND") {
                    BinaryOp::BitAnd
                } else if is("DIV") {
                    BinaryOp::IntDivide
                } else if is("MOD") {
                    BinaryOp::Modulo
                } else {
                    return None;
                }
            }
            _ => return None,
        })
    }
}

/// Deepest nesting of parentheses, calls and unary operators: a hostile line cannot exhaust
/// the stack.
const MAX_DEPTH: u32 = 64;

/// Reads one expression at the scanner's position; the scanner stops after its last token.
///
/// # Errors
/// [`AlarmCode::MacroSyntax`] for a missing operand, an unclosed parenthesis or nesting beyond
/// the limit; the scanner's alarms for bad characters and numbers.
pub(super) fn parse(scanner: &mut Scanner<'_>) -> Result<Expr, Alarm> {
    binary(scanner, 1, 0)
}

/// An expression whose operators bind at least as tight as `min`.
fn binary(scanner: &mut Scanner<'_>, min: u8, depth: u32) -> Result<Expr, Alarm> {
    let mut left = unary(scanner, depth)?;
    loop {
        let mark = scanner.mark();
        let Some((token, _)) = scanner.next_token()? else {
            scanner.reset(mark);
            break;
        };
        let op = match BinaryOp::of(&token, scanner.text()) {
            Some(op) if op.precedence() >= min => op,
            _ => {
                scanner.reset(mark);
                break;
            }
        };
        let right = binary(scanner, op.precedence() + 1, depth + 1)?;
        let span = left.span.to(right.span);
        left = Expr {
            kind: ExprKind::Binary(op, Box::new(left), Box::new(right)),
            span,
        };
    }
    Ok(left)
}

/// A unary operator and its operand, or an operand.
fn unary(scanner: &mut Scanner<'_>, depth: u32) -> Result<Expr, Alarm> {
    if depth > MAX_DEPTH {
        return Err(Alarm::error(
            AlarmCode::MacroSyntax,
            scanner.here(),
            format!("the expression nests deeper than {MAX_DEPTH} levels"),
        ));
    }
    let mark = scanner.mark();
    let Some((token, span)) = scanner.next_token()? else {
        return Err(missing_operand(scanner.here()));
    };
    let op = match &token {
        Token::Symbol("-") => Some(UnaryOp::Minus),
        Token::Symbol("+") => None,
        Token::Name(range) if scanner.text()[range.clone()].eq_ignore_ascii_case(b"NOT") => {
            Some(UnaryOp::Not)
        }
        Token::Name(range) if scanner.text()[range.clone()].eq_ignore_ascii_case(b"B_NOT") => {
            Some(UnaryOp::BitNot)
        }
        _ => {
            scanner.reset(mark);
            return primary(scanner, depth);
        }
    };
    let operand = unary(scanner, depth + 1)?;
    let span = span.to(operand.span);
    Ok(match op {
        Some(op) => Expr {
            kind: ExprKind::Unary(op, Box::new(operand)),
            span,
        },
        None => Expr {
            kind: operand.kind,
            span,
        },
    })
}

/// A number, a string, a name (with indices or arguments) or an expression in parentheses.
fn primary(scanner: &mut Scanner<'_>, depth: u32) -> Result<Expr, Alarm> {
    let Some((token, span)) = scanner.next_token()? else {
        return Err(missing_operand(scanner.here()));
    };
    match token {
        Token::Number(value) => Ok(Expr {
            kind: ExprKind::Number(value),
            span,
        }),
        Token::Text(range) => Ok(Expr {
            kind: ExprKind::Text(String::from_utf8_lossy(&scanner.text()[range]).into()),
            span,
        }),
        Token::Symbol("(") => {
            let inner = binary(scanner, 1, depth + 1)?;
            let close = expect(scanner, ")", "`)` to close the parenthesis")?;
            Ok(Expr {
                kind: inner.kind,
                span: span.to(close),
            })
        }
        Token::Name(range) => {
            let name = upper(&scanner.text()[range]);
            name_with_suffix(scanner, name, span, depth)
        }
        Token::Symbol(_) => Err(missing_operand(span)),
    }
}

/// A name, and what follows it without a blank: arguments in parentheses or indices in
/// brackets.
fn name_with_suffix(
    scanner: &mut Scanner<'_>,
    name: Box<str>,
    span: Span,
    depth: u32,
) -> Result<Expr, Alarm> {
    let name_end = scanner.mark();
    scanner.skip_blanks();
    if scanner.peek_byte() != Some(b'(') {
        scanner.reset(name_end);
    }
    if scanner.peek_byte() == Some(b'(') {
        scanner.next_token()?;
        let (arguments, close) = arguments(scanner, depth)?;
        return Ok(Expr {
            kind: ExprKind::Call(name, arguments),
            span: span.to(close),
        });
    }
    if scanner.peek_byte() == Some(b'[') {
        scanner.next_token()?;
        let (indices, close) = indices(scanner, depth)?;
        return Ok(Expr {
            kind: ExprKind::Index(name, indices),
            span: span.to(close),
        });
    }
    Ok(Expr {
        kind: ExprKind::Name(name),
        span,
    })
}

/// The indices after a `[`, up to and with the `]`; returns them and the span of the `]`.
pub(super) fn indices(scanner: &mut Scanner<'_>, depth: u32) -> Result<(Vec<Expr>, Span), Alarm> {
    let mut indices = Vec::new();
    loop {
        indices.push(binary(scanner, 1, depth + 1)?);
        match scanner.next_token()? {
            Some((Token::Symbol(","), _)) => {}
            Some((Token::Symbol("]"), at)) => return Ok((indices, at)),
            Some((_, at)) => return Err(unclosed(at, "`,` or `]` in the index")),
            None => return Err(unclosed(scanner.here(), "`]` to close the index")),
        }
    }
}

/// The arguments of a call after its `(`, up to and with the `)`; a left-out argument
/// (`CYCLE82(2,,1)`) is `None`. Returns them and the span of the `)`.
pub(super) fn arguments(
    scanner: &mut Scanner<'_>,
    depth: u32,
) -> Result<(Vec<Option<Expr>>, Span), Alarm> {
    let mut arguments = Vec::new();
    loop {
        let mark = scanner.mark();
        match scanner.next_token()? {
            Some((Token::Symbol(")"), at)) if arguments.is_empty() => return Ok((arguments, at)),
            Some((Token::Symbol(",") | Token::Symbol(")"), _)) => {
                scanner.reset(mark);
                arguments.push(None);
            }
            Some(_) => {
                scanner.reset(mark);
                arguments.push(Some(binary(scanner, 1, depth + 1)?));
            }
            None => return Err(unclosed(scanner.here(), "`)` to close the arguments")),
        }
        match scanner.next_token()? {
            Some((Token::Symbol(","), _)) => {}
            Some((Token::Symbol(")"), at)) => return Ok((arguments, at)),
            Some((_, at)) => return Err(unclosed(at, "`,` or `)` between the arguments")),
            None => return Err(unclosed(scanner.here(), "`)` to close the arguments")),
        }
    }
}

/// The next token must be `symbol`; its span.
fn expect(scanner: &mut Scanner<'_>, symbol: &str, what: &str) -> Result<Span, Alarm> {
    match scanner.next_token()? {
        Some((Token::Symbol(s), at)) if s == symbol => Ok(at),
        Some((_, at)) => Err(unclosed(at, what)),
        None => Err(unclosed(scanner.here(), what)),
    }
}

/// A name in upper case (the control does not tell cases apart).
pub(super) fn upper(name: &[u8]) -> Box<str> {
    // A name is ASCII but for a stray byte: made in one allocation.
    match std::str::from_utf8(name) {
        Ok(name) => {
            let mut upper = Box::<str>::from(name);
            upper.make_ascii_uppercase();
            upper
        }
        Err(_) => String::from_utf8_lossy(name).to_ascii_uppercase().into(),
    }
}

fn missing_operand(span: Span) -> Alarm {
    Alarm::error(AlarmCode::MacroSyntax, span, "a value is missing here")
        .with_help("an operator needs a value on each side, a call a value for each `,`")
}

fn unclosed(span: Span, what: &str) -> Alarm {
    Alarm::error(AlarmCode::MacroSyntax, span, format!("expected {what}"))
        .with_help("check the parentheses and brackets of the expression")
}
