//! The SINUMERIK statements as the syntax layer gives them to the interpreter: control
//! structures, jumps and declarations, each part with its span for alarms ([`Statement`],
//! [`StatementKind`] and the types of their parts). `control.rs` reads the control structures
//! and jumps, `declare.rs` the declarations.
//!
//! Plain data: no reading and no meaning here. Whether an IF has its ENDIF, a label exists or a
//! variable is defined is the interpreter's business (its structure scan), and so is what a
//! name in a jump target means (a label, or a STRING variable holding one).

use super::expr::Expr;
use crate::source::Span;

/// A statement of the language, from its keyword to its last part.
#[derive(Clone, Debug, PartialEq)]
pub struct Statement {
    /// What it is, with its parts.
    pub kind: StatementKind,
    /// From the keyword to the end of the statement's last part (comment and trailing blanks
    /// excluded).
    pub span: Span,
}

/// The statements.
#[derive(Clone, Debug, PartialEq)]
pub enum StatementKind {
    /// `IF cond`: the head of an IF ... [ELSE ...] ENDIF block form when `jump` is `None`, or the
    /// one-line conditional jump `IF cond GOTOF label`.
    If {
        /// The condition.
        condition: Expr,
        /// The jump of the one-line form.
        jump: Option<Jump>,
    },
    /// `ELSE`.
    Else,
    /// `ENDIF`.
    EndIf,
    /// `WHILE cond`.
    While {
        /// The condition, tested before each pass.
        condition: Expr,
    },
    /// `ENDWHILE`.
    EndWhile,
    /// `FOR variable = start TO end`.
    For {
        /// The counter: a name or an indexed name (`ExprKind::Name` or `ExprKind::Index`).
        variable: Expr,
        /// Its first value.
        start: Expr,
        /// Its last value.
        end: Expr,
    },
    /// `ENDFOR`.
    EndFor,
    /// `REPEAT` alone: the head of a REPEAT ... UNTIL loop.
    Repeat,
    /// `UNTIL cond`: the end of a REPEAT loop, left when the condition holds.
    Until {
        /// The condition, tested after each pass.
        condition: Expr,
    },
    /// `LOOP`: the head of an endless loop.
    Loop,
    /// `ENDLOOP`.
    EndLoop,
    /// `CASE(expr) OF c1 GOTOF l1 c2 GOTOB l2 ... DEFAULT GOTOF l`.
    Case(Case),
    /// `REPEAT start [end] [P=n]`: repeats the blocks from label `start` to label `end`, or, with
    /// one label, from it to the REPEAT block or to an `ENDLABEL` (the interpreter decides which).
    RepeatSection {
        /// The first label.
        start: Name,
        /// The second label, if written.
        end: Option<Name>,
        /// The number of repetitions of `P=n` (1 when left out).
        passes: Option<Expr>,
    },
    /// `REPEATB label [P=n]`: repeats the one block with that label.
    RepeatBlock {
        /// The label of the block.
        label: Name,
        /// The number of repetitions of `P=n` (1 when left out).
        passes: Option<Expr>,
    },
    /// `ENDLABEL:` (or `ENDLABEL`): the end of a section repeated by `REPEAT label`. Written with
    /// its colon, the block keeps it as its label too.
    EndLabel,
    /// A jump alone, or after the other words of its block (docs/SINUMERIK.md 3.1).
    Jump(Jump),
    /// `DEF`: a variable definition.
    Definition(Definition),
    /// `PROC`: a procedure (subprogram) header.
    Procedure(Procedure),
    /// `EXTERN`: the declaration of a subprogram with parameters.
    External(External),
    /// `DEFINE name AS text`: a macro.
    Macro(Macro),
    /// `SAVE` alone.
    Save,
    /// `CALL program [BLOCK start TO end]`: an indirect call, the program named by a string
    /// expression; with BLOCK, only the part between two labels (of the current program when no
    /// program is written).
    Call {
        /// The program's name (a string expression); `None` in `CALL BLOCK .. TO ..`.
        program: Option<Expr>,
        /// The first and the last label of the part to run.
        section: Option<(Name, Name)>,
    },
    /// A synchronized action (`WHEN`, `WHENEVER`, `EVERY`, `FROM` ... `DO` ..., or `DO` ...
    /// alone), not read yet: its keyword and the rest of the block after it.
    Action {
        /// The keyword.
        keyword: Name,
        /// The rest of the block, comment included.
        rest: Span,
    },
}

/// A value and where it was written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Spanned<T> {
    /// The value.
    pub value: T,
    /// Where it was written.
    pub span: Span,
}

/// A name as written, in upper case: a label, a variable, a procedure.
pub type Name = Spanned<Box<str>>;

/// A jump: `GOTOF label`, `GOTOB N100`, `GOTO ZIEL`, `GOTOS`.
#[derive(Clone, Debug, PartialEq)]
pub struct Jump {
    /// Which jump.
    pub kind: JumpKind,
    /// Where to; `None` only for GOTOS.
    pub target: Option<JumpTarget>,
    /// From the keyword to the end of the target.
    pub span: Span,
}

impl Jump {
    /// The target's expression, if the target is one.
    fn expression(&self) -> Option<&Expr> {
        match &self.target {
            Some(JumpTarget::Expression(e)) => Some(e),
            _ => None,
        }
    }
}

/// The jump instructions (spec/sinumerik-tables.md, manual L13272-13290).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JumpKind {
    /// `GOTO`: searches forwards, then backwards.
    Goto,
    /// `GOTOF`: searches forwards (towards the program end).
    GotoF,
    /// `GOTOB`: searches backwards (towards the program start).
    GotoB,
    /// `GOTOC`: as GOTO, but a target not found is no alarm (14080).
    GotoC,
    /// `GOTOS`: back to the program start; no target.
    GotoS,
}

impl JumpKind {
    /// The keyword, upper case (`GOTOF`), for messages.
    pub fn keyword(self) -> &'static str {
        match self {
            JumpKind::Goto => "GOTO",
            JumpKind::GotoF => "GOTOF",
            JumpKind::GotoB => "GOTOB",
            JumpKind::GotoC => "GOTOC",
            JumpKind::GotoS => "GOTOS",
        }
    }
}

/// The target of a jump.
#[derive(Clone, Debug, PartialEq)]
pub enum JumpTarget {
    /// A name alone: a label, or a STRING variable holding a label (the interpreter tells).
    Label(Name),
    /// A block number `N100`.
    BlockNumber(Spanned<u32>),
    /// A string expression that gives the label or block number (`"N"<<R1`, `ZIEL[2]`).
    Expression(Expr),
}

impl JumpTarget {
    /// Where the target was written.
    pub fn span(&self) -> Span {
        match self {
            JumpTarget::Label(name) => name.span,
            JumpTarget::BlockNumber(number) => number.span,
            JumpTarget::Expression(expr) => expr.span,
        }
    }
}

/// The parts of a CASE statement.
#[derive(Clone, Debug, PartialEq)]
pub struct Case {
    /// The value compared with the branches' constants.
    pub selector: Expr,
    /// `constant GOTOF label`, in written order.
    pub branches: Vec<CaseBranch>,
    /// The jump of `DEFAULT`, taken when no constant matches.
    pub default: Option<Jump>,
}

/// One branch of a CASE statement.
#[derive(Clone, Debug, PartialEq)]
pub struct CaseBranch {
    /// The constant.
    pub value: Expr,
    /// Where to jump when the selector equals it.
    pub jump: Jump,
}

impl StatementKind {
    /// The keyword that starts the statement, upper case (`IF`, `REPEATB`, `GOTOF`, `WHEN`), for
    /// messages such as "ENDIF without IF".
    pub fn keyword(&self) -> &str {
        match self {
            StatementKind::If { .. } => "IF",
            StatementKind::Else => "ELSE",
            StatementKind::EndIf => "ENDIF",
            StatementKind::While { .. } => "WHILE",
            StatementKind::EndWhile => "ENDWHILE",
            StatementKind::For { .. } => "FOR",
            StatementKind::EndFor => "ENDFOR",
            StatementKind::Repeat | StatementKind::RepeatSection { .. } => "REPEAT",
            StatementKind::RepeatBlock { .. } => "REPEATB",
            StatementKind::Until { .. } => "UNTIL",
            StatementKind::Loop => "LOOP",
            StatementKind::EndLoop => "ENDLOOP",
            StatementKind::Case(_) => "CASE",
            StatementKind::EndLabel => "ENDLABEL",
            StatementKind::Jump(jump) => jump.kind.keyword(),
            StatementKind::Definition(_) => "DEF",
            StatementKind::Procedure(_) => "PROC",
            StatementKind::External(_) => "EXTERN",
            StatementKind::Macro(_) => "DEFINE",
            StatementKind::Save => "SAVE",
            StatementKind::Call { .. } => "CALL",
            StatementKind::Action { keyword, .. } => &keyword.value,
        }
    }
}

impl Statement {
    /// Every expression of the statement at its top level (conditions, bounds, initial values,
    /// targets, dimensions), in written order: for the interpreter's checks, such as reads of
    /// `$A` variables that stop preprocessing.
    pub fn expressions(&self) -> Vec<&Expr> {
        let mut all = Vec::new();
        let jump = Jump::expression;
        match &self.kind {
            StatementKind::If { condition, jump: j } => {
                all.push(condition);
                all.extend(j.as_ref().and_then(jump));
            }
            StatementKind::While { condition } | StatementKind::Until { condition } => {
                all.push(condition);
            }
            StatementKind::For {
                variable,
                start,
                end,
            } => all.extend([variable, start, end]),
            StatementKind::Case(case) => {
                all.push(&case.selector);
                for branch in &case.branches {
                    all.push(&branch.value);
                    all.extend(jump(&branch.jump));
                }
                all.extend(case.default.as_ref().and_then(jump));
            }
            StatementKind::RepeatSection { passes, .. }
            | StatementKind::RepeatBlock { passes, .. } => all.extend(passes),
            StatementKind::Jump(j) => all.extend(jump(j)),
            StatementKind::Call { program, .. } => all.extend(program),
            StatementKind::Definition(definition) => definition.expressions(&mut all),
            StatementKind::Procedure(procedure) => {
                for parameter in &procedure.parameters {
                    all.extend(parameter.dimensions.iter().flatten());
                }
            }
            StatementKind::External(external) => {
                for parameter in &external.parameters {
                    all.extend(parameter.dimensions.iter().flatten());
                }
            }
            StatementKind::Else
            | StatementKind::EndIf
            | StatementKind::EndWhile
            | StatementKind::EndFor
            | StatementKind::Repeat
            | StatementKind::Loop
            | StatementKind::EndLoop
            | StatementKind::EndLabel
            | StatementKind::Macro(_)
            | StatementKind::Save
            | StatementKind::Action { .. } => {}
        }
        all
    }
}

/// `DEF [NCK|CHAN] type name[dims]=init, name2, ...`.
#[derive(Clone, Debug, PartialEq)]
pub struct Definition {
    /// `NCK` or `CHAN` before the type (global user data), if written.
    pub scope: Option<Spanned<Scope>>,
    /// The type of every variable of the definition.
    pub data_type: Spanned<DataType>,
    /// The variables, in written order (at least one).
    pub variables: Vec<Variable>,
}

/// Where a global variable of a definition is valid (tables: NCK, CHAN).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scope {
    /// `NCK`: the whole control.
    Nck,
    /// `CHAN`: the channel.
    Chan,
}

/// The data types of the language (tables: INT, REAL, BOOL, CHAR, STRING, AXIS, FRAME).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DataType {
    /// `INT`: a signed integer.
    Int,
    /// `REAL`: a floating-point number.
    Real,
    /// `BOOL`: TRUE or FALSE.
    Bool,
    /// `CHAR`: an ASCII character.
    Char,
    /// `STRING[n]`: a string of at most `n` characters.
    String(u32),
    /// `AXIS`: an axis identifier.
    Axis,
    /// `FRAME`: a coordinate transformation.
    Frame,
}

/// One variable of a definition.
#[derive(Clone, Debug, PartialEq)]
pub struct Variable {
    /// Its name.
    pub name: Name,
    /// The sizes of an array's dimensions (`ARR[3,4]`); empty for a single value.
    pub dimensions: Vec<Expr>,
    /// Its initial value, if written.
    pub init: Option<Spanned<Initializer>>,
    /// From the name to the end of the initial value.
    pub span: Span,
}

/// The initial value of a variable.
#[derive(Clone, Debug, PartialEq)]
pub enum Initializer {
    /// `= expression`.
    Value(Expr),
    /// `= SET(v1, v2, ...)`: an array's first elements, in order.
    Set(Vec<Expr>),
    /// `= REP(v)` or `= REP(v, n)`: every element (or the first `n`) set to `v`.
    Rep {
        /// The value.
        value: Expr,
        /// How many elements, if written.
        count: Option<Expr>,
    },
}

/// `PROC name(parameters) attributes`.
#[derive(Clone, Debug, PartialEq)]
pub struct Procedure {
    /// The procedure's name.
    pub name: Name,
    /// Its formal parameters, in order; each has a name.
    pub parameters: Vec<Parameter>,
    /// The words after the parameters (`SAVE`, `DISPLOF`, `SBLOF`, `ACTBLOCNO` ...), upper case.
    pub attributes: Vec<Name>,
}

/// `EXTERN name(types)`.
#[derive(Clone, Debug, PartialEq)]
pub struct External {
    /// The subprogram's name.
    pub name: Name,
    /// Its parameters' types, in order; none has a name.
    pub parameters: Vec<Parameter>,
}

/// A parameter of PROC (`VAR REAL X[,3]`) or EXTERN (`VAR REAL[,3]`).
#[derive(Clone, Debug, PartialEq)]
pub struct Parameter {
    /// The span of `VAR` (passed by reference), if written.
    pub by_reference: Option<Span>,
    /// Its type.
    pub data_type: Spanned<DataType>,
    /// Its name (PROC), or `None` (EXTERN).
    pub name: Option<Name>,
    /// An array's dimensions; a size left out (`[,3]`) is `None`.
    pub dimensions: Vec<Option<Expr>>,
    /// The whole parameter.
    pub span: Span,
}

/// `DEFINE name AS text`: the text is kept as written, for the interpreter to substitute.
#[derive(Clone, Debug, PartialEq)]
pub struct Macro {
    /// The macro's name.
    pub name: Name,
    /// The text after `AS` up to the comment, blanks trimmed (never empty).
    pub body: Span,
}

impl Definition {
    /// The dimensions and initial values of every variable, in written order.
    fn expressions<'a>(&'a self, all: &mut Vec<&'a Expr>) {
        for variable in &self.variables {
            all.extend(&variable.dimensions);
            match variable.init.as_ref().map(|i| &i.value) {
                Some(Initializer::Value(value)) => all.push(value),
                Some(Initializer::Set(values)) => all.extend(values),
                Some(Initializer::Rep { value, count }) => {
                    all.push(value);
                    all.extend(count);
                }
                None => {}
            }
        }
    }
}
