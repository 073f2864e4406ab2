//! The worked example of the chapter "Your own scenario": a user scenario
//! (`data/scenarios/examples/five_branch.toml`: a five-branch law with an upward jump,
//! loads ramped in) checked as `evhi show` checks it and run as `evhi solve` runs it,
//! with the same run directory and figures. The report goes to
//! `data/example_five_branch_show.txt`, the run's tables to
//! `data/example_five_branch_*.csv`, its figures to `figures/example_five_branch_*`.

use super::{Ctx, ExpError};
use crate::output::run::{Provenance, Recorder};
use crate::output::rundir::RunDir;
use crate::scenario::Scenario;
use crate::scheme::Settings;
use crate::step::newton::Newton;

/// The example's TOML, compiled in.
pub const TOML: &str = include_str!("../../data/scenarios/examples/five_branch.toml");

fn io(path: &std::path::Path) -> impl FnOnce(std::io::Error) -> ExpError + '_ {
    move |source| ExpError::Io {
        path: path.display().to_string(),
        source,
    }
}

pub fn run(ctx: &Ctx) -> Result<(), ExpError> {
    let scn = Scenario::from_toml(TOML, "data/scenarios/examples/five_branch.toml")?;
    let n = if ctx.quick { 16 } else { 64 };
    ctx.add_units(1);
    ctx.log(&format!("example: five_branch, h = k = 1/{n}"));
    let (report, _) = crate::show::report(&scn, n, n);
    ctx.write_file(
        &ctx.data_path("example_five_branch_show.txt"),
        format!(
            "# produced by evhi {} `evhi reproduce example{}` (the report of `evhi show`)\n{report}",
            env!("CARGO_PKG_VERSION"),
            if ctx.quick { " --quick" } else { "" }
        )
        .as_bytes(),
    )?;
    // The run, written exactly as `evhi solve` writes it, in a scratch directory.
    let scratch = std::env::temp_dir().join(format!("evhi-example-{}", std::process::id()));
    let out = RunDir::open(&scratch).map_err(|e| ExpError::Table {
        path: scratch.display().to_string(),
        message: e.to_string(),
    })?;
    let mut rec = Recorder::new(&scn, n, n, None)?;
    let res = crate::scheme::run_with_states(
        &scn,
        &Settings::new(n, n),
        &mut Newton::default(),
        &mut |step, t, u, c| rec.observe(&out, step, t, Some(u), c),
    )?;
    let prov = Provenance {
        command: format!(
            "reproduce example{}",
            if ctx.quick { " --quick" } else { "" }
        ),
        solver: crate::step::DEFAULT_SOLVER.into(),
        ordering: "nd".into(),
        path: "general".into(),
    };
    let h_s = crate::show::Smallness::of(&scn, n)
        .unwrap_or_else(|_| crate::show::Smallness::unknown(&scn, n));
    let err = |e: crate::output::rundir::OutError| ExpError::Table {
        path: scratch.display().to_string(),
        message: e.to_string(),
    };
    crate::output::run::write(&out, &scn, TOML, &res, rec, &prov, 0.0, &h_s).map_err(err)?;
    super::runplot::draw(&out.path(""))?;
    out.publish().map_err(err)?;
    // Tables into data/ (timing columns are not kept: they change from run to run).
    let copy = |from: std::path::PathBuf, to: std::path::PathBuf| -> Result<(), ExpError> {
        let bytes = std::fs::read(&from).map_err(io(&from))?;
        ctx.write_file(&to, &bytes)
    };
    for f in ["contact.csv", "regimes.csv"] {
        copy(
            scratch.join(f),
            ctx.data_path(&format!("example_five_branch_{f}")),
        )?;
    }
    for stem in ["deformed", "evolution"] {
        for ext in ["png", "svg"] {
            copy(
                scratch.join(format!("{stem}.{ext}")),
                ctx.figure_path(&format!("example_five_branch_{stem}"), ext),
            )?;
        }
    }
    let _ = std::fs::remove_dir_all(&scratch);
    Ok(())
}
