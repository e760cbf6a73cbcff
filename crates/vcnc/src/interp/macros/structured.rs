//! Running the statements of a Syntec `%@MACRO` program: IF/ELSEIF/ELSE/END_IF, CASE/END_CASE,
//! WHILE, FOR, REPEAT ... UNTIL, EXIT, the public variables `@n`, and ALARM(), MSG(), WAIT() and
//! SLEEP().
//!
//! A macro program runs from memory: its `%@MACRO` header, read from a streamed main program,
//! loads the program whole (as a jump does) and the run goes on there. The structured statements
//! jump to the partners `syntax::iso::structure` found for them when the program was read; a
//! statement without its partner raises that alarm when the run reaches it. Every pass back to
//! the start of a loop counts against the jump limit, so a loop that never ends stops with
//! [`AlarmCode::MacroLimit`] at its END_WHILE, END_FOR or UNTIL.
//!
//! The public variables are what Syntec's documentation calls them: `@1` to `@165535`, common to
//! every program of the run; `@0` is vacant. The control maps ranges of them to PLC registers
//! and battery-backed memory; vcnc keeps them all for the run (docs/DEVIATIONS.md).

use super::{eval, MacroValue, Next};
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::{Core, Place};
use crate::source::Span;
use crate::syntax::expr::{Expr, Instruction, Statement, VariableBank};
use crate::syntax::iso::structure::Link;
use crate::syntax::Block;
use std::sync::Arc;

use super::programs::{Position, Program, StoredProgram};

/// The link of the statement at `at` of `program` (a branch a CASE or IF looks at).
fn link_at(program: &StoredProgram, at: Position, span: Span) -> Result<Link, Alarm> {
    match program.structure().and_then(|s| s.link(at)) {
        Some(Ok(link)) => Ok(link),
        Some(Err(alarm)) => Err(alarm.clone()),
        None => Err(wrong_link(span)),
    }
}

/// The highest public variable number.
const PUBLIC_LAST: u32 = 165_535;

impl Core {
    /// `%@MACRO` read from the main program's stream: the program runs from memory from here
    /// on (in memory already, it means nothing).
    pub(crate) fn enter_macro_program(&mut self, span: Span, main_text: Option<&[u8]>) {
        if !matches!(self.place, Place::Stream { .. }) {
            return;
        }
        let loaded = self
            .load_main_whole(main_text, span)
            .and_then(|()| self.current_program(main_text, span));
        if let Err(alarm) = loaded {
            let alarm = if alarm.code == AlarmCode::NotSupportedYet {
                Alarm::not_supported(
                    span,
                    "a %@MACRO program read as a stream (it runs from memory)",
                    None,
                )
            } else {
                alarm
            };
            self.fail(alarm);
        }
    }

    /// The value of `@number`.
    pub(crate) fn read_public(&self, number: u32, span: Span) -> Result<MacroValue, Alarm> {
        match number {
            0 => Ok(None),
            1..=PUBLIC_LAST => Ok(self.macros.vars.public(number)),
            _ => Err(no_public_variable(number, span)),
        }
    }

    /// Sets `@number`.
    pub(crate) fn write_public(
        &mut self,
        number: u32,
        value: MacroValue,
        span: Span,
    ) -> Result<(), Alarm> {
        match number {
            0 => Err(Alarm::error(
                AlarmCode::BadVariable,
                span,
                "@0 cannot be written",
            )),
            1..=PUBLIC_LAST => {
                self.macros.vars.set_public(number, value);
                Ok(())
            }
            _ => Err(no_public_variable(number, span)),
        }
    }

    /// A statement of a macro program (any statement `run_statement` does not run itself).
    pub(super) fn run_structured(
        &mut self,
        statement: &Statement,
        block: &Block,
        main_text: Option<&[u8]>,
    ) -> Result<Next, Alarm> {
        let code = &block.code;
        match *statement {
            Statement::If { condition, span } => {
                let (program, link) = self.link(span, main_text)?;
                if eval::is_true(self.evaluate(condition, code)?) {
                    return Ok(Next::Block);
                }
                self.next_branch(program, link, span)
            }
            Statement::Case { selector, span } => {
                let (program, link) = self.link(span, main_text)?;
                let selector = self.evaluate(selector, code)?;
                self.case_branch(program, link, selector, span)
            }
            Statement::ElseIf { span, .. }
            | Statement::Else { span }
            | Statement::CaseLabel { span, .. } => {
                // Reached in sequence: the branch before it ran; on to the END_IF (END_CASE).
                let (program, link) = self.link(span, main_text)?;
                match link {
                    Link::Branch { end, .. } => Ok(self.jump_after(program, end)),
                    _ => Err(wrong_link(span)),
                }
            }
            Statement::WhileDo { condition, span } => {
                let (program, link) = self.link(span, main_text)?;
                let Link::Loop { end } = link else {
                    return Err(wrong_link(span));
                };
                if eval::is_true(self.evaluate(condition, code)?) {
                    Ok(Next::Block)
                } else {
                    Ok(self.jump_after(program, end))
                }
            }
            Statement::EndWhile { span } => {
                let (program, start) = self.loop_start(span, main_text)?;
                self.count_jump(span)?;
                Ok(self.jump_to(program, start))
            }
            Statement::For { span, .. } => self.start_for(statement, code, span, main_text),
            Statement::EndFor { span } => self.next_pass(span, main_text),
            Statement::Until { condition, span } => {
                let (program, start) = self.loop_start(span, main_text)?;
                if eval::is_true(self.evaluate(condition, code)?) {
                    return Ok(Next::Block);
                }
                self.count_jump(span)?;
                Ok(self.jump_after(program, start))
            }
            Statement::Exit { span } => {
                let (program, link) = self.link(span, main_text)?;
                match link {
                    Link::Exit { end } => Ok(self.jump_after(program, end)),
                    _ => Err(wrong_link(span)),
                }
            }
            Statement::EndIf { span }
            | Statement::EndCase { span }
            | Statement::Repeat { span }
            | Statement::EndRepeat { span } => {
                // Nothing to do, unless the statement has no partner.
                self.check_structure(span, main_text)?;
                Ok(Next::Block)
            }
            Statement::Alarm { number, span } => Err(self.user_alarm(number, block, span)?),
            Statement::Message { number, span } => {
                let number = match number {
                    Some(number) => self.evaluate(number, code)?,
                    None => None,
                };
                let text = block.message.as_deref().unwrap_or("");
                let shown = match number {
                    Some(n) => format!("message {}: {text}", eval::round_half_away(n)),
                    None => format!("message: {text}"),
                };
                let shown = shown.trim_end().trim_end_matches(':').to_string();
                self.out
                    .push_warning(Alarm::warning(AlarmCode::UserAlarm, span, shown));
                Ok(Next::Block)
            }
            _ => Ok(Next::Block),
        }
    }

    /// The program being run and the link of the statement being run.
    fn link(
        &mut self,
        span: Span,
        main_text: Option<&[u8]>,
    ) -> Result<(Arc<StoredProgram>, Link), Alarm> {
        // A main program run from an index is an ISO program: it has no structured statements.
        let Program::Stored(program) = self.current_program(main_text, span)? else {
            return Err(wrong_link(span));
        };
        let at = self.current_position();
        let link = match program.structure().and_then(|s| s.link(at)) {
            Some(Ok(link)) => link,
            Some(Err(alarm)) => return Err(alarm.clone()),
            None => return Err(wrong_link(span)),
        };
        Ok((program, link))
    }

    /// The alarm of a statement that has no partner, if it has one.
    fn check_structure(&mut self, span: Span, main_text: Option<&[u8]>) -> Result<(), Alarm> {
        let Program::Stored(program) = self.current_program(main_text, span)? else {
            return Ok(());
        };
        let at = self.current_position();
        match program.structure().and_then(|s| s.link(at)) {
            Some(Err(alarm)) => Err(alarm.clone()),
            _ => Ok(()),
        }
    }

    /// Where the loop that the statement being run ends starts.
    fn loop_start(
        &mut self,
        span: Span,
        main_text: Option<&[u8]>,
    ) -> Result<(Arc<StoredProgram>, Position), Alarm> {
        match self.link(span, main_text)? {
            (program, Link::Back { start }) => Ok((program, start)),
            _ => Err(wrong_link(span)),
        }
    }

    fn jump_to(&mut self, program: Arc<StoredProgram>, (line, block): Position) -> Next {
        self.place = Place::stored(Program::Stored(program), (line, block));
        Next::Jumped
    }

    fn jump_after(&mut self, program: Arc<StoredProgram>, (line, block): Position) -> Next {
        self.jump_to(program, (line, block + 1))
    }

    /// An IF or ELSEIF whose condition failed: the first later branch whose condition holds
    /// runs (an ELSE always does), else the run goes on after END_IF.
    fn next_branch(
        &mut self,
        program: Arc<StoredProgram>,
        link: Link,
        span: Span,
    ) -> Result<Next, Alarm> {
        self.take_branch(program, link, span, |core, block| {
            match block.statements.first() {
                Some(&Statement::ElseIf { condition, .. }) => {
                    Ok(eval::is_true(core.evaluate(condition, &block.code)?))
                }
                Some(Statement::Else { .. }) => Ok(true),
                _ => Err(wrong_link(span)),
            }
        })
    }

    /// CASE: the run goes on after the first label equal to `selector` (as EQ compares: a
    /// vacant selector equals no label), else after ELSE, else after END_CASE.
    fn case_branch(
        &mut self,
        program: Arc<StoredProgram>,
        link: Link,
        selector: MacroValue,
        span: Span,
    ) -> Result<Next, Alarm> {
        self.take_branch(program, link, span, |_, block| {
            if let Some(alarm) = block.alarms.iter().find(|a| a.is_error()) {
                // A label that could not be read: the CASE stops there.
                return Err(alarm.clone());
            }
            match block.statements.first() {
                Some(Statement::CaseLabel { .. }) => Ok(block.statements.iter().any(|s| {
                    matches!(*s, Statement::CaseLabel { value, .. } if eval::equal(selector, Some(value)))
                })),
                Some(Statement::Else { .. }) => Ok(true),
                _ => Err(wrong_link(span)),
            }
        })
    }

    /// Walks the branches from `link` on (an IF's ELSEIFs and ELSE, a CASE's labels and ELSE)
    /// until `runs` takes one: the run goes on after it, or after the END when none does.
    fn take_branch(
        &mut self,
        program: Arc<StoredProgram>,
        mut link: Link,
        span: Span,
        mut runs: impl FnMut(&Core, &Block) -> Result<bool, Alarm>,
    ) -> Result<Next, Alarm> {
        loop {
            let Link::Branch { next, end } = link else {
                return Err(wrong_link(span));
            };
            if next == end {
                return Ok(self.jump_after(program, end));
            }
            let Some(block) = program.block(next) else {
                return Err(wrong_link(span));
            };
            if runs(self, block)? {
                return Ok(self.jump_after(program, next));
            }
            link = link_at(&program, next, span)?;
        }
    }

    /// FOR: sets the counter to its first value and runs the body, unless that value is past
    /// the last.
    fn start_for(
        &mut self,
        statement: &Statement,
        code: &[Instruction],
        span: Span,
        main_text: Option<&[u8]>,
    ) -> Result<Next, Alarm> {
        let (program, link) = self.link(span, main_text)?;
        let Link::Loop { end } = link else {
            return Err(wrong_link(span));
        };
        let &Statement::For { variable, from, .. } = statement else {
            return Err(wrong_link(span));
        };
        let (number, number_span) = self.target_number(variable, code, span)?;
        let first = self.evaluate(from, code)?;
        self.write_target(variable.bank, number, first, number_span, None)?;
        if self.for_goes_on(statement, code, first.unwrap_or(0.0))? {
            Ok(Next::Block)
        } else {
            Ok(self.jump_after(program, end))
        }
    }

    /// END_FOR: the counter takes its next value; back to the body unless it is past the last.
    fn next_pass(&mut self, span: Span, main_text: Option<&[u8]>) -> Result<Next, Alarm> {
        let (program, start) = self.loop_start(span, main_text)?;
        let Some(for_block) = program.block(start) else {
            return Err(wrong_link(span));
        };
        let Some(&statement @ Statement::For { variable, step, .. }) = for_block.statements.first()
        else {
            return Err(wrong_link(span));
        };
        let code = &for_block.code;
        let (number, number_span) = self.target_number(variable, code, statement.span())?;
        let value = match variable.bank {
            VariableBank::Macro => self.read_variable(number, number_span)?,
            VariableBank::Public => self.read_public(number, number_span)?,
        };
        let next = value.unwrap_or(0.0) + self.for_step(step, code, statement.span())?;
        self.write_target(variable.bank, number, Some(next), number_span, None)?;
        if !self.for_goes_on(&statement, code, next)? {
            return Ok(Next::Block);
        }
        self.count_jump(span)?;
        Ok(self.jump_after(program, start))
    }

    /// True while the FOR counter `value` has not passed the last value (from above for a
    /// negative step).
    fn for_goes_on(
        &self,
        statement: &Statement,
        code: &[Instruction],
        value: f64,
    ) -> Result<bool, Alarm> {
        let &Statement::For { to, step, span, .. } = statement else {
            return Err(wrong_link(statement.span()));
        };
        let last = self.evaluate(to, code)?.unwrap_or(0.0);
        let step = self.for_step(step, code, span)?;
        Ok(if step > 0.0 {
            value <= last
        } else {
            value >= last
        })
    }

    /// The step of a FOR (BY, 1 when not written); 0 would never end.
    fn for_step(&self, step: Option<Expr>, code: &[Instruction], span: Span) -> Result<f64, Alarm> {
        let Some(step) = step else {
            return Ok(1.0);
        };
        let at = step.span(code).unwrap_or(span);
        match self.evaluate(step, code)? {
            Some(value) if value != 0.0 => Ok(value),
            _ => Err(Alarm::error(
                AlarmCode::MacroLimit,
                at,
                "FOR ... BY 0: the loop would never end",
            )),
        }
    }

    /// ALARM(n) or ALARM(n, "text"): the program stops with its own alarm.
    fn user_alarm(&self, number: Expr, block: &Block, span: Span) -> Result<Alarm, Alarm> {
        let number = self.evaluate(number, &block.code)?.unwrap_or(0.0);
        let text = block.message.as_deref().unwrap_or("");
        let message = format!("alarm {}: {text}", eval::round_half_away(number));
        Ok(Alarm::error(
            AlarmCode::UserAlarm,
            span,
            message.trim_end().trim_end_matches(':').to_string(),
        )
        .with_help("the program raised this alarm itself (ALARM)"))
    }
}

fn no_public_variable(number: u32, span: Span) -> Alarm {
    Alarm::error(
        AlarmCode::BadVariable,
        span,
        format!("@{number}: public variables are @1 to @{PUBLIC_LAST}"),
    )
}

/// A structured statement whose partner is not what it should be: the structure of the program
/// and the statement disagree (a bug, not the program's fault).
fn wrong_link(span: Span) -> Alarm {
    Alarm::error(
        AlarmCode::LoopStructure,
        span,
        "this statement has no partner in the program's structure",
    )
}
