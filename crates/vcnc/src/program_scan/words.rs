//! The words of one program line as the scan reads them: address words with their numbers
//! as written, `#` variable numbers, and sizes in inches inside comments. A byte-level reader
//! of its own, bounded by the line: it never fails and never allocates per line.

/// One address word of a line.
#[derive(Clone, Copy, Debug)]
pub(super) struct Word {
    pub(super) letter: u8,
    /// The whole part of the number (saturating).
    pub(super) whole: u64,
    /// The digits after the point as an integer over `scale` (enough for a magnitude).
    pub(super) after: u64,
    pub(super) scale: u64,
    /// Digits after the decimal point, not all zero.
    pub(super) fraction: bool,
    pub(super) decimal_point: bool,
    /// Its bytes in the line.
    pub(super) start: usize,
    pub(super) end: usize,
}

/// The first size in inches inside a comment of `line`: a number written against `IN`,
/// `INCH` or `"` (`1IN`, `3/8IN`, `.238"`), or a fraction before them (`1/4 IN`). Prose such
/// as `Z-5 in G54` is none. Returns its bytes.
pub(super) fn inch_size_in_comment(line: &[u8]) -> Option<(usize, usize)> {
    let mut depth = 0;
    for (i, &b) in line.iter().enumerate() {
        match b {
            b'(' => depth += 1,
            b')' => depth = std::cmp::max(depth, 1) - 1,
            b'0'..=b'9' if depth > 0 && !line.get(i + 1).is_some_and(u8::is_ascii_digit) => {
                let start = line[..i]
                    .iter()
                    .rposition(|c| !(c.is_ascii_digit() || *c == b'.' || *c == b'/'))
                    .map_or(0, |p| p + 1);
                let fraction = line[start..=i].contains(&b'/');
                let mut j = i + 1;
                if fraction {
                    while line.get(j) == Some(&b' ') {
                        j += 1;
                    }
                }
                let rest = &line[j..];
                let unit = if rest.first() == Some(&b'"') {
                    1
                } else if rest.len() >= 2 && rest[..2].eq_ignore_ascii_case(b"IN") {
                    // `IN` or `INCH`, not the start of another word (`10INSERTS`).
                    let word = rest.iter().take_while(|c| c.is_ascii_alphabetic()).count();
                    let inch = word == 2 || (word == 4 && rest[..4].eq_ignore_ascii_case(b"INCH"));
                    if inch {
                        word
                    } else {
                        0
                    }
                } else {
                    0
                };
                if unit > 0 {
                    return Some((start, j + unit));
                }
            }
            _ => {}
        }
    }
    None
}

/// The address words and the `#` variable numbers (number, start, end) of a line, into the
/// two lists (emptied first; kept from line to line so that no line allocates).
pub(super) fn words_of(
    line: &[u8],
    words: &mut Vec<Word>,
    variables: &mut Vec<(u32, usize, usize)>,
) {
    words.clear();
    variables.clear();
    let mut i = 0;
    let alpha = |i: usize| line.get(i).is_some_and(u8::is_ascii_alphabetic);
    while i < line.len() {
        match line[i].to_ascii_uppercase() {
            b'(' => {
                i += line[i..]
                    .iter()
                    .position(|&c| c == b')')
                    .unwrap_or(line.len() - i);
            }
            b'/' if line.get(i + 1) == Some(&b'/') => break,
            b'#' => {
                let digits = line[i + 1..]
                    .iter()
                    .take_while(|c| c.is_ascii_digit())
                    .count();
                if let Ok(number) = std::str::from_utf8(&line[i + 1..i + 1 + digits])
                    .unwrap_or("")
                    .parse()
                {
                    variables.push((number, i, i + 1 + digits));
                }
                i += digits;
            }
            // The addresses the scan reads; a letter inside a keyword (GOTO, DO1, SIN, THEN) is
            // none. The digits of the other words fall through below.
            b'G' | b'M' | b'N' | b'P' | b'X' | b'Y' | b'Z' | b'I' | b'J' | b'H' | b'D'
                if !(alpha(i + 1) || (i > 0 && alpha(i - 1))) =>
            {
                if let Some(word) = number_after(line, i) {
                    i = word.end - 1;
                    words.push(word);
                }
            }
            _ => {}
        }
        i += 1;
    }
}

/// The word whose letter is at `at`, when a number follows it (`X10.`, `Y -5`, not `X#1`).
fn number_after(line: &[u8], at: usize) -> Option<Word> {
    let mut i = at + 1;
    let skip_spaces = |i: &mut usize| {
        while line.get(*i).is_some_and(|&c| c == b' ' || c == b'\t') {
            *i += 1;
        }
    };
    skip_spaces(&mut i);
    if matches!(line.get(i), Some(b'+' | b'-')) {
        i += 1;
        skip_spaces(&mut i);
    }
    let (mut whole, mut digits, mut fraction, mut decimal_point) = (0u64, 0, false, false);
    let (mut after, mut scale) = (0u64, 1u64);
    while let Some(&c) = line.get(i) {
        match c {
            b'0'..=b'9' if !decimal_point => {
                whole = whole.saturating_mul(10).saturating_add(u64::from(c - b'0'));
                digits += 1;
            }
            b'0'..=b'9' => {
                fraction |= c != b'0';
                digits += 1;
                if scale < 1_000_000_000_000 {
                    after = after * 10 + u64::from(c - b'0');
                    scale *= 10;
                }
            }
            b'.' if !decimal_point => decimal_point = true,
            _ => break,
        }
        i += 1;
    }
    (digits > 0).then_some(Word {
        letter: line[at].to_ascii_uppercase(),
        whole,
        after,
        scale,
        fraction,
        decimal_point,
        start: at,
        end: i,
    })
}
