//! Planner throughput, in segments per second, on the CAM-style program of
//! `support/cam_program.rs` (feed lines wandering over 200 x 200 mm, every tenth block an arc)
//! at 40,000 and 400,000 motion blocks, on the default machine (S-curves, corner blends).
//!
//! - `plan/N`: the motion stream is interpreted once, before timing, into memory; the bench times
//!   `vcnc::plan::Planner` alone over it (the iterator, which moves every segment through a queue
//!   of its own). The target (#6): at least 5 million segments per second on one core.
//! - `timeline/N`: the same with `vcnc::plan::Timeline`, the planner's core as the command line
//!   uses it: segments by reference, timings back in order.
//! - `interp_plan/N`: interpreting and planning together, as `vcnc run` does; compare with the
//!   `interp` bench for what planning adds (the issue allows 30 % on the 400,000-block program).

use criterion::measurement::WallTime;
use criterion::{
    black_box, criterion_group, criterion_main, BenchmarkGroup, BenchmarkId, Criterion, Throughput,
};
use std::time::Duration;
use vcnc::plan::{PlanOptions, Planner, Timeline};
use vcnc::{interpret_str, Machine, Options, Segment};

#[path = "support/cam_program.rs"]
mod cam_program;

/// Program sizes in motion blocks, as in the `interp` bench.
const SIZES: [usize; 2] = [40_000, 400_000];

fn plan(c: &mut Criterion) {
    over_segments(c, "plan", |segments, machine| {
        let stream = segments
            .iter()
            .map(|segment| Ok(vcnc::Item::Segment(*segment)));
        total_seconds(Planner::new(stream, machine, PlanOptions::default()))
    });
}

fn timeline(c: &mut Criterion) {
    over_segments(c, "timeline", |segments, machine| {
        let mut timeline = Timeline::new(machine, PlanOptions::default());
        let mut end = 0.0;
        for segment in segments {
            timeline.push(segment);
            while let Some(timing) = timeline.next_timing() {
                end = black_box(timing.t + timing.dt);
            }
        }
        timeline.finish();
        while let Some(timing) = timeline.next_timing() {
            end = black_box(timing.t + timing.dt);
        }
        end
    });
}

/// A group named `name` timing `run` over the motion stream of each program size, interpreted
/// into memory before timing; `run` returns the program's time.
fn over_segments(c: &mut Criterion, name: &str, run: impl Fn(&[Segment], &Machine) -> f64) {
    let machine = Machine::default();
    let mut group = group(c, name, 6);
    for blocks in SIZES {
        let text = cam_program::program(blocks);
        let segments: Vec<Segment> = interpret_str(&text, &machine, Options::default())
            .filter_map(|item| {
                item.expect("the benchmark program runs without alarms")
                    .into_segment()
            })
            .collect();
        group.throughput(Throughput::Elements(segments.len() as u64));
        group.bench_with_input(
            BenchmarkId::from_parameter(blocks),
            &segments,
            |b, segments| b.iter(|| run(segments, &machine)),
        );
    }
    group.finish();
}

fn interp_plan(c: &mut Criterion) {
    let machine = Machine::default();
    let mut group = group(c, "interp_plan", 8);
    for blocks in SIZES {
        let text = cam_program::program(blocks);
        group.throughput(Throughput::Elements(blocks as u64));
        group.bench_with_input(BenchmarkId::from_parameter(blocks), &text, |b, text| {
            b.iter(|| {
                let stream = interpret_str(text, &machine, Options::default());
                total_seconds(Planner::new(stream, &machine, PlanOptions::default()))
            });
        });
    }
    group.finish();
}

/// A group of few samples (each runs a whole program) measured for `seconds`.
fn group<'a>(c: &'a mut Criterion, name: &str, seconds: u64) -> BenchmarkGroup<'a, WallTime> {
    let mut group = c.benchmark_group(name);
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(2))
        .measurement_time(Duration::from_secs(seconds));
    group
}

/// Runs the planner to the end; the program's time, so nothing is optimised away.
fn total_seconds(planner: impl Iterator<Item = Result<vcnc::plan::TimedItem, vcnc::Alarm>>) -> f64 {
    let mut end = 0.0;
    for item in planner {
        let item = item.expect("the benchmark program runs without alarms");
        if let Some(timed) = item.segment() {
            end = black_box(timed.t + timed.dt);
        }
    }
    end
}

criterion_group!(benches, plan, timeline, interp_plan);
criterion_main!(benches);
