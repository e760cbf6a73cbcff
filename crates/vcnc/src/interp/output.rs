//! The output of the blocks: the queue the stream is taken from, and the ordered chain of
//! stages a segment passes on its way there.
//!
//! Most programs have no stage: the executor's segments go straight into the queue, built in
//! place. Cutter compensation (G41/G42) is the first stage when it is on: it holds a move until
//! the next one shows where the corner is, so the items queued behind the held move wait too
//! (`held`). The transformations of finished motion come after it, in order (G12.1 polar
//! coordinate interpolation, G07.1 cylindrical interpolation, the 5-axis kinematic transform, and whatever a dialect adds; G07's hypothetical axes last): each reads the released part of its own
//! input queue and writes into the next stage's input, the last into the output queue. A stage
//! never reads program text or modal state; the executor starts and ends stages.

use super::comp::Compensator;
use super::corner_override::CornerStage;
use super::cylindrical::CylindricalStage;
use super::hypothetical::HypotheticalStage;
use super::kernel::BlockOrigin;
use super::polar_interpolation::PolarStage;
use super::tool_center::KinematicStage;
use crate::alarm::Alarm;
use crate::machine::AXES;
use crate::motion::{
    alarm_item, Item as Emitted, Plane, Segment, SegmentKind, StreamItem, WorkFrame,
};

/// An item of the stream.
type Item = StreamItem;

/// A stage between the executor and the output queue.
#[derive(Debug)]
pub(crate) enum Stage {
    /// Cutter radius compensation; always the first stage.
    Compensation(Box<Compensator>),
    /// G62's inner-corner override of the compensated path; always right behind compensation.
    CornerOverride(Box<CornerStage>),
    /// G12.1 polar coordinate interpolation: Cartesian motion to machine X and C.
    PolarInterpolation(Box<PolarStage>),
    /// G07.1 cylindrical interpolation: the unrolled surface to the linear and rotary axes.
    Cylindrical(Box<CylindricalStage>),
    /// G43.4 or G53.1: tool tip motion in the workpiece to the joints of a 5-axis machine.
    Kinematics(Box<KinematicStage>),
    /// G07: the hypothetical axes held where they stand; always the last stage.
    Hypothetical(Box<HypotheticalStage>),
}

/// What a transformation stage leaves when it ends: where the machine is.
enum Ended {
    /// G13.1: the plane before G12.1 and the machine position.
    Polar(Plane, [f64; AXES]),
    /// The kinematic transform: the machine position (joints).
    Kinematics([f64; AXES]),
    /// The inner-corner override: nothing.
    CornerOverride,
    /// G07.1 C0: the plane before G07.1 and the machine position.
    Cylindrical(Plane, [f64; AXES]),
    /// G07 α1 for the last hypothetical axis: nothing.
    Hypothetical,
}

/// The queue of what the blocks produced and nobody has taken yet: a few items for
/// [`Iterator::next`], or the caller's whole batch for `Interpreter::next_batch`.
#[derive(Debug, Default)]
pub(crate) struct Output {
    pub(super) items: Vec<Item>,
    /// Items from this index on wait for cutter compensation to know where a move ends.
    pub(super) held: Option<usize>,
    /// The stages in front of the queue, in the order a segment passes them.
    stages: Vec<Stage>,
    /// An alarm raised while queueing (a corner compensation cannot make): it ends the run.
    failed: Option<Alarm>,
}

impl Output {
    /// Records a segment of the block `block`.
    #[inline(always)]
    pub(crate) fn push(&mut self, block: &impl BlockOrigin, kind: SegmentKind) {
        if self.stages.is_empty() {
            // Built where it goes: a segment is a few hundred bytes, and this runs per move.
            self.items.push(Ok(Emitted::Segment(Segment {
                kind,
                span: block.span(),
                sequence: block.sequence(),
            })));
        } else {
            self.push_staged(block, kind);
        }
    }

    /// The queue itself when no stage is on: a segment pushed there is built in place (built
    /// before the test, as for [`Output::push`], it was built on the stack and copied over).
    #[inline(always)]
    pub(crate) fn direct(&mut self) -> Option<&mut Vec<Item>> {
        self.stages.is_empty().then_some(&mut self.items)
    }

    /// Records a segment of the block `block`, made by `kind` on the queue's own path and on the
    /// staged one apart: made before the test, a large segment was built on the stack and
    /// copied into the queue.
    #[inline(always)]
    pub(crate) fn push_with(
        &mut self,
        block: &impl BlockOrigin,
        kind: impl FnOnce() -> SegmentKind,
    ) {
        match self.direct() {
            Some(items) => items.push(Ok(Emitted::Segment(Segment {
                kind: kind(),
                span: block.span(),
                sequence: block.sequence(),
            }))),
            None => self.push_staged(block, kind()),
        }
    }

    /// Whether cutter compensation is on.
    #[inline(always)]
    pub(crate) fn compensating(&self) -> bool {
        self.compensation().is_some()
    }

    /// The cutter compensation in force.
    pub(crate) fn compensation(&self) -> Option<&Compensator> {
        match self.stages.first() {
            Some(Stage::Compensation(comp)) => Some(comp),
            _ => None,
        }
    }

    /// The cutter compensation in force, to change it.
    pub(crate) fn compensation_mut(&mut self) -> Option<&mut Compensator> {
        match self.stages.first_mut() {
            Some(Stage::Compensation(comp)) => Some(comp),
            _ => None,
        }
    }

    /// Cutter compensation starts: the first stage (in place of one that was on).
    pub(crate) fn start_compensation(&mut self, comp: Compensator) {
        match self.stages.first_mut() {
            Some(Stage::Compensation(on)) => **on = comp,
            _ => self.stages.insert(0, Stage::Compensation(Box::new(comp))),
        }
    }

    /// Cutter compensation leaves the chain (what it holds stays in it, for
    /// [`Output::finish_compensation`]).
    pub(crate) fn take_compensation(&mut self) -> Option<Compensator> {
        match self.stages.first() {
            Some(Stage::Compensation(_)) => match self.stages.remove(0) {
                Stage::Compensation(comp) => Some(*comp),
                _ => None,
            },
            _ => None,
        }
    }

    /// The inner-corner override (G62) starts, right behind compensation.
    pub(crate) fn start_corner_override(&mut self, stage: CornerStage) {
        let at = usize::from(self.compensating());
        self.stages
            .insert(at, Stage::CornerOverride(Box::new(stage)));
    }

    /// The inner-corner override ends with compensation: what it holds is passed on.
    fn end_corner_override(&mut self) {
        let at = usize::from(self.compensating());
        if matches!(self.stages.get(at), Some(Stage::CornerOverride(_))) {
            self.end_transform(at);
        }
    }

    /// Whether any stage is on (and may hold items until it ends).
    pub(crate) fn has_stages(&self) -> bool {
        !self.stages.is_empty()
    }

    /// Whether polar coordinate interpolation (G12.1) is on.
    pub(crate) fn polar_interpolating(&self) -> bool {
        self.stages
            .iter()
            .any(|stage| matches!(stage, Stage::PolarInterpolation(_)))
    }

    /// Polar coordinate interpolation starts: a stage behind the others.
    pub(crate) fn start_polar_interpolation(&mut self, stage: PolarStage) {
        self.stages.push(Stage::PolarInterpolation(Box::new(stage)));
    }

    /// Polar coordinate interpolation ends: what it holds is converted. The plane before G12.1
    /// and the machine position where its last piece ended, if it was on.
    pub(crate) fn end_polar_interpolation(&mut self) -> Option<(Plane, [f64; AXES])> {
        let at = self
            .stages
            .iter()
            .position(|stage| matches!(stage, Stage::PolarInterpolation(_)))?;
        match self.end_transform(at) {
            Some(Ended::Polar(plane, position)) => Some((plane, position)),
            _ => None,
        }
    }

    /// The rotary axis and the slot carrying its surface length while cylindrical
    /// interpolation (G07.1) is on.
    pub(crate) fn cylindrical_axes(&self) -> Option<(crate::machine::Axis, crate::machine::Axis)> {
        self.stages.iter().find_map(|stage| match stage {
            Stage::Cylindrical(stage) => Some(stage.axes()),
            _ => None,
        })
    }

    /// Cylindrical interpolation starts: a stage behind the others.
    pub(crate) fn start_cylindrical_interpolation(&mut self, stage: CylindricalStage) {
        self.stages.push(Stage::Cylindrical(Box::new(stage)));
    }

    /// Cylindrical interpolation ends: what it holds is converted. The plane before G07.1 and
    /// the machine position where its last piece ended, if it was on.
    pub(crate) fn end_cylindrical_interpolation(&mut self) -> Option<(Plane, [f64; AXES])> {
        let at = self
            .stages
            .iter()
            .position(|stage| matches!(stage, Stage::Cylindrical(_)))?;
        match self.end_transform(at) {
            Some(Ended::Cylindrical(plane, position)) => Some((plane, position)),
            _ => None,
        }
    }

    /// Whether an axis is hypothetical (G07).
    pub(crate) fn hypothetical(&self) -> bool {
        matches!(self.stages.last(), Some(Stage::Hypothetical(_)))
    }

    /// The machine position of each hypothetical axis, while one is (G07).
    pub(crate) fn frozen_axes(&self) -> Option<[Option<f64>; AXES]> {
        match self.stages.last() {
            Some(Stage::Hypothetical(stage)) => Some(stage.frozen()),
            _ => None,
        }
    }

    /// The hypothetical axes' stage, to change which axes it holds.
    pub(crate) fn hypothetical_mut(&mut self) -> Option<&mut HypotheticalStage> {
        match self.stages.last_mut() {
            Some(Stage::Hypothetical(stage)) => Some(stage),
            _ => None,
        }
    }

    /// An axis becomes hypothetical: the stage goes behind the others.
    pub(crate) fn start_hypothetical(&mut self, stage: HypotheticalStage) {
        self.stages.push(Stage::Hypothetical(Box::new(stage)));
    }

    /// No axis is hypothetical any more: what the stage holds is converted.
    pub(crate) fn end_hypothetical(&mut self) {
        if self.hypothetical() {
            self.end_transform(self.stages.len() - 1);
        }
    }

    /// The kinematic transform in force (G43.4, G43.5, G53.1).
    pub(crate) fn kinematics(&self) -> Option<&KinematicStage> {
        self.stages.iter().find_map(|stage| match stage {
            Stage::Kinematics(stage) => Some(&**stage),
            _ => None,
        })
    }

    /// The kinematic transform in force (G43.4, G53.1), to change it.
    pub(crate) fn kinematics_mut(&mut self) -> Option<&mut KinematicStage> {
        self.stages.iter_mut().find_map(|stage| match stage {
            Stage::Kinematics(stage) => Some(&mut **stage),
            _ => None,
        })
    }

    /// The kinematic transform starts: a stage behind the others.
    pub(crate) fn start_kinematics(&mut self, stage: KinematicStage) {
        self.stages.push(Stage::Kinematics(Box::new(stage)));
    }

    /// The kinematic transform ends: what it holds is converted. The machine position (joints)
    /// where its last piece ended, if it was on.
    pub(crate) fn end_kinematics(&mut self) -> Option<[f64; AXES]> {
        let at = self
            .stages
            .iter()
            .position(|stage| matches!(stage, Stage::Kinematics(_)))?;
        match self.end_transform(at) {
            Some(Ended::Kinematics(position)) => Some(position),
            _ => None,
        }
    }

    /// Removes the transformation stage `at`, its input settled into the queue behind it.
    fn end_transform(&mut self, at: usize) -> Option<Ended> {
        let stage = self.stages.remove(at);
        let (items, _) = input_of(&mut self.stages[at..], &mut self.items, &mut self.held);
        let ended = match stage {
            Stage::PolarInterpolation(stage) => {
                let (plane, position) = stage.flush(items);
                Ended::Polar(plane, position)
            }
            Stage::Kinematics(stage) => Ended::Kinematics(stage.flush(items)),
            Stage::CornerOverride(stage) => {
                stage.flush(items);
                Ended::CornerOverride
            }
            Stage::Cylindrical(stage) => {
                let (plane, position) = stage.flush(items);
                Ended::Cylindrical(plane, position)
            }
            Stage::Hypothetical(mut stage) => {
                stage.pieces.flush(items);
                Ended::Hypothetical
            }
            Stage::Compensation(_) => return None,
        };
        self.settle();
        Some(ended)
    }

    /// A segment through the stages that are on (kept out of line: the plain path is the hot
    /// one).
    #[inline(never)]
    fn push_staged(&mut self, block: &impl BlockOrigin, kind: SegmentKind) {
        let segment = Segment {
            kind,
            span: block.span(),
            sequence: block.sequence(),
        };
        let failing = self.failed.is_some();
        let (comp, items, held) = self.entry();
        match comp {
            // The compensator's alarm ends the run with this block: the block's further moves
            // (a contour's held cuts) meet a compensator left at the element it refused.
            Some(_) if failing => {}
            Some(comp) => {
                if let Err(alarm) = comp.push(segment, items, held) {
                    self.failed.get_or_insert(alarm);
                }
            }
            None => items.push(Ok(Emitted::Segment(segment))),
        }
        self.settle();
    }

    /// The compensation stage, if on, and the queue a segment enters after it: the first
    /// transformation's input, or the output queue.
    fn entry(&mut self) -> (Option<&mut Compensator>, &mut Vec<Item>, &mut Option<usize>) {
        let first = usize::from(self.compensating());
        let (head, rest) = self.stages.split_at_mut(first);
        let comp = match head.first_mut() {
            Some(Stage::Compensation(comp)) => Some(&mut **comp),
            _ => None,
        };
        let (items, held) = input_of(rest, &mut self.items, &mut self.held);
        (comp, items, held)
    }

    /// Moves what each transformation's input has released through it, in the chain's order.
    fn settle(&mut self) {
        let first = usize::from(self.compensating());
        if let [Stage::Compensation(comp), Stage::CornerOverride(corner), ..] = &mut self.stages[..]
        {
            corner.set_offset(comp.offset());
        }
        for at in first..self.stages.len() {
            if let Some((stage, behind)) = self.stages[at..].split_first_mut() {
                let (items, _) = input_of(behind, &mut self.items, &mut self.held);
                match stage {
                    Stage::PolarInterpolation(stage) => stage.settle(items),
                    Stage::Kinematics(stage) => stage.settle(items),
                    Stage::CornerOverride(stage) => stage.settle(items),
                    Stage::Cylindrical(stage) => stage.settle(items),
                    Stage::Hypothetical(stage) => stage.pieces.settle(items),
                    Stage::Compensation(_) => {}
                }
            }
        }
    }

    /// How many items can be handed out now.
    pub(super) fn releasable(&self) -> usize {
        self.held.unwrap_or(self.items.len())
    }

    /// Makes the caller's batch `out` the queue, its items first and what the queue held
    /// after them: the blocks then queue their items straight into it, and no item is moved
    /// twice. [`Output::give_back`] ends the loan.
    pub(super) fn lend(&mut self, out: &mut Vec<Item>) {
        let base = out.len();
        out.append(&mut self.items);
        self.held = self.held.map(|h| h + base);
        std::mem::swap(&mut self.items, out);
    }

    /// Ends [`Output::lend`]: `out` gets the items that can be handed out, what waits for
    /// compensation stays queued.
    pub(super) fn give_back(&mut self, out: &mut Vec<Item>) {
        std::mem::swap(&mut self.items, out);
        if let Some(held) = self.held {
            self.items = out.split_off(held);
            self.held = Some(0);
        }
    }

    /// A check cut the queue at an item and added its alarm: what compensation or G12.1 held
    /// is dropped with the cut (those blocks never moved), and the whole queue is released.
    pub(super) fn cut_by_check(&mut self) {
        self.held = None;
        self.reset_stages();
    }

    /// Nothing waits any more: the program is over.
    pub(super) fn finish(&mut self) {
        if let Some(mut comp) = self.take_compensation() {
            if let Err(alarm) = self.finish_compensation(&mut comp) {
                self.stop(alarm);
            }
        }
        // The program ends in G12.1 (or G43.4): reset cancels the mode (spec 1.13.2 rule 2).
        while !self.stages.is_empty() {
            self.end_transform(0);
        }
        self.held = None;
    }

    /// Whether an alarm raised while queueing waits to end the run.
    pub(super) fn failing(&self) -> bool {
        self.failed.is_some()
    }

    /// The alarm raised while queueing, once.
    pub(crate) fn take_failure(&mut self) -> Option<Alarm> {
        self.failed.take()
    }

    /// Ends compensation, taken out of the chain: whatever is pending is written out.
    ///
    /// # Errors
    /// Interference at the pending element's end.
    pub(crate) fn finish_compensation(&mut self, comp: &mut Compensator) -> Result<(), Alarm> {
        let (_, items, held) = self.entry();
        let finished = comp.finish(items, held);
        self.settle();
        self.end_corner_override();
        finished
    }

    /// Runs `change` on the compensation in force, with the queue its moves enter.
    ///
    /// # Errors
    /// The alarm `change` gives.
    pub(crate) fn change_compensation(
        &mut self,
        change: impl FnOnce(&mut Compensator, &mut Vec<Item>, &mut Option<usize>) -> Result<(), Alarm>,
    ) -> Result<(), Alarm> {
        let changed = match self.entry() {
            (Some(comp), items, held) => change(comp, items, held),
            (None, _, _) => Ok(()),
        };
        self.settle();
        changed
    }

    /// G28, G29, G30, G53 or G92 while compensating: cancelled for this block.
    ///
    /// # Errors
    /// Interference at the pending element's end.
    pub(crate) fn suspend_compensation(&mut self) -> Result<(), Alarm> {
        let suspended = match self.entry() {
            (Some(comp), items, held) => comp.suspend(items, held),
            (None, _, _) => Ok(()),
        };
        self.settle();
        suspended
    }

    /// A block ends: compensation counts blocks without motion in the plane.
    ///
    /// # Errors
    /// Interference where a pending element had to end.
    pub(super) fn end_block(&mut self) -> Result<(), Alarm> {
        let ended = match self.entry() {
            (Some(comp), items, held) => comp.end_block(items, held),
            (None, _, _) => Ok(()),
        };
        self.settle();
        ended
    }

    /// Tells the stream of a new frame, before the move made in it.
    pub(crate) fn push_frame(&mut self, frame: WorkFrame) {
        self.push_item(Ok(Emitted::Frame(frame)));
    }

    /// Records an alarm (a warning, or the error that ends the run).
    pub(crate) fn push_warning(&mut self, alarm: Alarm) {
        self.push_item(alarm_item(alarm));
    }

    /// Queues an item behind everything queued before it.
    pub(super) fn push_item(&mut self, item: Item) {
        let (_, items, _) = self.entry();
        items.push(item);
        self.settle();
    }

    /// An error ends the run. With compensation looking ahead, the control stops before the
    /// block that was waiting for this one: the pending move and the moves held after it never
    /// happen (their warnings stay).
    pub(super) fn stop(&mut self, alarm: Alarm) {
        let (comp, items, held) = self.entry();
        if let Some(held) = held.take() {
            let tail = items.split_off(held);
            items.extend(
                tail.into_iter()
                    .filter(|item| matches!(item, Ok(Emitted::Warning(_)) | Err(_))),
            );
        }
        if let Some(comp) = comp {
            comp.abandon();
        }
        self.settle();
        // What the corner override holds was released by compensation: it moves.
        self.end_corner_override();
        self.items.push(Err(alarm));
    }

    /// Every stage ends without a word: the program starts over (a reset).
    pub(super) fn reset_stages(&mut self) {
        self.stages.clear();
    }
}

/// The input queue of the first of `stages` (all transformations), or the output queue when
/// there is none.
fn input_of<'a>(
    stages: &'a mut [Stage],
    items: &'a mut Vec<Item>,
    held: &'a mut Option<usize>,
) -> (&'a mut Vec<Item>, &'a mut Option<usize>) {
    match stages.first_mut() {
        Some(Stage::PolarInterpolation(stage)) => (&mut stage.staged, &mut stage.held),
        Some(Stage::Kinematics(stage)) => (&mut stage.staged, &mut stage.held),
        Some(Stage::CornerOverride(stage)) => (&mut stage.staged, &mut stage.held),
        Some(Stage::Cylindrical(stage)) => (&mut stage.pieces.staged, &mut stage.pieces.held),
        Some(Stage::Hypothetical(stage)) => (&mut stage.pieces.staged, &mut stage.pieces.held),
        Some(Stage::Compensation(_)) | None => (items, held),
    }
}
