//! Which statements of a Syntec `%@MACRO` program belong together: an IF with its ELSEIFs, ELSE
//! and END_IF, a CASE with its labels, ELSE and END_CASE, a WHILE or FOR with its END, a REPEAT
//! with its UNTIL, an EXIT with the loop it leaves. Statements open inside one another more than
//! [`MAX_NESTING`] deep get an alarm.

//!
//! [`Structure::scan`] walks the program once with a stack of open statements, as the control
//! builds its table of jumps; the interpreter then jumps by looking a statement up, never by
//! searching the text. A statement that has no partner (END_IF without IF, a WHILE whose
//! END_WHILE is missing, an IF left open when END_WHILE closes the loop around it) gets its alarm
//! here, and the interpreter raises it only when the program reaches that statement, as the
//! control would: a program runs until it needs the missing piece.
//!
//! This module only reads statements; it never evaluates a condition and never decides where a
//! run goes.

use super::LineBlocks;
use crate::alarm::{Alarm, AlarmCode};
use crate::source::Span;
use crate::syntax::Statement;
use std::collections::HashMap;

/// How deep IF, CASE, WHILE, FOR and REPEAT may nest: the statement that opens level 11 raises
/// [`AlarmCode::MacroLimit`] when the run reaches it. Syntec's public macro documentation gives
/// 10 levels; the seed manual gives none (docs/DEVIATIONS.md).
pub const MAX_NESTING: usize = 10;

/// Where a block stands in a program: its line index (0 is the program's first line) and its
/// index among the blocks of that line.
pub type BlockPosition = (usize, usize);

/// What a structured statement needs to know to jump.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Link {
    /// IF, ELSEIF or ELSE: the next branch (ELSEIF, ELSE) or the END_IF, and the END_IF; the
    /// same for CASE, its labels, its ELSE and END_CASE.
    Branch {
        /// Where the next branch or the END_IF is.
        next: BlockPosition,
        /// Where the END_IF is.
        end: BlockPosition,
    },
    /// WHILE or FOR: where its END_WHILE or END_FOR is.
    Loop {
        /// The loop's end.
        end: BlockPosition,
    },
    /// END_WHILE, END_FOR or UNTIL: where its WHILE, FOR or REPEAT is.
    Back {
        /// The loop's start.
        start: BlockPosition,
    },
    /// EXIT: the end of the innermost loop around it (its END_WHILE, END_FOR or UNTIL).
    Exit {
        /// The loop's end.
        end: BlockPosition,
    },
}

/// The partners of a program's structured statements.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Structure {
    links: HashMap<BlockPosition, Result<Link, Alarm>>,
}

impl Structure {
    /// Pairs the structured statements of `lines`.
    pub fn scan(lines: &[LineBlocks]) -> Structure {
        let mut scan = Scan::default();
        for (l, line) in lines.iter().enumerate() {
            for (b, block) in line.as_slice().iter().enumerate() {
                for statement in &block.statements {
                    scan.statement(statement, (l, b));
                }
            }
        }
        scan.finish()
    }

    /// The link of the structured statement at `at`: `None` for statements that need none
    /// (REPEAT, END_IF, END_REPEAT, and anything not structured).
    ///
    /// # Errors
    /// [`AlarmCode::LoopStructure`] when the statement has no partner where it needs one.
    pub fn link(&self, at: BlockPosition) -> Option<Result<Link, &Alarm>> {
        self.links.get(&at).map(|entry| entry.as_ref().copied())
    }
}

/// The kinds of open statements.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    If,
    Case,
    While,
    For,
    Repeat,
}

impl Kind {
    fn opener(self) -> &'static str {
        match self {
            Kind::If => "IF",
            Kind::Case => "CASE",
            Kind::While => "WHILE",
            Kind::For => "FOR",
            Kind::Repeat => "REPEAT",
        }
    }

    fn closer(self) -> &'static str {
        match self {
            Kind::If => "END_IF",
            Kind::Case => "END_CASE",
            Kind::While => "END_WHILE",
            Kind::For => "END_FOR",
            Kind::Repeat => "UNTIL",
        }
    }
}

/// A statement waiting for its end.
#[derive(Debug)]
struct Open {
    kind: Kind,
    at: BlockPosition,
    span: Span,
    /// IF: the IF and its ELSEIFs and ELSE, in order (CASE: the CASE, its labels and ELSE).
    branches: Vec<(BlockPosition, Span)>,
    has_else: bool,
    /// Opened deeper than [`MAX_NESTING`]: the alarm its opener raises.
    too_deep: Option<Alarm>,
    /// Loops: the EXITs that leave this loop.
    exits: Vec<(BlockPosition, Span)>,
}

#[derive(Default)]
struct Scan {
    open: Vec<Open>,
    links: HashMap<BlockPosition, Result<Link, Alarm>>,
    /// An UNTIL that still needs its END_REPEAT (it must come next).
    until: Option<(BlockPosition, Span)>,
}

impl Scan {
    fn statement(&mut self, statement: &Statement, at: BlockPosition) {
        let span = statement.span();
        let after_until = self.until.take();
        if let Some((until, until_span)) = after_until {
            if !matches!(statement, Statement::EndRepeat { .. }) {
                self.missing_end_repeat(until, until_span);
            }
        }
        match *statement {
            Statement::If { .. } => self.push(Kind::If, at, span),
            Statement::ElseIf { .. } => self.branch(at, span, false),
            Statement::Else { .. } => self.branch(at, span, true),
            Statement::EndIf { .. } => self.close(Kind::If, at, span),
            Statement::Case { .. } => self.push(Kind::Case, at, span),
            Statement::CaseLabel { .. } => self.label(at, span),
            Statement::EndCase { .. } => self.close(Kind::Case, at, span),
            Statement::WhileDo { .. } => self.push(Kind::While, at, span),
            Statement::EndWhile { .. } => self.close(Kind::While, at, span),
            Statement::For { .. } => self.push(Kind::For, at, span),
            Statement::EndFor { .. } => self.close(Kind::For, at, span),
            Statement::Repeat { .. } => self.push(Kind::Repeat, at, span),
            Statement::Until { .. } => {
                self.close(Kind::Repeat, at, span);
                self.until = Some((at, span));
            }
            Statement::EndRepeat { .. } if after_until.is_none() => {
                self.error(at, span, "END_REPEAT without REPEAT ... UNTIL before it");
            }
            Statement::Exit { .. } => self.exit(at, span),
            _ => {}
        }
    }

    fn push(&mut self, kind: Kind, at: BlockPosition, span: Span) {
        let too_deep = (self.open.len() >= MAX_NESTING).then(|| {
            Alarm::error(
                AlarmCode::MacroLimit,
                span,
                format!(
                    "{} nested {} deep: IF, CASE, WHILE, FOR and REPEAT nest at most {MAX_NESTING} deep",
                    kind.opener(),
                    self.open.len() + 1
                ),
            )
            .with_help("move the inner part into a subprogram (M98) or a macro (G65)")
        });
        self.open.push(Open {
            kind,
            at,
            span,
            branches: vec![(at, span)],
            has_else: false,
            too_deep,
            exits: Vec::new(),
        });
    }

    /// A CASE label: a branch of the innermost open CASE (`2, 3:` is one branch).
    fn label(&mut self, at: BlockPosition, span: Span) {
        match self.open.last_mut() {
            Some(open) if open.kind == Kind::Case && !open.has_else => {
                if open.branches.last().map(|b| b.0) != Some(at) {
                    open.branches.push((at, span));
                }
            }
            Some(open) if open.kind == Kind::Case => {
                let message = format!(
                    "a CASE label after the ELSE of its CASE (line {})",
                    open.span.line
                );
                self.error(at, span, &message);
            }
            Some(open) => {
                let message = format!(
                    "a CASE label inside {} (line {}): {} is missing",
                    open.kind.opener(),
                    open.span.line,
                    open.kind.closer()
                );
                self.error(at, span, &message);
            }
            None => self.error(at, span, "a CASE label outside CASE"),
        }
    }

    /// ELSEIF or ELSE: a branch of the innermost open IF (ELSE also of a CASE).
    fn branch(&mut self, at: BlockPosition, span: Span, is_else: bool) {
        let word = if is_else { "ELSE" } else { "ELSEIF" };
        match self.open.last_mut() {
            Some(open)
                if (open.kind == Kind::If || (open.kind == Kind::Case && is_else))
                    && !open.has_else =>
            {
                open.branches.push((at, span));
                open.has_else = is_else;
            }
            Some(open) if matches!(open.kind, Kind::If | Kind::Case) && is_else => {
                let message = format!(
                    "ELSE after the ELSE of its {} (line {})",
                    open.kind.opener(),
                    open.span.line
                );
                self.error(at, span, &message);
            }
            Some(open) if open.kind == Kind::If => {
                let message = format!("{word} after the ELSE of its IF (line {})", open.span.line);
                self.error(at, span, &message);
            }
            Some(open) => {
                let message = format!(
                    "{word} inside {} (line {}): {} is missing",
                    open.kind.opener(),
                    open.span.line,
                    open.kind.closer()
                );
                self.error(at, span, &message);
            }
            None => self.error(at, span, &format!("{word} without IF")),
        }
    }

    /// EXIT: leaves the innermost loop.
    fn exit(&mut self, at: BlockPosition, span: Span) {
        match self
            .open
            .iter_mut()
            .rev()
            .find(|o| !matches!(o.kind, Kind::If | Kind::Case))
        {
            Some(open) => open.exits.push((at, span)),
            None => self.error(at, span, "EXIT outside WHILE, FOR and REPEAT"),
        }
    }

    /// The end of a `kind` statement at `at`: pairs it with the innermost open one; statements
    /// opened after that one were never closed.
    fn close(&mut self, kind: Kind, at: BlockPosition, span: Span) {
        let Some(index) = self.open.iter().rposition(|o| o.kind == kind) else {
            let message = format!("{} without {}", kind.closer(), kind.opener());
            return self.error(at, span, &message);
        };
        for inner in self.open.split_off(index + 1) {
            let message = format!(
                "{} is not closed: {} (line {}) ends the {} around it first",
                inner.kind.opener(),
                kind.closer(),
                span.line,
                kind.opener()
            );
            self.unclosed(inner, &message);
        }
        let Some(open) = self.open.pop() else {
            return;
        };
        let (too_deep, open_at) = (open.too_deep.clone(), open.at);
        match kind {
            Kind::If | Kind::Case => {
                let next = open.branches.iter().skip(1).map(|b| b.0).chain([at]);
                for (&(branch, _), next) in open.branches.iter().zip(next) {
                    self.links
                        .insert(branch, Ok(Link::Branch { next, end: at }));
                }
            }
            Kind::While | Kind::For | Kind::Repeat => {
                if kind != Kind::Repeat {
                    self.links.insert(open.at, Ok(Link::Loop { end: at }));
                }
                self.links.insert(at, Ok(Link::Back { start: open.at }));
                for (exit, _) in open.exits {
                    self.links.insert(exit, Ok(Link::Exit { end: at }));
                }
            }
        }
        if let Some(alarm) = too_deep {
            self.links.insert(open_at, Err(alarm));
        }
    }

    /// An open statement that has no end: it, its branches and its EXITs carry the alarm
    /// (at their own place, pointing back at the statement).
    fn unclosed(&mut self, open: Open, message: &str) {
        for &(at, span) in open.branches.iter().chain(&open.exits) {
            let mut alarm = Alarm::error(AlarmCode::LoopStructure, span, message);
            if at != open.at {
                alarm = alarm.with_label(open.span, format!("this {}", open.kind.opener()));
            }
            self.links.insert(at, Err(alarm));
        }
    }

    fn missing_end_repeat(&mut self, at: BlockPosition, span: Span) {
        self.error(at, span, "UNTIL needs END_REPEAT right after its condition");
    }

    fn error(&mut self, at: BlockPosition, span: Span, message: &str) {
        self.links.insert(
            at,
            Err(Alarm::error(AlarmCode::LoopStructure, span, message)),
        );
    }

    fn finish(mut self) -> Structure {
        if let Some((until, span)) = self.until.take() {
            self.missing_end_repeat(until, span);
        }
        for open in std::mem::take(&mut self.open) {
            let message = format!("{} has no {}", open.kind.opener(), open.kind.closer());
            self.unclosed(open, &message);
        }
        Structure { links: self.links }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::source::FileId;
    use crate::syntax::iso::{parse_program, SyntaxOptions};

    /// The link of each statement that has one, by 1-based line (one statement a line).
    fn links(text: &str) -> Vec<String> {
        let program = parse_program(text.as_bytes(), 0, 1, FileId(0), &SyntaxOptions::default());
        let structure = program.structure.expect("a macro program");
        let line = |p: BlockPosition| p.0 + 1;
        let mut out = Vec::new();
        for (l, blocks) in program.lines.iter().enumerate() {
            for b in 0..blocks.as_slice().len() {
                let shown = match structure.link((l, b)) {
                    None => continue,
                    Some(Err(alarm)) => alarm.message.clone(),
                    Some(Ok(Link::Branch { next, end })) => {
                        format!("next {} end {}", line(next), line(end))
                    }
                    Some(Ok(Link::Loop { end })) => format!("end {}", line(end)),
                    Some(Ok(Link::Back { start })) => format!("back {}", line(start)),
                    Some(Ok(Link::Exit { end })) => format!("exit after {}", line(end)),
                };
                out.push(format!("{}: {shown}", l + 1));
            }
        }
        out
    }

    #[test]
    fn an_if_chain_links_each_branch_to_the_next_and_to_its_end() {
        let text = "%@MACRO\nIF #1 = 1 THEN\n#2 := 1;\nELSIF #1 = 2 THEN\nELSEIF #1 = 3 THEN\nELSE\n#2 := 4;\nEND_IF;\n";
        assert_eq!(
            links(text),
            vec![
                "2: next 4 end 8",
                "4: next 5 end 8",
                "5: next 6 end 8",
                "6: next 8 end 8"
            ]
        );
    }

    #[test]
    fn loops_link_both_ways_and_exit_leaves_the_innermost() {
        let text = "%@MACRO\nWHILE #1 < 3 DO\nFOR #2 := 1 TO 3 DO\nIF #2 = 2 THEN\nEXIT;\nEND_IF;\nEND_FOR;\nREPEAT\nEXIT;\nUNTIL #3 > 1 END_REPEAT;\nEND_WHILE;\n";
        assert_eq!(
            links(text),
            vec![
                "2: end 11",
                "3: end 7",
                "4: next 6 end 6",
                "5: exit after 7",
                "7: back 3",
                "9: exit after 10",
                "10: back 8",
                "11: back 2"
            ]
        );
    }

    #[test]
    fn statements_without_partners_carry_alarms() {
        assert_eq!(links("%@MACRO\nEND_IF;\n"), vec!["2: END_IF without IF"]);
        assert_eq!(
            links("%@MACRO\nWHILE #1 DO\n#1 := 0;\n"),
            vec!["2: WHILE has no END_WHILE"]
        );
        assert_eq!(
            links("%@MACRO\nWHILE #1 DO\nIF #2 THEN\nEND_WHILE;\n"),
            vec![
                "2: end 4",
                "3: IF is not closed: END_WHILE (line 4) ends the WHILE around it first",
                "4: back 2"
            ]
        );
        assert_eq!(
            links("%@MACRO\nIF #1 THEN\nELSE\nELSE\nEND_IF;\n"),
            vec![
                "2: next 3 end 5",
                "3: next 5 end 5",
                "4: ELSE after the ELSE of its IF (line 2)"
            ]
        );
        assert_eq!(
            links("%@MACRO\nREPEAT\nUNTIL #1;\n#2 := 1;\nEND_REPEAT;\n"),
            vec![
                "3: UNTIL needs END_REPEAT right after its condition",
                "5: END_REPEAT without REPEAT ... UNTIL before it"
            ]
        );
        assert_eq!(
            links("%@MACRO\nEXIT;\nREPEAT\n"),
            vec![
                "2: EXIT outside WHILE, FOR and REPEAT",
                "3: REPEAT has no UNTIL"
            ]
        );
    }

    #[test]
    fn until_and_end_repeat_may_stand_in_separate_statements() {
        assert_eq!(
            links("%@MACRO\nREPEAT\nUNTIL #1 > 2;\nEND_REPEAT;\n"),
            vec!["3: back 2"]
        );
    }
}
