//! The spigot cycles: CYCLE76 (rectangular spigot) and CYCLE77 (circular spigot), milled from
//! outside: the material is around the outline, the tool goes round it in rings from the
//! blank's size in to the spigot's.
//!
//! Parameters (cycles manual; **inferred** where marked): CYCLE76(RTP, RFP, SDIS, DP, DPR, LENG,
//! WID, CRAD, PA, PO, STA, MID, FAL, FALD, FFP1, FFD, CDIR, VARI, AP1, AP2) and CYCLE77(RTP,
//! RFP, SDIS, DP, DPR, PRAD, PA, PO, MID, FAL, FALD, FFP1, FFD, CDIR, VARI, AP1): the spigot
//! LENG × WID with corners CRAD (CYCLE77: of diameter PRAD, **inferred**: the manual's word is
//! the diameter) about (PA, PO), its length at STA degrees; the blank AP1 × AP2 (CYCLE77: of
//! diameter AP1; 0: as large as the spigot, one ring).
//!
//! vcnc's path (**choice**, the manual gives the sequence only): each level (at most MID deep)
//! starts outside the blank, SDIS plus the tool radius beyond its right side, feeds down there
//! at FFD and in to the first ring; the rings are the outline's outward offsets from the
//! blank's size in to FAL plus the tool radius, at most the tool radius apart, at FFP1; CDIR 0
//! climbs (clockwise with M3), 1 is conventional, 2 G2, 3 G3. Finishing (VARI 2) goes round
//! once at the tool radius per level.
//!
//! Never: feed down where the blank is.

use super::pockets::{direction, tool_radius, Frame, Milling, Pocket};
use super::rings::{self, Piece};
use super::{alarm, machining_type, Levels, Params, Place};
use crate::alarm::Alarm;
use crate::interp::kernel::Kernel;

/// Where the parameters after the spigot's size are.
pub(super) struct Layout {
    pub(super) pa: usize,
    pub(super) sta: Option<usize>,
    pub(super) mid: usize,
}

/// The milling of a spigot and the offsets of its rings from the outline, outside in.
pub(super) fn milling(
    p: &Params,
    at: &Place,
    layout: &Layout,
    radius: Option<f64>,
    blank_extra: f64,
) -> Result<(Milling, Vec<f64>), Alarm> {
    let levels = Levels::read(p, Some(4))?;
    let r = tool_radius(p, radius)?;
    let m = layout.mid;
    let vari = p.or_zero(m + 6).round() as i64;
    if !(1..=2).contains(&(vari % 10)) {
        return Err(machining_type(p, vari, "1 roughing, 2 finishing"));
    }
    // Climbing round the outside of a contour with M3 goes clockwise: CDIR 0 and 1 read the
    // other way round from a pocket's (2 and 3 are G2 and G3 for both).
    let pocket_direction = direction(p, m + 5, at)?;
    let clockwise = if p.or_zero(m + 5).round() < 2.0 {
        !pocket_direction
    } else {
        pocket_direction
    };
    let finishing = vari % 10 == 2;
    let wall = p.length_or_zero(m + 1).abs();
    let feed = |index: usize| p.number(index).filter(|f| *f > 0.0);
    let milling = Milling {
        levels,
        step_down: p.length_or_zero(m).abs(),
        wall_allowance: wall,
        bottom_allowance: if finishing {
            0.0
        } else {
            p.length_or_zero(m + 2).abs()
        },
        plane_feed: feed(m + 3),
        depth_feed: feed(m + 4),
        clockwise,
        finishing: false,
        insertion: 1,
        step_over: r,
        helix: (0.0, 0.0),
        tool_radius: r,
    };
    let offsets = if finishing {
        vec![r]
    } else {
        let inner = r + wall;
        let mut offsets: Vec<f64> = rings::steps(blank_extra, r)
            .into_iter()
            .rev()
            .map(|e| inner + e)
            .collect();
        offsets.push(inner);
        offsets
    };
    Ok((milling, offsets))
}

/// Mills the spigot of `frame` with `ring(offset)` at each of `offsets`, going in at `entry`.
pub(super) fn mill(
    at: &mut Place,
    kernel: &mut Kernel,
    frame: Frame,
    milling: Milling,
    offsets: &[f64],
    entry: (f64, f64),
    ring: impl Fn(f64) -> Vec<Piece>,
) -> Result<(), Alarm> {
    let bottom = milling.levels.depth + milling.bottom_allowance;
    let rings: Vec<_> = offsets.iter().map(|&o| ring(o)).collect();
    let mut spigot = Pocket::new(at, kernel, frame, milling, entry);
    spigot.approach()?;
    spigot.clear(bottom, &rings)?;
    spigot.retract()
}

/// CYCLE76: a rectangular spigot (see the module's doc).
pub(super) fn rectangular(
    at: &mut Place,
    kernel: &mut Kernel,
    p: &Params,
    radius: Option<f64>,
) -> Result<(), Alarm> {
    const LAYOUT: Layout = Layout {
        pa: 8,
        sta: Some(10),
        mid: 11,
    };
    let (a, b) = (
        p.length_or_zero(5).abs() / 2.0,
        p.length_or_zero(6).abs() / 2.0,
    );
    let corner = p.length_or_zero(7).abs();
    if corner > a.min(b) {
        return Err(alarm(
            61113,
            p.span,
            format_args!("CYCLE76: parameter CRAD for the corner radius too large: {corner}"),
        ));
    }
    let blank = (
        p.length_or_zero(18).abs() / 2.0,
        p.length_or_zero(19).abs() / 2.0,
    );
    let extra = (blank.0 - a).max(blank.1 - b).max(0.0);
    let (milling, offsets) = milling(p, at, &LAYOUT, radius, extra)?;
    let frame = Frame::new(
        (p.length_or_zero(LAYOUT.pa), p.length_or_zero(LAYOUT.pa + 1)),
        LAYOUT.sta.map_or(0.0, |i| p.or_zero(i)),
    );
    let clearance = milling.levels.safety - milling.levels.reference;
    let entry = (a + offsets[0] + milling.tool_radius + clearance, 0.0);
    let ring = |o: f64| rings::rectangle(a + o, b + o, corner + o);
    mill(at, kernel, frame, milling, &offsets, entry, ring)
}

/// CYCLE77: a circular spigot (see the module's doc).
pub(super) fn circular(
    at: &mut Place,
    kernel: &mut Kernel,
    p: &Params,
    radius: Option<f64>,
) -> Result<(), Alarm> {
    const LAYOUT: Layout = Layout {
        pa: 6,
        sta: None,
        mid: 8,
    };
    let spigot = p.length_or_zero(5).abs() / 2.0;
    let blank = p.length_or_zero(15).abs() / 2.0;
    let (milling, offsets) = milling(p, at, &LAYOUT, radius, (blank - spigot).max(0.0))?;
    let frame = Frame::new(
        (p.length_or_zero(LAYOUT.pa), p.length_or_zero(LAYOUT.pa + 1)),
        0.0,
    );
    let clearance = milling.levels.safety - milling.levels.reference;
    let entry = (spigot + offsets[0] + milling.tool_radius + clearance, 0.0);
    let ring = |o: f64| rings::circle(spigot + o);
    mill(at, kernel, frame, milling, &offsets, entry, ring)
}
