//! Where the time goes: a consumer of timed segments that sums them by kind and by tool and
//! keeps the slowest blocks.
//!
//! Memory is constant: one total per kind, one per tool used, and the [`SLOWEST`] slowest
//! blocks. The segments of one block come one after another in the stream, so a block's time is
//! complete when the next block's first segment arrives.

use super::Timing;
use crate::motion::{Segment, SegmentKind};
use crate::source::Span;
use std::collections::BTreeMap;

/// How many of the slowest blocks a report keeps.
pub const SLOWEST: usize = 10;

/// What a segment's time counts as.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum TimeKind {
    /// Rapid moves.
    Rapid,
    /// Lines and arcs at feed.
    Cutting,
    /// G04.
    Dwell,
    /// M06.
    ToolChange,
    /// Spindle starts, stops and orientations, and anything else that takes time.
    Other,
}

impl TimeKind {
    /// All kinds, in report order.
    pub const ALL: [TimeKind; 5] = [
        TimeKind::Rapid,
        TimeKind::Cutting,
        TimeKind::Dwell,
        TimeKind::ToolChange,
        TimeKind::Other,
    ];

    /// The kind of a segment.
    pub fn of(kind: &SegmentKind) -> TimeKind {
        match kind {
            SegmentKind::Rapid { .. } => TimeKind::Rapid,
            SegmentKind::Line { .. } | SegmentKind::Arc { .. } => TimeKind::Cutting,
            SegmentKind::Dwell { .. } => TimeKind::Dwell,
            SegmentKind::ToolChange { .. } => TimeKind::ToolChange,
            _ => TimeKind::Other,
        }
    }

    /// `rapid`, `cutting`, `dwell`, `tool_change` or `other`.
    pub fn as_str(self) -> &'static str {
        match self {
            TimeKind::Rapid => "rapid",
            TimeKind::Cutting => "cutting",
            TimeKind::Dwell => "dwell",
            TimeKind::ToolChange => "tool_change",
            TimeKind::Other => "other",
        }
    }
}

/// One block and the time its segments took.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlockTime {
    /// The block.
    pub span: Span,
    /// Seconds.
    pub seconds: f64,
}

/// Totals of a timed run.
#[derive(Clone, Debug, Default)]
pub struct TimeReport {
    /// The program's time, seconds.
    pub total: f64,
    by_kind: [f64; 5],
    /// Seconds with each tool in the spindle (None: before the first tool change), tool change
    /// times included with the tool put in.
    pub by_tool: BTreeMap<Option<u32>, f64>,
    tool: Option<u32>,
    current: Option<BlockTime>,
    slowest: Vec<BlockTime>,
}

impl TimeReport {
    /// An empty report.
    pub fn new() -> TimeReport {
        TimeReport::default()
    }

    /// Adds one segment with its timing.
    pub fn add(&mut self, segment: &Segment, timing: &Timing) {
        let kind = TimeKind::of(&segment.kind);
        if let SegmentKind::ToolChange { tool, .. } = segment.kind {
            self.tool = Some(tool);
        }
        let dt = timing.dt;
        self.total = self.total.max(timing.t + dt);
        self.by_kind[kind as usize] += dt;
        *self.by_tool.entry(self.tool).or_insert(0.0) += dt;
        let span = segment.span;
        match &mut self.current {
            Some(block) if same_block(block.span, span) => block.seconds += dt,
            _ => {
                self.close_block();
                self.current = Some(BlockTime { span, seconds: dt });
            }
        }
    }

    /// Seconds spent on one kind.
    pub fn seconds(&self, kind: TimeKind) -> f64 {
        self.by_kind[kind as usize]
    }

    /// The slowest blocks, slowest first (at most [`SLOWEST`]); ties keep program order.
    pub fn slowest_blocks(&self) -> Vec<BlockTime> {
        let mut all = self.slowest.clone();
        if let Some(block) = self.current {
            insert_slow(&mut all, block);
        }
        all
    }

    fn close_block(&mut self) {
        if let Some(block) = self.current.take() {
            insert_slow(&mut self.slowest, block);
        }
    }
}

fn same_block(a: Span, b: Span) -> bool {
    a.file == b.file && a.line == b.line
}

/// Keeps `list` sorted slowest first and at most [`SLOWEST`] long; blocks that take no time are
/// not worth listing.
fn insert_slow(list: &mut Vec<BlockTime>, block: BlockTime) {
    if block.seconds <= 0.0 {
        return;
    }
    if list.len() == SLOWEST && list.last().is_some_and(|b| b.seconds >= block.seconds) {
        return;
    }
    let at = list.partition_point(|b| b.seconds >= block.seconds);
    list.insert(at, block);
    list.truncate(SLOWEST);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::{PlanOptions, Planner};
    use crate::{interpret_str, Machine, Options};

    fn report(program: &str) -> TimeReport {
        let machine = Machine::default();
        let stream = interpret_str(program, &machine, Options::default());
        let mut report = TimeReport::new();
        for item in Planner::new(stream, &machine, PlanOptions::default()) {
            if let Some(timed) = item.expect("no alarm").segment() {
                report.add(&timed.segment, &timed.timing());
            }
        }
        report
    }

    #[test]
    fn time_is_split_by_kind_and_tool_and_adds_up() {
        let r = report("G0 X10.\nG1 X20. F600.\nG4 X1.\nM6 T3\nG1 X30.\nM30\n");
        let by_kind: f64 = TimeKind::ALL.iter().map(|k| r.seconds(*k)).sum();
        assert!((by_kind - r.total).abs() < 1e-9);
        let by_tool: f64 = r.by_tool.values().sum();
        assert!((by_tool - r.total).abs() < 1e-9);
        assert_eq!(r.seconds(TimeKind::Dwell), 1.0);
        assert!(r.by_tool.contains_key(&Some(3)) && r.by_tool.contains_key(&None));
    }

    #[test]
    fn the_slowest_blocks_come_first_and_are_at_most_ten() {
        let mut program = String::new();
        for i in 1..=30 {
            program += &format!("G1 X{}. F600.\n", i * i);
        }
        let slowest = report(&(program + "M30\n")).slowest_blocks();
        assert_eq!(slowest.len(), SLOWEST);
        assert!(slowest.windows(2).all(|w| w[0].seconds >= w[1].seconds));
        assert_eq!(slowest[0].span.line, 30);
    }
}
