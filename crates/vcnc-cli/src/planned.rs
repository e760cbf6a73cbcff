//! The planner on a thread of its own, handing timed segments over in batches.
//!
//! Reading, interpreting and planning then overlap with whatever the consumer does with the
//! timed segments (formatting a trace, adding up a summary) on the other core. A fixed pool of
//! batch buffers goes round between the two threads: no allocation after the start, bounded
//! memory.

use crate::program::Interpreted;
use std::sync::mpsc::{sync_channel, Receiver, SyncSender};
use std::thread::JoinHandle;
use vcnc::plan::{PlanOptions, Planner, TimedSegment};
use vcnc::{Alarm, Machine};

/// What the planner thread hands over: a timed segment or an alarm.
pub(crate) type Item = Result<TimedSegment, Alarm>;

/// Timed segments per batch. Small enough that the batches in circulation stay in the
/// processors' caches (a timed segment is a few hundred bytes: 4096 of them were 1.5 MB a
/// batch, read back from memory by the other core), large enough that handing them over costs
/// nothing per segment.
const BATCH: usize = 512;

/// Batch buffers in circulation between the two threads.
const POOL: usize = 4;

/// A planner running on its own thread.
pub(crate) struct PlannedBatches {
    batches: Receiver<Vec<Item>>,
    recycle: SyncSender<Vec<Item>>,
    thread: JoinHandle<Interpreted>,
}

impl PlannedBatches {
    /// Starts planning `stream` for `machine`.
    pub(crate) fn spawn(
        stream: Interpreted,
        machine: &Machine,
        options: PlanOptions,
    ) -> PlannedBatches {
        let (sender, batches) = sync_channel::<Vec<Item>>(POOL);
        let (recycle, recycled) = sync_channel::<Vec<Item>>(POOL);
        for _ in 0..POOL {
            let _ = recycle.try_send(Vec::with_capacity(BATCH));
        }
        let mut planner = Planner::new(stream, machine, options);
        let thread = std::thread::spawn(move || {
            while let Ok(mut batch) = recycled.recv() {
                batch.clear();
                batch.extend(planner.by_ref().take(BATCH));
                let more = batch.len() == BATCH;
                if sender.send(batch).is_err() || !more {
                    break;
                }
            }
            planner.into_source()
        });
        PlannedBatches {
            batches,
            recycle,
            thread,
        }
    }

    /// Gives every batch to `consume`, in order, until the stream ends or `consume` returns
    /// false; then stops the planner and returns the interpreter's stream (to ask it how many
    /// blocks it ran).
    pub(crate) fn for_each(self, mut consume: impl FnMut(&[Item]) -> bool) -> Interpreted {
        let PlannedBatches {
            batches,
            recycle,
            thread,
        } = self;
        for batch in &batches {
            let go_on = consume(&batch);
            let _ = recycle.try_send(batch);
            if !go_on {
                break;
            }
        }
        // With both channel ends gone, the planner thread's next send or receive fails and it
        // ends.
        drop(batches);
        drop(recycle);
        match thread.join() {
            Ok(stream) => stream,
            Err(panic) => std::panic::resume_unwind(panic),
        }
    }
}
