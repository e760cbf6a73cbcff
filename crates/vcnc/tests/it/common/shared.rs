//! Where the reference material beside the repository is (`../shared`, or `$VCNC_SHARED`), and
//! what a test that needs it does when it is absent: skips with a notice on a developer's fresh
//! clone, fails under CI (`CI` set), where every suite must run. The CLI's tests include this
//! same file, so it must never use the crate under test.

use std::cell::Cell;
use std::io::Write;
use std::path::PathBuf;

thread_local! {
    /// Whether this test (libtest runs each on its own thread) has printed its notice.
    static NOTED: Cell<bool> = const { Cell::new(false) };
}

/// The reference material: `$VCNC_SHARED`, else `../shared` beside the repository. `None` when
/// that folder does not exist, after one notice per test on standard error: the caller skips
/// what needs it (a test that needs nothing else returns at once). When `CI` is set and not
/// empty, absence panics instead.
pub(crate) fn shared_dir() -> Option<PathBuf> {
    let (dir, reason) = match std::env::var_os("VCNC_SHARED") {
        Some(dir) => (
            PathBuf::from(&dir),
            format!("VCNC_SHARED={} is not a folder", dir.to_string_lossy()),
        ),
        None => (
            PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared"),
            "../shared is absent (set VCNC_SHARED)".to_string(),
        ),
    };
    if dir.is_dir() {
        return Some(dir);
    }
    assert!(
        std::env::var_os("CI").is_none_or(|value| value.is_empty()),
        "CI runs every suite, and {reason}"
    );
    if !NOTED.replace(true) {
        let test = std::thread::current()
            .name()
            .filter(|name| *name != "main")
            .map_or(String::new(), |name| format!("{name}: "));
        // Straight to the stream, not through eprintln!: libtest hides what a passing test prints.
        let notice = format!("note: {test}skipped what needs the reference material: {reason}\n");
        let _ = std::io::stderr().write_all(notice.as_bytes());
    }
    None
}
