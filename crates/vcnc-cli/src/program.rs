//! Opening a program file: dialect detection and a streaming line source.

use std::fs::File;
use std::io::Read;
use std::path::Path;
use vcnc::syntax::source::BackgroundParser;
use vcnc::syntax::{detect_dialect, Dialect};
use vcnc::{Alarm, FileId, Interpreter, Machine, Options, Segment};

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

/// The interpreter's stream, taken from it a batch at a time ([`Interpreter::next_batch`]) and
/// handed out one item at a time: the planner pulls items, and batches are the interpreter's
/// fast path.
pub(crate) struct Batched {
    interpreter: FileInterpreter,
    /// The current batch, reversed, so that `pop` gives the next item.
    items: Vec<Result<Segment, Alarm>>,
    more: bool,
}

/// Segments per batch taken from the interpreter.
const BATCH: usize = 1024;

impl Batched {
    pub(crate) fn new(interpreter: FileInterpreter) -> Batched {
        Batched {
            interpreter,
            items: Vec::with_capacity(BATCH + 64),
            more: true,
        }
    }

    /// Blocks the interpreter has run so far.
    pub(crate) fn blocks_executed(&self) -> u64 {
        self.interpreter.blocks_executed()
    }
}

impl Iterator for Batched {
    type Item = Result<Segment, Alarm>;

    fn next(&mut self) -> Option<Self::Item> {
        while self.items.is_empty() && self.more {
            self.more = self.interpreter.next_batch(&mut self.items, BATCH);
            self.items.reverse();
        }
        self.items.pop()
    }
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
