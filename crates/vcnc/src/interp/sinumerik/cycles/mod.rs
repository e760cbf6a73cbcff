//! SINUMERIK's standard cycles (CYCLE81 ... CYCLE89, CYCLE840, HOLES1, HOLES2, CYCLE801,
//! CYCLE802, POCKET3, POCKET4, SLOT1, SLOT2, LONGHOLE, CYCLE61, CYCLE71, CYCLE72, CYCLE76,
//! CYCLE77, CYCLE79, CYCLE800, and CYCLE832, the high-speed settings, in `high_speed.rs`)
//! built into the front end: called by name like a subprogram, directly or through MCALL, when
//! neither the program's directory nor `--lib` has a program of that name (a machine's own
//! cycle wins).
//!
//! A block's call is kept by [`Calls::call`] and run at the block's end by [`run_called`]: the
//! cycle reads its parameters (`params.rs`), checks them (the cycle's own alarm 61xxx as
//! `AlarmCode::CycleParameter`) and makes its moves (`place.rs`) as ordinary rapids, lines,
//! arcs and threads through the kernel, so the planner times them. A drilling cycle drills
//! where it is called: the programmed position in the plane in force (G17: X Y, along Z). The
//! cycles by kind: `drilling.rs`, `patterns.rs`, `pockets.rs` (with `rings.rs`, the closed
//! paths that clear a level), `slots.rs`, `facing.rs`, `spigots.rs`, `multi_edge.rs`, path
//! milling along a named contour (`contour_milling.rs`, `named_contour.rs`), and the swivel
//! CYCLE800 (`swivel.rs`).
//!
//! The parameter lists are the cycles manual's; the meanings vcnc had to infer are marked so
//! here and in docs/SINUMERIK.md ("Standard cycles").
//!
//! Never: move an axis outside the plane and its tool axis, or leave the programmed position
//! behind the machine's (the next block continues from where the cycle ends).

mod contour_milling;
mod drilling;
mod facing;
mod high_speed;
mod multi_edge;
mod named_contour;
mod params;
mod patterns;
mod place;
mod pockets;
mod rings;
mod slots;
mod spigots;
mod swivel;

use params::{alarm, machining_type, too_many, Levels, Params};
use place::Place;

use super::language::Argument;
use super::Sinumerik;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::kernel::Kernel;
use crate::source::Span;
use std::collections::HashSet;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

/// The cycles vcnc runs itself.
const BUILT_IN: [&str; 27] = [
    "CYCLE81", "CYCLE82", "CYCLE83", "CYCLE84", "CYCLE840", "CYCLE85", "CYCLE86", "CYCLE87",
    "CYCLE88", "CYCLE89", "HOLES1", "HOLES2", "CYCLE801", "CYCLE802", "POCKET3", "POCKET4",
    "SLOT1", "SLOT2", "LONGHOLE", "CYCLE61", "CYCLE71", "CYCLE76", "CYCLE77", "CYCLE800",
    "CYCLE832", "CYCLE79", "CYCLE72",
];

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
    /// The moves the call being run has made, its passes together ([`MAX_MOVES`]): shared
    /// with each [`Place`] the cycle makes its moves from.
    moves: Arc<AtomicU64>,
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
#[inline]
pub(super) fn run_called(front: &mut Sinumerik, kernel: &mut Kernel) -> Result<(), Alarm> {
    // The common block: no cycle called, no pattern going on.
    if front.cycles.waiting.is_none() && front.cycles.pattern.is_none() {
        return Ok(());
    }
    run_waiting(front, kernel)
}

/// [`run_called`] with a cycle called or a pattern going on.
// Out of line: the check before it is inlined into every block's step.
#[inline(never)]
fn run_waiting(front: &mut Sinumerik, kernel: &mut Kernel) -> Result<(), Alarm> {
    let Some(call) = front.cycles.waiting.take() else {
        return resume_pattern(front, kernel);
    };
    // A chamfer or rounding waiting for the next block is made first: the cycle's moves follow.
    front.flush_contour(kernel)?;
    front.cycles.moves.store(0, Ordering::Relaxed);
    for _ in 0..call.passes {
        run(front, kernel, &call)?;
    }
    Ok(())
}

/// Runs cycle `call` once at the programmed position.
fn run(front: &mut Sinumerik, kernel: &mut Kernel, call: &Call) -> Result<(), Alarm> {
    // The cycles move the tool's centre (and CYCLE72 compensates by its own RL): vcnc runs them
    // with G40, as their documentation programs them (a choice: docs/SINUMERIK.md 12).
    if call.name != "CYCLE832" && front.radius_compensation.is_selected() {
        return Err(Alarm::error(
            AlarmCode::CutterCompensation,
            call.span,
            format!(
                "{} is not run under G41 or G42: the standard cycles move the tool's centre",
                call.name
            ),
        )
        .with_help("cancel the radius compensation with G40 before the cycle call"));
    }
    let params = Params::read(front, call)?;
    let saved_feed = kernel.feed_setting();
    let result = match call.name.as_str() {
        "CYCLE832" => high_speed::settings(front, &params),
        "HOLES1" | "HOLES2" | "CYCLE801" | "CYCLE802" => {
            let from = Place::new(front, kernel).in_plane();
            patterns::positions(&call.name, &params, from)
                .and_then(|positions| patterns::visit(front, kernel, &positions))
        }
        "CYCLE800" => swivel::run(front, kernel, &params),
        "CYCLE72" => contour_milling::run(front, kernel, &params),
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
        "CYCLE79" => multi_edge::multi_edge(&mut at, kernel, params, radius),
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

/// The most pieces (levels, rings, rows, pecks, holes, slots) one cycle divides its work into:
/// vcnc's limit, no control's, so that a step written far too small cannot make a cycle run
/// for ever (levels, rings and rows then grow beyond their step; holes and slots alarm).
pub(super) const MAX_DIVISIONS: usize = 10_000;

/// The most moves one cycle call makes, its passes (`P`) together, before it stops with an
/// alarm (vcnc's limit).
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
