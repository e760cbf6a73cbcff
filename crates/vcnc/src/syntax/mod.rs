//! What a program says, before anyone decides what it means.
//!
//! The front ends turn program text into [`Block`]s of [`Word`]s, each carrying the [`Span`] it
//! was read from. Syntax knows nothing of machines, profiles' modal groups or units: a number is
//! kept as written (value, decimal point, sign) and the interpreter decides what it means.
//! Front ends never fail: a block that cannot be read carries the alarm, and reading goes on with
//! the next block.

pub mod blocks;
mod decimal;
pub mod expr;
pub mod iso;
pub mod lines;
pub mod sinumerik;

use crate::alarm::Alarm;
use crate::source::Span;
pub use expr::{Expr, Instruction, Statement, Target, VariableBank};

/// A number as written in a word: its value and how it was written.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Number {
    /// The value as written, with no unit applied (`X25` is 25.0, `X25.` is 25.0).
    pub value: f64,
    /// True when the number was written with a decimal point: `X25` reads in least input
    /// increments on most profiles, `X25.` in millimetres or inches.
    pub decimal_point: bool,
    /// True when written with a minus sign, also for `-0` (G45-G48 tell `Y0` from `Y-0`).
    pub negative: bool,
}

impl Number {
    /// The value as a code number in tenths (`54.1` is 541), if it has at most one decimal.
    pub fn tenths(&self) -> Option<i32> {
        let scaled = self.value * 10.0;
        // NaN fails this test too.
        if scaled.abs() >= 1e9 || scaled.is_nan() {
            return None;
        }
        // Rounded by a cast (no call to libm's `round`): G numbers are read for every block.
        let rounded = (scaled + if scaled < 0.0 { -0.5 } else { 0.5 }) as i32;
        if (scaled - f64::from(rounded)).abs() < 1e-6 {
            Some(rounded)
        } else {
            None
        }
    }

    /// The value as a whole number, if it is one.
    pub fn whole(&self) -> Option<i64> {
        let rounded = self.value.round();
        if (self.value - rounded).abs() < 1e-9 && rounded.abs() < 9.0e15 {
            Some(rounded as i64)
        } else {
            None
        }
    }
}

/// One address and its value: `X-12.5`, `G54.1`, `F2=1000`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Word {
    /// The address letter, upper case (`b'X'`). Program numbers written `:1234` use `b'O'`.
    pub letter: u8,
    /// The index of an extended address (`F2=` has 2, `S1=` has 1); 0 for plain addresses.
    pub index: u8,
    /// The value as written.
    pub number: Number,
    /// Where the word stands.
    pub span: Span,
    /// The value is an expression of the block's `code` (`X#1`, `G#8`, `P[10]`); `number` is
    /// then meaningless.
    pub expr: Option<Expr>,
}

/// What kind of block this is.
#[derive(Clone, Debug, PartialEq)]
pub enum BlockKind {
    /// An ordinary block of words (possibly none: a comment-only or empty line).
    Words,
    /// A `%` tape mark.
    TapeMark,
    /// `%@MACRO`: the program is a Syntec macro program (when this is its first line).
    MacroHeader,
}

/// One block: the words between two ends of block, in the order written.
#[derive(Clone, Debug, PartialEq)]
pub struct Block {
    /// The whole block, comments included.
    pub span: Span,
    /// The block-skip level when the block starts with `/` (1 for a bare `/`, n for `/n`).
    pub skip: Option<u8>,
    /// Ordinary words or a tape mark.
    pub kind: BlockKind,
    /// The words, in the order written (the sequence number `N` included).
    pub words: Vec<Word>,
    /// The span of the first comment, if any (program titles, operator messages).
    pub comment: Option<Span>,
    /// The problems found while reading the block; the block holds the words read before the first error.
    pub alarms: Vec<Alarm>,
    /// Macro statements (assignments, IF, WHILE, GOTO, END ...), in the order written.
    pub statements: Vec<Statement>,
    /// The instructions of the block's expressions (statements' and words').
    pub code: Vec<Instruction>,
    /// The text of the first comment, kept for blocks with statements only: `#3000 = 1 (NO
    /// TOOL)` shows it as the alarm message.
    pub message: Option<Box<str>>,
}

impl Block {
    /// An empty block, ready to be filled by a front end.
    pub fn new() -> Block {
        Block {
            span: Span::default(),
            skip: None,
            kind: BlockKind::Words,
            words: Vec::new(),
            comment: None,
            alarms: Vec::new(),
            statements: Vec::new(),
            code: Vec::new(),
            message: None,
        }
    }

    /// Empties the block for reuse, keeping its allocation.
    #[inline]
    pub fn clear(&mut self) {
        self.span = Span::default();
        self.skip = None;
        self.kind = BlockKind::Words;
        self.words.clear();
        self.comment = None;
        // A block of plain words, the common one, has nothing more to clear: one test for it.
        if !self.alarms.is_empty()
            | !self.statements.is_empty()
            | !self.code.is_empty()
            | self.message.is_some()
        {
            self.clear_contents();
        }
    }

    /// Empties what only blocks with alarms, statements or expressions hold.
    #[cold]
    fn clear_contents(&mut self) {
        self.alarms.clear();
        self.statements.clear();
        self.code.clear();
        self.message = None;
    }

    /// The first word with this letter (and no extended index).
    pub fn word(&self, letter: u8) -> Option<&Word> {
        self.words
            .iter()
            .find(|w| w.letter == letter && w.index == 0)
    }

    /// True when the block has no words, no statements and is not a tape mark.
    pub fn is_empty(&self) -> bool {
        self.kind == BlockKind::Words && self.words.is_empty() && self.statements.is_empty()
    }

    /// True when the block needs the macro executor: statements, or words whose values are
    /// expressions.
    pub fn has_macro(&self) -> bool {
        !self.code.is_empty() || !self.statements.is_empty()
    }
}

impl Default for Block {
    fn default() -> Block {
        Block::new()
    }
}

/// The program dialect a front end reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Dialect {
    /// FANUC-family ISO G-code (FANUC, Syntec, Mitsubishi, Haas).
    Iso,
    /// SINUMERIK 840D sl / 828D.
    Sinumerik,
}

/// Guesses the dialect of a program from its file name and first lines.
///
/// SINUMERIK programs are recognised by their `.MPF`/`.SPF` extension, by `%_N_..._MPF`
/// headers and `PROC`, `DEF` or `EXTERN` lines, and by `MSG(` — but `MSG(` is also a Syntec
/// macro function: a program with a `%@MACRO` header, `:=` assignments, `//` comments or `#`
/// variables in its first lines is ISO whatever else it holds.
pub fn detect_dialect(file_name: &str, head: &[u8]) -> Dialect {
    let lower = file_name.to_ascii_lowercase();
    if lower.ends_with(".mpf") || lower.ends_with(".spf") {
        return Dialect::Sinumerik;
    }
    let head = &head[..head.len().min(4096)];
    let text = String::from_utf8_lossy(head);
    let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
    let (mut sinumerik, mut message, mut iso_macro) = (false, false, false);
    for line in text.split(['\n', '\r']).take(40) {
        let line = line.trim_start();
        let upper = line.to_ascii_uppercase();
        // After a block number: `N20 DEF INT I`.
        let code = without_block_number(&upper);
        let code = code.split(';').next().unwrap_or_default();
        let code = &without_paren_comments(code);
        sinumerik |= upper.starts_with("%_N_")
            || code.starts_with("PROC ")
            || code.starts_with("DEF ")
            || code.starts_with("EXTERN ")
            || sinumerik_words(code);
        message |= upper.contains("MSG(") || upper.contains("MSG (\"");
        iso_macro |= upper.starts_with("%@MACRO")
            || upper.starts_with("//")
            || upper.contains(":=")
            || has_numbered_variable(&upper);
    }
    if iso_macro && !sinumerik {
        return Dialect::Iso;
    }
    if sinumerik || message {
        return Dialect::Sinumerik;
    }
    Dialect::Iso
}

/// `line` without ISO comments: a `(` at the start or after a blank opens one, to its `)` (a
/// SINUMERIK expression's parenthesis follows a name or an operator: `X=IC(5)`, `X=(1+2)`).
fn without_paren_comments(line: &str) -> String {
    let mut out = String::with_capacity(line.len());
    let mut depth = 0u32;
    let mut previous = ' ';
    for c in line.chars() {
        match c {
            '(' if depth > 0 || previous.is_whitespace() => depth += 1,
            ')' if depth > 0 => depth -= 1,
            _ if depth > 0 => {}
            c => out.push(c),
        }
        previous = c;
    }
    out
}

/// `line` without a leading block number (`N20 `, `:20 `).
fn without_block_number(line: &str) -> &str {
    let rest = line
        .strip_prefix('N')
        .or_else(|| line.strip_prefix(':'))
        .filter(|rest| rest.starts_with(|c: char| c.is_ascii_digit()));
    match rest {
        Some(rest) => rest
            .trim_start_matches(|c: char| c.is_ascii_digit())
            .trim_start(),
        None => line,
    }
}

/// True when a block (upper case, no comment) holds words only SINUMERIK writes: `CR=`, `X=IC(`,
/// `RND=`, `R1=`, the frame instructions and control structures with their own keywords.
fn sinumerik_words(code: &str) -> bool {
    const MARKS: [&str; 12] = [
        "CR=", "=IC(", "=AC(", "RND=", "CHF=", "AP=", "RP=", "TURN=", "GOTOF ", "GOTOB ", "ENDIF",
        "MCALL",
    ];
    let starts = [
        "TRANS ", "ATRANS ", "AROT ", "ROT ", "SUPA ", "ENDWHILE", "ENDFOR",
    ];
    MARKS.iter().any(|m| code.contains(m))
        || starts.iter().any(|s| code.starts_with(s))
        || code.as_bytes().windows(3).enumerate().any(|(i, w)| {
            w[0] == b'R'
                && (i == 0 || !code.as_bytes()[i - 1].is_ascii_alphanumeric())
                && w[1].is_ascii_digit()
                && code[i + 1..]
                    .trim_start_matches(|c: char| c.is_ascii_digit())
                    .starts_with('=')
        })
}

/// True when `line` holds a `#` followed by a digit or `[` (`#1`, `#[#2+1]`): a FANUC-family
/// macro variable, which SINUMERIK does not write.
fn has_numbered_variable(line: &str) -> bool {
    line.as_bytes()
        .windows(2)
        .any(|w| w[0] == b'#' && (w[1].is_ascii_digit() || w[1] == b'['))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sinumerik_words_tell_a_program_without_a_header() {
        for text in [
            "N20 DEF INT VAR1=5\nG0 X1",
            "G0 X0 Y0\nG2 X10 Y0 CR=5",
            "G1 X=IC(5) F100",
            "R1=10 ; depth\nG0 Z=R1",
            "N10 TRANS X10\nG0 X0",
            "G1 X10 RND=2",
        ] {
            assert_eq!(
                detect_dialect("part.nc", text.as_bytes()),
                Dialect::Sinumerik,
                "{text}"
            );
        }
        for text in [
            "G0 X1 R5.\nG2 X10 R5.",
            "#1=5\nG0 X#1",
            "O1234\nG81 R2. Z-5. F100",
            "(T1  D=2.65 CR=0 - ZMIN=-13.3 - flat end mill)\nG0 X1",
        ] {
            assert_eq!(
                detect_dialect("part.nc", text.as_bytes()),
                Dialect::Iso,
                "{text}"
            );
        }
    }

    #[test]
    fn g_code_numbers_are_read_in_tenths() {
        let n = |value| Number {
            value,
            decimal_point: true,
            negative: false,
        };
        assert_eq!(n(54.1).tenths(), Some(541));
        assert_eq!(n(1.0).tenths(), Some(10));
        assert_eq!(n(0.05).tenths(), None);
    }

    #[test]
    fn sinumerik_programs_are_recognised_by_name_and_header() {
        assert_eq!(detect_dialect("A.MPF", b"G0 X1"), Dialect::Sinumerik);
        assert_eq!(
            detect_dialect("a.nc", b"%_N_TEST_MPF\n;$PATH=/x\n"),
            Dialect::Sinumerik
        );
        assert_eq!(detect_dialect("a.nc", b"%\nO1000\nG0 X1.\n"), Dialect::Iso);
        assert_eq!(
            detect_dialect("a.nc", b"G0 X1\rMSG(\"START\")\rM30"),
            Dialect::Sinumerik
        );
    }

    #[test]
    fn syntec_macro_programs_with_msg_are_iso() {
        let syntec = [
            &b"%@MACRO\nMSG(\"ROUGHING\");\nG0 X1.;\nM30;\n"[..],
            b"\xEF\xBB\xBF%@MACRO\r// roughing\rMSG(\"GO\");\rM30;\r",
            b"%\n@1 := 10;\nMSG(\"A\");\n",
            b"O1000\n#1 = 5\nMSG(\"A\")\nM30\n",
            b"// by hand\nMSG(\"B\");\n",
        ];
        for text in syntec {
            assert_eq!(
                detect_dialect("p.nc", text),
                Dialect::Iso,
                "{}",
                String::from_utf8_lossy(text)
            );
        }
        // The headers that only SINUMERIK writes outweigh all of that.
        assert_eq!(
            detect_dialect("p.nc", b"%_N_P_MPF\nDEF INT N := 1\nMSG(\"X\")\n"),
            Dialect::Sinumerik
        );
    }
}
