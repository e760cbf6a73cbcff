//! Opening a program file: dialect detection and a streaming line source.

use crate::setup::MachineArgs;
use std::collections::VecDeque;
use std::fs::File;
use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{sync_channel, Receiver, RecvError, SyncSender, TryRecvError};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};
use vcnc::checks::TravelCheck;
use vcnc::interp::{DirectoryLibrary, LoadedFiles, PersistentVariables};
use vcnc::syntax::lines::ReaderLines;
use vcnc::syntax::source::{BackgroundParser, BlockSource, ParsedLines};
use vcnc::syntax::Block;
use vcnc::syntax::{detect_dialect, Dialect};
use vcnc::{Alarm, FileId, Interpreter, Machine, Options, Segment};

/// A program being interpreted from a file.
pub(crate) type FileInterpreter = Interpreter<FileBlocks>;

/// Where the interpreter's thread gets a file's blocks: parsed ahead on a thread of its own, or
/// parsed by the interpreter's thread itself as it reads.
///
/// A parser thread pays when there is a core for it: on two cores, `trace` and `run` keep both
/// busy with the interpreter's thread and their own (planning, writing), and a third thread only
/// takes turns with them (measured on the 400,000-block program, two cores: 0.81 times the
/// wall time of `trace` and 0.87 times that of `run` without it). `check`, which only counts what
/// comes, leaves a core free for it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Parsing {
    /// On a thread of its own, a few hundred lines ahead.
    Ahead,
    /// On the interpreter's thread.
    InLine,
}

/// How the consumer of the interpreter's batches waits for the next one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Waiting {
    /// Spinning a little before it sleeps: for a consumer with a core of its own that is a little
    /// faster than the interpreter, so that the interpreter never has to wake it (a system call
    /// on the slower thread for each batch).
    Spin,
    /// Asleep at once: for a consumer that does little, whose spinning would take a core from the
    /// parser's and the interpreter's threads.
    Sleep,
}

/// Where the interpreter's thread stops when the travel check stops the program.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Stopping {
    /// At the block of the move beyond the travel, as the control does: the travel is checked
    /// after every block. For a consumer that shows how many blocks ran (`run`), and whenever a
    /// state file keeps the macro variables the blocks write.
    AtTheBlock,
    /// At the end of the batch that holds it: the travel is checked a batch at a time, which
    /// costs less than after every block. The stream is the same, cut at the same item: only
    /// the blocks-executed count and variable writes after the alarm differ, and `trace`
    /// without a state file shows neither. The check stays on the interpreter's thread: moved
    /// to the consumer's, which has fewer instructions a block but takes longer over them
    /// (planning's divisions, roots and arc tangents), it made `trace` 1.05 times slower
    /// (paired wall time, 400,000 blocks).
    AfterTheBatch,
}

/// The threads of a run: where the file is parsed, how the consumer waits, and where the
/// interpreter stops at an overtravel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Layout {
    pub(crate) parsing: Parsing,
    pub(crate) waiting: Waiting,
    pub(crate) stopping: Stopping,
}

impl Layout {
    /// The layout for a consumer that keeps a core busy itself (`busy`: planning, writing) or
    /// not (counting alarms), on this machine.
    pub(crate) fn for_consumer(busy: bool) -> Layout {
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        Layout {
            parsing: if busy && cores < 3 {
                Parsing::InLine
            } else {
                Parsing::Ahead
            },
            waiting: if busy { Waiting::Spin } else { Waiting::Sleep },
            stopping: Stopping::AfterTheBatch,
        }
    }
}

/// A file's blocks, parsed as [`Parsing`] says.
pub(crate) enum FileBlocks {
    Ahead(BackgroundParser),
    InLine(ParsedLines<ReaderLines<File>>),
}

impl BlockSource for FileBlocks {
    fn advance(&mut self) -> std::io::Result<bool> {
        match self {
            FileBlocks::Ahead(blocks) => blocks.advance(),
            FileBlocks::InLine(blocks) => blocks.advance(),
        }
    }

    fn blocks(&self) -> &[Block] {
        match self {
            FileBlocks::Ahead(blocks) => blocks.blocks(),
            FileBlocks::InLine(blocks) => blocks.blocks(),
        }
    }

    fn text(&self) -> Option<&[u8]> {
        match self {
            FileBlocks::Ahead(blocks) => blocks.text(),
            FileBlocks::InLine(blocks) => blocks.text(),
        }
    }
}

/// The files a run reads: the main program (file 0) and the programs it calls.
#[derive(Debug, Clone)]
pub(crate) struct ProgramFiles {
    main: PathBuf,
    loaded: LoadedFiles,
}

impl ProgramFiles {
    /// The path of file `file`.
    pub(crate) fn path(&self, file: FileId) -> PathBuf {
        if file == FileId(0) {
            return self.main.clone();
        }
        self.loaded
            .lock()
            .ok()
            .and_then(|l| l.iter().find(|(id, _)| *id == file).map(|(_, p)| p.clone()))
            .unwrap_or_else(|| self.main.clone())
    }
}

/// Opens `path` and starts interpreting it on a thread of its own; the file is read and parsed
/// as `parsing` says. Called programs come from `--lib` directories and the program's own
/// directory; persistent variables from the state file.
pub(crate) fn open(
    path: &Path,
    machine: &Machine,
    mut options: Options,
    setup: &MachineArgs,
    layout: Layout,
) -> Result<(Interpreted, ProgramFiles), String> {
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
    let syntax = machine.profile.syntax();
    let blocks = match layout.parsing {
        Parsing::Ahead => {
            let length = file.metadata().map_or(0, |m| m.len());
            FileBlocks::Ahead(BackgroundParser::spawn_expecting(
                file,
                FileId(0),
                syntax,
                length,
            ))
        }
        Parsing::InLine => {
            FileBlocks::InLine(ParsedLines::new(ReaderLines::new(file), FileId(0), syntax))
        }
    };
    let mut directories = setup.lib.clone();
    if let Some(own) = path.parent() {
        let own = if own.as_os_str().is_empty() {
            PathBuf::from(".")
        } else {
            own.to_path_buf()
        };
        directories.push(own);
    }
    let library = DirectoryLibrary::new(Some(path.to_path_buf()), directories, 1);
    let files = ProgramFiles {
        main: path.to_path_buf(),
        loaded: library.loaded_files(),
    };
    let mut interpreter = Interpreter::from_blocks(blocks, FileId(0), machine, options)
        .with_library(Box::new(library));
    let state = setup.state_file().map(StateFile::new);
    let mut stopping = layout.stopping;
    if let Some(state) = &state {
        interpreter = interpreter.with_persistent_variables(&state.load()?);
        stopping = Stopping::AtTheBlock;
    }
    let travel = TravelCheck::new(machine);
    Ok((
        Interpreted::spawn(interpreter, state, travel, layout.waiting, stopping),
        files,
    ))
}

/// A program opened for a command that plans it (`run`, `trace`).
pub(crate) struct Planned {
    pub(crate) machine: Machine,
    pub(crate) plan_options: vcnc::plan::PlanOptions,
    pub(crate) stream: Interpreted,
    pub(crate) files: ProgramFiles,
}

/// Opens `path` on the machine and with the options of `setup`, for a consumer that keeps a
/// core busy and shows how many blocks ran (`counts_blocks`) or not.
pub(crate) fn open_planned(
    path: &Path,
    setup: &MachineArgs,
    counts_blocks: bool,
) -> Result<Planned, String> {
    let machine = setup.machine()?;
    let options = setup.options()?;
    let plan_options = setup.plan_options()?;
    let mut layout = Layout::for_consumer(true);
    if counts_blocks {
        layout.stopping = Stopping::AtTheBlock;
    }
    let (stream, files) = open(path, &machine, options, setup, layout)?;
    Ok(Planned {
        machine,
        plan_options,
        stream,
        files,
    })
}

/// The machine state file: the persistent macro variables between runs.
pub(crate) struct StateFile {
    path: PathBuf,
}

impl StateFile {
    fn new(path: PathBuf) -> StateFile {
        StateFile { path }
    }

    /// The saved values (none when the file does not exist yet).
    fn load(&self) -> Result<PersistentVariables, String> {
        let text = match std::fs::read_to_string(&self.path) {
            Ok(text) => text,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Default::default()),
            Err(e) => {
                return Err(format!(
                    "cannot read state file {}: {e}",
                    self.path.display()
                ))
            }
        };
        let table: toml::Table = text
            .parse()
            .map_err(|e| format!("state file {}: {e}", self.path.display()))?;
        let mut values = PersistentVariables::default();
        if let Some(toml::Value::Table(variables)) = table.get("variables") {
            for (key, value) in variables {
                let number = key.trim_start_matches('#').parse::<u32>().ok();
                let value = match value {
                    toml::Value::Float(f) => Some(*f),
                    toml::Value::Integer(i) => Some(*i as f64),
                    _ => None,
                };
                if let (Some(number), Some(value)) = (number, value) {
                    values.values.insert(number, value);
                }
            }
        }
        Ok(values)
    }

    /// Writes the values to a temporary file beside the state file and renames it over the
    /// state file: a run that is killed leaves the old file or the new one, never half of one.
    fn save(&self, values: &PersistentVariables) -> std::io::Result<()> {
        let mut text = String::from(
            "# vcnc machine state: persistent macro variables (#500-#999), saved by each run.\n[variables]\n",
        );
        for (number, value) in &values.values {
            text.push_str(&format!("\"#{number}\" = {value:?}\n"));
        }
        let name = self
            .path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "state.toml".into());
        let temporary = self
            .path
            .with_file_name(format!(".{name}.{}.tmp", std::process::id()));
        {
            let mut file = File::create(&temporary)?;
            file.write_all(text.as_bytes())?;
            file.sync_all()?;
        }
        std::fs::rename(&temporary, &self.path)
    }
}

/// The interpreter's stream, run on a thread of its own and handed over a batch at a time
/// ([`Interpreter::next_batch`]), one item at a time on this side: interpreting overlaps with
/// whatever the consumer does (planning, formatting) on the other core. A fixed pool of batch
/// buffers goes round between the two threads: no allocation after the start, bounded memory.
/// Persistent variables are saved to the state file as they change (at most twice a second, so
/// that a killed run keeps what it wrote) and when the interpreter ends; dropping the stream
/// waits for that.
pub(crate) struct Interpreted {
    /// The current batch; its front is the next item.
    items: VecDeque<Result<Segment, Alarm>>,
    /// None once the interpreter thread has ended (or is told to, on drop).
    batches: Option<Receiver<Vec<Result<Segment, Alarm>>>>,
    recycle: SyncSender<Vec<Result<Segment, Alarm>>>,
    waiting: Waiting,
    blocks: Arc<AtomicU64>,
    thread: Option<JoinHandle<()>>,
}

/// Segments per batch taken from the interpreter: small, so that the pool stays in the
/// caches (see the batches of `vcnc trace`).
const BATCH: usize = 256;

/// Batch buffers in circulation between the interpreter's thread and the consumer. A consumer
/// that keeps batches (see `planned.rs`) keeps fewer than this, so that the interpreter always
/// has one to fill. Eight, not four: the planner holds two or three batches for its look-ahead,
/// and with four the interpreter, the slower thread, often found no empty buffer and slept
/// until the consumer gave one back (on the 400,000-block trace: 0.95 times the wall time, the
/// interpreter's thread no longer waits; 0.3 MiB more memory).
pub(crate) const POOL: usize = 8;

/// Least time between two saves of the state file while a program runs.
const SAVE_INTERVAL: Duration = Duration::from_millis(500);

impl Interpreted {
    fn spawn(
        mut interpreter: FileInterpreter,
        state: Option<StateFile>,
        mut travel: TravelCheck,
        waiting: Waiting,
        stopping: Stopping,
    ) -> Interpreted {
        let (sender, batches) = sync_channel::<Vec<Result<Segment, Alarm>>>(POOL);
        let (recycle, recycled) = sync_channel::<Vec<Result<Segment, Alarm>>>(POOL);
        for _ in 0..POOL {
            let _ = recycle.try_send(Vec::with_capacity(BATCH + 64));
        }
        let blocks = Arc::new(AtomicU64::new(0));
        let counter = Arc::clone(&blocks);
        let thread = std::thread::spawn(move || {
            let mut saver = StateSaver::new(&interpreter, state);
            let pool = Pool {
                sender,
                recycled,
                counter,
            };
            // Each way of stopping has a copy of the loop of its own, so that the batch check,
            // the common one, is compiled as if it were the only one.
            match stopping {
                Stopping::AtTheBlock => pool.serve(&mut interpreter, &mut saver, |i, batch| {
                    i.next_batch_checked(batch, BATCH, &mut travel)
                }),
                Stopping::AfterTheBatch => pool.serve(&mut interpreter, &mut saver, |i, batch| {
                    let more = i.next_batch(batch, BATCH);
                    travel.check_batch(batch) && more
                }),
            }
            saver.save(&interpreter);
        });
        Interpreted {
            items: VecDeque::new(),
            batches: Some(batches),
            recycle,
            waiting,
            blocks,
            thread: Some(thread),
        }
    }

    /// The next batch of items, whole, in the buffer the interpreter filled (None once the
    /// stream has ended). Give the buffer back with [`Interpreted::recycle`] when done with it:
    /// the interpreter has only [`POOL`] of them.
    pub(crate) fn next_batch(&mut self) -> Option<Vec<Result<Segment, Alarm>>> {
        if !self.items.is_empty() {
            return Some(Vec::from(std::mem::take(&mut self.items)));
        }
        let batch = receive(self.batches.as_ref()?, self.waiting);
        match batch {
            Ok(batch) => Some(batch),
            Err(_) => {
                self.batches = None;
                None
            }
        }
    }

    /// Gives a batch's buffer back to the interpreter.
    pub(crate) fn recycle(&self, batch: Vec<Result<Segment, Alarm>>) {
        let _ = self.recycle.try_send(batch);
    }

    /// Blocks the interpreter has run so far (all of them once the stream has ended).
    pub(crate) fn blocks_executed(&self) -> u64 {
        self.blocks.load(Ordering::Acquire)
    }
}

impl Iterator for Interpreted {
    type Item = Result<Segment, Alarm>;

    fn next(&mut self) -> Option<Self::Item> {
        loop {
            if let Some(item) = self.items.pop_front() {
                return Some(item);
            }
            let batch = receive(self.batches.as_ref()?, self.waiting);
            // The emptied buffer goes back; converting between Vec and VecDeque moves nothing.
            let empty = Vec::from(std::mem::take(&mut self.items));
            let _ = self.recycle.try_send(empty);
            match batch {
                Ok(batch) => self.items = VecDeque::from(batch),
                Err(_) => {
                    self.batches = None;
                    return None;
                }
            }
        }
    }
}

impl Drop for Interpreted {
    fn drop(&mut self) {
        // Without its receiver the thread's next send fails, and without the recycling sender
        // its wait for an empty buffer does: either way it ends, saving the state. (Keeping the
        // sender alive here left a thread that had filled the whole pool waiting for ever, and
        // `vcnc trace | head` hung.)
        self.batches = None;
        let (orphan, _) = sync_channel(0);
        drop(std::mem::replace(&mut self.recycle, orphan));
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

/// The interpreter's side of the pool of batch buffers.
struct Pool {
    sender: SyncSender<Vec<Result<Segment, Alarm>>>,
    recycled: Receiver<Vec<Result<Segment, Alarm>>>,
    counter: Arc<AtomicU64>,
}

impl Pool {
    /// Fills the buffers that come back with `fill` (the interpreter's next batch, travel
    /// checked; false when nothing more will come) and sends them, until the stream ends or the
    /// consumer is gone.
    fn serve(
        self,
        interpreter: &mut FileInterpreter,
        saver: &mut StateSaver,
        mut fill: impl FnMut(&mut FileInterpreter, &mut Vec<Result<Segment, Alarm>>) -> bool,
    ) {
        // A batch can come back empty (a macro loop that does not move): its buffer is kept
        // for the next one, so the pool never runs dry.
        let mut spare = None;
        while let Some(mut batch) = spare.take().or_else(|| self.recycled.recv().ok()) {
            batch.clear();
            let more = fill(interpreter, &mut batch);
            self.counter
                .store(interpreter.blocks_executed(), Ordering::Release);
            if saver.due() {
                saver.save(interpreter);
            }
            if batch.is_empty() {
                spare = Some(batch);
            } else if self.sender.send(batch).is_err() {
                break;
            }
            if !more {
                break;
            }
        }
    }
}

/// How long a consumer that spins ([`Waiting::Spin`]) spins before it sleeps: longer than the
/// interpreter takes for a batch ([`BATCH`] blocks of a CAM program take about 50 µs), so that
/// it sleeps only when the interpreter is held up (a long macro loop, a slow disk).
const SPIN: Duration = Duration::from_micros(200);

/// The next value of `channel`, waited for as `waiting` says.
fn receive<T>(channel: &Receiver<T>, waiting: Waiting) -> Result<T, RecvError> {
    if waiting == Waiting::Sleep {
        return channel.recv();
    }
    let start = Instant::now();
    loop {
        match channel.try_recv() {
            Ok(value) => return Ok(value),
            Err(TryRecvError::Disconnected) => return Err(RecvError),
            Err(TryRecvError::Empty) => {}
        }
        if start.elapsed() > SPIN {
            return channel.recv();
        }
        // Yielding, not a busy loop: on a machine whose cores all have work (the interpreter
        // sharing this core with another process, parallel runs in a CI job), the processor
        // goes to whoever can use it; on an idle core the call returns at once.
        std::thread::yield_now();
    }
}

/// Saves the persistent variables when they were written since the last save.
struct StateSaver {
    state: Option<StateFile>,
    saved_writes: u64,
    saved_at: Instant,
}

impl StateSaver {
    fn new(interpreter: &FileInterpreter, state: Option<StateFile>) -> StateSaver {
        StateSaver {
            state,
            saved_writes: interpreter.persistent_writes(),
            saved_at: Instant::now(),
        }
    }

    fn due(&self) -> bool {
        self.state.is_some() && self.saved_at.elapsed() >= SAVE_INTERVAL
    }

    fn save(&mut self, interpreter: &FileInterpreter) {
        let writes = interpreter.persistent_writes();
        if writes == self.saved_writes {
            return;
        }
        if let Some(state) = &self.state {
            if let Err(e) = state.save(&interpreter.persistent_variables()) {
                eprintln!("vcnc: cannot save state file {}: {e}", state.path.display());
            }
        }
        self.saved_writes = writes;
        self.saved_at = Instant::now();
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dropping_the_stream_early_ends_the_interpreter_thread() {
        // Many more segments than the pool of batches holds, so the thread fills every buffer
        // and waits for an empty one: `vcnc trace | head` stops reading just like this.
        let mut text = String::from("G21 G90 G94 F1000\n");
        for i in 0..20_000 {
            text.push_str(&format!("G01 X{}. Y{}.\n", i % 100, i % 37));
        }
        text.push_str("M30\n");
        let machine = Machine::default();
        let blocks = BackgroundParser::spawn(
            std::io::Cursor::new(text.into_bytes()),
            FileId(0),
            machine.profile.syntax(),
        );
        let interpreter = Interpreter::from_blocks(
            FileBlocks::Ahead(blocks),
            FileId(0),
            &machine,
            Options::default(),
        );
        let mut stream = Interpreted::spawn(
            interpreter,
            None,
            TravelCheck::new(&machine),
            Waiting::Spin,
            Stopping::AtTheBlock,
        );
        assert!(matches!(stream.next(), Some(Ok(_))));
        // Time for the thread to fill the pool and block.
        std::thread::sleep(Duration::from_millis(300));
        let (done, dropped) = sync_channel(1);
        std::thread::spawn(move || {
            drop(stream);
            let _ = done.send(());
        });
        assert!(
            dropped.recv_timeout(Duration::from_secs(10)).is_ok(),
            "dropping the stream waited for ever on the interpreter thread"
        );
    }
}
