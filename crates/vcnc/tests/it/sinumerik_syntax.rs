//! The SINUMERIK block parser: DIN words and numeric extensions (manual 2.2.3), skip levels,
//! block numbers and labels, calls, statements, expressions and their precedence, and that no
//! line makes it panic. The expected values are worked out by hand in each test.

use vcnc::source::FileId;
use vcnc::syntax::sinumerik::{
    parse_block, BinaryOp, Block, DataType, Definition, Expr, ExprKind, Initializer, Jump,
    JumpKind, JumpTarget, Scope, Statement, StatementKind, UnaryOp, Value, Word,
};

fn block(text: &str) -> Block {
    let block = parse_block(text.as_bytes(), FileId(0), 1, 0);
    assert_eq!(block.alarm, None, "{text:?}");
    block
}

/// The words of `text` as (address, constant) for DIN words, (address, NaN) for others.
fn constants(text: &str) -> Vec<(String, f64)> {
    block(text)
        .words
        .iter()
        .map(|w| match &w.value {
            Value::Constant(n) => (w.address.to_string(), n.value),
            _ => (w.address.to_string(), f64::NAN),
        })
        .collect()
}

fn pairs(list: &[(&str, f64)]) -> Vec<(String, f64)> {
    list.iter().map(|(a, v)| (a.to_string(), *v)).collect()
}

/// The value of a constant expression, computed here by the manual's rules (comparisons give
/// 1 or 0; AND and OR on non-zero values).
fn eval(expr: &Expr) -> f64 {
    match &expr.kind {
        ExprKind::Number(v) => *v,
        ExprKind::Unary(UnaryOp::Minus, e) => -eval(e),
        ExprKind::Unary(UnaryOp::Not, e) => f64::from(u8::from(eval(e) == 0.0)),
        ExprKind::Unary(UnaryOp::BitNot, e) => f64::from(!(eval(e) as i32)),
        ExprKind::Call(name, args) if &**name == "SIN" => {
            eval(args[0].as_ref().unwrap()).to_radians().sin()
        }
        ExprKind::Binary(op, a, b) => {
            let (a, b) = (eval(a), eval(b));
            let truth = |t: bool| f64::from(u8::from(t));
            match op {
                BinaryOp::Equal => truth(a == b),
                BinaryOp::NotEqual => truth(a != b),
                BinaryOp::Less => truth(a < b),
                BinaryOp::Greater => truth(a > b),
                BinaryOp::LessEqual => truth(a <= b),
                BinaryOp::GreaterEqual => truth(a >= b),
                BinaryOp::Or => truth(a != 0.0 || b != 0.0),
                BinaryOp::Xor => truth((a != 0.0) != (b != 0.0)),
                BinaryOp::And => truth(a != 0.0 && b != 0.0),
                BinaryOp::BitOr => f64::from(a as i32 | b as i32),
                BinaryOp::BitXor => f64::from(a as i32 ^ b as i32),
                BinaryOp::BitAnd => f64::from(a as i32 & b as i32),
                BinaryOp::Add => a + b,
                BinaryOp::Subtract => a - b,
                BinaryOp::Multiply => a * b,
                BinaryOp::Divide => a / b,
                BinaryOp::IntDivide => (a / b).trunc(),
                BinaryOp::Modulo => a % b,
                BinaryOp::Chain => panic!("no strings here"),
            }
        }
        other => panic!("not a constant: {other:?}"),
    }
}

/// The value given to the one word of `text` (`R1=...`).
fn value_of(text: &str) -> f64 {
    match &block(text).words[..] {
        [Word {
            value: Value::Expression(e),
            ..
        }] => eval(e),
        other => panic!("{text:?}: {other:?}"),
    }
}

#[test]
fn din_words_with_and_without_blanks() {
    // Manual L592-594, and `N140G0 X34` (L3107): words need no separator where the split is
    // unambiguous; a blank may follow the address letter.
    let b = block("N140G0 X34");
    assert_eq!(b.number, Some(140));
    assert_eq!(constants("N140G0 X34"), pairs(&[("G", 0.0), ("X", 34.0)]));
    assert_eq!(
        constants("G1X-10.5Y+2 F 100"),
        pairs(&[("G", 1.0), ("X", -10.5), ("Y", 2.0), ("F", 100.0)])
    );
    assert_eq!(constants("g1 x.5"), pairs(&[("G", 1.0), ("X", 0.5)]));
}

#[test]
fn digits_before_equals_are_a_numeric_extension() {
    // L604-606: `X1=10` is X1 := 10, `X110` is X := 110, `M2=4` is M4 for spindle 2, `M2` is M2.
    let b = block("X1=10 X110 M2=4 M2 R10=5");
    let addresses: Vec<&str> = b.words.iter().map(|w| &*w.address).collect();
    assert_eq!(addresses, ["X1", "X", "M2", "M", "R10"]);
    assert!(matches!(b.words[0].value, Value::Expression(_)));
    assert!(matches!(b.words[1].value, Value::Constant(n) if n.value == 110.0));
    assert!(matches!(b.words[3].value, Value::Constant(n) if n.value == 2.0));
}

#[test]
fn an_expression_needs_equals_and_ends_at_the_next_word() {
    // L592-594: X=10*(5+SIN(37.5)).
    let b = block("G1 X=10*(5+SIN(37.5)) Y=R1 Z20");
    assert_eq!(b.words.len(), 4);
    let Value::Expression(x) = &b.words[1].value else {
        panic!("{:?}", b.words[1])
    };
    let expected = 10.0 * (5.0 + 37.5_f64.to_radians().sin());
    assert!((eval(x) - expected).abs() < 1e-12);
    assert!(
        matches!(&b.words[2].value, Value::Expression(Expr { kind: ExprKind::Name(n), .. }) if &**n == "R1")
    );
    assert!(matches!(b.words[3].value, Value::Constant(n) if n.value == 20.0));
}

#[test]
fn the_manuals_precedence() {
    assert_eq!(value_of("R1=2+3*4"), 14.0);
    assert_eq!(value_of("R1=(2+3)*4"), 20.0);
    assert_eq!(value_of("R1=2-3-4"), -5.0);
    assert_eq!(value_of("R1=7 DIV 2 + 7 MOD 2"), 4.0);
    assert_eq!(value_of("R1=-2*3"), -6.0);
    assert_eq!(value_of("R1=12/3/2"), 2.0);
    // Comparisons bind least: 1 == (1 AND 0) is 1 == 0.
    assert_eq!(value_of("R1=1==1 AND 0"), 0.0);
    assert_eq!(value_of("R1=(1==1) AND 1"), 1.0);
    // AND before OR: 1 OR (0 AND 0).
    assert_eq!(value_of("R1=1 OR 0 AND 0"), 1.0);
    // B_AND before B_OR: 1 B_OR (2 B_AND 3) = 1 | 2 = 3.
    assert_eq!(value_of("R1=1 B_OR 2 B_AND 3"), 3.0);
    // + before B_AND: 1 B_AND (1+2) = 1.
    assert_eq!(value_of("R1=1 B_AND 1+2"), 1.0);
    assert_eq!(value_of("R1=NOT 0"), 1.0);
    assert_eq!(value_of("R1=3<>4"), 1.0);
    assert_eq!(value_of("R1=2 >= 3"), 0.0);
}

#[test]
fn constants_in_other_notations() {
    assert_eq!(value_of("R1=1.5EX3"), 1500.0);
    // Part B, table of 15.x: X=-.1EX-3.
    assert!((value_of("R1=-.1EX-3") + 0.0001).abs() < 1e-15);
    assert_eq!(value_of("R1='H1F'"), 31.0);
    // Tables 0.3: 'B10000001' is 129.
    assert_eq!(value_of("R1='B10000001'"), 129.0);
}

#[test]
fn skip_levels_numbers_and_labels() {
    // Manual 2.2.5: `/` is the first level, `/0` too, `/9` the tenth.
    assert_eq!(block("/N20 G0").skip, Some(0));
    assert_eq!(block("/0 ; comment").skip, Some(0));
    assert_eq!(block("/9 N090").skip, Some(9));
    assert_eq!(block("N10 G0").skip, None);
    let b = block(":100 G0");
    assert_eq!(b.number, Some(100));
    // Example a/10, N280: a label after the block number.
    let b = block("N280  POSITION: ; jump label");
    assert_eq!(
        (b.number, b.label.as_deref()),
        (Some(280), Some("POSITION"))
    );
    assert!(b.words.is_empty());
    assert_eq!(block("ENDLABEL:").label.as_deref(), Some("ENDLABEL"));
    // A comment only: no words (example a/02).
    assert!(block("N10 ; G&S company, order no. 12A71").words.is_empty());
}

#[test]
fn calls_strings_and_keywords() {
    let b = block("N270 MCALL CYCLE82(2,0,1,-2.6,,0)");
    assert_eq!(&*b.words[0].address, "MCALL");
    assert_eq!(b.words[0].value, Value::Bare);
    assert_eq!(&*b.words[1].address, "CYCLE82");
    let Value::Call(args) = &b.words[1].value else {
        panic!("{:?}", b.words[1])
    };
    assert_eq!(args.len(), 6);
    assert!(args[4].is_none());
    assert_eq!(eval(args[3].as_ref().unwrap()), -2.6);
    let b = block("N10 T=\"PF60\" ; tool by name");
    assert!(
        matches!(&b.words[0].value, Value::Expression(Expr { kind: ExprKind::Text(t), .. }) if &**t == "PF60")
    );
    let b = block("MSG(\"THIS IS MY NC PROGRAM\")");
    assert!(matches!(&b.words[0].value, Value::Call(a) if a.len() == 1));
    assert!(matches!(&block("CYCLE800()").words[0].value, Value::Call(a) if a.is_empty()));
    // A multi-letter address with a constant and no `=`, as the manual writes FZ (L3909).
    assert_eq!(constants("G95 FZ0.03"), pairs(&[("G", 95.0), ("FZ", 0.03)]));
}

#[test]
fn a_name_that_begins_with_a_keyword_is_no_statement() {
    // `DEFX=1` assigns to a name that begins with DEF; `IF1=2` to one that begins with IF.
    assert_eq!(block("DEFX=1").statement, None);
    assert_eq!(block("IFX=2 GOTOX=1").statement, None);
    assert_eq!(block("LOOP[1]=3").statement, None);
}

#[test]
fn indexed_names_and_system_variables() {
    let b = block("$P_UIFR[1,X,TR]=10 R[2]=3");
    let Value::Indexed(indices, Some(value)) = &b.words[0].value else {
        panic!("{:?}", b.words[0])
    };
    assert_eq!(&*b.words[0].address, "$P_UIFR");
    assert_eq!(indices.len(), 3);
    assert_eq!(eval(value), 10.0);
    assert_eq!(&*b.words[1].address, "R");
}

#[test]
fn spans_point_at_the_words() {
    let text = "N10 G1 X=AC(5) ; c";
    let b = parse_block(text.as_bytes(), FileId(3), 7, 100);
    let x = &b.words[1];
    assert_eq!((x.span.line, x.span.file), (7, FileId(3)));
    assert_eq!(
        &text[x.span.start as usize - 100..x.span.end as usize - 100],
        "X=AC(5)"
    );
    assert!(
        matches!(&x.value, Value::Expression(Expr { kind: ExprKind::Call(n, a), .. }) if &**n == "AC" && a.len() == 1)
    );
}

#[test]
fn malformed_blocks_carry_an_alarm() {
    for text in [
        "G1 X=",
        "R1=(2+3",
        "R1=2+",
        "X=\"open",
        "G1 # X1",
        "R1='H'",
        "R1='Z12'",
        "R1=1EX",
        "CYCLE82(1,2",
        "A[1=2",
        "N99999999999 G0",
    ] {
        let b = parse_block(text.as_bytes(), FileId(0), 1, 0);
        let alarm = b
            .alarm
            .unwrap_or_else(|| panic!("{text:?} read as {:?}", b.words));
        let span = alarm.span.expect("an alarm of a block has a span");
        assert!(span.end as usize <= text.len(), "{text:?}: {alarm:?}");
    }
}

#[test]
fn deep_nesting_is_refused_not_a_stack_overflow() {
    let deep = format!("R1={}1{}", "(".repeat(5000), ")".repeat(5000));
    assert!(parse_block(deep.as_bytes(), FileId(0), 1, 0)
        .alarm
        .is_some());
    let minus = format!("R1={}1", "-".repeat(5000));
    assert!(parse_block(minus.as_bytes(), FileId(0), 1, 0)
        .alarm
        .is_some());
}

proptest::proptest! {
    #[test]
    fn no_line_makes_the_parser_panic(line in proptest::collection::vec(proptest::num::u8::ANY, 0..80)) {
        let _ = parse_block(&line, FileId(0), 1, 0);
    }

    #[test]
    fn no_line_of_its_characters_makes_the_parser_panic(
        line in "[A-Z0-9 =+*/<>()\\[\\],:;.'\"$_-]{0,60}",
    ) {
        let block = parse_block(line.as_bytes(), FileId(0), 1, 0);
        if let Some(alarm) = block.alarm {
            proptest::prop_assert!(alarm.span.is_some_and(|s| s.end as usize <= line.len()));
        }
    }

    /// Statement keywords among words and expressions: spans stay inside the line.
    #[test]
    fn no_statement_line_makes_the_parser_panic(
        line in "(IF |FOR |REPEAT |CASE\\(|DEF |PROC |EXTERN |DEFINE |GOTOF |GOTOS|ENDLABEL:)\
                 ([A-Z0-9 =+*<>(),\\[\\]\"_-]|TO |OF |GOTOB |DEFAULT |SET\\(|REP\\(|VAR |REAL |STRING\\[|AS |P=){0,20}",
    ) {
        let block = parse_block(line.as_bytes(), FileId(0), 1, 0);
        let inside = |s: vcnc::source::Span| s.start <= s.end && s.end as usize <= line.len();
        if let Some(alarm) = &block.alarm {
            proptest::prop_assert!(alarm.span.is_some_and(inside), "{alarm:?}");
        }
        if let Some(statement) = &block.statement {
            proptest::prop_assert!(inside(statement.span));
            for expr in statement.expressions() {
                proptest::prop_assert!(inside(expr.span) && statement.span.to(expr.span) == statement.span);
            }
        }
    }
}

/// The statement keyword a line of a program holds, found without the parser: the first name
/// after the skip mark, block number and label, or a jump's keyword anywhere.
fn keyword_of(line: &str) -> Option<String> {
    const FIRST: [&str; 18] = [
        "IF", "ELSE", "ENDIF", "WHILE", "ENDWHILE", "FOR", "ENDFOR", "REPEAT", "REPEATB", "UNTIL",
        "LOOP", "ENDLOOP", "CASE", "DEF", "PROC", "EXTERN", "DEFINE", "ENDLABEL",
    ];
    let code = line.split(';').next().unwrap_or("").to_ascii_uppercase();
    let names: Vec<&str> = code
        .split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .filter(|n| !n.is_empty())
        .collect();
    let mut first = names.iter().copied();
    let mut name = first.next()?;
    if name.starts_with('N') && name[1..].bytes().all(|b| b.is_ascii_digit()) {
        name = first.next()?;
    }
    // A label: the name is followed by `:` in the text.
    if code.contains(&format!("{name}:")) && name != "ENDLABEL" {
        name = first.next()?;
    }
    if FIRST.contains(&name) {
        return Some(name.to_string());
    }
    names
        .iter()
        .find(|n| matches!(**n, "GOTO" | "GOTOF" | "GOTOB" | "GOTOC" | "GOTOS"))
        .map(|n| n.to_string())
}

/// Every line of the manual's SINUMERIK examples and of the SINUMERIK corpus programs reads
/// without an alarm, but for the header line (`%_N_..`), which is not a block; and every line
/// that holds a statement keyword reads into that statement (an IF or CASE with its jumps for a
/// jump after them). Lines are split at LF, CR LF and CR.
#[test]
fn every_line_of_the_examples_and_the_corpus_reads() {
    let Some(shared) = crate::common::shared::shared_dir() else {
        return;
    };
    let mut files = Vec::new();
    for folder in [
        "spec/examples/sinumerik-a",
        "spec/examples/sinumerik-b",
        "corpus/sinumerik",
    ] {
        let mut entries: Vec<_> = std::fs::read_dir(shared.join(folder))
            .unwrap_or_else(|e| panic!("{folder}: {e}"))
            .map(|e| e.expect("a folder entry").path())
            .collect();
        entries.sort();
        files.extend(entries);
    }
    assert!(files.len() > 150, "{} files", files.len());
    let mut failures = Vec::new();
    let mut lines_read = 0;
    let mut seen = std::collections::BTreeMap::<String, usize>::new();
    for path in &files {
        let bytes = std::fs::read(path).expect("readable");
        let text = String::from_utf8_lossy(&bytes)
            .replace("\r\n", "\n")
            .replace('\r', "\n");
        for (number, line) in (1..).zip(text.lines()) {
            if line.trim_start().starts_with('%') {
                continue;
            }
            lines_read += 1;
            let block = parse_block(line.as_bytes(), FileId(0), number, 0);
            let place = format!("{}:{number}: {line}", path.display());
            if let Some(alarm) = block.alarm {
                failures.push(format!("{place}\n    {}", alarm.message));
                continue;
            }
            let read = block
                .statement
                .as_ref()
                .map(|s| s.kind.keyword().to_string());
            if let Some(kind) = &read {
                *seen.entry(kind.clone()).or_default() += 1;
            }
            let Some(expected) = keyword_of(line) else {
                continue;
            };
            let read = read.as_deref();
            let jump_inside = expected.starts_with("GOTO") && matches!(read, Some("IF" | "CASE"));
            if read != Some(&*expected) && !jump_inside {
                failures.push(format!("{place}\n    read as {read:?}, not {expected}"));
            }
        }
    }
    assert!(lines_read > 3000, "{lines_read} lines");
    assert!(
        failures.is_empty(),
        "{} of {lines_read} lines:\n{}",
        failures.len(),
        failures.join("\n")
    );
    // The kinds the examples and the corpus write (grep of the files): all of them read.
    for kind in [
        "IF", "ELSE", "ENDIF", "WHILE", "ENDWHILE", "FOR", "ENDFOR", "REPEAT", "CASE", "DEF",
        "PROC", "EXTERN", "ENDLABEL", "GOTOB", "WHEN", "WHENEVER", "EVERY", "DO",
    ] {
        assert!(seen.contains_key(kind), "no {kind} read: {seen:?}");
    }
}

#[test]
fn forms_real_programs_write() {
    // corpus jennings_CYCLE189.SPF: no blanks, R parameters end at their digits.
    let b = block("G0G90X=R24Y=R25");
    let addresses: Vec<&str> = b.words.iter().map(|w| &*w.address).collect();
    assert_eq!(addresses, ["G", "G", "X", "Y"]);
    let b = block("G3X=R24+R109I=(R109*(-1))J0.0F=R9*2");
    let addresses: Vec<&str> = b.words.iter().map(|w| &*w.address).collect();
    assert_eq!(addresses, ["G", "X", "I", "J", "F"]);
    // Blanks around `=` after a numeric extension (corpus, example a/35).
    let b = block("R107 = 1 S1 = 60");
    let addresses: Vec<&str> = b.words.iter().map(|w| &*w.address).collect();
    assert_eq!(addresses, ["R107", "S1"]);
    // A blank before a call's arguments (corpus dubovikov_CYCLE_KONUS.SPF, example b/74).
    assert!(
        matches!(&block("N480 MSG (\"KONUS OK?\")").words[0].value, Value::Call(a) if a.len() == 1)
    );
    let b = block("R104=ROUNDUP (R103/2)");
    assert!(
        matches!(&b.words[0].value, Value::Expression(Expr { kind: ExprKind::Call(n, a), .. }) if &**n == "ROUNDUP" && a.len() == 1)
    );
    // An axis keyword with an index and no value (example a/31).
    assert!(matches!(&block("N20 SCC[X]").words[0].value, Value::Indexed(i, None) if i.len() == 1));
    // A synchronized action after a word (example b/82).
    let b = block("N120 IDS=2 WHENEVER $AA_IM[AX4] > 100 DO ACCLIMA[AX4]=80");
    assert_eq!(b.words.len(), 1);
    let Some(Statement {
        kind: StatementKind::Action { keyword, rest },
        ..
    }) = b.statement
    else {
        panic!("{:?}", b.statement)
    };
    assert_eq!(&*keyword.value, "WHENEVER");
    let text = "N120 IDS=2 WHENEVER $AA_IM[AX4] > 100 DO ACCLIMA[AX4]=80";
    assert_eq!(
        &text[rest.start as usize..rest.end as usize],
        "$AA_IM[AX4] > 100 DO ACCLIMA[AX4]=80"
    );
    // An action without a condition (example a/37-fgroup-fgref.mpf).
    let text = "N130 DO $R1=$AC_TIME ; R1 = time";
    let b = block(text);
    assert!(b.words.is_empty());
    let Some(Statement {
        kind: StatementKind::Action { keyword, rest },
        ..
    }) = b.statement
    else {
        panic!("{:?}", b.statement)
    };
    assert_eq!(&*keyword.value, "DO");
    assert_eq!(
        &text[rest.start as usize..rest.end as usize],
        "$R1=$AC_TIME ; R1 = time"
    );
}

// ---- Statements ----

/// The statement of `text`, which must read without an alarm.
fn statement(text: &str) -> Statement {
    block(text)
        .statement
        .unwrap_or_else(|| panic!("{text:?} has no statement"))
}

/// The text of `span` in `text` (a line read at base 0).
fn at(text: &str, span: vcnc::source::Span) -> &str {
    &text[span.start as usize..span.end as usize]
}

/// The name an expression is, or panics.
fn name(expr: &Expr) -> &str {
    match &expr.kind {
        ExprKind::Name(n) => n,
        other => panic!("not a name: {other:?}"),
    }
}

/// A jump's kind and its target as a label name.
fn label_jump(jump: &Jump) -> (JumpKind, &str) {
    match &jump.target {
        Some(JumpTarget::Label(label)) => (jump.kind, &label.value),
        other => panic!("not a label: {other:?}"),
    }
}

#[test]
fn if_with_a_jump_in_one_line() {
    // Manual L2856 (part A 7.4 example): `N50 IF $AA_IM[X]==R100 GOTOF LABEL1`.
    let text = "N50 IF $AA_IM[X]==R100 GOTOF LABEL1 ; comment";
    let s = statement(text);
    assert_eq!(at(text, s.span), "IF $AA_IM[X]==R100 GOTOF LABEL1");
    let StatementKind::If {
        condition,
        jump: Some(jump),
    } = &s.kind
    else {
        panic!("{s:?}")
    };
    assert_eq!(at(text, condition.span), "$AA_IM[X]==R100");
    assert!(matches!(
        condition.kind,
        ExprKind::Binary(BinaryOp::Equal, ..)
    ));
    assert_eq!(label_jump(jump), (JumpKind::GotoF, "LABEL1"));
    assert_eq!(at(text, jump.span), "GOTOF LABEL1");
    assert_eq!(at(text, jump.target.as_ref().unwrap().span()), "LABEL1");
    // Manual L6715; corpus dubovikov_CHAMFER.SPF writes parentheses in the condition.
    let s = statement("N69 IF $AC_LIFTFAST GOTOB MM_THREAD");
    let StatementKind::If {
        condition,
        jump: Some(jump),
    } = &s.kind
    else {
        panic!("{s:?}")
    };
    assert_eq!(name(condition), "$AC_LIFTFAST");
    assert_eq!(label_jump(jump), (JumpKind::GotoB, "MM_THREAD"));
    for (text, kind) in [
        ("IF R10<(R7-0.5*R5) GOTO METKA1", JumpKind::Goto),
        ("if r1 goToC metka1", JumpKind::GotoC),
    ] {
        let StatementKind::If {
            jump: Some(jump), ..
        } = statement(text).kind
        else {
            panic!("{text}")
        };
        assert_eq!(label_jump(&jump), (kind, "METKA1"));
    }
}

#[test]
fn if_else_endif_block_form() {
    // corpus alloyx_DAILY.MPF: `IF CYCLES < 1` ... ENDIF; corpus dubovikov: `N410 ELSE`.
    let text = "IF CYCLES < 1";
    let s = statement(text);
    let StatementKind::If {
        condition,
        jump: None,
    } = &s.kind
    else {
        panic!("{s:?}")
    };
    assert!(matches!(
        condition.kind,
        ExprKind::Binary(BinaryOp::Less, ..)
    ));
    assert_eq!(at(text, s.span), text);
    assert_eq!(statement("N410 ELSE").kind, StatementKind::Else);
    assert_eq!(statement("N430 ENDIF ; end").kind, StatementKind::EndIf);
    // A label before the statement stays the block's label.
    let b = block("ANFANG: IF R1==1");
    assert_eq!(b.label.as_deref(), Some("ANFANG"));
    assert!(matches!(
        b.statement.unwrap().kind,
        StatementKind::If { jump: None, .. }
    ));
}

#[test]
fn loops_and_their_ends() {
    // corpus ncplot7py_user_siemens_program.MPF: `WHILE R107 < R104+1`.
    let text = "WHILE R107 < R104+1";
    let StatementKind::While { condition } = statement(text).kind else {
        panic!()
    };
    assert_eq!(at(text, condition.span), "R107 < R104+1");
    assert_eq!(statement("ENDWHILE").kind, StatementKind::EndWhile);
    assert_eq!(statement("N10 REPEAT").kind, StatementKind::Repeat);
    let text = "UNTIL R1>=10";
    let StatementKind::Until { condition } = statement(text).kind else {
        panic!()
    };
    assert_eq!(at(text, condition.span), "R1>=10");
    assert_eq!(statement("LOOP").kind, StatementKind::Loop);
    assert_eq!(statement("endloop").kind, StatementKind::EndLoop);
    assert_eq!(statement("ENDFOR").kind, StatementKind::EndFor);
}

#[test]
fn for_with_its_counter_and_bounds() {
    // corpus alloyx_DAILY.MPF.
    let text = "FOR COUNT = 1 TO CYCLES";
    let s = statement(text);
    let StatementKind::For {
        variable,
        start,
        end,
    } = &s.kind
    else {
        panic!("{s:?}")
    };
    assert_eq!(name(variable), "COUNT");
    assert_eq!(start.kind, ExprKind::Number(1.0));
    assert_eq!(name(end), "CYCLES");
    assert_eq!(at(text, variable.span), "COUNT");
    assert_eq!(at(text, end.span), "CYCLES");
    // No blanks, an R parameter, an expression as the end: 0 to 5-1 = 4.
    let StatementKind::For { variable, end, .. } = statement("FOR R1=0 TO 5-1").kind else {
        panic!()
    };
    assert_eq!(name(&variable), "R1");
    assert_eq!(eval(&end), 4.0);
}

#[test]
fn repeat_with_labels_is_a_part_repetition() {
    // Example a/10-milling-example.mpf, N380: from POSITION to ENDLABEL (N280-N300).
    let text = "N380  REPEAT POSITION ; repeat";
    let s = statement(text);
    let StatementKind::RepeatSection { start, end, passes } = &s.kind else {
        panic!("{s:?}")
    };
    assert_eq!((&*start.value, end, passes), ("POSITION", &None, &None));
    assert_eq!(at(text, start.span), "POSITION");
    assert_eq!(at(text, s.span), "REPEAT POSITION");
    let text = "REPEAT BEGIN END_1 P=3";
    let StatementKind::RepeatSection { start, end, passes } = statement(text).kind else {
        panic!()
    };
    assert_eq!(&*start.value, "BEGIN");
    assert_eq!(at(text, end.unwrap().span), "END_1");
    assert_eq!(eval(&passes.unwrap()), 3.0);
    // One label and P, P given by a parameter.
    let StatementKind::RepeatSection { end, passes, .. } = statement("REPEAT PART P = R2").kind
    else {
        panic!()
    };
    assert!(end.is_none());
    assert_eq!(name(passes.as_ref().unwrap()), "R2");
    // A label that begins with P is a label.
    let StatementKind::RepeatSection { end, .. } = statement("REPEAT A PLACE").kind else {
        panic!()
    };
    assert_eq!(&*end.unwrap().value, "PLACE");
    let StatementKind::RepeatBlock { label, passes } = statement("REPEATB MARK P=2").kind else {
        panic!()
    };
    assert_eq!((&*label.value, eval(&passes.unwrap())), ("MARK", 2.0));
    assert!(matches!(
        statement("REPEATB MARK").kind,
        StatementKind::RepeatBlock { passes: None, .. }
    ));
}

#[test]
fn endlabel_is_a_label_and_a_statement() {
    // Example a/10-milling-example.mpf, N300.
    let text = "N300  ENDLABEL: ; end identifier for repetition";
    let b = block(text);
    assert_eq!(b.label.as_deref(), Some("ENDLABEL"));
    let s = b.statement.unwrap();
    assert_eq!(s.kind, StatementKind::EndLabel);
    assert_eq!(at(text, s.span), "ENDLABEL:");
    assert_eq!(statement("ENDLABEL").kind, StatementKind::EndLabel);
}

#[test]
fn case_with_its_branches_and_default() {
    // corpus dubovikov_case_test.MPF, N30.
    let text = "N30 CASE(VAR1+VAR2-VAR3) OF 8 GOTOF Label_1 6 GOTOF Label_2 DEFAULT GOTOF Label_3";
    let s = statement(text);
    let StatementKind::Case(case) = &s.kind else {
        panic!("{s:?}")
    };
    assert_eq!(at(text, case.selector.span), "(VAR1+VAR2-VAR3)");
    assert_eq!(case.branches.len(), 2);
    assert_eq!(case.branches[0].value.kind, ExprKind::Number(8.0));
    assert_eq!(
        label_jump(&case.branches[0].jump),
        (JumpKind::GotoF, "LABEL_1")
    );
    assert_eq!(case.branches[1].value.kind, ExprKind::Number(6.0));
    assert_eq!(at(text, case.branches[1].jump.span), "GOTOF Label_2");
    let default = case.default.as_ref().unwrap();
    assert_eq!(label_jump(default), (JumpKind::GotoF, "LABEL_3"));
    assert_eq!(at(text, s.span), &text[4..]);
    // A negative constant after a label, GOTOB, no DEFAULT.
    let StatementKind::Case(case) = statement("CASE(R1) OF -1 GOTOB A 2 GOTOF B").kind else {
        panic!()
    };
    assert_eq!(eval(&case.branches[0].value), -1.0);
    assert_eq!(label_jump(&case.branches[0].jump), (JumpKind::GotoB, "A"));
    assert_eq!(label_jump(&case.branches[1].jump), (JumpKind::GotoF, "B"));
    assert!(case.default.is_none());
}

#[test]
fn jumps_to_labels_numbers_and_strings() {
    // corpus dubovikov_CHAMFER.SPF: `N41 GOTOB METKA1`.
    let s = statement("N41 GOTOB METKA1");
    let StatementKind::Jump(jump) = &s.kind else {
        panic!("{s:?}")
    };
    assert_eq!(label_jump(jump), (JumpKind::GotoB, "METKA1"));
    let text = "GOTOF N100";
    let StatementKind::Jump(jump) = statement(text).kind else {
        panic!()
    };
    let Some(JumpTarget::BlockNumber(number)) = &jump.target else {
        panic!("{jump:?}")
    };
    assert_eq!((number.value, at(text, number.span)), (100, "N100"));
    // A STRING variable as the target is a name the interpreter resolves.
    let StatementKind::Jump(jump) = statement("GOTO ZIEL").kind else {
        panic!()
    };
    assert_eq!(label_jump(&jump), (JumpKind::Goto, "ZIEL"));
    // A computed target.
    let text = "GOTOC \"MARK\"<<R1";
    let StatementKind::Jump(jump) = statement(text).kind else {
        panic!()
    };
    let Some(JumpTarget::Expression(target)) = &jump.target else {
        panic!("{jump:?}")
    };
    assert!(matches!(target.kind, ExprKind::Binary(BinaryOp::Chain, ..)));
    assert_eq!(at(text, target.span), "\"MARK\"<<R1");
    let StatementKind::Jump(jump) = statement("GOTOB ZIELE[2]").kind else {
        panic!()
    };
    assert!(
        matches!(&jump.target, Some(JumpTarget::Expression(e)) if matches!(e.kind, ExprKind::Index(..)))
    );
    let s = statement("GOTOS");
    assert_eq!(s.kind.keyword(), "GOTOS");
    let StatementKind::Jump(jump) = s.kind else {
        panic!()
    };
    assert_eq!((jump.kind, jump.target), (JumpKind::GotoS, None));
}

#[test]
fn a_jump_may_follow_the_words_of_its_block() {
    // docs/SINUMERIK.md 3.1: the words stay words, the jump is the statement.
    let text = "N10 G1 X10 F100 GOTOF END";
    let b = block(text);
    let addresses: Vec<&str> = b.words.iter().map(|w| &*w.address).collect();
    assert_eq!(addresses, ["G", "X", "F"]);
    let s = b.statement.unwrap();
    assert_eq!(at(text, s.span), "GOTOF END");
    let StatementKind::Jump(jump) = &s.kind else {
        panic!("{s:?}")
    };
    assert_eq!(label_jump(jump), (JumpKind::GotoF, "END"));
}

/// The definition of `text`.
fn definition(text: &str) -> Definition {
    match statement(text).kind {
        StatementKind::Definition(d) => d,
        other => panic!("{text:?}: {other:?}"),
    }
}

#[test]
fn definitions_with_types_and_initial_values() {
    // corpus dubovikov_case_test.MPF, N20.
    let text = "N20 DEF INT VAR1=5, VAR2=5, VAR3=1";
    let d = definition(text);
    assert_eq!((d.scope, d.data_type.value), (None, DataType::Int));
    assert_eq!(at(text, d.data_type.span), "INT");
    let names: Vec<&str> = d.variables.iter().map(|v| &*v.name.value).collect();
    assert_eq!(names, ["VAR1", "VAR2", "VAR3"]);
    let inits: Vec<f64> = d
        .variables
        .iter()
        .map(|v| match &v.init.as_ref().unwrap().value {
            Initializer::Value(e) => eval(e),
            other => panic!("{other:?}"),
        })
        .collect();
    assert_eq!(inits, [5.0, 5.0, 1.0]);
    assert_eq!(at(text, d.variables[1].span), "VAR2=5");
    // corpus philip_CAM_TEST.MPF: several names, no values.
    let d = definition("N10 DEF REAL _X_HOME, _Y_HOME, _Z_HOME, _A_HOME, _C_HOME");
    assert_eq!(d.variables.len(), 5);
    assert!(d
        .variables
        .iter()
        .all(|v| v.init.is_none() && v.dimensions.is_empty()));
    let text = "DEF STRING[20] ZIEL=\"MARK\"";
    let d = definition(text);
    assert_eq!(d.data_type.value, DataType::String(20));
    assert_eq!(at(text, d.data_type.span), "STRING[20]");
    for (text, data_type) in [
        ("DEF BOOL FLAG=TRUE", DataType::Bool),
        ("DEF CHAR C", DataType::Char),
        ("DEF AXIS AX=X", DataType::Axis),
        ("def frame F1", DataType::Frame),
        ("DEF REAL GLM6=14.", DataType::Real),
    ] {
        assert_eq!(definition(text).data_type.value, data_type, "{text}");
    }
}

#[test]
fn definitions_of_arrays_and_global_data() {
    let text = "DEF NCK REAL TABLE[2,3]=SET(1,2,3)";
    let d = definition(text);
    let scope = d.scope.unwrap();
    assert_eq!((scope.value, at(text, scope.span)), (Scope::Nck, "NCK"));
    let v = &d.variables[0];
    let sizes: Vec<f64> = v.dimensions.iter().map(eval).collect();
    assert_eq!(sizes, [2.0, 3.0]);
    let init = v.init.as_ref().unwrap();
    assert_eq!(at(text, init.span), "SET(1,2,3)");
    let Initializer::Set(values) = &init.value else {
        panic!("{init:?}")
    };
    assert_eq!(values.iter().map(eval).collect::<Vec<_>>(), [1.0, 2.0, 3.0]);
    let d = definition("DEF CHAN INT COUNTS[10]=REP(7), MORE[4]=REP(1, 2)");
    assert_eq!(d.scope.map(|s| s.value), Some(Scope::Chan));
    let Initializer::Rep { value, count } = &d.variables[0].init.as_ref().unwrap().value else {
        panic!("{d:?}")
    };
    assert_eq!((eval(value), count), (7.0, &None));
    let Initializer::Rep { count, .. } = &d.variables[1].init.as_ref().unwrap().value else {
        panic!("{d:?}")
    };
    assert_eq!(eval(count.as_ref().unwrap()), 2.0);
    // The expressions in written order: dimensions, then values.
    let s = statement("DEF REAL A[2]=SET(5,6), B=7");
    let all: Vec<f64> = s.expressions().into_iter().map(eval).collect();
    assert_eq!(all, [2.0, 5.0, 6.0, 7.0]);
}

#[test]
fn procedure_headers_with_parameters_and_attributes() {
    // corpus dubovikov_CYCLE_KONUS.SPF, N10 (11 REAL parameters, DISPLOF).
    let text = "N10 PROC CYCLE_KONUS(REAL OTVOD, REAL NACHALNII_RADIUS, REAL UGOL_DELENIYA, REAL SHAG, REAL NAKLON_KONUSA, REAL KONECHN_RADIUS, REAL RADIUS_FREZI, REAL RADIUS_PLASTIN, REAL NACHALNAYA_GLUBINA, REAL CPA, REAL CPO) DISPLOF";
    let StatementKind::Procedure(p) = statement(text).kind else {
        panic!()
    };
    assert_eq!(&*p.name.value, "CYCLE_KONUS");
    assert_eq!(p.parameters.len(), 11);
    assert!(p
        .parameters
        .iter()
        .all(|p| p.data_type.value == DataType::Real
            && p.by_reference.is_none()
            && p.dimensions.is_empty()));
    assert_eq!(&*p.parameters[10].name.as_ref().unwrap().value, "CPO");
    assert_eq!(at(text, p.parameters[0].span), "REAL OTVOD");
    let attributes: Vec<&str> = p.attributes.iter().map(|a| &*a.value).collect();
    assert_eq!(attributes, ["DISPLOF"]);
    // corpus dubovikov_KONUS.SPF: a blank before `)`.
    let StatementKind::Procedure(p) =
        statement("PROC KONUS(REAL rStart, REAL angDivide, REAL rEnd, REAL rMill )").kind
    else {
        panic!()
    };
    assert_eq!(&*p.parameters[3].name.as_ref().unwrap().value, "RMILL");
    // By reference, an open array, a string; several attributes.
    let text = "PROC SUB(VAR REAL POINTS[,3], INT N, STRING[10] TEXT) SAVE SBLOF DISPLOF";
    let StatementKind::Procedure(p) = statement(text).kind else {
        panic!()
    };
    let points = &p.parameters[0];
    assert_eq!(at(text, points.by_reference.unwrap()), "VAR");
    assert_eq!(points.dimensions.len(), 2);
    assert!(points.dimensions[0].is_none());
    assert_eq!(eval(points.dimensions[1].as_ref().unwrap()), 3.0);
    assert_eq!(at(text, points.span), "VAR REAL POINTS[,3]");
    assert_eq!(p.parameters[1].data_type.value, DataType::Int);
    assert_eq!(p.parameters[2].data_type.value, DataType::String(10));
    let attributes: Vec<&str> = p.attributes.iter().map(|a| &*a.value).collect();
    assert_eq!(attributes, ["SAVE", "SBLOF", "DISPLOF"]);
    let StatementKind::Procedure(p) = statement("PROC MAIN").kind else {
        panic!()
    };
    assert!(p.parameters.is_empty() && p.attributes.is_empty());
}

#[test]
fn external_declarations_macros_and_save() {
    // corpus alloyx_DAILY.MPF.
    let StatementKind::External(e) = statement("EXTERN WARMUP_CYCLE(REAL, REAL)").kind else {
        panic!()
    };
    assert_eq!(&*e.name.value, "WARMUP_CYCLE");
    assert_eq!(e.parameters.len(), 2);
    assert!(e.parameters.iter().all(|p| p.name.is_none()));
    let StatementKind::External(e) = statement("EXTERN SUB(VAR REAL[,3], INT, STRING[10])").kind
    else {
        panic!()
    };
    assert!(e.parameters[0].by_reference.is_some());
    assert_eq!(e.parameters[0].dimensions.len(), 2);
    assert_eq!(e.parameters[2].data_type.value, DataType::String(10));
    let text = "DEFINE LINE AS G1 G94 F300 ; a macro";
    let StatementKind::Macro(m) = statement(text).kind else {
        panic!()
    };
    assert_eq!((&*m.name.value, at(text, m.body)), ("LINE", "G1 G94 F300"));
    let text = "DEFINE M6 AS L6";
    let StatementKind::Macro(m) = statement(text).kind else {
        panic!()
    };
    assert_eq!((&*m.name.value, at(text, m.body)), ("M6", "L6"));
    assert_eq!(statement("SAVE").kind, StatementKind::Save);
}

#[test]
fn statement_spans_carry_the_line_and_base() {
    let text = "N5 FOR I=1 TO 3";
    let b = parse_block(text.as_bytes(), FileId(2), 9, 1000);
    let s = b.statement.unwrap();
    assert_eq!((s.span.file, s.span.line), (FileId(2), 9));
    assert_eq!((s.span.start, s.span.end), (1003, 1015));
    let StatementKind::For { end, .. } = s.kind else {
        panic!()
    };
    assert_eq!((end.span.start, end.span.end), (1014, 1015));
}

/// Each malformed statement, the words its alarm's message holds, and the text its span
/// covers.
#[test]
fn malformed_statements_carry_their_alarm() {
    for (text, message, cause) in [
        ("FOR I=1 5", "expected TO", "5"),
        ("FOR I=1", "expected TO", ""),
        ("FOR 1=1 TO 5", "must be a variable", "1"),
        ("FOR I 1 TO 5", "expected `=`", "1"),
        ("FOR", "needs its counter", "FOR"),
        ("IF", "needs a condition", "IF"),
        ("WHILE ; x", "needs a condition", "WHILE"),
        ("IF R1==1 X10", "expected a jump", "X10"),
        ("IF R1==1 GOTOF", "no target", "GOTOF"),
        ("GOTOB", "no target", "GOTOB"),
        ("GOTOS MARK", "GOTOS takes no target", "M"),
        ("GOTOF N99999999999", "too large", "N99999999999"),
        ("REPEATB", "needs the label", "REPEATB"),
        ("REPEAT A B C", "unexpected text after the REPEAT", "C"),
        ("REPEAT 5", "expected a label", "5"),
        ("CASE(R1) 1 GOTOF A", "expected OF", "1"),
        ("CASE(R1) OF", "no branch", "CASE"),
        ("CASE(R1) OF 1 A", "expected GOTOF or GOTOB", "A"),
        ("CASE(R1) OF 1 GOTOS", "a jump with a target", "GOTOS"),
        ("DEF INTEGER X", "unknown type INTEGER", "INTEGER"),
        ("DEF", "needs a type", ""),
        ("DEF REAL", "expected the name", ""),
        ("DEF REAL X Y", "unexpected text after the DEF", "Y"),
        ("DEF STRING X", "needs its length", "STRING"),
        ("DEF STRING[0] X", "whole number", "STRING[0]"),
        ("DEF REAL A[1,2,3,4]", "at most 3 dimensions", "[1,2,3,4]"),
        ("DEF REAL A[3]=SET(1,,2)", "missing in SET", "SET(1,,2)"),
        ("DEF REAL A[3]=REP(1,2,3)", "REP takes", "REP(1,2,3)"),
        ("PROC", "needs the name", ""),
        ("PROC SUB(REAL)", "name of the parameter", ")"),
        ("PROC SUB(REAL A", "expected `,` or `)`", ""),
        ("PROC SUB(REAL A) 5", "expected an attribute", "5"),
        ("EXTERN SUB(FOO)", "unknown type FOO", "FOO"),
        ("DEFINE X", "expected AS", ""),
        ("DEFINE X AS ; nothing", "no text after AS", "AS"),
        ("ELSE X10", "unexpected text after the ELSE", "X10"),
        ("N10 ENDIF 5 ; c", "unexpected text after the ENDIF", "5 "),
        ("G1 X10 ENDIF", "must begin its block", "ENDIF"),
        ("ENDLABEL: G0", "unexpected text after the ENDLABEL", "G0"),
    ] {
        let b = parse_block(text.as_bytes(), FileId(0), 1, 0);
        let alarm = b
            .alarm
            .unwrap_or_else(|| panic!("{text:?} read as {:?}", b.statement));
        assert!(
            alarm.message.contains(message),
            "{text:?}: {:?}",
            alarm.message
        );
        let span = alarm.span.expect("an alarm of a block has a span");
        assert_eq!(at(text, span), cause, "{text:?}: {alarm:?}");
        assert!(alarm.help.is_some(), "{text:?}: no help");
    }
}
