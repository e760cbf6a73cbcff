//! `cargo xtask bench-jumps PLAIN DIR`: reads the CAM-style benchmark program PLAIN (written by
//! `cargo xtask bench-program N`) and writes three variants of it into DIR that jump or call near
//! the start: `while.nc` (a WHILE loop of three passes), `m98.nc` (an M98 call of a subprogram that
//! follows M30 in the same file) and `g65.nc` (a chain of three G65 macro calls, each program
//! after M30). docs/benchmarks.md compares their peak memory and time with the plain program's:
//! a jump or a call must not make a long program's memory grow with its length.
//!
//! Invariants: the variants are the plain program with a few lines added after its header and
//! after its end, so their motion differs from it by a handful of moves; program numbers 2000 and
//! up, clear of the header's O1000. It never changes PLAIN.

use std::io::Write;
use std::path::Path;

/// The last line of the benchmark program's header: the variants' lines go right after it.
const HEADER_END: &str = "G01 Z-1. F1500.\n";

/// Each variant: its file name, the lines after the header, the programs after the end.
const VARIANTS: [(&str, &str, &str); 3] = [
    (
        "while.nc",
        "#1=0\nWHILE[#1LT3]DO1\nG01 X#1 Y1.\n#1=#1+1\nEND1\n",
        "",
    ),
    (
        "m98.nc",
        "M98 P2000\n",
        "O2000\nG01 X10. Y10.\nG01 X20.\nM99\n",
    ),
    (
        "g65.nc",
        "G65 P2001 A1.\n",
        "O2001\nG01 X#1 Y1.\nG65 P2002 A[#1+1]\nM99\n\
         O2002\nG01 Y#1\nG65 P2003 A[#1+1]\nM99\n\
         O2003\nG01 X#1 Y#1\nM99\n",
    ),
];

pub(crate) fn run(args: &[String]) -> Result<(), String> {
    let [plain, directory] = args else {
        return Err("usage: cargo xtask bench-jumps PLAIN DIR".into());
    };
    let program = std::fs::read(plain).map_err(|e| format!("cannot read {plain}: {e}"))?;
    let directory = Path::new(directory);
    std::fs::create_dir_all(directory)
        .map_err(|e| format!("cannot create {}: {e}", directory.display()))?;
    let header_end = program
        .windows(HEADER_END.len())
        .position(|w| w == HEADER_END.as_bytes())
        .map(|at| at + HEADER_END.len())
        .ok_or_else(|| format!("{plain} is not the benchmark program (no header)"))?;
    for (name, after_header, after_end) in VARIANTS {
        let path = directory.join(name);
        let write = || -> std::io::Result<()> {
            let mut out = std::io::BufWriter::new(std::fs::File::create(&path)?);
            out.write_all(&program[..header_end])?;
            out.write_all(after_header.as_bytes())?;
            out.write_all(&program[header_end..])?;
            out.write_all(after_end.as_bytes())?;
            out.flush()
        };
        write().map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    }
    Ok(())
}
