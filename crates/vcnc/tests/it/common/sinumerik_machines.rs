//! The machines the SINUMERIK corpus programs run on, one per author's machine (each says why
//! it fits), and their subprograms by name: shared by the corpus tests (corpus.rs,
//! corpus_tally.rs, sinumerik_corpus.rs) so that every one runs a program on the same machine.

use vcnc::kinematics::{Kinematics, KinematicsKind, RotaryJoint, Solution, Vec3};
use vcnc::machine::{AxisConfig, ToolEdge, WorkOffsetId};
use vcnc::{Axis, FileId, Machine, ProfileName};

/// The machine corpus program `file` (of corpus/sinumerik) runs on.
pub fn machine_for(file: &str) -> Machine {
    let author = file.split('_').next().unwrap_or(file);
    match author {
        "alloyx" => syil_x7(),
        "dangarpt" => dangarpt_mill(),
        "dubovikov" => dubovikov_boring_mill(),
        "elmoe" => dmg_five_axis(),
        "gcodeworkshop" => b_table_mill(),
        "jennings" => grob_g550(),
        "ncplot7py" => shopmill_mill(),
        "philip" => philip_ac_mill(),
        _ => Machine::default()
            .with_profile(ProfileName::Sinumerik)
            .unwrap(),
    }
}

/// Every subprogram (.SPF) of `folder` (corpus/sinumerik), under its own name: the file name
/// without its author prefix and extension (`alloyx_WARMUP_CYCLE.SPF` is WARMUP_CYCLE). Calls
/// by name find them as the control finds the files of its program directory.
pub fn library(folder: &std::path::Path) -> vcnc::interp::MemoryLibrary {
    let mut library = vcnc::interp::MemoryLibrary::new();
    for (i, path) in super::corpus::sorted_files(folder).iter().enumerate() {
        let file = path.file_name().unwrap().to_string_lossy().into_owned();
        if file.ends_with(".SPF") {
            let text = std::fs::read(path).unwrap();
            library.insert_named(
                program_name(&file),
                FileId(i as u32 + 1),
                &String::from_utf8_lossy(&text),
            );
        }
    }
    library
}

/// The name a corpus file's program is called by.
pub fn program_name(file: &str) -> &str {
    let stem = file.rsplit_once('.').map_or(file, |(stem, _)| stem);
    stem.split_once('_').map_or(stem, |(_, name)| name)
}

/// A linear axis from `min` to `max` (machine coordinates, mm).
pub fn linear(min: f64, max: f64) -> AxisConfig {
    AxisConfig {
        min,
        max,
        rapid: 30000.0,
        max_feed: 10000.0,
        acceleration: 2000.0,
        jerk: 50000.0,
    }
}

/// An 840D (or 828D) with the given travel of X, Y and Z, and the rotary axes `rotary`.
pub fn sinumerik(
    profile: ProfileName,
    x: (f64, f64),
    y: (f64, f64),
    z: (f64, f64),
    rotary: &[Axis],
) -> Machine {
    let mut machine = Machine::default().with_profile(profile).unwrap();
    machine.axes[Axis::X.index()] = Some(linear(x.0, x.1));
    machine.axes[Axis::Y.index()] = Some(linear(y.0, y.1));
    machine.axes[Axis::Z.index()] = Some(linear(z.0, z.1));
    for axis in rotary {
        machine.axes[axis.index()] = Some(super::rotary_axis());
    }
    machine
}

/// Tools 1, 2, ... by name: (name, diameter, drill).
pub fn named_tools(machine: &mut Machine, tools: &[(&str, f64, bool)]) {
    for (i, &(name, diameter, drill)) in tools.iter().enumerate() {
        machine
            .tools
            .push(tool(i as u32 + 1, Some(name), diameter, drill));
    }
}

/// Edge D1 of tool `t`: an end mill (type 120) or a drill (200) of `diameter`, length 0 (the
/// work offsets' Z is taken as touched off with the tool tip, so program Z is machine Z).
pub fn tool(t: u32, name: Option<&str>, diameter: f64, drill: bool) -> ToolEdge {
    ToolEdge {
        t,
        name: name.map(str::to_string),
        d: 1,
        tool_type: if drill { 200 } else { 120 },
        length: 0.0,
        length2: 0.0,
        length3: 0.0,
        radius: diameter / 2.0,
        teeth: Some(if drill { 2 } else { 4 }),
    }
}

/// AlloyX's Syil X7 with an 828D: 500 x 300 x 400 mm travel from a machine zero at the top
/// corner (the warm-up moves to SUPA X-5 Y-5 Z-4 inch, -127 mm, from there).
pub fn syil_x7() -> Machine {
    sinumerik(
        ProfileName::Sinumerik828d,
        (-500.0, 0.0),
        (-300.0, 0.0),
        (-400.0, 0.0),
        &[],
    )
}

/// DangaRPT's mill: a VMC with an A axis (`A0.0` on line 5), tool 1 an 8 mm end mill with edge
/// D1 (`G41 ... D01`). Its first move is a G1 at the height the tool change left, so the tool
/// starts 200 above the work zero (G54 zero is machine zero).
pub fn dangarpt_mill() -> Machine {
    let mut machine = sinumerik(
        ProfileName::Sinumerik,
        (-300.0, 300.0),
        (-200.0, 200.0),
        (-100.0, 400.0),
        &[Axis::A],
    );
    machine.tools.push(tool(1, None, 8.0, false));
    machine.start[Axis::Z.index()] = 200.0;
    machine
}

/// PDubovikov's shop: a large boring and milling machine (`FREZA D160`, X to +-1415, Z to
/// 1700), tools 1 to 5 with edge D1 (`T1D1M6` ... `T5 D1M6`): 160, 25, 25, 25 and 25 mm
/// cutters as the comments of dubovikov_123.MPF name them. R parameters to R99 suffice.
pub fn dubovikov_boring_mill() -> Machine {
    let mut machine = sinumerik(
        ProfileName::Sinumerik,
        (-2500.0, 2500.0),
        (-1000.0, 1500.0),
        (-500.0, 2000.0),
        &[],
    );
    // The quill W, parallel to Z (`Z0 W0` in dubovikov_KONUS.SPF).
    machine
        .add_axis("W", None, linear(-500.0, 1000.0))
        .expect("a free axis slot");
    machine.tools.push(tool(1, None, 160.0, false));
    for t in 2..=5 {
        machine.tools.push(tool(t, None, 25.0, false));
    }
    machine
}

/// ElMoe's DMG 5-axis mill (B head or table and C table, Siemens NX posts): home at SUPA X-365
/// Y224 Z610, so X -400..400, Y -300..300, Z 0..650; G54 at Z 200 puts the part's top (program
/// Z0) under the home height. The tools by the names the programs call.
pub fn dmg_five_axis() -> Machine {
    let mut machine = sinumerik(
        ProfileName::Sinumerik,
        (-400.0, 400.0),
        (-300.0, 300.0),
        (0.0, 650.0),
        &[Axis::B, Axis::C],
    );
    machine
        .work_offsets
        .insert(WorkOffsetId::Standard(1), [0.0, 0.0, 200.0, 0.0, 0.0, 0.0]);
    named_tools(
        &mut machine,
        &[
            ("SCHAFT_D8_N_AP20", 8.0, false),
            ("SCHAFT_D4_N_AP20", 4.0, false),
            ("ENTFRAESER_D8_90GRAD", 8.0, false),
            ("PLAN_D50_N_AP4", 50.0, false),
            ("SCHAFT_D12_N_AP30", 12.0, false),
            ("SCHAFT_D6_N_AP15", 6.0, false),
            ("ENTFRAESER_D8_N_90GRAD", 8.0, false),
            ("BOHRER_D3.3_VHM", 3.3, true),
        ],
    );
    machine
}

/// The GCodeWorkShop example's mill: a B rotary table (`B45.` ... `B315`), Z to 210 (Z =
/// WYSSKRZ+60), tools by number with the sizes their comments give (T1 an 80 mm mill, drills,
/// taps), R parameters to R199: the program reads R102 and R104 (N60), so the control has
/// more than the 100 of the default.
pub fn b_table_mill() -> Machine {
    let mut machine = sinumerik(
        ProfileName::Sinumerik,
        (-500.0, 500.0),
        (-300.0, 500.0),
        (-100.0, 500.0),
        &[Axis::B],
    );
    let numbered = [
        (1, 80.0, false),
        (9, 10.2, true),
        (7, 6.8, true),
        (22, 3.2, true),
        (20, 4.2, true),
        (5, 5.0, true),
        (32, 6.0, true),
        (33, 6.0, true),
        (10, 12.0, true),
        (18, 8.0, true),
        (21, 5.0, true),
        (6, 6.0, true),
    ];
    for (t, diameter, drill) in numbered {
        machine.tools.push(tool(t, None, diameter, drill));
    }
    machine.profile.sinumerik.as_mut().unwrap().r_parameters = 200;
    machine
}

/// David Jennings' GROB G550 (its header: `GROB G550 5 AXIS MILL`), inch programs on a metric
/// control: the tool named "52" a .250 in end mill (the program's tool list); R parameters to
/// R199, since CYCLE189 writes R103 to R109 (the control's MD28050 is larger than the 100
/// default).
///
/// Kinematics (the swivel data record "TC_GROB" of its CYCLE800): the G550 swivels the part,
/// not the spindle: a trunnion A (about X, through 230 degrees) carries the rotary table B
/// (about Y with A at zero, a full turn), and the program's own closing lines bring both home
/// (`G53 A=DC(0) B=DC(0)`, its work offset adjustment takes "A rotation" and "B rotation").
/// Its one swivel, 91.064 degrees about Y (N26), is the table's B. The axes' lines through
/// the machine's origin and the tool along Z are choices: the program's numbers do not depend
/// on them.
pub fn grob_g550() -> Machine {
    let mut machine = sinumerik(
        ProfileName::Sinumerik,
        (-800.0, 800.0),
        (-1000.0, 1000.0),
        (-500.0, 1000.0),
        &[Axis::A, Axis::B],
    );
    machine.tools.push(tool(52, Some("52"), 0.25 * 25.4, false));
    machine.profile.sinumerik.as_mut().unwrap().r_parameters = 200;
    machine.kinematics = Some(two_rotary(
        KinematicsKind::TableTable,
        [
            (Axis::A, [1.0, 0.0, 0.0], (-115.0, 115.0)),
            (Axis::B, [0.0, 1.0, 0.0], (-1.0e6, 1.0e6)),
        ],
    ));
    machine
}

/// Kinematics of two rotary axes (axis, direction, travel in degrees), first the carrier,
/// both lines through the origin, the tool along +Z.
pub fn two_rotary(kind: KinematicsKind, joints: [(Axis, Vec3, (f64, f64)); 2]) -> Kinematics {
    Kinematics {
        kind,
        joints: joints
            .map(|(axis, direction, limits)| RotaryJoint {
                axis,
                direction,
                center: [0.0; 3],
                limits,
            })
            .into(),
        tool_axis: [0.0, 0.0, 1.0],
        solution: Solution::Shortest,
    }
}

/// The ShopMill program of ncplot7py: a 5-axis mill with a swivel head B and a rotary table C
/// (a DMG DMU monoBLOCK with ShopMill is one), the tools by name. Why B-C: the program's
/// swivels tilt the tool towards -Y (N107, -15 degrees about X), towards +-X (N120, N126: 7
/// degrees about Y) and along a corner's diagonal (N150: 45 degrees about Z, then 54.365 about
/// X): one tilting axis with a rotary table under it reaches them all; "TC1" is ShopMill's
/// first swivel data record, and its calls turn the axes (`_DIR` 1, the plus solution of the
/// head). B tilts from -120 to 30 degrees as such a head does; both lines through the origin
/// and the tool along Z are choices: the program's numbers do not depend on them.
pub fn shopmill_mill() -> Machine {
    let mut machine = sinumerik(
        ProfileName::Sinumerik,
        (-500.0, 500.0),
        (-400.0, 400.0),
        (-200.0, 500.0),
        &[Axis::B, Axis::C],
    );
    named_tools(
        &mut machine,
        &[
            ("FACEMILL 63", 63.0, false),
            ("CUTTER 16", 16.0, false),
            ("CUTTER 8", 8.0, false),
            ("DRILL 8.5", 8.5, true),
        ],
    );
    machine.kinematics = Some(two_rotary(
        KinematicsKind::HeadTable,
        [
            (Axis::B, [0.0, 1.0, 0.0], (-120.0, 30.0)),
            (Axis::C, [0.0, 0.0, 1.0], (-1.0e6, 1.0e6)),
        ],
    ));
    machine
}

/// 121philip's 840D sl with A and C axes (`SUPA X=_X_HOME ... A=_A_HOME C=_C_HOME`): home
/// SUPA Z-10 under a machine zero at the top of Z, so Z -600..0 and G54 at Z-400 (the
/// program's Z60 clearance is then machine Z-340); tool "DRILL 8.5".
pub fn philip_ac_mill() -> Machine {
    let mut machine = sinumerik(
        ProfileName::Sinumerik,
        (-100.0, 600.0),
        (-100.0, 500.0),
        (-600.0, 0.0),
        &[Axis::A, Axis::C],
    );
    machine
        .work_offsets
        .insert(WorkOffsetId::Standard(1), [0.0, 0.0, -400.0, 0.0, 0.0, 0.0]);
    named_tools(&mut machine, &[("DRILL 8.5", 8.5, true)]);
    machine
}
