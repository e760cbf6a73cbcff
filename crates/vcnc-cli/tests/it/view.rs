//! `vcnc view` end to end: the page's data against `vcnc trace` of the same program, the server
//! on 127.0.0.1, and the page in Debian's headless Chromium driven over WebDriver (chromedriver's
//! HTTP API, by a few lines over `TcpStream`): it loads from a file with the network off, holds
//! one segment per motion record of the trace, a click on a segment shows its line, the slider
//! puts the tool where the trace's timing says. Without chromium and chromedriver the browser
//! test skips with a notice, unless `CI` is set (`.ci/install-chromium` installs them).

use crate::cli::{example, temp_program, vcnc};
use serde_json::{json, Value};
use std::io::{BufRead, BufReader, Read, Write};
use std::net::{Ipv4Addr, TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

fn temp_path(name: &str) -> String {
    let dir = std::env::temp_dir().join(format!("vcnc-cli-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name).display().to_string()
}

fn bracket_machine() -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/bracket-mill.toml")
        .display()
        .to_string()
}

/// The motion records (rapid, feed, arc) of `vcnc trace --work` with `args`.
fn trace_moves(args: &[&str]) -> Vec<Value> {
    let mut all = vec!["trace", "--work"];
    all.extend(args);
    let out = vcnc(&all);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|line| serde_json::from_str::<Value>(line).unwrap())
        .filter(|r| matches!(r["kind"].as_str(), Some("rapid" | "feed" | "arc")))
        .collect()
}

/// The scene the page at `html` holds.
fn page_data(html: &str) -> Value {
    let page = std::fs::read_to_string(html).unwrap();
    let start = r#"<script id="vcnc-data" type="application/json">"#;
    let from = page.find(start).unwrap() + start.len();
    let to = from + page[from..].find("</script>").unwrap();
    serde_json::from_str(&page[from..to]).unwrap()
}

/// Writes the page of `vcnc view` with `args`, which must end with `exit_code`.
fn write_page_ending(name: &str, args: &[&str], exit_code: i32) -> String {
    let html = temp_path(name);
    let mut all = vec!["view", "--html", &html];
    all.extend(args);
    let out = vcnc(&all);
    assert_eq!(
        out.status.code(),
        Some(exit_code),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    html
}

fn write_page(name: &str, args: &[&str]) -> String {
    write_page_ending(name, args, 0)
}

fn xyz(record: &Value, prefix: &str) -> [f64; 3] {
    ["x", "y", "z"].map(|a| record[format!("{prefix}{a}")].as_f64().unwrap())
}

#[test]
fn the_page_holds_one_segment_per_motion_record_of_the_trace() {
    // The bracket on its machine, and a FANUC 0M program whose rapids are per axis (a segment
    // per leg, as the trace writes them).
    let dog_leg = temp_program(
        "view_dog_leg.nc",
        "G21 G90 G54\nG0 X50. Y10. Z5.\nG1 Z-1. F300.\nX0\nG0 X100. Y80. Z20.\nM30\n",
    );
    let (bracket, machine) = (example(), bracket_machine());
    let cases: [(&str, Vec<&str>); 2] = [
        ("bracket.html", vec![&bracket, "--machine", &machine]),
        ("dog_leg.html", vec![&dog_leg, "--profile", "fanuc0m"]),
    ];
    for (name, args) in cases {
        let moves = trace_moves(&args);
        let data = page_data(&write_page(name, &args));
        let segments = data["segments"].as_array().unwrap();
        assert_eq!(segments.len(), moves.len(), "{name}");
        for (segment, record) in segments.iter().zip(&moves) {
            assert_eq!(segment[3], record["line"], "{name}: {record}");
            let t = segment[4].as_f64().unwrap();
            assert!((t - record["t"].as_f64().unwrap()).abs() < 1e-6, "{record}");
            // The end point (fields 9 to 11) is the trace's in program coordinates.
            let end = xyz(record, "w");
            for k in 0..3 {
                let at = segment[9 + k].as_f64().unwrap();
                assert!(
                    (at - end[k]).abs() < 1e-3,
                    "{name}: {segment} against {record}"
                );
            }
        }
    }
}

#[test]
fn the_page_has_the_stock_at_most_200_cells_a_side_and_can_leave_it_out() {
    let machine = bracket_machine();
    let data = page_data(&write_page(
        "stock.html",
        &[&example(), "--machine", &machine],
    ));
    let size: Vec<u64> = serde_json::from_value(data["stock"]["size"].clone()).unwrap();
    assert!(size.iter().all(|&n| (1..=200).contains(&n)), "{size:?}");
    let heights = data["stock"]["heights"].as_array().unwrap();
    assert_eq!(heights.len() as u64, size[0] * size[1]);
    // The bracket cuts its plate: some cell is below the stock's top.
    let top = data["stock"]["top"].as_f64().unwrap();
    assert!(heights.iter().any(|h| h.as_f64().unwrap() < top - 1.0));
    let bare = page_data(&write_page(
        "bare.html",
        &[&example(), "--machine", &machine, "--no-stock"],
    ));
    assert!(bare["stock"].is_null());
}

#[test]
fn the_page_places_a_rapid_into_the_stock_at_its_block() {
    // The default machine's tool 1 made 10 mm wide by G10; the slot along X is 3 mm deep and
    // the stock from the cut's extents reaches 1 mm beyond its sides (Y -6 to 6, Z0 at the
    // top): the rapid of line 7 leaves the slot's end sideways through the wall, 3 mm deep.
    // Its marker is where it first meets the wall, the page looking every 1.25 mm (a quarter
    // of the radius) under the centre and at eight points a cell (0.06 mm: 200 cells across the
    // 12 mm stock) inside the rim: at the start all eight are in the cut (4.94 mm from X50 Y0,
    // where the slot ends); 1.25 mm on, the look at 45 degrees, X 53.49 Y 4.74, is 5.89 mm from
    // X50 Y0 and beyond the slot's end, uncut, 3 mm above the tip.
    let program = temp_program(
        "view_crash.nc",
        "G21 G90 G10 L12 P1 R5.\nT1 M6\nS5000 M3\nG0 X0 Y0 Z5.\nG1 Z-3. F500.\nX50.\nG0 Y40.\nG0 Z5.\nM30\n",
    );
    // The alarm is an error: the command ends with 1, the page written all the same.
    let data = page_data(&write_page_ending("crash.html", &[&program], 1));
    let alarms = data["alarms"].as_array().unwrap();
    let crash = alarms
        .iter()
        .find(|a| a["line"] == 7 && a["at"].is_array())
        .unwrap_or_else(|| panic!("no alarm placed at line 7: {alarms:?}"));
    assert_eq!(crash["at"], json!([50.0, 1.25, -3.0]), "{crash}");
    assert_eq!(crash["code"], "V110", "{crash}");
    assert_eq!(crash["error"], true);
}

#[test]
fn the_server_answers_the_page_on_localhost() {
    let mut child = Command::new(env!("CARGO_BIN_EXE_vcnc"))
        .args(["view", &example(), "--no-stock", "--port", "0"])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    let url = line.split_whitespace().find(|w| w.starts_with("http://"));
    let answer = url.and_then(|url| {
        let address = url.trim_start_matches("http://").trim_end_matches('/');
        let mut stream = TcpStream::connect(address).ok()?;
        stream
            .write_all(b"GET / HTTP/1.1\r\nHost: x\r\n\r\n")
            .ok()?;
        let mut answer = String::new();
        stream.read_to_string(&mut answer).ok()?;
        Some(answer)
    });
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(line.contains("http://127.0.0.1:"), "{line}");
    let answer = answer.unwrap_or_default();
    assert!(answer.starts_with("HTTP/1.1 200 OK"), "{answer:.200}");
    assert!(answer.contains("window.vcncView") && answer.contains("N170 G01 X52."));
}

// ---- The page in a browser ----

/// `name` on PATH.
fn on_path(name: &str) -> Option<PathBuf> {
    std::env::split_paths(&std::env::var_os("PATH")?)
        .map(|dir| dir.join(name))
        .find(|path| path.is_file())
}

/// Chromium and its WebDriver, or `None` after a notice (a panic under CI).
fn browser() -> Option<(PathBuf, PathBuf)> {
    if let (Some(chromium), Some(driver)) = (on_path("chromium"), on_path("chromedriver")) {
        return Some((chromium, driver));
    }
    assert!(
        std::env::var_os("CI").is_none_or(|v| v.is_empty()),
        "CI runs the viewer's browser test: chromium and chromedriver are missing (.ci/install-chromium)"
    );
    // Straight to the stream: libtest hides what a passing test prints.
    let _ = std::io::stderr().write_all(
        b"note: view: skipped the browser test: chromium or chromedriver is not on PATH (.ci/install-chromium)\n",
    );
    None
}

/// A chromedriver process and one browser session in it, ended when dropped.
struct Driver {
    child: Child,
    port: u16,
    session: String,
}

impl Driver {
    fn start(chromium: &Path, chromedriver: &Path, profile: &Path) -> Driver {
        let port = TcpListener::bind((Ipv4Addr::LOCALHOST, 0))
            .unwrap()
            .local_addr()
            .unwrap()
            .port();
        let child = Command::new(chromedriver)
            .arg(format!("--port={port}"))
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        let mut driver = Driver {
            child,
            port,
            session: String::new(),
        };
        let started = Instant::now();
        while driver.try_request("GET", "/status", None).is_err() {
            assert!(
                started.elapsed() < Duration::from_secs(20),
                "chromedriver did not start"
            );
            std::thread::sleep(Duration::from_millis(100));
        }
        let args = [
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            // WebGL without a GPU: ANGLE on SwiftShader, the software Vulkan.
            "--use-angle=swiftshader",
            "--enable-unsafe-swiftshader",
            // The network off: no name resolves and no proxy answers.
            "--host-resolver-rules=MAP * ~NOTFOUND",
            "--proxy-server=127.0.0.1:9",
            "--window-size=1200,800",
            &format!("--user-data-dir={}", profile.display()),
        ];
        let capabilities = json!({ "capabilities": { "alwaysMatch": {
            "goog:chromeOptions": { "binary": chromium, "args": args }
        }}});
        let answer = driver.request("POST", "/session", Some(&capabilities));
        driver.session = answer["value"]["sessionId"].as_str().unwrap().to_string();
        driver
    }

    /// A WebDriver command on the session: its `value`.
    fn command(&self, method: &str, path: &str, body: Option<&Value>) -> Value {
        let path = format!("/session/{}{path}", self.session);
        self.request(method, &path, body)["value"].clone()
    }

    fn script(&self, script: &str) -> Value {
        self.command(
            "POST",
            "/execute/sync",
            Some(&json!({ "script": script, "args": [] })),
        )
    }

    fn request(&self, method: &str, path: &str, body: Option<&Value>) -> Value {
        let answer = self.try_request(method, path, body).unwrap();
        assert!(
            answer["value"]["error"].is_null(),
            "{method} {path}: {answer}"
        );
        answer
    }

    fn try_request(
        &self,
        method: &str,
        path: &str,
        body: Option<&Value>,
    ) -> std::io::Result<Value> {
        let body = body.map_or(String::new(), Value::to_string);
        let mut stream = TcpStream::connect((Ipv4Addr::LOCALHOST, self.port))?;
        stream.set_read_timeout(Some(Duration::from_secs(120)))?;
        write!(
            stream,
            "{method} {path} HTTP/1.1\r\nHost: 127.0.0.1:{}\r\nContent-Type: application/json\r\n\
             Content-Length: {}\r\nConnection: close\r\n\r\n{body}",
            self.port,
            body.len()
        )?;
        // chromedriver keeps the connection open: the answer ends by its length, or by the
        // last chunk.
        let mut answer = Vec::new();
        let mut buffer = [0u8; 65536];
        loop {
            let read = stream.read(&mut buffer)?;
            answer.extend_from_slice(&buffer[..read]);
            if read == 0 || complete(&answer).is_some() {
                break;
            }
        }
        let body = complete(&answer).ok_or_else(|| std::io::Error::other("a cut answer"))?;
        serde_json::from_slice(&body).map_err(std::io::Error::other)
    }
}

impl Drop for Driver {
    fn drop(&mut self) {
        if !self.session.is_empty() {
            let _ = self.try_request("DELETE", &format!("/session/{}", self.session), None);
        }
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The body of the HTTP answer `bytes` once it is all there.
fn complete(bytes: &[u8]) -> Option<Vec<u8>> {
    let split = bytes.windows(4).position(|w| w == b"\r\n\r\n")?;
    let head = String::from_utf8_lossy(&bytes[..split]).to_ascii_lowercase();
    let body = &bytes[split + 4..];
    if head.contains("transfer-encoding: chunked") {
        return body.ends_with(b"0\r\n\r\n").then(|| unchunk(body));
    }
    let length = head
        .lines()
        .find_map(|l| l.strip_prefix("content-length:"))
        .and_then(|v| v.trim().parse::<usize>().ok())?;
    (body.len() >= length).then(|| body[..length].to_vec())
}

/// The body of a chunked HTTP answer.
fn unchunk(mut bytes: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    while let Some(end) = bytes.windows(2).position(|w| w == b"\r\n") {
        let size_text = String::from_utf8_lossy(&bytes[..end]);
        let size =
            usize::from_str_radix(size_text.split(';').next().unwrap().trim(), 16).unwrap_or(0);
        if size == 0 {
            break;
        }
        let start = end + 2;
        out.extend_from_slice(&bytes[start..start + size]);
        bytes = &bytes[(start + size + 2).min(bytes.len())..];
    }
    out
}

/// Standard base64 (the screenshot WebDriver answers).
fn base64(text: &str) -> Vec<u8> {
    let value = |c: u8| match c {
        b'A'..=b'Z' => c - b'A',
        b'a'..=b'z' => c - b'a' + 26,
        b'0'..=b'9' => c - b'0' + 52,
        b'+' => 62,
        _ => 63,
    };
    let digits: Vec<u8> = text
        .bytes()
        .filter(|c| c.is_ascii_alphanumeric() || *c == b'+' || *c == b'/')
        .collect();
    let mut out = Vec::with_capacity(digits.len() * 3 / 4);
    for chunk in digits.chunks(4) {
        let bits = chunk.iter().enumerate().fold(0u32, |acc, (k, &c)| {
            acc | u32::from(value(c)) << (18 - 6 * k)
        });
        out.extend_from_slice(&bits.to_be_bytes()[1..chunk.len()]);
    }
    out
}

/// Where the tool is at `fraction` of trace record `k` (from the end of record `k - 1`), in
/// program coordinates: along the line, or around the arc's centre for an arc.
fn expected_point(moves: &[Value], k: usize, fraction: f64) -> [f64; 3] {
    let from = xyz(&moves[k - 1], "w");
    let to = xyz(&moves[k], "w");
    let mut p: [f64; 3] = std::array::from_fn(|i| from[i] + fraction * (to[i] - from[i]));
    if moves[k]["kind"] == "arc" {
        assert_eq!(moves[k]["plane"], "xy");
        // The centre in program coordinates: the frame here is a translation.
        let machine = xyz(&moves[k], "");
        let center = xyz(&moves[k], "c");
        let c = [0, 1].map(|i| center[i] + to[i] - machine[i]);
        let start = (from[1] - c[1]).atan2(from[0] - c[0]);
        let mut sweep = (to[1] - c[1]).atan2(to[0] - c[0]) - start;
        let clockwise = moves[k]["dir"] == "cw";
        if clockwise && sweep > 0.0 {
            sweep -= std::f64::consts::TAU;
        } else if !clockwise && sweep < 0.0 {
            sweep += std::f64::consts::TAU;
        }
        let radius = (from[0] - c[0]).hypot(from[1] - c[1]);
        let angle = start + fraction * sweep;
        p[0] = c[0] + radius * angle.cos();
        p[1] = c[1] + radius * angle.sin();
    }
    p
}

fn target_dir() -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../target"))
        .join("vcnc-view")
}

#[test]
fn the_page_in_headless_chromium_loads_offline_picks_and_follows_the_timeline() {
    let Some((chromium, chromedriver)) = browser() else {
        return;
    };
    let machine = bracket_machine();
    let args = [example(), "--machine".to_string(), machine];
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let moves = trace_moves(&args);
    let html = write_page("chromium.html", &args);
    let profile = PathBuf::from(temp_path("chromium-profile"));
    let _ = std::fs::remove_dir_all(&profile);
    let driver = Driver::start(&chromium, &chromedriver, &profile);
    let url = format!("file://{}", std::fs::canonicalize(&html).unwrap().display());
    driver.command("POST", "/url", Some(&json!({ "url": url })));
    let started = Instant::now();
    while driver.script("return !!window.vcncView") != json!(true) {
        assert!(
            started.elapsed() < Duration::from_secs(30),
            "the page did not start"
        );
        std::thread::sleep(Duration::from_millis(100));
    }
    assert_eq!(
        driver.script("return window.vcncView.webgl"),
        json!(true),
        "no WebGL"
    );
    // Nothing but the page itself was loaded.
    assert_eq!(
        driver.script("return performance.getEntriesByType('resource').length"),
        json!(0)
    );
    assert_eq!(
        driver.script("return window.vcncView.segmentCount()"),
        json!(moves.len())
    );

    // A click on the middle of the outline's long side (N170, line 27) shows its block.
    let k = moves.iter().position(|m| m["line"] == 27).unwrap();
    let at = driver.script(&format!("return window.vcncView.project({k})"));
    let [x, y] = [0, 1].map(|i| at[i].as_f64().unwrap().round() as i64);
    let click = json!({ "actions": [{
        "type": "pointer", "id": "mouse", "parameters": { "pointerType": "mouse" },
        "actions": [
            { "type": "pointerMove", "duration": 0, "x": x, "y": y, "origin": "viewport" },
            { "type": "pointerDown", "button": 0 },
            { "type": "pointerUp", "button": 0 },
        ],
    }]});
    driver.command("POST", "/actions", Some(&click));
    assert_eq!(driver.script("return window.vcncView.selected()"), json!(k));
    let info = driver.script("return document.getElementById('info').textContent");
    let info = info.as_str().unwrap();
    assert!(
        info.contains("bracket.nc:27") && info.contains("N170 G01 X52."),
        "{info}"
    );
    let current =
        driver.script("return document.querySelector('#program div.current').textContent");
    assert_eq!(current, json!("27N170 G01 X52."));

    // The slider at 37 % of a line (N170) and of an arc (N160, line 26) puts the tool where the
    // trace's start and duration of the segment say, an even speed along it.
    for line in [27, 26] {
        let k = moves.iter().position(|m| m["line"] == line).unwrap();
        let t = moves[k]["t"].as_f64().unwrap() + 0.37 * moves[k]["dt"].as_f64().unwrap();
        driver.script(&format!(
            "const s = document.getElementById('slider'); s.value = '{t}'; \
             s.dispatchEvent(new Event('input'));"
        ));
        let tool = driver.script("return window.vcncView.toolPosition()");
        let expected = expected_point(&moves, k, 0.37);
        for i in 0..3 {
            let got = tool[i].as_f64().unwrap();
            assert!(
                (got - expected[i]).abs() < 0.01,
                "line {line} at {t} s: tool at {tool}, the trace says {expected:?}"
            );
        }
    }

    let screenshot = driver.command("GET", "/screenshot", None);
    let png = base64(screenshot.as_str().unwrap());
    assert_eq!(&png[1..4], b"PNG");
    let dir = target_dir();
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("bracket.png"), png).unwrap();
}

/// Issue 21, acceptance 4: `vcnc plot`'s SVG, rendered by a real SVG renderer (Chromium, opened
/// as a file), has path pixels where the layout puts them. A 100 x 100 mm square (the last
/// corner an arc) drawn 600 px wide from the top: 40 px margins and 520 px for the 100 mm of X,
/// 5.2 px/mm, the top edge 20 px lower for the extents line. The edge Y0 lies at
/// y = 40 + 20 + 100 * 5.2 = 580 px, X100 at x = 40 + 100 * 5.2 = 560 px; X50 is x = 300, Y25 is
/// y = 580 - 25 * 5.2 = 450.
#[test]
fn the_plots_svg_renders_in_chromium_with_path_pixels_where_the_layout_puts_them() {
    let Some((chromium, chromedriver)) = browser() else {
        return;
    };
    let program = temp_program(
        "svg-square.nc",
        "G0 X0 Y0 Z5.\nG1 Z-1. F300.\nX100.\nY50.\nG3 X50. Y100. R50.\nG1 X0\nY0\nG0 Z5.\nM30\n",
    );
    let svg = temp_path("svg-square.svg");
    let out = vcnc(&[
        "plot", &program, "-o", &svg, "--view", "top", "--width", "600",
    ]);
    assert!(out.status.success(), "{out:?}");
    let profile = PathBuf::from(temp_path("chromium-svg-profile"));
    let _ = std::fs::remove_dir_all(&profile);
    let driver = Driver::start(&chromium, &chromedriver, &profile);
    let url = format!("file://{}", std::fs::canonicalize(&svg).unwrap().display());
    driver.command("POST", "/url", Some(&json!({ "url": url })));
    let screenshot = driver.command("GET", "/screenshot", None);
    let bytes = base64(screenshot.as_str().unwrap());
    let mut reader = png::Decoder::new(std::io::Cursor::new(&bytes))
        .read_info()
        .unwrap();
    let mut buffer = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buffer).unwrap();
    let channels = info.color_type.samples();
    let pixel = |x: usize, y: usize| {
        let i = (y * info.width as usize + x) * channels;
        [buffer[i], buffer[i + 1], buffer[i + 2]]
    };
    let white = [255, 255, 255];
    // On the edges Y0 (X50) and X100 (Y25), each within a pixel of where the layout says.
    let near =
        |x: usize, y: usize| (x - 1..=x + 1).any(|x| (y - 1..=y + 1).any(|y| pixel(x, y) != white));
    assert!(near(300, 580), "no path at (300, 580)");
    assert!(near(560, 450), "no path at (560, 450)");
    // On the arc, 45 degrees round from X100 Y50 about X50 Y50: X Y 85.355 at x = 40 + 85.355
    // * 5.2 = 483.8, y = 580 - 85.355 * 5.2 = 136.2.
    assert!(near(484, 136), "no arc at (484, 136)");
    // Inside the square and outside it: paper.
    assert_eq!(pixel(300, 450), white);
    assert_eq!(pixel(300, 570), white);
    assert_eq!(pixel(580, 450), white);
    let dir = target_dir();
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("svg-square.png"), bytes).unwrap();
}
