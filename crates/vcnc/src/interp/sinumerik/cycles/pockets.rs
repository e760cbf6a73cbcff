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

use super::rings::{self, Piece};
use super::{alarm, divisions, machining_type, Levels, Params, Place};
use crate::alarm::Alarm;
use crate::interp::kernel::Kernel;
use crate::interp::modal::FeedMode;

/// The parameters POCKET3 and POCKET4 share, read at their positions in each.
#[derive(Clone)]
pub(super) struct Milling {
    pub(super) levels: Levels,
    /// MID: the largest depth of a level (0: the whole depth at once).
    pub(super) step_down: f64,
    /// FAL, FALD: the allowances left on the wall and the bottom by roughing.
    pub(super) wall_allowance: f64,
    pub(super) bottom_allowance: f64,
    /// FFP1, FFD: the feeds in the plane and going in.
    pub(super) plane_feed: Option<f64>,
    pub(super) depth_feed: Option<f64>,
    /// The rings' direction: CDIR 0 (climb) or 1 (conventional) by the spindle's direction, 2
    /// (G2) or 3 (G3).
    pub(super) clockwise: bool,
    pub(super) finishing: bool,
    /// VARI's tens: 0 vertical in rapid, 1 vertical at FFD, 2 on a helix (3, POCKET3's
    /// oscillation, goes in vertically: a choice).
    pub(super) insertion: u32,
    /// MIDA: the largest step from ring to ring (0: the tool radius).
    pub(super) step_over: f64,
    /// RAD1 and DP1: the helix's radius and depth per turn.
    pub(super) helix: (f64, f64),
    pub(super) tool_radius: f64,
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
    /// SINUMERIK Operate's `_AMODE`, where the cycle's long form has it (ShopMill writes it).
    amode: Option<usize>,
}

/// The radius of the edge in force: alarm 61000 without one (D0, no tool), 61117 when it is
/// not above 0.
pub(super) fn tool_radius(p: &Params, radius: Option<f64>) -> Result<f64, Alarm> {
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
    Ok(tool_radius)
}

/// The milling direction CDIR at `index`: true for clockwise. 0 climbs, 1 is conventional
/// (by the spindle's direction: climbing inside a pocket with M3 goes counter-clockwise), 2
/// G2, 3 G3; anything else is alarm 61109.
pub(super) fn direction(p: &Params, index: usize, at: &Place) -> Result<bool, Alarm> {
    match p.or_zero(index).round() as i64 {
        0 => Ok(!at.clockwise),
        1 => Ok(at.clockwise),
        2 => Ok(true),
        3 => Ok(false),
        cdir => Err(alarm(
            61109,
            p.span,
            format_args!("{}: parameter CDIR defined incorrectly: {cdir}", p.name()),
        )
        .with_help("CDIR: 0 climb, 1 conventional, 2 G2, 3 G3")),
    }
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
    amode: None,
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
    amode: Some(22),
};

/// How SINUMERIK Operate's long form of a pocket cycle (the one ShopMill writes, 25
/// parameters for POCKET4: `POCKET4(10,0,2,15,40,50,51.75,2,0.1,0.1,2000,2000,0,21,50,9,15,6,1,
/// 0,1,2,10100,111,111)`) reads the parameters the short form gives in millimetres.
///
/// **Inferred** (the cycles manual's text for `_AMODE` is not among vcnc's sources, and no
/// description of the Operate form was found): `_AMODE` of five digits (ten thousands 1)
/// marks the long form; its hundreds digit 1 makes DP the depth below RFP (the incremental
/// depth of ShopMill's dialogue, "Z1 inc."), 0 leaves it absolute; and the long form gives
/// MIDA in percent of the cutter's diameter, as the dialogue does. The evidence is
/// ncplot7py_user_siemens_program.MPF's own numbers: its finishing call N114 steps down MID 15,
/// the DP of the pair, so DP 15 over RFP 0 is a depth of 15, not a bottom above the top (61101);
/// its drilling calls give their incremental depth in DPR (`CYCLE81(20,0,5,,2,...)`), which
/// POCKET4 lacks; its MIDA 50 for 16 and 8 mm cutters could only be percent (50 mm is alarm
/// 61111), as CYCLE61's 80 in the same program; CYCLE61's `_AMODE` 11010 (hundreds 0) goes
/// with an absolute DP 0 under RFP 25.88.
#[derive(Clone, Copy, Default)]
struct Operate {
    relative_depth: bool,
    infeed_percent: bool,
}

impl Operate {
    fn read(p: &Params, layout: &Layout) -> Operate {
        let Some(amode) = layout.amode.and_then(|i| p.number(i)) else {
            return Operate::default();
        };
        let amode = amode.round() as i64;
        if amode / 10_000 % 10 != 1 {
            return Operate::default();
        }
        Operate {
            relative_depth: amode / 100 % 10 == 1,
            infeed_percent: true,
        }
    }
}

impl Milling {
    fn read(
        p: &Params,
        at: &Place,
        layout: &Layout,
        radius: Option<f64>,
    ) -> Result<Milling, Alarm> {
        let operate = Operate::read(p, layout);
        // DP read as the depth below RFP, in the place of the DPR the short form lacks.
        let levels = Levels::read(p, operate.relative_depth.then_some(3))?;
        let tool_radius = tool_radius(p, radius)?;
        let vari = p.or_zero(layout.vari).round() as i64;
        let (units, tens) = (vari % 10, vari / 10 % 10);
        if !(1..=2).contains(&units) || !(0..=3).contains(&tens) {
            return Err(machining_type(
                p,
                vari,
                "units 1 roughing or 2 finishing; tens 0 or 1 vertical, 2 helical insertion",
            ));
        }
        let clockwise = direction(p, layout.cdir, at)?;
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
        let mida = match operate.infeed_percent {
            true => p.or_zero(layout.mida).abs() / 100.0 * 2.0 * tool_radius,
            false => p.length_or_zero(layout.mida).abs(),
        };
        let step_over = match mida {
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
        let count = divisions(total, self.step_down);
        (1..=count)
            .map(|k| self.levels.reference - total * k as f64 / count as f64)
            .collect()
    }
}

/// A cycle's own coordinates in the plane: its centre and its turn.
pub(super) struct Frame {
    pub(super) centre: (f64, f64),
    pub(super) cos: f64,
    pub(super) sin: f64,
}

impl Frame {
    /// The frame at `centre` turned `degrees` about it.
    pub(super) fn new(centre: (f64, f64), degrees: f64) -> Frame {
        let (sin, cos) = degrees.to_radians().sin_cos();
        Frame { centre, cos, sin }
    }

    fn point(&self, (u, v): (f64, f64)) -> (f64, f64) {
        (
            self.centre.0 + u * self.cos - v * self.sin,
            self.centre.1 + u * self.sin + v * self.cos,
        )
    }
}

/// A pocket being milled: where, how, and the moves.
pub(super) struct Pocket<'a> {
    at: &'a mut Place,
    kernel: &'a mut Kernel,
    frame: Frame,
    pub(super) milling: Milling,
    /// Where the tool goes in, in the pocket's coordinates (a pocket's centre, a circular
    /// slot's start).
    entry: (f64, f64),
    /// The feed mode of the call (FFP1 and FFD are read in it).
    feed_mode: FeedMode,
    /// Where the tool is in the pocket's coordinates.
    here: (f64, f64),
}

impl Pocket<'_> {
    /// The pocket of `frame` milled as `milling` says, going in at `entry`.
    pub(super) fn new<'a>(
        at: &'a mut Place,
        kernel: &'a mut Kernel,
        frame: Frame,
        milling: Milling,
        entry: (f64, f64),
    ) -> Pocket<'a> {
        let feed_mode = kernel.feed_setting().0;
        Pocket {
            at,
            kernel,
            frame,
            milling,
            entry,
            feed_mode,
            here: entry,
        }
    }

    fn set_feed(&mut self, feed: Option<f64>) {
        if let Some(feed) = feed {
            self.kernel.set_feed_in(self.feed_mode, Some(feed));
        }
    }

    /// Up to the retraction plane when below it (not above: the tool comes over the pocket at
    /// the height it has), over the way in, and down to the safety plane.
    pub(super) fn approach(&mut self) -> Result<(), Alarm> {
        let levels = self.milling.levels;
        if self.at.height() < levels.retraction {
            self.at.rapid_height(self.kernel, levels.retraction)?;
        }
        self.at
            .rapid_plane(self.kernel, self.frame.point(self.entry))?;
        self.here = self.entry;
        self.at.rapid_height(self.kernel, levels.safety)
    }

    /// Goes in at the way in from `top` (cut or open) down to `height`.
    fn go_in(&mut self, top: f64, height: f64) -> Result<(), Alarm> {
        self.line(self.entry)?;
        self.set_feed(self.milling.depth_feed);
        let result = match self.milling.insertion {
            0 => self.at.rapid_height(self.kernel, height),
            2 => self.helix(top, height),
            _ => self.at.feed_height(self.kernel, height),
        };
        self.set_feed(self.milling.plane_feed);
        result
    }

    /// A helix about the way in of radius RAD1 from `top` to `height`, DP1 or less per turn,
    /// then a full circle at `height` and back to the way in.
    fn helix(&mut self, top: f64, height: f64) -> Result<(), Alarm> {
        let (radius, per_turn) = self.milling.helix;
        let start = self.frame.point((self.entry.0 + radius, self.entry.1));
        let centre = self.frame.point(self.entry);
        let clockwise = self.milling.clockwise;
        self.at.rapid_height(self.kernel, top)?;
        self.at.feed_to(self.kernel, start, None)?;
        let turns = divisions(top - height, per_turn) as u32;
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
    fn line(&mut self, to: (f64, f64)) -> Result<(), Alarm> {
        if same(to, self.here) {
            return Ok(());
        }
        self.here = to;
        self.at.feed_to(self.kernel, self.frame.point(to), None)
    }

    /// Cuts `ring` in the milling direction from where the tool is.
    fn cut(&mut self, ring: &[Piece]) -> Result<(), Alarm> {
        for piece in rings::oriented(ring, self.milling.clockwise) {
            match piece {
                Piece::Line(to) => self.line(to)?,
                Piece::Arc { to, centre, ccw } => {
                    if same(to, self.here) {
                        continue;
                    }
                    self.here = to;
                    let (to, centre) = (self.frame.point(to), self.frame.point(centre));
                    self.at.arc_to(self.kernel, to, centre, !ccw, None, 0)?;
                }
            }
        }
        Ok(())
    }

    /// Clears every level down to `bottom` with `rings` (inside out), going in from the top.
    pub(super) fn clear(&mut self, bottom: f64, rings: &[Vec<Piece>]) -> Result<(), Alarm> {
        let mut top = self.milling.levels.safety;
        for height in self.milling.heights(bottom) {
            self.go_in(top, height)?;
            for ring in rings {
                self.cut(ring)?;
            }
            // Up by the clearance and back over the way in, inside what was cut, for the next
            // level's way in.
            top = height + self.clearance();
            self.at.rapid_height(self.kernel, top)?;
            self.at
                .rapid_plane(self.kernel, self.frame.point(self.entry))?;
            self.here = self.entry;
        }
        Ok(())
    }

    /// The height above a cut level the tool moves at: the safety clearance (0.1 mm when 0,
    /// a choice).
    fn clearance(&self) -> f64 {
        let levels = &self.milling.levels;
        (levels.safety - levels.reference).max(0.1)
    }

    /// Roughing clears the levels with `rough`; finishing clears the bottom with `bottom` (when
    /// FALD left some) and goes round `outline` at every level.
    pub(super) fn mill(
        &mut self,
        rough: &[Vec<Piece>],
        bottom: &[Vec<Piece>],
        outline: &[Vec<Piece>],
    ) -> Result<(), Alarm> {
        let depth = self.milling.levels.depth;
        if !self.milling.finishing {
            return self.clear(depth + self.milling.bottom_allowance, rough);
        }
        // Finishing: the pocket is open down to the bottom allowance; the tool goes in
        // vertically.
        self.milling.insertion = 1;
        if self.milling.bottom_allowance > 0.0 {
            let step_down = std::mem::replace(&mut self.milling.step_down, 0.0);
            self.clear(depth, bottom)?;
            self.milling.step_down = step_down;
        }
        self.clear(depth, outline)
    }

    /// LONGHOLE's levels: at each, in at FFD at the end the tool is at, then along the hole's
    /// centre line (from `-half` to `half`) at FFP1 to the other end.
    pub(super) fn oscillate(&mut self, bottom: f64, half: f64) -> Result<(), Alarm> {
        for height in self.milling.heights(bottom) {
            self.set_feed(self.milling.depth_feed);
            self.at.feed_height(self.kernel, height)?;
            self.set_feed(self.milling.plane_feed);
            let other = (-self.here.0.signum() * half, 0.0);
            self.line(if half > 0.0 { other } else { self.here })?;
        }
        Ok(())
    }

    pub(super) fn retract(&mut self) -> Result<(), Alarm> {
        self.at
            .rapid_height(self.kernel, self.milling.levels.retraction)
    }
}

fn same(a: (f64, f64), b: (f64, f64)) -> bool {
    (a.0 - b.0).abs() < 1e-9 && (a.1 - b.1).abs() < 1e-9
}

/// POCKET4(RTP, RFP, SDIS, DP, PRAD, PA, PO, MID, FAL, FALD, FFP1, FFD, CDIR, VARI, MIDA, AP1,
/// AD, RAD1, DP1): a circular pocket of radius PRAD about (PA, PO), DP deep (absolute; in
/// Operate's long form as `_AMODE` says: [`Operate`]). AP1 and AD (a pocket milled before) are
/// read but not used: the cycle clears from the centre (choice).
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
    let step = milling.step_over;
    let frame = Frame::new((p.length_or_zero(5), p.length_or_zero(6)), 0.0);
    let mut pocket = Pocket::new(at, kernel, frame, milling, (0.0, 0.0));
    pocket.approach()?;
    pocket.mill(
        &rings::circles(rough, step),
        &rings::circles(finish, step),
        &[rings::circle(finish)],
    )?;
    pocket.retract()
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
    let fal = milling.wall_allowance;
    let (finish_a, finish_b) = (length / 2.0 - r, width / 2.0 - r);
    let (rough_a, rough_b) = (finish_a - fal, finish_b - fal);
    if rough_a < 0.0 || rough_b < 0.0 {
        return Err(alarm(
            61105,
            p.span,
            format_args!("POCKET3: cutter radius too large: {r} for a pocket {length} × {width} with FAL {fal}"),
        ));
    }
    let step = milling.step_over;
    let frame = Frame::new((p.length_or_zero(7), p.length_or_zero(8)), p.or_zero(9));
    let finish_corner = (corner - r).max(0.0);
    let rough_corner = (finish_corner - fal).max(0.0);
    let mut pocket = Pocket::new(at, kernel, frame, milling, (0.0, 0.0));
    pocket.approach()?;
    pocket.mill(
        &rings::rectangles(rough_a, rough_b, rough_corner, step),
        &rings::rectangles(finish_a, finish_b, finish_corner, step),
        &[rings::rectangle(finish_a, finish_b, finish_corner)],
    )?;
    pocket.retract()
}

#[cfg(test)]
mod tests {
    use crate::machine::ToolEdge;
    use crate::{Machine, ProfileName, SegmentKind};

    /// The ends of the moves `text` makes after its first three (tool change and start), with
    /// 'R' rapid, 'L' line, 'A' arc; and its alarm.
    fn run(text: &str) -> (Vec<(char, [f64; 3])>, Option<crate::Alarm>) {
        let mut machine = Machine::default()
            .with_profile(ProfileName::Sinumerik)
            .unwrap();
        machine.tools.push(ToolEdge {
            t: 1,
            name: None,
            d: 1,
            tool_type: 120,
            length: 0.0,
            length2: 0.0,
            length3: 0.0,
            radius: 5.0,
            teeth: Some(4),
        });
        let mut moves = Vec::new();
        let mut alarm = None;
        let start = "T1 M6 D1\nG17 G90 F500 S3000 M3\nG0 X0 Y0 Z10\n";
        for item in crate::interp::sinumerik::run_str(&format!("{start}{text}\nM30\n"), &machine) {
            match item {
                Ok(crate::Item::Segment(s)) => {
                    let kind = match s.kind {
                        SegmentKind::Rapid { .. } => 'R',
                        SegmentKind::Line { .. } => 'L',
                        SegmentKind::Arc { .. } => 'A',
                        _ => continue,
                    };
                    let to = s.motion().expect("a move").to.0;
                    moves.push((kind, [to[0], to[1], to[2]]));
                }
                Err(a) => alarm = alarm.or(Some(a)),
                _ => {}
            }
        }
        (moves.split_off(1.min(moves.len())), alarm)
    }

    #[test]
    fn shopmills_long_form_reads_dp_as_a_depth_by_its_amode() {
        // ShopMill's POCKET4 with _AMODE 10100 (hundreds 1): DP 6 is 6 below RFP 0, so the
        // finishing (VARI 12, G2) of a pocket of radius 15 with the 10 mm mill goes in at the
        // centre at -3 and -6 (MID 3), out to 15 - 5 = 10, round in two halves, up by SDIS 1 and
        // back over the centre; then up to RTP 2. Worked by hand as the short form's
        // POCKET4(2,0,1,-6,15,0,0,3,0,0,800,300,2,12) (tests/it/sinumerik_cycles.rs).
        let long = "POCKET4(2,0,1,6,15,0,0,3,0,0,800,300,2,12,50,0,0,0,0,0,1,2,10100,111,111)";
        let (got, alarm) = run(long);
        assert!(alarm.is_none(), "{alarm:?}");
        let mut wanted = vec![('R', [0.0, 0.0, 1.0])];
        for z in [-3.0, -6.0] {
            wanted.extend([
                ('L', [0.0, 0.0, z]),
                ('L', [10.0, 0.0, z]),
                ('A', [-10.0, 0.0, z]),
                ('A', [10.0, 0.0, z]),
                ('R', [10.0, 0.0, z + 1.0]),
                ('R', [0.0, 0.0, z + 1.0]),
            ]);
        }
        wanted.push(('R', [0.0, 0.0, 2.0]));
        assert_eq!(got, wanted);
        // Hundreds 0: DP 6 is absolute, above RFP 0: alarm 61101 as in the short form.
        let absolute = long.replace("10100", "10000");
        let alarm = run(&absolute)
            .1
            .expect("the depth 6 is above the reference plane 0");
        assert!(alarm.message.contains("61101"), "{}", alarm.message);
    }

    #[test]
    fn shopmills_long_form_gives_mida_in_percent_of_the_cutter() {
        // Roughing (VARI 11) of radius 15 with the 10 mm mill, MIDA 50: 5 mm from ring to ring
        // (50 % of 10), the rings of the short form with MIDA 5. In the short form 50 mm would
        // be alarm 61111 (more than the diameter).
        let long = run("POCKET4(2,0,1,6,15,0,0,3,0,0,800,300,2,11,50,0,0,0,0,0,1,2,10100,111,111)");
        let short = run("POCKET4(2,0,1,-6,15,0,0,3,0,0,800,300,2,11,5)");
        assert!(
            long.1.is_none() && short.1.is_none(),
            "{:?} {:?}",
            long.1,
            short.1
        );
        assert_eq!(long.0, short.0);
        let alarm = run("POCKET4(2,0,1,-6,15,0,0,3,0,0,800,300,2,11,50)").1;
        assert!(alarm.is_some_and(|a| a.message.contains("61111")));
    }
}
