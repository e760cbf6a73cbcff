//! G51/G50 scaling and G51.1/G50.1 programmable mirror (spec iso-syntec-milling.md 1.28, 1.29).
//!
//! `G51 X_ Y_ Z_ P_` (or `I_ J_ K_`): the axes named are scaled about the centre their words give,
//! by P, or by I J K for X Y Z each. `G51.1 X_ Y_`: the axes named are mirrored about the
//! coordinate their words give (incremental from the current position in G91). Both live in the
//! coordinate chain (`mod.rs`) as one stretching of the programmed coordinates, applied before
//! a rotation; arcs take the larger factor of their plane for their radius and turn the other way
//! when one plane axis is reversed (`circular.rs`). Syntec refuses the two together (spec 1.28).

use super::{Frames, Scaling};
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::decode::Command;
use crate::interp::exec::Executor;
use crate::interp::modal::DistanceMode;
use crate::machine::AXES;
use crate::profile::{DecimalLess, Profile};

/// G51: scaling of the axes named.
///
/// # Errors
/// With the mirror on; without any factor; a factor of zero.
pub(crate) fn g51(exec: &mut Executor, cmd: &Command) -> Result<(), Alarm> {
    refuse_both(&exec.kernel.frames, cmd, false)?;
    let p = cmd
        .p()
        .map(|v| factor(exec.kernel.setup.profile(), v.number));
    let per_axis: [Option<f64>; 3] = std::array::from_fn(|i| {
        cmd.center(i)
            .map(|v| factor(exec.kernel.setup.profile(), v.number))
    });
    if p.is_none() && per_axis.iter().all(Option::is_none) {
        return Err(Alarm::error(
            AlarmCode::MissingValue,
            cmd.span,
            "G51 needs a scale factor: P for every axis named, or I J K for X Y Z",
        ));
    }
    exec.kernel.frames.set_scaling(None);
    let here = exec.kernel.program_position();
    let mut scaling = Scaling {
        center: here,
        factor: [1.0; AXES],
        mirror: false,
    };
    for axis in cmd.axes_present() {
        let i = axis.index();
        let Some(value) = cmd.axis(i) else { continue };
        scaling.center[i] = exec.axis_value(axis, &value);
        let f = p.or(per_axis.get(i).copied().flatten()).unwrap_or(1.0);
        if f == 0.0 {
            return Err(Alarm::error(
                AlarmCode::ValueOutOfRange,
                value.span,
                "a scale factor of zero would collapse the axis",
            ));
        }
        scaling.factor[i] = f;
    }
    exec.kernel.frames.set_scaling(Some(scaling));
    Ok(())
}

/// G51.1: mirror of the axes named, about the coordinates their words give.
///
/// # Errors
/// With scaling on.
pub(crate) fn g51_1(exec: &mut Executor, cmd: &Command) -> Result<(), Alarm> {
    refuse_both(&exec.kernel.frames, cmd, true)?;
    let previous = exec.kernel.frames.scaling().copied();
    exec.kernel.frames.set_scaling(None);
    let here = exec.kernel.program_position();
    let mut mirror = previous.unwrap_or(Scaling {
        center: here,
        factor: [1.0; AXES],
        mirror: true,
    });
    for axis in cmd.axes_present() {
        let i = axis.index();
        let Some(value) = cmd.axis(i) else { continue };
        let v = exec.axis_value(axis, &value);
        mirror.center[i] = match exec.modal.distance {
            DistanceMode::Absolute => v,
            DistanceMode::Incremental => here[i] + v,
        };
        mirror.factor[i] = -1.0;
    }
    exec.kernel.frames.set_scaling(Some(mirror));
    Ok(())
}

/// G50 (scaling off) or G50.1 (mirror off): only the one it names.
pub(crate) fn cancel(frames: &mut Frames, mirror: bool) {
    if frames.scaling().is_some_and(|s| s.mirror == mirror) {
        frames.set_scaling(None);
    }
}

/// Scaling and mirror cannot be on together (Syntec spec 1.28, 1.29).
fn refuse_both(frames: &Frames, cmd: &Command, mirror: bool) -> Result<(), Alarm> {
    match frames.scaling().copied() {
        Some(active) if active.mirror != mirror => Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            cmd.span,
            "scaling (G51) and the programmable mirror (G51.1) cannot be on together",
        )
        .with_help(if mirror {
            "cancel the scaling with G50 first"
        } else {
            "cancel the mirror with G50.1 first"
        })),
        _ => Ok(()),
    }
}

/// A scale factor as written: with a decimal point as is; without one in thousandths where the
/// profile reads numbers in least increments (FANUC's 0.001 unit), else as is.
fn factor(profile: &Profile, n: crate::syntax::Number) -> f64 {
    if !n.decimal_point && profile.units.decimal_less == DecimalLess::Increments {
        n.value * 0.001
    } else {
        n.value
    }
}
