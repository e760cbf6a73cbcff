//! The simulated part as a closed triangle mesh: the top surface through the cells' centres
//! (extended to the stock's edges), four walls down to the bottom, and the bottom as a fan. It
//! is watertight by construction (each edge is shared by exactly two triangles, oriented
//! outwards) and encloses the grid's own volume: each lattice point carries its cell's
//! height over a cell's area. Written as binary STL ([`write_stl`]) or drawn shaded as a PNG
//! ([`picture`]).

use super::HeightField;
use crate::plot::raster::Canvas;
use crate::plot::View;
use std::io::{self, Write};

/// Heights are kept this far above the bottom, mm, so that a cell cut through leaves no
/// triangle of zero area (a wall or top face squashed onto the bottom).
const FLOOR: f64 = 1e-3;

/// The lattice of the top surface: every `step`-th cell's centre, and the stock's edges.
struct Lattice<'a> {
    grid: &'a HeightField,
    xs: Vec<(f64, usize)>,
    ys: Vec<(f64, usize)>,
}

impl<'a> Lattice<'a> {
    fn new(grid: &'a HeightField, step: usize) -> Lattice<'a> {
        let axis = |k: usize| {
            let n = grid.size()[k];
            let origin = grid.origin()[k];
            let mut points = vec![(origin, 0)];
            let mut i = 0;
            while i < n {
                points.push((origin + (i as f64 + 0.5) * grid.cell(), i));
                i += step;
            }
            if points.last().map(|p| p.1) != Some(n - 1) {
                points.push((origin + (n as f64 - 0.5) * grid.cell(), n - 1));
            }
            points.push((origin + n as f64 * grid.cell(), n - 1));
            points
        };
        Lattice {
            grid,
            xs: axis(0),
            ys: axis(1),
        }
    }

    fn top(&self, a: usize, b: usize) -> [f64; 3] {
        let (x, i) = self.xs[a];
        let (y, j) = self.ys[b];
        let bottom = self.grid.bottom_top().0;
        [x, y, self.grid.height(i, j).max(bottom + FLOOR)]
    }

    /// The lattice points around the edge, counter-clockwise seen from above.
    fn boundary(&self) -> Vec<(usize, usize)> {
        let (na, nb) = (self.xs.len() - 1, self.ys.len() - 1);
        let mut points = Vec::with_capacity(2 * (na + nb));
        points.extend((0..na).map(|a| (a, 0)));
        points.extend((0..nb).map(|b| (na, b)));
        points.extend((1..=na).rev().map(|a| (a, nb)));
        points.extend((1..=nb).rev().map(|b| (0, b)));
        points
    }

    fn for_each_triangle(&self, mut visit: impl FnMut([[f64; 3]; 3])) {
        for b in 0..self.ys.len() - 1 {
            for a in 0..self.xs.len() - 1 {
                let (p00, p10) = (self.top(a, b), self.top(a + 1, b));
                let (p11, p01) = (self.top(a + 1, b + 1), self.top(a, b + 1));
                visit([p00, p10, p11]);
                visit([p00, p11, p01]);
            }
        }
        let bottom = self.grid.bottom_top().0;
        let ring = self.boundary();
        let low = |p: [f64; 3]| [p[0], p[1], bottom];
        let (first, last) = (self.xs[0].0, self.xs[self.xs.len() - 1].0);
        let (front, back) = (self.ys[0].0, self.ys[self.ys.len() - 1].0);
        let centre = [(first + last) / 2.0, (front + back) / 2.0, bottom];
        for k in 0..ring.len() {
            let (a0, b0) = ring[k];
            let (a1, b1) = ring[(k + 1) % ring.len()];
            let (t0, t1) = (self.top(a0, b0), self.top(a1, b1));
            visit([low(t0), low(t1), t1]);
            visit([low(t0), t1, t0]);
            visit([centre, low(t1), low(t0)]);
        }
    }
}

/// Calls `visit` with every triangle of the part's mesh, outward normals by the right-hand
/// rule.
pub fn for_each_triangle(grid: &HeightField, visit: impl FnMut([[f64; 3]; 3])) {
    Lattice::new(grid, 1).for_each_triangle(visit);
}

/// Writes the part as binary STL.
///
/// # Errors
/// Writing to `out` fails.
pub fn write_stl(grid: &HeightField, out: &mut impl Write) -> io::Result<()> {
    let mut count: u32 = 0;
    for_each_triangle(grid, |_| count = count.saturating_add(1));
    let mut header = [0u8; 80];
    let title = b"vcnc sim: simulated part, mm";
    header[..title.len()].copy_from_slice(title);
    out.write_all(&header)?;
    out.write_all(&count.to_le_bytes())?;
    let mut buffer = Vec::with_capacity(50 * 4096);
    let mut result = Ok(());
    for_each_triangle(grid, |t| {
        if result.is_err() {
            return;
        }
        let n = normal(t);
        for v in std::iter::once(n).chain(t) {
            for c in v {
                buffer.extend_from_slice(&(c as f32).to_le_bytes());
            }
        }
        buffer.extend_from_slice(&[0, 0]);
        if buffer.len() >= 50 * 4096 {
            result = out.write_all(&buffer);
            buffer.clear();
        }
    });
    result?;
    out.write_all(&buffer)
}

/// The unit normal of a triangle by the right-hand rule (zero for a degenerate one).
fn normal(t: [[f64; 3]; 3]) -> [f64; 3] {
    let u = [t[1][0] - t[0][0], t[1][1] - t[0][1], t[1][2] - t[0][2]];
    let v = [t[2][0] - t[0][0], t[2][1] - t[0][1], t[2][2] - t[0][2]];
    let n = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    let length = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if length > 0.0 {
        n.map(|c| c / length)
    } else {
        [0.0; 3]
    }
}

/// The part drawn shaded from `view`, `width` pixels wide, as a PNG file's bytes. Large grids
/// are drawn from every few cells, about two cells to a pixel.
pub fn picture(grid: &HeightField, view: View, width: u32) -> Vec<u8> {
    let width = width.clamp(100, 8000);
    let step = (grid.size()[0].max(grid.size()[1]) / (2 * width as usize)).max(1);
    let lattice = Lattice::new(grid, step);
    let toward_viewer = match view {
        View::Top => [0.0, 0.0, 1.0],
        View::Front => [0.0, -1.0, 0.0],
        View::Side => [1.0, 0.0, 0.0],
        View::Iso => [
            -0.577_350_269_189_625_8,
            -0.577_350_269_189_625_8,
            0.577_350_269_189_625_8,
        ],
    };
    let (bottom, top) = grid.bottom_top();
    let origin = grid.origin();
    let size = grid.size().map(|n| n as f64 * grid.cell());
    let mut low = [f64::INFINITY; 2];
    let mut high = [f64::NEG_INFINITY; 2];
    for corner in 0..8 {
        let p = [
            origin[0] + size[0] * f64::from(corner & 1),
            origin[1] + size[1] * f64::from((corner >> 1) & 1),
            if corner & 4 == 0 { bottom } else { top },
        ];
        let q = view.project(p);
        for i in 0..2 {
            low[i] = low[i].min(q[i]);
            high[i] = high[i].max(q[i]);
        }
    }
    let margin = 20.0;
    let scale = (f64::from(width) - 2.0 * margin) / (high[0] - low[0]).max(1e-6);
    let height = ((high[1] - low[1]) * scale + 2.0 * margin).clamp(50.0, 8000.0) as u32;
    let mut canvas = Canvas::new(width, height, [235, 238, 242]);
    let light = unit([
        toward_viewer[0] - 0.3,
        toward_viewer[1] + 0.4,
        toward_viewer[2] + 0.8,
    ]);
    lattice.for_each_triangle(|t| {
        let n = normal(t);
        let facing = n[0] * toward_viewer[0] + n[1] * toward_viewer[1] + n[2] * toward_viewer[2];
        if facing <= 0.0 {
            return;
        }
        let lambert = (n[0] * light[0] + n[1] * light[1] + n[2] * light[2]).max(0.0);
        // Floors are tinted by their height; walls (steep faces) all alike, so that the two
        // triangles of one wall quad do not differ.
        let z = (t[0][2] + t[1][2] + t[2][2]) / 3.0;
        let level = if n[2] > 0.3 {
            ((z - bottom) / (top - bottom).max(1e-9)).clamp(0.0, 1.0)
        } else {
            0.5
        };
        let base = [
            90.0 + 100.0 * level,
            120.0 + 90.0 * level,
            170.0 + 60.0 * level,
        ];
        let shade = 0.3 + 0.7 * lambert;
        let colour = base.map(|c: f64| (c * shade).clamp(0.0, 255.0) as u8);
        let corners = t.map(|p| {
            let q = view.project(p);
            [
                margin + (q[0] - low[0]) * scale,
                margin + (high[1] - q[1]) * scale,
                p[0] * toward_viewer[0] + p[1] * toward_viewer[1] + p[2] * toward_viewer[2],
            ]
        });
        canvas.triangle(corners, colour);
    });
    canvas.to_png()
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let length = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|c| c / length)
}
