//! Issue 21's acceptance 2 on the SINUMERIK corpus (../shared/corpus/sinumerik): each main
//! program simulated on the machine of its author (`common::sinumerik_machines`, whose tool
//! tables give the tools' sizes), its stock taken from the cut's extents below the first cut
//! (`CutExtents::stock_below_first_cut`), raises no event on its normal cuts: no rapid into the
//! stock, no holder or shank touching, no cut deeper than the flutes, no cutting with the
//! spindle stopped or plunging a tool that cannot. Subprogram files (.SPF) run through their
//! callers. The table: `cargo test -p vcnc --test it sim_sinumerik_corpus -- --nocapture`.

use crate::common;
use crate::common::sinumerik_machines::{library, machine_for};
use vcnc::interp::sinumerik::Sinumerik;
use vcnc::pipeline::Pipeline;
use vcnc::plan::PlanOptions;
use vcnc::sim::{resolution, CutExtents, Simulation};
use vcnc::{AlarmCode, FileId, Item, Machine};

/// The events the acceptance names: on a normal cut none of them may fire.
const CUT_EVENTS: [AlarmCode; 5] = [
    AlarmCode::RapidIntoStock,
    AlarmCode::HolderCollision,
    AlarmCode::BeyondCuttingLength,
    AlarmCode::CuttingWithSpindleStopped,
    AlarmCode::PlungeWithoutCenterCutting,
];

/// The blank of a program whose cut's extents hold stock the part has not, with the lines that
/// show it (machine coordinates: the DMG's G54 lifts Z by 200). `None`: the rule's stock.
fn blank(file: &str, extents: [[f64; 3]; 2]) -> Option<[[f64; 3]; 2]> {
    let low = extents[0][2];
    match file {
        // N330-N460: the 8 mm mill faces Z-1 with its centre from X0 to X16.8 and Y-7 to Y79:
        // the blank is X-4..20.8, Y-11..83 below Z0. The adaptive roughing (N640 on) enters at
        // X25.98 (N640-N650), 5 mm clear of it, and its outer passes cut air.
        "elmoe_Bottle_opener.MPF" => Some([[-4.0, -11.0, low], [20.8, 83.0, 200.0]]),
        // The CAM system rapids down only where its stock is not: the blank is where none of
        // its rapids below the top goes (file lines). 35 and 45: the 50 mm face mill down to
        // Z-1 and Z-2 at X-75 (its edge at X-50): X from -50. The 12 mm roughing mill's rapids
        // down to Z-5.45 and lower: at Y59.797 (line 110; its edge at Y53.80), at
        // (line 126; X-53.93), at X9.821 Y-1.503 (line 118; Y4.50), at X24.999 down to Z-3.7
        // (line 1180; X19.0). The blank, a cell (0.2 mm) inside those: X-50..18.8,
        // Y4.6..53.6 below Z0, which the face mill's passes (Y5.01 to Y34.99 +-25, X-50 to
        // X25 +-25) cover with room to spare.
        "elmoe_Coordinate_system_Achskreuz.MPF" => Some([[-50.0, 4.6, low], [18.8, 53.6, 200.0]]),
        _ => None,
    }
}

/// Runs `text` (corpus file `file`) on `machine` with the corpus's subprograms, handing each
/// item and its timing to `each`.
fn each_timed(
    text: &str,
    file: &str,
    machine: &Machine,
    folder: &std::path::Path,
    mut each: impl FnMut(&Item, &vcnc::plan::Timing),
) {
    let front =
        Sinumerik::new(text.as_bytes(), FileId(0), machine).with_library(Box::new(library(folder)));
    let mut stream = Pipeline::new(machine).open_front_end(front, file);
    stream.for_each_timed(PlanOptions::default(), |items, timings| {
        for (item, timing) in items.iter().zip(timings) {
            if let Ok(item) = item {
                each(item, timing);
            }
        }
        true
    });
}

#[test]
fn sinumerik_corpus_programs_cut_without_events() {
    let Some(shared) = common::shared_dir() else {
        return;
    };
    let folder = shared.join("corpus/sinumerik");
    let mut table =
        String::from("| program | stock | removed mm3 | events |\n|---|---|---:|---|\n");
    let (mut cut, mut failures) = (0, Vec::new());
    for path in common::corpus::sorted_files(&folder) {
        let file = path.file_name().unwrap().to_string_lossy().into_owned();
        if !file.ends_with(".MPF") {
            continue;
        }
        let text = String::from_utf8_lossy(&std::fs::read(&path).unwrap()).into_owned();
        let machine = machine_for(&file);
        let mut extents = CutExtents::new();
        extents.per_axis_rapids(&machine);
        each_timed(&text, &file, &machine, &folder, |item, _| extents.add(item));
        let Some(rule) = extents.stock_below_first_cut() else {
            table += &format!("| {file} | no cut | 0 | |\n");
            continue;
        };
        let stock = blank(&file, rule).unwrap_or(rule);
        // Coarse enough for a debug build: at most 300,000 cells (0.2 mm on a small stock).
        let mut simulation = Simulation::new(stock, resolution(stock, Some(0.2), 300_000));
        simulation.per_axis_rapids(&machine);
        each_timed(&text, &file, &machine, &folder, |item, timing| {
            simulation.add(item, timing)
        });
        let events = simulation.events();
        let fired: Vec<String> = CUT_EVENTS
            .iter()
            .filter(|code| events.count(**code) > 0)
            .map(|code| format!("{} x{}", code.code(), events.count(*code)))
            .collect();
        let removed = simulation.removed();
        if removed > 0.0 {
            cut += 1;
        }
        table += &format!(
            "| {file} | {:?} | {removed:.0} | {} |\n",
            stock.map(|p| p.map(|v| (v * 10.0).round() / 10.0)),
            fired.join(", ")
        );
        if !fired.is_empty() {
            let first = events
                .kept
                .iter()
                .find(|a| CUT_EVENTS.contains(&a.code))
                .map(|a| format!("line {:?}: {}", a.span.map(|s| s.line), a.message));
            failures.push(format!("{file}: {fired:?}, first {first:?}"));
        }
    }
    println!("{table}");
    assert!(
        failures.is_empty(),
        "events on normal cuts:\n{}\n{table}",
        failures.join("\n")
    );
    assert!(cut >= 5, "only {cut} programs cut\n{table}");
}
