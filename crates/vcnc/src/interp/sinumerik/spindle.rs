//! The spindle and the feed of a SINUMERIK block (docs/SINUMERIK.md 3.2 steps 6 and 7; PGsl 6
//! and 7): S, SVC (cutting rate from the tool's radius), G96/G961 constant cutting rate on the
//! transverse axis with LIMS, G97/G971, G25/G26 speed limits, M3/M4/M5, M19 and SPOS, and the
//! feeds F, FB (this block only) and FZ (per tooth).
//!
//! Never: give the kernel a speed beyond the limits in force (G25/G26, LIMS, the machine's
//! max_rpm), or a feed the block did not program.

use super::block::Words;
use super::Sinumerik;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::kernel::{Kernel, Origin};
use crate::interp::modal::FeedMode;
use crate::motion::SpindleState;
use crate::source::Span;

/// The spindle's programmed state beyond the kernel's speed and direction.
#[derive(Clone, Debug, Default)]
pub(super) struct Spindle {
    /// G96 (per revolution) or G961 (per minute) in force: S is a cutting rate, m/min.
    pub(super) constant_rate: Option<FeedMode>,
    /// The cutting rate of S under G96/G961, or of SVC, m/min.
    rate: Option<f64>,
    /// SVC rather than S gave the rate.
    from_svc: bool,
    /// LIMS: the upper speed under G96/G961.
    lims: Option<f64>,
    /// G25 S: the lower speed limit; G26 S: the upper one.
    min: f64,
    max: Option<f64>,
    /// The speed last given to the kernel, rpm.
    rpm: f64,
}

/// The words of a block for the spindle.
pub(super) struct SpindleWords {
    pub(super) g25: bool,
    pub(super) g26: bool,
}

impl Spindle {
    /// The speed within the limits in force.
    fn clamp(&self, rpm: f64, max_rpm: f64) -> f64 {
        let mut top = max_rpm;
        if let Some(max) = self.max {
            top = top.min(max);
        }
        if self.constant_rate.is_some() {
            if let Some(lims) = self.lims {
                top = top.min(lims);
            }
        }
        rpm.min(top).max(self.min.min(top))
    }
}

/// S, SVC, LIMS, G25/G26 S, G96/G961/G97, M3/M4/M5/M19, SPOS: before the block's motion.
pub(super) fn spindle(
    front: &mut Sinumerik,
    kernel: &mut Kernel,
    words: &Words<'_>,
    limits: &SpindleWords,
    origin: Origin,
) -> Result<(), Alarm> {
    let state = words.m.iter().find_map(|&(code, _)| match code {
        3 => Some(SpindleState::Clockwise),
        4 => Some(SpindleState::CounterClockwise),
        5 => Some(SpindleState::Stopped),
        19 => Some(SpindleState::Oriented),
        _ => None,
    });
    let state = state.or(words.spos.map(|_| SpindleState::Oriented));
    if let Some((lims, span)) = words.lims {
        check_speed(lims, span)?;
        front.spindle.lims = Some(lims);
    }
    let mut speed = None;
    if let Some((s, span)) = words.speed {
        check_speed(s, span)?;
        match (limits.g25, limits.g26) {
            (true, _) => front.spindle.min = s,
            (_, true) => front.spindle.max = Some(s),
            _ if front.spindle.constant_rate.is_some() => {
                front.spindle.rate = Some(s);
                front.spindle.from_svc = false;
            }
            _ => {
                front.spindle.from_svc = false;
                speed = Some(s);
            }
        }
    }
    if let Some((svc, span)) = words.svc {
        check_speed(svc, span)?;
        if words.speed.is_some() && !limits.g25 && !limits.g26 {
            return Err(Alarm::error(
                AlarmCode::WordNotAllowed,
                span,
                "S and SVC in one block: the spindle takes one of them",
            ));
        }
        front.spindle.rate = Some(svc);
        front.spindle.from_svc = true;
    }
    let max_rpm = kernel.state().setup.machine().spindle.max_rpm;
    let rpm = match speed {
        Some(s) => Some(s),
        None if front.spindle.from_svc
            && (words.svc.is_some() || words.tool.is_some() || words.edge.is_some()) =>
        {
            // SVC: the speed of the cutting rate at the tool's radius (PGsl 6.2, L1890-1906).
            let radius = front.edge().map_or(0.0, |e| e.radius);
            if radius <= 0.0 {
                return Err(Alarm::error(
                    AlarmCode::WordNotAllowed,
                    words.svc.map_or(origin.span, |(_, s)| s),
                    "SVC needs a tool with a radius: the active edge has none",
                )
                .with_help("activate the tool's edge (D) with its radius, or program S"));
            }
            Some(front.spindle.rate.unwrap_or(0.0) * 1000.0 / (std::f64::consts::TAU * radius))
        }
        // G96/G961: the speed where the tool stands, so that the spindle starts at it and the
        // block's own cut turns at it (cutting_rate.rs).
        None if front.spindle.constant_rate.is_some()
            && !front.spindle.from_svc
            && (words.speed.is_some() || words.lims.is_some() || state.is_some()) =>
        {
            let radius = super::cutting_rate::reference_radius(front);
            front
                .spindle
                .rate
                .zip(radius)
                .map(|(rate, radius)| super::cutting_rate::speed(rate, radius))
        }
        None => None,
    };
    // Under toolholders SVC may turn another spindle than the master (toolholder.rs).
    let rpm = match (rpm, speed, super::toolholder::svc_spindle(front)) {
        (Some(r), None, Some(n)) => {
            front.spindles.set_speed(n, r.min(max_rpm));
            None
        }
        (rpm, ..) => rpm,
    };
    let clamped = rpm.map(|r| front.spindle.clamp(r, max_rpm));
    if let Some(r) = clamped {
        front.spindle.rpm = r;
    }
    if clamped.is_some() || state.is_some() {
        kernel.spindle(clamped, state, origin);
    }
    Ok(())
}

/// Under G96/G961: the speed of the cutting rate at the reference axis (SCC, the transverse
/// axis X by default) of the block's end (the control follows it continuously; vcnc per
/// block, a choice), after the block's S.
#[inline]
pub(super) fn constant_rate(front: &mut Sinumerik, kernel: &mut Kernel, origin: Origin) {
    if front.spindle.constant_rate.is_none() || front.spindle.from_svc {
        return;
    }
    follow_rate(front, kernel, origin);
}

/// [`constant_rate`] under G96 or G961.
#[inline(never)]
fn follow_rate(front: &mut Sinumerik, kernel: &mut Kernel, origin: Origin) {
    let Some(rate) = front.spindle.rate else {
        return;
    };
    // The reference axis's radius (SCC, GEOAX: cutting_rate.rs); none: the speed stays.
    let Some(radius) = super::cutting_rate::reference_radius(front) else {
        return;
    };
    let max_rpm = kernel.state().setup.machine().spindle.max_rpm;
    let rpm = front
        .spindle
        .clamp(super::cutting_rate::speed(rate, radius), max_rpm);
    if (rpm - front.spindle.rpm).abs() > 1e-9 {
        front.spindle.rpm = rpm;
        kernel.spindle(Some(rpm), None, origin);
    }
}

fn check_speed(speed: f64, span: Span) -> Result<(), Alarm> {
    if speed < 0.0 {
        return Err(Alarm::error(
            AlarmCode::ValueOutOfRange,
            span,
            "a spindle speed cannot be negative",
        ));
    }
    Ok(())
}

/// F, FB and FZ: the feed of the block's moves. FB acts for this block only (PGsl 7.11), FZ is
/// the feed per tooth: under G95 the feed per revolution is FZ times the edge's teeth (PGsl
/// 7.12).
pub(super) fn feed(
    front: &mut Sinumerik,
    kernel: &mut Kernel,
    words: &Words<'_>,
    mode: FeedMode,
) -> Result<(), Alarm> {
    let unit = feed_unit(front);
    if let Some(percent) = words.override_percent {
        front.feed_override = percent / 100.0;
    }
    let factor = front.feed_override;
    if let Some((f, span)) = words.feed {
        program_feed(front, f, span)?;
    }
    if words.feed.is_some() || words.override_percent.is_some() {
        apply_feed(front, kernel, mode);
    }
    if let Some((fz, span)) = words.fz {
        check_feed(fz, span)?;
        front.tooth_feed = Some(fz * unit);
    }
    if words.fz.is_some()
        || (front.tooth_feed.is_some() && (words.tool.is_some() || words.edge.is_some()))
    {
        let fz = front.tooth_feed.unwrap_or(0.0);
        if mode != FeedMode::PerRevolution {
            return Err(Alarm::error(
                AlarmCode::WordNotAllowed,
                words.fz.map_or(
                    Span::new(front.last_span.file, front.last_span.line, 0..0),
                    |(_, s)| s,
                ),
                "FZ, the feed per tooth, acts under G95",
            )
            .with_help("program G95 with FZ, or F under G94"));
        }
        // Without an edge whose teeth are known there is no feed yet: a cut then alarms, as
        // it would without F.
        let teeth = front.edge().and_then(|e| e.teeth).unwrap_or(0);
        if teeth == 0 {
            kernel.set_feed_in(mode, None);
            return Ok(());
        }
        kernel.set_feed_in(mode, Some(fz * f64::from(teeth) * factor));
    }
    if let Some((fb, span)) = words.fb {
        check_feed(fb, span)?;
        front.block_feed_restore = Some(kernel.state().feed);
        kernel.set_feed_in(mode, Some(fb * unit * factor));
    }
    Ok(())
}

/// After a block with FB: the modal feed again.
/// The factor of F: 25.4 under G700 (inch feeds).
fn feed_unit(front: &Sinumerik) -> f64 {
    if front.modal.inch && front.modal.inch_feeds {
        25.4
    } else {
        1.0
    }
}

/// F programmed: the feed of the blocks to come, no longer per tooth nor for one block.
pub(super) fn program_feed(front: &mut Sinumerik, f: f64, span: Span) -> Result<(), Alarm> {
    check_feed(f, span)?;
    front.block_feed_restore = None;
    front.tooth_feed = None;
    front.programmed_feed = Some(f * feed_unit(front));
    Ok(())
}

/// The programmed feed, under the override, to the kernel (not while FZ sets it).
#[inline]
pub(super) fn apply_feed(front: &Sinumerik, kernel: &mut Kernel, mode: FeedMode) {
    // OVR scales the programmed feed as the panel's override would (PGsl 7.5).
    if let Some(f) = front.programmed_feed.filter(|_| front.tooth_feed.is_none()) {
        kernel.set_feed_in(mode, Some(f * front.feed_override));
    }
}

#[inline]
pub(super) fn restore_feed(front: &mut Sinumerik, kernel: &mut Kernel, mode: FeedMode) {
    if let Some(feed) = front.block_feed_restore.take() {
        kernel.set_feed_in(mode, feed);
    }
}

fn check_feed(feed: f64, span: Span) -> Result<(), Alarm> {
    if feed < 0.0 {
        return Err(Alarm::error(
            AlarmCode::BadFeedRate,
            span,
            "the feed cannot be negative",
        ));
    }
    Ok(())
}
