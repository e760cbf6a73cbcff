//! The G-code table: what each G number means on a profile, and its modal group.
//!
//! Codes are integers in tenths (G54.1 is 541), never floats. [`classify_g`] is the one place that
//! maps a number to a meaning; the interpreter matches on [`GCode`].

use super::{Profile, SmoothingCodes};
use crate::motion::ArcDirection;

/// The modal groups of the FANUC-family M-series numbering (spec/iso-syntec-milling.md A.4).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Group {
    /// Group 00: one-shot codes.
    NonModal,
    /// Group 01: motion.
    Motion,
    /// Group 02: plane.
    Plane,
    /// Group 03: absolute / incremental.
    Distance,
    /// Group 05: feed mode.
    FeedMode,
    /// Group 06: inch / metric.
    Units,
    /// Group 07: cutter radius compensation.
    CutterComp,
    /// Group 08: tool length compensation.
    LengthComp,
    /// Group 09: canned cycles.
    Cycle,
    /// Group 10: canned-cycle return level.
    CycleReturn,
    /// Group 11: scaling.
    Scaling,
    /// Group 12: modal macro call.
    ModalMacro,
    /// Group 13: constant surface speed.
    SpindleMode,
    /// Group 14: work coordinate system.
    WorkOffset,
    /// Group 15: path (cutting) mode.
    PathMode,
    /// Group 16: coordinate rotation.
    Rotation,
    /// Group 17: polar coordinate command.
    Polar,
    /// Group 21: polar coordinate interpolation.
    PolarInterpolation,
    /// Group 22: programmable mirror image.
    Mirror,
}

/// What a G code does.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum GCode {
    /// G00.
    Rapid,
    /// G01.
    Linear,
    /// G02.
    ArcClockwise,
    /// G03.
    ArcCounterClockwise,
    /// G33: thread cutting, the feed tied to the spindle (F is the lead).
    Thread,
    /// G04.
    Dwell,
    /// G31: a cutting move that a skip signal (a probe) may end early.
    Skip,
    /// G09: exact stop for this block.
    ExactStopOnce,
    /// G10.
    DataInput,
    /// G17.
    PlaneXy,
    /// G18.
    PlaneZx,
    /// G19.
    PlaneYz,
    /// G20 (Syntec also G70).
    Inch,
    /// G21 (Syntec also G71).
    Metric,
    /// G28.
    ReferenceReturn,
    /// G29.
    ReturnFromReference,
    /// G30.
    NthReferenceReturn,
    /// G40.
    CutterCompCancel,
    /// G41: cutter radius compensation, tool left of the path.
    CutterCompLeft,
    /// G42: cutter radius compensation, tool right of the path.
    CutterCompRight,
    /// G43.
    LengthCompPlus,
    /// G44.
    LengthCompMinus,
    /// G49.
    LengthCompCancel,
    /// G52.
    LocalCoordinates,
    /// G53.
    MachineCoordinates,
    /// G54 ... G59 (1 to 6), Syntec G59.1 ... G59.9 (7 to 15).
    WorkOffset(u8),
    /// G54.1 Pn (Haas G154 Pn).
    ExtendedWorkOffset,
    /// G61.
    ExactStopMode,
    /// G62.
    AutomaticCornerOverride,
    /// G63.
    TappingMode,
    /// G64.
    ContinuousMode,
    /// G80.
    CycleCancel,
    /// G73, G74, G76, G81 ... G89: a canned cycle (group 09).
    Cycle(CycleKind),
    /// Syntec G134, G135, G136, G137.1: holes in a pattern, drilled by the cycle in force.
    Pattern(PatternKind),
    /// Mitsubishi G12 (clockwise) and G13 (counter-clockwise): cut a circle's inside from its
    /// centre and come back.
    CircleCutting(ArcDirection),
    /// G90.
    Absolute,
    /// G91.
    Incremental,
    /// G92.
    SetCoordinates,
    /// Haas G47: text engraving.
    Engrave,
    /// G45 (+1), G46 (-1), G47 (+2), G48 (-2): tool position offset by that many times the D
    /// value along each axis's travel, one block.
    PositionOffset(i8),
    /// G92.1.
    PresetCoordinates,
    /// G93.
    InverseTimeFeed,
    /// G94.
    FeedPerMinute,
    /// G95.
    FeedPerRevolution,
    /// G96.
    ConstantSurfaceSpeed,
    /// G97.
    ConstantSpindleSpeed,
    /// G98.
    ReturnToInitialLevel,
    /// G99.
    ReturnToRLevel,
    /// G15.
    PolarCancel,
    /// G16: polar coordinate command.
    Polar,
    /// G50.
    ScalingCancel,
    /// G51: scaling.
    Scale,
    /// G50.1.
    MirrorCancel,
    /// G51.1: programmable mirror image.
    Mirror,
    /// G67.
    ModalMacroCancel,
    /// G65: call a macro once.
    MacroCall,
    /// G66: call a macro after every move.
    ModalMacroCall,
    /// G69.
    RotationCancel,
    /// G68: coordinate rotation in the selected plane.
    Rotate,
    /// G12.1: polar coordinate interpolation (X and a hypothetical axis C in the plane).
    PolarInterpolation,
    /// G13.1.
    PolarInterpolationCancel,
    /// G07.1: cylindrical interpolation (a rotary axis as a length on a cylinder's surface).
    CylindricalInterpolation,
    /// G07: hypothetical axis interpolation (`G07 α0` makes α hypothetical, `G07 α1` real).
    HypotheticalAxis,
    /// G05: high-speed high-precision (Syntec) or high-precision contour control (FANUC) on with
    /// P10000 (Syntec also E alone), off with P0.
    HighSpeedMode,
    /// G05.1: path smoothing (Syntec Q1/Q2 with E) or AI contour control (FANUC Q1), on or off.
    PathSmoothing,
    /// G08 on FANUC: look-ahead control on (P1) or off (P0).
    LookAhead,
    /// G43.4: tool centre point control (RTCP), the length applied along the turned tool.
    ToolCenterPoint,
    /// G43.5: tool centre point control type 2, the tool direction given by I J K and the rotary
    /// positions solved by the control (FANUC Series 30i).
    ToolCenterPointType2,
    /// G68.2: tilted working plane (feature coordinate system).
    TiltedPlane,
    /// G53.1: the rotary axes turn the tool normal to the tilted plane.
    ToolAxisDirection,
    /// G06.2: NURBS interpolation, the curve given by the blocks that follow (K, X Y Z, R).
    Nurbs,
    /// G22: stored stroke check 2 on (a forbidden zone, X Y Z I J K or the machine file's).
    StrokeCheckOn,
    /// G23: stored stroke check 2 off.
    StrokeCheckOff,
    /// G27: reference position return check.
    ReferenceCheck,
    /// G37: automatic tool length measurement, Z in program coordinates (Syntec 1.22).
    ToolMeasurement,
    /// G37.1: automatic tool length measurement II, Z in machine coordinates, two touches
    /// (Syntec 1.23).
    ToolMeasurementTwice,
    /// Haas G187: smoothness level (P) and corner rounding (E).
    SmoothnessSetting,
    /// Syntec G120.1: a machining-condition set of the control.
    MachiningConditions,
}

impl GCode {
    /// What the code does, in a few words (for the generated code table).
    pub fn description(self) -> &'static str {
        use GCode::*;
        match self {
            Rapid => "rapid positioning",
            Linear => "linear interpolation",
            ArcClockwise => "circular/helical interpolation CW",
            ArcCounterClockwise => "circular/helical interpolation CCW",
            Thread => "thread cutting",
            Dwell => "dwell",
            Skip => "skip function",
            ExactStopOnce => "exact stop, one block",
            DataInput => "programmable data input (work and tool offsets)",
            PlaneXy => "XY plane",
            PlaneZx => "ZX plane",
            PlaneYz => "YZ plane",
            Inch => "inch input",
            Metric => "metric input",
            ReferenceReturn => "reference point return",
            ReturnFromReference => "return from reference point",
            NthReferenceReturn => "2nd/3rd/4th reference point return",
            CutterCompCancel => "cutter compensation cancel",
            CutterCompLeft => "cutter compensation left",
            CutterCompRight => "cutter compensation right",
            LengthCompPlus => "tool length compensation +",
            LengthCompMinus => "tool length compensation -",
            LengthCompCancel => "tool length compensation cancel",
            LocalCoordinates => "local coordinate system",
            MachineCoordinates => "machine coordinate positioning",
            WorkOffset(_) => "work coordinate system",
            ExtendedWorkOffset => "extended work coordinate systems (P)",
            ExactStopMode => "exact stop mode",
            AutomaticCornerOverride => "automatic corner override mode",
            TappingMode => "tapping mode",
            ContinuousMode => "cutting (continuous) mode",
            CycleCancel => "canned cycle cancel",
            Cycle(kind) => kind.description(),
            Pattern(PatternKind::BoltCircle) => "bolt hole circle pattern",
            Pattern(PatternKind::Line) => "holes on a line at an angle",
            Pattern(PatternKind::Arc) => "holes on an arc",
            Pattern(PatternKind::Grid) => "grid hole pattern",
            CircleCutting(ArcDirection::Clockwise) => "circle cutting / circular pocket CW",
            CircleCutting(ArcDirection::CounterClockwise) => "circle cutting / circular pocket CCW",
            Absolute => "absolute programming",
            Incremental => "incremental programming",
            SetCoordinates => "coordinate system setting",
            PositionOffset(1) => "tool position offset +1",
            PositionOffset(-1) => "tool position offset -1",
            PositionOffset(2) => "tool position offset +2",
            PositionOffset(_) => "tool position offset -2",
            Engrave => "text engraving",
            PresetCoordinates => "work coordinate system preset",
            InverseTimeFeed => "inverse time feed",
            FeedPerMinute => "feed per minute",
            FeedPerRevolution => "feed per revolution",
            ConstantSurfaceSpeed => "constant surface speed",
            ConstantSpindleSpeed => "constant spindle speed",
            ReturnToInitialLevel => "canned cycle return to initial level",
            ReturnToRLevel => "canned cycle return to R level",
            PolarCancel => "polar coordinate command cancel",
            Polar => "polar coordinate command",
            ScalingCancel => "scaling cancel",
            Scale => "scaling",
            MirrorCancel => "programmable mirror image cancel",
            Mirror => "programmable mirror image",
            ModalMacroCancel => "modal macro call cancel",
            MacroCall => "macro call",
            ModalMacroCall => "modal macro call",
            RotationCancel => "coordinate rotation cancel",
            Rotate => "coordinate rotation",
            PolarInterpolation => "polar coordinate interpolation",
            PolarInterpolationCancel => "polar coordinate interpolation cancel",
            CylindricalInterpolation => "cylindrical interpolation",
            HypotheticalAxis => "hypothetical axis interpolation",
            HighSpeedMode => "high-speed high-precision mode",
            PathSmoothing => "path smoothing / AI contour control",
            LookAhead => "look-ahead control",
            ToolCenterPoint => "tool centre point control",
            ToolCenterPointType2 => "tool centre point control by tool direction",
            TiltedPlane => "tilted working plane",
            ToolAxisDirection => "tool axis direction control",
            Nurbs => "NURBS interpolation",
            StrokeCheckOn => "stored stroke check on",
            StrokeCheckOff => "stored stroke check off",
            ReferenceCheck => "reference position return check",
            ToolMeasurement => "automatic tool length measurement",
            ToolMeasurementTwice => "automatic tool length measurement II",
            SmoothnessSetting => "smoothness / accuracy setting",
            MachiningConditions => "machining condition selection",
        }
    }

    /// The modal group of the code.
    pub fn group(self) -> Group {
        use GCode::*;
        match self {
            Rapid | Linear | ArcClockwise | ArcCounterClockwise | Thread | Nurbs => Group::Motion,
            PlaneXy | PlaneZx | PlaneYz => Group::Plane,
            Absolute | Incremental => Group::Distance,
            InverseTimeFeed | FeedPerMinute | FeedPerRevolution => Group::FeedMode,
            Inch | Metric => Group::Units,
            CutterCompCancel | CutterCompLeft | CutterCompRight => Group::CutterComp,
            LengthCompPlus | LengthCompMinus | LengthCompCancel | ToolCenterPoint
            | ToolCenterPointType2 => Group::LengthComp,
            CycleCancel | Cycle(_) => Group::Cycle,
            ReturnToInitialLevel | ReturnToRLevel => Group::CycleReturn,
            ScalingCancel | Scale => Group::Scaling,
            ModalMacroCancel | ModalMacroCall => Group::ModalMacro,
            MacroCall => Group::NonModal,
            ConstantSurfaceSpeed | ConstantSpindleSpeed => Group::SpindleMode,
            WorkOffset(_) | ExtendedWorkOffset => Group::WorkOffset,
            ExactStopMode | AutomaticCornerOverride | TappingMode | ContinuousMode => {
                Group::PathMode
            }
            RotationCancel | Rotate | TiltedPlane => Group::Rotation,
            PolarCancel | Polar => Group::Polar,
            // G07.1 is a one-shot code that switches a mode like G12.1: in the same group, one
            // of them per block.
            PolarInterpolation | PolarInterpolationCancel | CylindricalInterpolation => {
                Group::PolarInterpolation
            }
            MirrorCancel | Mirror => Group::Mirror,
            Dwell | Skip | ExactStopOnce | DataInput | ReferenceReturn | ReturnFromReference
            | NthReferenceReturn | LocalCoordinates | MachineCoordinates | SetCoordinates
            | PresetCoordinates | PositionOffset(_) | Pattern(_) | CircleCutting(_) | Engrave
            | HighSpeedMode | PathSmoothing | LookAhead | ToolAxisDirection | StrokeCheckOn
            | StrokeCheckOff | HypotheticalAxis | ReferenceCheck | ToolMeasurement
            | ToolMeasurementTwice | SmoothnessSetting | MachiningConditions => Group::NonModal,
        }
    }
}

/// The answer of [`classify_g`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GLookup {
    /// A code vcnc runs.
    Known(GCode),
    /// A code the control has and vcnc does not run yet; the issue that adds it, if planned.
    NotSupported(Option<u32>),
    /// A code this control does not have.
    Unknown,
}

/// The canned cycles vcnc runs (spec iso-syntec-milling.md 1.40-1.52, iso-fanuc0m-mitsubishi.md
/// A.32-A.36).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CycleKind {
    /// G73: feed a peck, rapid back a little, feed on.
    HighSpeedPeck,
    /// G74: tap in with the spindle counter-clockwise, reverse, feed out.
    LeftHandTap,
    /// G76: bore, orient the spindle, shift off the wall, rapid out.
    FineBoring,
    /// G81: feed in, rapid out.
    Drill,
    /// G82: feed in, dwell, rapid out.
    DrillDwell,
    /// G83: feed a peck, rapid out to R, rapid back in, feed on.
    Peck,
    /// G84: tap in with the spindle clockwise, reverse, feed out.
    Tap,
    /// G85: feed in, feed out.
    Bore,
    /// G86: feed in, stop the spindle, rapid out.
    BoreSpindleStop,
    /// G87: from below the part, bore upwards.
    BackBore,
    /// G88: feed in, dwell, stop the spindle, wait for the operator to retract by hand.
    BoreManualRetract,
    /// G89: feed in, dwell, feed out.
    BoreDwell,
}

impl CycleKind {
    /// What the cycle does, in a few words.
    pub fn description(self) -> &'static str {
        match self {
            CycleKind::HighSpeedPeck => "high-speed peck drilling cycle",
            CycleKind::LeftHandTap => "left-hand tapping cycle",
            CycleKind::FineBoring => "fine boring cycle",
            CycleKind::Drill => "drilling cycle",
            CycleKind::DrillDwell => "drilling cycle with dwell",
            CycleKind::Peck => "peck drilling cycle",
            CycleKind::Tap => "tapping cycle",
            CycleKind::Bore => "boring cycle",
            CycleKind::BoreSpindleStop => "boring cycle, spindle stop",
            CycleKind::BackBore => "back boring cycle",
            CycleKind::BoreManualRetract => "boring cycle, manual retract",
            CycleKind::BoreDwell => "boring cycle with dwell",
        }
    }
}

/// Syntec's hole patterns (spec iso-syntec-milling.md 1.59-1.62).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PatternKind {
    /// G134: holes equally spaced on a circle.
    BoltCircle,
    /// G135: holes on a line at an angle.
    Line,
    /// G136: holes on an arc at an angular pitch.
    Arc,
    /// G137.1: a grid of holes.
    Grid,
}

/// A G code number as people write it: `G01`, `G54.1`.
pub fn g_name(tenths: i32) -> String {
    if tenths % 10 == 0 {
        format!("G{:02}", tenths / 10)
    } else {
        format!("G{:02}.{}", tenths / 10, tenths % 10)
    }
}

/// What G code `tenths` (G54.1 is 541) means on `profile`.
pub fn classify_g(tenths: i32, profile: &Profile) -> GLookup {
    use GCode::*;
    use GLookup::Known;
    let known = match tenths {
        0 => Rapid,
        10 => Linear,
        20 => ArcClockwise,
        30 => ArcCounterClockwise,
        40 => Dwell,
        90 => ExactStopOnce,
        100 => DataInput,
        120 if profile.motion.g12_g13_circle_cutting || profile.motion.g12_g13_pocket => {
            CircleCutting(ArcDirection::Clockwise)
        }
        130 if profile.motion.g12_g13_circle_cutting || profile.motion.g12_g13_pocket => {
            CircleCutting(ArcDirection::CounterClockwise)
        }
        121 if profile.motion.polar_interpolation => PolarInterpolation,
        131 if profile.motion.polar_interpolation => PolarInterpolationCancel,
        71 if profile.motion.cylindrical_interpolation => CylindricalInterpolation,
        70 if profile.motion.hypothetical_axis_interpolation => HypotheticalAxis,
        150 => PolarCancel,
        160 => Polar,
        170 => PlaneXy,
        180 => PlaneZx,
        190 => PlaneYz,
        200 => Inch,
        210 => Metric,
        700 if profile.units.g70_g71_units => Inch,
        710 if profile.units.g70_g71_units => Metric,
        280 => ReferenceReturn,
        290 => ReturnFromReference,
        300 => NthReferenceReturn,
        310 => Skip,
        330 => Thread,
        400 => CutterCompCancel,
        410 => CutterCompLeft,
        420 => CutterCompRight,
        430 => LengthCompPlus,
        440 => LengthCompMinus,
        450 if profile.compensation.tool_position_offset => PositionOffset(1),
        460 if profile.compensation.tool_position_offset => PositionOffset(-1),
        470 if profile.compensation.tool_position_offset => PositionOffset(2),
        470 => Engrave,
        480 if profile.compensation.tool_position_offset => PositionOffset(-2),
        490 => LengthCompCancel,
        500 => ScalingCancel,
        501 => MirrorCancel,
        510 => Scale,
        511 => Mirror,
        520 => LocalCoordinates,
        530 => MachineCoordinates,
        540..=590 if tenths % 10 == 0 => WorkOffset(((tenths - 530) / 10) as u8),
        541 if profile.coordinates.g54_1_count > 0 => ExtendedWorkOffset,
        1540 if profile.coordinates.g154_extended_offsets => ExtendedWorkOffset,
        591..=599 if profile.coordinates.g59_x_offsets => WorkOffset((tenths - 591 + 7) as u8),
        610 => ExactStopMode,
        620 => AutomaticCornerOverride,
        630 => TappingMode,
        640 => ContinuousMode,
        650 => MacroCall,
        660 => ModalMacroCall,
        670 => ModalMacroCancel,
        680 => Rotate,
        690 => RotationCancel,
        730 => Cycle(CycleKind::HighSpeedPeck),
        740 => Cycle(CycleKind::LeftHandTap),
        760 => Cycle(CycleKind::FineBoring),
        800 => CycleCancel,
        810 => Cycle(CycleKind::Drill),
        820 => Cycle(CycleKind::DrillDwell),
        830 => Cycle(CycleKind::Peck),
        840 => Cycle(CycleKind::Tap),
        850 => Cycle(CycleKind::Bore),
        860 => Cycle(CycleKind::BoreSpindleStop),
        870 => Cycle(CycleKind::BackBore),
        880 => Cycle(CycleKind::BoreManualRetract),
        890 => Cycle(CycleKind::BoreDwell),
        900 => Absolute,
        910 => Incremental,
        920 => SetCoordinates,
        921 => PresetCoordinates,
        930 => InverseTimeFeed,
        940 => FeedPerMinute,
        950 => FeedPerRevolution,
        960 => ConstantSurfaceSpeed,
        970 => ConstantSpindleSpeed,
        980 => ReturnToInitialLevel,
        1340 if profile.cycles.hole_patterns => Pattern(PatternKind::BoltCircle),
        1350 if profile.cycles.hole_patterns => Pattern(PatternKind::Line),
        1360 if profile.cycles.hole_patterns => Pattern(PatternKind::Arc),
        1371 if profile.cycles.hole_patterns => Pattern(PatternKind::Grid),
        990 => ReturnToRLevel,
        50 if profile.motion.smoothing_codes != SmoothingCodes::None => HighSpeedMode,
        51 if profile.motion.smoothing_codes != SmoothingCodes::None => PathSmoothing,
        80 if profile.motion.smoothing_codes == SmoothingCodes::Fanuc => LookAhead,
        434 if profile.motion.five_axis => ToolCenterPoint,
        435 if profile.motion.tool_center_point_type2 => ToolCenterPointType2,
        682 if profile.motion.five_axis => TiltedPlane,
        531 if profile.motion.five_axis => ToolAxisDirection,
        // NURBS runs in the high-speed mode (Syntec spec 1.10): where that mode exists.
        62 if profile.motion.smoothing_codes != SmoothingCodes::None => Nurbs,
        220 if profile.motion.stored_stroke_check => StrokeCheckOn,
        230 if profile.motion.stored_stroke_check => StrokeCheckOff,
        270 if profile.motion.reference_check => ReferenceCheck,
        370 if profile.motion.tool_length_measurement => ToolMeasurement,
        1870 if profile.motion.smoothness_setting => SmoothnessSetting,
        1201 if profile.motion.machining_condition_sets => MachiningConditions,
        371 if profile.motion.tool_length_measurement => ToolMeasurementTwice,
        _ => return not_yet(tenths),
    };
    Known(known)
}

/// Codes the controls have that vcnc does not run yet: (code in tenths, the issue that adds it,
/// what it does).
const NOT_YET: &[(i32, Option<u32>, &str)] = &[];

/// A code vcnc does not run yet: (issue, meaning).
fn not_yet_on(tenths: i32) -> Option<(Option<u32>, &'static str)> {
    NOT_YET
        .iter()
        .find(|(code, _, _)| *code == tenths)
        .map(|(_, issue, what)| (*issue, *what))
}

fn not_yet(tenths: i32) -> GLookup {
    match not_yet_on(tenths) {
        Some((issue, _)) => GLookup::NotSupported(issue),
        None => GLookup::Unknown,
    }
}

/// What a G code vcnc does not run yet does on `profile`, for messages and tables.
pub fn not_supported_description(tenths: i32, _profile: &Profile) -> Option<&'static str> {
    not_yet_on(tenths).map(|(_, what)| what)
}

/// What an M code does.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MCode {
    /// M00.
    ProgramStop,
    /// M01.
    OptionalStop,
    /// M02.
    ProgramEnd,
    /// M30.
    ProgramEndRewind,
    /// M03.
    SpindleClockwise,
    /// M04.
    SpindleCounterClockwise,
    /// M05.
    SpindleStop,
    /// M19.
    SpindleOrientation,
    /// M06.
    ToolChange,
    /// M07, M08.
    CoolantOn,
    /// M09.
    CoolantOff,
    /// M98: call a subprogram.
    SubprogramCall,
    /// M99: return from a subprogram (in a main program: start it again).
    SubprogramReturn,
    /// M198: call a subprogram from outside memory (Syntec).
    ExternalSubprogramCall,
    /// M97 on Haas: call a sequence number of the same program.
    LocalSubprogramCall,
    /// M96 on Syntec: arm the interrupt program.
    InterruptOn,
    /// M97 on Syntec: disarm the interrupt program.
    InterruptOff,
}

impl MCode {
    /// What the code does, in a few words.
    pub fn description(self) -> &'static str {
        match self {
            MCode::ProgramStop => "program stop",
            MCode::OptionalStop => "optional stop",
            MCode::ProgramEnd => "end of program",
            MCode::ProgramEndRewind => "end of program, rewind",
            MCode::SpindleClockwise => "spindle CW",
            MCode::SpindleCounterClockwise => "spindle CCW",
            MCode::SpindleStop => "spindle stop",
            MCode::SpindleOrientation => "spindle orientation",
            MCode::ToolChange => "tool change",
            MCode::CoolantOn => "coolant on",
            MCode::CoolantOff => "coolant off",
            MCode::SubprogramCall => "subprogram call",
            MCode::SubprogramReturn => "subprogram return",
            MCode::ExternalSubprogramCall => "external subprogram call",
            MCode::LocalSubprogramCall => "local subprogram call",
            MCode::InterruptOn => "interrupt program on",
            MCode::InterruptOff => "interrupt program off",
        }
    }

    /// True for the codes that call, return or arm subprograms: the macro layer runs them.
    pub fn is_subprogram_flow(self) -> bool {
        matches!(
            self,
            MCode::SubprogramCall
                | MCode::SubprogramReturn
                | MCode::ExternalSubprogramCall
                | MCode::LocalSubprogramCall
                | MCode::InterruptOn
                | MCode::InterruptOff
        )
    }
}

/// The answer of [`classify_m`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MLookup {
    /// A code vcnc runs.
    Known(MCode),
    /// A code of the control that vcnc does not run yet, with the issue that adds it.
    NotSupported(Option<u32>),
    /// A code for the machine (its PLC): passed on as an auxiliary event.
    Machine,
}

/// What M code `code` means on `profile`.
pub fn classify_m(code: u32, profile: &Profile) -> MLookup {
    if profile.subprograms.subprogram_m_codes.contains(&code) {
        return match code {
            98 => MLookup::Known(MCode::SubprogramCall),
            99 => MLookup::Known(MCode::SubprogramReturn),
            198 => MLookup::Known(MCode::ExternalSubprogramCall),
            97 if profile.subprograms.m97_local_subprogram => {
                MLookup::Known(MCode::LocalSubprogramCall)
            }
            96 => MLookup::Known(MCode::InterruptOn),
            97 => MLookup::Known(MCode::InterruptOff),
            _ => MLookup::NotSupported(Some(3)),
        };
    }
    MLookup::Known(match code {
        0 => MCode::ProgramStop,
        1 => MCode::OptionalStop,
        2 => MCode::ProgramEnd,
        30 => MCode::ProgramEndRewind,
        3 => MCode::SpindleClockwise,
        4 => MCode::SpindleCounterClockwise,
        5 => MCode::SpindleStop,
        19 => MCode::SpindleOrientation,
        6 => MCode::ToolChange,
        7 | 8 => MCode::CoolantOn,
        9 => MCode::CoolantOff,
        _ => return MLookup::Machine,
    })
}

/// The table of codes and their support on each built-in ISO profile, then the table of the
/// SINUMERIK profiles' G functions, as Markdown (README.md embeds them; a test keeps the two
/// equal, so the tables cannot drift from the code).
pub fn supported_codes_markdown() -> String {
    use super::ProfileName;
    let profiles: Vec<Profile> = ProfileName::ALL
        .iter()
        .map(|n| Profile::builtin(*n))
        .collect();
    let mut out = String::from("| code | meaning |");
    for p in &profiles {
        out.push_str(&format!(" {} |", p.name));
    }
    out.push_str("\n|---|---|");
    out.push_str(&"---|".repeat(profiles.len()));
    out.push('\n');
    for tenths in 0..2000 {
        let lookups: Vec<GLookup> = profiles.iter().map(|p| classify_g(tenths, p)).collect();
        if lookups.iter().all(|l| *l == GLookup::Unknown) {
            continue;
        }
        let meaning = lookups
            .iter()
            .find_map(|l| {
                if let GLookup::Known(g) = l {
                    Some(g.description())
                } else {
                    None
                }
            })
            .or_else(|| {
                profiles
                    .iter()
                    .find_map(|p| not_supported_description(tenths, p))
            })
            .unwrap_or("");
        out.push_str(&format!("| {} | {meaning} |", g_name(tenths)));
        for lookup in &lookups {
            match lookup {
                GLookup::Known(_) => out.push_str(" yes |"),
                GLookup::NotSupported(Some(issue)) => {
                    out.push_str(&format!(" planned (#{issue}) |"))
                }
                GLookup::NotSupported(None) => out.push_str(" not yet |"),
                GLookup::Unknown => out.push_str(" - |"),
            }
        }
        out.push('\n');
    }
    for code in 0..200 {
        let lookups: Vec<MLookup> = profiles.iter().map(|p| classify_m(code, p)).collect();
        if lookups.iter().all(|l| *l == MLookup::Machine) {
            continue;
        }
        let meaning = lookups
            .iter()
            .find_map(|l| {
                if let MLookup::Known(m) = l {
                    Some(m.description())
                } else {
                    None
                }
            })
            .unwrap_or("subprogram call, return or interrupt");
        out.push_str(&format!("| M{code:02} | {meaning} |"));
        for lookup in &lookups {
            out.push_str(match lookup {
                MLookup::Known(_) => " yes |",
                MLookup::NotSupported(_) => " planned (#3) |",
                MLookup::Machine => " machine |",
            });
        }
        out.push('\n');
    }
    out.push_str(&sinumerik_codes_markdown());
    out
}

/// The SINUMERIK table: every G function and named modal function of the 840D sl and the 828D,
/// by group, with what vcnc does with it (the front end's own table, interp/sinumerik/gcodes.rs).
fn sinumerik_codes_markdown() -> String {
    use crate::interp::sinumerik::GFunctionSupport as Support;
    let cell = |support: Support| match support {
        Support::Runs => "yes".to_string(),
        Support::State => "state".to_string(),
        Support::Planned => "planned (#22)".to_string(),
        Support::OutOfProduct(what) => format!("out of product: {what}"),
        Support::Unknown => "-".to_string(),
    };
    let mut out = String::from(
        "\n| SINUMERIK function | group | meaning | sinumerik | sinumerik828d |\n|---|---|---|---|---|\n",
    );
    for row in crate::interp::sinumerik::g_function_listing() {
        out.push_str(&format!(
            "| {} | {} | {} | {} | {} |\n",
            row.name,
            row.group.map_or("-".to_string(), |g| g.to_string()),
            row.meaning,
            cell(row.on_840d),
            cell(row.on_828d)
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::profile::{Profile, ProfileName};

    #[test]
    fn work_offsets_map_to_their_numbers() {
        let fanuc = Profile::builtin(ProfileName::Fanuc);
        assert_eq!(
            classify_g(540, &fanuc),
            GLookup::Known(GCode::WorkOffset(1))
        );
        assert_eq!(
            classify_g(590, &fanuc),
            GLookup::Known(GCode::WorkOffset(6))
        );
        assert_eq!(
            classify_g(541, &fanuc),
            GLookup::Known(GCode::ExtendedWorkOffset)
        );
        assert_eq!(classify_g(591, &fanuc), GLookup::Unknown);
        let syntec = Profile::builtin(ProfileName::Syntec);
        assert_eq!(
            classify_g(599, &syntec),
            GLookup::Known(GCode::WorkOffset(15))
        );
        assert_eq!(classify_g(710, &syntec), GLookup::Known(GCode::Metric));
        assert_eq!(classify_g(710, &fanuc), GLookup::Unknown);
    }

    #[test]
    fn planned_codes_name_their_issue() {
        let fanuc = Profile::builtin(ProfileName::Fanuc);
        assert_eq!(
            classify_g(410, &fanuc),
            GLookup::Known(GCode::CutterCompLeft)
        );
        assert_eq!(
            classify_g(810, &fanuc),
            GLookup::Known(GCode::Cycle(CycleKind::Drill))
        );
        assert_eq!(classify_g(1340, &fanuc), GLookup::Unknown);
        assert_eq!(classify_g(650, &fanuc), GLookup::Known(GCode::MacroCall));
        assert_eq!(classify_g(50, &fanuc), GLookup::Known(GCode::HighSpeedMode));
        // The 0M manual's table (spec A.16) has no G05.
        assert_eq!(
            classify_g(50, &Profile::builtin(ProfileName::Fanuc0m)),
            GLookup::Unknown
        );
        assert_eq!(
            classify_g(121, &fanuc),
            GLookup::Known(GCode::PolarInterpolation)
        );
        // FANUC 0M has no polar coordinate interpolation.
        let fanuc0m = Profile::builtin(ProfileName::Fanuc0m);
        assert_eq!(classify_g(121, &fanuc0m), GLookup::Unknown);
        // Haas G47 engraves text; elsewhere G47 is a tool position offset.
        let haas = Profile::builtin(ProfileName::Haas);
        assert_eq!(classify_g(470, &haas), GLookup::Known(GCode::Engrave));
        assert_eq!(
            classify_g(470, &fanuc),
            GLookup::Known(GCode::PositionOffset(2))
        );
    }
}
