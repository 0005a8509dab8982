//! Long straight programs, compiled a chunk at a time.
//!
//! CAM output is mostly one long program of plain blocks: moves, feeds,
//! speeds, M codes; no macro statement, no computed word, no call, no
//! G70–G73 cycle and no `/`. No block of such a program needs another to
//! be built, emitted or dry-run, so each chunk of lines is parsed and
//! dry-run (the front end, on a thread of its own), then built into IR,
//! validated and emitted (the back end), and dropped; the front end works
//! a chunk or two ahead. `gbcc` then holds the source, the
//! module, and a few chunks' trees and IR (docs/manual.md, "A long
//! program, a chunk at a time").
//!
//! The passes are the whole-file path's, given one chunk at a time, so the
//! module and the diagnostics are the ones it gives (tests compare them
//! byte for byte). A program found not to be plain on the way, or with an
//! error, is left to the whole-file path, which then compiles it from the
//! start: its diagnostics come out exactly as they always do.

use crate::build::{self, Builder, FileDiag, ProgBuild, ProgEnd};
use crate::check::ChunkedRun;
use crate::emit::{Emitter, OpenProgram, Room};
use crate::link::{self, Program, Unit};
use crate::{words, Compiled, Options};
use grammar::ast::{Addr, Ast, Body, Line, Value};
use grammar::{SourceFile, Span};
use isa::block::Records;
use std::sync::mpsc::{Receiver, Sender, SyncSender};
use std::sync::Arc;

/// Compiles `bytes` a chunk of `opts.chunk_bytes` at a time; `None` when
/// the program must go the whole-file way (short, not plain, or faulty).
pub fn compile(name: &str, bytes: &Arc<[u8]>, opts: &Options) -> Option<Compiled> {
    let table = &opts.machine.r#macro.g_code_macros;
    // (A G code may call a macro when the table names one; `-D` presets
    // are operations before the first block.)
    let wanted =
        bytes.len() > opts.chunk_bytes && opts.defines.is_empty() && table.iter().all(|&n| n == 0);
    if !wanted {
        return None;
    }
    let front = Front {
        name,
        bytes,
        opts,
        parse: Vec::new(),
        split: Vec::new(),
        shape: Shape::default(),
        dry_run: ChunkedRun::new(&opts.machine),
        hash: 0,
    };
    // The front end (parse, dry run) runs a chunk ahead of the back end
    // (build, emit), on a thread of its own; two chunks wait between them
    // at most. The back end hands each chunk's tree back to be freed
    // where it was made: a block freed by another thread goes through
    // the allocator's shared list, and the two threads contended for it
    // (about a tenth of the back end's time on 200 000 G1 blocks).
    let (front, back, files) = std::thread::scope(|s| {
        let (to_back, chunks) = std::sync::mpsc::sync_channel(2);
        let (to_front, spent) = std::sync::mpsc::channel();
        let front = std::thread::Builder::new()
            .name("gbc-front".into())
            .spawn_scoped(s, move || front.run(to_back, spent))
            .ok()?;
        // (The line table is built while the first chunk is parsed.)
        let files = vec![SourceFile::new(name.to_string(), bytes.clone())];
        let back = Back::new(&files, opts, to_front).run(chunks);
        // (A panic in the front end is the caller's, as in one thread.)
        let front = front
            .join()
            .unwrap_or_else(|p| std::panic::resume_unwind(p));
        Some((front?, back?, files))
    })?;
    let (mut module, records, build, emit) = back;
    module.files = vec![isa::SourceFileInfo {
        name: name.to_string(),
        hash: front.hash,
    }];
    let found = Found {
        parse: front.parse,
        split: front.split,
        build,
        emit,
        dry_run: front.dry_run.finish(),
    };
    // (An error, or a module that does not verify: the whole-file path
    // reports it. The back end walked the records as it emitted them:
    // the verifier does not walk them again.)
    if found.any_error() || module.verify_with(records).is_err() {
        return None;
    }
    Some(Compiled {
        module: Some(module),
        files,
        diags: found.into_diags(),
    })
}

/// The diagnostics, kept apart by pass: the whole-file path gives those of
/// every pass in turn, and so must this.
struct Found {
    parse: Vec<FileDiag>,
    split: Vec<FileDiag>,
    build: Vec<FileDiag>,
    emit: Vec<FileDiag>,
    dry_run: Vec<FileDiag>,
}

impl Found {
    fn into_diags(self) -> Vec<FileDiag> {
        let Found {
            mut parse,
            split,
            build,
            emit,
            dry_run,
        } = self;
        for more in [split, build, emit, dry_run] {
            parse.extend(more);
        }
        parse
    }

    fn any_error(&self) -> bool {
        [
            &self.parse,
            &self.split,
            &self.build,
            &self.emit,
            &self.dry_run,
        ]
        .iter()
        .any(|ds| any_error(ds))
    }
}

fn any_error(diags: &[FileDiag]) -> bool {
    diags.iter().any(|(_, d)| d.is_error())
}

/// What the chunks seen so far say of the program as a whole.
#[derive(Default)]
struct Shape {
    /// Its number and O line (from the first chunk).
    number: u32,
    span: Span,
    numbered: bool,
    /// A block with words has been seen: an O line after it would start
    /// a second program.
    any_block: bool,
    /// The last block, and whether the run cannot get past it (build's
    /// W101 rule): the last block with words ends the program, or an
    /// earlier one did (a plain program has no jumps, so nothing after
    /// an M02/M30 runs).
    end: Option<ProgEnd>,
    /// An M02/M30 has been seen.
    ended: bool,
}

/// A chunk on its way from the front end to the back end.
struct Chunk {
    unit: Unit,
    prog: Program,
    first: bool,
    /// How the program ends, with its last chunk.
    end: Option<ProgEnd>,
    /// How many leading blocks the dry run ran ([`ChunkedRun::chunk`]).
    ran_ahead: usize,
}

/// Parses the chunks, checks that they are plain and dry-runs them.
struct Front<'a> {
    name: &'a str,
    bytes: &'a Arc<[u8]>,
    opts: &'a Options,
    parse: Vec<FileDiag>,
    split: Vec<FileDiag>,
    shape: Shape,
    dry_run: ChunkedRun,
    /// The source's checksum, once every chunk went.
    hash: u32,
}

impl Front<'_> {
    /// Every chunk in turn to the back end; itself when all went, or
    /// `None` as soon as the program turns out not to be for this path
    /// (or the back end stops taking chunks).
    fn run(mut self, to_back: SyncSender<Chunk>, spent: Receiver<Spent>) -> Option<Self> {
        let mut start = 0;
        while start < self.bytes.len() {
            // (Freed here, on the thread that made them.)
            spent.try_iter().for_each(drop);
            let first = start == 0;
            let (unit, next) = self.parse(start, first)?;
            // A file of one chunk is the whole-file path's.
            let last = next >= self.bytes.len();
            if first && last {
                return None;
            }
            let prog = self.program(&unit, first)?;
            let ran_ahead = self.dry_run.chunk(&unit, &prog);
            if self.dry_run.failed() {
                return None;
            }
            let end = self.shape.end.unwrap_or(ProgEnd {
                span: self.shape.span,
                explicit: false,
            });
            let end = last.then_some(end);
            let chunk = Chunk {
                unit,
                prog,
                first,
                end,
                ran_ahead,
            };
            to_back.send(chunk).ok()?;
            start = next;
        }
        // The source's checksum while the back end finishes the last
        // chunks, then the last trees, as it finishes with them (it then
        // closes the channel).
        drop(to_back);
        self.hash = crc32fast::hash(self.bytes);
        spent.iter().for_each(drop);
        Some(self)
    }

    /// Parses the chunk from `start`: its unit, and where the next starts.
    fn parse(&mut self, start: usize, first: bool) -> Option<(Unit, usize)> {
        let len = self.opts.chunk_bytes;
        let (mut ast, mut found, mut next) = grammar::parse_lines(self.bytes, start, len);
        // The first chunk runs on to a block with words: the O line, if
        // any, stands before it (comment lines may lead into it).
        while first && next < self.bytes.len() && !ast.lines.iter().any(has_words) {
            let (more, also, after) = grammar::parse_lines(self.bytes, next, len);
            ast.lines.extend(more.lines);
            found.extend(also);
            next = after;
        }
        // (Only the chunk's own diagnostics are looked at: the earlier
        // ones had no error, or the path was left.)
        if found.iter().any(|d| d.is_error()) || !self.plain(&ast, first) {
            return None;
        }
        // No `data_setting::prepare`, which the whole-file path runs: it
        // rewrites only blocks after a G10, and a plain chunk has none (a
        // G word that rounds to G10 is G10 itself, the lexer allowing a G
        // one decimal, and `plain_word` refuses it).
        self.parse.extend(found.into_iter().map(|d| (0, d)));
        let unit = Unit {
            name: self.name.to_string(),
            bytes: self.bytes.clone(),
            ast,
        };
        Some((unit, next))
    }

    /// Whether a chunk's lines keep the program plain, noting its shape.
    fn plain(&mut self, ast: &Ast, first: bool) -> bool {
        for line in &ast.lines {
            match line {
                Line::Percent(_) => {}
                // One O line, in the first chunk, before any block: one
                // program.
                Line::ProgramStart(p) => {
                    if !first || self.shape.any_block || self.shape.numbered {
                        return false;
                    }
                    (self.shape.number, self.shape.span) = (p.number, p.span);
                    self.shape.numbered = true;
                }
                Line::Block(b) => {
                    let Body::Words(ws) = &b.body else {
                        return false;
                    };
                    if b.delete.is_some() {
                        return false;
                    }
                    let Some(any_m) = plain_words(ws) else {
                        return false;
                    };
                    self.shape.any_block |= !ws.is_empty();
                    // (Only an M word ends the program: a block without
                    // one is not looked at again.)
                    let ends = match any_m {
                        true => build::block_ends(b),
                        false => (!ws.is_empty()).then_some(false),
                    };
                    let explicit = match ends {
                        Some(ends) => {
                            self.shape.ended |= ends;
                            self.shape.ended
                        }
                        None => self.shape.end.is_some_and(|e| e.explicit),
                    };
                    self.shape.end = Some(ProgEnd {
                        span: b.span,
                        explicit,
                    });
                }
            }
        }
        true
    }

    /// The chunk's blocks as the program's; for the first chunk, the
    /// program as `link::split` finds it (with its W117).
    fn program(&mut self, unit: &Unit, first: bool) -> Option<Program> {
        if first {
            let mut programs = link::split(0, unit, &mut self.split);
            if any_error(&self.split) {
                return None;
            }
            return match programs.len() {
                1 => programs.pop(),
                _ => None,
            };
        }
        let blocks = (unit.ast.lines.iter().enumerate())
            .filter(|(_, l)| matches!(l, Line::Block(_)))
            .map(|(i, _)| i)
            .collect();
        Some(Program {
            number: self.shape.number,
            unit: 0,
            blocks,
            span: self.shape.span,
        })
    }
}

/// Builds the chunks into IR, validates and emits them.
struct Back<'a> {
    opts: &'a Options,
    builder: Builder<'a>,
    emitter: Emitter<'a>,
    program: OpenProgram,
    prog_build: ProgBuild,
    build: Vec<FileDiag>,
    /// The chunks built, back to the front end.
    spent: Sender<Spent>,
}

/// A chunk's tree and block list, built and emitted.
type Spent = ([Unit; 1], [Program; 1]);

/// What the back end made: the module without its `blocks`, the records
/// that are, and the diagnostics of build and emit.
type BackEnd = (isa::Module, Records, Vec<FileDiag>, Vec<FileDiag>);

impl<'a> Back<'a> {
    fn new(files: &'a [SourceFile], opts: &'a Options, spent: Sender<Spent>) -> Self {
        let bytes = files.first().map_or(0, |f| f.bytes().len());
        let emitter = Emitter::new(files, &opts.machine, room(bytes));
        Back {
            opts,
            builder: Builder::new(&[], &[], &opts.machine, opts.optimize),
            program: emitter.open_program(),
            emitter,
            prog_build: ProgBuild::default(),
            build: Vec::new(),
            spent,
        }
    }

    /// Takes the chunks until the last: the module (its `blocks` in the
    /// records, walked), and the diagnostics of build and emit; `None` on
    /// an error, or when the front end stopped before the last chunk.
    fn run(mut self, chunks: Receiver<Chunk>) -> Option<BackEnd> {
        let number = loop {
            let chunk = chunks.recv().ok()?;
            let number = chunk.prog.number;
            let last = chunk.end.is_some();
            self.chunk(chunk)?;
            if last {
                break number;
            }
        };
        self.emitter.close_program(number, self.program);
        let (module, records, emit) = self.emitter.finish_walked();
        Some((module, records, self.build, emit))
    }

    /// One chunk, built, validated and emitted (with the program's end
    /// after the last); `None` on an error.
    fn chunk(&mut self, chunk: Chunk) -> Option<()> {
        let machine = &self.opts.machine;
        let units = [chunk.unit];
        let programs = [chunk.prog];
        let builder = std::mem::replace(&mut self.builder, Builder::new(&[], &[], machine, false));
        let mut b = builder.rebind(&units, &programs, machine);
        if chunk.first {
            b.start_chunks(&programs[0]);
        }
        let mut parts = vec![b.build_chunk(&programs[0], &mut self.prog_build, chunk.ran_ahead)];
        if let Some(end) = chunk.end {
            let pb = std::mem::take(&mut self.prog_build);
            parts.push(b.end_chunks(&programs[0], pb, end));
        }
        let mut found = b.take_diags();
        if any_error(&found) {
            return None;
        }
        self.build.append(&mut found);
        self.emitter.sync_strings(&b.module().strings);
        for part in &mut parts {
            if self.opts.resolve {
                crate::resolve::function(part);
            }
        }
        for part in &parts {
            crate::ir::validate::validate_part(b.module(), part).ok()?;
            self.emitter.part(part, &mut self.program);
        }
        // The records walked here, while the front end works on: the
        // verifier, which runs once both are done, need not walk them.
        self.emitter.walk_records()?;
        self.builder = b.rebind(&[], &[], machine);
        // (A front end that has stopped frees nothing more: dropped here.)
        let _ = self.spent.send((units, programs));
        Some(())
    }
}

/// Whether a block's words keep the program plain: literal words
/// ([`plain_word`]), none that may call or return ([`words::may_call`]),
/// no G70–G73 cycle ([`crate::profile::names_cycle`]); and if so, whether
/// one is an M word. One pass over the words, where each test took one:
/// only a G or an M word can call, and only a G word names a cycle.
fn plain_words(ws: &[grammar::ast::Word]) -> Option<bool> {
    let mut any_m = false;
    for w in ws {
        let one = std::slice::from_ref(w);
        let plain = match w.addr {
            Addr::Letter('G') => {
                plain_word(w) && !words::may_call(one) && !crate::profile::names_cycle(one)
            }
            Addr::Letter('M') => {
                any_m = true;
                plain_word(w) && !words::may_call(one)
            }
            _ => plain_word(w),
        };
        if !plain {
            return None;
        }
    }
    Some(any_m)
}

/// A literal word that is not G10/G11 (data setting spans blocks; its
/// programs take the whole-file path).
fn plain_word(w: &grammar::ast::Word) -> bool {
    match &w.value {
        Value::Number(n) => {
            let data_setting = (10.0..12.0).contains(&n.value);
            !(w.addr == Addr::Letter('G') && data_setting)
        }
        Value::Expr(_) => false,
    }
}

fn has_words(line: &Line) -> bool {
    match line {
        Line::Block(b) => !matches!(&b.body, Body::Words(ws) if ws.is_empty()),
        _ => false,
    }
}

/// Room for the module of a plain program of `bytes` bytes. The tables
/// are only reserved, not written: a bound costs no memory until it is
/// used, and a table that grows copies itself. A plain block takes a line
/// of over 8 bytes (`G1X1Z1` and its line end) and one instruction, and
/// its record is shorter than its text.
fn room(bytes: usize) -> Room {
    Room {
        constants: 0,
        instrs: bytes / 8,
        records: bytes,
    }
}
