//! W118 at run time (`runtime::Engine::take_room_warning`): a thread
//! whose block is too short for the axis to reach thread speed, or to
//! stop from it, at the spindle speed the run really has (a speed from a
//! variable, an override, G96). gbcc warns of what it can compute; the
//! rest only the motion knows, when the thread starts.
//!
//! Taking a warning is the real-time side's (it copies a few numbers);
//! its text is made apart (`gbc_room_warning_text`), on any thread, as it
//! allocates.

use core::ffi::c_char;
use runtime::{RoomWarning, Tag};

use crate::split::with_motion;
use crate::{fail, give_text, put, GbcController, GbcStatus};

/// The warning's code, as gbcc's W118.
pub const GBC_ROOM_WARNING_CODE: u32 = 118;

/// A thread start without room (`gbc_take_room_warning`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GbcRoomWarning {
    /// [`GBC_ROOM_WARNING_CODE`] for a warning; 0: none was waiting.
    pub code: u32,
    /// Source line of the thread block.
    pub line: u32,
    /// Its source column.
    pub column: u32,
    /// Its source file, an index for `gbc_file_name` (0: the main program).
    pub file: u16,
    /// The room to stop at the thread's end is short (else the room to
    /// reach thread speed at its start).
    pub exit: bool,
    /// The thread's long axis is Z (else X).
    pub long_z: bool,
    /// The long axis's travel in the block, mm.
    pub room_mm: f64,
    /// The travel the axis needs to reach (or leave) thread speed, mm.
    pub need_mm: f64,
    /// The spindle speed the thread starts at, rev/min.
    pub rpm: f64,
}

impl GbcRoomWarning {
    fn none() -> GbcRoomWarning {
        GbcRoomWarning {
            code: 0,
            line: 0,
            column: 0,
            file: 0,
            exit: false,
            long_z: false,
            room_mm: 0.0,
            need_mm: 0.0,
            rpm: 0.0,
        }
    }
}

impl From<RoomWarning> for GbcRoomWarning {
    fn from(w: RoomWarning) -> GbcRoomWarning {
        GbcRoomWarning {
            code: GBC_ROOM_WARNING_CODE,
            line: w.tag.line,
            column: w.tag.col,
            file: w.tag.file,
            exit: w.exit,
            long_z: w.long_z,
            room_mm: w.room_mm,
            need_mm: w.need_mm,
            rpm: w.rpm,
        }
    }
}

impl From<&GbcRoomWarning> for RoomWarning {
    fn from(w: &GbcRoomWarning) -> RoomWarning {
        RoomWarning {
            tag: Tag {
                file: w.file,
                line: w.line,
                col: w.column,
                ..Tag::default()
            },
            exit: w.exit,
            room_mm: w.room_mm,
            need_mm: w.need_mm,
            rpm: w.rpm,
            long_z: w.long_z,
        }
    }
}

/// Takes the next W118 of the thread starts so far into `*out`, each
/// once, the entry's before the exit's: `code` 0 when none is waiting.
/// The motion finds them when a thread starts, so poll once a period
/// (a later start replaces those not taken). On a whole controller or
/// the real-time half of a split one; it allocates nothing. Before a
/// program is loaded: none.
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn gbc_take_room_warning(
    controller: GbcController,
    out: *mut GbcRoomWarning,
) -> GbcStatus {
    with_motion(controller, |s| {
        let taken = match s.motion {
            Ok(m) => m.engine_mut().take_room_warning(),
            Err(_) => None,
        };
        let w = taken.map_or_else(GbcRoomWarning::none, GbcRoomWarning::from);
        // SAFETY: the caller's promise.
        unsafe { put(out, w) }
    })
}

/// The text of `*warning` (from `gbc_take_room_warning`) into `buf` as
/// `gbc_message` gives a text, worded as gbcc's W118: "thread too short
/// to reach its lead: at 1500 rpm Z needs 1.442 mm to reach thread
/// speed, this block gives 1.000 mm". Needs no controller; it
/// allocates, so call it off the real-time thread. A record with `code`
/// 0: [`GbcStatus::InvalidArgument`].
///
/// # Safety
/// `warning` is null or readable; `buf` null or writable for `cap`
/// bytes; `len` null or writable.
#[no_mangle]
pub unsafe extern "C" fn gbc_room_warning_text(
    warning: *const GbcRoomWarning,
    buf: *mut c_char,
    cap: usize,
    len: *mut usize,
) -> GbcStatus {
    crate::guard(|| {
        // SAFETY: the caller's promise: null or readable.
        let Some(w) = (unsafe { warning.as_ref() }) else {
            return Err(fail(GbcStatus::NullPointer, "warning is null"));
        };
        if w.code != GBC_ROOM_WARNING_CODE {
            return Err(fail(
                GbcStatus::InvalidArgument,
                "the record holds no warning (code 0: none was waiting)",
            ));
        }
        // SAFETY: the caller's promise.
        unsafe { give_text(&RoomWarning::from(w).message(), buf, cap, len) }
    })
}
