//! W118: a thread chain whose first block is shorter than the distance its
//! long axis needs to reach thread speed, or whose last block is shorter
//! than the distance it needs to stop (`nc::thread_room`). Over those
//! lengths the lead is not the programmed one; where they run past a
//! block, that block is not cut at its lead at all. W126: a thread block
//! whose lead × spindle speed asks an axis for more than its maximum
//! cutting feed, where the run stops with E4010.
//!
//! The dry run of a static program feeds the canon events here as the
//! kernel makes them: the spindle speed, the tool's position and the
//! thread moves, in the order the runtime chains them (consecutive thread
//! moves, nothing between).

use grammar::{Diagnostic, Span};
use nc::thread_room::{entry_length, exit_length, long_axis_accel, z_is_long};
use nc::{Event, Machine};
use std::collections::HashSet;

/// One thread move of the chain being collected.
#[derive(Debug, Clone, Copy)]
struct Leg {
    /// Travel, radial X and Z.
    d_r: f64,
    d_z: f64,
    lead: f64,
    /// The block that made it (its unit and span).
    unit: usize,
    span: Span,
}

/// Watches the canon events of a dry run for W118.
pub struct RoomCheck {
    x_accel: f64,
    z_accel: f64,
    /// The axes' maximum cutting feeds, mm/min (X radial).
    x_max_feed: f64,
    z_max_feed: f64,
    spindle_accel: f64,
    max_rpm: f64,
    min_rpm: f64,
    override_factor: f64,
    /// `S` and whether it is a surface speed; the `G50 S` clamp.
    speed: Option<(f64, bool)>,
    clamp: f64,
    /// The tool's programmed point (X diameter, Z), once known.
    at: Option<(f64, f64)>,
    /// The chain: its legs and the rpm at its start.
    chain: Vec<Leg>,
    rpm: f64,
    /// A leg the check cannot measure (an arc thread): no check.
    unmeasured: bool,
    /// The block whose events come next (its unit and span).
    pub unit: usize,
    pub span: Span,
    /// Findings, one per block and kind, with their units.
    pub warnings: Vec<(usize, Diagnostic)>,
    /// The (unit, block, kind) of each finding, to say each once.
    told: HashSet<(usize, Span, String)>,
}

impl RoomCheck {
    /// A check with the machine's axes and spindle.
    pub fn new(m: &Machine) -> RoomCheck {
        RoomCheck {
            x_accel: m.axes.x.accel_mm_s2,
            z_accel: m.axes.z.accel_mm_s2,
            x_max_feed: m.axes.x.max_feed_mm_min,
            z_max_feed: m.axes.z.max_feed_mm_min,
            spindle_accel: m.spindle.accel_rpm_s,
            max_rpm: m.spindle.max_rpm,
            min_rpm: m.spindle.min_rpm.max(0.0),
            override_factor: m.operator.spindle_override_pct / 100.0,
            speed: None,
            clamp: f64::INFINITY,
            at: None,
            chain: Vec::new(),
            rpm: 0.0,
            unmeasured: false,
            unit: 0,
            span: Span::default(),
            warnings: Vec::new(),
            told: HashSet::new(),
        }
    }

    /// The spindle speed the thread starting at diameter `x` runs at (the
    /// runtime waits for it), or `None` when it is not known.
    fn rpm_at(&self, x: f64) -> Option<f64> {
        let (s, css) = self.speed?;
        let n = if css {
            if x.abs() < 1e-9 {
                self.clamp.min(self.max_rpm)
            } else {
                (1000.0 * s / (core::f64::consts::PI * x.abs()) * self.override_factor)
                    .min(self.clamp)
                    .min(self.max_rpm)
            }
        } else {
            (s * self.override_factor).min(self.max_rpm)
        };
        (n > 0.0).then(|| n.max(self.min_rpm))
    }

    /// One canon event of the block at [`RoomCheck::span`].
    pub fn event(&mut self, e: &Event) {
        match *e {
            Event::Thread { x, z, lead, .. } => {
                if let Some((x0, z0)) = self.at {
                    if self.chain.is_empty() {
                        self.rpm = self.rpm_at(x0).unwrap_or(0.0);
                    }
                    let leg = Leg {
                        d_r: (x - x0) / 2.0,
                        d_z: z - z0,
                        lead,
                        unit: self.unit,
                        span: self.span,
                    };
                    // A block that does not move has no speed to reach:
                    // the chain's first leg is the next one.
                    if leg.d_r != 0.0 || leg.d_z != 0.0 {
                        self.check_speed(&leg, self.chain.is_empty());
                        self.chain.push(leg);
                    }
                } else {
                    self.unmeasured = true;
                }
                self.at = Some((x, z));
                return;
            }
            Event::ArcThread { x, z, .. } => {
                self.unmeasured = true;
                self.at = Some((x, z));
                return;
            }
            _ => {}
        }
        self.finish();
        match *e {
            Event::Rapid { x, z, .. }
            | Event::Line { x, z, .. }
            | Event::Arc { x, z, .. }
            | Event::Ellipse { x, z, .. }
            | Event::Parabola { x, z, .. }
            | Event::Skip { x, z } => self.at = Some((x, z)),
            Event::Origin { .. } | Event::Home { .. } => self.at = None,
            Event::Speed { s, css, max } => {
                self.speed = Some((s, css));
                if let Some(m) = max {
                    self.clamp = if m > 0.0 { m } else { f64::INFINITY };
                }
            }
            _ => {}
        }
    }

    /// W126: a leg's lead at the chain's spindle speed against the axes'
    /// maximum cutting feeds, as the runtime checks every leg where the
    /// chain starts (E4010): the long axis runs at lead × rpm, the other
    /// in proportion (`first`: the leg starts the chain).
    fn check_speed(&mut self, leg: &Leg, first: bool) {
        let (dr, dz) = (leg.d_r.abs(), leg.d_z.abs());
        let long = dr.max(dz);
        if !is_pos(self.rpm) || !is_pos(long) {
            return;
        }
        let v_long = leg.lead * self.rpm;
        let speeds = [
            ("X", v_long * dr / long, self.x_max_feed),
            ("Z", v_long * dz / long, self.z_max_feed),
        ];
        let Some(&(axis, v, max)) = speeds.iter().find(|(_, v, max)| *v > max * (1.0 + 1e-9))
        else {
            return;
        };
        let stops = if first {
            "here"
        } else {
            "at the start of its thread chain"
        };
        let msg = format!(
            "thread too fast for the axis: at {:.0} rpm lead {} asks {axis} for {v:.0} mm/min, above its maximum cutting feed of {max:.0} mm/min; the run stops with E4010 {stops}",
            self.rpm, leg.lead
        );
        let kind = "W126".to_string();
        if self.told.insert((leg.unit, leg.span, kind)) {
            self.warnings
                .push((leg.unit, Diagnostic::warning("W126", leg.span, msg)));
        }
    }

    /// The chain ended: its first and last legs against the room they need.
    pub fn finish(&mut self) {
        // Most events end no chain: nothing to take apart.
        if self.chain.is_empty() {
            self.unmeasured = false;
            return;
        }
        let chain = core::mem::take(&mut self.chain);
        let unmeasured = core::mem::take(&mut self.unmeasured);
        let (Some(first), Some(last)) = (chain.first(), chain.last()) else {
            return;
        };
        if unmeasured || !is_pos(self.rpm) {
            return;
        }
        let (ax, az) = (self.x_accel, self.z_accel);
        let long = |l: &Leg| l.d_r.abs().max(l.d_z.abs());
        let axis = |l: &Leg| if z_is_long(l.d_r, l.d_z) { "Z" } else { "X" };
        let a_first = long_axis_accel(first.d_r, first.d_z, ax, az);
        let need = entry_length(first.lead, self.rpm, a_first, self.spindle_accel);
        if long(first) < need {
            self.warn(
                (first.unit, first.span),
                format!(
                    "thread too short to reach its lead: at {:.0} rpm {} needs {:.3} mm to reach thread speed, this block gives {:.3} mm",
                    self.rpm,
                    axis(first),
                    need,
                    long(first)
                ),
            );
        }
        let a_last = long_axis_accel(last.d_r, last.d_z, ax, az);
        let need = exit_length(last.lead, self.rpm, a_last);
        if long(last) < need {
            self.warn(
                (last.unit, last.span),
                format!(
                    "no room to stop at the thread's end: at {:.0} rpm {} needs {:.3} mm to stop from thread speed, this block gives {:.3} mm",
                    self.rpm,
                    axis(last),
                    need,
                    long(last)
                ),
            );
        }
    }

    /// One warning per block and message kind (a cycle's passes repeat
    /// it), looked up in a set: a scan of the warnings so far made a
    /// program of many thread blocks quadratic.
    fn warn(&mut self, (unit, span): (usize, Span), message: String) {
        let kind = message.split(':').next().unwrap_or_default().to_string();
        if self.told.insert((unit, span, kind)) {
            self.warnings
                .push((unit, Diagnostic::warning("W118", span, message)));
        }
    }
}

/// A speed above zero (not NaN).
fn is_pos(v: f64) -> bool {
    v > 0.0
}

impl nc::Sink for RoomCheck {
    fn emit(&mut self, e: Event) {
        self.event(&e);
    }
}

#[cfg(test)]
mod tests {
    use crate::{compile, Options};

    /// The W118 messages of a program, with their lines.
    fn w118(src: &str) -> Vec<(usize, String)> {
        let out = compile("t.nc", src.as_bytes(), &Options::default());
        out.diags
            .iter()
            .filter(|(_, d)| d.code == "W118")
            .map(|(_, d)| {
                let line = src[..d.span.start as usize].matches('\n').count() + 1;
                (line, d.message.clone())
            })
            .collect()
    }

    /// Lead 3 at 1500 rpm: v = 3 × 25 = 75 mm/s. Z keeps back
    /// 3 × 1000/60 = 50 of its 2000 mm/s² for the spindle, so it needs
    /// 75² / (2 × 1950) = 1.442 mm to reach thread speed, and
    /// 75² / (2 × 2000) = 1.406 mm to stop; the block gives 1 mm.
    #[test]
    fn a_thread_that_starts_too_close() {
        let src = "O1\nG97 S1500 M03\nG00 X30 Z1\nG32 Z0 F3\nG00 X40\nM30\n";
        let w = w118(src);
        assert_eq!(w.len(), 2, "{w:?}");
        assert_eq!(w[0].0, 4);
        assert!(
            w[0].1.contains("needs 1.442 mm to reach thread speed"),
            "{}",
            w[0].1
        );
        assert!(w[0].1.contains("gives 1.000 mm"), "{}", w[0].1);
        assert!(w[1].1.contains("needs 1.406 mm to stop"), "{}", w[1].1);
        // From Z3 both fit.
        assert!(w118(&src.replace("Z1\n", "Z3\n")).is_empty());
    }

    /// A 45° pull-out of 0.5 mm at the end of a chain (lead 3, 1500 rpm):
    /// X limits the leg's path to 1500/√½, Z's share is 1500 mm/s², so Z
    /// needs 75² / 3000 = 1.875 mm to stop: the chamfer block is named, the
    /// long thread before it is not.
    #[test]
    fn a_pull_out_too_short_to_stop_in() {
        let src = "O1\nG97 S1500 M03\nG00 X30 Z5\nG32 Z-20 F3\nG32 X31 Z-20.5\nG00 X40\nM30\n";
        let w = w118(src);
        assert_eq!(w.len(), 1, "{w:?}");
        assert_eq!(w[0].0, 5);
        assert!(w[0].1.contains("needs 1.875 mm to stop"), "{}", w[0].1);
        assert!(w[0].1.contains("gives 0.500 mm"), "{}", w[0].1);
    }

    /// A G92 cycle repeats its passes in one block: one warning for it.
    /// Each pass: RAPID to X23.2 Z0.2, THREAD to Z0, so 0.2 mm of Z at
    /// lead 2 × 1200/60 = 40 mm/s against 40² / (2 × (2000 − 2 × 1000/60))
    /// = 0.407 mm.
    #[test]
    fn a_cycle_is_named_once() {
        let src = "O1\nG97 S1200 M03\nG00 X26 Z0.2\nG92 X23.2 Z0 F2\nX22.8\nG00 X40\nM30\n";
        let w = w118(src);
        let lines: Vec<usize> = w.iter().map(|(l, _)| *l).collect();
        assert!(lines.contains(&4) && lines.contains(&5), "{w:?}");
        assert_eq!(
            w.iter()
                .filter(|(l, m)| *l == 4 && m.contains("reach"))
                .count(),
            1
        );
        assert!(w[0].1.contains("needs 0.407 mm"), "{}", w[0].1);
    }

    /// A subprogram run twice (M98 L2) passes its thread twice: each
    /// warning once, at the block, as the first test's two.
    #[test]
    fn a_block_run_again_is_named_once() {
        let src = "O1\nG97 S1500 M03\nM98 P2 L2\nM30\nO2\nG00 X30 Z1\nG32 Z0 F3\nG00 X40\nM99\n";
        let w = w118(src);
        let lines: Vec<usize> = w.iter().map(|(l, _)| *l).collect();
        assert_eq!(lines, [7, 7], "{w:?}");
        assert!(w[0].1.contains("reach") && w[1].1.contains("stop"), "{w:?}");
    }

    /// S from a variable: the compile-time run of the program with macros
    /// knows it (W124's run), and checks it as the dry run checks the
    /// static program with S1500 written; from #500, which `--vars` may
    /// set, the compiler cannot know it.
    #[test]
    fn a_computed_speed_is_checked_where_the_run_knows_it() {
        let src = "O1\n#1=1500\nG97 S#1 M03\nG00 X30 Z1\nG32 Z0 F3\nG00 X40\nM30\n";
        let literal = src.replace("#1=1500", "(S1500)").replace("S#1", "S1500");
        let w = w118(&literal);
        assert_eq!(w.iter().map(|(l, _)| *l).collect::<Vec<_>>(), [5, 5]);
        assert_eq!(w118(src), w);
        assert!(w118(&src.replace("#1=1500", "#1=#500")).is_empty());
    }

    /// A G32 with run-out words waits for the next block to know whether
    /// it ends its chain; its warnings still name its own line (3), not
    /// the M30 it is printed with. Lead 4 at 1500 rpm is 6000 mm/min, over
    /// Z's 5000 (W126); 100 mm/s stops in 100² / (2 × 2000) = 2.5 mm, more
    /// than the run-out's K2 (W118).
    #[test]
    fn a_waiting_thread_block_is_named_by_its_own_line() {
        let src = "G97 S1500 M03\nG00 X30 Z5\nG32 Z-20 F4 J1 K2\nM30\n";
        let out = compile("t.nc", src.as_bytes(), &Options::default());
        let found: Vec<(&str, usize)> = out
            .diags
            .iter()
            .map(|(_, d)| {
                (
                    d.code,
                    src[..d.span.start as usize].matches('\n').count() + 1,
                )
            })
            .collect();
        assert_eq!(found, [("W126", 3), ("W118", 3)]);
        let w = w118(src);
        assert!(w[0].1.contains("needs 2.500 mm to stop"), "{}", w[0].1);
    }

    /// A thread block that does not move (Z5 from Z5) is no leg: the
    /// next block (25 mm) starts the chain. Lead 6 at 100 rpm is 10 mm/s,
    /// which Z reaches within about 10² / (2 × 2000) = 0.025 mm.
    #[test]
    fn a_thread_block_that_does_not_move_is_no_leg() {
        let src = "G97 S100 M03\nG00 X30 Z5\nG32 Z5 F6\nG32 Z-20\nG00 X40\nM30\n";
        assert!(w118(src).is_empty(), "{:?}", w118(src));
    }
}
