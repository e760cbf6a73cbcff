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
//! - `interp_sinumerik/N` and `interp_sinumerik_jsonl/N`: the same two on the same path written
//!   the SINUMERIK way (`cam_program::Style::Sinumerik`: DEF'd feeds, N numbers, `;` comments,
//!   G2/G3 with CR=), run by the SINUMERIK front end (`vcnc::interp::sinumerik::run_str`). Issue
//!   20 asks for at least 0.7 times the ISO twin's blocks per second: compare with `interp/N`
//!   and `interp_jsonl/N`.
//!
//! The speed target (at least 30 times LinuxCNC's `rs274 -g` on 400,000 blocks, memory
//! flat as the program grows) is about the whole process and is measured outside criterion; the
//! method and the figures are in docs/benchmarks.md.

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::time::Duration;
use vcnc::interp::sinumerik;
use vcnc::motion::Feed;
use vcnc::{interpret_str, Item, Machine, Options, Segment, SegmentKind, StreamItem};

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

fn interp_sinumerik(c: &mut Criterion) {
    let machine = Machine::default();
    let mut group = c.benchmark_group("interp_sinumerik");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(2))
        .measurement_time(Duration::from_secs(8));
    for blocks in SIZES {
        let text = cam_program::program_in(blocks, cam_program::Style::Sinumerik);
        group.throughput(Throughput::Elements(blocks as u64));
        group.bench_with_input(BenchmarkId::from_parameter(blocks), &text, |b, text| {
            b.iter(|| {
                let mut segments = 0;
                for item in sinumerik::run_str(text, &machine) {
                    let segment = item.expect("the benchmark program runs without alarms");
                    black_box(&segment);
                    segments += 1;
                }
                segments
            });
        });
    }
    group.finish();
}

fn interp_sinumerik_jsonl(c: &mut Criterion) {
    let machine = Machine::default();
    let mut group = c.benchmark_group("interp_sinumerik_jsonl");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(2))
        .measurement_time(Duration::from_secs(8));
    for blocks in SIZES {
        let text = cam_program::program_in(blocks, cam_program::Style::Sinumerik);
        group.throughput(Throughput::Elements(blocks as u64));
        group.bench_with_input(BenchmarkId::from_parameter(blocks), &text, |b, text| {
            b.iter(|| {
                let mut run = sinumerik::run_str(text, &machine);
                write_batches(|batch, at_least| run.next_batch(batch, at_least))
            });
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
    write_batches(|batch, at_least| interpreter.next_batch(batch, at_least))
}

/// Takes batches from `next_batch` (it fills the batch with at least that many items and says
/// whether more come) and writes their JSON-lines trace; returns the bytes written.
fn write_batches(mut next_batch: impl FnMut(&mut Vec<StreamItem>, usize) -> bool) -> usize {
    let mut out = numbers::OutBuffer::new(1 << 16);
    let mut memory = [numbers::Remembered::default(); 4];
    let mut batch = Vec::with_capacity(BATCH + 16);
    let mut written = 0;
    loop {
        let more = next_batch(&mut batch, BATCH);
        for item in batch.drain(..) {
            // A frame is not a record of the trace.
            let item = item.expect("the benchmark program runs without alarms");
            if let Item::Segment(segment) = item {
                jsonl(&mut out, &mut memory, &segment);
            }
        }
        if out.is_full() || !more {
            written += black_box(out.as_bytes()).len();
            out.clear();
        }
        if !more {
            return written;
        }
    }
}

/// One `vcnc trace` record: the fields the command writes for motions (x y z and f with their
/// texts remembered, as the command does); events get their kind only.
fn jsonl(out: &mut numbers::OutBuffer, memory: &mut [numbers::Remembered; 4], segment: &Segment) {
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
    let mut text = out.record(0);
    text.put(b"{\"kind\":\"");
    text.put(kind.as_bytes());
    text.put(b"\",\"line\":");
    text.unsigned(b"", u64::from(segment.span.line));
    text.put(b",\"file\":\"/tmp/p400k.nc\"");
    if let Some(motion) = segment.motion() {
        for (slot, key) in [&b",\"x\":"[..], b",\"y\":", b",\"z\":"]
            .into_iter()
            .enumerate()
        {
            text.remembered(key, &mut memory[slot], motion.to.0[slot]);
        }
        if let Some(f) = feed.and_then(|feed| per_minute(feed, segment)) {
            text.remembered(b",\"f\":", &mut memory[3], f);
        }
        if let Some((center, dir, plane)) = arc {
            for (key, value) in [
                (&b",\"cx\":"[..], center[0]),
                (b",\"cy\":", center[1]),
                (b",\"cz\":", center[2]),
            ] {
                text.decimal(key, value);
            }
            text.put(b",\"dir\":\"");
            text.put(dir.as_bytes());
            text.put(b"\",\"plane\":\"");
            text.put(plane.as_bytes());
            text.byte(b'"');
        }
    }
    text.put(b"}\n");
}

fn per_minute(feed: &Feed, segment: &Segment) -> Option<f64> {
    match feed {
        Feed::PerMinute(f) => Some(*f),
        _ => feed.mm_per_min(segment.length()),
    }
}

/// Issue #3, acceptance 4: a Custom Macro B loop of 1,000,000 passes, each an assignment with
/// SIN and COS and a G1 move. The same loop as a LinuxCNC O-word program took 18.4 s under
/// `rs274 -g` on this machine (2026-11-22); the target is 20 times faster, under 0.92 s.
fn macro_loop(c: &mut Criterion) {
    let program = "#1=0\nG90 G1 F1000.\nWHILE [#1 LT 1000000] DO1\n#2=#1*0.01\n\
                   G1 X[SIN[#2]*10] Y[COS[#2]*10]\n#1=#1+1\nEND1\nM30\n";
    let machine = Machine::default();
    let mut group = c.benchmark_group("macro_loop");
    group
        .sample_size(10)
        .throughput(Throughput::Elements(1_000_000));
    group.bench_function("1000000", |b| {
        b.iter(|| {
            let segments = interpret_str(program, &machine, Options::default())
                .filter(Result::is_ok)
                .count();
            black_box(segments)
        })
    });
    group.finish();
}

criterion_group!(
    benches,
    interp,
    interp_jsonl,
    interp_sinumerik,
    interp_sinumerik_jsonl,
    macro_loop
);
criterion_main!(benches);
