//! What a control's custom macros (FANUC Custom Macro B and its relatives) look like: G65/G66
//! arguments, nesting and loop limits, and which system variables exist.

use serde::{Deserialize, Serialize};

/// How the argument letters of G65/G66 become local variables.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MacroArguments {
    /// FANUC argument specification I (A #1, B #2, C #3, I #4, J #5, K #6, D #7, E #8, F #9,
    /// H #11, M #13, Q #17, R #18, S #19, T #20, U #21, V #22, W #23, X #24, Y #25, Z #26) and
    /// II (I, J, K repeated: the n-th I is #(3n+1), J #(3n+2), K #(3n+3)).
    #[default]
    Fanuc,
}

/// Where the tool offsets are among the system variables.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ToolOffsetVariables {
    /// FANUC tool offset memory C: #2001 H wear, #2201 H geometry, #2401 D wear, #2601 D
    /// geometry (200 each; #10001/#11001/#12001/#13001 for 400).
    #[default]
    FanucC,
    /// Haas: #2001 length geometry, #2201 length wear, #2401 diameter geometry, #2601
    /// diameter wear.
    Haas,
}

/// `[macros]`: macro calls, loops and variables (every field has a default: FANUC's).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MacroRules {
    /// How G65/G66 argument letters map to local variables.
    #[serde(default)]
    pub macro_arguments: MacroArguments,
    /// Macro calls (G65, G66) nested at most this deep (FANUC: 4; PS0077 beyond).
    #[serde(default = "default_macro_call_depth")]
    pub macro_call_depth: u32,
    /// The loop numbers DO and END take: 1 to this (FANUC: 3).
    #[serde(default = "default_loop_numbers")]
    pub loop_numbers: u32,
    /// Which system variable numbers hold the tool offsets.
    #[serde(default)]
    pub tool_offset_variables: ToolOffsetVariables,
    /// Syntec's #1000 modal variables, #1901-#1916 G92 offsets and #1930 rotation.
    #[serde(default)]
    pub syntec_system_variables: bool,
    /// Haas's #3020-#3027 timers and spindle data, #4201+ modal data, #5401+ tool life.
    #[serde(default)]
    pub haas_system_variables: bool,
    /// Extra common variables kept between runs (Haas: #10000-#10999), first and last.
    #[serde(default)]
    pub extended_common_variables: Option<(u32, u32)>,
    /// Local variables are #1 to this, a set per macro call level (FANUC: 33; Syntec: 400,
    /// syntec-macro handbook 02-variables 2.1). From 33 to 400.
    #[serde(default = "default_last_local_variable")]
    pub last_local_variable: u32,
    /// Persistent variables are this to #999 (FANUC: 500; Syntec: 401, its "axis group user
    /// memory", handbook 2.6); the numbers from #100 between the locals and these are commons.
    /// From 401 to 500.
    #[serde(default = "default_first_persistent_variable")]
    pub first_persistent_variable: u32,
}

fn default_last_local_variable() -> u32 {
    33
}

fn default_first_persistent_variable() -> u32 {
    500
}

fn default_macro_call_depth() -> u32 {
    4
}

fn default_loop_numbers() -> u32 {
    3
}
