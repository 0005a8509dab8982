//! The range of every machine-file value (the table of `docs/machine.md`),
//! and where a key stands in the file so that an out-of-range value is
//! reported at its line and column.
//!
//! The bounds keep a value meaningful (a rate above 0, a count of tools
//! that fits a two-digit T word) and keep what is sized or counted by it
//! small (the look-ahead queue, the offset table); NaN and infinity are out
//! of every range.

use alloc::format;
use alloc::string::String;
use alloc::vec::Vec;

use crate::base::machine::{LinearAxis, Machine, Xz};

/// A key whose value is out of its range.
#[derive(Debug, Clone, PartialEq)]
pub struct BadKey {
    /// The dotted key, `[[…]]` entries numbered from 0: `axes.z.min_mm`,
    /// `tools.offset[1].radius`.
    pub key: String,
    pub msg: String,
}

type Check = Result<(), BadKey>;

fn bad(key: &str, msg: String) -> Check {
    Err(BadKey {
        key: key.into(),
        msg,
    })
}

/// A finite value in `lo ..= hi`.
fn within(key: &str, v: f64, lo: f64, hi: f64) -> Check {
    if v.is_finite() && (lo..=hi).contains(&v) {
        Ok(())
    } else {
        bad(key, format!("{v} is outside {lo} … {hi}"))
    }
}

/// A finite value above 0 and at most `hi` (a rate, a time, a size).
fn positive(key: &str, v: f64, hi: f64) -> Check {
    if v.is_finite() && v > 0.0 && v <= hi {
        Ok(())
    } else {
        bad(key, format!("{v} must be above 0 and at most {hi}"))
    }
}

/// A whole number in `lo ..= hi`.
fn count(key: &str, v: u64, lo: u64, hi: u64) -> Check {
    if (lo..=hi).contains(&v) {
        Ok(())
    } else {
        bad(key, format!("{v} is outside {lo} … {hi}"))
    }
}

/// Largest coordinate, offset or limit: a lathe of ±1 km would be odd.
const MAX_MM: f64 = 1.0e6;
/// Largest linear rate (mm/min) or acceleration (mm/s²).
const MAX_RATE: f64 = 1.0e6;
/// Largest jerk (mm/s³).
const MAX_JERK: f64 = 1.0e9;
/// Rotary rates are in degrees: 360 times the linear ones leave room.
const MAX_DEG_RATE: f64 = 1.0e7;
const MAX_DEG_JERK: f64 = 1.0e10;
/// Each look-ahead slot costs about 336 bytes, and the queue holds four
/// times the look-ahead: 16384 blocks is about 22 MB.
pub const MAX_LOOKAHEAD: u64 = 16384;
/// The offset table of the kernel (#2001…#2032, #2701…#2732).
pub const MAX_OFFSETS: u64 = 32;
/// The most a slide's compensation adds to the drive's command, mm (its
/// lost motion, a pitch correction): far more than any screw worth
/// compensating needs.
pub const MAX_COMP_MM: f64 = 2.0;
/// The most a rotary axis's compensation adds, degrees (its lost motion,
/// an angular correction): far more than any worm gear worth
/// compensating needs.
pub const MAX_COMP_DEG: f64 = 2.0;

/// The most points of a pitch error table (a laser calibration takes one
/// every 10–50 mm of a stroke of at most a few metres).
pub const MAX_PITCH_POINTS: usize = 1024;

/// The steepest a pitch error table may change between two points: a
/// micrometre a millimetre (a thousandth of a degree a degree on C). A
/// screw is far straighter; the drive's command then moves within 0.1 %
/// of the set point's speed.
pub const MAX_PITCH_SLOPE: f64 = 1e-3;

/// The axis a pitch error table corrects.
#[derive(Clone, Copy, PartialEq)]
enum TableAxis {
    /// X or Z: positions within ±[`MAX_MM`], corrections in mm.
    Slide,
    /// C: angles in one turn, 0 ≤ angle < 360, corrections in degrees;
    /// the table repeats every turn, so its last point leads on to its
    /// first one turn on.
    Rotary,
}

impl TableAxis {
    fn unit(self) -> &'static str {
        match self {
            TableAxis::Slide => "mm",
            TableAxis::Rotary => "°",
        }
    }
}

/// A pitch error table: none, or at least two points in ascending
/// position, each correction within [`MAX_COMP_MM`] ([`MAX_COMP_DEG`]),
/// the slope between two within [`MAX_PITCH_SLOPE`].
fn pitch_comp(key: &str, table: &[Vec<f64>], axis: TableAxis) -> Check {
    if table.len() == 1 || table.len() > MAX_PITCH_POINTS {
        let n = table.len();
        return bad(
            key,
            format!("{n} points: give none, or 2 … {MAX_PITCH_POINTS}"),
        );
    }
    let mut points = Vec::with_capacity(table.len() + 1);
    for (i, point) in table.iter().enumerate() {
        let &[at, add] = point.as_slice() else {
            let n = point.len();
            return bad(
                key,
                format!("point {i} gives {n} number(s): give [position, correction]"),
            );
        };
        table_point(&format!("{key}[{i}]"), at, add, axis)?;
        points.push([at, add]);
    }
    // A turn's table leads on from its last point to its first.
    if let (TableAxis::Rotary, Some(&[at, add])) = (axis, points.first()) {
        points.push([at + 360.0, add]);
    }
    for (i, w) in points.windows(2).enumerate() {
        let ([a, ca], [b, cb]) = (w[0], w[1]);
        let next = i + 1;
        if b <= a {
            let why = format!("point {next} at {b} is not past point {i} at {a}");
            return bad(key, format!("{why}: give the points in ascending position"));
        }
        let slope = libm::round((cb - ca) / (b - a) * 1e6) / 1e6;
        if slope.abs() > MAX_PITCH_SLOPE {
            let u = axis.unit();
            let why = format!("from {a} to {b} the correction changes {slope} {u} a {u}");
            return bad(key, format!("{why}, more than {MAX_PITCH_SLOPE}"));
        }
    }
    Ok(())
}

/// One point of a pitch error table: its position and correction in range.
fn table_point(key: &str, at: f64, add: f64, axis: TableAxis) -> Check {
    let max_add = match axis {
        TableAxis::Slide => {
            within(&format!("{key} position"), at, -MAX_MM, MAX_MM)?;
            MAX_COMP_MM
        }
        TableAxis::Rotary => {
            if !(0.0..360.0).contains(&at) {
                let why = format!("angle {at} is not within one turn");
                return bad(key, format!("{why}: give 0 ≤ angle < 360 (360 is 0)"));
            }
            MAX_COMP_DEG
        }
    };
    within(&format!("{key} correction"), add, -max_add, max_add)
}

/// A T word is tool × 100 + offset: two digits of tool.
pub const MAX_TOOLS: u64 = 99;

fn xz(key: &str, p: Xz) -> Check {
    within(&format!("{key}.x"), p.x, -MAX_MM, MAX_MM)?;
    within(&format!("{key}.z"), p.z, -MAX_MM, MAX_MM)
}

fn linear_axis(name: &str, a: &LinearAxis) -> Check {
    let k = |f: &str| format!("axes.{name}.{f}");
    positive(&k("rapid_mm_min"), a.rapid_mm_min, MAX_RATE)?;
    positive(&k("max_feed_mm_min"), a.max_feed_mm_min, MAX_RATE)?;
    positive(&k("accel_mm_s2"), a.accel_mm_s2, MAX_RATE)?;
    positive(&k("jerk_mm_s3"), a.jerk_mm_s3, MAX_JERK)?;
    within(&k("min_mm"), a.min_mm, -MAX_MM, MAX_MM)?;
    within(&k("max_mm"), a.max_mm, -MAX_MM, MAX_MM)?;
    within(&k("backlash_mm"), a.backlash_mm, 0.0, MAX_COMP_MM)?;
    pitch_comp(&k("pitch_comp_mm"), &a.pitch_comp_mm, TableAxis::Slide)?;
    if a.min_mm >= a.max_mm {
        return bad(
            &k("min_mm"),
            format!("{} must be below max_mm ({})", a.min_mm, a.max_mm),
        );
    }
    Ok(())
}

/// Every key's range; the first key out of range.
pub fn check(m: &Machine) -> Check {
    let s = &m.machine;
    within(
        "machine.interpolation_period_ms",
        s.interpolation_period_ms,
        0.125,
        8.0,
    )?;
    positive("machine.resolution_mm", s.resolution_mm, 1.0)?;
    positive("machine.arc_tolerance_mm", s.arc_tolerance_mm, 100.0)?;
    count(
        "machine.lookahead_blocks",
        s.lookahead_blocks.into(),
        1,
        MAX_LOOKAHEAD,
    )?;
    linear_axis("x", &m.axes.x)?;
    linear_axis("z", &m.axes.z)?;
    let c = &m.axes.c;
    count("axes.c.attribute", c.attribute.into(), 0, 255)?;
    positive("axes.c.rapid_deg_min", c.rapid_deg_min, MAX_DEG_RATE)?;
    positive("axes.c.max_feed_deg_min", c.max_feed_deg_min, MAX_DEG_RATE)?;
    positive("axes.c.accel_deg_s2", c.accel_deg_s2, MAX_DEG_RATE)?;
    positive("axes.c.jerk_deg_s3", c.jerk_deg_s3, MAX_DEG_JERK)?;
    within("axes.c.backlash_deg", c.backlash_deg, 0.0, MAX_COMP_DEG)?;
    pitch_comp(
        "axes.c.pitch_comp_deg",
        &c.pitch_comp_deg,
        TableAxis::Rotary,
    )?;
    if !(c.name.len() == 1 && c.name.bytes().all(|b| b.is_ascii_uppercase())) {
        return bad(
            "axes.c.name",
            format!("\"{}\" must be one letter A…Z", c.name),
        );
    }
    positive("feed.max_mm_min", m.feed.max_mm_min, MAX_RATE)?;
    spindle(m)?;
    let t = &m.threads;
    count("threads.pullout_tenths", t.pullout_tenths.into(), 0, 255)?;
    positive("threads.max_lead_mm", t.max_lead_mm, 10_000.0)?;
    count(
        "threads.repair_deviation_inc",
        t.repair_deviation_inc.into(),
        0,
        1_000_000,
    )?;
    within(
        "cycles.g71_retract_mm",
        m.cycles.g71_retract_mm,
        0.0,
        1000.0,
    )?;
    let co = &m.coords;
    for (name, p) in [
        ("exofs", co.exofs),
        ("g54", co.g54),
        ("g55", co.g55),
        ("g56", co.g56),
        ("g57", co.g57),
        ("g58", co.g58),
        ("g59", co.g59),
    ] {
        xz(&format!("coords.{name}"), p)?;
    }
    let r = &m.reference_points;
    positive(
        "reference_points.return_feed_mm_min",
        r.return_feed_mm_min,
        MAX_RATE,
    )?;
    xz("reference_points.second", r.second)?;
    xz("reference_points.third", r.third)?;
    xz("reference_points.fourth", r.fourth)?;
    let me = &m.measure;
    positive("measure.feed_mm_min", me.feed_mm_min, MAX_RATE)?;
    within("measure.gamma_x_mm", me.gamma_x_mm, 0.0, 1000.0)?;
    within("measure.gamma_z_mm", me.gamma_z_mm, 0.0, 1000.0)?;
    within("measure.epsilon_x_mm", me.epsilon_x_mm, 0.0, 1000.0)?;
    within("measure.epsilon_z_mm", me.epsilon_z_mm, 0.0, 1000.0)?;
    for (i, &input) in m.skip.inputs.iter().enumerate() {
        count(&format!("skip.inputs[{i}]"), input.into(), 0, 15)?;
    }
    xz("stroke_check_2.plus", m.stroke_check_2.plus)?;
    xz("stroke_check_2.minus", m.stroke_check_2.minus)?;
    count("polar.linear_axis", m.polar.linear_axis.into(), 1, 8)?;
    count("polar.rotary_axis", m.polar.rotary_axis.into(), 1, 8)?;
    tools(m)?;
    for (i, &g) in m.r#macro.g_code_macros.iter().enumerate() {
        count(&format!("macro.g_code_macros[{i}]"), g.into(), 0, 999)?;
    }
    let o = &m.operator;
    within(
        "operator.feed_override_pct",
        o.feed_override_pct,
        0.0,
        150.0,
    )?;
    within(
        "operator.rapid_override_pct",
        o.rapid_override_pct,
        0.0,
        100.0,
    )?;
    within(
        "operator.spindle_override_pct",
        o.spindle_override_pct,
        50.0,
        120.0,
    )?;
    host(m)?;
    count("run.max_blocks", m.run.max_blocks, 1, 1_000_000_000_000)?;
    positive("run.max_time_s", m.run.max_time_s, 1.0e6)
}

fn spindle(m: &Machine) -> Check {
    let s = &m.spindle;
    positive("spindle.max_rpm", s.max_rpm, 1.0e6)?;
    within("spindle.min_rpm", s.min_rpm, 0.0, s.max_rpm)?;
    positive("spindle.accel_rpm_s", s.accel_rpm_s, 1.0e7)?;
    count("spindle.encoder_ppr", s.encoder_ppr.into(), 1, 1_000_000)?;
    positive("spindle.stall_timeout_s", s.stall_timeout_s, 3600.0)
}

fn tools(m: &Machine) -> Check {
    let t = &m.tools;
    count("tools.count", t.count.into(), 1, MAX_TOOLS)?;
    count("tools.offsets", t.offsets.into(), 1, MAX_OFFSETS)?;
    let mut seen: Vec<u32> = Vec::with_capacity(t.offset.len().min(MAX_OFFSETS as usize));
    for (i, off) in t.offset.iter().enumerate() {
        let k = |f: &str| format!("tools.offset[{i}].{f}");
        count(&k("number"), off.number.into(), 1, t.offsets.into())?;
        if seen.contains(&off.number) {
            return bad(
                &k("number"),
                format!("offset {} is listed twice", off.number),
            );
        }
        seen.push(off.number);
        count(&k("tip"), off.tip.into(), 0, 9)?;
        within(&k("x"), off.x, -MAX_MM, MAX_MM)?;
        within(&k("z"), off.z, -MAX_MM, MAX_MM)?;
        within(&k("radius"), off.radius, 0.0, 1000.0)?;
        within(&k("wear_x"), off.wear_x, -MAX_MM, MAX_MM)?;
        within(&k("wear_z"), off.wear_z, -MAX_MM, MAX_MM)?;
        within(&k("wear_radius"), off.wear_radius, -1000.0, 1000.0)?;
    }
    Ok(())
}

/// The days of month `mo` (1–12) of year `y` (Gregorian).
fn days_in(y: u32, mo: u32) -> u32 {
    match mo {
        2 if (y.is_multiple_of(4) && !y.is_multiple_of(100)) || y.is_multiple_of(400) => 29,
        2 => 28,
        4 | 6 | 9 | 11 => 30,
        _ => 31,
    }
}

fn host(m: &Machine) -> Check {
    let h = &m.host;
    count("host.inputs", h.inputs.into(), 0, 0xffff)?;
    let (y, mo, d) = (h.date / 10000, h.date / 100 % 100, h.date % 100);
    if !((1..=9999).contains(&y) && (1..=12).contains(&mo) && (1..=days_in(y, mo)).contains(&d)) {
        return bad("host.date", format!("{} is not a date YYYYMMDD", h.date));
    }
    let (hh, mm, ss) = (h.time / 10000, h.time / 100 % 100, h.time % 100);
    if !(hh <= 23 && mm <= 59 && ss <= 59) {
        return bad("host.time", format!("{} is not a time HHMMSS", h.time));
    }
    Ok(())
}

/// Line and column (from 1) of `key` in a TOML `text`, found line by
/// line: `[table]` and `[[array]]` headers, `key = value` lines and the
/// keys of a one-line inline table (`second = { x = 1, z = nan }`).
/// Files that spell a key otherwise (dotted keys, multi-line values) get
/// no position; the message still names the key.
pub fn locate(text: &str, key: &str) -> Option<(usize, usize)> {
    let mut table = String::new();
    let mut arrays: Vec<(String, usize)> = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let trimmed = line.trim_start();
        let indent = line.len() - trimmed.len();
        if let Some(h) = trimmed.strip_prefix("[[") {
            let name = h.split("]]").next().unwrap_or("").trim();
            let i = match arrays.iter_mut().find(|(a, _)| a == name) {
                Some((_, i)) => {
                    *i += 1;
                    *i
                }
                None => {
                    arrays.push((name.into(), 0));
                    0
                }
            };
            table = format!("{name}[{i}]");
            continue;
        }
        if let Some(h) = trimmed.strip_prefix('[') {
            table = h.split(']').next().unwrap_or("").trim().into();
            continue;
        }
        let Some((k, rest)) = trimmed.split_once('=') else {
            continue;
        };
        let k = k.trim().trim_matches('"');
        let full = if table.is_empty() {
            k.into()
        } else {
            format!("{table}.{k}")
        };
        let col = |byte: usize| line[..byte].chars().count() + 1;
        if full == key || key.starts_with(&format!("{full}[")) {
            return Some((n + 1, col(indent)));
        }
        if let Some(inner) = key.strip_prefix(&format!("{full}.")) {
            // One field of an inline table.
            let value_at = line.len() - rest.len();
            let at = find_key(rest, inner).map_or(indent, |i| value_at + i);
            return Some((n + 1, col(at)));
        }
    }
    None
}

/// Byte offset of `name` as a key (followed by `=`) in an inline table.
fn find_key(text: &str, name: &str) -> Option<usize> {
    let mut from = 0;
    while let Some(i) = text[from..].find(name) {
        let at = from + i;
        let before = text[..at].chars().next_back();
        let after = text[at + name.len()..].trim_start();
        if matches!(before, Some('{' | ',' | ' ' | '\t')) && after.starts_with('=') {
            return Some(at);
        }
        from = at + name.len();
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_reference_is_in_range_and_each_kind_of_bad_value_is_not() {
        assert_eq!(check(&Machine::reference()), Ok(()));
        let key_of = |edit: fn(&mut Machine)| {
            let mut m = Machine::reference();
            edit(&mut m);
            check(&m).map_err(|b| b.key)
        };
        let nan = key_of(|m| m.axes.z.min_mm = f64::NAN);
        assert_eq!(nan, Err("axes.z.min_mm".into()));
        let inf = key_of(|m| m.reference_points.second.z = f64::INFINITY);
        assert_eq!(inf, Err("reference_points.second.z".into()));
        let zero = key_of(|m| m.spindle.encoder_ppr = 0);
        assert_eq!(zero, Err("spindle.encoder_ppr".into()));
        let huge = key_of(|m| m.machine.lookahead_blocks = u32::MAX);
        assert_eq!(huge, Err("machine.lookahead_blocks".into()));
        let negative = key_of(|m| m.spindle.stall_timeout_s = -1.0);
        assert_eq!(negative, Err("spindle.stall_timeout_s".into()));
        // The bounds themselves are in range.
        assert_eq!(key_of(|m| m.machine.lookahead_blocks = 16384), Ok(()));
        assert_eq!(key_of(|m| m.operator.feed_override_pct = 0.0), Ok(()));
        // No 30 February; 29 February in a leap year only (2000 is one,
        // 1900 is not).
        assert_eq!(key_of(|m| m.host.date = 20000230), Err("host.date".into()));
        assert_eq!(key_of(|m| m.host.date = 19000229), Err("host.date".into()));
        assert_eq!(key_of(|m| m.host.date = 20240431), Err("host.date".into()));
        assert_eq!(key_of(|m| m.host.date = 20000229), Ok(()));
        assert_eq!(key_of(|m| m.host.date = 20241231), Ok(()));
    }

    #[test]
    fn keys_are_found_in_tables_arrays_and_inline_tables() {
        let text = "[machine]\nlookahead_blocks = 5\n\n[reference_points]\nsecond = { x = 1.0, z = nan }\n\
                    [[tools.offset]]\nnumber = 1\n[[tools.offset]]\n  number = 1\n";
        assert_eq!(locate(text, "machine.lookahead_blocks"), Some((2, 1)));
        // `z` of the inline table: column 21 of line 5 (counted by hand).
        assert_eq!(locate(text, "reference_points.second.z"), Some((5, 21)));
        assert_eq!(locate(text, "tools.offset[1].number"), Some((9, 3)));
        assert_eq!(locate(text, "tools.offset[0].number"), Some((7, 1)));
        assert_eq!(locate(text, "axes.x.min_mm"), None);
    }
}
