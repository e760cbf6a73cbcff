//! How a control reads a dwell time: G04's P and X, and the P of the canned cycles.

use serde::{Deserialize, Serialize};

/// How `P` of G04 is read.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DwellP {
    /// Milliseconds; a decimal point is an alarm (FANUC).
    MillisecondsStrict,
    /// Milliseconds; a fraction is dropped (`P2.5` is 2 ms, Syntec manual L512).
    MillisecondsTruncated,
    /// Milliseconds without a decimal point, seconds with one (Haas, Mitsubishi).
    SecondsWithPoint,
}

/// `[dwell]`: how dwell times are written.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DwellRules {
    /// How G04 P is read.
    pub dwell_p: DwellP,
    /// FANUC 0M quirk (manual 001 L190-202): an X word written before G04 in the same block was
    /// already converted as a distance, and that count of increments becomes milliseconds.
    pub dwell_x_before_g04_is_increments: bool,
    /// How a canned cycle's P is read; when absent, as G04's P.
    #[serde(default)]
    pub cycle_dwell_p: Option<DwellP>,
}
