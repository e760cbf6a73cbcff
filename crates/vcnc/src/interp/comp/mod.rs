//! Cutter radius compensation (G40/G41/G42, issue #5).
//!
//! `geometry` is the plane geometry: compensated elements, the corner rules (inner, outer, sharp
//! outer), start-up and cancel vectors, checked against the manuals' worked examples and by
//! property tests. The executor part (the look-ahead window that holds a compensated block until
//! the next motion in the plane is known, D words, the alarms) comes next; until then G41/G42
//! alarm as not supported, and this module is used by its tests only.
#![cfg_attr(not(test), allow(dead_code))]

pub(crate) mod geometry;
