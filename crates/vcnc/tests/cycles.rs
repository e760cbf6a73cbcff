//! Canned cycles (issue #4) on the Syntec manual's examples (spec iso-syntec-milling.md
//! 1.41-1.52, files examples/syntec/5x-*.nc): every move of every hole is asserted. The
//! expected sequences are built here from the manual's step lists, not from vcnc: the common
//! frame (initial level Z10, R level Z-5, holes at (5,5), (15,5), (15,15) returning to R under
//! G99, then (5,15) and (10,10) returning to the initial level under G98) and each cycle's
//! moves at a hole.

mod common;

use common::{check_on, shared_dir};
use vcnc::{Machine, ProfileName};

/// A hole of the common frame: position, bottom, and the level it returns to.
struct Hole {
    x: f64,
    y: f64,
    bottom: f64,
    back: f64,
}

const R: f64 = -5.0;
const INITIAL: f64 = 10.0;

/// The frame's holes: the first `count` of the five (the examples without a fifth hole stop at
/// four).
fn holes(count: usize) -> Vec<Hole> {
    let all = [
        (5.0, 5.0, -10.0, R),
        (15.0, 5.0, -10.0, R),
        (15.0, 15.0, -10.0, R),
        (5.0, 15.0, -10.0, INITIAL),
        (10.0, 10.0, -20.0, INITIAL),
    ];
    all[..count]
        .iter()
        .map(|&(x, y, bottom, back)| Hole { x, y, bottom, back })
        .collect()
}

/// The moves of a program running the frame: for each hole a rapid over it at the level the
/// last hole left the tool, a rapid down to R (unless it is there), and `body`: the cycle's own moves from R to its
/// return level.
fn frame(
    head: &[&str],
    holes: &[Hole],
    body: impl Fn(&Hole) -> Vec<String>,
    tail: &[&str],
) -> String {
    let mut lines: Vec<String> = head.iter().map(|s| s.to_string()).collect();
    let mut level = INITIAL;
    for hole in holes {
        let (x, y) = (hole.x, hole.y);
        lines.push(format!("rapid X{x} Y{y} Z{level}"));
        if level != R {
            lines.push(format!("rapid X{x} Y{y} Z{R}"));
        }
        lines.extend(body(hole));
        level = hole.back;
    }
    lines.extend(tail.iter().map(|s| s.to_string()));
    lines.join("\n")
}

fn example(file: &str, expected: &str) {
    let text = std::fs::read_to_string(shared_dir().join("spec/examples/syntec").join(file))
        .expect("the example is in ../shared");
    let machine = Machine::default()
        .with_profile(ProfileName::Syntec)
        .unwrap();
    check_on(&machine, &text, expected);
}

fn feed(h: &Hole, z: f64) -> String {
    format!("line X{} Y{} Z{z} F1000", h.x, h.y)
}

fn rapid(h: &Hole, z: f64) -> String {
    format!("rapid X{} Y{} Z{z}", h.x, h.y)
}

/// Spec 1.44: G00 over the hole, G00 to R, G01 to Z, G00 back (F2= is the retract feed only in
/// Syntec's fast drilling mode, off by default, so the retract is rapid).
#[test]
fn g81_drilling() {
    example(
        "53-g81-drill-f2.nc",
        &frame(
            &["rapid X0 Y0 Z10"],
            &holes(5),
            |h| vec![feed(h, h.bottom), rapid(h, h.back)],
            &["end M30"],
        ),
    );
}

/// Spec 1.46: pecks of Q = 3 from R (-5): feed to -8, rapid to R, rapid to 1 mm (the
/// clearance) above -8, feed to -10 (the last peck shorter), then out.
#[test]
fn g83_peck_drilling() {
    example(
        "55-g83-peck-drill.nc",
        &frame(
            &["spindle Clockwise 500", "rapid X0 Y0 Z10"],
            &holes(4),
            |h| {
                vec![
                    feed(h, -8.0),
                    rapid(h, R),
                    rapid(h, -7.0),
                    feed(h, -10.0),
                    rapid(h, h.back),
                ]
            },
            &["spindle Stopped 500", "end M30"],
        ),
    );
}

/// Spec 1.41: pecks of Q = 2 from R, each followed by a retract of d = 1 (Pr4002), the next
/// feed starting from there: -7, up to -6, -9, up to -8, then the last peck to the bottom.
#[test]
fn g73_high_speed_peck_drilling() {
    example(
        "50-g73-peck-drill.nc",
        &frame(
            &["spindle Clockwise 500", "rapid X0 Y0 Z10"],
            &holes(5),
            |h| {
                let mut v = Vec::new();
                let mut depth = R;
                loop {
                    let next = (depth - 2.0).max(h.bottom);
                    v.push(feed(h, next));
                    if next == h.bottom {
                        break;
                    }
                    v.push(rapid(h, next + 1.0));
                    depth = next;
                }
                v.push(rapid(h, h.back));
                v
            },
            &["spindle Stopped 500", "end M30"],
        ),
    );
}

/// Spec 1.43: G01 to Z, dwell P5 (seconds with a decimal point), oriented stop, shift Q = 2 in
/// +X (Pr4020 = 0), G00 out, shift back over the hole, spindle on again.
#[test]
fn g76_fine_boring() {
    example(
        "52-g76-fine-boring.nc",
        &frame(
            &["spindle Clockwise 500", "rapid X0 Y0 Z10"],
            &holes(5),
            |h| {
                vec![
                    feed(h, h.bottom),
                    "dwell 5".to_string(),
                    "spindle Oriented 500".to_string(),
                    format!("rapid X{} Y{} Z{}", h.x + 2.0, h.y, h.bottom),
                    format!("rapid X{} Y{} Z{}", h.x + 2.0, h.y, h.back),
                    rapid(h, h.back),
                    "spindle Clockwise 500".to_string(),
                ]
            },
            &["spindle Stopped 500", "end M30"],
        ),
    );
}
