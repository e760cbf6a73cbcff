//! The front-end seam: a toy dialect of one move per line, written here against the public API
//! only, runs through the same kernel and planner as the ISO interpreter and gives the same
//! motion stream as the ISO program that says the same.
//!
//! The toy dialect: `feed F`, `rapid x.. y.. z..`, `line x.. y.. z..`, `cw`/`ccw x.. y.. i.. j..`
//! (an arc about the absolute centre `i j`), `dwell SECONDS`, `end`; `#` starts a comment.

use vcnc::interp::{FrontEnd, Kernel, Origin, Run, Step};
use vcnc::motion::{ArcDirection, EndKind};
use vcnc::plan::{PlanOptions, Planner};
use vcnc::{Alarm, AlarmCode, FileId, Item, Machine, Segment, SegmentKind, Span};

/// The toy dialect's block sequencer: its text and the next line to read.
struct Toy {
    text: String,
    at: usize,
    line: u32,
}

impl Toy {
    fn new(text: &str) -> Toy {
        Toy {
            text: text.to_string(),
            at: 0,
            line: 0,
        }
    }
}

/// A word `x12.5` read as its letter and number.
fn word(span: Span, text: &str) -> Result<(char, f64), Alarm> {
    let mut chars = text.chars();
    let letter = chars.next().unwrap_or(' ');
    let value = chars.as_str().parse::<f64>().map_err(|_| {
        Alarm::error(
            AlarmCode::BadNumber,
            span,
            format!("`{text}` is not a number"),
        )
    })?;
    Ok((letter, value))
}

impl FrontEnd for Toy {
    fn step(&mut self, kernel: &mut Kernel) -> Result<Step, Alarm> {
        let rest = &self.text[self.at..];
        if rest.is_empty() {
            return Ok(Step::End);
        }
        let length = rest.find('\n').map_or(rest.len(), |n| n + 1);
        let start = self.at;
        self.at += length;
        self.line += 1;
        let line = rest[..length].split('#').next().unwrap_or("").trim();
        let span = Span::new(FileId(0), self.line, start as u32..(start + length) as u32);
        let origin = Origin::at(span);
        let mut words = line.split_whitespace();
        let Some(command) = words.next() else {
            return Ok(Step::Next);
        };
        let mut target = [None; 6];
        let mut center = (0.0, 0.0);
        let mut number = None;
        for text in words {
            match word(span, text)? {
                (letter @ ('x' | 'y' | 'z'), value) => {
                    target[usize::from(letter as u8 - b'x')] = Some(value);
                }
                ('i', value) => center.0 = value,
                ('j', value) => center.1 = value,
                _ => number = text.parse::<f64>().ok(),
            }
        }
        match command {
            "feed" => kernel.set_feed(number.unwrap_or(0.0)),
            "rapid" => kernel.rapid_to(target, origin)?,
            "line" => kernel.feed_to(target, origin)?,
            "cw" => kernel.arc_to(target, center, ArcDirection::Clockwise, origin)?,
            "ccw" => kernel.arc_to(target, center, ArcDirection::CounterClockwise, origin)?,
            "dwell" => kernel.dwell(number.unwrap_or(0.0), origin)?,
            "end" => {
                kernel.end(EndKind::M30, origin);
                return Ok(Step::End);
            }
            other => {
                return Err(Alarm::error(
                    AlarmCode::UnexpectedCharacter,
                    span,
                    format!("`{other}` is not a toy command"),
                ))
            }
        }
        Ok(Step::Next)
    }
}

const TOY: &str = "# a pocket corner and a hole\n\
feed 600\n\
rapid x10 y5 z2\n\
line z-1\n\
line x20\n\
ccw x30 y5 i25 j5\n\
cw x20 y5 i25 j5\n\
dwell 0.5\n\
rapid z5\n\
end\n";

const ISO: &str = "G21 G90 G17 G94\n\
F600.\n\
G0 X10. Y5. Z2.\n\
G1 Z-1.\n\
X20.\n\
G3 X30. Y5. I5. J0.\n\
G2 X20. Y5. I-5. J0.\n\
G4 P500\n\
G0 Z5.\n\
M30\n";

/// The stream's items without their spans (the two programs' texts differ): kinds and alarms.
fn kinds(items: impl Iterator<Item = vcnc::StreamItem>) -> Vec<String> {
    items
        .map(|item| match item {
            Ok(Item::Segment(segment)) => format!("{:?}", segment.kind),
            Ok(Item::Frame(frame)) => format!("{frame:?}"),
            Ok(Item::Warning(alarm)) | Err(alarm) => format!("{:?}: {}", alarm.code, alarm.message),
        })
        .collect()
}

#[test]
fn a_toy_dialect_gives_the_stream_of_the_iso_program_that_says_the_same() {
    let machine = Machine::default();
    let toy = kinds(Run::new(Toy::new(TOY), Kernel::new(&machine)));
    let iso = kinds(vcnc::interpret_str(ISO, &machine, vcnc::Options::default()));
    assert_eq!(toy, iso);
    // The frame the first move is made in, then the items of the program.
    assert_eq!(toy.len(), 9, "{toy:#?}");
}

#[test]
fn the_planner_times_a_toy_program_as_the_iso_one() {
    let machine = Machine::default();
    let times = |items: Vec<vcnc::StreamItem>| -> Vec<(String, f64, f64)> {
        Planner::new(items.into_iter(), &machine, PlanOptions::default())
            .filter_map(|timed| {
                let timed = timed.expect("no alarm");
                let timed = timed.segment()?;
                Some((format!("{:?}", timed.segment.kind), timed.t, timed.dt))
            })
            .collect()
    };
    let toy = times(Run::new(Toy::new(TOY), Kernel::new(&machine)).collect());
    let iso = times(vcnc::interpret_str(ISO, &machine, vcnc::Options::default()).collect());
    assert_eq!(toy, iso);
}

#[test]
fn batches_give_the_items_the_iterator_gives() {
    let machine = Machine::default();
    let mut run = Run::new(Toy::new(TOY), Kernel::new(&machine));
    let (mut batched, mut batch) = (Vec::new(), Vec::new());
    loop {
        let more = run.next_batch(&mut batch, 3);
        batched.append(&mut batch);
        if !more {
            break;
        }
    }
    let one_by_one: Vec<_> = Run::new(Toy::new(TOY), Kernel::new(&machine)).collect();
    assert_eq!(batched, one_by_one);
}

#[test]
fn a_kernel_alarm_stops_the_toy_program_at_its_line() {
    let machine = Machine::default();
    let program = "rapid x1\nline x2\nline x3\nend\n";
    let items: Vec<_> = Run::new(Toy::new(program), Kernel::new(&machine)).collect();
    let alarm = items.last().unwrap().as_ref().unwrap_err();
    assert_eq!(alarm.code, AlarmCode::NoFeedRate);
    assert_eq!(alarm.span.map(|s| s.line), Some(2));
    assert_eq!(
        items.len(),
        3,
        "the frame, the rapid, then the alarm: {items:?}"
    );
    assert!(matches!(items[0], Ok(Item::Frame(_))));
    assert!(matches!(
        items[1],
        Ok(Item::Segment(Segment {
            kind: SegmentKind::Rapid { .. },
            ..
        }))
    ));
}

#[test]
fn a_dialect_alarm_ends_the_stream_too() {
    let machine = Machine::default();
    let items: Vec<_> = Run::new(Toy::new("spin 100\nrapid x1\n"), Kernel::new(&machine)).collect();
    assert_eq!(items.len(), 1);
    assert_eq!(
        items[0].as_ref().unwrap_err().code,
        AlarmCode::UnexpectedCharacter
    );
}

/// Every item a stream of the pipeline gives, with the planned start and duration of each.
fn timed_through_the_pipeline(stream: &mut vcnc::pipeline::Stream) -> Vec<(String, f64, f64)> {
    let mut timed = Vec::new();
    stream.for_each_timed(PlanOptions::default(), |items, timings| {
        for (item, timing) in items.iter().zip(timings) {
            let what = match item {
                Ok(Item::Segment(segment)) => format!("{:?}", segment.kind),
                Ok(Item::Frame(frame)) => format!("{frame:?}"),
                Ok(Item::Warning(alarm)) | Err(alarm) => format!("{:?}", alarm.code),
            };
            timed.push((what, timing.t, timing.dt));
        }
        true
    });
    timed
}

#[test]
fn the_library_pipeline_runs_a_toy_program_like_the_iso_one() {
    let machine = Machine::default();
    let pipeline = || vcnc::pipeline::Pipeline::new(&machine);
    let mut toy = pipeline().open_front_end(Toy::new(TOY), "toy.txt");
    let mut iso = pipeline().open_text(ISO, "iso.nc");
    let toy_timed = timed_through_the_pipeline(&mut toy);
    assert_eq!(toy_timed, timed_through_the_pipeline(&mut iso));
    // The frame of the first move, then the program's items.
    assert_eq!(toy_timed.len(), 9);
    assert_eq!(toy.finish().blocks_executed, 10, "one step a line");
}

#[test]
fn the_pipeline_stops_a_toy_program_at_an_overtravel() {
    let machine = Machine::default();
    let program = "rapid x10\nrapid x-99999\nrapid x20\nend\n";
    for layout in [
        vcnc::pipeline::Layout::for_busy_consumer(),
        vcnc::pipeline::Layout::for_idle_consumer(),
    ] {
        let stream = vcnc::pipeline::Pipeline::new(&machine)
            .layout(layout)
            .open_front_end(Toy::new(program), "toy.txt");
        let items: Vec<_> = stream.collect();
        assert_eq!(items.len(), 3, "the frame, the rapid, the alarm: {items:?}");
        assert_eq!(items[2].as_ref().unwrap_err().code, AlarmCode::Overtravel);
    }
}
