//! The corpus programs' controls and machines (spec: corpus/MANIFEST.md).

use vcnc::{Machine, ProfileName};

/// The control each corpus program was written for (spec: corpus/MANIFEST.md).
pub fn profile_for(name: &str) -> ProfileName {
    if name.starts_with("boreyko_")
        || name.starts_with("kiely_")
        || name.starts_with("ramos_")
        || name.starts_with("werocketry_")
        || name.contains("HAAS")
    {
        ProfileName::Haas
    } else if name.contains("FANUC0M") {
        ProfileName::Fanuc0m
    } else {
        ProfileName::Fanuc
    }
}

/// The machine each program runs on: the default machine with the program's profile, and the
/// parameter settings its author's control evidently had.
pub fn machine_for(name: &str) -> Machine {
    let mut machine = Machine::default().with_profile(profile_for(name)).unwrap();
    if name.starts_with("ledfloor_") {
        // A Fusion 360 generic post writes `Y35` and `Z10` meaning millimetres: the control it was
        // made for reads numbers without a decimal point as whole units (FANUC parameter DPI = 1).
        machine.profile.decimal_less = vcnc::profile::DecimalLess::WholeUnits;
    }
    if name.starts_with("kiely_") {
        // Hand-written for a Haas set to inch (setting 9): the programs never say G20.
        machine.profile.power_on.units = 200;
    }
    machine
}
