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

/// Where writing `path` would land: the file it names with every link
/// resolved (a dangling link too: the file writing through it creates),
/// or, for a name not there yet, its folder's real path and the name.
/// `None` when that cannot be told (a missing folder, a link loop).
pub fn landing(path: &Path) -> Option<PathBuf> {
    let mut p = path.to_path_buf();
    // (Past 40 links the system gives up too: a loop.)
    for _ in 0..40 {
        if let Ok(real) = p.canonicalize() {
            return Some(real);
        }
        match std::fs::read_link(&p) {
            // A relative target is relative to the link's folder.
            Ok(target) => p = p.parent().map_or(target.clone(), |d| d.join(&target)),
            Err(_) => {
                let dir = match p.parent().filter(|d| !d.as_os_str().is_empty()) {
                    Some(d) => d.canonicalize().ok()?,
                    None => std::env::current_dir().ok()?,
                };
                return Some(dir.join(p.file_name()?));
            }
        }
    }
    None
}

/// Whether writing `out` would replace `other`: the same file (by any
/// name, link or hard link), or the same place when neither is there yet
/// (an output and the dependency file named alike). Writing to a device
/// or a pipe (`/dev/null`) replaces nothing.
pub fn replaces(out: &Path, other: &Path) -> bool {
    if std::fs::metadata(out).is_ok_and(|m| !m.is_file()) {
        return false;
    }
    same_file(out, other) || matches!((landing(out), landing(other)), (Some(a), Some(b)) if a == b)
}

/// Whether `bytes` are a compiled module rather than a source program.
pub fn is_module(bytes: &[u8]) -> bool {
    bytes.starts_with(&isa::format::MAGIC)
}
