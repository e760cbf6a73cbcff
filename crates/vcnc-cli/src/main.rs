//! `vcnc`: run, check and trace NC programs on a virtual CNC milling controller.
//!
//! The binary parses arguments, calls one command, and turns its result into an exit code:
//! 0 clean, 1 a program raised an alarm, 2 a usage or setup error.

mod cmd;
mod diagnostics;
mod error;
mod excerpt;
mod numbers;
mod program;
mod progress;
mod setup;
mod view;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// A virtual CNC milling controller: runs FANUC-family ISO programs the way the control would.
#[derive(Parser, Debug)]
#[command(name = "vcnc", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Run a program and print what a CNC programmer wants to know: moves, lengths, time, extents, tools, alarms.
    Run(cmd::run::Args),
    /// Check programs and print only their alarms and warnings.
    Check(cmd::check::Args),
    /// Print the motion stream (machine coordinates) as JSON lines or CSV.
    Trace(cmd::trace::Args),
    /// Print the embedded default machine file (or --machine's), with --profile's name and its
    /// settings spelled out, to copy and edit.
    Machine(cmd::machine::Args),
    /// Draw the toolpath to scale as SVG or PNG: rapids dashed, cuts coloured by tool.
    Plot(cmd::plot::Args),
    /// Simulate 3-axis material removal on a box of stock: removed volume, cutting time,
    /// rapids into the stock and collisions; the part as STL and a shaded PNG.
    Sim(cmd::sim::Args),
    /// Show the toolpath in 3D in a local page (served on 127.0.0.1, or --html FILE): the
    /// planner's timeline, each segment's block, the simulated stock and its alarms.
    View(cmd::view::Args),
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(error) => {
            let _ = error.print();
            return if error.use_stderr() {
                ExitCode::from(2)
            } else {
                ExitCode::SUCCESS
            };
        }
    };
    let result = match cli.command {
        Command::Run(mut args) => {
            args.machine.keeps_state = true;
            cmd::run::run(&args)
        }
        Command::Check(args) => cmd::check::run(&args),
        Command::Trace(args) => cmd::trace::run(&args),
        Command::Machine(args) => cmd::machine::run(&args),
        Command::Plot(args) => cmd::plot::run(&args),
        Command::Sim(args) => cmd::sim::run(&args),
        Command::View(args) => cmd::view::run(&args),
    };
    match result {
        Ok(cmd::Outcome::Clean) => ExitCode::SUCCESS,
        Ok(cmd::Outcome::Alarm) => ExitCode::from(1),
        Ok(cmd::Outcome::Unread) => ExitCode::from(2),
        Err(error) => {
            eprintln!("vcnc: {error}");
            ExitCode::from(2)
        }
    }
}
