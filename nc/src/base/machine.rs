//! The machine configuration (machine.md §4): the reference lathe by
//! default, overridden by a TOML file whose unknown keys are errors.

use alloc::format;
use alloc::string::String;
use alloc::vec::Vec;

use serde::Deserialize;

/// A machine file could not be read or holds a bad value.
#[derive(Debug, thiserror::Error)]
pub enum MachineError {
    #[cfg(feature = "std")]
    #[error("machine file: {0}")]
    Toml(#[from] toml::de::Error),
    #[error("machine file: {0}")]
    Invalid(String),
    /// A key out of its range (machine_check.rs), at its line and column
    /// when read from a file.
    #[error("machine file: {}{}: {}", at.map_or(String::new(), |(l, c)| format!("line {l}, column {c}: ")), bad.key, bad.msg)]
    Range {
        bad: crate::base::machine_check::BadKey,
        at: Option<(usize, usize)>,
    },
}

macro_rules! section {
    ($(#[$m:meta])* $name:ident { $($field:ident : $ty:ty = $default:expr),* $(,)? }) => {
        $(#[$m])*
        #[derive(Debug, Clone, PartialEq, Deserialize)]
        #[serde(deny_unknown_fields, default)]
        pub struct $name { $(pub $field: $ty),* }
        impl Default for $name {
            fn default() -> Self { $name { $($field: $default),* } }
        }
    };
}

/// An X/Z pair of a table such as `g54 = { x = 0.0, z = 0.0 }`.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
pub struct Xz {
    pub x: f64,
    pub z: f64,
}

const fn xz(x: f64, z: f64) -> Xz {
    Xz { x, z }
}

section!(MachineSection {
    name: String = "gbc-reference-lathe".into(),
    decimal_point: DecimalPoint = DecimalPoint::Calculator,
    power_on_units: Units = Units::Mm,
    interpolation_period_ms: f64 = 1.0,
    resolution_mm: f64 = 0.001,
    arc_tolerance_mm: f64 = 0.02,
    arc_without_center: ArcWithoutCenter = ArcWithoutCenter::Alarm,
    lookahead_blocks: u32 = 1024,
});

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum DecimalPoint {
    Calculator,
    Increment,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Units {
    Mm,
    Inch,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ArcWithoutCenter {
    Alarm,
    Line,
}

/// The order of a program restart's approach (`run.restart_approach`):
/// which axis moves first from where the tool stands, as a control's
/// parameter sets it (Fanuc №7310).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RestartApproach {
    /// X (and C), then Z: the tool stands clear in +Z (the default).
    XThenZ,
    /// Z, then X (and C): the tool stands clear in X.
    ZThenX,
}

section!(LinearAxis {
    diameter: bool = true,
    rapid_mm_min: f64 = 6000.0,
    max_feed_mm_min: f64 = 4000.0,
    accel_mm_s2: f64 = 1500.0,
    jerk_mm_s3: f64 = 20000.0,
    soft_limits: bool = false,
    min_mm: f64 = -260.0,
    max_mm: f64 = 2.0,
    backlash_mm: f64 = 0.0,
    pitch_comp_mm: Vec<Vec<f64>> = Vec::new(),
});

section!(
    /// `[axes.z]` as a file writes it: Z's own defaults (a partial table
    /// keeps them), and no `diameter` (machine.md lists it for X only).
    ZAxisFile {
        rapid_mm_min: f64 = 10000.0,
        max_feed_mm_min: f64 = 5000.0,
        accel_mm_s2: f64 = 2000.0,
        jerk_mm_s3: f64 = 25000.0,
        soft_limits: bool = false,
        min_mm: f64 = -510.0,
        max_mm: f64 = 2.0,
        backlash_mm: f64 = 0.0,
        pitch_comp_mm: Vec<Vec<f64>> = Vec::new(),
    }
);

impl From<ZAxisFile> for LinearAxis {
    fn from(z: ZAxisFile) -> LinearAxis {
        LinearAxis {
            diameter: false,
            rapid_mm_min: z.rapid_mm_min,
            max_feed_mm_min: z.max_feed_mm_min,
            accel_mm_s2: z.accel_mm_s2,
            jerk_mm_s3: z.jerk_mm_s3,
            soft_limits: z.soft_limits,
            min_mm: z.min_mm,
            max_mm: z.max_mm,
            backlash_mm: z.backlash_mm,
            pitch_comp_mm: z.pitch_comp_mm,
        }
    }
}

fn z_from_file<'de, D: serde::Deserializer<'de>>(d: D) -> Result<LinearAxis, D::Error> {
    ZAxisFile::deserialize(d).map(LinearAxis::from)
}

section!(RotaryAxis {
    enabled: bool = false,
    name: String = "C".into(),
    attribute: u32 = 0,
    rapid_deg_min: f64 = 3600.0,
    max_feed_deg_min: f64 = 1800.0,
    accel_deg_s2: f64 = 3600.0,
    jerk_deg_s3: f64 = 36000.0,
    backlash_deg: f64 = 0.0,
    pitch_comp_deg: Vec<Vec<f64>> = Vec::new(),
});

/// `[axes]`: by hand rather than by `section!`, for Z's own reader.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Axes {
    pub x: LinearAxis,
    #[serde(deserialize_with = "z_from_file")]
    pub z: LinearAxis,
    pub c: RotaryAxis,
}

impl Default for Axes {
    fn default() -> Axes {
        Axes {
            x: LinearAxis::default(),
            z: ZAxisFile::default().into(),
            c: RotaryAxis::default(),
        }
    }
}

section!(Feed {
    max_mm_min: f64 = 5000.0
});

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SpindleType {
    Analog,
    Gear,
}

section!(Spindle {
    r#type: SpindleType = SpindleType::Analog,
    min_rpm: f64 = 30.0,
    max_rpm: f64 = 3000.0,
    accel_rpm_s: f64 = 1000.0,
    encoder_ppr: u32 = 1024,
    stall_timeout_s: f64 = 5.0,
});

section!(Threads {
    pullout_tenths: u32 = 0,
    max_lead_mm: f64 = 500.0,
    arc_thread_rigid: bool = false,
    repair_enabled: bool = false,
    repair_interpolating: bool = false,
    repair_deviation_inc: u32 = 0,
});

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
pub enum ChamferType {
    I,
    II,
}

section!(Cycles {
    chamfer_type: ChamferType = ChamferType::II,
    g71_retract_mm: f64 = 0.5,
});

section!(Motion {
    always_exact_stop: bool = false,
    // The runtime's S-curve (each axis within its jerk); off on the
    // reference machine, as machine.md §3 makes it an option.
    jerk_limiting: bool = false,
});

section!(Coords {
    aprs: bool = false,
    ppd: bool = false,
    exofs: Xz = Xz::default(),
    g54: Xz = Xz::default(),
    g55: Xz = Xz::default(),
    g56: Xz = Xz::default(),
    g57: Xz = Xz::default(),
    g58: Xz = Xz::default(),
    g59: Xz = Xz::default(),
});

section!(ReferencePoints {
    return_feed_mm_min: f64 = 4000.0,
    second: Xz = xz(-50.0, -20.0),
    third: Xz = xz(-150.0, -100.0),
    fourth: Xz = xz(0.0, -300.0),
});

section!(Measure {
    feed_mm_min: f64 = 50.0,
    gamma_x_mm: f64 = 2.0,
    gamma_z_mm: f64 = 2.0,
    epsilon_x_mm: f64 = 0.5,
    epsilon_z_mm: f64 = 0.5,
    overrides_apply: bool = false,
    signal_active_low: bool = false,
});

section!(Skip {
    inputs: SkipInputs = Exactly([0, 1, 2, 3])
});

/// №148–151: the input of each skip signal 1–4.
pub type SkipInputs = Exactly<u32, 4>;

/// A list of exactly `N` values: one of another length is refused, where
/// serde's array would drop the values past `N` of a longer one unseen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Exactly<T, const N: usize>(pub [T; N]);

impl<'de, T: Deserialize<'de>, const N: usize> Deserialize<'de> for Exactly<T, N> {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Exactly<T, N>, D::Error> {
        let v = Vec::<T>::deserialize(d)?;
        let n = v.len();
        let all: [T; N] = v.try_into().map_err(|_| {
            serde::de::Error::invalid_length(n, &format!("exactly {N} values").as_str())
        })?;
        Ok(Exactly(all))
    }
}

impl<T, const N: usize> core::ops::Deref for Exactly<T, N> {
    type Target = [T; N];
    fn deref(&self) -> &[T; N] {
        &self.0
    }
}

impl<T, const N: usize> core::ops::DerefMut for Exactly<T, N> {
    fn deref_mut(&mut self) -> &mut [T; N] {
        &mut self.0
    }
}

section!(StrokeCheck2 {
    enabled: bool = true,
    forbid_outside: bool = false,
    plus: Xz = Xz::default(),
    minus: Xz = Xz::default(),
});

section!(Polar {
    linear_axis: u32 = 1,
    rotary_axis: u32 = 3,
});

section!(ToolOffset {
    number: u32 = 0,
    x: f64 = 0.0,
    z: f64 = 0.0,
    radius: f64 = 0.0,
    tip: u32 = 0,
    wear_x: f64 = 0.0,
    wear_z: f64 = 0.0,
    wear_radius: f64 = 0.0,
});

section!(Tools {
    count: u32 = 32,
    offsets: u32 = 32,
    offset: Vec<ToolOffset> = Vec::new(),
});

section!(ToolLifeGroup {
    number: u32 = 0,
    life: f64 = 0.0,
    unit: String = "count".into(),
    tools: Vec<u32> = Vec::new(),
});

section!(ToolLife { group: Vec<ToolLifeGroup> = Vec::new() });

section!(Macro {
    g_code_macros: Exactly<u32, 10> = Exactly([0; 10]),
    persistent_file: String = String::new(),
    library_dirs: Vec<String> = Vec::new(),
});

section!(Operator {
    block_skip: Exactly<bool, 9> = Exactly([true; 9]),
    optional_stop: bool = true,
    single_block: bool = false,
    dry_run: bool = false,
    machine_lock: bool = false,
    aux_lock: bool = false,
    feed_override_pct: f64 = 100.0,
    rapid_override_pct: f64 = 100.0,
    spindle_override_pct: f64 = 100.0,
});

section!(Host {
    inputs: u32 = 0,
    skip_signal: bool = false,
    measure_at_target: bool = true,
    date: u32 = 20000101,
    time: u32 = 0,
});

section!(Run {
    max_blocks: u64 = 2_000_000,
    // Simulated seconds a timed run (trace, plot, stats) may last: E6006.
    max_time_s: f64 = 3600.0,
    // Cycle start after M30 runs the program again from its start, as a
    // reset would leave it (a controller's; a GSK's M30 rewinds).
    m30_rewinds: bool = false,
    // Which axis a program restart's approach moves first.
    restart_approach: RestartApproach = RestartApproach::XThenZ,
});

section!(
    /// The whole machine file.
    Machine {
        machine: MachineSection = MachineSection::default(),
        axes: Axes = Axes::default(),
        feed: Feed = Feed::default(),
        spindle: Spindle = Spindle::default(),
        threads: Threads = Threads::default(),
        cycles: Cycles = Cycles::default(),
        motion: Motion = Motion::default(),
        coords: Coords = Coords::default(),
        reference_points: ReferencePoints = ReferencePoints::default(),
        measure: Measure = Measure::default(),
        skip: Skip = Skip::default(),
        stroke_check_2: StrokeCheck2 = StrokeCheck2::default(),
        polar: Polar = Polar::default(),
        tools: Tools = Tools::default(),
        tool_life: ToolLife = ToolLife::default(),
        r#macro: Macro = Macro::default(),
        operator: Operator = Operator::default(),
        host: Host = Host::default(),
        run: Run = Run::default(),
        plc: crate::base::plc::Plc = crate::base::plc::Plc::default(),
    }
);

impl Machine {
    /// The reference machine of machine.md.
    pub fn reference() -> Machine {
        Machine::default()
    }

    /// The radial distance (mm) of an X value as the program writes it:
    /// half of it where X is programmed on the diameter, the reference,
    /// the value itself in radius programming (`axes.x.diameter = false`,
    /// №001.2 = 0).
    #[inline]
    pub fn radial(&self, programmed: f64) -> f64 {
        if self.axes.x.diameter {
            programmed / 2.0
        } else {
            programmed
        }
    }

    /// The X value the program reads for the radial coordinate `r`
    /// ([`radial`](Machine::radial) undone).
    #[inline]
    pub fn programmed_x(&self, r: f64) -> f64 {
        if self.axes.x.diameter {
            r * 2.0
        } else {
            r
        }
    }

    /// The diameter of an X value as the program writes it: what the
    /// kernel keeps where it keeps X as the canon prints it and the
    /// machine file writes it (tool offsets, G22's area).
    #[inline]
    pub fn diameter(&self, programmed: f64) -> f64 {
        if self.axes.x.diameter {
            programmed
        } else {
            programmed * 2.0
        }
    }

    /// The X value the program reads for the diameter `d`
    /// ([`diameter`](Machine::diameter) undone).
    #[inline]
    pub fn from_diameter(&self, d: f64) -> f64 {
        if self.axes.x.diameter {
            d
        } else {
            d / 2.0
        }
    }

    /// Reads a machine file: what it leaves out keeps the reference value.
    /// Without `std`, a host builds the `Machine` itself (or deserializes
    /// it with any serde format) and calls [`Machine::validate`].
    #[cfg(feature = "std")]
    pub fn from_toml(text: &str) -> Result<Machine, MachineError> {
        let m: Machine = toml::from_str(text)?;
        match m.validate() {
            Err(MachineError::Range { bad, .. }) => {
                let at = crate::base::machine_check::locate(text, &bad.key);
                Err(MachineError::Range { bad, at })
            }
            other => other.map(|()| m),
        }
    }

    /// Checks the values a file could get wrong (rates, limits, tables).
    pub fn validate(&self) -> Result<(), MachineError> {
        crate::base::machine_check::check(self)
            .map_err(|bad| MachineError::Range { bad, at: None })?;
        self.validate_tool_life()
    }

    /// `[[tool_life.group]]`: numbers 1…32 once each, a positive life,
    /// a known unit and T values of real tools and offsets.
    fn validate_tool_life(&self) -> Result<(), MachineError> {
        let bad = |what: String| Err(MachineError::Invalid(what));
        let groups = &self.tool_life.group;
        for (i, g) in groups.iter().enumerate() {
            let n = g.number;
            if !(1..=32).contains(&n) || groups[..i].iter().any(|o| o.number == n) {
                return bad(format!(
                    "tool_life.group number {n}: groups are 1…32, each once"
                ));
            }
            if !(g.life > 0.0 && g.life.is_finite()) {
                return bad(format!("tool_life.group {n}: life must be above 0"));
            }
            if g.unit != "count" && g.unit != "minutes" {
                return bad(format!(
                    "tool_life.group {n}: unit must be \"count\" or \"minutes\""
                ));
            }
            for &t in &g.tools {
                let (tool, offset) = (t / 100, t % 100);
                if t > 9999 || tool > self.tools.count || offset > self.tools.offsets {
                    return bad(format!(
                        "tool_life.group {n}: T{t:04} is outside the tool or offset table"
                    ));
                }
            }
        }
        Ok(())
    }

    /// The keys marked C in machine.md, in one canonical line: recorded in a
    /// `.gbc` so a VM refuses to run it on a machine that would change its
    /// meaning.
    pub fn compile_keys(&self) -> String {
        // Only an offset's nose (radius, wear radius, tip) is compiled in;
        // its lengths are the runtime's, and an all-zero nose is as unlisted.
        let offsets: Vec<String> = self
            .tools
            .offset
            .iter()
            .filter(|o| o.radius != 0.0 || o.wear_radius != 0.0 || o.tip != 0)
            .map(|o| format!("{}:{}:{}:{}", o.number, o.radius, o.wear_radius, o.tip))
            .collect();
        format!(
            "decimal_point={:?};power_on_units={:?};arc_tolerance_mm={};arc_without_center={:?};\
             x_diameter={};c_enabled={};spindle={:?};max_lead_mm={};chamfer={:?};g71_retract_mm={};\
             tools={}/{};offsets=[{}];g_code_macros={:?}",
            self.machine.decimal_point,
            self.machine.power_on_units,
            self.machine.arc_tolerance_mm,
            self.machine.arc_without_center,
            self.axes.x.diameter,
            self.axes.c.enabled,
            self.spindle.r#type,
            self.threads.max_lead_mm,
            self.cycles.chamfer_type,
            self.cycles.g71_retract_mm,
            self.tools.count,
            self.tools.offsets,
            offsets.join(","),
            self.r#macro.g_code_macros.0,
        )
    }

    /// Where two lines of [`Machine::compile_keys`] differ, for a message:
    /// the first differing key with both values; `None` when they agree.
    pub fn compile_keys_differ(recorded: &str, here: &str) -> Option<String> {
        let mut a = recorded.split(';');
        let mut b = here.split(';');
        loop {
            match (a.next(), b.next()) {
                (None, None) => return None,
                (x, y) if x == y => continue,
                (x, y) => {
                    let (key, was) = x.unwrap_or("").split_once('=').unwrap_or(("?", ""));
                    let now = y.and_then(|y| y.split_once('=')).map_or("", |(_, v)| v);
                    return Some(format!("{key}: {was} in the module, {now} here"));
                }
            }
        }
    }

    /// Work offset n (1 = G54 … 6 = G59) as configured.
    pub fn work_offset(&self, n: usize) -> Xz {
        let c = &self.coords;
        [c.g54, c.g55, c.g56, c.g57, c.g58, c.g59]
            .get(n.wrapping_sub(1))
            .copied()
            .unwrap_or_default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_file_is_the_reference() {
        assert_eq!(Machine::from_toml("").unwrap(), Machine::reference());
    }

    #[test]
    fn unknown_key_is_an_error() {
        assert!(Machine::from_toml("[machine]\ndecimal_pont = \"increment\"").is_err());
        assert!(Machine::from_toml("[nosuch]\n").is_err());
    }

    #[test]
    fn the_restart_approach_is_one_of_two_orders() {
        let m = Machine::from_toml("[run]\nrestart_approach = \"z_then_x\"\n").unwrap();
        assert_eq!(m.run.restart_approach, RestartApproach::ZThenX);
        assert_eq!(m.run.max_blocks, 2_000_000);
        let m = Machine::reference();
        assert_eq!(m.run.restart_approach, RestartApproach::XThenZ);
        assert!(Machine::from_toml("[run]\nrestart_approach = \"diagonal\"\n").is_err());
    }

    #[test]
    fn partial_tables_keep_the_rest() {
        let m = Machine::from_toml("[machine]\narc_without_center = \"line\"\n").unwrap();
        assert_eq!(m.machine.arc_without_center, ArcWithoutCenter::Line);
        assert_eq!(m.machine.arc_tolerance_mm, 0.02);
        let m =
            Machine::from_toml("[[tools.offset]]\nnumber = 1\nradius = 0.8\ntip = 3\n").unwrap();
        assert_eq!(m.tools.offset[0].radius, 0.8);
        assert_eq!(m.tools.count, 32);
        // A partial [axes.z] keeps Z's values of machine.md §3 (10 000
        // mm/min rapid, 5000 feed, 2000 mm/s², −510…+2), not X's.
        let m = Machine::from_toml("[axes.z]\nsoft_limits = true\n").unwrap();
        let z = &m.axes.z;
        assert!(z.soft_limits && !z.diameter);
        assert_eq!(
            (z.rapid_mm_min, z.max_feed_mm_min, z.accel_mm_s2, z.min_mm),
            (10000.0, 5000.0, 2000.0, -510.0)
        );
        assert!(Machine::from_toml("[axes.z]\nmax_mm = -400.0\n").is_ok());
        // Four skip inputs, no more and no fewer.
        assert!(Machine::from_toml("[skip]\ninputs = [0, 1, 2, 3, 4]\n").is_err());
        assert!(Machine::from_toml("[skip]\ninputs = [0, 1, 2]\n").is_err());
        // Longer lists too, which serde's arrays would cut short unseen.
        let nine = "true, true, true, true, true, true, true, true, true";
        let skips =
            |list: &str| Machine::from_toml(&format!("[operator]\nblock_skip = [{list}]\n"));
        assert!(skips(nine).is_ok());
        assert!(skips(&format!("{nine}, false")).is_err());
        let macros = |n: usize| {
            let list = alloc::vec!["0"; n].join(", ");
            Machine::from_toml(&format!("[macro]\ng_code_macros = [{list}]\n"))
        };
        assert!(macros(10).is_ok());
        assert!(macros(11).is_err() && macros(9).is_err());
        assert_eq!(
            Machine::from_toml("[skip]\ninputs = [3, 2, 1, 0]\n")
                .unwrap()
                .skip
                .inputs[0],
            3
        );
        // Z has no diameter key; X may be programmed on the radius.
        assert!(Machine::from_toml("[axes.z]\ndiameter = true\n").is_err());
        let radius = Machine::from_toml("[axes.x]\ndiameter = false\n").unwrap();
        assert!(!radius.axes.x.diameter);
    }

    #[test]
    fn only_an_offsets_nose_is_a_compile_key() {
        // machine.md §5: radius, wear_radius and tip are C; the lengths
        // x, z, wear_x, wear_z are the runtime's.
        let lengths = "[[tools.offset]]\nnumber = 2\nx = -6.0\nwear_z = 0.1\n";
        let reference = Machine::reference().compile_keys();
        assert_eq!(
            Machine::from_toml(lengths).unwrap().compile_keys(),
            reference
        );
        let nose = Machine::from_toml("[[tools.offset]]\nnumber = 2\nradius = 0.4\n").unwrap();
        let differ = Machine::compile_keys_differ(&reference, &nose.compile_keys());
        assert_eq!(
            differ.as_deref(),
            Some("offsets: [] in the module, [2:0.4:0:0] here")
        );
        assert_eq!(Machine::compile_keys_differ(&reference, &reference), None);
    }

    #[test]
    fn bad_values_are_rejected() {
        assert!(Machine::from_toml("[axes.x]\nrapid_mm_min = 0\n").is_err());
        assert!(Machine::from_toml("[[tools.offset]]\nnumber = 40\n").is_err());
        assert!(Machine::from_toml("[[tools.offset]]\nnumber = 1\ntip = 12\n").is_err());
        let group = |body: &str| Machine::from_toml(&format!("[[tool_life.group]]\n{body}"));
        assert!(group("number = 1\nlife = 5\ntools = [101]\n").is_ok());
        assert!(group("number = 0\nlife = 5\n").is_err());
        assert!(group("number = 1\nlife = 0\n").is_err());
        assert!(group("number = 1\nlife = 5\nunit = \"hours\"\n").is_err());
        assert!(group("number = 1\nlife = 5\ntools = [3301]\n").is_err());
    }

    /// The axis compensation: the lost motion within 0 … 2 mm (C's
    /// within 0 … 2°); a pitch
    /// table of none or two points and more, ascending, gentle.
    #[test]
    fn axis_compensation_is_checked() {
        let z = |body: &str| Machine::from_toml(&format!("[axes.z]\n{body}\n"));
        assert!(z("backlash_mm = 0.03").is_ok());
        assert!(z("backlash_mm = -0.01").is_err());
        assert!(z("backlash_mm = 2.5").is_err());
        let c = |body: &str| Machine::from_toml(&format!("[axes.c]\nenabled = true\n{body}\n"));
        assert!(c("backlash_deg = 0.05").is_ok());
        assert!(c("backlash_deg = -0.01").is_err());
        assert!(c("backlash_deg = 2.5").is_err());
        assert!(z("pitch_comp_mm = [[-300.0, -0.004], [0.0, 0.0]]").is_ok());
        assert!(z("pitch_comp_mm = []").is_ok());
        let err = |body: &str| {
            z(body)
                .err()
                .map(|e| alloc::format!("{e}"))
                .unwrap_or_default()
        };
        assert!(err("pitch_comp_mm = [[0.0, 0.0]]").contains("1 points"));
        assert!(err("pitch_comp_mm = [[0.0, 0.0, 3.0], [1.0, 0.0]]").contains("3 number(s)"));
        assert!(err("pitch_comp_mm = [[0.0], [1.0, 0.0]]").contains("1 number(s)"));
        assert!(err("pitch_comp_mm = [[0.0, 0.0], [0.0, 0.001]]").contains("ascending"));
        // 0.002 mm over 1 mm is twice the steepest allowed.
        assert!(err("pitch_comp_mm = [[0.0, 0.0], [1.0, 0.002]]").contains("0.002 mm a mm"));
        assert!(err("pitch_comp_mm = [[0.0, 0.0], [1000.0, 3.0]]").contains("correction"));
    }

    /// C's angular table: angles within one turn, ascending, gentle, the
    /// step from the last point round to the first (one turn on)
    /// included.
    #[test]
    fn the_angular_table_is_checked() {
        let c = |body: &str| {
            Machine::from_toml(&format!(
                "[axes.c]\nenabled = true\npitch_comp_deg = {body}\n"
            ))
            .err()
            .map(|e| alloc::format!("{e}"))
        };
        assert_eq!(c("[[0.0, 0.0], [180.0, 0.01]]"), None);
        assert_eq!(c("[]"), None);
        assert!(c("[[0.0, 0.0], [360.0, 0.0]]").is_some_and(|e| e.contains("one turn")));
        assert!(c("[[-1.0, 0.0], [90.0, 0.0]]").is_some_and(|e| e.contains("one turn")));
        assert!(c("[[90.0, 0.0], [45.0, 0.0]]").is_some_and(|e| e.contains("ascending")));
        assert!(c("[[0.0, 0.0], [90.0, 2.5]]").is_some_and(|e| e.contains("correction")));
        // 0.18° over 90° is 0.002 a degree: twice the steepest.
        let steep = c("[[0.0, 0.0], [90.0, 0.18]]");
        assert!(steep.is_some_and(|e| e.contains("0.002 ° a °")));
        // Each step gentle (0.09° over 90°), but from 270° back round to
        // 360° the correction falls by 0.27°: 0.003 a degree.
        let wrap = c("[[0.0, 0.0], [90.0, 0.09], [180.0, 0.18], [270.0, 0.27]]");
        assert!(wrap.is_some_and(|e| e.contains("from 270 to 360")), "wrap");
    }

    #[test]
    fn the_reference_file_of_the_spec_loads() {
        let text = "[machine]\nname = \"gbc-reference-lathe\"\ndecimal_point = \"calculator\"\n\
                    [coords]\nexofs = { x = 0.0, z = 0.0 }\n[reference_points]\nsecond = { x = -50.0, z = -20.0 }\n\
                    [operator]\nblock_skip = [true, true, true, true, true, true, true, true, true]\n";
        assert_eq!(Machine::from_toml(text).unwrap(), Machine::reference());
    }
}
