//! The gbc register VM. It runs a verified [`isa::Module`]: macro
//! arithmetic in registers, control flow and calls itself, and every NC
//! block through the kernel ([`nc::Nc`]), whose events go to a sink the VM
//! does not know. Execution is resumable and budgeted ([`Vm::step`]) so a
//! controller's loop can drive it without blocking.
//!
//! **The block budget** (`run.max_blocks`, E6005, dialect.md §7.12) is
//! charged for every executed block and assignment, every call, M99 and
//! GOTO, and every backward jump, conditional or not. Between two charges
//! the pc only moves forward, so any module, compiled or crafted, ends
//! within `(budget + 1) × (instructions + 1)` instructions
//! (`tests/random.rs` checks that bound). The compiler emits no backward
//! conditional jump, so charging one changes no compiled program's count.
//!
//! The crate is `no_std` + `alloc`; the `std` feature (on by default)
//! only forwards to `nc` and `isa`.

#![no_std]
#![deny(missing_docs)]

extern crate alloc;

mod block;
mod interp;
mod loc_cache;
pub mod restart;
mod tier;
mod vars;

pub use interp::{Alarm, Status, Storage, VariableRefused, Vm, PROFILE};
pub use nc::{Event, Sink};
pub use tier::{Entry, Kernel, LoopState, Ran, Tier, TierStats};
