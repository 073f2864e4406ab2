//! The worked examples of the chapter "Your own scenario": user scenarios checked as
//! `evhi show` checks them and run as `evhi solve` runs them, with the same run
//! directory and figures. `five_branch` (`data/scenarios/examples/five_branch.toml`:
//! a five-branch law with an upward jump, loads ramped in) and `softening`
//! (`data/scenarios/examples/softening.toml`: the smooth law family). The report of
//! example NAME goes to `data/example_NAME_show.txt`, the run's tables to
//! `data/example_NAME_*.csv`, its figures to `figures/example_NAME_*`; the law of
//! `softening` is drawn as Fig. 2 draws the paper's (`figures/example_softening_law`).

use super::{Ctx, ExpError};
use crate::output::run::{Provenance, Recorder, Recording};
use crate::output::rundir::RunDir;
use crate::scenario::Scenario;
use crate::scheme::Settings;
use crate::simulation::{Loop, RunSettings, Simulation};
use crate::step::newton::Newton;

/// The examples: name, TOML (compiled in), its path.
pub const EXAMPLES: [(&str, &str, &str); 2] = [
    (
        "five_branch",
        include_str!("../../data/scenarios/examples/five_branch.toml"),
        "data/scenarios/examples/five_branch.toml",
    ),
    (
        "softening",
        include_str!("../../data/scenarios/examples/softening.toml"),
        "data/scenarios/examples/softening.toml",
    ),
];

fn io(path: &std::path::Path) -> impl FnOnce(std::io::Error) -> ExpError + '_ {
    move |source| ExpError::Io {
        path: path.display().to_string(),
        source,
    }
}

pub fn run(ctx: &Ctx) -> Result<(), ExpError> {
    let n = if ctx.quick { 16 } else { 64 };
    ctx.add_units(EXAMPLES.len());
    let scratch = Scratch::new()?;
    for (name, toml, path) in EXAMPLES {
        let scn = Scenario::from_toml(toml, path)?;
        one(ctx, &scratch, name, toml, &scn, n)?;
        if name == "five_branch" {
            step_control(ctx, &scn, n)?;
            studies(ctx, &scratch, name, toml, path)?;
        } else {
            super::fig2::draw_law(ctx, &scn, &format!("example_{name}_law"))?;
        }
    }
    Ok(())
}

/// This process's scratch directory under the system's temporary directory, for the
/// run directories and studies the example writes as the command line would: removed
/// when dropped, with the locks those leave beside them. A process killed first
/// leaves it; the next run removes those of processes that are gone.
struct Scratch(std::path::PathBuf);

impl Scratch {
    const PREFIX: &'static str = "evhi-example-";

    fn new() -> Result<Scratch, ExpError> {
        let tmp = std::env::temp_dir();
        Scratch::clean(&tmp);
        let dir = tmp.join(format!("{}{}", Scratch::PREFIX, std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).map_err(io(&dir))?;
        Ok(Scratch(dir))
    }

    /// Removes the scratch directories of processes that are gone, and what earlier
    /// versions left: `evhi-example-studies-PID/` and the locks
    /// `.evhi-example-NAME-PID.lock` beside their run directories.
    fn clean(tmp: &std::path::Path) {
        let Ok(entries) = std::fs::read_dir(tmp) else {
            return;
        };
        for e in entries.flatten() {
            let file = e.file_name().to_string_lossy().into_owned();
            let Some(rest) = file
                .strip_prefix('.')
                .unwrap_or(&file)
                .strip_prefix(Scratch::PREFIX)
            else {
                continue;
            };
            let rest = rest.strip_suffix(".lock").unwrap_or(rest);
            let pid = rest.rsplit('-').next().unwrap_or(rest);
            if pid
                .parse::<u32>()
                .is_ok_and(|p| !crate::output::process_alive(p))
            {
                let _ = std::fs::remove_dir_all(e.path());
                let _ = std::fs::remove_file(e.path());
            }
        }
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// The three studies of `evhi study` on the worked example, in quick mode, run as the
/// command line would run them: their Markdown summaries into
/// `data/example_study_*.md`, their figures into `figures/example_study_*`.
/// A figure's stem in a study's directory and the suffix it gets here.
type Stem = (&'static str, &'static str);

fn studies(
    ctx: &Ctx,
    scratch: &Scratch,
    name: &str,
    toml: &str,
    path: &str,
) -> Result<(), ExpError> {
    use super::study::{ConvergenceArgs, StabilityArgs, Study, TimeArgs, run_as};
    // The studies read the scenario from a file: the compiled-in text, so that the
    // example runs from any working directory (the repository's path named in
    // `path` is what the summaries quote).
    let file = scratch.0.join(format!("{name}.toml"));
    std::fs::write(&file, toml).map_err(io(&file))?;
    let scenario = file.display().to_string();
    let scratch = scratch.0.join("studies");
    ctx.add_units(3);
    let [convergence, time, stability] = super::registry::STUDIES;
    // Each study's figures (stems in its directory) and the names they get here.
    let runs: [(&str, &[Stem], Study); 3] = [
        (
            convergence,
            &[("convergence", ""), ("split", "_split")],
            Study::Convergence(ConvergenceArgs {
                scenario: scenario.clone(),
                quick: true,
                out: scratch.join(convergence),
            }),
        ),
        (
            time,
            &[("time_study", "")],
            Study::Time(TimeArgs {
                scenario: scenario.clone(),
                quick: true,
                n: None,
                out: scratch.join(time),
            }),
        ),
        (
            stability,
            &[(stability, "")],
            Study::Stability(StabilityArgs {
                scenario: scenario.clone(),
                quick: true,
                out: scratch.join(stability),
            }),
        ),
    ];
    for (study, stems, args) in runs {
        let command = format!("study {study} --scenario {path} --quick --out DIR");
        let md = run_as(args, &command).map_err(|e| ExpError::Table {
            path: format!("example_study_{study}.md (`evhi {command}`)"),
            message: e.to_string(),
        })?;
        ctx.write_file(
            &ctx.data_path(&format!("example_study_{study}.md")),
            md.as_bytes(),
        )?;
        for (ext, (stem, suffix)) in stems.iter().flat_map(|s| ["png", "svg"].map(|e| (e, *s))) {
            let from = scratch.join(study).join(format!("{stem}.{ext}"));
            let bytes = std::fs::read(&from).map_err(|e| ExpError::Io {
                path: from.display().to_string(),
                source: e,
            })?;
            ctx.write_file(
                &ctx.figure_path(&format!("example_study_{study}{suffix}"), ext),
                &bytes,
            )?;
        }
        ctx.log(&format!("example: study {study}"));
    }
    Ok(())
}

/// Example `name`: its `show` report, its run directory's tables and figures.
fn one(
    ctx: &Ctx,
    scratch: &Scratch,
    name: &str,
    toml: &str,
    scn: &Scenario,
    n: usize,
) -> Result<(), ExpError> {
    let scn = scn.clone();
    ctx.log(&format!("example: {name}, h = k = 1/{n}"));
    let (report, _) = crate::show::report(&scn, n, n);
    ctx.write_file(
        &ctx.data_path(&format!("example_{name}_show.txt")),
        format!(
            "# produced by evhi {} `evhi reproduce example{}` (the report of `evhi show`)\n{report}",
            env!("CARGO_PKG_VERSION"),
            if ctx.quick { " --quick" } else { "" }
        )
        .as_bytes(),
    )?;
    // The run, written exactly as `evhi solve` writes it, in a scratch directory.
    let scratch = scratch.0.join(name);
    let out = RunDir::open(&scratch).map_err(|e| ExpError::Table {
        path: scratch.display().to_string(),
        message: e.to_string(),
    })?;
    // As `evhi solve --n N --steps N --path general` solves it: the library's one
    // way to run a scene, so no wiring here to keep in step with the command.
    let settings = RunSettings {
        n,
        steps: Some(n),
        path: Loop::General,
        ..RunSettings::default()
    };
    let sim = Simulation::new(scn.clone(), settings)?;
    let mut rec = Recording {
        recorder: Recorder::new(&scn, sim.mesh().clone(), n, None)?,
        out: &out,
    };
    let solution = sim.solve(&mut rec)?;
    let (res, rec) = (&solution.run, rec.recorder);
    let prov = Provenance::of(
        &sim,
        &solution,
        format!(
            "reproduce example{}",
            if ctx.quick { " --quick" } else { "" }
        ),
    );
    let h_s = crate::show::Smallness::of(&scn, n)
        .unwrap_or_else(|_| crate::show::Smallness::unknown(&scn, n));
    let err = |e: crate::output::rundir::OutError| ExpError::Table {
        path: scratch.display().to_string(),
        message: e.to_string(),
    };
    crate::output::run::write(&out, &scn, toml, res, rec, &prov, 0.0, &h_s).map_err(err)?;
    super::runplot::draw(&out.path(""))?;
    out.publish().map_err(err)?;
    // Newton's work per step, without the timing columns of steps.csv.
    let t = crate::output::run::step_work(&res.records);
    ctx.write(
        &format!("example_{name}_iterations.csv"),
        &t,
        &format!("scenario {name}, h = k = 1/{n}, solver newton; the iterations of each step and its certificate (steps.csv without its timings)"),
    )?;
    // Tables into data/ (timing columns are not kept: they change from run to run).
    let copy = |from: std::path::PathBuf, to: std::path::PathBuf| -> Result<(), ExpError> {
        let bytes = std::fs::read(&from).map_err(io(&from))?;
        ctx.write_file(&to, &bytes)
    };
    for f in ["contact.csv", "regimes.csv"] {
        copy(
            scratch.join(f),
            ctx.data_path(&format!("example_{name}_{f}")),
        )?;
    }
    for stem in ["deformed", "evolution"] {
        for ext in ["png", "svg"] {
            copy(
                scratch.join(format!("{stem}.{ext}")),
                ctx.figure_path(&format!("example_{name}_{stem}"), ext),
            )?;
        }
    }
    Ok(())
}

/// What one run of the example shows on $\Gamma_3$ over time.
struct Trace {
    steps: usize,
    /// Steps at which a node moved back to a lower regime (branch, or off the limit).
    reversals: usize,
    t_last_reversal: f64,
    /// $-\sigma_\nu$ at the middle node $x = 1$: its peak, when, and at $T$.
    peak: f64,
    t_peak: f64,
    at_t: f64,
    /// When the middle node first sits at the limit.
    t_landing: f64,
}

fn trace(scn: &Scenario, n: usize, steps: usize) -> Result<Trace, ExpError> {
    let mut prev: Option<Vec<i32>> = None;
    let mut tr = Trace {
        steps,
        reversals: 0,
        t_last_reversal: f64::NAN,
        peak: 0.0,
        t_peak: f64::NAN,
        at_t: f64::NAN,
        t_landing: f64::NAN,
    };
    let mid = n / 2;
    crate::scheme::run_with_states(
        scn,
        &Settings::new(n, steps),
        &mut Newton::default(),
        &mut |_, t, _, c| {
            let codes: Vec<i32> = c.iter().map(|s| s.regime_code(&scn.law, scn.g)).collect();
            if let Some(p) = &prev {
                let back = codes.iter().zip(p).filter(|(a, b)| a < b).count();
                if back > 0 {
                    tr.reversals += back;
                    tr.t_last_reversal = t;
                }
            }
            let s = -(c[mid].sigma_nu1 + c[mid].sigma_nu2);
            if s > tr.peak {
                (tr.peak, tr.t_peak) = (s, t);
            }
            if tr.t_landing.is_nan() && c[mid].at_limit {
                tr.t_landing = t;
            }
            tr.at_t = s;
            prev = Some(codes);
        },
    )?;
    Ok(tr)
}

/// The example at the same mesh with 1, 4, 16 and 64 times the steps: does the regime
/// chatter and the force peak at the landing follow the time step (a numerical
/// artefact) or stay (the solution's own)? `data/example_five_branch_steps.csv`.
fn step_control(ctx: &Ctx, scn: &Scenario, n: usize) -> Result<(), ExpError> {
    let rows: Vec<Trace> = [1, 4, 16, 64]
        .iter()
        .map(|m| trace(scn, n, m * n))
        .collect::<Result<_, _>>()?;
    let t = crate::output::csv::Table::new()
        .u64("steps", rows.iter().map(|r| r.steps as u64).collect())
        .f64("k", rows.iter().map(|r| 1.0 / r.steps as f64).collect())
        .u64(
            "reversals",
            rows.iter().map(|r| r.reversals as u64).collect(),
        )
        .f64(
            "t_last_reversal",
            rows.iter().map(|r| r.t_last_reversal).collect(),
        )
        .f64("t_landing_mid", rows.iter().map(|r| r.t_landing).collect())
        .f64("sigma_peak_mid", rows.iter().map(|r| r.peak).collect())
        .f64("t_sigma_peak_mid", rows.iter().map(|r| r.t_peak).collect())
        .f64("sigma_T_mid", rows.iter().map(|r| r.at_t).collect());
    ctx.write(
        "example_five_branch_steps.csv",
        &t,
        &format!(
            "scenario five_branch, h = 1/{n}, steps N = {n}, {}, {}, {}; reversals = node-steps at which a contact node's regime code fell (a lower branch, or off the limit), summed over the run; mid = the node x = 1; sigma = -(sigma_nu1 + sigma_nu2); t_last_reversal: the last step time with a reversal (NaN: none)",
            4 * n,
            16 * n,
            64 * n
        ),
    )?;
    Ok(())
}
