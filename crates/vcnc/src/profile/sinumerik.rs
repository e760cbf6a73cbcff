//! The settings of the SINUMERIK profiles: what the machine data of an 840D sl or 828D decide
//! for a program (docs/SINUMERIK.md section 8). The ISO fields of [`Profile`](super::Profile)
//! do not apply to SINUMERIK programs; these do.

use serde::{Deserialize, Serialize};

/// Which SINUMERIK control.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Variant {
    /// 840D sl: G58/G59 are axial programmable offsets, 99 settable frames.
    #[serde(rename = "840d")]
    Sl840d,
    /// 828D: G58/G59 are the 5th and 6th settable frames; G505..G599 do not exist.
    #[serde(rename = "828d")]
    M828d,
}

/// What a SINUMERIK machine's data decide for its programs.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SinumerikSettings {
    /// 840D sl or 828D.
    pub variant: Variant,
    /// The G functions in force at power-on and reset, one per group (MD20150
    /// `$MC_GCODE_RESET_VALUES`); a group not named takes the Siemens default.
    pub power_on: Vec<String>,
    /// R parameters R0 .. R(n-1) (MD28050 `$MC_MM_NUM_R_PARAM`).
    #[serde(default = "default_r_parameters")]
    pub r_parameters: u32,
    /// After a frame change, an incremental value traverses the change too (SD42440
    /// `$SC_FRAME_OFFSET_INCR_PROG` = 1, the default); false: only the programmed distance.
    #[serde(default = "default_true")]
    pub frame_change_in_increments: bool,
    /// T alone changes the tool (MD22550 `$MC_TOOL_CHANGE_MODE` = 0); false: T selects and
    /// M6 changes (milling machines with a magazine).
    #[serde(default)]
    pub t_changes_tool: bool,
    /// Which edge a tool change leaves active when the block names no D (MD20270
    /// `$MC_CUTTING_EDGE_DEFAULT`): n > 0 Dn, 0 none, -1 the same D number, -2 the old tool's
    /// offset until a D is programmed.
    #[serde(default = "default_cutting_edge")]
    pub cutting_edge_default: i32,
    /// MD20124 `$MC_TOOL_MANAGEMENT_TOOLHOLDER`: above 1, the toolholders decide the tool
    /// change and SVC acts on the spindle of the active offset's toolholder; 0: each spindle
    /// is its own toolholder.
    #[serde(default)]
    pub toolholder_management: u32,
    /// The number of settable frames G505.. beyond G54..G57 (MD28080; 840D only).
    #[serde(default = "default_user_frames")]
    pub user_frames: u32,
    /// Loop passes and jumps a program may make before the run stops with an alarm (a control
    /// would run for ever; a checker must end).
    #[serde(default = "default_iteration_limit")]
    pub iteration_limit: u64,
    /// Subprogram levels (the main program is level 0; the control has 16, cycles included).
    #[serde(default = "default_call_depth")]
    pub call_depth: u32,
}

fn default_r_parameters() -> u32 {
    100
}

fn default_cutting_edge() -> i32 {
    1
}

fn default_true() -> bool {
    true
}

fn default_user_frames() -> u32 {
    5
}

fn default_iteration_limit() -> u64 {
    10_000_000
}

fn default_call_depth() -> u32 {
    16
}
