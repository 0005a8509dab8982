//! What a motion controller (the runtime) may read from the kernel and
//! tell it, so that it never reaches into [`State`](super::state::State):
//! where the programmed point is, whether the last block ends in an exact
//! stop, the G22 area in force, the tool offset tables, and where the axes
//! really stopped after a skip or a reset.

use crate::base::point::Pt;
use crate::exec::stroke::Area;
use crate::exec::switches::Switch;
use crate::exec::Nc;

impl Nc {
    /// The programmed point after the last block, work coordinates.
    pub fn position(&self) -> Pt {
        self.st.pos
    }

    /// A G32/G34 block with run-out words waits for the next block, which
    /// says whether it ends its chain (and runs out): its thread legs are
    /// not printed yet, though [`position`](Nc::position) is already its
    /// end point.
    pub fn thread_waiting(&self) -> bool {
        self.st.cycles.chain.pending.is_some()
    }

    /// The printed moves are apart from the programmed point on purpose:
    /// a move waits in the contour queue for the next block (an L/D
    /// corner word, a move given by its angle, a compensated element whose
    /// end depends on the next), or tool-nose compensation offsets every
    /// printed point from the programmed one (G41/G42 in force, or a
    /// cancel to come). A motion controller must then follow the printed
    /// moves only, not reach for [`position`](Nc::position).
    pub fn contour_held(&self) -> bool {
        self.st.contour.is_holding() || crate::exec::comp::compensating(self)
    }

    /// The last block was a G32/G34 move, so that the next one may
    /// continue its chain. Read after a block that found a block waiting
    /// ([`thread_waiting`](Nc::thread_waiting)): when it continues the
    /// chain, the waiting block was printed as one leg; when not, with its
    /// run-out, as two.
    pub fn thread_chain_open(&self) -> bool {
        self.st.cycles.chain.open
    }

    /// The work zero in machine coordinates (EXOFS + G5x + G50 + G52).
    pub fn origin(&self) -> Pt {
        self.st.origin()
    }

    /// The last block ends in an exact stop (G09 in it, or G61 in force):
    /// the motion must not blend it into the next one.
    /// `#3004` bit 2 turns it off.
    pub fn exact_stop(&self) -> bool {
        self.st.exact_stop && !self.switch(Switch::NoExactStop)
    }

    /// Whether the program has set `s` (`#3003`, `#3004`).
    pub fn switch(&self, s: Switch) -> bool {
        self.st.switches.is_on(s)
    }

    /// The area stored stroke check 2 forbids while G22 is in force.
    pub fn stroke_area(&self) -> Option<Area> {
        self.st.stroke2
    }

    /// Geometry + wear of tool offset `d` as (X diameter, Z) sums; zero
    /// for a number outside the tables.
    pub fn tool_offset(&self, d: u32) -> (f64, f64) {
        let Some(i) = (d as usize)
            .checked_sub(1)
            .filter(|&i| i < self.st.geom.len())
        else {
            return (0.0, 0.0);
        };
        let (g, w) = (self.st.geom[i], self.st.wear[i]);
        (g[0] + w[0], g[1] + w[1])
    }

    /// The axes stand at `work` (work coordinates), as after a reset: the
    /// next block starts there.
    pub fn set_position(&mut self, work: Pt) {
        self.st.pos = work;
        self.st.printed = None;
    }

    /// The C axis angle after the last block, degrees (0 without a C
    /// axis).
    pub fn c(&self) -> f64 {
        self.st.c
    }

    /// The C axis stands at `c` degrees, as after a reset: the next block
    /// turns it from there (an `H` word, #5003).
    pub fn set_c(&mut self, c: f64) {
        self.st.c = c;
    }

    /// A G31 move ended: the axes stopped at `stop` and the signal came at
    /// `hit` (both work coordinates). The next block starts at `stop`;
    /// #5061/#5062 read `hit`.
    pub fn skip_ended(&mut self, stop: Pt, hit: Pt) {
        self.st.pos = stop;
        self.st.printed = None;
        self.st.skip = Some(hit);
    }
}

#[cfg(test)]
mod tests {
    use crate::base::machine::Machine;
    use crate::base::point::Pt;
    use crate::exec::Nc;

    #[test]
    fn a_skip_moves_the_programmed_point_and_stores_the_hit() {
        let mut nc = Nc::new(Machine::reference());
        nc.skip_ended(Pt::new(10.0, -5.0), Pt::new(10.0, -4.5));
        assert_eq!(nc.position(), Pt::new(10.0, -5.0));
        assert_eq!(nc.st.skip, Some(Pt::new(10.0, -4.5)));
        nc.set_position(Pt::new(1.0, 2.0));
        assert_eq!(nc.position(), Pt::new(1.0, 2.0));
    }

    #[test]
    fn offsets_outside_the_tables_are_zero() {
        let mut nc = Nc::new(Machine::reference());
        nc.st.geom[2] = [4.0, -1.0, 0.4];
        nc.st.wear[2] = [0.5, 0.25, 0.0, 0.0];
        // Offset 3 is index 2: 4 + 0.5 and -1 + 0.25.
        assert_eq!(nc.tool_offset(3), (4.5, -0.75));
        assert_eq!(nc.tool_offset(0), (0.0, 0.0));
        assert_eq!(nc.tool_offset(10_000), (0.0, 0.0));
    }
}
