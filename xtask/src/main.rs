//! Developer tasks for vcnc: `cargo xtask <task>`.
//!
//! `ci` runs what CI runs (fmt, clippy, docs, tests). The other tasks regenerate data that lives
//! in the repository (reference traces recorded from LinuxCNC, generated tables); none of them is
//! needed to build or test vcnc.

mod bench_jumps;
mod bench_program;
mod ci;
mod gen_plan;
mod readme;
mod record_lcnc;

use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(task) = args.first() else {
        eprintln!("{USAGE}");
        return ExitCode::from(2);
    };
    let result = match task.as_str() {
        "ci" => ci::run(&args[1..]),
        "record-lcnc" => record_lcnc::run(&args[1..]),
        "bench-program" => bench_program::run(&args[1..]),
        "bench-jumps" => bench_jumps::run(&args[1..]),
        "readme" => readme::run(&args[1..]),
        "gen-plan-programs" => gen_plan::run(&args[1..]),
        _ => {
            eprintln!("unknown task `{task}`\n{USAGE}");
            return ExitCode::from(2);
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::FAILURE
        }
    }
}

const USAGE: &str = "usage: cargo xtask <task>

tasks:
  ci              what CI runs: check rustc against rust-version, then fmt, clippy, docs and the tests
  record-lcnc     run LinuxCNC's `rs274 -g` on crates/vcnc/tests/data/lcnc/*.ngc and store its canonical output
  gen-plan-programs
                  write the random planner reference programs (20 of each kind) to
                  crates/vcnc/tests/data/plan/lcnc/random/ (tools/record-lcnc-time.sh times them)
  readme          regenerate the supported-codes table in README.md
  bench-program   write the CAM-style benchmark program (N blocks, an arc every tenth) to stdout;
                  --sinumerik writes the same path as a SINUMERIK program
  bench-jumps     write three variants of a bench-program file that jump or call (WHILE, M98, G65)";
