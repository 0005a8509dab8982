//! `gbvm run --jit`: whether hot macro loops run as machine code.

/// The `--jit` switch.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum JitMode {
    /// Every loop interpreted.
    Off,
    /// A loop compiled once it is hot.
    Auto,
    /// Every loop compiled at its first round.
    Always,
}

impl JitMode {
    /// Gives `vm` the loop tier for this mode (nothing for `off`, or in a
    /// build without the `jit` feature, where every loop is interpreted).
    pub fn attach(self, vm: &mut vm::Vm) {
        #[cfg(feature = "jit")]
        {
            let mode = match self {
                JitMode::Off => jit::Mode::Off,
                JitMode::Auto => jit::Mode::Auto,
                JitMode::Always => jit::Mode::Always,
            };
            if let Some(tier) = jit::Jit::new(mode) {
                vm.set_tier(Box::new(tier));
            }
        }
        #[cfg(not(feature = "jit"))]
        let _ = vm;
    }
}
