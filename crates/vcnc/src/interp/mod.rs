//! The interpreter: pulls blocks from a program's text and yields the motion stream.
//!
//! [`Interpreter`] is an iterator of [`StreamItem`]s. It reads one line at a time, decodes each
//! block (`decode`), and executes it (`exec`) in the control's order; the segments of a block go
//! into a small queue that the iterator drains. Warnings come out as [`Item::Warning`] and the
//! run goes on; the first error is the `Err` item, the last. Memory does not grow with the
//! program.
//!
//! The modules below follow the pipeline: decode, modal state, the coordinate chain (frames),
//! the executor and the parts it calls (motion, tool length, coordinate codes, reference
//! returns, data input, auxiliary functions).

mod arc;
mod auxiliary;
mod circle_cutting;
mod circle_pocket;
mod circular;
mod comp;
mod compensation;
mod corner_override;
mod cycles;
mod cylindrical;
mod data_input;
mod decode;
mod engraving;
mod exec;
mod frames;
mod front_end;
mod hypothetical;
mod kernel;
mod length;
mod macros;
pub mod modal;
mod nurbs;
mod output;
mod pieces;
mod polar_coordinates;
mod polar_interpolation;
mod position_offset;
mod reference;
mod reference_check;
mod setup;
pub mod sinumerik;
mod skip;
mod smoothing;
mod smoothness;
mod spindle;
mod spiral;
mod stroke_check;
mod thread;
mod tilted_plane;
mod tool_center;
mod tool_measurement;
mod tools;

use crate::alarm::{Alarm, AlarmCode};
use crate::checks::ReleasedCheck;
use crate::machine::Machine;
use crate::motion::{EndKind, Item, MachinePos, Segment, SegmentKind, StreamItem};
use crate::source::{FileId, Span};
use crate::syntax::blocks::{line_blocks, BlockSource, ParsedLines};
use crate::syntax::iso::LineBlocks;
use crate::syntax::lines::LineSource;
use crate::syntax::{Block, BlockKind, Dialect};
use decode::Command;
use exec::{Executor, Flow};
pub use front_end::{FrontEnd, Run, Step};
pub use kernel::{Kernel, Origin};
pub use macros::interrupt::InterruptAt;
pub use macros::programs::{
    DirectoryLibrary, LoadedFiles, LookupError, MemoryLibrary, ProgramLibrary, ProgramText,
};
pub use macros::vars::PersistentVariables;
pub use macros::Limits;
use output::Output;

pub use modal::ModalState;
pub use stroke_check::{AxisLimits, Forbidden, StrokeCheckConfig};

/// Run-time switches of the operator's panel.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Options {
    /// Block skip switches 1 to 9: a block starting with `/n` is skipped when switch n is on.
    pub block_skip: [bool; 9],
    /// The dialect of the program: the ISO interpreter gives a SINUMERIK program one alarm that
    /// says which front end runs it (the pipeline picks it by itself).
    pub dialect: Dialect,
    /// Limits on macro programs (loop passes, repeats of a main program ending in M99).
    pub limits: Limits,
    /// The blocks of the main program during which the interrupt signal comes (Syntec's C49,
    /// once each): with `M96 P_` in force, interrupt program P runs before the block; see
    /// [`InterruptAt`].
    pub interrupts: Vec<InterruptAt>,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            block_skip: [false; 9],
            dialect: Dialect::Iso,
            limits: Limits::default(),
            interrupts: Vec::new(),
        }
    }
}

/// No check: [`Interpreter::next_batch`], [`Run::next_batch`].
pub(crate) struct NoCheck;

impl ReleasedCheck for NoCheck {
    #[inline(always)]
    fn check_released(&mut self, _: &mut Vec<StreamItem>, _: std::ops::Range<usize>) -> bool {
        true
    }
}

/// Blocks run at most by one call of [`Interpreter::next_batch`].
const STEPS_PER_BATCH: u32 = 1 << 16;

/// Interprets an ISO program: an iterator over its motion stream.
pub struct Interpreter<B> {
    source: B,
    core: Core,
    /// Items released to [`Iterator::next`] and not yet taken, in order. Taken from the front of
    /// the queue one at a time, a block with many moves (a canned cycle of thousands of pecks)
    /// cost a shift of the whole queue per item: quadratic.
    ready: std::collections::VecDeque<StreamItem>,
}

/// Where the next block comes from.
#[derive(Clone, Debug)]
pub(crate) enum Place {
    /// The main program's block source, block `block` of its current line.
    Stream {
        /// Index of the next block in the line.
        block: usize,
        /// The main program's last line (1-based): back on the stream after running from an
        /// index, the stream ends there as the indexed program does (`u32::MAX` before).
        last_line: u32,
    },
    /// A program held in memory (a subprogram, or the main program once it jumped).
    Stored {
        /// The program.
        program: std::sync::Arc<macros::programs::StoredProgram>,
        /// Line index of the next block.
        line: usize,
        /// Index of the next block in the line.
        block: usize,
    },
    /// The main program once it jumped, run from an index into its file.
    Indexed {
        /// The file's index.
        program: std::sync::Arc<macros::indexed::IndexedFile>,
        /// The parsed lines around `line`, once fetched.
        chunk: Option<std::sync::Arc<macros::indexed::ParsedChunk>>,
        /// Line index of the next block.
        line: usize,
        /// Index of the next block in the line.
        block: usize,
    },
}

impl Place {
    /// Block `block` of line `line` of a program the run can jump in.
    pub(crate) fn stored(
        program: macros::programs::Program,
        (line, block): macros::programs::Position,
    ) -> Place {
        match program {
            macros::programs::Program::Stored(program) => Place::Stored {
                program,
                line,
                block,
            },
            macros::programs::Program::Indexed(program) => Place::Indexed {
                program,
                chunk: None,
                line,
                block,
            },
        }
    }
}

/// Everything but the block source: the part that runs blocks, wherever they come from.
pub(crate) struct Core {
    options: Options,
    exec: Executor,
    command: Command,
    out: Output,
    done: bool,
    started: bool,
    last_span: Span,
    blocks_executed: u64,
    place: Place,
    macros: macros::Macros,
    file: FileId,
}

impl<S: LineSource> Interpreter<ParsedLines<S>> {
    /// An interpreter for the program in `source` (file `file`) on `machine`; lines are parsed
    /// as they are needed.
    pub fn new(
        source: S,
        file: FileId,
        machine: &Machine,
        options: Options,
    ) -> Interpreter<ParsedLines<S>> {
        let blocks = ParsedLines::new(source, file, machine.profile.syntax());
        Interpreter::from_blocks(blocks, file, machine, options)
    }
}

impl<B: BlockSource<Line = LineBlocks>> Interpreter<B> {
    /// An interpreter for the blocks of `source` (file `file`) on `machine`; the source must
    /// parse with `machine.profile.syntax()`.
    pub fn from_blocks(
        source: B,
        file: FileId,
        machine: &Machine,
        options: Options,
    ) -> Interpreter<B> {
        let exec = Executor::new(machine);
        let mut core = Core {
            exec,
            command: Command::default(),
            out: Output::default(),
            done: false,
            started: false,
            last_span: Span::new(file, 1, 0..0),
            blocks_executed: 0,
            place: Place::Stream {
                block: 0,
                last_line: u32::MAX,
            },
            macros: macros::Macros::default(),
            file,
            options,
        };
        if core.options.dialect == Dialect::Sinumerik {
            core.out.push_warning(
                Alarm {
                    code: AlarmCode::DialectNotSupported,
                    severity: crate::alarm::Severity::Error,
                    message: "the ISO interpreter does not run SINUMERIK programs".to_string(),
                    span: None,
                    labels: Vec::new(),
                    help: Some("run them with vcnc::Pipeline, which starts the SINUMERIK front end for them, or vcnc::interp::sinumerik::run_str".into()),
                },
            );
            core.done = true;
        }
        Interpreter {
            source,
            core,
            ready: std::collections::VecDeque::new(),
        }
    }

    /// Where called programs come from: a program directory, programs in memory. Without one,
    /// only programs in the main program's own file can be called.
    pub fn with_library(mut self, library: Box<dyn ProgramLibrary>) -> Interpreter<B> {
        self.core.macros.library = Some(library);
        self
    }

    /// The persistent common variables (#500-#999, Syntec's #401-#999) as a previous run left
    /// them.
    pub fn with_persistent_variables(mut self, values: &PersistentVariables) -> Interpreter<B> {
        let ranges = macros::vars::Ranges::of(&self.core.exec.kernel.setup.profile().macros);
        self.core.macros.vars.load_persistent(values, &ranges);
        self
    }

    /// The persistent common variables now: what the caller saves for the next run.
    pub fn persistent_variables(&self) -> PersistentVariables {
        self.core.macros.vars.persistent()
    }

    /// Counts writes to persistent variables: when it changes, they may have changed.
    pub fn persistent_writes(&self) -> u64 {
        self.core.macros.vars.persistent_writes()
    }

    /// The value of macro variable `#number` now (`None` when vacant or not a plain variable).
    pub fn variable(&mut self, number: u32) -> Option<f64> {
        let span = self.core.last_span;
        self.core.read_variable(number, span).ok().flatten()
    }

    /// The value of Syntec's public variable `@number` now (`None` when vacant or not one).
    pub fn public_variable(&self, number: u32) -> Option<f64> {
        let span = self.core.last_span;
        self.core.read_public(number, span).ok().flatten()
    }

    /// Blocks executed so far (skipped, empty and comment-only blocks not counted).
    pub fn blocks_executed(&self) -> u64 {
        self.core.blocks_executed
    }

    /// The machine position now.
    pub fn position(&self) -> MachinePos {
        MachinePos(self.core.exec.kernel.position)
    }

    /// The position now in the program's coordinates (what the control shows as "absolute").
    pub fn program_position(&self) -> [f64; crate::machine::AXES] {
        self.core.exec.kernel.program_position()
    }

    /// The tool in the spindle (the last T put there by M06; 0 before any change).
    pub fn tool_in_spindle(&self) -> u32 {
        self.core.exec.kernel.tools.in_spindle()
    }

    /// The modal state now.
    pub fn modal(&self) -> &ModalState {
        &self.core.exec.modal
    }

    /// Appends the next items of the stream to `out` until it holds at least `at_least` items
    /// or the program is over (or a long stretch of blocks produced nothing: the batch may then
    /// be empty); returns false when nothing more will come. The same items as
    /// [`Iterator::next`] gives, with fewer moves: consumers of long streams use this.
    pub fn next_batch(&mut self, out: &mut Vec<StreamItem>, at_least: usize) -> bool {
        self.next_batch_checked(out, at_least, &mut NoCheck)
    }

    /// [`Interpreter::next_batch`] with `check` of the items as the blocks release them. When
    /// the check stops the program at an item, the interpreter stops at that block, as the
    /// control does (a travel check, [`crate::checks::TravelCheck`]): the blocks after it are not
    /// run, so they neither count as executed nor write macro variables.
    pub fn next_batch_checked(
        &mut self,
        out: &mut Vec<StreamItem>,
        at_least: usize,
        check: &mut impl ReleasedCheck,
    ) -> bool {
        // The executor writes straight into the caller's vector: no item is moved twice.
        let base = out.len();
        // What the iterator released and nobody took comes first (empty unless a caller mixes
        // `next` with batches).
        out.extend(self.ready.drain(..));
        self.core.out.lend(out);
        // Items before `checked` have passed the check (those of `out` passed it before).
        let mut checked = base;
        // A macro loop may run long without moving: the caller gets control back now and then
        // (to save state, to show progress) with whatever is ready, possibly nothing.
        let mut steps = 0u32;
        while !self.core.done && self.core.out.releasable() < at_least && steps < STEPS_PER_BATCH {
            self.step();
            steps += 1;
            let released = self.core.out.releasable();
            if released > checked {
                if !check.check_released(&mut self.core.out.items, checked..released) {
                    self.stop_checked();
                }
                checked = released;
            }
        }
        if self.core.done {
            self.core.out.finish();
            // The end of the program releases what compensation held.
            let released = self.core.out.items.len();
            if released > checked
                && !check.check_released(&mut self.core.out.items, checked..released)
            {
                self.stop_checked();
            }
        }
        self.return_batch(out)
    }

    /// Hands the items of a batch over in `out` (what compensation holds stays); false when
    /// nothing more will come.
    #[inline(always)]
    fn return_batch(&mut self, out: &mut Vec<StreamItem>) -> bool {
        self.core.out.give_back(out);
        !(self.core.done && out.is_empty() && self.core.out.items.is_empty())
    }

    /// A check cut the queue at an item and added its alarm: nothing after it runs. What
    /// compensation or G12.1 held is dropped with the cut (those blocks never moved).
    fn stop_checked(&mut self) {
        self.core.out.cut_by_check();
        self.core.done = true;
    }

    /// Reads and runs until something is queued or the program is over.
    fn step(&mut self) {
        match &mut self.core.place {
            Place::Stream { block, last_line } => {
                // The next line is read and its first block run in the same step: most lines
                // have one block.
                let mut blocks = line_blocks(&self.source);
                if *block >= blocks.len() {
                    match self.source.advance() {
                        Ok(true) => *block = 0,
                        Ok(false) => return self.core.end_of_text(),
                        Err(error) => return self.core.read_failed(&error),
                    }
                    blocks = line_blocks(&self.source);
                }
                if let Some(next) = blocks.get(*block) {
                    if next.span.line > *last_line {
                        return self.core.end_of_stored_program();
                    }
                    *block += 1;
                    self.core.macros.stream_line = next.span.line;
                    self.core.run_block(next, self.source.text());
                }
            }
            Place::Stored {
                program,
                line,
                block,
            } => {
                let program = std::sync::Arc::clone(program);
                match program.line(*line) {
                    Some(blocks) if *block < blocks.len() => {
                        let index = *block;
                        *block += 1;
                        self.core.run_block(&blocks[index], self.source.text());
                    }
                    Some(_) => {
                        *line += 1;
                        *block = 0;
                    }
                    None => self.core.end_of_stored_program(),
                }
            }
            Place::Indexed {
                program,
                chunk,
                line,
                block,
            } => {
                if self.core.macros.resumes_stream((*line, *block)) {
                    let last_line = u32::try_from(program.lines()).unwrap_or(u32::MAX);
                    let block = *block;
                    self.core.place = Place::Stream { block, last_line };
                    return;
                }
                let lines = match chunk {
                    Some(lines) if lines.line(*line).is_some() => std::sync::Arc::clone(lines),
                    _ => match program.chunk_of(*line) {
                        Ok(Some(lines)) => {
                            *chunk = Some(std::sync::Arc::clone(&lines));
                            lines
                        }
                        Ok(None) => return self.core.end_of_stored_program(),
                        Err(error) => return self.core.read_failed(&error),
                    },
                };
                match lines.line(*line) {
                    Some(blocks) if *block < blocks.len() => {
                        let index = *block;
                        *block += 1;
                        self.core.run_block(&blocks[index], self.source.text());
                    }
                    _ => {
                        *line += 1;
                        *block = 0;
                    }
                }
            }
        }
    }
}

impl Core {
    /// The program text cannot be read: the run ends here.
    #[cold]
    fn read_failed(&mut self, error: &std::io::Error) {
        self.out.stop(Alarm {
            code: AlarmCode::ReadError,
            severity: crate::alarm::Severity::Error,
            message: format!("cannot read the program: {error}"),
            span: None,
            labels: Vec::new(),
            help: None,
        });
        self.done = true;
    }

    fn end_of_text(&mut self) {
        let span = self.last_span;
        self.out.push_warning(
            Alarm::warning(
                AlarmCode::MissingProgramEnd,
                span,
                "the program ends without M02, M30 or %",
            )
            .with_help("end the program with M30"),
        );
        self.end(EndKind::EndOfText, span);
    }

    /// The run is over: the end item, and nothing more.
    fn end(&mut self, kind: EndKind, span: Span) {
        self.out.push_item(Ok(Item::Segment(Segment {
            kind: SegmentKind::End { kind },
            span,
            sequence: None,
        })));
        self.done = true;
    }

    /// Runs one block of the program, from the stream or from memory. `main_text` is the
    /// block source's text, when it has it (jumps need it).
    // Inlined, with the rare kinds of block out of line: this runs for every block.
    #[inline(always)]
    fn run_block(&mut self, block: &Block, main_text: Option<&[u8]>) {
        let ordinary = block.alarms.is_empty()
            && block.skip.is_none()
            && block.kind == BlockKind::Words
            && !self.interrupt_may_come();
        if !ordinary {
            return self.run_unusual_block(block, main_text);
        }
        if block.is_empty() {
            return;
        }
        self.run_contents(block, main_text);
    }

    /// [`Core::run_block`] for a block with alarms, a block skip, a tape mark or a macro
    /// header, or while an interrupt signal may come.
    #[inline(never)]
    fn run_unusual_block(&mut self, block: &Block, main_text: Option<&[u8]>) {
        for alarm in &block.alarms {
            if alarm.is_error() {
                self.out.stop(alarm.clone());
                self.done = true;
                return;
            }
            self.out.push_warning(alarm.clone());
        }
        if let Some(level) = block.skip {
            if self.options.block_skip[usize::from(level.clamp(1, 9)) - 1] {
                return;
            }
        }
        if block.kind == BlockKind::MacroHeader {
            self.enter_macro_program(block.span, main_text);
            return;
        }
        if block.kind == BlockKind::TapeMark {
            if self.macros.in_call() {
                self.end_of_stored_program();
            } else if self.started {
                let cmd = Command::at(block.span);
                self.out.push(
                    &cmd,
                    SegmentKind::End {
                        kind: EndKind::TapeMark,
                    },
                );
                self.done = true;
            }
            return;
        }
        if block.is_empty() {
            return;
        }
        if self.interrupt_may_come() && self.interrupt_before(block, main_text) {
            return;
        }
        self.run_contents(block, main_text);
    }

    /// Runs a block that is neither empty nor skipped: its statements, or its words.
    #[inline(always)]
    fn run_contents(&mut self, block: &Block, main_text: Option<&[u8]>) {
        self.started = true;
        self.last_span = block.span;
        if block.has_macro() {
            self.run_macro_block(block, main_text);
            return;
        }
        self.run_words(block, main_text);
    }

    /// Decodes and executes the words of a block (its expressions already evaluated).
    fn run_words(&mut self, block: &Block, main_text: Option<&[u8]>) {
        let decoded = decode::decode(
            block,
            self.exec.kernel.setup.profile(),
            self.exec.kernel.setup.axis_letters(),
            &mut self.command,
        );
        if self.command.has_warnings() {
            self.queue_decode_warnings();
        }
        if let Err(alarm) = decoded {
            self.out.stop(alarm);
            self.done = true;
            return;
        }
        self.blocks_executed += 1;
        if self.macros.in_call()
            && self
                .exec
                .kernel
                .setup
                .profile()
                .subprograms
                .end_in_subprogram_returns
        {
            // Syntec: M02/M30 in a subprogram return to the caller.
            if let Some(end) = self.command.take_program_end() {
                self.command
                    .set_subprogram(crate::profile::MCode::SubprogramReturn, end);
            }
        }
        if self.out.polar_interpolating() {
            if let Err(alarm) = polar_interpolation::prepare(&mut self.command) {
                return self.fail(alarm);
            }
        }
        if let Err(alarm) = cylindrical::prepare(&mut self.command, &self.out) {
            return self.fail(alarm);
        }
        if let Err(alarm) = hypothetical::prepare(&self.command, &self.out) {
            return self.fail(alarm);
        }
        // Only a block with a comment kept can be a G47 P1: one test for the others.
        let serial = self.command.text().is_some() && self.command.engraves_serial();
        if serial {
            if let Err(alarm) = self.serial_engraving(false) {
                return self.fail(alarm);
            }
        }
        let flow = self.exec.run(&self.command, &mut self.out);
        if serial && flow.is_ok() {
            if let Err(alarm) = self.serial_engraving(true) {
                return self.fail(alarm);
            }
        }
        if !self.out.compensating() && !self.out.failing() {
            // The common case, kept short: no compensation stage to tell about the block.
            match flow {
                Ok(Flow::Next) => {}
                Ok(Flow::End) => self.done = true,
                Err(alarm) => return self.fail(alarm),
            }
        } else {
            self.after_compensated_block(flow);
        }
        // Asked in this order: most blocks neither call nor end the program.
        if (self.command.has_calls() || self.macros.modal_call.is_some()) && !self.done {
            if let Err(alarm) = self.run_calls(block, main_text) {
                self.fail(alarm);
            }
        }
    }

    /// Queues the warnings decoding the block found (rare: kept out of the common path, where
    /// even an empty drain had a cost).
    #[cold]
    fn queue_decode_warnings(&mut self) {
        for warning in self.command.take_warnings() {
            self.out.push_warning(warning);
        }
    }

    /// The end of a block while compensation is on (or has failed): an alarm it raised while
    /// queueing comes first; otherwise it counts the block.
    #[inline(never)]
    fn after_compensated_block(&mut self, flow: Result<Flow, Alarm>) {
        let flow = match self.out.take_failure() {
            Some(alarm) => Err(alarm),
            None => flow.and_then(|flow| {
                if flow == Flow::Next {
                    self.out.end_block()?;
                }
                Ok(flow)
            }),
        };
        match flow {
            Ok(Flow::Next) => {}
            Ok(Flow::End) => self.done = true,
            Err(alarm) => self.fail(alarm),
        }
    }

    /// An error ends the run.
    #[cold]
    fn fail(&mut self, alarm: Alarm) {
        self.out.stop(alarm);
        self.done = true;
    }
}

impl<B: BlockSource<Line = LineBlocks>> Iterator for Interpreter<B> {
    type Item = StreamItem;

    fn next(&mut self) -> Option<Self::Item> {
        loop {
            if let Some(item) = self.ready.pop_front() {
                return Some(item);
            }
            let out = &mut self.core.out;
            let released = out.releasable();
            if released == 1 {
                // The common case, a block's one move: taken straight from the queue, behind
                // which wait at most the few items compensation holds (through the queue of
                // ready items it cost 16% of the iterator's time).
                if let Some(held) = out.held.as_mut() {
                    *held -= 1;
                }
                return Some(out.items.remove(0));
            }
            if released > 1 {
                // All that is released moves at once: a block's thousands of moves are moved
                // once each, not once per item taken before them.
                self.ready.extend(out.items.drain(..released));
                if let Some(held) = out.held.as_mut() {
                    *held -= released;
                }
                continue;
            }
            if self.core.done {
                // A stage may still hold moves (the corner override its last one).
                if out.items.is_empty() && !out.has_stages() {
                    return None;
                }
                out.finish();
                continue;
            }
            self.step();
        }
    }
}
