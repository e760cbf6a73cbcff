//! The toolpath plot: a consumer of the pipeline's stream drawing SVG and PNG to scale.

use vcnc::pipeline::Pipeline;
use vcnc::plan::PlanOptions;
use vcnc::plot::{Toolpath, View};
use vcnc::Machine;

fn toolpath(text: &str) -> Toolpath {
    let mut path = Toolpath::new();
    let mut stream = Pipeline::new(&Machine::default()).open_text(text, "plot.nc");
    stream.for_each_timed(PlanOptions::default(), |items, _| {
        for item in items.iter().flatten() {
            path.add(item);
        }
        true
    });
    path
}

const SQUARE: &str =
    "T1 M6\nG0 X0 Y0 Z5.\nG1 Z-1. F300.\nX100.\nY50.\nG3 X50. Y100. R50.\nG1 X0\nY0\nG0 Z5.\nT2 M6\nG0 X20. Y20.\nG1 Z-2.\nG0 Z5.\nM30\n";

#[test]
fn the_svg_has_dashed_rapids_arcs_and_tool_changes() {
    let path = toolpath(SQUARE);
    assert_eq!(path.extents().unwrap()[1][0], 100.0);
    let svg = path.to_svg(View::Top, 800);
    assert!(svg.starts_with("<svg"));
    assert!(svg.contains(r#"class="rapid""#) && svg.contains("stroke-dasharray"));
    // The G3 is one SVG arc (a quarter turn, counter-clockwise: sweep flag 0).
    assert_eq!(svg.matches(" 0 0 0 ").count(), 1, "{svg}");
    assert_eq!(svg.matches(r#"class="tool-change""#).count(), 2);
    // Two tools cut: two colours of feed paths.
    assert!(svg.contains(r#"data-tool="1""#) && svg.contains(r#"data-tool="2""#));
    // In the front view the arc is chords.
    assert!(!path.to_svg(View::Front, 800).contains(" 0 0 0 "));
}

#[test]
fn the_png_has_path_pixels_where_the_layout_puts_them() {
    let path = toolpath(SQUARE);
    let bytes = path.to_png(View::Top, 600);
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = decoder.read_info().unwrap();
    let mut buffer = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buffer).unwrap();
    assert_eq!(info.width, 600);
    // The layout: 40 px margins, 520 px for the 100 mm of X: 5.2 px/mm; the top edge 20 px
    // lower (the extents line). The line Y0 from X0 to X100 lies at y = 40 + 20 + 100 * 5.2
    // = 580 px (Y100 is the top); its middle X50 at x = 40 + 50 * 5.2 = 300 px.
    let pixel = |x: usize, y: usize| {
        let i = (y * info.width as usize + x) * 3;
        [buffer[i], buffer[i + 1], buffer[i + 2]]
    };
    assert_ne!(pixel(300, 580), [255, 255, 255]);
    assert_eq!(pixel(300, 570), [255, 255, 255]);
}
