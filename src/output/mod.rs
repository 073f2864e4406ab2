//! Results on disk: CSV tables (through polars) and VTK unstructured grids for
//! ParaView. Every file is written atomically: to a temporary file in the same
//! directory, flushed, then renamed, so an interrupted run leaves either the old
//! file or the new one, never half of one.

pub mod csv;
pub mod markdown;
pub mod plot;
pub mod raster;
pub mod rows;
pub mod run;
pub mod rundir;
pub mod runplot;
pub mod scene;
pub mod vtu;

/// A table or figure file that could not be read or written.
#[derive(Debug, thiserror::Error)]
pub enum FileError {
    /// The file system refused to read or write the file.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// What the file system said.
        source: std::io::Error,
    },
    /// A table whose text or contents are not what the reader expects.
    #[error("table {path}: {message}")]
    Table {
        /// The file, with `:line` when the fault is on one line.
        path: String,
        /// What is wrong.
        message: String,
    },
    /// A figure that could not be drawn or written.
    #[error("figure {path}: {message}")]
    Plot {
        /// The figure's file.
        path: String,
        /// What went wrong.
        message: String,
    },
    /// A path that is not what the reader reads (not a run directory); the caller
    /// names the path.
    #[error("{message}")]
    NotThere {
        /// What is missing, and what the reader reads instead (without the path).
        message: String,
    },
}

use std::io::Write;
use std::path::Path;

// ANCHOR: held_lock
/// An exclusive lock on a file that exists only while it is held, so that no lock
/// file is left behind a finished run.
///
/// Taking it: open the path (creating it), lock the open file, and check that the
/// path still names that file; if not, a holder that was releasing it unlinked it
/// between our open and our lock, and we try again on a fresh file. Releasing it:
/// unlink the path while the lock is still held, then close. Every holder has seen
/// the path name its file while holding it, and only a holder unlinks, so two
/// processes never hold "the" lock at once. A killed holder leaves the file, unlocked:
/// the next one takes it and removes it.
#[derive(Debug)]
pub struct HeldLock {
    _file: std::fs::File,
    path: std::path::PathBuf,
}

impl Drop for HeldLock {
    fn drop(&mut self) {
        // Still held here: `file` closes (and the kernel releases the lock) after
        // this body, when the fields drop.
        let _ = std::fs::remove_file(&self.path);
    }
}

/// Whether `a` and `b` describe the same file.
#[cfg(unix)]
fn same_file(a: &std::fs::Metadata, b: &std::fs::Metadata) -> bool {
    use std::os::unix::fs::MetadataExt;
    a.dev() == b.dev() && a.ino() == b.ino()
}

#[cfg(not(unix))]
fn same_file(_: &std::fs::Metadata, _: &std::fs::Metadata) -> bool {
    true
}

/// Takes the [`HeldLock`] of `path`: `Ok(None)` when another process holds it.
pub fn try_lock_file(path: &Path) -> std::io::Result<Option<HeldLock>> {
    for _ in 0..1000 {
        let file = std::fs::File::options()
            .create(true)
            .truncate(false)
            .write(true)
            .open(path)?;
        if file.try_lock().is_err() {
            return Ok(None);
        }
        match std::fs::metadata(path) {
            Ok(m) if same_file(&m, &file.metadata()?) => {
                return Ok(Some(HeldLock {
                    _file: file,
                    path: path.to_path_buf(),
                }));
            }
            // Unlinked (or replaced) since we opened it: a fresh file next time.
            _ => continue,
        }
    }
    Err(std::io::Error::other(format!(
        "the lock file {} kept being replaced while we took it",
        path.display()
    )))
}
// ANCHOR_END: held_lock

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
