//! Custom Macro B in a block: `#` assignments, IF/WHILE/DO/END/GOTO, and expressions as word
//! values (`X#1`, `G#8`, `P[10]`, `X-[#4/2]`).
//!
//! Expressions are read by recursive descent with FANUC's precedence (functions, then `*` `/`
//! `AND` `MOD`, then `+` `-` `OR` `XOR`, then the comparisons) and written out in postfix
//! order into the block's `code`. Spaces may stand anywhere, and keywords need none around them
//! (`IF[#1GT#2]GOTO10`, `WH[#18GT#26]DO1`): a run of letters is matched against the keywords
//! that can stand there, longest first.
//!
//! A Syntec `%@MACRO` statement (`Format::Macro`) is read with the precedence of IEC 61131-3
//! structured text, which Syntec's macro language follows: `NOT` and signs, then `*` `/` `MOD`,
//! then `+` `-`, then the comparisons (`=` `<>` `<` `<=` `>` `>=`, and FANUC's EQ ... LE),
//! then `AND`, `XOR`, `OR`; `( )` bracket like `[ ]`, functions take `( )` (`ABS(#1)`), and
//! `@n` is a public variable.

use super::Format;
use super::{fast_number, Exponent, Reader};
use crate::alarm::{Alarm, AlarmCode};
use crate::syntax::expr::{
    BinaryOp, Expr, Function, Function2, Instruction, Op, Statement, Target, VariableBank,
};
use crate::syntax::{Block, Number, Word};

/// Brackets and signs nested deeper than this are an alarm (FANUC allows five levels of
/// brackets; the limit here only keeps a hostile line from exhausting the stack).
const MAX_NESTING: usize = 64;

/// Operators between operands: (keyword or symbol, operator). A precedence level is a list of
/// these tables.
type Operators = &'static [(&'static str, BinaryOp)];

const COMPARISONS: Operators = &[
    ("EQ", BinaryOp::Equal),
    ("NE", BinaryOp::NotEqual),
    ("GT", BinaryOp::Greater),
    ("GE", BinaryOp::GreaterOrEqual),
    ("LT", BinaryOp::Less),
    ("LE", BinaryOp::LessOrEqual),
];
/// Syntec's comparison symbols.
const SYMBOL_COMPARISONS: Operators = &[
    ("=", BinaryOp::Equal),
    ("<>", BinaryOp::NotEqual),
    (">", BinaryOp::Greater),
    (">=", BinaryOp::GreaterOrEqual),
    ("<", BinaryOp::Less),
    ("<=", BinaryOp::LessOrEqual),
];
const SIGNS: Operators = &[("+", BinaryOp::Add), ("-", BinaryOp::Subtract)];
const PRODUCTS: Operators = &[
    ("*", BinaryOp::Multiply),
    ("/", BinaryOp::Divide),
    ("MOD", BinaryOp::Modulo),
];
const OR: Operators = &[("OR", BinaryOp::Or)];
const XOR: Operators = &[("XOR", BinaryOp::Xor)];
const AND: Operators = &[("AND", BinaryOp::And)];

/// FANUC's precedence levels, lowest first: the comparisons; `+` `-` `OR` `XOR`; `*` `/` `AND`
/// `MOD`.
const ISO_LEVELS: &[&[Operators]] = &[&[COMPARISONS], &[SIGNS, OR, XOR], &[PRODUCTS, AND]];

/// The precedence levels of a Syntec macro statement (IEC 61131-3), lowest first.
const MACRO_LEVELS: &[&[Operators]] = &[
    &[OR],
    &[XOR],
    &[AND],
    &[SYMBOL_COMPARISONS, COMPARISONS],
    &[SIGNS],
    &[PRODUCTS],
];

/// The one-argument functions a Syntec macro statement has besides FANUC's.
const MACRO_FUNCTIONS: &[(&str, Function)] = &[
    ("CEIL", Function::Ceil),
    ("FLOOR", Function::Floor),
    ("SIGN", Function::Sign),
];

/// The two-argument functions of a Syntec macro statement: name and instruction.
const MACRO_FUNCTIONS2: &[(&str, Op)] = &[
    ("POW", Op::Power),
    ("ATAN2", Op::Function2(Function2::Atan2)),
    ("MAX", Op::Function2(Function2::Max)),
    ("MIN", Op::Function2(Function2::Min)),
];

/// The function names, longest spelling first where one is a prefix of another.
const FUNCTIONS: &[(&str, Function)] = &[
    ("SIN", Function::Sin),
    ("COS", Function::Cos),
    ("TAN", Function::Tan),
    ("ASIN", Function::Asin),
    ("ACOS", Function::Acos),
    ("ATAN", Function::Atan),
    ("SQRT", Function::Sqrt),
    ("SQR", Function::Sqrt),
    ("ABS", Function::Abs),
    ("ROUND", Function::Round),
    ("RND", Function::Round),
    ("FIX", Function::Fix),
    ("FUP", Function::Fup),
    ("LN", Function::Ln),
    ("EXP", Function::Exp),
    ("BIN", Function::Bin),
    ("BCD", Function::Bcd),
];

/// Reading stops; the alarm is in the block.
pub(super) struct Failed;

type Read<T = ()> = Result<T, Failed>;

impl Reader<'_, '_> {
    /// The upper-case run of letters at the cursor (without moving).
    pub(super) fn letters(&self) -> String {
        self.text[self.pos..]
            .iter()
            .take_while(|b| b.is_ascii_alphabetic() || **b == b'_')
            .map(u8::to_ascii_uppercase)
            .map(char::from)
            .collect()
    }

    /// The longest entry of `table` that the text at the cursor starts with (case-insensitive).
    fn match_keyword<T: Copy>(&self, table: &[(&str, T)]) -> Option<(usize, T)> {
        let rest = &self.text[self.pos..];
        table
            .iter()
            .filter(|(k, _)| {
                rest.len() >= k.len() && rest[..k.len()].eq_ignore_ascii_case(k.as_bytes())
            })
            .max_by_key(|(k, _)| k.len())
            .map(|(k, v)| (k.len(), *v))
    }

    /// A span of the line, kept inside the text: an error at the end of the line points at
    /// its last character.
    pub(super) fn clamped(&self, start: usize, end: usize) -> crate::source::Span {
        let length = self.text.len();
        let end = end.max(start + 1).min(length);
        let start = start.min(end.saturating_sub(1));
        self.span(start, end)
    }

    pub(super) fn fail(
        &self,
        block: &mut Block,
        start: usize,
        end: usize,
        message: String,
    ) -> Failed {
        block.alarms.push(Alarm::error(
            AlarmCode::MacroSyntax,
            self.clamped(start, end),
            message,
        ));
        Failed
    }

    fn emit(&self, block: &mut Block, op: Op, start: usize, end: usize) {
        block.code.push(Instruction {
            op,
            span: self.span(start, end),
        });
    }

    pub(super) fn expect(&mut self, block: &mut Block, byte: u8, what: &str) -> Read {
        self.skip_blanks();
        if self.peek() == Some(byte) {
            self.pos += 1;
            Ok(())
        } else {
            let at = self.pos;
            Err(self.fail(
                block,
                at,
                at + 1,
                format!("expected `{}` {what}", byte as char),
            ))
        }
    }

    /// A whole expression, comparisons included; returns its range of `code`.
    pub(super) fn expression(&mut self, block: &mut Block) -> Read<Expr> {
        let start = block.code.len() as u32;
        self.binary(block, 0, 0)?;
        Ok(Expr {
            start,
            end: block.code.len() as u32,
        })
    }

    /// The precedence levels of this format, lowest first.
    fn levels(&self) -> &'static [&'static [Operators]] {
        match self.format {
            Format::Iso => ISO_LEVELS,
            Format::Macro => MACRO_LEVELS,
        }
    }

    /// `operand (op operand)*` at precedence level `level` (0 is the lowest: a whole
    /// expression), left to right; past the last level, a unary operand.
    fn binary(&mut self, block: &mut Block, depth: usize, level: usize) -> Read {
        let Some(&tables) = self.levels().get(level) else {
            return self.unary(block, depth);
        };
        let left = block.code.len();
        self.binary(block, depth, level + 1)?;
        loop {
            self.skip_blanks();
            let found = tables.iter().filter_map(|t| self.match_keyword(t));
            let Some((length, op)) = found.max_by_key(|&(length, _)| length) else {
                return Ok(());
            };
            // `/` right after an operand divides; `//` is a Syntec comment.
            if op == BinaryOp::Divide
                && self.options.slash_slash_comments
                && self.peek_at(1) == Some(b'/')
            {
                return Ok(());
            }
            let at = self.pos;
            self.pos += length;
            let right = block.code.len();
            self.binary(block, depth, level + 1)?;
            if op == BinaryOp::Modulo && self.format == Format::Macro {
                self.refuse_real_modulo(block, left, right)?;
            }
            self.emit(block, Op::Binary(op), at, at + length);
        }
    }

    /// Syntec's MOD takes Longs only: a number written with a decimal point as its operand is
    /// alarm COR-054 on the control (syntec-macro handbook 02-variables 3.5). Only a number
    /// written so is seen here; a variable's type is not known before the run.
    fn refuse_real_modulo(&self, block: &mut Block, left: usize, right: usize) -> Read {
        let operands = [&block.code[left..right], &block.code[right..]];
        let real = operands.iter().find_map(|operand| match operand {
            [Instruction {
                op: Op::Number(_),
                span,
            }] => Some(*span),
            _ => None,
        });
        match real {
            Some(span) => {
                block.alarms.push(
                    Alarm::error(
                        AlarmCode::MacroSyntax,
                        span,
                        "MOD takes whole numbers (Long) in a %@MACRO program: this number has a decimal point",
                    )
                    .with_help("write it without the decimal point (`10 MOD 3`); the control raises COR-054"),
                );
                Err(Failed)
            }
            None => Ok(()),
        }
    }

    fn unary(&mut self, block: &mut Block, depth: usize) -> Read {
        if depth > MAX_NESTING {
            let at = self.pos;
            return Err(self.fail(block, at, at + 1, "expression nested too deeply".into()));
        }
        self.skip_blanks();
        match self.peek() {
            Some(b'-') => {
                let at = self.pos;
                self.pos += 1;
                self.unary(block, depth + 1)?;
                self.emit(block, Op::Negate, at, at + 1);
                Ok(())
            }
            Some(b'+') => {
                self.pos += 1;
                self.unary(block, depth + 1)
            }
            Some(b'N' | b'n') if self.format == Format::Macro && self.letters() == "NOT" => {
                let at = self.pos;
                self.pos += 3;
                self.unary(block, depth + 1)?;
                self.emit(block, Op::Function(Function::Not), at, at + 3);
                Ok(())
            }
            _ => self.primary(block, depth),
        }
    }

    fn primary(&mut self, block: &mut Block, depth: usize) -> Read {
        self.skip_blanks();
        let start = self.pos;
        match self.peek() {
            Some(b'[') => self.bracketed(block, depth),
            Some(b'(') if self.format == Format::Macro => self.bracketed(block, depth),
            Some(sigil @ (b'#' | b'@')) if sigil == b'#' || self.format == Format::Macro => {
                let bank = if sigil == b'#' {
                    VariableBank::Macro
                } else {
                    VariableBank::Public
                };
                self.pos += 1;
                let before = block.code.len();
                self.variable_number(block, depth, sigil)?;
                // `#n` (or `#[n]`) with a constant n: one instruction instead of a constant and
                // an indirection.
                if block.code.len() == before + 1 {
                    let span = self.span(start, self.pos);
                    let last = &mut block.code[before];
                    if let Op::Number(n) | Op::Long(n) = last.op {
                        if let Some(number) = whole_variable_number(n) {
                            last.op = match bank {
                                VariableBank::Macro => Op::Variable(number),
                                VariableBank::Public => Op::Public(number),
                            };
                            last.span = span;
                            return Ok(());
                        }
                    }
                }
                let indirect = match bank {
                    VariableBank::Macro => Op::Indirect,
                    VariableBank::Public => Op::PublicIndirect,
                };
                self.emit(block, indirect, start, start + 1);
                Ok(())
            }
            Some(b'0'..=b'9' | b'.') => {
                let number = self.expression_number(block)?;
                // Syntec types a number by its decimal point: without one it is a Long
                // (syntec-macro handbook 02-variables 3.4, 3.9; docs/MACROS.md).
                let long =
                    self.format == Format::Macro && !self.text[start..self.pos].contains(&b'.');
                let op = if long {
                    Op::Long(number)
                } else {
                    Op::Number(number)
                };
                self.emit(block, op, start, self.pos);
                Ok(())
            }
            Some(b) if b.is_ascii_alphabetic() => match self.format {
                Format::Iso => self.function(block, depth),
                Format::Macro => self.macro_function(block, depth),
            },
            Some(b'"') if self.format == Format::Macro => Err(self.fail(
                block,
                start,
                start + 1,
                "a text is only an argument of MSG or ALARM here, not a value".into(),
            )),
            _ => {
                let found = match self.peek() {
                    None => "the end of the block".to_string(),
                    Some(b) => format!("`{}`", (b as char).escape_debug()),
                };
                Err(self.fail(
                    block,
                    start,
                    start + 1,
                    format!("expected a value (a number, #variable, [expression] or function), found {found}"),
                ))
            }
        }
    }

    /// `[ expression ]`, or `( expression )` in a macro statement.
    fn bracketed(&mut self, block: &mut Block, depth: usize) -> Read {
        let open = self.pos;
        let close = if self.peek() == Some(b'(') {
            b')'
        } else {
            b']'
        };
        self.pos += 1;
        self.binary(block, depth + 1, 0)?;
        self.skip_blanks();
        if self.peek() == Some(close) {
            self.pos += 1;
            Ok(())
        } else {
            let at = self.pos;
            block.alarms.push(
                Alarm::error(
                    AlarmCode::MacroSyntax,
                    self.clamped(at, at + 1),
                    format!("expected `{}` to close the bracket", close as char),
                )
                .with_label(self.clamped(open, open + 1), "opened here"),
            );
            Err(Failed)
        }
    }

    /// The number after `#` (or `@`): digits (`#5221`) or a bracketed expression (`#[#1+2]`).
    /// Emits it as an expression (a constant for digits).
    fn variable_number(&mut self, block: &mut Block, depth: usize, sigil: u8) -> Read {
        self.skip_blanks();
        let start = self.pos;
        match self.peek() {
            Some(b'[') => self.bracketed(block, depth),
            Some(b'0'..=b'9') => {
                let number = self.expression_number(block)?;
                self.emit(block, Op::Number(number), start, self.pos);
                Ok(())
            }
            _ => Err(self.fail(
                block,
                start.saturating_sub(1),
                start,
                format!(
                    "`{}` needs a variable number or a bracketed expression",
                    sigil as char
                ),
            )),
        }
    }

    /// A constant inside an expression.
    fn expression_number(&mut self, block: &mut Block) -> Read<f64> {
        let start = self.pos;
        let value = if let Some((number, length)) = fast_number(&self.text[self.pos..], false) {
            self.pos += length;
            number.value
        } else {
            match self.read_digits(start, b'#', false, block) {
                Some(number) => number.value,
                None => return Err(Failed),
            }
        };
        // Inside an expression E and a digit can be nothing but an exponent, which ISO G-code
        // does not have (EQ is an operator: `#1EQ#2`).
        let rest = &self.text[self.pos..];
        if matches!(
            rest,
            [b'e' | b'E', b'0'..=b'9', ..] | [b'e' | b'E', b'+' | b'-', b'0'..=b'9', ..]
        ) {
            self.exponent_alarm(block, start, Exponent::InExpression);
            return Err(Failed);
        }
        Ok(value)
    }

    /// `SIN[..]`, `ATAN[..]/[..]`, `ATAN[..,..]`, `POW[..,..]`.
    fn function(&mut self, block: &mut Block, depth: usize) -> Read {
        let start = self.pos;
        if let Some(length) = self.match_keyword(&[("POW", ())]).map(|(l, ())| l) {
            self.pos += length;
            self.expect(block, b'[', "after POW")?;
            self.binary(block, depth + 1, 0)?;
            self.expect(block, b',', "between POW's arguments")?;
            self.binary(block, depth + 1, 0)?;
            self.expect(block, b']', "to close POW's arguments")?;
            self.emit(block, Op::Power, start, start + length);
            return Ok(());
        }
        let Some((length, function)) = self.match_keyword(FUNCTIONS) else {
            let name = self.letters();
            let end = start + name.len();
            return Err(self.fail(
                block,
                start,
                end,
                format!("`{name}` is not a macro function or value"),
            ));
        };
        self.pos += length;
        self.skip_blanks();
        if self.peek() != Some(b'[') {
            let at = self.pos;
            return Err(self.fail(
                block,
                at,
                at + 1,
                format!(
                    "expected `[` after {}",
                    String::from_utf8_lossy(&self.text[start..start + length]).to_uppercase()
                ),
            ));
        }
        self.pos += 1;
        self.binary(block, depth + 1, 0)?;
        self.skip_blanks();
        if function == Function::Atan && self.peek() == Some(b',') {
            // ATAN[y, x]
            self.pos += 1;
            self.binary(block, depth + 1, 0)?;
            self.expect(block, b']', "to close ATAN's arguments")?;
            self.emit(block, Op::Atan2, start, start + length);
            return Ok(());
        }
        self.expect(block, b']', "to close the function's argument")?;
        if function == Function::Atan {
            // ATAN[y]/[x]: the slash belongs to the function, not a division.
            let save = self.pos;
            self.skip_blanks();
            if self.peek() == Some(b'/') {
                self.pos += 1;
                self.skip_blanks();
                if self.peek() == Some(b'[') {
                    self.bracketed(block, depth + 1)?;
                    self.emit(block, Op::Atan2, start, start + length);
                    return Ok(());
                }
            }
            self.pos = save;
        }
        self.emit(block, Op::Function(function), start, start + length);
        Ok(())
    }

    /// A function of a Syntec macro statement: `ABS(#1)`, `ATAN2(#2, #3)`, `MAX(a, b)`;
    /// `[ ]` bracket the arguments as well as `( )`.
    fn macro_function(&mut self, block: &mut Block, depth: usize) -> Read {
        let start = self.pos;
        // Names may hold digits after the first letter (ATAN2).
        let name: String = self.text[start..]
            .iter()
            .take_while(|b| b.is_ascii_alphanumeric() || **b == b'_')
            .map(|b| char::from(b.to_ascii_uppercase()))
            .collect();
        let end = start + name.len();
        let one = MACRO_FUNCTIONS
            .iter()
            .chain(FUNCTIONS)
            .find(|(n, _)| *n == name);
        let two = MACRO_FUNCTIONS2.iter().find(|(n, _)| *n == name);
        self.pos = end;
        self.skip_blanks();
        let close = match self.peek() {
            Some(b'(') => b')',
            Some(b'[') => b']',
            _ if one.is_some() || two.is_some() => {
                let at = self.pos;
                return Err(self.fail(block, at, at + 1, format!("expected `(` after {name}")));
            }
            _ => {
                return Err(self.fail(
                    block,
                    start,
                    end,
                    format!("`{name}` is not a macro function or value"),
                ))
            }
        };
        let op = match (one, two) {
            (Some(&(_, function)), _) => Op::Function(function),
            (None, Some(&(_, op))) => op,
            (None, None) => {
                let span = self.clamped(start, end);
                block.alarms.push(Alarm::not_supported(
                    span,
                    &format!("the macro function `{name}`"),
                    None,
                ));
                return Err(Failed);
            }
        };
        self.pos += 1;
        self.binary(block, depth + 1, 0)?;
        if two.is_some() {
            self.expect(block, b',', &format!("between {name}'s arguments"))?;
            self.binary(block, depth + 1, 0)?;
        }
        self.expect(block, close, &format!("to close {name}'s arguments"))?;
        self.emit(block, op, start, end);
        Ok(())
    }

    /// A word whose value is an expression: `X#1`, `X-#1`, `G#8`, `P[10]`, `Z-[#4/2]`; in a
    /// macro statement also `X(#1+2.)` and `X@3`. The cursor is after the address letter.
    pub(super) fn read_expression_word(
        &mut self,
        block: &mut Block,
        letter: u8,
        start: usize,
    ) -> Read {
        let first = block.code.len() as u32;
        self.unary(block, 0)?;
        let expr = Expr {
            start: first,
            end: block.code.len() as u32,
        };
        block.words.push(Word {
            letter,
            index: 0,
            number: Number::default(),
            span: self.span(start, self.pos),
            expr: Some(expr),
        });
        Ok(())
    }

    /// True when the text after an address letter is an expression value (`#`, `[`, or a sign
    /// before either; in a macro statement also `(` and `@`).
    pub(super) fn expression_value_follows(&self) -> bool {
        let rest = &self.text[self.pos..];
        let mut bytes = rest.iter().filter(|b| !matches!(b, b' ' | b'\t'));
        let opens = |b: Option<&u8>| match b {
            Some(b'#' | b'[') => true,
            Some(b'(' | b'@') => self.format == Format::Macro,
            _ => false,
        };
        match bytes.next() {
            Some(b'-' | b'+') => opens(bytes.next()),
            first => opens(first),
        }
    }

    /// `#i = expr` (or `:=`; `@i := expr` in a macro statement), the cursor on `#` or `@`.
    pub(super) fn read_assignment(&mut self, block: &mut Block) -> Read {
        let start = self.pos;
        let (variable, value) = self.assignment_parts(block)?;
        block.statements.push(Statement::Assign {
            variable,
            value,
            span: self.span(start, self.pos),
        });
        Ok(())
    }

    /// The variable at the cursor (`#n`, `#[..]`, `@n`, `@[..]`) up to `:=` or `=`.
    pub(super) fn assigned_variable(&mut self, block: &mut Block) -> Read<Target> {
        let start = self.pos;
        let sigil = self.peek().unwrap_or(b'#');
        self.pos += 1;
        let first = block.code.len() as u32;
        self.variable_number(block, 0, sigil)?;
        let number = Expr {
            start: first,
            end: block.code.len() as u32,
        };
        self.skip_blanks();
        if self.peek() == Some(b':') && self.peek_at(1) == Some(b'=') {
            self.pos += 2;
        } else if self.peek() == Some(b'=') {
            self.pos += 1;
        } else {
            let at = self.pos;
            return Err(self.fail(
                block,
                start,
                at,
                "a variable at the start of a statement must be assigned: `#1 = value`".into(),
            ));
        }
        let bank = if sigil == b'@' {
            VariableBank::Public
        } else {
            VariableBank::Macro
        };
        Ok(Target { bank, number })
    }

    fn assignment_parts(&mut self, block: &mut Block) -> Read<(Target, Expr)> {
        let variable = self.assigned_variable(block)?;
        let value = self.expression(block)?;
        Ok((variable, value))
    }

    /// A loop number after DO or END.
    fn loop_label(&mut self, block: &mut Block, keyword: &str, start: usize) -> Read<u32> {
        self.skip_blanks();
        let at = self.pos;
        let digits = self.text[at..]
            .iter()
            .take_while(|b| b.is_ascii_digit())
            .count();
        if digits == 0 || digits > 4 {
            return Err(self.fail(
                block,
                start,
                at,
                format!("{keyword} needs a loop number (DO1 ... END1)"),
            ));
        }
        self.pos += digits;
        let text = std::str::from_utf8(&self.text[at..at + digits]).unwrap_or("0");
        Ok(text.parse().unwrap_or(0))
    }

    /// A statement that starts with a keyword: IF, WHILE (WH), DO, END, GOTO. Returns `None`
    /// (nothing consumed) when the letters at the cursor are not one of them.
    pub(super) fn read_keyword_statement(&mut self, block: &mut Block) -> Option<Read> {
        const STATEMENTS: &[(&str, u8)] = &[
            ("IF", 0),
            ("WHILE", 1),
            ("WH", 1),
            ("DO", 2),
            ("END", 3),
            ("GOTO", 4),
        ];
        let start = self.pos;
        let word = self.letters();
        // `END_IF`, `ENDWHILE` ... are other languages' keywords: left to the caller.
        let (length, kind) = self.match_keyword(STATEMENTS)?;
        let rest = &word[length.min(word.len())..];
        let allowed_after = match kind {
            // IF[..], WH[..]: a bracket follows; GOTO#1, GOTO10, DO1: digits or `#`.
            0 | 1 => rest.is_empty() || rest.starts_with("THEN") || rest.starts_with("GOTO"),
            _ => rest.is_empty(),
        };
        if !allowed_after {
            return None;
        }
        self.pos += length;
        Some(match kind {
            0 => self.read_if(block, start),
            1 => self.read_while(block, start),
            2 => self.loop_label(block, "DO", start).map(|label| {
                block.statements.push(Statement::While {
                    condition: None,
                    label,
                    span: self.span(start, self.pos),
                });
            }),
            3 => self.loop_label(block, "END", start).map(|label| {
                block.statements.push(Statement::End {
                    label,
                    span: self.span(start, self.pos),
                });
            }),
            _ => self.expression(block).map(|target| {
                block.statements.push(Statement::Goto {
                    target,
                    span: self.span(start, self.pos),
                });
            }),
        })
    }

    /// The `[condition]` of IF and WHILE.
    fn condition(&mut self, block: &mut Block, keyword: &str) -> Read<Expr> {
        self.skip_blanks();
        if self.peek() != Some(b'[') {
            let at = self.pos;
            return Err(self.fail(
                block,
                at,
                at + 1,
                format!("{keyword} needs a condition in brackets: {keyword} [#1 GT 0] ..."),
            ));
        }
        let first = block.code.len() as u32;
        self.bracketed(block, 0)?;
        Ok(Expr {
            start: first,
            end: block.code.len() as u32,
        })
    }

    fn read_if(&mut self, block: &mut Block, start: usize) -> Read {
        let condition = self.condition(block, "IF")?;
        self.skip_blanks();
        match self.letters().as_str() {
            w if w.starts_with("GOTO") => {
                self.pos += 4;
                let target = self.expression(block)?;
                block.statements.push(Statement::IfGoto {
                    condition,
                    target,
                    span: self.span(start, self.pos),
                });
                Ok(())
            }
            w if w.starts_with("THEN") => {
                self.pos += 4;
                self.skip_blanks();
                if self.peek() != Some(b'#') {
                    let at = self.pos;
                    return Err(self.fail(
                        block,
                        at,
                        at + 1,
                        "THEN must be followed by an assignment (`THEN #1 = 0`)".into(),
                    ));
                }
                let (variable, value) = self.assignment_parts(block)?;
                block.statements.push(Statement::IfThen {
                    condition,
                    variable: variable.number,
                    value,
                    span: self.span(start, self.pos),
                });
                Ok(())
            }
            _ => {
                let at = self.pos;
                Err(self.fail(
                    block,
                    at,
                    at + 1,
                    "IF [condition] must be followed by GOTO or THEN".into(),
                ))
            }
        }
    }

    fn read_while(&mut self, block: &mut Block, start: usize) -> Read {
        let condition = self.condition(block, "WHILE")?;
        self.skip_blanks();
        if !self.letters().starts_with("DO") {
            let at = self.pos;
            return Err(self.fail(
                block,
                at,
                at + 1,
                "WHILE [condition] must be followed by DO and a loop number".into(),
            ));
        }
        self.pos += 2;
        let label = self.loop_label(block, "DO", start)?;
        block.statements.push(Statement::While {
            condition: Some(condition),
            label,
            span: self.span(start, self.pos),
        });
        Ok(())
    }
}

/// A variable number written as a constant (`#5221`): whole and in range.
fn whole_variable_number(n: f64) -> Option<u32> {
    (n >= 0.0 && n.fract() == 0.0 && n < f64::from(u32::MAX)).then_some(n as u32)
}

#[cfg(test)]
pub(super) mod tests {
    use crate::source::FileId;
    use crate::syntax::expr::{Expr, Instruction, Op, Statement, Target, VariableBank};
    use crate::syntax::iso::{parse_line, LineBlocks, SyntaxOptions};
    use crate::syntax::lines::Line;
    use crate::syntax::Block;

    fn parse(text: &str) -> Vec<Block> {
        let mut out = LineBlocks::new();
        let line = Line {
            text: text.as_bytes(),
            offset: 0,
            number: 1,
        };
        let options = SyntaxOptions {
            slash_slash_comments: true,
            ..SyntaxOptions::default()
        };
        parse_line(line, FileId(0), &options, &mut out);
        out.as_slice().to_vec()
    }

    /// An expression in postfix, with spaces.
    pub(crate) fn postfix(expr: Expr, code: &[Instruction]) -> String {
        expr.of(code)
            .iter()
            .map(|i| match i.op {
                Op::Number(n) | Op::Long(n) => format!("{n}"),
                Op::Variable(n) => format!("#{n}"),
                Op::Indirect => "#[]".into(),
                Op::Public(n) => format!("@{n}"),
                Op::PublicIndirect => "@[]".into(),
                Op::Negate => "neg".into(),
                Op::Binary(op) => format!("{op:?}"),
                Op::Function(f) => format!("{f:?}"),
                Op::Function2(f) => format!("{f:?}"),
                Op::Atan2 => "atan2".into(),
                Op::Power => "pow".into(),
            })
            .collect::<Vec<_>>()
            .join(" ")
    }

    /// A variable written: `#[number]` or `@[number]`.
    fn target(variable: Target, code: &[Instruction]) -> String {
        let sigil = match variable.bank {
            VariableBank::Macro => '#',
            VariableBank::Public => '@',
        };
        format!("{sigil}[{}]", postfix(variable.number, code))
    }

    /// A statement, short.
    fn statement(s: &Statement, code: &[Instruction]) -> String {
        let p = |e: Expr| postfix(e, code);
        match *s {
            Statement::Assign {
                variable, value, ..
            } => format!("{} = {}", target(variable, code), p(value)),
            Statement::Goto { target, .. } => format!("goto {}", p(target)),
            Statement::IfGoto {
                condition, target, ..
            } => format!("if {} goto {}", p(condition), p(target)),
            Statement::IfThen {
                condition,
                variable,
                value,
                ..
            } => format!("if {} then #[{}] = {}", p(condition), p(variable), p(value)),
            Statement::While {
                condition, label, ..
            } => match condition {
                Some(c) => format!("while {} do {label}", p(c)),
                None => format!("do {label}"),
            },
            Statement::End { label, .. } => format!("end {label}"),
            Statement::If { condition, .. } => format!("if {} then", p(condition)),
            Statement::ElseIf { condition, .. } => format!("elseif {} then", p(condition)),
            Statement::WhileDo { condition, .. } => format!("while {} do", p(condition)),
            Statement::For {
                variable,
                from,
                to,
                step,
                ..
            } => {
                let by = step.map_or(String::new(), |s| format!(" by {}", p(s)));
                format!(
                    "for {} = {} to {}{by} do",
                    target(variable, code),
                    p(from),
                    p(to)
                )
            }
            Statement::Until { condition, .. } => format!("until {}", p(condition)),
            Statement::Alarm { number, .. } => format!("alarm {}", p(number)),
            Statement::Message { number, .. } => {
                format!("msg {}", number.map_or(String::new(), p))
            }
            Statement::Else { .. } => "else".into(),
            Statement::EndIf { .. } => "end_if".into(),
            Statement::EndWhile { .. } => "end_while".into(),
            Statement::EndFor { .. } => "end_for".into(),
            Statement::Repeat { .. } => "repeat".into(),
            Statement::EndRepeat { .. } => "end_repeat".into(),
            Statement::Exit { .. } => "exit".into(),
            Statement::Wait { .. } => "wait".into(),
            Statement::Case { selector, .. } => format!("case {} of", p(selector)),
            Statement::CaseLabel { value, .. } => format!("label {value}"),
            Statement::EndCase { .. } => "end_case".into(),
        }
    }

    /// The block's first alarm, or its statements and words, one per `|`.
    pub(crate) fn describe(block: &Block) -> String {
        if let Some(alarm) = block.alarms.first() {
            return format!("alarm {}: {}", alarm.span.unwrap().start, alarm.message);
        }
        let code = &block.code;
        let mut parts: Vec<String> = block
            .statements
            .iter()
            .map(|s| statement(s, code))
            .collect();
        parts.extend(block.words.iter().map(|w| match w.expr {
            Some(e) => format!("{}({})", w.letter as char, postfix(e, code)),
            None => format!("{}{}", w.letter as char, w.number.value),
        }));
        if block.kind != crate::syntax::BlockKind::Words {
            parts.push(format!("{:?}", block.kind));
        }
        if let (Some(message), None) = (&block.message, block.comment) {
            parts.push(format!("{message:?}"));
        }
        parts.join(" | ")
    }

    /// The first block of `text` described.
    fn show(text: &str) -> String {
        describe(&parse(text)[0])
    }

    #[test]
    fn assignments_follow_fanuc_precedence() {
        assert_eq!(show("#1=#2+3*SIN[#4]"), "#[1] = #2 3 #4 Sin Multiply Add");
        assert_eq!(
            show("#1 = 1 + 2 * 3 EQ 7"),
            "#[1] = 1 2 3 Multiply Add 7 Equal"
        );
        assert_eq!(show("#1=#2 AND #3 OR #4"), "#[1] = #2 #3 And #4 Or");
        assert_eq!(show("#1=10 MOD 3 - 1"), "#[1] = 10 3 Modulo 1 Subtract");
        assert_eq!(show("#1=-#2*-3"), "#[1] = #2 neg 3 neg Multiply");
        assert_eq!(show("#1=8/4/2"), "#[1] = 8 4 Divide 2 Divide");
    }

    #[test]
    fn indirect_variables_and_syntec_assignment() {
        assert_eq!(show("#4= #[ 2400. + #3026 ]"), "#[4] = 2400 #3026 Add #[]");
        assert_eq!(show("#[#141]=#5221"), "#[#141] = #5221");
        assert_eq!(show("#[100]=1"), "#[100] = 1");
        assert_eq!(show("#30 := #1000;"), "#[30] = #1000");
    }

    #[test]
    fn words_take_expressions() {
        assert_eq!(show("G90G#3Z#18J#1"), "G90 | G(#3) | Z(#18) | J(#1)");
        assert_eq!(
            show("X [ - #4 / 2 - #9 ]"),
            "X(#4 neg 2 Divide #9 Subtract)"
        );
        assert_eq!(show("M98 P [ 10 ]"), "M98 | P(10)");
        assert_eq!(show("G91 A[360.0/#2]"), "G91 | A(360 #2 Divide)");
        assert_eq!(show("X-#1 Y#[#2]"), "X(#1 neg) | Y(#2 #[])");
        assert_eq!(show("F[#2*#4]"), "F(#2 #4 Multiply)");
    }

    #[test]
    fn control_statements_need_no_spaces() {
        assert_eq!(show("IF[#1GT#2]GOTO10"), "if #1 #2 Greater goto 10");
        assert_eq!(show("N41GOTO#22"), "goto #22 | N41");
        assert_eq!(
            show("WH[[#1GE#2]OR[#1EQ#2]]DO1"),
            "while #1 #2 GreaterOrEqual #1 #2 Equal Or do 1"
        );
        assert_eq!(
            show("WHILE [#18 GT #26] DO 2"),
            "while #18 #26 Greater do 2"
        );
        assert_eq!(show("N49END1"), "end 1 | N49");
        assert_eq!(show("DO3"), "do 3");
        assert_eq!(
            show("IF [#1 EQ #0] THEN #3000=1(NEED ROTATION AXIS)"),
            "if #1 #0 Equal then #[3000] = 1"
        );
        assert_eq!(show("IF[#1LT#2]THEN#1=#2"), "if #1 #2 Less then #[1] = #2");
    }

    #[test]
    fn functions_and_their_argument_forms() {
        assert_eq!(show("#1=ATAN[#2]/[#3]"), "#[1] = #2 #3 atan2");
        assert_eq!(show("#1=ATAN[#2,#3]"), "#[1] = #2 #3 atan2");
        assert_eq!(show("#1=ATAN[#2]/2"), "#[1] = #2 Atan 2 Divide");
        assert_eq!(show("#1=POW[2,10]"), "#[1] = 2 10 pow");
        assert_eq!(
            show("#1=SQRT[ABS[#2]]+FIX[#3]+FUP[#4]+ROUND[#5]"),
            "#[1] = #2 Abs Sqrt #3 Fix Add #4 Fup Add #5 Round Add"
        );
        assert_eq!(show("#1=#2GESQRT[4]"), "#[1] = #2 4 Sqrt GreaterOrEqual");
    }

    #[test]
    fn malformed_macro_text_is_an_alarm_at_its_place() {
        assert_eq!(
            show("#1=[1+2"),
            "alarm 6: expected `]` to close the bracket"
        );
        assert_eq!(
            show("IF[#1]X1"),
            "alarm 6: IF [condition] must be followed by GOTO or THEN"
        );
        assert!(show("#=1").starts_with("alarm 0: `#` needs"));
        assert!(show("#1 5").starts_with("alarm 0: a variable at the start"));
        assert!(show("#1=#1-#11:").starts_with("alarm 9: unexpected character"));
        assert!(show("#1=FOO[1]").starts_with("alarm 3: `FOO` is not a macro function"));
        assert!(show("DO").starts_with("alarm 0: DO needs a loop number"));
        let deep = format!("#1={}1{}", "[".repeat(200), "]".repeat(200));
        assert!(show(&deep).contains("nested too deeply"));
    }

    #[test]
    fn double_slash_after_an_operand_is_a_syntec_comment() {
        assert_eq!(show("#31 := #1004;   // mode backup"), "#[31] = #1004");
        assert_eq!(show("G#30 G#31;      // restore"), "G(#30) | G(#31)");
    }
}
