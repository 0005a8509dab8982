//! Canon and trace numbers without the float formatter.
//!
//! `format!("{:.4}", v)` rounds the exact binary value of `v` half to even,
//! which is what the canon wants (canon.md), but the standard library gets
//! there through its general exact algorithm, and printing the canon of a
//! long program spent about half its time in it (the trace's 6 decimals
//! too). A double is `m·2^e` exactly, so `v·10^d` is the integer `m·10^d`
//! shifted by `e`: the rounding is done in integers, exactly as the
//! formatter does it, and the digits are printed as integers.

use core::fmt::{self, Write};

/// 10^d for the decimals this module prints (at most 9: 10⁹·2⁵³ < 2⁸³).
const POW10: [u64; 10] = [
    1,
    10,
    100,
    1_000,
    10_000,
    100_000,
    1_000_000,
    10_000_000,
    100_000_000,
    1_000_000_000,
];

/// `v·10⁴` rounded half to even on the exact value; `None` when `v` is not
/// finite or the result does not fit an `i64` (|v| above about 9·10¹⁴).
pub fn ten_thousandths(v: f64) -> Option<i64> {
    scaled(v, 4)
}

/// `v·10^digits` rounded half to even on the exact value; `None` when `v`
/// is not finite, `digits` is above 9, or the result does not fit an
/// `i64`.
pub fn scaled(v: f64, digits: usize) -> Option<i64> {
    let pow = *POW10.get(digits)?;
    // Most values without the 128-bit arithmetic: below 2⁴⁰ the product
    // v·10^d computed in f64 is within 2⁻¹³ of the exact one, so when it
    // lies more than a quarter from a half, the exact product rounds to
    // the same integer (and no tie is near).
    let y = v * pow as f64;
    if y.abs() < FAST_BELOW {
        // An integer within about a half of y (the sum's rounding is far
        // below that at this size; which one a tie gives does not matter,
        // as a value near a half is not taken here), in two instructions
        // where a call to `round` took about twenty.
        let r = (y + 0.5f64.copysign(y)) as i64;
        if (y - r as f64).abs() < 0.25 {
            return Some(r);
        }
    }
    if !v.is_finite() {
        return None;
    }
    let bits = v.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i32;
    let fraction = bits & ((1 << 52) - 1);
    // Subnormals have no implicit bit and the exponent of the smallest normal.
    let (mantissa, exp) = if biased == 0 {
        (fraction, -1074)
    } else {
        (fraction | 1 << 52, biased - 1075)
    };
    // Below 2^83: 53 bits of mantissa times at most 10⁹ (30 bits).
    let scaled = u128::from(mantissa) * u128::from(pow);
    if exp >= 0 {
        // v ≥ 2^52: v·10^d is past the i64 range for d ≥ 3, and the few
        // whole numbers that fit with fewer decimals go the slow way.
        return None;
    }
    let magnitude = i64::try_from(round_shift(scaled, exp.unsigned_abs())).ok()?;
    Some(if bits >> 63 == 1 {
        -magnitude
    } else {
        magnitude
    })
}

/// 2⁴⁰: the bound of the fast path of [`ten_thousandths`].
const FAST_BELOW: f64 = 1_099_511_627_776.0;

/// `x / 2^shift`, rounded half to even.
fn round_shift(x: u128, shift: u32) -> u128 {
    if shift >= 128 {
        // x < 2^83, so the quotient is below 2^-45: rounds to 0.
        return 0;
    }
    let quotient = x >> shift;
    let rest = x & ((1u128 << shift) - 1);
    let half = 1u128 << (shift - 1);
    if rest > half || (rest == half && quotient & 1 == 1) {
        quotient + 1
    } else {
        quotient
    }
}

/// Writes `n / 10^digits` (from [`scaled`]) with exactly `digits`
/// decimals, as `format!("{:.digits$}")` writes the value: with a `-` when
/// the value was negative, also where it rounds to 0 (`negative`: its
/// sign bit, as the standard formatter prints `-0.000`).
pub fn write_fixed(f: &mut impl Write, n: i64, negative: bool, digits: usize) -> fmt::Result {
    let mut buf = [0u8; FIXED_CAPACITY];
    let text = fixed_digits(n, negative, digits, &mut buf).ok_or(fmt::Error)?;
    f.write_str(core::str::from_utf8(text).map_err(|_| fmt::Error)?)
}

/// The longest text of [`fixed_digits`]: a sign, 20 digits, the point and
/// 9 decimals.
pub const FIXED_CAPACITY: usize = 32;

/// The ASCII text [`write_fixed`] writes, built back to front at the end
/// of `buf` (the formatter's padding logic per integer cost more than the
/// digits); `None` when `digits` is above 9.
pub fn fixed_digits(
    n: i64,
    negative: bool,
    digits: usize,
    buf: &mut [u8; FIXED_CAPACITY],
) -> Option<&[u8]> {
    let pow = POW10.get(digits).copied()?;
    let abs = n.unsigned_abs();
    let mut at = buf.len();
    let mut put = |d: u8| {
        at -= 1;
        buf[at] = d;
    };
    let mut frac = abs % pow;
    for _ in 0..digits {
        put(b'0' + (frac % 10) as u8);
        frac /= 10;
    }
    if digits > 0 {
        put(b'.');
    }
    let mut whole = abs / pow;
    loop {
        put(b'0' + (whole % 10) as u8);
        whole /= 10;
        if whole == 0 {
            break;
        }
    }
    if negative {
        put(b'-');
    }
    Some(&buf[at..])
}

/// Writes `n / 10⁴` with at most 4 decimals, no trailing zeros, no
/// trailing point; 0 (also a negative value that rounds to 0) as `0`.
pub fn write_ten_thousandths(f: &mut impl Write, n: i64) -> fmt::Result {
    let abs = n.unsigned_abs();
    let (whole, mut frac) = (abs / 10_000, abs % 10_000);
    if n < 0 {
        f.write_char('-')?;
    }
    write!(f, "{whole}")?;
    if frac == 0 {
        return Ok(());
    }
    let mut width = 4;
    while frac % 10 == 0 {
        frac /= 10;
        width -= 1;
    }
    write!(f, ".{frac:0width$}")
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::format;
    use alloc::string::String;

    /// The reference: the standard library's exact formatter, trimmed as
    /// the canon wants.
    fn reference(v: f64) -> String {
        let mut s = format!("{v:.4}");
        if s.contains('.') {
            s = String::from(s.trim_end_matches('0').trim_end_matches('.'));
        }
        if s == "-0" {
            s = String::from("0");
        }
        s
    }

    fn fast(v: f64) -> Option<String> {
        let n = ten_thousandths(v)?;
        let mut s = String::new();
        write_ten_thousandths(&mut s, n).ok()?;
        Some(s)
    }

    fn check(v: f64) {
        if let Some(s) = fast(v) {
            assert_eq!(s, reference(v), "{v:e} ({:#x})", v.to_bits());
        } else {
            assert!(!v.is_finite() || v.abs() > 9.0e14, "{v:e} has no fast form");
        }
    }

    #[test]
    fn ties_round_half_to_even_on_the_exact_value() {
        // k/32 are exact in binary and end in 5 at the fifth decimal.
        for k in -4096..4096 {
            check(f64::from(k) / 32.0);
        }
        // 0.00015 is not exact: its binary value is just below the tie.
        for v in [0.00015, 0.00025, 1.00005, 2.5e-5, -2.5e-5, 1e-300, 5e-324] {
            check(v);
        }
    }

    /// xorshift64: the next of a fixed, reproducible sequence.
    fn xorshift(x: &mut u64) -> u64 {
        *x ^= *x << 13;
        *x ^= *x >> 7;
        *x ^= *x << 17;
        *x
    }

    #[test]
    fn agrees_with_the_exact_formatter_across_magnitudes() {
        // xorshift64: a fixed, reproducible spread of bit patterns and of
        // decimal-looking values (the canon's usual inputs).
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        for i in 0..200_000 {
            let x = xorshift(&mut x);
            let random_bits = f64::from_bits(x);
            check(random_bits);
            let decimal = (x % 2_000_000_001) as f64 / 10f64.powi(i % 9) - 1000.0;
            check(decimal);
            check(-decimal);
        }
    }

    #[test]
    fn values_on_both_sides_of_the_fast_paths_quarter_agree() {
        // Products a little more and a little less than a quarter from a
        // half, up to the fast path's bound and past it.
        let mut x: u64 = 0x2545_f491_4f6c_dd1d;
        for _ in 0..50_000 {
            let n = (xorshift(&mut x) % (1 << 42)) as f64;
            for d in [
                0.0, 0.2, 0.2499, 0.25, 0.2501, 0.3, 0.5, 0.7499, 0.75, 0.7501,
            ] {
                let v = (n + d) / 10_000.0;
                check(v);
                check(-v);
                check(f64::from_bits(v.to_bits() + 1));
            }
        }
    }

    /// `write_fixed` against `format!("{v:.d$}")` for the trace's 3 and 6
    /// decimals (and 0 and 9): random bit patterns, decimal-looking values,
    /// exact ties (k/1024 and k/128 end in 5 past 3 and 6 decimals) and
    /// their neighbours, negative values that round to 0.
    #[test]
    fn fixed_decimals_agree_with_the_exact_formatter() {
        let fixed = |v: f64, d: usize| -> Option<String> {
            let n = scaled(v, d)?;
            let mut s = String::new();
            write_fixed(&mut s, n, v.is_sign_negative(), d).ok()?;
            Some(s)
        };
        let check = |v: f64| {
            for d in [0, 3, 6, 9] {
                match fixed(v, d) {
                    Some(s) => {
                        assert_eq!(s, format!("{v:.d$}"), "{v:e} ({:#x}) to {d}", v.to_bits())
                    }
                    // Not finite, past the i64 range, or v ≥ 2⁵².
                    None => assert!(
                        !v.is_finite() || v.abs() * POW10[d] as f64 > 9.2e18 || v.abs() >= 4.5e15
                    ),
                }
            }
        };
        for k in -30_000..30_000 {
            for v in [f64::from(k) / 1024.0, f64::from(k) / 128.0] {
                check(v);
                check(f64::from_bits(v.to_bits() + 1));
                check(f64::from_bits(v.to_bits().saturating_sub(1)));
            }
        }
        for v in [
            -4e-7, -5e-7, -6e-7, -0.0, 0.0, -1e-300, 5e-324, 0.0005, -0.0005,
        ] {
            check(v);
        }
        let mut x: u64 = 0x0123_4567_89ab_cdef;
        for i in 0..200_000 {
            let x = xorshift(&mut x);
            check(f64::from_bits(x));
            let decimal = (x % 2_000_000_001) as f64 / 10f64.powi(i % 10) - 1000.0;
            check(decimal);
            check(-decimal);
        }
        assert_eq!(scaled(1.0, 10), None);
    }

    #[test]
    fn large_and_special_values_have_no_fast_form() {
        assert_eq!(ten_thousandths(f64::NAN), None);
        assert_eq!(ten_thousandths(f64::INFINITY), None);
        assert_eq!(ten_thousandths(1e15), None);
        assert_eq!(ten_thousandths(f64::MAX), None);
        assert_eq!(ten_thousandths(9.0e14), Some(9_000_000_000_000_000_000));
    }
}
