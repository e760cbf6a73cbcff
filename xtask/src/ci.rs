//! `cargo xtask ci`: what CI runs (`.ci/run`), the one command README.md gives for it. It checks
//! that the running rustc is not older than the workspace's declared `rust-version`, then runs
//! formatting, clippy, the docs and the tests in that order, stopping at the first failure. It
//! must never print after the tests: CI reads cargo's result lines at the end of the output.

use std::path::{Path, PathBuf};
use std::process::Command;

/// One step: cargo's arguments and the environment variables it adds.
struct Step {
    args: &'static [&'static str],
    env: &'static [(&'static str, &'static str)],
}

const STEPS: &[Step] = &[
    Step {
        args: &["fmt", "--all", "--check"],
        env: &[],
    },
    Step {
        args: &[
            "clippy",
            "--workspace",
            "--all-targets",
            "--locked",
            "--",
            "-D",
            "warnings",
        ],
        env: &[],
    },
    Step {
        args: &["doc", "--no-deps", "--workspace", "--locked"],
        env: &[("RUSTDOCFLAGS", "-D warnings")],
    },
    Step {
        args: &["test", "--workspace", "--locked"],
        env: &[],
    },
];

pub(crate) fn run(args: &[String]) -> Result<(), String> {
    if let Some(extra) = args.first() {
        return Err(format!("`ci` takes no arguments, got `{extra}`"));
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    check_rustc(&root)?;
    // The cargo that runs this task, so that every step uses the same toolchain.
    let cargo = std::env::var_os("CARGO").map_or_else(|| PathBuf::from("cargo"), PathBuf::from);
    for step in STEPS {
        let line = step
            .env
            .iter()
            .map(|(name, value)| format!("{name}='{value}' "))
            .chain([format!("cargo {}", step.args.join(" "))])
            .collect::<String>();
        println!("==> {line}");
        let status = Command::new(&cargo)
            .args(step.args)
            .envs(step.env.iter().copied())
            .current_dir(&root)
            .status()
            .map_err(|e| format!("cannot start `{line}`: {e}"))?;
        if !status.success() {
            return Err(format!("`{line}` failed ({status})"));
        }
    }
    Ok(())
}

/// Fails when `rustc --version` is older than the `rust-version` the workspace's Cargo.toml
/// declares: a build that passes on a newer compiler only is no proof for the declared one.
fn check_rustc(root: &Path) -> Result<(), String> {
    let manifest = root.join("Cargo.toml");
    let text =
        std::fs::read_to_string(&manifest).map_err(|e| format!("{}: {e}", manifest.display()))?;
    let declared = text
        .lines()
        .find_map(|line| {
            let (key, value) = line.split_once('=')?;
            (key.trim() == "rust-version").then(|| value.trim().trim_matches('"').to_string())
        })
        .ok_or_else(|| format!("{} declares no rust-version", manifest.display()))?;
    let output = Command::new("rustc")
        .arg("--version")
        .output()
        .map_err(|e| format!("cannot run `rustc --version`: {e}"))?;
    let reported = String::from_utf8_lossy(&output.stdout);
    // `rustc 1.95.0 (59807616e 2026-04-14)`: the second word.
    let running = reported.split_whitespace().nth(1).unwrap_or_default();
    let (Some(want), Some(have)) = (version(&declared), version(running)) else {
        return Err(format!(
            "cannot compare rustc `{}` with rust-version `{declared}`",
            reported.trim()
        ));
    };
    if have < want {
        return Err(format!(
            "rustc {running} is older than the rust-version {declared} that Cargo.toml declares \
             (the version CI builds with): install {declared} or newer"
        ));
    }
    println!("==> rustc {running}, declared rust-version {declared}");
    Ok(())
}

/// `1.95` or `1.95.0` (a `-nightly` or `-beta.N` tail ignored) as (major, minor, patch).
fn version(text: &str) -> Option<(u32, u32, u32)> {
    let numbers = text.split('-').next()?;
    let mut parts = numbers.split('.').map(str::parse::<u32>);
    let major = parts.next()?.ok()?;
    let minor = parts.next()?.ok()?;
    let patch = parts.next().transpose().ok()?.unwrap_or(0);
    parts.next().is_none().then_some((major, minor, patch))
}

#[cfg(test)]
mod tests {
    use super::version;

    #[test]
    fn versions_compare_by_number_not_by_text() {
        assert_eq!(version("1.95"), Some((1, 95, 0)));
        assert_eq!(version("1.95.0"), Some((1, 95, 0)));
        assert_eq!(version("1.96.0-nightly"), Some((1, 96, 0)));
        assert!(version("1.9.0") < version("1.80"));
        assert_eq!(version("1"), None);
        assert_eq!(version("1.x"), None);
    }
}
