//! Canned cycles (issue #4) on the Syntec manual's examples (spec iso-syntec-milling.md
//! 1.41-1.52, files examples/syntec/5x-*.nc): every move of every hole is asserted. The
//! expected sequences are built here from the manual's step lists, not from vcnc: the common
//! frame (initial level Z10, R level Z-5, holes at (5,5), (15,5), (15,15) returning to R under
//! G99, then (5,15) and (10,10) returning to the initial level under G98) and each cycle's
//! moves at a hole.

use crate::common;

use crate::common::{check_on, shared_dir};
use std::path::Path;
use vcnc::{Machine, ProfileName};

/// A hole of the common frame: position, bottom, and the level it returns to.
struct Hole {
    x: f64,
    y: f64,
    bottom: f64,
    back: f64,
}

const R: f64 = -5.0;
const INITIAL: f64 = 10.0;

/// The frame's holes: the first `count` of the five (the examples without a fifth hole stop at
/// four).
fn holes(count: usize) -> Vec<Hole> {
    let all = [
        (5.0, 5.0, -10.0, R),
        (15.0, 5.0, -10.0, R),
        (15.0, 15.0, -10.0, R),
        (5.0, 15.0, -10.0, INITIAL),
        (10.0, 10.0, -20.0, INITIAL),
    ];
    all[..count]
        .iter()
        .map(|&(x, y, bottom, back)| Hole { x, y, bottom, back })
        .collect()
}

/// The moves of a program running the frame: for each hole a rapid over it at the level the
/// last hole left the tool, a rapid down to R (unless it is there), and `body`: the cycle's own moves from R to its
/// return level.
fn frame(
    head: &[&str],
    holes: &[Hole],
    body: impl Fn(&Hole) -> Vec<String>,
    tail: &[&str],
) -> String {
    let mut lines: Vec<String> = head.iter().map(|s| s.to_string()).collect();
    let mut level = INITIAL;
    for hole in holes {
        let (x, y) = (hole.x, hole.y);
        lines.push(format!("rapid X{x} Y{y} Z{level}"));
        if level != R {
            lines.push(format!("rapid X{x} Y{y} Z{R}"));
        }
        lines.extend(body(hole));
        level = hole.back;
    }
    lines.extend(tail.iter().map(|s| s.to_string()));
    lines.join("\n")
}

fn example(file: &str, expected: &str) {
    let Some(shared) = shared_dir() else {
        return;
    };
    let text = std::fs::read_to_string(shared.join("spec/examples/syntec").join(file))
        .expect("the example is in ../shared");
    let machine = Machine::default()
        .with_profile(ProfileName::Syntec)
        .unwrap();
    check_on(&machine, &text, expected);
}

fn feed(h: &Hole, z: f64) -> String {
    format!("line X{} Y{} Z{z} F1000", h.x, h.y)
}

fn rapid(h: &Hole, z: f64) -> String {
    format!("rapid X{} Y{} Z{z}", h.x, h.y)
}

/// Spec 1.44: G00 over the hole, G00 to R, G01 to Z, G00 back (F2= is the retract feed only in
/// Syntec's fast drilling mode, off by default, so the retract is rapid).
#[test]
fn g81_drilling() {
    example(
        "53-g81-drill-f2.nc",
        &frame(
            &["rapid X0 Y0 Z10"],
            &holes(5),
            |h| vec![feed(h, h.bottom), rapid(h, h.back)],
            &["end M30"],
        ),
    );
}

/// Spec 1.46: pecks of Q = 3 from R (-5): feed to -8, rapid to R, rapid to 1 mm (the
/// clearance) above -8, feed to -10 (the last peck shorter), then out.
#[test]
fn g83_peck_drilling() {
    example(
        "55-g83-peck-drill.nc",
        &frame(
            &["spindle Clockwise 500", "rapid X0 Y0 Z10"],
            &holes(4),
            |h| {
                vec![
                    feed(h, -8.0),
                    rapid(h, R),
                    rapid(h, -7.0),
                    feed(h, -10.0),
                    rapid(h, h.back),
                ]
            },
            &["spindle Stopped 500", "end M30"],
        ),
    );
}

/// Spec 1.41: pecks of Q = 2 from R, each followed by a retract of d = 1 (Pr4002), the next
/// feed starting from there: -7, up to -6, -9, up to -8, then the last peck to the bottom.
#[test]
fn g73_high_speed_peck_drilling() {
    example(
        "50-g73-peck-drill.nc",
        &frame(
            &["spindle Clockwise 500", "rapid X0 Y0 Z10"],
            &holes(5),
            |h| {
                let mut v = Vec::new();
                let mut depth = R;
                loop {
                    let next = (depth - 2.0).max(h.bottom);
                    v.push(feed(h, next));
                    if next == h.bottom {
                        break;
                    }
                    v.push(rapid(h, next + 1.0));
                    depth = next;
                }
                v.push(rapid(h, h.back));
                v
            },
            &["spindle Stopped 500", "end M30"],
        ),
    );
}

/// Spec 1.43: G01 to Z, dwell P5 (seconds with a decimal point), oriented stop, shift Q = 2 in
/// +X (Pr4020 = 0), G00 out, shift back over the hole, spindle on again.
#[test]
fn g76_fine_boring() {
    example(
        "52-g76-fine-boring.nc",
        &frame(
            &["spindle Clockwise 500", "rapid X0 Y0 Z10"],
            &holes(5),
            |h| {
                vec![
                    feed(h, h.bottom),
                    "dwell 5".to_string(),
                    "spindle Oriented 500".to_string(),
                    format!("rapid X{} Y{} Z{}", h.x + 2.0, h.y, h.bottom),
                    format!("rapid X{} Y{} Z{}", h.x + 2.0, h.y, h.back),
                    rapid(h, h.back),
                    "spindle Clockwise 500".to_string(),
                ]
            },
            &["spindle Stopped 500", "end M30"],
        ),
    );
}

/// The head of the examples that start the spindle after moving to the initial point.
fn started(state: &str) -> Vec<String> {
    vec![
        "rapid X0 Y0 Z10".to_string(),
        format!("spindle {state} 500"),
    ]
}

fn run_example(file: &str, state: &str, count: usize, body: impl Fn(&Hole) -> Vec<String>) {
    let head = started(state);
    let head: Vec<&str> = head.iter().map(String::as_str).collect();
    let stop = "spindle Stopped 500";
    example(file, &frame(&head, &holes(count), body, &[stop, "end M30"]));
}

/// Spec 1.45: G01 to Z, dwell P2 (2 s), G00 out.
#[test]
fn g82_drilling_with_dwell() {
    run_example("54-g82-dwell-drill.nc", "Clockwise", 4, |h| {
        vec![feed(h, h.bottom), "dwell 2".into(), rapid(h, h.back)]
    });
}

/// Spec 1.42 type I: tapping in with the spindle counter-clockwise, dwell P2 and reverse at
/// the bottom, G01 out to R, dwell and reverse again, then up to the return level.
#[test]
fn g74_left_hand_tapping() {
    run_example("51-g74-left-tap.nc", "CounterClockwise", 5, |h| {
        let mut v = vec![
            feed(h, h.bottom),
            "dwell 2".into(),
            "spindle Clockwise 500".into(),
            feed(h, R),
            "dwell 2".into(),
            "spindle CounterClockwise 500".into(),
        ];
        if h.back != R {
            v.push(rapid(h, h.back));
        }
        v
    });
}

/// Spec 1.47: as G74 with the spindle clockwise; no P, no dwell.
#[test]
fn g84_tapping() {
    run_example("56-g84-tap.nc", "Clockwise", 4, |h| {
        let mut v = vec![
            feed(h, h.bottom),
            "spindle CounterClockwise 500".into(),
            feed(h, R),
            "spindle Clockwise 500".into(),
        ];
        if h.back != R {
            v.push(rapid(h, h.back));
        }
        v
    });
}

/// Spec 1.48: G01 in, G01 out to R, G00 to the initial level under G98.
#[test]
fn g85_boring() {
    run_example("57-g85-bore.nc", "Clockwise", 4, |h| {
        let mut v = vec![feed(h, h.bottom), feed(h, R)];
        if h.back != R {
            v.push(rapid(h, h.back));
        }
        v
    });
}

/// Spec 1.49: G01 in, spindle stop, G00 out, spindle on again (inferred, FANUC).
#[test]
fn g86_boring_with_spindle_stop() {
    run_example("58-g86-bore.nc", "Clockwise", 4, |h| {
        vec![
            feed(h, h.bottom),
            "spindle Stopped 500".into(),
            rapid(h, h.back),
            "spindle Clockwise 500".into(),
        ]
    });
}

/// Spec 1.52: G01 in, dwell P2.5 (seconds), G01 out to R, G00 to the initial level under G98.
#[test]
fn g89_boring_with_dwell() {
    run_example("61-g89-dwell-bore.nc", "Clockwise", 4, |h| {
        let mut v = vec![feed(h, h.bottom), "dwell 2.5".into(), feed(h, R)];
        if h.back != R {
            v.push(rapid(h, h.back));
        }
        v
    });
}

/// Hand-checked cases on the FANUC profile (spec A.32 and 1.40 rules).
fn fanuc(program: &str, expected: &str) {
    check_on(&Machine::default(), program, expected);
}

/// G91: R from the initial level (10 - 12 = -2), Z from R (-2 - 15 = -17); K3 repeats the
/// incremental X10 three times, returning to R (G99).
#[test]
fn incremental_hole_data_and_k_repeats() {
    fanuc(
        "G0 X0 Y0 Z10.\nG91 G99 G81 X10. Y0 Z-15. R-12. K3 F100.\nG80\nM30",
        "
        rapid X0 Y0 Z10
        rapid X10 Y0 Z10
        rapid X10 Y0 Z-2
        line X10 Y0 Z-17 F100
        rapid X10 Y0 Z-2
        rapid X20 Y0 Z-2
        line X20 Y0 Z-17 F100
        rapid X20 Y0 Z-2
        rapid X30 Y0 Z-2
        line X30 Y0 Z-17 F100
        rapid X30 Y0 Z-2
        end M30",
    );
}

/// K0 stores the hole data without moving; the next position drills with them. Blocks with no
/// position or hole data (M08) do not drill; G98 (power-on) returns to the initial level.
#[test]
fn k0_stores_and_blocks_without_positions_do_not_drill() {
    fanuc(
        "G0 X0 Y0 Z10.\nG81 X10. Z-5. R2. F100. K0\nM08\nX20.\nG80\nM30",
        "
        rapid X0 Y0 Z10
        coolant on
        rapid X20 Y0 Z10
        rapid X20 Y0 Z2
        line X20 Y0 Z-5 F100
        rapid X20 Y0 Z10
        end M30",
    );
}

/// G18: positioning in Z-X, drilling along Y (spec 1.40).
#[test]
fn in_g18_the_cycle_drills_along_y() {
    fanuc(
        "G18 G0 X0 Y10. Z0\nG81 X5. Z5. Y-5. R2. F100.\nG80\nM30",
        "
        rapid X0 Y10 Z0
        rapid X5 Y10 Z5
        rapid X5 Y2 Z5
        line X5 Y-5 Z5 F100
        rapid X5 Y10 Z5
        end M30",
    );
}

/// FANUC 0M: cycles drill along Z whatever the plane (spec A.32).
#[test]
fn on_the_0m_the_cycle_drills_along_z_in_g18() {
    check_on(
        &Machine::default()
            .with_profile(ProfileName::Fanuc0m)
            .unwrap(),
        "G18 G0 X0 Y0 Z10.\nG81 X5. Y5. Z-5. R2. F100.\nG80\nM30",
        "
        rapid X0 Y0 Z10
        rapid X5 Y5 Z10
        rapid X5 Y5 Z2
        line X5 Y5 Z-5 F100
        rapid X5 Y5 Z10
        end M30",
    );
}

/// A group-01 code ends the cycle: the next block is a plain move.
#[test]
fn a_group_01_code_cancels_the_cycle() {
    fanuc(
        "G0 Z10.\nG81 X5. Z-5. R2. F100.\nG0 X20.\nM30",
        "
        rapid X0 Y0 Z10
        rapid X5 Y0 Z10
        rapid X5 Y0 Z2
        line X5 Y0 Z-5 F100
        rapid X5 Y0 Z10
        rapid X20 Y0 Z10
        end M30",
    );
}

/// G80 clears the hole data (spec A.32): a new cycle without Z alarms; a peck cycle without Q
/// alarms (FANUC 045); the plane cannot change inside a cycle.
/// G83 with pecks shorter than the clearance (1 mm on the FANUC profile): the tool goes back
/// into the hole only as far as R, never out past it (a fuzz finding: it used to rapid above R
/// and feed the whole way down again). G73's retract is held at R the same way.
#[test]
fn a_peck_shorter_than_the_clearance_stays_below_r() {
    fanuc(
        "G0 Z10.\nG83 X5. R2. Z-1. Q0.5 F100.\nM30",
        "
        rapid X0 Y0 Z10
        rapid X5 Y0 Z10
        rapid X5 Y0 Z2
        line X5 Y0 Z1.5 F100
        rapid X5 Y0 Z2
        line X5 Y0 Z1 F100
        rapid X5 Y0 Z2
        line X5 Y0 Z0.5 F100
        rapid X5 Y0 Z2
        rapid X5 Y0 Z1.5
        line X5 Y0 Z0 F100
        rapid X5 Y0 Z2
        rapid X5 Y0 Z1
        line X5 Y0 Z-0.5 F100
        rapid X5 Y0 Z2
        rapid X5 Y0 Z0.5
        line X5 Y0 Z-1 F100
        rapid X5 Y0 Z10
        end M30",
    );
}

/// An M code on a cycle block with repeats acts once, before the first hole.
#[test]
fn an_m_code_on_a_repeated_cycle_block_acts_once() {
    fanuc(
        "G0 Z10.\nG91 G81 X5. Z-5. R-2. F100. K2 M08\nG80\nM30",
        "
        rapid X0 Y0 Z10
        coolant on
        rapid X5 Y0 Z10
        rapid X5 Y0 Z8
        line X5 Y0 Z3 F100
        rapid X5 Y0 Z10
        rapid X10 Y0 Z10
        rapid X10 Y0 Z8
        line X10 Y0 Z3 F100
        rapid X10 Y0 Z10
        end M30",
    );
}

/// The combinations the manuals flag but the control runs: a bottom above R (the FANUC 0M
/// manual's O1717, T04: `R-15. Z-10.`), and tapping without a spindle speed. Both warn at the
/// block and move as written.
#[test]
fn a_bottom_above_r_and_a_tap_without_speed_warn() {
    fanuc(
        "G0 Z10.\nG81 X5. R-15. Z-10. F100.\nM30",
        "
        rapid X0 Y0 Z10
        rapid X5 Y0 Z10
        rapid X5 Y0 Z-15
        line X5 Y0 Z-10 F100
        rapid X5 Y0 Z10
        end M30
        alarm cycle_data line 2",
    );
    fanuc(
        "M03\nG0 Z10.\nG84 X5. R2. Z-10. F100.\nM30",
        "
        spindle Clockwise 0
        rapid X0 Y0 Z10
        rapid X5 Y0 Z10
        rapid X5 Y0 Z2
        line X5 Y0 Z-10 F100
        spindle CounterClockwise 0
        line X5 Y0 Z2 F100
        spindle Clockwise 0
        rapid X5 Y0 Z10
        end M30
        alarm cycle_data line 3",
    );
    // G87 bores upwards: R below the bottom is right.
    let trace = common::trace_with(
        ProfileName::Fanuc,
        "M03 S500\nG0 Z10.\nG87 X5. R-30. Z-10. Q1. F100.\nM30",
    );
    assert!(!trace.contains("alarm"), "{trace}");
}

#[test]
fn missing_hole_data_and_plane_changes_alarm() {
    fanuc(
        "G0 Z10.\nG81 X5. Z-5. R2. F100.\nG80\nG81 X10.\nM30",
        "
        rapid X0 Y0 Z10
        rapid X5 Y0 Z10
        rapid X5 Y0 Z2
        line X5 Y0 Z-5 F100
        rapid X5 Y0 Z10
        alarm cycle_data line 4",
    );
    fanuc(
        "G0 Z10.\nG83 X5. Z-5. R2. F100.\nM30",
        "
        rapid X0 Y0 Z10
        alarm cycle_data line 2",
    );
    fanuc(
        "G0 Z10.\nG81 X5. Z-5. R2. F100.\nG18 X10.\nM30",
        "
        rapid X0 Y0 Z10
        rapid X5 Y0 Z10
        rapid X5 Y0 Z2
        line X5 Y0 Z-5 F100
        rapid X5 Y0 Z10
        alarm cycle_data line 3",
    );
}

/// G84 taps with the spindle clockwise: started the other way (or not at all), a warning.
#[test]
fn tapping_with_the_spindle_the_wrong_way_warns() {
    fanuc(
        "S500 M04\nG0 Z10.\nG84 X5. Z-5. R2. F500.\nG80\nM30",
        "
        spindle CounterClockwise 500
        rapid X0 Y0 Z10
        rapid X5 Y0 Z10
        rapid X5 Y0 Z2
        line X5 Y0 Z-5 F500
        spindle CounterClockwise 500
        line X5 Y0 Z2 F500
        spindle Clockwise 500
        rapid X5 Y0 Z10
        end M30
        alarm cycle_data line 3",
    );
}

/// Spec 1.50, file 59-g87-back-bore.nc (R-30 below the part, Z10, Q5, P4 s): orient, shift -Q
/// (against Pr4020's +X), down to R, back on the axis, spindle on, bore up to Z, dwell, orient,
/// shift, out to the initial level (here Z10 already), spindle on, back on the axis.
#[test]
fn g87_back_boring() {
    let mut lines = vec![
        "rapid X0 Y0 Z10".to_string(),
        "spindle Clockwise 500".to_string(),
    ];
    for (x, y) in [(5.0, 5.0), (15.0, 5.0), (15.0, 15.0)] {
        lines.extend([
            format!("rapid X{x} Y{y} Z10"),
            "spindle Oriented 500".into(),
            format!("rapid X{} Y{y} Z10", x - 5.0),
            format!("rapid X{} Y{y} Z-30", x - 5.0),
            format!("rapid X{x} Y{y} Z-30"),
            "spindle Clockwise 500".into(),
            format!("line X{x} Y{y} Z10 F1000"),
            "dwell 4".into(),
            "spindle Oriented 500".into(),
            format!("rapid X{} Y{y} Z10", x - 5.0),
            "spindle Clockwise 500".into(),
            format!("rapid X{x} Y{y} Z10"),
        ]);
    }
    lines.extend(["spindle Stopped 500".into(), "end M30".into()]);
    example("59-g87-back-bore.nc", &lines.join("\n"));
}

/// Spec 1.51: G01 in, dwell P3 (3 s), spindle stop, a stop for the operator's manual retract,
/// then from the bottom G01 to R, G00 to the initial level under G98, spindle on.
#[test]
fn g88_boring_with_manual_retract() {
    run_example("60-g88-semi-auto-bore.nc", "Clockwise", 4, |h| {
        let mut v = vec![
            feed(h, h.bottom),
            "dwell 3".into(),
            "spindle Stopped 500".into(),
            "stop Program".into(),
            feed(h, R),
        ];
        if h.back != R {
            v.push(rapid(h, h.back));
        }
        v.push("spindle Clockwise 500".into());
        v
    });
}

/// The FANUC 0M manual's O1616 (001:L1651-1697, file examples/fanuc0m/23-o1616-g73-g74.nc),
/// length offsets zero: G73 with Q5000 (5 mm in 0.001 mm units) from R3 to Z-15, peck bottoms
/// -2, -7, -12, -15 with a 1 mm retract (parameter 0531) after each, back to R (G99); then the
/// G74 tap from R3 to Z-15 with the spindle reversed at the bottom and back at R, out to the
/// initial level Z10 (G98), as the example's header works out.
#[test]
fn fanuc_0m_example_o1616() {
    let Some(shared) = shared_dir() else {
        return;
    };
    let text =
        std::fs::read_to_string(shared.join("spec/examples/fanuc0m/23-o1616-g73-g74.nc")).unwrap();
    let mut lines: Vec<String> = [
        "select T1",
        "change T1",
        "spindle Clockwise 800",
        "rapid X0 Y0 Z10",
        "rapid X20 Y28 Z10",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    for (x, y) in [(20, 28), (85, 38)] {
        // The first hole comes down from the initial level, the second moves over at R.
        lines.push(format!("rapid X{x} Y{y} Z3"));
        for bottom in [-2, -7, -12] {
            lines.push(format!("line X{x} Y{y} Z{bottom} F60"));
            lines.push(format!("rapid X{x} Y{y} Z{}", bottom + 1));
        }
        lines.push(format!("line X{x} Y{y} Z-15 F60"));
        lines.push(format!("rapid X{x} Y{y} Z3"));
    }
    lines.extend(
        [
            "rapid X85 Y38 Z0",
            "spindle Stopped 800",
            "select T2",
            "change T2",
            "spindle CounterClockwise 100",
            "rapid X85 Y38 Z10",
        ]
        .iter()
        .map(|s| s.to_string()),
    );
    for (x, y) in [(85, 38), (20, 28)] {
        if x == 20 {
            // The first tap hole is right below the tool: no positioning move.
            lines.push(format!("rapid X{x} Y{y} Z10"));
        }
        lines.extend([
            format!("rapid X{x} Y{y} Z3"),
            format!("line X{x} Y{y} Z-15 F125"),
            "spindle Clockwise 100".into(),
            format!("line X{x} Y{y} Z3 F125"),
            "spindle CounterClockwise 100".into(),
            format!("rapid X{x} Y{y} Z10"),
        ]);
    }
    lines.extend(["rapid X20 Y28 Z0".into(), "end M30".into()]);
    check_on(
        &Machine::default()
            .with_profile(ProfileName::Fanuc0m)
            .unwrap(),
        &text,
        &lines.join("\n"),
    );
}

/// The holes a Syntec example drills: the program-coordinate X Y of every feed move.
fn drilled(shared: &Path, file: &str) -> Vec<(f64, f64)> {
    let text = std::fs::read(shared.join("spec/examples/syntec").join(file)).unwrap();
    let machine = Machine::default()
        .with_profile(ProfileName::Syntec)
        .unwrap();
    let run = common::run(&text, &machine, vcnc::Options::default());
    assert!(run.error().is_none(), "{file}: {:?}", run.error());
    run.segments
        .iter()
        .filter_map(|s| match s.kind {
            vcnc::SegmentKind::Line { motion, .. } => {
                let w = motion.work_to();
                Some((w[0], w[1]))
            }
            _ => None,
        })
        .collect()
}

#[track_caller]
fn assert_holes(actual: &[(f64, f64)], expected: &[(f64, f64)]) {
    assert_eq!(actual.len(), expected.len(), "{actual:?}");
    for (a, e) in actual.iter().zip(expected) {
        assert!(
            (a.0 - e.0).abs() < 1e-3 && (a.1 - e.1).abs() < 1e-3,
            "hole {a:?}, expected {e:?}"
        );
    }
}

/// The hole patterns (spec 1.59-1.62, files 67-70): the hole positions the spec works out from
/// the manual's examples (G134 about the centre (700,200) after G92 X500 Y100 and G91 X200
/// Y100; the others from the start position, the origin).
#[test]
fn syntec_hole_patterns() {
    let Some(shared) = shared_dir() else {
        return;
    };
    assert_holes(
        &drilled(&shared, "67-g134-bolt-circle.nc"),
        &[
            (793.969, 234.202),
            (717.365, 298.481),
            (623.396, 264.279),
            (606.031, 165.798),
            (682.635, 101.519),
            (776.604, 135.721),
        ],
    );
    assert_holes(
        &drilled(&shared, "68-g135-angle-line.nc"),
        &[
            (200.0, 100.0),
            (286.603, 150.0),
            (373.205, 200.0),
            (459.808, 250.0),
            (546.410, 300.0),
        ],
    );
    assert_holes(
        &drilled(&shared, "69-g136-arc-holes.nc"),
        &[
            (595.442, 152.094),
            (571.892, 226.785),
            (529.813, 292.836),
            (472.073, 345.746),
            (402.606, 381.908),
            (326.147, 398.858),
        ],
    );
    // 10 x 8 holes row by row, every other row backwards: 80 holes, the last at (300, 600).
    let grid = drilled(&shared, "70-g137.1-grid.nc");
    let expected: Vec<(f64, f64)> = (0..8)
        .flat_map(|j| {
            (0..10).map(move |i| {
                let i = if j % 2 == 0 { i } else { 9 - i };
                (300.0 + 50.0 * i as f64, -100.0 + 100.0 * j as f64)
            })
        })
        .collect();
    assert_holes(&grid, &expected);
}

/// Syntec 1.62 example (file 70) move by move: G91 G81 Z-10. R5. K0 stores the cycle with R 5
/// above the initial level Z0 and the bottom 10 below R; G137.1 then drills the 10 x 8 grid
/// from (300, -100) (incremental from the start at the origin), every other row backwards (the
/// order the spec infers), each hole a rapid over it at Z0, a rapid to R, the feed at F20 to
/// the bottom and, in G98, a rapid back to Z0. The program has no M30: it ends at its text's
/// end with a warning.
#[test]
fn syntec_grid_example_move_by_move() {
    let mut lines = Vec::new();
    for j in 0..8 {
        for i in 0..10 {
            let i = if j % 2 == 0 { i } else { 9 - i };
            let (x, y) = (300 + 50 * i, -100 + 100 * j);
            lines.push(format!("rapid X{x} Y{y} Z0"));
            lines.push(format!("rapid X{x} Y{y} Z5"));
            lines.push(format!("line X{x} Y{y} Z-5 F20"));
            lines.push(format!("rapid X{x} Y{y} Z0"));
        }
    }
    lines.push("end EndOfText".into());
    // The warning for a program without M02/M30, at the last line.
    lines.push("alarm missing_program_end line 10".into());
    example("70-g137.1-grid.nc", &lines.join("\n"));
}

/// One hole of the bolt circle move by move (G91 R5 from the initial level 0: R at +5, the
/// bottom 10 below it; G98 back to 0).
#[test]
fn a_pattern_hole_is_a_full_cycle() {
    check_on(
        &Machine::default()
            .with_profile(ProfileName::Syntec)
            .unwrap(),
        "G91 G81 Z-10. R5. K0 F200.\nG134 X0 Y0 I10. J90. K1\nG80\nM30",
        "
        rapid X0 Y10 Z0
        rapid X0 Y10 Z5
        line X0 Y10 Z-5 F200
        rapid X0 Y10 Z0
        end M30",
    );
}

/// A pattern needs a cycle in force.
#[test]
fn a_pattern_without_a_cycle_alarms() {
    check_on(
        &Machine::default()
            .with_profile(ProfileName::Syntec)
            .unwrap(),
        "G134 X0 Y0 I10. J0 K4\nM30",
        "alarm cycle_data line 1",
    );
}

/// The holes of an example: machine X Y Z of every feed move's end, on `profile`.
fn bottoms(shared: &Path, file: &str, profile: ProfileName) -> Vec<(f64, f64, f64)> {
    let text = std::fs::read(shared.join("spec/examples").join(file)).unwrap();
    let run = common::run(
        &text,
        &Machine::default().with_profile(profile).unwrap(),
        vcnc::Options::default(),
    );
    assert!(run.error().is_none(), "{file}: {:?}", run.error());
    run.segments
        .iter()
        .filter_map(|s| match s.kind {
            vcnc::SegmentKind::Line { motion, .. } => {
                let p = motion.to.0;
                Some((p[0], p[1], p[2]))
            }
            _ => None,
        })
        .collect()
}

#[track_caller]
fn assert_points(actual: &[(f64, f64, f64)], expected: &[(f64, f64, f64)]) {
    assert!(actual.len() >= expected.len(), "{actual:?}");
    for (a, e) in actual.iter().zip(expected) {
        assert!(
            (a.0 - e.0).abs() < 1e-3 && (a.1 - e.1).abs() < 1e-3 && (a.2 - e.2).abs() < 1e-3,
            "point {a:?}, expected {e:?}"
        );
    }
}

/// Syntec 1.14 examples (files 20, 21): G16 hole positions as radius and angle. In example 2
/// the cycle's levels, set in G90, stay where they are when G91 steps the angle; K2 drills
/// twice, so a fourth hole falls at 450 = 90 degrees (the spec's literal reading).
#[test]
fn polar_hole_positions() {
    let Some(shared) = shared_dir() else {
        return;
    };
    let (c, s) = (86.60254, 50.0);
    assert_eq!(
        bottoms(
            &shared,
            "syntec/20-g16-polar-absolute.nc",
            ProfileName::Syntec
        )
        .len(),
        3
    );
    assert_points(
        &bottoms(
            &shared,
            "syntec/20-g16-polar-absolute.nc",
            ProfileName::Syntec,
        ),
        &[(0.0, 100.0, -12.0), (-c, -s, -12.0), (c, -s, -12.0)],
    );
    assert_points(
        &bottoms(
            &shared,
            "syntec/21-g16-polar-incremental.nc",
            ProfileName::Syntec,
        ),
        &[
            (0.0, 100.0, -12.0),
            (-c, -s, -12.0),
            (c, -s, -12.0),
            (0.0, 100.0, -12.0),
        ],
    );
}

/// Syntec 1.32 example (file 43): three holes in G54 at (90,15), (110,15), (100,65) to Z-15
/// (no length offset in the default machine), then the slot in the G52 system shifted by
/// (30,30) at Z-12.
#[test]
fn holes_and_a_slot_in_a_local_system() {
    let Some(shared) = shared_dir() else {
        return;
    };
    assert_points(
        &bottoms(
            &shared,
            "syntec/43-g52-local-coords.nc",
            ProfileName::Syntec,
        ),
        &[
            (90.0, 15.0, -15.0),
            (110.0, 15.0, -15.0),
            (100.0, 65.0, -15.0),
            (30.0, 30.0, -12.0),
            (50.0, 30.0, -12.0),
            (50.0, 40.0, -12.0),
        ],
    );
}

/// The FANUC 0M manual's O1717 (file examples/fanuc0m/24-o1717-drill-tap-bore.nc) calls G83
/// without Q after G80 has cleared it: the control stops with alarm 045 at that block (the
/// example's header; the original program is wrong there).
#[test]
fn fanuc_0m_o1717_stops_at_g83_without_q() {
    // Every move before the alarm, from the blocks: the G28 blocks in G91 with zero words do
    // not move; T01 drills (15,45) to Z-26 back to R-15 (G99), (40,15) back to the initial level
    // Z10 (G98), (90,30) from R5 to Z-6; G28 G91 Z0 lifts to the reference Z0; T02 drills the
    // first two holes to Z-45; the G83 block (line 37) has no Q.
    let Some(shared) = shared_dir() else {
        return;
    };
    let text =
        std::fs::read_to_string(shared.join("spec/examples/fanuc0m/24-o1717-drill-tap-bore.nc"))
            .unwrap();
    check_on(
        &Machine::default()
            .with_profile(ProfileName::Fanuc0m)
            .unwrap(),
        &text,
        "
        select T1
        change T1
        spindle Clockwise 2000
        rapid X0 Y0 Z10
        rapid X15 Y45 Z10
        rapid X15 Y45 Z-15
        line X15 Y45 Z-26 F200
        rapid X15 Y45 Z-15
        rapid X40 Y15 Z-15
        line X40 Y15 Z-26 F200
        rapid X40 Y15 Z10
        rapid X90 Y30 Z10
        rapid X90 Y30 Z5
        line X90 Y30 Z-6 F200
        rapid X90 Y30 Z10
        spindle Stopped 2000
        rapid X90 Y30 Z0
        select T2
        change T2
        spindle Clockwise 1800
        rapid X90 Y30 Z10
        rapid X15 Y45 Z10
        rapid X15 Y45 Z-15
        line X15 Y45 Z-45 F150
        rapid X15 Y45 Z-15
        rapid X40 Y15 Z-15
        line X40 Y15 Z-45 F150
        rapid X40 Y15 Z10
        alarm cycle_data line 37",
    );
}

/// The FANUC 0M manual's O1818 (file examples/fanuc0m/25-o1818-ream-bore-backbore.nc), length
/// offsets zero: the ends of every cutting move as the example's header works them out: centre
/// holes to Z-6 (R3 without a point is 0.003 mm on the 0M), drills to Z-24 (R cleared by G80:
/// the initial level Z5), the reamer fed in and out, counterbores to Z-12, the 30 mm drill to
/// Z-31, the boring bar to Z-22, and the back boring bar fed up from R-25 to Z-15.
#[test]
fn fanuc_0m_example_o1818() {
    let Some(shared) = shared_dir() else {
        return;
    };
    assert_points(
        &bottoms(
            &shared,
            "fanuc0m/25-o1818-ream-bore-backbore.nc",
            ProfileName::Fanuc0m,
        ),
        &[
            (15.0, 55.0, -6.0),
            (30.0, 35.0, -6.0),
            (50.0, 15.0, -6.0),
            (85.0, 35.0, -6.0),
            (85.0, 35.0, -24.0),
            (50.0, 15.0, -24.0),
            (15.0, 55.0, -24.0),
            (30.0, 35.0, -24.0),
            (30.0, 35.0, -24.0),
            (30.0, 35.0, 5.0),
            (15.0, 55.0, -12.0),
            (50.0, 15.0, -12.0),
            (85.0, 35.0, -31.0),
            (85.0, 35.0, -22.0),
            (85.0, 35.0, -15.0),
        ],
    );
}

/// The FANUC-family cycles in all three planes (spec A.32-A.43, 1.41-1.51): each cycle's
/// sequence written out from the manuals' step lists, for G17 (drilling along Z), G18 (along
/// Y) and G19 (along X). Holes at (5,5) and (15,5) return to R (G99), the third at (15,15) to
/// the initial level 10 (G98); R -5, bottom -10 (G87: from R -20 below up to -5), Q 2 (for the
/// taps: peck tapping, spec 1.42 type III), P 1 s.
#[test]
fn fanuc_cycles_in_three_planes() {
    // (plane code, positioning axes and drilling axis as X=0 Y=1 Z=2, their letters)
    let planes = [
        (17, [0, 1, 2], ["X", "Y", "Z"]),
        (18, [2, 0, 1], ["Z", "X", "Y"]),
        (19, [1, 2, 0], ["Y", "Z", "X"]),
    ];
    for (plane, axes, letters) in planes {
        for code in [73, 74, 76, 83, 84, 87, 88] {
            let point = |a: f64, b: f64, d: f64| {
                let mut p = [0.0; 3];
                (p[axes[0]], p[axes[1]], p[axes[2]]) = (a, b, d);
                format!("X{} Y{} Z{}", p[0], p[1], p[2])
            };
            let [la, lb, ld] = letters;
            let start = if code == 74 { "M04" } else { "M03" };
            let (r, z) = if code == 87 {
                (-20.0, -5.0)
            } else {
                (-5.0, -10.0)
            };
            let program = format!(
                "G{plane} G0 {la}0 {lb}0 {ld}10.\nS500 {start}\n\
                 G99 G{code} {la}5. {lb}5. {ld}{z}. R{r}. Q2. P1000 F100.\n{la}15.\nG98 {lb}15.\nG80\nM30"
            );
            let (forward, reverse) = if code == 74 {
                ("CounterClockwise", "Clockwise")
            } else {
                ("Clockwise", "CounterClockwise")
            };
            let mut expected = vec![format!("rapid {}", point(0.0, 0.0, 10.0))];
            expected.push(format!("spindle {forward} 500"));
            let mut level = 10.0;
            for (a, b, back) in [(5.0, 5.0, r), (15.0, 5.0, r), (15.0, 15.0, 10.0)] {
                let back = if code == 87 { 10.0 } else { back };
                let rapid = |d: f64| format!("rapid {}", point(a, b, d));
                let shifted = |d: f64, by: f64| format!("rapid {}", point(a + by, b, d));
                let feed = |d: f64| format!("line {} F100", point(a, b, d));
                let mut v = vec![rapid(level)];
                if code != 87 && level != r {
                    v.push(rapid(r));
                }
                match code {
                    73 => v.extend([
                        feed(-7.0),
                        rapid(-6.0),
                        feed(-9.0),
                        rapid(-8.0),
                        feed(-10.0),
                    ]),
                    83 => v.extend([
                        feed(-7.0),
                        rapid(r),
                        rapid(-6.0),
                        feed(-9.0),
                        rapid(r),
                        rapid(-8.0),
                        feed(-10.0),
                    ]),
                    // Q in a tapping cycle: peck tapping, back out to R after each peck.
                    74 | 84 => {
                        for depth in [-7.0, -9.0, -10.0] {
                            v.extend([
                                feed(depth),
                                "dwell 1".into(),
                                format!("spindle {reverse} 500"),
                                feed(r),
                                "dwell 1".into(),
                                format!("spindle {forward} 500"),
                            ]);
                        }
                    }
                    76 => v.extend([
                        feed(z),
                        "dwell 1".into(),
                        "spindle Oriented 500".into(),
                        shifted(z, 2.0),
                        shifted(back, 2.0),
                        rapid(back),
                        "spindle Clockwise 500".into(),
                    ]),
                    87 => v.extend([
                        "spindle Oriented 500".into(),
                        shifted(10.0, -2.0),
                        shifted(r, -2.0),
                        rapid(r),
                        "spindle Clockwise 500".into(),
                        feed(z),
                        "dwell 1".into(),
                        "spindle Oriented 500".into(),
                        shifted(z, -2.0),
                        shifted(10.0, -2.0),
                        "spindle Clockwise 500".into(),
                        rapid(10.0),
                    ]),
                    _ => v.extend([
                        feed(z),
                        "dwell 1".into(),
                        "spindle Stopped 500".into(),
                        "stop Program".into(),
                        feed(r),
                    ]),
                }
                // The return, where the cycle's own moves have not made it (G76 and G87 return
                // within their sequences; the others that end at R go on only under G98).
                match code {
                    73 | 83 => v.push(rapid(back)),
                    74 | 84 | 88 if back != r => v.push(rapid(back)),
                    _ => {}
                }
                if code == 88 {
                    v.push("spindle Clockwise 500".into());
                }
                expected.extend(v);
                level = back;
            }
            expected.push("end M30".into());
            check_on(&Machine::default(), &program, &expected.join("\n"));
        }
    }
}

/// A Mitsubishi machine with D1 = `d`.
fn mitsubishi(d: f64) -> Machine {
    let mut machine = Machine::default()
        .with_profile(ProfileName::Mitsubishi)
        .unwrap();
    machine.tool_offsets.insert(
        1,
        vcnc::machine::ToolOffset {
            number: 1,
            radius: d,
            ..Default::default()
        },
    );
    machine
}

/// Mitsubishi G12/G13 (spec B.6): from the centre a half circle of radius r/2 out to the circle,
/// the full circle, a half circle back, all clockwise for G12; r = |I| - D (15 here), a negative
/// offset enlarges it; in G18 the first plane axis is Z.
#[test]
fn mitsubishi_circle_cutting() {
    check_on(
        &mitsubishi(5.0),
        "G0 X10. Y10.\nG12 I20. D1 F100.\nM30",
        "
        rapid X10 Y10 Z0
        arc cw xy X25 Y10 Z0 C(17.5,10,0) F100
        arc cw xy X25 Y10 Z0 C(10,10,0) F100
        arc cw xy X10 Y10 Z0 C(17.5,10,0) F100
        end M30",
    );
    check_on(
        &mitsubishi(-5.0),
        "G18 G0 X10. Z10.\nG13 I-20. D1 F100.\nM30",
        "
        rapid X10 Y0 Z10
        arc ccw zx X10 Y0 Z35 C(10,0,22.5) F100
        arc ccw zx X10 Y0 Z35 C(10,0,10) F100
        arc ccw zx X10 Y0 Z10 C(10,0,22.5) F100
        end M30",
    );
}

#[test]
fn circle_cutting_alarms_and_exists_only_where_the_profile_has_it() {
    check_on(
        &mitsubishi(5.0),
        "G12 I20. F100.\nM30",
        "alarm circle_cutting line 1",
    );
    check_on(
        &mitsubishi(5.0),
        "G12 I5. D1 F100.\nM30",
        "alarm circle_cutting line 1",
    );
    check_on(
        &Machine::default(),
        "G12 I20. D1 F100.\nM30",
        "alarm unknown_g_code line 1",
    );
}

/// Syntec's E in G84 (spec 1.47): 20 threads per inch is a pitch of 1.27 mm; at S500 in G94 the
/// feed is 635 mm/min, in G95 1.27 mm/rev. With F in the block, E is ignored. E elsewhere is
/// refused.
#[test]
fn tapping_feed_from_threads_per_inch() {
    let syntec = Machine::default()
        .with_profile(ProfileName::Syntec)
        .unwrap();
    check_on(
        &syntec,
        "S500 M03\nG0 Z10.\nG84 X5. Z-5. R2. E20.\nG80\nM30",
        "
        spindle Clockwise 500
        rapid X0 Y0 Z10
        rapid X5 Y0 Z10
        rapid X5 Y0 Z2
        line X5 Y0 Z-5 F635
        spindle CounterClockwise 500
        line X5 Y0 Z2 F635
        spindle Clockwise 500
        rapid X5 Y0 Z10
        end M30",
    );
    check_on(
        &syntec,
        "S500 M03\nG95 G0 Z10.\nG84 X5. Z-5. R2. E20. F2.\nG80\nM30",
        "
        spindle Clockwise 500
        rapid X0 Y0 Z10
        rapid X5 Y0 Z10
        rapid X5 Y0 Z2
        line X5 Y0 Z-5 F2/rev
        spindle CounterClockwise 500
        line X5 Y0 Z2 F2/rev
        spindle Clockwise 500
        rapid X5 Y0 Z10
        end M30",
    );
    check_on(
        &syntec,
        "S500 M03\nG95 G0 Z10.\nG84 X5. Z-5. R2. E20.\nG80\nM30",
        "
        spindle Clockwise 500
        rapid X0 Y0 Z10
        rapid X5 Y0 Z10
        rapid X5 Y0 Z2
        line X5 Y0 Z-5 F1.27/rev
        spindle CounterClockwise 500
        line X5 Y0 Z2 F1.27/rev
        spindle Clockwise 500
        rapid X5 Y0 Z10
        end M30",
    );
    check_on(
        &syntec,
        "G0 Z10.\nG81 X5. Z-5. R2. E20. F100.\nM30",
        "
        rapid X0 Y0 Z10
        alarm cycle_data line 2",
    );
}

/// Limits that raise alarms instead of running for ever: K above the controls' 9999, a grid of
/// more than 9999 holes, a peck depth that would need more than 9999 pecks.
#[test]
fn counts_beyond_the_limits_alarm() {
    fanuc(
        "G0 Z10.\nG81 X5. Z-5. R2. F100. K10000\nM30",
        "
        rapid X0 Y0 Z10
        alarm cycle_data line 2",
    );
    fanuc(
        "G0 Z10.\nG83 X5. Z-5. R2. Q0.0001 F100.\nM30",
        "
        rapid X0 Y0 Z10
        rapid X5 Y0 Z10
        rapid X5 Y0 Z2
        alarm cycle_data line 2",
    );
    check_on(
        &Machine::default()
            .with_profile(ProfileName::Syntec)
            .unwrap(),
        "G81 Z-5. R2. F100. K0\nG137.1 X0 Y0 I1. P1000 J1. K1000\nM30",
        "alarm cycle_data line 2",
    );
}

/// A block that would make more than 100,000 moves alarms before moving.
#[test]
fn a_block_of_too_many_moves_alarms() {
    fanuc(
        "G0 Z10.\nG83 X5. Z-9. R0 Q0.001 K9999 F100.\nM30",
        "
        rapid X0 Y0 Z10
        alarm cycle_data line 2",
    );
}

/// Syntec 1.30 example (file 43) move by move, worked out from the blocks: the G54 block at the
/// start does not move; G99 G81 drills the three holes from R2 to Z-15 and stays at R; G28 goes
/// through G54 (0,0,10) to the reference point; the slot runs in the G52 system shifted by
/// (30,30) at Z-12 with the feed of the cycle block (F1000). D02 is not given in the manual, so
/// it holds 0 and the slot is the programmed path; H01 likewise.
#[test]
fn syntec_local_coordinates_example_move_by_move() {
    let slot = [
        (20, 0),
        (20, 10),
        (10, 10),
        (10, 20),
        (-10, 20),
        (-10, 10),
        (-20, 10),
        (-20, -10),
        (-10, -10),
        (-10, -20),
        (10, -20),
        (10, -10),
        (20, -10),
        (20, 0),
    ];
    // The holes: the tool is over the first one already and goes down to R; it reaches the
    // others over at R, where G99 left it.
    let mut lines = vec!["
        select T1
        spindle Clockwise 1000
        rapid X90 Y15 Z10
        rapid X90 Y15 Z2
        line X90 Y15 Z-15 F1000
        rapid X90 Y15 Z2
        rapid X110 Y15 Z2
        line X110 Y15 Z-15 F1000
        rapid X110 Y15 Z2
        rapid X100 Y65 Z2
        line X100 Y65 Z-15 F1000
        rapid X100 Y65 Z2
        spindle Stopped 1000
        rapid X0 Y0 Z10
        rapid X0 Y0 Z0
        select T2
        change T2
        spindle Clockwise 1000
        rapid X30 Y30 Z10
        line X30 Y30 Z-12 F1000"
        .to_string()];
    for (x, y) in slot {
        lines.push(format!("line X{} Y{} Z-12 F1000", x + 30, y + 30));
    }
    lines.extend(["rapid X50 Y30 Z10", "spindle Stopped 1000", "end M30"].map(String::from));
    let Some(shared) = shared_dir() else {
        return;
    };
    let text = std::fs::read_to_string(shared.join("spec/examples/syntec/43-g52-local-coords.nc"))
        .expect("the example is in ../shared");
    let machine = Machine::default()
        .with_profile(ProfileName::Syntec)
        .unwrap();
    check_on(&machine, &text, &lines.join("\n"));
}

/// A move of an expected sequence: kind, end point and, for arcs, the centre (machine X Y Z).
type Step = (&'static str, [f64; 3], Option<[f64; 3]>);

/// Asserts that `segments` are the moves of `expected` (events and alarms aside), within 1 um.
#[track_caller]
fn assert_moves(segments: &[vcnc::Segment], expected: &[Step]) {
    use vcnc::SegmentKind::{Arc, Line, Rapid};
    let actual: Vec<Step> = segments
        .iter()
        .filter_map(|s| {
            let to = |m: &vcnc::motion::Move| [m.to.0[0], m.to.0[1], m.to.0[2]];
            match &s.kind {
                Rapid { motion, .. } => Some(("rapid", to(motion), None)),
                Line { motion, .. } => Some(("line", to(motion), None)),
                Arc {
                    motion,
                    center,
                    direction,
                    ..
                } => Some((direction.as_str(), to(motion), Some(center.xyz()))),
                _ => None,
            }
        })
        .collect();
    assert_eq!(actual.len(), expected.len(), "{actual:?}");
    let near = |a: &[f64; 3], b: &[f64; 3]| a.iter().zip(b).all(|(a, b)| (a - b).abs() < 1e-3);
    for (i, (a, e)) in actual.iter().zip(expected).enumerate() {
        let centres = match (a.2, e.2) {
            (Some(a), Some(e)) => near(&a, &e),
            (None, None) => true,
            _ => false,
        };
        assert!(
            a.0 == e.0 && near(&a.1, &e.1) && centres,
            "move {i}: {a:?}, expected {e:?}"
        );
    }
}

/// Syntec 1.37 program 2 (file 49) move by move, executed literally (see the seed entry):
/// - eight petals, the path subprogram N100 under G68 by 0, 45 ... 315 degrees, in G16 polar
///   words: from 50 at 9.207 degrees a CCW R50 arc about the origin to 50 at 35.793 degrees,
///   then a CCW R8 half circle (its chord is 16.0002) about the chord's middle to 50 at
///   54.207 degrees, which is where the next petal starts (its G01 does not move);
/// - the small flower N200 at (-70, 10): four CCW R10 half circles round the square -90..-70 by
///   -10..10; it leaves G91 on, so `G51.1 Y-40.` mirrors about Y = 10 - 40 = -30 and the second
///   flower runs from (-70, -70) with CW arcs;
/// - G50 cancels scaling, not the mirror: the G134 holes (radius 75, 30 + 60k degrees) and the
///   G137.1 grid (X 60, 80, 100 by Y -60, -80, -100, every other row backwards) are mirrored
///   to y = -60 - y; each hole from the initial level Z0 to R2, the bottom Z-20 and back (G98).
#[test]
fn syntec_rotation_and_patterns_example_move_by_move() {
    let polar = |radius: f64, degrees: f64| {
        let r = degrees.to_radians();
        [radius * r.cos(), radius * r.sin(), 0.0]
    };
    let mut expected: Vec<Step> = vec![("rapid", polar(50.0, 9.207), None)];
    for k in 0..8 {
        let rotation = 45.0 * f64::from(k);
        expected.push(("ccw", polar(50.0, 35.793 + rotation), Some([0.0; 3])));
        let middle = polar(50.0 * 9.207_f64.to_radians().cos(), 45.0 + rotation);
        expected.push(("ccw", polar(50.0, 54.207 + rotation), Some(middle)));
    }
    expected.push(("rapid", [-80.0, 0.0, 0.0], None));
    expected.push(("rapid", [-70.0, 10.0, 0.0], None));
    for (end, centre) in [
        ([-90.0, 10.0], [-80.0, 10.0]),
        ([-90.0, -10.0], [-90.0, 0.0]),
        ([-70.0, -10.0], [-80.0, -10.0]),
        ([-70.0, 10.0], [-70.0, 0.0]),
    ] {
        expected.push((
            "ccw",
            [end[0], end[1], 0.0],
            Some([centre[0], centre[1], 0.0]),
        ));
    }
    let mirror = |p: [f64; 2]| [p[0], -60.0 - p[1], 0.0];
    expected.push(("rapid", mirror([-70.0, 10.0]), None));
    for (end, centre) in [
        ([-90.0, 10.0], [-80.0, 10.0]),
        ([-90.0, -10.0], [-90.0, 0.0]),
        ([-70.0, -10.0], [-80.0, -10.0]),
        ([-70.0, 10.0], [-70.0, 0.0]),
    ] {
        expected.push(("cw", mirror(end), Some(mirror(centre))));
    }
    let mut holes: Vec<[f64; 2]> = (0..6)
        .map(|k| {
            let p = polar(75.0, 30.0 + 60.0 * f64::from(k));
            [p[0], p[1]]
        })
        .collect();
    for j in 0..3 {
        for i in 0..3 {
            let i = if j % 2 == 0 { i } else { 2 - i };
            holes.push([60.0 + 20.0 * f64::from(i), -60.0 - 20.0 * f64::from(j)]);
        }
    }
    for hole in holes {
        let [x, y, _] = mirror(hole);
        expected.push(("rapid", [x, y, 0.0], None));
        expected.push(("rapid", [x, y, 2.0], None));
        expected.push(("line", [x, y, -20.0], None));
        expected.push(("rapid", [x, y, 0.0], None));
    }
    let Some(shared) = shared_dir() else {
        return;
    };
    let text =
        std::fs::read(shared.join("spec/examples/syntec/49-g68-rotation-8-petals-patterns.nc"))
            .expect("the example is in ../shared");
    let machine = Machine::default()
        .with_profile(ProfileName::Syntec)
        .unwrap();
    let run = common::run(&text, &machine, vcnc::Options::default());
    assert!(run.alarms.is_empty(), "{:?}", run.alarms);
    assert_moves(&run.segments, &expected);
}
