//! Material removal: a consumer of the motion stream that cuts a box of stock with the tool in
//! the spindle, along Z, on a height field ([`grid`]), and reports what it removed, where the
//! time went and what went wrong (a rapid into the stock, flutes too short, the shank or
//! holder touching, cutting with the spindle stopped, a plunge with a tool that cannot cut at
//! its centre). docs/SIMULATION.md says why a height field and what it cannot represent.
//!
//! A run is two passes over the program when the stock is not given: [`CutExtents`] finds the
//! cutting moves' extents for the default stock ([`CutExtents::stock`]), then [`Simulation`]
//! cuts. Memory is the grid's, whatever the program's length. Other stocks (a cylinder, an
//! STL) and the comparison with a design are in [`stock`].

pub mod grid;
pub mod mesh;
pub mod stock;

pub use grid::{Body, CutResult, HeightField};

use crate::alarm::{Alarm, AlarmCode};
use crate::motion::Item;
use crate::plan::Timing;
use crate::source::Span;
use crate::toolpath::{Followed, Tool, ToolFollower, ToolMove, Unfollowed};

/// The most events of one kind the report keeps (the count goes on).
const EVENTS_KEPT: usize = 100;

/// The extents of a program's cutting moves (part coordinates) and its widest tool: the first
/// pass of a run whose stock is not given.
#[derive(Clone, Debug, Default)]
pub struct CutExtents {
    follower: ToolFollower,
    low: Option<[f64; 3]>,
    high: [f64; 3],
    widest: f64,
    /// The lowest point of the first feed across X or Y: the depth the first pass reaches.
    first_cut: Option<f64>,
}

impl CutExtents {
    /// Before the first item.
    pub fn new() -> CutExtents {
        CutExtents::default()
    }

    /// Follows `machine`'s per-axis (dog-leg) rapids along the path its axes take.
    pub fn per_axis_rapids(&mut self, machine: &crate::machine::Machine) {
        self.follower.per_axis_rapids(machine);
    }

    /// Takes one item of the stream.
    pub fn add(&mut self, item: &Item) {
        let Followed::Move(motion) = self.follower.follow(item) else {
            return;
        };
        if motion.rapid {
            return;
        }
        self.widest = self.widest.max(self.follower.tool().shape.radius());
        if self.low.is_none() {
            self.high = motion.from;
        }
        let (low, high) = (&mut self.low, &mut self.high);
        let mut grow = |p: [f64; 3]| {
            let low = low.get_or_insert(p);
            for i in 0..3 {
                low[i] = low[i].min(p[i]);
                high[i] = high[i].max(p[i]);
            }
        };
        grow(motion.from);
        motion.for_each_point(0.01, grow);
        // The first pass is the first feed across X or Y: feeds along Z before it are approaches.
        if self.first_cut.is_none() {
            let (mut lowest, mut across) = (motion.from[2], false);
            motion.for_each_point(0.01, |p| {
                lowest = lowest.min(p[2]);
                across |= (p[0] - motion.from[0]).hypot(p[1] - motion.from[1]) > 1e-9;
            });
            self.first_cut = across.then_some(lowest);
        }
    }

    /// The default stock: the cutting moves' extents widened by the widest tool's radius and
    /// 1 mm in X and Y, from 1 mm below the deepest cut up to Z 0 when the cuts go below it
    /// and start above it (the usual zero on the part's top), else up to the highest cut.
    /// `None` when the program cuts nothing.
    pub fn stock(&self) -> Option<[[f64; 3]; 2]> {
        let low = self.low?;
        let high = self.high;
        let margin = self.widest + 1.0;
        let top = if low[2] < 0.0 && high[2] >= 0.0 {
            0.0
        } else {
            high[2]
        };
        let bottom = low[2] - 1.0;
        Some([
            [low[0] - margin, low[1] - margin, bottom],
            [high[0] + margin, high[1] + margin, top.max(bottom + 0.1)],
        ])
    }

    /// Issue 21's other rule: the default stock ([`CutExtents::stock`]) with its top lowered to
    /// the depth the first pass (the first feed across X or Y) reaches, for programs whose first
    /// pass faces the part: rapids down to that face are then no crash. Never raised.
    /// `None` when the program cuts nothing.
    pub fn stock_below_first_cut(&self) -> Option<[[f64; 3]; 2]> {
        let [low, mut high] = self.stock()?;
        let first = self.first_cut?;
        high[2] = high[2].min(first).max(low[2] + 0.1);
        Some([low, high])
    }
}

/// The grid's cell for a stock: `requested`, else 0.1 mm, or finer on a small stock (at least
/// 200 cells along its shorter side), and never more than `max_cells` cells in all.
pub fn resolution(stock: [[f64; 3]; 2], requested: Option<f64>, max_cells: usize) -> f64 {
    let (w, h) = (stock[1][0] - stock[0][0], stock[1][1] - stock[0][1]);
    let mut cell = requested.unwrap_or_else(|| 0.1f64.min(w.min(h) / 200.0));
    let cells = |cell: f64| (w / cell).ceil() * (h / cell).ceil();
    if cells(cell) > max_cells as f64 {
        cell = (w * h / max_cells as f64).sqrt() * 1.001;
    }
    cell.max(1e-4)
}

/// Material removed and time spent by one tool.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ToolReport {
    /// The tool.
    pub tool: Tool,
    /// Material it removed, mm^3.
    pub removed: f64,
    /// Time of its moves that removed material, seconds.
    pub cutting_seconds: f64,
}

/// Where the time of the motions went, seconds (from the planner's timings).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SimTimes {
    /// Cutting moves that removed material.
    pub cutting: f64,
    /// Cutting moves that removed nothing (in the air).
    pub feed_in_air: f64,
    /// Rapids.
    pub rapid: f64,
}

/// The events of a simulation: alarms (errors) and warnings, each with its block.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SimEvents {
    /// The events kept, in program order: at most 100 of each code.
    pub kept: Vec<Alarm>,
    /// How many of each code there were, kept or not.
    pub counts: Vec<(AlarmCode, usize)>,
}

impl SimEvents {
    fn push(&mut self, alarm: Alarm) {
        let code = alarm.code;
        let count = match self.counts.iter_mut().find(|(c, _)| *c == code) {
            Some((_, n)) => n,
            None => {
                self.counts.push((code, 0));
                &mut self.counts.last_mut().expect("just pushed").1
            }
        };
        *count += 1;
        if *count <= EVENTS_KEPT {
            self.kept.push(alarm);
        }
    }

    /// How many events of `code` there were.
    pub fn count(&self, code: AlarmCode) -> usize {
        self.counts
            .iter()
            .find(|(c, _)| *c == code)
            .map_or(0, |(_, n)| *n)
    }
}

/// The simulation: the stock, the tool following the stream, and what came of it.
#[derive(Clone, Debug)]
pub struct Simulation {
    grid: HeightField,
    follower: ToolFollower,
    tools: Vec<ToolReport>,
    times: SimTimes,
    events: SimEvents,
    unfollowed: Option<(Unfollowed, Span, usize)>,
}

impl Simulation {
    /// A simulation of `stock` (`[min, max]`, part coordinates) in cells of `cell` mm.
    pub fn new(stock: [[f64; 3]; 2], cell: f64) -> Simulation {
        Simulation::on(HeightField::new(stock, cell))
    }

    /// A simulation of a stock already in its grid (a cylinder, an STL: [`stock`]).
    pub fn on(grid: HeightField) -> Simulation {
        Simulation {
            grid,
            follower: ToolFollower::new(),
            tools: Vec::new(),
            times: SimTimes::default(),
            events: SimEvents::default(),
            unfollowed: None,
        }
    }

    /// Follows `machine`'s per-axis (dog-leg) rapids along the path its axes take: a rapid
    /// into the stock is found where the machine really goes.
    pub fn per_axis_rapids(&mut self, machine: &crate::machine::Machine) {
        self.follower.per_axis_rapids(machine);
    }

    /// Takes one item of the stream with its timing.
    pub fn add(&mut self, item: &Item, timing: &Timing) {
        match self.follower.follow(item) {
            Followed::Move(motion) => self.cut(&motion, timing.dt),
            Followed::ToolChange(tool, span) => self.change(tool, span),
            Followed::Unfollowed(why, span) => {
                self.unfollowed.get_or_insert((why, span, 0)).2 += 1;
            }
            Followed::Other => {}
        }
    }

    fn change(&mut self, tool: Tool, span: Span) {
        if !self.tools.iter().any(|t| t.tool.number == tool.number) {
            if !tool.described {
                self.events.push(
                    Alarm::warning(
                        AlarmCode::ToolWithoutShape,
                        span,
                        format!(
                            "T{} has no shape in the machine file: simulated as a flat end mill of radius {}",
                            tool.number,
                            tool.shape.radius()
                        ),
                    )
                    .with_help(AlarmCode::ToolWithoutShape.help()),
                );
            }
            self.tools.push(ToolReport {
                tool,
                removed: 0.0,
                cutting_seconds: 0.0,
            });
        }
    }

    fn cut(&mut self, motion: &ToolMove, seconds: f64) {
        let tool = self.follower.tool();
        let tolerance = self.grid.cell() / 4.0;
        let mut total = CutResult::default();
        let mut from = motion.from;
        let grid = &mut self.grid;
        motion.for_each_point(tolerance, |to| {
            let cut = grid.cut(from, to, &tool.shape);
            total.removed += cut.removed;
            total.depth = total.depth.max(cut.depth);
            total.beyond_cutting_length =
                max_option(total.beyond_cutting_length, cut.beyond_cutting_length);
            if let Some(hit) = cut.holder {
                if total.holder.is_none_or(|worst| hit.1 > worst.1) {
                    total.holder = Some(hit);
                }
            }
            from = to;
        });
        let removes = total.removed > 1e-9;
        match (motion.rapid, removes) {
            (true, _) => self.times.rapid += seconds,
            (false, true) => self.times.cutting += seconds,
            (false, false) => self.times.feed_in_air += seconds,
        }
        if removes {
            self.credit(
                tool,
                total.removed,
                if motion.rapid { 0.0 } else { seconds },
            );
        }
        self.events_of(motion, tool, &total);
    }

    fn credit(&mut self, tool: Tool, removed: f64, seconds: f64) {
        let entry = match self
            .tools
            .iter_mut()
            .position(|t| t.tool.number == tool.number)
        {
            Some(i) => &mut self.tools[i],
            None => {
                self.tools.push(ToolReport {
                    tool,
                    removed: 0.0,
                    cutting_seconds: 0.0,
                });
                self.tools.last_mut().expect("just pushed")
            }
        };
        entry.removed += removed;
        entry.cutting_seconds += seconds;
    }

    /// The events of one move: alarms for a rapid into the stock, flutes too short and the
    /// shank or holder touching; warnings for cutting with the spindle stopped and plunging a
    /// tool that cannot cut at its centre.
    fn events_of(&mut self, motion: &ToolMove, tool: Tool, cut: &CutResult) {
        let (span, t) = (motion.span, tool.number);
        let removes = cut.removed > 1e-9;
        // Within a quarter cell (the chord tolerance of arcs) the simulated surface itself is
        // uncertain: a rapid grazing it by less is not taken for a crash.
        if motion.rapid && removes && cut.depth > self.grid.cell() / 4.0 {
            self.events.push(
                Alarm::error(
                    AlarmCode::RapidIntoStock,
                    span,
                    format!("rapid into the stock: T{t} goes {:.3} mm deep", cut.depth),
                )
                .with_help(AlarmCode::RapidIntoStock.help()),
            );
        }
        if let Some(depth) = cut.beyond_cutting_length {
            self.events.push(
                Alarm::error(
                    AlarmCode::BeyondCuttingLength,
                    span,
                    format!(
                        "T{t} cuts {depth:.3} mm deep, beyond its cutting length of {} mm",
                        tool.shape.cutting_length
                    ),
                )
                .with_help(AlarmCode::BeyondCuttingLength.help()),
            );
        }
        if let Some((body, depth)) = cut.holder {
            let part = match body {
                Body::Shank => "shank",
                Body::Holder => "holder",
            };
            self.events.push(
                Alarm::error(
                    AlarmCode::HolderCollision,
                    span,
                    format!("the {part} of T{t} touches the stock, its tip {depth:.3} mm deep"),
                )
                .with_help(AlarmCode::HolderCollision.help()),
            );
        }
        if removes && !motion.rapid && !self.follower.spindle_turning() {
            self.events.push(Alarm::warning(
                AlarmCode::CuttingWithSpindleStopped,
                span,
                format!("T{t} removes material with the spindle stopped"),
            ));
        }
        let horizontal = (motion.to[0] - motion.from[0]).hypot(motion.to[1] - motion.from[1]);
        let descends = motion.to[2] < motion.from[2] - 1e-9;
        // A plunge: down into material while moving less than the tool's radius sideways, so
        // the dead centre of the end meets the stock.
        if removes && descends && !tool.shape.center_cutting && horizontal < tool.shape.radius() {
            self.events.push(
                Alarm::warning(
                    AlarmCode::PlungeWithoutCenterCutting,
                    span,
                    format!(
                        "T{t} cannot cut at its centre and plunges {:.3} mm into the stock",
                        cut.depth
                    ),
                )
                .with_help(AlarmCode::PlungeWithoutCenterCutting.help()),
            );
        }
    }

    /// The stock as cut so far.
    pub fn grid(&self) -> &HeightField {
        &self.grid
    }

    /// Material removed so far, mm^3 (the sum over the tools).
    pub fn removed(&self) -> f64 {
        self.tools.iter().map(|t| t.removed).sum()
    }

    /// Material removed and cutting time by tool, in the order the tools came.
    pub fn tools(&self) -> &[ToolReport] {
        &self.tools
    }

    /// Where the motion time went.
    pub fn times(&self) -> SimTimes {
        self.times
    }

    /// The events so far, with a warning for the moves that could not be cut, if any.
    pub fn events(&self) -> SimEvents {
        let mut events = self.events.clone();
        if let Some((why, span, count)) = self.unfollowed {
            events.push(
                Alarm::warning(
                    AlarmCode::NotSimulated,
                    span,
                    format!(
                        "{count} move(s) not simulated, from this block on: {}",
                        why.describe()
                    ),
                )
                .with_help(AlarmCode::NotSimulated.help()),
            );
        }
        events
    }
}

fn max_option(a: Option<f64>, b: Option<f64>) -> Option<f64> {
    match (a, b) {
        (Some(a), Some(b)) => Some(a.max(b)),
        (a, None) => a,
        (None, b) => b,
    }
}
