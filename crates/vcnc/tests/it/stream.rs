//! The stream's contract as a consumer sees it: warnings are items and only the error stops
//! `collect`, a frame comes before the first move made in it and every move names it, and a
//! move's work coordinates come from its frame's whole map (right under rotation and cutter
//! compensation, where a translation is not).

use vcnc::motion::{FrameId, Item, WorkFrame};
use vcnc::{interpret_str, Machine, Options, Segment};

/// The items of `program` on the default machine; panics on the error.
fn items(program: &str) -> Vec<Item> {
    interpret_str(program, &Machine::default(), Options::default())
        .collect::<Result<Vec<_>, _>>()
        .unwrap_or_else(|alarm| panic!("{alarm:?}"))
}

/// Each move with the frame in force when it came (the last frame item before it).
fn moves_in_frames(items: &[Item]) -> Vec<(Segment, WorkFrame)> {
    let mut frame = None;
    let mut moves = Vec::new();
    for item in items {
        match item {
            Item::Frame(new) => frame = Some(*new),
            Item::Segment(segment) if segment.motion().is_some() => {
                let frame = frame.expect("a frame comes before the first move");
                moves.push((*segment, frame));
            }
            _ => {}
        }
    }
    moves
}

#[test]
fn warnings_are_items_and_only_the_error_stops_a_collect() {
    // Two motion codes in one block: a warning, and the run goes on to its end.
    let collected: Vec<Item> = interpret_str(
        "G0 G1 X1. F100.\nM30\n",
        &Machine::default(),
        Options::default(),
    )
    .collect::<Result<_, _>>()
    .expect("a warning does not stop the run");
    assert_eq!(collected.iter().filter_map(Item::warning).count(), 1);
    assert!(collected.iter().filter_map(Item::segment).count() >= 2);
}

#[test]
fn every_move_names_the_frame_that_came_before_it() {
    let program = "G90 G54 G0 X0 Y0 Z5.\n\
                   G10 L2 P2 X100.\n\
                   G1 X1. F100.\n\
                   G55 G0 X1.\n\
                   G92 X0\n\
                   G0 X5.\n\
                   G10 L10 P1 R50.\n\
                   G43 H1 G0 Z5.\n\
                   G68 X0 Y0 R90.\n\
                   G0 X5.\n\
                   M30\n";
    let items = items(program);
    let moves = moves_in_frames(&items);
    let ids: Vec<u32> = moves.iter().map(|(_, frame)| frame.id.0).collect();
    // The write to G55 while G54 is in use moves nothing: no frame for it. G55, G92, G43 H1 and
    // G68 each bring one, numbered in order.
    assert_eq!(ids, [0, 0, 1, 2, 3, 4], "{items:#?}");
    for (segment, frame) in &moves {
        let motion = segment.motion().unwrap();
        assert_eq!(motion.frame, frame.id);
        // The map takes the end point back where the move's own offset says (exactly on a
        // translation, to rounding under the rotation).
        let work = frame.transform.program_map().to_program(motion.to.xyz());
        for (w, e) in work.iter().zip(motion.work_to()) {
            assert!((w - e).abs() < 1e-9, "{work:?} {segment:?}");
        }
    }
    // G55 is G54 moved by X100 (both zero on the default machine but for the write).
    let (g54, g55) = (moves[1].1.transform, moves[2].1.transform);
    assert_eq!(g55.translation[0] - g54.translation[0], 100.0);
    // G43 H1: the length vector is the register's 50 mm, in the map and beside it.
    let length = moves[4].1;
    assert_eq!(length.tool_length, [0.0, 0.0, 50.0]);
    assert_eq!(length.transform.translation[2] - g55.translation[2], 50.0);
    assert!(length.transform.is_translation());
    // G68 R90: program X runs along machine Y.
    let turned = moves[5].1.transform;
    assert_eq!(
        turned.linear,
        [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]
    );
    assert_eq!(moves[5].0.motion().unwrap().frame, FrameId(4));
}

#[test]
fn work_coordinates_under_rotation_and_compensation_come_from_the_frame() {
    // A cut along program X at Y0, turned by 90 degrees, with the tool (radius 5) on the left:
    // its centre runs along program Y5, so the cut ends at program (20, 5), machine (-5, 20).
    // The move's own offset is taken where the programmed end is, (20, 0): through it, the end
    // would read (15, 0).
    let program = "G90 G17 G54 G0 X0 Y-10. Z0\n\
                   G10 L12 P1 R5.\n\
                   G68 X0 Y0 R90.\n\
                   G41 D1 G1 X0 Y0 F100.\n\
                   X20.\n\
                   G40 X30. Y-10.\n\
                   G69\n\
                   M30\n";
    let items = items(program);
    let (cut, frame) = moves_in_frames(&items)
        .into_iter()
        .find(|(segment, _)| segment.span.line == 5)
        .expect("the cut along X");
    let motion = cut.motion().unwrap();
    let machine = motion.to.xyz();
    assert!((machine[0] + 5.0).abs() < 1e-9 && (machine[1] - 20.0).abs() < 1e-9);
    let work = frame.transform.program_map().to_program(machine);
    assert!(
        (work[0] - 20.0).abs() < 1e-9 && (work[1] - 5.0).abs() < 1e-9,
        "{work:?}"
    );
    let by_offset = motion.work_to();
    assert!((by_offset[0] - 20.0).abs() > 1.0, "{by_offset:?}");
}
