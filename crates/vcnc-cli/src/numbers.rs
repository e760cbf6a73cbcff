//! Fast, exact-enough number formatting for traces: fixed at most six decimals, trailing zeros
//! trimmed, never `-0`. Traces of millions of segments spend most of their time here, so this
//! avoids the general float formatter.

/// Appends `value` rounded to 1e-6 to `out`.
pub(crate) fn push_decimal(out: &mut Vec<u8>, value: f64) {
    if !value.is_finite() {
        out.extend_from_slice(b"null");
        return;
    }
    let scaled = (value * 1e6).round();
    if scaled.abs() >= 9.0e15 {
        out.extend_from_slice(format!("{value}").as_bytes());
        return;
    }
    let mut micro = scaled as i64;
    if micro == 0 {
        out.push(b'0');
        return;
    }
    if micro < 0 {
        out.push(b'-');
        micro = -micro;
    }
    let whole = (micro / 1_000_000) as u64;
    let mut fraction = (micro % 1_000_000) as u32;
    push_unsigned(out, whole);
    if fraction != 0 {
        out.push(b'.');
        let mut digits = 6;
        while fraction % 10 == 0 {
            fraction /= 10;
            digits -= 1;
        }
        let mut buffer = [b'0'; 6];
        for slot in buffer[..digits].iter_mut().rev() {
            *slot = b'0' + (fraction % 10) as u8;
            fraction /= 10;
        }
        out.extend_from_slice(&buffer[..digits]);
    }
}

/// Appends an unsigned integer.
pub(crate) fn push_unsigned(out: &mut Vec<u8>, mut value: u64) {
    let mut buffer = [0u8; 20];
    let mut i = buffer.len();
    loop {
        i -= 1;
        buffer[i] = b'0' + (value % 10) as u8;
        value /= 10;
        if value == 0 {
            break;
        }
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
    }
}
