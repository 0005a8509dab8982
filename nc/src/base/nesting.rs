//! How deep calls may nest (dialect.md §7.12): the VM raises E6004 past
//! these; the compiler's dry run follows calls within them, and it warns
//! (W121) of a chain of calls that always goes past them.

/// Macro levels: G65, G66 and G-code macro calls, each with its own
/// local variables.
pub const MAX_MACRO_LEVELS: usize = 4;

/// Subprogram levels: M98 and M-code calls, which share their caller's
/// locals.
pub const MAX_SUB_LEVELS: usize = 4;

/// Calls of both kinds together.
pub const MAX_CALLS: usize = 8;

/// The call levels open where a program runs: macro levels and
/// subprogram levels (the main program has none).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub struct Levels {
    pub macros: usize,
    pub subs: usize,
}

impl Levels {
    /// The levels inside a call (of a macro, or of a subprogram), or
    /// `None` when the call goes past a limit (E6004).
    pub fn enter(self, macro_level: bool) -> Option<Levels> {
        let next = match macro_level {
            true => Levels {
                macros: self.macros + 1,
                ..self
            },
            false => Levels {
                subs: self.subs + 1,
                ..self
            },
        };
        let fits = next.macros <= MAX_MACRO_LEVELS
            && next.subs <= MAX_SUB_LEVELS
            && next.macros + next.subs <= MAX_CALLS;
        fits.then_some(next)
    }
}
