//! `gbvm run --stats=json`: the cycle statistics as one JSON object, each
//! duration both in seconds and as `h:mm:ss`. The shape is documented in
//! `docs/formats.md`.

use runtime::stats::{Hms, Stats};
use serde::{Deserialize, Serialize};

#[derive(Debug, Serialize, Deserialize, PartialEq)]
pub struct Duration {
    pub s: f64,
    pub hms: String,
}

impl Duration {
    /// Seconds to the millisecond: a sum of periods carries rounding
    /// noise in its last digits.
    fn of(s: f64) -> Duration {
        Duration {
            s: (s * 1000.0).round() / 1000.0,
            hms: Hms(s).to_string(),
        }
    }
}

#[derive(Debug, Serialize, Deserialize, PartialEq)]
pub struct ToolTime {
    pub tool: u32,
    pub time: Duration,
}

#[derive(Debug, Serialize, Deserialize, PartialEq)]
pub struct Operation {
    pub tool: u32,
    /// Where it began: the file and line of its T block.
    pub file: String,
    pub line: u32,
    pub time: Duration,
    pub cut_mm: f64,
    pub rapid_mm: f64,
}

/// Where an interrupted run stopped.
#[derive(Debug, Serialize, Deserialize, PartialEq)]
pub struct Stopped {
    pub file: String,
    pub line: u32,
}

#[derive(Debug, Serialize, Deserialize, PartialEq)]
pub struct Report {
    pub cycle_time: Duration,
    pub per_tool: Vec<ToolTime>,
    pub operations: Vec<Operation>,
    pub cut_mm: f64,
    pub thread_mm: f64,
    pub rapid_mm: f64,
    /// Degrees the C axis turned; absent without a C axis.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub c_deg: Option<f64>,
    pub blocks: u64,
    /// Present when the run was interrupted (Ctrl-C): the figures are
    /// those of the run so far.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub interrupted_at: Option<Stopped>,
    /// What the loop JIT did; absent when it compiled nothing.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub jit: Option<Jit>,
}

/// The loop JIT's work in a run (`gbvm run --jit`).
#[derive(Debug, Serialize, Deserialize, PartialEq)]
pub struct Jit {
    pub loops_compiled: u32,
    /// Of those, loops compiled again with the optimiser after a long run.
    #[serde(default)]
    pub loops_optimized: u32,
    /// Loops it could not compile (they ran interpreted).
    pub loops_failed: u32,
    pub compile_ms: f64,
    /// Times compiled code was entered.
    pub entries: u64,
    /// NC blocks the code ran itself (a direct call into the kernel).
    pub blocks: u64,
}

impl Jit {
    /// The report of a tier that compiled (or tried to compile) a loop.
    pub fn of(s: vm::TierStats) -> Option<Jit> {
        (s.compiled + s.failed > 0).then(|| Jit {
            loops_compiled: s.compiled,
            loops_optimized: s.optimized,
            loops_failed: s.failed,
            compile_ms: s.compile_ns as f64 / 1e6,
            entries: s.entries,
            blocks: s.blocks,
        })
    }

    /// The line of `gbvm --stats`.
    pub fn line(&self) -> String {
        let failed = match self.loops_failed {
            0 => String::new(),
            n => format!(" ({n} left interpreted)"),
        };
        let optimized = match self.loops_optimized {
            0 => String::new(),
            n => format!(" ({n} again, optimised)"),
        };
        format!(
            "jit: {} loops compiled{optimized} in {:.2} ms{failed}, code entered {} times, {} blocks run from it\n",
            self.loops_compiled, self.compile_ms, self.entries, self.blocks
        )
    }
}

impl Report {
    /// `files` names the module's source files (`SetPoint::file` indexes).
    pub fn new(
        s: &Stats,
        files: &[String],
        interrupted_at: Option<Stopped>,
        jit: Option<Jit>,
    ) -> Report {
        let name = |i: u16| files.get(i as usize).cloned().unwrap_or_default();
        Report {
            cycle_time: Duration::of(s.total_s),
            per_tool: s
                .per_tool
                .iter()
                .map(|&(tool, t)| ToolTime {
                    tool,
                    time: Duration::of(t),
                })
                .collect(),
            operations: s
                .operations
                .iter()
                .map(|o| Operation {
                    tool: o.tool,
                    file: name(o.file),
                    line: o.line,
                    time: Duration::of(o.time_s),
                    cut_mm: o.cut_mm,
                    rapid_mm: o.rapid_mm,
                })
                .collect(),
            cut_mm: s.cut_mm,
            thread_mm: s.thread_mm,
            rapid_mm: s.rapid_mm,
            c_deg: s.c_deg,
            blocks: s.blocks,
            interrupted_at,
            jit,
        }
    }

    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_default()
    }
}
