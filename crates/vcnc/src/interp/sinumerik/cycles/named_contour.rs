//! The contour a cycle names (CYCLE72's KNAME): a subprogram, or a section of the calling
//! program between two labels (`"START:END"`), read into the plane's lines and arcs.
//!
//! The cycle reads the contour; it does not run it (**choice**, docs/SINUMERIK.md, Path milling):
//! of each block it takes G0/G1 (a line), G2/G3 (an arc, its centre by I J K, incremental from
//! its start, or its radius CR=), G90/G91, and the plane's two axes; values may be expressions
//! and variables. The first block that moves in the plane gives the contour's start (a
//! coordinate it leaves out is where the tool is); each later one an element. Words of the tool
//! axis, feeds, M functions and the compensation's own G codes are left alone; the contour
//! definitions that need the blocks around them (RND, CHF, ANG, polar and CIP moves) and any
//! control structure alarm V020.
//!
//! Never: run a block of the contour, or change the front end's state (its variables are read
//! only).

use super::super::block::number;
use super::super::motion::unit;
use super::super::Sinumerik;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::comp::geometry::{Element, V2};
use crate::interp::kernel::Kernel;
use crate::interp::sinumerik::arcs::centre_from_radius;
use crate::motion::ArcDirection;
use crate::source::Span;
use crate::syntax::sinumerik::{is_header, parse_block, Block, StatementKind};
use std::ops::Range;

/// Contour definitions a contour for a cycle cannot have: they need the blocks around them or
/// a geometry vcnc reads only in the running program.
const NOT_READ: [&str; 14] = [
    "RND", "RNDM", "CHF", "CHR", "ANG", "AR", "AP", "RP", "CT", "CIP", "TURN", "I1", "J1", "K1",
];

/// One element of the contour and the block that gave it.
pub(super) type Piece = (Element, Span);

/// The elements of the contour `name` (a program's name or `START:END`), in the plane in force.
///
/// # Errors
/// The program's loading alarms, [`AlarmCode::SequenceNotFound`] for a label not found,
/// [`AlarmCode::ContourDefinition`] for a contour without elements, V020 for a word or
/// statement the reader does not take, and the alarms of the values and arcs.
pub(super) fn read(
    front: &mut Sinumerik,
    kernel: &Kernel,
    name: &str,
    span: Span,
) -> Result<Vec<Piece>, Alarm> {
    let (program, lines) = locate(front, name, span)?;
    let mut reader = Reader::new(front);
    for index in lines {
        let text = &front.programs[program];
        let Some(line) = text.line(index) else {
            break;
        };
        if is_header(line.bytes) {
            continue;
        }
        let block = parse_block(line.bytes, text.file, line.number, line.base);
        let line_span = text.line_span(index);
        reader.block(front, kernel, &block, line_span)?;
    }
    if reader.pieces.is_empty() {
        return Err(Alarm::error(
            AlarmCode::ContourDefinition,
            span,
            format!("the contour {name} has no element in the plane"),
        )
        .with_help("the contour's first block gives its start, each later block that moves in the plane an element"));
    }
    Ok(reader.pieces)
}

/// The program and the lines of the contour `name`.
fn locate(front: &mut Sinumerik, name: &str, span: Span) -> Result<(usize, Range<usize>), Alarm> {
    let Some((start, end)) = name.split_once(':') else {
        let upper = name.trim().to_ascii_uppercase();
        let program = match front.programs.iter().position(|p| *p.name == *upper) {
            Some(program) => program,
            None => front.load(&upper, span)?.ok_or_else(|| {
                Alarm::error(
                    AlarmCode::ContourDefinition,
                    span,
                    format!("the contour {name} is a standard cycle, not a program"),
                )
            })?,
        };
        return Ok((program, 0..front.programs[program].lines()));
    };
    let program = front.levels.last().map_or(0, |level| level.program);
    front.make_whole(program)?;
    let text = &front.programs[program];
    let find = |label: &str, from: usize| {
        (from..text.lines()).find(|&i| {
            text.line(i).is_some_and(|line| {
                let block = parse_block(line.bytes, text.file, line.number, line.base);
                block
                    .label
                    .is_some_and(|l| l.eq_ignore_ascii_case(label.trim()))
            })
        })
    };
    let not_found = |label: &str| {
        Alarm::error(
            AlarmCode::SequenceNotFound,
            span,
            format!("the contour's label {} is not in the program", label.trim()),
        )
        .with_help("KNAME \"START:END\" names the labels of the contour's first and last block in the calling program")
    };
    let first = find(start, 0).ok_or_else(|| not_found(start))?;
    let last = find(end, first).ok_or_else(|| not_found(end))?;
    Ok((program, first..last + 1))
}

/// How the next block moves.
#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Line,
    Arc(ArcDirection),
}

/// The contour read so far.
struct Reader {
    /// The plane's abscissa and ordinate axes.
    axes: (usize, usize),
    /// The centre words of those axes (G17: I and J).
    centre_words: (&'static str, &'static str),
    unit: f64,
    absolute: bool,
    kind: Kind,
    /// Where the contour is (None before its start).
    at: Option<V2>,
    /// Where the tool is, for a start that leaves a coordinate out.
    tool: V2,
    pieces: Vec<Piece>,
}

/// The words of one block that shape the contour.
#[derive(Default)]
struct Words {
    end: [Option<f64>; 2],
    centre: [Option<f64>; 2],
    radius: Option<(f64, Span)>,
}

impl Reader {
    fn new(front: &Sinumerik) -> Reader {
        let (a, b, _) = front.modal.plane.axes();
        const CENTRES: [&str; 3] = ["I", "J", "K"];
        Reader {
            axes: (a, b),
            centre_words: (CENTRES[a.min(2)], CENTRES[b.min(2)]),
            unit: unit(front),
            absolute: front.modal.absolute,
            kind: Kind::Line,
            at: None,
            tool: V2::new(front.programmed[a], front.programmed[b]),
            pieces: Vec::new(),
        }
    }

    /// Reads `block` (at `span`) into the contour.
    fn block(
        &mut self,
        front: &mut Sinumerik,
        kernel: &Kernel,
        block: &Block,
        span: Span,
    ) -> Result<(), Alarm> {
        if let Some(alarm) = &block.alarm {
            return Err(alarm.clone());
        }
        if let Some(statement) = &block.statement {
            if !matches!(
                statement.kind,
                StatementKind::Procedure(_) | StatementKind::Definition(_)
            ) {
                return Err(not_read("a control structure", span));
            }
        }
        let words = self.words(front, kernel, block)?;
        if words.end == [None, None] && words.centre == [None, None] {
            return Ok(());
        }
        let from = self.at.unwrap_or(self.tool);
        let coordinate = |value: Option<f64>, here: f64, absolute: bool| match value {
            Some(v) if absolute => v,
            Some(v) => here + v,
            None => here,
        };
        let to = V2::new(
            coordinate(words.end[0], from.x, self.absolute),
            coordinate(words.end[1], from.y, self.absolute),
        );
        let Some(start) = self.at.replace(to) else {
            return Ok(());
        };
        let element = match self.kind {
            Kind::Line if start.distance(to) < 1e-9 => return Ok(()),
            Kind::Line => Element::Line { start, end: to },
            Kind::Arc(direction) => {
                let center = match (words.centre, words.radius) {
                    ([None, None], Some((radius, at))) => {
                        centre_from_radius(start, to, radius, direction, front.arc_tolerance, at)?
                    }
                    ([None, None], None) => {
                        return Err(Alarm::error(
                            AlarmCode::ContourDefinition,
                            span,
                            "an arc of the contour needs its centre (I, J, K) or its radius CR=",
                        ))
                    }
                    (centre, _) => V2::new(
                        start.x + centre[0].unwrap_or(0.0),
                        start.y + centre[1].unwrap_or(0.0),
                    ),
                };
                Element::Arc {
                    start,
                    end: to,
                    center,
                    ccw: direction == ArcDirection::CounterClockwise,
                }
            }
        };
        self.pieces.push((element, span));
        Ok(())
    }

    /// The words of `block` that shape the contour; G0-G3, G90 and G91 change the reader's
    /// modes.
    fn words(
        &mut self,
        front: &mut Sinumerik,
        kernel: &Kernel,
        block: &Block,
    ) -> Result<Words, Alarm> {
        let mut words = Words::default();
        for word in &block.words {
            let address = word.address.as_str();
            if NOT_READ.contains(&address) {
                return Err(not_read(address, word.span));
            }
            let slot = match address {
                "G" => {
                    self.g_function(number(front, kernel, word)?);
                    continue;
                }
                "CR" => {
                    words.radius = Some((number(front, kernel, word)? * self.unit, word.span));
                    continue;
                }
                a if a == self.centre_words.0 => &mut words.centre[0],
                a if a == self.centre_words.1 => &mut words.centre[1],
                a => match front.axes.index(a) {
                    Some(axis) if axis == self.axes.0 => &mut words.end[0],
                    Some(axis) if axis == self.axes.1 => &mut words.end[1],
                    _ => continue,
                },
            };
            *slot = Some(number(front, kernel, word)? * self.unit);
        }
        Ok(words)
    }

    fn g_function(&mut self, code: f64) {
        match code as i64 {
            0 | 1 => self.kind = Kind::Line,
            2 => self.kind = Kind::Arc(ArcDirection::Clockwise),
            3 => self.kind = Kind::Arc(ArcDirection::CounterClockwise),
            90 => self.absolute = true,
            91 => self.absolute = false,
            _ => {}
        }
    }
}

/// V020 for `what` in a contour a cycle reads.
fn not_read(what: &str, span: Span) -> Alarm {
    Alarm::error(
        AlarmCode::NotSupportedYet,
        span,
        format!("{what} in a contour for CYCLE72 is not read yet by vcnc"),
    )
    .with_help("write the contour with G1, G2 and G3 moves in the plane (issue 22)")
}
