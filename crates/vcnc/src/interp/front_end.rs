//! The seam between a dialect and the kernel: a [`FrontEnd`] runs its program's blocks on a
//! [`Kernel`], and [`Run`] turns that into the motion stream every consumer takes.
//!
//! [`Run`] gives the same contract as the ISO [`Interpreter`](super::Interpreter): an iterator of
//! [`StreamItem`]s that ends after the end item or after the first error (the `Err` item), and
//! [`Run::next_batch`] for consumers that take a batch at a time. A front end owns its text, its
//! blocks, its modal state and its language; it never builds a segment itself.

use super::kernel::Kernel;
use super::NoCheck;
use crate::alarm::Alarm;
use crate::checks::ReleasedCheck;
use crate::motion::StreamItem;
use std::collections::VecDeque;

/// What one step of a front end did to the flow of the program.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Step {
    /// Go on with the next block.
    Next,
    /// The program has ended (the front end called [`Kernel::end`], or its text ran out).
    End,
}

/// A dialect's block sequencer.
pub trait FrontEnd {
    /// Reads the program's next block and runs it on `kernel`.
    ///
    /// # Errors
    /// The alarm that stops the program at this block (the kernel's own, or the dialect's).
    fn step(&mut self, kernel: &mut Kernel) -> Result<Step, Alarm>;
}

/// A program of any dialect running on the kernel: an iterator over its motion stream.
pub struct Run<F> {
    front_end: F,
    kernel: Kernel,
    ready: VecDeque<StreamItem>,
    done: bool,
    /// Steps that ran a block (the last one, the end or an error, included).
    blocks: u64,
}

/// Blocks run at most by one call of [`Run::next_batch`], so that a front end's long loop
/// without motion hands control back now and then.
const STEPS_PER_BATCH: u32 = 1 << 16;

impl<F: FrontEnd> Run<F> {
    /// `front_end`'s program on `kernel`.
    pub fn new(front_end: F, kernel: Kernel) -> Run<F> {
        Run {
            front_end,
            kernel,
            ready: VecDeque::new(),
            done: false,
            blocks: 0,
        }
    }

    /// Runs one block; the end or an error closes the stream.
    fn step(&mut self) {
        self.blocks += 1;
        match self.front_end.step(&mut self.kernel) {
            Ok(Step::Next) => {}
            Ok(Step::End) => self.done = true,
            Err(alarm) => {
                self.kernel.stop(alarm);
                self.done = true;
            }
        }
        if self.done {
            self.kernel.finish();
        }
    }

    /// Appends the next items of the stream to `out` until it holds at least `at_least` items
    /// or the program is over; false when nothing more will come (what came is in `out`). The
    /// same items as [`Iterator::next`] gives.
    pub fn next_batch(&mut self, out: &mut Vec<StreamItem>, at_least: usize) -> bool {
        self.next_batch_checked(out, at_least, &mut NoCheck)
    }

    /// [`Run::next_batch`] with `check` asked of the items as the blocks release them: when it
    /// cuts the stream at an item, no block after it runs.
    pub fn next_batch_checked(
        &mut self,
        out: &mut Vec<StreamItem>,
        at_least: usize,
        check: &mut impl ReleasedCheck,
    ) -> bool {
        out.extend(self.ready.drain(..));
        let mut checked = out.len();
        // The kernel queues straight into `out`: no item is moved twice.
        self.kernel.lend(out);
        let mut steps = 0;
        loop {
            let (items, released) = self.kernel.released();
            if released > checked {
                if !check.check_released(items, checked..released) {
                    self.kernel.cut_by_check();
                    self.done = true;
                }
                checked = released;
            }
            if self.done || released >= at_least || steps >= STEPS_PER_BATCH {
                break;
            }
            self.step();
            steps += 1;
        }
        self.kernel.give_back(out);
        // Once the program is over, everything it made is in `out`.
        !self.done
    }

    /// Blocks run so far.
    pub fn blocks_executed(&self) -> u64 {
        self.blocks
    }

    /// The kernel, for what a caller wants to know of the machine's state.
    pub fn kernel(&self) -> &Kernel {
        &self.kernel
    }
}

impl<F: FrontEnd> Iterator for Run<F> {
    type Item = StreamItem;

    fn next(&mut self) -> Option<Self::Item> {
        loop {
            if let Some(item) = self.ready.pop_front() {
                return Some(item);
            }
            self.kernel.release(&mut self.ready);
            if !self.ready.is_empty() {
                continue;
            }
            if self.done {
                return None;
            }
            self.step();
        }
    }
}
