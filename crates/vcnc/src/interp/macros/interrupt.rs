//! Syntec's interrupt-type subprogram: `M96 P_` arms it, `M97` disarms it, and the PLC signal
//! C49 calls it in the middle of the main program (spec/iso-syntec-milling.md §2 item 11, seed
//! L4954-5043).
//!
//! A run has no PLC, so the signal comes from [`Options::interrupts`](crate::Options): each entry
//! names a block of the main program, and the signal arrives once, while that block runs. The
//! simulator has no partial motion, so the block is interrupted before it moves: the
//! interruption point is where the block starts. The interrupt program runs with the modal state
//! of that point (it is a call like M98, not a new program), and its `M99` returns:
//!
//! - without P or Q: the tool goes back to the interruption point at rapid and the interrupted
//!   block is run again, read afresh (in G91 it moves from there, in the modes the interrupt
//!   program left, which is why the manual's example restores them);
//! - with `P n`: to the block `N n` of the main program; with `Q n`: to line `n` of the main
//!   program's file (the interrupted block is abandoned).
//!
//! The control ignores the signal inside a subprogram and while a mode that needs the block's
//! start point is on (G41/G42, G12.1, G16, G51, G51.1, G05, G05.1; the manual's other modes,
//! G51.2, G114.1 and G114.3, are not run by vcnc at all). vcnc ignores it too and says so in a
//! warning ([`AlarmCode::InterruptIgnored`]), since the user asked for a signal that then does
//! nothing.

use super::programs::{sequence_number, Position, Program};
use super::Core;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::decode::Command;
use crate::interp::Place;
use crate::machine::AXES;
use crate::source::Span;
use crate::syntax::Block;
use std::fmt;
use std::str::FromStr;

/// The block of the main program during which the interrupt signal (Syntec's C49) comes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum InterruptAt {
    /// The block on this line of the main program's file (1-based; the first block run from
    /// the line, when it holds several).
    Line(u32),
    /// The block with this sequence number (`N120`) in the main program.
    Sequence(u32),
}

impl FromStr for InterruptAt {
    type Err = String;

    /// `12` is line 12, `N12` (or `n12`) the block numbered N12.
    fn from_str(text: &str) -> Result<InterruptAt, String> {
        let text = text.trim();
        let (sequence, digits) = match text.strip_prefix(['N', 'n']) {
            Some(rest) => (true, rest),
            None => (false, text),
        };
        let number: u32 = digits.parse().map_err(|_| {
            format!("`{text}`: expected a line number (12) or a sequence number (N12)")
        })?;
        match (sequence, number) {
            (_, 0) => Err(format!("`{text}`: lines and sequence numbers start at 1")),
            (true, n) => Ok(InterruptAt::Sequence(n)),
            (false, n) => Ok(InterruptAt::Line(n)),
        }
    }
}

impl fmt::Display for InterruptAt {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            InterruptAt::Line(n) => write!(f, "line {n}"),
            InterruptAt::Sequence(n) => write!(f, "N{n}"),
        }
    }
}

/// The interrupt program armed by M96.
#[derive(Clone, Copy, Debug)]
struct Armed {
    program: u32,
    /// The M96 block's P word.
    span: Span,
}

/// What the macro layer keeps of interrupts.
#[derive(Default)]
pub(crate) struct Interrupts {
    armed: Option<Armed>,
    /// The signals still to come (each comes once).
    pending: Vec<InterruptAt>,
    /// The signals given to the run are taken into `pending` (once, at its first block).
    loaded: bool,
}

/// What an interrupt call remembers for its return.
#[derive(Clone, Debug)]
pub(super) struct Interrupted {
    /// Machine position at the interruption point.
    at: [f64; AXES],
    /// The interrupted block, run again after a plain M99.
    block: Position,
}

impl Core {
    /// M96 P_: arms interrupt program P.
    pub(super) fn arm_interrupt(&mut self, span: Span) -> Result<(), Alarm> {
        let Some(p) = self.command.p() else {
            return Err(Alarm::error(
                AlarmCode::MissingValue,
                span,
                "M96 needs P (the interrupt program's number)",
            ));
        };
        let program = Core::whole_number(p, "P (program number)")?;
        self.macros.interrupts.armed = Some(Armed {
            program,
            span: p.span,
        });
        Ok(())
    }

    /// M97 (Syntec): no interrupt program from here on.
    pub(super) fn disarm_interrupt(&mut self) {
        self.macros.interrupts.armed = None;
    }

    /// True when a signal of the options may still come: the check that runs for every block.
    #[inline]
    pub(crate) fn interrupt_may_come(&self) -> bool {
        !self.macros.interrupts.loaded || !self.macros.interrupts.pending.is_empty()
    }

    /// Before `block` runs: when the signal comes during it, calls the interrupt program and
    /// returns true (the block runs later, when the program returns to it).
    pub(crate) fn interrupt_before(&mut self, block: &Block, main_text: Option<&[u8]>) -> bool {
        let in_call = self.macros.in_call();
        let file = self.file;
        let interrupts = &mut self.macros.interrupts;
        if !interrupts.loaded {
            interrupts.loaded = true;
            interrupts.pending = self.options.interrupts.clone();
        }
        let Some(index) = interrupts.pending.iter().position(|at| match *at {
            // A line names a place in the file: reached inside a subprogram of the same
            // file, the signal comes there (and is ignored).
            InterruptAt::Line(n) => block.span.file == file && block.span.line == n,
            // A sequence number names a block of the main program.
            InterruptAt::Sequence(n) => !in_call && sequence_number(block) == Some(n),
        }) else {
            return false;
        };
        let at = interrupts.pending.remove(index);
        if let Some(reason) = self.interrupt_excluded(in_call) {
            self.out.push_warning(
                Alarm::warning(
                    AlarmCode::InterruptIgnored,
                    block.span,
                    format!("the interrupt signal at {at} is ignored: {reason}"),
                )
                .with_help("the control ignores C49 here (spec 2, item 11)"),
            );
            return false;
        }
        match self.call_interrupt(block.span, main_text) {
            Ok(()) => true,
            Err(alarm) => {
                self.fail(alarm);
                true
            }
        }
    }

    /// Why the signal is ignored now, if it is.
    fn interrupt_excluded(&self, in_call: bool) -> Option<&'static str> {
        if self.macros.interrupts.armed.is_none() {
            return Some("no interrupt program is armed (M96 P_)");
        }
        if in_call {
            return Some("the control takes no interrupt inside a subprogram");
        }
        if self.out.compensating() {
            return Some("cutter compensation (G41/G42) is on");
        }
        if self.out.polar_interpolating() {
            return Some("polar coordinate interpolation (G12.1) is on");
        }
        if self.exec.polar.is_some() {
            return Some("polar coordinates (G16) are on");
        }
        if self.exec.modal.smoothing.high_speed.is_some() {
            return Some("high-speed high-precision mode (G05) is on");
        }
        if self.exec.modal.smoothing.path.is_some() {
            return Some("path smoothing (G05.1) is on");
        }
        let scaling = &self.exec.scaling;
        if scaling.mirror_on() {
            Some("the programmable mirror (G51.1) is on")
        } else if scaling.scaling_on() {
            Some("scaling (G51) is on")
        } else {
            None
        }
    }

    /// Calls the armed program; the block being run is where it returns to.
    fn call_interrupt(&mut self, span: Span, main_text: Option<&[u8]>) -> Result<(), Alarm> {
        let armed = self
            .macros
            .interrupts
            .armed
            .expect("interrupt_excluded has ruled out an unarmed interrupt");
        let main = self.current_program(main_text, span)?;
        let block = self.current_position();
        let program = self
            .find_program(armed.program, main_text, armed.span)
            .map_err(|alarm| alarm.with_label(span, "the interrupt signal came here"))?;
        self.call(Program::Stored(program), (0, 0), 1, None, false, span)?;
        let frame = self
            .macros
            .calls
            .last_mut()
            .expect("call has pushed the frame");
        frame.return_to = Place::stored(main, block);
        frame.interrupted = Some(Interrupted {
            at: self.exec.kernel.position,
            block,
        });
        Ok(())
    }

    /// M99 of an interrupt program, its frame popped and the main program in `self.place`:
    /// `label` (P) or `line` (Q) chosen, or back to the interrupted block.
    pub(super) fn return_from_interrupt(
        &mut self,
        interrupted: Interrupted,
        line: Option<u32>,
        span: Span,
    ) -> Result<(), Alarm> {
        // The frame's place is the main program in memory (`call_interrupt` put it there).
        let program = self.current_program(None, span)?;
        match line {
            Some(q) => {
                let index = (q as usize).wrapping_sub(1);
                if !program.has_line(index) {
                    return Err(Alarm::error(
                        AlarmCode::SequenceNotFound,
                        span,
                        format!("M99 Q{q}: the main program has no line {q}"),
                    ));
                }
                self.count_jump(span)?;
                self.macros.loops.clear();
                self.place = Place::stored(program, (index, 0));
            }
            None => {
                // Back to where the signal came, then the block again from its start.
                self.exec
                    .rapid_to(interrupted.at, &Command::at(span), &mut self.out)?;
                self.place = Place::stored(program, interrupted.block);
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::InterruptAt;

    #[test]
    fn a_signal_names_a_line_or_a_sequence_number() {
        assert_eq!("12".parse(), Ok(InterruptAt::Line(12)));
        assert_eq!(" N120 ".parse(), Ok(InterruptAt::Sequence(120)));
        assert_eq!("n7".parse(), Ok(InterruptAt::Sequence(7)));
        assert!("0".parse::<InterruptAt>().is_err());
        assert!("N".parse::<InterruptAt>().is_err());
        assert!("X12".parse::<InterruptAt>().is_err());
        assert!("-3".parse::<InterruptAt>().is_err());
    }
}
