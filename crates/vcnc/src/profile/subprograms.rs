//! How a control calls subprograms and ends them: which M codes call and return, M98's repeat
//! count, M97, what M02/M30 do in a subprogram, and how deep calls nest.

use serde::{Deserialize, Serialize};

/// `[subprograms]`: subprogram calls and returns (macro calls are the macros').
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SubprogramRules {
    /// M codes that are subprogram calls and returns on this control: 98 call, 99 return,
    /// 198 external call (Syntec), 96/97 interrupt on/off (Syntec) or 97 local call (Haas, see
    /// `m97_local_subprogram`).
    pub subprogram_m_codes: Vec<u32>,
    /// M97 P calls sequence number P of the running program (Haas); otherwise M97 turns the
    /// interrupt program off (Syntec).
    #[serde(default)]
    pub m97_local_subprogram: bool,
    /// `M98 P50001` without L calls O0001 five times: the digits before the last four count
    /// the repeats (FANUC).
    #[serde(default)]
    pub m98_p_holds_repeats: bool,
    /// M02 and M30 in a subprogram return to the caller (Syntec, spec section 2 item 12);
    /// otherwise they end the program (FANUC).
    #[serde(default)]
    pub end_in_subprogram_returns: bool,
    /// Subprogram and macro calls together nested at most this deep (FANUC 0i: 10).
    #[serde(default = "default_call_depth")]
    pub call_depth: u32,
}

fn default_call_depth() -> u32 {
    10
}
