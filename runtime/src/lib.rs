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
//! The embedding API for controllers is [`controller::Controller`] (the
//! `std` feature, on by default): load a verified `.gbc`, tick it once per
//! period, feed it overrides and signals, answer its PLC functions through
//! [`plc::Plc`]. `runtime/examples/controller.rs` runs a program tick by
//! tick.
//!
//! Without `std`, the crate is `no_std` + `alloc`: planner, interpolator,
//! spindle, trace, plot and statistics work on [`command::Command`]s that
//! the host builds itself. The controller needs `nc` (the canon events and
//! the kernel) and `vm`, which use `std` today; making them `no_std` would
//! take `alloc` collections in place of `std`'s, `core::fmt` for the
//! messages, `libm` for the kernel's float functions and a TOML-free
//! `Machine` constructor (the TOML reader staying behind `std`).
//!
//! Modules: [`planner`] (queue, corner speeds, backward pass), [`profile`]
//! (the discrete braking limit shared by planner and interpolator),
//! [`geom`] (exact lines, arcs, ellipses, parabolas), [`interpolate`] (the
//! period loop), [`spindle`], [`smooth`] (optional jerk limiting),
//! [`plc`], [`command`], [`config`], and the outputs [`trace`], [`plot`],
//! [`stats`].
//!
//! Determinism: all arithmetic is IEEE double in a fixed order and every
//! transcendental function comes from `libm`, so identical input and
//! configuration give bit-identical set points on every host.

#![no_std]

extern crate alloc;
#[cfg(feature = "std")]
extern crate std;

pub mod command;
pub mod config;
pub mod geom;
pub mod interpolate;
pub mod math;
pub mod planner;
pub mod plc;
pub mod plot;
pub mod profile;
pub mod smooth;
pub mod spindle;
pub mod stats;
pub mod trace;

#[cfg(feature = "std")]
pub mod controller;
#[cfg(feature = "std")]
pub mod translate;

pub use command::{Command, Tag};
pub use config::{Config, RapidOverride};
pub use interpolate::{Engine, Motion, RunState, SetPoint};
pub use plc::{AutoAck, Plc, PlcFunction};

#[cfg(feature = "std")]
pub use controller::{AlarmInfo, Controller, LoadError};
