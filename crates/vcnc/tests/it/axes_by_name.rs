//! Axes named by the machine file: the U V W of FANUC 0M's additional linear axes (spec
//! iso-fanuc0m-mitsubishi.md A.4: "U V W, additional linear axes"), SINUMERIK's own names
//! (`C1`), and a kind the file overrides. Positions are worked out by hand in each test.

use vcnc::interp::sinumerik::run_str;
use vcnc::machine::{AxisConfig, AxisKind};
use vcnc::{AlarmCode, Axis, Machine, ProfileName, SegmentKind};

use crate::common::{collect, run, Run};

fn travel() -> AxisConfig {
    crate::common::sinumerik_machines::linear(-1000.0, 1000.0)
}

/// The default machine on `profile` with the axes `names` added after X Y Z.
fn machine_with(profile: ProfileName, names: &[(&str, Option<AxisKind>)]) -> Machine {
    let mut machine = Machine::default().with_profile(profile).unwrap();
    for (name, kind) in names {
        machine.add_axis(name, *kind, travel()).unwrap();
    }
    machine
}

/// The end of every motion, machine coordinates.
fn ends(run: &Run) -> Vec<[f64; 6]> {
    run.segments
        .iter()
        .filter_map(|s| match &s.kind {
            SegmentKind::Rapid { motion, .. }
            | SegmentKind::Line { motion, .. }
            | SegmentKind::Arc { motion, .. } => Some(motion.to.0),
            _ => None,
        })
        .collect()
}

fn iso(text: &str, machine: &Machine) -> Run {
    run(text.as_bytes(), machine, vcnc::interp::Options::default())
}

#[test]
fn an_iso_u_axis_is_linear_incremental_under_g91_and_converted_by_g20() {
    let machine = machine_with(ProfileName::Fanuc0m, &[("U", None)]);
    let u = machine.layout.by_name("U").unwrap();
    // U5 absolute; G91 U2 adds 2 (7); G20 U1 is one inch more (7 + 25.4 = 32.4).
    let run = iso(
        "G90 G00 X10. U5.\nG91 G01 U2. F100.\nG20 U1.\nM30\n",
        &machine,
    );
    assert!(run.error().is_none(), "{:?}", run.alarms);
    let u_ends: Vec<f64> = ends(&run).iter().map(|p| p[u.index()]).collect();
    assert_eq!(u_ends.len(), 3);
    for (got, want) in u_ends.iter().zip([5.0, 7.0, 32.4]) {
        assert!((got - want).abs() < 1e-9, "{u_ends:?}");
    }
    assert_eq!(ends(&run)[0][0], 10.0);
}

#[test]
fn a_rotary_axis_is_never_converted_by_g20_and_a_kind_can_be_overridden() {
    // A is rotary by its name; W is declared rotary: G20 A1. W1. turns both one degree.
    let machine = machine_with(
        ProfileName::Fanuc,
        &[("A", None), ("W", Some(AxisKind::Rotary))],
    );
    let w = machine.layout.by_name("W").unwrap();
    let run = iso("G20 G91 G01 A1. W1. F100.\nM30\n", &machine);
    assert!(run.error().is_none(), "{:?}", run.alarms);
    let end = ends(&run)[0];
    assert_eq!((end[Axis::A.index()], end[w.index()]), (1.0, 1.0));
}

#[test]
fn a_renamed_slot_refuses_the_letter_it_had() {
    // U takes A's slot on a machine without A: an A word is an axis the machine lacks.
    let machine = machine_with(ProfileName::Fanuc0m, &[("U", None)]);
    assert_eq!(machine.layout.by_name("U"), Some(Axis::A));
    let run = iso("G00 X1. A5.\nM30\n", &machine);
    let alarm = run.error().expect("an alarm");
    assert_eq!(alarm.code, AlarmCode::AxisNotOnMachine);
    assert_eq!(alarm.message, "the machine has no A axis");
    let run = iso("G00 U1. U2.\nM30\n", &machine);
    let alarm = run.error().expect("an alarm");
    assert_eq!(alarm.code, AlarmCode::DuplicateAddress);
    assert_eq!(alarm.message, "address U appears twice in the block");
    // Without U, U is an axis the machine lacks too.
    let run = iso("G00 U1.\nM30\n", &Machine::default());
    assert_eq!(
        run.error().map(|a| a.code),
        Some(AlarmCode::AxisNotOnMachine)
    );
}

#[test]
fn sinumerik_positioning_axes_u_and_v_reach_their_targets() {
    // The manual's pallet example (PGsl 7.2, L2868-2872) on a machine with U and V: U to
    // 100, V to 90; $AA_IM[U] reads U's position back, an AXIS variable names V.
    let machine = machine_with(ProfileName::Sinumerik, &[("U", None), ("V", None)]);
    let (u, v) = (
        machine.layout.by_name("U").unwrap().index(),
        machine.layout.by_name("V").unwrap().index(),
    );
    let text =
        "DEF AXIS PALLET=V\nN10 FA[U]=100 FA[V]=100\nN20 POSA[V]=90 POSA[U]=100 G0 X50 Y70\n\
                N50 WAITP(U)\nR1=$AA_IM[U]\nPOS[PALLET]=IC(5)\nG0 X=R1\nM30\n";
    let run = collect(run_str(text, &machine));
    assert!(run.error().is_none(), "{:?}", run.alarms);
    let end = *ends(&run).last().unwrap();
    assert_eq!((end[0], end[1], end[u], end[v]), (100.0, 70.0, 100.0, 95.0));
}

#[test]
fn sinumerik_names_of_several_characters_are_axes_of_their_kind() {
    // C1 is rotary by its name, W linear: under G700 W=1 is 25.4 mm, C1=1 one degree.
    let machine = machine_with(ProfileName::Sinumerik, &[("C1", None), ("W", None)]);
    let c1 = machine.layout.by_name("C1").unwrap().index();
    let w = machine.layout.by_name("W").unwrap().index();
    let run = collect(run_str(
        "G700 G0 W=1 C1=1\nG710 C1=AC(90) W=IC(1)\nM30\n",
        &machine,
    ));
    assert!(run.error().is_none(), "{:?}", run.alarms);
    let all = ends(&run);
    assert_eq!((all[0][w], all[0][c1]), (25.4, 1.0));
    assert_eq!((all[1][w], all[1][c1]), (26.4, 90.0));
    // A name the machine does not have is an alarm naming it.
    let run = collect(run_str("G0 U=5\nM30\n", &machine));
    let alarm = run.error().expect("an alarm");
    assert_eq!(alarm.code, AlarmCode::AxisNotOnMachine);
    assert!(alarm.message.contains("no axis U"), "{}", alarm.message);
}
