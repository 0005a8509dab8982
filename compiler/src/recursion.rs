//! W115 and W121: calls that nest too deep on every run (dialect.md
//! §7.12). A call is unconditional when its block carries no block delete
//! and comes before any jump, loop, IF, return or program end of its
//! program, so that every pass through the program reaches it; its target
//! is a literal program number.
//!
//! - W115: a program that reaches itself through such calls only calls
//!   deeper on every pass and ends in E6004 at run time.
//! - W121: a chain of such calls from the main program's start that goes
//!   past the nesting limits ends in E6004 at its last call on every run.

use crate::link::{self, Program, Unit};
use crate::words::{self, Call};
use grammar::ast::{Body, Stmt};
use grammar::{Diagnostic, Span};
use nc::base::nesting::{Levels, MAX_CALLS, MAX_MACRO_LEVELS, MAX_SUB_LEVELS};
use std::collections::HashSet;

/// One unconditional call: the program index it goes to, where it stands,
/// and whether it opens a macro level (G65) or a subprogram level (M98).
struct Edge {
    to: usize,
    span: Span,
    macro_level: bool,
}

/// The unconditional calls of program `p`.
fn edges(units: &[Unit], programs: &[Program], p: &Program) -> Vec<Edge> {
    let unit = &units[p.unit];
    let mut out = Vec::new();
    for b in p.blocks.iter().filter_map(|&l| link::block(unit, l)) {
        let ws = match &b.body {
            Body::Stmt(s) if matches!(**s, Stmt::Assign { .. }) => continue,
            Body::Stmt(_) => break,
            Body::Words(ws) => ws,
        };
        if !words::may_call(ws) {
            // No call (classify would give every word and no call): only
            // a program end matters, found without sorting the words.
            if ws
                .iter()
                .any(|w| is_end(words::addr_code(w.addr), words::value_of(w)))
            {
                break;
            }
            continue;
        }
        let Ok(split) = words::classify(ws) else {
            break;
        };
        let ends = split.nc.iter().any(|w| is_end(w.addr, w.value));
        let macro_level = matches!(split.call, Some(Call::Macro { .. }));
        let target = match &split.call {
            Some(Call::Sub {
                p: Some(t),
                l,
                span,
            }) => {
                // A computed L: not known to call at all.
                let l = match l {
                    Some(l) => l.literal().map(Some),
                    None => Some(None),
                };
                match (t.literal(), l) {
                    (Some(t), Some(l)) => Some((crate::calls::m98_target(t, l).0, *span)),
                    _ => None,
                }
            }
            Some(Call::Macro {
                modal: false,
                p: Some(t),
                span,
                ..
            }) => t
                .literal()
                .map(|t| (nc::block::round_half_away(t).max(0.0) as u32, *span)),
            Some(Call::Ret { .. }) => break,
            _ => None,
        };
        if let (Some((n, span)), None) = (target, b.delete) {
            if let Some(to) = programs.iter().position(|q| q.number == n) {
                out.push(Edge {
                    to,
                    span,
                    macro_level,
                });
            }
        }
        if ends {
            break;
        }
    }
    out
}

/// Whether a word is a literal M02 or M30.
fn is_end(addr: u8, value: words::WordValue<'_>) -> bool {
    addr == b'M' - b'A' && value.literal().is_some_and(|m| m == 2.0 || m == 30.0)
}

/// W115 at every unconditional call that leads back to its own program,
/// then W121 at every call of a chain from the main program's start that
/// goes past the nesting limits (not at a W115 call: it says so already).
pub fn check(units: &[Unit], programs: &[Program]) -> Vec<(usize, Diagnostic)> {
    let graph: Vec<Vec<Edge>> = programs.iter().map(|p| edges(units, programs, p)).collect();
    let mut found = Vec::new();
    let mut recursive = HashSet::new();
    for (from, p) in programs.iter().enumerate() {
        for e in &graph[from] {
            if reaches(&graph, e.to, from) {
                recursive.insert((p.unit, e.span));
                found.push((
                    p.unit,
                    Diagnostic::warning(
                        "W115",
                        e.span,
                        format!(
                            "O{:04} calls itself on every pass through this call: the calls nest until E6004; end the recursion with a condition",
                            p.number
                        ),
                    ),
                ));
            }
        }
    }
    let mut deep = Depths {
        programs,
        graph: &graph,
        seen: HashSet::new(),
        told: recursive,
        chain: Vec::new(),
        found: Vec::new(),
    };
    if !programs.is_empty() {
        deep.walk(0, Levels::default());
    }
    found.append(&mut deep.found);
    found
}

/// The walk of the unconditional calls from the main program's start, for
/// W121. Each (program, levels) is walked once, so however many calls a
/// program makes the walk is at most the graph's size times the few level
/// pairs there are.
struct Depths<'a> {
    programs: &'a [Program],
    graph: &'a [Vec<Edge>],
    seen: HashSet<(usize, Levels)>,
    /// Calls already warned of, by unit and place.
    told: HashSet<(usize, Span)>,
    /// The programs of the chain being walked, the main one first.
    chain: Vec<u32>,
    found: Vec<(usize, Diagnostic)>,
}

impl Depths<'_> {
    fn walk(&mut self, from: usize, levels: Levels) {
        if !self.seen.insert((from, levels)) {
            return;
        }
        let Some(p) = self.programs.get(from) else {
            return;
        };
        self.chain.push(p.number);
        for e in &self.graph[from] {
            match levels.enter(e.macro_level) {
                Some(next) => self.walk(e.to, next),
                None => self.too_deep(p.unit, e),
            }
        }
        self.chain.pop();
    }

    /// W121 at call `e`, which goes past a limit.
    fn too_deep(&mut self, unit: usize, e: &Edge) {
        if !self.told.insert((unit, e.span)) {
            return;
        }
        let (kind, limit) = match e.macro_level {
            true => ("macro", MAX_MACRO_LEVELS),
            false => ("subprogram", MAX_SUB_LEVELS),
        };
        // (The chain starts at the main program, whatever its number.)
        let chain: Vec<String> = core::iter::once("the main program".to_string())
            .chain(self.chain.iter().skip(1).map(|n| format!("O{n:04}")))
            .collect();
        let d = Diagnostic::warning(
            "W121",
            e.span,
            format!(
                "this call nests deeper than the control allows ({limit} {kind} levels, {MAX_CALLS} calls in all) on every run: the run stops here with E6004"
            ),
        )
        .with_note(format!(
            "the calls that reach it on every run: {}",
            chain.join(" → ")
        ));
        self.found.push((unit, d));
    }
}

/// Whether program `target` is reachable from `start` along the edges.
fn reaches(graph: &[Vec<Edge>], start: usize, target: usize) -> bool {
    let mut seen = vec![false; graph.len()];
    let mut stack = vec![start];
    while let Some(n) = stack.pop() {
        if n == target {
            return true;
        }
        if std::mem::replace(&mut seen[n], true) {
            continue;
        }
        stack.extend(graph[n].iter().map(|e| e.to));
    }
    false
}
