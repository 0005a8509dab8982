//! Inputs and outputs as gcc names them: `-` is standard input or output,
//! write errors are reported (never a panic), and an output never
//! replaces an input.

use std::io::{Read, Seek, Write};
use std::path::{Path, PathBuf};
use std::sync::Arc;

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

/// Standard error for diagnostics, or, when it was closed as the tool
/// started (`2>&-`), a sink whose every write fails: what could not be
/// told is then told by the exit code (3), as when standard error is full.
pub enum ErrStream {
    Open(std::io::BufWriter<std::io::Stderr>),
    Closed,
}

impl ErrStream {
    pub fn new(closed: bool) -> ErrStream {
        match closed {
            true => ErrStream::Closed,
            false => ErrStream::Open(std::io::BufWriter::new(std::io::stderr())),
        }
    }
}

impl Write for ErrStream {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        match self {
            ErrStream::Open(w) => w.write(buf),
            ErrStream::Closed => Err(closed_stderr()),
        }
    }

    fn flush(&mut self) -> std::io::Result<()> {
        match self {
            ErrStream::Open(w) => w.flush(),
            ErrStream::Closed => Ok(()),
        }
    }
}

fn closed_stderr() -> std::io::Error {
    std::io::Error::other("standard error is closed")
}

/// The name diagnostics give standard input.
pub const STDIN_NAME: &str = "<stdin>";

/// The most read from a stream (standard input, a pipe): its length is not
/// known ahead, and an endless one (`cat /dev/zero |`) must end. A GiB is
/// some forty million blocks, far more than any program or module.
pub const MAX_STREAM: u64 = 1 << 30;

/// Reads an input: `-` is standard input. Returns the name for messages.
pub fn read_input(path: &Path) -> Result<(String, Vec<u8>), String> {
    if path.as_os_str() == "-" {
        let bytes = read_stream(std::io::stdin().lock(), MAX_STREAM)
            .map_err(|e| format!("{STDIN_NAME}: {e}"))?;
        return Ok((STDIN_NAME.into(), bytes));
    }
    let name = path.display().to_string();
    let bytes = read_file(path).map_err(|e| format!("{name}: {e}"))?;
    Ok((name, bytes))
}

/// [`read_input`] into a shared buffer, as the compiler keeps a source
/// (shared with its diagnostics).
pub fn read_input_shared(path: &Path) -> Result<(String, Arc<[u8]>), String> {
    if path.as_os_str() == "-" {
        let (name, bytes) = read_input(path)?;
        return Ok((name, bytes.into()));
    }
    let name = path.display().to_string();
    let bytes = read_file_shared(path).map_err(|e| format!("{name}: {e}"))?;
    Ok((name, bytes))
}

/// [`read_file`] into a shared buffer. A regular file is read straight
/// into it: read into a vector first, a source was copied once more into
/// fresh pages (`gbcc` on a 4.5 MB program: 5 007 page faults then, 4 021
/// now). A file whose length changes while it is read is read again the
/// usual way.
pub fn read_file_shared(path: &Path) -> std::io::Result<Arc<[u8]>> {
    let (mut file, kind) = open_readable(path)?;
    let len = usize::try_from(file.metadata()?.len()).unwrap_or(usize::MAX);
    if !kind.is_file() || len > MAX_STREAM as usize {
        return read_opened(file, kind).map(Arc::from);
    }
    // (Zeroed memory from the system costs no pass over it.)
    let zeroed = Arc::<[u8]>::new_zeroed_slice(len);
    // SAFETY: the slice's memory is filled with 0 bytes, and a 0 byte is
    // an initialised `u8`.
    let mut bytes = unsafe { zeroed.assume_init() };
    let read_whole = match Arc::get_mut(&mut bytes) {
        Some(buf) => file.read_exact(buf).is_ok() && file.read(&mut [0u8; 1])? == 0,
        None => false,
    };
    if read_whole {
        return Ok(bytes);
    }
    drop(bytes);
    file.seek(std::io::SeekFrom::Start(0))?;
    read_opened(file, kind).map(Arc::from)
}

/// A file given as text (a machine file, a `--vars` file), as
/// [`read_file`] reads it; the message names the file.
pub fn read_text(path: &Path) -> Result<String, String> {
    let bytes = read_file(path).map_err(|e| format!("{}: {e}", path.display()))?;
    String::from_utf8(bytes).map_err(|_| format!("{}: not UTF-8 text", path.display()))
}

/// A file's bytes: a regular file whole, a pipe (`<(…)`) or socket up to
/// [`MAX_STREAM`]. A device or a folder is refused, before it is opened
/// (an endless device such as /dev/zero was read until memory ran out,
/// and opening some devices does something); what was opened is looked
/// at again, in case the name changed in between.
pub fn read_file(path: &Path) -> std::io::Result<Vec<u8>> {
    let (file, kind) = open_readable(path)?;
    read_opened(file, kind)
}

/// `path` opened for reading, if it is a regular file or a stream, with
/// its kind.
fn open_readable(path: &Path) -> std::io::Result<(std::fs::File, std::fs::FileType)> {
    refuse_kind(std::fs::metadata(path)?.file_type())?;
    let file = std::fs::File::open(path)?;
    let kind = file.metadata()?.file_type();
    refuse_kind(kind)?;
    Ok((file, kind))
}

/// The rest of an opened file (or stream, up to [`MAX_STREAM`]).
fn read_opened(mut file: std::fs::File, kind: std::fs::FileType) -> std::io::Result<Vec<u8>> {
    if !kind.is_file() {
        return read_stream(file, MAX_STREAM);
    }
    let mut bytes = Vec::new();
    file.read_to_end(&mut bytes)?;
    Ok(bytes)
}

/// Only a regular file or a stream is read.
fn refuse_kind(kind: std::fs::FileType) -> std::io::Result<()> {
    if kind.is_file() || is_stream(kind) {
        return Ok(());
    }
    let what = if kind.is_dir() {
        "a folder"
    } else {
        "a device"
    };
    Err(std::io::Error::other(format!(
        "not a regular file ({what})"
    )))
}

/// A pipe or a socket: read as standard input is.
fn is_stream(kind: std::fs::FileType) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        kind.is_fifo() || kind.is_socket()
    }
    #[cfg(not(unix))]
    {
        let _ = kind;
        false
    }
}

/// Reads `from` to its end, failing past `cap` bytes (the bytes read so
/// far are dropped: memory stays bounded whatever the stream).
pub fn read_stream(from: impl Read, cap: u64) -> std::io::Result<Vec<u8>> {
    let mut bytes = Vec::new();
    from.take(cap.saturating_add(1)).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > cap {
        let most = match cap % (1 << 20) {
            0 => format!("{} MiB", cap >> 20),
            _ => format!("{cap} bytes"),
        };
        return Err(std::io::Error::other(format!(
            "longer than {most}, the most read from standard input or a pipe"
        )));
    }
    Ok(bytes)
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

/// Whether `path` is a regular file (not a link to one) that begins as a
/// compiled module does.
pub fn is_module_file(path: &Path) -> bool {
    if !std::fs::symlink_metadata(path).is_ok_and(|m| m.is_file()) {
        return false;
    }
    let mut head = [0u8; isa::format::MAGIC.len()];
    std::fs::File::open(path).is_ok_and(|mut f| f.read_exact(&mut head).is_ok()) && is_module(&head)
}

#[cfg(test)]
mod tests {
    use super::read_stream;

    /// An endless stream ends at the cap; one within it is read whole.
    #[test]
    fn streams_are_read_up_to_the_cap() {
        let err = read_stream(std::io::repeat(b'X'), 1000).unwrap_err();
        assert!(err.to_string().contains("longer than 1000 bytes"), "{err}");
        assert_eq!(read_stream(&b"G00 X1\n"[..], 7).unwrap(), b"G00 X1\n");
        assert!(read_stream(&b"G00 X1\n"[..], 6).is_err());
    }

    /// A file read into a shared buffer holds its bytes exactly, an empty
    /// one too; a folder is refused as by `read_file`.
    #[test]
    fn files_are_read_whole_into_a_shared_buffer() {
        let dir = std::env::temp_dir().join(format!("gbc-io-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let text: Vec<u8> = (0..70_000u32).map(|i| (i % 251) as u8).collect();
        for (name, bytes) in [("long.nc", &text[..]), ("empty.nc", &[][..])] {
            let path = dir.join(name);
            std::fs::write(&path, bytes).unwrap();
            assert_eq!(&*super::read_file_shared(&path).unwrap(), bytes, "{name}");
        }
        let err = super::read_file_shared(&dir).unwrap_err();
        assert!(err.to_string().contains("a folder"), "{err}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
