//! The SINUMERIK 840D sl / 828D front end: a block sequencer over the [`Kernel`] (docs/SINUMERIK.md
//! is the execution model it implements).
//!
//! It reads its own blocks (`crate::syntax::sinumerik`), keeps its own modal state, variables
//! and call stack, and asks the kernel for what every control shares: moves, dwells, events,
//! the frame chain, the tool length. It never builds a segment itself and never reads ISO
//! words.
//!
//! The parts: the texts and their lines (`program.rs`), the G functions by group (`gcodes.rs`),
//! one block's words in the control's order (`block.rs`), the language's values, variables and
//! expressions (`value.rs`, `vars.rs`, `eval.rs`), the programmable frame's algebra
//! (`frame.rs`), the geometry of arcs, polar coordinates and contour definitions (`arcs.rs`,
//! `polar.rs`, `contour.rs`).

mod arcs;
mod axes;
mod block;
mod compensation;
mod contour;
mod control;
mod cutting_rate;
mod cycles;
mod diameter;
mod dynamics;
mod eval;
mod feed_source;
mod flow;
mod frame;
mod gcodes;
mod geo_axes;
mod grinding;
mod instructions;
mod involute;
mod iso_mode;
mod language;
mod lift_fast;
mod machine_data;
mod motion;
mod multi_feed;
mod path_control;
mod plain_block;
mod polar;
mod predefined;
mod program;
mod spindle;
mod spindles;
mod threads;
mod tool_frame;
mod toolholder;
mod tools;
mod value;
mod vars;
mod work_area;

/// The G functions by group with their support, for README.md's table (profile::codes).
pub(crate) use gcodes::{listing as g_function_listing, Support as GFunctionSupport};

use super::front_end::{FrontEnd, Run, Step};
use super::kernel::{Kernel, Origin};
use super::macros::programs::ProgramLibrary;
use crate::alarm::{Alarm, AlarmCode};
use crate::machine::{Machine, ToolEdge, AXES};
use crate::motion::{EndKind, Plane};
use crate::profile::{SinumerikSettings, Variant};
use crate::source::{FileId, Span};
use crate::syntax::sinumerik::{is_header, parse_line_into, Block};
use gcodes::{FeedType, Motion};
use program::{Fetched, Program};
use std::io::Read;
use std::sync::Arc;

/// A SINUMERIK program running on the kernel: the [`FrontEnd`] of [`Run`].
pub struct Sinumerik {
    programs: Vec<Program>,
    /// The call stack: the main program at the bottom.
    levels: Vec<Level>,
    library: Option<Box<dyn ProgramLibrary>>,
    settings: SinumerikSettings,
    tools: Vec<ToolEdge>,
    modal: Modal,
    /// The programmed position of every axis, in the work system (Siemens' `$P_EP`).
    programmed: [f64; AXES],
    /// The machine's axes by name.
    axes: language::ChannelAxes,
    /// Block skip levels /0 .. /9 switched on.
    skip: [bool; 10],
    /// R parameters and user variables.
    vars: vars::Variables,
    tool: ToolState,
    /// Steps run (0 before the first: the power-on state is set then).
    iterations: u64,
    /// The last block's span, for the alarm at the end of the text.
    last_span: Span,
    /// Settable frames written by the block being read ($P_UIFR).
    frame_writes: Vec<(u32, usize, f64)>,
    /// TOFFL or TOFF in force.
    tool_offsets: tools::Offsets,
    /// The spindle's cutting rate and limits.
    spindle: spindle::Spindle,
    /// The spindles by number (S2=, SPOS[n]) and the master spindle's angle.
    spindles: spindles::Spindles,
    /// FGROUP, FGREF, FL and the positioning axes' FA.
    axis_feeds: axes::AxisFeeds,
    /// The modal feed to restore after a block with FB.
    block_feed_restore: Option<Option<f64>>,
    /// The path override OVR, as a factor.
    feed_override: f64,
    /// The programmed F in force, mm/min or mm/rev (before OVR).
    programmed_feed: Option<f64>,
    /// FZ in force: the feed per tooth.
    tooth_feed: Option<f64>,
    /// The pole and the stored polar angle and radius.
    polar: polar::Polar,
    /// A two-line ANG= definition waiting for its second block.
    angle_lines: contour::AngleLines<motion::Tag>,
    /// The block held for the chamfer or rounding at its end.
    contour: contour::Contour<motion::Tag>,
    /// Blocks without motion since the last move (a corner waits over a few).
    idle_blocks: u32,
    /// FRCM in force: the modal feed of chamfers and roundings.
    corner_feed_modal: Option<f64>,
    /// The feed of the corner being cut (FRC or FRCM of the block after it).
    corner_feed: Option<f64>,
    /// RNDM in force.
    rounding_modal: bool,
    /// The block the corner being cut follows, for its segments' origin.
    corner_origin: Option<Origin>,
    /// The element whose end direction is the path's at the last block's end in the plane
    /// (CT's tangent): kept whole, the direction is worked out only when CT asks for it.
    tangent: Option<motion::Tangent>,
    /// The profile's arc tolerance.
    arc_tolerance: f64,
    /// Tools called by names the tool table lacks, and the numbers they run under.
    unknown_tools: std::collections::HashMap<String, u32>,
    /// The commands kept as state that a note was given for.
    noted: std::collections::HashSet<String>,
    /// The modal call (MCALL) in force.
    modal_call: Option<ModalCall>,
    /// The programmable frame ($P_PFRAME).
    frame: frame::ProgrammableFrame,
    /// Structure partners, labels and block numbers found so far.
    structure: flow::Structure,
    /// Jumps made (GOTO, CASE, loops back).
    jumps: u64,
    /// A block to read the next line into, with the room of the last one's words (boxed:
    /// swapped with a line's block parsed ahead, it moves as a pointer).
    spare: Option<Box<Block>>,
    /// The words of a decoded plain line that runs the general way (`plain_block.rs`), their
    /// room kept from block to block.
    general_block: Option<Block>,
    /// Plain blocks run by the short path (off only in the differential tests).
    plain_blocks: bool,
    /// Tool radius compensation: G40/G41/G42 and how it approaches and turns corners.
    radius_compensation: compensation::RadiusCompensation,
    /// The standard cycle a block called, run at its end, and the names that are built in.
    cycles: cycles::Calls,
    /// G25/G26 with axes and WALIMON/WALIMOF: the working area (`work_area.rs`).
    work_area: work_area::WorkArea,
    /// The dynamic response's machine data the program wrote ($MA_MAX_AX_ACCEL ...).
    machine_data: machine_data::MachineData,
    /// VELOLIMA, ACCLIMA, JERKLIMA and the electronic gears (`dynamics.rs`).
    dynamics: dynamics::Dynamics,
    /// FPR, FPRAON and FDA: what feeds per revolution are per (`feed_source.rs`).
    feed_sources: feed_source::FeedSources,
    /// The toolholders, their spindles and SETMTH (`toolholder.rs`).
    toolholders: toolholder::Toolholders,
    /// DITS and DITE (SD42010) and the last thread's lead (`threads.rs`).
    threads: threads::Threads,
    /// The grinding tools' data and GWPS by spindle (`grinding.rs`).
    grinding: grinding::Grinding,
    /// DIAMON, DIAM90, DIAMONA[ax] ...: the axes programmed in diameter (`diameter.rs`).
    diameter: diameter::Diameter,
    /// GEOAX: the channel axes behind the geometry axes (`geo_axes.rs`).
    geo_axes: geo_axes::GeometryAxes,
    /// SCC: the constant cutting rate's reference axis (`cutting_rate.rs`).
    speed_reference: cutting_rate::ReferenceAxis,
}

/// One program level of the call stack.
struct Level {
    /// Index into `programs`.
    program: usize,
    /// The next line to run.
    next: usize,
    /// Passes of the subprogram still to run after this one (`P`).
    passes_left: u32,
    /// The part repetitions running (REPEAT, REPEATB), innermost last.
    sections: Vec<Section>,
    /// The arguments of the call, until its PROC takes them.
    arguments: Option<Vec<language::Argument>>,
    /// What a PROC with SAVE gives back on return.
    saved: Option<Saved>,
}

/// The modal state a PROC with SAVE restores.
#[derive(Clone, Copy)]
struct Saved {
    modal: Modal,
    frame: frame::ProgrammableFrame,
    /// Group 29 and the axes' own diameter programming.
    diameter: diameter::Diameter,
}

/// A modal subprogram call (MCALL): called after every block with motion of the level that
/// made it.
#[derive(Clone, Debug)]
struct ModalCall {
    name: String,
    arguments: Option<Vec<language::Argument>>,
    span: Span,
    /// The call stack's depth where MCALL stood.
    depth: usize,
}

/// A part repetition running: lines `first..=last`, then on at `back`.
struct Section {
    first: usize,
    last: usize,
    back: usize,
    /// Passes still to run after this one.
    passes_left: u32,
}

/// The modal state of the groups vcnc runs.
#[derive(Clone, Copy, Debug)]
pub(super) struct Modal {
    motion: Motion,
    plane: Plane,
    absolute: bool,
    inch: bool,
    /// G700/G710: feeds convert with the unit too.
    inch_feeds: bool,
    feed_type: FeedType,
    /// G60 (true) or a continuous-path mode.
    exact_stop: bool,
    /// The rounding of the continuous path (G64, G641-G645) and its parameters.
    path_control: path_control::PathControl,
    /// The settable frame: 0 for G500, 1..4 for G54..G57, 5.. beyond.
    settable: u32,
}

/// The tools: selected, in the spindle, and the edge in force.
#[derive(Clone, Debug, Default)]
pub(super) struct ToolState {
    selected: Option<u32>,
    in_spindle: Option<u32>,
    /// D: 0 is no offset.
    edge: u32,
    /// The tool whose edge D names: the one in the spindle, or after a change under MD20270
    /// = -2 the old one until a D is programmed.
    offset_tool: Option<u32>,
}

impl Sinumerik {
    /// The program `text` (file `file`) on `machine`, whose profile must be a SINUMERIK one (an
    /// ISO profile gets the 840D's settings).
    pub fn new(text: impl Into<Arc<[u8]>>, file: FileId, machine: &Machine) -> Sinumerik {
        let settings = machine.profile.sinumerik.clone().unwrap_or_else(|| {
            crate::profile::Profile::builtin(crate::ProfileName::Sinumerik)
                .sinumerik
                .expect("the SINUMERIK profile has its settings (checked by tests)")
        });
        let mut front_end = Sinumerik {
            programs: vec![Program::new(file, "", text.into())],
            levels: vec![Level {
                program: 0,
                next: 0,
                passes_left: 0,
                sections: Vec::new(),
                arguments: None,
                saved: None,
            }],
            structure: flow::Structure::default(),
            frame: frame::ProgrammableFrame::default(),
            modal_call: None,
            noted: std::collections::HashSet::new(),
            unknown_tools: std::collections::HashMap::new(),
            polar: polar::Polar::new(),
            spindle: spindle::Spindle::default(),
            tool_offsets: tools::Offsets::None,
            frame_writes: Vec::new(),
            block_feed_restore: None,
            tooth_feed: None,
            feed_override: 1.0,
            programmed_feed: None,
            angle_lines: contour::AngleLines::new(),
            contour: contour::Contour::new(),
            rounding_modal: false,
            idle_blocks: 0,
            corner_feed_modal: None,
            corner_feed: None,
            corner_origin: None,
            tangent: None,
            arc_tolerance: machine.profile.motion.arc_radius_tolerance,
            jumps: 0,
            spare: None,
            general_block: None,
            plain_blocks: true,
            radius_compensation: compensation::RadiusCompensation::default(),
            cycles: cycles::Calls::default(),
            work_area: work_area::WorkArea::default(),
            machine_data: machine_data::MachineData::default(),
            dynamics: dynamics::Dynamics::default(),
            feed_sources: feed_source::FeedSources::default(),
            toolholders: toolholder::Toolholders::default(),
            threads: threads::Threads::default(),
            grinding: grinding::Grinding::default(),
            diameter: diameter::Diameter::default(),
            geo_axes: geo_axes::GeometryAxes::default(),
            speed_reference: cutting_rate::ReferenceAxis::default(),
            library: None,
            vars: vars::Variables::new(settings.r_parameters as usize),
            tools: machine.tools.clone(),
            modal: Modal {
                motion: Motion::Line,
                plane: Plane::Xy,
                absolute: true,
                inch: false,
                inch_feeds: false,
                feed_type: FeedType::PerMinute,
                exact_stop: true,
                path_control: path_control::PathControl::default(),
                settable: 0,
            },
            programmed: [0.0; AXES],
            axes: language::ChannelAxes::new(machine),
            spindles: spindles::Spindles::new(machine.spindle.count),
            axis_feeds: axes::AxisFeeds::default(),
            skip: [false; 10],
            tool: ToolState::default(),
            iterations: 0,
            last_span: Span::new(file, 1, 0..0),
            settings,
        };
        front_end.skip[0] = false;
        front_end
    }

    /// The main program of `file`, read from `reader` as it runs, on `machine` (as
    /// [`Sinumerik::new`]): it runs in the same memory however long it is. A program that jumps
    /// or loops needs its whole text then, which the library gives
    /// ([`ProgramLibrary::main_text`]: read again from its file).
    pub fn streamed(reader: Box<dyn Read + Send>, file: FileId, machine: &Machine) -> Sinumerik {
        let mut front_end = Sinumerik::new(Vec::new(), file, machine);
        front_end.programs[0] = Program::streamed(file, reader, None);
        front_end
    }

    /// As [`Sinumerik::streamed`], with the program's lines read and parsed on a thread of their
    /// own, a few hundred lines ahead (`expected_bytes`: about the program's length, 0 when
    /// unknown): for a machine with a core to spare.
    pub fn streamed_ahead(
        reader: Box<dyn Read + Send>,
        expected_bytes: u64,
        file: FileId,
        machine: &Machine,
    ) -> Sinumerik {
        let mut front_end = Sinumerik::new(Vec::new(), file, machine);
        front_end.programs[0] = Program::streamed(file, reader, Some(expected_bytes));
        front_end
    }

    /// Where called programs come from.
    pub fn with_library(mut self, library: Box<dyn ProgramLibrary>) -> Sinumerik {
        self.library = Some(library);
        self
    }

    /// Every block run the general way, the plain CAM blocks too (`plain_block.rs` runs those by
    /// a short path): what the differential tests compare the short path with.
    #[doc(hidden)]
    pub fn without_plain_blocks(mut self) -> Sinumerik {
        self.plain_blocks = false;
        self
    }

    /// Block skip level `level` (0 for `/` and `/0`, 1 to 9) switched on or off.
    pub fn with_skip_level(mut self, level: u8, on: bool) -> Sinumerik {
        if let Some(switch) = self.skip.get_mut(level as usize) {
            *switch = on;
        }
        self
    }

    /// The power-on state of MD20150, applied to the kernel before the first block.
    fn power_on(&mut self, kernel: &mut Kernel) -> Result<(), Alarm> {
        let span = self.last_span;
        let names = self.settings.power_on.clone();
        for name in &names {
            let function = gcodes::function(name, self.is_828d()).ok_or_else(|| {
                Alarm::error(
                    AlarmCode::UnknownGCode,
                    span,
                    format!("the machine data's power-on state names `{name}`, which is not a G function"),
                )
            })?;
            block::apply_modal(self, kernel, function, span)?;
        }
        self.programmed = kernel.program_position();
        Ok(())
    }

    fn is_828d(&self) -> bool {
        self.settings.variant == Variant::M828d
    }

    /// The program and line to run next: the current level's next line, unless a part
    /// repetition ends there (then its next pass, or the line after its REPEAT).
    fn next_line(&mut self) -> (usize, usize) {
        let level = self.level();
        while let Some(section) = level.sections.last_mut() {
            if level.next != section.last + 1 {
                break;
            }
            if section.passes_left > 0 {
                section.passes_left -= 1;
                level.next = section.first;
                break;
            }
            level.next = section.back;
            level.sections.pop();
        }
        (level.program, level.next)
    }

    /// Makes line `index` of `program` at hand: the next line of a streamed main program is
    /// read, any other line needs its whole text.
    fn fetch(&mut self, program: usize, index: usize) -> Result<(), Alarm> {
        let fetched = self.programs[program].fetch(index).map_err(|error| {
            Alarm::error(
                AlarmCode::ReadError,
                self.last_span,
                format!("cannot read the program: {error}"),
            )
        })?;
        match fetched {
            Fetched::Ready => Ok(()),
            Fetched::NeedsWhole => self.make_whole(program),
        }
    }

    /// Holds `program` whole, so that any of its lines can be had (jumps, loops, structures).
    fn make_whole(&mut self, program: usize) -> Result<(), Alarm> {
        if self.programs[program].is_whole() {
            return Ok(());
        }
        let text = self.library.as_mut().and_then(|l| l.main_text());
        let Some(text) = text else {
            return Err(Alarm::error(
                AlarmCode::ReadError,
                self.last_span,
                "the program jumps or loops, and its text, read from a stream, cannot be read again",
            )
            .with_help("run the program from a file, or give its text whole"));
        };
        self.programs[program].make_whole(text);
        Ok(())
    }

    /// DEF, PROC and DEFINE.
    fn declaration(
        &mut self,
        kernel: &Kernel,
        statement: &crate::syntax::sinumerik::Statement,
        span: Span,
    ) -> Result<Step, Alarm> {
        use crate::syntax::sinumerik::StatementKind;
        match &statement.kind {
            StatementKind::Procedure(procedure) => {
                let arguments = self.level().arguments.take().unwrap_or_default();
                self.bind(arguments, procedure, span)?;
                if procedure.attributes.iter().any(|a| &*a.value == "SAVE") {
                    let saved = Saved {
                        modal: self.modal,
                        frame: self.frame,
                        diameter: self.diameter,
                    };
                    self.level().saved = Some(saved);
                }
            }
            StatementKind::Definition(definition) => self.define(kernel, definition)?,
            _ => {
                return Err(Alarm::error(
                    AlarmCode::NotSupportedYet,
                    span,
                    "DEFINE macros are not run yet by vcnc",
                ))
            }
        }
        Ok(Step::Next)
    }

    /// No element in the plane joins the held block: it moves without its corner.
    fn flush_contour(&mut self, kernel: &mut Kernel) -> Result<(), Alarm> {
        self.angle_lines.close()?;
        let cuts = self.contour.flush();
        let mut flushed = motion::Prepared::Cuts { cuts, held: 0 };
        flushed.release_held(self, kernel)?;
        flushed.finish(self, kernel)
    }

    /// A jump back (a loop's end, GOTOB, GOTO): counted against the limit that ends a program
    /// that would run for ever (a straight program of any length never reaches it).
    fn count_jump(&mut self, span: Span) -> Result<(), Alarm> {
        self.jumps += 1;
        if self.jumps > self.settings.iteration_limit {
            return Err(Alarm::error(
                AlarmCode::MacroLimit,
                span,
                format!(
                    "the program jumped back {} times without ending",
                    self.settings.iteration_limit
                ),
            )
            .with_help("a loop or jump never ends; the limit is iteration_limit in the profile's [sinumerik] table"));
        }
        Ok(())
    }

    /// The current level.
    fn level(&mut self) -> &mut Level {
        self.levels
            .last_mut()
            .expect("the main program's level stays until the end")
    }

    /// The edge in force: the tool in the spindle's edge D (none for D0 or no tool).
    fn edge(&self) -> Option<&ToolEdge> {
        let tool = self.tool.offset_tool?;
        (self.tool.edge != 0).then_some(())?;
        self.tools
            .iter()
            .find(|e| e.t == tool && e.d == self.tool.edge)
    }

    /// The text of the current level ran out: a subprogram returns, the main program ends.
    fn end_of_text(&mut self, kernel: &mut Kernel) -> Result<Step, Alarm> {
        if self.levels.len() > 1 {
            self.return_from_subprogram(kernel);
            return Ok(Step::Next);
        }
        kernel.warn(
            Alarm::warning(
                AlarmCode::MissingProgramEnd,
                self.last_span,
                "the program ends without M2, M30 or M17",
            )
            .with_help("end the main program with M30"),
        );
        kernel.end(EndKind::EndOfText, Origin::at(self.last_span));
        Ok(Step::End)
    }

    /// M17, RET or the end of a subprogram's text: the next pass, or back to the caller; a
    /// PROC with SAVE gives back the modal state it was called with.
    fn return_from_subprogram(&mut self, kernel: &mut Kernel) {
        let level = self.level();
        if level.passes_left > 0 {
            level.passes_left -= 1;
            level.next = 0;
            return;
        }
        let saved = self.levels.pop().and_then(|level| level.saved);
        self.vars.pop_level();
        // A modal call made in the subprogram ends with it.
        if self
            .modal_call
            .as_ref()
            .is_some_and(|c| c.depth > self.levels.len())
        {
            self.modal_call = None;
        }
        if let Some(saved) = saved {
            self.restore(kernel, saved);
        }
    }

    /// The modal state a PROC with SAVE restores on return (PGAsl SAVE): the G functions, the
    /// settable and the programmable frame.
    fn restore(&mut self, kernel: &mut Kernel, saved: Saved) {
        let settable = saved.modal.settable;
        self.modal = saved.modal;
        kernel.set_plane(self.modal.plane);
        kernel.select_work_offset(block::settable_id(settable, self.is_828d()));
        self.frame = saved.frame;
        self.diameter = saved.diameter;
        kernel.set_programmable(self.frame.to_affine());
        tools::apply_length(self, kernel);
    }

    /// Calls subprogram `name` for `passes` passes from the block at `span`, with the
    /// arguments of a call in parentheses.
    fn call(
        &mut self,
        name: &str,
        passes: u32,
        span: Span,
        arguments: Option<Vec<language::Argument>>,
    ) -> Result<(), Alarm> {
        if self.levels.len() > self.settings.call_depth as usize {
            return Err(Alarm::error(
                AlarmCode::MacroLimit,
                span,
                format!(
                    "calling {name} would nest more than {} program levels",
                    self.settings.call_depth
                ),
            )
            .with_help("a program that calls itself needs a condition that ends the calls"));
        }
        let program = match self.programs.iter().position(|p| *p.name == *name) {
            Some(index) => index,
            None => match self.load(name, span)? {
                Some(index) => index,
                // A standard cycle: run by the front end at the block's end.
                None => return self.cycles.call(name, passes, span, arguments),
            },
        };
        if passes == 0 {
            return Ok(());
        }
        self.vars.push_level(span)?;
        self.levels.push(Level {
            program,
            next: 0,
            passes_left: passes - 1,
            sections: Vec::new(),
            arguments,
            saved: None,
        });
        Ok(())
    }

    /// The program `name` loaded, from the library if it is not yet: a modal call checks its
    /// target where MCALL stands.
    fn preload(&mut self, name: &str, span: Span) -> Result<(), Alarm> {
        if !self.programs.iter().any(|p| *p.name == *name) {
            self.load(name, span)?;
        }
        Ok(())
    }

    /// Loads subprogram `name` from the library; None for a standard cycle the library does
    /// not have (a machine's own program of that name wins over the built-in cycle).
    fn load(&mut self, name: &str, span: Span) -> Result<Option<usize>, Alarm> {
        if self.cycles.is_built_in(name) {
            return Ok(None);
        }
        let found = match self.library.as_mut() {
            Some(library) => library
                .find_named(name)
                .map_err(|error| Alarm::error(AlarmCode::ReadError, span, error.to_string()))?,
            None => None,
        };
        let Some(found) = found else {
            if cycles::runs(name) {
                self.cycles.remember_built_in(name);
                return Ok(None);
            }
            return Err(gcodes::missing_program(name, span));
        };
        self.programs
            .push(Program::new(found.file, name, found.text));
        Ok(Some(self.programs.len() - 1))
    }
}

impl Sinumerik {
    /// The next block's step (see [`FrontEnd::step`]).
    fn next_step(&mut self, kernel: &mut Kernel) -> Result<Step, Alarm> {
        if self.iterations == 0 {
            self.power_on(kernel)?;
        }
        self.iterations += 1;
        loop {
            // A position pattern waiting for a subprogram that returned at its text's end.
            cycles::run_called(self, kernel)?;
            let (program, index) = self.next_line();
            self.fetch(program, index)?;
            let text = &mut self.programs[program];
            let file = text.file;
            let mut block = self.spare.take().unwrap_or_default();
            let Some((line, parsed)) = text.take_line(index, &mut block) else {
                self.spare = Some(block);
                return self.end_of_text(kernel);
            };
            let header = is_header(line.bytes);
            let (number, base) = (line.number, line.base);
            let span = Span::new(file, number, base..base + line.bytes.len() as u32);
            if !parsed && !header {
                parse_line_into(line.bytes, file, number, base, &mut block);
            }
            self.level().next = index + 1;
            if header {
                self.spare = Some(block);
                continue;
            }
            let step = self.run_line(kernel, &block, (program, index), span);
            // The block's room goes to the next line.
            self.spare = Some(block);
            let step = step?;
            // A standard cycle the block called runs at its end (docs/SINUMERIK.md, Standard
            // cycles).
            cycles::run_called(self, kernel)?;
            if let Some(step) = step {
                return Ok(step);
            }
        }
    }

    /// Runs the block of line `index` of `program`, written at `span`; None when it is skipped
    /// or has nothing to run.
    fn run_line(
        &mut self,
        kernel: &mut Kernel,
        block: &Block,
        (program, index): (usize, usize),
        span: Span,
    ) -> Result<Option<Step>, Alarm> {
        let no_words = block.words.is_empty() && block.plain.is_none();
        if no_words && block.statement.is_none() && block.alarm.is_none() {
            return Ok(None);
        }
        // The 828D has the skip levels /0 to /7 only (docs/SINUMERIK.md 9).
        if let Some(level @ 8..) = block.skip.filter(|_| self.is_828d()) {
            return Err(Alarm::error(
                AlarmCode::WordNotAllowed,
                Span::new(span.file, span.line, span.start..span.start + 2),
                format!("the 828D has no skip level /{level}: its levels are /0 to /7"),
            )
            .with_help("use a skip level from /0 to /7, or the 840D profile"));
        }
        if block.skip.is_some_and(|level| self.skip[level as usize]) {
            return Ok(None);
        }
        self.last_span = span;
        if let Some(alarm) = &block.alarm {
            return Err(alarm.clone());
        }
        let step = if no_words {
            Step::Next
        } else {
            block::run(self, kernel, block, span)?
        };
        let step = match (&block.statement, step) {
            (Some(statement), Step::Next) => {
                use crate::syntax::sinumerik::StatementKind;
                // Declarations run where they stand; every other statement may look at other
                // lines (its partner, a label), which a streamed text has not at hand.
                if !matches!(
                    statement.kind,
                    StatementKind::Definition(_)
                        | StatementKind::Procedure(_)
                        | StatementKind::Call { section: None, .. }
                ) {
                    self.make_whole(program)?;
                }
                control::run(self, kernel, statement, index, span)?
            }
            (_, step) => step,
        };
        Ok(Some(step))
    }
}

impl FrontEnd for Sinumerik {
    fn step(&mut self, kernel: &mut Kernel) -> Result<Step, Alarm> {
        let from = kernel.waiting();
        let step = self.next_step(kernel).map_err(with_sinumerik_help)?;
        self.work_area.check(kernel, from)?;
        // Compensation counts the blocks without motion in its plane, and stops at a corner
        // it could not make.
        kernel.end_block()?;
        Ok(step)
    }
}

/// `alarm` with a help line in SINUMERIK's terms where it has none of its own and its code's
/// help names ISO syntax (the codes are shared with the ISO front end: `#3000`, `( )` comments,
/// `G01`, `M99` mean nothing in a SINUMERIK program).
fn with_sinumerik_help(alarm: Alarm) -> Alarm {
    use AlarmCode::*;
    // The kernel's own help for a missing feed names the FANUC alarm: replaced too.
    if alarm.help.is_some() && alarm.code != NoFeedRate {
        return alarm;
    }
    let help = match alarm.code {
        UnexpectedCharacter => "remove the character, or put it in a comment after `;`",
        MacroSyntax => {
            "check the brackets, keywords and operators of the statement: the language is in docs/SINUMERIK.md"
        }
        BadVariable => "define the variable with DEF first; the system variables vcnc has are in docs/SINUMERIK.md",
        LoopStructure => "close every IF, WHILE, FOR, REPEAT and LOOP with its ENDIF, ENDWHILE, ENDFOR, UNTIL or ENDLOOP",
        UserAlarm => "the program raised this alarm itself with SETAL: see its message and the cycle that set it",
        MacroLimit => "a loop or jump never ends; the limit is iteration_limit in the profile's [sinumerik] table",
        ArcRadiusTooSmall => "make CR= at least half the distance between the start and the end point, or check I, J, K",
        ArcWithoutCenter => "give the arc its centre (I, J, K), its radius (CR=) or its opening angle (AR=)",
        NoFeedRate => "program an F word before or in the first G1/G2/G3 block",
        MissingProgramEnd => "end the main program with M30, and a subprogram with M17 or RET",
        SequenceNotFound => "add the label or N block the jump names, or change the jump's target",
        ProgramNotFound => "put the program's .SPF in the program's directory or in a directory given with --lib",
        _ => return alarm,
    };
    alarm.with_help(help)
}

/// A SINUMERIK program held in memory, as file 0, on `machine`.
pub fn run_str(text: &str, machine: &Machine) -> Run<Sinumerik> {
    let front_end = Sinumerik::new(text.as_bytes(), FileId(0), machine);
    Run::new(front_end, Kernel::new(machine))
}
