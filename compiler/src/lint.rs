//! Warnings a block's words show by themselves (dialect.md §8): W106, two
//! G codes of one modal group; W109, G28/G30 without an axis word.

use crate::build::Builder as Gen;
use crate::words::{round_g, Split, WordValue};
use nc::gcode;

const G: u8 = b'G' - b'A';

/// The block's literal G codes as the kernel codes them, with their words.
fn g_codes<'s>(split: &'s Split<'_>) -> impl Iterator<Item = (u16, &'s crate::words::NcWord<'s>)> {
    split.nc.iter().filter_map(|w| match (w.addr, &w.value) {
        (G, WordValue::Literal(v, _)) => Some((round_g(*v), w)),
        _ => None,
    })
}

/// W106 and W109 for one block.
pub fn block(gen: &mut Gen<'_>, split: &Split<'_>) {
    let mut codes = g_codes(split);
    let Some((first, _)) = codes.next() else {
        return;
    };
    if codes.next().is_none() {
        // One G code, the usual block: no two of a group, and W109 only
        // for G28/G30 itself.
        if matches!(first, 280 | 300) {
            home_without_axes(gen, split);
        }
        return;
    }
    same_group(gen, split);
    home_without_axes(gen, split);
}

/// W106: two codes of one modal group; the last one written wins (§3).
/// Two group-00 codes are E2002, checked by the kernel.
fn same_group(gen: &mut Gen<'_>, split: &Split<'_>) {
    // (No list of the codes: this runs for every block, most of which
    // hold one G code or none.)
    for (i, (code, w)) in g_codes(split).enumerate().skip(1) {
        let Some(group) = gcode::group(code).filter(|&g| g != gcode::ONE_SHOT) else {
            continue;
        };
        let earlier = g_codes(split)
            .take(i)
            .filter(|(c, _)| gcode::group(*c) == Some(group))
            .last();
        if let Some((first, _)) = earlier {
            gen.warn(
                "W106",
                w.span,
                format!(
                    "{} and {} are in the same modal group: the last one, {}, wins",
                    gcode::name(first),
                    gcode::name(code),
                    gcode::name(code)
                ),
            );
        }
    }
}

/// W109: G28/G30 without X, Z, U, W (or C, H on a machine with a C axis):
/// no axis returns (§4.5).
fn home_without_axes(gen: &mut Gen<'_>, split: &Split<'_>) {
    let Some((code, w)) = g_codes(split).find(|(c, _)| matches!(c, 280 | 300)) else {
        return;
    };
    let c_axis = gen.machine.axes.c.enabled;
    let axis = split.nc.iter().any(|w| match w.addr + b'A' {
        b'X' | b'Z' | b'U' | b'W' => true,
        b'C' | b'H' => c_axis,
        _ => false,
    });
    if !axis {
        gen.warn(
            "W109",
            w.span,
            format!(
                "{} names no axis, so no axis returns: write the axes that should go (e.g. U0 W0)",
                gcode::name(code)
            ),
        );
    }
}
