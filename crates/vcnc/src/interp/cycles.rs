//! Canned cycles (issue #4): G73, G74, G76, G81-G86, G89 with G98/G99, cancelled by G80 or any
//! group-01 code (spec iso-syntec-milling.md 1.40-1.52, iso-fanuc0m-mitsubishi.md A.32-A.36).
//!
//! A cycle block positions over the hole (rapid, in the plane), goes down to the R level
//! (rapid), machines to the bottom Z as the cycle says, and returns to the R level (G99) or the
//! initial level (G98): the drilling-axis position when the cycle mode was entered. Every move
//! is an ordinary rapid or feed of the block, so cutter compensation, the planner and the
//! trace need nothing new. Hole data (R, Z, Q, P) are modal until G80; K repeats the block
//! (each time moving by the block's X/Y in G91), K0 only stores the data.

use super::decode::Command;
use super::exec::Executor;
use super::modal::{CycleReturn, DistanceMode, FeedMode};
use super::spindle::Spindle;
use super::Output;
use crate::alarm::{Alarm, AlarmCode};
use crate::machine::{Axis, AXES};
use crate::motion::{Plane, SegmentKind, SpindleState, StopKind};
use crate::profile::{CycleKind, GCode, Group, PatternKind, Profile, ShiftDirection};

/// The most repeats (K) or pattern holes one block may make, and the most pecks in one hole:
/// the controls' own limit for K (spec 1.40: 0-9999), and a bound that turns a peck depth of
/// almost nothing into an alarm instead of a hang.
const MAX_COUNT: i64 = 9999;

/// The most moves one cycle block may make (repeats or pattern holes times the moves of each
/// hole): far beyond real programs, and a bound that keeps a K9999 of 9999-peck holes from
/// running for hours.
const MAX_BLOCK_MOVES: i64 = 100_000;

/// The cycle mode in force.
#[derive(Clone, Debug)]
pub(crate) struct Cycle {
    kind: CycleKind,
    /// The plane's first and second axis (positioning) and the drilling axis.
    axes: (usize, usize, usize),
    /// The plane the cycle started in: changing it needs G80 first.
    plane: Plane,
    /// The initial level: the drilling-axis program coordinate when the mode was entered.
    initial: f64,
    /// The R level, program coordinates: R as written in G90, the initial level plus R in G91.
    /// Levels stay where they were set when later blocks switch G90/G91 (spec 1.14 example 2).
    r: Option<f64>,
    /// The bottom, program coordinates: Z as written in G90, the R level plus Z in G91.
    z: Option<f64>,
    /// Q, mm: the peck depth (G73, G83) or the shift (G76).
    q: Option<f64>,
    /// P, seconds: the dwell at the bottom.
    p: f64,
    /// Syntec's `F2=` in the feed's unit, where the fast drilling mode uses it: G81 retracts at
    /// this feed instead of at rapid.
    retract_feed: Option<f64>,
}

impl Cycle {
    /// Which cycle this is.
    pub(crate) fn kind(&self) -> CycleKind {
        self.kind
    }
}

/// G80, a cycle code, or a group-01 code in the block: the cycle mode starts, changes or ends.
///
/// # Errors
/// A plane change while a cycle is in force.
pub(crate) fn apply_codes(exec: &mut Executor, cmd: &Command) -> Result<(), Alarm> {
    if exec.cycle.is_none() && cmd.group(Group::Cycle).is_none() {
        // Most blocks: no cycle in force and none named.
        return Ok(());
    }
    if cmd.group(Group::Motion).is_some() {
        // Any group-01 code cancels the cycle, also one in the cycle's own block (Syntec
        // restriction 4, FANUC).
        exec.cycle = None;
        return Ok(());
    }
    refuse_reference_return(exec, cmd)?;
    let Some(g) = cmd.group(Group::Cycle) else {
        if let Some(cycle) = &exec.cycle {
            if exec.modal.plane != cycle.plane
                && exec.kernel.setup.profile().cycles.cycle_plane_follows_g17
            {
                return Err(Alarm::error(
                    AlarmCode::CycleData,
                    cmd.group(Group::Plane).map_or(cmd.span, |g| g.span),
                    "the plane cannot change while a canned cycle is in force",
                )
                .with_help("cancel the cycle with G80 first"));
            }
        }
        return Ok(());
    };
    match g.code {
        GCode::CycleCancel => exec.cycle = None,
        GCode::Cycle(kind) => match exec.cycle.as_mut() {
            Some(cycle) => cycle.kind = kind,
            None => {
                let (a, b, d) = if exec.kernel.setup.profile().cycles.cycle_plane_follows_g17 {
                    exec.modal.plane.axes()
                } else {
                    Plane::Xy.axes()
                };
                exec.cycle = Some(Cycle {
                    kind,
                    axes: (a, b, d),
                    plane: exec.modal.plane,
                    initial: exec.kernel.program_position()[d],
                    r: None,
                    z: None,
                    q: None,
                    p: 0.0,
                    retract_feed: None,
                });
            }
        },
        _ => {}
    }
    Ok(())
}

/// G27 to G30 while a cycle is in force: the control's reference returns do not mix with the
/// cycle's hole data (FANUC alarm 044; the 0M manual's warning, 001 L1754, spec A.32).
fn refuse_reference_return(exec: &Executor, cmd: &Command) -> Result<(), Alarm> {
    let Some(g) = cmd.group(Group::NonModal) else {
        return Ok(());
    };
    let returns = matches!(
        g.code,
        GCode::ReferenceReturn | GCode::ReturnFromReference | GCode::NthReferenceReturn
    );
    let cancelled = cmd
        .group(Group::Cycle)
        .is_some_and(|c| c.code == GCode::CycleCancel);
    if exec.cycle.is_none() || !returns || cancelled {
        return Ok(());
    }
    Err(Alarm::error(
        AlarmCode::CycleData,
        g.span,
        "G28, G29 and G30 cannot be commanded while a canned cycle is in force",
    )
    .with_help("cancel the cycle with G80 first (FANUC alarm 044)"))
}

/// A block in cycle mode: stores its hole data and machines its holes. A block without a
/// position or hole data (X, Y, Z, R or another axis) does not drill.
///
/// # Errors
/// Missing or bad hole data, no feed.
pub(crate) fn run(exec: &mut Executor, cmd: &Command, out: &mut Output) -> Result<(), Alarm> {
    let Some(mut cycle) = exec.cycle.take() else {
        return Ok(());
    };
    if out.compensating() && (cmd.has_axis_words() || cmd.r().is_some()) {
        // Cutter compensation does not apply to a cycle's moves (spec 1.40 restriction 5): it is
        // cancelled for the block and starts up again after it.
        out.suspend_compensation()?;
    }
    let result = holes(exec, &mut cycle, cmd, out);
    exec.cycle = Some(cycle);
    result
}

fn holes(
    exec: &mut Executor,
    cycle: &mut Cycle,
    cmd: &Command,
    out: &mut Output,
) -> Result<(), Alarm> {
    if !cmd.has_axis_words() && cmd.r().is_none() {
        return Ok(());
    }
    store(exec, cycle, cmd)?;
    tapping_feed(exec, cycle, cmd)?;
    let repeats = match cmd.word(b'K') {
        Some(k) => match k.number.whole() {
            Some(n) if (0..=MAX_COUNT).contains(&n) => n,
            _ => {
                return Err(Alarm::error(
                    AlarmCode::CycleData,
                    k.span,
                    format!("K, the number of repeats, is a whole number from 0 to {MAX_COUNT}"),
                ))
            }
        },
        None => 1,
    };
    if repeats == 0 {
        return Ok(());
    }
    let levels = levels(&exec.kernel.spindle, cycle, cmd, out)?;
    check_size(cycle, levels, repeats, cmd)?;
    let (a, b, _) = cycle.axes;
    for _ in 0..repeats {
        // Over the hole: the plane axes as a move would go there (G91 steps on with each
        // repeat; G16 reads radius and angle), and other axes (a rotary table, say) with them.
        let target = exec.target_program(cmd);
        if let Some(point) = super::polar_coordinates::point(exec, cmd) {
            exec.polar = Some(point);
        }
        drill_at(
            exec,
            cycle,
            cmd,
            out,
            levels,
            (target[a], target[b]),
            Some(target),
        )?;
    }
    Ok(())
}

/// The R level and the bottom for the block's holes, program coordinates, after the checks a
/// cycle makes before it moves.
///
/// # Errors
/// No Z; a peck cycle without Q.
fn levels(
    spindle: &Spindle,
    cycle: &Cycle,
    cmd: &Command,
    out: &mut Output,
) -> Result<(f64, f64), Alarm> {
    let Some(bottom) = cycle.z else {
        return Err(Alarm::error(
            AlarmCode::CycleData,
            cmd.span,
            "a canned cycle needs Z, the hole bottom",
        ));
    };
    let r_level = cycle.r.unwrap_or(cycle.initial);
    if matches!(cycle.kind, CycleKind::HighSpeedPeck | CycleKind::Peck)
        && cycle.q.is_none_or(|q| q <= 0.0)
    {
        return Err(Alarm::error(
            AlarmCode::CycleData,
            cmd.span,
            "a peck drilling cycle needs Q, the depth of each peck, above zero",
        )
        .with_help("FANUC alarm 045"));
    }
    // Every cycle but G87 works from R down to the bottom; G87 from below the part upwards.
    let upwards = cycle.kind == CycleKind::BackBore;
    if (bottom > r_level && !upwards) || (bottom < r_level && upwards) {
        // A misprint, most likely (the FANUC 0M manual's O1717 has one): the control runs it,
        // the tool moves away from the part where it should cut.
        out.push_warning(Alarm::warning(
            AlarmCode::CycleData,
            cmd.span,
            format!(
                "the hole bottom ({}) lies {} the R level ({}): this cycle {} from R to the bottom",
                number(bottom),
                if upwards { "below" } else { "above" },
                number(r_level),
                if upwards {
                    "bores upwards"
                } else {
                    "machines downwards"
                },
            ),
        ));
    }
    let tapping = matches!(cycle.kind, CycleKind::Tap | CycleKind::LeftHandTap);
    if tapping && spindle.speed() <= 0.0 {
        // The tap's pitch is F / S (F itself in G95): without a speed the feed matches no thread.
        out.push_warning(Alarm::warning(
            AlarmCode::CycleData,
            cmd.span,
            "tapping without a spindle speed: the feed cannot match the tap's pitch (F = S x pitch)",
        ));
    }
    let wanted = match cycle.kind {
        CycleKind::Tap => Some(SpindleState::Clockwise),
        CycleKind::LeftHandTap => Some(SpindleState::CounterClockwise),
        _ => None,
    };
    if let Some(wanted) = wanted.filter(|&w| spindle.state() != w) {
        // The tap turns the way the spindle was started (spec 1.42, 1.47: M03 before G84, M04
        // before G74); anything else breaks the tap on a real machine.
        out.push_warning(Alarm::warning(
            AlarmCode::CycleData,
            cmd.span,
            format!(
                "tapping with the spindle {}: this cycle taps with it {}",
                spindle_words(spindle.state()),
                spindle_words(wanted)
            ),
        ));
    }
    Ok((r_level, bottom))
}

/// Refuses a block that would make more than [`MAX_BLOCK_MOVES`] moves for `holes` holes.
fn check_size(
    cycle: &Cycle,
    (r_level, bottom): (f64, f64),
    holes: i64,
    cmd: &Command,
) -> Result<(), Alarm> {
    let pecking = matches!(
        cycle.kind,
        CycleKind::HighSpeedPeck | CycleKind::Peck | CycleKind::Tap | CycleKind::LeftHandTap
    );
    let pecks = match cycle.q.filter(|&q| pecking && q > 0.0) {
        Some(q) => ((bottom - r_level).abs() / q).ceil().min(MAX_COUNT as f64) as i64,
        None => 1,
    };
    let moves = holes.saturating_mul(4 + 3 * pecks);
    if moves > MAX_BLOCK_MOVES {
        return Err(Alarm::error(
            AlarmCode::CycleData,
            cmd.span,
            format!("this block would make {moves} moves: vcnc makes at most {MAX_BLOCK_MOVES} in one block"),
        ));
    }
    Ok(())
}

/// One hole at `at` (the plane axes): a rapid over it at the level the last hole returned to
/// (`target` gives the other axes' positions when the block moves them), then the cycle.
fn drill_at(
    exec: &mut Executor,
    cycle: &Cycle,
    cmd: &Command,
    out: &mut Output,
    (r_level, bottom): (f64, f64),
    at: (f64, f64),
    target: Option<[f64; AXES]>,
) -> Result<(), Alarm> {
    let (a, b, d) = cycle.axes;
    let mut over = target.unwrap_or_else(|| exec.kernel.program_position());
    (over[a], over[b]) = at;
    over[d] = exec.kernel.program_position()[d];
    rapid(exec, cmd, out, over)?;
    let back = match exec.modal.cycle_return {
        CycleReturn::InitialLevel => cycle.initial,
        CycleReturn::RLevel => r_level,
    };
    Hole {
        exec,
        cmd,
        out,
        d,
        r_level,
        bottom,
        back,
    }
    .run(cycle)
}

/// G134, G135, G136, G137.1 (spec 1.59-1.62): the holes of the pattern, each drilled by the
/// cycle in force; X Y place the pattern (G91: from where the tool is), I J K P shape it. The
/// tool stays over the last hole.
///
/// # Errors
/// No cycle in force; a pattern word missing or out of range.
pub(crate) fn pattern(
    exec: &mut Executor,
    cmd: &Command,
    kind: PatternKind,
    out: &mut Output,
) -> Result<(), Alarm> {
    let Some(cycle) = exec.cycle.take() else {
        return Err(Alarm::error(
            AlarmCode::CycleData,
            cmd.span,
            "a hole pattern drills with the canned cycle in force, and none is",
        )
        .with_help("set the cycle first, e.g. G81 Z.. R.. F.. K0"));
    };
    let result = pattern_holes(exec, &cycle, cmd, kind, out);
    exec.cycle = Some(cycle);
    result
}

fn pattern_holes(
    exec: &mut Executor,
    cycle: &Cycle,
    cmd: &Command,
    kind: PatternKind,
    out: &mut Output,
) -> Result<(), Alarm> {
    let (a, b, _) = cycle.axes;
    let here = exec.kernel.program_position();
    let incremental = exec.modal.distance == DistanceMode::Incremental;
    let place = |axis: usize| {
        cmd.axis(axis).map_or(here[axis], |v| {
            let v = exec.axis_value(Axis::ALL[axis], &v);
            if incremental {
                here[axis] + v
            } else {
                v
            }
        })
    };
    let origin = (place(a), place(b));
    let need = |letter: u8, what: &str| {
        cmd.word(letter).ok_or_else(|| {
            Alarm::error(
                AlarmCode::CycleData,
                cmd.span,
                format!("this hole pattern needs {} ({what})", letter as char),
            )
        })
    };
    let count = |letter: u8, what: &str| -> Result<i64, Alarm> {
        let word = need(letter, what)?;
        match word.number.whole() {
            Some(n) if n != 0 && n.abs() <= 9999 => Ok(n),
            _ => Err(Alarm::error(
                AlarmCode::CycleData,
                word.span,
                format!(
                    "{} ({what}) is a whole number from 1 to 9999",
                    letter as char
                ),
            )),
        }
    };
    let polar = |radius: f64, degrees: f64| {
        let (sin, cos) = degrees.to_radians().sin_cos();
        (origin.0 + radius * cos, origin.1 + radius * sin)
    };
    let points: Vec<(f64, f64)> = match kind {
        PatternKind::BoltCircle => {
            let radius = exec.length(&need(b'I', "the radius")?);
            let first = exec
                .kernel
                .setup
                .angle(&need(b'J', "the first hole's angle")?);
            let n = count(b'K', "the number of holes; negative: clockwise")?;
            let step = 360.0 / n as f64;
            (0..n.abs())
                .map(|i| polar(radius, first + step * i as f64))
                .collect()
        }
        PatternKind::Line => {
            let spacing = exec.length(&need(b'I', "the spacing")?);
            let (sin, cos) = exec
                .kernel
                .setup
                .angle(&need(b'J', "the angle")?)
                .to_radians()
                .sin_cos();
            let n = count(b'K', "the number of holes")?.abs();
            (0..n)
                .map(|i| {
                    let d = spacing * i as f64;
                    (origin.0 + d * cos, origin.1 + d * sin)
                })
                .collect()
        }
        PatternKind::Arc => {
            let radius = exec.length(&need(b'I', "the radius")?);
            let first = exec
                .kernel
                .setup
                .angle(&need(b'J', "the first hole's angle")?);
            let pitch = exec
                .kernel
                .setup
                .angle(&need(b'P', "the angle between holes")?);
            let n = count(b'K', "the number of holes")?.abs();
            (0..n)
                .map(|i| polar(radius, first + pitch * i as f64))
                .collect()
        }
        PatternKind::Grid => {
            let dx = exec.length(&need(b'I', "the spacing along the first axis")?);
            let nx = count(b'P', "the number of holes along the first axis")?.abs();
            let dy = exec.length(&need(b'J', "the spacing along the second axis")?);
            let ny = count(b'K', "the number of rows")?.abs();
            if nx * ny > MAX_COUNT {
                return Err(Alarm::error(
                    AlarmCode::CycleData,
                    cmd.span,
                    format!(
                        "this grid has {} holes: vcnc drills at most {MAX_COUNT} in one block",
                        nx * ny
                    ),
                ));
            }
            // Row by row, each row the other way round (zig-zag), as FANUC-family grids go.
            (0..ny)
                .flat_map(|j| {
                    (0..nx).map(move |i| {
                        let i = if j % 2 == 0 { i } else { nx - 1 - i };
                        (origin.0 + dx * i as f64, origin.1 + dy * j as f64)
                    })
                })
                .collect()
        }
    };
    let levels = levels(&exec.kernel.spindle, cycle, cmd, out)?;
    check_size(cycle, levels, points.len() as i64, cmd)?;
    for at in points {
        drill_at(exec, cycle, cmd, out, levels, at, None)?;
    }
    Ok(())
}

/// Syntec's E (threads per inch) in a tapping cycle: without F, the feed is the pitch 25.4 / E
/// mm per revolution (G95), times the spindle speed (G94) (spec 1.42, 1.47).
///
/// # Errors
/// E where it means nothing: outside G74/G84, or not above zero.
fn tapping_feed(exec: &mut Executor, cycle: &Cycle, cmd: &Command) -> Result<(), Alarm> {
    let Some(e) = cmd.word(b'E') else {
        return Ok(());
    };
    if !matches!(cycle.kind, CycleKind::Tap | CycleKind::LeftHandTap) || e.number.value <= 0.0 {
        return Err(Alarm::error(
            AlarmCode::CycleData,
            e.span,
            "E, threads per inch, is for the tapping cycles G74 and G84, above zero",
        ));
    }
    if cmd.f().is_some() {
        // F and E together: E is ignored (spec 1.42).
        return Ok(());
    }
    let pitch = 25.4 / e.number.value;
    exec.kernel.feed = Some(match exec.modal.feed_mode {
        FeedMode::PerRevolution => pitch,
        _ => pitch * exec.kernel.spindle.speed(),
    });
    Ok(())
}

/// Stores the block's hole data.
fn store(exec: &Executor, cycle: &mut Cycle, cmd: &Command) -> Result<(), Alarm> {
    let incremental = exec.modal.distance == DistanceMode::Incremental;
    if let Some(r) = cmd.r() {
        let r = exec.length(&r);
        cycle.r = Some(if incremental { cycle.initial + r } else { r });
    }
    if let Some(z) = cmd.axis(cycle.axes.2) {
        let z = exec.axis_value(Axis::ALL[cycle.axes.2], &z);
        let r_level = cycle.r.unwrap_or(cycle.initial);
        cycle.z = Some(if incremental { r_level + z } else { z });
    }
    if let Some(q) = cmd.word(b'Q') {
        // A minus sign is ignored (spec 1.41).
        cycle.q = Some(exec.length(&q).abs());
    }
    if let Some(p) = cmd.p() {
        let rule = exec
            .kernel
            .setup
            .profile()
            .dwell
            .cycle_dwell_p
            .unwrap_or(exec.kernel.setup.profile().dwell.dwell_p);
        cycle.p = super::auxiliary::p_seconds(rule, p)?;
    }
    if let Some(f2) = cmd.retract_feed() {
        // Syntec's retract feed works only in its fast drilling mode (Pr4008 = 1, the profile's
        // `cycles.fast_drilling`); in the normal mode the retract stays a rapid, and so does it
        // for F2 <= 0 (spec 1.44, L3585-3610). It must be whole either way (COR-045).
        if f2.number.value.fract() != 0.0 {
            return Err(
                Alarm::error(AlarmCode::CycleData, f2.span, "F2= must be a whole number")
                    .with_help("Syntec alarm COR-045"),
            );
        }
        let used = exec.kernel.setup.profile().cycles.fast_drilling && f2.number.value > 0.0;
        cycle.retract_feed = used.then(|| f2.number.value * exec.modal.units.to_mm());
    }
    Ok(())
}

/// One hole being machined: the block and the levels on the drilling axis, program
/// coordinates.
struct Hole<'a> {
    exec: &'a mut Executor,
    cmd: &'a Command,
    out: &'a mut Output,
    d: usize,
    r_level: f64,
    bottom: f64,
    /// Where the tool returns: the R level (G99) or the initial level (G98).
    back: f64,
}

impl Hole<'_> {
    /// From over the hole: down to R, the cycle's own moves, back up.
    fn run(&mut self, cycle: &Cycle) -> Result<(), Alarm> {
        let (r, bottom, back) = (self.r_level, self.bottom, self.back);
        if cycle.kind != CycleKind::BackBore {
            // G87 goes down to R shifted off the hole's axis.
            self.rapid_to(r)?;
        }
        match cycle.kind {
            CycleKind::Drill => {
                self.feed_to(bottom)?;
                match cycle.retract_feed {
                    Some(feed) => self.feed_to_at(back, feed),
                    None => self.rapid_to(back),
                }
            }
            CycleKind::DrillDwell => {
                self.feed_to(bottom)?;
                self.dwell(cycle.p);
                self.rapid_to(back)
            }
            CycleKind::HighSpeedPeck | CycleKind::Peck => {
                self.peck(cycle)?;
                self.rapid_to(back)
            }
            CycleKind::Bore => {
                self.feed_to(bottom)?;
                self.feed_to(r)?;
                self.rapid_to(back)
            }
            CycleKind::BoreDwell => {
                self.feed_to(bottom)?;
                self.dwell(cycle.p);
                self.feed_to(r)?;
                self.rapid_to(back)
            }
            CycleKind::BoreSpindleStop => {
                let running = self.exec.kernel.spindle.state();
                self.feed_to(bottom)?;
                self.spindle(SpindleState::Stopped);
                self.rapid_to(back)?;
                self.spindle(running);
                Ok(())
            }
            CycleKind::Tap | CycleKind::LeftHandTap => {
                let (forward, reverse) = if cycle.kind == CycleKind::Tap {
                    (SpindleState::Clockwise, SpindleState::CounterClockwise)
                } else {
                    (SpindleState::CounterClockwise, SpindleState::Clockwise)
                };
                // Spec 1.42: type I taps in one pass; with Q, type III (Pr4001 = 0, FANUC's
                // standard peck tapping) taps Q deeper each time and backs out to R between
                // pecks. Dwell and reverse at each turn.
                let q = cycle.q.filter(|&q| q > 0.0).unwrap_or(f64::INFINITY);
                self.check_pecks(q)?;
                let mut depth = r;
                loop {
                    depth = self.next_depth(depth, q);
                    self.feed_to(depth)?;
                    self.dwell(cycle.p);
                    self.spindle(reverse);
                    self.feed_to(r)?;
                    self.dwell(cycle.p);
                    self.spindle(forward);
                    if depth == bottom {
                        break;
                    }
                }
                self.rapid_to(back)
            }
            CycleKind::BoreManualRetract => {
                // Spec 1.51: the operator retracts by hand and presses cycle start; vcnc stops
                // there and goes on from the bottom.
                let running = self.exec.kernel.spindle.state();
                self.feed_to(bottom)?;
                self.dwell(cycle.p);
                self.spindle(SpindleState::Stopped);
                self.out.push(
                    self.cmd,
                    SegmentKind::Stop {
                        kind: StopKind::Program,
                    },
                );
                self.feed_to(r)?;
                self.rapid_to(back)?;
                self.spindle(running);
                Ok(())
            }
            CycleKind::FineBoring => {
                let running = self.exec.kernel.spindle.state();
                self.feed_to(bottom)?;
                self.dwell(cycle.p);
                self.spindle(SpindleState::Oriented);
                // Off the wall, out, and back over the hole's centre.
                let centre = self.exec.kernel.program_position();
                self.shift_off(cycle, 1.0)?;
                self.rapid_to(back)?;
                self.shift_back(centre, cycle)?;
                self.spindle(running);
                Ok(())
            }
            CycleKind::BackBore => self.back_bore(cycle),
        }
    }

    /// G87 (spec 1.50): oriented and shifted off the axis, down through the hole to R below
    /// the part, back on the axis, spindle on, bore up to Z, dwell, orient and shift off, out
    /// to the initial level (never R), spindle on, back on the axis.
    fn back_bore(&mut self, cycle: &Cycle) -> Result<(), Alarm> {
        let running = self.exec.kernel.spindle.state();
        let centre = self.exec.kernel.program_position();
        self.spindle(SpindleState::Oriented);
        self.shift_off(cycle, -1.0)?;
        self.rapid_to(self.r_level)?;
        self.shift_back(centre, cycle)?;
        self.spindle(SpindleState::Clockwise);
        self.feed_to(self.bottom)?;
        self.dwell(cycle.p);
        self.spindle(SpindleState::Oriented);
        self.shift_off(cycle, -1.0)?;
        self.rapid_to(cycle.initial)?;
        self.spindle(running);
        self.shift_back(centre, cycle)
    }

    /// A rapid by Q along the shift direction (`sign` -1: against it), in the plane.
    fn shift_off(&mut self, cycle: &Cycle, sign: f64) -> Result<(), Alarm> {
        let (a, b, _) = cycle.axes;
        let (da, db) = shift(self.exec.kernel.setup.profile(), cycle);
        let mut off = self.exec.kernel.program_position();
        off[a] += sign * da;
        off[b] += sign * db;
        rapid(self.exec, self.cmd, self.out, off)
    }

    /// A rapid back over `centre` in the plane, at the present level.
    fn shift_back(&mut self, centre: [f64; AXES], cycle: &Cycle) -> Result<(), Alarm> {
        let (a, b, _) = cycle.axes;
        let mut target = self.exec.kernel.program_position();
        (target[a], target[b]) = (centre[a], centre[b]);
        rapid(self.exec, self.cmd, self.out, target)
    }

    /// G73 and G83 from the R level to the bottom, peck by peck; the last peck is shorter.
    fn peck(&mut self, cycle: &Cycle) -> Result<(), Alarm> {
        let q = cycle.q.unwrap_or(f64::INFINITY);
        self.check_pecks(q)?;
        let down = if self.bottom < self.r_level {
            -1.0
        } else {
            1.0
        };
        let mut depth = self.r_level;
        loop {
            let next = self.next_depth(depth, q);
            if depth != self.r_level && cycle.kind == CycleKind::Peck {
                // G83: back into the hole, stopping the clearance short of the last depth.
                self.rapid_to(self.short_of(
                    depth,
                    self.exec.kernel.setup.profile().cycles.peck_clearance,
                    down,
                ))?;
            }
            self.feed_to(next)?;
            depth = next;
            if depth == self.bottom {
                return Ok(());
            }
            match cycle.kind {
                CycleKind::Peck => self.rapid_to(self.r_level)?,
                _ => self.rapid_to(self.short_of(
                    depth,
                    self.exec.kernel.setup.profile().cycles.peck_retract,
                    down,
                ))?,
            }
        }
    }

    /// The level `distance` back from `depth` towards R, never beyond R: with a peck shorter
    /// than the clearance (or the G73 retract) the tool would otherwise rapid out of the hole
    /// past R and feed the whole way back.
    fn short_of(&self, depth: f64, distance: f64, down: f64) -> f64 {
        let level = depth - down * distance;
        if (level - self.r_level) * down < 0.0 {
            self.r_level
        } else {
            level
        }
    }

    /// Refuses a peck depth so small the hole would take more pecks than [`MAX_COUNT`].
    fn check_pecks(&self, q: f64) -> Result<(), Alarm> {
        if (self.bottom - self.r_level).abs() / q > MAX_COUNT as f64 {
            return Err(Alarm::error(
                AlarmCode::CycleData,
                self.cmd.span,
                format!("Q is so small that a hole would take more than {MAX_COUNT} pecks"),
            ));
        }
        Ok(())
    }

    /// One peck of `q` deeper than `depth`, the last one shortened to end at the bottom.
    fn next_depth(&self, depth: f64, q: f64) -> f64 {
        if (self.bottom - depth).abs() <= q {
            self.bottom
        } else if self.bottom < depth {
            depth - q
        } else {
            depth + q
        }
    }

    fn rapid_to(&mut self, level: f64) -> Result<(), Alarm> {
        let target = self.at(level);
        rapid(self.exec, self.cmd, self.out, target)
    }

    fn feed_to(&mut self, level: f64) -> Result<(), Alarm> {
        let target = self.at(level);
        let to = self.exec.machine_target(&target, true);
        if to == self.exec.kernel.position {
            return Ok(());
        }
        let feed = self.exec.cutting_feed(self.cmd)?;
        let motion = self.exec.move_to(to, self.cmd, self.out)?;
        self.out.push(self.cmd, SegmentKind::Line { motion, feed });
        Ok(())
    }

    /// A feed move to `level` at `feed` (the feed in force comes back after it).
    fn feed_to_at(&mut self, level: f64, feed: f64) -> Result<(), Alarm> {
        let in_force = self.exec.kernel.feed.replace(feed);
        let moved = self.feed_to(level);
        self.exec.kernel.feed = in_force;
        moved
    }

    /// Where the tool is, with the drilling axis at `level` (program coordinates).
    fn at(&self, level: f64) -> [f64; AXES] {
        let mut target = self.exec.kernel.program_position();
        target[self.d] = level;
        target
    }

    fn dwell(&mut self, seconds: f64) {
        if seconds > 0.0 {
            self.out.push(self.cmd, SegmentKind::Dwell { seconds });
        }
    }

    fn spindle(&mut self, state: SpindleState) {
        let event = self.exec.kernel.spindle.turn(state);
        self.out.push(self.cmd, event);
    }
}

/// A rapid to a program-coordinate point.
fn rapid(
    exec: &mut Executor,
    cmd: &Command,
    out: &mut Output,
    target: [f64; AXES],
) -> Result<(), Alarm> {
    let to = exec.machine_target(&target, true);
    exec.rapid_to(to, cmd, out)
}

/// G76's shift at the bottom: Q along the profile's direction, in the positioning plane.
fn shift(profile: &Profile, cycle: &Cycle) -> (f64, f64) {
    let q = cycle.q.unwrap_or(0.0);
    match profile.cycles.boring_shift {
        ShiftDirection::PlusFirst => (q, 0.0),
        ShiftDirection::MinusFirst => (-q, 0.0),
        ShiftDirection::PlusSecond => (0.0, q),
        ShiftDirection::MinusSecond => (0.0, -q),
    }
}

fn spindle_words(state: SpindleState) -> &'static str {
    match state {
        SpindleState::Clockwise => "turning clockwise (M03)",
        SpindleState::CounterClockwise => "turning counter-clockwise (M04)",
        SpindleState::Stopped => "stopped",
        SpindleState::Oriented => "oriented and stopped",
    }
}

/// A level as the message shows it: up to three decimals, no trailing zeros.
fn number(value: f64) -> String {
    let text = format!("{value:.3}");
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}
