//! SINUMERIK's contour cycles (docs/SINUMERIK.md, Standard cycles): CYCLE79, the multi-edge
//! spigot, and CYCLE72, path milling along a contour given by name, with their alarms.
//!
//! Every expected position is worked out by hand from the parameter meanings the docs give. The
//! machine is the default one with a 10 mm end mill (T1 D1, radius 5), no work offset and no
//! tool length, so program and machine coordinates are the same; the spindle turns M3.

use vcnc::AlarmCode;

use crate::common::sinumerik::machine;
use crate::sinumerik_cycles::{
    assert_moves, cycle_alarm, error, moves, pocket_machine, run, Move, POCKET_START,
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
