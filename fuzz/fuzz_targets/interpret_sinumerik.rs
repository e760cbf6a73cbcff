//! Fuzz target: arbitrary bytes through the SINUMERIK front end and the kernel
//! (`vcnc::interp::sinumerik::Sinumerik` in a `vcnc::interp::Run`), on both SINUMERIK profiles
//! (840D sl and 828D), on a machine with rotary A, B and C axes besides X, Y, Z.
//!
//! Each input runs twice: on the 840D with a program library that answers every call by name with
//! the input itself (so that calls, recursion and the depth limit run), and on the 828D without a
//! library (a call alarms). The profile's iteration limit is small so that fuzzed loops end fast.
//!
//! Properties (a broken one is a crash, and libFuzzer keeps the input):
//! - no panic, and the run ends: at most `MAX_ITEMS` items (the iteration limit bounds the lines
//!   read, a line yields a handful of items, a cycle call at most 2,000,000 moves); libFuzzer's
//!   `-timeout` catches a single
//!   `next()` that never returns;
//! - nothing comes out after the first error alarm;
//! - every alarm has a span inside the input (in-memory text has no whole-file problems), its
//!   labels' spans too, and a one-line message;
//! - every segment's span lies inside the input and all its numbers are finite.
//!
//! It must never write files or read anything but the input.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::sync::{Arc, OnceLock};
use vcnc::interp::sinumerik::Sinumerik;
use vcnc::interp::{Kernel, LookupError, ProgramLibrary, ProgramText, Run};
use vcnc::machine::AxisConfig;
use vcnc::motion::{Feed, Move};
use vcnc::{Alarm, Axis, FileId, Item, Machine, ProfileName, Segment, SegmentKind, Span};

/// Lines a run may read (loop passes and jumps included) before it stops with the limit alarm.
const ITERATIONS: u64 = 20_000;

/// Items a run may yield: the iteration limit times a generous number of items per line, and
/// a cycle call's 2,000,000 moves (its passes together) more than once.
const MAX_ITEMS: usize = 5_000_000;

fn machines() -> &'static [(ProfileName, Machine)] {
    static MACHINES: OnceLock<Vec<(ProfileName, Machine)>> = OnceLock::new();
    MACHINES.get_or_init(|| {
        ProfileName::SINUMERIK
            .iter()
            .map(|&p| {
                let mut machine = Machine::default()
                    .with_profile(p)
                    .expect("the SINUMERIK profiles fit the default machine");
                for axis in [Axis::A, Axis::B, Axis::C] {
                    machine.axes[axis.index()] = Some(AxisConfig {
                        min: -1.0e6,
                        max: 1.0e6,
                        rapid: 36000.0,
                        max_feed: 36000.0,
                        acceleration: 2000.0,
                        jerk: f64::INFINITY,
                    });
                }
                machine
                    .profile
                    .sinumerik
                    .as_mut()
                    .expect("a SINUMERIK profile has its settings")
                    .iteration_limit = ITERATIONS;
                (p, machine)
            })
            .collect()
    })
}

/// Every called program is the input itself, in file 0 (so its spans are the input's).
struct Itself(Arc<[u8]>);

impl ProgramLibrary for Itself {
    fn find(&mut self, _number: u32) -> Result<Option<ProgramText>, LookupError> {
        Ok(Some(ProgramText {
            file: FileId(0),
            text: self.0.clone(),
        }))
    }

    fn find_named(&mut self, _name: &str) -> Result<Option<ProgramText>, LookupError> {
        self.find(0)
    }
}

fuzz_target!(|data: &[u8]| {
    let len = u32::try_from(data.len()).expect("libFuzzer inputs are small");
    let text: Arc<[u8]> = Arc::from(data);
    for (index, (profile, machine)) in machines().iter().enumerate() {
        let mut front_end = Sinumerik::new(text.clone(), FileId(0), machine);
        if index == 0 {
            front_end = front_end.with_library(Box::new(Itself(text.clone())));
        }
        let mut error: Option<Alarm> = None;
        let mut items = 0usize;
        for item in Run::new(front_end, Kernel::new(machine)) {
            items += 1;
            assert!(
                items <= MAX_ITEMS,
                "{}: the run did not end within {MAX_ITEMS} items",
                profile.as_str()
            );
            assert!(
                error.is_none(),
                "{}: {item:?} came after the error {error:?}",
                profile.as_str()
            );
            match item {
                Ok(Item::Segment(segment)) => check_segment(&segment, len),
                Ok(Item::Frame(_)) => {}
                Ok(Item::Warning(alarm)) => check_alarm(&alarm, len),
                Err(alarm) => {
                    check_alarm(&alarm, len);
                    error = Some(alarm);
                }
            }
        }
    }
});

fn check_span(span: Span, len: u32, what: &dyn std::fmt::Debug) {
    assert!(
        span.start <= span.end && span.end <= len,
        "span {span} of {what:?} is outside the input of {len} bytes"
    );
}

fn check_alarm(alarm: &Alarm, len: u32) {
    let span = alarm
        .span
        .unwrap_or_else(|| panic!("alarm without a span: {alarm:?}"));
    check_span(span, len, alarm);
    for label in &alarm.labels {
        check_span(label.span, len, alarm);
    }
    assert!(
        !alarm.message.is_empty() && !alarm.message.contains('\n'),
        "alarm message is not one line: {alarm:?}"
    );
}

fn check_segment(segment: &Segment, len: u32) {
    check_span(segment.span, len, segment);
    let finite = match &segment.kind {
        SegmentKind::Rapid { motion, .. } => move_is_finite(motion),
        SegmentKind::Line { motion, feed } => move_is_finite(motion) && feed_is_finite(feed),
        SegmentKind::Arc {
            motion,
            center,
            feed,
            ..
        } => move_is_finite(motion) && all_finite(&center.0) && feed_is_finite(feed),
        SegmentKind::Dwell { seconds } => seconds.is_finite(),
        SegmentKind::Spindle { speed, .. } => speed.is_finite(),
        _ => true,
    };
    assert!(
        finite,
        "segment with a number that is not finite: {segment:?}"
    );
}

fn all_finite(values: &[f64]) -> bool {
    values.iter().all(|v| v.is_finite())
}

fn move_is_finite(motion: &Move) -> bool {
    all_finite(&motion.from.0) && all_finite(&motion.to.0) && all_finite(&motion.offset)
}

fn feed_is_finite(feed: &Feed) -> bool {
    match *feed {
        Feed::PerMinute(f) | Feed::InverseTime(f) => f.is_finite(),
        Feed::PerRevolution {
            per_revolution,
            rpm,
        } => per_revolution.is_finite() && rpm.map_or(true, f64::is_finite),
    }
}
