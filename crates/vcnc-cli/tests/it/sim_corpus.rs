//! Issue 21's acceptance 2 on the corpus: `vcnc sim` on every FANUC-family corpus program, with
//! its stock taken from the cut's extents, raises no event on the programs' normal cuts. Tools
//! without a size in the program are 6 mm flat end mills; where the program says its tools, its
//! blank or a parameter the operator sets, the run uses them (each case says which lines).

use crate::cli::{temp_program, vcnc};
use crate::shared::shared_dir;
use crate::traces::corpus_profile;

/// A machine file: the embedded machine with these `[[tool_shapes]]` appended.
fn machine(name: &str, shapes: &[(u32, &str)]) -> String {
    let mut text = include_str!("../../../vcnc/src/default_machine.toml").to_string();
    for (t, shape) in shapes {
        text.push_str(&format!("\n[[tool_shapes]]\nt = {t}\n{shape}\n"));
    }
    temp_program(name, &text)
}

/// How one corpus program is run: a changed text, its own tools, its blank.
struct Setup {
    text: Option<String>,
    machine: Option<String>,
    stock: Option<&'static str>,
}

fn setup(name: &str, text: &str) -> Setup {
    let plain = Setup {
        text: None,
        machine: None,
        stock: None,
    };
    match name {
        // #4 = 63 (the cutter's diameter), #5 = 0.8 (its insert's radius), #8 = 276 (the part's
        // length along X, centred): the radius is rolled on the edge at local Y0..4 of a blank
        // below it. With a 6 mm tool on the extents' box the step rapid (line 35, at X 169.5,
        // where the real cutter clears the part's end X 138 by its radius) grazes 0.03-0.1 mm.
        "boreyko_O00026_radius_profile.nc" => Setup {
            machine: Some(machine(
                "o26.toml",
                &[(4, "type = \"bull_nose\"\ndiameter = 63.0\ncorner_radius = 0.8\ncutting_length = 10.0")],
            )),
            stock: Some("-138,-30,-10,138,4,0"),
            ..plain
        },
        // The entry point is (2 #110 + #17, #110) (lines 18-19): with #110 vacant it is X50 Y0,
        // inside the hexagon of circumradius 130 (#11), and the rapid down each level (line 30)
        // is a real crash of 4 mm. The operator sets #110; 100 puts the entry outside the 50 mm
        // cutter's reach (#17) of a 270 x 240 blank around the hexagon.
        "boreyko_O00100_polygon_sin_cos.nc" => Setup {
            text: Some(text.replacen("G52 X0. Y0. Z0.", "#110= 100.\nG52 X0. Y0. Z0.", 1)),
            machine: Some(machine(
                "o100.toml",
                &[(14, "type = \"flat\"\ndiameter = 50.0\ncutting_length = 30.0")],
            )),
            stock: Some("-135,-120,-15,135,120,0"),
        },
        // Its tools are in its header (lines 4-10, inches). Only OP 1: OP 2 resets the offsets
        // after an M00 and OP 3 flips the part (lines 1397, 1557), which one stock in one frame
        // cannot follow (its drill cycles' is below OP 1's top).
        "ramos_O1006_motor_bracket_fusion_haas.nc" => {
            let op1 = text.split("(OP 2)").next().unwrap_or(text);
            Setup {
                text: Some(format!("{op1}M30\n%\n")),
                machine: Some(machine(
                    "o1006.toml",
                    &[
                        (1, "type = \"flat\"\ndiameter = 12.7\ncutting_length = 25.0"),
                        (2, "type = \"flat\"\ndiameter = 6.35\ncutting_length = 19.0"),
                        (3, "type = \"flat\"\ndiameter = 9.525\ncutting_length = 22.0"),
                        (7, "type = \"drill\"\ndiameter = 7.9375\npoint_angle = 118.0\ncutting_length = 60.0"),
                        (8, "type = \"drill\"\ndiameter = 6.35\npoint_angle = 118.0\ncutting_length = 50.0"),
                        (9, "type = \"chamfer\"\ndiameter = 6.35\nangle = 90.0\ncutting_length = 6.0"),
                        (10, "type = \"flat\"\ndiameter = 50.8\ncutting_length = 10.0"),
                    ],
                )),
                ..plain
            }
        }
        // M13 (spindle on clockwise with coolant, a builder's code) is not read as spindle on
        // by vcnc's profiles: said as M03 M08, or every cut warns of a stopped spindle.
        _ if name.starts_with("selyaev_") && text.contains("M13") => Setup {
            text: Some(text.replace("M13", "M03M08")),
            ..plain
        },
        _ => plain,
    }
}

#[test]
fn corpus_programs_cut_without_events() {
    let Some(shared) = shared_dir() else {
        return;
    };
    let folder = shared.join("corpus/fanuc");
    let mut names: Vec<String> = std::fs::read_dir(&folder)
        .expect("the corpus folder")
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".nc"))
        .collect();
    names.sort();
    let shapes: Vec<(u32, &str)> = (1..=99)
        .map(|t| (t, "type = \"flat\"\ndiameter = 6.0\ncutting_length = 30.0"))
        .collect();
    let six = machine("six_mm.toml", &shapes);
    let lib = folder.display().to_string();
    let (mut cut, mut failures, mut uncut, mut nothing) = (0, Vec::new(), Vec::new(), Vec::new());
    for name in &names {
        let text = std::fs::read_to_string(folder.join(name)).expect("a corpus program");
        let profile = corpus_profile(name);
        let case = setup(name, &text);
        let program = match &case.text {
            Some(changed) => temp_program(&format!("corpus_{name}"), changed),
            None => folder.join(name).display().to_string(),
        };
        let machine = case.machine.as_deref().unwrap_or(&six);
        let mut args = vec![
            "sim",
            "--format",
            "json",
            "--resolution",
            "0.2",
            "--no-state",
            "--profile",
            profile,
            "--machine",
            machine,
            "--lib",
            &lib,
        ];
        if let Some(stock) = case.stock {
            args.extend(["--stock", stock]);
        }
        args.push(&program);
        let out = vcnc(&args);
        let stdout = String::from_utf8_lossy(&out.stdout);
        if stdout.trim().is_empty() {
            // Subprogram files, macros that need their arguments, a probing cycle: nothing cuts.
            assert!(
                String::from_utf8_lossy(&out.stderr).contains("no cutting move"),
                "{name}: {}",
                String::from_utf8_lossy(&out.stderr)
            );
            nothing.push(name.as_str());
            continue;
        }
        let json: serde_json::Value = serde_json::from_str(&stdout).expect("the summary's JSON");
        if json["removed_mm3"].as_f64().unwrap() <= 0.0 {
            uncut.push(name.as_str());
        } else {
            cut += 1;
        }
        let events = &json["event_counts"];
        if events.as_object().is_none_or(|e| !e.is_empty()) {
            failures.push(format!("{name}: {events}"));
        }
    }
    assert!(
        failures.is_empty(),
        "events on normal cuts:\n{}",
        failures.join("\n")
    );
    // Its tools are loaded by hand at M0 (`( LOAD T3 - S580 )`), with no T word: no tool cuts.
    assert_eq!(uncut, ["gcodeworkshop_FANUC0M_0097.nc"]);
    // 15 of the 25 files cut: nine are subprogram or macro files run alone, a probing cycle, or
    // stop on an alarm before their first cut (`no cutting move`), one loads its tools by hand.
    assert!(cut >= 15, "only {cut} programs cut; none: {nothing:?}");
}
