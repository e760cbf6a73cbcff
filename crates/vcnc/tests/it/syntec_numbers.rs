//! Syntec `%@MACRO` numbers and variables (issue 23): whole numbers (Long) divide to a whole
//! number, MOD takes Longs only, DIV is no operator, locals run from #1 to #400 and the
//! persistent variables from #401. Source: the syntec-macro handbook
//! (github.com/SYNTEC-40101720/syntec-macro, its macro-handbook/02-variables.md, compiled from
//! Syntec's "Macro变数规格" pages): 2.1 locals #1-#400 (#27-#400 for the macro's own use), 2.3
//! G65 makes new locals and M98 shares them, 2.6 #401-#999 the axis group's user memory (kept at
//! power off), 3.4 "when the dividend and the divisor are both whole numbers the result is a
//! whole number" (`1/2` is 0, `(1/2)*1.0` is 0.0, `1./2` is 0.5) and DIV unsupported, 3.5 MOD
//! on a Double alarms COR-054, 3.9 Long with Long stays Long. The seed manual (000) describes
//! none of this.

use vcnc::interp::MemoryLibrary;
use vcnc::{interpret_str, Alarm, FileId, Machine, Options, ProfileName};

fn machine(profile: ProfileName) -> Machine {
    Machine::default().with_profile(profile).unwrap()
}

/// Runs `program` on `profile` with `library`: the error it stops with, if any, and `#0`-`#999`
/// at its end.
fn run(
    profile: ProfileName,
    program: &str,
    library: MemoryLibrary,
) -> (Option<Alarm>, Vec<Option<f64>>) {
    let mut interpreter = interpret_str(program, &machine(profile), Options::default())
        .with_library(Box::new(library));
    let error = interpreter.by_ref().find_map(Result::err);
    let values = (0..1000).map(|n| interpreter.variable(n)).collect();
    (error, values)
}

/// The `#` variables after a Syntec `program` that must run without an error.
fn syntec(program: &str) -> Vec<Option<f64>> {
    let (error, values) = run(ProfileName::Syntec, program, MemoryLibrary::new());
    assert!(error.is_none(), "{program}\n{error:?}");
    values
}

/// The error a Syntec `program` stops with.
fn syntec_error(program: &str) -> Alarm {
    run(ProfileName::Syntec, program, MemoryLibrary::new())
        .0
        .unwrap_or_else(|| panic!("no alarm:\n{program}"))
}

#[test]
fn two_whole_numbers_divide_to_a_whole_number() {
    // Handbook 3.4's four cases, then 7/2 = 3.5 with the fraction dropped = 3, and -7/2 = -3
    // (toward zero: the handbook leaves the direction open, vcnc takes C's). 7/2*2 = 3*2 = 6.
    let values = syntec(
        "%@MACRO\n#1 := 1. / 2;\n#2 := 1 / 2.0;\n#3 := 1 / 2;\n#4 := (1/2) * 1.0;\n#5 := 7/2;\n#6 := -7/2;\n#7 := 7/2*2;\nM30;\n",
    );
    let expected = [0.5, 0.5, 0.0, 0.0, 3.0, -3.0, 6.0];
    for (i, want) in expected.iter().enumerate() {
        assert_eq!(values[i + 1], Some(*want), "#{}", i + 1);
    }
}

#[test]
fn a_local_variable_divides_as_a_real() {
    // Locals are Double (handbook 2.1): #1 holds 7 as a real, so #1/2 = 3.5.
    let values = syntec("%@MACRO\n#1 := 7;\n#2 := #1 / 2;\nM30;\n");
    assert_eq!(values[2], Some(3.5));
}

#[test]
fn fanuc_macro_b_divides_as_reals() {
    // Custom Macro B has one type: #1=1/2 is 0.5 on the FANUC profile, as before.
    let (error, values) = run(ProfileName::Fanuc, "#1=1/2\nM30\n", MemoryLibrary::new());
    assert!(error.is_none(), "{error:?}");
    assert_eq!(values[1], Some(0.5));
}

#[test]
fn mod_takes_whole_numbers_only() {
    // Handbook 3.5: 10 MOD 3 = 1; `10. MOD 3` and `10 MOD 3.0` alarm (COR-054 on the control).
    assert_eq!(syntec("%@MACRO\n#1 := 10 MOD 3;\nM30;\n")[1], Some(1.0));
    for program in [
        "%@MACRO\n#1 := 10. MOD 3;\nM30;\n",
        "%@MACRO\n#1 := 10 MOD 3.0;\nM30;\n",
    ] {
        let alarm = syntec_error(program);
        assert!(alarm.message.contains("MOD"), "{alarm:?}");
        assert_eq!(alarm.span.map(|s| s.line), Some(2));
    }
}

#[test]
fn div_is_named_as_no_operator() {
    let alarm = syntec_error("%@MACRO\n#1 := 7 DIV 2;\nM30;\n");
    assert!(
        alarm.message.contains("`DIV` is not an operator"),
        "{alarm:?}"
    );
}

#[test]
fn locals_run_to_400_and_persistent_variables_from_401() {
    // #34, #100 and #400 are locals on Syntec; #401 and #999 the persistent user memory.
    let values =
        syntec("%@MACRO\n#34 := 1;\n#100 := 2;\n#400 := 3;\n#401 := 4;\n#999 := 5;\nM30;\n");
    for (n, want) in [(34, 1.0), (100, 2.0), (400, 3.0), (401, 4.0), (999, 5.0)] {
        assert_eq!(values[n], Some(want), "#{n}");
    }
}

#[test]
fn g65_gives_new_locals_above_33_and_m98_shares_them() {
    // Handbook 2.3: G65 makes a new #1-#400 (the callee finds #34 and #100 vacant and its own
    // #34 is gone at M99), M98 works on the caller's. The callee reports through the public
    // variables @1 and @2 (1 when vacant).
    let mut library = MemoryLibrary::new();
    library.insert(
        2000,
        FileId(1),
        "%@MACRO\n@1 := #34 = #0;\n@2 := #100 = #0;\n#34 := 9;\nM99;\n",
    );
    let program = "%@MACRO\n#34 := 5;\n#100 := 7;\nG65 P2000;\n#35 := @1;\n#36 := @2;\n#37 := #34;\nM98 P2000;\n#38 := @1;\n#39 := #34;\nM30;\n";
    let (error, values) = run(ProfileName::Syntec, program, library);
    assert!(error.is_none(), "{error:?}");
    // After G65: both vacant in the callee, #34 still 5; after M98: #34 seen (5), then 9.
    let expected = [(35, 1.0), (36, 1.0), (37, 5.0), (38, 0.0), (39, 9.0)];
    for (n, want) in expected {
        assert_eq!(values[n], Some(want), "#{n}");
    }
}

#[test]
fn fanuc_locals_end_at_33() {
    let (error, _) = run(ProfileName::Fanuc, "#34=1\nM30\n", MemoryLibrary::new());
    assert_eq!(error.map(|a| a.code.id()), Some("bad_variable"));
}
