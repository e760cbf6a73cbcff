//! The ISO (FANUC-family) front end: lines of text into blocks of words.
//!
//! Reads what the controls of the manuals accept: `%` tape marks, `O`/`:` program numbers, `N`
//! sequence numbers, `( )` comments (nested parentheses are tolerated, as real programs have
//! them), `//` line comments where the profile uses them (Syntec), `/` and `/n` block skip, `;`
//! or the line end as end of block, spaces anywhere between words and inside a word, addresses in
//! upper or lower case, and extended addresses such as `F2=` and `S1=`.
//!
//! Custom Macro B (`#` variables, `[ ]` expressions, IF/WHILE/GOTO) is read into statements
//! and postfix expressions (`parser/macros.rs`). A Syntec program whose first line is `%@MACRO`
//! is read statement by statement instead of line by line ([`parse_program`]), with the
//! structured statements of `parser/structured.rs` paired by [`structure`].
//!
//! This module never decides what a word means: `X20` stays 20 with no decimal point.

mod parser;
mod program;
pub mod structure;

pub(crate) use parser::parse_plain_line_in;
pub use parser::{parse_line, SyntaxOptions};
pub use program::{parse_program, parse_program_piece, ProgramBlocks};

/// The most words (and macro statements) one block may hold: far beyond any real block (a G65
/// call with argument specification II has under 40), and a bound on what a line of megabytes
/// costs to read.
pub(crate) const MAX_WORDS_PER_BLOCK: usize = 512;

/// A reusable set of blocks: the blocks of one line, overwritten line after line so that reading
/// does not allocate once the buffers have grown.
#[derive(Debug, Default)]
pub struct LineBlocks {
    blocks: Vec<super::Block>,
    len: usize,
    /// The first block holds nothing but what the reader of plain lines writes (its span and
    /// words; everything else as [`Block::clear`](super::Block::clear) leaves it), so that the
    /// next plain line needs only its words emptied ([`LineBlocks::push_plain`]).
    first_is_plain: bool,
}

impl LineBlocks {
    /// An empty set.
    pub fn new() -> LineBlocks {
        LineBlocks::default()
    }

    /// An empty set with room for one block of up to `words` words: what most lines need, so
    /// that a pool of these made up front does not allocate while lines are read.
    pub fn with_room(words: usize) -> LineBlocks {
        let mut block = super::Block::new();
        block.words.reserve(words);
        LineBlocks {
            blocks: vec![block],
            len: 0,
            first_is_plain: false,
        }
    }

    /// The blocks of the last line read.
    pub fn as_slice(&self) -> &[super::Block] {
        // `len` never exceeds the blocks made; no panic path in the interpreter's loop either way.
        self.blocks.get(..self.len).unwrap_or_default()
    }

    /// Forgets the blocks, keeping their allocations.
    pub(crate) fn reset(&mut self) {
        self.len = 0;
    }

    /// A cleared block at the end of the set.
    #[inline(always)]
    pub(crate) fn push(&mut self) -> &mut super::Block {
        // The block may be filled with anything: it is no longer known to be plain.
        self.first_is_plain = false;
        if self.len == self.blocks.len() {
            self.add_block();
        } else {
            self.blocks[self.len].clear();
        }
        self.len += 1;
        &mut self.blocks[self.len - 1]
    }

    /// The first block of an empty set, for the reader of plain lines: cleared, except that its
    /// span is left as it was (the reader writes all of it). After the line before, a plain one
    /// too as nearly always, only its words need emptying.
    #[inline(always)]
    pub(crate) fn push_plain(&mut self) -> &mut super::Block {
        debug_assert_eq!(self.len, 0, "a plain line is the only block of its set");
        if self.first_is_plain && !self.blocks.is_empty() {
            self.len = 1;
            let block = &mut self.blocks[0];
            block.words.clear();
            return block;
        }
        self.push_first_plain()
    }

    /// [`LineBlocks::push_plain`] after a line that was not plain: the block cleared in full.
    #[cold]
    fn push_first_plain(&mut self) -> &mut super::Block {
        self.len = 0;
        self.push();
        self.first_is_plain = true;
        &mut self.blocks[0]
    }

    /// A new block for a line with more blocks than any before it: rare once the set has been
    /// used, so kept out of the way of the reader's loop.
    #[cold]
    fn add_block(&mut self) {
        self.blocks.push(super::Block::new());
    }

    /// Drops the last block (it turned out to be empty).
    pub(crate) fn pop(&mut self) {
        self.len = self.len.saturating_sub(1);
    }
}
