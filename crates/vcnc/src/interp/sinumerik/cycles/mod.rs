//! SINUMERIK's standard cycles (CYCLE81 ... CYCLE89, CYCLE840, HOLES1, HOLES2, CYCLE801,
//! CYCLE802, POCKET3, POCKET4, ...) built into the front end: called by name like a
//! subprogram, directly or through MCALL, when neither the program's directory nor `--lib` has
//! a program of that name (a machine's own cycle wins).
//!
//! A block's call is kept by [`Calls::call`] and run at the block's end by [`run_called`]: the
//! cycle reads its parameters ([`Params`]), checks them (the cycle's own alarm 61xxx as
//! [`AlarmCode::CycleParameter`]) and makes its moves as ordinary rapids, lines and arcs through
//! the kernel, so the planner times them. The hole or pocket is where the cycle is called: the
//! programmed position in the plane in force (G17: X Y, drilling along Z).
//!
//! The parameter lists are the cycles manual's; the meanings vcnc had to infer are marked so
//! here and in docs/SINUMERIK.md ("Standard cycles").
//!
//! Never: move an axis outside the plane and its tool axis, or leave the programmed position
//! behind the machine's (the next block continues from where the cycle ends).

mod drilling;
mod facing;
mod patterns;
mod pockets;
mod rings;
mod slots;
mod spigots;

use super::language::Argument;
use super::motion::unit;
use super::Sinumerik;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::kernel::{Kernel, Origin};
use crate::machine::AXES;
use crate::motion::{ArcDirection, PathMode, Plane, SpindleState};
use crate::source::Span;
use std::collections::HashSet;

/// The cycles vcnc runs itself.
const BUILT_IN: [&str; 23] = [
    "CYCLE81", "CYCLE82", "CYCLE83", "CYCLE84", "CYCLE840", "CYCLE85", "CYCLE86", "CYCLE87",
    "CYCLE88", "CYCLE89", "HOLES1", "HOLES2", "CYCLE801", "CYCLE802", "POCKET3", "POCKET4",
    "SLOT1", "SLOT2", "LONGHOLE", "CYCLE61", "CYCLE71", "CYCLE76", "CYCLE77",
];

/// The most pieces (levels, rings, rows, pecks, holes, slots) one cycle divides its work into:
/// vcnc's limit, no control's, so that a step written far too small cannot make a cycle run
/// for ever (levels, rings and rows then grow beyond their step; holes and slots alarm).
pub(super) const MAX_DIVISIONS: usize = 10_000;

/// The most moves one cycle call makes before it stops with an alarm (vcnc's limit).
const MAX_MOVES: u64 = 2_000_000;

/// The number of equal pieces of at most `step` that `length` divides into: at least 1, at
/// most [`MAX_DIVISIONS`].
pub(super) fn divisions(length: f64, step: f64) -> usize {
    if step.is_nan() || step <= 0.0 {
        return 1;
    }
    (length.abs() / step - 1e-9)
        .ceil()
        .clamp(1.0, MAX_DIVISIONS as f64) as usize
}

/// Alarm V007 for a count of holes or slots beyond [`MAX_DIVISIONS`].
pub(super) fn too_many(p: &Params, count: f64, what: &str) -> Alarm {
    Alarm::error(
        AlarmCode::ValueOutOfRange,
        p.span,
        format!(
            "{}: {count} {what} is more than vcnc runs in one call ({MAX_DIVISIONS})",
            p.name()
        ),
    )
}

/// True when `name` is a standard cycle vcnc runs.
pub(super) fn runs(name: &str) -> bool {
    BUILT_IN.contains(&name)
}

/// A block's call of a standard cycle, waiting for the block's end.
#[derive(Clone, Debug)]
pub(super) struct Call {
    name: String,
    passes: u32,
    span: Span,
    arguments: Vec<Argument>,
}

/// The call waiting, the pattern waiting for a subprogram, and the cycle names found to be
/// built in (the library is asked once).
#[derive(Default)]
pub(super) struct Calls {
    waiting: Option<Call>,
    pattern: Option<Pattern>,
    built_in: HashSet<Box<str>>,
}

impl Calls {
    /// True when `name` was found to be a built-in cycle before.
    pub(super) fn is_built_in(&self, name: &str) -> bool {
        self.built_in.contains(name)
    }

    /// `name` is the built-in cycle from now on (the library has no program of that name).
    pub(super) fn remember_built_in(&mut self, name: &str) {
        self.built_in.insert(name.into());
    }

    /// Keeps the call of cycle `name` for the block's end.
    pub(super) fn call(
        &mut self,
        name: &str,
        passes: u32,
        span: Span,
        arguments: Option<Vec<Argument>>,
    ) -> Result<(), Alarm> {
        self.waiting = Some(Call {
            name: name.to_string(),
            passes,
            span,
            arguments: arguments.unwrap_or_default(),
        });
        Ok(())
    }
}

/// Runs the cycle the block called, if it called one, or goes on with a pattern whose
/// subprogram has returned.
pub(super) fn run_called(front: &mut Sinumerik, kernel: &mut Kernel) -> Result<(), Alarm> {
    let Some(call) = front.cycles.waiting.take() else {
        return resume_pattern(front, kernel);
    };
    // A chamfer or rounding waiting for the next block is made first: the cycle's moves follow.
    front.flush_contour(kernel)?;
    for _ in 0..call.passes {
        run(front, kernel, &call)?;
    }
    Ok(())
}

/// Runs cycle `call` once at the programmed position.
fn run(front: &mut Sinumerik, kernel: &mut Kernel, call: &Call) -> Result<(), Alarm> {
    let params = Params::read(front, call)?;
    let saved_feed = kernel.feed_setting();
    let result = match call.name.as_str() {
        "HOLES1" | "HOLES2" | "CYCLE801" | "CYCLE802" => {
            let from = Place::new(front, kernel).in_plane();
            patterns::positions(&call.name, &params, from)
                .and_then(|positions| patterns::visit(front, kernel, &positions))
        }
        _ => run_here(front, kernel, call, &params),
    };
    // The feed programmed before the call is in force again after it.
    kernel.set_feed_in(saved_feed.0, saved_feed.1);
    result
}

/// Runs a drilling or milling cycle where the tool is.
fn run_here(
    front: &mut Sinumerik,
    kernel: &mut Kernel,
    call: &Call,
    params: &Params,
) -> Result<(), Alarm> {
    let mut at = Place::new(front, kernel);
    let radius = edge_radius(front);
    let result = match call.name.as_str() {
        "CYCLE81" => drilling::centering(&mut at, kernel, params),
        "CYCLE82" => drilling::counterboring(&mut at, kernel, params),
        "CYCLE83" => drilling::deep_hole(&mut at, kernel, params),
        "CYCLE84" => drilling::rigid_tapping(&mut at, kernel, params),
        "CYCLE840" => drilling::floating_tapping(&mut at, kernel, params),
        "CYCLE85" => drilling::reaming(&mut at, kernel, params),
        "CYCLE86" => drilling::boring_oriented(&mut at, kernel, params),
        "CYCLE87" => drilling::boring_with_stop(&mut at, kernel, params, false),
        "CYCLE88" => drilling::boring_with_stop(&mut at, kernel, params, true),
        "CYCLE89" => drilling::boring_with_dwell(&mut at, kernel, params),
        "POCKET3" => pockets::rectangular(&mut at, kernel, params, radius),
        "POCKET4" => pockets::circular(&mut at, kernel, params, radius),
        "SLOT1" => slots::radial(&mut at, kernel, params, radius),
        "SLOT2" => slots::circumferential(&mut at, kernel, params, radius),
        "LONGHOLE" => slots::elongated(&mut at, kernel, params, radius),
        "CYCLE61" => facing::shopmill(&mut at, kernel, params, radius),
        "CYCLE71" => facing::classic(&mut at, kernel, params, radius),
        "CYCLE76" => spigots::rectangular(&mut at, kernel, params, radius),
        "CYCLE77" => spigots::circular(&mut at, kernel, params, radius),
        _ => unreachable!("BUILT_IN lists the cycles run_called runs"),
    };
    at.finish(front);
    result
}

/// What the modal call did at a pattern's position.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Modal {
    /// No modal call in force (the pattern only visits its positions).
    None,
    /// A standard cycle ran there.
    Ran,
    /// A subprogram was called: the pattern goes on when it returns.
    Called,
}

/// Runs the modal call (MCALL) of the current level, if any, at a position a pattern cycle
/// reached: a standard cycle at once, a subprogram by calling it.
pub(super) fn run_modal(front: &mut Sinumerik, kernel: &mut Kernel) -> Result<Modal, Alarm> {
    let Some(modal) = front
        .modal_call
        .as_ref()
        .filter(|c| c.depth == front.levels.len())
        .cloned()
    else {
        return Ok(Modal::None);
    };
    let is_program = front.programs.iter().any(|p| *p.name == *modal.name)
        || front.load(&modal.name, modal.span)?.is_some();
    if is_program {
        front.call(&modal.name, 1, modal.span, modal.arguments)?;
        return Ok(Modal::Called);
    }
    let call = Call {
        name: modal.name,
        passes: 1,
        span: modal.span,
        arguments: modal.arguments.unwrap_or_default(),
    };
    run(front, kernel, &call)?;
    Ok(Modal::Ran)
}

/// A pattern waiting for the subprogram its modal call called at one of its positions.
#[derive(Clone, Debug)]
pub(super) struct Pattern {
    /// The positions still to visit.
    rest: Vec<(f64, f64)>,
    /// The call stack's depth of the pattern's program.
    depth: usize,
}

/// Goes on with the pattern waiting for a subprogram, once the subprogram has returned.
fn resume_pattern(front: &mut Sinumerik, kernel: &mut Kernel) -> Result<(), Alarm> {
    let Some(depth) = front.cycles.pattern.as_ref().map(|p| p.depth) else {
        return Ok(());
    };
    if front.levels.len() > depth {
        return Ok(());
    }
    let pattern = front.cycles.pattern.take().expect("checked above");
    // A program that left the pattern's level another way (M30 in the subprogram) ends it.
    if front.levels.len() < depth {
        return Ok(());
    }
    let saved_feed = kernel.feed_setting();
    let result = patterns::visit(front, kernel, &pattern.rest);
    kernel.set_feed_in(saved_feed.0, saved_feed.1);
    result
}

/// The radius of the edge in force, for the milling cycles (None without a tool or with D0).
fn edge_radius(front: &Sinumerik) -> Option<f64> {
    front.edge().map(|edge| edge.radius)
}

/// A cycle's alarm: the control's number first, then what is wrong.
pub(super) fn alarm(number: u32, span: Span, message: impl std::fmt::Display) -> Alarm {
    Alarm::error(
        AlarmCode::CycleParameter,
        span,
        format!("cycle alarm {number}: {message}"),
    )
}

/// Alarm 61002 "machining type defined incorrectly" for VARI `vari`, with the values the cycle
/// takes.
pub(super) fn machining_type(p: &Params, vari: i64, values: &str) -> Alarm {
    alarm(
        61002,
        p.span,
        format_args!(
            "{}: machining type defined incorrectly: VARI {vari}",
            p.name()
        ),
    )
    .with_help(format!("VARI: {values}"))
}

/// A cycle's parameters as numbers, by position (0-based), lengths in mm.
pub(super) struct Params {
    name: String,
    values: Vec<Option<f64>>,
    /// The factor of lengths: 25.4 under G70/G700.
    unit: f64,
    /// The call's span: where a cycle's alarm points.
    pub(super) span: Span,
}

impl Params {
    /// The arguments of `call`, each a number or left out.
    fn read(front: &mut Sinumerik, call: &Call) -> Result<Params, Alarm> {
        let mut values = Vec::with_capacity(call.arguments.len());
        for argument in &call.arguments {
            let value = match argument {
                Argument::Omitted => None,
                Argument::Value(value) => value.as_f64(),
                Argument::Place(place) => front.vars.get(place, call.span)?.as_f64(),
            };
            values.push(value);
        }
        Ok(Params {
            name: call.name.clone(),
            values,
            unit: unit(front),
            span: call.span,
        })
    }

    /// Parameter `index` as written, if given.
    pub(super) fn number(&self, index: usize) -> Option<f64> {
        self.values.get(index).copied().flatten()
    }

    /// Parameter `index`, 0 when left out (the cycles' default for a number).
    pub(super) fn or_zero(&self, index: usize) -> f64 {
        self.number(index).unwrap_or(0.0)
    }

    /// Parameter `index` as a length in mm.
    pub(super) fn length(&self, index: usize) -> Option<f64> {
        self.number(index).map(|v| v * self.unit)
    }

    /// Parameter `index` as a length in mm, 0 when left out.
    pub(super) fn length_or_zero(&self, index: usize) -> f64 {
        self.length(index).unwrap_or(0.0)
    }

    /// The cycle's name, for messages.
    pub(super) fn name(&self) -> &str {
        &self.name
    }
}

/// Where a cycle works: the plane, the tool's position in program coordinates as the cycle
/// moves it, and the block its moves belong to.
pub(super) struct Place {
    /// The plane's first and second axes and the tool axis (G17: X, Y, Z).
    pub(super) axes: (usize, usize, usize),
    pub(super) plane: Plane,
    /// The position in program coordinates.
    position: [f64; AXES],
    pub(super) origin: Origin,
    /// Whether the spindle turns clockwise (M3) when the cycle starts: climb milling depends
    /// on it.
    pub(super) clockwise: bool,
    /// The path mode of the block (G60 or continuous), restored after a tapping move.
    pub(super) path_mode: PathMode,
    /// The moves made so far (at most [`MAX_MOVES`]).
    moves: u64,
}

impl Place {
    pub(super) fn new(front: &Sinumerik, kernel: &Kernel) -> Place {
        let plane = front.modal.plane;
        Place {
            axes: plane.axes(),
            plane,
            position: front.programmed,
            // The moves belong to the block that runs the cycle (the positioning block of a
            // modal call); alarms point at the call.
            origin: Origin::at(front.last_span),
            clockwise: kernel.state().spindle.state() != SpindleState::CounterClockwise,
            path_mode: if front.modal.exact_stop {
                PathMode::ExactStop
            } else {
                PathMode::Continuous
            },
            moves: 0,
        }
    }

    /// The position in the plane (abscissa, ordinate).
    pub(super) fn in_plane(&self) -> (f64, f64) {
        (self.position[self.axes.0], self.position[self.axes.1])
    }

    /// The position along the tool axis.
    pub(super) fn height(&self) -> f64 {
        self.position[self.axes.2]
    }

    /// The target of a move to `point` in the plane and `height` on the tool axis (each
    /// None: stays); an alarm past [`MAX_MOVES`].
    fn target(
        &mut self,
        point: Option<(f64, f64)>,
        height: Option<f64>,
    ) -> Result<[Option<f64>; AXES], Alarm> {
        self.moves += 1;
        if self.moves > MAX_MOVES {
            return Err(Alarm::error(
                AlarmCode::MacroLimit,
                self.origin.span,
                format!("the cycle makes more than {MAX_MOVES} moves"),
            )
            .with_help("check the cycle's steps (MID, MIDA, DXY, DP1): one is far too small"));
        }
        let (a, b, n) = self.axes;
        if let Some((x, y)) = point {
            self.position[a] = x;
            self.position[b] = y;
        }
        if let Some(h) = height {
            self.position[n] = h;
        }
        let mut target = [None; AXES];
        for i in [a, b, n] {
            target[i] = Some(self.position[i]);
        }
        Ok(target)
    }

    /// A rapid along the tool axis to `height`.
    pub(super) fn rapid_height(&mut self, kernel: &mut Kernel, height: f64) -> Result<(), Alarm> {
        let target = self.target(None, Some(height))?;
        kernel.rapid_to(target, self.origin)
    }

    /// A cutting line along the tool axis to `height` at the feed in force.
    pub(super) fn feed_height(&mut self, kernel: &mut Kernel, height: f64) -> Result<(), Alarm> {
        let target = self.target(None, Some(height))?;
        kernel.feed_to(target, self.origin)
    }

    /// A rapid in the plane to `point`.
    pub(super) fn rapid_plane(
        &mut self,
        kernel: &mut Kernel,
        point: (f64, f64),
    ) -> Result<(), Alarm> {
        let target = self.target(Some(point), None)?;
        kernel.rapid_to(target, self.origin)
    }

    /// A cutting line to `point` in the plane and `height` (None: stays) at the feed in force.
    pub(super) fn feed_to(
        &mut self,
        kernel: &mut Kernel,
        point: (f64, f64),
        height: Option<f64>,
    ) -> Result<(), Alarm> {
        let target = self.target(Some(point), height)?;
        kernel.feed_to(target, self.origin)
    }

    /// An arc in the plane to `point` about `centre` (a helix when `height` changes; `turns`
    /// full turns beyond the first when the end is the start) at the feed in force.
    pub(super) fn arc_to(
        &mut self,
        kernel: &mut Kernel,
        point: (f64, f64),
        centre: (f64, f64),
        clockwise: bool,
        height: Option<f64>,
        turns: u32,
    ) -> Result<(), Alarm> {
        let direction = if clockwise {
            ArcDirection::Clockwise
        } else {
            ArcDirection::CounterClockwise
        };
        let target = self.target(Some(point), height)?;
        kernel.arc_in(self.plane, target, centre, direction, turns, self.origin)
    }

    /// A thread along the tool axis to `height`, `lead` mm per revolution.
    pub(super) fn thread_height(
        &mut self,
        kernel: &mut Kernel,
        height: f64,
        lead: f64,
    ) -> Result<(), Alarm> {
        let target = self.target(None, Some(height))?;
        kernel.thread_to(target, lead, self.origin)
    }

    /// The programmed position becomes where the cycle left the tool.
    pub(super) fn finish(self, front: &mut Sinumerik) {
        let (a, b, n) = self.axes;
        for i in [a, b, n] {
            front.programmed[i] = self.position[i];
        }
    }
}

/// The planes of a drilling cycle along the tool axis: the retraction plane (RTP), the
/// reference plane (RFP), the safety clearance above it (SDIS) and the final depth (DP, or
/// DPR below the reference plane), read from the first five parameters every drilling and
/// milling cycle shares.
#[derive(Clone, Copy, Debug)]
pub(super) struct Levels {
    pub(super) retraction: f64,
    pub(super) reference: f64,
    /// The reference plane brought forward by the safety clearance.
    pub(super) safety: f64,
    pub(super) depth: f64,
}

impl Levels {
    /// RTP, RFP, SDIS, DP, DPR at `first..first + 5` (DPR at `relative`, when the cycle has
    /// one).
    ///
    /// The cycles manual: a relative depth DPR, when given, wins over DP. **Inferred**: the
    /// cycles drill toward the tool axis' negative side (G17: -Z), and alarm 61101 "reference
    /// plane defined incorrectly" stands for a depth not below the reference plane and for a
    /// retraction plane below it.
    pub(super) fn read(params: &Params, relative: Option<usize>) -> Result<Levels, Alarm> {
        let retraction = params.length_or_zero(0);
        let reference = params.length_or_zero(1);
        let clearance = params.length_or_zero(2).abs();
        let depth = match relative.and_then(|i| params.length(i)) {
            Some(below) if below != 0.0 => reference - below.abs(),
            _ => params.length_or_zero(3),
        };
        if depth >= reference {
            return Err(alarm(
                61101,
                params.span,
                format_args!(
                    "{}: reference plane defined incorrectly: the depth {depth} is not below the reference plane {reference}",
                    params.name()
                ),
            )
            .with_help("give the final depth below the reference plane (DP), or the depth below it (DPR)"));
        }
        if retraction < reference {
            return Err(alarm(
                61101,
                params.span,
                format_args!(
                    "{}: reference plane defined incorrectly: the retraction plane {retraction} is below the reference plane {reference}",
                    params.name()
                ),
            )
            .with_help("the retraction plane (RTP, the first parameter) must be at or above the reference plane (RFP, the second)"));
        }
        Ok(Levels {
            retraction,
            reference,
            safety: reference + clearance,
            depth,
        })
    }
}
