//! `gbcc`: the gbc compiler driver, with gcc's conventions.

use clap::Parser;
use compiler::{Compiled, Options};
use grammar::Severity;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// mimalloc (cli::allocator says why).
#[global_allocator]
static ALLOCATOR: cli::allocator::Mimalloc = cli::allocator::Mimalloc;

#[derive(Parser)]
#[command(
    name = "gbcc",
    version,
    about = "Compile GSK980TDi lathe G-code into .gbc bytecode"
)]
struct Args {
    /// Program files (.nc).
    #[arg(required = true)]
    files: Vec<PathBuf>,
    /// Output file (default: the input's name with .gbc, or .s with -S).
    #[arg(short = 'o')]
    output: Option<PathBuf>,
    /// Write the annotated bytecode listing instead of a .gbc.
    #[arg(short = 'S')]
    listing: bool,
    /// Print the program as plain G-code after macros, subprograms and
    /// cycles are resolved (a run on the reference host), on stdout.
    #[arg(short = 'E')]
    expand: bool,
    /// Library folder searched for called programs (repeatable).
    #[arg(short = 'I', value_name = "DIR")]
    include: Vec<PathBuf>,
    /// Preset a variable for the run: -D '#100=5'.
    #[arg(short = 'D', value_name = "#N=VALUE")]
    define: Vec<String>,
    /// Optimisation level: -O0 (no folding), -O1 (constant folding, default).
    #[arg(short = 'O', value_name = "LEVEL", default_value = "1")]
    opt: String,
    /// Warning options: -Werror, -Wall, -w.
    #[arg(short = 'W', value_name = "WARN")]
    warn: Vec<String>,
    /// Suppress every warning.
    #[arg(short = 'w')]
    no_warnings: bool,
    /// -fsyntax-only, -fdiagnostics-format=text|json.
    #[arg(short = 'f', value_name = "FLAG")]
    flags: Vec<String>,
    /// Machine file (TOML, machine.md §4); the reference machine by default.
    #[arg(long = "machine", value_name = "FILE")]
    machine: Option<PathBuf>,
}

fn usage(msg: &str) -> ExitCode {
    eprintln!("gbcc: error: {msg}");
    ExitCode::from(2)
}

/// `-D '#N=VALUE'`: N a variable a program may preset (locals #1–#33,
/// common #100–#199 and #500–#999), VALUE a finite number.
fn parse_define(d: &str) -> Result<(u32, f64), String> {
    let malformed = || format!("-D expects #N=VALUE, got '{d}'");
    let (var, value) = d
        .trim()
        .trim_start_matches('#')
        .split_once('=')
        .ok_or_else(malformed)?;
    let var: u32 = var.trim().parse().map_err(|_| malformed())?;
    let value: f64 = value.trim().parse().map_err(|_| malformed())?;
    if !matches!(var, 1..=33 | 100..=199 | 500..=999) {
        return Err(format!(
            "-D '{d}': #{var} cannot be preset (only #1–#33, #100–#199, #500–#999)"
        ));
    }
    if !value.is_finite() {
        return Err(format!("-D '{d}': the value must be a finite number"));
    }
    Ok((var, value))
}

fn main() -> ExitCode {
    let args = Args::parse();
    let mut syntax_only = false;
    let mut json = false;
    for f in &args.flags {
        match f.as_str() {
            "syntax-only" => syntax_only = true,
            "diagnostics-format=json" => json = true,
            "diagnostics-format=text" => json = false,
            other => return usage(&format!("unknown option -f{other}")),
        }
    }
    let werror = args.warn.iter().any(|w| w == "error");
    let optimize = match args.opt.as_str() {
        "0" => false,
        "1" | "2" | "s" => true,
        other => return usage(&format!("unknown optimisation level -O{other}")),
    };
    let machine = match cli::load_machine(args.machine.as_deref()) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("gbcc: error: {e}");
            return ExitCode::from(1);
        }
    };
    let mut defines = Vec::new();
    for d in &args.define {
        match parse_define(d) {
            Ok(def) => defines.push(def),
            Err(msg) => return usage(&msg),
        }
    }
    if args.output.is_some() && args.files.len() > 1 && !syntax_only {
        return usage("-o with several input files");
    }
    let opts = Options {
        machine,
        include: args.include.clone(),
        optimize,
        defines,
    };
    let mut failed = false;
    for file in &args.files {
        let bytes = match std::fs::read(file) {
            Ok(b) => b,
            Err(e) => {
                eprintln!("gbcc: error: {}: {e}", file.display());
                failed = true;
                continue;
            }
        };
        let name = file.display().to_string();
        let compiled = if syntax_only {
            syntax(&name, &bytes)
        } else {
            compiler::compile(&name, &bytes, &opts)
        };
        let errors = report(&compiled, json, werror, args.no_warnings);
        if errors {
            failed = true;
            continue;
        }
        if syntax_only {
            continue;
        }
        if args.expand {
            if let Err(e) = expand(&compiled, &bytes, &opts.machine) {
                eprintln!("{e}");
                failed = true;
            }
            continue;
        }
        if let Err(e) = write_output(&compiled, file, args.output.as_deref(), args.listing) {
            eprintln!("gbcc: error: {e}");
            failed = true;
        }
    }
    ExitCode::from(if failed { 1 } else { 0 })
}

/// -E: runs the module on the reference host and prints what it did as
/// G-code; a run-time alarm ends the listing with the alarm.
fn expand(c: &Compiled, src: &[u8], machine: &nc::Machine) -> Result<(), String> {
    let Some(module) = c.module.clone() else {
        return Err("no module was produced".into());
    };
    let (mut ast, _) = grammar::parse(src);
    // The N of a G10 L52 block is a parameter number, not a label.
    compiler::data_setting::prepare(&mut ast);
    let file = &c.files[0];
    let mut seqs = std::collections::HashMap::new();
    for line in &ast.lines {
        if let grammar::ast::Line::Block(b) = line {
            if let Some(s) = b.seq {
                seqs.insert(file.line_col(b.span.start).0 as u32, s.number);
            }
        }
    }
    let mut out = cli::expand::Expand::new(seqs);
    let mut vm = vm::Vm::new(module, machine.clone());
    let mut events: Vec<nc::Event> = Vec::new();
    loop {
        let start = (vm.nc.st.pos.x(), vm.nc.st.pos.z);
        let status = vm.step(1 << 16, &mut events);
        out.block_events(&events, vm.last_loc().line, start);
        events.clear();
        match status {
            vm::Status::Event | vm::Status::OutOfBudget | vm::Status::Sync => continue,
            vm::Status::Done => break,
            vm::Status::Alarm(a) => {
                print!("{}", out.out);
                return Err(a.header());
            }
        }
    }
    print!("{}", out.out);
    Ok(())
}

/// -fsyntax-only: the parser's findings alone.
fn syntax(name: &str, bytes: &[u8]) -> Compiled {
    let (_, diags) = grammar::parse(bytes);
    Compiled {
        module: None,
        files: vec![grammar::SourceFile::new(name, bytes)],
        diags: diags.into_iter().map(|d| (0, d)).collect(),
    }
}

/// Prints the diagnostics; true when the compilation failed.
fn report(c: &Compiled, json: bool, werror: bool, quiet: bool) -> bool {
    let mut failed = false;
    for (file, d) in &c.diags {
        let is_error = d.severity == Severity::Error || werror;
        if !is_error && quiet {
            continue;
        }
        failed |= is_error;
        let f = &c.files[*file];
        if json {
            eprintln!("{}", f.json(d));
        } else {
            eprintln!("{}", f.render(d));
        }
    }
    failed || c.has_errors()
}

fn write_output(
    c: &Compiled,
    input: &Path,
    output: Option<&Path>,
    listing: bool,
) -> Result<(), String> {
    let Some(module) = &c.module else {
        return Err("no module was produced".into());
    };
    let out = output.map(Path::to_path_buf).unwrap_or_else(|| {
        let name = input
            .file_name()
            .map(PathBuf::from)
            .unwrap_or_else(|| PathBuf::from("a"));
        name.with_extension(if listing { "s" } else { "gbc" })
    });
    let bytes = if listing {
        module.disassemble().into_bytes()
    } else {
        module.to_bytes()
    };
    if listing && out.as_os_str() == "-" {
        print!("{}", module.disassemble());
        return Ok(());
    }
    std::fs::write(&out, bytes).map_err(|e| format!("{}: {e}", out.display()))
}
