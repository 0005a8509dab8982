//! The room a thread needs along its long axis: the distance in which the
//! axis reaches thread speed after the spindle index, and the distance in
//! which it stops at the end of the chain. Over both the lead is not the
//! programmed one (the incomplete lead at entry and exit). The runtime
//! cuts threads with these figures; the compiler (W118) and the runtime's
//! own check compare them with the room the program gives.
//!
//! Units: mm, mm/s, mm/s², rev/min; accelerations are those of the long
//! axis (slide units: a radial X for a face thread).

/// Whether Z is the long axis of a thread block that travels `d_r`
/// (radial X, slide units) and `d_z`: Z when it moves at least as far as
/// X, a 45° move included. The tie is judged within [`TIE_MM`], so that a
/// 45° pull-out whose end points went through a work shift or a diameter
/// halving (a rounding of 1e-15 mm either way) keeps Z, as the listing
/// that printed its lead along Z says. The kernel, the runtime and its
/// check all choose the axis the lead is along with this.
pub fn z_is_long(d_r: f64, d_z: f64) -> bool {
    d_z.abs() >= d_r.abs() - TIE_MM
}

/// Two thread travels within this (mm) are equal when the long axis is
/// chosen: far below the 0.001 mm resolution, far above rounding.
pub const TIE_MM: f64 = 1e-9;

/// The acceleration of the long axis along a straight thread block that
/// travels `d_r` (radial X, slide units) and `d_z`, when the path may use `ax` on X and `az` on Z: the path acceleration
/// that keeps both axes within their limits, times the long axis's share
/// of the direction. Zero for a block without motion.
pub fn long_axis_accel(d_r: f64, d_z: f64, ax: f64, az: f64) -> f64 {
    let len = libm::sqrt(d_r * d_r + d_z * d_z);
    if len <= 0.0 || ax <= 0.0 || az <= 0.0 {
        return 0.0;
    }
    let (ur, uz) = (d_r.abs() / len, d_z.abs() / len);
    let path = 1.0 / (ur / ax).max(uz / az);
    path * ur.max(uz)
}

/// The acceleration the entry ramp plans with. The ramp is a function of
/// the spindle angle θ, so its axis acceleration is α·ω² + α·θ·ω̇, and
/// α·θ stays below the lead on the ramp: it keeps back lead × the
/// spindle's own acceleration (in rev/s²) for a spindle still settling,
/// but never more than half of `a_long`.
pub fn ramp_accel(a_long: f64, lead: f64, spindle_accel_rpm_s: f64) -> f64 {
    (a_long - lead * spindle_accel_rpm_s / 60.0).max(0.5 * a_long)
}

/// Thread speed of the long axis: lead × spindle revolutions per second.
pub fn thread_speed(lead: f64, rpm: f64) -> f64 {
    lead * rpm.abs() / 60.0
}

/// The entry length (incomplete lead at the start): the long-axis travel
/// from the thread's start point to where it reaches thread speed,
/// `v²/(2·a)` with `a` the [`ramp_accel`]. The ramp is exact in the
/// spindle angle, so the sampled trace meets it to rounding.
pub fn entry_length(lead: f64, rpm: f64, a_long: f64, spindle_accel_rpm_s: f64) -> f64 {
    let v = thread_speed(lead, rpm);
    let a = ramp_accel(a_long, lead, spindle_accel_rpm_s);
    if a > 0.0 {
        v * v / (2.0 * a)
    } else {
        f64::INFINITY
    }
}

/// The exit length (incomplete lead at the end): the long-axis travel in
/// which the axis stops from thread speed at `a_long`, `v²/(2·a)`. The
/// interpolator brakes in whole periods and lands exactly on the end
/// point, so its braking starts within one period's travel of this.
pub fn exit_length(lead: f64, rpm: f64, a_long: f64) -> f64 {
    let v = thread_speed(lead, rpm);
    if a_long > 0.0 {
        v * v / (2.0 * a_long)
    } else {
        f64::INFINITY
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Z is long on a tie, also one rounded by 1.8e-15 mm (a 45°
    /// pull-out whose end went through a diameter halving), not a
    /// micrometre over it.
    #[test]
    fn z_is_long_on_a_tie_within_rounding() {
        assert!(z_is_long(2.0, -2.0));
        assert!(z_is_long(2.0000000000000018, -2.0));
        assert!(!z_is_long(2.001, -2.0));
        assert!(!z_is_long(-2.000001, 2.0));
        assert!(z_is_long(0.0, 0.0));
    }

    /// M24×1.5 at 600 rpm on the reference Z (2000 mm/s², spindle
    /// 1000 rpm/s): v = 1.5 × 10 = 15 mm/s; the ramp keeps back
    /// 1.5 × 1000/60 = 25 mm/s², so a = 1975 and the entry is
    /// 15² / (2 × 1975) = 225 / 3950 = 0.056962 mm; the exit at the full
    /// 2000 is 225 / 4000 = 0.05625 mm.
    #[test]
    fn an_m24_thread_at_600_rpm() {
        assert_eq!(thread_speed(1.5, 600.0), 15.0);
        assert!((entry_length(1.5, 600.0, 2000.0, 1000.0) - 225.0 / 3950.0).abs() < 1e-12);
        assert!((exit_length(1.5, 600.0, 2000.0) - 0.05625).abs() < 1e-12);
    }

    /// A 45° chamfer on the reference machine: X (1500) limits the path
    /// to 1500/√½ = 2121.3 mm/s², of which the long axis gets √½: 1500.
    /// A straight Z thread gets all of Z's 2000.
    #[test]
    fn the_long_axis_share_of_the_path_acceleration() {
        assert!((long_axis_accel(1.5, -1.5, 1500.0, 2000.0) - 1500.0).abs() < 1e-9);
        assert_eq!(long_axis_accel(0.0, -24.0, 1500.0, 2000.0), 2000.0);
        assert_eq!(long_axis_accel(0.0, 0.0, 1500.0, 2000.0), 0.0);
    }

    /// A lead of 6 on a slow spindle accelerating fast would keep back
    /// more than half: the floor holds. 6 × 30000/60 = 3000 > 1000.
    #[test]
    fn the_ramp_keeps_at_least_half() {
        assert_eq!(ramp_accel(2000.0, 6.0, 30000.0), 1000.0);
    }
}
