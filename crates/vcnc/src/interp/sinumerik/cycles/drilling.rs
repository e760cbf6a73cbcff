//! The drilling cycles: CYCLE81 (drilling, centring), CYCLE82 (counterboring), CYCLE83 (deep
//! hole), CYCLE84 (rigid tapping), CYCLE840 (tapping with a compensating chuck), CYCLE85 to
//! CYCLE89 (boring 1 to 5). Each drills one hole where it is called, along the tool axis.
//!
//! Every cycle starts with a rapid to the reference plane brought forward by the safety
//! clearance and ends with a rapid to the retraction plane ([`Levels`]). Feeds are the feed
//! programmed before the call unless the cycle has feeds of its own (CYCLE85).
//!
//! Never: move in the plane, except CYCLE86's lift off the wall and back.

use super::{alarm, Levels, Params, Place};
use crate::alarm::Alarm;
use crate::interp::kernel::Kernel;
use crate::interp::modal::FeedMode;
use crate::motion::{PathMode, SegmentKind, SpindleState, StopKind};

/// CYCLE81(RTP, RFP, SDIS, DP, DPR): rapid to the safety plane, drill to the depth, rapid to
/// the retraction plane.
pub(super) fn centering(at: &mut Place, kernel: &mut Kernel, p: &Params) -> Result<(), Alarm> {
    let levels = Levels::read(p, Some(4))?;
    drill(at, kernel, &levels, None)
}

/// CYCLE82(RTP, RFP, SDIS, DP, DPR, DTB): CYCLE81 with a dwell DTB at the depth.
pub(super) fn counterboring(at: &mut Place, kernel: &mut Kernel, p: &Params) -> Result<(), Alarm> {
    let levels = Levels::read(p, Some(4))?;
    drill(at, kernel, &levels, p.number(5))
}

/// The moves of CYCLE81 and CYCLE82.
fn drill(
    at: &mut Place,
    kernel: &mut Kernel,
    levels: &Levels,
    dwell_time: Option<f64>,
) -> Result<(), Alarm> {
    at.rapid_height(kernel, levels.safety)?;
    at.feed_height(kernel, levels.depth)?;
    dwell(at, kernel, dwell_time)?;
    at.rapid_height(kernel, levels.retraction)
}

/// A dwell of DTB: seconds, or (negative, as ShopMill writes it) spindle revolutions; nothing
/// when left out or 0.
fn dwell(at: &Place, kernel: &mut Kernel, time: Option<f64>) -> Result<(), Alarm> {
    let seconds = match time {
        Some(t) if t > 0.0 => t,
        Some(t) if t < 0.0 => {
            let rpm = kernel.state().spindle.speed();
            if rpm <= 0.0 {
                return Ok(());
            }
            -t * 60.0 / rpm
        }
        _ => return Ok(()),
    };
    kernel.dwell(seconds, at.origin)
}

/// The infeeds of CYCLE83 below the reference plane: the first to the first depth, each next
/// one DAM shorter while it stays longer than DAM (then DAM), the last one up to the final
/// depth.
fn peck_depths(levels: &Levels, first: f64, degression: f64) -> Vec<f64> {
    let mut depths = vec![first];
    // At least the depth over MAX_DIVISIONS a peck: vcnc's limit.
    let least = (levels.reference - levels.depth) / super::MAX_DIVISIONS as f64;
    let mut infeed = (levels.reference - first).max(least);
    let mut reached = first;
    while reached > levels.depth {
        if degression > 0.0 {
            infeed = if infeed - degression > degression {
                infeed - degression
            } else {
                degression
            };
        }
        reached = (reached - infeed.max(least)).max(levels.depth);
        depths.push(reached);
    }
    depths
}

/// CYCLE83(RTP, RFP, SDIS, DP, DPR, FDEP, FDPR, DAM, DTB, DTS, FRF, VARI, _AXN, _MDEP, _VRT,
/// _DTD, _DIS1): deep-hole drilling in pecks, breaking the chip (VARI 0: back by _VRT, 1 mm
/// when 0, at the feed) or removing the swarf (VARI 1: out to the safety plane, dwell DTS, back
/// in rapid to the anticipation distance above the last depth).
pub(super) fn deep_hole(at: &mut Place, kernel: &mut Kernel, p: &Params) -> Result<(), Alarm> {
    let levels = Levels::read(p, Some(4))?;
    let depths = peck_depths(&levels, first_depth(p, &levels)?, p.length_or_zero(7).abs());
    let (mode, feed) = kernel.feed_setting();
    // FRF scales the first infeed's feed: 0.001 to 1 (0: 1); above 1 read as percent, as
    // ShopMill writes it (inferred).
    let factor = match p.or_zero(10) {
        f if f <= 0.0 => 1.0,
        f if f > 1.0 => f / 100.0,
        f => f,
    };
    let swarf_removal = p.or_zero(11) == 1.0;
    let back_off = match p.length_or_zero(14) {
        v if v > 0.0 => v,
        _ => 1.0,
    };
    let anticipation = anticipation(p, &levels);
    at.rapid_height(kernel, levels.safety)?;
    let mut last = levels.safety;
    for (k, &depth) in depths.iter().enumerate() {
        if k == 0 {
            kernel.set_feed_in(mode, feed.map(|f| f * factor));
        } else if swarf_removal {
            at.rapid_height(kernel, last + anticipation)?;
        }
        at.feed_height(kernel, depth)?;
        kernel.set_feed_in(mode, feed);
        dwell(at, kernel, p.number(8))?;
        last = depth;
        if depth <= levels.depth {
            break;
        }
        if swarf_removal {
            at.rapid_height(kernel, levels.safety)?;
            dwell(at, kernel, p.number(9))?;
        } else {
            at.feed_height(kernel, depth + back_off)?;
        }
    }
    at.rapid_height(kernel, levels.retraction)
}

/// CYCLE83's first drilling depth: FDPR (relative) wins over FDEP as DPR does over DP; with
/// neither, one infeed (choice). Alarm 61107 when it is not below the reference plane.
fn first_depth(p: &Params, levels: &Levels) -> Result<f64, Alarm> {
    let first = match (p.length(6), p.length(5)) {
        (Some(below), _) if below != 0.0 => levels.reference - below.abs(),
        (_, Some(depth)) => depth,
        _ => levels.depth,
    };
    if first >= levels.reference {
        return Err(alarm(
            61107,
            p.span,
            format_args!("CYCLE83: first drilling depth defined incorrectly: {first} is not below the reference plane {}", levels.reference),
        )
        .with_help("give the first depth below the reference plane (FDEP), or its distance from it (FDPR)"));
    }
    Ok(first.max(levels.depth))
}

/// The anticipation distance of swarf removal: _DIS1, or from the drilling path (0.6 mm up to
/// 30 mm, a fiftieth beyond, at most 7 mm: the cycles manual, inferred for 0).
fn anticipation(p: &Params, levels: &Levels) -> f64 {
    let path = levels.safety - levels.depth;
    match p.length_or_zero(16) {
        v if v > 0.0 => v,
        _ if path <= 30.0 => 0.6,
        _ => (path / 50.0).min(7.0),
    }
}

/// The pitch of an ISO metric coarse thread M3 to M48 (MPIT), mm.
fn coarse_pitch(size: f64) -> Option<f64> {
    const PITCHES: [(f64, f64); 21] = [
        (3.0, 0.5),
        (4.0, 0.7),
        (5.0, 0.8),
        (6.0, 1.0),
        (8.0, 1.25),
        (10.0, 1.5),
        (12.0, 1.75),
        (14.0, 2.0),
        (16.0, 2.0),
        (18.0, 2.5),
        (20.0, 2.5),
        (22.0, 2.5),
        (24.0, 3.0),
        (27.0, 3.0),
        (30.0, 3.5),
        (33.0, 3.5),
        (36.0, 4.0),
        (39.0, 4.0),
        (42.0, 4.5),
        (45.0, 4.5),
        (48.0, 5.0),
    ];
    PITCHES
        .iter()
        .find(|(s, _)| *s == size.abs())
        .map(|&(_, pitch)| pitch.copysign(size))
}

/// The signed pitch of a tapping cycle from MPIT (thread size) and PIT (pitch): positive for a
/// right-hand thread. Alarm 61001 when neither gives one, MPIT is not a size M3..M48, or the
/// two disagree.
fn pitch(p: &Params, mpit: usize, pit: usize) -> Result<Option<f64>, Alarm> {
    let wrong = |what: String| {
        alarm(
            61001,
            p.span,
            format_args!("{}: thread pitch wrong: {what}", p.name()),
        )
        .with_help("give the thread size (MPIT, 3 to 48 for M3 to M48) or the pitch (PIT), with the sign of the thread's hand")
    };
    let by_size = match p.or_zero(mpit) {
        0.0 => None,
        size => Some(
            coarse_pitch(size)
                .ok_or_else(|| wrong(format!("MPIT {size} is no thread size M3 to M48")))?,
        ),
    };
    let by_value = p.length(pit).filter(|v| *v != 0.0);
    match (by_size, by_value) {
        (Some(a), Some(b)) if (a - b).abs() > 1e-9 => {
            Err(wrong(format!("MPIT gives the pitch {a}, PIT {b}")))
        }
        (a, b) => Ok(a.or(b)),
    }
}

/// The spindle direction a parameter gives: 3 (M3), 4 (M4), 5 (M5); anything else is alarm
/// 61102 "no spindle direction programmed".
fn direction(p: &Params, index: usize, what: &str, stop: bool) -> Result<SpindleState, Alarm> {
    match p.or_zero(index) {
        3.0 => Ok(SpindleState::Clockwise),
        4.0 => Ok(SpindleState::CounterClockwise),
        5.0 if stop => Ok(SpindleState::Stopped),
        value => Err(alarm(
            61102,
            p.span,
            format_args!(
                "{}: no spindle direction programmed: {what} is {value}",
                p.name()
            ),
        )
        .with_help(format!(
            "give {what} as 3 (M3){}",
            if stop {
                ", 4 (M4) or 5 (M5)"
            } else {
                " or 4 (M4)"
            }
        ))),
    }
}

fn reversed(state: SpindleState) -> SpindleState {
    match state {
        SpindleState::CounterClockwise => SpindleState::Clockwise,
        _ => SpindleState::CounterClockwise,
    }
}

/// The spindle turns `state` from here (an event only when it changes).
fn turn(at: &Place, kernel: &mut Kernel, speed: Option<f64>, state: SpindleState) {
    let spindle = &kernel.state().spindle;
    let same_speed = speed.is_none_or(|s| s == spindle.speed());
    if spindle.state() != state || !same_speed {
        kernel.spindle(speed, Some(state), at.origin);
    }
}

/// CYCLE84(RTP, RFP, SDIS, DP, DPR, DTB, SDAC, MPIT, PIT, POSS, SST, SST1): rigid tapping. The
/// spindle stops oriented (POSS), taps to the depth at SST (the speed in force when 0) turning
/// by the thread's hand, dwells DTB, taps back out to the safety plane at SST1 (SST when 0)
/// the other way, the tool rapids to the retraction plane and the spindle turns as SDAC says
/// at the speed it had before the cycle.
pub(super) fn rigid_tapping(at: &mut Place, kernel: &mut Kernel, p: &Params) -> Result<(), Alarm> {
    let levels = Levels::read(p, Some(4))?;
    let after = direction(p, 6, "SDAC", true)?;
    let Some(lead) = pitch(p, 7, 8)? else {
        return Err(alarm(
            61001,
            p.span,
            "CYCLE84: thread pitch wrong: neither MPIT nor PIT gives one",
        )
        .with_help("give the thread size (MPIT, 3 to 48 for M3 to M48) or the pitch (PIT)"));
    };
    let speed_before = kernel.state().spindle.speed();
    let tap_speed = p.number(10).filter(|s| *s > 0.0).unwrap_or(speed_before);
    let out_speed = p.number(11).filter(|s| *s > 0.0).unwrap_or(tap_speed);
    let inward = if lead > 0.0 {
        SpindleState::Clockwise
    } else {
        SpindleState::CounterClockwise
    };
    at.rapid_height(kernel, levels.safety)?;
    kernel.spindle(None, Some(SpindleState::Oriented), at.origin);
    kernel.spindle(Some(tap_speed), Some(inward), at.origin);
    at.thread_height(kernel, levels.depth, lead.abs())?;
    dwell(at, kernel, p.number(5))?;
    kernel.spindle(Some(out_speed), Some(reversed(inward)), at.origin);
    at.thread_height(kernel, levels.safety, lead.abs())?;
    at.rapid_height(kernel, levels.retraction)?;
    kernel.spindle(Some(speed_before), Some(after), at.origin);
    Ok(())
}

/// CYCLE840(RTP, RFP, SDIS, DP, DPR, DTB, SDR, SDAC, ENC, MPIT, PIT): tapping with a
/// compensating chuck. With an encoder (ENC 0) and a pitch, the tap is a thread at that lead;
/// without (ENC 1), or without a pitch, a line at the feed in force (G63). The spindle turns
/// back (SDR: 3 or 4; 0 reverses it, with an encoder only) for the way out to the safety
/// plane, then as SDAC says.
pub(super) fn floating_tapping(
    at: &mut Place,
    kernel: &mut Kernel,
    p: &Params,
) -> Result<(), Alarm> {
    let levels = Levels::read(p, Some(4))?;
    let with_encoder = p.or_zero(8) == 0.0;
    let back = match p.or_zero(6) {
        0.0 if with_encoder => reversed(kernel.state().spindle.state()),
        _ => direction(p, 6, "SDR", false)?,
    };
    let after = direction(p, 7, "SDAC", true)?;
    let lead = if with_encoder { pitch(p, 9, 10)? } else { None };
    let speed = kernel.state().spindle.speed();
    at.rapid_height(kernel, levels.safety)?;
    tap_move(at, kernel, levels.depth, lead)?;
    dwell(at, kernel, p.number(5))?;
    kernel.spindle(None, Some(back), at.origin);
    tap_move(at, kernel, levels.safety, lead)?;
    at.rapid_height(kernel, levels.retraction)?;
    kernel.spindle(Some(speed), Some(after), at.origin);
    Ok(())
}

/// One way of a floating tap: a thread at `lead`, or a line at the feed in force in tapping
/// mode (no override, exact stop at its end, as G63).
fn tap_move(
    at: &mut Place,
    kernel: &mut Kernel,
    height: f64,
    lead: Option<f64>,
) -> Result<(), Alarm> {
    match lead {
        Some(lead) => at.thread_height(kernel, height, lead.abs()),
        None => {
            kernel.set_path_mode(PathMode::Tapping, true);
            let moved = at.feed_height(kernel, height);
            kernel.set_path_mode(at.path_mode, false);
            moved
        }
    }
}

/// CYCLE85(RTP, RFP, SDIS, DP, DPR, DTB, FFR, RFF): boring 1 (reaming): in at FFR, dwell DTB,
/// out to the safety plane at RFF, then rapid to the retraction plane. FFR and RFF are feeds
/// per minute; left out or 0, the feed in force (choice).
pub(super) fn reaming(at: &mut Place, kernel: &mut Kernel, p: &Params) -> Result<(), Alarm> {
    let levels = Levels::read(p, Some(4))?;
    let (mode, feed) = kernel.feed_setting();
    let feed_of = |index: usize| match p.number(index) {
        Some(f) if f > 0.0 => (FeedMode::PerMinute, Some(f)),
        _ => (mode, feed),
    };
    at.rapid_height(kernel, levels.safety)?;
    let (m, f) = feed_of(6);
    kernel.set_feed_in(m, f);
    at.feed_height(kernel, levels.depth)?;
    dwell(at, kernel, p.number(5))?;
    let (m, f) = feed_of(7);
    kernel.set_feed_in(m, f);
    at.feed_height(kernel, levels.safety)?;
    at.rapid_height(kernel, levels.retraction)
}

/// CYCLE86(RTP, RFP, SDIS, DP, DPR, DTB, SDIR, RPA, RPO, RPAP, POSS): boring 2. The spindle
/// turns SDIR; in at the feed, dwell DTB, the spindle stops oriented (POSS), the tool lifts off
/// the wall by RPA, RPO in the plane and RPAP along the tool axis (incremental, rapid), rapids
/// to the safety and the retraction plane, back to the hole's centre, and the spindle turns
/// SDIR again.
pub(super) fn boring_oriented(
    at: &mut Place,
    kernel: &mut Kernel,
    p: &Params,
) -> Result<(), Alarm> {
    let levels = Levels::read(p, Some(4))?;
    let spindle = direction(p, 6, "SDIR", false)?;
    let centre = at.in_plane();
    turn(at, kernel, None, spindle);
    at.rapid_height(kernel, levels.safety)?;
    at.feed_height(kernel, levels.depth)?;
    dwell(at, kernel, p.number(5))?;
    kernel.spindle(None, Some(SpindleState::Oriented), at.origin);
    let lift = (
        centre.0 + p.length_or_zero(7),
        centre.1 + p.length_or_zero(8),
    );
    at.rapid_plane(kernel, lift)?;
    at.rapid_height(kernel, levels.depth + p.length_or_zero(9))?;
    at.rapid_height(kernel, levels.safety)?;
    at.rapid_height(kernel, levels.retraction)?;
    at.rapid_plane(kernel, centre)?;
    kernel.spindle(None, Some(spindle), at.origin);
    Ok(())
}

/// CYCLE87(RTP, RFP, SDIS, DP, DPR, SDIR) and CYCLE88(RTP, RFP, SDIS, DP, DPR, DTB, SDIR):
/// boring 3 and 4. The spindle turns SDIR; in at the feed (CYCLE88: dwell DTB), the spindle
/// stops (M5) and the program stops (M0) for the operator; after NC start, rapid to the
/// retraction plane with the spindle stopped (inferred: the manual restarts nothing).
pub(super) fn boring_with_stop(
    at: &mut Place,
    kernel: &mut Kernel,
    p: &Params,
    with_dwell: bool,
) -> Result<(), Alarm> {
    let levels = Levels::read(p, Some(4))?;
    let spindle = direction(p, if with_dwell { 6 } else { 5 }, "SDIR", false)?;
    turn(at, kernel, None, spindle);
    at.rapid_height(kernel, levels.safety)?;
    at.feed_height(kernel, levels.depth)?;
    if with_dwell {
        dwell(at, kernel, p.number(5))?;
    }
    kernel.spindle(None, Some(SpindleState::Stopped), at.origin);
    kernel.event(
        SegmentKind::Stop {
            kind: StopKind::Program,
        },
        at.origin,
    );
    at.rapid_height(kernel, levels.retraction)
}

/// CYCLE89(RTP, RFP, SDIS, DP, DPR, DTB): boring 5: in at the feed, dwell DTB, out to the
/// safety plane at the same feed, rapid to the retraction plane.
pub(super) fn boring_with_dwell(
    at: &mut Place,
    kernel: &mut Kernel,
    p: &Params,
) -> Result<(), Alarm> {
    let levels = Levels::read(p, Some(4))?;
    at.rapid_height(kernel, levels.safety)?;
    at.feed_height(kernel, levels.depth)?;
    dwell(at, kernel, p.number(5))?;
    at.feed_height(kernel, levels.safety)?;
    at.rapid_height(kernel, levels.retraction)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn levels(reference: f64, depth: f64) -> Levels {
        Levels {
            retraction: reference + 10.0,
            reference,
            safety: reference + 1.0,
            depth,
        }
    }

    #[test]
    fn pecks_shrink_by_the_degression_down_to_it_and_stop_at_the_depth() {
        // First infeed 10 (to -10), then 7, 4, then 3 (not 1: never below DAM), then the
        // rest up to -25: -10, -17, -21, -24, -25.
        let depths = peck_depths(&levels(0.0, -25.0), -10.0, 3.0);
        assert_eq!(depths, vec![-10.0, -17.0, -21.0, -24.0, -25.0]);
    }

    #[test]
    fn without_degression_every_peck_is_the_first() {
        let depths = peck_depths(&levels(0.0, -12.0), -5.0, 0.0);
        assert_eq!(depths, vec![-5.0, -10.0, -12.0]);
    }

    #[test]
    fn thread_sizes_give_their_coarse_pitch_with_the_hand() {
        assert_eq!(coarse_pitch(12.0), Some(1.75));
        assert_eq!(coarse_pitch(-8.0), Some(-1.25));
        assert_eq!(coarse_pitch(7.0), None);
    }
}
