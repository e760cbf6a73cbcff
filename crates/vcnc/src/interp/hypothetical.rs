//! G07 hypothetical axis interpolation (FANUC 0i/15i/16i, Mitsubishi M70/M700): `G07 α0` makes
//! the axis α hypothetical, `G07 α1` makes it real again. A hypothetical axis takes part in the
//! interpolation (the program, its arcs and the feed treat it as moving) but the machine's axis
//! does not move, so a helix with one of its circle's axes hypothetical moves the other circle
//! axis sinusoidally along the helix's linear axis: `G07 X0` then `G17 G03 X0 Y0 Z40. I-10.`
//! from X0 Y0 Z0 traces Y = 10 sin(2 pi Z / 40) with X standing. None of the three ISO manuals
//! has the code; vcnc follows the controls that do (docs/DEVIATIONS.md).
//!
//! How it sits in the pipeline:
//!
//! - The executor, its arcs and cutter compensation run as if every axis were real: the program
//!   position of a hypothetical axis moves as written.
//! - [`HypotheticalStage`] is the last stage of the output chain. Each released motion is cut
//!   into straight pieces (`pieces.rs`) whose machine position holds every hypothetical axis at
//!   the place it had when G07 made it so; the other axes follow the path within the profile's
//!   `polar_interpolation_tolerance`. Each piece gets the time its share of the programmed
//!   contour (hypothetical axis included) takes at F: "the feedrate is distributed as for an
//!   actual axis" (Mitsubishi M700V programming manual, 6.16 precaution 4).
//! - `G07 α1` puts the machine's own position of α back in the executor: the axis is real
//!   where it stands (Mitsubishi 6.16 precaution 7 for an axis that was real already; where a
//!   hypothetical axis ends up is not written: vcnc takes the place it never left).
//!
//! What it must never do: cost anything when the mode is off (the queue asks for the stage only
//! when it exists).

use super::decode::Command;
use super::exec::Executor;
use super::pieces::{PieceMap, PieceQueue};
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::machine::{Axis, AXES};
use crate::profile::GCode;
use crate::source::Span;

/// Whether `code` cannot start while an axis is hypothetical: the other transformations of
/// finished motion (their stages would come after this one, which must see machine motion
/// last), and the high-speed mode, which Mitsubishi wants G07 cancelled for (6.16 precaution 2).
fn refused_in_mode(code: GCode) -> bool {
    matches!(
        code,
        GCode::PolarInterpolation
            | GCode::CylindricalInterpolation
            | GCode::ToolCenterPoint
            | GCode::TiltedPlane
            | GCode::ToolAxisDirection
            | GCode::HighSpeedMode
    )
}

/// Before a block while an axis is hypothetical: refuses the codes that cannot start in the
/// mode.
///
/// # Errors
/// [`AlarmCode::WordNotAllowed`] for G12.1, G07.1, G43.4, G68.2, G53.1 or G05.
pub(crate) fn prepare(cmd: &Command, out: &Output) -> Result<(), Alarm> {
    if !out.hypothetical() {
        return Ok(());
    }
    match cmd.g_codes().find(|g| refused_in_mode(g.code)) {
        Some(g) => Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            g.span,
            format!(
                "{} cannot be commanded while an axis is hypothetical (G07)",
                g.code.description()
            ),
        )
        .with_help("make the axes real again first (G07 X1, for the axis named in G07 X0)")),
        None => Ok(()),
    }
}

/// G07 in a block: each axis word with 0 makes its axis hypothetical, with any other value real
/// again (Mitsubishi 6.16 detail 4; FANUC names 0 and 1 only).
///
/// # Errors
/// G07 without an axis word, with cutter compensation on, or while another transformation is
/// on.
pub(crate) fn g07(
    exec: &mut Executor,
    cmd: &Command,
    span: Span,
    out: &mut Output,
) -> Result<(), Alarm> {
    if !cmd.has_axis_words() {
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            span,
            "G07 names the axes it makes hypothetical (G07 X0) or real again (G07 X1)",
        ));
    }
    if out.compensating() || (out.has_stages() && !out.hypothetical()) {
        // A stage already on would put this one before it, or hold moves whose machine
        // position is not yet known (compensation).
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            span,
            "G07 cannot be commanded while cutter compensation or another interpolation mode (G12.1, G07.1, G43.4, G53.1) is on",
        )
        .with_help("cancel it first; cutter compensation may be started after G07"));
    }
    let mut frozen = out.frozen_axes().unwrap_or([None; AXES]);
    for (axis, value) in cmd.axis_words() {
        let i = axis.index();
        match (value.number.value == 0.0, frozen[i]) {
            // The axis stands where the machine has it now; already hypothetical, it stays so
            // (6.16 precaution 6).
            (true, None) => frozen[i] = Some(exec.kernel.position[i]),
            (true, Some(_)) => {}
            (false, Some(machine)) => {
                exec.kernel.position[i] = machine;
                frozen[i] = None;
            }
            // Already real: nothing to do (6.16 precaution 7).
            (false, None) => {}
        }
    }
    if frozen.iter().all(Option::is_none) {
        out.end_hypothetical();
        return Ok(());
    }
    let map = Frozen { axes: frozen };
    match out.hypothetical_mut() {
        Some(stage) => stage.pieces.map = map,
        None => out.start_hypothetical(HypotheticalStage {
            pieces: PieceQueue::new(map, exec.kernel.position, exec.kernel.setup.profile()),
        }),
    }
    Ok(())
}

/// The stage at the end of the output chain while an axis is hypothetical.
#[derive(Clone, Debug)]
pub(crate) struct HypotheticalStage {
    /// Items as the program moves every axis, and the map that holds the hypothetical ones.
    pub(crate) pieces: PieceQueue<Frozen>,
}

impl HypotheticalStage {
    /// The machine position of each hypothetical axis (`None` for a real one).
    pub(crate) fn frozen(&self) -> [Option<f64>; AXES] {
        self.pieces.map.axes
    }
}

/// The machine axes that do not move, each held at its machine position.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Frozen {
    axes: [Option<f64>; AXES],
}

impl PieceMap for Frozen {
    /// The programmed point with every hypothetical axis where the machine holds it.
    fn to_machine(
        &self,
        p: &[f64; AXES],
        _offset: &[f64; AXES],
        _previous: &[f64; AXES],
    ) -> [f64; AXES] {
        std::array::from_fn(|i| self.axes[i].unwrap_or(p[i]))
    }

    /// The distance of the real linear axes from the programmed point: the hypothetical ones
    /// are not on the path by design.
    fn deviation(&self, machine: &[f64; AXES], _offset: &[f64; AXES], p: &[f64; AXES]) -> f64 {
        Axis::ALL[..3]
            .iter()
            .map(|axis| axis.index())
            .filter(|&i| self.axes[i].is_none())
            .map(|i| (machine[i] - p[i]).powi(2))
            .sum::<f64>()
            .sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_refused_codes_start_other_transformations() {
        assert!(refused_in_mode(GCode::PolarInterpolation));
        assert!(!refused_in_mode(GCode::ArcClockwise));
        assert_eq!(
            GCode::HypotheticalAxis.group(),
            crate::profile::Group::NonModal
        );
    }

    #[test]
    fn a_frozen_axis_keeps_its_machine_place_and_leaves_the_deviation() {
        let mut axes = [None; AXES];
        axes[0] = Some(3.0);
        let map = Frozen { axes };
        let p = [7.0, 2.0, 1.0, 0.0, 0.0, 0.0];
        let machine = map.to_machine(&p, &[0.0; AXES], &[0.0; AXES]);
        assert_eq!(machine, [3.0, 2.0, 1.0, 0.0, 0.0, 0.0]);
        // Y off by 3, Z off by 4: 5 mm; X's 4 mm do not count.
        let off = [3.0, 5.0, 5.0, 0.0, 0.0, 0.0];
        assert!((map.deviation(&off, &[0.0; AXES], &p) - 5.0).abs() < 1e-12);
    }
}
