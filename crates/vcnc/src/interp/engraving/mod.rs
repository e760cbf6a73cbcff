//! Haas G47 text engraving (the Haas mill manual, "G47 Text Engraving"): one block engraves a
//! line of text in the control's single-stroke font.
//!
//! `G47 P_ (TEXT) X_ Y_ I_ J_ R_ Z_ F_ E_`: P0 engraves the block's comment, P32-P126 the one
//! ASCII character of that code; X Y the lower left corner of the first character (the current
//! position without them), I the angle of the baseline in degrees (0), J the height of a
//! capital (1 inch), R the return plane and Z the depth (both the current Z without them; in
//! G91, R from the current Z and Z from R), F the engraving feed, E the plunge feed (F without
//! it). The moves: a rapid to X Y, a rapid to R, then for each stroke a rapid to its start, a
//! plunge to Z at E, the stroke at F and a rapid back to R, where the tool stays.
//!
//! Where the manual is silent (docs/DEVIATIONS.md): the font is vcnc's own (`font.rs`), since
//! the control's is compiled into it; its characters are two thirds of J wide and one J apart.
//! P1 engraves the serial number of #599 with as many digits as its comment has `#`
//! (`(####)`: 0042), then counts #599 on (the macro layer does both, `serial_text`).

mod font;

use super::decode::{Command, Value};
use super::exec::Executor;
use super::modal::DistanceMode;
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::machine::Axis;
use crate::motion::{Feed, Plane, SegmentKind};

/// The height of a capital without J: one inch.
const DEFAULT_HEIGHT_MM: f64 = 25.4;

/// Runs a G47 block.
///
/// # Errors
/// No or a bad P, P0 without a comment, a character the font lacks, not in G17, a J not above
/// zero, no feed.
pub(crate) fn g47(exec: &mut Executor, cmd: &Command, out: &mut Output) -> Result<(), Alarm> {
    let refuse = |span, message: String| Alarm::error(AlarmCode::Engraving, span, message);
    let text = text(cmd)?;
    if exec.modal.plane != Plane::Xy {
        return Err(refuse(
            cmd.span,
            "text engraving cuts in the X-Y plane (G17)".into(),
        ));
    }
    let feed = exec.cutting_feed(cmd)?;
    let plunge = match cmd.word(b'E') {
        Some(e) if e.number.value > 0.0 => Feed::PerMinute(exec.length(&e)),
        Some(e) => {
            return Err(refuse(
                e.span,
                "E, the plunge feed, must be above zero".into(),
            ))
        }
        None => feed,
    };
    let height = match cmd.word(b'J') {
        Some(j) if j.number.value > 0.0 => exec.length(&j),
        Some(j) => {
            return Err(refuse(
                j.span,
                "J, the text height, must be above zero".into(),
            ))
        }
        None => DEFAULT_HEIGHT_MM,
    };
    let degrees = cmd.word(b'I').map_or(0.0, |i| i.number.value);
    let (sin, cos) = super::frames::sin_cos_degrees(degrees);

    let here = exec.kernel.program_position();
    let incremental = exec.modal.distance == DistanceMode::Incremental;
    let place = |from: f64, word: Option<Value>| match word {
        Some(v) if incremental => from + exec.length(&v),
        Some(v) => exec.length(&v),
        None => from,
    };
    let start_x = place(here[0], cmd.axis(Axis::X.index()));
    let start_y = place(here[1], cmd.axis(Axis::Y.index()));
    let r = place(here[2], cmd.word(b'R'));
    let z = place(r, cmd.axis(Axis::Z.index()));
    let z = if incremental || cmd.axis(Axis::Z.index()).is_some() {
        z
    } else {
        here[2]
    };

    let scale = height / font::HEIGHT;
    let mut strokes = Vec::new();
    for (k, c) in text.chars().enumerate() {
        let lines = font::strokes(c).ok_or_else(|| {
            refuse(
                cmd.span,
                format!("the engraving font has no character {c:?} (printable ASCII only)"),
            )
        })?;
        let cell = k as f64 * font::ADVANCE;
        for line in lines {
            strokes.push(
                line.into_iter()
                    .map(|(gx, gy)| {
                        let (lx, ly) = ((cell + gx) * scale, gy * scale);
                        (start_x + lx * cos - ly * sin, start_y + lx * sin + ly * cos)
                    })
                    .collect::<Vec<_>>(),
            );
        }
    }

    let mut point = here;
    (point[0], point[1]) = (start_x, start_y);
    go(exec, cmd, &point, false, None, out)?;
    point[2] = r;
    go(exec, cmd, &point, true, None, out)?;
    for stroke in strokes {
        let Some(&(x0, y0)) = stroke.first() else {
            continue;
        };
        (point[0], point[1]) = (x0, y0);
        go(exec, cmd, &point, false, None, out)?;
        point[2] = z;
        go(exec, cmd, &point, true, Some(plunge), out)?;
        for &(x, y) in &stroke[1..] {
            (point[0], point[1]) = (x, y);
            go(exec, cmd, &point, false, Some(feed), out)?;
        }
        point[2] = r;
        go(exec, cmd, &point, true, None, out)?;
    }
    Ok(())
}

/// A move to `point` (program coordinates): a rapid, or a cutting line at `feed`; a move that
/// goes nowhere (the start of a dot) is left out.
fn go(
    exec: &mut Executor,
    cmd: &Command,
    point: &[f64; 6],
    moves_z: bool,
    feed: Option<Feed>,
    out: &mut Output,
) -> Result<(), Alarm> {
    let to = exec.machine_target(point, moves_z);
    if to == exec.kernel.position {
        return Ok(());
    }
    match feed {
        None => exec.rapid_to(to, cmd, out),
        Some(feed) => {
            let motion = exec.move_to(to, cmd, out)?;
            out.push(cmd, SegmentKind::Line { motion, feed });
            Ok(())
        }
    }
}

/// The serial number `value` (#599) as G47 P1 engraves it: as many digits as `comment` has
/// `#`, zeros in front.
///
/// # Errors
/// A comment without `#`, or a value that is not a whole number from 0 that fits them.
pub(crate) fn serial_text(
    comment: &str,
    value: Option<f64>,
    span: crate::source::Span,
) -> Result<String, Alarm> {
    let digits = comment.chars().filter(|&c| c == '#').count();
    let value = value.unwrap_or(0.0);
    let fits = (1..=9).contains(&digits)
        && value >= 0.0
        && value.fract() == 0.0
        && value < 10f64.powi(digits as i32);
    if !fits {
        return Err(Alarm::error(
            AlarmCode::Engraving,
            span,
            format!(
                "G47 P1 engraves #599 ({value}) in as many digits as its comment has # (1 to 9): \
                 {digits} here"
            ),
        ));
    }
    Ok(format!("{:0digits$}", value as u64))
}

/// The text P asks for: the comment (P0), the serial number put in its place (P1), or one
/// character (P32-P126).
fn text(cmd: &Command) -> Result<String, Alarm> {
    let refuse = |span, message: &str| Alarm::error(AlarmCode::Engraving, span, message);
    let Some(p) = cmd.p() else {
        return Err(refuse(
            cmd.span,
            "G47 needs P: 0 for the comment's text, 32-126 for one character",
        ));
    };
    match p.number.whole() {
        // The macro layer put the serial number of #599 in place of the comment.
        Some(0 | 1) => cmd.text().map(str::to_string).ok_or_else(|| {
            refuse(
                p.span,
                "G47 P0 engraves the block's comment: give the text as (TEXT)",
            )
        }),
        Some(code @ 32..=126) => Ok(char::from(code as u8).to_string()),
        _ => Err(refuse(
            p.span,
            "P is 0 (the comment), 1 (a serial number) or an ASCII code from 32 to 126",
        )),
    }
}
