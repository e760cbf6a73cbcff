//! The interpreter on a thread of its own, handing its stream over a batch at a time.
//!
//! Interpreting overlaps with whatever the consumer does (planning, writing) on the other core.
//! A fixed pool of batch buffers goes round between the two threads: the interpreter fills an
//! empty one ([`Interpreter::next_batch`](crate::Interpreter::next_batch)), checks the travel,
//! and sends it; the consumer takes it, and gives it back. No allocation after the start,
//! bounded memory. The thread also counts the blocks executed and saves the persistent
//! variables (`store.rs`).
//!
//! Never: leave the interpreter's thread running once the [`Stream`] is dropped (a consumer
//! that stops reading, `vcnc trace | head`, must end it), or print.

use super::planned;
use super::program::ProgramFiles;
use super::store::{PersistentStore, Saver};
use super::waiting::Waiter;
use super::{Item, Layout, Stopping};
use crate::checks::{ReleasedCheck, TravelCheck};
use crate::interp::{FrontEnd, Interpreter, PersistentVariables};
use crate::machine::Machine;
use crate::plan::{PlanOptions, Timeline, Timing};
use crate::syntax::blocks::BlockSource;
use crate::syntax::iso::LineBlocks;
use std::collections::VecDeque;
use std::io;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{sync_channel, Receiver, SyncSender};
use std::sync::Arc;
use std::thread::JoinHandle;

/// Segments per batch taken from the interpreter: small, so that the pool stays in the caches.
pub(crate) const BATCH: usize = 256;

/// Batch buffers in circulation between the interpreter's thread and the consumer. A consumer
/// that keeps batches (the timed view) keeps fewer than this, so that the interpreter always
/// has one to fill; eight, not four, because the planner holds two or three batches for its
/// look-ahead and the interpreter, often the slower thread, must not wait for a buffer.
pub(crate) const POOL: usize = 8;

/// A program being interpreted on a thread of its own: its items one at a time (an
/// iterator), or a batch at a time in the buffers the interpreter filled.
pub struct Stream {
    /// The current batch; its front is the next item.
    items: VecDeque<Item>,
    /// None once the interpreter thread has ended (or is told to, on drop).
    batches: Option<Receiver<Vec<Item>>>,
    recycle: SyncSender<Vec<Item>>,
    waiter: Waiter,
    blocks: Arc<AtomicU64>,
    thread: Option<JoinHandle<Option<io::Error>>>,
    files: ProgramFiles,
    machine: Machine,
}

/// How the interpreter's thread ended ([`Stream::finish`]).
#[derive(Debug)]
pub struct Finished {
    /// Blocks the interpreter ran.
    pub blocks_executed: u64,
    /// The first save of the persistent variables that failed (later ones were still tried).
    pub store_error: Option<io::Error>,
}

/// What the pipeline's thread runs: a program's stream, handed over a batch at a time. The ISO
/// [`Interpreter`](crate::Interpreter) is one; a [`Run`](crate::interp::Run) of any other
/// dialect's [`FrontEnd`](crate::interp::FrontEnd) is another.
pub trait BatchSource: Send + 'static {
    /// Appends the next items to `out` until it holds at least `at_least` (or a long stretch
    /// of blocks made nothing); false when nothing more will come.
    fn next_batch(&mut self, out: &mut Vec<Item>, at_least: usize) -> bool;

    /// [`BatchSource::next_batch`] with `check` asked of the items as the blocks release them:
    /// when it stops the program at an item, no block after it runs.
    fn next_batch_checked<C: ReleasedCheck>(
        &mut self,
        out: &mut Vec<Item>,
        at_least: usize,
        check: &mut C,
    ) -> bool;

    /// Blocks run so far.
    fn blocks_executed(&self) -> u64;

    /// How many times the persistent variables were written so far (none in a dialect without
    /// them).
    fn persistent_writes(&self) -> u64 {
        0
    }

    /// The persistent variables now.
    fn persistent_variables(&self) -> PersistentVariables {
        PersistentVariables::default()
    }
}

impl<B: BlockSource<Line = LineBlocks> + Send + 'static> BatchSource for Interpreter<B> {
    fn next_batch(&mut self, out: &mut Vec<Item>, at_least: usize) -> bool {
        Interpreter::next_batch(self, out, at_least)
    }

    fn next_batch_checked<C: ReleasedCheck>(
        &mut self,
        out: &mut Vec<Item>,
        at_least: usize,
        check: &mut C,
    ) -> bool {
        Interpreter::next_batch_checked(self, out, at_least, check)
    }

    fn blocks_executed(&self) -> u64 {
        Interpreter::blocks_executed(self)
    }

    fn persistent_writes(&self) -> u64 {
        Interpreter::persistent_writes(self)
    }

    fn persistent_variables(&self) -> PersistentVariables {
        Interpreter::persistent_variables(self)
    }
}

impl<F: FrontEnd + Send + 'static> BatchSource for crate::interp::Run<F> {
    fn next_batch(&mut self, out: &mut Vec<Item>, at_least: usize) -> bool {
        crate::interp::Run::next_batch(self, out, at_least)
    }

    fn next_batch_checked<C: ReleasedCheck>(
        &mut self,
        out: &mut Vec<Item>,
        at_least: usize,
        check: &mut C,
    ) -> bool {
        crate::interp::Run::next_batch_checked(self, out, at_least, check)
    }

    fn blocks_executed(&self) -> u64 {
        crate::interp::Run::blocks_executed(self)
    }
}

/// What the pipeline's thread is started with.
pub(crate) struct Started<S> {
    pub(crate) source: S,
    /// Where the persistent variables are saved, if anywhere.
    pub(crate) store: Option<Box<dyn PersistentStore>>,
    pub(crate) files: ProgramFiles,
    pub(crate) machine: Machine,
}

impl Stream {
    /// Starts `run`'s interpreter on a thread of its own, as `layout` says.
    pub(crate) fn spawn<S: BatchSource>(started: Started<S>, layout: Layout) -> Stream {
        let Started {
            source: mut interpreter,
            store,
            files,
            machine,
        } = started;
        let (sender, batches) = sync_channel::<Vec<Item>>(POOL);
        let (recycle, recycled) = sync_channel::<Vec<Item>>(POOL);
        for _ in 0..POOL {
            let _ = recycle.try_send(Vec::with_capacity(BATCH + 64));
        }
        let blocks = Arc::new(AtomicU64::new(0));
        let counter = Arc::clone(&blocks);
        let mut travel = TravelCheck::new(&machine);
        let stopping = layout.stopping;
        let thread = std::thread::spawn(move || {
            let mut saver = Saver::new(&interpreter, store);
            let pool = Pool {
                sender,
                recycled,
                counter,
            };
            // Each way of stopping has a copy of the loop of its own, so that the batch check,
            // the common one, is compiled as if it were the only one.
            match stopping {
                Stopping::AtTheBlock => pool.serve(&mut interpreter, &mut saver, |i, batch| {
                    i.next_batch_checked(batch, BATCH, &mut travel)
                }),
                Stopping::AfterTheBatch => pool.serve(&mut interpreter, &mut saver, |i, batch| {
                    let more = i.next_batch(batch, BATCH);
                    travel.check_batch(batch) && more
                }),
            }
            saver.save(&interpreter);
            saver.into_error()
        });
        Stream {
            items: VecDeque::new(),
            batches: Some(batches),
            recycle,
            waiter: Waiter::new(layout.waiting),
            blocks,
            thread: Some(thread),
            files,
            machine,
        }
    }

    /// The next batch of items, whole, in the buffer the interpreter filled (None once the
    /// stream has ended). Give the buffer back with [`Stream::recycle`] when done with it: the
    /// interpreter has only a few of them, and waits for one to fill.
    pub fn next_batch(&mut self) -> Option<Vec<Item>> {
        if !self.items.is_empty() {
            return Some(Vec::from(std::mem::take(&mut self.items)));
        }
        match self.waiter.receive(self.batches.as_ref()?) {
            Ok(batch) => Some(batch),
            Err(_) => {
                self.batches = None;
                None
            }
        }
    }

    /// Gives a batch's buffer back to the interpreter.
    pub fn recycle(&self, batch: Vec<Item>) {
        let _ = self.recycle.try_send(batch);
    }

    /// Gives every batch to `consume` with the planner's timing of each of its items, in order,
    /// until the stream ends or `consume` returns false. The planner runs on this thread and
    /// never copies a segment: the batches wait in the interpreter's buffers until their
    /// timings are final.
    pub fn for_each_timed(
        &mut self,
        options: PlanOptions,
        consume: impl FnMut(&[Item], &[Timing]) -> bool,
    ) {
        let timeline = Timeline::new(&self.machine, options);
        planned::for_each_timed(self, timeline, consume);
    }

    /// Blocks the interpreter has run so far (all of them once the stream has ended).
    pub fn blocks_executed(&self) -> u64 {
        self.blocks.load(Ordering::Acquire)
    }

    /// The files of the run, for diagnostics: the main program and those it called so far.
    pub fn files(&self) -> &ProgramFiles {
        &self.files
    }

    /// The machine the program runs on.
    pub fn machine(&self) -> &Machine {
        &self.machine
    }

    /// Ends the stream (the interpreter stops where it is, if it has not ended) and waits for
    /// the interpreter's thread: its last save of the persistent variables is done.
    pub fn finish(mut self) -> Finished {
        let store_error = self.stop();
        Finished {
            blocks_executed: self.blocks_executed(),
            store_error,
        }
    }

    /// Tells the interpreter's thread to end and waits for it.
    fn stop(&mut self) -> Option<io::Error> {
        // Without its receiver the thread's next send fails, and without the recycling sender
        // its wait for an empty buffer does: either way it ends, saving the variables. (Keeping
        // the sender alive here left a thread that had filled the whole pool waiting for ever.)
        self.batches = None;
        let (orphan, _) = sync_channel(0);
        drop(std::mem::replace(&mut self.recycle, orphan));
        self.thread.take()?.join().ok().flatten()
    }
}

impl Iterator for Stream {
    type Item = Item;

    fn next(&mut self) -> Option<Item> {
        loop {
            if let Some(item) = self.items.pop_front() {
                return Some(item);
            }
            let batch = self.waiter.receive(self.batches.as_ref()?);
            // The emptied buffer goes back; converting between Vec and VecDeque moves nothing.
            let empty = Vec::from(std::mem::take(&mut self.items));
            let _ = self.recycle.try_send(empty);
            match batch {
                Ok(batch) => self.items = VecDeque::from(batch),
                Err(_) => {
                    self.batches = None;
                    return None;
                }
            }
        }
    }
}

impl Drop for Stream {
    fn drop(&mut self) {
        self.stop();
    }
}

impl planned::BatchSource for Stream {
    fn next_batch(&mut self) -> Option<Vec<Item>> {
        Stream::next_batch(self)
    }

    fn recycle(&self, batch: Vec<Item>) {
        Stream::recycle(self, batch);
    }
}

/// The interpreter's side of the pool of batch buffers.
struct Pool {
    sender: SyncSender<Vec<Item>>,
    recycled: Receiver<Vec<Item>>,
    counter: Arc<AtomicU64>,
}

impl Pool {
    /// Fills the buffers that come back with `fill` (the interpreter's next batch, travel
    /// checked; false when nothing more will come) and sends them, until the stream ends or the
    /// consumer is gone.
    fn serve<S: BatchSource>(
        self,
        interpreter: &mut S,
        saver: &mut Saver,
        mut fill: impl FnMut(&mut S, &mut Vec<Item>) -> bool,
    ) {
        // A batch can come back empty (a macro loop that does not move): its buffer is kept
        // for the next one, so the pool never runs dry.
        let mut spare = None;
        while let Some(mut batch) = spare.take().or_else(|| self.recycled.recv().ok()) {
            batch.clear();
            let more = fill(interpreter, &mut batch);
            self.counter
                .store(interpreter.blocks_executed(), Ordering::Release);
            if saver.due() {
                saver.save(interpreter);
            }
            if batch.is_empty() {
                spare = Some(batch);
            } else if self.sender.send(batch).is_err() {
                break;
            }
            if !more {
                break;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::program::iso_program_lines;
    use super::super::{Parsing, Waiting};
    use super::*;
    use crate::interp::{Interpreter, LoadedFiles, Options};
    use crate::source::FileId;
    use std::time::Duration;

    #[test]
    fn dropping_the_stream_early_ends_the_interpreter_thread() {
        // Many more segments than the pool of batches holds, so the thread fills every buffer
        // and waits for an empty one: `vcnc trace | head` stops reading just like this.
        let mut text = String::from("G21 G90 G94 F1000\n");
        for i in 0..20_000 {
            text.push_str(&format!("G01 X{}. Y{}.\n", i % 100, i % 37));
        }
        text.push_str("M30\n");
        let machine = Machine::default();
        let blocks = iso_program_lines(
            Box::new(std::io::Cursor::new(text.into_bytes())),
            0,
            machine.profile.syntax(),
            Parsing::Ahead,
        );
        let interpreter = Interpreter::from_blocks(blocks, FileId(0), &machine, Options::default());
        let files = ProgramFiles::new("long.nc".into(), LoadedFiles::default());
        let layout = Layout {
            parsing: Parsing::Ahead,
            waiting: Waiting::Adaptive,
            stopping: Stopping::AtTheBlock,
        };
        let started = Started {
            source: interpreter,
            store: None,
            files,
            machine,
        };
        let mut stream = Stream::spawn(started, layout);
        assert!(matches!(stream.next(), Some(Ok(_))));
        // Time for the thread to fill the pool and block.
        std::thread::sleep(Duration::from_millis(300));
        let (done, dropped) = sync_channel(1);
        std::thread::spawn(move || {
            drop(stream);
            let _ = done.send(());
        });
        assert!(
            dropped.recv_timeout(Duration::from_secs(10)).is_ok(),
            "dropping the stream waited for ever on the interpreter thread"
        );
    }
}
