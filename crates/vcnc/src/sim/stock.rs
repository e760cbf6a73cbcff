//! Stocks other than a box, and the cut part against its design: a cylinder standing on Z, a
//! solid read from an STL file (binary or ASCII) and sampled into the height field as its top
//! surface per cell, and the deviation of a simulated part from a design STL sampled the same
//! way. A height field holds one surface per cell: an STL's overhangs are filled below.

use super::grid::HeightField;
use crate::plot::raster::Canvas;

/// The triangles of an STL file, mm.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Each triangle's three corners.
    pub triangles: Vec<[[f64; 3]; 3]>,
}

impl Mesh {
    /// Reads a binary STL, or an ASCII one (`solid` ... `vertex x y z` ...). `Err` says why not.
    pub fn parse(bytes: &[u8]) -> Result<Mesh, String> {
        // A binary file's size is exactly its header, count and 50 bytes a triangle; an ASCII
        // file starting with `solid` cannot match that by chance often, and is tried first.
        let binary_size = |n: usize| 84 + 50 * n;
        let count = bytes
            .get(80..84)
            .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]) as usize);
        let binary = count.is_some_and(|n| binary_size(n) == bytes.len());
        if !binary && bytes.trim_ascii_start().starts_with(b"solid") {
            return Mesh::parse_ascii(bytes);
        }
        let Some(n) = count.filter(|_| binary) else {
            return Err("neither a binary STL (size does not match its count) nor ASCII".into());
        };
        let value = |at: usize| {
            let b = &bytes[at..at + 4];
            f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        };
        let triangles = (0..n)
            .map(|t| {
                // Each record: a normal (ignored: the corners' order says it), three corners.
                let base = 84 + 50 * t + 12;
                std::array::from_fn(|c| std::array::from_fn(|k| value(base + 12 * c + 4 * k)))
            })
            .collect();
        Mesh::checked(triangles)
    }

    fn parse_ascii(bytes: &[u8]) -> Result<Mesh, String> {
        let text = std::str::from_utf8(bytes).map_err(|_| "an ASCII STL that is not UTF-8")?;
        let mut corners = Vec::new();
        for (n, line) in text.lines().enumerate() {
            let mut words = line.split_whitespace();
            if words.next() != Some("vertex") {
                continue;
            }
            let values: Vec<f64> = words
                .map(str::parse)
                .collect::<Result<_, _>>()
                .map_err(|e| format!("line {}: {e}", n + 1))?;
            let [x, y, z] = values[..] else {
                return Err(format!("line {}: a vertex needs three numbers", n + 1));
            };
            corners.push([x, y, z]);
        }
        if corners.len() % 3 != 0 {
            return Err("the vertices do not make whole triangles".into());
        }
        Mesh::checked(corners.chunks(3).map(|c| [c[0], c[1], c[2]]).collect())
    }

    fn checked(triangles: Vec<[[f64; 3]; 3]>) -> Result<Mesh, String> {
        if triangles.is_empty() {
            return Err("no triangles".into());
        }
        if !triangles.iter().flatten().flatten().all(|v| v.is_finite()) {
            return Err("a corner that is not a finite number".into());
        }
        Ok(Mesh { triangles })
    }

    /// The box around the mesh: `[min, max]`.
    pub fn extents(&self) -> [[f64; 3]; 2] {
        let mut low = [f64::INFINITY; 3];
        let mut high = [f64::NEG_INFINITY; 3];
        for p in self.triangles.iter().flatten() {
            for k in 0..3 {
                low[k] = low[k].min(p[k]);
                high[k] = high[k].max(p[k]);
            }
        }
        [low, high]
    }

    /// The highest point of the mesh above each cell centre of a grid of `cell` mm from
    /// `origin`, `size` cells: `NaN` where no triangle covers the centre.
    pub fn tops(&self, origin: [f64; 2], cell: f64, size: [usize; 2]) -> Vec<f64> {
        let mut tops = vec![f64::NAN; size[0] * size[1]];
        let index = |v: f64, o: f64, n: usize| ((v - o) / cell - 0.5).clamp(0.0, n as f64);
        for &[a, b, c] in &self.triangles {
            let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
            // Walls (seen edge-on from above) cover no centre.
            if area.abs() < 1e-12 {
                continue;
            }
            let i0 = index(a[0].min(b[0]).min(c[0]), origin[0], size[0]).ceil() as usize;
            let i1 = index(a[0].max(b[0]).max(c[0]), origin[0], size[0]).floor() as usize;
            let j0 = index(a[1].min(b[1]).min(c[1]), origin[1], size[1]).ceil() as usize;
            let j1 = index(a[1].max(b[1]).max(c[1]), origin[1], size[1]).floor() as usize;
            for j in j0..=j1.min(size[1] - 1) {
                let y = origin[1] + (j as f64 + 0.5) * cell;
                for i in i0..=i1.min(size[0] - 1) {
                    let x = origin[0] + (i as f64 + 0.5) * cell;
                    let w0 = ((b[0] - x) * (c[1] - y) - (b[1] - y) * (c[0] - x)) / area;
                    let w1 = ((c[0] - x) * (a[1] - y) - (c[1] - y) * (a[0] - x)) / area;
                    let w2 = 1.0 - w0 - w1;
                    // A centre on a shared edge belongs to both triangles: no gap between them.
                    if w0 < -1e-9 || w1 < -1e-9 || w2 < -1e-9 {
                        continue;
                    }
                    let z = w0 * a[2] + w1 * b[2] + w2 * c[2];
                    let top = &mut tops[j * size[0] + i];
                    if top.is_nan() || z > *top {
                        *top = z;
                    }
                }
            }
        }
        tops
    }
}

/// A cylinder standing on Z: centre X Y, diameter, bottom and top Z, mm.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cylinder {
    /// The axis's X and Y.
    pub center: [f64; 2],
    /// The diameter.
    pub diameter: f64,
    /// The bottom and the top face's Z.
    pub z: [f64; 2],
}

impl Cylinder {
    /// The box around it.
    pub fn extents(&self) -> [[f64; 3]; 2] {
        let r = self.diameter / 2.0;
        let [x, y] = self.center;
        [[x - r, y - r, self.z[0]], [x + r, y + r, self.z[1]]]
    }

    /// Its grid: cells whose centre is inside the circle are full.
    pub fn grid(&self, cell: f64) -> HeightField {
        let r2 = (self.diameter / 2.0).powi(2);
        let [cx, cy] = self.center;
        let top = self.z[1];
        HeightField::shaped(self.extents(), cell, |[x, y]| {
            ((x - cx).powi(2) + (y - cy).powi(2) <= r2).then_some(top)
        })
    }
}

/// A stock read from an STL: its box's grid, each cell full up to the mesh's top above it.
pub fn stl_grid(mesh: &Mesh, cell: f64) -> HeightField {
    let extents = mesh.extents();
    let empty = HeightField::new(extents, cell);
    let tops = mesh.tops(empty.origin(), cell, empty.size());
    let origin = empty.origin();
    let width = empty.size()[0];
    HeightField::shaped(extents, cell, |[x, y]| {
        let i = ((x - origin[0]) / cell) as usize;
        let j = ((y - origin[1]) / cell) as usize;
        Some(tops[j * width + i]).filter(|t| !t.is_nan())
    })
}

/// One extreme of the deviation: how far and where.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Extreme {
    /// mm, positive.
    pub amount: f64,
    /// The cell's centre X Y and the design's Z there.
    pub at: [f64; 3],
}

/// The cut part against the design, over the cells where the design has material.
#[derive(Clone, Debug, PartialEq)]
pub struct Deviation {
    /// The deepest cut below the design (material removed that the part needs).
    pub gouge: Option<Extreme>,
    /// The most material left above the design.
    pub excess: Option<Extreme>,
    /// Per cell (row-major, the grid's size): part minus design, mm; `NaN` off the design.
    pub cells: Vec<f64>,
    /// The grid's size.
    pub size: [usize; 2],
}

/// Compares the simulated part with the design's top surface: below it is a gouge, above it
/// an excess. Only cells over which the design has a surface count; over them a design's
/// surface below the stock's bottom compares with the bottom.
pub fn deviation(grid: &HeightField, design: &Mesh) -> Deviation {
    let size = grid.size();
    let tops = design.tops(grid.origin(), grid.cell(), size);
    let (bottom, _) = grid.bottom_top();
    let mut cells = vec![f64::NAN; size[0] * size[1]];
    let (mut gouge, mut excess): (Option<Extreme>, Option<Extreme>) = (None, None);
    for j in 0..size[1] {
        for i in 0..size[0] {
            let k = j * size[0] + i;
            let design_z = tops[k];
            if design_z.is_nan() {
                continue;
            }
            let d = grid.height(i, j) - design_z.max(bottom);
            cells[k] = d;
            let [x, y] = grid.center(i, j);
            let here = Extreme {
                amount: d.abs(),
                at: [x, y, design_z],
            };
            let slot = if d < 0.0 { &mut gouge } else { &mut excess };
            if slot.is_none_or(|e| here.amount > e.amount) {
                *slot = Some(here);
            }
        }
    }
    Deviation {
        gouge,
        excess,
        cells,
        size,
    }
}

impl Deviation {
    /// A top view coloured by deviation: blue for gouges, red for excess, white within
    /// `tolerance` mm, full colour at `scale` mm; grey off the design. `width` pixels wide.
    pub fn picture(&self, tolerance: f64, scale: f64, width: u32) -> Vec<u8> {
        let [nx, ny] = self.size;
        let width = width.max(1);
        let pixel = f64::from(width) / nx as f64;
        let height = ((ny as f64 * pixel).round() as u32).max(1);
        let mut canvas = Canvas::new(width, height, [255, 255, 255]);
        let colour = |d: f64| -> [u8; 3] {
            if d.is_nan() {
                return [200, 200, 200];
            }
            if d.abs() <= tolerance {
                return [255, 255, 255];
            }
            let t = ((d.abs() - tolerance) / (scale - tolerance).max(1e-9)).min(1.0);
            let fade = (255.0 * (1.0 - t)) as u8;
            if d < 0.0 {
                [fade, fade, 255]
            } else {
                [255, fade, fade]
            }
        };
        // One cell per pixel at most: a larger grid is sampled.
        let step = ((nx as f64 / f64::from(width)).ceil() as usize).max(1);
        for j in (0..ny).step_by(step) {
            for i in (0..nx).step_by(step) {
                let c = colour(self.cells[j * nx + i]);
                let x0 = i as f64 * pixel;
                let x1 = (i + step) as f64 * pixel;
                // Y up in the part, down in the picture.
                let y0 = f64::from(height) - (j + step) as f64 * pixel;
                let y1 = f64::from(height) - j as f64 * pixel;
                canvas.triangle([[x0, y0, 0.0], [x1, y0, 0.0], [x1, y1, 0.0]], c);
                canvas.triangle([[x0, y0, 0.0], [x1, y1, 0.0], [x0, y1, 0.0]], c);
            }
        }
        canvas.to_png()
    }
}
