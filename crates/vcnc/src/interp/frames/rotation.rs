//! G68/G69: coordinate rotation (spec iso-syntec-milling.md 1.37).
//!
//! `G68 X_ Y_ R_` (the two axes of the selected plane) turns every later position about the
//! centre by R degrees, counter-clockwise positive, until G69. The centre is absolute in the work
//! coordinate system; an omitted centre word takes the current position. In G90 a new G68
//! replaces the angle; in G91 its R adds to the angle in force. Incremental moves turn with the
//! rotation (their vectors are rotated), so the centre only matters to absolute positions. The
//! rotation lives in the coordinate chain (`mod.rs`), so moves, arcs and the positions the
//! control reports all follow it.

use super::{Frames, Rotation};
use crate::alarm::Alarm;
use crate::interp::decode::Command;
use crate::interp::exec::Executor;
use crate::interp::modal::DistanceMode;
use crate::machine::Axis;

/// G68: sets the rotation from the block's centre words and R.
///
/// # Errors
/// None today; kept fallible like the other coordinate codes.
pub(crate) fn g68(exec: &mut Executor, cmd: &Command) -> Result<(), Alarm> {
    let (a, b, _) = exec.modal.plane.axes();
    let previous = exec.kernel.frames.rotation().copied();
    exec.kernel.frames.set_rotation(None);
    // With the old rotation removed, this is the position in work coordinates.
    let here = exec.kernel.program_position();
    let word = |axis: usize| {
        cmd.axis(axis)
            .map_or(here[axis], |v| exec.axis_value(Axis::ALL[axis], &v))
    };
    let center = (word(a), word(b));
    let angle = cmd.r().map_or(0.0, |r| exec.kernel.setup.angle(&r));
    let degrees = match (exec.modal.distance, previous) {
        (DistanceMode::Incremental, Some(previous)) => previous.degrees + angle,
        _ => angle,
    };
    exec.kernel
        .frames
        .set_rotation(Some(Rotation::new((a, b), center, degrees)));
    Ok(())
}

/// G69: no rotation from here on.
pub(crate) fn g69(frames: &mut Frames) {
    frames.set_rotation(None);
}
