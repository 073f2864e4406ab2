//! The memory guard: a run's estimated peak against what this process can still
//! obtain, checked before any work so that a mesh too large is refused by name
//! instead of aborting in an allocation.

use crate::error::InputError;

/// Estimated peak memory of a run with $n$ contact segments on the paper's rectangle,
/// bytes (see [`memory_estimate_rows`]).
pub fn memory_estimate(n: usize) -> f64 {
    memory_estimate_rows(n, n / 2)
}

/// Estimated peak memory of a run on the grid of $n$ columns and $n_y$ rows of cells,
/// bytes. Nested dissection of the $n \times n/2$ grid fills the factor to about $6\,N\log_2 N$ entries for $N$ dofs
/// (28.5 M at $n = 512$), and a run peaks at about 20 bytes per entry of the factor
/// (529 MB at $n = 512$, `data/bench.csv`), plus 30 MB.
pub fn memory_estimate_rows(n: usize, ny: usize) -> f64 {
    dofs_memory(grid_dofs(n, ny))
}

/// The unknowns of the grid of $n \times n_y$ cells, in floating point: the integer
/// product wraps for an absurd $n$ (and a wrapped count once passed the guard).
fn grid_dofs(n: usize, ny: usize) -> f64 {
    2.0 * (n as f64 + 1.0) * (ny as f64 + 1.0)
}

/// The rule of [`memory_for_dofs`] on a count in floating point.
fn dofs_memory(dofs: f64) -> f64 {
    30e6 + 20.0 * 6.0 * dofs * dofs.log2()
}

/// Estimated peak memory of a run with `dofs` unknowns, bytes (the grid's rule of
/// [`memory_estimate_rows`] applied to any mesh).
pub fn memory_for_dofs(dofs: usize) -> f64 {
    dofs_memory(dofs as f64)
}

/// The most unknowns a run can have within the memory available now (the rule of
/// [`memory_for_dofs`], with the guard's margin of [`check_memory_dofs`]); `None`
/// where the available memory is unknown.
pub fn max_dofs() -> Option<usize> {
    let have = 0.9 * available_memory()?;
    if memory_for_dofs(2) > have {
        return Some(0);
    }
    // memory_for_dofs grows with dofs: bisect for the last count that fits.
    let (mut lo, mut hi) = (2usize, 2usize);
    while memory_for_dofs(hi) <= have && hi < usize::MAX / 4 {
        lo = hi;
        hi *= 2;
    }
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if memory_for_dofs(mid) <= have {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(lo)
}

/// A size in bytes as the guards' messages write it: MB below 0.1 GB (a small limit
/// would read 0.0 GB), exponent form for absurd needs.
pub fn size(bytes: f64) -> String {
    if bytes < 1e8 {
        format!("{:.0} MB", bytes / 1e6)
    } else if bytes < 1e15 {
        format!("{:.1} GB", bytes / 1e9)
    } else {
        format!("{:.1e} GB", bytes / 1e9)
    }
}

/// Refuses a mesh of `dofs` unknowns (a graded one) whose run would not fit.
pub fn check_memory_dofs(dofs: usize) -> Result<(), InputError> {
    let need = memory_for_dofs(dofs);
    match available_memory() {
        Some(have) if need > 0.9 * have => Err(InputError::field(
            "n",
            format!("a mesh of {dofs} unknowns"),
            format!(
                "a mesh that fits in memory: it needs about {}, but {} are available",
                size(need),
                size(have)
            ),
        )),
        _ => Ok(()),
    }
}

/// Memory this process can still obtain, bytes: the least of the machine's
/// `MemAvailable`, what the address-space limit (`ulimit -v`, `RLIMIT_AS`) leaves
/// above the process's current size, and what its cgroup's `memory.max` leaves above
/// the group's usage. `None` where none of them can be read.
pub fn available_memory() -> Option<f64> {
    let kb_field = |text: &str, key: &str| -> Option<f64> {
        let line = text.lines().find(|l| l.starts_with(key))?;
        Some(line.split_whitespace().nth(1)?.parse::<f64>().ok()? * 1024.0)
    };
    let mut limits = vec![];
    if let Ok(info) = std::fs::read_to_string("/proc/meminfo") {
        limits.extend(kb_field(&info, "MemAvailable:"));
    }
    #[cfg(target_os = "linux")]
    {
        let mut lim = libc::rlimit {
            rlim_cur: 0,
            rlim_max: 0,
        };
        // SAFETY: getrlimit writes into the struct we own; no other effect.
        let ok = unsafe { libc::getrlimit(libc::RLIMIT_AS, &mut lim) } == 0;
        if ok && lim.rlim_cur != libc::RLIM_INFINITY {
            let size = std::fs::read_to_string("/proc/self/status")
                .ok()
                .and_then(|s| kb_field(&s, "VmSize:"))
                .unwrap_or(0.0);
            limits.push((lim.rlim_cur as f64 - size).max(0.0));
        }
    }
    let read = |p: &str| {
        std::fs::read_to_string(p)
            .ok()
            .map(|s| s.trim().to_string())
    };
    if let (Some(max), Some(current)) = (
        read("/sys/fs/cgroup/memory.max").and_then(|s| s.parse::<f64>().ok()),
        read("/sys/fs/cgroup/memory.current").and_then(|s| s.parse::<f64>().ok()),
    ) {
        limits.push((max - current).max(0.0));
    }
    limits.into_iter().reduce(f64::min)
}

/// Refuses a mesh of $n$ columns and $n_y$ rows whose run would not fit in the
/// available memory, before any work.
pub fn check_memory(n: usize, ny: usize) -> Result<(), InputError> {
    let need = memory_estimate_rows(n, ny);
    match available_memory() {
        Some(have) if need > 0.9 * have => Err(InputError::field(
            "n",
            n,
            format!(
                "a mesh that fits in memory: n = {n} needs about {} (factor of about {:.2e} \
                 entries), but {} are available",
                size(need),
                6.0 * grid_dofs(n, ny) * grid_dofs(n, ny).log2(),
                size(have)
            ),
        )),
        _ => Ok(()),
    }
}
