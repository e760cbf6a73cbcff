//! Reads the SINUMERIK declarations into their parts with spans: `DEF` (variables), `PROC` (a
//! procedure's header), `EXTERN` (a subprogram's parameter types) and `DEFINE` (a macro).
//!
//! The forms are the programming manual's (PGAsl), as the tables of spec/sinumerik-tables.md
//! name their keywords (DEF, PROC, VAR, EXTERN, DEFINE ... AS, SET, REP, NCK, CHAN, the types)
//! and the corpus writes them (`DEF INT VAR1=5, VAR2=5`, `PROC KONUS(REAL rStart, ...)`,
//! `EXTERN WARMUP_CYCLE(REAL, REAL)`). What a definition does (its scope, its storage, whether a
//! name is defined twice) is the interpreter's business. Never panics: a malformed declaration
//! is an alarm with the span of its cause.

use super::control::{ahead, syntax, take_keyword, take_name, take_symbol, written_to};
use super::expr::{self, Expr, ExprKind};
use super::scan::{is_blank, Scanner};
use super::statement::{
    DataType, Definition, External, Initializer, Macro, Name, Parameter, Procedure, Scope, Spanned,
    Variable,
};
use crate::alarm::Alarm;
use crate::source::Span;

const DIMENSIONS_HELP: &str =
    "an array has one to three dimensions: NAME[n], NAME[n, m], NAME[n, m, k]";
const DEF_HELP: &str = "the form is DEF [NCK|CHAN] type name[dimensions]=value, name2, ...";
const TYPES_HELP: &str = "the types are INT, REAL, BOOL, CHAR, STRING[length], AXIS, FRAME";

/// `DEF ...` after its keyword.
pub(super) fn definition(scanner: &mut Scanner<'_>, keyword: &Name) -> Result<Definition, Alarm> {
    let mark = scanner.mark();
    let scope = take_name(scanner)?.and_then(|name| {
        let value = match &*name.value {
            "NCK" => Scope::Nck,
            "CHAN" => Scope::Chan,
            _ => return None,
        };
        Some(Spanned {
            value,
            span: name.span,
        })
    });
    if scope.is_none() {
        // The name is the type.
        scanner.reset(mark);
    }
    let Some(data_type) = data_type(scanner)? else {
        let at = after(scanner, keyword.span);
        return Err(syntax(at, "DEF needs a type").with_help(TYPES_HELP));
    };
    let mut variables = Vec::new();
    loop {
        variables.push(variable(scanner)?);
        if take_symbol(scanner, ",")?.is_none() {
            break;
        }
    }
    Ok(Definition {
        scope,
        data_type,
        variables,
    })
}

/// `name[dims]=init` of a definition.
fn variable(scanner: &mut Scanner<'_>) -> Result<Variable, Alarm> {
    let Some(name) = take_name(scanner)? else {
        return Err(syntax(ahead(scanner), "expected the name of a variable").with_help(DEF_HELP));
    };
    let mut dimensions = Vec::new();
    if let Some(open) = take_symbol(scanner, "[")? {
        let (sizes, _) = expr::indices(scanner, 0)?;
        dimensions = sizes;
        if dimensions.len() > 3 {
            // PGAsl: arrays have at most three dimensions.
            return Err(syntax(
                open.to(written_to(scanner)),
                "an array has at most 3 dimensions",
            )
            .with_help(DIMENSIONS_HELP));
        }
    }
    let init = if scanner.take_equals() {
        Some(initializer(scanner)?)
    } else {
        None
    };
    let span = name.span.to(written_to(scanner));
    Ok(Variable {
        name,
        dimensions,
        init,
        span,
    })
}

/// The value after `=` in a definition: an expression, `SET(...)` or `REP(...)`.
fn initializer(scanner: &mut Scanner<'_>) -> Result<Spanned<Initializer>, Alarm> {
    let value = expr::parse(scanner)?;
    let span = value.span;
    let ExprKind::Call(name, arguments) = &value.kind else {
        return Ok(Spanned {
            value: Initializer::Value(value),
            span,
        });
    };
    let value = match &**name {
        "SET" => Initializer::Set(all_given(arguments, span, "SET")?),
        "REP" => match &all_given(arguments, span, "REP")?[..] {
            [value] => Initializer::Rep {
                value: value.clone(),
                count: None,
            },
            [value, count] => Initializer::Rep {
                value: value.clone(),
                count: Some(count.clone()),
            },
            _ => {
                return Err(syntax(span, "REP takes a value and an optional count")
                    .with_help("REP(value) sets every element, REP(value, n) the first n"))
            }
        },
        _ => Initializer::Value(value),
    };
    Ok(Spanned { value, span })
}

/// The arguments of SET or REP, none left out.
fn all_given(arguments: &[Option<Expr>], span: Span, what: &str) -> Result<Vec<Expr>, Alarm> {
    let given: Option<Vec<Expr>> = arguments.iter().cloned().collect();
    match given {
        Some(values) if !values.is_empty() => Ok(values),
        _ => Err(syntax(span, format!("a value is missing in {what}(...)"))
            .with_help("write a value between each pair of commas")),
    }
}

/// A type at the position, if a name comes; an alarm for a name that is no type.
fn data_type(scanner: &mut Scanner<'_>) -> Result<Option<Spanned<DataType>>, Alarm> {
    let Some(name) = take_name(scanner)? else {
        return Ok(None);
    };
    let value = match &*name.value {
        "INT" => DataType::Int,
        "REAL" => DataType::Real,
        "BOOL" => DataType::Bool,
        "CHAR" => DataType::Char,
        "AXIS" => DataType::Axis,
        "FRAME" => DataType::Frame,
        "STRING" => {
            return string_length(scanner, name.span).map(|(length, span)| {
                Some(Spanned {
                    value: DataType::String(length),
                    span,
                })
            })
        }
        other => {
            return Err(syntax(name.span, format!("unknown type {other}")).with_help(TYPES_HELP))
        }
    };
    Ok(Some(Spanned {
        value,
        span: name.span,
    }))
}

/// The `[n]` after STRING (at `keyword`): the length and the span of the whole type.
fn string_length(scanner: &mut Scanner<'_>, keyword: Span) -> Result<(u32, Span), Alarm> {
    let help = "a STRING has its maximum length in brackets: STRING[20]";
    if take_symbol(scanner, "[")?.is_none() {
        return Err(syntax(keyword, "STRING needs its length").with_help(help));
    }
    let (sizes, close) = expr::indices(scanner, 0)?;
    let span = keyword.to(close);
    match &sizes[..] {
        [Expr {
            kind: ExprKind::Number(n),
            ..
        }] if n.fract() == 0.0 && *n >= 1.0 && *n <= f64::from(u32::MAX) => {
            // Checked just above: a whole number in u32's range.
            Ok((*n as u32, span))
        }
        _ => Err(
            syntax(span, "the length of a STRING must be a whole number from 1").with_help(help),
        ),
    }
}

const PROC_HELP: &str =
    "the form is PROC name(VAR type name[dimensions], type name, ...) attributes";

/// `PROC ...` after its keyword.
pub(super) fn procedure(scanner: &mut Scanner<'_>, keyword: &Name) -> Result<Procedure, Alarm> {
    let name = program_name(scanner, keyword, PROC_HELP)?;
    let parameters = parameters(scanner, Naming::Named)?;
    let mut attributes = Vec::new();
    while !scanner.at_end() {
        match take_name(scanner)? {
            Some(attribute) => attributes.push(attribute),
            None => {
                return Err(syntax(
                    ahead(scanner),
                    "expected an attribute such as SAVE or DISPLOF",
                )
                .with_help(PROC_HELP))
            }
        }
    }
    Ok(Procedure {
        name,
        parameters,
        attributes,
    })
}

/// `EXTERN ...` after its keyword.
pub(super) fn external(scanner: &mut Scanner<'_>, keyword: &Name) -> Result<External, Alarm> {
    let help = "the form is EXTERN name(VAR type[dimensions], type, ...)";
    let name = program_name(scanner, keyword, help)?;
    let parameters = parameters(scanner, Naming::Unnamed)?;
    Ok(External { name, parameters })
}

/// The name after PROC or EXTERN.
fn program_name(scanner: &mut Scanner<'_>, keyword: &Name, help: &str) -> Result<Name, Alarm> {
    take_name(scanner)?.ok_or_else(|| {
        syntax(
            after(scanner, keyword.span),
            format!("{} needs the name of the program", keyword.value),
        )
        .with_help(help)
    })
}

/// Whether parameters have names: PROC's do, EXTERN's do not.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Naming {
    Named,
    Unnamed,
}

/// `(parameter, ...)` if it comes: none when it does not.
fn parameters(scanner: &mut Scanner<'_>, naming: Naming) -> Result<Vec<Parameter>, Alarm> {
    let mut parameters = Vec::new();
    if take_symbol(scanner, "(")?.is_none() {
        return Ok(parameters);
    }
    if take_symbol(scanner, ")")?.is_some() {
        return Ok(parameters);
    }
    loop {
        parameters.push(parameter(scanner, naming)?);
        if take_symbol(scanner, ")")?.is_some() {
            return Ok(parameters);
        }
        if take_symbol(scanner, ",")?.is_none() {
            return Err(
                syntax(ahead(scanner), "expected `,` or `)` between the parameters")
                    .with_help(PROC_HELP),
            );
        }
    }
}

/// `[VAR] type [name] [dims]`.
fn parameter(scanner: &mut Scanner<'_>, naming: Naming) -> Result<Parameter, Alarm> {
    let start = ahead(scanner);
    let by_reference = take_keyword(scanner, "VAR")?;
    let Some(data_type) = data_type(scanner)? else {
        return Err(
            syntax(ahead(scanner), "expected the type of the parameter").with_help(TYPES_HELP)
        );
    };
    let name = match naming {
        Naming::Named => Some(take_name(scanner)?.ok_or_else(|| {
            syntax(ahead(scanner), "expected the name of the parameter").with_help(PROC_HELP)
        })?),
        Naming::Unnamed => None,
    };
    let dimensions = match take_symbol(scanner, "[")? {
        Some(_) => open_dimensions(scanner)?,
        None => Vec::new(),
    };
    Ok(Parameter {
        by_reference,
        data_type,
        name,
        dimensions,
        span: start.to(written_to(scanner)),
    })
}

/// An array parameter's sizes after its `[`, up to and with the `]`; a size may be left out
/// (`[,3]`: the first dimension is the caller's).
fn open_dimensions(scanner: &mut Scanner<'_>) -> Result<Vec<Option<Expr>>, Alarm> {
    let mut sizes = Vec::new();
    loop {
        let mark = scanner.mark();
        let left_out = take_symbol(scanner, ",")?.is_some() || take_symbol(scanner, "]")?.is_some();
        scanner.reset(mark);
        sizes.push(match left_out {
            true => None,
            false => Some(expr::parse(scanner)?),
        });
        if take_symbol(scanner, "]")?.is_some() {
            return Ok(sizes);
        }
        if take_symbol(scanner, ",")?.is_none() {
            return Err(
                syntax(ahead(scanner), "expected `,` or `]` in the dimensions").with_help(
                    "an array parameter gives its sizes as [n, m], a size left out as [, m]",
                ),
            );
        }
        if sizes.len() == 3 {
            // PGAsl: arrays have at most three dimensions.
            return Err(syntax(ahead(scanner), "an array has at most 3 dimensions")
                .with_help(DIMENSIONS_HELP));
        }
    }
}

/// `DEFINE name AS text` after its keyword.
pub(super) fn macro_definition(scanner: &mut Scanner<'_>, keyword: &Name) -> Result<Macro, Alarm> {
    let help = "the form is DEFINE name AS text";
    let Some(name) = take_name(scanner)? else {
        return Err(syntax(
            after(scanner, keyword.span),
            "DEFINE needs the macro's name",
        )
        .with_help(help));
    };
    let Some(as_keyword) = take_keyword(scanner, "AS")? else {
        return Err(syntax(
            after(scanner, name.span),
            "expected AS after the macro's name",
        )
        .with_help(help));
    };
    scanner.skip_blanks();
    let from = scanner.mark();
    let text = scanner.text();
    let to = comment_start(&text[from..]).map_or(text.len(), |i| from + i);
    let end = text[from..to]
        .iter()
        .rposition(|&b| !is_blank(b))
        .map_or(from, |i| from + i + 1);
    if end == from {
        return Err(syntax(as_keyword, "the macro has no text after AS").with_help(help));
    }
    scanner.reset(to);
    Ok(Macro {
        name,
        body: scanner.span(from..end),
    })
}

/// The offset of the `;` that starts the comment of `text`, outside strings.
fn comment_start(text: &[u8]) -> Option<usize> {
    let mut in_string = false;
    text.iter().position(|&b| {
        if b == b'"' {
            in_string = !in_string;
        }
        b == b';' && !in_string
    })
}

/// The span where something should have followed `span`: the next byte, or the end of `span`.
fn after(scanner: &mut Scanner<'_>, span: Span) -> Span {
    let here = ahead(scanner);
    if here.is_empty() {
        Span::new(span.file, span.line, span.end..span.end)
    } else {
        here
    }
}
