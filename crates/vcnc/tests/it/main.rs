//! The library's integration tests, one module per topic, built as one test binary: one link
//! instead of one per file, and the helpers in `common` compiled once. Run one topic with
//! `cargo test -p vcnc --test it <module>::` (e.g. `cycles::`). This file only declares the
//! modules; it must never hold tests or helpers of its own. proptest keeps the failing cases it
//! found in `tests/proptest-regressions/<module>.txt`: it looks beside the folder of `main.rs`.

mod common;

mod alarms;
mod axes_by_name;
mod compensation;
mod compensation_cases;
mod compensation_corpus;
mod compensation_property;
mod corpus;
mod corpus_tally;
mod cycles;
mod five_axis;
mod frames;
mod front_end;
mod input;
mod interrupt;
mod iso_f2_retract;
mod iso_g07;
mod iso_g62_g07;
mod iso_rollover_readout;
mod lcnc_traces;
mod macro_alarms;
mod macros;
mod mangled;
mod manual_rules;
mod modal;
mod nurbs;
mod pipeline;
mod plan_reference;
mod planner;
mod plot;
mod polar;
mod polar_interpolation;
mod position_offset;
mod probing;
mod readme;
mod rotation;
mod rtcp_four_axis;
mod scaling;
mod seed_examples;
mod sim;
mod sim_sinumerik_corpus;
mod sinumerik;
mod sinumerik_axes;
mod sinumerik_compensation;
mod sinumerik_contour_cycles;
mod sinumerik_corpus;
mod sinumerik_corpus_plausible;
mod sinumerik_cycles;
mod sinumerik_examples;
mod sinumerik_feeds;
mod sinumerik_language;
mod sinumerik_plain_blocks;
mod sinumerik_robust;
mod sinumerik_syntax;
mod sinumerik_threads;
mod sinumerik_turning;
mod sinumerik_work_area;
mod skip;
mod smoothing;
mod smoothness;
mod spiral;
mod stream;
mod streaming;
mod stroke_check;
mod syntec_macro;
mod syntec_numbers;
mod thread;
mod tilted_plane_forms;
mod tool_direction;
