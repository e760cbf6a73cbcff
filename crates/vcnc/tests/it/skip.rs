//! G31 skip function (Syntec spec 1.20): without a probe the signal never comes, so the block
//! is a cutting move to its end point with an exact stop, and that end point is the recorded
//! skip position (#5061-#5066). The manual's three examples are asserted in seed_examples.toml.

use crate::common::run;
use vcnc::{AlarmCode, Machine, Options, ProfileName, SegmentKind};

fn machine(profile: ProfileName) -> Machine {
    Machine::default().with_profile(profile).unwrap()
}

#[test]
fn g31_cuts_to_its_end_stops_there_and_records_it_in_program_coordinates() {
    // Work offset G54 = X10 Y20: #5061/#5062 are program coordinates.
    let program = "G10 L2 P1 X10. Y20.\nG54 G90 G00 X0 Y0\nG31 X30. Y5. F200.\n\
                   #100=#5061\n#101=#5062\nX0\nM30\n";
    let run = run(
        program.as_bytes(),
        &machine(ProfileName::Fanuc),
        Options::default(),
    );
    assert!(run.error().is_none(), "{:?}", run.error());
    let skip = run
        .segments
        .iter()
        .find(|s| s.span.line == 3)
        .expect("the G31 block moves");
    let SegmentKind::Line { motion, feed } = &skip.kind else {
        panic!("{skip:?}")
    };
    assert_eq!(motion.to.0[..2], [40.0, 25.0]);
    assert!(motion.exact_stop);
    assert_eq!(feed.mm_per_min(1.0), Some(200.0));
    // G31 is one-shot: the block after it moves in the G00 in force before it.
    let after = run.segments.iter().find(|s| s.span.line == 6).unwrap();
    assert!(matches!(after.kind, SegmentKind::Rapid { .. }), "{after:?}");
    let vars = vcnc::interpret_str(
        &program.replace("X0\nM30", "#3000=[#100*1000+#101]\nM30"),
        &machine(ProfileName::Fanuc),
        Options::default(),
    )
    .filter_map(Result::err)
    .find(|a| a.code == AlarmCode::UserAlarm)
    .expect("the #3000 alarm carries the values");
    // The control shows #3000 = n as alarm 3000 + n: here #5061 = 30 and #5062 = 5 make 30005.
    assert!(vars.message.contains("33005"), "{}", vars.message);
}

#[test]
fn g31_in_cutter_compensation_is_an_alarm() {
    let program = "G90 G00 X0 Y0\nG41 D1 G01 X10. F100.\nG31 X20.\nG40 X30.\nM30\n";
    let run = run(
        program.as_bytes(),
        &machine(ProfileName::Fanuc),
        Options::default(),
    );
    let alarm = run.error().expect("an alarm");
    assert_eq!(alarm.code, AlarmCode::WordNotAllowed, "{alarm:?}");
    assert_eq!(alarm.span.unwrap().line, 3);
}

#[test]
fn g31_needs_a_feed_and_takes_syntec_q() {
    let run_on = |profile, text: &str| run(text.as_bytes(), &machine(profile), Options::default());
    let no_feed = run_on(ProfileName::Fanuc, "G90 G31 X10.\nM30\n");
    assert_eq!(no_feed.error().map(|a| a.code), Some(AlarmCode::NoFeedRate));
    let with_q = run_on(ProfileName::Syntec, "G90 G31 X10. F100. Q101\nM30\n");
    assert!(with_q.error().is_none(), "{:?}", with_q.error());
}
