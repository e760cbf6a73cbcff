//! What the scan's findings mean on a machine: the clues that a program was written for
//! another profile, lengths read a thousandth of their size, an inch program run in mm. Each
//! finding gives at most one warning; the profiles are asked questions, never named.

use super::{power_on_unit, Place, ProgramScan, Units, SMALL_MM};
use crate::alarm::{Alarm, AlarmCode};
use crate::machine::Machine;
use crate::profile::{DecimalLess, Profile, ProfileName};
use crate::summary::LengthUnit;
use crate::Options;

/// One clue that the program was written for other profiles: where, what it says, and the
/// profiles on which it makes sense.
struct Clue {
    place: Place,
    says: String,
    fits: Vec<ProfileName>,
}

impl ProgramScan {
    /// What in the text runs wrong on `machine`'s profile and right on another of vcnc's.
    fn clues(&self, machine: &Machine) -> Vec<Clue> {
        let profile = &machine.profile;
        let here = profile.name.as_str();
        let mut clues = Vec::new();
        let local_calls: Vec<ProfileName> = ProfileName::ALL
            .into_iter()
            .filter(|&n| Profile::builtin(n).subprograms.m97_local_subprogram)
            .collect();
        if !profile.subprograms.m97_local_subprogram {
            let called = self
                .m97_targets
                .iter()
                .find(|(n, _)| self.has_sequence(**n));
            if let Some((n, place)) = called {
                let instead = if profile.subprograms.subprogram_m_codes.contains(&97) {
                    "turns the interrupt program off with M97"
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
        if let (Some(place), false) = (&self.radius_by_h, profile.compensation.radius_offset_by_h) {
            let fits: Vec<ProfileName> = ProfileName::ALL
                .into_iter()
                .filter(|&n| Profile::builtin(n).compensation.radius_offset_by_h)
                .collect();
            clues.push(Clue {
                says: format!(
                    "`{}` (line {}) takes the cutter radius from H on {}, but {here} from D (none here)",
                    place.text,
                    place.span.line,
                    names(&fits)
                ),
                place: place.clone(),
                fits,
            });
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
    pub(super) fn profile_warning(&self, machine: &Machine) -> Option<Alarm> {
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
    pub(super) fn decimal_less_warning(&self, profile: &Profile) -> Option<Alarm> {
        if profile.units.decimal_less != DecimalLess::Increments {
            return None;
        }
        let power_on_inch = power_on_unit(profile) == LengthUnit::Inch;
        let increment_mm = |units: usize| {
            let inch = units == Units::Inch as usize || (units == 0 && power_on_inch);
            if inch {
                profile.units.increment_inch * 25.4
            } else {
                profile.units.increment_mm
            }
        };
        let buckets = self
            .lengths
            .decimal_less
            .iter()
            .enumerate()
            .filter(|(_, b)| b.count > 0);
        let count: u64 = self.lengths.decimal_less.iter().map(|b| b.count).sum();
        let suspicious = if self.lengths.decimal_point_words == 0 {
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
        let read = if increment_mm(units) == profile.units.increment_mm {
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
        let others = if self.lengths.decimal_point_words == 0 {
            format!(
                "{} in this program, none with a decimal point, all come out under {SMALL_MM} mm so",
                lengths(count)
            )
        } else {
            format!(
                "{} in this program without a decimal point, beside {} with one (up to {})",
                lengths(count),
                self.lengths.decimal_point_words,
                self.lengths.largest_decimal_point
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
                "if it is, set `decimal_less = \"whole_units\"` under [profile_overrides.units] in the machine file (FANUC parameter DPI = 1); if not, write the decimal point (`{}.`)",
                place.text
            )),
        )
    }

    /// One warning when a program that never selects its unit, on a profile that starts in
    /// mm, gives its sizes in inches in its comments: a shop whose control starts in inches
    /// (Haas setting 9) writes no G20, and the part would come out 25.4 times too small.
    pub(super) fn unit_warning(&self, profile: &Profile) -> Option<Alarm> {
        let selected =
            self.units.first.is_some() || (self.units.g70_or_g71 && profile.units.g70_g71_units);
        if selected || power_on_unit(profile) != LengthUnit::Millimetre {
            return None;
        }
        let place = self.units.inch_comment.as_ref()?;
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
