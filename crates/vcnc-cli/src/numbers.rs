//! Fast, exact-enough number formatting for traces: fixed at most six decimals, trailing zeros
//! trimmed, never `-0`. Traces of millions of segments spend most of their time here, so this
//! avoids the general float formatter.

/// Two decimal digits for every number below 100: formatting two digits per step halves the
/// number of divisions.
const PAIRS: &[u8; 200] = b"0001020304050607080910111213141516171819\
2021222324252627282930313233343536373839\
4041424344454647484950515253545556575859\
6061626364656667686970717273747576777879\
8081828384858687888990919293949596979899";

/// Appends `value` rounded to 1e-6 to `out`.
pub(crate) fn push_decimal(out: &mut Vec<u8>, value: f64) {
    if !value.is_finite() {
        out.extend_from_slice(b"null");
        return;
    }
    let scaled = value * 1e6;
    if scaled.abs() >= 9.0e15 {
        out.extend_from_slice(format!("{value}").as_bytes());
        return;
    }
    // Round half away from zero without a call to libm's `round`.
    let micro = if scaled >= 0.0 {
        (scaled + 0.5) as i64
    } else {
        (scaled - 0.5) as i64
    };
    if micro == 0 {
        out.push(b'0');
        return;
    }
    if micro < 0 {
        out.push(b'-');
    }
    let micro = micro.unsigned_abs();
    push_unsigned(out, micro / 1_000_000);
    let fraction = (micro % 1_000_000) as u32;
    if fraction != 0 {
        let mut digits = [b'.', 0, 0, 0, 0, 0, 0];
        let pairs = [fraction / 10_000, fraction / 100 % 100, fraction % 100];
        for (k, pair) in pairs.iter().enumerate() {
            let i = *pair as usize * 2;
            digits[1 + 2 * k] = PAIRS[i];
            digits[2 + 2 * k] = PAIRS[i + 1];
        }
        let mut len = 7;
        while digits[len - 1] == b'0' {
            len -= 1;
        }
        out.extend_from_slice(&digits[..len]);
    }
}

/// Appends an unsigned integer.
pub(crate) fn push_unsigned(out: &mut Vec<u8>, mut value: u64) {
    let mut buffer = [0u8; 20];
    let mut i = buffer.len();
    while value >= 100 {
        let pair = (value % 100) as usize * 2;
        value /= 100;
        i -= 2;
        buffer[i] = PAIRS[pair];
        buffer[i + 1] = PAIRS[pair + 1];
    }
    if value >= 10 {
        let pair = value as usize * 2;
        i -= 2;
        buffer[i] = PAIRS[pair];
        buffer[i + 1] = PAIRS[pair + 1];
    } else {
        i -= 1;
        buffer[i] = b'0' + value as u8;
    }
    out.extend_from_slice(&buffer[i..]);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn show(value: f64) -> String {
        let mut out = Vec::new();
        push_decimal(&mut out, value);
        String::from_utf8(out).unwrap()
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
        let mut out = Vec::new();
        for n in [0u64, 7, 10, 99, 100, 12345, u64::MAX] {
            out.clear();
            push_unsigned(&mut out, n);
            assert_eq!(String::from_utf8(out.clone()).unwrap(), n.to_string());
        }
    }
}
