//! Cycle statistics from the set points: time in total, per tool and per
//! operation, distance cut (feeds and threads) and at rapid (the tool's
//! path over the work, C's turn included), blocks executed. An operation is a stretch of the run with one active tool:
//! it begins at the period the tool becomes active (the T block) and ends
//! when another tool does, so a tool used twice has two operations.

use crate::interpolate::{Motion, SetPoint};
use alloc::vec::Vec;
use core::fmt;

/// One operation: a stretch of the run with one active tool.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Operation {
    /// The active tool's number.
    pub tool: u32,
    /// The source file of its first period (an index into the module's
    /// file table): the T block, or the first move after it when the
    /// change took no period (at the start).
    pub file: u16,
    /// The source line of that period.
    pub line: u32,
    /// Seconds it lasted.
    pub time_s: f64,
    /// Path length at feed (threads included), mm.
    pub cut_mm: f64,
    /// Path length at rapid, mm.
    pub rapid_mm: f64,
}

#[derive(Debug, Clone, Default, PartialEq)]
/// Cycle time per tool, distances and blocks, summed over the periods of a run.
pub struct Stats {
    /// Seconds, from the first period to the last.
    pub total_s: f64,
    /// (tool number, seconds while it was the active tool), by first use.
    pub per_tool: Vec<(u32, f64)>,
    /// The operations in run order.
    pub operations: Vec<Operation>,
    /// Path length at feed (threads included), mm.
    pub cut_mm: f64,
    /// Of which threads, mm.
    pub thread_mm: f64,
    /// Path length at rapid, mm.
    pub rapid_mm: f64,
    /// How far the C axis turned, degrees; `None` without a C axis.
    pub c_deg: Option<f64>,
    /// Blocks executed, as the block budget counts them
    /// ([`crate::Controller::blocks`]).
    pub blocks: u64,
    last: Option<Place>,
    last_c: Option<f64>,
    dt: f64,
}

impl Stats {
    /// Empty statistics for this interpolation period (s).
    pub fn new(period_s: f64) -> Stats {
        Stats {
            dt: period_s,
            ..Stats::default()
        }
    }

    /// Accounts one period.
    pub fn add(&mut self, p: &SetPoint) {
        self.total_s = p.time_s;
        match self.per_tool.iter_mut().find(|(t, _)| *t == p.tool) {
            Some((_, s)) => *s += self.dt,
            None => self.per_tool.push((p.tool, self.dt)),
        }
        if self.operations.last().is_none_or(|o| o.tool != p.tool) {
            self.operations.push(Operation {
                tool: p.tool,
                file: p.file,
                line: p.line,
                ..Operation::default()
            });
        }
        let now = Place::of(p);
        // Before the first period the axes stand at machine zero (the
        // engine starts there): its travel counts too.
        let before = self.last.unwrap_or(Place {
            r: 0.0,
            z: 0.0,
            ..now
        });
        let d = before.to(&now);
        self.last = Some(now);
        if let Some(op) = self.operations.last_mut() {
            op.time_s += self.dt;
            match p.motion {
                Motion::Feed | Motion::Arc | Motion::Thread => op.cut_mm += d,
                Motion::Rapid => op.rapid_mm += d,
                Motion::None | Motion::Dwell => {}
            }
        }
        match p.motion {
            Motion::Feed | Motion::Arc => self.cut_mm += d,
            Motion::Thread => {
                self.cut_mm += d;
                self.thread_mm += d;
            }
            Motion::Rapid => self.rapid_mm += d,
            Motion::None | Motion::Dwell => {}
        }
        if let Some(c) = p.c {
            let turned = self.last_c.map_or(0.0, |l| (c - l).abs());
            self.c_deg = Some(self.c_deg.unwrap_or(0.0) + turned);
            self.last_c = Some(c);
        }
    }
}

/// Where the tool stands over the work in a period, for its travel.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Place {
    /// The axes' positions (tool offsets included: the tool's real
    /// travel), X back to a radius.
    r: f64,
    z: f64,
    /// The tool's distance from the spindle centre (work X as a radius)
    /// and the C angle (radians; 0 without a C axis).
    radius: f64,
    c: f64,
}

impl Place {
    fn of(p: &SetPoint) -> Place {
        Place {
            r: p.axis_x * 0.5,
            z: p.axis_z,
            radius: libm::fabs(p.x) * 0.5,
            c: p.c.unwrap_or(0.0).to_radians(),
        }
    }

    /// The tool's travel over the work from here to `to`: the axes' step
    /// and what C's turn carries the work under the tool, at the tool's
    /// distance from the centre (exact along a helix; a period's step
    /// elsewhere). In polar and cylindrical interpolation that is the
    /// path in the plane.
    fn to(&self, to: &Place) -> f64 {
        let turn = 0.5 * (self.radius + to.radius) * (to.c - self.c);
        libm::hypot(libm::hypot(to.r - self.r, to.z - self.z), turn)
    }
}

/// A duration as `h:mm:ss`, rounded to the second (as a machine's cycle
/// time display shows it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hms(pub f64);

impl fmt::Display for Hms {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = if self.0.is_finite() && self.0 > 0.0 {
            libm::round(self.0) as u64
        } else {
            0
        };
        write!(f, "{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60)
    }
}

impl fmt::Display for Stats {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "cycle time: {} ({:.3} s)",
            Hms(self.total_s),
            self.total_s
        )?;
        writeln!(f, "per tool:")?;
        for (t, s) in &self.per_tool {
            writeln!(f, "  T{t:02}: {} ({s:.3} s)", Hms(*s))?;
        }
        writeln!(f, "per operation:")?;
        for (i, o) in self.operations.iter().enumerate() {
            writeln!(
                f,
                "  {:>3}. T{:02} from line {}: {} ({:.3} s), cut {:.3} mm, rapid {:.3} mm",
                i + 1,
                o.tool,
                o.line,
                Hms(o.time_s),
                o.time_s,
                o.cut_mm,
                o.rapid_mm
            )?;
        }
        writeln!(
            f,
            "distance cut: {:.3} mm (threads {:.3} mm)",
            self.cut_mm, self.thread_mm
        )?;
        writeln!(f, "distance rapid: {:.3} mm", self.rapid_mm)?;
        if let Some(c) = self.c_deg {
            writeln!(f, "C axis turned: {c:.3} deg")?;
        }
        writeln!(f, "blocks: {}", self.blocks)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::string::ToString;

    fn point(t: f64, z: f64, c: Option<f64>, motion: Motion) -> SetPoint {
        SetPoint {
            time_s: t,
            x: 20.0,
            z,
            axis_x: 20.0,
            axis_z: z,
            counts: crate::Counts::default(),
            spindle_rpm: 0.0,
            spindle_turns: 0.0,
            c,
            feed: 0.0,
            line: 1,
            file: 0,
            motion,
            tool: 1,
        }
    }

    #[test]
    fn distances_and_c_rotation() {
        // Z 0 → −3 at feed, then back to −1 at rapid; C 0 → 90 → 45: it
        // turned 135°. At X20 the work turns under the tool at radius 10:
        // helices of √(3² + (10·π/2)²) and √(2² + (10·π/4)²).
        let mut s = Stats::new(0.001);
        s.add(&point(0.001, 0.0, Some(0.0), Motion::None));
        s.add(&point(0.002, -3.0, Some(90.0), Motion::Feed));
        s.add(&point(0.003, -1.0, Some(45.0), Motion::Rapid));
        let (quarter, eighth) = (
            10.0 * core::f64::consts::FRAC_PI_2,
            10.0 * core::f64::consts::FRAC_PI_4,
        );
        assert!((s.cut_mm - libm::sqrt(9.0 + quarter * quarter)).abs() < 1e-12);
        assert!((s.rapid_mm - libm::sqrt(4.0 + eighth * eighth)).abs() < 1e-12);
        assert_eq!(s.c_deg, Some(135.0));
        assert!(s.to_string().contains("C axis turned: 135.000 deg"));
        // C standing, the axes' travel alone.
        let mut s = Stats::new(0.001);
        s.add(&point(0.001, 0.0, Some(30.0), Motion::None));
        s.add(&point(0.002, -3.0, Some(30.0), Motion::Feed));
        assert_eq!(s.cut_mm, 3.0);
        // Without a C axis there is no C line.
        let mut s = Stats::new(0.001);
        s.add(&point(0.001, 0.0, None, Motion::None));
        assert_eq!(s.c_deg, None);
        assert!(!s.to_string().contains("C axis"));
    }

    #[test]
    fn the_first_period_travels_from_machine_zero() {
        // The engine starts at machine zero: a first period that has the
        // axes at Z−0.002 at rapid has travelled 0.002 mm.
        let mut s = Stats::new(0.001);
        s.add(&SetPoint {
            x: 0.0,
            axis_x: 0.0,
            ..point(0.001, -0.002, None, Motion::Rapid)
        });
        assert!((s.rapid_mm - 0.002).abs() < 1e-15, "{}", s.rapid_mm);
    }

    #[test]
    fn a_tool_used_twice_makes_two_operations() {
        // Periods of 0.5 s: T1 for two, T2 for one (a 4 mm feed), T1 for
        // one more (a 5 mm rapid from Z−4 to Z+1).
        let mut s = Stats::new(0.5);
        let at = |t, z, tool, line, motion| SetPoint {
            tool,
            line,
            ..point(t, z, None, motion)
        };
        s.add(&at(0.5, 0.0, 1, 3, Motion::None));
        s.add(&at(1.0, 0.0, 1, 4, Motion::None));
        s.add(&at(1.5, -4.0, 2, 7, Motion::Feed));
        s.add(&at(2.0, 1.0, 1, 9, Motion::Rapid));
        assert_eq!(s.per_tool, [(1, 1.5), (2, 0.5)]);
        let ops: Vec<_> = s
            .operations
            .iter()
            .map(|o| (o.tool, o.line, o.time_s, o.cut_mm, o.rapid_mm))
            .collect();
        assert_eq!(
            ops,
            [
                (1, 3, 1.0, 0.0, 0.0),
                (2, 7, 0.5, 4.0, 0.0),
                (1, 9, 0.5, 0.0, 5.0)
            ]
        );
        let text = s.to_string();
        assert!(text.contains("cycle time: 0:00:02 (2.000 s)"), "{text}");
        assert!(
            text.contains("    2. T02 from line 7: 0:00:01 (0.500 s), cut 4.000 mm"),
            "{text}"
        );
    }

    #[test]
    fn hms_rounds_to_the_second() {
        // 3725.4 s = 1 h + 2 min + 5.4 s; 59.5 s rounds up to a minute.
        assert_eq!(Hms(3725.4).to_string(), "1:02:05");
        assert_eq!(Hms(59.5).to_string(), "0:01:00");
        assert_eq!(Hms(0.2).to_string(), "0:00:00");
        assert_eq!(Hms(36_000.0).to_string(), "10:00:00");
        assert_eq!(Hms(f64::NAN).to_string(), "0:00:00");
    }
}
