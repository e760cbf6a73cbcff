//! How a control reads a program's text into blocks and words: block ends, comments, program
//! numbers, the digit limit, and what a block may hold. The number reading of lengths and angles
//! is the units' ([`UnitRules`](super::UnitRules)).

use crate::syntax::iso::SyntaxOptions;
use serde::{Deserialize, Serialize};

/// What two G codes of one modal group in one block do.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SameGroupRule {
    /// The last one written is effective (FANUC); vcnc warns.
    LastWins,
    /// An alarm.
    Alarm,
}

/// `[reading]`: how the text becomes blocks and words (the ISO front end and the decoder read it).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReadingRules {
    /// `;` ends a block (true) or starts a comment (false).
    pub semicolon_ends_block: bool,
    /// `//` starts a comment to the end of the line.
    pub slash_slash_comments: bool,
    /// `:1234` is a program number.
    pub colon_program_number: bool,
    /// Largest magnitude of any value as written (`X99999999` ...): the control's digit limit.
    #[serde(default = "default_max_word_value")]
    pub max_word_value: f64,
    /// M codes a block may hold; when a block has more, only the last ones run (FANUC 0M: one,
    /// spec A.15 and example fanuc0m/06).
    #[serde(default = "default_m_codes_per_block")]
    pub m_codes_per_block: u32,
    /// Two G codes of one group in a block.
    pub same_group: SameGroupRule,
    /// `G` with no number is G00 (Mitsubishi, 003 B.0).
    #[serde(default)]
    pub bare_g_is_g00: bool,
    /// G53 and G28 may share a block, the later one acting (Mitsubishi 003 L79); otherwise two
    /// one-shot codes in a block are an alarm.
    #[serde(default)]
    pub g53_g28_later_wins: bool,
    /// Most digits a number may be written with (FANUC 0M: "generally 7 digits", `X1.2345678`
    /// is an alarm, 001 L79-136); 0: no limit but `max_word_value`.
    #[serde(default)]
    pub max_digits: u32,
    /// A comment ends at its first `)`: `(` is control-out, `)` control-in (FANUC 0M); otherwise
    /// parentheses nest.
    #[serde(default)]
    pub comment_ends_at_first_paren: bool,
}

impl ReadingRules {
    /// The character-level options of the ISO front end.
    pub fn syntax(&self) -> SyntaxOptions {
        SyntaxOptions {
            semicolon_ends_block: self.semicolon_ends_block,
            slash_slash_comments: self.slash_slash_comments,
            colon_program_number: self.colon_program_number,
            bare_g_is_g00: self.bare_g_is_g00,
            comment_ends_at_first_paren: self.comment_ends_at_first_paren,
        }
    }
}

fn default_m_codes_per_block() -> u32 {
    3
}

fn default_max_word_value() -> f64 {
    // Nine digits before the point: FANUC's widest input format.
    999_999_999.0
}
