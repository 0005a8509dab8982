//! Building the control-flow graph: the open block, blocks that start
//! here (jump targets), terminators and the edges patched once their
//! target is known.

use super::{Builder, Tail};
use crate::ir::{self, Handle, Loc, Op, Terminator};
use grammar::Span;

impl Builder<'_> {
    pub(super) fn new_block(&mut self) -> Handle<ir::Block> {
        self.f.term_locs.push(Loc::default());
        self.f.blocks.append(ir::Block::default())
    }

    pub(super) fn block_mut(&mut self, b: Handle<ir::Block>) -> Option<&mut ir::Block> {
        self.f.blocks.get_mut(b)
    }

    /// The open block, opened after the layout's last one when there is
    /// none (code after a terminator that no jump reaches yet).
    pub(super) fn open(&mut self) -> Handle<ir::Block> {
        match self.cur {
            Some(b) => b,
            None => {
                let b = self.new_block();
                self.f.layout.push(b);
                self.cur = Some(b);
                b
            }
        }
    }

    /// Ends the open block with `term`.
    pub(crate) fn terminate(&mut self, term: Terminator) {
        let b = self.open();
        let loc = match term {
            // (They add no code: the next statement keeps its start.)
            Terminator::Follow(_) | Terminator::Ended => Loc {
                fresh: false,
                ..self.loc_peek()
            },
            _ => self.loc(),
        };
        self.tail = match term {
            Terminator::Follow(_) | Terminator::Ended => self.tail,
            Terminator::Return { seq: None } => Tail::Ret,
            _ => Tail::Other,
        };
        if let Some(l) = self.f.term_locs.get_mut(b.index()) {
            *l = loc;
        }
        if let Some(blk) = self.block_mut(b) {
            blk.term = Some(term);
        }
        self.cur = None;
    }

    pub(super) fn loc_peek(&self) -> Loc {
        Loc {
            file: self.unit as u16,
            fresh: self.fresh,
            span: self.span,
        }
    }

    /// Lays `b` out here: the open block goes on into it.
    pub(super) fn place(&mut self, b: Handle<ir::Block>) {
        if self.cur.is_some() {
            self.terminate(Terminator::Follow(b));
        }
        self.f.layout.push(b);
        self.cur = Some(b);
    }

    /// A block that starts here: a jump target.
    pub(crate) fn here(&mut self) -> Handle<ir::Block> {
        match self.cur {
            Some(b) if self.f.blocks.get(b).is_some_and(|x| x.ops.is_empty()) => b,
            _ => {
                let b = self.new_block();
                self.place(b);
                b
            }
        }
    }

    /// Adds an operation to the open block.
    pub(crate) fn push(&mut self, op: Op) -> Handle<Op> {
        let loc = self.loc();
        self.tail = Tail::Other;
        self.push_at(op, loc)
    }

    pub(super) fn push_at(&mut self, op: Op, loc: Loc) -> Handle<Op> {
        let b = self.open();
        let h = self.f.ops.append(op);
        self.f.op_locs.push(loc);
        if let Some(blk) = self.block_mut(b) {
            blk.ops.push(h);
        }
        h
    }

    /// Ends the open block with an unconditional jump whose target is set
    /// later ([`Builder::patch_jump`]); returns the block.
    pub(crate) fn jump_later(&mut self) -> Handle<ir::Block> {
        let at = self.open();
        self.terminate(Terminator::Jump(at));
        at
    }

    /// As [`Builder::jump_later`], for a `GOTO n` (charged as a block).
    pub(super) fn goto_later(&mut self) -> Handle<ir::Block> {
        let at = self.open();
        self.terminate(Terminator::GotoKnown(at));
        at
    }

    /// The other way of an IF: a block that charges the IF to the budget
    /// (`at`'s branch goes there), alone, so that a jump to the code after
    /// it is not charged.
    pub(super) fn charge_otherwise(&mut self, at: Handle<ir::Block>) {
        let other = self.here();
        self.patch_branch(at, other);
        self.push(Op::Charge);
        self.here();
    }

    pub(crate) fn patch_jump(&mut self, at: Handle<ir::Block>, target: Handle<ir::Block>) {
        if let Some(ir::Block {
            term: Some(Terminator::Jump(t) | Terminator::GotoKnown(t)),
            ..
        }) = self.block_mut(at)
        {
            *t = target;
        }
    }

    /// Ends the open block with a branch on `cond` that goes on here when
    /// it holds; returns the block, whose other edge is set by
    /// [`Builder::patch_branch`].
    pub(super) fn branch(&mut self, cond: Handle<ir::Expr>) -> Handle<ir::Block> {
        let then = self.new_block();
        let at = self.open();
        self.terminate(Terminator::Branch {
            cond,
            then,
            otherwise: then,
        });
        self.place(then);
        at
    }

    pub(super) fn patch_branch(&mut self, at: Handle<ir::Block>, target: Handle<ir::Block>) {
        if let Some(ir::Block {
            term: Some(Terminator::Branch { otherwise, .. }),
            ..
        }) = self.block_mut(at)
        {
            *otherwise = target;
        }
    }

    /// A `/n` block's guard; [`Builder::end_guard`] ends the block.
    pub(crate) fn skip_guard(&mut self, switch: u8) -> Handle<ir::Block> {
        let next = self.new_block();
        let at = self.open();
        self.terminate(Terminator::Skip {
            switch,
            skip: next,
            next,
        });
        self.place(next);
        at
    }

    /// Points the guard ending `at` past the block just built, where both
    /// ways meet.
    pub(crate) fn end_guard(&mut self, at: Handle<ir::Block>) {
        let join = self.here();
        if let Some(ir::Block {
            term: Some(Terminator::Skip { skip, .. }),
            ..
        }) = self.block_mut(at)
        {
            *skip = join;
        }
        self.tail = Tail::Join;
    }

    /// Ends the open block with a call; the program goes on after it.
    pub(crate) fn call(&mut self, call: ir::Call) {
        let next = self.new_block();
        self.terminate(Terminator::Call { call, next });
        self.place(next);
    }

    /// Ends the open block with G65 H81–H86's conditional GOTO.
    pub(crate) fn goto_if(
        &mut self,
        seq: Handle<ir::Expr>,
        op: nc::value::Rel,
        j: Handle<ir::Expr>,
        k: Handle<ir::Expr>,
    ) {
        let next = self.new_block();
        let inside = self.in_loop;
        self.terminate(Terminator::GotoIf {
            seq,
            inside,
            op,
            j,
            k,
            next,
        });
        self.place(next);
    }

    /// An NC block's words, from `words` on, as an operation.
    pub(crate) fn nc_op(&mut self, start: usize, kind: ir::NcKind, msg: Option<ir::StrId>) {
        let words = (start as u32, self.f.words.len() as u32);
        self.push(Op::Nc(ir::NcBlock { words, kind, msg }));
    }

    pub(crate) fn words_len(&self) -> usize {
        self.f.words.len()
    }

    pub(crate) fn push_word(&mut self, addr: u8, value: ir::WordValue, span: Span) {
        self.f.words.push(ir::Word::new(addr, value));
        self.f.word_spans.push(span);
    }

    pub(crate) fn add_expr(&mut self, e: ir::Expr) -> Handle<ir::Expr> {
        self.f.exprs.append(e)
    }
}
