//! The output set of `evhi reproduce` and `evhi bench`: the data and figure directories
//! one process writes its tables and figures into. Both commands claim it before any
//! work ([`claim_outputs`]): a directory holding files evhi did not write is refused,
//! one writer at a time holds the set's lock, and the temporaries a killed writer left
//! are removed. It lives with the commands so that `bench` does not reach into the
//! book's experiments for it.

/// Takes the lock of an output set: `.reproduce.lock` in its data directory, a
/// [`evhi::output::HeldLock`] (removed when the run ends; the kernel releases it if
/// the process dies). A
/// second `reproduce` into the same directories fails at once instead of mixing its
/// tables and figures with the first one's.
/// The caller has made the directory (and refused a `--data` that is no directory).
fn lock_outputs(data: &std::path::Path) -> Result<evhi::output::HeldLock, String> {
    let path = data.join(LOCK_NAME);
    evhi::output::try_lock_file(&path)
        .map_err(|e| format!("cannot open the lock {}: {e}", path.display()))?
        .ok_or_else(|| {
            format!(
                "another `evhi reproduce` or `evhi bench` is writing {} (it holds {}); wait for it to finish",
                data.display(),
                path.display()
            )
        })
}

/// Removes the temporaries `.NAME.tmp-PID` (of [`evhi::output::write_atomic`] and the
/// figures) that a killed process left in `dir`: those whose process is gone.
fn remove_stale_temporaries(dir: &std::path::Path) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let Some(pid) = temporary_pid(&name) else {
            continue;
        };
        if !evhi::output::process_alive(pid) && entry.path().is_file() {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

/// Marks a directory that `evhi reproduce` writes its tables or figures into, so that
/// a later run may replace the files there.
pub const OUTPUTS_MARKER: &str = ".evhi-outputs";

const OUTPUTS_MARKER_TEXT: &str = "evhi reproduce writes its tables and figures into this \
directory under fixed names, replacing files of the same names; this file marks it as one \
that it may write into.\n";

/// Refuses an output directory that `reproduce` would write into over files it did not
/// write: one that exists and is not a directory, or holds files but not the mark
/// [`OUTPUTS_MARKER`] of an earlier run (`/`, a home directory, a mistyped path). The
/// committed `data/` and `figures/` carry the mark.
fn check_output_dir(flag: &str, dir: &std::path::Path) -> Result<(), evhi::error::InputError> {
    let refuse = |what: String| evhi::error::InputError::field(flag, dir.display(), what);
    if dir.exists() && !dir.is_dir() {
        return Err(refuse(
            "a directory (created if missing): this path exists and is not one".into(),
        ));
    }
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Ok(());
    };
    // Its own lock and the temporaries of a killed run are reproduce's, not the user's.
    let mut names: Vec<String> = entries
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n != LOCK_NAME && temporary_pid(n).is_none())
        .collect();
    if names.is_empty() || dir.join(OUTPUTS_MARKER).exists() {
        return Ok(());
    }
    names.sort();
    Err(refuse(format!(
        "a new or empty directory, or one an earlier `evhi reproduce` or `bench` wrote (it holds \
         `{OUTPUTS_MARKER}`): this one holds files evhi did not write (for example `{}`), \
         and its tables and figures would replace any of the same names",
        names[0]
    )))
}

/// Makes `ctx`'s data and figure directories the output set of this process: refuses
/// either if it holds files evhi did not write ([`check_output_dir`], before anything
/// is created), creates and marks both, takes the set's lock (held while the returned
/// value lives) and removes the temporaries a killed writer left. `reproduce` and
/// `bench` call it before any work.
pub fn claim_outputs(
    ctx: &evhi::study::Ctx,
) -> Result<evhi::output::HeldLock, Box<dyn std::error::Error>> {
    for (flag, dir) in [("--data", &ctx.data), ("--figures", &ctx.figures)] {
        check_output_dir(flag, dir)?;
    }
    for (flag, dir) in [("--data", &ctx.data), ("--figures", &ctx.figures)] {
        std::fs::create_dir_all(dir)
            .and_then(|()| {
                let marker = dir.join(OUTPUTS_MARKER);
                if marker.exists() {
                    Ok(())
                } else {
                    evhi::output::write_atomic(&marker, OUTPUTS_MARKER_TEXT.as_bytes())
                }
            })
            .map_err(|e| {
                evhi::error::InputError::field(
                    flag,
                    dir.display(),
                    format!("a directory that can be created and written: {e}"),
                )
            })?;
    }
    // One writer of an output set at a time; then the temporaries a killed run left.
    let lock = lock_outputs(&ctx.data)?;
    for dir in [&ctx.data, &ctx.figures] {
        remove_stale_temporaries(dir);
    }
    Ok(lock)
}

/// The lock of an output set, in its data directory.
const LOCK_NAME: &str = ".reproduce.lock";

/// The process id in the name of a temporary `.NAME.tmp-PID` (or `.STEM.tmp-PID.EXT`
/// for a figure) that a writer of an output set leaves while it writes.
fn temporary_pid(name: &str) -> Option<u32> {
    name.strip_prefix('.')
        .and_then(|n| n.rsplit_once(".tmp-"))
        .map(|(_, rest)| rest.split('.').next().unwrap_or(""))
        .and_then(|p| p.parse::<u32>().ok())
}

/// `estimator.csv` (centroid x, y and `eta` of each triangle of the run's mesh, and
/// its `complementarity` term where given) and `solution.vtu` again with the cell
/// field `eta`.
pub fn write_eta(
    out: &evhi::output::rundir::RunDir,
    scn: &evhi::scenario::Scenario,
    run: &evhi::scheme::Run,
    eta: &[f64],
    complementarity: Option<&[f64]>,
) -> Result<(), Box<dyn std::error::Error>> {
    let mesh = &run.mesh;
    let dofs = evhi::mesh::Dofs::new(mesh, true);
    let mut csv = String::from(match complementarity {
        Some(_) => "x,y,eta,complementarity\n",
        None => "x,y,eta\n",
    });
    for (i, (tri, e)) in mesh.triangles.iter().zip(eta).enumerate() {
        let p = tri.map(|v| mesh.nodes[v]);
        let x = [0, 1].map(|i| (p[0][i] + p[1][i] + p[2][i]) / 3.0);
        match complementarity {
            Some(c) => csv += &format!("{},{},{:e},{:e}\n", x[0], x[1], e, c[i]),
            None => csv += &format!("{},{},{:e}\n", x[0], x[1], e),
        }
    }
    out.write("estimator.csv", csv.as_bytes())?;
    let disp = mesh.displacement(&dofs, &run.u);
    let codes: Vec<i32> = (run.contact.iter())
        .map(|c| c.regime_code(scn.law(), scn.g()))
        .collect();
    let vtu = evhi::output::vtu::vtu_cells(mesh, &disp, &run.contact, &codes, &[("eta", eta)]);
    out.write("solution.vtu", vtu.as_bytes())?;
    Ok(())
}
