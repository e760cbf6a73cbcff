//! The variable store: local variables (one level per macro call), common variables (cleared
//! at reset) and persistent common variables (kept between runs by the caller).
//!
//! System variables (#1000 and up: positions, offsets, modal information, alarms) are not
//! stored here: `system.rs` reads and writes them from the executor's state.

use super::MacroValue;

/// Local variables #1-#33 of one level.
pub(crate) type Locals = [MacroValue; 33];

/// The first and last persistent common variable (#500-#999 on the FANUC family).
pub(crate) const PERSISTENT_FIRST: u32 = 500;
/// See [`PERSISTENT_FIRST`].
pub(crate) const PERSISTENT_LAST: u32 = 999;

/// Where a variable number belongs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    /// #0: always vacant, read-only.
    Vacant,
    /// #1-#33.
    Local(usize),
    /// #100-#499 (cleared at reset).
    Common(usize),
    /// #500-#999 (kept in the machine's state).
    Persistent(usize),
    /// Extra common variables a profile has (Haas #10000-#10999 style numbers).
    Extended,
    /// Anything else: a system variable, or none.
    System,
}

/// All variables a program sees, but the system variables.
#[derive(Clone, Debug)]
pub(crate) struct Variables {
    /// Level 0 is the main program; G65 and G66 push a level, their return pops it.
    locals: Vec<Locals>,
    commons: Box<[MacroValue; 400]>,
    persistent: Box<[MacroValue; 500]>,
    /// Counts writes to the persistent variables, so the caller knows when to save them.
    persistent_writes: u64,
    extended: std::collections::BTreeMap<u32, MacroValue>,
    /// Syntec's public variables `@n`, kept for the run.
    public: std::collections::BTreeMap<u32, f64>,
}

impl Default for Variables {
    fn default() -> Variables {
        Variables {
            locals: vec![[None; 33]],
            commons: Box::new([None; 400]),
            persistent: Box::new([None; 500]),
            persistent_writes: 0,
            extended: std::collections::BTreeMap::new(),
            public: std::collections::BTreeMap::new(),
        }
    }
}

impl Variables {
    /// Where `#number` belongs; `extended` is the profile's extra common range.
    pub(crate) fn kind(number: u32, extended: Option<(u32, u32)>) -> Kind {
        match number {
            0 => Kind::Vacant,
            1..=33 => Kind::Local(number as usize - 1),
            100..=499 => Kind::Common(number as usize - 100),
            PERSISTENT_FIRST..=PERSISTENT_LAST => {
                Kind::Persistent((number - PERSISTENT_FIRST) as usize)
            }
            n if extended.is_some_and(|(first, last)| (first..=last).contains(&n)) => {
                Kind::Extended
            }
            _ => Kind::System,
        }
    }

    /// The value of a stored variable (`None` for system numbers: the caller asks `system`).
    #[inline]
    pub(crate) fn get(&self, number: u32, kind: Kind) -> MacroValue {
        match kind {
            Kind::Local(i) => self.locals.last().and_then(|l| l[i]),
            Kind::Common(i) => self.commons[i],
            Kind::Persistent(i) => self.persistent[i],
            Kind::Extended => self.extended.get(&number).copied().flatten(),
            Kind::Vacant | Kind::System => None,
        }
    }

    /// Stores a value; false for numbers that are not stored here.
    #[inline]
    pub(crate) fn set(&mut self, number: u32, kind: Kind, value: MacroValue) -> bool {
        match kind {
            Kind::Local(i) => {
                if let Some(level) = self.locals.last_mut() {
                    level[i] = value;
                }
            }
            Kind::Common(i) => self.commons[i] = value,
            Kind::Persistent(i) => {
                self.persistent[i] = value;
                self.persistent_writes += 1;
            }
            Kind::Extended => {
                self.extended.insert(number, value);
                self.persistent_writes += 1;
            }
            Kind::Vacant | Kind::System => return false,
        }
        true
    }

    /// The value of the public variable `@number`.
    pub(crate) fn public(&self, number: u32) -> MacroValue {
        self.public.get(&number).copied()
    }

    /// Sets the public variable `@number` (vacant removes it).
    pub(crate) fn set_public(&mut self, number: u32, value: MacroValue) {
        match value {
            Some(value) => self.public.insert(number, value),
            None => self.public.remove(&number),
        };
    }

    /// A macro call: a new level of locals holding the arguments.
    pub(crate) fn push_level(&mut self, arguments: Locals) {
        self.locals.push(arguments);
    }

    /// The end of a macro call: back to the caller's locals.
    pub(crate) fn pop_level(&mut self) {
        if self.locals.len() > 1 {
            self.locals.pop();
        }
    }

    /// Replaces the locals of the current level (a repeated G65 starts from its arguments).
    pub(crate) fn reset_level(&mut self, arguments: Locals) {
        if let Some(level) = self.locals.last_mut() {
            *level = arguments;
        }
    }

    /// Loads persistent values (#500-#999 and the profile's extended ones) saved by a run.
    pub(crate) fn load_persistent(&mut self, values: &PersistentVariables) {
        for (&number, &value) in &values.values {
            match Variables::kind(number, Some((number, number))) {
                Kind::Persistent(i) => self.persistent[i] = Some(value),
                Kind::Extended => {
                    self.extended.insert(number, Some(value));
                }
                _ => {}
            }
        }
    }

    /// The persistent values now (vacant ones left out).
    pub(crate) fn persistent(&self) -> PersistentVariables {
        let mut values = std::collections::BTreeMap::new();
        for (i, v) in self.persistent.iter().enumerate() {
            if let Some(v) = v {
                values.insert(PERSISTENT_FIRST + i as u32, *v);
            }
        }
        for (&n, v) in &self.extended {
            if let Some(v) = v {
                values.insert(n, *v);
            }
        }
        PersistentVariables { values }
    }

    /// How many times persistent variables were written (changes when they may have changed).
    pub(crate) fn persistent_writes(&self) -> u64 {
        self.persistent_writes
    }
}

/// The values of the persistent common variables (#500-#999, and the profile's extended
/// numbers), as a run starts with them and leaves them: what a control keeps in battery-backed
/// memory. Vacant variables are absent.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PersistentVariables {
    /// Variable number to value.
    pub values: std::collections::BTreeMap<u32, f64>,
}
