//! Loading never reserves memory because a length field says so: what
//! `from_bytes` allocates stays proportional to the bytes it was given.
//!
//! A separate test binary, because it installs a counting global allocator.

mod common;

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use common::{edit_lines, put_u32, reseal, sample_module, section};
use isa::format::Section;
use isa::Module;

struct Counting;

thread_local! {
    // `const` initialisers without destructors: reading them from inside
    // the allocator never allocates.
    static TRACKING: Cell<bool> = const { Cell::new(false) };
    static BYTES: Cell<usize> = const { Cell::new(0) };
}

fn note(size: usize) {
    let _ = TRACKING.try_with(|on| {
        if on.get() {
            let _ = BYTES.try_with(|b| b.set(b.get().saturating_add(size)));
        }
    });
}

// SAFETY: forwards every call to `System` unchanged; only counts sizes.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        note(layout.size());
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        note(layout.size());
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        note(new_size);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Total bytes requested (counting every growth) while loading `bytes`.
fn allocated_by_load(bytes: &[u8]) -> usize {
    BYTES.with(|b| b.set(0));
    TRACKING.with(|t| t.set(true));
    let result = Module::from_bytes(bytes);
    TRACKING.with(|t| t.set(false));
    drop(result);
    BYTES.with(Cell::get)
}

#[test]
fn allocation_is_bounded_by_input_size() {
    let bytes = sample_module().to_bytes();
    // An instruction is 8 bytes in memory and at least 1 in the file, and
    // the code vector may double while growing: 32x plus change is the
    // budget for any input.
    let budget = |len: usize| 32 * len + 4096;

    let valid = allocated_by_load(&bytes);
    assert!(valid > 0, "the counting allocator saw nothing");
    assert!(valid <= budget(bytes.len()), "valid file: {valid} bytes");
    eprintln!(
        "valid file of {} bytes: {valid} bytes allocated",
        bytes.len()
    );

    let strings = section(&bytes, Section::Strings);
    let programs = section(&bytes, Section::Programs);
    let fields = [
        section(&bytes, Section::Code).len_field,
        section(&bytes, Section::Consts).payload,
        strings.payload,
        strings.payload + 4,
        programs.payload,
        programs.payload + 16,
        section(&bytes, Section::Lines).payload,
        section(&bytes, Section::Files).payload,
        section(&bytes, Section::Machine).len_field,
    ];
    for at in fields {
        let mut bad = bytes.clone();
        put_u32(&mut bad, at, u32::MAX);
        let bad = reseal(bad);
        let used = allocated_by_load(&bad);
        assert!(used <= budget(bad.len()), "length at {at}: {used} bytes");
        eprintln!("u32::MAX at byte {at}: {used} bytes allocated");
    }

    // A large file of one-byte instructions costs in proportion.
    let mut big = sample_module();
    big.code
        .extend(std::iter::repeat_n(isa::Instr::Ret, 100_000));
    let first = big.lines.get(0).unwrap();
    edit_lines(&mut big, |l| l.resize(l.len() + 100_000, first));
    big.programs[1].end = big.code.len() as u32;
    let big = big.to_bytes();
    let used = allocated_by_load(&big);
    assert!(
        used <= budget(big.len()),
        "big file: {used} bytes for {}",
        big.len()
    );
    eprintln!("file of {} bytes: {used} bytes allocated", big.len());
}

/// The sample module with its code section replaced by `len` bytes of
/// one-byte `ret` instructions, the other sections as they were.
fn with_code_section(len: usize) -> Vec<u8> {
    let bytes = sample_module().to_bytes();
    let code = section(&bytes, Section::Code);
    let mut forged = bytes[..code.payload].to_vec();
    put_u32(&mut forged, code.len_field, len as u32);
    forged.resize(code.payload + len, isa::Opcode::Ret as u8);
    forged.extend_from_slice(&bytes[code.payload + code.len..]);
    reseal(forged)
}

#[test]
fn a_forged_100_mb_code_section_is_refused_before_allocating() {
    const HUNDRED_MB: usize = 100_000_000;
    // Refused from the declared sizes alone: 41 source locations (the
    // sample's 41 instructions) cannot describe 100 000 000 one-byte
    // instructions. Decoding them first would take 800 MB.
    let forged = with_code_section(HUNDRED_MB);
    assert_eq!(
        Module::from_bytes(&forged),
        Err(isa::TableError::CodeSize {
            bytes: HUNDRED_MB,
            lines: 41
        }
        .into())
    );
    let used = allocated_by_load(&forged);
    assert!(used <= 4096, "{used} bytes allocated");
    eprintln!("100 MB code section: {used} bytes allocated before refusal");

    // The same declaration in a file that does not hold it: refused at
    // the length field.
    let bytes = sample_module().to_bytes();
    let code = section(&bytes, Section::Code);
    let mut short = bytes.clone();
    put_u32(&mut short, code.len_field, HUNDRED_MB as u32);
    let short = reseal(short);
    assert_eq!(
        Module::from_bytes(&short),
        Err(isa::LoadError::Truncated { at: code.len_field })
    );
    assert!(allocated_by_load(&short) <= 4096);
}
