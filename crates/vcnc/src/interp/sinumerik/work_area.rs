//! SINUMERIK's working-area limitation in the basic coordinate system (PGsl 6.3, L9888-10010):
//! G25 and G26 with axis words set the lower and upper limit of each axis written, WALIMON
//! (the power-on state) and WALIMOF switch the limitation on and off. And the limitation in
//! the workpiece coordinate system (PGsl 14.3.2, L10012-10090): ten groups of limits per axis
//! and direction, written to `$P_WORKAREA_CS_LIMIT_PLUS/MINUS[group, axis]` and valid where
//! `$P_WORKAREA_CS_PLUS/MINUS_ENABLE` is TRUE; WALCS1-WALCS10 select a group, WALCS0 (the
//! power-on state) none. The two work independently: whichever limit a move reaches first
//! stops it.
//!
//! The manual: "all tool motions outside the area defined by G25/G26 are prohibited"; a tool
//! outside the area stops the program with an alarm. vcnc checks the moves each block makes,
//! end points and path (an arc also through its extremes: the travel check of
//! [`crate::checks`], given the area's limits), and a move leaving the area becomes the
//! control's alarm 10730 at its block, with the block's moves left out: the position stays at
//! the block's start.
//!
//! **Choices**: the limits are compared with the machine coordinates of the stream (vcnc's
//! three-axis mill has no kinematic between the basic and the machine system), and the tool's
//! radius is not added (MD21020 $MC_WORKAREA_WITH_TOOL_RADIUS is 0 by default). A limit
//! stays set when WALIMOF switches the check off, as the manual's example (L9941-9960)
//! relies on.
//!
//! The WCS limits are compared with the program coordinates of every move, the map of the
//! frames in force undone (the chain with its rotations: a swivelled plane's Z is the WCS Z),
//! lines and rapids by their ends (a box holds the segment between two of its points), arcs
//! also at the angles where a coordinate turns and every degree of a helix. A move leaving a
//! limit stops the program at its block, as 10730 does, with the control's alarm 10745
//! (**inferred** number: the manual's text gives none; "programmed end position beyond the
//! working area limitation in the WCS/SZS"). **Choices**: `$P_WORKAREA_CS_COORD_SYSTEM` 3
//! (the settable zero system) is read as the WCS: vcnc has no separate SZS frame; the tool
//! radius is not added (as for G25/G26); the limits are millimetres as written; with a
//! kinematic transform on (CYCLE800, TRAORI) the WCS check is left out: the stream then
//! carries joints, not the tip.
//!
//! Never: alarm at a move inside the area, or keep a move that leaves it.

use crate::alarm::{Alarm, AlarmCode};
use crate::checks::{ReleasedCheck, TravelCheck};
use crate::interp::kernel::Kernel;
use crate::machine::{Machine, AXES};
use crate::motion::{ArcDirection, Item, Segment, StreamItem, WorkTransform};

/// One working-area limitation group of the WCS (`$P_WORKAREA_CS_...[n, axis]`).
#[derive(Clone, Copy, Debug)]
struct CsGroup {
    plus: [Option<f64>; AXES],
    minus: [Option<f64>; AXES],
    plus_value: [f64; AXES],
    minus_value: [f64; AXES],
    plus_enable: [bool; AXES],
    minus_enable: [bool; AXES],
}

impl Default for CsGroup {
    fn default() -> CsGroup {
        CsGroup {
            plus: [None; AXES],
            minus: [None; AXES],
            plus_value: [0.0; AXES],
            minus_value: [0.0; AXES],
            plus_enable: [false; AXES],
            minus_enable: [false; AXES],
        }
    }
}

impl CsGroup {
    /// The limits in force: each value where its direction is enabled.
    fn refresh(&mut self) {
        for i in 0..AXES {
            self.plus[i] = self.plus_enable[i].then_some(self.plus_value[i]);
            self.minus[i] = self.minus_enable[i].then_some(self.minus_value[i]);
        }
    }

    /// The first axis of `p` (program coordinates) beyond a limit: (axis, limit, plus side).
    fn beyond(&self, p: &[f64; AXES]) -> Option<(usize, f64, bool)> {
        const EPS: f64 = 1e-9;
        (0..AXES).find_map(|i| {
            if let Some(limit) = self.plus[i].filter(|l| p[i] > l + EPS) {
                return Some((i, limit, true));
            }
            self.minus[i]
                .filter(|l| p[i] < l - EPS)
                .map(|limit| (i, limit, false))
        })
    }
}

/// The part of `$P_WORKAREA_CS_...` a write names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum CsVariable {
    LimitPlus,
    LimitMinus,
    PlusEnable,
    MinusEnable,
    CoordSystem,
}

impl CsVariable {
    /// The variable `name` (upper case, with its `$`), if it is one of the group's.
    pub(super) fn named(name: &str) -> Option<CsVariable> {
        Some(match name.strip_prefix("$P_WORKAREA_CS_")? {
            "LIMIT_PLUS" => CsVariable::LimitPlus,
            "LIMIT_MINUS" => CsVariable::LimitMinus,
            "PLUS_ENABLE" => CsVariable::PlusEnable,
            "MINUS_ENABLE" => CsVariable::MinusEnable,
            "COORD_SYSTEM" => CsVariable::CoordSystem,
            _ => return None,
        })
    }
}

/// The limits G25/G26 set, and whether WALIMON is in force.
#[derive(Clone, Debug)]
pub(super) struct WorkArea {
    low: [f64; AXES],
    high: [f64; AXES],
    off: bool,
    /// The travel check of the area, built when a limit is set (None: no limit yet).
    check: Option<TravelCheck>,
    /// The WCS groups 1-10 (index 0 unused) and the one WALCS1-WALCS10 selected (0: WALCS0).
    cs: [CsGroup; 11],
    cs_coord_system: [i32; 11],
    cs_active: usize,
}

impl Default for WorkArea {
    fn default() -> WorkArea {
        WorkArea {
            low: [f64::NEG_INFINITY; AXES],
            high: [f64::INFINITY; AXES],
            off: false,
            check: None,
            cs: [CsGroup::default(); 11],
            cs_coord_system: [1; 11],
            cs_active: 0,
        }
    }
}

impl WorkArea {
    /// G25 (`upper` false) or G26 (true) with `limits` (mm, None for an axis not written) on
    /// `machine`.
    pub(super) fn set(&mut self, upper: bool, limits: [Option<f64>; AXES], machine: &Machine) {
        let bounds = if upper { &mut self.high } else { &mut self.low };
        for (bound, limit) in bounds.iter_mut().zip(limits) {
            if let Some(limit) = limit {
                *bound = limit;
            }
        }
        // The machine's own check, given the area as its travel.
        let mut area = machine.clone();
        for (i, axis) in area.axes.iter_mut().enumerate() {
            if let Some(axis) = axis {
                axis.min = self.low[i];
                axis.max = self.high[i];
            }
        }
        self.check = Some(TravelCheck::new(&area));
    }

    /// WALIMON (`on` true) or WALIMOF.
    pub(super) fn switch(&mut self, on: bool) {
        self.off = !on;
    }

    /// WALCS0-WALCS10 (`name`): the WCS group selected; false for any other name.
    pub(super) fn select_cs(&mut self, name: &str) -> bool {
        match name
            .strip_prefix("WALCS")
            .and_then(|n| n.parse::<usize>().ok())
        {
            Some(n) if n <= 10 && !name[5..].starts_with('+') => {
                self.cs_active = n;
                true
            }
            _ => false,
        }
    }

    /// The group and axis of a `$P_WORKAREA_CS_...` write or read: group 1-10, else alarm.
    fn group(group: f64, span: crate::source::Span) -> Result<usize, Alarm> {
        if (1.0..=10.0).contains(&group) && group.fract() == 0.0 {
            return Ok(group as usize);
        }
        Err(Alarm::error(
            AlarmCode::BadVariable,
            span,
            format!("working-area limitation group {group}: the groups are 1 to 10"),
        ))
    }

    /// `$P_WORKAREA_CS_...[group, axis] = value` (`axis` unused for COORD_SYSTEM).
    pub(super) fn write_cs(
        &mut self,
        variable: CsVariable,
        (group, axis): (f64, usize),
        value: f64,
        span: crate::source::Span,
    ) -> Result<(), Alarm> {
        let n = WorkArea::group(group, span)?;
        let g = &mut self.cs[n];
        match variable {
            CsVariable::LimitPlus => g.plus_value[axis] = value,
            CsVariable::LimitMinus => g.minus_value[axis] = value,
            CsVariable::PlusEnable => g.plus_enable[axis] = value != 0.0,
            CsVariable::MinusEnable => g.minus_enable[axis] = value != 0.0,
            CsVariable::CoordSystem => {
                if value != 1.0 && value != 3.0 {
                    return Err(Alarm::error(
                        AlarmCode::BadVariable,
                        span,
                        format!("$P_WORKAREA_CS_COORD_SYSTEM is 1 (WCS) or 3 (SZS), not {value}"),
                    ));
                }
                self.cs_coord_system[n] = value as i32;
            }
        }
        g.refresh();
        Ok(())
    }

    /// The value of `$P_WORKAREA_CS_...[group, axis]` (a BOOL as 0 or 1).
    pub(super) fn read_cs(
        &self,
        variable: CsVariable,
        (group, axis): (f64, usize),
        span: crate::source::Span,
    ) -> Result<f64, Alarm> {
        let g = &self.cs[WorkArea::group(group, span)?];
        Ok(match variable {
            CsVariable::LimitPlus => g.plus_value[axis],
            CsVariable::LimitMinus => g.minus_value[axis],
            CsVariable::PlusEnable => f64::from(u8::from(g.plus_enable[axis])),
            CsVariable::MinusEnable => f64::from(u8::from(g.minus_enable[axis])),
            CsVariable::CoordSystem => {
                f64::from(self.cs_coord_system[WorkArea::group(group, span)?])
            }
        })
    }

    /// The moves the kernel made since it had `from` items waiting, checked against the area:
    /// the first that leaves it is cut with the rest and becomes alarm 10730.
    #[inline]
    pub(super) fn check(&mut self, kernel: &mut Kernel, from: usize) -> Result<(), Alarm> {
        // The common block: no limit of the working area in force.
        if self.cs_active == 0 && (self.off || self.check.is_none()) {
            return Ok(());
        }
        self.check_moves(kernel, from)
    }

    /// [`WorkArea::check`] with a limitation in force.
    // Out of line: the check before it is inlined into every block's step.
    #[inline(never)]
    fn check_moves(&mut self, kernel: &mut Kernel, from: usize) -> Result<(), Alarm> {
        self.check_cs(kernel, from)?;
        if self.off {
            return Ok(());
        }
        let Some(check) = self.check.as_mut() else {
            return Ok(());
        };
        // A fresh copy each time: the check remembers that it stopped.
        let mut check = check.clone();
        let Some(travel) =
            kernel.check_waiting(from, |items, range| check.check_released(items, range))
        else {
            return Ok(());
        };
        // The travel check's words, told of the working area instead.
        let message = travel
            .message
            .replace(" overtravel", "")
            .replace("the machine's travel limit", "the limit G25/G26 set");
        Err(Alarm {
            code: AlarmCode::Overtravel,
            message: format!("alarm 10730 working area limitation: {message}"),
            help: Some(
                "move inside the limits of G25 and G26, or switch the limitation off with WALIMOF"
                    .into(),
            ),
            ..travel
        })
    }
}

impl WorkArea {
    /// The moves since `from` against the WCS group WALCS selected: the first that leaves it
    /// is cut with the rest and becomes alarm 10745.
    fn check_cs(&self, kernel: &mut Kernel, from: usize) -> Result<(), Alarm> {
        if self.cs_active == 0 || kernel.state_and_output().1.kinematics_mut().is_some() {
            return Ok(());
        }
        let group = self.cs[self.cs_active];
        if group.plus.iter().chain(&group.minus).all(Option::is_none) {
            return Ok(());
        }
        let Some(back) = kernel.state().frames.work_transform().inverse() else {
            return Ok(());
        };
        let n = self.cs_active;
        kernel
            .check_waiting(from, |items, range| {
                cut_at_first_beyond(items, range, &group, &back, n)
            })
            .map_or(Ok(()), Err)
    }
}

/// Cuts `items` at the first move of `range` that leaves `group` (program coordinates through
/// `back`) and adds its alarm; true when none does.
fn cut_at_first_beyond(
    items: &mut Vec<StreamItem>,
    range: std::ops::Range<usize>,
    group: &CsGroup,
    back: &WorkTransform,
    n: usize,
) -> bool {
    for k in range {
        let Ok(Item::Segment(segment)) = &items[k] else {
            continue;
        };
        let Some(found) = points(segment, back).find_map(|p| group.beyond(&p)) else {
            continue;
        };
        let (axis, limit, plus) = found;
        let name = ["X", "Y", "Z", "A", "B", "C"][axis];
        let alarm = Alarm::error(
            AlarmCode::Overtravel,
            segment.span,
            format!(
                "alarm 10745 working area limitation in the WCS: axis {name} goes beyond its {} limit {limit} of group {n} (WALCS{n})",
                if plus { "plus" } else { "minus" },
            ),
        )
        .with_help(format!(
            "stay within the $P_WORKAREA_CS limits of group {n}, or deselect them with WALCS0"
        ));
        items.truncate(k);
        items.push(Err(alarm));
        return false;
    }
    true
}

/// The points of `segment` the WCS check looks at, program coordinates: a line's or a rapid's
/// ends; an arc's ends, the angles where a program coordinate turns back (its extremes, exact
/// for a flat arc) and, for a helix, every degree.
fn points<'a>(
    segment: &'a Segment,
    back: &'a WorkTransform,
) -> impl Iterator<Item = [f64; AXES]> + 'a {
    let (motion, arc) = match segment.kind.path() {
        Some((motion, arc)) => (Some(motion), arc),
        None => (None, None),
    };
    let ends = motion
        .into_iter()
        .flat_map(move |m| [back.to_machine(&m.from.0), back.to_machine(&m.to.0)]);
    let along = motion.zip(arc).into_iter().flat_map(move |(m, arc)| {
        let c = arc.center.0;
        let (a, b, h) = arc.plane.axes();
        let start = (m.from.0[b] - c[b]).atan2(m.from.0[a] - c[a]);
        let radius = (m.from.0[a] - c[a]).hypot(m.from.0[b] - c[b]);
        let ccw = arc.direction == ArcDirection::CounterClockwise;
        let tau = std::f64::consts::TAU;
        let sweep = arc.sweep(m);
        let rise = m.to.0[h] - m.from.0[h];
        let at = move |t: f64| {
            let phi = if ccw { start + t } else { start - t };
            let mut p = m.to.0;
            p[a] = c[a] + radius * phi.cos();
            p[b] = c[b] + radius * phi.sin();
            p[h] = m.from.0[h] + rise * t / sweep;
            back.to_machine(&p)
        };
        // Where program coordinate i of the flat circle turns: d/dphi (u_i cos + v_i sin) = 0.
        let mut ts: Vec<f64> = (0..3)
            .flat_map(|i| {
                let (u, v) = (back.linear[i][a], back.linear[i][b]);
                let phi = v.atan2(u);
                [phi, phi + std::f64::consts::PI]
            })
            .flat_map(|phi| {
                let t = if ccw { phi - start } else { start - phi }.rem_euclid(tau);
                (0..=arc.extra_turns).map(move |k| t + tau * f64::from(k))
            })
            .filter(|t| *t <= sweep)
            .collect();
        if rise.abs() > 1e-9 {
            let steps = (sweep.to_degrees().ceil() as usize).min(36_000);
            ts.extend((1..steps).map(|k| sweep * k as f64 / steps as f64));
        }
        ts.into_iter().map(at)
    });
    ends.chain(along)
}
