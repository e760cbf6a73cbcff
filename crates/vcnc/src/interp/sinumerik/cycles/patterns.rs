//! The position patterns: HOLES1 (a row of holes), HOLES2 (a circle of holes), CYCLE801 (a
//! grid), CYCLE802 (positions as listed). A pattern rapids in the plane to each position in
//! turn, at the height the tool is at, and runs the modal call (MCALL) there, which drills the
//! hole; without a modal call it only visits the positions. A modal call of a subprogram runs
//! the subprogram's blocks before the pattern goes on to its next position.
//!
//! Never: move along the tool axis itself (the drilling cycle does, and ends at its retraction
//! plane, from where the next position is reached).

use super::{alarm, run_modal, too_many, Modal, Params, Pattern, Place, MAX_DIVISIONS};
use crate::alarm::Alarm;
use crate::interp::kernel::Kernel;
use crate::interp::sinumerik::Sinumerik;

/// The positions of pattern `name` in the plane, in the order they are visited, from `from`.
pub(super) fn positions(
    name: &str,
    p: &Params,
    from: (f64, f64),
) -> Result<Vec<(f64, f64)>, Alarm> {
    match name {
        "HOLES1" => row(p),
        "HOLES2" => circle(p),
        "CYCLE801" => grid(p),
        _ => Ok(listed(p, from)),
    }
}

/// Rapids to every position, running the modal call at each; a subprogram it calls runs
/// before the next position (the pattern waits in `front`).
pub(super) fn visit(
    front: &mut Sinumerik,
    kernel: &mut Kernel,
    positions: &[(f64, f64)],
) -> Result<(), Alarm> {
    for (k, &position) in positions.iter().enumerate() {
        let mut at = Place::new(front, kernel);
        at.rapid_plane(kernel, position)?;
        at.finish(front);
        if run_modal(front, kernel)? == Modal::Called {
            front.cycles.pattern = Some(Pattern {
                rest: positions[k + 1..].to_vec(),
                depth: front.levels.len() - 1,
            });
            return Ok(());
        }
    }
    Ok(())
}

/// The number of holes NUM at `index`: alarm 61103 when 0 (or less).
fn count(p: &Params, index: usize) -> Result<usize, Alarm> {
    let number = p.or_zero(index).round();
    if number > MAX_DIVISIONS as f64 {
        return Err(too_many(p, number, "holes"));
    }
    if number < 1.0 {
        return Err(alarm(
            61103,
            p.span,
            format_args!("{}: number of holes is zero", p.name()),
        )
        .with_help("give the number of holes (NUM) as 1 or more"));
    }
    Ok(number as usize)
}

/// HOLES1(SPCA, SPCO, STA1, FDIS, DBH, NUM): NUM holes on the line through the reference point
/// (SPCA, SPCO) at STA1 degrees to the abscissa, the first FDIS from the point, DBH apart. The
/// holes are visited from the first (choice: the manual does not say whether the cycle starts
/// from the end nearer the tool).
fn row(p: &Params) -> Result<Vec<(f64, f64)>, Alarm> {
    let number = count(p, 5)?;
    let (x, y) = (p.length_or_zero(0), p.length_or_zero(1));
    let (sin, cos) = p.or_zero(2).to_radians().sin_cos();
    let (first, step) = (p.length_or_zero(3), p.length_or_zero(4));
    Ok((0..number)
        .map(|k| {
            let d = first + k as f64 * step;
            (x + d * cos, y + d * sin)
        })
        .collect())
}

/// HOLES2(CPA, CPO, RAD, STA1, INDA, NUM): NUM holes on the circle of radius RAD about (CPA,
/// CPO), the first at STA1 degrees from the abscissa, each next INDA degrees on (0: the circle
/// shared out evenly, 360/NUM).
fn circle(p: &Params) -> Result<Vec<(f64, f64)>, Alarm> {
    let number = count(p, 5)?;
    let (x, y, radius) = (
        p.length_or_zero(0),
        p.length_or_zero(1),
        p.length_or_zero(2),
    );
    let start = p.or_zero(3);
    let step = match p.or_zero(4) {
        0.0 => 360.0 / number as f64,
        step => step,
    };
    Ok((0..number)
        .map(|k| {
            let (sin, cos) = (start + k as f64 * step).to_radians().sin_cos();
            (x + radius * cos, y + radius * sin)
        })
        .collect())
}

/// CYCLE801(SPCA, SPCO, STA, DIS1, DIS2, NUM1, NUM2): a grid of NUM1 columns DIS1 apart and
/// NUM2 rows DIS2 apart from the reference point (SPCA, SPCO), turned STA degrees about it;
/// visited row by row, every other row backwards (meander: inferred from the cycle's help
/// pictures' order).
fn grid(p: &Params) -> Result<Vec<(f64, f64)>, Alarm> {
    let (columns, rows) = (count(p, 5)?, count(p, 6)?);
    if columns * rows > MAX_DIVISIONS {
        return Err(too_many(p, (columns * rows) as f64, "holes"));
    }
    let (x, y) = (p.length_or_zero(0), p.length_or_zero(1));
    let (sin, cos) = p.or_zero(2).to_radians().sin_cos();
    let (across, up) = (p.length_or_zero(3), p.length_or_zero(4));
    let mut positions = Vec::with_capacity(columns * rows);
    for row in 0..rows {
        for k in 0..columns {
            let column = if row % 2 == 0 { k } else { columns - 1 - k };
            let (u, v) = (column as f64 * across, row as f64 * up);
            positions.push((x + u * cos - v * sin, y + u * sin + v * cos));
        }
    }
    Ok(positions)
}

/// CYCLE802(_XYHIDE, _POSHIDE, X0, Y0, X1, Y1 ... X8, Y8): up to nine positions as listed;
/// a position whose abscissa and ordinate are both left out is no position, one of them left
/// out stays as the position before. **Inferred**: the first two parameters are the screen
/// form's masks and move nothing.
fn listed(p: &Params, from: (f64, f64)) -> Vec<(f64, f64)> {
    let mut last = from;
    (0..9)
        .filter_map(|k| {
            let (x, y) = (p.length(2 + 2 * k), p.length(3 + 2 * k));
            if x.is_none() && y.is_none() {
                return None;
            }
            last = (x.unwrap_or(last.0), y.unwrap_or(last.1));
            Some(last)
        })
        .collect()
}
