//! Helpers shared by the integration tests.
#![allow(dead_code, unreachable_pub)]

use std::path::PathBuf;
use vcnc::{interpret_bytes, Alarm, Machine, Options, Segment};

/// The reference material beside the repository (`../shared`), or `$VCNC_SHARED`.
pub fn shared_dir() -> PathBuf {
    if let Some(dir) = std::env::var_os("VCNC_SHARED") {
        return PathBuf::from(dir);
    }
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared");
    assert!(
        dir.is_dir(),
        "the shared reference material is expected at {} (or set VCNC_SHARED)",
        dir.display()
    );
    dir
}

/// Everything a run produced, split into segments and alarms.
pub struct Run {
    pub segments: Vec<Segment>,
    pub alarms: Vec<Alarm>,
}

impl Run {
    /// The first error alarm, if the run stopped with one.
    pub fn error(&self) -> Option<&Alarm> {
        self.alarms.iter().find(|a| a.is_error())
    }
}

/// Runs a program held in memory to its end.
pub fn run(text: &[u8], machine: &Machine, options: Options) -> Run {
    let mut segments = Vec::new();
    let mut alarms = Vec::new();
    for item in interpret_bytes(text, machine, options) {
        match item {
            Ok(segment) => segments.push(segment),
            Err(alarm) => alarms.push(alarm),
        }
    }
    Run { segments, alarms }
}
