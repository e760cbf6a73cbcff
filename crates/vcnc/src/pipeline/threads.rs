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

use super::balance::{Balance, Busy, Telling};
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
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc::{sync_channel, Receiver, SyncSender};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::Instant;

/// Segments per batch taken from the interpreter: small, so that the pool stays in the caches.
pub(crate) const BATCH: usize = 256;

/// Batch buffers in circulation between the interpreter's thread and the consumer. A consumer
/// that keeps batches (the timed view) keeps fewer than this, so that the interpreter always
/// has one to fill; eight, not four, because the planner holds two or three batches for its
/// look-ahead and the interpreter, often the slower thread, must not wait for a buffer.
pub(crate) const POOL: usize = 8;

/// A program being interpreted, on a thread of its own or between the consumer's batches: its
/// items one at a time (an iterator), or a batch at a time in the buffers the interpreter
/// filled.
pub struct Stream {
    /// The current batch; its front is the next item.
    items: VecDeque<Item>,
    interpreter: Interpreting,
    recycle: SyncSender<Vec<Item>>,
    waiter: Waiter,
    balance: Balance,
    blocks: Arc<AtomicU64>,
    files: ProgramFiles,
    machine: Machine,
}

/// Where the interpreter is.
enum Interpreting {
    /// On a thread of its own, sending its batches; `hand_back` asks it to come back to the
    /// consumer's thread after the batch it is making.
    Apart {
        batches: Receiver<Vec<Item>>,
        hand_back: Arc<AtomicBool>,
        /// The thread's working time.
        busy: Arc<Busy>,
        thread: JoinHandle<Handed>,
    },
    /// On the consumer's thread, with the pool's empty buffers.
    Here {
        fill: Box<dyn Fill>,
        recycled: Receiver<Vec<Item>>,
    },
    /// Ended (or told to), with the first failed save of the persistent variables.
    Ended(Option<io::Error>),
}

/// What the interpreter's thread gives back when it ends.
enum Handed {
    /// The stream ended, or the consumer went: the first failed save.
    Ended(Option<io::Error>),
    /// Asked to come back, the interpreter and the pool's empty buffers.
    Back(Box<dyn Fill>, Receiver<Vec<Item>>),
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
            source,
            store,
            files,
            machine,
        } = started;
        let (recycle, recycled) = sync_channel::<Vec<Item>>(POOL);
        for _ in 0..POOL {
            let _ = recycle.try_send(Vec::with_capacity(BATCH + 64));
        }
        let blocks = Arc::new(AtomicU64::new(0));
        let saver = Saver::new(&source, store);
        let mut travel = TravelCheck::new(&machine);
        // Each way of stopping has a copy of the loop of its own, so that the batch check, the
        // common one, is compiled as if it were the only one.
        let fill: Box<dyn Fill> = match layout.stopping {
            Stopping::AtTheBlock => Filling::boxed(source, saver, &blocks, move |i, batch| {
                i.next_batch_checked(batch, BATCH, &mut travel)
            }),
            Stopping::AfterTheBatch => Filling::boxed(source, saver, &blocks, move |i, batch| {
                let more = i.next_batch(batch, BATCH);
                travel.check_batch(batch) && more
            }),
        };
        Stream {
            items: VecDeque::new(),
            interpreter: apart(fill, recycled),
            recycle,
            waiter: Waiter::new(layout.waiting),
            balance: Balance::new(layout.threads),
            blocks,
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
        self.receive()
    }

    /// The interpreter's next batch, from its thread or made here.
    fn receive(&mut self) -> Option<Vec<Item>> {
        loop {
            match &mut self.interpreter {
                Interpreting::Apart {
                    batches,
                    hand_back,
                    busy,
                    ..
                } => match self.waiter.receive(batches) {
                    Ok(batch) => {
                        if !hand_back.load(Ordering::Relaxed) && self.balance.apart(busy) {
                            hand_back.store(true, Ordering::Relaxed);
                        }
                        return Some(batch);
                    }
                    // The thread ended, or came back as asked.
                    Err(_) => self.join(),
                },
                Interpreting::Here { fill, recycled } => {
                    let mut batch = recycled
                        .try_recv()
                        .unwrap_or_else(|_| Vec::with_capacity(BATCH + 64));
                    batch.clear();
                    let start = Instant::now();
                    let mut more = true;
                    while more && batch.is_empty() {
                        more = fill.fill(&mut batch);
                    }
                    let took = start.elapsed();
                    if !more {
                        self.end_here();
                    } else if self.balance.here(took) {
                        self.go_apart();
                    }
                    if !batch.is_empty() {
                        return Some(batch);
                    }
                }
                Interpreting::Ended(_) => return None,
            }
        }
    }

    /// Waits for the interpreter's thread, which ended or came back.
    fn join(&mut self) {
        let interpreter = std::mem::replace(&mut self.interpreter, Interpreting::Ended(None));
        let Interpreting::Apart { thread, .. } = interpreter else {
            self.interpreter = interpreter;
            return;
        };
        self.interpreter = match thread.join() {
            Ok(Handed::Back(fill, recycled)) => {
                self.balance.changed();
                Interpreting::Here { fill, recycled }
            }
            Ok(Handed::Ended(error)) => Interpreting::Ended(error),
            // The interpreter's panic is the consumer's, as it would be on one thread: a stream
            // that only ended would read as a program that ended.
            Err(panic) if !std::thread::panicking() => std::panic::resume_unwind(panic),
            Err(_) => Interpreting::Ended(None),
        };
    }

    /// Ends the interpreter running on this thread: its last save.
    fn end_here(&mut self) {
        let interpreter = std::mem::replace(&mut self.interpreter, Interpreting::Ended(None));
        self.interpreter = match interpreter {
            Interpreting::Here { fill, .. } => Interpreting::Ended(fill.end()),
            other => other,
        };
    }

    /// Gives the interpreter running on this thread a thread of its own again.
    fn go_apart(&mut self) {
        let interpreter = std::mem::replace(&mut self.interpreter, Interpreting::Ended(None));
        self.interpreter = match interpreter {
            Interpreting::Here { fill, recycled } => {
                self.balance.changed();
                apart(fill, recycled)
            }
            other => other,
        };
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

    /// Tells the interpreter to end, waits for its thread, and gives its first failed save.
    fn stop(&mut self) -> Option<io::Error> {
        if let Interpreting::Apart { batches, .. } = &mut self.interpreter {
            // Without its receiver the thread's next send fails, and without the recycling
            // sender its wait for an empty buffer does: either way it ends, saving the
            // variables. (Keeping the sender alive here left a thread that had filled the whole
            // pool waiting for ever.)
            let (_, orphan) = sync_channel(0);
            drop(std::mem::replace(batches, orphan));
            let (orphan, _) = sync_channel(0);
            drop(std::mem::replace(&mut self.recycle, orphan));
            self.join();
        }
        self.end_here();
        match std::mem::replace(&mut self.interpreter, Interpreting::Ended(None)) {
            Interpreting::Ended(error) => error,
            _ => None,
        }
    }
}

/// Starts `fill` on a thread of its own, with the pool's empty buffers.
fn apart(fill: Box<dyn Fill>, recycled: Receiver<Vec<Item>>) -> Interpreting {
    let (sender, batches) = sync_channel::<Vec<Item>>(POOL);
    let hand_back = Arc::new(AtomicBool::new(false));
    let busy = Arc::new(Busy::new());
    let thread = {
        let (hand_back, busy) = (Arc::clone(&hand_back), Arc::clone(&busy));
        std::thread::spawn(move || serve(fill, recycled, &sender, &hand_back, &busy))
    };
    Interpreting::Apart {
        batches,
        hand_back,
        busy,
        thread,
    }
}

impl Iterator for Stream {
    type Item = Item;

    fn next(&mut self) -> Option<Item> {
        loop {
            if let Some(item) = self.items.pop_front() {
                return Some(item);
            }
            let batch = self.receive()?;
            // The emptied buffer goes back; converting between Vec and VecDeque moves nothing.
            let empty = Vec::from(std::mem::replace(&mut self.items, VecDeque::from(batch)));
            let _ = self.recycle.try_send(empty);
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

/// The interpreter's side of a run, wherever it runs: it fills a batch and checks its travel,
/// counts the blocks, and saves the persistent variables when due.
trait Fill: Send {
    /// Fills `batch` (empty); false when nothing more will come.
    fn fill(&mut self, batch: &mut Vec<Item>) -> bool;

    /// The interpreter has ended, or is told to: the last save, and the first that failed.
    fn end(self: Box<Self>) -> Option<io::Error>;
}

/// A [`Fill`] of a source `S` whose batch is made and checked by `F`.
struct Filling<S, F> {
    source: S,
    saver: Saver,
    counter: Arc<AtomicU64>,
    make: F,
}

impl<S, F> Filling<S, F>
where
    S: BatchSource,
    F: FnMut(&mut S, &mut Vec<Item>) -> bool + Send + 'static,
{
    fn boxed(source: S, saver: Saver, counter: &Arc<AtomicU64>, make: F) -> Box<dyn Fill> {
        Box::new(Filling {
            source,
            saver,
            counter: Arc::clone(counter),
            make,
        })
    }
}

impl<S, F> Fill for Filling<S, F>
where
    S: BatchSource,
    F: FnMut(&mut S, &mut Vec<Item>) -> bool + Send,
{
    fn fill(&mut self, batch: &mut Vec<Item>) -> bool {
        let more = (self.make)(&mut self.source, batch);
        self.counter
            .store(self.source.blocks_executed(), Ordering::Release);
        if self.saver.due() {
            self.saver.save(&self.source);
        }
        more
    }

    fn end(mut self: Box<Self>) -> Option<io::Error> {
        self.saver.save(&self.source);
        self.saver.into_error()
    }
}

/// The interpreter's thread: fills the buffers that come back and sends them, until the stream
/// ends, the consumer is gone, or `hand_back` asks it back to the consumer's thread. Tells its
/// CPU time in `busy` now and then.
fn serve(
    mut fill: Box<dyn Fill>,
    recycled: Receiver<Vec<Item>>,
    sender: &SyncSender<Vec<Item>>,
    hand_back: &AtomicBool,
    busy: &Busy,
) -> Handed {
    // A batch can come back empty (a macro loop that does not move): its buffer is kept for
    // the next one, so the pool never runs dry.
    let mut spare = None;
    let mut telling = Telling::new(busy);
    while let Some(mut batch) = spare.take().or_else(|| recycled.recv().ok()) {
        batch.clear();
        let more = fill.fill(&mut batch);
        telling.batch_made(busy);
        if batch.is_empty() {
            spare = Some(batch);
        } else if sender.send(batch).is_err() {
            break;
        }
        if !more {
            break;
        }
        if spare.is_none() && hand_back.load(Ordering::Relaxed) {
            return Handed::Back(fill, recycled);
        }
    }
    Handed::Ended(fill.end())
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
            threads: super::super::Threads::Two,
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

    /// A loop of `moves` feed moves, which the interpreter makes one pass at a time.
    fn macro_loop(moves: u32) -> String {
        format!(
            "G21 G90 G94 F1000\n#1=0\nWHILE[#1LT{moves}]DO1\nG1 X[#1 MOD 100] Y[#1 MOD 37]\n\
             #1=#1+1\nEND1\nM30\n"
        )
    }

    fn layout(threads: super::super::Threads) -> Layout {
        Layout {
            threads,
            parsing: Parsing::InLine,
            waiting: Waiting::Sleep,
            stopping: Stopping::AfterTheBatch,
        }
    }

    #[test]
    fn the_interpreter_comes_to_a_waiting_consumer_and_goes_back_to_a_busy_one() {
        use super::super::{Pipeline, Threads};
        let machine = Machine::default();
        let text = macro_loop(300_000);
        let mut two = Pipeline::new(&machine)
            .layout(layout(Threads::Two))
            .open_text(&text, "loop.nc");
        let two_items: Vec<_> = two.by_ref().collect();
        let two_blocks = two.finish().blocks_executed;
        let mut stream = Pipeline::new(&machine)
            .layout(layout(Threads::Balanced))
            .open_text(&text, "loop.nc");
        let mut balanced = Vec::new();
        while let Some(batch) = stream.next_batch() {
            balanced.extend(batch.iter().cloned());
            stream.recycle(batch);
            if stream.balance.changes() == 1 {
                // Busy now: about as long a batch as the interpreter takes for it.
                std::thread::sleep(Duration::from_millis(2));
            }
        }
        let changes = stream.balance.changes();
        let finished = stream.finish();
        assert_eq!(balanced, two_items, "the same stream on one thread and two");
        assert_eq!(finished.blocks_executed, two_blocks);
        // To the consumer's thread while it waits, back to its own when the consumer works.
        assert!(changes >= 2, "{changes} changes of layout");
    }

    #[test]
    fn a_stream_dropped_while_its_interpreter_runs_on_the_consumers_thread_ends() {
        use super::super::{Pipeline, Threads};
        let machine = Machine::default();
        let mut stream = Pipeline::new(&machine)
            .layout(layout(Threads::Balanced))
            .open_text(macro_loop(1_000_000), "loop.nc");
        while stream.balance.changes() == 0 {
            let batch = stream.next_batch().expect("a long program");
            stream.recycle(batch);
        }
        assert!(matches!(stream.interpreter, Interpreting::Here { .. }));
        assert!(stream.next().is_some());
        let finished = stream.finish();
        assert!(finished.blocks_executed < 3 * 1_000_000);
    }

    /// Nine batches of a warning each, then a panic.
    struct Panicking(u32);

    impl BatchSource for Panicking {
        fn next_batch(&mut self, out: &mut Vec<Item>, _at_least: usize) -> bool {
            self.0 += 1;
            assert!(self.0 < 10, "an interpreter's bug");
            out.push(Ok(crate::motion::Item::Warning(
                crate::alarm::Alarm::warning(
                    crate::alarm::AlarmCode::NotSupportedYet,
                    crate::source::Span::default(),
                    "a warning",
                ),
            )));
            true
        }

        fn next_batch_checked<C: ReleasedCheck>(
            &mut self,
            out: &mut Vec<Item>,
            at_least: usize,
            _check: &mut C,
        ) -> bool {
            self.next_batch(out, at_least)
        }

        fn blocks_executed(&self) -> u64 {
            u64::from(self.0)
        }
    }

    #[test]
    fn a_panic_of_the_interpreter_is_the_consumers_on_either_thread() {
        for threads in [super::super::Threads::Two, super::super::Threads::Balanced] {
            let started = Started {
                source: Panicking(0),
                store: None,
                files: ProgramFiles::new("bug.nc".into(), LoadedFiles::default()),
                machine: Machine::default(),
            };
            let stream = Stream::spawn(started, layout(threads));
            let consumed =
                std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| stream.count()));
            assert!(
                consumed.is_err(),
                "{threads:?}: the stream ended as if the program had"
            );
        }
    }
}
