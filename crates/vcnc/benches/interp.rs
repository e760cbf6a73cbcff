//! Interpreter throughput, in blocks per second, on the CAM-style program of `support/cam_program.rs`
//! (feed lines wandering over 200 x 200 mm, every tenth block a G02/G03 arc with R or I J) at
//! 40,000 and 400,000 motion blocks, interpreted from memory on one thread.
//!
//! - `interp/N`: `vcnc::interpret_str` on the default machine, every segment counted. This is the
//!   library's cost alone, without reading a file or writing anything.
//! - `interp_jsonl/N`: the same stream taken in batches with `Interpreter::next_batch`, as
//!   `vcnc trace` takes it, and written as JSON lines into a `Vec<u8>` that is cleared every
//!   64 KiB, as the command's buffer is. The record writer of `vcnc trace` lives in the binary
//!   crate and cannot be called from here; `jsonl` below writes the same fields for the segments
//!   this program makes with the command's own number formatter (`vcnc-cli/src/numbers.rs`,
//!   included by path), so the figure is the command's formatting cost without its threads.
//!
//! The speed target (at least 30 times LinuxCNC's `rs274 -g` on 400,000 blocks, memory
//! flat as the program grows) is about the whole process and is measured outside criterion; the
//! method and the figures are in docs/benchmarks.md.

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::time::Duration;
use vcnc::motion::Feed;
use vcnc::{interpret_str, Machine, Options, Segment, SegmentKind};

#[path = "support/cam_program.rs"]
mod cam_program;

#[allow(dead_code, unreachable_pub)]
#[path = "../../vcnc-cli/src/numbers.rs"]
mod numbers;

/// Program sizes in motion blocks: a medium and the large size the speed target is stated for.
const SIZES: [usize; 2] = [40_000, 400_000];

/// Segments per batch, as `vcnc trace` takes them.
const BATCH: usize = 1024;

fn interp(c: &mut Criterion) {
    let machine = Machine::default();
    let mut group = c.benchmark_group("interp");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(2))
        .measurement_time(Duration::from_secs(8));
    for blocks in SIZES {
        let text = cam_program::program(blocks);
        group.throughput(Throughput::Elements(blocks as u64));
        group.bench_with_input(BenchmarkId::from_parameter(blocks), &text, |b, text| {
            b.iter(|| count_segments(text, &machine));
        });
    }
    group.finish();
}

fn interp_jsonl(c: &mut Criterion) {
    let machine = Machine::default();
    let mut group = c.benchmark_group("interp_jsonl");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(2))
        .measurement_time(Duration::from_secs(8));
    for blocks in SIZES {
        let text = cam_program::program(blocks);
        group.throughput(Throughput::Elements(blocks as u64));
        group.bench_with_input(BenchmarkId::from_parameter(blocks), &text, |b, text| {
            b.iter(|| trace_bytes(text, &machine));
        });
    }
    group.finish();
}

/// Interprets the program and counts its segments; an alarm would make the figure meaningless.
fn count_segments(text: &str, machine: &Machine) -> usize {
    let mut segments = 0;
    for item in interpret_str(text, machine, Options::default()) {
        let segment = item.expect("the benchmark program runs without alarms");
        black_box(&segment);
        segments += 1;
    }
    segments
}

/// Interprets the program in batches and writes its JSON-lines trace; returns the bytes written.
fn trace_bytes(text: &str, machine: &Machine) -> usize {
    let mut interpreter = interpret_str(text, machine, Options::default());
    let mut out = Vec::with_capacity(1 << 17);
    let mut batch = Vec::with_capacity(BATCH + 16);
    let mut written = 0;
    loop {
        let more = interpreter.next_batch(&mut batch, BATCH);
        for item in batch.drain(..) {
            jsonl(
                &mut out,
                &item.expect("the benchmark program runs without alarms"),
            );
        }
        if out.len() >= 1 << 16 || !more {
            written += black_box(&out).len();
            out.clear();
        }
        if !more {
            return written;
        }
    }
}

/// One `vcnc trace` record: the fields the command writes for motions; events get their kind only.
fn jsonl(out: &mut Vec<u8>, segment: &Segment) {
    let (kind, feed, arc) = match &segment.kind {
        SegmentKind::Rapid { .. } => ("rapid", None, None),
        SegmentKind::Line { feed, .. } => ("feed", Some(feed), None),
        SegmentKind::Arc {
            feed,
            center,
            direction,
            plane,
            ..
        } => (
            "arc",
            Some(feed),
            Some((center.xyz(), direction.as_str(), plane.as_str())),
        ),
        _ => ("event", None, None),
    };
    out.extend_from_slice(b"{\"kind\":\"");
    out.extend_from_slice(kind.as_bytes());
    out.extend_from_slice(b"\",\"line\":");
    numbers::push_unsigned(out, u64::from(segment.span.line));
    out.extend_from_slice(b",\"file\":\"/tmp/p400k.nc\"");
    if let Some(motion) = segment.motion() {
        for (key, value) in [
            (&b",\"x\":"[..], motion.to.0[0]),
            (b",\"y\":", motion.to.0[1]),
            (b",\"z\":", motion.to.0[2]),
        ] {
            out.extend_from_slice(key);
            numbers::push_decimal(out, value);
        }
        if let Some(f) = feed.and_then(|feed| per_minute(feed, segment)) {
            out.extend_from_slice(b",\"f\":");
            numbers::push_decimal(out, f);
        }
        if let Some((center, dir, plane)) = arc {
            for (key, value) in [
                (&b",\"cx\":"[..], center[0]),
                (b",\"cy\":", center[1]),
                (b",\"cz\":", center[2]),
            ] {
                out.extend_from_slice(key);
                numbers::push_decimal(out, value);
            }
            out.extend_from_slice(b",\"dir\":\"");
            out.extend_from_slice(dir.as_bytes());
            out.extend_from_slice(b"\",\"plane\":\"");
            out.extend_from_slice(plane.as_bytes());
            out.push(b'"');
        }
    }
    out.extend_from_slice(b"}\n");
}

fn per_minute(feed: &Feed, segment: &Segment) -> Option<f64> {
    match feed {
        Feed::PerMinute(f) => Some(*f),
        _ => feed.mm_per_min(segment.length()),
    }
}

criterion_group!(benches, interp, interp_jsonl);
criterion_main!(benches);
