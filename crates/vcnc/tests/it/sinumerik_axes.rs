//! SINUMERIK axes beyond the path's geometry, with times and positions worked out by hand:
//! the feed group (FGROUP, FGREF, FL, F of rotary axes under G700; PGsl 7.1, L2433-2740),
//! positioning axes (POS, POSA, FA, WAITP; PGsl 7.2) and spindles by number (S2=, M2=3,
//! SPOS[n], LIMS[n], G26 S2=; PGsl 6.1, 6.5, 7.4) on the spindles the machine file declares.
//! docs/SINUMERIK.md 10 is the model.

use vcnc::interp::sinumerik::run_str;
use vcnc::machine::DEFAULT_MACHINE_TOML;
use vcnc::motion::SpindleState;
use vcnc::{Alarm, AlarmCode, Axis, Machine, Segment, SegmentKind};

use crate::common::sinumerik::machine;
use crate::common::{collect, rotary_axis};

/// The SINUMERIK test machine with rotary axes A and C and `spindles` spindles.
fn five_axis(spindles: u32) -> Machine {
    let mut machine = machine();
    machine.axes[Axis::A.index()] = Some(rotary_axis());
    machine.axes[Axis::C.index()] = Some(rotary_axis());
    machine.spindle.count = spindles;
    machine
}

/// The segments of a program that must run to its end.
fn run(text: &str, machine: &Machine) -> Vec<Segment> {
    let run = collect(run_str(text, machine));
    assert!(run.error().is_none(), "{text}\n{:#?}", run.alarms);
    run.segments
}

fn error(text: &str, machine: &Machine) -> Alarm {
    let run = collect(run_str(text, machine));
    run.error()
        .cloned()
        .unwrap_or_else(|| panic!("no error in\n{text}"))
}

/// The time of every cutting line and arc at its programmed feed, seconds: the planner's
/// length (along X Y Z, in degrees when only rotary axes move) over the feed the segment
/// carries, which is what the control's time must come out as.
fn feed_seconds(segments: &[Segment]) -> Vec<f64> {
    segments
        .iter()
        .filter_map(|s| match &s.kind {
            SegmentKind::Line { feed, motion } | SegmentKind::Arc { feed, motion, .. } => {
                let mut length = s.length();
                if length < 1e-9 {
                    let (from, to) = (motion.from.0, motion.to.0);
                    length = (3..6)
                        .map(|i| (to[i] - from[i]).powi(2))
                        .sum::<f64>()
                        .sqrt();
                }
                let per_minute = feed.mm_per_min(length).expect("a feed per minute");
                Some(60.0 * length / per_minute)
            }
            _ => None,
        })
        .collect()
}

/// The end points of the moves, all six axes.
fn ends(segments: &[Segment]) -> Vec<[f64; 6]> {
    segments
        .iter()
        .filter_map(Segment::motion)
        .map(|m| m.to.0)
        .collect()
}

/// The master spindle's events: speed and state.
fn spindle_events(segments: &[Segment]) -> Vec<(f64, SpindleState)> {
    segments
        .iter()
        .filter_map(|s| match s.kind {
            SegmentKind::Spindle { speed, state } => Some((speed, state)),
            _ => None,
        })
        .collect()
}

fn assert_close(actual: &[f64], expected: &[f64], tolerance: f64) {
    assert_eq!(
        actual.len(),
        expected.len(),
        "{actual:?} against {expected:?}"
    );
    for (a, e) in actual.iter().zip(expected) {
        assert!((a - e).abs() < tolerance, "{actual:?} against {expected:?}");
    }
}

/// sinumerik-a/37 without its synchronized actions (the DO lines): the times its comments
/// give for $AC_TIME.
/// - N140 X10: 10 mm at 100 mm/min = 6 s.
/// - N160 X10 A10: sqrt(10^2 + 10^2) = 14.1421 mm (1 degree = 1 mm) = 8.4853 s.
/// - N180 A10: only A of the group, FGREF the default: 100 deg/min, 6 s.
/// - N200 X0.001 A10: sqrt(0.001^2 + 10^2) = 10.00000005 mm = 6 s.
/// - N210 G700 F100: 2540 mm/min. N230 X10 = 254 mm: 6 s.
/// - N250 X10 A10: sqrt(254^2 + 10^2) = 254.19677 mm / 2540 = 0.1000775 min = 6.00465 s.
/// - N270 A10: still 100 deg/min under G700 (the default FGREF): 6 s.
/// - N290 X0.001 A10: sqrt(0.0254^2 + 10^2) = 10.0000323 mm / 2540 = 0.236221 s.
/// - N300 FGREF[A]=360/(2 pi) inch: 1 degree = 1 inch. N320 X0.001 A10:
///   sqrt(0.0254^2 + 254^2) = 254.0000013 mm: 6 s.
///
/// The end: X 10 + 10 + 0.001 + 254 + 254 + 0.0254 + 0.0254 = 528.0518 mm, A 70.
#[test]
fn fgroup_with_a_rotary_axis_times_the_manuals_example() {
    let program = "\
N100 G0 X0 A0
N110 FGROUP(X,A)
N120 G91 G1 G710 F100
N140 X10
N160 X10 A10
N180 A10
N200 X0.001 A10
N210 G700 F100
N230 X10
N250 X10 A10
N270 A10
N290 X0.001 A10
N300 FGREF[A]=360/(2*$PI)
N320 X0.001 A10
N330 M30
";
    let segments = run(program, &five_axis(1));
    assert_close(
        &feed_seconds(&segments),
        &[
            6.0, 8.485_281, 6.0, 6.0, 6.0, 6.004_648, 6.0, 0.236_221, 6.0,
        ],
        1e-5,
    );
    let end = *ends(&segments).last().unwrap();
    assert!((end[0] - 528.0518).abs() < 1e-9, "{end:?}");
    assert!((end[3] - 70.0).abs() < 1e-9, "{end:?}");
}

/// sinumerik-a/39 without N100: FGROUP(X, Y) measures the helix in the plane only:
/// 2 pi 15 = 94.2478 mm at F1000 = 5.6549 s, Z's 15 mm then runs at 159.2 mm/min, under its
/// FL of 200. With FL[Z]=100, Z needs 15 / 100 min = 9 s, and the whole helix takes that.
#[test]
fn fgroup_measures_a_helix_in_its_plane_and_fl_slows_it() {
    let helix = |limit: f64| {
        format!(
            "N10 G17 G94 G1 Z0 F500\nN20 X10 Y20\nN25 FGROUP(X, Y)\n\
             N30 G2 X10 Y20 Z-15 I15 J0 F1000 FL[Z]={limit}\nN110 M30\n"
        )
    };
    let segments = run(&helix(200.0), &machine());
    let seconds = feed_seconds(&segments);
    let circle = 60.0 * std::f64::consts::TAU * 15.0 / 1000.0;
    assert!((circle - 5.654_867).abs() < 1e-6);
    assert!(
        (seconds.last().unwrap() - circle).abs() < 1e-6,
        "{seconds:?}"
    );
    let end = *ends(&segments).last().unwrap();
    assert_close(&end[..3], &[10.0, 20.0, -15.0], 1e-9);

    let seconds = feed_seconds(&run(&helix(100.0), &machine()));
    assert!((seconds.last().unwrap() - 9.0).abs() < 1e-6, "{seconds:?}");
}

/// sinumerik-a/38: FGROUP(X) with FL[Y]=500: X's 1000 mm at F1000 is 1 min, Y's 1000 mm at
/// 500 mm/min 2 min: 2 min (120 s) for the diagonal. N40 Z-50 moves no axis of the group:
/// Z at F1000, 3 s.
#[test]
fn fl_limits_a_synchronized_axis() {
    let program = "N10 G0 X0 Y0\nN20 FGROUP(X)\nN30 G1 X1000 Y1000 G94 F1000 FL[Y]=500\nN40 Z-50\n";
    assert_close(
        &feed_seconds(&run(program, &machine())),
        &[120.0, 3.0],
        1e-6,
    );
}

/// Under G700 F is inch/min for lengths, but a rotary axis alone stays in deg/min (L2592-2626):
/// A90 at F100 is 0.9 min = 54 s, not 90 / 2540 min. X1 (25.4 mm) at 2540 mm/min is 0.6 s.
#[test]
fn g700_leaves_a_rotary_feed_in_degrees_per_minute() {
    let segments = run("G700 G1 A90 F100\nX1\nM30\n", &five_axis(1));
    assert_close(&feed_seconds(&segments), &[54.0, 0.6], 1e-6);
}

/// FGROUP() brings back the geometry axes (L2581-2590): X10 A10 is measured along X only,
/// 10 mm at F100 = 6 s, as before any FGROUP.
#[test]
fn empty_fgroup_restores_the_geometry_axes() {
    let program = "FGROUP(X,A)\nG91 G1 X10 A10 F100\nFGROUP()\nX10 A10\nM30\n";
    assert_close(
        &feed_seconds(&run(program, &five_axis(1))),
        &[8.485_281, 6.0],
        1e-5,
    );
}

#[test]
fn fgroup_names_axes_of_the_machine() {
    let alarm = error("FGROUP(X,A)\n", &machine());
    assert_eq!(alarm.code, AlarmCode::AxisNotOnMachine);
    assert!(alarm.message.contains("no axis A"), "{}", alarm.message);
    let alarm = error("FGROUP(X,U)\n", &machine());
    assert_eq!(alarm.code, AlarmCode::AxisNotOnMachine);
    assert!(alarm.message.contains("no axis U"), "{}", alarm.message);
}

/// POS with FA: X 100 mm at 1000 mm/min takes 0.1 min, Y 50 mm at 100 mm/min 0.5 min; the two
/// positioning axes run together, so the move takes 0.5 min = 30 s, ending X100 Y50.
#[test]
fn positioning_axes_take_as_long_as_the_slowest() {
    let program = "FA[X]=1000 FA[Y]=100\nPOS[X]=100 POS[Y]=50\nM30\n";
    let segments = run(program, &machine());
    assert_close(&feed_seconds(&segments), &[30.0], 1e-6);
    assert_close(&ends(&segments)[0][..3], &[100.0, 50.0, 0.0], 1e-9);
}

/// A block with a positioning axis and a path: the path first (Y20 at F100: 12 s), then the
/// positioning move (X10 at rapid, no FA); POSA=IC(5) then goes from the programmed X10 to
/// X15, and G91 X1 moves on from there: X16.
#[test]
fn positioning_axes_move_after_the_path_and_update_the_position() {
    let program = "G1 Y20 F100 POS[X]=10\nPOSA[X]=IC(5)\nWAITP(X)\nG91 X1\nM30\n";
    let segments = run(program, &machine());
    let kinds: Vec<bool> = segments
        .iter()
        .filter(|s| s.motion().is_some())
        .map(|s| matches!(s.kind, SegmentKind::Rapid { .. }))
        .collect();
    assert_eq!(kinds, [false, true, true, false]);
    let xs: Vec<[f64; 2]> = ends(&segments).iter().map(|p| [p[0], p[1]]).collect();
    assert_eq!(xs, [[0.0, 20.0], [10.0, 20.0], [15.0, 20.0], [16.0, 20.0]]);
    assert_close(&feed_seconds(&segments), &[12.0, 0.6], 1e-6);
}

/// An axis is a path axis or a positioning axis of a block, not both; under a rotation the
/// path's X (filled in by rule 6.4.3) would otherwise undo the positioning.
#[test]
fn an_axis_is_not_both_path_and_positioning_axis_in_a_block() {
    let alarm = error("G1 X10 F100 POS[X]=20\n", &machine());
    assert_eq!(alarm.code, AlarmCode::WordNotAllowed);
    assert!(
        alarm.message.contains("X is a path axis"),
        "{}",
        alarm.message
    );
}

#[test]
fn positioning_axes_are_axes_of_the_machine() {
    let alarm = error("POS[U]=10 FA[U]=200\n", &machine());
    assert_eq!(alarm.code, AlarmCode::AxisNotOnMachine);
    assert!(alarm.message.contains("no axis U"), "{}", alarm.message);
    let alarm = error("POSA[A]=10\n", &machine());
    assert_eq!(alarm.code, AlarmCode::AxisNotOnMachine);
    assert!(alarm.message.contains("no axis A"), "{}", alarm.message);
}

/// A rotary axis of the machine in SINUMERIK blocks: G0 with A and C, AC and IC, G91.
#[test]
fn rotary_axes_of_the_machine_file_move_in_sinumerik_blocks() {
    let program = "G0 A90 C=IC(45)\nG91 A-30 C=AC(10)\nM30\n";
    let ends = ends(&run(program, &five_axis(1)));
    assert_eq!([ends[0][3], ends[0][5]], [90.0, 45.0]);
    assert_eq!([ends[1][3], ends[1][5]], [60.0, 10.0]);
}

/// The default machine file has one spindle; a spindle it does not declare is an alarm naming
/// it and the machine file's count.
#[test]
fn a_spindle_the_machine_lacks_is_an_alarm_naming_it() {
    let default = Machine::from_toml(DEFAULT_MACHINE_TOML).unwrap();
    assert_eq!(default.spindle.count, 1);
    for word in [
        "S2=780",
        "M2=4",
        "SPOS[2]=90",
        "SPOSA[3]=0",
        "LIMS[2]=450",
        "WAITS(2)",
    ] {
        let alarm = error(&format!("N10 {word}\n"), &machine());
        assert_eq!(alarm.code, AlarmCode::AxisNotOnMachine, "{word}");
        assert!(
            alarm.message.contains("no spindle") && alarm.message.contains("declares 1 spindle"),
            "{word}: {}",
            alarm.message
        );
    }
    let text = DEFAULT_MACHINE_TOML.replace("count = 1", "count = 2");
    let two = Machine::from_toml(&text).unwrap();
    assert_eq!(two.spindle.count, 2);
}

/// On a machine with two spindles, spindle 2's words leave the master spindle alone
/// (sinumerik-a/21): S300 M3 stays the master's, and S1=, M1= address the master too.
#[test]
fn the_second_spindle_leaves_the_master_spindle_alone() {
    let segments = run(
        "N10 S300 M3 S2=780 M2=4\nN20 SPOS[2]=90 SPOSA[2]=IC(90) WAITS(2)\nN30 S1=500 M1=4\nM30\n",
        &five_axis(2),
    );
    let spindle = spindle_events(&segments);
    assert_eq!(
        spindle,
        [
            (300.0, SpindleState::Clockwise),
            (500.0, SpindleState::CounterClockwise)
        ]
    );
}

/// G26 S1400 S2=350 (sinumerik-a/36): the master's limit is 1400 rpm whatever spindle 2's;
/// S2000 then turns the master at 1400.
#[test]
fn g26_limits_each_spindle_by_its_number() {
    let segments = run("G26 S2=350 S1400\nS2000 M3\nM30\n", &five_axis(2));
    let rpm = spindle_events(&segments).first().map(|e| e.0);
    assert_eq!(rpm, Some(1400.0));
}

/// SPOS=IC(90) turns the master spindle from its last position: SPOSA=DC(0), IC(90), AC(180)
/// and IC(90) (sinumerik-a/47) are each an oriented stop.
#[test]
fn master_spindle_positions_are_oriented_stops() {
    let segments = run(
        "SPOSA=DC(0)\nWAITS\nSPOS=IC(90)\nSPOS=AC(180)\nSPOS[1]=IC(90)\nM30\n",
        &machine(),
    );
    let oriented = spindle_events(&segments)
        .iter()
        .filter(|e| e.1 == SpindleState::Oriented)
        .count();
    assert_eq!(oriented, 4);
}

/// M2=70 puts spindle 2 into axis mode: a note (vcnc does not tie a spindle to an axis), and
/// the program's C words move the machine file's C (sinumerik-a/46): X50 C180 at F500.
#[test]
fn a_spindle_in_axis_mode_is_a_note_and_its_axis_moves_by_name() {
    let run = collect(run_str("M2=70\nG1 X50 C180 F500\nM30\n", &five_axis(2)));
    assert!(run.error().is_none(), "{:#?}", run.alarms);
    assert!(
        run.alarms
            .iter()
            .any(|a| a.code == AlarmCode::KeptAsState && a.message.contains("M2=70")),
        "{:#?}",
        run.alarms
    );
    let end = ends(&run.segments)[0];
    assert_eq!([end[0], end[5]], [50.0, 180.0]);
}

/// S0= is the master spindle's speed (PGsl 6.1): 600 rpm, M3 clockwise; a machine file may
/// declare up to five spindles (L1845), not six.
#[test]
fn s0_addresses_the_master_and_a_machine_has_at_most_five_spindles() {
    let segments = run("S0=600 M3\nM30\n", &machine());
    assert_eq!(
        spindle_events(&segments),
        [(600.0, SpindleState::Clockwise)]
    );
    assert!(Machine::from_toml(&DEFAULT_MACHINE_TOML.replace("count = 1", "count = 5")).is_ok());
    let refused = Machine::from_toml(&DEFAULT_MACHINE_TOML.replace("count = 1", "count = 6"));
    assert!(refused.unwrap_err().to_string().contains("spindle.count"));
}

/// A block held for the rounding at its end moves before a positioning axis of a later block:
/// G1 X10 RND=2 waits for its next path block, but POS[Z]=5 ends the contour, so X10 comes
/// first (without its rounding), then Z5, then Y10.
#[test]
fn a_positioning_axis_ends_a_held_contour_first() {
    let program = "G1 X10 F100 RND=2\nPOS[Z]=5\nY10\nM30\n";
    let ends: Vec<[f64; 3]> = ends(&run(program, &machine()))
        .iter()
        .map(|p| [p[0], p[1], p[2]])
        .collect();
    assert_eq!(
        ends,
        [[10.0, 0.0, 0.0], [10.0, 0.0, 5.0], [10.0, 10.0, 5.0]]
    );
}

/// FA names a spindle as S2 or SPI(2) (PGsl 7.5); on a machine with one spindle both alarm
/// naming spindle 2, and FA[S1] is the master's.
#[test]
fn fa_names_spindles_as_s_n_or_spi() {
    run("FA[S2]=100 FA[SPI(2)]=200 FA[S1]=50\nM30\n", &five_axis(2));
    for word in ["FA[S2]=100", "FA[SPI(2)]=100"] {
        let alarm = error(&format!("{word}\n"), &machine());
        assert_eq!(alarm.code, AlarmCode::AxisNotOnMachine, "{word}");
        assert!(alarm.message.contains("no spindle 2"), "{}", alarm.message);
    }
}
