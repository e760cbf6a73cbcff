//! A reader for the canonical calls LinuxCNC's standalone interpreter prints with `rs274 -g`,
//! turned into moves in machine coordinates and millimetres.
//!
//! Included by integration tests with `#[path = "common/lcnc_canon.rs"] mod lcnc_canon;`; it uses
//! `std` only and knows nothing of vcnc.
//!
//! # What a row of `rs274 -g` output looks like
//!
//! ```text
//!    13 N4     ARC_FEED(10.0000, 0.0000, 5.0000, 0.0000, -1, 0.0000, 0.0000, 0.0000, 0.0000)
//! ```
//!
//! - The first column is a counter of canonical calls (1, 2, 3 ... for the whole run, several per
//!   block), **not** a source line number.
//! - The second column is the `N` word of the block that made the call, copied digit for digit
//!   from the block's text (`N0123` prints as `N0123`) and padded with spaces to six digits, or
//!   `N.....` when the block has no `N` word (the start-up and some end-of-program calls also
//!   print `N.....`). It is the only source position rs274 reports, so the fixture programs in
//!   `tests/data/lcnc/` give every code line an `N` word equal to its 1-based line number in the
//!   file, and [`CanonMove::line`] is that number (0 where the block had no `N` word).
//! - Numbers are printed with four decimals (`%.4f`), in the program's units at the time of the
//!   call: 0.00005 mm of rounding in G21, 0.00005 inch (1.3 µm) in G20.
//!
//! # From canonical calls to machine coordinates
//!
//! The motion calls (`STRAIGHT_TRAVERSE`, `STRAIGHT_FEED`, `ARC_FEED`) carry *program*
//! coordinates in the current length units. The offsets arrive as separate calls whose values are
//! in the length units in force **when the call is made**; LinuxCNC's motion layer (`emccanon.cc`)
//! converts each value to millimetres at that moment and keeps it in millimetres, so a later
//! `USE_LENGTH_UNITS` does not rescale offsets already set. This reader does the same:
//!
//! ```text
//! machine = program * unit + g5x + g92 + tool      (per axis, millimetres)
//! unit    = 1 after USE_LENGTH_UNITS(CANON_UNITS_MM), 25.4 after ..._INCHES (10 for ..._CM)
//! ```
//!
//! | call | set by | becomes |
//! |---|---|---|
//! | `SET_G5X_OFFSET(n, x, y, z, ...)` | selecting G54..G59 (`n` = 1..6), `G10 L2` on the active system, program start and end | `g5x = (x, y, z) * unit` |
//! | `SET_G92_OFFSET(x, y, z, ...)` | `G92` (the offset that makes the current point read the given values), **`G52`** (LinuxCNC implements G52 with the G92 offset), `G92.1` | `g92 = (x, y, z) * unit` |
//! | `SET_ORIGIN_OFFSETS(x, y, z, ...)` | older LinuxCNC versions: G5x and G92 summed | `g5x = (x, y, z) * unit`, `g92 = 0` |
//! | `USE_TOOL_LENGTH_OFFSET(x y z, a b c, u v w)` | `G43 Hn` (the tool table length, converted to the current units), `G49` (zeros) | `tool = (x, y, z) * unit` |
//! | `USE_LENGTH_UNITS(CANON_UNITS_MM / _INCHES)` | `G21` / `G20` | `unit` |
//! | `SET_XY_ROTATION(deg)` | `G10 L2 R` (LinuxCNC only) | an error unless 0 |
//! | `SET_FEED_RATE(f)` | `F`; in G93 rs274 itself sends per move the equivalent units/min rate | feed = `f * unit` mm/min |
//! | `SET_FEED_MODE(spindle, mode)` | G93/G94 (mode 0: rs274 converts inverse time itself), G95 (mode 1) | an error unless 0 |
//!
//! `G53` moves and the two legs of `G28` need nothing special: rs274 prints them as ordinary
//! traverses whose program coordinates already subtract the active offsets (`G28`'s home leg is
//! machine 0 = `#5161..#5163` = 0 on a fresh parameter file).
//!
//! # Arcs
//!
//! `ARC_FEED(first_end, second_end, first_axis, second_axis, rotation, axis_end_point, a, b, c ...)`:
//! "first" and "second" are the plane's axes in LinuxCNC's order, and `axis_end_point` is the end on
//! the axis normal to the plane:
//!
//! | plane | `SELECT_PLANE` | first | second | normal |
//! |---|---|---|---|---|
//! | G17 | `CANON_PLANE_XY` | X | Y | Z |
//! | G18 | `CANON_PLANE_XZ` | Z | X | Y |
//! | G19 | `CANON_PLANE_YZ` | Y | Z | X |
//!
//! `rotation` is positive for counter-clockwise (G3) and negative for clockwise (G2), seen from the
//! positive end of the normal axis; its magnitude is the number of turns (1 for every ordinary arc
//! and for a full circle, where the end point equals the start point). The centre's normal-axis
//! coordinate is not defined by rs274; the `center` of [`CanonKind::Arc`] carries the arc's start value
//! there.
//!
//! # Start position
//!
//! rs274 starts with the program position at 0 and, on a fresh parameter file, all offsets 0, so
//! the first move starts at machine (0, 0, 0). Moves of zero length are kept (for example the
//! intermediate point of `G91 G28 Z0`); a comparison may skip them.
//!
//! # Tool table
//!
//! The standalone rs274 has no INI machine units: it reads the tool table in **inches**
//! (`GET_EXTERNAL_LENGTH_UNITS` is hard-wired to inch, and `-i` does not change it), so `Z+1.0`
//! in `tool.tbl` is a 25.4 mm tool length. [`parse_tool_table`] returns the lengths in mm.
#![allow(dead_code, unreachable_pub)]

/// One motion of the canonical output, in machine coordinates and millimetres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CanonMove {
    /// The `N` word of the block that made the move (the fixtures' `N` words are their line
    /// numbers); 0 when the block had none.
    pub line: u32,
    pub kind: CanonKind,
    /// Where the X, Y and Z axes are at the end of the move, machine coordinates in mm.
    pub to: [f64; 3],
}

/// What kind of motion a [`CanonMove`] is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CanonKind {
    /// `STRAIGHT_TRAVERSE`: G0, and the legs of G28 and G53 G0.
    Rapid,
    /// `STRAIGHT_FEED` at the feed in force, mm/min.
    Feed { feed_mm_per_min: f64 },
    /// `ARC_FEED`: a circular or helical move. `center` is in machine mm; its coordinate on the
    /// axis normal to the plane is the arc's start value on that axis.
    Arc {
        center: [f64; 3],
        clockwise: bool,
        plane: CanonPlane,
        turns: u32,
    },
    /// `DWELL`: no motion; `to` is where the machine waits.
    Dwell { seconds: f64 },
}

/// The plane of an arc: G17 (XY), G18 (ZX) or G19 (YZ).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CanonPlane {
    Xy,
    Zx,
    Yz,
}

impl CanonPlane {
    /// The machine-axis indices of LinuxCNC's first axis, second axis and normal axis.
    pub fn axes(self) -> (usize, usize, usize) {
        match self {
            CanonPlane::Xy => (0, 1, 2),
            CanonPlane::Zx => (2, 0, 1),
            CanonPlane::Yz => (1, 2, 0),
        }
    }
}

/// Reads `rs274 -g` output and returns its moves in machine coordinates (see the module docs for
/// how offsets and units are applied). Calls that do not move the machine are skipped; motion
/// this reader cannot represent (probing, rigid tapping, spindle-synchronised or per-revolution
/// feed, splines, XY rotation) is an error, as is a row it cannot read.
pub fn parse_canon(text: &str) -> Result<Vec<CanonMove>, String> {
    let mut state = State::default();
    let mut moves = Vec::new();
    for (index, row) in text.lines().enumerate() {
        if row.trim().is_empty() {
            continue;
        }
        let call = split_row(row).map_err(|e| format!("canon row {}: {e}: `{row}`", index + 1))?;
        state
            .apply(&call, &mut moves)
            .map_err(|e| format!("canon row {}: {e}: `{row}`", index + 1))?;
    }
    Ok(moves)
}

/// One tool of a LinuxCNC tool table, converted to millimetres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LcncTool {
    pub number: u32,
    /// `Z` of the table times 25.4: the length rs274 applies for `G43 H<number>`.
    pub length_mm: f64,
    /// `D` of the table times 25.4 (0 when absent).
    pub diameter_mm: f64,
}

/// Reads a LinuxCNC tool table (`T1 P1 Z+1.000000 D0.250000 ;comment`). rs274 reads it in inches;
/// the lengths and diameters returned are in mm.
pub fn parse_tool_table(text: &str) -> Result<Vec<LcncTool>, String> {
    let mut tools = Vec::new();
    for (index, line) in text.lines().enumerate() {
        let data = line.split(';').next().unwrap_or("");
        let mut number = None;
        let mut length = 0.0;
        let mut diameter = 0.0;
        for word in data.split_whitespace() {
            let mut chars = word.chars();
            let letter = chars.next().map(|c| c.to_ascii_uppercase());
            let value = chars.as_str();
            let bad = || format!("tool table line {}: cannot read `{word}`", index + 1);
            match letter {
                Some('T') => number = Some(value.parse::<u32>().map_err(|_| bad())?),
                Some('Z') => length = value.parse::<f64>().map_err(|_| bad())?,
                Some('D') => diameter = value.parse::<f64>().map_err(|_| bad())?,
                _ => {}
            }
        }
        if let Some(number) = number {
            tools.push(LcncTool {
                number,
                length_mm: length * INCH,
                diameter_mm: diameter * INCH,
            });
        }
    }
    Ok(tools)
}

const INCH: f64 = 25.4;

/// One row split into its parts.
struct Call<'a> {
    line: u32,
    name: &'a str,
    args: &'a str,
}

/// Splits `"   12 N4     NAME(args)"` into the N number, the call name and its argument text.
fn split_row(row: &str) -> Result<Call<'_>, String> {
    let rest = row.trim_start();
    let digits = rest.len() - rest.trim_start_matches(|c: char| c.is_ascii_digit()).len();
    if digits == 0 {
        return Err("no call counter".to_string());
    }
    let rest = rest[digits..].trim_start();
    let Some(rest) = rest.strip_prefix('N') else {
        return Err("no N column".to_string());
    };
    let (line, rest) = if let Some(rest) = rest.strip_prefix(".....") {
        (0, rest)
    } else {
        let digits = rest.len() - rest.trim_start_matches(|c: char| c.is_ascii_digit()).len();
        if digits == 0 {
            return Err("N column has neither digits nor `.....`".to_string());
        }
        let line = rest[..digits]
            .parse::<u32>()
            .map_err(|_| "N number too large".to_string())?;
        (line, &rest[digits..])
    };
    let rest = rest.trim();
    let (Some(open), Some(close)) = (rest.find('('), rest.rfind(')')) else {
        return Err("no `NAME(...)` call".to_string());
    };
    if close < open {
        return Err("unbalanced parentheses".to_string());
    }
    Ok(Call {
        line,
        name: rest[..open].trim(),
        args: &rest[open + 1..close],
    })
}

/// The numbers of an argument list; commas and spaces both separate them.
fn numbers(args: &str) -> Result<Vec<f64>, String> {
    args.split([',', ' '])
        .filter(|s| !s.is_empty())
        .map(|s| {
            s.parse::<f64>()
                .map_err(|_| format!("`{s}` is not a number"))
        })
        .collect()
}

fn at_least(values: &[f64], n: usize) -> Result<(), String> {
    if values.len() < n {
        return Err(format!(
            "expected at least {n} numbers, found {}",
            values.len()
        ));
    }
    Ok(())
}

/// The canonical machine state the reader keeps, all lengths in mm.
struct State {
    unit: f64,
    g5x: [f64; 3],
    g92: [f64; 3],
    tool: [f64; 3],
    plane: CanonPlane,
    feed_mm_per_min: f64,
    position: [f64; 3],
}

impl Default for State {
    fn default() -> Self {
        State {
            unit: 1.0,
            g5x: [0.0; 3],
            g92: [0.0; 3],
            tool: [0.0; 3],
            plane: CanonPlane::Xy,
            feed_mm_per_min: 0.0,
            position: [0.0; 3],
        }
    }
}

impl State {
    /// Machine mm of a value on `axis` given in program coordinates and current units.
    fn machine(&self, axis: usize, program: f64) -> f64 {
        program * self.unit + self.g5x[axis] + self.g92[axis] + self.tool[axis]
    }

    fn machine_xyz(&self, v: &[f64]) -> [f64; 3] {
        [
            self.machine(0, v[0]),
            self.machine(1, v[1]),
            self.machine(2, v[2]),
        ]
    }

    fn scaled(&self, v: &[f64]) -> [f64; 3] {
        [v[0] * self.unit, v[1] * self.unit, v[2] * self.unit]
    }

    fn apply(&mut self, call: &Call<'_>, moves: &mut Vec<CanonMove>) -> Result<(), String> {
        let line = call.line;
        match call.name {
            "USE_LENGTH_UNITS" => {
                self.unit = match call.args.trim() {
                    "CANON_UNITS_MM" => 1.0,
                    "CANON_UNITS_INCHES" => INCH,
                    "CANON_UNITS_CM" => 10.0,
                    other => return Err(format!("unknown length unit `{other}`")),
                };
            }
            "SET_G5X_OFFSET" => {
                let v = numbers(call.args)?;
                at_least(&v, 4)?;
                self.g5x = self.scaled(&v[1..4]);
            }
            "SET_G92_OFFSET" => {
                let v = numbers(call.args)?;
                at_least(&v, 3)?;
                self.g92 = self.scaled(&v[..3]);
            }
            "SET_ORIGIN_OFFSETS" => {
                let v = numbers(call.args)?;
                at_least(&v, 3)?;
                self.g5x = self.scaled(&v[..3]);
                self.g92 = [0.0; 3];
            }
            "USE_TOOL_LENGTH_OFFSET" => {
                let v = numbers(call.args)?;
                self.tool = match v.len() {
                    1 => [0.0, 0.0, v[0] * self.unit],
                    2 => [v[0] * self.unit, 0.0, v[1] * self.unit],
                    0 => return Err("no tool offset values".to_string()),
                    _ => self.scaled(&v[..3]),
                };
            }
            "SET_XY_ROTATION" => {
                let v = numbers(call.args)?;
                at_least(&v, 1)?;
                if v[0] != 0.0 {
                    return Err("XY rotation (G10 L2 R) is not supported".to_string());
                }
            }
            "SELECT_PLANE" => {
                self.plane = match call.args.trim() {
                    "CANON_PLANE_XY" => CanonPlane::Xy,
                    "CANON_PLANE_XZ" => CanonPlane::Zx,
                    "CANON_PLANE_YZ" => CanonPlane::Yz,
                    other => return Err(format!("plane `{other}` is not supported")),
                };
            }
            "SET_FEED_RATE" => {
                let v = numbers(call.args)?;
                at_least(&v, 1)?;
                self.feed_mm_per_min = v[0] * self.unit;
            }
            "SET_FEED_MODE" => {
                let v = numbers(call.args)?;
                if v.last().copied().unwrap_or(0.0) != 0.0 {
                    return Err("feed per revolution (G95) is not supported".to_string());
                }
            }
            "STRAIGHT_TRAVERSE" | "STRAIGHT_FEED" => {
                let v = numbers(call.args)?;
                at_least(&v, 3)?;
                let to = self.machine_xyz(&v);
                let kind = if call.name == "STRAIGHT_TRAVERSE" {
                    CanonKind::Rapid
                } else {
                    CanonKind::Feed {
                        feed_mm_per_min: self.feed_mm_per_min,
                    }
                };
                moves.push(CanonMove { line, kind, to });
                self.position = to;
            }
            "ARC_FEED" => {
                let v = numbers(call.args)?;
                at_least(&v, 6)?;
                let rotation = v[4];
                if rotation == 0.0 || rotation.fract() != 0.0 {
                    return Err(format!(
                        "arc rotation {rotation} is not a non-zero whole number"
                    ));
                }
                let (first, second, normal) = self.plane.axes();
                let mut program_end = [0.0; 3];
                program_end[first] = v[0];
                program_end[second] = v[1];
                program_end[normal] = v[5];
                let to = self.machine_xyz(&program_end);
                let mut center = [0.0; 3];
                center[first] = self.machine(first, v[2]);
                center[second] = self.machine(second, v[3]);
                center[normal] = self.position[normal];
                let kind = CanonKind::Arc {
                    center,
                    clockwise: rotation < 0.0,
                    plane: self.plane,
                    turns: rotation.abs() as u32,
                };
                moves.push(CanonMove { line, kind, to });
                self.position = to;
            }
            "DWELL" => {
                let v = numbers(call.args)?;
                at_least(&v, 1)?;
                moves.push(CanonMove {
                    line,
                    kind: CanonKind::Dwell { seconds: v[0] },
                    to: self.position,
                });
            }
            "STRAIGHT_PROBE"
            | "RIGID_TAP"
            | "START_SPEED_FEED_SYNCH"
            | "NURBS_FEED"
            | "SPLINE_FEED"
            | "NURBS_G5_FEED"
            | "NURBS_G6_FEED" => {
                return Err(format!("{} is not supported", call.name));
            }
            _ => {}
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: [f64; 3], b: [f64; 3]) -> bool {
        (0..3).all(|i| (a[i] - b[i]).abs() < 1e-9)
    }

    #[test]
    fn counter_and_n_column_are_read() {
        let call = split_row("   12 N4     STRAIGHT_FEED(1.0000, 2.0000, 3.0000)").unwrap();
        assert_eq!(
            (call.line, call.name, call.args),
            (4, "STRAIGHT_FEED", "1.0000, 2.0000, 3.0000")
        );
        let call = split_row("    1 N..... USE_LENGTH_UNITS(CANON_UNITS_MM)").unwrap();
        assert_eq!((call.line, call.name), (0, "USE_LENGTH_UNITS"));
        let call = split_row("   20 N0123  STRAIGHT_TRAVERSE(0.0000, 0.0000, 0.0000)").unwrap();
        assert_eq!(call.line, 123);
        let call = split_row("99999 N1234567ARC_FEED(1, 2, 3, 4, 1, 0)").unwrap();
        assert_eq!((call.line, call.name), (1234567, "ARC_FEED"));
        let call = split_row("    7 N..... COMMENT(\"a (nested) comment, with commas\")").unwrap();
        assert_eq!(call.name, "COMMENT");
    }

    #[test]
    fn unreadable_rows_are_errors() {
        assert!(parse_canon("executing\n").is_err());
        assert!(parse_canon("   3 N1     STRAIGHT_FEED\n").is_err());
        assert!(parse_canon("   3 N1     STRAIGHT_FEED(1.0, x, 2.0)\n").is_err());
        assert!(parse_canon("   3 N1     STRAIGHT_FEED(1.0, 2.0)\n").is_err());
    }

    #[test]
    fn blocks_without_n_words_give_line_zero() {
        let moves = parse_canon(
            "    9 N..... STRAIGHT_TRAVERSE(1.0000, 2.0000, 3.0000, 0.0000, 0.0000, 0.0000)\n",
        )
        .unwrap();
        assert_eq!(moves[0].line, 0);
    }

    #[test]
    fn calls_that_do_not_move_are_skipped() {
        let text = "\
    1 N..... USE_LENGTH_UNITS(CANON_UNITS_MM)
    5 N..... SET_FEED_REFERENCE(CANON_XYZ)
    6 N..... ON_RESET()
    7 N1     COMMENT(\"test\")
   21 N8     SELECT_TOOL(1)
   24 N8     CHANGE_TOOL(1)
   28 N10    SET_SPINDLE_SPEED(0, 1200.0000)
   29 N10    START_SPINDLE_CLOCKWISE(0)
   32 N14    FLOOD_ON()
   45 N17    SET_SPINDLE_MODE(0 0.0000)
   47 N17    PROGRAM_END()
";
        assert_eq!(parse_canon(text).unwrap(), vec![]);
    }

    #[test]
    fn work_and_g92_offsets_add_to_program_coordinates() {
        // G10 L2 P1 X10 Y20 Z-5, G54 G0 X5 Y5 Z5, G92 X0 Y0 Z0, G0 X1 Y1, G92 X10 Y10, G1 X11 F100,
        // G53 G0 X0 Y0 Z0.
        let text = "\
    9 N2     SET_G5X_OFFSET(1, 10.0000, 20.0000, -5.0000, 0.0000, 0.0000, 0.0000)
   10 N2     SET_XY_ROTATION(0.0000)
   12 N3     STRAIGHT_TRAVERSE(5.0000, 5.0000, 5.0000, 0.0000, 0.0000, 0.0000)
   13 N4     SET_G92_OFFSET(5.0000, 5.0000, 5.0000, 0.0000, 0.0000, 0.0000)
   14 N5     STRAIGHT_TRAVERSE(1.0000, 1.0000, 0.0000, 0.0000, 0.0000, 0.0000)
   15 N6     SET_G92_OFFSET(-4.0000, -4.0000, 5.0000, 0.0000, 0.0000, 0.0000)
   16 N7     SET_FEED_RATE(100.0000)
   17 N7     STRAIGHT_FEED(11.0000, 10.0000, 0.0000, 0.0000, 0.0000, 0.0000)
   18 N8     STRAIGHT_TRAVERSE(-6.0000, -16.0000, 0.0000, 0.0000, 0.0000, 0.0000)
";
        let moves = parse_canon(text).unwrap();
        assert_eq!(moves.len(), 4);
        assert!(close(moves[0].to, [15.0, 25.0, 0.0]));
        assert!(close(moves[1].to, [16.0, 26.0, 0.0]));
        assert!(close(moves[2].to, [17.0, 26.0, 0.0]));
        assert_eq!(
            moves[2].kind,
            CanonKind::Feed {
                feed_mm_per_min: 100.0
            }
        );
        assert_eq!(moves[2].line, 7);
        assert!(close(moves[3].to, [0.0, 0.0, 0.0]));
        assert_eq!(moves[3].kind, CanonKind::Rapid);
    }

    #[test]
    fn values_use_the_units_in_force_when_they_were_sent() {
        // G21 G10 L2 P1 X10 Y20 Z-5 ... F100 ... G20, G0 X1 (inch), F10 G1 X2 (inch/min), G21 G0 X0.
        let text = "\
    8 N1     USE_LENGTH_UNITS(CANON_UNITS_MM)
    9 N2     SET_G5X_OFFSET(1, 10.0000, 20.0000, -5.0000, 0.0000, 0.0000, 0.0000)
   10 N3     SET_FEED_RATE(100.0000)
   11 N3     STRAIGHT_FEED(0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)
   12 N4     USE_LENGTH_UNITS(CANON_UNITS_INCHES)
   13 N5     STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)
   14 N6     STRAIGHT_FEED(1.5000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)
   15 N7     SET_FEED_RATE(10.0000)
   16 N7     STRAIGHT_FEED(2.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)
   17 N8     SET_G5X_OFFSET(2, 1.0000, 2.0000, 3.0000, 0.0000, 0.0000, 0.0000)
   18 N8     STRAIGHT_TRAVERSE(0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)
   19 N9     USE_LENGTH_UNITS(CANON_UNITS_MM)
   20 N10    STRAIGHT_TRAVERSE(10.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)
";
        let moves = parse_canon(text).unwrap();
        assert!(close(moves[1].to, [35.4, 20.0, -5.0]));
        // A feed set in mm/min stays 100 mm/min after G20 (LinuxCNC converts it when it is set).
        assert_eq!(
            moves[2].kind,
            CanonKind::Feed {
                feed_mm_per_min: 100.0
            }
        );
        assert!((moves[3].to[0] - 60.8).abs() < 1e-9);
        match moves[3].kind {
            CanonKind::Feed { feed_mm_per_min } => assert!((feed_mm_per_min - 254.0).abs() < 1e-9),
            other => panic!("{other:?}"),
        }
        // An offset set in inches is kept in mm: 1, 2, 3 inch.
        assert!(close(moves[4].to, [25.4, 50.8, 76.2]));
        assert!(close(moves[5].to, [35.4, 50.8, 76.2]));
    }

    #[test]
    fn tool_length_offset_adds_to_z() {
        let text = "\
   25 N9     USE_TOOL_LENGTH_OFFSET(0.0000 0.0000 25.4000, 0.0000 0.0000 0.0000, 0.0000 0.0000 0.0000)
   26 N9     STRAIGHT_TRAVERSE(0.0000, 0.0000, 3.0000, 0.0000, 0.0000, 0.0000)
   28 N11    USE_TOOL_LENGTH_OFFSET(0.0000 0.0000 0.0000, 0.0000 0.0000 0.0000, 0.0000 0.0000 0.0000)
   29 N12    STRAIGHT_TRAVERSE(2.0000, 2.0000, 3.0000, 0.0000, 0.0000, 0.0000)
";
        let moves = parse_canon(text).unwrap();
        assert!(close(moves[0].to, [0.0, 0.0, 28.4]));
        assert!(close(moves[1].to, [2.0, 2.0, 3.0]));
    }

    #[test]
    fn xy_arcs_map_first_axis_to_x() {
        let text = "\
    9 N1     STRAIGHT_TRAVERSE(10.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)
   10 N2     SET_FEED_RATE(100.0000)
   11 N2     ARC_FEED(0.0000, 10.0000, -0.0000, 0.0000, 1, 0.0000, 0.0000, 0.0000, 0.0000)
   12 N3     ARC_FEED(10.0000, 0.0000, 5.0000, 0.0000, -1, -3.0000, 0.0000, 0.0000, 0.0000)
";
        let moves = parse_canon(text).unwrap();
        assert!(close(moves[1].to, [0.0, 10.0, 0.0]));
        assert_eq!(
            moves[1].kind,
            CanonKind::Arc {
                center: [0.0, 0.0, 0.0],
                clockwise: false,
                plane: CanonPlane::Xy,
                turns: 1
            }
        );
        // A helix: the end's Z comes from axis_end_point, the centre's Z is the start's.
        assert!(close(moves[2].to, [10.0, 0.0, -3.0]));
        assert_eq!(
            moves[2].kind,
            CanonKind::Arc {
                center: [5.0, 0.0, 0.0],
                clockwise: true,
                plane: CanonPlane::Xy,
                turns: 1
            }
        );
    }

    #[test]
    fn zx_arcs_map_first_axis_to_z_and_second_to_x() {
        // G18 G2 X10 Z-3 I5 K0 from (0, 0, -3), then a helix along Y.
        let text = "\
    9 N1     STRAIGHT_TRAVERSE(0.0000, 0.0000, -3.0000, 0.0000, 0.0000, 0.0000)
   16 N7     SELECT_PLANE(CANON_PLANE_XZ)
   17 N7     ARC_FEED(-3.0000, 10.0000, -3.0000, 5.0000, -1, 0.0000, 0.0000, 0.0000, 0.0000)
   23 N11    ARC_FEED(-3.0000, 0.0000, -3.0000, 5.0000, 1, 5.0000, 0.0000, 0.0000, 0.0000)
";
        let moves = parse_canon(text).unwrap();
        assert!(close(moves[1].to, [10.0, 0.0, -3.0]));
        assert_eq!(
            moves[1].kind,
            CanonKind::Arc {
                center: [5.0, 0.0, -3.0],
                clockwise: true,
                plane: CanonPlane::Zx,
                turns: 1
            }
        );
        assert!(close(moves[2].to, [0.0, 5.0, -3.0]));
        match moves[2].kind {
            CanonKind::Arc {
                center,
                clockwise: false,
                plane: CanonPlane::Zx,
                turns: 1,
            } => {
                assert!(close(center, [5.0, 0.0, -3.0]));
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn yz_arcs_map_first_axis_to_y_and_second_to_z() {
        let text = "\
   19 N9     SELECT_PLANE(CANON_PLANE_YZ)
   20 N9     ARC_FEED(10.0000, -3.0000, 5.0000, -3.0000, -1, 4.0000, 0.0000, 0.0000, 0.0000)
";
        let moves = parse_canon(text).unwrap();
        assert!(close(moves[0].to, [4.0, 10.0, -3.0]));
        assert_eq!(
            moves[0].kind,
            CanonKind::Arc {
                center: [0.0, 5.0, -3.0],
                clockwise: true,
                plane: CanonPlane::Yz,
                turns: 1
            }
        );
    }

    #[test]
    fn arcs_follow_offsets_and_report_turns() {
        let text = "\
    9 N2     SET_G5X_OFFSET(2, 100.0000, 50.0000, -20.0000, 0.0000, 0.0000, 0.0000)
   10 N3     STRAIGHT_TRAVERSE(10.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)
   11 N4     ARC_FEED(10.0000, 0.0000, 0.0000, 0.0000, -2, -1.0000, 0.0000, 0.0000, 0.0000)
";
        let moves = parse_canon(text).unwrap();
        assert!(close(moves[1].to, [110.0, 50.0, -21.0]));
        assert_eq!(
            moves[1].kind,
            CanonKind::Arc {
                center: [100.0, 50.0, -20.0],
                clockwise: true,
                plane: CanonPlane::Xy,
                turns: 2
            }
        );
    }

    #[test]
    fn dwell_stays_where_the_machine_is() {
        let text = "\
   10 N3     STRAIGHT_TRAVERSE(1.0000, 2.0000, 3.0000, 0.0000, 0.0000, 0.0000)
   11 N4     DWELL(1.5000)
";
        let moves = parse_canon(text).unwrap();
        assert_eq!(
            moves[1],
            CanonMove {
                line: 4,
                kind: CanonKind::Dwell { seconds: 1.5 },
                to: [1.0, 2.0, 3.0]
            }
        );
    }

    #[test]
    fn unsupported_state_is_an_error() {
        assert!(parse_canon("   10 N2     SET_XY_ROTATION(30.0000)\n").is_err());
        assert!(parse_canon("   10 N2     SET_FEED_MODE(0, 1)\n").is_err());
        assert!(parse_canon("   10 N2     SELECT_PLANE(CANON_PLANE_UV)\n").is_err());
        assert!(parse_canon(
            "   10 N2     STRAIGHT_PROBE(1.0000, 2.0000, 3.0000, 0.0000, 0.0000, 0.0000)\n"
        )
        .is_err());
        assert!(
            parse_canon("   10 N2     ARC_FEED(1.0000, 2.0000, 3.0000, 4.0000, 0, 0.0000)\n")
                .is_err()
        );
    }

    #[test]
    fn tool_table_lengths_are_inches() {
        let text = "; comment line\nT1 P1 Z+1.000000 D+0.250000 ;one\n\nt4 p4 z-0.25 ;four\n";
        let tools = parse_tool_table(text).unwrap();
        assert_eq!(tools.len(), 2);
        assert_eq!(
            tools[0],
            LcncTool {
                number: 1,
                length_mm: 25.4,
                diameter_mm: 6.35
            }
        );
        assert_eq!(tools[1].number, 4);
        assert!((tools[1].length_mm + 6.35).abs() < 1e-12);
        assert!(parse_tool_table("T1 Zx\n").is_err());
    }
}
