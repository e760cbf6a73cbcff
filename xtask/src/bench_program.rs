//! `cargo xtask bench-program [N]`: writes the CAM-style benchmark program of N motion blocks
//! (default 400,000) to stdout, for the whole-process comparison with LinuxCNC in
//! docs/benchmarks.md. The generator is the `interp` bench's own, included here so that there is
//! one copy of it.

use std::io::Write;

#[path = "../../crates/vcnc/benches/support/cam_program.rs"]
mod cam_program;

/// Motion blocks when no count is given: the size the speed target is stated for.
const DEFAULT_BLOCKS: usize = 400_000;

pub(crate) fn run(args: &[String]) -> Result<(), String> {
    let blocks = match args {
        [] => DEFAULT_BLOCKS,
        [count] => count
            .replace('_', "")
            .parse()
            .map_err(|_| format!("`{count}` is not a number of blocks"))?,
        _ => return Err("usage: cargo xtask bench-program [BLOCKS]".into()),
    };
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::with_capacity(1 << 16, stdout.lock());
    cam_program::write_program(&mut out, blocks)
        .and_then(|()| out.flush())
        .map_err(|e| format!("cannot write the program: {e}"))
}
