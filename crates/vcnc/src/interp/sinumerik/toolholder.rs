//! Toolholders and the spindles they are assigned to (PGsl 6.2 SVC, examples 4 and 5,
//! L1994-2073; docs/SINUMERIK.md 10.7): the buffer magazine's locations (`$TC_MPP1[9998,n]=2`
//! a toolholder, `$TC_MPP5[9998,n]` its number, `$TC_MPP_SP[9998,n]` its spindle), a tool's
//! name (`$TC_TP2[t]="WZ2"`), and the master toolholder `SETMTH(n)`, into which M6 loads the
//! tool.
//!
//! With MD20124 `$MC_TOOL_MANAGEMENT_TOOLHOLDER` above 1, SVC acts on the spindle of the
//! toolholder that holds the tool of the active offset (ex. A-26: toolholder 1 on spindle 3);
//! otherwise on the master spindle, as before. Which offset a tool change leaves active is
//! MD20270 `$MC_CUTTING_EDGE_DEFAULT` (`tools.rs`).
//!
//! Never: write a magazine other than the buffer (9998), whose locations are the toolholders
//! and spindles; the real magazines stay outside the product (V022).

use super::predefined::written;
use super::Sinumerik;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::kernel::{Kernel, Origin};
use crate::machine::ToolEdge;
use crate::syntax::sinumerik::{ExprKind, Value, Word};

/// The buffer magazine: its locations are the spindles and toolholders (PGsl 6.2, L1994).
const BUFFER: f64 = 9998.0;

/// One location of the buffer magazine.
#[derive(Clone, Copy, Debug, Default)]
struct Location {
    /// $TC_MPP1: the location's kind (2: a toolholder or spindle).
    kind: Option<u32>,
    /// $TC_MPP5: the toolholder's number.
    holder: Option<u32>,
    /// $TC_MPP_SP: the spindle the toolholder is assigned to.
    spindle: Option<u32>,
}

/// The toolholders, the master toolholder and what each holds.
#[derive(Clone, Debug, Default)]
pub(super) struct Toolholders {
    /// By location number - 1.
    locations: Vec<Location>,
    /// SETMTH: the master toolholder (None: 1, MD20126's default).
    master: Option<u32>,
    /// The tools M6 loaded, and the toolholder each went into.
    loaded: Vec<(u32, u32)>,
    /// SETMS of the block being run: the master spindle from its end.
    new_master: Option<u32>,
}

impl Toolholders {
    /// The spindle toolholder `holder` is assigned to: its $TC_MPP_SP, else the spindle of
    /// its number (toolholder = spindle, MD20124 = 0).
    fn spindle(&self, holder: u32) -> u32 {
        self.locations
            .iter()
            .find(|l| l.kind == Some(2) && l.holder == Some(holder))
            .and_then(|l| l.spindle)
            .unwrap_or(holder)
    }
}

/// Reads $TC_MPP1, $TC_MPP5, $TC_MPP_SP, $TC_TP2 and SETMTH; false for other words.
pub(super) fn read_word(
    front: &mut Sinumerik,
    kernel: &Kernel,
    word: &Word,
) -> Result<bool, Alarm> {
    let address = &*word.address;
    match (address, &word.value) {
        ("$TC_MPP1" | "$TC_MPP5" | "$TC_MPP_SP", Value::Indexed(indices, Some(expr))) => {
            let [magazine, location] = indices.as_slice() else {
                return Err(syntax(
                    word,
                    "takes the magazine and the location: [9998,1]",
                ));
            };
            if front.value(kernel, magazine)? != BUFFER {
                return Err(Alarm::error(
                    AlarmCode::NotInProduct,
                    word.span,
                    format!("{}: vcnc keeps the buffer magazine 9998 (the toolholders and spindles); the real magazines belong to the control's tool management, which vcnc does not simulate", written(word)),
                ));
            }
            let location = whole(front.value(kernel, location)?, word)?;
            let value = whole(front.value(kernel, expr)?, word)?;
            let locations = &mut front.toolholders.locations;
            let index = location.max(1) as usize - 1;
            if locations.len() <= index {
                locations.resize(index + 1, Location::default());
            }
            let slot = &mut locations[index];
            match address {
                "$TC_MPP1" => slot.kind = Some(value),
                "$TC_MPP5" => slot.holder = Some(value),
                _ => slot.spindle = Some(front.spindles.check(f64::from(value), word)?),
            }
        }
        ("$TC_TP2", Value::Indexed(indices, Some(expr))) => {
            let [tool] = indices.as_slice() else {
                return Err(syntax(word, "takes the tool: $TC_TP2[2]=\"WZ2\""));
            };
            let t = whole(front.value(kernel, tool)?, word)?;
            let ExprKind::Text(name) = &expr.kind else {
                return Err(syntax(word, "is the tool's name: $TC_TP2[2]=\"WZ2\""));
            };
            name_tool(&mut front.tools, t, name);
        }
        ("SETMTH", Value::Call(arguments)) => {
            front.toolholders.master = match arguments.as_slice() {
                [] | [None] => None,
                [Some(n)] => Some(whole(front.value(kernel, n)?, word)?),
                _ => return Err(syntax(word, "takes one toolholder: SETMTH(4)")),
            };
        }
        ("SETMTH", Value::Bare) => front.toolholders.master = None,
        // SETMS on a machine of one spindle is accepted and ignored (block.rs's note).
        ("SETMS", Value::Bare | Value::Call(_)) if front.spindles.count() > 1 => {
            let n = match &word.value {
                Value::Call(arguments) => match arguments.as_slice() {
                    [] | [None] => 1.0,
                    [Some(n)] => front.value(kernel, n)?,
                    _ => return Err(syntax(word, "takes one spindle: SETMS(3)")),
                },
                _ => 1.0,
            };
            front.toolholders.new_master = Some(front.spindles.check(n, word)?);
        }
        _ => return Ok(false),
    }
    Ok(true)
}

fn syntax(word: &Word, usage: &str) -> Alarm {
    Alarm::error(
        AlarmCode::MacroSyntax,
        word.span,
        format!("{} {usage}", word.address),
    )
}

fn whole(value: f64, word: &Word) -> Result<u32, Alarm> {
    if value.fract() != 0.0 || !(1.0..=f64::from(u16::MAX)).contains(&value) {
        return Err(Alarm::error(
            AlarmCode::ValueOutOfRange,
            word.span,
            format!(
                "{}: {value} is no number of a location, toolholder, spindle or tool",
                written(word)
            ),
        ));
    }
    Ok(value as u32)
}

/// $TC_TP2: every edge of tool `t` takes the name; a tool without edges gets its first.
fn name_tool(tools: &mut Vec<ToolEdge>, t: u32, name: &str) {
    let mut named = false;
    for edge in tools.iter_mut().filter(|e| e.t == t) {
        edge.name = Some(name.into());
        named = true;
    }
    if !named {
        tools.push(ToolEdge {
            name: Some(name.into()),
            ..program_edge(t, 1)
        });
    }
}

/// Edge `d` of tool `t` as a program's write of its data creates it: a milling tool (type 120)
/// without lengths, radius or name until the program gives them.
pub(super) fn program_edge(t: u32, d: u32) -> ToolEdge {
    ToolEdge {
        t,
        name: None,
        d,
        tool_type: 120,
        length: 0.0,
        length2: 0.0,
        length3: 0.0,
        radius: 0.0,
        teeth: None,
    }
}

/// M6 loaded tool `t`: into the master toolholder, or with each spindle its own toolholder
/// (MD20124 = 0, ex. A-27's "M6 corresponds to M3=6") into the master spindle.
pub(super) fn load(front: &mut Sinumerik, t: u32) {
    let holder = if front.settings.toolholder_management > 1 {
        front.toolholders.master.unwrap_or(1)
    } else {
        front.spindles.master()
    };
    let loaded = &mut front.toolholders.loaded;
    loaded.retain(|&(tool, h)| tool != t && h != holder);
    loaded.push((t, holder));
}

/// The spindle SVC acts on when it is not the master spindle: under MD20124 above 1, the
/// spindle of the toolholder holding the active offset's tool (PGsl 6.2, ex. 4, L1994-2024).
pub(super) fn svc_spindle(front: &Sinumerik) -> Option<u32> {
    if front.settings.toolholder_management <= 1 {
        return None;
    }
    let tool = front.tool.offset_tool?;
    let holders = &front.toolholders;
    let &(_, holder) = holders.loaded.iter().find(|&&(t, _)| t == tool)?;
    Some(holders.spindle(holder)).filter(|&n| n != 1)
}

/// At the block's end, before its motion: SVC[n] of the block turns spindle n at the active
/// offset's radius, and SETMS makes its spindle the master: the kernel's spindle (S, M3, G95
/// and the stream's spindle events) is then that one, the old master turning on as it did.
#[inline]
pub(super) fn before_motion(front: &mut Sinumerik, kernel: &mut Kernel, origin: Origin) {
    // The common block: no SVC waiting for its spindle, no new master.
    if front.toolholders.new_master.is_none() && !front.spindles.any_rate_pending() {
        return;
    }
    apply(front, kernel, origin);
}

/// [`before_motion`] for a block with an SVC[n] waiting or a new master spindle.
// Out of line: the check before it is inlined into every block's step.
#[inline(never)]
fn apply(front: &mut Sinumerik, kernel: &mut Kernel, origin: Origin) {
    let radius = front.edge().map_or(0.0, |e| e.radius);
    let max_rpm = kernel.state().setup.machine().spindle.max_rpm;
    for (n, rate) in front.spindles.take_pending_rates() {
        // Without a radius the rate waits for a tool, as the master's SVC does.
        if radius > 0.0 {
            let rpm = rate * 1000.0 / (std::f64::consts::TAU * radius);
            front.spindles.set_speed(n, rpm.min(max_rpm));
        }
    }
    let Some(n) = front.toolholders.new_master.take() else {
        return;
    };
    if n == front.spindles.master() {
        return;
    }
    let spindle = &kernel.state().spindle;
    let (speed, state) = front
        .spindles
        .switch_master(n, spindle.speed(), spindle.state());
    kernel.spindle(Some(speed), Some(state), origin);
}
