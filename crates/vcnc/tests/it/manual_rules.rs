//! Rules of the ISO manuals that vcnc once read differently from the controls (issue 23's list),
//! each test quoting its rule: the compensation and cycle alarms of the FANUC family, Mitsubishi's
//! G30 P and bare G, Syntec's `S1=`.

use vcnc::{AlarmCode, Machine, ProfileName};

use crate::common::{run, trace_on, Run};

fn on(profile: ProfileName) -> Machine {
    Machine::default().with_profile(profile).unwrap()
}

/// Writes tool offset register `number` of `machine`: its length and radius.
fn set_register(machine: &mut Machine, number: u32, length: f64, radius: f64) {
    let register = vcnc::machine::ToolOffset {
        number,
        length,
        radius,
        ..Default::default()
    };
    machine.tool_offsets.insert(number, register);
}

fn iso(text: &str, machine: &Machine) -> Run {
    run(text.as_bytes(), machine, vcnc::interp::Options::default())
}

/// The code and line of the alarm that stops `text` on `profile`.
fn stop(text: &str, profile: ProfileName) -> (AlarmCode, u32, String) {
    let run = iso(text, &on(profile));
    let alarm = run
        .error()
        .unwrap_or_else(|| panic!("no alarm on {profile:?}:\n{text}"));
    (
        alarm.code,
        alarm.span.map_or(0, |s| s.line),
        alarm.message.clone(),
    )
}

const ISO: [ProfileName; 5] = [
    ProfileName::Fanuc,
    ProfileName::Fanuc0m,
    ProfileName::Mitsubishi,
    ProfileName::Syntec,
    ProfileName::Haas,
];

/// "G41/G42 start-up and G40 cancel are allowed only in blocks with G00 or G01 motion, never with
/// G02/G03" (Syntec L1740; FANUC alarm 034). Before, the cancel arc ran from the offset point
/// (radius 11.18) to the programmed one (radius 10): no arc at all.
#[test]
fn cutter_compensation_ends_only_in_a_straight_move() {
    let text = "G90 G17 G00 X0 Y0\nG41 D1 G01 X20. Y0. F100.\nG40 G02 X30. Y10. R10.\nM30\n";
    for profile in ISO {
        let (code, line, message) = stop(text, profile);
        assert_eq!(
            (code, line),
            (AlarmCode::CutterCompensation, 3),
            "{profile:?}"
        );
        assert!(
            message.contains("ends only in a G00 or G01 block"),
            "{message}"
        );
    }
    // G40 with G01, then the arc: fine.
    let text =
        "G90 G17 G00 X0 Y0\nG41 D1 G01 X20. Y0. F100.\nG40 G01 X20. Y0.\nG02 X30. Y10. R10.\nM30\n";
    assert!(iso(text, &on(ProfileName::Fanuc)).error().is_none());
}

/// The offset vector lies in the plane of G41/G42: another plane while it is on is FANUC alarm
/// 037; the G40 block may change it.
#[test]
fn the_plane_cannot_change_while_compensating() {
    let text = "G90 G17 G00 X0 Y0\nG41 D1 G01 X20. Y0. F100.\nG18 X30.\nG40 X0\nM30\n";
    for profile in ISO {
        let (code, line, _) = stop(text, profile);
        assert_eq!(
            (code, line),
            (AlarmCode::CutterCompensation, 3),
            "{profile:?}"
        );
    }
    let text = "G90 G17 G00 X0 Y0\nG41 D1 G01 X20. Y0. F100.\nG17 Y10.\nG40 G18 X0 Y0\nG02 X10. Z0 R5.\nM30\n";
    let run = iso(text, &on(ProfileName::Fanuc));
    assert!(run.error().is_none(), "{:?}", run.alarms);
}

/// "Cancel with G80 ... otherwise the machine cannot return to the machine origin" (0M 001
/// L1754, spec A.32): G28/G29/G30 while a canned cycle is in force is FANUC alarm 044. Before,
/// the G28 ran and the next X drilled a hole down from the reference point.
#[test]
fn a_reference_return_in_a_canned_cycle_is_an_alarm() {
    let text = "G90 G00 X0 Y0 Z10.\nG81 X10. Y10. Z-5. R2. F100.\nG28 Z10.\nX20.\nG80\nM30\n";
    for profile in ISO {
        let (code, line, message) = stop(text, profile);
        assert_eq!((code, line), (AlarmCode::CycleData, 3), "{profile:?}");
        assert!(
            message.contains("while a canned cycle is in force"),
            "{message}"
        );
    }
    // With G80 in the block, or before it, the return runs.
    let text = "G90 G00 X0 Y0 Z10.\nG81 X10. Y10. Z-5. R2. F100.\nG80 G28 Z10.\nM30\n";
    assert!(iso(text, &on(ProfileName::Fanuc)).error().is_none());
}

/// "P omitted, P0, P1 or P >= 5 -> 2nd reference point" (Mitsubishi 003 L50, spec B.9); FANUC
/// has no such rule: a P it lacks is an alarm.
#[test]
fn mitsubishi_g30_with_another_p_goes_to_the_second_reference_point() {
    let mut machine = on(ProfileName::Mitsubishi);
    machine.reference_points[1][0] = 222.0; // the 2nd point's X
    machine.reference_points[2][0] = 333.0; // the 3rd's
    for (p, x) in [
        ("", 222.0),
        ("P0", 222.0),
        ("P1", 222.0),
        ("P2", 222.0),
        ("P3", 333.0),
        ("P5", 222.0),
        ("P9", 222.0),
    ] {
        // G91 X0: the intermediate point is where the tool stands; then X to the point.
        let trace = trace_on(&machine, &format!("G91 G30 {p} X0\nM30\n"));
        let last_rapid = trace.lines().rev().find(|l| l.starts_with("rapid"));
        assert_eq!(
            last_rapid,
            Some(format!("rapid X{x} Y0 Z0").as_str()),
            "{p}: {trace}"
        );
    }
    let (code, _, _) = stop("G91 G30 P5 X0\nM30\n", ProfileName::Fanuc);
    assert_eq!(code, AlarmCode::ReferencePointOutOfRange);
}

/// "G (no number): treated as G00" (Mitsubishi 003 B.0); elsewhere an address without a value.
#[test]
fn a_bare_g_is_g00_on_mitsubishi_only() {
    let trace = trace_on(
        &on(ProfileName::Mitsubishi),
        "G01 X1. F100.\nG X10. Y5.\nM30\n",
    );
    assert!(trace.contains("rapid X10 Y5 Z0"), "{trace}");
    let (code, line, _) = stop("G X10. Y5.\nM30\n", ProfileName::Fanuc);
    assert_eq!((code, line), (AlarmCode::MissingValue, 1));
}

/// "`Sn=` addresses spindle n explicitly" (Syntec 1.64, L4865): `S1=150` is spindle 1's speed.
#[test]
fn syntec_s1_sets_the_speed_of_spindle_one() {
    let trace = trace_on(&on(ProfileName::Syntec), "M03 S1=150\nM30\n");
    assert!(trace.contains("spindle Clockwise 150"), "{trace}");
}

/// "G43/G44 H or G49 without a Z move still performs the offset movement, as if `G00 G91 Z0`
/// had been commanded" (Mitsubishi 003 L65 note 1): at rapid, also in G01.
#[test]
fn mitsubishi_moves_a_length_change_without_z_at_rapid() {
    let mut machine = on(ProfileName::Mitsubishi);
    set_register(&mut machine, 1, 50.0, 0.0);
    let text = "G90 G00 Z100.\nG01 F100. X1.\nG43 H01\nG49\nM30\n";
    let trace = trace_on(&machine, text);
    let lines: Vec<&str> = trace.lines().collect();
    // Z100 with the 50 mm tool is machine Z150; G49 takes it back to 100: both at rapid.
    assert!(lines.contains(&"rapid X1 Y0 Z150"), "{trace}");
    assert!(lines.contains(&"rapid X1 Y0 Z100"), "{trace}");
    // On FANUC the same block moves in the mode in force, G01.
    machine.profile = on(ProfileName::Fanuc).profile;
    let trace = trace_on(&machine, text);
    assert!(trace.contains("line X1 Y0 Z150 F100"), "{trace}");
}

/// "At reference point return the local coordinate system is cancelled" (Mitsubishi 003 L75):
/// after G28 the program's X0 is the work zero again; FANUC keeps G52.
#[test]
fn mitsubishi_g28_cancels_the_local_coordinate_system() {
    let text = "G90 G52 X10.\nG00 X0 Y0\nG91 G28 X0\nG90 G00 X0\nM30\n";
    let last = |profile| {
        let trace = trace_on(&on(profile), text);
        trace
            .lines()
            .rev()
            .find(|l| l.starts_with("rapid"))
            .map(str::to_string)
    };
    assert_eq!(
        last(ProfileName::Mitsubishi).as_deref(),
        Some("rapid X0 Y0 Z0")
    );
    assert_eq!(last(ProfileName::Fanuc).as_deref(), Some("rapid X10 Y0 Z0"));
}

/// Haas's G28 cancels tool length compensation: the next Z move is without it; FANUC only
/// clears the vector until the next Z move (spec A.26).
#[test]
fn haas_g28_cancels_the_tool_length_offset() {
    let text = "G90 G00 G43 H01 Z100.\nG91 G28 Z0\nG90 G00 Z100.\nM30\n";
    let last = |profile| {
        let mut machine = on(profile);
        set_register(&mut machine, 1, 50.0, 0.0);
        let trace = trace_on(&machine, text);
        trace
            .lines()
            .rev()
            .find(|l| l.starts_with("rapid"))
            .map(str::to_string)
    };
    assert_eq!(last(ProfileName::Haas).as_deref(), Some("rapid X0 Y0 Z100"));
    assert_eq!(
        last(ProfileName::Fanuc).as_deref(),
        Some("rapid X0 Y0 Z150")
    );
}

/// "If G53 and G28 are in the same block, the later one is effective" (Mitsubishi 003 L79);
/// FANUC refuses two one-shot codes in a block.
#[test]
fn mitsubishi_takes_the_later_of_g53_and_g28() {
    let text = "G90 G00 X10. Y10. Z10.\nG53 G28 Z5.\nG28 G53 X5.\nM30\n";
    let trace = trace_on(&on(ProfileName::Mitsubishi), text);
    let rapids: Vec<&str> = trace.lines().filter(|l| l.starts_with("rapid")).collect();
    // G28 Z5: through Z5 to the reference point Z0; G53 X5: machine X5.
    assert_eq!(
        rapids,
        [
            "rapid X10 Y10 Z10",
            "rapid X10 Y10 Z5",
            "rapid X10 Y10 Z0",
            "rapid X5 Y10 Z0"
        ],
        "{trace}"
    );
    let (code, line, _) = stop(text, ProfileName::Fanuc);
    assert_eq!((code, line), (AlarmCode::SameGroupGCodes, 2));
}

/// A G04 block only dwells: its other axis words were dropped without a word; now a warning
/// names the first (X is the dwell time when P is absent, spec A.8).
#[test]
fn axis_words_of_a_dwell_block_are_warned() {
    let run = iso(
        "G01 X10. Y0. F100. G04 P1000\nM30\n",
        &on(ProfileName::Fanuc),
    );
    assert!(run.error().is_none());
    let warning = run
        .alarms
        .iter()
        .find(|a| a.message.contains("G04 block"))
        .expect("a warning");
    assert_eq!(warning.code, AlarmCode::WordNotAllowed);
    assert_eq!(warning.span.map(|s| s.start), Some(4));
    // G04 X2. is a dwell of 2 s: no warning.
    let run = iso("G04 X2.\nM30\n", &on(ProfileName::Fanuc));
    assert!(run.alarms.is_empty(), "{:?}", run.alarms);
}

/// FANUC's `(` is control-out and the first `)` control-in: on FANUC 0M `(A (B) C)` ends at
/// `(B)`, and ` C)` is read as words (an alarm, as on the control); the default profile nests
/// parentheses for programs that write them (docs/DEVIATIONS.md).
#[test]
fn a_fanuc_0m_comment_ends_at_its_first_parenthesis() {
    let text = "G00 X1. (A (B) C) Y2.\nM30\n";
    let (code, line, message) = stop(text, ProfileName::Fanuc0m);
    assert_eq!((code, line), (AlarmCode::MissingValue, 1));
    assert!(message.contains("address C"), "{message}");
    assert!(iso(text, &on(ProfileName::Fanuc)).error().is_none());
}

/// "Excess decimals are ignored: X1.23456 is taken as X1.234 (mm) or X1.2345 (inch)"; "generally
/// 7 digits: X1.2345678 raises an alarm" (FANUC 0M, 001 L79-136, spec A.5). Other profiles keep
/// the value whole (docs/DEVIATIONS.md).
#[test]
fn fanuc_0m_drops_excess_decimals_and_limits_digits() {
    let machine = on(ProfileName::Fanuc0m);
    let trace = trace_on(&machine, "G90 G00 X1.23456 Y-0.0019\nM30\n");
    assert!(trace.starts_with("rapid X1.234 Y-0.001 Z0"), "{trace}");
    // Inches: 1.23456 in is 1.2345 in = 31.3563 mm.
    let trace = trace_on(&machine, "G20 G90 G00 X1.23456\nM30\n");
    assert!(trace.starts_with("rapid X31.3563 Y0 Z0"), "{trace}");
    // A value on the grid stays as written, binary error or not.
    let trace = trace_on(&machine, "G90 G00 X1.234 Y4.35\nM30\n");
    assert!(trace.starts_with("rapid X1.234 Y4.35 Z0"), "{trace}");
    let (code, line, message) = stop("G00 X1.2345678\nM30\n", ProfileName::Fanuc0m);
    assert_eq!((code, line), (AlarmCode::ValueOutOfRange, 1));
    assert!(message.contains("8 digits"), "{message}");
    // FANUC keeps the whole value and reads the 8 digits.
    let trace = trace_on(&on(ProfileName::Fanuc), "G90 G00 X1.2345678\nM30\n");
    assert!(trace.starts_with("rapid X1.2346 Y0 Z0"), "{trace}");
}

/// G96: "N = 1000 V / (pi D)", clamped by `G92 S` (Syntec 1.58, L4597-4628; example 65 in the
/// seed table): with a 10 mm cutter S130 is 4138.03 rpm; G92 S2000 clamps it; under G20, S100
/// ft/min on the same cutter (0.3937 in) is 12 x 100 / (pi x 0.3937) = 970.2 rpm; G97 S is rpm.
#[test]
fn g96_turns_the_surface_speed_into_the_cutters_rpm() {
    let mut machine = on(ProfileName::Syntec);
    set_register(&mut machine, 1, 0.0, 5.0);
    // D2 for inch programs: the register is read in the unit in force, as the radius of G41.
    set_register(&mut machine, 2, 0.0, 0.19685);
    let speeds = |text: &str| -> Vec<f64> {
        iso(text, &machine)
            .segments
            .iter()
            .filter_map(|s| match s.kind {
                vcnc::SegmentKind::Spindle { speed, .. } => Some((speed * 10.0).round() / 10.0),
                _ => None,
            })
            .collect()
    };
    assert_eq!(speeds("D1 G96 S130 M03\nG97 S500\nM30\n"), [4138.0, 500.0]);
    assert_eq!(speeds("G92 S2000\nD1 G96 S130 M03\nM30\n"), [2000.0]);
    assert_eq!(speeds("G20 D2 G96 S100 M03\nM30\n"), [970.2]);
    // No diameter: a warning, and the speed stays as it was (0).
    let run = iso("G96 S130 M03\nM30\n", &machine);
    assert!(run
        .alarms
        .iter()
        .any(|a| a.message.contains("no cutter diameter")));
}

/// Haas G12/G13 circular pocket milling (Haas mill manual: I the first circle's radius, K the
/// finish one, Q the step, L passes, D the cutter, Z the depth): with a 2 mm cutter, G13 I4. K10.
/// Q3. cuts the tool centre on radii 2, 5 and 8 (4, 7, 10 less the cutter), each reached by a
/// half circle out, then back to the centre; before, G12/G13 were refused on Haas.
#[test]
fn haas_g12_g13_mill_a_circular_pocket() {
    let mut machine = on(ProfileName::Haas);
    // Haas's D registers hold diameters: 4 mm is the 2 mm radius.
    set_register(&mut machine, 1, 0.0, 4.0);
    let text = "G90 G00 X0 Y0 Z1.\nG13 X20. Y10. I4. K10. Q3. Z-2. D01 F300.\nM30\n";
    let trace = trace_on(&machine, text);
    let lines: Vec<&str> = trace.lines().collect();
    assert_eq!(lines[1], "rapid X20 Y10 Z1", "{trace}");
    assert_eq!(lines[2], "line X20 Y10 Z-2 F300", "{trace}");
    let arcs: Vec<&str> = lines
        .iter()
        .copied()
        .filter(|l| l.starts_with("arc"))
        .collect();
    assert_eq!(
        arcs,
        [
            "arc ccw xy X22 Y10 Z-2 C(21,10,-2) F300",
            "arc ccw xy X22 Y10 Z-2 C(20,10,-2) F300",
            "arc ccw xy X25 Y10 Z-2 C(23.5,10,-2) F300",
            "arc ccw xy X25 Y10 Z-2 C(20,10,-2) F300",
            "arc ccw xy X28 Y10 Z-2 C(26.5,10,-2) F300",
            "arc ccw xy X28 Y10 Z-2 C(20,10,-2) F300",
            "arc ccw xy X20 Y10 Z-2 C(24,10,-2) F300",
        ],
        "{trace}"
    );
    // G91 Z-1. L2: two passes, 1 mm deeper each.
    let trace = trace_on(
        &machine,
        "G90 G00 X0 Y0 Z0\nG91 G12 I5. Z-1. L2 D01 F300.\nM30\n",
    );
    let depths: Vec<&str> = trace.lines().filter(|l| l.starts_with("line")).collect();
    assert_eq!(
        depths,
        ["line X0 Y0 Z-1 F300", "line X0 Y0 Z-2 F300"],
        "{trace}"
    );
    let (code, _, message) = stop("G12 I5. K10. D01 F300.\nM30\n", ProfileName::Haas);
    assert_eq!(code, AlarmCode::CircleCutting);
    assert!(message.contains("K needs Q"), "{message}");
    let run = iso("G12 I1.5 D01 F300.\nM30\n", &machine);
    assert!(run
        .error()
        .is_some_and(|a| a.message.contains("not larger than the cutter")));
}

/// The end points of the moves of `text` on `profile` (rapids and lines), one per line.
fn ends(profile: ProfileName, text: &str) -> Vec<String> {
    trace_on(&on(profile), text)
        .lines()
        .filter(|l| l.starts_with("rapid") || l.starts_with("line"))
        .map(|l| l.split(" F").next().unwrap_or(l).to_string())
        .collect()
}

/// A FANUC's G16: "the current position is set as the origin of the polar coordinate system"
/// when the radius is programmed incrementally, and an incremental angle adds to the previous
/// one; a radius in G90 is measured from the work origin. Syntec adds both to the previous
/// polar point (spec 1.14, L1033).
#[test]
fn a_fanuc_g16_radius_in_g91_is_measured_from_the_current_position() {
    // From (50, 0), polar angle 0: radius 10 at +30 degrees about (50, 0) is
    // (50 + 10 cos 30, 10 sin 30) = (58.6603, 5); the angle alone then steps to 60 degrees about
    // the same pole: (50 + 10 cos 60, 10 sin 60) = (55, 8.6603).
    let text = "G90 G17 G00 X50. Y0\nG16\nG91 G01 X10. Y30. F100.\nY30.\nM30\n";
    for profile in [
        ProfileName::Fanuc,
        ProfileName::Fanuc0m,
        ProfileName::Mitsubishi,
        ProfileName::Haas,
    ] {
        assert_eq!(
            ends(profile, text),
            [
                "rapid X50 Y0 Z0",
                "line X58.6603 Y5 Z0",
                "line X55 Y8.6603 Z0"
            ],
            "{profile:?}"
        );
    }
    // Syntec: radius 50 + 10 = 60 at 30 degrees, then 60 degrees: (51.9615, 30), (30, 51.9615).
    assert_eq!(
        ends(ProfileName::Syntec, text),
        [
            "rapid X50 Y0 Z0",
            "line X51.9615 Y30 Z0",
            "line X30 Y51.9615 Z0"
        ]
    );
}

/// The bolt-hole circle of a FANUC's polar coordinates: radius in G90, angles stepped in G91;
/// the pole stays the work origin since no radius is programmed incrementally. Every profile
/// agrees: 100 at 30, 150 and 270 degrees.
#[test]
fn polar_angles_stepped_in_g91_keep_the_pole_at_the_origin() {
    let text = "G90 G17 G16 G00 X100. Y30.\nG91 Y120.\nY120.\nG15 M30\n";
    for profile in ISO {
        assert_eq!(
            ends(profile, text),
            [
                "rapid X86.6025 Y50 Z0",
                "rapid X-86.6025 Y50 Z0",
                "rapid X0 Y-100 Z0"
            ],
            "{profile:?}"
        );
    }
}

/// A FANUC scales the axes its parameters select (X Y Z), "if X Y Z are omitted, the tool
/// position where G51 is commanded serves as the scaling center" (Haas says the same of its
/// G51); Syntec scales only the axes named (spec 1.28).
#[test]
fn a_fanuc_g51_scales_every_basic_axis_about_the_current_position() {
    // Z's centre is the current Z 10: 10 + 2 (5 - 10) = 0; X Y about (0, 0): (20, 20).
    let text = "G90 G00 X0 Y0 Z10.\nG51 X0 Y0 P2.\nG01 X10. Y10. Z5. F100.\nG50\nM30\n";
    for profile in [
        ProfileName::Fanuc,
        ProfileName::Haas,
        ProfileName::Mitsubishi,
    ] {
        assert_eq!(ends(profile, text)[1], "line X20 Y20 Z0", "{profile:?}");
    }
    assert_eq!(ends(ProfileName::Syntec, text)[1], "line X20 Y20 Z5");
}

/// "Processing proceeds from program mirror image to scaling and coordinate rotation in the
/// stated order" (a FANUC; Syntec refuses the two together, spec 1.28): G50 and G50.1 each end
/// only their own.
#[test]
fn a_fanuc_combines_the_mirror_and_scaling() {
    // Mirror about X = 50, scaling by 2 about (0, 0): X10 Y10 scales to (20, 20) and mirrors to
    // (80, 20). After G50 the mirror alone: X10 -> 90, Y stays where the tool is (20). After
    // G50.1: X10.
    let text = "G90 G00 X0 Y0\nG51.1 X50.\nG51 X0 Y0 P2.\nG01 X10. Y10. F100.\nG50\nX10.\n\
        G50.1\nX10.\nM30\n";
    assert_eq!(
        ends(ProfileName::Fanuc, text),
        ["line X80 Y20 Z0", "line X90 Y20 Z0", "line X10 Y20 Z0"]
    );
    let (code, line, _) = stop(text, ProfileName::Syntec);
    assert_eq!((code, line), (AlarmCode::WordNotAllowed, 3));
}

/// "Even when G53 is commanded, the tool radius compensation of the commanded axes is not
/// cancelled" (Mitsubishi 003 L79): its rapid is an element of the compensated path; a FANUC
/// makes the block without compensation, as G28 (spec A.22 rule 4).
#[test]
fn mitsubishi_g53_keeps_the_radius_compensation() {
    // Radius 5 on the left: up X20 from Y0 to Y20, then G53 along +X to X50 and a cancel up to
    // Y40. Kept, the G53 element ends 5 to its left, (50, 25), as the last element before G40
    // does; suspended, the tool centre goes to (50, 20) itself.
    let text = "G90 G17 G00 X20. Y-10.\nG41 D1 G01 Y0 F100.\nY20.\nG53 X50. Y20.\n\
        G40 G00 Y40.\nM30\n";
    let g53_end = |profile| {
        let mut machine = on(profile);
        set_register(&mut machine, 1, 0.0, 5.0);
        let trace = trace_on(&machine, text);
        let rapids: Vec<_> = trace.lines().filter(|l| l.starts_with("rapid")).collect();
        rapids[rapids.len() - 2].to_string()
    };
    assert_eq!(g53_end(ProfileName::Mitsubishi), "rapid X50 Y25 Z0");
    assert_eq!(g53_end(ProfileName::Fanuc), "rapid X50 Y20 Z0");
}

/// Haas G47 engraves the comment's text (P0) or one ASCII character (P32-126) from X Y, J tall,
/// turned by I degrees: a rapid to X Y and to R, and each stroke plunged to Z at E, cut at F and
/// left at rapid to R. The font is vcnc's own: an A is (0,0)-(2,6)-(4,0) and (1,2)-(3,2) on a
/// grid 6 units tall, so J6. draws it in millimetres as written.
#[test]
fn haas_g47_engraves_text_stroke_by_stroke() {
    let machine = on(ProfileName::Haas);
    let text = "G90 G17 G00 X0 Y0 Z5.\nF100.\nG47 P0 (A) X10. Y5. J6. R1. Z-0.5 E50.\nM30\n";
    let trace = trace_on(&machine, text);
    let moves: Vec<&str> = trace.lines().skip(1).take(9).collect();
    assert_eq!(
        moves,
        [
            "rapid X10 Y5 Z5",
            "rapid X10 Y5 Z1",
            "line X10 Y5 Z-0.5 F50",
            "line X12 Y11 Z-0.5 F100",
            "line X14 Y5 Z-0.5 F100",
            "rapid X14 Y5 Z1",
            "rapid X11 Y7 Z1",
            "line X11 Y7 Z-0.5 F50",
            "line X13 Y7 Z-0.5 F100",
        ]
    );
    // P65 is the same A; I90 turns it about X Y: grid (x, y) goes to (-y, x), the apex (2, 6)
    // to (-6, 2).
    let turned = "G90 G17 G00 X0 Y0 Z5.\nG47 P65 X0 Y0 I90. J6. R1. Z-0.5 F100.\nM30\n";
    let trace = trace_on(&machine, turned);
    assert!(trace.contains("line X-6 Y2 Z-0.5 F100"), "{trace}");
    // P0 without a comment, a character the font lacks, or G47 elsewhere than on Haas.
    let (code, line, _) = stop("F100.\nG47 P0 X0 Y0 Z-1.\nM30\n", ProfileName::Haas);
    assert_eq!((code, line), (AlarmCode::Engraving, 2));
    let (code, _, _) = stop("F100.\nG47 P7 X0 Y0 Z-1.\nM30\n", ProfileName::Haas);
    assert_eq!(code, AlarmCode::Engraving);
}

/// Haas G47 P1 engraves the serial number of #599 in as many digits as its comment has `#`,
/// then counts #599 on: 41 in `(####)` is 0041, the 4 starting at (12 + 3, 0) and the 1 at
/// (18 + 1, 5) on the font's grid (J6.: millimetres as written).
#[test]
fn haas_g47_p1_engraves_the_serial_number_and_counts_it_on() {
    let machine = on(ProfileName::Haas);
    let text = "#599=41\nG90 G17 G00 X0 Y0 Z5.\nF100.\nG47 P1 (####) X0 Y0 J6. R1. Z-0.5\n\
        IF[#599NE42]THEN#3000=1(SERIAL NOT COUNTED)\nM30\n";
    let trace = trace_on(&machine, text);
    assert!(!trace.contains("alarm"), "{trace}");
    assert!(trace.contains("rapid X15 Y0 Z1"), "{trace}");
    assert!(trace.contains("rapid X19 Y5 Z1"), "{trace}");
    // Five digits do not fit in four.
    let (code, line, _) = stop(
        "#599=12345\nF100.\nG47 P1 (####) X0 Y0 Z-1.\nM30\n",
        ProfileName::Haas,
    );
    assert_eq!((code, line), (AlarmCode::Engraving, 3));
}
