//! Opening a program file: dialect detection and a streaming line source.

use std::fs::File;
use std::io::Read;
use std::path::Path;
use vcnc::syntax::lines::ReaderLines;
use vcnc::syntax::{detect_dialect, Dialect};
use vcnc::{FileId, Interpreter, Machine, Options};

/// A program being interpreted from a file.
pub(crate) type FileInterpreter = Interpreter<ReaderLines<File>>;

/// Opens `path` and starts interpreting it; the file is read as the interpreter goes.
pub(crate) fn open(path: &Path, machine: &Machine, mut options: Options) -> Result<FileInterpreter, String> {
    let mut head = Vec::with_capacity(4096);
    let file = File::open(path).map_err(|e| format!("cannot open {}: {e}", path.display()))?;
    file.take(4096).read_to_end(&mut head).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    options.dialect = detect_dialect(&name, &head);
    let file = File::open(path).map_err(|e| format!("cannot open {}: {e}", path.display()))?;
    let lines = ReaderLines::new(file);
    Ok(Interpreter::new(lines, FileId(0), machine, options))
}

/// The dialect a file would be read in.
#[allow(dead_code)]
pub(crate) fn dialect(path: &Path) -> Dialect {
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    detect_dialect(&name, &std::fs::read(path).unwrap_or_default())
}
