//! Reads a SINUMERIK statement from the rest of a block: which keywords start one and where
//! they may stand, the control structures (IF, ELSE, ENDIF, WHILE, FOR, REPEAT, UNTIL, LOOP,
//! CASE, part repetition with REPEAT/REPEATB, ENDLABEL) and jumps (GOTO, GOTOF, GOTOB, GOTOC,
//! GOTOS) here, the declarations in `declare.rs`; synchronized actions are kept as text.
//!
//! The forms are those of the programming manual (PGAsl) as the tables name them
//! (spec/sinumerik-tables.md) and the examples and corpus write them. It reads one block's
//! statement only, never another line. Never panics: a malformed statement is an alarm
//! ([`AlarmCode::MacroSyntax`]) with the span of its cause and a help line.

use super::declare;
use super::expr::{self, Expr, ExprKind};
use super::scan::{is_blank, Scanner, Token};
use super::statement::{
    Case, CaseBranch, Jump, JumpKind, JumpTarget, Name, Spanned, Statement, StatementKind,
};
use crate::alarm::{Alarm, AlarmCode};
use crate::source::Span;

/// Where a statement's keyword may stand in its block.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Place {
    /// First, after the block number and label only (docs/SINUMERIK.md 3.1).
    First,
    /// Also after other words: jumps and synchronized actions.
    AfterWords,
}

/// The keywords that make the rest of a block a statement, and where each may stand.
const KEYWORDS: [(&str, Place); 30] = [
    ("IF", Place::First),
    ("ELSE", Place::First),
    ("ENDIF", Place::First),
    ("WHILE", Place::First),
    ("ENDWHILE", Place::First),
    ("FOR", Place::First),
    ("ENDFOR", Place::First),
    ("REPEAT", Place::First),
    ("REPEATB", Place::First),
    ("UNTIL", Place::First),
    ("LOOP", Place::First),
    ("ENDLOOP", Place::First),
    ("CASE", Place::First),
    ("DEF", Place::First),
    ("PROC", Place::First),
    ("EXTERN", Place::First),
    ("DEFINE", Place::First),
    ("SAVE", Place::First),
    ("ENDLABEL", Place::First),
    ("CALL", Place::First),
    ("GOTO", Place::AfterWords),
    ("GOTOF", Place::AfterWords),
    ("GOTOB", Place::AfterWords),
    ("GOTOC", Place::AfterWords),
    ("GOTOS", Place::AfterWords),
    // Synchronized actions: the rest of the block from any word on (`IDS=2 WHENEVER ...`).
    ("WHEN", Place::AfterWords),
    ("WHENEVER", Place::AfterWords),
    ("EVERY", Place::AfterWords),
    ("FROM", Place::AfterWords),
    // An action without a condition (example a/37: `N130 DO $R1=$AC_TIME`).
    ("DO", Place::AfterWords),
];

/// Where the statement keyword written `name` (in any case) may stand, if it is one.
pub(super) fn place_of(name: &[u8]) -> Option<Place> {
    KEYWORDS
        .iter()
        .find(|(keyword, _)| keyword.as_bytes().eq_ignore_ascii_case(name))
        .map(|(_, place)| *place)
}

/// Where the statement keyword `name` (upper case) may stand, if it is one.
pub(super) fn place(name: &str) -> Option<Place> {
    KEYWORDS
        .iter()
        .find(|(keyword, _)| *keyword == name)
        .map(|(_, place)| *place)
}

/// Reads the statement of `keyword` (consumed, upper case) to the end of the block.
///
/// # Errors
/// [`AlarmCode::MacroSyntax`] for a malformed statement or anything after its end; the
/// expression reader's and the scanner's alarms.
pub(super) fn read(scanner: &mut Scanner<'_>, keyword: Name) -> Result<Statement, Alarm> {
    let kind = match &*keyword.value {
        "IF" => if_statement(scanner, &keyword)?,
        "ELSE" => StatementKind::Else,
        "ENDIF" => StatementKind::EndIf,
        "WHILE" => StatementKind::While {
            condition: condition(scanner, &keyword)?,
        },
        "ENDWHILE" => StatementKind::EndWhile,
        "FOR" => for_statement(scanner, &keyword)?,
        "ENDFOR" => StatementKind::EndFor,
        "REPEAT" => repeat(scanner)?,
        "REPEATB" => repeat_block(scanner, &keyword)?,
        "UNTIL" => StatementKind::Until {
            condition: condition(scanner, &keyword)?,
        },
        "LOOP" => StatementKind::Loop,
        "ENDLOOP" => StatementKind::EndLoop,
        "CASE" => StatementKind::Case(case(scanner, &keyword)?),
        "DEF" => StatementKind::Definition(declare::definition(scanner, &keyword)?),
        "PROC" => StatementKind::Procedure(declare::procedure(scanner, &keyword)?),
        "EXTERN" => StatementKind::External(declare::external(scanner, &keyword)?),
        "DEFINE" => StatementKind::Macro(declare::macro_definition(scanner, &keyword)?),
        "SAVE" => StatementKind::Save,
        "ENDLABEL" => StatementKind::EndLabel,
        "CALL" => call(scanner, &keyword)?,
        other => match jump_kind(other) {
            Some(kind) => StatementKind::Jump(jump(scanner, kind, keyword.span)?),
            None => {
                // A synchronized action: kept as text for now.
                scanner.skip_blanks();
                let rest = scanner.span(scanner.mark()..scanner.text().len());
                scanner.reset(scanner.text().len());
                let span = keyword.span.to(rest);
                return Ok(Statement {
                    kind: StatementKind::Action { keyword, rest },
                    span,
                });
            }
        },
    };
    let span = keyword.span.to(written_to(scanner));
    end(scanner, &keyword.value)?;
    Ok(Statement { kind, span })
}

/// The jump of a keyword, if it is one.
fn jump_kind(keyword: &str) -> Option<JumpKind> {
    Some(match keyword {
        "GOTO" => JumpKind::Goto,
        "GOTOF" => JumpKind::GotoF,
        "GOTOB" => JumpKind::GotoB,
        "GOTOC" => JumpKind::GotoC,
        "GOTOS" => JumpKind::GotoS,
        _ => return None,
    })
}

/// `IF cond` or `IF cond GOTOx target`.
fn if_statement(scanner: &mut Scanner<'_>, keyword: &Name) -> Result<StatementKind, Alarm> {
    let condition = condition(scanner, keyword)?;
    if scanner.at_end() {
        return Ok(StatementKind::If {
            condition,
            jump: None,
        });
    }
    let Some(keyword) = take_name(scanner)? else {
        return Err(after_condition(ahead(scanner)));
    };
    let Some(kind) = jump_kind(&keyword.value) else {
        return Err(after_condition(keyword.span));
    };
    let jump = jump(scanner, kind, keyword.span)?;
    Ok(StatementKind::If {
        condition,
        jump: Some(jump),
    })
}

fn after_condition(span: Span) -> Alarm {
    syntax(
        span,
        "expected a jump (GOTOF, GOTOB, GOTO, GOTOC) or the end of the block after the IF condition",
    )
    .with_help("an IF with other words after its condition is no SINUMERIK form; write IF cond, the blocks, ENDIF")
}

/// The condition of IF, WHILE or UNTIL.
fn condition(scanner: &mut Scanner<'_>, keyword: &Name) -> Result<Expr, Alarm> {
    if scanner.at_end() {
        return Err(
            syntax(keyword.span, format!("{} needs a condition", keyword.value)).with_help(
                format!(
                    "write the condition after {}, as in {} R1>0",
                    keyword.value, keyword.value
                ),
            ),
        );
    }
    expr::parse(scanner)
}

/// `FOR variable = start TO end`.
fn for_statement(scanner: &mut Scanner<'_>, keyword: &Name) -> Result<StatementKind, Alarm> {
    let help = "the form is FOR variable = start TO end";
    if scanner.at_end() {
        return Err(syntax(keyword.span, "FOR needs its counter").with_help(help));
    }
    let variable = expr::parse(scanner)?;
    if !matches!(variable.kind, ExprKind::Name(_) | ExprKind::Index(..)) {
        return Err(syntax(variable.span, "the counter of FOR must be a variable").with_help(help));
    }
    if !scanner.take_equals() {
        return Err(syntax(ahead(scanner), "expected `=` after the FOR counter").with_help(help));
    }
    let start = expr::parse(scanner)?;
    if take_keyword(scanner, "TO")?.is_none() {
        return Err(
            syntax(ahead(scanner), "expected TO after the start value of FOR").with_help(help),
        );
    }
    let end = expr::parse(scanner)?;
    Ok(StatementKind::For {
        variable,
        start,
        end,
    })
}

/// `REPEAT` alone (a loop head) or `REPEAT start [end] [P=n]`.
fn repeat(scanner: &mut Scanner<'_>) -> Result<StatementKind, Alarm> {
    if scanner.at_end() {
        return Ok(StatementKind::Repeat);
    }
    let help = "the forms are REPEAT alone (a loop up to UNTIL) and REPEAT label [label] [P=n]";
    let start = label(scanner, "REPEAT", help)?;
    let end = match passes(scanner)? {
        Some(passes) => {
            return Ok(StatementKind::RepeatSection {
                start,
                end: None,
                passes: Some(passes),
            })
        }
        None if scanner.at_end() => None,
        None => Some(label(scanner, "REPEAT", help)?),
    };
    Ok(StatementKind::RepeatSection {
        start,
        end,
        passes: passes(scanner)?,
    })
}

/// `REPEATB label [P=n]`.
fn repeat_block(scanner: &mut Scanner<'_>, keyword: &Name) -> Result<StatementKind, Alarm> {
    let help = "the form is REPEATB label [P=n]";
    if scanner.at_end() {
        return Err(syntax(keyword.span, "REPEATB needs the label of its block").with_help(help));
    }
    let label = label(scanner, "REPEATB", help)?;
    Ok(StatementKind::RepeatBlock {
        label,
        passes: passes(scanner)?,
    })
}

/// `CALL program`, `CALL program BLOCK start TO end` or `CALL BLOCK start TO end` (PGAsl,
/// indirect call and indirect part repetition).
fn call(scanner: &mut Scanner<'_>, keyword: &Name) -> Result<StatementKind, Alarm> {
    let help = "the forms are CALL \"NAME\", CALL variable, and CALL \"NAME\" BLOCK start TO end";
    if scanner.at_end() {
        return Err(syntax(keyword.span, "CALL needs the program to call").with_help(help));
    }
    let program = match take_keyword(scanner, "BLOCK")? {
        Some(_) => None,
        None => Some(expr::parse(scanner)?),
    };
    let block = program.is_none() || take_keyword(scanner, "BLOCK")?.is_some();
    let section = if block {
        let start = label(scanner, "CALL .. BLOCK", help)?;
        if take_keyword(scanner, "TO")?.is_none() {
            return Err(syntax(ahead(scanner), "expected TO after the first label").with_help(help));
        }
        Some((start, label(scanner, "CALL .. BLOCK .. TO", help)?))
    } else {
        None
    };
    Ok(StatementKind::Call { program, section })
}

/// `P=n` after the labels of REPEAT and REPEATB, if it comes.
fn passes(scanner: &mut Scanner<'_>) -> Result<Option<Expr>, Alarm> {
    let mark = scanner.mark();
    scanner.skip_blanks();
    let is_p = scanner
        .peek_byte()
        .is_some_and(|b| b.eq_ignore_ascii_case(&b'P'));
    if is_p {
        scanner.bump();
        if scanner.take_equals() {
            return expr::parse(scanner).map(Some);
        }
    }
    scanner.reset(mark);
    Ok(None)
}

/// A label name after REPEAT or REPEATB.
fn label(scanner: &mut Scanner<'_>, keyword: &str, help: &str) -> Result<Name, Alarm> {
    match take_name(scanner)? {
        Some(name) => Ok(name),
        None => {
            Err(syntax(ahead(scanner), format!("expected a label after {keyword}")).with_help(help))
        }
    }
}

/// `CASE(expr) OF c1 GOTOF l1 ... DEFAULT GOTOF l`.
fn case(scanner: &mut Scanner<'_>, keyword: &Name) -> Result<Case, Alarm> {
    let help = "the form is CASE(expression) OF constant GOTOF label ... DEFAULT GOTOF label";
    if scanner.at_end() {
        return Err(syntax(keyword.span, "CASE needs the expression it compares").with_help(help));
    }
    let selector = expr::parse(scanner)?;
    if take_keyword(scanner, "OF")?.is_none() {
        return Err(
            syntax(ahead(scanner), "expected OF after the CASE expression").with_help(help),
        );
    }
    let mut branches = Vec::new();
    let mut default = None;
    while !scanner.at_end() {
        if let Some(word) = take_keyword(scanner, "DEFAULT")? {
            default = Some(case_jump(scanner, word, help)?);
            break;
        }
        let value = expr::parse(scanner)?;
        let jump = case_jump(scanner, value.span, help)?;
        branches.push(CaseBranch { value, jump });
    }
    if branches.is_empty() && default.is_none() {
        return Err(syntax(keyword.span, "CASE has no branch").with_help(help));
    }
    Ok(Case {
        selector,
        branches,
        default,
    })
}

/// The jump after a CASE constant or DEFAULT (at `after`).
fn case_jump(scanner: &mut Scanner<'_>, after: Span, help: &str) -> Result<Jump, Alarm> {
    let keyword = take_name(scanner)?;
    match keyword
        .as_ref()
        .and_then(|k| jump_kind(&k.value).map(|kind| (kind, k.span)))
    {
        Some((JumpKind::GotoS, span)) => {
            Err(syntax(span, "a CASE branch needs a jump with a target").with_help(help))
        }
        Some((kind, span)) => jump(scanner, kind, span),
        None => {
            let at = keyword.map_or_else(|| ahead(scanner), |k| k.span);
            Err(
                syntax(at, "expected GOTOF or GOTOB after the CASE constant")
                    .with_help(help)
                    .with_label(after, "the constant or DEFAULT"),
            )
        }
    }
}

/// A jump's target after its keyword (at `keyword`).
fn jump(scanner: &mut Scanner<'_>, kind: JumpKind, keyword: Span) -> Result<Jump, Alarm> {
    if kind == JumpKind::GotoS {
        // PGAsl: GOTOS jumps to the program start and takes no target (manual L13290).
        if !scanner.at_end() {
            return Err(syntax(ahead(scanner), "GOTOS takes no target")
                .with_help("GOTOS jumps back to the program start; GOTOB jumps back to a label"));
        }
        return Ok(Jump {
            kind,
            target: None,
            span: keyword,
        });
    }
    if scanner.at_end() {
        return Err(syntax(keyword, "the jump has no target").with_help(
            "write the label (GOTOF MARK1), a block number (GOTOB N100) or a STRING variable",
        ));
    }
    let target = target(scanner)?;
    Ok(Jump {
        kind,
        span: keyword.to(target.span()),
        target: Some(target),
    })
}

/// A jump target: a name alone, `N` and a block number, or a string expression.
fn target(scanner: &mut Scanner<'_>) -> Result<JumpTarget, Alarm> {
    let mark = scanner.mark();
    let Some((token, span)) = scanner.next_token()? else {
        return Err(syntax(ahead(scanner), "the jump has no target"));
    };
    let Token::Name(range) = token else {
        // `"MARK"<<R1`, `("N"<<R1)`: an expression that gives the target.
        scanner.reset(mark);
        return expr::parse(scanner).map(JumpTarget::Expression);
    };
    let after = scanner.mark();
    let suffix = matches!(scanner.peek_byte(), Some(b'[' | b'('));
    scanner.skip_blanks();
    let chained = scanner.text()[scanner.mark()..].starts_with(b"<<");
    scanner.reset(after);
    if suffix || chained {
        scanner.reset(mark);
        return expr::parse(scanner).map(JumpTarget::Expression);
    }
    let name = expr::upper(&scanner.text()[range]);
    match block_number(&name) {
        Some(Some(number)) => Ok(JumpTarget::BlockNumber(Spanned {
            value: number,
            span,
        })),
        Some(None) => Err(Alarm::error(
            AlarmCode::BadNumber,
            span,
            "the block number of the jump is too large",
        )
        .with_help("a block number is at most 4294967295")),
        None => Ok(JumpTarget::Label(Spanned { value: name, span })),
    }
}

/// The number of `N123` (`Some(None)` when it does not fit), `None` for other names.
fn block_number(name: &str) -> Option<Option<u32>> {
    let digits = name.strip_prefix('N')?;
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    Some(digits.parse().ok())
}

/// The next token if it is a name, consumed, in upper case; the position stays otherwise.
pub(super) fn take_name(scanner: &mut Scanner<'_>) -> Result<Option<Name>, Alarm> {
    let mark = scanner.mark();
    match scanner.next_token()? {
        Some((Token::Name(range), span)) => Ok(Some(Spanned {
            value: expr::upper(&scanner.text()[range]),
            span,
        })),
        _ => {
            scanner.reset(mark);
            Ok(None)
        }
    }
}

/// The keyword `word` (upper case) if it comes next, consumed; its span.
pub(super) fn take_keyword(scanner: &mut Scanner<'_>, word: &str) -> Result<Option<Span>, Alarm> {
    let mark = scanner.mark();
    match take_name(scanner)? {
        Some(name) if &*name.value == word => Ok(Some(name.span)),
        _ => {
            scanner.reset(mark);
            Ok(None)
        }
    }
}

/// The next token if it is `symbol`, consumed; its span.
pub(super) fn take_symbol(scanner: &mut Scanner<'_>, symbol: &str) -> Result<Option<Span>, Alarm> {
    let mark = scanner.mark();
    match scanner.next_token()? {
        Some((Token::Symbol(s), span)) if s == symbol => Ok(Some(span)),
        _ => {
            scanner.reset(mark);
            Ok(None)
        }
    }
}

/// The span of the last byte read before the position that is no blank (an empty span at the
/// start of the line).
pub(super) fn written_to(scanner: &Scanner<'_>) -> Span {
    let text = scanner.text();
    let end = text[..scanner.mark()]
        .iter()
        .rposition(|&b| !is_blank(b))
        .map_or(0, |i| i + 1);
    scanner.span(end.saturating_sub(1)..end)
}

/// The span of the next byte that is no blank (empty at the end of the line), for an alarm
/// about what comes next.
pub(super) fn ahead(scanner: &mut Scanner<'_>) -> Span {
    scanner.skip_blanks();
    scanner.here()
}

/// The end of the block (or its comment) must follow the statement of `keyword`.
fn end(scanner: &mut Scanner<'_>, keyword: &str) -> Result<(), Alarm> {
    if scanner.at_end() {
        return Ok(());
    }
    let from = scanner.mark();
    let to = scanner.text()[from..]
        .iter()
        .position(|&b| b == b';')
        .map_or(scanner.text().len(), |i| from + i);
    let rest = scanner.span(from..to);
    Err(syntax(
        rest,
        format!("unexpected text after the {keyword} statement"),
    )
    .with_help(format!(
        "{keyword} stands in a block of its own, with nothing after it but a comment"
    )))
}

/// The alarm of a malformed statement.
pub(super) fn syntax(span: Span, message: impl Into<String>) -> Alarm {
    Alarm::error(AlarmCode::MacroSyntax, span, message)
}
