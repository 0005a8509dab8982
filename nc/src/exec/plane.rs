//! Polar interpolation (G12.1/G13.1 with G15/G16) and cylindrical
//! interpolation (G7.1 type I) on a machine with a C axis (dialect.md
//! §4.6, seed 000; decisions in docs/language.md "Polar and cylindrical
//! interpolation").
//!
//! Between G12.1 and G13.1 the program writes a Cartesian plane: X (a
//! diameter, as everywhere) and the hypothetical axis C (mm, a radius
//! value) perpendicular to it, both measured from the spindle centre. G16
//! reads X as the distance from the centre (mm) and C as the angle
//! (degrees, counter-clockwise from +X). Between `G7.1 C<r>` and `G7.1 C0`
//! it writes the surface of the cylinder of radius r developed flat: Z
//! and C in degrees, which count as the arc length r·C·π/180 along the
//! surface. The canon prints the moves in the plane (`RAPID`, `LINE`,
//! `ARC` with the plane's letters, event.rs); the runtime turns them into
//! joint motion of X, C (polar) or Z, C (cylinder) at the programmed
//! tangential feed (runtime/src/polar.rs). The axis outside the plane, Z
//! (polar) or X (cylinder), moves in a G00/G01 block of its own, the plane
//! point standing (seed 000), or along a G00/G01 of the plane, in
//! proportion (`PlaneMove`'s `off`; not under compensation); an arc
//! ignores it.
//!
//! The kernel keeps the joint position current after every move: `pos`
//! (X and Z) and `c`, which follows the path continuously (a circle about
//! the centre turns C by 360°), so #5041…, later C moves and G13.1 see
//! where the axes are.
//!
//! Arc geometry works in `Pt` with the plane's first axis as `z` and its
//! second as `r`, so that base/geom's "counter-clockwise from +Z" is
//! counter-clockwise as seen with the first axis to the right and the
//! second up: G17 (X, C) for polar, G19 (C, Z) for the cylinder, as Fanuc
//! orients them.

use alloc::format;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::event::{Dir, Event, Plane, PlaneMotion};
use crate::base::gcode::{self, Comp, Drill, FeedMode, Motion, OneShot, Polar, PolarCmd, G};
use crate::base::geom::{self, Element};
use crate::base::point::Pt;
use crate::base::words::addr;
use crate::block::Parsed;
use crate::exec::{Nc, Outcome, Sink};

mod conic;
pub(crate) use conic::printed_curve;

/// Which interpolation is on, and the plane's own data.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Kind {
    Polar,
    /// The cylinder's radius, mm.
    Cylinder(f64),
}

/// The state of polar or cylindrical interpolation while it is on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneState {
    pub kind: Kind,
    /// The programmed point in the plane (module comment): `z` the first
    /// axis (polar X as a radius, cylinder developed C), `r` the second
    /// (polar hypothetical C, cylinder Z).
    pub pt: Pt,
    /// Where the tool's path was last printed to: the programmed point,
    /// but under nose-radius compensation (`print_element`).
    pub tool: Pt,
}

impl PlaneState {
    fn plane(&self) -> Plane {
        match self.kind {
            Kind::Polar => Plane::Polar,
            Kind::Cylinder(_) => Plane::Cylinder,
        }
    }

    fn what(&self) -> &'static str {
        match self.kind {
            Kind::Polar => "polar interpolation (G12.1)",
            Kind::Cylinder(_) => "cylindrical interpolation (G7.1)",
        }
    }

    /// The canon's two numbers of a plane point: polar X (diameter) and C
    /// (mm), cylinder Z and C (degrees).
    fn printed(&self, p: Pt) -> (f64, f64) {
        match self.kind {
            Kind::Polar => (2.0 * p.z, p.r),
            Kind::Cylinder(radius) => (p.r, (p.z / radius).to_degrees()),
        }
    }

    /// The plane point of the canon's two numbers (`printed` undone).
    pub(crate) fn point(&self, a: f64, b: f64) -> Pt {
        match self.kind {
            Kind::Polar => Pt::new(b, a / 2.0),
            Kind::Cylinder(radius) => Pt::new(a, radius * b.to_radians()),
        }
    }

    /// The work point of the X/Z joints (the tool's X is its distance
    /// from the centre in polar interpolation, Z the cylinder's second
    /// axis) when the plane point is `p` and the joints were at `at`.
    pub(crate) fn joints(&self, p: Pt, at: Pt) -> Pt {
        match self.kind {
            Kind::Polar => Pt::new(libm::hypot(p.z, p.r), at.z),
            Kind::Cylinder(_) => Pt::new(at.r, p.r),
        }
    }
}

/// The mode in force, by name: polar or cylindrical interpolation.
pub(crate) fn mode_name(nc: &Nc) -> Option<&'static str> {
    nc.st.plane.map(|st| st.what())
}

/// Whether the block starts polar or cylindrical interpolation.
fn starts(nc: &Nc, p: &Parsed) -> bool {
    p.has_g(Polar::On)
        || (p.one_shot() == Some(OneShot::Cylindrical)
            && nc.st.plane.is_none()
            && p.get(b'C').is_some_and(|c| c != 0.0))
}

/// Before a block: what cannot happen inside either mode, and a corner
/// still waiting is printed whole before a mode starts.
#[inline]
pub(crate) fn before_block(nc: &mut Nc, p: &Parsed, sink: &mut dyn Sink) -> Result<(), NcError> {
    // Outside both modes a block without G12.1 or a group-00 code (G7.1)
    // neither starts one nor is checked: the usual block stops here.
    if nc.st.plane.is_none() && p.one_shot().is_none() && !p.has_g(Polar::On) {
        return Ok(());
    }
    check_block(nc, p, sink)
}

fn check_block(nc: &mut Nc, p: &Parsed, sink: &mut dyn Sink) -> Result<(), NcError> {
    let starting = starts(nc, p);
    if starting {
        crate::exec::contour::flush(nc, sink)?;
    }
    // A block that starts a mode runs the rest of its words inside it
    // (group 0 comes before T and the motion, canon.md).
    let (what, polar) = match (nc.st.plane, starting) {
        (Some(st), _) => (st.what(), st.kind == Kind::Polar),
        (None, true) if p.has_g(Polar::On) => ("polar interpolation (G12.1)", true),
        (None, true) => ("cylindrical interpolation (G7.1)", false),
        (None, false) => return Ok(()),
    };
    if p.has(b'T') {
        let msg =
            format!("no tool or offset change during {what}: change the tool before it starts");
        return Err(NcError::new(Alarm::PolarInComp, msg).on_addr(addr(b'T')));
    }
    if let Some(n) = p
        .gs()
        .position(|g| g == G::FeedMode(FeedMode::PerRev))
        .filter(|_| polar)
    {
        let msg = "G99 during polar interpolation: its F is a tangential feed per minute";
        return Err(NcError::new(Alarm::PolarInComp, msg).on_nth(addr(b'G'), n));
    }
    // Drilling cycles and work systems have no meaning in the plane: a
    // cycle would run as one rapid to its bottom, a new zero move the
    // plane under the tool.
    let refused = p.gs().enumerate().find(|(_, g)| match g {
        G::Drill(d) => *d != Drill::Off,
        G::Work(_) => true,
        _ => false,
    });
    if let Some((n, g)) = refused {
        let msg = format!("{} cannot run during {what}", gcode::name(g.code()));
        return Err(NcError::new(Alarm::IncompatibleWords, msg).on_nth(addr(b'G'), n));
    }
    Ok(())
}

/// Whether the block writes the axis outside the plane: Z (W) in polar
/// interpolation, X (U) in cylindrical.
fn other_axis(kind: Kind, p: &Parsed) -> bool {
    match kind {
        Kind::Polar => p.has(b'Z') || p.has(b'W'),
        Kind::Cylinder(_) => p.has(b'X') || p.has(b'U'),
    }
}

/// Whether the block writes a coordinate of the plane.
fn plane_words(kind: Kind, p: &Parsed) -> bool {
    let first = match kind {
        Kind::Polar => p.has(b'X') || p.has(b'U'),
        Kind::Cylinder(_) => p.has(b'Z') || p.has(b'W'),
    };
    first || p.has(b'C') || p.has(b'H')
}

/// The checks every start shares: compensation off, feed per minute, no
/// other mode on, nothing else in the block.
fn check_start(nc: &Nc, p: &Parsed, what: &str) -> Result<(), NcError> {
    if nc.st.modal.comp() != Comp::Off || crate::exec::comp::running(nc) {
        return fail(
            Alarm::PolarInComp,
            format!("{what} cannot start while nose-radius compensation is on: cancel it with G40 first"),
        );
    }
    if nc.st.per_rev() {
        return fail(
            Alarm::PolarInComp,
            format!("{what} cannot start in G99: its F is a tangential feed per minute (G98)"),
        );
    }
    if let Some(other) = nc.st.plane {
        return fail(
            Alarm::IncompatibleWords,
            format!("{what} cannot start during {}", other.what()),
        );
    }
    if let Some(drill) = nc.st.modal.drill() {
        return fail(
            Alarm::IncompatibleWords,
            format!(
                "{what} cannot start while {} is in force: cancel it with G80 first",
                gcode::name(G::Drill(drill).code())
            ),
        );
    }
    if p.has_axis() {
        return fail(
            Alarm::IncompatibleWords,
            format!("{what} stands alone in its block: move before it or after it"),
        );
    }
    Ok(())
}

/// G12.1: polar interpolation on, from the current point with C at 0°.
pub(crate) fn polar_on(nc: &mut Nc, p: &Parsed, sink: &mut dyn Sink) -> Result<(), NcError> {
    let what = "G12.1 polar interpolation";
    if !nc.machine.axes.c.enabled {
        return fail(Alarm::MissingEquipment, format!("{what} needs a C axis"));
    }
    check_start(nc, p, what)?;
    if p.has(b'C') || p.has(b'H') {
        return fail(
            Alarm::IncompatibleWords,
            format!("{what} stands alone in its block: move before it or after it"),
        );
    }
    let turns = nc.st.c / 360.0;
    if (turns - libm::round(turns)).abs() * 360.0 > 1e-6 {
        return fail(
            Alarm::PolarInComp,
            format!(
                "{what} starts with C at 0 degrees, C is at {:.4}: turn it to 0 first (G00 C0)",
                nc.st.c
            ),
        );
    }
    if nc.st.pos.r < 0.0 {
        // (The plane's joints put a point of negative x at C 180°: the
        // axes would have to jump there.)
        return fail(
            Alarm::PolarInComp,
            format!(
                "{what} starts with the tool at a positive X (C at 0 degrees is the plane's +X), X is {:.4}: move to a positive X first",
                nc.machine.programmed_x(nc.st.pos.r)
            ),
        );
    }
    nc.st.modal.polar = Polar::On;
    let pt = Pt::new(0.0, nc.st.pos.r);
    nc.st.plane = Some(PlaneState {
        kind: Kind::Polar,
        pt,
        tool: pt,
    });
    sink.emit(Event::PolarOn);
    Ok(())
}

/// G13.1: polar interpolation off (nothing when it is not on); G16 ends
/// with it.
pub(crate) fn polar_off(nc: &mut Nc, p: &Parsed, sink: &mut dyn Sink) -> Result<(), NcError> {
    if p.has_axis() || p.has(b'C') || p.has(b'H') {
        return fail(
            Alarm::IncompatibleWords,
            "G13.1 stands alone in its block: move before it or after it",
        );
    }
    let on = matches!(
        nc.st.plane,
        Some(PlaneState {
            kind: Kind::Polar,
            ..
        })
    );
    if on {
        ends_uncompensated(nc, "G13.1")?;
    }
    nc.st.modal.polar = Polar::Off;
    nc.st.modal.polar_cmd = PolarCmd::Off;
    if on {
        nc.st.plane = None;
        sink.emit(Event::PolarOff {
            x: nc.st.pos.x(),
            c: nc.st.c,
        });
    }
    Ok(())
}

/// E4033 where a mode ends (`what`) while nose-radius compensation is on:
/// its last element would end off the path, in the plane's coordinates.
fn ends_uncompensated(nc: &Nc, what: &str) -> Result<(), NcError> {
    if crate::exec::comp::compensating(nc) {
        return fail(
            Alarm::PolarInComp,
            format!("{what} while nose-radius compensation is on: cancel it first (G40 and a move in the plane)"),
        );
    }
    Ok(())
}

/// G16 only inside G12.1 (E2007).
pub(crate) fn polar_command(nc: &mut Nc, code: PolarCmd) -> Result<(), NcError> {
    let polar = matches!(
        nc.st.plane,
        Some(PlaneState {
            kind: Kind::Polar,
            ..
        })
    );
    if code == PolarCmd::On && !polar {
        return fail(
            Alarm::IncompatibleWords,
            "G16 (polar coordinates) works only during polar interpolation: write G12.1 before it",
        );
    }
    nc.st.modal.polar_cmd = code;
    Ok(())
}

/// G7.1: `C<radius>` starts cylindrical interpolation, `C0` ends it; the
/// roughing form with J L R K is not supported yet (cycles.md §23).
pub(crate) fn cylinder(nc: &mut Nc, p: &Parsed, sink: &mut dyn Sink) -> Result<(), NcError> {
    let what = "G7.1 cylindrical interpolation";
    if !nc.machine.axes.c.enabled {
        return fail(Alarm::MissingEquipment, format!("{what} needs a C axis"));
    }
    if [b'J', b'L', b'R', b'K'].iter().any(|&l| p.has(l)) {
        return fail(
            Alarm::NotSupportedYet,
            "G7.1 type II (the roughing cycle with J L R K) is not supported yet",
        );
    }
    let Some(radius) = nc.len_of(p, b'C') else {
        return fail(
            Alarm::MissingWord,
            "G7.1 needs C: the cylinder's radius to start, C0 to end",
        );
    };
    if radius < 0.0 || !radius.is_finite() {
        return fail(
            Alarm::ValueOutOfRange,
            format!("G7.1 C{radius}: the cylinder's radius cannot be negative"),
        );
    }
    if radius == 0.0 {
        if matches!(
            nc.st.plane,
            Some(PlaneState {
                kind: Kind::Cylinder(_),
                ..
            })
        ) {
            ends_uncompensated(nc, "G7.1 C0")?;
            nc.st.plane = None;
            sink.emit(Event::Cylinder(None));
        }
        return Ok(());
    }
    check_start(nc, p, what)?;
    let pt = Pt::new(nc.st.pos.z, radius * nc.st.c.to_radians());
    nc.st.plane = Some(PlaneState {
        kind: Kind::Cylinder(radius),
        pt,
        tool: pt,
    });
    sink.emit(Event::Cylinder(Some(radius)));
    Ok(())
}

/// The block's motion while a mode is on: G00, G01, G02, G03 in the
/// plane, G04; nothing else.
pub(crate) fn motion(
    nc: &mut Nc,
    st: PlaneState,
    p: &Parsed,
    sink: &mut dyn Sink,
    out: &mut Outcome,
) -> Result<(), NcError> {
    let Some(code) = plane_code(nc, &st, p, sink, out)? else {
        return Ok(());
    };
    let arc = code.is_arc();
    // In an arc, an ellipse or a parabola the axis outside the plane is
    // ignored (seed 000: the compiler warns, W104); a straight move takes
    // it along.
    let curved = arc || code.is_conic();
    let off = (!curved && other_axis(st.kind, p)).then(|| off_target(nc, st.kind, p));
    let to = target(nc, &st, p);
    if off.is_some() && (!plane_words(st.kind, p) || to == st.pt) {
        // The axis alone, the plane point standing (held behind a
        // compensated element that waits).
        crate::exec::comp::moved_off_plane(nc);
        crate::exec::contour::in_order(nc, sink, |nc, s| {
            axis_move(nc, st, code == Motion::Rapid, p, s);
            Ok(())
        })?;
        out.moved = true;
        return Ok(());
    }
    let moves = plane_words(st.kind, p);
    if code.is_conic() && moves {
        return conic::run(nc, st, code, to, p, sink, out);
    }
    if !moves && !(arc && (p.has(b'I') || p.has(b'J') || p.has(b'R'))) {
        return Ok(());
    }
    let Some((motion, path)) = plane_motion(nc, &st, code, st.pt, to, p)? else {
        return Ok(());
    };
    let step = Step {
        motion,
        to,
        path,
        off,
    };
    run_move(nc, st, step, sink, out)
}

/// A line, arc or rapid of the plane: how it runs, its end, its arc and
/// where it takes the axis outside the plane.
struct Step {
    motion: PlaneMotion,
    to: Pt,
    path: ArcPath,
    off: Option<f64>,
}

/// A step of the plane: checked against the centre, then compensated, or
/// moved and printed.
fn run_move(
    nc: &mut Nc,
    st: PlaneState,
    step: Step,
    sink: &mut dyn Sink,
    out: &mut Outcome,
) -> Result<(), NcError> {
    let Step {
        motion,
        to,
        path,
        off,
    } = step;
    let from = st.pt;
    if st.kind == Kind::Polar
        && nearest_to_centre(from, to, path) < nc.machine.machine.resolution_mm
    {
        return fail(
            Alarm::PolarInComp,
            "this move of polar interpolation passes through the spindle centre, where C would turn half a turn at once: program the path round the centre",
        );
    }
    out.moved = true;
    if crate::exec::comp::compensating(nc) {
        let rapid = motion == PlaneMotion::Rapid;
        return compensated(nc, st, (rapid, off), to, path, sink);
    }
    if !matches!(motion, PlaneMotion::Rapid) {
        nc.feed_due(sink);
    }
    follow(nc, st, to, path);
    if let Some(v) = off {
        set_off(nc, st.kind, v);
    }
    emit_move(&st, motion, to, off, sink);
    Ok(())
}

/// Prints a move of the plane to plane point `to` (`off`: where it takes
/// the axis outside the plane).
fn emit_move(st: &PlaneState, motion: PlaneMotion, to: Pt, off: Option<f64>, sink: &mut dyn Sink) {
    let (a, b) = st.printed(to);
    sink.emit(Event::PlaneMove {
        plane: st.plane(),
        motion,
        a,
        b,
        off,
    });
}

/// Where the block's words take the axis outside the plane: polar Z,
/// cylinder X (a diameter), work coordinates.
fn off_target(nc: &Nc, kind: Kind, p: &Parsed) -> f64 {
    let to = nc.target(p);
    match kind {
        Kind::Polar => to.z,
        Kind::Cylinder(_) => to.x(),
    }
}

/// The joint position after the axis outside the plane moved to `v`
/// (`off_target`).
fn set_off(nc: &mut Nc, kind: Kind, v: f64) {
    match kind {
        Kind::Polar => nc.st.pos.z = v,
        Kind::Cylinder(_) => nc.st.pos.r = v / 2.0,
    }
}

/// A plane move under nose-radius compensation: it joins the contour
/// queue as any compensated move does (comp module), in the plane's
/// coordinates, and prints through `print_element` once its neighbours
/// are known. The programmed point moves now, and so does the axis
/// outside the plane where a line takes it along (`off`, carried to the
/// printed element); the joints and C follow what is printed.
fn compensated(
    nc: &mut Nc,
    mut st: PlaneState,
    (rapid, off): (bool, Option<f64>),
    to: Pt,
    path: ArcPath,
    sink: &mut dyn Sink,
) -> Result<(), NcError> {
    let from = st.pt;
    let elem = match path {
        None => Element::Line { from, to },
        Some((centre, cw)) => Element::Arc {
            from,
            to,
            centre,
            cw,
        },
    };
    st.pt = to;
    nc.st.plane = Some(st);
    if let Some(v) = off {
        set_off(nc, st.kind, v);
    }
    let mut m = crate::exec::contour::Move::new(nc, elem, rapid, None);
    m.off = off;
    crate::exec::contour::advance(nc, m, sink)
}

/// E4033 for a compensated element of polar interpolation whose path,
/// from where the tool stands, passes through the spindle centre (as
/// `motion` checks the programmed path).
pub(crate) fn check_element(nc: &Nc, st: &PlaneState, e: &Element) -> Result<(), NcError> {
    let arc = match *e {
        Element::Line { .. } => None,
        Element::Arc { centre, cw, .. } => Some((centre, cw)),
    };
    if st.kind == Kind::Polar
        && nearest_to_centre(st.tool, e.end(), arc) < nc.machine.machine.resolution_mm
    {
        return fail(
            Alarm::PolarInComp,
            "the compensated path of polar interpolation passes through the spindle centre, where C would turn half a turn at once: keep the tool's centre off it",
        );
    }
    Ok(())
}

/// Prints an element of a plane move the contour queue hands on (a
/// compensated one): the plane motion to its end, the joints and C moved
/// along the path from where the tool stands (`follow` does so for a move
/// printed at once), and the axis outside the plane to `off` when the
/// element takes it along. A cancel's element starts at the programmed
/// point, the tool where the compensated path left it.
pub(crate) fn print_element(
    nc: &mut Nc,
    mut st: PlaneState,
    e: &Element,
    rapid: bool,
    off: Option<f64>,
    sink: &mut dyn Sink,
) {
    let (to, arc) = match *e {
        Element::Line { to, .. } => (to, None),
        Element::Arc { to, centre, cw, .. } => (to, Some((centre, cw))),
    };
    let motion = match arc {
        None if rapid => PlaneMotion::Rapid,
        None => PlaneMotion::Line,
        Some((centre, cw)) => {
            let (ca, cb) = st.printed(centre);
            let dir = if cw { Dir::Cw } else { Dir::Ccw };
            PlaneMotion::Arc { dir, ca, cb }
        }
    };
    move_joints(nc, &st, st.tool, to, arc);
    st.tool = to;
    nc.st.plane = Some(st);
    emit_move(&st, motion, to, off, sink);
}

/// The block's motion code in the plane (G00–G03); `None` when the block
/// was a G04, run here, or the G7.1 that acted in group 0.
fn plane_code(
    nc: &mut Nc,
    st: &PlaneState,
    p: &Parsed,
    sink: &mut dyn Sink,
    out: &mut Outcome,
) -> Result<Option<Motion>, NcError> {
    if let Some(code) = p.one_shot() {
        return match code {
            OneShot::Dwell => crate::exec::contour::in_order(nc, sink, |nc, s| {
                nc.one_shot(code, p, s, out).map(|()| None)
            }),
            OneShot::Cylindrical => Ok(None),
            _ => fail(
                Alarm::IncompatibleWords,
                format!("{} cannot run during {}", code.name(), st.what()),
            ),
        };
    }
    match nc.st.modal.motion {
        c if c.is_straight() || c.is_arc() || c.is_conic() => Ok(Some(c)),
        c => fail(
            Alarm::IncompatibleWords,
            format!("{} cannot run during {}", c.name(), st.what()),
        ),
    }
}

/// The centre of a plane arc and whether it runs clockwise; `None` for a
/// line.
type ArcPath = Option<(Pt, bool)>;

/// How a plane move from `from` to `to` runs, and its arc (centre,
/// clockwise) if it is one; `None`: an R arc whose end is its start.
fn plane_motion(
    nc: &Nc,
    st: &PlaneState,
    code: Motion,
    from: Pt,
    to: Pt,
    p: &Parsed,
) -> Result<Option<(PlaneMotion, ArcPath)>, NcError> {
    if !code.is_arc() {
        let motion = if code == Motion::Rapid {
            PlaneMotion::Rapid
        } else {
            PlaneMotion::Line
        };
        return Ok(Some((motion, None)));
    }
    let cw = code == Motion::ArcCw;
    let Some(c) = centre(nc, st, from, to, cw, p)? else {
        return Ok(None);
    };
    let (ca, cb) = st.printed(c);
    let dir = if cw { Dir::Cw } else { Dir::Ccw };
    Ok(Some((PlaneMotion::Arc { dir, ca, cb }, Some((c, cw)))))
}

/// Z (polar) or X (cylinder) moves alone, as the seed lets it: the plane
/// point stands, and so do the joints of the plane.
fn axis_move(nc: &mut Nc, st: PlaneState, rapid: bool, p: &Parsed, sink: &mut dyn Sink) {
    if !rapid {
        nc.feed_due(sink);
    }
    let to = off_target(nc, st.kind, p);
    set_off(nc, st.kind, to);
    sink.emit(Event::PlaneAxis {
        plane: st.plane(),
        rapid,
        to,
        c: nc.st.c,
    });
}

/// The end point of a plane move from its words (module comment).
fn target(nc: &Nc, st: &PlaneState, p: &Parsed) -> Pt {
    let mut t = st.pt;
    let deg = |letter| p.word(letter).map(|w| crate::exec::caxis::degrees(nc, w));
    match st.kind {
        Kind::Polar if nc.st.modal.polar_cmd == PolarCmd::On => {
            let (mut rho, mut theta) = (libm::hypot(t.z, t.r), libm::atan2(t.r, t.z).to_degrees());
            if let Some(x) = nc.len_of(p, b'X') {
                rho = x;
            } else if let Some(u) = nc.len_of(p, b'U') {
                rho += u;
            }
            if let Some(c) = deg(b'C') {
                theta = c;
            } else if let Some(h) = deg(b'H') {
                theta += h;
            }
            let th = theta.to_radians();
            t = Pt::new(rho * libm::sin(th), rho * libm::cos(th));
        }
        Kind::Polar => {
            if let Some(r) = nc.radial_of(p, b'X') {
                t.z = r;
            } else if let Some(u) = nc.radial_of(p, b'U') {
                t.z += u;
            }
            if let Some(c) = nc.len_of(p, b'C') {
                t.r = c;
            } else if let Some(h) = nc.len_of(p, b'H') {
                t.r += h;
            }
        }
        Kind::Cylinder(radius) => {
            if let Some(c) = deg(b'C') {
                t.z = radius * c.to_radians();
            } else if let Some(h) = deg(b'H') {
                t.z += radius * h.to_radians();
            }
            if let Some(z) = nc.len_of(p, b'Z') {
                t.r = z;
            } else if let Some(w) = nc.len_of(p, b'W') {
                t.r += w;
            }
        }
    }
    t
}

/// The centre of a plane arc: R, or (polar only) I along X and J along
/// C, both radius values. `None`: an R arc whose end is its start.
fn centre(
    nc: &Nc,
    st: &PlaneState,
    from: Pt,
    to: Pt,
    cw: bool,
    p: &Parsed,
) -> Result<Option<Pt>, NcError> {
    let g = if cw { "G02" } else { "G03" };
    if p.has(b'K') || (st.kind != Kind::Polar && (p.has(b'I') || p.has(b'J'))) {
        let words = if st.kind == Kind::Polar {
            "R or I/J"
        } else {
            "R"
        };
        return fail(
            Alarm::IncompatibleWords,
            format!("a {g} of {} takes {words} for its centre", st.what()),
        );
    }
    if let Some(r) = nc.len_of(p, b'R') {
        return geom::centre_from_radius(from, to, r, cw);
    }
    if p.has(b'I') || p.has(b'J') {
        let i = nc.len_of(p, b'I').unwrap_or(0.0);
        let j = nc.len_of(p, b'J').unwrap_or(0.0);
        let c = Pt::new(from.r + j, from.z + i);
        geom::check_on_circle(from, to, c, nc.machine.machine.arc_tolerance_mm)?;
        return Ok(Some(c));
    }
    fail(
        Alarm::MissingWord,
        format!("{g} during {} needs R or I/J for its centre", st.what()),
    )
}

/// Moves the programmed point to `to` (along the arc about `centre`
/// when given) and the joints with it.
fn follow(nc: &mut Nc, mut st: PlaneState, to: Pt, arc: Option<(Pt, bool)>) {
    move_joints(nc, &st, st.pt, to, arc);
    st.pt = to;
    st.tool = to;
    nc.st.plane = Some(st);
}

/// The joints and C after a plane path from `from` to `to` (along the
/// arc about `arc`'s centre when given).
fn move_joints(nc: &mut Nc, st: &PlaneState, from: Pt, to: Pt, arc: ArcPath) {
    nc.st.c = match st.kind {
        Kind::Polar => nc.st.c + swept(from, to, arc).to_degrees(),
        Kind::Cylinder(radius) => (to.z / radius).to_degrees(),
    };
    nc.st.pos = st.joints(to, nc.st.pos);
}

/// The angle (radians, counter-clockwise positive) a path from `from` to
/// `to` turns about the plane's origin, whole turns counted. A line (the
/// origin off it) turns by less than half a turn: the angle between its
/// end points. So does an arc whose circle leaves the origin outside: the
/// arc stays within the angle the circle subtends there, less than half a
/// turn. About an origin inside its circle the angle runs one way all
/// along the arc, up to a whole turn for a full circle. (Summing chords
/// of the arc miscounted a turn where the origin lay between an arc and
/// its chord, a few µm from a tool path.)
pub fn swept(from: Pt, to: Pt, arc: Option<(Pt, bool)>) -> f64 {
    let turn = |a: Pt, b: Pt| libm::atan2(a.z * b.r - a.r * b.z, a.z * b.z + a.r * b.r);
    let origin = Pt::new(0.0, 0.0);
    match arc {
        Some((c, cw)) if origin.dist(c) < from.dist(c) => {
            let s = sweep(angle(origin, from), angle(origin, to), cw);
            if cw {
                -s
            } else {
                s
            }
        }
        _ => turn(from, to),
    }
}

/// The least distance from the spindle centre (the plane's origin) to a
/// line from `from` to `to`, or to the arc about `arc`'s centre (`true`:
/// clockwise) between them.
fn nearest_to_centre(from: Pt, to: Pt, arc: Option<(Pt, bool)>) -> f64 {
    let ends = from.norm().min(to.norm());
    let Some((c, cw)) = arc else {
        let d = to - from;
        let len2 = d.dot(d);
        if len2 == 0.0 {
            return ends;
        }
        let t = (-from.dot(d) / len2).clamp(0.0, 1.0);
        return (from + d * t).norm();
    };
    let (radius, dist) = (from.dist(c), c.norm());
    if dist == 0.0 {
        return radius;
    }
    // The circle's point nearest the origin lies in the origin's
    // direction from the centre: the arc reaches it when its sweep does.
    let a0 = angle(c, from);
    if sweep(a0, angle(c, Pt::new(0.0, 0.0)), cw) <= sweep(a0, angle(c, to), cw) {
        (dist - radius).abs()
    } else {
        ends
    }
}

/// The angle an arc turns (`cw`: clockwise) from angle `a0` to angle `a`
/// about its centre, in (0, 2π]: the same angle is a full circle.
fn sweep(a0: f64, a: f64, cw: bool) -> f64 {
    let tau = 2.0 * core::f64::consts::PI;
    let s = if cw { a0 - a } else { a - a0 };
    let s = s - tau * libm::floor(s / tau);
    if s < 1e-12 {
        tau
    } else {
        s
    }
}

/// The angle of `p` about `c`, counter-clockwise from the first axis.
fn angle(c: Pt, p: Pt) -> f64 {
    libm::atan2(p.r - c.r, p.z - c.z)
}

#[cfg(test)]
mod tests;
