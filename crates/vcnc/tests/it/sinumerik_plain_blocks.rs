//! The short path of plain SINUMERIK blocks (`interp/sinumerik/plain_block.rs`) against the
//! general one: every program runs both ways, and the two streams (segments, frames, warnings,
//! the alarm that ends it) are the same item for item. The programs: the manual's examples and
//! the corpus on their machines, a CAM-style program like the speed benchmark's, and random
//! programs of plain lines mixed with the words and states that make a block leave the short
//! path (corners, frames, compensation, modal calls, feeds by variable, G91, inches).

use crate::common::shared::shared_dir;
use crate::common::sinumerik_machines::{library, machine_for};
use proptest::prelude::*;
use std::path::Path;
use vcnc::interp::sinumerik::Sinumerik;
use vcnc::interp::{Kernel, Run};
use vcnc::{FileId, Machine, ProfileName};

/// The stream of `text` on `machine`, by the short path or not, as text item by item.
fn stream(text: &[u8], machine: &Machine, folder: Option<&Path>, plain: bool) -> Vec<String> {
    let mut front_end = Sinumerik::new(text.to_vec(), FileId(0), machine);
    if let Some(folder) = folder {
        front_end = front_end.with_library(Box::new(library(folder)));
    }
    if !plain {
        front_end = front_end.without_plain_blocks();
    }
    Run::new(front_end, Kernel::new(machine))
        .take(200_000)
        .map(|item| format!("{item:?}"))
        .collect()
}

fn assert_same(text: &[u8], machine: &Machine, folder: Option<&Path>, name: &str) {
    let short = stream(text, machine, folder, true);
    let general = stream(text, machine, folder, false);
    if short != general {
        let at = short.iter().zip(&general).position(|(a, b)| a != b);
        panic!(
            "{name}: the short path's stream differs from the general one's at item {at:?} \
             ({} and {} items):\n  short:   {:?}\n  general: {:?}",
            short.len(),
            general.len(),
            at.and_then(|i| short.get(i)),
            at.and_then(|i| general.get(i)),
        );
    }
}

#[test]
fn the_manuals_examples_and_the_corpus_run_the_same_both_ways() {
    let Some(shared) = shared_dir() else {
        return;
    };
    let sinumerik = Machine::default()
        .with_profile(ProfileName::Sinumerik)
        .unwrap();
    let mut count = 0;
    for folder in ["spec/examples/sinumerik-a", "spec/examples/sinumerik-b"] {
        for entry in std::fs::read_dir(shared.join(folder)).unwrap() {
            let path = entry.unwrap().path();
            let text = std::fs::read(&path).unwrap();
            assert_same(&text, &sinumerik, None, &path.display().to_string());
            count += 1;
        }
    }
    let corpus = shared.join("corpus/sinumerik");
    for entry in std::fs::read_dir(&corpus).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let text = std::fs::read(&path).unwrap();
        assert_same(&text, &machine_for(&name), Some(&corpus), &name);
        count += 1;
    }
    assert!(count > 180, "{count} programs");
}

#[test]
fn a_cam_program_runs_the_same_both_ways() {
    // The shape of the speed benchmark's SINUMERIK program: DEF'd feeds, lines, arcs with CR=
    // (negative past half a circle) and with I J.
    let mut text = String::from(
        "DEF REAL FEED1=1500.0\nDEF REAL FEED2=FEED1\nN10 G71 G17 G90 G94 G54\nN20 T1 M6\nN30 D1\nN40 S8000 M3\nN50 G0 X0 Y0 Z5\nN60 G1 Z-1 F=FEED2\n",
    );
    let mut n = 70;
    for k in 0..200 {
        let x = f64::from(k) * 1.5;
        if k % 10 == 9 {
            text.push_str(&format!(
                "N{n} G2 X{:.3} Y{:.3} CR=-{:.3} F=FEED2\n",
                x + 3.0,
                4.0,
                2.5
            ));
            n += 10;
            text.push_str(&format!("N{n} G3 X{:.3} Y0 I-1.5 J-2 F=FEED1\n", x + 6.0));
        } else {
            text.push_str(&format!(
                "N{n} G1 X{x:.3} Y{:.3} Z-1.{k:03}\n",
                (k % 7) as f64
            ));
        }
        n += 10;
    }
    text.push_str("M30\n");
    let machine = Machine::default()
        .with_profile(ProfileName::Sinumerik)
        .unwrap();
    assert_same(text.as_bytes(), &machine, None, "the CAM program");
}

/// A line of a random program: mostly plain lines, with the words and states that take a block
/// off the short path now and then (each feature that acts on every block belongs here).
fn line() -> impl Strategy<Value = String> {
    let coordinate = (-500i32..500).prop_map(|v| f64::from(v) / 10.0);
    let plain = (
        prop::sample::select(vec!["", "G0 ", "G1 ", "G2 ", "G3 "]),
        proptest::option::of(coordinate.clone()),
        proptest::option::of(coordinate.clone()),
        proptest::option::of(coordinate.clone()),
        prop::sample::select(vec![
            "",
            " CR=5",
            " CR=-7.5",
            " I3 J4",
            " I-2",
            " F=FEED",
            " F300",
            " F=NOTDEF",
            " CR=0",
        ]),
    )
        .prop_map(|(g, x, y, z, tail)| {
            let mut line = g.to_string();
            for (letter, value) in [("X", x), ("Y", y), ("Z", z)] {
                if let Some(v) = value {
                    line.push_str(&format!("{letter}{v} "));
                }
            }
            line.push_str(tail);
            line
        });
    prop_oneof![
        6 => plain,
        1 => prop::sample::select(vec![
            "RND=2", "CHF=1", "RNDM=1.5", "RNDM=0", "G41 D1", "G40", "G91", "G90", "G70", "G71",
            "TRANS X5", "ROT RPL=30", "TRANS", "MCALL CYCLE81(10,0,2,-5)", "MCALL", "G18", "G17",
            "ANG=30", "G64", "G60", "G95 S1000 M3", "G94", "FEED=FEED*2", "STOPRE", "CT X1 Y1",
            "G0 AP=45 RP=10", "$P_UIFR[1,X,TR]=3", "G54", "OVR=50", "FRCM=200",
            "ACCLIMA[X]=50", "VELOLIMA[Y]=80", "EGON(Z,\"FINE\",X,1,2)", "EGOFS(Z)",
            "FPR(S1)", "SCC[X]", "DIAMON", "DIAMOF", "G96 S100 LIMS=3000", "G97",
        ])
        .prop_map(str::to_string),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]
    #[test]
    fn random_programs_run_the_same_both_ways(lines in proptest::collection::vec(line(), 1..40)) {
        let mut machine = Machine::default().with_profile(ProfileName::Sinumerik).unwrap();
        machine.tools.push(crate::common::sinumerik::mill(1, "MILL", 1, 0.0, 3.0));
        let mut text = String::from("DEF REAL FEED=400\nT1 M6\nD1\nS1000 M3\nF500\nG0 X0 Y0 Z0\n");
        for line in &lines {
            text.push_str(line);
            text.push('\n');
        }
        text.push_str("M30\n");
        assert_same(text.as_bytes(), &machine, None, &text);
    }
}

#[test]
fn the_features_that_act_on_every_block_run_the_same_both_ways() {
    // Each state a later plain block must see: a gear (the plain X move alarms), reduced axis
    // dynamics, a feed per revolution of a spindle, a constant cutting rate, compensation.
    let mut machine = Machine::default()
        .with_profile(ProfileName::Sinumerik)
        .unwrap();
    machine
        .tools
        .push(crate::common::sinumerik::mill(1, "MILL", 1, 0.0, 3.0));
    for text in [
        "F500\nEGON(Z,\"FINE\",X,1,2)\nG1 X10\nG1 X20\nM30\n",
        "F500\nACCLIMA[X]=50\nG1 X10\nG1 X20\nM30\n",
        "S1000 M3\nFPR(S1)\nG95 F0.1\nG1 X10\nG1 X20\nM30\n",
        "G96 S100 LIMS=3000 M3\nF0.1\nG1 X10\nG1 X20\nG97\nG1 X30\nM30\n",
        "T1 M6\nD1\nF500\nG0 X-10 Y-10\nG41 G1 X0 Y0\nG1 X20\nG1 Y20\nG40 G1 X30 Y30\nM30\n",
    ] {
        assert_same(text.as_bytes(), &machine, None, text);
    }
}
