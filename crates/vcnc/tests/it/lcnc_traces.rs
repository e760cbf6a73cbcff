//! Reference traces: programs of the ISO subset where LinuxCNC and FANUC agree, with the
//! canonical motion LinuxCNC's interpreter (`rs274 -g`) printed for them, recorded as fixtures by
//! `cargo xtask record-lcnc` (tests/data/lcnc/*.ngc and *.canon). vcnc's motion on the FANUC
//! profile must match within 0.001 mm: every rapid, feed and arc, its end point, arc centre,
//! direction and plane, and the feed rate. LinuxCNC is not needed to run this test. The canned
//! cycle programs (G81, G82, G85, G86, G89 in three planes, G98/G99, G90/G91 with repeats) are
//! read by vcnc with the repeat count as K, FANUC's address for LinuxCNC's L.

use crate::common;
use crate::common::lcnc_canon;

use lcnc_canon::{parse_canon, CanonKind, CanonMove, CanonPlane};
use std::path::{Path, PathBuf};
use vcnc::machine::ToolOffset;
use vcnc::motion::{ArcDirection, Feed, Plane};
use vcnc::{Machine, Options, SegmentKind};

const TOLERANCE: f64 = 0.001;

fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/lcnc")
}

/// The tool table LinuxCNC was given (`T<n> P<pocket> Z<length> ...`), as vcnc offsets H<n>.
/// The standalone `rs274` reads its tool table in inches, so lengths are converted to mm.
fn machine_with_tool_table(dir: &Path) -> Machine {
    let mut machine = Machine::default();
    let Ok(table) = std::fs::read_to_string(dir.join("tool.tbl")) else {
        return machine;
    };
    for line in table.lines() {
        let line = line.split(';').next().unwrap_or("");
        let mut number = None;
        let mut length = 0.0;
        for word in line.split_whitespace() {
            let (letter, value) = word.split_at(1);
            match letter {
                "T" | "t" => number = value.parse::<u32>().ok(),
                "Z" | "z" => length = value.parse::<f64>().unwrap_or(0.0) * 25.4,
                _ => {}
            }
        }
        if let Some(number) = number {
            machine.tool_offsets.insert(
                number,
                ToolOffset {
                    number,
                    length,
                    ..ToolOffset::default()
                },
            );
        }
    }
    machine
}

/// A motion of vcnc's stream in the shape of a canonical move.
#[derive(Debug)]
struct Motion {
    line: u32,
    kind: &'static str,
    to: [f64; 3],
    center: Option<([f64; 3], bool, Plane)>,
    feed: Option<f64>,
}

/// The program as a FANUC control reads it: LinuxCNC writes a canned cycle's repeat count as L
/// where FANUC writes K (the only dialect difference the fixtures use).
fn fanuc_text(text: &str) -> String {
    text.lines()
        .map(|line| {
            let cycle = ["G81", "G82", "G83", "G73", "G85", "G86", "G89"]
                .iter()
                .any(|g| line.contains(g));
            if cycle {
                line.replace(" L", " K")
            } else {
                line.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn vcnc_motions(text: &str, machine: &Machine) -> Result<Vec<Motion>, String> {
    let run = common::run(fanuc_text(text).as_bytes(), machine, Options::default());
    if let Some(alarm) = run.error() {
        return Err(format!("vcnc alarm: {alarm}"));
    }
    let mut motions = Vec::new();
    for segment in &run.segments {
        let Some(motion) = segment.motion() else {
            continue;
        };
        if motion.from == motion.to && !matches!(segment.kind, SegmentKind::Arc { .. }) {
            continue;
        }
        let (kind, center, feed) = match segment.kind {
            SegmentKind::Rapid { .. } => ("rapid", None, None),
            SegmentKind::Line { feed, .. } => ("feed", None, feed_of(&feed, segment.length())),
            SegmentKind::Arc {
                center,
                direction,
                plane,
                feed,
                ..
            } => (
                "arc",
                Some((center.xyz(), direction == ArcDirection::Clockwise, plane)),
                feed_of(&feed, segment.length()),
            ),
            _ => continue,
        };
        motions.push(Motion {
            line: segment.span.line,
            kind,
            to: motion.to.xyz(),
            center,
            feed,
        });
    }
    Ok(motions)
}

fn feed_of(feed: &Feed, length: f64) -> Option<f64> {
    feed.mm_per_min(length)
}

fn canon_kind(m: &CanonMove) -> &'static str {
    match m.kind {
        CanonKind::Rapid => "rapid",
        CanonKind::Feed { .. } => "feed",
        CanonKind::Arc { .. } => "arc",
        CanonKind::Dwell { .. } => "dwell",
    }
}

fn close(a: [f64; 3], b: [f64; 3]) -> bool {
    (0..3).all(|i| (a[i] - b[i]).abs() <= TOLERANCE)
}

/// Compares one program; returns the differences.
fn compare(
    name: &str,
    ours: &[Motion],
    theirs: &[CanonMove],
    previous_end: [f64; 3],
) -> Vec<String> {
    let mut problems = Vec::new();
    let mut last = previous_end;
    let theirs: Vec<&CanonMove> = theirs
        .iter()
        .filter(|m| !matches!(m.kind, CanonKind::Dwell { .. }))
        .filter(|m| {
            // LinuxCNC prints moves of zero length; vcnc does not move there.
            let moving = !close(m.to, last) || matches!(m.kind, CanonKind::Arc { .. });
            last = m.to;
            moving
        })
        .collect();
    if ours.len() != theirs.len() {
        problems.push(format!(
            "{name}: vcnc has {} motions, LinuxCNC {}",
            ours.len(),
            theirs.len()
        ));
    }
    for (k, (a, b)) in ours.iter().zip(&theirs).enumerate() {
        let at = format!("{name} motion {} (vcnc line {})", k + 1, a.line);
        // The fixtures give every block an N word equal to its line number (0: none).
        if b.line != 0 && b.line != a.line {
            problems.push(format!(
                "{at}: LinuxCNC made this motion at line {}",
                b.line
            ));
        }
        if a.kind != canon_kind(b) {
            problems.push(format!(
                "{at}: vcnc {} vs LinuxCNC {}",
                a.kind,
                canon_kind(b)
            ));
            break;
        }
        if !close(a.to, b.to) {
            problems.push(format!("{at}: end {:?} vs LinuxCNC {:?}", a.to, b.to));
        }
        match (&b.kind, &a.center) {
            (
                CanonKind::Arc {
                    center,
                    clockwise,
                    plane,
                    turns: _,
                },
                Some((c, cw, p)),
            ) => {
                let plane_ok = matches!(
                    (plane, p),
                    (CanonPlane::Xy, Plane::Xy)
                        | (CanonPlane::Zx, Plane::Zx)
                        | (CanonPlane::Yz, Plane::Yz)
                );
                // The centre's normal-axis value is not meaningful (helices): compare the plane axes.
                let (i, j, _) = p.axes();
                let centre_ok =
                    (c[i] - center[i]).abs() <= TOLERANCE && (c[j] - center[j]).abs() <= TOLERANCE;
                if !plane_ok || *cw != *clockwise || !centre_ok {
                    problems.push(format!(
                        "{at}: arc centre {c:?} cw {cw} {p:?} vs LinuxCNC {center:?} cw {clockwise} {plane:?}"
                    ));
                }
            }
            (CanonKind::Feed { feed_mm_per_min }, None) => {
                if let Some(f) = a.feed {
                    if (f - feed_mm_per_min).abs() > 1e-3 * feed_mm_per_min.max(1.0) {
                        problems.push(format!("{at}: feed {f} vs LinuxCNC {feed_mm_per_min}"));
                    }
                }
            }
            _ => {}
        }
    }
    problems
}

#[test]
fn vcnc_matches_linuxcnc_on_the_common_iso_subset() {
    let dir = data_dir();
    let machine = machine_with_tool_table(&dir);
    let mut programs: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("tests/data/lcnc exists")
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "ngc"))
        .collect();
    programs.sort();
    let mut problems = Vec::new();
    let mut compared = 0;
    let mut motions = 0;
    for path in &programs {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let text = std::fs::read_to_string(path).unwrap();
        let canon_text =
            std::fs::read_to_string(path.with_extension("canon")).unwrap_or_else(|_| {
                panic!("{name}: no recorded .canon (run `cargo xtask record-lcnc`)")
            });
        let theirs = match parse_canon(&canon_text) {
            Ok(moves) => moves,
            Err(e) => {
                problems.push(format!("{name}: cannot read the canon file: {e}"));
                continue;
            }
        };
        let ours = match vcnc_motions(&text, &machine) {
            Ok(m) => m,
            Err(e) => {
                problems.push(format!("{name}: {e}"));
                continue;
            }
        };
        motions += ours.len();
        compared += 1;
        problems.extend(compare(
            &name,
            &ours,
            &theirs,
            machine.start[..3].try_into().unwrap(),
        ));
    }
    println!("LinuxCNC reference traces: {compared} programs, {motions} motions compared");
    assert!(
        problems.is_empty(),
        "{} differences:\n{}",
        problems.len(),
        problems.join("\n")
    );
    assert!(
        compared >= 60,
        "at least 60 reference programs are expected, found {compared}"
    );
}
