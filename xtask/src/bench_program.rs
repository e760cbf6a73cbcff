//! `cargo xtask bench-program [--sinumerik] [N]`: writes the CAM-style benchmark program of N
//! motion blocks (default 400,000) to stdout, for the whole-process comparisons in
//! docs/benchmarks.md: in ISO form (against LinuxCNC), or the same path in SINUMERIK form
//! (against its ISO twin). The generator is the `interp` bench's own, included here so that
//! there is one copy of it.

use std::io::Write;

#[path = "../../crates/vcnc/benches/support/cam_program.rs"]
mod cam_program;

use cam_program::Style;

/// Motion blocks when no count is given: the size the speed target is stated for.
const DEFAULT_BLOCKS: usize = 400_000;

const USAGE: &str = "usage: cargo xtask bench-program [--sinumerik] [BLOCKS]";

pub(crate) fn run(args: &[String]) -> Result<(), String> {
    let (style, args) = match args {
        [flag, rest @ ..] if flag == "--sinumerik" => (Style::Sinumerik, rest),
        _ => (Style::Iso, args),
    };
    let blocks = match args {
        [] => DEFAULT_BLOCKS,
        [count] => count
            .replace('_', "")
            .parse()
            .map_err(|_| format!("`{count}` is not a number of blocks\n{USAGE}"))?,
        _ => return Err(USAGE.into()),
    };
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::with_capacity(1 << 16, stdout.lock());
    cam_program::write_program_in(&mut out, blocks, style)
        .and_then(|()| out.flush())
        .map_err(|e| format!("cannot write the program: {e}"))
}

#[cfg(test)]
mod tests {
    use super::cam_program::{program_in, Style};
    use vcnc::{Machine, Pipeline, SegmentKind};

    /// The moves the program traces (where each goes, its feed, and an arc's centre), with any
    /// alarm as a failure.
    fn moves(text: &str, name: &str) -> Vec<String> {
        Pipeline::new(&Machine::default())
            .open_text(text, name)
            .filter_map(|item| {
                let segment = match item {
                    Ok(vcnc::Item::Segment(segment)) => segment,
                    Ok(vcnc::Item::Frame(_)) => return None,
                    Ok(vcnc::Item::Warning(alarm)) | Err(alarm) => panic!("{name}: {alarm:?}"),
                };
                let motion = segment.motion()?;
                let centre = match segment.kind {
                    SegmentKind::Arc { center, .. } => format!(" around {center:?}"),
                    _ => String::new(),
                };
                Some(format!("{:?}{centre}", motion.to))
            })
            .collect()
    }

    #[test]
    fn the_sinumerik_twin_traces_the_iso_programs_path() {
        // 2,500 blocks: 250 arcs, R and I J, short and long (negative CR), and the comment
        // lines between passes.
        let iso = program_in(2_500, Style::Iso);
        let sinumerik = program_in(2_500, Style::Sinumerik);
        assert!(sinumerik.contains("CR=-") && sinumerik.contains("DEF REAL FEED1"));
        let (iso, sinumerik) = (moves(&iso, "bench.nc"), moves(&sinumerik, "bench.mpf"));
        assert!(iso.len() > 2_500, "{} moves", iso.len());
        for (i, (a, b)) in iso.iter().zip(&sinumerik).enumerate() {
            assert_eq!(a, b, "move {i}");
        }
        assert_eq!(iso.len(), sinumerik.len());
    }
}
