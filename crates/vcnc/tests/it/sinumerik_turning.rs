//! SINUMERIK's turning language on the same control: diameter programming (DIAMON, DIAM90,
//! DIAMOF, DIAMONA[ax], DIAMCHANA, DAC/DIC/RAC/RIC; PGsl 8.3.6-8.3.7, seed 002 L4504-4764), the
//! constant cutting rate's reference axis (G96 with SCC; PGsl 6.3, L2127-2328) and the
//! geometry axis exchange it reads (GEOAX). Every position and speed is worked out by hand in
//! the test; docs/SINUMERIK.md section 14 is the model.

use vcnc::interp::sinumerik::run_str;
use vcnc::machine::AxisKind;
use vcnc::{Alarm, AlarmCode, Machine, Segment, SegmentKind};

use crate::common::collect;
use crate::common::sinumerik::machine;
use crate::common::sinumerik_machines::linear;

/// The segments of a program that must run to its end.
fn run(text: &str, machine: &Machine) -> Vec<Segment> {
    let run = collect(run_str(text, machine));
    assert!(run.error().is_none(), "{text}\n{:#?}", run.alarms);
    run.segments
}

fn error(text: &str, machine: &Machine) -> Alarm {
    let run = collect(run_str(text, machine));
    run.error()
        .cloned()
        .unwrap_or_else(|| panic!("no error in\n{text}"))
}

/// The end point (X, Y, Z) of every motion.
fn ends(segments: &[Segment]) -> Vec<[f64; 3]> {
    segments
        .iter()
        .filter_map(|s| s.motion().map(|m| [m.to.0[0], m.to.0[1], m.to.0[2]]))
        .collect()
}

/// The speed of every spindle event, rpm.
fn speeds(segments: &[Segment]) -> Vec<f64> {
    segments
        .iter()
        .filter_map(|s| match s.kind {
            SegmentKind::Spindle { speed, .. } => Some(speed),
            _ => None,
        })
        .collect()
}

fn assert_points(actual: &[[f64; 3]], expected: &[[f64; 3]]) {
    assert_eq!(actual.len(), expected.len(), "{actual:?}");
    for (a, e) in actual.iter().zip(expected) {
        for k in 0..3 {
            assert!(
                (a[k] - e[k]).abs() < 1e-9,
                "{actual:?}, expected {expected:?}"
            );
        }
    }
}

fn assert_close(actual: f64, expected: f64, tolerance: f64) {
    assert!(
        (actual - expected).abs() < tolerance,
        "{actual}, expected {expected}"
    );
}

/// The test machine with the linear channel axis X2 beside X (X1) Y Z.
fn with_x2() -> Machine {
    let mut machine = machine();
    machine
        .add_axis("x2", Some(AxisKind::Linear), linear(-1000.0, 1000.0))
        .expect("a free slot for X2");
    machine
}

// Diameter programming.

#[test]
fn diamof_is_the_power_on_state() {
    let segments = run("G0 X40 Z5", &machine());
    assert_points(&ends(&segments), &[[40.0, 0.0, 5.0]]);
}

#[test]
fn diamon_halves_absolute_and_incremental_transverse_values() {
    // L4527-4531: DIAMON reads X as a diameter under G90 and under G91. X40 -> radius 20;
    // G91 X10 -> radius +5 = 25. Z is no transverse axis: as written.
    let segments = run("G18 DIAMON\nG0 X40 Z-10\nG91 X10 Z-10", &machine());
    assert_points(&ends(&segments), &[[20.0, 0.0, -10.0], [25.0, 0.0, -20.0]]);
}

#[test]
fn diam90_halves_absolute_values_only() {
    // L4533-4536: DIAM90 reads X as a diameter under G90, as a radius under G91. X40 -> 20,
    // G91 X10 -> 30, G90 X10 -> 5.
    let segments = run("DIAM90\nG0 X40\nG91 X10\nG90 X10", &machine());
    assert_points(
        &ends(&segments),
        &[[20.0, 0.0, 0.0], [30.0, 0.0, 0.0], [5.0, 0.0, 0.0]],
    );
}

#[test]
fn diamon_in_the_block_acts_on_its_own_values() {
    // G functions take effect before the block's values are read: X30 is a diameter.
    let segments = run("G0 X30 DIAMON", &machine());
    assert_points(&ends(&segments), &[[15.0, 0.0, 0.0]]);
}

#[test]
fn an_incremental_centre_stays_a_radius_and_an_ac_centre_is_a_diameter() {
    // L4560-4564. G18 DIAMON, from X20 (radius 10) Z0 to X20 Z-20 counter-clockwise about the
    // centre at radius 4, Z-10: I-6 (a radius increment, 10 - 6 = 4) K-10, or I=AC(8) (a
    // diameter, radius 4) K=AC(-10). Both arcs have radius sqrt(6^2 + 10^2) at both ends.
    for centre in ["I-6 K-10", "I=AC(8) K=AC(-10)"] {
        let text = format!("G18 DIAMON F100\nG0 X20 Z0\nG3 X20 Z-20 {centre}");
        let segments = run(&text, &machine());
        let arc = segments
            .iter()
            .find_map(|s| match s.kind {
                SegmentKind::Arc { center, .. } => Some(center.0),
                _ => None,
            })
            .expect("an arc");
        assert_close(arc[0], 4.0, 1e-9);
        assert_close(arc[2], -10.0, 1e-9);
        assert_points(&ends(&segments)[1..], &[[10.0, 0.0, -20.0]]);
    }
}

#[test]
fn dac_dic_rac_ric_give_one_value_its_dimension() {
    // The manual's example 2 (a/81, L4709-4716), N10-N25, F from the prelude: X20 Y40 both
    // diameters (DIAMON, DIAMONA[Y]) -> X10 Y20; X=RIC(5) -> 15; X=RAC(80) -> 80; then
    // X=DIC(10) -> +5 = 85 and, DIAMOF, X=DAC(10) -> 5 while X40 stays a radius.
    let text = "F100\nDIAMON\nG0 G90 X20 Y40 DIAMONA[Y]\nG01 X=RIC(5)\nX=RAC(80)\n\
                X=DIC(10)\nDIAMOF\nX=DAC(10)\nX40";
    let segments = run(text, &machine());
    assert_points(
        &ends(&segments),
        &[
            [10.0, 20.0, 0.0],
            [15.0, 20.0, 0.0],
            [80.0, 20.0, 0.0],
            [85.0, 20.0, 0.0],
            [5.0, 20.0, 0.0],
            [40.0, 20.0, 0.0],
        ],
    );
}

#[test]
fn dac_halves_its_value_on_a_machine_that_never_saw_diameter_programming() {
    // L4670-4681: DAC is a diameter for its word whatever the modes: X=DAC(10) is radius 5;
    // RIC(3) a radius increment, 8.
    let segments = run("F100\nG1 X=DAC(10)\nX=RIC(3)", &machine());
    assert_points(&ends(&segments), &[[5.0, 0.0, 0.0], [8.0, 0.0, 0.0]]);
}

#[test]
fn an_axis_of_its_own_follows_the_channel_after_diamchana_and_diamchan() {
    // DIAMONA[Y]: Y100 -> 50 whatever the channel; DIAMCHANA[Y] under DIAMOF: Y100 as written;
    // DIAM90A[Y] then DIAMCHAN under DIAMON: Y100 -> 50 again, and G91 Y10 -> +5.
    let text = "DIAMONA[Y]\nG0 Y100\nDIAMCHANA[Y]\nY100\nDIAM90A[Y]\nG91 Y10\nDIAMON\nDIAMCHAN\n\
                G90 Y100\nG91 Y10";
    let segments = run(text, &machine());
    let y: Vec<f64> = ends(&segments).iter().map(|p| p[1]).collect();
    // DIAM90A[Y] with G91 Y10: a radius, 100 + 10 = 110.
    assert_eq!(y, vec![50.0, 100.0, 110.0, 50.0, 55.0]);
}

#[test]
fn a_lathe_whose_machine_data_power_on_in_diamon_reads_diameters() {
    // PGsl 8.3.6: the power-on member of group 29 is the machine manufacturer's (lathes are
    // usually DIAMON); MD20150 in the machine file's power_on.
    let mut lathe = machine();
    let settings = lathe
        .profile
        .sinumerik
        .as_mut()
        .expect("SINUMERIK settings");
    settings.power_on.push("DIAMON".into());
    let segments = run("G0 X40", &lathe);
    assert_points(&ends(&segments), &[[20.0, 0.0, 0.0]]);
}

#[test]
fn the_work_position_of_a_diameter_axis_reads_as_a_diameter() {
    // L4547-4549: $P_EP[X] and $AA_IW[X] read a diameter under DIAMON and DIAM90; radius 20
    // reads 40, which Z (a radius axis) then goes to. Under DIAMOF it reads 20 again.
    let text = "DIAMON\nG0 X40\nR1=$P_EP[X]\nR2=$AA_IW[X]\nG0 Z=R1\nDIAM90\nR3=$P_EP[X]\n\
                DIAMOF\nR4=$P_EP[X]\nG0 Y=R2+R3+R4";
    let segments = run(text, &machine());
    assert_points(
        &ends(&segments),
        &[[20.0, 0.0, 0.0], [20.0, 0.0, 40.0], [20.0, 100.0, 40.0]],
    );
}

#[test]
fn p_gg_29_reads_the_member_of_group_29_in_force() {
    // sinumerik-tables.md group 29: DIAMOF 1, DIAMON 2, DIAM90 3, DIAMCYCOF 4. Each read goes
    // to X as ten times its value; DIAMCYCOF keeps DIAM90's halving of absolute values.
    let text = "R1=$P_GG[29]\nDIAMON\nR2=$P_GG[29]\nDIAM90\nR3=$P_GG[29]\nDIAMCYCOF\n\
                R4=$P_GG[29]\nG0 X=R1*1000+R2*100+R3*10+R4";
    let segments = run(text, &machine());
    // 1234 as written under DIAM90 (absolute: a diameter) is radius 617.
    assert_points(&ends(&segments), &[[617.0, 0.0, 0.0]]);
}

#[test]
fn a_proc_with_save_gives_back_the_diameter_programming_it_was_called_with() {
    // PGAsl SAVE: the G functions in force at the call come back at its return; group 29 is
    // one. The PROC's DIAMON reads X40 as radius 20; back in DIAMOF, X40 is 40.
    use vcnc::interp::sinumerik::Sinumerik;
    use vcnc::interp::{Kernel, MemoryLibrary, Run};
    use vcnc::FileId;
    let mut library = MemoryLibrary::new();
    library.insert_named(
        "LATHE1",
        FileId(1),
        "PROC LATHE1 SAVE\nDIAMON\nG0 X40\nM17\n",
    );
    let machine = machine();
    let text = "LATHE1\nG0 X40\nM30\n";
    let front_end =
        Sinumerik::new(text.as_bytes(), FileId(0), &machine).with_library(Box::new(library));
    let run = collect(Run::new(front_end, Kernel::new(&machine)));
    assert!(run.error().is_none(), "{:?}", run.alarms);
    assert_points(&ends(&run.segments), &[[20.0, 0.0, 0.0], [40.0, 0.0, 0.0]]);
}

#[test]
fn positioning_axes_take_the_diameter_programming_too() {
    // L4748-4752: POS and POSA are among the commands diameter programming acts on.
    let segments = run("DIAMON\nPOS[X]=60 FA[X]=1000", &machine());
    assert_points(&ends(&segments), &[[30.0, 0.0, 0.0]]);
}

#[test]
fn diameter_commands_that_cannot_run_are_alarms() {
    let mut with_c = machine();
    with_c.axes[vcnc::Axis::C.index()] = Some(crate::common::rotary_axis());
    // L4606-4610: a rotary axis cannot be a transverse axis.
    let rotary = error("DIAMONA[C]", &with_c);
    assert_eq!(rotary.code, AlarmCode::WordNotAllowed);
    assert!(rotary.message.contains("rotary"), "{}", rotary.message);
    assert_eq!(error("DIAMONA", &machine()).code, AlarmCode::MissingValue);
    assert_eq!(
        error("DIAMONA[U]", &machine()).code,
        AlarmCode::AxisNotOnMachine
    );
}

// The constant cutting rate.

#[test]
fn g96_follows_the_diameter_of_a_diameter_programmed_transverse_axis() {
    // The manual's turning header (a/05, L779-787): 300 m/min at diameter 82 is
    // 300000 / (pi 82) = 1164.548 rpm, under LIMS 3000. Before N60 the tool stands at X200
    // (radius programming of N10's G153 X200: radius 200): 300000 / (2 pi 200) = 238.732.
    let text = "N10 G0 G153 X200 Z500\nN40 G96 S300 LIMS=3000 M4\nN50 DIAMON\n\
                N60 G54 G18 G0 X82 Z0.2";
    let speeds = speeds(&run(text, &machine()));
    assert_eq!(speeds.len(), 2, "{speeds:?}");
    assert_close(speeds[0], 238.732, 1e-3);
    assert_close(speeds[1], 1164.548, 1e-3);
}

#[test]
fn g96_speed_at_the_end_of_a_facing_cut_in_radius_programming() {
    // a/30 N40-N60 (L2220-2226): 20 m/min; at X34 in radius programming the diameter is 68:
    // 20000 / (pi 68) = 93.621 rpm, the header's figure.
    let text = "G18 LIMS=3000\nG0 X100 Z100\nG96 S20 M3\nG0 X80\nG1 F1.2 X34";
    let speeds = speeds(&run(text, &machine()));
    assert_close(*speeds.last().expect("a speed"), 93.621, 1e-3);
}

#[test]
fn g94_ends_the_constant_cutting_rate_and_keeps_the_speed() {
    // L2254-2255: after G94 the last speed stays. At X50: 100000 / (2 pi 50) = 318.310 rpm;
    // X25 after G94 changes nothing.
    let text = "G0 X50\nG96 S100 M3\nG94 F100\nG1 X25";
    let segments = run(text, &machine());
    let speeds = speeds(&segments);
    assert_eq!(speeds.len(), 1, "{speeds:?}");
    assert_close(speeds[0], 318.310, 1e-3);
}

#[test]
fn scc_makes_another_geometry_axis_the_reference_axis() {
    // L2188-2189: at Y20, 100000 / (2 pi 20) = 795.775 rpm; X stays out of it.
    let text = "G0 X10 Y20\nSCC[Y]\nG96 S100 M3";
    let speeds = speeds(&run(text, &machine()));
    assert_close(*speeds.last().expect("a speed"), 795.775, 1e-3);
}

#[test]
fn the_feed_per_revolution_follows_the_cutting_rate() {
    // a/34 (L2320-2328): S20 at X35 = 90.946 rpm, 1.5 mm/rev -> 136.419 mm/min for N25;
    // SCC[Y] at Y30 = 106.103 rpm, 1.2 mm/rev -> 127.324 mm/min for N40.
    let text = "G0 Z50\nX35 Y30\nSCC[X]\nG96 M3 S20\nG1 F1.5 X20\nG0 Z51\nSCC[Y]\nG1 F1.2 Y25";
    let segments = run(text, &machine());
    let feeds: Vec<f64> = segments
        .iter()
        .filter_map(|s| match &s.kind {
            SegmentKind::Line { feed, .. } => feed.mm_per_min(s.length()),
            _ => None,
        })
        .collect();
    assert_eq!(feeds.len(), 2);
    assert_close(feeds[0], 136.419, 1e-3);
    assert_close(feeds[1], 127.324, 1e-3);
}

// Geometry axis exchange.

#[test]
fn scc_of_a_channel_axis_that_is_no_geometry_axis_is_an_alarm() {
    // The manual's case 3 (a/33, L2315-2318).
    let alarm = error("G95 F0.1\nGEOAX(1, X2)\nSCC[X1]", &with_x2());
    assert_eq!(alarm.code, AlarmCode::WordNotAllowed);
    assert!(alarm.message.contains("SCC[X1]"), "{}", alarm.message);
    // Cases 1 and 2 run (a/31, a/32).
    run(
        "G95 F0.1\nGEOAX(1, X1)\nSCC[X]\nGEOAX(1, X2)\nG96 M3 S20",
        &with_x2(),
    );
    run(
        "G95 F0.1\nGEOAX(1, X1)\nSCC[X1]\nGEOAX(1, X2)\nG96 M3 S20",
        &with_x2(),
    );
}

#[test]
fn the_reference_axis_reads_the_channel_axis_geoax_put_behind_it() {
    // L2291-2292: X2 at 25 behind geometry axis X after GEOAX: 100000 / (2 pi 25) = 636.620;
    // before it X (X1) at 0 gives the LIMS of 5000.
    let text = "G0 X2=25\nG96 S100 M3 LIMS=5000\nGEOAX(1, X2)\nG0 Z1";
    let speeds = speeds(&run(text, &with_x2()));
    assert_eq!(speeds.len(), 2, "{speeds:?}");
    assert_close(speeds[0], 5000.0, 1e-9);
    assert_close(speeds[1], 636.620, 1e-3);
}

#[test]
fn geoax_zero_leaves_no_reference_position_and_the_speed_stays() {
    // L2294-2295: GEOAX(0, X) takes X out; the speed is frozen as under G97.
    let text = "G0 X50\nG96 S100 M3\nGEOAX(0, X)\nG0 Z10\nGEOAX()\nG0 X25";
    let speeds = speeds(&run(text, &machine()));
    // 318.310 at X50, frozen while X is out, 636.620 at X25 after GEOAX() brings it back.
    assert_eq!(speeds.len(), 2, "{speeds:?}");
    assert_close(speeds[0], 318.310, 1e-3);
    assert_close(speeds[1], 636.620, 1e-3);
}

#[test]
fn a_geometry_axis_moved_after_an_exchange_is_an_alarm() {
    let alarm = error("GEOAX(1, X2)\nG0 X10", &with_x2());
    assert_eq!(alarm.code, AlarmCode::NotSupportedYet);
    assert!(alarm.message.contains("X2"), "{}", alarm.message);
    // GEOAX() brings the machine's geometry axes back.
    let segments = run("GEOAX(1, X2)\nGEOAX()\nG0 X10", &with_x2());
    assert_points(&ends(&segments), &[[10.0, 0.0, 0.0]]);
    assert_eq!(
        error("GEOAX(1, Q7)", &machine()).code,
        AlarmCode::AxisNotOnMachine
    );
    assert_eq!(
        error("GEOAX(1, Y)", &machine()).code,
        AlarmCode::WordNotAllowed
    );
    assert_eq!(error("GEOAX(1)", &machine()).code, AlarmCode::MacroSyntax);
}
