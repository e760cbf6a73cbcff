//! The SINUMERIK 840D sl / 828D front end's syntax: blocks, words, statements and expressions
//! as the control reads them (manual "Fundamentals" 2.2 and 3.2; docs/SINUMERIK.md).
//!
//! A dialect of its own: SINUMERIK owns its word, block, statement and expression types
//! ([`Block`], [`Word`], [`Statement`], [`Expr`]); nothing here is shared with the ISO front end but [`crate::syntax::Number`]
//! and spans. What the words mean is the SINUMERIK interpreter's business.

mod block;
mod control;
mod declare;
mod expr;
mod lines;
mod plain;
mod scan;
mod statement;

pub use block::{parse_block, parse_block_into, parse_line_into, Address, Block, Value, Word};
pub use expr::{BinaryOp, Expr, ExprKind, UnaryOp};
pub use lines::{is_header, ParsedLine, SinumerikParser};
pub use plain::{PlainKind, PlainWord, PlainWords};
pub use statement::{
    Case, CaseBranch, DataType, Definition, External, Initializer, Jump, JumpKind, JumpTarget,
    Macro, Name, Parameter, Procedure, Scope, Spanned, Statement, StatementKind, Variable,
};
