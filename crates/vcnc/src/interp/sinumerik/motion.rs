//! A block's motion: its end point from the axis words, AC/IC, G90/G91, polar words and `ANG=`
//! (docs/SINUMERIK.md 6), its path (G0, G1, G2/G3 with I J K, CR=, AR=, TURN=, CT, CIP), the
//! chamfers and roundings between blocks (`contour.rs`), and the moves the kernel makes of it.
//!
//! The programmed position p moves when a block is read; the machine follows when the kernel
//! moves. A block held for the corner at its end is moved when the next block arrives
//! ([`Contour`]): the caller runs [`prepare`], then [`Prepared::release_held`] (the held
//! block's moves), then the block's own events, then [`Prepared::finish`].
//!
//! Never: move an axis the block does not move, except the geometry axes under a rotation
//! (docs/SINUMERIK.md 6.4 rule 3).

use super::arcs::{self, Tangential};
use super::block::{AxisValue, Words};
use super::contour::{AngleStep, CornerKind, CornerSpec, Cut, LineBlock};
use super::gcodes::{Motion, OneBlock};
use super::involute;
use super::polar::{PolarBlock, PolarMove, PolarValue};
use super::Sinumerik;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::comp::geometry::{Element, EPSILON, V2};
use crate::interp::kernel::{Kernel, Origin};
use crate::interp::modal::DistanceMode;
use crate::machine::{WorkOffsetId, AXES};
use crate::motion::{ArcDirection, Plane, SpindleState};
use crate::source::Span;

/// What the contour state machine keeps of a block: where it goes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Tag {
    origin: Origin,
    /// The work position the block ends at, every axis it moves.
    target: [Option<f64>; AXES],
    rapid: bool,
    turns: u32,
}

/// The path's direction in the plane at the last block's end (CT's tangent).
#[derive(Clone, Copy, Debug)]
pub(super) enum Tangent {
    /// The direction at the end of this element, worked out when CT asks (most blocks are
    /// never followed by CT).
    EndOf(Element),
    Direction(V2),
}

impl Tangent {
    pub(super) fn direction(self) -> V2 {
        match self {
            Tangent::EndOf(element) => element.end_tangent(),
            Tangent::Direction(direction) => direction,
        }
    }
}

/// A plain block's move ([`prepare_plain`]), made by [`Direct::make`].
pub(super) struct Direct(Tag, Option<Arc>);

impl Direct {
    /// Moves the block.
    pub(super) fn make(&self, front: &Sinumerik, kernel: &mut Kernel) -> Result<(), Alarm> {
        direct(front, kernel, &self.0, self.1)
    }
}

/// A block's motion, prepared.
pub(super) enum Prepared {
    /// Nothing moves.
    None,
    /// Nothing moves yet: the first block of a two-line ANG= definition waits for the second.
    Waiting,
    /// Cuts of the contour: the held block's first (`held` of them), then this block's.
    Cuts { cuts: Vec<Cut<Tag>>, held: usize },
    /// A move made directly (no corner to wait for).
    Direct(Tag, Option<Arc>),
    /// A circle in no plane of G17/G18/G19 (CIP): straight pieces along it.
    Chords(Tag, Vec<[f64; 3]>),
    /// A thread (G33, G331, G332): a line at `lead` mm per spindle revolution along the path,
    /// the spindle turning as `spindle` says first.
    Thread(Tag, f64, Option<SpindleState>),
}

/// The arc of a direct move: centre (plane coordinates) and direction, in `plane`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Arc {
    centre: V2,
    direction: ArcDirection,
    plane: Plane,
}

impl Arc {
    /// The arc from `start` to `end`, and the contour's element of it.
    fn with_element(self, start: V2, end: V2) -> (Arc, Element) {
        let element = Element::Arc {
            start,
            end,
            center: self.centre,
            ccw: self.direction == ArcDirection::CounterClockwise,
        };
        (self, element)
    }
}

/// What an arc's centre comes from: I J K, CR=, AR=, and whether AP= or RP= make it polar.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct ArcWords {
    pub(super) centre: [Option<AxisValue>; 3],
    pub(super) radius: Option<(f64, Span)>,
    pub(super) opening: Option<(f64, Span)>,
    pub(super) polar: bool,
}

impl Words<'_> {
    /// The block's words that make an arc.
    fn arc_words(&self) -> ArcWords {
        ArcWords {
            centre: self.centre,
            radius: self.radius,
            opening: self.opening,
            polar: self.ap.is_some() || self.rp.is_some(),
        }
    }
}

/// The direction of an element's arc.
fn direction(ccw: bool) -> ArcDirection {
    if ccw {
        ArcDirection::CounterClockwise
    } else {
        ArcDirection::Clockwise
    }
}

/// The factor of lengths: 25.4 under G70/G700.
pub(super) fn unit(front: &Sinumerik) -> f64 {
    if front.modal.inch {
        25.4
    } else {
        1.0
    }
}

fn in_plane(plane: Plane, point: &[f64; AXES]) -> V2 {
    let (a, b, _) = plane.axes();
    V2::new(point[a], point[b])
}

fn distance_mode(front: &Sinumerik) -> DistanceMode {
    if front.modal.absolute {
        DistanceMode::Absolute
    } else {
        DistanceMode::Incremental
    }
}

/// The block's end point in the work system, per axis (None: not programmed).
fn end_point(front: &Sinumerik, axes: &[Option<AxisValue>; AXES]) -> [Option<f64>; AXES] {
    let unit = unit(front);
    std::array::from_fn(|i| {
        let v = axes[i]?;
        let scale = front.axes.scale(i, unit);
        Some(if v.absolute.unwrap_or(front.modal.absolute) {
            v.value * scale
        } else {
            front.programmed[i] + v.value * scale
        })
    })
}

/// A polar word's value as the polar module reads it.
fn polar_value(value: Option<AxisValue>, scale: f64) -> Option<PolarValue> {
    let v = value?;
    Some(match v.absolute {
        None => PolarValue::Plain(v.value * scale),
        Some(true) => PolarValue::Absolute(v.value * scale),
        Some(false) => PolarValue::Incremental(v.value * scale),
    })
}

/// Prepares the block's motion: its end point and path, p moved to its end, the contour's
/// corners.
pub(super) fn prepare(
    front: &mut Sinumerik,
    kernel: &Kernel,
    words: &Words<'_>,
    origin: Origin,
) -> Result<Prepared, Alarm> {
    let plane = front.modal.plane;
    let (a, b, _) = plane.axes();
    let unit = unit(front);
    // The corner before this block is cut at this block's FRC, or the FRCM in force (the
    // technology of the block after the corner: PGsl 9.15, ex. B-45).
    if let Some((frcm, _)) = words.frcm {
        front.corner_feed_modal = (frcm > 0.0).then_some(frcm * unit);
    }
    front.corner_feed = words
        .frc
        .map(|(f, _)| f * unit)
        .filter(|f| *f > 0.0)
        .or(front.corner_feed_modal);
    let mut target = end_point(front, &words.axes);
    let motion = front.modal.motion;
    let arc = matches!(motion, Motion::Clockwise | Motion::CounterClockwise);
    // Polar end points (AP=, RP=) in the plane.
    if words.ap.is_some() || words.rp.is_some() {
        if target[a].is_some() || target[b].is_some() {
            return Err(Alarm::error(
                AlarmCode::WordNotAllowed,
                origin.span,
                "a block with AP= or RP= takes no axis of the plane",
            )
            .with_help(
                "give the end point either by its polar angle and radius or by the plane's axes",
            ));
        }
        let start = [
            front.programmed[0],
            front.programmed[1],
            front.programmed[2],
        ];
        let kind = if arc {
            PolarMove::Circle
        } else {
            PolarMove::Line
        };
        let block = PolarBlock {
            plane,
            start,
            angle: polar_value(words.ap, 1.0),
            radius: polar_value(words.rp, unit),
            distance: distance_mode(front),
            motion: kind,
            span: origin.span,
        };
        let end = front.polar.end_point(&block)?;
        target[a] = Some(end.x);
        target[b] = Some(end.y);
    }
    let start = in_plane(plane, &front.programmed);
    // ANG= lines (one or two blocks).
    let corner = corner_spec(words)?;
    if words.ang.is_some() || front.angle_lines.is_open() {
        if !matches!(motion, Motion::Rapid | Motion::Line) {
            return Err(Alarm::error(
                AlarmCode::ContourDefinition,
                origin.span,
                "ANG= defines straight lines: it takes G0 or G1",
            ));
        }
        let tag = tag(target, origin, motion == Motion::Rapid, 0);
        let step = front.angle_lines.block(LineBlock {
            start,
            written: (target[a], target[b]),
            angle: words.ang.map(|(v, _)| v),
            tag,
            corner,
            span: origin.span,
        })?;
        let lines = match step {
            AngleStep::Held => {
                advance(front, &target);
                return Ok(Prepared::Waiting);
            }
            AngleStep::Lines(lines) => lines,
        };
        // The lines' ends are where the block goes.
        if let Some((last, _, _)) = lines.last() {
            target[a] = Some(last.end().x);
            target[b] = Some(last.end().y);
        }
        let mut cuts = Vec::new();
        let mut held = None;
        for (element, mut tag, corner) in lines {
            tag.target[a] = Some(element.end().x);
            tag.target[b] = Some(element.end().y);
            let before = front.contour.is_holding();
            let new = front.contour.push(element, tag, corner)?;
            if before && held.is_none() {
                held = Some(new.iter().filter(|c| !is_of(c, origin)).count());
            }
            cuts.extend(new);
        }
        advance(front, &target);
        return Ok(Prepared::Cuts {
            held: held.unwrap_or(0),
            cuts,
        });
    }
    let moves = target.iter().any(Option::is_some);
    let has_arc_data = words.centre.iter().any(Option::is_some)
        || words.radius.is_some()
        || words.opening.is_some();
    let cip_data = motion == Motion::ThroughPoint && words.via.iter().any(Option::is_some);
    let involute_data = matches!(motion, Motion::Involute { .. }) && words.opening.is_some();
    if !(moves || cip_data || involute_data || arc && has_arc_data) {
        return Ok(Prepared::None);
    }
    // With a rotation in the frame, every geometry axis goes to its programmed value
    // (docs/SINUMERIK.md 6.4 rule 3).
    if front.frame.has_rotation() {
        for (t, p) in target.iter_mut().zip(front.programmed).take(3) {
            t.get_or_insert(p);
        }
    }
    let turns = match words.turn {
        Some((turn, span)) if arc => arcs::extra_turns(turn, span)?,
        Some((_, span)) => {
            return Err(Alarm::error(
                AlarmCode::WordNotAllowed,
                span,
                "TURN= makes a helix of G2 or G3",
            ))
        }
        None => 0,
    };
    let rapid = motion == Motion::Rapid;
    let element;
    let mut direct_arc = None;
    match motion {
        Motion::Rapid | Motion::Line | Motion::Clockwise | Motion::CounterClockwise => {
            let (path, arc) = line_or_arc(front, &words.arc_words(), &mut target, origin)?;
            element = Some(path);
            direct_arc = arc;
        }
        Motion::Tangential => {
            let end = V2::new(target[a].unwrap_or(start.x), target[b].unwrap_or(start.y));
            let tangent = front.tangent.map(Tangent::direction).unwrap_or_default();
            match arcs::tangential_arc(start, end, tangent, origin.span)? {
                Tangential::Line => element = Some(Element::Line { start, end }),
                Tangential::Arc { centre, direction } => {
                    let (arc, arc_element) = Arc {
                        centre,
                        direction,
                        plane,
                    }
                    .with_element(start, end);
                    element = Some(arc_element);
                    direct_arc = Some(arc);
                }
            }
        }
        Motion::ThroughPoint
        | Motion::Thread
        | Motion::VariableThread { .. }
        | Motion::Tap { .. }
        | Motion::Involute { .. } => {
            // These paths are moved straight to the kernel, past the contour's corners.
            if let Some(span) = corner
                .map(|c| c.span)
                .or(front.rounding_modal.then_some(origin.span))
            {
                return Err(Alarm::error(
                    AlarmCode::NotSupportedYet,
                    span,
                    "a chamfer or rounding (CHF, CHR, RND, RNDM) at the end of a CIP, involute or thread block is not run yet",
                )
                .with_help("end the block without it, or make the corner on a G1, G2 or G3 block"));
            }
            return match motion {
                Motion::ThroughPoint => through_point(front, kernel, words, target, origin),
                Motion::Involute { ccw } => involute(front, words, target, ccw, origin),
                _ => thread(front, words, target, origin),
            };
        }
    }
    let element = element.expect("every motion above makes an element");
    let tag = tag(target, origin, rapid, turns);
    update_tangent(front, &element, &target, plane);
    advance(front, &target);
    if corner.is_none() && !front.contour.is_holding() && !front.rounding_modal {
        return Ok(Prepared::Direct(tag, direct_arc));
    }
    let held = front.contour.is_holding();
    let cuts = front.contour.push(element, tag, corner)?;
    let held = if held {
        cuts.iter().filter(|c| !is_of(c, origin)).count()
    } else {
        0
    };
    Ok(Prepared::Cuts { cuts, held })
}

/// Prepares a plain block's motion (`plain_block.rs`): G0, G1, G2 or G3 in force, axis words,
/// an arc's I J K or CR=, and no corner held, pending or programmed: what [`prepare`] does with
/// such a block, without the words that are not there.
pub(super) fn prepare_plain(
    front: &mut Sinumerik,
    axes: &[Option<AxisValue>; AXES],
    arc_words: &ArcWords,
    origin: Origin,
) -> Result<Option<Direct>, Alarm> {
    front.corner_feed = front.corner_feed_modal;
    let mut target = end_point(front, axes);
    let motion = front.modal.motion;
    let arc = matches!(motion, Motion::Clockwise | Motion::CounterClockwise);
    let has_arc_data = arc_words.centre.iter().any(Option::is_some) || arc_words.radius.is_some();
    if !(target.iter().any(Option::is_some) || arc && has_arc_data) {
        return Ok(None);
    }
    if front.frame.has_rotation() {
        for (t, p) in target.iter_mut().zip(front.programmed).take(3) {
            t.get_or_insert(p);
        }
    }
    let (element, direct_arc) = line_or_arc(front, arc_words, &mut target, origin)?;
    let tag = tag(target, origin, motion == Motion::Rapid, 0);
    update_tangent(front, &element, &target, front.modal.plane);
    advance(front, &target);
    Ok(Some(Direct(tag, direct_arc)))
}

/// The path of G0, G1, G2 or G3 (the motion in force) from p to `target`, whose plane's axes an
/// arc sets to its end.
fn line_or_arc(
    front: &Sinumerik,
    arc_words: &ArcWords,
    target: &mut [Option<f64>; AXES],
    origin: Origin,
) -> Result<(Element, Option<Arc>), Alarm> {
    let plane = front.modal.plane;
    let (a, b, _) = plane.axes();
    let start = in_plane(plane, &front.programmed);
    let direction = match front.modal.motion {
        Motion::Clockwise => ArcDirection::Clockwise,
        Motion::CounterClockwise => ArcDirection::CounterClockwise,
        _ => {
            let end = V2::new(target[a].unwrap_or(start.x), target[b].unwrap_or(start.y));
            return Ok((Element::Line { start, end }, None));
        }
    };
    let (centre, end) = arc_geometry(front, arc_words, target, direction, origin)?;
    target[a] = Some(end.x);
    target[b] = Some(end.y);
    let (arc, element) = Arc {
        centre,
        direction,
        plane,
    }
    .with_element(start, end);
    Ok((element, Some(arc)))
}

/// True when `cut` is the block of `origin` (not the held one, not a corner).
fn is_of(cut: &Cut<Tag>, origin: Origin) -> bool {
    matches!(cut, Cut::Block { tag, .. } if tag.origin == origin)
}

fn tag(target: [Option<f64>; AXES], origin: Origin, rapid: bool, turns: u32) -> Tag {
    Tag {
        origin,
        target,
        rapid,
        turns,
    }
}

/// p of the axes the block moves becomes their end.
fn advance(front: &mut Sinumerik, target: &[Option<f64>; AXES]) {
    for (p, t) in front.programmed.iter_mut().zip(target) {
        if let Some(t) = t {
            *p = *t;
        }
    }
}

/// The direction the path leaves the block's end in the plane: what CT is tangent to.
fn update_tangent(
    front: &mut Sinumerik,
    element: &Element,
    target: &[Option<f64>; AXES],
    plane: Plane,
) {
    let (a, b, _) = plane.axes();
    if target[a].is_none() && target[b].is_none() && matches!(element, Element::Line { .. }) {
        return;
    }
    // The element is kept when its end has a direction: a line at least EPSILON long in the
    // plane (`V2::unit`), told without measuring it where the sum of its legs decides (the
    // length lies between that sum and the sum over the square root of 2; NaN measures).
    let has_direction = match *element {
        Element::Line { start, end } => {
            let legs = (end.x - start.x).abs() + (end.y - start.y).abs();
            if (EPSILON * std::f64::consts::SQRT_2..1e300).contains(&legs) {
                true
            } else if legs < EPSILON {
                false
            } else {
                nonzero(element.end_tangent())
            }
        }
        Element::Arc { .. } => nonzero(element.end_tangent()),
    };
    if has_direction {
        front.tangent = Some(Tangent::EndOf(*element));
    }
}

/// A unit vector or zero (or NaN): true for the unit vector.
fn nonzero(v: V2) -> bool {
    v.x.abs() + v.y.abs() > 0.0
}

/// The chamfer or rounding a block programs at its end.
fn corner_spec(words: &Words<'_>) -> Result<Option<CornerSpec>, Alarm> {
    let specs = [
        (words.rnd, CornerKind::Round),
        (words.chf, CornerKind::Chamfer),
        (words.chr, CornerKind::ChamferLeg),
    ];
    let mut found = None;
    for (word, kind) in specs {
        if let Some((size, span)) = word {
            if found.is_some() {
                return Err(Alarm::error(
                    AlarmCode::ContourDefinition,
                    span,
                    "a block takes one chamfer or rounding at its end",
                ));
            }
            found = Some(CornerSpec { kind, size, span });
        }
    }
    Ok(found)
}

/// The centre and end (plane coordinates) of G2/G3: with I J K (incremental from the start
/// unless `=AC(..)`), CR=, or AR= with the end or the centre; a polar arc turns about the pole.
fn arc_geometry(
    front: &Sinumerik,
    words: &ArcWords,
    target: &[Option<f64>; AXES],
    direction: ArcDirection,
    origin: super::Origin,
) -> Result<(V2, V2), Alarm> {
    let plane = front.modal.plane;
    let (a, b, _) = plane.axes();
    let start = in_plane(plane, &front.programmed);
    let unit = unit(front);
    let centre_of = |axis: usize, start: f64| -> Option<f64> {
        let v = words.centre[axis]?;
        Some(if v.absolute == Some(true) {
            v.value * unit
        } else {
            start + v.value * unit
        })
    };
    let (ca, cb) = (centre_of(a, start.x), centre_of(b, start.y));
    let tolerance = front.arc_tolerance;
    let end_written = target[a].is_some() || target[b].is_some();
    let end = V2::new(target[a].unwrap_or(start.x), target[b].unwrap_or(start.y));
    // A polar arc: the pole is its centre (PGsl 9.6.5).
    if words.polar {
        return Ok((front.polar.pole_in(plane), end));
    }
    let centre_given = ca.is_some() || cb.is_some();
    let centre = V2::new(ca.unwrap_or(start.x), cb.unwrap_or(start.y));
    match (words.radius, words.opening, centre_given) {
        (Some((radius, span)), None, false) => Ok((
            arcs::centre_from_radius(start, end, radius * unit, direction, tolerance, span)?,
            end,
        )),
        (None, Some((opening, span)), false) if end_written => Ok((
            arcs::centre_from_opening(start, end, opening, direction, span)?,
            end,
        )),
        (None, Some((opening, span)), true) if !end_written => Ok((
            centre,
            arcs::end_from_opening(start, centre, opening, direction, span)?,
        )),
        (None, None, true) => Ok((centre, end)),
        (Some((_, span)), _, _) | (_, Some((_, span)), _) => Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            span,
            "an arc takes its centre (I J K), its radius (CR=) or its opening (AR=) with the end or the centre, one of these",
        )),
        _ => Err(Alarm::error(
            AlarmCode::ArcWithoutCenter,
            origin.span,
            "G2/G3 without a centre (I J K), a radius (CR=) or an opening (AR=)",
        )
        .with_help("give the centre with I, J, K (incremental from the start) or the radius with CR=")),
    }
}

/// CIP: the circle through the intermediate point I1 J1 K1 (absolute unless `=IC(..)`, or under
/// G91) to the end. In a plane of G17/G18/G19 it is an ordinary arc; inclined, straight pieces
/// along it within a micrometre.
fn through_point(
    front: &mut Sinumerik,
    kernel: &Kernel,
    words: &Words<'_>,
    target: [Option<f64>; AXES],
    origin: Origin,
) -> Result<Prepared, Alarm> {
    let unit = unit(front);
    let p = front.programmed;
    let via: [f64; 3] = std::array::from_fn(|i| match words.via[i] {
        Some(v) if v.absolute.unwrap_or(front.modal.absolute) => v.value * unit,
        Some(v) => p[i] + v.value * unit,
        None => p[i],
    });
    let start = [p[0], p[1], p[2]];
    let end: [f64; 3] = std::array::from_fn(|i| target[i].unwrap_or(p[i]));
    let circle = arcs::circle_through(start, via, end, origin.span)?;
    let mut full = target;
    for (i, t) in full.iter_mut().enumerate().take(3) {
        *t = Some(end[i]);
    }
    let tag = tag(full, origin, false, 0);
    advance(front, &full);
    if let Some((plane, direction)) = circle.machine_plane() {
        let (a, b, _) = plane.axes();
        if kernel.state().frames.affine_frames_keep_plane((a, b)) {
            let (arc, element) = Arc {
                centre: V2::new(circle.centre[a], circle.centre[b]),
                direction,
                plane,
            }
            .with_element(V2::new(start[a], start[b]), V2::new(end[a], end[b]));
            if plane == front.modal.plane {
                update_tangent(front, &element, &full, plane);
            }
            return Ok(Prepared::Direct(tag, Some(arc)));
        }
    }
    let pieces = arcs::chord_count(circle.sweep, circle.radius, 0.001, origin.span)?;
    let u: [f64; 3] = std::array::from_fn(|i| (start[i] - circle.centre[i]) / circle.radius);
    let n = circle.normal;
    let v = [
        n[1] * u[2] - n[2] * u[1],
        n[2] * u[0] - n[0] * u[2],
        n[0] * u[1] - n[1] * u[0],
    ];
    let points = (1..=pieces)
        .map(|k| {
            if k == pieces {
                return end;
            }
            let angle = circle.sweep * k as f64 / pieces as f64;
            let (sin, cos) = angle.sin_cos();
            std::array::from_fn(|i| circle.centre[i] + circle.radius * (cos * u[i] + sin * v[i]))
        })
        .collect();
    Ok(Prepared::Chords(tag, points))
}

/// INVCW, INVCCW (PGsl 9.8): the involute in the plane from p, its base circle's centre I J K
/// from p (or absolute with AC), radius CR=, to the plane's end point or by AR=; the axis normal
/// to the plane moves along in proportion (as in a helix). Cut into straight pieces within a
/// micrometre, as a CIP circle in no machine plane.
fn involute(
    front: &mut Sinumerik,
    words: &Words<'_>,
    target: [Option<f64>; AXES],
    ccw: bool,
    origin: Origin,
) -> Result<Prepared, Alarm> {
    let name = if ccw { "INVCCW" } else { "INVCW" };
    let (a, b, c) = front.modal.plane.axes();
    let unit = unit(front);
    let p = front.programmed;
    let start = V2::new(p[a], p[b]);
    let centre_of = |i: usize| match words.centre[i] {
        Some(v) if v.absolute == Some(true) => v.value * unit,
        Some(v) => p[i] + v.value * unit,
        None => p[i],
    };
    let centre = V2::new(centre_of(a), centre_of(b));
    let Some((radius, _)) = words.radius else {
        return Err(Alarm::error(
            AlarmCode::ArcWithoutCenter,
            origin.span,
            format!("{name} needs the base circle's radius CR="),
        )
        .with_help("write CR= and the base circle's centre I J K (from the start point)"));
    };
    let in_plane = target[a].is_some() || target[b].is_some();
    let end = match (words.opening, in_plane) {
        (Some(_), true) => {
            return Err(Alarm::error(
                AlarmCode::WordNotAllowed,
                origin.span,
                format!("{name} takes its end point or AR=, not both (PGsl 9.8)"),
            ))
        }
        (Some((opening, _)), false) => involute::End::Opening(opening),
        (None, true) => involute::End::Point(V2::new(
            target[a].unwrap_or(start.x),
            target[b].unwrap_or(start.y),
        )),
        (None, false) => {
            return Err(Alarm::error(
                AlarmCode::ArcEndNotOnCircle,
                origin.span,
                format!("{name} needs an end point in the plane or AR="),
            ))
        }
    };
    let path = involute::Involute::new(start, centre, radius * unit, end, ccw, origin.span)?;
    let end = match end {
        involute::End::Point(point) => point,
        involute::End::Opening(_) => path.end(),
    };
    let normal_end = target[c].unwrap_or(p[c]);
    let pieces = path.pieces(0.001, origin.span)?;
    let points = (1..=pieces)
        .map(|k| {
            let u = k as f64 / pieces as f64;
            let point = if k == pieces { end } else { path.point(u) };
            let mut xyz = [0.0; 3];
            xyz[a] = point.x;
            xyz[b] = point.y;
            xyz[c] = p[c] + u * (normal_end - p[c]);
            xyz
        })
        .collect();
    let mut full = target;
    full[a] = Some(end.x);
    full[b] = Some(end.y);
    full[c] = Some(normal_end);
    front.tangent = Some(Tangent::Direction(path.end_tangent()));
    advance(front, &full);
    Ok(Prepared::Chords(tag(full, origin, false, 0), points))
}

/// G33, G331, G332: the lead from I (X), J (Y) or K (Z), the one of the axis that moves most
/// (PGsl 10.1-10.3); the feed per revolution along the path is that lead scaled to the path.
/// G331 turns the spindle by the lead's sign (negative: counter-clockwise), G332 the other way.
fn thread(
    front: &mut Sinumerik,
    words: &Words<'_>,
    mut target: [Option<f64>; AXES],
    origin: Origin,
) -> Result<Prepared, Alarm> {
    let p = front.programmed;
    if front.frame.has_rotation() {
        for (t, p) in target.iter_mut().zip(p).take(3) {
            t.get_or_insert(p);
        }
    }
    let end: [f64; 3] = std::array::from_fn(|i| target[i].unwrap_or(p[i]));
    let travel: [f64; 3] = std::array::from_fn(|i| (end[i] - p[i]).abs());
    let dominant = (0..3)
        .max_by(|&i, &j| travel[i].total_cmp(&travel[j]))
        .unwrap_or(2);
    let path = travel.iter().map(|t| t * t).sum::<f64>().sqrt();
    let lead_word =
        words.centre[dominant].or_else(|| words.centre.iter().flatten().next().copied());
    let written = lead_word.map(|lead| lead.value * unit(front));
    let Some(value) = front.threads.lead(written) else {
        return Err(Alarm::error(
            AlarmCode::NoFeedRate,
            origin.span,
            "a thread needs its lead: I for X, J for Y, K for Z",
        )
        .with_help(
            "give the lead (mm per revolution) with the axis that moves most: G33 Z-50 K1.5",
        ));
    };
    if value == 0.0 {
        return Err(Alarm::error(
            AlarmCode::ValueOutOfRange,
            origin.span,
            "the thread's lead is 0",
        ));
    }
    let spindle = match front.modal.motion {
        Motion::Tap { retract } => Some(if (value < 0.0) != retract {
            SpindleState::CounterClockwise
        } else {
            SpindleState::Clockwise
        }),
        _ => None,
    };
    // G34/G35: the lead that gives the block its time (threads.rs); F is their lead change.
    let change = words.feed.map(|(f, span)| (f * unit(front), span));
    let lead = super::threads::mean_lead(
        front.modal.motion,
        value,
        change,
        travel[dominant],
        origin.span,
    )?;
    let per_revolution = if travel[dominant] > 0.0 {
        lead * path / travel[dominant]
    } else {
        lead
    };
    let tag = tag(target, origin, false, 0);
    advance(front, &target);
    Ok(Prepared::Thread(tag, per_revolution, spindle))
}

impl Prepared {
    /// Moves the held block (and the corner after it): what comes before this block's events.
    pub(super) fn release_held(
        &mut self,
        front: &mut Sinumerik,
        kernel: &mut Kernel,
    ) -> Result<(), Alarm> {
        if let Prepared::Cuts { cuts, held } = self {
            let held_cuts: Vec<_> = cuts.drain(..*held).collect();
            *held = 0;
            for cut in held_cuts {
                execute(front, kernel, cut)?;
            }
        }
        Ok(())
    }

    /// Moves this block.
    pub(super) fn finish(self, front: &mut Sinumerik, kernel: &mut Kernel) -> Result<(), Alarm> {
        match self {
            Prepared::None | Prepared::Waiting => Ok(()),
            Prepared::Cuts { cuts, .. } => {
                for cut in cuts {
                    execute(front, kernel, cut)?;
                }
                Ok(())
            }
            Prepared::Direct(tag, arc) => direct(front, kernel, &tag, arc),
            Prepared::Thread(tag, lead, spindle) => {
                if spindle.is_some() {
                    kernel.spindle(None, spindle, tag.origin);
                }
                kernel.thread_to(tag.target, lead, tag.origin)
            }
            Prepared::Chords(tag, points) => {
                for point in points {
                    let mut target = tag.target;
                    for (i, v) in point.into_iter().enumerate() {
                        target[i] = Some(v);
                    }
                    kernel.feed_to(target, tag.origin)?;
                }
                Ok(())
            }
        }
    }
}

fn direct(
    front: &Sinumerik,
    kernel: &mut Kernel,
    tag: &Tag,
    arc: Option<Arc>,
) -> Result<(), Alarm> {
    // The feed group's measure of the path (FGROUP, FGREF, FL: axes.rs).
    let shape = arc.map(|arc| super::axes::ArcShape {
        plane: arc.plane,
        centre: (arc.centre.x, arc.centre.y),
        direction: arc.direction,
        turns: tag.turns,
    });
    let saved = (!tag.rapid)
        .then(|| super::axes::scale_feed(front, kernel, &tag.target, shape))
        .flatten();
    let moved = match arc {
        None if tag.rapid => kernel.rapid_to(tag.target, tag.origin),
        None => kernel.feed_to(tag.target, tag.origin),
        Some(arc) => arc_through_frames(kernel, tag, arc),
    };
    if let Some((mode, feed)) = saved {
        kernel.set_feed_in(mode, feed);
    }
    moved
}

/// An arc of `plane` (program coordinates) to `target` about `centre`, as the frames in force
/// map it: an arc of the stream, or straight pieces where they tilt its plane. The cycles'
/// arcs go this way too (under CYCLE800's swivel a pocket's circles are tilted).
#[allow(clippy::too_many_arguments)] // the arc's own parts, as `Kernel::arc_in` takes them
pub(super) fn arc_in_frames(
    kernel: &mut Kernel,
    plane: Plane,
    target: [Option<f64>; AXES],
    centre: (f64, f64),
    direction: ArcDirection,
    turns: u32,
    origin: Origin,
) -> Result<(), Alarm> {
    let tag = Tag {
        origin,
        target,
        rapid: false,
        turns,
    };
    let arc = Arc {
        centre: V2::new(centre.0, centre.1),
        direction,
        plane,
    };
    arc_through_frames(kernel, &tag, arc)
}

fn arc_through_frames(kernel: &mut Kernel, tag: &Tag, arc: Arc) -> Result<(), Alarm> {
    if keeps_plane(kernel, arc.plane) {
        return kernel.arc_in(
            arc.plane,
            tag.target,
            (arc.centre.x, arc.centre.y),
            arc.direction,
            tag.turns,
            tag.origin,
        );
    }
    match turned_plane(kernel, arc.plane) {
        Some((onto, reversed)) => kernel.arc_onto(
            arc.plane,
            onto,
            reversed,
            tag.target,
            (arc.centre.x, arc.centre.y),
            arc.direction,
            tag.turns,
            tag.origin,
        ),
        None => tilted_arc(kernel, tag, arc),
    }
}

/// True when the frame maps the arc's plane onto a machine plane as a circle (the stream's arcs
/// lie in G17/G18/G19 planes).
fn keeps_plane(kernel: &Kernel, plane: Plane) -> bool {
    let (a, b, _) = plane.axes();
    kernel.state().frames.affine_frames_keep_plane((a, b))
}

/// The machine plane the frame turns the arc's plane onto, when that is another coordinate
/// plane (ROT Y90 takes X-Y onto Y-Z): the arc stays an arc of the stream there; and whether it
/// turns the other way there.
fn turned_plane(kernel: &Kernel, plane: Plane) -> Option<(Plane, bool)> {
    let (a, b, _) = plane.axes();
    let frames = &kernel.state().frames;
    // Under CYCLE800's swivel frame the arc is cut in pieces: the image of the plane through
    // both frames is not looked for.
    if frames.swivel().is_some() {
        return None;
    }
    let frame = frames.programmable()?;
    let ((c, _), reversed) = frame.plane_image((a, b))?;
    let onto = match c {
        0 => Plane::Xy,
        2 => Plane::Zx,
        _ => Plane::Yz,
    };
    Some((onto, reversed))
}

/// An arc whose plane the frame tilts (or scales unevenly): straight pieces within 1 µm of the
/// circle in program coordinates, each mapped through the frame (docs/SINUMERIK.md 9).
fn tilted_arc(kernel: &mut Kernel, tag: &Tag, arc: Arc) -> Result<(), Alarm> {
    let (a, b, n) = arc.plane.axes();
    let p = kernel.program_position();
    let start = V2::new(p[a], p[b]);
    let end = V2::new(tag.target[a].unwrap_or(p[a]), tag.target[b].unwrap_or(p[b]));
    let (r0, r1) = ((start - arc.centre).length(), (end - arc.centre).length());
    let tolerance = kernel.state().setup.profile().motion.arc_radius_tolerance;
    if (r0 - r1).abs() > tolerance.max(1e-9 * r0) {
        return Err(Alarm::error(
            AlarmCode::ArcEndNotOnCircle,
            tag.origin.span,
            format!("the arc's end is {:.4} mm off its circle (radius {r0:.4} at the start, {r1:.4} at the end)", (r0 - r1).abs()),
        )
        .with_help("check the end point and the centre (I J K are incremental unless =AC(..))"));
    }
    let height = (p[n], tag.target[n].unwrap_or(p[n]));
    let points = arcs::helix_points(
        start,
        arc.centre,
        end,
        height,
        arc.direction,
        tag.turns,
        0.001,
        tag.origin.span,
    )?;
    let last = points.len() - 1;
    for (k, (point, h)) in points.into_iter().enumerate() {
        let mut target = if k == last { tag.target } else { [None; AXES] };
        target[a] = Some(point.x);
        target[b] = Some(point.y);
        target[n] = Some(h);
        kernel.feed_to(target, tag.origin)?;
    }
    Ok(())
}

/// One cut of the contour.
fn execute(front: &mut Sinumerik, kernel: &mut Kernel, cut: Cut<Tag>) -> Result<(), Alarm> {
    let plane = front.modal.plane;
    let (a, b, _) = plane.axes();
    let is_corner = matches!(cut, Cut::Corner { .. });
    let (element, tag) = match cut {
        Cut::Block { element, tag } => (element, tag),
        Cut::Corner {
            element, warning, ..
        } => {
            if let Some(warning) = warning {
                kernel.warn(warning);
            }
            let origin = front.corner_origin.unwrap_or(Origin::at(front.last_span));
            let mut target = [None; AXES];
            target[a] = Some(element.end().x);
            target[b] = Some(element.end().y);
            let tag = Tag {
                origin,
                target,
                rapid: false,
                turns: 0,
            };
            (element, tag)
        }
    };
    front.corner_origin = Some(tag.origin);
    let mut target = tag.target;
    target[a] = Some(element.end().x);
    target[b] = Some(element.end().y);
    let tag = Tag { target, ..tag };
    let corner_feed = front.corner_feed.filter(|_| is_corner);
    let mode = super::block::feed_mode(front.modal.feed_type);
    let saved = corner_feed.map(|f| {
        let saved = kernel.state().feed;
        kernel.set_feed_in(mode, Some(f));
        saved
    });
    let result = match element {
        Element::Line { .. } => direct(front, kernel, &tag, None),
        Element::Arc { center, ccw, .. } => direct(
            front,
            kernel,
            &tag,
            Some(Arc {
                centre: center,
                direction: direction(ccw),
                plane,
            }),
        ),
    };
    if let Some(saved) = saved {
        kernel.set_feed_in(mode, saved);
    }
    result
}

/// G74 (the reference point) or G75 FP=n (fixed point n, the machine's reference point n+1):
/// the named axes, geometry or machine names, go there at rapid in machine coordinates
/// (PGsl 14.4, 14.5; docs/SINUMERIK.md 1 for the fixed points' place in the machine file).
pub(super) fn reference_move(
    front: &mut Sinumerik,
    kernel: &mut Kernel,
    words: &Words<'_>,
    reference: bool,
    origin: Origin,
) -> Result<(), Alarm> {
    let n = if reference {
        1
    } else {
        let Some((n, span)) = words.fixed_point else {
            return Err(Alarm::error(
                AlarmCode::WordNotAllowed,
                origin.span,
                "G75 needs the fixed point's number: FP=1",
            ));
        };
        if n == 0 {
            return Err(Alarm::error(
                AlarmCode::ValueOutOfRange,
                span,
                "FP=0 is no fixed point",
            ));
        }
        n + 1
    };
    let points = &kernel.state().setup.machine().reference_points;
    let Some(&point) = points.get(n as usize - 1) else {
        return Err(Alarm::error(
            AlarmCode::ReferencePointOutOfRange,
            words.fixed_point.map_or(origin.span, |(_, s)| s),
            format!("the machine file has no fixed point {}", n - 1),
        )
        .with_help("add it to the machine file's [reference_points] (fixed point n is reference point n+1)"));
    };
    let mut to = kernel.state().position;
    let mut any = false;
    for i in 0..AXES {
        if words.axes[i].is_some() || words.machine_axes[i].is_some() {
            to[i] = point[i];
            any = true;
        }
    }
    if !any {
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            origin.span,
            "G74 and G75 name the axes to move: X1=0 Z1=0 (the values do not count)",
        ));
    }
    kernel.rapid_to_machine(to, origin)?;
    let now = kernel.program_position();
    for (i, (p, now)) in front.programmed.iter_mut().zip(now).enumerate() {
        if words.axes[i].is_some() || words.machine_axes[i].is_some() {
            *p = now;
        }
    }
    Ok(())
}

/// A move of a block with G53, G153 or SUPA: the programmed axes go to machine positions
/// without the suppressed frames; the tool length stays (docs/SINUMERIK.md 5.6).
pub(super) fn suppressed_move(
    front: &mut Sinumerik,
    kernel: &mut Kernel,
    words: &Words<'_>,
    level: OneBlock,
    origin: Origin,
) -> Result<(), Alarm> {
    if words.axes.iter().all(Option::is_none) {
        return Ok(());
    }
    let state = kernel.state();
    let external = match level {
        OneBlock::SuppressAll => [0.0; AXES],
        _ => state.frames.work_offset(WorkOffsetId::External),
    };
    let [lx, ly] = state.frames.lateral_length();
    let tool = [lx, ly, state.frames.length_vector()];
    let here = state.position;
    let unit = unit(front);
    let mut to = here;
    for (i, value) in words.axes.iter().enumerate() {
        let Some(v) = value else { continue };
        let scale = front.axes.scale(i, unit);
        let length = tool.get(i).copied().unwrap_or(0.0);
        to[i] = if v.absolute.unwrap_or(front.modal.absolute) {
            v.value * scale + external[i] + length
        } else {
            here[i] + v.value * scale
        };
    }
    match front.modal.motion {
        Motion::Rapid => kernel.rapid_to_machine(to, origin)?,
        Motion::Line => kernel.feed_to_machine(to, origin)?,
        _ => {
            return Err(Alarm::error(
                AlarmCode::WordNotAllowed,
                origin.span,
                "G53, G153 and SUPA take G0 or G1",
            ))
        }
    }
    // The next block starts from where the tool stands, seen through the normal chain.
    let now = kernel.program_position();
    for (i, value) in words.axes.iter().enumerate() {
        if value.is_some() {
            front.programmed[i] = now[i];
        }
    }
    Ok(())
}
