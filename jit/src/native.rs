//! The Cranelift backend: a JIT module that turns regions into machine
//! code, and the call into that code.

use std::mem::ManuallyDrop;
use std::time::{Duration, Instant};

use cranelift_codegen::ir::{types, AbiParam, Signature};
use cranelift_codegen::settings::{self, Configurable};
use cranelift_codegen::Context;
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext};
use cranelift_jit::{JITBuilder, JITModule};
use cranelift_module::{default_libcall_names, FuncId, Linkage, Module as _};
use nc::words::Words;
use vm::{Kernel, LoopState};

use crate::helpers;
use crate::lower::{Lower, Refs};
use crate::region::Region;

/// What compiled code reads and writes, laid out for it: the VM's state
/// as pointers, and the counters by value (copied back after the call).
#[repr(C)]
pub struct Ctx {
    pub regs: *mut f64,
    pub locals: *mut f64,
    pub common: *mut f64,
    pub persistent: *const f64,
    pub words: *mut Words,
    pub blocks: u64,
    pub max_blocks: u64,
    pub fuel: u64,
    /// The kernel's executor (`helpers::block`): a `*mut &mut dyn Kernel`.
    pub kernel: *mut std::ffi::c_void,
    /// Blocks run through it.
    pub blocks_run: u64,
}

/// A compiled loop: `fn(ctx, entry pc) -> pc to go on at`.
type LoopFn = unsafe extern "C" fn(*mut Ctx, u32) -> u32;

/// One loop's machine code, and the register count it was compiled for.
#[derive(Clone, Copy)]
pub struct Code {
    entry: LoopFn,
    num_regs: usize,
}

/// What a run of compiled code did.
pub struct Run {
    /// The pc at which the interpreter goes on.
    pub next: u32,
    /// NC blocks it ran through the kernel.
    pub blocks: u64,
    /// Instructions it ran (the fuel it spent).
    pub work: u64,
}

impl Code {
    /// The register count the code was compiled for.
    pub fn num_regs(&self) -> usize {
        self.num_regs
    }

    /// Runs the code from `pc` (one of the region's entries) on the VM's
    /// state.
    pub fn run(&self, pc: u32, state: LoopState<'_>) -> Option<Run> {
        if state.regs.len() != self.num_regs {
            return None;
        }
        let mut kernel: &mut dyn Kernel = state.kernel;
        let mut ctx = Ctx {
            regs: state.regs.as_mut_ptr(),
            locals: state.locals.as_mut_ptr(),
            common: state.common.as_mut_ptr(),
            persistent: state.persistent.as_ptr(),
            words: state.words,
            blocks: *state.blocks,
            max_blocks: state.max_blocks,
            fuel: *state.fuel,
            kernel: (&raw mut kernel).cast(),
            blocks_run: 0,
        };
        // SAFETY: the code was compiled for a register file of this length
        // and touches only the locals (33), commons (100) and persistent
        // variables (500, read only) at indexes below those lengths, the
        // words through `helpers::push_word`, the kernel through
        // `helpers::block` (which changes no register or variable when it
        // lets the code go on, and after which the code touches nothing
        // otherwise), and `ctx` itself; every one is borrowed mutably (or
        // shared, the persistent ones) for this call, so nothing else
        // reads or writes them meanwhile.
        let next = unsafe { (self.entry)(&mut ctx, pc) };
        let work = state.fuel.saturating_sub(ctx.fuel);
        *state.blocks = ctx.blocks;
        *state.fuel = ctx.fuel;
        Some(Run {
            next,
            blocks: ctx.blocks_run,
            work,
        })
    }
}

/// The helpers the code calls, declared to the module.
struct HelperIds {
    binary: FuncId,
    func: FuncId,
    atan2: FuncId,
    push_word: FuncId,
    block: FuncId,
}

/// The JIT module and its reusable contexts.
pub struct Backend {
    /// Dropped by hand, with its code memory (`Drop`).
    module: ManuallyDrop<JITModule>,
    ctx: Context,
    fctx: FunctionBuilderContext,
    helpers: HelperIds,
    count: u32,
}

// SAFETY: `JITModule` holds raw pointers into the code memory it owns and
// hands out; the backend is used by one thread at a time (it moves with
// its VM, `&mut` only), and the code it made does not refer to any thread.
unsafe impl Send for Backend {}

/// How hard Cranelift works on a loop's code.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Level {
    /// A short compile, for a loop that has just become hot (compile time
    /// counts: the loop waits for it): no optimiser (`lower` emits what it
    /// would have left of the arithmetic) and the single-pass register
    /// allocator, which spills every value across blocks. The ellipse's
    /// loop: about 120 µs.
    Quick,
    /// The optimiser and the backtracking register allocator, for a loop
    /// that has run long in quick code: 2.5× the compile time for code
    /// with a third fewer instructions (the numeric loop, lowered alike:
    /// 224 against 350 a round).
    Full,
}

impl Backend {
    /// A backend at `level`; `verify`: Cranelift's verifier checks each
    /// function (the tests'; a run's compile leaves it off).
    pub fn new(level: Level, verify: bool) -> Result<Backend, String> {
        let mut flags = settings::builder();
        let set = |flags: &mut settings::Builder, k: &str, v: &str| {
            flags
                .set(k, v)
                .map_err(|e| format!("cranelift setting {k}: {e}"))
        };
        let (opt_level, regalloc) = match level {
            Level::Quick => ("none", "single_pass"),
            Level::Full => ("speed", "backtracking"),
        };
        // No unwind info: nothing unwinds through the code (the helpers
        // cannot panic across it: `extern "C"` aborts).
        set(&mut flags, "opt_level", opt_level)?;
        set(&mut flags, "regalloc_algorithm", regalloc)?;
        set(
            &mut flags,
            "enable_verifier",
            if verify { "true" } else { "false" },
        )?;
        set(&mut flags, "unwind_info", "false")?;
        set(&mut flags, "use_colocated_libcalls", "false")?;
        set(&mut flags, "is_pic", "false")?;
        let isa = cranelift_native::builder()
            .map_err(|e| format!("no Cranelift backend for this host: {e}"))?
            .finish(settings::Flags::new(flags))
            .map_err(|e| format!("Cranelift: {e}"))?;
        let mut builder = JITBuilder::with_isa(isa, default_libcall_names());
        builder.symbol("gbc_binary", helpers::binary as *const u8);
        builder.symbol("gbc_func", helpers::func as *const u8);
        builder.symbol("gbc_atan2", helpers::atan2 as *const u8);
        builder.symbol("gbc_push_word", helpers::push_word as *const u8);
        builder.symbol("gbc_block", helpers::block as *const u8);
        let mut module = JITModule::new(builder);
        let helpers = declare_helpers(&mut module)?;
        Ok(Backend {
            ctx: module.make_context(),
            module: ManuallyDrop::new(module),
            fctx: FunctionBuilderContext::new(),
            helpers,
            count: 0,
        })
    }

    /// Compiles a region of `module` for a register file of `num_regs`;
    /// returns its code and how long compiling took.
    pub fn compile(
        &mut self,
        module: &isa::Module,
        region: &Region,
        num_regs: usize,
    ) -> Result<(Code, Duration), String> {
        let started = Instant::now();
        let ptr = self.module.target_config().pointer_type();
        self.module.clear_context(&mut self.ctx);
        let sig = &mut self.ctx.func.signature;
        sig.params.push(AbiParam::new(ptr));
        sig.params.push(AbiParam::new(types::I32));
        sig.returns.push(AbiParam::new(types::I32));
        let refs = self.import_helpers();
        let builder = FunctionBuilder::new(&mut self.ctx.func, &mut self.fctx);
        Lower::build(builder, module, region, refs, ptr, num_regs);
        self.count += 1;
        let name = format!("loop{}_{}", self.count, region.head);
        let err = |e: &dyn std::fmt::Display| format!("compiling the loop at {}: {e}", region.head);
        let id = self
            .module
            .declare_function(&name, Linkage::Local, &self.ctx.func.signature)
            .map_err(|e| err(&e))?;
        self.module
            .define_function(id, &mut self.ctx)
            .map_err(|e| err(&e))?;
        self.module.clear_context(&mut self.ctx);
        self.module.finalize_definitions().map_err(|e| err(&e))?;
        let raw = self.module.get_finalized_function(id);
        // SAFETY: `raw` is the function just defined with the signature
        // `(ptr, i32) -> i32` in the platform's C convention, which is
        // `LoopFn`.
        let entry = unsafe { std::mem::transmute::<*const u8, LoopFn>(raw) };
        Ok((Code { entry, num_regs }, started.elapsed()))
    }

    fn import_helpers(&mut self) -> Refs {
        let f = &mut self.ctx.func;
        let m = &mut *self.module;
        let mut unary = Signature::new(m.target_config().default_call_conv);
        unary.params.push(AbiParam::new(types::F64));
        unary.returns.push(AbiParam::new(types::F64));
        Refs {
            unary: f.import_signature(unary),
            binary: m.declare_func_in_func(self.helpers.binary, f),
            func: m.declare_func_in_func(self.helpers.func, f),
            atan2: m.declare_func_in_func(self.helpers.atan2, f),
            push_word: m.declare_func_in_func(self.helpers.push_word, f),
            block: m.declare_func_in_func(self.helpers.block, f),
        }
    }
}

impl Drop for Backend {
    fn drop(&mut self) {
        // SAFETY: `module` is not used after this, and no `Code` outlives
        // the backend (the tier owns both and drops them together), so
        // nothing calls the code any more.
        unsafe { ManuallyDrop::take(&mut self.module).free_memory() };
    }
}

fn declare_helpers(module: &mut JITModule) -> Result<HelperIds, String> {
    let ptr = module.target_config().pointer_type();
    let call_conv = module.target_config().default_call_conv;
    let mut declare = |name: &str, params: &[types::Type], ret: Option<types::Type>| {
        let mut sig = Signature::new(call_conv);
        sig.params.extend(params.iter().map(|&t| AbiParam::new(t)));
        sig.returns.extend(ret.map(AbiParam::new));
        module
            .declare_function(name, Linkage::Import, &sig)
            .map_err(|e| format!("declaring {name}: {e}"))
    };
    let (f64t, i32t) = (types::F64, types::I32);
    Ok(HelperIds {
        binary: declare("gbc_binary", &[i32t, f64t, f64t], Some(f64t))?,
        func: declare("gbc_func", &[i32t, f64t], Some(f64t))?,
        atan2: declare("gbc_atan2", &[f64t, f64t], Some(f64t))?,
        push_word: declare("gbc_push_word", &[ptr, i32t, f64t, i32t], None)?,
        block: declare("gbc_block", &[ptr, i32t], Some(i32t))?,
    })
}
