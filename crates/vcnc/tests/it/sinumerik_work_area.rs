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
