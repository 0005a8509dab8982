//! The handle table: GBC_HANDLE_CAPACITY handles at once, machines and
//! controllers together; the next is GBC_STATUS_LIMIT with a text that
//! says so. A test binary of its own: it fills the process's table.

use core::ffi::c_char;
use gbc::*;
use std::ptr::null_mut;

fn last_error() -> String {
    let mut buf = [0 as c_char; 256];
    assert_eq!(
        unsafe { gbc_last_error(buf.as_mut_ptr(), buf.len(), null_mut()) },
        GbcStatus::Ok
    );
    unsafe { std::ffi::CStr::from_ptr(buf.as_ptr()) }
        .to_string_lossy()
        .into_owned()
}

#[test]
fn the_table_holds_the_documented_number_of_handles() {
    let mut m = 0;
    assert_eq!(unsafe { gbc_machine_reference(&mut m) }, GbcStatus::Ok);
    let mut controllers = Vec::new();
    loop {
        let mut c = 0;
        match unsafe { gbc_controller_new(m, std::ptr::null(), &mut c) } {
            GbcStatus::Ok => controllers.push(c),
            GbcStatus::Limit => break,
            s => panic!("{s:?}"),
        }
        assert!(controllers.len() <= GBC_HANDLE_CAPACITY, "no limit");
    }
    // The machine and the controllers share the table.
    assert_eq!(controllers.len() + 1, GBC_HANDLE_CAPACITY);
    assert!(last_error().contains("in use"), "{}", last_error());
    let mut other = 0;
    assert_eq!(
        unsafe { gbc_machine_reference(&mut other) },
        GbcStatus::Limit
    );
    assert_eq!(other, 0, "nothing written");
    // One freed, one made again.
    let c = controllers.pop().expect("a controller");
    assert_eq!(gbc_controller_free(c), GbcStatus::Ok);
    assert_eq!(unsafe { gbc_machine_reference(&mut other) }, GbcStatus::Ok);
    for h in controllers {
        assert_eq!(gbc_controller_free(h), GbcStatus::Ok);
    }
    assert_eq!(gbc_controller_free(c), GbcStatus::InvalidHandle);
    assert_eq!(gbc_machine_free(other), GbcStatus::Ok);
    assert_eq!(gbc_machine_free(m), GbcStatus::Ok);
}
