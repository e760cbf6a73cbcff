//! The front end's side of the language: what the evaluator asks of the machine (system
//! variables, axis names), definitions (DEF), and the parameters of a PROC call.
//!
//! Never: let a program write machine state the manual keeps read-only; a system variable vcnc
//! does not model is an alarm naming it, never a silent 0.

use super::eval::{self, Environment};
use super::frame::ProgrammableFrame;
use super::value::{Type, Value};
use super::vars::{Init, ParamType, Variables};
use super::work_area::CsVariable;
use super::{Modal, Sinumerik, ToolState};
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::kernel::Kernel;
use crate::machine::{AxisLayout, AxisName, ToolEdge, AXES};
use crate::source::Span;
use crate::syntax::sinumerik::{DataType, Definition, Expr, ExprKind, Parameter, Procedure, Scope};

/// The machine's axes as programs name them: the machine file's names (X Y Z, A B C by
/// default, or U V W, C1 ...), which axes it has, and a table for the one-letter names of the
/// plain blocks.
#[derive(Clone, Debug)]
pub(super) struct ChannelAxes {
    layout: AxisLayout,
    present: [bool; AXES],
    /// Rotary (degrees, never converted by G70/G700) or linear, by index.
    rotary: [bool; AXES],
    /// The index of the present axis each letter A-Z names alone; `u8::MAX` for none.
    by_letter: [u8; 26],
}

/// What a name is among the machine's axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum AxisLookup {
    /// An axis of the machine, by index.
    Present(usize),
    /// An axis name the machine does not have: its own absent slots (X Y Z A B C), or U V W.
    Absent,
    /// No axis name.
    NotAnAxis,
}

impl ChannelAxes {
    pub(super) fn new(machine: &crate::machine::Machine) -> ChannelAxes {
        let present: [bool; AXES] = std::array::from_fn(|i| machine.axes[i].is_some());
        let mut by_letter = [u8::MAX; 26];
        for axis in crate::machine::Axis::ALL
            .into_iter()
            .filter(|a| present[a.index()])
        {
            if let Some(letter) = machine.layout.name(axis).single_letter() {
                by_letter[usize::from(letter - b'A')] = axis.index() as u8;
            }
        }
        ChannelAxes {
            layout: machine.layout,
            rotary: machine.layout.rotary_mask(),
            present,
            by_letter,
        }
    }

    /// The machine's axis that `name` calls.
    pub(super) fn lookup(&self, name: &str) -> AxisLookup {
        match self.layout.by_name(name) {
            Some(axis) if self.present[axis.index()] => AxisLookup::Present(axis.index()),
            Some(_) => AxisLookup::Absent,
            None if matches!(name, "A" | "B" | "C" | "U" | "V" | "W") => AxisLookup::Absent,
            None => AxisLookup::NotAnAxis,
        }
    }

    /// The index of the machine's axis `name` calls, if it has one.
    pub(super) fn index(&self, name: &str) -> Option<usize> {
        match self.lookup(name) {
            AxisLookup::Present(i) => Some(i),
            _ => None,
        }
    }

    /// The index of the present axis whose name is the letter `letter` (upper case).
    #[inline]
    pub(super) fn by_letter(&self, letter: u8) -> Option<usize> {
        let i = *self.by_letter.get(usize::from(letter.wrapping_sub(b'A')))?;
        (i != u8::MAX).then_some(usize::from(i))
    }

    /// The name of the axis of index `i`.
    pub(super) fn name(&self, i: usize) -> AxisName {
        self.layout.name(crate::machine::Axis::ALL[i])
    }

    /// Rotary or not, by index.
    pub(super) fn rotary(&self) -> &[bool; AXES] {
        &self.rotary
    }

    /// The factor to mm of an axis value of index `i` in the length unit `unit` (rotary axes
    /// are in degrees whatever the unit).
    #[inline]
    pub(super) fn scale(&self, i: usize, unit: f64) -> f64 {
        if self.rotary[i] {
            1.0
        } else {
            unit
        }
    }
}

/// What the evaluator may read of the machine: the front end's state beside its variables.
pub(super) struct Machine<'a> {
    pub(super) kernel: &'a Kernel,
    pub(super) programmed: &'a [f64; AXES],
    /// Diameter programming: the work positions of a diameter axis read as diameters.
    pub(super) diameter: &'a super::diameter::Diameter,
    pub(super) axes: &'a ChannelAxes,
    pub(super) frame: &'a ProgrammableFrame,
    pub(super) tool: &'a ToolState,
    pub(super) tools: &'a mut Vec<ToolEdge>,
    /// Settable frames the program wrote ($P_UIFR), for the kernel after the block's words.
    pub(super) frame_writes: &'a mut Vec<(u32, usize, f64)>,
    pub(super) modal: &'a Modal,
    /// The working area's WCS groups ($P_WORKAREA_CS_...).
    pub(super) work_area: &'a mut super::work_area::WorkArea,
    /// The dynamic response's machine data ($MA_MAX_AX_ACCEL[n, axis] ...).
    pub(super) machine_data: &'a mut super::machine_data::MachineData,
    /// The spindles by number ($P_S[n]).
    pub(super) spindles: &'a super::spindles::Spindles,
    /// The grinding tools' data and GWPS ($TC_TPG1, $P_GWPS ...).
    pub(super) grinding: &'a mut super::grinding::Grinding,
}

/// The front end's variables, and the machine the evaluator reads, borrowed apart.
pub(super) fn split<'a>(
    front: &'a mut Sinumerik,
    kernel: &'a Kernel,
) -> (&'a mut Variables, Machine<'a>) {
    (
        &mut front.vars,
        Machine {
            kernel,
            programmed: &front.programmed,
            diameter: &front.diameter,
            axes: &front.axes,
            frame: &front.frame,
            tool: &front.tool,
            tools: &mut front.tools,
            frame_writes: &mut front.frame_writes,
            modal: &front.modal,
            work_area: &mut front.work_area,
            machine_data: &mut front.machine_data,
            spindles: &front.spindles,
            grinding: &mut front.grinding,
        },
    )
}

impl Machine<'_> {
    /// The group and the axis of `$P_WORKAREA_CS_...[group, axis]` (COORD_SYSTEM: the group
    /// only, axis 0).
    fn cs_indices(
        &self,
        variable: CsVariable,
        indices: &[Value],
        span: Span,
    ) -> Result<(f64, usize), Alarm> {
        let group = indices.first().and_then(Value::as_f64).unwrap_or(-1.0);
        if variable == CsVariable::CoordSystem {
            return Ok((group, 0));
        }
        Ok((group, self.axis(indices.get(1), span)?))
    }

    /// The kernel index of an axis value (`X`, or an AXIS variable's value).
    fn axis(&self, value: Option<&Value>, span: Span) -> Result<usize, Alarm> {
        let name = match value {
            Some(Value::Axis(name) | Value::Str(name)) => name.as_str(),
            _ => "",
        };
        self.axes.index(name).ok_or_else(|| {
            Alarm::error(
                AlarmCode::BadVariable,
                span,
                format!("`{name}` is not an axis of the machine"),
            )
        })
    }

    /// The edge `$TC_DP..[t, d]` names.
    fn edge(&self, indices: &[Value], span: Span) -> Result<Option<&ToolEdge>, Alarm> {
        let number = |v: Option<&Value>| v.and_then(Value::as_f64).map(|x| x as u32);
        let (Some(t), Some(d)) = (number(indices.first()), number(indices.get(1))) else {
            return Err(Alarm::error(
                AlarmCode::BadVariable,
                span,
                "$TC_DP.. takes the tool and the edge: $TC_DP3[1,1]",
            ));
        };
        Ok(self.tools.iter().find(|e| e.t == t && e.d == d))
    }
}

impl Environment for Machine<'_> {
    fn system_variable(
        &mut self,
        name: &str,
        indices: &[Value],
        span: Span,
    ) -> Result<Value, Alarm> {
        let real = |x: f64| Value::real(x, span);
        match name {
            // The machine position and the work position at the end of the previous block
            // (docs/SINUMERIK.md 3.2 step 2).
            "$AA_IM" | "$AA_IW" | "$P_EP" | "$AC_RETPOINT" => {
                let axis = self.axis(indices.first(), span)?;
                let value = match name {
                    "$AA_IM" => self.kernel.position().0[axis],
                    "$AA_IW" => self.kernel.program_position()[axis] * self.diameter.readout(axis),
                    "$P_EP" => self.programmed[axis] * self.diameter.readout(axis),
                    _ => self.programmed[axis],
                };
                real(value)
            }
            "$P_TOOLNO" | "$TC_MPP6" => Ok(Value::Int(self.tool.in_spindle.unwrap_or(0) as i32)),
            "$P_TOOL" => Ok(Value::Int(self.tool.edge as i32)),
            "$P_TOOLP" => Ok(Value::Int(self.tool.selected.unwrap_or(0) as i32)),
            "$P_F" => real(self.kernel.state().feed.unwrap_or(0.0)),
            // $P_S[n]: spindle n's programmed speed; without n (or n the master) the master's.
            "$P_S" => match indices.first().and_then(Value::as_f64) {
                Some(n) if n >= 1.0 && n.fract() == 0.0 && n != f64::from(self.spindles.master()) => {
                    real(self.spindles.programmed_speed(n as u32))
                }
                _ => real(self.kernel.state().spindle.speed()),
            },
            super::lift_fast::FLAG => Ok(super::lift_fast::read_flag()),
            _ if super::grinding::Grinding::holds(name) => self.grinding.read(name, indices, span),
            "$P_GG" => {
                let group = indices.first().and_then(Value::as_f64).unwrap_or(0.0) as u32;
                if group == 29 {
                    return Ok(Value::Int(self.diameter.group_member()));
                }
                Ok(Value::Int(super::gcodes::member(self.modal, group)))
            }
            "$TC_DP1" | "$TC_DP3" | "$TC_DP4" | "$TC_DP5" | "$TC_DP6" => {
                let edge = self.edge(indices, span)?;
                let value = edge.map_or(0.0, |e| match name {
                    "$TC_DP1" => f64::from(e.tool_type),
                    "$TC_DP3" => e.length,
                    "$TC_DP4" => e.length2,
                    "$TC_DP5" => e.length3,
                    _ => e.radius,
                });
                if name == "$TC_DP1" {
                    return Ok(Value::Int(value as i32));
                }
                real(value)
            }
            "$P_PFRAME" => {
                let axis = self.axis(indices.first(), span)?;
                let part = match indices.get(1) {
                    Some(Value::Str(part) | Value::Axis(part)) => part.as_str(),
                    _ => "TR",
                };
                let value = match (part, axis) {
                    ("TR", i) => self.frame.translation()[i],
                    ("RT", i) if i < 3 => self.frame.rpy_degrees()[i],
                    ("SC", i) if i < 3 => self.frame.scale_factors()[i],
                    ("MI", i) if i < 3 => f64::from(u8::from(self.frame.mirrored()[i])),
                    _ => {
                        return Err(Alarm::error(
                            AlarmCode::BadVariable,
                            span,
                            format!("$P_PFRAME has no part {part} for this axis"),
                        ))
                    }
                };
                real(value)
            }
            "$P_UIFR" => {
                let n = indices.first().and_then(Value::as_f64).unwrap_or(-1.0);
                let axis = self.axis(indices.get(1), span)?;
                let id = super::block::settable_id(n as u32, false);
                real(self.kernel.state().frames.work_offset(id)[axis])
            }
            _ if CsVariable::named(name).is_some() => {
                let variable = CsVariable::named(name).expect("just matched");
                let at = self.cs_indices(variable, indices, span)?;
                let value = self.work_area.read_cs(variable, at, span)?;
                match variable {
                    CsVariable::PlusEnable | CsVariable::MinusEnable => Ok(Value::Bool(value != 0.0)),
                    CsVariable::CoordSystem => Ok(Value::Int(value as i32)),
                    _ => real(value),
                }
            }
            _ if super::machine_data::holds(name) => {
                let group = indices.first().and_then(Value::as_f64);
                let axis = self.axis(indices.get(1), span)?;
                let config = self.kernel.state().setup.machine().axes[axis].as_ref();
                real(self.machine_data.read(name, group, axis, config, span)?)
            }
            _ if super::gcodes::out_of_product(name).is_some() => Err(Alarm::error(
                AlarmCode::NotInProduct,
                span,
                format!(
                    "{name} belongs to {}, which vcnc does not simulate",
                    super::gcodes::out_of_product(name).unwrap_or_default()
                ),
            )),
            _ => Err(Alarm::error(
                AlarmCode::NotSupportedYet,
                span,
                format!("the system variable {name} is not modelled by vcnc"),
            )
            .with_help("vcnc reads $AA_IM, $AA_IW, $P_EP, $P_TOOLNO, $P_TOOL, $P_F, $P_S, $P_GG, $P_PFRAME, $P_UIFR and $TC_DP1..6")),
        }
    }

    fn write_system_variable(
        &mut self,
        name: &str,
        indices: &[Value],
        value: Value,
        span: Span,
    ) -> Result<(), Alarm> {
        let number = |v: &Value| -> Result<f64, Alarm> {
            v.as_f64().ok_or_else(|| {
                Alarm::error(AlarmCode::MacroArithmetic, span, "a number is needed here")
            })
        };
        match name {
            super::lift_fast::FLAG => super::lift_fast::write_flag(value.as_f64(), span),
            _ if super::grinding::Grinding::holds(name) => {
                self.grinding.write(name, indices, &value, span)
            }
            // The tool table's edge data (PGsl 5; $TC_DP1 type, 3-5 lengths, 6 radius).
            "$TC_DP1" | "$TC_DP3" | "$TC_DP4" | "$TC_DP5" | "$TC_DP6" | "$TC_DPNT" => {
                let whole = |v: Option<&Value>| v.and_then(Value::as_f64).map(|x| x as u32);
                let (Some(t), Some(d)) = (whole(indices.first()), whole(indices.get(1))) else {
                    return Err(Alarm::error(
                        AlarmCode::BadVariable,
                        span,
                        format!("{name} takes the tool and the edge: {name}[1,1]"),
                    ));
                };
                let value = number(&value)?;
                let edge = match self.tools.iter_mut().position(|e| e.t == t && e.d == d) {
                    Some(i) => &mut self.tools[i],
                    None => {
                        self.tools.push(super::toolholder::program_edge(t, d));
                        self.tools.last_mut().expect("just pushed")
                    }
                };
                match name {
                    "$TC_DP1" => edge.tool_type = value as u32,
                    "$TC_DP3" => edge.length = value,
                    "$TC_DP4" => edge.length2 = value,
                    "$TC_DP5" => edge.length3 = value,
                    "$TC_DP6" => edge.radius = value,
                    _ => edge.teeth = Some(value as u32),
                }
                Ok(())
            }
            // A settable frame's translation: `$P_UIFR[1,X,TR]=10` (or `$P_UIFR[1,X]`).
            "$P_UIFR" => {
                let n = indices.first().and_then(Value::as_f64).unwrap_or(-1.0);
                let axis = self.axis(indices.get(1), span)?;
                let part = match indices.get(2) {
                    Some(Value::Str(part) | Value::Axis(part)) => part.as_str(),
                    _ => "TR",
                };
                if part != "TR" || !(0.0..=99.0).contains(&n) || n.fract() != 0.0 {
                    return Err(Alarm::error(
                        AlarmCode::NotSupportedYet,
                        span,
                        "vcnc's settable frames hold translations: $P_UIFR[n, axis, TR] only",
                    ));
                }
                self.frame_writes.push((n as u32, axis, number(&value)?));
                Ok(())
            }
            _ if CsVariable::named(name).is_some() => {
                let variable = CsVariable::named(name).expect("just matched");
                let (group, axis) = self.cs_indices(variable, indices, span)?;
                let value = number(&value)?;
                self.work_area
                    .write_cs(variable, (group, axis), value, span)
            }
            _ if name.starts_with("$P_WORKAREA") || name.starts_with("$SA_WORKAREA") => {
                Err(Alarm::error(
                    AlarmCode::NotSupportedYet,
                    span,
                    format!("{name} is not run yet (planned: issue 22, the working area)"),
                ))
            }
            _ if super::machine_data::holds(name) => {
                let group = indices.first().and_then(Value::as_f64);
                let axis = self.axis(indices.get(1), span)?;
                let value = number(&value)?;
                self.machine_data.write(name, group, axis, value, span)
            }
            _ if super::gcodes::out_of_product(name).is_some() => Err(Alarm::error(
                AlarmCode::NotInProduct,
                span,
                format!(
                    "{name} belongs to {}, which vcnc does not simulate",
                    super::gcodes::out_of_product(name).unwrap_or_default()
                ),
            )),
            _ => Err(Alarm::error(
                AlarmCode::BadVariable,
                span,
                format!("{name} cannot be written by a program"),
            )),
        }
    }

    fn call(
        &mut self,
        name: &str,
        arguments: &[Option<Value>],
        span: Span,
    ) -> Option<Result<Value, Alarm>> {
        match (name, arguments) {
            // QU(n): the auxiliary function n output without waiting (PGsl 13.3); its value is n.
            ("QU", [Some(value)]) => Some(Ok(value.clone())),
            ("QU", _) => Some(Err(Alarm::error(
                AlarmCode::MacroSyntax,
                span,
                "QU takes the function's value: M=QU(7)",
            ))),
            _ => None,
        }
    }

    fn is_axis(&self, name: &str) -> bool {
        self.axes.index(name).is_some()
    }
}

impl Sinumerik {
    /// An expression's value.
    pub(super) fn evaluate(&mut self, kernel: &Kernel, expr: &Expr) -> Result<Value, Alarm> {
        let (vars, mut machine) = split(self, kernel);
        eval::evaluate(expr, vars, &mut machine)
    }

    /// An expression's value as a number.
    pub(super) fn value(&mut self, kernel: &Kernel, expr: &Expr) -> Result<f64, Alarm> {
        let value = self.evaluate(kernel, expr)?;
        value.as_f64().ok_or_else(|| {
            Alarm::error(
                AlarmCode::MacroArithmetic,
                expr.span,
                format!("a number is needed here, not {}", value.to_text()),
            )
        })
    }

    /// The truth of a condition.
    pub(super) fn condition(&mut self, kernel: &Kernel, expr: &Expr) -> Result<bool, Alarm> {
        match self
            .evaluate(kernel, expr)?
            .convert(Type::Bool, expr.span)?
        {
            Value::Bool(b) => Ok(b),
            _ => unreachable!("converted to BOOL"),
        }
    }

    /// An expression's value as text.
    pub(super) fn text(&mut self, kernel: &Kernel, expr: &Expr) -> Result<String, Alarm> {
        Ok(self.evaluate(kernel, expr)?.to_text())
    }

    /// `target = value`: a variable, an element, an R parameter or a writable system variable.
    pub(super) fn assign(
        &mut self,
        kernel: &Kernel,
        target: &Expr,
        value: f64,
    ) -> Result<(), Alarm> {
        let (name, indices) = match &target.kind {
            ExprKind::Name(name) => (name, &[][..]),
            ExprKind::Index(name, indices) => (name, &indices[..]),
            _ => {
                return Err(Alarm::error(
                    AlarmCode::BadVariable,
                    target.span,
                    "a variable is needed here",
                ))
            }
        };
        let (vars, mut machine) = split(self, kernel);
        let indices = indices
            .iter()
            .map(|i| eval::evaluate(i, vars, &mut machine))
            .collect::<Result<Vec<_>, _>>()?;
        let value = Value::real(value, target.span)?;
        eval::assign(vars, name, &indices, value, target.span)
    }

    /// The assignment word `name[indices] = expr` of a block.
    pub(super) fn assign_word(
        &mut self,
        kernel: &Kernel,
        name: &str,
        indices: &[Expr],
        expr: &Expr,
        span: Span,
    ) -> Result<(), Alarm> {
        let (vars, mut machine) = split(self, kernel);
        eval::assign_expr(vars, &mut machine, name, indices, expr, span)
    }

    /// The settable frames the block's assignments wrote, into the kernel's work offsets.
    pub(super) fn apply_frame_writes(&mut self, kernel: &mut Kernel) {
        for (n, axis, value) in self.frame_writes.drain(..) {
            let id = super::block::settable_id(
                n,
                self.settings.variant == crate::profile::Variant::M828d,
            );
            kernel.set_work_offset(id, axis, value);
        }
    }

    /// True when `name` is an R parameter or a variable visible here.
    pub(super) fn is_variable(&self, name: &str) -> bool {
        self.vars.is_defined(name)
    }

    /// DEF: the variables of a definition, declared in the current program level.
    pub(super) fn define(&mut self, kernel: &Kernel, definition: &Definition) -> Result<(), Alarm> {
        let ty = value_type(definition.data_type.value, definition.data_type.span)?;
        for variable in &definition.variables {
            let (vars, mut machine) = split(self, kernel);
            let dims = variable
                .dimensions
                .iter()
                .map(|d| eval::evaluate(d, vars, &mut machine))
                .collect::<Result<Vec<_>, _>>()?;
            let init = match &variable.init {
                None => Init::Default,
                Some(init) => initialiser(vars, &mut machine, &init.value)?,
            };
            let name = &variable.name.value;
            match definition.scope.map(|s| s.value) {
                Some(Scope::Nck | Scope::Chan) => {
                    vars.declare_global(name, ty, &dims, init, variable.span)?;
                }
                None => vars.declare(name, ty, &dims, init, variable.span)?,
            }
        }
        Ok(())
    }

    /// Binds the arguments of a call (evaluated in the caller's level, before it is left) to the
    /// parameters of `procedure`, in the new level the call made.
    pub(super) fn bind(
        &mut self,
        arguments: Vec<Argument>,
        procedure: &Procedure,
        span: Span,
    ) -> Result<(), Alarm> {
        if arguments.len() > procedure.parameters.len() {
            return Err(Alarm::error(
                AlarmCode::MacroSyntax,
                span,
                format!(
                    "{} takes {} parameters, the call gives {}",
                    procedure.name.value,
                    procedure.parameters.len(),
                    arguments.len()
                ),
            ));
        }
        for (n, parameter) in procedure.parameters.iter().enumerate() {
            let Some(name) = &parameter.name else {
                continue;
            };
            let ty = value_type(parameter.data_type.value, parameter.data_type.span)?;
            match (arguments.get(n), parameter.by_reference) {
                (Some(Argument::Place(place)), Some(_)) => {
                    let param = ParamType {
                        ty,
                        dims: parameter_dims(parameter),
                    };
                    self.vars
                        .bind_reference(&name.value, &param, place.clone(), span)?;
                }
                (Some(Argument::Value(value)), None) => {
                    self.vars.bind_value(&name.value, ty, value.clone(), span)?;
                }
                (Some(Argument::Place(place)), None) => {
                    // A variable passed by value: its value.
                    let value = self.vars.get(place, span)?;
                    self.vars.bind_value(&name.value, ty, value, span)?;
                }
                (Some(Argument::Value(_)), Some(at)) => {
                    return Err(Alarm::error(
                        AlarmCode::BadVariable,
                        at,
                        format!(
                            "VAR {} needs a variable in the call, not a value",
                            name.value
                        ),
                    ))
                }
                // A parameter left out keeps its type's default (PGAsl: omitted parameters).
                (None | Some(Argument::Omitted), _) => {
                    self.vars
                        .declare(&name.value, ty, &[], Init::Default, span)?;
                }
            }
        }
        Ok(())
    }

    /// The arguments of a call, evaluated in the caller's level: a place for an argument that
    /// is a variable (a VAR parameter may take it), else a value.
    pub(super) fn arguments(
        &mut self,
        kernel: &Kernel,
        arguments: &[Option<Expr>],
    ) -> Result<Vec<Argument>, Alarm> {
        let (vars, mut machine) = split(self, kernel);
        arguments
            .iter()
            .map(|argument| {
                let Some(expr) = argument else {
                    return Ok(Argument::Omitted);
                };
                let is_variable = match &expr.kind {
                    ExprKind::Name(name) | ExprKind::Index(name, _) => {
                        !name.starts_with('$') && vars.is_defined(name)
                    }
                    _ => false,
                };
                if is_variable {
                    if let Ok(place) = eval::place_of(expr, vars, &mut machine) {
                        return Ok(Argument::Place(place));
                    }
                }
                eval::evaluate(expr, vars, &mut machine).map(Argument::Value)
            })
            .collect()
    }
}

/// One argument of a call.
#[derive(Clone, Debug)]
pub(super) enum Argument {
    /// Left out (`CYCLE(1,,3)`).
    Omitted,
    /// A value.
    Value(Value),
    /// A variable, for a VAR parameter (or its value for one by value).
    Place(super::vars::Place),
}

/// The value type of a data type; FRAME variables are not run yet.
fn value_type(data_type: DataType, span: Span) -> Result<Type, Alarm> {
    Ok(match data_type {
        DataType::Int => Type::Int,
        DataType::Real => Type::Real,
        DataType::Bool => Type::Bool,
        DataType::Char => Type::Char,
        DataType::String(n) => Type::string(i64::from(n), span)?,
        DataType::Axis => Type::Axis,
        DataType::Frame => {
            return Err(Alarm::error(
                AlarmCode::NotSupportedYet,
                span,
                "FRAME variables are not run yet by vcnc",
            ))
        }
    })
}

fn parameter_dims(parameter: &Parameter) -> Vec<Option<usize>> {
    parameter
        .dimensions
        .iter()
        .map(|d| match d.as_ref().map(|e| &e.kind) {
            Some(ExprKind::Number(n)) if *n >= 1.0 => Some(*n as usize),
            _ => None,
        })
        .collect()
}

fn initialiser(
    vars: &Variables,
    machine: &mut Machine<'_>,
    init: &crate::syntax::sinumerik::Initializer,
) -> Result<Init, Alarm> {
    use crate::syntax::sinumerik::Initializer;
    let mut value = |e: &Expr| eval::evaluate(e, vars, machine);
    Ok(match init {
        Initializer::Value(e) => Init::Value(value(e)?),
        Initializer::Set(list) => Init::Set(list.iter().map(&mut value).collect::<Result<_, _>>()?),
        Initializer::Rep { value: v, .. } => Init::Rep(value(v)?),
    })
}
