//! G22/G23 stored stroke check 2 (Syntec spec 1.16, manual 000 L1149-1219): a zone of machine
//! X Y Z forbidden inside (or outside) its range, from the block's pairs or the machine file's
//! `[stroke_check]`; a move into it is left out and stops the program with V078.

use crate::common::{run, Run};
use vcnc::interp::{AxisLimits, Forbidden, StrokeCheckConfig};
use vcnc::{AlarmCode, Machine, Options, ProfileName};

fn syntec(config: StrokeCheckConfig) -> Machine {
    let mut machine = Machine::default()
        .with_profile(ProfileName::Syntec)
        .unwrap();
    machine.stroke_check = config;
    machine
}

fn ran(program: &str, machine: &Machine) -> Run {
    run(program.as_bytes(), machine, Options::default())
}

/// The alarm's code and line, and the lines that moved.
fn outcome(run: &Run) -> (Option<(AlarmCode, u32)>, Vec<u32>) {
    let alarm = run.error().map(|a| (a.code, a.span.unwrap().line));
    let mut lines: Vec<u32> = run
        .segments
        .iter()
        .filter(|s| s.motion().is_some())
        .map(|s| s.span.line)
        .collect();
    lines.dedup();
    (alarm, lines)
}

/// Across X at Y75, Z-10: through the box 50..100 x 50..100 x -50..0 when it is on.
const ACROSS: &str = "G90 G00 Z-10.\nG01 X0 Y75. F500.\nX200.\nM30\n";

#[test]
fn a_move_into_the_inside_zone_is_left_out_with_its_alarm() {
    // X Y Z are the positive limits and I J K the negative ones (L1159-1167).
    let program = format!("G22 X100. Y100. Z0 I50. J50. K-50.\n{ACROSS}");
    let run = ran(&program, &syntec(StrokeCheckConfig::default()));
    assert_eq!(
        outcome(&run),
        (Some((AlarmCode::StrokeCheck, 4)), vec![2, 3])
    );
    // A pair may be given either way round (L1194).
    let swapped = program
        .replace("X100. Y100.", "X50. Y100.")
        .replace("I50.", "I100.");
    let run = ran(&swapped, &syntec(StrokeCheckConfig::default()));
    assert_eq!(outcome(&run).0, Some((AlarmCode::StrokeCheck, 4)));
    // G23 switches it off: the same path runs.
    let off = format!("G22 X100. Y100. Z0 I50. J50. K-50.\nG23\n{ACROSS}");
    let run = ran(&off, &syntec(StrokeCheckConfig::default()));
    assert_eq!(outcome(&run), (None, vec![3, 4, 5]));
}

#[test]
fn an_axis_whose_pair_is_equal_is_not_protected() {
    // G22 X0. I0. leaves X free (L1199): the zone is every X with Y 50..100, Z -50..0, so a
    // move along Y at X500 that crosses Y75 enters it.
    let program = "G22 X0 I0 Y100. J50. Z0 K-50.\nG90 G00 X500. Y0 Z-10.\nG01 Y200. F500.\nM30\n";
    let run = ran(program, &syntec(StrokeCheckConfig::default()));
    assert_eq!(outcome(&run).0, Some((AlarmCode::StrokeCheck, 3)));
}

#[test]
fn an_arc_through_the_zone_is_caught_between_its_ends() {
    // From X0 Y0 round the centre X75 Y0 (radius 75): the arc's top, X75 Y75, is inside the
    // box while both ends (X0 and X150 at Y0) are outside it.
    let program =
        "G22 X100. Y100. Z0 I50. J50. K-50.\nG90 G00 X0 Y0 Z-10.\nG02 X150. Y0 R75. F500.\nM30\n";
    let run = ran(program, &syntec(StrokeCheckConfig::default()));
    assert_eq!(outcome(&run).0, Some((AlarmCode::StrokeCheck, 3)));
    // Below the box the same arc passes.
    let run = ran(
        &program.replace("Z-10.", "Z-60."),
        &syntec(StrokeCheckConfig::default()),
    );
    assert_eq!(outcome(&run).0, None);
}

#[test]
fn the_outside_zone_of_the_parameters_keeps_the_tool_in_its_range() {
    // Pr2542 outside, Pr2501.. the range X -100..100, Y -100..100: a bare G22 takes them.
    let config = StrokeCheckConfig {
        min: AxisLimits {
            x: Some(-100.0),
            y: Some(-100.0),
            z: None,
        },
        max: AxisLimits {
            x: Some(100.0),
            y: Some(100.0),
            z: None,
        },
        forbidden: Forbidden::Outside,
        on_at_power_on: false,
    };
    let program = "G22\nG90 G01 X90. Y-90. Z-500. F800.\nX120.\nM30\n";
    let run = ran(program, &syntec(config));
    assert_eq!(outcome(&run), (Some((AlarmCode::StrokeCheck, 3)), vec![2]));
    // Switched on at power-on (Pr3838), the check needs no G22.
    let on = StrokeCheckConfig {
        on_at_power_on: true,
        ..config
    };
    let run = ran(&program.replace("G22\n", "G90\n"), &syntec(on));
    assert_eq!(outcome(&run).0, Some((AlarmCode::StrokeCheck, 3)));
}

#[test]
fn a_limit_without_its_pair_is_cor_109() {
    let run = ran("G22 X100.\nM30\n", &syntec(StrokeCheckConfig::default()));
    let alarm = run.error().expect("an alarm");
    assert_eq!(
        (alarm.code, alarm.span.unwrap().line),
        (AlarmCode::StrokeCheck, 1)
    );
    assert!(alarm.help.as_deref().unwrap_or("").contains("COR-109"));
    // Controls without the check have no G22.
    let mitsubishi = Machine::default()
        .with_profile(ProfileName::Mitsubishi)
        .unwrap();
    let run = ran("G22 X100. I0\nM30\n", &mitsubishi);
    assert_eq!(run.error().map(|a| a.code), Some(AlarmCode::UnknownGCode));
}

/// How far `p` is inside the box `low`-`high` (negative: outside, by the largest axis excess).
fn depth(p: [f64; 3], low: [f64; 3], high: [f64; 3]) -> f64 {
    (0..3)
        .map(|i| (p[i] - low[i]).min(high[i] - p[i]))
        .fold(f64::INFINITY, f64::min)
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(300))]

    /// A random line against the inside zone 50..100 x 50..100 x -50..0 stops the program exactly
    /// when it passes through the box: checked here by 20 000 points along it, to within 0.02 mm
    /// of the faces (the sample spacing).
    #[test]
    fn a_line_alarms_exactly_when_it_crosses_the_inside_zone(
        from in (0..150i32, 0..150i32, -80..30i32),
        to in (0..150i32, 0..150i32, -80..30i32),
    ) {
        let (low, high) = ([50.0, 50.0, -50.0], [100.0, 100.0, 0.0]);
        let a = [f64::from(from.0), f64::from(from.1), f64::from(from.2)];
        let b = [f64::from(to.0), f64::from(to.1), f64::from(to.2)];
        proptest::prop_assume!(depth(a, low, high) < -0.05);
        let program = format!(
            "G90 G00 X{}. Y{}. Z{}.\nG22 X100. Y100. Z0 I50. J50. K-50.\nG01 X{}. Y{}. Z{}. F500.\nM30\n",
            from.0, from.1, from.2, to.0, to.1, to.2
        );
        let run = ran(&program, &syntec(StrokeCheckConfig::default()));
        let deepest = (0..=20_000)
            .map(|k| {
                let t = f64::from(k) / 20_000.0;
                depth([0, 1, 2].map(|i| a[i] + t * (b[i] - a[i])), low, high)
            })
            .fold(f64::NEG_INFINITY, f64::max);
        match run.error() {
            Some(alarm) => {
                proptest::prop_assert_eq!(alarm.code, AlarmCode::StrokeCheck);
                proptest::prop_assert!(deepest > -0.02, "alarm, deepest {deepest}\n{program}");
            }
            None => proptest::prop_assert!(deepest < 0.02, "no alarm, deepest {deepest}\n{program}"),
        }
    }
}
