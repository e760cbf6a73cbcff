//! Mangled input: whatever bytes a program holds, the interpreter ends without a panic or a hang,
//! and everything it says points inside the text.
//!
//! Three sources of bad input run on every built-in profile: a fixed list of nasty programs
//! (empty files, stray bytes, invalid UTF-8, unclosed comments, huge numbers, lone addresses,
//! macro syntax ...), deterministic mutations of the seed examples in
//! `../shared/spec/examples/{syntec,fanuc0m,mitsubishi}` (byte flips, deletions, duplications
//! and splices between files, from a small seeded xorshift generator so every run sees the same
//! cases), and proptest over random bytes and random G-code-like text. The properties are those of
//! the fuzz targets in `fuzz/` (see `fuzz/README.md`), which search the same space for longer.
//!
//! The properties, for every input and profile:
//! - the run ends, with at most a few items per input byte (a bounded `take` turns a stream that
//!   never ends into a failure instead of a hang);
//! - nothing comes after the first error alarm;
//! - every alarm has a code, a one-line message and a span with `start <= end <= len`;
//! - every segment's span lies inside the text and all its numbers (positions, offsets, arc
//!   centres, feeds, speeds, dwell times) are finite.

use crate::common;

use proptest::prelude::*;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;
use vcnc::motion::{Feed, Move};
use vcnc::{interpret_bytes, Alarm, Machine, Options, ProfileName, Segment, SegmentKind, Span};

/// Items a run may yield per input byte (plus a constant for the empty text). A block yields a
/// handful of items (its warnings, a few segments, at most one error) and takes at least one byte;
/// the bound is loose on purpose: it is there to catch streams that do not end.
const ITEMS_PER_BYTE: usize = 8;
const ITEMS_ALWAYS: usize = 16;

/// What a run produced, for the tests that want to say more than "the properties hold".
#[derive(Debug, Default, Clone, Copy)]
struct Stats {
    items: usize,
    errors: usize,
}

/// Runs `text` on `machine` and checks the properties; the error names the first one broken.
fn check_run(text: &[u8], machine: &Machine) -> Result<Stats, String> {
    let limit = ITEMS_PER_BYTE * text.len() + ITEMS_ALWAYS;
    let len = u32::try_from(text.len()).map_err(|_| "test input longer than 4 GiB".to_string())?;
    let mut stats = Stats::default();
    let mut error_seen: Option<Alarm> = None;
    for item in interpret_bytes(text, machine, Options::default()).take(limit + 1) {
        stats.items += 1;
        if stats.items > limit {
            return Err(format!(
                "the run did not end within {limit} items for {} bytes",
                text.len()
            ));
        }
        if let Some(error) = &error_seen {
            return Err(format!("{item:?} came after the error alarm {error:?}"));
        }
        match item {
            Ok(vcnc::Item::Segment(segment)) => check_segment(&segment, len)?,
            Ok(vcnc::Item::Frame(frame)) => check_frame(&frame)?,
            Ok(vcnc::Item::Warning(alarm)) | Err(alarm) => {
                check_alarm(&alarm, len)?;
                if alarm.is_error() {
                    stats.errors += 1;
                    error_seen = Some(alarm);
                }
            }
        }
    }
    Ok(stats)
}

fn check_span(span: Span, len: u32, what: &str) -> Result<(), String> {
    if span.start <= span.end && span.end <= len {
        Ok(())
    } else {
        Err(format!(
            "{what} span {span} is not inside the text of {len} bytes"
        ))
    }
}

pub(crate) fn check_alarm(alarm: &Alarm, len: u32) -> Result<(), String> {
    // In-memory ISO text can neither fail to read nor be SINUMERIK: every alarm has a place.
    let span = alarm
        .span
        .ok_or_else(|| format!("alarm without a span: {alarm:?}"))?;
    check_span(span, len, &format!("alarm {}", alarm.code.id()))?;
    for label in &alarm.labels {
        check_span(
            label.span,
            len,
            &format!("a label of alarm {}", alarm.code.id()),
        )?;
    }
    if alarm.message.is_empty() || alarm.message.contains('\n') {
        return Err(format!("alarm message is not one line: {alarm:?}"));
    }
    Ok(())
}

pub(crate) fn check_segment(segment: &Segment, len: u32) -> Result<(), String> {
    check_span(segment.span, len, "segment")?;
    let finite = match &segment.kind {
        SegmentKind::Rapid { motion, .. } => move_is_finite(motion),
        SegmentKind::Line { motion, feed } => move_is_finite(motion) && feed_is_finite(feed),
        SegmentKind::Arc {
            motion,
            center,
            feed,
            ..
        } => move_is_finite(motion) && all_finite(&center.0) && feed_is_finite(feed),
        SegmentKind::Dwell { seconds } => seconds.is_finite(),
        SegmentKind::Spindle { speed, .. } => speed.is_finite(),
        _ => true,
    };
    if finite {
        Ok(())
    } else {
        Err(format!(
            "segment with a number that is not finite: {segment:?}"
        ))
    }
}

/// A frame's map and tool length are finite numbers, and the map can be undone.
fn check_frame(frame: &vcnc::motion::WorkFrame) -> Result<(), String> {
    let map = &frame.transform;
    let finite = map.linear.iter().all(|row| all_finite(row))
        && all_finite(&map.rotary)
        && all_finite(&map.translation)
        && all_finite(&frame.tool_length)
        && map.inverse().is_some();
    if finite {
        Ok(())
    } else {
        Err(format!(
            "frame that is not finite or cannot be undone: {frame:?}"
        ))
    }
}

fn all_finite(values: &[f64]) -> bool {
    values.iter().all(|v| v.is_finite())
}

fn move_is_finite(motion: &Move) -> bool {
    all_finite(&motion.from.0) && all_finite(&motion.to.0) && all_finite(&motion.offset)
}

fn feed_is_finite(feed: &Feed) -> bool {
    match *feed {
        Feed::PerMinute(f) | Feed::InverseTime(f) => f.is_finite(),
        Feed::PerRevolution {
            per_revolution,
            rpm,
        } => per_revolution.is_finite() && rpm.is_none_or(f64::is_finite),
    }
}

/// The default machine with each built-in profile.
fn machines() -> Vec<(ProfileName, Machine)> {
    ProfileName::ALL
        .iter()
        .map(|&p| {
            (
                p,
                Machine::default()
                    .with_profile(p)
                    .expect("built-in profiles fit the default machine"),
            )
        })
        .collect()
}

/// The input as people can read it in a failure message: escaped, and shortened when long.
pub(crate) fn shown(text: &[u8]) -> String {
    let escaped = text.escape_ascii().to_string();
    if escaped.len() <= 400 {
        escaped
    } else {
        format!("{} ... ({} bytes)", &escaped[..400], text.len())
    }
}

/// Checks `text` on every profile; a panic is caught so that the failure names the input.
fn check_everywhere(text: &[u8], machines: &[(ProfileName, Machine)]) -> Result<Stats, String> {
    let mut total = Stats::default();
    for (profile, machine) in machines {
        let outcome = catch_unwind(AssertUnwindSafe(|| check_run(text, machine)));
        let result = match outcome {
            Ok(result) => result,
            Err(panic) => {
                let message = panic
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| panic.downcast_ref::<&str>().map(|s| (*s).to_string()))
                    .unwrap_or_default();
                Err(format!("panic: {message}"))
            }
        };
        let stats = result.map_err(|e| {
            format!(
                "{} on the {} profile, input `{}`",
                e,
                profile.as_str(),
                shown(text)
            )
        })?;
        total.items += stats.items;
        total.errors += stats.errors;
    }
    Ok(total)
}

/// Checks every input and reports all the broken ones at once.
#[track_caller]
fn check_all(inputs: &[Vec<u8>]) {
    let machines = machines();
    let failures: Vec<String> = inputs
        .iter()
        .filter_map(|text| check_everywhere(text, &machines).err())
        .collect();
    assert!(
        failures.is_empty(),
        "{} of {} inputs break a property:\n{}",
        failures.len(),
        inputs.len(),
        failures.join("\n")
    );
}

// ---------------------------------------------------------------------------------------------
// Fixed nasty programs.

fn b(text: &str) -> Vec<u8> {
    text.as_bytes().to_vec()
}

/// Programs that are wrong at the level of characters and lines.
fn nasty_characters() -> Vec<Vec<u8>> {
    let mut inputs = vec![
        b(""),
        b("%"),
        b("%\n"),
        b("%%%%"),
        b("%\n%\n%\n"),
        b("\n"),
        b(&"\n".repeat(1000)),
        b("\r\n\r\n\r\n"),
        b("G0 X1.\r\nG1 Y2. F100.\r\nM30\r\n"),
        b("\r"),
        b("G0 X1.\rG1 Y2. F100.\rM30\r"),
        b("\r\r\r\n\n\r"),
        // A byte-order mark: whole, alone, cut short, in the middle of a line, twice.
        b("\u{feff}"),
        b("\u{feff}G0 X1.\rG1 Y2. F100.\rM30\r"),
        b("\u{feff}%\r\u{feff}O1\r#1=1\rWHILE[#1LT3]DO1\r#1=#1+1\rEND1\rM99\r%"),
        vec![0xEF, 0xBB],
        vec![0xEF, 0xBB, b'\n', 0xBF],
        b("G0\u{feff}X1."),
        // Exponents, whole and cut short.
        b("G0 X1e308\nM30"),
        b("G0 X1e"),
        b("G0 X1E-"),
        b("#1=1E308"),
        b("#1=[2.5e-3*2]"),
        b("#1=1e"),
        b("\0"),
        b("\0\0\0\0\0\0\0\0\0"),
        b("G0\0X1.\0\nG1\0Y2.F100.\0M30"),
        b("G0 X\0 1."),
        b("\t\x0b\x0c \t"),
        b(" \n \n \n"),
        b(";"),
        b(";;;;"),
        b(";\n;\n;"),
        b("G0 X1.;;;;;;G1 Y1.;;"),
        b("/"),
        b("/0"),
        b("/9"),
        b("//"),
        b("/ / / /"),
        b("/1/2/3 G0 X1."),
        b("//// comment"),
        b(":"),
        b(":="),
        b("::::"),
        b(":1234"),
        b("X:1"),
        b("(unclosed"),
        b("G0 X1. (unclosed\nG1 Y1. F100."),
        b("((((((((((((((("),
        b(")))))))))))))))"),
        b("(a(b(c(d)c)b)a)G0 X1."),
        b("G0 (a) X1. (b (c) d) Y2. ((e)) Z3."),
        b(")G0 X1."),
        b("G0 X1.)"),
        b("()()()()"),
        b("G0 X(1.)"),
        b("X(comment)1."),
        b("G0 X1. (M30)"),
        b("%\nO0001\nG0 X1.\nM30\n%\n"),
        b("%\nG0 X1.\n%\nG0 X2.\n%\n"),
        b("M30\nG0 X1.\nM30"),
        b("G0 X1.\x7fY1."),
        b("G0 X1. $ Y1."),
        b("G0 X1. @"),
        b("\"G0 X1.\""),
        b("G0 X1. ~ ` ! ^ & * | \\ { } < > ?"),
    ];
    // Invalid UTF-8 and Latin-1, inside and outside comments.
    inputs.push(b"(Drehteil \xe4\xf6\xfc \xb0 \xb5m)\nG0 X1.\nM30".to_vec());
    inputs.push(b"G0 X1. \xe4\nM30".to_vec());
    inputs.push(b"G0 X\xff1.".to_vec());
    inputs.push(b"\xff\xfe\xfd".to_vec());
    inputs.push(b"\xef\xbb\xbfG0 X1.\nM30".to_vec());
    inputs.push(b"\xc3".to_vec());
    inputs.push(b"G0 X1.\xc3".to_vec());
    inputs.push(b"\xe2\x82".to_vec());
    inputs.push(b"\xf0\x9f\x98".to_vec());
    inputs.push("G0 X1. \u{1F600} Y1.".as_bytes().to_vec());
    inputs.push("(\u{00e9}t\u{00e9}) G0 X\u{00b2}".as_bytes().to_vec());
    inputs.push(b"(\xff\xff\xff".to_vec());
    inputs.push(b"\x80\x80\x80\x80(".to_vec());
    inputs.push(b"\xc0\xaf\xe0\x80\xaf".to_vec());
    inputs.push(b"G0 X1.\xed\xa0\x80".to_vec());
    // Very long lines: 100 kB of words, of digits, of comment, of blanks, of letters.
    inputs.push("G1 X1. Y1. ".repeat(10_000).into_bytes());
    inputs.push(format!("X{}", "9".repeat(100_000)).into_bytes());
    inputs.push(format!("X1.{}", "1".repeat(100_000)).into_bytes());
    inputs.push(format!("X0.{}1", "0".repeat(100_000)).into_bytes());
    inputs.push(format!("({}", "a".repeat(100_000)).into_bytes());
    inputs.push(format!("({})G0 X1.", "(".repeat(50_000)).into_bytes());
    inputs.push(format!("G0{}X1.", " ".repeat(100_000)).into_bytes());
    inputs.push(format!("X{}1.", " ".repeat(100_000)).into_bytes());
    inputs.push("A".repeat(100_000).into_bytes());
    inputs.push(";".repeat(100_000).into_bytes());
    inputs.push("/".repeat(100_000).into_bytes());
    inputs.push("\r".repeat(100_000).into_bytes());
    inputs
}

/// Programs whose words are wrong: bad numbers, lone addresses, macro syntax.
fn nasty_words() -> Vec<Vec<u8>> {
    let texts = [
        "X99999999999999999999999.9",
        "G1 X99999999999999999999999.9 F100.",
        "G0 X99999999999999999999999.9 Y-99999999999999999999999.9",
        "G1 F99999999999999999999999.9 X1.",
        "G1 F0.000000000000000000001 X1.",
        "G91 G1 X99999999999999999. F1.\nX99999999999999999.\nX99999999999999999.",
        "G2 X1. R99999999999999999999. F100.",
        "G2 X1. R0.00000000000000001 F100.",
        "G2 X0.00000000000000001 I99999999999999999. F100.",
        "G3 I0.000000000000000001 F100.",
        "G4 P99999999999999999999999",
        "G4 X99999999999999999999999.",
        "S99999999999999999999999 M3",
        "T99999999999999999999999 M6",
        "M99999999999999999999999",
        "N99999999999999999999999 G0 X1.",
        "O99999999999999999999999",
        "H99999999999999999999999 G43 Z1.",
        "G10 L2 P1 X99999999999999999999999.",
        "G10 L2 P99999999999999999999 X1.",
        "G54.1 P99999999999999999999",
        "G99999999999999999999999",
        "G1.00000000000000000001",
        "X1e5",
        "G0 X1e5 Y1E-5",
        "X1.5e",
        "X1..",
        "X1.2.3",
        "X...",
        "X.",
        "X-.",
        "X+.",
        "X-",
        "X+",
        "X--1",
        "X+-1",
        "X-+1",
        "X- 1",
        "X 1 2 . 3 4",
        "X1 2 3 4 5 6 7 8 9 0 1 2 3 4 5 6 7 8 9 0 1 2 3",
        "X-0",
        "X-0.",
        "G",
        "G-1",
        "G-0",
        "G1.23",
        "G0.5",
        "G.",
        "G 0 0 X1.",
        "G00000000000000000000001 X1.",
        "N",
        "N-1",
        "N1.5",
        "N0 N0 N0",
        "O",
        "O-1",
        "O1.5",
        "M",
        "M-3",
        "M3.5",
        "T-1",
        "S-1000 M3",
        "F-100. G1 X1.",
        "F0 G1 X1.",
        "G4 P-1",
        "G4 X-1.",
        "H-1 G43 Z1.",
        "D-1",
        "G10 L-2 P-1 X1.",
        "F2=",
        "F2=1000",
        "F0=1000",
        "F10=1000",
        "F1.5=1000",
        "F-1=1000",
        "F2==1000",
        "F2=#1",
        "X=1",
        "=",
        "#",
        "#1",
        "#1=2",
        "#1=#2+1",
        "X#1",
        "X-#1",
        "G#1",
        "[",
        "]",
        "[[[[[[[[[[",
        "X[1+2]",
        "IF",
        "IF[#1GT2]GOTO5",
        "WHILE[#1LT10]DO1",
        "END1",
        "GOTO",
        "IFF",
        "XX",
        "XYZ",
        "ABC",
        "SIN[1]",
        "g0 x1. y2.",
        "g1 x1. f100.\nm30",
        "g01x1.y1.z1.f100.",
        "n10 g90 g54 g0 x0 y0\nm30",
        "G0 X1. X2.",
        "G0 G1 G2 G3 X1.",
        "G90 G91 X1.",
        "G17 G18 G19",
        "G20 G21 X1.",
        "G28",
        "G28 X0 Y0 Z0 A0 B0 C0",
        "G29",
        "G30 P5 X0",
        "G53",
        "G92",
        "G2 F100.",
        "G2 X1. F100.",
        "G2 X0 Y0 I0 J0 F100.",
        "G3 X1. Y1. R0 F100.",
        "G2 X1. Y1. R-0.1 F100.",
        "G17 G2 X10. Y0 I5. J0 Z-5. F100. L99999999",
        "G18 G3 Z10. I5. F100.",
        "G19 G2 Y10. K5. F100.",
        "G41 D1 X5.",
        "G43 H1 Z0",
        "G43 H0 Z0",
        "G49 G40 G80",
        "G81 X1. Y1. Z-1. R1. F100.",
        "A1. B2. C3. U4. V5. W6.",
        "Q1 R1 E1 K1 L1 P1",
        "M3 M8 M3 M8 M3 M8 M3 M8",
        "M0",
        "M1",
        "M2",
        "M30 M30",
        "M98 P1",
        "M99",
        "T1 M6 T2 M6 T3 M6",
    ];
    let mut inputs: Vec<Vec<u8>> = texts.iter().map(|t| b(t)).collect();
    // Numbers beyond f64 (309 digits) and near its top (1e308) after every address and in the
    // blocks that store them: offsets, tool data, feeds, dwells, radii, centres.
    let beyond = "9".repeat(309);
    let near = format!("1{}.", "0".repeat(308));
    for value in [&beyond, &near] {
        for letter in b'A'..=b'Z' {
            let letter = letter as char;
            inputs.push(b(&format!("G1 F100. {letter}{value}\nX1.\nM30")));
            inputs.push(b(&format!("G1 F100. {letter}-{value}\nX1.\nM30")));
        }
        for block in [
            "G1 X1. F",
            "G93 G1 X1. F",
            "G95 S1000 M3 G1 X1. F",
            "S",
            "G4 P",
            "G4 X",
            "G2 X1. R",
            "G2 X1. I",
            "G3 X1. Y1. J",
            "G10 L2 P1 X",
            "G10 L20 P1 X",
            "G10 L10 P1 R",
            "G10 L11 P1 R",
            "G10 L12 P1 R",
            "G10 L13 P1 R",
            "G92 X",
            "G52 X",
            "G28 X",
            "G30 X",
            "G53 X",
            "G20 X",
            "G68 R",
            "G51 P",
            "G16 X",
        ] {
            inputs.push(b(&format!(
                "{block}{value}\nG43 H1 G1 X1. Y1. Z1. F100.\nG2 X2. R1.\nM30"
            )));
        }
    }
    inputs
}

/// Every byte alone, and every letter followed by every punctuation character (and a digit after
/// it, so the letter's number is read too).
fn every_byte_and_pair() -> Vec<Vec<u8>> {
    let mut inputs: Vec<Vec<u8>> = (0..=255u8).map(|byte| vec![byte]).collect();
    for letter in (b'A'..=b'Z').chain(b'a'..=b'z') {
        for punct in (0x20..0x7fu8).filter(|c| c.is_ascii_punctuation() || *c == b' ') {
            inputs.push(vec![letter, punct]);
            inputs.push(vec![letter, punct, b'1']);
        }
    }
    inputs
}

/// The same word again and again, on one line and on many.
fn repeated_words() -> Vec<Vec<u8>> {
    let mut inputs = Vec::new();
    for word in [
        "G1",
        "X1.",
        "G0 X1.",
        "M3",
        "N1",
        "G91 X1.",
        "(x)",
        "/",
        "%",
        "G2 X1. R1. F1.",
        "T1 M6",
        "F1.",
    ] {
        inputs.push(word.repeat(5_000).into_bytes());
        inputs.push(format!("{word}\n").repeat(5_000).into_bytes());
        inputs.push(format!("{word};").repeat(5_000).into_bytes());
    }
    inputs.push("G91 G1 F100. X1.\n".repeat(20_000).into_bytes());
    inputs.push("G91 G2 X0 Y0 I1. F100.\n".repeat(5_000).into_bytes());
    inputs
}

#[test]
fn characters_that_no_program_should_hold_end_in_an_alarm_or_nothing() {
    check_all(&nasty_characters());
}

#[test]
fn bad_numbers_lone_addresses_and_macro_syntax_end_in_an_alarm_with_a_span() {
    check_all(&nasty_words());
}

#[test]
fn every_byte_alone_and_every_letter_before_every_punctuation_character_ends() {
    check_all(&every_byte_and_pair());
}

#[test]
fn deeply_repeated_words_end_with_a_bounded_stream() {
    check_all(&repeated_words());
}

#[test]
fn a_lone_address_or_stray_character_is_an_error_that_ends_the_run() {
    // The checker proves nothing if nothing raises alarms: these must stop with an error. (`G`
    // alone is G00 on Mitsubishi, 003 B.0; `G.` is an error everywhere.)
    let machines = machines();
    for text in [
        "X-", "G.", "N", "O", "X1.2.3", "#1=", "[", "IF", "G0 X1. $", "XX",
    ] {
        let stats = check_everywhere(text.as_bytes(), &machines).unwrap();
        assert_eq!(
            stats.errors,
            machines.len(),
            "`{text}` stops with one error on every profile"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Seeded mutations of the seed examples.

/// Mutations per example file; with about 100 files and five profiles this is some ten thousand
/// runs of short programs, a second or two in a debug build.
const MUTANTS_PER_FILE: usize = 24;

/// Marsaglia's xorshift64: small, deterministic, and good enough to choose mutations.
pub(crate) struct XorShift(pub(crate) u64);

impl XorShift {
    pub(crate) fn next(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        self.0 = x;
        x
    }

    /// A number in `0..n` (`n` > 0).
    pub(crate) fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    /// A range inside `0..len`, at most `max` long.
    pub(crate) fn range(&mut self, len: usize, max: usize) -> std::ops::Range<usize> {
        let start = self.below(len + 1);
        let end = start + self.below(max.min(len - start) + 1);
        start..end
    }
}

/// Bytes a mutation likes to write: the characters the parser treats specially.
const INTERESTING: &[u8] = b"0123456789.-+ ;%()/:#[]=\n\r\t\0XYZGMFNOIJKRPLHDSTABCxgn\xff\xe4\x80";

/// Applies one to four random edits to `text`; `other` is the file splices come from.
pub(crate) fn mutate(text: &[u8], other: &[u8], rng: &mut XorShift) -> Vec<u8> {
    let mut out = text.to_vec();
    for _ in 0..1 + rng.below(4) {
        match rng.below(8) {
            0 if !out.is_empty() => {
                let at = rng.below(out.len());
                out[at] ^= 1 << rng.below(8);
            }
            1 if !out.is_empty() => {
                let at = rng.below(out.len());
                out[at] = INTERESTING[rng.below(INTERESTING.len())];
            }
            2 => {
                let at = rng.below(out.len() + 1);
                out.insert(at, INTERESTING[rng.below(INTERESTING.len())]);
            }
            3 => {
                let cut = rng.range(out.len(), 64);
                out.drain(cut);
            }
            4 => {
                let piece = rng.range(out.len(), 64);
                let copy = out[piece.clone()].to_vec();
                let at = rng.below(out.len() + 1);
                out.splice(at..at, copy.iter().copied());
            }
            5 => {
                // Splice: a piece of another example replaces a piece of this one.
                let from = rng.range(other.len(), 256);
                let into = rng.range(out.len(), 256);
                out.splice(into, other[from].iter().copied());
            }
            6 => {
                // Repeat a short piece many times: long lines, deep nesting, many blocks.
                let piece = rng.range(out.len(), 8);
                let copy = out[piece.clone()].repeat(1 + rng.below(200));
                out.splice(piece.end..piece.end, copy.iter().copied());
            }
            _ => {
                let keep = rng.below(out.len() + 1);
                out.truncate(keep);
            }
        }
    }
    out
}

/// The ISO seed examples, sorted by path so that the mutations do not depend on directory order.
fn seed_examples(shared: &Path) -> Vec<(String, Vec<u8>)> {
    let examples = shared.join("spec/examples");
    let mut files = Vec::new();
    for folder in ["syntec", "fanuc0m", "mitsubishi"] {
        let entries = std::fs::read_dir(examples.join(folder))
            .unwrap_or_else(|e| panic!("reading {folder}: {e}"));
        for entry in entries {
            let path = entry.unwrap().path();
            let name = format!("{folder}/{}", path.file_name().unwrap().to_string_lossy());
            files.push((name, std::fs::read(&path).unwrap()));
        }
    }
    files.sort();
    files
}

#[test]
fn seeded_mutations_of_the_seed_examples_end_with_spans_inside_the_text() {
    let Some(shared) = common::shared_dir() else {
        return;
    };
    let files = seed_examples(&shared);
    assert!(
        files.len() >= 50,
        "expected the ISO seed examples, found {} files",
        files.len()
    );
    let machines = machines();
    let mut rng = XorShift(0x9E37_79B9_7F4A_7C15);
    let mut failures = Vec::new();
    let mut runs = 0;
    for (index, (name, text)) in files.iter().enumerate() {
        // The untouched example is checked too: the properties hold for good programs as well.
        if let Err(e) = check_everywhere(text, &machines) {
            failures.push(format!("{name} (unmutated): {e}"));
        }
        for mutant in 0..MUTANTS_PER_FILE {
            let other = &files[(index + 1 + rng.below(files.len() - 1)) % files.len()].1;
            let mangled = mutate(text, other, &mut rng);
            runs += machines.len();
            if let Err(e) = check_everywhere(&mangled, &machines) {
                failures.push(format!("{name} mutant {mutant}: {e}"));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {runs} runs break a property:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn the_mutation_generator_is_deterministic() {
    let mut a = XorShift(42);
    let mut b = XorShift(42);
    let text = b"G0 X1. Y2.\nG1 Z-1. F100.\nM30\n";
    let other = b"(other) G2 X5. R5.\n";
    for _ in 0..100 {
        assert_eq!(mutate(text, other, &mut a), mutate(text, other, &mut b));
    }
}

// ---------------------------------------------------------------------------------------------
// Random input from proptest.

/// Text made of the pieces G-code is made of: it reaches the interpreter far more often than
/// random bytes, which mostly stop at the first unexpected character.
fn gcode_like() -> impl Strategy<Value = Vec<u8>> {
    let piece = prop_oneof![
        prop::sample::select(vec![
            "G0", "G1", "G2", "G3", "G4", "G17", "G18", "G19", "G20", "G21", "G28", "G30", "G40",
            "G43", "G49", "G52", "G53", "G54", "G54.1", "G80", "G81", "G90", "G91", "G92", "G94",
            "G95", "M3", "M5", "M6", "M30", "X", "Y", "Z", "A", "I", "J", "K", "R", "F", "P", "L",
            "H", "D", "S", "T", "N", "O", "Q", "E", "-", ".", " ", ";", "\n", "\r\n", "(", ")",
            "/", "%", ":", "=", "#", "[",
        ])
        .prop_map(|s: &str| s.as_bytes().to_vec()),
        (-100_000i64..100_000, 0u32..5).prop_map(|(n, point)| {
            let text = if point == 0 {
                format!("{n}")
            } else {
                format!("{}", n as f64 / 10f64.powi(point as i32))
            };
            text.into_bytes()
        }),
        any::<u8>().prop_map(|byte| vec![byte]),
    ];
    prop::collection::vec(piece, 0..60).prop_map(|pieces| pieces.concat())
}

/// The front end alone, with the character rules of every profile: every block, word, comment
/// and alarm span lies inside its line, and every word inside its block.
fn check_front_end(text: &[u8]) -> Result<(), String> {
    use vcnc::syntax::iso::{parse_line, LineBlocks};
    use vcnc::syntax::lines::{LineSource, TextLines};
    let mut blocks = LineBlocks::new();
    for name in ProfileName::ALL {
        let syntax = vcnc::Profile::builtin(name).syntax();
        let mut lines = TextLines::new(text);
        while let Some(line) = lines.next_line().map_err(|e| e.to_string())? {
            let (start, end) = (line.offset, line.offset + line.text.len() as u32);
            let number = line.number;
            parse_line(line, vcnc::FileId(0), &syntax, &mut blocks);
            let inside = |span: Span, what: &str| {
                if start <= span.start
                    && span.start <= span.end
                    && span.end <= end
                    && span.line == number
                {
                    Ok(())
                } else {
                    Err(format!(
                        "{what} span {span} is not inside line {number} ({start}..{end}) on {}",
                        name.as_str()
                    ))
                }
            };
            for block in blocks.as_slice() {
                inside(block.span, "block")?;
                for word in &block.words {
                    inside(word.span, "word")?;
                    if word.span.start < block.span.start || word.span.end > block.span.end {
                        return Err(format!("word {word:?} is outside its block {}", block.span));
                    }
                }
                if let Some(comment) = block.comment {
                    inside(comment, "comment")?;
                }
                for alarm in &block.alarms {
                    inside(
                        alarm.span.ok_or("front-end alarm without a span")?,
                        alarm.code.id(),
                    )?;
                }
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn random_bytes_end_with_spans_inside_the_text(text in prop::collection::vec(any::<u8>(), 0..300)) {
        let machines = machines();
        if let Err(e) = check_everywhere(&text, &machines) {
            prop_assert!(false, "{}", e);
        }
    }

    #[test]
    fn random_g_code_like_text_parses_into_words_inside_their_lines(text in gcode_like()) {
        if let Err(e) = check_front_end(&text) {
            prop_assert!(false, "{} for input `{}`", e, shown(&text));
        }
    }

    #[test]
    fn random_g_code_like_text_ends_with_spans_inside_the_text(text in gcode_like()) {
        let machines = machines();
        if let Err(e) = check_everywhere(&text, &machines) {
            prop_assert!(false, "{}", e);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Findings: one test per problem that these tests found, with its minimal input. All three were
// fixed in 91bb730 ("Values and positions beyond the control's range stop with an alarm").

/// Asserts that `text` keeps every property on every profile and stops with an error alarm.
#[track_caller]
fn check_stops_with_an_alarm(text: &str) {
    let machines = machines();
    let stats = check_everywhere(text.as_bytes(), &machines).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        stats.errors,
        machines.len(),
        "`{}` stops with an error alarm on every profile",
        shown(text.as_bytes())
    );
}

/// `1` followed by `zeros` zeros and a decimal point: a finite number near the top of f64.
fn power_of_ten(zeros: usize) -> String {
    format!("1{}.", "0".repeat(zeros))
}

#[test]
fn a_number_with_more_digits_than_f64_holds_stops_with_an_alarm() {
    // 309 nines read as +inf, and the rapid went to X=inf. The controls accept eight or nine
    // digits per address; more is a format alarm.
    check_stops_with_an_alarm(&format!("X{}", "9".repeat(309)));
}

#[test]
fn a_position_that_overflows_when_an_increment_or_offset_is_added_stops_with_an_alarm() {
    // Each number is finite (1e308); the sum of two is not, and the move went to X=inf.
    let big = power_of_ten(308);
    check_stops_with_an_alarm(&format!("G91X{big}\nX{big}"));
    check_stops_with_an_alarm(&format!("G52X{big}\nX{big}"));
    check_stops_with_an_alarm(&format!("G92X{big}\nX-{big}"));
}

#[test]
fn an_arc_radius_whose_square_overflows_stops_with_an_alarm() {
    // R = 1e155: its square is +inf, and the arc's centre came out as (NaN, -inf).
    check_stops_with_an_alarm(&format!("G2X1.R{}F1.", power_of_ten(155)));
}

/// A line of a million words (8 MB) is refused at its 513th word, whether the fast reader or
/// the general one reads it; before, every word was kept (a 50 MB line of `X1.` held 658 MB).
#[test]
fn a_line_of_a_million_words_is_refused_not_held() {
    let machine = Machine::default();
    for word in ["X1. ", "#1=1 ", "G1 "] {
        let text = format!("G1 F100 {}\nM30\n", word.repeat(1_000_000));
        let items: Vec<_> =
            interpret_bytes(text.as_bytes(), &machine, Options::default()).collect();
        let alarm = items
            .iter()
            .find_map(|item| item.as_ref().err().filter(|a| a.is_error()))
            .unwrap_or_else(|| panic!("{word:?}: no error"));
        assert!(
            alarm.message.contains("more than 512 words"),
            "{word:?}: {alarm}"
        );
    }
}
