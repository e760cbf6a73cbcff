//! The modal state: one value per modal group, as the control keeps it between blocks.

use crate::machine::WorkOffsetId;
use crate::motion::{ArcDirection, PathMode, Plane, Smoothing};
use crate::profile::{GCode, PowerOn};

/// Group 01.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MotionMode {
    /// G00.
    Rapid,
    /// G01.
    Linear,
    /// G02 / G03.
    Arc(ArcDirection),
    /// G33.
    Thread,
}

/// Group 03.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DistanceMode {
    /// G90.
    Absolute,
    /// G91.
    Incremental,
}

/// Group 06.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Units {
    /// G21 (Syntec G71).
    Millimetres,
    /// G20 (Syntec G70).
    Inches,
}

impl Units {
    /// Millimetres per program unit.
    pub fn to_mm(self) -> f64 {
        match self {
            Units::Millimetres => 1.0,
            Units::Inches => 25.4,
        }
    }
}

/// Group 05.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FeedMode {
    /// G94.
    PerMinute,
    /// G95.
    PerRevolution,
    /// G93.
    InverseTime,
}

/// Group 08.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LengthComp {
    /// G49.
    Off,
    /// G43.
    Plus,
    /// G44.
    Minus,
    /// G43.4: tool centre point control, the length applied like G43's and the tip kept on the
    /// path (`tool_center.rs`).
    CenterPoint,
}

/// Group 13.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SpindleMode {
    /// G97.
    Rpm,
    /// G96.
    SurfaceSpeed,
}

/// Group 10.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CycleReturn {
    /// G98.
    InitialLevel,
    /// G99.
    RLevel,
}

/// The modal state of the control: one field per modal group.
#[derive(Clone, Debug, PartialEq)]
pub struct ModalState {
    /// Group 01.
    pub motion: MotionMode,
    /// Group 02.
    pub plane: Plane,
    /// Group 03.
    pub distance: DistanceMode,
    /// Group 05.
    pub feed_mode: FeedMode,
    /// Group 06.
    pub units: Units,
    /// Group 08.
    pub length_comp: LengthComp,
    /// Group 10.
    pub cycle_return: CycleReturn,
    /// Group 13.
    pub spindle_mode: SpindleMode,
    /// Group 14.
    pub work_offset: WorkOffsetId,
    /// Group 15.
    pub path_mode: PathMode,
    /// The high-speed (G05) and smoothing (G05.1, G08) modes: group 00 codes whose state
    /// persists.
    pub smoothing: SmoothingModes,
}

/// The high-speed and smoothing modes switched on, each with its tolerance.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SmoothingModes {
    /// Syntec G05 (high-speed high-precision contour control).
    pub high_speed: Option<Smoothing>,
    /// G05.1 (Syntec path smoothing, FANUC AI contour control) or FANUC G08 look-ahead.
    pub path: Option<Smoothing>,
}

impl ModalState {
    /// The smoothing a motion gets: the larger tolerance of the modes that are on, none in G61
    /// or G63, which suspend them until G64 (spec 1.8 restriction 7, 1.9 restriction 5).
    // Inlined: every move asks, and out of line the answer cost a call.
    #[inline(always)]
    pub fn smoothing_for_motion(&self) -> Option<Smoothing> {
        if matches!(self.path_mode, PathMode::ExactStop | PathMode::Tapping) {
            return None;
        }
        match (self.smoothing.high_speed, self.smoothing.path) {
            (Some(a), Some(b)) => Some(if a.mm() >= b.mm() { a } else { b }),
            (a, b) => a.or(b),
        }
    }

    /// G09 in the block, unless Syntec's high-speed mode (G05) is on, where it has no effect
    /// (spec 1.8, restriction 6).
    pub(crate) fn exact_stop_once(&self, cmd: &super::decode::Command) -> bool {
        cmd.exact_stop_once() && self.smoothing.high_speed.is_none()
    }

    /// How the block `cmd` makes its moves in the modes in force.
    #[inline(always)]
    pub(crate) fn move_modes(&self, cmd: &super::decode::Command) -> super::kernel::MoveModes {
        super::kernel::MoveModes {
            path_mode: self.path_mode,
            exact_stop: self.exact_stop_once(cmd),
            smoothing: self.smoothing_for_motion(),
        }
    }
}

impl ModalState {
    /// The state at power-on, from the profile's G codes.
    pub fn power_on(power_on: &PowerOn) -> ModalState {
        let mut state = ModalState {
            motion: MotionMode::Rapid,
            plane: Plane::Xy,
            distance: DistanceMode::Absolute,
            feed_mode: FeedMode::PerMinute,
            units: Units::Millimetres,
            length_comp: LengthComp::Off,
            cycle_return: CycleReturn::InitialLevel,
            spindle_mode: SpindleMode::Rpm,
            work_offset: WorkOffsetId::Standard(1),
            path_mode: PathMode::Continuous,
            smoothing: SmoothingModes::default(),
        };
        for code in [
            power_on.motion,
            power_on.plane,
            power_on.distance,
            power_on.units,
            power_on.feed_mode,
            power_on.work_offset,
            power_on.path_mode,
            power_on.cycle_return,
        ] {
            if let Some(g) = power_on_code(code) {
                state.apply(g);
            }
        }
        state
    }

    /// Sets the group of `code` to it. Codes of other kinds (one-shot, cancels of features that
    /// are never on) change nothing here.
    // Inlined: the executor applies the codes of every block.
    #[inline(always)]
    pub fn apply(&mut self, code: GCode) {
        use GCode::*;
        match code {
            Rapid => self.motion = MotionMode::Rapid,
            Linear => self.motion = MotionMode::Linear,
            ArcClockwise => self.motion = MotionMode::Arc(ArcDirection::Clockwise),
            ArcCounterClockwise => self.motion = MotionMode::Arc(ArcDirection::CounterClockwise),
            Thread => self.motion = MotionMode::Thread,
            PlaneXy => self.plane = Plane::Xy,
            PlaneZx => self.plane = Plane::Zx,
            PlaneYz => self.plane = Plane::Yz,
            Absolute => self.distance = DistanceMode::Absolute,
            Incremental => self.distance = DistanceMode::Incremental,
            FeedPerMinute => self.feed_mode = FeedMode::PerMinute,
            FeedPerRevolution => self.feed_mode = FeedMode::PerRevolution,
            InverseTimeFeed => self.feed_mode = FeedMode::InverseTime,
            Inch => self.units = Units::Inches,
            Metric => self.units = Units::Millimetres,
            LengthCompPlus => self.length_comp = LengthComp::Plus,
            LengthCompMinus => self.length_comp = LengthComp::Minus,
            LengthCompCancel => self.length_comp = LengthComp::Off,
            ToolCenterPoint | ToolCenterPointType2 => self.length_comp = LengthComp::CenterPoint,
            ReturnToInitialLevel => self.cycle_return = CycleReturn::InitialLevel,
            ReturnToRLevel => self.cycle_return = CycleReturn::RLevel,
            ConstantSurfaceSpeed => self.spindle_mode = SpindleMode::SurfaceSpeed,
            ConstantSpindleSpeed => self.spindle_mode = SpindleMode::Rpm,
            WorkOffset(n) => self.work_offset = WorkOffsetId::Standard(n),
            ExactStopMode => self.path_mode = PathMode::ExactStop,
            AutomaticCornerOverride => self.path_mode = PathMode::CornerOverride,
            TappingMode => self.path_mode = PathMode::Tapping,
            ContinuousMode => self.path_mode = PathMode::Continuous,
            ExtendedWorkOffset
            | Dwell
            | Skip
            | ExactStopOnce
            | DataInput
            | ReferenceReturn
            | ReturnFromReference
            | NthReferenceReturn
            | CutterCompCancel
            | CutterCompLeft
            | CutterCompRight
            | LocalCoordinates
            | MachineCoordinates
            | CycleCancel
            | Cycle(_)
            | SetCoordinates
            | PresetCoordinates
            | PositionOffset(_)
            | Pattern(_)
            | CircleCutting(_)
            | Engrave
            | PolarCancel
            | Polar
            | ScalingCancel
            | Scale
            | MirrorCancel
            | Mirror
            | ModalMacroCancel
            | MacroCall
            | HighSpeedMode
            | PathSmoothing
            | LookAhead
            | ModalMacroCall
            | RotationCancel
            | TiltedPlane
            | ToolAxisDirection
            | Rotate
            | PolarInterpolation
            | PolarInterpolationCancel
            | CylindricalInterpolation
            // G06.2 is of group 01, but its curve ends with its last knot and the motion in
            // force before it goes on (vcnc's choice, spec 1.10 is silent).
            | Nurbs
            | StrokeCheckOn
            | StrokeCheckOff
            | HypotheticalAxis
            | ReferenceCheck
            | ToolMeasurement
            | ToolMeasurementTwice
            | SmoothnessSetting
            | MachiningConditions => {}
        }
    }
}

/// The G code of a power-on setting, read without a profile (the codes are the same everywhere,
/// but for Syntec's G70/G71).
fn power_on_code(tenths: u32) -> Option<GCode> {
    use GCode::*;
    Some(match tenths {
        0 => Rapid,
        10 => Linear,
        170 => PlaneXy,
        180 => PlaneZx,
        190 => PlaneYz,
        900 => Absolute,
        910 => Incremental,
        200 | 700 => Inch,
        210 | 710 => Metric,
        930 => InverseTimeFeed,
        940 => FeedPerMinute,
        950 => FeedPerRevolution,
        540..=590 if tenths.is_multiple_of(10) => WorkOffset(((tenths - 530) / 10) as u8),
        610 => ExactStopMode,
        640 => ContinuousMode,
        980 => ReturnToInitialLevel,
        990 => ReturnToRLevel,
        _ => return None,
    })
}
