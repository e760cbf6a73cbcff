//! `vcnc trace`: the motion stream, one record per segment, in execution order.
//!
//! JSON lines carry `kind`, `line`, `file`, the planner's start time `t` and duration `dt` in
//! seconds, the end point `x y z` (and `a b c` when the machine has them) in machine coordinates, `f` in mm/min for cutting moves, `cx cy cz dir plane` for
//! arcs, and `n` (sequence number) and, with `--work`, `wx wy wz` (end point in program
//! coordinates) as extras; on a machine with `[kinematics]`, `tx ty tz`, the tool tip in the
//! workpiece (the kinematics' forward transform of the joints `x y z a b c`).
//! Events carry their own fields (`tool`, `state`, `speed`, `on`, `seconds`, `stop`, `end`, `code`).

use super::{Outcome, SetupError};
use crate::diagnostics::{Output, Texts};
use crate::numbers::{
    FixedText, Key, OutBuffer, PaddedText, RecordText, Remembered, RememberedRun,
};
use crate::program::{open_planned, Planned, Source};
use crate::progress::Progress;
use crate::setup::MachineArgs;
use clap::{Args as ClapArgs, ValueEnum};
use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use vcnc::motion::{
    segment_of, ArcDirection, EndKind, Feed, Item as Emitted, Move, Plane, ProgramMap,
    SpindleState, StopKind,
};
use vcnc::pipeline::{Item, ProgramFiles};
use vcnc::plan::{DogLeg, Timing};
use vcnc::{Alarm, Axis, FileId, Segment, SegmentKind};

/// Output format of the trace.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum Format {
    /// One JSON object per line.
    Jsonl,
    /// Comma-separated values with a header line.
    Csv,
}

/// `vcnc trace` arguments.
#[derive(ClapArgs, Debug)]
pub(crate) struct Args {
    /// The program (`-`: standard input; a pipe or FIFO is read whole first).
    program: PathBuf,
    /// Output format.
    #[arg(long, value_enum, default_value = "jsonl")]
    format: Format,
    /// Add the end point in program (work) coordinates to every motion: `wx wy wz`.
    #[arg(long)]
    work: bool,
    #[command(flatten)]
    machine: MachineArgs,
}

pub(crate) fn run(args: &Args) -> Result<Outcome, SetupError> {
    let stdout = std::io::stdout();
    let (alarms, texts, saved) = write_trace(args, &mut stdout.lock())?;
    crate::diagnostics::print_human(&texts, &alarms, Output::Stderr);
    saved?;
    Ok(if alarms.iter().any(Alarm::is_error) {
        Outcome::Alarm
    } else {
        Outcome::Clean
    })
}

/// What a trace leaves for the diagnostics: the alarms and warnings met on the way, the files
/// read, and whether the state file (kept only with `--state`) was saved.
type Traced = (Vec<Alarm>, Texts, Result<(), SetupError>);

/// Runs the program and writes its trace to `output`. A reader that goes away (`| head`)
/// ends the run quietly.
fn write_trace(args: &Args, output: &mut impl Write) -> Result<Traced, SetupError> {
    let source = Source::read(&args.program)?;
    let Planned {
        plan_options,
        mut stream,
    } = open_planned(&source, &args.machine, false)?;
    let texts = crate::program::files(&stream, &source);
    let files = stream.files().clone();
    let mut writer = Writer::new(files.clone(), stream.machine(), args.work);
    if args.format == Format::Csv {
        writer.csv_header();
    }
    let mut alarms: Vec<Alarm> = Vec::new();
    let mut written = Ok(());
    // Beside a trace written to a file or a pipe, never among the records on a terminal.
    let name = source.name().display().to_string();
    let mut progress = Progress::on_stderr(&name, !std::io::stdout().is_terminal());
    stream.for_each_timed(plan_options, |items, timings| {
        if let Some(last) = items.iter().rev().find_map(segment_of) {
            progress.batch(last.span.line, items.len());
        }
        writer.batch(items, timings, args.format, &mut alarms);
        if writer.out.is_full() {
            written = output.write_all(writer.out.as_bytes());
            writer.out.clear();
        }
        written.is_ok()
    });
    if written.is_ok() {
        written = output
            .write_all(writer.out.as_bytes())
            .and_then(|()| output.flush());
    }
    progress.finish();
    let (_, saved) = crate::program::finish(stream, &args.machine);
    match written {
        // The reader went away (`| head`): it has what it wanted.
        Err(error) if error.kind() != std::io::ErrorKind::BrokenPipe => {
            Err(SetupError::Output(error))
        }
        _ => Ok((alarms, texts, saved)),
    }
}

/// The key of a JSON field after a previous field: `key!("x")` is `,"x":`.
macro_rules! key {
    ($name:literal) => {{
        const KEY: Key = Key::new(concat!(",\"", $name, "\":"));
        KEY
    }};
}

/// The key of a CSV field after a previous field.
const COMMA: Key = Key::new(",");

/// No key: a CSV field after a comma already written, or a JSON number after its key.
const NO_KEY: Key = Key::new("");

struct Writer {
    out: OutBuffer,
    /// The text of the last z, a, b, c and f written, by axis index (6: f): most records repeat
    /// some of them. x and y are not remembered: in contouring they repeat in about one record
    /// in a hundred, and remembering costs a little on every record that does not repeat.
    memory: [Remembered; 7],
    /// The text of the end of the last record that ended with z, f and nothing else: see
    /// [`Writer::jsonl`].
    end: RememberedRun,
    /// True when a motion's record has no field after z but f and the arc's: no axis after Z,
    /// no work coordinates.
    plain_end: bool,
    /// The program files, for the name of a called program's file.
    files: ProgramFiles,
    /// The file of the last record, and its name as a JSON field and as a CSV field.
    file: FileId,
    file_json: PaddedText,
    file_csv: PaddedText,
    /// The machine's axes after X Y Z, with their JSON keys (`,"a":`, `,"u":`) and names.
    extra: Vec<(Axis, Key, String)>,
    work: bool,
    /// The map back to program coordinates of the frame in force (`--work`); None before the
    /// stream's first frame.
    frame: Option<ProgramMap>,
    arc_words: [[ArcWords; 3]; 2],
    /// Where a per-axis rapid really goes: a record for each piece between the moments its
    /// axes come to rest.
    dog_leg: DogLeg,
    /// A 5-axis machine's kinematics and the tool length of the frame in force: each motion's
    /// record then ends with the tool tip in the workpiece, `tx ty tz`.
    tip: Option<(vcnc::kinematics::Kinematics, f64)>,
}

/// The parts of a record, shared by both formats.
struct Record<'a> {
    kind: &'static KindText,
    motion: Option<&'a Move>,
    feed: Option<f64>,
    arc: Option<([f64; 3], ArcDirection, Plane)>,
}

/// An arc's direction and plane: the end of its JSON object, `,"dir":"cw","plane":"xy"`, and its
/// CSV fields, `,cw,xy`.
struct ArcWords {
    json: FixedText,
    csv: FixedText,
}

/// The [`ArcWords`] of every direction and plane, indexed by [`arc_index`]; made once, from the
/// names the library gives.
fn arc_words() -> [[ArcWords; 3]; 2] {
    [ArcDirection::Clockwise, ArcDirection::CounterClockwise].map(|direction| {
        [Plane::Xy, Plane::Zx, Plane::Yz].map(|plane| {
            let (direction, plane) = (direction.as_str(), plane.as_str());
            ArcWords {
                json: FixedText::join(&[",\"dir\":\"", direction, "\",\"plane\":\"", plane, "\""]),
                csv: FixedText::join(&[",", direction, ",", plane]),
            }
        })
    })
}

/// Where the words of an arc are in [`arc_words`]: by direction, then by the plane's normal
/// axis (Z for XY, Y for ZX, X for YZ).
fn arc_index(direction: ArcDirection, plane: Plane) -> (usize, usize) {
    let by_direction = usize::from(direction == ArcDirection::CounterClockwise);
    let by_plane = 2 - plane.axes().2;
    (by_direction, by_plane)
}

impl<'a> Record<'a> {
    /// A cutting move's record, at a feed per minute.
    #[inline(always)]
    fn fed(
        kind: &'static KindText,
        motion: &'a Move,
        feed: f64,
        arc: Option<([f64; 3], ArcDirection, Plane)>,
    ) -> Record<'a> {
        Record {
            kind,
            motion: Some(motion),
            feed: Some(feed),
            arc,
        }
    }
}

/// How a record of one kind starts: its JSON object up to the `line` key, and its CSV field
/// with the comma after it.
struct KindText {
    json: FixedText,
    csv: FixedText,
}

/// The [`KindText`] of a kind, written once here.
macro_rules! kind {
    ($kind:literal) => {{
        const TEXT: KindText = KindText {
            json: FixedText::join(&["{\"kind\":\"", $kind, "\",\"line\":"]),
            csv: FixedText::join(&[$kind, ","]),
        };
        &TEXT
    }};
}

#[inline(always)]
fn record(segment: &Segment) -> Record<'_> {
    let mut record = Record {
        kind: kind!("other"),
        motion: segment.motion(),
        feed: None,
        arc: None,
    };
    record.kind = match &segment.kind {
        SegmentKind::Rapid { .. } => kind!("rapid"),
        SegmentKind::Line { feed, .. } => {
            record.feed = feed_mm_per_min(feed, segment);
            kind!("feed")
        }
        SegmentKind::Arc {
            feed,
            center,
            direction,
            plane,
            ..
        } => {
            record.feed = feed_mm_per_min(feed, segment);
            record.arc = Some((center.xyz(), *direction, *plane));
            kind!("arc")
        }
        SegmentKind::Dwell { .. } => kind!("dwell"),
        SegmentKind::ToolSelect { .. } => kind!("tool_select"),
        SegmentKind::ToolChange { .. } => kind!("tool_change"),
        SegmentKind::Spindle { .. } => kind!("spindle"),
        SegmentKind::Coolant { .. } => kind!("coolant"),
        SegmentKind::Stop { .. } => kind!("stop"),
        SegmentKind::Auxiliary { .. } => kind!("aux"),
        SegmentKind::End { .. } => kind!("end"),
        _ => kind!("other"),
    };
    record
}

fn feed_mm_per_min(feed: &Feed, segment: &Segment) -> Option<f64> {
    match feed {
        Feed::PerMinute(f) => Some(*f),
        _ => feed.mm_per_min(segment.length()),
    }
}

impl Writer {
    fn new(files: ProgramFiles, machine: &vcnc::Machine, work: bool) -> Writer {
        let mut writer = Writer {
            out: OutBuffer::new(1 << 16),
            memory: [Remembered::default(); 7],
            end: RememberedRun::default(),
            files,
            file: FileId(0),
            file_json: PaddedText::default(),
            file_csv: PaddedText::default(),
            extra: Axis::ALL[3..]
                .iter()
                .filter(|a| machine.has_axis(**a))
                .map(|&a| {
                    let name = machine.layout.name(a).as_str().to_ascii_lowercase();
                    (a, Key::new(&format!(",\"{name}\":")), name)
                })
                .collect(),
            work,
            frame: None,
            arc_words: arc_words(),
            plain_end: false,
            dog_leg: DogLeg::new(machine),
            tip: machine.kinematics.clone().map(|k| (k, 0.0)),
        };
        writer.plain_end = writer.extra.is_empty() && !work && writer.tip.is_none();
        writer.set_file(FileId(0));
        writer
    }

    /// Items of the planner's stream: records, and alarms kept for the diagnostics. The format
    /// is chosen once for the batch.
    fn batch(
        &mut self,
        items: &[Item],
        timings: &[Timing],
        format: Format,
        alarms: &mut Vec<Alarm>,
    ) {
        match format {
            Format::Jsonl => self.records::<true>(items, timings, alarms),
            Format::Csv => self.records::<false>(items, timings, alarms),
        }
    }

    /// [`Writer::batch`] in one format, JSON lines or CSV, whose record function is inlined
    /// here.
    #[inline(always)]
    fn records<const JSON: bool>(
        &mut self,
        items: &[Item],
        timings: &[Timing],
        alarms: &mut Vec<Alarm>,
    ) {
        for (item, timing) in items.iter().zip(timings) {
            // The most common record, a line at a feed per minute, is tested first by its own
            // pattern (one comparison of the kind and one of the feed), and has a copy of the
            // record function of its own, in which the compiler knows which fields the record
            // has instead of testing them field by field.
            if let Ok(Emitted::Segment(
                segment @ Segment {
                    kind:
                        SegmentKind::Line {
                            motion,
                            feed: Feed::PerMinute(feed),
                            ..
                        },
                    ..
                },
            )) = item
            {
                if segment.span.file != self.file {
                    self.set_file(segment.span.file);
                }
                let record = Record::fed(kind!("feed"), motion, *feed, None);
                self.write::<JSON>(segment, timing, record);
                continue;
            }
            let segment = match item {
                Ok(Emitted::Segment(segment)) => segment,
                Ok(Emitted::Frame(frame)) => {
                    self.frame = Some(frame.transform.program_map());
                    if let Some((kinematics, length)) = &mut self.tip {
                        let k = kinematics.tool_axis;
                        let l = frame.tool_length;
                        *length = l[0] * k[0] + l[1] * k[1] + l[2] * k[2];
                    }
                    continue;
                }
                Ok(Emitted::Warning(alarm)) | Err(alarm) => {
                    alarms.push(alarm.clone());
                    continue;
                }
            };
            if segment.span.file != self.file {
                self.set_file(segment.span.file);
            }
            self.write_other::<JSON>(segment, timing);
        }
    }

    /// Every record but a line at a feed per minute, out of line: the loop above keeps its
    /// registers for the common record. Arcs at a feed per minute have a copy of their own.
    #[inline(never)]
    fn write_other<const JSON: bool>(&mut self, segment: &Segment, timing: &Timing) {
        match &segment.kind {
            SegmentKind::Arc {
                motion,
                feed: Feed::PerMinute(feed),
                center,
                direction,
                plane,
                ..
            } => {
                let arc = Some((center.xyz(), *direction, *plane));
                self.write::<JSON>(
                    segment,
                    timing,
                    Record::fed(kind!("arc"), motion, *feed, arc),
                );
            }
            SegmentKind::Rapid {
                motion,
                per_axis: true,
            } => self.write_dog_leg::<JSON>(segment, timing, motion),
            _ => self.write::<JSON>(segment, timing, record(segment)),
        }
    }

    /// A per-axis rapid as the machine moves it: a record for each piece, ending where an axis
    /// comes to rest, timed by the axes' own profiles (scaled to the planner's duration).
    fn write_dog_leg<const JSON: bool>(
        &mut self,
        segment: &Segment,
        timing: &Timing,
        motion: &Move,
    ) {
        let corners = self.dog_leg.corners(motion);
        let total = corners.last().map_or(0.0, |&(t, _)| t);
        if corners.len() < 2 || total <= 0.0 {
            return self.write::<JSON>(segment, timing, record(segment));
        }
        let scale = timing.dt / total;
        let (mut from, mut started) = (motion.from, 0.0);
        for (t, to) in corners {
            let piece = Move {
                from,
                to,
                ..*motion
            };
            let piece_timing = Timing {
                t: timing.t + started * scale,
                dt: (t - started) * scale,
                ..*timing
            };
            let record = Record {
                kind: kind!("rapid"),
                motion: Some(&piece),
                feed: None,
                arc: None,
            };
            self.write::<JSON>(segment, &piece_timing, record);
            (from, started) = (to, t);
        }
    }

    #[inline(always)]
    fn write<const JSON: bool>(&mut self, segment: &Segment, timing: &Timing, record: Record<'_>) {
        if JSON {
            self.jsonl(segment, timing, record);
        } else {
            self.csv(segment, timing, record);
        }
    }

    /// Makes `file` the file named in the records; segments of a called program name its file.
    fn set_file(&mut self, file: FileId) {
        let name = self.files.path(file).display().to_string();
        self.file = file;
        let json = format!(
            ",\"file\":{}",
            serde_json::to_string(&name).unwrap_or_else(|_| "\"\"".into())
        );
        self.file_json = PaddedText::new(json.as_bytes());
        self.file_csv = PaddedText::new(csv_field(&name).as_bytes());
    }

    #[inline(always)]
    fn jsonl(&mut self, segment: &Segment, timing: &Timing, record: Record<'_>) {
        let mut text = self.out.record(self.file_json.room());
        text.fixed(&record.kind.json);
        text.unsigned(NO_KEY, u64::from(segment.span.line));
        text.padded(&self.file_json);
        if let Some(n) = segment.sequence {
            text.unsigned(key!("n"), u64::from(n));
        }
        text.decimal(key!("t"), timing.t);
        text.decimal(key!("dt"), timing.dt);
        if let Some(motion) = record.motion {
            let to = &motion.to.0;
            text.decimal(key!("x"), to[0]);
            text.decimal(key!("y"), to[1]);
            if let (true, Some(f), None) = (self.plain_end, record.feed, record.arc) {
                // The end of the common record, a line at a feed: z and f mostly repeat
                // together.
                let values = [to[2].to_bits(), f.to_bits()];
                if !text.reused(&self.end, values) {
                    let start = text.run_start();
                    text.remembered(key!("z"), &mut self.memory[2], to[2]);
                    text.remembered(key!("f"), &mut self.memory[6], f);
                    text.put(b"}\n");
                    text.remember_run(start, &mut self.end, values);
                }
                return;
            }
            text.remembered(key!("z"), &mut self.memory[2], to[2]);
            // The fields after the rotary axes are written by two copies of the same code: in
            // the one without the loop over the axes, the compiler can bound the record's
            // length and checks no window.
            if self.extra.is_empty() {
                let [_, _, z_memory, _, _, _, feed_memory] = &mut self.memory;
                jsonl_end(
                    &mut text,
                    [z_memory, feed_memory],
                    &self.arc_words,
                    self.work.then_some(self.frame.as_ref()),
                    &record,
                    None,
                );
            } else {
                for &(axis, key, _) in &self.extra {
                    text.remembered(key, &mut self.memory[axis.index()], to[axis.index()]);
                }
                let tip = tip_point(self.tip.as_ref(), motion);
                let [_, _, z_memory, _, _, _, feed_memory] = &mut self.memory;
                jsonl_end(
                    &mut text,
                    [z_memory, feed_memory],
                    &self.arc_words,
                    self.work.then_some(self.frame.as_ref()),
                    &record,
                    tip,
                );
            }
        } else {
            event_fields(&mut text, &segment.kind);
            text.put(b"}\n");
        }
    }

    fn csv_header(&mut self) {
        self.out.put(b"kind,line,file,n,t,dt,x,y,z");
        for (_, _, name) in &self.extra {
            self.out.put(b",");
            self.out.put(name.as_bytes());
        }
        self.out.put(b",f,cx,cy,cz,dir,plane");
        if self.work {
            self.out.put(b",wx,wy,wz");
        }
        if self.tip.is_some() {
            self.out.put(b",tx,ty,tz");
        }
        self.out.put(b",value\n");
    }

    #[inline(always)]
    fn csv(&mut self, segment: &Segment, timing: &Timing, record: Record<'_>) {
        let mut text = self.out.record(self.file_csv.room());
        text.fixed(&record.kind.csv);
        text.unsigned(NO_KEY, u64::from(segment.span.line));
        text.byte(b',');
        text.padded(&self.file_csv);
        text.byte(b',');
        if let Some(n) = segment.sequence {
            text.unsigned(NO_KEY, u64::from(n));
        }
        text.decimal(COMMA, timing.t);
        text.decimal(COMMA, timing.dt);
        match record.motion {
            Some(motion) => {
                let to = motion.to.0;
                for i in [0, 1, 2]
                    .into_iter()
                    .chain(self.extra.iter().map(|(a, _, _)| a.index()))
                {
                    // x and y are not remembered: see `memory`.
                    if i < 2 {
                        text.decimal(COMMA, to[i]);
                    } else {
                        text.remembered(COMMA, &mut self.memory[i], to[i]);
                    }
                }
            }
            None => (0..3 + self.extra.len()).for_each(|_| text.byte(b',')),
        }
        text.byte(b',');
        if let Some(f) = record.feed {
            text.remembered(NO_KEY, &mut self.memory[6], f);
        }
        match record.arc {
            Some((center, direction, plane)) => {
                for c in center {
                    text.decimal(COMMA, c);
                }
                let (by_direction, by_plane) = arc_index(direction, plane);
                text.fixed(&self.arc_words[by_direction][by_plane].csv);
            }
            None => text.put(b",,,,,"),
        }
        if self.work {
            match record.motion {
                Some(motion) => {
                    for w in work_point(self.frame.as_ref(), motion) {
                        text.decimal(COMMA, w);
                    }
                }
                None => text.put(b",,,"),
            }
        }
        if self.tip.is_some() {
            match record.motion.and_then(|m| tip_point(self.tip.as_ref(), m)) {
                Some(tip) => tip.into_iter().for_each(|t| text.decimal(COMMA, t)),
                None => text.put(b",,,"),
            }
        }
        text.byte(b',');
        if record.motion.is_none() {
            text.put(csv_value(&segment.kind).as_bytes());
        }
        text.byte(b'\n');
    }
}

/// The fields of a motion's JSON record after its axes, and the record's end. Not a method: the
/// record's text borrows the writer's buffer.
#[inline(always)]
fn jsonl_end(
    text: &mut RecordText<'_>,
    [z_memory, feed_memory]: [&mut Remembered; 2],
    arc_words: &[[ArcWords; 3]; 2],
    work: Option<Option<&ProgramMap>>,
    record: &Record<'_>,
    tip: Option<[f64; 3]>,
) {
    if let Some(f) = record.feed {
        text.remembered(key!("f"), feed_memory, f);
    }
    if let Some((center, direction, plane)) = record.arc {
        text.decimal(key!("cx"), center[0]);
        text.decimal(key!("cy"), center[1]);
        // In the XY plane, the centre's Z is the end's, just written.
        text.decimal_as(key!("cz"), z_memory, center[2]);
        let (by_direction, by_plane) = arc_index(direction, plane);
        text.fixed(&arc_words[by_direction][by_plane].json);
    }
    if let (Some(frame), Some(motion)) = (work, record.motion) {
        let work = work_point(frame, motion);
        text.decimal(key!("wx"), work[0]);
        text.decimal(key!("wy"), work[1]);
        text.decimal(key!("wz"), work[2]);
    }
    if let Some(tip) = tip {
        text.decimal(key!("tx"), tip[0]);
        text.decimal(key!("ty"), tip[1]);
        text.decimal(key!("tz"), tip[2]);
    }
    text.put(b"}\n");
}

/// The tool tip in the workpiece at the end of `motion`, on a machine with kinematics.
fn tip_point(tip: Option<&(vcnc::kinematics::Kinematics, f64)>, motion: &Move) -> Option<[f64; 3]> {
    tip.map(|(kinematics, length)| kinematics.forward(&motion.to.0, *length).tip)
}

/// The end point of `motion` in program coordinates: through the whole frame it was made in
/// (right under rotation, scaling and cutter compensation), or from its own translation before
/// the stream named a frame.
fn work_point(frame: Option<&ProgramMap>, motion: &Move) -> [f64; 3] {
    match frame {
        Some(frame) => frame.to_program(motion.to.xyz()),
        None => {
            let work = motion.work_to();
            [work[0], work[1], work[2]]
        }
    }
}

/// Writes `key` and `value` as a JSON string (`value` needs no escapes).
fn quoted(text: &mut RecordText<'_>, key: Key, value: &str) {
    text.put(key.as_bytes());
    text.byte(b'"');
    text.put(value.as_bytes());
    text.byte(b'"');
}

/// The fields of an event record.
fn event_fields(text: &mut RecordText<'_>, kind: &SegmentKind) {
    match *kind {
        SegmentKind::Dwell { seconds } => text.decimal(key!("seconds"), seconds),
        SegmentKind::ToolSelect { tool } | SegmentKind::ToolChange { tool, .. } => {
            text.unsigned(key!("tool"), u64::from(tool));
        }
        SegmentKind::Spindle { state, speed } => {
            quoted(text, key!("state"), spindle_name(state));
            text.decimal(key!("speed"), speed);
        }
        SegmentKind::Coolant { on } => {
            text.put(key!("on").as_bytes());
            text.put(if on { b"true" } else { b"false" });
        }
        SegmentKind::Stop { kind } => quoted(text, key!("stop"), stop_name(kind)),
        SegmentKind::Auxiliary { code } => text.unsigned(key!("code"), u64::from(code)),
        SegmentKind::End { kind } => quoted(text, key!("end"), end_name(kind)),
        _ => {}
    }
}

/// The one value of an event, for the CSV `value` column.
fn csv_value(kind: &SegmentKind) -> String {
    match *kind {
        SegmentKind::Dwell { seconds } => seconds.to_string(),
        SegmentKind::ToolSelect { tool } | SegmentKind::ToolChange { tool, .. } => tool.to_string(),
        SegmentKind::Spindle { state, speed } => format!("{} {speed}", spindle_name(state)),
        SegmentKind::Coolant { on } => if on { "on" } else { "off" }.to_string(),
        SegmentKind::Stop { kind } => stop_name(kind).to_string(),
        SegmentKind::Auxiliary { code } => format!("M{code}"),
        SegmentKind::End { kind } => end_name(kind).to_string(),
        _ => String::new(),
    }
}

fn spindle_name(state: SpindleState) -> &'static str {
    match state {
        SpindleState::Clockwise => "cw",
        SpindleState::CounterClockwise => "ccw",
        SpindleState::Stopped => "stop",
        SpindleState::Oriented => "orient",
    }
}

fn stop_name(kind: StopKind) -> &'static str {
    match kind {
        StopKind::Program => "program",
        StopKind::Optional => "optional",
        StopKind::Message => "message",
    }
}

fn end_name(kind: EndKind) -> &'static str {
    match kind {
        EndKind::M02 => "m02",
        EndKind::M30 => "m30",
        EndKind::TapeMark => "tape_mark",
        EndKind::EndOfText => "end_of_text",
        EndKind::M99 => "m99",
    }
}

fn csv_field(text: &str) -> String {
    if text.contains([',', '"', '\n']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;
    use std::fmt::Write as _;
    use vcnc::plan::{PlanOptions, Planner};
    use vcnc::{Machine, Options};

    #[derive(Parser)]
    struct Command {
        #[command(flatten)]
        args: Args,
    }

    /// A long program of every kind of record: lines, arcs, rapids, dwells, tool changes,
    /// spindle and coolant events, with a block of each now and then.
    fn long_program(blocks: usize) -> String {
        let mut text = String::from("G21 G17 G90 G94 G54\nT1 M06\nS6000 M03\nG43 H1 Z5. F1200\n");
        for i in 0..blocks {
            let (x, y) = ((i * 7 % 200) as f64, (i * 13 % 150) as f64);
            match i % 50 {
                10 => text.push_str("G02 I5. J0.\n"),
                11 => text.push_str("G00 X0. Y0.\n"),
                20 => text.push_str("G04 P250\n"),
                30 => text.push_str("M08\n"),
                31 => text.push_str("M09\n"),
                40 if i % 500 == 40 => text.push_str("T2 M06\nS3000 M03\nG43 H2 Z5.\n"),
                _ => writeln!(text, "G01 X{x:.3} Y{y:.3}").unwrap(),
            }
        }
        text.push_str("G00 Z50.\nM05\nM30\n");
        text
    }

    #[test]
    fn arc_words_name_the_direction_and_plane_of_every_arc() {
        let words = arc_words();
        for direction in [ArcDirection::Clockwise, ArcDirection::CounterClockwise] {
            for plane in [Plane::Xy, Plane::Zx, Plane::Yz] {
                let (by_direction, by_plane) = arc_index(direction, plane);
                let (direction, plane) = (direction.as_str(), plane.as_str());
                let words = &words[by_direction][by_plane];
                assert_eq!(
                    words.json.as_bytes(),
                    format!(",\"dir\":\"{direction}\",\"plane\":\"{plane}\"").as_bytes()
                );
                assert_eq!(
                    words.csv.as_bytes(),
                    format!(",{direction},{plane}").as_bytes()
                );
            }
        }
    }

    /// The threaded pipeline (parser and interpreter threads, batches timed on the writer's)
    /// writes exactly what the library's plain iterators give in one thread.
    #[test]
    fn streamed_trace_equals_the_trace_of_the_collected_stream() {
        let dir = std::env::temp_dir().join(format!("vcnc-trace-unit-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("long.nc");
        let text = long_program(40_000);
        std::fs::write(&path, &text).unwrap();
        for format in ["jsonl", "csv"] {
            let command = Command::parse_from([
                "trace",
                path.to_str().unwrap(),
                "--format",
                format,
                "--work",
            ]);
            let args = &command.args;
            let mut streamed = Vec::new();
            let (alarms, _, _) = write_trace(args, &mut streamed).unwrap();
            assert!(alarms.is_empty(), "{alarms:?}");

            let machine = Machine::default();
            let files = vcnc::Pipeline::new(&machine)
                .open_path(&args.program)
                .unwrap()
                .files()
                .clone();
            let mut writer = Writer::new(files, &machine, true);
            if args.format == Format::Csv {
                writer.csv_header();
            }
            let stream = vcnc::interpret_str(&text, &machine, Options::default());
            let mut collected = Vec::new();
            let mut none = Vec::new();
            for item in Planner::new(stream, &machine, PlanOptions::default()) {
                let (item, timing) = match item {
                    Ok(timed) => {
                        let (item, timing) = timed.into_parts();
                        (Ok(item), timing)
                    }
                    Err(alarm) => (Err(alarm), Timing::default()),
                };
                let (item, timing) = (std::slice::from_ref(&item), std::slice::from_ref(&timing));
                writer.batch(item, timing, args.format, &mut none);
                if writer.out.is_full() {
                    collected.extend_from_slice(writer.out.as_bytes());
                    writer.out.clear();
                }
            }
            collected.extend_from_slice(writer.out.as_bytes());
            assert!(
                streamed.len() > 1_000_000,
                "{format}: {} bytes",
                streamed.len()
            );
            assert!(
                streamed == collected,
                "{format}: the streamed trace differs from the collected one"
            );
        }
    }
}
