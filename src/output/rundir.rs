//! A run's output directory, published as one set.
//!
//! A run writes every file into a staging directory beside the target
//! (`.NAME.staging-PID`), then swaps the two in one atomic rename (Linux
//! `renameat2(RENAME_EXCHANGE)`; elsewhere two renames). A reader of the target
//! therefore sees the previous set or the new one, never a mix, whatever interrupts
//! the run. A lock beside the target (`.NAME.lock`, a [`super::HeldLock`]: it exists
//! only while a run holds it, and the kernel releases it when the process dies)
//! makes a second writer fail at once. Leftovers of a killed run
//! (staging directories, an old set that was swapped out) are removed by the next
//! run that takes the lock.
//!
//! The target must be absent, empty, or a directory this program wrote (it holds
//! the marker `.evhi-run`, which lists the files of its set): a directory holding
//! other files is refused, so that a mistyped `--out` can never replace the user's
//! files.

use std::fs::File;
use std::path::{Path, PathBuf};

/// Marks a directory as a run directory written by this program.
pub const MARKER: &str = ".evhi-run";

/// Test hook: milliseconds to sleep after each file written, so that a test can
/// interrupt the write phase (`EVHI_WRITE_DELAY_MS`).
pub const DELAY_ENV: &str = "EVHI_WRITE_DELAY_MS";

/// The files a run writes into its directory (besides [`MARKER`] and the numbered
/// snapshots `solution_NNNNNN.vtu` of `--vtk-every`).
pub const RUN_FILES: [&str; 15] = [
    "contact.csv",
    "estimator.csv",
    "summary.csv",
    "steps.csv",
    "nodes.csv",
    "evolution.csv",
    "regimes.csv",
    "scenario.toml",
    "solution.vtu",
    "solution.pvd",
    "deformed.png",
    "deformed.svg",
    "evolution.png",
    "evolution.svg",
    MARKER,
];

/// Whether `name` is a file a run writes ([`RUN_FILES`], a numbered snapshot, or the
/// temporary of one of them that an interrupted write left: `.FILE.tmp-PID` or, for a
/// figure, `.STEM.tmp-PID.EXT`, with FILE or STEM.EXT a run's file and PID digits).
/// A user's `.notes.tmp-1.txt` is no run's and is never taken for one.
pub fn is_run_file(name: &str) -> bool {
    RUN_FILES.contains(&name) || is_run_temporary(name) || is_snapshot(name)
}

fn is_run_temporary(name: &str) -> bool {
    let Some((stem, rest)) = name.strip_prefix('.').and_then(|n| n.split_once(".tmp-")) else {
        return false;
    };
    let digits = |d: &str| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit());
    match rest.split_once('.') {
        None => digits(rest) && is_snapshot_or_file(stem),
        Some((pid, ext)) => digits(pid) && is_snapshot_or_file(&format!("{stem}.{ext}")),
    }
}

fn is_snapshot_or_file(name: &str) -> bool {
    RUN_FILES.contains(&name) || is_snapshot(name)
}

fn is_snapshot(name: &str) -> bool {
    name.strip_prefix("solution_")
        .and_then(|r| r.strip_suffix(".vtu"))
        .is_some_and(|d| d.len() >= 6 && d.bytes().all(|b| b.is_ascii_digit()))
}

/// Why the output directory cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum OutError {
    /// The directory cannot be used; `role` names it as the command does (`--out` for
    /// a run being written, `run directory` for one `evhi plot` redraws).
    #[error("{role} `{path}`: {message}")]
    Unusable {
        /// The directory as the command names it (`--out` or `run directory`).
        role: &'static str,
        /// The directory.
        path: String,
        /// Why it cannot be used.
        message: String,
    },
    /// Another process holds the directory's lock.
    #[error("{role} `{path}`: another evhi run is writing to it (lock `{lock}`); {remedy}")]
    Busy {
        /// The directory as the command names it (`--out` or `run directory`).
        role: &'static str,
        /// The directory.
        path: String,
        /// The lock file, `.NAME.lock` beside the directory.
        lock: String,
        /// What to do about it.
        remedy: &'static str,
    },
    /// A file or directory of the run could not be written.
    #[error("writing `{path}`: {source}")]
    Io {
        /// The file or directory.
        path: String,
        /// What the file system said.
        source: std::io::Error,
    },
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> OutError + '_ {
    move |source| OutError::Io {
        path: path.display().to_string(),
        source,
    }
}

/// An output directory being written: files go to [`RunDir::path`], and
/// [`RunDir::publish`] makes them the target's content at once.
pub struct RunDir {
    target: PathBuf,
    staging: PathBuf,
    _lock: super::HeldLock,
    delay: Option<std::time::Duration>,
}

impl RunDir {
    /// Checks `target`, takes its lock and creates the staging directory: every
    /// reason the output cannot be written shows here, before any computation.
    pub fn open(target: &Path) -> Result<RunDir, OutError> {
        let unusable = |message: String| OutError::Unusable {
            role: WRITER.role,
            path: target.display().to_string(),
            message,
        };
        let (parent, name) = parent_and_name(target, WRITER)?;
        if let Ok(meta) = std::fs::symlink_metadata(target) {
            if meta.file_type().is_symlink() {
                return Err(unusable(
                    "is a symbolic link; a run replaces its directory as a whole, so name \
                     the directory itself (or a new path)"
                        .into(),
                ));
            }
            if !meta.is_dir() {
                return Err(unusable(
                    "exists and is not a directory; choose a directory path".into(),
                ));
            }
            let foreign: Vec<String> = std::fs::read_dir(target)
                .map_err(|e| unusable(format!("cannot be read: {e}")))?
                .filter_map(|e| e.ok())
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .collect();
            if !foreign.is_empty() && !target.join(MARKER).exists() {
                return Err(unusable(format!(
                    "is a directory with files in it that is not an evhi run directory (it \
                     has no `{MARKER}`; for example it holds `{}`), and a run replaces its \
                     directory as a whole; choose a new or empty directory (for runs kept \
                     side by side, name one inside it)",
                    foreign[0]
                )));
            }
            // An earlier run directory is replaced as a whole: refuse if the user has
            // put anything else in it, rather than delete it with the old set. Ours
            // are a run's files and those the marker lists (a study's own set).
            let listed = listed_files(target);
            let mut others: Vec<String> = foreign
                .iter()
                .filter(|n| !is_run_file(n) && !listed.contains(n))
                .map(|n| {
                    if target.join(n).is_dir() {
                        format!("{n}/")
                    } else {
                        n.clone()
                    }
                })
                .collect();
            if !others.is_empty() {
                others.sort();
                return Err(unusable(format!(
                    "is an earlier run directory that also holds files evhi did not write ({}); \
                     a new run replaces the whole directory, so move them out or choose \
                     another --out",
                    others
                        .iter()
                        .map(|n| format!("`{n}`"))
                        .collect::<Vec<_>>()
                        .join(", ")
                )));
            }
        }
        std::fs::create_dir_all(&parent)
            .map_err(|e| unusable(format!("its parent cannot be created: {e}")))?;
        let lock = lock_beside(target, &parent, &name, WRITER)?;
        clean_leftovers(&parent, &name, target);
        let staging = parent.join(format!(".{name}.staging-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&staging);
        std::fs::create_dir(&staging).map_err(|e| {
            unusable(format!(
                "cannot create a directory beside it (`{}`): {e}",
                staging.display()
            ))
        })?;
        let delay = std::env::var(DELAY_ENV)
            .ok()
            .and_then(|v| v.parse::<u64>().ok())
            .map(std::time::Duration::from_millis);
        Ok(RunDir {
            target: target.to_path_buf(),
            staging,
            _lock: lock,
            delay,
        })
    }

    /// Where to write `file` of the set.
    pub fn path(&self, file: &str) -> PathBuf {
        self.staging.join(file)
    }

    /// Writes `bytes` as `file` of the set.
    pub fn write(&self, file: &str, bytes: &[u8]) -> Result<(), OutError> {
        let path = self.path(file);
        std::fs::write(&path, bytes).map_err(io(&path))?;
        self.pause();
        Ok(())
    }

    /// The test hook's pause after a file (see [`DELAY_ENV`]).
    pub fn pause(&self) {
        if let Some(d) = self.delay {
            std::thread::sleep(d);
        }
    }

    /// Writes a table as `file` of the set, with its `#` comment lines.
    pub fn write_table(
        &self,
        file: &str,
        table: &super::csv::Table,
        comments: &[String],
    ) -> Result<(), OutError> {
        let path = self.path(file);
        table.write(&path, comments).map_err(io(&path))?;
        self.pause();
        Ok(())
    }

    /// Makes the staged set the target's content in one step and removes the old set.
    pub fn publish(self) -> Result<(), OutError> {
        let marker = self.staging.join(MARKER);
        // The marker lists the set, so that the next writer knows these files as ours.
        let mut names: Vec<String> = std::fs::read_dir(&self.staging)
            .map_err(io(&self.staging))?
            .filter_map(|e| e.ok())
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|n| n != MARKER)
            .collect();
        names.sort();
        let mut text = String::from("written by evhi\n");
        for n in &names {
            text.push_str(n);
            text.push('\n');
        }
        std::fs::write(&marker, text).map_err(io(&marker))?;
        // Flush every file and the directory before the swap makes them visible.
        for entry in std::fs::read_dir(&self.staging).map_err(io(&self.staging))? {
            let p = entry.map_err(io(&self.staging))?.path();
            File::open(&p).and_then(|f| f.sync_all()).map_err(io(&p))?;
        }
        if let Ok(d) = File::open(&self.staging) {
            let _ = d.sync_all();
        }
        if self.target.exists() {
            exchange(&self.staging, &self.target).map_err(io(&self.target))?;
            // The staging path now holds the previous set. A file the user put there
            // during the run (the check at the start saw none) is moved into the new
            // set, not deleted with the old one; the next run then refuses it by name.
            let listed = listed_files(&self.staging);
            let mut kept = vec![];
            for entry in std::fs::read_dir(&self.staging).map_err(io(&self.staging))? {
                let name = entry.map_err(io(&self.staging))?.file_name();
                let name = name.to_string_lossy().into_owned();
                if !is_run_file(&name) && !listed.contains(&name) {
                    let (from, to) = (self.staging.join(&name), self.target.join(&name));
                    std::fs::rename(&from, &to).map_err(io(&to))?;
                    kept.push(name);
                }
            }
            if !kept.is_empty() {
                crate::diag!(
                    "warning: {} appeared in `{}` during the run and was kept beside the new \
                     set; a later run into it will refuse until it is moved out",
                    kept.iter()
                        .map(|n| format!("`{n}`"))
                        .collect::<Vec<_>>()
                        .join(", "),
                    self.target.display()
                );
            }
            let _ = std::fs::remove_dir_all(&self.staging);
        } else {
            std::fs::rename(&self.staging, &self.target).map_err(io(&self.target))?;
        }
        Ok(())
    }
}

/// The files the marker of the run directory `target` lists (none for a marker of a
/// version that did not list them).
fn listed_files(target: &Path) -> Vec<String> {
    std::fs::read_to_string(target.join(MARKER))
        .map(|t| t.lines().skip(1).map(str::to_string).collect())
        .unwrap_or_default()
}

/// Who uses a run directory, as its messages name it and what they advise.
#[derive(Clone, Copy)]
struct User {
    /// The directory as the command names it.
    role: &'static str,
    /// What to do when another process holds the lock.
    remedy: &'static str,
}

/// A run writing its directory (`evhi solve`, `evhi study`: `--out`).
const WRITER: User = User {
    role: "--out",
    remedy: "wait for it or choose another directory",
};

/// `evhi plot` redrawing a run directory's figures.
const REDRAWER: User = User {
    role: "run directory",
    remedy: "wait for it to finish, then redraw",
};

/// Takes the lock `.NAME.lock` beside the run directory `target` (in `parent`, the
/// directory's name `name`), or fails at once if another process holds it.
fn lock_beside(
    target: &Path,
    parent: &Path,
    name: &str,
    user: User,
) -> Result<super::HeldLock, OutError> {
    let lock_path = parent.join(format!(".{name}.lock"));
    match super::try_lock_file(&lock_path) {
        Ok(Some(lock)) => Ok(lock),
        Ok(None) => Err(OutError::Busy {
            role: user.role,
            path: target.display().to_string(),
            lock: lock_path.display().to_string(),
            remedy: user.remedy,
        }),
        Err(e) => Err(OutError::Unusable {
            role: user.role,
            path: target.display().to_string(),
            message: format!(
                "cannot create a file beside it (`{}`): {e}",
                lock_path.display()
            ),
        }),
    }
}

/// The directory that holds `target` (`.` for a bare name) and `target`'s own name,
/// which must name a directory (not `.`, `..` or `/`).
/// The longest last component of a run directory's path, in bytes.
pub const MAX_NAME_BYTES: usize = 235;

fn parent_and_name(target: &Path, user: User) -> Result<(PathBuf, String), OutError> {
    let name = target
        .file_name()
        .filter(|n| !n.is_empty() && *n != "." && *n != "..")
        .ok_or_else(|| OutError::Unusable {
            role: user.role,
            path: target.display().to_string(),
            message: "name a directory (not `.`, `..` or `/`)".into(),
        })?
        .to_string_lossy()
        .into_owned();
    // The run writes beside its directory `.{name}.staging-{pid}` (and `.lock`):
    // 20 bytes more than the name, within the 255 bytes a file name may have.
    if name.len() > MAX_NAME_BYTES {
        return Err(OutError::Unusable {
            role: user.role,
            path: target.display().to_string(),
            message: format!(
                "its last component is {} bytes long; at most {MAX_NAME_BYTES} are allowed \
                 (the run stages its files beside it under a name 20 bytes longer, and a file \
                 name has at most 255)",
                name.len()
            ),
        });
    }
    let parent = match target.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    Ok((parent, name))
}

/// The run that `name` is the staging directory of (`.NAME.staging-PID` gives NAME).
fn staging_of(name: &str) -> Option<&str> {
    let (run, pid) = name.strip_prefix('.')?.rsplit_once(".staging-")?;
    (!run.is_empty() && !pid.is_empty() && pid.bytes().all(|b| b.is_ascii_digit())).then_some(run)
}

/// Takes the lock of an existing run directory for a reader that rewrites part of it
/// (`evhi plot`), so that it never mixes its figures with a `solve` writing there.
pub fn lock_run_dir(dir: &Path) -> Result<super::HeldLock, OutError> {
    let (parent, name) = parent_and_name(dir, REDRAWER)?;
    // A run's staging directory is under the lock of the run it becomes, which a
    // lock by its own name would not wait for.
    if let Some(run) = staging_of(&name) {
        return Err(OutError::Unusable {
            role: REDRAWER.role,
            path: dir.display().to_string(),
            message: format!(
                "a run directory, not the staging directory of a `solve` writing `{run}`; \
                 plot `{run}` once that solve has ended"
            ),
        });
    }
    lock_beside(dir, &parent, &name, REDRAWER)
}

impl Drop for RunDir {
    /// A run that fails before publishing leaves the target untouched and removes
    /// its staging directory (a published one is already gone).
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.staging);
        // `_lock` drops after this: its file is removed while still held.
    }
}

/// Removes what a killed run left beside `target`: staging directories whose
/// process is gone. Called with the lock held.
fn clean_leftovers(parent: &Path, name: &str, target: &Path) {
    let prefix = format!(".{name}.staging-");
    let Ok(entries) = std::fs::read_dir(parent) else {
        return;
    };
    for e in entries.filter_map(|e| e.ok()) {
        let file = e.file_name().to_string_lossy().into_owned();
        if file.starts_with(&prefix) && e.path() != target {
            let _ = std::fs::remove_dir_all(e.path());
        }
    }
}

/// Swaps two directories atomically.
#[cfg(target_os = "linux")]
fn exchange(a: &Path, b: &Path) -> std::io::Result<()> {
    use std::ffi::CString;
    use std::os::unix::ffi::OsStrExt;
    let ca = CString::new(a.as_os_str().as_bytes())?;
    let cb = CString::new(b.as_os_str().as_bytes())?;
    // SAFETY: both paths are valid NUL-terminated strings for the duration of the call.
    let rc = unsafe {
        libc::renameat2(
            libc::AT_FDCWD,
            ca.as_ptr(),
            libc::AT_FDCWD,
            cb.as_ptr(),
            libc::RENAME_EXCHANGE,
        )
    };
    if rc == 0 {
        Ok(())
    } else {
        let err = std::io::Error::last_os_error();
        // Filesystems without RENAME_EXCHANGE: fall back to two renames.
        if err.raw_os_error() == Some(libc::EINVAL) || err.raw_os_error() == Some(libc::ENOSYS) {
            swap_by_renames(a, b)
        } else {
            Err(err)
        }
    }
}

#[cfg(not(target_os = "linux"))]
fn exchange(a: &Path, b: &Path) -> std::io::Result<()> {
    swap_by_renames(a, b)
}

/// Two renames: the target is briefly absent (not atomic; the fallback only).
fn swap_by_renames(staging: &Path, target: &Path) -> std::io::Result<()> {
    let old = staging.with_extension("old");
    std::fs::rename(target, &old)?;
    std::fs::rename(staging, target)?;
    std::fs::rename(&old, staging)
}
