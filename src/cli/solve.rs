//! `evhi solve`: one scenario, written as a self-describing run directory.

pub use super::solve_args::{SolveArgs, settings, settings_flag};
use evhi::certificate::ContactState;
use evhi::diagnostics;
use evhi::output::run::{Provenance, Recorder, Recording};
use evhi::output::rundir::RunDir;
use evhi::scenario::Scenario;
use evhi::simulation::{Observer, Simulation};
use indicatif::{ProgressBar, ProgressStyle};
use std::time::{Duration, Instant};

/// Solves and writes the run directory.
pub fn run(args: SolveArgs) -> Result<(), Box<dyn std::error::Error>> {
    let wall = Instant::now();
    // Read once: the run writes this text, whatever happens to the file meanwhile.
    let (scn, toml) = Scenario::read(&args.scenario)?;
    let scn = scn
        .with_loads(args.f0, args.f2)
        .map_err(|e| e.for_flag("loads.f0", "--f0").for_flag("loads.f2", "--f2"))?;
    let scn = match args.g {
        Some(g) => scn.with_g(g).map_err(|e| e.for_flag("g", "--g"))?,
        None => scn,
    };
    let scn = match args.ramp {
        Some(t_r) => scn.with_ramp(t_r)?,
        None => scn,
    };
    if let Some(n) = args.n {
        scn.refuse_level_on_mesh(n)
            .map_err(|e| e.for_flag("n", "--n"))?;
    }
    if let Some(tol) = args.adapt {
        return super::adapt::run(&args, scn, &toml, tol, wall);
    }
    if let (Some(i), false) = (args.indicators, args.estimate) {
        return Err(evhi::error::InputError::field(
            "--indicators",
            format!("{i:?}").to_lowercase(),
            "only with --adapt or --estimate, which compute indicators",
        )
        .into());
    }
    let sim = Simulation::new(scn, settings(&args)).map_err(settings_flag)?;
    // The output directory is checked and locked before any work.
    let out = RunDir::open(&args.out)?;
    let (sim, chosen) = match args.adapt_time {
        Some(tol) => {
            let (sim, chosen) = super::adapt_time::choose(&args, sim, tol)?;
            (sim, Some(chosen))
        }
        None => (sim, None),
    };
    let (scn, entry) = (sim.scenario(), sim.solver());
    diagnostics::before(scn, entry)
        .iter()
        .for_each(|l| evhi::diag!("{l}"));
    let (mesh, steps) = (sim.mesh().clone(), sim.steps());
    if let Some(every) = args.vtk_every {
        check_vtk_volume(&args.out, mesh.nodes.len(), steps, every)?;
    }
    let mut cli = Progress {
        recording: Recording {
            recorder: Recorder::new(scn, mesh.clone(), steps, args.vtk_every)?,
            out: &out,
        },
        bar: None,
        started: Instant::now(),
        steps: steps as u64,
        estimate: args.estimate,
        last: vec![],
    };
    let (solution, h_s) = sim.solve_checking_smallness(&mut cli);
    let Progress {
        recording,
        bar,
        last,
        ..
    } = cli;
    if let Some(b) = &bar {
        b.finish_and_clear();
    }
    let solution = solution?;
    let (lines, h_s) = diagnostics::after(scn, entry, &solution, solution.run.n, h_s);
    lines.iter().for_each(|l| evhi::diag!("{l}"));
    let t_out = Instant::now();
    let prov = Provenance::of(&sim, &solution, evhi::output::run::command_line());
    let run = &solution.run;
    let seconds = wall.elapsed().as_secs_f64();
    evhi::output::run::write(
        &out,
        scn,
        &toml,
        run,
        recording.recorder,
        &prov,
        seconds,
        &h_s,
    )?;
    let t_est = if args.estimate {
        Some(write_estimate(
            &out,
            scn,
            run,
            &last,
            (sim.grid().k(sim.steps()), args.indicators),
        )?)
    } else {
        None
    };
    // The run's figures, drawn from the tables just written; a mesh that is no
    // lattice (its nodes.csv holds every node) has its nodes drawn from memory.
    let disp = if run.mesh.pattern.is_grid() {
        Vec::new()
    } else {
        (run.mesh).displacement(&evhi::mesh::Dofs::new(&run.mesh, true), &run.u)
    };
    evhi::output::runplot::draw_scene(
        &out.path(""),
        Some(evhi::output::runplot::Written {
            scene: scn,
            triangles: &run.mesh.triangles,
            nodes: &run.mesh.nodes,
            disp: &disp,
        }),
    )?;
    if let Some(chosen) = &chosen {
        super::adapt_time::write(&out, &prov, scn, run, chosen, "the run's mesh")?;
    }
    out.publish()?;
    if args.timings {
        if let Some(chosen) = &chosen {
            super::adapt_time::print_search(chosen, "the run below");
        }
        let (output, total) = (t_out.elapsed(), wall.elapsed());
        evhi::diag_text!(
            "{}",
            evhi::output::run::timings(&sim, run, output, total, t_est)
        );
    }
    evhi::diag!(
        "solved: {} steps, n = {}, largest certificate {:.1e}, {:.2} s wall; run directory {}",
        run.steps,
        run.n,
        solution.max_certificate(),
        wall.elapsed().as_secs_f64(),
        evhi::term::one_line(&args.out.display().to_string())
    );
    Ok(())
}

/// The command line's observer: the run's records and files, and a progress bar
/// once the run has taken a second.
struct Progress<'a> {
    recording: Recording<'a>,
    bar: Option<ProgressBar>,
    started: Instant,
    steps: u64,
    /// Whether `--estimate` asked for the last two fields.
    estimate: bool,
    /// The last two fields formed (free dofs), oldest first, with their steps.
    last: Vec<(usize, Vec<f64>)>,
}

/// The estimate of the run's last step (the residual indicators, or the equilibrated
/// ones if `indicators` says so): `estimator.csv` and `solution.vtu` again with the
/// cell field `eta`. $u^{N-1}$ is the field before the last (zero for a run of one
/// step). Returns the seconds the estimate took (not the writing).
fn write_estimate(
    out: &RunDir,
    scn: &Scenario,
    run: &evhi::scheme::Run,
    last: &[(usize, Vec<f64>)],
    (k, indicators): (f64, Option<super::solve_args::IndicatorArg>),
) -> Result<f64, Box<dyn std::error::Error>> {
    use evhi::estimator::estimate_scene;
    let mesh = &run.mesh;
    let dofs = evhi::mesh::Dofs::new(mesh, true);
    let u = dofs.expand(&run.u);
    let u_prev = match last.iter().find(|(n, _)| *n + 1 == run.steps) {
        Some((_, f)) => dofs.expand(f),
        None if run.steps == 1 => vec![[0.0; 2]; mesh.nodes.len()],
        None => return Err("the run did not keep the field before the last step".into()),
    };
    // The last step's time; `k` is its length on the run's grid.
    let t = run.records.last().map_or(scn.t_end(), |r| r.t);
    let clock = Instant::now();
    if indicators.map(|i| i.indicator()) == Some(evhi::adapt::Indicator::Equilibrated) {
        let mut eq = evhi::equilibrated::Equilibrator::new(mesh)?;
        let est = eq.estimate_scene(scn, &u, &u_prev, k, t, &run.contact);
        let eta: Vec<f64> = est.eta_sq.iter().map(|e| e.sqrt()).collect();
        let seconds = clock.elapsed().as_secs_f64();
        super::outputs::write_eta(out, scn, run, &eta, None)?;
        return Ok(seconds);
    }
    let est = estimate_scene(scn, mesh, &u, &u_prev, k, t, &run.contact);
    let seconds = clock.elapsed().as_secs_f64();
    super::outputs::write_eta(out, scn, run, &est.eta(), Some(&est.complementarity))?;
    Ok(seconds)
}

impl Observer for Progress<'_> {
    fn wants_field(&self, step: usize) -> bool {
        self.recording.wants_field(step) || (self.estimate && step as u64 + 1 >= self.steps)
    }

    fn step(&mut self, n: usize, t: f64, u: Option<&[f64]>, contact: &[ContactState]) {
        self.recording.step(n, t, u, contact);
        if let (true, Some(u)) = (self.estimate, u) {
            self.last.push((n, u.to_vec()));
            if self.last.len() > 2 {
                self.last.remove(0);
            }
        }
        if self.bar.is_none() && self.started.elapsed() > Duration::from_secs(1) {
            let b = ProgressBar::new(self.steps).with_style(
                ProgressStyle::with_template(
                    "{spinner} step {pos}/{len} [{bar:40}] {elapsed} (eta {eta})",
                )
                .expect("valid template")
                .progress_chars("=> "),
            );
            self.bar = Some(b);
        }
        if let Some(b) = &self.bar {
            b.set_position(n as u64);
        }
    }

    fn restart(&mut self) {
        self.recording.restart();
        self.last.clear();
    }
}

/// The largest VTK series `--vtk-every` may write, bytes.
pub const VTK_CAP_BYTES: f64 = 20e9;

/// Refuses a `--vtk-every` series that would not fit: about 120 bytes per mesh node
/// per file (0.95 MB at n = 128), one file every `every` steps and one at T, against
/// [`VTK_CAP_BYTES`] and the free space where the run is written.
fn check_vtk_volume(
    out: &std::path::Path,
    nodes: usize,
    steps: usize,
    every: u64,
) -> Result<(), evhi::error::InputError> {
    let nodes = nodes as f64;
    let files = (steps as u64).div_ceil(every) as f64 + 1.0;
    let bytes = 120.0 * nodes * files;
    let free = free_bytes(
        out.parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(std::path::Path::new(".")),
    );
    let limit = free.map_or(VTK_CAP_BYTES, |f| f.min(VTK_CAP_BYTES));
    if bytes > limit {
        return Err(evhi::error::InputError::field(
            "vtk-every",
            every,
            format!(
                "a series that fits: {files} files of about {} each, {} in all, but at most \
                 {} may be written ({}); write fewer snapshots",
                evhi::term::size_text(120.0 * nodes),
                evhi::term::size_text(bytes),
                evhi::term::size_text(limit),
                match free {
                    Some(f) if f < VTK_CAP_BYTES =>
                        format!("the free space there, {}", evhi::term::size_text(f)),
                    _ => format!("the cap of {}", evhi::term::size_text(VTK_CAP_BYTES)),
                }
            ),
        ));
    }
    Ok(())
}

/// Free bytes for an unprivileged writer on the file system of `dir` (`statvfs`).
fn free_bytes(dir: &std::path::Path) -> Option<f64> {
    #[cfg(target_os = "linux")]
    {
        use std::os::unix::ffi::OsStrExt;
        let path = std::ffi::CString::new(dir.as_os_str().as_bytes()).ok()?;
        // SAFETY: statvfs writes into the zeroed struct we own; the path is a valid C string.
        let mut st: libc::statvfs = unsafe { std::mem::zeroed() };
        if unsafe { libc::statvfs(path.as_ptr(), &mut st) } != 0 {
            return None;
        }
        Some(st.f_bavail as f64 * st.f_frsize as f64)
    }
    #[cfg(not(target_os = "linux"))]
    {
        let _ = dir;
        None
    }
}
