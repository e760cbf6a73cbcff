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
    /// `#i = expr` (`:=` on Syntec); `variable` computes the variable number.
    Assign {
        /// The variable number.
        variable: Expr,
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
            | Statement::End { span, .. } => *span,
        }
    }
}
