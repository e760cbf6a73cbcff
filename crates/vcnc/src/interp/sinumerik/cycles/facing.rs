//! CYCLE61, face milling: a rectangle of the plane milled down in levels, row by row, the tool
//! starting each row outside the area.
//!
//! **Inferred** parameter list (the ShopMill/Operate form the corpus writes, e.g.
//! `CYCLE61(35.8,25.88,5,0,0,0,102,105,2,80,0.2,3000,31,0,1,11010)`; the Fundamentals
//! manual names the cycle only): RTP, RFP, SDIS, DP (absolute), the corners X0, Y0 and X1, Y1
//! (absolute), DZ the largest depth of a level, DXY the step between rows in percent of the
//! tool's diameter, UZ the allowance roughing leaves, F the feed, VARI (units 1 roughing, 2
//! finishing; tens odd: rows along the abscissa, even: along the ordinate), then three
//! parameters read and not used (the limits and the screen form's modes).
//!
//! Never: feed down inside the area (every level starts outside it).

use super::pockets::tool_radius;
use super::{machining_type, Levels, Params, Place};
use crate::alarm::Alarm;
use crate::interp::kernel::Kernel;

/// CYCLE61(RTP, RFP, SDIS, DP, X0, Y0, X1, Y1, DZ, DXY, UZ, F, VARI, ...): rows meandering across
/// the rectangle, at most DXY % of the tool's diameter apart, the tool's centre from SDIS plus its
/// radius before the area to its radius past it; levels equal and at most DZ deep, down to DP+UZ
/// (roughing) or DP in one level (finishing). Between levels the tool rapids up to the safety
/// plane and back to the first row's start.
pub(super) fn face(
    at: &mut Place,
    kernel: &mut Kernel,
    p: &Params,
    radius: Option<f64>,
) -> Result<(), Alarm> {
    let levels = Levels::read(p, None)?;
    let r = tool_radius(p, radius)?;
    let vari = p.or_zero(12).round() as i64;
    let (units, tens) = (vari % 10, vari / 10 % 10);
    if !(1..=2).contains(&units) || !(0..=4).contains(&tens) {
        return Err(machining_type(
            p,
            vari,
            "units 1 roughing or 2 finishing, tens the direction of the rows",
        ));
    }
    let percent = match p.or_zero(9) {
        v if v > 0.0 => v.min(100.0),
        _ => 50.0,
    };
    let step = 2.0 * r * percent / 100.0;
    // Rows along the abscissa (u) or the ordinate: u runs along the rows, v across them.
    let along_x = tens % 2 == 1 || tens == 0;
    let (x0, y0, x1, y1) = (
        p.length_or_zero(4),
        p.length_or_zero(5),
        p.length_or_zero(6),
        p.length_or_zero(7),
    );
    let (u_range, v_range) = if along_x {
        ((x0.min(x1), x0.max(x1)), (y0.min(y1), y0.max(y1)))
    } else {
        ((y0.min(y1), y0.max(y1)), (x0.min(x1), x0.max(x1)))
    };
    let point = |u: f64, v: f64| if along_x { (u, v) } else { (v, u) };
    let clearance = levels.safety - levels.reference;
    let (start, end) = (u_range.0 - r - clearance, u_range.1 + r);
    let width = v_range.1 - v_range.0;
    let rows = ((width / step) - 1e-9).ceil().max(0.0) as usize;
    let row_at = |k: usize| {
        if rows == 0 {
            v_range.0
        } else {
            v_range.0 + width * k as f64 / rows as f64
        }
    };
    let bottom = if units == 1 {
        levels.depth + p.length_or_zero(10).abs()
    } else {
        levels.depth
    };
    let step_down = if units == 1 {
        p.length_or_zero(8).abs()
    } else {
        0.0
    };
    let total = levels.reference - bottom;
    let count = match step_down {
        s if s > 0.0 => (total / s - 1e-9).ceil().max(1.0) as usize,
        _ => 1,
    };
    let (mode, feed) = kernel.feed_setting();
    kernel.set_feed_in(mode, p.number(11).filter(|f| *f > 0.0).or(feed));
    if at.height() < levels.retraction {
        at.rapid_height(kernel, levels.retraction)?;
    }
    at.rapid_plane(kernel, point(start, row_at(0)))?;
    at.rapid_height(kernel, levels.safety)?;
    for level in 1..=count {
        let height = levels.reference - total * level as f64 / count as f64;
        at.feed_height(kernel, height)?;
        for k in 0..=rows {
            let (from, to) = if k % 2 == 0 {
                (start, end)
            } else {
                (end, start)
            };
            if k > 0 {
                at.feed_to(kernel, point(from, row_at(k)), None)?;
            }
            at.feed_to(kernel, point(to, row_at(k)), None)?;
        }
        at.rapid_height(kernel, levels.safety)?;
        if level < count {
            at.rapid_plane(kernel, point(start, row_at(0)))?;
        }
    }
    at.rapid_height(kernel, levels.retraction)
}
