//! `[plc]` of the machine file: what the machine's own PLC adds to the
//! reference PLC table (docs/machine.md). Today its M codes: an M code
//! listed here is the machine's, so the compiler does not warn that it is
//! unknown (W113).

use alloc::vec::Vec;
use serde::Deserialize;

#[derive(Debug, Clone, PartialEq, Eq, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Plc {
    /// M codes the machine's PLC handles beyond the reference table
    /// (`m_codes = [8, 9, 77]`).
    pub m_codes: Vec<u32>,
}

impl Plc {
    /// Whether the machine's PLC lists M`m`.
    pub fn lists_m(&self, m: u32) -> bool {
        self.m_codes.contains(&m)
    }
}
