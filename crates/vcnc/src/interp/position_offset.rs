//! G45/G46/G47/G48 tool position offset (spec iso-syntec-milling.md 1.27, issue #5): in its own
//! block only, every axis with a word travels farther (G45, G47) or shorter (G46, G48) by one or
//! two times the value of offset D, in its direction of travel. The old way to mill a contour
//! with a tool of any radius before G41/G42.

use super::decode::Command;
use super::modal::DistanceMode;
use super::tools::ToolMemory;
use crate::alarm::{Alarm, AlarmCode};
use crate::machine::AXES;
use crate::profile::{GCode, Group};
use crate::source::Span;

/// The factor of the block's G45 (+1), G46 (-1), G47 (+2) or G48 (-2), with its span.
pub(crate) fn factor(cmd: &Command) -> Option<(f64, Span)> {
    match cmd.group(Group::NonModal) {
        Some(g) => match g.code {
            GCode::PositionOffset(k) => Some((f64::from(k), g.span)),
            _ => None,
        },
        None => None,
    }
}

/// Moves the block's target (program coordinates, from `start`) by `k` times the offset along
/// each named axis's travel. An axis word that does not move the axis takes its direction from
/// its sign in G91 (`Y0` forward, `Y-0` back) and gets no offset in G90 (spec 1.27 table).
///
/// # Errors
/// G45-G48 while cutter compensation is on (Syntec COR-082).
pub(crate) fn apply(
    tools: &ToolMemory,
    distance: DistanceMode,
    cmd: &Command,
    (k, span): (f64, Span),
    compensating: bool,
    start: &[f64; AXES],
    target: &mut [f64; AXES],
) -> Result<(), Alarm> {
    if compensating {
        return Err(Alarm::error(
            AlarmCode::PositionOffset,
            span,
            "G45-G48 cannot be used while cutter compensation (G41/G42) is on",
        )
        .with_help("cancel it with G40 first (Syntec alarm COR-082)"));
    }
    // The offset value: offset D's radius register as it stands.
    let d = tools.radius_offset();
    let incremental = distance == DistanceMode::Incremental;
    for axis in cmd.axes_present() {
        let i = axis.index();
        let Some(word) = cmd.axis(i) else { continue };
        let travel = target[i] - start[i];
        let direction = if travel != 0.0 {
            travel.signum()
        } else if incremental {
            if word.number.negative {
                -1.0
            } else {
                1.0
            }
        } else {
            0.0
        };
        target[i] += k * d * direction;
    }
    Ok(())
}

/// The arc's centre offsets (first and second plane axis) under G45-G48: a component that is
/// not zero grows by `k` times the offset in its own direction, so the radius changes by that
/// much (spec 1.27, example 38: `G45 G03 X30. Y30. J30.` is an arc of radius 30 + d).
pub(crate) fn centre(tools: &ToolMemory, (k, _): (f64, Span), offset: (f64, f64)) -> (f64, f64) {
    let d = k * tools.radius_offset();
    let grow = |c: f64| if c == 0.0 { 0.0 } else { c + d * c.signum() };
    (grow(offset.0), grow(offset.1))
}

/// Only quarter and three-quarter arcs can be offset: their start and end radii are at right
/// angles (plane coordinates).
///
/// # Errors
/// Any other arc (Syntec COR-081).
pub(crate) fn check_quarter(
    (_, span): (f64, Span),
    start: (f64, f64),
    end: (f64, f64),
    centre: (f64, f64),
) -> Result<(), Alarm> {
    let (u, v) = (
        (start.0 - centre.0, start.1 - centre.1),
        (end.0 - centre.0, end.1 - centre.1),
    );
    let cos = (u.0 * v.0 + u.1 * v.1) / (u.0.hypot(u.1) * v.0.hypot(v.1));
    if cos.abs() < 1e-6 {
        return Ok(());
    }
    Err(Alarm::error(
        AlarmCode::PositionOffset,
        span,
        "under G45-G48 an arc must be a quarter or three quarters of a circle",
    )
    .with_help("Syntec alarm COR-081"))
}

/// The refusal of a G45-G48 arc given by R.
pub(crate) fn radius_refused((_, span): (f64, Span)) -> Alarm {
    Alarm::error(
        AlarmCode::PositionOffset,
        span,
        "under G45-G48 an arc's centre must be given by I J K, not R",
    )
    .with_help("Syntec alarm COR-081")
}
