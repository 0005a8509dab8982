//! The functions compiled code calls for what it does not inline: the
//! kernel's own value functions (`nc::value`), so that a function or a MOD
//! gives the interpreter's bits, the word buffer, and the kernel's
//! executor for a block.
//!
//! A fault is reported as NaN: no operation here returns NaN as a value
//! (a result that is not finite is itself a fault, E5006), so the code
//! takes NaN as "leave to the interpreter at this instruction", which then
//! raises the alarm with its message.

use nc::value::{self, Bin, Func};
use nc::words::Words;
use vm::{Kernel, Ran};

use crate::native::Ctx;

/// The binary operations the code calls out for, by the number it passes.
pub const BINARY_OPS: [Bin; 5] = [Bin::Div, Bin::Mod, Bin::And, Bin::Or, Bin::Xor];

/// The index of `op` in [`BINARY_OPS`].
pub fn binary_code(op: Bin) -> Option<u32> {
    BINARY_OPS.iter().position(|&o| o == op).map(|i| i as u32)
}

pub extern "C" fn binary(op: u32, a: f64, b: f64) -> f64 {
    match BINARY_OPS.get(op as usize) {
        Some(&op) => value::binary(op, a, b).unwrap_or(f64::NAN),
        None => f64::NAN,
    }
}

pub extern "C" fn func(code: u32, a: f64) -> f64 {
    let Some(f) = u8::try_from(code).ok().and_then(Func::from_code) else {
        return f64::NAN;
    };
    value::func(f, a).unwrap_or(f64::NAN)
}

/// The functions whose only fault is a result that is not finite, as C
/// functions the code calls directly (checking the result itself): the
/// kernel's own computation, without `func`'s dispatch.
pub fn total(f: Func) -> Option<extern "C" fn(f64) -> f64> {
    extern "C" fn sin(x: f64) -> f64 {
        value::sin_deg(x)
    }
    extern "C" fn cos(x: f64) -> f64 {
        value::cos_deg(x)
    }
    extern "C" fn atan(x: f64) -> f64 {
        value::atan_deg(x)
    }
    extern "C" fn exp(x: f64) -> f64 {
        libm::exp(x)
    }
    match f {
        Func::Sin => Some(sin),
        Func::Cos => Some(cos),
        Func::Atan => Some(atan),
        Func::Exp => Some(exp),
        _ => None,
    }
}

pub extern "C" fn atan2(y: f64, x: f64) -> f64 {
    value::atan2(y, x).unwrap_or(f64::NAN)
}

/// Adds a word to the block being built.
///
/// # Safety
/// `words` is the `Words` the VM lent for this entry of the code (the
/// code passes on the pointer it was given, nothing else).
pub unsafe extern "C" fn push_word(words: *mut Words, addr: u32, v: f64, flags: u32) {
    // SAFETY: the caller's contract; the VM holds no other reference to
    // its words while the code runs.
    let words = unsafe { &mut *words };
    words.push(addr as u8, v, flags as u8);
}

/// Runs the block instruction at `pc` through the kernel the VM lent
/// (`vm::Kernel::run_block`): what became of it, a [`Ran`] as `u32`.
///
/// # Safety
/// `ctx` is the context `Code::run` made for this entry of the code: its
/// `kernel` points at the `&mut dyn Kernel` of that call and its `words`
/// at the VM's words; after `Ran::Leave` or `Ran::Not` the code touches
/// the state no more.
pub unsafe extern "C" fn block(ctx: *mut Ctx, pc: u32) -> u32 {
    // SAFETY: the caller's contract: the pointers are live for this entry
    // and nothing else uses them while the kernel runs.
    let ctx = unsafe { &mut *ctx };
    let kernel = unsafe { &mut *ctx.kernel.cast::<&mut dyn Kernel>() };
    let words = unsafe { &mut *ctx.words };
    let ran = kernel.run_block(pc, words, &mut ctx.blocks);
    ctx.blocks_run += u64::from(ran != Ran::Not);
    ran as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn faults_come_back_as_nan_and_values_as_the_kernel_computes_them() {
        let div = binary_code(Bin::Div).unwrap_or(99);
        assert!(binary(div, 1.0, 0.0).is_nan());
        assert_eq!(binary(div, 1.0, 4.0), 0.25);
        assert!(binary(99, 1.0, 1.0).is_nan());
        assert!(func(Func::Sqrt as u32, -1.0).is_nan());
        assert_eq!(func(Func::Sqrt as u32, 9.0), 3.0);
        assert!(func(200, 1.0).is_nan());
        assert!(atan2(0.0, 0.0).is_nan());
    }

    /// The direct calls give `value::func`'s bits wherever it gives a
    /// value, and a result that is not finite (which the code checks)
    /// wherever it faults; no function with a domain is among them.
    #[test]
    fn total_functions_are_the_kernels_computation() {
        let xs = [
            0.0, -0.0, 1e-300, 0.5, -1.0, 30.0, 45.0, 90.0, -180.0, 359.99, 1e6, 709.0, 710.0,
            -745.5, 1e308, 3.0e15,
        ];
        for f in Func::ALL {
            let Some(total) = total(f) else {
                continue;
            };
            assert!(
                matches!(f, Func::Sin | Func::Cos | Func::Atan | Func::Exp),
                "{f:?} has a domain to check"
            );
            for x in xs {
                let direct = total(x);
                match value::func(f, x) {
                    Ok(v) => assert_eq!((direct + 0.0).to_bits(), v.to_bits(), "{f:?}({x})"),
                    Err(_) => assert!(!direct.is_finite(), "{f:?}({x}) = {direct}"),
                }
            }
        }
        let covered = Func::ALL.iter().filter(|&&f| total(f).is_some()).count();
        assert_eq!(covered, 4);
    }
}
