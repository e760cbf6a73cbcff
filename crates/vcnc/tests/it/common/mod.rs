//! Helpers shared by the integration tests.
#![allow(dead_code, unreachable_pub)]

pub mod contour;
pub mod corpus;
pub mod example_checks;
pub mod lcnc_canon;
pub mod plan;
pub mod plane;
pub mod shared;
pub mod sinumerik;
pub mod sinumerik_machines;
pub mod variables;

pub(crate) use shared::shared_dir;

use vcnc::{interpret_bytes, Alarm, Machine, Options, Segment};

/// The default machine on `profile`, with a C axis turning the part (for G12.1).
pub fn with_c_axis(profile: vcnc::ProfileName) -> Machine {
    let mut machine = Machine::default()
        .with_profile(profile)
        .expect("every built-in profile fits the default machine");
    machine.axes[vcnc::Axis::C.index()] = Some(rotary_axis());
    machine
}

/// A rotary axis without travel limits, 36000 deg/min.
pub fn rotary_axis() -> vcnc::machine::AxisConfig {
    vcnc::machine::AxisConfig {
        min: -1.0e6,
        max: 1.0e6,
        rapid: 36000.0,
        max_feed: 36000.0,
        acceleration: 2000.0,
        jerk: f64::INFINITY,
    }
}

/// Everything a run produced, split into segments and alarms.
pub struct Run {
    pub segments: Vec<Segment>,
    pub alarms: Vec<Alarm>,
}

impl Run {
    /// The first error alarm, if the run stopped with one.
    pub fn error(&self) -> Option<&Alarm> {
        self.alarms.iter().find(|a| a.is_error())
    }
}

/// Runs a program held in memory to its end.
pub fn run(text: &[u8], machine: &Machine, options: Options) -> Run {
    collect(interpret_bytes(text, machine, options))
}

/// Runs a program held in memory to its end, with the programs of `library` to call.
#[allow(dead_code)]
pub fn run_with_library(
    text: &[u8],
    machine: &Machine,
    options: Options,
    library: Box<dyn vcnc::interp::ProgramLibrary>,
) -> Run {
    collect(interpret_bytes(text, machine, options).with_library(library))
}

/// Everything `items` yields, split into segments and alarms (warnings and the error); the
/// frames are left out.
pub fn collect(items: impl Iterator<Item = vcnc::StreamItem>) -> Run {
    let mut segments = Vec::new();
    let mut alarms = Vec::new();
    for item in items {
        match item {
            Ok(vcnc::Item::Segment(segment)) => segments.push(segment),
            Ok(vcnc::Item::Frame(_)) => {}
            Ok(vcnc::Item::Warning(alarm)) | Err(alarm) => alarms.push(alarm),
        }
    }
    Run { segments, alarms }
}

/// The segments of a stream that runs without any alarm (a warning included); panics on one.
#[allow(dead_code)]
pub fn segments(items: impl Iterator<Item = vcnc::StreamItem>) -> Vec<Segment> {
    let run = collect(items);
    assert!(run.alarms.is_empty(), "{:?}", run.alarms);
    run.segments
}

/// The motion stream as text, one segment per line, machine coordinates rounded to 1e-4:
/// `rapid X10 Y5 Z5`, `line X.. F200`, `arc cw xy X.. C(15,5,-1)`, `dwell 2.5`, `tool 1` ...
pub fn trace_text(segments: &[Segment]) -> String {
    use vcnc::motion::Feed;
    use vcnc::SegmentKind::*;
    let num = |v: f64| {
        let r = (v * 1e4).round() / 1e4;
        let r = if r == 0.0 { 0.0 } else { r };
        format!("{r}")
    };
    let pos = |p: &[f64; 6]| format!("X{} Y{} Z{}", num(p[0]), num(p[1]), num(p[2]));
    let feed = |f: &Feed| match f {
        Feed::PerMinute(v) => format!("F{}", num(*v)),
        Feed::PerRevolution { per_revolution, .. } => format!("F{}/rev", num(*per_revolution)),
        Feed::InverseTime(v) => format!("F1/{}min", num(*v)),
    };
    let mut lines = Vec::new();
    for s in segments {
        let line = match &s.kind {
            Rapid { motion, .. } => format!("rapid {}", pos(&motion.to.0)),
            Line { motion, feed: f } => format!("line {} {}", pos(&motion.to.0), feed(f)),
            Arc {
                motion,
                center,
                direction,
                plane,
                feed: f,
                ..
            } => format!(
                "arc {} {} {} C({},{},{}) {}",
                direction.as_str(),
                plane.as_str(),
                pos(&motion.to.0),
                num(center.0[0]),
                num(center.0[1]),
                num(center.0[2]),
                feed(f)
            ),
            Dwell { seconds } => format!("dwell {}", num(*seconds)),
            ToolSelect { tool } => format!("select T{tool}"),
            ToolChange { tool, .. } => format!("change T{tool}"),
            Spindle { state, speed } => format!("spindle {state:?} {}", num(*speed)),
            Coolant { on } => format!("coolant {}", if *on { "on" } else { "off" }),
            Stop { kind } => format!("stop {kind:?}"),
            Auxiliary { code } => format!("M{code}"),
            End { kind } => format!("end {kind:?}"),
            other => format!("{other:?}"),
        };
        lines.push(line);
    }
    lines.join("\n")
}

/// Runs `program` on the default machine with `profile` and returns its trace text; alarms are
/// appended as `alarm <id> line <n>` lines.
pub fn trace_with(profile: vcnc::ProfileName, program: &str) -> String {
    let machine = Machine::default().with_profile(profile).unwrap();
    trace_on(&machine, program)
}

/// Like [`trace_with`] on a given machine.
pub fn trace_on(machine: &Machine, program: &str) -> String {
    let run = run(program.as_bytes(), machine, Options::default());
    let mut text = trace_text(&run.segments);
    for alarm in &run.alarms {
        if !text.is_empty() {
            text.push('\n');
        }
        text.push_str(&format!(
            "alarm {} line {}",
            alarm.code.id(),
            alarm.span.map_or(0, |s| s.line)
        ));
    }
    text
}

/// Asserts the FANUC-profile trace of `program`.
#[track_caller]
pub fn check(program: &str, expected: &str) {
    check_with(vcnc::ProfileName::Fanuc, program, expected);
}

/// Asserts the trace of `program` on `profile`.
#[track_caller]
pub fn check_with(profile: vcnc::ProfileName, program: &str, expected: &str) {
    check_on(
        &Machine::default().with_profile(profile).unwrap(),
        program,
        expected,
    );
}

/// Asserts the trace of `program` on `machine`.
#[track_caller]
pub fn check_on(machine: &Machine, program: &str, expected: &str) {
    let actual = trace_on(machine, program);
    let expected = expected
        .trim()
        .lines()
        .map(str::trim)
        .collect::<Vec<_>>()
        .join("\n");
    assert_eq!(
        actual, expected,
        "\nprogram:\n{program}\nactual trace:\n{actual}\n"
    );
}
