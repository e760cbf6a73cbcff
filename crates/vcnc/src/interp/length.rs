//! G43/G44/G49: tool length compensation along Z (and G43.4's length, `tool_center.rs`).
//!
//! The H number selects an entry of the offset memory (geometry + wear). A block with G43/G44/G49
//! or a new H and no Z word still moves Z by the change of offset, as if `G91 Z0` had been
//! commanded (spec/iso-fanuc0m-mitsubishi.md B.12 note 1); H0 means an offset of zero.

use super::decode::Command;
use super::exec::Executor;
use super::modal::{LengthComp, MotionMode};
use super::Output;
use crate::alarm::Alarm;
use crate::motion::SegmentKind;
use crate::profile::Group;

/// Takes G43/G44/G49 and H from the block. Returns true when the applied length vector must
/// change in this block.
///
/// # Errors
/// [`AlarmCode::OffsetNumberOutOfRange`] for an H number the control does not have.
pub(crate) fn apply(exec: &mut Executor, cmd: &Command, out: &mut Output) -> Result<bool, Alarm> {
    // In the old FANUC 0M form `G42 H19` the H belongs to cutter compensation.
    let h = cmd
        .h()
        .filter(|_| !super::compensation::h_names_radius_offset(exec.kernel.setup.profile(), cmd));
    if let Some(h) = h {
        let number = exec.kernel.setup.offset_number(h, 'H')?;
        exec.kernel.tools.select_length(number);
    }
    // G43.4 starts tool centre point control with its H in force; G43, G44, G49 end it.
    super::tool_center::switch(exec, cmd, out)?;
    super::tool_center::refuse_compensation(cmd, out)?;
    super::tool_center::refuse_high_speed(exec, cmd, out)?;
    let changed = cmd.group(Group::LengthComp).is_some()
        || (h.is_some() && exec.modal.length_comp != LengthComp::Off);
    Ok(changed && (exec.active_length() - exec.kernel.frames.length_vector()).abs() > 0.0)
}

/// Moves Z so that the program position stays where it is under the new offset.
///
/// # Errors
/// None today; kept fallible for the feed check of a G01-mode offset move.
pub(crate) fn move_to_new_vector(
    exec: &mut Executor,
    cmd: &Command,
    out: &mut Output,
) -> Result<(), Alarm> {
    let program = exec.kernel.program_position();
    let target = exec.machine_target(&program, true);
    let at_rapid = exec
        .kernel
        .setup
        .profile()
        .compensation
        .length_change_at_rapid;
    match (exec.modal.motion, exec.kernel.feed) {
        (MotionMode::Linear | MotionMode::Arc(_), Some(_)) if !at_rapid => {
            let feed = exec.cutting_feed(cmd)?;
            let motion = exec.move_to(target, cmd, out)?;
            out.push(cmd, SegmentKind::Line { motion, feed });
        }
        _ => exec.rapid_to(target, cmd, out)?,
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::{interpret_str, Machine, Options};

    /// The Z at the end of every move of `program` on the default machine (no alarm allowed).
    fn z_ends(program: &str) -> Vec<f64> {
        interpret_str(program, &Machine::default(), Options::default())
            .map(|item| item.expect("the program runs without an alarm"))
            .filter_map(|item| item.segment()?.motion().map(|motion| motion.to.0[2]))
            .collect()
    }

    #[test]
    fn offsets_written_by_the_program_apply_to_the_next_z_move() {
        // The executor keeps the offset of the H number in force: every write to the offset
        // memory and every new H must reach it.
        let z = z_ends(
            "G10 L10 P1 R10.\nG43 H1 G0 Z0\nG10 L10 P1 R20.\nG0 Z0\nX1.\n#2201 = 30.\n\
             G0 Z1.\n#2001 = 2.\nG1 Z0 F100.\nG10 L11 P1 R1.\nG0 Z0\nH2 Z0\nG10 L10 P2 R5.\n\
             G0 Z0\nG49 Z0\nM30",
        );
        assert_eq!(
            z,
            [10.0, 20.0, 20.0, 31.0, 32.0, 31.0, 0.0, 5.0, 0.0],
            "{z:?}"
        );
    }
}
