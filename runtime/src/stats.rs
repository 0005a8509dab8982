//! Cycle statistics from the set points: time per tool and in total,
//! distance cut (feeds and threads) and at rapid, blocks executed.

use crate::interpolate::{Motion, SetPoint};
use alloc::vec::Vec;
use core::fmt;

#[derive(Debug, Clone, Default, PartialEq)]
/// Cycle time per tool, distances and blocks, summed over the periods of a run.
pub struct Stats {
    /// Seconds, from the first period to the last.
    pub total_s: f64,
    /// (tool number, seconds while it was the active tool), by first use.
    pub per_tool: Vec<(u32, f64)>,
    /// Path length at feed (threads included), mm.
    pub cut_mm: f64,
    /// Of which threads, mm.
    pub thread_mm: f64,
    /// Path length at rapid, mm.
    pub rapid_mm: f64,
    /// How far the C axis turned, degrees; `None` without a C axis.
    pub c_deg: Option<f64>,
    /// NC blocks executed.
    pub blocks: u64,
    last: Option<(f64, f64)>,
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
        // Axis positions: the tool's real travel, X back to a radius.
        let now = (p.axis_x * 0.5, p.axis_z);
        if let Some((r, z)) = self.last {
            let d = libm::hypot(now.0 - r, now.1 - z);
            match p.motion {
                Motion::Feed => self.cut_mm += d,
                Motion::Thread => {
                    self.cut_mm += d;
                    self.thread_mm += d;
                }
                Motion::Rapid => self.rapid_mm += d,
                Motion::None => {}
            }
        }
        self.last = Some(now);
        if let Some(c) = p.c {
            let turned = self.last_c.map_or(0.0, |l| (c - l).abs());
            self.c_deg = Some(self.c_deg.unwrap_or(0.0) + turned);
            self.last_c = Some(c);
        }
    }
}

impl fmt::Display for Stats {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "cycle time: {:.3} s", self.total_s)?;
        for (t, s) in &self.per_tool {
            writeln!(f, "  T{t:02}: {s:.3} s")?;
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
            spindle_rpm: 0.0,
            spindle_turns: 0.0,
            c,
            feed: 0.0,
            line: 1,
            motion,
            tool: 1,
        }
    }

    #[test]
    fn distances_and_c_rotation() {
        // Z 0 → −3 at feed, then back to −1 at rapid; C 0 → 90 → 45: it
        // turned 135°.
        let mut s = Stats::new(0.001);
        s.add(&point(0.001, 0.0, Some(0.0), Motion::None));
        s.add(&point(0.002, -3.0, Some(90.0), Motion::Feed));
        s.add(&point(0.003, -1.0, Some(45.0), Motion::Rapid));
        assert_eq!((s.cut_mm, s.rapid_mm), (3.0, 2.0));
        assert_eq!(s.c_deg, Some(135.0));
        assert!(s.to_string().contains("C axis turned: 135.000 deg"));
        // Without a C axis there is no C line.
        let mut s = Stats::new(0.001);
        s.add(&point(0.001, 0.0, None, Motion::None));
        assert_eq!(s.c_deg, None);
        assert!(!s.to_string().contains("C axis"));
    }
}
