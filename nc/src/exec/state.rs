//! The state of the control between blocks: the position, offsets and
//! spindle, the modal codes and the state of each feature.

use crate::base::decimal::ten_thousandths;
use crate::base::event::SpindleDir;
use crate::base::machine::Machine;
use crate::base::point::Pt;
use crate::modal::Modal;

/// Everything a block can change and a later block can see.
#[derive(Debug, Clone)]
pub struct State {
    /// The programmed point, local coordinates (mm).
    pub pos: Pt,
    /// The C angle in degrees (machine = work: the C axis has no offsets).
    pub c: f64,
    /// The block being executed programs C/H: its moves print `C=`.
    pub c_block: bool,
    /// The code in force in each modal group.
    pub modal: Modal,
    /// EXOFS, the six work offsets, the G50 shift, the G52 origin (all in
    /// machine coordinates, r/z).
    pub exofs: Pt,
    pub work: [Pt; 6],
    pub shift: Pt,
    pub local: Pt,
    /// Modal F as written (program units).
    pub feed: f64,
    /// The (F in mm, per-rev) last printed by `FEED`.
    pub feed_printed: Option<(f64, bool)>,
    /// Spindle: rpm (G97), surface speed m/min (G96), `G50 S` limit.
    pub rpm: f64,
    pub css: f64,
    pub rpm_limit: Option<f64>,
    pub spindle: SpindleDir,
    pub tool: u32,
    pub offset: u32,
    /// Tool offset tables #2001… (wear X, Z, R, tip) and #2701… (geometry).
    pub wear: [[f64; 4]; 32],
    pub geom: [[f64; 3]; 32],
    /// The last G31 skip position.
    pub skip: Option<Pt>,
    /// Virtual clock (#3001, ms): the sum of dwells.
    pub clock_ms: f64,
    /// Last value of B D E F H M N O S T (#4102 …), NaN when never set.
    pub last: [f64; 26],
    pub parts: f64,
    /// Output signals UO0–UO15 (#1100…).
    pub outputs: u32,
    /// The last block ends in an exact stop (G09 in it, or G61 in force):
    /// the runtime must not blend it into the next one.
    pub exact_stop: bool,
    /// `#3003` and `#3004` as the program wrote them.
    pub switches: crate::exec::switches::Switches,
    /// The area stored stroke check 2 forbids while G22 is in force.
    pub stroke2: Option<crate::exec::stroke::Area>,
    /// The tool length offset the axes carry (geometry + wear of the last
    /// `TOOL`, none after a `HOME`), as the soft limits see the slide;
    /// kept only on a machine with soft limits (travel.rs).
    pub slide_off: Pt,
    /// Where the last motion event the guard passed ended (work
    /// coordinates): the printed point, which lags the programmed one
    /// while a corner or nose-radius compensation holds an element back.
    /// `None` when not known (no guard ran the last block, or the axes
    /// were set elsewhere): the next guard starts from `pos`.
    pub printed: Option<Pt>,
    pub parts_required: f64,
    /// State of the single cycles and threads (cycles module).
    pub cycles: crate::exec::cycles::CycleState,
    /// State of G70–G73 (compound module).
    pub compound: crate::exec::compound::CompoundState,
    /// Pending corners (contour module).
    pub contour: crate::exec::contour::ContourState,
    /// Nose-radius compensation (comp module).
    pub comp: crate::exec::comp::CompState,
    /// G10/G11 modes and the tool-life table (data_setting module).
    pub data: crate::exec::data_setting::DataState,
    /// Polar or cylindrical interpolation while it is on (plane module).
    pub plane: Option<crate::exec::plane::PlaneState>,
}

impl State {
    pub fn power_on(m: &Machine) -> State {
        let modal = Modal::power_on(m);
        let c = &m.coords;
        let p = |v: crate::base::machine::Xz| Pt::xz(v.x, v.z);
        let mut wear = [[0.0; 4]; 32];
        let mut geom = [[0.0; 3]; 32];
        for o in &m.tools.offset {
            if let Some(i) = (o.number as usize).checked_sub(1).filter(|&i| i < 32) {
                wear[i] = [o.wear_x, o.wear_z, o.wear_radius, o.tip as f64];
                geom[i] = [o.x, o.z, o.radius];
            }
        }
        let mut st = State {
            pos: Pt::default(),
            c: 0.0,
            c_block: false,
            modal,
            exofs: p(c.exofs),
            work: [p(c.g54), p(c.g55), p(c.g56), p(c.g57), p(c.g58), p(c.g59)],
            shift: Pt::default(),
            local: Pt::default(),
            feed: 0.0,
            feed_printed: None,
            rpm: 0.0,
            css: 0.0,
            rpm_limit: None,
            spindle: SpindleDir::Stop,
            tool: 1,
            offset: 0,
            wear,
            geom,
            skip: None,
            clock_ms: 0.0,
            last: [f64::NAN; 26],
            parts: 0.0,
            outputs: 0,
            exact_stop: false,
            switches: Default::default(),
            stroke2: None,
            slide_off: Pt::ZERO,
            printed: None,
            parts_required: 0.0,
            cycles: Default::default(),
            compound: Default::default(),
            contour: Default::default(),
            comp: Default::default(),
            data: crate::exec::data_setting::DataState::power_on(m),
            plane: None,
        };
        // Homed at power-on: the tool stands at machine X0 Z0 (machine.md
        // §1), which the machine file's work offsets put off work zero.
        st.pos = Pt::default().sub(st.origin());
        st
    }

    #[inline]
    pub fn inch(&self) -> bool {
        self.modal.inch()
    }

    #[inline]
    pub fn per_rev(&self) -> bool {
        self.modal.per_rev()
    }

    #[inline]
    pub fn css_mode(&self) -> bool {
        self.modal.css_mode()
    }

    /// Index 0..6 of the active work system (G54 = 0).
    #[inline]
    pub fn work_index(&self) -> usize {
        self.modal.work_index()
    }

    /// The local zero in machine coordinates: EXOFS + G5x + G50 + G52.
    pub fn origin(&self) -> Pt {
        self.exofs
            .add(self.work[self.work_index()])
            .add(self.shift)
            .add(self.local)
    }

    /// Whether a `FEED` of `now` (F, per rev) is due: its F or mode as
    /// printed (four decimals, canon.md) differs from the last printed.
    /// One that is not leaves the last printed feed in force, off by less
    /// than half a digit of the fourth decimal.
    #[inline]
    pub fn feed_due(&mut self, now: (f64, bool)) -> bool {
        // (Most feed moves keep the feed: one comparison.)
        if self.feed_printed == Some(now) {
            return false;
        }
        let same = |(f, r): (f64, bool)| {
            r == now.1
                && match (ten_thousandths(f), ten_thousandths(now.0)) {
                    (Some(a), Some(b)) => a == b,
                    _ => f == now.0,
                }
        };
        if self.feed_printed.is_some_and(same) {
            return false;
        }
        self.feed_printed = Some(now);
        true
    }

    /// The tool point in machine coordinates.
    pub fn machine_pos(&self) -> Pt {
        self.pos.add(self.origin())
    }

    /// Length unit factor of the words (mm per program unit).
    #[inline]
    pub fn unit(&self) -> f64 {
        if self.inch() {
            25.4
        } else {
            1.0
        }
    }
}
