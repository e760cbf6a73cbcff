//! G51/G50 scaling and G51.1/G50.1 programmable mirror (spec iso-syntec-milling.md 1.28, 1.29).
//!
//! `G51 X_ Y_ Z_ P_` (or `I_ J_ K_`): the axes scaled (the profile's `scaling_axes`: those named,
//! or X Y Z) are scaled about the centre their words give (the current position for an axis not
//! named), by P, or by I J K for X Y Z each. `G51.1 X_ Y_`: the axes named are mirrored about the
//! coordinate their words give (incremental from the current position in G91). Both live in the
//! coordinate chain (`mod.rs`) as one stretching of the programmed coordinates, applied before
//! a rotation; arcs take the larger factor of their plane for their radius and turn the other way
//! when one plane axis is reversed (`circular.rs`). Syntec refuses the two together (spec 1.28);
//! a FANUC combines them, the mirror first and the scaling's centre mirrored with the program
//! (`scaling_with_mirror`): the same as scaling about the centre as written, then mirroring.

use super::Scaling;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::decode::Command;
use crate::interp::exec::Executor;
use crate::interp::modal::DistanceMode;
use crate::machine::{Axis, AXES};
use crate::profile::{DecimalLess, Profile, ScalingAxes};
use crate::source::Span;

/// G51 and G51.1 as the program set them; the chain holds their composition.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct ScalingState {
    /// G51's centre and factors.
    scale: Option<Scaling>,
    /// G51.1's centre and the axes it mirrors (factor -1).
    mirror: Option<Scaling>,
}

impl ScalingState {
    /// G51 is on.
    pub(crate) fn scaling_on(&self) -> bool {
        self.scale.is_some()
    }

    /// G51.1 is on.
    pub(crate) fn mirror_on(&self) -> bool {
        self.mirror.is_some()
    }
}

/// G51: scaling of the axes named.
///
/// # Errors
/// With the mirror on, where the profile refuses the two together; without any factor; a factor
/// of zero.
pub(crate) fn g51(exec: &mut Executor, cmd: &Command) -> Result<(), Alarm> {
    refuse_both(exec, cmd, false)?;
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
    // The centre of an axis not named is the current position without the old scaling.
    exec.scaling.scale = None;
    compose(exec, cmd.span)?;
    let here = exec.kernel.program_position();
    let mut scaling = Scaling {
        center: here,
        factor: [1.0; AXES],
    };
    let basic = exec.kernel.setup.profile().coordinates.scaling_axes == ScalingAxes::BasicAxes;
    let factor_of = |i: usize| p.or(per_axis.get(i).copied().flatten()).unwrap_or(1.0);
    for axis in cmd.axes_present() {
        let i = axis.index();
        let Some(value) = cmd.axis(i) else { continue };
        scaling.center[i] = exec.axis_value(axis, &value);
        let f = factor_of(i);
        refuse_zero(f, value.span)?;
        scaling.factor[i] = f;
    }
    if basic {
        // X Y Z whether named or not; an axis not named keeps the current position as its
        // centre (a FANUC; Haas says so of its G51).
        for axis in [Axis::X, Axis::Y, Axis::Z] {
            let f = factor_of(axis.index());
            refuse_zero(f, cmd.span)?;
            scaling.factor[axis.index()] = f;
        }
    }
    exec.scaling.scale = Some(scaling);
    compose(exec, cmd.span)
}

/// A scale factor of zero would collapse the axis.
fn refuse_zero(f: f64, span: Span) -> Result<(), Alarm> {
    if f == 0.0 {
        return Err(Alarm::error(
            AlarmCode::ValueOutOfRange,
            span,
            "a scale factor of zero would collapse the axis",
        ));
    }
    Ok(())
}

/// G51.1: mirror of the axes named, about the coordinates their words give.
///
/// # Errors
/// With scaling on, where the profile refuses the two together.
pub(crate) fn g51_1(exec: &mut Executor, cmd: &Command) -> Result<(), Alarm> {
    refuse_both(exec, cmd, true)?;
    // Axes mirrored before stay so; the current position is read without the mirror.
    let previous = exec.scaling.mirror.take();
    compose(exec, cmd.span)?;
    let here = exec.kernel.program_position();
    let mut mirror = previous.unwrap_or(Scaling {
        center: here,
        factor: [1.0; AXES],
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
    exec.scaling.mirror = Some(mirror);
    compose(exec, cmd.span)
}

/// Sets the chain's scaling frame to what G51 and G51.1 make together.
///
/// # Errors
/// A negative scale factor on a mirrored axis: the two cancel into a shift, which a scaling
/// frame cannot hold.
fn compose(exec: &mut Executor, span: Span) -> Result<(), Alarm> {
    let composed = match (exec.scaling.scale, exec.scaling.mirror) {
        (Some(scale), Some(mirror)) => Some(scaled_then_mirrored(&scale, &mirror, span)?),
        (scale, mirror) => scale.or(mirror),
    };
    exec.kernel.frames.set_scaling(composed);
    Ok(())
}

/// Scaling about its centre, then the mirror, as one scaling: per mirrored axis
/// `m(c + f (x - c))` with `m(y) = 2 cm - y` is `C + F (x - C)` with `F = -f` and
/// `C = (2 cm - c (1 - f)) / (1 + f)`.
fn scaled_then_mirrored(scale: &Scaling, mirror: &Scaling, span: Span) -> Result<Scaling, Alarm> {
    let mut composed = *scale;
    for i in 0..AXES {
        if mirror.factor[i] > 0.0 {
            continue;
        }
        let (c, f, cm) = (scale.center[i], scale.factor[i], mirror.center[i]);
        if f == -1.0 {
            return Err(Alarm::error(
                AlarmCode::WordNotAllowed,
                span,
                "a scale factor of -1 on a mirrored axis cancels the mirror into a shift",
            )
            .with_help("mirror the axis with G51.1 or with the factor, not both"));
        }
        composed.factor[i] = -f;
        composed.center[i] = (2.0 * cm - c * (1.0 - f)) / (1.0 + f);
    }
    Ok(composed)
}

/// G50 (scaling off) or G50.1 (mirror off): only the one it names.
pub(crate) fn cancel(exec: &mut Executor, mirror: bool) {
    if mirror {
        exec.scaling.mirror = None;
    } else {
        exec.scaling.scale = None;
    }
    // What is left is one of the two alone, which composes without an alarm.
    let left = exec.scaling.scale.or(exec.scaling.mirror);
    exec.kernel.frames.set_scaling(left);
}

/// Scaling and mirror cannot be on together where the profile says so (Syntec spec 1.28, 1.29).
fn refuse_both(exec: &Executor, cmd: &Command, mirror: bool) -> Result<(), Alarm> {
    if exec.kernel.setup.profile().coordinates.scaling_with_mirror {
        return Ok(());
    }
    let other_on = if mirror {
        exec.scaling.scaling_on()
    } else {
        exec.scaling.mirror_on()
    };
    if !other_on {
        return Ok(());
    }
    Err(Alarm::error(
        AlarmCode::WordNotAllowed,
        cmd.span,
        "scaling (G51) and the programmable mirror (G51.1) cannot be on together",
    )
    .with_help(if mirror {
        "cancel the scaling with G50 first"
    } else {
        "cancel the mirror with G50.1 first"
    }))
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The composed frame gives what scaling and then mirroring give, point by point.
    #[test]
    fn the_composition_is_scaling_then_mirroring() {
        let scale = Scaling {
            center: [3.0, -7.0, 10.0, 0.0, 0.0, 0.0],
            factor: [2.5, 0.5, 1.0, 1.0, 1.0, 1.0],
        };
        let mirror = Scaling {
            center: [50.0, 4.0, 0.0, 0.0, 0.0, 0.0],
            factor: [-1.0, -1.0, 1.0, 1.0, 1.0, 1.0],
        };
        let composed = scaled_then_mirrored(&scale, &mirror, Span::default()).unwrap();
        for x in [-20.0, 0.0, 3.0, 17.5, 120.0] {
            for i in 0..3 {
                let scaled = scale.center[i] + scale.factor[i] * (x - scale.center[i]);
                let expected = if mirror.factor[i] < 0.0 {
                    2.0 * mirror.center[i] - scaled
                } else {
                    scaled
                };
                let got = composed.center[i] + composed.factor[i] * (x - composed.center[i]);
                assert!(
                    (got - expected).abs() < 1e-9,
                    "axis {i} at {x}: {got} {expected}"
                );
            }
        }
        let minus_one = Scaling {
            factor: [-1.0, 1.0, 1.0, 1.0, 1.0, 1.0],
            ..scale
        };
        assert!(scaled_then_mirrored(&minus_one, &mirror, Span::default()).is_err());
    }
}
