//! Alarms: every one has a code, a message and the span of the word that caused it.

use vcnc::{interpret_str, AlarmCode, Machine, Options, Severity};

/// The first alarm of `program` on the FANUC profile: code, line, and the text under its span.
fn first_alarm(program: &str) -> (AlarmCode, u32, String, String) {
    let alarm = interpret_str(program, &Machine::default(), Options::default())
        .find_map(Result::err)
        .expect("the program raises an alarm");
    let span = alarm.span.expect("alarm has a span");
    let text = program[span.start as usize..span.end as usize].to_string();
    (alarm.code, span.line, text, alarm.message)
}

#[test]
fn a_word_vcnc_does_not_run_is_named() {
    // G07 was the example until it ran (issue 23): no G code of the ISO profiles is "not yet".
    let alarm = interpret_str(
        "G0 X1.\nG01 X2. E5. F100.\n",
        &Machine::default(),
        Options::default(),
    )
    .find_map(Result::err)
    .unwrap();
    assert_eq!(alarm.code, AlarmCode::NotSupportedYet);
    assert_eq!(
        alarm.message,
        "address E outside a tapping cycle is not supported yet"
    );
    assert_eq!(alarm.help, None);
    assert_eq!(alarm.span.unwrap().line, 2);
    assert_eq!(alarm.severity, Severity::Error);
}

#[test]
fn a_code_planned_in_an_issue_says_which() {
    let alarm = vcnc::Alarm::not_supported(
        vcnc::Span::new(vcnc::FileId(0), 1, 0..3),
        "G08 (look-ahead control)",
        Some(6),
    );
    assert_eq!(alarm.help.as_deref(), Some("planned in vcnc issue #6"));
}

#[test]
fn a_g_code_the_control_does_not_have_is_unknown() {
    let (code, line, text, message) = first_alarm("G1 X1. F1.\nG07.5 X1.\n");
    assert_eq!(
        (code, line, text.as_str()),
        (AlarmCode::UnknownGCode, 2, "G07.5")
    );
    assert_eq!(message, "G07.5 does not exist on the fanuc profile");
}

#[test]
fn the_same_address_twice_points_at_the_second() {
    let (code, _, text, _) = first_alarm("G0 X1. X2.\n");
    assert_eq!((code, text.as_str()), (AlarmCode::DuplicateAddress, "X2."));
}

#[test]
fn an_axis_the_machine_lacks_is_an_alarm() {
    let (code, _, text, _) = first_alarm("G0 A90.\n");
    assert_eq!((code, text.as_str()), (AlarmCode::AxisNotOnMachine, "A90."));
}

#[test]
fn an_arc_end_off_its_circle_is_alarm_020() {
    let (code, _, text, _) = first_alarm("G2 X10. Y5. I5. F100.\n");
    assert_eq!((code, text.as_str()), (AlarmCode::ArcEndNotOnCircle, "I5."));
}

#[test]
fn an_arc_without_centre_words_is_an_alarm() {
    let (code, _, _, _) = first_alarm("G2 X10. F100.\n");
    assert_eq!(code, AlarmCode::ArcWithoutCenter);
}

#[test]
fn an_r_too_small_for_the_chord_is_an_alarm() {
    let (code, _, text, _) = first_alarm("G2 X30. R10. F100.\n");
    assert_eq!(
        (code, text.as_str()),
        (AlarmCode::ArcRadiusTooSmall, "R10.")
    );
}

#[test]
fn a_cut_before_any_feed_is_fanuc_alarm_011() {
    let (code, line, _, _) = first_alarm("G0 X1.\nG1 X2.\n");
    assert_eq!((code, line), (AlarmCode::NoFeedRate, 2));
}

#[test]
fn a_call_to_a_program_nowhere_to_be_found_names_it() {
    let (code, line, text, message) = first_alarm("G0 X1.\nM98 P1234\n");
    assert_eq!(
        (code, line, text.as_str()),
        (AlarmCode::ProgramNotFound, 2, "P1234")
    );
    assert!(message.contains("O1234"), "{message}");
}

#[test]
fn an_h_number_beyond_the_offset_memory_is_an_alarm() {
    let (code, _, text, _) = first_alarm("G43 H999 Z1.\n");
    assert_eq!(
        (code, text.as_str()),
        (AlarmCode::OffsetNumberOutOfRange, "H999")
    );
}

#[test]
fn a_bad_g10_l_number_is_an_alarm() {
    let (code, _, text, _) = first_alarm("G10 L77 P1 X0\n");
    assert_eq!((code, text.as_str()), (AlarmCode::BadDataInput, "L77"));
}

#[test]
fn sinumerik_programs_get_one_clear_alarm() {
    let options = Options {
        dialect: vcnc::syntax::Dialect::Sinumerik,
        ..Options::default()
    };
    let items: Vec<_> = interpret_str("G0 X=10\n", &Machine::default(), options).collect();
    assert_eq!(items.len(), 1);
    let alarm = items[0].as_ref().unwrap_err();
    assert_eq!(alarm.code, AlarmCode::DialectNotSupported);
}

#[test]
fn nothing_comes_after_an_error() {
    let items: Vec<_> = interpret_str(
        "G0 X1.\nG1 X2.\nG0 X3.\n",
        &Machine::default(),
        Options::default(),
    )
    .collect();
    // The frame of the first move, the move, the alarm of the line without a feed.
    assert_eq!(items.len(), 3, "{items:?}");
    assert!(items[2].is_err());
}

#[test]
fn every_alarm_code_has_a_distinct_code_and_id() {
    let mut codes = std::collections::BTreeSet::new();
    let mut ids = std::collections::BTreeSet::new();
    for code in AlarmCode::ALL {
        assert!(codes.insert(code.code()), "{} twice", code.code());
        assert!(ids.insert(code.id()), "{} twice", code.id());
    }
}
