//! Elements that wait for the next move, and the events held behind them.

use alloc::vec::Vec;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::event::{Dir, Event};
use crate::base::geom::Element;
use crate::base::point::Pt;
use crate::exec::comp::{Leg, Step};
use crate::exec::{Nc, Sink};
use crate::plan::angle;
use crate::plan::corner::{corner, Corner};
use crate::plan::elem::{self, EPS_LEN};
use crate::plan::offset;

/// One move of a block as it will be printed.
#[derive(Debug, Clone)]
pub(crate) struct Move {
    pub elem: Element,
    /// A G00 line (`RAPID`); never takes a corner.
    pub rapid: bool,
    /// The F (mm) and per-rev mode of the block the move belongs to.
    pub feed: (f64, bool),
    /// The block's corner word, until the next move has used it.
    pub corner: Option<Corner>,
    /// Shortened by a corner: when nothing is left it is not printed.
    pub trimmed: bool,
    /// Its nose-radius compensation (comp module); `None`: uncompensated.
    pub comp: Option<Leg>,
    /// The C angle its line prints (`C=`), when its block programs C/H.
    pub c: Option<f64>,
    /// Where a line of polar (cylindrical) interpolation takes Z (X, a
    /// diameter) along (plane.rs), printed on the block's own element:
    /// a corner's arc before it holds the axis, as a corner block would.
    pub off: Option<f64>,
    /// The tag of its block ([`Nc::origin`]).
    pub origin: u32,
}

impl Move {
    pub fn new(nc: &Nc, elem: Element, rapid: bool, corner: Option<Corner>) -> Move {
        let corner = if rapid { None } else { corner };
        Move {
            elem,
            rapid,
            feed: feed_now(nc),
            corner,
            trimmed: false,
            comp: None,
            c: None,
            off: None,
            origin: nc.origin,
        }
    }

    /// Whether the move must wait for the next one before it is printed:
    /// for its corner word, or for the element its compensated end
    /// depends on.
    fn waits(&self) -> bool {
        (self.corner.is_some() && !elem::shorter_than(&self.elem, EPS_LEN)) || self.comp_open()
    }

    /// A compensated move whose end is still open.
    fn comp_open(&self) -> bool {
        self.comp.as_ref().is_some_and(|l| l.open(&self.elem))
    }
}

/// The first block of the two-block angle form (dialect.md §5.2).
#[derive(Debug, Clone)]
pub(crate) struct AngleFirst {
    from: Pt,
    angle: f64,
    rapid: bool,
    feed: (f64, bool),
    corner: Option<Corner>,
    /// Blocks run since, and whether the block that made it is still running.
    between: u32,
    fresh: bool,
    /// The tag of its block ([`Nc::origin`]).
    origin: u32,
}

impl AngleFirst {
    pub fn new(
        from: Pt,
        angle: f64,
        rapid: bool,
        feed: (f64, bool),
        corner: Option<Corner>,
        origin: u32,
    ) -> AngleFirst {
        AngleFirst {
            from,
            angle,
            rapid,
            feed,
            corner,
            between: 0,
            fresh: true,
            origin,
        }
    }
}

#[derive(Debug, Clone)]
enum Item {
    /// An event held behind what waits, with its block's tag.
    Event(Event, u32),
    Move(Move),
    Angle(AngleFirst),
}

/// What waits for the next block: the elements of earlier blocks whose
/// corner or end point is not known yet, and, in block order behind them,
/// the events printed since. Empty unless something waits.
#[derive(Debug, Clone, Default)]
pub struct ContourState {
    items: Vec<Item>,
    /// Corner words applied so far (chamfers and roundings inserted): a
    /// dry run compares it with the corner words it saw to warn about
    /// the ignored ones (W112).
    pub applied: u32,
}

impl ContourState {
    /// Whether events must be held (something waits).
    pub fn is_holding(&self) -> bool {
        !self.items.is_empty()
    }

    /// Events of the block tagged `origin`, held behind what waits.
    pub(crate) fn hold(&mut self, events: Vec<Event>, origin: u32) {
        self.items
            .extend(events.into_iter().map(|e| Item::Event(e, origin)));
    }

    pub(crate) fn angle_waiting(&self) -> bool {
        self.items.iter().any(|i| matches!(i, Item::Angle(_)))
    }

    pub(crate) fn wait_angle(&mut self, a: AngleFirst) {
        self.items.push(Item::Angle(a));
    }

    /// A group-00 code came before the second block: the first block's
    /// corner word is ignored (W112).
    pub(crate) fn drop_angle_corner(&mut self) {
        for item in &mut self.items {
            if let Item::Angle(a) = item {
                a.corner = None;
            }
        }
    }

    /// The last waiting compensated element (not a start-up) and its
    /// tool: a compensated conic meets it (`comp::conic`).
    pub(crate) fn last_compensated(&self) -> Option<(Element, crate::exec::comp::Tool)> {
        let m = self.items.iter().rev().find_map(|i| match i {
            Item::Move(m) => Some(m),
            _ => None,
        })?;
        let leg = m.comp.as_ref()?;
        (leg.role == crate::exec::comp::Role::Body).then_some((m.elem, leg.tool))
    }

    /// A G04 under compensation: the corner words of waiting elements are
    /// ignored, as a flush would ignore them (W112).
    pub(crate) fn drop_corners(&mut self) {
        for item in &mut self.items {
            if let Item::Move(m) = item {
                m.corner = None;
            }
        }
    }

    /// Counts a finished block against a waiting angle pair: how many
    /// blocks now stand between its two blocks (0 when none waits).
    pub(crate) fn count_block_between(&mut self) -> u32 {
        for item in &mut self.items {
            if let Item::Angle(a) = item {
                if a.fresh {
                    a.fresh = false;
                } else {
                    a.between += 1;
                }
                return a.between;
            }
        }
        0
    }
}

/// The feed a move of the current block runs at, as `FEED` prints it.
pub(crate) fn feed_now(nc: &Nc) -> (f64, bool) {
    (nc.st.feed * nc.st.unit(), nc.st.per_rev())
}

/// Runs `f` with a sink that holds its events behind what waits (and
/// passes them straight on when nothing does).
pub(crate) fn in_order<R>(
    nc: &mut Nc,
    sink: &mut dyn Sink,
    f: impl FnOnce(&mut Nc, &mut dyn Sink) -> Result<R, NcError>,
) -> Result<R, NcError> {
    if !nc.st.contour.is_holding() {
        return f(nc, sink);
    }
    let mut held: Vec<Event> = Vec::new();
    // A held feed move prints its FEED whatever was printed last: the
    // elements that wait print theirs before it, and `drain` drops it
    // where the canon already has that feed.
    let printed = nc.st.feed_printed.take();
    let r = f(nc, &mut held);
    nc.st.feed_printed = printed;
    // Kept even on an error: a later flush prints them before the alarm.
    nc.st.contour.hold(held, nc.origin);
    r
}

/// The last waiting element (move or angle pair) in `items`.
fn last_waiting(items: &[Item]) -> Option<usize> {
    items.iter().rposition(|i| !matches!(i, Item::Event(..)))
}

/// The tag of the last waiting element's block (`Nc::waiting_block`).
pub(crate) fn last_waiting_tag(nc: &Nc) -> Option<u32> {
    let items = &nc.st.contour.items;
    match items.get(last_waiting(items)?)? {
        Item::Move(m) => Some(m.origin),
        Item::Angle(a) => Some(a.origin),
        Item::Event(..) => None,
    }
}

/// Applies `prev`'s corner word to the join with `next`: both are
/// shortened and the inserted element returned (at `prev`'s feed: the
/// chamfer or rounding belongs to the block that carries the word).
fn join(prev: &mut Move, next: &mut Move) -> Result<Option<Move>, NcError> {
    let Some(c) = prev.corner.take() else {
        return Ok(None);
    };
    // The next move is not G01/G02/G03: the word is ignored (W112).
    if next.rapid {
        return Ok(None);
    }
    // The error is about the earlier block's corner word: it names that
    // block (`NcError::at`), the word the corner's.
    let joined = corner(&prev.elem, &next.elem, c).map_err(|e| e.at(prev.origin))?;
    let Some((a, inserted, b)) = joined else {
        return Ok(None);
    };
    prev.elem = a;
    prev.trimmed = true;
    next.elem = b;
    next.trimmed = true;
    Ok(Some(Move {
        elem: inserted,
        rapid: false,
        feed: prev.feed,
        corner: None,
        trimmed: false,
        comp: prev.comp.as_ref().map(Leg::inserted),
        c: None,
        off: None,
        origin: prev.origin,
    }))
}

/// Joins the waiting element at `i` (if it is a move) with `next` and
/// puts the inserted element after it. The faulty element is dropped on
/// an error (the alarm is about its corner).
fn join_at(items: &mut Vec<Item>, i: usize, next: &mut Move) -> Result<bool, NcError> {
    let Some(Item::Move(prev)) = items.get_mut(i) else {
        return Ok(false);
    };
    match join(prev, next) {
        Ok(Some(inserted)) => {
            items.insert(i + 1, Item::Move(inserted));
            Ok(true)
        }
        Ok(None) => Ok(false),
        Err(e) => {
            items.remove(i);
            Err(e)
        }
    }
}

/// A new move of the current block: it takes the corner of the element
/// waiting before it, everything before it is printed, and it is printed
/// too unless its own corner word makes it wait.
pub(crate) fn advance(nc: &mut Nc, mut next: Move, sink: &mut dyn Sink) -> Result<(), NcError> {
    let step = compensate(nc, &mut next)?;
    if let Some(i) = last_waiting(&nc.st.contour.items) {
        if join_at(&mut nc.st.contour.items, i, &mut next)? {
            nc.st.contour.applied += 1;
        }
    }
    if step == Step::Behind {
        // Printed where the compensated tool will stand: behind the
        // element that still waits (comp.md §7).
        nc.st.contour.items.push(Item::Move(next));
        return Ok(());
    }
    if let Err(e) = resolve(&mut nc.st.contour.items, &mut next, step) {
        forget_from(&mut nc.st.contour.items, e.at);
        return Err(e);
    }
    drain(nc, sink)?;
    if next.waits() {
        nc.st.contour.items.push(Item::Move(next));
        Ok(())
    } else {
        emit_move(nc, &next, sink)
    }
}

/// What [`advance`] does with a line from `from` to `to` when nothing
/// waits, nothing compensates and the line has no corner word: prints it.
pub(crate) fn print_line(
    nc: &mut Nc,
    from: Pt,
    to: Pt,
    rapid: bool,
    sink: &mut dyn Sink,
) -> Result<(), NcError> {
    let line = Element::Line { from, to };
    emit_element(nc, &line, rapid, feed_now(nc), Third::default(), sink)
}

/// The second block of an angle pair ends at `end` on the line at `q2`:
/// the first block's line ends at the intersection, then the second
/// block's line (`template` gives its kind, feed and corner) runs to `end`.
pub(crate) fn finish_angle(
    nc: &mut Nc,
    end: Pt,
    q2: f64,
    template: Move,
    sink: &mut dyn Sink,
) -> Result<(), NcError> {
    let items = &mut nc.st.contour.items;
    let Some(i) = items.iter().position(|it| matches!(it, Item::Angle(_))) else {
        return fail(
            Alarm::BadAngle,
            "angle programming: no first block waits for this one",
        );
    };
    let Item::Angle(a) = items.remove(i) else {
        return fail(
            Alarm::BadAngle,
            "angle programming: no first block waits for this one",
        );
    };
    let meet = angle::intersection(a.from, a.angle, end, q2)?;
    let mut first = Move {
        elem: Element::Line {
            from: a.from,
            to: meet,
        },
        rapid: a.rapid,
        feed: a.feed,
        corner: if a.rapid { None } else { a.corner },
        trimmed: false,
        comp: None,
        c: None,
        off: None,
        origin: a.origin,
    };
    let step = compensate(nc, &mut first)?;
    let items = &mut nc.st.contour.items;
    let mut at = i;
    if let Some(j) = last_waiting(&items[..i]) {
        if join_at(items, j, &mut first)? {
            nc.st.contour.applied += 1;
            at += 1;
        }
    }
    if let Some(before) = items.get_mut(..at) {
        resolve(before, &mut first, step)?;
    }
    items.insert(at, Item::Move(first));
    let second = Move {
        elem: Element::Line {
            from: meet,
            to: end,
        },
        ..template
    };
    advance(nc, second, sink)
}

/// Gives every element and event that waits the block tag `f` makes of
/// its own: for a host whose tags of earlier blocks no longer name them.
pub(crate) fn retag(nc: &mut Nc, f: &mut dyn FnMut(u32) -> u32) {
    for item in &mut nc.st.contour.items {
        let origin = match item {
            Item::Event(_, origin) => origin,
            Item::Move(m) => &mut m.origin,
            Item::Angle(a) => &mut a.origin,
        };
        *origin = f(*origin);
    }
}

/// Prints everything that waits, each element as it stands (corners not
/// yet taken are ignored). E4008 when an angle pair lacked its second
/// block.
pub(crate) fn flush(nc: &mut Nc, sink: &mut dyn Sink) -> Result<(), NcError> {
    let incomplete = nc.st.contour.angle_waiting();
    // Compensation is suspended: the waiting element ends on its own
    // normal (comp.md §6, §8); printed even when that fails.
    let closed = chain(&mut nc.st.contour.items, None);
    nc.st.comp.stop();
    let printed = drain(nc, sink);
    closed?;
    printed?;
    if incomplete {
        return fail(
            Alarm::BadAngle,
            "angle programming: the block after a Q_ block must be X_ Z_ Q_",
        );
    }
    Ok(())
}

/// Prints and forgets every item, in order, up to a plane element that
/// cannot run (`plane::print_element`); each told to the sink with its
/// block's tag, and the running block's again after them.
fn drain(nc: &mut Nc, sink: &mut dyn Sink) -> Result<(), NcError> {
    let running = nc.origin;
    let mut told = running;
    let result = drain_items(nc, sink, &mut told);
    if told != running {
        sink.origin(running);
    }
    result
}

/// `drain`'s items; `told`: the block tag last told to the sink.
fn drain_items(nc: &mut Nc, sink: &mut dyn Sink, told: &mut u32) -> Result<(), NcError> {
    for item in core::mem::take(&mut nc.st.contour.items) {
        let origin = match &item {
            Item::Event(_, o) => *o,
            Item::Move(m) => m.origin,
            Item::Angle(_) => *told,
        };
        if origin != *told {
            sink.origin(origin);
            *told = origin;
        }
        match item {
            Item::Event(Event::Feed { f, per_rev }, _) => {
                // (A held FEED: `in_order`.)
                if nc.st.feed_due((f, per_rev)) {
                    sink.emit(Event::Feed { f, per_rev });
                }
            }
            Item::Event(mut e, _) => {
                // A move of the axis outside a plane, held behind a
                // compensated element (plane.rs), starts where the joints
                // stand once that element is printed.
                if let Event::PlaneAxis { c, .. } = &mut e {
                    *c = nc.st.c;
                }
                sink.emit(e)
            }
            Item::Move(m) => emit_move(nc, &m, sink)?,
            Item::Angle(_) => {}
        }
    }
    Ok(())
}

/// Prints one move: compensated, as its leg says (comp module).
fn emit_move(nc: &mut Nc, m: &Move, sink: &mut dyn Sink) -> Result<(), NcError> {
    if m.trimmed && elem::shorter_than(&m.elem, EPS_LEN) {
        return Ok(());
    }
    let third = Third { c: m.c, off: m.off };
    match &m.comp {
        Some(leg) => {
            let printed = crate::exec::comp::printed(&mut nc.st.comp, &m.elem, leg, m.rapid);
            let last = printed.len().saturating_sub(1);
            for (i, (e, rapid)) in printed.into_iter().enumerate() {
                let third = if i == last { third } else { Third::default() };
                emit_element(nc, &e, rapid, m.feed, third, sink)?;
            }
            Ok(())
        }
        None => emit_element(nc, &m.elem, m.rapid, m.feed, third, sink),
    }
}

/// What a printed element takes along besides its path: C (ZX plane),
/// the axis outside a plane (polar, cylindrical).
#[derive(Clone, Copy, Default)]
struct Third {
    c: Option<f64>,
    off: Option<f64>,
}

/// Prints one element, with `FEED` first when its feed differs from the
/// last one printed.
fn emit_element(
    nc: &mut Nc,
    e: &Element,
    rapid: bool,
    feed: (f64, bool),
    third: Third,
    sink: &mut dyn Sink,
) -> Result<(), NcError> {
    let plane = nc.st.plane;
    if let Some(st) = &plane {
        crate::exec::plane::check_element(nc, st, e)?;
    }
    if !rapid && nc.st.feed_due(feed) {
        sink.emit(Event::Feed {
            f: feed.0,
            per_rev: feed.1,
        });
    }
    if let Some(st) = plane {
        crate::exec::plane::print_element(nc, st, e, rapid, third.off, sink);
        return Ok(());
    }
    let to = e.end();
    sink.emit(match *e {
        Element::Line { .. } if rapid => Event::Rapid {
            x: to.x(),
            z: to.z,
            c: third.c,
        },
        Element::Line { .. } => Event::Line {
            x: to.x(),
            z: to.z,
            c: third.c,
        },
        Element::Arc { centre, cw, .. } => Event::Arc {
            dir: if cw { Dir::Cw } else { Dir::Ccw },
            x: to.x(),
            z: to.z,
            cx: centre.x(),
            cz: centre.z,
        },
    });
    Ok(())
}

/// Asks the comp module what `m` is (start-up, element, cancel ...) and
/// gives it its leg. A zero-length move takes no corner word.
fn compensate(nc: &mut Nc, m: &mut Move) -> Result<Step, NcError> {
    let (step, leg) = crate::exec::comp::classify(nc, &m.elem)?;
    m.comp = leg;
    if step == Step::Behind {
        m.corner = None;
    }
    Ok(step)
}

/// After an error about the element of block `at`: that element and
/// what waits behind it are not printed (canon.md, ALARM: the faulty
/// block's motion is not printed); the earlier blocks' still are.
fn forget_from(items: &mut Vec<Item>, at: Option<u32>) {
    let faulty = |i: &Item| matches!(i, Item::Move(m) if Some(m.origin) == at);
    if let Some(k) = items.iter().position(faulty) {
        items.truncate(k);
    }
}

/// Joins the waiting compensated elements in `items` with the new move
/// `next` as `step` says.
fn resolve(items: &mut [Item], next: &mut Move, step: Step) -> Result<(), NcError> {
    match step {
        Step::Join => chain(items, Some(next)),
        Step::Close => chain(items, None),
        Step::Plain | Step::Start | Step::Behind => Ok(()),
    }
}

/// The compensated elements whose end is open (the waiting one and those
/// an L/D corner inserted after it), then `next`, joined pairwise in
/// order; without `next` the last one ends on its own normal.
fn chain(items: &mut [Item], next: Option<&mut Move>) -> Result<(), NcError> {
    let mut open: Vec<&mut Move> = items
        .iter_mut()
        .filter_map(|i| match i {
            Item::Move(m) if m.comp_open() => Some(m),
            _ => None,
        })
        .collect();
    let close = next.is_none();
    open.extend(next);
    // An interference found here is about an element of an earlier block
    // than the running one: the error names that block (`NcError::at`).
    for k in 1..open.len() {
        let (done, rest) = open.split_at_mut(k);
        if let (Some(a), Some(b)) = (done.last_mut(), rest.first_mut()) {
            if let (Some(la), Some(lb)) = (a.comp.as_mut(), b.comp.as_mut()) {
                // A rounding L/D inserted is its own block's element.
                offset::check_arc(&b.elem, &la.tool).map_err(|e| e.at(b.origin))?;
                crate::exec::comp::join(&a.elem, la, &b.elem, lb).map_err(|e| e.at(a.origin))?;
            }
        }
    }
    match open.last_mut() {
        Some(last) if close => match last.comp.as_mut() {
            Some(leg) => crate::exec::comp::close(&last.elem, leg).map_err(|e| e.at(last.origin)),
            None => Ok(()),
        },
        _ => Ok(()),
    }
}
