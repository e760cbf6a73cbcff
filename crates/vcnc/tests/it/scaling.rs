//! G51/G50 scaling and G51.1/G50.1 programmable mirror: the manual's mirror passes, the
//! alarms, and programs scaled or mirrored by code against the same programs transformed by hand
//! (spec iso-syntec-milling.md 1.28, 1.29). The manual's two scaling examples are asserted in
//! `seed_examples.rs`.

use crate::common::check_with;
use crate::common::contour::{assert_coded_is_by_hand, step};
use proptest::prelude::*;
use vcnc::{Machine, ProfileName};

/// The contour of the Syntec manual's mirror example 1 (spec 1.29, file
/// examples/syntec/41-g51.1-mirror-subprogram.nc), its subprogram written out in line.
const CONTOUR: &str =
    "G00 X60.0 Y55.0\nG01 Y75.0 F1000.\nX80.0\nX120.0\nY105.0\nX80.0 Y95.0\nY75.0\n";

#[test]
fn the_manuals_mirror_about_x_60() {
    check_with(
        ProfileName::Syntec,
        &format!("G51.1 X60.0\n{CONTOUR}G50.1\nM30"),
        "
        rapid X60 Y55 Z0
        line X60 Y75 Z0 F1000
        line X40 Y75 Z0 F1000
        line X0 Y75 Z0 F1000
        line X0 Y105 Z0 F1000
        line X40 Y95 Z0 F1000
        line X40 Y75 Z0 F1000
        end M30",
    );
}

#[test]
fn the_manuals_mirror_about_y_55() {
    check_with(
        ProfileName::Syntec,
        &format!("G51.1 Y55.0\n{CONTOUR}G50.1\nM30"),
        "
        rapid X60 Y55 Z0
        line X60 Y35 Z0 F1000
        line X80 Y35 Z0 F1000
        line X120 Y35 Z0 F1000
        line X120 Y5 Z0 F1000
        line X80 Y15 Z0 F1000
        line X80 Y35 Z0 F1000
        end M30",
    );
}

#[test]
fn scaling_and_mirror_together_is_an_alarm_and_g51_needs_a_factor() {
    check_with(
        ProfileName::Syntec,
        "G51 X0 Y0 P2.\nG51.1 X10.\nM30",
        "alarm word_not_allowed line 2",
    );
    check_with(
        ProfileName::Syntec,
        "G51.1 X10.\nG51 X0 Y0 P2.\nM30",
        "alarm word_not_allowed line 2",
    );
    check_with(
        ProfileName::Syntec,
        "G51 X0 Y0\nM30",
        "alarm missing_value line 1",
    );
}

#[test]
fn g50_cancels_only_scaling_and_g50_1_only_the_mirror() {
    check_with(
        ProfileName::Syntec,
        "G51.1 X0\nG50\nG0 X10.\nG50.1\nG0 X10.\nM30",
        "
        rapid X-10 Y0 Z0
        rapid X10 Y0 Z0
        end M30",
    );
}

fn syntec() -> Machine {
    Machine::default()
        .with_profile(ProfileName::Syntec)
        .unwrap()
}

proptest! {
    /// G51.1 about X = m (and Y = n when `both`) gives the path of the program mirrored by hand,
    /// arcs turning the other way when one axis is mirrored.
    #[test]
    fn mirroring_by_code_is_mirroring_by_hand(
        steps in proptest::collection::vec(step(), 1..10),
        m in -50.0f64..50.0,
        n in -50.0f64..50.0,
        both in proptest::bool::ANY,
    ) {
        let by_hand = move |x: f64, y: f64| (2.0 * m - x, if both { 2.0 * n - y } else { y });
        let words = if both { format!("X{m:.9} Y{n:.9}") } else { format!("X{m:.9}") };
        assert_coded_is_by_hand(&steps, &by_hand, !both, &format!("G51.1 {words}\n"), &syntec())?;
    }

    /// G51 with P about a centre gives the path of the program scaled by hand (arcs included).
    #[test]
    fn scaling_by_code_is_scaling_by_hand(
        steps in proptest::collection::vec(step(), 1..10),
        cx in -50.0f64..50.0,
        cy in -50.0f64..50.0,
        factor in 0.2f64..4.0,
    ) {
        let by_hand = move |x: f64, y: f64| (cx + factor * (x - cx), cy + factor * (y - cy));
        let header = format!("G51 X{cx:.9} Y{cy:.9} P{factor:.9}\n");
        assert_coded_is_by_hand(&steps, &by_hand, false, &header, &syntec())?;
    }
}
