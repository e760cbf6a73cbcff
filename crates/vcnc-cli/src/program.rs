//! Opening a program file: dialect detection and a streaming line source.

use std::fs::File;
use std::io::Read;
use std::path::Path;
use vcnc::syntax::source::BackgroundParser;
use vcnc::syntax::{detect_dialect, Dialect};
use vcnc::{FileId, Interpreter, Machine, Options};

/// A program being interpreted from a file.
pub(crate) type FileInterpreter = Interpreter<BackgroundParser>;

/// Opens `path` and starts interpreting it; the file is read and parsed on a thread of its own,
/// a few hundred lines ahead of the interpreter.
pub(crate) fn open(
    path: &Path,
    machine: &Machine,
    mut options: Options,
) -> Result<FileInterpreter, String> {
    let mut head = Vec::with_capacity(4096);
    let file = File::open(path).map_err(|e| format!("cannot open {}: {e}", path.display()))?;
    file.take(4096)
        .read_to_end(&mut head)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    options.dialect = detect_dialect(&name, &head);
    let file = File::open(path).map_err(|e| format!("cannot open {}: {e}", path.display()))?;
    let length = file.metadata().map_or(0, |m| m.len());
    let blocks =
        BackgroundParser::spawn_expecting(file, FileId(0), machine.profile.syntax(), length);
    Ok(Interpreter::from_blocks(
        blocks,
        FileId(0),
        machine,
        options,
    ))
}

/// The dialect a file would be read in.
#[allow(dead_code)]
pub(crate) fn dialect(path: &Path) -> Dialect {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    detect_dialect(&name, &std::fs::read(path).unwrap_or_default())
}
