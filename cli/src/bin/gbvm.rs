//! `gbvm`: runs, disassembles and verifies `.gbc` modules.

use clap::{Parser, Subcommand, ValueEnum};
use nc::{Event, Sink};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use vm::{Status, Vm};

#[derive(Parser)]
#[command(name = "gbvm", version, about = "Run gbc bytecode")]
struct Args {
    #[command(subcommand)]
    command: Command,
}

#[derive(Clone, Copy, ValueEnum)]
enum Emit {
    Canon,
    Trace,
}

#[derive(Subcommand)]
enum Command {
    /// Run a module and print what the machine is told to do.
    Run {
        file: PathBuf,
        /// canon: the motion listing of canon.md.
        #[arg(long, value_enum, default_value = "canon")]
        emit: Emit,
        #[arg(long, value_name = "FILE")]
        machine: Option<PathBuf>,
        /// Block budget (E6005 past it); default run.max_blocks.
        #[arg(long, value_name = "N")]
        max_blocks: Option<u64>,
        /// Passes a main-program M99 makes before the run ends.
        #[arg(long, value_name = "N", default_value_t = 1)]
        repeat: u32,
        /// Keep #500–#999 in FILE (loaded at the start, rewritten
        /// crash-safely whenever the program changes them).
        #[arg(long, value_name = "FILE")]
        vars: Option<PathBuf>,
    },
    /// Print the annotated listing of a module.
    Disasm { file: PathBuf },
    /// Load and verify a module.
    Verify { file: PathBuf },
}

fn load(path: &Path) -> Result<isa::Module, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    isa::Module::from_bytes(&bytes)
        .map_err(|e| format!("{}: not a valid .gbc module: {e}", path.display()))
}

fn fail(msg: &str) -> ExitCode {
    eprintln!("gbvm: error: {msg}");
    ExitCode::from(1)
}

/// Prints each event as one canon line.
struct Canon<W: Write> {
    out: W,
    broken: bool,
}

impl<W: Write> Sink for Canon<W> {
    fn emit(&mut self, e: Event) {
        if !self.broken && writeln!(self.out, "{e}").is_err() {
            self.broken = true;
        }
    }
}

fn main() -> ExitCode {
    let args = Args::parse();
    match args.command {
        Command::Disasm { file } => match load(&file) {
            Ok(m) => {
                print!("{}", m.disassemble());
                ExitCode::SUCCESS
            }
            Err(e) => fail(&e),
        },
        Command::Verify { file } => match load(&file) {
            Ok(_) => {
                println!("{}: ok", file.display());
                ExitCode::SUCCESS
            }
            Err(e) => fail(&e),
        },
        Command::Run {
            file,
            emit,
            machine,
            max_blocks,
            repeat,
            vars,
        } => {
            if let Emit::Trace = emit {
                return fail("--emit trace needs the interpolation runtime, which this build does not have yet");
            }
            run(
                &file,
                machine.as_deref(),
                max_blocks,
                repeat,
                vars.as_deref(),
            )
        }
    }
}

fn run(
    file: &Path,
    machine: Option<&Path>,
    max_blocks: Option<u64>,
    repeat: u32,
    vars: Option<&Path>,
) -> ExitCode {
    let module = match load(file) {
        Ok(m) => m,
        Err(e) => return fail(&e),
    };
    let machine = match cli::load_machine(machine) {
        Ok(m) => m,
        Err(e) => return fail(&e),
    };
    if module.machine != machine.compile_keys() {
        return fail(&format!(
            "{} was compiled for another machine configuration (its compile-time keys differ); compile it again with this --machine",
            file.display()
        ));
    }
    let mut vm = Vm::new(module, machine);
    if let Some(n) = max_blocks {
        vm.max_blocks = n;
    }
    vm.repeat = repeat.max(1);
    let store = vars.map(Path::to_path_buf).or_else(|| {
        let f = &vm.nc.machine.r#macro.persistent_file;
        (!f.is_empty()).then(|| PathBuf::from(f))
    });
    if let Some(path) = store {
        match cli::vars::load(&path) {
            Ok(values) => *vm.persistent_mut() = values,
            Err(e) => return fail(&e),
        }
        vm.set_storage(Box::new(cli::vars::FileStorage(path)));
    }
    let stdout = std::io::stdout();
    let mut sink = Canon {
        out: BufWriter::new(stdout.lock()),
        broken: false,
    };
    let status = vm.run(&mut sink);
    let _ = sink.out.flush();
    match status {
        Status::Alarm(a) => {
            eprintln!("{}", a.header());
            ExitCode::from(2)
        }
        _ => ExitCode::SUCCESS,
    }
}
