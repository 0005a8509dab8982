//! The NC kernel of gbc: the machine configuration, the modal state and
//! the meaning of one block (dialect.md §2–§6, canon.md). The compiler
//! uses it to check and pre-run static programs; the VM executes every
//! block through it, so both share one implementation.
//!
//! The crate is `no_std` + `alloc`, so the kernel runs on an embedded
//! controller; every float function comes from `libm`, so a host build and
//! an embedded build compute the same bits. The `std` feature (on by
//! default) adds [`Machine::from_toml`].

#![no_std]

extern crate alloc;
#[cfg(feature = "std")]
extern crate std;

pub mod block;
mod caxis;
pub mod comp;
pub mod compound;
pub mod contour;
pub mod cycles;
pub mod data_setting;
pub mod error;
pub mod event;
pub mod exec;
pub mod gcode;
pub mod geom;
pub mod machine;
pub mod machine_check;
pub mod measure;
pub mod params;
pub mod state;
pub mod stroke;
pub mod sysvar;
pub mod tool_life;
pub mod value;
pub mod words;

pub use error::NcError;
pub use event::Event;
pub use exec::{Nc, Outcome, Sink};
pub use machine::Machine;
