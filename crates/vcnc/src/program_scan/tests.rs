//! The program scan's tests: short programs and the warnings they give.

use super::words::inch_size_in_comment;
use super::*;
use crate::alarm::AlarmCode;
use crate::profile::{DecimalLess, ProfileName};

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
fn radius_compensation_by_h_names_the_0m_profile_with_its_colon_mark() {
    let program = ":0097\nG55 G0 X2. Y0\nG42 H19 Y10. F39\nX11.\nM30\n";
    let warnings = check(program, ProfileName::Fanuc);
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(
        warnings[0].1.contains("for the fanuc0m profile, not fanuc"),
        "{warnings:?}"
    );
    assert!(
        warnings[0]
            .1
            .contains("`G42 H19` (line 3) takes the cutter radius from H"),
        "{warnings:?}"
    );
    assert!(
        warnings[0].1.contains("`:0097` (line 1) is fanuc0m's"),
        "{warnings:?}"
    );
    assert!(check(program, ProfileName::Fanuc0m).is_empty());
    assert!(check("G41 D1 H1 X1.\nM30\n", ProfileName::Fanuc).is_empty());
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
    machine.profile.units.decimal_less = DecimalLess::WholeUnits;
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
    let (_, place) = scan.lengths.decimal_less[Units::Millimetre as usize]
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
    assert_eq!(
        scan.lengths
            .decimal_less
            .iter()
            .map(|b| b.count)
            .sum::<u64>(),
        0
    );
    // GOTO20 and DO1 set no sequence number.
    assert!(!scan.has_sequence(20) && !scan.has_sequence(1));
}

proptest::proptest! {
    #[test]
    fn any_bytes_scan_without_panic_and_every_place_lies_in_the_text(
        bytes in proptest::collection::vec(
            proptest::prop_oneof![
                proptest::sample::select(b"XYZIJGMNP#()/.-+ 0123456789\r\n:%@".to_vec()),
                proptest::num::u8::ANY,
            ],
            0..400,
        ),
        split in 0usize..400,
    ) {
        // Fed in two pieces, cut anywhere (a `\r\n` too), as a reader hands it over.
        let mut scan = ProgramScan::new(FileId(0));
        let (a, b) = bytes.split_at(split.min(bytes.len()));
        scan.add(a);
        scan.add(b);
        scan.finish();
        for profile in ProfileName::ALL {
            let machine = Machine::default().with_profile(profile).unwrap();
            for alarm in scan.warnings(&machine) {
                let span = alarm.span.unwrap();
                proptest::prop_assert!(span.start <= span.end && span.end as usize <= bytes.len());
            }
        }
        let whole = ProgramScan::of_text(&bytes);
        proptest::prop_assert_eq!(whole.line.number, scan.line.number);
    }
}
