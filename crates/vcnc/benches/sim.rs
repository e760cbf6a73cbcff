//! Material removal throughput, in segments per second: `vcnc::sim::HeightField::cut` against a
//! naive height field written here (every cell of each segment's bounding box, widened by the
//! tool's radius, tested against the tool stamped every half cell along the segment), on the
//! same segments, grid and tool: a 6 mm flat end mill at 0.1 mm cells on a 60 x 40 mm stock,
//! 400 feed lines of 2 to 12 mm in every direction at Z-1 (a CAM-like finishing pass). The
//! issue's target (#21, acceptance 6): at least 20 times the naive rate.

use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use std::time::Duration;
use vcnc::motion::ToolShape;
use vcnc::sim::HeightField;

const STOCK: [[f64; 3]; 2] = [[0.0, 0.0, -10.0], [60.0, 40.0, 0.0]];
const CELL: f64 = 0.1;
const RADIUS: f64 = 3.0;

/// Feed lines wandering over the stock, each from the end of the last.
fn segments() -> Vec<([f64; 3], [f64; 3])> {
    let mut at = [30.0, 20.0, -1.0];
    let mut segments = Vec::new();
    for i in 0..400u32 {
        let angle = f64::from(i) * 2.399_963;
        let length = 2.0 + f64::from(i % 11);
        let mut to = [
            at[0] + length * angle.cos(),
            at[1] + length * angle.sin(),
            -1.0,
        ];
        to[0] = to[0].clamp(5.0, 55.0);
        to[1] = to[1].clamp(5.0, 35.0);
        segments.push((at, to));
        at = to;
    }
    segments
}

/// The naive field: heights of cells of `CELL` over `STOCK`.
struct Naive {
    heights: Vec<f64>,
    size: [usize; 2],
}

impl Naive {
    fn new() -> Naive {
        let size = [
            ((STOCK[1][0] - STOCK[0][0]) / CELL).round() as usize,
            ((STOCK[1][1] - STOCK[0][1]) / CELL).round() as usize,
        ];
        Naive {
            heights: vec![STOCK[1][2]; size[0] * size[1]],
            size,
        }
    }

    /// Every cell of the widened bounding box against every stamp of the flat tool.
    fn cut(&mut self, from: [f64; 3], to: [f64; 3]) -> f64 {
        let length = (to[0] - from[0]).hypot(to[1] - from[1]);
        let stamps = ((length / (CELL / 2.0)).ceil() as usize).max(1);
        let cell_of = |v: f64, k: usize| {
            ((v - STOCK[0][k]) / CELL)
                .floor()
                .clamp(0.0, (self.size[k] - 1) as f64) as usize
        };
        let (i0, i1) = (
            cell_of(from[0].min(to[0]) - RADIUS, 0),
            cell_of(from[0].max(to[0]) + RADIUS, 0),
        );
        let (j0, j1) = (
            cell_of(from[1].min(to[1]) - RADIUS, 1),
            cell_of(from[1].max(to[1]) + RADIUS, 1),
        );
        let mut removed = 0.0;
        for j in j0..=j1 {
            for i in i0..=i1 {
                let c = [
                    STOCK[0][0] + (i as f64 + 0.5) * CELL,
                    STOCK[0][1] + (j as f64 + 0.5) * CELL,
                ];
                let mut lowest = f64::INFINITY;
                for s in 0..=stamps {
                    let t = s as f64 / stamps as f64;
                    let p = [
                        from[0] + (to[0] - from[0]) * t,
                        from[1] + (to[1] - from[1]) * t,
                    ];
                    if (c[0] - p[0]).hypot(c[1] - p[1]) <= RADIUS {
                        lowest = lowest.min(from[2] + (to[2] - from[2]) * t);
                    }
                }
                let k = j * self.size[0] + i;
                if lowest < self.heights[k] {
                    removed += self.heights[k] - lowest;
                    self.heights[k] = lowest;
                }
            }
        }
        removed * CELL * CELL
    }
}

fn sim(c: &mut Criterion) {
    let segments = segments();
    let tool = ToolShape::flat(RADIUS);
    let mut group = c.benchmark_group("sim");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(5))
        .throughput(Throughput::Elements(segments.len() as u64));
    group.bench_function("height_field", |b| {
        b.iter(|| {
            let mut grid = HeightField::new(STOCK, CELL);
            let removed: f64 = segments
                .iter()
                .map(|(from, to)| grid.cut(*from, *to, &tool).removed)
                .sum();
            black_box(removed)
        });
    });
    group.bench_function("naive", |b| {
        b.iter(|| {
            let mut naive = Naive::new();
            let removed: f64 = segments
                .iter()
                .map(|(from, to)| naive.cut(*from, *to))
                .sum();
            black_box(removed)
        });
    });
    group.finish();
}

criterion_group!(benches, sim);
criterion_main!(benches);
