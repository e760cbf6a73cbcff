//! Syntec's G81 retract feed `F2=` (spec iso-syntec-milling.md 1.44, seed 000 L3585-3610): in
//! the fast drilling mode (Pr4008 = 1, the profile's `cycles.fast_drilling`) the tool comes back
//! up at F2; in the normal mode, or with F2 not given or 0, at rapid.

use vcnc::motion::Feed;
use vcnc::{Machine, ProfileName, SegmentKind};

/// The manual's example (L3629-3661, file 53-g81-drill-f2.nc as the spec restores it): five
/// holes, F2=1000 given with the first.
const EXAMPLE: &str = "N001 F1000. S500\nN002 G90\nN003 G00 X0. Y0. Z10.\nN004 G17\nN005 G90 G99\nN006 G81 X5. Y5. Z-10. R-5. F2=1000\nN007 X15.\nN008 Y15.\nN009 G98 X5.\nN010 X10. Y10. Z-20.\nN011 G80\nN012 M30\n";

/// The upward moves of `program` after N003's rise to the initial level: (ends at Z, fed at
/// mm/min or None for a rapid).
fn retracts(fast_drilling: bool, program: &str) -> Vec<(f64, Option<f64>)> {
    let mut machine = Machine::default()
        .with_profile(ProfileName::Syntec)
        .unwrap();
    machine.profile.cycles.fast_drilling = fast_drilling;
    let run = crate::common::run(program.as_bytes(), &machine, vcnc::Options::default());
    assert!(run.error().is_none(), "{:?}", run.error());
    run.segments
        .iter()
        .filter_map(|s| {
            let motion = s.motion()?;
            let up = motion.to.0[2] > motion.from.0[2] && motion.to.0[..2] == motion.from.0[..2];
            let feed = match s.kind {
                SegmentKind::Line {
                    feed: Feed::PerMinute(f),
                    ..
                } => Some(f),
                _ => None,
            };
            up.then_some((motion.to.0[2], feed))
        })
        .skip(1)
        .collect()
}

#[test]
fn fast_drilling_retracts_at_f2() {
    // Holes 1-3 back to R (-5, G99), holes 4-5 to the initial level (10, G98), each at 1000.
    let expected: Vec<_> = [-5.0, -5.0, -5.0, 10.0, 10.0]
        .into_iter()
        .map(|z| (z, Some(1000.0)))
        .collect();
    assert_eq!(retracts(true, EXAMPLE), expected);
}

#[test]
fn normal_drilling_and_f2_zero_retract_at_rapid() {
    let rapid: Vec<_> = [-5.0, -5.0, -5.0, 10.0, 10.0]
        .into_iter()
        .map(|z| (z, None))
        .collect();
    assert_eq!(retracts(false, EXAMPLE), rapid);
    let f2_zero = EXAMPLE.replace("F2=1000", "F2=0");
    assert_eq!(retracts(true, &f2_zero), rapid);
}
