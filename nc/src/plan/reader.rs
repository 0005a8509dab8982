//! Reading a parsed block's words as geometry, read-only: lengths in mm,
//! end points, the element of an arc, the corner word, the shape of a
//! conic. The executor reads its blocks through a [`Reader`] made from its
//! state; the profile reader (`plan::profile`) reads the ns…nf blocks of a
//! cycle with one made from the state the cycle starts in, and so could
//! the compiler.

use alloc::format;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::gcode::Motion;
use crate::base::geom::{self, Element};
use crate::base::machine::{ArcWithoutCenter, ChamferType, DecimalPoint, Machine};
use crate::base::mcode::M;
use crate::base::point::Pt;
use crate::base::words::{Word, COMMA_C, COMMA_R, NO_POINT};
use crate::block::Parsed;
use crate::plan::conic::{ellipse_centre, parabola_vertex};
use crate::plan::corner::Corner;
use crate::plan::curve::Curve;

/// What reading words needs besides the words.
#[derive(Debug, Clone, Copy)]
pub struct Reader<'a> {
    pub machine: &'a Machine,
    /// G20 in force: lengths are inches.
    pub inch: bool,
    /// Where the tool stands (work coordinates, X as a radius).
    pub at: Pt,
    /// The group-01 code in force.
    pub motion: Motion,
}

/// The shape words of a conic block.
#[derive(Debug, Clone, Copy)]
pub enum Shape {
    /// Semi-axes A, B (mm) and axis angle Q (degrees).
    Ellipse { a: f64, b: f64, q: f64 },
    /// Parameter P (mm) and axis angle Q (degrees, sign ignored).
    Parabola { p: f64, q: f64 },
}

impl Reader<'_> {
    /// mm per program unit.
    #[inline]
    pub fn unit(&self) -> f64 {
        if self.inch {
            25.4
        } else {
            1.0
        }
    }

    /// A length word in mm: the unit, and the decimal-point rule for
    /// literals written without a point in increment mode.
    #[inline]
    pub fn length(&self, w: Word) -> f64 {
        let mut v = w.value;
        if w.flags & NO_POINT != 0 && self.machine.machine.decimal_point == DecimalPoint::Increment
        {
            v *= if self.inch { 0.0001 } else { 0.001 };
        }
        v * self.unit()
    }

    #[inline]
    pub fn len_of(&self, p: &Parsed, letter: u8) -> Option<f64> {
        p.word(letter).map(|w| self.length(w))
    }

    /// An X-axis word (X, U, a diameter allowance) as a radial distance
    /// in mm: on the diameter or in radius programming as the machine has
    /// it ([`Machine::radial`]).
    #[inline]
    pub fn radial_of(&self, p: &Parsed, letter: u8) -> Option<f64> {
        self.len_of(p, letter).map(|v| self.machine.radial(v))
    }

    /// The end point of a move that starts at `from`: X/Z absolute, U/W
    /// incremental, axes left out keep their coordinate.
    pub fn target_from(&self, p: &Parsed, from: Pt) -> Pt {
        let mut t = from;
        if let Some(r) = self.radial_of(p, b'X') {
            t.r = r;
        } else if let Some(u) = self.radial_of(p, b'U') {
            t.r += u;
        }
        if let Some(z) = self.len_of(p, b'Z') {
            t.z = z;
        } else if let Some(w) = self.len_of(p, b'W') {
            t.z += w;
        }
        t
    }

    /// The element of a G02/G03 block from `from`: its arc from R or I/K,
    /// or a line where `arc_without_center = "line"`. `None` for a 0° arc
    /// with R (end = start), which is no move (W108), and for a block that
    /// names neither a centre nor an axis.
    pub fn arc_element(
        &self,
        from: Pt,
        cw: bool,
        to: Pt,
        p: &Parsed,
    ) -> Result<Option<Element>, NcError> {
        let centre = if let Some(r) = self.len_of(p, b'R') {
            match geom::centre_from_radius(from, to, r, cw)? {
                Some(c) => c,
                None => return Ok(None),
            }
        } else if p.has(b'I') || p.has(b'K') {
            let i = self.len_of(p, b'I').unwrap_or(0.0);
            let k = self.len_of(p, b'K').unwrap_or(0.0);
            let c = Pt::new(from.r + i, from.z + k);
            geom::check_on_circle(from, to, c, self.machine.machine.arc_tolerance_mm)?;
            c
        } else if !p.has_axis() {
            return Ok(None);
        } else {
            return match self.machine.machine.arc_without_center {
                ArcWithoutCenter::Line => Ok(Some(Element::Line { from, to })),
                ArcWithoutCenter::Alarm => fail(
                    Alarm::MissingWord,
                    format!(
                        "{} needs R or I/K to define its centre",
                        if cw { "G02" } else { "G03" }
                    ),
                ),
            };
        };
        Ok(Some(Element::Arc {
            from,
            to,
            centre,
            cw,
        }))
    }

    /// The arc of a G05 (mid point I/K relative to the start) or G05.1
    /// (`absolute` mid point) block from `from` to `to`.
    pub fn three_point(
        &self,
        absolute: bool,
        p: &Parsed,
        from: Pt,
        to: Pt,
    ) -> Result<Element, NcError> {
        if !p.has(b'I') && !p.has(b'K') {
            return fail(Alarm::MissingWord, "G05 needs the mid point I/K");
        }
        let i = self.len_of(p, b'I');
        let k = self.len_of(p, b'K');
        let mid = if absolute {
            // (I is then an X value: a diameter, unless in radius programming.)
            Pt::new(
                i.map_or(from.r, |x| self.machine.radial(x)),
                k.unwrap_or(from.z),
            )
        } else {
            Pt::new(from.r + i.unwrap_or(0.0), from.z + k.unwrap_or(0.0))
        };
        let (centre, cw) = geom::circle_through(from, mid, to)?;
        Ok(Element::Arc {
            from,
            to,
            centre,
            cw,
        })
    }

    /// The corner word of a block whose motion is `code` (dialect.md §5.1,
    /// §5.3): `L`/`,C` chamfer, `D`/`,R` rounding. E2040 for both at once,
    /// on G00, or not greater than 0. Other motions give L and D other
    /// meanings.
    pub fn corner_word(&self, code: Motion, p: &Parsed) -> Result<Option<Corner>, NcError> {
        if !p.has_corner_word() {
            return Ok(None);
        }
        // With M98 the L is the repeat count.
        let l = p.word(b'L').filter(|_| !p.has_m(M::SubCall));
        let comma_c = p.word_at(COMMA_C);
        let chamfer = l.or(comma_c);
        let round = p.word(b'D').or(p.word_at(COMMA_R));
        let Some(word) = chamfer.or(round) else {
            return Ok(None);
        };
        if !(code.is_straight() || code.is_arc()) {
            return Ok(None);
        }
        if code == Motion::Rapid {
            let e = NcError::new(
                Alarm::BadCornerLength,
                "a chamfer or corner rounding cannot be given on G00",
            );
            // A mill's habit: `G41 D1`, `T0101 D1` (an offset number).
            return Err(match p.word(b'D') {
                Some(_) => e.with_help(
                    "D is a corner rounding here, not an offset number: the T word selects the tool's offset, and G41/G42 take the nose radius from it",
                ),
                None => e,
            });
        }
        if chamfer.is_some() && round.is_some() {
            return fail(
                Alarm::BadCornerLength,
                "a block takes either a chamfer or a corner rounding, not both",
            );
        }
        let size = self.length(word);
        // Written so that a NaN fails too.
        if size.partial_cmp(&0.0) != Some(core::cmp::Ordering::Greater) {
            return fail(
                Alarm::BadCornerLength,
                "a chamfer or corner radius must be greater than 0",
            );
        }
        Ok(Some(match chamfer {
            // ,C is always Fanuc's type II; L follows №181.0.
            Some(_) if comma_c.is_some() => Corner::Chamfer {
                size,
                kind: ChamferType::II,
                word: word.addr,
            },
            Some(_) => Corner::Chamfer {
                size,
                kind: self.machine.cycles.chamfer_type,
                word: word.addr,
            },
            None => Corner::Round {
                radius: size,
                word: word.addr,
            },
        }))
    }

    /// The shape words of a G6.2/G6.3 (`ellipse`) or G7.2/G7.3 block.
    pub fn conic_shape(&self, ellipse: bool, p: &Parsed) -> Result<Shape, NcError> {
        let q = p.get(b'Q').unwrap_or(0.0) * 0.001;
        if ellipse {
            return Ok(Shape::Ellipse {
                a: self.len_of(p, b'A').unwrap_or(0.0),
                b: self.len_of(p, b'B').unwrap_or(0.0),
                q,
            });
        }
        // P is an integer in increments, its sign ignored.
        let inc = if self.inch { 0.0001 * 25.4 } else { 0.001 };
        let pp = p.get(b'P').unwrap_or(0.0).abs() * inc;
        if pp <= 0.0 {
            return fail(
                Alarm::BadParabola,
                "G7.2/G7.3 need a parameter P greater than 0",
            );
        }
        Ok(Shape::Parabola { p: pp, q: q.abs() })
    }

    /// The curve of a conic block from `from` to `to` as a contour
    /// element: an ellipse with A = B is the circular arc it prints as.
    /// `None` when the block does not move.
    pub fn conic_curve(
        &self,
        ellipse: bool,
        cw: bool,
        p: &Parsed,
        from: Pt,
        to: Pt,
    ) -> Result<Option<Curve>, NcError> {
        match self.conic_shape(ellipse, p)? {
            Shape::Ellipse { a, b, q } => {
                let Some(c) = ellipse_centre(from, to, a, b, q, cw)? else {
                    return Ok(None);
                };
                Ok(Some(if (a - b).abs() < 1e-9 {
                    Curve::new(Element::Arc {
                        from,
                        to,
                        centre: c,
                        cw,
                    })
                } else {
                    Curve::ellipse(from, to, c, a, b, q, cw)
                }))
            }
            Shape::Parabola { p: pp, q } => {
                if from.dist(to) < 1e-9 {
                    return Ok(None);
                }
                let vertex = parabola_vertex(from, to, pp, q, cw)?;
                Ok(Some(Curve::parabola(from, to, vertex, pp, q, cw)))
            }
        }
    }
}
