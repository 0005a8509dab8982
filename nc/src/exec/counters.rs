//! The production counters a controller carries from part to part: the
//! parts machined and required (#3901, #3902) and what each tool of the
//! machine file's tool-life groups has used. A run starts with them and
//! counts on them; a controller keeps what a finished run counted
//! (docs/embedding.md, "Production runs"). A plain `gbvm run` starts
//! every run from zero, so that no run depends on an earlier one.
//!
//! A run's counting is taken as a change (what the run ended with less
//! what it started with) and added to the counters as they stand then,
//! so an operator's edit made while the run went on is kept, and the
//! run's M30 still counts on it, as a control's part counter does.

use alloc::format;
use alloc::vec::Vec;

use crate::base::machine::Machine;
use crate::base::machine_check::BadKey;
use crate::exec::tool_life::{Group, ToolLife};
use crate::exec::Nc;

/// The most a part counter holds (eight digits, as a control's screen).
pub const MAX_PARTS: f64 = 99_999_999.0;

/// Parts machined (#3901: M30 adds one) and parts required (#3902).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Parts {
    pub machined: f64,
    pub required: f64,
}

impl Parts {
    /// The required count is set and reached (a control's "parts
    /// reached" signal; what the machine does then is the PLC's).
    pub fn reached(&self) -> bool {
        self.required > 0.0 && self.machined >= self.required
    }

    /// Whole numbers within 0 ..= [`MAX_PARTS`], as an operator enters them.
    pub fn valid(&self) -> bool {
        [self.machined, self.required]
            .iter()
            .all(|v| (0.0..=MAX_PARTS).contains(v) && libm::trunc(*v) == *v)
    }

    /// [`Parts::valid`], or why not.
    pub fn check(&self) -> Result<(), BadKey> {
        if self.valid() {
            return Ok(());
        }
        Err(BadKey {
            key: "parts".into(),
            msg: format!(
                "parts machined {} and required {} must be whole numbers 0 … {MAX_PARTS}",
                self.machined, self.required
            ),
        })
    }
}

/// The counters: the parts, and the machine file's tool-life groups with
/// each tool's use and the tool a `Txx99` selected last.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Counters {
    pub parts: Parts,
    pub life: Vec<Group>,
}

impl Counters {
    /// Zero parts, and the machine file's groups unused.
    pub fn power_on(m: &Machine) -> Counters {
        Counters {
            parts: Parts::default(),
            life: ToolLife::power_on(m).groups,
        }
    }

    /// Adds what a run counted: `end` less `start`. A run whose table is
    /// no longer the machine file's (a `G10 L3` replaced it, for that run
    /// only: machine.md) leaves the tool life as it was.
    pub fn add_run(&mut self, start: &Counters, end: &Counters) {
        let p = &mut self.parts;
        p.machined += end.parts.machined - start.parts.machined;
        p.required += end.parts.required - start.parts.required;
        if !start.same_groups(end) || !start.same_groups(self) {
            return;
        }
        for ((now, s), e) in self.life.iter_mut().zip(&start.life).zip(&end.life) {
            for ((u, su), eu) in now.used.iter_mut().zip(&s.used).zip(&e.used) {
                *u += eu - su;
            }
            if e.current != s.current {
                now.current = e.current;
            }
        }
    }

    /// The same tool-life groups: numbers, lives, units and tools.
    pub fn same_groups(&self, other: &Counters) -> bool {
        let (a, b) = (&self.life, &other.life);
        a.len() == b.len()
            && a.iter().zip(b).all(|(a, b)| {
                a.number == b.number && a.life == b.life && a.unit == b.unit && a.tools == b.tools
            })
    }

    /// Counters a host kept (over a power-off) fit the machine whose
    /// counters are `now`: valid parts, the machine file's groups, uses
    /// finite and not negative, a current tool within its group.
    pub fn check_fits(&self, now: &Counters) -> Result<(), BadKey> {
        self.parts.check()?;
        let bad_use = |g: &Group| {
            g.used.iter().any(|u| !u.is_finite() || *u < 0.0)
                || g.current.is_some_and(|c| c >= g.tools.len())
        };
        let why = if !self.same_groups(now) {
            "the tool-life groups are not the machine file's"
        } else if self.life.iter().any(bad_use) {
            "a tool's use is negative or not finite, or its current tool is not in the group"
        } else {
            return Ok(());
        };
        Err(BadKey {
            key: "counters".into(),
            msg: why.into(),
        })
    }

    /// Tool-life group `number` as new: its tools unused, none selected
    /// (the operator changed the inserts). Refused for a group the
    /// machine file does not have.
    pub fn renew_group(&mut self, number: u32) -> Result<(), BadKey> {
        let Some(g) = self.life.iter_mut().find(|g| g.number == number) else {
            return Err(BadKey {
                key: "tool_life.group".into(),
                msg: format!("the machine file has no tool-life group {number}"),
            });
        };
        g.used.iter_mut().for_each(|u| *u = 0.0);
        g.current = None;
        Ok(())
    }
}

impl Nc {
    /// Starts this run's counting from `c` (a fresh run: nothing counted
    /// yet).
    pub fn set_counters(&mut self, c: &Counters) {
        self.st.parts = c.parts.machined;
        self.st.parts_required = c.parts.required;
        self.st.data.life = ToolLife {
            groups: c.life.clone(),
            ..ToolLife::default()
        };
    }

    /// The counters as the run stands now.
    pub fn counters(&self) -> Counters {
        Counters {
            parts: Parts {
                machined: self.st.parts,
                required: self.st.parts_required,
            },
            life: self.st.data.life.groups.clone(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exec::tool_life::LifeUnit;

    fn group(number: u32, used: &[f64]) -> Group {
        let mut g = Group::new(number, 3.0, LifeUnit::Count);
        for (i, &u) in used.iter().enumerate() {
            g.add(101 + i as u32 * 101);
            g.used[i] = u;
        }
        g
    }

    fn counters(machined: f64, used: &[f64]) -> Counters {
        Counters {
            parts: Parts {
                machined,
                required: 10.0,
            },
            life: alloc::vec![group(1, used)],
        }
    }

    #[test]
    fn a_run_adds_its_change_to_an_edit_made_meanwhile() {
        // The run started at 4 parts and ended at 5; meanwhile the
        // operator set the counter to 0: the M30 counts on the 0.
        let start = counters(4.0, &[1.0, 0.0]);
        let mut end = counters(5.0, &[3.0, 1.0]);
        end.life[0].current = Some(1);
        let mut now = counters(0.0, &[1.0, 0.0]);
        now.add_run(&start, &end);
        assert_eq!(now.parts.machined, 1.0);
        assert_eq!(now.parts.required, 10.0);
        assert_eq!(now.life[0].used, [3.0, 1.0]);
        assert_eq!(now.life[0].current, Some(1));
    }

    #[test]
    fn a_table_replaced_by_the_run_leaves_the_life_as_it_was() {
        let start = counters(0.0, &[1.0]);
        let mut end = counters(1.0, &[2.0]);
        end.life[0].tools[0] = 505;
        let mut now = start.clone();
        now.add_run(&start, &end);
        assert_eq!(now.parts.machined, 1.0);
        assert_eq!(now.life[0].used, [1.0]);
    }

    #[test]
    fn renewing_a_group_clears_its_use() {
        let mut c = counters(0.0, &[3.0, 2.0]);
        c.life[0].current = Some(1);
        assert_eq!(c.renew_group(1), Ok(()));
        assert_eq!(c.life[0].used, [0.0, 0.0]);
        assert_eq!(c.life[0].current, None);
        assert!(c.renew_group(2).is_err());
    }

    #[test]
    fn parts_are_whole_and_within_eight_digits() {
        let p = |machined, required| Parts { machined, required };
        assert!(p(0.0, 0.0).valid() && p(MAX_PARTS, 5.0).valid());
        assert!(!p(-1.0, 0.0).valid() && !p(1.5, 0.0).valid());
        assert!(!p(0.0, f64::NAN).valid() && !p(1e8, 0.0).valid());
        assert!(p(5.0, 5.0).reached() && !p(5.0, 0.0).reached() && !p(4.0, 5.0).reached());
    }
}
