//! The axes of a position: slots in position arrays, and the machine's names and kinds for them.
//!
//! Shared by the machine (its axes' limits) and the motion stream (its positions), so that
//! neither depends on the other for it. A position is a fixed array of [`AXES`] slots: the
//! three geometry axes X Y Z, then three more that a machine file names (`A B C` by default,
//! or `U V W`, or SINUMERIK names such as `C1`). Fixed arrays keep the common X Y Z A B C as
//! fast as before; an [`AxisLayout`] says what each slot is called and how it moves.

/// An axis: a slot of the position arrays.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Axis(u8);

/// Number of axes in a position array: three geometry axes and three more.
pub const AXES: usize = 6;

impl Axis {
    /// The first geometry axis.
    pub const X: Axis = Axis(0);
    /// The second geometry axis.
    pub const Y: Axis = Axis(1);
    /// The third geometry axis (the tool axis under G17).
    pub const Z: Axis = Axis(2);
    /// The axis named A when the machine has one: A, B and C always take the 4th, 5th and
    /// 6th slots; other names (U V W, C1) take the slots of the three the machine lacks.
    pub const A: Axis = Axis(3);
    /// The axis named B when the machine has one (see [`Axis::A`]).
    pub const B: Axis = Axis(4);
    /// The axis named C when the machine has one (see [`Axis::A`]).
    pub const C: Axis = Axis(5);

    /// All axes in array order.
    pub const ALL: [Axis; AXES] = [Axis(0), Axis(1), Axis(2), Axis(3), Axis(4), Axis(5)];

    /// The axis of slot `index`, if there is one.
    pub const fn from_index(index: usize) -> Option<Axis> {
        if index < AXES {
            Some(Axis(index as u8))
        } else {
            None
        }
    }

    /// Index into position arrays.
    pub const fn index(self) -> usize {
        self.0 as usize
    }

    /// True for X, Y and Z, the axes of the planes, arcs and frames.
    pub const fn is_geometry(self) -> bool {
        self.0 < 3
    }
}

/// How an axis moves: a length in mm or an angle in degrees.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum AxisKind {
    /// A linear axis (mm; converted by G20/G70).
    Linear,
    /// A rotary axis (degrees; never converted by the unit of length).
    Rotary,
}

/// Longest axis name, in bytes (SINUMERIK's machine data allow eight characters).
const NAME_LENGTH: usize = 8;

/// An axis name as the programs write it: upper case, 1 to 8 letters, digits or `_`, starting
/// with a letter. Kept inline, so a layout is `Copy`.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct AxisName {
    bytes: [u8; NAME_LENGTH],
    len: u8,
}

impl AxisName {
    /// The name `text` in upper case, if it is a valid axis name.
    pub fn new(text: &str) -> Option<AxisName> {
        let bytes = text.as_bytes();
        let valid = (1..=NAME_LENGTH).contains(&bytes.len())
            && bytes[0].is_ascii_alphabetic()
            && bytes
                .iter()
                .all(|b| b.is_ascii_alphanumeric() || *b == b'_');
        if !valid {
            return None;
        }
        let mut name = AxisName {
            bytes: [0; NAME_LENGTH],
            len: bytes.len() as u8,
        };
        for (to, from) in name.bytes.iter_mut().zip(bytes) {
            *to = from.to_ascii_uppercase();
        }
        Some(name)
    }

    const fn letter(letter: u8) -> AxisName {
        let mut bytes = [0; NAME_LENGTH];
        bytes[0] = letter;
        AxisName { bytes, len: 1 }
    }

    /// The name, upper case.
    pub fn as_str(&self) -> &str {
        // Built from ASCII only (checked in `new`).
        std::str::from_utf8(&self.bytes[..usize::from(self.len)]).unwrap_or("?")
    }

    /// The name's letter when it is one letter (the only names ISO programs can address).
    pub fn single_letter(&self) -> Option<u8> {
        (self.len == 1).then_some(self.bytes[0])
    }
}

impl std::fmt::Debug for AxisName {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl std::fmt::Display for AxisName {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// What a machine calls each slot of the position arrays and how each moves. The default is
/// X Y Z (linear) and A B C (rotary); a machine file names the three slots after the geometry
/// axes (see `Machine::from_toml`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AxisLayout {
    names: [AxisName; AXES],
    kinds: [AxisKind; AXES],
}

impl Default for AxisLayout {
    fn default() -> AxisLayout {
        use AxisKind::{Linear, Rotary};
        AxisLayout {
            names: [b'X', b'Y', b'Z', b'A', b'B', b'C'].map(AxisName::letter),
            kinds: [Linear, Linear, Linear, Rotary, Rotary, Rotary],
        }
    }
}

impl AxisLayout {
    /// The kind a name has unless the machine file says otherwise: rotary for A, B and C (and
    /// SINUMERIK's A1, C2 ...), linear for every other name.
    pub fn default_kind(name: &AxisName) -> AxisKind {
        match name.bytes[0] {
            b'A' | b'B' | b'C' => AxisKind::Rotary,
            _ => AxisKind::Linear,
        }
    }

    /// The default layout with `name` of `kind` in slot `axis` (not a geometry axis).
    pub(crate) fn with(mut self, axis: Axis, name: AxisName, kind: AxisKind) -> AxisLayout {
        debug_assert!(!axis.is_geometry());
        self.names[axis.index()] = name;
        self.kinds[axis.index()] = kind;
        self
    }

    /// The name of `axis`.
    pub fn name(&self, axis: Axis) -> AxisName {
        self.names[axis.index()]
    }

    /// How `axis` moves.
    pub fn kind(&self, axis: Axis) -> AxisKind {
        self.kinds[axis.index()]
    }

    /// True when `axis` is rotary.
    pub fn is_rotary(&self, axis: Axis) -> bool {
        self.kinds[axis.index()] == AxisKind::Rotary
    }

    /// Rotary or not, by slot.
    pub fn rotary_mask(&self) -> [bool; AXES] {
        self.kinds.map(|kind| kind == AxisKind::Rotary)
    }

    /// The axis a name (any case) calls, if the layout has it.
    pub fn by_name(&self, name: &str) -> Option<Axis> {
        let name = AxisName::new(name)?;
        Axis::ALL
            .into_iter()
            .find(|a| self.names[a.index()] == name)
    }

    /// The axis an ISO address letter (upper case) calls, if the layout has it.
    pub fn by_letter(&self, letter: u8) -> Option<Axis> {
        Axis::ALL
            .into_iter()
            .find(|a| self.names[a.index()].single_letter() == Some(letter))
    }

    /// The axis's address letter in ISO programs and messages: its name's first letter for
    /// names of several characters (which ISO programs cannot address).
    pub fn letter(&self, axis: Axis) -> u8 {
        self.names[axis.index()].bytes[0]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_layout_is_xyz_and_rotary_abc() {
        let layout = AxisLayout::default();
        assert_eq!(layout.by_letter(b'C'), Some(Axis::ALL[5]));
        assert_eq!(layout.by_name("b"), Some(Axis::ALL[4]));
        assert!(layout.is_rotary(Axis::ALL[3]) && !layout.is_rotary(Axis::Z));
        assert_eq!(layout.by_letter(b'U'), None);
    }

    #[test]
    fn names_are_upper_case_letters_digits_and_underscores() {
        assert_eq!(
            AxisName::new("c1").map(|n| n.to_string()),
            Some("C1".into())
        );
        for bad in ["", "1A", "A-B", "TOOLONGNAME", "Ä"] {
            assert_eq!(AxisName::new(bad), None, "{bad}");
        }
        let name = AxisName::new("U").unwrap();
        assert_eq!(AxisLayout::default_kind(&name), AxisKind::Linear);
        assert_eq!(
            AxisLayout::default_kind(&AxisName::new("A2").unwrap()),
            AxisKind::Rotary
        );
    }

    #[test]
    fn a_renamed_slot_answers_to_its_new_name_only() {
        let u = AxisName::new("U").unwrap();
        let layout = AxisLayout::default().with(Axis::ALL[3], u, AxisKind::Linear);
        assert_eq!(layout.by_letter(b'U'), Some(Axis::ALL[3]));
        assert_eq!(layout.by_letter(b'A'), None);
        assert!(!layout.is_rotary(Axis::ALL[3]));
        assert_eq!(layout.letter(Axis::ALL[3]), b'U');
    }
}
