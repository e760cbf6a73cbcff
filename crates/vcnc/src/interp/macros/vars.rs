//! The variable store: local variables (one level per macro call), common variables (cleared
//! at reset) and persistent common variables (kept between runs by the caller).
//!
//! The ranges are the profile's (`macros.last_local_variable`, `first_persistent_variable`):
//! FANUC's locals #1-#33, commons #100-#499, persistent #500-#999; Syntec's locals #1-#400 and
//! persistent #401-#999 (its "axis group user memory"), with no commons among the `#`
//! variables (its public variables `@n` are those). Locals past #33 live in a block of their
//! own per level, made when the first of them is written, so a FANUC call level stays small.
//!
//! System variables (#1000 and up: positions, offsets, modal information, alarms) are not
//! stored here: `system.rs` reads and writes them from the executor's state.

use super::MacroValue;

/// Local variables #1-#33 of one level.
pub(crate) type Locals = [MacroValue; 33];

/// The first local past #33.
const UPPER_LOCAL_FIRST: u32 = 34;
/// The last local a profile can have (Syntec's #400).
pub(crate) const LAST_LOCAL_MOST: u32 = 400;
/// How many locals past #33 a level can hold.
const UPPER_LOCALS: usize = (LAST_LOCAL_MOST - UPPER_LOCAL_FIRST + 1) as usize;
/// Locals #34-#400 of one level.
type UpperLocals = [MacroValue; UPPER_LOCALS];

/// The first persistent variable a profile can have (Syntec's #401; FANUC's is #500).
pub(crate) const PERSISTENT_FIRST_LEAST: u32 = 401;
/// The last persistent common variable.
pub(crate) const PERSISTENT_LAST: u32 = 999;

/// The local, common and persistent variable numbers of a profile.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Ranges {
    /// Locals are #1 to this.
    pub(crate) last_local: u32,
    /// Persistent variables are this to #999; commons are #100-#499 below it and above the
    /// locals.
    pub(crate) first_persistent: u32,
    /// The profile's extra common range (Haas #10000-#10999), first and last.
    pub(crate) extended: Option<(u32, u32)>,
}

impl Ranges {
    /// The ranges of `rules`.
    pub(crate) fn of(rules: &crate::profile::MacroRules) -> Ranges {
        Ranges {
            last_local: rules.last_local_variable,
            first_persistent: rules.first_persistent_variable,
            extended: rules.extended_common_variables,
        }
    }
}

/// One call level's locals.
#[derive(Clone, Debug)]
struct Level {
    /// #1-#33 (the arguments and the FANUC locals).
    first: Locals,
    /// #34 and up, where the profile has them, once one is written.
    upper: Option<Box<UpperLocals>>,
}

impl Level {
    fn new(first: Locals) -> Level {
        Level { first, upper: None }
    }
}

/// Where a variable number belongs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    /// #0: always vacant, read-only.
    Vacant,
    /// #1-#33.
    Local(usize),
    /// #34 and up to the profile's last local (Syntec's #400).
    UpperLocal(usize),
    /// #100-#499 (cleared at reset).
    Common(usize),
    /// #500-#999, Syntec's #401-#999 (kept in the machine's state).
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
    locals: Vec<Level>,
    commons: Box<[MacroValue; 400]>,
    /// From [`PERSISTENT_FIRST_LEAST`] to [`PERSISTENT_LAST`].
    persistent: Box<[MacroValue; (PERSISTENT_LAST - PERSISTENT_FIRST_LEAST + 1) as usize]>,
    /// Counts writes to the persistent variables, so the caller knows when to save them.
    persistent_writes: u64,
    extended: std::collections::BTreeMap<u32, MacroValue>,
    /// Syntec's public variables `@n`, kept for the run.
    public: std::collections::BTreeMap<u32, f64>,
}

impl Default for Variables {
    fn default() -> Variables {
        Variables {
            locals: vec![Level::new([None; 33])],
            commons: Box::new([None; 400]),
            persistent: Box::new([None; (PERSISTENT_LAST - PERSISTENT_FIRST_LEAST + 1) as usize]),
            persistent_writes: 0,
            extended: std::collections::BTreeMap::new(),
            public: std::collections::BTreeMap::new(),
        }
    }
}

impl Variables {
    /// Where `#number` belongs on a profile with the variables `ranges`.
    pub(crate) fn kind(number: u32, ranges: &Ranges) -> Kind {
        match number {
            0 => Kind::Vacant,
            1..=33 => Kind::Local(number as usize - 1),
            n if n <= ranges.last_local.min(LAST_LOCAL_MOST) => {
                Kind::UpperLocal((n - UPPER_LOCAL_FIRST) as usize)
            }
            n if n >= ranges.first_persistent.max(PERSISTENT_FIRST_LEAST)
                && n <= PERSISTENT_LAST =>
            {
                Kind::Persistent((n - PERSISTENT_FIRST_LEAST) as usize)
            }
            100..=499 => Kind::Common(number as usize - 100),
            n if ranges
                .extended
                .is_some_and(|(first, last)| (first..=last).contains(&n)) =>
            {
                Kind::Extended
            }
            _ => Kind::System,
        }
    }

    /// The value of a stored variable (`None` for system numbers: the caller asks `system`).
    #[inline]
    pub(crate) fn get(&self, number: u32, kind: Kind) -> MacroValue {
        match kind {
            Kind::Local(i) => self.locals.last().and_then(|l| l.first[i]),
            Kind::UpperLocal(i) => self
                .locals
                .last()
                .and_then(|l| l.upper.as_ref())
                .and_then(|upper| upper[i]),
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
                    level.first[i] = value;
                }
            }
            Kind::UpperLocal(i) => {
                if let Some(level) = self.locals.last_mut() {
                    let upper = level
                        .upper
                        .get_or_insert_with(|| Box::new([None; UPPER_LOCALS]));
                    upper[i] = value;
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
        self.locals.push(Level::new(arguments));
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
            *level = Level::new(arguments);
        }
    }

    /// Loads persistent values (#500-#999, or the profile's range, and extended ones) saved by
    /// a run; a number of neither kind on the profile `ranges` is kept as an extended one.
    pub(crate) fn load_persistent(&mut self, values: &PersistentVariables, ranges: &Ranges) {
        for (&number, &value) in &values.values {
            let ranges = Ranges {
                extended: Some((number, number)),
                ..*ranges
            };
            match Variables::kind(number, &ranges) {
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
                values.insert(PERSISTENT_FIRST_LEAST + i as u32, *v);
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
