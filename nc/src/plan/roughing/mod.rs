//! The roughing cycles G71, G72 (types I and II) and G73 (cycles.md §5–§7,
//! §15) as paths: the profile's elements and the cycle's words in, the
//! legs out. The cycles compute in a *frame*: the real ZX plane for G71
//! and G73, the plane mirrored at r = z for G72, so that one algorithm
//! serves both stock-removal directions; [`Path`] records the legs in real
//! coordinates. The executor (`exec::compound`) reads the profile blocks
//! and prints the legs.

use alloc::format;
use alloc::vec::Vec;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::event::Dir;
use crate::base::point::Pt;
use crate::plan::curve::{swap, Axis, ConicKind, Curve, EPS};

pub mod pattern;
pub mod pockets;
pub mod rough;
pub mod turn;

/// One element of a profile.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Seg {
    pub curve: Curve,
    /// Written as G00: the ns infeed of the cycles is then a rapid.
    pub rapid: bool,
    /// The element of the first (ns) block.
    pub ns: bool,
    /// The tag of the profile block it comes from (`Nc::push_profile`),
    /// for errors about it.
    pub tag: u32,
}

impl Seg {
    /// The same element with its curve changed (moved, mirrored).
    pub fn map(self, f: impl Fn(&Curve) -> Curve) -> Seg {
        Seg {
            curve: f(&self.curve),
            ..self
        }
    }
}

/// A G71/G72 cycle in its frame (see the module comment).
pub struct Job {
    /// The cycle start A and A′ = A moved by the finishing allowance.
    pub a: Pt,
    pub a1: Pt,
    /// The offset profile P′ (K′ of type II), ns element first.
    pub segs: Vec<Seg>,
    /// Depth of cut Δd and retract e.
    pub dd: f64,
    pub e: f64,
    pub k1: bool,
    pub j1: bool,
}

/// Passes a cycle may make: a depth of cut far below the stock would
/// otherwise print millions of legs.
const MAX_PASSES: f64 = 100_000.0;

pub fn too_many(passes: f64) -> Result<(), NcError> {
    if passes <= MAX_PASSES {
        Ok(())
    } else {
        fail(
            Alarm::BadRoughing,
            format!("the cycle would make more than {MAX_PASSES} passes"),
        )
    }
}

/// The deepest point of a curve below the level `base` (r), infeed
/// direction `sx`: sx·(r − base) at its largest.
pub fn max_depth(c: &Curve, base: f64, sx: f64) -> f64 {
    let (lo, hi) = c.range(Axis::R, 0.0, 1.0);
    (sx * (lo - base)).max(sx * (hi - base))
}

/// Where the tail of a profile starts (cycles.md §5): the final elements
/// that lie on or outside the start level `base` at every point. The ns
/// element is never part of it, so `segs` holds the elements after it.
pub fn tail_start(segs: &[Seg], base: f64, sx: f64) -> usize {
    let mut t = segs.len();
    while t > 0 && max_depth(&segs[t - 1].curve, base, sx) <= EPS {
        t -= 1;
    }
    t
}

/// One leg of a roughing cycle, in real coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Step {
    Rapid(Pt),
    Line(Pt),
    Arc {
        to: Pt,
        centre: Pt,
        dir: Dir,
    },
    /// A piece of an ellipse (≤ 180°) or parabola: the same curve between
    /// its own ends, printed with the block's words.
    Conic {
        to: Pt,
        dir: Dir,
        kind: ConicKind,
    },
}

/// The legs of a cycle as it makes them. Generated legs take part in
/// neither corners nor compensation, and a leg to where the tool already
/// stands is left out (cycles.md §0).
pub struct Path {
    steps: Vec<Step>,
    /// Where the tool stands after the legs so far (real coordinates).
    at: Pt,
    /// The frame is mirrored (G72).
    mirrored: bool,
}

impl Path {
    /// An empty path from the tool position `at`.
    pub fn new(at: Pt, mirrored: bool) -> Path {
        Path {
            steps: Vec::new(),
            at,
            mirrored,
        }
    }

    /// The legs made.
    pub fn steps(&self) -> &[Step] {
        &self.steps
    }

    /// A frame point in real coordinates and back (the mirror is its own
    /// inverse).
    pub fn real(&self, p: Pt) -> Pt {
        if self.mirrored {
            swap(p)
        } else {
            p
        }
    }

    /// The tool position in the frame.
    pub fn pos(&self) -> Pt {
        self.real(self.at)
    }

    /// Whether the tool already stands at frame point `p` (within 1e-6 mm
    /// on X, as printed, and on Z).
    fn there(&self, p: Pt) -> bool {
        let (a, b) = (self.at, self.real(p));
        (a.x() - b.x()).abs() <= EPS && (a.z - b.z).abs() <= EPS
    }

    pub fn rapid(&mut self, to: Pt) {
        if self.there(to) {
            return;
        }
        self.at = self.real(to);
        self.steps.push(Step::Rapid(self.at));
    }

    pub fn line(&mut self, to: Pt) {
        if self.there(to) {
            return;
        }
        self.at = self.real(to);
        self.steps.push(Step::Line(self.at));
    }

    /// `RAPID` or `LINE` as the ns block's mode says.
    pub fn infeed(&mut self, rapid: bool, to: Pt) {
        if rapid {
            self.rapid(to);
        } else {
            self.line(to);
        }
    }

    /// The part [s0, s1] of a curve: a line at feed (or rapid), an arc at
    /// feed with the curve's centre and direction.
    pub fn piece(&mut self, c: &Curve, s0: f64, s1: f64, rapid: bool) {
        match *c {
            Curve::Line { .. } => self.infeed(rapid, c.at(s1)),
            Curve::Arc { centre, cw, .. } => {
                if c.length(s0, s1) <= EPS {
                    return;
                }
                let (to, centre) = (self.real(c.at(s1)), self.real(centre));
                // A mirror turns the direction round.
                let dir = if cw != self.mirrored {
                    Dir::Cw
                } else {
                    Dir::Ccw
                };
                self.at = to;
                self.steps.push(Step::Arc { to, centre, dir });
            }
            Curve::Conic { kind, cw, .. } => {
                if c.length(s0, s1) <= EPS {
                    return;
                }
                let to = self.real(c.at(s1));
                let dir = if cw != self.mirrored {
                    Dir::Cw
                } else {
                    Dir::Ccw
                };
                self.at = to;
                self.steps.push(Step::Conic { to, dir, kind });
            }
        }
    }

    /// A whole curve at feed, or its first element as the ns mode says.
    pub fn follow(&mut self, c: &Curve, rapid: bool) {
        self.piece(c, 0.0, 1.0, rapid);
    }
}
