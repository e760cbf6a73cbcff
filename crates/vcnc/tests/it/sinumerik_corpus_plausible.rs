//! The toolpaths of the real SINUMERIK programs (../shared/corpus/sinumerik) checked for
//! plausibility (issue 22, acceptance 1): each program that runs to its end on the machine of
//! its author (`common::sinumerik_machines`) must make no rapid through material it cut, and
//! cut only inside its part's extents (the second half at the end of this file).
//!
//! The rule, in machine coordinates (a frame or a rotation changes nothing physical):
//! - The *top* is the highest Z at which a feed move travels in XY: the stock's highest level
//!   the program cuts at (its face, or the first level of a pocket).
//! - The *cut box* is the XY extent of the feed moves below the top: where material was cut.
//! - A rapid after the first feed move (the moves before it start at the machine file's start
//!   position, not the program's) is walked in steps of 0.5 mm. A point of it below the top and
//!   inside the cut box, more than [`REACH`] from its rim (where an approach to a profile from
//!   outside the stock lands), must be over ground already cleared: a feed move made before it passed within
//!   [`REACH`] in XY at that point's Z or lower. So a rapid back into a pocket already cut (or
//!   down a hole already drilled) passes; a rapid at a pocket's depth across material not yet
//!   cut, or through the wall between two pockets, does not.
//!
//! Feed moves are walked along their chord (an arc's bulge is within [`REACH`] for the arcs
//! of these programs, **choice**). Programs that stop before their end (a subprogram the corpus
//! lacks, a function not run yet) are listed and not checked. Run with `-- --nocapture` for the
//! table.

use crate::common;
use crate::common::sinumerik_machines::machine_for;
use std::collections::HashMap;
use vcnc::interp::sinumerik::Sinumerik;
use vcnc::interp::{Kernel, Run};
use vcnc::machine::WorkOffsetId;
use vcnc::{FileId, Machine, Segment, SegmentKind};

/// How near in XY a cut must have passed for a rapid's point to count as over cleared ground,
/// mm: the radius of the smallest end mill of these programs, about (**choice**).
const REACH: f64 = 3.0;

/// The grid's cell, mm: cuts are kept per cell with the lowest Z they reached.
const CELL: f64 = 1.0;

/// The steps a move is walked in, mm, and the most points one move is walked at.
const STEP: f64 = 0.5;
const MAX_POINTS: usize = 4000;

/// A move as the check needs it: rapid or not, from, to (machine X Y Z), its line, and the
/// radius of the tool in the spindle (0 before the first change that gives one).
#[derive(Clone, Copy)]
struct Path {
    rapid: bool,
    from: [f64; 3],
    to: [f64; 3],
    line: u32,
    radius: f64,
}

/// The moves of `segments` as the check walks them, one list per direction of the tool. On a
/// machine with kinematics the points are the tool tip in the workpiece (the forward transform
/// of the joints, tool length 0 as the corpus machines' tools have), turned so that the tool
/// axis is +Z: each direction of a 3+2 program is checked as a 3-axis one, its top the highest
/// level it cuts at. The moves that turn the rotary axes (CYCLE800's swivel) are left out:
/// vcnc does not run the swivel's retract `_FR` before them (docs/KINEMATICS.md, Not yet).
fn directions(segments: &[Segment], machine: &Machine) -> Vec<Vec<Path>> {
    let Some(kinematics) = &machine.kinematics else {
        return vec![paths(segments)];
    };
    let mut groups: Vec<([f64; 3], Vec<Path>)> = Vec::new();
    for (path, s) in paths(segments).into_iter().zip(moves(segments)) {
        let m = s.motion().expect("a move");
        let (from, to) = (m.from.0, m.to.0);
        if (3..from.len()).any(|i| (from[i] - to[i]).abs() > 1e-9) {
            continue;
        }
        let pose = kinematics.forward(&to, 0.0);
        let turned = |q: [f64; 3]| into_tool_frame(q, pose.axis);
        let path = Path {
            from: turned(kinematics.forward(&from, 0.0).tip),
            to: turned(pose.tip),
            ..path
        };
        let same = |a: &[f64; 3]| (0..3).all(|i| (a[i] - pose.axis[i]).abs() < 1e-6);
        match groups.iter_mut().find(|(axis, _)| same(axis)) {
            Some((_, group)) => group.push(path),
            None => groups.push((pose.axis, vec![path])),
        }
    }
    groups.into_iter().map(|(_, group)| group).collect()
}

/// `q` in a right-handed frame whose Z is `axis` (a unit vector).
fn into_tool_frame(q: [f64; 3], axis: [f64; 3]) -> [f64; 3] {
    let helper = if axis[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let v = cross(axis, helper);
    let n = v.iter().map(|c| c * c).sum::<f64>().sqrt();
    let v = v.map(|c| c / n);
    let u = cross(v, axis);
    let dot = |a: [f64; 3]| a[0] * q[0] + a[1] * q[1] + a[2] * q[2];
    [dot(u), dot(v), dot(axis)]
}

/// The segments that are moves, as [`paths`] keeps them.
fn moves(segments: &[Segment]) -> impl Iterator<Item = &Segment> {
    segments.iter().filter(|s| {
        matches!(
            s.kind,
            SegmentKind::Rapid { .. } | SegmentKind::Line { .. } | SegmentKind::Arc { .. }
        ) && s.motion().is_some()
    })
}

/// The moves of `segments`.
fn paths(segments: &[Segment]) -> Vec<Path> {
    let mut radius = 0.0;
    segments
        .iter()
        .filter_map(|s| {
            let rapid = match s.kind {
                SegmentKind::Rapid { .. } => true,
                SegmentKind::Line { .. } | SegmentKind::Arc { .. } => false,
                SegmentKind::ToolChange { geometry, .. } => {
                    radius = geometry.map_or(0.0, |g| g.radius);
                    return None;
                }
                _ => return None,
            };
            let m = s.motion()?;
            let (f, t) = (m.from.0, m.to.0);
            Some(Path {
                rapid,
                from: [f[0], f[1], f[2]],
                to: [t[0], t[1], t[2]],
                line: s.span.line,
                radius,
            })
        })
        .collect()
}

/// The points of `path` every [`STEP`] mm, both ends included.
fn walk(path: &Path) -> impl Iterator<Item = [f64; 3]> + '_ {
    let length = (0..3)
        .map(|i| (path.to[i] - path.from[i]).powi(2))
        .sum::<f64>()
        .sqrt();
    let n = ((length / STEP).ceil() as usize).clamp(1, MAX_POINTS);
    (0..=n).map(move |k| {
        let t = k as f64 / n as f64;
        std::array::from_fn(|i| path.from[i] + (path.to[i] - path.from[i]) * t)
    })
}

fn cell(p: &[f64; 3]) -> (i64, i64) {
    ((p[0] / CELL).floor() as i64, (p[1] / CELL).floor() as i64)
}

/// The coarse cells of the wide cutters' check, mm.
const WIDE_CELL: f64 = 8.0;

/// Whether `q` lies within the radius of a cut made at its Z or lower: `wide` keeps per
/// [`WIDE_CELL`] the lowest Z a cut's centre reached there and the widest cutter that did
/// (**choice**: the two may come from different cuts; a plausibility check, not a simulation).
fn under_a_wide_cut(wide: &HashMap<(i64, i64), (f64, f64)>, widest: f64, q: &[f64; 3]) -> bool {
    if widest <= REACH {
        return false;
    }
    let n = (widest / WIDE_CELL).ceil() as i64 + 1;
    let (cx, cy) = (
        (q[0] / WIDE_CELL).floor() as i64,
        (q[1] / WIDE_CELL).floor() as i64,
    );
    (-n..=n).any(|dx| {
        (-n..=n).any(|dy| {
            wide.get(&(cx + dx, cy + dy)).is_some_and(|&(z, radius)| {
                // From q to the nearest point of the cell.
                let gap = |c: i64, v: f64| {
                    let (low, high) = (c as f64 * WIDE_CELL, (c + 1) as f64 * WIDE_CELL);
                    (low - v).max(v - high).max(0.0)
                };
                let d = gap(cx + dx, q[0]).hypot(gap(cy + dy, q[1]));
                z <= q[2] + 1e-3 && d <= radius
            })
        })
    })
}

/// The lines of the rapids that pass through material (see the module's doc).
fn rapids_through_material(paths: &[Path]) -> Vec<u32> {
    const EPS: f64 = 1e-3;
    let planar = |p: &&Path| !p.rapid && (p.to[0] - p.from[0]).hypot(p.to[1] - p.from[1]) > EPS;
    let Some(top) = paths
        .iter()
        .filter(planar)
        .map(|p| p.from[2].max(p.to[2]))
        .reduce(f64::max)
    else {
        return Vec::new();
    };
    let mut low = [f64::INFINITY; 2];
    let mut high = [f64::NEG_INFINITY; 2];
    for p in paths.iter().filter(|p| !p.rapid) {
        for q in [p.from, p.to] {
            if q[2] < top - EPS {
                for i in 0..2 {
                    low[i] = low[i].min(q[i]);
                    high[i] = high[i].max(q[i]);
                }
            }
        }
    }
    // The rim of REACH inside the box is where an approach to a profile from outside lands.
    let inside = |q: &[f64; 3]| (0..2).all(|i| q[i] > low[i] + REACH && q[i] < high[i] - REACH);
    let reach = (REACH / CELL).ceil() as i64;
    let mut cleared: HashMap<(i64, i64), f64> = HashMap::new();
    // Cutters wider than REACH (a face mill's passes) clear their width: kept coarser.
    let mut wide_cuts: HashMap<(i64, i64), (f64, f64)> = HashMap::new();
    let mut widest: f64 = 0.0;
    let mut found = Vec::new();
    // The moves before the first cut start where the machine file starts, not the program.
    let first_cut = paths.iter().position(|p| !p.rapid).unwrap_or(paths.len());
    for path in &paths[first_cut..] {
        if !path.rapid {
            for q in walk(path) {
                let z = cleared.entry(cell(&q)).or_insert(f64::INFINITY);
                *z = z.min(q[2]);
                let c = (
                    (q[0] / WIDE_CELL).floor() as i64,
                    (q[1] / WIDE_CELL).floor() as i64,
                );
                let wide = wide_cuts.entry(c).or_insert((f64::INFINITY, 0.0));
                *wide = (wide.0.min(q[2]), wide.1.max(path.radius));
            }
            widest = widest.max(path.radius);
            continue;
        }
        let through = walk(path).any(|q| {
            if q[2] >= top - EPS || !inside(&q) {
                return false;
            }
            let (cx, cy) = cell(&q);
            let over_cleared = (-reach..=reach).any(|dx| {
                (-reach..=reach).any(|dy| {
                    cleared
                        .get(&(cx + dx, cy + dy))
                        .is_some_and(|&z| z <= q[2] + EPS)
                })
            });
            !over_cleared && !under_a_wide_cut(&wide_cuts, widest, &q)
        });
        if through {
            found.push(path.line);
        }
    }
    found
}

/// Runs `text` on `machine` with the corpus in its library: its segments and whether it ended.
fn run(text: &str, machine: &Machine, folder: Option<&std::path::Path>) -> (Vec<Segment>, bool) {
    let mut front = Sinumerik::new(text.as_bytes(), FileId(0), machine);
    if let Some(folder) = folder {
        front = front.with_library(Box::new(common::sinumerik_machines::library(folder)));
    }
    let run = common::collect(Run::new(front, Kernel::new(machine)));
    let ended = run.error().is_none()
        && run
            .segments
            .iter()
            .any(|s| matches!(s.kind, SegmentKind::End { .. }));
    (run.segments, ended)
}

/// Rapids the check finds, each looked at by hand: (file, lines).
const LOOKED_AT: &[(&str, &[u32])] = &[
    // N158 `G0 X0 Y0` and N159's POCKET4 over the first corner, N162 and N163 over the second:
    // the first moves after N157's and N161's CYCLE800 turn the head and the table. The tip is
    // held through the turn where N153 left it, at the retraction plane over the other
    // corner: in N157's frame (origin the centroid of the corner N151 faced, workpiece X8.41
    // Y8.41 Z41.58) that is Z-1.19, and N158 goes across at that height, 1.19 mm under the
    // faced corner at its end. The control first retracts along the tool as `_FR` 4 says
    // (its maximum in the tool's direction); vcnc does not run `_FR` yet (docs/KINEMATICS.md).
    ("ncplot7py_user_siemens_program.MPF", &[68, 69, 73, 74]),
];

/// A corpus program's run: its file, its machine, its segments, whether it ended.
type CorpusRun = (String, Machine, Vec<Segment>, bool);

/// Every corpus program run on its author's machine; None without ../shared.
fn corpus_runs() -> Option<Vec<CorpusRun>> {
    let folder = common::shared_dir()?.join("corpus/sinumerik");
    let runs = common::corpus::sorted_files(&folder)
        .iter()
        .map(|path| {
            let file = path.file_name().unwrap().to_string_lossy().into_owned();
            let text = String::from_utf8_lossy(&std::fs::read(path).unwrap()).into_owned();
            let machine = machine_for(&file);
            let (segments, ended) = run(&text, &machine, Some(&folder));
            (file, machine, segments, ended)
        })
        .collect();
    Some(runs)
}

#[test]
fn the_corpus_programs_that_end_rapid_through_no_material_they_cut() {
    let Some(runs) = corpus_runs() else {
        return;
    };
    let mut checked = 0;
    let mut table =
        String::from("| program | ended | moves | rapids through material |\n|---|---|---:|---|\n");
    let mut failures = Vec::new();
    for (file, machine, segments, ended) in runs {
        let groups = directions(&segments, &machine);
        let moves: usize = groups.iter().map(Vec::len).sum();
        let bad: Vec<u32> = if ended {
            checked += 1;
            let mut bad: Vec<u32> = groups
                .iter()
                .flat_map(|g| rapids_through_material(g))
                .collect();
            bad.sort_unstable();
            bad.dedup();
            bad
        } else {
            Vec::new()
        };
        table += &format!("| {file} | {ended} | {moves} | {bad:?} |\n");
        let looked_at = LOOKED_AT
            .iter()
            .find(|(f, _)| *f == file)
            .map_or(&[][..], |(_, lines)| *lines);
        if bad != looked_at {
            failures.push(format!(
                "{file}: rapids through material at lines {bad:?}, looked at {looked_at:?}"
            ));
        }
    }
    println!("{table}");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(
        checked >= 5,
        "only {checked} corpus programs ran to their end\n{table}"
    );
}

/// A face cut at Z0 along Y-5 (the top), then two pockets at Z-5, X0-20 and X40-60 by Y0-20,
/// each round its outline and once along its middle, Y10: the text (18 lines, ending at X60
/// Y0 Z-5) before the rapids the tests add.
const TWO_POCKETS: &str = "G17 G90 G0 X-5 Y-5 Z0\nG1 X65 F100\nG0 Z5\nX0 Y0\n\
G1 Z-5\nX20\nY20\nX0\nY10\nX20\nG0 Z5\nX40 Y10\nG1 Z-5\nX60\nY20\nX40\nY0\nX60\n";

#[test]
fn a_planted_rapid_across_the_wall_between_two_pockets_is_caught() {
    let machine = common::sinumerik::machine();
    // Up to Z-3, below the top Z0, to the middle line Y10 (along the box's rim X60), then back
    // to the first pocket: X20 to X40 is the uncut wall (at X30 the nearest cut is 10 mm away,
    // beyond REACH). Line 21.
    let text = format!("{TWO_POCKETS}G0 Z-3\nY10\nX10\nM30\n");
    let (segments, ended) = run(&text, &machine, None);
    assert!(ended);
    assert_eq!(rapids_through_material(&paths(&segments)), vec![21]);
}

#[test]
fn a_rapid_inside_a_pocket_already_cut_or_above_the_stock_passes() {
    let machine = common::sinumerik::machine();
    // Along the second pocket's middle line, cut at Z-5; then above the top Z0 to the first
    // pocket and down to Z-4 into it (cut at Z-5 there).
    let text = format!("{TWO_POCKETS}G0 Z-3\nY10\nX40\nZ5\nX10\nZ-4\nM30\n");
    let (segments, ended) = run(&text, &machine, None);
    assert!(ended);
    assert_eq!(
        rapids_through_material(&paths(&segments)),
        Vec::<u32>::new()
    );
}

// Cut inside the part (issue 22, acceptance 1): every feed move of a program that runs to its
// end lies, where it is below the part's top (in the material's height), within the part's
// extents plus the radius of the tool in the spindle. The extents are derived per program
// from what the program itself says of its blank ([`PARTS`]); a program that says nothing
// of one is named with the reason ([`NO_PART`]). Points are G54 coordinates: the machine's
// less its G54 offset (the corpus tools have length 0), the tool tip through the kinematics
// on a 5-axis machine. Feed moves are walked every [`STEP`] along their chord.

/// A part's extents, G54 coordinates (mm): X, Y, Z from `min` to `max`; `max[2]` its top.
/// `air`: the lines whose feed moves go beyond it, each looked at by hand (in the air beside
/// the part, cutting nothing).
struct Part {
    min: [f64; 3],
    max: [f64; 3],
    air: &'static [u32],
}

/// The parts of the programs that run to their end, each derived in its comment.
const PARTS: &[(&str, Part)] = &[
    // No workpiece: a spindle warm-up in the air. Its "part" is the box it names, SUPA X-5
    // Y-5 Z-4 inch from the machine zero (WARMUP_CYCLE.SPF N50-N80): X -127..0, Y -127..0,
    // Z -101.6..0, machine coordinates (the Syil's G54 is zero).
    (
        "alloyx_DAILY.MPF",
        Part {
            min: [-127.0, -127.0, -101.6],
            max: [0.0, 0.0, 0.0],
            air: &[],
        },
    ),
    (
        "alloyx_WARMUP_CYCLE.SPF",
        Part {
            min: [-127.0, -127.0, -101.6],
            max: [0.0, 0.0, 0.0],
            air: &[],
        },
    ),
    // ShopMill's blank N103 `WORKPIECE(,,,"BOX",64,0,50,-80,0,0,100.2,100.4)`: a box from
    // X0 Y0 to X100.2 Y100.4, Z 0 to 50. The top at 50, not 0, is the cycles' geometry: N108
    // faces from RFP 25.88 in a plane turned -15 degrees about X at Z50, and 25.88 is 100.4 sin
    // 15 degrees less the 0.2 mm, the height of the top's far edge at Z50 in that plane
    // (**reading**: WORKPIECE's 0 and 50 as the blank's Z range).
    (
        "ncplot7py_user_siemens_program.MPF",
        Part {
            min: [0.0, 0.0, 0.0],
            max: [100.2, 100.4, 50.0],
            // N108 and N109, CYCLE61 with the 63 mm face mill: each level starts and ends
            // SDIS 5 beyond the rim plus the radius, as the facing cycle goes in from outside
            // (5.00 mm past part + radius, measured). N151 and N153, CYCLE61 on the corners
            // with the 16 mm mill: the rectangle they face in the turned plane (PA -24, LENG
            // 20, WID 35) is larger than the corner it cuts off, so its passes run up to 31.6
            // mm beside the blank, below its top, in the air.
            air: &[9, 10, 59, 62],
        },
    ),
];

/// The programs that run to their end with no part to check against, and why.
const NO_PART: &[(&str, &str)] = &[
    ("dubovikov_case_test.MPF", "a test of its author's interpreter: one rapid, no feed move"),
    (
        "dubovikov_kanavka_vint_sector.MPF",
        "a helical groove in a ring of outer radius 993.5 (R9) over a sector (R4, R7): the part is a ring sector the program does not bound in X, Y and Z",
    ),
    (
        "elmoe_Bottle_opener.MPF",
        "NX writes no blank (no WORKPIECE, no stock in its comments); its operations (facing PLANFLAECHE, adaptive roughing entering from outside the stock, wall profiling) give the part's shape, not the blank's",
    ),
    (
        "elmoe_Keychain.MPF",
        "NX writes no blank and no facing: its curve drives follow the keychain's outline, the part itself",
    ),
    (
        "philip_CAM_TEST.MPF",
        "a CAM test with no blank: an 8.5 mm drill traces a figure from Z49 to Z40 on a top the program does not give",
    ),
];

/// The feed moves of `segments` as the extents check walks them: the tool tip in G54
/// coordinates, with the radius of the tool in the spindle.
fn feeds_in_g54(segments: &[Segment], machine: &Machine) -> Vec<Path> {
    let g54 = machine
        .work_offsets
        .get(&WorkOffsetId::Standard(1))
        .copied()
        .unwrap_or_default();
    paths(segments)
        .into_iter()
        .zip(moves(segments))
        .filter(|(p, _)| !p.rapid)
        .map(|(path, s)| {
            let m = s.motion().expect("a move");
            let tip = |joints: &[f64; vcnc::machine::AXES]| match &machine.kinematics {
                Some(k) => k.forward(joints, 0.0).tip,
                None => [joints[0], joints[1], joints[2]],
            };
            let g = |q: [f64; 3]| std::array::from_fn(|i| q[i] - g54[i]);
            Path {
                from: g(tip(&m.from.0)),
                to: g(tip(&m.to.0)),
                ..path
            }
        })
        .collect()
}

/// The lines of the feed moves that cut outside `part` (see above).
fn cuts_outside(feeds: &[Path], part: &Part) -> Vec<u32> {
    const EPS: f64 = 1e-6;
    let mut found: Vec<u32> = feeds
        .iter()
        .filter(|path| {
            walk(path).any(|q| {
                let r = path.radius + EPS;
                q[2] < part.max[2] - EPS
                    && ((0..2).any(|i| q[i] < part.min[i] - r || q[i] > part.max[i] + r)
                        || q[2] < part.min[2] - r)
            })
        })
        .map(|p| p.line)
        .collect();
    found.dedup();
    found
}

#[test]
fn the_corpus_programs_that_end_cut_inside_their_part() {
    let Some(runs) = corpus_runs() else {
        return;
    };
    let mut table =
        String::from("| program | feed moves | part | cuts outside |\n|---|---:|---|---|\n");
    let mut failures = Vec::new();
    for (file, machine, segments, ended) in runs {
        if !ended {
            continue;
        }
        let feeds = feeds_in_g54(&segments, &machine);
        let part = PARTS.iter().find(|(f, _)| *f == file).map(|(_, p)| p);
        let none = NO_PART.iter().find(|(f, _)| *f == file);
        match (part, none) {
            (Some(part), None) => {
                let outside = cuts_outside(&feeds, part);
                table += &format!(
                    "| {file} | {} | {:?} .. {:?} | {outside:?} |\n",
                    feeds.len(),
                    part.min,
                    part.max
                );
                if outside != part.air {
                    failures.push(format!(
                        "{file}: cuts outside its part at lines {outside:?}, looked at {:?}",
                        part.air
                    ));
                }
            }
            (None, Some((_, why))) => {
                table += &format!("| {file} | {} | none: {why} | - |\n", feeds.len())
            }
            _ => failures.push(format!(
                "{file} ends: give it a part or say why it has none"
            )),
        }
    }
    println!("{table}");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn a_planted_cut_beyond_the_part_is_caught() {
    let machine = common::sinumerik::machine();
    // TWO_POCKETS on a part X-5..65 by Y-5..25, Z -10..0, with no tool in the spindle (radius
    // 0): inside. A cut to X70 Y10 at Z-2 (line 20), 5 beyond X65, is caught; one further out
    // above the top (line 22, Z1) is in the air and passes.
    let part = Part {
        min: [-5.0, -5.0, -10.0],
        max: [65.0, 25.0, 0.0],
        air: &[],
    };
    let (segments, ended) = run(&format!("{TWO_POCKETS}M30\n"), &machine, None);
    assert!(ended);
    assert_eq!(
        cuts_outside(&feeds_in_g54(&segments, &machine), &part),
        Vec::<u32>::new()
    );
    let text = format!("{TWO_POCKETS}G1 Z-2\nX70 Y10\nG0 Z1\nG1 X80\nM30\n");
    let (segments, ended) = run(&text, &machine, None);
    assert!(ended);
    assert_eq!(
        cuts_outside(&feeds_in_g54(&segments, &machine), &part),
        vec![20]
    );
}
