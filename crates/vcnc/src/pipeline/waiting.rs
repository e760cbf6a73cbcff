//! How the consumer waits for the interpreter's next batch.
//!
//! Spinning (trying again, yielding the processor between tries) spares the interpreter's
//! thread the system call that wakes a sleeping consumer.
//!
//! Never spins longer than [`SPIN`] a wait.

use std::sync::mpsc::{Receiver, RecvError, TryRecvError};
use std::time::{Duration, Instant};

/// How the consumer of the interpreter's batches waits for the next one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Waiting {
    /// Spinning a little before it sleeps: for a consumer with a core of its own that is a
    /// little faster than the interpreter, so that the interpreter never has to wake it (a
    /// system call on the slower thread for each batch).
    Adaptive,
    /// Asleep at once: for a consumer that does little, whose spinning would take a core from
    /// the parser's and the interpreter's threads.
    Sleep,
}

/// How long a consumer that spins spins before it sleeps: longer than the interpreter takes
/// for a batch of a CAM program, so that it sleeps only when the interpreter is held up.
const SPIN: Duration = Duration::from_micros(200);

/// A consumer's way of waiting.
#[derive(Debug)]
pub(crate) struct Waiter {
    waiting: Waiting,
}

impl Waiter {
    pub(crate) fn new(waiting: Waiting) -> Waiter {
        Waiter { waiting }
    }

    /// The next value of `channel`, waited for as the consumer's [`Waiting`] says.
    pub(crate) fn receive<T>(&mut self, channel: &Receiver<T>) -> Result<T, RecvError> {
        if self.waiting == Waiting::Sleep {
            return channel.recv();
        }
        let start = Instant::now();
        loop {
            match channel.try_recv() {
                Ok(value) => return Ok(value),
                Err(TryRecvError::Disconnected) => return Err(RecvError),
                Err(TryRecvError::Empty) => {}
            }
            if start.elapsed() > SPIN {
                return channel.recv();
            }
            // Yielding, not a busy loop: on a machine whose cores all have work, the processor
            // goes to whoever can use it; on an idle core the call returns at once.
            std::thread::yield_now();
        }
    }
}
