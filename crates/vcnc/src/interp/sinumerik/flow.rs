//! The program flow of the SINUMERIK language: IF/ELSE/ENDIF, WHILE, FOR, REPEAT/UNTIL, LOOP,
//! CASE, the jumps GOTO/GOTOF/GOTOB/GOTOC/GOTOS, and part repetition (REPEAT label, REPEATB)
//! (manual PGAsl 1.x "program jumps", "control structures"; spec/sinumerik-tables.md).
//!
//! A structure's partner (the ENDIF of an IF, the WHILE of an ENDWHILE) is found by reading the
//! lines between them once, counting the nesting, and remembered; labels and block numbers are
//! indexed per program on its first jump. Never: run a block twice without counting the pass
//! against the iteration limit (the caller counts every block), or jump into a program other
//! than the current one.

use super::program::Program;
use crate::alarm::{Alarm, AlarmCode};
use crate::source::Span;
use crate::syntax::sinumerik::{parse_block, Jump, JumpKind, JumpTarget, StatementKind};
use std::collections::HashMap;

/// The structure a line opens or closes, as far as matching goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Mark {
    If,
    Else,
    EndIf,
    While,
    EndWhile,
    For,
    EndFor,
    Repeat,
    Until,
    Loop,
    EndLoop,
    EndLabel,
    Other,
}

/// What is known of a program's structure: partners found so far, its labels and numbers.
#[derive(Default)]
pub(super) struct Structure {
    /// (program, line) -> the line of its partner.
    partners: HashMap<(usize, usize), usize>,
    /// Per program: label -> lines, block number -> lines, in line order.
    index: HashMap<usize, Index>,
}

#[derive(Default)]
struct Index {
    labels: HashMap<Box<str>, Vec<usize>>,
    numbers: HashMap<u32, Vec<usize>>,
}

/// The mark of line `index` of `program`.
fn mark(program: &Program, index: usize) -> Mark {
    let Some(line) = program.line(index) else {
        return Mark::Other;
    };
    // Only lines that may hold a statement need a parse.
    if !line.bytes.iter().any(u8::is_ascii_alphabetic) {
        return Mark::Other;
    }
    let block = parse_block(line.bytes, program.file, line.number, line.base);
    match block.statement.map(|s| s.kind) {
        Some(StatementKind::If { jump: None, .. }) => Mark::If,
        Some(StatementKind::Else) => Mark::Else,
        Some(StatementKind::EndIf) => Mark::EndIf,
        Some(StatementKind::While { .. }) => Mark::While,
        Some(StatementKind::EndWhile) => Mark::EndWhile,
        Some(StatementKind::For { .. }) => Mark::For,
        Some(StatementKind::EndFor) => Mark::EndFor,
        Some(StatementKind::Repeat) => Mark::Repeat,
        Some(StatementKind::Until { .. }) => Mark::Until,
        Some(StatementKind::Loop) => Mark::Loop,
        Some(StatementKind::EndLoop) => Mark::EndLoop,
        Some(StatementKind::EndLabel) => Mark::EndLabel,
        _ => Mark::Other,
    }
}

/// The structure a closing mark closes.
fn opener(close: Mark) -> Mark {
    match close {
        Mark::EndIf | Mark::Else => Mark::If,
        Mark::EndWhile => Mark::While,
        Mark::EndFor => Mark::For,
        Mark::Until => Mark::Repeat,
        Mark::EndLoop => Mark::Loop,
        _ => Mark::Other,
    }
}

/// The closing mark of a structure.
fn closer(open: Mark) -> Mark {
    match open {
        Mark::If => Mark::EndIf,
        Mark::While => Mark::EndWhile,
        Mark::For => Mark::EndFor,
        Mark::Repeat => Mark::Until,
        Mark::Loop => Mark::EndLoop,
        _ => Mark::Other,
    }
}

fn is_open(mark: Mark) -> bool {
    matches!(
        mark,
        Mark::If | Mark::While | Mark::For | Mark::Repeat | Mark::Loop
    )
}

fn is_close(mark: Mark) -> bool {
    matches!(
        mark,
        Mark::EndIf | Mark::EndWhile | Mark::EndFor | Mark::Until | Mark::EndLoop
    )
}

fn keyword(mark: Mark) -> &'static str {
    match mark {
        Mark::If => "IF",
        Mark::Else => "ELSE",
        Mark::EndIf => "ENDIF",
        Mark::While => "WHILE",
        Mark::EndWhile => "ENDWHILE",
        Mark::For => "FOR",
        Mark::EndFor => "ENDFOR",
        Mark::Repeat => "REPEAT",
        Mark::Until => "UNTIL",
        Mark::Loop => "LOOP",
        Mark::EndLoop => "ENDLOOP",
        Mark::EndLabel => "ENDLABEL",
        Mark::Other => "",
    }
}

fn structure_alarm(span: Span, message: String) -> Alarm {
    Alarm::error(AlarmCode::LoopStructure, span, message).with_help(
        "every IF needs its ENDIF, WHILE its ENDWHILE, FOR its ENDFOR, REPEAT its UNTIL and LOOP its ENDLOOP, nested inside each other",
    )
}

impl Structure {
    /// The line after an IF whose condition is false: past its ELSE, or its ENDIF.
    pub(super) fn skip_if(
        &mut self,
        programs: &[Program],
        program: usize,
        line: usize,
        span: Span,
    ) -> Result<usize, Alarm> {
        let (end, _) = self.forward(programs, program, line, Mark::If, true, span)?;
        Ok(end + 1)
    }

    /// The line after the end of the structure opened at `line` (an IF reached through its
    /// ELSE: `line` is the ELSE, the ENDIF is wanted).
    pub(super) fn past_end(
        &mut self,
        programs: &[Program],
        program: usize,
        line: usize,
        open: Mark,
        span: Span,
    ) -> Result<usize, Alarm> {
        let (end, _) = self.forward(programs, program, line, open, false, span)?;
        Ok(end + 1)
    }

    /// The line of the structure's head that the closing mark at `line` closes.
    pub(super) fn head(
        &mut self,
        programs: &[Program],
        program: usize,
        line: usize,
        close: Mark,
        span: Span,
    ) -> Result<usize, Alarm> {
        if let Some(&head) = self.partners.get(&(program, line)) {
            return Ok(head);
        }
        let text = &programs[program];
        let mut depth = 0usize;
        for index in (0..line).rev() {
            let m = mark(text, index);
            if is_close(m) {
                depth += 1;
            } else if is_open(m) {
                if depth == 0 {
                    if m != opener(close) {
                        return Err(structure_alarm(
                            span,
                            format!("{} closes a {}", keyword(close), keyword(m)),
                        ));
                    }
                    self.partners.insert((program, line), index);
                    return Ok(index);
                }
                depth -= 1;
            }
        }
        Err(structure_alarm(
            span,
            format!("{} without its {}", keyword(close), keyword(opener(close))),
        ))
    }

    /// The closing line of the structure `open` starting after `line` (its ELSE too, for an IF
    /// when `stop_at_else`), and its mark.
    fn forward(
        &mut self,
        programs: &[Program],
        program: usize,
        line: usize,
        open: Mark,
        stop_at_else: bool,
        span: Span,
    ) -> Result<(usize, Mark), Alarm> {
        let key = (program, line);
        // Remembered ends: an IF's first stop (its ELSE or ENDIF) under `line`; the ENDIF of an
        // ELSE under the ELSE's line.
        if let Some(&end) = self.partners.get(&key) {
            return Ok((end, mark(&programs[program], end)));
        }
        let text = &programs[program];
        let mut depth = 0usize;
        for index in line + 1..text.lines() {
            let m = mark(text, index);
            if is_open(m) {
                depth += 1;
            } else if is_close(m) || m == Mark::Else {
                if depth == 0 {
                    if m == Mark::Else && !(open == Mark::If && stop_at_else) {
                        if open == Mark::If {
                            continue;
                        }
                        return Err(structure_alarm(
                            span,
                            format!("ELSE inside a {} without an IF", keyword(open)),
                        ));
                    }
                    if m != Mark::Else && m != closer(open) {
                        return Err(structure_alarm(
                            span,
                            format!("{} ends with {}", keyword(open), keyword(m)),
                        ));
                    }
                    self.partners.insert(key, index);
                    return Ok((index, m));
                }
                if m != Mark::Else {
                    depth -= 1;
                }
            }
        }
        Err(structure_alarm(
            span,
            format!("{} without its {}", keyword(open), keyword(closer(open))),
        ))
    }

    /// The line a jump goes to from `line`, or None for GOTOC without its target.
    pub(super) fn jump(
        &mut self,
        programs: &[Program],
        program: usize,
        line: usize,
        jump: &Jump,
        target: Target<'_>,
    ) -> Result<Option<usize>, Alarm> {
        if jump.kind == JumpKind::GotoS {
            return Ok(Some(0));
        }
        let index = self.index.entry(program).or_insert_with(|| {
            let text = &programs[program];
            let mut index = Index::default();
            for i in 0..text.lines() {
                let Some(l) = text.line(i) else { continue };
                let block = parse_block(l.bytes, text.file, l.number, l.base);
                if let Some(label) = block.label {
                    index.labels.entry(label).or_default().push(i);
                }
                if let Some(n) = block.number {
                    index.numbers.entry(n).or_default().push(i);
                }
            }
            index
        });
        let lines: &[usize] = match target {
            Target::Label(name) => index.labels.get(name).map_or(&[], Vec::as_slice),
            Target::Number(n) => index.numbers.get(&n).map_or(&[], Vec::as_slice),
        };
        let forward = lines.iter().copied().find(|&l| l > line);
        let backward = lines.iter().rev().copied().find(|&l| l <= line);
        let found = match jump.kind {
            JumpKind::GotoF => forward,
            JumpKind::GotoB => backward,
            JumpKind::Goto | JumpKind::GotoC => forward.or(backward),
            JumpKind::GotoS => Some(0),
        };
        match found {
            Some(l) => Ok(Some(l)),
            None if jump.kind == JumpKind::GotoC => Ok(None),
            None => {
                let what = match target {
                    Target::Label(name) => format!("label {name}"),
                    Target::Number(n) => format!("block N{n}"),
                };
                let direction = match jump.kind {
                    JumpKind::GotoF => " after this block",
                    JumpKind::GotoB => " before this block",
                    _ => "",
                };
                let span = jump.target.as_ref().map_or(jump.span, JumpTarget::span);
                Err(Alarm::error(
                    AlarmCode::SequenceNotFound,
                    span,
                    format!("jump target {what} not found{direction} (alarm 14080)"),
                )
                .with_help("GOTOF searches towards the program end, GOTOB towards its start, GOTO and GOTOC both ways"))
            }
        }
    }

    /// The line of label `name` searched backwards from `line` (part repetition), or forwards
    /// when `forward`.
    pub(super) fn label(
        &mut self,
        programs: &[Program],
        program: usize,
        line: usize,
        name: &str,
        forward: bool,
        span: Span,
    ) -> Result<usize, Alarm> {
        let kind = if forward {
            JumpKind::GotoF
        } else {
            JumpKind::GotoB
        };
        let jump = Jump {
            kind,
            target: None,
            span,
        };
        self.jump(programs, program, line, &jump, Target::Label(name))?
            .ok_or_else(|| Alarm::error(AlarmCode::SequenceNotFound, span, "label not found"))
    }

    /// The first ENDLABEL after `from` and before `to`, if any.
    pub(super) fn end_label(
        programs: &[Program],
        program: usize,
        from: usize,
        to: usize,
    ) -> Option<usize> {
        (from + 1..to).find(|&i| mark(&programs[program], i) == Mark::EndLabel)
    }
}

/// Where a jump goes, as the program names it.
#[derive(Clone, Copy, Debug)]
pub(super) enum Target<'a> {
    Label(&'a str),
    Number(u32),
}
