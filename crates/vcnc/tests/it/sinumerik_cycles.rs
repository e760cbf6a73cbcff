//! SINUMERIK's standard cycles (docs/SINUMERIK.md, Standard cycles): the drilling cycles, the
//! position patterns with MCALL, the pockets, and the cycles' alarms (61xxx, V074).
//!
//! Every expected position is worked out by hand from the parameter meanings the docs give:
//! the hole is where the cycle is called, RFP+SDIS is the safety plane the tool rapids to,
//! DP (or RFP-DPR) the depth it feeds to, RTP the plane it rapids back to. The machine is the
//! default one with no work offset and no tool length, so program and machine coordinates are
//! the same.

use vcnc::interp::sinumerik::{run_str, Sinumerik};
use vcnc::interp::{Kernel, MemoryLibrary, Run};
use vcnc::motion::SpindleState;
use vcnc::source::FileId;
use vcnc::{Alarm, AlarmCode, Machine, Segment, SegmentKind};

use crate::common::collect;
use crate::common::sinumerik::{machine, mill};

/// A move as the tests compare it: R rapid, L line, A arc, T thread (a line per revolution),
/// and its end X Y Z.
pub(crate) type Move = (char, [f64; 3]);

pub(crate) fn run(text: &str, machine: &Machine) -> Vec<Segment> {
    let run = collect(run_str(text, machine));
    assert!(run.error().is_none(), "{text}\n{:#?}", run.alarms);
    run.segments
}

pub(crate) fn moves(segments: &[Segment]) -> Vec<Move> {
    segments
        .iter()
        .filter_map(|s| {
            let kind = match &s.kind {
                SegmentKind::Rapid { .. } => 'R',
                SegmentKind::Line {
                    feed: vcnc::motion::Feed::PerRevolution { .. },
                    ..
                } => 'T',
                SegmentKind::Line { .. } => 'L',
                SegmentKind::Arc { .. } => 'A',
                _ => return None,
            };
            let to = s.motion()?.to.0;
            Some((kind, [to[0], to[1], to[2]]))
        })
        .collect()
}

/// The moves of `text` after its first `skip` (the positioning before the cycle).
fn moves_after(text: &str, skip: usize) -> Vec<Move> {
    moves(&run(text, &machine()))[skip..].to_vec()
}

pub(crate) fn assert_moves(got: &[Move], wanted: &[Move]) {
    assert_eq!(got.len(), wanted.len(), "got {got:?}\nwanted {wanted:?}");
    for (k, (g, w)) in got.iter().zip(wanted).enumerate() {
        let close = (0..3).all(|i| (g.1[i] - w.1[i]).abs() < 1e-3);
        assert!(
            g.0 == w.0 && close,
            "move {k}: got {g:?}, wanted {w:?}\nall: {got:?}"
        );
    }
}

/// The feed of every cutting line in order, mm/min.
pub(crate) fn line_feeds(segments: &[Segment]) -> Vec<f64> {
    segments
        .iter()
        .filter_map(|s| match &s.kind {
            SegmentKind::Line { feed, .. } => feed.mm_per_min(1.0),
            _ => None,
        })
        .collect()
}

pub(crate) fn error(text: &str, machine: &Machine) -> Alarm {
    collect(run_str(text, machine))
        .error()
        .cloned()
        .unwrap_or_else(|| panic!("no error in\n{text}"))
}

/// The cycle alarm of `text` on a machine with a 10 mm end mill (T1 D1): its number.
pub(crate) fn cycle_alarm(text: &str) -> String {
    let mut machine = machine();
    machine.tools.push(mill(1, "MILL", 1, 0.0, 5.0));
    let alarm = error(text, &machine);
    assert_eq!(alarm.code, AlarmCode::CycleParameter, "{alarm:?}");
    let span = alarm.span.expect("a cycle alarm points at the call");
    assert!(span.end > span.start, "{alarm:?}");
    alarm.message.split(':').next().unwrap_or("").to_string()
}

const START: &str = "G17 G90 F100 S1000 M3\nG0 X10 Y20 Z50\n";

#[test]
fn cycle81_rapids_to_the_safety_plane_drills_and_rapids_to_the_retraction_plane() {
    // RTP 10, RFP 0, SDIS 2, DP -15: rapid to Z 0+2, feed to Z-15, rapid to Z10, at X10 Y20.
    let got = moves_after(&format!("{START}CYCLE81(10,0,2,-15)\nM30\n"), 1);
    assert_moves(
        &got,
        &[
            ('R', [10.0, 20.0, 2.0]),
            ('L', [10.0, 20.0, -15.0]),
            ('R', [10.0, 20.0, 10.0]),
        ],
    );
}

#[test]
fn a_relative_depth_wins_over_the_absolute_one() {
    // DPR 5 below RFP 1: the depth is 1-5 = -4, whatever DP says.
    let got = moves_after(&format!("{START}CYCLE81(10,1,2,-15,5)\nM30\n"), 1);
    assert_moves(
        &got,
        &[
            ('R', [10.0, 20.0, 3.0]),
            ('L', [10.0, 20.0, -4.0]),
            ('R', [10.0, 20.0, 10.0]),
        ],
    );
}

#[test]
fn the_next_block_continues_from_the_retraction_plane() {
    // After the cycle the programmed Z is RTP 10: G91 Z5 goes to 15.
    let got = moves_after(&format!("{START}CYCLE81(10,0,2,-15)\nG91 Z5\nM30\n"), 4);
    assert_moves(&got, &[('R', [10.0, 20.0, 15.0])]);
}

#[test]
fn cycle82_dwells_at_the_depth() {
    let segments = run(
        &format!("{START}CYCLE82(10,0,2,-6,,1.5)\nM30\n"),
        &machine(),
    );
    let kinds: Vec<_> = segments
        .iter()
        .filter_map(|s| match s.kind {
            SegmentKind::Line { .. } => Some("line".to_string()),
            SegmentKind::Dwell { seconds } => Some(format!("dwell {seconds}")),
            SegmentKind::Rapid { .. } => Some("rapid".to_string()),
            _ => None,
        })
        .collect();
    assert_eq!(kinds, ["rapid", "rapid", "line", "dwell 1.5", "rapid"]);
}

#[test]
fn cycle83_removing_the_swarf_goes_out_after_every_peck_and_back_to_the_anticipation_distance() {
    // RTP 10, RFP 0, SDIS 1, DP -20, FDEP -8, DAM 3, VARI 1. The infeeds: 8 (to -8), 5 (-13),
    // 3 (5-3 = 2 is less than DAM: 3, to -16), 3 (-19), the rest (-20). The drilling path
    // 1-(-20) = 21 is under 30 mm: the anticipation distance is 0.6 mm.
    let got = moves_after(
        &format!("{START}CYCLE83(10,0,1,-20,,-8,,3,0,0,1,1)\nM30\n"),
        1,
    );
    let mut wanted = vec![('R', [10.0, 20.0, 1.0]), ('L', [10.0, 20.0, -8.0])];
    for (last, next) in [
        (-8.0, -13.0),
        (-13.0, -16.0),
        (-16.0, -19.0),
        (-19.0, -20.0),
    ] {
        wanted.push(('R', [10.0, 20.0, 1.0]));
        wanted.push(('R', [10.0, 20.0, last + 0.6]));
        wanted.push(('L', [10.0, 20.0, next]));
    }
    wanted.push(('R', [10.0, 20.0, 10.0]));
    assert_moves(&got, &wanted);
}

#[test]
fn cycle83_breaking_the_chip_backs_off_one_millimetre_at_the_feed() {
    // FDEP -5, no degression, VARI 0: pecks to -5, -10, -12, each followed by 1 mm back.
    let got = moves_after(
        &format!("{START}CYCLE83(10,0,1,-12,,-5,,0,0,0,1,0)\nM30\n"),
        1,
    );
    assert_moves(
        &got,
        &[
            ('R', [10.0, 20.0, 1.0]),
            ('L', [10.0, 20.0, -5.0]),
            ('L', [10.0, 20.0, -4.0]),
            ('L', [10.0, 20.0, -10.0]),
            ('L', [10.0, 20.0, -9.0]),
            ('L', [10.0, 20.0, -12.0]),
            ('R', [10.0, 20.0, 10.0]),
        ],
    );
}

#[test]
fn cycle83_cuts_its_first_peck_at_the_feed_factor() {
    // F100 with FRF 0.5: the first infeed at 50 mm/min, the others at 100.
    let segments = run(
        &format!("{START}CYCLE83(10,0,1,-8,,-4,,0,0,0,0.5,1)\nM30\n"),
        &machine(),
    );
    let feeds = line_feeds(&segments);
    assert_eq!(feeds, [50.0, 100.0]);
}

#[test]
fn cycle84_taps_in_at_sst_and_out_at_sst1_the_other_way() {
    // MPIT 8: M8, pitch 1.25, right hand. SDAC 3: M3 again at S1000 afterwards.
    let segments = run(
        &format!("{START}CYCLE84(10,0,2,-20,,0,3,8,,0,500,800)\nM30\n"),
        &machine(),
    );
    let got = moves(&segments)[1..].to_vec();
    assert_moves(
        &got,
        &[
            ('R', [10.0, 20.0, 2.0]),
            ('T', [10.0, 20.0, -20.0]),
            ('T', [10.0, 20.0, 2.0]),
            ('R', [10.0, 20.0, 10.0]),
        ],
    );
    let spindle: Vec<_> = segments
        .iter()
        .filter_map(|s| match s.kind {
            SegmentKind::Spindle { speed, state } => Some((speed, state)),
            _ => None,
        })
        .collect();
    assert_eq!(
        spindle[1..],
        [
            (1000.0, SpindleState::Oriented),
            (500.0, SpindleState::Clockwise),
            (800.0, SpindleState::CounterClockwise),
            (1000.0, SpindleState::Clockwise),
        ]
    );
    let leads: Vec<f64> = segments
        .iter()
        .filter_map(|s| match &s.kind {
            SegmentKind::Line {
                feed: vcnc::motion::Feed::PerRevolution { per_revolution, .. },
                ..
            } => Some(*per_revolution),
            _ => None,
        })
        .collect();
    assert_eq!(leads, [1.25, 1.25]);
}

#[test]
fn cycle85_feeds_in_at_ffr_and_out_at_rff() {
    let segments = run(
        &format!("{START}CYCLE85(10,0,2,-10,,0,300,600)\nM30\n"),
        &machine(),
    );
    let got = moves(&segments)[1..].to_vec();
    assert_moves(
        &got,
        &[
            ('R', [10.0, 20.0, 2.0]),
            ('L', [10.0, 20.0, -10.0]),
            ('L', [10.0, 20.0, 2.0]),
            ('R', [10.0, 20.0, 10.0]),
        ],
    );
    let feeds = line_feeds(&segments);
    assert_eq!(feeds, [300.0, 600.0]);
}

#[test]
fn cycle86_lifts_off_the_wall_before_it_comes_out() {
    // SDIR 3, RPA -1, RPO 0, RPAP 0.5: after the oriented stop the tool moves to X9, up 0.5,
    // out to the safety plane and RTP, and back over the hole's centre.
    let got = moves_after(
        &format!("{START}CYCLE86(10,0,2,-10,,0,3,-1,0,0.5,0)\nM30\n"),
        1,
    );
    assert_moves(
        &got,
        &[
            ('R', [10.0, 20.0, 2.0]),
            ('L', [10.0, 20.0, -10.0]),
            ('R', [9.0, 20.0, -10.0]),
            ('R', [9.0, 20.0, -9.5]),
            ('R', [9.0, 20.0, 2.0]),
            ('R', [9.0, 20.0, 10.0]),
            ('R', [10.0, 20.0, 10.0]),
        ],
    );
}

#[test]
fn cycle89_comes_out_at_the_feed() {
    let got = moves_after(&format!("{START}CYCLE89(10,0,2,-10,,0.5)\nM30\n"), 1);
    assert_moves(
        &got,
        &[
            ('R', [10.0, 20.0, 2.0]),
            ('L', [10.0, 20.0, -10.0]),
            ('L', [10.0, 20.0, 2.0]),
            ('R', [10.0, 20.0, 10.0]),
        ],
    );
}

#[test]
fn mcall_drills_after_every_positioning_block_until_mcall_alone() {
    let text = format!("{START}MCALL CYCLE81(10,0,2,-5)\nX30\nY40\nMCALL\nX50\nM30\n");
    // X30 moves in G0 at Z50, Y40 at RTP 10 where the first hole left the tool; X50 after
    // MCALL alone moves only.
    let got = moves_after(&text, 1);
    assert_moves(
        &got,
        &[
            ('R', [30.0, 20.0, 50.0]),
            ('R', [30.0, 20.0, 2.0]),
            ('L', [30.0, 20.0, -5.0]),
            ('R', [30.0, 20.0, 10.0]),
            ('R', [30.0, 40.0, 10.0]),
            ('R', [30.0, 40.0, 2.0]),
            ('L', [30.0, 40.0, -5.0]),
            ('R', [30.0, 40.0, 10.0]),
            ('R', [50.0, 40.0, 10.0]),
        ],
    );
}

#[test]
fn holes2_drills_the_circle_of_the_manuals_milling_example() {
    // HOLES2(0,0,25,0,45,6) of sinumerik-a/10-milling-example.mpf: six holes 45° apart on a
    // circle of radius 25: 25·(cos, sin) of 0°, 45°, ... 225°; each drilled to -2.6 and back
    // to RTP 2.
    let text = "G17 G90 F100 S1000 M3\nG0 X25 Y0 Z2\nMCALL CYCLE82(2,0,1,-2.6,,0)\nHOLES2(0,0,25,0,45,6)\nMCALL\nM30\n";
    let got = moves_after(text, 1);
    let mut wanted = Vec::new();
    for k in 0..6 {
        let (sin, cos) = (45.0 * k as f64).to_radians().sin_cos();
        let (x, y) = (25.0 * cos, 25.0 * sin);
        wanted.extend([
            ('R', [x, y, 2.0]),
            ('R', [x, y, 1.0]),
            ('L', [x, y, -2.6]),
            ('R', [x, y, 2.0]),
        ]);
    }
    // The first position is where the tool already is: no move there.
    wanted.remove(0);
    assert_moves(&got, &wanted);
}

#[test]
fn holes1_and_cycle801_visit_their_positions_in_order() {
    // HOLES1(5,10,0,10,20,3): from (5,10) along X, the first 10 away, 20 apart.
    let got = moves_after("G0 X0 Y0 Z5\nHOLES1(5,10,0,10,20,3)\nM30\n", 1);
    assert_moves(
        &got,
        &[
            ('R', [15.0, 10.0, 5.0]),
            ('R', [35.0, 10.0, 5.0]),
            ('R', [55.0, 10.0, 5.0]),
        ],
    );
    // CYCLE801(0,0,0,10,5,3,2): three columns 10 apart, two rows 5 apart, in a meander.
    let got = moves_after("G0 X-1 Y0 Z5\nCYCLE801(0,0,0,10,5,3,2)\nM30\n", 1);
    let wanted: Vec<Move> = [
        (0.0, 0.0),
        (10.0, 0.0),
        (20.0, 0.0),
        (20.0, 5.0),
        (10.0, 5.0),
        (0.0, 5.0),
    ]
    .iter()
    .map(|&(x, y)| ('R', [x, y, 5.0]))
    .collect();
    assert_moves(&got, &wanted);
}

#[test]
fn a_subprogram_of_the_cycles_name_wins_over_the_built_in_cycle() {
    let mut library = MemoryLibrary::new();
    library.insert_named(
        "CYCLE81.SPF",
        FileId(1),
        "PROC CYCLE81(REAL _XPOS)\nG0 X=_XPOS\nM17\n",
    );
    let machine = machine();
    let text = "G0 X0 Y0 Z0\nCYCLE81(7)\nM30\n";
    let front_end =
        Sinumerik::new(text.as_bytes(), FileId(0), &machine).with_library(Box::new(library));
    let run = collect(Run::new(front_end, Kernel::new(&machine)));
    assert!(run.error().is_none(), "{:?}", run.alarms);
    assert_moves(&moves(&run.segments), &[('R', [7.0, 0.0, 0.0])]);
}

/// The machine with a 10 mm end mill in the spindle (T1 D1) for the pockets.
pub(crate) fn pocket_machine() -> Machine {
    let mut machine = machine();
    machine.tools.push(mill(1, "MILL", 1, 0.0, 5.0));
    machine
}

pub(crate) const POCKET_START: &str = "T1 M6 D1\nG17 G90 F500 S3000 M3\nG0 X0 Y0 Z10\n";

#[test]
fn pocket4_stays_inside_the_pocket_and_reaches_its_depth() {
    // The manual's POCKET4(2,0,1,-5,15,0,0,0,0,0,800,1300,0,21,5,,,2,0.5) with a 10 mm mill:
    // the tool centre stays within 15-5 = 10 of the centre, reaches Z-5 in one level, goes in
    // on a helix of radius 2 (0.5 per turn: 12 turns from the safety plane at 1), and ends at
    // the retraction plane 2.
    let text =
        format!("{POCKET_START}POCKET4(2,0,1,-5,15,0,0,0,0,0,800,1300,0,21,5,,,2,0.5)\nM30\n");
    let segments = run(&text, &pocket_machine());
    let got = moves(&segments);
    let lowest = got.iter().map(|m| m.1[2]).fold(f64::MAX, f64::min);
    assert!((lowest + 5.0).abs() < 1e-9, "{lowest}");
    for m in &got {
        let r = m.1[0].hypot(m.1[1]);
        assert!(r <= 10.0 + 1e-9, "{m:?} is {r} from the centre");
    }
    // The outermost ring is at radius 10, cut as two half circles.
    assert!(got
        .iter()
        .any(|m| m.0 == 'A' && (m.1[0] + 10.0).abs() < 1e-9));
    assert_eq!(got.last().map(|m| m.1[2]), Some(2.0));
    // No rapid below the reference plane outside what was cut: every rapid below Z0 is at
    // the level's height plus the clearance or above the centre.
    for m in got.iter().filter(|m| m.0 == 'R' && m.1[2] < 0.0) {
        assert!(m.1[0].hypot(m.1[1]) <= 10.0 + 1e-9, "{m:?}");
    }
}

#[test]
fn pocket3_clears_a_rectangle_in_levels_of_mid() {
    // POCKET3(RTP 10, RFP 0, SDIS 1, DP -6, LENG 40, WID 20, CRAD 6, PA 50, PO 30, STA 0, MID
    // 3, FAL 0, FALD 0, FFP1 400, FFD 100, CDIR 0, VARI 11 (roughing, vertical at G1), MIDA 4):
    // two levels (-3, -6); the centre path's outline is 20-5 = 15 by 10-5 = 5 about (50, 30).
    let text =
        format!("{POCKET_START}POCKET3(10,0,1,-6,40,20,6,50,30,0,3,0,0,400,100,0,11,4)\nM30\n");
    let got = moves(&run(&text, &pocket_machine()));
    let heights: Vec<f64> = got
        .iter()
        .filter(|m| m.0 == 'L' && (m.1[0] - 50.0).abs() < 1e-9 && (m.1[1] - 30.0).abs() < 1e-9)
        .map(|m| m.1[2])
        .collect();
    assert_eq!(heights, [-3.0, -6.0]);
    for m in &got[1..] {
        assert!(
            (m.1[0] - 50.0).abs() <= 15.0 + 1e-9 && (m.1[1] - 30.0).abs() <= 5.0 + 1e-9,
            "{m:?}"
        );
    }
    // The outline's corners are arcs of radius 6-5 = 1, cut counter-clockwise (climb with
    // M3): the last one ends at (50+15, 30-5+1).
    assert!(got
        .iter()
        .any(|m| m.0 == 'A' && (m.1[0] - 65.0).abs() < 1e-9 && (m.1[1] - 26.0).abs() < 1e-9));
    assert_eq!(got.last().map(|m| m.1[2]), Some(10.0));
}

#[test]
fn the_cycles_alarms_give_their_numbers() {
    let cases = [
        // The depth is above the reference plane, or the retraction plane below it.
        ("CYCLE81(10,0,2,5)", "cycle alarm 61101"),
        ("CYCLE81(-5,0,2,-10)", "cycle alarm 61101"),
        // No pitch, a size that is no thread, MPIT and PIT disagreeing.
        ("CYCLE84(10,0,2,-10,,0,3)", "cycle alarm 61001"),
        ("CYCLE84(10,0,2,-10,,0,3,7)", "cycle alarm 61001"),
        ("CYCLE84(10,0,2,-10,,0,3,8,1.5)", "cycle alarm 61001"),
        // No spindle direction: SDAC, SDIR, SDR.
        ("CYCLE84(10,0,2,-10,,0,0,8)", "cycle alarm 61102"),
        ("CYCLE86(10,0,2,-10,,0,0)", "cycle alarm 61102"),
        ("CYCLE87(10,0,2,-10,,6)", "cycle alarm 61102"),
        ("CYCLE840(10,0,2,-10,,0,0,3,1)", "cycle alarm 61102"),
        ("HOLES2(0,0,25,0,45,0)", "cycle alarm 61103"),
        ("CYCLE83(10,0,1,-20,,5)", "cycle alarm 61107"),
        (
            "POCKET4(2,0,1,-5,4,0,0,0,0,0,800,1300,0,11)",
            "cycle alarm 61105",
        ),
        (
            "POCKET4(2,0,1,-5,15,0,0,0,0,0,800,1300,0,15)",
            "cycle alarm 61002",
        ),
        (
            "POCKET4(2,0,1,-5,15,0,0,0,0,0,800,1300,0,21,5,,,0,0.5)",
            "cycle alarm 61108",
        ),
        (
            "POCKET4(2,0,1,-5,15,0,0,0,0,0,800,1300,7,11)",
            "cycle alarm 61109",
        ),
        (
            "POCKET4(2,0,1,-5,15,0,0,1,0,2,800,1300,0,11)",
            "cycle alarm 61110",
        ),
        (
            "POCKET4(2,0,1,-5,15,0,0,0,0,0,800,1300,0,11,12)",
            "cycle alarm 61111",
        ),
        (
            "POCKET3(2,0,1,-5,40,20,11,0,0,0,0,0,0,800,1300,0,11)",
            "cycle alarm 61113",
        ),
    ];
    for (call, number) in cases {
        let text = format!("{POCKET_START}{call}\nM30\n");
        assert_eq!(cycle_alarm(&text), number, "{call}");
    }
}

#[test]
fn a_pocket_needs_a_tool_edge_with_a_radius() {
    let pocket = "POCKET4(2,0,1,-5,15,0,0,0,0,0,800,1300,0,11)";
    // No D in force: 61000.
    let alarm = error(&format!("G0 X0 Y0 Z10\nF100\n{pocket}\nM30\n"), &machine());
    assert!(alarm.message.starts_with("cycle alarm 61000"), "{alarm:?}");
    // An edge of radius 0: 61117.
    let mut machine = machine();
    machine.tools.push(mill(1, "POINT", 1, 0.0, 0.0));
    let alarm = error(
        &format!("T1 M6 D1\nG0 X0 Y0 Z10\nF100\n{pocket}\nM30\n"),
        &machine,
    );
    assert!(alarm.message.starts_with("cycle alarm 61117"), "{alarm:?}");
}

#[test]
fn slot1_mills_its_slots_along_the_radius() {
    // SLOT1(RTP 10, RFP 0, SDIS 1, DP -4, -, NUM 2, LENG 30, WID 12, CPA 50, CPO 50, RAD 25, STA1
    // 0, INDA 180, FFD 100, FFP1 400, MID 0, CDIR 2, FAL 0, VARI 1): the slots' middles at
    // (75, 50) and (25, 50), along X. With the 10 mm mill the centre path stays within 15-5 =
    // 10 of the middle along the slot and 6-5 = 1 across it.
    let text =
        format!("{POCKET_START}SLOT1(10,0,1,-4,,2,30,12,50,50,25,0,180,100,400,0,2,0,1)\nM30\n");
    let got = moves(&run(&text, &pocket_machine()));
    let inside = |m: &Move, middle: f64| {
        (m.1[0] - middle).abs() <= 10.0 + 1e-9 && (m.1[1] - 50.0).abs() <= 1.0 + 1e-9
    };
    let cutting: Vec<_> = got.iter().filter(|m| m.1[2] < 0.0).collect();
    assert!(!cutting.is_empty());
    for m in &cutting {
        assert!(inside(m, 75.0) || inside(m, 25.0), "{m:?}");
    }
    // Both slots reach -4 and their round ends (75 ± 10, 25 ± 10).
    for x in [85.0, 65.0, 35.0, 15.0] {
        assert!(
            cutting
                .iter()
                .any(|m| (m.1[0] - x).abs() < 1e-9 && m.1[2] == -4.0),
            "{x}"
        );
    }
    assert_eq!(got.last().map(|m| m.1[2]), Some(10.0));
}

#[test]
fn slot2_as_wide_as_the_tool_goes_along_its_arc_and_back() {
    // SLOT2(RTP 10, RFP 0, SDIS 1, DP -3, -, NUM 1, AFSL 90, WID 10, CPA 0, CPO 0, RAD 30, STA1
    // 0, INDA 0, FFD 100, FFP1 400, MID 0, CDIR 3, FAL 0, VARI 1) with the 10 mm mill: in at
    // the start (30, 0), G3 to (0, 30), back to the start, up by SDIS, out to RTP.
    let text = format!("{POCKET_START}SLOT2(10,0,1,-3,,1,90,10,0,0,30,0,0,100,400,0,3,0,1)\nM30\n");
    // The first move is POCKET_START's G0 Z10.
    let got = moves(&run(&text, &pocket_machine()));
    assert_moves(
        &got[1..],
        &[
            ('R', [30.0, 0.0, 10.0]),
            ('R', [30.0, 0.0, 1.0]),
            ('L', [30.0, 0.0, -3.0]),
            ('A', [0.0, 30.0, -3.0]),
            ('A', [30.0, 0.0, -3.0]),
            ('R', [30.0, 0.0, -2.0]),
            ('R', [30.0, 0.0, 10.0]),
        ],
    );
}

#[test]
fn longhole_goes_in_at_either_end_in_turn() {
    // LONGHOLE(RTP 10, RFP 0, SDIS 1, DP -6, -, NUM 1, LENG 30, CPA 0, CPO 0, RAD 20, STA1 90,
    // INDA 0, FFD 100, FFP1 400, MID 3): the hole's middle at (0, 20), along Y; the 10 mm mill's
    // centre goes from Y10 to Y30. Levels -3 and -6, each in at one end and along to the other.
    let text = format!("{POCKET_START}LONGHOLE(10,0,1,-6,,1,30,0,0,20,90,0,100,400,3)\nM30\n");
    let got = moves(&run(&text, &pocket_machine()));
    assert_moves(
        &got[1..],
        &[
            ('R', [0.0, 10.0, 10.0]),
            ('R', [0.0, 10.0, 1.0]),
            ('L', [0.0, 10.0, -3.0]),
            ('L', [0.0, 30.0, -3.0]),
            ('L', [0.0, 30.0, -6.0]),
            ('L', [0.0, 10.0, -6.0]),
            ('R', [0.0, 10.0, 10.0]),
        ],
    );
}

#[test]
fn the_slots_alarms_give_their_numbers() {
    let cases = [
        // RAD 20: the inner ends 20-15 = 5 from the centre, 180 degrees apart: 10 < WID 12.
        (
            "SLOT1(10,0,1,-4,,2,30,12,50,50,20,0,180,100,400,0,2,0,1)",
            "cycle alarm 61104",
        ),
        // A slot 8 wide for a 10 mm mill.
        (
            "SLOT1(10,0,1,-4,,1,30,8,50,50,25,0,0,100,400,0,2,0,1)",
            "cycle alarm 61105",
        ),
        // Four slots 120 degrees apart do not fit on the circle.
        (
            "SLOT1(10,0,1,-4,,4,30,12,50,50,25,0,120,100,400,0,2,0,1)",
            "cycle alarm 61106",
        ),
        (
            "SLOT1(10,0,1,-4,,1,30,12,50,50,25,0,0,100,400,0,2,0,7)",
            "cycle alarm 61002",
        ),
        // Two slots of 175 degrees 180 apart: with their round ends (2 asin(5/30) = 19.2
        // degrees) they overlap.
        (
            "SLOT2(10,0,1,-3,,2,175,10,0,0,30,0,180,100,400,0,3,0,1)",
            "cycle alarm 61104",
        ),
        (
            "LONGHOLE(10,0,1,-6,,0,30,0,0,20,90,0,100,400,3)",
            "cycle alarm 61106",
        ),
    ];
    for (call, number) in cases {
        let text = format!("{POCKET_START}{call}\nM30\n");
        assert_eq!(cycle_alarm(&text), number, "{call}");
    }
}

#[test]
fn cycle61_faces_the_rectangle_in_rows_from_outside_it() {
    // CYCLE61(RTP 10, RFP 0, SDIS 2, DP -3, X0 0, Y0 0, X1 40, Y1 20, DZ 2, DXY 50, UZ 0.5, F
    // 1000, VARI 11) with the 10 mm mill: rows 50 % of 10 = 5 apart (Y 0, 5, 10, 15, 20), from
    // X 0-5-2 = -7 to 40+5 = 45; roughing down to -3+0.5 = -2.5 in two levels of 1.25.
    let text = format!("{POCKET_START}CYCLE61(10,0,2,-3,0,0,40,20,2,50,0.5,1000,11)\nM30\n");
    let got = moves(&run(&text, &pocket_machine()));
    let mut wanted = vec![('R', [-7.0, 0.0, 10.0]), ('R', [-7.0, 0.0, 2.0])];
    for (level, z) in [-1.25, -2.5].into_iter().enumerate() {
        if level > 0 {
            wanted.push(('R', [-7.0, 0.0, 2.0]));
        }
        wanted.push(('L', [-7.0, 0.0, z]));
        for k in 0..5 {
            let y = 5.0 * k as f64;
            let (from, to) = if k % 2 == 0 {
                (-7.0, 45.0)
            } else {
                (45.0, -7.0)
            };
            if k > 0 {
                wanted.push(('L', [from, y, z]));
            }
            wanted.push(('L', [to, y, z]));
        }
        wanted.push(('R', [45.0, 20.0, 2.0]));
    }
    wanted.push(('R', [45.0, 20.0, 10.0]));
    assert_moves(&got[1..], &wanted);
}

/// The moves of `text` with the subprograms of `library`.
pub(crate) fn moves_with(text: &str, programs: &[(&str, &str)], machine: &Machine) -> Vec<Move> {
    let mut library = MemoryLibrary::new();
    for (k, (name, program)) in programs.iter().enumerate() {
        library.insert_named(name, FileId(k as u32 + 1), program);
    }
    let front_end =
        Sinumerik::new(text.as_bytes(), FileId(0), machine).with_library(Box::new(library));
    let run = collect(Run::new(front_end, Kernel::new(machine)));
    assert!(run.error().is_none(), "{:?}", run.alarms);
    moves(&run.segments)
}

#[test]
fn a_pattern_runs_a_modal_subprogram_at_each_position_before_the_next() {
    // HOLES1(0,0,0,10,10,3): X10, X20, X30 on Y0; the shop's own cycle DRILL (a subprogram,
    // called modally) feeds to its depth and rapids back to Z5 at each, before the next
    // position. The second form ends at its text's end, without M17.
    let text = "G0 X0 Y0 Z5 F100\nMCALL DRILL(-4)\nHOLES1(0,0,0,10,10,3)\nMCALL\nG0 X0\nM30\n";
    for drill in [
        "PROC DRILL(REAL DEPTH)\nG1 Z=DEPTH\nG0 Z5\nM17\n",
        "PROC DRILL(REAL DEPTH)\nG1 Z=DEPTH\nG0 Z5\n",
    ] {
        let got = moves_with(text, &[("DRILL.SPF", drill)], &machine());
        let mut wanted = vec![('R', [0.0, 0.0, 5.0])];
        for x in [10.0, 20.0, 30.0] {
            wanted.extend([
                ('R', [x, 0.0, 5.0]),
                ('L', [x, 0.0, -4.0]),
                ('R', [x, 0.0, 5.0]),
            ]);
        }
        wanted.push(('R', [0.0, 0.0, 5.0]));
        assert_moves(&got, &wanted);
    }
}

#[test]
fn cycle77_mills_round_the_spigot_from_the_blank_in() {
    // CYCLE77(RTP 10, RFP 0, SDIS 1, DP -4, -, PRAD 40, PA 50, PO 50, MID 0, FAL 0, FALD 0, FFP1
    // 400, FFD 100, CDIR 0, VARI 1, AP1 60) with the 10 mm mill: the spigot of diameter 40
    // (radius 20) from a blank of diameter 60; rings at the tool radius 5 outside the spigot
    // plus 10, 5, 0 (the blank's 10 in steps of the tool radius): radii 35, 30, 25, clockwise
    // (climbing outside with M3). In at 20+15+5+1 = 41 from the centre, outside the blank.
    let text = format!("{POCKET_START}CYCLE77(10,0,1,-4,,40,50,50,0,0,0,400,100,0,1,60)\nM30\n");
    let got = moves(&run(&text, &pocket_machine()));
    let mut wanted = vec![
        ('R', [91.0, 50.0, 10.0]),
        ('R', [91.0, 50.0, 1.0]),
        ('L', [91.0, 50.0, -4.0]),
    ];
    for r in [35.0, 30.0, 25.0] {
        wanted.extend([
            ('L', [50.0 + r, 50.0, -4.0]),
            ('A', [50.0 - r, 50.0, -4.0]),
            ('A', [50.0 + r, 50.0, -4.0]),
        ]);
    }
    wanted.extend([
        ('R', [75.0, 50.0, -3.0]),
        ('R', [91.0, 50.0, -3.0]),
        ('R', [91.0, 50.0, 10.0]),
    ]);
    assert_moves(&got[1..], &wanted);
    let segments = run(&text, &pocket_machine());
    assert!(segments.iter().all(|s| !matches!(
        s.kind,
        SegmentKind::Arc {
            direction: vcnc::motion::ArcDirection::CounterClockwise,
            ..
        }
    )));
}

#[test]
fn cycle76_keeps_outside_the_rectangular_spigot() {
    // CYCLE76(RTP 10, RFP 0, SDIS 1, DP -6, -, LENG 40, WID 20, CRAD 5, PA 0, PO 0, STA 0, MID 3,
    // FAL 0.5, FALD 0, FFP1 400, FFD 100, CDIR 0, VARI 1, AP1 50, AP2 30): two levels (-3, -6);
    // the innermost ring is the spigot's outline plus the tool radius 5 and FAL 0.5: the tool
    // centre never comes within 5.5 of the 40 × 20 rectangle, and reaches it on the right side
    // (20 + 5.5 = 25.5).
    let text =
        format!("{POCKET_START}CYCLE76(10,0,1,-6,,40,20,5,0,0,0,3,0.5,0,400,100,0,1,50,30)\nM30\n");
    let got = moves(&run(&text, &pocket_machine()));
    for m in got.iter().filter(|m| m.1[2] < 0.0) {
        let dx = (m.1[0].abs() - 20.0).max(0.0);
        let dy = (m.1[1].abs() - 10.0).max(0.0);
        assert!(dx.hypot(dy) >= 5.5 - 1e-9, "{m:?}");
    }
    for z in [-3.0, -6.0] {
        assert!(got.iter().any(|m| m.1 == [25.5, 0.0, z]), "{z}");
    }
    assert_eq!(got.last().map(|m| m.1[2]), Some(10.0));
}

#[test]
fn cycle71_faces_in_rows_mida_apart_one_way_or_alternating() {
    // CYCLE71(RTP 10, RFP 0, SDIS 2, DP -2, PA 0, PO 0, LENG 30, WID 10, STA 0, MID 0, MIDA 4,
    // FDP 3, FALD 0, FFP1 600, VARI, FDP1 1) with the 10 mm mill: rows from X -3-5 = -8 to
    // 30+3+5 = 38; the first row's centre on Y0, the last one's edge 1 past Y10 (centre 6):
    // rows 0, 3, 6 (MIDA 4: two steps of 3). One level at -2.
    let wanted_start = [
        ('R', [-8.0, 0.0, 10.0]),
        ('R', [-8.0, 0.0, 2.0]),
        ('L', [-8.0, 0.0, -2.0]),
    ];
    let end = |x: f64| [('R', [x, 6.0, 2.0]), ('R', [x, 6.0, 10.0])];
    // VARI 31: alternating along X.
    let text = format!("{POCKET_START}CYCLE71(10,0,2,-2,0,0,30,10,0,0,4,3,0,600,31,1)\nM30\n");
    let got = moves(&run(&text, &pocket_machine()));
    let mut wanted = wanted_start.to_vec();
    wanted.extend([
        ('L', [38.0, 0.0, -2.0]),
        ('L', [38.0, 3.0, -2.0]),
        ('L', [-8.0, 3.0, -2.0]),
        ('L', [-8.0, 6.0, -2.0]),
        ('L', [38.0, 6.0, -2.0]),
    ]);
    wanted.extend(end(38.0));
    assert_moves(&got[1..], &wanted);
    // VARI 11: one direction, back over the face at the safety plane.
    let text = format!("{POCKET_START}CYCLE71(10,0,2,-2,0,0,30,10,0,0,4,3,0,600,11,1)\nM30\n");
    let got = moves(&run(&text, &pocket_machine()));
    let mut wanted = wanted_start.to_vec();
    wanted.push(('L', [38.0, 0.0, -2.0]));
    for y in [3.0, 6.0] {
        wanted.extend([
            ('R', [38.0, y - 3.0, 2.0]),
            ('R', [-8.0, y, 2.0]),
            ('L', [-8.0, y, -2.0]),
            ('L', [38.0, y, -2.0]),
        ]);
    }
    wanted.extend(end(38.0));
    assert_moves(&got[1..], &wanted);
    // MIDA 0 and MIDA above the diameter.
    for (call, number) in [
        (
            "CYCLE71(10,0,2,-2,0,0,30,10,0,0,0,3,0,600,31,1)",
            "cycle alarm 61124",
        ),
        (
            "CYCLE71(10,0,2,-2,0,0,30,10,0,0,12,3,0,600,31,1)",
            "cycle alarm 61111",
        ),
        (
            "CYCLE71(10,0,2,-2,0,0,0,10,0,0,4,3,0,600,31,1)",
            "cycle alarm 61118",
        ),
    ] {
        assert_eq!(
            cycle_alarm(&format!("{POCKET_START}{call}\nM30\n")),
            number,
            "{call}"
        );
    }
}

/// The spindle, dwell and stop events of `segments` in order, as text.
fn events(segments: &[Segment]) -> Vec<String> {
    segments
        .iter()
        .filter_map(|s| match s.kind {
            SegmentKind::Spindle { speed, state } => Some(format!("S{speed} {state:?}")),
            SegmentKind::Dwell { seconds } => Some(format!("dwell {seconds}")),
            SegmentKind::Stop { kind } => Some(format!("stop {kind:?}")),
            _ => None,
        })
        .collect()
}

#[test]
fn cycle87_and_cycle88_stop_the_spindle_and_the_program_at_the_depth() {
    // CYCLE87(RTP 10, RFP 0, SDIS 2, DP -10, -, SDIR 3): M3 already turns; in at the feed, M5,
    // M0, out in rapid to RTP with the spindle stopped.
    let segments = run(&format!("{START}CYCLE87(10,0,2,-10,,3)\nM30\n"), &machine());
    assert_moves(
        &moves(&segments)[1..],
        &[
            ('R', [10.0, 20.0, 2.0]),
            ('L', [10.0, 20.0, -10.0]),
            ('R', [10.0, 20.0, 10.0]),
        ],
    );
    assert_eq!(events(&segments)[1..], ["S1000 Stopped", "stop Program"]);
    // CYCLE88(..., DTB 1, SDIR 4): the spindle turns M4 first, dwells 1 s at the depth.
    let segments = run(
        &format!("{START}CYCLE88(10,0,2,-10,,1,4)\nM30\n"),
        &machine(),
    );
    assert_eq!(
        events(&segments)[1..],
        [
            "S1000 CounterClockwise",
            "dwell 1",
            "S1000 Stopped",
            "stop Program"
        ]
    );
}

#[test]
fn cycle840_taps_with_the_feed_without_an_encoder_and_with_the_pitch_with_one() {
    // CYCLE840(RTP 10, RFP 0, SDIS 2, DP -10, -, DTB 0, SDR 4, SDAC 3, ENC 1): in and out as
    // lines at F100 (G63), the spindle turning M4 for the way out, M3 again after.
    let segments = run(
        &format!("{START}CYCLE840(10,0,2,-10,,0,4,3,1)\nM30\n"),
        &machine(),
    );
    assert_moves(
        &moves(&segments)[1..],
        &[
            ('R', [10.0, 20.0, 2.0]),
            ('L', [10.0, 20.0, -10.0]),
            ('L', [10.0, 20.0, 2.0]),
            ('R', [10.0, 20.0, 10.0]),
        ],
    );
    assert_eq!(
        events(&segments)[1..],
        ["S1000 CounterClockwise", "S1000 Clockwise"]
    );
    // With an encoder (ENC 0) and MPIT 10 (M10, pitch 1.5): threads; SDR 0 reverses the
    // spindle.
    let segments = run(
        &format!("{START}CYCLE840(10,0,2,-10,,0,0,3,0,10)\nM30\n"),
        &machine(),
    );
    assert_moves(
        &moves(&segments)[1..],
        &[
            ('R', [10.0, 20.0, 2.0]),
            ('T', [10.0, 20.0, -10.0]),
            ('T', [10.0, 20.0, 2.0]),
            ('R', [10.0, 20.0, 10.0]),
        ],
    );
}

#[test]
fn cycle802_visits_its_listed_positions() {
    // (10, 20); (30, Y left out: 20); (X left out: 30, 40); the rest left out: no position.
    let got = moves_after("G0 X0 Y0 Z5\nCYCLE802(1,1,10,20,30,,,40)\nM30\n", 1);
    assert_moves(
        &got,
        &[
            ('R', [10.0, 20.0, 5.0]),
            ('R', [30.0, 20.0, 5.0]),
            ('R', [30.0, 40.0, 5.0]),
        ],
    );
}

#[test]
fn pocket4_finishing_goes_round_the_outline_at_every_level() {
    // POCKET4(RTP 2, RFP 0, SDIS 1, DP -6, PRAD 15, PA 0, PO 0, MID 3, FAL 0, FALD 0, FFP1 800,
    // FFD 300, CDIR 2, VARI 12): finishing, G2; at -3 and -6 in vertically at the centre, out to
    // the outline's radius 15-5 = 10, round it in two halves, up by SDIS, back over the centre.
    // The tool stands over the centre at Z10, above RTP: it goes straight down to RFP+SDIS.
    let text = format!("{POCKET_START}POCKET4(2,0,1,-6,15,0,0,3,0,0,800,300,2,12)\nM30\n");
    let got = moves(&run(&text, &pocket_machine()));
    let mut wanted = vec![('R', [0.0, 0.0, 1.0])];
    for z in [-3.0, -6.0] {
        wanted.extend([
            ('L', [0.0, 0.0, z]),
            ('L', [10.0, 0.0, z]),
            ('A', [-10.0, 0.0, z]),
            ('A', [10.0, 0.0, z]),
            ('R', [10.0, 0.0, z + 1.0]),
            ('R', [0.0, 0.0, z + 1.0]),
        ]);
    }
    wanted.push(('R', [0.0, 0.0, 2.0]));
    assert_moves(&got[1..], &wanted);
}

#[test]
fn steps_written_far_too_small_neither_hang_nor_run_away() {
    // MID 0.000001 on a 5 mm deep pocket would be 5 million levels: vcnc makes 10000 at most.
    let text = format!("{POCKET_START}POCKET4(2,0,1,-5,15,0,0,0.000001,0,0,800,1300,0,11)\nM30\n");
    let got = moves(&run(&text, &pocket_machine()));
    let levels = got
        .iter()
        .filter(|m| m.0 == 'L' && m.1[0] == 0.0 && m.1[1] == 0.0)
        .count();
    assert_eq!(levels, 10_000);
    // A first peck a millionth of a millimetre deep: at most 10000 pecks.
    let text = format!("{START}CYCLE83(10,0,1,-20,,-0.000001,,0,0,0,1,0)\nM30\n");
    assert!(moves(&run(&text, &machine())).len() <= 2 * 10_001 + 3);
    // A billion holes alarm.
    let alarm = error(
        &format!("{START}HOLES2(0,0,25,0,0,1000000000)\nM30\n"),
        &machine(),
    );
    assert_eq!(alarm.code, AlarmCode::ValueOutOfRange, "{alarm:?}");
}

#[test]
fn the_planes_are_absolute_under_g91_and_inches_under_g70() {
    // G91: the positioning blocks move 10 at a time (X20, X30); the cycle's planes stay
    // absolute: Z2, Z-5, Z10 at each hole.
    let text = "G17 G90 F100 S1000 M3\nG0 X10 Y20 Z50\nG91\nMCALL CYCLE81(10,0,2,-5)\nX10\nX10\nMCALL\nM30\n";
    let got = moves_after(text, 1);
    let hole = |x: f64, above: f64| {
        [
            ('R', [x, 20.0, above]),
            ('R', [x, 20.0, 2.0]),
            ('L', [x, 20.0, -5.0]),
            ('R', [x, 20.0, 10.0]),
        ]
    };
    let mut wanted = hole(20.0, 50.0).to_vec();
    wanted.extend(hole(30.0, 10.0));
    assert_moves(&got, &wanted);
    // G70: RTP 1, SDIS 0.1, DP -0.5 inch: 25.4, 2.54, -12.7 mm.
    let got = moves_after(&format!("{START}G70 CYCLE81(1,0,0.1,-0.5)\nM30\n"), 1);
    assert_moves(
        &got,
        &[
            ('R', [10.0, 20.0, 2.54]),
            ('L', [10.0, 20.0, -12.7]),
            ('R', [10.0, 20.0, 25.4]),
        ],
    );
}

#[test]
fn under_g18_the_cycle_drills_along_y() {
    // G18: the plane is Z X, the tool axis Y.
    let got = moves_after("G18 G90 F100\nG0 X10 Z20 Y50\nCYCLE81(10,0,2,-5)\nM30\n", 1);
    assert_moves(
        &got,
        &[
            ('R', [10.0, 2.0, 20.0]),
            ('L', [10.0, -5.0, 20.0]),
            ('R', [10.0, 10.0, 20.0]),
        ],
    );
}

/// Every built-in cycle called with arbitrary parameters (left out, zero, negative, tiny, huge)
/// ends with its moves or an alarm: never a panic or a hang. A fixed linear congruential
/// sequence picks them, so the test is the same on every run.
#[test]
fn arbitrary_parameters_end_in_moves_or_an_alarm() {
    const CYCLES: [&str; 24] = [
        "CYCLE81", "CYCLE82", "CYCLE83", "CYCLE84", "CYCLE840", "CYCLE85", "CYCLE86", "CYCLE87",
        "CYCLE88", "CYCLE89", "HOLES1", "HOLES2", "CYCLE801", "CYCLE802", "POCKET3", "POCKET4",
        "SLOT1", "SLOT2", "LONGHOLE", "CYCLE61", "CYCLE71", "CYCLE76", "CYCLE77", "CYCLE79",
    ];
    const VALUES: [&str; 12] = [
        "", "0", "1", "-1", "2", "-5", "10", "25", "0.001", "1000000", "-0.5", "3",
    ];
    let mut state: u64 = 22;
    let mut next = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 33) as usize
    };
    let machine = pocket_machine();
    for round in 0..40 {
        for cycle in CYCLES {
            let count = 4 + next() % 20;
            let args: Vec<&str> = (0..count).map(|_| VALUES[next() % VALUES.len()]).collect();
            let text = format!("{POCKET_START}{cycle}({})\nM30\n", args.join(","));
            let run = collect(run_str(&text, &machine));
            if let Some(alarm) = run.error() {
                assert!(alarm.span.is_some(), "round {round}: {text}\n{alarm:?}");
            }
        }
    }
}

#[test]
fn a_cycle_called_under_g41_or_g42_is_an_alarm_at_its_call() {
    // Found by the fuzz target: G41 starting in the block of a position pattern fed the pattern's
    // moves to a compensator still waiting for its first element. The cycles move the tool's
    // centre, and vcnc runs them with G40.
    let mut machine = machine();
    machine.tools.push(mill(1, "MILL", 1, 0.0, 5.0));
    for text in [
        "T1 D1 M6\nOFFN=20 G41 HOLES2(,,5,,,6)\nM30\n",
        "T1 D1 M6\nG17 G90 F100 S1000 M3\nG0 X0 Y0 Z10\nG41 G1 X10 Y10\nCYCLE81(10,0,2,-5)\nM30\n",
        "T1 D1 M6\nG17 G90 F100 S1000 M3\nG0 X0 Y0 Z10\nG42 G1 X10 Y10\nMCALL CYCLE81(10,0,2,-5)\nX20\nM30\n",
    ] {
        let alarm = error(text, &machine);
        assert_eq!(alarm.code, AlarmCode::CutterCompensation, "{text}: {alarm:?}");
        assert!(alarm.message.contains("G41 or G42"), "{alarm:?}");
    }
    // After G40 the same cycle runs.
    let text = "T1 D1 M6\nG17 G90 F100 S1000 M3\nG0 X0 Y0 Z10\nG41 G1 X10 Y10\nG40 G1 X0 Y0\nCYCLE81(10,0,2,-5)\nM30\n";
    assert!(collect(run_str(text, &machine)).error().is_none());
}

#[test]
fn cycle832_alarms_for_its_machining_type_and_tolerance() {
    // _TOLM's units digit is 0 to 3 (deselect, finishing, semi-finishing, roughing): 4 is the
    // cycles' 61002, a fraction too.
    assert_eq!(
        cycle_alarm(&format!("{START}CYCLE832(0.05,4,1)\nM30\n")),
        "cycle alarm 61002"
    );
    assert_eq!(
        cycle_alarm(&format!("{START}CYCLE832(0.05,1.5,1)\nM30\n")),
        "cycle alarm 61002"
    );
    // A tolerance beyond what the path smoothing takes (32.767 mm) is out of range.
    let alarm = error(&format!("{START}CYCLE832(40,1,1)\nM30\n"), &machine());
    assert_eq!(alarm.code, AlarmCode::ValueOutOfRange, "{alarm:?}");
    // Within range, and deselected, it runs.
    for text in ["CYCLE832(0.05,3,1)", "CYCLE832(0.05,0,1)", "CYCLE832()"] {
        let text = format!("{START}{text}\nG1 X20\nM30\n");
        assert!(
            collect(run_str(&text, &machine())).error().is_none(),
            "{text}"
        );
    }
}
