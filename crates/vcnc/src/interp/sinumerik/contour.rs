//! Contour definitions of the SINUMERIK front end: lines given by an angle (`ANG=`), and the
//! chamfers and roundings the control inserts at the corner between two blocks (`CHF=`, `CHR=`,
//! `RND=`, `RNDM=`) (spec sinumerik-part-b.md 1.9 and 1.15; PGsl 9.9, L5832-6118, and 9.15,
//! L6749-6947).
//!
//! Everything is in the plane's (abscissa, ordinate) coordinates as [`Plane::axes`] orders them
//! (G18: Z then X), with comp's plane [`Element`]s. A corner needs the element after it, so
//! [`Contour`] holds back the block whose end gets a chamfer or rounding until the next element
//! in the plane arrives ([`Contour::push`]) or the front end knows none will
//! ([`Contour::flush`]: a block out of the plane, a plane change, too many blocks without
//! motion, the program's end; the control then makes no corner, L6797-6803). It holds at most
//! one element, never moves anything itself, and never drops a programmed element that still
//! has length. [`AngleLines`] does the same for the first block of a two-line `ANG=`
//! definition, whose end only the second block fixes; its lines then go through [`Contour`].
//!
//! The file's seam, should it grow: the `ANG=` definitions above [`CornerKind`], the corners
//! below.
//!
//! [`Plane::axes`]: crate::motion::Plane::axes
#![cfg_attr(not(test), allow(dead_code))] // wired in by the front end (issue 20)

use super::arcs::turned;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::comp::geometry::{corner, Element, Side, V2};
use crate::source::Span;
use std::f64::consts::{PI, TAU};

/// Pieces shorter than this are left out, in mm: a corner that uses up an element leaves a
/// rest of rounding noise, far below the control's least increment.
const SHORT: f64 = 1e-6;

/// Angles closer than this (radians) to 0 or 180 degrees make lines parallel.
const ANGLE_EPSILON: f64 = 1e-9;

/// Elements whose directions at a corner differ by less than this (radians) meet tangentially:
/// no corner to make. Wider than comp's own test of a straight corner, whose inner-corner rule
/// finds the rounding's centre.
const TANGENT: f64 = 1e-7;

/// A line given by `ANG=` and one coordinate of its end (PGsl 9.9.2, L5868-5901).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum AngleEnd {
    /// The abscissa of the end is written (X in G17, Z in G18).
    Abscissa(f64),
    /// The ordinate of the end is written (Y in G17, X in G18).
    Ordinate(f64),
}

/// The end of the line from `start` at `angle` degrees (counter-clockwise from the abscissa)
/// whose end has the one coordinate `known`. A coordinate behind the start gives the line
/// run backwards along the angle (choice: the manual does not say; ex. b-27, b-28).
///
/// # Errors
/// [`AlarmCode::ContourDefinition`] when the line runs along the axis of the known
/// coordinate (that coordinate cannot fix the end).
pub(crate) fn angle_line_end(
    start: V2,
    angle: f64,
    known: AngleEnd,
    span: Span,
) -> Result<V2, Alarm> {
    let (sin, cos) = angle.to_radians().sin_cos();
    let along = match known {
        AngleEnd::Abscissa(a) if cos.abs() > ANGLE_EPSILON => (a - start.x) / cos,
        AngleEnd::Ordinate(o) if sin.abs() > ANGLE_EPSILON => (o - start.y) / sin,
        _ => {
            return Err(Alarm::error(
                AlarmCode::ContourDefinition,
                span,
                format!("ANG={angle} runs parallel to the axis of the one coordinate written"),
            )
            .with_help("write the other coordinate of the end point"))
        }
    };
    let end = start + V2::new(cos, sin) * along;
    // The written coordinate exactly as written, not as recomputed.
    Ok(match known {
        AngleEnd::Abscissa(a) => V2::new(a, end.y),
        AngleEnd::Ordinate(o) => V2::new(end.x, o),
    })
}

/// The corner of a two-line contour definition (PGsl 9.9.3, L5902-5996): the first line leaves
/// `start` at `first_angle`, the second ends at `end` and runs at `second_angle` (degrees); the
/// corner is where they meet.
///
/// # Errors
/// [`AlarmCode::ContourDefinition`] when the two lines are parallel.
pub(crate) fn angle_corner(
    start: V2,
    first_angle: f64,
    end: V2,
    second_angle: f64,
    span: Span,
) -> Result<V2, Alarm> {
    let direction = |angle: f64| {
        let (sin, cos) = angle.to_radians().sin_cos();
        V2::new(cos, sin)
    };
    let (u, v) = (direction(first_angle), direction(second_angle));
    let across = u.cross(v);
    if across.abs() < ANGLE_EPSILON {
        return Err(Alarm::error(
            AlarmCode::ContourDefinition,
            span,
            format!("ANG={first_angle} and ANG={second_angle} are parallel: the lines do not meet"),
        ));
    }
    Ok(start + u * ((end - start).cross(v) / across))
}

/// The first block of a two-line definition (`ANG=` and no coordinate of the plane), waiting
/// for the second, which fixes the corner.
#[derive(Clone, Debug, PartialEq)]
struct OpenLine<T> {
    start: V2,
    angle: f64,
    tag: T,
    corner: Option<CornerSpec>,
    span: Span,
}

/// A G0/G1 block as [`AngleLines`] needs it.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct LineBlock<T> {
    /// Where it starts: the last position reached.
    pub(crate) start: V2,
    /// The plane coordinates it writes (abscissa, ordinate), absolute.
    pub(crate) written: (Option<f64>, Option<f64>),
    /// `ANG=`, degrees, if written.
    pub(crate) angle: Option<f64>,
    /// The caller's tag of the block.
    pub(crate) tag: T,
    /// The chamfer or rounding at its end.
    pub(crate) corner: Option<CornerSpec>,
    /// The block, for alarms.
    pub(crate) span: Span,
}

/// What an `ANG=` block gives.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum AngleStep<T> {
    /// The first block of a two-line definition: nothing moves until the next block.
    Held,
    /// Lines to push into the [`Contour`], in order, each with its block's tag and corner
    /// (lines of no length in the plane are left out).
    Lines(Vec<(Element, T, Option<CornerSpec>)>),
}

/// The contour definitions by angle (PGsl 9.9.2-9.9.5, L5868-6107): a line from `ANG=` and one
/// coordinate, or two lines, the first given by `ANG=` alone, the second by its end and
/// `ANG=`, meeting at the corner they define. The front end calls [`AngleLines::block`] for
/// each G0/G1 block with `ANG=`, and for the block after a held one.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct AngleLines<T> {
    open: Option<OpenLine<T>>,
}

impl<T> Default for AngleLines<T> {
    fn default() -> Self {
        AngleLines { open: None }
    }
}

impl<T> AngleLines<T> {
    pub(crate) fn new() -> Self {
        AngleLines::default()
    }

    /// True while the first block of a two-line definition waits for the second.
    pub(crate) fn is_open(&self) -> bool {
        self.open.is_some()
    }

    /// A line block (L6078-6107):
    ///
    /// - no coordinate of the plane: the first block of two (held); if one is held, the second,
    ///   whose end in the plane is its start (the definition then moves at most out of the
    ///   plane);
    /// - one coordinate: after a held block the second, the other coordinate that of the start
    ///   (the last position reached); otherwise a single line ([`angle_line_end`]);
    /// - both: the second block of two; without a held first block, an alarm.
    ///
    /// # Errors
    /// [`AlarmCode::ContourDefinition`] for both coordinates and `ANG=` without a held first
    /// block, a held first block followed by a block without `ANG=`, and the alarms of
    /// [`angle_line_end`] and [`angle_corner`].
    pub(crate) fn block(&mut self, block: LineBlock<T>) -> Result<AngleStep<T>, Alarm> {
        let LineBlock {
            start,
            written,
            angle,
            tag,
            corner,
            span,
        } = block;
        let end = V2::new(written.0.unwrap_or(start.x), written.1.unwrap_or(start.y));
        let Some(angle) = angle else {
            if let Some(open) = self.open.take() {
                return Err(without_end(&open)
                    .with_label(span, "the next block gives no angle for the second line"));
            }
            return Ok(lines(vec![(line(start, end), tag, corner)]));
        };
        if let Some(open) = self.open.take() {
            let meet = angle_corner(open.start, open.angle, end, angle, span)?;
            return Ok(lines(vec![
                (line(open.start, meet), open.tag, open.corner),
                (line(meet, end), tag, corner),
            ]));
        }
        let known = match written {
            (None, None) => {
                self.open = Some(OpenLine {
                    start,
                    angle,
                    tag,
                    corner,
                    span,
                });
                return Ok(AngleStep::Held);
            }
            (Some(abscissa), None) => AngleEnd::Abscissa(abscissa),
            (None, Some(ordinate)) => AngleEnd::Ordinate(ordinate),
            (Some(_), Some(_)) => {
                return Err(Alarm::error(
                    AlarmCode::ContourDefinition,
                    span,
                    "both coordinates with ANG= need a block with ANG= alone before them",
                )
                .with_help("write one coordinate with ANG=, or leave ANG= out"))
            }
        };
        let end = angle_line_end(start, angle, known, span)?;
        Ok(lines(vec![(line(start, end), tag, corner)]))
    }

    /// No further block can finish a held first line (the program ends, or the front end
    /// meets a block that cannot be its second).
    ///
    /// # Errors
    /// [`AlarmCode::ContourDefinition`] when a first line is held.
    pub(crate) fn close(&mut self) -> Result<(), Alarm> {
        match self.open.take() {
            None => Ok(()),
            Some(open) => Err(without_end(&open)),
        }
    }
}

/// The alarm for a held first line that no second line finishes.
fn without_end<T>(open: &OpenLine<T>) -> Alarm {
    Alarm::error(
        AlarmCode::ContourDefinition,
        open.span,
        format!("the line of ANG={} has no end", open.angle),
    )
    .with_help("follow it with the second line's end and angle: X.. Z.. ANG=..")
}

fn line(start: V2, end: V2) -> Element {
    Element::Line { start, end }
}

/// The lines of an [`AngleStep`], without those of no length.
fn lines<T>(all: Vec<(Element, T, Option<CornerSpec>)>) -> AngleStep<T> {
    AngleStep::Lines(
        all.into_iter()
            .filter(|(element, ..)| element.start().distance(element.end()) >= SHORT)
            .collect(),
    )
}

/// What the control inserts at a corner.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum CornerKind {
    /// `RND=` or `RNDM=`: an arc of the given radius tangent to both elements.
    Round,
    /// `CHF=`: a chamfer of the given length (L6771).
    Chamfer,
    /// `CHR=`: a chamfer whose ends are the given width from the corner, along each element
    /// (L6774, "in the original direction of motion"; ex. b-29, b-30).
    ChamferLeg,
}

/// A chamfer or rounding programmed for the corner at the end of a block.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct CornerSpec {
    pub(crate) kind: CornerKind,
    /// The radius, chamfer length or width, mm.
    pub(crate) size: f64,
    /// The word, for alarms.
    pub(crate) span: Span,
}

/// What to cut, in order.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Cut<T> {
    /// A programmed element, or what its corners leave of it, with the caller's tag of its
    /// block. An element a corner uses up entirely gives no cut.
    Block { element: Element, tag: T },
    /// The chamfer (a line) or rounding (an arc) at the corner after the previous block: the
    /// one pushed before the push that returns it (its technology, MD20201, comes from one of
    /// the two).
    Corner {
        element: Element,
        kind: CornerKind,
        /// A warning when the chamfer or rounding was made smaller to fit its elements.
        warning: Option<Alarm>,
    },
}

/// The block held back for the corner at its end.
#[derive(Clone, Debug, PartialEq)]
struct Held<T> {
    /// What is left of the element (its start trimmed by the corner before it); `None` when
    /// that corner used it up.
    element: Option<Element>,
    tag: T,
    corner: CornerSpec,
}

/// The chamfer and rounding state machine: feed it the plane elements of consecutive blocks
/// with the corner each block programs at its end; it hands back what to cut.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Contour<T> {
    held: Option<Held<T>>,
    /// `RNDM=`: the rounding of every corner that programs none of its own.
    modal_round: Option<CornerSpec>,
}

impl<T> Default for Contour<T> {
    fn default() -> Self {
        Contour {
            held: None,
            modal_round: None,
        }
    }
}

impl<T> Contour<T> {
    pub(crate) fn new() -> Self {
        Contour::default()
    }

    /// `RNDM=radius`: round every following corner that programs no chamfer or rounding of
    /// its own, from the corner at the end of the block that writes it; `RNDM=0` ends it
    /// (L6783-6785).
    ///
    /// # Errors
    /// [`AlarmCode::ValueOutOfRange`] for a negative radius.
    pub(crate) fn set_modal_rounding(&mut self, radius: f64, span: Span) -> Result<(), Alarm> {
        let spec = CornerSpec {
            kind: CornerKind::Round,
            size: radius,
            span,
        };
        self.modal_round = checked(Some(spec))?;
        Ok(())
    }

    /// True while a block is held back for its corner.
    pub(crate) fn is_holding(&self) -> bool {
        self.held.is_some()
    }

    /// The next block's element in the plane (it starts where the previous one ended), with
    /// the chamfer or rounding programmed for the corner at its end (`None`: the modal
    /// rounding, if any). Returns what can be cut now: the held block up to its corner, the
    /// corner, and this block too unless it is held for its own corner. A size of 0 programs
    /// no corner; elements that meet tangentially get none.
    ///
    /// # Errors
    /// [`AlarmCode::ValueOutOfRange`] for a negative size; [`AlarmCode::ContourDefinition`]
    /// where the path turns back on itself at a corner to be made, or no rounding touches
    /// both elements. The contour is then empty; the caller stops.
    pub(crate) fn push(
        &mut self,
        element: Element,
        tag: T,
        corner: Option<CornerSpec>,
    ) -> Result<Vec<Cut<T>>, Alarm> {
        let spec = checked(corner.or(self.modal_round))?;
        let mut cuts = Vec::new();
        let mut element = Some(element);
        if let Some(held) = self.held.take() {
            let made = match (held.element, element) {
                (Some(a), Some(b)) => make_corner(&a, &b, held.corner)?,
                _ => None,
            };
            match made {
                Some(made) => {
                    let a = held
                        .element
                        .and_then(|a| trim_end(&a, made.element.start()));
                    cuts.extend(a.map(|element| Cut::Block {
                        element,
                        tag: held.tag,
                    }));
                    element = element.and_then(|b| trim_start(&b, made.element.end()));
                    cuts.push(Cut::Corner {
                        element: made.element,
                        kind: held.corner.kind,
                        warning: made.warning,
                    });
                }
                None => cuts.extend(held.element.map(|element| Cut::Block {
                    element,
                    tag: held.tag,
                })),
            }
        }
        match spec {
            Some(corner) => {
                self.held = Some(Held {
                    element,
                    tag,
                    corner,
                })
            }
            None => cuts.extend(element.map(|element| Cut::Block { element, tag })),
        }
        Ok(cuts)
    }

    /// No further element in the plane joins the held block: it is cut without its corner
    /// (L6797-6803). The modal rounding stays in force.
    pub(crate) fn flush(&mut self) -> Vec<Cut<T>> {
        self.held
            .take()
            .and_then(|held| {
                held.element.map(|element| Cut::Block {
                    element,
                    tag: held.tag,
                })
            })
            .into_iter()
            .collect()
    }
}

/// A corner spec with a size of 0 taken as none.
///
/// # Errors
/// [`AlarmCode::ValueOutOfRange`] for a negative or non-finite size.
fn checked(spec: Option<CornerSpec>) -> Result<Option<CornerSpec>, Alarm> {
    match spec {
        Some(spec) if spec.size == 0.0 => Ok(None),
        Some(spec) if !(spec.size > 0.0 && spec.size.is_finite()) => Err(Alarm::error(
            AlarmCode::ValueOutOfRange,
            spec.span,
            format!("{} is not a size: it must be positive", describe(spec)),
        )),
        other => Ok(other),
    }
}

/// The word as the program writes it, for messages.
fn describe(spec: CornerSpec) -> String {
    let name = match spec.kind {
        CornerKind::Round => "RND",
        CornerKind::Chamfer => "CHF",
        CornerKind::ChamferLeg => "CHR",
    };
    format!("{name}={}", spec.size)
}

/// A corner made: its element (it starts on the first element and ends on the second).
struct Made {
    element: Element,
    warning: Option<Alarm>,
}

/// The chamfer or rounding between `a` and `b` (`a` ends where `b` starts); `None` when the
/// elements meet tangentially.
fn make_corner(a: &Element, b: &Element, spec: CornerSpec) -> Result<Option<Made>, Alarm> {
    let (ta, tb) = (a.end_tangent(), b.start_tangent());
    let (cross, dot) = (ta.cross(tb), ta.dot(tb));
    let turn = cross.atan2(dot);
    if turn.abs() < TANGENT {
        return Ok(None);
    }
    if PI - turn.abs() < TANGENT {
        return Err(Alarm::error(
            AlarmCode::ContourDefinition,
            spec.span,
            format!(
                "{}: the path turns back on itself at this corner",
                describe(spec)
            ),
        ));
    }
    let left = turn > 0.0;
    match spec.kind {
        CornerKind::Round => rounding(a, b, left, spec).map(Some),
        CornerKind::Chamfer | CornerKind::ChamferLeg => Ok(Some(chamfer(a, b, spec))),
    }
}

/// The rounding of radius `spec.size` on the inner side of the corner (the left when `left`):
/// its centre is where the two elements moved inwards by the radius meet (comp's inner
/// corner). Too large a radius is made the largest that fits (L6793-6795).
fn rounding(a: &Element, b: &Element, left: bool, spec: CornerSpec) -> Result<Made, Alarm> {
    let side = if left { Side::Left } else { Side::Right };
    let fits = |radius: f64| -> Option<(V2, V2, V2)> {
        let centre = corner(a, b, side, radius).ok()?.a_end;
        let (on_a, on_b) = (foot(a, centre), foot(b, centre));
        (on_element(a, on_a) && on_element(b, on_b)).then_some((centre, on_a, on_b))
    };
    let (radius, (centre, on_a, on_b)) = match fits(spec.size) {
        Some(found) => (spec.size, found),
        None => {
            let radius = largest(spec.size, |r| fits(r).is_some());
            let found = fits(radius).filter(|_| radius > SHORT).ok_or_else(|| {
                Alarm::error(
                    AlarmCode::ContourDefinition,
                    spec.span,
                    format!("{}: no rounding touches both elements", describe(spec)),
                )
            })?;
            (radius, found)
        }
    };
    // Snapped to an element's far end only by a sliver of the radius: moving a tangent point
    // of a tiny rounding (a corner that nearly turns back) by SHORT turned its tangent by a
    // thousandth of a radian.
    let within = SHORT.min(radius * 1e-7);
    let element = Element::Arc {
        start: snap_within(on_a, a.start(), within),
        end: snap_within(on_b, b.end(), within),
        center: centre,
        ccw: left,
    };
    Ok(Made {
        element,
        warning: reduced(spec, radius),
    })
}

/// The chamfer of `spec`: a line between the points of `a` and `b` at the same straight
/// distance (the leg) from the corner. CHR gives the leg; CHF the chamfer's length, from which
/// the leg is found (for two lines `leg = length / (2 cos(turn / 2))`). Too large a chamfer is
/// made the largest that fits (L6793-6795). On an arc the leg is the chord from the corner
/// (choice: the manual shows chamfers between lines only).
fn chamfer(a: &Element, b: &Element, spec: CornerSpec) -> Made {
    let longest = max_leg(a).min(max_leg(b));
    let ends = |leg: f64| (leg_point(a, leg, true), leg_point(b, leg, false));
    let length = |leg: f64| {
        let (p, q) = ends(leg);
        p.distance(q)
    };
    let leg = match spec.kind {
        CornerKind::ChamferLeg => spec.size.min(longest),
        _ if length(longest) <= spec.size => longest,
        // The chamfer's length grows with its leg: the leg whose chamfer is as long as asked.
        _ => largest(longest, |leg| length(leg) <= spec.size),
    };
    let (p, q) = ends(leg);
    let reduced_to = match spec.kind {
        CornerKind::ChamferLeg => leg,
        _ => length(leg),
    };
    Made {
        element: Element::Line {
            start: snap(p, a.start()),
            end: snap(q, b.end()),
        },
        warning: reduced(spec, reduced_to),
    }
}

/// The warning for a corner made smaller than programmed (`made` against `spec.size`).
fn reduced(spec: CornerSpec, made: f64) -> Option<Alarm> {
    (made < spec.size * (1.0 - 1e-9)).then(|| {
        Alarm::warning(
            AlarmCode::ContourDefinition,
            spec.span,
            format!(
                "{} is too large for the elements it joins: made {made:.4}",
                describe(spec)
            ),
        )
        .with_help("the control makes a chamfer or rounding smaller where it does not fit")
    })
}

/// The largest value in (0, `limit`] for which `fits` holds, by bisection (`fits` holds below
/// some bound and not above it); 0 when it holds nowhere.
fn largest(limit: f64, fits: impl Fn(f64) -> bool) -> f64 {
    let (mut low, mut high) = (0.0, limit);
    for _ in 0..200 {
        if high - low <= 1e-13 * limit {
            break;
        }
        let middle = (low + high) / 2.0;
        if fits(middle) {
            low = middle;
        } else {
            high = middle;
        }
    }
    low
}

/// `point` replaced by `end` when it lies within [`SHORT`] of it, so that pieces join exactly.
fn snap(point: V2, end: V2) -> V2 {
    snap_within(point, end, SHORT)
}

/// `point` replaced by `end` when it lies within `distance` of it.
fn snap_within(point: V2, end: V2, distance: f64) -> V2 {
    if point.distance(end) < distance {
        end
    } else {
        point
    }
}

/// The point of the element's line or circle nearest `point` (where a circle about `point`
/// touches it).
fn foot(element: &Element, point: V2) -> V2 {
    match *element {
        Element::Line { start, end } => {
            let u = (end - start).unit();
            start + u * (point - start).dot(u)
        }
        Element::Arc { start, center, .. } => {
            center + (point - center).unit() * start.distance(center)
        }
    }
}

/// True when `point` (on the element's line or circle) lies between its ends, to 1e-9 mm.
fn on_element(element: &Element, point: V2) -> bool {
    let tolerance = 1e-9;
    let (travelled, total) = match *element {
        Element::Line { start, end } => {
            let d = end - start;
            ((point - start).dot(d.unit()), d.length())
        }
        Element::Arc { start, center, .. } => {
            let radius = start.distance(center);
            let mut angle = travelled_angle(element, point);
            // Just short of a full turn is just before the start.
            if angle > TAU - tolerance / radius {
                angle -= TAU;
            }
            (angle * radius, sweep(element) * radius)
        }
    };
    travelled >= -tolerance && travelled <= total + tolerance
}

/// The angle an arc travels from its start to `point`, in [0, 2 pi).
fn travelled_angle(element: &Element, point: V2) -> f64 {
    let Element::Arc {
        start, center, ccw, ..
    } = *element
    else {
        return 0.0;
    };
    let (from, to) = (start - center, point - center);
    let turn = from.cross(to).atan2(from.dot(to));
    let angle = if ccw { turn } else { -turn };
    angle.rem_euclid(TAU)
}

/// An arc's swept angle; start on end is a full circle.
fn sweep(element: &Element) -> f64 {
    match *element {
        Element::Arc { start, end, .. } if start.distance(end) < SHORT => TAU,
        Element::Arc { end, .. } => travelled_angle(element, end),
        Element::Line { .. } => 0.0,
    }
}

/// The largest leg (straight distance from the corner) a chamfer can have on the element: the
/// whole line, or the longest chord of the arc from either end (the chord grows up to the
/// diameter, half a turn away).
fn max_leg(element: &Element) -> f64 {
    match *element {
        Element::Line { start, end } => start.distance(end),
        Element::Arc { start, center, .. } => {
            2.0 * start.distance(center) * (sweep(element).min(PI) / 2.0).sin()
        }
    }
}

/// The point of the element at straight distance `leg` from its end (`at_end`) or its start,
/// on the element (`leg` at most [`max_leg`]).
fn leg_point(element: &Element, leg: f64, at_end: bool) -> V2 {
    let (from, towards) = if at_end {
        (element.end(), -element.end_tangent())
    } else {
        (element.start(), element.start_tangent())
    };
    match *element {
        Element::Line { .. } => from + towards * leg,
        Element::Arc { center, ccw, .. } => {
            let radius = from.distance(center);
            // A chord of length `leg` spans 2 asin(leg / 2r) about the centre.
            let angle = 2.0 * (leg / (2.0 * radius)).min(1.0).asin();
            // Forward along a counter-clockwise arc is a positive turn; back from the end, negative.
            let sign = if ccw != at_end { 1.0 } else { -1.0 };
            turned(from, center, sign * angle)
        }
    }
}

/// The element from its start to `point` (on it); `None` when nothing is left.
fn trim_end(element: &Element, point: V2) -> Option<Element> {
    if element.start().distance(point) < SHORT {
        return None;
    }
    Some(match *element {
        Element::Line { start, .. } => Element::Line { start, end: point },
        Element::Arc {
            start, center, ccw, ..
        } => Element::Arc {
            start,
            end: point,
            center,
            ccw,
        },
    })
}

/// The element from `point` (on it) to its end; `None` when nothing is left.
fn trim_start(element: &Element, point: V2) -> Option<Element> {
    if element.end().distance(point) < SHORT {
        return None;
    }
    Some(match *element {
        Element::Line { end, .. } => Element::Line { start: point, end },
        Element::Arc {
            end, center, ccw, ..
        } => Element::Arc {
            start: point,
            end,
            center,
            ccw,
        },
    })
}

#[cfg(test)]
mod tests {
    use super::super::arcs::tests::{assert_near, p, SPAN};
    use super::*;

    fn line(a: (f64, f64), b: (f64, f64)) -> Element {
        Element::Line {
            start: p(a.0, a.1),
            end: p(b.0, b.1),
        }
    }

    fn arc(a: (f64, f64), b: (f64, f64), centre: (f64, f64), ccw: bool) -> Element {
        Element::Arc {
            start: p(a.0, a.1),
            end: p(b.0, b.1),
            center: p(centre.0, centre.1),
            ccw,
        }
    }

    fn spec(kind: CornerKind, size: f64) -> Option<CornerSpec> {
        Some(CornerSpec {
            kind,
            size,
            span: SPAN,
        })
    }

    fn round(size: f64) -> Option<CornerSpec> {
        spec(CornerKind::Round, size)
    }

    /// The cuts of a contour of programmed points (a polyline from `points[0]`), each block
    /// tagged with its index and given the corner at its end, then flushed.
    fn polyline(points: &[(f64, f64)], corners: &[Option<CornerSpec>]) -> Vec<Cut<usize>> {
        let mut contour = Contour::new();
        let mut cuts = Vec::new();
        for (i, pair) in points.windows(2).enumerate() {
            let element = line(pair[0], pair[1]);
            cuts.extend(contour.push(element, i, corners[i]).unwrap());
        }
        cuts.extend(contour.flush());
        cuts
    }

    fn element_of(cut: &Cut<usize>) -> &Element {
        match cut {
            Cut::Block { element, .. } | Cut::Corner { element, .. } => element,
        }
    }

    /// The start, end and (for an arc) centre and direction of a cut's element.
    fn ends(cut: &Cut<usize>) -> (V2, V2, Option<(V2, bool)>) {
        match *element_of(cut) {
            Element::Line { start, end } => (start, end, None),
            Element::Arc {
                start,
                end,
                center,
                ccw,
            } => (start, end, Some((center, ccw))),
        }
    }

    /// Checks a cut: block or corner, its start and end to `tolerance`.
    fn assert_cut(
        cut: &Cut<usize>,
        corner: bool,
        start: (f64, f64),
        end: (f64, f64),
        tolerance: f64,
    ) {
        assert_eq!(matches!(cut, Cut::Corner { .. }), corner, "{cut:?}");
        let (s, e, _) = ends(cut);
        assert_near(s, start, tolerance);
        assert_near(e, end, tolerance);
    }

    /// Checks an arc cut's centre and direction.
    fn assert_centre(cut: &Cut<usize>, centre: (f64, f64), ccw: bool, tolerance: f64) {
        let (_, _, Some((c, direction))) = ends(cut) else {
            panic!("not an arc: {cut:?}")
        };
        assert_near(c, centre, tolerance);
        assert_eq!(direction, ccw, "{cut:?}");
    }

    #[test]
    fn rnd_between_a_line_along_x_and_one_along_y() {
        // By hand: (0,0)->(50,0) then (50,0)->(50,40) turns left 90 degrees; RND=10 touches
        // each line 10 tan 45 = 10 from the corner: (40,0) and (50,10), centre (40,10),
        // counter-clockwise.
        let cuts = polyline(
            &[(0.0, 0.0), (50.0, 0.0), (50.0, 40.0)],
            &[round(10.0), None],
        );
        assert_eq!(cuts.len(), 3, "{cuts:?}");
        assert_cut(&cuts[0], false, (0.0, 0.0), (40.0, 0.0), 1e-12);
        assert_cut(&cuts[1], true, (40.0, 0.0), (50.0, 10.0), 1e-12);
        assert_centre(&cuts[1], (40.0, 10.0), true, 1e-12);
        assert_cut(&cuts[2], false, (50.0, 10.0), (50.0, 40.0), 1e-12);
        assert!(matches!(cuts[2], Cut::Block { tag: 1, .. }));
        let Cut::Corner { warning, kind, .. } = &cuts[1] else {
            unreachable!()
        };
        assert_eq!((warning, *kind), (&None, CornerKind::Round));
    }

    #[test]
    fn milling_example_a10_rounds_and_chamfers_the_rectangle() {
        // sinumerik-a/10-milling-example.mpf N80-N120: (-40,-72) -> (-40,30) RND=10 ->
        // (40,30) CHR=10 -> (40,-30) -> (-41,-30): rounding (-40,20) -> (-30,30) about
        // (-30,20), clockwise; chamfer (30,30) -> (40,20).
        let points = [
            (-40.0, -72.0),
            (-40.0, 30.0),
            (40.0, 30.0),
            (40.0, -30.0),
            (-41.0, -30.0),
        ];
        let corners = [round(10.0), spec(CornerKind::ChamferLeg, 10.0), None, None];
        let cuts = polyline(&points, &corners);
        assert_eq!(cuts.len(), 6, "{cuts:?}");
        assert_cut(&cuts[0], false, (-40.0, -72.0), (-40.0, 20.0), 1e-12);
        assert_cut(&cuts[1], true, (-40.0, 20.0), (-30.0, 30.0), 1e-12);
        assert_centre(&cuts[1], (-30.0, 20.0), false, 1e-12);
        assert_cut(&cuts[2], false, (-30.0, 30.0), (30.0, 30.0), 1e-12);
        assert_cut(&cuts[3], true, (30.0, 30.0), (40.0, 20.0), 1e-12);
        assert_cut(&cuts[4], false, (40.0, 20.0), (40.0, -30.0), 1e-12);
        assert_cut(&cuts[5], false, (40.0, -30.0), (-41.0, -30.0), 1e-12);
    }

    /// A line block: (abscissa, ordinate) as written, ANG=, corner.
    type AngleBlock = ((Option<f64>, Option<f64>), Option<f64>, Option<CornerSpec>);

    fn line_block(
        start: V2,
        written: (Option<f64>, Option<f64>),
        angle: Option<f64>,
        tag: usize,
        corner: Option<CornerSpec>,
    ) -> LineBlock<usize> {
        LineBlock {
            start,
            written,
            angle,
            tag,
            corner,
            span: SPAN,
        }
    }

    /// Runs blocks (start taken from the previous block's end) through [`AngleLines`] and
    /// [`Contour`].
    fn angle_program(start: (f64, f64), blocks: &[AngleBlock]) -> Vec<Cut<usize>> {
        let mut angles = AngleLines::new();
        let mut contour = Contour::new();
        let mut at = p(start.0, start.1);
        let mut cuts = Vec::new();
        for (i, &(written, angle, corner)) in blocks.iter().enumerate() {
            let step = angles
                .block(line_block(at, written, angle, i, corner))
                .unwrap();
            let AngleStep::Lines(lines) = step else {
                continue;
            };
            for (element, tag, corner) in lines {
                at = element.end();
                cuts.extend(contour.push(element, tag, corner).unwrap());
            }
        }
        angles.close().unwrap();
        cuts.extend(contour.flush());
        cuts
    }

    #[test]
    fn two_angle_lines_of_example_b29_meet_and_get_their_chamfer() {
        // sinumerik-b/29-contour-2lines.mpf in (Z, X): from Z80 X10, ANG=148.65 CHR=5.5, then
        // X85 Z40 ANG=100: corner Z50.002 X28.275, chamfer Z54.699 X25.413 -> Z49.047 X33.691.
        let corner = angle_corner(p(80.0, 10.0), 148.65, p(40.0, 85.0), 100.0, SPAN).unwrap();
        assert_near(corner, (50.002, 28.275), 1e-3);
        let cuts = angle_program(
            (80.0, 10.0),
            &[
                (
                    (None, None),
                    Some(148.65),
                    spec(CornerKind::ChamferLeg, 5.5),
                ),
                ((Some(40.0), Some(85.0)), Some(100.0), None),
            ],
        );
        assert_eq!(cuts.len(), 3, "{cuts:?}");
        assert_cut(&cuts[0], false, (80.0, 10.0), (54.699, 25.413), 1e-3);
        assert_cut(&cuts[1], true, (54.699, 25.413), (49.047, 33.691), 1e-3);
        assert_cut(&cuts[2], false, (49.047, 33.691), (40.0, 85.0), 1e-3);
        assert!(matches!(cuts[2], Cut::Block { tag: 1, .. }));
    }

    #[test]
    fn three_lines_of_example_b30_get_a_chamfer_and_a_rounding() {
        // sinumerik-b/30-contour-3lines.mpf in (Z, X): from Z100 X10, ANG=140 CHR=7.5, then
        // X80 Z70 ANG=95.824 RND=10, then X70 Z50. Corner 1 Z75.000 X30.977, chamfer
        // Z80.746 X26.156 -> Z74.239 X38.439; rounding Z71.469 X65.595 -> Z57.049 X73.524
        // about Z61.521 X64.580, a left turn of 110.74 degrees.
        let corner = angle_corner(p(100.0, 10.0), 140.0, p(70.0, 80.0), 95.824, SPAN).unwrap();
        assert_near(corner, (75.0, 30.977), 1e-3);
        let cuts = angle_program(
            (100.0, 10.0),
            &[
                ((None, None), Some(140.0), spec(CornerKind::ChamferLeg, 7.5)),
                ((Some(70.0), Some(80.0)), Some(95.824), round(10.0)),
                ((Some(50.0), Some(70.0)), None, None),
            ],
        );
        assert_eq!(cuts.len(), 5, "{cuts:?}");
        assert_cut(&cuts[0], false, (100.0, 10.0), (80.746, 26.156), 1e-3);
        assert_cut(&cuts[1], true, (80.746, 26.156), (74.239, 38.439), 1e-3);
        assert_cut(&cuts[2], false, (74.239, 38.439), (71.469, 65.595), 1e-3);
        assert_cut(&cuts[3], true, (71.469, 65.595), (57.049, 73.524), 1e-3);
        assert_centre(&cuts[3], (61.521, 64.580), true, 1e-3);
        assert_cut(&cuts[4], false, (57.049, 73.524), (50.0, 70.0), 1e-3);
    }

    #[test]
    fn angle_blocks_that_cannot_define_a_line_are_alarms() {
        // L6099-6101: both coordinates with ANG= need an ANG= block alone before them.
        let mut angles = AngleLines::<usize>::new();
        let origin = p(0.0, 0.0);
        let both = angles.block(line_block(
            origin,
            (Some(1.0), Some(2.0)),
            Some(30.0),
            0,
            None,
        ));
        assert_eq!(both.unwrap_err().code, AlarmCode::ContourDefinition);
        // A held first line and then a block without ANG=, or the end of the program.
        let held = angles.block(line_block(origin, (None, None), Some(30.0), 0, None));
        assert_eq!(held, Ok(AngleStep::Held));
        assert!(angles.is_open());
        let next = angles.block(line_block(origin, (Some(5.0), Some(5.0)), None, 1, None));
        assert_eq!(next.unwrap_err().code, AlarmCode::ContourDefinition);
        let again = angles.block(line_block(origin, (None, None), Some(30.0), 2, None));
        assert_eq!(again, Ok(AngleStep::Held));
        assert_eq!(
            angles.close().unwrap_err().code,
            AlarmCode::ContourDefinition
        );
        assert_eq!(angles.close(), Ok(()));
    }

    #[test]
    fn a_second_angle_block_with_one_coordinate_keeps_the_other_from_the_start() {
        // L6094-6097. By hand: from (0,0), ANG=45 alone, then X10 (abscissa) ANG=135: the end
        // is (10, 0), the ordinate of the start; the lines meet at (5, 5).
        let cuts = angle_program(
            (0.0, 0.0),
            &[
                ((None, None), Some(45.0), None),
                ((Some(10.0), None), Some(135.0), None),
            ],
        );
        assert_eq!(cuts.len(), 2, "{cuts:?}");
        assert_cut(&cuts[0], false, (0.0, 0.0), (5.0, 5.0), 1e-12);
        assert_cut(&cuts[1], false, (5.0, 5.0), (10.0, 0.0), 1e-12);
    }

    #[test]
    fn chamfers_and_modal_rounding_of_example_b45() {
        // sinumerik-b/45-chamfer-round-tech-next.mpf: X10 CHF=2, Y10 CHF=4, X20 CHF=3, RNDM=2,
        // Y20, X30, Y30 CHF=3, X40, Y40, (S1000 M3), X50. 90-degree corners: a chamfer of
        // length c has legs c / sqrt 2 (1.4142, 2.8284, 2.1213); a rounding of 2 runs from 2
        // before to 2 after its corner.
        let mut contour = Contour::new();
        let mut cuts = Vec::new();
        let chf = |size| spec(CornerKind::Chamfer, size);
        let blocks = [
            ((0.0, 0.0), (10.0, 0.0), chf(2.0)),
            ((10.0, 0.0), (10.0, 10.0), chf(4.0)),
            ((10.0, 10.0), (20.0, 10.0), chf(3.0)),
            ((20.0, 10.0), (20.0, 20.0), None),
            ((20.0, 20.0), (30.0, 20.0), None),
            ((30.0, 20.0), (30.0, 30.0), chf(3.0)),
            ((30.0, 30.0), (40.0, 30.0), None),
            ((40.0, 30.0), (40.0, 40.0), None),
            ((40.0, 40.0), (50.0, 40.0), None),
        ];
        for (i, (a, b, corner)) in blocks.into_iter().enumerate() {
            if i == 3 {
                // N50 RNDM=2, before N60.
                contour.set_modal_rounding(2.0, SPAN).unwrap();
            }
            cuts.extend(contour.push(line(a, b), i, corner).unwrap());
        }
        cuts.extend(contour.flush());
        let r = std::f64::consts::SQRT_2;
        let corners: Vec<_> = cuts
            .iter()
            .filter(|cut| matches!(cut, Cut::Corner { .. }))
            .collect();
        assert_eq!(corners.len(), 8, "{cuts:?}");
        let want = [
            ((10.0 - r, 0.0), (10.0, r)),
            ((10.0, 10.0 - 2.0 * r), (10.0 + 2.0 * r, 10.0)),
            ((20.0 - 1.5 * r, 10.0), (20.0, 10.0 + 1.5 * r)),
            ((20.0, 18.0), (22.0, 20.0)),
            ((28.0, 20.0), (30.0, 22.0)),
            ((30.0, 30.0 - 1.5 * r), (30.0 + 1.5 * r, 30.0)),
            ((38.0, 30.0), (40.0, 32.0)),
            ((40.0, 38.0), (42.0, 40.0)),
        ];
        for (cut, (start, end)) in corners.iter().zip(want) {
            assert_cut(cut, true, start, end, 1e-9);
        }
        assert_centre(corners[3], (22.0, 18.0), false, 1e-9);
        assert_centre(corners[4], (28.0, 22.0), true, 1e-9);
        // 9 blocks and 8 corners; the last block from its rounding to X50 Y40.
        assert_eq!(cuts.len(), 17);
        assert_cut(&cuts[16], false, (42.0, 40.0), (50.0, 40.0), 1e-9);
    }

    #[test]
    fn rnd_between_a_line_and_the_inside_of_an_arc() {
        // By hand: (0,0)->(10,0), then counter-clockwise about (0,0) from (10,0) to (0,10): a
        // left turn of 90 degrees. RND=2 lies inside the arc: its centre is 2 above the line
        // and 8 from (0,0): (sqrt 60, 2) = (7.74597, 2); it touches the line at (7.74597, 0)
        // and the arc at 10/8 of its centre: (9.68246, 2.5).
        let mut contour = Contour::new();
        assert!(contour
            .push(line((0.0, 0.0), (10.0, 0.0)), 0, round(2.0))
            .unwrap()
            .is_empty());
        let b = arc((10.0, 0.0), (0.0, 10.0), (0.0, 0.0), true);
        let cuts = contour.push(b, 1, None).unwrap();
        let x = 60f64.sqrt();
        assert_eq!(cuts.len(), 3, "{cuts:?}");
        assert_cut(&cuts[0], false, (0.0, 0.0), (x, 0.0), 1e-9);
        assert_cut(&cuts[1], true, (x, 0.0), (x * 1.25, 2.5), 1e-9);
        assert_centre(&cuts[1], (x, 2.0), true, 1e-9);
        assert_cut(&cuts[2], false, (x * 1.25, 2.5), (0.0, 10.0), 1e-9);
        assert_centre(&cuts[2], (0.0, 0.0), true, 0.0);
    }

    #[test]
    fn rnd_between_an_arc_and_a_line_outside_it() {
        // By hand: clockwise about (0,0) from (0,10) to (10,0) ends heading -Y; then
        // (10,0)->(20,0) heads +X: a left turn. RND=2 lies outside the arc, above the line:
        // centre 2 above y = 0 and 12 from (0,0): (sqrt 140, 2) = (11.83216, 2); it touches
        // the arc at 10/12 of that, (9.86013, 1.66667), and the line at (11.83216, 0).
        let mut contour = Contour::new();
        let a = arc((0.0, 10.0), (10.0, 0.0), (0.0, 0.0), false);
        assert!(contour.push(a, 0, round(2.0)).unwrap().is_empty());
        let cuts = contour
            .push(line((10.0, 0.0), (20.0, 0.0)), 1, None)
            .unwrap();
        let x = 140f64.sqrt();
        assert_eq!(cuts.len(), 3, "{cuts:?}");
        assert_cut(&cuts[0], false, (0.0, 10.0), (x / 1.2, 2.0 / 1.2), 1e-9);
        assert_centre(&cuts[0], (0.0, 0.0), false, 0.0);
        assert_cut(&cuts[1], true, (x / 1.2, 2.0 / 1.2), (x, 0.0), 1e-9);
        assert_centre(&cuts[1], (x, 2.0), true, 1e-9);
        assert_cut(&cuts[2], false, (x, 0.0), (20.0, 0.0), 1e-9);
    }

    #[test]
    fn rnd_between_two_arcs() {
        // By hand: counter-clockwise about (0,0) from (0,-10) to (10,0), heading +Y; then
        // counter-clockwise about (10,10) from (10,0), heading +X: a right turn. RND=2 lies
        // outside both circles: 12 from (0,0) and from (10,10), on x + y = 10 at
        // (5,5) + sqrt(94) (1,-1)/sqrt2 = (11.85565, -1.85565). It touches the first arc at
        // 10/12 of that, (9.87971, -1.54638), and the second at (10,10) + 10/12 of
        // (1.85565, -11.85565): (11.54638, 0.12029). Clockwise.
        let mut contour = Contour::new();
        let a = arc((0.0, -10.0), (10.0, 0.0), (0.0, 0.0), true);
        assert!(contour.push(a, 0, round(2.0)).unwrap().is_empty());
        let b = arc((10.0, 0.0), (20.0, 10.0), (10.0, 10.0), true);
        let cuts = contour.push(b, 1, None).unwrap();
        let h = 47f64.sqrt();
        let centre = (5.0 + h, 5.0 - h);
        let on_a = (centre.0 / 1.2, centre.1 / 1.2);
        let on_b = (
            10.0 + (centre.0 - 10.0) / 1.2,
            10.0 + (centre.1 - 10.0) / 1.2,
        );
        assert_eq!(cuts.len(), 3, "{cuts:?}");
        assert_cut(&cuts[0], false, (0.0, -10.0), on_a, 1e-9);
        assert_cut(&cuts[1], true, on_a, on_b, 1e-9);
        assert_centre(&cuts[1], centre, false, 1e-9);
        assert_cut(&cuts[2], false, on_b, (20.0, 10.0), 1e-9);
        assert_near(p(on_a.0, on_a.1), (9.87971, -1.54638), 1e-5);
        assert_near(p(on_b.0, on_b.1), (11.54638, 0.12029), 1e-5);
    }

    #[test]
    fn chr_on_an_arc_measures_the_chord_from_the_corner() {
        // By hand: (0,0)->(10,0), then counter-clockwise about (0,0) from (10,0) to (0,10).
        // CHR=2: 2 back along the line, (8,0); on the arc the point 2 from (10,0), turned
        // 2 asin(0.1) = 11.4783 degrees: (9.8, 1.98997).
        let mut contour = Contour::new();
        let corner = spec(CornerKind::ChamferLeg, 2.0);
        assert!(contour
            .push(line((0.0, 0.0), (10.0, 0.0)), 0, corner)
            .unwrap()
            .is_empty());
        let b = arc((10.0, 0.0), (0.0, 10.0), (0.0, 0.0), true);
        let cuts = contour.push(b, 1, None).unwrap();
        assert_eq!(cuts.len(), 3, "{cuts:?}");
        let y = 3.96f64.sqrt();
        assert_cut(&cuts[1], true, (8.0, 0.0), (9.8, y), 1e-12);
        assert_cut(&cuts[2], false, (9.8, y), (0.0, 10.0), 1e-12);
        // CHF=2 on the same corner: the legs w with |P_line(w) - P_arc(w)| = 2.
        let mut contour = Contour::new();
        let corner = spec(CornerKind::Chamfer, 2.0);
        contour
            .push(line((0.0, 0.0), (10.0, 0.0)), 0, corner)
            .unwrap();
        let cuts = contour.push(b, 1, None).unwrap();
        let (start, end, _) = ends(&cuts[1]);
        assert!((start.distance(end) - 2.0).abs() < 1e-9, "{cuts:?}");
        assert!((start.distance(p(10.0, 0.0)) - end.distance(p(10.0, 0.0))).abs() < 1e-9);
    }

    #[test]
    fn too_large_a_corner_is_made_to_fit_with_a_warning() {
        // L6793-6795. By hand: (0,0)->(5,0)->(5,20), a left turn of 90 degrees. RND=10 needs
        // 10 of each line; the first has 5: the rounding becomes R5 from (0,0) to (5,5) about
        // (0,5), and the first line is used up.
        let cuts = polyline(&[(0.0, 0.0), (5.0, 0.0), (5.0, 20.0)], &[round(10.0), None]);
        assert_eq!(cuts.len(), 2, "{cuts:?}");
        assert_cut(&cuts[0], true, (0.0, 0.0), (5.0, 5.0), 1e-9);
        assert_centre(&cuts[0], (0.0, 5.0), true, 1e-9);
        let Cut::Corner {
            warning: Some(warning),
            ..
        } = &cuts[0]
        else {
            panic!("{cuts:?}")
        };
        assert_eq!(warning.code, AlarmCode::ContourDefinition);
        assert!(!warning.is_error());
        // CHR=8 on it: legs of 5; CHF=10 (legs 7.07) too: the chamfer is 5 sqrt 2 long.
        for corner in [
            spec(CornerKind::ChamferLeg, 8.0),
            spec(CornerKind::Chamfer, 10.0),
        ] {
            let cuts = polyline(&[(0.0, 0.0), (5.0, 0.0), (5.0, 20.0)], &[corner, None]);
            assert_eq!(cuts.len(), 2, "{cuts:?}");
            assert_cut(&cuts[0], true, (0.0, 0.0), (5.0, 5.0), 1e-9);
            assert!(matches!(
                &cuts[0],
                Cut::Corner {
                    warning: Some(_),
                    ..
                }
            ));
        }
    }

    #[test]
    fn a_corner_where_the_path_turns_back_is_an_alarm() {
        let mut contour = Contour::new();
        contour
            .push(line((0.0, 0.0), (10.0, 0.0)), 0, round(1.0))
            .unwrap();
        let error = contour.push(line((10.0, 0.0), (0.0, 0.0)), 1, None);
        assert_eq!(error.unwrap_err().code, AlarmCode::ContourDefinition);
    }

    #[test]
    fn tangent_elements_get_no_corner() {
        // (0,0)->(10,0), then counter-clockwise about (10,5) from (10,0): it leaves heading
        // +X, as the line arrives. RND=2 makes nothing; both come back whole.
        let mut contour = Contour::new();
        let a = line((0.0, 0.0), (10.0, 0.0));
        let b = arc((10.0, 0.0), (15.0, 5.0), (10.0, 5.0), true);
        contour.push(a, 0, round(2.0)).unwrap();
        let cuts = contour.push(b, 1, None).unwrap();
        assert_eq!(
            cuts,
            vec![
                Cut::Block { element: a, tag: 0 },
                Cut::Block { element: b, tag: 1 }
            ]
        );
    }

    #[test]
    fn flush_cuts_the_held_block_whole_and_rndm_0_ends_the_rounding() {
        let mut contour = Contour::new();
        contour.set_modal_rounding(3.0, SPAN).unwrap();
        let a = line((0.0, 0.0), (10.0, 0.0));
        assert!(contour.push(a, 0, None).unwrap().is_empty());
        assert!(contour.is_holding());
        assert_eq!(contour.flush(), vec![Cut::Block { element: a, tag: 0 }]);
        assert!(!contour.is_holding());
        // RNDM=0: the next block is cut at once.
        contour.set_modal_rounding(0.0, SPAN).unwrap();
        let cuts = contour.push(a, 1, None).unwrap();
        assert_eq!(cuts, vec![Cut::Block { element: a, tag: 1 }]);
        // A size of 0 is no corner, a negative one an alarm.
        assert_eq!(contour.push(a, 2, round(0.0)).unwrap().len(), 1);
        let error = contour.push(a, 3, spec(CornerKind::Chamfer, -1.0));
        assert_eq!(error.unwrap_err().code, AlarmCode::ValueOutOfRange);
        let error = contour.set_modal_rounding(-2.0, SPAN);
        assert_eq!(error.unwrap_err().code, AlarmCode::ValueOutOfRange);
    }

    #[test]
    fn one_angle_line_of_examples_b27_and_b28_ends_at_x88_8_z39_5() {
        // sinumerik-b/27 and -28 in (Z, X): from Z70 X5, ANG=110 with X88.8 or with Z39.5:
        // both end at X88.8 Z39.5 (Z = 70 + 83.8 / tan 110 = 39.499; X = 5 + 30.5 tan 110 =
        // 88.80).
        let start = p(70.0, 5.0);
        let end = angle_line_end(start, 110.0, AngleEnd::Ordinate(88.8), SPAN).unwrap();
        assert_near(end, (39.499, 88.8), 1e-3);
        let end = angle_line_end(start, 110.0, AngleEnd::Abscissa(39.5), SPAN).unwrap();
        assert_near(end, (39.5, 88.8), 1e-2);
        assert_eq!(end.x, 39.5);
        let cuts = angle_program((70.0, 5.0), &[((None, Some(88.8)), Some(110.0), None)]);
        assert_eq!(cuts.len(), 1, "{cuts:?}");
        assert_cut(&cuts[0], false, (70.0, 5.0), (39.499, 88.8), 1e-3);
    }

    #[test]
    fn angle_lines_that_cannot_meet_their_coordinate_are_alarms() {
        // ANG=0 runs along the abscissa: an ordinate cannot end it; ANG=90 the other way.
        let start = p(0.0, 0.0);
        let along = angle_line_end(start, 0.0, AngleEnd::Ordinate(5.0), SPAN);
        assert_eq!(along.unwrap_err().code, AlarmCode::ContourDefinition);
        let up = angle_line_end(start, 90.0, AngleEnd::Abscissa(5.0), SPAN);
        assert_eq!(up.unwrap_err().code, AlarmCode::ContourDefinition);
        // Two lines at 30 and 210 degrees are parallel.
        let parallel = angle_corner(start, 30.0, p(10.0, 0.0), 210.0, SPAN);
        assert_eq!(parallel.unwrap_err().code, AlarmCode::ContourDefinition);
        // By hand: 45 degrees from (0,0) meets the line at 135 degrees through (10,0) at (5,5).
        let corner = angle_corner(start, 45.0, p(10.0, 0.0), 135.0, SPAN).unwrap();
        assert_near(corner, (5.0, 5.0), 1e-12);
    }

    proptest::proptest! {
        #[test]
        fn corners_join_the_pieces_of_a_polyline_without_gaps(
            points in proptest::collection::vec((-50.0..50.0f64, -50.0..50.0f64), 3..8),
            sizes in proptest::collection::vec((0..4u8, 0.1..20.0f64), 8),
        ) {
            let corners: Vec<_> = sizes
                .iter()
                .map(|&(kind, size)| match kind {
                    0 => None,
                    1 => round(size),
                    2 => spec(CornerKind::Chamfer, size),
                    _ => spec(CornerKind::ChamferLeg, size),
                })
                .collect();
            let mut contour = Contour::new();
            let mut cuts = Vec::new();
            let direction = |i: usize| (p(points[i + 1].0, points[i + 1].1) - p(points[i].0, points[i].1)).unit();
            for (i, pair) in points.windows(2).enumerate() {
                proptest::prop_assume!(p(pair[0].0, pair[0].1).distance(p(pair[1].0, pair[1].1)) > 0.01);
                let more = match contour.push(line(pair[0], pair[1]), i, corners[i]) {
                    Ok(more) => more,
                    // Only a corner that turns back may refuse.
                    Err(alarm) => {
                        proptest::prop_assert_eq!(alarm.code, AlarmCode::ContourDefinition);
                        return Ok(());
                    }
                };
                // A rounding made now joins line i - 1 to line i, tangent to both.
                for cut in &more {
                    if let Cut::Corner { kind: CornerKind::Round, element, .. } = cut {
                        proptest::prop_assert!(element.start_tangent().distance(direction(i - 1)) < 1e-6, "{:?}", cut);
                        proptest::prop_assert!(element.end_tangent().distance(direction(i)) < 1e-6, "{:?}", cut);
                    }
                }
                cuts.extend(more);
            }
            cuts.extend(contour.flush());
            let mut at = p(points[0].0, points[0].1);
            for cut in &cuts {
                let (start, end, _) = ends(cut);
                proptest::prop_assert!(start.distance(at) < 1e-6, "{:?} after {:?}", cut, at);
                at = end;
            }
            let last = points[points.len() - 1];
            proptest::prop_assert!(at.distance(p(last.0, last.1)) < 1e-6);
        }

        #[test]
        fn roundings_touch_lines_and_arcs_tangentially(
            a_arc in proptest::bool::ANY, b_arc in proptest::bool::ANY,
            a_turn in 0.3..3.0f64, b_turn in 0.3..3.0f64,
            a_heading in 0.0..std::f64::consts::TAU, b_heading in 0.0..std::f64::consts::TAU,
            a_ccw in proptest::bool::ANY, b_ccw in proptest::bool::ANY,
            a_size in 5.0..50.0f64, b_size in 5.0..50.0f64, radius in 0.1..10.0f64,
        ) {
            // Two elements meeting at the origin: `a` arrives heading `a_heading`, `b` leaves
            // heading `b_heading`; an arc turns by `*_turn` radians on a circle of `*_size`.
            let corner = p(0.0, 0.0);
            let heading = |angle: f64| p(angle.cos(), angle.sin());
            // The side of its travel an arc's centre is on: the left when counter-clockwise.
            let inward = |travel: V2, ccw: bool| if ccw { travel.left() } else { -travel.left() };
            let a = if a_arc {
                let centre = corner + inward(heading(a_heading), a_ccw) * a_size;
                let start = turned(corner, centre, if a_ccw { -a_turn } else { a_turn });
                Element::Arc { start, end: corner, center: centre, ccw: a_ccw }
            } else {
                Element::Line { start: corner - heading(a_heading) * a_size, end: corner }
            };
            let b = if b_arc {
                let centre = corner + inward(heading(b_heading), b_ccw) * b_size;
                let end = turned(corner, centre, if b_ccw { b_turn } else { -b_turn });
                Element::Arc { start: corner, end, center: centre, ccw: b_ccw }
            } else {
                Element::Line { start: corner, end: corner + heading(b_heading) * b_size }
            };
            proptest::prop_assert!(a.end_tangent().distance(heading(a_heading)) < 1e-9);
            proptest::prop_assert!(b.start_tangent().distance(heading(b_heading)) < 1e-9);
            let mut contour = Contour::new();
            contour.push(a, 0, round(radius)).unwrap();
            let cuts = match contour.push(b, 1, None) {
                Ok(cuts) => cuts,
                Err(alarm) => {
                    proptest::prop_assert_eq!(alarm.code, AlarmCode::ContourDefinition);
                    return Ok(());
                }
            };
            let mut at = a.start();
            let mut previous: Option<Element> = None;
            for cut in &cuts {
                let element = *element_of(cut);
                proptest::prop_assert!(element.start().distance(at) < 1e-6, "{:?}", cuts);
                if let Some(previous) = previous {
                    // Pieces of a and b meet the rounding tangentially.
                    proptest::prop_assert!(
                        previous.end_tangent().distance(element.start_tangent()) < 1e-6,
                        "{:?}", cuts
                    );
                }
                // Pieces of a programmed arc keep its centre.
                if let (Cut::Block { tag, .. }, Element::Arc { center, .. }) = (cut, element) {
                    let programmed = if *tag == 0 { a } else { b };
                    let same = matches!(programmed, Element::Arc { center: c, .. } if c == center);
                    proptest::prop_assert!(same, "{:?}", cuts);
                }
                at = element.end();
                previous = Some(element);
            }
            proptest::prop_assert!(at.distance(b.end()) < 1e-6);
        }
    }
}
