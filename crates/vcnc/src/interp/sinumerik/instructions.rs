//! The instructions of group 3 that stand in a block of their own: the frame instructions
//! (TRANS ... AMIRROR, the 840D's G58/G59) and the pole (G110, G111, G112)
//! (docs/SINUMERIK.md 3.1, 5.3, 6.5).
//!
//! Never: move an axis; they change the frame or the pole only.

use super::block::Words;
use super::gcodes::{self, FrameOp, Function};
use super::motion::unit;
use super::Sinumerik;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::kernel::{Kernel, Origin};
use crate::machine::AXES;
use crate::source::Span;
use crate::syntax::sinumerik::Word;

/// A frame instruction: the programmable frame changes, nothing moves (docs/SINUMERIK.md 5.3).
pub(super) fn frame_instruction(
    front: &mut Sinumerik,
    kernel: &mut Kernel,
    words: &Words<'_>,
    op: FrameOp,
    word: &Word,
) -> Result<(), Alarm> {
    if let Some(&(_, _, other)) = words
        .functions
        .iter()
        .find(|(f, _, w)| !std::ptr::eq(*w, word) && !matches!(f, Function::Plane(_)))
    {
        return Err(own_block(word, other.span));
    }
    if words.feed.is_some() || words.speed.is_some() || words.tool.is_some() || !words.m.is_empty()
    {
        return Err(own_block(word, word.span));
    }
    let unit = unit(front);
    let lengths: [Option<f64>; AXES] = std::array::from_fn(|i| {
        let scale = front.axes.scale(i, unit);
        words.axes[i].map(|v| v.value * scale)
    });
    let plain: [Option<f64>; 3] = std::array::from_fn(|i| words.axes[i].map(|v| v.value));
    let frame = &mut front.frame;
    let plane = front.modal.plane;
    let result = match op {
        FrameOp::Trans => frame.trans(lengths),
        FrameOp::Atrans => frame.atrans(lengths),
        FrameOp::G58 => frame.g58(lengths),
        FrameOp::G59 => frame.g59(lengths),
        FrameOp::Rot | FrameOp::Rots | FrameOp::Arot | FrameOp::Arots => match (words.rpl, op) {
            (Some((angle, _)), FrameOp::Rot | FrameOp::Rots) => frame.rot_rpl(plane, angle),
            (Some((angle, _)), _) => frame.arot_rpl(plane, angle),
            (None, FrameOp::Rot) => frame.rot(plain),
            (None, FrameOp::Rots) => frame.rots(plain),
            (None, FrameOp::Arot) => frame.arot(plain),
            (None, _) => frame.arots(plain),
        },
        FrameOp::Scale => frame.scale(plain),
        FrameOp::Ascale => frame.ascale(plain),
        FrameOp::Mirror => {
            frame.mirror(plain.map(|v| v.is_some()));
            Ok(())
        }
        FrameOp::Amirror => {
            frame.amirror(plain.map(|v| v.is_some()));
            Ok(())
        }
        FrameOp::Tool {
            applicate,
            rotation_only,
        } => {
            let direction = super::tool_frame::tool_direction(kernel);
            frame.tool_frame(
                super::tool_frame::rotation(direction, applicate),
                rotation_only,
            )
        }
    };
    result.map_err(|error| Alarm::error(AlarmCode::ValueOutOfRange, word.span, error.message()))?;
    kernel.set_programmable(front.frame.to_affine());
    Ok(())
}

/// G110, G111, G112: a new pole, from the words of its block (docs/SINUMERIK.md 6.5).
pub(super) fn pole(
    front: &mut Sinumerik,
    words: &Words<'_>,
    reference: gcodes::Pole,
    origin: Origin,
) -> Result<(), Alarm> {
    use super::polar::{PoleDefinition, PoleReference};
    let plane = front.modal.plane;
    let unit = unit(front);
    let reference = match reference {
        gcodes::Pole::LastPoint => PoleReference::LastPoint([
            front.programmed[0],
            front.programmed[1],
            front.programmed[2],
        ]),
        gcodes::Pole::WorkZero => PoleReference::WorkZero,
        gcodes::Pole::Previous => PoleReference::LastPole,
    };
    let definition = match (words.ap, words.rp) {
        (None, None) => PoleDefinition::Cartesian(std::array::from_fn(|i| {
            words.axes[i].map(|v| v.value * unit)
        })),
        (ap, rp) => {
            if words.axes.iter().take(3).any(Option::is_some) {
                return Err(Alarm::error(
                    AlarmCode::WordNotAllowed,
                    origin.span,
                    "a pole takes either axis values or AP= and RP=",
                ));
            }
            PoleDefinition::Polar {
                angle: ap.map_or(0.0, |v| v.value),
                radius: rp.map_or(0.0, |v| v.value * unit),
            }
        }
    };
    front.polar.set_pole(reference, definition, plane);
    Ok(())
}

/// The alarm of an instruction that must stand in a block of its own (docs/SINUMERIK.md 3.1).
fn own_block(word: &Word, at: Span) -> Alarm {
    Alarm::error(
        AlarmCode::WordNotAllowed,
        at,
        format!("{} must be programmed in a block of its own", word.address),
    )
    .with_help("put the frame instruction in its own block, with its axis values only")
}
