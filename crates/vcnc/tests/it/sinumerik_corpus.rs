//! Every real SINUMERIK program of ../shared/corpus/sinumerik runs on the SINUMERIK front end to
//! its end, or stops only where issue 20 says it may (acceptance 3): at a function the next
//! SINUMERIK issue adds (V020 naming issue 22), at one outside the product (V022), or at a
//! subprogram the corpus does not contain (V084 naming it). Each program runs on the machine of
//! its author (tests/it/common/sinumerik_machines.rs says why each fits), with the corpus's
//! subprograms in its library under their own names; a subprogram file with PROC parameters runs through a small call written
//! here, with the arguments its author's main program would pass.
//!
//! The table (program, outcome, moves, cutting extents, alarm) is printed:
//! `cargo test -p vcnc --test it sinumerik_corpus:: -- --nocapture`.

use crate::common;
use crate::common::sinumerik_machines::machine_for;
use vcnc::checks::TravelLimits;
use vcnc::interp::sinumerik::Sinumerik;
use vcnc::interp::{Kernel, MemoryLibrary, Run};
use vcnc::summary::{LengthUnit, Summary};
use vcnc::{Alarm, AlarmCode, FileId, Machine, ProfileName, SegmentKind};

/// How a program must end.
#[derive(Clone, Copy, Debug)]
enum Expect {
    /// Its End item (M2, M30, or the end of the text).
    End,
    /// V022 at `line`, the message naming `what`.
    OutOfProduct { line: u32, what: &'static str },
    /// V084 at `line`: the corpus lacks subprogram `name`.
    Missing { line: u32, name: &'static str },
    /// V010 at `line`: `what` is no G function of the SINUMERIK.
    Unknown { line: u32, what: &'static str },
}

/// One corpus program: its file, how it is called, how it ends. It runs on the machine of its
/// author (`common::sinumerik_machines::machine_for`).
struct Case {
    file: &'static str,
    /// For a subprogram with PROC parameters: the main program that calls it.
    call: Option<&'static str>,
    expect: Expect,
    /// Worked out by hand (in the case's comment): the moves of the run and the lowest cutting
    /// Z (program coordinates, mm).
    hand: Option<(u64, f64)>,
    /// Rapids that end below the deepest cut so far (their lines), each looked at by hand:
    /// CAM approaches from outside the stock.
    rapids_below_cuts: &'static [u32],
}

/// The corpus, file by file. Lines are those of the corpus file (for a called subprogram, of
/// the subprogram's file).
const CASES: &[Case] = &[
    Case {
        file: "alloyx_DAILY.MPF",
        call: None,
        expect: Expect::End,
        // Two calls of 600 / 15 = 40 passes of 13 moves: 1040; the four SUPA moves home start
        // and end at machine zero, so they do not move. Lowest: SUPA Z-4 inch, -101.6 mm.
        hand: Some((1040, -101.6)),
        rapids_below_cuts: &[],
    },
    Case {
        file: "alloyx_WARMUP_CYCLE.SPF",
        // As DAILY.MPF calls it (inch, absolute, XY; 3600 rpm), for 15 seconds instead of 600:
        // `CYCLES = _DURATION / 15` gives one pass of its 13 moves, which the test counts.
        call: Some("G70 G90 G17\nG700\nWARMUP_CYCLE(3600, 15)\nM5\nM30\n"),
        expect: Expect::End,
        // One pass: 13 moves, down to SUPA Z-4 inch.
        hand: Some((13, -101.6)),
        rapids_below_cuts: &[],
    },
    Case {
        file: "dangarpt_test.MPF",
        call: None,
        // Compensated from line 25 on; its post writes the ISO drilling cycle G81 in the
        // SINUMERIK text (N000196), which the control has not.
        expect: Expect::Unknown {
            line: 196,
            what: "G81",
        },
        hand: None,
        rapids_below_cuts: &[],
    },
    Case {
        file: "dubovikov_123.MPF",
        call: None,
        expect: Expect::Missing {
            line: 13,
            name: "L140",
        },
        hand: None,
        rapids_below_cuts: &[],
    },
    Case {
        file: "dubovikov_CHAMFER.SPF",
        // A 45-degree chamfer 2 mm wide round a bore of radius 20 (rStart 20, rEnd 22), 5
        // degrees a step, 0.5 mm a turn along the cone, a cutter of radius 5 with an insert
        // radius of 0.4: the values its comments name (UGOL DELENIA, SHAG, NAKLON KONUSA,
        // RADIUS FREZI, RADIUS PLASTINI) at the size of a small bore. The tool stands 100 above
        // the part first, as the author's main program leaves it.
        call: Some("G90 G54 G0 Z100\nCHAMFER(20, 5, 0.5, 45, 22, 5, 0.4)\nM30\n"),
        expect: Expect::End,
        // The radius grows 0.5 cos45 tan45 = 0.35355 a turn from 25 (20 + cutter 5) and the
        // loop stops once it reaches 27 (22 + 5): at the step of 5 degrees past 2 / 0.35355
        // turns, R2 = 2040 degrees, 408 steps. Z there: -(0.35355 * 2040/360 + 0.4 (1 - sin
        // 45)) = -2.1206. Moves: the call's G0 Z100, G1 X35, Z2, 408 steps, the full circle
        // and G1 Z100: 413.
        hand: Some((413, -2.1206)),
        rapids_below_cuts: &[],
    },
    Case {
        file: "dubovikov_CYCLE_KONUS.SPF",
        // Retract plane 100, a cone from radius 30 in to radius 10, 5 degrees a step, 0.5 mm a
        // turn, 45 degrees, cutter radius 5, insert radius 0.4, starting at Z0, centred on
        // X0 Y0: its parameters in their order (OTVOD, NACHALNII_RADIUS, ... CPA, CPO). The
        // cycle programs no F and starts no spindle: the caller's F1000 S1000 M3 are a choice.
        call: Some("G90 G54 G0 Z100 F1000 S1000 M3\nCYCLE_KONUS(100, 30, 5, 0.5, 45, 10, 5, 0.4, 0, 0, 0)\nM30\n"),
        expect: Expect::End,
        hand: None,
        rapids_below_cuts: &[],
    },
    Case {
        file: "dubovikov_KANAVKA_SFERA.SPF",
        // A spherical recess of radius 25 opened from radius 20 at Z0, 10 degrees a step round
        // Z and a pitch of at most 5 degrees of latitude, a cutter of radius 4: its parameters
        // in their order (angDivXY, angDivZ, radius, rStart, rMill). The cut then ends at the
        // sphere's pole, Z = sqrt(25^2 - 20^2) - 25 = -10.
        call: Some("G90 G54 G0 Z100\nKANAVKA_SFERA(10, 5, 25, 20, 4)\nM30\n"),
        expect: Expect::End,
        // Latitude from acos(20/25) = 36.870 to 90 in 1 + trunc(53.130 / 5) = 11 turns of 36
        // steps: 396 steps, the last at the pole, Z = 15 - 25 = -10. Moves: the call's G0 Z100,
        // G1 Z0, 396 steps, G0 Z100 (G0 Z100, Y0, X0 and G1 X0 Y0 at the pole do not move):
        // 399.
        hand: Some((399, -10.0)),
        rapids_below_cuts: &[],
    },
    Case {
        file: "dubovikov_KONUS.SPF",
        // The values its own comments give: start radius 36, 0.2 degrees a step, 0.5 mm a
        // turn, 37.5 degrees, end radius 6.5, cutter radius 6.
        call: Some("KONUS(36, 0.2, 0.5, 37.5, 6.5, 6)\nM30\n"),
        expect: Expect::Missing {
            line: 16,
            name: "L140",
        },
        hand: None,
        rapids_below_cuts: &[],
    },
    Case {
        file: "dubovikov_case_test.MPF",
        call: None,
        expect: Expect::End,
        hand: None,
        rapids_below_cuts: &[],
    },
    Case {
        file: "dubovikov_kanavka_vint_sector.MPF",
        call: None,
        expect: Expect::End,
        hand: None,
        rapids_below_cuts: &[],
    },
    Case {
        file: "elmoe_Bottle_opener.MPF",
        call: None,
        expect: Expect::End,
        hand: None,
        // N650 `Z-9.` at X25.98 Y54.664, the +X edge of the part: 3D adaptive roughing
        // enters from outside the stock.
        rapids_below_cuts: &[65],
    },
    Case {
        file: "elmoe_Coordinate_system_Achskreuz.MPF",
        call: None,
        expect: Expect::OutOfProduct {
            line: 1031,
            what: "TRAORI",
        },
        hand: None,
        // N440 at X-75 (the face mill outside the part) and the roughing levels' entries at
        // X3.859 Y60.241, the part's +Y edge: 3 mm over each next level, from outside the stock.
        rapids_below_cuts: &[45, 78, 289, 500, 711],
    },
    Case {
        file: "elmoe_Keychain.MPF",
        call: None,
        // Its last operation drills one hole with MCALL CYCLE81 (line 632) down to -6.1835.
        expect: Expect::End,
        hand: None,
        rapids_below_cuts: &[],
    },
    Case {
        file: "gcodeworkshop_SINUMERIK840D.MPF",
        call: None,
        expect: Expect::Missing {
            line: 24,
            name: "L54",
        },
        hand: None,
        rapids_below_cuts: &[],
    },
    Case {
        file: "jennings_CYCLE189.SPF",
        // Exactly as CYCLE189_TEST.MPF calls it (N14-N35): tool "52" in the spindle, inch with
        // inch feeds (G700), G54, at the clearance plane over the bore, then the call.
        call: Some(
            "T=\"52\"\nM6\nG700\nM3 S6000\nG54\nG17\nD1\nG0 X5.8893 Y10.2375\nZ1.4182\nZ.4182\n\
             CYCLE189(.5,5.8893,10.2375,.4182,.3182,5,-.0203,.1)\nG0 Z1.4182\nM30\n",
        ),
        expect: Expect::End,
        // Rapids over the bore (3), G1 to Z .3432 in and out to the radius (2), ROUNDUP(.3635
        // / .1) = 4 helical turns down to Z_BOT -.0203 in = -0.5156 mm, a full turn, the arc
        // and line to the centre and back out, the arc back (5), 4 turns up (R107 3 to 0), G1
        // to the centre, G0 to the R plane and the call's G0 (the cycle's first G0s do not
        // move): 3 + 2 + 4 + 1 + 4 + 4 + 1 + 2 = 21.
        hand: Some((21, -0.0203 * 25.4)),
        rapids_below_cuts: &[],
    },
    Case {
        file: "jennings_CYCLE189_TEST.MPF",
        call: None,
        expect: Expect::Missing {
            line: 21,
            name: "G_ZP_WRITE",
        },
        hand: None,
        rapids_below_cuts: &[],
    },
    Case {
        file: "ncplot7py_user_siemens_program.MPF",
        call: None,
        // On its B-C machine (sinumerik_machines.rs) every CYCLE800 turns the head and the
        // table; its POCKET4s are ShopMill's long form (DP relative by _AMODE, cycles/pockets.rs).
        expect: Expect::End,
        hand: None,
        // Program Z under a swivel is no height: N150, N152 and N161 turn B and C (rapids of
        // the axes, the tip held) and N162 goes over the next corner pocket, each in a frame
        // turned 54.365 degrees from the one the deepest cut was made in. The plausibility
        // test (sinumerik_corpus_plausible.rs) checks the tool tip in the workpiece.
        rapids_below_cuts: &[58, 61, 72, 73],
    },
    Case {
        file: "philip_CAM_TEST.MPF",
        call: None,
        expect: Expect::End,
        hand: None,
        rapids_below_cuts: &[],
    },
];

/// The warnings the corpus runs give, each the program's own doing: (file, warning, line,
/// why). Every other run is warning-free.
const EXPECTED_WARNINGS: &[(&str, AlarmCode, u32, &str)] = &[
    (
        "dubovikov_CHAMFER.SPF",
        AlarmCode::CuttingWithSpindleStopped,
        26,
        "N20 `G1 X=R1+10` and N21 `Z2` feed to the start before N22 `S1900 M3`, in the air",
    ),
    (
        "dubovikov_case_test.MPF",
        AlarmCode::MissingProgramEnd,
        6,
        "a test of its author's interpreter, without M30",
    ),
    (
        "elmoe_Bottle_opener.MPF",
        AlarmCode::OffsetNumberOutOfRange,
        19,
        "the NX post writes D1 on the move home before the first tool change",
    ),
    (
        "elmoe_Coordinate_system_Achskreuz.MPF",
        AlarmCode::OffsetNumberOutOfRange,
        20,
        "D1 before the first tool change",
    ),
    (
        "elmoe_Keychain.MPF",
        AlarmCode::OffsetNumberOutOfRange,
        19,
        "D1 before the first tool change",
    ),
    (
        "philip_CAM_TEST.MPF",
        AlarmCode::OffsetNumberOutOfRange,
        9,
        "D1 on the move home before `T=\"DRILL 8.5\" M6`",
    ),
    (
        "philip_CAM_TEST.MPF",
        AlarmCode::KeptAsState,
        17,
        "SETMS(1) (the master spindle)",
    ),
];

/// What one run gave.
struct Outcome {
    ended: bool,
    moves: u64,
    feed_moves: u64,
    /// The first error alarm.
    error: Option<Alarm>,
    /// Warnings of the run, the travel check and the summary.
    warnings: Vec<Alarm>,
    summary: Summary,
    /// Rapids that end below the deepest cut so far (program Z): into the part, likely.
    rapids_below_cuts: Vec<u32>,
    /// The end points of the moves, program coordinates X Y Z.
    ends: Vec<[f64; 3]>,
    /// The end points of the moves, machine coordinates X Y Z, and their lines.
    machine_ends: Vec<(u32, [f64; 3])>,
}

fn run(case: &Case, folder: &std::path::Path) -> Outcome {
    run_with(case, folder, &[])
}

/// [`run`] with `stand_ins` (name, text) added to the library.
fn run_with(case: &Case, folder: &std::path::Path, stand_ins: &[(&str, &str)]) -> Outcome {
    let machine = machine_for(case.file);
    let text = match case.call {
        Some(call) => call.to_string(),
        None => {
            String::from_utf8_lossy(&std::fs::read(folder.join(case.file)).unwrap()).into_owned()
        }
    };
    let mut library = common::sinumerik_machines::library(folder);
    for (i, (name, text)) in stand_ins.iter().enumerate() {
        library.insert_named(name, FileId(100 + i as u32), text);
    }
    let front_end =
        Sinumerik::new(text.as_bytes(), FileId(0), &machine).with_library(Box::new(library));
    let stream = Run::new(front_end, Kernel::new(&machine));
    let mut summary = Summary::new(&machine);
    let mut outcome = Outcome {
        ended: false,
        moves: 0,
        feed_moves: 0,
        error: None,
        warnings: Vec::new(),
        summary: Summary::new(&machine),
        rapids_below_cuts: Vec::new(),
        ends: Vec::new(),
        machine_ends: Vec::new(),
    };
    let mut deepest_cut = f64::INFINITY;
    for item in TravelLimits::new(stream, &machine) {
        match item {
            Ok(vcnc::Item::Frame(frame)) => summary.add_frame(&frame),
            Ok(vcnc::Item::Segment(segment)) => {
                summary.add(&segment);
                if let Some(motion) = segment.motion() {
                    outcome.moves += 1;
                    let to = motion.work_to();
                    outcome.ends.push([to[0], to[1], to[2]]);
                    let m = motion.to.0;
                    outcome
                        .machine_ends
                        .push((segment.span.line, [m[0], m[1], m[2]]));
                    if matches!(segment.kind, SegmentKind::Rapid { .. }) {
                        if deepest_cut.is_finite() && to[2] < deepest_cut - 1e-6 {
                            outcome.rapids_below_cuts.push(segment.span.line);
                        }
                    } else {
                        outcome.feed_moves += 1;
                        deepest_cut = deepest_cut.min(to[2]);
                    }
                }
                if matches!(segment.kind, SegmentKind::End { .. }) {
                    outcome.ended = true;
                }
            }
            Err(alarm) => {
                outcome.error.get_or_insert(alarm);
            }
            Ok(vcnc::Item::Warning(alarm)) => outcome.warnings.push(alarm),
        }
    }
    // A rotary rapid comes in pieces: one line each.
    outcome.rapids_below_cuts.dedup();
    outcome.warnings.extend(summary.warnings());
    outcome.summary = summary;
    outcome
}

/// Whether `outcome` is what `expect` says; otherwise why not.
fn check(expect: Expect, outcome: &Outcome) -> Result<(), String> {
    let at = |code: AlarmCode, line: u32, words: &[&str]| -> Result<(), String> {
        match &outcome.error {
            Some(alarm)
                if alarm.code == code
                    && alarm.span.map_or(0, |s| s.line) == line
                    && words.iter().all(|w| alarm.message.contains(w)) =>
            {
                Ok(())
            }
            other => Err(format!(
                "expected {} at line {line} naming {words:?}, got {other:?}",
                code.id()
            )),
        }
    };
    match expect {
        Expect::End if outcome.ended && outcome.error.is_none() => Ok(()),
        Expect::End => Err(format!("expected its end, got {:?}", outcome.error)),
        Expect::OutOfProduct { line, what } => at(AlarmCode::NotInProduct, line, &[what]),
        Expect::Missing { line, name } => at(AlarmCode::ProgramNotFound, line, &[name]),
        Expect::Unknown { line, what } => at(AlarmCode::UnknownGCode, line, &[what]),
    }
}

#[test]
fn every_corpus_program_ends_or_stops_where_issue_20_allows() {
    let Some(shared) = common::shared_dir() else {
        return;
    };
    let folder = shared.join("corpus/sinumerik");
    let mut files: Vec<String> = std::fs::read_dir(&folder)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    files.sort();
    let listed: Vec<&str> = CASES.iter().map(|c| c.file).collect();
    assert_eq!(
        files, listed,
        "every corpus file has its case, in name order"
    );
    let mut table = String::from(
        "| program | outcome | moves (cutting) | cutting extents (program, mm) | alarm | warnings | rapids below the deepest cut |\n|---|---|---:|---|---|---|---|\n",
    );
    let mut failures = Vec::new();
    for case in CASES {
        let outcome = run(case, &folder);
        let result = check(case.expect, &outcome);
        let alarm = outcome.error.as_ref().map_or("-".to_string(), |a| {
            format!(
                "{} line {}: {}",
                a.code.id(),
                a.span.map_or(0, |s| s.line),
                a.message
            )
        });
        let mut warnings: Vec<String> = outcome
            .warnings
            .iter()
            .map(|w| format!("{} line {}", w.code.id(), w.span.map_or(0, |s| s.line)))
            .collect();
        warnings.dedup();
        table.push_str(&format!(
            "| {}{} | {} | {} ({}) | {} | {} | {} | {:?} |\n",
            case.file,
            if case.call.is_some() { " (called)" } else { "" },
            if outcome.ended { "end" } else { "stopped" },
            outcome.moves,
            outcome.feed_moves,
            if outcome.summary.cutting_extents.is_empty() {
                "-".to_string()
            } else {
                outcome
                    .summary
                    .cutting_extents
                    .describe(LengthUnit::Millimetre)
            },
            alarm,
            if warnings.is_empty() {
                "-".to_string()
            } else {
                warnings.join(", ")
            },
            outcome.rapids_below_cuts
        ));
        if let Err(why) = result {
            failures.push(format!("{}: {why}", case.file));
        }
        let mut warned: Vec<(AlarmCode, u32)> = outcome
            .warnings
            .iter()
            .map(|w| (w.code, w.span.map_or(0, |s| s.line)))
            .collect();
        warned.dedup();
        let expected: Vec<(AlarmCode, u32)> = EXPECTED_WARNINGS
            .iter()
            .filter(|w| w.0 == case.file)
            .map(|w| (w.1, w.2))
            .collect();
        if warned != expected {
            failures.push(format!(
                "{}: warnings {warned:?}, expected {expected:?}",
                case.file
            ));
        }
        if outcome.rapids_below_cuts != case.rapids_below_cuts {
            failures.push(format!(
                "{}: rapids below the deepest cut at lines {:?}, expected {:?}",
                case.file, outcome.rapids_below_cuts, case.rapids_below_cuts
            ));
        }
        if let Some((moves, lowest)) = case.hand {
            let cut = outcome.summary.cutting_extents.min[2];
            if outcome.moves != moves || (cut - lowest).abs() > 1e-3 {
                failures.push(format!(
                    "{}: {} moves down to Z{cut:.4}, worked out {moves} down to Z{lowest:.4}",
                    case.file, outcome.moves
                ));
            }
        }
        if case.file == "dubovikov_case_test.MPF" {
            // CASE(5 + 5 - 1) OF 8 ... 6 ... DEFAULT: 9 jumps to Label_3, X = 3.5 COS(3.1415):
            // SINUMERIK angles are degrees, so 3.5 * 0.998497 = 3.49474, not -3.5 (the author
            // seems to have meant radians: VAR0 = 3.1415).
            #[allow(clippy::approx_constant)] // the program's own value, not pi
            let x = 3.5 * 3.1415_f64.to_radians().cos();
            let end = outcome.ends.last().copied().unwrap_or_default();
            if (end[0] - x).abs() > 1e-9 || (end[1] - 3.0).abs() > 1e-9 || outcome.moves != 1 {
                failures.push(format!(
                    "{}: ends at {end:?} after {} moves, worked out X{x} Y3 after 1",
                    case.file, outcome.moves
                ));
            }
        }
    }
    println!("{table}");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A user cycle whose name starts with CYCLE (jennings_CYCLE189.SPF, dubovikov_CYCLE_KONUS.SPF)
/// is a subprogram like any other: the control calls it from the program directory. A
/// standard cycle the library lacks is the front end's own (docs/SINUMERIK.md, Standard
/// cycles).
#[test]
fn a_user_cycle_named_cycle_is_called_from_the_library() {
    let machine = Machine::default()
        .with_profile(ProfileName::Sinumerik)
        .unwrap();
    let mut library = MemoryLibrary::new();
    library.insert_named(
        "CYCLE189.SPF",
        FileId(1),
        "PROC CYCLE189(REAL X_POS)\nG1 X=X_POS F100\nM17\n",
    );
    let front_end = Sinumerik::new(
        &b"CYCLE189(5)\nCYCLE81(10, 0, 2, -5)\nM30\n"[..],
        FileId(0),
        &machine,
    )
    .with_library(Box::new(library));
    let mut ends = Vec::new();
    let mut error = None;
    for item in Run::new(front_end, Kernel::new(&machine)) {
        match item {
            Ok(vcnc::Item::Segment(segment)) => {
                ends.extend(segment.motion().map(|m| (m.to.0[0], m.to.0[2])))
            }
            Ok(_) => {}
            Err(alarm) => error = Some(alarm),
        }
    }
    // CYCLE189 moves X to 5 (its argument); CYCLE81, not in the library, is the built-in
    // cycle: it drills at X5 from the safety plane Z2 to Z-5 and rapids to Z10.
    assert!(error.is_none(), "{error:?}");
    assert_eq!(ends, vec![(5.0, 0.0), (5.0, 2.0), (5.0, -5.0), (5.0, 10.0)]);
}

/// The machine builder's and shop's subprograms the corpus lacks, as stand-ins that do
/// nothing, with the parameters their calls pass: the programs that stop at V084 run on to
/// their next stop, so that the rest of their path is read too.
const STAND_INS: &[(&str, &str)] = &[
    // dubovikov: L140(n) sets up the angle head, L143(angle) turns the table, L106(n) loads a
    // cutter (the comments of dubovikov_123.MPF and KONUS.SPF).
    ("L140", "PROC L140(INT HEAD)\nRET\n"),
    ("L143", "PROC L143(REAL ANGLE)\nRET\n"),
    ("L106", "PROC L106(INT TOOL)\nRET\n"),
    // GCodeWorkShop: L54 and L55 set the work offsets from R0-R4 (measured ones, so zero here).
    ("L54", "M17\n"),
    ("L55", "M17\n"),
    // GCodeWorkShop's chamfering cycle FAZOWANIE(RTP, RFP, SDIS, DP, DPR, diameter), as its
    // calls (MCALL too, with HOLES2) pass them.
    (
        "FAZOWANIE",
        "PROC FAZOWANIE(REAL _RTP, REAL _RFP, REAL _SDIS, REAL _DP, REAL _DPR, REAL _DIAM)\nRET\n",
    ),
    // GROB routines of jennings_CYCLE189_TEST.MPF: offset adjustment, retract, tool offsets.
    (
        "G_ZP_WRITE",
        "PROC G_ZP_WRITE(INT NR, REAL XOFF, REAL YOFF, REAL ZOFF, REAL ANGA, REAL ANGB)\nRET\n",
    ),
    ("G_BACK_TUNNEL", "M17\n"),
    ("G_TOOL", "PROC G_TOOL(REAL LENGTH, REAL RADIUS)\nRET\n"),
];

/// Where each program stops with [`STAND_INS`]: (file, alarm, line, word the message names),
/// or None for a program that then runs to its end.
type StopAt = Option<(AlarmCode, u32, &'static str)>;
const AFTER_STAND_INS: &[(&str, StopAt)] = &[
    (
        "dubovikov_123.MPF",
        Some((AlarmCode::NotSupportedYet, 56, "G41")),
    ),
    // `Z0 W0`: W is the quill of the author's boring mill, an axis of its machine file.
    ("dubovikov_KONUS.SPF", None),
    // Its drilling and tapping run (CYCLE81 and CYCLE84, with MCALL and HOLES2), and the
    // chamfering cycle's stand-in at each position of its MCALL and HOLES2.
    ("gcodeworkshop_SINUMERIK840D.MPF", None),
    // Past N26's CYCLE800 (the table's B turns 91.064 degrees) and the bore to N47
    // `HOME_PROG=""`: HOME_PROG, O_PROG_READY and X/Y/Z_HOMEPOS are GROB's global user data,
    // declared in the machine's definition files the corpus lacks: the control without them
    // alarms there too (12550, name not defined).
    (
        "jennings_CYCLE189_TEST.MPF",
        Some((AlarmCode::WordNotAllowed, 67, "HOME_PROG")),
    ),
];

#[test]
fn with_stand_ins_for_missing_subprograms_the_programs_run_on() {
    let Some(shared) = common::shared_dir() else {
        return;
    };
    let folder = shared.join("corpus/sinumerik");
    let missing: Vec<&str> = CASES
        .iter()
        .filter(|c| matches!(c.expect, Expect::Missing { .. }))
        .map(|c| c.file)
        .collect();
    let listed: Vec<&str> = AFTER_STAND_INS.iter().map(|a| a.0).collect();
    assert_eq!(missing, listed);
    for &(file, stop) in AFTER_STAND_INS {
        let case = CASES.iter().find(|c| c.file == file).unwrap();
        let outcome = run_with(case, &folder, STAND_INS);
        println!(
            "{file}: {} moves ({} cutting), {:?}",
            outcome.moves,
            outcome.feed_moves,
            outcome
                .error
                .as_ref()
                .map(|a| (a.code.id(), a.span.map_or(0, |s| s.line), &a.message))
        );
        let Some((code, line, word)) = stop else {
            assert!(outcome.error.is_none(), "{file}: {:?}", outcome.error);
            continue;
        };
        let error = outcome.error.as_ref().expect("a stop");
        assert_eq!(
            (error.code, error.span.map_or(0, |s| s.line)),
            (code, line),
            "{file}: {error:?}"
        );
        assert!(error.message.contains(word), "{file}: {}", error.message);
        if file == "dubovikov_123.MPF" {
            // ROT Y-90 (N16), a rotation of -90 degrees about Y, turns program X onto machine
            // +Z and program Z onto machine -X (x = -z, z = x). N17 `G0 X1000
            // Y0` goes to machine Z1000; N18 `Z=1589+1` to machine X-1590, the end face of a
            // part 3178 long centred on X0 (its header: ZERO X SEREDINA 3178/2); N24 `X266`
            // cuts across it to machine Z266.
            let at = |l: u32| {
                outcome
                    .machine_ends
                    .iter()
                    .find(|(line, _)| *line == l)
                    .map(|(_, p)| p.map(|v| (v * 1e6).round() / 1e6))
            };
            assert_eq!(at(18), Some([0.0, 0.0, 1000.0]));
            assert_eq!(at(19), Some([-1590.0, 0.0, 1000.0]));
            assert_eq!(at(25), Some([-1590.0, 130.0, 266.0]));
        }
    }
}

/// The summary's cutting extents are program coordinates; under a frame rotated about Y (3+2
/// work, dubovikov_123.MPF's `ROT Y-90`) a cut along program X at Z10 spans program Z 10 only.
/// The summary measures Z from each move's end offset, a translation, so the move's start
/// lands at Z-90 (machine Z 0 less the end's offset 90): found by this corpus run (with stand-ins,
/// dubovikov_123.MPF reads Z 1323 .. 1590 where it cuts at Z 1589 .. 1590).
#[test]
fn cutting_extents_under_a_rotation_about_y_stay_in_the_program_plane() {
    let machine = Machine::default()
        .with_profile(ProfileName::Sinumerik)
        .unwrap();
    let mut summary = Summary::new(&machine);
    let text = "ROT Y-90\nG0 X0 Y0 Z10\nG1 X100 F100\nM30\n";
    for item in vcnc::interp::sinumerik::run_str(text, &machine).flatten() {
        summary.add_item(&item);
    }
    let extents = &summary.cutting_extents;
    assert_eq!((extents.min[2], extents.max[2]), (10.0, 10.0));
}
