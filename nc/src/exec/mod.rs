//! Executing one block: its events in the order of canon.md, and the state
//! it leaves behind.

pub mod active;
pub mod caxis;
pub mod comp;
pub mod compound;
pub mod contour;
pub mod counters;
pub mod cycles;
pub mod data_setting;
pub mod measure;
mod motion_api;
pub mod params;
mod plain;
pub mod plane;
pub mod state;
pub mod stroke;
pub mod switches;
pub mod sysvar;
pub mod tool_life;
pub mod travel;
pub mod zero_feed;

use alloc::boxed::Box;
use alloc::format;
use alloc::vec::Vec;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::event::{Dir, Event, SpindleDir, StopKind};
use crate::base::gcode::{self, Drill, Motion, OneShot, Polar, SpeedMode, Work, G};
use crate::base::geom::Element;
use crate::base::machine::{DecimalPoint, Machine, SpindleType};
use crate::base::mcode::{Timing, M};
use crate::base::point::Pt;
use crate::base::words::{addr, Word, NO_POINT};
use crate::block::{self, round_half_away, Parsed};
use crate::exec::state::State;
use crate::modal::PathMode;
use crate::plan::reader::Reader;

/// Where the events of a run go; the kernel does not know who listens.
pub trait Sink {
    fn emit(&mut self, event: Event);

    /// The events that follow belong to the block tagged `block` (the
    /// VM's pc, [`Nc::origin`]), until the next call: an element that
    /// waited in the contour queue for the next block (a corner word,
    /// nose-radius compensation) is printed while that block runs, and
    /// so are the events held behind it. Called only where the block
    /// changes. A sink that does not place events by block ignores it.
    /// [`RUNNING`] gives the events that follow back to the block running.
    fn origin(&mut self, _block: u32) {}
}

/// The tag [`Sink::origin`] takes for "the block running": what follows
/// belongs to the block the host is running, as before any tag was told.
/// (The VM tags what a statement between blocks prints, a `#3006`
/// message, with the statement's own pc, then gives this.)
pub const RUNNING: u32 = u32::MAX;

impl Sink for Vec<Event> {
    fn emit(&mut self, event: Event) {
        self.push(event);
    }
}

/// A sink that drops the events: for a run whose end alone is wanted.
pub struct Discard;

impl Sink for Discard {
    fn emit(&mut self, _: Event) {}
}

/// A sink that keeps the events and where those of an earlier block
/// begin ([`Sink::origin`]): a host that places events by block (the
/// runtime's tags, `gbcc -E`'s comments) reads them from here.
#[derive(Debug, Default)]
pub struct Placed {
    pub events: Vec<Event>,
    /// (index in `events`, the block's tag), in order.
    pub origins: Vec<(usize, u32)>,
}

impl Sink for Placed {
    fn emit(&mut self, e: Event) {
        self.events.push(e);
    }

    fn origin(&mut self, block: u32) {
        self.origins.push((self.events.len(), block));
    }
}

impl Placed {
    pub fn clear(&mut self) {
        self.events.clear();
        self.origins.clear();
    }

    /// The events in runs of one block each, empty runs left out: the
    /// events and their block's tag (`None`: the block that ran).
    pub fn runs(&self) -> impl Iterator<Item = (&[Event], Option<u32>)> + '_ {
        let tag = |block| Some(block).filter(|&b| b != RUNNING);
        let starts = core::iter::once((0, None)).chain(
            self.origins
                .iter()
                .map(move |&(at, block)| (at, tag(block))),
        );
        let ends =
            (self.origins.iter().map(|&(at, _)| at)).chain(core::iter::once(self.events.len()));
        starts.zip(ends).filter_map(|((from, block), to)| {
            Some((self.events.get(from..to).filter(|r| !r.is_empty())?, block))
        })
    }
}

/// What a block did, for the caller's control flow.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Outcome {
    /// The block moved the tool.
    pub moved: bool,
    /// It moved by a group-01 code (threads and G90/G92/G94 included), not
    /// a group-00 function or cycle nor a drilling cycle: a G66 call
    /// follows it (dialect.md §7.9).
    pub modal_call: bool,
    /// M02/M30 ended the program.
    pub end: Option<StopKind>,
    /// A G31 skip position to store in #995/#996.
    pub skip: Option<Pt>,
    /// A `G10 L52` read: the variable to set and the parameter's value
    /// (variables #1–#999 live in the VM, not in the kernel).
    pub store: Option<(u32, f64)>,
    /// The call or return of a computed M code (`M#1` with #1 = 98, 99 or
    /// 9000–9999): the VM makes it after the block, as a written one
    /// (dialect.md §6.1, group 6), whose words the compiler takes.
    pub call: Option<WordCall>,
}

/// A call or return that a block's computed M code asks for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum WordCall {
    /// M98 P \[L\]: with L, P is the program; without, P is
    /// `<count:4><program:4>` (§7.11).
    Sub { p: Option<f64>, l: Option<f64> },
    /// M99 \[P\].
    Return { seq: Option<f64> },
    /// M9000–M9999: O9000–O9999, once (§7.10).
    Macro(u16),
}

/// The NC kernel: a machine and its state.
#[derive(Debug, Clone)]
pub struct Nc {
    pub machine: Machine,
    pub st: State,
    /// The ns…nf blocks handed over for the next G70–G73 block, each with
    /// the tag its errors carry (the VM uses the pc, the compiler the block
    /// index).
    pub profile: Vec<(Vec<Word>, u32)>,
    /// The parse of the running block, kept between blocks so that no
    /// block builds or moves a fresh one (taken while a block runs).
    parsed: Option<Box<Parsed>>,
    /// Legs the cycles have printed since the caller last took the count
    /// ([`take_generated`](Nc::take_generated)), and how many more blocks
    /// the caller's budget allows ([`set_allowance`](Nc::set_allowance)).
    generated: u64,
    allowance: u64,
    /// Plain moves take their short path (`plain`); off, every block runs
    /// the general one, for tests that compare both.
    plain_path: bool,
    /// The tag of the block running (the VM sets its pc; 0 unless set):
    /// what waits in the contour queue keeps its block's, and is told to
    /// the sink with it when printed ([`Sink::origin`]).
    pub origin: u32,
    /// A block's moves pass the guard (stroke.rs) now: the blocks it runs
    /// inside it (G70's profile) take no guard of their own.
    guarding: bool,
}

impl Nc {
    pub fn new(machine: Machine) -> Nc {
        let st = State::power_on(&machine);
        Nc {
            machine,
            st,
            profile: Vec::new(),
            parsed: None,
            generated: 0,
            allowance: u64::MAX,
            plain_path: true,
            origin: 0,
            guarding: false,
        }
    }

    /// Whether plain moves take their short path (on by default); the
    /// general path gives the same events and state, which tests check
    /// by running programs both ways.
    pub fn set_plain_path(&mut self, on: bool) {
        self.plain_path = on;
    }

    /// Back to the power-on state (a new run).
    pub fn reset(&mut self) {
        self.st = State::power_on(&self.machine);
    }

    /// The legs the canned cycles printed since the last call, and the
    /// count back to zero. A cycle stands for the blocks it generates, so
    /// the block budget (dialect.md §7.12, "all passes counted") charges
    /// them: a cycle whose step is tiny against its depth then ends the
    /// run with E6005 instead of running for hours.
    pub fn take_generated(&mut self) -> u64 {
        core::mem::take(&mut self.generated)
    }

    /// How many blocks the run may still execute after the current one:
    /// a cycle that would print more legs than that (its first leg being
    /// its own block) stops with E6005 before it prints any.
    pub fn set_allowance(&mut self, blocks: u64) {
        self.allowance = blocks;
    }

    /// Charges the legs a cycle is about to print (see
    /// [`take_generated`](Nc::take_generated)).
    pub(crate) fn generate(&mut self, legs: usize) -> Result<(), NcError> {
        let further = (legs as u64).saturating_sub(1);
        if further > self.allowance {
            return fail(
                Alarm::BlockBudget,
                format!(
                    "the cycle makes {legs} moves, more than the {} blocks left in the block budget",
                    self.allowance.saturating_add(1)
                ),
            );
        }
        self.generated = self.generated.saturating_add(legs as u64);
        Ok(())
    }

    /// Hands over one ns…nf block for the next G70–G73 block.
    pub fn push_profile(&mut self, words: &[Word], tag: u32) {
        self.profile.push((words.to_vec(), tag));
    }

    /// Executes one block of NC words.
    pub fn exec(&mut self, words: &[Word], sink: &mut dyn Sink) -> Result<Outcome, NcError> {
        // G10/G11 blocks and the blocks of their modes (data_setting).
        if let Some(out) = crate::exec::data_setting::intercept(self, words)? {
            return Ok(out);
        }
        // Minutes tool-life groups time the feed moves (tool_life).
        crate::exec::tool_life::timed(self, words, sink, Nc::exec_guarded)
    }

    /// Executes a plain move the compiler typed (the `move` instruction:
    /// X/Z/U/W, F, N and an arc's R or I/K, and at most a G00–G03
    /// written as 0–3): as [`exec`](Nc::exec) does, its words read by
    /// [`block::parse_move`], which skips what such a block cannot hold.
    /// Other words are taken as `exec` takes them.
    pub fn exec_move(&mut self, words: &[Word], sink: &mut dyn Sink) -> Result<Outcome, NcError> {
        // In a G10 data-setting mode a block is data; a G10 or G11 is not
        // a move (data_setting::intercept).
        let other_g = |w: &Word| w.addr == addr(b'G') && !(0.0..=3.0).contains(&w.value);
        if self.st.data.mode != crate::exec::data_setting::Mode::Off || words.iter().any(other_g) {
            return self.exec(words, sink);
        }
        crate::exec::tool_life::timed(self, words, sink, Nc::exec_guarded_move)
    }

    /// A block behind the G22 stroke check and the soft limits, when in
    /// force (stroke.rs), and the check for feed moves at F = 0
    /// (zero_feed) when the block can print one; of their alarms the one
    /// of the earlier event (neither passes events on after its own).
    fn exec_guarded(&mut self, words: &[Word], sink: &mut dyn Sink) -> Result<Outcome, NcError> {
        self.guarded(words, sink, block::parse_into)
    }

    /// `exec_guarded` for a typed plain move.
    fn exec_guarded_move(
        &mut self,
        words: &[Word],
        sink: &mut dyn Sink,
    ) -> Result<Outcome, NcError> {
        self.guarded(words, sink, block::parse_move)
    }

    #[inline(always)]
    fn guarded(
        &mut self,
        words: &[Word],
        sink: &mut dyn Sink,
        parse: fn(&[Word], &Machine, &mut Parsed) -> Result<(), NcError>,
    ) -> Result<Outcome, NcError> {
        // (A block run from inside a block, as G70's profile, finds no
        // parse kept and makes its own.)
        let mut p = self.parsed.take().unwrap_or_default();
        let result = match parse(words, &self.machine, &mut p) {
            Err(e) => Err(e),
            // The usual block: nothing to check on its way out, and the
            // block's execution in line here (it runs for every block).
            Ok(()) if !self.guards_moves() && !crate::exec::zero_feed::may_fault(self, &p) => {
                if plain::takes(self, &p) {
                    plain::run(self, &p, sink)
                } else {
                    self.exec_parsed(&p, words, sink)
                }
            }
            Ok(()) => self.exec_watched(&p, words, sink),
        };
        self.parsed = Some(p);
        result
    }

    /// The parsed block behind the sinks that check it.
    #[inline(never)]
    fn exec_watched(
        &mut self,
        p: &Parsed,
        words: &[Word],
        sink: &mut dyn Sink,
    ) -> Result<Outcome, NcError> {
        let watched = crate::exec::zero_feed::may_fault(self, p);
        let (printed, at) = (self.st.feed_printed, self.st.pos);
        // A block run from inside a guarded one (G70's profile) passes
        // that block's guard.
        if !self.guards_moves() || self.guarding {
            let mut watch = crate::exec::zero_feed::Watch::new(sink, printed, at);
            let result = self.exec_behind(p, words, &mut watch);
            return watch.finish().map_or(result, Err);
        }
        // G22 in force or soft limits: every move passes the guard.
        let mut guard = crate::exec::stroke::Guard::new(sink, self);
        self.guarding = true;
        let (result, zero_feed) = if watched {
            let mut watch = crate::exec::zero_feed::Watch::new(&mut guard, printed, at);
            let result = self.exec_behind(p, words, &mut watch);
            (result, watch.finish())
        } else {
            (self.exec_behind(p, words, &mut guard), None)
        };
        self.guarding = false;
        match guard.finish(&mut self.st).or(zero_feed) {
            Some(e) => Err(e),
            None => result,
        }
    }

    /// Whether the block's moves pass the guard (stroke.rs): G22 is in
    /// force, or the machine has soft limits.
    #[inline]
    fn guards_moves(&self) -> bool {
        let axes = &self.machine.axes;
        self.st.stroke2.is_some() || axes.x.soft_limits || axes.z.soft_limits
    }

    /// `exec_parsed` out of line, for the checked blocks.
    #[inline(never)]
    fn exec_behind(
        &mut self,
        p: &Parsed,
        words: &[Word],
        sink: &mut dyn Sink,
    ) -> Result<Outcome, NcError> {
        self.exec_parsed(p, words, sink)
    }

    #[inline(always)]
    fn exec_parsed(
        &mut self,
        p: &Parsed,
        words: &[Word],
        sink: &mut dyn Sink,
    ) -> Result<Outcome, NcError> {
        self.st.c_block = false;
        crate::exec::comp::before_block(self, p, sink)?;
        crate::exec::plane::before_block(self, p, sink)?;
        let mut out = Outcome::default();
        // While an element waits for its corner (contour module), the
        // block's events are held behind it so the canon keeps block order.
        contour::in_order(self, sink, |nc, s| {
            nc.modal_settings(p, s)?;
            crate::exec::caxis::check(nc, p)?;
            nc.st.c_block = crate::exec::caxis::programs_c(nc, p);
            nc.before_motion(p, words, s)
        })?;
        self.remember(p);
        self.st.exact_stop =
            p.has_g(OneShot::ExactStop) || self.st.modal.path_mode() == PathMode::ExactStop;
        self.motion(p, sink, &mut out)?;
        contour::in_order(self, sink, |nc, s| {
            nc.after_motion(p, s);
            Ok(())
        })?;
        if p.ends_program() {
            // The program ends: a waiting element is printed whole.
            contour::flush(self, sink)?;
        }
        contour::in_order(self, sink, |nc, s| {
            nc.stops(p, s, &mut out);
            Ok(())
        })?;
        out.call = word_call(p);
        // (G09 is the one group-00 code that rides on a group-01 move.)
        let group_00 = p.one_shot().is_some_and(|o| o != OneShot::ExactStop);
        out.modal_call = out.moved && !group_00 && self.st.modal.drill().is_none();
        contour::end_of_block(self)?;
        crate::exec::comp::end_of_block(self, p, out.moved)?;
        self.profile.clear();
        self.st.c_block = false;
        Ok(out)
    }

    /// Group 0: the block's modal codes, in written order.
    fn modal_settings(&mut self, p: &Parsed, sink: &mut dyn Sink) -> Result<(), NcError> {
        for g in p.gs() {
            match g {
                G::OneShot(_) => {}
                G::SpeedMode(code) => self.speed_mode(code, p, sink),
                G::Stroke(code) => {
                    self.st.modal.set(g);
                    crate::exec::stroke::select(self, code, p);
                }
                G::Work(code) => self.select_work(code, p, sink),
                G::Motion(_) => {
                    self.st.modal.set(g);
                    // Any group-01 code cancels the drilling cycles.
                    self.st.modal.drill = Drill::Off;
                }
                G::Polar(Polar::On) => plane::polar_on(self, p, sink)?,
                G::Polar(_) => plane::polar_off(self, p, sink)?,
                G::PolarCmd(code) => plane::polar_command(self, code)?,
                _ => self.st.modal.set(g),
            }
        }
        if p.one_shot() == Some(OneShot::Cylindrical) {
            // G7.1 switches a mode (plane.rs).
            plane::cylinder(self, p, sink)?;
        }
        Ok(())
    }

    /// G96/G97 without S that changes the mode prints the new speed.
    fn speed_mode(&mut self, code: SpeedMode, p: &Parsed, sink: &mut dyn Sink) {
        let was_css = self.st.css_mode();
        self.st.modal.speed_mode = code;
        let now_css = code == SpeedMode::SurfaceSpeed;
        if was_css == now_css || p.has(b'S') {
            return;
        }
        if now_css {
            sink.emit(Event::Speed {
                s: self.st.css,
                css: true,
                max: None,
            });
        } else {
            self.st.rpm = self.css_rpm(self.st.pos.x());
            sink.emit(Event::Speed {
                s: self.st.rpm,
                css: false,
                max: None,
            });
        }
    }

    /// The rpm of constant surface speed at diameter x, clamped.
    pub(crate) fn css_rpm(&self, x: f64) -> f64 {
        let limit = self.st.rpm_limit.map_or(self.machine.spindle.max_rpm, |l| {
            l.min(self.machine.spindle.max_rpm)
        });
        if x.abs() < 1e-9 {
            return limit;
        }
        (1000.0 * self.st.css / (core::f64::consts::PI * x.abs())).min(limit)
    }

    /// G54–G59: the tool stays where it is on the machine and its
    /// coordinates change to the new system's. With G50 in the block the
    /// selection is ignored and G50 alone acts (seed 000, G54–G59 note 6).
    fn select_work(&mut self, code: Work, p: &Parsed, sink: &mut dyn Sink) {
        if p.one_shot() == Some(OneShot::SetCoordinates) {
            return;
        }
        let before = self.st.origin();
        let machine = self.st.machine_pos();
        self.st.modal.work = code;
        self.st.pos = machine.sub(self.st.origin());
        self.print_origin_if_moved(before, sink);
    }

    fn print_origin_if_moved(&self, before: Pt, sink: &mut dyn Sink) {
        let now = self.st.origin();
        if (now.r - before.r).abs() * 2.0 > 1e-6 || (now.z - before.z).abs() > 1e-6 {
            sink.emit(Event::Origin {
                x: now.x(),
                z: now.z,
            });
        }
    }

    /// Group 1: spindle start, PLC M codes, S and T, in written order.
    fn before_motion(
        &mut self,
        p: &Parsed,
        words: &[Word],
        sink: &mut dyn Sink,
    ) -> Result<(), NcError> {
        // Thread chains, M29 rules; a drilling block's M is its clamp code.
        let clamp = crate::exec::cycles::before_block(self, p, sink)?;
        let g50 = p.one_shot() == Some(OneShot::SetCoordinates);
        for w in words {
            match w.addr {
                a if a == b'M' - b'A' => {
                    // (0…9999: the block's check has passed.)
                    match M::from_code(round_half_away(w.value) as u16) {
                        M::SpindleCw => self.spindle(SpindleDir::Cw, sink),
                        M::SpindleCcw => self.spindle(SpindleDir::Ccw, sink),
                        m if m.timing() != Timing::Before => {}
                        m if clamp == Some(m) => {}
                        m => sink.emit(Event::M(m.code().into())),
                    }
                }
                a if a == b'S' - b'A' => self.s_word(w, g50, sink)?,
                a if a == b'T' - b'A' => self.t_word(w.value, sink)?,
                _ => {}
            }
        }
        Ok(())
    }

    fn spindle(&mut self, dir: SpindleDir, sink: &mut dyn Sink) {
        self.st.spindle = dir;
        sink.emit(Event::Spindle(dir));
    }

    fn s_word(&mut self, w: &Word, g50: bool, sink: &mut dyn Sink) -> Result<(), NcError> {
        let s = w.value;
        if s < 0.0 {
            return fail(Alarm::out_of_range(w.flags), "S must not be negative");
        }
        let css = self.st.css_mode();
        if g50 {
            self.st.rpm_limit = Some(s);
            let current = if css { self.st.css } else { self.st.rpm };
            sink.emit(Event::Speed {
                s: current,
                css,
                max: Some(s),
            });
            return Ok(());
        }
        if self.machine.spindle.r#type == SpindleType::Gear {
            let n = round_half_away(s);
            if !(0.0..=4.0).contains(&n) {
                return fail(
                    Alarm::out_of_range(w.flags),
                    format!("gear code S{n} outside S00…S04"),
                );
            }
            sink.emit(Event::Gear { n: n as u32 });
            return Ok(());
        }
        if css {
            // G20 surface speeds are ft/min.
            self.st.css = if self.st.inch() { s * 0.3048 } else { s };
            sink.emit(Event::Speed {
                s: self.st.css,
                css: true,
                max: None,
            });
        } else {
            self.st.rpm = s;
            sink.emit(Event::Speed {
                s,
                css: false,
                max: None,
            });
        }
        Ok(())
    }

    /// A T word (the block layer checked its range).
    fn t_word(&mut self, t: f64, sink: &mut dyn Sink) -> Result<(), NcError> {
        let t = round_half_away(t);
        let (tool, offset) = (t as u32 / 100, t as u32 % 100);
        check_tool(&self.machine, tool, offset)?;
        // Txx99 / Txx88 are tool-life words (tool_life module).
        if let Some(done) = crate::exec::tool_life::t_word(self, tool, offset, sink) {
            return done;
        }
        self.st.tool = tool;
        self.st.offset = offset;
        sink.emit(Event::Tool { t: tool, d: offset });
        Ok(())
    }

    /// Group 2: the motion or the one-shot function.
    fn motion(
        &mut self,
        p: &Parsed,
        sink: &mut dyn Sink,
        out: &mut Outcome,
    ) -> Result<(), NcError> {
        if let Some(st) = self.st.plane {
            return plane::motion(self, st, p, sink, out);
        }
        if let Some(code) = p.one_shot() {
            if code == OneShot::ExactStop {
                // G09: its move decides about waiting corners.
                return self.one_shot(code, p, sink, out);
            }
            contour::before_one_shot(self, code, sink)?;
            return contour::in_order(self, sink, |nc, s| nc.one_shot(code, p, s, out));
        }
        if p.has_g(gcode::Stroke::On) {
            // G22 owns the block's X Z I K: they are its limits.
            return Ok(());
        }
        if let Some(drill) = self.st.modal.drill() {
            self.flush_if_moving(p, sink)?;
            return crate::exec::cycles::drill(self, drill, p, sink, out);
        }
        let code = self.st.modal.motion;
        if !code.is_contour() {
            return if code.is_conic() {
                contour::conic(self, code, p, sink, out)
            } else {
                self.flush_if_moving(p, sink)?;
                crate::exec::cycles::motion(self, code, p, sink, out)
            };
        }
        let corner = contour::corner_word(self, code, p)?;
        // G05 with a mid point and no end point ends where it starts: a
        // full circle, which it cannot make (E4004 below).
        let arc_words = (code.is_arc() && (p.has(b'I') || p.has(b'K') || p.has(b'R')))
            || (matches!(code, Motion::ThreePoint | Motion::ThreePointAbs)
                && (p.has(b'I') || p.has(b'K')));
        let angle_words = code.is_straight() && contour::has_angle(p);
        if !p.has_axis() && !arc_words && !angle_words && !self.st.c_block {
            return Ok(());
        }
        let target = self.target(p);
        match code {
            Motion::Rapid | Motion::Line => {
                contour::straight(self, code == Motion::Rapid, p, corner, sink)?
            }
            Motion::ArcCw | Motion::ArcCcw => {
                if let Some(e) = self.arc_element(self.st.pos, code == Motion::ArcCw, target, p)? {
                    contour::feed_element(self, e, corner, sink)?;
                }
            }
            _ => {
                contour::flush(self, sink)?;
                self.three_point_arc(code == Motion::ThreePointAbs, target, p, sink)?
            }
        }
        out.moved = true;
        Ok(())
    }

    /// A move that cannot take a corner prints what waits first.
    fn flush_if_moving(&mut self, p: &Parsed, sink: &mut dyn Sink) -> Result<(), NcError> {
        if p.has_axis() {
            contour::flush(self, sink)?;
        }
        Ok(())
    }

    /// The words of this block read against the state the kernel is in.
    #[inline]
    pub(crate) fn reader(&self) -> Reader<'_> {
        Reader {
            machine: &self.machine,
            inch: self.st.inch(),
            at: self.st.pos,
            motion: self.st.modal.motion,
        }
    }

    /// A length word in mm (plan::reader).
    #[inline]
    pub(crate) fn len_of(&self, p: &Parsed, letter: u8) -> Option<f64> {
        self.reader().len_of(p, letter)
    }

    /// An X-axis word as a radial distance in mm (plan::reader).
    #[inline]
    pub(crate) fn radial_of(&self, p: &Parsed, letter: u8) -> Option<f64> {
        self.reader().radial_of(p, letter)
    }

    /// The end point of a move: X/Z absolute, U/W incremental, axes left
    /// out keep their coordinate.
    #[inline(always)]
    pub(crate) fn target(&self, p: &Parsed) -> Pt {
        self.target_from(p, self.st.pos)
    }

    /// The end point of a move that starts at `from` (a profile block's U/W
    /// are relative to the previous profile point, not to the tool).
    #[inline(always)]
    pub(crate) fn target_from(&self, p: &Parsed, from: Pt) -> Pt {
        self.reader().target_from(p, from)
    }

    /// A rapid to `to`, C already at its end angle (it started at `c_from`).
    pub(crate) fn rapid_c(&mut self, to: Pt, c_from: f64, sink: &mut dyn Sink) {
        self.st.pos = to;
        sink.emit(Event::Rapid {
            x: to.x(),
            z: to.z,
            c: self.c_field(c_from),
        });
    }

    /// A rapid that leaves C where it is.
    pub(crate) fn rapid(&mut self, to: Pt, sink: &mut dyn Sink) {
        self.rapid_c(to, self.st.c, sink);
    }

    /// Whether the block names an axis: X, Z, U, W, or C/H on a machine
    /// with a C axis.
    pub(crate) fn axis_words(&self, p: &Parsed) -> bool {
        p.has_axis() || self.st.c_block
    }

    /// Prints `FEED` when the feed of the next feed event differs from the
    /// last one printed.
    pub(crate) fn feed_due(&mut self, sink: &mut dyn Sink) {
        let f = self.st.feed * self.st.unit();
        let per_rev = self.st.per_rev();
        if self.st.feed_due((f, per_rev)) {
            sink.emit(Event::Feed { f, per_rev });
        }
    }

    /// The element of a G02/G03 block from `from` (the current point, or
    /// the previous point of a profile), as plan::reader reads it.
    #[inline(always)]
    pub(crate) fn arc_element(
        &self,
        from: Pt,
        cw: bool,
        to: Pt,
        p: &Parsed,
    ) -> Result<Option<Element>, NcError> {
        self.reader().arc_element(from, cw, to, p)
    }

    pub(crate) fn emit_arc(&mut self, cw: bool, to: Pt, c: Pt, sink: &mut dyn Sink) {
        self.feed_due(sink);
        self.st.pos = to;
        let dir = if cw { Dir::Cw } else { Dir::Ccw };
        sink.emit(Event::Arc {
            dir,
            x: to.x(),
            z: to.z,
            cx: c.x(),
            cz: c.z,
        });
    }

    /// G05 (I/K relative to the start) and G05.1 (absolute mid point).
    fn three_point_arc(
        &mut self,
        absolute: bool,
        to: Pt,
        p: &Parsed,
        sink: &mut dyn Sink,
    ) -> Result<(), NcError> {
        let from = self.st.pos;
        let Element::Arc { centre, cw, .. } = self.reader().three_point(absolute, p, from, to)?
        else {
            return Ok(());
        };
        self.emit_arc(cw, to, centre, sink);
        Ok(())
    }

    fn one_shot(
        &mut self,
        code: OneShot,
        p: &Parsed,
        sink: &mut dyn Sink,
        out: &mut Outcome,
    ) -> Result<(), NcError> {
        match code {
            OneShot::Dwell => self.dwell(p, sink),
            OneShot::ExactStop => {
                // G09: exact stop is the runtime's; the motion runs as usual.
                let mut q = p.clone();
                q.clear_gs();
                return self.motion(&q, sink, out);
            }
            OneShot::Home => self.home(p, 1, sink),
            OneShot::HomeN => self.home_n(p, sink),
            OneShot::Skip => self.skip(p, sink, out),
            OneShot::MeasureX | OneShot::MeasureZ => {
                crate::exec::measure::run(self, code == OneShot::MeasureX, p, sink)?
            }
            OneShot::SetCoordinates => self.set_coordinates(p, sink),
            OneShot::Local => self.set_local(p, sink),
            OneShot::MachineCoords => self.machine_coords(p, sink)?,
            OneShot::Finish | OneShot::RoughTurn | OneShot::RoughFace | OneShot::Pattern => {
                return crate::exec::compound::run(self, code, p, sink, out)
            }
            OneShot::PeckFace
            | OneShot::PeckGroove
            | OneShot::MultiThread
            | OneShot::SpiralThread => {
                return crate::exec::cycles::one_shot(self, code, p, sink, out)
            }
            // G7.1 switched its mode in group 0 (plane.rs).
            OneShot::Cylindrical => {}
            _ => {
                return fail(
                    Alarm::NotSupportedYet,
                    format!("{} is not implemented yet", code.name()),
                )
            }
        }
        out.moved = matches!(
            code,
            OneShot::Home
                | OneShot::HomeN
                | OneShot::Skip
                | OneShot::MeasureX
                | OneShot::MeasureZ
                | OneShot::MachineCoords
        );
        Ok(())
    }

    /// G30 P2…P4 (the block layer checked the range): to the second,
    /// third or fourth reference point.
    fn home_n(&mut self, p: &Parsed, sink: &mut dyn Sink) {
        let n = p.get(b'P').map_or(2.0, round_half_away);
        self.home(p, n as u32, sink);
    }

    /// G31: the skip move; the runtime stops it where the signal comes.
    fn skip(&mut self, p: &Parsed, sink: &mut dyn Sink, out: &mut Outcome) {
        let to = self.target(p);
        self.feed_due(sink);
        self.st.pos = to;
        self.st.skip = Some(to);
        out.skip = Some(to);
        sink.emit(Event::Skip { x: to.x(), z: to.z });
    }

    /// G53: a rapid to machine coordinates, X on the diameter.
    fn machine_coords(&mut self, p: &Parsed, sink: &mut dyn Sink) -> Result<(), NcError> {
        if p.has(b'U') || p.has(b'W') {
            let msg = "G53 takes machine coordinates X/Z only, not U/W";
            let e = NcError::new(Alarm::IncompatibleWords, msg);
            return Err(e.on_pair(addr(b'U'), addr(b'W')));
        }
        let origin = self.st.origin();
        let mut m = self.st.machine_pos();
        if let Some(r) = self.radial_of(p, b'X') {
            m.r = r;
        }
        if let Some(z) = self.len_of(p, b'Z') {
            m.z = z;
        }
        self.rapid(m.sub(origin), sink);
        Ok(())
    }

    fn dwell(&mut self, p: &Parsed, sink: &mut dyn Sink) {
        let secs = if let Some(ms) = p.get(b'P') {
            // Whole milliseconds (§1.9): a computed P is rounded.
            round_half_away(ms) / 1000.0
        } else if let Some(w) = p.word(b'X').or(p.word(b'U')) {
            let mut s = w.value;
            if w.flags & NO_POINT != 0
                && self.machine.machine.decimal_point == DecimalPoint::Increment
            {
                s *= 0.001;
            }
            s
        } else {
            // G04 alone: an exact stop, nothing printed.
            return;
        };
        let s = secs.max(0.0);
        self.st.clock_ms += s * 1000.0;
        sink.emit(Event::Dwell { s });
    }

    /// G28/G30: rapid to the intermediate point, then the named axes go to
    /// reference point n.
    fn home(&mut self, p: &Parsed, n: u32, sink: &mut dyn Sink) {
        let named_x = p.has(b'X') || p.has(b'U');
        let named_z = p.has(b'Z') || p.has(b'W');
        let named_c = self.st.c_block;
        if !named_x && !named_z && !named_c {
            return;
        }
        let mid = self.target(p);
        let c_from = self.st.c;
        let c_mid = crate::exec::caxis::target_from(self, p, c_from);
        if mid.dist(self.st.pos) > 1e-9 || (c_mid - c_from).abs() > 1e-9 {
            self.st.c = c_mid;
            self.rapid_c(mid, c_from, sink);
        }
        self.st.pos = mid;
        if named_c {
            // The C reference point is 0° (machine.md has no C angles).
            self.st.c = 0.0;
        }
        let rp = self.reference_point(n);
        let origin = self.st.origin();
        if named_x {
            self.st.pos.r = rp.r - origin.r;
        }
        if named_z {
            self.st.pos.z = rp.z - origin.z;
        }
        sink.emit(Event::Home {
            n,
            x: named_x,
            z: named_z,
            c: named_c,
        });
    }

    pub(crate) fn reference_point(&self, n: u32) -> Pt {
        let r = &self.machine.reference_points;
        match n {
            2 => Pt::xz(r.second.x, r.second.z),
            3 => Pt::xz(r.third.x, r.third.z),
            4 => Pt::xz(r.fourth.x, r.fourth.z),
            _ => Pt::default(),
        }
    }

    /// G50 X Z: the current point gets these coordinates (U W: changes).
    fn set_coordinates(&mut self, p: &Parsed, sink: &mut dyn Sink) {
        let before = self.st.origin();
        let now = self.target(p);
        let machine = self.st.machine_pos();
        if p.has(b'X') || p.has(b'U') {
            self.st.local.r = 0.0;
            let base = self.st.exofs.r + self.st.work[self.st.work_index()].r;
            self.st.shift.r = machine.r - now.r - base;
            self.st.pos.r = now.r;
        }
        if p.has(b'Z') || p.has(b'W') {
            self.st.local.z = 0.0;
            let base = self.st.exofs.z + self.st.work[self.st.work_index()].z;
            self.st.shift.z = machine.z - now.z - base;
            self.st.pos.z = now.z;
        }
        self.print_origin_if_moved(before, sink);
    }

    /// G52: the local origin in workpiece coordinates (U = X, W = Z).
    fn set_local(&mut self, p: &Parsed, sink: &mut dyn Sink) {
        let before = self.st.origin();
        let machine = self.st.machine_pos();
        if let Some(r) = self.radial_of(p, b'X').or(self.radial_of(p, b'U')) {
            self.st.local.r = r;
        }
        if let Some(z) = self.len_of(p, b'Z').or(self.len_of(p, b'W')) {
            self.st.local.z = z;
        }
        self.st.pos = machine.sub(self.st.origin());
        self.print_origin_if_moved(before, sink);
    }

    /// Group 3: spindle stop and the "off" PLC codes.
    fn after_motion(&mut self, p: &Parsed, sink: &mut dyn Sink) {
        for &m in p.ms() {
            if m == M::SpindleStop {
                self.spindle(SpindleDir::Stop, sink);
            } else if m.timing() == Timing::After {
                sink.emit(Event::M(m.code().into()));
            }
        }
    }

    /// Group 4: program stops and ends.
    // (Group 6, a call or return, is the VM's: `word_call`.)
    fn stops(&mut self, p: &Parsed, sink: &mut dyn Sink, out: &mut Outcome) {
        for &m in p.ms() {
            let kind = match m {
                M::Stop => StopKind::M00,
                M::OptionalStop if self.machine.operator.optional_stop => StopKind::M01,
                M::End => StopKind::M02,
                M::EndRewind => StopKind::M30,
                _ => continue,
            };
            sink.emit(Event::Stop(kind));
            if matches!(kind, StopKind::M02 | StopKind::M30) {
                if kind == StopKind::M30 {
                    self.st.parts += 1.0;
                }
                out.end = Some(kind);
            }
        }
    }

    /// Before the motion: F is modal (the block's own move uses it); the last B D E F H M N O S T are kept for #4102….
    #[inline]
    fn remember(&mut self, p: &Parsed) {
        // The F of a thread block is its lead, not a feed (cycles.md §0).
        if let Some(f) = p
            .get(b'F')
            .filter(|_| !crate::exec::cycles::f_is_lead(self, p))
        {
            self.st.feed = f;
        }
        for letter in [b'B', b'D', b'E', b'F', b'H', b'S', b'T'] {
            if let Some(v) = p.get(letter) {
                self.st.last[(letter - b'A') as usize] = v;
            }
        }
        if let Some(&m) = p.ms().last() {
            self.st.last[(b'M' - b'A') as usize] = f64::from(m.code());
        }
    }
}

/// E7004: a tool or offset number outside the machine's table.
pub fn check_tool(m: &Machine, tool: u32, offset: u32) -> Result<(), NcError> {
    if tool > m.tools.count {
        return fail(
            Alarm::ToolNumber,
            format!(
                "tool {tool} is outside the tool table (1…{})",
                m.tools.count
            ),
        );
    }
    if offset > m.tools.offsets && offset != 88 && offset != 99 {
        return fail(
            Alarm::ToolNumber,
            format!(
                "offset {offset} is outside the offset table (1…{})",
                m.tools.offsets
            ),
        );
    }
    Ok(())
}

/// The call or return a block's M code asks for (group 6), with its P and
/// L. Only a computed M gets here: the compiler takes a written one's
/// words, and E1012 lets a block hold one at most.
fn word_call(p: &Parsed) -> Option<WordCall> {
    let value = |letter: u8| p.word(letter).map(|w| w.value);
    p.ms().iter().find_map(|&m| match m {
        M::SubCall => Some(WordCall::Sub {
            p: value(b'P'),
            l: value(b'L'),
        }),
        M::Return => Some(WordCall::Return { seq: value(b'P') }),
        M::MacroCall(n) => Some(WordCall::Macro(n)),
        _ => None,
    })
}
