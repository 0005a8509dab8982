//! G70 finishing (cycles.md §8): the profile blocks run as ordinary
//! blocks, so G00 stays rapid and their F, S and T act where they would in
//! any block; only their M codes are dropped.

use alloc::vec::Vec;

use crate::base::error::NcError;
use crate::base::words::{addr, Word};
use crate::block;
use crate::exec::{Nc, Sink};
use crate::plan::profile::check_codes;
use crate::plan::roughing::Path;

pub fn run(nc: &mut Nc, blocks: &[(Vec<Word>, u32)], sink: &mut dyn Sink) -> Result<(), NcError> {
    let a = nc.st.pos;
    let motion = nc.st.modal.motion;
    let comp = nc.st.modal.comp;
    for (words, tag) in blocks {
        let tag = *tag;
        let p = block::parse(words, &nc.machine).map_err(|e| e.at(tag))?;
        check_codes(&nc.reader(), &p, tag)?;
        let kept: Vec<Word> = words
            .iter()
            .filter(|w| w.addr != addr(b'M'))
            .copied()
            .collect();
        nc.exec(&kept, sink)
            .map_err(|e| if e.at.is_some() { e } else { e.at(tag) })?;
    }
    // An element still waiting for a corner word of the nf block is
    // printed whole before the return (W112).
    crate::exec::contour::flush(nc, sink)?;
    let mut back = Path::new(nc.st.pos, false);
    back.rapid(a);
    super::out::print(nc, sink, back.steps())?;
    // The modes in force before G70 are back (cycles.md §8, comp.md §8).
    nc.st.modal.motion = motion;
    nc.st.modal.comp = comp;
    Ok(())
}
