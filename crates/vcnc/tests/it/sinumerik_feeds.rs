//! SINUMERIK feeds and dynamics beyond the path's own (docs/SINUMERIK.md 10.5-10.7), with the
//! figures worked out by hand: the axes' dynamic limits VELOLIMA, ACCLIMA, JERKLIMA and the
//! electronic gear EGON/EGOFS (PGsl 14.7.2, L10555-10623); revolutional feeds derived from
//! another spindle or a rotary axis, FPR, FPRAON, FPRAOF (PGsl 7.5, L3169-3311); the
//! handwheel's override of a positioning axis, FDA (PGsl 7.8, L3443-3593).

use vcnc::interp::sinumerik::run_str;
use vcnc::machine::AxisKind;
use vcnc::plan::{PlanOptions, Planner, TimedItem};
use vcnc::{Alarm, AlarmCode, Axis, Machine, ProfileName, Segment, SegmentKind};

use crate::common::collect;
use crate::common::plan::Limits;

/// A SINUMERIK machine whose X, Y, Z and the linear axis AX4 (the 4th slot) all go up to
/// `speed` mm/s at `acceleration` mm/s^2, without a jerk limit.
fn machine_with_ax4(speed: f64, acceleration: f64) -> Machine {
    let limits = Limits {
        speed,
        acceleration,
        ..Limits::default()
    };
    let mut machine = crate::common::plan::machine(&limits)
        .with_profile(ProfileName::Sinumerik)
        .expect("the test machine fits the SINUMERIK profile");
    let config = machine.axes[0].clone().expect("X");
    let axis = machine
        .add_axis("ax4", Some(AxisKind::Linear), config)
        .expect("AX4 fits the machine");
    assert_eq!(axis, Axis::A);
    machine
}

/// The segments of a program that must run to its end.
fn run(text: &str, machine: &Machine) -> Vec<Segment> {
    let run = collect(run_str(text, machine));
    assert!(run.error().is_none(), "{text}\n{:#?}", run.alarms);
    run.segments
}

fn error(text: &str, machine: &Machine) -> Alarm {
    collect(run_str(text, machine))
        .error()
        .cloned()
        .unwrap_or_else(|| panic!("no error in\n{text}"))
}

/// The program's time as the planner makes it, seconds.
fn seconds(text: &str, machine: &Machine) -> f64 {
    let mut end = 0.0;
    for item in Planner::new(run_str(text, machine), machine, PlanOptions::default()) {
        match item {
            Ok(TimedItem::Segment(timed)) => end = timed.t + timed.dt,
            Ok(TimedItem::Frame(_) | TimedItem::Warning(_)) => {}
            Err(alarm) => panic!("{text}: {alarm}"),
        }
    }
    end
}

/// The axis-limit events: axis, velocity, acceleration, jerk (fractions).
fn limit_events(segments: &[Segment]) -> Vec<(Axis, [f64; 3])> {
    segments
        .iter()
        .filter_map(|s| match s.kind {
            SegmentKind::AxisLimits {
                axis,
                velocity,
                acceleration,
                jerk,
            } => Some((axis, [velocity, acceleration, jerk])),
            _ => None,
        })
        .collect()
}

fn close(actual: f64, expected: f64) -> bool {
    (actual - expected).abs() <= 1e-9 * expected.abs().max(1.0)
}

#[test]
fn velolima_acclima_jerklima_correct_the_axis_limits_in_the_stream() {
    // b/80: 75 %, 50 %, 50 % of the machine data; each correction is an event with all three.
    let machine = machine_with_ax4(100.0, 1000.0);
    let segments = run(
        "VELOLIMA[AX4]=75\nACCLIMA[AX4]=50\nJERKLIMA[AX4]=50\nM30\n",
        &machine,
    );
    assert_eq!(
        limit_events(&segments),
        vec![
            (Axis::A, [0.75, 1.0, 1.0]),
            (Axis::A, [0.75, 0.5, 1.0]),
            (Axis::A, [0.75, 0.5, 0.5]),
        ]
    );
    // Several corrections of one axis in a block make one event.
    let segments = run("VELOLIMA[AX4]=75 ACCLIMA[AX4]=50\nM30\n", &machine);
    assert_eq!(limit_events(&segments), vec![(Axis::A, [0.75, 0.5, 1.0])]);
}

#[test]
fn acclima_50_makes_a_short_move_of_the_axis_take_sqrt_2_as_long() {
    // 10 mm at 1000 mm/s^2 never reaches 100 mm/s: accelerate half way, brake half way,
    // t = 2 sqrt(d / a) = 2 sqrt(10 / 1000) = 0.2 s (peak 100 mm/s, just at the limit).
    // ACCLIMA 50 %: a = 500, t = 2 sqrt(10 / 500) = 0.28284 s, sqrt(2) as long.
    let machine = machine_with_ax4(200.0, 1000.0);
    let plain = seconds("G0 AX4=10\nM30\n", &machine);
    let reduced = seconds("ACCLIMA[AX4]=50\nG0 AX4=10\nM30\n", &machine);
    assert!(close(plain, 0.2), "{plain}");
    assert!(close(reduced, 2.0 * (10.0_f64 / 500.0).sqrt()), "{reduced}");
    // X keeps its own limits.
    let x = seconds("ACCLIMA[AX4]=50\nG0 X10\nM30\n", &machine);
    assert!(close(x, 0.2), "{x}");
}

#[test]
fn velolima_50_makes_a_long_move_cruise_at_half_speed() {
    // 100 mm at up to 100 mm/s, 1000 mm/s^2: t = d / v + v / a = 1 + 0.1 = 1.1 s.
    // VELOLIMA 50 %: v = 50 mm/s, t = 2 + 0.05 = 2.05 s; at 100 % again: 1.1 s.
    let machine = machine_with_ax4(100.0, 1000.0);
    let plain = seconds("G0 AX4=100\nM30\n", &machine);
    let reduced = seconds("VELOLIMA[AX4]=50\nG0 AX4=100\nM30\n", &machine);
    let restored = seconds(
        "VELOLIMA[AX4]=50\nVELOLIMA[AX4]=100\nG0 AX4=100\nM30\n",
        &machine,
    );
    assert!(close(plain, 1.1), "{plain}");
    assert!(close(reduced, 2.05), "{reduced}");
    assert!(close(restored, 1.1), "{restored}");
    // A feed move of AX4 too: F6000 is 100 mm/s, capped at 50.
    let feed = seconds("VELOLIMA[AX4]=50\nG1 AX4=100 F6000\nM30\n", &machine);
    assert!(close(feed, 2.05), "{feed}");
}

#[test]
fn a_correction_of_an_axis_the_machine_lacks_or_out_of_range_is_an_alarm() {
    let machine = machine_with_ax4(100.0, 1000.0);
    let alarm = error("ACCLIMA[AX5]=50\n", &machine);
    assert_eq!(alarm.code, AlarmCode::AxisNotOnMachine, "{alarm}");
    let alarm = error("VELOLIMA[AX4]=0\n", &machine);
    assert_eq!(alarm.code, AlarmCode::ValueOutOfRange, "{alarm}");
    let alarm = error("JERKLIMA[AX4]=250\n", &machine);
    assert_eq!(alarm.code, AlarmCode::ValueOutOfRange, "{alarm}");
}

#[test]
fn egon_couples_and_a_move_of_the_coupled_axes_is_outside_the_product() {
    // b/81: the gear is state; moving the follower or its leader stops with V022, other
    // axes move, and EGOFS frees both.
    let machine = machine_with_ax4(100.0, 1000.0);
    let couple = "ACCLIMA[AX4]=70\nVELOLIMA[AX4]=50\nEGON(AX4,\"FINE\",X,1,2)\n";
    for moving in ["G0 X10", "G0 AX4=5", "POS[AX4]=5"] {
        let alarm = error(&format!("{couple}{moving}\n"), &machine);
        assert_eq!(alarm.code, AlarmCode::NotInProduct, "{moving}: {alarm}");
        assert!(alarm.message.contains("AX4"), "{alarm}");
    }
    let segments = run(
        &format!("{couple}G0 Y10\nEGOFS(AX4)\nG0 X10 AX4=5\nM30\n"),
        &machine,
    );
    let ends: Vec<[f64; 6]> = segments
        .iter()
        .filter_map(Segment::motion)
        .map(|m| m.to.0)
        .collect();
    assert_eq!(
        ends,
        vec![
            [0.0, 10.0, 0.0, 0.0, 0.0, 0.0],
            [10.0, 10.0, 0.0, 5.0, 0.0, 0.0]
        ]
    );
    // EGOFS with a leader ends that leader's part: the coupling to X is gone.
    run(&format!("{couple}EGOFS(AX4,X)\nG0 X10\nM30\n"), &machine);
}

/// The SINUMERIK default machine with rotary axis A and `spindles` spindles.
fn machine_with_a(spindles: u32) -> Machine {
    let mut machine = crate::common::sinumerik::machine();
    machine.axes[Axis::A.index()] = Some(crate::common::rotary_axis());
    machine.spindle.count = spindles;
    machine
}

/// The feed of every cutting move, mm/min (None where it cannot be known).
fn feeds(segments: &[Segment]) -> Vec<Option<f64>> {
    segments
        .iter()
        .filter_map(|s| match &s.kind {
            SegmentKind::Line { feed, .. } | SegmentKind::Arc { feed, .. } => {
                Some(feed.mm_per_min(s.length()))
            }
            _ => None,
        })
        .collect()
}

#[test]
fn fpr_of_another_spindle_makes_g95_feeds_per_its_revolution() {
    // Master spindle S100, spindle 2 at 400 rpm. G95 F0.5: 0.5 x 100 = 50 mm/min; after
    // FPR(S2) 0.5 x 400 = 200; S2=800 in force from the next block: 400; FPR(SPI(1)) brings
    // the master spindle back: 50.
    let machine = machine_with_a(2);
    let segments = run(
        "S100 M3\nS2=400 M2=3\nG95 G1 X10 F0.5\nFPR(S2)\nX20\nS2=800\nX30\nFPR(SPI(1))\nX40\nM30\n",
        &machine,
    );
    assert_eq!(
        feeds(&segments),
        vec![Some(50.0), Some(200.0), Some(400.0), Some(50.0)]
    );
}

#[test]
fn fpr_of_a_rotary_axis_takes_its_fa_as_its_speed_and_the_planner_times_it() {
    // FA[A]=720 deg/min is 2 rev/min: G95 F100 is 200 mm/min. 100 mm at 200 mm/min
    // (v = 3.3333 mm/s) on the default machine's X (2000 mm/s^2, 50000 mm/s^3): the speed
    // is reached at a peak acceleration sqrt(v j) = 408 mm/s^2, below the limit, so each
    // ramp is a pure jerk one of 2 sqrt(v / j) = 0.016330 s covering half its time at v:
    // t = d / v + 2 sqrt(v / j) = 30 + 0.016330 = 30.016330 s.
    let machine = machine_with_a(1);
    let program = "FA[A]=720\nFPR(A)\nG95 G1 X100 F100\nM30\n";
    assert_eq!(feeds(&run(program, &machine)), vec![Some(200.0)]);
    let t = seconds(program, &machine);
    let v = 100.0 / 30.0;
    assert!(
        (t - (30.0 + 2.0 * (v / 50000.0_f64).sqrt())).abs() < 1e-6,
        "{t}"
    );
    // Without an FA, A has no speed: the feed is unknown, as G95 without S.
    let segments = run("FPR(A)\nS100 M3\nG95 G1 X10 F1\nM30\n", &machine);
    assert_eq!(feeds(&segments), vec![None]);
}

#[test]
fn fpr_of_a_linear_axis_or_a_missing_spindle_is_an_alarm() {
    let machine = machine_with_a(2);
    let alarm = error("FPR(Y)\n", &machine);
    assert_eq!(alarm.code, AlarmCode::WordNotAllowed, "{alarm}");
    let alarm = error("FPR(S3)\n", &machine);
    assert_eq!(alarm.code, AlarmCode::AxisNotOnMachine, "{alarm}");
    let alarm = error("FPRAON(X,S3)\n", &machine);
    assert_eq!(alarm.code, AlarmCode::AxisNotOnMachine, "{alarm}");
}

#[test]
fn fpraon_makes_a_positioning_axis_fa_per_revolution_until_fpraof() {
    // S20: FA[X]=5 with FPRAON(X) is 5 x 20 = 100 mm/min; with FPRAON(X,S2) and S2=30,
    // 150 mm/min; after FPRAOF(X) FA is 5 mm/min again.
    let machine = machine_with_a(2);
    let segments = run(
        "S20 M3\nS2=30\nFPRAON(X)\nPOS[X]=10 FA[X]=5\nFPRAON(X,S2)\nPOS[X]=20\nFPRAOF(X)\nPOS[X]=21\nM30\n",
        &machine,
    );
    assert_eq!(feeds(&segments), vec![Some(100.0), Some(150.0), Some(5.0)]);
}

#[test]
fn fda_zero_moves_the_axis_at_its_fa_with_a_note_and_fda_sets_one_block_feed() {
    let machine = machine_with_a(1);
    let run = collect(run_str(
        "FA[X]=300\nPOS[X]=90 FDA[X]=0\nPOS[X]=100 FDA[X]=200\nPOS[X]=110\nM30\n",
        &machine,
    ));
    assert!(run.error().is_none(), "{:?}", run.alarms);
    assert_eq!(
        feeds(&run.segments),
        vec![Some(300.0), Some(200.0), Some(300.0)]
    );
    assert!(
        run.alarms.iter().any(|a| a.code == AlarmCode::KeptAsState
            && a.message.contains("FDA[X]=0")
            && a.message.contains("handwheel")),
        "{:?}",
        run.alarms
    );
    let alarm = error("FDA[X]=100\n", &machine);
    assert_eq!(alarm.code, AlarmCode::WordNotAllowed, "{alarm}");
}

/// The master spindle's events: speed (rounded to 0.01 rpm) and state.
fn spindle_events(segments: &[Segment]) -> Vec<(f64, vcnc::motion::SpindleState)> {
    segments
        .iter()
        .filter_map(|s| match s.kind {
            SegmentKind::Spindle { speed, state } => Some(((speed * 100.0).round() / 100.0, state)),
            _ => None,
        })
        .collect()
}

/// The tools of examples A-26 and A-27 (PGsl 6.2, L1994-2073): T2 "WZ2" D1 r 5, T8 "WZ8" D1 r 9
/// and D4 r 7, named and sized by the program as the manual's blocks do.
const TOOLS: &str = "$TC_TP2[2]=\"WZ2\"\n$TC_DP6[2,1]=5.0\n$TC_TP2[8]=\"WZ8\"\n$TC_DP6[8,1]=9.0\n$TC_DP6[8,4]=7.0\n";

fn machine_with_spindles(spindles: u32, toolholders: u32, cutting_edge_default: i32) -> Machine {
    let mut machine = crate::common::sinumerik::machine();
    machine.spindle.count = spindles;
    let settings = machine.profile.sinumerik.as_mut().expect("SINUMERIK");
    settings.toolholder_management = toolholders;
    settings.cutting_edge_default = cutting_edge_default;
    machine
}

#[test]
fn setms_makes_another_spindle_the_master_of_s_m_and_svc() {
    // Ex. A-27 (L2037-2073), S = SVC 1000 / (2 pi r): 100 at r 5 is 3183.10 on spindle 1;
    // SETMS(3) gives the stream spindle 3 (stopped); 150 and 200 at r 5 are 4774.65 and
    // 6366.20 (T="WZ8" only preselects: WZ2's D1 stays, the speed again); M6 with D4 (MD20270
    // = 4, r 7) and SVC=50: 1136.82; D1 (r 9): 884.19. SVC[1]=300 at r 9 turns spindle 1 at
    // 5305.16, which $P_S[1] reads.
    use vcnc::motion::SpindleState::{Clockwise, CounterClockwise, Stopped};
    let machine = machine_with_spindles(3, 0, 4);
    let program = format!(
        "{TOOLS}$TC_MPP1[9998,1]=2\n$TC_MPP5[9998,1]=1\n$TC_MPP1[9998,2]=2\n$TC_MPP5[9998,2]=3\n\
         SETMS(1)\nT=\"WZ2\" M6 D1\nG1 G94 F1000 M3 SVC=100\nSETMS (3)\nM4 SVC=150\nT=\"WZ8\"\n\
         M4 SVC=200\nM6\nSVC=50\nD1\nSVC[1]=300\nG0 X=$P_S[1]/10 Y=$P_S[3]/10\nM30\n"
    );
    let segments = run(&program, &machine);
    assert_eq!(
        spindle_events(&segments),
        vec![
            (3183.10, Clockwise),
            (0.0, Stopped),
            (4774.65, CounterClockwise),
            (4774.65, CounterClockwise),
            (6366.20, CounterClockwise),
            (1136.82, CounterClockwise),
            (884.19, CounterClockwise),
        ]
    );
    let end = segments
        .iter()
        .rev()
        .find_map(Segment::motion)
        .unwrap()
        .to
        .0;
    assert!((end[0] - 530.516477).abs() < 1e-6, "{end:?}");
    assert!((end[1] - 88.419413).abs() < 1e-6, "{end:?}");
}

#[test]
fn under_toolholders_svc_turns_the_spindle_of_the_active_offsets_toolholder() {
    // Ex. A-26 (L1994-2024), MD20124 = 2, MD20270 = -2: toolholder 1 on spindle 3, 4 on 6.
    // S3 = 100000 / (2 pi 5) = 3183.10 at N120 (read by $P_S[3] there), 1591.55 after the
    // change to WZ8 (WZ2's offset stays), then D4 (r 7) in toolholder 4: S6 = 300000 /
    // (2 pi 7) = 6820.93. The master spindle 1 never turns: no spindle event.
    let machine = machine_with_spindles(6, 2, -2);
    let program = format!(
        "$TC_MPP1[9998,1]=2\n$TC_MPP5[9998,1]=1\n$TC_MPP_SP[9998,1]=3\n\
         $TC_MPP1[9998,2]=2\n$TC_MPP5[9998,2]=4\n$TC_MPP_SP[9998,2]=6\n{TOOLS}\
         SETMTH(1)\nT=\"WZ2\" M6 D1\nG1 G94 F1000 M3=3 SVC=100\nG0 X=$P_S[3]/10\n\
         SETMTH(4)\nT=\"WZ8\"\nM6\nSVC=50\nG0 X=$P_S[3]/10\nD4\nSVC=300\nG0 X=$P_S[6]/10\nM30\n"
    );
    let segments = run(&program, &machine);
    assert_eq!(spindle_events(&segments), vec![]);
    let xs: Vec<f64> = segments
        .iter()
        .filter_map(Segment::motion)
        .map(|m| m.to.0[0])
        .collect();
    let expected = [318.309886, 159.154943, 682.092613];
    assert!(
        xs.len() == 3 && xs.iter().zip(expected).all(|(&x, e)| (x - e).abs() < 1e-6),
        "{xs:?}"
    );
}

#[test]
fn setms_on_one_spindle_is_a_note_and_a_missing_spindle_an_alarm() {
    // One spindle: SETMS(2) is accepted and ignored, S addresses spindle 1.
    let machine = machine_with_spindles(1, 0, 1);
    let segments = run("SETMS(2)\nS300 M3\nM30\n", &machine);
    assert_eq!(
        spindle_events(&segments),
        vec![(300.0, vcnc::motion::SpindleState::Clockwise)]
    );
    let machine = machine_with_spindles(3, 0, 1);
    let alarm = error("SETMS(4)\n", &machine);
    assert_eq!(alarm.code, AlarmCode::AxisNotOnMachine, "{alarm}");
    // A real magazine's data stays outside the product.
    let alarm = error("$TC_MPP1[1,1]=1\n", &machine);
    assert_eq!(alarm.code, AlarmCode::NotInProduct, "{alarm}");
}
