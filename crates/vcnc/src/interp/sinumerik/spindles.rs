//! Spindles by number (PGsl 6.1, 7.4; docs/SINUMERIK.md 10.3): `S2=`, `M2=3`, `SPOS[n]=`,
//! `SPOSA[n]=`, `SPOS=IC(..)`, `WAITS`, `LIMS[n]=`, `SVC[n]=`, `G26 S2=`, `FA[S2]=`, on the
//! spindles the machine file declares (`[spindle] count`; spindle 1 is the master spindle).
//!
//! The master spindle's words go to the block's words as `S`, `LIMS`, `SVC` and `SPOS` do;
//! the other spindles turn in this module's state only: nothing of a milling path depends on
//! them, so the stream's spindle events stay the master's.
//!
//! Never: accept a spindle the machine does not have; the alarm names it and the machine
//! file's count.

use super::block::{self, Words};
use super::predefined::written;
use super::Sinumerik;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::kernel::Kernel;
use crate::motion::SpindleState;
use crate::syntax::sinumerik::{Block, Expr, ExprKind, Value, Word};

/// What the program set of a spindle other than the master spindle: kept as the control keeps
/// it, though nothing vcnc models reads it yet (no milling path depends on it).
#[allow(dead_code)]
#[derive(Clone, Debug, Default)]
pub(super) struct OtherSpindle {
    /// S<n>=: the speed, rpm.
    speed: Option<f64>,
    /// M<n>=3, 4, 5, 19.
    state: Option<SpindleState>,
    /// SVC[n]: the cutting rate, m/min.
    rate: Option<f64>,
    /// SVC[n] was programmed in the block being run: its speed is still to be computed.
    rate_pending: bool,
    /// LIMS[n], G25 S<n>=, G26 S<n>=.
    lims: Option<f64>,
    min: Option<f64>,
    max: Option<f64>,
    /// FA[S<n>]: the positioning speed, deg/min.
    positioning_speed: Option<f64>,
}

/// The spindles of the machine: how many, the master spindle's position, the others' state.
#[allow(dead_code)]
#[derive(Clone, Debug)]
pub(super) struct Spindles {
    count: u32,
    /// SETMS: the master spindle's number (1 at power-on).
    master: u32,
    /// The master spindle's angle after its last SPOS, degrees (0 to 360).
    master_angle: f64,
    /// FA[S1]: the master spindle's positioning speed, deg/min.
    master_positioning_speed: Option<f64>,
    /// Spindle angles of the others after SPOS, by number - 1 (the master's unused).
    angles: Vec<f64>,
    /// The others' state, by number - 1 (the master's is the kernel's while it is master).
    others: Vec<OtherSpindle>,
}

impl Spindles {
    /// The `count` spindles of the machine file.
    pub(super) fn new(count: u32) -> Spindles {
        let others = count.max(1) as usize;
        Spindles {
            count,
            master: 1,
            master_angle: 0.0,
            master_positioning_speed: None,
            angles: vec![0.0; others],
            others: vec![OtherSpindle::default(); others],
        }
    }

    /// Spindle `n` of `word`, or the alarm of a spindle the machine lacks.
    pub(super) fn check(&self, n: f64, word: &Word) -> Result<u32, Alarm> {
        if n.fract() == 0.0 && n >= 1.0 && n <= f64::from(self.count) {
            return Ok(n as u32);
        }
        let plural = if self.count == 1 { "" } else { "s" };
        Err(Alarm::error(
            AlarmCode::AxisNotOnMachine,
            word.span,
            format!(
                "{}: the machine has no spindle {n} (its machine file declares {} spindle{plural})",
                written(word),
                self.count
            ),
        )
        .with_help("declare the machine's spindles in the machine file's [spindle] count (spindle 1 is the master spindle)"))
    }

    /// S<n>= of spindle `n` (2 and up), rpm; 0 before any.
    pub(super) fn programmed_speed(&self, n: u32) -> f64 {
        self.others
            .get((n as usize).saturating_sub(1))
            .and_then(|other| other.speed)
            .unwrap_or(0.0)
    }

    /// Spindle `n` turns at `rpm`, set by other than its S word: SVC of a toolholder's spindle,
    /// GWPS (grinding.rs).
    pub(super) fn set_speed(&mut self, n: u32, rpm: f64) {
        self.other(n).speed = Some(rpm);
    }

    fn other(&mut self, n: u32) -> &mut OtherSpindle {
        &mut self.others[n as usize - 1]
    }

    /// How many spindles the machine has.
    pub(super) fn count(&self) -> u32 {
        self.count
    }

    /// The master spindle's number (SETMS).
    pub(super) fn master(&self) -> u32 {
        self.master
    }

    /// True when an SVC waits for its spindle's speed ([`Spindles::take_pending_rates`]).
    pub(super) fn any_rate_pending(&self) -> bool {
        self.others.iter().any(|other| other.rate_pending)
    }

    /// The spindles whose SVC[n] of this block waits for the radius, with their rates; their
    /// wait ends.
    pub(super) fn take_pending_rates(&mut self) -> Vec<(u32, f64)> {
        let mut pending = Vec::new();
        for (i, other) in self.others.iter_mut().enumerate() {
            if std::mem::take(&mut other.rate_pending) {
                pending.extend(other.rate.map(|rate| (i as u32 + 1, rate)));
            }
        }
        pending
    }

    /// SETMS(n): spindle `n` becomes the master; the old master keeps turning as the kernel's
    /// spindle turned (`speed`, `state`). Gives the new master's speed and state for the
    /// kernel.
    pub(super) fn switch_master(
        &mut self,
        n: u32,
        speed: f64,
        state: SpindleState,
    ) -> (f64, SpindleState) {
        let old = self.master;
        let (old_angle, old_feed) = (self.master_angle, self.master_positioning_speed);
        let kept = self.other(old);
        kept.speed = Some(speed);
        kept.state = Some(state);
        kept.positioning_speed = old_feed;
        self.angles[old as usize - 1] = old_angle;
        self.master = n;
        self.master_angle = self.angles[n as usize - 1];
        let new = self.other(n).clone();
        self.master_positioning_speed = new.positioning_speed;
        (
            new.speed.unwrap_or(0.0),
            new.state.unwrap_or(SpindleState::Stopped),
        )
    }

    /// Spindle `n`'s speed (n 2 or more), for the tests of what sets it.
    #[cfg(test)]
    pub(super) fn speed(&self, n: u32) -> Option<f64> {
        self.others.get(n as usize - 1)?.speed
    }
}

/// Reads a word addressing a spindle by number; false for other words. Master-spindle words
/// become the block's `S`, `M`, `LIMS`, `SVC` and `SPOS`. The caller has made sure no variable
/// of the program has the word's name.
pub(super) fn read_word(
    front: &mut Sinumerik,
    kernel: &Kernel,
    block: &Block,
    word: &Word,
    words: &mut Words<'_>,
) -> Result<bool, Alarm> {
    let address = &*word.address;
    let number_after = |letter: &str| {
        address
            .strip_prefix(letter)
            .filter(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
            .and_then(|n| n.parse::<u32>().ok())
    };
    match (address, &word.value) {
        ("SPOS" | "SPOSA", _) => {
            let (n, angle) = position(front, kernel, word)?;
            if n == front.spindles.master {
                words.spos = Some((angle, word.span));
            }
        }
        ("WAITS", Value::Bare) => {}
        ("WAITS", Value::Call(arguments)) => {
            for argument in arguments.iter().flatten() {
                let n = front.value(kernel, argument)?;
                front.spindles.check(n, word)?;
            }
        }
        ("LIMS" | "SVC", Value::Indexed(indices, Some(expr))) => {
            let n = spindle_index(front, kernel, indices, word)?;
            let value = front.value(kernel, expr)?;
            if value < 0.0 {
                return Err(negative(word));
            }
            let master = front.spindles.master;
            match (n, address) {
                (n, "LIMS") if n == master => words.lims = Some((value, word.span)),
                (n, _) if n == master => words.svc = Some((value, word.span)),
                (n, "LIMS") => front.spindles.other(n).lims = Some(value),
                (n, _) => {
                    // Its speed comes from the active offset's radius once the block's tool
                    // and D are in (PGsl 6.2 ex. 3: SVC[3]=100 M6 T1 D1).
                    let other = front.spindles.other(n);
                    other.rate = Some(value);
                    other.rate_pending = true;
                }
            }
        }
        ("FA", Value::Indexed(indices, Some(expr))) if named_spindle(indices).is_some() => {
            let n = match named_spindle(indices) {
                Some(NamedSpindle::Number(n)) => n,
                Some(NamedSpindle::Expression(e)) => front.value(kernel, e)?,
                None => unreachable!("matched above"),
            };
            let n = front.spindles.check(n, word)?;
            let speed = front.value(kernel, expr)?;
            if speed < 0.0 {
                return Err(negative(word));
            }
            if n == front.spindles.master {
                front.spindles.master_positioning_speed = Some(speed);
            } else {
                front.spindles.other(n).positioning_speed = Some(speed);
            }
        }
        // S0= is the master spindle's speed, as S<master>= is (PGsl 6.1).
        _ if number_after("S").is_some_and(|n| n == 0 || n == front.spindles.master) => {
            words.speed = Some((block::number(front, kernel, word)?, word.span));
        }
        _ if number_after("M") == Some(front.spindles.master) && front.spindles.master != 1 => {
            let code = block::whole(front, kernel, word)?;
            words.m.push((code, word.span));
        }
        _ if number_after("S").is_some_and(|n| n >= 1) => {
            let n = front
                .spindles
                .check(f64::from(number_after("S").unwrap_or(0)), word)?;
            let speed = block::number(front, kernel, word)?;
            if speed < 0.0 {
                return Err(negative(word));
            }
            // G25 and G26 make S<n> the spindle's limits (PGsl 6.5), wherever they stand in
            // the block.
            let lower_limit = block
                .words
                .iter()
                .find_map(|w| match (&*w.address, &w.value) {
                    ("G", Value::Constant(g)) if g.value == 25.0 || g.value == 26.0 => {
                        Some(g.value == 25.0)
                    }
                    _ => None,
                });
            let other = front.spindles.other(n);
            match lower_limit {
                Some(true) => other.min = Some(speed),
                Some(false) => other.max = Some(speed),
                None => other.speed = Some(speed),
            }
        }
        _ if number_after("M").is_some_and(|n| n >= 1 && n != front.spindles.master) => {
            let n = front
                .spindles
                .check(f64::from(number_after("M").unwrap_or(0)), word)?;
            let code = block::whole(front, kernel, word)?;
            let state = match code {
                3 => SpindleState::Clockwise,
                4 => SpindleState::CounterClockwise,
                5 => SpindleState::Stopped,
                19 => SpindleState::Oriented,
                // Axis mode (PGsl 7.4): the spindle then moves by its axis name, which vcnc
                // moves as the machine file's rotary axis of that name; vcnc does not tie the
                // two, so the switch itself is a note.
                70 => {
                    if front.noted.insert(format!("M{n}=70")) {
                        words.warnings.push(Alarm::warning(
                            AlarmCode::KeptAsState,
                            word.span,
                            format!("M{n}=70 switches spindle {n} to axis mode: vcnc does not tie a spindle to an axis; the program's rotary axis words move the machine file's axis of that name"),
                        ));
                    }
                    return Ok(true);
                }
                code => {
                    return Err(Alarm::error(
                        AlarmCode::NotSupportedYet,
                        word.span,
                        format!("M{n}={code}: vcnc runs M3, M4, M5 and M19 of spindle {n}"),
                    ))
                }
            };
            front.spindles.other(n).state = Some(state);
        }
        _ => return Ok(false),
    }
    Ok(true)
}

/// SPOS / SPOSA, bare or `[n]`, with a plain angle or AC, IC, DC, ACP, ACN: the spindle and its
/// new angle (0 to 360). IC turns from the last position; the others go to the angle
/// (vcnc does not time the turn, so the direction changes nothing it models).
fn position(front: &mut Sinumerik, kernel: &Kernel, word: &Word) -> Result<(u32, f64), Alarm> {
    let (n, expr) = match &word.value {
        Value::Indexed(indices, Some(expr)) => (spindle_index(front, kernel, indices, word)?, expr),
        Value::Expression(expr) => (front.spindles.master, expr),
        Value::Constant(c) => {
            let angle = c.value.rem_euclid(360.0);
            front.spindles.master_angle = angle;
            return Ok((front.spindles.master, angle));
        }
        _ => {
            return Err(Alarm::error(
                AlarmCode::MissingValue,
                word.span,
                format!("{} needs the spindle's angle: SPOS=90", word.address),
            ))
        }
    };
    let (incremental, value) = match &expr.kind {
        ExprKind::Call(name, args) if matches!(&**name, "AC" | "IC" | "DC" | "ACP" | "ACN") => {
            let [Some(arg)] = args.as_slice() else {
                return Err(Alarm::error(
                    AlarmCode::MacroSyntax,
                    word.span,
                    format!("{name}(..) takes one value"),
                ));
            };
            (&**name == "IC", front.value(kernel, arg)?)
        }
        _ => (false, front.value(kernel, expr)?),
    };
    let spindles = &mut front.spindles;
    let angle = if n == spindles.master {
        &mut spindles.master_angle
    } else {
        &mut spindles.angles[n as usize - 1]
    };
    *angle = if incremental { *angle + value } else { value }.rem_euclid(360.0);
    Ok((n, *angle))
}

/// A spindle where an axis may stand (`FA[S2]`, `FA[SPI(2)]`; PGsl 7.5).
enum NamedSpindle<'e> {
    Number(f64),
    Expression(&'e Expr),
}

fn named_spindle(indices: &[Expr]) -> Option<NamedSpindle<'_>> {
    match indices {
        [Expr {
            kind: ExprKind::Name(name),
            ..
        }] => name
            .strip_prefix('S')
            .filter(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
            .and_then(|n| n.parse().ok())
            .map(NamedSpindle::Number),
        [Expr {
            kind: ExprKind::Call(name, arguments),
            ..
        }] if &**name == "SPI" => match arguments.as_slice() {
            [Some(n)] => Some(NamedSpindle::Expression(n)),
            _ => None,
        },
        _ => None,
    }
}

/// The spindle number of `[n]`, checked against the machine.
fn spindle_index(
    front: &mut Sinumerik,
    kernel: &Kernel,
    indices: &[Expr],
    word: &Word,
) -> Result<u32, Alarm> {
    let [index] = indices else {
        return Err(Alarm::error(
            AlarmCode::MacroSyntax,
            word.span,
            format!("{}[n] takes one spindle number", word.address),
        ));
    };
    let n = front.value(kernel, index)?;
    front.spindles.check(n, word)
}

fn negative(word: &Word) -> Alarm {
    Alarm::error(
        AlarmCode::ValueOutOfRange,
        word.span,
        format!("{}: a spindle's speed cannot be negative", written(word)),
    )
}
