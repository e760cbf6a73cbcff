//! The axes of a position: their order in position arrays, letters and kinds.
//!
//! Shared by the machine (its axes' limits) and the motion stream (its positions), so that
//! neither depends on the other for it. Axes are a fixed set of six today; a machine's own axis
//! names (U V W, SINUMERIK's) are to come.

/// The axes vcnc knows, in the order of position arrays.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Axis {
    /// X.
    X,
    /// Y.
    Y,
    /// Z.
    Z,
    /// A, rotary about X.
    A,
    /// B, rotary about Y.
    B,
    /// C, rotary about Z.
    C,
}

/// Number of axes in a position array.
pub const AXES: usize = 6;

impl Axis {
    /// All axes in array order.
    pub const ALL: [Axis; AXES] = [Axis::X, Axis::Y, Axis::Z, Axis::A, Axis::B, Axis::C];

    /// Index into position arrays.
    pub const fn index(self) -> usize {
        self as usize
    }

    /// The address letter.
    pub const fn letter(self) -> u8 {
        b"XYZABC"[self.index()]
    }

    /// The axis of an address letter.
    pub fn from_letter(letter: u8) -> Option<Axis> {
        match letter.to_ascii_uppercase() {
            b'X' => Some(Axis::X),
            b'Y' => Some(Axis::Y),
            b'Z' => Some(Axis::Z),
            b'A' => Some(Axis::A),
            b'B' => Some(Axis::B),
            b'C' => Some(Axis::C),
            _ => None,
        }
    }

    /// True for A, B and C.
    pub fn is_rotary(self) -> bool {
        matches!(self, Axis::A | Axis::B | Axis::C)
    }
}
