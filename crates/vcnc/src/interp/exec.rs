//! Executing one decoded block, in the order the control executes its parts.
//!
//! Order within a block (FANUC M-series practice): modal G codes, F, S, T, M06, spindle and
//! coolant M codes, G04, tool length compensation, one-shot coordinate codes (G10, G92, G92.1,
//! G52, G28, G29, G30, G53), the motion, then program stops and ends (M00, M01, M02, M30).
//! Each part is a function of its own module; this file only sequences them.

use super::decode::{Command, GWord, Value};
use super::frames::Frames;
use super::kernel::{rollover_turn, same_place, KernelState};
use super::modal::{FeedMode, LengthComp, ModalState, MotionMode};
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::machine::{Axis, Machine, AXES};
use crate::motion::{EndKind, Feed, Move, SegmentKind, StopKind};
use crate::profile::RotaryRollover;
use crate::profile::{GCode, Group};

/// Everything the control remembers between blocks: the state every dialect shares, and the
/// ISO control's own.
#[derive(Clone, Debug)]
pub(crate) struct Executor {
    /// Setup, position and frames, tools, feed and spindle.
    pub(crate) kernel: KernelState,
    /// The G codes in force, and the numbers G43 and G41 read.
    pub(crate) modal: ModalState,
    /// The G28/G30 intermediate point, program coordinates, per axis.
    pub(crate) intermediate: [Option<f64>; AXES],
    /// G16: the last polar point, while polar coordinate command is on.
    pub(crate) polar: Option<super::polar_coordinates::PolarPoint>,
    /// G51 and G51.1 as set (the chain holds what they make together).
    pub(crate) scaling: super::frames::scaling::ScalingState,
    /// The canned cycle in force.
    pub(crate) cycle: Option<super::cycles::Cycle>,
    /// Where the last G31 ended, program coordinates (FANUC #5061-#5066).
    pub(crate) skip_position: [f64; AXES],
    /// The G06.2 curve whose blocks are being read.
    pub(crate) nurbs: Option<Box<super::nurbs::NurbsInput>>,
    /// What G31 and the tool setter touch.
    pub(crate) probe: std::sync::Arc<crate::probe::Probe>,
    /// The zone of stored stroke check 2 while G22 is in force.
    pub(crate) stroke_zone: Option<super::stroke_check::StrokeZone>,
    /// A FANUC G68.2 P2/P3 plane whose blocks are being read.
    pub(crate) plane_parts: super::tilted_plane::PlaneParts,
}

/// What one block did to the flow of the program.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Flow {
    /// Go on with the next block.
    Next,
    /// The program has ended.
    End,
}

/// Whom a block's axis words belong to, once its frame and one-shot codes have run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum AxisWords {
    /// The motion (or the canned cycle) of the block.
    ForMotion,
    /// A code that reads them as its own data (a centre, a G92 position, a G28 point).
    Taken,
}

impl Executor {
    pub(crate) fn new(machine: &Machine) -> Executor {
        let mut kernel = KernelState::new(machine);
        let modal = ModalState::power_on(&kernel.setup.profile().power_on);
        kernel.frames.select(modal.work_offset);
        Executor {
            kernel,
            intermediate: [None; AXES],
            polar: None,
            scaling: Default::default(),
            cycle: None,
            skip_position: [0.0; AXES],
            nurbs: None,
            plane_parts: Default::default(),
            probe: std::sync::Arc::new(crate::probe::Probe::new(
                &machine.probe,
                &machine.tool_offsets,
            )),
            stroke_zone: machine
                .stroke_check
                .on_at_power_on
                .then(|| super::stroke_check::StrokeZone::from_parameters(&machine.stroke_check)),
            modal,
        }
    }

    /// Runs one block.
    ///
    /// # Errors
    /// The alarm that stops the program at this block.
    pub(crate) fn run(&mut self, cmd: &Command, out: &mut Output) -> Result<Flow, Alarm> {
        self.apply_modal(cmd)?;
        // The common block takes the short path without a second call; a NURBS curve and the
        // stored stroke check, rare, are the other path's.
        if cmd.is_plain()
            && self.cycle.is_none()
            && !out.compensating()
            && self.nurbs.is_none()
            && self.stroke_zone.is_none()
            && !super::nurbs::starts(cmd)
        {
            return self.run_plain(cmd, out);
        }
        self.run_other(cmd, out)
    }

    /// Runs a block off the short path: a NURBS block, every stage of the block, and the stored
    /// stroke check of the moves it made.
    #[inline(never)]
    fn run_other(&mut self, cmd: &Command, out: &mut Output) -> Result<Flow, Alarm> {
        let released = out.items.len();
        let flow = if super::nurbs::takes(self, cmd) {
            super::nurbs::block(self, cmd, out).map(|()| Flow::Next)?
        } else if cmd.is_plain() && self.cycle.is_none() && !out.compensating() {
            self.run_plain(cmd, out)?
        } else {
            self.run_stages(cmd, out)?
        };
        if let Some(zone) = &self.stroke_zone {
            super::stroke_check::check_released(zone, out, released)?;
        }
        Ok(flow)
    }

    /// The block of a CAM program (a motion code, axis and centre words, F) outside canned
    /// cycles and cutter compensation: every stage of [`Executor::run_stages`] but the feed and
    /// the motion would find nothing to do in it, so they are not asked.
    // Inlined into `run`: the common block pays for one call, not two.
    #[inline(always)]
    fn run_plain(&mut self, cmd: &Command, out: &mut Output) -> Result<Flow, Alarm> {
        self.set_feed(cmd)?;
        if cmd.has_axis_words() || has_center_words(cmd) {
            match self.modal.motion {
                // The line, most blocks of a CAM program, is built here: through `motion`, out
                // of line, every block paid a call and its result came back through memory.
                MotionMode::Linear => self.plain_line(cmd, out)?,
                MotionMode::Arc(direction) => {
                    super::circular::plain_arc(self, cmd, direction, out)?;
                }
                _ => self.motion(cmd, false, out)?,
            }
        }
        self.end_inverse_time_feed();
        Ok(Flow::Next)
    }

    /// A G01 block on the short path: [`Executor::feed_to`] the block's target, with the line
    /// built where it is queued.
    #[inline(always)]
    fn plain_line(&mut self, cmd: &Command, out: &mut Output) -> Result<(), Alarm> {
        let to = self.block_target(cmd, false, out)?;
        if out.direct().is_none() {
            return self.feed_to(to, cmd, false, out);
        }
        if same_place(&to, &self.kernel.position) {
            return Ok(());
        }
        let feed = self.cutting_feed(cmd)?;
        let motion = self.move_to(to, cmd, out)?;
        // Pushed as a whole segment: through `Output::push` the kind was copied once more.
        if let Some(items) = out.direct() {
            items.push(Ok(crate::motion::Item::Segment(crate::motion::Segment {
                kind: SegmentKind::Line { motion, feed },
                span: cmd.span,
                sequence: cmd.sequence(),
            })));
        }
        Ok(())
    }

    /// Runs the stages of a block after its modal codes, in the control's order (the module
    /// doc gives it with its source); each stage is a function that finds nothing to do in a
    /// block without its words.
    ///
    /// # Errors
    /// The alarm that stops the program at this block.
    #[inline(never)]
    fn run_stages(&mut self, cmd: &Command, out: &mut Output) -> Result<Flow, Alarm> {
        super::cycles::apply_codes(self, cmd)?;
        self.set_feed(cmd)?;
        self.auxiliary_before_motion(cmd, out)?;
        self.dwell(cmd, out)?;
        let smoothing = self.smoothing_modes(cmd, out)?;
        let length_changed = super::length::apply(self, cmd, out)?;
        super::compensation::before_motion(self, cmd, out)?;
        refuse_presets_while_rotated(&self.kernel.frames, cmd)?;
        let axis_words = match self.frame_codes(cmd, out)? {
            AxisWords::ForMotion => self.one_shot_codes(cmd, out)?,
            taken => taken,
        };
        self.refuse_stray_e(cmd, smoothing)?;
        self.motion_stage(cmd, axis_words, length_changed, out)?;
        super::compensation::after_motion(self, cmd, out)?;
        self.end_inverse_time_feed();
        self.auxiliary_after_motion(cmd, out)
    }

    /// S, T, M06, the spindle and coolant M codes: what acts before the motion.
    fn auxiliary_before_motion(&mut self, cmd: &Command, out: &mut Output) -> Result<(), Alarm> {
        if cmd.has_auxiliary_words() {
            super::auxiliary::speed_and_tool(self, cmd, out)?;
            super::auxiliary::before_motion(self, cmd, out)?;
        }
        Ok(())
    }

    /// G04.
    fn dwell(&mut self, cmd: &Command, out: &mut Output) -> Result<(), Alarm> {
        match cmd.group(Group::NonModal) {
            Some(g) if g.code == GCode::Dwell => super::auxiliary::dwell(self, cmd, g.order, out),
            _ => Ok(()),
        }
    }

    /// G05, G05.1, G08: the high-speed and smoothing modes, and the settings of their tolerance
    /// (G187, G120.1); the code, if the block has one.
    fn smoothing_modes(&mut self, cmd: &Command, out: &mut Output) -> Result<Option<GWord>, Alarm> {
        let smoothing = cmd.group(Group::NonModal).filter(|g| {
            matches!(
                g.code,
                GCode::HighSpeedMode
                    | GCode::PathSmoothing
                    | GCode::LookAhead
                    | GCode::SmoothnessSetting
                    | GCode::MachiningConditions
            )
        });
        match smoothing {
            Some(g)
                if matches!(
                    g.code,
                    GCode::SmoothnessSetting | GCode::MachiningConditions
                ) =>
            {
                super::smoothness::run(self, cmd, g, out)?;
            }
            Some(g) => super::smoothing::switch(self, cmd, g)?,
            None => {}
        }
        Ok(smoothing)
    }

    /// The codes that change the program's frame: scaling, mirror, polar coordinates, polar
    /// coordinate interpolation and rotation, in that order. The axis words of a G68, G51 or
    /// G51.1 block are its centre, those of G12.1 its eccentricity.
    fn frame_codes(&mut self, cmd: &Command, out: &mut Output) -> Result<AxisWords, Alarm> {
        let scaling = cmd.group(Group::Scaling).map(|g| g.code);
        let mirror = cmd.group(Group::Mirror).map(|g| g.code);
        let rotation = cmd.group(Group::Rotation).map(|g| g.code);
        match scaling {
            Some(GCode::Scale) => super::frames::scaling::g51(self, cmd)?,
            Some(GCode::ScalingCancel) => super::frames::scaling::cancel(self, false),
            _ => {}
        }
        match mirror {
            Some(GCode::Mirror) => super::frames::scaling::g51_1(self, cmd)?,
            Some(GCode::MirrorCancel) => super::frames::scaling::cancel(self, true),
            _ => {}
        }
        match cmd.group(Group::Polar).map(|g| g.code) {
            Some(GCode::Polar) => super::polar_coordinates::g16(self),
            Some(GCode::PolarCancel) => super::polar_coordinates::g15(&mut self.polar),
            _ => {}
        }
        let polar_interpolation = cmd.group(Group::PolarInterpolation);
        match polar_interpolation {
            Some(g) if g.code == GCode::CylindricalInterpolation => {
                super::cylindrical::switch(self, cmd, g, out)?;
            }
            Some(g) => super::polar_interpolation::switch(self, cmd, g, out)?,
            None => {}
        }
        match rotation {
            Some(GCode::Rotate) => super::frames::rotation::g68(self, cmd)?,
            Some(GCode::TiltedPlane) => super::tilted_plane::g68_2(self, cmd)?,
            Some(GCode::RotationCancel) => super::tilted_plane::g69(self, out),
            _ => {}
        }
        let taken = polar_interpolation.is_some()
            || matches!(rotation, Some(GCode::Rotate | GCode::TiltedPlane))
            || scaling == Some(GCode::Scale)
            || mirror == Some(GCode::Mirror);
        Ok(if taken {
            AxisWords::Taken
        } else {
            AxisWords::ForMotion
        })
    }

    /// The one-shot codes of group 00 (G10, G92, G92.1, G52, G28, G29, G30, G53, G31, G04,
    /// G07, G22/G23, G27, G37/G37.1, circle cutting, hole patterns): whether the axis words are
    /// theirs. They run only in a block whose axis words no frame code took.
    fn one_shot_codes(&mut self, cmd: &Command, out: &mut Output) -> Result<AxisWords, Alarm> {
        use super::tool_measurement::Measurement::{TwoTouches, Window};
        let taken = match cmd.group(Group::NonModal).map(|g| g.code) {
            Some(GCode::DataInput) => super::data_input::g10(self, cmd)?,
            Some(GCode::SetCoordinates) => super::frames::coords::g92(self, cmd)?,
            Some(GCode::PresetCoordinates) => super::frames::coords::g92_1(self, cmd)?,
            Some(GCode::LocalCoordinates) => super::frames::coords::g52(self, cmd)?,
            Some(GCode::ReferenceReturn) => super::reference::g28(self, cmd, out)?,
            Some(GCode::NthReferenceReturn) => super::reference::g30(self, cmd, out)?,
            Some(GCode::ReturnFromReference) => super::reference::g29(self, cmd, out)?,
            Some(GCode::MachineCoordinates) => super::frames::coords::g53(self, cmd, out)?,
            Some(GCode::Dwell) => true,
            Some(GCode::ToolAxisDirection) => {
                super::tilted_plane::g53_1(self, cmd, out)?;
                true
            }
            Some(GCode::Skip) => {
                super::skip::g31(self, cmd, out)?;
                true
            }
            Some(GCode::StrokeCheckOn) => {
                super::stroke_check::g22(self, cmd, non_modal_span(cmd))?;
                true
            }
            Some(GCode::StrokeCheckOff) => {
                super::stroke_check::g23(self);
                true
            }
            Some(GCode::HypotheticalAxis) => {
                super::hypothetical::g07(self, cmd, non_modal_span(cmd), out)?;
                true
            }
            Some(GCode::ReferenceCheck) => {
                super::reference_check::g27(self, cmd, non_modal_span(cmd), out)?;
                true
            }
            Some(GCode::ToolMeasurement) => {
                super::tool_measurement::run(self, cmd, non_modal_span(cmd), Window, out)?;
                true
            }
            Some(GCode::ToolMeasurementTwice) => {
                super::tool_measurement::run(self, cmd, non_modal_span(cmd), TwoTouches, out)?;
                true
            }
            Some(GCode::CircleCutting(direction)) => {
                if self.kernel.setup.profile().motion.g12_g13_pocket {
                    super::circle_pocket::run(self, cmd, direction, out)?;
                } else {
                    super::circle_cutting::run(self, cmd, direction, out)?;
                }
                true
            }
            Some(GCode::Engrave) => {
                super::engraving::g47(self, cmd, out)?;
                true
            }
            Some(GCode::Pattern(kind)) => {
                super::cycles::pattern(self, cmd, kind, out)?;
                true
            }
            _ => false,
        };
        Ok(if taken {
            AxisWords::Taken
        } else {
            AxisWords::ForMotion
        })
    }

    /// E is read by tapping cycles, the smoothing modes and (on some profiles) threading only.
    fn refuse_stray_e(&self, cmd: &Command, smoothing: Option<GWord>) -> Result<(), Alarm> {
        let Some(e) = cmd.word(b'E') else {
            return Ok(());
        };
        let thread_e = self.kernel.setup.profile().motion.thread_e_per_inch
            && self.modal.motion == MotionMode::Thread;
        let engraving = cmd
            .group(Group::NonModal)
            .is_some_and(|g| g.code == GCode::Engrave);
        if self.cycle.is_none() && smoothing.is_none() && !thread_e && !engraving {
            return Err(Alarm::not_supported(
                e.span,
                "address E outside a tapping cycle",
                None,
            ));
        }
        Ok(())
    }

    /// The block's motion: the canned cycle in force, the motion mode's move to the axis
    /// words, or the move that applies a new tool length.
    fn motion_stage(
        &mut self,
        cmd: &Command,
        axis_words: AxisWords,
        length_changed: bool,
        out: &mut Output,
    ) -> Result<(), Alarm> {
        if axis_words == AxisWords::Taken {
            return Ok(());
        }
        if self.cycle.is_some() {
            super::cycles::run(self, cmd, out)
        } else if cmd.has_axis_words() || has_center_words(cmd) {
            self.motion(cmd, length_changed, out)
        } else if length_changed {
            super::length::move_to_new_vector(self, cmd, out)
        } else {
            Ok(())
        }
    }

    /// G93: F is not modal (spec 1.56): every cutting block needs its own.
    fn end_inverse_time_feed(&mut self) {
        if self.modal.feed_mode == FeedMode::InverseTime {
            self.kernel.feed = None;
        }
    }

    /// M00, M01, M02, M30 and the other M codes that act after the motion.
    fn auxiliary_after_motion(&mut self, cmd: &Command, out: &mut Output) -> Result<Flow, Alarm> {
        if cmd.has_auxiliary_words() {
            super::auxiliary::after_motion(self.kernel.setup.profile(), cmd, out)
        } else {
            Ok(Flow::Next)
        }
    }

    fn apply_modal(&mut self, cmd: &Command) -> Result<(), Alarm> {
        if cmd.only_motion_codes() {
            // The block of a CAM program: its motion code in force (the last one written), if
            // any, is all there is to apply, without the loop below and its tests for the codes
            // that need more than the modal state.
            if let Some(g) = cmd.group(Group::Motion) {
                self.modal.apply(g.code);
            }
            return Ok(());
        }
        self.apply_modal_codes(cmd)
    }

    /// [`Executor::apply_modal`] for any block: every code in force, in the order written.
    fn apply_modal_codes(&mut self, cmd: &Command) -> Result<(), Alarm> {
        for g in cmd.g_codes() {
            match g.code {
                GCode::ExtendedWorkOffset => self.extended_work_offset(cmd, *g)?,
                GCode::FeedPerMinute | GCode::FeedPerRevolution | GCode::InverseTimeFeed => {
                    let before = self.modal.feed_mode;
                    self.modal.apply(g.code);
                    if self.modal.feed_mode != before {
                        // F means something else in the new mode; FANUC clears it.
                        self.kernel.feed = match self.modal.feed_mode {
                            FeedMode::PerMinute => self.kernel.setup.profile().motion.default_feed,
                            _ => None,
                        };
                    }
                }
                GCode::PlaneXy | GCode::PlaneZx | GCode::PlaneYz
                    if self.kernel.frames.rotated() =>
                {
                    let before = self.modal.plane;
                    self.modal.apply(g.code);
                    if self.modal.plane != before {
                        return Err(Alarm::error(
                            AlarmCode::WordNotAllowed,
                            g.span,
                            "the plane cannot change while coordinate rotation (G68) is on",
                        )
                        .with_help("cancel the rotation with G69 first"));
                    }
                }
                code => self.modal.apply(code),
            }
        }
        // Only a work-offset code (G54-G59, G54.1) changes the system in use.
        if cmd.group(Group::WorkOffset).is_some() {
            self.kernel.frames.select(self.modal.work_offset);
        }
        Ok(())
    }

    /// G54.1 P: the extended work offset P (kept out of line: it is rare, and inlined, its P
    /// was read for every block).
    #[inline(never)]
    fn extended_work_offset(&mut self, cmd: &Command, g: GWord) -> Result<(), Alarm> {
        let p = cmd.p().ok_or_else(|| {
            Alarm::error(
                AlarmCode::WorkOffsetOutOfRange,
                g.span,
                "G54.1 needs P (1 to the number of extended offsets)",
            )
        })?;
        self.modal.work_offset = self.kernel.setup.extended_offset(&p)?;
        Ok(())
    }

    pub(crate) fn set_feed(&mut self, cmd: &Command) -> Result<(), Alarm> {
        let Some(f) = cmd.f() else { return Ok(()) };
        if f.number.value < 0.0 {
            return Err(Alarm::error(
                AlarmCode::BadFeedRate,
                f.span,
                "feed rate cannot be negative",
            ));
        }
        let value = match self.modal.feed_mode {
            FeedMode::PerMinute | FeedMode::PerRevolution => {
                f.number.value * self.modal.units.to_mm()
            }
            FeedMode::InverseTime => f.number.value,
        };
        self.kernel.feed = Some(value);
        Ok(())
    }

    /// A length word (axis, I J K, R, Q) converted to mm with the units and input rules in force.
    pub(crate) fn length(&self, value: &Value) -> f64 {
        self.kernel.setup.length(self.modal.units, value)
    }

    /// An axis word converted: mm for linear axes, degrees for rotary ones.
    pub(crate) fn axis_value(&self, axis: Axis, value: &Value) -> f64 {
        if self.kernel.setup.is_rotary(axis) {
            self.kernel.setup.angle(value)
        } else {
            self.length(value)
        }
    }

    /// The program-coordinate target of the axis words (G90 or G91), other axes where they are.
    #[inline(always)]
    pub(crate) fn target_program(&self, cmd: &Command) -> [f64; AXES] {
        let mut target = self.cartesian_target(cmd);
        if let Some(point) = super::polar_coordinates::point(self, cmd) {
            let (a, b, _) = self.modal.plane.axes();
            (target[a], target[b]) = super::polar_coordinates::cartesian(point);
        }
        target
    }

    /// The target of the axis words read as Cartesian coordinates.
    #[inline(always)]
    fn cartesian_target(&self, cmd: &Command) -> [f64; AXES] {
        let mut target = self.kernel.program_position();
        let start = target;
        let incremental = self.modal.distance == super::modal::DistanceMode::Incremental;
        let mut place = |i: usize, v: f64| {
            target[i] = if incremental { target[i] + v } else { v };
        };
        // X, Y and Z, linear axes, one test each (most blocks); the other axes, rare, through
        // the loop over the words present. Looping over all, every word paid for finding its
        // axis and asking whether it is rotary.
        for (i, letter) in [b'X', b'Y', b'Z'].into_iter().enumerate() {
            if let Some(value) = cmd.word_ref(letter) {
                place(i, self.length(value));
            }
        }
        if cmd.has_extra_axis_words() {
            let rollover = self.kernel.setup.profile().motion.rotary_rollover;
            for (axis, value) in cmd.axis_words().filter(|(axis, _)| !axis.is_geometry()) {
                let (i, value) = (axis.index(), self.axis_value(axis, value));
                // Without rollover the angle is placed as written (a sum would round it).
                let rolls = rollover != RotaryRollover::Off && !incremental;
                match rolls && self.kernel.setup.is_rotary(axis) {
                    true => place(i, start[i] + rollover_turn(rollover, start[i], value)),
                    false => place(i, value),
                }
            }
        }
        target
    }

    /// The tool length offset of the active compensation, mm (signed for G44).
    #[inline(always)]
    pub(crate) fn active_length(&self) -> f64 {
        let value = self.kernel.tools.length();
        match self.modal.length_comp {
            LengthComp::Off => 0.0,
            LengthComp::Plus | LengthComp::CenterPoint => value,
            LengthComp::Minus => -value,
        }
    }

    /// Machine coordinates for a program target; the length vector follows the compensation in
    /// force when the block moves Z (or changes the compensation).
    #[inline(always)]
    pub(crate) fn machine_target(&mut self, target: &[f64; AXES], moves_z: bool) -> [f64; AXES] {
        if moves_z {
            self.kernel.frames.set_length_vector(self.active_length());
        }
        self.kernel
            .frames
            .to_machine(target, self.kernel.frames.length_vector())
    }

    fn motion(
        &mut self,
        cmd: &Command,
        length_changed: bool,
        out: &mut Output,
    ) -> Result<(), Alarm> {
        let machine_target = self.block_target(cmd, length_changed, out)?;
        match self.modal.motion {
            MotionMode::Rapid => self.rapid_to(machine_target, cmd, out),
            MotionMode::Linear => self.feed_to(machine_target, cmd, false, out),
            MotionMode::Arc(direction) => {
                super::circular::arc(self, cmd, direction, machine_target, out)
            }
            MotionMode::Thread => super::thread::g33(self, cmd, machine_target, out),
        }
    }

    /// The machine position the block's axis words name (with G45-G48 and G16 applied, and
    /// G43.5's tool direction); the length vector follows the compensation when the block moves
    /// Z or changed it.
    // Inlined, like `move_to`: out of line, the target and the move were copied between frames.
    #[inline(always)]
    pub(crate) fn block_target(
        &mut self,
        cmd: &Command,
        length_changed: bool,
        out: &Output,
    ) -> Result<[f64; AXES], Alarm> {
        let mut target = self.target_program(cmd);
        if let Some(factor) = super::position_offset::factor(cmd) {
            let start = self.kernel.program_position();
            let compensating = out.compensating();
            let (tools, distance) = (&self.kernel.tools, self.modal.distance);
            super::position_offset::apply(
                tools,
                distance,
                cmd,
                factor,
                compensating,
                &start,
                &mut target,
            )?;
        }
        if let Some(point) = super::polar_coordinates::point(self, cmd) {
            self.polar = Some(point);
        }
        let moves_z = cmd.axis(Axis::Z.index()).is_some() || length_changed;
        let machine = self.machine_target(&target, moves_z);
        super::tool_center::tool_direction(self, cmd, machine, out)
    }

    /// A cutting line to a machine position at the feed in force, recorded in the stream; with
    /// `exact_stop` the axes come to rest at its end whatever the path mode.
    ///
    /// # Errors
    /// No feed in force, a position beyond the control's range.
    #[inline(always)]
    pub(crate) fn feed_to(
        &mut self,
        to: [f64; AXES],
        cmd: &Command,
        exact_stop: bool,
        out: &mut Output,
    ) -> Result<(), Alarm> {
        let modes = self.modal.move_modes(cmd);
        let feed_mode = self.modal.feed_mode;
        self.kernel
            .feed_to(to, cmd, feed_mode, modes.stopping(exact_stop), out)
    }

    /// A rapid to a machine position, recorded in the stream.
    ///
    /// # Errors
    /// [`AlarmCode::ValueOutOfRange`] for a position beyond the control's range.
    pub(crate) fn rapid_to(
        &mut self,
        to: [f64; AXES],
        cmd: &Command,
        out: &mut Output,
    ) -> Result<(), Alarm> {
        let modes = self.modal.move_modes(cmd);
        self.kernel.rapid_to(to, cmd, modes, out)
    }

    /// A [`Move`] from the current position to `to` with the modes in force; the position
    /// becomes `to`.
    ///
    /// # Errors
    /// [`AlarmCode::ValueOutOfRange`] for a position beyond the control's range.
    #[inline(always)]
    pub(crate) fn move_to(
        &mut self,
        to: [f64; AXES],
        cmd: &Command,
        out: &mut Output,
    ) -> Result<Move, Alarm> {
        let modes = self.modal.move_modes(cmd);
        self.kernel.move_to(to, cmd, modes, out)
    }

    /// The feed of a cutting move in the mode in force.
    ///
    /// # Errors
    /// [`AlarmCode::NoFeedRate`] when no F is in force (FANUC alarm 011).
    #[inline(always)]
    pub(crate) fn cutting_feed(&self, cmd: &Command) -> Result<Feed, Alarm> {
        self.kernel.cutting_feed(self.modal.feed_mode, cmd)
    }
}

/// G92 and G92.1 under a rotation are refused (vcnc does not model how the rotated system
/// would be preset).
fn refuse_presets_while_rotated(frames: &Frames, cmd: &Command) -> Result<(), Alarm> {
    let non_modal = cmd.group(Group::NonModal);
    let preset = matches!(
        non_modal.map(|g| g.code),
        Some(GCode::SetCoordinates | GCode::PresetCoordinates)
    );
    if preset && frames.rotated() {
        let span = non_modal.map_or(cmd.span, |g| g.span);
        return Err(Alarm::not_supported(
            span,
            "G92 or G92.1 while the coordinate system is rotated (G68, G92.1 R)",
            Some(5),
        ));
    }
    Ok(())
}

/// The span of the block's one-shot G code (the block's, if it has none).
fn non_modal_span(cmd: &Command) -> crate::Span {
    cmd.group(Group::NonModal).map_or(cmd.span, |g| g.span)
}

fn has_center_words(cmd: &Command) -> bool {
    cmd.has_center_words()
}

/// Ends the program with the given end code.
pub(crate) fn end_program(cmd: &Command, kind: EndKind, out: &mut Output) -> Flow {
    out.push(cmd, SegmentKind::End { kind });
    Flow::End
}

/// An M00/M01 stop.
pub(crate) fn stop(cmd: &Command, kind: StopKind, out: &mut Output) {
    out.push(cmd, SegmentKind::Stop { kind });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::interp::decode::decode;
    use crate::source::FileId;
    use crate::syntax::iso::{parse_line, LineBlocks, SyntaxOptions};
    use crate::syntax::lines::Line;

    /// Runs the blocks of `program` on two executors, one through `run` (which takes the plain
    /// path where it can) and one through all the stages; they must queue the same items, end
    /// each block the same way and be left in the same state. True when every block ran (the
    /// first alarm ends the comparison).
    fn assert_plain_path_agrees(program: &str) -> bool {
        let machine = Machine::default();
        let mut fast = Executor::new(&machine);
        let mut full = fast.clone();
        let (mut fast_out, mut full_out) = (Output::default(), Output::default());
        let mut cmd = Command::default();
        let mut blocks = LineBlocks::new();
        for (number, text) in (1..).zip(program.lines()) {
            let line = Line {
                text: text.as_bytes(),
                offset: 0,
                number,
            };
            parse_line(line, FileId(0), &SyntaxOptions::default(), &mut blocks);
            for block in blocks.as_slice() {
                if decode(
                    block,
                    fast.kernel.setup.profile(),
                    fast.kernel.setup.axis_letters(),
                    &mut cmd,
                )
                .is_err()
                {
                    return false;
                }
                let by_run = fast.run(&cmd, &mut fast_out);
                let by_stages = full
                    .apply_modal(&cmd)
                    .and_then(|()| full.run_stages(&cmd, &mut full_out));
                assert_eq!(by_run, by_stages, "{text:?} in {program:?}");
                assert_eq!(fast_out.items, full_out.items, "{text:?} in {program:?}");
                // To the bit: `==` takes -0 for 0.
                let debug = |items: &Vec<_>| format!("{items:?}");
                assert_eq!(debug(&fast_out.items), debug(&full_out.items), "{text:?}");
                assert_eq!(fast.kernel.position, full.kernel.position, "{text:?}");
                assert_eq!(fast.modal, full.modal, "{text:?}");
                assert_eq!(fast.kernel.feed, full.kernel.feed, "{text:?}");
                if by_run.is_err() {
                    return false;
                }
            }
        }
        true
    }

    #[test]
    fn plain_blocks_run_the_same_on_the_short_path_and_through_every_stage() {
        assert!(assert_plain_path_agrees(
            "G21 G17 G90 G94\nG00 X0. Y0. Z5.\nG01 Z-1. F1500.\nX2.221 Y2.696\n\
             G02 X12.221 Y2.696 I5. J0.\nG03 X2.221 Y2.696 R5.\nG91 G01 X1. Y-1.\n\
             G20 G90 X1. Y1. F10.\nG18 G02 X2. Z1. R3.\nG93 G01 X5. F2.\nG00 X1.\n",
        ));
    }

    /// The target of the axis words as the executor read them before X, Y and Z had a path of
    /// their own: every word through its axis's conversion, in axis order.
    fn target_word_by_word(exec: &Executor, cmd: &Command) -> [f64; AXES] {
        let mut target = exec.kernel.program_position();
        let incremental = exec.modal.distance == super::super::modal::DistanceMode::Incremental;
        for (axis, value) in cmd.axis_words() {
            let v = exec.axis_value(axis, value);
            let i = axis.index();
            target[i] = if incremental { target[i] + v } else { v };
        }
        target
    }

    proptest::proptest! {
        #[test]
        fn modal_codes_apply_the_same_on_the_short_path_and_through_the_loop(
            blocks in proptest::collection::vec(
                "(G0[0-3] )?(G0[0-3] )?(G1[789] )?(G9[01345] )?(G2[01] )?(G6[14] )?(G5[4-9] )?(G0[0-3] )?(G4[39] )?(X1\\.)?",
                1..10,
            ),
        ) {
            let machine = Machine::default();
            let mut fast = Executor::new(&machine);
            let mut full = fast.clone();
            let mut cmd = Command::default();
            let mut lines = LineBlocks::new();
            for (number, text) in (1..).zip(&blocks) {
                let line = Line { text: text.as_bytes(), offset: 0, number };
                parse_line(line, FileId(0), &SyntaxOptions::default(), &mut lines);
                for block in lines.as_slice() {
                    if decode(block, fast.kernel.setup.profile(), fast.kernel.setup.axis_letters(), &mut cmd).is_err() {
                        return Ok(());
                    }
                    let (by_run, by_loop) = (fast.apply_modal(&cmd), full.apply_modal_codes(&cmd));
                    proptest::prop_assert_eq!(&by_run, &by_loop, "{:?}", text);
                    proptest::prop_assert_eq!(&fast.modal, &full.modal, "{:?}", text);
                    proptest::prop_assert_eq!(fast.kernel.feed, full.kernel.feed, "{:?}", text);
                    proptest::prop_assert_eq!(fast.kernel.program_position(), full.kernel.program_position());
                    if by_run.is_err() {
                        return Ok(());
                    }
                }
            }
        }

        #[test]
        fn axis_words_give_the_same_target_as_word_by_word(
            blocks in proptest::collection::vec(
                "(G9[01] )?(G2[01] )?(G0[01] )?(X-?[0-9]{1,3}\\.?[0-9]? )?(Y-?[0-9]{1,2} )?(Z-?[0-9]\\.?[0-9]? )?(A-?[0-9]{1,3}\\.?[0-9]? )?(B[0-9]{1,2} )?(C-?[0-9]{1,2}\\. )?(F500\\.)?",
                1..10,
            ),
        ) {
            let mut machine = Machine::default();
            for axis in [Axis::A, Axis::B, Axis::C] {
                machine.axes[axis.index()] = machine.axes[0].clone();
            }
            let mut exec = Executor::new(&machine);
            let mut out = Output::default();
            let mut cmd = Command::default();
            let mut lines = LineBlocks::new();
            for (number, text) in (1..).zip(&blocks) {
                let line = Line { text: text.as_bytes(), offset: 0, number };
                parse_line(line, FileId(0), &SyntaxOptions::default(), &mut lines);
                for block in lines.as_slice() {
                    if decode(block, exec.kernel.setup.profile(), exec.kernel.setup.axis_letters(), &mut cmd).is_err() {
                        return Ok(());
                    }
                    if exec.apply_modal(&cmd).is_err() {
                        return Ok(());
                    }
                    let (got, want) = (exec.cartesian_target(&cmd), target_word_by_word(&exec, &cmd));
                    proptest::prop_assert_eq!(got.map(f64::to_bits), want.map(f64::to_bits), "{:?}", text);
                    if exec.run_stages(&cmd, &mut out).is_err() {
                        return Ok(());
                    }
                }
            }
        }

        #[test]
        fn arcs_that_end_on_their_circle_run_the_same_on_both_paths(
            arcs in proptest::collection::vec(
                (
                    (-200_000..200_000i32, -200_000..200_000i32, -20_000..20_000i32),
                    (-20_000..20_000i32, -20_000..20_000i32),
                    (0..4u8, proptest::bool::ANY, 0..6u8),
                ),
                1..6,
            ),
        ) {
            // Each arc from a line's end, a quarter turn about I J (the end on the circle but
            // for rounding), as R or as I J, now and then helical, incremental, in G18 or G02 R
            // short of the half chord.
            let mm = |micrometres: i32| format!("{:.3}", f64::from(micrometres) / 1000.0);
            let mut program = String::from("G17 G90 G01 F800.\n");
            for ((x, y, z), (i, j), (form, clockwise, variant)) in arcs {
                let g = if clockwise { "G02" } else { "G03" };
                let (ex, ey) = (x + i + j, y + j - i);
                program += &format!("G90 G01 X{} Y{}\n", mm(x), mm(y));
                let words = match form {
                    0 => format!("I{} J{}", mm(i), mm(j)),
                    1 => format!("I{}", mm(i)),
                    2 => format!("R{}", mm(f64::from(i).hypot(f64::from(j)) as i32)),
                    _ => format!("R-{}", mm(f64::from(i).hypot(f64::from(j)) as i32 + 1)),
                };
                let end = match variant {
                    0 => format!("G91 X{} Y{}", mm(ex - x), mm(ey - y)),
                    1 => format!("X{} Y{} Z{}", mm(ex), mm(ey), mm(z)),
                    2 => format!("G18 X{} Z{}", mm(ex), mm(ey)),
                    3 => format!("X{} Y{}", mm(x + 2 * i), mm(y + 2 * j)),
                    _ => format!("X{} Y{}", mm(ex), mm(ey)),
                };
                program += &format!("{g} {end} {words}\nG17\n");
            }
            assert_plain_path_agrees(&program);
        }

        #[test]
        fn any_plain_program_runs_the_same_on_both_paths(
            blocks in proptest::collection::vec(
                "(G0[0-3] |G9[0134] |G1[789] |G2[01] )?(X-?[0-9]{1,2}\\.[0-9]? )?(Y-?[0-9]{1,2} )?(Z-?[0-9]\\. )?((I-?[0-9]\\. J-?[0-9]\\. )|(R[0-9]{1,2}\\. ))?(F[0-9]{1,3}\\.)?",
                1..12,
            ),
        ) {
            assert_plain_path_agrees(&blocks.join("\n"));
        }
    }
}
