//! Predefined procedures and what the front end says of words it does not run: SETAL, the notes of commands kept as state, and the alarms of words outside the
//! product, planned for issue 22, or unknown.
//!
//! Never: pass over a word silently; each one here runs, is noted once, or alarms naming it.

use super::gcodes;
use super::Sinumerik;
use crate::alarm::{Alarm, AlarmCode};
use crate::interp::kernel::Kernel;
use crate::syntax::sinumerik::{Expr, ExprKind, Value, Word};

/// SETAL(number[, text]): the program raises an alarm of its own (cycle alarms 60000-67999
/// stop it).
pub(super) fn user_alarm(
    front: &mut Sinumerik,
    kernel: &Kernel,
    word: &Word,
) -> Result<Alarm, Alarm> {
    let Value::Call(arguments) = &word.value else {
        return Err(Alarm::error(
            AlarmCode::MacroSyntax,
            word.span,
            "SETAL takes the alarm number in parentheses: SETAL(61000)",
        ));
    };
    let number = match arguments.first() {
        Some(Some(expr)) => front.value(kernel, expr)?,
        _ => 0.0,
    };
    let text = match arguments.get(1) {
        Some(Some(expr)) => format!(": {}", front.text(kernel, expr)?),
        _ => String::new(),
    };
    Ok(Alarm::error(
        AlarmCode::UserAlarm,
        word.span,
        format!("alarm {number}{text} (set by the program with SETAL)"),
    ))
}

/// The G functions a machine has at power-on that change nothing vcnc models: no note.
const QUIET_STATE: [&str; 18] = [
    "BRISK", "FFWOF", "COMPOF", "CFC", "NORM", "G450", "G601", "WALIMON", "DIAMOF", "FNORM",
    "RTLION", "DYNNORM", "CUT2D", "G40", "G290", "CDOF", "TRAFOOF", "G460",
];

/// A note, once per command, that vcnc keeps a command as state without its effect on the
/// control's timing (docs/SINUMERIK.md 1, issue 20's "accepted as state").
pub(super) fn note_state(
    front: &mut Sinumerik,
    name: &str,
    word: &Word,
    warnings: &mut Vec<Alarm>,
) {
    if QUIET_STATE.contains(&name) || !front.noted.insert(name.to_string()) {
        return;
    }
    warnings.push(Alarm::warning(
        AlarmCode::KeptAsState,
        word.span,
        format!("{name} is kept as state: vcnc moves as programmed without modelling its effect on the control's path or timing"),
    ));
}

/// A word as the program wrote it, for messages: `M2=70`, `SVC[2]`, `POSA`.
pub(super) fn written(word: &Word) -> String {
    match &word.value {
        Value::Constant(n) => format!("{}{}", word.address, n.value),
        Value::Expression(Expr {
            kind: ExprKind::Number(n),
            ..
        }) => format!("{}={n}", word.address),
        Value::Indexed(..) => format!("{}[..]", word.address),
        _ => word.address.to_string(),
    }
}

/// The alarm of a word vcnc does not run: out of the product, planned, or unknown.
pub(super) fn unknown_word(word: &Word) -> Alarm {
    let name = &*word.address;
    if let Some(what) =
        gcodes::out_of_product(name).or_else(|| gcodes::other_unit(name, &word.value))
    {
        return Alarm::error(
            AlarmCode::NotInProduct,
            word.span,
            format!("{name} belongs to {what}, which vcnc does not simulate"),
        );
    }
    if gcodes::planned_call(name) {
        return Alarm::error(
            AlarmCode::NotSupportedYet,
            word.span,
            format!("{name} is not run yet (planned: issue 22, SINUMERIK cycles and compensation)"),
        );
    }
    if matches!(word.value, Value::Bare | Value::Call(_)) {
        return Alarm::error(
            AlarmCode::NotSupportedYet,
            word.span,
            format!("{name} is not run yet by vcnc's SINUMERIK front end"),
        )
        .with_help("see docs/SINUMERIK.md for what runs today");
    }
    Alarm::error(
        AlarmCode::WordNotAllowed,
        word.span,
        format!("the address {name} is not run yet by vcnc's SINUMERIK front end"),
    )
    .with_help("see docs/SINUMERIK.md for what runs today")
}
