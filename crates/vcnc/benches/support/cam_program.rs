//! The CAM-style benchmark program: a header, N motion blocks that wander over a 200 x 200 mm
//! area (feed lines, every tenth block an arc), and a footer.
//!
//! The same path can be written the SINUMERIK way ([`Style::Sinumerik`]), as a CAM post for an
//! 840D writes it: `DEF REAL` feeds at the top, `N` numbers, `;` comments, `G1 ... F=FEED1`,
//! `G2 ... CR=...` (CR is R's twin: negative past half a circle). The feeds are equal to the ISO
//! program's F, so both programs trace the same segments (xtask's tests check it).
//!
//! One copy serves two users: the `interp` bench includes it with `#[path]`, and
//! `cargo xtask bench-program` includes it the same way to write the program to a file for the
//! whole-process comparison with LinuxCNC's `rs274 -g` (docs/benchmarks.md). It uses only std and
//! knows nothing of vcnc.
//!
//! Invariants: the output depends on N alone (a fixed-seed generator), so every machine
//! benchmarks the same text; every line runs on vcnc's FANUC profile and on LinuxCNC (decimal
//! points on every length, no `;` comments, ends with M30 and `%`). Coordinates are whole
//! micrometres, so every value prints exactly with three decimals, and an arc's end point is
//! exactly on its circle: the centre is the start plus k * (a, b) and the end is the centre plus
//! k times another vector of length c of the same Pythagorean triple (a, b, c). No float is
//! involved, and neither control sees a radius difference, however small its tolerance.

use std::io::{self, Write};

/// Side of the square work area, micrometres (0 to 200 mm in X and Y).
const AREA: i64 = 200_000;
/// Lines turn back this far from the edge; it is larger than a line's longest step in one axis.
const MARGIN: i64 = 10_000;
/// The largest step of a feed line in one axis, micrometres.
const MAX_STEP: i64 = 6_000;
/// Arc radii, micrometres.
const RADII: (i64, i64) = (2_000, 20_000);
/// Pythagorean triples (a, b, c): a^2 + b^2 = c^2.
const TRIPLES: [(i64, i64, i64); 6] = [
    (3, 4, 5),
    (5, 12, 13),
    (8, 15, 17),
    (7, 24, 25),
    (20, 21, 29),
    (12, 35, 37),
];

/// How the program is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Style {
    /// FANUC-family ISO, the form LinuxCNC also reads.
    Iso,
    /// SINUMERIK 840D, as a CAM post writes it.
    Sinumerik,
}

const HEADER: &str = "%\nO1000\nG21 G17 G90 G94 G54\nT1 M06\nS8000 M03\nG00 X0. Y0. Z5.\nG43 H1 Z5.\nG01 Z-1. F1500.\n";
const FOOTER: &str = "G00 Z5.\nM05\nM30\n%\n";

/// The SINUMERIK header: the ISO header's moves, with the feeds declared first (DEF comes before
/// any other statement, PGAsl 1.1). `T1 M6` takes edge D1, as the ISO header's G43 H1 does.
const SINUMERIK_HEADER: &str = "; CAM-style benchmark program, SINUMERIK 840D
; post: generic 3-axis mill
DEF REAL FEED1=1500.0
DEF REAL FEED2=FEED1
N10 G71 G17 G90 G94 G54
N20 T1 M6
N30 D1
N40 S8000 M3
N50 G0 X0 Y0 Z5
N60 G1 Z-1 F=FEED2
; roughing
";
const SINUMERIK_FOOTER: &str = "G0 Z5\nM5\nM30\n";
/// The N number of the first motion block, and the step between block numbers.
const FIRST_NUMBER: usize = 70;
const NUMBER_STEP: usize = 10;

/// The whole program of `blocks` motion blocks, as text.
#[allow(dead_code)] // xtask streams with `write_program` instead.
pub(crate) fn program(blocks: usize) -> String {
    let mut text = Vec::with_capacity(blocks * 28 + 256);
    write_program(&mut text, blocks).expect("writing to a Vec cannot fail");
    String::from_utf8(text).expect("the generator writes ASCII")
}

/// The whole program of `blocks` motion blocks in `style`, as text.
#[allow(dead_code)] // each user takes one of the two forms.
pub(crate) fn program_in(blocks: usize, style: Style) -> String {
    let mut text = Vec::with_capacity(blocks * 36 + 512);
    write_program_in(&mut text, blocks, style).expect("writing to a Vec cannot fail");
    String::from_utf8(text).expect("the generator writes ASCII")
}

/// Writes the program of `blocks` motion blocks to `out`.
pub(crate) fn write_program<W: Write>(out: &mut W, blocks: usize) -> io::Result<()> {
    write_program_in(out, blocks, Style::Iso)
}

/// Writes the program of `blocks` motion blocks in `style` to `out`.
pub(crate) fn write_program_in<W: Write>(
    out: &mut W,
    blocks: usize,
    style: Style,
) -> io::Result<()> {
    out.write_all(match style {
        Style::Iso => HEADER.as_bytes(),
        Style::Sinumerik => SINUMERIK_HEADER.as_bytes(),
    })?;
    let mut tool = Tool {
        x: 0,
        y: 0,
        vx: 3_000,
        vy: 2_000,
        random: Random(0x5EED_CAFE_F00D_0001),
        style,
    };
    for block in 1..=blocks {
        if style == Style::Sinumerik {
            if block % 1000 == 1 {
                // CAM posts mark the operations they chain; a comment line is not a block.
                writeln!(out, "; pass {}", block / 1000 + 1)?;
            }
            write!(out, "N{} ", FIRST_NUMBER + (block - 1) * NUMBER_STEP)?;
        }
        if block % 10 == 0 {
            tool.arc(out)?;
        } else {
            tool.line(out, block % 10 == 1)?;
        }
    }
    out.write_all(match style {
        Style::Iso => FOOTER.as_bytes(),
        Style::Sinumerik => SINUMERIK_FOOTER.as_bytes(),
    })
}

/// The tool position and the drift of its path, micrometres.
struct Tool {
    x: i64,
    y: i64,
    vx: i64,
    vy: i64,
    random: Random,
    style: Style,
}

impl Tool {
    /// A feed line: the step drifts a little each block and turns back near the edges.
    /// `after_arc`: the line follows an arc, and a SINUMERIK post states its feed again.
    fn line<W: Write>(&mut self, out: &mut W, after_arc: bool) -> io::Result<()> {
        self.vx = steer(self.vx + self.random.between(-1_500, 1_500), self.x);
        self.vy = steer(self.vy + self.random.between(-1_500, 1_500), self.y);
        if self.vx.abs() + self.vy.abs() < 300 {
            self.vx = if self.x < AREA / 2 { 2_000 } else { -2_000 };
        }
        self.x += self.vx;
        self.y += self.vy;
        let g1 = match self.style {
            Style::Iso => "G01",
            Style::Sinumerik => "G1",
        };
        write!(out, "{g1} X{} Y{}", Mm(self.x), Mm(self.y))?;
        if self.random.between(0, 7) == 0 {
            write!(out, " Z{}", Mm(self.random.between(-2_000, -500)))?;
        }
        if self.style == Style::Sinumerik && after_arc {
            out.write_all(b" F=FEED1")?;
        }
        out.write_all(b"\n")
    }

    /// A G02 or G03 arc in the XY plane, with R or with I J, ending exactly on its circle.
    fn arc<W: Write>(&mut self, out: &mut W) -> io::Result<()> {
        let (cx, cy, radius, triple, k) = self.centre();
        let (ex, ey) = loop {
            let (dx, dy) = self.random.vector(triple);
            let end = (cx + k * dx, cy + k * dy);
            if end != (self.x, self.y) {
                break end;
            }
        };
        let clockwise = self.random.between(0, 1) == 0;
        let g = match (self.style, clockwise) {
            (Style::Iso, true) => "G02",
            (Style::Iso, false) => "G03",
            (Style::Sinumerik, true) => "G2",
            (Style::Sinumerik, false) => "G3",
        };
        write!(out, "{g} X{} Y{}", Mm(ex), Mm(ey))?;
        if self.random.between(0, 1) == 0 {
            // The cross product of (start - centre) and (end - centre) says on which side the end
            // lies: R is negative when the arc sweeps more than half a circle.
            let cross = (self.x - cx) * (ey - cy) - (self.y - cy) * (ex - cx);
            let long = if clockwise { cross > 0 } else { cross < 0 };
            let r = match self.style {
                Style::Iso => " R",
                Style::Sinumerik => " CR=",
            };
            write!(out, "{r}{}", Mm(if long { -radius } else { radius }))?;
        } else {
            write!(out, " I{} J{}", Mm(cx - self.x), Mm(cy - self.y))?;
        }
        self.x = ex;
        self.y = ey;
        if self.style == Style::Sinumerik {
            out.write_all(b" F=FEED2")?;
        }
        out.write_all(b"\n")
    }

    /// A centre whose circle lies inside the area: (cx, cy, radius, triple, k).
    fn centre(&mut self) -> (i64, i64, i64, (i64, i64, i64), i64) {
        let mut last = (self.x, self.y, 0, TRIPLES[0], 0);
        for _ in 0..32 {
            let triple = TRIPLES[self.random.between(0, TRIPLES.len() as i64 - 1) as usize];
            let c = triple.2;
            let k = self.random.between((RADII.0 + c - 1) / c, RADII.1 / c);
            let (dx, dy) = self.random.vector(triple);
            let (cx, cy, radius) = (self.x + k * dx, self.y + k * dy, k * c);
            last = (cx, cy, radius, triple, k);
            let inside = |v: i64| v - radius >= 0 && v + radius <= AREA;
            if inside(cx) && inside(cy) {
                break;
            }
        }
        last
    }
}

/// Turns a step back towards the area near its edges and bounds it.
fn steer(step: i64, at: i64) -> i64 {
    let step = step.clamp(-MAX_STEP, MAX_STEP);
    if at < MARGIN {
        step.abs()
    } else if at > AREA - MARGIN {
        -step.abs()
    } else {
        step
    }
}

/// A length in micrometres, shown in mm with three decimals (`12.345`, `-0.500`).
struct Mm(i64);

impl std::fmt::Display for Mm {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let sign = if self.0 < 0 { "-" } else { "" };
        let v = self.0.unsigned_abs();
        write!(f, "{sign}{}.{:03}", v / 1000, v % 1000)
    }
}

/// xorshift64*: small, fast and the same everywhere, which is all a benchmark input needs.
struct Random(u64);

impl Random {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// A whole number in `low..=high`.
    fn between(&mut self, low: i64, high: i64) -> i64 {
        let span = (high - low + 1) as u64;
        low + ((self.next() >> 11) % span) as i64
    }

    /// One of the twelve vectors of length c on the triple's grid: (±a, ±b), (±b, ±a), (±c, 0), (0, ±c).
    fn vector(&mut self, (a, b, c): (i64, i64, i64)) -> (i64, i64) {
        let vectors = [
            (a, b),
            (-a, b),
            (a, -b),
            (-a, -b),
            (b, a),
            (-b, a),
            (b, -a),
            (-b, -a),
            (c, 0),
            (-c, 0),
            (0, c),
            (0, -c),
        ];
        vectors[self.between(0, 11) as usize]
    }
}
