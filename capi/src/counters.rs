//! The production counters (`runtime::Controller::counters`,
//! `set_parts`, `renew_tool_life`, `restore_counters`): the parts machined
//! and required (#3901, #3902) and the uses of the machine file's
//! tool-life groups, which carry from part to part.
//!
//! Before a program is loaded the counters are the controller's own
//! (zero parts and the groups unused, or what the host set or restored),
//! which the program loaded later starts from, as the offset page is
//! kept for it; once one is loaded, that program's controller has them
//! and keeps them over resets, restarts and `gbc_controller_select`.

use crate::offsets::refused;
use crate::{fail, put, with_ctl, Ctl, Failure, GbcController, GbcStatus};
use runtime::{Counters, LifeGroup, LifeUnit, Parts};

/// [`GbcToolLife::unit`]: the group's life is a number of uses (each
/// `Txx99` that selects the tool counts one).
pub const GBC_LIFE_COUNT: u32 = 0;
/// [`GbcToolLife::unit`]: the group's life is minutes of cutting (the
/// feed moves made while the tool is the group's selected one).
pub const GBC_LIFE_MINUTES: u32 = 1;

/// The part counters: parts machined (#3901, which M30 adds one to) and
/// parts required (#3902; 0: none set). Whole numbers 0 … 99 999 999.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GbcParts {
    /// Parts machined.
    pub machined: f64,
    /// Parts required.
    pub required: f64,
}

/// One tool of a tool-life group (the machine file's
/// `[[tool_life.group]]`), as the finished runs and the operator's edits
/// left it.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GbcToolLife {
    /// The tool's T value, tool × 100 + offset (101: tool 1, offset 1).
    pub tool: u32,
    /// The group's life, in its unit.
    pub life: f64,
    /// What the tool has used, in the group's unit; at `life` it is worn
    /// out and `Txx99` takes the group's next tool.
    pub used: f64,
    /// [`GBC_LIFE_COUNT`] or [`GBC_LIFE_MINUTES`].
    pub unit: u32,
    /// The tool is the one the group's last `Txx99` selected.
    pub current: bool,
}

/// The counters as the runs start with them: the program's, or the
/// controller's own before one is loaded.
fn counters(c: &Ctl) -> &Counters {
    match (&c.interp, &c.run) {
        (Some(i), _) => i.counters(),
        (None, Some(r)) => r.counters(),
        (None, None) => &c.counters,
    }
}

/// The part counters as the finished runs and the operator's edits left
/// them: a run's counting is kept when the motion reaches the program's
/// end (seen at the next `gbc_run_ahead`); a run a reset or an alarm
/// abandons counts nothing. The program reads #3901 as the counter stood
/// when its run began.
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn gbc_parts(controller: GbcController, out: *mut GbcParts) -> GbcStatus {
    with_ctl(controller, |c| {
        let p = counters(c).parts;
        let parts = GbcParts {
            machined: p.machined,
            required: p.required,
        };
        // SAFETY: the caller's promise.
        unsafe { put(out, parts) }
    })
}

/// Sets the part counters, as the operator does on the setting page: at
/// once while the controller is idle (a program not yet started starts
/// afresh with them); while a program runs, it keeps counting from what
/// it started with, and its M30 then adds one to this value (0 set during
/// a part reads 1 after it). Before a program is loaded they are kept
/// for it. Refused with [`GbcStatus::InvalidArgument`], changing nothing,
/// unless both are whole numbers 0 … 99 999 999 (`gbc_last_error` says
/// why).
#[no_mangle]
pub extern "C" fn gbc_set_parts(controller: GbcController, parts: GbcParts) -> GbcStatus {
    with_ctl(controller, |c| {
        let parts = Parts {
            machined: parts.machined,
            required: parts.required,
        };
        let r = match c.program() {
            Ok(mut p) => p.set_parts(parts),
            Err(_) => parts.check().map(|()| c.counters.parts = parts),
        };
        r.map_err(|e| refused("the part counters", e))
    })
}

/// Whether the required count is set and reached (parts required above 0
/// and parts machined at least that): a control's "parts reached"
/// signal, to `*out`. What the machine does then is the host's.
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn gbc_parts_reached(controller: GbcController, out: *mut bool) -> GbcStatus {
    with_ctl(controller, |c| {
        let reached = counters(c).parts.reached();
        // SAFETY: the caller's promise.
        unsafe { put(out, reached) }
    })
}

/// The tool in `slot` (0 for the group's first tool, in the machine
/// file's order) of tool-life group `group_number`, with its use, as the
/// finished runs and the operator's edits left it. A group the machine
/// file does not have, or a slot past its last tool:
/// [`GbcStatus::InvalidArgument`], so a host reads a group's tools from
/// slot 0 until it gets that.
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn gbc_tool_life(
    controller: GbcController,
    group_number: u32,
    slot: u32,
    out: *mut GbcToolLife,
) -> GbcStatus {
    with_ctl(controller, |c| {
        if out.is_null() {
            return Err(fail(GbcStatus::NullPointer, "the output pointer is null"));
        }
        let g = group(counters(c), group_number)?;
        let i = tool_index(g, slot)?;
        let (Some(&tool), Some(&used)) = (g.tools.get(i), g.used.get(i)) else {
            return Err(no_slot(g, slot));
        };
        let life = GbcToolLife {
            tool,
            life: g.life,
            used,
            unit: match g.unit {
                LifeUnit::Count => GBC_LIFE_COUNT,
                LifeUnit::Minutes => GBC_LIFE_MINUTES,
            },
            current: g.current == Some(i),
        };
        // SAFETY: checked non-null; the caller's promise.
        unsafe { put(out, life) }
    })
}

/// Sets what the tool in `slot` of tool-life group `group_number` has
/// used (in the group's unit): a host gives back, after power-on, the
/// uses it kept, or the operator corrects one. It holds as
/// `gbc_set_parts`'s counters do (a running program's use is added to
/// it when the program ends). Refused with [`GbcStatus::InvalidArgument`],
/// changing nothing, for a group or slot `gbc_tool_life` refuses or a use
/// that is negative or not finite.
#[no_mangle]
pub extern "C" fn gbc_set_tool_life_used(
    controller: GbcController,
    group_number: u32,
    slot: u32,
    used: f64,
) -> GbcStatus {
    with_ctl(controller, |c| {
        let mut next = counters(c).clone();
        let gi = next
            .life
            .iter()
            .position(|g| g.number == group_number)
            .ok_or_else(|| no_group(counters(c), group_number))?;
        let g = &mut next.life[gi];
        let i = tool_index(g, slot)?;
        let Some(u) = g.used.get_mut(i) else {
            return Err(no_slot(g, slot));
        };
        *u = used;
        let r = match c.program() {
            Ok(mut p) => p.restore_counters(next),
            Err(_) => next.check_fits(&c.counters).map(|()| c.counters = next),
        };
        r.map_err(|e| refused(&format!("tool-life group {group_number} slot {slot}"), e))
    })
}

/// Renews tool-life group `group_number` (the operator changed its
/// inserts): its tools unused and none selected, so the next `Txx99`
/// takes its first tool. It holds as `gbc_set_parts`'s counters do. A
/// group the machine file does not have: [`GbcStatus::InvalidArgument`].
#[no_mangle]
pub extern "C" fn gbc_renew_tool_life(controller: GbcController, group_number: u32) -> GbcStatus {
    with_ctl(controller, |c| {
        let r = match c.program() {
            Ok(mut p) => p.renew_tool_life(group_number),
            Err(_) => c.counters.renew_group(group_number),
        };
        r.map_err(|e| refused(&format!("tool-life group {group_number}"), e))
    })
}

/// Tool-life group `number` of the counters.
fn group(c: &Counters, number: u32) -> Result<&LifeGroup, Failure> {
    c.life
        .iter()
        .find(|g| g.number == number)
        .ok_or_else(|| no_group(c, number))
}

/// The index of `slot` in group `g`'s tools.
fn tool_index(g: &LifeGroup, slot: u32) -> Result<usize, Failure> {
    match usize::try_from(slot) {
        Ok(i) if i < g.tools.len() => Ok(i),
        _ => Err(no_slot(g, slot)),
    }
}

fn no_group(c: &Counters, number: u32) -> Failure {
    let numbers: Vec<String> = c.life.iter().map(|g| g.number.to_string()).collect();
    let have = if numbers.is_empty() {
        "none".to_string()
    } else {
        numbers.join(", ")
    };
    fail(
        GbcStatus::InvalidArgument,
        format!(
            "the machine file has no tool-life group {number} \
             ([[tool_life.group]] numbers: {have})"
        ),
    )
}

fn no_slot(g: &LifeGroup, slot: u32) -> Failure {
    fail(
        GbcStatus::InvalidArgument,
        format!(
            "tool-life group {} has {} tools: slot {slot} is past its last (slots count from 0)",
            g.number,
            g.tools.len()
        ),
    )
}
