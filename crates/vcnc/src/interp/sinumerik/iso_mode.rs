//! G291: the ISO dialect mode of a SINUMERIK program (PGsl 16.4 group 47, L17548-17557). The
//! blocks from the one after G291 to the next that holds G290 are ISO G-code; the ISO
//! interpreter runs them on the same machine state (position, frames, tool, feed, spindle), and
//! the SINUMERIK front end goes on at the G290 block with what they left.
//!
//! The ISO interpreter reads a copy of the program in which every line outside the section is
//! blank, so that its spans are the program's own lines and columns. Never: let the ISO
//! interpreter's end of text end the SINUMERIK program.

use super::gcodes::Motion;
use super::Sinumerik;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::kernel::Kernel;
use crate::interp::modal::{DistanceMode, MotionMode, Units};
use crate::interp::{Interpreter, Options};
use crate::motion::{ArcDirection, Item, SegmentKind};
use crate::syntax::lines::TextLines;

/// The most moves one ISO section makes (vcnc's limit): the section runs within one block
/// of the SINUMERIK program, its moves held until it ends (about 850 bytes a move), so a loop
/// of ISO blocks that ran long would hold them all.
const MAX_MOVES: u64 = 100_000;

fn too_many_moves(span: crate::source::Span) -> Alarm {
    Alarm::error(
        AlarmCode::MacroLimit,
        span,
        format!("the ISO section after G291 makes more than {MAX_MOVES} moves"),
    )
    .with_help("check the section's loops and jumps (GOTO, WHILE): one runs far too long; or end the section with G290 sooner")
}

/// True when the line holds the word G290 (not G2900, not in a comment).
fn has_g290(line: &[u8]) -> bool {
    let code = line
        .iter()
        .position(|&b| b == b';' || b == b'(')
        .map_or(line, |end| &line[..end]);
    code.windows(4).enumerate().any(|(i, w)| {
        w.eq_ignore_ascii_case(b"G290")
            && (i == 0 || !code[i - 1].is_ascii_alphanumeric())
            && code.get(i + 4).is_none_or(|b| !b.is_ascii_digit())
    })
}

/// Runs the ISO section that starts at line `first` of the current level's program; returns
/// the line of its G290 (where the SINUMERIK front end goes on), or the number of lines when
/// the section runs to the end of the program.
///
/// # Errors
/// The ISO interpreter's error, which stops the program.
pub(super) fn run(
    front: &mut Sinumerik,
    kernel: &mut Kernel,
    first: usize,
) -> Result<usize, Alarm> {
    let level = front.levels.last().expect("a level");
    let program = &front.programs[level.program];
    let mut end = first;
    while let Some(line) = program.line(end) {
        if has_g290(line.bytes) {
            break;
        }
        end += 1;
    }
    // The program up to the section's end, every line outside it blank.
    let mut text = Vec::new();
    for index in 0..end {
        let Some(line) = program.line(index) else {
            break;
        };
        // Padding to the line's own offset keeps the spans the program's (a CR of a CRLF
        // line end becomes a blank).
        text.resize(line.base as usize, b' ');
        if index >= first {
            text.extend_from_slice(line.bytes);
        } else {
            text.extend(std::iter::repeat_n(b' ', line.bytes.len()));
        }
        text.push(b'\n');
    }
    let file = program.file;
    let machine = kernel.state().setup.machine().clone();
    // The section's loops count against the program's limit of jumps.
    let mut options = Options::default();
    options.limits.jumps = front.settings.iteration_limit;
    let mut iso = Interpreter::new(TextLines::new(&text), file, &machine, options);
    // The ISO blocks start from the state the SINUMERIK blocks left.
    let modal = &mut iso.core.exec.modal;
    modal.plane = front.modal.plane;
    modal.distance = if front.modal.absolute {
        DistanceMode::Absolute
    } else {
        DistanceMode::Incremental
    };
    modal.units = if front.modal.inch {
        Units::Inches
    } else {
        Units::Millimetres
    };
    modal.motion = match front.modal.motion {
        Motion::Rapid => MotionMode::Rapid,
        Motion::Clockwise => MotionMode::Arc(ArcDirection::Clockwise),
        Motion::CounterClockwise => MotionMode::Arc(ArcDirection::CounterClockwise),
        _ => MotionMode::Linear,
    };
    std::mem::swap(&mut iso.core.exec.kernel, kernel.state_mut());
    let mut result = Ok(());
    let mut moves = 0u64;
    for item in iso.by_ref() {
        if matches!(&item, Ok(Item::Segment(s)) if s.motion().is_some()) {
            moves += 1;
            if moves > MAX_MOVES {
                result = Err(too_many_moves(front.last_span));
                break;
            }
        }
        match item {
            Ok(Item::Segment(segment)) if matches!(segment.kind, SegmentKind::End { .. }) => break,
            Ok(Item::Warning(alarm)) if alarm.code == AlarmCode::MissingProgramEnd => {}
            Ok(Item::Warning(warning)) => kernel.warn(warning),
            Ok(item) => kernel.push_item(item),
            Err(alarm) => {
                result = Err(alarm);
                break;
            }
        }
    }
    std::mem::swap(&mut iso.core.exec.kernel, kernel.state_mut());
    result?;
    // The SINUMERIK blocks go on from what the ISO blocks left.
    let modal = &iso.core.exec.modal;
    front.modal.plane = modal.plane;
    kernel.set_plane(modal.plane);
    front.modal.absolute = modal.distance == DistanceMode::Absolute;
    front.modal.inch = modal.units == Units::Inches;
    front.modal.motion = match modal.motion {
        MotionMode::Rapid => Motion::Rapid,
        MotionMode::Arc(ArcDirection::Clockwise) => Motion::Clockwise,
        MotionMode::Arc(ArcDirection::CounterClockwise) => Motion::CounterClockwise,
        MotionMode::Linear | MotionMode::Thread => Motion::Line,
    };
    front.programmed = kernel.program_position();
    Ok(end)
}

#[cfg(test)]
mod tests {
    use super::has_g290;

    #[test]
    fn g290_is_found_as_a_word_only() {
        assert!(has_g290(b"G290"));
        assert!(has_g290(b"N20 g290 ; back"));
        assert!(!has_g290(b"G2900"));
        assert!(!has_g290(b"G1 X1 ; G290 later"));
        assert!(!has_g290(b"(G290) G1"));
    }
}
