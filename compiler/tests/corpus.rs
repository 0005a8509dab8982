//! Every program of the public corpus (../shared/corpus/public, real lathe
//! programs from machinists) compiles and runs to its end under the
//! reference machine, or is rejected with the diagnostic that names its
//! real problem at the right line. The expectation of each file is in the
//! table below, each with the reason.

use compiler::{compile, Options};
use nc::Machine;
use std::path::Path;
use vm::{Status, Vm};

#[derive(Debug, Clone, Copy, PartialEq)]
enum Expect {
    /// Compiles and runs to M02/M30/M99 or past its last block.
    Runs,
    /// Compiles; the run stops on this alarm (the program's own, or a
    /// value it needs from its caller).
    Alarm(u32),
    /// Rejected at compile time: this code at this line.
    Rejected(&'static str, usize),
}
use Expect::*;

/// (file, expectation, why).
const TABLE: &[(&str, Expect, &str)] = &[
    ("citizen-syntax__sample-citizen.cnc", Rejected("E1001", 1), "Citizen multi-path `$1` section, not this dialect (§4.13)"),
    ("cnclearn__205", Runs, "G71/G70 with angle programming in the profile"),
    ("cnclearn__215.txt", Rejected("E1008", 4), "`TO303`: the letter O written for the digit 0 (T0303)"),
    ("cnclearn__220", Rejected("E2001", 2), "G49 is a mill code (§4.13)"),
    ("cnclearn__230", Rejected("E2001", 5), "G49 is a mill code (§4.13)"),
    ("cnclearn__240", Rejected("E2001", 4), "G49 is a mill code (§4.13)"),
    ("cnclearn__Izolyator095-1000.NC", Rejected("E1007", 41), "typo `Z-0.5.`: a second decimal point"),
    ("cnclearn__Kolco-dc8-061-1003.NC", Rejected("E1008", 55), "`GO Y0.`: the letter O written for the digit 0"),
    ("cnclearn__Vtulka-dc8-210-1004.NC", Rejected("E1007", 27), "typo `-12.8.`: a second decimal point"),
    ("donpayne-cnc__advanced_arcs_o2001.cnc", Rejected("E1004", 23), "`:(Solve …)`: a `:` program-number mark with no number"),
    ("donpayne-cnc__advanced_arcs_o9001.cnc", Alarm(5009), "a G65 macro run on its own: its arguments are vacant, so #[#22] has no number"),
    ("donpayne-cnc__gauge_tool_o1012.cnc", Rejected("E2005", 3), "mill program: Y axis"),
    ("doosan-lynx300__O0001", Runs, "Fanuc 0i-TD program"),
    ("doosan-lynx300__O0024", Rejected("E1010", 72), "`G00 3.7347`: the X address is missing, so the blanks join it to G00 (G003.7347)"),
    ("doosan-lynx300__O0076", Runs, "G70–G74 with standard-notation units"),
    ("doosan-lynx300__O0200", Runs, "G71/G70"),
    ("doosan-lynx300__O0201", Runs, "G71/G70/G76"),
    ("doosan-lynx300__O0309", Runs, "G71/G72/G70"),
    ("doosan-lynx300__O1002", Runs, "G71"),
    ("doosan-lynx300__O2000", Runs, "plain turning"),
    ("doosan-lynx300__O2031", Runs, "G74, arcs without centre as lines (CIR = 0)"),
    ("doosan-lynx300__O2101", Runs, "arcs without centre as lines (CIR = 0)"),
    ("doosan-lynx300__O2270", Runs, "plain turning"),
    ("doosan-lynx300__O2301", Runs, "G71/G70/G83"),
    ("doosan-lynx300__O2311", Runs, "G83"),
    ("doosan-lynx300__O2321", Runs, "G71/G70/G74, arcs without centre as lines"),
    ("doosan-lynx300__O2403", Runs, "G72/G70"),
    ("doosan-lynx300__O2411", Runs, "G71/G72/G70"),
    ("doosan-lynx300__O2700", Runs, "G71/G70"),
    ("doosan-lynx300__O2701", Runs, "G75, arcs without centre as lines"),
    ("doosan-lynx300__O3369", Runs, "G71/G70/G75"),
    ("doosan-lynx300__O3380", Runs, "G32 threading, block delete"),
    ("doosan-lynx300__O4520", Runs, "G71/G70/G75"),
    ("doosan-lynx300__O6845", Runs, "plain turning"),
    ("enier-cnc__02_round_head_plug_right_part.nc", Runs, "one-block G71 with D, G53"),
    ("enier-cnc__lathe_hp_1.nc", Rejected("E2004", 70), "Haas `G75 … I` peck word (§4.13)"),
    ("enier-cnc__lathe_hp_2.nc", Rejected("E2004", 75), "Haas `G75 … I` peck word (§4.13)"),
    ("enier-cnc__o20013.nc", Runs, "G53, G50 S, G96"),
    ("enier-cnc__round_head_plug.nc", Runs, "one-block G71 with D, one-block G76 with K/D"),
    ("enier-cnc__valve.nc", Rejected("E2004", 127), "Haas `G75 … I` peck word (§4.13)"),
    ("enier-cnc__weld_pin.nc", Rejected("E2004", 85), "Haas `G75 … I` peck word (§4.13)"),
    ("gcodeworkshop__0100.nc", Runs, "macro variables, `:0100` program number"),
    ("gcodeworkshop__FANUC0T.nc", Runs, "Fanuc 0T program"),
    ("gcodeworkshop__HAAS.nc", Rejected("E2003", 4), "mill program: G17 needs a Y axis"),
    ("gsk218m__O72000.txt", Rejected("E2012", 5), "`M98 P72100` is 7 × O2100 (§7.11), and O2100 is in no file"),
    ("gsk218m__O72010.txt", Rejected("E2012", 8), "`M98 P72100` is 7 × O2100 (§7.11), and O2100 is in no file"),
    ("gsk218m__O72100.txt", Alarm(3001), "the program raises #3000 = 1 itself when run without its probe input"),
    ("hass-cnc-programs__CaliperDepthAttachmentThumbscrew.nc", Rejected("E2004", 49), "Haas `G75 … I` peck word (§4.13)"),
    ("hass-cnc-programs__Lathe-L8-Ex1.nc", Rejected("E2004", 30), "Haas `G75 … I` peck word (§4.13)"),
    ("hass-cnc-programs__O58214.nc", Rejected("E1009", 11), "`G04 P3.`: G04 P is an integer in ms"),
    ("icnc__T2019-1-S42-Gabriel-e-Kalwey-TORNO1.txt", Rejected("E2001", 85), "G81 is a mill drilling code (§4.13)"),
    ("icnc__T2019-1-S42-Gabriel-e-Kalwey-TORNO2.txt", Runs, "simulator program with a [BILLET line"),
    ("icnc__T2019-1-S42-Luiz-LUIZ2.txt", Rejected("E1008", 12), "commas between comments: `(…), (…)`"),
    ("icnc__T2019-1-S43-Baratieri-PT01.txt", Rejected("E1011", 8), "`G50 S500 G96 S100`: two S words in one block"),
    ("icnc__T2019-1-S43-Cesar-Rottava-TORN_AO-O001.txt", Rejected("E4009", 76), "bore profile whose last arc `G03 X10 Z-30 R2` (line 84, to which the error at the cycle block points) bulges 0.268 mm past Z-30 and comes back: not monotonic in Z (§4.8)"),
    ("icnc__T2019-1-S43-Giordano-O0001.TXT", Runs, "simulator program"),
    ("icnc__T2019-1-S43-Joao-Luiz-p1proj.txt", Rejected("E2007", 84), "`G71 U0.5 X0.1`: X beside U"),
    ("icnc__T2019-1-S43-Laura-programa1.txt", Runs, "G71 OD profile, the profile repeated for finishing"),
    ("icnc__T2019-1-S43-Renan-e-Pietra-FASE1.txt", Runs, "simulator program"),
    ("icnc__T2019-2-S42-Andrey-e-Fabio-TORNO1.txt", Rejected("E1002", 69), "`(DESBASTE INTERNO`: comment not closed"),
    ("icnc__T2019-2-S43-Alexandre-e-Alexandre-TORNFASE2.txt", Rejected("E1007", 20), "`X45s`: S without a value"),
    ("icnc__T2019-2-S43-Esther-e-Julio-FASE3.txt", Rejected("E4010", 38), "`G76 X… Z… P244 F2` without Q: the first depth Δd is 0"),
    ("icnc__T2019-2-S43-Gabriel-Delorensi-FASE2.txt", Rejected("E2005", 36), "`V0.2` (incremental Y) where W was meant"),
    ("icnc__T2019-2-S43-Henrique-TOR-HV.FNC", Runs, "simulator program, runs off its end"),
    ("icnc__T2019-2-S43-Vitor-e-Pedro-TORFASE2.txt", Alarm(7001), "`N25 G01 X00` feeds with no F in force (a simulator program; W107 at compile time)"),
    ("projetocnc1__programa-completo.gcode", Rejected("E1008", 38), "`;bedame de 3mm`: text after `;` (put comments in ( ))"),
    ("projetocnc3__usinagem-dois-lados.gcode", Rejected("E2004", 4), "`G92 S`: the speed clamp of systems B/C (§4.13)"),
    ("rcod2__SHABLON-O00999.nc", Rejected("E2001", 3), "G49 is a mill code"),
    ("rcod2__SHABLON2-SHABLON2-1-VERH-O00025.nc", Rejected("E1014", 42), "`IF […] S900. F500.` without THEN"),
    ("rcod2__SHABLON2-SHABLON2-9-SPIRAL-O00010.nc", Rejected("E2001", 3), "G49 is a mill code"),
    ("rcod2__SHABLON3-2-KONTUR-O00012.nc", Rejected("E2001", 3), "G49 is a mill code"),
    ("rcod2__SHABLON3-7-GRAVER-O00001.nc", Rejected("E2001", 3), "G49 is a mill code"),
    ("rcod2__SHABLON3-O00999.nc", Rejected("E2005", 30), "mill program: Y axis"),
    ("rcod2__SHABLON3-RAZNOE-6-grannik-O00001.nc", Rejected("E2001", 4), "G49 is a mill code"),
    ("rcod2__SHABLON3-RAZNOE-O00030.nc", Rejected("E2001", 3), "G49 is a mill code"),
    ("rcod2__SHABLON3-RAZNOE-shabloNi-0000-O00041.nc", Rejected("E2001", 3), "G49 is a mill code"),
    ("rcod2__SHABLON3-RAZNOE-shabloNi-0000-O00044.nc", Rejected("E1013", 3), "`THEN M31`: only an assignment may follow THEN"),
    ("sk7420__O0100", Rejected("E1005", 3), "O0100 written twice"),
    ("sk7420__O8000", Rejected("E1014", 32), "`IF[#609GT0]#712=#609` without THEN"),
    ("sk7420__O8200", Rejected("E2004", 33), "G91 incremental mode of systems B/C (§4.13)"),
    ("sk7420__O8300", Alarm(5007), "reads #3101, not a variable of this control (§7.2)"),
    ("sk7420__O8400", Rejected("E2012", 7), "G65 P8000: O8000 is a separate file that no -I folder provides"),
];

fn machine_for(file: &str, features: &str) -> Machine {
    let mut toml = String::from("[machine]\n");
    if features.contains("int-units-no-decimal") {
        toml.push_str("decimal_point = \"increment\"\n");
    }
    // The Doosan Lynx 300 runs a Fanuc 0i-TD with CIR = 0 (machine.md §4).
    if file.starts_with("doosan-lynx300__") {
        toml.push_str("arc_without_center = \"line\"\n");
    }
    Machine::from_toml(&toml).expect("a valid machine")
}

fn outcome(path: &Path, machine: &Machine) -> Expect {
    let bytes = std::fs::read(path).expect("readable");
    let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
    let opts = Options {
        machine: machine.clone(),
        ..Options::default()
    };
    let c = compile(name, &bytes, &opts);
    if let Some((f, d)) = c.diags.iter().find(|(_, d)| d.is_error()) {
        return Rejected(d.code, c.files[*f].line_col(d.span.start).0);
    }
    let mut vm = Vm::new(c.module.expect("module"), machine.clone());
    let mut events: Vec<nc::Event> = Vec::new();
    match vm.run(&mut events) {
        Status::Alarm(a) => Alarm(a.code),
        _ => Runs,
    }
}

#[test]
fn every_corpus_program_runs_or_is_rejected_for_its_real_problem() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/corpus/public");
    let Ok(manifest) = std::fs::read_to_string(dir.join("MANIFEST.tsv")) else {
        eprintln!("corpus not found at {}: skipped", dir.display());
        return;
    };
    let mut wrong = Vec::new();
    let mut seen = 0;
    for line in manifest.lines().skip(1) {
        let cols: Vec<&str> = line.split('\t').collect();
        let (file, features) = (cols[0], cols.get(6).copied().unwrap_or(""));
        let Some((_, want, why)) = TABLE.iter().find(|(f, ..)| *f == file) else {
            wrong.push(format!("{file}: not in the table"));
            continue;
        };
        seen += 1;
        let got = outcome(&dir.join(file), &machine_for(file, features));
        if got != *want {
            wrong.push(format!("{file}: expected {want:?} ({why}), got {got:?}"));
        }
    }
    assert_eq!(
        seen,
        TABLE.len(),
        "the table names files the manifest does not"
    );
    assert!(
        wrong.is_empty(),
        "{} of {} differ:\n{}",
        wrong.len(),
        seen,
        wrong.join("\n")
    );
}
