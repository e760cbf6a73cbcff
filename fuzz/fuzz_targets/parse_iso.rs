//! Fuzz target: the ISO front end alone, `parse_line` over the lines of `TextLines`, with the
//! character rules of every built-in profile.
//!
//! Properties: no panic; every line lies inside the input and is the text at its offset (after
//! [`normalize`](vcnc::syntax::lines::normalize), which keeps every byte's place); every
//! block's span, word's span, comment's span and alarm's span lie inside its line (and so inside
//! the input) and name that line; every word lies inside its block, has an upper-case letter and
//! a non-empty span, and follows the word before it without overlap; every alarm has a span and a
//! one-line message.
//! (Words cannot be printed back yet, so "parse, print, parse again" waits for a printer.)
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::sync::OnceLock;
use vcnc::source::{FileId, Span};
use vcnc::syntax::iso::{parse_line, LineBlocks, SyntaxOptions};
use vcnc::syntax::lines::{LineSource, TextLines};
use vcnc::{Profile, ProfileName};

/// The distinct character rules of the built-in profiles.
fn syntaxes() -> &'static [SyntaxOptions] {
    static SYNTAXES: OnceLock<Vec<SyntaxOptions>> = OnceLock::new();
    SYNTAXES.get_or_init(|| {
        let mut all: Vec<SyntaxOptions> = Vec::new();
        for name in ProfileName::ALL {
            let syntax = Profile::builtin(name).syntax();
            if !all.contains(&syntax) {
                all.push(syntax);
            }
        }
        all
    })
}

fuzz_target!(|data: &[u8]| {
    let len = data.len();
    // Lines are the text with a byte-order mark blanked and lone CRs made line ends, in place.
    let mut normalized = data.to_vec();
    vcnc::syntax::lines::normalize(&mut normalized, true);
    let mut blocks = LineBlocks::new();
    for syntax in syntaxes() {
        let mut lines = TextLines::new(data);
        let mut previous_end = 0usize;
        while let Some(line) = lines
            .next_line()
            .expect("in-memory text cannot fail to read")
        {
            let start = line.offset as usize;
            let end = start + line.text.len();
            assert!(
                start >= previous_end && end <= len,
                "line {} at {start}..{end} is outside 0..{len}",
                line.number
            );
            assert_eq!(
                &normalized[start..end],
                line.text,
                "line {} is not the text at its offset",
                line.number
            );
            previous_end = end;
            parse_line(line, FileId(0), syntax, &mut blocks);
            let inside = |span: Span, what: &dyn std::fmt::Debug| {
                assert!(
                    start as u32 <= span.start
                        && span.start <= span.end
                        && span.end as usize <= end,
                    "span {span} of {what:?} is outside line {} ({start}..{end}) with {syntax:?}",
                    line.number
                );
                assert_eq!(
                    span.line, line.number,
                    "span {span} of {what:?} names the wrong line"
                );
            };
            for block in blocks.as_slice() {
                inside(block.span, block);
                let mut word_end = start as u32;
                for word in &block.words {
                    inside(word.span, word);
                    assert!(
                        block.span.start <= word.span.start && word.span.end <= block.span.end,
                        "word {word:?} is outside its block {}",
                        block.span
                    );
                    assert!(
                        word.span.start >= word_end,
                        "word {word:?} overlaps the word before it"
                    );
                    assert!(
                        word.span.start < word.span.end,
                        "word {word:?} has an empty span"
                    );
                    assert!(
                        word.letter.is_ascii_uppercase(),
                        "word {word:?} has no upper-case letter"
                    );
                    word_end = word.span.end;
                }
                if let Some(comment) = block.comment {
                    inside(comment, block);
                }
                for alarm in &block.alarms {
                    let span = alarm
                        .span
                        .unwrap_or_else(|| panic!("front-end alarm without a span: {alarm:?}"));
                    inside(span, alarm);
                    assert!(
                        !alarm.message.is_empty() && !alarm.message.contains('\n'),
                        "{alarm:?}"
                    );
                }
            }
        }
        assert!(previous_end <= len);
    }
});
