//! How the consumer waits for the interpreter's next batch.
//!
//! Spinning (trying again, yielding the processor between tries) spares the interpreter's
//! thread the system call that wakes a sleeping consumer: worth it when the consumer is the
//! slower side and waits only now and then, briefly. When the interpreter is the slower side
//! the consumer would spin through most of every wait and burn a core doing nothing. So the
//! spinning is paid from a budget the consumer earns by working: a sixteenth of its time
//! between waits, kept up to a few full spins. A wait beyond the budget naps (sleeps for a
//! set time and looks again), so that the interpreter's thread need not wake it, and after two
//! naps sleeps until the batch comes; after a wait longer than the naps, the next one sleeps at
//! once.
//!
//! Never spins beyond its budget, and never reads the clock when a batch is ready.

use std::sync::mpsc::{Receiver, RecvError, TryRecvError};
use std::time::{Duration, Instant};

/// How the consumer of the interpreter's batches waits for the next one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Waiting {
    /// Spinning a little before it sleeps, as long as the spinning stays a small share of the
    /// consumer's own working time: for a consumer that keeps a core busy (planning,
    /// writing), whether the interpreter or the consumer is the slower side.
    Adaptive,
    /// Asleep at once: for a consumer that does little, whose spinning would take a core from
    /// the parser's and the interpreter's threads.
    Sleep,
}

/// The longest spin of one wait: longer than the interpreter takes for a batch of a CAM
/// program, so that a consumer with budget sleeps only when the interpreter is held up.
const SPIN: Duration = Duration::from_micros(200);

/// The consumer may spin for one part in this many of its working time.
const SHARE: u32 = 16;

/// The most spinning budget kept: a consumer that worked long without waiting does not then
/// spin through a long stretch of waits.
const MOST_BUDGET: Duration = Duration::from_millis(1);

/// The first nap of a wait beyond the spinning budget: about two batches of a CAM program.
const FIRST_NAP: Duration = Duration::from_micros(100);

/// Naps, each twice as long as the one before, before the consumer sleeps until the batch
/// comes: after 0.3 ms the interpreter is held up by more than a few batches' work, and one
/// wake-up a batch no longer counts, while a nap a batch would.
const NAPS: u32 = 2;

/// A wait longer than the naps (100 and 200 µs): the next one sleeps until the batch comes
/// without napping first.
const NAPPING: Duration = Duration::from_micros(300);

/// A consumer's way of waiting, with its spinning budget.
#[derive(Debug)]
pub(crate) struct Waiter {
    waiting: Waiting,
    budget: Duration,
    /// How long the last wait took.
    last_wait: Duration,
    /// When the last wait ended: the consumer has worked since (a batch that was ready at once
    /// is no wait).
    last_wait_ended: Instant,
}

impl Waiter {
    pub(crate) fn new(waiting: Waiting) -> Waiter {
        Waiter {
            waiting,
            budget: Duration::ZERO,
            last_wait: Duration::ZERO,
            last_wait_ended: Instant::now(),
        }
    }

    /// The next value of `channel`, waited for as the consumer's [`Waiting`] says.
    #[inline]
    pub(crate) fn receive<T>(&mut self, channel: &Receiver<T>) -> Result<T, RecvError> {
        if self.waiting == Waiting::Sleep {
            return channel.recv();
        }
        match channel.try_recv() {
            Ok(value) => Ok(value),
            Err(TryRecvError::Disconnected) => Err(RecvError),
            Err(TryRecvError::Empty) => self.wait(channel),
        }
    }

    /// Waits for a value that is not there yet: spins while the budget lasts, then naps, then
    /// sleeps until it comes.
    #[inline(never)]
    fn wait<T>(&mut self, channel: &Receiver<T>) -> Result<T, RecvError> {
        let start = Instant::now();
        let spin = self.spin_allowed(start);
        loop {
            let spun = start.elapsed();
            if spun >= spin {
                self.budget = self.budget.saturating_sub(spun);
                // Napping pays while waits are short; a long wait costs the interpreter one
                // wake-up, which is little beside it, and naps would cost the consumer more.
                let value = if self.last_wait < NAPPING {
                    nap_then_sleep(channel)
                } else {
                    channel.recv()
                };
                self.last_wait_ended = Instant::now();
                self.last_wait = self.last_wait_ended - start;
                return value;
            }
            // Yielding, not a busy loop: on a machine whose cores all have work, the processor
            // goes to whoever can use it; on an idle core the call returns at once.
            std::thread::yield_now();
            match channel.try_recv() {
                Ok(value) => {
                    let spun = start.elapsed();
                    self.budget = self.budget.saturating_sub(spun);
                    self.last_wait_ended = start + spun;
                    self.last_wait = spun;
                    return Ok(value);
                }
                Err(TryRecvError::Disconnected) => return Err(RecvError),
                Err(TryRecvError::Empty) => {}
            }
        }
    }

    /// How long the wait that starts at `start` may spin: the budget with what the work since
    /// the last wait earned, up to a full spin.
    fn spin_allowed(&mut self, start: Instant) -> Duration {
        let worked = start.saturating_duration_since(self.last_wait_ended);
        self.budget = (self.budget + worked / SHARE).min(MOST_BUDGET);
        self.budget.min(SPIN)
    }
}

/// The next value of `channel`, after naps of growing length and then asleep in `recv`. A
/// consumer asleep in `recv` costs the interpreter's thread, the slower one, a system call to
/// wake it for every batch; one that naps is never woken, and finds a batch or two ready when
/// it looks again (the pool has room for them).
fn nap_then_sleep<T>(channel: &Receiver<T>) -> Result<T, RecvError> {
    let mut nap = FIRST_NAP;
    for _ in 0..NAPS {
        std::thread::sleep(nap);
        match channel.try_recv() {
            Ok(value) => return Ok(value),
            Err(TryRecvError::Disconnected) => return Err(RecvError),
            Err(TryRecvError::Empty) => nap *= 2,
        }
    }
    channel.recv()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::mpsc::sync_channel;

    #[test]
    fn a_consumer_that_has_not_worked_sleeps_at_once() {
        let (sender, receiver) = sync_channel(1);
        let mut waiter = Waiter::new(Waiting::Adaptive);
        waiter.last_wait_ended = Instant::now() + Duration::from_secs(1);
        let late = std::thread::spawn(move || {
            std::thread::sleep(Duration::from_millis(20));
            sender.send(7).unwrap();
        });
        assert_eq!(waiter.receive(&receiver), Ok(7));
        assert_eq!(waiter.budget, Duration::ZERO);
        late.join().unwrap();
        assert_eq!(waiter.receive(&receiver), Err(RecvError));
    }

    #[test]
    fn spinning_is_a_sixteenth_of_the_work_at_most() {
        let mut waiter = Waiter::new(Waiting::Adaptive);
        let start = waiter.last_wait_ended + Duration::from_micros(3200);
        assert_eq!(waiter.spin_allowed(start), SPIN);
        waiter.last_wait_ended = start;
        waiter.budget = Duration::ZERO;
        assert_eq!(
            waiter.spin_allowed(start + Duration::from_micros(800)),
            Duration::from_micros(50)
        );
        // Budget saved up is kept to a few spins.
        waiter.last_wait_ended = start;
        waiter.spin_allowed(start + Duration::from_secs(1));
        assert_eq!(waiter.budget, MOST_BUDGET);
    }

    #[test]
    fn a_long_wait_spends_the_budget_then_naps_and_sleeps() {
        let (sender, receiver) = sync_channel(1);
        let mut waiter = Waiter::new(Waiting::Adaptive);
        waiter.budget = Duration::from_micros(100);
        let late = std::thread::spawn(move || {
            std::thread::sleep(Duration::from_millis(300));
            sender.send(7).unwrap();
        });
        waiter.last_wait_ended = Instant::now();
        assert_eq!(waiter.receive(&receiver), Ok(7));
        assert_eq!(waiter.budget, Duration::ZERO);
        late.join().unwrap();
    }

    #[test]
    fn a_ready_value_is_taken_without_waiting() {
        let (sender, receiver) = sync_channel(2);
        let mut waiter = Waiter::new(Waiting::Adaptive);
        let before = waiter.last_wait_ended;
        sender.send(1).unwrap();
        assert_eq!(waiter.receive(&receiver), Ok(1));
        assert_eq!(waiter.last_wait_ended, before, "no wait");
    }
}
