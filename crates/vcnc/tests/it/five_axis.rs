//! 5-axis machining (issue #23): G43.4 tool centre point control, G68.2 tilted working plane and
//! G53.1 tool axis direction on machines whose kinematics the machine file describes.
//!
//! Every check looks at the tool as the machine holds it: each joint move of the stream is
//! sampled, the kinematics' forward transform gives the tool tip and axis in the workpiece, and
//! those are compared with the programmed path. The manual's examples (Syntec 37 and 45) are
//! run with the manual's numbers; the property test runs random rotary moves on each type.

use crate::common;

use proptest::prelude::*;
use vcnc::kinematics::{Kinematics, ToolPose, Vec3};
use vcnc::{AlarmCode, Machine, Options, Segment};

/// The machine's smoothing tolerance (default machine file), mm: the tip's largest distance from
/// the programmed path between the ends of the pieces.
pub(crate) const TOLERANCE: f64 = 0.01;

/// Rotary axes `a`, `b`, `c` without limits, and a `[kinematics]` table, on the default machine
/// of `profile` with H1 = `length`.
pub(crate) fn machine(kinematics: &str, length: f64) -> Machine {
    let axis = |name: &str| {
        format!(
            "[axes.{name}]\nmin = -100000.0\nmax = 100000.0\nrapid = 36000.0\nmax_feed = 36000.0\n\n"
        )
    };
    let text = vcnc::machine::DEFAULT_MACHINE_TOML
        .replace("profile = \"fanuc\"", "profile = \"syntec\"")
        .replace(
            "[start]",
            &format!(
                "{}{}{}{kinematics}\n[start]",
                axis("a"),
                axis("b"),
                axis("c")
            ),
        )
        .replace(
            "number = 1\nlength = 0.0",
            &format!("number = 1\nlength = {length:?}"),
        );
    Machine::from_toml(&text).expect("a valid machine file")
}

/// A B-C table: B about Y through (10, 0, -150), C about Z on it through (10, 5, -150).
const TABLE_TABLE: &str = "[kinematics]\ntype = \"table_table\"\nrotary = [\n\
    { axis = \"b\", direction = [0.0, 1.0, 0.0], center = [10.0, 0.0, -150.0] },\n\
    { axis = \"c\", direction = [0.0, 0.0, 1.0], center = [10.0, 5.0, -150.0] },\n]\n";
/// An A-C table (trunnion A about X carrying C), centres at the origin's 100 below.
pub(crate) const A_C_TABLE: &str = "[kinematics]\ntype = \"table_table\"\nrotary = [\n\
    { axis = \"a\", direction = [1.0, 0.0, 0.0], center = [0.0, 0.0, -100.0] },\n\
    { axis = \"c\", direction = [0.0, 0.0, 1.0], center = [0.0, 0.0, -100.0] },\n]\n";
/// A C-B head: C about Z carrying a B fork about Y, pivot 120 above the spindle nose, C's line
/// 2 mm off the spindle.
const HEAD_HEAD: &str = "[kinematics]\ntype = \"head_head\"\nrotary = [\n\
    { axis = \"c\", direction = [0.0, 0.0, 1.0], center = [2.0, 0.0, 120.0] },\n\
    { axis = \"b\", direction = [0.0, 1.0, 0.0], center = [0.0, 0.0, 120.0] },\n]\n";
/// A B head (pivot 90 above the nose) and a C table through (0, 0, -50).
const HEAD_TABLE: &str = "[kinematics]\ntype = \"head_table\"\nrotary = [\n\
    { axis = \"b\", direction = [0.0, 1.0, 0.0], center = [0.0, 0.0, 90.0] },\n\
    { axis = \"c\", direction = [0.0, 0.0, 1.0], center = [0.0, 0.0, -50.0] },\n]\n";

const KINDS: [(&str, &str); 3] = [
    ("table_table", TABLE_TABLE),
    ("head_head", HEAD_HEAD),
    ("head_table", HEAD_TABLE),
];

pub(crate) fn kinematics(machine: &Machine) -> &Kinematics {
    machine
        .kinematics
        .as_ref()
        .expect("the machine has kinematics")
}

#[track_caller]
pub(crate) fn run(program: &str, machine: &Machine) -> common::Run {
    let run = common::run(program.as_bytes(), machine, Options::default());
    assert!(run.error().is_none(), "{:?}", run.error());
    run
}

/// The motion segments of `run` written by program line `line` (1-based).
pub(crate) fn motions_of(run: &common::Run, line: u32) -> Vec<Segment> {
    run.segments
        .iter()
        .filter(|s| s.motion().is_some() && s.span.line == line)
        .copied()
        .collect()
}

/// Where the last motion of program line `line` leaves the joints.
pub(crate) fn end_of(run: &common::Run, line: u32) -> [f64; 6] {
    let last = motions_of(run, line)
        .last()
        .and_then(|s| s.motion().copied());
    last.expect("the line moves").to.0
}

/// Where the last motion of `run` leaves the joints.
pub(crate) fn last_joints(run: &common::Run) -> [f64; 6] {
    let last = run.segments.iter().rev().find_map(|s| s.motion());
    last.expect("the program moves").to.0
}

pub(crate) fn lerp(a: &[f64; 6], b: &[f64; 6], s: f64) -> [f64; 6] {
    std::array::from_fn(|i| a[i] + (b[i] - a[i]) * s)
}

/// Distance from `p` to the segment `a`-`b`, and the parameter of the nearest point.
pub(crate) fn to_segment(p: Vec3, a: Vec3, b: Vec3) -> (f64, f64) {
    let d: Vec3 = std::array::from_fn(|i| b[i] - a[i]);
    let len2 = d.iter().map(|v| v * v).sum::<f64>();
    let t = if len2 == 0.0 {
        0.0
    } else {
        ((0..3).map(|i| (p[i] - a[i]) * d[i]).sum::<f64>() / len2).clamp(0.0, 1.0)
    };
    let q: Vec3 = std::array::from_fn(|i| a[i] + d[i] * t - p[i]);
    (q.iter().map(|v| v * v).sum::<f64>().sqrt(), t)
}

/// The largest distance of the tip from the line `a`-`b` over 16 samples of every joint move
/// of `pieces`, with a tool `length` long.
pub(crate) fn largest_deviation(
    kin: &Kinematics,
    pieces: &[Segment],
    length: f64,
    a: Vec3,
    b: Vec3,
) -> f64 {
    let mut worst: f64 = 0.0;
    for piece in pieces {
        let m = piece.motion().expect("a motion");
        for k in 0..=16 {
            let joints = lerp(&m.from.0, &m.to.0, f64::from(k) / 16.0);
            let tip = kin.forward(&joints, length).tip;
            worst = worst.max(to_segment(tip, a, b).0);
        }
    }
    worst
}

fn pose_at(kin: &Kinematics, angles: [(usize, f64); 2], length: f64) -> ToolPose {
    let mut joints = [0.0; 6];
    for (slot, angle) in angles {
        joints[slot] = angle;
    }
    kin.forward(&joints, length)
}

/// The Syntec manual's example `file` from ../shared (none when ../shared is absent).
fn example(file: &str) -> Option<String> {
    let path = common::shared::shared_dir()?
        .join("spec/examples/syntec")
        .join(file);
    Some(std::fs::read_to_string(path).expect("the example is in ../shared"))
}

#[track_caller]
pub(crate) fn assert_close(got: Vec3, want: Vec3, within: f64) {
    let d = (0..3).map(|i| (got[i] - want[i]).abs()).fold(0.0, f64::max);
    assert!(d <= within, "{got:?} is not {want:?} (within {within})");
}

#[test]
fn syntec_example_37_keeps_the_tip_on_the_line_while_b_turns() {
    // spec/examples/syntec/37-g43.4-with-rtcp.nc (seed 000 L1930): "the tool tip moves on the
    // straight line 0,0,0 to 50,0,0 while B turns to -45 deg, the linear axes compensating". The
    // manual gives no kinematics, so the example runs on all three types with a 100 mm tool.
    let Some(program) = example("37-g43.4-with-rtcp.nc") else {
        return;
    };
    for (name, table) in KINDS {
        let machine = machine(table, 100.0);
        let kin = kinematics(&machine);
        let run = run(&program, &machine);
        let line = 1 + program.lines().position(|l| l.starts_with("G01")).unwrap() as u32;
        let pieces = motions_of(&run, line);
        assert!(pieces.len() > 1, "{name}: the block is cut into pieces");
        let worst = largest_deviation(kin, &pieces, 100.0, [0.0; 3], [50.0, 0.0, 0.0]);
        assert!(
            worst <= TOLERANCE,
            "{name}: the tip leaves the line by {worst}"
        );
        let end = last_joints(&run);
        let pose = kin.forward(&end, 100.0);
        assert_close(pose.tip, [50.0, 0.0, 0.0], 1e-9);
        assert_eq!(
            (end[4], end[5]),
            (-45.0, 0.0),
            "{name}: B and C as programmed"
        );
    }
    // On the B-C table the part turns -45 about Y, so the tool seen from the part leans to +X:
    // R_y(45) (0, 0, 1) = (sin 45, 0, cos 45).
    let machine = machine(TABLE_TABLE, 100.0);
    let pose = pose_at(kinematics(&machine), [(4, -45.0), (5, 0.0)], 100.0);
    let h = 0.5f64.sqrt();
    assert_close(pose.axis, [h, 0.0, h], 1e-12);
}

#[test]
fn syntec_example_36_without_rtcp_lets_the_tip_swing_off_the_line() {
    // spec/examples/syntec/36-g43.4-without-rtcp.nc: "linear and rotary axes move
    // independently: X to 50 while B turns to -45 deg, the tool tip leaves the straight line".
    // On the B-C table (B's line 150 below the zero) the joints run straight, so half way (B at
    // -22.5) the tip is off the line Y0 Z0 by far more than the tolerance.
    let program = "G43 H1\nG00 X0 Y0 Z0 B0 C0\nG01 X50. Y0 Z0 B-45. C0\nM30\n";
    let machine = machine(TABLE_TABLE, 100.0);
    let run = run(program, &machine);
    let pieces = motions_of(&run, 3);
    assert_eq!(pieces.len(), 1, "one straight joint move");
    let m = pieces[0].motion().unwrap();
    assert_eq!(m.to.0, [50.0, 0.0, 100.0, 0.0, -45.0, 0.0]);
    let worst = largest_deviation(
        kinematics(&machine),
        &pieces,
        100.0,
        [0.0; 3],
        [50.0, 0.0, 0.0],
    );
    assert!(worst > 10.0, "{worst}");
}

#[test]
fn g49_gives_the_joints_back_to_plain_moves() {
    // After G49 the machine's X Y Z are programmed directly again: from the joints where RTCP
    // left them (B -45), G91 X10. moves X alone by 10.
    let program = "G43.4 H1\nG01 X50. B-45. F1000.\nG49\nG91 G01 X10.\nM30\n";
    let machine = machine(TABLE_TABLE, 100.0);
    let run = run(program, &machine);
    let rtcp_end = end_of(&run, 2);
    let after: Vec<_> = motions_of(&run, 4);
    assert_eq!(after.len(), 1);
    let m = after[0].motion().unwrap();
    assert_eq!(m.from.0[4], -45.0);
    assert!((m.to.0[0] - m.from.0[0] - 10.0).abs() < 1e-12);
    assert!((m.to.0[2] - m.from.0[2]).abs() < 1e-12);
    // G49 without Z took the length away as `G91 Z0` would: Z moved down by the length.
    let g49 = motions_of(&run, 3);
    assert!((g49[0].motion().unwrap().to.0[2] - (rtcp_end[2] - 100.0)).abs() < 1e-9);
}

#[test]
fn syntec_example_45_turns_the_tool_normal_to_the_tilted_plane() {
    // spec/examples/syntec/45-g68.2-g53.1-tilted-plane.nc (seed 000 L2583-2628): R = Rz(30)
    // Rx(15) Rz(20). N3 ends at G54 (106.4705, 88.7928, 98.2963) with the tool unturned; N4
    // turns the tool axis to (0.129410, -0.224144, 0.965926); N6 puts the tool tip at G54
    // (100, 100, 50). On an A-C table the tool seen from the part is
    // (sin A sin C, sin A cos C, cos A): A = -15, C = -30 (the nearer of two solutions; the
    // other is A 15, C 150).
    let Some(program) = example("45-g68.2-g53.1-tilted-plane.nc") else {
        return;
    };
    let machine = machine(A_C_TABLE, 100.0);
    let kin = kinematics(&machine);
    let run = run(&program, &machine);
    let line = |n: &str| {
        1 + program
            .lines()
            .position(|l| l.starts_with(n))
            .expect("the block") as u32
    };
    let n3 = end_of(&run, line("N3 "));
    assert_close([n3[0], n3[1], n3[2]], [106.4705, 88.7928, 98.2963], 5e-5);
    let n4 = end_of(&run, line("N4 "));
    assert!(
        (n4[3] + 15.0).abs() < 1e-9 && (n4[5] + 30.0).abs() < 1e-9,
        "{n4:?}"
    );
    assert_eq!(
        [n4[0], n4[1], n4[2]],
        [n3[0], n3[1], n3[2]],
        "N4 turns only A and C"
    );
    let axis = kin.forward(&n4, 0.0).axis;
    assert_close(axis, [0.129410, -0.224144, 0.965926], 5e-7);
    let n6 = last_joints(&run);
    let pose = kin.forward(&n6, 100.0);
    assert_close(pose.tip, [100.0, 100.0, 50.0], 1e-9);
    assert_close(pose.axis, [0.129410, -0.224144, 0.965926], 5e-7);
}

#[test]
fn g53_1_on_a_head_turns_the_head_and_the_tip_reaches_the_feature_point() {
    // The same program on the C-B head: the tool must end along the feature Z with its tip at
    // G54 (100, 100, 50) whatever the head's solution.
    let program = "G90 G54 G01 X0 Y0 Z50. F1000\nG68.2 X100. Y100. Z50. I30. J15. K20.\n\
                   G01 X0 Y0 Z50.\nG53.1\nG43 H1\nG01 X0 Y0 Z0\nM30\n";
    let machine = machine(HEAD_HEAD, 100.0);
    let pose = kinematics(&machine).forward(&last_joints(&run(program, &machine)), 100.0);
    assert_close(pose.tip, [100.0, 100.0, 50.0], 1e-9);
    assert_close(pose.axis, [0.129410, -0.224144, 0.965926], 5e-7);
}

#[test]
fn g43_4_under_g68_2_follows_the_feature_line() {
    // G68.2 turns the program about Z by 90 degrees (I90): feature X is work Y. Under G43.4 a
    // feature line X0 -> X40 with B turning is a work line (10, 0, 5) -> (10, 40, 5).
    let program = "G68.2 X10. Y0 Z5. I90. J0 K0\nG43.4 H1\nG00 X0 Y0 Z0 B0 C0\n\
                   G01 X40. B30. C20. F1000\nG69\nG49\nM30\n";
    for (name, table) in KINDS {
        let machine = machine(table, 80.0);
        let run = run(program, &machine);
        let pieces = motions_of(&run, 4);
        let kin = kinematics(&machine);
        let worst = largest_deviation(kin, &pieces, 80.0, [10.0, 0.0, 5.0], [10.0, 40.0, 5.0]);
        assert!(worst <= TOLERANCE, "{name}: {worst}");
        let end = pieces.last().unwrap().motion().unwrap().to.0;
        assert_close(kin.forward(&end, 80.0).tip, [10.0, 40.0, 5.0], 1e-9);
    }
}

#[test]
fn five_axis_codes_without_kinematics_or_plane_are_alarms() {
    let plain = common::with_c_axis(vcnc::ProfileName::Syntec);
    let run = common::run(b"G43.4 H1\nM30\n", &plain, Options::default());
    assert_eq!(run.error().map(|a| a.code), Some(AlarmCode::FiveAxis));
    let machine = machine(TABLE_TABLE, 100.0);
    let run = common::run(b"G53.1\nM30\n", &machine, Options::default());
    assert_eq!(run.error().map(|a| a.code), Some(AlarmCode::FiveAxis));
    let run = common::run(
        b"G43.4 H1\nG41 D1 X10.\nM30\n",
        &machine,
        Options::default(),
    );
    assert_eq!(run.error().map(|a| a.code), Some(AlarmCode::WordNotAllowed));
    // Spec 1.26 rule 5: G05 P10000 in G43.4 is Syntec's COR-140.
    let hpcc = b"G43.4 H1\nG05 P10000\nM30\n";
    let run = common::run(hpcc, &machine, Options::default());
    let alarm = run.error().expect("COR-140");
    assert_eq!(alarm.code, AlarmCode::SmoothingCommand);
    assert!(alarm.message.contains("COR-140"), "{}", alarm.message);
    // FANUC 0M's manual has no G43.4.
    let old = plain.with_profile(vcnc::ProfileName::Fanuc0m).unwrap();
    let run = common::run(b"G43.4 H1\nM30\n", &old, Options::default());
    assert_eq!(run.error().map(|a| a.code), Some(AlarmCode::UnknownGCode));
}

/// The same machine on the SINUMERIK profile.
fn sinumerik_machine(kinematics: &str) -> Machine {
    machine(kinematics, 0.0)
        .with_profile(vcnc::ProfileName::Sinumerik)
        .expect("the machine fits the SINUMERIK profile")
}

/// The linear part of the swivel frame `CYCLE800(0,"TC1",200000,{params})` sets with _DIR 0
/// (the frame only: no rotary axis moves), read from the frame of the move after it.
fn swivel_frame(params: &str) -> [[f64; 3]; 3] {
    let program = format!("CYCLE800(0,\"TC1\",200000,{params})\nG0 X10 Y20 Z30\nM30\n");
    let machine = sinumerik_machine(A_C_TABLE);
    let items: Vec<_> = vcnc::interp::sinumerik::run_str(&program, &machine).collect();
    let linear = items.iter().rev().find_map(|item| match item {
        Ok(vcnc::Item::Frame(frame)) => Some(frame.transform.linear),
        _ => None,
    });
    let run = common::collect(items.into_iter());
    assert!(run.error().is_none(), "{:?}", run.error());
    let rotary_moved = |s: &Segment| s.motion().is_some_and(|m| m.to.0[3..] != [0.0; 3]);
    assert!(!run.segments.iter().any(rotary_moved));
    linear.expect("a frame")
}

#[test]
fn cycle800_swivels_an_a_c_table_and_the_tip_reaches_the_swivelled_point() {
    // Mode 57 (axis by axis, X then Y then Z), _A -15: the plane turned -15 about X, its Z
    // (0, sin 15, cos 15). The A-C table shows the part that direction with A 15, C 0 or with
    // A -15, C 180; _DIR +1 takes the first rotary axis (A) the plus way. The reference point
    // (10, 0, 0) and the zero point after the turn (0, 0, 5) put the program zero at
    // (10, 0, 0) + R (0, 0, 5) = (10, 5 sin 15, 5 cos 15) = (10, 1.294095, 4.829629).
    let program = "G90 G0 X0 Y0 Z100
                   CYCLE800(0,\"TC1\",200000,57,10,0,0,-15,0,0,0,0,5,1,,1)
                   G0 X0 Y0 Z0
CYCLE800()
G0 Z200
M30
";
    let machine = sinumerik_machine(A_C_TABLE);
    let kin = kinematics(&machine);
    let run = common::collect(vcnc::interp::sinumerik::run_str(program, &machine));
    assert!(run.error().is_none(), "{:?}", run.error());
    let swivel = end_of(&run, 2);
    assert!(
        (swivel[3] - 15.0).abs() < 1e-9 && swivel[5].abs() < 1e-9,
        "{swivel:?}"
    );
    let tip = end_of(&run, 3);
    let pose = kin.forward(&tip, 0.0);
    let (s, c) = 15f64.to_radians().sin_cos();
    assert_close(pose.tip, [10.0, 5.0 * s, 5.0 * c], 1e-9);
    assert_close(pose.axis, [0.0, s, c], 1e-12);
    // CYCLE800() ends the swivel: Z200 is a plain machine Z again, the table stays at A 15.
    let last = last_joints(&run);
    assert_eq!((last[2], last[3]), (200.0, tip[3]));
}

#[test]
fn cycle800_projection_angles_tip_the_plane_by_its_traces() {
    // Mode 128 + 57 (projection angles, X then Y), _A 30, _B 30: the second turn about Y is b'
    // with tan b' = tan 30 cos 30 = 0.5, so the plane's Z is (sin b', -sin 30 cos b',
    // cos 30 cos b') = (0.447214, -0.447214, 0.774597), and the plane's trace in the X-Z plane
    // leans 30 degrees: atan(0.447214 / 0.774597) = 30. _DIR 0: the frame only, no rotary move.
    let linear = swivel_frame("185,0,0,0,30,30,0,0,0,0,0");
    let z = [linear[0][2], linear[1][2], linear[2][2]];
    assert_close(z, [0.447214, -0.447214, 0.774597], 1e-6);
}

#[test]
fn cycle800_axis_order_follows_the_mode_bits() {
    // Mode 54 = 0b110110: Y first (10), then X (01), then Z (11), so R = Ry(_A) Rx(_B) Rz(_C).
    // With _A 90, _B 90: Rx(90) takes the plane's Y to Z, Ry(90) takes Z to +X.
    let linear = swivel_frame("54,0,0,0,90,90,0,0,0,0,0");
    let y = [linear[0][1], linear[1][1], linear[2][1]];
    assert_close(y, [1.0, 0.0, 0.0], 1e-12);
}

#[test]
fn an_arc_in_the_tilted_plane_is_cut_into_chords_on_its_circle() {
    // G68.2 tips the plane 30 degrees about X (J30) about the work point (5, 0, 2). A full
    // circle of R10 about the feature origin (I-10 from X10): every chord end lies on the circle
    // of radius 10 about (5, 0, 2) in the tilted plane, whose normal is (0, -sin 30, cos 30), and
    // the chords stay within 0.001 mm of it (the sagitta of each chord).
    let program = "G68.2 X5. Y0 Z2. I0 J30. K0\nG00 X10. Y0 Z0\nG03 X10. Y0 I-10. J0 F500\nM30\n";
    let machine = machine(TABLE_TABLE, 0.0);
    let run = run(program, &machine);
    let chords = motions_of(&run, 3);
    assert!(chords.len() > 100, "{}", chords.len());
    let (s, c) = 30f64.to_radians().sin_cos();
    let centre = [5.0, 0.0, 2.0];
    for chord in &chords {
        let m = chord.motion().unwrap();
        for k in 0..=4 {
            let p = lerp(&m.from.0, &m.to.0, f64::from(k) / 4.0);
            let d: Vec3 = std::array::from_fn(|i| p[i] - centre[i]);
            let off_plane = d[1] * -s + d[2] * c;
            let radius = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            assert!(off_plane.abs() < 1e-9, "{p:?}");
            let within = if k % 4 == 0 { 1e-9 } else { 0.001 + 1e-9 };
            assert!((radius - 10.0).abs() <= within, "{p:?}: {radius}");
        }
    }
    let end = last_joints(&run);
    assert_close([end[0], end[1], end[2]], [15.0, 0.0, 2.0], 1e-9);
}

/// A block of a random RTCP program: the tip's end point and the rotary axes' angles, one per
/// axis of the kinematics from the base outwards.
pub(crate) type RtcpBlock = (Vec3, Vec<f64>);

/// A random RTCP block for a machine of `axes` rotary axes.
pub(crate) fn rtcp_block(axes: usize) -> impl Strategy<Value = RtcpBlock> {
    (
        prop::array::uniform3(-80.0..80.0f64),
        prop::collection::vec(-120.0..120.0f64, axes),
    )
        .prop_map(|(p, a)| {
            (
                p.map(|v| (v * 1000.0).round() / 1000.0),
                a.into_iter().map(f64::round).collect(),
            )
        })
}

/// Acceptance 2 of #23 on the kinematics `table` (called `name`): `blocks` run under G43.4 with
/// a 60 mm tool; every sampled point of every joint move puts the tip within the tolerance of
/// its block's line, at every piece end the rotary axes are where the block's linear
/// interpolation of the programmed angles puts them for that tip (so the tool axis there is the
/// programmed one), and each block ends on its point and angles.
pub(crate) fn check_rtcp(
    name: &str,
    table: &str,
    blocks: &[RtcpBlock],
) -> Result<(), TestCaseError> {
    let machine = machine(table, 60.0);
    let kin = kinematics(&machine);
    let rotary = kin.rotary_axes();
    let words = |angles: &[f64]| -> String {
        let words = rotary.iter().zip(angles);
        words
            .map(|(axis, a)| format!(" {}{a:.1}", machine.layout.name(*axis)))
            .collect()
    };
    let mut program = format!(
        "G43.4 H1\nG00 X0 Y0 Z0{}\n",
        words(&vec![0.0; rotary.len()])
    );
    for (p, angles) in blocks {
        program += &format!(
            "G01 X{:.3} Y{:.3} Z{:.3}{} F2000\n",
            p[0],
            p[1],
            p[2],
            words(angles)
        );
    }
    program += "M30\n";
    let run = run(&program, &machine);
    let mut from: RtcpBlock = ([0.0; 3], vec![0.0; rotary.len()]);
    for (i, to) in blocks.iter().enumerate() {
        let pieces = motions_of(&run, 3 + i as u32);
        let worst = largest_deviation(kin, &pieces, 60.0, from.0, to.0);
        prop_assert!(worst <= TOLERANCE, "{}: block {}: {}", name, i, worst);
        let length = (0..3)
            .map(|k| (to.0[k] - from.0[k]).powi(2))
            .sum::<f64>()
            .sqrt();
        for piece in &pieces {
            let end = piece.motion().unwrap().to.0;
            let pose = kin.forward(&end, 60.0);
            // Where along the block this end is, by its tip (blocks that move the tip): the
            // programmed angles there, linearly interpolated, give the programmed axis.
            if length > 1.0 {
                let (off, t) = to_segment(pose.tip, from.0, to.0);
                prop_assert!(off < 1e-6, "{}: a piece end off the line by {}", name, off);
                let mut programmed = [0.0; 6];
                for (k, axis) in rotary.iter().enumerate() {
                    programmed[axis.index()] = from.1[k] + (to.1[k] - from.1[k]) * t;
                }
                let axis = kin.forward(&programmed, 60.0).axis;
                for k in 0..3 {
                    prop_assert!(
                        (axis[k] - pose.axis[k]).abs() < 1e-6,
                        "{}: tool axis {:?}, programmed {:?}",
                        name,
                        pose.axis,
                        axis
                    );
                }
            }
        }
        let end = pieces
            .last()
            .map_or(last_joints(&run), |p| p.motion().unwrap().to.0);
        for (k, axis) in rotary.iter().enumerate() {
            prop_assert!(
                (end[axis.index()] - to.1[k]).abs() < 1e-9,
                "{}: angle",
                name
            );
        }
        let tip = kin.forward(&end, 60.0).tip;
        for k in 0..3 {
            prop_assert!(
                (tip[k] - to.0[k]).abs() < 1e-9,
                "{}: end {:?} {:?}",
                name,
                tip,
                to.0
            );
        }
        from = to.clone();
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn rtcp_keeps_the_tip_on_the_path_and_the_axis_on_the_angles(
        kind in 0..3usize,
        blocks in prop::collection::vec(rtcp_block(2), 1..4),
    ) {
        // Acceptance 2 of #23 on each 5-axis kinematics type.
        let (name, table) = KINDS[kind];
        check_rtcp(name, table, &blocks)?;
    }
}

/// SINUMERIK TOFRAME (PGsl 4.8) on the C-B head with B at 30: the frame's Z is the tool's
/// direction, which the kinematics give as B's turn of (0, 0, 1) about Y: (sin 30, 0, cos 30)
/// = (0.5, 0, 0.866025) up to the sign of the turn. G91 Z10 then moves the head 10 along it and
/// X10 along the frame's X, (cos 30, 0, -sin 30) by the same sign: the machine's linear axes
/// move those amounts (the tool keeps its direction, so the pivot moves as the tip). TOROTOF
/// keeps the frame; TOFRAME with B back at 0 turns nothing: from X0 Y0 Z0, Z5 moves Z alone.
#[test]
fn sinumerik_toframe_retracts_along_a_tilted_tool() {
    let machine = sinumerik_machine(HEAD_HEAD);
    let kin = kinematics(&machine);
    let program = "G0 X0 Y0 Z0 B30 C0\nTOFRAME\nG91 G0 Z10\nX10\nTOROTOF\nG90 G0 B0\nTOFRAME\nG0 X0 Y0 Z0\nG91 Z5\nM30\n";
    let run = common::collect(vcnc::interp::sinumerik::run_str(program, &machine));
    assert!(run.error().is_none(), "{:?}", run.error());
    let mut joints = [0.0; 6];
    joints[4] = 30.0;
    let axis = kin.forward(&joints, 0.0).axis;
    let s = 30f64.to_radians().sin().copysign(axis[0]);
    assert_close(axis, [s, 0.0, 30f64.to_radians().cos()], 1e-9);
    let start = end_of(&run, 1);
    let retract = end_of(&run, 3);
    let across = end_of(&run, 4);
    let c = 30f64.to_radians().cos();
    assert_close(
        [
            retract[0] - start[0],
            retract[1] - start[1],
            retract[2] - start[2],
        ],
        [10.0 * s, 0.0, 10.0 * c],
        1e-9,
    );
    assert_close(
        [
            across[0] - retract[0],
            across[1] - retract[1],
            across[2] - retract[2],
        ],
        [10.0 * c, 0.0, -10.0 * s],
        1e-9,
    );
    // B back at 0: the tool along Z again, the frame no turn: Z5 moves Z only.
    let upright = end_of(&run, 8);
    let last = end_of(&run, 9);
    assert_close(
        [
            last[0] - upright[0],
            last[1] - upright[1],
            last[2] - upright[2],
        ],
        [0.0, 0.0, 5.0],
        1e-9,
    );
}
