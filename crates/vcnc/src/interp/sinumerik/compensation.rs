//! SINUMERIK tool radius compensation (docs/SINUMERIK.md 11; sinumerik-part-b.md 2, seed 002
//! L6949-7986): G40/G41/G42 with the edge's radius ($TC_DP6) and OFFN, NORM/KONT/KONTC/KONTT,
//! G450/G451 and DISC, the smooth approach and retraction (G140-G143, G147-G348, G340/G341,
//! DISR, DISCL, FAD), G460-G462, CDON/CDOF/CDOF2, CUTCONON/CUTCONOF, in the plane of
//! G17/G18/G19.
//!
//! The front end keeps the programmed functions; the kernel's compensator (`interp/comp`, the
//! FANUC compensator's look-ahead stage) makes the tool-centre path under SINUMERIK's rules
//! ([`Rules`]: transition circle, conic or intersection at outer corners, the approach round the
//! start point or on a curve, the extension of a contour's short ends, bottleneck detection). A block's compensation is settled after its tool words and before its motion
//! ([`before_motion`]), and a cancelling block's return onto the programmed point after it
//! ([`after_motion`]).
//!
//! Never: change a rule of the ISO compensation; every SINUMERIK choice is in this file or in
//! the rules it hands the kernel.

use super::gcodes::Motion;
use super::Sinumerik;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::comp::extension::Extension;
use crate::interp::comp::geometry::Side;
use crate::interp::comp::smooth::{self, Clearance, Shape};
use crate::interp::comp::transition::{Approach, OuterCorner, Rules};
use crate::interp::kernel::{Kernel, Origin};
use crate::motion::Feed;
use crate::motion::Plane;
use crate::source::Span;
use crate::syntax::sinumerik::{ExprKind, Value, Word};

/// The compensation functions vcnc runs: groups 7 (G40, G41, G42), 17 (NORM, KONT) and 18
/// (G450, G451).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum RadiusFunction {
    /// G40.
    Off,
    /// G41: the tool left of the contour.
    Left,
    /// G42: the tool right of the contour.
    Right,
    /// NORM or KONT.
    Approach(Approach),
    /// G450 or G451.
    Outer(OuterCorner),
    /// CUTCONON (true) or CUTCONOF.
    Constant(bool),
    /// G147, G247, G347: a smooth approach in this block.
    Smooth(Shape),
    /// G148, G248, G348: a smooth retraction in this block.
    Retreat(Shape),
    /// G341 (true) or G340: the smooth approach's infeed first, or in space.
    SmoothInPlane(bool),
    /// G140-G143: the side the approach and retraction contour lies on.
    SmoothSide(smooth::Direction),
    /// G460, G461, G462: the approach and retraction where the contour's first or last element
    /// meets no neighbour.
    Extension(Extension),
    /// CDON (true), CDOF or CDOF2: bottleneck detection beyond the neighbouring block.
    Bottleneck(bool),
}

/// The smooth approach's words of a block (DISR, DISCL, FAD are non-modal).
#[derive(Clone, Copy, Debug, Default)]
struct SmoothWords {
    shape: Option<Shape>,
    retreat: Option<Shape>,
    distance: Option<f64>,
    /// DISCL, with true for `AC(..)`.
    clearance: Option<(f64, bool)>,
    /// FAD, with `PM` (Some(false)) or `PR` (Some(true)) when written so.
    slow: Option<(f64, Option<bool>)>,
}

impl SmoothWords {
    fn is_empty(&self) -> bool {
        self.shape.is_none()
            && self.retreat.is_none()
            && self.distance.is_none()
            && self.clearance.is_none()
            && self.slow.is_none()
    }
}

/// The blocks without motion in the compensation plane after which the element waiting for
/// its corner ends perpendicular to itself: MD20250 $MC_CUTCOM_MAXNUM_DUMMY_BLOCKS (seed 002
/// L7150-7155 names the machine data, not its value; 3 is vcnc's choice).
const DUMMY_BLOCKS: u32 = 3;

/// What the interference alarm tells on a SINUMERIK (seed 002 L7761 gives 10751).
const ALARM_HELP: &str = "SINUMERIK alarm 10751 (collision danger): a smaller tool, a smaller OFFN or another path; the compensated path would cut into the contour";

/// The compensation's modal state.
#[derive(Clone, Copy, Debug)]
pub(super) struct RadiusCompensation {
    /// G41 (Some(true)), G42 (Some(false)) or G40.
    left: Option<bool>,
    approach: Approach,
    outer: OuterCorner,
    extension: Extension,
    /// CDON in force (CDOF at power-on).
    bottleneck: bool,
    /// DISC: 0 the transition circle, up to 100 flattened towards the intersection.
    disc: u8,
    /// OFFN: the contour offset added to the radius.
    offset: f64,
    /// CUTCONON programmed, and whether the kernel keeps the offset constant now.
    constant: bool,
    kept: bool,
    /// G341 in force (G340 at power-on).
    smooth_in_plane: bool,
    smooth_side: smooth::Direction,
    smooth: SmoothWords,
    /// While compensating: its plane, and the side and radius the kernel has.
    on: Option<(Plane, (Side, f64))>,
}

impl RadiusCompensation {
    /// G41 or G42 is in force.
    pub(super) fn is_selected(&self) -> bool {
        self.left.is_some()
    }
}

impl Default for RadiusCompensation {
    /// The power-on state: G40, NORM, G450, OFFN=0 (group defaults, seed 002 L7176, L7295).
    fn default() -> Self {
        RadiusCompensation {
            left: None,
            approach: Approach::Straight,
            outer: OuterCorner::TransitionCircle,
            // G460 is group 48's power-on member in the G-group table; the text's "initial
            // setting" at G462 (L7701-7703, L7751-7753) is read as G462 being the default
            // element of the extension.
            extension: Extension::None,
            disc: 0,
            bottleneck: false,
            offset: 0.0,
            constant: false,
            kept: false,
            smooth_in_plane: false,
            smooth_side: smooth::Direction::Compensation,
            smooth: SmoothWords::default(),
            on: None,
        }
    }
}

/// A compensation function of the block, taken as it is read.
pub(super) fn select(front: &mut Sinumerik, function: RadiusFunction) {
    let state = &mut front.radius_compensation;
    match function {
        RadiusFunction::Off => state.left = None,
        RadiusFunction::Left => state.left = Some(true),
        RadiusFunction::Right => state.left = Some(false),
        RadiusFunction::Approach(approach) => state.approach = approach,
        RadiusFunction::Outer(outer) => state.outer = outer,
        RadiusFunction::Constant(constant) => state.constant = constant,
        RadiusFunction::Smooth(shape) => state.smooth.shape = Some(shape),
        RadiusFunction::Retreat(shape) => state.smooth.retreat = Some(shape),
        RadiusFunction::SmoothInPlane(in_plane) => state.smooth_in_plane = in_plane,
        RadiusFunction::SmoothSide(direction) => state.smooth_side = direction,
        RadiusFunction::Extension(extension) => state.extension = extension,
        RadiusFunction::Bottleneck(on) => state.bottleneck = on,
    }
}

/// OFFN= and DISC=: the contour offset, and the transition circle's shape.
///
/// # Errors
/// A value that is not a number; DISC above 0, which vcnc does not run.
pub(super) fn word(front: &mut Sinumerik, kernel: &Kernel, word: &Word) -> Result<(), Alarm> {
    // DISCL=AC(..), FAD=PM(..), FAD=PR(..).
    let mut wrapped = None;
    let value = match &word.value {
        Value::Expression(expr) => match &expr.kind {
            ExprKind::Call(name, args) if matches!(&**name, "AC" | "PM" | "PR") => {
                let [Some(arg)] = args.as_slice() else {
                    return Err(Alarm::error(
                        AlarmCode::MacroSyntax,
                        word.span,
                        format!("{name}(..) takes one value"),
                    ));
                };
                wrapped = Some(name.to_string());
                front.value(kernel, arg)?
            }
            _ => front.value(kernel, expr)?,
        },
        Value::Constant(n) => n.value,
        _ => {
            return Err(Alarm::error(
                AlarmCode::MissingValue,
                word.span,
                format!("{} needs a value: {}=5", word.address, word.address),
            ))
        }
    };
    let unit = super::motion::unit(front);
    let smooth = &mut front.radius_compensation.smooth;
    match (&*word.address, wrapped.as_deref()) {
        ("DISR", None) => smooth.distance = Some(value * unit),
        ("DISCL", None) => smooth.clearance = Some((value * unit, false)),
        ("DISCL", Some("AC")) => smooth.clearance = Some((value * unit, true)),
        ("FAD", None) => smooth.slow = Some((value, None)),
        ("FAD", Some("PM")) => smooth.slow = Some((value, Some(false))),
        ("FAD", Some("PR")) => smooth.slow = Some((value, Some(true))),
        (_, Some(wrapper)) => {
            return Err(Alarm::error(
                AlarmCode::WordNotAllowed,
                word.span,
                format!("{} does not take {wrapper}(..)", word.address),
            ))
        }
        ("OFFN", _) => front.radius_compensation.offset = value * unit,
        // DISC is an INT of 0 to 100 (seed 002 L7314-7320); a REAL is rounded as the
        // language assigns it to an INT.
        (_, _) if (-0.5..100.5).contains(&value) => {
            front.radius_compensation.disc = value.round() as u8;
        }
        (_, _) => {
            return Err(Alarm::error(
                AlarmCode::ValueOutOfRange,
                word.span,
                format!(
                "DISC={value} is out of range: 0 (the transition circle) to 100 (the intersection)"
            ),
            ))
        }
    }
    Ok(())
}

/// The side and radius of G41 (`left`) or G42 now: the edge's radius plus OFFN, a negative
/// total and a mirrored plane each swapping the side (seed 002 L7097).
fn setting(front: &Sinumerik, kernel: &Kernel, left: bool, plane: Plane) -> (Side, f64) {
    let radius = front.edge().map_or(0.0, |edge| edge.radius) + front.radius_compensation.offset;
    let side = Side::of(left, radius);
    let (a, b, _) = plane.axes();
    let side = match (kernel.state().frames.reverses_plane((a, b)), side) {
        (false, side) => side,
        (true, Side::Left) => Side::Right,
        (true, Side::Right) => Side::Left,
    };
    (side, radius.abs())
}

/// The rules the kernel compensates by.
fn rules(front: &Sinumerik, kernel: &Kernel, plane: Plane) -> Rules {
    let (a, b, _) = plane.axes();
    let axes = &kernel.state().setup.machine().axes;
    let rapid = [a, b]
        .iter()
        .filter_map(|&i| axes[i].as_ref().map(|axis| axis.rapid))
        .fold(f64::INFINITY, f64::min);
    let state = &front.radius_compensation;
    Rules {
        outer: match (state.outer, state.disc) {
            (OuterCorner::TransitionCircle, disc @ 1..) => OuterCorner::Conic(disc),
            (outer, _) => outer,
        },
        approach: front.radius_compensation.approach,
        extension: front.radius_compensation.extension,
        bottleneck: front.radius_compensation.bottleneck,
        alarm_help: ALARM_HELP,
        rapid_arc_feed: if rapid.is_finite() { rapid } else { 10_000.0 },
    }
}

/// Before the block's motion (after its D): compensation starts, changes or is cancelled.
///
/// # Errors
/// G41/G42 starting in a circle block; a change of plane while compensating.
#[inline]
pub(super) fn before_motion(
    front: &mut Sinumerik,
    kernel: &mut Kernel,
    moves: bool,
    span: Span,
) -> Result<(), Alarm> {
    // The common block: G40 in force and left alone, no approach or retraction words.
    let state = &front.radius_compensation;
    if state.left.is_none() && state.on.is_none() && !state.kept && state.smooth.is_empty() {
        return Ok(());
    }
    switch_or_keep(front, kernel, moves, span)
}

/// [`before_motion`] for a block with compensation in force, selected or deselected, or with
/// smooth approach words.
// Out of line: the check before it is inlined into every block's step.
#[inline(never)]
fn switch_or_keep(
    front: &mut Sinumerik,
    kernel: &mut Kernel,
    moves: bool,
    span: Span,
) -> Result<(), Alarm> {
    let state = front.radius_compensation;
    let plane = front.modal.plane;
    let (a, b, _) = plane.axes();
    if state.left.is_some()
        && kernel
            .state()
            .frames
            .programmable()
            .is_some_and(|frame| !frame.keeps_plane((a, b)))
    {
        return Err(Alarm::error(
            AlarmCode::NotSupportedYet,
            span,
            "G41 and G42 in a frame that tilts or unevenly scales the plane are not run yet",
        )
        .with_help("vcnc compensates in a machine plane, under CUT2D and CUT2DF alike: turn the frame about the plane's normal only"));
    }
    if matches!(state.approach, Approach::Curve(_))
        && moves
        && state.left.is_some() != state.on.is_some()
        && front.modal.motion != Motion::Line
    {
        // The control replaces the G1 block by its polynomial (seed 002 L7207-7208).
        return Err(Alarm::error(
            AlarmCode::CutterCompensation,
            span,
            "KONTC and KONTT approach and retract only in a G1 block",
        )
        .with_help("write G1 in the block that switches G41, G42 or G40"));
    }
    match (state.left, state.on) {
        (None, None) => {}
        (None, Some((plane, _))) => {
            kernel.cancel_compensation();
            if let Some(retraction) = smooth_retraction(front, kernel, plane, moves, span)? {
                kernel.approach_smoothly(retraction);
            }
        }
        (Some(left), None) => {
            let rapid_or_line = matches!(front.modal.motion, Motion::Rapid | Motion::Line);
            if moves && !rapid_or_line {
                return Err(Alarm::error(
                    AlarmCode::CutterCompensation,
                    span,
                    "G41 and G42 start in a G0 or G1 block",
                )
                .with_help("switch the compensation on in the straight approach block before the contour (seed 002 L6968)"));
            }
            // Turning and grinding tools (types 400-599) have a cutting edge position
            // (seed 002 L7988-8032): their compensation is a lathe's.
            if let Some(edge) = front.edge().filter(|e| (400..600).contains(&e.tool_type)) {
                return Err(Alarm::error(
                    AlarmCode::NotInProduct,
                    span,
                    format!(
                        "{} with tool type {} belongs to turning (the nose radius compensation of a turning tool), which vcnc does not simulate",
                        if left { "G41" } else { "G42" },
                        edge.tool_type
                    ),
                ));
            }
            let setting = setting(front, kernel, left, plane);
            let rules = rules(front, kernel, plane);
            kernel.start_compensation(setting, plane, left, rules, DUMMY_BLOCKS);
            front.radius_compensation.on = Some((plane, setting));
            if let Some(approach) = smooth_approach(front, kernel, plane, span)? {
                kernel.approach_smoothly(approach);
            }
        }
        (Some(left), Some((on_plane, old))) => {
            if plane != on_plane {
                return Err(Alarm::error(
                    AlarmCode::CutterCompensation,
                    span,
                    "the working plane cannot change while G41 or G42 is on",
                )
                .with_help("cancel the compensation with G40 before G17, G18 or G19"));
            }
            let setting = setting(front, kernel, left, plane);
            if setting != old {
                kernel.change_compensation(setting, left);
                front.radius_compensation.on = Some((plane, setting));
            }
            let rules = rules(front, kernel, plane);
            kernel.set_compensation_rules(rules);
        }
    }
    let state = &mut front.radius_compensation;
    let words = std::mem::take(&mut state.smooth);
    if let Some(shape) = words.shape {
        // Still programmed: the block did not start the compensation.
        let name = match shape {
            Shape::Line => "G147",
            Shape::QuarterCircle => "G247",
            Shape::HalfCircle => "G347",
        };
        if !matches!((state.left, state.on), (Some(_), Some(_))) || moves {
            return Err(Alarm::error(
                AlarmCode::NotSupportedYet,
                span,
                format!("{name} without G41 or G42 starting in its block is not run yet"),
            )
            .with_help(
                "start the compensation in the block of the smooth approach: G41 G247 ...",
            ));
        }
    }
    if let Some(shape) = words.retreat {
        // Still programmed: the block did not end the compensation.
        return Err(Alarm::error(
            AlarmCode::NotSupportedYet,
            span,
            format!(
                "{} without G40 in its block is not run yet",
                retreat_name(shape)
            ),
        )
        .with_help("end the compensation in the block of the smooth retraction: G40 G248 ..."));
    }
    let constant = state.constant && state.on.is_some();
    if constant != state.kept {
        state.kept = constant;
        kernel.keep_compensation_constant(constant)?;
    }
    Ok(())
}

fn retreat_name(shape: Shape) -> &'static str {
    match shape {
        Shape::Line => "G148",
        Shape::QuarterCircle => "G248",
        Shape::HalfCircle => "G348",
    }
}

/// The smooth approach the block programs with the compensation it starts (SAR, seed 002
/// L7398-7672), its words taken; None without G147, G247 or G347.
///
/// # Errors
/// G247 or G347 without DISR; FAD under G93.
fn smooth_approach(
    front: &mut Sinumerik,
    kernel: &Kernel,
    plane: Plane,
    span: Span,
) -> Result<Option<smooth::Approach>, Alarm> {
    let state = &mut front.radius_compensation;
    let words = std::mem::take(&mut state.smooth);
    let Some(shape) = words.shape else {
        return Ok(None);
    };
    smooth_moves(front, kernel, plane, span, (shape, words)).map(Some)
}

/// The smooth retraction the block programs with the G40 it ends the compensation with (SAR,
/// seed 002 L7551-7646), its words taken; None without G148, G248 or G348.
///
/// # Errors
/// G248 or G348 without DISR; FAD under G93; a retraction block without axes (the manual ends
/// it at P2, not run).
fn smooth_retraction(
    front: &mut Sinumerik,
    kernel: &Kernel,
    plane: Plane,
    moves: bool,
    span: Span,
) -> Result<Option<smooth::Approach>, Alarm> {
    let state = &mut front.radius_compensation;
    let Some(shape) = state.smooth.retreat.take() else {
        return Ok(None);
    };
    let words = std::mem::take(&mut state.smooth);
    if !moves {
        return Err(Alarm::error(
            AlarmCode::NotSupportedYet,
            span,
            format!(
                "{} in a block without axes is not run yet",
                retreat_name(shape)
            ),
        )
        .with_help("program the retraction's end point P0 in the block (seed 002 L7551-7619)"));
    }
    smooth_moves(front, kernel, plane, span, (shape, words)).map(Some)
}

/// The moves of an approach or retraction of `shape` by the block's SAR words.
///
/// # Errors
/// A circle without DISR; FAD under G93.
fn smooth_moves(
    front: &Sinumerik,
    kernel: &Kernel,
    plane: Plane,
    span: Span,
    (shape, words): (Shape, SmoothWords),
) -> Result<smooth::Approach, Alarm> {
    let distance = match (words.distance, shape) {
        (Some(d), _) => d,
        (None, Shape::Line) => 0.0,
        (None, _) => {
            return Err(Alarm::error(
                AlarmCode::MissingValue,
                span,
                "an approach on a circle needs its radius: DISR=",
            )
            .with_help("DISR is the radius of the tool centre's path (seed 002 L7526-7538)"))
        }
    };
    let (_, _, normal) = plane.axes();
    let clearance = match words.clearance {
        None => Clearance::Above(0.0),
        Some((d, false)) => Clearance::Above(d),
        // The work system's position along the normal, in machine coordinates (the frames'
        // translation; the plane is never tilted here).
        Some((z, true)) => {
            Clearance::At(z + kernel.position().0[normal] - kernel.program_position()[normal])
        }
    };
    let rpm = kernel.state().spindle.speed();
    let per_revolution = |per_revolution: f64| Feed::PerRevolution {
        per_revolution,
        rpm: (rpm > 0.0).then_some(rpm),
    };
    let slow = match words.slow {
        None => None,
        Some((f, Some(false))) => Some(Feed::PerMinute(f)),
        Some((f, Some(true))) => Some(per_revolution(f)),
        Some((f, None)) => Some(match front.modal.feed_type {
            super::gcodes::FeedType::PerMinute => Feed::PerMinute(f),
            super::gcodes::FeedType::PerRevolution => per_revolution(f),
            super::gcodes::FeedType::InverseTime => {
                return Err(Alarm::error(
                    AlarmCode::NotSupportedYet,
                    span,
                    "FAD under G93 is not run yet: write FAD=PM(..)",
                ))
            }
        }),
    };
    Ok(smooth::Approach {
        shape,
        direction: front.radius_compensation.smooth_side,
        in_plane: front.radius_compensation.smooth_in_plane,
        distance,
        clearance,
        slow,
        feed: kernel.cutting_feed(Origin::at(span))?,
        per_axis: kernel.state().setup.profile().motion.rapid_path
            == crate::profile::RapidPath::PerAxis,
    })
}

/// After the block's motion: a G40 block ends compensation, the tool centre going onto the
/// programmed point if the block itself did not move in the plane.
///
/// # Errors
/// Interference where the last element ends; a line without a feed.
#[inline]
pub(super) fn after_motion(
    front: &mut Sinumerik,
    kernel: &mut Kernel,
    origin: Origin,
) -> Result<(), Alarm> {
    if front.radius_compensation.left.is_some() || front.radius_compensation.on.is_none() {
        return Ok(());
    }
    end_compensation(front, kernel, origin)
}

/// [`after_motion`] in the block that deselected the compensation.
#[inline(never)]
fn end_compensation(
    front: &mut Sinumerik,
    kernel: &mut Kernel,
    origin: Origin,
) -> Result<(), Alarm> {
    front.radius_compensation.on = None;
    kernel.end_compensation(front.modal.motion == Motion::Rapid, origin)
}
