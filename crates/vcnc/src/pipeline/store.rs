//! Saving the persistent macro variables (#500-#999) while a program runs.
//!
//! The caller owns where and how they are kept (a state file, a database): it gives a
//! [`PersistentStore`], and this module decides when to save: at most twice a second while the
//! program runs and writes them, so that a killed run keeps what it wrote, and once more when
//! the interpreter ends. It never prints: the first failed save is kept for the caller.

use super::threads::BatchSource;
use crate::interp::PersistentVariables;
use std::io;
use std::time::{Duration, Instant};

/// Where a run's persistent variables are kept between runs.
///
/// Any `FnMut(&PersistentVariables) -> io::Result<()>` that can go to another thread is one.
pub trait PersistentStore: Send {
    /// Saves `values`, the persistent variables now (all of them, not only those changed).
    ///
    /// # Errors
    /// Whatever keeping them met; the run goes on, and later saves are still tried.
    fn save(&mut self, values: &PersistentVariables) -> io::Result<()>;
}

impl<F: FnMut(&PersistentVariables) -> io::Result<()> + Send> PersistentStore for F {
    fn save(&mut self, values: &PersistentVariables) -> io::Result<()> {
        self(values)
    }
}

/// Least time between two saves while a program runs.
const SAVE_INTERVAL: Duration = Duration::from_millis(500);

/// Saves the persistent variables when they were written since the last save.
pub(crate) struct Saver {
    store: Option<Box<dyn PersistentStore>>,
    saved_writes: u64,
    saved_at: Instant,
    error: Option<io::Error>,
}

impl Saver {
    /// Saves `interpreter`'s variables in `store`, if there is one.
    pub(crate) fn new(
        interpreter: &impl BatchSource,
        store: Option<Box<dyn PersistentStore>>,
    ) -> Saver {
        Saver {
            store,
            saved_writes: interpreter.persistent_writes(),
            saved_at: Instant::now(),
            error: None,
        }
    }

    /// True when a save is due, should the variables have changed.
    pub(crate) fn due(&self) -> bool {
        self.store.is_some() && self.saved_at.elapsed() >= SAVE_INTERVAL
    }

    /// Saves the variables if they were written since the last save.
    pub(crate) fn save(&mut self, interpreter: &impl BatchSource) {
        let writes = interpreter.persistent_writes();
        if writes == self.saved_writes {
            return;
        }
        if let Some(store) = self.store.as_mut() {
            if let Err(error) = store.save(&interpreter.persistent_variables()) {
                self.error.get_or_insert(error);
            }
        }
        self.saved_writes = writes;
        self.saved_at = Instant::now();
    }

    /// The first save that failed.
    pub(crate) fn into_error(self) -> Option<io::Error> {
        self.error
    }
}
