//! The toolpath drawn to scale: a consumer of the motion stream that keeps the tool's moves
//! ([`Toolpath`]) and draws them from a [`View`] as SVG ([`Toolpath::to_svg`]) or PNG
//! ([`Toolpath::to_png`]).
//!
//! Rapids are dashed, cutting moves coloured by tool, tool changes marked; the drawing has its
//! extents and a scale bar. In the top view an arc in the XY plane is an SVG arc; elsewhere
//! arcs are chords within a hundredth of the drawing's pixel. The PNG is rasterised here (a
//! small anti-aliased line rasteriser, [`raster`]), no graphics stack.
//!
//! The toolpath is held whole (a drawing needs its extents before its first line): memory grows
//! with the program's moves, a few dozen bytes each.

pub mod raster;
mod svg;

use crate::motion::Item;
use crate::source::Span;
use crate::toolpath::{Followed, ToolFollower, ToolMove, Unfollowed};

/// Where the toolpath is seen from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum View {
    /// Looking down Z: X to the right, Y up.
    #[default]
    Top,
    /// Looking along +Y: X to the right, Z up.
    Front,
    /// Looking along -X: Y to the right, Z up.
    Side,
    /// Isometric: X to the lower right, Y to the upper right, Z up.
    Iso,
}

impl View {
    /// Reads `top`, `front`, `side` or `iso`.
    pub fn parse(text: &str) -> Option<View> {
        match text {
            "top" => Some(View::Top),
            "front" => Some(View::Front),
            "side" => Some(View::Side),
            "iso" => Some(View::Iso),
            _ => None,
        }
    }

    /// The point as drawn: right and up, mm.
    pub fn project(self, p: [f64; 3]) -> [f64; 2] {
        // cos 30° and sin 30° of the isometric axes.
        const COS: f64 = 0.866_025_403_784_438_6;
        match self {
            View::Top => [p[0], p[1]],
            View::Front => [p[0], p[2]],
            View::Side => [p[1], p[2]],
            View::Iso => [(p[0] - p[1]) * COS, p[2] + (p[0] + p[1]) * 0.5],
        }
    }

    /// The names of the drawing's axes, right then up.
    pub fn axis_names(self) -> (&'static str, &'static str) {
        match self {
            View::Top => ("X", "Y"),
            View::Front => ("X", "Z"),
            View::Side => ("Y", "Z"),
            View::Iso => ("iso", "iso"),
        }
    }
}

/// One thing to draw.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Element {
    Move { motion: ToolMove, tool: u32 },
    ToolChange { at: [f64; 3], tool: u32 },
}

/// The moves of a run, kept to be drawn.
#[derive(Clone, Debug, Default)]
pub struct Toolpath {
    follower: ToolFollower,
    elements: Vec<Element>,
    tools: Vec<u32>,
    pending_change: Option<u32>,
    unfollowed: Option<(Unfollowed, Span, usize)>,
}

impl Toolpath {
    /// An empty toolpath.
    pub fn new() -> Toolpath {
        Toolpath::default()
    }

    /// Draws `machine`'s per-axis (dog-leg) rapids along the path its axes take.
    pub fn per_axis_rapids(&mut self, machine: &crate::machine::Machine) {
        self.follower.per_axis_rapids(machine);
    }

    /// Takes one item of the stream.
    pub fn add(&mut self, item: &Item) {
        match self.follower.follow(item) {
            Followed::Move(motion) => {
                let tool = self.follower.tool().number;
                if let Some(tool) = self.pending_change.take() {
                    // Marked where the new tool first arrives: the change itself is usually
                    // far away, at the machine's home.
                    self.elements.push(Element::ToolChange {
                        at: motion.to,
                        tool,
                    });
                }
                if !self.tools.contains(&tool) {
                    self.tools.push(tool);
                }
                self.elements.push(Element::Move { motion, tool });
            }
            Followed::ToolChange(tool, _) => self.pending_change = Some(tool.number),
            Followed::Unfollowed(why, span) => {
                let entry = self.unfollowed.get_or_insert((why, span, 0));
                entry.2 += 1;
            }
            Followed::Other => {}
        }
    }

    /// How many moves it holds.
    pub fn moves(&self) -> usize {
        self.elements
            .iter()
            .filter(|e| matches!(e, Element::Move { .. }))
            .count()
    }

    /// The first move that could not be drawn (rotary axes, a tool not along Z), with the
    /// count of such moves: none of them is drawn.
    pub fn unfollowed(&self) -> Option<(Unfollowed, Span, usize)> {
        self.unfollowed
    }

    /// The extents of the cutting moves in part coordinates, `[min, max]`, arcs through their
    /// chords (of all moves when none cuts): the drawing is framed on them, so that rapids
    /// from and to the machine's home do not shrink the part to a dot.
    pub fn extents(&self) -> Option<[[f64; 3]; 2]> {
        let cuts = self
            .elements
            .iter()
            .any(|e| matches!(e, Element::Move { motion, .. } if !motion.rapid));
        let mut extents: Option<[[f64; 3]; 2]> = None;
        let mut grow = |p: [f64; 3]| {
            let e = extents.get_or_insert([p, p]);
            for i in 0..3 {
                e[0][i] = e[0][i].min(p[i]);
                e[1][i] = e[1][i].max(p[i]);
            }
        };
        for element in &self.elements {
            if let Element::Move { motion, .. } = element {
                if motion.rapid && cuts {
                    continue;
                }
                grow(motion.from);
                motion.for_each_point(0.001, &mut grow);
            }
        }
        extents
    }

    /// The drawing as SVG text, `width` pixels wide.
    pub fn to_svg(&self, view: View, width: u32) -> String {
        svg::draw(self, &self.layout(view, width))
    }

    /// The drawing as a PNG file's bytes, `width` pixels wide.
    pub fn to_png(&self, view: View, width: u32) -> Vec<u8> {
        let layout = self.layout(view, width);
        let mut canvas = raster::Canvas::new(layout.width, layout.height, raster::WHITE);
        for element in &self.elements {
            match element {
                Element::Move { motion, tool } => {
                    let colour = self.colour(*tool, motion.rapid);
                    let mut from = layout.pixel(motion.from);
                    let dash = motion.rapid.then_some(6.0);
                    motion.for_each_point(layout.tolerance, |p| {
                        let to = layout.pixel(p);
                        canvas.line(from, to, colour, 1.2, dash);
                        from = to;
                    });
                }
                Element::ToolChange { at, tool } => {
                    let [x, y] = layout.pixel(*at);
                    canvas.ring([x, y], 5.0, self.colour(*tool, false));
                    canvas.text([x + 7.0, y - 9.0], &format!("T{tool}"), raster::BLACK);
                }
            }
        }
        let bar = layout.scale_bar();
        canvas.line(bar.from, bar.to, raster::BLACK, 2.0, None);
        canvas.text([bar.from[0], bar.from[1] + 6.0], &bar.label, raster::BLACK);
        canvas.text([8.0, 8.0], &layout.extents_label, raster::BLACK);
        canvas.to_png()
    }

    fn colour(&self, tool: u32, rapid: bool) -> [u8; 3] {
        if rapid {
            return RAPID_COLOUR;
        }
        let slot = self.tools.iter().position(|&t| t == tool).unwrap_or(0);
        PALETTE[slot % PALETTE.len()]
    }

    fn layout(&self, view: View, width: u32) -> Layout {
        let extents = self.extents().unwrap_or([[0.0; 3], [1.0; 3]]);
        // The drawing's box: the projection of the extents' eight corners.
        let mut low = [f64::INFINITY; 2];
        let mut high = [f64::NEG_INFINITY; 2];
        for corner in 0..8 {
            let p = std::array::from_fn(|i| extents[(corner >> i) & 1][i]);
            let q = view.project(p);
            for i in 0..2 {
                low[i] = low[i].min(q[i]);
                high[i] = high[i].max(q[i]);
            }
        }
        let width = width.clamp(100, 20_000);
        let margin = 40.0;
        let span = [(high[0] - low[0]).max(1e-3), (high[1] - low[1]).max(1e-3)];
        let scale = (f64::from(width) - 2.0 * margin) / span[0].max(span[1] * 0.25);
        let height = (span[1] * scale + 2.0 * margin + 30.0).clamp(100.0, 20_000.0) as u32;
        let extents_label = format!(
            "X {:.3} .. {:.3}  Y {:.3} .. {:.3}  Z {:.3} .. {:.3}",
            extents[0][0],
            extents[1][0],
            extents[0][1],
            extents[1][1],
            extents[0][2],
            extents[1][2]
        );
        Layout {
            view,
            width,
            height,
            scale,
            low,
            high,
            margin,
            tolerance: 0.01 / scale,
            extents_label,
        }
    }
}

/// The colour of rapids (dashed).
pub const RAPID_COLOUR: [u8; 3] = [150, 150, 150];

/// The colours of cutting moves, one per tool in the order the tools first cut (then again).
pub const PALETTE: [[u8; 3]; 8] = [
    [31, 119, 180],
    [214, 39, 40],
    [44, 160, 44],
    [255, 127, 14],
    [148, 103, 189],
    [140, 86, 75],
    [227, 119, 194],
    [23, 190, 207],
];

/// Where the drawing's points go in pixels.
#[derive(Clone, Debug)]
struct Layout {
    view: View,
    width: u32,
    height: u32,
    /// Pixels per mm.
    scale: f64,
    low: [f64; 2],
    high: [f64; 2],
    margin: f64,
    /// Chord tolerance of arcs, mm: a hundredth of a pixel.
    tolerance: f64,
    extents_label: String,
}

/// A scale bar: a round length of about a fifth of the drawing.
struct ScaleBar {
    from: [f64; 2],
    to: [f64; 2],
    label: String,
}

impl Layout {
    /// The pixel of a point (y down).
    fn pixel(&self, p: [f64; 3]) -> [f64; 2] {
        let q = self.view.project(p);
        [
            self.margin + (q[0] - self.low[0]) * self.scale,
            self.margin + 20.0 + (self.high[1] - q[1]) * self.scale,
        ]
    }

    fn scale_bar(&self) -> ScaleBar {
        let target = (f64::from(self.width) - 2.0 * self.margin) / 5.0 / self.scale;
        let magnitude = 10f64.powf(target.log10().floor());
        let length = [5.0, 2.0, 1.0]
            .into_iter()
            .map(|m| m * magnitude)
            .find(|&l| l <= target)
            .unwrap_or(magnitude);
        let y = f64::from(self.height) - 22.0;
        let x = f64::from(self.width) - self.margin - length * self.scale;
        ScaleBar {
            from: [x, y],
            to: [x + length * self.scale, y],
            label: format!("{} mm", trim_number(length)),
        }
    }
}

/// A length as written by people: `10`, `0.5`, `0.02`.
fn trim_number(value: f64) -> String {
    let text = format!("{value:.6}");
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_scale_bar_is_a_round_length() {
        assert_eq!(trim_number(20.0), "20");
        assert_eq!(trim_number(0.05), "0.05");
        let layout = Layout {
            view: View::Top,
            width: 1000,
            height: 600,
            scale: 8.0,
            low: [0.0; 2],
            high: [115.0; 2],
            margin: 40.0,
            tolerance: 0.001,
            extents_label: String::new(),
        };
        // A fifth of 920 px at 8 px/mm is 23 mm: the bar is 20 mm, 160 px.
        let bar = layout.scale_bar();
        assert_eq!(bar.label, "20 mm");
        assert!((bar.to[0] - bar.from[0] - 160.0).abs() < 1e-9);
    }
}
