//! Options shared by every command: the machine, the profile, the panel switches.

use crate::error::CliError;
use clap::Args;
use std::path::PathBuf;
use vcnc::plan::PlanOptions;
use vcnc::{Machine, Options, ProfileName};

/// The machine file and the profile: the options every command takes.
#[derive(Args, Debug, Clone)]
pub(crate) struct MachineChoice {
    /// Machine file (TOML; `vcnc machine` prints the default to start from).
    #[arg(long, value_name = "FILE")]
    pub(crate) machine: Option<PathBuf>,
    /// Controller profile: fanuc, syntec, fanuc0m, mitsubishi, haas, sinumerik or sinumerik828d (default: the machine file's, else fanuc; SINUMERIK programs run on sinumerik).
    #[arg(long, value_name = "NAME")]
    pub(crate) profile: Option<ProfileName>,
}

impl MachineChoice {
    /// The machine file's text (the embedded default's without `--machine`).
    pub(crate) fn text(&self) -> Result<String, CliError> {
        match &self.machine {
            Some(path) => std::fs::read_to_string(path).map_err(|source| CliError::ReadMachine {
                path: path.clone(),
                source,
            }),
            None => Ok(vcnc::machine::DEFAULT_MACHINE_TOML.to_string()),
        }
    }

    /// The machine to run on.
    pub(crate) fn machine(&self) -> Result<Machine, CliError> {
        let machine = match &self.machine {
            Some(path) => {
                Machine::from_toml(&self.text()?).map_err(|source| CliError::Machine {
                    path: Some(path.clone()),
                    source,
                })?
            }
            None => Machine::default(),
        };
        match self.profile {
            Some(name) => machine
                .with_profile(name)
                .map_err(|source| CliError::Machine { path: None, source }),
            None => Ok(machine),
        }
    }
}

/// Machine and control options.
#[derive(Args, Debug, Clone)]
pub(crate) struct MachineArgs {
    #[command(flatten)]
    pub(crate) choice: MachineChoice,
    /// Turn block skip switch N on (1-9; repeatable): blocks starting with `/N` are skipped.
    #[arg(long = "block-skip", value_name = "N", num_args = 0..=1, default_missing_value = "1")]
    pub(crate) block_skip: Vec<u8>,
    /// Feed override, percent (as the panel's dial): scales programmed feeds, not rapids.
    #[arg(
        long = "feed-override",
        value_name = "PERCENT",
        default_value_t = 100.0
    )]
    pub(crate) feed_override: f64,
    /// A program directory (repeatable): M98, M198, G65 and G66 find O1234 there as a file
    /// named `O1234`, `O1234.nc` or `1234.nc`, or headed by `O1234`. The program's own
    /// directory is searched last.
    #[arg(long = "lib", value_name = "DIR")]
    pub(crate) lib: Vec<PathBuf>,
    /// Machine state file: the persistent macro variables #500-#999 are read from it and
    /// saved to it. `run` keeps one by default, beside the machine file as
    /// `<machine>.state.toml` (none for the embedded machine); `check` and `trace` only with
    /// this option, so that running them twice gives the same result.
    #[arg(long, value_name = "FILE", conflicts_with = "no_state")]
    pub(crate) state: Option<PathBuf>,
    /// Neither read nor save a state file: the persistent variables start vacant.
    #[arg(long = "no-state")]
    pub(crate) no_state: bool,
    /// True for a command that keeps the machine's default state file (`run`).
    #[arg(skip)]
    pub(crate) keeps_state: bool,
    /// How many times a main program that ends in M99 runs (the control repeats it forever).
    #[arg(long = "main-passes", value_name = "N", default_value_t = 1)]
    pub(crate) main_passes: u32,
    /// Loop passes and backward jumps allowed before a macro program is taken to loop forever.
    #[arg(long = "max-jumps", value_name = "N", default_value_t = 10_000_000)]
    pub(crate) max_jumps: u64,
    /// The interrupt signal (Syntec's C49) comes during this block of the main program: a line
    /// of its file (`12`) or a sequence number (`N120`); repeatable, once each. With `M96 P_`
    /// in force, program P runs before the block; its M99 brings the tool back and runs the
    /// block again (M99 P_ / Q_: on at that sequence number / line instead).
    #[arg(long = "interrupt", value_name = "LINE|Nn")]
    pub(crate) interrupt: Vec<vcnc::interp::InterruptAt>,
}

impl MachineArgs {
    /// The machine to run on.
    pub(crate) fn machine(&self) -> Result<Machine, CliError> {
        self.choice.machine()
    }

    /// The planner's options (the feed override dial).
    pub(crate) fn plan_options(&self) -> Result<PlanOptions, CliError> {
        let percent = self.feed_override;
        if !(percent > 0.0 && percent <= 1000.0) {
            return Err(CliError::Option {
                option: "--feed-override",
                value: percent.to_string(),
                expected: "expected a percentage above 0, at most 1000",
            });
        }
        Ok(PlanOptions {
            feed_override: percent / 100.0,
        })
    }

    /// The panel switches.
    pub(crate) fn options(&self) -> Result<Options, CliError> {
        let mut options = Options::default();
        for &n in &self.block_skip {
            if !(1..=9).contains(&n) {
                return Err(CliError::Option {
                    option: "--block-skip",
                    value: n.to_string(),
                    expected: "switches are 1 to 9",
                });
            }
            options.block_skip[usize::from(n) - 1] = true;
        }
        if self.main_passes == 0 {
            return Err(CliError::Option {
                option: "--main-passes",
                value: "0".into(),
                expected: "a program runs at least once",
            });
        }
        options.limits.main_program_passes = self.main_passes;
        options.limits.jumps = self.max_jumps;
        options.interrupts.clone_from(&self.interrupt);
        Ok(options)
    }

    /// Finds the errors of the machine file and the options before any program runs.
    pub(crate) fn check(&self) -> Result<(), CliError> {
        self.machine()?;
        self.options()?;
        self.plan_options()?;
        Ok(())
    }

    /// The machine state file, if the command keeps one.
    pub(crate) fn state_file(&self) -> Option<PathBuf> {
        if self.no_state {
            return None;
        }
        self.state.clone().or_else(|| {
            if !self.keeps_state {
                return None;
            }
            let machine = self.choice.machine.as_ref()?;
            let stem = machine.file_stem()?.to_string_lossy().into_owned();
            Some(machine.with_file_name(format!("{stem}.state.toml")))
        })
    }
}
