//! Haas G187 and Syntec G120.1, the accuracy settings mapped onto the smoothing tolerance every
//! motion carries for the planner (interp/smoothness.rs).

use crate::common::run;
use vcnc::{AlarmCode, Machine, Options, ProfileName};

fn machine(profile: ProfileName) -> Machine {
    Machine::default().with_profile(profile).unwrap()
}

/// The smoothing tolerance of each motion, mm, and the alarms' codes.
fn tolerances(profile: ProfileName, program: &str) -> (Vec<Option<f64>>, Vec<AlarmCode>) {
    let run = run(program.as_bytes(), &machine(profile), Options::default());
    let tolerances = run
        .segments
        .iter()
        .filter_map(|s| s.motion())
        .map(|m| m.smoothing.map(|s| s.mm()))
        .collect();
    (tolerances, run.alarms.iter().map(|a| a.code).collect())
}

#[test]
fn haas_g187_e_sets_the_corner_rounding_until_a_bare_g187() {
    let program = "G90 G01 X1. F500.\nG187 P3 E0.05\nX2.\nG187 P1\nX3.\nG187\nX4.\nM30\n";
    let (tolerances, alarms) = tolerances(ProfileName::Haas, program);
    assert_eq!(tolerances, [None, Some(0.05), Some(0.05), None]);
    // P alone keeps the tolerance in force, and says so.
    assert_eq!(alarms, [AlarmCode::KeptAsState]);
}

#[test]
fn haas_g187_refuses_other_levels_and_a_zero_e() {
    for program in ["G187 P4\nM30\n", "G187 E0\nM30\n"] {
        let (_, alarms) = tolerances(ProfileName::Haas, program);
        assert_eq!(alarms, [AlarmCode::SmoothingCommand], "{program}");
    }
    // G187 is Haas's: elsewhere there is no such code.
    let (_, alarms) = tolerances(ProfileName::Fanuc, "G187 E0.05\nM30\n");
    assert_eq!(alarms, [AlarmCode::UnknownGCode]);
}

#[test]
fn syntec_g120_1_is_accepted_and_leaves_the_planner_settings() {
    let program = "G120.1 P2\nG90 G01 X1. F500.\nM30\n";
    let (tolerances, alarms) = tolerances(ProfileName::Syntec, program);
    assert_eq!(tolerances, [None]);
    assert_eq!(alarms, [AlarmCode::KeptAsState]);
}
