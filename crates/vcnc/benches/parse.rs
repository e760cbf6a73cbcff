//! ISO front-end throughput, in bytes per second, on the CAM-style program of
//! `support/cam_program.rs` (feed lines wandering over 200 x 200 mm, every tenth block a G02/G03
//! arc with R or I J) at 40,000 and 400,000 motion blocks.
//!
//! - `parse/N`: the text split into lines and each line read into blocks of words, on one
//!   thread, as `vcnc::syntax::blocks::ParsedLines` does for the interpreter (and the parser
//!   thread of `vcnc trace` does for each batch). No interpreting: this is the front end's cost
//!   alone, the part of the pipeline that runs on the parser thread.
//! - `parse_sinumerik/N`: the same path written the SINUMERIK way
//!   (`cam_program::Style::Sinumerik`), each line read by `vcnc::syntax::sinumerik::parse_block`
//!   as the SINUMERIK front end reads it where it runs (it has no parser thread).
//!
//! Seconds are noisy on a shared machine: to compare two versions of the reader, instructions per
//! line under callgrind (`vcnc trace` on `cargo xtask bench-program 40000`, the inclusive count of
//! `parse_line`) are the steadier figure.

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::time::Duration;
use vcnc::syntax::blocks::{line_blocks, BlockSource, ParsedLines};
use vcnc::syntax::iso::SyntaxOptions;
use vcnc::syntax::lines::{LineSource, TextLines};
use vcnc::syntax::sinumerik::parse_block;
use vcnc::FileId;

#[path = "support/cam_program.rs"]
mod cam_program;

/// Program sizes in motion blocks, as in the `interp` bench.
const SIZES: [usize; 2] = [40_000, 400_000];

fn parse(c: &mut Criterion) {
    let mut group = c.benchmark_group("parse");
    group
        .sample_size(20)
        .warm_up_time(Duration::from_secs(2))
        .measurement_time(Duration::from_secs(6));
    for blocks in SIZES {
        let text = cam_program::program_in(blocks, cam_program::Style::Iso);
        group.throughput(Throughput::Bytes(text.len() as u64));
        group.bench_with_input(BenchmarkId::from_parameter(blocks), &text, |b, text| {
            b.iter(|| count_words(text));
        });
    }
    group.finish();
}

fn parse_sinumerik(c: &mut Criterion) {
    let mut group = c.benchmark_group("parse_sinumerik");
    group
        .sample_size(20)
        .warm_up_time(Duration::from_secs(2))
        .measurement_time(Duration::from_secs(6));
    for blocks in SIZES {
        let text = cam_program::program_in(blocks, cam_program::Style::Sinumerik);
        group.throughput(Throughput::Bytes(text.len() as u64));
        group.bench_with_input(BenchmarkId::from_parameter(blocks), &text, |b, text| {
            b.iter(|| count_sinumerik_words(text));
        });
    }
    group.finish();
}

/// Reads every line of the SINUMERIK program into its block and counts the words.
fn count_sinumerik_words(text: &str) -> usize {
    let mut lines = TextLines::new(text.as_bytes());
    let mut words = 0;
    while let Some(line) = lines
        .next_line()
        .expect("text in memory cannot fail to read")
    {
        let block = parse_block(line.text, FileId(0), line.number, line.offset);
        assert!(
            block.alarm.is_none(),
            "the benchmark program reads without alarms"
        );
        words += black_box(block).words.len();
    }
    words
}

/// Reads every line of the program and counts its words; an alarm would make the figure
/// meaningless.
fn count_words(text: &str) -> usize {
    let lines = TextLines::new(text.as_bytes());
    let mut source = ParsedLines::new(lines, FileId(0), SyntaxOptions::default());
    let mut words = 0;
    while source
        .advance()
        .expect("text in memory cannot fail to read")
    {
        for block in black_box(line_blocks(&source)) {
            assert!(
                block.alarms.is_empty(),
                "the benchmark program reads without alarms"
            );
            words += block.words.len();
        }
    }
    words
}

criterion_group!(benches, parse, parse_sinumerik);
criterion_main!(benches);
