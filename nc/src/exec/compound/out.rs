//! Printing the legs of a roughing cycle. The cycles compute in a *frame*:
//! the real ZX plane for G71 and G73, the plane mirrored at r = z for G72,
//! so that one algorithm serves both stock-removal directions.
//!
//! Legs are printed here rather than through `Nc::rapid`/`Nc::line`: those
//! are the path of programmed G00/G01 blocks (corners, compensation), and a
//! generated leg takes part in neither. Zero-length legs are not printed
//! (cycles.md §0).

use crate::base::event::{Dir, Event};
use crate::base::point::Pt;
use crate::exec::{Nc, Sink};
use crate::plan::curve::{swap, ConicKind, Curve, EPS};

pub struct Out<'a> {
    pub nc: &'a mut Nc,
    pub sink: &'a mut dyn Sink,
    /// The frame is mirrored (G72).
    pub mirrored: bool,
}

impl Out<'_> {
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
        self.real(self.nc.st.pos)
    }

    /// Whether the tool already stands at frame point `p` (within 1e-6 mm
    /// on X, as printed, and on Z).
    fn there(&self, p: Pt) -> bool {
        let (a, b) = (self.nc.st.pos, self.real(p));
        (a.x() - b.x()).abs() <= EPS && (a.z - b.z).abs() <= EPS
    }

    pub fn rapid(&mut self, to: Pt) {
        if self.there(to) {
            return;
        }
        let to = self.real(to);
        self.nc.st.pos = to;
        self.sink.emit(Event::Rapid {
            x: to.x(),
            z: to.z,
            c: None,
        });
    }

    pub fn line(&mut self, to: Pt) {
        if self.there(to) {
            return;
        }
        let to = self.real(to);
        self.nc.feed_due(self.sink);
        self.nc.st.pos = to;
        self.sink.emit(Event::Line {
            x: to.x(),
            z: to.z,
            c: None,
        });
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
                self.nc.feed_due(self.sink);
                self.nc.st.pos = to;
                self.sink.emit(Event::Arc {
                    dir,
                    x: to.x(),
                    z: to.z,
                    cx: centre.x(),
                    cz: centre.z,
                });
            }
            Curve::Conic { kind, cw, .. } => {
                if c.length(s0, s1) <= EPS {
                    return;
                }
                // A piece of an ellipse (≤ 180°) or parabola is the same
                // curve between its own ends: the block's words print it.
                let to = self.real(c.at(s1));
                let dir = if cw != self.mirrored {
                    Dir::Cw
                } else {
                    Dir::Ccw
                };
                self.nc.feed_due(self.sink);
                self.nc.st.pos = to;
                self.sink.emit(match kind {
                    ConicKind::Ellipse { a, b, q } => Event::Ellipse {
                        dir,
                        x: to.x(),
                        z: to.z,
                        a,
                        b,
                        q,
                    },
                    ConicKind::Parabola { p, q } => Event::Parabola {
                        dir,
                        x: to.x(),
                        z: to.z,
                        p,
                        q,
                    },
                });
            }
        }
    }

    /// A whole curve at feed, or its first element as the ns mode says.
    pub fn follow(&mut self, c: &Curve, rapid: bool) {
        self.piece(c, 0.0, 1.0, rapid);
    }
}
