//! The position a program reads of a rotary axis that rolls over (issue 23): within one turn, as
//! FANUC shows it, while the motion stream keeps the continuous position the axis travelled.
//! The case is FANUC's own example of the roll-over function (B-63534EN 20.2.1: A with 360
//! degrees a turn, the shorter way in G90), here on C.

use vcnc::profile::RotaryRollover;
use vcnc::{Machine, ProfileName};

fn machine(rule: RotaryRollover) -> Machine {
    let mut machine = crate::common::with_c_axis(ProfileName::Fanuc);
    machine.profile.motion.rotary_rollover = rule;
    machine
}

/// FANUC's example, each block's readouts kept in commons: #101+ the absolute position
/// (#5046), #111+ the machine position (#5026), #121+ the block end (#5006).
const EXAMPLE: &str = "G90 G00 C0\nN1 G90 C-150.\n#101=#5046 #111=#5026 #121=#5006\nN2 G90 C540.\n#102=#5046 #112=#5026 #122=#5006\nN3 G90 C-620.\n#103=#5046 #113=#5026 #123=#5006\nN4 G91 C380.\n#104=#5046 #114=#5026 #124=#5006\nN5 G91 C-840.\n#105=#5046 #115=#5026 #125=#5006\nM30\n";

fn run(rule: RotaryRollover) -> (Vec<f64>, Vec<Option<f64>>) {
    let mut interpreter = vcnc::interpret_str(EXAMPLE, &machine(rule), vcnc::Options::default());
    let mut ends = Vec::new();
    for item in interpreter.by_ref() {
        match item {
            Ok(vcnc::Item::Segment(segment)) => {
                if let Some(motion) = segment.motion() {
                    ends.push(motion.to.0[vcnc::Axis::C.index()]);
                }
            }
            Ok(_) => {}
            Err(alarm) => panic!("{alarm:?}"),
        }
    }
    let values = (0..200).map(|n| interpreter.variable(n)).collect();
    (ends, values)
}

#[test]
fn a_rollover_axis_reads_within_one_turn_and_moves_continuously() {
    // The example's table: moves -150, -30, -80, +380, -840 (the stream's continuous C: -150,
    // -180, -260, 120, -720); absolute coordinates after each 210, 180, 100, 120, 0.
    let (ends, values) = run(RotaryRollover::Shortest);
    assert_eq!(ends, [-150.0, -180.0, -260.0, 120.0, -720.0]);
    for (i, want) in [210.0, 180.0, 100.0, 120.0, 0.0].into_iter().enumerate() {
        for base in [101, 111, 121] {
            assert_eq!(values[base + i], Some(want), "#{}", base + i);
        }
    }
}

#[test]
fn without_rollover_the_axis_reads_as_it_moved() {
    // G90 goes to the angle written: -150, 540, -620, then +380 and -840 from there.
    let (ends, values) = run(RotaryRollover::Off);
    assert_eq!(ends, [-150.0, 540.0, -620.0, -240.0, -1080.0]);
    for (i, want) in ends.iter().enumerate() {
        assert_eq!(values[111 + i], Some(*want), "#{}", 111 + i);
    }
}

#[test]
fn a_rotary_axis_reads_in_degrees_in_inch_mode() {
    // G20 changes lengths only: C90. reads 90 degrees, not 90 / 25.4.
    let program = "G20 G90 G00 C90.\n#101=#5026\nM30\n";
    let mut interpreter = vcnc::interpret_str(
        program,
        &machine(RotaryRollover::Off),
        vcnc::Options::default(),
    );
    assert!(interpreter.by_ref().all(|item| item.is_ok()));
    assert_eq!(interpreter.variable(101), Some(90.0));
}
