//! SINUMERIK's bottleneck detection (CDON; sinumerik-part-b.md 2.5, seed 002 L7796-7852): the
//! compensated path of a block checked against the programmed contour of the blocks before
//! its neighbour, which the corner rules never see. A tool too large for a narrow passage
//! comes within its radius of a block further back: the control skips the bottleneck and
//! gives an alarm; vcnc stops with the alarm there (the skip is the control's repair, not a
//! path to time).
//!
//! CDOF (power-on) and CDOF2 (which differs from CDOF only in 3D circumferential milling) check
//! neighbouring blocks only, as every corner does. Plane geometry only.

use super::geometry::{Element, V2};

/// The programmed blocks a compensated block is checked against, its neighbour included:
/// MD20240 $MC_CUTCOM_MAXNUM_CHECK_BLOCKS (the manual names the machine data, not its value,
/// seed 002 L7812; 3 is vcnc's choice).
pub(crate) const CHECKED_BLOCKS: usize = 3;

/// How much nearer than the radius the path may come before it cuts, mm: far below a
/// control's least increment, above the rounding of a program's six decimals.
const TOLERANCE: f64 = 1e-4;

/// Points along the compensated `programmed` element from `start` to `end` (compensated
/// points), both ends included.
fn path_points(programmed: &Element, start: V2, end: V2) -> Vec<V2> {
    const STEPS: u32 = 64;
    match *programmed {
        Element::Line { .. } => (0..=STEPS)
            .map(|k| start + (end - start) * (f64::from(k) / f64::from(STEPS)))
            .collect(),
        Element::Arc { center, ccw, .. } => {
            let piece = Element::Arc {
                start,
                end,
                center,
                ccw,
            };
            let sweep = piece.sweep();
            let radius = start.distance(center);
            let from = (start - center).y.atan2((start - center).x);
            let turn = if ccw { 1.0 } else { -1.0 };
            (0..=STEPS)
                .map(|k| {
                    let angle = from + turn * sweep * f64::from(k) / f64::from(STEPS);
                    center + V2::new(angle.cos(), angle.sin()) * radius
                })
                .collect()
        }
    }
}

/// True when the tool centre going along `programmed` compensated from `start` to `end` comes
/// nearer than `r` to one of `earlier` (programmed blocks before its neighbour).
pub(crate) fn cuts_into(
    programmed: &Element,
    (start, end): (V2, V2),
    earlier: &[Element],
    r: f64,
) -> bool {
    path_points(programmed, start, end)
        .into_iter()
        .any(|p| earlier.iter().any(|e| e.distance(p) < r - TOLERANCE))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(a: (f64, f64), b: (f64, f64)) -> Element {
        Element::Line {
            start: V2::new(a.0, a.1),
            end: V2::new(b.0, b.1),
        }
    }

    /// A slot 6 wide (walls Y0 and Y6 joined by X20) with a tool of r 4 on the inside: the
    /// compensated wall Y6 (at Y2) runs 2 from the wall Y0, two blocks back.
    #[test]
    fn a_slot_narrower_than_the_tool_is_a_bottleneck() {
        let earlier = [line((0.0, 0.0), (20.0, 0.0))];
        let back = line((20.0, 6.0), (0.0, 6.0));
        assert!(cuts_into(
            &back,
            (V2::new(16.0, 2.0), V2::new(0.0, 2.0)),
            &earlier,
            4.0
        ));
        // r 3 fits: the compensated wall at Y3 is 3 from Y0.
        assert!(!cuts_into(
            &back,
            (V2::new(17.0, 3.0), V2::new(0.0, 3.0)),
            &earlier,
            3.0
        ));
    }
}
