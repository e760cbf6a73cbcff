//! SINUMERIK's working-area limitation, G25/G26 with axes and WALIMON/WALIMOF
//! (docs/SINUMERIK.md, "Working area"; the manual PGsl 6.3, L9888-10010).
//!
//! The manual's rules checked here: "all tool motions outside the area defined by G25/G26 are
//! prohibited"; G25/G26 are non-modal instructions whose limits persist; WALIMON is the
//! default, WALIMOF switches the limitation off; a tool outside the area stops the program
//! with an alarm. vcnc alarms 10730 at the block whose move leaves the area (its end or its
//! path) and leaves that move out. The machine is the default one with no work offset and no
//! tool, so program and machine coordinates are the same.

use vcnc::interp::sinumerik::run_str;
use vcnc::{Alarm, AlarmCode, SegmentKind};

use crate::common::collect;
use crate::common::sinumerik::machine;

/// The alarm `text` stops with (if any) and the end X Y Z of each of its moves.
fn run(text: &str) -> (Option<Alarm>, Vec<[f64; 3]>) {
    let run = collect(run_str(text, &machine()));
    let ends = run
        .segments
        .iter()
        .filter(|s| {
            matches!(
                s.kind,
                SegmentKind::Rapid { .. } | SegmentKind::Line { .. } | SegmentKind::Arc { .. }
            )
        })
        .filter_map(|s| s.motion().map(|m| [m.to.0[0], m.to.0[1], m.to.0[2]]))
        .collect();
    (run.error().cloned(), ends)
}

/// The 1-based line of `text` the alarm points at.
fn line_of(text: &str, alarm: &Alarm) -> usize {
    let span = alarm.span.expect("the alarm points at its block");
    text[..span.start as usize].matches('\n').count() + 1
}

const LIMITS: &str = "G17 G90 G0 X0 Y0 Z10\nG25 X-50 Y-40 Z-20\nG26 X50 Y40 Z100\n";

#[test]
fn a_move_inside_the_area_runs() {
    let text = format!("{LIMITS}G1 X50 Y-40 Z-20 F500\nG0 X-50 Y40 Z100\nM30\n");
    let (alarm, ends) = run(&text);
    assert!(alarm.is_none(), "{alarm:?}");
    // The moves end on the limits themselves: inside.
    assert_eq!(ends.last(), Some(&[-50.0, 40.0, 100.0]));
}

#[test]
fn a_move_ending_outside_alarms_10730_at_its_block_before_it_moves() {
    let text = format!("{LIMITS}G1 X20 F500\nG1 X60\nG1 X0\nM30\n");
    let (alarm, ends) = run(&text);
    let alarm = alarm.expect("X60 is beyond G26 X50");
    assert_eq!(alarm.code, AlarmCode::Overtravel);
    assert!(alarm.message.contains("10730"), "{}", alarm.message);
    assert_eq!(line_of(&text, &alarm), 5, "{alarm:?}");
    // The first move X0 Y0 Z10 and X20 were made; X60 was not, nor anything after it.
    assert_eq!(ends.last(), Some(&[20.0, 0.0, 10.0]));
}

#[test]
fn an_arc_leaving_the_area_between_its_ends_alarms() {
    // From X-30 Y0 to X30 Y0 clockwise about X0 Y0: the arc passes through X0 Y30, then the
    // circle's top Y30 is inside G26 Y40. Radius 45 (from X-45 to X45, centre I45): the top
    // Y45 is beyond Y40 though both ends are inside.
    let inside = format!("{LIMITS}G0 X-30\nG2 X30 Y0 I30 J0 F500\nM30\n");
    assert!(run(&inside).0.is_none());
    let text = format!("{LIMITS}G0 X-45\nG2 X45 Y0 I45 J0 F500\nM30\n");
    let alarm = run(&text).0.expect("the arc's top Y45 is beyond G26 Y40");
    assert!(alarm.message.contains("10730"), "{}", alarm.message);
    assert_eq!(line_of(&text, &alarm), 5);
}

#[test]
fn walimof_lets_the_tool_out_and_walimon_limits_it_again() {
    // The manual's example (L9941-9960, examples/sinumerik-b/76-g25-g26-walimon.mpf) drills
    // to Z-2 below G25 Z30 only because WALIMOF is in force; here the same on a mill's Z.
    let text = "G90 G0 X0 Y0 Z50\nG25 Z30\nG26 Z330\nWALIMOF\nG1 Z-2 F100\nG0 Z200\nWALIMON\nX70\nG0 Z0\nM30\n";
    let (alarm, ends) = run(text);
    let alarm = alarm.expect("Z0 is below G25 Z30 again after WALIMON");
    assert_eq!(line_of(text, &alarm), 9);
    assert_eq!(ends.last(), Some(&[70.0, 0.0, 200.0]));
}

#[test]
fn g25_with_s_still_limits_the_spindle_not_the_area() {
    let text = "G90 G0 X0 Y0 Z10\nG25 S100\nG26 S2000\nG0 X500\nM30\n";
    assert!(run(text).0.is_none());
}

#[test]
fn a_limit_written_once_persists_for_later_blocks() {
    // G25/G26 are non-modal instructions whose values persist: G26 X50 still holds after G25
    // sets another axis.
    let text = "G90 G0 X0 Y0 Z10\nG26 X50\nG25 Y-10\nG0 X40\nG0 Y-5\nG0 X51\nM30\n";
    let alarm = run(text).0.expect("X51 is beyond the earlier G26 X50");
    assert_eq!(line_of(text, &alarm), 6);
}

// WALCS1-WALCS10: the working-area limitation in the WCS (PGsl 14.3.2, L10012-10090; spec
// sinumerik-part-b.md 6.4): limits per group and axis in `$P_WORKAREA_CS_LIMIT_PLUS/MINUS`,
// valid where `..._PLUS/MINUS_ENABLE` is TRUE, selected by WALCS1-WALCS10, WALCS0 deselects.

/// The manual's example (L10072-10090, examples/sinumerik-b/77-walcs.mpf) for group 2: X+ 10,
/// no X-, Y+ 34, Y- -25, no Z+, Z- -600; with N83 as the text means it (LIMIT_MINUS), the
/// seed's LIMIT_PLUS being its error (spec 6.4, Notes).
const GROUP_2: &str = "G17 G90 G0 X0 Y0 Z10\n\
$P_WORKAREA_CS_COORD_SYSTEM[2]=1\n\
$P_WORKAREA_CS_PLUS_ENABLE[2,X]=TRUE\n\
$P_WORKAREA_CS_LIMIT_PLUS[2,X]=10\n\
$P_WORKAREA_CS_MINUS_ENABLE[2,X]=FALSE\n\
$P_WORKAREA_CS_PLUS_ENABLE[2,Y]=TRUE\n\
$P_WORKAREA_CS_LIMIT_PLUS[2,Y]=34\n\
$P_WORKAREA_CS_MINUS_ENABLE[2,Y]=TRUE\n\
$P_WORKAREA_CS_LIMIT_MINUS[2,Y]=-25\n\
$P_WORKAREA_CS_PLUS_ENABLE[2,Z]=FALSE\n\
$P_WORKAREA_CS_MINUS_ENABLE[2,Z]=TRUE\n\
$P_WORKAREA_CS_LIMIT_MINUS[2,Z]=-600\n\
WALCS2\n";

/// The 1-based line after [`GROUP_2`]'s 13.
const AFTER: usize = 14;

#[test]
fn walcs2_keeps_the_manuals_limits_and_lets_the_unlimited_sides_go() {
    // To the limits themselves (inside), and far out where a side is not enabled: X- and Z+.
    let text = format!("{GROUP_2}G1 X10 Y34 F500\nY-25 Z-600\nG0 X-900 Z900\nM30\n");
    let (alarm, ends) = run(&text);
    assert!(alarm.is_none(), "{alarm:?}");
    assert_eq!(ends.last(), Some(&[-900.0, -25.0, 900.0]));
}

#[test]
fn a_move_beyond_a_wcs_limit_alarms_10745_at_its_block_before_it_moves() {
    for (mv, axis) in [
        ("X10.01", "X"),
        ("Y34.5", "Y"),
        ("Y-26", "Y"),
        ("Z-601", "Z"),
    ] {
        let text = format!("{GROUP_2}G1 X5 F500\nG1 {mv}\nM30\n");
        let (alarm, ends) = run(&text);
        let alarm = alarm.unwrap_or_else(|| panic!("{mv} is beyond group 2's limits"));
        assert_eq!(alarm.code, AlarmCode::Overtravel);
        assert!(alarm.message.contains("10745"), "{}", alarm.message);
        assert!(
            alarm.message.contains(&format!("axis {axis}")),
            "{}",
            alarm.message
        );
        assert_eq!(line_of(&text, &alarm), AFTER + 1, "{mv}");
        assert_eq!(ends.last(), Some(&[5.0, 0.0, 10.0]), "{mv}");
    }
}

#[test]
fn walcs0_deselects_and_limits_set_before_walcs_wait_for_it() {
    // WALCS0 (the manual: "deactivates the working-area limitation group in force"): X20 runs.
    let text = format!("{GROUP_2}WALCS0\nG0 X20\nM30\n");
    assert!(run(&text).0.is_none());
    // Written, not selected: no limit until WALCS2.
    let text = GROUP_2.replace("WALCS2\n", "G0 X20\nG0 X0\nWALCS2\nG0 X20\nM30\n");
    let (alarm, _) = run(&text);
    assert_eq!(line_of(&text, &alarm.expect("X20 under WALCS2")), AFTER + 2);
}

#[test]
fn the_limits_are_in_the_workpiece_system_after_the_frames() {
    // "Working-area limits ... that refer to the WCS": with TRANS X100 the WCS X10 is machine
    // X110, inside; WCS X11 (machine X111) is beyond.
    let text = format!("{GROUP_2}TRANS X100\nG0 X10\nG0 X11\nM30\n");
    let (alarm, ends) = run(&text);
    assert_eq!(line_of(&text, &alarm.expect("WCS X11")), AFTER + 2);
    assert_eq!(ends.last(), Some(&[110.0, 0.0, 10.0]));
    // ROT Z90: WCS X runs along machine Y. G0 X11 goes to machine Y11 (beyond WCS X+10 though
    // machine X stays 0); G0 Y30 to machine X-30 (WCS Y30 is inside Y+34).
    let text = format!("{GROUP_2}ROT Z90\nG0 Y30\nG0 X11\nM30\n");
    let (alarm, ends) = run(&text);
    assert_eq!(line_of(&text, &alarm.expect("WCS X11")), AFTER + 2);
    let end = ends.last().unwrap().map(|v| (v * 1e9).round() / 1e9);
    assert_eq!(end, [-30.0, 0.0, 10.0]);
}

#[test]
fn an_arc_bulging_beyond_a_wcs_limit_between_its_ends_alarms() {
    // From X0 Y-5 to X0 Y5 about X0 Y0, counter-clockwise through X5: beyond X+4 though both
    // ends (X0) are inside; clockwise through X-5 it stays inside (no X- limit).
    let limits = "G17 G90 G0 X0 Y-5 Z10\n$P_WORKAREA_CS_PLUS_ENABLE[1,X]=TRUE\n\
                  $P_WORKAREA_CS_LIMIT_PLUS[1,X]=4\nWALCS1\n";
    let text = format!("{limits}G2 X0 Y5 I0 J5 F500\nM30\n");
    assert!(run(&text).0.is_none());
    let text = format!("{limits}G3 X0 Y5 I0 J5 F500\nM30\n");
    let alarm = run(&text).0.expect("the arc passes X5");
    assert!(alarm.message.contains("10745"), "{}", alarm.message);
    assert_eq!(line_of(&text, &alarm), 5);
}

#[test]
fn walcs_works_independently_of_walimon() {
    // "The working-area limits with WALCS1-WALCS10 work independently of the limitation with
    // WALIMON; if both are on, the limit an axis reaches first takes effect": WALIMOF switches
    // G25/G26 off, not group 2; G26 X5 stops X8 though group 2 allows X10.
    let text = format!("{GROUP_2}G26 X5\nWALIMOF\nG0 X8\nG0 X11\nM30\n");
    let (alarm, _) = run(&text);
    let alarm = alarm.expect("X11 beyond group 2");
    assert!(alarm.message.contains("10745"), "{}", alarm.message);
    assert_eq!(line_of(&text, &alarm), AFTER + 3);
    let text = format!("{GROUP_2}G26 X5\nG0 X8\nM30\n");
    let alarm = run(&text).0.expect("X8 beyond G26 X5");
    assert!(alarm.message.contains("10730"), "{}", alarm.message);
}

#[test]
fn the_manuals_n83_as_written_leaves_z_minus_at_its_power_on_zero() {
    // The seed's N83 writes LIMIT_PLUS[2,Z]=-600 (its Z+ side disabled), so the Z- side
    // N82 enabled keeps the value it had: 0 at power-on (choice: the control's default of the
    // system variable). Z-1 is then beyond it.
    let text = GROUP_2.replace("LIMIT_MINUS[2,Z]", "LIMIT_PLUS[2,Z]") + "G1 Z0 F500\nG1 Z-1\nM30\n";
    let alarm = run(&text).0.expect("Z-1 below the Z- limit 0");
    assert!(alarm.message.contains("axis Z"), "{}", alarm.message);
    assert_eq!(line_of(&text, &alarm), AFTER + 1);
}

#[test]
fn a_group_outside_1_to_10_is_refused() {
    let text = "$P_WORKAREA_CS_LIMIT_PLUS[11,X]=10\nM30\n";
    let alarm = run(text).0.expect("group 11");
    assert_eq!(alarm.code, AlarmCode::BadVariable);
    // Read back as written.
    let text = "$P_WORKAREA_CS_LIMIT_PLUS[3,Y]=7.5\n$P_WORKAREA_CS_PLUS_ENABLE[3,Y]=TRUE\n\
                IF ($P_WORKAREA_CS_LIMIT_PLUS[3,Y]==7.5) AND $P_WORKAREA_CS_PLUS_ENABLE[3,Y]\n\
                G0 X1\nENDIF\nM30\n";
    let (alarm, ends) = run(text);
    assert!(alarm.is_none(), "{alarm:?}");
    assert_eq!(ends.last().map(|e| e[0]), Some(1.0));
}
