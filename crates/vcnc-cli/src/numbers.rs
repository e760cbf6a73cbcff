//! Fast text output for traces: numbers fixed at most six decimals, trailing zeros trimmed, never
//! `-0`, written into a buffer that flushes in large pieces.
//!
//! Traces of millions of segments spend most of their time here, so this avoids the general float
//! formatter, writes digits straight into the buffer's free room (which is never shorter than
//! [`SLACK`]: no bounds to grow in the middle of a record), and remembers the text of values that
//! repeat from record to record (z, feed).

/// Two decimal digits for every number below 100: formatting two digits per step halves the
/// number of divisions.
const PAIRS: &[u8; 200] = b"0001020304050607080910111213141516171819\
2021222324252627282930313233343536373839\
4041424344454647484950515253545556575859\
6061626364656667686970717273747576777879\
8081828384858687888990919293949596979899";

/// The longest text [`write_decimal`] writes: sign, ten integer digits, point, six decimals.
const SHORT: usize = 24;

/// Writes `value` rounded to 1e-6 at the start of `out`; returns its length, or `None` when the
/// value is not finite or has more than ten integer digits (those go through the general
/// formatter: no machine position comes near).
#[inline(always)]
fn write_decimal(out: &mut [u8; SHORT], value: f64) -> Option<usize> {
    let scaled = value * 1e6;
    if scaled.is_nan() || scaled.abs() >= 9.0e15 {
        return None;
    }
    // Round half away from zero without a call to libm's `round`.
    let micro = if scaled >= 0.0 {
        (scaled + 0.5) as i64
    } else {
        (scaled - 0.5) as i64
    };
    if micro == 0 {
        out[0] = b'0';
        return Some(1);
    }
    out[0] = b'-';
    let mut len = usize::from(micro < 0);
    let micro = micro.unsigned_abs();
    len += write_unsigned(&mut out[len..], micro / 1_000_000);
    let fraction = (micro % 1_000_000) as u32;
    if fraction != 0 {
        out[len] = b'.';
        let pairs = [fraction / 10_000, fraction / 100 % 100, fraction % 100];
        for (k, pair) in pairs.iter().enumerate() {
            let i = *pair as usize * 2;
            out[len + 1 + 2 * k] = PAIRS[i];
            out[len + 2 + 2 * k] = PAIRS[i + 1];
        }
        // Trailing zeros are trimmed: keep up to the last pair that is not zero, and drop its
        // second digit when that is a zero.
        let kept = match pairs {
            [_, _, last] if last != 0 => 6 - usize::from(last % 10 == 0),
            [_, middle, _] if middle != 0 => 4 - usize::from(middle % 10 == 0),
            [first, _, _] => 2 - usize::from(first % 10 == 0),
        };
        len += 1 + kept;
    }
    Some(len)
}

/// Writes the digits of `value` at the start of `out`, which must have room for them (20 at
/// most); returns how many.
#[inline(always)]
fn write_unsigned(out: &mut [u8], mut value: u64) -> usize {
    // Coordinates mostly have few integer digits: compare before taking the logarithm.
    let len = match value {
        0..=9 => 1,
        10..=99 => 2,
        100..=999 => 3,
        _ => value.ilog10() as usize + 1,
    };
    let mut i = len;
    while value >= 100 {
        let pair = (value % 100) as usize * 2;
        value /= 100;
        i -= 2;
        out[i] = PAIRS[pair];
        out[i + 1] = PAIRS[pair + 1];
    }
    if value >= 10 {
        let pair = value as usize * 2;
        out[0] = PAIRS[pair];
        out[1] = PAIRS[pair + 1];
    } else {
        out[0] = b'0' + value as u8;
    }
    len
}

/// The text of the last value written in one field of a record: z and f repeat from record to
/// record, and copying their text costs less than formatting them again.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Remembered {
    bits: u64,
    /// 0 when nothing is remembered.
    len: usize,
    text: [u8; SHORT],
}

impl Default for Remembered {
    fn default() -> Remembered {
        Remembered {
            bits: 0,
            len: 0,
            text: [0; SHORT],
        }
    }
}

/// Room that is always free at the end of an [`OutBuffer`] after a [`OutBuffer::put`] or
/// [`OutBuffer::start_record`]: more than any record needs apart from its variable texts (file
/// names), which `put` and `start_record` make room for.
const SLACK: usize = 4096;

/// Where a trace's text is assembled before it is written out in large pieces.
///
/// After a `put`, the bytes after `len` are at least [`SLACK`] long, so numbers are written in
/// place and remembered ones copied as one fixed-size block; a record is a few hundred bytes and
/// starts with a `put`.
#[derive(Debug)]
pub(crate) struct OutBuffer {
    bytes: Vec<u8>,
    len: usize,
    /// Flush when this much is written.
    flush_at: usize,
}

impl OutBuffer {
    /// A buffer that asks to be flushed at `flush_at` bytes.
    pub(crate) fn new(flush_at: usize) -> OutBuffer {
        OutBuffer {
            bytes: vec![0; flush_at + SLACK],
            len: 0,
            flush_at,
        }
    }

    /// True when the text should be written out now.
    pub(crate) fn is_full(&self) -> bool {
        self.len >= self.flush_at
    }

    /// The text assembled so far.
    pub(crate) fn as_bytes(&self) -> &[u8] {
        &self.bytes[..self.len]
    }

    /// Forgets the text (after it was written out).
    pub(crate) fn clear(&mut self) {
        self.len = 0;
    }

    /// Appends any bytes.
    #[inline(always)]
    pub(crate) fn put(&mut self, text: &[u8]) {
        let end = self.len + text.len();
        if end + SLACK > self.bytes.len() {
            self.grow_to(end + SLACK);
        }
        self.bytes[self.len..end].copy_from_slice(text);
        self.len = end;
    }

    /// Makes room for a record of at most [`SLACK`] bytes plus `long` bytes of variable text:
    /// the record's pieces are then written with the `*_in_record` methods, which do not check.
    #[inline(always)]
    pub(crate) fn start_record(&mut self, long: usize) {
        if self.len + long + SLACK > self.bytes.len() {
            self.grow_to(self.len + long + SLACK);
        }
    }

    /// Appends bytes inside a record started with [`OutBuffer::start_record`] (a slice index
    /// panics, never writes out of bounds, if the record is longer than it said).
    #[inline(always)]
    pub(crate) fn put_in_record(&mut self, text: &[u8]) {
        self.bytes[self.len..self.len + text.len()].copy_from_slice(text);
        self.len += text.len();
    }

    /// Appends one byte.
    #[inline(always)]
    pub(crate) fn byte(&mut self, byte: u8) {
        self.bytes[self.len] = byte;
        self.len += 1;
    }

    /// The free room at the cursor where a number is written.
    #[inline(always)]
    fn window(&mut self) -> &mut [u8; SHORT] {
        let window = &mut self.bytes[self.len..self.len + SHORT];
        window.try_into().expect("the slack holds a number")
    }

    /// Appends `value` rounded to 1e-6.
    #[inline(always)]
    pub(crate) fn decimal(&mut self, value: f64) {
        match write_decimal(self.window(), value) {
            Some(len) => self.len += len,
            None => self.general(value),
        }
    }

    /// Appends `value` rounded to 1e-6, reusing the text of `memory` when the value is the same
    /// as last time.
    #[inline(always)]
    pub(crate) fn remembered(&mut self, memory: &mut Remembered, value: f64) {
        let bits = value.to_bits();
        if bits == memory.bits && memory.len > 0 {
            *self.window() = memory.text;
            self.len += memory.len;
            return;
        }
        match write_decimal(self.window(), value) {
            Some(len) => {
                memory.text = *self.window();
                memory.bits = bits;
                memory.len = len;
                self.len += len;
            }
            None => {
                memory.len = 0;
                self.general(value);
            }
        }
    }

    /// Values [`write_decimal`] does not take: `null` for NaN and infinities, else every digit.
    #[cold]
    fn general(&mut self, value: f64) {
        if value.is_finite() {
            self.put(format!("{value}").as_bytes());
        } else {
            self.put(b"null");
        }
    }

    /// Appends an unsigned integer.
    #[inline(always)]
    pub(crate) fn unsigned(&mut self, value: u64) {
        let len = write_unsigned(&mut self.bytes[self.len..self.len + 20], value);
        self.len += len;
    }

    #[cold]
    fn grow_to(&mut self, len: usize) {
        self.bytes.resize(len.max(2 * self.bytes.len()), 0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn show(value: f64) -> String {
        let mut out = OutBuffer::new(64);
        out.decimal(value);
        String::from_utf8(out.as_bytes().to_vec()).unwrap()
    }

    #[test]
    fn decimals_are_trimmed_and_rounded() {
        assert_eq!(show(0.0), "0");
        assert_eq!(show(-0.0000001), "0");
        assert_eq!(show(12.5), "12.5");
        assert_eq!(show(-1.833), "-1.833");
        assert_eq!(show(72.80109889), "72.801099");
        assert_eq!(show(100.0), "100");
        assert_eq!(show(0.000001), "0.000001");
        assert_eq!(show(-123456.5), "-123456.5");
        assert_eq!(show(1234567.000123), "1234567.000123");
        assert_eq!(show(-999999999.999999), "-999999999.999999");
        assert_eq!(show(1.0e10), "10000000000");
        assert_eq!(show(f64::NAN), "null");
        assert_eq!(show(f64::NEG_INFINITY), "null");
    }

    #[test]
    fn every_text_reads_back_within_half_a_micrometre() {
        // A fixed pseudo-random walk over magnitudes from 1e-7 to 1e9, both signs.
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        for _ in 0..200_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let mantissa = (state >> 11) as f64 / (1u64 << 53) as f64;
            let exponent = (state % 17) as i32 - 7;
            let sign = if state & 1 == 0 { 1.0 } else { -1.0 };
            let value = sign * mantissa * 10f64.powi(exponent);
            let text = show(value);
            let back: f64 = text.parse().unwrap();
            assert!(
                (back - value).abs() <= 5.0e-7 * (1.0 + 1e-9) + value.abs() * 1e-15,
                "{value} {text}"
            );
            assert!(!text.starts_with("-0") || text.starts_with("-0."), "{text}");
            assert_ne!(text, "-0");
            if text.contains('.') {
                assert!(!text.ends_with('0') && !text.ends_with('.'), "{text}");
            }
        }
    }

    #[test]
    fn unsigned_integers_have_every_digit() {
        for n in [0u64, 7, 10, 99, 100, 12345, u64::MAX] {
            let mut out = OutBuffer::new(64);
            out.unsigned(n);
            assert_eq!(
                String::from_utf8(out.as_bytes().to_vec()).unwrap(),
                n.to_string()
            );
        }
    }

    #[test]
    fn remembered_text_follows_the_value() {
        let mut out = OutBuffer::new(64);
        let mut memory = Remembered::default();
        for value in [1.5, 1.5, -2.0, -2.0, 0.0, f64::NAN, f64::NAN, 0.0, 3.25] {
            out.remembered(&mut memory, value);
            out.byte(b' ');
        }
        assert_eq!(
            String::from_utf8(out.as_bytes().to_vec()).unwrap(),
            "1.5 1.5 -2 -2 0 null null 0 3.25 "
        );
    }

    #[test]
    fn long_pieces_grow_the_buffer_and_keep_the_slack() {
        let mut out = OutBuffer::new(16);
        let long = vec![b'a'; 3 * SLACK];
        out.put(&long);
        out.decimal(-1.25);
        out.unsigned(42);
        assert!(out.is_full());
        assert_eq!(out.as_bytes().len(), 3 * SLACK + 5 + 2);
        assert!(out.as_bytes().ends_with(b"-1.2542"));
    }
}
