//! The reader's fast path: the common line of a CAM program, and the common number.
//!
//! A CAM program is hundreds of thousands of lines like `G01 X54.808 Y30.491`: plain words (a
//! letter right before a decimal number) separated by blanks, nothing else. [`read_plain_line`]
//! reads such a line in one pass over its bytes and gives up on anything else, which the general
//! reader then reads; [`read_plain_line_in`] reads it from the text at hand, before the line is
//! cut out, and finds its `\n` on the way (no search of its own for it); [`fast_number`] does the
//! same for the number of one word inside the general reader. In the text at hand, which runs
//! on past the line, the digits of a number are read from fixed windows ([`windowed_decimal`]):
//! the compiler unrolls that loop, and no digit pays an end-of-text test.
//!
//! Invariant: the fast path gives exactly the blocks the general reader gives (values to the
//! bit, spans, decimal points, signs), or nothing. The differential tests at the bottom check it,
//! word by word and line by line. It never raises an alarm: a line that needs one is not plain.

use super::super::LineBlocks;
use crate::source::{FileId, Span};
use crate::syntax::decimal::{unsigned_decimal, windowed_decimal, WINDOW};
use crate::syntax::lines::{Line, Unread};
use crate::syntax::{Number, Word};

/// The longest line the fast path reads: two bytes a word at the least (`X1Y2`), so a plain
/// line holds at most [`super::super::MAX_WORDS_PER_BLOCK`] words; a longer line (none of a
/// real program) is the general reader's, which refuses a block of more words than that.
const MAX_PLAIN_BYTES: usize = 2 * super::super::MAX_WORDS_PER_BLOCK;

/// Reads `line` into one block of `out` when it is a plain line: blanks, then words such as
/// `X-12.5`, `g1` or `Y.5` (a letter, an optional sign, digits with an optional decimal point),
/// each followed by blanks or directly by the next word's letter. Returns false for any other
/// line (comments, `;`, `/`, `%`, `#`, `=`, a blank inside a number, a blank line, a number the
/// general reader would refuse); the block it may have begun is then to be thrown away.
#[inline(always)]
pub(super) fn read_plain_line(line: Line<'_>, file: FileId, out: &mut LineBlocks) -> bool {
    // A span is the line's offset plus a position in the text. When the end of the text fits in
    // u32, that sum never overflows (the general reader saturates: it takes the other lines).
    let Some(text_end) = u32::try_from(line.text.len())
        .ok()
        .and_then(|length| line.offset.checked_add(length))
    else {
        return false;
    };
    if line.text.len() > MAX_PLAIN_BYTES {
        return false;
    }
    // Read as text at hand that ends where the line ends.
    let text = Unread {
        text: line.text,
        end_offset: text_end,
        number: line.number,
    };
    read_plain_words::<false>(text, file, out) == Some(LineEnd::TextEnd)
}

/// Reads the first line of `unread` (text from the start of a line on, its line end included)
/// into one block of `out` when it is a plain line ended by `\n`, as [`read_plain_line`] reads
/// the line without its line end: how many bytes of `unread` follow the line's `\n`, or `None`
/// for a line that is not plain, whose `\n` is not in `unread`, with a `\r` elsewhere than
/// before its `\n`, or with a word or its end closer than [`WINDOW`] + 2 bytes to the end of
/// `unread` (the block it may have begun is then to be thrown away).
#[inline(always)]
pub(super) fn read_plain_line_in(
    unread: Unread<'_>,
    file: FileId,
    out: &mut LineBlocks,
) -> Option<usize> {
    // The text at hand runs past the line, nearly always far enough for the numbers' windows;
    // a number too close to its end leaves the line to the line reader. Cut to
    // [`MAX_PLAIN_BYTES`]: a longer line ends the same way, and goes to the general reader.
    let cut = unread.text.len().saturating_sub(MAX_PLAIN_BYTES);
    let unread = Unread {
        text: &unread.text[..unread.text.len() - cut],
        end_offset: unread.end_offset - cut as u32,
        number: unread.number,
    };
    match read_plain_words::<true>(unread, file, out)? {
        LineEnd::Newline(after) => Some(after + cut),
        LineEnd::TextEnd => None,
    }
}

/// Where a plain line read by [`read_plain_words`] ends.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum LineEnd {
    /// At the end of the text.
    TextEnd,
    /// At a `\n`, followed by this many bytes of the text.
    Newline(usize),
}

/// The reader of both: the words of `line.text` up to its end or its first `\n`, into one block
/// of `out`, and where the line ended; `None` when the line is not plain. `WINDOWED` reads the
/// numbers with [`windowed_decimal`] (also `None` when the text ends too close after one), else
/// with [`unsigned_decimal`].
#[inline(always)]
fn read_plain_words<const WINDOWED: bool>(
    line: Unread<'_>,
    file: FileId,
    out: &mut LineBlocks,
) -> Option<LineEnd> {
    let text = line.text;
    // Every offset in the text fits in u32 (see [`Unread::end_offset`]).
    let text_end = line.end_offset;
    // The offset in the file of the start of `rest`, a tail of the text.
    let offset_of = |rest: &[u8]| text_end - rest.len() as u32;
    // A `\r` at the start is a blank like any other: a line of blanks is not plain.
    let first_word = skip_blanks::<true>(text);
    if matches!(first_word, [] | [b'\n', ..]) {
        return None;
    }
    let line_number = line.number;
    let block = out.push_plain();
    // The block's start, file and line are known now and stored at once (the end is stored at
    // the end); the words take the file and the line from the locals, not from the span.
    block.span = Span::new(file, line_number, offset_of(first_word)..0);
    let mut rest = first_word;
    loop {
        // A word's number needs its window: WINDOW bytes after the letter and the sign. Tested
        // once here, before the letter, the tests of the letter, the sign and the window fold
        // into it (a line's end closer than that to the end of the text is left to the line
        // reader too).
        if WINDOWED && rest.len() < WINDOW + 2 {
            return None;
        }
        let [letter, after_letter @ ..] = rest else {
            break;
        };
        // An ASCII letter and its capital differ in bit 5 alone: one mask tests for a letter and
        // gives the capital.
        let capital = letter & !0x20;
        // E words are rare in plain lines; the general reader tells an exponent (`X1e308`) from
        // the address.
        if !capital.is_ascii_uppercase() || capital == b'E' {
            // Read from the text at hand, the blanks between words leave out `\r`: the `\r` of
            // a `\r\n` ends the line's span, and is found here, off the common path, instead of
            // by a look back from the `\n`. A line with a `\r` elsewhere is left to the line
            // reader (which hands the line out without its line end, where `\r` is a blank).
            match rest {
                [b'\n', ..] | [b'\r', b'\n', ..] => break,
                _ => return None,
            }
        }
        let (number, after_number) = signed_number::<WINDOWED>(after_letter)?;
        block.words.push(Word {
            letter: capital,
            index: 0,
            number,
            // The file and the line from the arguments, not read back from the block's span:
            // the span was just stored as four 32-bit fields, and a 64-bit load of two of them
            // cannot be forwarded from the stores, so it waited until they reached the cache
            // (3.5 % of the interpreter thread's busy time on the 4,000,000-block trace).
            span: Span {
                file,
                line: line_number,
                start: offset_of(rest),
                end: offset_of(after_number),
            },
            expr: None,
        });
        // What follows a word must be the next word's letter, after blanks or none: a digit or
        // a point there (`X1 2.5`, `X1.2.3`), `=` (`F2=100`) or anything else is refused by the
        // letter test above, and the general reader decides.
        rest = if WINDOWED {
            skip_blanks::<false>(after_number)
        } else {
            skip_blanks::<true>(after_number)
        };
    }
    // A line handed out whole has lost the `\r` of its `\r\n`: its span ends before it, where
    // `rest` starts.
    block.span.end = offset_of(rest);
    Some(match rest {
        [] => LineEnd::TextEnd,
        [b'\n', after @ ..] | [_, b'\n', after @ ..] => LineEnd::Newline(after.len()),
        // Any other byte ends the words only when it is refused above.
        _ => return None,
    })
}

/// The common case of the general reader's number: `digits [. digits]` (or `. digits`) with at
/// most [`MAX_DIGITS`](crate::syntax::decimal::MAX_DIGITS) digits and nothing after it that could continue the number (a blank
/// followed by more digits, a second point). Returns the number and the bytes it took; `None`
/// sends the caller to the general path, which gives the same value (checked by the tests).
#[inline(always)]
pub(super) fn fast_number(bytes: &[u8], negative: bool) -> Option<(Number, usize)> {
    let (decimal, rest) = unsigned_decimal(bytes)?;
    match rest.first() {
        Some(b'.') => return None,
        Some(b' ' | b'\t') => {
            // Blanks inside a number are ignored (`X1 2.5`): only a blank before the next word
            // ends it.
            let next = rest.iter().find(|b| !matches!(b, b' ' | b'\t'));
            if matches!(next, Some(b'0'..=b'9' | b'.')) {
                return None;
            }
        }
        _ => {}
    }
    Some((decimal.number(negative), bytes.len() - rest.len()))
}

/// The blanks the reader skips between words (a line end is never inside a line), `\r` among
/// them when `CARRIAGE_RETURN`.
#[inline(always)]
fn is_blank<const CARRIAGE_RETURN: bool>(byte: u8) -> bool {
    matches!(byte, b' ' | b'\t' | b'\x0c' | b'\x0b' | 0) || (CARRIAGE_RETURN && byte == b'\r')
}

/// `bytes` from its first byte that is not a blank (see [`is_blank`]).
#[inline(always)]
fn skip_blanks<const CARRIAGE_RETURN: bool>(bytes: &[u8]) -> &[u8] {
    // One space is what usually stands between two words: stepping over it first spares the
    // common case the loop.
    let bytes = match bytes {
        [b' ', rest @ ..] => rest,
        _ => bytes,
    };
    match bytes {
        [first, ..] if is_blank::<CARRIAGE_RETURN>(*first) => {
            skip_blank_run::<CARRIAGE_RETURN>(bytes)
        }
        _ => bytes,
    }
}

/// `bytes` from its first byte that is not a blank, for any run of blanks.
fn skip_blank_run<const CARRIAGE_RETURN: bool>(mut bytes: &[u8]) -> &[u8] {
    while let [first, rest @ ..] = bytes {
        if !is_blank::<CARRIAGE_RETURN>(*first) {
            break;
        }
        bytes = rest;
    }
    bytes
}

/// `[+|-]` and an unsigned decimal, read as [`read_plain_words`] says; the number and the bytes
/// after it.
#[inline(always)]
fn signed_number<const WINDOWED: bool>(bytes: &[u8]) -> Option<(Number, &[u8])> {
    let (negative, unsigned) = match bytes {
        [b'-', rest @ ..] => (true, rest),
        [b'+', rest @ ..] => (false, rest),
        _ => (false, bytes),
    };
    let (decimal, rest) = if WINDOWED {
        windowed_decimal(unsigned)?
    } else {
        unsigned_decimal(unsigned)?
    };
    Some((decimal.number(negative), rest))
}

#[cfg(test)]
mod tests {
    use super::super::{parse_any_line, parse_line, Format, Reader, SyntaxOptions};
    use super::*;
    use crate::syntax::decimal::tests::assert_windowed_agrees;
    use crate::syntax::decimal::MAX_DIGITS;
    use crate::syntax::Block;

    /// A number read by the general digit reader.
    fn general_number(text: &str, negative: bool) -> Option<Number> {
        let options = SyntaxOptions::default();
        let mut reader = Reader {
            text: text.as_bytes(),
            pos: 0,
            file: FileId(0),
            base: 0,
            line: 1,
            options: &options,
            format: Format::Iso,
            line_breaks: &[],
        };
        reader.read_digits(0, b'X', negative, &mut Block::new())
    }

    /// Equal numbers, to the bit: `==` on f64 takes -0 for 0.
    fn same_number(a: Number, b: Number) -> bool {
        a == b && a.value.to_bits() == b.value.to_bits()
    }

    fn line(text: &str, offset: u32) -> Line<'_> {
        Line {
            text: text.as_bytes(),
            offset,
            number: 3,
        }
    }

    /// `text` as the text at hand from byte `offset` of a file on; `None` past 4 GiB, as the
    /// line sources give it.
    fn unread_text(text: &str, offset: u32) -> Option<Unread<'_>> {
        Some(Unread {
            text: text.as_bytes(),
            end_offset: u32::try_from(text.len())
                .ok()
                .and_then(|length| offset.checked_add(length))?,
            number: 3,
        })
    }

    /// The blocks of a line as `read` gives them: `parse_line` (which takes the fast path when it
    /// can) or `parse_any_line` (the general reader alone).
    fn read_with(
        read: fn(Line<'_>, FileId, &SyntaxOptions, &mut LineBlocks),
        text: &str,
        offset: u32,
    ) -> Vec<Block> {
        let mut out = LineBlocks::new();
        read(
            line(text, offset),
            FileId(1),
            &SyntaxOptions::default(),
            &mut out,
        );
        out.as_slice().to_vec()
    }

    /// True when the fast path takes the line.
    fn is_plain(text: &str) -> bool {
        read_plain_line(line(text, 7), FileId(1), &mut LineBlocks::new())
    }

    /// Both paths give the same blocks, every value the same to the bit.
    fn assert_same_blocks(text: &str, offset: u32) {
        let fast = read_with(parse_line, text, offset);
        let general = read_with(parse_any_line, text, offset);
        assert_eq!(fast, general, "{text:?}");
        let values = |blocks: &[Block]| -> Vec<u64> {
            blocks
                .iter()
                .flat_map(|b| b.words.iter().map(|w| w.number.value.to_bits()))
                .collect()
        };
        assert_eq!(values(&fast), values(&general), "{text:?}");
        // Read from text at hand that runs on past its `\n` (as the reader of a file takes it),
        // the line gives the same blocks as the line handed out without its line end.
        if !text.contains('\n') {
            let handed_out = text.strip_suffix('\r').unwrap_or(text);
            let unread = format!("{text}\n{NEXT_LINE}");
            let mut at_hand = LineBlocks::new();
            let taken = unread_text(&unread, offset)
                .and_then(|unread| read_plain_line_in(unread, FileId(1), &mut at_hand));
            if let Some(after) = taken {
                assert_eq!(unread.len() - after, text.len() + 1, "{text:?}");
                let general = read_with(parse_any_line, handed_out, offset);
                assert_eq!(at_hand.as_slice(), general, "{text:?}");
                assert_eq!(values(at_hand.as_slice()), values(&general), "{text:?}");
            } else {
                // Refused only when the line is not plain, when the text at hand runs past
                // 4 GiB (where spans saturate), or when the line has a `\r` elsewhere than
                // before its `\n`.
                let past_4_gib = u32::try_from(unread.len())
                    .ok()
                    .and_then(|length| offset.checked_add(length))
                    .is_none();
                let inner_carriage_return = handed_out.contains('\r');
                assert!(
                    past_4_gib || inner_carriage_return || !is_plain(handed_out),
                    "{text:?}"
                );
            }
        }
    }

    #[test]
    fn the_fast_and_the_general_number_paths_agree() {
        for text in [
            "0",
            "1.",
            ".5",
            "0.",
            "1.833",
            "123456.789",
            "0.0010",
            "000012",
            "99999.9999",
            "25",
            "999999999999999",
            "1.00000000000001",
            "000000000000001",
            ".000000000000001",
            "2.22044604925031",
        ] {
            for negative in [false, true] {
                let (fast, length) = fast_number(text.as_bytes(), negative).expect(text);
                let general = general_number(text, negative).expect(text);
                assert!(same_number(fast, general), "{text}: {fast:?} {general:?}");
                assert_eq!(length, text.len());
            }
        }
    }

    #[test]
    fn the_fast_number_path_leaves_the_rest_to_the_general_one() {
        // No digits, more digits than the fast path reads, a second point, a blank inside.
        for text in [
            "",
            ".",
            "-1",
            "+1",
            "1.000000000000001",
            "0000000000000001",
            "12345678901234567890",
            "1.2.",
            "1 2",
            "1\t.5",
            "1. .5",
        ] {
            assert_eq!(fast_number(text.as_bytes(), false), None, "{text:?}");
        }
    }

    #[test]
    fn numbers_without_a_decimal_point_say_so() {
        // Most profiles read `X25` in least input increments: the flag must survive the fast path.
        let blocks = read_with(parse_line, "G1 X25 Y25. Z-0", 0);
        let point: Vec<bool> = blocks[0]
            .words
            .iter()
            .map(|w| w.number.decimal_point)
            .collect();
        assert_eq!(point, [false, false, true, false]);
        assert!(blocks[0].words[3].number.negative);
        assert_eq!(
            blocks[0].words[3].number.value.to_bits(),
            (-0.0f64).to_bits()
        );
    }

    #[test]
    fn cam_lines_take_the_fast_path_and_others_do_not() {
        for text in [
            "G01 X54.808 Y30.491 Z-1.288",
            "G02 X51.438 Y26.151 R11.700  \r",
            "  g1x1y2",
            "N10 G1 X+.5 Y-0. F1500.",
        ] {
            assert!(is_plain(text), "{text:?}");
        }
        for text in [
            "",
            "   ",
            "X1 2.5",
            "N10 G1 X1. (comment)",
            "F2=100",
            "G1 X1.;",
            "G1 X",
            "#1=2",
            "/G1 X1.",
            "%",
            "GOTO10",
            "X1.000000000000001",
        ] {
            assert!(!is_plain(text), "{text:?}");
        }
    }

    #[test]
    fn plain_and_general_lines_agree_on_examples() {
        for text in [
            "G01 X54.808 Y30.491 Z-1.288",
            "G02 X51.438 Y26.151 R11.700  \r",
            "  g1x1y2",
            "X1 2.5",
            "X1 .5",
            "X1. .5",
            "X1.2.3",
            "X1\r2",
            "\0X1\x0bY2\x0c",
            "N10 G1 X1. (comment)",
            "F2=100",
            "F2 =100",
            "G1 X+.5 Y-0. Z",
            "X. Y1",
            "X- Y1",
            "X+ Y1",
            "X-. Y1",
            "X00012 Y-000.0100",
            "X999999999999999 Y0.00000000000001",
            "X1.000000000000001 Y1",
            "X12345678901234567890",
            "G1 X1 e5",
            "G1 X1;Y2",
            "G1 X1 #1=2",
            "",
            "   ",
        ] {
            assert_same_blocks(text, 7);
        }
    }

    /// The lines of `texts` read one after the other through one set of blocks, as the reading
    /// loops reuse it, each compared with the line read into a new set.
    fn assert_reused_blocks_read_as_new(texts: &[&str]) {
        let mut reused = LineBlocks::new();
        let mut reused_at_hand = LineBlocks::new();
        for text in texts {
            parse_line(
                line(text, 7),
                FileId(1),
                &SyntaxOptions::default(),
                &mut reused,
            );
            let new = read_with(parse_line, text, 7);
            assert_eq!(reused.as_slice(), new, "{text:?} after {texts:?}");
            let unread = format!("{text}\n{NEXT_LINE}");
            reused_at_hand.reset();
            let unread = unread_text(&unread, 7).expect("far below 4 GiB");
            if read_plain_line_in(unread, FileId(1), &mut reused_at_hand).is_some() {
                assert_eq!(reused_at_hand.as_slice(), new, "{text:?} after {texts:?}");
            } else {
                // As the reading loop does: the line reader takes what the plain reader left.
                parse_line(
                    line(text, 7),
                    FileId(1),
                    &SyntaxOptions::default(),
                    &mut reused_at_hand,
                );
                assert_eq!(reused_at_hand.as_slice(), new, "{text:?} after {texts:?}");
            }
        }
    }

    #[test]
    fn a_plain_line_after_any_other_line_reads_as_in_new_blocks() {
        // Lines that leave a skip level, a tape mark, a comment, alarms, statements, code, a
        // message or several blocks behind, each before and after plain lines.
        let others = [
            "/2 G1 X1.",
            "%",
            "G1 X1. (comment)",
            "G1 X1 2.5.5",
            "#1 = 2 (MESSAGE)",
            "#3000 = 1 (NO TOOL)",
            "G1 X#1",
            "G1 X1.; G1 Y2.; G1 Z3.",
            "",
            "G1 X",
            "X1.000000000000001",
        ];
        let plain = ["G01 X54.808 Y30.491", "G02 X1. Y2. R3.", "Y1"];
        for other in others {
            for first in plain {
                for second in plain {
                    assert_reused_blocks_read_as_new(&[first, other, second, other, other, first]);
                }
            }
        }
    }

    /// What follows a line in the tests of text at hand: enough for the number windows of the
    /// line before it.
    const NEXT_LINE: &str = "G01 X1.5 (the next line: text for the windows of the line before)\n";

    #[test]
    fn a_line_read_with_its_line_end_reads_as_the_line_without_it() {
        for (unread, line_length) in [
            ("G01 X54.808 Y30.491\nG1 X1", 19),
            ("G01 X54.808 Y30.491\r\nG1 X1", 19),
            ("G02 X1 R2  \r\n", 11),
            ("  g1x1y2\n(comment)\n", 8),
        ] {
            let unread = &format!("{unread}{NEXT_LINE}");
            let mut fast = LineBlocks::new();
            let taken = read_plain_line_in(unread_text(unread, 7).unwrap(), FileId(1), &mut fast);
            let after_newline = unread.len() - unread.find('\n').unwrap() - 1;
            assert_eq!(taken, Some(after_newline), "{unread:?}");
            let mut by_line = LineBlocks::new();
            assert!(read_plain_line(
                line(&unread[..line_length], 7),
                FileId(1),
                &mut by_line
            ));
            assert_eq!(fast.as_slice(), by_line.as_slice(), "{unread:?}");
        }
        // Not plain, not ended by `\n` where the text at hand ends, or with a `\r` inside:
        // left to the line reader (which reads the last as a plain line, `\r` as a blank).
        for unread in [
            "G1 X1",
            "G1 X1 (C)\n",
            "\nG1 X1\n",
            " \r\nG1\n",
            "G1 X1.2.3\n",
            "X1\rY2\n",
            "X1\r\rY2\n",
            "X1\r \r\n",
            "G02 X1 R2  \r\r\n",
        ] {
            let unread = unread_text(unread, 7).unwrap();
            let taken = read_plain_line_in(unread, FileId(1), &mut LineBlocks::new());
            assert_eq!(taken, None, "{unread:?}");
        }
        assert!(is_plain("X1\rY2"));
        // A line handed out whole never holds a `\n`; if one did, it would not be plain.
        assert!(!is_plain("G1 X1\nG1 X2"));
    }

    #[test]
    fn a_line_too_close_to_the_end_of_the_text_at_hand_is_left_to_the_line_reader() {
        let read = |unread: &str| {
            read_plain_line_in(
                unread_text(unread, 7).unwrap(),
                FileId(1),
                &mut LineBlocks::new(),
            )
        };
        // Every word takes WINDOW + 2 bytes from its letter on (letter, sign, window), and the
        // line's end as many from its `\n` or `\r\n` on: what follows the line counts.
        let tail = |length: usize| "\n".repeat(length);
        let room = WINDOW + 2;
        for line in ["G1 X1.5", "G1 X15", "G1 X-15", "X1"] {
            assert_eq!(read(&format!("{line}{}", tail(room))), Some(room - 1));
            assert_eq!(read(&format!("{line}{}", tail(room - 1))), None);
            assert_eq!(read(&format!("{line}\r{}", tail(room - 1))), Some(room - 2));
            assert_eq!(read(&format!("{line}\r{}", tail(room - 2))), None);
        }
    }

    #[test]
    fn lines_at_the_end_of_a_4_gib_file_read_the_same_on_both_paths() {
        // Spans saturate there; the fast path leaves such lines to the general reader.
        for offset in [u32::MAX - 20, u32::MAX - 5, u32::MAX] {
            assert_same_blocks("G1 X1.5 Y-2.", offset);
        }
    }

    proptest::proptest! {
        #[test]
        fn the_fast_path_reads_what_the_general_path_reads(
            whole in "[0-9]{0,18}",
            point in proptest::bool::ANY,
            fraction in "[0-9]{0,18}",
            negative in proptest::bool::ANY,
        ) {
            let text = if point { format!("{whole}.{fraction}") } else { whole.clone() };
            for after in [
                "",
                " ",
                "X1.5 Y-2.",
                "\nG01 X54.808 Y30.491 Z-1.288\n",
                "\nG01 X54.808 Y30.491 Z-1.288\nG01 X54.808 Y30.491\n",
            ] {
                assert_windowed_agrees(format!("{text}{after}").as_bytes());
            }
            let general = general_number(&text, negative);
            match fast_number(text.as_bytes(), negative) {
                Some((fast, length)) => {
                    let general = general.expect("the general path reads what the fast one does");
                    proptest::prop_assert!(same_number(fast, general), "{:?} {:?}", fast, general);
                    proptest::prop_assert_eq!(length, text.len());
                }
                None => {
                    let digits = text.len() - usize::from(point);
                    proptest::prop_assert!(general.is_none() || digits > MAX_DIGITS);
                }
            }
        }

        #[test]
        fn plain_lines_read_the_same_on_both_paths(
            text in "[ \t]{0,2}([GXYZIJKRFSMNgx][-+]?[0-9]{0,4}[.]?[0-9]{0,4}[ \t=;(#]{0,2}){0,6}",
        ) {
            assert_same_blocks(&text, 7);
        }

        #[test]
        fn any_line_of_word_characters_reads_the_same_on_both_paths(
            text in "[GXYgx0-9.+\\- \t\r\x0b\x00=;(#/%]{0,24}",
        ) {
            assert_same_blocks(&text, 7);
        }
    }
}
