//! The command line's integration tests, built as one test binary: one link instead of one per
//! file. Run one module with `cargo test -p vcnc-cli --test it <module>::` (e.g. `golden::`).
//! This file only declares the modules; it must never hold tests or helpers of its own.

// The rule for `../shared` (skip with a notice, fail under CI) is the library tests' own file.
#[path = "../../../vcnc/tests/it/common/shared.rs"]
mod shared;

mod check_report;
mod cli;
mod golden;
mod inputs;
mod plot_sim;
mod results;
mod saved_programs;
mod sim_corpus;
mod state;
mod traces;
mod view;
