//! SINUMERIK's contour cycles (docs/SINUMERIK.md, Standard cycles): CYCLE79, the multi-edge
//! spigot, and CYCLE72, path milling along a contour given by name, with their alarms.
//!
//! Every expected position is worked out by hand from the parameter meanings the docs give. The
//! machine is the default one with a 10 mm end mill (T1 D1, radius 5), no work offset and no
//! tool length, so program and machine coordinates are the same; the spindle turns M3.

use vcnc::AlarmCode;

use crate::common::sinumerik::machine;
use crate::sinumerik_cycles::{
    assert_moves, cycle_alarm, error, moves, moves_with, pocket_machine, run, Move, POCKET_START,
};

/// The moves of `text` on the pocket machine after the positioning before the cycle.
fn cycle_moves(text: &str) -> Vec<Move> {
    moves(&run(text, &pocket_machine()))[1..].to_vec()
}

/// sqrt(3), for the hexagon's corners.
const ROOT3: f64 = 1.732_050_807_568_877_2;

#[test]
fn cycle79_goes_round_a_hexagon_once_at_the_tool_radius() {
    // CYCLE79(RTP 10, RFP 0, SDIS 1, DP -4, -, NUM 6, SWL 40, CRAD 0, PA 0, PO 0, STA 0, MID 0,
    // FAL 0, FALD 0, FFP1 400, FFD 100, CDIR 0, VARI 1, AP1 0): a hexagon 40 across flats, its
    // first flat facing +X at X20. Its corners are 20/cos 30 = 40/sqrt3 from the centre at
    // -30, 30, 90 ... degrees: (20, -20/sqrt3), (20, 20/sqrt3), (0, 40/sqrt3) ... No blank
    // beyond the hexagon: one ring at the tool radius 5, one level at Z-4. In at 20+5+5+1 = 31
    // on the X axis (the ring, the tool's radius and SDIS outside the flat), down at FFD, in to
    // the flat's middle at X25, then clockwise (climbing outside with M3): along each flat 5
    // out, round each corner on an arc of radius 5 to the next flat's normal (the normals at
    // 0, -60, -120 ... degrees, 5 along them: (2.5, -5 sqrt3 / 2) at -60).
    let text = format!("{POCKET_START}CYCLE79(10,0,1,-4,,6,40,0,0,0,0,0,0,0,400,100,0,1,0)\nM30\n");
    let got = cycle_moves(&text);
    let (c, h) = (20.0 / ROOT3, 40.0 / ROOT3);
    let (dx, dy) = (2.5, 2.5 * ROOT3);
    let z = -4.0;
    let wanted = [
        ('R', [31.0, 0.0, 10.0]),
        ('R', [31.0, 0.0, 1.0]),
        ('L', [31.0, 0.0, z]),
        ('L', [25.0, 0.0, z]),
        ('L', [25.0, -c, z]),
        ('A', [20.0 + dx, -c - dy, z]),
        ('L', [dx, -h - dy, z]),
        ('A', [-dx, -h - dy, z]),
        ('L', [-20.0 - dx, -c - dy, z]),
        ('A', [-25.0, -c, z]),
        ('L', [-25.0, c, z]),
        ('A', [-20.0 - dx, c + dy, z]),
        ('L', [-dx, h + dy, z]),
        ('A', [dx, h + dy, z]),
        ('L', [20.0 + dx, c + dy, z]),
        ('A', [25.0, c, z]),
        ('L', [25.0, 0.0, z]),
        // Up by SDIS, out to the way in, up to RTP.
        ('R', [25.0, 0.0, -3.0]),
        ('R', [31.0, 0.0, -3.0]),
        ('R', [31.0, 0.0, 10.0]),
    ];
    assert_moves(&got, &wanted);
}

/// The distance from `p` to a square of half side `a` with corners of radius `corner`, centred
/// at the origin and axis-parallel (negative inside).
fn square_distance(p: (f64, f64), a: f64, corner: f64) -> f64 {
    let core = a - corner;
    let (dx, dy) = ((p.0.abs() - core).max(0.0), (p.1.abs() - core).max(0.0));
    dx.hypot(dy) - corner
}

#[test]
fn cycle79_clears_a_turned_square_from_its_blank_in_levels() {
    // CYCLE79(RTP 10, RFP 0, SDIS 1, DP -6, -, NUM 4, SWL -30 (an edge 30 long: 30 across
    // flats), CRAD 5, PA 50, PO 50, STA 45, MID 3, FAL 0, FALD 0, FFP1 400, FFD 100, CDIR 0,
    // VARI 1, AP1 50): a square 30 × 30 with corners of radius 5, turned 45 degrees about
    // (50, 50), from a round blank of radius 25. The blank passes 25-15 = 10 beyond the flats'
    // middles: rings 15, 10, 5 outside the square (the tool radius 5 apart). Levels -3, -6.
    // The way in is 15+15+5+1 = 36 from the centre along 45 degrees.
    let text =
        format!("{POCKET_START}CYCLE79(10,0,1,-6,,4,-30,5,50,50,45,3,0,0,400,100,0,1,50)\nM30\n");
    let got = cycle_moves(&text);
    let diagonal = |d: f64| 50.0 + d / 2f64.sqrt();
    assert_eq!(got[0], ('R', [diagonal(36.0), diagonal(36.0), 10.0]));
    // Back in the square's own frame: turned back by 45 degrees about (50, 50).
    let local = |m: &Move| {
        let (x, y) = (m.1[0] - 50.0, m.1[1] - 50.0);
        let s = 0.5f64.sqrt();
        (x * s + y * s, -x * s + y * s)
    };
    let below: Vec<_> = got.iter().filter(|m| m.1[2] < 0.0).collect();
    for m in &below {
        // The tool's centre never comes nearer the square than its radius.
        assert!(square_distance(local(m), 15.0, 5.0) >= 5.0 - 1e-9, "{m:?}");
    }
    for z in [-3.0, -6.0] {
        // Each ring starts at the middle of the first flat, 20, 25 and 30 out along 45 degrees.
        for out in [20.0, 25.0, 30.0] {
            let start = [diagonal(out), diagonal(out), z];
            assert!(
                got.iter()
                    .any(|m| m.0 == 'L' && (0..3).all(|i| (m.1[i] - start[i]).abs() < 1e-9)),
                "no ring start {start:?}"
            );
        }
    }
    // The innermost ring runs at exactly the tool radius from the square: its arcs about the
    // corners' centres have the radius 5+5.
    let innermost: Vec<_> = below
        .iter()
        .filter(|m| m.0 == 'A' && (square_distance(local(m), 15.0, 5.0) - 5.0).abs() < 1e-9)
        .collect();
    assert_eq!(innermost.len(), 2 * 4, "{innermost:?}");
    assert_eq!(got.last().map(|m| m.1[2]), Some(10.0));
}

#[test]
fn cycle79_finishes_two_key_flats_on_the_blank() {
    // CYCLE79(RTP 10, RFP 0, SDIS 1, DP -2, -, NUM 2, SWL 30, CRAD 0, PA 0, PO 0, STA 0, MID 0,
    // FAL 0, FALD 0, FFP1 400, FFD 100, CDIR 2 (G2), VARI 2 (finishing), AP1 40): flats at X±15
    // on a blank of radius 20, meeting it at Y ±sqrt(400 - 225) = ±sqrt 175. Finishing: one
    // ring at the tool radius 5. In at 15+5+5+1 = 26. Clockwise from (20, 0): down the flat to
    // (20, -sqrt175), round the corner (15, -sqrt175) to 5 beyond it from the centre: the
    // corner times 25/20 = (18.75, -1.25 sqrt175); along the blank at radius 25 to
    // (-18.75, -1.25 sqrt175), round the corner to (-20, -sqrt175), up the other flat, and so
    // back.
    let text =
        format!("{POCKET_START}CYCLE79(10,0,1,-2,,2,30,0,0,0,0,0,0,0,400,100,2,2,40)\nM30\n");
    let got = cycle_moves(&text);
    let h = 175f64.sqrt();
    let z = -2.0;
    let wanted = [
        ('R', [26.0, 0.0, 10.0]),
        ('R', [26.0, 0.0, 1.0]),
        ('L', [26.0, 0.0, z]),
        ('L', [20.0, 0.0, z]),
        ('L', [20.0, -h, z]),
        ('A', [18.75, -1.25 * h, z]),
        ('A', [-18.75, -1.25 * h, z]),
        ('A', [-20.0, -h, z]),
        ('L', [-20.0, h, z]),
        ('A', [-18.75, 1.25 * h, z]),
        ('A', [18.75, 1.25 * h, z]),
        ('A', [20.0, h, z]),
        ('L', [20.0, 0.0, z]),
        ('R', [20.0, 0.0, -1.0]),
        ('R', [26.0, 0.0, -1.0]),
        ('R', [26.0, 0.0, 10.0]),
    ];
    assert_moves(&got, &wanted);
}

#[test]
fn cycle79_alarms_give_their_numbers() {
    let cases = [
        // A depth above the reference plane.
        (
            "CYCLE79(10,0,1,4,,6,40,0,0,0,0,0,0,0,400,100,0,1)",
            "cycle alarm 61101",
        ),
        // VARI 3 and CDIR 7.
        (
            "CYCLE79(10,0,1,-4,,6,40,0,0,0,0,0,0,0,400,100,0,3)",
            "cycle alarm 61002",
        ),
        (
            "CYCLE79(10,0,1,-4,,6,40,0,0,0,0,0,0,0,400,100,7,1)",
            "cycle alarm 61109",
        ),
        // A hexagon 40 across flats has edges 40/sqrt3 = 23.1 long: a corner radius above the
        // apothem 20, or a chamfer above half an edge (11.5), takes more than the edges have.
        (
            "CYCLE79(10,0,1,-4,,6,40,21,0,0,0,0,0,0,400,100,0,1)",
            "cycle alarm 61113",
        ),
        (
            "CYCLE79(10,0,1,-4,,6,40,-12,0,0,0,0,0,0,400,100,0,1)",
            "cycle alarm 61113",
        ),
    ];
    for (call, number) in cases {
        let text = format!("{POCKET_START}{call}\nM30\n");
        assert_eq!(cycle_alarm(&text), number, "{call}");
    }
    // No edges, no size, key flats without a blank or wider than it: values out of range
    // (V007; the control's own numbers for them are not known).
    for call in [
        "CYCLE79(10,0,1,-4,,0,40,0,0,0,0,0,0,0,400,100,0,1)",
        "CYCLE79(10,0,1,-4,,6,0,0,0,0,0,0,0,0,400,100,0,1)",
        "CYCLE79(10,0,1,-4,,2,30,0,0,0,0,0,0,0,400,100,0,1)",
        "CYCLE79(10,0,1,-4,,2,50,0,0,0,0,0,0,0,400,100,0,1,40)",
    ] {
        let alarm = error(&format!("{POCKET_START}{call}\nM30\n"), &pocket_machine());
        assert_eq!(alarm.code, AlarmCode::ValueOutOfRange, "{call}: {alarm:?}");
        assert!(alarm.span.is_some_and(|s| s.end > s.start), "{alarm:?}");
    }
    // Without a tool edge in force: 61000.
    let alarm = error(
        "G0 X0 Y0 Z10\nF100\nCYCLE79(10,0,1,-4,,6,40,0,0,0,0,0,0,0,400,100,0,1)\nM30\n",
        &machine(),
    );
    assert!(alarm.message.starts_with("cycle alarm 61000"), "{alarm:?}");
}

/// A square 40 × 40 from (0, 0) to (40, 40), clockwise from the middle of its bottom side,
/// between the labels C1 and C1E after the program's end.
const SQUARE: &str = "C1: G1 X20 Y0\nX0\nY40\nX40\nY0\nC1E: X20\n";

/// The tool centre's way round [`SQUARE`] at `z`, 5 (the tool radius) left of it, outside,
/// from (20, -5): along each side, round each corner clockwise on the transition circle of
/// radius 5 about it (G450), from one side's normal to the next one's.
fn square_outside(z: f64) -> [Move; 9] {
    [
        ('L', [0.0, -5.0, z]),
        ('A', [-5.0, 0.0, z]),
        ('L', [-5.0, 40.0, z]),
        ('A', [0.0, 45.0, z]),
        ('L', [40.0, 45.0, z]),
        ('A', [45.0, 40.0, z]),
        ('L', [45.0, 0.0, z]),
        ('A', [40.0, -5.0, z]),
        ('L', [20.0, -5.0, z]),
    ]
}

#[test]
fn cycle72_goes_round_a_square_left_of_it_with_a_straight_approach() {
    // CYCLE72(KNAME "C1:C1E", RTP 10, RFP 0, SDIS 1, DP -5, MID 0, FAL 0, FALD 0, FFP1 400,
    // FFD 100, VARI 1 (roughing, rapid between levels, up to RTP), RL 41, AS1 1 (straight,
    // tangential, in the plane), LP1 10, FF3 300, AS2 1, LP2 10). Going clockwise round the
    // square, left of it is outside: the tool centre 5 (the radius) outside each side, round
    // each corner on the transition circle of radius 5 about it (G450). It starts at (20, -5)
    // going -X: the way in starts 10 behind it at (30, -5), the way out ends 10 beyond the
    // end (20, -5) at (10, -5). One level at Z-5.
    let text = format!(
        "{POCKET_START}CYCLE72(\"C1:C1E\",10,0,1,-5,0,0,0,400,100,1,41,1,10,300,1,10)\nM30\n{SQUARE}"
    );
    let segments = run(&text, &pocket_machine());
    let got = moves(&segments)[1..].to_vec();
    let z = -5.0;
    let wanted = [
        ('R', [30.0, -5.0, 10.0]),
        ('R', [30.0, -5.0, 1.0]),
        ('L', [30.0, -5.0, z]),
        ('L', [20.0, -5.0, z]),
    ]
    .into_iter()
    .chain(square_outside(z))
    .chain([('L', [10.0, -5.0, z]), ('R', [10.0, -5.0, 10.0])])
    .collect::<Vec<_>>();
    assert_moves(&got, &wanted);
    // Down at FFD, the way in and the contour's five lines at FFP1, out at FF3.
    assert_eq!(
        crate::sinumerik_cycles::line_feeds(&segments),
        [100.0, 400.0, 400.0, 400.0, 400.0, 400.0, 400.0, 300.0]
    );
    // The corners are arcs clockwise about the square's corners.
    assert!(segments.iter().all(|s| !matches!(
        s.kind,
        vcnc::SegmentKind::Arc {
            direction: vcnc::motion::ArcDirection::CounterClockwise,
            ..
        }
    )));
}

#[test]
fn cycle72_on_the_contour_follows_the_programmed_points() {
    // The same square with RL 40: the tool centre on the contour, no corner arcs; the way in
    // 10 behind (20, 0) along the first side's direction -X, at (30, 0); out to (10, 0).
    let text = format!(
        "{POCKET_START}CYCLE72(\"C1:C1E\",10,0,1,-5,0,0,0,400,100,1,40,1,10,300,1,10)\nM30\n{SQUARE}"
    );
    let got = cycle_moves(&text);
    let z = -5.0;
    let wanted = [
        ('R', [30.0, 0.0, 10.0]),
        ('R', [30.0, 0.0, 1.0]),
        ('L', [30.0, 0.0, z]),
        ('L', [20.0, 0.0, z]),
        ('L', [0.0, 0.0, z]),
        ('L', [0.0, 40.0, z]),
        ('L', [40.0, 40.0, z]),
        ('L', [40.0, 0.0, z]),
        ('L', [20.0, 0.0, z]),
        ('L', [10.0, 0.0, z]),
        ('R', [10.0, 0.0, 10.0]),
    ];
    assert_moves(&got, &wanted);
}

/// An open contour in a subprogram: along X from (0, 0) to (30, 0), a quarter circle G3 of
/// radius 10 about (30, 10) up to (40, 10), and up to (40, 30).
const KONTUR: &str = "PROC KONTUR\nG1 X0 Y0\nX30\nG3 X40 Y10 CR=10\nG1 Y30\nM17\n";

#[test]
fn cycle72_mills_a_subprograms_contour_right_of_it_in_levels_with_circles_in_and_out() {
    // CYCLE72(KNAME "KONTUR", RTP 10, RFP 0, SDIS 1, DP -5, MID 2.5, FAL 0.5, FALD 0, FFP1 400,
    // FFD 100, VARI 101 (roughing, rapid between levels, up to RFP+SDIS at the contour's end),
    // RL 42, AS1 2 (quarter circle) LP1 5, FF3 300, AS2 3 (semicircle) LP2 5). Right of the
    // contour at 5 + 0.5: the line at Y-5.5 from X0 to X30, the arc about (30, 10) of radius
    // 15.5 to (45.5, 10), the line at X45.5 up to Y30. The way in: the right normal of +X is
    // -Y, the circle's centre 5 below the start (0, -5.5) at (0, -10.5), the way in starts a
    // quarter before, at (-5, -10.5), clockwise. The way out: the right normal of +Y is +X,
    // the centre (50.5, 30), the semicircle ends at (55.5, 30), clockwise. Levels -2.5, -5;
    // between them up to RFP+SDIS 1, over to the way in, down to 1 above the cut level.
    let text = format!(
        "{POCKET_START}CYCLE72(\"KONTUR\",10,0,1,-5,2.5,0.5,0,400,100,101,42,2,5,300,3,5)\nM30\n"
    );
    let got = moves_with(&text, &[("KONTUR.SPF", KONTUR)], &pocket_machine())[1..].to_vec();
    let mut wanted = vec![('R', [-5.0, -10.5, 10.0]), ('R', [-5.0, -10.5, 1.0])];
    for z in [-2.5, -5.0] {
        if z < -2.5 {
            wanted.extend([('R', [-5.0, -10.5, 1.0]), ('R', [-5.0, -10.5, -1.5])]);
        }
        wanted.extend([
            ('L', [-5.0, -10.5, z]),
            ('A', [0.0, -5.5, z]),
            ('L', [30.0, -5.5, z]),
            ('A', [45.5, 10.0, z]),
            ('L', [45.5, 30.0, z]),
            ('A', [55.5, 30.0, z]),
            ('R', [55.5, 30.0, 1.0]),
        ]);
    }
    wanted.push(('R', [55.5, 30.0, 10.0]));
    assert_moves(&got, &wanted);
}

#[test]
fn cycle72_in_space_goes_down_along_a_normal_way_in_and_back_at_ff3() {
    // The square with RL 41, VARI 212 (finishing: no allowance FAL; FF3 between levels; up by
    // SDIS at the contour's end), MID 2, DP -4 (levels -2, -4), AS1 14 (along the normal, in
    // space) LP1 8, AS2 11 (straight and tangential, in space) with LP2 left out (LP1's 8).
    // Left of -X is -Y: the way in starts 8 below the start (20, -5), at (20, -13), and goes
    // down with the move, from the safety plane 1 to the level; the way out goes from the end
    // (20, -5) 8 on along -X and up by SDIS, to (12, -5); that is SDIS above the level, so no
    // lift; then at FF3 back to the way in, and down along it to the next level.
    let text = format!(
        "{POCKET_START}CYCLE72(\"C1:C1E\",10,0,1,-4,2,0.5,0,400,100,212,41,14,8,300,11)\nM30\n{SQUARE}"
    );
    let segments = run(&text, &pocket_machine());
    let got = moves(&segments)[1..].to_vec();
    let mut wanted = vec![('R', [20.0, -13.0, 10.0]), ('R', [20.0, -13.0, 1.0])];
    for z in [-2.0, -4.0] {
        if z < -2.0 {
            wanted.push(('L', [20.0, -13.0, -1.0]));
        }
        // Down along the way in; round; out along the way out.
        wanted.push(('L', [20.0, -5.0, z]));
        wanted.extend(square_outside(z));
        wanted.push(('L', [12.0, -5.0, z + 1.0]));
    }
    wanted.push(('R', [12.0, -5.0, 10.0]));
    assert_moves(&got, &wanted);
    // Per level: in at FFD, five lines at FFP1, out at FF3; between the levels FF3.
    let level = [100.0, 400.0, 400.0, 400.0, 400.0, 400.0, 300.0];
    let feeds = [&level[..], &[300.0], &level[..]].concat();
    assert_eq!(crate::sinumerik_cycles::line_feeds(&segments), feeds);
}

#[test]
fn cycle72_alarms_give_their_numbers() {
    let cycle =
        |parameters: &str| format!("{POCKET_START}CYCLE72(\"C1:C1E\",{parameters})\nM30\n{SQUARE}");
    let cases = [
        // The depth above the reference plane, RTP below it.
        ("10,0,1,5,0,0,0,400,100,1,41,1,10", "cycle alarm 61101"),
        ("-10,0,1,-5,0,0,0,400,100,1,41,1,10", "cycle alarm 61101"),
        // VARI: units 3, tens 2, hundreds 4.
        ("10,0,1,-5,0,0,0,400,100,3,41,1,10", "cycle alarm 61002"),
        ("10,0,1,-5,0,0,0,400,100,21,41,1,10", "cycle alarm 61002"),
        ("10,0,1,-5,0,0,0,400,100,401,41,1,10", "cycle alarm 61002"),
        // FALD 2 above MID 1.
        ("10,0,1,-5,1,0,2,400,100,1,41,1,10", "cycle alarm 61110"),
    ];
    for (parameters, number) in cases {
        assert_eq!(cycle_alarm(&cycle(parameters)), number, "{parameters}");
    }
    // RL 41 without a tool edge: 61000; RL 40 needs none.
    let no_tool = |rl: u32| {
        format!(
            "G0 X0 Y0 Z10\nF100\nCYCLE72(\"C1:C1E\",10,0,1,-5,0,0,0,400,100,1,{rl},1,10)\nM30\n{SQUARE}"
        )
    };
    let alarm = error(&no_tool(41), &machine());
    assert!(alarm.message.starts_with("cycle alarm 61000"), "{alarm:?}");
    assert!(!run(&no_tool(40), &machine()).is_empty());
    // RL, AS1 and AS2 that are none of their values: V007.
    for parameters in [
        "10,0,1,-5,0,0,0,400,100,1,43,1,10",
        "10,0,1,-5,0,0,0,400,100,1,41,5,10",
        "10,0,1,-5,0,0,0,400,100,1,41,0,10",
        "10,0,1,-5,0,0,0,400,100,1,41,21,10",
        "10,0,1,-5,0,0,0,400,100,1,41,1,10,300,7",
    ] {
        let alarm = error(&cycle(parameters), &pocket_machine());
        assert_eq!(
            alarm.code,
            AlarmCode::ValueOutOfRange,
            "{parameters}: {alarm:?}"
        );
    }
}

#[test]
fn cycle72_names_what_is_wrong_with_its_contour() {
    let code = |text: &str, programs: &[(&str, &str)]| {
        let mut library = vcnc::interp::MemoryLibrary::new();
        for (k, (name, program)) in programs.iter().enumerate() {
            library.insert_named(name, vcnc::source::FileId(k as u32 + 1), program);
        }
        let machine = pocket_machine();
        let front_end = vcnc::interp::sinumerik::Sinumerik::new(
            text.as_bytes(),
            vcnc::source::FileId(0),
            &machine,
        )
        .with_library(Box::new(library));
        let run = crate::common::collect(vcnc::interp::Run::new(
            front_end,
            vcnc::interp::Kernel::new(&machine),
        ));
        let alarm = run.error().cloned().expect("an alarm");
        assert!(alarm.span.is_some(), "{alarm:?}");
        alarm.code
    };
    let call = |kname: &str| {
        format!("{POCKET_START}CYCLE72({kname},10,0,1,-5,0,0,0,400,100,1,41,1,10)\nM30\n")
    };
    // No KNAME, a label not in the program, a program not found.
    assert_eq!(code(&call(""), &[]), AlarmCode::MissingValue);
    assert_eq!(
        code(&format!("{}{SQUARE}", call("\"C1:C9\"")), &[]),
        AlarmCode::SequenceNotFound
    );
    assert_eq!(code(&call("\"NOWHERE\""), &[]), AlarmCode::ProgramNotFound);
    // A contour with no element in the plane; one with a rounding (RND needs the blocks
    // around it).
    let empty = ("EMPTY.SPF", "G1 X0 Y0\nZ5\nM17\n");
    assert_eq!(
        code(&call("\"EMPTY\""), &[empty]),
        AlarmCode::ContourDefinition
    );
    let round = ("ROUND.SPF", "G1 X0 Y0\nX10 RND=2\nY10\nM17\n");
    assert_eq!(
        code(&call("\"ROUND\""), &[round]),
        AlarmCode::NotSupportedYet
    );
    // Left of a G3 quarter circle of radius 3 is its inside: the tool's radius 5 does not fit.
    let small = ("SMALL.SPF", "G1 X0 Y0\nX10\nG3 X13 Y3 CR=3\nG1 Y10\nM17\n");
    assert_eq!(
        code(&call("\"SMALL\""), &[small]),
        AlarmCode::CutterCompensation
    );
}

/// Each parameter of a working CYCLE72 call replaced in turn by odd values (left out, zero,
/// negative, tiny, huge) ends in moves or an alarm with a span: never a panic or a hang.
#[test]
fn cycle72_with_any_one_parameter_changed_ends_in_moves_or_an_alarm() {
    const BASE: [&str; 16] = [
        "10", "0", "1", "-5", "2", "0.5", "0", "400", "100", "101", "41", "2", "5", "300", "3", "5",
    ];
    const VALUES: [&str; 12] = [
        "", "0", "1", "-1", "2", "-5", "10", "42", "0.001", "1000000", "-0.5", "113",
    ];
    let machine = pocket_machine();
    for index in 0..BASE.len() {
        for value in VALUES {
            let mut parameters = BASE;
            parameters[index] = value;
            let text = format!(
                "{POCKET_START}CYCLE72(\"C1:C1E\",{})\nM30\n{SQUARE}",
                parameters.join(",")
            );
            let run = crate::common::collect(vcnc::interp::sinumerik::run_str(&text, &machine));
            if let Some(alarm) = run.error() {
                assert!(alarm.span.is_some(), "{text}\n{alarm:?}");
            }
        }
    }
}

#[test]
fn cycle72_reads_variables_increments_and_centres_in_its_contour() {
    // The contour between C2 and C2E: the start X=R1 (R1 = 2) Y0; G91 X10: a line to (12, 0);
    // G3 X10 Y10 I0 J10: an arc counter-clockwise about (12, 0) + (0, 10) to (22, 10); G90 Y30:
    // a line up to (22, 30). RL 40, AS1 1 LP1 5: the way in starts 5 behind the start along
    // +X, at (-3, 0); the way out (AS2 as AS1, LP2 left out: 5) ends 5 on along +Y, at
    // (22, 35). VARI 1: one level at -3, then up to RTP.
    let text = format!(
        "R1=2\n{POCKET_START}CYCLE72(\"C2:C2E\",10,0,1,-3,0,0,0,400,100,1,40,1,5)\nM30\n\
         C2: G1 X=R1 Y0\nG91 X10\nG3 X10 Y10 I0 J10\nC2E: G90 G1 Y30\n"
    );
    let got = cycle_moves(&text);
    let z = -3.0;
    let wanted = [
        ('R', [-3.0, 0.0, 10.0]),
        ('R', [-3.0, 0.0, 1.0]),
        ('L', [-3.0, 0.0, z]),
        ('L', [2.0, 0.0, z]),
        ('L', [12.0, 0.0, z]),
        ('A', [22.0, 10.0, z]),
        ('L', [22.0, 30.0, z]),
        ('L', [22.0, 35.0, z]),
        ('R', [22.0, 35.0, 10.0]),
    ];
    assert_moves(&got, &wanted);
}
