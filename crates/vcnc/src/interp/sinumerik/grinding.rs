//! Constant grinding wheel peripheral speed (PGsl 6.4, seed 002 L2329-2401; docs/SINUMERIK.md
//! 10.10): GWPSON and GWPSOF for the active tool or a tool by number, S and `S<n>=` read as the
//! wheel's peripheral speed in m/s on a spindle where it is on, the grinding data `$TC_TPG1`
//! (the wheel's spindle), `$TC_TPG8` (an inclined wheel's angle) and `$TC_TPG9` (which edge
//! parameter is the wheel's radius), and `$P_GWPS[n]`.
//!
//! The speed a peripheral speed v gives is n = v * 60 * 1000 / (2 pi r) rpm with the wheel's
//! radius r in mm (spec part A 6.4, inferred: the manual names the function, not the formula).
//! The master spindle's speed reaches the stream as any S does; another spindle's is that
//! spindle's state (spindles.rs).
//!
//! Never: switch GWPS on for a tool that is not a grinding tool (types 400 to 499, L2357), or
//! without the grinding data that name its spindle and radius (L2375-2376), or for a second tool
//! on a spindle where it is on (L2387).

use std::collections::BTreeMap;

use super::block::Words;
use super::value::Value;
use super::Sinumerik;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::kernel::Kernel;
use crate::machine::ToolEdge;
use crate::source::Span;
use crate::syntax::sinumerik::{Block, Value as WordValue, Word};

/// A tool's grinding data.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct GrindingData {
    /// `$TC_TPG1`: the spindle the wheel turns on.
    spindle: f64,
    /// `$TC_TPG8`: an inclined wheel's angle, degrees; kept (choice: the peripheral speed is
    /// taken at the radius `$TC_TPG9` names, whatever the inclination).
    angle: f64,
    /// `$TC_TPG9`: the edge parameter that is the wheel's radius: 3 `$TC_DP3` (length 1) to 6
    /// `$TC_DP6` (the radius).
    radius_parameter: f64,
}

/// The grinding data of the tools and where GWPS is on.
#[derive(Clone, Debug, Default)]
pub(super) struct Grinding {
    data: BTreeMap<u32, GrindingData>,
    /// GWPS in force: the tool whose wheel it measures, by spindle.
    active: BTreeMap<u32, u32>,
}

impl Grinding {
    /// Whether `name` is a system variable of this module.
    pub(super) fn holds(name: &str) -> bool {
        matches!(name, "$TC_TPG1" | "$TC_TPG8" | "$TC_TPG9" | "$P_GWPS")
    }

    /// Reads `$TC_TPG1/8/9[t]` (0 when never written) or `$P_GWPS[n]`.
    pub(super) fn read(&self, name: &str, indices: &[Value], span: Span) -> Result<Value, Alarm> {
        let index = first_index(name, indices, span)?;
        if name == "$P_GWPS" {
            return Ok(Value::Bool(self.active.contains_key(&index)));
        }
        let data = self.data.get(&index).copied().unwrap_or_default();
        let value = match name {
            "$TC_TPG1" => data.spindle,
            "$TC_TPG8" => data.angle,
            _ => data.radius_parameter,
        };
        Value::real(value, span)
    }

    /// Writes `$TC_TPG1/8/9[t]`; `$P_GWPS` is read only.
    pub(super) fn write(
        &mut self,
        name: &str,
        indices: &[Value],
        value: &Value,
        span: Span,
    ) -> Result<(), Alarm> {
        let tool = first_index(name, indices, span)?;
        let Some(value) = value.as_f64().filter(|_| name != "$P_GWPS") else {
            return Err(Alarm::error(
                AlarmCode::BadVariable,
                span,
                format!("{name} is read only, or not given a number"),
            ));
        };
        let data = self.data.entry(tool).or_default();
        match name {
            "$TC_TPG1" => data.spindle = value,
            "$TC_TPG8" => data.angle = value,
            _ => data.radius_parameter = value,
        }
        Ok(())
    }

    /// True when GWPS is on for some spindle: only then is an S word looked at here.
    pub(super) fn any_active(&self) -> bool {
        !self.active.is_empty()
    }
}

/// The whole number in the first index of `name[n]`.
fn first_index(name: &str, indices: &[Value], span: Span) -> Result<u32, Alarm> {
    match indices.first().and_then(Value::as_f64) {
        Some(n) if n >= 0.0 && n.fract() == 0.0 && n <= f64::from(u32::MAX) => Ok(n as u32),
        _ => Err(Alarm::error(
            AlarmCode::BadVariable,
            span,
            format!("{name} takes a number in brackets: {name}[1]"),
        )),
    }
}

/// GWPSON or GWPSOF, alone (the active tool) or with a tool number (`GWPSON(5)`).
///
/// # Errors
/// No tool; a tool that is not a grinding tool, lacks its grinding data or names a spindle the
/// machine lacks; GWPSON on a spindle where another tool's GWPS is on.
pub(super) fn switch(front: &mut Sinumerik, kernel: &Kernel, word: &Word) -> Result<(), Alarm> {
    let on = &*word.address == "GWPSON";
    let tool = match &word.value {
        WordValue::Call(arguments) if !arguments.is_empty() => {
            let [Some(argument)] = arguments.as_slice() else {
                return Err(Alarm::error(
                    AlarmCode::MacroSyntax,
                    word.span,
                    format!("{} takes one tool number", word.address),
                ));
            };
            let t = front.value(kernel, argument)?;
            (t >= 1.0 && t.fract() == 0.0).then_some(t as u32)
        }
        _ => front.tool.in_spindle,
    };
    let Some(tool) = tool else {
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            word.span,
            format!("{}: no tool is active and none is named", word.address),
        )
        .with_help(format!("name the grinding tool: {}(5)", word.address)));
    };
    let spindle = wheel_spindle(front, kernel, tool, word)?;
    if !on {
        if front.grinding.active.get(&spindle) == Some(&tool) {
            front.grinding.active.remove(&spindle);
        }
        return Ok(());
    }
    wheel(front, tool, word.span)?;
    match front.grinding.active.get(&spindle) {
        Some(&other) if other != tool => Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            word.span,
            format!("GWPSON for T{tool}: GWPS of T{other} is on on spindle {spindle}"),
        )
        .with_help(format!(
            "switch it off first with GWPSOF({other}) (seed 002 L2387)"
        ))),
        _ => {
            front.grinding.active.insert(spindle, tool);
            Ok(())
        }
    }
}

/// The spindle `$TC_TPG1` names for `tool`, checked against the machine.
fn wheel_spindle(front: &Sinumerik, kernel: &Kernel, tool: u32, word: &Word) -> Result<u32, Alarm> {
    let data = front.grinding.data.get(&tool).copied().unwrap_or_default();
    let count = kernel.state().setup.machine().spindle.count;
    if data.spindle >= 1.0 && data.spindle.fract() == 0.0 && data.spindle <= f64::from(count) {
        return Ok(data.spindle as u32);
    }
    Err(Alarm::error(
        AlarmCode::BadDataInput,
        word.span,
        format!(
            "{}: $TC_TPG1[{tool}] = {} names no spindle of the machine (it has {count})",
            word.address, data.spindle
        ),
    )
    .with_help(format!(
        "write the wheel's spindle first: $TC_TPG1[{tool}]=1 (seed 002 L2375-2376)"
    )))
}

/// The wheel's radius, mm: the edge parameter `$TC_TPG9` names, of the tool's active edge when
/// it is the active tool and its first edge otherwise (choice: GWPSON(t) names no edge).
fn wheel(front: &Sinumerik, tool: u32, span: Span) -> Result<f64, Alarm> {
    let edge = if front.tool.in_spindle == Some(tool) && front.tool.edge != 0 {
        front.edge()
    } else {
        front
            .tools
            .iter()
            .filter(|e| e.t == tool)
            .min_by_key(|e| e.d)
    };
    let Some(edge) = edge.filter(|e| has_peripheral_speed(e.tool_type)) else {
        let kind = edge.map_or("not in the tool table".to_string(), |e| {
            format!("of type {}", e.tool_type)
        });
        return Err(Alarm::error(
            AlarmCode::WordNotAllowed,
            span,
            format!("GWPS needs a grinding wheel (types 400 to 499 but 403, 413 and the dresser 490): T{tool} is {kind}"),
        ));
    };
    let parameter = front
        .grinding
        .data
        .get(&tool)
        .map_or(0.0, |d| d.radius_parameter);
    let radius = radius_of(edge, parameter).ok_or_else(|| {
        Alarm::error(
            AlarmCode::BadDataInput,
            span,
            format!("GWPS: $TC_TPG9[{tool}] = {parameter} names no edge parameter of the wheel's radius"),
        )
        .with_help(format!("write $TC_TPG9[{tool}]=6 for the radius $TC_DP6, or 3 to 5 for a length"))
    })?;
    if radius > 0.0 {
        return Ok(radius);
    }
    Err(Alarm::error(
        AlarmCode::BadDataInput,
        span,
        format!("GWPS: the wheel of T{tool} has the radius {radius} mm"),
    ))
}

/// Whether a tool of `tool_type` is a wheel GWPS may act on: the grinding tools (L2357) but the
/// wheels "without wheel peripheral speed GWPS", 403 and 413, and the dresser 490, which is no
/// wheel (choice from the types' names, L1365-1373).
fn has_peripheral_speed(tool_type: u32) -> bool {
    (400..500).contains(&tool_type) && !matches!(tool_type, 403 | 413 | 490)
}

/// The edge parameter `$TC_DP<n>` that `$TC_TPG9` names, n 3 to 6.
fn radius_of(edge: &ToolEdge, parameter: f64) -> Option<f64> {
    if parameter.fract() != 0.0 {
        return None;
    }
    match parameter as i64 {
        3 => Some(edge.length),
        4 => Some(edge.length2),
        5 => Some(edge.length3),
        6 => Some(edge.radius),
        _ => None,
    }
}

/// Reads an S word (`S`, `S0=`, `S1=`, `S<n>=`) of a spindle with GWPS on as the wheel's
/// peripheral speed, m/s, and sets the spindle's speed from it; false for other words and in a
/// block where S is no speed (G4's revolutions, G25/G26's limits).
pub(super) fn read_speed(
    front: &mut Sinumerik,
    kernel: &Kernel,
    block: &Block,
    word: &Word,
    words: &mut Words<'_>,
) -> Result<bool, Alarm> {
    let Some(spindle) = spindle_of(&word.address) else {
        return Ok(false);
    };
    let Some(&tool) = front.grinding.active.get(&spindle) else {
        return Ok(false);
    };
    let not_speed = block.words.iter().any(|w| {
        &*w.address == "G"
            && matches!(&w.value, WordValue::Constant(g) if [4.0, 25.0, 26.0].contains(&g.value))
    });
    if not_speed {
        return Ok(false);
    }
    let written = super::block::number(front, kernel, word)?;
    // ft/s in inch (L2350-2351; choice: the unit G70/G700 put in force).
    let metres_per_second = if front.modal.inch {
        written * 0.3048
    } else {
        written
    };
    if metres_per_second.is_nan() || metres_per_second < 0.0 {
        return Err(Alarm::error(
            AlarmCode::ValueOutOfRange,
            word.span,
            format!("{}: a peripheral speed cannot be negative", word.address),
        ));
    }
    let radius = wheel(front, tool, word.span)?;
    let rpm = speed(metres_per_second, radius);
    if spindle == 1 {
        words.speed = Some((rpm, word.span));
    } else {
        front.spindles.set_speed(spindle, rpm);
    }
    Ok(true)
}

/// The spindle an S address names: `S`, `S0`, `S1` the master spindle, `S<n>` spindle n.
fn spindle_of(address: &str) -> Option<u32> {
    let number = address.strip_prefix('S')?;
    if number.is_empty() {
        return Some(1);
    }
    if !number.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    number.parse::<u32>().ok().map(|n| n.max(1))
}

/// The speed, rpm, at which a wheel of `radius` mm has the peripheral speed `metres_per_second`:
/// one turn is 2 pi r mm, so n = v * 1000 * 60 / (2 pi r).
fn speed(metres_per_second: f64, radius: f64) -> f64 {
    metres_per_second * 1000.0 * 60.0 / (2.0 * std::f64::consts::PI * radius)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The front end after running `text` to its end on a machine with two spindles and the
    /// grinding wheels T1 (r 200 mm, spindle 1) and T5 (r 150 mm, spindle 2).
    fn run(text: &str) -> Sinumerik {
        let mut machine = crate::Machine::default()
            .with_profile(crate::ProfileName::Sinumerik)
            .expect("the default machine fits the SINUMERIK profile");
        machine.spindle.count = 2;
        for (t, radius) in [(1, 200.0), (5, 150.0)] {
            machine.tools.push(ToolEdge {
                t,
                name: None,
                d: 1,
                tool_type: 401,
                length: 0.0,
                length2: 0.0,
                length3: 0.0,
                radius,
                teeth: None,
            });
        }
        let preset = "$TC_TPG1[1]=1\n$TC_TPG9[1]=6\n$TC_TPG1[5]=2\n$TC_TPG9[5]=6\n";
        super::super::threads::run_to_end(&format!("{preset}{text}"), &machine)
    }

    #[test]
    fn gwps_of_tool_5_sets_spindle_2_and_gwpsof_keeps_the_speed() {
        // a/35's N50-N65: 40 m/s on the 150 mm wheel, 40 * 60000 / (2 pi 150) = 2546.479 rpm,
        // which stays after GWPSOF(5) (seed 002 L2391).
        let front = run("S2=1500 M2=3\nGWPSON(5)\nS2 = 40\nGWPSOF(5)\nM30\n");
        let rpm = front.spindles.speed(2).unwrap();
        assert!((rpm - 2_546.479_089_470_325).abs() < 1e-6, "{rpm}");
        assert!(!front.grinding.any_active());
    }

    #[test]
    fn s2_without_gwps_is_a_speed() {
        let front = run("S2=1500 M2=3\nGWPSON(5)\nGWPSOF(5)\nS2=40\nM30\n");
        assert_eq!(front.spindles.speed(2), Some(40.0));
    }

    #[test]
    fn sixty_metres_a_second_on_a_wheel_of_200_mm_is_2864_8_rpm() {
        // 60 * 60000 / (2 pi 200) = 3,600,000 / 1256.637 = 2864.789 rpm.
        assert!((speed(60.0, 200.0) - 2_864.788_975_654_116).abs() < 1e-9);
    }

    #[test]
    fn the_s_addresses_name_their_spindles() {
        assert_eq!(spindle_of("S"), Some(1));
        assert_eq!(spindle_of("S0"), Some(1));
        assert_eq!(spindle_of("S1"), Some(1));
        assert_eq!(spindle_of("S2"), Some(2));
        assert_eq!(spindle_of("SPOS"), None);
        assert_eq!(spindle_of("SF"), None);
    }
}
