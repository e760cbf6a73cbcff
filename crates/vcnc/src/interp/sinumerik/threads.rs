//! Threads beyond G33's constant lead (docs/SINUMERIK.md 10.8): G34 and G35, whose lead grows or
//! shrinks linearly with the spindle's revolutions (PGsl 9.11, seed 002 L6317-6381), and the run-in
//! and run-out paths DITS= and DITE= (PGsl 9.10.2, L6260-6315), the setting data SD42010
//! `$SC_THREAD_RAMP_DISP[0, 1]`.
//!
//! A G34/G35 block reaches the kernel as G33's does: one line at a feed per revolution, here the
//! lead that gives the block its true time at a constant spindle speed (the mean of its start
//! and end leads, [`mean_lead`]). DITS and DITE are kept as the setting data the control writes;
//! the planner ramps the thread with the axes' own acceleration (docs/SINUMERIK.md 10.8 says
//! why).
//!
//! Never: run a thread whose lead would reach zero or turn back before its end point, or take a
//! ramp path the control refuses (below -1).

use super::block::number;
use super::gcodes::Motion;
use super::Sinumerik;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::kernel::Kernel;
use crate::source::Span;
use crate::syntax::sinumerik::Word;

/// What the threads keep from block to block: SD42010 `$SC_THREAD_RAMP_DISP`, the run-in ([0],
/// DITS) and run-out ([1], DITE) paths in mm (-1 ramps with the axes' configured acceleration,
/// 0 with a step in speed, n > 0 within n mm: PGsl 9.10.2, the meanings inferred in spec part B
/// 1.10.2), and the lead of the last thread block.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Threads {
    pub(super) run_in: f64,
    pub(super) run_out: f64,
    lead: Option<f64>,
}

impl Default for Threads {
    /// -1 in both paths: the setting data's value before a program writes it (choice: the manual
    /// gives no default; -1 is the axes' own acceleration, what a thread does without DITS).
    fn default() -> Threads {
        Threads {
            run_in: -1.0,
            run_out: -1.0,
            lead: None,
        }
    }
}

impl Threads {
    /// The lead of a thread block: the one `written` in it, else the last thread block's. A thread
    /// chain's next block may leave the lead out (b/42's N71 `G33 Z55 X15` after N70's K5, seed
    /// 002 L6706, L6713; choice: the manual does not say how long the lead is kept, vcnc keeps it to
    /// the program's end).
    pub(super) fn lead(&mut self, written: Option<f64>) -> Option<f64> {
        if written.is_some() {
            self.lead = written;
        }
        self.lead
    }
}

/// Reads DITS= or DITE= into the setting data (modal: they stay for the following threads).
///
/// # Errors
/// [`AlarmCode::ValueOutOfRange`] for a path below -1 or between -1 and 0.
pub(super) fn ramp_word(front: &mut Sinumerik, kernel: &Kernel, word: &Word) -> Result<(), Alarm> {
    let value = number(front, kernel, word)?;
    // The range is -1, 0 and positive paths (L6278): -0.5 means nothing.
    if value.is_nan() || (value < 0.0 && value != -1.0) {
        return Err(Alarm::error(
            AlarmCode::ValueOutOfRange,
            word.span,
            format!(
                "{}={value}: a thread's run-in or run-out path is -1 (the axes' acceleration), 0 (no ramp) or a path in mm",
                word.address
            ),
        ));
    }
    // A path is a length in the unit in force (L6316); -1 and 0 are codes, not lengths.
    let value = if value > 0.0 {
        value * super::motion::unit(front)
    } else {
        value
    };
    if &*word.address == "DITS" {
        front.threads.run_in = value;
    } else {
        front.threads.run_out = value;
    }
    Ok(())
}

/// The lead along the thread's leading axis that times the block: `start` itself for G33, and
/// for G34 (`increasing`) or G35 the mean of the start and end leads, with `change` (F,
/// mm/rev^2) over `length` mm of the leading axis.
///
/// With k(n) = ka +- F n after n revolutions the axis has gone L(n) = ka n +- F n^2 / 2, so the
/// end lead is ke = sqrt(ka^2 +- 2 F L) (the manual's F = |ke^2 - ka^2| / 2L) and the block
/// takes |ke - ka| / F revolutions: L over those is (ka + ke) / 2 per revolution.
///
/// # Errors
/// [`AlarmCode::MissingValue`] without F; [`AlarmCode::ValueOutOfRange`] for a negative F, or a
/// G35 whose lead reaches zero before the end point.
pub(super) fn mean_lead(
    motion: Motion,
    start: f64,
    change: Option<(f64, Span)>,
    length: f64,
    span: Span,
) -> Result<f64, Alarm> {
    let Motion::VariableThread { increasing } = motion else {
        return Ok(start.abs());
    };
    let name = if increasing { "G34" } else { "G35" };
    let Some((change, change_span)) = change else {
        return Err(Alarm::error(
            AlarmCode::MissingValue,
            span,
            format!("{name} needs the lead's change in F (mm/rev^2)"),
        )
        .with_help(format!(
            "{name} Z-50 K2 F0.1: the lead starts at K and changes by F each revolution"
        )));
    };
    if change.is_nan() || change < 0.0 {
        return Err(Alarm::error(
            AlarmCode::ValueOutOfRange,
            change_span,
            format!("F{change}: {name}'s lead change is a size; G34 increases the lead, G35 decreases it"),
        ));
    }
    let start = start.abs();
    let signed = if increasing { change } else { -change };
    let end_squared = start * start + 2.0 * signed * length;
    // The manual gives no alarm number for a lead run out (choice: the range alarm).
    if end_squared <= 0.0 {
        let reach = start * start / (2.0 * change);
        return Err(Alarm::error(
            AlarmCode::ValueOutOfRange,
            span,
            format!(
                "{name}: the lead {start} falling by F{change} per revolution reaches 0 after {reach:.3} mm, before the thread's {length:.3} mm"
            ),
        )
        .with_help("a smaller F, a larger start lead or a shorter thread"));
    }
    Ok((start + end_squared.sqrt()) / 2.0)
}

/// The front end after running `text` to its end on `machine`, for the tests of the state it
/// keeps (here and in grinding.rs).
#[cfg(test)]
pub(super) fn run_to_end(text: &str, machine: &crate::Machine) -> Sinumerik {
    use crate::interp::front_end::{FrontEnd, Step};
    let mut front = Sinumerik::new(text.as_bytes(), crate::source::FileId(0), machine);
    let mut kernel = Kernel::new(machine);
    loop {
        match front.step(&mut kernel) {
            Ok(Step::End) => return front,
            Ok(Step::Next) => {}
            Err(alarm) => panic!("{alarm:?}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dits_and_dite_are_kept_as_sd42010_in_the_unit_in_force() {
        // -1 before any write; DITS=1 DITE=3 in mm; under G70 DITE=0.5 is 12.7 mm, DITS=-1 a code.
        let machine = crate::Machine::default()
            .with_profile(crate::ProfileName::Sinumerik)
            .expect("the default machine fits the SINUMERIK profile");
        assert_eq!(run_to_end("M30\n", &machine).threads, Threads::default());
        let front = run_to_end("M3 S100\nG33 Z-5 K1 DITS=1 DITE=3\nM30\n", &machine);
        assert_eq!((front.threads.run_in, front.threads.run_out), (1.0, 3.0));
        let front = run_to_end("G70\nDITS=-1 DITE=0.5\nM30\n", &machine);
        assert_eq!(front.threads.run_in, -1.0);
        assert!((front.threads.run_out - 12.7).abs() < 1e-12);
    }

    fn span() -> Span {
        Span::default()
    }

    #[test]
    fn a_constant_thread_keeps_its_lead() {
        assert_eq!(mean_lead(Motion::Thread, -2.5, None, 40.0, span()), Ok(2.5));
    }

    #[test]
    fn g34_times_the_block_by_the_mean_of_its_leads() {
        // ka 2, F 0.1, 30 mm: ke = sqrt(4 + 6) = 3.1623, mean 2.5811.
        let lead = mean_lead(
            Motion::VariableThread { increasing: true },
            2.0,
            Some((0.1, span())),
            30.0,
            span(),
        )
        .unwrap();
        assert!((lead - (2.0 + 10f64.sqrt()) / 2.0).abs() < 1e-12);
    }

    #[test]
    fn g35_whose_lead_runs_out_is_an_alarm() {
        // ka 2, F 0.1: the lead is 0 after 4 / 0.2 = 20 mm.
        let alarm = mean_lead(
            Motion::VariableThread { increasing: false },
            2.0,
            Some((0.1, span())),
            20.0,
            span(),
        )
        .unwrap_err();
        assert_eq!(alarm.code, AlarmCode::ValueOutOfRange);
        assert!(alarm.message.contains("20.000 mm"), "{}", alarm.message);
    }
}
