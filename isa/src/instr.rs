//! [`Instr`] and [`Opcode`], generated from the opcode table in
//! `opcodes.rs`, with the encoder, decoder, operand visitors and
//! disassembly text.

use alloc::vec::Vec;
use core::fmt;

use crate::encoding::{Le, Reader};
use crate::opcodes::for_each_instr;
use crate::operand::*;
use crate::LoadError;

/// Expands the opcode table into the instruction enum and everything that
/// must agree with it.
macro_rules! define_instr {
    ($(
        $(#[$doc:meta])*
        $name:ident = $code:literal, $mnemonic:literal $({ $($field:ident : $kind:ident),* $(,)? })?;
    )*) => {
        /// One VM instruction. Fields are register numbers, table indexes
        /// and small codes, typed by their [`OperandKind`] alias.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum Instr {
            $( $(#[$doc])* $name $({ $(
                #[doc = concat!("A [`", stringify!($kind), "`] operand.")]
                $field: $kind
            ),* })?, )*
        }

        /// The opcode of an [`Instr`]; its value is the encoded opcode byte.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
        #[repr(u8)]
        pub enum Opcode {
            $( $(#[$doc])* $name = $code, )*
        }

        impl Opcode {
            /// Every opcode, in table order: lets tests cover each one
            /// without listing them again.
            pub const ALL: &'static [Opcode] = &[$(Opcode::$name),*];

            /// The opcode with this byte, if any.
            pub const fn from_u8(byte: u8) -> Option<Opcode> {
                match byte {
                    $( $code => Some(Opcode::$name), )*
                    _ => None,
                }
            }

            /// The disassembly mnemonic (`"add"`).
            pub const fn mnemonic(self) -> &'static str {
                match self {
                    $( Opcode::$name => $mnemonic, )*
                }
            }

            /// The Rust variant name (`"Add"`).
            pub const fn name(self) -> &'static str {
                match self {
                    $( Opcode::$name => stringify!($name), )*
                }
            }

            /// The operand kinds, in encoding order.
            pub const fn operand_kinds(self) -> &'static [OperandKind] {
                match self {
                    $( Opcode::$name => &[$($(OperandKind::$kind),*)?], )*
                }
            }

            /// The operand field names, in encoding order.
            pub const fn operand_names(self) -> &'static [&'static str] {
                match self {
                    $( Opcode::$name => &[$($(stringify!($field)),*)?], )*
                }
            }
        }

        impl Instr {
            /// The opcode of this instruction.
            pub const fn opcode(&self) -> Opcode {
                match self {
                    $( Instr::$name { .. } => Opcode::$name, )*
                }
            }

            /// Appends the encoding: the opcode byte, then each operand
            /// little-endian in table order.
            pub fn encode(&self, out: &mut Vec<u8>) {
                out.push(self.opcode() as u8);
                match *self {
                    $( Instr::$name { $($($field),*)? } => { $($( Le::put($field, out); )*)? } )*
                }
            }

            /// Reads one instruction at the reader's position; `pc` is only
            /// used to label a bad opcode.
            pub(crate) fn read(r: &mut Reader<'_>, pc: u32) -> Result<Instr, LoadError> {
                let byte = r.u8()?;
                // Struct expression fields are evaluated in the order
                // written, which is the encoding order.
                Ok(match Opcode::from_u8(byte) {
                    $( Some(Opcode::$name) => Instr::$name { $($($field: <$kind as Le>::get(r)?),*)? }, )*
                    None => return Err(LoadError::BadOpcode { pc, byte }),
                })
            }

            /// Calls `f` with every operand in table order, stopping at the
            /// first error (the verifier and the disassembler use this, so
            /// neither matches on opcodes).
            pub fn try_visit_operands<E>(
                &self,
                mut f: impl FnMut(Operand) -> Result<(), E>,
            ) -> Result<(), E> {
                match *self {
                    $( Instr::$name { $($($field),*)? } => { $($( f(Operand::$kind($field))?; )*)? } )*
                }
                Ok(())
            }

            /// Calls `f` with a mutable reference to every operand, e.g. to
            /// patch jump targets once labels are placed.
            pub fn visit_operands_mut(&mut self, mut f: impl FnMut(OperandMut<'_>)) {
                match self {
                    $( Instr::$name { $($($field),*)? } => { $($( f(OperandMut::$kind($field)); )*)? } )*
                }
            }
        }
    };
}

for_each_instr!(define_instr);

// Instructions are copied around a lot by the compiler and the VM; keep
// them two words at most.
const _: () = assert!(core::mem::size_of::<Instr>() <= 8);

/// The longest encoding of any instruction, in bytes (the loader bounds
/// a code section's instruction count with it).
pub(crate) const MAX_ENCODED_LEN: usize = {
    let mut max = 0;
    let mut i = 0;
    while i < Opcode::ALL.len() {
        let kinds = Opcode::ALL[i].operand_kinds();
        let mut len = 1;
        let mut j = 0;
        while j < kinds.len() {
            len += kinds[j].width();
            j += 1;
        }
        if len > max {
            max = len;
        }
        i += 1;
    }
    max
};

impl Opcode {
    /// Encoded size of an instruction with this opcode, in bytes.
    pub fn encoded_len(self) -> usize {
        1 + self
            .operand_kinds()
            .iter()
            .map(|k| k.width())
            .sum::<usize>()
    }
}

impl Instr {
    /// Decodes the instruction starting at `bytes[pos]`; returns it and the
    /// position just past it.
    ///
    /// Only the syntax is checked (a known opcode, enough bytes); operand
    /// ranges are the business of [`Module::verify`](crate::Module::verify),
    /// which knows the tables. A [`LoadError::BadOpcode`] from here carries
    /// the byte position `pos` as its `pc`.
    pub fn decode(bytes: &[u8], pos: usize) -> Result<(Instr, usize), LoadError> {
        let mut r = Reader::new(bytes, pos);
        let instr = Instr::read(&mut r, u32::try_from(pos).unwrap_or(u32::MAX))?;
        Ok((instr, r.pos()))
    }

    /// Calls `f` with every operand in table order.
    pub fn visit_operands(&self, mut f: impl FnMut(Operand)) {
        let done: Result<(), core::convert::Infallible> = self.try_visit_operands(|op| {
            f(op);
            Ok(())
        });
        let Ok(()) = done;
    }

    /// Encoded size in bytes.
    pub fn encoded_len(&self) -> usize {
        self.opcode().encoded_len()
    }
}

/// The disassembly text: the mnemonic, then the operands separated by
/// commas (`add r3, r1, r2`). Table contents are not shown here (an `Instr`
/// does not know its module); [`Module::disassemble`](crate::Module::disassemble)
/// adds them.
impl fmt::Display for Instr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.opcode().mnemonic())?;
        let mut sep = " ";
        self.try_visit_operands(|op| {
            write!(f, "{sep}{op}")?;
            sep = ", ";
            Ok(())
        })
    }
}
