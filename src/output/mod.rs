//! Results on disk: CSV tables (through polars) and VTK unstructured grids for
//! ParaView. Every file is written atomically: to a temporary file in the same
//! directory, flushed, then renamed, so an interrupted run leaves either the old
//! file or the new one, never half of one.

pub mod csv;
pub mod markdown;
pub mod run;
pub mod rundir;
pub mod vtu;

use std::io::Write;
use std::path::Path;

/// Opens (creating it if missing, never truncating or deleting it) the lock file
/// `path` and takes its exclusive lock: `Ok(None)` when another process holds it.
/// The kernel releases the lock when the returned file is closed or the process ends.
pub fn try_lock_file(path: &Path) -> std::io::Result<Option<std::fs::File>> {
    let file = std::fs::File::options()
        .create(true)
        .truncate(false)
        .write(true)
        .open(path)?;
    Ok(file.try_lock().is_ok().then_some(file))
}

/// Whether process `pid` may still be running, for removing what a killed process
/// left behind (temporaries and scratch directories named by their process): this
/// process, or one that `/proc` still lists. Where there is no `/proc` to ask, every
/// process counts as running, so nothing of a live one is removed.
pub fn process_alive(pid: u32) -> bool {
    if pid == std::process::id() || cfg!(not(target_os = "linux")) {
        return true;
    }
    Path::new(&format!("/proc/{pid}")).exists()
}

/// Writes `bytes` to `path` atomically (temporary file + rename).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let dir = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir)?;
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tmp = dir.join(format!(".{name}.tmp-{}", std::process::id()));
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}
