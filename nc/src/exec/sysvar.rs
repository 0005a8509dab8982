//! System variables (dialect.md §7.2) that live in the kernel's state:
//! offsets, clocks, modal information, positions, work offsets.

use alloc::format;

use crate::base::error::{fail, Alarm, NcError};
use crate::base::event::Event;
use crate::base::gcode;
use crate::base::point::Pt;
use crate::exec::{Nc, Sink};

/// Is `n` a system variable the kernel answers (1000 and above)?
pub fn is_system(n: u32) -> bool {
    n >= 1000
}

/// Is `n` a current position (#5021–#5023 machine, #5041–#5043 local)?
/// A real control reads these only when the motion before them has ended
/// (the block-end positions #5001… are known ahead and need no wait).
pub fn is_current_position(n: u32) -> bool {
    matches!(n, 5021..=5023 | 5041..=5043)
}

fn not_readable(n: u32) -> NcError {
    NcError::new(
        Alarm::VariableAccess,
        format!("#{n} is not a readable variable"),
    )
}

fn read_only(n: u32) -> NcError {
    NcError::new(Alarm::VariableAccess, format!("#{n} is read-only"))
}

/// `None` is the vacant value.
type Value = Option<f64>;

impl Nc {
    /// Reads system variable `n`.
    pub fn read_var(&self, n: u32) -> Result<Value, NcError> {
        let (st, m) = (&self.st, &self.machine);
        let v = match n {
            1000..=1015 => Some(((self.machine.host.inputs >> (n - 1000)) & 1) as f64),
            1032 => Some((self.machine.host.inputs & 0xffff) as f64),
            1100..=1115 => Some(((st.outputs >> (n - 1100)) & 1) as f64),
            1132 => Some(st.outputs as f64),
            2001..=2032 => Some(m.from_diameter(st.wear[(n - 2001) as usize][0])),
            2101..=2132 => Some(st.wear[(n - 2101) as usize][1]),
            2201..=2232 => Some(st.wear[(n - 2201) as usize][2]),
            2301..=2332 => Some(st.wear[(n - 2301) as usize][3]),
            2701..=2732 => Some(m.from_diameter(st.geom[(n - 2701) as usize][0])),
            2801..=2832 => Some(st.geom[(n - 2801) as usize][1]),
            2901..=2932 => Some(st.geom[(n - 2901) as usize][2]),
            3001 => Some(st.clock_ms),
            3002 => Some(st.clock_ms / 3_600_000.0),
            3003 | 3004 => Some(st.switches.read(n)),
            3011 => Some(self.machine.host.date as f64),
            3012 => Some(self.machine.host.time as f64),
            3901 => Some(st.parts),
            3902 => Some(st.parts_required),
            4001..=4021 => {
                let g = (n - 4000) as usize;
                gcode::power_on(g as u8).map(|_| st.modal.group(g as u8) as f64 / 10.0)
            }
            4102 | 4107 | 4108 | 4109 | 4111 | 4113 | 4119 | 4120 => {
                let letter = [
                    (4102, b'B'),
                    (4107, b'D'),
                    (4108, b'E'),
                    (4109, b'F'),
                    (4111, b'H'),
                    (4113, b'M'),
                    (4119, b'S'),
                    (4120, b'T'),
                ]
                .iter()
                .find(|(v, _)| *v == n)
                .map_or(b'A', |(_, l)| *l);
                let v = st.last[(letter - b'A') as usize];
                (!v.is_nan()).then_some(v)
            }
            // Last N and O: the VM answers them from its module.
            4114 | 4115 => None,
            // C: block end and current angle alike (the C axis has no
            // offsets, so machine and local C are the same).
            5003 | 5023 | 5043 if self.machine.axes.c.enabled => Some(st.c),
            5001 => Some(m.programmed_x(st.pos.r)),
            5002 => Some(st.pos.z),
            5021 => Some(m.programmed_x(st.machine_pos().r)),
            5022 => Some(st.machine_pos().z),
            5041 => Some(m.programmed_x(st.pos.r)),
            5042 => Some(st.pos.z),
            5061 => st.skip.map(|p| m.programmed_x(p.r)),
            5062 => st.skip.map(|p| p.z),
            5081 => Some(m.from_diameter(self.active_offset(true))),
            5082 => Some(self.active_offset(false)),
            5201 => Some(m.programmed_x(st.exofs.r)),
            5202 => Some(st.exofs.z),
            5221..=5322 => {
                let (sys, axis) = ((n - 5221) / 20, (n - 5221) % 20);
                match axis {
                    0 => Some(m.programmed_x(st.work[sys as usize].r)),
                    1 => Some(st.work[sys as usize].z),
                    _ => return Err(not_readable(n)),
                }
            }
            _ => return Err(not_readable(n)),
        };
        Ok(v)
    }

    fn active_offset(&self, x: bool) -> f64 {
        let Some(i) = (self.st.offset as usize).checked_sub(1).filter(|&i| i < 32) else {
            return 0.0;
        };
        let k = if x { 0 } else { 1 };
        self.st.geom[i][k] + self.st.wear[i][k]
    }

    /// Writes system variable `n`; a work-offset write that moves the zero
    /// prints `ORIGIN`.
    pub fn write_var(&mut self, n: u32, v: Value, sink: &mut dyn Sink) -> Result<(), NcError> {
        let x = v.unwrap_or(0.0);
        let before = self.st.origin();
        let (st, m) = (&mut self.st, &self.machine);
        match n {
            1100..=1115 => {
                let bit = 1u32 << (n - 1100);
                st.outputs = if x != 0.0 {
                    st.outputs | bit
                } else {
                    st.outputs & !bit
                };
            }
            1132 => st.outputs = (x.max(0.0) as u32) & 0xffff,
            2001..=2032 => st.wear[(n - 2001) as usize][0] = m.diameter(x),
            2101..=2132 => st.wear[(n - 2101) as usize][1] = x,
            2201..=2232 => st.wear[(n - 2201) as usize][2] = x,
            2301..=2332 => st.wear[(n - 2301) as usize][3] = x,
            2701..=2732 => st.geom[(n - 2701) as usize][0] = m.diameter(x),
            2801..=2832 => st.geom[(n - 2801) as usize][1] = x,
            2901..=2932 => st.geom[(n - 2901) as usize][2] = x,
            3001 => st.clock_ms = x,
            3002 => st.clock_ms = x * 3_600_000.0,
            3003 | 3004 => st.switches.write(n, x)?,
            3901 => st.parts = x,
            3902 => st.parts_required = x,
            5201 => st.exofs.r = m.radial(x),
            5202 => st.exofs.z = x,
            5221..=5322 => {
                let (sys, axis) = (((n - 5221) / 20) as usize, (n - 5221) % 20);
                match axis {
                    0 => st.work[sys].r = m.radial(x),
                    1 => st.work[sys].z = x,
                    _ => return Err(read_only(n)),
                }
            }
            1000..=1015 | 1032 | 3011 | 3012 | 4001..=4120 | 5001..=5082 => {
                return Err(read_only(n))
            }
            _ => {
                return fail(
                    Alarm::VariableAccess,
                    format!("#{n} is not a writable variable"),
                )
            }
        }
        // The tool stays where it is on the machine; its work coordinates
        // change with the zero.
        let after = self.st.origin();
        if after != before {
            if let Some(what) = crate::exec::plane::mode_name(self) {
                // (The plane would move under the tool: G54–G59 are
                // refused there too.)
                return fail(
                    Alarm::PolarInComp,
                    format!(
                        "#{n} moves the work zero during {what}: change it before the mode starts"
                    ),
                );
            }
            // A running compensation is suspended first (comp.md §8).
            crate::exec::comp::suspend(self, sink)?;
            let machine = self.st.pos.add(before);
            self.st.pos = machine.sub(after);
            if (after.r - before.r).abs() * 2.0 > 1e-6 || (after.z - before.z).abs() > 1e-6 {
                let origin = Event::Origin {
                    x: after.x(),
                    z: after.z,
                };
                // Behind a move that still waits for its corner.
                self.emit_in_order(origin, sink);
            }
        }
        Ok(())
    }

    /// The skip position as #995/#996 store it.
    pub fn skip_point(&self) -> Option<Pt> {
        self.st.skip
    }
}
