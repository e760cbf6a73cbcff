//! A decimal constant as both front ends' short paths read it: digits with at most one point, at
//! most [`MAX_DIGITS`] of them, made into the correctly rounded value by one division (the ISO
//! reader's `plain.rs` and SINUMERIK's `plain.rs` share it; each checks what may follow). Read
//! byte by byte ([`unsigned_decimal`]), or from fixed windows of a text that runs on past the
//! number ([`windowed_decimal`], for the readers of the text at hand).

use crate::syntax::Number;

/// The most digits the fast path reads in one number. Below 10^15 every mantissa is an integer
/// that f64 holds exactly, and so is every power of ten it is divided by (up to 10^22): one
/// division then rounds once, correctly, as the general reader's does. Longer numbers, rare in a
/// program, take the general reader.
pub(crate) const MAX_DIGITS: usize = 15;

/// The powers of ten that are exact in f64.
pub(crate) const POWERS_OF_TEN: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// A decimal number as its digits read it: `12.50` is 1250 with two fraction digits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Decimal {
    /// The digits as one integer, below 10^[`MAX_DIGITS`].
    pub(crate) mantissa: u64,
    /// How many of the digits stand after the point (at most [`MAX_DIGITS`]).
    pub(crate) fraction_digits: usize,
    /// The number has a decimal point (`X25.` and `X25` differ on most profiles).
    pub(crate) decimal_point: bool,
}

impl Decimal {
    /// The value, correctly rounded: both operands of the division are exact (see
    /// [`MAX_DIGITS`]), so it rounds once.
    #[inline(always)]
    pub(crate) fn number(self, negative: bool) -> Number {
        // Below 2^53 the mantissa converts exactly either way; from i64 it takes one
        // instruction on x86-64, from u64 six.
        let mantissa = self.mantissa as i64 as f64;
        // `fraction_digits` is at most MAX_DIGITS (15): the mask changes nothing and spares
        // the bounds check.
        debug_assert!(self.fraction_digits <= MAX_DIGITS);
        let magnitude = mantissa / POWERS_OF_TEN[self.fraction_digits & 15];
        Number {
            value: if negative { -magnitude } else { magnitude },
            decimal_point: self.decimal_point,
            negative,
        }
    }
}

/// `digits [. [digits]]` or `. digits` at the start of `bytes`, with one to [`MAX_DIGITS`]
/// digits; the decimal and the bytes after it.
#[inline(always)]
pub(crate) fn unsigned_decimal(bytes: &[u8]) -> Option<(Decimal, &[u8])> {
    // One loop over digits and point: the point is rare enough per byte that testing for it
    // only on bytes that are not digits costs less than a second loop for the fraction.
    let mut mantissa = 0u64;
    let mut length = 0;
    let mut point = None;
    while let Some(&byte) = bytes.get(length) {
        // Widened before the subtraction, the digit needs no second widening to be added.
        let digit = u64::from(byte).wrapping_sub(u64::from(b'0'));
        if digit <= 9 {
            // Wrapping: past MAX_DIGITS digits the number is refused below.
            mantissa = mantissa.wrapping_mul(10).wrapping_add(digit);
        } else if byte == b'.' && point.is_none() {
            point = Some(length);
        } else {
            break;
        }
        length += 1;
    }
    let digits = length - usize::from(point.is_some());
    if digits == 0 || digits > MAX_DIGITS {
        return None;
    }
    let decimal = Decimal {
        mantissa,
        fraction_digits: point.map_or(0, |point| length - point - 1),
        decimal_point: point.is_some(),
    };
    Some((decimal, &bytes[length..]))
}

/// [`unsigned_decimal`] where `bytes` runs on far enough after the number: its digits are read
/// from one window of [`WINDOW`] bytes, the whole digits from its first [`RUN`], the fraction's
/// from the [`RUN`] after the point, with no end test per digit (the compiler unrolls the loop of
/// [`digit_run`]) and none for the point or the fraction. `None` as well when `bytes` is shorter
/// than the window.
#[inline(always)]
pub(crate) fn windowed_decimal(bytes: &[u8]) -> Option<(Decimal, &[u8])> {
    let window = bytes.first_chunk::<WINDOW>()?;
    let (whole, whole_digits) = digit_run(0, first_run(window)?);
    // `whole_digits` is at most RUN: the point's place and the fraction's run are in the window
    // (the compiler sees it, and drops the tests).
    let (decimal, length) = match window.get(whole_digits..) {
        Some([b'.', fraction @ ..]) => {
            let (mantissa, fraction_digits) = digit_run(whole, first_run(fraction)?);
            let decimal = Decimal {
                mantissa,
                fraction_digits,
                decimal_point: true,
            };
            (decimal, whole_digits + 1 + fraction_digits)
        }
        _ => {
            let decimal = Decimal {
                mantissa: whole,
                fraction_digits: 0,
                decimal_point: false,
            };
            (decimal, whole_digits)
        }
    };
    let digits = whole_digits + decimal.fraction_digits;
    if digits == 0 || digits > MAX_DIGITS {
        return None;
    }
    // The number takes at most MAX_DIGITS digits and a point, RUN bytes: the minimum changes
    // nothing, and tells the compiler that the RUN + 1 bytes after them in the window follow
    // the number (no tests for the end of the text at the blank and the next letter).
    Some((decimal, bytes.get(length.min(RUN)..).unwrap_or_default()))
}

/// The first [`RUN`] bytes of `bytes`, if it has as many.
#[inline(always)]
fn first_run(bytes: &[u8]) -> Option<&[u8; RUN]> {
    bytes.first_chunk::<RUN>()
}

/// The bytes [`windowed_decimal`] reads: a run of digits, a point, and a run of digits.
pub(crate) const WINDOW: usize = 2 * RUN + 1;

/// The bytes [`digit_run`] reads: one more than [`MAX_DIGITS`], so that a run that fills them
/// is refused.
const RUN: usize = MAX_DIGITS + 1;

/// The digits at the start of `bytes` appended to `mantissa`, and how many there are (`RUN`
/// when all are digits: the run may go on, and the number is too long).
#[inline(always)]
fn digit_run(mut mantissa: u64, bytes: &[u8; RUN]) -> (u64, usize) {
    for (count, &byte) in bytes.iter().enumerate() {
        // Widened before the subtraction, the digit needs no second widening to be added.
        let digit = u64::from(byte).wrapping_sub(u64::from(b'0'));
        if digit > 9 {
            return (mantissa, count);
        }
        // Wrapping: a number of more than MAX_DIGITS digits is refused by the caller.
        mantissa = mantissa.wrapping_mul(10).wrapping_add(digit);
    }
    (mantissa, RUN)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// The windowed reader reads what the byte-by-byte one reads, or leaves it when `bytes` is
    /// shorter than its window.
    pub(crate) fn assert_windowed_agrees(bytes: &[u8]) {
        let by_byte = unsigned_decimal(bytes).map(|(decimal, rest)| (decimal, rest.len()));
        match windowed_decimal(bytes).map(|(decimal, rest)| (decimal, rest.len())) {
            Some(windowed) => assert_eq!(Some(windowed), by_byte, "{bytes:?}"),
            None => assert!(
                by_byte.is_none() || bytes.len() < WINDOW,
                "{bytes:?}: windowed refused {by_byte:?}"
            ),
        }
    }

    #[test]
    fn the_windowed_and_the_byte_by_byte_readers_agree() {
        for text in [
            "0",
            "1.",
            ".5",
            "54.808",
            "-1",
            ".",
            "",
            "1.2.3",
            "1 2",
            "999999999999999",
            "9999999999999999",
            "99999999.9999999",
            "99999999.99999999",
            "1.00000000000001",
            "1.000000000000001",
            "000000000000001",
            "0000000000000001",
            ".000000000000001",
            "123456789012345678901234567890.5",
        ] {
            // Every length of text after the number, from none to more than the windows need,
            // with what may follow a number: a blank, a letter, a line end, a point.
            for after in [" ", "X", "\n", "."] {
                for length in 0..=2 * WINDOW {
                    let bytes = format!("{text}{}", after.repeat(length));
                    assert_windowed_agrees(bytes.as_bytes());
                }
            }
        }
        // A number with text enough after it is read by the windows.
        assert!(windowed_decimal(b"54.808 Y30.491 Z-1.288\nG01 X54.808 Y30.491\n").is_some());
        assert!(windowed_decimal(b"54.808 Y30.491 Z-1.288\n").is_none());
    }
}
