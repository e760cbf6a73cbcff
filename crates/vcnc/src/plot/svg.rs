//! The toolpath as SVG: one path per run of moves of one kind and tool, arcs of the XY plane as
//! SVG arcs in the top view, everything in pixels of the drawing.

use super::{Element, Layout, Toolpath, View};
use crate::motion::Plane;
use crate::toolpath::ToolMove;
use std::fmt::Write;

/// Writes the drawing.
pub(super) fn draw(path: &Toolpath, layout: &Layout) -> String {
    let mut out = String::new();
    let (w, h) = (layout.width, layout.height);
    // Writing into a String cannot fail.
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">"#
    );
    let _ = writeln!(out, r#"<rect width="{w}" height="{h}" fill="white"/>"#);
    let mut run = Run::default();
    for element in &path.elements {
        match element {
            Element::Move { motion, tool } => {
                let key = (*tool, motion.rapid);
                let start = layout.pixel(motion.from);
                if run.key != Some(key) || !run.ends_at(start) {
                    run.flush(&mut out, path);
                    run.key = Some(key);
                    let _ = write!(run.d, "M{:.3} {:.3}", start[0], start[1]);
                    run.end = start;
                }
                add_move(&mut run, motion, layout);
            }
            Element::ToolChange { at, tool } => {
                run.flush(&mut out, path);
                let [x, y] = layout.pixel(*at);
                let [r, g, b] = path.colour(*tool, false);
                let _ = writeln!(
                    out,
                    r#"<circle class="tool-change" cx="{x:.3}" cy="{y:.3}" r="5" fill="none" stroke="rgb({r},{g},{b})" stroke-width="1.5"/>"#
                );
                let _ = writeln!(
                    out,
                    r#"<text x="{:.3}" y="{:.3}" font-family="sans-serif" font-size="11">T{tool}</text>"#,
                    x + 7.0,
                    y - 6.0
                );
            }
        }
    }
    run.flush(&mut out, path);
    let bar = layout.scale_bar();
    let _ = writeln!(
        out,
        r#"<path class="scale-bar" d="M{:.3} {:.3}H{:.3}M{:.3} {:.3}v-6M{:.3} {:.3}v-6" stroke="black" stroke-width="2" fill="none"/>"#,
        bar.from[0], bar.from[1], bar.to[0], bar.from[0], bar.from[1], bar.to[0], bar.to[1]
    );
    let _ = writeln!(
        out,
        r#"<text x="{:.3}" y="{:.3}" font-family="sans-serif" font-size="12">{}</text>"#,
        bar.from[0],
        bar.from[1] + 16.0,
        bar.label
    );
    let _ = writeln!(
        out,
        r#"<text class="extents" x="8" y="18" font-family="sans-serif" font-size="12">{}</text>"#,
        layout.extents_label
    );
    out.push_str("</svg>\n");
    out
}

/// Moves of one tool and kind that follow each other, as one path's `d`.
#[derive(Default)]
struct Run {
    key: Option<(u32, bool)>,
    d: String,
    end: [f64; 2],
}

impl Run {
    fn ends_at(&self, p: [f64; 2]) -> bool {
        (self.end[0] - p[0]).abs() < 1e-3 && (self.end[1] - p[1]).abs() < 1e-3
    }

    fn flush(&mut self, out: &mut String, path: &Toolpath) {
        if let Some((tool, rapid)) = self.key.take() {
            let [r, g, b] = path.colour(tool, rapid);
            let (class, dash) = if rapid {
                ("rapid", r#" stroke-dasharray="6 4""#)
            } else {
                ("feed", "")
            };
            let _ = writeln!(
                out,
                r#"<path class="{class}" data-tool="{tool}" d="{}" fill="none" stroke="rgb({r},{g},{b})" stroke-width="1.2"{dash}/>"#,
                self.d
            );
            self.d.clear();
        }
    }
}

/// One move into the run's path: an SVG arc for an XY arc in the top view, else lines.
fn add_move(run: &mut Run, motion: &ToolMove, layout: &Layout) {
    match motion.arc {
        Some(arc) if layout.view == View::Top && arc.plane == Plane::Xy => {
            // SVG draws an arc of at most a half turn well: cut longer ones in equal pieces.
            let pieces = (arc.sweep.abs() / (0.99 * std::f64::consts::PI))
                .ceil()
                .max(1.0);
            let start = (motion.from[1] - arc.center[1]).atan2(motion.from[0] - arc.center[0]);
            let radius = arc.radius * layout.scale;
            // Y points down in SVG: a counter-clockwise arc is drawn with the sweep flag 0.
            let sweep_flag = u8::from(arc.sweep < 0.0);
            for i in 1..=pieces as usize {
                let angle = start + arc.sweep * i as f64 / pieces;
                let end = if i == pieces as usize {
                    layout.pixel(motion.to)
                } else {
                    layout.pixel([
                        arc.center[0] + arc.radius * angle.cos(),
                        arc.center[1] + arc.radius * angle.sin(),
                        motion.from[2],
                    ])
                };
                let _ = write!(
                    run.d,
                    "A{radius:.3} {radius:.3} 0 0 {sweep_flag} {:.3} {:.3}",
                    end[0], end[1]
                );
                run.end = end;
            }
        }
        _ => motion.for_each_point(layout.tolerance, |p| {
            let q = layout.pixel(p);
            let _ = write!(run.d, "L{:.3} {:.3}", q[0], q[1]);
            run.end = q;
        }),
    }
}
