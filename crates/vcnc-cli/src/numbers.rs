//! Fast text output for traces: numbers fixed at most six decimals, trailing zeros trimmed, never
//! `-0`, written into a buffer that flushes in large pieces.
//!
//! Traces of millions of segments spend most of their time here, so this avoids the general float
//! formatter and the buffer's bookkeeping per field. A record is written through a
//! [`RecordText`], which makes room once for the whole record and keeps its own cursor. Numbers
//! are written in place as whole words, three digits at a time from tables: the whole part from
//! a table of texts without leading zeros, the six decimals as one word whose trailing zeros are
//! dropped by counting its zero bytes; no loop and no division instruction. Constant texts are
//! copied as fixed-size blocks, and the text of values that repeat from record to record (z,
//! feed) is remembered.

/// The longest text [`write_decimal`] writes, with the bytes past its end that it may overwrite:
/// sign, ten integer digits, point, six decimals, and junk up to a whole word.
const SHORT: usize = 24;

/// The longest text [`write_unsigned`] writes, with the junk after a short one.
const UNSIGNED: usize = 20;

/// The longest key a field is written with (`,"seconds":`).
const KEY: usize = 16;

/// Every number below 1000 as three digits, one per byte (values 0 to 9, not yet text), the
/// first digit in the lowest byte: the byte order in which little-endian words are written.
/// Padded to 1024 entries, so that an index masked to ten bits needs no bounds check.
static DIGITS3: [u32; 1024] = {
    let mut table = [0; 1024];
    let mut i = 0;
    while i < 1000 {
        table[i] = (i / 100) as u32 | ((i / 10 % 10) as u32) << 8 | ((i % 10) as u32) << 16;
        i += 1;
    }
    table
};

/// Every number below 1000 as text without leading zeros in the three low bytes (first digit
/// lowest), and its length in the two high bits: a whole number below 1000 is one load and one
/// store, and a length the compiler knows is at most 3. Padded to 1024 entries like
/// [`DIGITS3`].
static TEXT3: [u32; 1024] = {
    let mut table = [0; 1024];
    let mut i = 0;
    while i < 1000 {
        let len = 1 + (i >= 10) as u32 + (i >= 100) as u32;
        // The digits, leading zeros dropped, and `b'0'` added to each.
        let text = (DIGITS3[i] | 0x30_3030) >> (8 * (3 - len));
        table[i] = text | len << 30;
        i += 1;
    }
    table
};

/// Every number below 1000 as three digits of text, leading zeros included (first digit
/// lowest): the low part of a larger number. Padded to 1024 entries like [`DIGITS3`].
static ZERO_FILLED3: [u32; 1024] = {
    let mut table = [0; 1024];
    let mut i = 0;
    while i < 1000 {
        table[i] = DIGITS3[i] | 0x30_3030;
        i += 1;
    }
    table
};

/// `b'0'` in the six low bytes: added to the digits of [`digits6`], it gives their text.
const ZEROS: u64 = 0x3030_3030_3030;

/// The six digits of `value` (below 10^6), leading zeros included, one per byte in the six low
/// bytes of the word (first digit lowest); the two high bytes are zero.
#[inline(always)]
fn digits6(value: u32) -> u64 {
    let high = value / 1000;
    let low = value % 1000;
    // `high` is below 1000 for every value this is given: the mask only spares a bounds check.
    u64::from(DIGITS3[(high & 1023) as usize]) | u64::from(DIGITS3[low as usize]) << 24
}

/// Writes `value` (below 10^6) at the start of `out`, followed by junk up to the seventh byte;
/// returns its length. Whole millimetres and seconds are mostly below 1000: one branch that
/// is predicted field by field is cheaper than finding the length of six digits.
#[inline(always)]
fn write_below_million(out: &mut [u8; 7], value: u32) -> usize {
    if value < 1000 {
        write_below_thousand(out, value)
    } else {
        write_thousands(out, value)
    }
}

/// [`write_below_million`] for `value` below 1000: one load and one store.
#[inline(always)]
fn write_below_thousand(out: &mut [u8; 7], value: u32) -> usize {
    // `value` is below 1000: the mask only spares a bounds check.
    let text = TEXT3[(value & 1023) as usize];
    out[..4].copy_from_slice(&text.to_le_bytes());
    (text >> 30) as usize
}

/// [`write_below_million`] for `value` from 1000 to 999,999.
#[inline(always)]
fn write_thousands(out: &mut [u8; 7], value: u32) -> usize {
    let high = TEXT3[((value / 1000) & 1023) as usize];
    let len = (high >> 30) as usize;
    let low = ZERO_FILLED3[(value % 1000) as usize];
    out[..4].copy_from_slice(&high.to_le_bytes());
    out[len..len + 4].copy_from_slice(&low.to_le_bytes());
    len + 3
}

/// Writes `key` and `value` rounded to 1e-6 at the start of `out`; returns the length of both,
/// or `None` when the value is not finite or has more than ten integer digits (those go through
/// the general formatter: no machine position comes near), with the key written.
#[inline(always)]
fn write_decimal(out: &mut [u8; KEY + SHORT], key: &Key, value: f64) -> Option<usize> {
    // The key and a minus sign after it, as one block: whether the sign stays is known later.
    *out.first_chunk_mut().expect("room for the key") = key.block;
    let key_len = key.len();
    let number: &mut [u8; SHORT] = (&mut out[key_len..key_len + SHORT])
        .try_into()
        .expect("a number's room");
    // NaN gives 0 and magnitudes past 2^63 saturate: the tests of `micro` and `whole` below
    // sort both out, so that no test of the float is needed on the way of a common number.
    let micro = micrometres((value * 1e6).abs());
    if micro == 0 {
        if value.is_nan() {
            return None;
        }
        // Never `-0`.
        number[0] = b'0';
        return Some(key_len + 1);
    }
    let sign = usize::from(value.is_sign_negative());
    let whole_text: &mut [u8; 7] = (&mut number[sign..sign + 7])
        .try_into()
        .expect("seven bytes");
    // Machine positions and durations are mostly below 1000: one branch that is predicted field
    // by field is cheaper than finding the length of six digits.
    // The split into whole and fraction in the width the value needs: a whole part below 1000
    // fits 32 bits with its micrometres, where dividing by a constant takes fewer instructions.
    let (whole_len, fraction) = if micro < 1_000_000_000 {
        let micro = micro as u32;
        let whole = micro / 1_000_000;
        (write_below_thousand(whole_text, whole), micro % 1_000_000)
    } else if micro < 1_000_000_000_000 {
        let whole = (micro / 1_000_000) as u32;
        (
            write_thousands(whole_text, whole),
            (micro % 1_000_000) as u32,
        )
    } else {
        // Never more than `SHORT`: the minimum tells the compiler, which does not see the
        // length through the call, so that the fields after this one need no bounds check.
        return write_long_decimal(number, value).map(|len| key_len + len.min(SHORT));
    };
    let len = sign + whole_len;
    Some(key_len + len + write_decimals(&mut number[len..len + 8], fraction))
}

/// `magnitude` (micrometres, not negative) rounded half up to a whole number, without a call to
/// libm's `round`: the magnitude of `scaled + 0.5` or `scaled - 0.5` chosen by the sign of
/// `scaled`, as floating-point rounding is the same for both signs. NaN gives 0, and magnitudes
/// of 2^63 and more give `i64::MAX` (Rust's conversions saturate).
#[inline(always)]
fn micrometres(magnitude: f64) -> u64 {
    (magnitude + 0.5) as i64 as u64
}

/// Writes the point and the six decimals of `fraction` (micrometres, below 10^6) as one word at
/// the start of `out`; returns how many of its bytes are kept. The word's zero bytes at the high
/// end are the trailing zeros: they are dropped, and the point with them when no decimal is left.
#[inline(always)]
fn write_decimals(out: &mut [u8], fraction: u32) -> usize {
    let decimals = digits6(fraction) << 8;
    out[..8].copy_from_slice(&(decimals | ZEROS << 8 | u64::from(b'.')).to_le_bytes());
    // With the point and k decimals kept, the last decimal that is not 0 (1 to 9) is in byte k:
    // its highest bit is bit 8k to 8k + 3, or 8k + 1 to 8k + 4 in the word doubled, whose added
    // low bit makes it never 0 (so the count needs no case for 0) and gives 0 kept for no
    // decimal at all.
    ((decimals << 1 | 1).ilog2() as usize).div_ceil(8)
}

/// [`write_decimal`]'s number for values of a million and more, far beyond any machine position:
/// up to ten integer digits, or `None`. Out of line, so that the short path's lengths stay small
/// enough for the compiler to check no bounds.
#[cold]
#[inline(never)]
fn write_long_decimal(out: &mut [u8; SHORT], value: f64) -> Option<usize> {
    let magnitude = (value * 1e6).abs();
    // False for NaN too.
    let in_range = magnitude < 9.0e15;
    if !in_range {
        return None;
    }
    // Not 0: the whole part is a million or more.
    let micro = micrometres(magnitude);
    out[0] = b'-';
    let sign = usize::from(value.is_sign_negative());
    let len = sign + write_unsigned(&mut out[sign..], micro / 1_000_000);
    Some(len + write_decimals(&mut out[len..], (micro % 1_000_000) as u32))
}

/// Writes the digits of `value` at the start of `out`, followed by junk up to the seventh byte
/// when there are fewer; `out` must hold [`UNSIGNED`] bytes (seven for a value below 10^6).
/// Returns how many digits.
#[inline(always)]
fn write_unsigned(out: &mut [u8], value: u64) -> usize {
    if value < 1_000_000 {
        write_below_million(
            (&mut out[..7]).try_into().expect("seven bytes"),
            value as u32,
        )
    } else {
        // Never more than `UNSIGNED`: the minimum tells the compiler, which does not see the
        // length through the call, so that the fields after this one need no bounds check.
        write_long_unsigned(out, value).min(UNSIGNED)
    }
}

/// [`write_unsigned`] for values of seven digits and more: line numbers of long programs, times
/// past eleven days.
#[inline(never)]
fn write_long_unsigned(out: &mut [u8], value: u64) -> usize {
    if value >= 1_000_000_000_000 {
        return write_huge_unsigned(out, value);
    }
    let len = write_below_million(
        (&mut out[..7]).try_into().expect("seven bytes"),
        (value / 1_000_000) as u32,
    );
    let low = digits6((value % 1_000_000) as u32) | ZEROS;
    out[len..len + 8].copy_from_slice(&low.to_le_bytes());
    len + 6
}

/// [`write_unsigned`] for values of thirteen digits and more, which no trace has.
#[cold]
#[inline(never)]
fn write_huge_unsigned(out: &mut [u8], mut value: u64) -> usize {
    let mut digits = [0; UNSIGNED];
    let mut start = UNSIGNED;
    loop {
        start -= 1;
        digits[start] = b'0' + (value % 10) as u8;
        value /= 10;
        if value == 0 {
            break;
        }
    }
    out[..UNSIGNED - start].copy_from_slice(&digits[start..]);
    UNSIGNED - start
}

/// A field's key (`,"x":`, `,` or nothing), followed by minus signs up to [`KEY`] bytes: a
/// number's key and its sign, when it is negative, are written as one block.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Key {
    block: [u8; KEY],
    /// A byte, so that the compiler knows a bound of the record's length after it.
    len: u8,
}

impl Key {
    /// The key `text`, shorter than [`KEY`]; fails to compile (or panics, made at run time)
    /// when it is longer.
    pub(crate) const fn new(text: &str) -> Key {
        Key::from_bytes(text.as_bytes())
    }

    /// [`Key::new`] of bytes.
    const fn from_bytes(text: &[u8]) -> Key {
        assert!(text.len() < KEY, "a key's length");
        let mut block = [b'-'; KEY];
        let mut i = 0;
        while i < text.len() {
            block[i] = text[i];
            i += 1;
        }
        Key {
            block,
            len: text.len() as u8,
        }
    }

    fn len(&self) -> usize {
        usize::from(self.len)
    }

    /// The key's text.
    pub(crate) fn as_bytes(&self) -> &[u8] {
        &self.block[..self.len()]
    }
}

/// A key made of bytes when the record is written, for callers that have no constant [`Key`]
/// (the `interp` bench of the library): the compiler does not fold the block into a constant.
impl From<&[u8]> for Key {
    fn from(text: &[u8]) -> Key {
        Key::from_bytes(text)
    }
}

/// As for `&[u8]`.
impl<const N: usize> From<&[u8; N]> for Key {
    fn from(text: &[u8; N]) -> Key {
        Key::from_bytes(text)
    }
}

/// A short constant text, padded to a fixed size so that it is copied as one block of
/// [`FixedText::SIZE`] bytes (a few moves) instead of a call to `memcpy`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FixedText {
    bytes: [u8; FixedText::SIZE],
    /// A byte, so that the compiler knows a bound of the record's length after it.
    len: u8,
}

impl FixedText {
    /// The room a fixed text takes, and the longest text it holds.
    pub(crate) const SIZE: usize = 32;

    /// The pieces of `parts` one after the other; fails to compile (or panics, made at run
    /// time) when they are longer than [`FixedText::SIZE`].
    pub(crate) const fn join(parts: &[&str]) -> FixedText {
        let mut text = FixedText {
            bytes: [0; FixedText::SIZE],
            len: 0,
        };
        let mut part = 0;
        while part < parts.len() {
            let bytes = parts[part].as_bytes();
            let mut i = 0;
            while i < bytes.len() {
                text.bytes[text.len as usize] = bytes[i];
                text.len += 1;
                i += 1;
            }
            part += 1;
        }
        text
    }

    /// The text.
    #[cfg(test)]
    pub(crate) fn as_bytes(&self) -> &[u8] {
        &self.bytes[..usize::from(self.len)]
    }
}

/// A text of any length (a file name), kept with zeros after it up to a multiple of
/// [`PaddedText::BLOCK`] bytes, at least one block, so that it is copied in blocks without a
/// call to `memcpy`: in one block when it is short.
#[derive(Clone, Debug, Default)]
pub(crate) struct PaddedText {
    /// The first block, and the blocks after it (empty for a short text).
    first: [u8; PaddedText::BLOCK],
    rest: Vec<u8>,
    /// A u32, so that the cursor after the text cannot overflow.
    len: u32,
}

impl PaddedText {
    const BLOCK: usize = 32;

    /// Keeps `text`.
    pub(crate) fn new(text: &[u8]) -> PaddedText {
        let mut bytes = text.to_vec();
        bytes.resize(text.len().next_multiple_of(Self::BLOCK).max(Self::BLOCK), 0);
        let rest = bytes.split_off(Self::BLOCK);
        PaddedText {
            first: bytes.try_into().expect("one block"),
            rest,
            len: u32::try_from(text.len()).expect("a text shorter than 4 GiB"),
        }
    }

    /// Its length with the padding: the room it takes in a record. A u32 (as its length), so
    /// that the room of a record with it is known not to overflow.
    pub(crate) fn room(&self) -> u32 {
        (Self::BLOCK + self.rest.len()) as u32
    }
}

/// The text of the last value written in one field of a record: z and f repeat from record to
/// record, and copying their text costs less than formatting them again.
///
/// It always holds the text of the value of `bits`, so that one comparison tells whether the
/// text can be reused: at first, and after a value whose text is longer than
/// [`Remembered::LONGEST`] or went through the general formatter, the text of 0.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Remembered {
    bits: u64,
    /// A byte, so that the compiler knows a bound of the record's length after it.
    len: u8,
    text: [u8; Remembered::LONGEST],
}

impl Remembered {
    /// The longest text remembered: longer ones are rare (ten significant digits), and a
    /// shorter block is copied with fewer moves.
    const LONGEST: usize = 16;
}

impl Default for Remembered {
    fn default() -> Remembered {
        let mut text = [0; Remembered::LONGEST];
        text[0] = b'0';
        Remembered {
            bits: 0.0f64.to_bits(),
            len: 1,
            text,
        }
    }
}

/// The text of the last run of fields written at one place of a record, with the values they
/// were written from: at the end of the common record, z, f and the record's end repeat from
/// record to record together, and copying their text costs less than writing each field.
///
/// When it holds a text, it is the text of the values of `values`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RememberedRun {
    /// The bits of the values the text was written from, `None` before the first run and after
    /// a run longer than [`RememberedRun::LONGEST`].
    values: Option<[u64; 2]>,
    /// A byte, so that the compiler knows a bound of the record's length after it.
    len: u8,
    text: [u8; RememberedRun::LONGEST],
}

impl RememberedRun {
    /// The longest run remembered: two short fields and a little more.
    const LONGEST: usize = 48;
}

/// Where a run of fields starts in a record: see [`RecordText::reused`].
#[derive(Clone, Copy, Debug)]
pub(crate) struct RunStart(u32);

impl Default for RememberedRun {
    fn default() -> RememberedRun {
        RememberedRun {
            values: None,
            len: 0,
            text: [0; RememberedRun::LONGEST],
        }
    }
}

/// The longest text of a number that [`write_decimal`] does not take: `-` and the 309 digits of
/// `f64::MAX` (never an exponent).
const GENERAL: usize = 310;

/// The room a record has after its padded text (or from its start when it has none): more than
/// any record needs. A record has at most 16 numbers (t, dt, six axes, f, three centre and three
/// work coordinates), each at most [`GENERAL`] long with its key, and a few hundred bytes more.
const FIELDS: usize = 16 * (KEY + GENERAL) + 1024;

/// The room a record has before its padded text: its kind, line and a comma.
const HEAD: usize = 64;

/// Room that is always free at the end of an [`OutBuffer`] after a [`OutBuffer::put`], and that
/// [`OutBuffer::record`] gives a record besides its padded text (a file name), which `record`
/// makes room for.
const SLACK: usize = HEAD + FIELDS;

/// Where a trace's text is assembled before it is written out in large pieces.
///
/// After a `put`, the bytes after `len` are at least [`SLACK`] long; a record starts with
/// [`OutBuffer::record`], which makes room for it once.
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
    pub(crate) fn put(&mut self, text: &[u8]) {
        let end = self.len + text.len();
        if end + SLACK > self.bytes.len() {
            self.grow_to(end + SLACK);
        }
        self.bytes[self.len..end].copy_from_slice(text);
        self.len = end;
    }

    /// Starts a record of at most [`HEAD`] bytes, then at most one padded text of `long` bytes
    /// with its padding, then at most [`FIELDS`] bytes: its pieces are written into the returned
    /// room, and the buffer takes them when it is dropped.
    #[inline(always)]
    pub(crate) fn record(&mut self, long: u32) -> RecordText<'_> {
        let need = long as usize + SLACK;
        if self.len + need > self.bytes.len() {
            self.grow_to(self.len + need);
        }
        let OutBuffer { bytes, len, .. } = self;
        let room = &mut bytes[*len..];
        // True after the growth above; said again where the compiler sees it, so that the
        // bounds checks of the windows at the record's start (constant offsets) and of the
        // fields after a short padded text fold into it.
        assert!(room.len() >= SLACK, "a record's room");
        RecordText {
            room,
            len: 0,
            before: 0,
            taken: len,
        }
    }

    #[cold]
    fn grow_to(&mut self, len: usize) {
        self.bytes.resize(len.max(2 * self.bytes.len()), 0);
    }
}

/// The room where one record is written, with its own cursor; the record's text joins the
/// buffer when this is dropped.
///
/// Every piece is written into a fixed-size window of the room, so that a field takes at most
/// one bounds check (a slice index panics, never writes out of bounds, if a record were longer
/// than its room), and numbers and constant texts are written as whole words, with junk after
/// them that the next piece overwrites. After the padded text the room is [`FIELDS`] bytes
/// from the cursor, a constant: as long as the compiler can bound the cursor (no loop, every
/// length bounded), the windows of the fields that follow need no check at all.
///
/// No function out of line takes the room itself (`&mut self`): the compiler keeps it and the
/// cursor in registers.
#[derive(Debug)]
pub(crate) struct RecordText<'a> {
    room: &'a mut [u8],
    /// A u32, far more than a record's length, so that the end of a window (its start plus a
    /// constant) cannot overflow and its bounds check is one comparison.
    len: u32,
    /// The record's bytes before the room: the room starts again after a padded text.
    before: usize,
    /// The buffer's length, to which the record's is added at the end.
    taken: &'a mut usize,
}

impl Drop for RecordText<'_> {
    fn drop(&mut self) {
        *self.taken += self.before + self.len as usize;
    }
}

impl RecordText<'_> {
    /// Moves the cursor past `written` bytes.
    #[inline(always)]
    fn advance(&mut self, written: usize) {
        self.len += written as u32;
    }

    /// The `N` bytes of room at the cursor.
    #[inline(always)]
    fn window<const N: usize>(&mut self) -> &mut [u8; N] {
        let start = self.len as usize;
        let window = &mut self.room[start..start + N];
        window.try_into().expect("a window of N bytes")
    }

    /// Appends any bytes (a constant is copied without a call).
    #[inline(always)]
    pub(crate) fn put(&mut self, text: &[u8]) {
        let start = self.len as usize;
        self.room[start..start + text.len()].copy_from_slice(text);
        self.advance(text.len());
    }

    /// Appends one byte.
    #[inline(always)]
    pub(crate) fn byte(&mut self, byte: u8) {
        self.window::<1>()[0] = byte;
        self.len += 1;
    }

    /// Appends a short constant text.
    #[inline(always)]
    pub(crate) fn fixed(&mut self, text: &FixedText) {
        *self.window() = text.bytes;
        self.advance(usize::from(text.len));
    }

    /// Appends a text of any length, the record's only one; the room after it is at least
    /// [`FIELDS`] bytes.
    #[inline(always)]
    pub(crate) fn padded(&mut self, text: &PaddedText) {
        *self.window() = text.first;
        if text.len <= PaddedText::BLOCK as u32 {
            // The common case, a short text: the cursor stays below `HEAD` + `BLOCK` for the
            // compiler, and the room as it is holds the fields after it.
            self.advance(text.len as usize);
        } else {
            let start = self.len as usize;
            copy_blocks(&mut self.room[start + PaddedText::BLOCK..], &text.rest);
            // The room starts again after the text, with a constant length: the compiler can
            // bound the cursor again.
            let end = start + text.len as usize;
            let room = std::mem::take(&mut self.room);
            self.room = &mut room[end..end + FIELDS];
            self.before += end;
            self.len = 0;
        }
    }

    /// Appends `key` and `value` rounded to 1e-6.
    #[inline(always)]
    pub(crate) fn decimal(&mut self, key: impl Into<Key>, value: f64) {
        let key = &key.into();
        let window: &mut [u8; KEY + GENERAL] = self.window();
        let len = match write_decimal(
            window.first_chunk_mut().expect("a field's room"),
            key,
            value,
        ) {
            Some(len) => len,
            None => key.len() + general(&mut window[key.len()..key.len() + GENERAL], value),
        };
        self.advance(len);
    }

    /// Appends `key` and `value` rounded to 1e-6, copying the text `memory` holds when it is
    /// the text of `value`, and leaving `memory` as it is: for a field that often has the value
    /// of another (an arc's centre in Z, the end's Z).
    #[inline(always)]
    pub(crate) fn decimal_as(&mut self, key: impl Into<Key>, memory: &Remembered, value: f64) {
        let key = &key.into();
        if value.to_bits() != memory.bits {
            self.decimal(*key, value);
            return;
        }
        let window: &mut [u8; KEY + Remembered::LONGEST] = self.window();
        *window.first_chunk_mut().expect("room") = key.block;
        let text: &mut [u8; Remembered::LONGEST] = (&mut window
            [key.len()..key.len() + Remembered::LONGEST])
            .try_into()
            .expect("room");
        *text = memory.text;
        self.advance(key.len() + usize::from(memory.len));
    }

    /// Appends `key` and `value` rounded to 1e-6, reusing the text of `memory` when the value
    /// is the same as last time.
    #[inline(always)]
    pub(crate) fn remembered(&mut self, key: impl Into<Key>, memory: &mut Remembered, value: f64) {
        let key = &key.into();
        let window: &mut [u8; KEY + GENERAL] = self.window();
        let bits = value.to_bits();
        if bits == memory.bits {
            *window.first_chunk_mut().expect("room") = key.block;
            let text: &mut [u8; Remembered::LONGEST] = (&mut window
                [key.len()..key.len() + Remembered::LONGEST])
                .try_into()
                .expect("room");
            *text = memory.text;
            self.advance(key.len() + usize::from(memory.len));
            return;
        }
        let len = match write_decimal(
            window.first_chunk_mut().expect("a field's room"),
            key,
            value,
        ) {
            Some(len) => {
                let number = &window[key.len()..];
                *memory = match u8::try_from(len - key.len()) {
                    Ok(len) if usize::from(len) <= Remembered::LONGEST => Remembered {
                        bits,
                        len,
                        text: *number.first_chunk().expect("room"),
                    },
                    _ => Remembered::default(),
                };
                len
            }
            None => {
                *memory = Remembered::default();
                key.len() + general(&mut window[key.len()..key.len() + GENERAL], value)
            }
        };
        self.advance(len);
    }

    /// Appends the text of the run `memory` holds if it was written from the values of
    /// `values` (their bits), and says whether it did. When it did not, the caller writes the
    /// fields after a [`RecordText::run_start`] and gives them to [`RecordText::remember_run`].
    /// (Two calls rather than one taking the writing as a closure: a closure is not always
    /// inlined, and the record's room would leave the registers.)
    #[inline(always)]
    pub(crate) fn reused(&mut self, memory: &RememberedRun, values: [u64; 2]) -> bool {
        if memory.values != Some(values) {
            return false;
        }
        *self.window() = memory.text;
        self.advance(usize::from(memory.len));
        true
    }

    /// Where a run of fields starts.
    #[inline(always)]
    pub(crate) fn run_start(&self) -> RunStart {
        RunStart(self.len)
    }

    /// Keeps in `memory` the text written since `start`, from the values of `values`.
    #[inline(always)]
    pub(crate) fn remember_run(
        &self,
        start: RunStart,
        memory: &mut RememberedRun,
        values: [u64; 2],
    ) {
        let start = start.0;
        *memory = match u8::try_from(self.len - start) {
            Ok(len) if usize::from(len) <= RememberedRun::LONGEST => {
                let start = start as usize;
                RememberedRun {
                    values: Some(values),
                    len,
                    text: self.room[start..start + RememberedRun::LONGEST]
                        .try_into()
                        .expect("a run's room"),
                }
            }
            _ => RememberedRun::default(),
        };
    }

    /// Appends `key` and an unsigned integer.
    #[inline(always)]
    pub(crate) fn unsigned(&mut self, key: impl Into<Key>, value: u64) {
        let key = &key.into();
        let window: &mut [u8; KEY + UNSIGNED] = self.window();
        // The digits overwrite the block of an empty key (a constant: the test is the
        // compiler's).
        if key.len != 0 {
            *window.first_chunk_mut().expect("room") = key.block;
        }
        let len = write_unsigned(&mut window[key.len()..key.len() + UNSIGNED], value);
        self.advance(key.len() + len);
    }
}

/// Copies the blocks of a padded text after its first to the start of `room`.
#[inline(never)]
fn copy_blocks(room: &mut [u8], blocks: &[u8]) {
    room[..blocks.len()].copy_from_slice(blocks);
}

/// Values [`write_decimal`] does not take, written at the start of `out` ([`GENERAL`] bytes):
/// `null` for NaN and infinities, else every digit. Returns the length.
#[inline(always)]
fn general(out: &mut [u8], value: f64) -> usize {
    // Never more than `GENERAL`: the minimum tells the compiler, which does not see the length
    // through the call, so that the fields after this one need no bounds check.
    write_general(out, value).min(GENERAL)
}

/// [`general`], out of line.
#[cold]
#[inline(never)]
fn write_general(out: &mut [u8], value: f64) -> usize {
    let text = if value.is_finite() {
        format!("{value}")
    } else {
        "null".to_string()
    };
    out[..text.len()].copy_from_slice(text.as_bytes());
    text.len()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn text(out: &OutBuffer) -> String {
        String::from_utf8(out.as_bytes().to_vec()).unwrap()
    }

    fn show(value: f64) -> String {
        let mut out = OutBuffer::new(64);
        out.record(0).decimal(Key::new(""), value);
        text(&out)
    }

    /// The text the trace has always given, made the plain way: `value` rounded half away from
    /// zero to a whole number of micrometres in floating point (as `write_decimal` does),
    /// then printed by `format!` with six decimals and trimmed.
    fn reference(value: f64) -> String {
        let scaled = value * 1e6;
        if scaled.is_nan() || scaled.abs() >= 9.0e15 {
            return if value.is_finite() {
                format!("{value}")
            } else {
                "null".to_string()
            };
        }
        let micro = if scaled >= 0.0 {
            (scaled + 0.5) as i64
        } else {
            (scaled - 0.5) as i64
        };
        let sign = if micro < 0 { "-" } else { "" };
        let micro = micro.unsigned_abs();
        let text = format!("{sign}{}.{:06}", micro / 1_000_000, micro % 1_000_000);
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    }

    #[test]
    fn decimals_are_trimmed_and_rounded() {
        assert_eq!(show(0.0), "0");
        assert_eq!(show(-0.0), "0");
        assert_eq!(show(-0.0000001), "0");
        assert_eq!(show(-0.0000005), "-0.000001");
        assert_eq!(show(12.5), "12.5");
        assert_eq!(show(-1.833), "-1.833");
        assert_eq!(show(72.80109889), "72.801099");
        assert_eq!(show(100.0), "100");
        assert_eq!(show(0.000001), "0.000001");
        assert_eq!(show(0.1), "0.1");
        assert_eq!(show(-0.25), "-0.25");
        assert_eq!(show(999999.9999996), "1000000");
        assert_eq!(show(-123456.5), "-123456.5");
        assert_eq!(show(1234567.000123), "1234567.000123");
        assert_eq!(show(-999999999.999999), "-999999999.999999");
        // Where the short path ends: a whole part of 999,999 and the first of a million.
        assert_eq!(show(999999.9999994), "999999.999999");
        assert_eq!(show(-999999.9999994), "-999999.999999");
        assert_eq!(show(999999.9999996), "1000000");
        assert_eq!(show(-1000000.0000004), "-1000000");
        assert_eq!(show(1000000.0000006), "1000000.000001");
        assert_eq!(show(4.9e-7), "0");
        assert_eq!(show(-4.9e-7), "0");
        assert_eq!(show(5.0e-7), reference(5.0e-7));
        assert_eq!(show(f64::MIN_POSITIVE), "0");
        assert_eq!(show(-f64::MIN_POSITIVE), "0");
        assert_eq!(show(8999999999.5), "8999999999.5");
        assert_eq!(show(1.0e10), "10000000000");
        assert_eq!(show(-1.0e300), format!("{}", -1.0e300));
        assert_eq!(show(f64::MAX), format!("{}", f64::MAX));
        assert_eq!(show(f64::NAN), "null");
        assert_eq!(show(f64::INFINITY), "null");
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
            assert_eq!(text, reference(value));
        }
    }

    #[test]
    fn every_six_digit_fraction_is_written_as_the_reference_writes_it() {
        for micro in 0..1_000_000 {
            for whole in [0.0, 7.0, -42.0] {
                let value = whole + f64::from(micro) * 1e-6;
                assert_eq!(show(value), reference(value), "{value}");
            }
        }
    }

    #[test]
    fn digits_of_every_number_below_a_million() {
        for value in 0..1_000_000u32 {
            let mut out = [0; 7];
            let len = write_below_million(&mut out, value);
            assert_eq!(&out[..len], value.to_string().as_bytes());
        }
    }

    proptest! {
        #[test]
        fn any_float_is_written_as_the_reference_writes_it(value in any::<f64>()) {
            prop_assert_eq!(show(value), reference(value));
        }

        #[test]
        fn machine_sized_values_are_written_as_the_reference_writes_it(
            value in -1.0e7..1.0e7f64,
        ) {
            prop_assert_eq!(show(value), reference(value));
        }

        #[test]
        fn halves_of_a_micrometre_round_as_the_reference_rounds_them(
            micro in -10_000_000_000_000i64..10_000_000_000_000,
            nudge in -2i64..=2,
        ) {
            // x.xxxxxx5 and its neighbouring floats: where rounding in floating point decides.
            let value = (micro as f64 + 0.5) / 1e6;
            let value = f64::from_bits((value.to_bits() as i64 + nudge) as u64);
            prop_assert_eq!(show(value), reference(value));
        }

        #[test]
        fn a_key_and_its_number_are_the_key_and_the_reference_text(
            value in prop_oneof![any::<f64>(), -2.0e6..2.0e6f64],
            key in 0usize..4,
            remember in any::<bool>(),
        ) {
            // The key's block carries the number's minus sign: keys of every length, constant
            // and made when the record is written, before numbers of both signs.
            let keys = [",\"x\":", ",", "", ",\"seconds\":_xxx"];
            let key = keys[key];
            let mut out = OutBuffer::new(64);
            let mut memory = Remembered::default();
            {
                let mut record = out.record(0);
                if remember {
                    record.remembered(Key::new(key), &mut memory, value);
                    record.remembered(key.as_bytes(), &mut memory, value);
                } else {
                    record.decimal(Key::new(key), value);
                    record.decimal(key.as_bytes(), value);
                }
            }
            let field = format!("{key}{}", reference(value));
            prop_assert_eq!(text(&out), format!("{field}{field}"));
        }

        #[test]
        fn a_number_written_as_a_remembered_one_is_its_reference_text(
            value in prop_oneof![any::<f64>(), -2.0e6..2.0e6f64],
            other in prop_oneof![any::<f64>(), -2.0e6..2.0e6f64],
            same in any::<bool>(),
        ) {
            // The memory holds the text of the value or of another; it is copied only in the
            // first case, and stays as it was in both.
            let mut out = OutBuffer::new(64);
            let mut memory = Remembered::default();
            out.record(0).remembered(Key::new(""), &mut memory, if same { value } else { other });
            out.clear();
            let before = (memory.bits, memory.len, memory.text);
            out.record(0).decimal_as(Key::new(",\"cz\":"), &memory, value);
            prop_assert_eq!(text(&out), format!(",\"cz\":{}", reference(value)));
            prop_assert_eq!((memory.bits, memory.len, memory.text), before);
        }

        #[test]
        fn unsigned_integers_have_every_digit(value in any::<u64>()) {
            let mut out = OutBuffer::new(64);
            out.record(0).unsigned(Key::new(""), value);
            prop_assert_eq!(text(&out), value.to_string());
        }
    }

    #[test]
    fn unsigned_integers_of_every_length_have_every_digit() {
        let mut value = 1u64;
        for _ in 0..20 {
            for n in [value - 1, value, value + 1, value.saturating_mul(9)] {
                let mut out = OutBuffer::new(64);
                out.record(0).unsigned(Key::new(",\"n\":"), n);
                assert_eq!(text(&out), format!(",\"n\":{n}"));
            }
            value = value.saturating_mul(10);
        }
        let mut out = OutBuffer::new(64);
        out.record(0).unsigned(Key::new(""), u64::MAX);
        assert_eq!(text(&out), u64::MAX.to_string());
    }

    #[test]
    fn remembered_text_follows_the_value() {
        let mut out = OutBuffer::new(64);
        let mut memory = Remembered::default();
        {
            let mut record = out.record(0);
            for value in [
                1.5,
                1.5,
                -2.0,
                -2.0,
                0.0,
                f64::NAN,
                f64::NAN,
                0.0,
                3.25,
                1e20,
                1e20,
                0.0,
                -8999999999.123456,
                -8999999999.123456,
                -0.0,
            ] {
                record.remembered(Key::new(" "), &mut memory, value);
            }
        }
        assert_eq!(
            text(&out),
            " 1.5 1.5 -2 -2 0 null null 0 3.25 100000000000000000000 100000000000000000000 0 \
             -8999999999.123456 -8999999999.123456 0"
        );
    }

    #[test]
    fn a_remembered_run_is_the_text_of_its_fields() {
        let mut out = OutBuffer::new(64);
        let mut expected = String::new();
        let mut run = RememberedRun::default();
        let mut memory = [Remembered::default(); 2];
        for (z, f) in [
            (1.5, 1500.0),
            (1.5, 1500.0),
            (-2.25, 1500.0),
            (-2.25, 1500.0),
            (-2.25, 800.0),
            (1.0e20, 1.0),
            (1.0e20, 1.0),
            (-1.0e300, 1.0),
            (-1.0e300, 1.0),
            (f64::NAN, 2.0),
            (f64::NAN, 2.0),
            (0.0, 2.0),
            (-0.0, 2.0),
        ] {
            let values = [f64::to_bits(z), f64::to_bits(f)];
            let mut record = out.record(0);
            if !record.reused(&run, values) {
                let start = record.run_start();
                record.remembered(Key::new(",\"z\":"), &mut memory[0], z);
                record.remembered(Key::new(",\"f\":"), &mut memory[1], f);
                record.put(b"}\n");
                record.remember_run(start, &mut run, values);
            }
            expected += &format!(",\"z\":{},\"f\":{}}}\n", reference(z), reference(f));
        }
        assert_eq!(text(&out), expected);
    }

    #[test]
    fn texts_are_joined_in_order() {
        let mut out = OutBuffer::new(64);
        const HEAD: FixedText = FixedText::join(&["{\"kind\":\"", "tool_select", "\",\"line\":"]);
        assert_eq!(HEAD.as_bytes(), b"{\"kind\":\"tool_select\",\"line\":");
        for name in ["", "a.nc", "/a/rather/long/path/to/a/program/file.nc"] {
            let file = PaddedText::new(name.as_bytes());
            let mut record = out.record(file.room());
            record.fixed(&HEAD);
            record.unsigned(Key::new(""), 12);
            record.padded(&file);
            record.byte(b'|');
            record.put(b"}\n");
        }
        assert_eq!(
            text(&out),
            "{\"kind\":\"tool_select\",\"line\":12|}\n\
             {\"kind\":\"tool_select\",\"line\":12a.nc|}\n\
             {\"kind\":\"tool_select\",\"line\":12/a/rather/long/path/to/a/program/file.nc|}\n"
        );
    }

    #[test]
    fn long_pieces_grow_the_buffer_and_keep_the_slack() {
        let mut out = OutBuffer::new(16);
        let long = vec![b'a'; 3 * SLACK];
        out.put(&long);
        let name = PaddedText::new(&long);
        {
            let mut record = out.record(name.room());
            record.padded(&name);
            record.decimal(Key::new(""), -1.25);
            record.unsigned(Key::new(""), 42);
            for _ in 0..16 {
                record.decimal(Key::new(",\"seconds\":"), -f64::MAX);
            }
        }
        assert!(out.is_full());
        let general = format!(",\"seconds\":{}", -f64::MAX);
        assert_eq!(general.len(), 11 + GENERAL);
        assert_eq!(out.as_bytes().len(), 6 * SLACK + 5 + 2 + 16 * general.len());
        assert!(out.as_bytes()[..6 * SLACK + 7].ends_with(b"a-1.2542"));
        assert!(out.as_bytes().ends_with(general.as_bytes()));
    }
}
