//! The keyword statements of a Syntec `%@MACRO` program: IF ... THEN, ELSEIF (ELSIF), ELSE,
//! END_IF, WHILE ... DO, END_WHILE, FOR ... := ... TO ... BY ... DO, END_FOR, REPEAT, UNTIL,
//! END_REPEAT, CASE ... OF with its labels (`1:`, `2, 3:`) and END_CASE, EXIT, GOTO, and the
//! calls WAIT(), SLEEP(), ALARM() and MSG().
//!
//! Each statement is read alone (`macro_program.rs` cuts the text at `;` and after THEN, DO,
//! ELSE and REPEAT), so a keyword statement must start its statement and nothing may follow it.
//! Which END_IF closes which IF is not decided here: `structure.rs` pairs them over the whole
//! program. The spellings without underscore (`ENDIF`, `ENDWHILE` ...) are read too.

use super::macros::Failed;
use super::Reader;
use crate::alarm::{Alarm, AlarmCode};
use crate::syntax::expr::Statement;
use crate::syntax::Block;

type Read<T = ()> = Result<T, Failed>;

/// The keyword statements, by their spellings.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Keyword {
    If,
    ElseIf,
    Else,
    EndIf,
    While,
    EndWhile,
    For,
    EndFor,
    Repeat,
    Until,
    EndRepeat,
    Case,
    EndCase,
    Exit,
    Goto,
    Wait,
    Alarm,
    Message,
}

const KEYWORDS: &[(&str, Keyword)] = &[
    ("IF", Keyword::If),
    ("ELSEIF", Keyword::ElseIf),
    ("ELSIF", Keyword::ElseIf),
    ("ELSE", Keyword::Else),
    ("END_IF", Keyword::EndIf),
    ("ENDIF", Keyword::EndIf),
    ("WHILE", Keyword::While),
    ("END_WHILE", Keyword::EndWhile),
    ("ENDWHILE", Keyword::EndWhile),
    ("FOR", Keyword::For),
    ("END_FOR", Keyword::EndFor),
    ("ENDFOR", Keyword::EndFor),
    ("REPEAT", Keyword::Repeat),
    ("UNTIL", Keyword::Until),
    ("END_REPEAT", Keyword::EndRepeat),
    ("ENDREPEAT", Keyword::EndRepeat),
    ("CASE", Keyword::Case),
    ("END_CASE", Keyword::EndCase),
    ("ENDCASE", Keyword::EndCase),
    ("EXIT", Keyword::Exit),
    ("GOTO", Keyword::Goto),
    ("WAIT", Keyword::Wait),
    ("SLEEP", Keyword::Wait),
    ("ALARM", Keyword::Alarm),
    ("MSG", Keyword::Message),
];

impl Reader<'_, '_> {
    /// A keyword statement of a macro program at the cursor; `None` (nothing consumed) when
    /// the letters there are no keyword.
    pub(super) fn read_structured_statement(&mut self, block: &mut Block) -> Option<Read> {
        let name = self.letters();
        let &(_, keyword) = KEYWORDS.iter().find(|(k, _)| *k == name)?;
        let start = self.pos;
        let at_start = block.words.is_empty() && block.statements.is_empty();
        if !at_start && keyword != Keyword::Goto {
            let span = self.clamped(start, start + name.len());
            block.alarms.push(
                Alarm::error(
                    AlarmCode::MacroSyntax,
                    span,
                    format!("{name} must start a statement"),
                )
                .with_help("is a `;` missing before it?"),
            );
            return Some(Err(Failed));
        }
        self.pos += name.len();
        let read = self
            .structured_statement(block, keyword, &name, start)
            .and_then(|()| self.end_of_statement(block, &name));
        Some(read)
    }

    fn structured_statement(
        &mut self,
        block: &mut Block,
        keyword: Keyword,
        name: &str,
        start: usize,
    ) -> Read {
        if let Some(statement) = lone_keyword(keyword, self.span(start, self.pos)) {
            block.statements.push(statement);
            return Ok(());
        }
        let statement = match keyword {
            Keyword::If | Keyword::ElseIf => {
                let condition = self.expression(block)?;
                self.keyword(block, "THEN", name)?;
                let span = self.span(start, self.pos);
                if keyword == Keyword::If {
                    Statement::If { condition, span }
                } else {
                    Statement::ElseIf { condition, span }
                }
            }
            Keyword::While => {
                let condition = self.expression(block)?;
                self.keyword(block, "DO", name)?;
                Statement::WhileDo {
                    condition,
                    span: self.span(start, self.pos),
                }
            }
            Keyword::For => self.read_for(block, start)?,
            Keyword::Case => {
                let selector = self.expression(block)?;
                self.keyword(block, "OF", name)?;
                Statement::Case {
                    selector,
                    span: self.span(start, self.pos),
                }
            }
            Keyword::Until => {
                let condition = self.expression(block)?;
                block.statements.push(Statement::Until {
                    condition,
                    span: self.span(start, self.pos),
                });
                // `UNTIL condition END_REPEAT;` closes the loop in one statement.
                self.skip_blanks();
                let end = self.letters();
                if end != "END_REPEAT" && end != "ENDREPEAT" {
                    return Ok(());
                }
                let at = self.pos;
                self.pos += end.len();
                Statement::EndRepeat {
                    span: self.span(at, self.pos),
                }
            }
            Keyword::Goto => {
                // `GOTO N10` names the block as it is written.
                self.skip_blanks();
                if matches!(self.peek(), Some(b'N' | b'n'))
                    && self.peek_at(1).is_some_and(|b| b.is_ascii_digit())
                {
                    self.pos += 1;
                }
                let target = self.expression(block)?;
                Statement::Goto {
                    target,
                    span: self.span(start, self.pos),
                }
            }
            Keyword::Wait => {
                self.expect(block, b'(', &format!("after {name}"))?;
                self.expect(block, b')', &format!("after {name}(: it takes no argument"))?;
                Statement::Wait {
                    span: self.span(start, self.pos),
                }
            }
            Keyword::Alarm => {
                self.expect(block, b'(', "after ALARM")?;
                let number = self.expression(block)?;
                self.optional_text(block)?;
                self.expect(block, b')', "to close ALARM's arguments")?;
                Statement::Alarm {
                    number,
                    span: self.span(start, self.pos),
                }
            }
            Keyword::Message => self.read_message(block, start)?,
            _ => return Ok(()),
        };
        block.statements.push(statement);
        Ok(())
    }

    /// `FOR #i := from TO to [BY step] DO`, the cursor after FOR.
    fn read_for(&mut self, block: &mut Block, start: usize) -> Read<Statement> {
        self.skip_blanks();
        if !matches!(self.peek(), Some(b'#' | b'@')) {
            let at = self.pos;
            return Err(self.fail(
                block,
                at,
                at + 1,
                "FOR needs a counter variable: FOR #1 := 1 TO 10 DO".into(),
            ));
        }
        let variable = self.assigned_variable(block)?;
        let from = self.expression(block)?;
        self.keyword(block, "TO", "FOR")?;
        let to = self.expression(block)?;
        self.skip_blanks();
        let step = if self.letters() == "BY" {
            self.pos += 2;
            Some(self.expression(block)?)
        } else {
            None
        };
        self.keyword(block, "DO", "FOR")?;
        Ok(Statement::For {
            variable,
            from,
            to,
            step,
            span: self.span(start, self.pos),
        })
    }

    /// `MSG("text")`, `MSG(n)` or `MSG(n, "text")`, the cursor after MSG.
    fn read_message(&mut self, block: &mut Block, start: usize) -> Read<Statement> {
        self.expect(block, b'(', "after MSG")?;
        self.skip_blanks();
        let number = if self.peek() == Some(b'"') {
            None
        } else {
            Some(self.expression(block)?)
        };
        if number.is_none() {
            self.text_argument(block)?;
        } else {
            self.optional_text(block)?;
        }
        self.expect(block, b')', "to close MSG's arguments")?;
        Ok(Statement::Message {
            number,
            span: self.span(start, self.pos),
        })
    }

    /// `, "text"` if it follows: the text becomes the block's message.
    fn optional_text(&mut self, block: &mut Block) -> Read {
        self.skip_blanks();
        if self.peek() != Some(b',') {
            return Ok(());
        }
        self.pos += 1;
        self.text_argument(block)
    }

    /// `"text"`: the block's message.
    fn text_argument(&mut self, block: &mut Block) -> Read {
        self.skip_blanks();
        let open = self.pos;
        if self.peek() != Some(b'"') {
            return Err(self.fail(block, open, open + 1, "expected a text in `\"`".into()));
        }
        let Some(length) = self.text[open + 1..].iter().position(|&b| b == b'"') else {
            return Err(self.fail(
                block,
                open,
                open + 1,
                "the text is not closed with `\"`".into(),
            ));
        };
        let text = &self.text[open + 1..open + 1 + length];
        block.message = Some(String::from_utf8_lossy(text).trim().into());
        self.pos = open + length + 2;
        Ok(())
    }

    /// The keyword `word` (THEN, DO, TO) that must follow the statement's `what`.
    fn keyword(&mut self, block: &mut Block, word: &str, what: &str) -> Read {
        self.skip_blanks();
        if self.letters() == word {
            self.pos += word.len();
            if word == "DO" && self.peek().is_some_and(|b| b.is_ascii_digit()) {
                let at = self.pos;
                return Err(self.fail(
                    block,
                    at,
                    at + 1,
                    format!("{what} ... DO takes no loop number in a %@MACRO program: END_{what} ends the loop"),
                ));
            }
            return Ok(());
        }
        let at = self.pos;
        let found = match self.peek() {
            None => "the end of the statement".to_string(),
            Some(_) => format!("`{}`", self.token_at(at)),
        };
        Err(self.fail(
            block,
            at,
            at + 1,
            format!("{what} needs {word} here, found {found}"),
        ))
    }

    /// A CASE label at the cursor (`2:`, `2, -3:`), as the cutter hands it over: nothing
    /// after its `:`. False (nothing consumed) when the statement is no label.
    pub(super) fn read_case_label(&mut self, block: &mut Block) -> bool {
        let rest = &self.text[self.pos..];
        let Some(colon) = rest.iter().position(|&b| b == b':') else {
            return false;
        };
        if rest.get(colon + 1) == Some(&b'=') || !is_case_label_list(&rest[..colon]) {
            return false;
        }
        let end = self.pos + colon;
        let mut start = self.pos;
        while start < end {
            let length = self.text[start..end]
                .iter()
                .position(|&b| b == b',')
                .unwrap_or(end - start);
            if self.read_label_value(block, start, start + length).is_err() {
                return true;
            }
            start += length + 1;
        }
        self.pos = end + 1;
        // The alarm is in the block already.
        let _ = self.end_of_statement(block, "a CASE label");
        true
    }

    /// One value of a CASE label list, the bytes `start..end` (blanks around it). A value that
    /// cannot be read is still a label (one that equals nothing), so that the CASE reaches its
    /// block and raises the alarm there.
    fn read_label_value(&mut self, block: &mut Block, start: usize, end: usize) -> Read {
        let raw = &self.text[start..end];
        let first = start + raw.iter().take_while(|b| b.is_ascii_whitespace()).count();
        let last = end
            - raw
                .iter()
                .rev()
                .take_while(|b| b.is_ascii_whitespace())
                .count();
        let text = String::from_utf8_lossy(&self.text[first..last.max(first)]).into_owned();
        let value = text.parse::<i32>().map_or(f64::NAN, f64::from);
        // A label may run over lines; a message stays on one.
        let text = text.split_whitespace().collect::<Vec<_>>().join(" ");
        block.statements.push(Statement::CaseLabel {
            value,
            span: self.span(first, last),
        });
        if text.contains("..") {
            block.alarms.push(Alarm::not_supported(
                self.clamped(first, last),
                &format!("the CASE label range `{text}`"),
                None,
            ));
            return Err(Failed);
        }
        match value.is_nan() {
            false => Ok(()),
            true => Err(self.fail(
                block,
                first,
                last.max(first + 1),
                format!("`{text}`: a CASE label is a whole number (`2:`, `2, 3:`)"),
            )),
        }
    }

    /// Nothing may follow a keyword statement but the `;` that was cut off.
    fn end_of_statement(&mut self, block: &mut Block, name: &str) -> Read {
        self.skip_blanks();
        if self.at_end() {
            return Ok(());
        }
        let at = self.pos;
        let alarm = Alarm::error(
            AlarmCode::MacroSyntax,
            self.clamped(at, at + self.token_at(at).len().max(1)),
            format!("`{}` after {name}", self.token_at(at)),
        )
        .with_help("is a `;` missing?");
        block.alarms.push(alarm);
        Err(Failed)
    }

    /// The word or character at `at`, to name it in a message.
    fn token_at(&self, at: usize) -> String {
        let rest = &self.text[at.min(self.text.len())..];
        let length = rest
            .iter()
            .take_while(|b| b.is_ascii_alphanumeric() || **b == b'_')
            .count()
            .max(1)
            .min(rest.len());
        String::from_utf8_lossy(&rest[..length]).into_owned()
    }
}

/// The statements that are their keyword alone (ELSE, END_IF, REPEAT ...), at `span`.
/// The text before a `:` is a CASE label list: whole numbers (signs, commas and blanks
/// between them; `..` is read to name ranges in an alarm) and at least one digit.
pub(crate) fn is_case_label_list(text: &[u8]) -> bool {
    text.iter().any(u8::is_ascii_digit)
        && text
            .iter()
            .all(|b| b.is_ascii_digit() || b.is_ascii_whitespace() || b"+-,.".contains(b))
}

fn lone_keyword(keyword: Keyword, span: crate::source::Span) -> Option<Statement> {
    Some(match keyword {
        Keyword::Else => Statement::Else { span },
        Keyword::EndIf => Statement::EndIf { span },
        Keyword::EndWhile => Statement::EndWhile { span },
        Keyword::EndFor => Statement::EndFor { span },
        Keyword::Repeat => Statement::Repeat { span },
        Keyword::EndRepeat => Statement::EndRepeat { span },
        Keyword::Exit => Statement::Exit { span },
        Keyword::EndCase => Statement::EndCase { span },
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::super::macros::tests::describe;
    use crate::source::FileId;
    use crate::syntax::iso::parser::parse_macro_statement;
    use crate::syntax::iso::{LineBlocks, SyntaxOptions};

    /// One macro statement (as the cutter hands it over: no `;`), described.
    fn show(text: &str) -> String {
        let mut out = LineBlocks::new();
        let options = SyntaxOptions::default();
        parse_macro_statement(text.as_bytes(), 0, 1, FileId(0), &options, &mut out);
        out.as_slice().first().map_or("nothing".into(), describe)
    }

    #[test]
    fn conditions_follow_structured_text_precedence() {
        assert_eq!(
            show("IF #1 = 1 AND #2 <> 3 THEN"),
            "if #1 1 Equal #2 3 NotEqual And then"
        );
        assert_eq!(
            show("#3 := 1 + 2 * 3 >= 7 OR NOT #2 < 0"),
            "#[3] = 1 2 3 Multiply Add 7 GreaterOrEqual #2 Not 0 Less Or"
        );
        assert_eq!(
            show("#3 := (1 + 2) * 3 MOD 4"),
            "#[3] = 1 2 Add 3 Multiply 4 Modulo"
        );
        assert_eq!(
            show("ELSIF #1 > 2 XOR #2 <= 1 THEN"),
            "elseif #1 2 Greater #2 1 LessOrEqual Xor then"
        );
        assert_eq!(show("ELSEIF [#1 GT 2] THEN"), "elseif #1 2 Greater then");
    }

    #[test]
    fn loops_read_their_parts() {
        assert_eq!(
            show("FOR #1 := 10 TO 0 BY -2 DO"),
            "for #[1] = 10 to 0 by 2 neg do"
        );
        assert_eq!(show("for @7 := #2 to #3 do"), "for @[7] = #2 to #3 do");
        assert_eq!(show("WHILE #1 < 3 DO"), "while #1 3 Less do");
        assert_eq!(
            show("UNTIL #1 >= 3 END_REPEAT"),
            "until #1 3 GreaterOrEqual | end_repeat"
        );
        assert_eq!(show("UNTIL #1 ENDREPEAT"), "until #1 | end_repeat");
        assert_eq!(show("ENDWHILE"), "end_while");
        assert_eq!(show("EXIT"), "exit");
    }

    #[test]
    fn public_variables_functions_and_words() {
        assert_eq!(
            show("@5 := @[#1 + 1] * 2"),
            "@[5] = #1 1 Add @[] 2 Multiply"
        );
        assert_eq!(
            show("#1 := ABS(-2) + MAX(1, 2) + ATAN2(1, -1) + CEIL[1.2]"),
            "#[1] = 2 neg Abs 1 2 Max Add 1 1 neg Atan2 Add 1.2 Ceil Add"
        );
        assert_eq!(
            show("G01 X(#1 + 50.) Y@2 F#9"),
            "G1 | X(#1 50 Add) | Y(@2) | F(#9)"
        );
        assert_eq!(show("G#30 G#31"), "G(#30) | G(#31)");
    }

    #[test]
    fn calls_and_jumps() {
        assert_eq!(show("GOTO N100"), "goto 100");
        assert_eq!(show("GOTO #2"), "goto #2");
        assert_eq!(
            show("ALARM(301, \"TOOL MISSING\")"),
            "alarm 301 | \"TOOL MISSING\""
        );
        assert_eq!(
            show("MSG(\"check; the tool\")"),
            "msg  | \"check; the tool\""
        );
        assert_eq!(show("WAIT()"), "wait");
        assert_eq!(show("SLEEP ( )"), "wait");
    }

    #[test]
    fn malformed_statements_are_alarms_that_name_the_problem() {
        assert_eq!(show("END_IF G01"), "alarm 7: `G01` after END_IF");
        assert_eq!(
            show("#1 := 1 IF #2 THEN"),
            "alarm 8: IF must start a statement"
        );
        assert_eq!(
            show("FOR 1 TO 2 DO"),
            "alarm 4: FOR needs a counter variable: FOR #1 := 1 TO 10 DO"
        );
        assert_eq!(
            show("WHILE #1 < 2"),
            "alarm 11: WHILE needs DO here, found the end of the statement"
        );
        assert_eq!(
            show("IF #1 = 1 DO"),
            "alarm 10: IF needs THEN here, found `DO`"
        );
        assert_eq!(show("CASE #1 + 1 OF"), "case #1 1 Add of");
        assert_eq!(
            show("CASE #1"),
            "alarm 6: CASE needs OF here, found the end of the statement"
        );
        assert_eq!(show("2, -3 :"), "label 2 | label -3");
        assert_eq!(show("END_CASE"), "end_case");
        assert_eq!(
            show("1.5:"),
            "alarm 0: `1.5`: a CASE label is a whole number (`2:`, `2, 3:`)"
        );
        // A label over two lines (a fuzz finding): the message stays on one line.
        assert_eq!(
            show("2\n1:"),
            "alarm 0: `2 1`: a CASE label is a whole number (`2:`, `2, 3:`)"
        );
        assert_eq!(
            show("1..3:"),
            "alarm 0: the CASE label range `1..3` is not supported yet"
        );
        assert_eq!(show("1: #2 := 1"), "alarm 3: `#` after a CASE label");
        assert_eq!(
            show("#1 := GETARG(X)"),
            "alarm 6: the macro function `GETARG` is not supported yet"
        );
        assert_eq!(
            show("(comment) G01 X1."),
            "alarm 0: `(` where a statement or a word should start"
        );
        assert_eq!(
            show("#1 := (1 + 2"),
            "alarm 11: expected `)` to close the bracket"
        );
        assert_eq!(
            show("#1 := FOO"),
            "alarm 6: `FOO` is not a macro function or value"
        );
        assert_eq!(
            show("WHILE [#1 LT 3] DO1"),
            "alarm 18: WHILE ... DO takes no loop number in a %@MACRO program: END_WHILE ends the loop"
        );
    }
}
