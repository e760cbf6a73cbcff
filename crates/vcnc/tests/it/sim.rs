//! Tools with geometry, material removal and its events: consumers of the motion stream through
//! the library pipeline, on ISO and SINUMERIK programs alike.

use vcnc::machine::DEFAULT_MACHINE_TOML;
use vcnc::motion::{ToolShape, ToolTip};
use vcnc::pipeline::Pipeline;
use vcnc::plan::PlanOptions;
use vcnc::{Item, Machine, SegmentKind};

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
