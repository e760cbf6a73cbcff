//! Tools with geometry, material removal and its events: consumers of the motion stream through
//! the library pipeline, on ISO and SINUMERIK programs alike.

use std::collections::HashMap;
use vcnc::machine::DEFAULT_MACHINE_TOML;
use vcnc::motion::{ToolShape, ToolTip};
use vcnc::pipeline::Pipeline;
use vcnc::plan::PlanOptions;
use vcnc::sim::{mesh, Simulation};
use vcnc::{AlarmCode, Item, Machine, SegmentKind};

/// The default machine with these `[[tool_shapes]]` entries.
fn machine_with_tools(tools: &str) -> Machine {
    Machine::from_toml(&format!("{DEFAULT_MACHINE_TOML}\n{tools}")).unwrap()
}

/// The shapes every tool change of `text` (file `name`) carries, through the pipeline.
fn changes(text: &str, name: &str, machine: &Machine) -> Vec<(u32, Option<ToolShape>)> {
    let mut stream = Pipeline::new(machine).open_text(text, name);
    let mut changes = Vec::new();
    stream.for_each_timed(PlanOptions::default(), |items, _| {
        for item in items {
            if let Ok(Item::Segment(segment)) = item {
                if let SegmentKind::ToolChange { tool, shape, .. } = segment.kind {
                    changes.push((tool, shape));
                }
            }
        }
        true
    });
    changes
}

const TWO_TOOLS: &str = r#"
[[tool_shapes]]
t = 1
type = "ball"
diameter = 6.0
cutting_length = 12.0
[[tool_shapes]]
t = 2
type = "drill"
diameter = 8.5
point_angle = 118.0
"#;

#[test]
fn a_tool_change_carries_the_shape_of_the_machine_files_tool() {
    let machine = machine_with_tools(TWO_TOOLS);
    let text = "T1 M6\nG0 X0 Y0\nT2 M6\nT3 M6\nM30\n";
    let changes = changes(text, "tools.nc", &machine);
    assert_eq!(changes.len(), 3);
    assert_eq!(changes[0].1.unwrap().tip, ToolTip::Ball);
    assert_eq!(changes[0].1.unwrap().cutting_length, 12.0);
    assert_eq!(
        changes[1].1.unwrap().tip,
        ToolTip::Drill { point_angle: 118.0 }
    );
    // Tool 3 is not in the table: no shape (a consumer takes a flat mill of its radius).
    assert_eq!(changes[2], (3, None));
}

#[test]
fn a_sinumerik_tool_change_carries_the_shape_too() {
    let machine = machine_with_tools(TWO_TOOLS);
    let text = "T2 D1\nM6\nG0 X0 Y0 Z10\nM30\n";
    let changes = changes(text, "TOOLS.MPF", &machine);
    assert_eq!(changes.len(), 1);
    assert_eq!(changes[0].0, 2);
    assert_eq!(changes[0].1.unwrap().diameter, 8.5);
}

/// Runs `text` through the pipeline into a simulation of `stock` in cells of `cell` mm.
fn simulate(text: &str, machine: &Machine, stock: [[f64; 3]; 2], cell: f64) -> Simulation {
    simulate_on(text, machine, vcnc::sim::HeightField::new(stock, cell))
}

const FLAT_10: &str = r#"
[[tool_shapes]]
t = 1
type = "flat"
diameter = 10.0
cutting_length = 20.0
"#;

#[test]
fn a_slot_of_a_flat_mill_removes_its_closed_form_volume() {
    // A flat mill of radius 5 plunged to Z-2 at X0 and moved 100 mm along X: the slot is a
    // 100 x 10 rectangle with two half discs at its ends, 2 deep: (100 * 10 + pi * 25) * 2
    // = 2157.08 mm^3.
    let machine = machine_with_tools(FLAT_10);
    let text = "T1 M6\nS5000 M3\nG0 X0 Y0 Z5.\nG1 Z-2. F200.\nX100.\nG0 Z5.\nM30\n";
    let stock = [[-10.0, -10.0, -5.0], [110.0, 10.0, 0.0]];
    let simulation = simulate(text, &machine, stock, 0.1);
    let expected = (100.0 * 10.0 + std::f64::consts::PI * 25.0) * 2.0;
    let removed = simulation.removed();
    assert!(
        (removed - expected).abs() < expected * 0.005,
        "{removed} vs {expected}"
    );
    // What the grid lost is what the tool removed.
    let grid = simulation.grid();
    assert!((grid.stock_volume() - grid.volume() - removed).abs() < 1e-6 * expected);
    assert_eq!(simulation.events().kept, vec![]);
    let times = simulation.times();
    assert!(times.cutting > 0.0 && times.rapid > 0.0, "{times:?}");
}

#[test]
fn a_ball_groove_has_the_balls_profile() {
    // A ball of radius 3 with its tip at Z-3 along 50 mm of X: its centre runs on the stock's
    // top, so the groove is half a cylinder and half a sphere:
    // pi * 9 * 50 / 2 + 2 / 3 * pi * 27 = 763.41 mm^3. Across it, 1.5 mm off the axis, the
    // floor is at -3 + (3 - sqrt(9 - 1.5^2)) = -2.598.
    let machine = machine_with_tools("[[tool_shapes]]\nt = 2\ntype = \"ball\"\ndiameter = 6.0\n");
    let text = "T2 M6\nS5000 M3\nG0 X0 Y0 Z5.\nG1 Z-3. F200.\nX50.\nG0 Z5.\nM30\n";
    let stock = [[-5.0, -5.0, -6.0], [55.0, 5.0, 0.0]];
    let cell = 0.05;
    let simulation = simulate(text, &machine, stock, cell);
    let pi = std::f64::consts::PI;
    let expected = pi * 9.0 * 50.0 / 2.0 + 2.0 / 3.0 * pi * 27.0;
    let removed = simulation.removed();
    assert!(
        (removed - expected).abs() < expected * 0.005,
        "{removed} vs {expected}"
    );
    let grid = simulation.grid();
    // Cell 500 along X is at 20.025; cell 130 along Y at 1.525 from the axis.
    let floor = grid.height(500, 130);
    let y = grid.center(500, 130)[1];
    let expected_floor = -3.0 + (3.0 - (9.0 - y * y).sqrt());
    assert!(
        (floor - expected_floor).abs() < 1e-4,
        "{floor} vs {expected_floor}"
    );
}

#[test]
fn a_rapid_into_the_stock_is_an_alarm_with_its_block_and_depth() {
    // Line 4 rapids to Z-1.5 inside the stock whose top is Z0: 1.5 mm deep.
    let machine = machine_with_tools(FLAT_10);
    let text = "T1 M6\nS5000 M3\nG0 X0 Y0 Z5.\nG0 Z-1.5\nG0 Z5.\nM30\n";
    let stock = [[-10.0, -10.0, -5.0], [10.0, 10.0, 0.0]];
    let simulation = simulate(text, &machine, stock, 0.25);
    let events = simulation.events();
    assert_eq!(
        events.count(AlarmCode::RapidIntoStock),
        1,
        "{:?}",
        events.kept
    );
    let alarm = &events.kept[0];
    assert_eq!(alarm.span.unwrap().line, 4);
    assert!(
        alarm.message.contains("T1 goes 1.500 mm deep"),
        "{}",
        alarm.message
    );
}

#[test]
fn flutes_too_short_a_stopped_spindle_and_a_holder_are_told() {
    let machine = machine_with_tools(
        r#"
[[tool_shapes]]
t = 1
type = "flat"
diameter = 10.0
cutting_length = 5.0
center_cutting = false
stickout = 12.0
holder = [{ length = 30.0, diameter = 30.0 }]
"#,
    );
    // Line 3 plunges (spindle off) 8 mm deep: beyond the 5 mm flutes, a plunge of a tool
    // without centre cutting, and no spindle. Line 5 goes 15 mm deep: the holder's face,
    // 12 mm above the tip, is 3 mm into the stock.
    let text = "T1 M6\nG0 X0 Y0 Z5.\nG1 Z-8. F100.\nM3 S1000\nG1 Z-15.\nG0 Z50.\nM30\n";
    let stock = [[-20.0, -20.0, -20.0], [20.0, 20.0, 0.0]];
    let simulation = simulate(text, &machine, stock, 0.5);
    let events = simulation.events();
    let line_of = |code: AlarmCode| {
        events
            .kept
            .iter()
            .find(|a| a.code == code)
            .map(|a| a.span.unwrap().line)
    };
    assert_eq!(line_of(AlarmCode::BeyondCuttingLength), Some(3));
    assert_eq!(line_of(AlarmCode::CuttingWithSpindleStopped), Some(3));
    assert_eq!(line_of(AlarmCode::PlungeWithoutCenterCutting), Some(3));
    assert_eq!(line_of(AlarmCode::HolderCollision), Some(5));
}

#[test]
fn rotary_moves_are_named_not_cut() {
    let machine = vcnc::Machine::from_toml(&format!(
        "{DEFAULT_MACHINE_TOML}\n[axes.a]\nmin = -360.0\nmax = 360.0\nrapid = 10000.0\nmax_feed = 5000.0\n"
    ))
    .unwrap();
    let text = "G0 X0 Y0 Z5.\nG1 Z-1. F100.\nG1 A90. X10.\nM30\n";
    let stock = [[-10.0, -10.0, -5.0], [20.0, 10.0, 0.0]];
    let simulation = simulate(text, &machine, stock, 0.5);
    let events = simulation.events();
    let warning = events
        .kept
        .iter()
        .find(|a| a.code == AlarmCode::NotSimulated)
        .expect("a warning for the rotary move");
    assert_eq!(warning.span.unwrap().line, 3);
}

#[test]
fn the_stl_is_watertight_and_holds_the_stock_less_the_cut() {
    let machine = machine_with_tools(FLAT_10);
    let text = "T1 M6\nS5000 M3\nG0 X0 Y0 Z5.\nG1 Z-2. F200.\nG2 X0 Y0 I10. J0\nG0 Z5.\nM30\n";
    let stock = [[-10.0, -20.0, -5.0], [30.0, 20.0, 0.0]];
    let simulation = simulate(text, &machine, stock, 0.5);
    let mut edges: HashMap<([u32; 3], [u32; 3]), i32> = HashMap::new();
    let mut volume = 0.0;
    let key = |p: [f64; 3]| p.map(|c| (c as f32).to_bits());
    mesh::for_each_triangle(simulation.grid(), |t| {
        for k in 0..3 {
            let (a, b) = (key(t[k]), key(t[(k + 1) % 3]));
            assert_ne!(a, b, "a degenerate edge");
            // Each directed edge once, and its reverse once: +1 and -1 cancel per pair.
            *edges.entry((a, b)).or_default() += 1;
        }
        // The signed volume of the tetrahedron from the origin (divergence theorem).
        let [p, q, r] = t;
        volume += (p[0] * (q[1] * r[2] - q[2] * r[1]) - p[1] * (q[0] * r[2] - q[2] * r[0])
            + p[2] * (q[0] * r[1] - q[1] * r[0]))
            / 6.0;
    });
    for (&(a, b), &count) in &edges {
        assert_eq!(count, 1, "edge used {count} times one way");
        assert_eq!(edges.get(&(b, a)), Some(&1), "edge without its twin");
    }
    let grid = simulation.grid();
    let expected = grid.stock_volume() - simulation.removed();
    assert!(
        (volume - expected).abs() < expected * 0.005,
        "{volume} vs {expected}"
    );
    let mut stl = Vec::new();
    mesh::write_stl(grid, &mut stl).unwrap();
    let count = u32::from_le_bytes(stl[80..84].try_into().unwrap()) as usize;
    assert_eq!(stl.len(), 84 + 50 * count);
}

/// Asserts that `removed` is within 0.5 % of `expected`.
fn assert_volume(removed: f64, expected: f64) {
    assert!(
        (removed - expected).abs() < expected * 0.005,
        "{removed} vs {expected} ({:+.3} %)",
        (removed / expected - 1.0) * 100.0
    );
}

#[test]
fn drilled_holes_remove_a_cylinder_and_the_points_cone() {
    // A 10 mm drill with a 90° point, its tip to Z-10 from above the stock (top Z0), twice:
    // the point is a cone 5 high (r / tan 45°), above it a cylinder 5 high:
    // 2 * (pi 25 * 5 + pi 25 * 5 / 3) = 1047.20 mm^3.
    let machine = machine_with_tools(
        "[[tool_shapes]]\nt = 3\ntype = \"drill\"\ndiameter = 10.0\npoint_angle = 90.0\n",
    );
    let text =
        "T3 M6\nS2000 M3\nG0 X0 Y0 Z10.\nG81 X0 Y0 Z-10. R2. F100.\nX20.\nG80\nG0 Z10.\nM30\n";
    let stock = [[-10.0, -10.0, -15.0], [30.0, 10.0, 0.0]];
    let simulation = simulate(text, &machine, stock, 0.1);
    let pi = std::f64::consts::PI;
    assert_volume(
        simulation.removed(),
        2.0 * (pi * 25.0 * 5.0 + pi * 25.0 * 5.0 / 3.0),
    );
    assert_eq!(simulation.events().kept, vec![]);
}

#[test]
fn a_helically_milled_bore_leaves_an_annulus() {
    // A flat mill of radius 3 on a helix of radius 5 about the origin, 1 mm down per turn to
    // Z-4, then a level turn: it clears the ring from r 2 to r 8, 4 deep:
    // pi (64 - 4) 4 = 753.98 mm^3 (the island inside r 2 stays).
    let machine = machine_with_tools("[[tool_shapes]]\nt = 1\ntype = \"flat\"\ndiameter = 6.0\n");
    let mut text = String::from("T1 M6\nS5000 M3\nG0 X5. Y0 Z1.\nG1 Z0 F300.\n");
    for turn in 1..=4 {
        text.push_str(&format!("G2 X5. Y0 Z-{turn}. I-5. J0\n"));
    }
    text.push_str("G2 X5. Y0 I-5. J0\nG0 Z5.\nM30\n");
    let stock = [[-10.0, -10.0, -6.0], [10.0, 10.0, 0.0]];
    let simulation = simulate(&text, &machine, stock, 0.1);
    let pi = std::f64::consts::PI;
    assert_volume(simulation.removed(), pi * (64.0 - 4.0) * 4.0);
}

#[test]
fn a_rectangular_pocket_is_its_rounded_rectangle() {
    // A flat mill of radius 5 zigzags over X0-40, Y0-20 in 5 mm steps, then follows the
    // rectangle's edge: it clears the rectangle widened by 5 with corners of radius 5,
    // 50 x 30 less (4 - pi) 25, 3 deep: (1500 - (4 - pi) 25) 3 = 4435.62 mm^3.
    let machine = machine_with_tools(FLAT_10);
    let mut text = String::from("T1 M6\nS5000 M3\nG0 X0 Y0 Z2.\nG1 Z-3. F300.\n");
    for (k, y) in [0.0, 5.0, 10.0, 15.0, 20.0].into_iter().enumerate() {
        let x = if k % 2 == 0 { 40.0 } else { 0.0 };
        text.push_str(&format!("G1 Y{y:.1}\nG1 X{x:.1}\n"));
    }
    text.push_str("G1 X0 Y20.\nY0\nX40.\nY20.\nX0\nG0 Z5.\nM30\n");
    let stock = [[-10.0, -10.0, -5.0], [50.0, 30.0, 0.0]];
    let simulation = simulate(&text, &machine, stock, 0.1);
    let pi = std::f64::consts::PI;
    assert_volume(simulation.removed(), (1500.0 - (4.0 - pi) * 25.0) * 3.0);
}

#[test]
fn a_sinumerik_program_cuts_the_same_slot() {
    // The slot of the first test, written for a SINUMERIK control.
    let machine = machine_with_tools(FLAT_10);
    let text = "T1 D1\nM6\nS5000 M3\nG0 X0 Y0 Z5\nG1 Z-2 F200\nX100\nG0 Z5\nM30\n";
    let stock = [[-10.0, -10.0, -5.0], [110.0, 10.0, 0.0]];
    let mut simulation = Simulation::new(stock, 0.1);
    let mut stream = Pipeline::new(&machine).open_text(text, "SLOT.MPF");
    stream.for_each_timed(PlanOptions::default(), |items, timings| {
        for (item, timing) in items.iter().zip(timings) {
            simulation.add(item.as_ref().unwrap(), timing);
        }
        true
    });
    assert_volume(
        simulation.removed(),
        (1000.0 + std::f64::consts::PI * 25.0) * 2.0,
    );
}

#[test]
fn the_stock_below_the_first_cut_has_its_top_at_that_cuts_depth() {
    // A flat mill of radius 5 feeds down from Z2 to Z-0.5 at X0 Y0, faces to X50, then cuts a
    // slot at Z-3 from X10 to X40. Extents X0..50, Y0, Z-3..2, widened by 5 + 1 mm in X and Y:
    // X -6..56, Y -6..6, bottom Z-4. The usual top is Z0 (the cuts start above it and go
    // below); the first feed across X is at Z-0.5, the top of the other rule.
    let machine = machine_with_tools(FLAT_10);
    let text = "T1 M6\nS5000 M3\nG0 X0 Y0 Z5.\nG1 Z2. F500.\nZ-0.5\nX50.\nG0 Z5.\n\
                X10.\nG1 Z-3.\nX40.\nG0 Z5.\nM30\n";
    let mut extents = vcnc::sim::CutExtents::new();
    let mut stream = Pipeline::new(&machine).open_text(text, "first_cut.nc");
    stream.for_each_timed(PlanOptions::default(), |items, _| {
        for item in items.iter().flatten() {
            extents.add(item);
        }
        true
    });
    let usual = extents.stock().unwrap();
    let close = |a: [f64; 3], b: [f64; 3]| (0..3).all(|i| (a[i] - b[i]).abs() < 1e-9);
    assert!(close(usual[0], [-6.0, -6.0, -4.0]), "{usual:?}");
    assert!(close(usual[1], [56.0, 6.0, 0.0]), "{usual:?}");
    let first = extents.stock_below_first_cut().unwrap();
    assert!(close(first[0], usual[0]), "{first:?}");
    assert!(close(first[1], [56.0, 6.0, -0.5]), "{first:?}");
}

/// The same program on a given grid.
fn simulate_on(text: &str, machine: &Machine, grid: vcnc::sim::HeightField) -> Simulation {
    let mut simulation = Simulation::on(grid);
    let mut stream = Pipeline::new(machine).open_text(text, "sim.nc");
    stream.for_each_timed(PlanOptions::default(), |items, timings| {
        for (item, timing) in items.iter().zip(timings) {
            if let Ok(item) = item {
                simulation.add(item, timing);
            }
        }
        true
    });
    simulation
}

#[test]
fn a_cylinder_stock_faced_by_one_mm_loses_a_disc() {
    // A 40 mm bar standing on Z from -20 to 0 holds pi 20^2 20 = 25132.7 mm^3. A 10 mm flat
    // mill facing 1 mm deep over the whole square X -25..25 at 8 mm steps takes a disc
    // pi 20^2 1 = 1256.6 mm^3 and nothing outside the bar.
    let bar = vcnc::sim::stock::Cylinder {
        center: [0.0, 0.0],
        diameter: 40.0,
        z: [-20.0, 0.0],
    };
    let grid = bar.grid(0.1);
    let pi = std::f64::consts::PI;
    assert_volume(grid.stock_volume(), pi * 400.0 * 20.0);
    let mut text = String::from("T1 M6\nS5000 M3\nG0 X-30. Y-25. Z5.\nG1 Z-1. F1000.\n");
    for (n, y) in (0..=7).map(|k| -25.0 + 8.0 * f64::from(k)).enumerate() {
        let x = if n % 2 == 0 { 30.0 } else { -30.0 };
        text.push_str(&format!("Y{y:.1}\nX{x:.1}\n"));
    }
    text.push_str("G0 Z5.\nM30\n");
    let simulation = simulate_on(&text, &machine_with_tools(FLAT_10), grid);
    assert_volume(simulation.removed(), pi * 400.0);
    assert_eq!(simulation.events().kept, vec![]);
}

#[test]
fn an_stl_stock_holds_what_its_mesh_encloses() {
    // A 30 x 20 x 10 box written as STL by the mesh writer and read back as the stock: 6000
    // mm^3, whatever the grid it is sampled into.
    let grid = vcnc::sim::HeightField::new([[0.0, 0.0, -10.0], [30.0, 20.0, 0.0]], 0.5);
    let mut bytes = Vec::new();
    mesh::write_stl(&grid, &mut bytes).unwrap();
    let stock = vcnc::sim::stock::Mesh::parse(&bytes).unwrap();
    let sampled = vcnc::sim::stock::stl_grid(&stock, 0.1);
    assert_volume(sampled.stock_volume(), 6000.0);
    // The same box in ASCII.
    let mut ascii = String::from("solid box\n");
    mesh::for_each_triangle(&grid, |t| {
        ascii.push_str("facet normal 0 0 0\nouter loop\n");
        for p in t {
            ascii.push_str(&format!("vertex {} {} {}\n", p[0], p[1], p[2]));
        }
        ascii.push_str("endloop\nendfacet\n");
    });
    ascii.push_str("endsolid box\n");
    let stock = vcnc::sim::stock::Mesh::parse(ascii.as_bytes()).unwrap();
    assert_volume(
        vcnc::sim::stock::stl_grid(&stock, 0.1).stock_volume(),
        6000.0,
    );
    assert!(vcnc::sim::stock::Mesh::parse(b"solid x\nvertex 1 2\n").is_err());
    assert!(vcnc::sim::stock::Mesh::parse(&[0u8; 90]).is_err());
}

#[test]
fn the_design_comparison_finds_a_planted_gouge() {
    // The design is the uncut 40 x 20 x 10 block (top Z0); the program faces nothing but cuts a
    // slot 0.2 mm deep with a 10 mm flat mill from X10 to X30 at Y10: a 0.2 mm gouge, in the
    // slot (X 5..35, Y 5..15), and no excess (the rest of the top is untouched).
    let block = [[0.0, 0.0, -10.0], [40.0, 20.0, 0.0]];
    let mut bytes = Vec::new();
    mesh::write_stl(&vcnc::sim::HeightField::new(block, 1.0), &mut bytes).unwrap();
    let design = vcnc::sim::stock::Mesh::parse(&bytes).unwrap();
    let text = "T1 M6\nS5000 M3\nG0 X10. Y10. Z5.\nG1 Z-0.2 F500.\nX30.\nG0 Z5.\nM30\n";
    let simulation = simulate(text, &machine_with_tools(FLAT_10), block, 0.1);
    let deviation = vcnc::sim::stock::deviation(simulation.grid(), &design);
    let gouge = deviation.gouge.expect("a gouge");
    assert!((gouge.amount - 0.2).abs() < 1e-4, "{gouge:?}");
    let [x, y, z] = gouge.at;
    assert!(
        (5.0..=35.0).contains(&x) && (5.0..=15.0).contains(&y),
        "{gouge:?}"
    );
    assert!(z.abs() < 1e-9, "{gouge:?}");
    let excess = deviation.excess.expect("cells on the design");
    assert!(excess.amount < 1e-4, "{excess:?}");
    // The picture: a PNG, bluest in the slot.
    let png = deviation.picture(0.025, 1.0, 400);
    assert_eq!(&png[1..4], b"PNG");
}
