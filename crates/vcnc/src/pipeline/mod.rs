//! The threaded pipeline: a program opened, interpreted on a thread of its own, checked against
//! the machine's travel, and handed to the consumer a batch at a time, with the planner's
//! timings when the consumer wants them.
//!
//! [`Pipeline`] is the builder: the machine, the panel's options, the directories of called
//! programs, where the persistent macro variables are kept, and the [`Layout`] of the threads.
//! Opening a program (a file, any reader, text in memory) starts the interpreter's thread and
//! gives a [`Stream`]: its items one at a time (it is an iterator), a batch at a time
//! ([`Stream::next_batch`]), or a batch at a time with each item's [`Timing`](crate::plan::Timing)
//! ([`Stream::for_each_timed`]). A fixed pool of batch buffers goes round between the two
//! threads, so memory stays bounded on any program length, and no segment is copied on its way
//! from the interpreter to the consumer.
//!
//! The parts: `program.rs` (the text, its dialect, where it is parsed, the programs it calls),
//! `threads.rs` (the interpreter's thread and the pool of batches, the travel check),
//! `waiting.rs` (how the consumer waits for a batch), `store.rs` (saving the persistent
//! variables while the program runs), `planned.rs` (the batches timed by the planner on the
//! consumer's thread).
//!
//! Invariants: the stream is the interpreter's, cut by the travel check at the same item in
//! either [`Stopping`] mode; dropping the stream ends the threads. The pipeline never prints:
//! what goes wrong while it runs (a failed save) is handed back by [`Stream::finish`].
//!
//! ```
//! use vcnc::motion::Item;
//! use vcnc::pipeline::Pipeline;
//! use vcnc::plan::PlanOptions;
//! use vcnc::Machine;
//!
//! let machine = Machine::default();
//! let program = "G90 G21 G17 F3000.\nG1 X100.\nG2 X120. Y20. R20.\nM30\n";
//! let mut stream = Pipeline::new(&machine).open_text(program, "part.nc");
//! let (mut moves, mut seconds) = (0, 0.0);
//! stream.for_each_timed(PlanOptions::default(), |items, timings| {
//!     for (item, timing) in items.iter().zip(timings) {
//!         // Frames, warnings and the alarm that stops the program are items too.
//!         if let Ok(Item::Segment(segment)) = item {
//!             moves += usize::from(segment.motion().is_some());
//!         }
//!         seconds += timing.dt;
//!     }
//!     true // Go on: false would stop the stream here.
//! });
//! let finished = stream.finish();
//! assert_eq!(moves, 2);
//! assert!(seconds > 2.0, "100 mm at 50 mm/s and an arc, with the ramps");
//! assert_eq!(finished.blocks_executed, 4);
//! ```

mod balance;
mod planned;
mod program;
mod store;
mod threads;
mod waiting;

pub use balance::Threads;
pub use program::{OpenError, ProgramFiles};
pub use store::PersistentStore;
pub use threads::{BatchSource, Finished, Stream};
pub use waiting::Waiting;

use crate::interp::{FrontEnd, Kernel, Options, PersistentVariables};
use crate::machine::Machine;
use program::{MainText, Opened};
use std::io::Read;
use std::path::{Path, PathBuf};

/// An item of the stream: `Ok` a segment, a new frame or a warning, `Err` the error that ends
/// it ([`StreamItem`](crate::motion::StreamItem)).
pub type Item = crate::motion::StreamItem;

/// Where the interpreter's thread gets the program's blocks.
///
/// A parser thread pays when there is a core for it: on two cores a consumer that keeps a core
/// busy (planning, writing) and the interpreter's thread fill both, and a third thread only
/// takes turns with them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Parsing {
    /// Parsed on a thread of its own, a few hundred lines ahead.
    Ahead,
    /// Parsed on the interpreter's thread as it reads.
    InLine,
    /// Parsed ahead when the front end's reading is heavy, in line otherwise. The SINUMERIK
    /// front end reads a block in about as many instructions as it runs it, five times the
    /// consumer's work: a parser thread takes half of that to the consumer's core. The ISO
    /// front end's reading is light, and a third thread only takes turns with the other two.
    AheadWhenHeavy,
}

/// Where the interpreter's thread stops when the travel check stops the program. The stream is
/// the same either way, cut at the same item.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stopping {
    /// At the block of the move beyond the travel, as the control does: the travel is checked
    /// after every block. For a consumer that shows how many blocks ran, and whenever the
    /// persistent variables are kept (the blocks after the alarm must not write them).
    AtTheBlock,
    /// At the end of the batch that holds it: the travel is checked a batch at a time, which
    /// costs less than after every block. Only the blocks-executed count and variable writes
    /// after the alarm differ. The check stays on the interpreter's thread: on the consumer's,
    /// which takes longer over fewer instructions a block, it made the whole run slower.
    AfterTheBatch,
}

/// The threads of a run: where the program is parsed, where it is interpreted, how the
/// consumer waits, where the interpreter stops at an overtravel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Layout {
    /// Where the interpreter runs.
    pub threads: Threads,
    /// Where the program is parsed.
    pub parsing: Parsing,
    /// How the consumer waits for a batch.
    pub waiting: Waiting,
    /// Where the interpreter stops at an overtravel.
    pub stopping: Stopping,
}

impl Layout {
    /// For a consumer that keeps a core busy itself (planning, writing a trace), on this
    /// machine: the program is parsed ahead on three cores or more, on two when its reading
    /// is heavy ([`Parsing::AheadWhenHeavy`]), in line on one.
    pub fn for_busy_consumer() -> Layout {
        Layout {
            threads: Threads::Balanced,
            parsing: match cores() {
                ..=1 => Parsing::InLine,
                2 => Parsing::AheadWhenHeavy,
                _ => Parsing::Ahead,
            },
            waiting: Waiting::Adaptive,
            stopping: Stopping::AfterTheBatch,
        }
    }

    /// For a consumer that does little with each item (collecting alarms): a core is left for
    /// a parser thread, and the consumer sleeps while it waits.
    pub fn for_idle_consumer() -> Layout {
        Layout {
            threads: Threads::Balanced,
            parsing: Parsing::Ahead,
            waiting: Waiting::Sleep,
            stopping: Stopping::AfterTheBatch,
        }
    }
}

/// The processors this process may run on.
fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// How a program is to be run: the machine, the panel's options, the programs it can call,
/// its persistent variables and the threads' layout. Opening a program starts it.
pub struct Pipeline {
    machine: Machine,
    options: Options,
    layout: Layout,
    library_directories: Vec<PathBuf>,
    persistent: Option<(PersistentVariables, Box<dyn PersistentStore>)>,
}

impl Pipeline {
    /// A pipeline for `machine`, with the default options and the layout of a busy consumer
    /// ([`Layout::for_busy_consumer`]).
    pub fn new(machine: &Machine) -> Pipeline {
        Pipeline {
            machine: machine.clone(),
            options: Options::default(),
            layout: Layout::for_busy_consumer(),
            library_directories: Vec::new(),
            persistent: None,
        }
    }

    /// The panel's options. Their dialect is replaced by the one the program is detected in
    /// when it is opened.
    pub fn options(mut self, options: Options) -> Pipeline {
        self.options = options;
        self
    }

    /// The layout of the threads.
    pub fn layout(mut self, layout: Layout) -> Pipeline {
        self.layout = layout;
        self
    }

    /// Directories where called programs (M98, G65 ...) are searched, in order; a program
    /// opened from a file searches its own directory last.
    pub fn library_directories(mut self, directories: Vec<PathBuf>) -> Pipeline {
        self.library_directories = directories;
        self
    }

    /// The persistent variables (#500-#999) as a previous run left them, and where to save
    /// them: while the program runs, at most twice a second when they changed, and when the
    /// interpreter ends. The interpreter then stops at the block of an overtravel
    /// ([`Stopping::AtTheBlock`]), so that no block after it writes a variable.
    pub fn persistent(
        mut self,
        values: PersistentVariables,
        store: impl PersistentStore + 'static,
    ) -> Pipeline {
        self.persistent = Some((values, Box::new(store)));
        self
    }

    /// Opens the program file `path` and starts interpreting it. Its dialect is detected from
    /// its name and first lines. A path that is not a regular file (a pipe, a FIFO,
    /// `/dev/stdin`) is read once and whole, as [`Pipeline::open_text`] takes it.
    ///
    /// # Errors
    /// The file cannot be opened or read.
    pub fn open_path(self, path: impl AsRef<Path>) -> Result<Stream, OpenError> {
        let path = path.as_ref();
        let (head, file) = match program::open_file(path)? {
            program::OpenedFile::Regular { head, file } => (head, file),
            program::OpenedFile::Stream(text) => return Ok(self.open_text(text, path)),
        };
        let dialect = program::dialect(path, &head);
        let length = file.metadata().map_or(0, |m| m.len());
        Ok(self.start(Opened {
            main: MainText::File(path.to_path_buf()),
            name: path.to_path_buf(),
            reader: Box::new(file),
            length,
            dialect,
        }))
    }

    /// Starts interpreting the program read from `reader`, named `name` in diagnostics and
    /// dialect detection. The text is read once, as it runs: a program that jumps (GOTO, WHILE,
    /// M99) needs its whole text, which a reader cannot give again, and stops with an alarm
    /// there (use [`Pipeline::open_text`] or [`Pipeline::open_path`] for those).
    ///
    /// # Errors
    /// Reading the first lines (for the dialect) fails.
    pub fn open_reader(
        self,
        reader: impl Read + Send + 'static,
        name: impl AsRef<Path>,
    ) -> Result<Stream, OpenError> {
        let name = name.as_ref();
        let (head, reader) = program::read_head(reader, name)?;
        let dialect = program::dialect(name, &head);
        Ok(self.start(Opened {
            main: MainText::None,
            name: name.to_path_buf(),
            reader,
            length: 0,
            dialect,
        }))
    }

    /// Starts interpreting the program `text`, named `name` in diagnostics and dialect
    /// detection.
    pub fn open_text(self, text: impl AsRef<[u8]>, name: impl AsRef<Path>) -> Stream {
        let (text, name) = (text.as_ref(), name.as_ref());
        let dialect = program::dialect(name, text);
        let length = text.len() as u64;
        let text: std::sync::Arc<[u8]> = text.into();
        let reader = Box::new(std::io::Cursor::new(std::sync::Arc::clone(&text)));
        self.start(Opened {
            main: MainText::Memory(text),
            name: name.to_path_buf(),
            reader,
            length,
            dialect,
        })
    }

    /// Builds the interpreter over the opened text and starts its thread.
    fn start(self, opened: Opened) -> Stream {
        if opened.is_sinumerik(&self.machine) {
            let (front_end, machine, files) = opened.sinumerik(
                &self.machine,
                &self.options,
                self.layout.parsing,
                &self.library_directories,
            );
            let run = crate::interp::Run::new(front_end, Kernel::new(&machine));
            let started = threads::Started {
                source: run,
                store: None,
                files,
                machine,
            };
            return Stream::spawn(started, self.layout);
        }
        let mut layout = self.layout;
        let mut options = self.options;
        options.dialect = opened.dialect;
        let (interpreter, files) = opened.interpreter(
            &self.machine,
            options,
            layout.parsing,
            &self.library_directories,
        );
        let (interpreter, store) = match self.persistent {
            Some((values, store)) => {
                layout.stopping = Stopping::AtTheBlock;
                (interpreter.with_persistent_variables(&values), Some(store))
            }
            None => (interpreter, None),
        };
        let started = threads::Started {
            source: interpreter,
            store,
            files,
            machine: self.machine,
        };
        Stream::spawn(started, layout)
    }

    /// Starts the program of `front_end`, a dialect's block sequencer, on the kernel of this
    /// pipeline's machine, named `name` in diagnostics: the same threads, travel check and
    /// timings as an ISO program gets. (The panel's options and the persistent variables are
    /// the ISO interpreter's; a front end keeps its own.)
    pub fn open_front_end<F: FrontEnd + Send + 'static>(
        self,
        front_end: F,
        name: impl AsRef<Path>,
    ) -> Stream {
        let run = crate::interp::Run::new(front_end, Kernel::new(&self.machine));
        let started = threads::Started {
            source: run,
            store: None,
            files: ProgramFiles::new(name.as_ref().to_path_buf(), Default::default()),
            machine: self.machine,
        };
        Stream::spawn(started, self.layout)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_busy_consumer_on_two_cores_parses_ahead_only_heavy_reading() {
        let layout = Layout::for_busy_consumer();
        assert_eq!(layout.parsing == Parsing::AheadWhenHeavy, cores() == 2);
        assert_eq!(layout.parsing == Parsing::Ahead, cores() > 2);
        assert_eq!(layout.waiting, Waiting::Adaptive);
        assert_eq!(Layout::for_idle_consumer().waiting, Waiting::Sleep);
    }
}
