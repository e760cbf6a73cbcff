//! Macro expressions and statements, as written.
//!
//! An expression is kept in postfix order: a range of its block's [`Instruction`]s, which the
//! interpreter runs on a small stack. That is quick to evaluate (no tree to walk, no allocation
//! per expression) and each instruction keeps the span of the text it came from, so a division
//! by zero or the square root of a negative number points at its operator.
//!
//! Syntax knows no values: `#5221` is a variable number, and whether that variable exists, and
//! what a vacant one does in arithmetic, is the interpreter's business.

use crate::source::Span;

/// One step of a postfix expression.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Op {
    /// Pushes a constant.
    Number(f64),
    /// Pushes a whole number written without a decimal point in a Syntec `%@MACRO` program: a
    /// Long, which stays whole in arithmetic with another Long (`1/2` is 0, `1./2` is 0.5).
    Long(f64),
    /// Pushes the value of variable `#n` (a number written after `#`).
    Variable(u32),
    /// Pops a number n and pushes the value of `#n` (`#[expr]`).
    Indirect,
    /// Pops a value and pushes its negation (`-#1`, `-[..]`).
    Negate,
    /// Pops two values and pushes the result.
    Binary(BinaryOp),
    /// Pops one value and pushes the function of it.
    Function(Function),
    /// Pops x, then y, and pushes the angle of (x, y) in degrees: `ATAN[y]/[x]` or `ATAN[y,x]`.
    Atan2,
    /// Pops the exponent and the base (`POW[base,exponent]`).
    Power,
    /// Pops the second argument, then the first, and pushes the function of both (Syntec
    /// `MAX(a,b)`, `MIN(a,b)`, `ATAN2(y,x)`).
    Function2(Function2),
    /// Pushes the value of Syntec's public variable `@n`.
    Public(u32),
    /// Pops a number n and pushes the value of `@n` (`@[expr]`).
    PublicIndirect,
}

/// The binary operators of Custom Macro B.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinaryOp {
    /// `+`
    Add,
    /// `-`
    Subtract,
    /// `*`
    Multiply,
    /// `/`
    Divide,
    /// `MOD` (remainder)
    Modulo,
    /// `AND` (bitwise on whole numbers, logical on conditions)
    And,
    /// `OR`
    Or,
    /// `XOR`
    Xor,
    /// `EQ`
    Equal,
    /// `NE`
    NotEqual,
    /// `GT`
    Greater,
    /// `GE`
    GreaterOrEqual,
    /// `LT`
    Less,
    /// `LE`
    LessOrEqual,
}

impl BinaryOp {
    /// True for `+`, `-`, `*`, `/` and MOD, whose result has the type of their operands in a
    /// Syntec program (two Longs give a Long).
    pub fn is_arithmetic(self) -> bool {
        matches!(
            self,
            BinaryOp::Add
                | BinaryOp::Subtract
                | BinaryOp::Multiply
                | BinaryOp::Divide
                | BinaryOp::Modulo
        )
    }

    /// True for the comparisons, whose vacant-operand rule differs from arithmetic.
    pub fn is_comparison(self) -> bool {
        matches!(
            self,
            BinaryOp::Equal
                | BinaryOp::NotEqual
                | BinaryOp::Greater
                | BinaryOp::GreaterOrEqual
                | BinaryOp::Less
                | BinaryOp::LessOrEqual
        )
    }
}

/// The one-argument functions of Custom Macro B.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Function {
    /// `SIN`, degrees.
    Sin,
    /// `COS`, degrees.
    Cos,
    /// `TAN`, degrees.
    Tan,
    /// `ASIN`, degrees.
    Asin,
    /// `ACOS`, degrees.
    Acos,
    /// `ATAN` with one argument, degrees.
    Atan,
    /// `SQRT` (also written `SQR`).
    Sqrt,
    /// `ABS`.
    Abs,
    /// `ROUND` (also `RND`): to the nearest whole number, halves away from zero.
    Round,
    /// `FIX`: toward zero.
    Fix,
    /// `FUP`: away from zero.
    Fup,
    /// `LN`.
    Ln,
    /// `EXP`.
    Exp,
    /// `BIN`: binary-coded decimal to binary.
    Bin,
    /// `BCD`: binary to binary-coded decimal.
    Bcd,
    /// `CEIL` (Syntec): the next whole number up, toward plus infinity.
    Ceil,
    /// `FLOOR` (Syntec): the next whole number down, toward minus infinity.
    Floor,
    /// `SIGN` (Syntec): -1, 0 or 1.
    Sign,
    /// `NOT` (Syntec): 1 when the value is 0 or vacant, else 0.
    Not,
}

/// The two-argument functions of Syntec macro programs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Function2 {
    /// `MAX(a,b)`: the larger.
    Max,
    /// `MIN(a,b)`: the smaller.
    Min,
    /// `ATAN2(y,x)`: the angle of (x, y) in degrees, -180 to 180.
    Atan2,
}

/// Which set of variables a number names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VariableBank {
    /// `#n`: the macro variables (locals, commons, system variables).
    Macro,
    /// `@n`: Syntec's public variables.
    Public,
}

/// A variable a statement writes: its bank and the expression of its number.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Target {
    /// `#` or `@`.
    pub bank: VariableBank,
    /// Computes the variable number.
    pub number: Expr,
}

/// An instruction with the span of the text it came from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Instruction {
    /// What to do.
    pub op: Op,
    /// Where it was written.
    pub span: Span,
}

/// An expression: the instructions `start..end` of its block's `code`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Expr {
    /// Index of the first instruction.
    pub start: u32,
    /// Index one past the last instruction.
    pub end: u32,
}

impl Expr {
    /// The instructions of this expression in `code`.
    pub fn of<'a>(&self, code: &'a [Instruction]) -> &'a [Instruction] {
        code.get(self.start as usize..self.end as usize)
            .unwrap_or(&[])
    }

    /// The span covering the expression's text.
    pub fn span(&self, code: &[Instruction]) -> Option<Span> {
        let code = self.of(code);
        let first = code.first()?.span;
        Some(code.iter().fold(first, |span, i| span.to(i.span)))
    }
}

/// A macro statement: what a block does besides (or instead of) its words.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Statement {
    /// `#i = expr` (`:=` on Syntec; `@i := expr` in a Syntec macro program).
    Assign {
        /// The variable written.
        variable: Target,
        /// The value.
        value: Expr,
        /// The whole statement.
        span: Span,
    },
    /// `GOTO n`: continue at sequence number n.
    Goto {
        /// The sequence number.
        target: Expr,
        /// The whole statement.
        span: Span,
    },
    /// `IF [condition] GOTO n`.
    IfGoto {
        /// The condition.
        condition: Expr,
        /// The sequence number.
        target: Expr,
        /// The whole statement.
        span: Span,
    },
    /// `IF [condition] THEN #i = expr`.
    IfThen {
        /// The condition.
        condition: Expr,
        /// The variable number.
        variable: Expr,
        /// The value.
        value: Expr,
        /// The whole statement.
        span: Span,
    },
    /// `WHILE [condition] DO m`, or `DO m` alone (`condition` is `None`: an endless loop).
    While {
        /// The condition, tested before each pass.
        condition: Option<Expr>,
        /// The loop's identification number m.
        label: u32,
        /// The whole statement.
        span: Span,
    },
    /// `END m`: the end of loop m.
    End {
        /// The loop's identification number m.
        label: u32,
        /// The whole statement.
        span: Span,
    },
    /// `IF condition THEN` of a Syntec macro program: the statements up to the next ELSEIF,
    /// ELSE or END_IF run when the condition holds.
    If {
        /// The condition.
        condition: Expr,
        /// The whole statement.
        span: Span,
    },
    /// `ELSEIF condition THEN` (also spelled `ELSIF`).
    ElseIf {
        /// The condition.
        condition: Expr,
        /// The whole statement.
        span: Span,
    },
    /// `ELSE`.
    Else {
        /// The whole statement.
        span: Span,
    },
    /// `END_IF` (also `ENDIF`).
    EndIf {
        /// The whole statement.
        span: Span,
    },
    /// `WHILE condition DO`: the statements up to END_WHILE run while the condition holds.
    WhileDo {
        /// The condition, tested before each pass.
        condition: Expr,
        /// The whole statement.
        span: Span,
    },
    /// `END_WHILE` (also `ENDWHILE`).
    EndWhile {
        /// The whole statement.
        span: Span,
    },
    /// `FOR #i := from TO to [BY step] DO`.
    For {
        /// The counter.
        variable: Target,
        /// Its first value.
        from: Expr,
        /// The last value it may take.
        to: Expr,
        /// What each pass adds (1 when BY is not written).
        step: Option<Expr>,
        /// The whole statement.
        span: Span,
    },
    /// `END_FOR` (also `ENDFOR`).
    EndFor {
        /// The whole statement.
        span: Span,
    },
    /// `REPEAT`: the statements up to UNTIL run at least once.
    Repeat {
        /// The whole statement.
        span: Span,
    },
    /// `UNTIL condition`: back to REPEAT unless the condition holds.
    Until {
        /// The condition, tested after each pass.
        condition: Expr,
        /// The whole statement.
        span: Span,
    },
    /// `END_REPEAT` (also `ENDREPEAT`), right after UNTIL.
    EndRepeat {
        /// The whole statement.
        span: Span,
    },
    /// `CASE selector OF`: the run goes on after the first label that equals the selector, or
    /// after ELSE, or after END_CASE.
    Case {
        /// The value the labels are compared with.
        selector: Expr,
        /// The whole statement.
        span: Span,
    },
    /// One value of a CASE label (`2:`; `2, 3:` is two of them in one block): reached in
    /// sequence, the branch before it is over.
    CaseLabel {
        /// The value, a whole number as written.
        value: f64,
        /// The value as written.
        span: Span,
    },
    /// `END_CASE` (also `ENDCASE`).
    EndCase {
        /// The whole statement.
        span: Span,
    },
    /// `EXIT`: leaves the innermost WHILE, FOR or REPEAT.
    Exit {
        /// The whole statement.
        span: Span,
    },
    /// `WAIT()` or `SLEEP()`: they pace the control's read-ahead and its screen, which a
    /// simulation does not have; nothing to do.
    Wait {
        /// The whole statement.
        span: Span,
    },
    /// `ALARM(n)` or `ALARM(n, "text")`: stops the program with alarm n; the text is the
    /// block's `message`.
    Alarm {
        /// The alarm number.
        number: Expr,
        /// The whole statement.
        span: Span,
    },
    /// `MSG("text")`, `MSG(n)` or `MSG(n, "text")`: shows a message and goes on; the text
    /// is the block's `message`.
    Message {
        /// The message number, if one is given.
        number: Option<Expr>,
        /// The whole statement.
        span: Span,
    },
}

impl Statement {
    /// Where the statement stands.
    pub fn span(&self) -> Span {
        match self {
            Statement::Assign { span, .. }
            | Statement::Goto { span, .. }
            | Statement::IfGoto { span, .. }
            | Statement::IfThen { span, .. }
            | Statement::While { span, .. }
            | Statement::End { span, .. }
            | Statement::If { span, .. }
            | Statement::ElseIf { span, .. }
            | Statement::Else { span }
            | Statement::EndIf { span }
            | Statement::WhileDo { span, .. }
            | Statement::EndWhile { span }
            | Statement::For { span, .. }
            | Statement::EndFor { span }
            | Statement::Repeat { span }
            | Statement::Until { span, .. }
            | Statement::EndRepeat { span }
            | Statement::Case { span, .. }
            | Statement::CaseLabel { span, .. }
            | Statement::EndCase { span }
            | Statement::Exit { span }
            | Statement::Wait { span }
            | Statement::Alarm { span, .. }
            | Statement::Message { span, .. } => *span,
        }
    }
}
