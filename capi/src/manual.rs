//! Manual moves between programs (`runtime::Manual`): jog, step or
//! handwheel, reference return, and their stop.

use crate::split::with_motion;
use crate::{fail, GbcController, GbcStatus, Outcome};
use runtime::{JogRate, Manual, ManualAxis, ManualRefused};

/// `axis` of a manual move: the cross slide.
pub const GBC_AXIS_X: u8 = 0;
/// `axis` of a manual move: the carriage.
pub const GBC_AXIS_Z: u8 = 1;
/// `axis` of a manual move: the C axis (degrees, feeds in degrees per
/// minute), on a machine with one.
pub const GBC_AXIS_C: u8 = 2;

/// A continuous jog of `axis` ([`GBC_AXIS_X`], [`GBC_AXIS_Z`],
/// [`GBC_AXIS_C`]) toward +
/// (`plus`) or −, at `feed_mm_min` (0: the axis's rapid rate; X's feed is
/// its radial speed), until `gbc_manual_stop` or the axis's soft limit.
/// Taken only while no program runs ([`GbcStatus::NotIdle`] otherwise:
/// `gbc_reset` first); when the move has stopped, the program starts
/// again from its beginning where the axes stand.
#[no_mangle]
pub extern "C" fn gbc_jog(
    controller: GbcController,
    axis: u8,
    plus: bool,
    feed_mm_min: f64,
) -> GbcStatus {
    manual(controller, axis, feed_mm_min, |axis, rate| Manual::Jog {
        axis,
        plus,
        rate,
    })
}

/// An incremental jog of `axis` by `distance_mm` (signed; X on the
/// diameter), at `feed_mm_min` (0: rapid); a handwheel's pulses times
/// its increment. Steps given while one runs follow it; a step beyond a
/// soft limit ends at the limit. Otherwise as `gbc_jog`.
#[no_mangle]
pub extern "C" fn gbc_jog_step(
    controller: GbcController,
    axis: u8,
    distance_mm: f64,
    feed_mm_min: f64,
) -> GbcStatus {
    manual(controller, axis, feed_mm_min, |axis, rate| Manual::Step {
        axis,
        distance: distance_mm,
        rate,
    })
}

/// A reference return of `axis`: to machine zero at the machine's
/// reference-return feed (№113). Otherwise as `gbc_jog`.
#[no_mangle]
pub extern "C" fn gbc_home(controller: GbcController, axis: u8) -> GbcStatus {
    manual(controller, axis, 0.0, |axis, _| Manual::Home { axis })
}

/// Stops a manual move: the axes decelerate and stand (nothing without
/// one).
#[no_mangle]
pub extern "C" fn gbc_manual_stop(controller: GbcController) -> GbcStatus {
    with_motion(controller, |mut s| {
        s.motion()?.engine_mut().manual_stop();
        Ok(())
    })
}

/// Gives the controller the manual command `make` builds from the axis
/// and rate.
fn manual(
    controller: GbcController,
    axis: u8,
    feed_mm_min: f64,
    make: impl FnOnce(ManualAxis, JogRate) -> Manual,
) -> GbcStatus {
    with_motion(controller, |mut s| {
        let r = s.motion()?.engine_mut();
        let axis = match axis {
            GBC_AXIS_X => ManualAxis::X,
            GBC_AXIS_Z => ManualAxis::Z,
            GBC_AXIS_C => ManualAxis::C,
            _ => return Err(bad("the axis is not GBC_AXIS_X, GBC_AXIS_Z or GBC_AXIS_C")),
        };
        let rate = match feed_mm_min {
            0.0 => JogRate::Rapid,
            f => JogRate::Feed(f),
        };
        refused(r.manual(make(axis, rate)))
    })
}

/// The status of a refused manual command.
fn refused(r: Result<(), ManualRefused>) -> Outcome {
    r.map_err(|e| match e {
        ManualRefused::NotIdle => fail(
            GbcStatus::NotIdle,
            "a program runs, stands stopped, ended or in an alarm: gbc_reset first",
        ),
        ManualRefused::BadValue => {
            bad("the distance or feed is not a finite number, or the feed is negative")
        }
        ManualRefused::NoSuchAxis => bad("this machine has no C axis"),
        ManualRefused::Full => fail(
            GbcStatus::QueueFull,
            "the motion queue is full: give the next step once the axes have caught up",
        ),
    })
}

fn bad(message: &'static str) -> crate::Failure {
    fail(GbcStatus::InvalidArgument, message)
}
