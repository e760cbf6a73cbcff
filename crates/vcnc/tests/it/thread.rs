//! G33 thread cutting (Syntec spec 1.21, FANUC 0M A.30, Mitsubishi B.10): a straight move at one
//! lead per spindle revolution, modal, with the override locked and a stop at the end of the
//! pass. The manuals' examples (Syntec 31, FANUC 0M O1212) are asserted in seed_examples.toml.

use crate::common::run;
use vcnc::motion::{Feed, PathMode};
use vcnc::plan::{PlanOptions, Planner};
use vcnc::{AlarmCode, Machine, Options, ProfileName, Segment, SegmentKind};

fn machine(profile: ProfileName) -> Machine {
    Machine::default().with_profile(profile).unwrap()
}

fn threads(segments: &[Segment]) -> Vec<(f64, f64, Feed, PathMode)> {
    segments
        .iter()
        .filter_map(|s| match &s.kind {
            SegmentKind::Line { motion, feed } => {
                Some((motion.from.0[2], motion.to.0[2], *feed, motion.path_mode))
            }
            _ => None,
        })
        .collect()
}

#[test]
fn g33_moves_one_lead_per_revolution_and_is_modal() {
    let program =
        "G21 G90 S400 M03\nG00 X0 Y0 Z10.\nG33 Z-45. F1.5\nG00 Z10.\nG33 Z-20.\nZ-45.\nM30\n";
    let run = run(
        program.as_bytes(),
        &machine(ProfileName::Fanuc),
        Options::default(),
    );
    assert!(run.error().is_none(), "{:?}", run.error());
    let feed = Feed::PerRevolution {
        per_revolution: 1.5,
        rpm: Some(400.0),
    };
    assert_eq!(
        threads(&run.segments),
        vec![
            (10.0, -45.0, feed, PathMode::Tapping),
            (10.0, -20.0, feed, PathMode::Tapping),
            (-20.0, -45.0, feed, PathMode::Tapping),
        ]
    );
    assert_eq!(feed.mm_per_min(55.0), Some(600.0));
}

#[test]
fn mitsubishi_e_gives_threads_per_inch() {
    let program = "G21 G90 S200 M03\nG33 Z-25.4 E8.\nM30\n";
    let run = run(
        program.as_bytes(),
        &machine(ProfileName::Mitsubishi),
        Options::default(),
    );
    assert!(run.error().is_none(), "{:?}", run.error());
    let (_, _, feed, _) = threads(&run.segments)[0];
    assert_eq!(
        feed,
        Feed::PerRevolution {
            per_revolution: 25.4 / 8.0,
            rpm: Some(200.0)
        }
    );
}

#[test]
fn a_thread_needs_a_lead_and_no_cutter_compensation() {
    let cases = [
        ("G90 S100 M03\nG33 Z-10.\nM30\n", AlarmCode::NoFeedRate),
        (
            "G90 S100 M03 F100.\nG41 D1 G01 X10.\nG33 Z-10. F1.\nM30\n",
            AlarmCode::NotSupportedYet,
        ),
        // E is threads per inch on the Mitsubishi profile only.
        (
            "G90 S100 M03\nG33 Z-10. E8.\nM30\n",
            AlarmCode::NotSupportedYet,
        ),
    ];
    for (program, code) in cases {
        let run = run(
            program.as_bytes(),
            &machine(ProfileName::Fanuc),
            Options::default(),
        );
        assert_eq!(run.error().map(|a| a.code), Some(code), "{program}");
    }
}

#[test]
fn the_feed_override_does_not_touch_a_thread() {
    let machine = machine(ProfileName::Fanuc);
    let time = |feed_override: f64| -> f64 {
        let program = "G21 G90 S400 M03\nG00 Z10.\nG33 Z-45. F1.5\nM30\n";
        let stream = vcnc::interpret_str(program, &machine, Options::default());
        Planner::new(stream, &machine, PlanOptions { feed_override })
            .filter_map(|item| item.ok()?.segment().copied())
            .filter(|t| t.segment.span.line == 3)
            .map(|t| t.dt)
            .sum()
    };
    // 55 mm at 1.5 x 400 = 600 mm/min: 5.5 s and the ramps.
    let full = time(1.0);
    assert!(full > 5.5 && full < 5.6, "{full}");
    assert_eq!(time(0.5), full);
    assert_eq!(time(1.5), full);
}
