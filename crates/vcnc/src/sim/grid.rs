//! The height field: the stock as one column of material per grid cell, from the stock's
//! bottom up to the height the cell has left, and the removal of material by a tool swept
//! along one straight move ([`HeightField::cut`]).
//!
//! A cell is cut where the tool passes over its centre: the lowest point of the tool's surface
//! above that centre over the whole move, found in closed form for level moves and plunges
//! (the nearest point of the move) and by a golden-section search for sloped ones (the height
//! of a profile that is convex and rises with the radius, plus a linear descent, is convex
//! along the move). Only the cells of the rows the swept tool covers are visited: on each row,
//! the interval the move's capsule (the move widened by the tool's radius) covers.

use crate::motion::{ToolShape, ToolTip};

/// A cell is cut only when the tool goes this far below its height, mm: heights are kept as
/// f32 (a hundred-thousandth of a millimetre at a metre), and a tool passing again over what it
/// cut must not cut it again by that rounding.
const HEIGHT_TOLERANCE: f64 = 1e-4;

/// The stock as a grid of columns.
#[derive(Clone, Debug)]
pub struct HeightField {
    origin: [f64; 2],
    cell: f64,
    size: [usize; 2],
    bottom: f64,
    top: f64,
    heights: Vec<f32>,
    /// The material the stock had, mm^3.
    initial: f64,
}

/// What one straight move did to the stock.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CutResult {
    /// Material removed, mm^3.
    pub removed: f64,
    /// The deepest the tool's tip went below the stock's surface where it removed material, mm.
    pub depth: f64,
    /// Material above the flutes (beyond the cutting length): the depth of the tip below it.
    pub beyond_cutting_length: Option<f64>,
    /// Material touching the shank (wider than the cutter) or the holder: the depth of the tip.
    pub holder: Option<(Body, f64)>,
}

/// The parts of a tool above its flutes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Body {
    /// The shank.
    Shank,
    /// The holder.
    Holder,
}

impl HeightField {
    /// A box of stock `[min, max]` in cells of `cell` mm, full to its top.
    pub fn new(stock: [[f64; 3]; 2], cell: f64) -> HeightField {
        let [low, high] = stock;
        let size = [
            (((high[0] - low[0]) / cell).round() as usize).max(1),
            (((high[1] - low[1]) / cell).round() as usize).max(1),
        ];
        let mut grid = HeightField {
            origin: [low[0], low[1]],
            cell,
            size,
            bottom: low[2],
            top: high[2],
            heights: vec![high[2] as f32; size[0] * size[1]],
            initial: 0.0,
        };
        grid.initial = (grid.top - grid.bottom) * (size[0] * size[1]) as f64 * cell * cell;
        grid
    }

    /// A stock of another shape inside the box `stock`: each cell full up to `top` of its
    /// centre (clamped to the box), empty where `top` is `None` (a cylinder's corners, where
    /// an STL has no triangle above).
    pub fn shaped(
        stock: [[f64; 3]; 2],
        cell: f64,
        top: impl Fn([f64; 2]) -> Option<f64>,
    ) -> HeightField {
        let mut grid = HeightField::new(stock, cell);
        for j in 0..grid.size[1] {
            for i in 0..grid.size[0] {
                let h =
                    top(grid.center(i, j)).map_or(grid.bottom, |h| h.clamp(grid.bottom, grid.top));
                grid.heights[j * grid.size[0] + i] = h as f32;
            }
        }
        grid.initial = grid.volume();
        grid
    }

    /// The cell size, mm.
    pub fn cell(&self) -> f64 {
        self.cell
    }

    /// Cells along X and Y.
    pub fn size(&self) -> [usize; 2] {
        self.size
    }

    /// The stock's bottom and original top, mm.
    pub fn bottom_top(&self) -> (f64, f64) {
        (self.bottom, self.top)
    }

    /// The corner of the grid (its lowest X and Y), mm.
    pub fn origin(&self) -> [f64; 2] {
        self.origin
    }

    /// The height left at cell (i, j).
    pub fn height(&self, i: usize, j: usize) -> f64 {
        f64::from(self.heights[j * self.size[0] + i])
    }

    /// The centre of cell (i, j).
    pub fn center(&self, i: usize, j: usize) -> [f64; 2] {
        [
            self.origin[0] + (i as f64 + 0.5) * self.cell,
            self.origin[1] + (j as f64 + 0.5) * self.cell,
        ]
    }

    /// The material left, mm^3.
    pub fn volume(&self) -> f64 {
        let sum: f64 = self
            .heights
            .iter()
            .map(|&h| f64::from(h) - self.bottom)
            .sum();
        sum * self.cell * self.cell
    }

    /// The material the stock had, mm^3.
    pub fn stock_volume(&self) -> f64 {
        self.initial
    }

    /// Sweeps `tool` (along Z, its tip at the points) from `from` to `to` and removes what it
    /// cuts; checks the parts above its flutes against the stock as it was.
    pub fn cut(&mut self, from: [f64; 3], to: [f64; 3], tool: &ToolShape) -> CutResult {
        let sweep = Sweep::new(from, to);
        let bodies = Bodies::of(tool, from[2].min(to[2]), self.top);
        let radius = tool.radius();
        let reach = bodies.reach.max(radius);
        let mut result = CutResult::default();
        if reach <= 0.0 {
            return result;
        }
        let flat = tool.tip == ToolTip::Flat;
        let cutter = |d: f64| tool.height_at(d.min(radius)).unwrap_or(0.0);
        let area = self.cell * self.cell;
        let (y_low, y_high) = (from[1].min(to[1]) - reach, from[1].max(to[1]) + reach);
        let Some(rows) = self.index_range(1, y_low, y_high) else {
            return result;
        };
        for j in rows {
            let y = self.origin[1] + (j as f64 + 0.5) * self.cell;
            let Some((x_low, x_high)) = sweep.row_interval(y, reach) else {
                continue;
            };
            let Some(columns) = self.index_range(0, x_low, x_high) else {
                continue;
            };
            for i in columns {
                let c = [self.origin[0] + (i as f64 + 0.5) * self.cell, y];
                let k = j * self.size[0] + i;
                let old = f64::from(self.heights[k]);
                let touched = sweep.lowest(c, radius, flat, cutter);
                if let Some((z, tip)) = touched {
                    let new = z.max(self.bottom);
                    if new < old - HEIGHT_TOLERANCE {
                        result.removed += (old - new) * area;
                        result.depth = result.depth.max(old - tip);
                        self.heights[k] = new as f32;
                    }
                    if old > tip + tool.cutting_length + 1e-6 {
                        let depth = old - tip;
                        let worst = result.beyond_cutting_length.get_or_insert(depth);
                        *worst = worst.max(depth);
                    }
                }
                if bodies.any {
                    if let Some(hit) = bodies.touch(&sweep, c, old, touched.is_some()) {
                        let worst = result.holder.get_or_insert(hit);
                        if hit.1 > worst.1 {
                            *worst = hit;
                        }
                    }
                }
            }
        }
        result
    }

    /// The cells whose centres lie in `[low, high]` along axis `axis` (0 X, 1 Y), if any.
    fn index_range(
        &self,
        axis: usize,
        low: f64,
        high: f64,
    ) -> Option<std::ops::RangeInclusive<usize>> {
        let first = ((low - self.origin[axis]) / self.cell - 0.5)
            .ceil()
            .max(0.0);
        let last = ((high - self.origin[axis]) / self.cell - 0.5).floor();
        let count = self.size[axis] as f64;
        // NaN bounds (a move at infinity) compare false and visit nothing.
        if first.partial_cmp(&last).is_none_or(|o| o.is_gt()) || last < 0.0 || first >= count {
            return None;
        }
        Some(first as usize..=(last.min(count - 1.0) as usize))
    }
}

/// One straight move in the plane, with what every cell asks of it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Sweep {
    from: [f64; 3],
    to: [f64; 3],
    d: [f64; 2],
    length2: f64,
}

impl Sweep {
    pub(crate) fn new(from: [f64; 3], to: [f64; 3]) -> Sweep {
        let d = [to[0] - from[0], to[1] - from[1]];
        Sweep {
            from,
            to,
            d,
            length2: d[0] * d[0] + d[1] * d[1],
        }
    }

    /// The X interval of row `y` within `radius` of the move in the plane: the row's chord of
    /// the capsule, whose ends lie on the end circles or on the two sides.
    pub(crate) fn row_interval(&self, y: f64, radius: f64) -> Option<(f64, f64)> {
        let mut low = f64::INFINITY;
        let mut high = f64::NEG_INFINITY;
        let mut take = |x: f64| {
            low = low.min(x);
            high = high.max(x);
        };
        for end in [self.from, self.to] {
            let dy = y - end[1];
            if dy.abs() <= radius {
                let w = (radius * radius - dy * dy).sqrt();
                take(end[0] - w);
                take(end[0] + w);
            }
        }
        if self.length2 > 0.0 {
            let length = self.length2.sqrt();
            let normal = [-self.d[1] / length, self.d[0] / length];
            for sign in [-1.0, 1.0] {
                let p0 = [
                    self.from[0] + sign * radius * normal[0],
                    self.from[1] + sign * radius * normal[1],
                ];
                if self.d[1].abs() > 1e-15 {
                    let t = (y - p0[1]) / self.d[1];
                    if (0.0..=1.0).contains(&t) {
                        take(p0[0] + t * self.d[0]);
                    }
                }
            }
        }
        (low <= high).then_some((low, high))
    }

    /// The lowest height of a body whose surface is `profile(d)` above the tip at `d` from its
    /// axis (up to `radius`) over cell centre `c`, with the tip's height there: `None` where
    /// the body never covers `c`. `flat` says the profile is constant.
    pub(crate) fn lowest(
        &self,
        c: [f64; 2],
        radius: f64,
        flat: bool,
        profile: impl Fn(f64) -> f64,
    ) -> Option<(f64, f64)> {
        let p = [c[0] - self.from[0], c[1] - self.from[1]];
        let r2 = radius * radius;
        let dz = self.to[2] - self.from[2];
        if self.length2 < 1e-18 {
            let d2 = p[0] * p[0] + p[1] * p[1];
            if d2 > r2 {
                return None;
            }
            let tip = self.from[2].min(self.to[2]);
            return Some((tip + profile(d2.sqrt()), tip));
        }
        let tc = (p[0] * self.d[0] + p[1] * self.d[1]) / self.length2;
        let e = [p[0] - tc * self.d[0], p[1] - tc * self.d[1]];
        let e2 = e[0] * e[0] + e[1] * e[1];
        if e2 > r2 {
            return None;
        }
        let s = ((r2 - e2) / self.length2).sqrt();
        let (t_low, t_high) = ((tc - s).max(0.0), (tc + s).min(1.0));
        if t_low > t_high {
            return None;
        }
        let at = |t: f64| {
            let d = (e2 + self.length2 * (t - tc) * (t - tc)).sqrt().min(radius);
            let tip = self.from[2] + dz * t;
            (tip + profile(d), tip)
        };
        if dz.abs() < 1e-12 {
            return Some(at(tc.clamp(t_low, t_high)));
        }
        if flat {
            return Some(at(if dz > 0.0 { t_low } else { t_high }));
        }
        Some(golden_minimum(t_low, t_high, at))
    }
}

/// The minimum of a convex function of `t` on `[low, high]` by golden-section search, to a
/// millionth of the interval.
fn golden_minimum(mut low: f64, mut high: f64, f: impl Fn(f64) -> (f64, f64)) -> (f64, f64) {
    const R: f64 = 0.618_033_988_749_894_8;
    let mut a = high - R * (high - low);
    let mut b = low + R * (high - low);
    let (mut fa, mut fb) = (f(a), f(b));
    for _ in 0..30 {
        if fa.0 <= fb.0 {
            high = b;
            b = a;
            fb = fa;
            a = high - R * (high - low);
            fa = f(a);
        } else {
            low = a;
            a = b;
            fa = fb;
            b = low + R * (high - low);
            fb = f(b);
        }
    }
    let ends = [f(low), f(high), fa, fb];
    ends.into_iter().fold(
        (f64::INFINITY, 0.0),
        |best, v| if v.0 < best.0 { v } else { best },
    )
}

/// The parts above the flutes that can touch the stock on a move: the shank where it is wider
/// than the cutter, and each holder section, as heights above the tip at a radius.
struct Bodies {
    shank: Option<(f64, f64)>,
    sections: [Option<Section>; crate::motion::HOLDER_SECTIONS],
    reach: f64,
    any: bool,
}

/// A holder section as a body: its bottom above the tip, its radii and length.
#[derive(Clone, Copy)]
struct Section {
    bottom: f64,
    bottom_radius: f64,
    top_radius: f64,
    length: f64,
}

impl Section {
    /// Its lower surface above the tip at `d` from the axis: the bottom face out to its radius,
    /// then, for a cone widening upwards, its slope.
    fn lower(&self, d: f64) -> f64 {
        if d <= self.bottom_radius || self.top_radius <= self.bottom_radius {
            self.bottom
        } else {
            self.bottom
                + (d - self.bottom_radius) / (self.top_radius - self.bottom_radius) * self.length
        }
    }
}

impl Bodies {
    /// The bodies of `tool` that can reach the stock (top `top`) when its tip goes down to
    /// `lowest_tip`: the others are left out, so that most moves check none.
    fn of(tool: &ToolShape, lowest_tip: f64, top: f64) -> Bodies {
        let radius = tool.radius();
        let shank_radius = tool.shank_diameter / 2.0;
        let shank = (shank_radius > radius && lowest_tip + tool.cutting_length < top)
            .then_some((tool.cutting_length, shank_radius));
        let mut sections = [None; crate::motion::HOLDER_SECTIONS];
        let mut bottom = tool.stickout;
        let mut reach = shank.map_or(0.0, |s| s.1);
        for (slot, section) in sections.iter_mut().zip(tool.holder.sections()) {
            if lowest_tip + bottom < top {
                let s = Section {
                    bottom,
                    bottom_radius: section.bottom_diameter / 2.0,
                    top_radius: section.top_diameter / 2.0,
                    length: section.length,
                };
                reach = reach.max(s.bottom_radius.max(s.top_radius));
                *slot = Some(s);
            }
            bottom += section.length;
        }
        let any = shank.is_some() || sections.iter().any(Option::is_some);
        Bodies {
            shank,
            sections,
            reach,
            any,
        }
    }

    /// The body that touches the material `old` high at `c`, with the tip's depth below it;
    /// the shank only outside the cutter's own path (`under_cutter`), where the flute check
    /// has not already seen it.
    fn touch(
        &self,
        sweep: &Sweep,
        c: [f64; 2],
        old: f64,
        under_cutter: bool,
    ) -> Option<(Body, f64)> {
        if let Some((above, radius)) = self.shank.filter(|_| !under_cutter) {
            if let Some((z, tip)) = sweep.lowest(c, radius, true, |_| above) {
                if old > z + 1e-6 {
                    return Some((Body::Shank, old - tip));
                }
            }
        }
        for section in self.sections.iter().flatten() {
            let radius = section.bottom_radius.max(section.top_radius);
            let flat = section.top_radius <= section.bottom_radius;
            if let Some((z, tip)) = sweep.lowest(c, radius, flat, |d| section.lower(d)) {
                if old > z + 1e-6 {
                    return Some((Body::Holder, old - tip));
                }
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_row_of_a_diagonal_capsule_is_cut_at_its_sides() {
        // A move from (0, 0) to (10, 10), radius 1: the row y = 5 crosses the sides at
        // x = 5 -+ sqrt(2).
        let sweep = Sweep::new([0.0; 3], [10.0, 10.0, 0.0]);
        let (low, high) = sweep.row_interval(5.0, 1.0).unwrap();
        assert!((low - (5.0 - 2f64.sqrt())).abs() < 1e-12, "{low}");
        assert!((high - (5.0 + 2f64.sqrt())).abs() < 1e-12, "{high}");
        assert_eq!(sweep.row_interval(12.0, 1.0), None);
    }

    #[test]
    fn a_ball_on_a_ramp_is_lowest_where_the_search_finds_it() {
        // A ball of radius 2 descending from z 0 to z -10 over 10 mm of X: straight under the
        // end point, the lowest the ball reaches is the end's tip, -10.
        let ball = ToolShape {
            tip: ToolTip::Ball,
            ..ToolShape::flat(2.0)
        };
        let sweep = Sweep::new([0.0, 0.0, 0.0], [10.0, 0.0, -10.0]);
        let (z, _) = sweep
            .lowest([10.0, 0.0], 2.0, false, |d| ball.height_at(d).unwrap())
            .unwrap();
        assert!((z + 10.0).abs() < 1e-6, "{z}");
    }
}
