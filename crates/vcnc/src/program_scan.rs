//! What a program's text says about the control it was written for, read beside the run: the
//! clues that a program meant for another profile, or for whole-unit input, would otherwise run
//! to a wrong result that ends "ok".
//!
//! [`ProgramScan`] reads the text once and keeps only counts and a few first places: sequence
//! numbers, `M97 P_` calls, system variable numbers, dialect marks (`%@MACRO`, `:` program
//! numbers) and the numbers without a decimal point in length words. [`ProgramScan::warnings`]
//! weighs them against the machine's profile and gives at most one warning per kind of finding
//! ([`AlarmCode::WrittenForAnotherProfile`], [`AlarmCode::DecimalLessScale`]). It asks the
//! profiles questions (does M97 call a sequence number? is #3026 a variable?), never which
//! controller they are. The scan never raises an error, never changes how the program runs,
//! and its memory does not grow with the program's length.

use crate::alarm::{Alarm, AlarmCode};
use crate::machine::Machine;
use crate::profile::{DecimalLess, Profile, ProfileName};
use crate::source::{FileId, Span};
use crate::summary::LengthUnit;
use crate::Options;
use std::collections::BTreeMap;
use std::io::{self, BufRead};

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
    /// Decimal-less lengths by unit mode, indexed by [`Units`].
    decimal_less: [DecimalLessWords; 3],
    /// Length words written with a decimal point.
    decimal_point_words: u64,
    /// The largest of them, in the units written.
    largest_decimal_point: f64,
    units: Units,
    /// The units of the first G20 or G21.
    first_units: Option<Units>,
    /// A G70 or G71 (units on Syntec).
    g70_or_g71: bool,
    /// The first comment that gives a size in inches (`1/2" END MILL`, `3/8IN DRILL`).
    inch_comment: Option<Place>,
    /// The line being read: its number, the offset of its first byte, its first bytes (at most
    /// [`LINE_CAP`]) and its length.
    line_number: u32,
    line_offset: u64,
    line: Vec<u8>,
    line_length: u64,
    /// The last byte was a `\r` that ended a line: a `\n` right after it is the same line end.
    after_cr: bool,
    /// The words of the line being read, kept from line to line.
    words: Vec<Word>,
    variable_words: Vec<(u32, usize, usize)>,
}

/// One address word of a line.
#[derive(Clone, Copy, Debug)]
struct Word {
    letter: u8,
    /// The whole part of the number (saturating).
    whole: u64,
    /// The digits after the point as an integer over `scale` (enough for a magnitude).
    after: u64,
    scale: u64,
    /// Digits after the decimal point, not all zero.
    fraction: bool,
    decimal_point: bool,
    /// Its bytes in the line.
    start: usize,
    end: usize,
}

impl Word {
    /// `G04`, `M97`: the letter with this whole number.
    fn is(&self, letter: u8, number: u64) -> bool {
        self.letter == letter && !self.fraction && self.whole == number
    }
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
            decimal_less: Default::default(),
            decimal_point_words: 0,
            largest_decimal_point: 0.0,
            units: Units::PowerOn,
            first_units: None,
            g70_or_g71: false,
            inch_comment: None,
            line_number: 1,
            line_offset: 0,
            line: Vec::new(),
            line_length: 0,
            after_cr: false,
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
            if std::mem::take(&mut self.after_cr) && first == b'\n' {
                // The `\n` of a `\r\n` whose `\r` ended the line.
                self.line_offset += 1;
                bytes = &bytes[1..];
                continue;
            }
            let end = bytes.iter().position(|&b| b == b'\n' || b == b'\r');
            let piece = &bytes[..end.unwrap_or(bytes.len())];
            let room = LINE_CAP.saturating_sub(self.line.len());
            self.line.extend_from_slice(&piece[..piece.len().min(room)]);
            self.line_length += piece.len() as u64;
            let Some(end) = end else { break };
            self.after_cr = bytes[end] == b'\r';
            self.end_line();
            bytes = &bytes[end + 1..];
        }
    }

    /// Ends the text: a last line without a line end is read too.
    pub fn finish(&mut self) {
        if self.line_length > 0 {
            self.scan_line();
        }
    }

    fn end_line(&mut self) {
        self.scan_line();
        self.line_number = self.line_number.saturating_add(1);
        self.line_offset += self.line_length + 1;
        self.line.clear();
        self.line_length = 0;
    }

    /// The place of bytes `start..end` of the line being read.
    fn place(&self, start: usize, end: usize) -> Place {
        let at = |i: usize| u32::try_from(self.line_offset + i as u64).unwrap_or(u32::MAX);
        Place {
            span: Span::new(self.file, self.line_number, at(start)..at(end)),
            text: String::from_utf8_lossy(&self.line[start..end]).into_owned(),
        }
    }

    fn scan_line(&mut self) {
        let trimmed = self.line.trim_ascii_start();
        let indent = self.line.len() - trimmed.len();
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
        if self.inch_comment.is_none() && self.line.contains(&b'(') {
            self.inch_comment = inch_size_in_comment(&self.line).map(|(a, b)| self.place(a, b));
        }
        let (mut words, mut variables) = (
            std::mem::take(&mut self.words),
            std::mem::take(&mut self.variable_words),
        );
        words_of(&self.line, &mut words, &mut variables);
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
        for word in words {
            if word.is(b'G', 20) {
                self.units = Units::Inch;
                self.first_units.get_or_insert(Units::Inch);
            } else if word.is(b'G', 21) {
                self.units = Units::Millimetre;
                self.first_units.get_or_insert(Units::Millimetre);
            } else if word.is(b'G', 70) || word.is(b'G', 71) {
                self.g70_or_g71 = true;
            } else if word.letter == b'N' && !word.fraction && word.whole < SEQUENCE_BITS as u64 {
                let n = word.whole as usize;
                self.sequences[n / 64] |= 1 << (n % 64);
            }
        }
        if let Some(m97) = words.iter().find(|w| w.is(b'M', 97)) {
            let target = words.iter().find(|w| w.letter == b'P' && !w.fraction);
            if let Some(p) = target.and_then(|p| u32::try_from(p.whole).ok().map(|n| (n, p))) {
                let (number, p) = p;
                if self.m97_targets.len() < KEPT && !self.m97_targets.contains_key(&number) {
                    let place = self.place(m97.start.min(p.start), m97.end.max(p.end));
                    self.m97_targets.insert(number, place);
                }
            }
        }
        // X of G04 is a time; the words of G10, G65 and G66 are data and arguments.
        let data = words
            .iter()
            .any(|w| w.is(b'G', 4) || w.is(b'G', 10) || w.is(b'G', 65) || w.is(b'G', 66));
        if data {
            return;
        }
        for word in words.iter().filter(|w| b"XYZIJ".contains(&w.letter)) {
            if word.decimal_point {
                self.decimal_point_words += 1;
                // Converted only when it may be the largest: most words are not.
                if word.whole as f64 + 1.0 > self.largest_decimal_point {
                    let value = word.whole as f64 + word.after as f64 / word.scale as f64;
                    self.largest_decimal_point = self.largest_decimal_point.max(value);
                }
            } else if word.whole > 0 {
                let units = self.units as usize;
                let place = self.decimal_less[units]
                    .keeps(word.whole)
                    .then(|| self.place(word.start, word.end));
                self.decimal_less[units].add(word.whole, place);
            }
        }
    }

    /// The unit the program is written in: its first G20 or G21, else the profile's power-on
    /// unit.
    pub fn program_unit(&self, profile: &Profile) -> LengthUnit {
        match self.first_units {
            Some(Units::Inch) => LengthUnit::Inch,
            Some(_) => LengthUnit::Millimetre,
            None => power_on_unit(profile),
        }
    }

    /// The warnings this program's text gives on `machine`: a program that looks written for
    /// another of vcnc's profiles, and lengths without a decimal point that make the part a
    /// thousandth of its size.
    pub fn warnings(&self, machine: &Machine) -> Vec<Alarm> {
        self.profile_warning(machine)
            .into_iter()
            .chain(self.decimal_less_warning(&machine.profile))
            .chain(self.unit_warning(&machine.profile))
            .collect()
    }

    /// One warning when a program that never selects its unit, on a profile that starts in
    /// mm, gives its sizes in inches in its comments: a shop whose control starts in inches
    /// (Haas setting 9) writes no G20, and the part would come out 25.4 times too small.
    fn unit_warning(&self, profile: &Profile) -> Option<Alarm> {
        let selected = self.first_units.is_some() || (self.g70_or_g71 && profile.g70_g71_units);
        if selected || power_on_unit(profile) != LengthUnit::Millimetre {
            return None;
        }
        let place = self.inch_comment.as_ref()?;
        Some(
            Alarm::warning(
                AlarmCode::UnitNotSelected,
                place.span,
                format!(
                    "the program never selects its unit (no G20 or G21) and its comments give sizes in inches (`{}`): the {} profile starts in mm, so the part comes out 25.4 times too small if it is meant in inches",
                    place.text,
                    profile.name.as_str()
                ),
            )
            .with_help("if it is, add G20 at its start (the control it was written for starts in inches)"),
        )
    }
}

/// The first size in inches inside a comment of `line`: a number written against `IN`,
/// `INCH` or `"` (`1IN`, `3/8IN`, `.238"`), or a fraction before them (`1/4 IN`). Prose such
/// as `Z-5 in G54` is none. Returns its bytes.
fn inch_size_in_comment(line: &[u8]) -> Option<(usize, usize)> {
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
fn words_of(line: &[u8], words: &mut Vec<Word>, variables: &mut Vec<(u32, usize, usize)>) {
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
            b'G' | b'M' | b'N' | b'P' | b'X' | b'Y' | b'Z' | b'I' | b'J'
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

/// One clue that the program was written for other profiles: where, what it says, and the
/// profiles on which it makes sense.
struct Clue {
    place: Place,
    says: String,
    fits: Vec<ProfileName>,
}

impl ProgramScan {
    /// The sequence number `n` is in the program.
    fn has_sequence(&self, n: u32) -> bool {
        let n = n as usize;
        n < SEQUENCE_BITS && self.sequences[n / 64] & (1 << (n % 64)) != 0
    }

    /// What in the text runs wrong on `machine`'s profile and right on another of vcnc's.
    fn clues(&self, machine: &Machine) -> Vec<Clue> {
        let profile = &machine.profile;
        let here = profile.name.as_str();
        let mut clues = Vec::new();
        let local_calls: Vec<ProfileName> = ProfileName::ALL
            .into_iter()
            .filter(|&n| Profile::builtin(n).m97_local_subprogram)
            .collect();
        if !profile.m97_local_subprogram {
            let called = self
                .m97_targets
                .iter()
                .find(|(n, _)| self.has_sequence(**n));
            if let Some((n, place)) = called {
                let instead = if profile.subprogram_m_codes.contains(&97) {
                    "reads M97 as another code"
                } else {
                    "passes M97 to the machine as an M code"
                };
                clues.push(Clue {
                    says: format!(
                        "`{}` (line {}) calls N{n} of this program on {}, but {here} {instead} and never runs N{n}",
                        place.text,
                        place.span.line,
                        names(&local_calls)
                    ),
                    place: place.clone(),
                    fits: local_calls.clone(),
                });
            }
        }
        for (&number, place) in &self.variables {
            if has_variable(machine, number) {
                continue;
            }
            let fits: Vec<ProfileName> = ProfileName::ALL
                .into_iter()
                .filter(|&n| n != profile.name)
                .filter(|&n| {
                    machine
                        .clone()
                        .with_profile(n)
                        .is_ok_and(|m| has_variable(&m, number))
                })
                .collect();
            if !fits.is_empty() {
                clues.push(Clue {
                    says: format!(
                        "#{number} (line {}) is a variable of {}, not of {here}",
                        place.span.line,
                        names(&fits)
                    ),
                    place: place.clone(),
                    fits,
                });
            }
        }
        clues.sort_by_key(|c| c.place.span.start);
        clues
    }

    /// One warning naming the profile the program looks written for, when the text holds
    /// something that runs wrong on this machine's profile and right on that one.
    fn profile_warning(&self, machine: &Machine) -> Option<Alarm> {
        let clues = self.clues(machine);
        // Dialect marks only back up a real clue: on their own they change nothing in the run.
        let marks = [
            (self.syntec_macro.as_ref(), ProfileName::Syntec),
            (self.colon_number.as_ref(), ProfileName::Fanuc0m),
        ];
        let score = |name: ProfileName| {
            let fitting = clues.iter().filter(|c| c.fits.contains(&name)).count();
            let marked = marks
                .iter()
                .filter(|(m, n)| m.is_some() && *n == name)
                .count();
            2 * fitting + marked
        };
        let best = ProfileName::ALL
            .into_iter()
            .filter(|&n| clues.iter().any(|c| c.fits.contains(&n)))
            .max_by_key(|&n| (score(n), std::cmp::Reverse(n as u8)))?;
        let fitting: Vec<&Clue> = clues.iter().filter(|c| c.fits.contains(&best)).collect();
        let mut says: Vec<String> = fitting.iter().map(|c| c.says.clone()).collect();
        for (mark, name) in marks {
            if let (Some(mark), true) = (mark, name == best) {
                says.push(format!(
                    "`{}` (line {}) is {}'s",
                    mark.text,
                    mark.span.line,
                    best.as_str()
                ));
            }
        }
        let mut alarm = Alarm::warning(
            AlarmCode::WrittenForAnotherProfile,
            fitting[0].place.span,
            format!(
                "this program looks written for the {} profile, not {}: {}",
                best.as_str(),
                machine.profile.name.as_str(),
                says.join("; ")
            ),
        )
        .with_help(format!(
            "run it with `--profile {0}`, or set `profile = \"{0}\"` in the machine file",
            best.as_str()
        ));
        for clue in &fitting[1..] {
            alarm = alarm.with_label(clue.place.span, clue.says.clone());
        }
        Some(alarm)
    }

    /// One warning when the lengths written without a decimal point come out under a
    /// millimetre: all of them in a program that never writes a decimal point, any of them in
    /// one that also does (a post that drops `.0`, a forgotten point).
    fn decimal_less_warning(&self, profile: &Profile) -> Option<Alarm> {
        if profile.decimal_less != DecimalLess::Increments {
            return None;
        }
        let power_on_inch = power_on_unit(profile) == LengthUnit::Inch;
        let increment_mm = |units: usize| {
            let inch = units == Units::Inch as usize || (units == 0 && power_on_inch);
            if inch {
                profile.increment_inch * 25.4
            } else {
                profile.increment_mm
            }
        };
        let buckets = self
            .decimal_less
            .iter()
            .enumerate()
            .filter(|(_, b)| b.count > 0);
        let count: u64 = self.decimal_less.iter().map(|b| b.count).sum();
        let suspicious = if self.decimal_point_words == 0 {
            count > 0
                && buckets
                    .clone()
                    .all(|(u, b)| b.largest as f64 * increment_mm(u) < SMALL_MM)
        } else {
            buckets.clone().any(|(u, b)| {
                b.smallest
                    .as_ref()
                    .is_some_and(|(v, _)| *v as f64 * increment_mm(u) < SMALL_MM)
            })
        };
        if !suspicious {
            return None;
        }
        // The first small word shows where the run goes wrong; else the smallest.
        let small = |u: usize, (v, _): &(u64, Place)| *v as f64 * increment_mm(u) < SMALL_MM;
        let (units, (value, place)) = buckets
            .clone()
            .find_map(|(u, b)| b.first.as_ref().filter(|f| small(u, f)).map(|f| (u, f)))
            .or_else(|| {
                buckets
                    .filter_map(|(u, b)| b.smallest.as_ref().map(|s| (u, s)))
                    .find(|(u, s)| small(*u, s))
            })?;
        let read_mm = *value as f64 * increment_mm(units);
        let read = if increment_mm(units) == profile.increment_mm {
            format!("{read_mm:.4} mm")
        } else {
            format!("{:.4} inch ({read_mm:.4} mm)", read_mm / 25.4)
        };
        let lengths = |n: u64| {
            if n == 1 {
                "1 length".to_string()
            } else {
                format!("{n} lengths")
            }
        };
        let others = if self.decimal_point_words == 0 {
            format!(
                "{} in this program, none with a decimal point, all come out under {SMALL_MM} mm so",
                lengths(count)
            )
        } else {
            format!(
                "{} in this program without a decimal point, beside {} with one (up to {})",
                lengths(count),
                self.decimal_point_words,
                self.largest_decimal_point
            )
        };
        Some(
            Alarm::warning(
                AlarmCode::DecimalLessScale,
                place.span,
                format!(
                    "`{}` has no decimal point: the {} profile reads it in least increments, {read}; {others}: the program is most likely meant in whole units",
                    place.text,
                    profile.name.as_str()
                ),
            )
            .with_help(format!(
                "if it is, set `decimal_less = \"whole_units\"` under [profile_overrides] in the machine file (FANUC parameter DPI = 1); if not, write the decimal point (`{}.`)",
                place.text
            )),
        )
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

/// `fanuc`, `fanuc and haas`, `fanuc, syntec and haas`.
fn names(profiles: &[ProfileName]) -> String {
    let names: Vec<&str> = profiles.iter().map(|n| n.as_str()).collect();
    match names.split_last() {
        None => String::new(),
        Some((last, [])) => (*last).to_string(),
        Some((last, rest)) => format!("{} and {last}", rest.join(", ")),
    }
}

/// `machine`'s profile reads system variable `number`: asked of the interpreter itself, so that
/// the list of each profile's variables lives in one place.
fn has_variable(machine: &Machine, number: u32) -> bool {
    let probe = format!("#1=#{number}\nM30\n");
    !crate::interpret_str(&probe, machine, Options::default())
        .any(|item| item.is_err_and(|alarm| alarm.code == AlarmCode::BadVariable))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The warnings of `program` on the default machine with `profile`: code and message.
    fn check(program: &str, profile: ProfileName) -> Vec<(AlarmCode, String)> {
        let machine = Machine::default().with_profile(profile).unwrap();
        ProgramScan::of_text(program.as_bytes())
            .warnings(&machine)
            .into_iter()
            .map(|a| (a.code, a.message))
            .collect()
    }

    #[test]
    fn m97_to_a_sequence_of_the_program_names_the_profile_that_calls_it() {
        let program = "O1\nG0 X0. Y0.\nM97 P15\nM30\nN15 G1 X1. F100.\nM99\n";
        let warnings = check(program, ProfileName::Fanuc);
        assert_eq!(warnings.len(), 1, "{warnings:?}");
        let (code, message) = &warnings[0];
        assert_eq!(*code, AlarmCode::WrittenForAnotherProfile);
        assert!(
            message.contains("for the haas profile, not fanuc"),
            "{message}"
        );
        assert!(
            message.contains("`M97 P15` (line 3) calls N15"),
            "{message}"
        );
        assert!(check(program, ProfileName::Haas).is_empty());
        // Without N15 in the program, M97 P15 is the machine's business.
        assert!(check("M97 P15\nM30\n", ProfileName::Fanuc).is_empty());
    }

    #[test]
    fn a_variable_only_another_profile_has_names_it() {
        let warnings = check("#1 = #3026\nG0 X1.\nM30\n", ProfileName::Fanuc);
        assert_eq!(warnings.len(), 1, "{warnings:?}");
        assert!(
            warnings[0]
                .1
                .contains("#3026 (line 1) is a variable of haas, not of fanuc"),
            "{warnings:?}"
        );
        // A variable every profile has, or none has, is no clue.
        assert!(check("#1 = #5221\n#2 = #4444\nM30\n", ProfileName::Fanuc).is_empty());
    }

    #[test]
    fn a_syntec_mark_backs_up_a_syntec_variable() {
        let warnings = check("%@MACRO\n#1 := #1000;\nM30;\n", ProfileName::Fanuc);
        assert_eq!(warnings.len(), 1, "{warnings:?}");
        assert!(
            warnings[0].1.contains("for the syntec profile"),
            "{warnings:?}"
        );
        assert!(
            warnings[0].1.contains("`%@MACRO` (line 1) is syntec's"),
            "{warnings:?}"
        );
    }

    #[test]
    fn whole_unit_lengths_without_a_decimal_point_are_found() {
        let tiny = "G90 G21\nG0 X10 Y10\nG1 Z-2 F100\nX50\nM30\n";
        let warnings = check(tiny, ProfileName::Fanuc);
        assert_eq!(warnings.len(), 1, "{warnings:?}");
        assert_eq!(warnings[0].0, AlarmCode::DecimalLessScale);
        assert!(
            warnings[0].1.starts_with("`X10` has no decimal point"),
            "{warnings:?}"
        );
        // A post that drops `.0` beside decimal values: the one small value is enough.
        let mixed = "G0 X1.5 Y35.263\nZ10\nG1 Z-1.25 F300.\nM30\n";
        assert_eq!(
            check(mixed, ProfileName::Fanuc)[0].0,
            AlarmCode::DecimalLessScale
        );
        // A program in increments: thousands.
        let increments = "G90 G0 X20000 Y15000\nG1 Z-5000 F100\nX500\nM30\n";
        assert!(check(increments, ProfileName::Fanuc).is_empty());
        // Zero, a dwell's X and a cycle count are no lengths.
        assert!(check("G0 X0 Y0.\nG04 X2500\nM30\n", ProfileName::Fanuc).is_empty());
        // The setting that reads them in whole units is the fix.
        let mut machine = Machine::default();
        machine.profile.decimal_less = DecimalLess::WholeUnits;
        assert!(ProgramScan::of_text(tiny.as_bytes())
            .warnings(&machine)
            .is_empty());
    }

    #[test]
    fn inch_sizes_in_the_comments_of_a_program_without_g20_are_found() {
        let program = "O1\n(T 2 = 1/2 END MILL)\n(T 5 = 1/4 IN DRILL)\nG0 X1. Y.5\nM30\n";
        let warnings = check(program, ProfileName::Haas);
        assert_eq!(warnings.len(), 1, "{warnings:?}");
        assert_eq!(warnings[0].0, AlarmCode::UnitNotSelected);
        assert!(warnings[0].1.contains("(`1/4 IN`)"), "{warnings:?}");
        // G20 says it; prose is no size; a machine that starts in inches needs nothing.
        assert!(check(&format!("G20\n{program}"), ProfileName::Haas).is_empty());
        assert!(check(
            "(Z-5 in G54, 20000 inch)\nG0 X1.\nM30\n",
            ProfileName::Fanuc
        )
        .is_empty());
        let mut machine = Machine::default();
        machine.profile.power_on.units = 200;
        assert!(ProgramScan::of_text(program.as_bytes())
            .warnings(&machine)
            .is_empty());
        assert_eq!(
            inch_size_in_comment(b"(T22 = .238\" B DRILL)"),
            Some((7, 12))
        );
        assert_eq!(inch_size_in_comment(b"(1IN FACE MILL)"), Some((1, 4)));
        assert_eq!(inch_size_in_comment(b"(10INSERTS) X1IN"), None);
    }

    #[test]
    fn places_are_byte_offsets_of_the_file_whatever_its_line_ends() {
        let scan = ProgramScan::of_text(b"G21\r\nG0 X1.\rZ5\n");
        let (_, place) = scan.decimal_less[Units::Millimetre as usize]
            .smallest
            .clone()
            .unwrap();
        assert_eq!(
            (place.span.line, place.span.start, place.span.end),
            (3, 12, 14)
        );
        assert_eq!(place.text, "Z5");
    }

    #[test]
    fn keywords_comments_and_arguments_are_not_words() {
        let scan = ProgramScan::of_text(
            b"(X5 IN A COMMENT)\nIF [#1 GT 10] GOTO20\nWHILE [#2 LT 3] DO1\nEND1\nG65 P9000 X5\n",
        );
        assert_eq!(scan.decimal_less.iter().map(|b| b.count).sum::<u64>(), 0);
        // GOTO20 and DO1 set no sequence number.
        assert!(!scan.has_sequence(20) && !scan.has_sequence(1));
    }
}
