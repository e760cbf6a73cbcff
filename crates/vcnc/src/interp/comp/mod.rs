//! Cutter radius compensation (G40/G41/G42, issue #5).
//!
//! `geometry` is the plane geometry: compensated elements, the corner rules (inner, outer, sharp
//! outer), start-up and cancel vectors, checked against the manuals' worked examples and by
//! property tests. Until the executor part below exists, G41/G42 alarm as not supported and
//! this module is used by its tests only.
//!
//! The executor part, as designed (not built yet):
//!
//! - State: the side and radius (D word, sign swaps the side), the programmed (uncompensated)
//!   position of the plane axes, and at most one pending compensated element: its programmed
//!   element, its compensated start, and the segment it will become (span, feed, path mode,
//!   the other axes' targets for helices).
//! - A motion block in the plane executes at once, but its segment cannot be written until the
//!   next element in the plane is known (the corner decides where it ends). The output queue
//!   gets a hold mark where the pending segment goes; whatever the following blocks emit
//!   (events, Z moves) is queued after the mark and not handed to the consumer until the hold
//!   is resolved. Moves of other axes during the hold are made at a provisional plane position
//!   and patched to the corner point when it is known.
//! - Resolution: the next plane motion (corner from `geometry::corner`; its links are moves of
//!   the resolving block), G40 and program end (`geometry::perpendicular_end`, then the G40
//!   move to the programmed point), or too many blocks without plane motion (the look-ahead
//!   limit, a profile setting: the vector is perpendicular to the pending element, as FANUC
//!   does after two such blocks).
//! - Start-up: G41/G42 in a G00/G01 block with plane motion (in G02/G03 it is an alarm, FANUC
//!   034); the block ends at `geometry::start_up_end` of the next element (type A).
//! - Alarms: `GeometryError`s mapped to alarm codes at the block of the element concerned;
//!   G28/G53 and G92 in compensation as the manuals say (temporarily cancelled for the block).
#![cfg_attr(not(test), allow(dead_code))]

pub(crate) mod geometry;
