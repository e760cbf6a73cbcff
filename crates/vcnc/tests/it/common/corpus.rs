//! The corpus programs' controls and machines (spec: corpus/MANIFEST.md).

use vcnc::{AlarmCode, Machine, ProfileName};

/// The control each corpus program was written for (spec: corpus/MANIFEST.md).
pub fn profile_for(name: &str) -> ProfileName {
    if name.starts_with("boreyko_")
        || name.starts_with("kiely_")
        || name.starts_with("ramos_")
        || name.starts_with("werocketry_")
        || name.contains("HAAS")
    {
        ProfileName::Haas
    } else if name.contains("FANUC0M") {
        ProfileName::Fanuc0m
    } else {
        ProfileName::Fanuc
    }
}

/// True for a program of corpus/sinumerik (`.MPF` main programs, `.SPF` subprograms).
pub fn is_sinumerik(name: &str) -> bool {
    let upper = name.to_ascii_uppercase();
    upper.ends_with(".MPF") || upper.ends_with(".SPF")
}

/// The machine each program runs on: the default machine with the program's profile, and the
/// parameter settings its author's control evidently had; a SINUMERIK program's is its
/// author's machine (tests/it/common/sinumerik_machines.rs).
pub fn machine_for(name: &str) -> Machine {
    if is_sinumerik(name) {
        return super::sinumerik_machines::machine_for(name);
    }
    let mut machine = Machine::default().with_profile(profile_for(name)).unwrap();
    if name.starts_with("ledfloor_") {
        // A Fusion 360 generic post writes `Y35` and `Z10` meaning millimetres: the control it was
        // made for reads numbers without a decimal point as whole units (FANUC parameter DPI = 1).
        machine.profile.units.decimal_less = vcnc::profile::DecimalLess::WholeUnits;
    }
    if name.starts_with("boreyko_") {
        // Macro templates that read the tool diameter from the offset table (`#[2400 + #3026]`):
        // on the author's machine the tools in use had their diameters set. A 10 mm cutter in
        // every pocket the programs use.
        for number in 1..=40 {
            machine.tool_offsets.insert(
                number,
                vcnc::machine::ToolOffset {
                    number,
                    length: 100.0,
                    radius: 10.0,
                    ..Default::default()
                },
            );
        }
    }
    if name.starts_with("z64_") {
        // Bolt circles indexed on a rotary table: `G91 A[360.0/#2]`.
        let rotary = vcnc::machine::AxisConfig {
            min: -1.0e6,
            max: 1.0e6,
            ..machine.axes[0].clone().expect("the default machine has X")
        };
        machine.axes[vcnc::Axis::A.index()] = Some(rotary);
    }
    if name.starts_with("kiely_") {
        // Hand-written for a Haas set to inch (setting 9): the programs never say G20.
        machine.profile.power_on.units = 200;
    }
    machine
}

/// The programs a corpus program can call: those of the same author in `folder` (the prefix
/// before the first `_`), found by their `O` headers, as in that author's control memory.
/// Programs of other authors are not on that machine.
#[allow(dead_code)]
pub fn library_for(name: &str, folder: &std::path::Path) -> vcnc::interp::MemoryLibrary {
    let author = name.split('_').next().unwrap_or(name);
    let mut library = vcnc::interp::MemoryLibrary::new();
    let mut file_id = 1;
    for path in sorted_files(folder) {
        let file_name = path.file_name().unwrap().to_string_lossy().into_owned();
        if file_name == name || file_name.split('_').next() != Some(author) {
            continue;
        }
        let text = String::from_utf8_lossy(&std::fs::read(&path).unwrap()).into_owned();
        for line in text.lines() {
            let line = line.trim_start();
            let digits: String = line
                .strip_prefix('O')
                .unwrap_or("")
                .chars()
                .take_while(char::is_ascii_digit)
                .collect();
            if let Ok(number) = digits.parse::<u32>() {
                library.insert(number, vcnc::FileId(file_id), &text);
            }
        }
        file_id += 1;
    }
    library
}

/// The motion stream of the corpus program at `path` (`text`) on `machine`: an ISO program
/// through the interpreter with `options` and its author's programs to call; a SINUMERIK
/// program (of corpus/sinumerik) through the SINUMERIK front end with the corpus's
/// subprograms under their names.
pub fn stream<'a>(
    path: &std::path::Path,
    text: &'a [u8],
    machine: &Machine,
    options: vcnc::Options,
) -> Box<dyn Iterator<Item = vcnc::StreamItem> + 'a> {
    let dir = path.parent().expect("a corpus program is in a folder");
    let name = path.file_name().unwrap().to_string_lossy();
    if dir.ends_with("sinumerik") {
        let front_end = vcnc::interp::sinumerik::Sinumerik::new(text, vcnc::FileId(0), machine)
            .with_library(Box::new(super::sinumerik_machines::library(dir)));
        Box::new(vcnc::interp::Run::new(
            front_end,
            vcnc::interp::Kernel::new(machine),
        ))
    } else {
        let library = library_for(&name, dir);
        Box::new(vcnc::interpret_bytes(text, machine, options).with_library(Box::new(library)))
    }
}

/// The corpus programs that stop with an alarm, as the real control would stop them: (file,
/// alarm, line, why). Every other corpus program runs to its end (issue #3, acceptance 2).
#[allow(dead_code)]
pub const EXPECTED_ALARMS: &[(&str, AlarmCode, u32, &str)] = &[
    (
        "boreyko_O00030_probe_g65_calls.nc",
        AlarmCode::ProgramNotFound,
        13,
        "calls the probing macro O9832, which is not in the corpus",
    ),
    (
        "boreyko_O00999_main_m98_bracket_p.nc",
        AlarmCode::ProgramNotFound,
        5,
        "calls O10 to O80, which are not in the corpus",
    ),
    (
        "brown_O9250_dynamic_offset_rotation.nc",
        AlarmCode::UserAlarm,
        15,
        "run alone, without its G65 arguments: `#3000=1(NEED ROTATION AXIS)`",
    ),
    (
        "selyaev_O0001_quad_main.nc",
        AlarmCode::ArcRadiusTooSmall,
        66,
        "O3001 line 47 sets #621 from #610 where #620 is meant: the last corner arc (R0.2, line 66) cannot reach its end point",
    ),
    (
        "selyaev_O0002_carving_main.nc",
        AlarmCode::UnexpectedCharacter,
        15,
        "`#1=#1-#11:` ends in a stray colon (a typo in the original)",
    ),
    (
        "selyaev_O3001_quad_pocket_macro.nc",
        AlarmCode::MacroArithmetic,
        27,
        "run alone: its arguments are vacant, and `[#1-#2]/#17` divides by Q/2 = 0",
    ),
    (
        "selyaev_O3002_carving_macro.nc",
        AlarmCode::SequenceNotFound,
        6,
        "run alone: `N41GOTO#22` with #22 vacant",
    ),
    (
        "selyaev_O3003_spiral_holes_macro.nc",
        AlarmCode::ArcWithoutCenter,
        23,
        "run alone: its arguments are vacant, and the helical arc has radius 0",
    ),
    (
        "dangarpt_test.MPF",
        AlarmCode::UnknownGCode,
        196,
        "its post writes the ISO drilling cycle G81 into SINUMERIK text, which an 840D in Siemens mode rejects (alarm 12470)",
    ),
    (
        "dubovikov_123.MPF",
        AlarmCode::ProgramNotFound,
        13,
        "calls L140 (the machine's angle-head set-up), which is not in the corpus",
    ),
    (
        "dubovikov_CHAMFER.SPF",
        AlarmCode::MacroArithmetic,
        19,
        "run alone: its PROC parameters are 0, and `R11=(R10*360/R4)` divides by the pitch 0",
    ),
    (
        "dubovikov_CYCLE_KONUS.SPF",
        AlarmCode::MacroArithmetic,
        42,
        "run alone: its PROC parameters are 0, and `SHETCIK_6=(KONECHN_RADIUS*360/SHAG_PO_Z)` divides by the pitch 0",
    ),
    (
        "dubovikov_KANAVKA_SFERA.SPF",
        AlarmCode::MacroArithmetic,
        8,
        "run alone: its PROC parameters are 0, and `R21=ACOS(R10/R5)` divides by the radius 0",
    ),
    (
        "dubovikov_KONUS.SPF",
        AlarmCode::MacroArithmetic,
        14,
        "run alone: its PROC parameters are 0, and `R11=(R10*360/R4)` divides by the pitch 0",
    ),
    (
        "gcodeworkshop_SINUMERIK840D.MPF",
        AlarmCode::ProgramNotFound,
        24,
        "calls L54 and L55 (the shop's offset routines), which are not in the corpus",
    ),
    (
        "jennings_CYCLE189.SPF",
        AlarmCode::MacroArithmetic,
        15,
        "run alone: its PROC parameters are 0, and `ROUNDUP (R103/(R17*(-1)))` divides by the step 0",
    ),
    (
        "jennings_CYCLE189_TEST.MPF",
        AlarmCode::ProgramNotFound,
        21,
        "calls the GROB routine G_ZP_WRITE, which is not in the corpus",
    ),
];

/// The alarm and line a corpus program is expected to stop with, if any.
#[allow(dead_code)]
pub fn expected_alarm(name: &str) -> Option<(AlarmCode, u32)> {
    EXPECTED_ALARMS
        .iter()
        .find(|(file, ..)| *file == name)
        .map(|&(_, code, line, _)| (code, line))
}

/// The corpus's folders, and the programs of each in name order.
pub fn programs(corpus: &std::path::Path) -> Vec<(&'static str, std::path::PathBuf)> {
    let mut programs = Vec::new();
    for folder in ["fanuc", "large", "sinumerik"] {
        let files = sorted_files(&corpus.join(folder));
        programs.extend(files.into_iter().map(|path| (folder, path)));
    }
    programs
}

/// The files of `folder`, in name order.
pub fn sorted_files(folder: &std::path::Path) -> Vec<std::path::PathBuf> {
    let mut files: Vec<_> = std::fs::read_dir(folder)
        .unwrap_or_else(|e| panic!("{}: {e}", folder.display()))
        .map(|e| e.expect("a folder entry").path())
        .collect();
    files.sort();
    files
}
