//! The SINUMERIK block parser: DIN words and numeric extensions (manual 2.2.3), skip levels,
//! block numbers and labels, calls, statements, expressions and their precedence, and that no
//! line makes it panic. The expected values are worked out by hand in each test.

use vcnc::source::FileId;
use vcnc::syntax::sinumerik::{parse_block, BinaryOp, Block, Expr, ExprKind, UnaryOp, Value, Word};

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
fn statements_keep_the_rest_of_the_block() {
    let text = "N10 IF R1==1 GOTOF MARK";
    let b = block(text);
    let (keyword, rest) = b.statement.expect("a statement");
    assert_eq!(&*keyword, "IF");
    assert_eq!(
        &text[rest.start as usize..rest.end as usize],
        "R1==1 GOTOF MARK"
    );
    // `DEFX=1` assigns to a name that begins with DEF.
    assert_eq!(block("DEFX=1").statement, None);
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
}

/// Every line of the manual's SINUMERIK examples and of the SINUMERIK corpus programs reads
/// without an alarm, but for the header line (`%_N_..`), which is not a block. Lines are split
/// at LF, CR LF and CR.
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
            if let Some(alarm) = parse_block(line.as_bytes(), FileId(0), number, 0).alarm {
                failures.push(format!(
                    "{}:{number}: {line}\n    {}",
                    path.display(),
                    alarm.message
                ));
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
    assert_eq!(b.statement.map(|(k, _)| k).as_deref(), Some("WHENEVER"));
}
