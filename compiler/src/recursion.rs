//! W115: unconditional call recursion (dialect.md §7.12). A call is
//! unconditional when its block carries no block delete and comes before
//! any jump, loop, IF, return or program end of its program, so that every
//! pass through the program reaches it; its target is a literal program
//! number. A program that reaches itself through such calls only calls
//! deeper on every pass and ends in E6004 at run time.

use crate::link::{self, Program, Unit};
use crate::words::{self, Call};
use grammar::ast::{Body, Stmt};
use grammar::{Diagnostic, Span};

/// One unconditional call: the program index it goes to, where it stands.
struct Edge {
    to: usize,
    span: Span,
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
                out.push(Edge { to, span });
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

/// W115 at every unconditional call that leads back to its own program.
pub fn check(units: &[Unit], programs: &[Program]) -> Vec<(usize, Diagnostic)> {
    let graph: Vec<Vec<Edge>> = programs.iter().map(|p| edges(units, programs, p)).collect();
    let mut found = Vec::new();
    for (from, p) in programs.iter().enumerate() {
        for e in &graph[from] {
            if reaches(&graph, e.to, from) {
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
    found
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
