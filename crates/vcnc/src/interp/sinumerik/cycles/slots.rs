//! The slot cycles: SLOT1 (slots on a circle, their length radial), SLOT2 (circumferential
//! slots along a circle) and LONGHOLE (elongated holes as wide as the tool, radial), each NUM of
//! them about (CPA, CPO), the first at STA1 degrees, each next INDA on (0: the circle shared
//! out evenly).
//!
//! A slot is milled as a pocket (`pockets.rs`): levels at most MID deep, going in vertically at
//! FFD, rings at FFP1 from the slot's centre line out to its outline (a rectangle whose corners
//! are half its width, or a ring sector with round ends); between slots the tool rapids up to
//! the retraction plane. **Inferred**: RAD reaches the middle of a SLOT1 slot and of an
//! elongated hole (the manual's pictures are not in the seeds).
//!
//! Never: cut outside a slot's outline less the tool radius.

use super::pockets::{Frame, Milling, Pocket};
use super::rings::{self, polar};
use super::{alarm, machining_type, too_many, Levels, Params, Place, MAX_DIVISIONS};
use crate::alarm::Alarm;
use crate::interp::kernel::Kernel;

/// Where each parameter of SLOT1 and SLOT2 is; LONGHOLE lacks WID and those after MID.
struct Layout {
    num: usize,
    /// LENG (SLOT1, LONGHOLE) or AFSL (SLOT2).
    size: usize,
    wid: Option<usize>,
    cpa: usize,
    rad: usize,
    sta1: usize,
    inda: usize,
    ffd: usize,
    ffp1: usize,
    mid: usize,
}

const SLOT: Layout = Layout {
    num: 5,
    size: 6,
    wid: Some(7),
    cpa: 8,
    rad: 10,
    sta1: 11,
    inda: 12,
    ffd: 13,
    ffp1: 14,
    mid: 15,
};

const LONGHOLE: Layout = Layout {
    num: 5,
    size: 6,
    wid: None,
    cpa: 7,
    rad: 9,
    sta1: 10,
    inda: 11,
    ffd: 12,
    ffp1: 13,
    mid: 14,
};

/// SLOT1, SLOT2 and LONGHOLE's shared data: the slots' angles, the circle, the width.
struct Slots {
    angles: Vec<f64>,
    centre: (f64, f64),
    radius: f64,
    /// The slot's width (LONGHOLE: the tool's diameter).
    width: f64,
    /// LENG, or SLOT2's AFSL in degrees.
    size: f64,
    milling: Milling,
    /// VARI 0: roughing, then finishing.
    complete: bool,
    /// MIDF and FFP2: the finishing's depth per level (0: at once) and feed (0: FFP1).
    finishing: (f64, Option<f64>),
}

impl Slots {
    fn read(p: &Params, at: &Place, layout: &Layout, radius: Option<f64>) -> Result<Slots, Alarm> {
        let levels = Levels::read(p, Some(4))?;
        let tool_radius = super::pockets::tool_radius(p, radius)?;
        let (units, clockwise) = match layout.wid {
            Some(_) => (variant(p, 18)?, super::pockets::direction(p, 16, at)?),
            None => (1, at.clockwise),
        };
        let width = layout
            .wid
            .map_or(2.0 * tool_radius, |i| p.length_or_zero(i).abs());
        if 2.0 * tool_radius > width + 1e-9 {
            return Err(alarm(
                61105,
                p.span,
                format_args!(
                    "{}: cutter radius too large: {tool_radius} for a slot {width} wide",
                    p.name()
                ),
            ));
        }
        let number = p.or_zero(layout.num).round();
        if number > MAX_DIVISIONS as f64 {
            return Err(too_many(p, number, "slots"));
        }
        let step = match p.or_zero(layout.inda) {
            0.0 if number > 0.0 => 360.0 / number,
            step => step,
        };
        if number < 1.0 || (number - 1.0) * step.abs() >= 360.0 - 1e-9 {
            return Err(alarm(
                61106,
                p.span,
                format_args!("{}: number or distance of circular elements: {number} slots {step} degrees apart", p.name()),
            )
            .with_help("give NUM as 1 or more, and INDA so that the slots fit on the circle"));
        }
        let start = p.or_zero(layout.sta1);
        let feed = |index: usize| p.number(index).filter(|f| *f > 0.0);
        let milling = Milling {
            levels,
            step_down: p.length_or_zero(layout.mid).abs(),
            wall_allowance: if layout.wid.is_some() {
                p.length_or_zero(17).abs()
            } else {
                0.0
            },
            bottom_allowance: 0.0,
            plane_feed: feed(layout.ffp1),
            depth_feed: feed(layout.ffd),
            clockwise,
            finishing: units == 2,
            insertion: 1,
            step_over: tool_radius,
            helix: (0.0, 0.0),
            tool_radius,
        };
        let finishing = match layout.wid {
            Some(_) => (p.length_or_zero(19).abs(), feed(20)),
            None => (0.0, None),
        };
        Ok(Slots {
            angles: (0..number as usize)
                .map(|k| start + k as f64 * step)
                .collect(),
            centre: (
                p.length_or_zero(layout.cpa),
                p.length_or_zero(layout.cpa + 1),
            ),
            radius: p.length_or_zero(layout.rad).abs(),
            width,
            size: p.length_or_zero(layout.size).abs(),
            milling,
            complete: units == 0,
            finishing,
        })
    }

    /// Radial slots (SLOT1, LONGHOLE) whose inner ends cross the centre or meet: alarm 61104.
    fn check_inner_ends(&self, p: &Params) -> Result<(), Alarm> {
        let inner = self.radius - self.size / 2.0;
        let chord = 2.0 * inner * (self.spacing() / 2.0).to_radians().sin();
        if self.angles.len() > 1 && (inner < 0.0 || chord < self.width) {
            return Err(violation(p, "their inner ends meet"));
        }
        Ok(())
    }

    /// The coordinates of the radial slot at `angle`: its middle, its length along the radius.
    fn radial_frame(&self, angle: f64) -> Frame {
        let (x, y) = polar(self.radius, angle);
        Frame::new((self.centre.0 + x, self.centre.1 + y), angle)
    }

    /// The smallest angle between two slots next to each other (360 for one slot).
    fn spacing(&self) -> f64 {
        match self.angles.as_slice() {
            [first, second, ..] => (second - first).abs(),
            _ => 360.0,
        }
    }

    /// Mills every slot with `rings(offset from the centre line)`: the rough ones, then (VARI
    /// 0 or 2) the finishing outline.
    fn mill(
        &self,
        at: &mut Place,
        kernel: &mut Kernel,
        frame_of: impl Fn(f64) -> Frame,
        entry: (f64, f64),
        rings: impl Fn(f64) -> Vec<Vec<rings::Piece>>,
    ) -> Result<(), Alarm> {
        let r = self.milling.tool_radius;
        let finish = self.width / 2.0 - r;
        let rough = finish - self.milling.wall_allowance;
        for &angle in &self.angles {
            let mut milling = self.milling.clone();
            if !milling.finishing {
                let mut pocket = Pocket::new(at, kernel, frame_of(angle), milling.clone(), entry);
                pocket.approach()?;
                pocket.clear(milling.levels.depth, &rings(rough))?;
                pocket.retract()?;
            }
            if milling.finishing || self.complete {
                milling.finishing = true;
                milling.step_down = self.finishing.0;
                milling.plane_feed = self.finishing.1.or(milling.plane_feed);
                let outline = rings(finish).pop().unwrap_or_default();
                let mut pocket = Pocket::new(at, kernel, frame_of(angle), milling, entry);
                pocket.approach()?;
                pocket.mill(&[], &[], &[outline])?;
                pocket.retract()?;
            }
        }
        Ok(())
    }
}

/// VARI of a slot: 0 complete, 1 roughing, 2 finishing; anything else is alarm 61002.
fn variant(p: &Params, index: usize) -> Result<i64, Alarm> {
    match p.or_zero(index).round() as i64 {
        units @ 0..=2 => Ok(units),
        vari => Err(machining_type(
            p,
            vari,
            "0 complete, 1 roughing, 2 finishing",
        )),
    }
}

/// The contour violation of slots or elongated holes that overlap or cross the centre.
fn violation(p: &Params, what: &str) -> Alarm {
    alarm(
        61104,
        p.span,
        format_args!("{}: contour violation of the slots: {what}", p.name()),
    )
    .with_help("make RAD larger, the slots shorter or narrower, or INDA larger")
}

/// SLOT1(RTP, RFP, SDIS, DP, DPR, NUM, LENG, WID, CPA, CPO, RAD, STA1, INDA, FFD, FFP1, MID,
/// CDIR, FAL, VARI, MIDF, FFP2, SSF): NUM slots LENG long and WID wide, their length along
/// the radius, their middles at RAD. SSF (the finishing speed) is read and not used.
pub(super) fn radial(
    at: &mut Place,
    kernel: &mut Kernel,
    p: &Params,
    radius: Option<f64>,
) -> Result<(), Alarm> {
    let slots = Slots::read(p, at, &SLOT, radius)?;
    slots.check_inner_ends(p)?;
    let half = slots.size / 2.0 - slots.milling.tool_radius;
    if half < slots.width / 2.0 - slots.milling.tool_radius {
        return Err(violation(p, "LENG is smaller than WID"));
    }
    let step = slots.milling.step_over;
    let frame_of = |angle: f64| slots.radial_frame(angle);
    // The rings of a slot: rectangles whose corners are their half width, about its middle.
    let rings = |b: f64| {
        let a = half - (slots.width / 2.0 - slots.milling.tool_radius - b);
        rings::rectangles(a, b, b, step)
    };
    slots.mill(at, kernel, frame_of, (0.0, 0.0), rings)
}

/// SLOT2(RTP, RFP, SDIS, DP, DPR, NUM, AFSL, WID, CPA, CPO, RAD, STA1, INDA, FFD, FFP1, MID,
/// CDIR, FAL, VARI, MIDF, FFP2, SSF): NUM slots WID wide along the circle of radius RAD, each
/// AFSL degrees long (of the centre line), going in at its start.
pub(super) fn circumferential(
    at: &mut Place,
    kernel: &mut Kernel,
    p: &Params,
    radius: Option<f64>,
) -> Result<(), Alarm> {
    let slots = Slots::read(p, at, &SLOT, radius)?;
    if slots.radius <= slots.width / 2.0 {
        return Err(violation(p, "RAD is not larger than half of WID"));
    }
    let cap = 2.0 * (slots.width / 2.0 / slots.radius).asin().to_degrees();
    if slots.size + cap > slots.spacing() {
        return Err(violation(p, "they overlap along the circle"));
    }
    let step = slots.milling.step_over;
    let (radius, length) = (slots.radius, slots.size);
    // In the circle's coordinates turned to the slot's start: the arc from 0 to AFSL degrees.
    let frame_of = |angle: f64| Frame::new(slots.centre, angle);
    let rings = |outer: f64| {
        let mut all = vec![rings::sector(radius, 0.0, length, 0.0)];
        all.extend(
            rings::steps(outer, step)
                .into_iter()
                .map(|e| rings::sector(radius, 0.0, length, e)),
        );
        all
    };
    slots.mill(at, kernel, frame_of, (radius, 0.0), rings)
}

/// LONGHOLE(RTP, RFP, SDIS, DP, DPR, NUM, LENG, CPA, CPO, RAD, STA1, INDA, FFD, FFP1, MID):
/// NUM elongated holes as wide as the tool, LENG long along the radius, their middles at RAD:
/// each level goes in at FFD at one end and along the hole at FFP1 to the other, the next
/// level from there (the oscillating infeed of the cycles manual).
pub(super) fn elongated(
    at: &mut Place,
    kernel: &mut Kernel,
    p: &Params,
    radius: Option<f64>,
) -> Result<(), Alarm> {
    let slots = Slots::read(p, at, &LONGHOLE, radius)?;
    let half = slots.size / 2.0 - slots.milling.tool_radius;
    if half < 0.0 {
        return Err(violation(p, "LENG is shorter than the tool's diameter"));
    }
    slots.check_inner_ends(p)?;
    for &angle in &slots.angles {
        let frame = slots.radial_frame(angle);
        let mut pocket = Pocket::new(at, kernel, frame, slots.milling.clone(), (-half, 0.0));
        pocket.approach()?;
        pocket.oscillate(slots.milling.levels.depth, half)?;
        pocket.retract()?;
    }
    Ok(())
}
