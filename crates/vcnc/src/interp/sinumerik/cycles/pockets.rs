//! The pocket cycles: POCKET3 (rectangular pocket) and POCKET4 (circular pocket), milled with
//! the edge in force level by level down to the depth.
//!
//! The cycles manual gives each cycle's parameters and sequence, not its exact path; vcnc's
//! path (docs/SINUMERIK.md, Standard cycles) is: at each depth level (at most MID deep, the
//! levels equal) the tool goes in at the pocket's centre (vertically, or on a helix of radius
//! RAD1 and DP1 per turn), then clears the level in closed rings about the centre, each at
//! most MIDA (0: the tool radius) outside the one before, the last one the pocket's outline
//! less the allowance FAL and the tool radius; then it rapids up to the retraction plane.
//! Finishing (VARI units 2) goes round the outline at the final size, level by level, and
//! clears the bottom when FALD left some.
//!
//! Never: let the tool centre leave the pocket's outline less the tool radius, or rapid below
//! the reference plane except where the tool has cut.

use super::{alarm, Levels, Params, Place};
use crate::alarm::Alarm;
use crate::interp::kernel::Kernel;
use crate::interp::modal::FeedMode;

/// A piece of a ring in the pocket's own coordinates (centre at 0, length along u).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Piece {
    Line((f64, f64)),
    Arc { to: (f64, f64), centre: (f64, f64) },
}

/// The parameters POCKET3 and POCKET4 share, read at their positions in each.
struct Milling {
    levels: Levels,
    /// MID: the largest depth of a level (0: the whole depth at once).
    step_down: f64,
    /// FAL, FALD: the allowances left on the wall and the bottom by roughing.
    wall_allowance: f64,
    bottom_allowance: f64,
    /// FFP1, FFD: the feeds in the plane and going in.
    plane_feed: Option<f64>,
    depth_feed: Option<f64>,
    /// The rings' direction: CDIR 0 (climb) or 1 (conventional) by the spindle's direction, 2
    /// (G2) or 3 (G3).
    clockwise: bool,
    finishing: bool,
    /// VARI's tens: 0 vertical in rapid, 1 vertical at FFD, 2 on a helix (3, POCKET3's
    /// oscillation, goes in vertically: a choice).
    insertion: u32,
    /// MIDA: the largest step from ring to ring (0: the tool radius).
    step_over: f64,
    /// RAD1 and DP1: the helix's radius and depth per turn.
    helix: (f64, f64),
    tool_radius: f64,
}

/// Where each parameter of a pocket cycle is: MID, FAL, FALD, FFP1, FFD, CDIR, VARI, MIDA,
/// RAD1, DP1.
struct Layout {
    mid: usize,
    fal: usize,
    fald: usize,
    ffp1: usize,
    ffd: usize,
    cdir: usize,
    vari: usize,
    mida: usize,
    rad1: usize,
    dp1: usize,
}

/// POCKET3's places of the shared parameters.
const POCKET3: Layout = Layout {
    mid: 10,
    fal: 11,
    fald: 12,
    ffp1: 13,
    ffd: 14,
    cdir: 15,
    vari: 16,
    mida: 17,
    rad1: 21,
    dp1: 22,
};

/// POCKET4's places of the shared parameters.
const POCKET4: Layout = Layout {
    mid: 7,
    fal: 8,
    fald: 9,
    ffp1: 10,
    ffd: 11,
    cdir: 12,
    vari: 13,
    mida: 14,
    rad1: 17,
    dp1: 18,
};

impl Milling {
    fn read(
        p: &Params,
        at: &Place,
        layout: &Layout,
        radius: Option<f64>,
    ) -> Result<Milling, Alarm> {
        let levels = Levels::read(p, None)?;
        let Some(tool_radius) = radius else {
            return Err(alarm(
                61000,
                p.span,
                format_args!("{}: no tool offset active", p.name()),
            )
            .with_help("select the tool's edge with D before the cycle"));
        };
        if tool_radius <= 0.0 {
            return Err(alarm(
                61117,
                p.span,
                format_args!("{}: active tool radius <= 0", p.name()),
            )
            .with_help("give the edge in force its radius in the tool table"));
        }
        let vari = p.or_zero(layout.vari).round() as i64;
        let (units, tens) = (vari % 10, vari / 10 % 10);
        if !(1..=2).contains(&units) || !(0..=3).contains(&tens) {
            return Err(alarm(
                61002,
                p.span,
                format_args!(
                    "{}: machining type defined incorrectly: VARI {vari}",
                    p.name()
                ),
            )
            .with_help(
                "VARI: units 1 roughing or 2 finishing; tens 0 or 1 vertical, 2 helical insertion",
            ));
        }
        let clockwise = match p.or_zero(layout.cdir).round() as i64 {
            // Climb milling inside a pocket with the spindle turning M3 goes counter-clockwise.
            0 => !at.clockwise,
            1 => at.clockwise,
            2 => true,
            3 => false,
            cdir => {
                return Err(alarm(
                    61109,
                    p.span,
                    format_args!("{}: parameter CDIR defined incorrectly: {cdir}", p.name()),
                )
                .with_help("CDIR: 0 climb, 1 conventional, 2 G2, 3 G3"))
            }
        };
        let step_down = p.length_or_zero(layout.mid).abs();
        let bottom_allowance = p.length_or_zero(layout.fald).abs();
        if step_down > 0.0 && bottom_allowance > step_down {
            return Err(alarm(
                61110,
                p.span,
                format_args!(
                    "{}: finishing allowance at the bottom {bottom_allowance} > the infeed depth {step_down}",
                    p.name()
                ),
            ));
        }
        let step_over = match p.length_or_zero(layout.mida).abs() {
            0.0 => tool_radius,
            step if step > 2.0 * tool_radius => {
                return Err(alarm(
                    61111,
                    p.span,
                    format_args!(
                        "{}: infeed width {step} > tool diameter {}",
                        p.name(),
                        2.0 * tool_radius
                    ),
                ))
            }
            step => step,
        };
        let helix = (p.length_or_zero(layout.rad1), p.length_or_zero(layout.dp1));
        if tens == 2 && (helix.0 <= 0.0 || helix.1 <= 0.0) {
            return Err(alarm(
                61108,
                p.span,
                format_args!(
                    "{}: illegal values for RAD1 and DP1: {} and {}",
                    p.name(),
                    helix.0,
                    helix.1
                ),
            )
            .with_help(
                "a helical insertion needs its radius (RAD1) and its depth per turn (DP1) above 0",
            ));
        }
        let feed = |index: usize| p.number(index).filter(|f| *f > 0.0);
        Ok(Milling {
            levels,
            step_down,
            wall_allowance: p.length_or_zero(layout.fal).abs(),
            bottom_allowance,
            plane_feed: feed(layout.ffp1),
            depth_feed: feed(layout.ffd),
            clockwise,
            finishing: units == 2,
            insertion: tens as u32,
            step_over,
            helix,
            tool_radius,
        })
    }

    /// The heights of the levels, top first, down to `bottom`.
    fn heights(&self, bottom: f64) -> Vec<f64> {
        let total = self.levels.reference - bottom;
        let count = match self.step_down {
            s if s > 0.0 => (total / s - 1e-9).ceil().max(1.0),
            _ => 1.0,
        };
        (1..=count as usize)
            .map(|k| self.levels.reference - total * k as f64 / count)
            .collect()
    }
}

/// The pocket's own coordinates in the plane: its centre and its turn.
struct Frame {
    centre: (f64, f64),
    cos: f64,
    sin: f64,
}

impl Frame {
    fn point(&self, (u, v): (f64, f64)) -> (f64, f64) {
        (
            self.centre.0 + u * self.cos - v * self.sin,
            self.centre.1 + u * self.sin + v * self.cos,
        )
    }
}

/// A pocket being milled: where, how, and the moves.
struct Pocket<'a> {
    at: &'a mut Place,
    kernel: &'a mut Kernel,
    frame: Frame,
    milling: Milling,
    /// The feed mode of the call (FFP1 and FFD are read in it).
    feed_mode: FeedMode,
    /// Where the tool is in the pocket's coordinates.
    here: (f64, f64),
}

impl Pocket<'_> {
    fn set_feed(&mut self, feed: Option<f64>) {
        if let Some(feed) = feed {
            self.kernel.set_feed_in(self.feed_mode, Some(feed));
        }
    }

    /// A rapid to the pocket's centre above it, and down to the safety plane.
    fn approach(&mut self) -> Result<(), Alarm> {
        let centre = self.frame.point((0.0, 0.0));
        let safety = self.milling.levels.safety;
        if self.at.height() < safety {
            self.at.rapid_height(self.kernel, safety)?;
        }
        self.at.rapid_plane(self.kernel, centre)?;
        self.here = (0.0, 0.0);
        self.at.rapid_height(self.kernel, safety)
    }

    /// Goes in at the centre from `top` (cut or open) down to `height`.
    fn go_in(&mut self, top: f64, height: f64) -> Result<(), Alarm> {
        self.line((0.0, 0.0), None)?;
        self.set_feed(self.milling.depth_feed);
        let result = match self.milling.insertion {
            0 => self.at.rapid_height(self.kernel, height),
            2 => self.helix(top, height),
            _ => self.at.feed_height(self.kernel, height),
        };
        self.set_feed(self.milling.plane_feed);
        result
    }

    /// A helix about the centre of radius RAD1 from `top` to `height`, DP1 or less per turn,
    /// then a full circle at `height` and back to the centre.
    fn helix(&mut self, top: f64, height: f64) -> Result<(), Alarm> {
        let (radius, per_turn) = self.milling.helix;
        let start = self.frame.point((radius, 0.0));
        let centre = self.frame.point((0.0, 0.0));
        let clockwise = self.milling.clockwise;
        self.at.rapid_height(self.kernel, top)?;
        self.at.feed_to(self.kernel, start, None)?;
        let turns = ((top - height) / per_turn - 1e-9).ceil().max(1.0) as u32;
        self.at.arc_to(
            self.kernel,
            start,
            centre,
            clockwise,
            Some(height),
            turns - 1,
        )?;
        self.at
            .arc_to(self.kernel, start, centre, clockwise, None, 0)?;
        self.at.feed_to(self.kernel, centre, None)
    }

    /// A cutting line to `to` (pocket coordinates), none when the tool is there.
    fn line(&mut self, to: (f64, f64), height: Option<f64>) -> Result<(), Alarm> {
        if same(to, self.here) && height.is_none() {
            return Ok(());
        }
        self.here = to;
        self.at.feed_to(self.kernel, self.frame.point(to), height)
    }

    /// Cuts `pieces` in order from where the tool is.
    fn cut(&mut self, pieces: &[Piece]) -> Result<(), Alarm> {
        for &piece in pieces {
            match piece {
                Piece::Line(to) => self.line(to, None)?,
                Piece::Arc { to, centre } => {
                    self.here = to;
                    let (to, centre) = (self.frame.point(to), self.frame.point(centre));
                    self.at
                        .arc_to(self.kernel, to, centre, self.milling.clockwise, None, 0)?;
                }
            }
        }
        Ok(())
    }

    /// Clears every level down to `bottom` with `rings` (inside out), going in from the top.
    fn clear(&mut self, bottom: f64, rings: &[Vec<Piece>]) -> Result<(), Alarm> {
        let mut top = self.milling.levels.safety;
        for height in self.milling.heights(bottom) {
            self.go_in(top, height)?;
            for ring in rings {
                self.cut(ring)?;
            }
            // Back over the cleared level to the centre, for the next level's way in.
            self.at
                .rapid_height(self.kernel, height + self.clearance())?;
            self.at
                .rapid_plane(self.kernel, self.frame.point((0.0, 0.0)))?;
            self.here = (0.0, 0.0);
            top = height + self.clearance();
        }
        Ok(())
    }

    /// The height above a cut level the tool moves at: the safety clearance, at most the
    /// level's depth (choice).
    fn clearance(&self) -> f64 {
        let levels = &self.milling.levels;
        (levels.safety - levels.reference).max(0.1)
    }

    fn retract(&mut self) -> Result<(), Alarm> {
        self.at
            .rapid_height(self.kernel, self.milling.levels.retraction)
    }
}

fn same(a: (f64, f64), b: (f64, f64)) -> bool {
    (a.0 - b.0).abs() < 1e-9 && (a.1 - b.1).abs() < 1e-9
}

/// The radii of the rings out to `outer`, at most `step` apart.
fn ring_radii(outer: f64, step: f64) -> Vec<f64> {
    if outer <= 0.0 {
        return Vec::new();
    }
    let count = (outer / step - 1e-9).ceil().max(1.0) as usize;
    (1..=count)
        .map(|k| outer * k as f64 / count as f64)
        .collect()
}

/// A full circle of `radius` about the centre, from and back to (radius, 0), in two halves
/// (the direction is the pocket's).
fn circle_ring(radius: f64) -> Vec<Piece> {
    if radius <= 0.0 {
        return Vec::new();
    }
    let centre = (0.0, 0.0);
    vec![
        Piece::Line((radius, 0.0)),
        Piece::Arc {
            to: (-radius, 0.0),
            centre,
        },
        Piece::Arc {
            to: (radius, 0.0),
            centre,
        },
    ]
}

/// POCKET4(RTP, RFP, SDIS, DP, PRAD, PA, PO, MID, FAL, FALD, FFP1, FFD, CDIR, VARI, MIDA, AP1,
/// AD, RAD1, DP1): a circular pocket of radius PRAD about (PA, PO), DP deep (absolute). AP1
/// and AD (a pocket milled before) are read but not used: the cycle clears from the centre
/// (choice).
pub(super) fn circular(
    at: &mut Place,
    kernel: &mut Kernel,
    p: &Params,
    radius: Option<f64>,
) -> Result<(), Alarm> {
    let milling = Milling::read(p, at, &POCKET4, radius)?;
    let pocket_radius = p.length_or_zero(4).abs();
    let finish = pocket_radius - milling.tool_radius;
    let rough = finish - milling.wall_allowance;
    if rough < 0.0 {
        return Err(alarm(
            61105,
            p.span,
            format_args!(
                "POCKET4: cutter radius too large: {} for a pocket of radius {pocket_radius} with FAL {}",
                milling.tool_radius, milling.wall_allowance
            ),
        ));
    }
    let frame = Frame {
        centre: (p.length_or_zero(5), p.length_or_zero(6)),
        cos: 1.0,
        sin: 0.0,
    };
    let step = milling.step_over;
    let rings = |outer: f64| -> Vec<Vec<Piece>> {
        ring_radii(outer, step)
            .into_iter()
            .map(circle_ring)
            .collect()
    };
    let outline = vec![circle_ring(finish)];
    mill(
        at,
        kernel,
        frame,
        milling,
        rings(rough),
        rings(finish),
        outline,
    )
}

/// The rings of a rectangle of half sizes `a` × `b` (a ≥ b ≥ 0 not needed) with corners of
/// radius `corner`, from and back to (a, 0).
fn rectangle_ring(a: f64, b: f64, corner: f64, clockwise: bool) -> Vec<Piece> {
    let c = corner.min(a).min(b).max(0.0);
    // Counter-clockwise from the middle of the right side.
    let mut pieces = vec![Piece::Line((a, 0.0)), Piece::Line((a, b - c))];
    let corners = [
        ((a - c, b), (a - c, b - c), (-a + c, b)),
        ((-a, b - c), (-a + c, b - c), (-a, -b + c)),
        ((-a + c, -b), (-a + c, -b + c), (a - c, -b)),
        ((a, -b + c), (a - c, -b + c), (a, 0.0)),
    ];
    for (to, centre, next) in corners {
        if c > 0.0 {
            pieces.push(Piece::Arc { to, centre });
        }
        pieces.push(Piece::Line(next));
    }
    if clockwise {
        reverse(&mut pieces);
    }
    pieces
}

/// The same closed path the other way round (from and back to its first point).
fn reverse(pieces: &mut Vec<Piece>) {
    let end = |piece: &Piece| match *piece {
        Piece::Line(to) | Piece::Arc { to, .. } => to,
    };
    let start = end(&pieces[0]);
    let ends: Vec<_> = pieces.iter().map(end).collect();
    let mut reversed = vec![Piece::Line(start)];
    for k in (1..pieces.len()).rev() {
        let to = ends[k - 1];
        reversed.push(match pieces[k] {
            Piece::Line(_) => Piece::Line(to),
            Piece::Arc { centre, .. } => Piece::Arc { to, centre },
        });
    }
    *pieces = reversed;
}

/// POCKET3(RTP, RFP, SDIS, DP, LENG, WID, CRAD, PA, PO, STA, MID, FAL, FALD, FFP1, FFD, CDIR,
/// VARI, MIDA, AP1, AP2, AD, RAD1, DP1): a rectangular pocket LENG × WID with corners of
/// radius CRAD about (PA, PO), its length at STA degrees to the abscissa, DP deep (absolute).
pub(super) fn rectangular(
    at: &mut Place,
    kernel: &mut Kernel,
    p: &Params,
    radius: Option<f64>,
) -> Result<(), Alarm> {
    let milling = Milling::read(p, at, &POCKET3, radius)?;
    let (length, width) = (p.length_or_zero(4).abs(), p.length_or_zero(5).abs());
    let corner = p.length_or_zero(6).abs();
    if corner > length.min(width) / 2.0 {
        return Err(alarm(
            61113,
            p.span,
            format_args!("POCKET3: parameter CRAD for the corner radius too large: {corner} for a pocket {length} × {width}"),
        ));
    }
    let r = milling.tool_radius;
    let (finish_a, finish_b) = (length / 2.0 - r, width / 2.0 - r);
    let fal = milling.wall_allowance;
    let (rough_a, rough_b) = (finish_a - fal, finish_b - fal);
    if rough_a < 0.0 || rough_b < 0.0 {
        return Err(alarm(
            61105,
            p.span,
            format_args!("POCKET3: cutter radius too large: {r} for a pocket {length} × {width} with FAL {fal}"),
        ));
    }
    let (sin, cos) = p.or_zero(9).to_radians().sin_cos();
    let frame = Frame {
        centre: (p.length_or_zero(7), p.length_or_zero(8)),
        cos,
        sin,
    };
    let clockwise = milling.clockwise;
    let step = milling.step_over;
    // The rings shrink from the outline by equal steps until the smaller side closes.
    let rings = |a: f64, b: f64, offset: f64| -> Vec<Vec<Piece>> {
        let corner = (corner - r - offset).max(0.0);
        let inner = a.min(b);
        let count = (inner / step - 1e-9).ceil().max(0.0) as usize;
        (0..=count)
            .rev()
            .map(|k| {
                let d = if count == 0 {
                    0.0
                } else {
                    inner * k as f64 / count as f64
                };
                let c = if k == 0 { corner } else { 0.0 };
                rectangle_ring(a - d, b - d, c, clockwise)
            })
            .collect()
    };
    let outline = vec![rectangle_ring(
        finish_a,
        finish_b,
        (corner - r).max(0.0),
        clockwise,
    )];
    mill(
        at,
        kernel,
        frame,
        milling,
        rings(rough_a, rough_b, fal),
        rings(finish_a, finish_b, 0.0),
        outline,
    )
}

/// Mills a pocket: roughing clears the levels with `rough`; finishing clears the bottom with
/// `bottom` (when FALD left some) and goes round `outline` at every level.
fn mill(
    at: &mut Place,
    kernel: &mut Kernel,
    frame: Frame,
    milling: Milling,
    rough: Vec<Vec<Piece>>,
    bottom: Vec<Vec<Piece>>,
    outline: Vec<Vec<Piece>>,
) -> Result<(), Alarm> {
    let feed_mode = kernel.feed_setting().0;
    let mut pocket = Pocket {
        at,
        kernel,
        frame,
        milling,
        feed_mode,
        here: (0.0, 0.0),
    };
    pocket.approach()?;
    let depth = pocket.milling.levels.depth;
    if !pocket.milling.finishing {
        pocket.clear(depth + pocket.milling.bottom_allowance, &rough)?;
        return pocket.retract();
    }
    // Finishing: the pocket is open down to the bottom allowance; the tool goes in vertically.
    pocket.milling.insertion = 1;
    if pocket.milling.bottom_allowance > 0.0 {
        let step_down = std::mem::replace(&mut pocket.milling.step_down, 0.0);
        pocket.clear(depth, &bottom)?;
        pocket.milling.step_down = step_down;
    }
    pocket.clear(depth, &outline)?;
    pocket.retract()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rings_are_shared_out_evenly_up_to_the_outline() {
        assert_eq!(ring_radii(10.0, 5.0), vec![5.0, 10.0]);
        assert_eq!(ring_radii(11.0, 5.0), vec![11.0 / 3.0, 22.0 / 3.0, 11.0]);
        assert!(ring_radii(0.0, 5.0).is_empty());
    }

    #[test]
    fn a_rectangle_ring_goes_round_and_back_both_ways() {
        let ccw = rectangle_ring(10.0, 5.0, 2.0, false);
        assert_eq!(ccw.first(), Some(&Piece::Line((10.0, 0.0))));
        assert_eq!(ccw.last(), Some(&Piece::Line((10.0, 0.0))));
        // Four lines and four arcs after the first point and the way up the right side.
        assert_eq!(ccw.len(), 10);
        let cw = rectangle_ring(10.0, 5.0, 2.0, true);
        assert_eq!(cw.len(), 10);
        // Clockwise, the way from the right side's middle goes down first.
        assert_eq!(cw[1], Piece::Line((10.0, -3.0)));
        assert_eq!(cw.last(), Some(&Piece::Line((10.0, 0.0))));
    }
}
