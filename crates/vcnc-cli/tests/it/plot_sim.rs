//! `vcnc plot` and `vcnc sim` end to end: files written, the summary's JSON, exit codes.

use crate::cli::{example, temp_program, vcnc};

fn temp_path(name: &str) -> String {
    let dir = std::env::temp_dir().join(format!("vcnc-cli-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name).display().to_string()
}

#[test]
fn plot_writes_svg_and_png_of_the_bundled_example() {
    let svg = temp_path("bracket.svg");
    let out = vcnc(&["plot", &example(), "-o", &svg]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg") && text.contains(r#"class="feed""#));
    let png = temp_path("bracket.png");
    let out = vcnc(&[
        "plot",
        &example(),
        "-o",
        &png,
        "--view",
        "iso",
        "--width",
        "400",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
    // Width 400 in the header (bytes 16 to 20, big-endian).
    assert_eq!(u32::from_be_bytes(bytes[16..20].try_into().unwrap()), 400);
}

#[test]
fn plot_refuses_an_output_it_cannot_write() {
    let out = vcnc(&["plot", &example(), "-o", &temp_path("bracket.jpg")]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains(".svg or .png"));
}

#[test]
fn sim_json_gives_the_removed_volume_and_the_time() {
    // The default machine's tool 1 has radius 0 and no shape: give it radius 5 with G10.
    // A slot 100 mm long, 2 deep: (100 * 10 + 25 pi) * 2 = 2157.08 mm^3; 0.5 mm cells on a
    // 120 x 20 stock keep the grid's error under 1 %.
    let program = temp_program(
        "sim_slot.nc",
        "G21 G90 G10 L12 P1 R5.\nT1 M6\nS5000 M3\nG0 X0 Y0 Z5.\nG1 Z-2. F500.\nX100.\nG0 Z5.\nM30\n",
    );
    let stl = temp_path("sim_slot.stl");
    let out = vcnc(&[
        "sim",
        &program,
        "--stock",
        "-10,-10,-5,110,10,0",
        "--resolution",
        "0.5",
        "--format",
        "json",
        "--stl",
        &stl,
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let removed = json["removed_mm3"].as_f64().unwrap();
    let expected = (1000.0 + 25.0 * std::f64::consts::PI) * 2.0;
    assert!((removed - expected).abs() < expected * 0.01, "{removed}");
    assert_eq!(json["tools"][0]["tool"], 1);
    assert!(json["time"]["cutting_seconds"].as_f64().unwrap() > 0.0);
    // The tool without a shape is said once.
    assert_eq!(json["event_counts"]["tool_without_shape"], 1);
    let bytes = std::fs::read(&stl).unwrap();
    let count = u32::from_le_bytes(bytes[80..84].try_into().unwrap()) as usize;
    assert_eq!(bytes.len(), 84 + 50 * count);
}

#[test]
fn sim_alarms_a_rapid_into_the_stock_with_exit_code_1() {
    let program = temp_program(
        "sim_rapid.nc",
        "G21 G90 G10 L12 P1 R3.\nT1 M6\nS5000 M3\nG0 X0 Y0 Z5.\nG0 Z-1.\nG0 Z5.\nM30\n",
    );
    let out = vcnc(&[
        "sim",
        &program,
        "--stock",
        "-10,-10,-5,10,10,0",
        "--resolution",
        "0.5",
        "--format",
        "json",
    ]);
    assert_eq!(
        out.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let alarms = json["alarms"].as_array().unwrap();
    let rapid = alarms
        .iter()
        .find(|a| a["code"] == "V110")
        .unwrap_or_else(|| panic!("{alarms:?}"));
    assert_eq!(rapid["line"], 5, "{rapid}");
}

#[test]
fn sim_takes_its_stock_from_the_cut_by_default() {
    let out = vcnc(&["sim", &example(), "--resolution", "0.5"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.contains("stock             X -21.000 .. 74.000"),
        "{text}"
    );
    assert!(text.contains("T1    flat 10 mm"), "{text}");
}

#[test]
fn the_readmes_sim_summary_is_what_sim_prints() {
    let root = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let start = readme
        .find("```text\nexamples/bracket.nc\n")
        .expect("README shows the summary")
        + 8;
    let end = start + readme[start..].find("```").unwrap();
    // From the repository's root, as the README runs it (the summary names the program so).
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_vcnc"))
        .current_dir(&root)
        .args([
            "sim",
            "examples/bracket.nc",
            "--machine",
            "examples/bracket-mill.toml",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(String::from_utf8(out.stdout).unwrap(), &readme[start..end]);
}

/// An ASCII STL of the box `[low, high]`: twelve triangles, outward.
fn box_stl(low: [f64; 3], high: [f64; 3]) -> String {
    let corner = |k: usize| {
        [
            if k & 1 == 0 { low[0] } else { high[0] },
            if k & 2 == 0 { low[1] } else { high[1] },
            if k & 4 == 0 { low[2] } else { high[2] },
        ]
    };
    // Each face's corners (by bit index) counter-clockwise seen from outside.
    let faces = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let mut text = String::from("solid box\n");
    for f in faces {
        for t in [[f[0], f[1], f[2]], [f[0], f[2], f[3]]] {
            text.push_str("facet normal 0 0 0\nouter loop\n");
            for k in t {
                let [x, y, z] = corner(k);
                text.push_str(&format!("vertex {x} {y} {z}\n"));
            }
            text.push_str("endloop\nendfacet\n");
        }
    }
    text + "endsolid box\n"
}

#[test]
fn sim_finds_a_planted_gouge_against_the_design_on_a_cylinder() {
    // A 40 mm bar (Z -10..0) and a design that is the bar's square 20 x 20 core at full height:
    // a 10 mm flat mill cuts 0.2 mm deep from X-5 to X5 at Y0, inside the core: a 0.2 mm gouge
    // there. The removed volume is the slot's (10 * 10 + 25 pi) * 0.2 = 35.71 mm^3.
    let design = temp_program(
        "core.stl",
        &box_stl([-10.0, -10.0, -10.0], [10.0, 10.0, 0.0]),
    );
    let program = temp_program(
        "gouge.nc",
        "G21 G90 G10 L12 P1 R5.\nT1 M6\nS5000 M3\nG0 X-5. Y0 Z5.\nG1 Z-0.2 F500.\nX5.\nG0 Z5.\nM30\n",
    );
    let png = temp_path("deviation.png");
    let out = vcnc(&[
        "sim",
        "--stock",
        "cyl:0,0,40,-10,0",
        "--design",
        &design,
        "--design-png",
        &png,
        "--format",
        "json",
        &program,
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let gouge = &json["design"]["gouge"];
    assert!(
        (gouge["mm"].as_f64().unwrap() - 0.2).abs() < 1e-3,
        "{json:#}"
    );
    let x = gouge["at"][0].as_f64().unwrap();
    assert!((-10.0..=10.0).contains(&x), "{json:#}");
    let removed = json["removed_mm3"].as_f64().unwrap();
    let expected = (100.0 + 25.0 * std::f64::consts::PI) * 0.2;
    assert!(
        (removed - expected).abs() < expected * 0.02,
        "{removed} vs {expected}"
    );
    assert_eq!(&std::fs::read(&png).unwrap()[1..4], b"PNG");
}
