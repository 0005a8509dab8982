//! The warnings of dialect.md §8 that depend on the modal state, found by
//! the dry run of a static program (check.rs) block by block: W104 (a
//! word the block's motion or form does not use), W105 (inch length
//! without a point), W107 (feed move at F = 0), W108 (arc or conic without
//! motion), W110 (thread in G96), W111 (feed mode changed without a new
//! F), W112 (corner word ignored), W114 (S above the spindle maximum),
//! W125 (a feed per minute below 1: a feed per revolution written for a
//! control that starts in G99). A program with macro
//! statements or computed words is not dry-run: where its run is known,
//! the compile-time run in the VM (`predict`) hands its blocks to the
//! same [`Warner`], all but W107.

use grammar::ast::Addr;
use grammar::{Diagnostic, Span};
use nc::block::round_half_away;
use nc::exec::plane::Kind as PlaneKind;
use nc::gcode::{self, Motion, OneShot, Stroke};
use nc::machine::{DecimalPoint, SpindleType};
use nc::words::{Word, ADDR_COUNT, COMMA_C, COMMA_R, NO_POINT};
use nc::{Event, Nc, Sink};

use crate::words::{addr_code, value_of, WordValue};
use std::collections::HashSet;

/// W125's bound: a feed per minute below it is taken for a feed per
/// revolution. No cut runs at less than 1 mm a minute, and turning feeds
/// per revolution lie below it (the seeds' own example is `G99 F0.15`).
const SLOW_FEED: f64 = 1.0;

/// The sink of the dry run: what a block printed, for the warnings.
#[derive(Default)]
pub struct Counts {
    /// Motion events of any kind.
    pub motions: u32,
    /// Feed moves (moves at the modal F).
    pub feeds: u32,
    /// Thread events.
    pub threads: u32,
    /// Any event at all.
    pub events: u32,
    /// The F of the block's first feed move when a `FEED` came before it
    /// in the block (`None`: the F in force when the block started).
    pub first_f: Option<f64>,
    last_f: Option<f64>,
}

impl Sink for Counts {
    fn emit(&mut self, e: Event) {
        self.count(&e);
    }
}

impl Counts {
    /// Counts `e`, one event the block printed.
    pub fn count(&mut self, e: &Event) {
        self.events += 1;
        self.motions += u32::from(e.is_motion());
        if let Event::Feed { f, .. } = *e {
            self.last_f = Some(f);
        }
        if e.is_feed() && self.feeds == 0 {
            self.first_f = self.last_f;
        }
        self.feeds += u32::from(e.is_feed());
        self.threads += u32::from(matches!(e, Event::Thread { .. } | Event::ArcThread { .. }));
    }
}

/// The state a block starts from, taken before it runs.
pub struct Before {
    per_rev: bool,
    /// The modal F (a G70's profile may leave another).
    feed: f64,
    /// The point on the programmed path (`path_point`).
    pos: nc::point::Pt,
    applied: u32,
}

/// The warnings found so far and what they wait for.
#[derive(Default)]
pub struct Warner {
    pub diags: Vec<(usize, Diagnostic)>,
    /// Each warning is said once where it stands, however often the dry
    /// run passes there (a loop, a subprogram called again): the thousands
    /// of copies a program that loops until its budget is spent made told
    /// nothing more than the first.
    told: HashSet<(usize, &'static str, Span)>,
    /// W107 is given once: the run stops at the first such move.
    zero_feed_told: bool,
    /// A G98/G99 block that kept the old F (W111 when a feed move uses it).
    mode_change: Option<(usize, Span, f64)>,
    /// Where the F in force was written: its word (W125 points there).
    feed_word: Option<(usize, Span)>,
    /// W125 is given once: the program's F words share the one mistake.
    slow_feed_told: bool,
    /// A corner word waiting for the next move, with the count of applied
    /// corners when it was written (W112 when that count stays).
    corner: Option<(usize, Span, u32)>,
    /// The last block that moved an axis or wrote Q was angle
    /// programming's first block, `Q_` alone (§5.2).
    angle_first: bool,
}

/// The word of `letter` (an address code) in the block.
fn find(ws: &[grammar::ast::Word], letter: u8) -> Option<&grammar::ast::Word> {
    ws.iter().find(|w| addr_code(w.addr) == letter)
}

/// The block's F word, as [`find`] gives it: the one at its index among
/// the literal words when that is the block's F (no search: a plain
/// move's F is asked for every block).
fn f_word<'w>(ws: &'w [grammar::ast::Word], seen: &Seen) -> Option<&'w grammar::ast::Word> {
    const F: u8 = b'F' - b'A';
    let at_index = seen.f_at.and_then(|i| ws.get(i));
    match at_index.filter(|w| addr_code(w.addr) == F) {
        Some(w) => Some(w),
        None if seen.written(F) => find(ws, F),
        None => None,
    }
}

/// The values of G00–G03 written as whole numbers: motions (group 01),
/// of which [`Seen`] notes nothing.
const PLAIN_MOTIONS: [f64; 4] = [0.0, 1.0, 2.0, 3.0];

/// The G code of `value` as the kernel codes it (tenths: G6.2 is 62),
/// typed. (Out of line, as [`m_of`]: the constants of their rounding
/// would otherwise be loaded for every block, whatever its codes.)
#[inline(never)]
fn g_of(value: f64) -> Option<gcode::G> {
    gcode::G::from_code(crate::words::round_g(value))
}

/// The M code of `value`.
#[inline(never)]
fn m_of(value: f64) -> f64 {
    round_half_away(value)
}

/// What the warnings ask about a block's words, found in one pass over
/// them: the checks below run for every block of the dry run, and asking
/// each question of the words anew cost more than the block's execution.
struct Seen {
    /// Bit `a`: address `a` among the literal words.
    lits: u32,
    /// Bit `a`: address `a` among the block's words as written.
    written: u32,
    /// The group-00 code that owns the block (one at most: two are
    /// E2002).
    one_shot_code: Option<OneShot>,
    /// G22 is in the block.
    stroke_on: bool,
    /// M98 (M99) is in the block, as a literal.
    m98: bool,
    m99: bool,
    /// The letters may belong to something other than the motion: G66,
    /// a G code not of the dialect (a G-code macro's arguments), a
    /// computed G or M.
    other_function: bool,
    /// The index of the block's first F word, where the literal words
    /// are all the block's ([`f_word`]).
    f_at: Option<usize>,
}

impl Seen {
    fn of(ws: &[grammar::ast::Word], lits: &[Word]) -> Seen {
        let mut seen = Seen {
            lits: 0,
            written: 0,
            one_shot_code: None,
            stroke_on: false,
            m98: false,
            m99: false,
            other_function: false,
            f_at: None,
        };
        for (i, w) in lits.iter().enumerate() {
            let b = bit(w.addr);
            seen.lits |= b;
            // (One test passes the words nothing more is asked of.)
            if b & const { letters(b"FGM") } != 0 {
                seen.note(i, w);
            }
        }
        let computed = |w: &grammar::ast::Word| {
            matches!(w.addr, Addr::Letter('G' | 'M')) && matches!(value_of(w), WordValue::Expr(_))
        };
        seen.other_function |= ws.len() != lits.len() && ws.iter().any(computed);
        // A call's M98 (M99) goes with its P and L, so it is not among
        // the literal words of a block that has others: it is written.
        if ws.len() != lits.len() {
            for w in ws.iter().filter(|w| w.addr == Addr::Letter('M')) {
                if let WordValue::Literal(v, _) = value_of(w) {
                    let m = m_of(v);
                    seen.m98 |= m == 98.0;
                    seen.m99 |= m == 99.0;
                }
            }
        }
        // The literal words are the written ones, or some of them in the
        // same order (a call takes its P and L): as many means the same
        // words, and an F's index among them its index in the block.
        seen.written = seen.lits;
        if ws.len() != lits.len() {
            seen.written = ws.iter().fold(0, |m, w| m | bit(addr_code(w.addr)));
            seen.f_at = None;
        }
        seen
    }

    /// What the literal word `w`, F, G or M, the `i`th, tells.
    fn note(&mut self, i: usize, w: &Word) {
        match w.addr + b'A' {
            // (The first, as `find` gives it.)
            b'F' => {
                self.f_at.get_or_insert(i);
            }
            // (G00–G03 written whole, the G of most blocks, are motions:
            // nothing to note, and no code to round.)
            b'G' if PLAIN_MOTIONS.contains(&w.value) => {}
            b'G' => match g_of(w.value) {
                Some(gcode::G::OneShot(o)) => self.one_shot_code = Some(o),
                Some(gcode::G::Stroke(Stroke::On)) => self.stroke_on = true,
                Some(gcode::G::ModalCall(gcode::ModalCall::On)) | None => {
                    self.other_function = true
                }
                _ => {}
            },
            b'M' => {
                let m = m_of(w.value);
                self.m98 |= m == 98.0;
                self.m99 |= m == 99.0;
            }
            _ => {}
        }
    }

    /// A group-00 code owns the block.
    fn one_shot(&self) -> bool {
        self.one_shot_code.is_some()
    }

    /// `o` owns the block.
    fn is(&self, o: OneShot) -> bool {
        self.one_shot_code == Some(o)
    }

    fn has(&self, letter: u8) -> bool {
        self.lits & bit(letter - b'A') != 0
    }

    fn written(&self, a: u8) -> bool {
        self.written & bit(a) != 0
    }
}

/// The point on the programmed path: the plane's point during polar or
/// cylindrical interpolation (an arc about the spindle centre leaves the
/// joints' X where it was), the position otherwise.
fn path_point(nc: &Nc) -> nc::point::Pt {
    nc.st.plane.map_or(nc.st.pos, |plane| plane.pt)
}

/// The bit of address `a` (0..ADDR_COUNT: the words' addresses, and
/// [`addr_code`]'s, are below it).
fn bit(a: u8) -> u32 {
    const { assert!(ADDR_COUNT <= 32) };
    // (Not a checked shift: this runs for every word of the dry run.)
    1 << (a % 32)
}

/// The bits of the letters A–Z (not the comma words).
const LETTERS: u32 = (1 << 26) - 1;

/// The bits of `ls` (upper-case letters).
const fn letters(ls: &[u8]) -> u32 {
    let mut m = 0;
    let mut i = 0;
    while i < ls.len() {
        m |= 1 << (ls[i] - b'A');
        i += 1;
    }
    m
}

/// What any block may carry: feed, codes, sequence and program numbers,
/// speed, tool, the axes (Y and V are E2005 on a lathe, C and H without
/// a C axis).
const ANY_BLOCK: u32 = letters(b"FGMNOSTXZUWCHYV");

/// The letters a block of `motion` uses besides [`ANY_BLOCK`] (dialect.md
/// §4.1, §4.3, §4.8): angles Q, corners L and D, centres, radii, leads
/// and counts. An arc of polar interpolation takes its centre as I, J.
fn motion_letters(motion: Motion, in_plane: bool) -> u32 {
    // (Each mask made when the compiler is built: this runs for every
    // block of the dry run.)
    match motion {
        Motion::Rapid => const { letters(b"Q") },
        Motion::Line => const { letters(b"LDQ") },
        Motion::ArcCw | Motion::ArcCcw if in_plane => const { letters(b"RIJKLD") },
        Motion::ArcCw | Motion::ArcCcw => const { letters(b"RIKLD") },
        Motion::ThreePoint | Motion::ThreePointAbs => const { letters(b"IK") },
        Motion::EllipseCw | Motion::EllipseCcw => const { letters(b"ABQ") },
        Motion::ParabolaCw | Motion::ParabolaCcw => const { letters(b"PQ") },
        Motion::Thread => const { letters(b"IJKQ") },
        Motion::RigidThread => const { letters(b"IJK") },
        Motion::ArcThreadCw | Motion::ArcThreadCcw => const { letters(b"RIKQ") },
        Motion::Tapping => const { letters(b"IL") },
        Motion::VariableThread => const { letters(b"IJKR") },
        Motion::TurningCycle | Motion::FacingCycle => const { letters(b"R") },
        Motion::ThreadCycle => const { letters(b"RIJKLP") },
        Motion::RigidThreadCycle => const { letters(b"RILP") },
    }
}

/// The letters a block owned by group-00 code `o` uses (dialect.md §4.2,
/// §4.4–§4.6, §4.8): its own words and the feed, codes, numbers, speed
/// and tool any block may carry; all letters where the block is not
/// checked (G09 with its move, G10/G11 (`data_setting`), G65's
/// arguments).
fn one_shot_letters(o: OneShot, written: u32) -> u32 {
    const BASE: u32 = letters(b"FGMNOSTYV");
    BASE | match o {
        OneShot::Dwell => const { letters(b"PXUQ") },
        OneShot::Cylindrical => const { letters(b"CJLRK") },
        OneShot::Home => const { letters(b"XZUWCH") },
        OneShot::HomeN => const { letters(b"PXZUWCH") },
        OneShot::Skip => const { letters(b"XZUWCHP") },
        OneShot::MeasureX => const { letters(b"XU") },
        OneShot::MeasureZ => const { letters(b"ZW") },
        OneShot::SetCoordinates | OneShot::Local | OneShot::MachineCoords => {
            const { letters(b"XZUWCH") }
        }
        OneShot::Finish => const { letters(b"PQ") },
        OneShot::RoughTurn
        | OneShot::RoughFace
        | OneShot::Pattern
        | OneShot::PeckFace
        | OneShot::PeckGroove
        | OneShot::MultiThread
        | OneShot::SpiralThread => cycle_form(o, written).map_or(0, |(l, _)| l),
        OneShot::ExactStop
        | OneShot::DataSetting
        | OneShot::DataSettingEnd
        | OneShot::MacroCall => LETTERS,
    }
}

/// The letters a block of the two-block cycle `o` (G71–G76, G78) uses
/// beside the base ones, by the block's form, and the form's name for
/// messages. The form is told by the block's letters `written`, as the
/// kernel tells it (cycles.md §0, "Which block is which"; dialect.md §4.8,
/// §4.12): a G71–G73 block with P or Q is the cycle block (one without
/// the other is an error of its own), a G74–G78 block with an axis word the
/// second block, G76's with K or D the one-block form (its P, ignored, is
/// `ignored_forms`' to tell).
fn cycle_form(o: OneShot, written: u32) -> Option<(u32, &'static str)> {
    let cycle = written & const { letters(b"PQ") } != 0;
    let second = written & const { letters(b"XZUW") } != 0;
    let one_block = second && written & const { letters(b"KD") } != 0;
    Some(match o {
        OneShot::RoughTurn if !cycle => (const { letters(b"UR") }, "first block (U R)"),
        OneShot::RoughFace if !cycle => (const { letters(b"WR") }, "first block (W R)"),
        OneShot::Pattern if !cycle => (const { letters(b"UWR") }, "first block (U W R)"),
        OneShot::RoughTurn | OneShot::RoughFace => {
            (const { letters(b"PQUWDKJ") }, "cycle block (P Q U W D K J)")
        }
        OneShot::Pattern => (const { letters(b"PQUW") }, "cycle block (P Q U W)"),
        OneShot::PeckFace | OneShot::PeckGroove if !second => {
            (const { letters(b"R") }, "first block (R)")
        }
        OneShot::PeckFace | OneShot::PeckGroove => (
            const { letters(b"XZUWPQR") },
            "second block (X Z U W P Q R)",
        ),
        OneShot::MultiThread if !second => (const { letters(b"PQRJK") }, "first block (P Q R J K)"),
        OneShot::MultiThread if one_block => (
            const { letters(b"XZUWIKDAP") },
            "one-block form (X Z U W I K D A)",
        ),
        OneShot::SpiralThread if !second => (
            const { letters(b"PQRJKDLE") },
            "first block (P Q R J K D L E)",
        ),
        OneShot::MultiThread | OneShot::SpiralThread => (
            const { letters(b"XZUWRPQI") },
            "second block (X Z U W R P Q I)",
        ),
        _ => return None,
    })
}

/// What owns a block's letters: its group-00 code, else the drilling
/// cycle in force (group 10, dialect.md §4.8), else its motion (group 01).
#[derive(Clone, Copy)]
enum Owner {
    OneShot(OneShot),
    Drill(gcode::Drill),
    Motion(Motion),
}

impl Owner {
    fn of(nc: &Nc, seen: &Seen) -> Owner {
        match (seen.one_shot_code, nc.st.modal.drill) {
            (Some(o), _) => Owner::OneShot(o),
            (None, gcode::Drill::Off) => Owner::Motion(nc.st.modal.motion),
            (None, drill) => Owner::Drill(drill),
        }
    }

    /// The letters of a block it owns.
    fn letters(self, nc: &Nc, seen: &Seen) -> u32 {
        match self {
            Owner::OneShot(o) => one_shot_letters(o, seen.written),
            Owner::Drill(d) if d.taps() => ANY_BLOCK | const { letters(b"PIK") },
            Owner::Drill(_) => ANY_BLOCK | const { letters(b"PQRJK") },
            Owner::Motion(motion) => {
                let own = motion_letters(motion, nc.st.plane.is_some());
                // An arc's R wins over I and K (§4.1 rule 1, G32.2/G32.3 too).
                match by_radius(self, seen) {
                    true => ANY_BLOCK | own & !const { letters(b"IJK") },
                    false => ANY_BLOCK | own,
                }
            }
        }
    }

    /// Its name in messages.
    fn name(self, seen: &Seen) -> String {
        match self {
            Owner::OneShot(o) => match cycle_form(o, seen.written) {
                Some((_, form)) => format!("{}'s {form}", o.name()),
                None => o.name(),
            },
            Owner::Drill(d) => d.name(),
            Owner::Motion(motion) => gcode::name(motion.code()),
        }
    }
}

/// Whether the block is an arc (or arc thread) given by its radius R.
fn by_radius(owner: Owner, seen: &Seen) -> bool {
    let arc = |m: Motion| m.is_arc() || matches!(m, Motion::ArcThreadCw | Motion::ArcThreadCcw);
    matches!(owner, Owner::Motion(m) if arc(m)) && seen.written(b'R' - b'A')
}

impl Warner {
    pub fn before(&self, nc: &Nc) -> Before {
        Before {
            per_rev: nc.st.per_rev(),
            feed: nc.st.feed,
            pos: path_point(nc),
            applied: nc.st.contour.applied,
        }
    }

    /// Tells `msg` at `span`, once. (Cold and out of line, as
    /// `warn_help` and `ignored`: a warning is rare, and the checks that
    /// call them run for every block.)
    #[cold]
    #[inline(never)]
    fn warn(&mut self, unit: usize, code: &'static str, span: Span, msg: String) {
        if self.told.insert((unit, code, span)) {
            self.diags
                .push((unit, Diagnostic::warning(code, span, msg)));
        }
    }

    /// [`warn`](Self::warn) with a help line.
    #[cold]
    #[inline(never)]
    fn warn_help(&mut self, at: (usize, Span), code: &'static str, msg: String, help: String) {
        let (unit, span) = at;
        if self.told.insert((unit, code, span)) {
            let d = Diagnostic::warning(code, span, msg).with_help(help);
            self.diags.push((unit, d));
        }
    }

    /// W107: the block ran a feed move at F = 0 (the kernel's E7001).
    pub fn zero_feed(&mut self, unit: usize, span: Span) {
        if !std::mem::replace(&mut self.zero_feed_told, true) {
            self.warn(
                unit,
                "W107",
                span,
                "this feed move runs at F = 0: no F is in force here, so the run stops with E7001; give an F".into(),
            );
        }
    }

    /// W120: the run stops at this block, its extra steps spent (`extra`
    /// blocks run beyond the first pass over each block).
    pub fn budget_spent(&mut self, unit: usize, span: Span, extra: u64) {
        let msg = format!(
            "the compile-time dry run stops here: it has run {extra} blocks beyond its first pass over each (loop rounds, repeated calls, cycle passes); what runs after this block is checked only when the program runs"
        );
        let help = "does the program run for ever? After a G71-G73 cycle the run goes on after its profile's last block, so a profile that stands before its cycle sends the run back to the cycle. An M98 with a large L repeats its subprogram's blocks too, and an M99 P that returns to a block before its call runs the call again";
        self.warn_help((unit, span), "W120", msg, help.into());
    }

    /// W122: by the block at `span` the run has used up the machine's
    /// block budget of `max` (the dry run counted `counted` blocks in
    /// all), so `gbvm` stops it there with E6005 at the latest.
    pub fn over_budget(&mut self, unit: usize, span: Span, max: u64, counted: u64) {
        let msg = format!(
            "the run uses up the block budget here: by this block it has run more than run.max_blocks = {max} blocks, so `gbvm run` stops with E6005 at this block at the latest"
        );
        let help = format!(
            "a program this long needs a larger budget: set run.max_blocks in the machine file, or run it with `gbvm run --max-blocks N`, N at least {counted} (the blocks the compile-time dry run counted)"
        );
        self.warn_help((unit, span), "W122", msg, help);
    }

    /// W123: the `M99 P seq` at `at` returns to a caller (`None`: the
    /// main program, else its number) that has no block N`seq`, where
    /// the run stops with E6002.
    pub fn return_missing(&mut self, at: (usize, Span), seq: u32, caller: Option<u32>) {
        let caller = caller.map_or("the main program".to_string(), |n| format!("O{n:04}"));
        let msg = format!(
            "M99 P{seq} returns to block N{seq} of the calling program, {caller}, which has none: the run stops here with E6002"
        );
        let help = format!(
            "number the block {caller} should go on at N{seq}, or return with M99 alone (to the block after the call)"
        );
        self.warn_help(at, "W123", msg, help);
    }

    /// W124: the kernel faulted at `at`, where the run stops.
    pub fn run_stops(&mut self, at: (usize, Span), e: &nc::NcError) {
        let (unit, span) = at;
        if self.stopped_before() {
            return;
        }
        if self.told.insert((unit, "W124", span)) {
            let d = crate::predict::warning(u32::from(e.code), &e.message, span);
            self.diags.push((unit, d));
        }
    }

    /// Whether the run stops before this block: the dry run goes on past
    /// a feed move at F = 0 (W107, for the errors after it), but a run
    /// stops there with E7001 and meets no later alarm (W124).
    fn stopped_before(&self) -> bool {
        self.zero_feed_told
    }

    /// W124 for the user alarm `code` (`G65 H99`) the run stops with at
    /// `at`.
    pub fn user_alarm(&mut self, at: (usize, Span), code: u32, msg: &str) {
        let (unit, span) = at;
        if self.stopped_before() {
            return;
        }
        if self.told.insert((unit, "W124", span)) {
            let d = crate::predict::warning(code, msg, span);
            self.diags.push((unit, d));
        }
    }

    /// The warnings of a block that ran without error.
    pub fn after(
        &mut self,
        unit: usize,
        nc: &Nc,
        block: (&[grammar::ast::Word], Span),
        lits: &[Word],
        counts: &Counts,
        before: Before,
    ) {
        let (ws, span) = block;
        let seen = Seen::of(ws, lits);
        self.inch_lengths(unit, nc, ws, &seen);
        self.feed_mode(unit, nc, &seen, span, counts, &before);
        self.slow_feed(unit, nc, (ws, &seen, span), counts);
        self.no_motion(unit, nc, &seen, span, &before);
        self.corners(unit, nc, ws, &seen, counts, &before);
        if counts.threads > 0 && nc.st.css_mode() {
            self.warn(
                unit,
                "W110",
                span,
                "thread cut in constant surface speed (G96): the spindle speed changes with X, and the lead follows it; cut threads in G97".into(),
            );
        }
        self.spindle_max(unit, nc, ws, &seen);
        self.outside_plane(unit, nc, ws, &seen);
        self.unused_words(unit, nc, ws, &seen);
        self.ignored_forms(unit, nc, ws, &seen);
    }

    /// W104 for the words that a form of the block ignores (§4.3, §4.12,
    /// §5.2): P of G92/G92.1 without thread repair (№174.4), P of the
    /// one-block G76, Q of `X_ Z_ Q_` without a first block before it, R
    /// (and G92's L) in a G90/G92/G94 run's block without an axis word, I
    /// beside F in a thread block or G76's second block (F gives the
    /// lead). Each such word is told, a block may hold several.
    fn ignored_forms(&mut self, unit: usize, nc: &Nc, ws: &[grammar::ast::Word], seen: &Seen) {
        if seen.other_function
            || nc.st.modal.drill != gcode::Drill::Off
            || nc.st.data.mode != nc::exec::data_setting::Mode::Off
        {
            return;
        }
        if let Some((letter, why)) = self.angle_or_g76(nc, seen) {
            self.ignored(unit, ws, letter, why);
        }
        // (Masks, not letter by letter: this runs for every block.)
        let written = |mask: u32| seen.written & mask != 0;
        let f = written(const { letters(b"F") });
        if f && g76_second_block(seen) {
            self.ignored(unit, ws, 'I', I_BESIDE_F);
        }
        if seen.one_shot() {
            return;
        }
        let motion = nc.st.modal.motion;
        let g92 = matches!(motion, Motion::ThreadCycle | Motion::RigidThreadCycle);
        if g92 && !nc.machine.threads.repair_enabled {
            self.ignored(
                unit,
                ws,
                'P',
                "thread repair is off on this machine (№174.4)",
            );
        }
        let run = g92 || matches!(motion, Motion::TurningCycle | Motion::FacingCycle);
        if run && !written(const { letters(b"XZUW") }) {
            // R (and G92's L) are values of the run (cycles.md §4).
            let kept = if g92 { "RL" } else { "R" };
            for letter in kept.chars() {
                let why = format!("a block without X, U, Z or W does not run the cycle, and its {letter} is not kept for the next block");
                self.ignored(unit, ws, letter, &why);
            }
        }
        // F or I (threads per inch) is the lead, F when both are written
        // (`exec::cycles::lead::written`); the arc threads' I is a centre.
        let by_lead =
            motion.is_thread() && !matches!(motion, Motion::ArcThreadCw | Motion::ArcThreadCcw);
        if by_lead && f {
            self.ignored(unit, ws, 'I', I_BESIDE_F);
        }
    }

    /// The word a form of angle programming or of G76 ignores: Q of
    /// `X_ Z_ Q_` without the `Q_` block before it (and the state of that
    /// pair, kept block by block), P of the one-block G76.
    fn angle_or_g76(&mut self, nc: &Nc, seen: &Seen) -> Option<(char, &'static str)> {
        let written = |mask: u32| seen.written & mask != 0;
        const AXES: u32 = letters(b"XZUW");
        let straight = !seen.one_shot() && nc.st.modal.motion.is_straight();
        let q = written(const { letters(b"Q") });
        let x_and_z = written(const { letters(b"X") }) && written(const { letters(b"Z") });
        let first = std::mem::replace(&mut self.angle_first, false);
        if straight && q && !written(AXES) {
            self.angle_first = true;
        } else if !q && !written(AXES) {
            self.angle_first = first;
        }
        if straight && q && x_and_z && !first {
            let why = "X, Z and Q end angle programming, but no Q_ block began it: the block is an ordinary line";
            return Some(('Q', why));
        }
        let g76 =
            seen.is(OneShot::MultiThread) && written(AXES) && written(const { letters(b"KD") });
        g76.then_some((
            'P',
            "the one-block G76 takes its cutting method from the modal G76 state",
        ))
    }

    /// W104 at the block's word of `letter`, if it has one.
    #[cold]
    #[inline(never)]
    fn ignored(&mut self, unit: usize, ws: &[grammar::ast::Word], letter: char, why: &str) {
        if let Some(w) = find(ws, letter as u8 - b'A') {
            let msg = format!("{letter} is ignored: {why}");
            self.warn(unit, "W104", w.span, msg);
        }
    }

    /// W104: a letter that neither the block's function ([`Owner`]: its
    /// group-00 code, else the drilling cycle in force, else its motion)
    /// nor any block uses (dialect.md §1.8): `G01 Z-20 R2` (a Fanuc corner
    /// R; here D), `G00 X20 I1`, `G04 X1 Z5`, `G83 … L2` (a mill's
    /// repeats; here K). Blocks whose letters belong to another function
    /// are left alone: G22's limits, a call's arguments (G65, G66, a
    /// G-code macro), the G10 modes, and a block whose G or M is computed.
    fn unused_words(&mut self, unit: usize, nc: &Nc, ws: &[grammar::ast::Word], seen: &Seen) {
        // Every owner but a group-00 code uses the letters any block may
        // carry ([`Owner::letters`]): a block of those alone, as most
        // moves are, has none unused.
        if !seen.one_shot() && seen.written & LETTERS & !ANY_BLOCK == 0 {
            return;
        }
        let owner = Owner::of(nc, seen);
        let mut allowed = owner.letters(nc, seen);
        if seen.m98 {
            allowed |= const { letters(b"PL") };
        }
        if seen.m99 {
            allowed |= const { letters(b"P") };
        }
        if seen.written & LETTERS & !allowed == 0
            || seen.stroke_on
            || seen.other_function
            || nc.st.data.mode != nc::exec::data_setting::Mode::Off
        {
            return;
        }
        let code = owner.name(seen);
        for w in ws {
            let a = addr_code(w.addr);
            if LETTERS & !allowed & bit(a) == 0 {
                continue;
            }
            let why = match (owner, w.addr) {
                (Owner::Motion(Motion::Line), Addr::Letter('R')) => {
                    "does not use it: a rounding is D (or ,R)"
                }
                (Owner::Motion(Motion::Line), Addr::Letter('I' | 'K')) => {
                    "does not use it: a chamfer is L (or ,C)"
                }
                (
                    Owner::Motion(Motion::TurningCycle | Motion::FacingCycle),
                    Addr::Letter('I' | 'K'),
                ) => "does not use it: a taper is R (the Fanuc A system's word)",
                (Owner::Motion(_), Addr::Letter('I' | 'J' | 'K')) if by_radius(owner, seen) => {
                    "takes its radius from R"
                }
                _ => "does not use it",
            };
            let msg = format!("{} is ignored: {code} {why}", w.addr);
            self.warn(unit, "W104", w.span, msg);
        }
    }

    /// W104: during polar (cylindrical) interpolation an arc, an ellipse
    /// or a parabola ignores the axis outside the plane, Z (X), as seed
    /// 000 says; G00/G01 move it.
    fn outside_plane(&mut self, unit: usize, nc: &Nc, ws: &[grammar::ast::Word], seen: &Seen) {
        let Some(plane) = nc.st.plane else {
            return;
        };
        let motion = nc.st.modal.motion;
        if seen.one_shot() || !(motion.is_arc() || motion.is_conic()) {
            return;
        }
        let (letters, what) = match plane.kind {
            PlaneKind::Polar => (*b"ZW", "polar interpolation (G12.1)"),
            PlaneKind::Cylinder(_) => (*b"XU", "cylindrical interpolation (G7.1)"),
        };
        for letter in letters {
            if let Some(w) = find(ws, letter - b'A') {
                let msg = format!(
                    "{} is ignored: a curve during {what} stays in the plane; move {} with a G00 or G01",
                    w.addr, letters[0] as char
                );
                self.warn(unit, "W104", w.span, msg);
            }
        }
    }

    /// W105: in calculator mode a G20 length written without a point and
    /// ≥ 100 is probably an increment count (§1.9). Lengths: X Z U W R I
    /// K (not X/U of a G04, which are seconds; not I of a thread, which is
    /// threads per inch).
    fn inch_lengths(&mut self, unit: usize, nc: &Nc, ws: &[grammar::ast::Word], seen: &Seen) {
        if !nc.st.inch() || nc.machine.machine.decimal_point != DecimalPoint::Calculator {
            return;
        }
        let dwell = seen.is(OneShot::Dwell);
        let motion = nc.st.modal.motion;
        let thread = motion.is_thread() && motion != Motion::RigidThreadCycle;
        for w in ws {
            let Addr::Letter(c) = w.addr else { continue };
            let length = match c {
                'Z' | 'W' | 'R' | 'K' => true,
                'X' | 'U' => !dwell,
                'I' => !thread,
                _ => false,
            };
            let WordValue::Literal(v, flags) = value_of(w) else {
                continue;
            };
            if length && flags & NO_POINT != 0 && v.abs() >= 100.0 {
                self.warn(
                    unit,
                    "W105",
                    w.span,
                    format!(
                        "{c}{v} without a decimal point is {v} inches here (G20, calculator mode); did you mean increments ({c}{})?",
                        v / 10_000.0
                    ),
                );
            }
        }
    }

    /// W111: G98/G99 changed the feed mode and the block gave no F, so the
    /// old number is read in the new unit; said at the mode change when a
    /// feed move uses it; not when that move runs at an F of its own (a
    /// G70 profile block's: its F stays in force after the cycle).
    fn feed_mode(
        &mut self,
        unit: usize,
        nc: &Nc,
        seen: &Seen,
        span: Span,
        counts: &Counts,
        before: &Before,
    ) {
        if seen.has(b'F') {
            // A new F: no old number is read in the new mode.
            self.mode_change = None;
            return;
        }
        if nc.st.per_rev() != before.per_rev && before.feed != 0.0 {
            self.mode_change = Some((unit, span, before.feed));
        }
        if counts.feeds == 0 {
            return;
        }
        if let Some((u, at, f)) = self.mode_change.take() {
            // (A G70 profile block that brings an F of its own: no.)
            if counts.first_f.is_some_and(|used| used != f) {
                return;
            }
            let (now, was) = match nc.st.per_rev() {
                true => ("mm/rev (G99)", "mm/min"),
                false => ("mm/min (G98)", "mm/rev"),
            };
            self.warn(
                u,
                "W111",
                at,
                format!(
                    "the feed mode changes to {now} without a new F: the F{} given in {was} is now read in {now}",
                    nc::event::Num(f)
                ),
            );
        }
    }

    /// W125: a feed move in G98 at an F below 1 (mm/min, or in/min in
    /// G20): such an F is a feed per revolution, written for a control
    /// that powers on in G99; here the move crawls. Said once, at the F
    /// word of the first feed move that runs so (the block when no F word
    /// is known).
    fn slow_feed(
        &mut self,
        unit: usize,
        nc: &Nc,
        block: (&[grammar::ast::Word], &Seen, Span),
        counts: &Counts,
    ) {
        let (ws, seen, span) = block;
        // (On a thread F is the lead.)
        if let (Some(f), 0) = (f_word(ws, seen), counts.threads) {
            self.feed_word = Some((unit, f.span));
        }
        let f = nc.st.feed;
        if counts.feeds == 0 || nc.st.per_rev() || !(f > 0.0 && f < SLOW_FEED) {
            return;
        }
        if std::mem::replace(&mut self.slow_feed_told, true) {
            return;
        }
        let (u, at) = self.feed_word.unwrap_or((unit, span));
        let unit_name = if nc.st.inch() { "in/min" } else { "mm/min" };
        // The F word may stand in a G99 block: the message names the
        // mode of the moves, not of the word.
        let msg = format!(
            "F{f} is read as {f} {unit_name} where the feed moves run in G98 (feed per minute): they crawl; is it a feed per revolution?",
            f = nc::event::Num(f)
        );
        let help = "this control powers on in G98 (feed per minute), where many Fanuc lathes start in G99: if the F is per revolution, write G99 at the program's start; else give the feed in per-minute units";
        self.warn_help((u, at), "W125", msg, help.into());
    }

    /// W108: an arc with R, an ellipse or a parabola whose end is its
    /// start: no move, nothing printed (§4.1).
    fn no_motion(&mut self, unit: usize, nc: &Nc, seen: &Seen, span: Span, before: &Before) {
        if seen.one_shot() || nc.st.modal.drill().is_some() || seen.stroke_on {
            return;
        }
        let what = match nc.st.modal.motion {
            Motion::ArcCw | Motion::ArcCcw if seen.has(b'R') => "arc",
            Motion::EllipseCw | Motion::EllipseCcw if seen.has(b'A') || seen.has(b'B') => "ellipse",
            Motion::ParabolaCw | Motion::ParabolaCcw if seen.has(b'P') => "parabola",
            _ => return,
        };
        // (Both coordinates within 1e-9 first: the distance is only
        // computed for a block that may not have moved.)
        let (now, was) = (path_point(nc), before.pos);
        let near = (now.r - was.r).abs() < 1e-9 && (now.z - was.z).abs() < 1e-9;
        if near && now.dist(was) < 1e-9 {
            self.warn(
                unit,
                "W108",
                span,
                format!("this {what} ends where it starts: it makes no move and nothing is cut"),
            );
        }
    }

    /// W112: a corner word (L, D, ,C, ,R) whose element was printed without
    /// its corner: the next move goes the same way, is not G01–G03, or a
    /// group-00 code came first (§5.1).
    fn corners(
        &mut self,
        unit: usize,
        nc: &Nc,
        ws: &[grammar::ast::Word],
        seen: &Seen,
        counts: &Counts,
        before: &Before,
    ) {
        // The waiting element was printed by this block (with or without
        // its corner) when the block printed anything at all.
        if counts.events > 0 {
            if let Some((u, at, applied)) = self.corner.take() {
                if nc.st.contour.applied == applied {
                    self.warn(
                        u,
                        "W112",
                        at,
                        "this chamfer or rounding is ignored: the next move goes the same way, is not G01–G03, or a group-00 code comes first".into(),
                    );
                }
            }
        }
        let motion = nc.st.modal.motion;
        if !matches!(motion, Motion::Line | Motion::ArcCw | Motion::ArcCcw)
            || seen.one_shot()
            || nc.st.modal.drill().is_some()
        {
            return;
        }
        const CORNER_WORDS: u32 = letters(b"LD") | 1 << COMMA_C | 1 << COMMA_R;
        if seen.written & CORNER_WORDS == 0 {
            return;
        }
        let l = find(ws, b'L' - b'A').filter(|_| !seen.m98);
        let word = l
            .or(find(ws, nc::words::COMMA_C))
            .or(find(ws, b'D' - b'A'))
            .or(find(ws, nc::words::COMMA_R));
        if let Some(w) = word {
            self.corner = Some((unit, w.span, before.applied.max(nc.st.contour.applied)));
        }
    }

    /// W114: a literal S above the spindle maximum in G97 (the runtime
    /// clamps it, §6.2); not the G50 S limit, not a G96 surface speed, not
    /// a gear code.
    fn spindle_max(&mut self, unit: usize, nc: &Nc, ws: &[grammar::ast::Word], seen: &Seen) {
        let m = &nc.machine.spindle;
        if !seen.written(b'S' - b'A')
            || m.r#type != SpindleType::Analog
            || nc.st.css_mode()
            || seen.is(OneShot::SetCoordinates)
        {
            return;
        }
        let Some(w) = find(ws, b'S' - b'A') else {
            return;
        };
        if let WordValue::Literal(s, _) = value_of(w) {
            if s > m.max_rpm {
                self.warn(
                    unit,
                    "W114",
                    w.span,
                    format!(
                        "S{} is above the spindle maximum of {} rpm: the spindle turns at {} rpm",
                        nc::event::Num(s),
                        nc::event::Num(m.max_rpm),
                        nc::event::Num(m.max_rpm)
                    ),
                );
            }
        }
    }
}

/// Why I is ignored beside F (`exec::cycles::lead::written`).
const I_BESIDE_F: &str = "F gives the lead; I (threads per inch) counts only in a block without F";

/// Whether the block is the second block of the two-block G76 (axis words,
/// no K or D): its I is threads per inch, where the one-block K/D form's I
/// is the taper (`exec::cycles::multi::g76`).
fn g76_second_block(seen: &Seen) -> bool {
    let written = |mask: u32| seen.written & mask != 0;
    seen.is(OneShot::MultiThread)
        && written(const { letters(b"XZUW") })
        && !written(const { letters(b"KD") })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_sort_events() {
        let mut c = Counts::default();
        c.emit(Event::Line {
            x: 1.0,
            z: 0.0,
            c: None,
        });
        c.emit(Event::Rapid {
            x: 1.0,
            z: 0.0,
            c: None,
        });
        c.emit(Event::M(8));
        assert_eq!((c.events, c.motions, c.feeds, c.threads), (3, 2, 1, 0));
    }

    /// [`Seen::note`] passes these values by without decoding them: each
    /// must be a motion, of which it notes nothing (not a group-00 code,
    /// G22, G66 or a code outside the dialect).
    #[test]
    fn plain_motions_are_motions() {
        for v in PLAIN_MOTIONS {
            let g = gcode::G::from_code(crate::words::round_g(v));
            assert!(matches!(g, Some(gcode::G::Motion(_))), "G{v}: {g:?}");
        }
    }
}
