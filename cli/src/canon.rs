//! The canon on standard output, as `gbvm` writes it.
//!
//! Writing a long program's canon (its lines formatted and handed to the
//! system) is about a fifth of `gbvm run`'s time. [`on_writer_thread`]
//! does it on a second thread: the machine's events go over in batches, in
//! order, and the text is the same byte for byte (one writer, one order).

use nc::{Event, Sink};
use std::io::{BufWriter, Write};
use std::sync::mpsc::{Receiver, Sender, SyncSender};

/// The canon written to `out`: one line per event, nothing after an
/// `ALARM` line, and the first write error kept (the run goes on; its
/// result is then the error).
pub struct Canon<W: Write> {
    out: W,
    error: Option<std::io::Error>,
    /// An `ALARM` line has been printed: it is the last line of the run.
    alarmed: bool,
}

impl<W: Write> Canon<W> {
    pub fn new(out: W) -> Self {
        Canon {
            out,
            error: None,
            alarmed: false,
        }
    }

    /// Writes `text` unless an earlier write failed.
    pub fn write(&mut self, text: &str) {
        if self.error.is_none() {
            if let Err(err) = self.out.write_all(text.as_bytes()) {
                self.error = Some(err);
            }
        }
    }

    /// Whether a write has failed.
    pub fn failed(&self) -> bool {
        self.error.is_some()
    }

    /// Flushes, and gives the first write error.
    pub fn finish(mut self) -> Option<std::io::Error> {
        if let (None, Err(e)) = (&self.error, self.out.flush()) {
            self.error = Some(e);
        }
        self.error
    }
}

impl<W: Write> Sink for Canon<W> {
    fn emit(&mut self, e: Event) {
        if self.alarmed {
            return;
        }
        self.alarmed = matches!(e, Event::Alarm { .. });
        if self.error.is_some() {
            return;
        }
        // Moves (most of the canon) as bytes; the rest through Display.
        let mut line = nc::base::canon_line::LineBuf::default();
        let written = match e.write_fast(&mut line) {
            true => self
                .out
                .write_all(line.as_bytes())
                .and_then(|()| self.out.write_all(b"\n")),
            false => writeln!(self.out, "{e}"),
        };
        if let Err(err) = written {
            self.error = Some(err);
        }
    }
}

/// Events per batch: the hand-over's cost spread over many, few enough
/// that the batches in flight stay small (a few hundred kilobytes).
const BATCH: usize = 2048;

/// The canon's output buffer: a write call per 64 KiB rather than per
/// 8 KiB (the standard buffer); 66 calls instead of 506 for 200 000
/// lines.
const OUT_BUFFER: usize = 1 << 16;

/// Batches sent and not yet written, at most: the machine waits for the
/// writer beyond that, so memory stays bounded whatever the run's length.
const IN_FLIGHT: usize = 2;

/// The sink the machine runs into: events gathered into batches for the
/// writer thread, their vectors reused once written.
struct Handoff {
    batch: Vec<Event>,
    full: SyncSender<Vec<Event>>,
    empty: Receiver<Vec<Event>>,
}

impl Handoff {
    fn send(&mut self) {
        let next = self
            .empty
            .try_recv()
            .unwrap_or_else(|_| Vec::with_capacity(BATCH));
        let batch = std::mem::replace(&mut self.batch, next);
        // (A writer that is gone has failed; its error is reported.)
        let _ = self.full.send(batch);
    }
}

impl Sink for Handoff {
    fn emit(&mut self, e: Event) {
        self.batch.push(e);
        if self.batch.len() == BATCH {
            self.send();
        }
    }
}

/// Runs `run` with a sink whose events a second thread writes to standard
/// output as the canon; `run`'s result and the first write error, once
/// every event is written. Without a second thread, the canon is written
/// on this one.
pub fn on_writer_thread<R>(run: impl FnOnce(&mut dyn Sink) -> R) -> (R, Option<std::io::Error>) {
    std::thread::scope(|s| {
        let (full, batches) = std::sync::mpsc::sync_channel(IN_FLIGHT);
        let (spent, empty) = std::sync::mpsc::channel();
        let writer = std::thread::Builder::new()
            .name("gbvm-canon".into())
            .spawn_scoped(s, move || write_batches(batches, spent));
        let Ok(writer) = writer else {
            let mut canon = Canon::new(stdout_buffered());
            let result = run(&mut canon);
            return (result, canon.finish());
        };
        let mut handoff = Handoff {
            batch: Vec::with_capacity(BATCH),
            full,
            empty,
        };
        let result = run(&mut handoff);
        handoff.send();
        // (The channel closes: the writer finishes the last batch.)
        drop(handoff);
        let error = writer
            .join()
            .unwrap_or_else(|p| std::panic::resume_unwind(p));
        (result, error)
    })
}

/// Standard output through a buffer of [`OUT_BUFFER`] bytes.
fn stdout_buffered() -> BufWriter<std::io::StdoutLock<'static>> {
    BufWriter::with_capacity(OUT_BUFFER, std::io::stdout().lock())
}

/// The writer thread: every batch in turn into the canon, each vector
/// handed back empty.
fn write_batches(
    batches: Receiver<Vec<Event>>,
    spent: Sender<Vec<Event>>,
) -> Option<std::io::Error> {
    let mut canon = Canon::new(stdout_buffered());
    for mut batch in batches {
        batch.drain(..).for_each(|e| canon.emit(e));
        let _ = spent.send(batch);
    }
    canon.finish()
}
