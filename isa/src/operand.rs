//! Operand kinds: what an instruction field means, how wide it is encoded,
//! how it is printed and what the verifier checks about it.
//!
//! Every field of [`Instr`](crate::Instr) has one of these kinds. The kind
//! names double as type aliases (`Reg = u8`, `Const = u32`, …), so the
//! opcode table can say `dst: Reg` and the generated enum field is a plain
//! `u8`: the kind carries the meaning, the alias carries the width.

use core::fmt;

/// Generates the kind aliases, [`OperandKind`], [`Operand`] and
/// [`OperandMut`] from one list, so a new kind cannot be added to one and
/// forgotten in another.
macro_rules! define_operands {
    ($( $(#[$doc:meta])* $kind:ident : $ty:ty ),* $(,)?) => {
        $( $(#[$doc])* pub type $kind = $ty; )*

        /// The kind of an instruction operand, as listed in the opcode table.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum OperandKind {
            $( $(#[$doc])* $kind, )*
        }

        impl OperandKind {
            /// Encoded size in bytes (little-endian).
            pub const fn width(self) -> usize {
                match self {
                    $( OperandKind::$kind => core::mem::size_of::<$ty>(), )*
                }
            }
        }

        /// One operand of an instruction, tagged with its kind; what
        /// [`Instr::visit_operands`](crate::Instr::visit_operands) yields.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum Operand {
            $( $(#[$doc])* $kind($ty), )*
        }

        impl Operand {
            /// The kind of this operand.
            pub const fn kind(&self) -> OperandKind {
                match self {
                    $( Operand::$kind(_) => OperandKind::$kind, )*
                }
            }

            /// The raw value, widened (for tests and generic tools).
            pub fn value(&self) -> u32 {
                match *self {
                    $( Operand::$kind(v) => u32::from(v), )*
                }
            }
        }

        /// A mutable reference to one operand, from
        /// [`Instr::visit_operands_mut`](crate::Instr::visit_operands_mut):
        /// lets the compiler patch jump targets or renumber registers
        /// without matching every opcode.
        #[derive(Debug, PartialEq, Eq)]
        pub enum OperandMut<'a> {
            $( $(#[$doc])* $kind(&'a mut $ty), )*
        }
    };
}

define_operands! {
    /// A register number; must be `< Module::num_regs`.
    Reg: u8,
    /// A plain byte (flags).
    U8: u8,
    /// A plain 16-bit number (alarm codes).
    U16: u16,
    /// A plain 32-bit number.
    U32: u32,
    /// A jump target: an index into `Module::code`; must be `< code.len()`.
    Pc: u32,
    /// An index into `Module::consts`.
    Const: u32,
    /// An index into `Module::strings`.
    Str: u32,
    /// An index into `Module::programs`.
    Prog: u32,
    /// A macro variable number written literally (`#100`); the VM decides
    /// which numbers exist, so the verifier accepts any.
    Var: u32,
    /// A macro-call argument variable, `#1..=#33`.
    ArgVar: u8,
    /// A word address: `0..=25` are the letters `A..=Z`, 26/27/28 are
    /// `,A` `,C` `,R` (see [`addr`]).
    Addr: u8,
    /// A [`MathFunc`] code.
    FuncCode: u8,
    /// A [`CmpOp`] code.
    CmpCode: u8,
    /// A block-skip switch, `1..=9` (`/` is 1, `/n` is n; see [`SWITCHES`]).
    Switch: u8,
    /// A typed block: the byte offset of a record in `Module::blocks`;
    /// must be where a record starts.
    Rec: u32,
}

/// The block-skip switches a [`Switch`] operand may name.
pub const SWITCHES: core::ops::RangeInclusive<u8> = 1..=9;

/// Prints an operand the way the disassembly shows it: registers `r3`,
/// constants `k3`, strings `s3`, programs `p3`, jump targets `@0012`,
/// variables `#100`, word addresses and function/comparison names as in
/// G-code (`X`, `,R`, `SIN`, `EQ`). Constants are not `#3` because `#`
/// already means a macro variable in the source language.
impl fmt::Display for Operand {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Operand::Reg(r) => write!(f, "r{r}"),
            Operand::U8(v) => write!(f, "{v}"),
            Operand::U16(v) => write!(f, "{v}"),
            Operand::U32(v) => write!(f, "{v}"),
            Operand::Pc(t) => write!(f, "@{t:04}"),
            Operand::Const(k) => write!(f, "k{k}"),
            Operand::Str(s) => write!(f, "s{s}"),
            Operand::Prog(p) => write!(f, "p{p}"),
            Operand::Var(v) => write!(f, "#{v}"),
            Operand::ArgVar(v) => write!(f, "#{v}"),
            Operand::Addr(a) => match addr::name(a) {
                Some(name) => f.write_str(name),
                None => write!(f, "addr?{a}"),
            },
            Operand::FuncCode(c) => match MathFunc::from_code(c) {
                Some(func) => f.write_str(func.name()),
                None => write!(f, "func?{c}"),
            },
            Operand::CmpCode(c) => match CmpOp::from_code(c) {
                Some(op) => f.write_str(op.name()),
                None => write!(f, "cmp?{c}"),
            },
            Operand::Switch(n) => write!(f, "/{n}"),
            Operand::Rec(b) => write!(f, "b{b}"),
        }
    }
}

/// Generates a `u8`-coded enum with `from_code`, `code`, `name` and `ALL`.
macro_rules! coded_enum {
    ($(#[$doc:meta])* $name:ident { $( $(#[$vdoc:meta])* $variant:ident = $code:literal $text:literal, )* }) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        #[repr(u8)]
        pub enum $name {
            $( $(#[$vdoc])* $variant = $code, )*
        }

        impl $name {
            /// Every value, in code order.
            pub const ALL: &'static [$name] = &[$($name::$variant),*];

            /// The value with this code, or `None` if the code is unassigned.
            pub const fn from_code(code: u8) -> Option<$name> {
                match code {
                    $( $code => Some($name::$variant), )*
                    _ => None,
                }
            }

            /// The code stored in the instruction.
            pub const fn code(self) -> u8 {
                self as u8
            }

            /// The name as written in G-code.
            pub const fn name(self) -> &'static str {
                match self {
                    $( $name::$variant => $text, )*
                }
            }
        }
    };
}

coded_enum! {
    /// The one-argument functions of `Func` (`#1 = SIN[#2]`).
    MathFunc {
        /// Sine, argument in degrees.
        Sin = 0 "SIN",
        /// Cosine, argument in degrees.
        Cos = 1 "COS",
        /// Tangent, argument in degrees.
        Tan = 2 "TAN",
        /// Arc sine, result in degrees.
        Asin = 3 "ASIN",
        /// Arc cosine, result in degrees.
        Acos = 4 "ACOS",
        /// Arc tangent, result in degrees.
        Atan = 5 "ATAN",
        /// Square root.
        Sqrt = 6 "SQRT",
        /// Absolute value.
        Abs = 7 "ABS",
        /// Round half away from zero.
        Round = 8 "ROUND",
        /// Truncate toward zero.
        Fix = 9 "FIX",
        /// Round away from zero.
        Fup = 10 "FUP",
        /// Natural logarithm.
        Ln = 11 "LN",
        /// `e` to the power.
        Exp = 12 "EXP",
        /// BCD to binary.
        Bin = 13 "BIN",
        /// Binary to BCD.
        Bcd = 14 "BCD",
    }
}

coded_enum! {
    /// The comparison of `Cmp` (`EQ NE GT LT GE LE`).
    CmpOp {
        /// Equal.
        Eq = 0 "EQ",
        /// Not equal.
        Ne = 1 "NE",
        /// Greater than.
        Gt = 2 "GT",
        /// Less than.
        Lt = 3 "LT",
        /// Greater or equal.
        Ge = 4 "GE",
        /// Less or equal.
        Le = 5 "LE",
    }
}

/// Word addresses of `Word`/`WordK`: `0..=25` are `A..=Z`, then the comma
/// words `,A` `,C` `,R` (chamfer/corner-rounding arguments).
pub mod addr {
    /// `,A` (angle).
    pub const COMMA_A: u8 = 26;
    /// `,C` (chamfer).
    pub const COMMA_C: u8 = 27;
    /// `,R` (corner rounding).
    pub const COMMA_R: u8 = 28;
    /// The largest valid address.
    pub const MAX: u8 = COMMA_R;

    const NAMES: [&str; MAX as usize + 1] = [
        "A", "B", "C", "D", "E", "F", "G", "H", "I", "J", "K", "L", "M", "N", "O", "P", "Q", "R",
        "S", "T", "U", "V", "W", "X", "Y", "Z", ",A", ",C", ",R",
    ];

    /// The address of a letter word (`'X'` → 23); either case.
    pub const fn from_letter(letter: char) -> Option<u8> {
        let upper = letter.to_ascii_uppercase();
        if upper.is_ascii_uppercase() {
            Some(upper as u8 - b'A')
        } else {
            None
        }
    }

    /// The address as written in G-code (`23` → `"X"`, `28` → `",R"`).
    pub fn name(addr: u8) -> Option<&'static str> {
        NAMES.get(usize::from(addr)).copied()
    }
}
