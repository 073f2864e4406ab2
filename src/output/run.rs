//! A run directory's content, as `evhi solve` writes it: the tables of the run at
//! $t = T$ (`contact.csv`, `nodes.csv`, `solution.vtu`), per step (`steps.csv`,
//! `evolution.csv`, `regimes.csv`, with `--vtk-every` a VTU series and
//! `solution.pvd`), the run's summary and the scenario it solved. Every CSV opens
//! with the same two provenance lines.

use super::csv::Table;
use super::rows::{ContactRow, StepRow, SummaryRow, TriangleRow};
use super::rundir::{OutError, RunDir};
use super::vtu;
use crate::certificate::ContactState;
use crate::mesh::{Dofs, Mesh};
use crate::scenario::Scenario;
use crate::scheme::Run;
use std::collections::BTreeMap;

/// Who produced a run: the command line, the step solver and the ordering.
#[derive(Debug, Clone)]
pub struct Provenance {
    /// The command line that asked for the run, after the program's name (as
    /// [`command_line`] gives it).
    pub command: String,
    /// The step solver that certified the run (a fallback's, if one did).
    pub solver: String,
    /// The fill-reducing ordering of $K$, by name.
    pub ordering: String,
    /// The time loop that ran: `general` or `reduced`.
    pub path: String,
    /// The mesh: `uniform`, `graded mu = …` (its exponent), or `file PATH` (a mesh
    /// scene's, as its scenario names it).
    pub mesh: String,
}

impl Provenance {
    /// What a run of `sim` records of itself, `command` the command line that asked
    /// for it: the solver that certified it (a fallback's, if one did), the ordering,
    /// the time loop and the mesh.
    pub fn of(
        sim: &crate::simulation::Simulation,
        solution: &crate::simulation::Solution,
        command: String,
    ) -> Provenance {
        use crate::simulation::MeshKind;
        let s = sim.settings();
        Provenance {
            command,
            solver: solution
                .fallback
                .as_ref()
                .map_or(sim.solver().name, |f| f.solver)
                .to_string(),
            ordering: sim.ordering().name().to_string(),
            path: (if solution.reduced {
                "reduced"
            } else {
                "general"
            })
            .to_string(),
            mesh: match (sim.scenario().body(), s.mesh) {
                (Some(body), _) => format!("file {}", body.file),
                (None, MeshKind::Graded) => format!(
                    "graded mu = {}",
                    s.grading.unwrap_or(crate::simulation::DEFAULT_GRADING)
                ),
                (None, MeshKind::Uniform) => "uniform".to_string(),
            },
        }
    }
}

/// The observer that writes a run directory: the [`Recorder`] and the directory its
/// VTK series goes into (`evhi solve` and the example experiment hand it to
/// [`crate::simulation::Simulation::solve`]).
pub struct Recording<'a> {
    /// What the run records as it goes.
    pub recorder: Recorder,
    /// The run directory the VTK series is written into.
    pub out: &'a RunDir,
}

impl crate::simulation::Observer for Recording<'_> {
    fn wants_field(&self, step: usize) -> bool {
        self.recorder.wants_field(step)
    }

    fn step(&mut self, n: usize, t: f64, u: Option<&[f64]>, contact: &[ContactState]) {
        self.recorder.observe(self.out, n, t, u, contact);
    }

    fn restart(&mut self) {
        self.recorder.reset();
    }
}

/// `text` on one line: control characters (a line feed or carriage return in a path)
/// written as escapes, so that a provenance line cannot break out of its `#`.
pub fn one_line(text: &str) -> String {
    text.chars()
        .map(|c| {
            if crate::error::breaks_line(c) {
                c.escape_default().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}

/// This process's command line after the program's name, for a provenance line:
/// [`quote_args`] of its arguments, each read lossily (a path that is not UTF-8, legal
/// on Linux, shows its undecodable bytes as U+FFFD instead of stopping the run).
pub fn command_line() -> String {
    quote_args(
        std::env::args_os()
            .skip(1)
            .map(|a| a.to_string_lossy().into_owned()),
    )
}

/// A command line as a shell would read it back: arguments with spaces, quotes or
/// control characters in single quotes (control characters escaped, see [`one_line`]).
pub fn quote_args(args: impl IntoIterator<Item = String>) -> String {
    args.into_iter()
        .map(|a| {
            let plain = !a.is_empty()
                && a.chars()
                    .all(|c| c.is_ascii_alphanumeric() || "-_./=,:+@%".contains(c));
            if plain {
                a
            } else {
                format!("'{}'", one_line(&a).replace('\'', "'\\''"))
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// The `#` lines that open every CSV of a run: the command and the data it solved,
/// every load among them (the file's `[[loads.traction]]`s after `f0_modulation`,
/// where it has any).
pub fn header(p: &Provenance, scn: &Scenario, n: usize, steps: usize) -> Vec<String> {
    vec![
        format!(
            "produced by evhi {} `evhi {}`",
            env!("CARGO_PKG_VERSION"),
            one_line(&p.command)
        ),
        format!(
            "scenario {}; n = {n}, steps = {steps}, T = {}; solver {}, ordering {}; g = {}; \
             f0 = ({}, {}), f2 = ({}, {}), f0_modulation = {}{}; load history: {}; \
             material: {}, alpha = {}, beta = {}",
            scn.name,
            scn.t_end,
            p.solver,
            p.ordering,
            scn.g,
            scn.f0[0],
            scn.f0[1],
            scn.f2[0],
            scn.f2[1],
            scn.f0_modulation,
            tractions(scn),
            scn.history,
            scn.material_form.describe(scn.e, scn.kappa),
            scn.alpha,
            scn.beta
        ),
    ]
}

/// The file's further tractions as the header names them, each after a comma:
/// `, loads.traction[0] = (0, -75) on the top side over [0, 2]` (empty without any).
fn tractions(scn: &Scenario) -> String {
    scn.tractions
        .iter()
        .map(|t| {
            format!(
                ", {} = ({}, {}) on the {} side over [{}, {}]",
                t.field,
                t.f[0],
                t.f[1],
                t.side.name(),
                t.from,
                t.to
            )
        })
        .collect()
}

/// Peak resident memory of this process (Linux `VmHWM`), MiB; NaN where unknown.
pub fn peak_rss_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines().find(|l| l.starts_with("VmHWM:")).and_then(|l| {
                l.split_whitespace()
                    .nth(1)
                    .and_then(|v| v.parse::<f64>().ok())
            })
        })
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

/// What a run records as it goes: the state at five contact nodes and the regime
/// counts every step, and (with `vtk_every`) a VTU every so many steps.
pub struct Recorder {
    law: crate::law::Law,
    g: f64,
    steps: usize,
    /// The watched contact nodes (indices into the contact nodes) and their x.
    watch: Vec<usize>,
    watch_x: Vec<f64>,
    evolution: Vec<(usize, f64, f64, ContactState, String)>,
    counts: Vec<(usize, f64, BTreeMap<String, u64>)>,
    vtk: Option<(u64, std::sync::Arc<Mesh>, Dofs)>,
    series: Vec<(f64, String)>,
    error: Option<OutError>,
}

impl Recorder {
    /// The recorder of a run of `scn` on `mesh`: it watches five contact nodes, the
    /// ends and quarters of the contact nodes' list.
    pub fn new(
        scn: &Scenario,
        mesh: std::sync::Arc<Mesh>,
        steps: usize,
        vtk_every: Option<u64>,
    ) -> Result<Recorder, crate::error::InputError> {
        let m = mesh.contact.len();
        let watch: Vec<usize> = (0..5).map(|q| q * (m.max(1) - 1) / 4).collect();
        let watch_x = watch
            .iter()
            .map(|&i| mesh.nodes[mesh.contact[i]][0])
            .collect();
        let vtk = vtk_every.map(|k| {
            let dofs = Dofs::new(&mesh, true);
            (k, mesh, dofs)
        });
        Ok(Recorder {
            law: scn.law.clone(),
            g: scn.g,
            steps,
            watch,
            watch_x,
            evolution: vec![],
            counts: vec![],
            vtk,
            series: vec![],
            error: None,
        })
    }

    /// Forgets every step recorded: the run starts again from $t = 0$.
    pub fn reset(&mut self) {
        self.evolution.clear();
        self.counts.clear();
        self.series.clear();
        self.error = None;
    }

    /// Whether step `step` is written as a field (so the reduced loop forms it).
    pub fn wants_field(&self, step: usize) -> bool {
        self.vtk
            .as_ref()
            .is_some_and(|(k, ..)| (step as u64).is_multiple_of(*k) || step == self.steps)
    }

    /// Records step `step` (time `t`, field `u` where one was formed, contact
    /// states `contact`).
    pub fn observe(
        &mut self,
        out: &RunDir,
        step: usize,
        t: f64,
        u: Option<&[f64]>,
        contact: &[ContactState],
    ) {
        let mut counts = BTreeMap::new();
        for c in contact {
            *counts.entry(c.regime(&self.law, self.g)).or_insert(0) += 1;
        }
        self.counts.push((step, t, counts));
        for (&i, &x) in self.watch.iter().zip(&self.watch_x) {
            if let Some(c) = contact.get(i) {
                self.evolution
                    .push((step, t, x, *c, c.regime(&self.law, self.g)));
            }
        }
        if let Some((_, mesh, dofs)) = &self.vtk
            && let Some(u) = u.filter(|_| self.wants_field(step))
            && self.error.is_none()
        {
            let file = format!("solution_{step:06}.vtu");
            let codes: Vec<i32> = contact
                .iter()
                .map(|c| c.regime_code(&self.law, self.g))
                .collect();
            let text = vtu::vtu(mesh, &mesh.displacement(dofs, u), contact, &codes);
            match out.write(&file, text.as_bytes()) {
                Ok(()) => self.series.push((t, file)),
                Err(e) => self.error = Some(e),
            }
        }
    }
}

/// Writes the whole set of a finished run into `out` (not yet published): `toml` is
/// the scenario's text as read, `wall_s` the run's wall time so far, `h_s` the two
/// sides of H(s).
#[allow(clippy::too_many_arguments)]
pub fn write(
    out: &RunDir,
    scn: &Scenario,
    toml: &str,
    run: &Run,
    rec: Recorder,
    prov: &Provenance,
    wall_s: f64,
    h_s: &crate::show::Smallness,
) -> Result<(), OutError> {
    if let Some(e) = rec.error {
        return Err(e);
    }
    let header = header(prov, scn, run.n, run.steps);
    if rec.vtk.is_some() {
        out.write("solution.pvd", vtu::pvd(&rec.series).as_bytes())?;
    }
    let mesh = &*run.mesh;
    let dofs = Dofs::new(mesh, true);
    let contact = ContactRow::of(run, scn);
    out.write_table("contact.csv", &ContactRow::table(&contact), &header)?;
    let r = &run.records;
    out.write_table("steps.csv", &StepRow::table(&step_rows(r)), &header)?;
    let max_cert = r.iter().map(|s| s.certificate.max()).fold(0.0, f64::max);
    let iters: usize = r.iter().map(|s| s.iterations).sum();
    let t = &run.timings;
    let summary = SummaryRow {
        n: run.n as u64,
        steps: run.steps as u64,
        dofs: run.dofs as u64,
        energy_norm_t: r.last().map_or(0.0, |s| s.energy_norm),
        max_certificate: max_cert,
        wall_s,
        max_overshoot_over_g: max_overshoot(r),
        scenario: scn.name.clone(),
        solver: prov.solver.clone(),
        h: run.mesh.h(),
        k: run.k,
        g: scn.g,
        f0_x: scn.f0[0],
        f0_y: scn.f0[1],
        f2_x: scn.f2[0],
        f2_y: scn.f2[1],
        load_history: scn.history.to_string(),
        compatible_data: scn.time_hypotheses().h_0().to_string(),
        mean_iterations: iters as f64 / run.steps as f64,
        step_curvature_min: run.hessian_min,
        beta_b: h_s.beta_b,
        m_trace_norm_sq: if scn.law.down_jumps().is_empty() {
            h_s.rhs()
        } else {
            f64::NAN
        },
        assembly_s: t.assembly,
        factorisation_s: t.factorisation,
        condensation_s: t.condensation,
        steps_s: t.steps,
        nnz_l: run.nnz_l as u64,
        one_solve_s: t.one_solve,
        floor_ratio: t.floor_ratio(run.steps),
        peak_rss_mb: peak_rss_mb(),
        ordering: prov.ordering.clone(),
        path: prov.path.clone(),
        mesh: prov.mesh.clone(),
        sweep_threads: run.sweep_threads as u64,
        version: format!("evhi {}", env!("CARGO_PKG_VERSION")),
        e: scn.e,
        kappa: scn.kappa,
        alpha: scn.alpha,
        beta: scn.beta,
        tractions: (scn.tractions.len() + scn.body().map_or(0, |b| b.tractions.len())) as u64,
    };
    out.write_table("summary.csv", &SummaryRow::table(&[summary]), &header)?;
    let disp = run.mesh.displacement(&dofs, &run.u);
    let codes: Vec<i32> = run
        .contact
        .iter()
        .map(|c| c.regime_code(&scn.law, scn.g))
        .collect();
    out.write(
        "solution.vtu",
        vtu::vtu(mesh, &disp, &run.contact, &codes).as_bytes(),
    )?;
    if !mesh.pattern.is_grid() {
        // No lattice: every node, and the triangles the figure draws.
        let col = |c: usize| mesh.nodes.iter().map(|p| p[c]).collect();
        let dcol = |c: usize| disp.iter().map(|d| d[c]).collect();
        out.write_table(
            "nodes.csv",
            &Table::new()
                .f64("x", col(0))
                .f64("y", col(1))
                .f64("ux", dcol(0))
                .f64("uy", dcol(1)),
            &header,
        )?;
        let triangles: Vec<TriangleRow> = (mesh.triangles.iter())
            .map(|t| TriangleRow {
                a: t[0] as u64,
                b: t[1] as u64,
                c: t[2] as u64,
            })
            .collect();
        out.write_table("triangles.csv", &TriangleRow::table(&triangles), &header)?;
    } else {
        out.write_table(
            "nodes.csv",
            &nodes_table(mesh, &disp, lattice_stride(mesh.n, mesh.ny)),
            &header,
        )?;
    }
    // The evolution at five contact nodes, and the regime counts.
    let ev = &rec.evolution;
    out.write_table(
        "evolution.csv",
        &Table::new()
            .u64("step", ev.iter().map(|e| e.0 as u64).collect())
            .f64("t", ev.iter().map(|e| e.1).collect())
            .f64("x", ev.iter().map(|e| e.2).collect())
            .f64("u_nu", ev.iter().map(|e| e.3.u_nu).collect())
            .f64("sigma_nu1", ev.iter().map(|e| e.3.sigma_nu1).collect())
            .f64("sigma_nu2", ev.iter().map(|e| e.3.sigma_nu2).collect())
            .str("regime", ev.iter().map(|e| e.4.clone()).collect()),
        &header,
    )?;
    let all: Vec<String> = rec
        .counts
        .iter()
        .flat_map(|r| r.2.keys().cloned())
        .collect();
    let mut regimes = Table::new()
        .u64("step", rec.counts.iter().map(|r| r.0 as u64).collect())
        .f64("t", rec.counts.iter().map(|r| r.1).collect());
    for name in crate::certificate::regime_order(&all) {
        let col = rec
            .counts
            .iter()
            .map(|r| *r.2.get(&name).unwrap_or(&0))
            .collect();
        regimes = regimes.u64(&name, col);
    }
    out.write_table("regimes.csv", &regimes, &header)?;
    // The scenario as solved: its TOML, with the command line that may override it. A
    // mesh scene's run keeps the mesh as read beside it, and its TOML names that copy.
    let toml = match scn.body() {
        None => toml.to_string(),
        Some(body) => {
            out.write(RUN_MESH, &body.bytes)?;
            with_mesh(toml, RUN_MESH)
        }
    };
    out.write(
        "scenario.toml",
        format!(
            "# The scenario of this run, as read. Command-line overrides apply on top of it:\n\
             # evhi {}\n# (summary.csv records the values solved.)\n{toml}",
            one_line(&prov.command)
        )
        .as_bytes(),
    )?;
    Ok(())
}

/// The copy of a mesh scene's mesh file in its run directory.
pub const RUN_MESH: &str = "mesh.msh";

/// A mesh scene's TOML with `geometry.mesh` set to `file` (rewritten from its
/// tables, so the comments are dropped; the values are unchanged).
fn with_mesh(toml: &str, file: &str) -> String {
    let Ok(mut table) = toml.parse::<toml::Table>() else {
        return toml.to_string();
    };
    if let Some(toml::Value::Table(geo)) = table.get_mut("geometry") {
        geo.insert("mesh".into(), toml::Value::String(file.into()));
    }
    format!(
        "# (geometry.mesh names the copy of the mesh file this run read.)\n{}",
        toml::to_string(&table).unwrap_or_else(|_| toml.to_string())
    )
}

/// The stride, in cells, of the lattice a uniform run writes to `nodes.csv`: about
/// n/32 (some 33 nodes across), lowered until it divides both the columns and the
/// rows, so that the lattice keeps the mesh's last column and row (n/32 alone left
/// them out for n = 100, say).
pub fn lattice_stride(n: usize, ny: usize) -> usize {
    let mut s = (n / 32).max(1);
    while !(n.is_multiple_of(s) && ny.is_multiple_of(s)) {
        s -= 1;
    }
    s
}

/// The lattice of a run's mesh every `stride` cells, with the displacement (`nodes.csv`).
pub fn nodes_table(mesh: &Mesh, disp: &[[f64; 2]], stride: usize) -> Table {
    let (mut x, mut y, mut ux, mut uy) = (vec![], vec![], vec![], vec![]);
    let n = mesh.n;
    for j in (0..=mesh.ny).step_by(stride) {
        for i in (0..=n).step_by(stride) {
            let v = j * (n + 1) + i;
            x.push(mesh.nodes[v][0]);
            y.push(mesh.nodes[v][1]);
            ux.push(disp[v][0]);
            uy.push(disp[v][1]);
        }
    }
    Table::new()
        .f64("x", x)
        .f64("y", y)
        .f64("ux", ux)
        .f64("uy", uy)
}

/// The largest overshoot of the limit over the run, $\max_n \max_i (u_{\nu,i} - g)^+ / g$
/// beyond rounding (each step's feasibility): 0 for a certified run, the price of
/// the penalty for the penalty solver.
pub fn max_overshoot(records: &[crate::scheme::StepRecord]) -> f64 {
    records
        .iter()
        .map(|s| s.certificate.feasibility)
        .fold(0.0, f64::max)
}

/// The rows of `steps.csv`, one per step record.
pub fn step_rows(r: &[crate::scheme::StepRecord]) -> Vec<StepRow> {
    r.iter()
        .map(|s| StepRow {
            step: s.step as u64,
            t: s.t,
            iterations: s.iterations as u64,
            inner_iterations: s.inner_iterations as u64,
            solver_residual: s.solver_residual,
            certificate: s.certificate.max(),
            stationarity: s.certificate.stationarity,
            feasibility: s.certificate.feasibility,
            complementarity: s.certificate.complementarity,
            energy_norm: s.energy_norm,
            time_s: s.time_s,
            check: s.check.name().to_string(),
            recovery: s.certificate.recovery,
        })
        .collect()
}

/// The work of each step: its number and time, the solver's iterations and residual,
/// and its certificate (the first columns of `steps.csv`, without timings).
pub fn step_work(r: &[crate::scheme::StepRecord]) -> Table {
    StepRow::table(&step_rows(r)).first(StepRow::WORK)
}

/// The `--timings` report of a solve: the phases, the sizes, the cost of one solve
/// against the run and the peak memory; `output` and `total` are the seconds spent
/// writing the run directory and in all, `estimator` the seconds of the residual
/// estimator on the last step when `--estimate` asked for it (a phase of its own,
/// with what estimating every step would cost against the solve).
pub fn timings(
    sim: &crate::simulation::Simulation,
    run: &crate::scheme::Run,
    output: std::time::Duration,
    total: std::time::Duration,
    estimator: Option<f64>,
) -> String {
    let t = &run.timings;
    let solve = t.assembly + t.factorisation + t.condensation + t.steps;
    let est = estimator.map_or(String::new(), |e| {
        format!(
            "  estimator {e:.4} (one step; every step would be {:.1} % of the solve)",
            100.0 * run.steps as f64 * e / solve
        )
    });
    format!(
        "timings (s): assembly {:.4}  factorisation {:.4}  condensation {:.4}  steps {:.4} \
         (step solver {:.4}, certificates {:.4}){est}  output {:.4}  total {:.4}\n\
         dofs {}  contact nodes {}  nnz(L) {} ({}, {} sweep thread(s))\n\
         one solve {:.4} s; run / (factorisation + N solves) = {:.3}; peak memory {:.0} MB\n",
        t.assembly,
        t.factorisation,
        t.condensation,
        t.steps,
        t.step_solver,
        t.certificates,
        output.as_secs_f64(),
        total.as_secs_f64(),
        run.dofs,
        run.contact.len(),
        run.nnz_l,
        sim.ordering().name(),
        run.sweep_threads,
        t.one_solve,
        t.floor_ratio(run.steps),
        peak_rss_mb()
    )
}
