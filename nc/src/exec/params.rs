//! The parameters of machine.md §2 by number, as `G10 L52` reads and
//! writes them (dialect.md §4.9): each number maps to the machine-file
//! field of its TOML key, in that key's unit. Bit parameters travel as an
//! eight-digit 0/1 number, bit 7 first (`00010000` is bit 4 set).
//!
//! Writes change the kernel's machine for the rest of the run. Bits that
//! machine.md gives no meaning (e.g. №172.0) have no field: they read 0
//! and a write to them is dropped.

use alloc::format;
use alloc::string::ToString;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::gcode;
use crate::base::machine::{ChamferType, Machine, Units, Xz};
use crate::block::round_half_away;
use crate::exec::Nc;

/// Is `n` a parameter of machine.md §2?
pub fn exists(n: u32) -> bool {
    is_bits(n)
        || matches!(
            n,
            19 | 22
                | 27
                | 86..=95
                | 100
                | 101
                | 113
                | 121..=123
                | 141..=145
                | 148..=151
                | 191
                | 225
                | 230
                | 235
                | 236
        )
}

/// Bit parameters (written №nnn.b in machine.md).
pub fn is_bits(n: u32) -> bool {
    matches!(n, 1 | 5 | 7 | 12 | 172 | 174 | 181 | 185 | 202)
}

/// Reads parameter `n` (`axis` is the P word, when written).
pub fn read(nc: &Nc, n: u32, axis: Option<f64>) -> Result<f64, NcError> {
    if is_bits(n) {
        return Ok(bits_to_number(read_bits(nc, n)));
    }
    let m = &nc.machine;
    let v = match n {
        19 => m.threads.pullout_tenths as f64,
        22 => match axis_of(n, axis, &[1, 2, 3])? {
            1 => m.axes.x.rapid_mm_min,
            2 => m.axes.z.rapid_mm_min,
            _ => m.axes.c.rapid_deg_min,
        },
        // №027 without P is the path limit, with P the limit of one axis.
        27 if axis.is_none() => m.feed.max_mm_min,
        27 => match axis_of(n, axis, &[1, 2, 3])? {
            1 => m.axes.x.max_feed_mm_min,
            2 => m.axes.z.max_feed_mm_min,
            _ => m.axes.c.max_feed_deg_min,
        },
        86..=95 => m.r#macro.g_code_macros[(n - 86) as usize] as f64,
        100 | 101 | 121..=123 => {
            let xz = xz_of(m, n);
            match axis_of(n, axis, &[1, 2])? {
                1 => xz.x,
                _ => xz.z,
            }
        }
        113 => m.reference_points.return_feed_mm_min,
        141 => m.measure.feed_mm_min,
        142 => m.measure.gamma_x_mm,
        143 => m.measure.gamma_z_mm,
        144 => m.measure.epsilon_x_mm,
        145 => m.measure.epsilon_z_mm,
        148..=151 => m.skip.inputs[(n - 148) as usize] as f64,
        191 => m.threads.repair_deviation_inc as f64,
        225 => {
            c_axis_only(n, axis)?;
            m.axes.c.name.bytes().next().map_or(0.0, f64::from)
        }
        230 => {
            c_axis_only(n, axis)?;
            m.axes.c.attribute as f64
        }
        235 => m.polar.linear_axis as f64,
        236 => m.polar.rotary_axis as f64,
        _ => return unknown(n),
    };
    Ok(v)
}

/// Writes `v` into parameter `n`. A value the machine file would refuse
/// (a rate of 0, say) is refused here too (E5010) and nothing changes.
pub fn write(nc: &mut Nc, n: u32, axis: Option<f64>, v: f64) -> Result<(), NcError> {
    if !v.is_finite() {
        return fail(
            Alarm::ValueOutOfRange,
            format!("№{n:03} cannot be set to {v}"),
        );
    }
    if is_bits(n) {
        let byte = number_to_bits(n, v)?;
        write_bits(nc, n, byte);
        return Ok(());
    }
    let before = nc.machine.clone();
    write_value(nc, n, axis, v)?;
    if let Err(e) = nc.machine.validate() {
        nc.machine = before;
        return fail(Alarm::ValueOutOfRange, format!("№{n:03} = {v}: {e}"));
    }
    Ok(())
}

fn write_value(nc: &mut Nc, n: u32, axis: Option<f64>, v: f64) -> Result<(), NcError> {
    let m = &mut nc.machine;
    match n {
        19 => m.threads.pullout_tenths = count(n, v)?,
        22 => match axis_of(n, axis, &[1, 2, 3])? {
            1 => m.axes.x.rapid_mm_min = v,
            2 => m.axes.z.rapid_mm_min = v,
            _ => m.axes.c.rapid_deg_min = v,
        },
        27 if axis.is_none() => m.feed.max_mm_min = v,
        27 => match axis_of(n, axis, &[1, 2, 3])? {
            1 => m.axes.x.max_feed_mm_min = v,
            2 => m.axes.z.max_feed_mm_min = v,
            _ => m.axes.c.max_feed_deg_min = v,
        },
        // The compiler binds G codes to O9010…O9019 when it compiles the
        // program; a run-time change could not reach those calls.
        86..=95 => {
            return fail(
                Alarm::NotSupportedYet,
                format!(
                    "writing №{n:03}: the G-code macro table is fixed when the program is compiled"
                ),
            )
        }
        100 | 101 | 121..=123 => {
            let first = axis_of(n, axis, &[1, 2])? == 1;
            let xz = xz_of_mut(m, n);
            if first {
                xz.x = v;
            } else {
                xz.z = v;
            }
        }
        113 => m.reference_points.return_feed_mm_min = v,
        141 => m.measure.feed_mm_min = v,
        142 => m.measure.gamma_x_mm = v,
        143 => m.measure.gamma_z_mm = v,
        144 => m.measure.epsilon_x_mm = v,
        145 => m.measure.epsilon_z_mm = v,
        148..=151 => m.skip.inputs[(n - 148) as usize] = count(n, v)?,
        191 => m.threads.repair_deviation_inc = count(n, v)?,
        225 => {
            c_axis_only(n, axis)?;
            let code = round_half_away(v);
            if !(65.0..=90.0).contains(&code) {
                return fail(
                    Alarm::ValueOutOfRange,
                    format!("№225 = {code}: an axis name is a letter A…Z (65…90)"),
                );
            }
            m.axes.c.name = ((code as u8) as char).to_string();
        }
        230 => {
            c_axis_only(n, axis)?;
            m.axes.c.attribute = count(n, v)?;
        }
        235 => m.polar.linear_axis = count(n, v)?,
        236 => m.polar.rotary_axis = count(n, v)?,
        _ => return unknown(n),
    }
    Ok(())
}

fn unknown<T>(n: u32) -> Result<T, NcError> {
    fail(
        Alarm::UnknownParameterAtRun,
        format!("there is no parameter №{n:03} on this machine (machine.md §2)"),
    )
}

/// The X/Z pair of №100, №101, №121–123.
fn xz_of(m: &Machine, n: u32) -> Xz {
    match n {
        100 => m.stroke_check_2.plus,
        101 => m.stroke_check_2.minus,
        121 => m.reference_points.second,
        122 => m.reference_points.third,
        _ => m.reference_points.fourth,
    }
}

fn xz_of_mut(m: &mut Machine, n: u32) -> &mut Xz {
    match n {
        100 => &mut m.stroke_check_2.plus,
        101 => &mut m.stroke_check_2.minus,
        121 => &mut m.reference_points.second,
        122 => &mut m.reference_points.third,
        _ => &mut m.reference_points.fourth,
    }
}

/// The axis (1 X, 2 Z, 3 C) that P names for an axis parameter; the
/// parameter has values only for `allowed`.
fn axis_of(n: u32, p: Option<f64>, allowed: &[u32]) -> Result<u32, NcError> {
    let Some(p) = p else {
        return fail(
            Alarm::MissingWord,
            format!("№{n:03} is an axis parameter: P1 (X), P2 (Z) or P3 (C) names the axis"),
        );
    };
    let a = round_half_away(p);
    if !(1.0..=3.0).contains(&a) {
        return fail(
            Alarm::ValueOutOfRange,
            format!("P{a}: the axes are P1 (X), P2 (Z), P3 (C)"),
        );
    }
    let a = a as u32;
    if !allowed.contains(&a) {
        return fail(
            Alarm::ValueOutOfRange,
            format!("№{n:03} has no value for axis P{a}"),
        );
    }
    Ok(a)
}

/// №225 and №230 describe the added (third) axis: P3 or no P.
fn c_axis_only(n: u32, p: Option<f64>) -> Result<(), NcError> {
    match p {
        None => Ok(()),
        Some(_) => axis_of(n, p, &[3]).map(|_| ()),
    }
}

/// A count or number field: a non-negative integer.
fn count(n: u32, v: f64) -> Result<u32, NcError> {
    let r = round_half_away(v);
    if !(0.0..=u32::MAX as f64).contains(&r) {
        return fail(
            Alarm::ValueOutOfRange,
            format!("№{n:03} takes a whole number ≥ 0, not {v}"),
        );
    }
    Ok(r as u32)
}

fn read_bits(nc: &Nc, n: u32) -> u8 {
    let m = &nc.machine;
    let b = |on: bool, bit: u8| u8::from(on) << bit;
    match n {
        // №001.0 follows G20/G21 (seed 000: executing G20/G21 changes it).
        1 => b(nc.st.inch(), 0) | b(m.axes.x.diameter, 2),
        5 => b(m.coords.ppd, 1),
        7 => b(m.motion.always_exact_stop, 5),
        12 => b(m.coords.aprs, 7),
        172 => b(m.stroke_check_2.forbid_outside, 2) | b(m.stroke_check_2.enabled, 4),
        174 => b(m.threads.repair_enabled, 4) | b(m.threads.repair_interpolating, 5),
        181 => b(m.cycles.chamfer_type == ChamferType::II, 0),
        185 => b(m.measure.overrides_apply, 6) | b(m.measure.signal_active_low, 7),
        202 => b(m.threads.arc_thread_rigid, 7),
        _ => 0,
    }
}

fn write_bits(nc: &mut Nc, n: u32, byte: u8) {
    let on = |bit: u8| (byte >> bit) & 1 == 1;
    let m = &mut nc.machine;
    match n {
        1 => {
            // Setting №001.0 changes the G20/G21 mode too (seed 000).
            let inch = on(0);
            m.machine.power_on_units = if inch { Units::Inch } else { Units::Mm };
            nc.st.modal.units = if inch {
                gcode::Units::Inch
            } else {
                gcode::Units::Metric
            };
            // Bit 2 off: radius programming, for the X words read from
            // now on (the kernel keeps X as a radius either way).
            m.axes.x.diameter = on(2);
        }
        5 => m.coords.ppd = on(1),
        7 => m.motion.always_exact_stop = on(5),
        12 => m.coords.aprs = on(7),
        172 => {
            m.stroke_check_2.forbid_outside = on(2);
            m.stroke_check_2.enabled = on(4);
        }
        174 => {
            m.threads.repair_enabled = on(4);
            m.threads.repair_interpolating = on(5);
        }
        181 => {
            m.cycles.chamfer_type = if on(0) {
                ChamferType::II
            } else {
                ChamferType::I
            }
        }
        185 => {
            m.measure.overrides_apply = on(6);
            m.measure.signal_active_low = on(7);
        }
        202 => m.threads.arc_thread_rigid = on(7),
        _ => {}
    }
}

/// Bits 7…0 as the decimal digits of a number: bit 4 alone is 10000.
pub fn bits_to_number(byte: u8) -> f64 {
    (0..8)
        .rev()
        .fold(0.0, |acc, bit| acc * 10.0 + f64::from((byte >> bit) & 1))
}

/// The inverse of [`bits_to_number`]: every decimal digit must be 0 or 1,
/// at most eight of them.
pub fn number_to_bits(n: u32, v: f64) -> Result<u8, NcError> {
    let bad = || {
        fail(
            Alarm::ValueOutOfRange,
            format!(
                "№{n:03} is a bit parameter: write eight digits 0 or 1, bit 7 first (not {})",
                crate::base::event::Num(v)
            ),
        )
    };
    let mut rest = round_half_away(v);
    if !(0.0..=11_111_111.0).contains(&rest) || rest != v {
        return bad();
    }
    let mut byte = 0u8;
    for bit in 0..8 {
        let digit = rest % 10.0;
        if digit > 1.0 {
            return bad();
        }
        byte |= (digit as u8) << bit;
        rest = libm::floor(rest / 10.0);
    }
    Ok(byte)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bit_numbers_read_bit_7_first() {
        assert_eq!(bits_to_number(0b0001_0000), 10000.0);
        assert_eq!(bits_to_number(0b1000_0001), 10000001.0);
        assert_eq!(bits_to_number(0), 0.0);
        assert_eq!(number_to_bits(172, 10100.0), Ok(0b0001_0100));
        assert_eq!(number_to_bits(172, 11111111.0), Ok(0xff));
        assert_eq!(number_to_bits(172, 120.0).unwrap_err().code, 5010);
        assert_eq!(number_to_bits(172, 111111111.0).unwrap_err().code, 5010);
        assert_eq!(number_to_bits(172, 1.5).unwrap_err().code, 5010);
    }

    #[test]
    fn the_reference_values_read_back() {
        let nc = Nc::new(Machine::reference());
        // №172: bit 4 (enabled) set, bit 2 (forbid outside) clear.
        assert_eq!(read(&nc, 172, None), Ok(10000.0));
        // №001: bit 2 (X diameter) set, mm.
        assert_eq!(read(&nc, 1, None), Ok(100.0));
        // №181.0 = 1 (chamfer type II).
        assert_eq!(read(&nc, 181, None), Ok(1.0));
        assert_eq!(read(&nc, 22, Some(2.0)), Ok(10000.0));
        assert_eq!(read(&nc, 27, None), Ok(5000.0));
        assert_eq!(read(&nc, 27, Some(1.0)), Ok(4000.0));
        assert_eq!(read(&nc, 121, Some(1.0)), Ok(-50.0));
        assert_eq!(read(&nc, 123, Some(2.0)), Ok(-300.0));
        assert_eq!(read(&nc, 150, None), Ok(2.0));
        assert_eq!(read(&nc, 225, None), Ok(67.0));
        assert_eq!(read(&nc, 22, None).unwrap_err().code, 2006);
        assert_eq!(read(&nc, 100, Some(3.0)).unwrap_err().code, 5010);
        assert_eq!(read(&nc, 999, None).unwrap_err().code, 7008);
    }

    #[test]
    fn writes_change_the_machine_and_bad_values_change_nothing() {
        let mut nc = Nc::new(Machine::reference());
        write(&mut nc, 172, None, 10100.0).unwrap();
        assert!(nc.machine.stroke_check_2.forbid_outside);
        assert!(nc.machine.stroke_check_2.enabled);
        write(&mut nc, 181, None, 0.0).unwrap();
        assert_eq!(nc.machine.cycles.chamfer_type, ChamferType::I);
        write(&mut nc, 113, None, 2500.0).unwrap();
        assert_eq!(read(&nc, 113, None), Ok(2500.0));
        assert_eq!(write(&mut nc, 22, Some(1.0), 0.0).unwrap_err().code, 5010);
        assert_eq!(nc.machine.axes.x.rapid_mm_min, 6000.0);
        assert_eq!(write(&mut nc, 86, None, 120.0).unwrap_err().code, 2099);
        // №001.0 = 1 selects inch, like G20.
        write(&mut nc, 1, None, 101.0).unwrap();
        assert!(nc.st.inch());
        // №001.2 = 0 is radius programming; 1 is the diameter again.
        write(&mut nc, 1, None, 1.0).unwrap();
        assert!(!nc.machine.axes.x.diameter);
        assert_eq!(read(&nc, 1, None), Ok(1.0));
        write(&mut nc, 1, None, 100.0).unwrap();
        assert!(nc.machine.axes.x.diameter);
    }
}
