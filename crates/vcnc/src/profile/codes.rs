//! The G-code table: what each G number means on a profile, and its modal group.
//!
//! Codes are integers in tenths (G54.1 is 541), never floats. [`classify_g`] is the one place that
//! maps a number to a meaning; the interpreter matches on [`GCode`].

use super::Profile;

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
    /// G04.
    Dwell,
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
    /// G90.
    Absolute,
    /// G91.
    Incremental,
    /// G92.
    SetCoordinates,
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
    /// G50.
    ScalingCancel,
    /// G50.1.
    MirrorCancel,
    /// G67.
    ModalMacroCancel,
    /// G69.
    RotationCancel,
    /// G13.1.
    PolarInterpolationCancel,
}

impl GCode {
    /// The modal group of the code.
    pub fn group(self) -> Group {
        use GCode::*;
        match self {
            Rapid | Linear | ArcClockwise | ArcCounterClockwise => Group::Motion,
            PlaneXy | PlaneZx | PlaneYz => Group::Plane,
            Absolute | Incremental => Group::Distance,
            InverseTimeFeed | FeedPerMinute | FeedPerRevolution => Group::FeedMode,
            Inch | Metric => Group::Units,
            CutterCompCancel => Group::CutterComp,
            LengthCompPlus | LengthCompMinus | LengthCompCancel => Group::LengthComp,
            CycleCancel => Group::Cycle,
            ReturnToInitialLevel | ReturnToRLevel => Group::CycleReturn,
            ScalingCancel => Group::Scaling,
            ModalMacroCancel => Group::ModalMacro,
            ConstantSurfaceSpeed | ConstantSpindleSpeed => Group::SpindleMode,
            WorkOffset(_) | ExtendedWorkOffset => Group::WorkOffset,
            ExactStopMode | AutomaticCornerOverride | TappingMode | ContinuousMode => Group::PathMode,
            RotationCancel => Group::Rotation,
            PolarCancel => Group::Polar,
            PolarInterpolationCancel => Group::PolarInterpolation,
            MirrorCancel => Group::Mirror,
            Dwell | ExactStopOnce | DataInput | ReferenceReturn | ReturnFromReference | NthReferenceReturn
            | LocalCoordinates | MachineCoordinates | SetCoordinates | PresetCoordinates => Group::NonModal,
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
        131 => PolarInterpolationCancel,
        150 => PolarCancel,
        170 => PlaneXy,
        180 => PlaneZx,
        190 => PlaneYz,
        200 => Inch,
        210 => Metric,
        700 if profile.g70_g71_units => Inch,
        710 if profile.g70_g71_units => Metric,
        280 => ReferenceReturn,
        290 => ReturnFromReference,
        300 => NthReferenceReturn,
        400 => CutterCompCancel,
        430 => LengthCompPlus,
        440 => LengthCompMinus,
        490 => LengthCompCancel,
        500 => ScalingCancel,
        501 => MirrorCancel,
        520 => LocalCoordinates,
        530 => MachineCoordinates,
        540..=590 if tenths % 10 == 0 => WorkOffset(((tenths - 530) / 10) as u8),
        541 if profile.g54_1_count > 0 => ExtendedWorkOffset,
        1540 if profile.g154_extended_offsets => ExtendedWorkOffset,
        591..=599 if profile.g59_x_offsets => WorkOffset((tenths - 591 + 7) as u8),
        610 => ExactStopMode,
        620 => AutomaticCornerOverride,
        630 => TappingMode,
        640 => ContinuousMode,
        670 => ModalMacroCancel,
        690 => RotationCancel,
        800 => CycleCancel,
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
        990 => ReturnToRLevel,
        _ => return not_yet(tenths, profile),
    };
    Known(known)
}

/// Codes that exist on the controls but are not run yet, with the issue that adds them.
fn not_yet(tenths: i32, profile: &Profile) -> GLookup {
    use GLookup::NotSupported;
    match tenths {
        // Macro calls.
        650 | 660 => NotSupported(Some(3)),
        // Canned cycles and hole patterns.
        730 | 740 | 760 | 810..=890 if tenths % 10 == 0 => NotSupported(Some(4)),
        1340 | 1350 | 1360 | 1371 => NotSupported(Some(4)),
        120 | 130 if profile.g12_g13_circle_cutting => NotSupported(Some(4)),
        // Compensation and transformations.
        410 | 420 | 450 | 460 | 470 | 480 | 510 | 511 | 680 | 160 | 121 => NotSupported(Some(5)),
        // High-speed and smoothing modes.
        50 | 51 | 80 | 1870 => NotSupported(Some(6)),
        // Known codes with no issue planned yet.
        62 | 70 | 71 | 220 | 230 | 270 | 310 | 330 | 370 | 371 | 434 | 531 | 682 | 1031 | 1030 | 1201
        | 1430 => NotSupported(None),
        _ => GLookup::Unknown,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::profile::{Profile, ProfileName};

    #[test]
    fn work_offsets_map_to_their_numbers() {
        let fanuc = Profile::builtin(ProfileName::Fanuc);
        assert_eq!(classify_g(540, &fanuc), GLookup::Known(GCode::WorkOffset(1)));
        assert_eq!(classify_g(590, &fanuc), GLookup::Known(GCode::WorkOffset(6)));
        assert_eq!(classify_g(541, &fanuc), GLookup::Known(GCode::ExtendedWorkOffset));
        assert_eq!(classify_g(591, &fanuc), GLookup::Unknown);
        let syntec = Profile::builtin(ProfileName::Syntec);
        assert_eq!(classify_g(599, &syntec), GLookup::Known(GCode::WorkOffset(15)));
        assert_eq!(classify_g(710, &syntec), GLookup::Known(GCode::Metric));
        assert_eq!(classify_g(710, &fanuc), GLookup::Unknown);
    }

    #[test]
    fn planned_codes_name_their_issue() {
        let fanuc = Profile::builtin(ProfileName::Fanuc);
        assert_eq!(classify_g(410, &fanuc), GLookup::NotSupported(Some(5)));
        assert_eq!(classify_g(810, &fanuc), GLookup::NotSupported(Some(4)));
        assert_eq!(classify_g(650, &fanuc), GLookup::NotSupported(Some(3)));
    }
}
