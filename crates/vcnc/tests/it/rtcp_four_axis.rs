//! 4-axis machines (one rotary axis, issue #23): G43.4 keeps the tool tip on the programmed
//! path while the one rotary axis turns, and G68.2 with G53.1 reaches the tilted planes that one
//! axis can (the others are the control's alarm). Checked as `five_axis.rs` checks 5-axis
//! machines: every joint move of the stream sampled through the kinematics' forward transform.

use super::five_axis::{
    assert_close, check_rtcp, end_of, kinematics, largest_deviation, last_joints, machine,
    motions_of, rtcp_block, run, TOLERANCE,
};
use crate::common;

use proptest::prelude::*;
use vcnc::{AlarmCode, Options};

/// A trunnion A about X alone, its line through (0, 5, -120).
const A_TABLE: &str = "[kinematics]\ntype = \"table\"\nrotary = [\n\
    { axis = \"a\", direction = [1.0, 0.0, 0.0], center = [0.0, 5.0, -120.0] },\n]\n";
/// A tilting table B about Y alone, its line through (10, 0, -80).
const B_TABLE: &str = "[kinematics]\ntype = \"table\"\nrotary = [\n\
    { axis = \"b\", direction = [0.0, 1.0, 0.0], center = [10.0, 0.0, -80.0] },\n]\n";
/// A rotary table C alone, its line through (3, 4, 0).
const C_TABLE: &str = "[kinematics]\ntype = \"table\"\nrotary = [\n\
    { axis = \"c\", direction = [0.0, 0.0, 1.0], center = [3.0, 4.0, 0.0] },\n]\n";
/// A B head alone, its pivot 90 above the spindle nose.
const B_HEAD: &str = "[kinematics]\ntype = \"head\"\nrotary = [\n\
    { axis = \"b\", direction = [0.0, 1.0, 0.0], center = [0.0, 0.0, 90.0] },\n]\n";
/// An A-C table's A with its line through the origin's 100 below, for the worked cases.
const A_TABLE_100: &str = "[kinematics]\ntype = \"table\"\nrotary = [\n\
    { axis = \"a\", direction = [1.0, 0.0, 0.0], center = [0.0, 0.0, -100.0] },\n]\n";

const KINDS: [(&str, &str); 4] = [
    ("a table", A_TABLE),
    ("b table", B_TABLE),
    ("c table", C_TABLE),
    ("b head", B_HEAD),
];

#[test]
fn a_turning_a_table_keeps_the_tip_where_it_is() {
    // G43.4 with a 60 mm tool on the A table whose line runs through (0, 0, -100): A 0 -> 90
    // with no X Y Z keeps the tip on the part's (0, 0, 0). Worked by hand at A 90: the part
    // point 100 above the line is carried to R_x(90) (0, 0, 100) = (0, -100, 0) about it, the
    // machine's (0, -100, -100); the control point is 60 above the tip: (0, -100, -40).
    let machine = machine(A_TABLE_100, 60.0);
    let kin = kinematics(&machine);
    let run = run("G43.4 H1\nG01 A90. F1000.\nM30\n", &machine);
    // G43.4 takes the length up as G43 does: the control point 60 above the tip.
    let start = end_of(&run, 1);
    assert_eq!(start[..4], [0.0, 0.0, 60.0, 0.0]);
    let pieces = motions_of(&run, 2);
    assert!(pieces.len() > 1, "the turn is cut into pieces");
    let worst = largest_deviation(kin, &pieces, 60.0, [0.0; 3], [0.0; 3]);
    assert!(worst <= TOLERANCE, "the tip wanders {worst}");
    let end = end_of(&run, 2);
    let want = [0.0, -100.0, -40.0, 90.0];
    assert!((0..4).all(|i| (end[i] - want[i]).abs() < 1e-9), "{end:?}");
}

#[test]
fn g53_1_tips_an_a_table_to_a_plane_about_x() {
    // G68.2 J30 tips the feature Z to Rx(30) z = (0, -sin 30, cos 30); the A table shows the
    // part the tool as R_x(-A) z = (0, sin A, cos A): A = -30. The tip then reaches the
    // feature point under G43.
    let program = "G68.2 X10. Y0 Z5. I0 J30. K0\nG53.1\nG43 H1\nG01 X0 Y0 Z0 F1000.\nM30\n";
    let machine = machine(A_TABLE_100, 60.0);
    let run = run(program, &machine);
    let turned = end_of(&run, 2);
    assert!((turned[3] + 30.0).abs() < 1e-9, "{turned:?}");
    let pose = kinematics(&machine).forward(&last_joints(&run), 60.0);
    assert_close(pose.tip, [10.0, 0.0, 5.0], 1e-9);
    let (s, c) = 30f64.to_radians().sin_cos();
    assert_close(pose.axis, [0.0, -s, c], 1e-12);
}

#[test]
fn g53_1_alarms_a_plane_one_axis_cannot_reach() {
    // I90 J30 turns that normal about Z: Rz(90) (0, -0.5, 0.866) = (0.5, 0, 0.866), which has
    // an X part no turn about X gives: the control's alarm. A B table reaches it at B -30
    // (R_y(-B) z = (-sin B, 0, cos B)).
    let program = "G68.2 X0 Y0 Z0 I90. J30. K0\nG53.1\nM30\n";
    let machine_a = machine(A_TABLE_100, 60.0);
    let run_a = common::run(program.as_bytes(), &machine_a, Options::default());
    let alarm = run_a.error().expect("out of reach");
    assert_eq!(alarm.code, AlarmCode::FiveAxis);
    assert!(
        alarm.message.contains("cannot point the tool"),
        "{}",
        alarm.message
    );
    let machine_b = machine(B_TABLE, 60.0);
    let turned = end_of(&run(program, &machine_b), 2);
    assert!((turned[4] + 30.0).abs() < 1e-9, "{turned:?}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    #[test]
    fn rtcp_on_one_rotary_axis_keeps_the_tip_on_the_path_and_the_axis_on_the_angle(
        kind in 0..4usize,
        blocks in prop::collection::vec(rtcp_block(1), 1..4),
    ) {
        // Acceptance 2 of #23 for the 4-axis kinematics, as `five_axis.rs` checks the others.
        let (name, table) = KINDS[kind];
        check_rtcp(name, table, &blocks)?;
    }
}
