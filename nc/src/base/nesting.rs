//! How deep calls may nest (dialect.md §7.12): the VM raises E6004 past
//! these, and the compiler warns (W121) of a chain of calls that always
//! goes past them.

/// Macro levels: G65, G66 and G-code macro calls, each with its own
/// local variables.
pub const MAX_MACRO_LEVELS: usize = 4;

/// Subprogram levels: M98 and M-code calls, which share their caller's
/// locals.
pub const MAX_SUB_LEVELS: usize = 4;

/// Calls of both kinds together.
pub const MAX_CALLS: usize = 8;
