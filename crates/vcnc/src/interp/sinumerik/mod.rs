//! The SINUMERIK 840D sl / 828D front end: a block sequencer over the [`Kernel`](super::Kernel)
//! (docs/SINUMERIK.md is the execution model it implements).
//!
//! It reads its own blocks (`crate::syntax::sinumerik`), keeps its own modal state, variables
//! and call stack, and asks the kernel for what every control shares: moves, dwells, events,
//! the frame chain, the tool length. It never builds a segment itself and never reads ISO
//! words.
//!
//! The parts: the language's values, variables and expressions (`value.rs`, `vars.rs`,
//! `eval.rs`), the programmable frame's algebra (`frame.rs`), the geometry of arcs and contour
//! definitions (`arcs.rs`, `contour.rs`).

mod arcs;
mod contour;
mod eval;
mod frame;
mod polar;
mod value;
mod vars;
