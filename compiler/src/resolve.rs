//! Pass `resolve`: NC blocks that are plain moves become typed moves.
//!
//! A block executed where it stands whose words make a plain move (X/Z/U/W,
//! at least one, F, N and an arc's R or I/K, each once, and at most a G
//! code written as 0–3) is marked [`NcKind::Move`] with its motion. Its
//! words other than G may be computed (`G1 X#5 Z#4`). `emit` gives a move
//! of constants the `move` instruction and its record, a move with a
//! computed word its words and `execmove`; either way the kernel reads the
//! words with its short parse (`nc::block::parse_move`) instead of decoding
//! every word in general.
//!
//! The kernel's rules on the words themselves were checked when the block
//! was built (a literal block that breaks one is a compile error), and
//! `parse_move` checks again the few a plain move can break; what depends
//! on the modal state (a plane mode, a waiting chamfer, a G10 data mode)
//! the kernel decides as it runs the move, as for any block.

use crate::ir::{Function, Module, NcKind, Op, Word};
use nc::gcode::Motion;
use nc::words::addr;

/// Marks the plain moves of every function.
pub fn module(ir: &mut Module) {
    for f in &mut ir.functions {
        function(f);
    }
}

/// Marks the plain moves of `f` (a whole function or a chunk's part).
pub fn function(f: &mut Function) {
    for op in f.ops.items_mut() {
        let Op::Nc(nc) = op else {
            continue;
        };
        let (a, b) = (nc.words.0 as usize, nc.words.1 as usize);
        if nc.kind != NcKind::Run {
            continue;
        }
        if let Some(motion) = f.words.get(a..b).and_then(plain_move) {
            nc.kind = NcKind::Move(motion);
        }
    }
}

/// The motion of words that make a plain move (`None` inside: the one in
/// force), or `None` when they do not.
pub fn plain_move(words: &[Word]) -> Option<Option<Motion>> {
    const AXES: u32 = bits(b"XZUW");
    const OTHERS: u32 = bits(b"FNRIK");
    let mut seen = 0u32;
    let mut motion = None;
    for w in words {
        let bit = 1u32.checked_shl(u32::from(w.addr))?;
        if seen & bit != 0 {
            return None;
        }
        seen |= bit;
        if w.addr == addr(b'G') {
            // (A computed G could be any code.)
            motion = Some(nc::block::written_motion(w.constant()?)?);
        } else if (AXES | OTHERS) & bit == 0 {
            return None;
        }
    }
    (seen & AXES != 0).then_some(motion)
}

/// The address bits of some letters.
const fn bits(letters: &[u8]) -> u32 {
    let mut m = 0;
    let mut i = 0;
    while i < letters.len() {
        m |= 1 << addr(letters[i]);
        i += 1;
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::{Handle, WordValue};

    fn words(spec: &[(u8, f64)]) -> Vec<Word> {
        spec.iter()
            .map(|&(l, v)| Word::new(addr(l), WordValue::Const(v, 0)))
            .collect()
    }

    #[test]
    fn plain_moves_and_blocks_that_are_not() {
        let line = [(b'G', 1.0), (b'X', 12.5), (b'Z', -3.0), (b'F', 100.0)];
        assert_eq!(plain_move(&words(&line)), Some(Some(Motion::Line)));
        let modal = [(b'N', 10.0), (b'U', 1.0), (b'W', -2.0)];
        assert_eq!(plain_move(&words(&modal)), Some(None));
        let arc = [(b'G', 3.0), (b'X', 20.0), (b'Z', -5.0), (b'R', 5.0)];
        assert_eq!(plain_move(&words(&arc)), Some(Some(Motion::ArcCcw)));
        for not in [
            &[(b'G', 1.0), (b'F', 100.0)][..],        // no axis
            &[(b'G', 4.0), (b'X', 1.0)],              // a dwell
            &[(b'G', 1.5), (b'X', 1.0)],              // not 0–3
            &[(b'G', 0.0), (b'G', 1.0), (b'X', 1.0)], // two G codes
            &[(b'X', 1.0), (b'X', 2.0)],              // X twice
            &[(b'X', 1.0), (b'M', 3.0)],              // an M code
            &[(b'X', 1.0), (b'S', 300.0)],            // S
            &[(b'X', 1.0), (b'C', 30.0)],             // a C axis word
            &[(b'G', 1.0), (b'X', 1.0), (b'L', 2.0)], // a chamfer
        ] {
            assert_eq!(plain_move(&words(not)), None, "{not:?}");
        }
        // Computed words: any but the G code.
        let expr = WordValue::Expr(Handle::from_index(0).unwrap());
        let mut computed = words(&line);
        computed[1] = Word::new(addr(b'X'), expr);
        computed[3] = Word::new(addr(b'F'), expr);
        assert_eq!(plain_move(&computed), Some(Some(Motion::Line)));
        computed[0] = Word::new(addr(b'G'), expr);
        assert_eq!(plain_move(&computed), None);
        let mut dwell = words(&[(b'G', 4.0), (b'X', 1.0)]);
        dwell[1] = Word::new(addr(b'X'), expr);
        assert_eq!(plain_move(&dwell), None);
    }
}
