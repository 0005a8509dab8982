//! The instruction set of the gbc register VM and its `.gbc` container.
//!
//! This crate sits between the compiler and the VM (`compiler → isa ← vm`):
//! the compiler emits [`Instr`]s into a [`Module`] and writes it with
//! [`Module::to_bytes`]; the VM loads it with [`Module::from_bytes`], which
//! parses *and* verifies, so the interpreter can index registers, constants,
//! strings, programs and jump targets without bounds checks of its own.
//!
//! Every opcode is listed once, in `src/opcodes.rs`; the enum, the
//! encoder, the decoder, the operand visitor and the disassembly text are all
//! generated from that table so they cannot drift apart.
//!
//! The crate is `#![no_std]` and needs only `alloc`. The `std` feature (on by
//! default) only forwards to the dependencies.
//!
//! ```
//! use isa::{Instr, Module, Program, SourceFileInfo, SourceLoc};
//!
//! let module = Module {
//!     code: vec![
//!         Instr::LoadK { dst: 0, k: 0 },
//!         Instr::StoreVar { var: 100, src: 0 },
//!         Instr::Halt,
//!     ],
//!     consts: vec![12.5],
//!     programs: vec![Program { number: 1, entry: 0, end: 3, seqs: vec![(10, 0)], ..Program::default() }],
//!     lines: vec![SourceLoc { file: 0, line: 1, col: 1 }; 3].into(),
//!     files: vec![SourceFileInfo { name: "part.nc".into(), hash: 0 }],
//!     num_regs: 1,
//!     ..Module::default()
//! };
//! let bytes = module.to_bytes();
//! let loaded = Module::from_bytes(&bytes)?;
//! assert_eq!(loaded, module);
//! assert_eq!(loaded.code[1].to_string(), "storevar #100, r0");
//! assert_eq!(loaded.pc_of_seq(0, 10), Some(0));
//! # Ok::<(), isa::LoadError>(())
//! ```

#![no_std]
#![deny(missing_docs)]

extern crate alloc;

pub mod block;
mod disasm;
mod encoding;
mod error;
pub mod format;
mod instr;
mod lines;
mod module;
mod opcodes;
pub mod operand;
mod verify;

pub use block::BlockWord;
pub use error::{LoadError, TableError};
pub use instr::{Instr, Opcode};
pub use lines::{LineTable, LineTableError};
pub use module::{loop_holds, Module, Program, SourceFileInfo, SourceLoc};
pub use operand::{
    addr, Addr, ArgVar, CmpCode, CmpOp, Const, FuncCode, MathFunc, Operand, OperandKind,
    OperandMut, Pc, Prog, Reg, Str, Switch, Var, SWITCHES, U16, U32, U8,
};
