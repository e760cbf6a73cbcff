//! `cargo xtask gen-plan-programs [--count N]`: writes random planner reference programs, N of
//! each kind (20 by default), to crates/vcnc/tests/data/plan/lcnc/random/.
//!
//! The kinds are the situations a cycle-time model must get right beyond its hand-made test set
//! (issue 24): CAM chords along smooth curves, zigzags and pockets with and without a blend
//! tolerance, 3D rapid tours, arc chains, and drilling that mixes rapids and feeds. Each program
//! is LinuxCNC rs274ngc that vcnc's `fanuc` profile reads alike, starts at X0 Y0 Z0, stays inside
//! ±2000 mm, and names on its first line the limits it is timed with, `(limits: --vel V --acc A
//! [--blend-tol T])`, which `tools/record-lcnc-time.sh` passes to lcnc-time and
//! `tests/it/plan_reference.rs` gives the vcnc machine. The generator is seeded by kind and
//! number: the same command writes the same files, so a program and its recorded time stay a
//! pair.

use std::fmt::Write as _;
use std::path::Path;

/// The kinds, each with what its second line says.
const KINDS: [(&str, &str); 6] = [
    ("chords", "CAM chords along a smooth curve, continuous"),
    ("zigzag", "zigzag passes, continuous"),
    ("pocket", "a rectangular pocket cut outwards, continuous"),
    (
        "rapids",
        "a tour of rapids between random 3D points, continuous",
    ),
    (
        "arcs",
        "a chain of arcs of random radius and direction, continuous",
    ),
    ("drill", "a hole pattern: rapid, plunge at feed, rapid out"),
];

pub(crate) fn run(args: &[String]) -> Result<(), String> {
    let mut count = 20;
    let mut iter = args.iter();
    while let Some(arg) = iter.next() {
        match arg.as_str() {
            "--count" => {
                count = iter
                    .next()
                    .and_then(|n| n.parse().ok())
                    .ok_or("--count needs a number")?;
            }
            other => return Err(format!("unknown argument `{other}`")),
        }
    }
    let dir =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../crates/vcnc/tests/data/plan/lcnc/random");
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    for (k, (kind, what)) in KINDS.iter().enumerate() {
        for n in 1..=count {
            let mut rng = Rng::new(((k as u64 + 1) << 32) | n as u64);
            let text = program(kind, what, &mut rng);
            let path = dir.join(format!("{kind}_{n:02}.ngc"));
            std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))?;
        }
    }
    println!("{} programs in {}", KINDS.len() * count, dir.display());
    Ok(())
}

/// One program of `kind`.
fn program(kind: &str, what: &str, rng: &mut Rng) -> String {
    let vel = *rng.pick(&[50.0, 100.0, 100.0, 150.0]);
    let acc = *rng.pick(&[500.0, 1000.0, 1000.0, 2000.0]);
    // Half the zigzags and pockets run under a blend tolerance (LinuxCNC's G64 P).
    let tolerance = matches!(kind, "zigzag" | "pocket" | "chords")
        .then(|| rng.below(2) == 0)
        .unwrap_or(false)
        .then(|| *rng.pick(&[0.005, 0.01, 0.02, 0.05, 0.1]));
    let mut out = format!("(limits: --vel {vel} --acc {acc}");
    if let Some(t) = tolerance {
        let _ = write!(out, " --blend-tol {t}");
    }
    let body = match kind {
        "chords" => chords(rng),
        "zigzag" => zigzag(rng),
        "pocket" => pocket(rng),
        "rapids" => rapids(rng),
        "arcs" => arcs(rng),
        _ => drill(rng),
    };
    // The program sets its tolerance itself: LinuxCNC takes a `G64 P` of its startup code (where
    // lcnc-time's --blend-tol puts it) into the interpreter's state but never sends it to the
    // motion planner, which blends as in plain G64 (measured: a square at F6000 takes 3.768 s
    // with and without --blend-tol 0.001, 4.897 s with `G64 P0.001` in the program). Q0 turns
    // off the naive CAM detector, which a P turns on at the same tolerance: it merges nearly
    // collinear lines in LinuxCNC's interpreter, a change of the path that vcnc does not make.
    // vcnc's fanuc profile reads P and Q and leaves them: the tests give vcnc the --blend-tol.
    let moves = match tolerance {
        Some(t) => match body.1.strip_prefix("G64\n") {
            Some(rest) => format!("G64 P{} Q0.0\n{rest}", n(t)),
            None => body.1,
        },
        None => body.1,
    };
    let _ = write!(out, ")\n({what}: {})\nG21 G90 G17 G94\n{moves}M2\n", body.0);
    out
}

/// A number as LinuxCNC and vcnc both read it: always with a decimal point.
fn n(v: f64) -> String {
    let s = format!("{v:.4}");
    let s = s.trim_end_matches('0');
    if s.ends_with('.') {
        format!("{s}0")
    } else {
        s.to_string()
    }
}

fn chords(rng: &mut Rng) -> (String, String) {
    let chord = *rng.pick(&[0.1, 0.2, 0.3, 0.5, 1.0, 2.0]);
    let feed = *rng.pick(&[600.0, 1200.0, 2400.0, 3000.0, 4800.0, 6000.0]);
    let amplitude = rng.range(1.0, 15.0);
    let wavelength = rng.range(10.0, 60.0);
    let length = rng.range(40.0, 120.0);
    let curve = rng.below(3);
    let mut body = format!("G64\nG1 F{}\n", n(feed));
    // The curve's points at about `chord` apart along x (a circle: along its angle).
    let steps = (length / chord).ceil() as usize;
    for i in 1..=steps {
        let s = i as f64 * length / steps as f64;
        let (x, y) = match curve {
            0 => (
                s,
                amplitude * (std::f64::consts::TAU * s / wavelength).sin(),
            ),
            1 => {
                let r = amplitude * 2.0 + 5.0;
                let angle = s / r;
                (r * angle.sin(), r - r * angle.cos())
            }
            _ => (s, amplitude * (s / wavelength).powi(2)),
        };
        let _ = writeln!(body, "X{} Y{}", n(x), n(y));
    }
    let name = ["sine", "circle", "parabola"][curve as usize];
    (format!("{name}, {chord} mm chords at F{feed}"), body)
}

fn zigzag(rng: &mut Rng) -> (String, String) {
    let width = rng.range(10.0, 50.0);
    let step = rng.range(0.5, 3.0);
    let passes = 6 + rng.below(15) as usize;
    let feed = *rng.pick(&[600.0, 1200.0, 2400.0, 3000.0, 4800.0]);
    let mut body = format!("G64\nG1 F{}\n", n(feed));
    for i in 0..passes {
        let y = i as f64 * step;
        let x = if i % 2 == 0 { width } else { 0.0 };
        let _ = writeln!(body, "X{} Y{}", n(x), n(y));
        let _ = writeln!(body, "Y{}", n(y + step));
    }
    (
        format!(
            "{passes} passes of {:.1} mm, {step:.2} mm steps at F{feed}",
            width
        ),
        body,
    )
}

fn pocket(rng: &mut Rng) -> (String, String) {
    let step = rng.range(0.5, 4.0);
    let rings = 3 + rng.below(8) as usize;
    let aspect = rng.range(0.5, 2.0);
    let feed = *rng.pick(&[600.0, 1200.0, 2400.0, 3000.0]);
    let mut body = format!("G64\nG1 Z-1.0 F{}\n", n(feed / 2.0));
    let _ = writeln!(body, "F{}", n(feed));
    for ring in 1..=rings {
        let half_x = ring as f64 * step * aspect;
        let half_y = ring as f64 * step;
        for (x, y) in [
            (half_x, -half_y),
            (half_x, half_y),
            (-half_x, half_y),
            (-half_x, -half_y),
            (half_x, -half_y),
        ] {
            let _ = writeln!(body, "X{} Y{}", n(x), n(y));
        }
    }
    (format!("{rings} rings {step:.2} mm apart at F{feed}"), body)
}

fn rapids(rng: &mut Rng) -> (String, String) {
    let points = 15 + rng.below(16) as usize;
    let mut body = String::from("G64\n");
    for _ in 0..points {
        let _ = writeln!(
            body,
            "G0 X{} Y{} Z{}",
            n(rng.range(-100.0, 100.0)),
            n(rng.range(-100.0, 100.0)),
            n(rng.range(-50.0, 50.0))
        );
    }
    (format!("{points} rapids"), body)
}

fn arcs(rng: &mut Rng) -> (String, String) {
    let count = 6 + rng.below(15) as usize;
    let feed = *rng.pick(&[600.0, 1200.0, 2400.0, 3000.0, 4800.0]);
    let mut body = format!("G64\nG1 F{}\n", n(feed));
    let (mut x, mut y) = (0.0f64, 0.0f64);
    // The direction the path leaves the last arc: the next arc starts tangent to it or turns.
    let mut heading = 0.0f64;
    for _ in 0..count {
        let radius = rng.range(2.0, 30.0);
        let clockwise = rng.below(2) == 0;
        let sweep = rng.range(0.3, 2.5);
        // A kink of up to 60 degrees now and then.
        if rng.below(3) == 0 {
            heading += rng.range(-1.0, 1.0);
        }
        let side = if clockwise { -1.0 } else { 1.0 };
        let (cx, cy) = (
            x + radius * (heading + side * std::f64::consts::FRAC_PI_2).cos(),
            y + radius * (heading + side * std::f64::consts::FRAC_PI_2).sin(),
        );
        let start_angle = (y - cy).atan2(x - cx);
        let end_angle = start_angle + side * sweep;
        let (ex, ey) = (cx + radius * end_angle.cos(), cy + radius * end_angle.sin());
        let _ = writeln!(
            body,
            "G{} X{} Y{} I{} J{}",
            if clockwise { 2 } else { 3 },
            n(ex),
            n(ey),
            n(cx - x),
            n(cy - y)
        );
        heading += side * sweep;
        (x, y) = (ex, ey);
    }
    (format!("{count} arcs at F{feed}"), body)
}

fn drill(rng: &mut Rng) -> (String, String) {
    let columns = 2 + rng.below(5) as usize;
    let rows = 2 + rng.below(4) as usize;
    let pitch = rng.range(5.0, 30.0);
    let depth = rng.range(2.0, 15.0);
    let feed = *rng.pick(&[100.0, 200.0, 300.0, 600.0]);
    let exact = rng.below(2) == 0;
    let mut body = String::from(if exact { "G61\n" } else { "G64\n" });
    for row in 0..rows {
        for column in 0..columns {
            let _ = writeln!(
                body,
                "G0 X{} Y{}\nG0 Z2.0\nG1 Z{} F{}\nG0 Z5.0",
                n(column as f64 * pitch),
                n(row as f64 * pitch),
                n(-depth),
                n(feed)
            );
        }
    }
    let mode = if exact { "G61" } else { "G64" };
    (
        format!(
            "{} holes {depth:.1} mm deep at F{feed}, {mode}",
            rows * columns
        ),
        body,
    )
}

/// splitmix64: a small, well-mixed generator, enough for test programs.
struct Rng(u64);

impl Rng {
    fn new(seed: u64) -> Rng {
        Rng(seed)
    }

    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A whole number in 0..n.
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }

    /// A number in lo..hi.
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        let unit = (self.next() >> 11) as f64 / (1u64 << 53) as f64;
        lo + (hi - lo) * unit
    }

    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len() as u64) as usize]
    }
}
