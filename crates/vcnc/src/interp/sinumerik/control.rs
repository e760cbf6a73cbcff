//! Running a statement of the SINUMERIK language: where the program goes next after an IF, a
//! loop's head or end, a CASE, a jump or a part repetition (`flow.rs` finds the lines).
//!
//! Never: move the machine. A statement changes only which line runs next (and a FOR
//! counter).

use super::flow::{Mark, Structure, Target};
use super::{Section, Sinumerik, Step};
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::kernel::Kernel;
use crate::source::Span;
use crate::syntax::sinumerik::{Expr, Jump, JumpKind, JumpTarget, Name, Statement, StatementKind};

/// Runs `statement` of line `line` of the current level's program.
pub(super) fn run(
    front: &mut Sinumerik,
    kernel: &Kernel,
    statement: &Statement,
    line: usize,
    span: Span,
) -> Result<Step, Alarm> {
    let program = front.levels.last().expect("a level").program;
    let next = match &statement.kind {
        StatementKind::If {
            condition,
            jump: None,
        } => {
            if front.condition(kernel, condition)? {
                None
            } else {
                Some(front.structure.skip_if(&front.programs, program, line, span)?)
            }
        }
        StatementKind::If {
            condition,
            jump: Some(jump),
        } => {
            if front.condition(kernel, condition)? {
                return jump_to(front, kernel, jump, line);
            }
            None
        }
        // The true branch ran to its ELSE: on after the ENDIF.
        StatementKind::Else => {
            Some(front.structure.past_end(&front.programs, program, line, Mark::If, span)?)
        }
        StatementKind::While { condition } => {
            if front.condition(kernel, condition)? {
                None
            } else {
                Some(front.structure.past_end(
                    &front.programs,
                    program,
                    line,
                    Mark::While,
                    span,
                )?)
            }
        }
        StatementKind::EndWhile => {
            Some(front.structure.head(&front.programs, program, line, Mark::EndWhile, span)?)
        }
        StatementKind::For {
            variable,
            start,
            end,
        } => {
            let first = front.value(kernel, start)?;
            front.assign(kernel, variable, first)?;
            if first <= front.value(kernel, end)? {
                None
            } else {
                Some(front.structure.past_end(&front.programs, program, line, Mark::For, span)?)
            }
        }
        StatementKind::EndFor => {
            let head = front.structure.head(&front.programs, program, line, Mark::EndFor, span)?;
            let (variable, end) = for_parts(front, program, head)?;
            let counter = front.value(kernel, &variable)? + 1.0;
            front.assign(kernel, &variable, counter)?;
            // The end value is read again at every pass (choice: the manual does not say when).
            (counter <= front.value(kernel, &end)?).then_some(head + 1)
        }
        StatementKind::Until { condition } => {
            if front.condition(kernel, condition)? {
                None
            } else {
                let head = front.structure.head(&front.programs, program, line, Mark::Until, span)?;
                Some(head + 1)
            }
        }
        StatementKind::EndLoop => {
            let head = front.structure.head(&front.programs, program, line, Mark::EndLoop, span)?;
            Some(head + 1)
        }
        StatementKind::Case(case) => {
            let selector = front.value(kernel, &case.selector)?;
            for branch in &case.branches {
                if front.value(kernel, &branch.value)? == selector {
                    return jump_to(front, kernel, &branch.jump, line);
                }
            }
            if let Some(jump) = &case.default {
                return jump_to(front, kernel, jump, line);
            }
            None
        }
        StatementKind::RepeatSection { start, end, passes } => {
            let passes = passes_of(front, kernel, passes.as_ref())?;
            let first = front.structure.label(
                &front.programs,
                program,
                line,
                &start.value,
                false,
                start.span,
            )?;
            let last = match end {
                Some(end) => {
                    front.structure.label(
                        &front.programs,
                        program,
                        first,
                        &end.value,
                        true,
                        end.span,
                    )?
                }
                // One label: to an ENDLABEL between it and this block, or to the block before
                // this one.
                None => Structure::end_label(&front.programs, program, first, line)
                    .unwrap_or(line.saturating_sub(1)),
            };
            repeat(front, first, last, line, passes)
        }
        StatementKind::RepeatBlock { label, passes } => {
            let passes = passes_of(front, kernel, passes.as_ref())?;
            let at = front.structure.label(
                &front.programs,
                program,
                line,
                &label.value,
                false,
                label.span,
            )?;
            repeat(front, at, at, line, passes)
        }
        StatementKind::Jump(jump) => return jump_to(front, kernel, jump, line),
        StatementKind::Call { program, section } => {
            return call(front, kernel, program.as_ref(), section.as_ref(), line, span)
        }
        StatementKind::EndIf
        | StatementKind::Repeat
        | StatementKind::Loop
        | StatementKind::EndLabel
        | StatementKind::External(_)
        | StatementKind::Save => None,
        StatementKind::Action { keyword, .. } => {
            return Err(Alarm::error(
                AlarmCode::NotInProduct,
                keyword.span,
                format!(
                    "{} starts a synchronized action, which belongs to the control's real-time events, which vcnc does not simulate",
                    keyword.value
                ),
            ))
        }
        StatementKind::Definition(_) | StatementKind::Procedure(_) | StatementKind::Macro(_) => {
            return front.declaration(kernel, statement, span);
        }
    };
    if let Some(next) = next {
        if next <= line {
            front.count_jump(span)?;
        }
        front.level().next = next;
    }
    Ok(Step::Next)
}

/// The counter and the end of the FOR at line `head`.
fn for_parts(front: &Sinumerik, program: usize, head: usize) -> Result<(Expr, Expr), Alarm> {
    let text = &front.programs[program];
    let line = text.line(head).expect("the head was found on this line");
    let block =
        crate::syntax::sinumerik::parse_block(line.bytes, text.file, line.number, line.base);
    match block.statement.map(|s| s.kind) {
        Some(StatementKind::For { variable, end, .. }) => Ok((variable, end)),
        _ => unreachable!("flow.rs matched an ENDFOR with a FOR"),
    }
}

/// `P=n` of a repetition: 1 when left out.
fn passes_of(front: &mut Sinumerik, kernel: &Kernel, passes: Option<&Expr>) -> Result<u32, Alarm> {
    let Some(expr) = passes else { return Ok(1) };
    let value = front.value(kernel, expr)?;
    if value.fract() != 0.0 || !(0.0..=1e9).contains(&value) {
        return Err(Alarm::error(
            AlarmCode::ValueOutOfRange,
            expr.span,
            format!("P={value}: the number of repetitions is a whole number from 0"),
        ));
    }
    Ok(value as u32)
}

/// `CALL`: the program a string names, whole or between two of its labels; `CALL BLOCK` alone
/// runs a part of the current program once (PGAsl, indirect call).
fn call(
    front: &mut Sinumerik,
    kernel: &Kernel,
    program: Option<&Expr>,
    section: Option<&(Name, Name)>,
    line: usize,
    span: Span,
) -> Result<Step, Alarm> {
    let Some(program) = program else {
        let (start, end) = section.expect("the reader gives CALL a program or a BLOCK part");
        let current = front.levels.last().expect("a level").program;
        let (first, last) = section_lines(front, current, 0, start, end)?;
        if let Some(next) = repeat(front, first, last, line, 1) {
            front.level().next = next;
        }
        return Ok(Step::Next);
    };
    let name = front.text(kernel, program)?;
    let name = program_name(&name);
    if name.is_empty() {
        return Err(Alarm::error(
            AlarmCode::ValueOutOfRange,
            program.span,
            "CALL names no program: the string is empty",
        )
        .with_help("give CALL the program's name, as in CALL \"CONTOUR1\""));
    }
    front.call(&name, 1, span, None)?;
    if let Some((start, end)) = section {
        let called = front.levels.last().expect("the call's level").program;
        let (first, last) = section_lines(front, called, 0, start, end)?;
        let level = front.level();
        level.next = first;
        // After its part the called program returns: its section goes on past the text's end.
        level.sections.push(Section {
            first,
            last,
            back: usize::MAX,
            passes_left: 0,
        });
    }
    Ok(Step::Next)
}

/// The lines of labels `start` and `end` of `program`: the start searched from `from` forwards,
/// then backwards (as GOTO does), the end from the start on.
fn section_lines(
    front: &mut Sinumerik,
    program: usize,
    from: usize,
    start: &Name,
    end: &Name,
) -> Result<(usize, usize), Alarm> {
    let mut find = |line: usize, label: &Name| {
        let jump = Jump {
            kind: JumpKind::Goto,
            target: None,
            span: label.span,
        };
        front
            .structure
            .jump(
                &front.programs,
                program,
                line,
                &jump,
                Target::Label(&label.value),
            )?
            .ok_or_else(|| Alarm::error(AlarmCode::SequenceNotFound, label.span, "label not found"))
    };
    let first = find(from, start)?;
    let last = find(first.saturating_sub(1), end)?;
    if last < first {
        return Err(Alarm::error(
            AlarmCode::SequenceNotFound,
            end.span,
            format!("label {} comes before label {}", end.value, start.value),
        )
        .with_help("CALL .. BLOCK runs from its first label down to its second"));
    }
    Ok((first, last))
}

/// The program's name in a CALL string: `"CONTOUR1"`, or a path of the control's file system
/// (`"/_N_WKS_DIR/_N_PART_WPD/_N_CONTOUR1_SPF"`) reduced to the name.
fn program_name(written: &str) -> String {
    let last = written.rsplit('/').next().unwrap_or(written).trim();
    let upper = last.to_ascii_uppercase();
    let bare = upper.strip_prefix("_N_").unwrap_or(&upper);
    let bare = [".SPF", ".MPF", "_SPF", "_MPF"]
        .iter()
        .find_map(|suffix| bare.strip_suffix(suffix))
        .unwrap_or(bare);
    bare.to_string()
}

/// Runs lines `first..=last` `passes` times, then goes on after line `back`.
fn repeat(
    front: &mut Sinumerik,
    first: usize,
    last: usize,
    back: usize,
    passes: u32,
) -> Option<usize> {
    if passes == 0 || last < first {
        return None;
    }
    front.level().sections.push(Section {
        first,
        last,
        back: back + 1,
        passes_left: passes - 1,
    });
    Some(first)
}

/// Jumps as `jump` says from `line`.
fn jump_to(
    front: &mut Sinumerik,
    kernel: &Kernel,
    jump: &Jump,
    line: usize,
) -> Result<Step, Alarm> {
    let program = front.levels.last().expect("a level").program;
    let label;
    let target = match &jump.target {
        None => Target::Number(0),
        Some(JumpTarget::Label(name)) => Target::Label(&name.value),
        Some(JumpTarget::BlockNumber(n)) => Target::Number(n.value),
        Some(JumpTarget::Expression(expr)) => {
            label = front.text(kernel, expr)?;
            match label.strip_prefix('N').and_then(|n| n.parse::<u32>().ok()) {
                Some(n) => Target::Number(n),
                None => Target::Label(&label),
            }
        }
    };
    if let Some(next) = front
        .structure
        .jump(&front.programs, program, line, jump, target)?
    {
        if next <= line {
            front.count_jump(jump.span)?;
        }
        // A jump leaves the part repetitions it jumps out of.
        let level = front.level();
        level
            .sections
            .retain(|s| (s.first..=s.last).contains(&next));
        level.next = next;
    }
    Ok(Step::Next)
}
