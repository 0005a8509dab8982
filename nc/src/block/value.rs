//! Macro values (dialect.md §7.4–§7.6): the arithmetic, functions and
//! comparisons with their vacant rules. The VM evaluates with these and the
//! compiler folds constants with them, so both agree bit for bit.
//!
//! A value is an `f64`; the vacant value is [`VACANT`], a NaN. Results that
//! are not finite are alarms (E5006), so a NaN never means anything else.

use alloc::format;

use crate::base::error::{fail, Alarm, NcError};
use crate::block::round_half_away;

/// The vacant ("null") value.
pub const VACANT: f64 = f64::NAN;

pub fn is_vacant(v: f64) -> bool {
    v.is_nan()
}

/// Vacant counts as 0 in arithmetic and functions.
fn num(v: f64) -> f64 {
    if v.is_nan() {
        0.0
    } else {
        v
    }
}

fn finite(v: f64) -> Result<f64, NcError> {
    if v.is_finite() {
        // -0 is 0 (§7.6).
        Ok(if v == 0.0 { 0.0 } else { v })
    } else {
        fail(Alarm::NotFinite, "the result is not a finite number")
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bin {
    Add,
    Sub,
    Mul,
    Div,
    Mod,
    And,
    Or,
    Xor,
}

fn int(v: f64) -> Result<i64, NcError> {
    let r = round_half_away(num(v));
    if r.abs() > 9.0e18 {
        return fail(
            Alarm::NotFinite,
            "the operand is too large for a bitwise operation",
        );
    }
    Ok(r as i64)
}

pub fn binary(op: Bin, a: f64, b: f64) -> Result<f64, NcError> {
    let (x, y) = (num(a), num(b));
    finite(match op {
        Bin::Add => x + y,
        Bin::Sub => x - y,
        Bin::Mul => x * y,
        Bin::Div => {
            if y == 0.0 {
                return fail(Alarm::DivisionByZero, "division by zero");
            }
            x / y
        }
        Bin::Mod => {
            let (i, j) = (int(a)?, int(b)?);
            if j == 0 {
                return fail(Alarm::DivisionByZero, "MOD by zero");
            }
            // The remainder takes the sign of the dividend (−7 MOD 3 = −1).
            (i % j) as f64
        }
        Bin::And => (int(a)? & int(b)?) as f64,
        Bin::Or => (int(a)? | int(b)?) as f64,
        Bin::Xor => (int(a)? ^ int(b)?) as f64,
    })
}

pub fn neg(a: f64) -> f64 {
    let v = -num(a);
    if v == 0.0 {
        0.0
    } else {
        v
    }
}

/// The functions, numbered as the ISA's `Func` operand.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Func {
    Sin = 0,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Sqrt,
    Abs,
    Round,
    Fix,
    Fup,
    Ln,
    Exp,
    Bin,
    Bcd,
}

impl Func {
    pub const ALL: [Func; 15] = [
        Func::Sin,
        Func::Cos,
        Func::Tan,
        Func::Asin,
        Func::Acos,
        Func::Atan,
        Func::Sqrt,
        Func::Abs,
        Func::Round,
        Func::Fix,
        Func::Fup,
        Func::Ln,
        Func::Exp,
        Func::Bin,
        Func::Bcd,
    ];

    pub fn from_code(code: u8) -> Option<Func> {
        Func::ALL.get(code as usize).copied()
    }
}

fn deg(v: f64) -> f64 {
    v.to_radians()
}

/// SIN, COS and ATAN in degrees, as `func` computes them (public for the
/// JIT, which calls them with its own finite check).
pub fn sin_deg(x: f64) -> f64 {
    libm::sin(deg(x))
}

pub fn cos_deg(x: f64) -> f64 {
    libm::cos(deg(x))
}

pub fn atan_deg(x: f64) -> f64 {
    libm::atan(x).to_degrees()
}

pub fn func(f: Func, a: f64) -> Result<f64, NcError> {
    let x = num(a);
    finite(match f {
        Func::Sin => sin_deg(x),
        Func::Cos => cos_deg(x),
        Func::Tan => {
            // 90° + k·180° has no tangent.
            let k = (x - 90.0) / 180.0;
            if (k - libm::round(k)).abs() < 1e-12 {
                return fail(Alarm::UndefinedFunction, format!("TAN of {x}°"));
            }
            libm::tan(deg(x))
        }
        Func::Asin | Func::Acos => {
            if !(-1.0..=1.0).contains(&x) {
                return fail(
                    Alarm::ArcFunctionRange,
                    format!(
                        "{} of {x}: the argument must lie in −1…1",
                        match f {
                            Func::Asin => "ASIN",
                            _ => "ACOS",
                        }
                    ),
                );
            }
            let r = if f == Func::Asin {
                libm::asin(x)
            } else {
                libm::acos(x)
            };
            r.to_degrees()
        }
        Func::Atan => atan_deg(x),
        Func::Sqrt => {
            if x < 0.0 {
                return fail(
                    Alarm::NegativeRoot,
                    format!("square root of the negative value {x}"),
                );
            }
            libm::sqrt(x)
        }
        Func::Abs => x.abs(),
        Func::Round => round_half_away(x),
        Func::Fix => libm::trunc(x),
        Func::Fup => {
            if x < 0.0 {
                -libm::ceil(-x)
            } else {
                libm::ceil(x)
            }
        }
        Func::Ln => {
            if x <= 0.0 {
                return fail(
                    Alarm::LogOfNonPositive,
                    format!("LN of {x}: the argument must be positive"),
                );
            }
            libm::log(x)
        }
        Func::Exp => libm::exp(x),
        Func::Bin => bcd_to_bin(x)?,
        Func::Bcd => bin_to_bcd(x)?,
    })
}

fn bcd_to_bin(x: f64) -> Result<f64, NcError> {
    let mut v = int(x)?;
    if v < 0 {
        return fail(Alarm::NegativeBcd, "BIN of a negative value");
    }
    let (mut out, mut scale) = (0i64, 1i64);
    while v > 0 {
        out += (v & 0xf) * scale;
        v >>= 4;
        scale *= 10;
    }
    Ok(out as f64)
}

fn bin_to_bcd(x: f64) -> Result<f64, NcError> {
    let mut v = int(x)?;
    if v < 0 {
        return fail(Alarm::NegativeBcd, "BCD of a negative value");
    }
    let (mut out, mut shift) = (0i64, 0u32);
    while v > 0 && shift < 60 {
        out |= (v % 10) << shift;
        v /= 10;
        shift += 4;
    }
    Ok(out as f64)
}

/// `ATAN[y]/[x]`: the direction of (x, y) in degrees, 0…360.
pub fn atan2(y: f64, x: f64) -> Result<f64, NcError> {
    let (y, x) = (num(y), num(x));
    if y == 0.0 && x == 0.0 {
        return fail(Alarm::UndefinedFunction, "ATAN[0]/[0] has no direction");
    }
    let mut d = libm::atan2(y, x).to_degrees();
    if d < 0.0 {
        d += 360.0;
    }
    finite(d)
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rel {
    Eq = 0,
    Ne,
    Gt,
    Lt,
    Ge,
    Le,
}

impl Rel {
    pub fn from_code(code: u8) -> Option<Rel> {
        [Rel::Eq, Rel::Ne, Rel::Gt, Rel::Lt, Rel::Ge, Rel::Le]
            .get(code as usize)
            .copied()
    }
}

/// A comparison (1 or 0). EQ/NE tell vacant from 0; the others count it as
/// 0; equality is relative to 10⁻⁹ (§7.6).
pub fn compare(op: Rel, a: f64, b: f64) -> f64 {
    let result = match op {
        Rel::Eq | Rel::Ne => {
            let same = match (is_vacant(a), is_vacant(b)) {
                (true, true) => true,
                (false, false) => near(a, b),
                _ => false,
            };
            same == (op == Rel::Eq)
        }
        _ => {
            let (x, y) = (num(a), num(b));
            let eq = near(x, y);
            match op {
                Rel::Gt => x > y && !eq,
                Rel::Lt => x < y && !eq,
                Rel::Ge => x > y || eq,
                _ => x < y || eq,
            }
        }
    };
    if result {
        1.0
    } else {
        0.0
    }
}

fn near(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * 1f64.max(a.abs()).max(b.abs())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vacant_rules() {
        assert_eq!(binary(Bin::Mul, VACANT, 5.0).unwrap(), 0.0);
        assert_eq!(binary(Bin::Add, VACANT, 7.0).unwrap(), 7.0);
        assert_eq!(neg(VACANT), 0.0);
        assert_eq!(compare(Rel::Eq, VACANT, VACANT), 1.0);
        assert_eq!(compare(Rel::Eq, VACANT, 0.0), 0.0);
        assert_eq!(compare(Rel::Ne, VACANT, 0.0), 1.0);
        assert_eq!(compare(Rel::Ge, VACANT, 0.0), 1.0);
        assert_eq!(compare(Rel::Gt, VACANT, 0.0), 0.0);
    }

    #[test]
    fn functions_follow_the_spec_table() {
        assert_eq!(func(Func::Round, -2.5).unwrap(), -3.0);
        assert_eq!(func(Func::Fix, -2.7).unwrap(), -2.0);
        assert_eq!(func(Func::Fup, -2.2).unwrap(), -3.0);
        assert_eq!(func(Func::Fup, 2.2).unwrap(), 3.0);
        assert_eq!(binary(Bin::Mod, -7.0, 3.0).unwrap(), -1.0);
        assert_eq!(atan2(-1.0, -1.0).unwrap(), 225.0);
        assert_eq!(func(Func::Bcd, 25.0).unwrap(), 37.0);
        assert_eq!(func(Func::Bin, 37.0).unwrap(), 25.0);
        assert!((func(Func::Sin, 30.0).unwrap() - 0.5).abs() < 1e-15);
    }

    #[test]
    fn domain_errors_have_their_codes() {
        assert_eq!(binary(Bin::Div, 1.0, 0.0).unwrap_err().code, 5001);
        assert_eq!(func(Func::Sqrt, -1.0).unwrap_err().code, 5002);
        assert_eq!(func(Func::Asin, 2.0).unwrap_err().code, 5003);
        assert_eq!(func(Func::Ln, 0.0).unwrap_err().code, 5004);
        assert_eq!(func(Func::Tan, 90.0).unwrap_err().code, 5005);
        assert_eq!(func(Func::Tan, -270.0).unwrap_err().code, 5005);
        assert_eq!(atan2(0.0, 0.0).unwrap_err().code, 5005);
        assert_eq!(func(Func::Exp, 1000.0).unwrap_err().code, 5006);
        assert_eq!(func(Func::Bcd, -1.0).unwrap_err().code, 5011);
    }

    #[test]
    fn comparisons_use_relative_equality() {
        assert_eq!(compare(Rel::Eq, 0.1 + 0.2, 0.3), 1.0);
        assert_eq!(compare(Rel::Gt, 0.1 + 0.2, 0.3), 0.0);
        assert_eq!(compare(Rel::Le, 0.1 + 0.2, 0.3), 1.0);
    }
}
