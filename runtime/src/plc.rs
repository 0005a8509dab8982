//! The PLC side of M, S and T functions: the runtime hands each one over
//! when the motion before it is complete and waits for its completion
//! signal (FIN) before the next command runs — so M08 is on before the
//! cut that follows it.

/// Spindle directions as the runtime sees them (independent of `nc`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SpindleDir {
    /// M03.
    Cw,
    /// M04.
    Ccw,
    /// M05.
    Stop,
}

/// One auxiliary function.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PlcFunction {
    /// Any M code handed to the PLC (M08, M09, M10 …).
    M(u32),
    /// M03 / M04 / M05.
    Spindle(SpindleDir),
    /// S: rpm (G97) or surface speed m/min (G96); `max`: the `G50 S`
    /// limit when this is a G50 block.
    Speed {
        /// rev/min (G97) or m/min (G96).
        s: f64,
        /// Constant surface speed (G96).
        css: bool,
        /// The `G50 S` limit of a G50 block.
        max: Option<f64>,
    },
    /// S00…S04 of a gear spindle.
    Gear(u32),
    /// T: tool and offset number.
    Tool {
        /// Tool number.
        t: u32,
        /// Offset number.
        d: u32,
    },
}

/// What a host implements to run the machine's auxiliary functions.
/// Both calls come from the period loop: they must return at once and
/// should not allocate or block.
pub trait Plc {
    /// A function starts (strobe on).
    fn request(&mut self, f: PlcFunction);
    /// Polled once a period until it returns true: the function is
    /// complete (FIN).
    fn done(&mut self, f: PlcFunction) -> bool;
}

/// The reference host: every function completes at once.
#[derive(Debug, Clone, Copy, Default)]
pub struct AutoAck;

impl Plc for AutoAck {
    fn request(&mut self, _: PlcFunction) {}
    fn done(&mut self, _: PlcFunction) -> bool {
        true
    }
}
