//! Polar (G12.1) and cylindrical (G7.1) interpolation through the
//! runtime: bytes → a contour in the plane (lines, arcs, ellipses,
//! parabolas, rapids, the axis outside the plane moving alone or with a
//! line, nose-radius compensation) on a machine with a C axis → a run that stops with an
//! alarm or that `gbvm check` certifies: every joint (X, Z, C) within its
//! speed, acceleration and (with jerk limiting) jerk, every end point
//! reached. runtime/tests/plane_limits.rs runs a fixed set of such
//! programs; this target lets the fuzzer look for the ones it misses.

use nc::Machine;

/// Radii of the cylinder (mm) byte 1 chooses from (mod 4).
pub const CYLINDERS: [f64; 4] = [5.0, 10.0, 20.0, 40.0];
/// Radii of the tool under compensation (mm), byte 1 bits 2–3.
pub const TOOLS: [f64; 4] = [0.5, 1.0, 2.0, 3.0];
/// Feeds (mm/min), the low 2 bits of a move's last byte.
pub const FEEDS: [u32; 4] = [100, 300, 1000, 3000];
/// Moves a program has at most (4 bytes each).
pub const MAX_MOVES: usize = 10;
/// Periods a plane run may take: 3600 s. Its moves are long and slow: on
/// the largest cylinder (radius 40) a move turns C up to 400°, 279 mm,
/// and an arc or a conic runs longer than its chord, at F100 as slowest:
/// ten such moves take some 2700 s, more under jerk limiting.
pub const MAX_TICKS: u64 = 3_600_000;

/// A plane program read from bytes, and whether jerk limiting is on.
///
/// Byte 0: bit 0 the plane (polar, cylinder), bits 1–2 compensation (0
/// or 3 none, 1 G41, 2 G42), bit 3 jerk limiting. Byte 1: the cylinder's
/// radius ([`CYLINDERS`], mod 4) and the tool's radius ([`TOOLS`], bits
/// 2–3). Then 4 bytes a move: the kind (mod 9: G01, G00, G02, G03, the
/// axis outside the plane alone, G01 or G00 taking it along, an ellipse,
/// a parabola), the plane's two coordinates (polar x −30…30 and c
/// −20…20 as radius values; cylinder Z −30…0 and C −200…200°), and a
/// last byte whose low 2 bits are the feed ([`FEEDS`]) and whose upper 6
/// (h = 0…1) the axis outside the plane (polar Z −5…2, cylinder X 0…2 mm
/// below the surface as a radius), an arc's R (1.01…3 times half the
/// chord, polar; 20…200 mm, cylinder), an ellipse's B (A is 1.5 times
/// half the chord, B 0.3…1.5 times A) or a parabola's P (0.5…4 times
/// half the chord). A conic's sense is bit 0 of the kind byte divided by
/// 9 (G6.2/G7.2 when clear), its Q 22.5° times the next 3 bits. Values
/// are written to 3 decimals.
pub fn decode(data: &[u8]) -> (String, Machine, bool) {
    let b = |i: usize| data.get(i).copied().unwrap_or(0);
    let polar = b(0) & 1 == 0;
    let comp = match (b(0) >> 1) & 3 {
        1 => Some("G41"),
        2 => Some("G42"),
        _ => None,
    };
    let jerk = b(0) & 8 != 0;
    let radius = CYLINDERS[usize::from(b(1) & 3)];
    let tool = TOOLS[usize::from((b(1) >> 2) & 3)];
    let t = if comp.is_some() { " T0101" } else { "" };
    let mut s = match polar {
        true => format!("G98 G00 X40 Z2 C0{t}\nG12.1\n"),
        false => format!("G98 G00 X{:.3} Z0 C0{t}\nG7.1 C{radius}.\n", 2.0 * radius),
    };
    let (start, cancel, end) = match polar {
        true => ("X40 C0.5", "X40 C0", "G13.1"),
        false => ("Z0.5 C0", "Z0 C0", "G7.1 C0"),
    };
    if let Some(side) = comp {
        s += &format!("{side} G01 {start} F300\n");
    }
    let mut at = if polar { (20.0, 0.0) } else { (0.0, 0.0) };
    for m in data
        .get(2..)
        .unwrap_or_default()
        .chunks_exact(4)
        .take(MAX_MOVES)
    {
        let unit = |i: usize| f64::from(m[i]) / 255.0;
        let to = match polar {
            true => (-30.0 + 60.0 * unit(1), -20.0 + 40.0 * unit(2)),
            false => (-30.0 * unit(1), -200.0 + 400.0 * unit(2)),
        };
        let (f, high) = (FEEDS[usize::from(m[3] & 3)], f64::from(m[3] >> 2) / 63.0);
        let off = match polar {
            true => format!("Z{:.3}", -5.0 + 7.0 * high),
            false => format!("X{:.3}", 2.0 * (radius - 2.0 * high)),
        };
        let words = |(a, b): (f64, f64)| match polar {
            true => format!("X{:.3} C{b:.3}", 2.0 * a),
            false => format!("Z{a:.3} C{b:.3}"),
        };
        let kind = m[0] % 9;
        let half = match polar {
            true => (to.0 - at.0).hypot(to.1 - at.1) / 2.0,
            false => (to.0 - at.0).hypot((to.1 - at.1).to_radians() * radius) / 2.0,
        };
        let (cw, q) = ((m[0] / 9) % 2 == 0, 22.5 * f64::from((m[0] / 18) % 8));
        match kind {
            0 => s += &format!("G01 {} F{f}\n", words(to)),
            1 => s += &format!("G00 {}\n", words(to)),
            2 | 3 => {
                let g = if kind == 2 { "G02" } else { "G03" };
                let r = match polar {
                    true => half * (1.01 + 1.99 * high),
                    false => 20.0 + 180.0 * high,
                };
                s += &format!("{g} {} R{r:.3} F{f}\n", words(to));
            }
            4 => {
                s += &format!("G01 {off} F{f}\n");
                continue;
            }
            5 => s += &format!("G01 {} {off} F{f}\n", words(to)),
            6 => s += &format!("G00 {} {off}\n", words(to)),
            7 => {
                let g = if cw { "G6.2" } else { "G6.3" };
                let a = 1.5 * half;
                let b = a * (0.3 + 1.2 * high);
                s += &format!(
                    "{g} {} A{a:.3} B{b:.3} Q{:.0} F{f}\n",
                    words(to),
                    q * 1000.0
                );
            }
            _ => {
                let g = if cw { "G7.2" } else { "G7.3" };
                let p = half * (0.5 + 3.5 * high);
                s += &format!(
                    "{g} {} P{:.0} Q{:.0} F{f}\n",
                    words(to),
                    p * 1000.0,
                    q * 1000.0
                );
            }
        }
        at = to;
    }
    if comp.is_some() {
        s += &format!("G40 G01 {cancel} F300\n");
    }
    s += &format!("{end}\nM30\n");
    let toml = format!("[axes.c]\nenabled = true\n[[tools.offset]]\nnumber = 1\nradius = {tool}\n");
    let machine = match Machine::from_toml(&toml) {
        Ok(m) => m,
        Err(e) => panic!("the target's machine file is wrong: {e}"),
    };
    (s, machine, jerk)
}

/// The target: a program that compiles either stops with an alarm (an
/// arc that cannot be drawn, a path through the centre) or runs to its
/// end within [`MAX_TICKS`] and is certified.
pub fn certified(data: &[u8]) {
    let (src, machine, jerk) = decode(data);
    crate::contour::certified_on("plane.nc", &src, machine, jerk, MAX_TICKS);
}
