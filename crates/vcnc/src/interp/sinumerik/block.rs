//! One SINUMERIK block run in the control's order (docs/SINUMERIK.md 3.2): read and check the
//! words, assignments, G functions, settable frame, feed, spindle, tool, other functions, the
//! motion, then the block's end (stops, calls, returns, the program end).
//!
//! Never: let the written order of the words change what a block does, or run a word it does not
//! understand: an unknown address or name is an alarm naming it.

use super::gcodes::{self, FeedType, Function, OneBlock};
use super::instructions::{frame_instruction, pole};
use super::language::Argument;
use super::motion::{self, unit};
use super::predefined::{note_state, unknown_word, user_alarm, written};
use super::spindle;
use super::tools;
use super::{axes, multi_feed, spindles};
use super::{Sinumerik, Step};
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::kernel::{Kernel, Origin};
use crate::interp::modal::FeedMode;
use crate::machine::{WorkOffsetId, AXES};
use crate::motion::{EndKind, PathMode, SegmentKind, StopKind};
use crate::source::Span;
use crate::syntax::sinumerik::{Block, Expr, ExprKind, UnaryOp, Value, Word};

/// The numbers given to tools called by a name the tool table lacks.
const UNLISTED_TOOLS: u32 = 1_000_000;

/// Predefined procedures that are neither subprograms nor cycles (the language's own).
const PREDEFINED: [&str; 3] = ["MSG", "SETAL", "STOPRE"];

use super::language::AxisLookup;

/// A value on an axis or centre word: as written, or made absolute or incremental for this word
/// (`X=AC(10)`, `X=IC(5)`).
#[derive(Clone, Copy, Debug)]
pub(super) struct AxisValue {
    pub(super) value: f64,
    /// Some(true) for AC, Some(false) for IC.
    pub(super) absolute: Option<bool>,
    /// Some(true) for DAC, DIC (a diameter), Some(false) for RAC, RIC, whatever the diameter
    /// programming in force (`diameter.rs`).
    pub(super) diameter: Option<bool>,
}

/// The words of one block, sorted by what they do.
#[derive(Default)]
pub(super) struct Words<'a> {
    /// The G functions, with their groups.
    pub(super) functions: Functions<'a>,
    pub(super) axes: [Option<AxisValue>; AXES],
    /// I J K.
    pub(super) centre: [Option<AxisValue>; 3],
    /// I1 J1 K1: CIP's intermediate point.
    pub(super) via: [Option<AxisValue>; 3],
    /// CR=.
    pub(super) radius: Option<(f64, Span)>,
    /// AR=: the opening angle.
    pub(super) opening: Option<(f64, Span)>,
    /// TURN=.
    pub(super) turn: Option<(f64, Span)>,
    /// AP= and RP=.
    pub(super) ap: Option<AxisValue>,
    pub(super) rp: Option<AxisValue>,
    /// ANG=.
    pub(super) ang: Option<(f64, Span)>,
    /// RND=, CHF=, CHR= at the block's end; RNDM= from it on.
    pub(super) rnd: Option<(f64, Span)>,
    pub(super) chf: Option<(f64, Span)>,
    pub(super) chr: Option<(f64, Span)>,
    pub(super) rndm: Option<(f64, Span)>,
    /// Machine axes named X1 .. C1 (G74, G75).
    pub(super) machine_axes: [Option<f64>; AXES],
    /// FP=n: G75's fixed point.
    pub(super) fixed_point: Option<(u32, Span)>,
    /// FRC, FRCM: the feed of chamfers and roundings.
    pub(super) frc: Option<(f64, Span)>,
    pub(super) frcm: Option<(f64, Span)>,
    /// SVC, LIMS, SPOS (its angle).
    pub(super) svc: Option<(f64, Span)>,
    pub(super) lims: Option<(f64, Span)>,
    pub(super) spos: Option<(f64, Span)>,
    /// TOFFL, TOFF and TOFFR words of the block.
    pub(super) offsets: Vec<tools::OffsetWord>,
    /// OVR: the path override, percent.
    pub(super) override_percent: Option<f64>,
    /// FB (this block's feed), FZ (per tooth).
    pub(super) fb: Option<(f64, Span)>,
    pub(super) fz: Option<(f64, Span)>,
    /// RPL: the angle of a rotation in the plane.
    pub(super) rpl: Option<(f64, Span)>,
    pub(super) feed: Option<(f64, Span)>,
    pub(super) speed: Option<(f64, Span)>,
    pub(super) tool: Option<(u32, Span)>,
    pub(super) edge: Option<(u32, Span)>,
    pub(super) m: Vec<(u32, Span)>,
    /// POS and POSA: positioning axes.
    pub(super) positioning: axes::Positioning,
    call: Option<(String, Span)>,
    /// Warnings the words raised, for the stream.
    pub(super) warnings: Vec<Alarm>,
    /// MCALL: the block's call becomes modal (or, without one, the modal call ends).
    mcall: Option<Span>,
    /// The arguments of a call with parentheses, evaluated where the call stands.
    arguments: Option<Vec<Argument>>,
    passes: Option<(u32, Span)>,
    ends: Option<(End, Span)>,
}

/// A G function of a block: what it does, its group, its word.
pub(super) type FunctionWord<'a> = (Function, Option<u8>, &'a Word);

/// The G functions of a block in their order: a block has one or two, held in place (a
/// vector allocated and freed a block cost about as much as sorting the block's words).
#[derive(Default)]
pub(super) struct Functions<'a> {
    first: [Option<FunctionWord<'a>>; 4],
    more: Vec<FunctionWord<'a>>,
}

impl<'a> Functions<'a> {
    fn push(&mut self, function: FunctionWord<'a>) {
        match self.first.iter_mut().find(|slot| slot.is_none()) {
            Some(slot) => *slot = Some(function),
            None => self.more.push(function),
        }
    }

    /// The functions in the order of their words.
    pub(super) fn iter(&self) -> impl Iterator<Item = &FunctionWord<'a>> {
        self.first
            .iter()
            .map_while(Option::as_ref)
            .chain(&self.more)
    }
}

/// How a block ends the program or the subprogram.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum End {
    /// M2 or M30: the main program ends (a subprogram returns).
    Program(EndKind),
    /// M17 or RET: a subprogram returns.
    Return,
}

/// Runs `block` (at `span`) of the front end on the kernel.
pub(super) fn run(
    front: &mut Sinumerik,
    kernel: &mut Kernel,
    block: &Block,
    span: Span,
) -> Result<Step, Alarm> {
    if let Some(plain) = &block.plain {
        if front.plain_blocks {
            if let Some(step) = super::plain_block::run(front, kernel, plain, block.number, span) {
                return step;
            }
        }
        // The general way, from the words the line reads as.
        let mut general = front.general_block.take().unwrap_or_default();
        general.number = block.number;
        general.words.clear();
        plain.to_words(&mut general.words);
        let step = run(front, kernel, &general, span);
        front.general_block = Some(general);
        return step;
    }
    let origin = Origin {
        span,
        sequence: block.number,
    };
    // Filled in place: a Words is large, and returned through a Result it was copied twice.
    let mut words = Words::default();
    read(front, kernel, block, &mut words)?;
    front.apply_frame_writes(kernel);
    for warning in words.warnings.drain(..) {
        kernel.warn(warning);
    }
    // A block held for its corner moves with the feed it was read with.
    let feed_before = kernel.feed_setting();
    // G functions take their new members before any value of the block is read.
    let mut one_block = Vec::new();
    // The groups seen so far, a bit each: the first word of a group is looked up again only
    // for the alarm.
    let mut groups = 0u64;
    for &(function, group, word) in words.functions.iter() {
        if let Some(group) = group {
            let bit = 1u64 << (group % 64);
            if groups & bit != 0 {
                let first = words
                    .functions
                    .iter()
                    .find(|(_, g, _)| *g == Some(group))
                    .map_or(word.span, |(_, _, w)| w.span);
                return Err(Alarm::error(
                    AlarmCode::SameGroupGCodes,
                    word.span,
                    format!("two G functions of group {group} in one block"),
                )
                .with_label(first, "the first one")
                .with_help("keep one G function of each group in a block"));
            }
            groups |= bit;
        }
        match function {
            Function::OneBlock(f) => one_block.push((f, word.span)),
            _ => apply_modal(front, kernel, function, word.span)?,
        }
    }
    if let Some(&(Function::Frame(op), _, word)) = words
        .functions
        .iter()
        .find(|(f, _, _)| matches!(f, Function::Frame(_)))
    {
        front.flush_contour(kernel)?;
        frame_instruction(front, kernel, &words, op, word)?;
        return Ok(Step::Next);
    }
    if let Some(&(Function::Pole(reference), _, _)) = words
        .functions
        .iter()
        .find(|(f, _, _)| matches!(f, Function::Pole(_)))
    {
        front.flush_contour(kernel)?;
        return pole(front, &words, reference, origin).map(|()| Step::Next);
    }
    let speed_limit = words.functions.iter().find_map(|(f, _, w)| match f {
        Function::SpeedLimit(max) => Some((*max, *w)),
        _ => None,
    });
    if let Some((upper, _)) = speed_limit {
        if words.axes.iter().any(Option::is_some) {
            // With axes, G25/G26 are the working area's limits, and the block does nothing else.
            let unit = super::motion::unit(front);
            let limits = words.axes.map(|a| a.map(|a| a.value * unit));
            front
                .work_area
                .set(upper, limits, kernel.state().setup.machine());
            return Ok(Step::Next);
        }
    }
    let speed_limit = speed_limit.map(|(max, _)| max);
    super::geo_axes::check_block(front, &words, span)?;
    super::diameter::convert(front, &mut words);
    let dwell = one_block.iter().any(|(f, _)| *f == OneBlock::Dwell);
    let suppress = one_block.iter().find_map(|&(f, _)| match f {
        OneBlock::SuppressFrames
        | OneBlock::SuppressBasic
        | OneBlock::SuppressAll
        | OneBlock::Reference
        | OneBlock::FixedPoint => Some(f),
        _ => None,
    });
    // G63 cuts a G1 line in tapping mode, whatever group 1 says.
    let floating_tap = one_block.iter().any(|(f, _)| *f == OneBlock::FloatingTap);
    let modal_motion = front.modal.motion;
    if floating_tap {
        front.modal.motion = gcodes::Motion::Line;
    }
    if let Some((radius, span)) = words.rndm {
        front
            .contour
            .set_modal_rounding(radius * unit(front), span)?;
        front.rounding_modal = radius != 0.0;
    }
    let prepared = if dwell || suppress.is_some() {
        Ok(motion::Prepared::None)
    } else {
        motion::prepare(front, kernel, &words, origin)
    };
    front.modal.motion = modal_motion;
    let mut prepared = prepared?;
    let moved = suppress.is_some()
        || !matches!(prepared, motion::Prepared::None | motion::Prepared::Waiting);
    // A corner waits over a few blocks without motion (PGsl 9.15, L6797-6803; five is vcnc's
    // choice of the machine data's number); a dwell, a tool change, a call or the end do not.
    let breaks = dwell
        || suppress.is_some()
        || words.tool.is_some()
        || words.m.iter().any(|&(m, _)| m == 6)
        || words.call.is_some()
        || words.ends.is_some();
    if matches!(prepared, motion::Prepared::None) {
        front.idle_blocks += 1;
        if breaks || front.idle_blocks > 5 {
            front.flush_contour(kernel)?;
        }
    } else {
        front.idle_blocks = 0;
    }
    let feed_now = kernel.feed_setting();
    kernel.set_feed_in(feed_before.0, feed_before.1);
    prepared.release_held(front, kernel)?;
    kernel.set_feed_in(feed_now.0, feed_now.1);
    let limits = spindle::SpindleWords {
        g25: speed_limit == Some(false),
        g26: speed_limit == Some(true),
    };
    let mode = feed_mode(front.modal.feed_type);
    // The tool first: SVC and FZ in its block read the new edge, and the spindle starts with
    // the new tool in it (docs/SINUMERIK.md 3.2 steps 6-8).
    tools::change(front, kernel, &words, origin)?;
    // G34 and G35 read F as the lead's change, not as the path feed (threads.rs).
    if matches!(front.modal.motion, gcodes::Motion::VariableThread { .. }) {
        words.feed = None;
    }
    if !dwell {
        spindle::feed(front, kernel, &words, mode)?;
        spindle::spindle(front, kernel, &words, &limits, origin)?;
    }
    super::dynamics::before_motion(front, kernel, &words.axes, &words.positioning, origin)?;
    super::feed_source::before_motion(front, kernel, &words.positioning, origin)?;
    super::toolholder::before_motion(front, kernel, origin);
    for &(code, span) in &words.m {
        auxiliary(kernel, code, Origin { span, ..origin });
    }
    if dwell {
        axes::position(front, kernel, &words, origin)?;
        return dwell_block(kernel, &words, origin).map(|()| Step::Next);
    }
    let exact_stop = one_block.iter().any(|(f, _)| *f == OneBlock::ExactStop);
    let path_mode = if floating_tap {
        PathMode::Tapping
    } else if front.modal.exact_stop {
        PathMode::ExactStop
    } else {
        PathMode::Continuous
    };
    kernel.set_path_mode(path_mode, exact_stop);
    let rapid = front.modal.motion == gcodes::Motion::Rapid;
    let planner = &kernel.state().setup.machine().planner;
    kernel.set_smoothing(front.modal.path_control.smoothing(rapid, planner));
    super::compensation::before_motion(front, kernel, moved, origin.span)?;
    match suppress {
        Some(OneBlock::Reference | OneBlock::FixedPoint) => {
            motion::reference_move(
                front,
                kernel,
                &words,
                suppress == Some(OneBlock::Reference),
                origin,
            )?;
        }
        Some(level) => motion::suppressed_move(front, kernel, &words, level, origin)?,
        None => prepared.finish(front, kernel)?,
    }
    super::compensation::after_motion(front, kernel, origin)?;
    axes::position(front, kernel, &words, origin)?;
    spindle::constant_rate(front, kernel, origin);
    spindle::restore_feed(front, kernel, mode);
    for &(code, span) in &words.m {
        if let Some(kind) = stop_kind(code) {
            kernel.event(SegmentKind::Stop { kind }, Origin { span, ..origin });
        }
    }
    match (words.mcall, &words.call) {
        (Some(_), Some((name, span))) => {
            front.preload(name, *span)?;
            front.modal_call = Some(super::ModalCall {
                name: name.clone(),
                arguments: words.arguments.clone(),
                span: *span,
                depth: front.levels.len(),
            });
        }
        (Some(_), None) => front.modal_call = None,
        (None, Some((name, span))) => {
            let passes = words.passes.map_or(1, |(p, _)| p);
            front.call(name, passes, *span, words.arguments.clone())?;
        }
        // After every block with motion of the program that made it modal (not inside the
        // called program itself).
        (None, None) if moved => {
            if let Some(call) = front
                .modal_call
                .as_ref()
                .filter(|c| c.depth == front.levels.len())
                .cloned()
            {
                front.call(&call.name, 1, call.span, call.arguments)?;
            }
        }
        (None, None) => {}
    }
    if words
        .functions
        .iter()
        .any(|(f, _, _)| *f == Function::IsoMode)
    {
        front.flush_contour(kernel)?;
        // The ISO section reads the lines after this one: a streamed main program is read
        // whole first.
        let program = front.level().program;
        front.make_whole(program)?;
        let first = front.level().next;
        let back = super::iso_mode::run(front, kernel, first)?;
        front.level().next = back;
    }
    match words.ends {
        Some((End::Program(kind), span)) if front.levels.len() == 1 => {
            kernel.end(kind, Origin { span, ..origin });
            Ok(Step::End)
        }
        Some(_) if front.levels.len() > 1 => {
            front.return_from_subprogram(kernel);
            Ok(Step::Next)
        }
        // M17 or RET in the main program ends it, as M30 would (docs/SINUMERIK.md 8.3).
        Some((End::Return, span)) => {
            kernel.end(EndKind::M30, Origin { span, ..origin });
            Ok(Step::End)
        }
        _ => Ok(Step::Next),
    }
}

/// Sorts the block's words; a word vcnc does not run is an alarm naming it.
fn read<'a>(
    front: &mut Sinumerik,
    kernel: &Kernel,
    block: &'a Block,
    words: &mut Words<'a>,
) -> Result<(), Alarm> {
    for word in &block.words {
        if let (Some(letter), Value::Constant(n)) = (word.address.letter(), &word.value) {
            if letter_constant(front, words, letter, n.value, word) {
                continue;
            }
        }
        let address = &*word.address;
        // S as a grinding wheel's peripheral speed where GWPS is on (grinding.rs).
        if front.grinding.any_active()
            && address.starts_with('S')
            && !front.is_variable(address)
            && super::grinding::read_speed(front, kernel, block, word, words)?
        {
            continue;
        }
        // Spindles by number, the feed group and positioning axes: names of two letters or more.
        if address.len() > 1
            && matches!(
                address.as_bytes()[0],
                b'S' | b'M' | b'W' | b'L' | b'F' | b'P'
            )
            && !front.is_variable(address)
            && (spindles::read_word(front, kernel, block, word, words)?
                || axes::read_word(front, kernel, word, words)?
                || multi_feed::read_word(front, kernel, word, words)?)
        {
            continue;
        }
        if address.len() > 2
            && (super::dynamics::read_word(front, kernel, word)?
                || super::feed_source::read_word(front, kernel, word)?
                || super::toolholder::read_word(front, kernel, word)?)
        {
            continue;
        }
        if let Some(what) = gcodes::other_unit(address, &word.value) {
            return Err(Alarm::error(
                AlarmCode::NotInProduct,
                word.span,
                format!(
                    "{} belongs to {what}, which vcnc does not simulate",
                    written(word)
                ),
            ));
        }
        if let Some((function, group)) = gcodes_word(front, word)? {
            if function == Function::State {
                let name = match &word.value {
                    Value::Constant(n) => format!("G{}", n.value),
                    _ => word.address.to_string(),
                };
                if let "WALIMON" | "WALIMOF" = name.as_str() {
                    front.work_area.switch(name == "WALIMON");
                }
                // WALCS0-WALCS10 select the WCS limits (work_area.rs): run, not kept as state.
                if !front.work_area.select_cs(&name) {
                    note_state(front, &name, word, &mut words.warnings);
                }
            }
            words.functions.push((function, group, word));
            continue;
        }
        match front.axes.lookup(address) {
            AxisLookup::Present(axis) => {
                words.axes[axis] = Some(axis_value(front, kernel, word)?);
                continue;
            }
            AxisLookup::Absent => {
                return Err(Alarm::error(
                    AlarmCode::AxisNotOnMachine,
                    word.span,
                    format!("the machine has no axis {address}"),
                )
                .with_help(format!(
                    "add the axis to the machine file (`[axes.{}]`), or remove the word",
                    address.to_ascii_lowercase()
                )));
            }
            AxisLookup::NotAnAxis => {}
        }
        match address {
            "I" | "J" | "K" => {
                let i = (address.as_bytes()[0] - b'I') as usize;
                words.centre[i] = Some(axis_value(front, kernel, word)?);
            }
            "CR" => words.radius = Some((number(front, kernel, word)?, word.span)),
            "OFFN" | "DISC" | "DISR" | "DISCL" | "FAD" => {
                super::compensation::word(front, kernel, word)?
            }
            // H functions go to the machine's PLC; they move nothing (H=QU(..) included).
            "H" => {}
            // Machine axes by their own names (G74, G75): X1, Y1, Z1, A1, B1, C1.
            _ if address.len() == 2
                && address.ends_with('1')
                && front.axes.lookup(&address[..1]) != AxisLookup::NotAnAxis
                && !front.is_variable(address) =>
            {
                let Some(axis) = front.axes.index(&address[..1]) else {
                    return Err(Alarm::error(
                        AlarmCode::AxisNotOnMachine,
                        word.span,
                        format!("the machine has no axis {address}"),
                    ));
                };
                words.machine_axes[axis] = Some(number(front, kernel, word)?);
            }
            "FP" => words.fixed_point = Some((whole(front, kernel, word)?, word.span)),
            "I1" | "J1" | "K1" => {
                let i = (address.as_bytes()[0] - b'I') as usize;
                words.via[i] = Some(axis_value(front, kernel, word)?);
            }
            "AR" => words.opening = Some((number(front, kernel, word)?, word.span)),
            "TURN" => words.turn = Some((number(front, kernel, word)?, word.span)),
            "AP" => words.ap = Some(axis_value(front, kernel, word)?),
            "RP" => words.rp = Some(axis_value(front, kernel, word)?),
            "ANG" => words.ang = Some((number(front, kernel, word)?, word.span)),
            "ADIS" | "ADISPOS" => super::path_control::distance(front, kernel, word)?,
            "RND" => words.rnd = Some((number(front, kernel, word)?, word.span)),
            "CHF" => words.chf = Some((number(front, kernel, word)?, word.span)),
            "CHR" => words.chr = Some((number(front, kernel, word)?, word.span)),
            "RNDM" => words.rndm = Some((number(front, kernel, word)?, word.span)),
            "FRC" => words.frc = Some((number(front, kernel, word)?, word.span)),
            "FRCM" => words.frcm = Some((number(front, kernel, word)?, word.span)),
            "SVC" => words.svc = Some((number(front, kernel, word)?, word.span)),
            "LIMS" => words.lims = Some((number(front, kernel, word)?, word.span)),
            "FB" => words.fb = Some((number(front, kernel, word)?, word.span)),
            "FZ" => words.fz = Some((number(front, kernel, word)?, word.span)),
            // The master spindle by its number: S1=, M1=3, SPOS / SPOS[1].
            "S1" => words.speed = Some((number(front, kernel, word)?, word.span)),
            "M1" => {
                let code = whole(front, kernel, word)?;
                words.m.push((code, word.span));
            }
            "TOFFL" | "TOFF" | "TOFFR" => {
                tools::offset_word(front, kernel, word, &mut words.offsets)?
            }
            // Overrides and feed groups: the operator's panel and the path's axes; they change
            // no position (docs/SINUMERIK.md 1, accepted as state).
            "OVR" => {
                let percent = number(front, kernel, word)?;
                if !(0.0..=200.0).contains(&percent) {
                    return Err(Alarm::error(
                        AlarmCode::ValueOutOfRange,
                        word.span,
                        format!("OVR={percent}: the path override is 0 to 200 %"),
                    ));
                }
                words.override_percent = Some(percent);
            }
            // SF: a thread's start angle, which changes neither path nor time.
            "SF" => {}
            "OVRRAP" | "OVRA" | "ACC" | "SETMS" => {
                note_state(front, address, word, &mut words.warnings);
            }
            "GWPSON" | "GWPSOF" if !front.is_variable(address) => {
                super::grinding::switch(front, kernel, word)?
            }
            "DITS" | "DITE" if !front.is_variable(address) => {
                super::threads::ramp_word(front, kernel, word)?
            }
            "DILF" | "ALF" | "POLF" | "POLFMASK" | "POLFMLIN"
                if !front.is_variable(address)
                    && super::lift_fast::read_word(front, kernel, word, words)? => {}
            "RPL" => words.rpl = Some((number(front, kernel, word)?, word.span)),
            // Diameter programming of an axis, the cutting rate's reference axis, GEOAX.
            _ if super::diameter::axis_word(front, word)?
                || super::cutting_rate::read_word(front, word)?
                || super::geo_axes::read_word(front, kernel, word)? => {}
            "F" => words.feed = Some((number(front, kernel, word)?, word.span)),
            "S" => words.speed = Some((number(front, kernel, word)?, word.span)),
            "T" => {
                let t = tool_number(front, kernel, word, &mut words.warnings)?;
                words.tool = Some((t, word.span));
            }
            "D" => words.edge = Some((whole(front, kernel, word)?, word.span)),
            "P" => words.passes = Some((whole(front, kernel, word)?, word.span)),
            "M" => {
                let code = whole(front, kernel, word)?;
                match code {
                    2 => words.ends = Some((End::Program(EndKind::M02), word.span)),
                    30 => words.ends = Some((End::Program(EndKind::M30), word.span)),
                    17 => words.ends = Some((End::Return, word.span)),
                    _ => words.m.push((code, word.span)),
                }
            }
            "RET" => words.ends = Some((End::Return, word.span)),
            "L" => {
                let n = whole(front, kernel, word)?;
                words.call = Some((format!("L{n}"), word.span));
            }
            // The message only shows on the control's screen; STOPRE only waits for the
            // block preparation (vcnc prepares block by block); SBLOF/SBLON only change how
            // single-block mode stops, which vcnc has not.
            "STOPRE" | "MSG" | "SBLOF" | "SBLON" => {}
            // MCALL with a call makes it modal; alone, it ends the modal call (PGAsl MCALL).
            "MCALL" if matches!(word.value, Value::Bare) => words.mcall = Some(word.span),
            "SETAL" => return Err(user_alarm(front, kernel, word)?),
            // WRTPR writes to the control's printer; nothing moves.
            "WRTPR" => {}
            "CPRECON" | "CPRECOF" => {
                note_state(front, address, word, &mut words.warnings);
            }
            // The blank of ShopMill programs: the simulation's stock (issue 21), no motion.
            "WORKPIECE" => {}
            // A name alone that is no keyword calls the subprogram of that name (`L140`,
            // `CHAMFER`).
            _ if matches!(word.value, Value::Bare) && gcodes::out_of_product(address).is_none() => {
                words.call = Some((address.to_string(), word.span));
            }
            // An assignment: `R1=5`, `COUNT=COUNT+1`, `$P_UIFR[1,X,TR]=10`, `ARR[2]=7`, and
            // `R[R1+1]=8`, an R parameter by its number as an expression (PGAsl R parameters).
            _ if matches!(
                word.value,
                Value::Expression(_) | Value::Indexed(_, Some(_))
            ) && (address.starts_with('$')
                || front.is_variable(address)
                || address == "R" && matches!(word.value, Value::Indexed(..))) =>
            {
                let (indices, expr) = match &word.value {
                    Value::Expression(expr) => (&[][..], expr),
                    Value::Indexed(indices, Some(expr)) => (&indices[..], expr),
                    _ => unreachable!("matched above"),
                };
                front.assign_word(kernel, address, indices, expr, word.span)?;
            }
            // A call with arguments: a procedure (`L140(2)`, `CHAMFER(5)`).
            _ if matches!(word.value, Value::Call(_))
                && gcodes::out_of_product(address).is_none()
                && !PREDEFINED.contains(&address) =>
            {
                let Value::Call(arguments) = &word.value else {
                    unreachable!("matched above")
                };
                words.call = Some((address.to_string(), word.span));
                words.arguments = Some(front.arguments(kernel, arguments)?);
            }
            _ => return Err(unknown_word(word)),
        }
    }
    Ok(())
}

/// The common words of a CAM block, a letter and a constant (`X12.5`, `G1`, `F1500`), sorted
/// as [`read`] sorts them, without looking their address up by name; false for any other
/// (and for what raises an alarm: an axis the machine lacks), which `read` then takes.
fn letter_constant<'a>(
    front: &Sinumerik,
    words: &mut Words<'a>,
    letter: u8,
    value: f64,
    word: &'a Word,
) -> bool {
    let plain = AxisValue {
        value,
        absolute: None,
        diameter: None,
    };
    if let Some(axis) = front.axes.by_letter(letter) {
        words.axes[axis] = Some(plain);
        return true;
    }
    match letter {
        b'I' | b'J' | b'K' => words.centre[usize::from(letter - b'I')] = Some(plain),
        b'F' => words.feed = Some((value, word.span)),
        b'G' => {
            let common = (value.fract() == 0.0 && (0.0..100.0).contains(&value))
                .then(|| gcodes::common(value as u32))
                .flatten();
            let Some((function, group)) = common else {
                return false;
            };
            words.functions.push((function, Some(group), word));
        }
        _ => return false,
    }
    true
}

/// The G function a word is (`G1`, or a named one: `CIP`, `SOFT`) and its group; None for
/// other words.
fn gcodes_word(front: &Sinumerik, word: &Word) -> Result<Option<(Function, Option<u8>)>, Alarm> {
    let name: std::borrow::Cow<'_, str> = match (&*word.address, &word.value) {
        ("G", Value::Constant(n)) => {
            if n.value.fract() != 0.0 || n.value < 0.0 {
                return Err(Alarm::error(
                    AlarmCode::UnknownGCode,
                    word.span,
                    format!("G{} is not a G function", n.value),
                ));
            }
            let number = n.value as u32;
            if let Some((function, group)) = gcodes::common(number) {
                return Ok(Some((function, Some(group))));
            }
            format!("G{number}").into()
        }
        (name, Value::Bare) => name.into(),
        _ => return Ok(None),
    };
    let function = gcodes::function(&name, front.is_828d());
    match function {
        Some(Function::Planned) => Err(Alarm::error(
            AlarmCode::NotSupportedYet,
            word.span,
            format!("{name} is not run yet (planned: issue 22, SINUMERIK path control, compensation and working area)"),
        )),
        Some(Function::IsoMode) => Ok(Some((Function::IsoMode, gcodes::group(&name)))),
        Some(Function::OutOfProduct(what)) => Err(Alarm::error(
            AlarmCode::NotInProduct,
            word.span,
            format!("{name} belongs to {what}, which vcnc does not simulate"),
        )),
        Some(f) => Ok(Some((f, gcodes::group(&name)))),
        None if word.address.as_ref() == "G" => Err(Alarm::error(
            AlarmCode::UnknownGCode,
            word.span,
            format!("{name} is not a G function of the SINUMERIK"),
        )),
        None => Ok(None),
    }
}

/// Applies a modal G function.
pub(super) fn apply_modal(
    front: &mut Sinumerik,
    kernel: &mut Kernel,
    function: Function,
    _span: Span,
) -> Result<(), Alarm> {
    match function {
        Function::Motion(motion) => front.modal.motion = motion,
        Function::Plane(plane) => {
            if plane != front.modal.plane {
                front.flush_contour(kernel)?;
                front.polar.plane_changed();
                front.tangent = None;
            }
            front.modal.plane = plane;
            kernel.set_plane(plane);
            // The lengths act along the new plane's axes (PGsl 5.6).
            tools::apply_length(front, kernel);
        }
        Function::Absolute(absolute) => front.modal.absolute = absolute,
        Function::Units { inch, feeds } => {
            front.modal.inch = inch;
            front.modal.inch_feeds = feeds;
        }
        Function::FeedType(feed_type) => {
            // G93/G94/G95 end G96/G961, keeping the speed (group 15; PGsl 6.3, L2254-2255).
            front.spindle.constant_rate = None;
            // A change of feed type leaves no feed in force (docs/SINUMERIK.md 4.1).
            if feed_type != front.modal.feed_type {
                front.modal.feed_type = feed_type;
                front.programmed_feed = None;
                kernel.set_feed_in(feed_mode(feed_type), None);
            }
        }
        Function::Settable(n) => {
            front.modal.settable = n;
            kernel.select_work_offset(settable_id(n, front.is_828d()));
        }
        Function::Radius(function) => super::compensation::select(front, function),
        Function::ExactStop => front.modal.exact_stop = true,
        Function::ContinuousPath(rounding) => {
            front.modal.exact_stop = false;
            front.modal.path_control.rounding = rounding;
        }
        Function::CuttingRate(constant, feed_type) => {
            apply_modal(front, kernel, Function::FeedType(feed_type), _span)?;
            front.spindle.constant_rate = constant.then_some(feed_mode(feed_type));
        }
        Function::Diameter(command) => super::diameter::apply(front, command, _span)?,
        Function::Frame(_)
        | Function::Pole(_)
        | Function::SpeedLimit(_)
        | Function::IsoMode
        | Function::State
        | Function::OneBlock(_)
        | Function::Planned
        | Function::OutOfProduct(_) => {}
    }
    Ok(())
}

/// The machine file's work offset of settable frame `n` (`$P_UIFR[n]`): G54..G57 are its
/// `G54`..`G57`; the 828D's G58 and G59 its `G58` and `G59`; G500 and G505.. its `G500`, `G505`...
pub(super) fn settable_id(n: u32, m828d: bool) -> WorkOffsetId {
    match n {
        1..=4 => WorkOffsetId::Standard(n as u8),
        5 | 6 if m828d => WorkOffsetId::Standard(n as u8),
        n => WorkOffsetId::Settable(n),
    }
}

pub(super) fn feed_mode(feed_type: FeedType) -> FeedMode {
    match feed_type {
        FeedType::InverseTime => FeedMode::InverseTime,
        FeedType::PerMinute => FeedMode::PerMinute,
        FeedType::PerRevolution => FeedMode::PerRevolution,
    }
}

/// M functions other than the spindle's, the tool change and the ends: coolant and the machine's
/// own, output before the motion; M0 and M1 come after it.
fn auxiliary(kernel: &mut Kernel, code: u32, origin: Origin) {
    let kind = match code {
        3 | 4 | 5 | 19 | 6 | 0 | 1 => return,
        7 | 8 => SegmentKind::Coolant { on: true },
        9 => SegmentKind::Coolant { on: false },
        code => SegmentKind::Auxiliary { code },
    };
    kernel.event(kind, origin);
}

fn stop_kind(code: u32) -> Option<StopKind> {
    match code {
        0 => Some(StopKind::Program),
        1 => Some(StopKind::Optional),
        _ => None,
    }
}

/// G4: F seconds or S spindle revolutions.
fn dwell_block(kernel: &mut Kernel, words: &Words<'_>, origin: Origin) -> Result<(), Alarm> {
    let seconds = match (words.feed, words.speed) {
        (Some((f, _)), None) => f,
        (None, Some((s, span))) => {
            let rpm = kernel.state().spindle.speed();
            if rpm <= 0.0 {
                return Err(Alarm::error(
                    AlarmCode::BadDwell,
                    span,
                    "a dwell in revolutions (G4 S) needs the spindle's speed",
                ));
            }
            s * 60.0 / rpm
        }
        _ => {
            return Err(Alarm::error(
                AlarmCode::BadDwell,
                origin.span,
                "G4 takes either F (seconds) or S (revolutions)",
            ))
        }
    };
    kernel.dwell(seconds, origin)
}

/// An axis or centre word's value, with `AC(..)` or `IC(..)` when written so.
fn axis_value(front: &mut Sinumerik, kernel: &Kernel, word: &Word) -> Result<AxisValue, Alarm> {
    if let Value::Expression(Expr {
        kind: ExprKind::Call(name, args),
        ..
    }) = &word.value
    {
        if let Some((absolute, diameter)) = super::diameter::value_form(name) {
            let [Some(arg)] = args.as_slice() else {
                return Err(Alarm::error(
                    AlarmCode::MacroSyntax,
                    word.span,
                    format!("{name}(..) takes one value"),
                ));
            };
            return Ok(AxisValue {
                value: front.value(kernel, arg)?,
                absolute: Some(absolute),
                diameter,
            });
        }
    }
    Ok(AxisValue {
        value: number(front, kernel, word)?,
        absolute: None,
        diameter: None,
    })
}

/// A word's value as a number.
pub(super) fn number(front: &mut Sinumerik, kernel: &Kernel, word: &Word) -> Result<f64, Alarm> {
    match &word.value {
        Value::Constant(n) => Ok(n.value),
        Value::Expression(expr) => match literal(expr).or_else(|| variable(front, expr)) {
            Some(value) => Ok(value),
            None => front.value(kernel, expr),
        },
        _ => Err(Alarm::error(
            AlarmCode::MissingValue,
            word.span,
            format!("{} needs a value", word.address),
        )),
    }
}

/// The value of an expression that is a number or a negated number (`CR=5`, `CR=-11.7`), as
/// the evaluator gives it, without the evaluator: a whole number is an INT there, so -0 is 0.
fn literal(expr: &Expr) -> Option<f64> {
    let value = match &expr.kind {
        ExprKind::Number(x) => *x + 0.0,
        ExprKind::Unary(UnaryOp::Minus, operand) => match operand.kind {
            ExprKind::Number(x) => 0.0 - x,
            _ => return None,
        },
        _ => return None,
    };
    value.is_finite().then_some(value)
}

/// The value of an expression that is the name of a number variable the program defined
/// (`F=FEED1`), as the evaluator gives it, with one look-up; None for anything else (the
/// evaluator's constants TRUE, FALSE and `$` names first).
fn variable(front: &Sinumerik, expr: &Expr) -> Option<f64> {
    let ExprKind::Name(name) = &expr.kind else {
        return None;
    };
    if matches!(&**name, "TRUE" | "FALSE") || name.starts_with('$') {
        return None;
    }
    front.vars.scalar(name)?.as_f64()
}

/// A word's value as a whole number (M, D, P, L).
pub(super) fn whole(front: &mut Sinumerik, kernel: &Kernel, word: &Word) -> Result<u32, Alarm> {
    let value = number(front, kernel, word)?;
    if value.fract() != 0.0 || !(0.0..=f64::from(u32::MAX)).contains(&value) {
        return Err(Alarm::error(
            AlarmCode::ValueOutOfRange,
            word.span,
            format!("{} takes a whole number, not {value}", word.address),
        ));
    }
    Ok(value as u32)
}

/// T by number, or `T="name"` from the machine's tool table.
fn tool_number(
    front: &mut Sinumerik,
    kernel: &Kernel,
    word: &Word,
    warnings: &mut Vec<Alarm>,
) -> Result<u32, Alarm> {
    if let Value::Expression(Expr {
        kind: ExprKind::Text(name),
        ..
    }) = &word.value
    {
        let known = front.tools.iter().find(|e| {
            e.name
                .as_deref()
                .is_some_and(|n| n.eq_ignore_ascii_case(name))
        });
        if let Some(edge) = known {
            return Ok(edge.t);
        }
        // A tool the machine file does not list runs without offsets, as a T number without
        // registers does on the ISO side; said once per name (the control itself would refuse
        // a tool its magazine lacks, but the machine file is rarely the whole magazine).
        let upper = name.to_ascii_uppercase();
        let count = front.unknown_tools.len() as u32;
        let number = *front.unknown_tools.entry(upper).or_insert_with(|| {
            warnings.push(
                Alarm::warning(
                    AlarmCode::OffsetNumberOutOfRange,
                    word.span,
                    format!("the tool table has no tool named \"{name}\": it runs without length or radius"),
                )
                .with_help("add the tool to the machine file's [[tools]] with its name, edges and lengths"),
            );
            UNLISTED_TOOLS + count
        });
        return Ok(number);
    }
    whole(front, kernel, word)
}
