//! G68.2's angle conventions (issue #23, acceptance 2: hand-worked cases for each): the Euler
//! Z-X'-Z" form every profile with G68.2 has, and FANUC's P1 roll-pitch-yaw, P2 three points
//! and P3 two vectors (docs/KINEMATICS.md). Each case moves to a point of the feature system
//! and compares where the tool ends, in work coordinates (the default machine's G54 is zero),
//! with the point worked out by hand.

use crate::common;

use vcnc::{AlarmCode, Machine, Options, ProfileName};

/// √2 / 2.
const H: f64 = std::f64::consts::FRAC_1_SQRT_2;

fn machine(profile: ProfileName) -> Machine {
    common::with_c_axis(profile)
}

/// Where the last motion of `program` ends, X Y Z.
#[track_caller]
fn end_of(profile: ProfileName, program: &str) -> [f64; 3] {
    let run = common::run(program.as_bytes(), &machine(profile), Options::default());
    assert!(run.error().is_none(), "{:?}", run.error());
    let last = run.segments.iter().rev().find_map(|s| s.motion());
    let to = last.expect("the program moves").to.0;
    [to[0], to[1], to[2]]
}

#[track_caller]
fn assert_near(got: [f64; 3], want: [f64; 3]) {
    let d = (0..3).map(|i| (got[i] - want[i]).abs()).fold(0.0, f64::max);
    assert!(d < 1e-5, "{got:?} is not {want:?}");
}

#[track_caller]
fn alarm_of(profile: ProfileName, program: &str) -> vcnc::Alarm {
    let run = common::run(program.as_bytes(), &machine(profile), Options::default());
    run.error().expect("an alarm").clone()
}

#[test]
fn the_euler_form_turns_z_then_x_then_z_on_every_profile_with_g68_2() {
    // I90 J45: Rz(90) Rx(45). The feature Y is Rz(90) (0, cos 45, sin 45) = (-H, 0, H); the
    // feature point (0, 10, 0) from the origin (1, 2, 3) is (1 - 10 H, 2, 3 + 10 H). P0 is the
    // same form on FANUC.
    let want = [1.0 - 10.0 * H, 2.0, 3.0 + 10.0 * H];
    for (profile, p) in [(ProfileName::Syntec, ""), (ProfileName::Fanuc, " P0")] {
        let program = format!("G68.2{p} X1. Y2. Z3. I90. J45. K0\nG01 X0 Y10. Z0 F100.\nM30\n");
        assert_near(end_of(profile, &program), want);
    }
}

#[test]
fn p1_roll_pitch_yaw_turns_about_the_fixed_axes_in_q_order() {
    // Q123 I30 J20: X by 30, then the work Y by 20: Ry(20) Rx(30). The feature Z is
    // Ry(20) (0, -sin 30, cos 30) = (cos 30 sin 20, -sin 30, cos 30 cos 20)
    // = (0.296198, -0.5, 0.813798); Z10 from the origin (10, 0, 0) ends there times 10.
    let (s30, c30) = 30f64.to_radians().sin_cos();
    let (s20, c20) = 20f64.to_radians().sin_cos();
    let q123 = "G68.2 P1 Q123 X10. Y0 Z0 I30. J20. K0\nG01 X0 Y0 Z10. F100.\nM30\n";
    let z123 = [c30 * s20, -s30, c30 * c20];
    assert_near(
        end_of(ProfileName::Fanuc, q123),
        [10.0 + 10.0 * z123[0], 10.0 * z123[1], 10.0 * z123[2]],
    );
    // Without Q the order is 123.
    let plain = q123.replace(" Q123", "");
    assert_near(
        end_of(ProfileName::Fanuc, &plain),
        end_of(ProfileName::Fanuc, q123),
    );
    // Q321: Z first (K0), then Y by 20, then X by 30: Rx(30) Ry(20). The feature Z is
    // Rx(30) (sin 20, 0, cos 20) = (sin 20, -sin 30 cos 20, cos 30 cos 20).
    let q321 = q123.replace("Q123", "Q321");
    let z321 = [s20, -s30 * c20, c30 * c20];
    assert_near(
        end_of(ProfileName::Fanuc, &q321),
        [10.0 + 10.0 * z321[0], 10.0 * z321[1], 10.0 * z321[2]],
    );
    // K alone is a turn about Z: Q123 K90 takes the feature X to the work Y.
    let k90 = "G68.2 P1 X0 Y0 Z0 I0 J0 K90.\nG01 X5. Y0 Z0 F100.\nM30\n";
    assert_near(end_of(ProfileName::Fanuc, k90), [0.0, 5.0, 0.0]);
}

#[test]
fn p2_three_points_give_x_along_the_first_two_and_y_towards_the_third() {
    // (0,0,0) -> (10,0,0) is X = (1, 0, 0); (0,10,10) is on the +Y side: Z = X × (0, 10, 10)
    // normalised = (0, -H, H), Y = Z × X = (0, H, H): the plane G68.2 J45 gives. The feature
    // point (5, 10, 2) from the first point: 5 X + 10 Y + 2 Z = (5, 8 H, 12 H).
    let points = "G68.2 P2 Q1 X0 Y0 Z0\nG68.2 P2 Q2 X10. Y0 Z0\nG68.2 P2 Q3 X0 Y10. Z10.\n\
                  G01 X5. Y10. Z2. F100.\nM30\n";
    assert_near(end_of(ProfileName::Fanuc, points), [5.0, 8.0 * H, 12.0 * H]);
    let euler = "G68.2 X0 Y0 Z0 I0 J45. K0\nG01 X5. Y10. Z2. F100.\nM30\n";
    assert_near(
        end_of(ProfileName::Fanuc, points),
        end_of(ProfileName::Fanuc, euler),
    );
    // Q0 moves the origin to (1, 2, 3) and R90 turns the plane about its Z: the new X is the
    // old Y, the new Y minus the old X. (5, 10, 2) is 5 (0, H, H) - 10 (1, 0, 0) + 2 (0, -H, H)
    // = (-10, 3 H, 7 H), from (1, 2, 3).
    let shifted = format!("G68.2 P2 Q0 X1. Y2. Z3. R90.\n{points}");
    assert_near(
        end_of(ProfileName::Fanuc, &shifted),
        [-9.0, 2.0 + 3.0 * H, 3.0 + 7.0 * H],
    );
}

#[test]
fn p3_two_vectors_give_the_x_and_z_directions() {
    // Q1: origin (5, 0, 0), X along (1, 0, 0); Q2: Z along (0, -1, 1). Y = Z × X = (0, H, H):
    // the feature point (0, 10, 0) is (5, 10 H, 10 H).
    let vectors = "G68.2 P3 Q1 X5. Y0 Z0 I1. J0 K0\nG68.2 P3 Q2 I0 J-1. K1.\n\
                   G01 X0 Y10. Z0 F100.\nM30\n";
    assert_near(
        end_of(ProfileName::Fanuc, vectors),
        [5.0, 10.0 * H, 10.0 * H],
    );
    // 4 degrees off square (X along (1, 0, 0.07)): accepted, X squared to Z = (0, 0, 1), so the
    // feature X stays the work X.
    let skew = "G68.2 P3 Q1 X0 Y0 Z0 I1. J0 K0.07\nG68.2 P3 Q2 I0 J0 K1.\n\
                G01 X10. Y0 Z0 F100.\nM30\n";
    assert_near(end_of(ProfileName::Fanuc, skew), [10.0, 0.0, 0.0]);
    // 11 degrees off (0.2): FANUC's limit is 5.
    let far = skew.replace("K0.07", "K0.2");
    assert_eq!(alarm_of(ProfileName::Fanuc, &far).code, AlarmCode::FiveAxis);
}

#[test]
fn forms_a_control_lacks_or_planes_that_are_no_planes_are_alarms() {
    // Syntec's manual gives G68.2 X Y Z I J K only.
    let p1 = "G68.2 P1 Q123 X0 Y0 Z0 I30.\nM30\n";
    assert_eq!(
        alarm_of(ProfileName::Syntec, p1).code,
        AlarmCode::ValueOutOfRange
    );
    let cases = [
        ("G68.2 P4 X0 Y0 Z0\nM30\n", AlarmCode::ValueOutOfRange),
        ("G68.2 P1 Q112 I30.\nM30\n", AlarmCode::ValueOutOfRange),
        ("G68.2 P2 X0 Y0 Z0\nM30\n", AlarmCode::ValueOutOfRange),
        ("G68.2 P2 Q3 X0 Y10. Z0\nM30\n", AlarmCode::FiveAxis),
        (
            "G68.2 P2 Q1 X0 Y0 Z0\nG68.2 P2 Q2 X10. Y0 Z0\nG68.2 P2 Q3 X20. Y0 Z0\nM30\n",
            AlarmCode::FiveAxis,
        ),
        ("G68.2 P3 Q2 I0 J0 K1.\nM30\n", AlarmCode::FiveAxis),
        // G69 drops a plane half given.
        (
            "G68.2 P3 Q1 X0 Y0 Z0 I1. J0 K0\nG69\nG68.2 P3 Q2 I0 J0 K1.\nM30\n",
            AlarmCode::FiveAxis,
        ),
        (
            "G68.2 P3 Q1 X0 Y0 Z0 I0 J0 K0\nG68.2 P3 Q2 I0 J0 K1.\nM30\n",
            AlarmCode::FiveAxis,
        ),
    ];
    for (program, code) in cases {
        let alarm = alarm_of(ProfileName::Fanuc, program);
        assert_eq!(alarm.code, code, "{program}: {}", alarm.message);
    }
}
