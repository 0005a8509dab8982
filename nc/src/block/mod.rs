//! Checking one block's words: which G and M codes it holds, which other
//! addresses, and the rules that need no machine state (dialect.md §1.7,
//! §1.9, §3, §4.13, §6). The compiler runs these checks on literal blocks,
//! the kernel on every block it executes.

pub mod value;

use alloc::format;
use alloc::string::String;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::gcode::{self, Code, Drill, Motion, OneShot, Plane, SpeedMode, G};
use crate::base::machine::{Machine, SpindleType};
use crate::base::mcode::{Class, M};
use crate::base::words::{addr, addr_name, Word, ADDR_COUNT, COMMA_A, COMMA_C, COMMA_R};

/// At most this many G words fit a block (one per modal group).
const MAX_G: usize = 16;

/// The words of a block sorted by kind. The kernel parses every block it
/// runs into one of these, so it is kept small and is filled in place
/// ([`parse_into`]): only the presence mask says which values hold.
#[derive(Debug, Clone)]
pub struct Parsed {
    /// G codes in written order, typed as they are added: the kernel reads
    /// them several times per block.
    g: [G; MAX_G],
    g_len: usize,
    /// The block's one-shot (group 00) code and its last group-01 code,
    /// noted as the G codes are added: the kernel asks for them many
    /// times per block.
    one_shot: Option<OneShot>,
    motion: Option<Motion>,
    /// M codes in written order, typed.
    m: [M; 3],
    m_len: usize,
    /// Bit `a`: address `a` (every one but G and M) is written.
    present: u32,
    /// The value (program units) and flags of each written address.
    value: [f64; ADDR_COUNT],
    flags: [u8; ADDR_COUNT],
}

impl Default for Parsed {
    fn default() -> Parsed {
        Parsed {
            // (A filler: only the first `g_len` codes count.)
            g: [G::Motion(Motion::Rapid); MAX_G],
            g_len: 0,
            one_shot: None,
            motion: None,
            m: [M::Stop; 3],
            m_len: 0,
            present: 0,
            value: [0.0; ADDR_COUNT],
            flags: [0; ADDR_COUNT],
        }
    }
}

impl Parsed {
    /// The block's G codes, typed, in written order.
    #[inline]
    pub fn gs(&self) -> impl DoubleEndedIterator<Item = G> + '_ {
        self.g[..self.g_len].iter().copied()
    }

    #[inline]
    pub fn ms(&self) -> &[M] {
        &self.m[..self.m_len]
    }

    #[inline]
    pub fn has_g(&self, g: impl Into<G>) -> bool {
        let g = g.into();
        self.g[..self.g_len].contains(&g)
    }

    #[inline]
    pub fn has_m(&self, m: M) -> bool {
        self.ms().contains(&m)
    }

    /// M02 or M30 ends the program in this block.
    #[inline]
    pub fn ends_program(&self) -> bool {
        self.ms().iter().any(|m| m.ends_program())
    }

    /// The value of a letter address.
    pub fn get(&self, letter: u8) -> Option<f64> {
        self.has(letter).then(|| self.value[addr(letter) as usize])
    }

    pub fn word(&self, letter: u8) -> Option<Word> {
        self.word_at(addr(letter))
    }

    /// The word of address number `a` (letters and comma words).
    pub fn word_at(&self, a: u8) -> Option<Word> {
        self.has_at(a).then(|| Word {
            addr: a,
            value: self.value[a as usize],
            flags: self.flags[a as usize],
        })
    }

    pub fn has(&self, letter: u8) -> bool {
        self.has_at(addr(letter))
    }

    /// E1010 or E5010 for the letter's value out of range, as it was
    /// written or computed (`Alarm::out_of_range`).
    pub fn range_alarm(&self, letter: u8) -> Alarm {
        Alarm::out_of_range(self.flags[addr(letter) as usize])
    }

    pub fn has_at(&self, a: u8) -> bool {
        (a as usize) < ADDR_COUNT && self.present & (1 << a) != 0
    }

    /// Whether any of the addresses in the mask `bits` is written.
    fn has_any(&self, bits: u32) -> bool {
        self.present & bits != 0
    }

    /// The group-00 code of the block, if any.
    pub fn one_shot(&self) -> Option<OneShot> {
        self.one_shot
    }

    /// The last group-01 code written in the block.
    pub fn motion(&self) -> Option<Motion> {
        self.motion
    }

    /// Takes the block's G codes out (its other words stay).
    pub fn clear_gs(&mut self) {
        self.g_len = 0;
        self.one_shot = None;
        self.motion = None;
    }

    pub fn has_axis(&self) -> bool {
        self.has_any(mask(b"XZUW"))
    }

    /// Whether a corner word (L, D, `,C`, `,R`) is written: most blocks
    /// have none, and this is one test.
    pub fn has_corner_word(&self) -> bool {
        self.has_any(mask(b"LD") | 1 << COMMA_C | 1 << COMMA_R)
    }

    /// A plain move: axis words, perhaps F, N and an arc's R or I/K, and
    /// at most a G00–G03 (the usual block of CAM output).
    pub fn is_plain_move(&self) -> bool {
        self.present & !mask(b"XZUWFNRIK") == 0
            && self.has_axis()
            && self.m_len == 0
            && self.g_len == usize::from(self.motion.is_some())
            && matches!(
                self.motion,
                None | Some(Motion::Rapid | Motion::Line | Motion::ArcCw | Motion::ArcCcw)
            )
    }
}

/// Rounds half away from zero, as every integer address does (§7.6).
#[inline]
pub fn round_half_away(v: f64) -> f64 {
    if v < 0.0 {
        -crate::base::geom::floor_non_negative((-v) + 0.5)
    } else {
        crate::base::geom::floor_non_negative(v + 0.5)
    }
}

/// The presence bits of some letters.
const fn mask(letters: &[u8]) -> u32 {
    let mut bits = 0;
    let mut i = 0;
    while i < letters.len() {
        bits |= 1 << addr(letters[i]);
        i += 1;
    }
    bits
}

/// Sorts the words of a block and checks what needs no state.
pub fn parse(words: &[Word], m: &Machine) -> Result<Parsed, NcError> {
    let mut p = Parsed::default();
    parse_into(words, m, &mut p)?;
    Ok(p)
}

/// [`parse`] into `p`, whatever it held before.
pub fn parse_into(words: &[Word], m: &Machine, p: &mut Parsed) -> Result<(), NcError> {
    p.clear_gs();
    p.m_len = 0;
    p.present = 0;
    for (i, w) in words.iter().enumerate() {
        add_word(p, w).map_err(|e| e.on_word(i))?;
    }
    check_words(p, m, words).map_err(|e| on_its_word(e, words))
}

/// One word of `parse_into`.
fn add_word(p: &mut Parsed, w: &Word) -> Result<(), NcError> {
    match w.addr {
        a if a == addr(b'G') => add_g(p, w),
        a if a == addr(b'M') => add_m(p, w),
        a if (a as usize) < ADDR_COUNT => {
            if p.has_at(a) {
                return fail(
                    Alarm::AddressRepeated,
                    format!("address {} written twice in the block", addr_name(a)),
                );
            }
            p.present |= 1 << a;
            p.value[a as usize] = w.value;
            p.flags[a as usize] = w.flags;
            Ok(())
        }
        a => fail(Alarm::UnknownAddress, format!("unknown address number {a}")),
    }
}

/// The addresses a plain move may write besides its G code
/// ([`Parsed::is_plain_move`]).
const MOVE_WORDS: u32 = mask(b"XZUWFNRIK");

/// The motion of a G word whose value is exactly 0, 1, 2 or 3 (G00–G03),
/// the G code of a plain move; `None` for any other value, which the
/// general parse decodes (and rounds).
pub fn written_motion(value: f64) -> Option<Motion> {
    Some(match value {
        0.0 => Motion::Rapid,
        1.0 => Motion::Line,
        2.0 => Motion::ArcCw,
        3.0 => Motion::ArcCcw,
        _ => return None,
    })
}

/// [`parse_into`] for the words of a plain move whose G code, if any, is
/// written as G00–G03 exactly (what the compiler types as `move`): the
/// same result, without decoding a G code in general or the rules that
/// no such block can break. Any other block is handed to `parse_into`,
/// so the result never depends on the words being of that shape.
pub fn parse_move(words: &[Word], m: &Machine, p: &mut Parsed) -> Result<(), NcError> {
    p.clear_gs();
    p.m_len = 0;
    p.present = 0;
    for w in words {
        let a = w.addr;
        if a == addr(b'G') {
            let Some(motion) = written_motion(w.value) else {
                return parse_into(words, m, p);
            };
            if p.g_len != 0 {
                return parse_into(words, m, p);
            }
            p.g[0] = G::Motion(motion);
            p.g_len = 1;
            p.motion = Some(motion);
        } else if a < 32 && MOVE_WORDS & 1 << a != 0 && !p.has_at(a) {
            p.present |= 1 << a;
            p.value[a as usize] = w.value;
            p.flags[a as usize] = w.flags;
        } else {
            return parse_into(words, m, p);
        }
    }
    // `check_words` for these words: the integer-only rule and the C, H,
    // Y, comma-word, M-code and foreign rules have nothing to look at.
    check_sign(p, b'F')
        .and_then(|()| check_end_point(p))
        .map_err(|e| on_its_word(e, words))
}

/// An error of a rule about one address (or a pair) names that
/// address's word by its index (the compiler points at it).
fn on_its_word(e: NcError, words: &[Word]) -> NcError {
    match e.word_among(words.iter().map(|w| w.addr)) {
        Some(i) => e.on_word(i),
        None => e,
    }
}

fn add_g(p: &mut Parsed, w: &Word) -> Result<(), NcError> {
    // Rounded to one decimal first (§7.6): −0.04 is G−0.0, G00.
    let tenths = round_half_away(w.value * 10.0);
    if !(0.0..=99990.0).contains(&tenths) {
        return fail(
            Alarm::UnknownGCode,
            format!("G{} is not a G code", crate::base::event::Num(w.value)),
        );
    }
    let code = tenths as Code;
    if let Some((err, hint)) = gcode::foreign(code) {
        return fail(
            err,
            format!("{} is not in this dialect: {hint}", gcode::name(code)),
        );
    }
    let Some(g) = G::from_code(code) else {
        // A computed G1.25 is named as it is, not as the G1.3 it rounds to.
        let shown = match f64::from(code) / 10.0 == w.value {
            true => gcode::name(code),
            false => format!("G{}", crate::base::event::Num(w.value)),
        };
        return fail(Alarm::UnknownGCode, format!("unknown G code {shown}"));
    };
    if let (G::OneShot(_), Some(other)) = (g, p.one_shot()) {
        return fail(
            Alarm::OneShotConflict,
            format!(
                "{} and {} are both one-shot (group 00) codes: write them in separate blocks",
                gcode::name(other.code()),
                gcode::name(code)
            ),
        );
    }
    if p.g_len == MAX_G {
        return fail(Alarm::AddressRepeated, "too many G codes in one block");
    }
    p.g[p.g_len] = g;
    p.g_len += 1;
    match g {
        G::OneShot(c) => p.one_shot = Some(c),
        G::Motion(c) => p.motion = Some(c),
        _ => {}
    }
    Ok(())
}

fn add_m(p: &mut Parsed, w: &Word) -> Result<(), NcError> {
    if w.literal_with_point() {
        return fail(
            Alarm::DecimalPointNotAllowed,
            format!(
                "M{}: an M code is a whole number; a decimal point is not allowed",
                crate::base::event::Num(w.value)
            ),
        );
    }
    let code = round_half_away(w.value);
    if !(0.0..=9999.0).contains(&code) {
        return fail(
            Alarm::out_of_range(w.flags),
            format!(
                "M{} is out of range (M0…M9999)",
                crate::base::event::Num(w.value)
            ),
        );
    }
    if p.m_len == 3 {
        return fail(Alarm::TooManyMCodes, "more than three M codes in one block");
    }
    // (0…9999: the range checked above.)
    p.m[p.m_len] = M::from_code(code as u16);
    p.m_len += 1;
    Ok(())
}

/// Addresses that only take integers (§1.9), by the block's function.
fn integer_only(p: &Parsed, letter: u8) -> bool {
    match letter {
        // Every use of P and Q is a count, a number or 0.001 units (§1.9).
        b'T' | b'H' | b'O' | b'N' | b'P' | b'Q' => true,
        // L is a count except as the chamfer of G01–G03.
        b'L' => {
            p.has_m(M::SubCall)
                || p.has_g(OneShot::SpiralThread)
                || [
                    Motion::Tapping,
                    Motion::ThreadCycle,
                    Motion::RigidThreadCycle,
                ]
                .iter()
                .any(|&c| p.has_g(c))
        }
        // G78 D (finishing passes) and the drilling repeats K are counts.
        b'D' => p.has_g(OneShot::SpiralThread),
        b'K' => p.gs().any(|g| matches!(g, G::Drill(d) if d != Drill::Off)),
        _ => false,
    }
}

/// Words given in increments (§1.9): the unit they count, and how many
/// make a whole one (`Q3.` for 3 mm: Q3000). Depths and steps count
/// 0.001 mm (0.0001 in under G20, which the block may not show), angles
/// 0.001°. G76/G78's first block P is digits (`mmrraa`), their second
/// block's (with X/U or Z/W) the thread height k.
fn increments(p: &Parsed, letter: u8) -> Option<Increment> {
    let shot = p.one_shot();
    let second_block = || [b'X', b'U', b'Z', b'W'].iter().any(|&a| p.has(a));
    let threading = matches!(shot, Some(OneShot::MultiThread | OneShot::SpiralThread));
    let pecking = matches!(shot, Some(OneShot::PeckFace | OneShot::PeckGroove));
    let drilling = p
        .gs()
        .any(|g| matches!(g, G::Drill(Drill::FaceDrill | Drill::SideDrill)));
    let angled = p.gs().any(|g| {
        matches!(
            g,
            G::Motion(
                Motion::Rapid
                    | Motion::Line
                    | Motion::EllipseCw
                    | Motion::EllipseCcw
                    | Motion::ParabolaCw
                    | Motion::ParabolaCcw
                    | Motion::Thread
                    | Motion::ArcThreadCw
                    | Motion::ArcThreadCcw
            )
        )
    });
    let parabola = p
        .gs()
        .any(|g| matches!(g, G::Motion(Motion::ParabolaCw | Motion::ParabolaCcw)));
    match letter {
        b'Q' if threading || pecking || drilling => Some(Increment::Length),
        b'Q' if angled => Some(Increment::Angle),
        b'P' if pecking || parabola || (threading && second_block()) => Some(Increment::Length),
        _ => None,
    }
}

/// The least input increment a word counts (§0).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Increment {
    /// 0.001 mm (0.0001 in).
    Length,
    /// 0.001°.
    Angle,
}

/// What to write for an integer-only word given with a point: the same
/// whole number without it (a fraction names none). A dwell's P is in ms:
/// a point there most often means seconds (`P1.5` for 1.5 s: P1500, or
/// G04's X).
fn integer_hint(p: &Parsed, letter: u8, value: f64) -> String {
    use crate::base::event::Num;
    let (l, n) = (letter as char, Num(value));
    if l == 'P' && p.one_shot() == Some(OneShot::Dwell) {
        let ms = Num(value * 1000.0);
        return format!("the dwell's P is in ms: for {n} s write P{ms}, or X{n}");
    }
    // A point on a word in increments most often means the whole unit:
    // `Q3.` for 3 mm is Q3000 (dialect.md §4.13).
    let thousand = Num(value * 1000.0);
    match increments(p, letter) {
        Some(Increment::Length) => {
            return format!("{l} counts 0.001 mm: for {n} mm write {l}{thousand}");
        }
        Some(Increment::Angle) => {
            return format!("{l} counts 0.001°: for {n}° write {l}{thousand}");
        }
        None => {}
    }
    let letter = l;
    match value == libm::trunc(value) {
        true => format!("write {letter}{n}"),
        false => format!("write a whole number of {letter}'s unit"),
    }
}

/// F < 0 is the left-hand lead of G32.1, G92.1, G84 and G88. A block that
/// names another function (group 00, 01 or 10) cannot use it; a block that
/// names none runs the modal function, which the kernel checks
/// (`cycles::before_block`).
fn negative_f_allowed(p: &Parsed) -> bool {
    let left_hand = |g: G| match g {
        G::Motion(m) => matches!(m, Motion::RigidThread | Motion::RigidThreadCycle),
        G::Drill(d) => d.taps(),
        _ => false,
    };
    if p.gs().any(left_hand) {
        return true;
    }
    !p.gs()
        .any(|g| matches!(g, G::OneShot(_) | G::Motion(_) | G::Drill(_)))
}

fn check_words(p: &Parsed, m: &Machine, words: &[Word]) -> Result<(), NcError> {
    // Most blocks are moves: no integer-only, sign-checked or exclusive
    // address at all (the rules below would all pass).
    const CHECKED: u32 = mask(b"TPLQHDKFSUWYVC") | 1 << COMMA_A | 1 << COMMA_C | 1 << COMMA_R;
    if !p.has_any(CHECKED) {
        return check_m_codes(p, words).and_then(|()| check_codes(p, m));
    }
    for letter in [b'T', b'P', b'L', b'Q', b'H', b'D', b'K'] {
        // With a C axis, H is the incremental C angle (decimals allowed).
        if letter == b'H' && m.axes.c.enabled {
            continue;
        }
        if let Some(w) = p.word(letter) {
            if w.literal_with_point() && integer_only(p, letter) {
                let msg = format!(
                    "{} takes an integer here; a decimal point is not allowed ({})",
                    letter as char,
                    integer_hint(p, letter, w.value)
                );
                let e = NcError::new(Alarm::DecimalPointNotAllowed, msg);
                return Err(e.on_addr(addr(letter)));
            }
        }
    }
    for letter in [b'F', b'S'] {
        check_sign(p, letter)?;
    }
    check_ranges(p)?;
    check_end_point(p)?;
    check_axes(p, m)?;
    check_pairs(p)?;
    check_m_codes(p, words)?;
    check_codes(p, m)
}

/// E2005 for a word of an axis the machine lacks, naming that word (Y
/// when the block holds both Y and V).
fn check_axes(p: &Parsed, m: &Machine) -> Result<(), NcError> {
    if p.has(b'Y') || p.has(b'V') {
        let y = if p.has(b'Y') { b'Y' } else { b'V' };
        let e = NcError::new(Alarm::AxisNotConfigured, "this machine has no Y axis");
        return Err(e.on_addr(addr(y)));
    }
    if !m.axes.c.enabled
        && p.has(b'C')
        && p.one_shot().is_none()
        && p.motion() != Some(Motion::RigidThread)
    {
        let e = NcError::new(Alarm::AxisNotConfigured, "this machine has no C axis");
        return Err(e.on_addr(addr(b'C')));
    }
    // Outside G65 (which never reaches the kernel) H is the incremental C
    // angle, in a move as in a drilling cycle.
    if !m.axes.c.enabled && p.has(b'H') {
        let msg = "this machine has no C axis (H is the incremental C angle)";
        return Err(NcError::new(Alarm::AxisNotConfigured, msg).on_addr(addr(b'H')));
    }
    Ok(())
}

/// E2007 for two words that give the same thing, naming the later one.
fn check_pairs(p: &Parsed) -> Result<(), NcError> {
    let pairs = [
        (
            COMMA_A,
            b'Q',
            "Q and ,A both give the angle: write one of them",
        ),
        (
            COMMA_C,
            b'L',
            "L and ,C both give the chamfer: write one of them",
        ),
        (
            COMMA_R,
            b'D',
            "D and ,R both give the corner radius: write one of them",
        ),
    ];
    for (comma, letter, msg) in pairs {
        if p.has_at(comma) && p.has(letter) {
            let e = NcError::new(Alarm::IncompatibleWords, msg);
            return Err(e.on_pair(comma, addr(letter)));
        }
    }
    Ok(())
}

/// F and S are not negative (but F of a left-hand tap, or of a block
/// without a code that feeds).
#[inline]
fn check_sign(p: &Parsed, letter: u8) -> Result<(), NcError> {
    match p.get(letter) {
        Some(v) if v < 0.0 && !(letter == b'F' && negative_f_allowed(p)) => {
            let msg = format!("{} must not be negative", letter as char);
            Err(NcError::new(p.range_alarm(letter), msg).on_addr(addr(letter)))
        }
        _ => Ok(()),
    }
}

/// Numbers that name one of a few things (§1.9, §4.2, §4.4, §4.5): a
/// written one out of range is E1010 here, in every block the compiler
/// sees, reached or not; a computed one E5010.
fn check_ranges(p: &Parsed) -> Result<(), NcError> {
    let out = |letter: u8, lo: f64, hi: f64| {
        p.get(letter)
            .map(round_half_away)
            .filter(|v| !(lo..=hi).contains(v))
    };
    if let Some(t) = out(b'T', 0.0, 9999.0) {
        let msg = format!("T{t} is out of range (T0…T9999)");
        return Err(NcError::new(p.range_alarm(b'T'), msg).on_addr(addr(b'T')));
    }
    let (letter, lo, hi, what) = match p.one_shot() {
        Some(OneShot::HomeN) => (b'P', 2.0, 4.0, "G30 P: the reference points are 2…4"),
        Some(OneShot::Skip) => (b'P', 1.0, 4.0, "G31 P: the skip signals are 1…4"),
        Some(OneShot::Dwell) => (b'Q', 1.0, 4.0, "G04 Q: the skip signals are 1…4"),
        Some(OneShot::MultiThread) => return check_g76_passes(p),
        _ => return Ok(()),
    };
    match out(letter, lo, hi) {
        Some(v) => {
            let msg = format!("{what}, not {v}");
            Err(NcError::new(p.range_alarm(letter), msg).on_addr(addr(letter)))
        }
        None => Ok(()),
    }
}

/// G76's first block (no end point): m of P mmrraa, the finishing
/// passes, is 01…99 (§4.8); with m = 00 the thread would stay d short of
/// its depth.
fn check_g76_passes(p: &Parsed) -> Result<(), NcError> {
    let end_point = [b'X', b'U', b'Z', b'W'].iter().any(|&a| p.has(a));
    let Some(digits) = p.get(b'P').map(round_half_away).filter(|_| !end_point) else {
        return Ok(());
    };
    let m = libm::trunc(digits / 10000.0);
    if (1.0..=99.0).contains(&m) {
        return Ok(());
    }
    let msg = format!(
        "G76 P: m, the finishing passes (mm of the digits mmrraa), is 01…99; P{} gives {}",
        crate::base::event::Num(digits),
        crate::base::event::Num(m)
    );
    Err(NcError::new(p.range_alarm(b'P'), msg).on_addr(addr(b'P')))
}

/// An end point is written absolute or incremental, not both.
#[inline]
fn check_end_point(p: &Parsed) -> Result<(), NcError> {
    // In G04 X and U are both the dwell in seconds and X wins (seed G04
    // note 3), so only moves forbid the pair.
    if p.has(b'X') && p.has(b'U') && p.one_shot() != Some(OneShot::Dwell) {
        let msg = "X and U in one block: write the X end point either absolute or incremental";
        let e = NcError::new(Alarm::IncompatibleWords, msg);
        return Err(e.on_pair(addr(b'X'), addr(b'U')));
    }
    if p.has(b'Z') && p.has(b'W') {
        let msg = "Z and W in one block: write the Z end point either absolute or incremental";
        let e = NcError::new(Alarm::IncompatibleWords, msg);
        return Err(e.on_pair(addr(b'Z'), addr(b'W')));
    }
    Ok(())
}

/// E1012 names the M word that makes the block wrong: the second call,
/// or the later of a call and a stop.
fn check_m_codes(p: &Parsed, words: &[Word]) -> Result<(), NcError> {
    let nth = |class: Class, n: usize| {
        let mut of_class = p
            .ms()
            .iter()
            .enumerate()
            .filter(|(_, m)| m.class() == class);
        of_class.nth(n).map(|(k, _)| k)
    };
    let too_many = |msg: &str, k: usize| {
        let e = NcError::new(Alarm::TooManyMCodes, msg);
        match m_word(words, k) {
            Some(i) => Err(e.on_word(i)),
            None => Err(e),
        }
    };
    if let Some(k) = nth(Class::Call, 1) {
        return too_many("at most one of M98, M99 and M9000…M9999 in a block", k);
    }
    if let (Some(call), Some(stop)) = (nth(Class::Call, 0), nth(Class::ProgramStop, 0)) {
        let msg = "M98/M99 cannot share a block with M00, M01, M02 or M30";
        return too_many(msg, call.max(stop));
    }
    if p.has_m(M::ForeignLocalCall) {
        return fail(
            Alarm::ForeignDialect,
            "M97 is a Haas/Citizen local subprogram call: put the block in an O program and call it with M98",
        );
    }
    Ok(())
}

/// The index among `words` of the block's M word number `k` (0 the
/// first): the block's M codes are kept in written order.
fn m_word(words: &[Word], k: usize) -> Option<usize> {
    let mut ms = words
        .iter()
        .enumerate()
        .filter(|(_, w)| w.addr == addr(b'M'));
    ms.nth(k).map(|(i, _)| i)
}

/// Codes of other dialects, and codes that need equipment the machine
/// lacks (E2003).
fn check_codes(p: &Parsed, m: &Machine) -> Result<(), NcError> {
    // One pass over the G codes; the rules then apply in their order.
    let (mut g92, mut peck, mut plane, mut css) = (false, false, false, false);
    for g in p.gs() {
        match g {
            G::Motion(Motion::ThreadCycle) => g92 = true,
            G::OneShot(OneShot::PeckFace | OneShot::PeckGroove) => peck = true,
            G::Plane(Plane::Xy | Plane::Yz) => plane = true,
            G::SpeedMode(SpeedMode::SurfaceSpeed) => css = true,
            _ => {}
        }
    }
    if g92 && p.has(b'S') && !p.has_axis() {
        return fail(
            Alarm::ForeignDialect,
            "G92 S is the speed clamp of systems B/C: use G50 S",
        );
    }
    if peck && (p.has(b'I') || p.has(b'K')) {
        return fail(
            Alarm::ForeignDialect,
            "GSK pecks are P/Q in 0.001 mm, not Haas I/K words",
        );
    }
    if plane {
        return fail(
            Alarm::MissingEquipment,
            "G17/G19 need a Y axis; this lathe works in the ZX plane (G18)",
        );
    }
    if css && m.spindle.r#type == SpindleType::Gear {
        return fail(
            Alarm::MissingEquipment,
            "G96 needs a spindle whose speed the control sets; this one has gears (S00…S04): turn at a gear with G97",
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::{parse, parse_into, parse_move, round_half_away, Parsed};
    use crate::base::gcode::{self, Code};
    use crate::base::machine::Machine;
    use crate::base::words::{addr, Word, LITERAL, NO_POINT};
    use alloc::format;
    use alloc::vec::Vec;

    /// `parse_move` gives what `parse_into` gives, alarm or parse, on
    /// every block of a G code (none, G00–G03, and codes it hands on)
    /// with every set of the plain move's other addresses, F of both
    /// signs, with and without decimal points; and on blocks it hands on
    /// (a repeated address, a second G, an M, a T).
    #[test]
    fn parse_move_agrees_with_parse_into() {
        let m = Machine::reference();
        let letters = *b"XZUWFNRIK";
        let gs: [Option<f64>; 7] = [
            None,
            Some(0.0),
            Some(1.0),
            Some(2.0),
            Some(3.0),
            Some(4.0),
            Some(1.5),
        ];
        let extras: [&[(u8, f64)]; 5] = [
            &[],
            &[(b'X', 3.0)],
            &[(b'G', 1.0)],
            &[(b'M', 3.0)],
            &[(b'T', 101.0)],
        ];
        let mut compared = 0;
        for g in gs {
            for set in 0u32..1 << letters.len() {
                for (f, flags) in [(-0.2, LITERAL), (100.0, LITERAL | NO_POINT)] {
                    for extra in extras {
                        let mut words: Vec<Word> = Vec::new();
                        let mut push = |letter: u8, value: f64| {
                            words.push(Word {
                                addr: addr(letter),
                                value,
                                flags,
                            });
                        };
                        if let Some(code) = g {
                            push(b'G', code);
                        }
                        for (i, &letter) in letters.iter().enumerate() {
                            if set & 1 << i != 0 {
                                push(letter, if letter == b'F' { f } else { 1.5 + i as f64 });
                            }
                        }
                        for &(letter, value) in extra.iter() {
                            push(letter, value);
                        }
                        let (mut a, mut b) = (Parsed::default(), Parsed::default());
                        let ra = parse_into(&words, &m, &mut a);
                        let rb = parse_move(&words, &m, &mut b);
                        assert_eq!(format!("{ra:?}"), format!("{rb:?}"), "{words:?}");
                        if ra.is_ok() {
                            assert_eq!(format!("{a:?}"), format!("{b:?}"), "{words:?}");
                        }
                        compared += 1;
                    }
                }
            }
        }
        assert_eq!(compared, 7 * 512 * 2 * 5);
    }

    /// The one-shot and motion codes noted while parsing are what a scan
    /// of the block's G codes finds (the first group-00 code, the last
    /// group-01 code), on every block of three G words from a mixed set;
    /// `clear_gs` forgets them.
    #[test]
    fn noted_codes_equal_a_scan_of_the_g_codes() {
        let codes = [
            0.0, 1.0, 2.0, 3.0, 4.0, 9.0, 21.0, 28.0, 32.0, 40.0, 41.0, 50.0, 70.0, 71.0, 90.0,
            92.0, 96.0, 97.0, 98.0, 99.0,
        ];
        let word = |letter: u8, value: f64| Word {
            addr: addr(letter),
            value,
            flags: LITERAL,
        };
        let scan = |p: &super::Parsed, group: u8, last: bool| -> Option<Code> {
            let mut found = p
                .gs()
                .map(|g| g.code())
                .filter(|&c| gcode::group(c) == Some(group));
            if last {
                found.next_back()
            } else {
                found.next()
            }
        };
        let m = Machine::reference();
        let mut parsed = 0;
        for a in codes {
            for b in codes {
                for c in codes {
                    let words = [
                        word(b'G', a),
                        word(b'G', b),
                        word(b'G', c),
                        word(b'X', 10.0),
                    ];
                    let Ok(mut p) = parse(&words, &m) else {
                        continue;
                    };
                    parsed += 1;
                    assert_eq!(
                        p.one_shot().map(|c| c.code()),
                        scan(&p, gcode::ONE_SHOT, false),
                        "G{a} G{b} G{c}"
                    );
                    assert_eq!(
                        p.motion().map(|c| c.code()),
                        scan(&p, gcode::MOTION, true),
                        "G{a} G{b} G{c}"
                    );
                    p.clear_gs();
                    assert!(
                        p.gs().next().is_none() && p.one_shot().is_none() && p.motion().is_none()
                    );
                }
            }
        }
        assert!(parsed > 1000, "only {parsed} blocks parsed");
    }

    /// E1012 names the M word that makes the block wrong (dialect.md
    /// §6.1): the second call, or the later of a call and a stop.
    #[test]
    fn an_m_code_rule_names_the_m_word_at_fault() {
        let m = Machine::reference();
        let w = |letter: u8, value: f64| Word {
            addr: addr(letter),
            value,
            flags: LITERAL | NO_POINT,
        };
        let named = |words: &[Word]| parse(words, &m).err().map(|e| (e.code, e.word));
        let (m98, m99, m30, m02) = (w(b'M', 98.0), w(b'M', 99.0), w(b'M', 30.0), w(b'M', 2.0));
        let (p, x) = (w(b'P', 1.0), w(b'X', 1.0));
        assert_eq!(named(&[m98, p, m99]), Some((1012, Some(2))));
        assert_eq!(named(&[m30, x, m98]), Some((1012, Some(2))));
        assert_eq!(named(&[m98, m02, x]), Some((1012, Some(1))));
    }

    /// The cast-based rounding agrees with `libm::floor` everywhere,
    /// halves away from zero, large values and NaN included.
    #[test]
    fn round_half_away_matches_floor() {
        let reference = |v: f64| {
            if v < 0.0 {
                -libm::floor(-v + 0.5)
            } else {
                libm::floor(v + 0.5)
            }
        };
        let values = [
            0.0,
            0.5,
            1.5,
            2.5,
            2.4999,
            -0.5,
            -1.5,
            -2.4999,
            7.0,
            321.0,
            3209.9999,
            1e15,
            4.5e15,
            4_503_599_627_370_495.5,
            4.6e15,
            1e300,
            -1e300,
        ];
        for v in values {
            assert_eq!(round_half_away(v), reference(v), "{v}");
        }
        assert_eq!(round_half_away(2.5), 3.0);
        assert_eq!(round_half_away(-2.5), -3.0);
        assert!(round_half_away(f64::NAN).is_nan());
        assert_eq!(round_half_away(f64::INFINITY), f64::INFINITY);
    }
}
