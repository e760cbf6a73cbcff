//! Mitsubishi G12/G13 circle cutting (spec iso-fanuc0m-mitsubishi.md B.6, issue #4): from the
//! circle's centre, a half circle out to the circle, the whole circle, a half circle back to the
//! centre, all in the cutting direction, in the selected plane. The tool centre runs on radius
//! |I| minus offset D (a negative offset enlarges it).

use super::decode::Command;
use super::exec::Executor;
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::machine::AXES;
use crate::motion::{ArcDirection, Feed, MachinePos, Plane, SegmentKind};

/// Runs a G12 (clockwise) or G13 block.
///
/// # Errors
/// No I or D, an offset number out of range, a circle no larger than the offset, no feed.
pub(crate) fn run(
    exec: &mut Executor,
    cmd: &Command,
    direction: ArcDirection,
    out: &mut Output,
) -> Result<(), Alarm> {
    let refuse = |message: &str| Alarm::error(AlarmCode::CircleCutting, cmd.span, message);
    let i = cmd
        .word(b'I')
        .ok_or_else(|| refuse("circle cutting needs I, the circle's radius"))?;
    let d = cmd.word(b'D').ok_or_else(|| {
        refuse("circle cutting needs D, the offset number")
            .with_help("Mitsubishi program error P170")
    })?;
    let number = exec.kernel.setup.offset_number(d, 'D')?;
    let offset = exec.kernel.tools.radius(number);
    let r = exec.length(&i).abs() - offset;
    if r <= 0.0 {
        return Err(Alarm::error(
            AlarmCode::CircleCutting,
            i.span,
            format!(
                "the circle's radius {:.4} is not larger than the offset {offset:.4}",
                exec.length(&i).abs()
            ),
        )
        .with_help("Mitsubishi program error P233"));
    }
    let feed = exec.cutting_feed(cmd)?;
    let centre = exec.kernel.program_position();
    let circle = Circles {
        centre,
        plane: exec.modal.plane,
        direction,
        feed,
    };
    // Out on a half circle about (r/2, 0), round the circle about the centre, back again.
    for step in [(r, r / 2.0), (r, 0.0), (0.0, r / 2.0)] {
        circle.arc(exec, cmd, step, out)?;
    }
    Ok(())
}

/// Arcs about points on the first axis of the plane through `centre`, the shape of circle
/// cutting and of Haas's circular pocket.
pub(super) struct Circles {
    /// The circle's centre, program coordinates.
    pub(super) centre: [f64; AXES],
    pub(super) plane: Plane,
    pub(super) direction: ArcDirection,
    pub(super) feed: Feed,
}

impl Circles {
    /// An arc to the point `to` along the plane's first axis from the centre, about the point
    /// `about` along it.
    pub(super) fn arc(
        &self,
        exec: &mut Executor,
        cmd: &Command,
        (to, about): (f64, f64),
        out: &mut Output,
    ) -> Result<(), Alarm> {
        let (a, _, _) = self.plane.axes();
        let at = |da: f64| {
            let mut p = self.centre;
            p[a] += da;
            p
        };
        let target = exec.machine_target(&at(to), false);
        let about = exec.machine_target(&at(about), false);
        let motion = exec.move_to(target, cmd, out)?;
        out.push(
            cmd,
            SegmentKind::Arc {
                motion,
                center: MachinePos(about),
                direction: self.direction,
                plane: self.plane,
                extra_turns: 0,
                feed: self.feed,
            },
        );
        Ok(())
    }
}
