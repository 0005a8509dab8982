//! The production counters through the C interface: the part counter
//! and the tool life of the machine file's groups carry from part to
//! part, on a machine whose M30 rewinds (cycle start runs the next part).
//! The expected counts are counted by hand from the program: each part
//! is one `T0199` (one use of group 1's current tool) and one M30 (one
//! part).

mod periods;

use gbc::*;
use periods::*;
use std::ptr::null_mut;

/// Group 1: tools 101 and 202, each good for two uses.
const LIFE: &str =
    "[[tool_life.group]]\nnumber = 1\nlife = 2\nunit = \"count\"\ntools = [101, 202]\n";

/// A part: the counter read at its start, a tool of group 1, one cut.
const PART: &str = "#100=#3901\nT0199\nG00 X40 Z2\nG01 Z-20 F300\nG00 X60 Z2\nM30\n";

fn machine_text(rewinds: bool) -> String {
    format!("[run]\nm30_rewinds = {rewinds}\n{LIFE}")
}

fn module(src: &str, machine: &str) -> Vec<u8> {
    let opts = compiler::Options {
        machine: nc::Machine::from_toml(machine).expect("a machine file"),
        ..compiler::Options::default()
    };
    let out = compiler::compile("part.nc", src.as_bytes(), &opts);
    out.module.expect("compiles").to_bytes()
}

/// A controller of the machine (M30 rewinding or not), no program yet.
fn controller(rewinds: bool) -> (GbcMachine, GbcController) {
    controller_on(&machine_text(rewinds))
}

fn load(c: GbcController, src: &str, rewinds: bool) {
    let prog = module(src, &machine_text(rewinds));
    assert_eq!(
        unsafe { gbc_controller_load(c, prog.as_ptr(), prog.len()) },
        GbcStatus::Ok
    );
}

/// A controller with `PART` loaded.
fn loaded(rewinds: bool) -> (GbcMachine, GbcController) {
    let (m, c) = controller(rewinds);
    load(c, PART, rewinds);
    (m, c)
}

/// Cycle start, then every period until the program has ended (after
/// running, not the end it stood at before the cycle start); a last
/// run-ahead then sees the end, and the counters have the part. The set
/// point of the last period.
fn part(c: GbcController) -> GbcSetPoint {
    assert_eq!(gbc_cycle_start(c), GbcStatus::Ok);
    let mut left_end = false;
    for _ in 0..400_000 {
        let (sp, st) = period(c);
        match st {
            GbcRunState::Ended if left_end => {
                assert_eq!(gbc_run_ahead(c), GbcStatus::Ok);
                return sp;
            }
            GbcRunState::Ended => {}
            GbcRunState::Alarm | GbcRunState::Stopped => panic!("{st:?}"),
            _ => left_end = true,
        }
    }
    panic!("the part did not end");
}

/// Cycle start and periods until the X axis has left X0: the part is
/// under way, and the VM has read it to its M30 long before.
fn into_the_part(c: GbcController) {
    assert_eq!(gbc_cycle_start(c), GbcStatus::Ok);
    for _ in 0..400_000 {
        if period(c).0.x > 10.0 {
            return;
        }
    }
    panic!("never moved");
}

/// Reset, and periods until the controller is idle.
fn reset(c: GbcController) {
    assert_eq!(gbc_reset(c), GbcStatus::Ok);
    for _ in 0..100_000 {
        if state(c) == GbcRunState::Idle {
            return;
        }
        period(c);
    }
    panic!("the reset did not finish");
}

fn parts(c: GbcController) -> (f64, f64) {
    let mut p = GbcParts {
        machined: f64::NAN,
        required: f64::NAN,
    };
    assert_eq!(unsafe { gbc_parts(c, &mut p) }, GbcStatus::Ok);
    (p.machined, p.required)
}

fn set_parts(c: GbcController, machined: f64, required: f64) -> GbcStatus {
    gbc_set_parts(c, GbcParts { machined, required })
}

fn reached(c: GbcController) -> bool {
    let mut out = false;
    assert_eq!(unsafe { gbc_parts_reached(c, &mut out) }, GbcStatus::Ok);
    out
}

const UNREAD: GbcToolLife = GbcToolLife {
    tool: 7,
    life: -7.0,
    used: -7.0,
    unit: 7,
    current: true,
};

fn tool_life(c: GbcController, group: u32, slot: u32) -> Result<GbcToolLife, GbcStatus> {
    let mut out = UNREAD;
    match unsafe { gbc_tool_life(c, group, slot, &mut out) } {
        GbcStatus::Ok => Ok(out),
        s => {
            assert_eq!(out, UNREAD, "nothing written on {s:?}");
            Err(s)
        }
    }
}

/// The uses of group 1's tools, and the slot its last `T0199` selected.
fn used(c: GbcController) -> ([f64; 2], Option<u32>) {
    let mut u = [f64::NAN; 2];
    let mut current = None;
    for slot in 0..2u32 {
        let t = tool_life(c, 1, slot).expect("group 1 has two tools");
        u[slot as usize] = t.used;
        if t.current {
            assert_eq!(current, None, "one current tool");
            current = Some(slot);
        }
    }
    (u, current)
}

#[test]
fn cycle_start_after_m30_runs_the_next_part_and_counts_it() {
    let (m, c) = loaded(true);
    assert_eq!(parts(c), (0.0, 0.0));
    assert_eq!(used(c), ([0.0, 0.0], None));
    // Part 1: T0199 takes tool 1 (its first use); the part ends at X60 Z2.
    let sp = part(c);
    assert_eq!((sp.x, sp.z, sp.tool), (60.0, 2.0, 1));
    assert_eq!(parts(c), (1.0, 0.0));
    assert_eq!(used(c), ([1.0, 0.0], Some(0)));
    // Part 2, with no reset between: tool 1's second use.
    let sp = part(c);
    assert_eq!(sp.tool, 1);
    assert_eq!(parts(c), (2.0, 0.0));
    assert_eq!(used(c), ([2.0, 0.0], Some(0)));
    // Part 3: tool 1 has had its two uses, T0199 takes tool 2.
    let sp = part(c);
    assert_eq!(sp.tool, 2);
    assert_eq!(parts(c), (3.0, 0.0));
    assert_eq!(used(c), ([2.0, 1.0], Some(1)));
    assert!(!reached(c), "no count required");
    free(m, c);
}

#[test]
fn without_the_key_cycle_start_after_m30_waits_for_a_reset() {
    let (m, c) = loaded(false);
    part(c);
    assert_eq!(gbc_cycle_start(c), GbcStatus::Ok);
    for _ in 0..100 {
        assert_eq!(period(c).1, GbcRunState::Ended);
    }
    assert_eq!(parts(c), (1.0, 0.0));
    // After a reset the next part counts on.
    reset(c);
    part(c);
    assert_eq!(parts(c), (2.0, 0.0));
    assert_eq!(used(c), ([2.0, 0.0], Some(0)));
    free(m, c);
}

#[test]
fn the_required_count_is_reached_and_bad_parts_are_refused() {
    let (m, c) = loaded(true);
    assert_eq!(set_parts(c, 10.0, 12.0), GbcStatus::Ok);
    assert_eq!(parts(c), (10.0, 12.0));
    assert!(!reached(c));
    part(c);
    assert_eq!(parts(c), (11.0, 12.0));
    assert!(!reached(c));
    part(c);
    assert_eq!(parts(c), (12.0, 12.0));
    assert!(reached(c));
    // Not whole, negative, NaN, nine digits: refused, nothing changed.
    let bad = [(1.5, 0.0), (-1.0, 0.0), (0.0, f64::NAN), (1e8, 0.0)];
    for (machined, required) in bad {
        assert_eq!(
            set_parts(c, machined, required),
            GbcStatus::InvalidArgument,
            "{machined} {required}"
        );
        let text = last_error();
        assert!(
            text.contains("part counters") && text.contains("whole numbers"),
            "{text}"
        );
    }
    assert_eq!(parts(c), (12.0, 12.0));
    assert!(reached(c));
    // Over the required count it stays reached; 0 required is none.
    part(c);
    assert_eq!(parts(c), (13.0, 12.0));
    assert!(reached(c));
    assert_eq!(set_parts(c, 13.0, 0.0), GbcStatus::Ok);
    assert!(!reached(c));
    free(m, c);
}

#[test]
fn a_part_count_set_while_running_gets_the_parts_m30() {
    let (m, c) = loaded(true);
    into_the_part(c);
    assert_eq!(set_parts(c, 0.0, 5.0), GbcStatus::Ok);
    assert_eq!(parts(c), (0.0, 5.0), "the page has it at once");
    // The run counts on the operator's 0: its M30 makes it 1.
    let mut left = 0;
    while period(c).1 != GbcRunState::Ended {
        left += 1;
        assert!(left < 400_000, "did not end");
    }
    assert_eq!(gbc_run_ahead(c), GbcStatus::Ok);
    assert_eq!(parts(c), (1.0, 5.0));
    assert_eq!(used(c), ([1.0, 0.0], Some(0)));
    free(m, c);
}

#[test]
fn tool_life_is_read_slot_by_slot_until_refused() {
    let (m, c) = loaded(true);
    let first = tool_life(c, 1, 0).expect("slot 0");
    assert_eq!(
        first,
        GbcToolLife {
            tool: 101,
            life: 2.0,
            used: 0.0,
            unit: GBC_LIFE_COUNT,
            current: false
        }
    );
    let second = tool_life(c, 1, 1).expect("slot 1");
    assert_eq!((second.tool, second.life, second.used), (202, 2.0, 0.0));
    assert_eq!(tool_life(c, 1, 2), Err(GbcStatus::InvalidArgument));
    assert!(last_error().contains("slot 2"), "{}", last_error());
    assert_eq!(tool_life(c, 1, u32::MAX), Err(GbcStatus::InvalidArgument));
    assert_eq!(tool_life(c, 9, 0), Err(GbcStatus::InvalidArgument));
    let text = last_error();
    assert!(text.contains("group 9") && text.contains(": 1)"), "{text}");
    assert_eq!(
        unsafe { gbc_tool_life(c, 1, 0, null_mut()) },
        GbcStatus::NullPointer
    );
    free(m, c);
}

#[test]
fn a_minutes_group_says_its_unit() {
    let text = "[[tool_life.group]]\nnumber = 3\nlife = 45.5\nunit = \"minutes\"\ntools = [505]\n";
    let (m, c) = controller_on(text);
    let t = tool_life(c, 3, 0).expect("before a program too");
    assert_eq!((t.tool, t.life, t.unit), (505, 45.5, GBC_LIFE_MINUTES));
    assert_eq!(tool_life(c, 1, 0), Err(GbcStatus::InvalidArgument));
    free(m, c);
}

#[test]
fn a_use_set_by_the_host_moves_on_to_the_next_tool() {
    let (m, c) = loaded(true);
    // Tool 1 worn out (its two uses), set while idle.
    assert_eq!(gbc_set_tool_life_used(c, 1, 0, 2.0), GbcStatus::Ok);
    assert_eq!(used(c), ([2.0, 0.0], None));
    let sp = part(c);
    assert_eq!(sp.tool, 2);
    assert_eq!(parts(c), (1.0, 0.0));
    assert_eq!(used(c), ([2.0, 1.0], Some(1)));
    // Refused, changing nothing: no slot 2, no group 9, a use that is
    // negative or not finite.
    let arg = GbcStatus::InvalidArgument;
    assert_eq!(gbc_set_tool_life_used(c, 1, 2, 0.0), arg);
    assert!(last_error().contains("slot 2"), "{}", last_error());
    assert_eq!(gbc_set_tool_life_used(c, 9, 0, 0.0), arg);
    assert!(last_error().contains("group 9"), "{}", last_error());
    for bad in [-1.0, f64::NAN, f64::INFINITY] {
        assert_eq!(gbc_set_tool_life_used(c, 1, 1, bad), arg, "{bad}");
        let text = last_error();
        assert!(
            text.contains("tool-life group 1 slot 1") && text.contains("negative"),
            "{text}"
        );
    }
    assert_eq!(used(c), ([2.0, 1.0], Some(1)));
    // Back to unused (a new insert in slot 0): the next part takes it.
    assert_eq!(gbc_set_tool_life_used(c, 1, 0, 0.0), GbcStatus::Ok);
    assert_eq!(used(c), ([0.0, 1.0], Some(1)));
    let sp = part(c);
    assert_eq!(sp.tool, 1);
    assert_eq!(used(c), ([1.0, 1.0], Some(0)));
    free(m, c);
}

/// A host restores what it kept over a power-off before loading the
/// program: the counters set on the controller carry into it.
#[test]
fn counters_set_before_the_load_are_the_programs() {
    let (m, c) = controller(true);
    assert_eq!(parts(c), (0.0, 0.0));
    assert!(!reached(c));
    assert_eq!(used(c), ([0.0, 0.0], None));
    assert_eq!(set_parts(c, 7.0, 8.0), GbcStatus::Ok);
    assert_eq!(gbc_set_tool_life_used(c, 1, 0, 2.0), GbcStatus::Ok);
    // Refused before a program as after.
    let arg = GbcStatus::InvalidArgument;
    assert_eq!(set_parts(c, 1.5, 0.0), arg);
    assert!(last_error().contains("whole numbers"), "{}", last_error());
    assert_eq!(gbc_set_tool_life_used(c, 1, 1, -1.0), arg);
    assert_eq!(gbc_set_tool_life_used(c, 1, 2, 0.0), arg);
    assert_eq!(gbc_renew_tool_life(c, 9), arg);
    assert!(last_error().contains("group 9"), "{}", last_error());
    assert_eq!(parts(c), (7.0, 8.0));
    assert_eq!(used(c), ([2.0, 0.0], None));
    load(c, PART, true);
    assert_eq!(parts(c), (7.0, 8.0));
    assert_eq!(used(c), ([2.0, 0.0], None));
    // Tool 1 is worn out: the part takes tool 2 and is the eighth.
    let sp = part(c);
    assert_eq!(sp.tool, 2);
    assert_eq!(parts(c), (8.0, 8.0));
    assert!(reached(c));
    assert_eq!(used(c), ([2.0, 1.0], Some(1)));
    free(m, c);
}

#[test]
fn renewing_a_group_starts_again_at_its_first_tool() {
    let (m, c) = loaded(true);
    for _ in 0..3 {
        part(c);
    }
    assert_eq!(used(c), ([2.0, 1.0], Some(1)));
    assert_eq!(gbc_renew_tool_life(c, 1), GbcStatus::Ok);
    assert_eq!(used(c), ([0.0, 0.0], None));
    assert_eq!(gbc_renew_tool_life(c, 9), GbcStatus::InvalidArgument);
    assert!(last_error().contains("group 9"), "{}", last_error());
    let sp = part(c);
    assert_eq!(sp.tool, 1);
    assert_eq!(parts(c), (4.0, 0.0));
    assert_eq!(used(c), ([1.0, 0.0], Some(0)));
    free(m, c);
}

/// A part a reset abandons counts nothing; the counters stay over the
/// reset and over another program selected after it.
#[test]
fn the_counters_outlive_a_reset_and_a_select() {
    let (m, c) = loaded(true);
    part(c);
    into_the_part(c);
    reset(c);
    assert_eq!(gbc_run_ahead(c), GbcStatus::Ok);
    assert_eq!(parts(c), (1.0, 0.0), "the abandoned part");
    assert_eq!(used(c), ([1.0, 0.0], Some(0)));
    part(c);
    assert_eq!(parts(c), (2.0, 0.0));
    reset(c);
    let other = module("T0199\nG00 X50 Z5\nM30\n", &machine_text(true));
    assert_eq!(
        unsafe { gbc_controller_select(c, other.as_ptr(), other.len()) },
        GbcStatus::Ok
    );
    assert_eq!(parts(c), (2.0, 0.0));
    let sp = part(c);
    assert_eq!((sp.x, sp.z, sp.tool), (50.0, 5.0, 2));
    assert_eq!(parts(c), (3.0, 0.0));
    assert_eq!(used(c), ([2.0, 1.0], Some(1)));
    free(m, c);
}

#[test]
fn null_pointers_and_bad_handles_are_refused() {
    let (m, c) = loaded(true);
    let null = GbcStatus::NullPointer;
    unsafe {
        assert_eq!(gbc_parts(c, null_mut()), null);
        assert_eq!(gbc_parts_reached(c, null_mut()), null);
        assert_eq!(gbc_tool_life(c, 1, 0, null_mut()), null);
    }
    assert!(last_error().contains("null"), "{}", last_error());
    // A bad handle is reported before a bad argument.
    let mut p = GbcParts {
        machined: 5.0,
        required: 5.0,
    };
    let mut yes = true;
    let mut t = UNREAD;
    for h in [0, m, c | (0x5a << 24)] {
        let status = if h == m {
            GbcStatus::WrongKind
        } else {
            GbcStatus::InvalidHandle
        };
        unsafe {
            assert_eq!(gbc_parts(h, &mut p), status);
            assert_eq!(gbc_parts_reached(h, &mut yes), status);
            assert_eq!(gbc_tool_life(h, 9, 0, &mut t), status);
            assert_eq!(gbc_parts(h, null_mut()), status);
        }
        assert_eq!(set_parts(h, f64::NAN, 0.0), status);
        assert_eq!(gbc_set_tool_life_used(h, 9, 5, f64::NAN), status);
        assert_eq!(gbc_renew_tool_life(h, 9), status);
    }
    assert_eq!((p.machined, p.required, yes, t), (5.0, 5.0, true, UNREAD));
    free(m, c);
}
