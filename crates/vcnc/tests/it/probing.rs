//! The virtual probe (the machine file's `[probe]`): G31 stops where the tool's tip touches a
//! plane or a box and records that point in #5061-#5063, runs to its end with a warning when it
//! touches nothing; Syntec's G37 and G37.1 measure tools against the tool setter and write the
//! H register (examples 32 and 33); FANUC 0M's G27 checks the reference position (alarm PS 092).

use crate::common::{self, run};
use vcnc::machine::{ToolOffset, WorkOffsetId};
use vcnc::probe::{BoxTarget, PlaneTarget, Point, ProbeConfig, ToolSetter};
use vcnc::{AlarmCode, Machine, Options, ProfileName, SegmentKind};

fn point(x: f64, y: f64, z: f64) -> Point {
    Point { x, y, z }
}

/// The default machine on `profile` with tools 1 (100 mm) and 2 (103 mm) and `probe`.
fn machine(profile: ProfileName, probe: ProbeConfig) -> Machine {
    let mut machine = Machine::default().with_profile(profile).unwrap();
    for (number, length) in [(1, 100.0), (2, 103.0)] {
        machine.tool_offsets.insert(
            number,
            ToolOffset {
                number,
                length,
                ..ToolOffset::default()
            },
        );
    }
    machine.probe = probe;
    machine
}

/// A part whose top face is the plane z = -20 (machine coordinates).
fn part_top() -> ProbeConfig {
    ProbeConfig {
        planes: vec![PlaneTarget {
            point: point(0.0, 0.0, -20.0),
            normal: point(0.0, 0.0, 1.0),
        }],
        ..ProbeConfig::default()
    }
}

/// The machine Z of every line and rapid of line `line`, in order.
fn ends_on_line(run: &common::Run, line: u32) -> Vec<[f64; 3]> {
    run.segments
        .iter()
        .filter(|s| s.span.line == line)
        .filter_map(|s| match &s.kind {
            SegmentKind::Line { motion, .. } | SegmentKind::Rapid { motion, .. } => {
                Some([motion.to.0[0], motion.to.0[1], motion.to.0[2]])
            }
            _ => None,
        })
        .collect()
}

/// Runs `program` to its end and reads common variables.
fn variables(program: &str, machine: &Machine, numbers: &[u32]) -> Vec<Option<f64>> {
    let mut interpreter = vcnc::interpret_str(program, machine, Options::default());
    for item in interpreter.by_ref() {
        assert!(item.is_ok(), "{item:?}");
    }
    numbers.iter().map(|n| interpreter.variable(*n)).collect()
}

#[test]
fn g31_stops_where_the_tip_touches_a_plane_and_records_the_point() {
    // G54 Z-5: machine -20 is program -15. Tool 0 has no length: the tip is the control point.
    let mut m = machine(ProfileName::Fanuc, part_top());
    m.work_offsets
        .insert(WorkOffsetId::Standard(1), [0.0, 0.0, -5.0, 0.0, 0.0, 0.0]);
    let program = "G90 G54 G00 X10. Y5. Z10.\nG31 Z-50. F100.\n#100=#5061\n#101=#5063\nM30\n";
    let ran = run(program.as_bytes(), &m, Options::default());
    assert!(ran.alarms.is_empty(), "{:?}", ran.alarms);
    assert_eq!(ends_on_line(&ran, 2), [[10.0, 5.0, -20.0]]);
    assert_eq!(
        variables(program, &m, &[100, 101]),
        [Some(10.0), Some(-15.0)]
    );
}

#[test]
fn the_tool_length_puts_the_tip_below_the_control_point() {
    // Tool 1 is 100 long: its tip meets z = -20 with the control point at 80, a quarter of the
    // way from 120 down to -40.
    let m = machine(ProfileName::Fanuc, part_top());
    let program = "T1 M06\nG90 G00 X0 Y0 Z120.\nG31 Z-40. F100.\nM30\n";
    let ran = run(program.as_bytes(), &m, Options::default());
    assert!(ran.error().is_none(), "{:?}", ran.error());
    assert_eq!(ends_on_line(&ran, 3), [[0.0, 0.0, 80.0]]);
}

#[test]
fn g31_sideways_into_a_box_stops_at_its_face() {
    let m = machine(
        ProfileName::Fanuc,
        ProbeConfig {
            boxes: vec![BoxTarget {
                min: point(30.0, -10.0, -50.0),
                max: point(40.0, 10.0, -10.0),
            }],
            ..ProbeConfig::default()
        },
    );
    let program = "G90 G00 X0 Y0 Z-15.\nG31 X100. F200.\nG91 Y20.\nM30\n";
    let ran = run(program.as_bytes(), &m, Options::default());
    assert!(ran.alarms.is_empty(), "{:?}", ran.alarms);
    assert_eq!(ends_on_line(&ran, 2), [[30.0, 0.0, -15.0]]);
    // The next block starts from the touch (spec 1.20).
    assert_eq!(ends_on_line(&ran, 3), [[30.0, 20.0, -15.0]]);
}

#[test]
fn g31_that_touches_nothing_runs_to_its_end_and_says_so() {
    let m = machine(ProfileName::Fanuc, part_top());
    let program = "G90 G00 X0 Y0 Z10.\nG31 X50. Z-10. F100.\n#100=#5061\nM30\n";
    let ran = run(program.as_bytes(), &m, Options::default());
    assert!(ran.error().is_none(), "{:?}", ran.error());
    assert_eq!(ends_on_line(&ran, 2), [[50.0, 0.0, -10.0]]);
    let warning = ran.alarms.first().expect("a warning");
    assert_eq!(
        (warning.code, warning.span.unwrap().line),
        (AlarmCode::Probing, 2)
    );
    assert_eq!(variables(program, &m, &[100]), [Some(50.0)]);
    // Without targets, the block is quiet, as before the probe existed.
    let bare = machine(ProfileName::Fanuc, ProbeConfig::default());
    assert!(run(program.as_bytes(), &bare, Options::default())
        .alarms
        .is_empty());
}

#[test]
fn the_machine_file_describes_the_targets() {
    let text = format!(
        "{}\n[probe]\ntool_setter = {{ x = 75.0, y = 25.0, z = -245.0 }}\n\
         planes = [{{ point = {{ z = -20.0 }}, normal = {{ z = 1.0 }} }}]\n\
         [probe.measurement]\nmeasuring_distance = 100.0\nallowed_distance = 60.0\n",
        vcnc::machine::DEFAULT_MACHINE_TOML
    );
    let m = Machine::from_toml(&text).unwrap();
    assert_eq!(
        m.probe.tool_setter,
        Some(ToolSetter {
            x: 75.0,
            y: 25.0,
            z: -245.0,
            radius: 10.0
        })
    );
    assert_eq!(m.probe.planes, part_top().planes);
    assert_eq!(m.probe.measurement.allowed_distance, 60.0);
    let bad = format!(
        "{}\n[probe]\nplanes = [{{ point = {{ z = 1.0 }}, normal = {{ z = 0.0 }} }}]\n",
        vcnc::machine::DEFAULT_MACHINE_TOML
    );
    assert!(Machine::from_toml(&bad).is_err());
}

/// The machine of the Syntec measuring examples: the tool setter's face at machine z -245
/// under reference points 2 and 3 (X75 Y25), R100 and D60 by default, and the example's `Z-150`
/// read as -150 mm as its comment says (spec 1.22 note: decimal-less lengths in whole units).
fn measuring_machine() -> Machine {
    let mut m = machine(
        ProfileName::Syntec,
        ProbeConfig {
            tool_setter: Some(ToolSetter {
                x: 75.0,
                y: 25.0,
                z: -245.0,
                radius: 10.0,
            }),
            ..ProbeConfig::default()
        },
    );
    m.probe.measurement.measuring_distance = 100.0;
    m.probe.measurement.allowed_distance = 60.0;
    m.reference_points[1] = [75.0, 25.0, 0.0, 0.0, 0.0, 0.0];
    m.reference_points[2] = [75.0, 25.0, 0.0, 0.0, 0.0, 0.0];
    m.profile.units.decimal_less = vcnc::profile::DecimalLess::WholeUnits;
    m
}

/// An example of the Syntec manual followed by `G43` moves that show H1, H2 and H3.
fn example_then_lengths(file: &str) -> Option<String> {
    let path = common::shared_dir()?
        .join("spec/examples/syntec")
        .join(file);
    let text = std::fs::read_to_string(path).unwrap();
    Some(text + "\nG43 H1 G00 Z10.\nH2 Z20.\nH3 Z30.\nM30\n")
}

/// The machine Z of the last three rapids: Z10, Z20, Z30 plus H1, H2, H3.
fn last_three_z(run: &common::Run) -> Vec<f64> {
    let z: Vec<f64> = run
        .segments
        .iter()
        .filter_map(|s| match &s.kind {
            SegmentKind::Rapid { motion, .. } => Some(motion.to.0[2]),
            _ => None,
        })
        .collect();
    z[z.len() - 3..].to_vec()
}

#[test]
fn syntec_example_32_measures_tools_1_2_and_2_again_into_h1_h2_h3() {
    // Example 32 (000 L1523-1555): the tool of length L touches the face at -245 with its
    // control point at -245 + L, the length measured: H1 = 100, H2 = 103 and, no tool change
    // before the third, H3 = 103 (the header: "H3 measures tool 2 again").
    let Some(program) = example_then_lengths("32-g37-tool-measure.nc") else {
        return;
    };
    let ran = run(program.as_bytes(), &measuring_machine(), Options::default());
    assert!(ran.alarms.is_empty(), "{:?}", ran.alarms);
    assert_eq!(last_three_z(&ran), [110.0, 123.0, 133.0]);
    // The first measurement (line 14): Z at rapid to Z + R = -50, at F to Z + D = -90 without
    // a touch, on toward Z = -150 until the touch at -145.
    let g37: Vec<f64> = ends_on_line(&ran, 14).iter().map(|p| p[2]).collect();
    assert_eq!(g37, [-50.0, -90.0, -145.0]);
    // The third (line 19): first to reference point 3, then down from Z + R = -100.
    let third = ends_on_line(&ran, 19);
    assert_eq!(third[0], [75.0, 25.0, 0.0]);
    assert_eq!(third.last().unwrap()[2], -142.0);
}

#[test]
fn syntec_example_33_touches_twice_and_retracts_to_the_machine_zero() {
    // Example 33 (000 L1615-1649): M90, Z to Z + R = -50, M91, a touch toward -150 at -145, 1 mm
    // back at rapid, a second touch at F50, Z back to machine zero; the same lengths as 32.
    let Some(program) = example_then_lengths("33-g37.1-tool-measure.nc") else {
        return;
    };
    let ran = run(program.as_bytes(), &measuring_machine(), Options::default());
    assert!(ran.alarms.is_empty(), "{:?}", ran.alarms);
    assert_eq!(last_three_z(&ran), [110.0, 123.0, 133.0]);
    let first: Vec<&SegmentKind> = ran
        .segments
        .iter()
        .filter(|s| s.span.line == 12)
        .map(|s| &s.kind)
        .collect();
    let described: Vec<String> = first
        .iter()
        .map(|kind| match kind {
            SegmentKind::Auxiliary { code } => format!("M{code}"),
            SegmentKind::Rapid { motion, .. } => format!("rapid {}", motion.to.0[2]),
            SegmentKind::Line { motion, feed } => {
                format!("feed {} F{}", motion.to.0[2], feed.mm_per_min(1.0).unwrap())
            }
            other => format!("{other:?}"),
        })
        .collect();
    assert_eq!(
        described,
        [
            "M90",
            "rapid -50",
            "M91",
            "feed -145 F100",
            "rapid -144",
            "feed -145 F50",
            "rapid 0"
        ]
    );
}

fn alarm_of(program: &str, m: &Machine) -> (AlarmCode, u32, String) {
    let ran = run(program.as_bytes(), m, Options::default());
    let alarm = ran.error().unwrap_or_else(|| panic!("no alarm: {program}"));
    (alarm.code, alarm.span.unwrap().line, alarm.message.clone())
}

#[test]
fn measurements_that_cannot_be_made_are_the_manuals_alarms() {
    let m = measuring_machine();
    let head = "G30 P2 X75. Y25.\nM06 T1\n";
    let cases = [
        ("H1\nG37\n", "MAR-330"),
        ("G37 Z-150.\n", "MAR-334"),
        ("H1\nG00 Z-200.\nG37 Z-150.\n", "MAR-333"),
        // The face at -145 is above the window's start, -150 + 2: the signal comes too early.
        ("H1\nG37 Z-150. D2.\n", "MAR-335"),
        // Measuring beside the setter: no signal by Z.
        ("H1\nG00 X0\nG37 Z-150.\n", "MAR-336"),
        ("H1\nG00 X0\nG37.1 Z-150.\n", "MAR-336"),
    ];
    for (body, number) in cases {
        let program = format!("{head}{body}M30\n");
        let (code, line, message) = alarm_of(&program, &m);
        assert_eq!(code, AlarmCode::Probing, "{program}");
        assert!(message.contains(number), "{message} for {program}");
        assert_eq!(line as usize, program.lines().count() - 1, "{program}");
    }
    let no_setter = machine(ProfileName::Syntec, ProbeConfig::default());
    let (code, _, message) = alarm_of("H1\nG37 Z-150.\nM30\n", &no_setter);
    assert_eq!(code, AlarmCode::Probing);
    assert!(message.contains("tool setter"), "{message}");
}

#[test]
fn fanuc_0m_g27_passes_at_the_reference_point_and_alarms_elsewhere() {
    // 001 L1288-1306 (spec A.25): G27 Y210.812 Z421.226 is the machine origin seen
    // from a program origin whose G54 offsets are 385.612, -210.812, -421.226.
    let mut m = Machine::default()
        .with_profile(ProfileName::Fanuc0m)
        .unwrap();
    m.work_offsets.insert(
        WorkOffsetId::Standard(1),
        [385.612, -210.812, -421.226, 0.0, 0.0, 0.0],
    );
    let program = "G90 G54 G00 X0 Y0 Z0\nG40 G49\nG27 X-385.612 Y210.812 Z421.226\nM30\n";
    let ran = run(program.as_bytes(), &m, Options::default());
    assert!(ran.alarms.is_empty(), "{:?}", ran.alarms);
    assert_eq!(ends_on_line(&ran, 3), [[0.0, 0.0, 0.0]]);
    // Off by 0.1 on Y: the rapid is made, then PS 092 names the axis.
    let off = program.replace("Y210.812", "Y210.712");
    let (code, line, message) = alarm_of(&off, &m);
    assert_eq!((code, line), (AlarmCode::ReferenceCheck, 3));
    assert!(
        message.contains("Y not") && message.contains("092"),
        "{message}"
    );
    let ran = run(off.as_bytes(), &m, Options::default());
    let reached = ends_on_line(&ran, 3);
    assert_eq!(reached.len(), 1);
    assert!((reached[0][1] + 0.1).abs() < 1e-9, "{reached:?}");
    // Under cutter compensation the block is refused; Syntec has no G27.
    let compensating = "G90 G00 X0 Y0\nG41 D1 G01 X10. F100.\nG27 X0\nM30\n";
    assert_eq!(alarm_of(compensating, &m).0, AlarmCode::ReferenceCheck);
    let syntec = Machine::default()
        .with_profile(ProfileName::Syntec)
        .unwrap();
    assert_eq!(
        alarm_of("G27 X0\nM30\n", &syntec).0,
        AlarmCode::UnknownGCode
    );
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(300))]

    /// A G31 between two points on either side of a random plane stops on the plane (the tip,
    /// tool 0, is the control point): its end satisfies the plane's equation, lies on the
    /// programmed segment, and #5061-#5063 hold it.
    #[test]
    fn g31_across_a_random_plane_stops_on_it(
        normal in (-10..10i32, -10..10i32, 1..10i32),
        offset in -20..20i32,
        start in (-50..50i32, -50..50i32),
        end in (-50..50i32, -50..50i32),
    ) {
        let n = [f64::from(normal.0), f64::from(normal.1), f64::from(normal.2)];
        let p0 = [f64::from(start.0), f64::from(start.1), 100.0];
        let p1 = [f64::from(end.0), f64::from(end.1), -100.0];
        let point = [0.0, 0.0, f64::from(offset)];
        let side = |p: [f64; 3]| (0..3).map(|i| (p[i] - point[i]) * n[i]).sum::<f64>();
        // Z from 100 to -100 with |n.z| >= |n.x|/10: the start above the plane, the end below.
        proptest::prop_assume!(side(p0) > 0.0 && side(p1) < 0.0);
        let m = machine(
            ProfileName::Fanuc,
            ProbeConfig {
                planes: vec![PlaneTarget {
                    point: Point { x: point[0], y: point[1], z: point[2] },
                    normal: Point { x: n[0], y: n[1], z: n[2] },
                }],
                ..ProbeConfig::default()
            },
        );
        let program = format!(
            "G90 G00 X{}. Y{}. Z100.\nG31 X{}. Y{}. Z-100. F500.\n#100=#5061\n#101=#5062\n#102=#5063\nM30\n",
            start.0, start.1, end.0, end.1
        );
        let ran = run(program.as_bytes(), &m, Options::default());
        proptest::prop_assert!(ran.alarms.is_empty(), "{:?}", ran.alarms);
        let stop = ends_on_line(&ran, 2);
        proptest::prop_assert_eq!(stop.len(), 1);
        let q = stop[0];
        let norm = n.iter().map(|v| v * v).sum::<f64>().sqrt();
        proptest::prop_assert!(side(q).abs() / norm < 1e-9, "{q:?} off the plane");
        // On the segment: the same share of the way on every axis.
        let t = (100.0 - q[2]) / 200.0;
        for i in 0..2 {
            proptest::prop_assert!((p0[i] + t * (p1[i] - p0[i]) - q[i]).abs() < 1e-9);
        }
        let recorded = variables(&program, &m, &[100, 101, 102]);
        for i in 0..3 {
            let v = recorded[i].unwrap();
            proptest::prop_assert!((v - q[i]).abs() < 1e-9, "#{} = {v}", 5061 + i);
        }
    }
}
