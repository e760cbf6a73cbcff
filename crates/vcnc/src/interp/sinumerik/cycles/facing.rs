//! Face milling: CYCLE71 (the 840D's) and CYCLE61 (ShopMill's): a rectangle of the plane milled
//! down in levels, row by row, the tool starting each row outside the area.
//!
//! CYCLE71(RTP, RFP, SDIS, DP, PA, PO, LENG, WID, STA, MID, MIDA, FDP, FALD, FFP1, VARI, FDP1)
//! as the cycles manual gives it. CYCLE61's list is **inferred** from the ShopMill/Operate
//! calls the corpus writes (`CYCLE61(35.8,25.88,5,0,0,0,102,105,2,80,0.2,3000,31,0,1,11010)`;
//! the Fundamentals manual names the cycle only): RTP, RFP, SDIS, DP (absolute), the corners
//! X0, Y0 and X1, Y1 (absolute), DZ the largest depth of a level, DXY the step between rows in
//! percent of the tool's diameter, UZ the allowance roughing leaves, F the feed, VARI (units 1
//! roughing, 2 finishing; tens odd: rows along the abscissa, even: along the ordinate), then
//! three parameters read and not used (the limits and the screen form's modes).
//!
//! Never: feed down inside the area (every level starts outside it).

use super::pockets::tool_radius;
use super::{alarm, divisions, machining_type, Levels, Params, Place};
use crate::alarm::Alarm;
use crate::interp::kernel::Kernel;

/// A face to mill, in its own coordinates: u along the rows, v across them.
struct Face {
    levels: Levels,
    /// The corner (PA, PO) the area is measured from and the area's turn; whether u is the
    /// plane's abscissa.
    corner: (f64, f64),
    cos: f64,
    sin: f64,
    along_abscissa: bool,
    /// Where each row starts and ends along u (outside the area at both ends).
    row: (f64, f64),
    /// The rows' v, in order.
    rows: Vec<f64>,
    /// The bottom of the last level and the largest depth of a level (0: one level).
    bottom: f64,
    step_down: f64,
    /// Rows alternating in direction (meander); otherwise each row from the start, the tool
    /// back over the face at the safety plane.
    meander: bool,
    feed: Option<f64>,
}

impl Face {
    /// The plane point of (u, v).
    fn point(&self, u: f64, v: f64) -> (f64, f64) {
        let (x, y) = if self.along_abscissa { (u, v) } else { (v, u) };
        (
            self.corner.0 + x * self.cos - y * self.sin,
            self.corner.1 + x * self.sin + y * self.cos,
        )
    }

    /// The heights of the levels, top first.
    fn heights(&self) -> Vec<f64> {
        let total = self.levels.reference - self.bottom;
        let count = divisions(total, self.step_down);
        (1..=count)
            .map(|k| self.levels.reference - total * k as f64 / count as f64)
            .collect()
    }

    /// Mills the face: over the first row's start, down to the safety plane; per level, down at
    /// the feed outside the area, the rows, up to the safety plane; at the end up to RTP.
    fn mill(&self, at: &mut Place, kernel: &mut Kernel) -> Result<(), Alarm> {
        let (mode, feed) = kernel.feed_setting();
        kernel.set_feed_in(mode, self.feed.or(feed));
        let levels = &self.levels;
        let (start, end) = self.row;
        let first = self.rows.first().copied().unwrap_or(0.0);
        if at.height() < levels.retraction {
            at.rapid_height(kernel, levels.retraction)?;
        }
        at.rapid_plane(kernel, self.point(start, first))?;
        at.rapid_height(kernel, levels.safety)?;
        let heights = self.heights();
        for (level, &height) in heights.iter().enumerate() {
            if level > 0 {
                at.rapid_plane(kernel, self.point(start, first))?;
            }
            at.feed_height(kernel, height)?;
            for (k, &v) in self.rows.iter().enumerate() {
                let backwards = self.meander && k % 2 == 1;
                let (from, to) = if backwards {
                    (end, start)
                } else {
                    (start, end)
                };
                if k > 0 && !self.meander {
                    // One direction: back over the face at the safety plane.
                    at.rapid_height(kernel, levels.safety)?;
                    at.rapid_plane(kernel, self.point(from, v))?;
                    at.feed_height(kernel, height)?;
                } else if k > 0 {
                    at.feed_to(kernel, self.point(from, v), None)?;
                }
                at.feed_to(kernel, self.point(to, v), None)?;
            }
            at.rapid_height(kernel, levels.safety)?;
        }
        at.rapid_height(kernel, levels.retraction)
    }
}

/// `count` rows shared out evenly from `first` to `last`, at most `step` apart.
fn rows(first: f64, last: f64, step: f64) -> Vec<f64> {
    let width = last - first;
    if width.abs() < 1e-9 {
        return vec![first];
    }
    let count = divisions(width, step);
    (0..=count)
        .map(|k| first + width * k as f64 / count as f64)
        .collect()
}

/// VARI's units (1 roughing, 2 finishing) and tens (the rows' direction, `0..=max_tens`).
fn variant(p: &Params, index: usize, max_tens: i64) -> Result<(i64, i64), Alarm> {
    let vari = p.or_zero(index).round() as i64;
    let (units, tens) = (vari % 10, vari / 10 % 10);
    if !(1..=2).contains(&units) || !(0..=max_tens).contains(&tens) {
        return Err(machining_type(
            p,
            vari,
            "units 1 roughing or 2 finishing, tens the direction of the rows",
        ));
    }
    Ok((units, tens))
}

/// CYCLE61(RTP, RFP, SDIS, DP, X0, Y0, X1, Y1, DZ, DXY, UZ, F, VARI, ...): rows meandering across
/// the rectangle, at most DXY % of the tool's diameter apart (0: 50 %), from its first edge to
/// its second, the tool's centre from SDIS plus its radius before the area to its radius past
/// it; levels equal and at most DZ deep, down to DP+UZ (roughing) or DP in one level
/// (finishing).
pub(super) fn shopmill(
    at: &mut Place,
    kernel: &mut Kernel,
    p: &Params,
    radius: Option<f64>,
) -> Result<(), Alarm> {
    let levels = Levels::read(p, None)?;
    let r = tool_radius(p, radius)?;
    let (units, tens) = variant(p, 12, 4)?;
    let percent = match p.or_zero(9) {
        v if v > 0.0 => v.min(100.0),
        _ => 50.0,
    };
    let along_abscissa = tens % 2 == 1 || tens == 0;
    let (x0, x1) = (p.length_or_zero(4), p.length_or_zero(6));
    let (y0, y1) = (p.length_or_zero(5), p.length_or_zero(7));
    let (u, v) = if along_abscissa {
        ((x0.min(x1), x0.max(x1)), (y0.min(y1), y0.max(y1)))
    } else {
        ((y0.min(y1), y0.max(y1)), (x0.min(x1), x0.max(x1)))
    };
    let clearance = levels.safety - levels.reference;
    let roughing = units == 1;
    let face = Face {
        levels,
        corner: (0.0, 0.0),
        cos: 1.0,
        sin: 0.0,
        along_abscissa,
        row: (u.0 - r - clearance, u.1 + r),
        rows: rows(v.0, v.1, 2.0 * r * percent / 100.0),
        bottom: levels.depth
            + if roughing {
                p.length_or_zero(10).abs()
            } else {
                0.0
            },
        step_down: if roughing {
            p.length_or_zero(8).abs()
        } else {
            0.0
        },
        meander: true,
        feed: p.number(11).filter(|f| *f > 0.0),
    };
    face.mill(at, kernel)
}

/// CYCLE71's checks: VARI's tens 1 to 4 (61002), MIDA programmed (61124) and at most the tool's
/// diameter (61111), LENG and WID not 0 (61118). Gives MIDA, LENG and WID.
fn check_classic(p: &Params, tens: i64, r: f64) -> Result<(f64, f64, f64), Alarm> {
    if tens == 0 {
        return Err(machining_type(
            p,
            p.or_zero(14).round() as i64,
            "units 1 roughing or 2 finishing; tens 1 to 4, the rows' direction",
        ));
    }
    let step = p.length_or_zero(10).abs();
    if step == 0.0 {
        return Err(
            alarm(61124, p.span, "CYCLE71: infeed width is not programmed")
                .with_help("give MIDA, the largest step between rows"),
        );
    }
    if step > 2.0 * r + 1e-9 {
        return Err(alarm(
            61111,
            p.span,
            format_args!("CYCLE71: infeed width {step} > tool diameter {}", 2.0 * r),
        ));
    }
    let (length, width) = (p.length_or_zero(6), p.length_or_zero(7));
    if length == 0.0 || width == 0.0 {
        return Err(alarm(61118, p.span, "CYCLE71: length or width = 0")
            .with_help("give the face's length (LENG) and width (WID)"));
    }
    Ok((step, length, width))
}

/// CYCLE71(RTP, RFP, SDIS, DP, PA, PO, LENG, WID, STA, MID, MIDA, FDP, FALD, FFP1, VARI, FDP1):
/// the rectangle LENG × WID from the corner (PA, PO) (their signs give the directions), turned
/// STA degrees about it. Rows MIDA apart (at most the tool's diameter; 0 is alarm 61124),
/// along the abscissa (VARI tens 1, 3) or the ordinate (2, 4), in one direction (1, 2: back at
/// the safety plane) or alternating (3, 4); each row from FDP plus the tool radius before the
/// area to FDP plus the radius past it; the first row's centre on the near edge, the last one's
/// edge FDP1 past the far edge (**inferred**). Levels at most MID deep down to DP+FALD
/// (roughing) or DP (finishing), at FFP1.
pub(super) fn classic(
    at: &mut Place,
    kernel: &mut Kernel,
    p: &Params,
    radius: Option<f64>,
) -> Result<(), Alarm> {
    let levels = Levels::read(p, None)?;
    let r = tool_radius(p, radius)?;
    let (units, tens) = variant(p, 14, 4)?;
    let (step, length, width) = check_classic(p, tens, r)?;
    let along_abscissa = tens % 2 == 1;
    // u runs along the rows, v across them; a negative size runs the other way from the
    // corner.
    let (u_size, v_size) = if along_abscissa {
        (length, width)
    } else {
        (width, length)
    };
    let overrun = p.length_or_zero(11).abs() + r;
    let u_sign = u_size.signum();
    let v_sign = v_size.signum();
    let last = v_size - v_sign * (r - p.length_or_zero(15).abs());
    let (sin, cos) = p.or_zero(8).to_radians().sin_cos();
    let roughing = units == 1;
    let face = Face {
        levels,
        corner: (p.length_or_zero(4), p.length_or_zero(5)),
        cos,
        sin,
        along_abscissa,
        row: (-u_sign * overrun, u_size + u_sign * overrun),
        rows: rows(0.0, last, step),
        bottom: levels.depth
            + if roughing {
                p.length_or_zero(12).abs()
            } else {
                0.0
            },
        step_down: p.length_or_zero(9).abs(),
        meander: tens >= 3,
        feed: p.number(13).filter(|f| *f > 0.0),
    };
    face.mill(at, kernel)
}
