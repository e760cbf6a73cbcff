//! G43.5, FANUC's tool centre point control type 2 (issue #23): the motion blocks give the tool
//! direction by I J K and the control solves the rotary axes (docs/KINEMATICS.md, the rule in
//! `interp/tool_center.rs`). Worked by hand on the A-C table of `five_axis.rs` (A about X
//! carrying C about Z), where the tool seen from the part is (sin A sin C, sin A cos C, cos A).

use super::five_axis::{
    end_of, kinematics, largest_deviation, machine, motions_of, run, A_C_TABLE, TOLERANCE,
};
use crate::common;

use proptest::prelude::*;
use vcnc::{AlarmCode, Machine, Options, ProfileName};

const C_B_HEAD: &str = "[kinematics]\ntype = \"head_head\"\nrotary = [\n\
    { axis = \"c\", direction = [0.0, 0.0, 1.0], center = [0.0, 0.0, 120.0] },\n\
    { axis = \"b\", direction = [0.0, 1.0, 0.0], center = [0.0, 0.0, 120.0] },\n]\n";
const A_TABLE: &str = "[kinematics]\ntype = \"table\"\nrotary = [\n\
    { axis = \"a\", direction = [1.0, 0.0, 0.0], center = [0.0, 0.0, -100.0] },\n]\n";

fn fanuc(kinematics: &str) -> Machine {
    machine(kinematics, 100.0)
        .with_profile(ProfileName::Fanuc)
        .expect("the fanuc profile")
}

#[track_caller]
fn alarm(program: &str, machine: &Machine) -> AlarmCode {
    let run = common::run(program.as_bytes(), machine, Options::default());
    run.error().expect("an alarm").code
}

/// A and C where program line `line` leaves them.
fn a_c(run: &common::Run, line: u32) -> (f64, f64) {
    let end = end_of(run, line);
    (end[3], end[5])
}

#[track_caller]
fn assert_angles(got: (f64, f64), want: (f64, f64)) {
    assert!(
        (got.0 - want.0).abs() < 1e-9 && (got.1 - want.1).abs() < 1e-9,
        "A C {got:?}, want {want:?}"
    );
}

#[test]
fn the_rotary_axes_follow_the_programmed_direction_by_the_shortest_way() {
    // Line 2, (0, 1, 1): sin A cos C = cos A, sin A sin C = 0: A 45 C 0 (travel 45) or A -45
    // C 180 (225): A 45 C 0. Line 3, (1, 0, 1): A 45 C 90 (travel 90) or A -45 C -90 (180).
    // Line 4, (-1, 0, 1): A 45 C -90 (C turns 180) or A -45 C 90 (A turns 90): the second.
    // Line 5, (0, 0, 1): A 0, C stays (any C gives it).
    let program = "G43.5 H1\nG01 X10. Y0 Z0 I0 J1. K1. F1000.\nG01 X20. I1. J0 K1.\n\
                   G01 X30. I-1. J0 K1.\nG01 I0 J0 K1.\nG49\nM30\n";
    let machine = fanuc(A_C_TABLE);
    let run = run(program, &machine);
    assert_angles(a_c(&run, 2), (45.0, 0.0));
    assert_angles(a_c(&run, 3), (45.0, 90.0));
    assert_angles(a_c(&run, 4), (-45.0, 90.0));
    assert_angles(a_c(&run, 5), (0.0, 90.0));
    // The tip stays on each line while the axes turn, and on its point at the end of line 5
    // (I J K alone turn the tool about its tip).
    let kin = kinematics(&machine);
    for (line, from, to) in [
        (2, [0.0; 3], [10.0, 0.0, 0.0]),
        (3, [10.0, 0.0, 0.0], [20.0, 0.0, 0.0]),
        (4, [20.0, 0.0, 0.0], [30.0, 0.0, 0.0]),
        (5, [30.0, 0.0, 0.0], [30.0, 0.0, 0.0]),
    ] {
        let pieces = motions_of(&run, line);
        let worst = largest_deviation(kin, &pieces, 100.0, from, to);
        assert!(worst <= TOLERANCE, "line {line}: {worst}");
    }
    let pose = kin.forward(&end_of(&run, 5), 100.0);
    assert!(
        (pose.tip[0] - 30.0).abs() < 1e-9 && pose.tip[2].abs() < 1e-9,
        "{pose:?}"
    );
}

#[test]
fn the_direction_is_read_in_the_program_system() {
    // Under G68.2 I90 (Rz(90)) the program's (1, 0, 1) is the work's (0, 1, 1): A 45 C 0.
    let program = "G68.2 X0 Y0 Z0 I90. J0 K0\nG43.5 H1\nG01 X10. I1. J0 K1. F1000.\nM30\n";
    let run = run(program, &fanuc(A_C_TABLE));
    assert_angles(a_c(&run, 3), (45.0, 0.0));
}

#[test]
fn a_head_machine_takes_the_direction_in_the_g43_5_block() {
    // On the C-B head the G43.5 block may carry I J K (FANUC: only where the table does not
    // turn). (1, 0, 1): B 45 with C 0 (R_y(45) z = (sin 45, 0, cos 45)).
    let run = run("G43.5 H1 I1. J0 K1.\nM30\n", &fanuc(C_B_HEAD));
    let end = end_of(&run, 1);
    assert!(
        (end[4] - 45.0).abs() < 1e-9 && end[5].abs() < 1e-9,
        "{end:?}"
    );
}

#[test]
fn what_g43_5_refuses() {
    let table = fanuc(A_C_TABLE);
    let cases = [
        // PS5421: I J K in the G43.5 block of a machine whose table turns.
        ("G43.5 H1 I0 J1. K1.\nM30\n", AlarmCode::WordNotAllowed),
        // Rotary words beside I J K, and I J K as an arc's centre.
        (
            "G43.5 H1\nG01 X1. A10. I0 J1. K1. F100.\nM30\n",
            AlarmCode::WordNotAllowed,
        ),
        (
            "G43.5 H1\nG02 X10. Y0 I5. J0 F100.\nM30\n",
            AlarmCode::WordNotAllowed,
        ),
        ("G43.5 H1 Q2.\nM30\n", AlarmCode::NotSupportedYet),
        (
            "G43.5 H1\nG01 X1. I0 J0 K0 F100.\nM30\n",
            AlarmCode::FiveAxis,
        ),
    ];
    for (program, code) in cases {
        assert_eq!(alarm(program, &table), code, "{program}");
    }
    // A turn about X alone cannot lean the tool towards X.
    let program = "G43.5 H1\nG01 X1. I1. J0 K1. F100.\nM30\n";
    assert_eq!(alarm(program, &fanuc(A_TABLE)), AlarmCode::FiveAxis);
    // Syntec's manual has no G43.5.
    let syntec = machine(A_C_TABLE, 100.0);
    assert_eq!(alarm("G43.5 H1\nM30\n", &syntec), AlarmCode::UnknownGCode);
}

/// A random G43.5 block: a tip end point and a tool direction leaning at most about 78 degrees
/// from Z (within reach of both machines below).
fn direction_block() -> impl Strategy<Value = ([f64; 3], [f64; 3])> {
    (
        prop::array::uniform3(-80.0..80.0f64),
        prop::array::uniform2(-1.0..1.0f64),
        0.2..1.0f64,
    )
        .prop_map(|(p, [i, j], k)| {
            let round = |v: f64, places: f64| (v * places).round() / places;
            (
                p.map(|v| round(v, 1e3)),
                [round(i, 1e4), round(j, 1e4), round(k, 1e4)],
            )
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn g43_5_ends_each_block_on_its_point_with_the_programmed_direction(
        head in any::<bool>(),
        blocks in prop::collection::vec(direction_block(), 1..4),
    ) {
        // On the A-C table and the C-B head: the tip within the tolerance of each block's line,
        // and at the block's end the tool along I J K (normalised) with the tip on its point.
        let (name, table) = if head { ("head", C_B_HEAD) } else { ("table", A_C_TABLE) };
        let machine = fanuc(table);
        let kin = kinematics(&machine);
        let mut program = String::from("G43.5 H1\n");
        for (p, d) in &blocks {
            program += &format!(
                "G01 X{:.3} Y{:.3} Z{:.3} I{:.4} J{:.4} K{:.4} F2000.\n",
                p[0], p[1], p[2], d[0], d[1], d[2]
            );
        }
        program += "G49\nM30\n";
        let run = run(&program, &machine);
        let mut from = [0.0; 3];
        for (i, (to, d)) in blocks.iter().enumerate() {
            let line = 2 + i as u32;
            let worst = largest_deviation(kin, &motions_of(&run, line), 100.0, from, *to);
            prop_assert!(worst <= TOLERANCE, "{}: block {}: {}", name, i, worst);
            let pose = kin.forward(&end_of(&run, line), 100.0);
            let n = d.iter().map(|v| v * v).sum::<f64>().sqrt();
            for k in 0..3 {
                prop_assert!((pose.axis[k] - d[k] / n).abs() < 1e-9, "{}: {:?} {:?}", name, pose.axis, d);
                prop_assert!((pose.tip[k] - to[k]).abs() < 1e-9, "{}: {:?} {:?}", name, pose.tip, to);
            }
            from = *to;
        }
    }
}
