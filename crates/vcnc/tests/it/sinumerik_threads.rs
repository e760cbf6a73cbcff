//! SINUMERIK threads beyond G33 and the turning and grinding words around them, with leads,
//! feeds, times and speeds worked out by hand: G34/G35 (PGsl 9.11, seed 002 L6317-6381), the
//! run-in and run-out paths DITS/DITE (PGsl 9.10.2, L6260-6315), `$AC_LIFTFAST` (PGsl 9.14,
//! L6594-6747) and the grinding wheel's peripheral speed GWPSON/GWPSOF (PGsl 6.4, L2329-2401).
//! docs/SINUMERIK.md 10.8 to 10.10 are the model.

use vcnc::interp::sinumerik::run_str;
use vcnc::machine::ToolEdge;
use vcnc::plan::{PlanOptions, Planner, TimedItem};
use vcnc::{Alarm, AlarmCode, Machine, ProfileName, Segment, SegmentKind};

use crate::common::collect;
use crate::common::plan::{machine as limited_machine, Limits};
use crate::common::sinumerik::machine;

/// The segments of a program that must run to its end.
fn run(text: &str) -> Vec<Segment> {
    let run = collect(run_str(text, &machine()));
    assert!(run.error().is_none(), "{text}\n{:#?}", run.alarms);
    run.segments
}

fn error(text: &str) -> Alarm {
    let run = collect(run_str(text, &machine()));
    run.error()
        .cloned()
        .unwrap_or_else(|| panic!("no error in\n{text}"))
}

/// The path speed of every feed motion, mm/min.
fn feeds(segments: &[Segment]) -> Vec<f64> {
    segments
        .iter()
        .filter_map(|s| match &s.kind {
            SegmentKind::Line { feed, .. } | SegmentKind::Arc { feed, .. } => {
                feed.mm_per_min(s.length())
            }
            _ => None,
        })
        .collect()
}

/// The end points of the moves, X Y Z.
fn ends(segments: &[Segment]) -> Vec<[f64; 3]> {
    segments
        .iter()
        .filter_map(Segment::motion)
        .map(|m| [m.to.0[0], m.to.0[1], m.to.0[2]])
        .collect()
}

fn assert_close(actual: f64, expected: f64, tolerance: f64) {
    assert!(
        (actual - expected).abs() <= tolerance,
        "{actual} is not {expected} (within {tolerance})"
    );
}

#[test]
fn g35_cuts_at_the_mean_of_its_start_and_end_leads() {
    // ka = 2, F = 0.05, 30 mm: ke^2 = 4 - 2 * 0.05 * 30 = 1, ke = 1; (2 + 1) / 2 = 1.5 mm/rev at
    // 100 rpm is 150 mm/min (20 revolutions, 12 s, for 30 mm).
    let segments = run("M3 S100\nG0 X10 Z0\nG35 Z-30 K2 F0.05\nG0 X20\nM30\n");
    assert_eq!(
        ends(&segments),
        vec![[10.0, 0.0, 0.0], [10.0, 0.0, -30.0], [20.0, 0.0, -30.0]]
    );
    assert_eq!(feeds(&segments).len(), 1);
    assert_close(feeds(&segments)[0], 150.0, 1e-9);
}

#[test]
fn g34_cuts_at_the_mean_of_its_start_and_end_leads() {
    // ka = 1, F = 0.05, 30 mm: ke^2 = 1 + 3 = 4, ke = 2; mean 1.5 mm/rev, 150 mm/min at 100 rpm.
    let segments = run("M3 S100\nG0 X10 Z0\nG34 Z-30 K1 F0.05\nM30\n");
    assert_close(feeds(&segments)[0], 150.0, 1e-9);
}

#[test]
fn a_taper_thread_of_variable_lead_takes_its_lead_along_the_leading_axis() {
    // Z leads (30 mm against X's 4): the mean lead 1.5 along Z becomes 1.5 * 30.2655 / 30 along
    // the path, sqrt(4^2 + 30^2) = 30.2655 mm; at 100 rpm 151.3275 mm/min, 20 revolutions still.
    let segments = run("M3 S100\nG0 X10 Z0\nG35 X14 Z-30 K2 F0.05\nM30\n");
    let path = (16.0f64 + 900.0).sqrt();
    assert_close(feeds(&segments)[0], 150.0 * path / 30.0, 1e-9);
}

#[test]
fn the_planner_times_a_g35_block_by_its_revolutions() {
    // 20 revolutions at 100 rpm (above) take 12 s; at 1e6 mm/s^2 the ramps to 2.5 mm/s add
    // under a microsecond.
    let mut machine = limited_machine(&Limits {
        acceleration: 1.0e6,
        ..Limits::default()
    })
    .with_profile(ProfileName::Sinumerik)
    .unwrap();
    machine.start = [10.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    let seconds = thread_seconds("M3 S100\nG35 Z-30 K2 F0.05\nM30\n", &machine);
    assert_close(seconds, 12.0, 1e-3);
}

/// The time of the program's feed motions, seconds, as the planner gives it.
fn thread_seconds(text: &str, machine: &Machine) -> f64 {
    Planner::new(run_str(text, machine), machine, PlanOptions::default())
        .map(|item| match item {
            Ok(TimedItem::Segment(timed)) => match timed.segment.kind {
                SegmentKind::Line { .. } => timed.dt,
                _ => 0.0,
            },
            Ok(_) => 0.0,
            Err(alarm) => panic!("{alarm:?}"),
        })
        .sum()
}

#[test]
fn g35_whose_lead_runs_out_before_the_end_point_is_an_alarm() {
    // ka = 2, F = 0.05: the lead is 0 after 2^2 / (2 * 0.05) = 40 mm, short of 50.
    let alarm = error("M3 S100\nG35 Z-50 K2 F0.05\nM30\n");
    assert_eq!(alarm.code, AlarmCode::ValueOutOfRange);
    assert!(alarm.message.contains("G35"), "{}", alarm.message);
    assert!(alarm.message.contains("40.000 mm"), "{}", alarm.message);
}

#[test]
fn g34_without_its_lead_change_is_an_alarm() {
    let alarm = error("M3 S100\nG34 Z-50 K2\nM30\n");
    assert_eq!(alarm.code, AlarmCode::MissingValue);
    assert!(alarm.message.contains("G34"), "{}", alarm.message);
}

#[test]
fn the_f_of_a_g35_block_is_not_the_path_feed() {
    // F0.05 is the lead change; the G1 after the thread keeps F200 (mm/min, G94).
    let segments = run("M3 S100\nG1 X10 F200\nG35 Z-30 K2 F0.05\nG1 X20\nM30\n");
    let feeds = feeds(&segments);
    assert_eq!(feeds.len(), 3);
    assert_close(feeds[0], 200.0, 1e-9);
    assert_close(feeds[2], 200.0, 1e-9);
}

#[test]
fn p_gg_reads_g34_and_g35_as_members_16_and_17() {
    // The tables' numbers of group 1 (sinumerik-tables.md: G34 16, G35 17), made positions.
    let segments = run(
        "M3 S100\nG34 Z-1 K1 F0.01\nR1=$P_GG[1]\nG35 Z-2 K1 F0.01\nR2=$P_GG[1]\nG1 X=R1 Y=R2 F100\nM30\n",
    );
    assert_eq!(ends(&segments).last(), Some(&[16.0, 17.0, -2.0]));
}

#[test]
fn dits_and_dite_leave_the_thread_at_its_lead_times_the_speed() {
    // b/33's blocks: 5 mm/rev at 500 rpm is 2500 mm/min over Z100 -> Z50, whatever the ramps.
    let segments = run(
        "G90 G0 Z100 X10 SOFT M3 S500\nG33 Z50 K5 SF=180 DITS=1 DITE=3\nG0 X20\nDITS=-1 DITE=0\nM30\n",
    );
    assert_eq!(
        ends(&segments),
        vec![[10.0, 0.0, 100.0], [10.0, 0.0, 50.0], [20.0, 0.0, 50.0]]
    );
    assert_eq!(feeds(&segments), vec![2500.0]);
}

#[test]
fn a_ramp_path_below_minus_one_or_between_minus_one_and_zero_is_an_alarm() {
    for word in ["DITS=-2", "DITE=-0.5"] {
        let alarm = error(&format!("M3 S100\nG33 Z-10 K1 {word}\nM30\n"));
        assert_eq!(alarm.code, AlarmCode::ValueOutOfRange, "{word}");
        assert!(alarm.message.contains(&word[..4]), "{}", alarm.message);
    }
}

#[test]
fn a_thread_block_without_its_lead_keeps_the_last_threads() {
    // N2 leaves K out (b/42's N71): K2 at 300 rpm stays 600 mm/min.
    let segments = run("M3 S300\nG33 Z-10 K2\nG33 Z-20\nM30\n");
    assert_eq!(feeds(&segments), vec![600.0, 600.0]);
}

#[test]
fn ac_liftfast_reads_zero_as_no_retraction_happens() {
    // 0 + 7: the flag read into a position.
    let segments = run("$AC_LIFTFAST=0\nR1=$AC_LIFTFAST+7\nG0 X=R1\nM30\n");
    assert_eq!(ends(&segments), vec![[7.0, 0.0, 0.0]]);
}

#[test]
fn a_thread_guarded_by_ac_liftfast_runs_once() {
    // b/42's loop: without an interruption the jump back is not taken; the thread's two blocks
    // move once (Z5, X10, Z30, then X15 Z55).
    let segments = run(
        "M3 S500 G90 G18\nAGAIN:\n$AC_LIFTFAST=0\nG0 Z5\nX10\nG33 Z30 K5 LFON DILF=10 LFWP ALF=7\nG33 Z55 X15\nG1\nIF $AC_LIFTFAST GOTOB AGAIN\nM30\n",
    );
    assert_eq!(
        ends(&segments),
        vec![
            [0.0, 0.0, 5.0],
            [10.0, 0.0, 5.0],
            [10.0, 0.0, 30.0],
            [15.0, 0.0, 55.0]
        ]
    );
}

#[test]
fn ac_liftfast_set_to_anything_but_zero_is_an_alarm() {
    let alarm = error("$AC_LIFTFAST=1\nM30\n");
    assert_eq!(alarm.code, AlarmCode::ValueOutOfRange);
    assert!(alarm.message.contains("$AC_LIFTFAST"), "{}", alarm.message);
}

/// The SINUMERIK test machine with two spindles, T changing the tool at once, and the tools
/// `(t, type, radius)`.
fn grinder(tools: &[(u32, u32, f64)]) -> Machine {
    let mut machine = machine();
    machine.spindle.count = 2;
    if let Some(settings) = machine.profile.sinumerik.as_mut() {
        settings.t_changes_tool = true;
    }
    for &(t, tool_type, radius) in tools {
        machine.tools.push(ToolEdge {
            t,
            name: None,
            d: 1,
            tool_type,
            length: 0.0,
            length2: 0.0,
            length3: 0.0,
            radius,
            teeth: None,
        });
    }
    machine
}

/// The master spindle's speeds at its events, rpm.
fn speeds(text: &str, machine: &Machine) -> Vec<f64> {
    let run = collect(run_str(text, machine));
    assert!(run.error().is_none(), "{text}\n{:#?}", run.alarms);
    run.segments
        .iter()
        .filter_map(|s| match s.kind {
            SegmentKind::Spindle { speed, .. } => Some(speed),
            _ => None,
        })
        .collect()
}

fn grinder_error(text: &str, machine: &Machine) -> Alarm {
    let run = collect(run_str(text, machine));
    run.error()
        .cloned()
        .unwrap_or_else(|| panic!("no error in\n{text}"))
}

#[test]
fn s_under_gwps_is_the_wheels_peripheral_speed() {
    // 30 m/s on a wheel of radius 100 mm ($TC_DP6, $TC_TPG9 = 6): 30 * 60000 / (2 pi 100) =
    // 2864.789 rpm; after GWPSOF, S1200 is rpm again.
    let machine = grinder(&[(1, 400, 100.0)]);
    let speeds = speeds(
        "$TC_TPG1[1]=1\n$TC_TPG9[1]=6\nT1 D1\nM3 S500\nGWPSON\nS30\nGWPSOF\nS1200\nM30\n",
        &machine,
    );
    assert_eq!(speeds.len(), 3, "{speeds:?}");
    assert_close(speeds[0], 500.0, 1e-9);
    assert_close(
        speeds[1],
        1_800_000.0 / (2.0 * std::f64::consts::PI * 100.0),
        1e-9,
    );
    assert_close(speeds[2], 1200.0, 1e-9);
}

#[test]
fn tpg9_names_the_edge_parameter_that_is_the_wheels_radius() {
    // $TC_TPG9 = 3: the radius is length 1, $TC_DP3 = 250 mm; 25 m/s is 25 * 60000 /
    // (2 pi 250) = 954.930 rpm. G4 S2 stays two revolutions (no speed event).
    let machine = grinder(&[(1, 401, 5.0)]);
    let speeds = speeds(
        "$TC_DP3[1,1]=250\n$TC_TPG1[1]=1\n$TC_TPG9[1]=3\nT1 D1\nM3 S100\nGWPSON(1)\nS1=25\nG4 S2\nM30\n",
        &machine,
    );
    assert_eq!(speeds.len(), 2, "{speeds:?}");
    assert_close(
        speeds[1],
        1_500_000.0 / (2.0 * std::f64::consts::PI * 250.0),
        1e-9,
    );
}

#[test]
fn p_gwps_says_where_gwps_is_on() {
    // $P_GWPS[2] TRUE (1) after GWPSON(5) with T5 on spindle 2, FALSE (0) after GWPSOF(5).
    let machine = grinder(&[(5, 410, 80.0)]);
    let run = collect(run_str(
        "$TC_TPG1[5]=2\n$TC_TPG9[5]=6\nGWPSON(5)\nR1=$P_GWPS[2]\nR2=$P_GWPS[1]\nGWPSOF(5)\nR3=$P_GWPS[2]\nG0 X=R1 Y=R2 Z=R3+7\nM30\n",
        &machine,
    ));
    assert!(run.error().is_none(), "{:#?}", run.alarms);
    assert_eq!(ends(&run.segments), vec![[1.0, 0.0, 7.0]]);
}

#[test]
fn gwps_refuses_a_tool_that_is_no_grinding_wheel() {
    // A milling tool (type 120) and a wheel "without GWPS" (type 403, PGsl 5.5.4).
    for tool_type in [120, 403] {
        let machine = grinder(&[(1, tool_type, 50.0)]);
        let alarm = grinder_error(
            "$TC_TPG1[1]=1\n$TC_TPG9[1]=6\nT1 D1\nGWPSON\nM30\n",
            &machine,
        );
        assert_eq!(alarm.code, AlarmCode::WordNotAllowed, "{tool_type}");
        assert!(
            alarm.message.contains(&format!("type {tool_type}")),
            "{}",
            alarm.message
        );
    }
}

#[test]
fn gwps_without_the_grinding_data_is_an_alarm() {
    // No $TC_TPG1: no spindle; $TC_TPG1 but no $TC_TPG9: no radius parameter.
    let machine = grinder(&[(1, 400, 50.0)]);
    let alarm = grinder_error("T1 D1\nGWPSON\nM30\n", &machine);
    assert_eq!(alarm.code, AlarmCode::BadDataInput);
    assert!(alarm.message.contains("$TC_TPG1[1]"), "{}", alarm.message);
    let alarm = grinder_error("$TC_TPG1[1]=1\nT1 D1\nGWPSON\nM30\n", &machine);
    assert_eq!(alarm.code, AlarmCode::BadDataInput);
    assert!(alarm.message.contains("$TC_TPG9[1]"), "{}", alarm.message);
}

#[test]
fn a_second_tools_gwps_on_a_spindle_waits_for_gwpsof() {
    // T1 and T2 both on spindle 1 (PGsl 6.4, L2387: deselect first).
    let machine = grinder(&[(1, 400, 50.0), (2, 400, 60.0)]);
    let preset = "$TC_TPG1[1]=1\n$TC_TPG9[1]=6\n$TC_TPG1[2]=1\n$TC_TPG9[2]=6\n";
    let alarm = grinder_error(&format!("{preset}GWPSON(1)\nGWPSON(2)\nM30\n"), &machine);
    assert_eq!(alarm.code, AlarmCode::WordNotAllowed);
    assert!(
        alarm
            .help
            .as_deref()
            .is_some_and(|h| h.contains("GWPSOF(1)")),
        "{alarm:?}"
    );
    speeds(
        &format!("{preset}GWPSON(1)\nGWPSOF(1)\nGWPSON(2)\nM30\n"),
        &machine,
    );
}
