//! Random sequences of C calls, as a careless or confused host makes
//! them: the operator's signals in any state, pages edited mid-run,
//! restarts and MDI at odd moments, a split in the middle, calls on the
//! wrong half, bad arguments. Whatever the order, no call panics inside
//! the library (`GBC_STATUS_PANIC`), every call returns a status of the
//! enum, and the controller still ticks afterwards. `CAPI_CASES` sets the
//! number of sequences (default 48).

mod periods;

use gbc::*;
use periods::{blank, controller_on};
use proptest::prelude::*;
use std::ffi::c_char;

/// A program with a bit of everything a sequence may meet: a tool, the
/// spindle, a macro loop with a message stop in it, a thread cycle.
const PROGRAM: &str = "O0001\nT0101\nG97 S800 M03\nG00 X50 Z2\n#1=0\nWHILE[#1LT2]DO1\nG99 G01 Z[-5-#1] F0.2\n#3006=1(CHECK)\n#1=#1+1\nEND1\nG00 X52 Z2\nG92 X48 Z-20 F1.5\nG00 X100 Z100\nM30\n";

/// The other program a selection loads.
const OTHER: &str = "O0002\nG00 X20 Z5\nG98 G01 Z-5 F300\nM30\n";

#[derive(Debug, Clone)]
enum Op {
    Tick(u16),
    RunAhead,
    CycleStart,
    FeedHold,
    Reset,
    Override(f64),
    Switch(u8, bool),
    Jog(u8, bool, f64),
    Step(u8, f64),
    Home(u8),
    ManualStop,
    Mdi(usize),
    Restart(u32, u32),
    RestartResult,
    ToolOffset(u32, f64),
    Measure(u32, u8, f64),
    Variable(u32, f64),
    BlockSkip(u8, bool),
    Select,
    Split,
    /// A call on the half that does not take it (or on both).
    Crossed(u8),
    Read(u8),
}

const MDI: [&str; 3] = ["G00 X30 Z10", "M03 S500\nG04 X0.1", "G01 X"];

fn number() -> impl Strategy<Value = f64> {
    prop_oneof![
        -200.0..200.0f64,
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(-1e300),
        Just(0.0),
    ]
}

fn op() -> impl Strategy<Value = Op> {
    prop_oneof![
        4 => (1u16..600).prop_map(Op::Tick),
        3 => Just(Op::RunAhead),
        2 => Just(Op::CycleStart),
        1 => Just(Op::FeedHold),
        1 => Just(Op::Reset),
        1 => number().prop_map(Op::Override),
        1 => (0u8..6, any::<bool>()).prop_map(|(s, on)| Op::Switch(s, on)),
        1 => (0u8..4, any::<bool>(), number()).prop_map(|(a, p, f)| Op::Jog(a, p, f)),
        1 => (0u8..4, number()).prop_map(|(a, d)| Op::Step(a, d)),
        1 => (0u8..4).prop_map(Op::Home),
        1 => Just(Op::ManualStop),
        1 => (0..MDI.len()).prop_map(Op::Mdi),
        1 => (0u32..16, 0u32..3).prop_map(|(l, p)| Op::Restart(l, p)),
        1 => Just(Op::RestartResult),
        1 => (0u32..40, number()).prop_map(|(n, v)| Op::ToolOffset(n, v)),
        1 => (0u32..4, 0u8..3, number()).prop_map(|(n, a, v)| Op::Measure(n, a, v)),
        1 => (prop_oneof![Just(1u32), Just(500), Just(999), Just(5021), Just(100_000)], number())
            .prop_map(|(n, v)| Op::Variable(n, v)),
        1 => (0u8..11, any::<bool>()).prop_map(|(n, on)| Op::BlockSkip(n, on)),
        1 => Just(Op::Select),
        1 => Just(Op::Split),
        1 => (0u8..6).prop_map(Op::Crossed),
        2 => (0u8..7).prop_map(Op::Read),
    ]
}

fn module(src: &str) -> Vec<u8> {
    let out = compiler::compile("p.nc", src.as_bytes(), &compiler::Options::default());
    out.module.expect("compiles").to_bytes()
}

/// The controller under test: the program side's handle and, once
/// split, the real-time half's.
struct Host {
    c: GbcController,
    rt: Option<GbcController>,
    other: Vec<u8>,
}

impl Host {
    /// The handle the motion side's calls take.
    fn motion(&self) -> GbcController {
        self.rt.unwrap_or(self.c)
    }

    fn run(&mut self, op: &Op) -> Vec<GbcStatus> {
        let (c, m) = (self.c, self.motion());
        match *op {
            Op::Tick(n) => (0..n)
                .map(|_| unsafe { gbc_tick(m, &mut blank()) })
                .collect(),
            Op::RunAhead => vec![gbc_run_ahead(c)],
            Op::CycleStart => vec![gbc_cycle_start(m)],
            Op::FeedHold => vec![gbc_feed_hold(m)],
            Op::Reset => vec![gbc_reset(m)],
            Op::Override(v) => vec![
                gbc_set_feed_override(m, v),
                gbc_set_rapid_override(m, v),
                gbc_set_spindle_override(m, v),
            ],
            Op::Switch(s, on) => vec![match s {
                0 => gbc_set_single_block(m, on),
                1 => gbc_set_optional_stop(m, on),
                2 => gbc_set_dry_run(m, on),
                3 => gbc_set_machine_lock(m, on),
                4 => gbc_set_aux_lock(m, on),
                _ => gbc_set_skip_input(m, on),
            }],
            Op::Jog(a, plus, f) => vec![gbc_jog(m, a, plus, f)],
            Op::Step(a, d) => vec![gbc_jog_step(m, a, d, 0.0)],
            Op::Home(a) => vec![gbc_home(m, a)],
            Op::ManualStop => vec![gbc_manual_stop(m)],
            Op::Mdi(i) => {
                let text = MDI[i];
                vec![unsafe { gbc_mdi(c, text.as_ptr().cast(), text.len()) }]
            }
            Op::Restart(line, pass) => vec![gbc_restart_from(c, line, pass)],
            Op::RestartResult => vec![gbc_restart_result(c)],
            Op::ToolOffset(n, v) => {
                let l = GbcOffsetLengths {
                    x: v,
                    z: v / 2.0,
                    wear_x: 0.0,
                    wear_z: 0.0,
                };
                vec![unsafe { gbc_set_tool_offset(c, n, &l) }]
            }
            Op::Measure(n, axis, v) => vec![gbc_measure_tool_offset(c, n, axis, v)],
            Op::Variable(n, v) => {
                let mut out = 0.0;
                vec![gbc_set_variable(c, n, v), unsafe {
                    gbc_variable(c, n, &mut out)
                }]
            }
            Op::BlockSkip(n, on) => vec![gbc_set_block_skip(c, n, on)],
            Op::Select => {
                let p = &self.other;
                vec![unsafe { gbc_controller_select(c, p.as_ptr(), p.len()) }]
            }
            Op::Split => {
                let mut rt = 0;
                let s = unsafe { gbc_controller_split(c, &mut rt) };
                if s == GbcStatus::Ok {
                    self.rt = Some(rt);
                }
                vec![s]
            }
            Op::Crossed(k) => self.crossed(k),
            Op::Read(k) => self.read(k),
        }
    }

    /// Calls a split controller's halves do not take (on a whole
    /// controller they are ordinary calls).
    fn crossed(&self, k: u8) -> Vec<GbcStatus> {
        let (c, m) = (self.c, self.motion());
        match k {
            0 => vec![unsafe { gbc_tick(c, &mut blank()) }],
            1 => vec![gbc_run_ahead(m)],
            2 => vec![gbc_set_feed_override(c, 50.0)],
            3 => vec![gbc_set_variable(m, 500, 1.0)],
            4 => vec![gbc_restart_result(m)],
            _ => vec![gbc_realtime_free(c)],
        }
    }

    /// The screen's reads, on both handles.
    fn read(&self, k: u8) -> Vec<GbcStatus> {
        let mut out = Vec::new();
        for h in [self.c, self.motion()] {
            out.push(match k {
                0 => unsafe { gbc_active_codes(h, &mut std::mem::zeroed()) },
                1 => {
                    let (mut x, mut z) = (0.0, 0.0);
                    unsafe { gbc_distance_to_go(h, &mut x, &mut z) }
                }
                2 => {
                    let mut i = 0;
                    unsafe { gbc_message_index(h, &mut i) }
                }
                3 => {
                    let mut buf = [0 as c_char; 32];
                    unsafe {
                        gbc_message_at(h, 0, buf.as_mut_ptr(), buf.len(), std::ptr::null_mut())
                    }
                }
                4 => {
                    let (mut x, mut z) = (0.0, 0.0);
                    unsafe { gbc_restart_destination(h, &mut x, &mut z) }
                }
                5 => unsafe { gbc_take_room_warning(h, &mut std::mem::zeroed()) },
                _ => unsafe { gbc_alarm(h, &mut std::mem::zeroed()) },
            });
        }
        out
    }

    fn free(self) {
        if let Some(rt) = self.rt {
            assert_eq!(gbc_realtime_free(rt), GbcStatus::Ok);
        }
        assert_eq!(gbc_controller_free(self.c), GbcStatus::Ok);
    }
}

fn cases() -> u32 {
    std::env::var("CAPI_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(48)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases()))]

    #[test]
    fn no_sequence_of_calls_panics(ops in prop::collection::vec(op(), 1..60)) {
        let (m, c) = controller_on("[[tools.offset]]\nnumber = 1\nx = 1.0\nz = 2.0\n");
        let prog = module(PROGRAM);
        prop_assert_eq!(unsafe { gbc_controller_load(c, prog.as_ptr(), prog.len()) }, GbcStatus::Ok);
        let mut host = Host { c, rt: None, other: module(OTHER) };
        for op in &ops {
            for s in host.run(op) {
                prop_assert_ne!(s, GbcStatus::Panic, "{:?}", op);
            }
        }
        // Still alive: a reset, and the motion ticks again.
        let motion = host.motion();
        prop_assert_eq!(gbc_reset(motion), GbcStatus::Ok);
        for _ in 0..2000 {
            let s = unsafe { gbc_tick(motion, &mut blank()) };
            prop_assert!(s == GbcStatus::Ok || s == GbcStatus::Alarm, "{:?}", s);
            prop_assert_eq!(gbc_run_ahead(host.c), GbcStatus::Ok);
        }
        host.free();
        prop_assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
    }
}
