//! Cycle statistics from the set points: time per tool and in total,
//! distance cut (feeds and threads) and at rapid, blocks executed.

use crate::interpolate::{Motion, SetPoint};
use alloc::vec::Vec;
use core::fmt;

#[derive(Debug, Clone, Default, PartialEq)]
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
    /// NC blocks executed.
    pub blocks: u64,
    last: Option<(f64, f64)>,
    dt: f64,
}

impl Stats {
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
        writeln!(f, "blocks: {}", self.blocks)
    }
}
