//! `cargo xtask readme`: regenerates the supported-codes table in README.md from the code.

use std::path::Path;

const START: &str = "<!-- codes:start -->";
const END: &str = "<!-- codes:end -->";

pub(crate) fn run(_args: &[String]) -> Result<(), String> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../README.md");
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let (Some(start), Some(end)) = (text.find(START), text.find(END)) else {
        return Err(format!(
            "{} has no {START} ... {END} section",
            path.display()
        ));
    };
    let table = vcnc::profile::supported_codes_markdown();
    let new = format!(
        "{}{START}\n{table}{END}{}",
        &text[..start],
        &text[end + END.len()..]
    );
    std::fs::write(&path, new).map_err(|e| format!("{}: {e}", path.display()))?;
    println!("README.md: supported-codes table regenerated");
    Ok(())
}
