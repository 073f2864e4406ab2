//! The worked examples of the chapter "Your own scenario": user scenarios checked as
//! `evhi show` checks them and run as `evhi solve` runs them, with the same run
//! directory and figures. `five_branch` (`data/scenarios/examples/five_branch.toml`:
//! a five-branch law with an upward jump, loads ramped in) and `softening`
//! (`data/scenarios/examples/softening.toml`: the smooth law family). The report of
//! example NAME goes to `data/example_NAME_show.txt`, the run's tables to
//! `data/example_NAME_*.csv`, its figures to `figures/example_NAME_*`; the law of
//! `softening` is drawn as Fig. 2 draws the paper's (`figures/example_softening_law`).

use super::{Ctx, ExpError};
use evhi::certificate::ContactState;
use evhi::output::run::{Provenance, Recorder, Recording};
use evhi::output::rundir::RunDir;
use evhi::scenario::Scenario;
use evhi::simulation::{OnStep, RunSettings, Simulation};
use evhi::step::newton::Newton;

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
    move |source| {
        ExpError::File(evhi::output::FileError::Io {
            path: path.display().to_string(),
            source,
        })
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
                .is_ok_and(|p| !evhi::output::process_alive(p))
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

/// The studies of `evhi study` (every entry of the registry) on the worked example, in
/// quick mode, run as the command line would run them: their Markdown summaries into
/// `data/example_study_*.md`, their figures into `figures/example_study_*`.
fn studies(
    ctx: &Ctx,
    scratch: &Scratch,
    name: &str,
    toml: &str,
    path: &str,
) -> Result<(), ExpError> {
    use evhi::study::{STUDIES, Study, run_as};
    // The studies read the scenario from a file: the compiled-in text, so that the
    // example runs from any working directory (the repository's path named in
    // `path` is what the summaries quote).
    let file = scratch.0.join(format!("{name}.toml"));
    std::fs::write(&file, toml).map_err(io(&file))?;
    let scenario = file.display().to_string();
    let scratch = scratch.0.join("studies");
    ctx.add_units(STUDIES.len());
    // Every study of the registry, as `evhi study NAME --scenario FILE --quick --out DIR`
    // reads it.
    for entry in &STUDIES {
        let (study, stems) = (entry.name, entry.figures);
        let out = scratch.join(study).display().to_string();
        let words = [study, "--scenario", &scenario, "--quick", "--out", &out];
        let args = Study::parse(&words).map_err(|e| {
            ExpError::File(evhi::output::FileError::Table {
                path: format!("evhi study {study}"),
                message: e.to_string(),
            })
        })?;
        let command = format!("study {study} --scenario {path} --quick --out DIR");
        let md = run_as(args, &command).map_err(|e| {
            ExpError::File(evhi::output::FileError::Table {
                path: format!("example_study_{study}.md (`evhi {command}`)"),
                message: e.to_string(),
            })
        })?;
        ctx.write_file(
            &ctx.data_path(&format!("example_study_{study}.md")),
            md.as_bytes(),
        )?;
        for (ext, (stem, suffix)) in stems.iter().flat_map(|s| ["png", "svg"].map(|e| (e, *s))) {
            let from = scratch.join(study).join(format!("{stem}.{ext}"));
            let bytes = std::fs::read(&from).map_err(|e| {
                ExpError::File(evhi::output::FileError::Io {
                    path: from.display().to_string(),
                    source: e,
                })
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
    let (report, _) = evhi::show::report(&scn, n, n);
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
    let out = RunDir::open(&scratch).map_err(|e| {
        ExpError::File(evhi::output::FileError::Table {
            path: scratch.display().to_string(),
            message: e.to_string(),
        })
    })?;
    // As `evhi solve --n N --steps N --path general` solves it: the library's one
    // way to run a scene, so no wiring here to keep in step with the command.
    let settings = RunSettings::general(n, n);
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
    let h_s = evhi::show::Smallness::of(&scn, n)
        .unwrap_or_else(|_| evhi::show::Smallness::unknown(&scn, n));
    let err = |e: evhi::output::rundir::OutError| {
        ExpError::File(evhi::output::FileError::Table {
            path: scratch.display().to_string(),
            message: e.to_string(),
        })
    };
    evhi::output::run::write(&out, &scn, toml, res, rec, &prov, 0.0, &h_s).map_err(err)?;
    evhi::output::runplot::draw(&out.path(""))?;
    out.publish().map_err(err)?;
    // Newton's work per step, without the timing columns of steps.csv.
    let t = evhi::output::run::step_work(&res.records);
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
    // The figures the book shows: softening's deformed body is not among them (its
    // law and evolution are).
    let stems: &[&str] = if name == "softening" {
        &["evolution"]
    } else {
        &["deformed", "evolution"]
    };
    for stem in stems {
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
    /// When each contact node first sits at the limit (NaN: never).
    landings: Vec<f64>,
    /// The middle node's normal velocity over the last step before it lands,
    /// $(u_{\nu,m} - u_{\nu,m-1})/k$, and which nodes sat at the limit then.
    v_before: f64,
    at_limit_before: Vec<bool>,
    /// $-\sigma_\nu$ at the middle node at the last step before it lands.
    sigma_before: f64,
    /// $-\sigma_\nu$ at the middle node after every step.
    mid_sigma: Vec<f64>,
}

impl Trace {
    /// When the first of the middle node's two neighbours lands.
    fn first_neighbour(&self, mid: usize) -> f64 {
        let at = |i: usize| self.landings.get(i).copied().unwrap_or(f64::NAN);
        at(mid - 1).min(at(mid + 1))
    }

    /// $-\sigma_\nu$ at the middle node at time `t` (a step time of the run).
    fn mid_sigma_at(&self, t: f64) -> f64 {
        let step = (t * self.steps as f64).round() as usize;
        step.checked_sub(1)
            .and_then(|i| self.mid_sigma.get(i))
            .copied()
            .unwrap_or(f64::NAN)
    }
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
        landings: vec![],
        v_before: f64::NAN,
        at_limit_before: vec![],
        sigma_before: f64::NAN,
        mid_sigma: Vec::with_capacity(steps),
    };
    let mid = n / 2;
    let k = scn.t_end() / steps as f64;
    let mut last: Option<(f64, Vec<bool>)> = None;
    let sim = crate::experiments::runs::simulation(scn, n, steps)?;
    let mut observer = OnStep::new(|_, t, _: Option<&[f64]>, c: &[ContactState]| {
        let codes: Vec<i32> = c
            .iter()
            .map(|s| s.regime_code(scn.law(), scn.g()))
            .collect();
        if let Some(p) = &prev {
            let back = codes.iter().zip(p).filter(|(a, b)| a < b).count();
            if back > 0 {
                tr.reversals += back;
                tr.t_last_reversal = t;
            }
        }
        let s = -(c[mid].sigma_nu1 + c[mid].sigma_nu2);
        tr.mid_sigma.push(s);
        if s > tr.peak {
            (tr.peak, tr.t_peak) = (s, t);
        }
        if tr.t_landing.is_nan() && c[mid].at_limit {
            tr.t_landing = t;
            // The state of the step before: its limit set; v_before is the
            // velocity of the step that ended there.
            if let Some((_, limit)) = last.take() {
                tr.at_limit_before = limit;
            }
        }
        if tr.landings.is_empty() {
            tr.landings = vec![f64::NAN; c.len()];
        }
        for (l, s) in tr.landings.iter_mut().zip(c) {
            if l.is_nan() && s.at_limit {
                *l = t;
            }
        }
        if tr.t_landing.is_nan() {
            if let Some((u_prev, _)) = &last {
                tr.v_before = (c[mid].u_nu - u_prev) / k;
            }
            last = Some((c[mid].u_nu, c.iter().map(|s| s.at_limit).collect()));
            tr.sigma_before = s;
        }
        tr.at_t = s;
        prev = Some(codes);
    });
    sim.solve_with(&mut Newton::default(), &mut observer)?;
    Ok(tr)
}

/// The jump of the middle node's reaction when it lands, from the space-discrete,
/// time-continuous problem on the contact nodes. With proportional damping ($A = \tau B$)
/// it reads $\tau S\dot r + S r + W(p(r) + \lambda) = F(t)$, $S$ the condensed stiffness,
/// $W$ the nodal weights. At the landing $r$, $p(r)$ and $F$ are continuous; the middle
/// node's velocity drops from $v$ to 0, the nodes already at the limit stay at rest,
/// and on the free set $\mathcal F$ the equations without reaction keep
/// $(S\,\Delta\dot r)_{\mathcal F} = 0$. So
/// $$w_m\,\Delta\lambda_m = \tau v\,\big(S_{mm} - S_{m\mathcal F}S_{\mathcal F\mathcal F}^{-1}S_{\mathcal F m}\big),$$
/// the middle node's stiffness with the free nodes condensed out and the limit nodes
/// held: a finite jump, which the scheme can resolve only with steps shorter than the
/// time in which the next nodes land.
// ANCHOR: landing_jump
fn landing_jump(red: &evhi::reduced::Reduced, v: f64, at_limit: &[bool]) -> Result<f64, ExpError> {
    let mid = red.disc.mesh.n / 2;
    let s = &red.s_b;
    let free: Vec<usize> = (0..s.nrows())
        .filter(|&i| i != mid && !at_limit.get(i).copied().unwrap_or(false))
        .collect();
    let sff = nalgebra::DMatrix::from_fn(free.len(), free.len(), |a, b| s[(free[a], free[b])]);
    let sfm = nalgebra::DVector::from_fn(free.len(), |a, _| s[(free[a], mid)]);
    let x = sff
        .cholesky()
        .ok_or_else(|| {
            evhi::scheme::RunError::Condense("the free block of S is not positive definite".into())
        })?
        .solve(&sfm);
    let s_eff = s[(mid, mid)] - sfm.dot(&x);
    let w = red.disc.mesh.contact_weights()[mid];
    Ok(red.c * v * s_eff / w)
}
// ANCHOR_END: landing_jump

/// The example at the same mesh with 1, 4, 16, 64 and 256 times the steps: does the
/// regime chatter and the force peak at the landing follow the time step (a numerical
/// artefact) or stay (the solution's own)? And the landing's own scale: when the
/// neighbours of the middle node land, and the reaction jump [`landing_jump`]
/// predicts. `data/example_five_branch_steps.csv`.
fn step_control(ctx: &Ctx, scn: &Scenario, n: usize) -> Result<(), ExpError> {
    let rows: Vec<Trace> = [1, 4, 16, 64, 256]
        .iter()
        .map(|m| trace(scn, n, m * n))
        .collect::<Result<_, _>>()?;
    let mid = n / 2;
    // The condensed operator of the mesh, once for every row.
    let settings = RunSettings::general(n, n).with_threads(1);
    let sim = Simulation::new(scn.clone(), settings)?;
    let disc = sim.discretisation();
    let red = sim.reduced_operator(&disc, &mut evhi::scheme::Timings::default())?;
    let jumps: Vec<f64> = rows
        .iter()
        .map(|r| landing_jump(&red, r.v_before, &r.at_limit_before))
        .collect::<Result<_, _>>()?;
    let side = |r: &Trace, i: usize| r.landings.get(i).copied().unwrap_or(f64::NAN);
    let after = |r: &Trace| r.mid_sigma_at(r.t_landing + 1.0 / r.steps as f64);
    let t = evhi::output::csv::Table::new()
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
        .f64("sigma_T_mid", rows.iter().map(|r| r.at_t).collect())
        .f64(
            "t_landing_left",
            rows.iter().map(|r| side(r, mid - 1)).collect(),
        )
        .f64(
            "t_landing_right",
            rows.iter().map(|r| side(r, mid + 1)).collect(),
        )
        .f64(
            "landing_interval",
            rows.iter()
                .map(|r| r.first_neighbour(mid) - r.t_landing)
                .collect(),
        )
        .u64(
            "at_limit_before",
            rows.iter()
                .map(|r| r.at_limit_before.iter().filter(|&&b| b).count() as u64)
                .collect(),
        )
        .f64("v_before_mid", rows.iter().map(|r| r.v_before).collect())
        .f64(
            "sigma_before_mid",
            rows.iter().map(|r| r.sigma_before).collect(),
        )
        .f64(
            "sigma_landing_step_mid",
            rows.iter().map(|r| r.mid_sigma_at(r.t_landing)).collect(),
        )
        .f64("sigma_after_mid", rows.iter().map(after).collect())
        .f64(
            "sigma_first_neighbour_mid",
            rows.iter()
                .map(|r| r.mid_sigma_at(r.first_neighbour(mid)))
                .collect(),
        )
        .f64("sigma_jump_predicted", jumps.clone())
        .f64(
            "sigma_after_predicted",
            rows.iter()
                .zip(&jumps)
                .map(|(r, j)| r.sigma_before + j)
                .collect(),
        );
    ctx.write(
        "example_five_branch_steps.csv",
        &t,
        &format!(
            "scenario five_branch, h = 1/{n}, steps N = {n}, {}, {}, {}, {}; reversals = node-steps at which a contact node's regime code fell (a lower branch, or off the limit), summed over the run; mid = the node x = 1; sigma = -(sigma_nu1 + sigma_nu2); t_last_reversal: the last step time with a reversal (NaN: none); sigma is a traction (per unit length of Gamma_3; the nodal force is w_m sigma, w_m = 2/n); t_landing_left, t_landing_right: when the nodes x = 1 - 2/n and 1 + 2/n first sit at the limit, landing_interval the delay of the first of them after mid; at_limit_before: nodes at the limit at the step before mid lands; v_before_mid: mid's normal velocity over the step before that; sigma_landing_step_mid, sigma_after_mid, sigma_first_neighbour_mid: sigma at mid at the step it lands, the step after, and the step its first neighbour lands; sigma_jump_predicted = tau v (S_mm - S_mF S_FF^-1 S_Fm) / w_m, the reaction jump of the time-continuous problem on this mesh when mid stops (S the condensed stiffness, F the free nodes); sigma_after_predicted = sigma_before_mid + that jump, the value just after the stop",
            4 * n,
            16 * n,
            64 * n,
            256 * n
        ),
    )?;
    Ok(())
}
