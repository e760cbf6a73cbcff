//! Custom Macro B and subprograms: variables, expressions, IF/WHILE/GOTO, and the calls M98,
//! M99, M97 (Haas), M198, G65 and G66; the structured statements and public variables of
//! Syntec `%@MACRO` programs are in `structured.rs`.
//!
//! A block with macro content comes here from the interpreter: its statements run in the order
//! written, then its words are evaluated (a vacant variable drops its word) and the block runs
//! as any other. Calls and returns run after the block's own words, as the controls do
//! (`G52 X100. M98 P2011` shifts, then calls). Programs are found in memory or loaded once
//! (`programs.rs`); a jump in a main program that was streamed indexes its file and runs from
//! the index (`indexed.rs`), or loads it whole when its text is in memory or cannot be read
//! again from any place.
//!
//! Limits keep a program from running forever or nesting without end: backward jumps per run
//! ([`Limits::jumps`]), call depth (the profile's `call_depth`, `macro_call_depth`), and the
//! size of a program held in memory.

pub(crate) mod eval;
pub(crate) mod indexed;
pub(crate) mod interrupt;
pub(crate) mod programs;
mod structured;
pub(crate) mod system;
pub(crate) mod vars;

use super::{Core, Place};
use crate::alarm::{Alarm, AlarmCode};
use crate::motion::{EndKind, SegmentKind, StopKind};
use crate::profile::{DecimalLess, GCode, Group, MCode};
use crate::source::Span;
use crate::syntax::expr::{Expr, Instruction, Statement, Target, VariableBank};
use crate::syntax::lines::{needs_normalizing, normalize};
use crate::syntax::{Block, Number, Word};
use indexed::IndexedFile;
use programs::{Position, Program, ProgramLibrary, StoredProgram};
use std::collections::HashMap;
use std::sync::Arc;
use system::{Counters, WriteEffect};
use vars::{Kind, Locals, Ranges, Variables};

/// A macro value: `None` is vacant.
pub(crate) type MacroValue = Option<f64>;

/// Limits on a macro program's run.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Limits {
    /// Backward jumps (loop passes, GOTO back, repeats) in one run: beyond, the program is taken
    /// to loop forever and stops with an alarm.
    pub jumps: u64,
    /// Passes of a main program that ends in M99 (the control repeats it until reset): after
    /// these, the run ends with a warning.
    pub main_program_passes: u32,
    /// The largest program text held in memory for jumps and calls, bytes.
    pub program_bytes: usize,
}

impl Default for Limits {
    fn default() -> Limits {
        Limits {
            jumps: 10_000_000,
            main_program_passes: 1,
            program_bytes: 256 << 20,
        }
    }
}

/// A loop being run: its number and where its WHILE (or DO) is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct ActiveLoop {
    label: u32,
    at: Position,
}

/// A call in progress.
struct CallFrame {
    /// Where the caller goes on after M99.
    return_to: Place,
    /// The called program and where the call started in it (for repeats).
    program: Program,
    start: Position,
    repeats_left: u32,
    /// G65/G66: the arguments the call started with (a level of locals was pushed).
    arguments: Option<Box<Locals>>,
    /// The caller's loops, back in force after the return.
    loops: Vec<ActiveLoop>,
    /// Called by G66 after a move: moves inside do not call again.
    modal: bool,
    /// The calling block.
    span: Span,
    /// Called by the interrupt signal (M96): where it came.
    interrupted: Option<interrupt::Interrupted>,
}

/// G66 in force.
#[derive(Clone, Debug)]
pub(crate) struct ModalCall {
    program: u32,
    repeats: u32,
    arguments: Box<Locals>,
}

/// The main program's file, loaded when needed.
enum MainFile {
    /// Its text, whole: the block source's, or a file that cannot be read again from any place.
    Whole(FileText),
    /// An index into the file (`indexed.rs`).
    Indexed(Arc<IndexedFile>),
}

/// The main program's file, held whole.
struct FileText {
    text: Arc<[u8]>,
    headers: Vec<(u32, usize, u32)>,
    main_end: usize,
}

/// What the macro layer keeps between blocks.
#[derive(Default)]
pub(crate) struct Macros {
    pub(crate) vars: Variables,
    pub(crate) counters: Counters,
    calls: Vec<CallFrame>,
    loops: Vec<ActiveLoop>,
    pub(crate) modal_call: Option<ModalCall>,
    jumps: u64,
    main_passes: u32,
    pub(crate) library: Option<Box<dyn ProgramLibrary>>,
    main: Option<Program>,
    file: Option<MainFile>,
    programs: HashMap<u32, Arc<StoredProgram>>,
    /// The words of the block being run, with their expressions evaluated (reused).
    resolved: Block,
    /// The line of the main program's stream that is being run (1-based).
    pub(crate) stream_line: u32,
    /// Where the stream stopped when the main program went to its index: (line, next block).
    stream_at: Option<Position>,
    /// M96's interrupt program and the signals still to come.
    pub(crate) interrupts: interrupt::Interrupts,
}

/// Where M99 goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Return {
    /// Back to the caller (after the calling block; an interrupt program: to the interrupted
    /// block).
    Caller,
    /// P: the block with this sequence number in the caller.
    Sequence(u32),
    /// Q: this line of the main program (an interrupt program's return).
    Line(u32),
}

impl Macros {
    /// True inside a called program.
    #[inline]
    pub(crate) fn in_call(&self) -> bool {
        !self.calls.is_empty()
    }

    /// True when the main program, run from its index, has come to where its stream stopped:
    /// the run goes on from the stream (parsed ahead, and nothing read twice), which then
    /// forgets that place.
    #[inline]
    pub(crate) fn resumes_stream(&mut self, at: Position) -> bool {
        let resumes = self.stream_at == Some(at) && !self.in_call();
        if resumes {
            self.stream_at = None;
        }
        resumes
    }
}

/// What a statement did to the flow of the program.
enum Next {
    /// Go on with the block.
    Block,
    /// Control went elsewhere: the rest of the block does not run.
    Jumped,
}

/// Reads variables through the interpreter's state.
struct StateReader<'a> {
    core: &'a Core,
}

impl eval::VariableReader for StateReader<'_> {
    fn read(&mut self, number: u32, span: Span) -> Result<MacroValue, Alarm> {
        self.core.read_variable(number, span)
    }

    fn read_public(&mut self, number: u32, span: Span) -> Result<MacroValue, Alarm> {
        self.core.read_public(number, span)
    }
}

fn alarm(code: AlarmCode, span: Span, message: impl Into<String>) -> Alarm {
    Alarm::error(code, span, message)
}

impl Core {
    /// What kind of variable `#number` is on this profile.
    fn variable_kind(&self, number: u32) -> Kind {
        let ranges = Ranges::of(&self.exec.kernel.setup.profile().macros);
        Variables::kind(number, &ranges)
    }

    /// The value of `#number`.
    pub(crate) fn read_variable(&self, number: u32, span: Span) -> Result<MacroValue, Alarm> {
        let kind = self.variable_kind(number);
        match kind {
            Kind::System => {
                system::read(&self.exec, &self.out, &self.macros.counters, number, span)
            }
            _ => Ok(self.macros.vars.get(number, kind)),
        }
    }

    fn evaluate(&self, expr: Expr, code: &[Instruction]) -> Result<MacroValue, Alarm> {
        eval::evaluate(expr, code, &mut StateReader { core: self })
    }

    /// Haas G47 P1: the block's `(####)` becomes the serial number of #599 with as many digits,
    /// and #599 counts on once the block has run (`engraved`).
    ///
    /// # Errors
    /// A comment without `#`, a serial number that is not a whole number from 0.
    pub(crate) fn serial_engraving(&mut self, engraved: bool) -> Result<(), Alarm> {
        const SERIAL: u32 = 599;
        let span = self.command.span;
        let value = self.read_variable(SERIAL, span)?;
        if engraved {
            let next = value.unwrap_or(0.0) + 1.0;
            return self.write_variable(SERIAL, Some(next), span, None);
        }
        let comment = self.command.text().unwrap_or("");
        let text = super::engraving::serial_text(comment, value, span)?;
        self.command.replace_text(&text);
        Ok(())
    }

    /// Sets `#number`; `message` is the block's comment (for #3000 and #3006).
    fn write_variable(
        &mut self,
        number: u32,
        value: MacroValue,
        span: Span,
        message: Option<&str>,
    ) -> Result<(), Alarm> {
        let kind = self.variable_kind(number);
        match kind {
            Kind::Vacant => Err(alarm(AlarmCode::BadVariable, span, "#0 cannot be written")),
            Kind::System => {
                match system::write(
                    &mut self.exec,
                    &mut self.macros.counters,
                    number,
                    value,
                    span,
                )? {
                    WriteEffect::None => Ok(()),
                    WriteEffect::Alarm(n) => {
                        let number = 3000.0 + n.round();
                        let text = message.unwrap_or("");
                        Err(alarm(
                            AlarmCode::UserAlarm,
                            span,
                            format!("alarm {number}: {text}")
                                .trim_end()
                                .trim_end_matches(':')
                                .to_string(),
                        )
                        .with_help("the program raised this alarm itself (#3000)"))
                    }
                    WriteEffect::Stop => {
                        let cmd = super::decode::Command::at(span);
                        self.out.push(
                            &cmd,
                            SegmentKind::Stop {
                                kind: StopKind::Message,
                            },
                        );
                        self.out.push_warning(Alarm::warning(
                            AlarmCode::UserAlarm,
                            span,
                            format!("program stop (#3006): {}", message.unwrap_or("")),
                        ));
                        Ok(())
                    }
                }
            }
            _ => {
                self.macros.vars.set(number, kind, value);
                Ok(())
            }
        }
    }

    /// A block with statements or expression words.
    pub(super) fn run_macro_block(&mut self, block: &Block, main_text: Option<&[u8]>) {
        for statement in &block.statements {
            match self.run_statement(statement, block, main_text) {
                Ok(Next::Block) => {}
                Ok(Next::Jumped) => {
                    self.blocks_executed += 1;
                    return;
                }
                Err(alarm) => return self.fail(self.with_call_stack(alarm)),
            }
        }
        if !block.words.iter().any(|w| w.letter != b'N') {
            self.blocks_executed += 1;
            return;
        }
        let mut resolved = std::mem::take(&mut self.macros.resolved);
        match self.resolve_words(block, &mut resolved) {
            Ok(()) => self.run_words(&resolved, main_text),
            Err(alarm) => self.fail(self.with_call_stack(alarm)),
        }
        self.macros.resolved = resolved;
    }

    /// `alarm` with the calls that led to it, innermost first: one label on each calling
    /// block (G65/G66, M98, M96's interrupt), saying which program it called.
    fn with_call_stack(&self, mut alarm: Alarm) -> Alarm {
        for frame in self.macros.calls.iter().rev() {
            let called = frame
                .program
                .number()
                .map_or_else(|| "a program".to_string(), |n| format!("O{n:04}"));
            let how = if frame.interrupted.is_some() {
                "the interrupt signal called"
            } else if frame.arguments.is_some() {
                "this macro call ran"
            } else {
                "this call ran"
            };
            alarm = alarm.with_label(frame.span, format!("{how} {called}"));
        }
        alarm
    }

    /// The words of `block` with their expressions evaluated, into `out`: a vacant value
    /// leaves its word out (`G00 X1. Y#1` with #1 vacant is `G00 X1.`).
    fn resolve_words(&self, block: &Block, out: &mut Block) -> Result<(), Alarm> {
        out.clear();
        out.span = block.span;
        out.comment = block.comment;
        for word in &block.words {
            let Some(expr) = word.expr else {
                out.words.push(*word);
                continue;
            };
            let Some(value) = self.evaluate(expr, &block.code)? else {
                continue;
            };
            out.words.push(Word {
                number: self.address_number(word.letter, value),
                expr: None,
                ..*word
            });
        }
        Ok(())
    }

    /// A macro value given to an address: rounded to the least input increment for lengths
    /// and angles, as the controls do, and read as if written with a decimal point.
    fn address_number(&self, letter: u8, value: f64) -> Number {
        let profile = self.exec.kernel.setup.profile();
        let increment = match letter {
            b'X' | b'Y' | b'Z' | b'U' | b'V' | b'W' | b'I' | b'J' | b'K' | b'R' | b'Q' => {
                match self.exec.modal.units {
                    super::modal::Units::Millimetres => profile.units.increment_mm,
                    super::modal::Units::Inches => profile.units.increment_inch,
                }
            }
            b'A' | b'B' | b'C' => profile.units.increment_deg,
            _ => 0.0,
        };
        let rounded = if increment > 0.0 && value.abs() < 1e12 {
            (value / increment).round() * increment
        } else {
            value
        };
        Number {
            value: rounded,
            decimal_point: true,
            negative: value.is_sign_negative(),
        }
    }

    fn run_statement(
        &mut self,
        statement: &Statement,
        block: &Block,
        main_text: Option<&[u8]>,
    ) -> Result<Next, Alarm> {
        let code = &block.code;
        let message = block.message.as_deref();
        match *statement {
            Statement::Assign {
                variable,
                value,
                span,
            } => {
                self.assign(variable, value, code, span, message)?;
                Ok(Next::Block)
            }
            Statement::IfThen {
                condition,
                variable,
                value,
                span,
            } => {
                if eval::is_true(self.evaluate(condition, code)?) {
                    let variable = Target {
                        bank: VariableBank::Macro,
                        number: variable,
                    };
                    self.assign(variable, value, code, span, message)?;
                }
                Ok(Next::Block)
            }
            Statement::Goto { target, span } => {
                let label = self.sequence_number(target, code, span)?;
                self.goto(label, span, main_text)?;
                Ok(Next::Jumped)
            }
            Statement::IfGoto {
                condition,
                target,
                span,
            } => {
                if !eval::is_true(self.evaluate(condition, code)?) {
                    return Ok(Next::Block);
                }
                let label = self.sequence_number(target, code, span)?;
                self.goto(label, span, main_text)?;
                Ok(Next::Jumped)
            }
            Statement::While {
                condition,
                label,
                span,
            } => self.run_while(condition, label, code, span, main_text),
            Statement::End { label, span } => {
                self.run_end(label, span, main_text)?;
                Ok(Next::Jumped)
            }
            _ => self.run_structured(statement, block, main_text),
        }
    }

    fn assign(
        &mut self,
        variable: Target,
        value: Expr,
        code: &[Instruction],
        span: Span,
        message: Option<&str>,
    ) -> Result<(), Alarm> {
        let (number, number_span) = self.target_number(variable, code, span)?;
        let value = self.evaluate(value, code)?;
        self.write_target(variable.bank, number, value, number_span, message)
    }

    /// The number of the variable `variable` names, and where it is written.
    fn target_number(
        &self,
        variable: Target,
        code: &[Instruction],
        span: Span,
    ) -> Result<(u32, Span), Alarm> {
        let number_span = variable.number.span(code).unwrap_or(span);
        let number = eval::variable_number(self.evaluate(variable.number, code)?, number_span)?;
        Ok((number, number_span))
    }

    /// Sets `#number` or `@number`.
    fn write_target(
        &mut self,
        bank: VariableBank,
        number: u32,
        value: MacroValue,
        span: Span,
        message: Option<&str>,
    ) -> Result<(), Alarm> {
        match bank {
            VariableBank::Macro => self.write_variable(number, value, span, message),
            VariableBank::Public => self.write_public(number, value, span),
        }
    }

    /// The sequence number of a GOTO.
    fn sequence_number(
        &self,
        target: Expr,
        code: &[Instruction],
        span: Span,
    ) -> Result<u32, Alarm> {
        let at = target.span(code).unwrap_or(span);
        match self.evaluate(target, code)? {
            Some(v) if (1.0..=99_999_999.0).contains(&eval::round_half_away(v)) => {
                Ok(eval::round_half_away(v) as u32)
            }
            Some(v) => Err(alarm(
                AlarmCode::SequenceNotFound,
                at,
                format!("GOTO {v}: a sequence number is 1 to 99999999"),
            )),
            None => Err(alarm(
                AlarmCode::SequenceNotFound,
                at,
                "GOTO to a vacant sequence number",
            )),
        }
    }

    /// Where the block being run stands in its program.
    fn current_position(&self) -> Position {
        match &self.place {
            Place::Stored { line, block, .. } | Place::Indexed { line, block, .. } => {
                (*line, block.saturating_sub(1))
            }
            Place::Stream { block, .. } => (
                self.macros.stream_line.saturating_sub(1) as usize,
                block.saturating_sub(1),
            ),
        }
    }

    /// The program being run, in memory: a streamed main program is loaded now, and the run
    /// goes on from memory at the same place.
    fn current_program(&mut self, main_text: Option<&[u8]>, span: Span) -> Result<Program, Alarm> {
        match &self.place {
            Place::Stored { program, .. } => Ok(Program::Stored(Arc::clone(program))),
            Place::Indexed { program, .. } => Ok(Program::Indexed(Arc::clone(program))),
            Place::Stream { block, .. } => {
                let block = *block;
                let main = self.main_program(main_text, span)?;
                let line = self.macros.stream_line.saturating_sub(1) as usize;
                if matches!(&main, Program::Indexed(index) if line < index.lines()) {
                    // The stream stays here: the run goes back to it when it gets here again.
                    self.macros.stream_at = Some((line, block));
                }
                self.place = Place::stored(main.clone(), (line, block));
                Ok(main)
            }
        }
    }

    /// Loads the main program's file (once): its text when the block source has it, else an
    /// index into the file, else (a file that cannot be read again from any place) its text.
    fn load_file(&mut self, main_text: Option<&[u8]>, span: Span) -> Result<&MainFile, Alarm> {
        if self.macros.file.is_none() {
            let file = match main_text {
                Some(text) => MainFile::Whole(self.whole_file(Arc::from(text), span)?),
                None => self.library_file(span)?,
            };
            self.macros.file = Some(file);
        }
        Ok(self.macros.file.as_ref().expect("loaded above"))
    }

    /// The main program's file through the library: indexed when it can be read again.
    fn library_file(&mut self, span: Span) -> Result<MainFile, Alarm> {
        let library = self.macros.library.as_mut();
        if let Some(file) = library.and_then(|l| l.open_main()) {
            let scanned = IndexedFile::scan(
                &file,
                indexed::Bytes::File(file.try_clone().map_err(|e| read_alarm(span, &e))?),
                self.file,
                self.exec.kernel.setup.profile().syntax(),
            );
            return match scanned {
                Ok(index) => Ok(MainFile::Indexed(Arc::new(index))),
                Err(error) => Err(read_alarm(span, &error)),
            };
        }
        match self.macros.library.as_mut().and_then(|l| l.main_text()) {
            Some(text) => Ok(MainFile::Whole(self.whole_file(text, span)?)),
            None => Err(alarm(
                AlarmCode::NotSupportedYet,
                span,
                "this jump or call needs the program text in memory, and the program is read as a stream",
            )
            .with_help("give the interpreter a program library that can read the main file")),
        }
    }

    /// A main program's text of `length` bytes may be held whole.
    fn check_held_size(&self, length: usize, span: Span) -> Result<(), Alarm> {
        let most = self.options.limits.program_bytes;
        if length > most {
            return Err(alarm(
                AlarmCode::MacroLimit,
                span,
                format!("the program is larger than {most} bytes: too large to hold for jumps"),
            ));
        }
        Ok(())
    }

    /// A main program's file held whole, its headers found.
    fn whole_file(&self, text: Arc<[u8]>, span: Span) -> Result<FileText, Alarm> {
        self.check_held_size(text.len(), span)?;
        // Read as the line readers read it: a byte-order mark and lone `\r`s rewritten.
        let text = if needs_normalizing(&text, true) {
            let mut copy = text.to_vec();
            normalize(&mut copy, true);
            Arc::from(copy)
        } else {
            text
        };
        let headers = programs::program_headers(&text, &self.exec.kernel.setup.profile().syntax());
        let main_end = programs::main_program_end(&text, &headers);
        Ok(FileText {
            text,
            headers,
            main_end,
        })
    }

    fn main_program(&mut self, main_text: Option<&[u8]>, span: Span) -> Result<Program, Alarm> {
        if let Some(main) = &self.macros.main {
            return Ok(main.clone());
        }
        let syntax = self.exec.kernel.setup.profile().syntax();
        let file_id = self.file;
        let main = match self.load_file(main_text, span)? {
            MainFile::Whole(file) => Program::Stored(Arc::new(StoredProgram::parse(
                &file.text,
                (0, 1, file.main_end),
                file_id,
                &syntax,
                None,
            ))),
            MainFile::Indexed(index) => Program::Indexed(Arc::clone(index)),
        };
        self.macros.main = Some(main.clone());
        Ok(main)
    }

    /// Loads the main program whole, whatever file it is in: a Syntec `%@MACRO` program runs
    /// from its whole text (its statements' partners are found over all of it).
    fn load_main_whole(&mut self, main_text: Option<&[u8]>, span: Span) -> Result<(), Alarm> {
        if self.macros.main.is_some() {
            return Ok(());
        }
        let text = match self.load_file(main_text, span)? {
            MainFile::Whole(_) => return Ok(()),
            MainFile::Indexed(index) => index.main_text().map_err(|e| read_alarm(span, &e))?,
        };
        self.check_held_size(text.len(), span)?;
        let program = StoredProgram::parse(
            &text,
            (0, 1, text.len()),
            self.file,
            &self.exec.kernel.setup.profile().syntax(),
            None,
        );
        self.macros.main = Some(Program::Stored(Arc::new(program)));
        Ok(())
    }

    /// Program `number`: from the main program's file, else from the library.
    fn find_program(
        &mut self,
        number: u32,
        main_text: Option<&[u8]>,
        span: Span,
    ) -> Result<Arc<StoredProgram>, Alarm> {
        if let Some(program) = self.macros.programs.get(&number) {
            return Ok(Arc::clone(program));
        }
        let mut found = None;
        let have_text = main_text.is_some() || self.macros.library.is_some();
        if have_text && self.load_file(main_text, span).is_ok() {
            found = self.program_in_main_file(number, span)?;
        }
        if found.is_none() {
            found = self.program_in_library(number, span)?;
        }
        let Some(program) = found else {
            return Err(alarm(
                AlarmCode::ProgramNotFound,
                span,
                format!(
                    "program O{number:04} is neither in this file nor in the program directory"
                ),
            )
            .with_help("put it after M30 in the same file, or pass its directory with --lib DIR"));
        };
        let program = Arc::new(program);
        self.macros.programs.insert(number, Arc::clone(&program));
        Ok(program)
    }

    /// Program `number` from the main program's file, once that is loaded.
    fn program_in_main_file(
        &self,
        number: u32,
        span: Span,
    ) -> Result<Option<StoredProgram>, Alarm> {
        let syntax = self.exec.kernel.setup.profile().syntax();
        match &self.macros.file {
            None => Ok(None),
            Some(MainFile::Whole(file)) => {
                let extent = programs::program_extent(&file.headers, number, file.text.len());
                let Some((offset, line, end)) = extent else {
                    return Ok(None);
                };
                Ok(Some(StoredProgram::parse(
                    &file.text,
                    (offset, line, end),
                    self.file,
                    &syntax,
                    Some(number),
                )))
            }
            Some(MainFile::Indexed(index)) => {
                let text = index
                    .program_text(number)
                    .map_err(|e| read_alarm(span, &e))?;
                let Some((text, base, line)) = text else {
                    return Ok(None);
                };
                if text.len() > self.options.limits.program_bytes {
                    return Err(too_large(number, span));
                }
                let base = usize::try_from(base).unwrap_or(usize::MAX);
                Ok(Some(StoredProgram::parse_piece(
                    &text,
                    (base, line),
                    self.file,
                    &syntax,
                    Some(number),
                )))
            }
        }
    }

    /// Program `number` from the library, if there is one and it has it.
    fn program_in_library(
        &mut self,
        number: u32,
        span: Span,
    ) -> Result<Option<StoredProgram>, Alarm> {
        let syntax = self.exec.kernel.setup.profile().syntax();
        let Some(library) = self.macros.library.as_mut() else {
            return Ok(None);
        };
        let Some(text) = library.find(number).map_err(|e| lookup_alarm(&e, span))? else {
            return Ok(None);
        };
        if text.text.len() > self.options.limits.program_bytes {
            return Err(too_large(number, span));
        }
        let headers = programs::program_headers(&text.text, &syntax);
        let (offset, line, end) = programs::program_extent(&headers, number, text.text.len())
            .unwrap_or((0, 1, text.text.len()));
        Ok(Some(StoredProgram::parse(
            &text.text,
            (offset, line, end),
            text.file,
            &syntax,
            Some(number),
        )))
    }

    /// Counts a backward jump against the limit.
    fn count_jump(&mut self, span: Span) -> Result<(), Alarm> {
        self.macros.jumps += 1;
        if self.macros.jumps > self.options.limits.jumps {
            return Err(alarm(
                AlarmCode::MacroLimit,
                span,
                format!(
                    "more than {} loop passes and backward jumps: the program seems to loop forever",
                    self.options.limits.jumps
                ),
            )
            .with_help("raise the limit with --max-jumps if the program really needs more"));
        }
        Ok(())
    }

    fn goto(&mut self, label: u32, span: Span, main_text: Option<&[u8]>) -> Result<(), Alarm> {
        let program = self.current_program(main_text, span)?;
        let from = self.current_position();
        let found = program.find_label(label, Some(from));
        let Some(target) = found.map_err(|e| read_alarm(span, &e))? else {
            return Err(alarm(
                AlarmCode::SequenceNotFound,
                span,
                format!("GOTO {label}: the program has no block N{label}"),
            ));
        };
        if target <= from {
            self.count_jump(span)?;
        }
        // Loops the jump leaves are over.
        while let Some(active) = self.macros.loops.last() {
            let end = program
                .find_loop_end(active.at, active.label)
                .map_err(|e| read_alarm(span, &e))?;
            if target > active.at && end.is_some_and(|end| target <= end) {
                break;
            }
            self.macros.loops.pop();
        }
        self.place = Place::stored(program, target);
        Ok(())
    }

    fn check_loop_number(&self, label: u32, span: Span) -> Result<(), Alarm> {
        let most = self.exec.kernel.setup.profile().macros.loop_numbers;
        if label == 0 || label > most {
            return Err(alarm(
                AlarmCode::LoopStructure,
                span,
                format!("loop number {label}: this control has DO1 to DO{most}"),
            ));
        }
        Ok(())
    }

    fn run_while(
        &mut self,
        condition: Option<Expr>,
        label: u32,
        code: &[Instruction],
        span: Span,
        main_text: Option<&[u8]>,
    ) -> Result<Next, Alarm> {
        self.check_loop_number(label, span)?;
        let at = self.current_position();
        let holds = match condition {
            Some(condition) => eval::is_true(self.evaluate(condition, code)?),
            None => true,
        };
        let active = self.macros.loops.last().is_some_and(|l| l.at == at);
        if holds {
            if !active {
                if self.macros.loops.iter().any(|l| l.label == label) {
                    return Err(alarm(
                        AlarmCode::LoopStructure,
                        span,
                        format!("DO{label} inside a loop that already uses DO{label}"),
                    ));
                }
                self.macros.loops.push(ActiveLoop { label, at });
            }
            return Ok(Next::Block);
        }
        if active {
            self.macros.loops.pop();
        }
        let program = self.current_program(main_text, span)?;
        let found = program.find_loop_end(at, label);
        let Some(end) = found.map_err(|e| read_alarm(span, &e))? else {
            return Err(alarm(
                AlarmCode::LoopStructure,
                span,
                format!("DO{label} has no END{label} after it"),
            ));
        };
        self.place = Place::stored(program, (end.0, end.1 + 1));
        Ok(Next::Jumped)
    }

    fn run_end(&mut self, label: u32, span: Span, main_text: Option<&[u8]>) -> Result<(), Alarm> {
        self.check_loop_number(label, span)?;
        let at = match self.macros.loops.last() {
            Some(active) if active.label == label => active.at,
            Some(active) => {
                return Err(alarm(
                    AlarmCode::LoopStructure,
                    span,
                    format!(
                        "END{label} inside DO{}: loops must nest, not overlap",
                        active.label
                    ),
                ))
            }
            None => {
                return Err(alarm(
                    AlarmCode::LoopStructure,
                    span,
                    format!("END{label} without its DO{label}"),
                )
                .with_help("a GOTO may leave a loop but not jump into one"))
            }
        };
        self.count_jump(span)?;
        let program = self.current_program(main_text, span)?;
        self.place = Place::stored(program, at);
        Ok(())
    }

    /// The calls, returns and modal calls of the block just run.
    ///
    /// # Errors
    /// The alarm of a call or return that cannot be made, with the calls that led to it.
    pub(super) fn run_calls(
        &mut self,
        block: &Block,
        main_text: Option<&[u8]>,
    ) -> Result<(), Alarm> {
        self.run_calls_of(block, main_text)
            .map_err(|alarm| self.with_call_stack(alarm))
    }

    fn run_calls_of(&mut self, block: &Block, main_text: Option<&[u8]>) -> Result<(), Alarm> {
        if self
            .command
            .group(Group::ModalMacro)
            .is_some_and(|g| g.code == GCode::ModalMacroCancel)
        {
            self.macros.modal_call = None;
        }
        if let Some((code, word)) = self.command.subprogram() {
            return match code {
                MCode::SubprogramCall | MCode::ExternalSubprogramCall => {
                    self.subprogram_call(word.span, main_text)
                }
                MCode::LocalSubprogramCall => self.local_call(word.span, main_text),
                MCode::SubprogramReturn => self.subprogram_return(word.span, main_text),
                MCode::InterruptOn => self.arm_interrupt(word.span),
                MCode::InterruptOff => {
                    self.disarm_interrupt();
                    Ok(())
                }
                // Only the codes above are subprogram flow (`MCode::is_subprogram_flow`).
                _ => Ok(()),
            };
        }
        if let Some((g, first_argument)) = self.command.macro_call() {
            let (number, repeats, arguments) =
                self.macro_arguments(block, first_argument, g.span)?;
            if g.code == GCode::MacroCall {
                let program = Program::Stored(self.find_program(number, main_text, g.span)?);
                return self.call(program, (0, 0), repeats, Some(arguments), false, g.span);
            }
            self.macros.modal_call = Some(ModalCall {
                program: number,
                repeats,
                arguments,
            });
            return Ok(());
        }
        let in_modal_macro = self.macros.calls.iter().any(|c| c.modal);
        if let Some(modal) = &self.macros.modal_call {
            if self.command.has_axis_words() && !in_modal_macro {
                let modal = modal.clone();
                let program = self.find_program(modal.program, main_text, block.span)?;
                return self.call(
                    Program::Stored(program),
                    (0, 0),
                    modal.repeats,
                    Some(modal.arguments),
                    true,
                    block.span,
                );
            }
        }
        Ok(())
    }

    /// The repeat count of a call (L, default 1).
    fn repeats(&self) -> Result<u32, Alarm> {
        match self.command.l() {
            None => Ok(1),
            Some(l) => match l.number.whole() {
                Some(n) if (0..=9999).contains(&n) => Ok(n as u32),
                _ => Err(alarm(
                    AlarmCode::ValueOutOfRange,
                    l.span,
                    "L (repeats) is 0 to 9999",
                )),
            },
        }
    }

    /// A program number or sequence number word.
    fn whole_number(word: super::decode::Value, what: &str) -> Result<u32, Alarm> {
        match word.number.whole() {
            Some(n) if (0..=99_999_999).contains(&n) => Ok(n as u32),
            _ => Err(alarm(
                AlarmCode::ValueOutOfRange,
                word.span,
                format!("{what} must be a whole number"),
            )),
        }
    }

    /// M98 P_ L_ (H_ on Syntec), M198.
    fn subprogram_call(&mut self, span: Span, main_text: Option<&[u8]>) -> Result<(), Alarm> {
        let mut repeats = self.repeats()?;
        let start_label = match self.command.h() {
            Some(h) => Some(Core::whole_number(h, "H (sequence number)")?),
            None => None,
        };
        let Some(p) = self.command.p() else {
            // Syntec: M98 H_ without P calls a sequence number of this program.
            if start_label.is_some() {
                return self.local_call_at(start_label, span, main_text);
            }
            return Err(alarm(
                AlarmCode::MissingValue,
                span,
                "M98 needs P (the program number)",
            ));
        };
        let mut number = Core::whole_number(p, "P (program number)")?;
        if self
            .exec
            .kernel
            .setup
            .profile()
            .subprograms
            .m98_p_holds_repeats
            && self.command.l().is_none()
            && number > 9999
        {
            repeats = number / 10_000;
            number %= 10_000;
        }
        if repeats == 0 {
            return Ok(());
        }
        let program = self.find_program(number, main_text, p.span)?;
        let start = match start_label {
            Some(label) => program.find_label(label, None).ok_or_else(|| {
                alarm(
                    AlarmCode::SequenceNotFound,
                    span,
                    format!("O{number:04} has no block N{label}"),
                )
            })?,
            None => (0, 0),
        };
        self.call(Program::Stored(program), start, repeats, None, false, span)
    }

    /// Haas M97 P_ L_: sequence number P of the running program.
    fn local_call(&mut self, span: Span, main_text: Option<&[u8]>) -> Result<(), Alarm> {
        let Some(p) = self.command.p() else {
            return Err(alarm(
                AlarmCode::MissingValue,
                span,
                "M97 needs P (the sequence number)",
            ));
        };
        let label = Core::whole_number(p, "P (sequence number)")?;
        self.local_call_at(Some(label), span, main_text)
    }

    fn local_call_at(
        &mut self,
        label: Option<u32>,
        span: Span,
        main_text: Option<&[u8]>,
    ) -> Result<(), Alarm> {
        let repeats = self.repeats()?;
        if repeats == 0 {
            return Ok(());
        }
        let program = self.current_program(main_text, span)?;
        let label = label.unwrap_or(0);
        let found = program.find_label(label, None);
        let Some(start) = found.map_err(|e| read_alarm(span, &e))? else {
            return Err(alarm(
                AlarmCode::SequenceNotFound,
                span,
                format!("the program has no block N{label} to call"),
            ));
        };
        self.call(program, start, repeats, None, false, span)
    }

    /// Enters a called program.
    fn call(
        &mut self,
        program: Program,
        start: Position,
        repeats: u32,
        arguments: Option<Box<Locals>>,
        modal: bool,
        span: Span,
    ) -> Result<(), Alarm> {
        if repeats == 0 {
            return Ok(());
        }
        let depth = self.macros.calls.len() as u32;
        if depth >= self.exec.kernel.setup.profile().subprograms.call_depth {
            return Err(alarm(
                AlarmCode::MacroLimit,
                span,
                format!(
                    "calls nested deeper than {} levels (FANUC alarm PS0077)",
                    self.exec.kernel.setup.profile().subprograms.call_depth
                ),
            ));
        }
        if arguments.is_some() {
            let macros = self
                .macros
                .calls
                .iter()
                .filter(|c| c.arguments.is_some())
                .count() as u32;
            if macros >= self.exec.kernel.setup.profile().macros.macro_call_depth {
                return Err(alarm(
                    AlarmCode::MacroLimit,
                    span,
                    format!(
                        "macro calls (G65, G66) nested deeper than {} levels (FANUC alarm PS0077)",
                        self.exec.kernel.setup.profile().macros.macro_call_depth
                    ),
                ));
            }
        }
        if let Some(arguments) = &arguments {
            self.macros.vars.push_level(**arguments);
        }
        let loops = std::mem::take(&mut self.macros.loops);
        self.macros.calls.push(CallFrame {
            return_to: self.place.clone(),
            program: program.clone(),
            start,
            repeats_left: repeats,
            arguments,
            loops,
            modal,
            span,
            interrupted: None,
        });
        self.place = Place::stored(program, start);
        Ok(())
    }

    /// M99 [P_] [Q_]: back to the caller (or, in a main program, to its start).
    fn subprogram_return(&mut self, span: Span, main_text: Option<&[u8]>) -> Result<(), Alarm> {
        let label = match self.command.p() {
            Some(p) => Some(Core::whole_number(p, "P (sequence number)")?),
            None => None,
        };
        // Q (a line of the main program) is read by an interrupt program's return only.
        let line = match self.command.word(b'Q') {
            Some(q) => Some(Core::whole_number(q, "Q (line number)")?),
            None => None,
        };
        let target = match (label, line) {
            (Some(label), _) => Return::Sequence(label),
            (None, Some(line)) => Return::Line(line),
            (None, None) => Return::Caller,
        };
        self.return_from_call(target, span, main_text)
    }

    fn return_from_call(
        &mut self,
        target: Return,
        span: Span,
        main_text: Option<&[u8]>,
    ) -> Result<(), Alarm> {
        let label = match target {
            Return::Sequence(label) => Some(label),
            Return::Caller | Return::Line(_) => None,
        };
        let Some(frame) = self.macros.calls.last_mut() else {
            return self.restart_main(label, span, main_text);
        };
        if frame.repeats_left > 1 {
            frame.repeats_left -= 1;
            let (program, start) = (frame.program.clone(), frame.start);
            if let Some(arguments) = &frame.arguments {
                self.macros.vars.reset_level(**arguments);
            }
            self.macros.loops.clear();
            self.count_jump(span)?;
            self.place = Place::stored(program, start);
            return Ok(());
        }
        let frame = self.macros.calls.pop().expect("a frame is there");
        if frame.arguments.is_some() {
            self.macros.vars.pop_level();
        }
        self.macros.loops = frame.loops;
        self.place = frame.return_to;
        if let (Some(interrupted), None) = (frame.interrupted, label) {
            let line = match target {
                Return::Line(line) => Some(line),
                _ => None,
            };
            return self.return_from_interrupt(interrupted, line, span);
        }
        if let Some(label) = label {
            let program = self.current_program(main_text, span)?;
            let found = program.find_label(label, None);
            let Some(target) = found.map_err(|e| read_alarm(span, &e))? else {
                return Err(alarm(
                    AlarmCode::SequenceNotFound,
                    span,
                    format!("M99 P{label}: the calling program has no block N{label}"),
                )
                .with_label(frame.span, "called from here"));
            };
            self.count_jump(span)?;
            self.macros.loops.clear();
            self.place = Place::stored(program, target);
        }
        Ok(())
    }

    /// M99 in a main program: the control starts it again (or at N P) until reset.
    fn restart_main(
        &mut self,
        label: Option<u32>,
        span: Span,
        main_text: Option<&[u8]>,
    ) -> Result<(), Alarm> {
        self.macros.main_passes += 1;
        if self.macros.main_passes >= self.options.limits.main_program_passes {
            self.out.push_warning(
                Alarm::warning(
                    AlarmCode::MacroLimit,
                    span,
                    format!(
                        "M99 in the main program: the control runs it again until reset; vcnc stopped after {} pass(es)",
                        self.macros.main_passes
                    ),
                )
                .with_help("set the number of passes with --main-passes"),
            );
            self.end(EndKind::M99, span);
            return Ok(());
        }
        self.count_jump(span)?;
        let program = self.main_program(main_text, span)?;
        let target = match label {
            Some(label) => {
                let found = program.find_label(label, None);
                found.map_err(|e| read_alarm(span, &e))?.ok_or_else(|| {
                    alarm(
                        AlarmCode::SequenceNotFound,
                        span,
                        format!("M99 P{label}: the program has no block N{label}"),
                    )
                })?
            }
            None => program
                .start_after_tape_mark()
                .map_err(|e| read_alarm(span, &e))?,
        };
        self.macros.loops.clear();
        self.place = Place::stored(program, target);
        Ok(())
    }

    /// The text of a called program ran out (no M99): the control returns; the main program
    /// held in memory ends as its text does.
    pub(super) fn end_of_stored_program(&mut self) {
        let span = self.last_span;
        if let Some(frame) = self.macros.calls.last() {
            let name = frame
                .program
                .number()
                .map_or("the called program".to_string(), |n| format!("O{n:04}"));
            self.out.push_warning(
                Alarm::warning(
                    AlarmCode::MissingProgramEnd,
                    span,
                    format!("{name} ends without M99: returning to the caller"),
                )
                .with_label(frame.span, "called from here"),
            );
            if let Err(alarm) = self.return_from_call(Return::Caller, span, None) {
                self.fail(alarm);
            }
            return;
        }
        self.end_of_text();
    }

    /// G65/G66: program number, repeats and the local variables the arguments set.
    fn macro_arguments(
        &self,
        block: &Block,
        first: usize,
        span: Span,
    ) -> Result<(u32, u32, Box<Locals>), Alarm> {
        // The profile's letter-to-variable mapping. Every control vcnc models maps as FANUC
        // does (the Syntec manual's G65 example passes X and Y the same way): one arm today, and
        // a profile with another mapping must add its own here.
        let crate::profile::MacroArguments::Fanuc =
            self.exec.kernel.setup.profile().macros.macro_arguments;
        let mut locals: Locals = [None; 33];
        let mut program = None;
        let mut repeats = 1;
        // Argument specification II: the n-th I, J, K of the block.
        let mut ijk = [0usize; 3];
        for word in block.words.iter().skip(first) {
            let value = word.number.value;
            let index = match word.letter {
                b'P' => {
                    program = Some(word_whole(word, "P (program number)")?);
                    continue;
                }
                b'L' => {
                    repeats = word_whole(word, "L (repeats)")?;
                    continue;
                }
                b'N' | b'O' => continue,
                b'A' => 0,
                b'B' => 1,
                b'C' => 2,
                b'I' | b'J' | b'K' => {
                    let k = usize::from(word.letter - b'I');
                    let n = ijk[k];
                    ijk[k] += 1;
                    if n >= 10 {
                        return Err(alarm(
                            AlarmCode::WordNotAllowed,
                            word.span,
                            "more than ten I, J, K argument sets",
                        ));
                    }
                    3 + 3 * n + k
                }
                b'D' => 6,
                b'E' => 7,
                b'F' => 8,
                b'H' => 10,
                b'M' => 12,
                b'Q' => 16,
                b'R' => 17,
                b'S' => 18,
                b'T' => 19,
                b'U' => 20,
                b'V' => 21,
                b'W' => 22,
                b'X' => 23,
                b'Y' => 24,
                b'Z' => 25,
                other => {
                    return Err(alarm(
                        AlarmCode::WordNotAllowed,
                        word.span,
                        format!("{} cannot be a macro argument", other as char),
                    ))
                }
            };
            locals[index] = Some(self.argument_value(word.letter, word.number, value));
        }
        let Some(program) = program else {
            return Err(alarm(
                AlarmCode::MissingValue,
                span,
                "G65/G66 needs P (the macro's program number)",
            ));
        };
        Ok((program, repeats, Box::new(locals)))
    }

    /// An argument written without a decimal point is read in least input increments where
    /// the control reads addresses so (FANUC: "the units of the address").
    fn argument_value(&self, letter: u8, number: Number, value: f64) -> f64 {
        let profile = self.exec.kernel.setup.profile();
        if number.decimal_point || profile.units.decimal_less != DecimalLess::Increments {
            return value;
        }
        match letter {
            b'X' | b'Y' | b'Z' | b'U' | b'V' | b'W' | b'I' | b'J' | b'K' | b'R' | b'Q' => {
                match self.exec.modal.units {
                    super::modal::Units::Millimetres => value * profile.units.increment_mm,
                    super::modal::Units::Inches => value * profile.units.increment_inch,
                }
            }
            b'A' | b'B' | b'C' => value * profile.units.increment_deg,
            _ => value,
        }
    }
}

/// The main program's file could not be read again.
fn read_alarm(span: Span, error: &std::io::Error) -> Alarm {
    alarm(
        AlarmCode::ReadError,
        span,
        format!("cannot read the program again: {error}"),
    )
}

/// The library could not give the program called at `span`.
fn lookup_alarm(error: &programs::LookupError, span: Span) -> Alarm {
    match error {
        programs::LookupError::Ambiguous { .. } => {
            alarm(AlarmCode::ProgramAmbiguous, span, error.to_string()).with_help(
                "a control holds one program per number: keep one of these files in the \
                 directory, or renumber the other",
            )
        }
        programs::LookupError::Unreadable { .. }
        | programs::LookupError::NamedUnreadable { .. } => {
            alarm(AlarmCode::ReadError, span, error.to_string())
        }
    }
}

fn too_large(number: u32, span: Span) -> Alarm {
    alarm(
        AlarmCode::MacroLimit,
        span,
        format!("O{number:04} is too large to load"),
    )
}

fn word_whole(word: &Word, what: &str) -> Result<u32, Alarm> {
    match word.number.whole() {
        Some(n) if (0..=99_999_999).contains(&n) => Ok(n as u32),
        _ => Err(alarm(
            AlarmCode::ValueOutOfRange,
            word.span,
            format!("{what} must be a whole number"),
        )),
    }
}
