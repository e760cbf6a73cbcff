//! G68/G69 coordinate rotation: hand-checked moves, and a program rotated by the code against
//! the same program rotated by hand (spec iso-syntec-milling.md 1.37).

use crate::common;

use crate::common::check;
use crate::common::contour::{assert_coded_is_by_hand, step};
use proptest::prelude::*;
use vcnc::{interpret_str, Machine, Options, SegmentKind};

#[test]
fn a_square_turned_a_quarter_turn_about_the_origin() {
    check(
        "G90 G17 G0 X0 Y0\nG68 X0 Y0 R90.\nG1 X10. F100.\nY10.\nX0\nG69\nX5.\nM30",
        "
        line X0 Y10 Z0 F100
        line X-10 Y10 Z0 F100
        line X-10 Y0 Z0 F100
        line X5 Y0 Z0 F100
        end M30",
    );
}

#[test]
fn the_centre_is_absolute_and_defaults_to_the_current_position() {
    // About (10,10) by 45 degrees: (20,10) goes to (10 + 10 cos 45, 10 + 10 sin 45).
    check(
        "G90 G0 X0 Y0\nG68 X10. Y10. R45.\nG1 X20. Y10. F100.\nM30",
        "
        line X17.0711 Y17.0711 Z0 F100
        end M30",
    );
    // No centre words: about the current position (5,0).
    check(
        "G90 G0 X5. Y0\nG68 R90.\nG1 X10. F100.\nM30",
        "
        rapid X5 Y0 Z0
        line X5 Y5 Z0 F100
        end M30",
    );
}

#[test]
fn incremental_moves_turn_with_the_rotation() {
    check(
        "G90 G0 X30. Y0\nG68 X0 Y0 R90.\nG91 G1 X10. F100.\nY10.\nM30",
        "
        rapid X30 Y0 Z0
        line X30 Y10 Z0 F100
        line X20 Y10 Z0 F100
        end M30",
    );
}

#[test]
fn an_incremental_angle_adds_to_the_rotation_in_force() {
    // 30 degrees, then G91 R60: 90 degrees in all. In G90 a second G68 replaces the angle: the
    // position (0,10) reads (0,-10) turned back by 180, so X10 goes to (10,-10), turned (-10,10).
    check(
        "G90 G0 X0 Y0\nG68 X0 Y0 R30.\nG91 G68 R60.\nG90 G1 X10. F100.\nG68 X0 Y0 R180.\nX10.\nM30",
        "
        line X0 Y10 Z0 F100
        line X-10 Y10 Z0 F100
        end M30",
    );
}

#[test]
fn arcs_turn_with_their_centre_offsets() {
    // The tool at (0,-10) reads (-10,0) in the system turned by 90 degrees; the arc's centre is
    // (-10,0) + (0,10) there, (-10,-10) on the machine, and its end (0,10) is (-10,0).
    check(
        "G90 G0 X0 Y-10.\nG68 X0 Y0 R90.\nG3 X0 Y10. I0 J10. F100.\nM30",
        "
        rapid X0 Y-10 Z0
        arc ccw xy X-10 Y0 Z0 C(-10,-10,0) F100
        end M30",
    );
}

#[test]
fn the_g68_block_does_not_move() {
    check(
        "G90 G0 X1. Y2.\nG68 X50. Y50. R10.\nG69\nM30",
        "
        rapid X1 Y2 Z0
        end M30",
    );
}

#[test]
fn the_plane_cannot_change_while_rotated_and_g92_is_refused() {
    check(
        "G17 G68 X0 Y0 R10.\nG18\nM30",
        "alarm word_not_allowed line 2",
    );
    check(
        "G68 X0 Y0 R10.\nG92 X0 Y0\nM30",
        "alarm not_supported_yet line 2",
    );
}

#[test]
fn the_reported_position_is_the_programmed_one() {
    let machine = Machine::default();
    let mut interpreter = interpret_str(
        "G90 G0 X0 Y0\nG68 X0 Y0 R90.\nG1 X10. Y5. F100.\nM30",
        &machine,
        Options::default(),
    );
    for item in interpreter.by_ref() {
        let Some(segment) = item.unwrap().into_segment() else {
            continue;
        };
        if let SegmentKind::Line { motion, .. } = segment.kind {
            assert!((motion.to.0[0] + 5.0).abs() < 1e-12);
            assert!((motion.to.0[1] - 10.0).abs() < 1e-12);
        }
    }
    let position = interpreter.program_position();
    assert!((position[0] - 10.0).abs() < 1e-12 && (position[1] - 5.0).abs() < 1e-12);
}

proptest! {
    /// G68 about (cx, cy) by a random angle gives the machine path of the same program with
    /// every point rotated by hand.
    #[test]
    fn rotating_by_code_is_rotating_by_hand(
        steps in proptest::collection::vec(step(), 1..12),
        cx in -50.0f64..50.0,
        cy in -50.0f64..50.0,
        degrees in -360.0f64..360.0,
    ) {
        let (sin, cos) = degrees.to_radians().sin_cos();
        let by_hand = move |x: f64, y: f64| {
            (cx + (x - cx) * cos - (y - cy) * sin, cy + (x - cx) * sin + (y - cy) * cos)
        };
        let header = format!("G68 X{cx:.9} Y{cy:.9} R{degrees:.9}\n");
        assert_coded_is_by_hand(&steps, &by_hand, false, &header, &Machine::default())?;
    }
}

/// Syntec's G92.1 with rotation (spec 1.55, file examples/syntec/63-g92.1-rotated-preset.nc):
/// after `G92.1 X10. Y10. K1. R45.` at (20,20) the program position is (14.142, 0); `G01 X100.`
/// (Syntec's default feed) goes to machine (10,10) + 100 (cos 45, sin 45) = (80.711, 80.711),
/// program (100, 0).
#[test]
fn syntec_g92_1_presets_with_a_rotation() {
    let Some(shared) = common::shared_dir() else {
        return;
    };
    let text =
        std::fs::read(shared.join("spec/examples/syntec/63-g92.1-rotated-preset.nc")).unwrap();
    let machine = vcnc::Machine::default()
        .with_profile(vcnc::ProfileName::Syntec)
        .unwrap();
    let run = common::run(&text, &machine, vcnc::Options::default());
    assert!(run.error().is_none(), "{:?}", run.error());
    let last = run
        .segments
        .iter()
        .rev()
        .find_map(|s| s.motion())
        .expect("the example moves");
    let (m, w) = (last.to.0, last.work_to());
    assert!(
        (m[0] - 80.7107).abs() < 1e-4 && (m[1] - 80.7107).abs() < 1e-4,
        "{m:?}"
    );
    assert!((w[0] - 100.0).abs() < 1e-9 && w[1].abs() < 1e-9, "{w:?}");
    // FANUC's G92.1 has no rotation.
    let fanuc = common::run(
        b"G92.1 X10. Y10. K1. R45.\nM30\n",
        &vcnc::Machine::default(),
        vcnc::Options::default(),
    );
    assert!(fanuc.error().is_some());
}
