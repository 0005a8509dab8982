//! Inputs and outputs as gcc names them: `-` is standard input or output,
//! write errors are reported (never a panic), and an output never
//! replaces an input.

use std::io::{Read, Write};
use std::path::{Path, PathBuf};

/// Where an output goes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Dest {
    Stdout,
    File(PathBuf),
}

impl Dest {
    /// `-o -` is standard output.
    pub fn new(path: &Path) -> Dest {
        if path.as_os_str() == "-" {
            Dest::Stdout
        } else {
            Dest::File(path.to_path_buf())
        }
    }

    /// The name messages give it.
    pub fn name(&self) -> String {
        match self {
            Dest::Stdout => "<stdout>".into(),
            Dest::File(p) => p.display().to_string(),
        }
    }

    /// Writes what `produce` hands its sink, buffered, piece by piece;
    /// the message names the output and the cause.
    pub fn write_with(
        &self,
        produce: impl FnOnce(&mut dyn FnMut(&[u8]) -> std::io::Result<()>) -> std::io::Result<()>,
    ) -> Result<(), String> {
        fn to(
            out: impl Write,
            produce: impl FnOnce(&mut dyn FnMut(&[u8]) -> std::io::Result<()>) -> std::io::Result<()>,
        ) -> std::io::Result<()> {
            let mut out = std::io::BufWriter::with_capacity(1 << 16, out);
            produce(&mut |bytes| out.write_all(bytes))?;
            out.flush()
        }
        let done = match self {
            Dest::Stdout => to(std::io::stdout().lock(), produce),
            Dest::File(p) => std::fs::File::create(p).and_then(|f| to(f, produce)),
        };
        done.map_err(|e| format!("cannot write {}: {e}", self.name()))
    }

    /// Writes `bytes` in full; the message names the output and the cause.
    pub fn write(&self, bytes: &[u8]) -> Result<(), String> {
        let done = match self {
            Dest::Stdout => {
                let mut out = std::io::stdout().lock();
                out.write_all(bytes).and_then(|()| out.flush())
            }
            Dest::File(p) => std::fs::write(p, bytes),
        };
        done.map_err(|e| format!("cannot write {}: {e}", self.name()))
    }
}

/// The name diagnostics give standard input.
pub const STDIN_NAME: &str = "<stdin>";

/// Reads an input: `-` is standard input. Returns the name for messages.
pub fn read_input(path: &Path) -> Result<(String, Vec<u8>), String> {
    if path.as_os_str() == "-" {
        let mut bytes = Vec::new();
        std::io::stdin()
            .lock()
            .read_to_end(&mut bytes)
            .map_err(|e| format!("{STDIN_NAME}: {e}"))?;
        return Ok((STDIN_NAME.into(), bytes));
    }
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok((path.display().to_string(), bytes))
}

/// Whether `a` and `b` name the same existing file (through links too).
pub fn same_file(a: &Path, b: &Path) -> bool {
    let (Ok(ma), Ok(mb)) = (std::fs::metadata(a), std::fs::metadata(b)) else {
        return false;
    };
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        ma.dev() == mb.dev() && ma.ino() == mb.ino()
    }
    #[cfg(not(unix))]
    {
        let _ = (ma, mb);
        matches!((a.canonicalize(), b.canonicalize()), (Ok(x), Ok(y)) if x == y)
    }
}

/// Whether `bytes` are a compiled module rather than a source program.
pub fn is_module(bytes: &[u8]) -> bool {
    bytes.starts_with(&isa::format::MAGIC)
}
