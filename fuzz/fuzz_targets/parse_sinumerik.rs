//! Fuzz target: the SINUMERIK block reader alone, `vcnc::syntax::sinumerik::parse_block` on
//! every line of the input.
//!
//! Properties: no panic (deep nesting is an alarm, not a stack overflow); a block that cannot
//! be read carries an alarm with a span inside its line that names the line; every word's span
//! and every expression's span lie inside the line, and words follow each other without
//! overlap; a statement and its expressions lie inside the line.
#![no_main]

use libfuzzer_sys::fuzz_target;
use vcnc::source::{FileId, Span};
use vcnc::syntax::sinumerik::{parse_block, Expr, ExprKind, Value};

fn check_expr(expr: &Expr, inside: &dyn Fn(Span, &str)) {
    inside(expr.span, "expression");
    match &expr.kind {
        ExprKind::Index(_, items) => items.iter().for_each(|e| check_expr(e, inside)),
        ExprKind::Call(_, args) => args.iter().flatten().for_each(|e| check_expr(e, inside)),
        ExprKind::Unary(_, e) => check_expr(e, inside),
        ExprKind::Binary(_, a, b) => {
            check_expr(a, inside);
            check_expr(b, inside);
        }
        ExprKind::Number(_) | ExprKind::Text(_) | ExprKind::Name(_) => {}
    }
}

fuzz_target!(|data: &[u8]| {
    let mut offset = 0usize;
    for (number, line) in (1u32..).zip(data.split(|&b| b == b'\n')) {
        let base = offset as u32;
        let end = offset + line.len();
        let inside = |span: Span, what: &str| {
            assert!(
                base <= span.start && span.start <= span.end && span.end as usize <= end,
                "{what} at {span} is outside line {number} ({offset}..{end})"
            );
            assert_eq!(span.line, number, "{what} at {span} names the wrong line");
        };
        let block = parse_block(line, FileId(0), number, base);
        if let Some(alarm) = &block.alarm {
            inside(alarm.span.expect("a block's alarm has a span"), "alarm");
            assert!(!alarm.message.contains('\n'), "a message of two lines");
        }
        let mut previous = base;
        for word in &block.words {
            inside(word.span, "word");
            assert!(
                word.span.start >= previous,
                "word {word:?} overlaps the one before"
            );
            previous = word.span.end;
            match &word.value {
                Value::Expression(e) => check_expr(e, &inside),
                Value::Indexed(items, value) => {
                    items.iter().for_each(|e| check_expr(e, &inside));
                    if let Some(e) = value {
                        check_expr(e, &inside);
                    }
                }
                Value::Call(args) => args.iter().flatten().for_each(|e| check_expr(e, &inside)),
                Value::Constant(_) | Value::Bare => {}
            }
        }
        if let Some(statement) = &block.statement {
            inside(statement.span, "statement");
            assert!(
                statement.span.start >= previous,
                "statement {statement:?} overlaps the words"
            );
            for expr in statement.expressions() {
                check_expr(expr, &inside);
            }
        }
        offset = end + 1;
    }
});
