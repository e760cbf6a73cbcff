//! What the viewer shows, gathered from the motion stream: the tool's moves in part coordinates
//! with their place on the planner's timeline, the tools and their colours (as `vcnc plot`
//! gives them), the program texts, the simulated stock at a coarse resolution and the alarms
//! with where they happened; written as the JSON the page reads.
//!
//! A per-axis (dog-leg) rapid is one piece per leg, timed as `vcnc trace` times its records,
//! so that the page holds one segment for each motion record of the trace.

use crate::diagnostics::Texts;
use serde_json::{json, Value};
use std::collections::HashMap;
use vcnc::plan::{DogLeg, Timing};
use vcnc::plot::{PALETTE, RAPID_COLOUR};
use vcnc::sim::HeightField;
use vcnc::toolpath::{ArcPath, Followed, ToolFollower, ToolMove};
use vcnc::{Alarm, FileId, Item, Machine, SegmentKind, Span};

/// The most cells along a side of the stock the page gets: 200 x 200 heights keep it small.
pub(crate) const STOCK_CELLS: usize = 200;

/// The most alarms listed (a warning repeated on every block of a loop would fill the page).
const MOST_ALARMS: usize = 200;

/// One segment of the page: a move, or one leg of a per-axis rapid.
#[derive(Clone, Copy, Debug)]
struct Piece {
    rapid: bool,
    /// The tool's place in the order of first cuts (its colour).
    slot: usize,
    span: Span,
    t: f64,
    dt: f64,
    from: [f64; 3],
    to: [f64; 3],
    arc: Option<ArcPath>,
    /// For a rapid: where it first meets the stock as it was before the rapid, if it does.
    contact: Option<[f64; 3]>,
}

/// A tool that moved, in the order tools first move.
#[derive(Clone, Copy, Debug)]
struct SceneTool {
    number: u32,
    diameter: f64,
    /// The drawn length: the flutes, or three diameters when the table does not say.
    length: f64,
}

/// The moves of a run, kept for the page.
pub(crate) struct Scene {
    follower: ToolFollower,
    dog_leg: DogLeg,
    pieces: Vec<Piece>,
    tools: Vec<SceneTool>,
}

impl Scene {
    /// An empty scene on `machine` (its per-axis rapids are followed leg by leg).
    pub(crate) fn new(machine: &Machine) -> Scene {
        let mut follower = ToolFollower::new();
        follower.per_axis_rapids(machine);
        Scene {
            follower,
            dog_leg: DogLeg::new(machine),
            pieces: Vec::new(),
            tools: Vec::new(),
        }
    }

    /// Takes one item of the stream with its timing; `stock` is the simulated stock before the
    /// item cuts it, if there is one (a rapid's first contact with it is kept for its marker).
    pub(crate) fn add(&mut self, item: &Item, timing: &Timing, stock: Option<&HeightField>) {
        let Followed::Move(motion) = self.follower.follow(item) else {
            return;
        };
        let slot = self.slot();
        let piece = Piece {
            rapid: motion.rapid,
            slot,
            span: motion.span,
            t: timing.t,
            dt: timing.dt,
            from: motion.from,
            to: motion.to,
            arc: motion.arc,
            contact: None,
        };
        let start = self.pieces.len();
        match item {
            Item::Segment(segment) => match &segment.kind {
                SegmentKind::Rapid {
                    motion: machine_move,
                    per_axis: true,
                } if motion.corners[0].is_some() => {
                    let times = self.dog_leg.corners(machine_move);
                    self.add_legs(piece, &motion, &times);
                }
                _ => self.pieces.push(piece),
            },
            _ => self.pieces.push(piece),
        }
        if let (true, Some(stock)) = (motion.rapid, stock) {
            let radius = self.follower.tool().shape.radius();
            for piece in &mut self.pieces[start..] {
                piece.contact = first_contact(stock, piece.from, piece.to, radius);
            }
        }
    }

    /// The slot of the tool in the spindle, added at its first move.
    fn slot(&mut self) -> usize {
        let tool = self.follower.tool();
        if let Some(slot) = self.tools.iter().position(|t| t.number == tool.number) {
            return slot;
        }
        let diameter = tool.shape.diameter;
        let length = if tool.shape.cutting_length.is_finite() {
            tool.shape.cutting_length
        } else {
            3.0 * diameter
        };
        self.tools.push(SceneTool {
            number: tool.number,
            diameter,
            length: length.max(5.0),
        });
        self.tools.len() - 1
    }

    /// The legs of a per-axis rapid, each timed by when its axes come to rest (the machine's
    /// times scaled to the planner's duration, as the trace does).
    fn add_legs(
        &mut self,
        whole: Piece,
        motion: &ToolMove,
        times: &[(f64, vcnc::motion::MachinePos)],
    ) {
        let total = times.last().map_or(0.0, |&(t, _)| t);
        let ends: Vec<[f64; 3]> = motion
            .corners
            .iter()
            .flatten()
            .copied()
            .chain([motion.to])
            .collect();
        if total <= 0.0 || ends.len() != times.len() {
            self.pieces.push(whole);
            return;
        }
        let scale = whole.dt / total;
        let (mut from, mut started) = (whole.from, 0.0);
        for (&to, &(t, _)) in ends.iter().zip(times) {
            self.pieces.push(Piece {
                t: whole.t + started * scale,
                dt: (t - started) * scale,
                from,
                to,
                ..whole
            });
            (from, started) = (to, t);
        }
    }

    /// The page's data: `name` is the program's, `stock` the simulated part (if any), `alarms`
    /// the run's and the simulation's.
    pub(crate) fn to_json(
        &self,
        name: &str,
        texts: &Texts,
        stock: Option<&HeightField>,
        alarms: &[Alarm],
    ) -> Value {
        let mut files: Vec<FileId> = Vec::new();
        let mut file_index = |file: FileId| match files.iter().position(|&f| f == file) {
            Some(i) => i,
            None => {
                files.push(file);
                files.len() - 1
            }
        };
        let segments: Vec<Value> = self
            .pieces
            .iter()
            .map(|p| piece_json(p, file_index(p.span.file)))
            .collect();
        let alarms: Vec<Value> = self.alarms_json(alarms, texts, &mut file_index);
        let files: Vec<Value> = files
            .iter()
            .map(|&file| {
                let text = texts.text(file);
                let text = String::from_utf8_lossy(&text);
                let lines: Vec<&str> = text.lines().collect();
                json!({ "name": texts.name(file), "lines": lines })
            })
            .collect();
        let tools: Vec<Value> = self
            .tools
            .iter()
            .enumerate()
            .map(|(slot, t)| {
                json!({
                    "number": t.number,
                    "colour": PALETTE[slot % PALETTE.len()],
                    "diameter": round(t.diameter, 1e4),
                    "length": round(t.length, 1e4),
                })
            })
            .collect();
        json!({
            "name": name,
            "rapid_colour": RAPID_COLOUR,
            "tools": tools,
            "segments": segments,
            "files": files,
            "stock": stock.map(stock_json),
            "alarms": alarms,
        })
    }

    /// The alarms, each with a segment of its block (none when its block made no move: a tool
    /// change, a stop before the first move) and a marker: where a rapid first met the
    /// stock, else the segment's lower end, or its start when it does not descend (the simulator
    /// does not say where along a move an event happened: the page highlights the whole move
    /// when the alarm is clicked).
    fn alarms_json(
        &self,
        alarms: &[Alarm],
        texts: &Texts,
        file_index: &mut impl FnMut(FileId) -> usize,
    ) -> Vec<Value> {
        let alarms = &alarms[..alarms.len().min(MOST_ALARMS)];
        let mut placed: HashMap<(FileId, u32), Option<usize>> = alarms
            .iter()
            .filter_map(|a| a.span)
            .map(|s| ((s.file, s.start), None))
            .collect();
        // The block's first segment that met the stock, else its first: a block run again
        // (a loop, a subprogram) may hit on a later run.
        for (index, p) in self.pieces.iter().enumerate() {
            if let Some(first) = placed.get_mut(&(p.span.file, p.span.start)) {
                let met = |i: usize| self.pieces[i].contact.is_some();
                if first.is_none_or(|i| !met(i) && p.contact.is_some()) {
                    *first = Some(index);
                }
            }
        }
        alarms
            .iter()
            .map(|alarm| {
                let segment = alarm
                    .span
                    .and_then(|s| placed.get(&(s.file, s.start)).copied().flatten());
                let at = segment.map(|i| {
                    let p = &self.pieces[i];
                    match p.contact {
                        Some(contact) => contact,
                        None if p.to[2] < p.from[2] - 1e-9 => p.to,
                        None => p.from,
                    }
                });
                let (file, line) = alarm
                    .span
                    .map_or((None, None), |s| (Some(file_index(s.file)), Some(s.line)));
                json!({
                    "code": alarm.code.code(),
                    "error": alarm.is_error(),
                    "message": alarm.message,
                    "file": file,
                    "line": line,
                    "at": at.map(|p| p.map(|v| round(v, 1e4))),
                    "segment": segment,
                    "name": alarm.span.map(|s| texts.name(s.file)),
                })
            })
            .collect()
    }
}

/// `[kind, tool slot, file, line, t, dt, x0, y0, z0, x1, y1, z1]`, kind 0 a rapid, 1 a line,
/// 2 an arc followed by `cx, cy, cz, first axis, second axis, sweep` (radians, counter-clockwise
/// positive in the plane).
fn piece_json(p: &Piece, file: usize) -> Value {
    let mm = |v: f64| round(v, 1e4);
    let seconds = |v: f64| round(v, 1e6);
    let kind = match (p.rapid, p.arc) {
        (true, _) => 0,
        (false, None) => 1,
        (false, Some(_)) => 2,
    };
    let mut record = vec![
        json!(kind),
        json!(p.slot),
        json!(file),
        json!(p.span.line),
        json!(seconds(p.t)),
        json!(seconds(p.dt)),
    ];
    record.extend(p.from.iter().chain(&p.to).map(|&v| json!(mm(v))));
    if let Some(arc) = p.arc {
        let (a, b, _) = arc.plane.axes();
        record.extend(arc.center.iter().map(|&v| json!(mm(v))));
        record.extend([json!(a), json!(b), json!(round(arc.sweep, 1e9))]);
    }
    Value::Array(record)
}

/// The stock at most [`STOCK_CELLS`] a side: each coarse cell the mean of the cells it covers
/// (the volume left stays the grid's; a groove narrower than a coarse cell shows shallower).
fn stock_json(grid: &HeightField) -> Value {
    let [nx, ny] = grid.size();
    let step = nx.max(ny).div_ceil(STOCK_CELLS).max(1);
    let [cx, cy] = [nx.div_ceil(step), ny.div_ceil(step)];
    let mut heights = Vec::with_capacity(cx * cy);
    for j in 0..cy {
        for i in 0..cx {
            let (mut sum, mut count) = (0.0, 0.0);
            for jj in j * step..((j + 1) * step).min(ny) {
                for ii in i * step..((i + 1) * step).min(nx) {
                    sum += grid.height(ii, jj);
                    count += 1.0;
                }
            }
            heights.push(json!(round(sum / count, 1e3)));
        }
    }
    let (bottom, top) = grid.bottom_top();
    json!({
        "origin": grid.origin(),
        // The last coarse cell may reach past the grid: its size is the grid's over the count.
        "cell": [nx as f64 * grid.cell() / cx as f64, ny as f64 * grid.cell() / cy as f64],
        "size": [cx, cy],
        "bottom": bottom,
        "top": top,
        "heights": heights,
    })
}

/// The first point along the straight move `from` to `to` where a tool of `radius` has its tip
/// below `stock`'s surface, looking under its centre and eight points a cell inside its rim,
/// every quarter radius (or cell) along; `None` when it stays above. A marker's place, not the
/// simulation: a thin wall between two looks can be missed.
fn first_contact(
    stock: &HeightField,
    from: [f64; 3],
    to: [f64; 3],
    radius: f64,
) -> Option<[f64; 3]> {
    let cell = stock.cell();
    let rim = (radius - cell).max(0.0);
    let length = (0..3)
        .map(|k| (to[k] - from[k]).powi(2))
        .sum::<f64>()
        .sqrt();
    let steps = (length / (radius / 4.0).max(cell)).ceil().min(100_000.0) as usize;
    let [nx, ny] = stock.size();
    let origin = stock.origin();
    let height = |x: f64, y: f64| {
        let i = ((x - origin[0]) / cell).floor();
        let j = ((y - origin[1]) / cell).floor();
        let inside = i >= 0.0 && j >= 0.0 && (i as usize) < nx && (j as usize) < ny;
        inside.then(|| stock.height(i as usize, j as usize))
    };
    (0..=steps).find_map(|step| {
        let f = if steps == 0 {
            1.0
        } else {
            step as f64 / steps as f64
        };
        let p: [f64; 3] = std::array::from_fn(|k| from[k] + f * (to[k] - from[k]));
        let looks = (0..9).map(|n| match n {
            0 => (p[0], p[1]),
            _ => {
                let angle = f64::from(n) * std::f64::consts::FRAC_PI_4;
                (p[0] + rim * angle.cos(), p[1] + rim * angle.sin())
            }
        });
        let touches = looks
            .filter_map(|(x, y)| height(x, y))
            .any(|h| p[2] < h - cell / 4.0);
        touches.then_some(p)
    })
}

/// `value` to the nearest `1 / per`: the page's numbers stay short.
fn round(value: f64, per: f64) -> f64 {
    (value * per).round() / per
}
