//! The interpreter's batches with their timings, planned on the consumer's thread.
//!
//! The planner's [`Timeline`] takes the items by reference and gives their timings back in
//! order once the look-ahead has passed them; meanwhile the batches wait here, in the buffers
//! the interpreter filled. A segment is never copied on its way from the interpreter to the
//! consumer: planning adds the arithmetic and nothing else. (On two cores a thread of its own
//! for the planner gained nothing and cost the copies of every segment into and out of it.)
//!
//! Never keeps every buffer of the pool: the interpreter must always have one to fill.

use super::threads::POOL;
use super::Item;
use crate::motion::Item as Emitted;
use crate::plan::{Timeline, Timing};

/// A stream handed over a batch at a time, in buffers that go back to it.
pub(crate) trait BatchSource {
    /// The next batch (None at the end of the stream).
    fn next_batch(&mut self) -> Option<Vec<Item>>;
    /// Gives a batch's buffer back.
    fn recycle(&self, batch: Vec<Item>);
}

/// A batch from the interpreter and the timings of its first items.
struct Held {
    items: Vec<Item>,
    timings: Vec<Timing>,
}

impl Held {
    fn is_complete(&self) -> bool {
        self.timings.len() == self.items.len()
    }
}

/// Gives `consume` every batch of `stream` with the timings `timeline` gives its items, in
/// order, until the stream ends or `consume` returns false.
pub(crate) fn for_each_timed<S: BatchSource>(
    stream: &mut S,
    mut timeline: Timeline,
    mut consume: impl FnMut(&[Item], &[Timing]) -> bool,
) {
    // A few batches at most (fewer than the interpreter's pool): a vector, whose front is
    // removed by moving the two or three others.
    let mut held: Vec<Held> = Vec::with_capacity(POOL);
    let mut spare_timings: Vec<Vec<Timing>> = Vec::new();
    // The first held batch whose timings are not all known.
    let mut filling = 0;
    let mut go_on = true;
    while go_on {
        let Some(items) = stream.next_batch() else {
            timeline.finish();
            deal(&mut timeline, &mut held, &mut filling);
            deal_last_frames(&mut held);
            break;
        };
        let keep_all = held.len() + 1 < POOL;
        let first_new = match held.last_mut() {
            // The interpreter must always have a buffer to fill: when this side would keep the
            // last but one, the new items join the newest batch kept. That happens with tiny
            // batches (a macro loop that rarely moves) or a look-ahead longer than a few
            // batches; what is kept then grows with the look-ahead window, its only buffer.
            Some(last) if !keep_all => {
                let first_new = last.items.len();
                let mut items = items;
                last.items.append(&mut items);
                stream.recycle(items);
                first_new
            }
            _ => {
                let timings = spare_timings.pop().unwrap_or_default();
                held.push(Held { items, timings });
                0
            }
        };
        let newest = held.len() - 1;
        let mut next = first_new;
        // The items go to the timeline straight from the newest batch until timings are ready,
        // then the timings to the held batches: one lookup of the batch for each run of items.
        while next < held[newest].items.len() {
            for item in &held[newest].items[next..] {
                timeline.push_item_line_first(item);
                next += 1;
                if timeline.has_timing() {
                    break;
                }
            }
            deal(&mut timeline, &mut held, &mut filling);
        }
        while held.first().is_some_and(Held::is_complete) {
            let mut done = held.remove(0);
            filling = filling.saturating_sub(1);
            go_on = go_on && consume(&done.items, &done.timings);
            stream.recycle(done.items);
            done.timings.clear();
            spare_timings.push(done.timings);
        }
    }
    if go_on {
        for done in held.drain(..) {
            if !consume(&done.items, &done.timings) {
                break;
            }
        }
    }
}

/// Gives the timings the timeline has made final to the held batches, in order. A frame has
/// none of its own (the timeline skips it): it takes the start of the item after it, with no
/// duration.
// Inlined: it runs for every item pushed. Batch by batch, so that the batch being filled is
// looked up once for all the timings it takes, not once a timing.
#[inline(always)]
fn deal(timeline: &mut Timeline, held: &mut [Held], filling: &mut usize) {
    let Some(mut timing) = timeline.next_timing() else {
        return;
    };
    // Every timing belongs to an item pushed, and every item pushed is held.
    for batch in held.iter_mut().skip(*filling) {
        while let Some(next) = batch.items.get(batch.timings.len()) {
            if let Ok(Emitted::Frame(_)) = next {
                batch.timings.push(Timing {
                    dt: 0.0,
                    feed_unknown: false,
                    ..timing
                });
                continue;
            }
            batch.timings.push(timing);
            match timeline.next_timing() {
                Some(following) => timing = following,
                None => return,
            }
        }
        *filling += 1;
    }
}

/// The stream has ended: a frame no timed item followed (none does: a frame comes before a
/// move) gets the last item's end.
fn deal_last_frames(held: &mut [Held]) {
    let mut end = 0.0;
    for batch in held {
        if let Some(last) = batch.timings.last() {
            end = last.t + last.dt;
        }
        while !batch.is_complete() {
            batch.timings.push(Timing {
                t: end,
                dt: 0.0,
                feed_unknown: false,
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::{PlanOptions, Planner};
    use crate::{interpret_str, Machine, Options};
    use std::cell::Cell;

    /// A stream in batches of a given size that counts the buffers not given back.
    struct Fake {
        items: std::vec::IntoIter<Item>,
        size: usize,
        out: Cell<usize>,
    }

    impl BatchSource for Fake {
        fn next_batch(&mut self) -> Option<Vec<Item>> {
            // The consumer asks for a batch only while the interpreter has a buffer to fill it
            // in: with every buffer out, the interpreter would wait for one, and both for ever.
            assert!(self.out.get() < POOL, "the consumer keeps every buffer");
            let batch: Vec<Item> = self.items.by_ref().take(self.size).collect();
            if batch.is_empty() {
                return None;
            }
            self.out.set(self.out.get() + 1);
            Some(batch)
        }

        fn recycle(&self, _: Vec<Item>) {
            self.out.set(self.out.get() - 1);
        }
    }

    fn program() -> String {
        let mut text = String::from("G21 G90 G94 F1200\n");
        for i in 0..1000 {
            text.push_str(&format!("G1 X{}. Y{}.\n", i % 37, i % 23));
            if i % 300 == 299 {
                text.push_str("G4 P100\n");
            }
            // A new frame in the middle of the motion, twice.
            if i % 400 == 399 {
                text.push_str("G92 X0\n");
            }
        }
        text + "M30\n"
    }

    fn fake(text: &str, machine: &Machine, size: usize) -> Fake {
        Fake {
            items: interpret_str(text, machine, Options::default())
                .collect::<Vec<_>>()
                .into_iter(),
            size,
            out: Cell::new(0),
        }
    }

    #[test]
    fn batches_of_any_size_get_the_planners_timings_and_keep_a_buffer_free() {
        let machine = Machine::default();
        let text = program();
        let mut expected: Vec<(Item, Timing)> = Planner::new(
            interpret_str(&text, &machine, Options::default()),
            &machine,
            PlanOptions::default(),
        )
        .map(|item| match item {
            Ok(timed) => {
                let (item, timing) = timed.into_parts();
                (Ok(item), timing)
            }
            Err(alarm) => (Err(alarm), Timing::default()),
        })
        .collect();
        // A frame takes no time and starts with the item after it (the planner gives it none).
        let mut frames = 0;
        for at in (0..expected.len() - 1).rev() {
            if matches!(expected[at].0, Ok(crate::motion::Item::Frame(_))) {
                expected[at].1 = Timing {
                    dt: 0.0,
                    feed_unknown: false,
                    ..expected[at + 1].1
                };
                frames += 1;
            }
        }
        assert_eq!(frames, 3, "the first move's, and one after each G92");
        // One item a batch (a macro loop that rarely moves) up to batches longer than the
        // look-ahead window.
        for size in [1, 2, 7, 100, 256, 5000] {
            let mut got = Vec::new();
            let timeline = Timeline::new(&machine, PlanOptions::default());
            for_each_timed(
                &mut fake(&text, &machine, size),
                timeline,
                |items, timings| {
                    assert_eq!(items.len(), timings.len());
                    got.extend(items.iter().cloned().zip(timings.iter().copied()));
                    true
                },
            );
            assert_eq!(got, expected, "batches of {size}");
        }
    }

    #[test]
    fn a_consumer_that_stops_gets_no_more_batches() {
        let machine = Machine::default();
        let mut calls = 0;
        let timeline = Timeline::new(&machine, PlanOptions::default());
        for_each_timed(&mut fake(&program(), &machine, 10), timeline, |_, _| {
            calls += 1;
            calls < 3
        });
        assert_eq!(calls, 3);
    }
}
