//! A progress line on the terminal for runs that take more than a second: the program, the
//! line it has reached, the segments (moves and events) so far and the time spent, rewritten in place on standard
//! error and wiped at the end.
//!
//! It is shown only when standard error is a terminal and the command's output is for people;
//! it never writes to standard output, into a pipe or a file, or among JSON.
//! (Hand-written: a line rewritten with `\r` is all it needs, not worth a dependency's build.)
//! `VCNC_PROGRESS_AFTER_MS` changes the second it waits, for the tests: a test cannot count on
//! a run taking a second on every machine.

use std::io::{IsTerminal, Write};
use std::time::{Duration, Instant};

/// How long a run goes before its progress shows, and how often the line is rewritten.
const AFTER: Duration = Duration::from_secs(1);
const AFTER_VARIABLE: &str = "VCNC_PROGRESS_AFTER_MS";
const EVERY: Duration = Duration::from_millis(200);
/// Items between two looks at the clock.
const ITEMS_PER_LOOK: u32 = 1024;

/// The progress of one program.
pub(crate) struct Progress<W: Write> {
    /// Where it is written; `None` when it is not to be shown.
    out: Option<W>,
    name: String,
    started: Instant,
    after: Duration,
    last: Option<Instant>,
    items: u32,
    segments: u64,
}

impl Progress<std::io::Stderr> {
    /// The progress of the program `name` on standard error, shown when `for_people` (the
    /// output is not JSON) and standard error is a terminal.
    pub(crate) fn on_stderr(name: &str, for_people: bool) -> Progress<std::io::Stderr> {
        let shown = for_people && std::io::stderr().is_terminal();
        let mut progress = Progress::new(shown.then(std::io::stderr), name, Instant::now());
        if let Some(after) = std::env::var(AFTER_VARIABLE)
            .ok()
            .and_then(|ms| ms.parse().ok())
        {
            progress.after = Duration::from_millis(after);
        }
        progress
    }
}

impl<W: Write> Progress<W> {
    fn new(out: Option<W>, name: &str, started: Instant) -> Progress<W> {
        Progress {
            out,
            name: crate::excerpt::escape(name),
            started,
            after: AFTER,
            last: None,
            items: 0,
            segments: 0,
        }
    }

    /// Counts one segment of the stream, at `line`; now and then looks at the clock and
    /// rewrites the line.
    pub(crate) fn segment(&mut self, line: u32) {
        if self.out.is_none() {
            return;
        }
        self.segments += 1;
        self.items += 1;
        if self.items >= ITEMS_PER_LOOK {
            self.items = 0;
            self.show(line, Instant::now());
        }
    }

    /// Counts a batch of `segments` segments that ends at `line`, and rewrites the line if it
    /// is time to.
    pub(crate) fn batch(&mut self, line: u32, segments: usize) {
        if self.out.is_some() {
            self.segments += segments as u64;
            self.show(line, Instant::now());
        }
    }

    /// Rewrites the line at `now` if the run is long enough and the line old enough.
    fn show(&mut self, line: u32, now: Instant) {
        let Some(out) = self.out.as_mut() else {
            return;
        };
        let elapsed = now.saturating_duration_since(self.started);
        if elapsed < self.after || self.last.is_some_and(|last| now - last < EVERY) {
            return;
        }
        self.last = Some(now);
        let _ = write!(
            out,
            "\r\x1b[2K{}: line {line}, {} segments, {:.0} s",
            self.name,
            self.segments,
            elapsed.as_secs_f64()
        );
        let _ = out.flush();
    }

    /// Wipes the line, if it was shown, before the command's own output.
    pub(crate) fn finish(&mut self) {
        if let (Some(out), Some(_)) = (self.out.as_mut(), self.last) {
            let _ = write!(out, "\r\x1b[2K");
            let _ = out.flush();
        }
        self.last = None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn progress_shows_after_a_second_and_is_wiped_at_the_end() {
        let start = Instant::now();
        let mut progress = Progress::new(Some(Vec::new()), "part.nc", start);
        progress.segments = 5;
        progress.show(10, start + Duration::from_millis(500));
        assert!(progress.out.as_ref().unwrap().is_empty(), "not before 1 s");
        progress.show(20, start + Duration::from_millis(1500));
        progress.show(21, start + Duration::from_millis(1600));
        progress.finish();
        let text = String::from_utf8(progress.out.take().unwrap()).unwrap();
        assert_eq!(
            text, "\r\x1b[2Kpart.nc: line 20, 5 segments, 2 s\r\x1b[2K",
            "once in 200 ms, then wiped"
        );
    }

    #[test]
    fn progress_not_shown_writes_nothing() {
        let start = Instant::now();
        let mut progress = Progress::<Vec<u8>>::new(None, "part.nc", start);
        for _ in 0..10_000 {
            progress.segment(1);
        }
        progress.batch(1, 100);
        progress.show(1, start + Duration::from_secs(5));
        progress.finish();
        assert!(progress.out.is_none());
    }
}
