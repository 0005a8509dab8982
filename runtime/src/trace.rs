//! The per-period trace: one line per interpolation period, as CSV under
//! [`CSV_HEADER`] or as JSON lines with the same fields. X is a diameter,
//! in work coordinates as in the canon ([`Frame::Work`]) or in machine
//! coordinates as the drives get it ([`Frame::Machine`]), or in whole steps
//! of the resolution ([`Frame::Counts`]); `feed` is the
//! actual path speed in mm/min; `line` the source line of the block whose
//! motion the period runs; `motion` the kind of motion of the period as a word
//! ([`crate::Motion::word`]); `tool` the active tool number; `file` the
//! source file of the line (the name given to the compiler: a library
//! program found with `-I` names its own file). Positions carry 6
//! decimals (finer than the 0.001 mm resolution) so a reader can
//! differentiate them. On a machine with a C axis a `c` column (degrees)
//! follows `z` ([`CSV_HEADER_C`]). `file` is the last column, so the
//! columns before it keep their places. The format is documented in
//! `docs/formats.md`.

use crate::interpolate::SetPoint;
use core::fmt::{self, Write};
use nc::base::decimal;

/// The CSV header of a machine without a C axis.
pub const CSV_HEADER: &str = "time_s,x,z,spindle_rpm,feed,line,motion,tool,file";
/// The CSV header of a machine with a C axis.
pub const CSV_HEADER_C: &str = "time_s,x,z,c,spindle_rpm,feed,line,motion,tool,file";

/// The coordinates a trace gives X and Z (and C) in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Frame {
    /// The programmed point in work coordinates, as the canon prints it:
    /// an origin change (G50, G54–G59) moves it without motion.
    #[default]
    Work,
    /// The axis set points in machine coordinates (from machine zero,
    /// work zero and tool offset applied): continuous across an origin
    /// change, what the drives follow.
    Machine,
    /// The machine set points in whole steps of the resolution (C in
    /// 0.001°), as integers, the axis compensation added: what a
    /// position-command or pulse interface sends ([`crate::counts`]).
    Counts,
}

impl Frame {
    /// X (a diameter), Z and C (where the machine has one) of a set point
    /// in this frame.
    fn coords(self, p: &SetPoint) -> [Option<Coord>; 3] {
        let mm = |v: f64| Some(Coord::Mm(v));
        match self {
            Frame::Work => [mm(p.x), mm(p.z), p.c.and_then(mm)],
            Frame::Machine => [mm(p.axis_x), mm(p.axis_z), p.c.and_then(mm)],
            Frame::Counts => {
                let n = |v: i64| Some(Coord::Count(v));
                [n(p.counts.x), n(p.counts.z), p.c.and(n(p.counts.c))]
            }
        }
    }
}

/// A position field: mm (or degrees) to 6 decimals, or a whole count.
#[derive(Clone, Copy)]
enum Coord {
    Mm(f64),
    Count(i64),
}

impl fmt::Display for Coord {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Coord::Mm(v) => Fixed(v, 6).fmt(f),
            Coord::Count(n) => n.fmt(f),
        }
    }
}

/// The CSV header of a machine with (`true`) or without a C axis.
pub fn csv_header(c_axis: bool) -> &'static str {
    if c_axis {
        CSV_HEADER_C
    } else {
        CSV_HEADER
    }
}

/// A number with `d` decimals (at most 6) and no `-0`.
#[derive(Clone, Copy)]
struct Fixed(f64, usize);

/// Half of the last decimal's unit for 0 to 6 decimals: values below it
/// print as 0. These are the values `0.5·libm::pow(10, -d)` gave before
/// the table spared a `pow` per field, bit for bit (a test checks): 5·10⁻⁶
/// is one unit in the last place below the nearest double.
const HALF_UNIT: [f64; 7] = [0.5, 0.05, 0.005, 0.0005, 5e-5, 4.9999999999999996e-6, 5e-7];

impl Fixed {
    /// The value printed: 0 below half the last decimal's unit (no `-0`)
    /// and for what is not finite.
    fn shown(self) -> f64 {
        let Fixed(v, d) = self;
        let half = HALF_UNIT.get(d).copied().unwrap_or(0.0);
        if v.abs() < half || !v.is_finite() {
            0.0
        } else {
            v
        }
    }
}

impl fmt::Display for Fixed {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (v, d) = (self.shown(), self.1);
        // As `{v:.d$}` prints it, in integers (nc::base::decimal).
        match decimal::scaled(v, d) {
            Some(n) => decimal::write_fixed(f, n, v.is_sign_negative(), d),
            None => write!(f, "{v:.d$}"),
        }
    }
}

/// A trace line's fields before the file name, as bytes: the `Display`s
/// of [`write_csv_fmt`] and [`write_json_fmt`] cost more than the digits
/// (a trace has one line per period), so the common line is put together
/// here and written at once.
struct LineBytes {
    bytes: [u8; LINE_CAPACITY],
    len: usize,
    json: bool,
}

/// Room for nine fields of at most [`decimal::FIXED_CAPACITY`] bytes, each
/// with its JSON name (at most `"spindle_rpm":`), quotes and comma, and
/// the JSON line's `{`.
const LINE_CAPACITY: usize = 1 + 9 * (decimal::FIXED_CAPACITY + 17);

impl LineBytes {
    /// The fields of `p` in `frame`, each followed by a comma: CSV values,
    /// or after `{` JSON members; `None` for a number past the integer
    /// path (left to the `core::fmt` writers).
    fn of(p: &SetPoint, frame: Frame, json: bool) -> Option<LineBytes> {
        let mut l = LineBytes {
            bytes: [0; LINE_CAPACITY],
            len: 0,
            json,
        };
        if json {
            l.push(b"{")?;
        }
        l.fixed(b"time_s", Fixed(p.time_s, 6))?;
        for (name, v) in [b"x", b"z", b"c"].into_iter().zip(frame.coords(p)) {
            match v {
                Some(Coord::Mm(v)) => l.fixed(name, Fixed(v, 6))?,
                Some(Coord::Count(n)) => l.whole(name, n)?,
                None => {}
            }
        }
        l.fixed(b"spindle_rpm", Fixed(p.spindle_rpm, 3))?;
        l.fixed(b"feed", Fixed(p.feed, 3))?;
        l.whole(b"line", i64::from(p.line))?;
        l.field(b"motion", p.motion.word().as_bytes(), json)?;
        l.whole(b"tool", i64::from(p.tool))?;
        Some(l)
    }

    fn push(&mut self, s: &[u8]) -> Option<()> {
        let end = self.len.checked_add(s.len())?;
        self.bytes.get_mut(self.len..end)?.copy_from_slice(s);
        self.len = end;
        Some(())
    }

    /// One field and its comma: `value,` in CSV, `"name":value,` in JSON
    /// (the value in quotes where `quoted`).
    fn field(&mut self, name: &[u8], value: &[u8], quoted: bool) -> Option<()> {
        if self.json {
            self.push(b"\"")?;
            self.push(name)?;
            self.push(b"\":")?;
        }
        if quoted {
            self.push(b"\"")?;
            self.push(value)?;
            return self.push(b"\",");
        }
        // The value and its comma in one piece: a CSV line is nearly all
        // numbers.
        let end = self.len.checked_add(value.len() + 1)?;
        let slot = self.bytes.get_mut(self.len..end)?;
        let (digits, comma) = slot.split_at_mut(value.len());
        digits.copy_from_slice(value);
        comma.fill(b',');
        self.len = end;
        Some(())
    }

    /// A number as [`Fixed`] prints it.
    fn fixed(&mut self, name: &[u8], x: Fixed) -> Option<()> {
        let (v, d) = (x.shown(), x.1);
        let mut buf = [0; decimal::FIXED_CAPACITY];
        let n = decimal::scaled(v, d)?;
        self.field(
            name,
            decimal::fixed_digits(n, v.is_sign_negative(), d, &mut buf)?,
            false,
        )
    }

    /// An integer.
    fn whole(&mut self, name: &[u8], n: i64) -> Option<()> {
        let mut buf = [0; decimal::FIXED_CAPACITY];
        self.field(name, decimal::fixed_digits(n, n < 0, 0, &mut buf)?, false)
    }

    fn as_str(&self) -> Result<&str, fmt::Error> {
        core::str::from_utf8(&self.bytes[..self.len]).map_err(|_| fmt::Error)
    }
}

/// A CSV field (RFC 4180): quoted, with `"` doubled, only when it holds a
/// comma, a quote or a line end.
struct CsvField<'a>(&'a str);

/// Whether a CSV field holds a comma, a quote or a line end. Bytes, not
/// chars: the four are ASCII, and a byte scan spares decoding the file
/// name on every line.
fn needs_quotes(s: &str) -> bool {
    s.bytes().any(|b| matches!(b, b',' | b'"' | b'\n' | b'\r'))
}

impl fmt::Display for CsvField<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if !needs_quotes(self.0) {
            return f.write_str(self.0);
        }
        f.write_char('"')?;
        for c in self.0.chars() {
            if c == '"' {
                f.write_char('"')?;
            }
            f.write_char(c)?;
        }
        f.write_char('"')
    }
}

/// A JSON string literal.
struct JsonStr<'a>(&'a str);

impl fmt::Display for JsonStr<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_char('"')?;
        // A name with nothing to escape (every file name in practice) in
        // one piece: it is written on every line.
        if !self.0.bytes().any(|b| b == b'"' || b == b'\\' || b < 0x20) {
            f.write_str(self.0)?;
            return f.write_char('"');
        }
        for c in self.0.chars() {
            match c {
                '"' => f.write_str("\\\"")?,
                '\\' => f.write_str("\\\\")?,
                '\n' => f.write_str("\\n")?,
                '\r' => f.write_str("\\r")?,
                '\t' => f.write_str("\\t")?,
                c if (c as u32) < 0x20 => write!(f, "\\u{:04x}", c as u32)?,
                c => f.write_char(c)?,
            }
        }
        f.write_char('"')
    }
}

/// One CSV line (with its `\n`) in `frame`; `file` is the name of `p.file`.
pub fn write_csv<W: Write>(w: &mut W, p: &SetPoint, frame: Frame, file: &str) -> fmt::Result {
    match LineBytes::of(p, frame, false) {
        Some(l) => w.write_str(l.as_str()?)?,
        None => write_csv_fmt(w, p, frame)?,
    }
    writeln!(w, "{}", CsvField(file))
}

/// The fields of a CSV line before the file name, each with its comma,
/// through `core::fmt`: the reference of [`LineBytes`], and what a number
/// past its integer path takes.
fn write_csv_fmt<W: Write>(w: &mut W, p: &SetPoint, frame: Frame) -> fmt::Result {
    write!(w, "{},", Fixed(p.time_s, 6))?;
    for v in frame.coords(p).into_iter().flatten() {
        write!(w, "{v},")?;
    }
    write!(
        w,
        "{},{},{},{},{},",
        Fixed(p.spindle_rpm, 3),
        Fixed(p.feed, 3),
        p.line,
        p.motion.word(),
        p.tool,
    )
}

/// One JSON line (with its `\n`) in `frame`; `file` is the name of `p.file`.
pub fn write_json<W: Write>(w: &mut W, p: &SetPoint, frame: Frame, file: &str) -> fmt::Result {
    match LineBytes::of(p, frame, true) {
        Some(l) => w.write_str(l.as_str()?)?,
        None => write_json_fmt(w, p, frame)?,
    }
    writeln!(w, "\"file\":{}}}", JsonStr(file))
}

/// The members of a JSON line before the file name, after its `{`, each
/// with its comma, through `core::fmt`: the reference of [`LineBytes`],
/// and what a number past its integer path takes.
fn write_json_fmt<W: Write>(w: &mut W, p: &SetPoint, frame: Frame) -> fmt::Result {
    write!(w, "{{\"time_s\":{},", Fixed(p.time_s, 6))?;
    for (name, v) in ["x", "z", "c"].into_iter().zip(frame.coords(p)) {
        if let Some(v) = v {
            write!(w, "\"{name}\":{v},")?;
        }
    }
    write!(
        w,
        "\"spindle_rpm\":{},\"feed\":{},\"line\":{},\"motion\":\"{}\",\"tool\":{},",
        Fixed(p.spindle_rpm, 3),
        Fixed(p.feed, 3),
        p.line,
        p.motion.word(),
        p.tool,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::interpolate::Motion;
    use alloc::string::String;

    #[test]
    fn lines_have_the_header_fields() {
        let p = SetPoint {
            time_s: 0.001,
            x: 40.0,
            z: -0.0000001,
            spindle_rpm: 800.0,
            feed: 1200.0,
            line: 7,
            motion: Motion::Arc,
            tool: 3,
            ..Default::default()
        };
        let mut s = String::new();
        write_csv(&mut s, &p, Frame::Work, "part.nc").unwrap();
        assert_eq!(
            s,
            "0.001000,40.000000,0.000000,800.000,1200.000,7,arc,3,part.nc\n"
        );
        s.clear();
        write_json(&mut s, &p, Frame::Work, "part.nc").unwrap();
        assert_eq!(s, "{\"time_s\":0.001000,\"x\":40.000000,\"z\":0.000000,\"spindle_rpm\":800.000,\"feed\":1200.000,\"line\":7,\"motion\":\"arc\",\"tool\":3,\"file\":\"part.nc\"}\n");
        // With a C axis the angle follows z.
        let p = SetPoint {
            c: Some(-90.5),
            ..p
        };
        s.clear();
        write_csv(&mut s, &p, Frame::Work, "part.nc").unwrap();
        assert_eq!(
            s,
            "0.001000,40.000000,0.000000,-90.500000,800.000,1200.000,7,arc,3,part.nc\n"
        );
        s.clear();
        write_json(&mut s, &p, Frame::Work, "part.nc").unwrap();
        assert!(
            s.contains("\"z\":0.000000,\"c\":-90.500000,\"spindle_rpm\""),
            "{s}"
        );
    }

    /// The byte-built lines against the `core::fmt` ones, CSV and JSON,
    /// field for field, on random set points in the three frames: values
    /// of every size and sign, tiny ones that print as 0, huge ones past
    /// the integer path.
    #[test]
    fn lines_built_as_bytes_are_those_fmt_writes() {
        let mut x: u64 = 0x5151_7e57_dead_beef;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        let mut value = |r: u64| -> f64 {
            let k = next();
            match r % 5 {
                0 => f64::from_bits(k),
                1 => (k % 2_000_000_001) as f64 / 1e6 - 1000.0,
                2 => (k % 2001) as f64 * 1e-9 - 1e-6,
                3 => f64::from(k as u32) / 128.0 - 1e7,
                _ => (k % 100_000) as f64 * 0.001,
            }
        };
        let motions = [
            Motion::None,
            Motion::Rapid,
            Motion::Feed,
            Motion::Thread,
            Motion::Arc,
            Motion::Dwell,
        ];
        let (mut fast, mut slow) = (0, 0);
        for i in 0..30_000u64 {
            let p = SetPoint {
                time_s: value(i),
                x: value(i / 2),
                z: value(i / 3),
                axis_x: value(i / 5),
                axis_z: value(i / 7),
                counts: crate::Counts {
                    x: (value(i / 19) * 1000.0) as i64,
                    z: (value(i) * 1000.0) as i64,
                    c: i as i64 - 15_000,
                },
                c: (i % 3 == 0).then(|| value(i / 11)),
                spindle_rpm: value(i / 13),
                feed: value(i / 17),
                line: i as u32 * 7919,
                tool: (i % 40) as u32,
                motion: motions[i as usize % motions.len()],
                ..Default::default()
            };
            for frame in [Frame::Work, Frame::Machine, Frame::Counts] {
                for json in [false, true] {
                    let mut reference = String::new();
                    if json {
                        write_json_fmt(&mut reference, &p, frame).unwrap();
                    } else {
                        write_csv_fmt(&mut reference, &p, frame).unwrap();
                    }
                    match LineBytes::of(&p, frame, json) {
                        Some(l) => {
                            fast += 1;
                            assert_eq!(l.as_str().unwrap(), reference);
                        }
                        None => slow += 1,
                    }
                }
            }
        }
        // Most lines take the byte path; some numbers are past it.
        assert!(fast > 20_000 && slow > 2_000, "{fast} fast, {slow} slow");
    }

    #[test]
    fn the_half_units_are_those_pow_gives() {
        for (d, half) in HALF_UNIT.iter().enumerate() {
            assert_eq!(
                half.to_bits(),
                (0.5 * libm::pow(10.0, -(d as f64))).to_bits()
            );
        }
    }

    #[test]
    fn file_names_are_quoted_where_the_format_needs_it() {
        let p = SetPoint::default();
        let mut s = String::new();
        // CSV: a comma or a quote makes a quoted field, quotes doubled.
        write_csv(&mut s, &p, Frame::Work, "a,b \"c\".nc").unwrap();
        assert!(s.ends_with(",0,\"a,b \"\"c\"\".nc\"\n"), "{s}");
        s.clear();
        write_csv(&mut s, &p, Frame::Work, "lib/O9001.nc").unwrap();
        assert!(s.ends_with(",0,lib/O9001.nc\n"), "{s}");
        // JSON: backslash and quote escaped.
        s.clear();
        write_json(&mut s, &p, Frame::Work, "C:\\nc\\\"x\".nc").unwrap();
        assert!(
            s.ends_with("\"file\":\"C:\\\\nc\\\\\\\"x\\\".nc\"}\n"),
            "{s}"
        );
    }

    #[test]
    fn the_machine_frame_gives_the_axis_set_points() {
        // Work X40 Z0 with the work zero at machine X-100 Z-300 (G54) and
        // a tool offset: the axes are at X-60.5 Z-299.75 (diameter).
        let p = SetPoint {
            time_s: 1.0,
            x: 40.0,
            z: 0.0,
            axis_x: -60.5,
            axis_z: -299.75,
            motion: Motion::Dwell,
            tool: 12,
            ..Default::default()
        };
        let mut s = String::new();
        write_csv(&mut s, &p, Frame::Machine, "a.nc").unwrap();
        assert_eq!(
            s,
            "1.000000,-60.500000,-299.750000,0.000,0.000,0,dwell,12,a.nc\n"
        );
        s.clear();
        write_csv(&mut s, &p, Frame::Work, "a.nc").unwrap();
        assert_eq!(
            s,
            "1.000000,40.000000,0.000000,0.000,0.000,0,dwell,12,a.nc\n"
        );
        s.clear();
        write_json(&mut s, &p, Frame::Machine, "a.nc").unwrap();
        assert!(
            s.starts_with("{\"time_s\":1.000000,\"x\":-60.500000,\"z\":-299.750000,"),
            "{s}"
        );
        // Counts: the same machine point in whole steps, C too.
        let p = SetPoint {
            c: Some(90.0),
            counts: crate::Counts {
                x: -60_500,
                z: -299_750,
                c: 90_000,
            },
            ..p
        };
        s.clear();
        write_csv(&mut s, &p, Frame::Counts, "a.nc").unwrap();
        assert_eq!(
            s,
            "1.000000,-60500,-299750,90000,0.000,0.000,0,dwell,12,a.nc\n"
        );
        s.clear();
        write_json(&mut s, &p, Frame::Counts, "a.nc").unwrap();
        assert!(
            s.starts_with(
                "{\"time_s\":1.000000,\"x\":-60500,\"z\":-299750,\"c\":90000,\"spindle_rpm\""
            ),
            "{s}"
        );
        // The header names every column of a line.
        assert_eq!(CSV_HEADER.split(',').count(), 9);
        assert_eq!(CSV_HEADER_C.split(',').count(), 10);
    }
}
