//! Alarms: what the control says when a program is wrong or uses what vcnc cannot run yet.
//!
//! An [`Alarm`] is plain data (code, severity, message, the span of the word that caused it,
//! secondary labels, help). Every stage produces the same type; rendering for people or machines
//! is the caller's business. Front ends never fail: they report an alarm and go on with the next
//! block. The interpreter stops at the first alarm of severity [`Severity::Error`], exactly where
//! the control would stop, and goes on after a [`Severity::Warning`].

use crate::source::Span;
use std::fmt;

/// How serious an alarm is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Severity {
    /// The control would run on, but the program probably does not do what its author meant.
    Warning,
    /// The control stops with an alarm at this block.
    Error,
}

impl Severity {
    /// The lower-case name used in text and JSON output.
    pub fn as_str(self) -> &'static str {
        match self {
            Severity::Warning => "warning",
            Severity::Error => "error",
        }
    }
}

/// The kind of an alarm. Each variant has a stable string id ([`AlarmCode::id`]) for JSON output
/// and a short code for people ([`AlarmCode::code`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum AlarmCode {
    /// A character that cannot start a word (e.g. `$` in an ISO block). Fix: remove it or put it
    /// in a comment.
    UnexpectedCharacter,
    /// An address letter with no number after it (`X;`). FANUC: alarm PS0003-like "format error".
    MissingValue,
    /// A number that cannot be read (`X1.2.3`, too many digits).
    BadNumber,
    /// A `(` comment that is not closed before the end of the line.
    UnclosedComment,
    /// The same address twice in one block where the control allows it once (`X1. X2.`).
    DuplicateAddress,
    /// A decimal point in a word that takes whole numbers only (`H1.5`, `M3.5`).
    DecimalPointNotAllowed,
    /// A value outside the range the control accepts for that address.
    ValueOutOfRange,
    /// A G code that does not exist on this controller profile.
    UnknownGCode,
    /// Two G codes of the same modal group in one block, where the profile does not allow it.
    SameGroupGCodes,
    /// A code or construct the controller accepts but vcnc does not implement yet. The message
    /// names it; the issue that will add it is in the help text.
    NotSupportedYet,
    /// A program given to an interpreter of another dialect (SINUMERIK text to the ISO
    /// interpreter).
    DialectNotSupported,
    /// A command of the control that vcnc keeps as state without modelling its effect (a
    /// compressor, an acceleration profile, high-speed settings): a note, once per command.
    KeptAsState,
    /// A command of the control that is outside what vcnc models (turning, grinding, couplings,
    /// several channels, orientation transformations). The message names it and says why.
    NotInProduct,
    /// A cutting move (G01/G02/G03) before any feed rate was programmed. FANUC alarm 011.
    NoFeedRate,
    /// A circular move with neither a radius (R) nor centre words (I J K).
    ArcWithoutCenter,
    /// A circular move whose end point is not on the circle through its start point: the
    /// distances from the centre differ by more than the profile's arc tolerance. FANUC alarm 020.
    ArcEndNotOnCircle,
    /// A circular move with R smaller than half the distance between start and end.
    ArcRadiusTooSmall,
    /// A SINUMERIK contour definition that cannot be made: two `ANG=` lines that are parallel,
    /// an `ANG=` line along the axis of its one coordinate, a chamfer or rounding where the path
    /// turns back on itself or where no rounding touches both elements. As a warning: a chamfer
    /// or rounding too large for its elements, made smaller as the control does (PGsl 9.15).
    ContourDefinition,
    /// An H or D offset number the tool table does not have.
    OffsetNumberOutOfRange,
    /// A work offset number that does not exist (G54.1 P0, P301 ...).
    WorkOffsetOutOfRange,
    /// A G10 block with an L number or word the profile does not accept.
    BadDataInput,
    /// An axis word for an axis the machine does not have.
    AxisNotOnMachine,
    /// A word that has no meaning in this block (e.g. R in a G00 block where nothing reads it).
    WordNotAllowed,
    /// A reference point number that does not exist (G30 P5).
    ReferencePointOutOfRange,
    /// A 5-axis function the machine cannot do: G43.4, G53.1 or CYCLE800 on a machine file
    /// without `[kinematics]`, a tool direction its rotary axes cannot reach, G53.1 without
    /// G68.2 (Syntec spec 1.32: the manual gives no number), a negative tool length under G43.4
    /// (spec 1.26 rule 3).
    FiveAxis,
    /// G29 for an axis that no G28/G30 has given an intermediate point.
    NoIntermediatePoint,
    /// The program text ended without M02, M30 or `%`.
    MissingProgramEnd,
    /// A feed rate of zero or a negative feed rate.
    BadFeedRate,
    /// A dwell with a negative time.
    BadDwell,
    /// The program file could not be read.
    ReadError,
    /// Cutter radius compensation cannot make the tool-centre path: an arc the tool does not
    /// fit inside, or a corner where the compensated path would cut into the contour. FANUC
    /// alarms 033 and 041.
    CutterCompensation,
    /// G45-G48 where they cannot work: with cutter compensation (Syntec COR-082), on an arc that
    /// is not 90 or 270 degrees or is given by R (COR-081).
    PositionOffset,
    /// A canned cycle without the data it needs (Z, Q), with a bad K, or a plane change inside
    /// a cycle.
    CycleData,
    /// A SINUMERIK standard cycle (CYCLE81 ..., HOLES2, POCKET4 ...) refuses its parameters or
    /// the state it is called in: the cycle's own alarm 61000-61999, whose number the message
    /// gives first (61101 reference plane defined incorrectly, 61102 no spindle direction
    /// programmed, 61103 number of holes is zero ...; docs/SINUMERIK.md "Standard cycles").
    /// Fix: correct the parameter the message names.
    CycleParameter,
    /// G12/G13 circle cutting without an offset number, or with a circle no larger than the
    /// offset (Mitsubishi P170, P233).
    CircleCutting,
    /// Haas G47 text engraving with a bad P, J or E, no text, a character the font lacks, or
    /// outside the X-Y plane.
    Engraving,
    /// A high-speed or smoothing code (G05, G05.1, G08) with a word missing or out of range
    /// (Syntec COR-107), or switched on in exact stop or tapping mode, G61/G63 (Syntec COR-106),
    /// or high-speed mode with inverse time feed, G93 (spec 1.8, restriction 14).
    SmoothingCommand,
    /// A move that would take an axis beyond the machine's travel (the machine file's `min` and
    /// `max`): the control's stored stroke limit 1 (FANUC OT0500/OT0501).
    Overtravel,
    /// G06.2 NURBS interpolation given a curve that cannot be made: an order outside 2-4, knots
    /// that decrease or do not start and end with `order` equal values, a weight outside
    /// 0.001-1000, fewer control points than the order, a first control point away from the
    /// start, or a block without K before the knots are complete (Syntec spec 1.10).
    NurbsDefinition,
    /// Probing: automatic tool length measurement (Syntec G37, G37.1) cannot measure: no Z
    /// (MAR-330), a start not above the measuring position (MAR-333), no H number before
    /// (MAR-334), the signal before the allowed distance (MAR-335) or never (MAR-336), or no tool
    /// setter in the machine file's `[probe]`. As a warning: a G31 that touched none of the
    /// machine file's targets and ran to its end point.
    Probing,
    /// G27 reference position return check: an axis the block names is not at reference point
    /// 1 when the rapid ends (FANUC 0M alarm PS 092), or G27 under cutter compensation.
    ReferenceCheck,
    /// A move into the forbidden zone of the stored stroke check 2 (Syntec G22, spec 1.16), or a
    /// G22 block whose limits do not pair (COR-109).
    StrokeCheck,
    /// A macro statement or expression that cannot be read: an unclosed bracket, `IF` without
    /// GOTO or THEN, `#` without a number. FANUC alarms PS0114/PS0118-like "format error".
    MacroSyntax,
    /// A macro expression with no value: division by zero, SQRT of a negative number, ASIN of
    /// more than 1, a value too large for its address. FANUC alarms PS0112/PS0119.
    MacroArithmetic,
    /// A variable that does not exist on this control or cannot be written (`#0 = 1`, an
    /// unknown system variable). FANUC alarm PS0115/PS0116.
    BadVariable,
    /// GOTO, M99 P or M98 H to a sequence number the program does not have. FANUC alarm
    /// PS0078.
    SequenceNotFound,
    /// M98, M198, G65 or G66 calls a program that is neither in the file nor in the program
    /// directory. FANUC alarm PS0078.
    ProgramNotFound,
    /// A called program number that more than one file of a program directory holds (two files
    /// named for it, or headed by it): vcnc cannot tell which one the control would have in its
    /// memory. Fix: keep one of them in the directory, or renumber one.
    ProgramAmbiguous,
    /// DO and END that do not pair: END without its DO, a loop number outside 1-3, a DO that
    /// never ends. FANUC alarms PS0126/PS0128.
    LoopStructure,
    /// A macro program ran into a limit: too many loop passes or jumps (a program that would
    /// never end), calls nested too deeply (FANUC alarm PS0077), a program too large.
    MacroLimit,
    /// The program raised its own alarm by writing `#3000` (FANUC alarm 3000 + n).
    UserAlarm,
    /// A warning: the interrupt signal an option named (Syntec's C49) came when the control
    /// ignores it: no `M96 P_` in force, inside a subprogram, or in a mode that excludes
    /// interrupts (G41/G42, G12.1, G16, G51, G51.1, G05, G05.1). Fix: name a block where M96 is in force
    /// and none of these modes is on.
    InterruptIgnored,
    /// A warning: the program looks written for another of vcnc's profiles. Its text holds
    /// something that this profile runs otherwise, and that one as written: `M97 P15` with an
    /// N15 in the program (Haas's local subprogram call; elsewhere an M code for the machine),
    /// a system variable this profile does not have (#3026, #5405). Fix: `--profile`, or the
    /// machine file's `profile`.
    WrittenForAnotherProfile,
    /// A warning: lengths written without a decimal point come out under a millimetre read in
    /// least increments (`G0 X10 Y10` goes to 0.010 mm): a program meant in whole units. Fix:
    /// `decimal_less = "whole_units"` under `[profile_overrides.units]` in the machine file, or the
    /// decimal points.
    DecimalLessScale,
    /// A warning: a cutting move while the spindle is stopped (before M03/M04, after M05).
    CuttingWithSpindleStopped,
    /// A warning: a spindle speed above the machine's `max_rpm` (the control clamps it, or
    /// refuses it).
    SpindleSpeedAboveMaximum,
    /// A warning: the program never selects its unit (no G20 or G21), the profile starts in
    /// mm, and the program's comments give sizes in inches (`1/2" END MILL`): written for a
    /// control that starts in inches. Fix: G20 at the program's start.
    UnitNotSelected,
    /// The simulator (`vcnc sim`): a rapid (G0) removes material, the tool crashing into the
    /// stock at rapid rate. Fix: a cutting feed (G01) there, or a clearance plane above the stock.
    RapidIntoStock,
    /// The simulator: the shank or the holder touches the stock. Fix: a longer stickout, a
    /// slimmer holder, or shallower steps.
    HolderCollision,
    /// The simulator: the tool cuts deeper than its flutes (the machine file's
    /// `cutting_length`). Fix: a tool with longer flutes, or more, shallower steps.
    BeyondCuttingLength,
    /// A warning of the simulator: a flat tool that cannot cut at its centre
    /// (`center_cutting = false`) plunges into the stock. Fix: ramp or helix in, or pre-drill.
    PlungeWithoutCenterCutting,
    /// A warning of the simulator: moves it cannot cut (a rotary axis moving or away from 0, a
    /// tool not along Z) are left out of the simulated part.
    NotSimulated,
    /// A warning of the simulator and the plot: the machine file's `[[tool_shapes]]` does not
    /// describe a tool, taken as a flat end mill of its radius offset.
    ToolWithoutShape,
}

impl AlarmCode {
    /// The stable identifier used in JSON output (`snake_case`).
    pub fn id(self) -> &'static str {
        use AlarmCode::*;
        match self {
            UnexpectedCharacter => "unexpected_character",
            MissingValue => "missing_value",
            BadNumber => "bad_number",
            UnclosedComment => "unclosed_comment",
            DuplicateAddress => "duplicate_address",
            DecimalPointNotAllowed => "decimal_point_not_allowed",
            ValueOutOfRange => "value_out_of_range",
            UnknownGCode => "unknown_g_code",
            SameGroupGCodes => "same_group_g_codes",
            NotSupportedYet => "not_supported_yet",
            DialectNotSupported => "dialect_not_supported",
            NotInProduct => "not_in_product",
            KeptAsState => "kept_as_state",
            NoFeedRate => "no_feed_rate",
            ArcWithoutCenter => "arc_without_center",
            ArcEndNotOnCircle => "arc_end_not_on_circle",
            ArcRadiusTooSmall => "arc_radius_too_small",
            ContourDefinition => "contour_definition",
            OffsetNumberOutOfRange => "offset_number_out_of_range",
            WorkOffsetOutOfRange => "work_offset_out_of_range",
            BadDataInput => "bad_data_input",
            AxisNotOnMachine => "axis_not_on_machine",
            FiveAxis => "five_axis",
            WordNotAllowed => "word_not_allowed",
            ReferencePointOutOfRange => "reference_point_out_of_range",
            NoIntermediatePoint => "no_intermediate_point",
            MissingProgramEnd => "missing_program_end",
            BadFeedRate => "bad_feed_rate",
            BadDwell => "bad_dwell",
            ReadError => "read_error",
            CutterCompensation => "cutter_compensation",
            PositionOffset => "position_offset",
            CycleData => "cycle_data",
            CycleParameter => "cycle_parameter",
            CircleCutting => "circle_cutting",
            Engraving => "engraving",
            SmoothingCommand => "smoothing_command",
            Overtravel => "overtravel",
            NurbsDefinition => "nurbs_definition",
            Probing => "probing",
            ReferenceCheck => "reference_check",
            StrokeCheck => "stroke_check",
            MacroSyntax => "macro_syntax",
            MacroArithmetic => "macro_arithmetic",
            BadVariable => "bad_variable",
            SequenceNotFound => "sequence_not_found",
            ProgramNotFound => "program_not_found",
            ProgramAmbiguous => "program_ambiguous",
            LoopStructure => "loop_structure",
            MacroLimit => "macro_limit",
            UserAlarm => "user_alarm",
            InterruptIgnored => "interrupt_ignored",
            WrittenForAnotherProfile => "written_for_another_profile",
            DecimalLessScale => "decimal_less_scale",
            CuttingWithSpindleStopped => "cutting_with_spindle_stopped",
            SpindleSpeedAboveMaximum => "spindle_speed_above_maximum",
            UnitNotSelected => "unit_not_selected",
            RapidIntoStock => "rapid_into_stock",
            HolderCollision => "holder_collision",
            BeyondCuttingLength => "beyond_cutting_length",
            PlungeWithoutCenterCutting => "plunge_without_center_cutting",
            NotSimulated => "not_simulated",
            ToolWithoutShape => "tool_without_shape",
        }
    }

    /// The short code shown to people, `V` and a number: stable across releases.
    pub fn code(self) -> &'static str {
        use AlarmCode::*;
        match self {
            UnexpectedCharacter => "V001",
            MissingValue => "V002",
            BadNumber => "V003",
            UnclosedComment => "V004",
            DuplicateAddress => "V005",
            DecimalPointNotAllowed => "V006",
            ValueOutOfRange => "V007",
            UnknownGCode => "V010",
            SameGroupGCodes => "V011",
            NotSupportedYet => "V020",
            DialectNotSupported => "V021",
            NotInProduct => "V022",
            KeptAsState => "V023",
            NoFeedRate => "V030",
            ArcWithoutCenter => "V031",
            ArcEndNotOnCircle => "V032",
            ArcRadiusTooSmall => "V033",
            ContourDefinition => "V034",
            OffsetNumberOutOfRange => "V040",
            WorkOffsetOutOfRange => "V041",
            BadDataInput => "V042",
            AxisNotOnMachine => "V043",
            FiveAxis => "V047",
            WordNotAllowed => "V044",
            ReferencePointOutOfRange => "V045",
            NoIntermediatePoint => "V046",
            MissingProgramEnd => "V050",
            BadFeedRate => "V051",
            BadDwell => "V052",
            ReadError => "V090",
            CutterCompensation => "V060",
            PositionOffset => "V061",
            CycleData => "V070",
            CycleParameter => "V074",
            CircleCutting => "V071",
            Engraving => "V125",
            SmoothingCommand => "V072",
            Overtravel => "V073",
            NurbsDefinition => "V075",
            Probing => "V076",
            ReferenceCheck => "V077",
            StrokeCheck => "V078",
            MacroSyntax => "V080",
            MacroArithmetic => "V081",
            BadVariable => "V082",
            SequenceNotFound => "V083",
            ProgramNotFound => "V084",
            LoopStructure => "V085",
            MacroLimit => "V086",
            UserAlarm => "V087",
            InterruptIgnored => "V088",
            ProgramAmbiguous => "V089",
            WrittenForAnotherProfile => "V100",
            DecimalLessScale => "V101",
            CuttingWithSpindleStopped => "V102",
            SpindleSpeedAboveMaximum => "V103",
            UnitNotSelected => "V104",
            RapidIntoStock => "V110",
            HolderCollision => "V111",
            BeyondCuttingLength => "V112",
            PlungeWithoutCenterCutting => "V113",
            NotSimulated => "V114",
            ToolWithoutShape => "V115",
        }
    }

    /// A line on how to fix an alarm of this code, for alarms that carry no help of their own
    /// ([`Alarm::help_line`]).
    pub fn help(self) -> &'static str {
        use AlarmCode::*;
        match self {
            UnexpectedCharacter => "remove the character, or put it inside a ( ) comment",
            MissingValue => "give the address its number (`X10.`), or remove the letter",
            BadNumber => "write the number as digits with at most one decimal point (`X-12.5`)",
            UnclosedComment => "close the comment with `)` on the same line",
            DuplicateAddress => "keep one of the two words, or split the block in two",
            DecimalPointNotAllowed => "write this address as a whole number (`H1`, `M3`)",
            ValueOutOfRange => "use a value in the range the message gives",
            UnknownGCode => "check the G code against the control's manual, or choose the profile the program was written for (--profile)",
            SameGroupGCodes => "keep one G code of the group in the block",
            NotSupportedYet => "vcnc cannot run this yet: see docs/DEVIATIONS.md and the issue the message names, if any",
            DialectNotSupported => "this interpreter runs another dialect: vcnc::Pipeline picks the front end a program needs",
            NotInProduct => "vcnc simulates 3-axis milling on one channel: run this part of the program on the control",
            KeptAsState => "the path and its positions are as programmed; the control's own timing of this command may differ",
            NoFeedRate => "program an F word before or in the first G01/G02/G03 block",
            ArcWithoutCenter => "give the arc its radius (R) or its centre (I, J, K)",
            ArcEndNotOnCircle => "check the end point and the centre (I, J, K): they must describe one circle",
            ArcRadiusTooSmall => "make R at least half the distance between the start and the end point",
            ContourDefinition => "check the angles (ANG=) and the chamfer or rounding (CHF=, CHR=, RND=) against the lengths of the elements they join",
            OffsetNumberOutOfRange => "use an offset number the tool table has (max_offset_number of the profile)",
            WorkOffsetOutOfRange => "use a work offset the control has (G54-G59, G54.1 P1 and up to the profile's count)",
            BadDataInput => "check the L and P words of G10 against the profile's table",
            AxisNotOnMachine => "add the axis to the machine file (`[axes.a]` ...) or remove the word",
            FiveAxis => "describe the machine's rotary axes in its [kinematics] table (docs/KINEMATICS.md) and program a direction they reach",
            WordNotAllowed => "remove the word, or move it to a block that reads it",
            ReferencePointOutOfRange => "use a reference point the machine has (G30 P2 to P4 on most controls)",
            NoIntermediatePoint => "run G28 or G30 for this axis before G29",
            MissingProgramEnd => "end the program with M30 (or M02), and a called program with M99",
            BadFeedRate => "program a feed rate above zero",
            BadDwell => "give the dwell a time of zero or more",
            ReadError => "check that the file exists and can be read",
            CutterCompensation => "use a smaller tool radius (D), or change the contour so that the tool fits",
            PositionOffset => "cancel cutter compensation first, and give G45-G48 arcs of 90 or 270 degrees with I, J",
            CycleData => "give the cycle the words it needs (Z, R, Q ...); cancel it with G80 before changing the plane",
            CycleParameter => "correct the cycle's parameter the message names: the parameter lists are in docs/SINUMERIK.md, Standard cycles",
            CircleCutting => "give G12/G13 a D offset smaller than the circle's radius I",
            Engraving => "give G47 P0 with the text as a comment, P32-126 for one character, J and E above zero, in G17",
            SmoothingCommand => "give the smoothing code its words (P, Q, E), and switch it on outside G61/G63/G93",
            Overtravel => "move the program's zero (work offset) or change the travel limits of the machine file",
            NurbsDefinition => "give G06.2 an order P2-P4, one K per control point and `order` K-only blocks after them, knots that never decrease",
            Probing => "select the H number first, start above the measuring position, and describe the tool setter and targets under [probe] in the machine file",
            ReferenceCheck => "cancel compensation (G40, G49) and give G27 the reference point in program coordinates",
            StrokeCheck => "keep the path out of the forbidden zone, or switch the check off with G23",
            MacroSyntax => "check the brackets and keywords of the statement: the macro language is in docs/MACROS.md",
            MacroArithmetic => "check the values of the variables the expression reads (shown under them)",
            BadVariable => "locals are #1-#33, commons #100-#499 and #500-#999; the system variables vcnc has are in docs/MACROS.md",
            SequenceNotFound => "add the block with that N number, or change the jump's target",
            ProgramNotFound => "put the program after M30 in the same file, or pass its directory with --lib DIR",
            ProgramAmbiguous => "keep one file per program number in the directory",
            LoopStructure => "pair every WHILE [..] DOn with an ENDn of the same number (1-3)",
            MacroLimit => "raise the limit (--max-jumps, --main-passes), or end the loop",
            UserAlarm => "the program raised this alarm itself (#3000): see its message",
            InterruptIgnored => "name a block where M96 is in force and no excluding mode (G41/G42, G16 ...) is on",
            WrittenForAnotherProfile => "run it with the profile the warning names (--profile), or set that profile in the machine file",
            DecimalLessScale => "write the lengths with a decimal point, or set decimal_less = \"whole_units\" in the machine file's [profile_overrides.units]",
            CuttingWithSpindleStopped => "start the spindle (M03 or M04 with S) before the first cut",
            SpindleSpeedAboveMaximum => "program S within the machine file's spindle.max_rpm",
            UnitNotSelected => "add G20 (inch) or G21 (mm) at the program's start",
            RapidIntoStock => "cut there with G01, or keep rapids above the stock",
            HolderCollision => "use a longer stickout or a slimmer holder, or cut in shallower steps",
            BeyondCuttingLength => "use a tool with longer flutes, or cut in shallower steps",
            PlungeWithoutCenterCutting => "ramp or helix into the material, or pre-drill, with a tool that cannot cut at its centre",
            NotSimulated => "the simulator cuts with a tool along Z and the rotary axes at 0",
            ToolWithoutShape => "describe the tool under [[tool_shapes]] in the machine file",
        }
    }

    /// Every code, in catalog order (for generated documentation).
    pub const ALL: &'static [AlarmCode] = &[
        AlarmCode::UnexpectedCharacter,
        AlarmCode::MissingValue,
        AlarmCode::BadNumber,
        AlarmCode::UnclosedComment,
        AlarmCode::DuplicateAddress,
        AlarmCode::DecimalPointNotAllowed,
        AlarmCode::ValueOutOfRange,
        AlarmCode::UnknownGCode,
        AlarmCode::SameGroupGCodes,
        AlarmCode::NotSupportedYet,
        AlarmCode::DialectNotSupported,
        AlarmCode::NotInProduct,
        AlarmCode::KeptAsState,
        AlarmCode::NoFeedRate,
        AlarmCode::ArcWithoutCenter,
        AlarmCode::ArcEndNotOnCircle,
        AlarmCode::ArcRadiusTooSmall,
        AlarmCode::ContourDefinition,
        AlarmCode::OffsetNumberOutOfRange,
        AlarmCode::WorkOffsetOutOfRange,
        AlarmCode::BadDataInput,
        AlarmCode::AxisNotOnMachine,
        AlarmCode::FiveAxis,
        AlarmCode::WordNotAllowed,
        AlarmCode::ReferencePointOutOfRange,
        AlarmCode::NoIntermediatePoint,
        AlarmCode::MissingProgramEnd,
        AlarmCode::BadFeedRate,
        AlarmCode::BadDwell,
        AlarmCode::ReadError,
        AlarmCode::CutterCompensation,
        AlarmCode::PositionOffset,
        AlarmCode::CycleData,
        AlarmCode::CircleCutting,
        AlarmCode::Engraving,
        AlarmCode::SmoothingCommand,
        AlarmCode::Overtravel,
        AlarmCode::NurbsDefinition,
        AlarmCode::Probing,
        AlarmCode::ReferenceCheck,
        AlarmCode::StrokeCheck,
        AlarmCode::MacroSyntax,
        AlarmCode::MacroArithmetic,
        AlarmCode::BadVariable,
        AlarmCode::SequenceNotFound,
        AlarmCode::ProgramNotFound,
        AlarmCode::ProgramAmbiguous,
        AlarmCode::LoopStructure,
        AlarmCode::MacroLimit,
        AlarmCode::UserAlarm,
        AlarmCode::InterruptIgnored,
        AlarmCode::WrittenForAnotherProfile,
        AlarmCode::DecimalLessScale,
        AlarmCode::CuttingWithSpindleStopped,
        AlarmCode::SpindleSpeedAboveMaximum,
        AlarmCode::UnitNotSelected,
        AlarmCode::RapidIntoStock,
        AlarmCode::HolderCollision,
        AlarmCode::BeyondCuttingLength,
        AlarmCode::PlungeWithoutCenterCutting,
        AlarmCode::NotSimulated,
        AlarmCode::ToolWithoutShape,
    ];
}

impl fmt::Display for AlarmCode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.code())
    }
}

/// A secondary place an alarm points at (e.g. the call site of a subprogram).
#[derive(Clone, Debug, PartialEq)]
pub struct Label {
    /// Where.
    pub span: Span,
    /// What it has to do with the alarm.
    pub message: String,
}

/// One alarm or warning, with the place that caused it.
#[derive(Clone, Debug, PartialEq)]
pub struct Alarm {
    /// What kind of alarm.
    pub code: AlarmCode,
    /// Stop, or go on.
    pub severity: Severity,
    /// One line, no trailing period.
    pub message: String,
    /// The word (or block) that caused it; `None` only for whole-file problems.
    pub span: Option<Span>,
    /// Other places worth showing.
    pub labels: Vec<Label>,
    /// How to fix it, when there is something useful to say.
    pub help: Option<String>,
}

impl Alarm {
    /// An error alarm at `span`.
    pub fn error(code: AlarmCode, span: Span, message: impl Into<String>) -> Alarm {
        Alarm {
            code,
            severity: Severity::Error,
            message: message.into(),
            span: Some(span),
            labels: Vec::new(),
            help: None,
        }
    }

    /// A warning at `span`.
    pub fn warning(code: AlarmCode, span: Span, message: impl Into<String>) -> Alarm {
        Alarm {
            severity: Severity::Warning,
            ..Alarm::error(code, span, message)
        }
    }

    /// "`what` is not supported yet", pointing at the code, with the issue that will add it.
    pub fn not_supported(span: Span, what: &str, issue: Option<u32>) -> Alarm {
        let alarm = Alarm::error(
            AlarmCode::NotSupportedYet,
            span,
            format!("{what} is not supported yet"),
        );
        match issue {
            Some(n) => alarm.with_help(format!("planned in vcnc issue #{n}")),
            None => alarm,
        }
    }

    /// The same alarm with a help text.
    pub fn with_help(mut self, help: impl Into<String>) -> Alarm {
        self.help = Some(help.into());
        self
    }

    /// The same alarm with one more secondary label.
    pub fn with_label(mut self, span: Span, message: impl Into<String>) -> Alarm {
        self.labels.push(Label {
            span,
            message: message.into(),
        });
        self
    }

    /// How to fix it: the alarm's own help, else its code's ([`AlarmCode::help`]).
    pub fn help_line(&self) -> &str {
        self.help.as_deref().unwrap_or(self.code.help())
    }

    /// True when the run stops here.
    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }
}

impl fmt::Display for Alarm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}[{}]: {}",
            self.severity.as_str(),
            self.code,
            self.message
        )?;
        if let Some(span) = self.span {
            write!(f, " (line {})", span.line)?;
        }
        Ok(())
    }
}

impl std::error::Error for Alarm {}
