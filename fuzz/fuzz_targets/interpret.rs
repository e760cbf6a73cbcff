//! Fuzz target: arbitrary bytes through the whole interpreter, on every built-in profile.
//!
//! Properties (a broken one is a crash, and libFuzzer keeps the input):
//! - no panic, and the run ends: at most `ITEMS_PER_BLOCK` items per pass through a block (a
//!   block takes at least one byte; most yield a handful of items, a canned cycle block up to
//!   vcnc's limit of 100,000 moves with their events), and a block runs at most once more than
//!   the backward jumps allowed (`JUMPS`, kept small so that a macro loop ends fast);
//!   libFuzzer's `-timeout` catches a single `next()` that never returns;
//! - nothing comes out after the first error alarm;
//! - every alarm has a span (in-memory ISO text has no whole-file problems), its span and its
//!   labels' spans lie inside the input (`start <= end <= len`), and its message is one line;
//! - every segment's span lies inside the input and all its numbers are finite.
//!
//! Each run also carries two interrupt signals (a line chosen by the input's length, and N10),
//! so that M96 programs take their interrupt paths.
//!
//! `VCNC_FUZZ_ALLOW_NONFINITE=1` skips the last check, so that a long run can look for other
//! bugs while the known overflow of huge numbers is open (see README.md).
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::sync::OnceLock;
use vcnc::interp::InterruptAt;
use vcnc::motion::{Feed, Move};
use vcnc::{
    interpret_bytes, Alarm, Item, Machine, Options, ProfileName, Segment, SegmentKind, Span,
};

/// Items one block may yield: a cycle block's 100,000 moves, each with at most a spindle event
/// or a dwell beside it, and a few more.
const ITEMS_PER_BLOCK: usize = 250_000;

/// Items of one run checked before the run is left (see the loop).
const MAX_ITEMS: usize = 1_000_000;

/// Backward jumps (loop passes, GOTOs back, M99 repeats) a run may make before it stops with the
/// limit alarm: few, so that fuzzed loops end in microseconds.
const JUMPS: u64 = 200;

struct Setup {
    machines: Vec<(ProfileName, Machine)>,
    allow_nonfinite: bool,
}

fn setup() -> &'static Setup {
    static SETUP: OnceLock<Setup> = OnceLock::new();
    SETUP.get_or_init(|| Setup {
        machines: ProfileName::ALL
            .iter()
            .map(|&p| {
                (
                    p,
                    Machine::default()
                        .with_profile(p)
                        .expect("built-in profiles fit the default machine"),
                )
            })
            .collect(),
        allow_nonfinite: std::env::var_os("VCNC_FUZZ_ALLOW_NONFINITE").is_some_and(|v| v != "0"),
    })
}

fuzz_target!(|data: &[u8]| {
    let setup = setup();
    let len = u32::try_from(data.len()).expect("libFuzzer inputs are small");
    for (profile, machine) in &setup.machines {
        // Items per block, by the block's first byte.
        let mut per_block: std::collections::HashMap<u32, usize> = Default::default();
        let mut error: Option<Alarm> = None;
        let mut options = Options::default();
        options.limits.jumps = JUMPS;
        // An interrupt signal (M96) on a line and a sequence number the input chooses, so that
        // the interrupt paths run too: the line from the input's length, N10 always.
        options.interrupts = vec![InterruptAt::Line(1 + len % 8), InterruptAt::Sequence(10)];
        // Every jump may run a block once more (a subprogram call runs its blocks once per
        // call, and calls nest only as deep as the profile allows: their passes are jumps too
        // when they repeat).
        let per_block_limit = ITEMS_PER_BLOCK * (JUMPS as usize + 2);
        // A legitimate program can be long (a loop of deep peck cycles yields millions of
        // moves); past this many items a run has shown what it can, and the next input waits.
        for item in interpret_bytes(data, machine, options).take(MAX_ITEMS) {
            let start = match &item {
                Ok(Item::Segment(segment)) => segment.span.start,
                // A frame names no block; it counts with the move it comes before.
                Ok(Item::Frame(_)) => {
                    assert!(error.is_none(), "a frame came after the error {error:?}");
                    continue;
                }
                Ok(Item::Warning(alarm)) | Err(alarm) => alarm.span.map_or(0, |s| s.start),
            };
            let count = per_block.entry(start).or_default();
            *count += 1;
            assert!(
                *count <= per_block_limit,
                "{}: the block at byte {start} yields more than {per_block_limit} items",
                profile.as_str()
            );
            assert!(
                error.is_none(),
                "{}: {item:?} came after the error {error:?}",
                profile.as_str()
            );
            match item {
                Ok(Item::Segment(segment)) => check_segment(&segment, len, setup.allow_nonfinite),
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

fn check_segment(segment: &Segment, len: u32, allow_nonfinite: bool) {
    check_span(segment.span, len, segment);
    if allow_nonfinite {
        return;
    }
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
