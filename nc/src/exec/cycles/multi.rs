//! The multiple threading cycles G76 (cycles.md §11, §12) and G78 (§19):
//! depths, flank or alternating infeed, run-in, pull-out and starts.

use alloc::format;

use super::lead;
use super::legs::{self, jk_pair, PullOut};
use super::words;
use crate::base::error::{fail, Alarm, NcError};
use crate::block::{round_half_away, Parsed};
use crate::exec::{Nc, Outcome, Sink};
use crate::plan::threading::{check_depths, g76_path, g78_path, Infeed, Passes, Thread};

/// The words of the last G76 first block (§0: m = 1, r = 0, a = 60 before
/// any).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct G76First {
    finishing: i64,
    /// rr: the 45° pull-out in 0.1 lead when no J/K is given.
    pull_tenths: i64,
    angle: f64,
    dmin: f64,
    allowance: f64,
    pull: Option<(f64, f64)>,
}

impl Default for G76First {
    fn default() -> Self {
        G76First {
            finishing: 1,
            pull_tenths: 0,
            angle: 60.0,
            dmin: 0.0,
            allowance: 0.0,
            pull: None,
        }
    }
}

/// The words of the last G78 first block (§19).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct G78First {
    /// m: 0 equal depths, 1 decreasing depths as G76.
    decreasing: bool,
    /// r: 0 radial, 1 left flank, 2 right flank, 3 alternating.
    cut_in: i64,
    angle: f64,
    dmin: f64,
    allowance: f64,
    pull: Option<(f64, f64)>,
    finishing: i64,
    starts: i64,
    run_in: f64,
}

impl Default for G78First {
    fn default() -> Self {
        G78First {
            decreasing: true,
            cut_in: 0,
            angle: 60.0,
            dmin: 0.0,
            allowance: 0.0,
            pull: None,
            finishing: 1,
            starts: 1,
            run_in: 0.0,
        }
    }
}

/// `P` of a first block: mmrraa as (mm, rr, aa).
fn digits(p: &Parsed) -> Result<Option<(i64, i64, f64)>, NcError> {
    let Some(v) = p.get(b'P').map(round_half_away) else {
        return Ok(None);
    };
    if v < 0.0 {
        return fail(
            Alarm::BadThread,
            format!("P{v}: the mmrraa digits cannot be negative"),
        );
    }
    let v = v as i64;
    Ok(Some((v / 10000, (v / 100) % 100, (v % 100) as f64)))
}

/// A G76 block: the first block sets the modal words, the second cuts.
pub(crate) fn g76(
    nc: &mut Nc,
    p: &Parsed,
    sink: &mut dyn Sink,
    out: &mut Outcome,
) -> Result<(), NcError> {
    if !p.has_axis() {
        return g76_first(nc, p);
    }
    let first = nc.st.cycles.g76;
    // The Fanuc one-block form: K is the height and D the first depth
    // (lengths), I the taper, A the angle (dialect.md §4.12).
    let fanuc = p.has(b'K') || p.has(b'D');
    let (taper, height, dd, angle) = if fanuc {
        (
            words::length_or(nc, p, b'I', 0.0),
            words::length_or(nc, p, b'K', 0.0),
            words::length_or(nc, p, b'D', 0.0),
            p.get(b'A').unwrap_or(first.angle),
        )
    } else {
        (
            words::length_or(nc, p, b'R', 0.0),
            words::increments(nc, p, b'P').unwrap_or(0.0),
            words::increments(nc, p, b'Q').unwrap_or(0.0),
            first.angle,
        )
    };
    check_depths(height, dd)?;
    let lead = lead::resolve(nc, lead::written(nc, p, !fanuc))?;
    let t = Thread {
        a: nc.st.pos,
        end: nc.target(p),
        taper,
        height,
        first: dd,
        lead,
    };
    let pull = match first.pull {
        Some(pair) => PullOut::from_pair(pair),
        None => {
            let g = first.pull_tenths as f64 * lead / 10.0;
            PullOut::from_pair((g, g))
        }
    };
    lead::check_pull_out(nc, lead, pull)?;
    let passes = Passes {
        dmin: first.dmin,
        allowance: first.allowance,
        decreasing: true,
        finishing: first.finishing,
        angle,
        pull,
    };
    let path = g76_path(&t, &passes)?;
    legs::emit(nc, &path, true, sink)?;
    out.moved = true;
    Ok(())
}

/// P(mmrraa) Q(Δdmin) R(d) [J K]: each word given replaces its value; J/K
/// are replaced as a pair by every first block (dialect.md §4.3).
fn g76_first(nc: &mut Nc, p: &Parsed) -> Result<(), NcError> {
    let mut f = nc.st.cycles.g76;
    if let Some((m, r, a)) = digits(p)? {
        f.finishing = m;
        f.pull_tenths = r;
        f.angle = a;
    }
    if let Some(q) = words::increments(nc, p, b'Q') {
        f.dmin = q.abs();
    }
    if let Some(r) = nc.len_of(p, b'R') {
        f.allowance = r.abs();
    }
    f.pull = jk_pair(nc.len_of(p, b'J'), nc.len_of(p, b'K'));
    nc.st.cycles.g76 = f;
    Ok(())
}

/// A G78 block: the first block sets the modal words, the second cuts.
pub(crate) fn g78(
    nc: &mut Nc,
    p: &Parsed,
    sink: &mut dyn Sink,
    out: &mut Outcome,
) -> Result<(), NcError> {
    if !p.has_axis() {
        return g78_first(nc, p);
    }
    let f = nc.st.cycles.g78;
    let height = words::increments(nc, p, b'P').unwrap_or(0.0);
    let dd = words::increments(nc, p, b'Q').unwrap_or(0.0);
    check_depths(height, dd)?;
    let t = Thread {
        a: nc.st.pos,
        end: nc.target(p),
        taper: words::length_or(nc, p, b'R', 0.0),
        height,
        first: dd,
        lead: lead::resolve(nc, lead::written(nc, p, true))?,
    };
    let pull = f.pull.and_then(PullOut::from_pair);
    lead::check_pull_out(nc, t.lead, pull)?;
    let passes = Passes {
        dmin: f.dmin,
        allowance: f.allowance,
        decreasing: f.decreasing,
        finishing: f.finishing,
        angle: f.angle,
        pull,
    };
    let infeed = Infeed {
        cut_in: f.cut_in,
        starts: f.starts,
        run_in: f.run_in,
    };
    let path = g78_path(&t, &passes, &infeed)?;
    legs::emit(nc, &path, true, sink)?;
    out.moved = true;
    Ok(())
}

/// P(mmrraa) Q(Δdmin) R(d) [J K] [D] [L] [E], with the range checks of
/// §19: m 0/1, r 0–3, L ≥ 1, D ≥ 0.
fn g78_first(nc: &mut Nc, p: &Parsed) -> Result<(), NcError> {
    let mut f = nc.st.cycles.g78;
    if let Some((m, r, a)) = digits(p)? {
        if !(0..=1).contains(&m) || !(0..=3).contains(&r) {
            return fail(
                Alarm::BadThread,
                format!("G78 P: infeed mode {m} (0/1) or cut-in mode {r} (0–3) out of range"),
            );
        }
        f.decreasing = m == 1;
        f.cut_in = r;
        f.angle = a;
    }
    if let Some(q) = words::increments(nc, p, b'Q') {
        f.dmin = q.abs();
    }
    if let Some(r) = nc.len_of(p, b'R') {
        f.allowance = r.abs();
    }
    if let Some(d) = words::count(p, b'D')? {
        if d < 0 {
            return fail(
                Alarm::BadThread,
                format!("G78 D{d}: finishing passes cannot be negative"),
            );
        }
        f.finishing = d;
    }
    if let Some(l) = words::count(p, b'L')? {
        if l < 1 {
            return fail(
                Alarm::BadThread,
                format!("G78 L{l}: a thread has at least one start"),
            );
        }
        f.starts = l;
    }
    if let Some(e) = nc.len_of(p, b'E') {
        f.run_in = e;
    }
    f.pull = jk_pair(nc.len_of(p, b'J'), nc.len_of(p, b'K'));
    nc.st.cycles.g78 = f;
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::exec::cycles::testing::{assert_line, nums, run_err, Lathe};
    use alloc::format;
    use alloc::string::String;
    use alloc::vec::Vec;

    fn lathe(at: &str) -> Lathe {
        let mut m = Lathe::new();
        m.run("M03 S300");
        m.run(at);
        m
    }

    /// The THREAD lines' start rapids: every pass begins with a RAPID from
    /// A, so the passes are the RAPIDs not to xA.
    fn pass_starts(lines: &[String], xa: f64) -> Vec<Vec<f64>> {
        lines
            .iter()
            .filter(|l| l.starts_with("RAPID"))
            .map(|l| nums(l))
            .filter(|v| (v[0] - xa).abs() > 1e-9)
            .collect()
    }

    #[test]
    fn g76_taper_thread_depths_clamp_and_finishing() {
        // A = X40 Z2, end X30 Z-30, i = -1.5 (root from X27 at Z2), lead 2,
        // k = 1.3, Δd = 0.35, Δdmin = 0.2, d = 0.1, m = 2, a = 60.
        // Depths: 0.35; 0.35√2 = 0.495 (step 0.145 < 0.2) → 0.55; 0.35√3 =
        // 0.606 → 0.75; 0.7 → 0.95; 0.783 → 1.15 ≥ k − d = 1.2? no →
        // 1.15; next 1.35 ≥ 1.2 → 1.2; then 1.3 twice.
        let mut m = lathe("G00 X40 Z2");
        m.run("G76 P020060 Q200 R0.1");
        let l = m.run("G76 X30 Z-30 R-1.5 P1300 Q350 F2");
        let depths = [0.35, 0.55, 0.75, 0.95, 1.15, 1.2, 1.3, 1.3];
        let starts = pass_starts(&l, 40.0);
        assert_eq!(starts.len(), depths.len());
        let tan30 = 30f64.to_radians().tan();
        for (s, d) in starts.iter().zip(depths) {
            // The pass line at depth d: r = 15 + (-1.5)·(z + 30)/32 + (1.3 − d).
            let z = 2.0 - d * tan30;
            let r = 15.0 - 1.5 * (z + 30.0) / 32.0 + (1.3 - d);
            assert!(
                (s[0] - 2.0 * r).abs() < 1e-4 && (s[1] - z).abs() < 1e-4,
                "{s:?} vs depth {d}"
            );
        }
        // Every pass ends at its own line's X at Z-30; the last on the root.
        assert_eq!(l[l.len() - 3], "THREAD X=30 Z=-30 LEAD=2");
        assert_eq!(l[l.len() - 2], "RAPID X=40 Z=-30");
        assert_eq!(l[l.len() - 1], "RAPID X=40 Z=2");
        assert_eq!(l.len(), 8 * 4);
    }

    #[test]
    fn g76_with_j_k_and_an_inside_thread() {
        // Inside: A = X16 Z2, end X20 Z-12, k = 1, Δd = 0.6, d = 0, m = 1,
        // a = 0 (radial): depths 0.6, then 0.8485 → … ≥ 1? no: 0.6√2 =
        // 0.8485 → pass; 0.6√3 = 1.039 ≥ 1 → 1.0; finishing 1.0.
        // J0.5 K1: pull-out from Z-11 lifting 0.5 inwards.
        let mut m = lathe("G00 X16 Z2");
        m.run("G76 P010000 J0.5 K1");
        let l = m.run("G76 X20 Z-12 P1000 Q600 F1");
        let depths = [0.6, 0.6 * 2f64.sqrt(), 1.0, 1.0];
        assert_eq!(l.len(), depths.len() * 5);
        for (pass, d) in l.chunks(5).zip(depths) {
            let x = 20.0 - 2.0 * (1.0 - d);
            assert_line(&pass[0], "RAPID", &[x, 2.0]);
            assert_line(&pass[1], "THREAD", &[x, -11.0, 1.0]);
            assert_line(&pass[2], "THREAD", &[x - 1.0, -12.0, 1.0]);
            assert_line(&pass[3], "RAPID", &[16.0, -12.0]);
        }
    }

    #[test]
    fn g76_fanuc_one_block_form() {
        // G76 X30 Z-20 K1.2 D0.6 F2 A0: k and Δd as lengths, radial infeed;
        // m, Δdmin, d from the (power-on) modal state: m = 1, d = 0.
        // Depths 0.6, 0.6√2 = 0.8485, 0.6√3 = 1.0392 → 1.2? no: 1.0392 < 1.2
        // → pass; 1.2 (√4·0.6 = 1.2 ≥ 1.2); finishing 1.2.
        let mut m = lathe("G00 X34 Z3");
        let l = m.run("G76 X30 Z-20 K1.2 D0.6 F2 A0");
        let xs: Vec<f64> = pass_starts(&l, 34.0).iter().map(|s| s[0]).collect();
        let want: Vec<f64> = [0.6, 0.6 * 2f64.sqrt(), 0.6 * 3f64.sqrt(), 1.2, 1.2]
            .iter()
            .map(|d| 30.0 + 2.0 * (1.2 - d))
            .collect();
        assert_eq!(xs.len(), want.len());
        for (x, w) in xs.iter().zip(want) {
            assert!((x - w).abs() < 1e-4);
        }
    }

    #[test]
    fn g78_right_flank_equal_depths_two_starts() {
        // A = X40 Z4, end X36 Z-10 (outside), lead 3, k = 1, Δd = 0.3,
        // m = 0 equal depths: 0.3, 0.6, 0.9 = k − d (d = 0.1) → 0.9 … 0.9
        // ≥ 0.9: the third pass is the last roughing; D1 finishing at 1.
        // r = 2: shift −δ·tan 30°; L2: every pass twice, Q=180 the second.
        let mut m = lathe("G00 X40 Z4");
        m.run("G78 P000260 R0.1 D1 L2");
        let l = m.run("G78 X36 Z-10 P1000 Q300 F3");
        let depths = [0.3, 0.6, 0.9, 1.0];
        assert_eq!(l.len(), depths.len() * 2 * 4);
        let tan30 = 30f64.to_radians().tan();
        for (i, d) in depths.iter().enumerate() {
            let x = 36.0 + 2.0 * (1.0 - d);
            let z = 4.0 - d * tan30;
            for start in 0..2 {
                let pass = &l[(2 * i + start) * 4..][..4];
                assert_line(&pass[0], "RAPID", &[x, z]);
                if start == 0 {
                    assert_line(&pass[1], "THREAD", &[x, -10.0, 3.0]);
                } else {
                    assert_line(&pass[1], "THREAD", &[x, -10.0, 3.0, 180.0]);
                }
                assert_line(&pass[2], "RAPID", &[40.0, -10.0]);
                assert_line(&pass[3], "RAPID", &[40.0, 4.0]);
            }
        }
    }

    #[test]
    fn g78_inside_left_flank_with_run_in() {
        // Inside: A = X20 Z3, end X24 Z-12, k = 0.6, Δd = 0.3, Δdmin = 0,
        // d = 0, m = 1: depths 0.3, 0.3√2, 0.3√3, then 0.6 (0.3√4 reaches
        // k); D1 at 0.6. r = 1: start Z = 3 + δ·tan 30°. E0.5 (radius):
        // the rapid ends 0.5 inwards (so = -1), the run-in enters 0.5
        // deeper over 0.5 along -Z.
        let mut m = lathe("G00 X20 Z3");
        m.run("G78 P010160 Q0 R0 D1 E0.5");
        let l = m.run("G78 X24 Z-12 P600 Q300 F1.5");
        let depths = [0.3, 0.3 * 2f64.sqrt(), 0.3 * 3f64.sqrt(), 0.6, 0.6];
        assert_eq!(l.len(), depths.len() * 5);
        let tan30 = 30f64.to_radians().tan();
        for (pass, d) in l.chunks(5).zip(depths) {
            let x = 24.0 - 2.0 * (0.6 - d);
            let z = 3.0 + d * tan30;
            assert_line(&pass[0], "RAPID", &[x - 1.0, z]);
            assert_line(&pass[1], "THREAD", &[x, z - 0.5, 1.5]);
            assert_line(&pass[2], "THREAD", &[x, -12.0, 1.5]);
            assert_line(&pass[3], "RAPID", &[20.0, -12.0]);
            assert_line(&pass[4], "RAPID", &[20.0, 3.0]);
        }
    }

    #[test]
    fn g78_errors() {
        assert_eq!(run_err(&["G78 P020060"]), 4010);
        assert_eq!(run_err(&["G78 P010460"]), 4010);
        assert_eq!(run_err(&["G78 L0"]), 4010);
        assert_eq!(run_err(&["G78 D-1"]), 4010);
        assert_eq!(run_err(&["G00 X30 Z5", "G78 X22 Z-15 P0 Q400 F2"]), 4010);
        // The run-in and the pull-out take the whole pass.
        assert_eq!(
            run_err(&["G00 X30 Z5", "G78 E10 K10", "G78 X22 Z-15 P1000 Q400 F2"]),
            4010
        );
        assert_eq!(run_err(&["G00 X30 Z5", "G76 X22 Z-15 P1000 Q0 F2"]), 4010);
        // A pull-out of J10 over K1 at lead 100 cuts at 1000 mm (§12),
        // above the 500 mm maximum: G76 and G78 alike.
        for code in ["G76", "G78"] {
            let first = format!("{code} P010060 Q100 R0.1 J10 K1");
            let second = format!("{code} X28 Z-20 P1000 Q300 F100");
            assert_eq!(run_err(&["G00 X30 Z5", &first, &second]), 4010, "{code}");
        }
    }
}
