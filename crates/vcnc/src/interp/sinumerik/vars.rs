#![cfg_attr(not(test), allow(dead_code))] // wired in by the front end (issue 20)
//! The SINUMERIK variable store: R parameters, user variables declared with DEF, their scopes,
//! and the parameters of PROC calls.
//!
//! Two stores of cells: the global one holds the R parameters (R0..R(n-1), n from the machine
//! data MD28050, standard 0-99: PGsl 15.4 L11254-11258) and global user data (GUD, declared by
//! the front end for definition files); the local one holds the local user data (LUD) of each
//! program level, a stack that a subprogram call pushes and its return pops. A name is looked up
//! in the current level, then among the globals (**choice**: a subprogram does not see its
//! caller's LUD, the control's default with MD11120 LUD_EXTENDED_SCOPE = 0). A `VAR` parameter
//! binds a name of the new level to a [`Place`] of the caller: a variable, an array, an array
//! element or an R parameter, so that writes reach the caller.
//!
//! Arrays have one to three dimensions, indices 0..n-1, the last index running fastest (SET
//! fills `A[0,0]`, `A[0,1]` ... ). Every value stored is converted to the variable's type.
//! Bad input is an alarm with its span, never a panic; the stores are bounded ([`MAX_CELLS`],
//! [`MAX_LEVELS`]) so that no program can grow them without end.

use super::value::{int_of, kind_name, Type, Value};
use crate::alarm::{Alarm, AlarmCode};
use crate::source::Span;
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// Variables by name. A block reads its variables by name (`F=FEED1`): SipHash cost about a
/// hundred instructions a name; the names are short, and a multiply-and-rotate hash (as the
/// Rust compiler's own maps use) costs a few a byte. A program that chose colliding names
/// only slows its own look-ups, bounded by the number of variables it may define.
type Names = HashMap<Box<str>, Place, BuildHasherDefault<NameHasher>>;

/// The hasher of [`Names`].
#[derive(Default)]
struct NameHasher(u64);

impl Hasher for NameHasher {
    fn write(&mut self, bytes: &[u8]) {
        for &byte in bytes {
            self.0 =
                (self.0.rotate_left(5) ^ u64::from(byte)).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
        }
    }

    fn finish(&self) -> u64 {
        self.0
    }
}

/// The number of R parameters without a machine file's word: R0 to R99 (PGsl 15.4, L11254-11258,
/// "standard 0 to 99"; MD28050 MM_NUM_R_PARAM sets it on the control).
pub(crate) const DEFAULT_R_PARAMETERS: usize = 100;

/// The most cells (scalars and array elements) each store holds: a bound on memory, far above
/// what the manual's and the corpus's programs declare (**choice**: the control's limit is its
/// memory configuration, MD18242 and others).
pub(crate) const MAX_CELLS: usize = 65_536;

/// The most program levels at once; the front end's call-depth limit comes first.
pub(crate) const MAX_LEVELS: usize = 256;

/// Arrays have at most three dimensions (tables 12.2 tier 2: "arrays with SET/REP"; PGAsl).
pub(crate) const MAX_DIMENSIONS: usize = 3;

/// The longest variable name (PGsl 15.5, L11416-11462: variable identifiers 31 characters).
const MAX_NAME: usize = 31;

/// The largest size of one dimension (**choice**: PGAsl's 32767).
const MAX_EXTENT: usize = 32_767;

/// Words a variable may not be named: the language's own (PGsl 15.5: "reserved keywords cannot
/// be used"). The front end checks G codes, axis names and other keywords it knows.
const RESERVED: [&str; 44] = [
    "TRUE", "FALSE", "AND", "OR", "XOR", "NOT", "B_AND", "B_OR", "B_XOR", "B_NOT", "DIV", "MOD",
    "INT", "REAL", "BOOL", "CHAR", "STRING", "AXIS", "FRAME", "DEF", "PROC", "VAR", "SET", "REP",
    "SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN2", "SQRT", "ABS", "POT", "TRUNC", "ROUND",
    "ROUNDUP", "LN", "EXP", "MINVAL", "MAXVAL", "BOUND", "STRLEN", "INDEX", "SUBSTR",
];

/// Which store a cell is in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Store {
    Global,
    Local,
}

/// Where a variable, an array or one element lives: what a name is bound to, and what a `VAR`
/// parameter aliases. Valid until the program level it lives in is popped.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Place {
    store: Store,
    /// The first cell.
    base: usize,
    /// One past the last cell a SET or REP from here may fill (the end of the array).
    end: usize,
    /// The type of each cell.
    ty: Type,
    /// The extents of an array; empty for a scalar or one element.
    dims: Vec<usize>,
}

impl Place {
    /// The type of the variable or of each element.
    pub(crate) fn ty(&self) -> Type {
        self.ty
    }

    /// The extents of an array; empty for a scalar or an element.
    pub(crate) fn dims(&self) -> &[usize] {
        &self.dims
    }
}

/// What a DEF gives its variable.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Init {
    /// Nothing: the type's default value.
    Default,
    /// `=value`: a scalar's value, or every element of an array (**choice**, as REP).
    Value(Value),
    /// `=SET(a, b, c)`: the first elements in order, the rest default.
    Set(Vec<Value>),
    /// `=REP(v)`: every element.
    Rep(Value),
}

/// The type of a `VAR` parameter: its type and, for an array, its extents, `None` where the
/// PROC leaves one open (`VAR REAL A[,3]`).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ParamType {
    /// The element type; any STRING length matches any other.
    pub(crate) ty: Type,
    /// The extents, empty for a scalar.
    pub(crate) dims: Vec<Option<usize>>,
}

/// The names of one program level and where its cells start.
#[derive(Debug, Default)]
struct Level {
    names: Names,
    start: usize,
}

/// The variables of one channel.
#[derive(Debug)]
pub(crate) struct Variables {
    r_count: usize,
    global_cells: Vec<Value>,
    globals: Names,
    local_cells: Vec<Value>,
    /// Never empty: level 0 is the main program.
    levels: Vec<Level>,
}

impl Default for Variables {
    fn default() -> Variables {
        Variables::new(DEFAULT_R_PARAMETERS)
    }
}

impl Variables {
    /// A store with R0 to R(`r_count`-1), all 0, and no user variables (at most [`MAX_CELLS`]
    /// R parameters).
    pub(crate) fn new(r_count: usize) -> Variables {
        let r_count = r_count.min(MAX_CELLS);
        Variables {
            r_count,
            global_cells: vec![Value::Real(0.0); r_count],
            globals: Names::default(),
            local_cells: Vec::new(),
            levels: vec![Level::default()],
        }
    }

    /// How many R parameters there are.
    pub(crate) fn r_count(&self) -> usize {
        self.r_count
    }

    /// The current program level: 0 in the main program.
    pub(crate) fn depth(&self) -> usize {
        self.levels.len() - 1
    }

    /// Enters a program level (a subprogram or PROC call): its names start empty.
    ///
    /// # Errors
    /// [`AlarmCode::MacroLimit`] beyond [`MAX_LEVELS`].
    pub(crate) fn push_level(&mut self, span: Span) -> Result<(), Alarm> {
        if self.levels.len() >= MAX_LEVELS {
            return Err(Alarm::error(
                AlarmCode::MacroLimit,
                span,
                format!("more than {MAX_LEVELS} program levels hold variables"),
            )
            .with_help("a subprogram calls itself without end: check its return condition"));
        }
        self.levels.push(Level {
            names: Names::default(),
            start: self.local_cells.len(),
        });
        Ok(())
    }

    /// Leaves the current level (return from a subprogram): its variables are gone, what its
    /// `VAR` parameters wrote stays in the caller's. The main program's level stays.
    pub(crate) fn pop_level(&mut self) {
        if self.levels.len() > 1 {
            if let Some(level) = self.levels.pop() {
                self.local_cells.truncate(level.start);
            }
        }
    }

    /// The end of the main program: every level and every LUD is gone; R parameters and GUD
    /// keep their values (they are retentive on the control).
    pub(crate) fn end_program(&mut self) {
        self.levels.truncate(1);
        self.levels[0].names.clear();
        self.local_cells.clear();
    }

    /// True when `name` is an R parameter (`R7`) or a user variable visible here.
    pub(crate) fn is_defined(&self, name: &str) -> bool {
        self.r_number(name).is_some() || self.binding(name).is_some()
    }

    /// Declares a local user variable of the current level (DEF in a program).
    ///
    /// # Errors
    /// [`AlarmCode::BadVariable`] for a name that is not an identifier, is reserved or already
    /// declared here or globally; [`AlarmCode::ValueOutOfRange`] for a bad extent;
    /// [`AlarmCode::MacroLimit`] when the store is full; conversion alarms of the initial
    /// values; [`AlarmCode::MacroArithmetic`] for more SET values than elements.
    pub(crate) fn declare(
        &mut self,
        name: &str,
        ty: Type,
        dims: &[Value],
        init: Init,
        span: Span,
    ) -> Result<(), Alarm> {
        let place = self.allocate(name, Store::Local, ty, dims, init, span)?;
        self.current().names.insert(name.into(), place);
        Ok(())
    }

    /// Declares a global user variable (GUD: `DEF NCK` or `DEF CHAN` in a definition file).
    ///
    /// # Errors
    /// As [`Variables::declare`].
    pub(crate) fn declare_global(
        &mut self,
        name: &str,
        ty: Type,
        dims: &[Value],
        init: Init,
        span: Span,
    ) -> Result<(), Alarm> {
        let place = self.allocate(name, Store::Global, ty, dims, init, span)?;
        self.globals.insert(name.into(), place);
        Ok(())
    }

    /// The cells of a new variable `name` in `store`, initialised.
    fn allocate(
        &mut self,
        name: &str,
        store: Store,
        ty: Type,
        dims: &[Value],
        init: Init,
        span: Span,
    ) -> Result<Place, Alarm> {
        self.check_new_name(name, store, span)?;
        let dims = extents(dims, span)?;
        let size: usize = dims.iter().product();
        let base = self.cells(store).len();
        if base + size > MAX_CELLS {
            return Err(full(span));
        }
        self.cells_vec(store)
            .resize(base + size, ty.default_value());
        let place = Place {
            store,
            base,
            end: base + size,
            ty,
            dims,
        };
        // A failed initialiser leaves no half-declared variable behind.
        if let Err(alarm) = self.initialise(&place, init, span) {
            self.cells_vec(store).truncate(base);
            return Err(alarm);
        }
        Ok(place)
    }

    /// Binds a by-value parameter of a PROC in the current (new) level: a local scalar with
    /// `value` converted to `ty`.
    ///
    /// # Errors
    /// As [`Variables::declare`].
    pub(crate) fn bind_value(
        &mut self,
        name: &str,
        ty: Type,
        value: Value,
        span: Span,
    ) -> Result<(), Alarm> {
        self.declare(name, ty, &[], Init::Value(value), span)
    }

    /// Binds a `VAR` parameter of a PROC in the current (new) level to `place`, a place of the
    /// caller resolved with [`Variables::place`] before [`Variables::push_level`].
    ///
    /// # Errors
    /// [`AlarmCode::BadVariable`] for a bad or taken name, a type or dimensions that differ
    /// from the parameter's.
    pub(crate) fn bind_reference(
        &mut self,
        name: &str,
        param: &ParamType,
        place: Place,
        span: Span,
    ) -> Result<(), Alarm> {
        self.check_new_name(name, Store::Local, span)?;
        let dims_match = param.dims.len() == place.dims.len()
            && param
                .dims
                .iter()
                .zip(&place.dims)
                .all(|(want, have)| want.is_none_or(|w| w == *have));
        if !param.ty.same_kind(place.ty) || !dims_match {
            return Err(Alarm::error(
                AlarmCode::BadVariable,
                span,
                format!(
                    "VAR {name} is {}, the call passes {}",
                    describe(param.ty, &param.dims),
                    describe(
                        place.ty,
                        &place.dims.iter().map(|&d| Some(d)).collect::<Vec<_>>()
                    )
                ),
            )
            .with_help("a VAR parameter takes a variable of exactly its type and dimensions"));
        }
        // A scalar alias never reaches the rest of the array it may sit in.
        let place = match place.dims.is_empty() {
            true => Place {
                end: place.base + 1,
                ..place
            },
            false => place,
        };
        self.current().names.insert(name.into(), place);
        Ok(())
    }

    /// Where `name` with `indices` lives: an R parameter (`R7`, or `R` with one index), a
    /// variable, a whole array (no indices), or one element (all indices).
    ///
    /// # Errors
    /// [`AlarmCode::BadVariable`] for an unknown name, an R number beyond the last, indices
    /// out of range or of the wrong count; conversion alarms of the indices.
    pub(crate) fn place(&self, name: &str, indices: &[Value], span: Span) -> Result<Place, Alarm> {
        if name == "R" && !indices.is_empty() {
            let [index] = indices else {
                return Err(bad(span, "an R parameter takes one index: R[n]"));
            };
            let n = index_of(index, span)?;
            return self.r_place(n, span);
        }
        if let Some(n) = self.r_number(name) {
            if !indices.is_empty() {
                return Err(bad(
                    span,
                    format!("{name} is an R parameter and takes no index"),
                ));
            }
            return self.r_place(n, span);
        }
        let binding = self.binding(name).ok_or_else(|| {
            Alarm::error(
                AlarmCode::BadVariable,
                span,
                format!("{name} is not a variable, an axis or a function the control knows"),
            )
            .with_help("declare it with DEF (`DEF REAL NAME`), or check its spelling")
        })?;
        if indices.is_empty() {
            return Ok(binding.clone());
        }
        if indices.len() != binding.dims.len() {
            return Err(bad(
                span,
                match binding.dims.len() {
                    0 => format!("{name} is no array and takes no index"),
                    n => format!("{name} has {n} dimensions, {} indices given", indices.len()),
                },
            ));
        }
        let mut flat = 0;
        for (index, &extent) in indices.iter().zip(&binding.dims) {
            let i = index_of(index, span)?;
            if i >= extent {
                return Err(out_of_range(name, i, extent, span));
            }
            flat = flat * extent + i;
        }
        Ok(Place {
            base: binding.base + flat,
            dims: Vec::new(),
            ..binding.clone()
        })
    }

    /// The value at a scalar place.
    ///
    /// # Errors
    /// [`AlarmCode::BadVariable`] for a whole array.
    pub(crate) fn get(&self, place: &Place, span: Span) -> Result<Value, Alarm> {
        if !place.dims.is_empty() {
            return Err(whole_array(span));
        }
        self.cells(place.store)
            .get(place.base)
            .cloned()
            .ok_or_else(|| gone(span))
    }

    /// The value of `name` when it names a scalar variable the program defined, as
    /// [`Variables::read`] gives it without indices; None for any other name (an R parameter,
    /// an array, an unknown name), which `read` then takes. One look-up: a block's `F=FEED1`.
    pub(crate) fn scalar(&self, name: &str) -> Option<&Value> {
        if self.r_number(name).is_some() {
            return None;
        }
        let place = self.binding(name)?;
        if !place.dims.is_empty() {
            return None;
        }
        self.cells(place.store).get(place.base)
    }

    /// Reads `name` with `indices` ([`Variables::place`], then [`Variables::get`]).
    ///
    /// # Errors
    /// As those two.
    pub(crate) fn read(&self, name: &str, indices: &[Value], span: Span) -> Result<Value, Alarm> {
        self.get(&self.place(name, indices, span)?, span)
    }

    /// Stores `value` at a scalar place, converted to its type.
    ///
    /// # Errors
    /// [`AlarmCode::BadVariable`] for a whole array; the conversion's alarms.
    pub(crate) fn set(&mut self, place: &Place, value: Value, span: Span) -> Result<(), Alarm> {
        if !place.dims.is_empty() {
            return Err(whole_array(span));
        }
        let value = value.convert(place.ty, span)?;
        let cell = self
            .span_of(place, span)?
            .first_mut()
            .ok_or_else(|| gone(span))?;
        *cell = value;
        Ok(())
    }

    /// `place = SET(values)`: the values in order from the place (an array's first element, or
    /// one element) on.
    ///
    /// # Errors
    /// [`AlarmCode::MacroArithmetic`] for more values than cells up to the array's end; the
    /// conversion's alarms (nothing is stored then).
    pub(crate) fn set_list(
        &mut self,
        place: &Place,
        values: Vec<Value>,
        span: Span,
    ) -> Result<(), Alarm> {
        let room = place.end - place.base;
        if values.len() > room {
            return Err(Alarm::error(
                AlarmCode::MacroArithmetic,
                span,
                format!("SET gives {} values for {room} elements", values.len()),
            )
            .with_help("give SET at most as many values as the array has elements from there"));
        }
        let converted = values
            .into_iter()
            .map(|v| v.convert(place.ty, span))
            .collect::<Result<Vec<_>, _>>()?;
        for (cell, value) in self.span_of(place, span)?.iter_mut().zip(converted) {
            *cell = value;
        }
        Ok(())
    }

    /// `place = REP(value)`: every cell from the place to the array's end.
    ///
    /// # Errors
    /// The conversion's alarms.
    pub(crate) fn fill(&mut self, place: &Place, value: Value, span: Span) -> Result<(), Alarm> {
        let value = value.convert(place.ty, span)?;
        for cell in self.span_of(place, span)? {
            *cell = value.clone();
        }
        Ok(())
    }

    fn initialise(&mut self, place: &Place, init: Init, span: Span) -> Result<(), Alarm> {
        match init {
            Init::Default => Ok(()),
            Init::Value(value) | Init::Rep(value) => self.fill(place, value, span),
            Init::Set(values) => self.set_list(place, values, span),
        }
    }

    fn current(&mut self) -> &mut Level {
        let last = self.levels.len() - 1;
        &mut self.levels[last]
    }

    fn binding(&self, name: &str) -> Option<&Place> {
        self.levels
            .last()
            .and_then(|level| level.names.get(name))
            .or_else(|| self.globals.get(name))
    }

    fn cells(&self, store: Store) -> &[Value] {
        match store {
            Store::Global => &self.global_cells,
            Store::Local => &self.local_cells,
        }
    }

    /// The cells from the place to the end of its array (its one cell for a scalar).
    fn span_of(&mut self, place: &Place, span: Span) -> Result<&mut [Value], Alarm> {
        self.cells_vec(place.store)
            .get_mut(place.base..place.end)
            .ok_or_else(|| gone(span))
    }

    fn cells_vec(&mut self, store: Store) -> &mut Vec<Value> {
        match store {
            Store::Global => &mut self.global_cells,
            Store::Local => &mut self.local_cells,
        }
    }

    /// `R12` as 12; `None` for any other name.
    fn r_number(&self, name: &str) -> Option<usize> {
        let digits = name.strip_prefix('R')?;
        if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        // An absurdly long number is beyond every R parameter.
        Some(digits.parse().unwrap_or(usize::MAX))
    }

    fn r_place(&self, n: usize, span: Span) -> Result<Place, Alarm> {
        if n >= self.r_count {
            return Err(Alarm::error(
                AlarmCode::BadVariable,
                span,
                format!(
                    "R{n} does not exist: this control has R0 to R{}",
                    self.r_count.saturating_sub(1)
                ),
            )
            .with_help("use a lower R number, or raise the number of R parameters (MD28050)"));
        }
        Ok(Place {
            store: Store::Global,
            base: n,
            end: n + 1,
            ty: Type::Real,
            dims: Vec::new(),
        })
    }

    /// The identifier rule (PGsl 15.5, L11416-11462), the reserved words, and no second
    /// declaration of a name in its scope or of a global's name.
    fn check_new_name(&self, name: &str, store: Store, span: Span) -> Result<(), Alarm> {
        let bytes = name.as_bytes();
        let lead = |b: &u8| b.is_ascii_uppercase() || *b == b'_';
        let identifier = bytes.len() >= 2
            && bytes.len() <= MAX_NAME
            && bytes[..2].iter().all(lead)
            && bytes.iter().all(|b| lead(b) || b.is_ascii_digit());
        if !identifier {
            return Err(bad(
                span,
                format!("{name} is no variable name: letters, digits and _, the first two letters or _, at most {MAX_NAME}"),
            ));
        }
        if RESERVED.contains(&name) {
            return Err(bad(span, format!("{name} is a word of the language")));
        }
        let taken = match store {
            Store::Local => {
                self.levels
                    .last()
                    .is_some_and(|l| l.names.contains_key(name))
                    || self.globals.contains_key(name)
            }
            Store::Global => {
                self.globals.contains_key(name)
                    || self.levels.iter().any(|l| l.names.contains_key(name))
            }
        };
        if taken {
            return Err(Alarm::error(
                AlarmCode::BadVariable,
                span,
                format!("{name} is already declared"),
            )
            .with_help(
                "a name is declared once in a program: remove the second DEF or rename it",
            ));
        }
        Ok(())
    }
}

/// The extents of a DEF: one to three, each 1 to [`MAX_EXTENT`], all within [`MAX_CELLS`].
fn extents(dims: &[Value], span: Span) -> Result<Vec<usize>, Alarm> {
    if dims.len() > MAX_DIMENSIONS {
        return Err(Alarm::error(
            AlarmCode::ValueOutOfRange,
            span,
            format!("an array has at most {MAX_DIMENSIONS} dimensions"),
        ));
    }
    let mut extents = Vec::with_capacity(dims.len());
    let mut size = 1usize;
    for dim in dims {
        let n = int_of(
            dim.as_f64()
                .ok_or_else(|| bad(span, "an array extent is a number"))?,
            span,
        )?;
        let n = usize::try_from(n)
            .ok()
            .filter(|n| (1..=MAX_EXTENT).contains(n))
            .ok_or_else(|| {
                Alarm::error(
                    AlarmCode::ValueOutOfRange,
                    span,
                    format!("an array extent of {n}: it is 1 to {MAX_EXTENT}"),
                )
            })?;
        size = size.saturating_mul(n);
        extents.push(n);
    }
    if size > MAX_CELLS {
        return Err(full(span));
    }
    Ok(extents)
}

/// An index value as a position: INT, or a REAL rounded (**choice**: the conversion rule;
/// R parameters are REAL and index arrays in real programs).
fn index_of(index: &Value, span: Span) -> Result<usize, Alarm> {
    let Some(x) = index.as_f64().filter(|_| !matches!(index, Value::Bool(_))) else {
        return Err(bad(
            span,
            format!("an index is a number, not {}", kind_name(index.type_of())),
        ));
    };
    let i = int_of(x, span)?;
    usize::try_from(i).map_err(|_| bad(span, format!("the index {i} is negative")))
}

fn describe(ty: Type, dims: &[Option<usize>]) -> String {
    if dims.is_empty() {
        return ty.name();
    }
    let extents: Vec<String> = dims
        .iter()
        .map(|d| d.map(|n| n.to_string()).unwrap_or_default())
        .collect();
    format!("{}[{}]", ty.name(), extents.join(","))
}

fn bad(span: Span, message: impl Into<String>) -> Alarm {
    Alarm::error(AlarmCode::BadVariable, span, message)
        .with_help("check the variable's DEF: its name, type and extents")
}

fn out_of_range(name: &str, i: usize, extent: usize, span: Span) -> Alarm {
    Alarm::error(
        AlarmCode::BadVariable,
        span,
        format!(
            "{name}: index {i} is out of range 0 to {}",
            extent.saturating_sub(1)
        ),
    )
    .with_help("array indices start at 0 and end one below the extent in the DEF")
}

fn whole_array(span: Span) -> Alarm {
    bad(
        span,
        "an array is read and written element by element: give its indices",
    )
}

/// A place kept past the end of its program level: the front end's mistake, not the
/// program's, but an alarm rather than a panic.
fn gone(span: Span) -> Alarm {
    bad(
        span,
        "the variable no longer exists: its program level has ended",
    )
}

fn full(span: Span) -> Alarm {
    Alarm::error(
        AlarmCode::MacroLimit,
        span,
        format!("the variables need more than {MAX_CELLS} values"),
    )
    .with_help("declare smaller arrays, or fewer variables in the levels called")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::source::FileId;

    fn span() -> Span {
        Span::new(FileId(0), 1, 0..1)
    }

    fn int(i: i32) -> Value {
        Value::Int(i)
    }

    fn read(variables: &Variables, name: &str, indices: &[i32]) -> Result<Value, Alarm> {
        let indices: Vec<Value> = indices.iter().map(|&i| int(i)).collect();
        variables.read(name, &indices, span())
    }

    fn write(variables: &mut Variables, name: &str, indices: &[i32], value: Value) {
        let indices: Vec<Value> = indices.iter().map(|&i| int(i)).collect();
        let place = variables.place(name, &indices, span()).unwrap();
        variables.set(&place, value, span()).unwrap();
    }

    fn declare(variables: &mut Variables, name: &str, ty: Type, dims: &[i32], init: Init) {
        let dims: Vec<Value> = dims.iter().map(|&i| int(i)).collect();
        variables.declare(name, ty, &dims, init, span()).unwrap();
    }

    fn declare_err(variables: &mut Variables, name: &str, ty: Type, dims: &[i32]) -> Alarm {
        let dims: Vec<Value> = dims.iter().map(|&i| int(i)).collect();
        variables
            .declare(name, ty, &dims, Init::Default, span())
            .unwrap_err()
    }

    #[test]
    fn r_parameters_are_r0_to_r99_by_default() {
        // PGsl 15.4 (L11254-11258): standard R0 to R99.
        let variables = Variables::default();
        assert_eq!(variables.r_count(), 100);
        assert_eq!(read(&variables, "R0", &[]), Ok(Value::Real(0.0)));
        assert_eq!(read(&variables, "R99", &[]), Ok(Value::Real(0.0)));
        assert_eq!(
            read(&variables, "R100", &[]).unwrap_err().code,
            AlarmCode::BadVariable
        );
        assert_eq!(read(&variables, "R", &[99]), Ok(Value::Real(0.0)));
        assert!(read(&variables, "R", &[-1]).is_err());
        assert!(read(&variables, "R", &[1, 2]).is_err());
        assert!(read(&variables, "R1", &[1]).is_err());
        // A machine with MD28050 = 300.
        let variables = Variables::new(300);
        assert_eq!(read(&variables, "R299", &[]), Ok(Value::Real(0.0)));
    }

    #[test]
    fn uninitialised_variables_have_the_types_defaults() {
        let mut variables = Variables::default();
        declare(&mut variables, "COUNT", Type::Int, &[], Init::Default);
        declare(&mut variables, "FLAG", Type::Bool, &[], Init::Default);
        declare(&mut variables, "TEXT", Type::String(10), &[], Init::Default);
        declare(&mut variables, "LETTER", Type::Char, &[], Init::Default);
        assert_eq!(read(&variables, "COUNT", &[]), Ok(int(0)));
        assert_eq!(read(&variables, "FLAG", &[]), Ok(Value::Bool(false)));
        assert_eq!(read(&variables, "TEXT", &[]), Ok(Value::Str(String::new())));
        assert_eq!(read(&variables, "LETTER", &[]), Ok(Value::Char(0)));
    }

    #[test]
    fn initial_values_convert_to_the_declared_type() {
        // DEF INT VAR1=5, DEF REAL GLPAK=17 (corpus), DEF INT N=2.5 rounds to 3.
        let mut variables = Variables::default();
        declare(&mut variables, "VAR1", Type::Int, &[], Init::Value(int(5)));
        declare(
            &mut variables,
            "GLPAK",
            Type::Real,
            &[],
            Init::Value(int(17)),
        );
        declare(
            &mut variables,
            "NN",
            Type::Int,
            &[],
            Init::Value(Value::Real(2.5)),
        );
        assert_eq!(read(&variables, "VAR1", &[]), Ok(int(5)));
        assert_eq!(read(&variables, "GLPAK", &[]), Ok(Value::Real(17.0)));
        assert_eq!(read(&variables, "NN", &[]), Ok(int(3)));
        // A failed initialiser declares nothing.
        let alarm = variables
            .declare(
                "BAD",
                Type::Int,
                &[],
                Init::Value(Value::Str("A".into())),
                span(),
            )
            .unwrap_err();
        assert_eq!(alarm.code, AlarmCode::MacroArithmetic);
        assert!(!variables.is_defined("BAD"));
    }

    #[test]
    fn set_fills_a_two_dimensional_array_with_the_last_index_fastest() {
        // DEF REAL FIELD[2,3]=SET(1,2,3,4): [0,0]=1 [0,1]=2 [0,2]=3 [1,0]=4, the rest 0.
        let mut variables = Variables::default();
        let values = vec![int(1), int(2), int(3), int(4)];
        declare(
            &mut variables,
            "FIELD",
            Type::Real,
            &[2, 3],
            Init::Set(values),
        );
        assert_eq!(read(&variables, "FIELD", &[0, 2]), Ok(Value::Real(3.0)));
        assert_eq!(read(&variables, "FIELD", &[1, 0]), Ok(Value::Real(4.0)));
        assert_eq!(read(&variables, "FIELD", &[1, 1]), Ok(Value::Real(0.0)));
        // Seven values for six elements.
        let seven = vec![int(0); 7];
        let dims = [int(2), int(3)];
        let alarm = variables
            .declare("FIELD2", Type::Real, &dims, Init::Set(seven), span())
            .unwrap_err();
        assert_eq!(alarm.code, AlarmCode::MacroArithmetic);
    }

    #[test]
    fn rep_fills_every_element_of_a_three_dimensional_array() {
        let mut variables = Variables::default();
        declare(
            &mut variables,
            "CUBE",
            Type::Int,
            &[2, 2, 2],
            Init::Rep(int(7)),
        );
        for (i, j, k) in [(0, 0, 0), (1, 0, 1), (1, 1, 1)] {
            assert_eq!(read(&variables, "CUBE", &[i, j, k]), Ok(int(7)));
        }
    }

    #[test]
    fn indices_out_of_range_alarm() {
        let mut variables = Variables::default();
        declare(&mut variables, "ARR", Type::Real, &[5], Init::Default);
        let alarm = read(&variables, "ARR", &[5]).unwrap_err();
        assert_eq!(alarm.code, AlarmCode::BadVariable);
        assert!(alarm.message.contains("out of range 0 to 4"));
        assert!(read(&variables, "ARR", &[-1]).is_err());
        assert!(read(&variables, "ARR", &[1, 1]).is_err());
        // A REAL index is rounded: 3.6 is 4.
        let place = variables.place("ARR", &[Value::Real(3.6)], span()).unwrap();
        variables.set(&place, int(9), span()).unwrap();
        assert_eq!(read(&variables, "ARR", &[4]), Ok(Value::Real(9.0)));
        // The whole array is no value.
        assert_eq!(
            read(&variables, "ARR", &[]).unwrap_err().code,
            AlarmCode::BadVariable
        );
        declare(&mut variables, "ONE", Type::Real, &[], Init::Default);
        assert!(read(&variables, "ONE", &[0]).is_err());
    }

    #[test]
    fn bad_extents_and_dimensions_alarm() {
        let mut variables = Variables::default();
        let four = declare_err(&mut variables, "ARR", Type::Int, &[2, 2, 2, 2]);
        assert_eq!(four.code, AlarmCode::ValueOutOfRange);
        let zero = declare_err(&mut variables, "ARR", Type::Int, &[0]);
        assert_eq!(zero.code, AlarmCode::ValueOutOfRange);
        // 30000 x 3 = 90000 cells, above the 65536 of the store.
        let big = declare_err(&mut variables, "ARR", Type::Int, &[30_000, 3]);
        assert_eq!(big.code, AlarmCode::MacroLimit);
    }

    #[test]
    fn the_store_is_bounded() {
        // Two arrays of 32767 fill 65534 cells; the next three do not fit.
        let mut variables = Variables::default();
        declare(&mut variables, "AA", Type::Int, &[32_767], Init::Default);
        declare(&mut variables, "BB", Type::Int, &[32_767], Init::Default);
        let alarm = declare_err(&mut variables, "CC", Type::Int, &[3]);
        assert_eq!(alarm.code, AlarmCode::MacroLimit);
        let mut variables = Variables::default();
        for _ in 0..MAX_LEVELS - 1 {
            variables.push_level(span()).unwrap();
        }
        let alarm = variables.push_level(span()).unwrap_err();
        assert_eq!(alarm.code, AlarmCode::MacroLimit);
    }

    #[test]
    fn names_follow_the_identifier_rule_and_are_declared_once() {
        // PGsl 15.5: the first two characters are letters or _, at most 31 characters.
        let mut variables = Variables::default();
        declare(&mut variables, "_X_HOME", Type::Real, &[], Init::Default);
        declare(&mut variables, "VAR0", Type::Real, &[], Init::Default);
        for name in ["X", "R1", "1AB", "A1B", "LÄNGE", &"L".repeat(32)] {
            let alarm = declare_err(&mut variables, name, Type::Real, &[]);
            assert_eq!(alarm.code, AlarmCode::BadVariable, "{name}");
        }
        assert!(declare_err(&mut variables, "SIN", Type::Real, &[])
            .message
            .contains("word of the language"));
        let twice = declare_err(&mut variables, "VAR0", Type::Int, &[]);
        assert!(twice.message.contains("already declared"));
    }

    #[test]
    fn strings_keep_their_declared_length() {
        let mut variables = Variables::default();
        declare(&mut variables, "NAME", Type::String(5), &[], Init::Default);
        let place = variables.place("NAME", &[], span()).unwrap();
        variables
            .set(&place, Value::Str("ABCDE".into()), span())
            .unwrap();
        let alarm = variables
            .set(&place, Value::Str("ABCDEF".into()), span())
            .unwrap_err();
        assert!(alarm.message.contains("STRING[5]"));
        assert_eq!(
            read(&variables, "NAME", &[]),
            Ok(Value::Str("ABCDE".into()))
        );
    }

    #[test]
    fn a_subprogram_level_has_its_own_names() {
        // Main: DEF REAL DEPTH=5. The subprogram does not see it, declares its own DEPTH=1;
        // after the return main's DEPTH is 5 again.
        let mut variables = Variables::default();
        declare(
            &mut variables,
            "DEPTH",
            Type::Real,
            &[],
            Init::Value(int(5)),
        );
        variables.push_level(span()).unwrap();
        assert_eq!(variables.depth(), 1);
        assert_eq!(
            read(&variables, "DEPTH", &[]).unwrap_err().code,
            AlarmCode::BadVariable
        );
        declare(
            &mut variables,
            "DEPTH",
            Type::Real,
            &[],
            Init::Value(int(1)),
        );
        assert_eq!(read(&variables, "DEPTH", &[]), Ok(Value::Real(1.0)));
        variables.pop_level();
        assert_eq!(variables.depth(), 0);
        assert_eq!(read(&variables, "DEPTH", &[]), Ok(Value::Real(5.0)));
        // The main level is never popped.
        variables.pop_level();
        assert_eq!(read(&variables, "DEPTH", &[]), Ok(Value::Real(5.0)));
    }

    #[test]
    fn r_parameters_and_globals_are_seen_on_every_level() {
        let mut variables = Variables::default();
        variables
            .declare_global("GUD_FEED", Type::Real, &[], Init::Value(int(100)), span())
            .unwrap();
        variables.push_level(span()).unwrap();
        write(&mut variables, "R10", &[], Value::Real(2.5));
        write(&mut variables, "GUD_FEED", &[], int(200));
        // A local may not take a global's name.
        assert!(declare_err(&mut variables, "GUD_FEED", Type::Int, &[])
            .message
            .contains("already declared"));
        variables.pop_level();
        assert_eq!(read(&variables, "R10", &[]), Ok(Value::Real(2.5)));
        assert_eq!(read(&variables, "GUD_FEED", &[]), Ok(Value::Real(200.0)));
    }

    #[test]
    fn end_of_program_drops_local_data_and_keeps_r_parameters() {
        let mut variables = Variables::default();
        declare(&mut variables, "LOCAL", Type::Int, &[], Init::Default);
        write(&mut variables, "R1", &[], int(4));
        variables.push_level(span()).unwrap();
        variables.end_program();
        assert_eq!(variables.depth(), 0);
        assert!(!variables.is_defined("LOCAL"));
        assert_eq!(read(&variables, "R1", &[]), Ok(Value::Real(4.0)));
    }

    #[test]
    fn var_parameters_alias_the_callers_element_array_and_r_parameter() {
        // Main: DEF REAL ARR[3]. PROC P(VAR REAL ELEM, VAR REAL WHOLE[], VAR REAL RP)
        // called as P(ARR[1], ARR, R10): ELEM=5, WHOLE[2]=7, RP=-1 reach the caller.
        let mut variables = Variables::default();
        declare(&mut variables, "ARR", Type::Real, &[3], Init::Default);
        let element = variables.place("ARR", &[int(1)], span()).unwrap();
        let array = variables.place("ARR", &[], span()).unwrap();
        let r10 = variables.place("R10", &[], span()).unwrap();
        assert_eq!((array.ty(), array.dims()), (Type::Real, &[3][..]));
        assert_eq!((element.ty(), element.dims()), (Type::Real, &[][..]));
        variables.push_level(span()).unwrap();
        let scalar = ParamType {
            ty: Type::Real,
            dims: Vec::new(),
        };
        let open = ParamType {
            ty: Type::Real,
            dims: vec![None],
        };
        variables
            .bind_reference("ELEM", &scalar, element, span())
            .unwrap();
        variables
            .bind_reference("WHOLE", &open, array, span())
            .unwrap();
        variables
            .bind_reference("RP", &scalar, r10, span())
            .unwrap();
        write(&mut variables, "ELEM", &[], int(5));
        write(&mut variables, "WHOLE", &[2], int(7));
        write(&mut variables, "RP", &[], int(-1));
        // The alias of one element is no array: SET from it stops at the element.
        let elem = variables.place("ELEM", &[], span()).unwrap();
        assert!(variables
            .set_list(&elem, vec![int(1), int(2)], span())
            .is_err());
        variables.pop_level();
        assert_eq!(read(&variables, "ARR", &[0]), Ok(Value::Real(0.0)));
        assert_eq!(read(&variables, "ARR", &[1]), Ok(Value::Real(5.0)));
        assert_eq!(read(&variables, "ARR", &[2]), Ok(Value::Real(7.0)));
        assert_eq!(read(&variables, "R10", &[]), Ok(Value::Real(-1.0)));
    }

    #[test]
    fn var_parameters_of_another_type_or_shape_alarm() {
        let mut variables = Variables::default();
        declare(&mut variables, "ARR", Type::Real, &[3], Init::Default);
        declare(&mut variables, "COUNT", Type::Int, &[], Init::Default);
        let array = variables.place("ARR", &[], span()).unwrap();
        let count = variables.place("COUNT", &[], span()).unwrap();
        variables.push_level(span()).unwrap();
        let real = ParamType {
            ty: Type::Real,
            dims: Vec::new(),
        };
        let alarm = variables
            .bind_reference("PP", &real, count, span())
            .unwrap_err();
        assert_eq!(alarm.code, AlarmCode::BadVariable);
        assert!(alarm
            .message
            .contains("VAR PP is REAL, the call passes INT"));
        let four = ParamType {
            ty: Type::Real,
            dims: vec![Some(4)],
        };
        let alarm = variables
            .bind_reference("PP", &four, array, span())
            .unwrap_err();
        assert!(alarm.message.contains("REAL[4]"));
    }

    #[test]
    fn a_place_kept_past_its_level_alarms_instead_of_panicking() {
        let mut variables = Variables::default();
        variables.push_level(span()).unwrap();
        declare(&mut variables, "LOCAL", Type::Int, &[3], Init::Default);
        let place = variables.place("LOCAL", &[int(2)], span()).unwrap();
        variables.pop_level();
        assert!(variables.get(&place, span()).is_err());
        assert!(variables.set(&place, int(1), span()).is_err());
        assert!(variables.fill(&place, int(1), span()).is_err());
    }

    #[test]
    fn value_parameters_are_copies() {
        // PROC P(INT N) called with R1 = 2.4: N is 2; N=9 leaves R1 alone.
        let mut variables = Variables::default();
        write(&mut variables, "R1", &[], Value::Real(2.4));
        let argument = read(&variables, "R1", &[]).unwrap();
        variables.push_level(span()).unwrap();
        variables
            .bind_value("NN", Type::Int, argument, span())
            .unwrap();
        assert_eq!(read(&variables, "NN", &[]), Ok(int(2)));
        write(&mut variables, "NN", &[], int(9));
        variables.pop_level();
        assert_eq!(read(&variables, "R1", &[]), Ok(Value::Real(2.4)));
        assert!(!variables.is_defined("NN"));
    }
}
