//! The behaviour check: every program vcnc has to answer for — the manuals' examples, the corpus,
//! the test fixtures and the bundled example — is run through `vcnc trace --format jsonl`,
//! `vcnc trace --format csv --work` and `vcnc run --format json`, and a fingerprint of each
//! output (exit code, length and hash of standard output, hash of standard error) is compared
//! with the one kept in `tests/traces.manifest`.
//!
//! A change that reshapes code without meaning to change behaviour must leave every line of the
//! manifest as it is. A change that is meant to change what vcnc does rewrites the lines it
//! changes, and the diff of the manifest shows which programs it touched:
//! `VCNC_BLESS=1 cargo test -p vcnc-cli --test it traces::` (with `../shared` present).
//!
//! The programs under `../shared` are checked only when that folder is there (or `VCNC_SHARED`
//! names it); without it they are skipped with a notice, unless `CI` is set, where they are
//! required. The hash is FNV-1a (64 bits): the check looks for accidental change, not for an
//! adversary.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// Where a program's path is relative to: the path goes on the command line as written, with
/// that folder as the working directory, so the `file` of every record is the same everywhere.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Root {
    Repository,
    Shared,
}

impl Root {
    fn name(self) -> &'static str {
        match self {
            Root::Repository => "repo",
            Root::Shared => "shared",
        }
    }
}

/// One program and the controller profile it was written for.
#[derive(Clone, Debug)]
struct Case {
    root: Root,
    path: String,
    profile: &'static str,
}

/// The commands whose outputs are fingerprinted, by name.
const COMMANDS: &[(&str, &[&str])] = &[
    ("jsonl", &["trace", "--format", "jsonl"]),
    ("csv", &["trace", "--format", "csv", "--work"]),
    ("run", &["run", "--format", "json"]),
];

fn repository() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The control a corpus program was written for (corpus/MANIFEST.md; the same rule as the
/// library's corpus tests).
pub(crate) fn corpus_profile(name: &str) -> &'static str {
    if ["boreyko_", "kiely_", "ramos_", "werocketry_"]
        .iter()
        .any(|author| name.starts_with(author))
        || name.contains("HAAS")
    {
        "haas"
    } else if name.contains("FANUC0M") {
        "fanuc0m"
    } else {
        "fanuc"
    }
}

/// The files below `root/dir` (recursively), as paths relative to `root`, sorted.
fn files_below(root: &Path, dir: &str) -> Vec<String> {
    let mut found = Vec::new();
    let mut pending = vec![root.join(dir)];
    while let Some(folder) = pending.pop() {
        let Ok(entries) = std::fs::read_dir(&folder) else {
            continue;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                pending.push(path);
            } else if let Ok(relative) = path.strip_prefix(root) {
                found.push(relative.to_string_lossy().replace('\\', "/"));
            }
        }
    }
    found.sort();
    found
}

fn cases(shared: Option<&Path>) -> Vec<Case> {
    let mut cases = vec![Case {
        root: Root::Repository,
        path: "examples/bracket.nc".into(),
        profile: "fanuc",
    }];
    let repository = repository();
    for dir in ["crates/vcnc/tests/data", "crates/vcnc-cli/tests/data"] {
        for path in files_below(&repository, dir) {
            if path.ends_with(".ngc") || path.ends_with(".nc") {
                cases.push(Case {
                    root: Root::Repository,
                    path,
                    profile: "fanuc",
                });
            }
        }
    }
    let Some(shared) = shared else {
        return cases;
    };
    for path in files_below(shared, "spec/examples") {
        let folder = path.split('/').nth(2).unwrap_or_default();
        let profile = match folder {
            "syntec" => "syntec",
            "fanuc0m" => "fanuc0m",
            "mitsubishi" => "mitsubishi",
            _ => "fanuc",
        };
        cases.push(Case {
            root: Root::Shared,
            path,
            profile,
        });
    }
    for path in files_below(shared, "corpus") {
        if path.ends_with(".md") {
            continue;
        }
        let name = path.rsplit('/').next().unwrap_or_default();
        let profile = corpus_profile(name);
        cases.push(Case {
            root: Root::Shared,
            path,
            profile,
        });
    }
    cases
}

/// 64-bit FNV-1a.
fn hash(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// The manifest's key of one program and command.
fn key(case: &Case, command: &str) -> String {
    format!(
        "{}:{}\t{}\t{command}",
        case.root.name(),
        case.path,
        case.profile
    )
}

/// The fingerprint of one command's run on one program.
fn fingerprint(case: &Case, folder: &Path, arguments: &[&str]) -> String {
    let output = Command::new(env!("CARGO_BIN_EXE_vcnc"))
        .args(arguments)
        .args(["--profile", case.profile, &case.path])
        .current_dir(folder)
        .env("NO_COLOR", "1")
        .output()
        .expect("vcnc runs");
    let code = output
        .status
        .code()
        .map_or_else(|| "signal".to_string(), |c| c.to_string());
    format!(
        "{code}\t{}\t{:016x}\t{:016x}",
        output.stdout.len(),
        hash(&output.stdout),
        hash(&output.stderr)
    )
}

fn manifest_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/traces.manifest")
}

/// The manifest's lines: key -> fingerprint.
fn read_manifest() -> BTreeMap<String, String> {
    let text = std::fs::read_to_string(manifest_path()).unwrap_or_default();
    text.lines()
        .filter(|line| !line.starts_with('#') && !line.is_empty())
        .filter_map(|line| {
            let mut fields = line.splitn(4, '\t');
            let key = [fields.next()?, fields.next()?, fields.next()?].join("\t");
            Some((key, fields.next()?.to_string()))
        })
        .collect()
}

fn write_manifest(lines: &BTreeMap<String, String>) {
    let mut text = String::from(
        "# Fingerprints of vcnc's output on every program it answers for: program, profile, command,\n\
         # exit code, stdout bytes, stdout FNV-1a, stderr FNV-1a. Written by\n\
         # `VCNC_BLESS=1 cargo test -p vcnc-cli --test it traces::`; see tests/it/traces.rs.\n",
    );
    for (key, value) in lines {
        text.push_str(&format!("{key}\t{value}\n"));
    }
    std::fs::write(manifest_path(), text).expect("the manifest is writable");
}

/// Runs every case's commands on one thread per core.
fn fingerprints(cases: &[Case], shared: Option<&Path>) -> BTreeMap<String, String> {
    let repository = repository();
    let jobs: Vec<(&Case, &str, &[&str])> = cases
        .iter()
        .flat_map(|case| {
            COMMANDS
                .iter()
                .map(move |(name, args)| (case, *name, *args))
        })
        .collect();
    let next = AtomicUsize::new(0);
    let results = Mutex::new(BTreeMap::new());
    let workers = std::thread::available_parallelism().map_or(2, |n| n.get());
    std::thread::scope(|scope| {
        for _ in 0..workers {
            scope.spawn(|| loop {
                let index = next.fetch_add(1, Ordering::Relaxed);
                let Some(&(case, name, args)) = jobs.get(index) else {
                    break;
                };
                let folder = match case.root {
                    Root::Repository => repository.as_path(),
                    Root::Shared => shared.expect("shared cases only with shared"),
                };
                let value = fingerprint(case, folder, args);
                results
                    .lock()
                    .expect("no worker panics while holding the lock")
                    .insert(key(case, name), value);
            });
        }
    });
    results.into_inner().expect("the workers are done")
}

#[test]
fn every_program_gives_the_output_recorded_in_the_manifest() {
    let shared = crate::shared::shared_dir();
    let cases = cases(shared.as_deref());
    let now = fingerprints(&cases, shared.as_deref());
    let recorded = read_manifest();
    if std::env::var_os("VCNC_BLESS").is_some() {
        assert!(
            shared.is_some(),
            "blessing needs ../shared: the manifest covers its programs"
        );
        write_manifest(&now);
        return;
    }
    let mut differences = Vec::new();
    for (key, value) in &now {
        match recorded.get(key) {
            Some(old) if old == value => {}
            Some(old) => differences.push(format!("changed  {key}\n  was {old}\n  now {value}")),
            None => differences.push(format!("new      {key}")),
        }
    }
    for key in recorded.keys() {
        let is_shared = key.starts_with("shared:");
        if !now.contains_key(key) && (shared.is_some() || !is_shared) {
            differences.push(format!("missing  {key}"));
        }
    }
    assert!(
        differences.is_empty(),
        "{} of {} outputs differ from tests/traces.manifest (if the change is meant, rewrite it \
         with `VCNC_BLESS=1 cargo test -p vcnc-cli --test it traces::` and review its diff):\n{}",
        differences.len(),
        now.len(),
        differences
            .iter()
            .take(30)
            .cloned()
            .collect::<Vec<_>>()
            .join("\n")
    );
}
