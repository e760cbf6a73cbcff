//! Tools of a SINUMERIK program: T (by number or name), M6, D, and the tool's offset vector:
//! lengths L1-L3 by the plane (G17: L1 on Z, L2 on Y, L3 on X; G18: L1 on Y, L2 on X, L3 on Z;
//! G19: L1 on X, L2 on Z, L3 on Y) plus TOFFL (along L1-L3) or TOFF (along X, Y, Z)
//! (docs/SINUMERIK.md 7; PGsl 5.6-5.8).
//!
//! Never: apply a length the program did not activate (D0 and no tool apply none).

use super::block::Words;
use super::Sinumerik;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::kernel::{Kernel, Origin};
use crate::motion::{Plane, SegmentKind, ToolGeometry};
use crate::syntax::sinumerik::{ExprKind, Value, Word};

/// The programmed offsets of the tool's lengths: TOFFL along L1-L3, or TOFF along the geometry
/// axes; writing one kind clears the other (PGsl 5.8, L1572-1582).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) enum Offsets {
    #[default]
    None,
    /// TOFFL[1..3].
    Lengths([f64; 3]),
    /// TOFF[X], TOFF[Y], TOFF[Z].
    Axes([f64; 3]),
}

/// One TOFFL or TOFF word: which component it sets, and its value.
#[derive(Clone, Copy, Debug)]
pub(super) struct OffsetWord {
    /// Along a length (L1-L3, 0-based) or along an axis (X, Y, Z).
    along_length: bool,
    index: usize,
    value: f64,
}

/// Reads `TOFFL=v`, `TOFFL[n]=v`, `TOFF[axis]=v` (TOFFR is the radius: issue 22).
pub(super) fn offset_word(
    front: &mut Sinumerik,
    kernel: &Kernel,
    word: &Word,
    into: &mut Vec<OffsetWord>,
) -> Result<(), Alarm> {
    let name = &*word.address;
    if name == "TOFFR" {
        return Err(Alarm::error(
            AlarmCode::NotSupportedYet,
            word.span,
            "TOFFR, the radius offset, is not run yet (planned: issue 22, with the radius compensation)",
        ));
    }
    let (index, expr) = match &word.value {
        Value::Expression(expr) if name == "TOFFL" => (None, expr),
        Value::Indexed(indices, Some(expr)) if indices.len() == 1 => (Some(&indices[0]), expr),
        _ => {
            return Err(Alarm::error(
                AlarmCode::MacroSyntax,
                word.span,
                format!("{name} takes a value: TOFFL=1, TOFFL[2]=1, TOFF[Z]=1"),
            ))
        }
    };
    let value = front.value(kernel, expr)? * super::motion::unit(front);
    let slot = match (name, index) {
        ("TOFFL", None) => 0,
        ("TOFFL", Some(index)) => {
            let n = front.value(kernel, index)?;
            if !(1.0..=3.0).contains(&n) || n.fract() != 0.0 {
                return Err(Alarm::error(
                    AlarmCode::ValueOutOfRange,
                    index.span,
                    "TOFFL[n] takes the length 1, 2 or 3",
                ));
            }
            n as usize - 1
        }
        (_, Some(index)) => match &index.kind {
            ExprKind::Name(axis) if matches!(&**axis, "X" | "Y" | "Z") => {
                (axis.as_bytes()[0] - b'X') as usize
            }
            _ => {
                return Err(Alarm::error(
                    AlarmCode::WordNotAllowed,
                    index.span,
                    "TOFF[axis] takes a geometry axis: X, Y or Z",
                ))
            }
        },
        (_, None) => unreachable!("TOFF without an index is refused above"),
    };
    into.push(OffsetWord {
        along_length: name == "TOFFL",
        index: slot,
        value,
    });
    Ok(())
}

/// The axis (X Y Z index) each of L1, L2, L3 acts along in `plane`, for a milling tool.
fn length_axes(plane: Plane) -> [usize; 3] {
    match plane {
        Plane::Xy => [2, 1, 0],
        Plane::Zx => [1, 0, 2],
        Plane::Yz => [0, 2, 1],
    }
}

/// The tool's offset vector now, into the kernel: the edge's lengths and the programmed offsets.
pub(super) fn apply_length(front: &mut Sinumerik, kernel: &mut Kernel) {
    let axes = length_axes(front.modal.plane);
    let mut lengths = front
        .edge()
        .map_or([0.0; 3], |e| [e.length, e.length2, e.length3]);
    let mut vector = [0.0; 3];
    if let Offsets::Lengths(extra) = front.tool_offsets {
        for (l, e) in lengths.iter_mut().zip(extra) {
            *l += e;
        }
    }
    for (l, axis) in lengths.into_iter().zip(axes) {
        vector[axis] += l;
    }
    if let Offsets::Axes(extra) = front.tool_offsets {
        for (v, e) in vector.iter_mut().zip(extra) {
            *v += e;
        }
    }
    kernel.set_tool_vector(vector);
}

/// T, M6, D in that order whatever their written order (docs/SINUMERIK.md 3.2 step 8).
pub(super) fn change(
    front: &mut Sinumerik,
    kernel: &mut Kernel,
    words: &Words<'_>,
    origin: Origin,
) -> Result<(), Alarm> {
    let change = words.m.iter().any(|&(code, _)| code == 6);
    if let Some((t, _)) = words.tool {
        front.tool.selected = Some(t);
        kernel.event(SegmentKind::ToolSelect { tool: t }, origin);
    }
    let changing = change || (words.tool.is_some() && front.settings.t_changes_tool);
    if changing {
        let Some(t) = front.tool.selected else {
            return Err(Alarm::error(
                AlarmCode::WordNotAllowed,
                origin.span,
                "M6 without a tool selected (T)",
            )
            .with_help("select the tool with T before M6"));
        };
        front.tool.in_spindle = Some(t);
        super::toolholder::load(front, t);
        // A change activates an edge of the new tool unless the block says D (MD20270: D1
        // by default; -2 keeps the old tool's offset until a D, ex. A-26).
        if words.edge.is_none() {
            match front.settings.cutting_edge_default {
                -2 => {}
                -1 => front.tool.offset_tool = Some(t),
                n => {
                    front.tool.edge = n.max(0) as u32;
                    front.tool.offset_tool = Some(t);
                }
            }
        }
        let geometry = front
            .tools
            .iter()
            .find(|e| e.t == t && e.d == 1)
            .map(|e| ToolGeometry {
                length: e.length,
                radius: e.radius,
            });
        let shape = kernel.state().setup.machine().tool_shapes.get(t);
        kernel.event(
            SegmentKind::ToolChange {
                tool: t,
                geometry,
                shape,
            },
            origin,
        );
    }
    if let Some((d, span)) = words.edge {
        front.tool.edge = d;
        front.tool.offset_tool = front.tool.in_spindle;
        // An edge of no tool gives no offset; said once (docs/SINUMERIK.md 9).
        if d != 0
            && front.tool.in_spindle.is_none()
            && front.noted.insert("D without a tool".into())
        {
            kernel.warn(
                Alarm::warning(
                    AlarmCode::OffsetNumberOutOfRange,
                    span,
                    format!("D{d} with no tool in the spindle: no length or radius applies"),
                )
                .with_help("change the tool in (T and M6) before activating its edge"),
            );
        }
    }
    for offset in &words.offsets {
        let mut values = match (front.tool_offsets, offset.along_length) {
            (Offsets::Lengths(v), true) | (Offsets::Axes(v), false) => v,
            _ => [0.0; 3],
        };
        values[offset.index] = offset.value;
        front.tool_offsets = if offset.along_length {
            Offsets::Lengths(values)
        } else {
            Offsets::Axes(values)
        };
    }
    if changing || words.edge.is_some() || !words.offsets.is_empty() {
        apply_length(front, kernel);
    }
    Ok(())
}
