//! Which thread runs the interpreter: a thread of its own, or the consumer's.
//!
//! A thread of its own pays when the interpreter's work overlaps with enough other work: the
//! consumer's (planning, writing) and a parser thread's. When the rest of the run is small
//! beside the interpreter (a macro loop that moves a little each pass, a G12.1 contour cut into
//! short pieces, a check that only collects alarms), the second core would mostly wait, and each
//! batch would still cost a hand-over and a wake-up; then the interpreter runs on the consumer's
//! thread between its batches, and the run's CPU time is its wall time. The price is the rest
//! of the run's time, now added to the interpreter's: less than half of it, by the threshold.
//!
//! The balance is measured over windows of the run, as CPU time (which other threads and
//! processes taking turns on the cores do not change), and the layout follows it both ways,
//! with room between the two thresholds so that a balance near one of them does not go back
//! and forth. Never decides on the run's first windows, and reads the clock once every few
//! batches while the interpreter has a thread of its own.

use cpu_time::{ProcessTime, ThreadTime};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// Where the interpreter runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Threads {
    /// On a thread of its own, always.
    Two,
    /// On a thread of its own while the rest of the run's work is at least half the
    /// interpreter's, on the consumer's thread while it is less.
    Balanced,
}

/// Batches between two looks at the clock.
const LOOK_EVERY: u32 = 16;

/// The shortest window measured: many batches, so that one slow block does not count much.
const WINDOW: Duration = Duration::from_millis(20);

/// Windows measured with two threads before the run may go to one: the measure is an average
/// over them, each window weighing as much as all those before it, so that a moment's other
/// load on the machine does not decide. Each time the run comes back to two threads, twice as
/// many: a run whose measure strays below the threshold now and then is not taken there often.
const WINDOWS_TO_ONE: u32 = 3;

/// Windows measured with one thread before the run may go back to two: a measure that took it
/// to one thread wrongly costs little.
const WINDOWS_TO_TWO: u32 = 2;

/// The most windows [`WINDOWS_TO_ONE`] grows to (several seconds).
const MOST_WINDOWS: u32 = 256;

/// To one thread when the rest of the run's work is less than this share of the interpreter's
/// (one half), back to two when it is more than the second share (three fifths).
const TO_ONE: (u32, u32) = (1, 2);
const BACK_TO_TWO: (u32, u32) = (3, 5);

/// How often at most the interpreter's thread tells its CPU time: a system call, once every
/// few batches of a CAM program, and many times a window.
const TELL_EVERY: Duration = Duration::from_millis(1);

/// The CPU time of the interpreter's thread, as it last told it.
#[derive(Debug)]
pub(crate) struct Busy {
    /// Nanoseconds; [`Busy::NOT_TOLD`] before the first time.
    nanos: AtomicU64,
}

impl Busy {
    const NOT_TOLD: u64 = u64::MAX;

    pub(crate) fn new() -> Busy {
        Busy {
            nanos: AtomicU64::new(Busy::NOT_TOLD),
        }
    }

    /// Tells the CPU time of the calling thread, the interpreter's.
    pub(crate) fn tell(&self) {
        if let Ok(time) = ThreadTime::try_now() {
            let nanos = u64::try_from(time.as_duration().as_nanos()).unwrap_or(u64::MAX - 1);
            self.nanos.store(nanos, Ordering::Relaxed);
        }
    }

    fn time(&self) -> Option<Duration> {
        let nanos = self.nanos.load(Ordering::Relaxed);
        (nanos != Busy::NOT_TOLD).then(|| Duration::from_nanos(nanos))
    }
}

/// When the interpreter's thread tells its CPU time next.
#[derive(Debug)]
pub(crate) struct Telling(Instant);

impl Telling {
    pub(crate) fn new(busy: &Busy) -> Telling {
        busy.tell();
        Telling(Instant::now())
    }

    /// A batch was made: tells the thread's CPU time if it is time to.
    #[inline]
    pub(crate) fn batch_made(&mut self, busy: &Busy) {
        let now = Instant::now();
        if now.saturating_duration_since(self.0) >= TELL_EVERY {
            busy.tell();
            self.0 = now;
        }
    }
}

/// CPU times at a look, when the system tells them.
#[derive(Clone, Copy, Debug, Default)]
struct CpuTimes {
    /// The whole process's.
    process: Duration,
    /// The consumer's thread's.
    consumer: Duration,
    /// The interpreter's thread's, when it has one.
    interpreter: Option<Duration>,
}

impl CpuTimes {
    fn now(busy: Option<&Busy>) -> Option<CpuTimes> {
        Some(CpuTimes {
            process: ProcessTime::try_now().ok()?.as_duration(),
            consumer: ThreadTime::try_now().ok()?.as_duration(),
            interpreter: match busy {
                Some(busy) => Some(busy.time()?),
                None => None,
            },
        })
    }
}

/// The interpreter's work and the rest of the run's (the consumer's, a parser thread's), in a
/// window or on average.
#[derive(Clone, Copy, Debug, Default)]
struct Work {
    interpreter: Duration,
    rest: Duration,
}

impl Work {
    /// The average that gives `next` as much weight as all the windows before.
    fn halfway_to(self, next: Work) -> Work {
        Work {
            interpreter: (self.interpreter + next.interpreter) / 2,
            rest: (self.rest + next.rest) / 2,
        }
    }
}

/// The measure of a run's balance, window by window: the interpreter's work against the rest
/// of the run's. With two threads, the interpreter thread's CPU time against the rest of the
/// process's; with one, the time the interpreter takes of the consumer's thread against the
/// rest of that thread's time and the other threads' CPU time.
#[derive(Debug)]
pub(crate) struct Balance {
    threads: Threads,
    one_thread: bool,
    /// When the window began: None until the first look at the clock.
    start: Option<Instant>,
    batches: u32,
    /// In the window, one thread: the interpreter's time.
    interpreting: Duration,
    /// The threads' CPU times when the window began, two threads.
    cpu_at_start: Option<CpuTimes>,
    /// The consumer's and the interpreter's work, averaged over the windows so far.
    average: Work,
    windows: u32,
    /// Windows measured with two threads before the run may go to one.
    windows_to_one: u32,
    /// How many times the run changed its layout.
    changes: u32,
}

impl Balance {
    pub(crate) fn new(threads: Threads) -> Balance {
        Balance {
            threads,
            one_thread: false,
            start: None,
            batches: 0,
            interpreting: Duration::ZERO,
            cpu_at_start: None,
            average: Work::default(),
            windows: 0,
            windows_to_one: WINDOWS_TO_ONE,
            changes: 0,
        }
    }

    /// How many times the run changed its layout so far.
    #[cfg(test)]
    pub(crate) fn changes(&self) -> u32 {
        self.changes
    }

    /// A batch came from the interpreter's thread, whose CPU time `busy` tells. True when the
    /// interpreter should come to the consumer's thread.
    #[inline]
    pub(crate) fn apart(&mut self, busy: &Busy) -> bool {
        self.counted(Duration::ZERO) && self.look(Instant::now(), || CpuTimes::now(Some(busy)))
    }

    /// The interpreter made a batch on the consumer's thread in `took`. True when it should
    /// have a thread of its own again.
    #[inline]
    pub(crate) fn here(&mut self, took: Duration) -> bool {
        self.counted(took) && self.look(Instant::now(), || CpuTimes::now(None))
    }

    /// Adds a batch's time of interpreting (none with two threads); true when it is time to
    /// look at the clock.
    #[inline]
    fn counted(&mut self, interpreting: Duration) -> bool {
        if self.threads == Threads::Two {
            return false;
        }
        self.interpreting += interpreting;
        self.batches += 1;
        self.batches >= LOOK_EVERY
    }

    /// The decision at a look at the clock, `now`, with the CPU times of two threads.
    #[inline(never)]
    fn look(&mut self, now: Instant, cpu: impl FnOnce() -> Option<CpuTimes>) -> bool {
        self.batches = 0;
        let Some(start) = self.start else {
            self.restart(now, cpu());
            return false;
        };
        let elapsed = now.saturating_duration_since(start);
        if elapsed < WINDOW {
            return false;
        }
        let cpu = cpu();
        let work = self.cpu_at_start.zip(cpu).and_then(|(then, now)| {
            let process = now.process.saturating_sub(then.process);
            match (then.interpreter, now.interpreter) {
                (Some(before), Some(after)) => {
                    let interpreter = after.saturating_sub(before);
                    Some(Work {
                        interpreter,
                        rest: process.saturating_sub(interpreter),
                    })
                }
                (None, None) => {
                    let other_threads =
                        process.saturating_sub(now.consumer.saturating_sub(then.consumer));
                    Some(Work {
                        interpreter: self.interpreting,
                        rest: elapsed.saturating_sub(self.interpreting) + other_threads,
                    })
                }
                // A system that does not tell a thread's CPU time keeps two threads.
                _ => None,
            }
        });
        self.restart(now, cpu);
        let Some(work) = work else {
            return false;
        };
        self.average = match self.windows {
            0 => work,
            _ => self.average.halfway_to(work),
        };
        self.windows += 1;
        let Work { interpreter, rest } = self.average;
        match self.one_thread {
            false => {
                self.windows >= self.windows_to_one && rest * TO_ONE.1 < interpreter * TO_ONE.0
            }
            true => {
                self.windows >= WINDOWS_TO_TWO && rest * BACK_TO_TWO.1 > interpreter * BACK_TO_TWO.0
            }
        }
    }

    /// The run changed its layout: the next window measures the other one.
    pub(crate) fn changed(&mut self) {
        if self.one_thread {
            self.windows_to_one = (self.windows_to_one * 2).min(MOST_WINDOWS);
        }
        self.one_thread = !self.one_thread;
        self.changes += 1;
        self.start = None;
        self.batches = 0;
        self.windows = 0;
    }

    fn restart(&mut self, now: Instant, cpu: Option<CpuTimes>) {
        self.start = Some(now);
        self.interpreting = Duration::ZERO;
        self.cpu_at_start = cpu;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ms(n: u64) -> Duration {
        Duration::from_millis(n)
    }

    /// CPU times with the interpreter on a thread of its own.
    fn apart(process: u64, interpreter: u64) -> Option<CpuTimes> {
        Some(CpuTimes {
            process: ms(process),
            consumer: ms(process - interpreter),
            interpreter: Some(ms(interpreter)),
        })
    }

    /// CPU times with the interpreter on the consumer's thread.
    fn here(process: u64, consumer: u64) -> Option<CpuTimes> {
        Some(CpuTimes {
            process: ms(process),
            consumer: ms(consumer),
            interpreter: None,
        })
    }

    /// Looks every 30 ms from `t0` with the CPU times `cpu` gives for each look; the decisions.
    fn looks(balance: &mut Balance, cpu: impl Fn(u64) -> Option<CpuTimes>) -> Vec<bool> {
        let t0 = Instant::now();
        (0..=WINDOWS_TO_ONE as u64 + 1)
            .map(|n| balance.look(t0 + ms(30 * n), || cpu(n)))
            .collect()
    }

    #[test]
    fn two_threads_become_one_when_the_rest_works_less_than_half_as_long() {
        // Each window: the interpreter 28 ms of CPU, the consumer 13.
        let mut balance = Balance::new(Threads::Balanced);
        let decisions = looks(&mut balance, |n| apart(41 * n, 28 * n));
        assert_eq!(decisions, [false, false, false, true, true]);
        // The consumer 15: just over half.
        let mut balance = Balance::new(Threads::Balanced);
        assert!(!looks(&mut balance, |n| apart(43 * n, 28 * n)).contains(&true));
    }

    #[test]
    fn a_parser_threads_work_counts_with_the_consumers() {
        // The consumer 8 ms a window, a parser thread 10, the interpreter 28: the second core
        // has work, and taking the consumer's to the interpreter's core would cost more than
        // it saves.
        let mut balance = Balance::new(Threads::Balanced);
        assert!(!looks(&mut balance, |n| apart(46 * n, 28 * n)).contains(&true));
    }

    #[test]
    fn the_first_windows_do_not_decide_and_the_average_forgets() {
        let mut balance = Balance::new(Threads::Balanced);
        let t0 = Instant::now();
        assert!(!balance.look(t0, || apart(0, 0)), "the first look starts");
        assert!(
            !balance.look(t0 + ms(10), || apart(5, 5)),
            "too short a window"
        );
        // Two windows of an idle consumer, then a busy one: too few to decide.
        assert!(!balance.look(t0 + ms(30), || apart(30, 29)));
        assert!(!balance.look(t0 + ms(60), || apart(60, 58)));
        // The third, busy, brings the average (weights 1/4, 1/4, 1/2) over the half.
        assert!(!balance.look(t0 + ms(90), || apart(100, 72)));
    }

    #[test]
    fn one_thread_becomes_two_when_the_rest_works_more_than_three_fifths_as_long() {
        let mut balance = Balance::new(Threads::Balanced);
        balance.changed();
        let t0 = Instant::now();
        balance.look(t0, || here(0, 0));
        // 20 ms of interpreting in 30: the consumer's 10 ms are half of it.
        balance.interpreting = ms(20);
        assert!(!balance.look(t0 + ms(30), || here(30, 30)));
        // 20 of 34: the consumer's 14 ms are seven tenths, the average three fifths.
        balance.interpreting = ms(20);
        assert!(!balance.look(t0 + ms(64), || here(64, 64)));
        balance.interpreting = ms(20);
        assert!(balance.look(t0 + ms(98), || here(98, 98)));
    }

    #[test]
    fn a_parser_thread_takes_one_thread_back_to_two() {
        // The interpreter 20 ms of the consumer's thread's 30, a parser thread 6 ms.
        let mut balance = Balance::new(Threads::Balanced);
        balance.changed();
        let t0 = Instant::now();
        balance.look(t0, || here(0, 0));
        for n in 1..=2 {
            balance.interpreting = ms(20);
            let decided = balance.look(t0 + ms(30 * n), || here(36 * n, 30 * n));
            assert_eq!(decided, n == 2);
        }
    }

    #[test]
    fn each_way_back_to_two_threads_makes_the_next_way_to_one_longer() {
        let mut balance = Balance::new(Threads::Balanced);
        balance.changed();
        balance.changed();
        let decisions = looks(&mut balance, |n| apart(30 * n, 28 * n));
        assert!(!decisions.contains(&true), "{decisions:?}");
    }

    #[test]
    fn without_cpu_times_two_threads_stay_two() {
        let mut balance = Balance::new(Threads::Balanced);
        assert!(!looks(&mut balance, |_| None).contains(&true));
    }

    #[test]
    fn two_threads_stay_two() {
        let mut balance = Balance::new(Threads::Two);
        let busy = Busy::new();
        busy.tell();
        for _ in 0..1000 {
            assert!(!balance.apart(&busy));
        }
    }

    #[test]
    fn a_thread_tells_its_cpu_time() {
        let busy = Busy::new();
        assert_eq!(busy.time(), None);
        let start = Instant::now();
        while start.elapsed() < ms(5) {}
        busy.tell();
        assert!(busy.time().is_some_and(|time| time >= ms(1)));
    }
}
