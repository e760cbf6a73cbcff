//! Checks shared by the macro test suites: variable values after a run, and where its moves end.

use vcnc::{Segment, SegmentKind};

/// Asserts variable values (`values[n]` is `#n`; `None` = vacant) after `program` ran.
pub fn assert_values(program: &str, values: &[Option<f64>], expected: &[(usize, Option<f64>)]) {
    for &(n, want) in expected {
        match (values[n], want) {
            (Some(got), Some(want)) => assert!(
                (got - want).abs() < 1e-9,
                "#{n} = {got}, expected {want}\n{program}"
            ),
            (got, want) => assert_eq!(got, want, "#{n}\n{program}"),
        }
    }
}

/// End points (machine X, Y, Z, rounded to 1e-4 mm) of the moves among `segments`.
pub fn move_ends(segments: &[Segment]) -> Vec<[f64; 3]> {
    segments
        .iter()
        .filter_map(|s| match &s.kind {
            SegmentKind::Rapid { motion, .. }
            | SegmentKind::Line { motion, .. }
            | SegmentKind::Arc { motion, .. } => {
                let p = motion.to.0.map(|c| (c * 1e4).round() / 1e4 + 0.0);
                Some([p[0], p[1], p[2]])
            }
            _ => None,
        })
        .collect()
}
