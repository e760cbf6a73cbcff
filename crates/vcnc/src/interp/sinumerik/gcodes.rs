//! The G functions and the named modal functions of SINUMERIK (`G1`, `CIP`, `SOFT`, `G500`):
//! which group each belongs to, and what vcnc does with it (docs/SINUMERIK.md 4.1).
//!
//! Never: accept a function without saying what it does. A function is run, kept as state with
//! no geometric effect on a 3-axis mill, planned for the next SINUMERIK issue (alarm V020 naming
//! it), or outside the product (alarm V022 naming it).

/// What a G function or named modal function does in vcnc.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Function {
    /// Group 1: how the block's end point is reached.
    Motion(Motion),
    /// G4, G9, G53, G153, SUPA, G63: for this block only.
    OneBlock(OneBlock),
    /// G17, G18, G19.
    Plane(crate::motion::Plane),
    /// G90 (true) or G91.
    Absolute(bool),
    /// G70, G71, G700, G710: inch (true) or metric, and whether F converts too.
    Units { inch: bool, feeds: bool },
    /// G93, G94, G95.
    FeedType(FeedType),
    /// G500 (0), G54..G57 (1..4), G505..G599 (5..99); on the 828D, G58 and G59 are 5 and 6.
    Settable(u32),
    /// G60 exact stop.
    ExactStop,
    /// G64 continuous path, G641-G645 with their rounding.
    ContinuousPath(super::path_control::Rounding),
    /// A frame instruction of group 3 (a block of its own; its axis words are the frame's).
    Frame(FrameOp),
    /// G110, G111, G112: the pole of polar coordinates.
    Pole(Pole),
    /// G96, G961 (a constant cutting rate, true) or G97, G971, with the feed type each sets.
    CuttingRate(bool, FeedType),
    /// G25 (false) or G26 (true): with S, the spindle's speed limits; with axes, the working
    /// area (issue 22).
    SpeedLimit(bool),
    /// Tool radius compensation: G40/G41/G42, NORM/KONT, G450/G451 (`compensation.rs`).
    Radius(super::compensation::RadiusFunction),
    /// Kept as state: no geometric effect on a 3-axis mill (or the planner's default already).
    State,
    /// The next SINUMERIK issue adds it.
    Planned,
    /// G291: the blocks after it, to the next G290, are ISO dialect.
    IsoMode,
    /// DIAMON, DIAMOF, DIAM90 ... (group 29 and the axis-specific forms): `diameter.rs`.
    Diameter(super::diameter::Command),
    /// Outside the product: the name says what it belongs to.
    OutOfProduct(&'static str),
}

/// The motions of group 1.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Motion {
    /// G0.
    Rapid,
    /// G1.
    Line,
    /// G2.
    Clockwise,
    /// G3.
    CounterClockwise,
    /// CIP: circle through an intermediate point.
    ThroughPoint,
    /// CT: tangential circle.
    Tangential,
    /// G33: a thread of constant lead, the axes tied to the spindle.
    Thread,
    /// G34 (increasing) and G35: a thread whose lead changes linearly (threads.rs).
    VariableThread { increasing: bool },
    /// G331: tapping with the spindle in position control; G332: its retraction.
    Tap { retract: bool },
    /// INVCW, INVCCW: along an involute of a base circle (involute.rs).
    Involute { ccw: bool },
}

/// The one-block functions vcnc runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum OneBlock {
    /// G4.
    Dwell,
    /// G9.
    ExactStop,
    /// G53: without the programmable and settable frames.
    SuppressFrames,
    /// G153: also without the basic frame.
    SuppressBasic,
    /// SUPA: also without the external offsets.
    SuppressAll,
    /// G63: tapping with a compensating chuck (no override, no blending).
    FloatingTap,
    /// G74: the reference point of the named axes.
    Reference,
    /// G75: a fixed point (FP=n) of the named axes.
    FixedPoint,
}

/// What the pole is measured from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Pole {
    /// G110: the last programmed point.
    LastPoint,
    /// G111: the work zero.
    WorkZero,
    /// G112: the last pole.
    Previous,
}

/// The frame instructions (docs/SINUMERIK.md 5.3, 5.4).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum FrameOp {
    Trans,
    Atrans,
    Rot,
    Arot,
    Rots,
    Arots,
    Scale,
    Ascale,
    Mirror,
    Amirror,
    /// 840D: the coarse translation of the named axes.
    G58,
    /// 840D: the fine translation of the named axes.
    G59,
    /// TOFRAME, TOROT and their X Y Z forms: the frame along the tool (`tool_frame.rs`);
    /// TOROT keeps the frame's other components.
    Tool {
        applicate: super::tool_frame::Applicate,
        rotation_only: bool,
    },
}

/// The feed types of group 15 that vcnc runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum FeedType {
    /// G93: inverse time.
    InverseTime,
    /// G94: mm/min.
    PerMinute,
    /// G95: mm/rev.
    PerRevolution,
}

/// The SINUMERIK group of a G function, by number (docs/SINUMERIK.md 4.1): blocks may hold one
/// function per group.
pub(super) fn group(name: &str) -> Option<u8> {
    let g = |n: u8| Some(n);
    match name {
        "G0" | "G1" | "G2" | "G3" | "CIP" | "CT" | "G33" | "G34" | "G35" | "G331" | "G332"
        | "ASPLINE" | "BSPLINE" | "CSPLINE" | "POLY" | "INVCW" | "INVCCW" | "OEMIPO1"
        | "OEMIPO2" => g(1),
        "TRANS" | "ATRANS" | "ROT" | "AROT" | "ROTS" | "AROTS" | "SCALE" | "ASCALE" | "MIRROR"
        | "AMIRROR" | "G58" | "G59" | "G25" | "G26" | "G110" | "G111" | "G112" => g(3),
        "G4" | "G63" | "G74" | "G75" | "G147" | "G148" | "G247" | "G248" | "G347" | "G348" => g(2),
        "G17" | "G18" | "G19" => g(6),
        "G40" | "G41" | "G42" => g(7),
        "LFON" | "LFOF" => g(41),
        "LFTXT" | "LFWP" | "LFPOS" => g(46),
        "TOROTOF" | "TOROT" | "TOROTZ" | "TOROTY" | "TOROTX" | "TOFRAME" | "TOFRAMEZ"
        | "TOFRAMEY" | "TOFRAMEX" => g(53),
        "G53" | "G153" | "SUPA" => g(9),
        "G60" | "G64" | "G641" | "G642" | "G643" | "G644" | "G645" => g(10),
        "G9" => g(11),
        "G601" | "G602" | "G603" => g(12),
        "G70" | "G71" | "G700" | "G710" => g(13),
        "G90" | "G91" => g(14),
        "G93" | "G94" | "G95" | "G96" | "G97" | "G931" | "G961" | "G971" | "G942" | "G952"
        | "G962" | "G972" | "G973" => g(15),
        "CFC" | "CFTCP" | "CFIN" => g(16),
        "NORM" | "KONT" | "KONTT" | "KONTC" => g(17),
        "G450" | "G451" => g(18),
        "BRISK" | "SOFT" | "DRIVE" => g(21),
        "CUT2D" | "CUT2DF" | "CUT3DC" | "CUT3DF" | "CUT3DFS" | "CUT3DFF" | "CUT3DCC"
        | "CUT3DCCD" => g(22),
        "FFWOF" | "FFWON" => g(24),
        "WALIMON" | "WALIMOF" => g(28),
        "WALCS0" | "WALCS1" | "WALCS2" | "WALCS3" | "WALCS4" | "WALCS5" | "WALCS6" | "WALCS7"
        | "WALCS8" | "WALCS9" | "WALCS10" => g(60),
        "DIAMOF" | "DIAMON" | "DIAM90" | "DIAMONA" | "DIAM90A" | "DIAMCHANA" | "DIAMCHAN"
        | "DIAMCYCOF" => g(29),
        "COMPOF" | "COMPON" | "COMPCURV" | "COMPCAD" => g(30),
        "FNORM" | "FLIN" | "FCUB" | "FPO" => g(37),
        "G290" | "G291" => g(47),
        "RTLION" | "RTLIOF" => g(55),
        "DYNNORM" | "DYNPOS" | "DYNROUGH" | "DYNSEMIFIN" | "DYNFINISH" => g(59),
        "G140" | "G141" | "G142" | "G143" => g(43),
        "G340" | "G341" => g(44),
        "G460" | "G461" | "G462" => g(48),
        "CDOF" | "CDON" | "CDOF2" => g(23),
        "CUTCONON" | "CUTCONOF" => g(40),
        "G500" | "G54" | "G55" | "G56" | "G57" => g(8),
        _ => settable_number(name).map(|_| 8),
    }
}

/// The settable frame a `G5xx` name selects beyond G54..G57 (G505..G599: 5..99).
fn settable_number(name: &str) -> Option<u32> {
    let n: u32 = name.strip_prefix("G5")?.parse().ok()?;
    (name.len() == 4 && (5..=99).contains(&n)).then_some(n)
}

/// The G functions CAM programs write in nearly every block, by number, with their groups: the
/// look-up by name would build the name first.
pub(super) fn common(number: u32) -> Option<(Function, u8)> {
    Some(match number {
        0 => (Function::Motion(Motion::Rapid), 1),
        1 => (Function::Motion(Motion::Line), 1),
        2 => (Function::Motion(Motion::Clockwise), 1),
        3 => (Function::Motion(Motion::CounterClockwise), 1),
        17 => (Function::Plane(crate::motion::Plane::Xy), 6),
        18 => (Function::Plane(crate::motion::Plane::Zx), 6),
        19 => (Function::Plane(crate::motion::Plane::Yz), 6),
        90 => (Function::Absolute(true), 14),
        91 => (Function::Absolute(false), 14),
        94 => (Function::FeedType(FeedType::PerMinute), 15),
        95 => (Function::FeedType(FeedType::PerRevolution), 15),
        _ => return None,
    })
}

/// What `name` does, on the 828D when `m828d`; None for a name that is not a G function or a
/// named modal function.
pub(super) fn function(name: &str, m828d: bool) -> Option<Function> {
    use super::compensation::RadiusFunction;
    use super::path_control::Rounding;
    use crate::interp::comp::extension::Extension;
    use crate::interp::comp::polynomial::Continuity;
    use crate::interp::comp::smooth::{Direction, Shape};
    use crate::interp::comp::transition::{Approach, OuterCorner};
    use Function::*;
    if let Some(command) = super::diameter::command(name) {
        return Some(Diameter(command));
    }
    let f = match name {
        "G0" => Motion(self::Motion::Rapid),
        "G1" => Motion(self::Motion::Line),
        "G2" => Motion(self::Motion::Clockwise),
        "G3" => Motion(self::Motion::CounterClockwise),
        "CIP" => Motion(self::Motion::ThroughPoint),
        "INVCW" => Motion(self::Motion::Involute { ccw: false }),
        "INVCCW" => Motion(self::Motion::Involute { ccw: true }),
        "CT" => Motion(self::Motion::Tangential),
        "G33" => Motion(self::Motion::Thread),
        "G34" => Motion(self::Motion::VariableThread { increasing: true }),
        "G35" => Motion(self::Motion::VariableThread { increasing: false }),
        "G331" => Motion(self::Motion::Tap { retract: false }),
        "G332" => Motion(self::Motion::Tap { retract: true }),
        "G63" => OneBlock(self::OneBlock::FloatingTap),
        "G74" => OneBlock(self::OneBlock::Reference),
        "G75" => OneBlock(self::OneBlock::FixedPoint),
        "G4" => OneBlock(self::OneBlock::Dwell),
        "G9" => OneBlock(self::OneBlock::ExactStop),
        "G53" => OneBlock(self::OneBlock::SuppressFrames),
        "G153" => OneBlock(self::OneBlock::SuppressBasic),
        "SUPA" => OneBlock(self::OneBlock::SuppressAll),
        "G17" => Plane(crate::motion::Plane::Xy),
        "G18" => Plane(crate::motion::Plane::Zx),
        "G19" => Plane(crate::motion::Plane::Yz),
        "G90" => Absolute(true),
        "G91" => Absolute(false),
        "G70" => Units {
            inch: true,
            feeds: false,
        },
        "G71" => Units {
            inch: false,
            feeds: false,
        },
        "G700" => Units {
            inch: true,
            feeds: true,
        },
        "G710" => Units {
            inch: false,
            feeds: true,
        },
        "G93" => FeedType(self::FeedType::InverseTime),
        "G94" => FeedType(self::FeedType::PerMinute),
        "G95" => FeedType(self::FeedType::PerRevolution),
        "G500" => Settable(0),
        "G54" => Settable(1),
        "G55" => Settable(2),
        "G56" => Settable(3),
        "G57" => Settable(4),
        "G58" if m828d => Settable(5),
        "G59" if m828d => Settable(6),
        "G60" => ExactStop,
        // G64 slows at corners by the machine's corner tolerance; G641-G645 round them
        // (path_control.rs).
        "G64" => ContinuousPath(Rounding::None),
        "G641" => ContinuousPath(Rounding::Distance),
        "G642" => ContinuousPath(Rounding::Tolerance(2)),
        "G643" => ContinuousPath(Rounding::Tolerance(3)),
        "G644" => ContinuousPath(Rounding::Tolerance(4)),
        "G645" => ContinuousPath(Rounding::Tolerance(5)),
        "G96" => CuttingRate(true, self::FeedType::PerRevolution),
        "G961" => CuttingRate(true, self::FeedType::PerMinute),
        "G97" => CuttingRate(false, self::FeedType::PerRevolution),
        "G971" => CuttingRate(false, self::FeedType::PerMinute),
        "G25" => SpeedLimit(false),
        "G26" => SpeedLimit(true),
        "G110" => Pole(self::Pole::LastPoint),
        "G111" => Pole(self::Pole::WorkZero),
        "G112" => Pole(self::Pole::Previous),
        "TRANS" => Frame(FrameOp::Trans),
        "ATRANS" => Frame(FrameOp::Atrans),
        "ROT" => Frame(FrameOp::Rot),
        "AROT" => Frame(FrameOp::Arot),
        "ROTS" => Frame(FrameOp::Rots),
        "AROTS" => Frame(FrameOp::Arots),
        "SCALE" => Frame(FrameOp::Scale),
        "ASCALE" => Frame(FrameOp::Ascale),
        "MIRROR" => Frame(FrameOp::Mirror),
        "AMIRROR" => Frame(FrameOp::Amirror),
        "G58" => Frame(FrameOp::G58),
        "TOFRAME" | "TOFRAMEZ" | "TOFRAMEY" | "TOFRAMEX" | "TOROT" | "TOROTZ" | "TOROTY"
        | "TOROTX" => {
            use super::tool_frame::Applicate;
            let applicate = match name.as_bytes().last() {
                Some(b'Y') => Applicate::Y,
                Some(b'X') => Applicate::X,
                _ => Applicate::Z,
            };
            Frame(FrameOp::Tool {
                applicate,
                rotation_only: name.starts_with("TOROT"),
            })
        }
        // The tool frame's group back to its default: the frame it made stays (choice,
        // docs/SINUMERIK.md 5.3).
        "TOROTOF" => State,
        // Fast retraction: acts on an NC stop or a fast input during G33 only (lift_fast.rs).
        "LFON" | "LFOF" | "LFTXT" | "LFWP" | "LFPOS" => State,
        "G59" => Frame(FrameOp::G59),
        "G40" => Radius(RadiusFunction::Off),
        "G41" => Radius(RadiusFunction::Left),
        "G42" => Radius(RadiusFunction::Right),
        "NORM" => Radius(RadiusFunction::Approach(Approach::Straight)),
        "KONT" => Radius(RadiusFunction::Approach(Approach::AroundPoint)),
        "KONTT" => Radius(RadiusFunction::Approach(Approach::Curve(
            Continuity::Tangent,
        ))),
        "KONTC" => Radius(RadiusFunction::Approach(Approach::Curve(
            Continuity::Curvature,
        ))),
        "G450" => Radius(RadiusFunction::Outer(OuterCorner::TransitionCircle)),
        "G451" => Radius(RadiusFunction::Outer(OuterCorner::Intersection)),
        "CUTCONON" => Radius(RadiusFunction::Constant(true)),
        "CUTCONOF" => Radius(RadiusFunction::Constant(false)),
        "G147" => Radius(RadiusFunction::Smooth(Shape::Line)),
        "G247" => Radius(RadiusFunction::Smooth(Shape::QuarterCircle)),
        "G347" => Radius(RadiusFunction::Smooth(Shape::HalfCircle)),
        "G148" => Radius(RadiusFunction::Retreat(Shape::Line)),
        "G248" => Radius(RadiusFunction::Retreat(Shape::QuarterCircle)),
        "G348" => Radius(RadiusFunction::Retreat(Shape::HalfCircle)),
        "G340" => Radius(RadiusFunction::SmoothInPlane(false)),
        "G341" => Radius(RadiusFunction::SmoothInPlane(true)),
        "G140" => Radius(RadiusFunction::SmoothSide(Direction::Compensation)),
        "G141" => Radius(RadiusFunction::SmoothSide(Direction::Left)),
        "G142" => Radius(RadiusFunction::SmoothSide(Direction::Right)),
        "G143" => Radius(RadiusFunction::SmoothSide(Direction::Tangent)),
        "G460" => Radius(RadiusFunction::Extension(Extension::None)),
        "CDON" => Radius(RadiusFunction::Bottleneck(true)),
        // CDOF2 differs from CDOF in 3D circumferential milling only (seed 002 L7810-7815).
        "CDOF" | "CDOF2" => Radius(RadiusFunction::Bottleneck(false)),
        "G461" => Radius(RadiusFunction::Extension(Extension::Circle)),
        "G462" => Radius(RadiusFunction::Extension(Extension::Line)),
        "G601" | "G602" | "G603" | "CFC" | "CFTCP" | "CFIN" | "BRISK" | "SOFT" | "DRIVE"
        | "CUT2D" | "FFWOF" | "FFWON" | "WALIMON" | "WALIMOF" | "COMPOF" | "COMPON"
        | "COMPCURV" | "COMPCAD" | "FNORM" | "RTLION" | "RTLIOF" | "DYNNORM" | "DYNPOS"
        | "DYNROUGH" | "DYNSEMIFIN" | "DYNFINISH" | "G290" | "TRAFOOF" | "WALCS0" | "WALCS1"
        | "WALCS2" | "WALCS3" | "WALCS4" | "WALCS5" | "WALCS6" | "WALCS7" | "WALCS8" | "WALCS9"
        | "WALCS10"
        // CUT2DF compensates in the frame's plane: with a frame that keeps the plane (the
        // only kind vcnc compensates under) that is CUT2D's (seed 002 L7854-7928).
        | "CUT2DF" => State,
        "FLIN" | "FCUB" => Planned,
        "G291" => IsoMode,
        "CUT3DC" | "CUT3DF" | "CUT3DFS" | "CUT3DFF" | "CUT3DCC" | "CUT3DCCD" => {
            OutOfProduct("5-axis 3D tool radius compensation")
        }
        "ASPLINE" | "BSPLINE" | "CSPLINE" | "POLY" => OutOfProduct("spline interpolation"),
        "OEMIPO1" | "OEMIPO2" => OutOfProduct("OEM interpolation"),
        "G931" | "G942" | "G952" | "G962" | "G972" | "G973" | "FPO" => {
            OutOfProduct("feed types of turning and grinding")
        }
        _ => {
            let n = settable_number(name)?;
            if m828d {
                return None;
            }
            Settable(n)
        }
    };
    Some(f)
}

/// Predefined procedures and keywords outside the product, by what they belong to.
pub(super) fn out_of_product(name: &str) -> Option<&'static str> {
    Some(match name {
        "TRANSMIT" | "TRACYL" | "TRAORI" | "TRAANG" | "TRACON" | "TRAFOON" => {
            "kinematic transformations"
        }
        "COUPON" | "COUPOF" | "COUPDEF" | "COUPDEL" | "TRAILON" | "TRAILOF" | "LEADON"
        | "LEADOF" | "EGON" | "EGOFS" => "axis couplings",
        "WAITM" | "WAITMC" | "WAITE" | "SETM" | "CLEARM" | "START" | "INIT" => "several channels",
        "PUNCHACC" | "SPOF" | "SON" | "PON" => "punching",
        "ORIWKS" | "ORIMKS" | "ORIAXES" | "ORIVECT" | "ORIEULER" | "ORIRPY" => {
            "orientation transformations"
        }
        "FPR" | "FPRAON" | "FPRAOF" | "FDA" | "FAD" => {
            "feeds derived from another axis or spindle, the handwheel, synchronized actions or soft approach"
        }
        "LIFTFAST" => "fast retraction outside a thread",
        "VELOLIMA" | "ACCLIMA" | "JERKLIMA" | "EGONSYN" => {
            "the axes' dynamic limits and electronic gears"
        }
        "IDS" | "ID" | "WHEN" | "WHENEVER" | "EVERY" | "FROM" | "DO" => {
            "synchronized actions (the control's real-time events)"
        }
        _ if name.starts_with("$MA_") || name.starts_with("$MC_") || name.starts_with("$MN_") => {
            "the control's machine data"
        }
        _ if name.starts_with("$TC_MPP")
            || name.starts_with("$AC_")
            || name.starts_with("$AA_")
            || name.starts_with("$SA_") =>
        {
            "the control's real-time and magazine data"
        }
        _ => return None,
    })
}

/// What an address with a number names beyond the master spindle and the path (`S2=`, `M2=`,
/// `F7=`, `SVC[2]`): units a 3-axis mill with one spindle does not have.
pub(super) fn other_unit(
    name: &str,
    value: &crate::syntax::sinumerik::Value,
) -> Option<&'static str> {
    let extended = |letter: &str| {
        name.strip_prefix(letter)
            .is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()) && n != "1")
    };
    if extended("S") || extended("M") || extended("SPOS") {
        return Some("spindles other than the master spindle");
    }
    if extended("F") {
        return Some("feeds of several axes or in synchronized actions (F1 to F7)");
    }
    if matches!(name, "SVC" | "LIMS" | "SPOS")
        && matches!(value, crate::syntax::sinumerik::Value::Indexed(..))
    {
        return Some("spindles other than the master spindle");
    }
    None
}

/// Predefined procedures and the standard cycles the next SINUMERIK issue adds: the cycles'
/// own names only (a machine's own cycle, such as CYCLE189 of a manufacturer, is a subprogram
/// like any other and is found in the library first), less those the front end runs
/// (`cycles/`).
pub(super) fn planned_call(name: &str) -> bool {
    if super::cycles::runs(name) {
        return false;
    }
    let standard_cycle = name
        .strip_prefix("CYCLE")
        .and_then(|n| n.parse::<u32>().ok())
        .is_some_and(|n| {
            matches!(n, 60..=99 | 801 | 802 | 830..=899 | 4071..=4079 | 952) && n != 832
        });
    standard_cycle
        || matches!(
            name,
            "POCKET1"
                | "POCKET2"
                | "POCKET3"
                | "POCKET4"
                | "SLOT1"
                | "SLOT2"
                | "LONGHOLE"
                | "HOLES1"
                | "HOLES2"
        )
}

/// The alarm of a call whose program the library does not have: a standard cycle not run yet
/// (V020, issue 22), a procedure outside the product (V022), or a subprogram not found.
pub(super) fn missing_program(name: &str, span: crate::source::Span) -> crate::alarm::Alarm {
    use crate::alarm::{Alarm, AlarmCode};
    if planned_call(name) {
        return Alarm::error(
            AlarmCode::NotSupportedYet,
            span,
            format!("{name} is not run yet (planned: issue 22, SINUMERIK cycles and compensation)"),
        );
    }
    if let Some(what) = out_of_product(name) {
        return Alarm::error(
            AlarmCode::NotInProduct,
            span,
            format!("{name} belongs to {what}, which vcnc does not simulate"),
        );
    }
    Alarm::error(
        AlarmCode::ProgramNotFound,
        span,
        format!("subprogram {name} not found"),
    )
    .with_help(format!(
        "put {name}.SPF in the program's directory or in a directory given with --lib"
    ))
}

/// The number of the member of `group` in force, as `$P_GG[group]` reads it (the tables'
/// "No." column); 0 for a group vcnc keeps no state of.
pub(super) fn member(modal: &super::Modal, group: u32) -> i32 {
    use crate::motion::Plane;
    match group {
        1 => match modal.motion {
            Motion::Rapid => 1,
            Motion::Line => 2,
            Motion::Clockwise => 3,
            Motion::CounterClockwise => 4,
            Motion::ThroughPoint => 5,
            Motion::Tangential => 15,
            Motion::Thread => 10,
            Motion::VariableThread { increasing: true } => 16,
            Motion::VariableThread { increasing: false } => 17,
            Motion::Tap { retract: false } => 11,
            Motion::Tap { retract: true } => 12,
            Motion::Involute { ccw: false } => 18,
            Motion::Involute { ccw: true } => 19,
        },
        6 => match modal.plane {
            Plane::Xy => 1,
            Plane::Zx => 2,
            Plane::Yz => 3,
        },
        8 => match modal.settable {
            0 => 1,
            n => n as i32 + 1,
        },
        10 if modal.exact_stop => 1,
        10 => modal.path_control.group_value(),
        13 => match (modal.inch, modal.inch_feeds) {
            (true, false) => 1,
            (false, false) => 2,
            (true, true) => 3,
            (false, true) => 4,
        },
        14 => 2 - i32::from(modal.absolute),
        15 => match modal.feed_type {
            FeedType::InverseTime => 1,
            FeedType::PerMinute => 2,
            FeedType::PerRevolution => 3,
        },
        _ => 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_common_g_functions_are_the_named_ones() {
        for n in 0..1000 {
            if let Some((function, group)) = common(n) {
                let name = format!("G{n}");
                assert_eq!(Some(function), super::function(&name, false), "{name}");
                assert_eq!(Some(group), super::group(&name), "{name}");
            }
        }
    }

    #[test]
    fn every_function_has_a_group() {
        for name in [
            "G0", "CIP", "G17", "G500", "G505", "G599", "SOFT", "G9", "SUPA",
        ] {
            assert!(group(name).is_some(), "{name}");
            assert!(function(name, false).is_some(), "{name}");
        }
        assert_eq!(function("G599", false), Some(Function::Settable(99)));
        assert_eq!(function("G505", true), None);
        assert_eq!(function("G58", true), Some(Function::Settable(5)));
        assert_eq!(function("G5", false), None);
    }
}

// The table of G functions for README.md (`crate::profile::supported_codes_markdown`).

/// What vcnc does with a G function or named modal function, as README.md's table says it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Support {
    /// Runs: it moves, or changes what the following blocks do.
    Runs,
    /// Kept as state, with no geometric effect on a 3-axis mill.
    State,
    /// The next SINUMERIK issue (22) adds it: alarm V020 naming it.
    Planned,
    /// Outside the product: alarm V022 naming it and what it belongs to.
    OutOfProduct(&'static str),
    /// Not a G function of this control (the 828D has no G505 ... G599).
    Unknown,
}

/// One row of the table: the function (`G505 … G599` stands for the range), its group, what
/// the manual calls it (sinumerik-tables.md 4.2), and its support on the 840D sl and the 828D.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Listed {
    pub(crate) name: &'static str,
    pub(crate) group: Option<u8>,
    pub(crate) meaning: &'static str,
    pub(crate) on_840d: Support,
    pub(crate) on_828d: Support,
}

/// Every G function and named modal function [`function`] knows, by group, with what the
/// manual calls it.
const LISTED: &[(&str, &str)] = &[
    ("G0", "Rapid traverse"),
    ("G1", "Linear interpolation"),
    ("G2", "Circular interpolation clockwise"),
    ("G3", "Circular interpolation counter-clockwise"),
    ("CIP", "Circular interpolation through intermediate point"),
    ("CT", "Circle with tangential transition"),
    ("G33", "Thread cutting with constant lead"),
    ("G34", "Thread cutting with linearly increasing lead"),
    ("G35", "Thread cutting with linearly decreasing lead"),
    ("G331", "Tapping"),
    ("G332", "Retraction (tapping)"),
    ("ASPLINE", "Akima spline"),
    ("BSPLINE", "B-spline"),
    ("CSPLINE", "Cubic spline"),
    ("POLY", "Polynomial interpolation"),
    ("INVCW", "Involute interpolation clockwise"),
    ("INVCCW", "Involute interpolation counter-clockwise"),
    ("OEMIPO1", "Reserved"),
    ("OEMIPO2", "Reserved"),
    ("G4", "Preset dwell time"),
    ("G63", "Tapping without synchronization"),
    ("G74", "Reference point approach with synchronization"),
    ("G75", "Fixed point approach"),
    ("G147", "Approach contour with straight line"),
    ("G148", "Leave contour with straight line"),
    ("G247", "Approach contour with quarter circle"),
    ("G248", "Leave contour with quarter circle"),
    ("G347", "Approach contour with semicircle"),
    ("G348", "Leave contour with semicircle"),
    ("TRANS", "TRANSLATION: programmable offset"),
    ("ATRANS", "Additive TRANSLATION: additive programmable offset"),
    ("ROT", "ROTATION: programmable rotation"),
    ("AROT", "Additive ROTATION: programmable rotation"),
    ("ROTS", "Rotation with solid angles"),
    ("AROTS", "Additive rotation with solid angles"),
    ("SCALE", "SCALE: programmable scaling"),
    ("ASCALE", "Additive SCALE: programmable scaling"),
    ("MIRROR", "MIRROR: programmable mirroring"),
    ("AMIRROR", "Additive MIRROR: programmable mirroring"),
    ("G58", "Axial programmable offset, coarse (840D); the 5th settable zero offset on the 828D"),
    ("G59", "Axial programmable offset, fine (840D); the 6th settable zero offset on the 828D"),
    ("G25", "Minimum working-area limitation / spindle speed limitation"),
    ("G26", "Maximum working-area limitation / spindle speed limitation"),
    ("G110", "Pole relative to the last programmed position"),
    ("G111", "Pole programming relative to the origin of the current WCS"),
    ("G112", "Pole programming relative to the last valid pole"),
    ("G17", "Plane selection 1st – 2nd geometry axis (X/Y)"),
    ("G18", "Plane selection 3rd – 1st geometry axis (Z/X)"),
    ("G19", "Plane selection 2nd – 3rd geometry axis (Y/Z)"),
    ("G40", "No tool radius compensation"),
    ("G41", "Tool radius compensation left of contour"),
    ("G42", "Tool radius compensation right of contour"),
    ("G500", "Deactivation of settable zero offsets (G54 … G57, G505 … G599)"),
    ("G54", "1st settable zero offset"),
    ("G55", "2nd settable zero offset"),
    ("G56", "3rd settable zero offset"),
    ("G57", "4th settable zero offset"),
    ("G505 … G599", "5th to 99th settable zero offset"),
    ("G53", "Suppression of the programmable and settable frames (one block)"),
    ("G153", "As G53, plus suppression of the basic frames"),
    ("SUPA", "As G153, plus suppression of the system frames, DRF and external offset"),
    ("G60", "Exact stop"),
    ("G64", "Continuous-path mode"),
    ("G641", "Continuous-path mode, smoothing by distance"),
    ("G642", "Continuous-path mode with smoothing within defined tolerances"),
    ("G643", "Continuous-path mode with smoothing within defined tolerances (block-internal)"),
    ("G644", "Continuous-path mode with smoothing with maximum possible dynamic response"),
    ("G645", "Continuous-path mode, smoothing with tangential transitions"),
    ("G9", "Exact stop"),
    ("G601", "Block change at exact stop fine"),
    ("G602", "Block change at exact stop coarse"),
    ("G603", "Block change at IPO end of block"),
    ("G70", "Inch input system (lengths)"),
    ("G71", "Metric input system, mm (lengths)"),
    ("G700", "Inch input system, lengths and feeds"),
    ("G710", "Metric input system, lengths and feeds"),
    ("G90", "Absolute dimensioning"),
    ("G91", "Incremental dimensioning input"),
    ("G93", "Inverse-time feedrate 1/min"),
    ("G94", "Linear feedrate in mm/min, inch/min"),
    ("G95", "Revolutional feedrate in mm/rev, inch/rev"),
    ("G96", "Constant cutting rate and feed type as for G95 ON"),
    ("G97", "Constant cutting rate and feed type as for G95 OFF"),
    ("G931", "Feed specified by traversing time, deactivate constant path velocity"),
    ("G961", "Constant cutting rate and feed type as for G94 ON"),
    ("G971", "Constant cutting rate and feed type as for G94 OFF"),
    ("G942", "Freeze linear feedrate and constant cutting rate or spindle speed"),
    ("G952", "Freeze revolutional feedrate and constant cutting rate or spindle speed"),
    ("G962", "Linear or revolutional feedrate and constant cutting rate"),
    ("G972", "Freeze linear or revolutional feedrate and constant spindle speed"),
    ("G973", "Revolutional feedrate without spindle speed limitation (ISO mode)"),
    ("CFC", "Constant feedrate at contour, effective on inside and outside radii"),
    ("CFTCP", "Constant feedrate at tool centre point (centre-point path)"),
    ("CFIN", "Constant feedrate on inside radius only, acceleration on outside radius"),
    ("NORM", "Normal position at start and end point"),
    ("KONT", "Travel around contour at start and end point"),
    ("KONTT", "Approach/retract with constant tangent"),
    ("KONTC", "Approach/retract with constant curvature"),
    ("G450", "Transition circle at outer corners"),
    ("G451", "Intersection of equidistant paths at outer corners"),
    ("BRISK", "Fast, non-smoothed path acceleration"),
    ("SOFT", "Soft, smoothed (jerk-limited) path acceleration"),
    ("DRIVE", "Velocity-dependent path acceleration"),
    ("CUT2D", "2½D tool offset determined by G17–G19"),
    ("CUT2DF", "2½D tool offset relative to the current frame"),
    ("CUT3DC", "3D tool offset, circumferential milling"),
    ("CUT3DF", "3D tool offset, face milling with non-constant tool orientation"),
    ("CUT3DFS", "3D tool offset, face milling with constant tool orientation independent of the active frame"),
    ("CUT3DFF", "3D tool offset, face milling with constant tool orientation dependent on the active frame"),
    ("CUT3DCC", "3D tool offset, circumferential milling with limit surfaces"),
    ("CUT3DCCD", "3D tool offset, circumferential milling, limit surfaces, differential tool"),
    ("FFWOF", "Feedforward control OFF"),
    ("FFWON", "Feedforward control ON"),
    ("WALIMON", "Working-area limitation ON"),
    ("WALIMOF", "Working-area limitation OFF"),
    ("DIAMOF", "Channel-specific diameter programming OFF"),
    ("DIAMON", "Channel-specific diameter programming ON"),
    ("DIAM90", "Diameter programming for G90, radius for G91"),
    ("DIAMONA", "Axis-specific diameter programming ON"),
    ("DIAM90A", "Axis-specific diameter programming for G90, radius for G91"),
    ("DIAMCHANA", "Axis takes the channel's diameter programming status"),
    ("DIAMCHAN", "All axes take the channel's diameter programming status"),
    ("DIAMCYCOF", "Diameter programming OFF during cycles"),
    ("DIAMOFA", "Axis-specific diameter programming OFF"),
    ("DIACYCOFA", "Axis-specific diameter programming OFF during cycles"),
    ("COMPOF", "NC block compression OFF"),
    ("COMPON", "Compressor function COMPON ON"),
    ("COMPCURV", "Compressor function COMPCURV ON"),
    ("COMPCAD", "Compressor function COMPCAD ON"),
    ("FNORM", "Feed normal according to DIN 66025"),
    ("FLIN", "Feed linear variable"),
    ("FCUB", "Feed variable according to cubic spline"),
    ("FPO", "Feed characteristic as a polynomial"),
    ("CDOF", "Collision detection OFF"),
    ("CDON", "Collision detection ON"),
    ("CDOF2", "Collision detection OFF (currently only for CUT3DC)"),
    ("G140", "SAR approach direction defined by G41/G42"),
    ("G141", "SAR approach direction to the left of the contour"),
    ("G142", "SAR approach direction to the right of the contour"),
    ("G143", "SAR approach direction dependent on tangent"),
    ("G340", "Spatial approach block (infeed and approach in one block)"),
    ("G341", "Infeed in the perpendicular axis, then approach in the plane"),
    ("G290", "Activate SINUMERIK language mode"),
    ("G291", "Activate ISO language mode"),
    ("G460", "Collision detection for approach and retraction block ON"),
    ("G461", "If no intersection in the TRC block, extend the border block with an arc"),
    ("G462", "If no intersection in the TRC block, extend the border block with a straight line"),
    ("RTLION", "Rapid traverse motion with linear interpolation ON"),
    ("RTLIOF", "Rapid traverse with single-axis interpolation"),
    ("DYNNORM", "Standard dynamic response, as previously"),
    ("DYNPOS", "Positioning mode, tapping"),
    ("DYNROUGH", "Roughing"),
    ("DYNSEMIFIN", "Finishing (semi-finishing)"),
    ("DYNFINISH", "Smooth finishing"),
    ("TRAFOOF", "Transformation OFF"),
    ("CUTCONON", "Constant tool radius compensation ON"),
    ("CUTCONOF", "Constant tool radius compensation OFF"),
];

/// The G functions and named modal functions, by group (those without one last), each with
/// its support on the 840D sl and the 828D.
pub(crate) fn listing() -> Vec<Listed> {
    let support = |name: &str, m828d: bool| match function(name, m828d) {
        None => Support::Unknown,
        Some(Function::State) => Support::State,
        Some(Function::Planned) => Support::Planned,
        Some(Function::OutOfProduct(what)) => Support::OutOfProduct(what),
        Some(_) => Support::Runs,
    };
    let mut rows: Vec<Listed> = LISTED
        .iter()
        .map(|&(name, meaning)| {
            // The range is listed once; its first member speaks for it.
            let probe = if name.contains('…') { "G505" } else { name };
            Listed {
                name,
                group: group(probe),
                meaning,
                on_840d: support(probe, false),
                on_828d: support(probe, true),
            }
        })
        .collect();
    // Stable: within a group, the order of LISTED.
    rows.sort_by_key(|row| row.group.unwrap_or(u8::MAX));
    rows
}

#[cfg(test)]
mod listing_tests {
    use super::*;

    #[test]
    fn the_listing_holds_every_function_and_every_name_in_it_is_one() {
        let listed = listing();
        for row in &listed {
            assert!(
                row.on_840d != Support::Unknown || row.on_828d != Support::Unknown,
                "{}",
                row.name
            );
        }
        // Every G number a control could write: listed, or in the range G505 ... G599.
        for n in 0..1000 {
            let name = format!("G{n}");
            let known = function(&name, false).is_some() || group(&name).is_some();
            let listed_here = listed.iter().any(|row| row.name == name) || (505..=599).contains(&n);
            assert_eq!(known, listed_here, "{name}");
        }
        let mut names: Vec<&str> = listed.iter().map(|row| row.name).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), listed.len(), "a name listed twice");
    }

    #[test]
    fn the_listing_says_what_each_variant_does() {
        let row = |name: &str| listing().into_iter().find(|row| row.name == name).unwrap();
        assert_eq!(row("G1").on_840d, Support::Runs);
        assert_eq!(row("SOFT").on_828d, Support::State);
        assert_eq!(row("G41").on_840d, Support::Runs);
        assert_eq!(row("G641").on_840d, Support::Runs);
        assert_eq!(row("FLIN").on_840d, Support::Planned);
        assert_eq!(row("DIAMON").on_840d, Support::Runs);
        assert_eq!(row("G34").on_840d, Support::Runs);
        assert!(matches!(row("G962").on_840d, Support::OutOfProduct(_)));
        let range = row("G505 … G599");
        assert_eq!(
            (range.on_840d, range.on_828d),
            (Support::Runs, Support::Unknown)
        );
        assert_eq!(range.group, Some(8));
    }

    /// sinumerik-tables.md 4.2: CDON, CDOF, CDOF2 are group 23 (collision monitoring at inside
    /// contours), CUTCONON and CUTCONOF group 40 (constant tool radius compensation).
    #[test]
    fn collision_monitoring_and_constant_compensation_have_their_groups() {
        for name in ["CDON", "CDOF", "CDOF2"] {
            assert_eq!(group(name), Some(23), "{name}");
        }
        for name in ["CUTCONON", "CUTCONOF"] {
            assert_eq!(group(name), Some(40), "{name}");
        }
    }
}
