//! What a program's text says about the control it was written for, read beside the run: the
//! clues that a program meant for another profile, or for whole-unit input, would otherwise run
//! to a wrong result that ends "ok".
//!
//! [`ProgramScan`] reads the text once and keeps only counts and a few first places: sequence
//! numbers, `M97 P_` calls, system variable numbers, dialect marks (`%@MACRO`, `:` program
//! numbers), the numbers without a decimal point in length words, the unit codes and sizes in
//! inches in comments (`words.rs` reads a line). [`ProgramScan::warnings`] weighs them against
//! the machine's profile (`warnings.rs`) and gives at most one warning per kind of finding:
//! V100 written for another profile, V101 lengths a thousandth of their size, V104 an inch
//! program run in mm ([`AlarmCode`](crate::AlarmCode)). It asks the profiles questions (does
//! M97 call a sequence number? is #3026 a variable?), never which controller they are. The
//! scan never raises an error, never changes how the program runs, and its memory does not
//! grow with the program's length.

mod warnings;
mod words;

use crate::alarm::Alarm;
use crate::machine::Machine;
use crate::profile::Profile;
use crate::source::{FileId, Span};
use crate::summary::LengthUnit;
use std::collections::BTreeMap;
use std::io::{self, BufRead};
use words::{inch_size_in_comment, words_of, Word};

/// Bytes of a line that are looked at: the rest of a longer line is read past, unscanned.
const LINE_CAP: usize = 4096;
/// Sequence numbers N1 to N99999 are kept for `M97 P_`, a bit each (Haas's range).
const SEQUENCE_BITS: usize = 100_000;
/// Distinct system variables and `M97` targets remembered.
const KEPT: usize = 32;
/// A length without a decimal point that comes out under this many mm read in increments is
/// taken for a whole-unit value: the lengths of a program written in increments are thousands.
const SMALL_MM: f64 = 1.0;

/// One place in the text: its span and the word as written.
#[derive(Clone, Debug, PartialEq)]
struct Place {
    span: Span,
    text: String,
}

/// The numbers without a decimal point in length words of one unit mode.
#[derive(Clone, Debug, Default, PartialEq)]
struct DecimalLessWords {
    /// Words with a non-zero number and no decimal point.
    count: u64,
    /// The largest such number, as written.
    largest: u64,
    /// The smallest such number, and where it is.
    smallest: Option<(u64, Place)>,
    /// The first such number, and where it is.
    first: Option<(u64, Place)>,
}

impl DecimalLessWords {
    /// True when `value` would be the first or the new smallest (its place is then worth
    /// making).
    fn keeps(&self, value: u64) -> bool {
        self.smallest.as_ref().is_none_or(|(v, _)| value < *v)
    }

    fn add(&mut self, value: u64, place: Option<Place>) {
        self.count += 1;
        self.largest = self.largest.max(value);
        if let Some(place) = place {
            if self.first.is_none() {
                self.first = Some((value, place.clone()));
            }
            self.smallest = Some((value, place));
        }
    }
}

/// The unit mode a length word was written in, as far as the text says.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Units {
    /// Before any G20 or G21: the profile's power-on units.
    PowerOn = 0,
    /// After G21.
    Millimetre = 1,
    /// After G20.
    Inch = 2,
}

/// The length words of a program (X Y Z I J outside G04, G10, G65 and G66 blocks).
#[derive(Clone, Debug, Default)]
struct Lengths {
    /// Those without a decimal point, by unit mode, indexed by [`Units`].
    decimal_less: [DecimalLessWords; 3],
    /// Those with a decimal point.
    decimal_point_words: u64,
    /// The largest of them, in the units written.
    largest_decimal_point: f64,
}

/// What the text says of its unit.
#[derive(Clone, Debug)]
struct UnitMarks {
    /// The mode in force at the line being read.
    current: Units,
    /// The units of the first G20 or G21.
    first: Option<Units>,
    /// A G70 or G71 (units on Syntec).
    g70_or_g71: bool,
    /// The first comment that gives a size in inches (`1/2" END MILL`, `3/8IN DRILL`).
    inch_comment: Option<Place>,
}

/// The line being read: its number, the offset of its first byte, its first bytes (at most
/// [`LINE_CAP`]) and its whole length.
#[derive(Clone, Debug)]
struct LineBuffer {
    number: u32,
    offset: u64,
    bytes: Vec<u8>,
    length: u64,
    /// The last byte was a `\r` that ended a line: a `\n` right after it is the same line end.
    after_cr: bool,
}

/// What a program's text shows of the control it was written for (see the module doc).
#[derive(Clone, Debug)]
pub struct ProgramScan {
    file: FileId,
    /// Sequence numbers N1 to N99999 present, a bit each.
    sequences: Vec<u64>,
    /// `M97 P_` calls: the first place of each target.
    m97_targets: BTreeMap<u32, Place>,
    /// System variables (#1000 up): the first place of each.
    variables: BTreeMap<u32, Place>,
    /// A Syntec `%@MACRO` header.
    syntec_macro: Option<Place>,
    /// A `:1234` program number (FANUC 0M tapes).
    colon_number: Option<Place>,
    /// The first G41 or G42 block with H and no D (`G42 H19`, FANUC 0M's radius by H).
    radius_by_h: Option<Place>,
    /// The length words, with and without a decimal point.
    lengths: Lengths,
    /// The unit codes and the inch sizes in comments.
    units: UnitMarks,
    /// The line being read.
    line: LineBuffer,
    /// The words of the line being read, kept from line to line.
    words: Vec<Word>,
    variable_words: Vec<(u32, usize, usize)>,
}

impl ProgramScan {
    /// An empty scan of file `file`, to [`add`](ProgramScan::add) the text to.
    pub fn new(file: FileId) -> ProgramScan {
        ProgramScan {
            file,
            sequences: vec![0; SEQUENCE_BITS.div_ceil(64)],
            m97_targets: BTreeMap::new(),
            variables: BTreeMap::new(),
            syntec_macro: None,
            colon_number: None,
            radius_by_h: None,
            lengths: Lengths::default(),
            units: UnitMarks {
                current: Units::PowerOn,
                first: None,
                g70_or_g71: false,
                inch_comment: None,
            },
            line: LineBuffer {
                number: 1,
                offset: 0,
                bytes: Vec::new(),
                length: 0,
                after_cr: false,
            },
            words: Vec::new(),
            variable_words: Vec::new(),
        }
    }

    /// The scan of a program held in memory, as file 0.
    pub fn of_text(text: &[u8]) -> ProgramScan {
        let mut scan = ProgramScan::new(FileId(0));
        scan.add(text);
        scan.finish();
        scan
    }

    /// The scan of the program `reader` gives, as file `file`.
    ///
    /// # Errors
    /// Whatever the reader reports.
    pub fn of_reader(mut reader: impl BufRead, file: FileId) -> io::Result<ProgramScan> {
        let mut scan = ProgramScan::new(file);
        loop {
            let chunk = match reader.fill_buf() {
                Ok(chunk) => chunk,
                Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
                Err(e) => return Err(e),
            };
            if chunk.is_empty() {
                break;
            }
            let n = chunk.len();
            scan.add(chunk);
            reader.consume(n);
        }
        scan.finish();
        Ok(scan)
    }

    /// The scan of the ISO program file at `path`, as file 0; `None` when it is not a regular
    /// file (a pipe can be read once only, and the run reads it) or not an ISO program (the
    /// clues here are ISO's).
    ///
    /// # Errors
    /// Whatever the file system reports.
    pub fn of_file(path: &std::path::Path) -> io::Result<Option<ProgramScan>> {
        use std::io::Read;
        if !std::fs::metadata(path)?.is_file() {
            return Ok(None);
        }
        let mut file = std::fs::File::open(path)?;
        let mut head = Vec::new();
        file.by_ref().take(4096).read_to_end(&mut head)?;
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        if crate::syntax::detect_dialect(&name, &head) != crate::syntax::Dialect::Iso {
            return Ok(None);
        }
        let rest = io::BufReader::with_capacity(256 * 1024, io::Cursor::new(head).chain(file));
        ProgramScan::of_reader(rest, FileId(0)).map(Some)
    }

    /// Reads the next bytes of the text. A line ends at `\n`, `\r\n` or a lone `\r`.
    pub fn add(&mut self, mut bytes: &[u8]) {
        while let Some(&first) = bytes.first() {
            if std::mem::take(&mut self.line.after_cr) && first == b'\n' {
                // The `\n` of a `\r\n` whose `\r` ended the line.
                self.line.offset += 1;
                bytes = &bytes[1..];
                continue;
            }
            let end = bytes.iter().position(|&b| b == b'\n' || b == b'\r');
            let piece = &bytes[..end.unwrap_or(bytes.len())];
            let room = LINE_CAP.saturating_sub(self.line.bytes.len());
            self.line
                .bytes
                .extend_from_slice(&piece[..piece.len().min(room)]);
            self.line.length += piece.len() as u64;
            let Some(end) = end else { break };
            self.line.after_cr = bytes[end] == b'\r';
            self.end_line();
            bytes = &bytes[end + 1..];
        }
    }

    /// Ends the text: a last line without a line end is read too.
    pub fn finish(&mut self) {
        if self.line.length > 0 {
            self.scan_line();
        }
    }

    fn end_line(&mut self) {
        self.scan_line();
        self.line.number = self.line.number.saturating_add(1);
        self.line.offset += self.line.length + 1;
        self.line.bytes.clear();
        self.line.length = 0;
    }

    /// The place of bytes `start..end` of the line being read.
    fn place(&self, start: usize, end: usize) -> Place {
        let at = |i: usize| u32::try_from(self.line.offset + i as u64).unwrap_or(u32::MAX);
        Place {
            span: Span::new(self.file, self.line.number, at(start)..at(end)),
            text: String::from_utf8_lossy(&self.line.bytes[start..end]).into_owned(),
        }
    }

    fn scan_line(&mut self) {
        let trimmed = self.line.bytes.trim_ascii_start();
        let indent = self.line.bytes.len() - trimmed.len();
        if self.syntec_macro.is_none()
            && trimmed.len() >= 7
            && trimmed[..7].eq_ignore_ascii_case(b"%@MACRO")
        {
            self.syntec_macro = Some(self.place(indent, indent + 7));
        }
        if self.colon_number.is_none()
            && trimmed.first() == Some(&b':')
            && trimmed.get(1).is_some_and(u8::is_ascii_digit)
        {
            let digits = trimmed[1..]
                .iter()
                .take_while(|b| b.is_ascii_digit())
                .count();
            self.colon_number = Some(self.place(indent, indent + 1 + digits));
        }
        if self.units.inch_comment.is_none() && self.line.bytes.contains(&b'(') {
            self.units.inch_comment =
                inch_size_in_comment(&self.line.bytes).map(|(a, b)| self.place(a, b));
        }
        let (mut words, mut variables) = (
            std::mem::take(&mut self.words),
            std::mem::take(&mut self.variable_words),
        );
        words_of(&self.line.bytes, &mut words, &mut variables);
        for &(number, start, end) in &variables {
            if number >= 1000
                && self.variables.len() < KEPT
                && !self.variables.contains_key(&number)
            {
                let place = self.place(start, end);
                self.variables.insert(number, place);
            }
        }
        self.read_words(&words);
        (self.words, self.variable_words) = (words, variables);
    }

    fn read_words(&mut self, words: &[Word]) {
        // One pass for the codes; a second over the lengths, once the line's G20/G21 is known.
        let (mut m97, mut p, mut compensation, mut h) = (None, None, None, None);
        let (mut d, mut data) = (false, false);
        for word in words {
            match (word.letter, word.fraction) {
                (b'G', false) => match word.whole {
                    20 => {
                        self.units.current = Units::Inch;
                        self.units.first.get_or_insert(Units::Inch);
                    }
                    21 => {
                        self.units.current = Units::Millimetre;
                        self.units.first.get_or_insert(Units::Millimetre);
                    }
                    70 | 71 => self.units.g70_or_g71 = true,
                    41 | 42 => {
                        compensation.get_or_insert(word);
                    }
                    // X of G04 is a time; the words of G10, G65 and G66 are data and arguments.
                    4 | 10 | 65 | 66 => data = true,
                    _ => {}
                },
                (b'N', false) if word.whole < SEQUENCE_BITS as u64 => {
                    let n = word.whole as usize;
                    self.sequences[n / 64] |= 1 << (n % 64);
                }
                (b'M', false) if word.whole == 97 => {
                    m97.get_or_insert(word);
                }
                (b'P', false) => {
                    p.get_or_insert(word);
                }
                (b'H', _) => {
                    h.get_or_insert(word);
                }
                (b'D', _) => d = true,
                _ => {}
            }
        }
        if let (Some(m97), Some(p)) = (m97, p) {
            if let Ok(number) = u32::try_from(p.whole) {
                if self.m97_targets.len() < KEPT && !self.m97_targets.contains_key(&number) {
                    let place = self.place(m97.start.min(p.start), m97.end.max(p.end));
                    self.m97_targets.insert(number, place);
                }
            }
        }
        if self.radius_by_h.is_none() && !d {
            if let (Some(g), Some(h)) = (compensation, h) {
                let start = g.start.min(h.start);
                self.radius_by_h = Some(self.place(start, h.end.max(start)));
            }
        }
        if data {
            return;
        }
        for word in words.iter().filter(|w| b"XYZIJ".contains(&w.letter)) {
            if word.decimal_point {
                self.lengths.decimal_point_words += 1;
                // Converted only when it may be the largest: most words are not.
                if word.whole as f64 + 1.0 > self.lengths.largest_decimal_point {
                    let value = word.whole as f64 + word.after as f64 / word.scale as f64;
                    self.lengths.largest_decimal_point =
                        self.lengths.largest_decimal_point.max(value);
                }
            } else if word.whole > 0 {
                let units = self.units.current as usize;
                let place = self.lengths.decimal_less[units]
                    .keeps(word.whole)
                    .then(|| self.place(word.start, word.end));
                self.lengths.decimal_less[units].add(word.whole, place);
            }
        }
    }

    /// The sequence number `n` is in the program.
    fn has_sequence(&self, n: u32) -> bool {
        let n = n as usize;
        n < SEQUENCE_BITS && self.sequences[n / 64] & (1 << (n % 64)) != 0
    }

    /// The unit the program is written in: its first G20 or G21, else the profile's power-on
    /// unit.
    pub fn program_unit(&self, profile: &Profile) -> LengthUnit {
        match self.units.first {
            Some(Units::Inch) => LengthUnit::Inch,
            Some(_) => LengthUnit::Millimetre,
            None => power_on_unit(profile),
        }
    }

    /// The warnings this program's text gives on `machine`: a program that looks written for
    /// another of vcnc's profiles (V100), lengths without a decimal point that make the part a
    /// thousandth of its size (V101), an inch program without G20 on a profile that starts in
    /// mm (V104).
    pub fn warnings(&self, machine: &Machine) -> Vec<Alarm> {
        self.profile_warning(machine)
            .into_iter()
            .chain(self.decimal_less_warning(&machine.profile))
            .chain(self.unit_warning(&machine.profile))
            .collect()
    }
}

/// The unit `profile` starts in (G20 or G21 at power-on).
pub fn power_on_unit(profile: &Profile) -> LengthUnit {
    if profile.power_on.units == 200 {
        LengthUnit::Inch
    } else {
        LengthUnit::Millimetre
    }
}

#[cfg(test)]
mod tests;
