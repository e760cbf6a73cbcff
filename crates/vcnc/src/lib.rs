//! vcnc: a virtual CNC milling controller.
//!
//! vcnc runs NC part programs the way the control would: it reads the program text
//! ([`syntax`]), interprets every block with the modal state, coordinate systems and offsets of
//! the control ([`interp`]), and yields the canonical motion stream ([`motion`]) in machine
//! coordinates, each segment tagged with the span of the block it came from. Problems are
//! [`Alarm`]s with a code and a span, never panics: a warning is an item of the stream
//! ([`motion::Item::Warning`]), the alarm that stops the run its `Err`, the last item.
//!
//! ```
//! use vcnc::motion::Item;
//! use vcnc::{interpret_str, AlarmCode, Machine, Options, SegmentKind};
//!
//! let machine = Machine::default();
//! // Two motion codes in one block: the last wins with a warning, and the run goes on.
//! let program = "G90 G21 G17\nG0 X10. Y5.\nG0 G1 Z-1. F200.\nG2 X20. Y5. R5.\nM30\n";
//! // A warning is an `Ok` item: `collect` (or `?`) stops only at the alarm that stops the run.
//! let items: Vec<Item> =
//!     interpret_str(program, &machine, Options::default()).collect::<Result<_, _>>()?;
//! let arcs = items
//!     .iter()
//!     .filter_map(Item::segment)
//!     .filter(|segment| matches!(segment.kind, SegmentKind::Arc { .. }))
//!     .count();
//! let warnings = items.iter().filter_map(Item::warning).count();
//! assert_eq!((arcs, warnings), (1, 1));
//!
//! // A cut before any feed is programmed stops the control (FANUC alarm 011): the `Err` item.
//! let stopped = interpret_str("G1 X10.\nM30\n", &machine, Options::default())
//!     .collect::<Result<Vec<_>, _>>();
//! assert_eq!(stopped.unwrap_err().code, AlarmCode::NoFeedRate);
//! # Ok::<(), vcnc::Alarm>(())
//! ```
//!
//! The pipeline streams: the interpreter pulls one line at a time from a
//! [`LineSource`](syntax::lines::LineSource), so a program of any length runs in constant memory.
//! [`Pipeline`] runs it the way the `vcnc` command does: the interpreter on a thread of its own,
//! the machine's travel checked, the stream handed over in batches, timed by the planner on the
//! consumer's thread ([`pipeline`] has an example of a consumer).

#![warn(missing_docs)]

pub mod alarm;
pub mod axis;
pub mod checks;
pub mod interp;
pub mod kinematics;
pub mod machine;
pub mod motion;
pub mod pipeline;
pub mod plan;
pub mod plot;
pub mod probe;
pub mod profile;
pub mod program_scan;
pub mod sim;
pub mod source;
pub mod summary;
pub mod syntax;
pub mod tool_geometry;
pub mod toolpath;

pub use alarm::{Alarm, AlarmCode, Severity};
pub use interp::{Interpreter, Options};
pub use machine::{Axis, Machine};
pub use motion::{Item, Segment, SegmentKind, StreamItem};
pub use pipeline::Pipeline;
pub use profile::{Profile, ProfileName};
pub use source::{FileId, Span};

use syntax::blocks::ParsedLines;
use syntax::lines::TextLines;

/// The README's Rust examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeDoctests;

/// Interprets a program held in memory, as file 0.
pub fn interpret_str<'a>(
    text: &'a str,
    machine: &Machine,
    options: Options,
) -> Interpreter<ParsedLines<TextLines<'a>>> {
    Interpreter::new(TextLines::new(text.as_bytes()), FileId(0), machine, options)
}

/// Interprets a program held in memory as bytes (Latin-1 comments are fine), as file 0.
pub fn interpret_bytes<'a>(
    text: &'a [u8],
    machine: &Machine,
    options: Options,
) -> Interpreter<ParsedLines<TextLines<'a>>> {
    Interpreter::new(TextLines::new(text), FileId(0), machine, options)
}
