//! Data setting at compile time (dialect.md §4.9): `G10 L3 … G11` and
//! `G10 L52 … G11`, read once over the syntax tree right after parsing.
//!
//! - Inside `G10 L52` the `N` word is a parameter number, not a sequence
//!   number (§1.6). The grammar cannot know the mode, so it parses `N` as
//!   the block's sequence number; this pass moves it back into the block's
//!   words. Everything after it (GOTO targets, W103, G70–G73 `P`/`Q`,
//!   E2022) then never sees it as a sequence number, and the kernel gets
//!   it as an ordinary `N` word.
//! - `R#100` names the variable that receives the parameter: the pass
//!   rewrites the word's value to the variable's number (`R100`, or
//!   `R[#1]` for `R#[#1]`), so the VM hands 100 — not the value of #100 —
//!   to the kernel, which answers with the variable to set
//!   (`Outcome::store`). The lowering forgets the folded value of that
//!   variable after the block.
//! - Diagnostics: E2004 (other G10 forms), E2050 (unknown literal
//!   parameter), E2099 (PLC parameters K/D), E2006/E2007 (neither or both of
//!   R and W), and W104 for the words a mode ignores and for a G11 without
//!   G10.
//!
//! The modes are followed in the order the blocks are written, program by
//! program (block delete aside); the kernel follows them as the program
//! runs. The rewrite runs at parse time ([`prepare`]), because the lowering
//! and the profile module read the sequence numbers of a whole program
//! first; the diagnostics come while lowering ([`Checker`]), in block
//! order with the others.

use grammar::ast::{Addr, Ast, Block, Body, Expr, Line, Number, Value, VarIndex, Word};
use grammar::Span;

use crate::build::Builder as Gen;
use nc::block::round_half_away;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
enum Mode {
    #[default]
    Off,
    ToolLife,
    Parameters,
}

/// What a block is to data setting, given the mode before it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Role {
    /// `G10 L3` / `G10 L52`.
    Open(Mode),
    /// G10 with an L the kernel judges at run time (`G10 L#1`).
    OpenComputed,
    /// G10 with no L or another literal L: E2004.
    OtherG10,
    /// G11, and whether a mode was open.
    Close(bool),
    /// A block inside a mode.
    Inside(Mode),
    Outside,
}

impl Role {
    fn mode_after(self, before: Mode) -> Mode {
        match self {
            Role::Open(m) => m,
            Role::OpenComputed | Role::OtherG10 | Role::Close(_) => Mode::Off,
            Role::Inside(_) | Role::Outside => before,
        }
    }
}

fn role(ws: &[Word], mode: Mode) -> Role {
    if let Some(g) = ws.iter().find(|w| opens_or_closes(w)) {
        if literal_g(g) == Some(110) {
            return Role::Close(mode != Mode::Off);
        }
        return match find(ws, 'L').map(|l| &l.value) {
            Some(Value::Number(n)) if n.value == 3.0 => Role::Open(Mode::ToolLife),
            Some(Value::Number(n)) if n.value == 52.0 => Role::Open(Mode::Parameters),
            Some(Value::Expr(_)) => Role::OpenComputed,
            _ => Role::OtherG10,
        };
    }
    match mode {
        Mode::Off => Role::Outside,
        m => Role::Inside(m),
    }
}

/// Right after parsing: gives the `N` of every `G10 L52` block back to its
/// words and turns its `R#var` into the variable number.
pub fn prepare(ast: &mut Ast) {
    let mut mode = Mode::Off;
    for line in &mut ast.lines {
        let b = match line {
            Line::ProgramStart(_) => {
                mode = Mode::Off;
                continue;
            }
            Line::Block(b) => b,
            Line::Percent(_) => continue,
        };
        let Body::Words(ws) = &mut b.body else {
            continue;
        };
        let r = role(ws, mode);
        if r == Role::Inside(Mode::Parameters) {
            if let Some(seq) = b.seq.take() {
                ws.insert(0, parameter_word(seq.number, seq.span));
            }
            if let Some(r) = ws.iter_mut().find(|w| letter(w) == Some('R')) {
                to_variable_number(r);
            }
        }
        mode = r.mode_after(mode);
    }
}

/// Whether a word is a literal G10 or G11.
fn opens_or_closes(w: &Word) -> bool {
    match &w.value {
        // (Only a value between 9 and 12 rounds to either: the rest, most
        // G words, are told without the rounding.)
        Value::Number(n) if (9.0..=12.0).contains(&n.value) => {
            matches!(literal_g(w), Some(100 | 110))
        }
        _ => false,
    }
}

/// The literal code of a G word ×10 (`G10` → 100).
fn literal_g(w: &Word) -> Option<i64> {
    match (&w.addr, &w.value) {
        (Addr::Letter('G'), Value::Number(n)) => Some(round_half_away(n.value * 10.0) as i64),
        _ => None,
    }
}

fn letter(w: &Word) -> Option<char> {
    match w.addr {
        Addr::Letter(c) => Some(c),
        Addr::Comma(_) => None,
    }
}

fn find(ws: &[Word], c: char) -> Option<&Word> {
    ws.iter().find(|w| letter(w) == Some(c))
}

/// The `N` word that the grammar took for a sequence number.
fn parameter_word(number: u32, span: Span) -> Word {
    Word {
        addr: Addr::Letter('N'),
        value: Value::Number(Number {
            value: number as f64,
            has_point: false,
            decimals: 0,
            span,
        }),
        span,
    }
}

/// The diagnostics of data setting, block by block while a program is
/// lowered (so they stand in block order with the others).
#[derive(Debug, Default)]
pub struct Checker {
    mode: Mode,
    /// Inside G10 L3: a `P` group block has come (tools have a group).
    group_open: bool,
}

impl Checker {
    pub fn block(&mut self, gen: &mut Gen<'_>, b: &Block) {
        let Body::Words(ws) = &b.body else {
            return;
        };
        let r = role(ws, self.mode);
        match r {
            Role::Open(_) => ignored(gen, ws, &['L'], "a G10 block"),
            Role::OtherG10 => {
                let at = find(ws, 'L').map_or(b.span, |l| l.span);
                gen.error(
                    "E2004",
                    at,
                    "only G10 L3 (tool life) and G10 L52 (parameters) are GSK980TDi data setting; \
                     Fanuc G10 offset and work-offset input (G10 P… X… Z…, G10 L2) is not in this dialect",
                );
            }
            Role::Close(open) => {
                if !open {
                    let at = ws
                        .iter()
                        .find(|w| literal_g(w) == Some(110))
                        .map_or(b.span, |w| w.span);
                    gen.warn(
                        "W104",
                        at,
                        "G11 without G10 L3 or G10 L52 before it: nothing to end",
                    );
                }
                ignored(gen, ws, &[], "a G11 block");
            }
            Role::Inside(Mode::ToolLife) => self.tool_life_block(gen, ws),
            Role::Inside(_) => parameter_block(gen, ws),
            Role::OpenComputed | Role::Outside => {}
        }
        if matches!(r, Role::Open(_)) {
            self.group_open = false;
        }
        self.mode = r.mode_after(self.mode);
    }

    fn tool_life_block(&mut self, gen: &mut Gen<'_>, ws: &[Word]) {
        self.group_open |= find(ws, 'P').is_some();
        match find(ws, 'T') {
            Some(t) if !self.group_open => gen.warn(
                "W104",
                t.span,
                "T is ignored in G10 L3 before the first group (P… L…): it has no group",
            ),
            _ => {}
        }
        ignored(gen, ws, &['P', 'L', 'Q', 'T'], "G10 L3 (tool-life data)");
    }
}

/// W104 for every word of the block but G10/G11 and the letters `used`.
/// Calls and returns (M98, M99, M9xxx, G65–G67 blocks) still happen inside
/// the modes: they are program flow, which the kernel never sees.
fn ignored(gen: &mut Gen<'_>, ws: &[Word], used: &[char], what: &str) {
    if ws
        .iter()
        .any(|w| matches!(literal_g(w), Some(650 | 660 | 670)))
    {
        return;
    }
    for w in ws {
        let kept = letter(w).is_some_and(|c| used.contains(&c))
            || matches!(literal_g(w), Some(100 | 110))
            || is_call(w);
        if !kept {
            gen.warn("W104", w.span, format!("{} is ignored in {what}", w.addr));
        }
    }
}

/// M98, M99, M9000–M9999.
fn is_call(w: &Word) -> bool {
    match (&w.addr, &w.value) {
        (Addr::Letter('M'), Value::Number(n)) => {
            n.value == 98.0 || n.value == 99.0 || (9000.0..=9999.0).contains(&n.value)
        }
        _ => false,
    }
}

/// A block inside `G10 L52` (already prepared): `N [P] R` or `N [P] W`.
fn parameter_block(gen: &mut Gen<'_>, ws: &[Word]) {
    if let Some(plc) = ws.iter().find(|w| matches!(letter(w), Some('K' | 'D'))) {
        gen.error(
            "E2099",
            plc.span,
            "PLC parameters (K, D, DT, DC) in G10 L52 are not implemented yet",
        );
        return;
    }
    let Some(n) = find(ws, 'N') else {
        ignored(gen, ws, &[], "G10 L52 without a parameter number N");
        return;
    };
    if let Value::Number(num) = &n.value {
        let number = round_half_away(num.value);
        if !(0.0..=99999.0).contains(&number) || !nc::params::exists(number as u32) {
            gen.error(
                "E2050",
                n.span,
                format!("there is no parameter №{number:03} on this machine (machine.md §2)"),
            );
        }
    }
    match (find(ws, 'R').is_some(), find(ws, 'W').is_some()) {
        (true, true) => gen.error(
            "E2007",
            n.span,
            "R reads the parameter and W writes it: write one of them",
        ),
        (false, false) => gen.error(
            "E2006",
            n.span,
            "a parameter block needs R<#variable> to read or W<value> to write",
        ),
        _ => {}
    }
    ignored(gen, ws, &['N', 'P', 'R', 'W'], "G10 L52 (parameters)");
}

/// `R#100` → `R100`, `R#[e]` → `R[e]`: the word carries the number of the
/// variable to fill, not its value. A literal (`R100`) already is one
/// (seed: R is "the read address, only a macro variable number").
fn to_variable_number(r: &mut Word) {
    let Value::Expr(e) = &r.value else {
        return;
    };
    let Expr::Var(v) = &**e else {
        return;
    };
    r.value = match &v.index {
        VarIndex::Number(n, span) => Value::Number(Number::digits(*n, *span)),
        VarIndex::Expr(e) => Value::Expr(e.clone()),
    };
}
