//! The tools: the offset memory (the H and D registers), the H and D numbers in force, the tool
//! selected (T) and the one in the spindle (M06).
//!
//! A part of the executor with private fields: every write to an offset goes through
//! [`ToolMemory::write`], which refreshes the length of the active H number itself, so the
//! value a move reads is right by construction. Machine-file offsets are the power-on contents;
//! G10 L10-L13 and the tool offset macro variables change them while a program runs.

use crate::machine::ToolOffset;
use crate::motion::ToolGeometry;
use std::collections::BTreeMap;

/// The offset registers, the numbers in force and the tools selected and in the spindle.
#[derive(Clone, Debug)]
pub(crate) struct ToolMemory {
    offsets: BTreeMap<u32, ToolOffset>,
    /// The D number of cutter radius compensation.
    radius_number: u32,
    /// The tool the last T word selected.
    selected: u32,
    /// The tool the last M06 put in the spindle.
    in_spindle: u32,
    /// The H number of the active length compensation.
    length_number: u32,
    /// Geometry plus wear of `length_number`'s register: every move of Z reads it, and a
    /// look-up in the map would cost that move more than the rest of its arithmetic.
    length: f64,
}

impl ToolMemory {
    /// The memory at power-on: the machine file's offsets, H0 selected.
    pub(crate) fn new(offsets: BTreeMap<u32, ToolOffset>) -> ToolMemory {
        let mut memory = ToolMemory {
            offsets,
            radius_number: 0,
            selected: 0,
            in_spindle: 0,
            length_number: 0,
            length: 0.0,
        };
        memory.length = memory.length_of(0);
        memory
    }

    /// Register `number`, if it was ever set.
    pub(crate) fn get(&self, number: u32) -> Option<&ToolOffset> {
        self.offsets.get(&number)
    }

    /// Geometry plus wear of register `number`'s length (0 for a register never set).
    fn length_of(&self, number: u32) -> f64 {
        self.get(number).map_or(0.0, |t| t.length + t.length_wear)
    }

    /// Geometry plus wear of register `number`'s radius (0 for a register never set).
    pub(crate) fn radius(&self, number: u32) -> f64 {
        self.get(number).map_or(0.0, |t| t.radius + t.radius_wear)
    }

    /// Changes register `number` (created empty if it was never set).
    pub(crate) fn write(&mut self, number: u32, change: impl FnOnce(&mut ToolOffset)) {
        let offset = self.offsets.entry(number).or_default();
        offset.number = number;
        change(offset);
        if number == self.length_number {
            self.length = self.length_of(number);
        }
    }

    /// The H number of the active length compensation.
    pub(crate) fn length_number(&self) -> u32 {
        self.length_number
    }

    /// Selects the register of length compensation (H).
    pub(crate) fn select_length(&mut self, number: u32) {
        self.length_number = number;
        self.length = self.length_of(number);
    }

    /// The D number of cutter radius compensation.
    pub(crate) fn radius_number(&self) -> u32 {
        self.radius_number
    }

    /// Selects the register of cutter radius compensation (D).
    pub(crate) fn select_radius(&mut self, number: u32) {
        self.radius_number = number;
    }

    /// Geometry plus wear of the radius register in force (D), as written there.
    pub(crate) fn radius_offset(&self) -> f64 {
        self.radius(self.radius_number)
    }

    /// The tool the last T word selected.
    pub(crate) fn selected(&self) -> u32 {
        self.selected
    }

    /// A T word: the tool to put in the spindle at the next M06.
    pub(crate) fn select(&mut self, tool: u32) {
        self.selected = tool;
    }

    /// The tool in the spindle.
    pub(crate) fn in_spindle(&self) -> u32 {
        self.in_spindle
    }

    /// M06: the selected tool goes into the spindle; its number.
    pub(crate) fn change(&mut self) -> u32 {
        self.in_spindle = self.selected;
        self.in_spindle
    }

    /// The offsets of register `number` as a tool's geometry (None for a register never set);
    /// `diameters` when the radius registers hold diameters.
    pub(crate) fn geometry(&self, number: u32, diameters: bool) -> Option<ToolGeometry> {
        let offset = self.get(number)?;
        let radius = offset.radius + offset.radius_wear;
        Some(ToolGeometry {
            length: offset.length + offset.length_wear,
            radius: if diameters { radius / 2.0 } else { radius },
        })
    }

    /// Geometry plus wear of the selected length register, mm.
    #[inline(always)]
    pub(crate) fn length(&self) -> f64 {
        self.length
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn memory() -> ToolMemory {
        let mut offsets = BTreeMap::new();
        offsets.insert(
            1,
            ToolOffset {
                number: 1,
                length: 100.0,
                length_wear: -0.5,
                radius: 5.0,
                radius_wear: 0.1,
            },
        );
        ToolMemory::new(offsets)
    }

    #[test]
    fn the_selected_length_follows_every_write_to_its_register() {
        let mut tools = memory();
        assert_eq!(tools.length(), 0.0);
        tools.select_length(1);
        assert_eq!(tools.length(), 99.5);
        tools.write(1, |t| t.length_wear = 0.25);
        assert_eq!(tools.length(), 100.25);
        tools.write(2, |t| t.length = 50.0);
        assert_eq!(tools.length(), 100.25);
        tools.select_length(2);
        assert_eq!(tools.length(), 50.0);
        assert_eq!(tools.get(2).map(|t| t.number), Some(2));
    }

    #[test]
    fn a_register_never_set_has_no_length_or_radius() {
        let tools = memory();
        assert_eq!(tools.radius(7), 0.0);
        assert_eq!(tools.radius(1), 5.1);
    }
}
