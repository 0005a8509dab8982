//! The NC kernel of gbc: the machine configuration, the modal state and
//! the meaning of one block (dialect.md §2–§6, canon.md). The compiler
//! uses it to check and pre-run static programs; the VM executes every
//! block through it, so both share one implementation.
//!
//! The crate is `no_std` + `alloc`, so the kernel runs on an embedded
//! controller; every float function comes from `libm`, so a host build and
//! an embedded build compute the same bits. The `std` feature (on by
//! default) adds [`Machine::from_toml`].
//!
//! # Layers
//!
//! The kernel is five layers; each module imports only from its own layer
//! and the layers below it (the test `nc/tests/layers.rs` reads the sources
//! and fails on an import that points up or a circle across layers):
//!
//! 1. [`base`] — points and units, the G-code table with one typed enum
//!    per modal group, the M-code table (`base::mcode`: the codes the
//!    kernel gives a meaning to, their class and canon group), words, the
//!    machine configuration, events, the geometry element, the alarms. (Rust's own crate is called `core`,
//!    hence the name.)
//! 2. [`block`] — parsing and checking one block's words into a
//!    [`block::Parsed`] block; macro arithmetic on word values.
//! 3. [`modal`] — the modal state, one typed field per group, and how a
//!    block changes it.
//! 4. [`plan`] — pure geometry: corners, angle programming, conics, the
//!    single cycles, grooving, drilling and tapping, threading passes and
//!    run-outs, the roughing cycles and the reading of their ns…nf
//!    profile (`plan::profile`), nose-radius offsets and corners.
//!    Arguments and a read-only context (`plan::reader::Reader`: machine,
//!    units, position, motion in force) in, path elements (legs) out; no
//!    sink and no kernel.
//! 5. [`exec`] — the stateful executor [`Nc`]: position, variables, tool
//!    life, data setting, stroke check, the contour and compensation queue,
//!    the cycles, and the order of events.
//!
//! The other crates use the paths re-exported below (`nc::machine`,
//! `nc::state`, …), so they do not depend on where a module sits.

#![no_std]

extern crate alloc;
#[cfg(feature = "std")]
extern crate std;

pub mod base;
pub mod block;
pub mod exec;
pub mod modal;
pub mod plan;

pub use base::{
    error, event, gcode, geom, machine, machine_check, mcode, offset_page, plc, point, thread_room,
    words,
};
pub use block::value;
pub use exec::{
    active, comp, compound, contour, counters, cycles, data_setting, measure, params, state,
    stroke, sysvar, tool_life,
};

pub use error::NcError;
pub use event::Event;
pub use exec::active::ActiveCodes;
pub use exec::{Discard, Nc, Outcome, Placed, Sink, WordCall, RUNNING};
pub use machine::Machine;
