//! High-speed and smoothing modes (issue #6): Syntec G05 and G05.1 (spec iso-syntec-milling.md
//! 1.8, 1.9), FANUC G05, G05.1 Q1 and G08 P1. The interpreter puts the mode's tolerance on every
//! motion; the planner cuts corners between two such motions within it.

use crate::common;

use vcnc::plan::{PlanOptions, Planner};
use vcnc::{interpret_str, AlarmCode, Machine, Options, ProfileName};

fn machine(profile: ProfileName) -> Machine {
    Machine::default().with_profile(profile).unwrap()
}

/// The smoothing tolerance (mm) of each motion of `program`, and the first error alarm.
fn tolerances(profile: ProfileName, program: &str) -> (Vec<Option<f64>>, Option<AlarmCode>) {
    let run = common::run(program.as_bytes(), &machine(profile), Options::default());
    let tolerances = run
        .segments
        .iter()
        .filter_map(|s| s.motion())
        .map(|m| m.smoothing.map(|s| s.mm()))
        .collect();
    (tolerances, run.error().map(|a| a.code))
}

#[track_caller]
fn assert_tolerances(profile: ProfileName, program: &str, expected: &[Option<f64>]) {
    let (actual, alarm) = tolerances(profile, program);
    assert_eq!(alarm, None, "{program}");
    assert_eq!(actual, expected, "{program}");
}

#[track_caller]
fn assert_alarm(profile: ProfileName, program: &str, line: u32) {
    let run = common::run(program.as_bytes(), &machine(profile), Options::default());
    let alarm = run
        .error()
        .unwrap_or_else(|| panic!("no alarm:\n{program}"));
    assert_eq!(
        (alarm.code, alarm.span.map(|s| s.line)),
        (AlarmCode::SmoothingCommand, Some(line)),
        "{program}\n{alarm:?}"
    );
}

/// The default machine's tolerance for a code without E (`planner.smoothing_tolerance`).
const DEFAULT: f64 = 0.01;

#[test]
fn syntec_path_smoothing_sets_its_tolerance_until_q0() {
    assert_tolerances(
        ProfileName::Syntec,
        "G90 G01 X1. F1000.\nG05.1 Q1 E0.005\nX2.\nY1.\nG05.1 Q0\nX3.\nM30",
        &[None, Some(0.005), Some(0.005), None],
    );
    // Q2 is the other smoothing mode; the planner treats both alike.
    assert_tolerances(
        ProfileName::Syntec,
        "G05.1 Q2 E0.01\nG01 X1. F1000.\nM30",
        &[Some(0.01)],
    );
}

#[test]
fn syntec_path_smoothing_clamps_e_to_2_to_20_thousandths() {
    assert_tolerances(
        ProfileName::Syntec,
        "G05.1 Q1 E0.5\nG01 X1. F1000.\nG05.1 Q1 E0.0001\nX2.\nM30",
        &[Some(0.02), Some(0.002)],
    );
    // In inch: thousandths of an inch (E0.01 in = 0.254 mm, inside the range).
    assert_tolerances(
        ProfileName::Syntec,
        "G70 G05.1 Q1 E0.01\nG01 X1. F10.\nM30",
        &[Some(0.254)],
    );
}

#[test]
fn syntec_high_speed_mode_takes_e_or_the_machine_tolerance() {
    assert_tolerances(
        ProfileName::Syntec,
        "G05 P10000\nG01 X1. F1000.\nG05 P0\nX2.\nG05 E0.003\nX3.\nG05\nX4.\nM30",
        &[Some(DEFAULT), None, Some(0.003), None],
    );
}

#[test]
fn g09_has_no_effect_in_high_speed_mode() {
    let run = common::run(
        b"G05 P10000\nG01 G09 X1. F1000.\nG05 P0\nG09 X2.\nM30",
        &machine(ProfileName::Syntec),
        Options::default(),
    );
    let stops: Vec<bool> = run
        .segments
        .iter()
        .filter_map(|s| s.motion())
        .map(|m| m.exact_stop)
        .collect();
    assert_eq!(stops, [false, true]);
}

#[test]
fn g61_suspends_the_modes_until_g64() {
    assert_tolerances(
        ProfileName::Syntec,
        "G05.1 Q1 E0.01\nG01 X1. F1000.\nG61 X2.\nG64 X3.\nM30",
        &[Some(0.01), None, Some(0.01)],
    );
}

#[test]
fn syntec_bad_words_and_exact_stop_mode_alarm() {
    // COR-107: Q or E missing, Q out of range, E not positive, P other than 0 or 10000.
    assert_alarm(ProfileName::Syntec, "G05.1 E0.01\nM30", 1);
    assert_alarm(ProfileName::Syntec, "G01 X1. F100.\nG05.1 Q1\nM30", 2);
    assert_alarm(ProfileName::Syntec, "G05.1 Q3 E0.01\nM30", 1);
    assert_alarm(ProfileName::Syntec, "G05.1 Q1 E-0.01\nM30", 1);
    assert_alarm(ProfileName::Syntec, "G05 P5\nM30", 1);
    assert_alarm(ProfileName::Syntec, "G05 E0.\nM30", 1);
    // COR-106: not in G61 or G63.
    assert_alarm(ProfileName::Syntec, "G61\nG05.1 Q1 E0.01\nM30", 2);
    assert_alarm(ProfileName::Syntec, "G63\nG05 P10000\nM30", 2);
    // High-speed mode does not run in inverse time feed.
    assert_alarm(ProfileName::Syntec, "G93\nG05 P10000\nM30", 2);
}

#[test]
fn fanuc_ai_contour_and_look_ahead_use_the_machine_tolerance() {
    assert_tolerances(
        ProfileName::Fanuc,
        "G05.1 Q1\nG01 X1. F1000.\nG05.1 Q0\nX2.\nG08 P1\nX3.\nG08 P0\nX4.\nG05 P10000\nX5.\nM30",
        &[Some(DEFAULT), None, Some(DEFAULT), None, Some(DEFAULT)],
    );
    assert_alarm(ProfileName::Fanuc, "G08 P2\nM30", 1);
    assert_alarm(ProfileName::Fanuc, "G05.1\nM30", 1);
}

#[test]
fn controls_without_the_modes_name_them() {
    // The 0M manual's G code table (spec A.16, 001 L579-726) has no G05.1: the code does not
    // exist there.
    let run = common::run(
        b"G05.1 Q1\nM30",
        &machine(ProfileName::Fanuc0m),
        Options::default(),
    );
    assert_eq!(run.error().map(|a| a.code), Some(AlarmCode::UnknownGCode));
}

/// The planned time of `program` on `machine`.
fn seconds(machine: &Machine, program: &str) -> f64 {
    let stream = interpret_str(program, machine, Options::default());
    Planner::new(stream, machine, PlanOptions::default())
        .map(|item| item.expect("no alarm"))
        .filter_map(|timed| timed.segment().map(|timed| timed.dt))
        .sum()
}

/// A zigzag of 0.5 mm steps at F3000: its time is mostly its corners.
fn zigzag(head: &str) -> String {
    let mut program = format!("G90 G17 G64 G01 F3000.\n{head}\n");
    for i in 1..=200 {
        let y = if i % 2 == 0 { 0.0 } else { 0.3 };
        program.push_str(&format!("X{:.1} Y{y:.1}\n", f64::from(i) * 0.5));
    }
    program.push_str("M30\n");
    program
}

#[test]
fn corners_in_a_smoothing_mode_are_cut_within_its_tolerance() {
    let syntec = machine(ProfileName::Syntec);
    let with_mode = seconds(&syntec, &zigzag("G05.1 Q1 E0.005"));
    // The same corners without the mode, on a machine whose G64 tolerance is that E.
    let mut tight = syntec.clone();
    tight.planner.corner_tolerance = 0.005;
    let by_tolerance = seconds(&tight, &zigzag(""));
    assert!(
        (with_mode - by_tolerance).abs() <= 1e-9 * by_tolerance,
        "{with_mode} {by_tolerance}"
    );
    // The machine's own G64 tolerance (0.02) blends wider, so faster.
    let plain = seconds(&syntec, &zigzag(""));
    assert!(plain < with_mode * 0.99, "{plain} {with_mode}");
}
