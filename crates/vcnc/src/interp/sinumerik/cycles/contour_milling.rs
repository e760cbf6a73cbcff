//! CYCLE72, path milling: the tool goes along a contour given by name (`named_contour.rs`), on
//! it or left or right of it with its radius, level by level down to the depth, reaching and
//! leaving the contour on a line or a circle.
//!
//! Parameters (the cycles manual's list; meanings **inferred** where docs/SINUMERIK.md says so):
//! CYCLE72(KNAME, RTP, RFP, SDIS, DP, MID, FAL, FALD, FFP1, FFD, VARI, RL, AS1, LP1, FF3, AS2,
//! LP2). VARI: units 1 roughing (FAL left on the wall, FALD on the bottom), 2 finishing; tens 0
//! the moves between levels in rapid, 1 at FF3; hundreds where the tool goes at the end of the
//! contour: 0 RTP, 1 RFP+SDIS, 2 up by SDIS, 3 nowhere. RL 40 on the contour, 41 left, 42 right
//! (the tool centre at the tool radius plus FAL from it, round outer corners on the transition
//! circle, G450). AS1/AS2 units: 1 a straight line along the contour's tangent, 2 a quarter
//! circle, 3 a semicircle, both tangential, 4 a straight line along the normal; tens 0 in the
//! plane, 1 in space (down or up by SDIS along the way). LP1/LP2 the line's length or the
//! circle's radius (of the tool centre's path). AS2 0 and LP2 left out are AS1's and LP1's.
//!
//! Never: cut a level before the tool has gone down to it at the way in, or leave the tool
//! below the retraction plane at the end.
//!
//! The file's seam, should it grow: `ToolPath` (the tool centre's path, from the contour and
//! the compensation's corners) above the moves (`Pass`).

use super::named_contour;
use super::pockets::tool_radius;
use super::rings::Piece;
use super::{alarm, divisions, machining_type, Levels, Params, Place};
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::comp::geometry::{Element, GeometryError, Link, Side, V2};
use crate::interp::comp::transition::{corner, OuterCorner};
use crate::interp::kernel::Kernel;
use crate::interp::modal::FeedMode;
use crate::interp::sinumerik::Sinumerik;

/// The parameters of a CYCLE72 call, read and checked.
struct PathMilling {
    levels: Levels,
    /// MID (0: the whole depth at once).
    step_down: f64,
    /// The tool centre's distance from the contour (RL 41/42) and the side.
    offset: Option<(Side, f64)>,
    bottom: f64,
    plane_feed: Option<f64>,
    depth_feed: Option<f64>,
    /// FF3: the retraction and the moves between levels (0: FFP1).
    retract_feed: Option<f64>,
    /// VARI's tens: the moves between levels at FF3 rather than in rapid.
    linear_between: bool,
    /// VARI's hundreds.
    lift: Lift,
    approach: Way,
    retraction: Way,
}

/// Where the tool goes when it has left the contour (VARI's hundreds).
#[derive(Clone, Copy, PartialEq)]
enum Lift {
    Retraction,
    Safety,
    Clearance,
    Stay,
}

/// How the tool reaches or leaves the contour (AS1, AS2 with LP1, LP2).
#[derive(Clone, Copy)]
struct Way {
    shape: Shape,
    /// Tens 1: down (or up) by SDIS along the way.
    spatial: bool,
    size: f64,
}

#[derive(Clone, Copy, PartialEq)]
enum Shape {
    Tangent,
    Quarter,
    Half,
    Normal,
}

/// CYCLE72 (see the module's doc).
pub(super) fn run(front: &mut Sinumerik, kernel: &mut Kernel, p: &Params) -> Result<(), Alarm> {
    let Some(name) = p.text(0).map(str::to_string) else {
        return Err(Alarm::error(
            AlarmCode::MissingValue,
            p.span,
            "CYCLE72: the contour's name KNAME is missing",
        )
        .with_help(
            "KNAME: the contour's subprogram, or \"START:END\", its labels in this program",
        ));
    };
    let radius = front.edge().map(|edge| edge.radius);
    let milling = PathMilling::read(p, radius)?;
    let contour = named_contour::read(front, kernel, &name, p.span)?;
    let path = ToolPath::new(&contour, milling.offset)?;
    let mut at = Place::new(front, kernel);
    let result = Pass::new(&mut at, kernel, &milling, &path).mill();
    at.finish(front);
    result
}

impl PathMilling {
    fn read(p: &Params, radius: Option<f64>) -> Result<PathMilling, Alarm> {
        let levels = Levels::read_from(p, 1, None)?;
        let vari = p.or_zero(10).round() as i64;
        let (units, tens, hundreds) = (vari % 10, vari / 10 % 10, vari / 100);
        if !(1..=2).contains(&units) || !(0..=1).contains(&tens) || !(0..=3).contains(&hundreds) {
            return Err(machining_type(
                p,
                vari,
                "units 1 roughing, 2 finishing; tens 0 rapid, 1 FF3 between levels; hundreds 0 to RTP, 1 to RFP+SDIS, 2 up by SDIS, 3 no retraction",
            ));
        }
        let finishing = units == 2;
        let wall = if finishing {
            0.0
        } else {
            p.length_or_zero(6).abs()
        };
        let bottom_allowance = if finishing {
            0.0
        } else {
            p.length_or_zero(7).abs()
        };
        let step_down = p.length_or_zero(5).abs();
        if step_down > 0.0 && bottom_allowance > step_down {
            return Err(alarm(
                61110,
                p.span,
                format_args!(
                    "CYCLE72: finishing allowance at the bottom {bottom_allowance} > the infeed depth {step_down}"
                ),
            ));
        }
        let offset = match p.or_zero(11).round() as i64 {
            40 => None,
            41 => Some((Side::Left, tool_radius(p, radius)? + wall)),
            42 => Some((Side::Right, tool_radius(p, radius)? + wall)),
            rl => {
                return Err(out_of_range(
                    p,
                    "RL",
                    rl,
                    "40 on the contour, 41 left, 42 right",
                ))
            }
        };
        let feed = |index: usize| p.number(index).filter(|f| *f > 0.0);
        let approach = Way::read(p, "AS1", 12, 13)?;
        let retraction = match p.or_zero(15).round() as i64 {
            0 => approach,
            _ => Way::read(p, "AS2", 15, 16)?,
        };
        let retraction = Way {
            size: p.length(16).unwrap_or(approach.size).abs(),
            ..retraction
        };
        Ok(PathMilling {
            levels,
            step_down,
            offset,
            // An allowance deeper than the cut leaves one level at the reference plane.
            bottom: (levels.depth + bottom_allowance).min(levels.reference),
            plane_feed: feed(8),
            depth_feed: feed(9),
            retract_feed: feed(14).or(feed(8)),
            linear_between: tens == 1,
            lift: [Lift::Retraction, Lift::Safety, Lift::Clearance, Lift::Stay][hundreds as usize],
            approach,
            retraction,
        })
    }

    /// The heights of the levels, top first.
    fn heights(&self) -> Vec<f64> {
        let top = self.levels.reference;
        let total = top - self.bottom;
        let count = divisions(total, self.step_down);
        (1..=count)
            .map(|k| top - total * k as f64 / count as f64)
            .collect()
    }

    /// SDIS.
    fn clearance(&self) -> f64 {
        self.levels.safety - self.levels.reference
    }
}

impl Way {
    /// AS1 or AS2 (`name`) at `shape` and LP1 or LP2 at `size`: V007 for a way that is none.
    fn read(p: &Params, name: &str, shape: usize, size: usize) -> Result<Way, Alarm> {
        let written = p.or_zero(shape).round() as i64;
        let kind = match (written % 10, written / 10) {
            (1, 0..=1) => Shape::Tangent,
            (2, 0..=1) => Shape::Quarter,
            (3, 0..=1) => Shape::Half,
            (4, 0..=1) => Shape::Normal,
            _ => {
                return Err(out_of_range(
                    p,
                    name,
                    written,
                    "units 1 straight, 2 quarter circle, 3 semicircle (tangential), 4 straight along the normal; tens 0 in the plane, 1 in space",
                ));
            }
        };
        Ok(Way {
            shape: kind,
            spatial: written / 10 == 1,
            size: p.length_or_zero(size).abs(),
        })
    }

    /// The way between the contour's end `at` (the tool going along `tangent` there, its side's
    /// normal `normal`) and the point it starts or ends at: the point, and the circle's centre
    /// and direction (clockwise) when it is an arc. `backwards` for the approach, which ends
    /// at `at`.
    fn end(
        &self,
        at: V2,
        tangent: V2,
        normal: V2,
        side: Side,
        backwards: bool,
    ) -> (V2, Option<(V2, bool)>) {
        let r = self.size;
        let along = if backwards { tangent * -r } else { tangent * r };
        let clockwise = side == Side::Right;
        match self.shape {
            Shape::Tangent => (at + along, None),
            Shape::Normal => (at + normal * r, None),
            Shape::Quarter => (at + along + normal * r, Some((at + normal * r, clockwise))),
            Shape::Half => (at + normal * (2.0 * r), Some((at + normal * r, clockwise))),
        }
    }
}

/// V007 for parameter `name` written `value`, with the values it takes.
fn out_of_range(p: &Params, name: &str, value: i64, values: &str) -> Alarm {
    Alarm::error(
        AlarmCode::ValueOutOfRange,
        p.span,
        format!("CYCLE72: {name} {value} is none of the values it takes"),
    )
    .with_help(format!("{name}: {values}"))
}

/// The tool centre's path along the contour.
struct ToolPath {
    start: V2,
    pieces: Vec<Piece>,
    /// The direction of travel where the path starts and where it ends.
    start_tangent: V2,
    end: V2,
    end_tangent: V2,
    /// The side the ways in and out lie on (RL 40: the left, a **choice**).
    side: Side,
}

impl ToolPath {
    /// The path of the tool centre along `contour`, at `offset` on its side (None: on it).
    fn new(
        contour: &[named_contour::Piece],
        offset: Option<(Side, f64)>,
    ) -> Result<ToolPath, Alarm> {
        let first = contour[0].0;
        let last = contour[contour.len() - 1].0;
        let Some((side, r)) = offset else {
            return Ok(ToolPath {
                start: first.start(),
                pieces: contour.iter().map(|(e, _)| piece_to(e, e.end())).collect(),
                start_tangent: first.start_tangent(),
                end: last.end(),
                end_tangent: last.end_tangent(),
                side: Side::Left,
            });
        };
        let start = first
            .offset(side, r)
            .map_err(|e| geometry(e, contour[0].1))?
            .start();
        let mut pieces = Vec::with_capacity(2 * contour.len());
        let mut from = start;
        for (k, (element, span)) in contour.iter().enumerate() {
            let compensated = element.offset(side, r).map_err(|e| geometry(e, *span))?;
            let (end, links) = match contour.get(k + 1) {
                Some((next, _)) => {
                    let c = corner(OuterCorner::TransitionCircle, element, next, side, r)
                        .map_err(|e| geometry(e, *span))?;
                    (c.a_end, c.links)
                }
                None => (compensated.end(), Vec::new()),
            };
            // Corners that trim a line beyond its length would send the tool back along it.
            if let Element::Line { start, end: to } = compensated {
                if (end - from).dot(to - start) < -1e-9 {
                    return Err(geometry(GeometryError::Interference, *span));
                }
            }
            pieces.push(piece_to(&compensated, end));
            from = end;
            for link in links {
                from = link.to();
                pieces.push(match link {
                    Link::Line(to) => Piece::Line((to.x, to.y)),
                    Link::Arc { to, center, ccw } => Piece::Arc {
                        to: (to.x, to.y),
                        centre: (center.x, center.y),
                        ccw,
                    },
                });
            }
        }
        Ok(ToolPath {
            start,
            pieces,
            start_tangent: first.start_tangent(),
            end: from,
            end_tangent: last.end_tangent(),
            side,
        })
    }
}

/// The move along `element` (or its compensated copy) to `to`.
fn piece_to(element: &Element, to: V2) -> Piece {
    match *element {
        Element::Line { .. } => Piece::Line((to.x, to.y)),
        Element::Arc { center, ccw, .. } => Piece::Arc {
            to: (to.x, to.y),
            centre: (center.x, center.y),
            ccw,
        },
    }
}

/// The compensation's alarm for the contour's block at `span`.
fn geometry(error: GeometryError, span: crate::source::Span) -> Alarm {
    let message = match error {
        GeometryError::ArcSmallerThanTool {
            arc_radius,
            tool_radius,
        } => format!(
            "CYCLE72: the arc's radius {arc_radius:.4} is not larger than the tool's distance {tool_radius:.4} from it on its inside"
        ),
        GeometryError::ZeroLength => "CYCLE72: an element of no length in the contour".to_string(),
        _ => "CYCLE72: the tool's path would cut into the contour here (interference)".to_string(),
    };
    Alarm::error(AlarmCode::CutterCompensation, span, message)
        .with_help("a smaller tool or allowance FAL, or a contour the tool fits")
}

/// The moves of one CYCLE72 call.
struct Pass<'a> {
    at: &'a mut Place,
    kernel: &'a mut Kernel,
    milling: &'a PathMilling,
    path: &'a ToolPath,
    feed_mode: FeedMode,
}

impl<'a> Pass<'a> {
    fn new(
        at: &'a mut Place,
        kernel: &'a mut Kernel,
        milling: &'a PathMilling,
        path: &'a ToolPath,
    ) -> Pass<'a> {
        let feed_mode = kernel.feed_setting().0;
        Pass {
            at,
            kernel,
            milling,
            path,
            feed_mode,
        }
    }

    fn set_feed(&mut self, feed: Option<f64>) {
        if let Some(feed) = feed {
            self.kernel.set_feed_in(self.feed_mode, Some(feed));
        }
    }

    /// Every level: down at the way in, along the way in, the contour and the way out, then up
    /// as VARI's hundreds say; at the end up to RTP.
    fn mill(&mut self) -> Result<(), Alarm> {
        let levels = self.milling.levels;
        let normal = self.path.side.normal(self.path.start_tangent);
        let (entry, arc) = self.milling.approach.end(
            self.path.start,
            self.path.start_tangent,
            normal,
            self.path.side,
            true,
        );
        if self.at.height() < levels.retraction {
            self.at.rapid_height(self.kernel, levels.retraction)?;
        }
        self.at.rapid_plane(self.kernel, point(entry))?;
        let mut top = levels.safety;
        for (k, height) in self.milling.heights().into_iter().enumerate() {
            if k > 0 {
                self.between(entry)?;
            }
            if self.at.height() > top {
                self.at.rapid_height(self.kernel, top)?;
            }
            self.approach(height, arc)?;
            self.set_feed(self.milling.plane_feed);
            for piece in &self.path.pieces {
                self.cut(*piece, None)?;
            }
            self.retract(height)?;
            self.lift(height)?;
            top = height + self.milling.clearance();
        }
        if self.at.height() < levels.retraction {
            self.at.rapid_height(self.kernel, levels.retraction)?;
        }
        Ok(())
    }

    /// From the way in down to `height` and along the way in to the contour: down at FFD and
    /// along at FFP1 in the plane, or along and down at once at FFD in space.
    fn approach(&mut self, height: f64, arc: Option<(V2, bool)>) -> Result<(), Alarm> {
        self.set_feed(self.milling.depth_feed);
        let spatial = self.milling.approach.spatial;
        if !spatial {
            self.at.feed_height(self.kernel, height)?;
            self.set_feed(self.milling.plane_feed);
        }
        let to = point(self.path.start);
        let piece = match arc {
            Some((centre, clockwise)) => Piece::Arc {
                to,
                centre: point(centre),
                ccw: !clockwise,
            },
            None => Piece::Line(to),
        };
        self.cut(piece, spatial.then_some(height))
    }

    /// Along the way out at FF3, up by SDIS on the way in space.
    fn retract(&mut self, height: f64) -> Result<(), Alarm> {
        let way = self.milling.retraction;
        let normal = self.path.side.normal(self.path.end_tangent);
        let (to, arc) = way.end(
            self.path.end,
            self.path.end_tangent,
            normal,
            self.path.side,
            false,
        );
        self.set_feed(self.milling.retract_feed);
        let rise = way.spatial.then_some(height + self.milling.clearance());
        let piece = match arc {
            Some((centre, clockwise)) => Piece::Arc {
                to: point(to),
                centre: point(centre),
                ccw: !clockwise,
            },
            None => Piece::Line(point(to)),
        };
        self.cut(piece, rise)
    }

    /// Up as VARI's hundreds say, from the level at `height`.
    fn lift(&mut self, height: f64) -> Result<(), Alarm> {
        let levels = &self.milling.levels;
        let target = match self.milling.lift {
            Lift::Retraction => levels.retraction,
            Lift::Safety => levels.safety,
            Lift::Clearance => height + self.milling.clearance(),
            Lift::Stay => return Ok(()),
        };
        if target > self.at.height() {
            self.at.rapid_height(self.kernel, target)?;
        }
        Ok(())
    }

    /// Back to the way in for the next level: in rapid, or at FF3 (VARI's tens 1).
    fn between(&mut self, entry: V2) -> Result<(), Alarm> {
        let here = self.at.in_plane();
        if (entry.x - here.0).hypot(entry.y - here.1) < 1e-9 {
            return Ok(());
        }
        if self.milling.linear_between {
            self.set_feed(self.milling.retract_feed);
            self.at.feed_to(self.kernel, point(entry), None)
        } else {
            self.at.rapid_plane(self.kernel, point(entry))
        }
    }

    /// A cutting move along `piece` (to `height` on the tool axis, when given); none where the
    /// tool already is.
    fn cut(&mut self, piece: Piece, height: Option<f64>) -> Result<(), Alarm> {
        let (here, level) = (self.at.in_plane(), self.at.height());
        let to = match piece {
            Piece::Line(to) | Piece::Arc { to, .. } => to,
        };
        let still = (to.0 - here.0).hypot(to.1 - here.1) < 1e-9;
        if still && height.is_none_or(|h| (h - level).abs() < 1e-9) {
            return Ok(());
        }
        match piece {
            Piece::Arc { to, centre, ccw } if !still => {
                self.at.arc_to(self.kernel, to, centre, !ccw, height, 0)
            }
            _ => self.at.feed_to(self.kernel, to, height),
        }
    }
}

fn point(v: V2) -> (f64, f64) {
    (v.x, v.y)
}
