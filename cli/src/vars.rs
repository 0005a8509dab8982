//! `gbvm run --vars FILE`: #500–#999 kept in a text file, one `#n=value`
//! line per variable that is not vacant.
//!
//! The file is held for the whole run: opened once, refused unless it is a
//! writable regular file, and locked so that a second run on it stops at
//! once instead of racing. Each save writes a fresh temporary file with a
//! unique name beside the real file (created exclusively, so a planted link
//! is never followed), gives it FILE's permissions, fsyncs it and renames it
//! over FILE: a killed run leaves the old or the new values, never a torn
//! file. A FILE that is a symbolic link stays one; the values go to the
//! file it names. Saves are batched: at most one per [`SAVE_PERIOD`], the
//! last one when the run ends ([`VarsFile::finish`]).

use std::fs::{self, File, OpenOptions, TryLockError};
use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::{Duration, Instant};

/// The shortest time between two saves: a loop that changes #500 every
/// block costs one rewrite per period, not one per block, and a crash
/// loses at most this much of the newest values.
pub const SAVE_PERIOD: Duration = Duration::from_millis(100);

/// Attempts at opening FILE when another run replaces it meanwhile.
const OPEN_ATTEMPTS: usize = 8;

/// Parses the file's text: empty is all vacant; a malformed line is an error.
pub fn parse(text: &str, path: &Path) -> Result<[f64; 500], String> {
    let mut vars = [f64::NAN; 500];
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() {
            continue;
        }
        let bad = || {
            format!(
                "{}:{}: expected '#n=value' with n in 500…999, got '{line}'",
                path.display(),
                i + 1
            )
        };
        let (n, v) = line
            .strip_prefix('#')
            .and_then(|l| l.split_once('='))
            .ok_or_else(bad)?;
        let n: usize = n.trim().parse().map_err(|_| bad())?;
        let v: f64 = v.trim().parse().map_err(|_| bad())?;
        if !(500..=999).contains(&n) || !v.is_finite() {
            return Err(bad());
        }
        vars[n - 500] = v;
    }
    Ok(vars)
}

/// The file's text: increasing n, shortest round-trip values, vacant left out.
pub fn format(vars: &[f64; 500]) -> String {
    let mut out = String::new();
    for (i, v) in vars.iter().enumerate() {
        if !v.is_nan() {
            out.push_str(&format!("#{}={}\n", i + 500, v));
        }
    }
    out
}

/// The file the values really live in: FILE, or what a link FILE names.
fn real_path(path: &Path) -> Result<PathBuf, String> {
    let err = |e: std::io::Error| format!("{}: {e}", path.display());
    match fs::symlink_metadata(path) {
        // An existing file or link: resolve every link on the way.
        Ok(_) => fs::canonicalize(path).map_err(|e| {
            format!(
                "{}: {e} (a link to a missing file is not created)",
                path.display()
            )
        }),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            let name = path
                .file_name()
                .ok_or_else(|| format!("{}: not a file name", path.display()))?;
            let dir = match path.parent().filter(|d| !d.as_os_str().is_empty()) {
                Some(d) => fs::canonicalize(d).map_err(err)?,
                None => std::env::current_dir().map_err(err)?,
            };
            Ok(dir.join(name))
        }
        Err(e) => Err(err(e)),
    }
}

/// Opens FILE (creating it empty when missing) and locks it.
fn open_locked(shown: &Path, real: &Path) -> Result<File, String> {
    let err = |e: std::io::Error| format!("{}: {e}", shown.display());
    for _ in 0..OPEN_ATTEMPTS {
        if let Ok(meta) = fs::metadata(real) {
            if !meta.is_file() {
                return Err(format!("{}: not a regular file", shown.display()));
            }
            if meta.permissions().readonly() {
                return Err(format!(
                    "{}: the file is read-only; #500–#999 could not be kept",
                    shown.display()
                ));
            }
        }
        let file = match OpenOptions::new().read(true).write(true).open(real) {
            Ok(f) => f,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                // Exclusive creation: never through a link planted meanwhile.
                match OpenOptions::new()
                    .read(true)
                    .write(true)
                    .create_new(true)
                    .open(real)
                {
                    Ok(f) => f,
                    Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
                    Err(e) => return Err(err(e)),
                }
            }
            Err(e) => return Err(err(e)),
        };
        match file.try_lock() {
            Ok(()) => {}
            Err(TryLockError::WouldBlock) => {
                return Err(format!(
                    "{}: in use by another run (the file is locked)",
                    shown.display()
                ))
            }
            Err(TryLockError::Error(e)) => return Err(err(e)),
        }
        // Another run may have renamed a new file over FILE between our
        // open and our lock: then the lock holds a stale file; open again.
        if same_file(&file, real) {
            return Ok(file);
        }
    }
    Err(format!(
        "{}: replaced again and again while opening it",
        shown.display()
    ))
}

#[cfg(unix)]
fn same_file(file: &File, path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (file.metadata(), fs::metadata(path)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

#[cfg(not(unix))]
fn same_file(_: &File, _: &Path) -> bool {
    true
}

/// FILE, open and locked for a run.
struct Held {
    /// FILE as the user named it (for messages).
    shown: PathBuf,
    /// Where the values are written (links resolved).
    real: PathBuf,
    /// The current file, locked; replaced by each save.
    file: File,
    /// Values not yet saved.
    pending: Option<Box<[f64; 500]>>,
    last_save: Option<Instant>,
    period: Duration,
}

impl Held {
    fn save(&mut self, vars: &[f64; 500]) -> Result<(), String> {
        let err = |e: std::io::Error| format!("{}: {e}", self.shown.display());
        let dir = self.real.parent().unwrap_or(Path::new("."));
        let mut tmp = tempfile::Builder::new()
            .prefix(".gbvm-vars-")
            .tempfile_in(dir)
            .map_err(err)?;
        let perms = self.file.metadata().map_err(err)?.permissions();
        tmp.as_file().set_permissions(perms).map_err(err)?;
        // Locked before it becomes FILE, so FILE is never unlocked.
        tmp.as_file().lock().map_err(err)?;
        tmp.write_all(format(vars).as_bytes()).map_err(err)?;
        tmp.as_file().sync_all().map_err(err)?;
        let file = tmp.persist(&self.real).map_err(|e| err(e.error))?;
        // The rename itself must reach the disk too.
        if let Ok(d) = File::open(dir) {
            let _ = d.sync_all();
        }
        self.file = file;
        self.last_save = Some(Instant::now());
        Ok(())
    }

    fn store(&mut self, vars: &[f64; 500]) -> Result<(), String> {
        let due = self.last_save.is_none_or(|t| t.elapsed() >= self.period);
        if due {
            self.pending = None;
            self.save(vars)
        } else {
            match self.pending.as_mut() {
                Some(p) => **p = *vars,
                None => self.pending = Some(Box::new(*vars)),
            }
            Ok(())
        }
    }

    fn flush(&mut self) -> Result<(), String> {
        match self.pending.take() {
            Some(v) => self.save(&v),
            None => Ok(()),
        }
    }
}

/// `--vars FILE` for one run: hand [`VarsFile::storage`] to the VM and
/// call [`VarsFile::finish`] when the run is over.
pub struct VarsFile(Arc<Mutex<Held>>);

impl VarsFile {
    /// Opens and locks FILE and reads its values (a missing FILE is
    /// created empty: all vacant).
    pub fn open(path: &Path) -> Result<(VarsFile, [f64; 500]), String> {
        VarsFile::open_with_period(path, SAVE_PERIOD)
    }

    /// As [`VarsFile::open`], saving at most once per `period`.
    pub fn open_with_period(
        path: &Path,
        period: Duration,
    ) -> Result<(VarsFile, [f64; 500]), String> {
        let real = real_path(path)?;
        let mut file = open_locked(path, &real)?;
        let mut text = String::new();
        file.read_to_string(&mut text)
            .map_err(|e| format!("{}: {e}", path.display()))?;
        let values = parse(&text, path)?;
        let held = Held {
            shown: path.to_path_buf(),
            real,
            file,
            pending: None,
            last_save: None,
            period,
        };
        Ok((VarsFile(Arc::new(Mutex::new(held))), values))
    }

    /// The VM's storage hook; it shares this file.
    pub fn storage(&self) -> Box<dyn vm::Storage> {
        Box::new(Storage(Arc::clone(&self.0)))
    }

    /// Saves what is still pending; the lock ends with `self`.
    pub fn finish(self) -> Result<(), String> {
        self.0
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .flush()
    }
}

/// The VM's side of a [`VarsFile`].
struct Storage(Arc<Mutex<Held>>);

impl vm::Storage for Storage {
    fn store(&mut self, persistent: &[f64; 500]) -> Result<(), String> {
        self.0
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .store(persistent)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp_dir(tag: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("gbc-vars-{tag}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn values_are_written_in_shortest_round_trip_form() {
        let mut v = [f64::NAN; 500];
        v[0] = 0.1;
        v[1] = -3.0;
        v[2] = 123.456;
        assert_eq!(format(&v), "#500=0.1\n#501=-3\n#502=123.456\n");
    }

    #[test]
    fn save_then_load_round_trips_and_bad_files_are_rejected() {
        let dir = temp_dir("round");
        let file = dir.join("vars.txt");
        let (store, back) = VarsFile::open(&file).unwrap();
        assert!(back.iter().all(|x| x.is_nan()), "a missing file is vacant");
        let mut v = [f64::NAN; 500];
        v[499] = 1.0 / 3.0;
        store.storage().store(&v).unwrap();
        store.finish().unwrap();
        let (_store, back) = VarsFile::open(&file).unwrap();
        assert_eq!(back[499].to_bits(), v[499].to_bits());
        assert!(back[0].is_nan());
        assert!(parse("#100=1\n", &file).is_err());
        assert!(parse("#500=abc\n", &file).is_err());
        assert!(parse("#500=inf\n", &file).is_err());
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn saves_within_a_period_wait_for_the_next_one_or_the_end() {
        let dir = temp_dir("batch");
        let file = dir.join("vars.txt");
        let (store, _) = VarsFile::open_with_period(&file, Duration::from_secs(3600)).unwrap();
        let mut hook = store.storage();
        let mut v = [f64::NAN; 500];
        for i in 0..1000 {
            v[0] = f64::from(i);
            hook.store(&v).unwrap();
        }
        // The first store is saved at once, the other 999 within the hour
        // are held back...
        assert_eq!(fs::read_to_string(&file).unwrap(), "#500=0\n");
        // ...and the newest is saved when the run ends.
        store.finish().unwrap();
        assert_eq!(fs::read_to_string(&file).unwrap(), "#500=999\n");
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_second_open_of_a_held_file_is_refused() {
        let dir = temp_dir("lock");
        let file = dir.join("vars.txt");
        let (store, _) = VarsFile::open(&file).unwrap();
        let mut v = [f64::NAN; 500];
        v[1] = 2.0;
        // A save replaces the file; the new one is locked too.
        store.storage().store(&v).unwrap();
        let again = VarsFile::open(&file).err().unwrap();
        assert!(again.contains("in use by another run"), "{again}");
        drop(store);
        assert!(VarsFile::open(&file).is_ok());
        fs::remove_dir_all(&dir).unwrap();
    }
}
