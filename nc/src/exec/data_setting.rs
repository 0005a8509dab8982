//! Data setting, dialect.md §4.9: `G10 L3 … G11` (tool-life table) and
//! `G10 L52 … G11` (parameter read and write).
//!
//! The kernel sees every block of these modes before its ordinary
//! execution ([`intercept`]): the blocks inside print nothing, move
//! nothing and leave the modal state alone. Words that the mode does not
//! use are ignored (the compiler warns W104 where it can tell).

use crate::base::gcode::OneShot;
use alloc::format;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::machine::Machine;
use crate::base::words::{addr, Word, LITERAL};
use crate::block::{self, round_half_away, Parsed};
use crate::exec::params;
use crate::exec::tool_life::{LifeUnit, ToolLife};
use crate::exec::{check_tool, Nc, Outcome};

/// Which data-setting mode is open.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Mode {
    #[default]
    Off,
    /// `G10 L3`: tool-life data.
    ToolLife,
    /// `G10 L52`: parameter access.
    Parameters,
}

/// The state of this module in the kernel's `State`.
#[derive(Debug, Clone, PartialEq)]
pub struct DataState {
    pub mode: Mode,
    pub life: ToolLife,
}

impl DataState {
    pub fn power_on(m: &Machine) -> DataState {
        DataState {
            mode: Mode::Off,
            life: ToolLife::power_on(m),
        }
    }
}

/// Is this word `G10` or `G11`?
fn is_g10_or_g11(w: &Word) -> bool {
    // (Only values in [9.95, 11.05) round to G10 or G11: most G words are
    // turned away without rounding.)
    w.addr == addr(b'G')
        && (9.9..11.1).contains(&w.value)
        && matches!(
            OneShot::from_code(round_half_away(w.value * 10.0) as u16),
            Some(OneShot::DataSetting | OneShot::DataSettingEnd)
        )
}

/// Executes the block when it belongs to data setting (a G10 or G11
/// block, or any block while a mode is open): `Some` with its outcome.
/// `None` for every other block, which executes as usual.
pub fn intercept(nc: &mut Nc, words: &[Word]) -> Result<Option<Outcome>, NcError> {
    // The common case costs one scan of the words.
    if nc.st.data.mode == Mode::Off && !words.iter().any(is_g10_or_g11) {
        return Ok(None);
    }
    let p = block::parse(words, &nc.machine)?;
    if p.has_g(OneShot::DataSetting) {
        nc.st.data.mode = open(nc, &p)?;
        return Ok(Some(Outcome::default()));
    }
    if p.has_g(OneShot::DataSettingEnd) {
        // G11 ends either mode; without one it does nothing (W104).
        nc.st.data.mode = Mode::Off;
        return Ok(Some(Outcome::default()));
    }
    match nc.st.data.mode {
        Mode::Off => Ok(None),
        Mode::ToolLife => tool_life_block(nc, &p).map(|()| Some(Outcome::default())),
        Mode::Parameters => parameter_block(nc, &p).map(Some),
    }
}

/// `G10 L3` / `G10 L52`; every other G10 form is another dialect's.
fn open(nc: &mut Nc, p: &Parsed) -> Result<Mode, NcError> {
    match p.get(b'L').map(round_half_away) {
        Some(3.0) => {
            // Running a tool-life program replaces the whole table (seed).
            nc.st.data.life.clear();
            Ok(Mode::ToolLife)
        }
        Some(52.0) => Ok(Mode::Parameters),
        _ => fail(
            Alarm::ForeignDialect,
            "only G10 L3 (tool life) and G10 L52 (parameters) are GSK980TDi data setting; \
             Fanuc G10 offset and work-offset input (G10 P… X… Z…, G10 L2) is not in this dialect",
        ),
    }
}

/// Inside `G10 L3`: `P L [Q]` opens a group, `T` adds a tool to it.
fn tool_life_block(nc: &mut Nc, p: &Parsed) -> Result<(), NcError> {
    if let Some(group) = p.get(b'P') {
        let (number, life, unit) = group_words(group, p)?;
        nc.st.data.life.open(number, life, unit);
    }
    if let Some(t) = p.get(b'T') {
        // (0…9999: the block layer's range, `block::check_ranges`.)
        let t = round_half_away(t) as u32;
        let (tool, offset) = (t / 100, t % 100);
        if matches!(offset, 88 | 99) {
            return fail(
                Alarm::ToolNumber,
                format!("T{t:04}: a tool-life tool needs a real offset number, not {offset}"),
            );
        }
        check_tool(&nc.machine, tool, offset)?;
        // A T before any group opens has nowhere to go: ignored (W104).
        nc.st.data.life.add_tool(t);
    }
    Ok(())
}

/// The group number, life and unit of a `P L [Q]` block.
fn group_words(group: f64, p: &Parsed) -> Result<(u32, f64, LifeUnit), NcError> {
    let number = round_half_away(group);
    if !(1.0..=32.0).contains(&number) {
        return fail(
            p.range_alarm(b'P'),
            format!("P{number}: tool-life groups are 1…32"),
        );
    }
    let Some(life) = p.get(b'L') else {
        return fail(
            Alarm::MissingWord,
            format!("the tool-life group P{number} needs its life L"),
        );
    };
    if life <= 0.0 || !life.is_finite() {
        return fail(
            p.range_alarm(b'L'),
            format!("L{life}: a tool life must be above 0"),
        );
    }
    let unit = match p.get(b'Q').map(round_half_away) {
        None | Some(1.0) => LifeUnit::Count,
        Some(2.0) => LifeUnit::Minutes,
        Some(q) => {
            return fail(
                p.range_alarm(b'Q'),
                format!("Q{q}: a tool life counts uses (Q1) or minutes (Q2)"),
            )
        }
    };
    Ok((number as u32, life, unit))
}

/// Inside `G10 L52`: `N [P] R` reads into a variable, `N [P] W` writes.
fn parameter_block(nc: &mut Nc, p: &Parsed) -> Result<Outcome, NcError> {
    if p.has(b'K') || p.has(b'D') {
        return fail(
            Alarm::NotSupportedYet,
            "PLC parameters (K, D, DT, DC) in G10 L52 are not implemented yet",
        );
    }
    let Some(n) = p.get(b'N') else {
        // No parameter number: nothing to read or write (W104).
        return Ok(Outcome::default());
    };
    let n = parameter_number(n)?;
    let axis = p.get(b'P');
    let mut out = Outcome::default();
    match (p.get(b'R'), p.get(b'W')) {
        (Some(_), Some(_)) => {
            let msg = format!("N{n}: R reads and W writes; write one of them");
            let e = NcError::new(Alarm::IncompatibleWords, msg);
            return Err(e.on_pair(addr(b'R'), addr(b'W')));
        }
        (Some(var), None) => {
            let value = params::read(nc, n, axis).map_err(|e| written_fault(e, p, b"P"))?;
            out.store = Some((variable_number(var)?, value));
        }
        (None, Some(value)) => {
            params::write(nc, n, axis, value).map_err(|e| written_fault(e, p, b"PW"))?
        }
        (None, None) => {
            return fail(
                Alarm::MissingWord,
                format!("N{n} needs R<#variable> to read the parameter or W<value> to write it (a vacant value leaves its word out)"),
            )
        }
    }
    Ok(out)
}

/// A value out of range (E5010) that only written words gave is the
/// literal's fault: E1010, which the compiler reports before the run.
fn written_fault(e: NcError, p: &Parsed, letters: &[u8]) -> NcError {
    let written = |&l: &u8| p.word(l).is_none_or(|w| w.flags & LITERAL != 0);
    if e.code == Alarm::ValueOutOfRange.code() && letters.iter().all(written) {
        NcError {
            code: Alarm::LiteralOutOfRange.code(),
            ..e
        }
    } else {
        e
    }
}

/// A parameter number that machine.md lists, else E7008 (the compiler
/// reports a literal one as E2050 before the program runs).
fn parameter_number(v: f64) -> Result<u32, NcError> {
    let n = round_half_away(v);
    if (0.0..=99999.0).contains(&n) && params::exists(n as u32) {
        return Ok(n as u32);
    }
    fail(
        Alarm::UnknownParameterAtRun,
        format!("there is no parameter №{n} on this machine (machine.md §2)"),
    )
}

/// The R word carries the number of the variable to fill (the compiler
/// lowers `R#100` to 100, not to the value of #100).
fn variable_number(v: f64) -> Result<u32, NcError> {
    let n = round_half_away(v);
    if !(0.0..=u32::MAX as f64).contains(&n) {
        return fail(Alarm::NoSuchVariable, format!("#{n} names no variable"));
    }
    Ok(n as u32)
}

#[cfg(test)]
mod tests {
    use crate::base::machine::Machine;
    use crate::exec::cycles::testing::{words, Lathe};
    use crate::exec::Nc;
    use crate::exec::Outcome;

    /// Runs blocks and returns the outcome of the last one.
    fn outcome(lathe: &mut Lathe, blocks: &[&str]) -> Outcome {
        let mut out = Outcome::default();
        for b in blocks {
            let mut events = alloc::vec::Vec::new();
            out = lathe.nc.exec(&words(b), &mut events).unwrap();
            assert!(events.is_empty(), "{b} printed {events:?}");
        }
        out
    }

    #[test]
    fn g10_l3_replaces_the_table_and_prints_nothing() {
        let mut m = Lathe::new();
        outcome(
            &mut m,
            &[
                "G10 L3",
                "P1 L2 Q1",
                "T0101",
                "T0202",
                "P2 L30 Q2",
                "T0303",
                "X10 Z5 F2",
                "G11",
            ],
        );
        let groups = &m.nc.st.data.life.groups;
        assert_eq!(groups.len(), 2);
        assert_eq!(groups[0].tools, [101, 202]);
        assert_eq!(groups[1].tools, [303]);
        assert_eq!(groups[1].life, 30.0);
        // The X Z F block inside the mode moved nothing and set no feed.
        assert_eq!(m.nc.st.pos.z, 0.0);
        assert_eq!(m.nc.st.feed, 0.0);
        // A second G10 L3 starts from an empty table.
        outcome(&mut m, &["G10 L3", "P5 L1", "T0505", "G11"]);
        assert_eq!(m.nc.st.data.life.groups.len(), 1);
        assert_eq!(m.nc.st.data.life.groups[0].number, 5);
    }

    #[test]
    fn other_g10_forms_are_another_dialect() {
        let mut m = Lathe::new();
        assert_eq!(m.try_run("G10 P1 X10 Z5"), Err(2004));
        assert_eq!(m.try_run("G10 L2 P1 X10"), Err(2004));
        assert_eq!(m.try_run("G10"), Err(2004));
    }

    #[test]
    fn a_group_needs_life_and_a_known_unit() {
        let mut m = Lathe::new();
        m.run("G10 L3");
        assert_eq!(m.try_run("P1 Q1"), Err(2006));
        // Written values out of range are the literal's fault (E1010).
        assert_eq!(m.try_run("P1 L10 Q3"), Err(1010));
        assert_eq!(m.try_run("P33 L10"), Err(1010));
        m.run("P1 L10");
        assert_eq!(m.try_run("T0199"), Err(7004));
        assert_eq!(m.try_run("T3301"), Err(7004));
    }

    #[test]
    fn g11_alone_does_nothing() {
        let mut m = Lathe::new();
        assert!(m.run("G11").is_empty());
        assert_eq!(m.run("G00 X10 Z2"), ["RAPID X=10 Z=2"]);
    }

    #[test]
    fn g10_l52_reads_into_the_named_variable() {
        let mut m = Lathe::new();
        // №172: bit 4 set on the reference machine → 00010000.
        let out = outcome(&mut m, &["G10 L52", "N172 R100"]);
        assert_eq!(out.store, Some((100, 10000.0)));
        // №022 of the Z axis: 10000 mm/min.
        let out = outcome(&mut m, &["N22 P2 R101"]);
        assert_eq!(out.store, Some((101, 10000.0)));
        outcome(&mut m, &["G11"]);
        assert_eq!(m.run("G00 X10 Z2"), ["RAPID X=10 Z=2"]);
    }

    #[test]
    fn g10_l52_writes_last_for_the_run() {
        let mut m = Lathe::new();
        outcome(&mut m, &["G10 L52", "N181 W0", "N121 P1 W-80.", "G11"]);
        assert_eq!(
            m.nc.machine.cycles.chamfer_type,
            crate::base::machine::ChamferType::I
        );
        // G30 P2 now returns X to machine -80 (zero = machine zero).
        let lines = m.run("G30 U0 W0");
        assert_eq!(lines.last().map(String::as_str), Some("HOME N=2 AXES=XZ"));
        assert_eq!(m.nc.st.pos.x(), -80.0);
        assert_eq!(m.nc.st.pos.z, -20.0);
    }

    #[test]
    fn g10_l52_faults() {
        let mut m = Lathe::new();
        m.run("G10 L52");
        assert_eq!(m.try_run("N999 R100"), Err(7008));
        assert_eq!(m.try_run("N172 R100 W1"), Err(2007));
        assert_eq!(m.try_run("N172"), Err(2006));
        assert_eq!(m.try_run("K5 R100"), Err(2099));
        assert_eq!(m.try_run("N172 W12"), Err(1010));
        assert_eq!(m.try_run("N22 P4 R100"), Err(1010));
        // A block without N reads and writes nothing.
        assert!(m.run("X10 Z5").is_empty());
    }

    use alloc::string::String;

    #[test]
    fn the_machine_file_gives_the_power_on_table() {
        let text =
            "[[tool_life.group]]\nnumber = 3\nlife = 2\nunit = \"count\"\ntools = [101, 202]\n";
        let m = Machine::from_toml(text).unwrap();
        let nc = Nc::new(m);
        assert_eq!(nc.st.data.life.groups[0].tools, [101, 202]);
    }
}
