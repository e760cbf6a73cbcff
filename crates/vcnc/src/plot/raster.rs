//! A small RGB canvas: anti-aliased lines (dashed or not), rings, a 3x5 pixel font for
//! numbers and axis letters, triangles behind a depth buffer, and PNG output through the `png`
//! crate. Enough for a toolpath plot and a shaded simulated part; nothing of a graphics stack.

/// White.
pub const WHITE: [u8; 3] = [255, 255, 255];
/// Black.
pub const BLACK: [u8; 3] = [0, 0, 0];

/// An RGB picture with an optional depth buffer.
#[derive(Clone, Debug)]
pub struct Canvas {
    width: u32,
    height: u32,
    pixels: Vec<u8>,
    depth: Vec<f32>,
}

impl Canvas {
    /// A canvas of one colour.
    pub fn new(width: u32, height: u32, background: [u8; 3]) -> Canvas {
        let count = width as usize * height as usize;
        let mut pixels = Vec::with_capacity(count * 3);
        for _ in 0..count {
            pixels.extend_from_slice(&background);
        }
        Canvas {
            width,
            height,
            pixels,
            depth: Vec::new(),
        }
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The colour of a pixel.
    pub fn pixel(&self, x: u32, y: u32) -> [u8; 3] {
        let i = (y as usize * self.width as usize + x as usize) * 3;
        [self.pixels[i], self.pixels[i + 1], self.pixels[i + 2]]
    }

    /// Mixes `colour` into pixel (x, y) by `alpha` (0 to 1); outside the canvas nothing.
    fn blend(&mut self, x: i64, y: i64, colour: [u8; 3], alpha: f64) {
        if x < 0 || y < 0 || x >= i64::from(self.width) || y >= i64::from(self.height) {
            return;
        }
        let alpha = alpha.clamp(0.0, 1.0);
        let i = (y as usize * self.width as usize + x as usize) * 3;
        for (c, &target) in self.pixels[i..i + 3].iter_mut().zip(&colour) {
            *c = (f64::from(*c) * (1.0 - alpha) + f64::from(target) * alpha).round() as u8;
        }
    }

    /// A line `width` pixels wide, anti-aliased; dashed with dashes of `dash` pixels (and gaps
    /// of two thirds of that) when given.
    pub fn line(
        &mut self,
        from: [f64; 2],
        to: [f64; 2],
        colour: [u8; 3],
        width: f64,
        dash: Option<f64>,
    ) {
        let length = (to[0] - from[0]).hypot(to[1] - from[1]);
        let Some(dash) = dash.filter(|&d| d > 0.0 && length > d) else {
            self.solid_line(from, to, colour, width);
            return;
        };
        let period = dash * 5.0 / 3.0;
        let mut s = 0.0;
        while s < length {
            let e = (s + dash).min(length);
            let at = |t: f64| {
                [
                    from[0] + (to[0] - from[0]) * t / length,
                    from[1] + (to[1] - from[1]) * t / length,
                ]
            };
            self.solid_line(at(s), at(e), colour, width);
            s += period;
        }
    }

    /// A solid line: each pixel near it covered by how far its centre is from the line.
    fn solid_line(&mut self, from: [f64; 2], to: [f64; 2], colour: [u8; 3], width: f64) {
        if !(from.iter().chain(&to).all(|v| v.is_finite())) {
            return;
        }
        let half = width / 2.0;
        let (dx, dy) = (to[0] - from[0], to[1] - from[1]);
        let length2 = dx * dx + dy * dy;
        // Along the major axis one pixel at a time, across it only the line's own width.
        let steep = dy.abs() > dx.abs();
        let (a0, a1) = if steep {
            (from[1], to[1])
        } else {
            (from[0], to[0])
        };
        // Only the part on the canvas: a rapid from far away costs its visible length.
        let extent = i64::from(if steep { self.height } else { self.width });
        let lo = (a0.min(a1).floor() as i64 - 1).max(-2);
        let hi = (a0.max(a1).ceil() as i64 + 1).min(extent + 2);
        let reach = (half + 1.5)
            * (1.0
                + if steep {
                    (dx / dy).abs()
                } else {
                    (dy / dx.max(1e-12)).abs()
                }
                .min(1.0));
        for major in lo..=hi {
            let m = major as f64 + 0.5;
            let t = if steep {
                if dy.abs() < 1e-12 {
                    0.0
                } else {
                    (m - from[1]) / dy
                }
            } else if dx.abs() < 1e-12 {
                0.0
            } else {
                (m - from[0]) / dx
            };
            let t = t.clamp(0.0, 1.0);
            let centre = if steep {
                from[0] + dx * t
            } else {
                from[1] + dy * t
            };
            let (min, max) = (
                (centre - reach).floor() as i64,
                (centre + reach).ceil() as i64,
            );
            for minor in min..=max {
                let (x, y) = if steep {
                    (minor, major)
                } else {
                    (major, minor)
                };
                let p = [x as f64 + 0.5, y as f64 + 0.5];
                let u = if length2 > 0.0 {
                    (((p[0] - from[0]) * dx + (p[1] - from[1]) * dy) / length2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let d = (p[0] - from[0] - dx * u).hypot(p[1] - from[1] - dy * u);
                let coverage = (half + 0.5 - d).clamp(0.0, 1.0);
                if coverage > 0.0 {
                    self.blend(x, y, colour, coverage);
                }
            }
        }
    }

    /// A circle's outline of `radius` pixels.
    pub fn ring(&mut self, centre: [f64; 2], radius: f64, colour: [u8; 3]) {
        let r = radius.ceil() as i64 + 2;
        let (cx, cy) = (centre[0].floor() as i64, centre[1].floor() as i64);
        for y in cy - r..=cy + r {
            for x in cx - r..=cx + r {
                let d = (x as f64 + 0.5 - centre[0]).hypot(y as f64 + 0.5 - centre[1]);
                let coverage = (1.25 - (d - radius).abs()).clamp(0.0, 1.0);
                if coverage > 0.0 {
                    self.blend(x, y, colour, coverage);
                }
            }
        }
    }

    /// Text in the 3x5 font at twice its size, its top left corner at `at`; characters the
    /// font lacks are left blank.
    pub fn text(&mut self, at: [f64; 2], text: &str, colour: [u8; 3]) {
        let (x0, y0) = (at[0].round() as i64, at[1].round() as i64);
        for (i, c) in text.chars().enumerate() {
            let rows = glyph(c);
            for (row, bits) in rows.iter().enumerate() {
                for col in 0..3 {
                    if bits & (4 >> col) != 0 {
                        for (sx, sy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                            let x = x0 + i as i64 * 8 + col * 2 + sx;
                            let y = y0 + row as i64 * 2 + sy;
                            self.blend(x, y, colour, 1.0);
                        }
                    }
                }
            }
        }
    }

    /// A triangle in pixels with a depth at each corner (larger is nearer), drawn where it is
    /// nearer than what is there.
    pub fn triangle(&mut self, corners: [[f64; 3]; 3], colour: [u8; 3]) {
        if self.depth.is_empty() {
            self.depth = vec![f32::NEG_INFINITY; self.width as usize * self.height as usize];
        }
        let [a, b, c] = corners;
        let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        if area.abs() < 1e-12 || !corners.iter().flatten().all(|v| v.is_finite()) {
            return;
        }
        let x_min = a[0].min(b[0]).min(c[0]).floor().max(0.0) as i64;
        let x_max = a[0]
            .max(b[0])
            .max(c[0])
            .ceil()
            .min(f64::from(self.width) - 1.0) as i64;
        let y_min = a[1].min(b[1]).min(c[1]).floor().max(0.0) as i64;
        let y_max = a[1]
            .max(b[1])
            .max(c[1])
            .ceil()
            .min(f64::from(self.height) - 1.0) as i64;
        for y in y_min..=y_max {
            for x in x_min..=x_max {
                let p = [x as f64 + 0.5, y as f64 + 0.5];
                let w0 = ((b[0] - p[0]) * (c[1] - p[1]) - (b[1] - p[1]) * (c[0] - p[0])) / area;
                let w1 = ((c[0] - p[0]) * (a[1] - p[1]) - (c[1] - p[1]) * (a[0] - p[0])) / area;
                let w2 = 1.0 - w0 - w1;
                if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                    continue;
                }
                let z = (w0 * a[2] + w1 * b[2] + w2 * c[2]) as f32;
                let i = y as usize * self.width as usize + x as usize;
                if z > self.depth[i] {
                    self.depth[i] = z;
                    self.blend(x, y, colour, 1.0);
                }
            }
        }
    }

    /// The picture as a PNG file's bytes.
    pub fn to_png(&self) -> Vec<u8> {
        let mut bytes = Vec::new();
        let mut encoder = png::Encoder::new(&mut bytes, self.width, self.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        // Writing a well-formed RGB buffer of the header's size into memory cannot fail.
        let mut writer = encoder
            .write_header()
            .expect("a PNG header into memory cannot fail");
        writer
            .write_image_data(&self.pixels)
            .expect("the buffer holds width x height RGB pixels");
        drop(writer);
        bytes
    }
}

/// The 3x5 glyph of a character: five rows of three bits, the left column the high bit.
fn glyph(c: char) -> [u8; 5] {
    match c {
        '0' => [7, 5, 5, 5, 7],
        '1' => [2, 6, 2, 2, 7],
        '2' => [7, 1, 7, 4, 7],
        '3' => [7, 1, 3, 1, 7],
        '4' => [5, 5, 7, 1, 1],
        '5' => [7, 4, 7, 1, 7],
        '6' => [7, 4, 7, 5, 7],
        '7' => [7, 1, 1, 2, 2],
        '8' => [7, 5, 7, 5, 7],
        '9' => [7, 5, 7, 1, 7],
        '.' => [0, 0, 0, 0, 2],
        '-' => [0, 0, 7, 0, 0],
        'm' => [0, 0, 7, 7, 5],
        'X' | 'x' => [5, 5, 2, 5, 5],
        'Y' => [5, 5, 2, 2, 2],
        'Z' => [7, 1, 2, 4, 7],
        'T' => [7, 2, 2, 2, 2],
        _ => [0; 5],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_horizontal_line_covers_its_row_and_not_the_rows_beyond() {
        let mut canvas = Canvas::new(20, 10, WHITE);
        canvas.line([2.0, 5.5], [18.0, 5.5], BLACK, 1.0, None);
        assert_eq!(canvas.pixel(10, 5), BLACK);
        assert_eq!(canvas.pixel(10, 2), WHITE);
        assert_eq!(canvas.pixel(0, 5), WHITE);
    }

    #[test]
    fn a_png_decodes_to_the_canvas() {
        let mut canvas = Canvas::new(4, 3, WHITE);
        canvas.line([0.0, 1.5], [4.0, 1.5], [255, 0, 0], 1.0, None);
        let bytes = canvas.to_png();
        let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
        let mut reader = decoder.read_info().unwrap();
        let mut buffer = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut buffer).unwrap();
        assert_eq!((info.width, info.height), (4, 3));
        assert_eq!(&buffer[3 * 4 + 3..3 * 4 + 6], &[255, 0, 0]);
    }
}
