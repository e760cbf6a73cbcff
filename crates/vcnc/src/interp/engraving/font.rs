//! vcnc's single-stroke engraving font: each printable ASCII character as polylines on a grid
//! 4 units wide and 6 units tall (the capital height), baseline at 0; a few strokes reach below
//! the baseline (`,` `;`) or above the capitals (`$` `|`). Lower-case letters are the capitals
//! at the height of a lower-case letter (small capitals). Drawn for this project.
//!
//! A glyph is written as polylines separated by `;`, each a list of `x,y` points separated by
//! blanks: `"0,0 2,6 4,0; 1,2 3,2"` is an A.

/// The grid's capital height: a character `J` tall is scaled by `J / HEIGHT`.
pub(crate) const HEIGHT: f64 = 6.0;

/// How far one character moves the next along the baseline, in grid units (the glyph's 4 and a
/// gap of 2).
pub(crate) const ADVANCE: f64 = 6.0;

/// The height of a lower-case letter, as a fraction of the capitals'.
const LOWER_CASE: f64 = 0.7;

/// The strokes of `c`, as polylines in grid units; None for a character the font lacks (no
/// strokes at all for a blank).
pub(crate) fn strokes(c: char) -> Option<Vec<Vec<(f64, f64)>>> {
    if c.is_ascii_lowercase() {
        let capital = strokes(c.to_ascii_uppercase())?;
        return Some(
            capital
                .into_iter()
                .map(|line| line.into_iter().map(|(x, y)| (x, y * LOWER_CASE)).collect())
                .collect(),
        );
    }
    let glyph = glyph(c)?;
    Some(
        glyph
            .split(';')
            .map(str::trim)
            .filter(|line| !line.is_empty())
            .map(|line| {
                line.split_whitespace()
                    .filter_map(|point| {
                        let (x, y) = point.split_once(',')?;
                        Some((x.parse().ok()?, y.parse().ok()?))
                    })
                    .collect()
            })
            .collect(),
    )
}

/// The glyph of a character that is not a lower-case letter.
fn glyph(c: char) -> Option<&'static str> {
    Some(match c {
        ' ' => "",
        'A' => "0,0 2,6 4,0; 1,2 3,2",
        'B' => "0,0 0,6 3,6 4,5 4,4 3,3 0,3; 3,3 4,2 4,1 3,0 0,0",
        'C' => "4,5 3,6 1,6 0,5 0,1 1,0 3,0 4,1",
        'D' => "0,0 0,6 3,6 4,5 4,1 3,0 0,0",
        'E' => "4,6 0,6 0,0 4,0; 0,3 3,3",
        'F' => "4,6 0,6 0,0; 0,3 3,3",
        'G' => "4,5 3,6 1,6 0,5 0,1 1,0 3,0 4,1 4,3 2,3",
        'H' => "0,0 0,6; 4,0 4,6; 0,3 4,3",
        'I' => "1,6 3,6; 2,6 2,0; 1,0 3,0",
        'J' => "4,6 4,1 3,0 1,0 0,1",
        'K' => "0,0 0,6; 4,6 0,2; 1,3 4,0",
        'L' => "0,6 0,0 4,0",
        'M' => "0,0 0,6 2,3 4,6 4,0",
        'N' => "0,0 0,6 4,0 4,6",
        'O' => "1,0 0,1 0,5 1,6 3,6 4,5 4,1 3,0 1,0",
        'P' => "0,0 0,6 3,6 4,5 4,4 3,3 0,3",
        'Q' => "1,0 0,1 0,5 1,6 3,6 4,5 4,1 3,0 1,0; 2,2 4,0",
        'R' => "0,0 0,6 3,6 4,5 4,4 3,3 0,3; 2,3 4,0",
        'S' => "4,5 3,6 1,6 0,5 0,4 1,3 3,3 4,2 4,1 3,0 1,0 0,1",
        'T' => "0,6 4,6; 2,6 2,0",
        'U' => "0,6 0,1 1,0 3,0 4,1 4,6",
        'V' => "0,6 2,0 4,6",
        'W' => "0,6 1,0 2,4 3,0 4,6",
        'X' => "0,0 4,6; 0,6 4,0",
        'Y' => "0,6 2,3 4,6; 2,3 2,0",
        'Z' => "0,6 4,6 0,0 4,0",
        '0' => "1,0 0,1 0,5 1,6 3,6 4,5 4,1 3,0 1,0; 0,1 4,5",
        '1' => "1,5 2,6 2,0; 1,0 3,0",
        '2' => "0,5 1,6 3,6 4,5 4,4 0,0 4,0",
        '3' => "0,5 1,6 3,6 4,5 4,4 3,3 1,3; 3,3 4,2 4,1 3,0 1,0 0,1",
        '4' => "3,0 3,6 0,2 4,2",
        '5' => "4,6 0,6 0,3 3,3 4,2 4,1 3,0 1,0 0,1",
        '6' => "4,5 3,6 1,6 0,5 0,1 1,0 3,0 4,1 4,2 3,3 0,3",
        '7' => "0,6 4,6 1,0",
        '8' => "1,3 0,4 0,5 1,6 3,6 4,5 4,4 3,3 1,3 0,2 0,1 1,0 3,0 4,1 4,2 3,3",
        '9' => "4,3 1,3 0,4 0,5 1,6 3,6 4,5 4,1 3,0 1,0 0,1",
        '!' => "2,6 2,2; 2,0.5 2,0",
        '"' => "1,6 1,4; 3,6 3,4",
        '#' => "1,0 1,6; 3,0 3,6; 0,2 4,2; 0,4 4,4",
        '$' => "4,5 3,6 1,6 0,5 0,4 1,3 3,3 4,2 4,1 3,0 1,0 0,1; 2,6.5 2,-0.5",
        '%' => "0,0 4,6; 0,5 1,5 1,6 0,6 0,5; 3,0 4,0 4,1 3,1 3,0",
        '&' => "4,0 1,4 1,5 2,6 3,5 3,4 0,2 0,1 1,0 2,0 4,2",
        '\'' => "2,6 2,4",
        '(' => "3,6 1,4 1,2 3,0",
        ')' => "1,6 3,4 3,2 1,0",
        '*' => "2,1 2,5; 0,2 4,4; 0,4 4,2",
        '+' => "0,3 4,3; 2,1 2,5",
        ',' => "2,1 2,0 1,-1",
        '-' => "1,3 3,3",
        '.' => "2,0.5 2,0",
        '/' => "0,0 4,6",
        ':' => "2,4.5 2,4; 2,1.5 2,1",
        ';' => "2,4.5 2,4; 2,1 2,0 1,-1",
        '<' => "4,5 0,3 4,1",
        '=' => "0,2 4,2; 0,4 4,4",
        '>' => "0,5 4,3 0,1",
        '?' => "0,5 1,6 3,6 4,5 4,4 2,3 2,2; 2,0.5 2,0",
        '@' => "3,2 1,2 1,4 3,4 3,1 4,1 4,5 3,6 1,6 0,5 0,1 1,0 4,0",
        '[' => "3,6 1,6 1,0 3,0",
        '\\' => "0,6 4,0",
        ']' => "1,6 3,6 3,0 1,0",
        '^' => "1,4 2,6 3,4",
        '_' => "0,0 4,0",
        '`' => "1,6 2,4",
        '{' => "3,6 2,5 2,4 1,3 2,2 2,1 3,0",
        '|' => "2,6.5 2,-0.5",
        '}' => "1,6 2,5 2,4 3,3 2,2 2,1 1,0",
        '~' => "0,3 1,4 3,2 4,3",
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every printable ASCII character has a glyph whose polylines have two points or more,
    /// inside the cell (a little below and above it for the few that reach out).
    #[test]
    fn every_printable_character_has_strokes_in_its_cell() {
        for code in 32u8..=126 {
            let c = char::from(code);
            let lines = strokes(c).unwrap_or_else(|| panic!("no glyph for {c:?}"));
            assert_eq!(lines.is_empty(), c == ' ', "{c:?}");
            for line in &lines {
                assert!(line.len() >= 2, "{c:?}: {line:?}");
                for &(x, y) in line {
                    assert!((0.0..=4.0).contains(&x), "{c:?}: x {x}");
                    assert!((-1.0..=6.5).contains(&y), "{c:?}: y {y}");
                }
            }
        }
        assert!(strokes('\u{e9}').is_none());
    }
}
