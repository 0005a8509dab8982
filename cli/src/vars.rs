//! `gbvm run --vars FILE`: #500–#999 kept in a text file, one `#n=value`
//! line per variable that is not vacant, rewritten crash-safely (temporary
//! file, fsync, rename) so a killed run leaves the old or the new values.

use std::fs::{self, File};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Reads FILE: a missing file is all vacant; a malformed one is an error.
pub fn load(path: &Path) -> Result<[f64; 500], String> {
    let mut vars = [f64::NAN; 500];
    let text = match fs::read_to_string(path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(vars),
        Err(e) => return Err(format!("{}: {e}", path.display())),
    };
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

/// Writes FILE atomically.
pub fn save(path: &Path, vars: &[f64; 500]) -> Result<(), String> {
    let err = |e: std::io::Error| format!("{}: {e}", path.display());
    let tmp = temp_name(path);
    let mut f = File::create(&tmp).map_err(err)?;
    f.write_all(format(vars).as_bytes()).map_err(err)?;
    f.sync_all().map_err(err)?;
    drop(f);
    fs::rename(&tmp, path).map_err(err)?;
    // The rename itself must reach the disk too.
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        if let Ok(d) = File::open(dir) {
            let _ = d.sync_all();
        }
    }
    Ok(())
}

fn temp_name(path: &Path) -> PathBuf {
    let mut name = path
        .file_name()
        .map(|n| n.to_os_string())
        .unwrap_or_default();
    name.push(".tmp");
    path.with_file_name(name)
}

/// The VM's storage hook over a file.
pub struct FileStorage(pub PathBuf);

impl vm::Storage for FileStorage {
    fn store(&mut self, persistent: &[f64; 500]) -> Result<(), String> {
        save(&self.0, persistent)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
        let dir = std::env::temp_dir().join(format!("gbc-vars-{}", std::process::id()));
        fs::create_dir_all(&dir).unwrap();
        let file = dir.join("vars.txt");
        let mut v = [f64::NAN; 500];
        v[499] = 1.0 / 3.0;
        save(&file, &v).unwrap();
        let back = load(&file).unwrap();
        assert_eq!(back[499].to_bits(), v[499].to_bits());
        assert!(back[0].is_nan());
        assert!(load(&dir.join("missing"))
            .unwrap()
            .iter()
            .all(|x| x.is_nan()));
        fs::write(&file, "#100=1\n").unwrap();
        assert!(load(&file).is_err());
        fs::write(&file, "#500=abc\n").unwrap();
        assert!(load(&file).is_err());
        fs::remove_dir_all(&dir).unwrap();
    }
}
