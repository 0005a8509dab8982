//! The real-time interpolation runtime of gbc.
//!
//! A compiled program runs in the VM, whose canon events (canon.md) become
//! [`command::Command`]s in machine coordinates; the [`planner`] queues
//! them with a look-ahead of at least 1024 blocks and 200 ms of motion and
//! keeps, for every move, the speed envelope that lets the machine stop on
//! the last planned point; the interpolator ([`interpolate::Engine`])
//! advances the machine by one fixed period per call — linear acceleration
//! before interpolation, exact curves, G00 dog-legs, spindle-synchronised
//! threads, a simulated spindle — and returns the axis set points.
//!
//! The embedding API for controllers is [`controller::Controller`]: load a
//! verified `.gbc`, tick it once per period, feed it overrides and
//! signals, answer its PLC functions through [`plc::Plc`]. [`split`]
//! divides it into an interpreter thread and a lock-free real-time half.
//! `runtime/examples/controller.rs` runs a program tick by tick.
//!
//! The crate is `no_std` + `alloc`, the controller included, and so are
//! the kernel (`nc`), the VM and the module format (`isa`) under it; CI
//! builds them for a bare-metal target (`thumbv7em-none-eabihf`). The
//! `std` feature (on by default) only forwards to those crates, where it
//! adds the TOML reader of the machine file.
//!
//! Modules: [`planner`] (queue, corner speeds, backward pass), [`profile`]
//! (the discrete braking limit shared by planner and interpolator),
//! [`geom`] (exact lines, arcs, ellipses, parabolas), [`interpolate`] (the
//! period loop), [`follow`] (axes following thread chains), [`spindle`],
//! [`smooth`] (optional jerk limiting),
//! [`plc`], [`command`], [`config`], [`counts`] (set points in whole
//! steps of the resolution), and the outputs [`trace`], [`plot`]
//! (with [`simplify`]), [`stats`], and the motion certificate of
//! `gbvm check`, [`certify`].
//!
//! Determinism: all arithmetic is IEEE double in a fixed order and every
//! transcendental function comes from `libm`, so identical input and
//! configuration give bit-identical set points on every host.

#![no_std]
#![deny(missing_docs)]

extern crate alloc;
#[cfg(feature = "std")]
extern crate std;

mod backlash;
pub mod certify;
pub mod command;
pub mod config;
pub mod counts;
pub mod follow;
pub mod geom;
pub mod interpolate;
mod machine_lock;
pub mod math;
pub mod pitch;
pub mod planner;
pub mod plc;
pub mod plot;
pub mod polar;
pub mod profile;
pub mod simplify;
pub mod smooth;
pub mod spindle;
pub mod stats;
pub mod trace;

pub mod controller;
mod runahead;
pub mod split;
pub mod translate;

pub use command::{Command, Tag};
pub use config::{Config, RapidOverride};
pub use counts::Counts;
pub use interpolate::{
    Engine, JogRate, Manual, ManualAxis, ManualRefused, Motion, RoomWarning, RunState, SetPoint,
};
pub use plc::{AutoAck, Plc, PlcFunction};

pub use controller::{
    AlarmInfo, Controller, LoadError, MeasureRefused, MeasuredAxis, RestartRefused, SelectRefused,
};
pub use nc::active::{ActiveCodes, GROUPS as ACTIVE_GROUPS};
pub use nc::counters::{Counters, Parts, MAX_PARTS};
pub use nc::machine::Xz;
pub use nc::machine_check::BadKey;
pub use nc::offset_page::{OffsetLengths, WorkOffset};
pub use nc::tool_life::{Group as LifeGroup, LifeUnit};
pub use split::{Interpreter, Realtime};
pub use vm::restart::{RestartAt, RestartError, Restarted, Target};
pub use vm::VariableRefused;
