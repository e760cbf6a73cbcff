//! A decimal constant as both front ends' short paths read it: digits with at most one point, at
//! most [`MAX_DIGITS`] of them, made into the correctly rounded value by one division (the ISO
//! reader's `plain.rs` and SINUMERIK's `plain.rs` share it; each checks what may follow).

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
