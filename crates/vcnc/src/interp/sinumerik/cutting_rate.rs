//! The reference axis of the constant cutting rate (PGsl 6.3, seed 002 L2127-2328): SCC[axis]
//! makes a geometry axis the one whose position gives the diameter of G96/G961; without it,
//! the transverse axis (MD20100, vcnc's X: `diameter.rs`).
//!
//! The speed is n = S * 1000 / (2 pi r), S in m/min and r the radius the reference axis's
//! position stands at (the tool's distance from the turning centre: a diameter-programmed axis
//! is held in radius, so r is its position as the machine moves it). `spindle.rs` clamps n by
//! LIMS, G26 and the machine's top speed.
//!
//! The attribute belongs to a geometry axis, not a channel axis (L2288-2295): after GEOAX the
//! geometry axis's new channel axis gives the position; with none behind it the speed stays
//! as it is (as under G97). SCC names a geometry axis (X, Y, Z) or the channel axis behind one
//! now (SCC[X1] while X1 is the first geometry axis); a channel axis that is not a geometry
//! axis is an alarm (L2199-2200, the manual's case 3, L2315-2318).
//!
//! **Choices**: r is the work position (the frames between the WCS and the settable zero
//! system, which the control also considers, L2261-2264, are left out: the programmable
//! frame's SCALE would change it); the speed follows the block's end point, once per block (the
//! control follows the position continuously), and also after G0 blocks (the control keeps the
//! speed during G0 unless a cut follows, L2273-2278: only the time of a G4 S after a G0 sees
//! the difference).
//!
//! Never: compute a speed from an axis that is not the reference axis.

use super::geo_axes;
use super::Sinumerik;
use crate::alarm::{Alarm, AlarmCode};
use crate::syntax::sinumerik::Word;

/// The geometry axis whose position gives the constant cutting rate's diameter.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct ReferenceAxis {
    /// 0 for the first geometry axis (the transverse axis X, the default).
    geometry: usize,
}

/// The distance of the tool from the turning centre on the reference axis, mm; None when no
/// channel axis stands behind the reference geometry axis (the speed is then frozen).
pub(super) fn reference_radius(front: &Sinumerik) -> Option<f64> {
    let slot = front.geo_axes.slot(front.speed_reference.geometry)?;
    Some(front.programmed[slot].abs())
}

/// The speed of the cutting rate `rate` (m/min) at `radius` (mm), rpm: infinite at the centre,
/// for the limits to clamp.
pub(super) fn speed(rate: f64, radius: f64) -> f64 {
    if radius > 1e-9 {
        rate * 1000.0 / (std::f64::consts::TAU * radius)
    } else {
        f64::INFINITY
    }
}

/// SCC[axis]: true for that word, false for any other.
///
/// # Errors
/// No axis or several; an axis that is neither a geometry axis nor on the machine; a channel
/// axis that is no geometry axis now.
pub(super) fn read_word(front: &mut Sinumerik, word: &Word) -> Result<bool, Alarm> {
    if &*word.address != "SCC" {
        return Ok(false);
    }
    let name = geo_axes::bracketed_axis(word)?;
    let geometry = match geo_axes::geometry_number(name) {
        Some(number) => number,
        None => {
            let Some(slot) = geo_axes::channel_axis(front, name) else {
                return Err(Alarm::error(
                    AlarmCode::AxisNotOnMachine,
                    word.span,
                    format!("SCC[{name}]: the machine has no axis {name}"),
                ));
            };
            front.geo_axes.number_of(slot).ok_or_else(|| {
                Alarm::error(
                    AlarmCode::WordNotAllowed,
                    word.span,
                    format!("SCC[{name}]: {name} is not a geometry axis now; the cutting rate's reference axis is one"),
                )
                .with_help("name a geometry axis (X, Y, Z), or make the axis one first with GEOAX")
            })?
        }
    };
    front.speed_reference.geometry = geometry;
    Ok(true)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_speed_of_300_m_per_min_at_diameter_82_is_1164_5_rpm() {
        // a/05: 300 * 1000 / (pi * 82) = 1164.548.
        assert!((speed(300.0, 41.0) - 1164.548).abs() < 0.001);
        assert_eq!(speed(20.0, 0.0), f64::INFINITY);
    }
}
