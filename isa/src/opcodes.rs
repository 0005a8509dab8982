//! The opcode table: every instruction, once.
//!
//! Each entry is `Name = opcode byte, "mnemonic" { field: Kind, … };` (no
//! braces for an instruction without operands). Operands are encoded after
//! the opcode byte in the order listed, each as wide as its kind (see
//! [`OperandKind::width`](crate::OperandKind::width)).
//!
//! The table is handed to a generator macro (`for_each_instr!(gen)`) rather
//! than expanded in place, so another generator — a test, a future JIT —
//! can walk the same list.
//!
//! Opcode bytes are part of the file format: never renumber one, only add.
//! They start at 1 so a zero-filled code section is rejected. The mnemonic
//! is the lower-cased name (a test checks it).

macro_rules! for_each_instr {
    ($gen:ident) => {
        $gen! {
            // --- registers, constants and variables ---
            /// `dst = consts[k]`.
            LoadK = 0x01, "loadk" { dst: Reg, k: Const };
            /// `dst = <vacant>` (the VM's vacant NaN, `#0`).
            LoadNull = 0x02, "loadnull" { dst: Reg };
            /// `dst = src`.
            Mov = 0x03, "mov" { dst: Reg, src: Reg };
            /// `dst = #var` for a variable number known at compile time.
            LoadVar = 0x04, "loadvar" { dst: Reg, var: Var };
            /// `dst = #[idx]`: the variable number is computed.
            LoadVarInd = 0x05, "loadvarind" { dst: Reg, idx: Reg };
            /// `#var = src`.
            StoreVar = 0x06, "storevar" { var: Var, src: Reg };
            /// `#[idx] = src`.
            StoreVarInd = 0x07, "storevarind" { idx: Reg, src: Reg };

            // --- arithmetic ---
            /// `dst = -a`.
            Neg = 0x10, "neg" { dst: Reg, a: Reg };
            /// `dst = a + b`.
            Add = 0x11, "add" { dst: Reg, a: Reg, b: Reg };
            /// `dst = a - b`.
            Sub = 0x12, "sub" { dst: Reg, a: Reg, b: Reg };
            /// `dst = a * b`.
            Mul = 0x13, "mul" { dst: Reg, a: Reg, b: Reg };
            /// `dst = a / b`.
            Div = 0x14, "div" { dst: Reg, a: Reg, b: Reg };
            /// `dst = a MOD b`.
            Mod = 0x15, "mod" { dst: Reg, a: Reg, b: Reg };
            /// `dst = a AND b`.
            BitAnd = 0x16, "bitand" { dst: Reg, a: Reg, b: Reg };
            /// `dst = a OR b`.
            BitOr = 0x17, "bitor" { dst: Reg, a: Reg, b: Reg };
            /// `dst = a XOR b`.
            BitXor = 0x18, "bitxor" { dst: Reg, a: Reg, b: Reg };
            /// `dst = f[a]` for a [`MathFunc`](crate::MathFunc) code `f`.
            Func = 0x19, "func" { dst: Reg, a: Reg, f: FuncCode };
            /// `dst = ATAN[y]/[x]`, two-argument arc tangent in degrees.
            Atan2 = 0x1A, "atan2" { dst: Reg, y: Reg, x: Reg };
            /// `dst = a <op> b` (1 or 0) for a [`CmpOp`](crate::CmpOp) code.
            Cmp = 0x1B, "cmp" { dst: Reg, a: Reg, b: Reg, op: CmpCode };
            /// `dst = a + consts[k]`: an operand that is a constant is
            /// read from the pool, not loaded into a register first.
            AddK = 0x1C, "addk" { dst: Reg, a: Reg, k: Const };
            /// `dst = a - consts[k]`.
            SubK = 0x1D, "subk" { dst: Reg, a: Reg, k: Const };
            /// `dst = a * consts[k]`.
            MulK = 0x1E, "mulk" { dst: Reg, a: Reg, k: Const };
            /// `dst = a / consts[k]`. (0x1x is full: the byte is free.)
            DivK = 0x0F, "divk" { dst: Reg, a: Reg, k: Const };
            /// `dst = a <op> consts[k]` (1 or 0).
            CmpK = 0x1F, "cmpk" { dst: Reg, a: Reg, k: Const, op: CmpCode };

            // --- control flow ---
            /// Continue at `target`.
            Jump = 0x20, "jump" { target: Pc };
            /// Continue at `target` unless `cond` is true (IF/WHILE tests).
            JumpIfNot = 0x21, "jumpifnot" { cond: Reg, target: Pc };
            /// `GOTO [seq]`: the sequence number is computed, so the VM looks
            /// it up in the current program's sequence table at run time.
            GotoSeq = 0x22, "gotoseq" { seq: Reg };
            /// `GOTO [seq]` inside DO loop `inside` of the program (its
            /// loop table): a target in a loop that does not hold this one
            /// is jumped into from outside (E6008).
            GotoSeqIn = 0x24, "gotoseqin" { seq: Reg, inside: U32 };
            /// A macro statement block that no other instruction charges
            /// to the block budget: a WHILE's test, an IF whose THEN does
            /// not run, an IF whose GOTO is not taken.
            Charge = 0x25, "charge";
            /// `GOTO n` to a number known at compile time: a jump that is
            /// a block of its own, charged once whichever way it goes (a
            /// backward `jump` is charged as closing a loop, a forward one
            /// not at all).
            Goto = 0x26, "goto" { target: Pc };
            /// The guard of a `/n` block (block delete): continue at
            /// `target`, the code after the block, when block-skip switch
            /// `switch` is on as the block is read; else run the block.
            /// The verifier holds `target` past the guard, so a skip never
            /// closes a loop.
            SkipBlock = 0x23, "skipblock" { switch: Switch, target: Pc };

            // --- building and executing blocks ---
            /// Add a word with a computed value to the block being built.
            Word = 0x30, "word" { addr: Addr, src: Reg };
            /// Add a literal word; `flags` bit 0: written without a decimal
            /// point (the machine may scale such values).
            WordK = 0x31, "wordk" { addr: Addr, k: Const, flags: U8 };
            /// Set the comment text of the current block (operator message).
            SetMsg = 0x32, "setmsg" { s: Str };
            /// Execute the block built since the last `Exec`.
            Exec = 0x33, "exec" { flags: U8 };
            /// Execute the typed block whose record starts at byte `rec` of
            /// the `Blocks` section: its words, all known at compile time,
            /// go to the kernel as one block (no `wordk` run, no `exec`).
            Block = 0x34, "block" { rec: Rec };
            /// Hand the typed block at `rec` to the kernel as a G70–G73
            /// profile block for the cycle that follows (as `exec` with its
            /// profile flag), its tag being this pc.
            Profile = 0x35, "profile" { rec: Rec };
            /// Execute the typed block at `rec` as a plain move: its words
            /// are X/Z/U/W, F, N and an arc's R or I/K, each at most once,
            /// and at most one G written as 0–3 (the verifier checks), so
            /// the kernel reads them without its general block parse.
            Move = 0x36, "move" { rec: Rec };
            /// Execute the block built since the last `exec` as a plain
            /// move whose words are computed: the compiler emits it for a
            /// block of X/Z/U/W, F, N and an arc's R or I/K, each at most
            /// once, with at most one G written as 0–3, so the kernel
            /// reads its words with the short parse of `move`. (Words
            /// computed at run time cannot be checked here: the kernel's
            /// short parse hands any other block to its general one.)
            ExecMove = 0x37, "execmove";

            // --- calls ---
            /// `M98 P… L count`: call a subprogram known at compile time.
            CallSub = 0x40, "callsub" { prog: Prog, count: Reg };
            /// `M98` with a computed program number.
            CallSubDyn = 0x41, "callsubdyn" { num: Reg, count: Reg };
            /// `M98 P…` computed without L: `num` is `<count:4><program:4>`
            /// (count 0: once), split when it runs; vacant is E5009.
            CallSubPacked = 0x4A, "callsubpacked" { num: Reg };
            /// `G65 P… L count`: macro call, new local variable level, the
            /// arguments set by the preceding `Arg`s.
            CallMacro = 0x42, "callmacro" { prog: Prog, count: Reg };
            /// `G65` with a computed program number.
            CallMacroDyn = 0x43, "callmacrodyn" { num: Reg, count: Reg };
            /// Set argument `#var` (1..=33) of the next macro call.
            Arg = 0x44, "arg" { var: ArgVar, src: Reg };
            /// `G66`: call the macro after every following move block.
            ModalCall = 0x45, "modalcall" { prog: Prog, count: Reg };
            /// `G66` with a computed program number.
            ModalCallDyn = 0x46, "modalcalldyn" { num: Reg, count: Reg };
            /// `G67`: cancel the modal call.
            ModalCancel = 0x47, "modalcancel";
            /// `M99`: return to the caller.
            Ret = 0x48, "ret";
            /// `M99 P seq`: return and continue at a sequence number of the
            /// caller.
            RetSeq = 0x49, "retseq" { seq: Reg };

            // --- stopping ---
            /// An alarm the compiler proved will happen (`E5001` → 5001).
            Alarm = 0x50, "alarm" { code: U16, msg: Str };
            /// `G65 H99 Q…` with a computed Q: alarm 500 + Q (Q rounded,
            /// vacant as 0; outside 0…99 a value out of range, E5010).
            UserAlarm = 0x52, "useralarm" { q: Reg, msg: Str };
            /// End of the main program.
            Halt = 0x51, "halt";
        }
    };
}

pub(crate) use for_each_instr;
