//! The SINUMERIK front end's semantics, block by block, with positions worked out by hand
//! (docs/SINUMERIK.md names the manual's rules; each test says which it checks).

use vcnc::interp::sinumerik::{run_str, Sinumerik};
use vcnc::interp::{Kernel, MemoryLibrary, Run};
use vcnc::machine::WorkOffsetId;
use vcnc::motion::{ArcDirection, EndKind, Plane, SpindleState};
use vcnc::{Alarm, AlarmCode, FileId, Machine, ProfileName, Segment, SegmentKind};

use crate::common::sinumerik::{machine, mill};

/// G54 at X100 Y50, G55 at X200; tool 1 "MILL10" with D1 length 100 and D2 length 50.
fn shop() -> Machine {
    let mut machine = machine();
    machine
        .work_offsets
        .insert(WorkOffsetId::Standard(1), [100.0, 50.0, 0.0, 0.0, 0.0, 0.0]);
    machine
        .work_offsets
        .insert(WorkOffsetId::Standard(2), [200.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    machine
        .work_offsets
        .insert(WorkOffsetId::External, [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    for (d, length) in [(1, 100.0), (2, 50.0)] {
        machine.tools.push(mill(1, "MILL10", d, length, 5.0));
    }
    machine
}

/// The stream of `text` on `machine`, stopping at the first error.
fn stream(text: &str, machine: &Machine) -> (Vec<Segment>, Vec<Alarm>) {
    collect(run_str(text, machine))
}

fn collect(run: Run<Sinumerik>) -> (Vec<Segment>, Vec<Alarm>) {
    let mut segments = Vec::new();
    let mut alarms = Vec::new();
    for item in run {
        match item {
            Ok(vcnc::Item::Segment(segment)) => segments.push(segment),
            Ok(vcnc::Item::Frame(_)) => {}
            Ok(vcnc::Item::Warning(alarm)) | Err(alarm) => alarms.push(alarm),
        }
    }
    (segments, alarms)
}

/// The end points of the moves, machine coordinates X Y Z.
fn ends(segments: &[Segment]) -> Vec<[f64; 3]> {
    segments
        .iter()
        .filter_map(Segment::motion)
        .map(|m| [m.to.0[0], m.to.0[1], m.to.0[2]])
        .collect()
}

fn moves(text: &str, machine: &Machine) -> Vec<[f64; 3]> {
    let (segments, alarms) = stream(text, machine);
    assert!(alarms.iter().all(|a| !a.is_error()), "{text}\n{alarms:#?}");
    ends(&segments)
}

fn error(text: &str, machine: &Machine) -> Alarm {
    let (_, alarms) = stream(text, machine);
    alarms
        .into_iter()
        .find(Alarm::is_error)
        .unwrap_or_else(|| panic!("no error in\n{text}"))
}

/// The first arc of a stream.
fn arc(segments: &[Segment]) -> Option<SegmentKind> {
    segments
        .iter()
        .map(|s| s.kind)
        .find(|k| matches!(k, SegmentKind::Arc { .. }))
}

fn close(a: [f64; 3], b: [f64; 3]) -> bool {
    a.iter().zip(b).all(|(p, q)| (p - q).abs() < 1e-6)
}

#[track_caller]
fn assert_moves(text: &str, machine: &Machine, expected: &[[f64; 3]]) {
    let got = moves(text, machine);
    assert!(
        got.len() == expected.len() && got.iter().zip(expected).all(|(g, e)| close(*g, *e)),
        "{text}\ngot {got:?}\nwanted {expected:?}"
    );
}

#[test]
fn power_on_is_g500_g90_g71_g1_g17_without_a_work_offset() {
    // G500: no settable offset; G1 at power-on with a feed: the first block cuts.
    let (segments, _) = stream("F100 X10 Y5\nM30\n", &shop());
    assert!(matches!(segments[0].kind, SegmentKind::Line { .. }));
    assert!(close(ends(&segments)[0], [10.0 + 1.0, 5.0, 0.0]));
}

#[test]
fn g54_acts_in_its_own_block() {
    // PGsl 8.1: `G54 G0 X-72` already uses G54 (X100 Y50), plus the external X1.
    assert_moves("G54 G0 X-72 Y-72\nM30\n", &shop(), &[[29.0, -22.0, 0.0]]);
}

#[test]
fn incremental_values_add_to_the_programmed_position() {
    assert_moves(
        "G54 G0 X10 Y0\nG91 X5\nX5 Y1\nM30\n",
        &shop(),
        &[[111.0, 50.0, 0.0], [116.0, 50.0, 0.0], [121.0, 51.0, 0.0]],
    );
}

#[test]
fn ac_and_ic_act_on_one_word_without_changing_the_group() {
    // docs/SINUMERIK.md 6.2: `G90 G0 X10` / `X=IC(5)` / `X20` -> X15 then X20; `G91 X=AC(50)`.
    assert_moves(
        "G0 X10\nX=IC(5)\nX20\nG91 X=AC(50) Y2\nY2\nM30\n",
        &machine(),
        &[
            [10.0, 0.0, 0.0],
            [15.0, 0.0, 0.0],
            [20.0, 0.0, 0.0],
            [50.0, 2.0, 0.0],
            [50.0, 4.0, 0.0],
        ],
    );
}

#[test]
fn a_word_written_after_g91_is_still_incremental() {
    // The G functions of a block act before its values are read (3.2 step 3).
    assert_moves(
        "G0 X10\nX10 G91\nM30\n",
        &machine(),
        &[[10.0, 0.0, 0.0], [20.0, 0.0, 0.0]],
    );
}

#[test]
fn g70_converts_positions_but_not_the_feed() {
    // Ex. A-78: G70 X2.75 Y3.22 -> X69.85 Y81.788 mm; F500 stays 500 mm/min.
    let (segments, _) = stream("G70 G1 X2.75 Y3.22 F500\nM30\n", &machine());
    assert!(close(ends(&segments)[0], [69.85, 81.788, 0.0]));
    let SegmentKind::Line { feed, .. } = segments[0].kind else {
        panic!("{segments:?}")
    };
    assert_eq!(feed, vcnc::motion::Feed::PerMinute(500.0));
}

#[test]
fn g700_converts_the_feed_too() {
    let (segments, _) = stream("G700 G1 X1 F10\nM30\n", &machine());
    let SegmentKind::Line { feed, .. } = segments[0].kind else {
        panic!("{segments:?}")
    };
    assert_eq!(feed, vcnc::motion::Feed::PerMinute(254.0));
}

#[test]
fn a_change_of_feed_type_leaves_no_feed() {
    // PGsl 7.1: after G95 the G94 feed is gone; the next cut without F alarms.
    let alarm = error("G1 X1 F100\nG95 S1000 M3\nX2\nM30\n", &machine());
    assert_eq!(alarm.code, AlarmCode::NoFeedRate);
    assert_eq!(alarm.span.unwrap().line, 3);
}

#[test]
fn cr_gives_the_short_arc_when_positive_and_the_long_one_when_negative() {
    for (cr, centre_y) in [("10", -0.0), ("-10", 0.0)] {
        let text = format!("G0 X0 Y0\nG2 X20 Y0 CR={cr} F100\nM30\n");
        let (segments, alarms) = stream(&text, &machine());
        assert!(alarms.is_empty(), "{alarms:?}");
        let Some(SegmentKind::Arc {
            center, direction, ..
        }) = arc(&segments)
        else {
            panic!("{segments:?}")
        };
        // Chord 20 = diameter: both arcs are half circles about (10, 0).
        assert!((center.0[0] - 10.0).abs() < 1e-9 && (center.0[1] - centre_y).abs() < 1e-9);
        assert_eq!(direction, ArcDirection::Clockwise);
    }
    // Chord 10, radius 10: the centre is 8.660 off the chord's middle, on the right of the
    // way for the short clockwise arc and on the left for the long one.
    for (cr, centre_y) in [("10", -8.660254), ("-10", 8.660254)] {
        let text = format!("G0 X0 Y0\nG2 X10 Y0 CR={cr} F100\nM30\n");
        let (segments, _) = stream(&text, &machine());
        let Some(SegmentKind::Arc { center, .. }) = arc(&segments) else {
            panic!("{segments:?}")
        };
        assert!(
            (center.0[0] - 5.0).abs() < 1e-6 && (center.0[1] - centre_y).abs() < 1e-6,
            "CR={cr}: {center:?}"
        );
    }
}

#[test]
fn i_j_are_incremental_unless_written_with_ac() {
    // Ex.: from X45 Y60, `G2 X20 Y35 I=AC(45) J=AC(35)` equals `I0 J-25`.
    for centre in ["I=AC(45) J=AC(35)", "I0 J-25"] {
        let text = format!("G0 X45 Y60\nG2 X20 Y35 {centre} F100\nM30\n");
        let (segments, alarms) = stream(&text, &machine());
        assert!(alarms.is_empty(), "{alarms:?}");
        let SegmentKind::Arc { center, .. } = segments[1].kind else {
            panic!("{segments:?}")
        };
        assert!(close([center.0[0], center.0[1], 0.0], [45.0, 35.0, 0.0]));
    }
}

#[test]
fn an_arc_needs_a_centre_or_a_radius() {
    let alarm = error("G0 X0 Y0\nG2 X10 Y0 F100\nM30\n", &machine());
    assert_eq!(alarm.code, AlarmCode::ArcWithoutCenter);
}

#[test]
fn g18_arcs_turn_in_z_x() {
    let (segments, _) = stream("G18 G0 X0 Z0\nG3 X20 Z0 I10 K0 F100\nM30\n", &machine());
    let Some(SegmentKind::Arc { plane, center, .. }) = arc(&segments) else {
        panic!("{segments:?}")
    };
    assert_eq!(plane, vcnc::motion::Plane::Zx);
    assert!((center.0[0] - 10.0).abs() < 1e-9);
}

#[test]
fn t_by_name_m6_and_d_apply_the_edge_length_on_the_next_z_move() {
    // PGsl 5.6: the length is traversed by the next move of Z; D2 changes it to 50.
    assert_moves(
        "T=\"MILL10\"\nM6\nG0 X0 Y0\nZ10\nD2\nZ10\nD0\nZ10\nM30\n",
        &shop(),
        &[
            [1.0, 0.0, 0.0],
            [1.0, 0.0, 110.0],
            [1.0, 0.0, 60.0],
            [1.0, 0.0, 10.0],
        ],
    );
}

#[test]
fn a_tool_change_is_in_the_stream() {
    let (segments, _) = stream("T1 D1 M6\nM30\n", &shop());
    let kinds: Vec<_> = segments.iter().map(|s| s.kind).collect();
    assert!(matches!(kinds[0], SegmentKind::ToolSelect { tool: 1 }));
    assert!(matches!(kinds[1], SegmentKind::ToolChange { tool: 1, .. }));
}

#[test]
fn a_tool_name_the_table_lacks_runs_without_offsets_and_is_said_once() {
    let (segments, alarms) = stream(
        "T=\"DRILL5\" M6 D1\nG0 Z10\nT=\"DRILL5\" M6\nM30\n",
        &shop(),
    );
    assert_eq!(alarms.len(), 1, "{alarms:?}");
    assert!(!alarms[0].is_error() && alarms[0].message.contains("DRILL5"));
    assert!(close(ends(&segments)[0], [0.0, 0.0, 10.0]));
}

#[test]
fn g53_suppresses_the_frames_but_keeps_the_length() {
    // docs/SINUMERIK.md 5.6: G54 X100 + external X1; G53 X0 -> X1; SUPA X0 -> X0; SUPA Z0 keeps
    // the length (100); the next plain block has the frames again.
    assert_moves(
        "T1 M6 D1\nG54 G0 X0 Y0 Z0\nG53 X0\nSUPA X0\nSUPA Z0\nX0\nM30\n",
        &shop(),
        &[
            [101.0, 50.0, 100.0],
            [1.0, 50.0, 100.0],
            [0.0, 50.0, 100.0],
            [101.0, 50.0, 100.0],
        ],
    );
}

#[test]
fn a_work_offset_change_moves_only_the_axes_programmed() {
    // docs/SINUMERIK.md 6.4 rule 2: G55 (X200) then `G0 Y7`: X stays where it is.
    assert_moves(
        "G54 G0 X10 Y0\nG55\nY7\nX10\nM30\n",
        &shop(),
        &[[111.0, 50.0, 0.0], [111.0, 7.0, 0.0], [211.0, 7.0, 0.0]],
    );
}

#[test]
fn g4_dwells_f_seconds_or_s_revolutions_and_keeps_the_feed() {
    // PGsl 14.10, ex. B-85: F in a G4 block is the time; the modal F stays.
    let (segments, alarms) = stream(
        "G1 F200 X1\nG4 F2.5\nS600 M3\nG4 S30\nX2\nM30\n",
        &machine(),
    );
    assert!(alarms.is_empty(), "{alarms:?}");
    let dwells: Vec<f64> = segments
        .iter()
        .filter_map(|s| match s.kind {
            SegmentKind::Dwell { seconds } => Some(seconds),
            _ => None,
        })
        .collect();
    assert_eq!(dwells, [2.5, 3.0]);
    let last_feed = segments.iter().rev().find_map(|s| match s.kind {
        SegmentKind::Line { feed, .. } => Some(feed),
        _ => None,
    });
    assert_eq!(last_feed, Some(vcnc::motion::Feed::PerMinute(200.0)));
}

#[test]
fn the_spindle_starts_before_the_motion_of_its_block() {
    let (segments, _) = stream("G0 X10 S1000 M3\nM30\n", &machine());
    assert!(matches!(
        segments[0].kind,
        SegmentKind::Spindle {
            state: SpindleState::Clockwise,
            speed
        } if speed == 1000.0
    ));
    assert!(matches!(segments[1].kind, SegmentKind::Rapid { .. }));
}

#[test]
fn two_g_functions_of_one_group_in_a_block_alarm() {
    let alarm = error("G0 G1 X10\nM30\n", &machine());
    assert_eq!(alarm.code, AlarmCode::SameGroupGCodes);
}

#[test]
fn r_parameters_are_set_left_to_right_in_a_block() {
    // 3.2 step 2: `R1=5 X=R1` moves to X5; `X=R1 R1=7` still uses 5.
    assert_moves(
        "R1=5 G0 X=R1\nX=-R1 R1=7\nX=R1\nM30\n",
        &machine(),
        &[[5.0, 0.0, 0.0], [-5.0, 0.0, 0.0], [7.0, 0.0, 0.0]],
    );
}

#[test]
fn subprograms_run_by_name_and_by_l_with_p_passes() {
    let mut library = MemoryLibrary::new();
    library.insert_named("L10.SPF", FileId(1), "G91 G0 X1\nM17\n");
    library.insert_named("SIDE", FileId(2), "G91 G0 Y1\nRET\n");
    let text = "G0 X0 Y0\nL10 P3\nSIDE\nG90 X0\nM30\n";
    let machine = machine();
    let front_end =
        Sinumerik::new(text.as_bytes(), FileId(0), &machine).with_library(Box::new(library));
    let (segments, alarms) = collect(Run::new(front_end, Kernel::new(&machine)));
    assert!(alarms.is_empty(), "{alarms:?}");
    let got = ends(&segments);
    let wanted = [
        [1.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [3.0, 0.0, 0.0],
        [3.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    assert!(
        got.iter().zip(&wanted).all(|(g, w)| close(*g, *w)) && got.len() == 5,
        "{got:?}"
    );
}

#[test]
fn a_missing_subprogram_alarms_with_its_name() {
    let alarm = error("G0 X0\nPART7\nM30\n", &machine());
    assert_eq!(alarm.code, AlarmCode::ProgramNotFound);
    assert!(alarm.message.contains("PART7"));
}

#[test]
fn a_program_that_calls_itself_stops_at_the_depth_limit() {
    let mut library = MemoryLibrary::new();
    library.insert_named("AGAIN", FileId(1), "G91 G0 X1\nAGAIN\nM17\n");
    let machine = machine();
    let front_end =
        Sinumerik::new(&b"AGAIN\nM30\n"[..], FileId(0), &machine).with_library(Box::new(library));
    let (_, alarms) = collect(Run::new(front_end, Kernel::new(&machine)));
    assert_eq!(alarms.last().unwrap().code, AlarmCode::MacroLimit);
}

#[test]
fn m2_and_m30_end_the_program_and_nothing_after_runs() {
    let (segments, _) = stream("G0 X1\nM2\nG0 X5\n", &machine());
    assert_eq!(ends(&segments).len(), 1);
    assert!(matches!(
        segments.last().unwrap().kind,
        SegmentKind::End { kind: EndKind::M02 }
    ));
}

#[test]
fn a_program_without_an_end_warns() {
    let (segments, alarms) = stream("G0 X1\n", &machine());
    assert_eq!(alarms[0].code, AlarmCode::MissingProgramEnd);
    assert!(!alarms[0].is_error());
    assert!(matches!(
        segments.last().unwrap().kind,
        SegmentKind::End {
            kind: EndKind::EndOfText
        }
    ));
}

#[test]
fn a_file_header_and_comments_are_no_blocks() {
    assert_moves(
        "%_N_PART_MPF\n;$PATH=/_N_MPF_DIR\nN10 G0 X3 ; to the start\nM30\n",
        &machine(),
        &[[3.0, 0.0, 0.0]],
    );
}

#[test]
fn skipped_blocks_run_unless_their_level_is_on() {
    let machine = machine();
    let text = "G0 X1\n/ X2\n/3 X3\nM30\n";
    assert_eq!(moves(text, &machine).len(), 3);
    let front_end = Sinumerik::new(text.as_bytes(), FileId(0), &machine)
        .with_skip_level(0, true)
        .with_skip_level(3, true);
    let (segments, _) = collect(Run::new(front_end, Kernel::new(&machine)));
    assert_eq!(ends(&segments).len(), 1);
}

#[test]
fn what_the_next_issue_adds_alarms_planned_with_its_number() {
    for (text, name) in [
        ("FLIN\nM30\n", "FLIN"),
        // The standard cycles vcnc does not run yet (CYCLE81, POCKET3 ... run: sinumerik_cycles).
        ("CYCLE70(10,0,2,-5)\nM30\n", "CYCLE70"),
        ("CYCLE899(1,2,3)\nM30\n", "CYCLE899"),
    ] {
        let alarm = error(text, &machine());
        assert_eq!(alarm.code, AlarmCode::NotSupportedYet, "{text}");
        assert!(
            alarm.message.contains(name) && alarm.message.contains("issue 22"),
            "{alarm:?}"
        );
    }
}

#[test]
fn what_is_outside_the_product_alarms_with_what_it_belongs_to() {
    for (text, what) in [
        ("TRACYL(20)\nM30\n", "kinematic transformations"),
        ("G962 S100\nM30\n", "turning"),
        ("COUPON(C2,C1,1)\nM30\n", "couplings"),
    ] {
        let alarm = error(text, &machine());
        assert_eq!(alarm.code, AlarmCode::NotInProduct, "{text}");
        assert!(alarm.message.contains(what), "{alarm:?}");
    }
}

#[test]
fn an_axis_the_machine_lacks_alarms() {
    let alarm = error("G0 A10\nM30\n", &machine());
    assert_eq!(alarm.code, AlarmCode::AxisNotOnMachine);
}

#[test]
fn the_828d_has_g58_as_a_settable_frame() {
    let mut machine = Machine::default()
        .with_profile(ProfileName::Sinumerik828d)
        .unwrap();
    machine
        .work_offsets
        .insert(WorkOffsetId::Standard(5), [7.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    assert_moves("G58 G0 X1\nM30\n", &machine, &[[8.0, 0.0, 0.0]]);
    assert_eq!(error("G505\nM30\n", &machine).code, AlarmCode::UnknownGCode);
}

/// The X values the rapids go to, in order.
fn xs(text: &str) -> Vec<f64> {
    moves(text, &machine()).iter().map(|p| p[0]).collect()
}

#[test]
fn if_else_endif_runs_one_branch() {
    let text = "R1=1\nIF R1\nG0 X1\nELSE\nG0 X2\nENDIF\nR1=0\nIF R1\nG0 X3\nELSE\nG0 X4\nENDIF\nG0 X5\nM30\n";
    assert_eq!(xs(text), [1.0, 4.0, 5.0]);
}

#[test]
fn nested_structures_find_their_own_ends() {
    // The inner IF's ENDIF is not the outer one's: a false outer IF skips the whole inner one.
    let text = "R1=0\nIF R1\nIF R1\nG0 X1\nENDIF\nG0 X2\nELSE\nG0 X3\nENDIF\nM30\n";
    assert_eq!(xs(text), [3.0]);
}

#[test]
fn for_counts_to_its_end_inclusive() {
    let text = "G91\nFOR R1=1 TO 3\nG0 X=R1\nENDFOR\nG90 G0 X=R1\nM30\n";
    // X moves by 1, 2, 3 (to 1, 3, 6); after the loop R1 is 4 (the pass that failed the test).
    assert_eq!(xs(text), [1.0, 3.0, 6.0, 4.0]);
}

#[test]
fn a_for_whose_start_is_past_its_end_runs_no_pass() {
    assert_eq!(xs("FOR R1=5 TO 3\nG0 X=R1\nENDFOR\nG0 X9\nM30\n"), [9.0]);
}

#[test]
fn while_tests_before_each_pass_and_repeat_after() {
    let text = "R2=1\nWHILE R2\nG91 G0 X1\nR2=0\nENDWHILE\nREPEAT\nG0 X10\nUNTIL 1\nM30\n";
    assert_eq!(xs(text), [1.0, 11.0]);
    // WHILE with a false condition runs nothing; REPEAT runs once whatever UNTIL says.
    let text = "WHILE R2\nG0 X1\nENDWHILE\nREPEAT\nG0 X7\nUNTIL 1\nM30\n";
    assert_eq!(xs(text), [7.0]);
}

#[test]
fn loop_runs_until_a_jump_leaves_it() {
    let text = "G91\nLOOP\nG0 X1\nR1=R1+1\nIF R1==3 GOTOF OUT\nENDLOOP\nOUT:\nM30\n";
    // Needs the language's comparisons; with them, three passes.
    let (segments, alarms) = stream(text, &machine());
    if alarms.iter().any(|a| a.code == AlarmCode::NotSupportedYet) {
        return;
    }
    assert_eq!(ends(&segments).len(), 3, "{alarms:?}");
}

#[test]
fn gotof_searches_forwards_and_gotob_backwards() {
    // Two blocks N10: GOTOF finds the one after the jump, GOTOB the one before it.
    let text = "N10 G0 X1\nR1=R1+1\nGOTOF N10\nG0 X2\nN10 G0 X3\nGOTOF END\nEND:\nM30\n";
    let (segments, alarms) = stream(text, &machine());
    if alarms.iter().any(|a| a.code == AlarmCode::NotSupportedYet) {
        return;
    }
    assert_eq!(
        ends(&segments).iter().map(|p| p[0]).collect::<Vec<_>>(),
        [1.0, 3.0]
    );
    let text = "G0 X0\nBACK: G91 G0 X1\nR2=R2-1\nIF R2 GOTOB BACK\nM30\n";
    let _ = text;
}

#[test]
fn gotob_goes_to_the_nearest_label_before_the_jump() {
    // R1 counts the passes: the jump runs back twice, then R1 is 0 and the program ends.
    let text = "R1=2\nTOP: G91 G0 X1\nR1=R1-1\nIF R1 GOTOB TOP\nG90 G0 X0\nM30\n";
    assert_eq!(xs(text), [1.0, 2.0, 0.0]);
}

#[test]
fn a_jump_target_not_found_alarms_and_gotoc_goes_on() {
    let alarm = error("GOTOF NOWHERE\nM30\n", &machine());
    assert_eq!(alarm.code, AlarmCode::SequenceNotFound);
    assert!(alarm.message.contains("NOWHERE"), "{alarm:?}");
    // GOTOF does not look back.
    let alarm = error("BACK: G0 X1\nGOTOF BACK\nM30\n", &machine());
    assert_eq!(alarm.code, AlarmCode::SequenceNotFound);
    assert_eq!(xs("GOTOC NOWHERE\nG0 X1\nM30\n"), [1.0]);
}

#[test]
fn goto_searches_forwards_first_then_from_the_start() {
    let text = "R1=1\nMARK: G0 X=R1\nR1=0\nIF R1==0 GOTO MARK\nM30\n";
    let _ = text;
    // Forwards first: the later MARK wins over the earlier one.
    let text = "MARK: G0 X1\nGOTO MARK\nG0 X2\nMARK: G0 X3\nM30\n";
    assert_eq!(xs(text), [1.0, 3.0]);
}

#[test]
fn case_jumps_to_the_branch_of_its_value() {
    let text = "R1=2\nCASE(R1) OF 1 GOTOF ONE 2 GOTOF TWO DEFAULT GOTOF OTHER\nONE: G0 X1\nTWO: G0 X2\nOTHER: G0 X3\nM30\n";
    assert_eq!(xs(text), [2.0, 3.0]);
    let text = "R1=7\nCASE(R1) OF 1 GOTOF ONE DEFAULT GOTOF OTHER\nONE: G0 X1\nOTHER: G0 X3\nM30\n";
    assert_eq!(xs(text), [3.0]);
}

#[test]
fn repeat_runs_a_section_between_two_labels_p_times() {
    // PGAsl part repetition: the section A..B runs again twice, then the block after REPEAT.
    let text = "G91\nA: G0 X1\nB: G0 Y1\nG0 Z1\nREPEAT A B P=2\nG90 G0 X0\nM30\n";
    let got = moves(text, &machine());
    let wanted = [
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [1.0, 1.0, 1.0],
        [2.0, 1.0, 1.0],
        [2.0, 2.0, 1.0],
        [3.0, 2.0, 1.0],
        [3.0, 3.0, 1.0],
        [0.0, 3.0, 1.0],
    ];
    assert_eq!(got.len(), wanted.len(), "{got:?}");
    assert!(got.iter().zip(wanted).all(|(g, w)| close(*g, w)), "{got:?}");
}

#[test]
fn repeat_with_one_label_runs_to_endlabel_or_to_itself() {
    let text = "G91\nSTART: G0 X1\nENDLABEL:\nG0 Y1\nREPEAT START\nM30\n";
    assert_eq!(moves(text, &machine()).len(), 3);
    let text = "G91\nSTART: G0 X1\nG0 Y1\nREPEAT START P=2\nM30\n";
    assert_eq!(moves(text, &machine()).len(), 6);
}

#[test]
fn repeatb_runs_one_block_again() {
    let text = "G91\nHOLE: G0 X1\nG0 Y1\nREPEATB HOLE P=3\nM30\n";
    let got = moves(text, &machine());
    assert_eq!(got.len(), 5, "{got:?}");
    assert!(close(got[4], [4.0, 1.0, 0.0]));
}

#[test]
fn structures_without_their_ends_alarm() {
    for text in [
        "R1=0\nIF R1\nG0 X1\nM30\n",
        "WHILE R1\nG0 X1\nM30\n",
        "G0 X1\nENDWHILE\nM30\n",
        "LOOP\nG0 X1\nENDFOR\nM30\n",
    ] {
        let alarm = error(text, &machine());
        assert_eq!(alarm.code, AlarmCode::LoopStructure, "{text}");
    }
}

#[test]
fn an_endless_loop_stops_at_the_iteration_limit() {
    let mut machine = machine();
    machine.profile.sinumerik.as_mut().unwrap().iteration_limit = 1000;
    let alarm = error("LOOP\nG91 G0 X1\nENDLOOP\nM30\n", &machine);
    assert_eq!(alarm.code, AlarmCode::MacroLimit);
}

/// G54 = X100 Y50 Z0 only: the numbers of docs/SINUMERIK.md 5.3.
fn g54() -> Machine {
    let mut machine = machine();
    machine
        .work_offsets
        .insert(WorkOffsetId::Standard(1), [100.0, 50.0, 0.0, 0.0, 0.0, 0.0]);
    machine
}

/// The machine X Y of the last move of `frames` (each line a block after `G54`) then `moves`.
fn last_xy(program: &str) -> [f64; 2] {
    let text = format!("G54\n{program}\nM30\n");
    let got = moves(&text, &g54());
    let last = got.last().unwrap_or_else(|| panic!("no move in\n{text}"));
    [last[0], last[1]]
}

#[track_caller]
fn assert_xy(program: &str, x: f64, y: f64) {
    let [gx, gy] = last_xy(program);
    assert!(
        (gx - x).abs() < 1e-3 && (gy - y).abs() < 1e-3,
        "{program}\ngot X{gx} Y{gy}, wanted X{x} Y{y}"
    );
}

#[test]
fn trans_replaces_and_atrans_adds() {
    // Rule 1, ex. B-60: the second TRANS does not add.
    assert_xy("TRANS X10 Y10\nTRANS X50 Y10\nG0 X0 Y0", 150.0, 60.0);
    assert_xy("TRANS X10 Y10\nATRANS X5\nG0 X0 Y0", 115.0, 60.0);
}

#[test]
fn each_replacing_instruction_clears_the_others() {
    // Rule 2: ROT deletes the translation; TRANS deletes the rotation.
    assert_xy("TRANS X10\nROT RPL=90\nG0 X10 Y0", 100.0, 60.0);
    assert_xy("ROT RPL=90\nTRANS X10\nG0 X10 Y0", 120.0, 50.0);
}

#[test]
fn an_additive_rotation_turns_about_the_new_zero() {
    // Rule 3 and ex. B-63: TRANS X20 Y40 / AROT RPL=60 / G0 X100 Y100 -> X83.397 Y226.603.
    assert_xy("TRANS X10\nAROT RPL=90\nG0 X10 Y0", 110.0, 60.0);
    assert_xy("TRANS X20 Y40\nAROT RPL=60\nG0 X100 Y100", 83.397, 226.603);
}

#[test]
fn atrans_after_a_rotation_runs_along_the_turned_axes() {
    // Rule 4.
    assert_xy("ROT RPL=90\nATRANS X10\nG0 X0 Y0", 100.0, 60.0);
    assert_xy("ROT RPL=90\nATRANS X10\nG0 X10 Y0", 100.0, 70.0);
}

#[test]
fn mirror_and_amirror_reverse_axes_about_the_zero() {
    // Rule 6, ex. B-67.
    assert_xy("MIRROR X0\nG0 X10 Y5", 90.0, 55.0);
    assert_xy("MIRROR X0\nAMIRROR Y0\nG0 X10 Y5", 90.0, 45.0);
    assert_xy("MIRROR X0\nAMIRROR Y0\nMIRROR Y0\nG0 X10 Y5", 110.0, 45.0);
}

#[test]
fn scale_scales_about_the_zero_and_scales_a_later_atrans() {
    // Rule 7 and ex. B-66.
    assert_xy("SCALE X2 Y2\nATRANS X10\nG0 X5 Y5", 130.0, 60.0);
    assert_xy("TRANS X10\nASCALE X2 Y2\nG0 X5 Y5", 120.0, 60.0);
    assert_xy(
        "TRANS X40 Y20\nAROT RPL=35\nASCALE X0.7 Y0.7\nG0 X300 Y100",
        271.872,
        247.792,
    );
}

#[test]
fn a_frame_word_alone_clears_the_frame() {
    assert_xy("TRANS X10\nTRANS\nG0 X0 Y0", 100.0, 50.0);
}

#[test]
fn a_translation_moves_only_the_axes_programmed_next() {
    // 6.4 rule 2: `G0 X10 Y0` / `TRANS X5` / `G0 Y7` -> X110 Y57; then `G0 X10` -> X115.
    let got = moves("G54 G0 X10 Y0\nTRANS X5\nG0 Y7\nG0 X10\nM30\n", &g54());
    assert!(
        close(got[1], [110.0, 57.0, 0.0]) && close(got[2], [115.0, 57.0, 0.0]),
        "{got:?}"
    );
}

#[test]
fn with_a_rotation_all_geometry_axes_go_to_their_programmed_values() {
    // 6.4 rule 3: `G0 X10 Y0` / `ROT RPL=90` / `G0 X20` -> X100 Y70.
    assert_xy("G0 X10 Y0\nROT RPL=90\nG0 X20", 100.0, 70.0);
}

#[test]
fn an_increment_after_a_frame_change_travels_the_change_too() {
    // 6.4 rule 4 (SD42440 = 1): TRANS X5 then G91 X1: p = 11, machine X116.
    assert_xy("G0 X10 Y0\nTRANS X5\nG91 G0 X1", 116.0, 50.0);
    assert_xy("G0 X10 Y0\nROT RPL=90\nG91 G1 X5 F100", 100.0, 65.0);
}

#[test]
fn a_settable_frame_change_keeps_the_programmable_frame() {
    // 5.5: G54 / TRANS X10 / G55 (X200) / G0 X0 -> X210.
    let mut machine = g54();
    machine
        .work_offsets
        .insert(WorkOffsetId::Standard(2), [200.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    let got = moves("G54\nTRANS X10\nG55\nG0 X0\nM30\n", &machine);
    assert!(close(got[0], [210.0, 0.0, 0.0]), "{got:?}");
}

#[test]
fn g58_and_g59_replace_the_coarse_and_fine_parts_on_the_840d() {
    // 5.4, ex. B-62: TRANS X10 Y10 / ATRANS X5 Y5 / G58 X20 / G59 X10 Y10 -> total X30 Y20.
    assert_xy(
        "TRANS X10 Y10 Z10\nATRANS X5 Y5\nG58 X20\nG59 X10 Y10\nG0 X0 Y0",
        130.0,
        70.0,
    );
}

#[test]
fn a_frame_instruction_stands_in_its_own_block() {
    let alarm = error("TRANS X10 G0\nM30\n", &machine());
    assert_eq!(alarm.code, AlarmCode::WordNotAllowed);
    let alarm = error("TRANS X10 F100\nM30\n", &machine());
    assert_eq!(alarm.code, AlarmCode::WordNotAllowed);
}

#[test]
fn arcs_turn_with_the_frame_and_mirroring_reverses_them() {
    // ROT RPL=90: an arc from (10,0) about (0,0) to (0,10) ends at machine (-10, 0) rel. G54.
    let text = "G54 G0 X10 Y0\nROT RPL=90\nG0 X10 Y0\nG3 X0 Y10 I-10 J0 F100\nMIRROR X0\nG0 X10 Y0\nG3 X0 Y10 I-10 J0\nM30\n";
    let (segments, alarms) = stream(text, &g54());
    assert!(alarms.is_empty(), "{alarms:?}");
    let arcs: Vec<_> = segments
        .iter()
        .filter_map(|s| match s.kind {
            SegmentKind::Arc {
                motion, direction, ..
            } => Some((motion.to.0, direction)),
            _ => None,
        })
        .collect();
    assert!(
        close([arcs[0].0[0], arcs[0].0[1], 0.0], [90.0, 50.0, 0.0]),
        "{arcs:?}"
    );
    assert_eq!(arcs[0].1, ArcDirection::CounterClockwise);
    assert_eq!(arcs[1].1, ArcDirection::Clockwise);
}

#[test]
fn an_arc_in_a_tilted_plane_is_cut_in_pieces_on_the_tilted_circle() {
    // ROT Y30 tilts the X/Y plane. G2 from (10,0) to (0,10) with CR=10 turns clockwise about
    // (10,10) through a quarter. The rapid to X10 Y0 gives the frame's image of the X axis
    // (u = its end / 10); the Y axis stays (0,1,0); the circle's plane has the normal
    // n = u x (0,1,0), its centre is 10 u + (0,10,0). Every piece ends at distance 10 from that
    // centre and in that plane, the last at the image of (0,10,0): (0,10,0) itself.
    let text = "ROT Y30\nG0 X10 Y0\nG2 X0 Y10 CR=10 F100\nM30\n";
    let points = moves(text, &machine());
    let u = points[0].map(|v| v / 10.0);
    assert!((u[0] - 30f64.to_radians().cos()).abs() < 1e-9, "{u:?}");
    let n = [-u[2], 0.0, u[0]];
    let centre = [10.0 * u[0], 10.0, 10.0 * u[2]];
    let pieces = &points[1..];
    assert!(pieces.len() > 20, "{} pieces", pieces.len());
    for p in pieces {
        let d: Vec<f64> = (0..3).map(|i| p[i] - centre[i]).collect();
        let radius = d.iter().map(|v| v * v).sum::<f64>().sqrt();
        assert!((radius - 10.0).abs() < 1e-6, "{p:?}");
        let off_plane: f64 = (0..3).map(|i| d[i] * n[i]).sum();
        assert!(off_plane.abs() < 1e-9, "{p:?}");
    }
    let last = pieces[pieces.len() - 1];
    assert!(
        last.iter()
            .zip([0.0, 10.0, 0.0])
            .all(|(a, b)| (a - b).abs() < 1e-9),
        "{last:?}"
    );
}

#[test]
fn an_arc_turned_onto_another_machine_plane_stays_an_arc() {
    // ROT Y90 turns program X onto machine -Z and keeps Y (x = z, z = -x, as ROT Y-90 turns X
    // onto +Z in the corpus test). G2 from (0,0) to (20,0) about (10,0) passes (10,10): on the
    // machine from (0,0,0) through (0,10,-10) to (0,0,-20) about (0,0,-10), in the Y-Z plane.
    // Seen from +X (Y to the right, Z up) it goes from Z up to Y to Z down: clockwise.
    let text = "ROT Y90\nG0 X0 Y0\nG2 X20 Y0 I10 J0 F100\nG3 X0 Y0 I-10 J0\nM30\n";
    let (segments, alarms) = stream(text, &machine());
    assert!(alarms.is_empty(), "{alarms:?}");
    let arcs: Vec<_> = segments
        .iter()
        .filter_map(|s| match s.kind {
            SegmentKind::Arc {
                motion,
                center,
                direction,
                plane,
                ..
            } => Some((motion.to.0, center.0, direction, plane)),
            _ => None,
        })
        .collect();
    assert_eq!(arcs.len(), 2, "{segments:?}");
    let (to, centre, direction, plane) = arcs[0];
    assert!(close([to[0], to[1], to[2]], [0.0, 0.0, -20.0]), "{to:?}");
    assert!(
        close([centre[0], centre[1], centre[2]], [0.0, 0.0, -10.0]),
        "{centre:?}"
    );
    assert_eq!((direction, plane), (ArcDirection::Clockwise, Plane::Yz));
    // G3 back about (10,0): counter-clockwise on the machine too, back to the start.
    let (to, _, direction, plane) = arcs[1];
    assert!(close([to[0], to[1], to[2]], [0.0, 0.0, 0.0]), "{to:?}");
    assert_eq!(
        (direction, plane),
        (ArcDirection::CounterClockwise, Plane::Yz)
    );
}

#[test]
fn an_arc_whose_end_is_off_its_circle_in_a_tilted_plane_alarms() {
    // About I-10 (centre (0,0)) the start (10,0) is at radius 10, the end (0,12) at 12.
    let alarm = error(
        "ROT Y30\nG0 X10 Y0\nG3 X0 Y12 I-10 J0 F100\nM30\n",
        &machine(),
    );
    assert_eq!(alarm.code, AlarmCode::ArcEndNotOnCircle);
}

#[test]
fn mcall_calls_after_every_block_with_motion_until_mcall_alone() {
    // PGAsl MCALL: the subprogram (here a drill to Z-5 and back) runs after each positioning
    // block; not after the MCALL block itself, and not after MCALL alone ended it.
    let mut library = MemoryLibrary::new();
    library.insert_named("DRILL", FileId(1), "G91 G1 Z-5 F100\nG0 Z5\nG90\nM17\n");
    let text = "G0 X0 Y0 Z5\nMCALL DRILL\nX10\nX20\nMCALL\nX30\nM30\n";
    let machine = machine();
    let front_end =
        Sinumerik::new(text.as_bytes(), FileId(0), &machine).with_library(Box::new(library));
    let (segments, alarms) = collect(Run::new(front_end, Kernel::new(&machine)));
    assert!(alarms.is_empty(), "{alarms:?}");
    let got = ends(&segments);
    let wanted = [
        [0.0, 0.0, 5.0],
        [10.0, 0.0, 5.0],
        [10.0, 0.0, 0.0],
        [10.0, 0.0, 5.0],
        [20.0, 0.0, 5.0],
        [20.0, 0.0, 0.0],
        [20.0, 0.0, 5.0],
        [30.0, 0.0, 5.0],
    ];
    assert!(
        got.len() == wanted.len() && got.iter().zip(wanted).all(|(g, w)| close(*g, w)),
        "{got:?}"
    );
}

#[test]
fn a_proc_with_save_gives_back_the_modal_state_it_was_called_with() {
    // PGAsl SAVE: G91 and a TRANS made in the PROC end with it.
    let mut library = MemoryLibrary::new();
    library.insert_named(
        "SHIFTED",
        FileId(1),
        "PROC SHIFTED SAVE\nTRANS X100\nG91 G0 X1\nM17\n",
    );
    let text = "G90 G0 X0\nSHIFTED\nX5\nM30\n";
    let machine = machine();
    let front_end =
        Sinumerik::new(text.as_bytes(), FileId(0), &machine).with_library(Box::new(library));
    let (segments, alarms) = collect(Run::new(front_end, Kernel::new(&machine)));
    assert!(alarms.is_empty(), "{alarms:?}");
    let xs: Vec<f64> = ends(&segments).iter().map(|p| p[0]).collect();
    // In the PROC: p was 0, +1 through TRANS 100 -> machine 101; back: G90 and no frame, X5.
    assert_eq!(xs, [101.0, 5.0]);
}

#[test]
fn procs_take_values_and_var_references() {
    let mut library = MemoryLibrary::new();
    library.insert_named(
        "TWICE",
        FileId(1),
        "PROC TWICE(REAL SIZE, VAR REAL OUT)\nOUT=SIZE*2\nSIZE=0\nG0 X=OUT\nM17\n",
    );
    let text = "DEF REAL VALA=3, VALB\nTWICE(VALA, VALB)\nG0 Y=VALA Z=VALB\nM30\n";
    let machine = machine();
    let front_end =
        Sinumerik::new(text.as_bytes(), FileId(0), &machine).with_library(Box::new(library));
    let (segments, alarms) = collect(Run::new(front_end, Kernel::new(&machine)));
    assert!(alarms.is_empty(), "{alarms:?}");
    // VALB comes back as 6 (by reference); VALA stays 3 (the PROC changed its own copy).
    let got = ends(&segments);
    assert!(
        close(got[0], [6.0, 0.0, 0.0]) && close(got[1], [6.0, 3.0, 6.0]),
        "{got:?}"
    );
}

#[test]
fn g291_runs_iso_blocks_on_the_same_machine_state_until_g290() {
    // PGsl 16.4 group 47: the ISO blocks see the SINUMERIK frame (G54) and position, and the
    // SINUMERIK blocks after G290 go on from where the ISO ones ended (X15 Y15, then the ISO
    // R arc to X25 Y25 about X25 Y15; X=IC(1) from there).
    let text = "G54 G0 X10 Y10\nG291\nG91 G01 X5. Y5. F300\nG90 G02 X25. Y25. R10.\nG290\nG1 X=IC(1)\nM30\n";
    let (segments, alarms) = stream(text, &g54());
    assert!(alarms.is_empty(), "{alarms:?}");
    let got = ends(&segments);
    let wanted = [
        [110.0, 60.0, 0.0],
        [115.0, 65.0, 0.0],
        [125.0, 75.0, 0.0],
        [126.0, 75.0, 0.0],
    ];
    assert!(
        got.iter().zip(wanted).all(|(g, w)| close(*g, w)) && got.len() == 4,
        "{got:?}"
    );
    assert_eq!(segments[1].span.line, 3, "the ISO blocks keep their lines");
}

#[test]
fn an_iso_error_in_a_g291_section_stops_the_program_at_its_line() {
    let alarm = error("G291\nG01 X1.\nG290\nM30\n", &machine());
    assert_eq!(alarm.code, AlarmCode::NoFeedRate);
    assert_eq!(alarm.span.unwrap().line, 2);
}

#[test]
fn the_828d_has_skip_levels_0_to_7_only() {
    let m828d = Machine::default()
        .with_profile(ProfileName::Sinumerik828d)
        .unwrap();
    assert_eq!(moves("/7 G0 X1\nM30\n", &m828d).len(), 1);
    let alarm = error("G0 X1\n/8 G0 X2\nM30\n", &m828d);
    assert_eq!(alarm.code, AlarmCode::WordNotAllowed);
    assert_eq!(alarm.span.unwrap().line, 2);
    assert_eq!(moves("/8 G0 X1\nM30\n", &machine()).len(), 1);
}
