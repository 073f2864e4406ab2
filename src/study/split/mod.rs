//! Table 1's computation on any scenes: the $h = k$, $h$ and $k$ families on the
//! uniform meshes of a plan, against a uniform reference, with the relative energy
//! errors at $T$ and over the time levels, their observed orders, and where in
//! $\Omega$ the error sits (by [`Regions`]). The book's Table 1 (experiment `table1`)
//! and `evhi study convergence`'s error split run it.
//!
//! Every run goes by the reduced loop ([`crate::reduced`]): one factorisation of
//! $B$ per mesh serves all its step lengths, and the errors between the time
//! levels need no field (see `Reference::coarse`). At $T$ the fields are formed,
//! the coarse one embedded exactly in the reference space (the spaces are
//! nested). The error over time is
//! $\max_n \|e_n\|_E / \max_n \|u_{ref,n}\|_E$ over the time levels shared with the
//! reference (the norm of Corollary 4.1's left side).

use super::{Ctx, ExpError};
use crate::element::strain_matrix;
use crate::mesh::{Dofs, Interpolation, Mesh};
use crate::output::csv::Table;
use crate::output::csv::{col_f64, col_str, read_csv};
use crate::output::plot::{Figure, both, circle_legend, dashed_legend, e2s, legend};
use crate::reduced::{Reduced, State};
use crate::scenario::Scenario;
use crate::scheme::Timings;
use crate::simulation::{Loop, RunSettings, Simulation};
use plotters::prelude::*;
use std::collections::BTreeMap;

pub mod figure;
pub use figure::draw_split;

/// Levels and reference of a study.
pub struct Plan {
    /// The levels $n$ of the families: $h = 1/n$ in the $h = k$ and $h$ families, $n$
    /// time steps in the $h = k$ and $k$ families.
    pub levels: Vec<usize>,
    /// The level of the reference, $h = k = 1/n_{ref}$.
    pub n_ref: usize,
    /// The step solver of every run (the registry's; `newton` in the book's study).
    pub solver: &'static crate::step::SolverEntry,
}

/// The levels of the study: with `quick`, 4 to 16 against a reference at 32; else
/// 4 to 128 against 512 (Table 1's); the default step solver.
pub fn plan(quick: bool) -> Plan {
    if quick {
        Plan {
            levels: vec![4, 8, 16],
            n_ref: 32,
            solver: crate::step::DEFAULT_SOLVER_ENTRY,
        }
    } else {
        Plan {
            levels: vec![4, 8, 16, 32, 64, 128],
            n_ref: 512,
            solver: crate::step::DEFAULT_SOLVER_ENTRY,
        }
    }
}

/// The reference runs of a group of scenarios that share the step matrix (so the
/// mesh and the energy norm too), with what the levels need of them at the time
/// levels $t = j/N_{grid}$.
struct Reference {
    mesh: std::sync::Arc<Mesh>,
    dofs: Dofs,
    grid: usize,
    runs: Vec<RefRun>,
    tensor: crate::material::Isotropic,
    regions: Regions,
    /// The step solver of every run.
    solver: &'static crate::step::SolverEntry,
}

/// One scenario's reference.
struct RefRun {
    /// The load vector $f$ on the reference mesh.
    f: Vec<f64>,
    /// By level $j$: the reduced state and $u^\top B u$.
    at: BTreeMap<usize, (State, f64)>,
    /// $u_{ref}(T)$.
    field_t: Vec<f64>,
}

/// Error of one level against the reference.
#[derive(Debug, Clone)]
pub struct LevelError {
    /// The family: `h=k`, `h` or `k`.
    pub family: &'static str,
    /// The mesh level $n$, $h = 1/n$.
    pub n: usize,
    /// The number of time steps $N$.
    pub steps: usize,
    /// The relative energy error at $T$, $\|e(T)\|_E / \|u_{ref}(T)\|_E$.
    pub rel_t: f64,
    /// The relative energy error over time, $\max_n \|e_n\|_E / \max_n \|u_{ref,n}\|_E$
    /// over the time levels shared with the reference.
    pub rel_max: f64,
    /// Squared error at $t = T$ in three regions: near the clamp ends, near $\Gamma_3$, the rest.
    pub regions: [f64; 3],
}

/// Where the error is measured apart: near singular points, near the contact side
/// $y = 0$, and the rest.
#[derive(Debug, Clone)]
pub struct Regions {
    /// The singular points the first region surrounds.
    pub points: Vec<[f64; 2]>,
    /// The radius of the first region around each point, and the width of the second
    /// along $y = 0$.
    pub radius: f64,
    /// What the points are, naming the first share's column `share_<near>`.
    pub near: &'static str,
}

impl Regions {
    /// Table 1's: within 1/8 of the ends of $\Gamma_1$ at $(0, 1/2)$, $(2, 1/2)$, then
    /// within 1/8 of $\Gamma_3$.
    pub fn paper() -> Regions {
        Regions {
            points: vec![[0.0, 0.5], [2.0, 0.5]],
            radius: 0.125,
            near: "clamp_ends",
        }
    }

    /// Region of a point: 0 within `radius` of a point, 1 within `radius` of
    /// $y = 0$, 2 elsewhere.
    pub fn of(&self, x: f64, y: f64) -> usize {
        let d = (self.points.iter())
            .map(|p| (x - p[0]).hypot(y - p[1]))
            .fold(f64::INFINITY, f64::min);
        if d < self.radius {
            0
        } else if y < self.radius {
            1
        } else {
            2
        }
    }
}

/// The running error measures of one scenario in one level.
#[derive(Default)]
struct Accumulator {
    max_e: f64,
    max_u: f64,
    /// $\|e(T)\|_E$ from the reduced quantities (what the table reports).
    e_t_reduced: f64,
    /// $\|e(T)\|_E$ from the formed fields (the check, and the regions).
    e_t: f64,
    u_t: f64,
    regions: [f64; 3],
}

impl Accumulator {
    /// Adds the error $\|e\|_E$ at level $j$ of the grid.
    fn add(&mut self, e: f64, u_ref: f64, at_t: bool) {
        self.max_e = self.max_e.max(e);
        self.max_u = self.max_u.max(u_ref);
        if at_t {
            self.e_t_reduced = e;
            self.u_t = u_ref;
        }
    }

    /// The level's row, once the error at $T$ has also been formed from the fields:
    /// the two must agree to $10^{-9}\,\|u_{ref}(T)\|_E$. Each formed field carries
    /// the rounding of a solve with $B$ (measured: the two routes differ by at most
    /// $7\cdot10^{-11}\,\|u_{ref}(T)\|_E$ at $h = 1/512$), which the reduced route
    /// does not, so the table reports the reduced error (it moves by $10^{-13}$
    /// relative where the formed one moves by $10^{-9}$ when the matrices change
    /// in their last bit).
    fn finish(
        self,
        family: &'static str,
        (n, steps): (usize, usize),
        scenario: &str,
    ) -> Result<LevelError, ExpError> {
        let agree = (self.e_t - self.e_t_reduced).abs() <= 1e-9 * self.u_t;
        if !self.e_t.is_finite() || !agree {
            return Err(ExpError::File(crate::output::FileError::Table {
                path: format!("table1, scenario {scenario}"),
                message: format!(
                    "h = 1/{n}, {steps} steps: the error at T is {:e} from the fields and {:e} \
                     from the reduced quantities (||u_ref(T)||_E = {:e})",
                    self.e_t, self.e_t_reduced, self.u_t
                ),
            }));
        }
        Ok(LevelError {
            family,
            n,
            steps,
            rel_t: self.e_t_reduced / self.u_t,
            rel_max: self.max_e / self.max_u,
            regions: self.regions,
        })
    }
}

/// $\|v\|_E$ from $v^\top B v$.
fn energy_of_quad(quad: f64) -> f64 {
    (0.5 * quad).max(0.0).sqrt()
}

/// The time levels $t = j/N_{grid}$ a run of `steps` steps shares with the grid:
/// $j$ of step `step`, if it is one.
fn grid_level(step: usize, steps: usize, grid: usize) -> Option<usize> {
    (step * grid)
        .is_multiple_of(steps)
        .then(|| step * grid / steps)
}

/// The simulation of level `n` of the study, which prepares its discretisation and
/// reduced operator. Two workers already keep both cores busy, so its solves take
/// one thread.
fn prepared(scn: &Scenario, n: usize) -> Result<Simulation, ExpError> {
    let settings = RunSettings::default()
        .with_n(n)
        .with_path(Loop::Reduced)
        .with_threads(1);
    Ok(Simulation::new(scn.clone(), settings)?)
}

/// Marches `scn` under `load` with `steps` steps on `op`, calls `at_level(j, state)`
/// at every step on the grid $t = j/N_{grid}$, and returns the field at $T$.
fn march_on_grid(
    op: &Reduced,
    scn: &Scenario,
    load: &crate::reduced::Load,
    steps: usize,
    (grid, solver): (usize, &crate::step::SolverEntry),
    timings: &mut Timings,
    mut at_level: impl FnMut(usize, &State),
) -> Result<Vec<f64>, ExpError> {
    let mut field_t = vec![];
    op.march(
        scn,
        load,
        steps,
        solver.build().as_mut(),
        crate::scheme::CERTIFICATE_TOL,
        &|step| step == steps,
        timings,
        &mut |s| {
            if let Some(j) = grid_level(s.step, steps, grid) {
                at_level(j, s.state);
            }
            if let Some(u) = s.field {
                field_t = u.to_vec();
            }
        },
    )?;
    Ok(field_t)
}

impl Reference {
    /// The references of a group of scenarios that share the step matrix, and the
    /// group's $k$ family (the reference mesh, coarser steps): all on one
    /// factorisation of $B$ (the reduced loop of [`crate::reduced`]). Returns the
    /// reference and, per scenario of the group, its $k$-family errors by level.
    fn compute(
        scns: &[Scenario],
        plan: &Plan,
        grid: usize,
        ctx: &Ctx,
        regions: &Regions,
    ) -> Result<(Reference, Vec<Vec<LevelError>>), ExpError> {
        let n_ref = plan.n_ref;
        let clock = std::time::Instant::now();
        let sim = prepared(&scns[0], n_ref)?;
        let disc = sim.discretisation();
        let mut timings = Timings::default();
        let op = sim.reduced_operator(&disc, &mut timings)?;
        let tensor = scns[0].elasticity();
        let mut runs = Vec::with_capacity(scns.len());
        for scn in scns {
            let load = op.load_of(scn);
            let mut at = BTreeMap::new();
            let field_t = march_on_grid(
                &op,
                scn,
                &load,
                n_ref,
                (grid, plan.solver),
                &mut timings,
                |j, st| {
                    at.insert(j, (st.clone(), op.quad(&load, st)));
                },
            )?;
            runs.push((
                load,
                RefRun {
                    f: vec![],
                    at,
                    field_t,
                },
            ));
        }
        let names: Vec<&str> = scns.iter().map(|s| s.name.as_str()).collect();
        ctx.log(&format!(
            "{}: reference, h = k = 1/{n_ref} ({:.1} s)",
            names.join(" + "),
            clock.elapsed().as_secs_f64()
        ));
        let mut reference = Reference {
            mesh: disc.mesh.clone(),
            dofs: Dofs::new(&disc.mesh, true),
            grid,
            runs: vec![],
            tensor,
            regions: regions.clone(),
            solver: plan.solver,
        };
        // The k family: h = 1/n_ref, k = 1/n, on the same factorisation.
        let clock = std::time::Instant::now();
        let mut k_family = vec![vec![]; scns.len()];
        for (i, scn) in scns.iter().enumerate() {
            let (load, run) = &runs[i];
            for &steps in &plan.levels {
                let mut acc = Accumulator::default();
                let field_t = march_on_grid(
                    &op,
                    scn,
                    load,
                    steps,
                    (grid, plan.solver),
                    &mut timings,
                    |j, st| {
                        let (st_ref, quad) = &run.at[&j];
                        acc.add(
                            op.energy_diff(load, st_ref, st),
                            energy_of_quad(*quad),
                            j == grid,
                        );
                    },
                )?;
                let diff: Vec<f64> = run
                    .field_t
                    .iter()
                    .zip(&field_t)
                    .map(|(a, b)| a - b)
                    .collect();
                acc.regions = reference.regions(&diff);
                acc.e_t = acc.regions.iter().sum::<f64>().sqrt();
                k_family[i].push(acc.finish(FAMILIES[2], (n_ref, steps), &scn.name)?);
            }
        }
        ctx.log(&format!(
            "{}: k family, h = 1/{n_ref} ({:.1} s)",
            names.join(" + "),
            clock.elapsed().as_secs_f64()
        ));
        reference.runs = runs
            .into_iter()
            .map(|(load, run)| RefRun { f: load.f, ..run })
            .collect();
        Ok((reference, k_family))
    }

    /// The errors of the coarse mesh $h = 1/n$ for each scenario of the group, in
    /// the $h = k$ family ($k = 1/n$) and the $h$ family ($k$ of the reference),
    /// both on one factorisation of its $B$. Between the time levels of the grid
    /// no field is formed: with $P$ the exact embedding of the coarse space in the
    /// reference one and $g_{ref} = B u_{ref} = Y f + E_C^\top W$,
    /// $$\|u_{ref} - P u_h\|_B^2 = u_{ref}^\top B u_{ref} - 2\, g_{ref}^\top P u_h + u_h^\top B_h u_h,$$
    /// where $f^\top P u_h = (P^\top f)^\top u_h$ and $E_C P u_h$ interpolates $-r_h$ along
    /// $\Gamma_3$. At $T$ the fields are formed, and the two must agree.
    fn coarse(
        &self,
        scns: &[Scenario],
        n: usize,
        n_ref: usize,
    ) -> Result<[Vec<LevelError>; 2], ExpError> {
        let sim = prepared(&scns[0], n)?;
        let disc = sim.discretisation();
        let mut timings = Timings::default();
        let op = sim.reduced_operator(&disc, &mut timings)?;
        let interp = Interpolation::nested(&disc.mesh, &self.mesh)?;
        // Per coarse node: its index among the contact nodes.
        let mut contact_index = vec![None; disc.mesh.nodes.len()];
        for (i, &v) in disc.mesh.contact.iter().enumerate() {
            contact_index[v] = Some(i);
        }
        // Interpolates coarse contact values r at the reference contact nodes.
        let on_contact = |r: &[f64]| -> Vec<f64> {
            (self.mesh.contact.iter())
                .map(|&v| {
                    (interp.weights[v].iter())
                        .map(|&(c, wt)| contact_index[c].map_or(0.0, |i| wt * r[i]))
                        .sum()
                })
                .collect()
        };
        let mut out = [vec![], vec![]];
        for (scn, run) in scns.iter().zip(&self.runs) {
            let load = op.load_of(scn);
            // d = B_h^{-1} P^T f_ref.
            let pt_f = interp.apply_transpose(&self.dofs.expand(&run.f), disc.mesh.nodes.len());
            let d = op.chol.solve(&disc.dofs.gather(&pt_f));
            let d_f: f64 = d.iter().zip(&load.f).map(|(a, b)| a * b).sum();
            let d_c: Vec<f64> = disc.contact_dofs.iter().map(|&c| d[c]).collect();
            for (slot, steps) in [(0, n), (1, n_ref)] {
                let mut acc = Accumulator::default();
                let field_t = march_on_grid(
                    &op,
                    scn,
                    &load,
                    steps,
                    (self.grid, self.solver),
                    &mut timings,
                    |j, st| {
                        let (st_ref, quad_ref) = &run.at[&j];
                        let wd: f64 = st.w.iter().zip(&d_c).map(|(a, b)| a * b).sum();
                        let wr: f64 = (st_ref.w.iter().zip(on_contact(&st.r)))
                            .map(|(a, b)| a * b)
                            .sum();
                        let cross = st_ref.y * (st.y * d_f + wd) - wr;
                        let quad = quad_ref - 2.0 * cross + op.quad(&load, st);
                        acc.add(
                            energy_of_quad(quad),
                            energy_of_quad(*quad_ref),
                            j == self.grid,
                        );
                    },
                )?;
                let fine = self.dofs.gather(&interp.apply(&disc.dofs.expand(&field_t)));
                let diff: Vec<f64> = run.field_t.iter().zip(&fine).map(|(a, b)| a - b).collect();
                acc.regions = self.regions(&diff);
                acc.e_t = acc.regions.iter().sum::<f64>().sqrt();
                out[slot].push(acc.finish(FAMILIES[slot], (n, steps), &scn.name)?);
            }
        }
        Ok(out)
    }

    /// $\tfrac12(\mathcal G\varepsilon(v), \varepsilon(v))$ per region.
    fn regions(&self, v: &[f64]) -> [f64; 3] {
        let nodal = self.dofs.expand(v);
        let d = self.tensor.voigt();
        let mut out = [0.0; 3];
        for tri in &self.mesh.triangles {
            let p = tri.map(|k| self.mesh.nodes[k]);
            let (area, bm) = strain_matrix(p);
            let ue = nalgebra::SVector::<f64, 6>::from_fn(|a, _| nodal[tri[a / 2]][a % 2]);
            let eps = bm * ue;
            let dens = 0.5 * (eps.transpose() * d * eps)[(0, 0)] * area;
            let cx = (p[0][0] + p[1][0] + p[2][0]) / 3.0;
            let cy = (p[0][1] + p[1][1] + p[2][1]) / 3.0;
            out[self.regions.of(cx, cy)] += dens;
        }
        out
    }
}

/// One unit of the study's work: the references of a group of scenarios that
/// share the step matrix with their $k$ family, or one coarse mesh of such a
/// group with its $h = k$ and $h$ families.
#[derive(Debug, Clone, Copy)]
enum Task {
    Reference(usize),
    Level {
        group: usize,
        /// Index of the level in the plan.
        level: usize,
    },
}

/// The three families: $(n, N)$ from the level's $n$ and the reference's $n$ are
/// $(n, n)$, $(n, n_{ref})$ and $(n_{ref}, n)$.
const FAMILIES: [&str; 3] = ["h=k", "h", "k"];

/// What the workers share: the tasks not yet started, the references done so far,
/// and the first error.
struct Queue {
    pending: Vec<Task>,
    references: Vec<Option<std::sync::Arc<Reference>>>,
    /// (table row, error).
    levels: Vec<(usize, LevelError)>,
    /// References being computed now.
    running: usize,
    error: Option<ExpError>,
}

/// All three families of all scenarios, on two threads (this machine has two
/// cores), by the reduced loop: one factorisation of $B$ per mesh serves every
/// $k$. References go first (each with its $k$ family); then the coarse meshes,
/// finest first, each as soon as its reference is there.
fn study(
    scenarios: &[Scenario],
    plan: &Plan,
    grid: usize,
    ctx: &Ctx,
    regions: &Regions,
) -> Result<Vec<(String, LevelError)>, ExpError> {
    let mut groups: Vec<Vec<Scenario>> = vec![];
    for scn in scenarios {
        match groups.iter_mut().find(|g| g[0].same_operator(scn)) {
            Some(g) => g.push(scn.clone()),
            None => groups.push(vec![scn.clone()]),
        }
    }
    // Table rows: scenario, level, family.
    let nl = plan.levels.len();
    let row = |name: &str, level: usize, family: usize| {
        let s = scenarios
            .iter()
            .position(|x| x.name == name)
            .expect("listed");
        (s * nl + level) * FAMILIES.len() + family
    };
    let mut pending: Vec<Task> = (0..groups.len()).map(Task::Reference).collect();
    for level in (0..nl).rev() {
        for group in 0..groups.len() {
            pending.push(Task::Level { group, level });
        }
    }
    // Each reference logs twice (itself, its k family), each coarse mesh once.
    ctx.add_units(pending.len() + groups.len());
    // A reference holds the factor of its B: two at once only where both fit in
    // 2 GB (h = 1/512 needs about 0.5 GB; h = 1/1024 about 2 GB, so one at a time).
    let concurrent = if 2.0 * crate::scheme::memory_estimate(plan.n_ref) <= 2e9 {
        2
    } else {
        1
    };
    let queue = std::sync::Mutex::new(Queue {
        pending,
        references: vec![None; groups.len()],
        levels: vec![],
        running: 0,
        error: None,
    });
    let ready = std::sync::Condvar::new();
    let worker = || loop {
        let (task, reference) = {
            let mut q = queue.lock().expect("study queue");
            loop {
                if q.error.is_some() || q.pending.is_empty() {
                    return;
                }
                let runnable = q.pending.iter().position(|t| match t {
                    Task::Reference(_) => q.running < concurrent,
                    Task::Level { group, .. } => q.references[*group].is_some(),
                });
                match runnable {
                    Some(i) => {
                        let task = q.pending.remove(i);
                        if let Task::Reference(_) = task {
                            q.running += 1;
                        }
                        let reference = match task {
                            Task::Level { group, .. } => q.references[group].clone(),
                            Task::Reference(_) => None,
                        };
                        break (task, reference);
                    }
                    None => q = ready.wait(q).expect("study queue"),
                }
            }
        };
        let outcome = match (task, reference) {
            (Task::Reference(g), _) => Reference::compute(&groups[g], plan, grid, ctx, regions)
                .map(|(r, k_family)| {
                    let rows: Vec<(usize, LevelError)> = (groups[g].iter().zip(k_family))
                        .flat_map(|(s, errs)| {
                            (errs.into_iter().enumerate())
                                .map(|(level, e)| (row(&s.name, level, 2), e))
                                .collect::<Vec<_>>()
                        })
                        .collect();
                    (Some((g, std::sync::Arc::new(r))), rows)
                }),
            (Task::Level { group, level }, Some(reference)) => {
                let n = plan.levels[level];
                let clock = std::time::Instant::now();
                let errors = reference
                    .coarse(&groups[group], n, plan.n_ref)
                    .map_err(|e| e.at(format!("the h = k and h families, level n = {n}")));
                let names: Vec<&str> = groups[group].iter().map(|s| s.name.as_str()).collect();
                ctx.log(&format!(
                    "{}: h = k and h families, h = 1/{n} ({:.1} s)",
                    names.join(" + "),
                    clock.elapsed().as_secs_f64()
                ));
                errors.map(|[hk, h]| {
                    let rows: Vec<(usize, LevelError)> =
                        (groups[group].iter().zip(hk.into_iter().zip(h)))
                            .flat_map(|(s, (hk, h))| {
                                [(row(&s.name, level, 0), hk), (row(&s.name, level, 1), h)]
                            })
                            .collect();
                    (None, rows)
                })
            }
            (Task::Level { .. }, None) => unreachable!("levels wait for their reference"),
        };
        let mut q = queue.lock().expect("study queue");
        if let Task::Reference(_) = task {
            q.running -= 1;
        }
        match outcome {
            Ok((reference, rows)) => {
                if let Some((g, r)) = reference {
                    q.references[g] = Some(r);
                }
                q.levels.extend(rows);
                // References no pending level needs are let go (their fields are
                // large); running levels hold their own handle.
                for g in 0..groups.len() {
                    let needed = (q.pending.iter())
                        .any(|t| matches!(t, Task::Level { group, .. } if *group == g));
                    if !needed {
                        q.references[g] = None;
                    }
                }
            }
            Err(e) => {
                q.error.get_or_insert(e);
            }
        }
        ready.notify_all();
    };
    std::thread::scope(|s| {
        let handles: Vec<_> = (0..2).map(|_| s.spawn(worker)).collect();
        for h in handles {
            h.join().expect("convergence thread");
        }
    });
    let q = queue.into_inner().expect("study queue");
    if let Some(e) = q.error {
        return Err(e);
    }
    let mut rows = q.levels;
    rows.sort_by_key(|r| r.0);
    Ok(rows
        .into_iter()
        .map(|(i, e)| {
            let s = i / (nl * FAMILIES.len());
            (scenarios[s].name.clone(), e)
        })
        .collect())
}

/// The three families ($h = k$, $h$, $k$) of each scenario on the uniform meshes of
/// `plan` against a uniform reference, with the error's shares by `regions` (and,
/// with `paper`, its values, keyed by $n$, beside the $h = k$ rows): the table of
/// `table1.csv` and its parameter line. The scenarios' meshes must be nested from
/// level to level (the structured meshes of [`Scenario::mesh`] are).
pub fn compute(
    scenarios: &[Scenario],
    plan: &Plan,
    ctx: &Ctx,
    regions: &Regions,
    paper: Option<&[(usize, f64)]>,
) -> Result<(Table, String), ExpError> {
    let grid = *plan.levels.last().expect("levels");
    let all = study(scenarios, plan, grid, ctx, regions)?;
    let params = format!(
        "reference h = k = 1/{}; families: h=k (h = k = 1/n), h (k = 1/{}), k (h = 1/{}); rel_err_T at t = T, rel_err_max = max_n ||e_n||_E / max_n ||u_ref,n||_E over the level's own time steps (all on the grid t = j/{grid}); solver {}",
        plan.n_ref, plan.n_ref, plan.n_ref, plan.solver.name
    );
    // Observed orders within each (scenario, family), against the parameter that varies.
    let order = |v: &dyn Fn(&LevelError) -> f64| -> Vec<f64> {
        all.iter()
            .enumerate()
            .map(|(i, (s, e))| {
                all[..i]
                    .iter()
                    .rev()
                    .find(|(s2, e2)| s2 == s && e2.family == e.family)
                    .map(|(_, p)| {
                        let (hp, hc) = if e.family == "k" {
                            (p.steps, e.steps)
                        } else {
                            (p.n, e.n)
                        };
                        (v(p) / v(e)).ln() / (hc as f64 / hp as f64).ln()
                    })
                    .unwrap_or(f64::NAN)
            })
            .collect()
    };
    let order_t = order(&|e| e.rel_t);
    let order_max = order(&|e| e.rel_max);
    let total = |e: &LevelError| e.regions.iter().sum::<f64>();
    let paper_col: Vec<f64> = all
        .iter()
        .map(|(_, e)| {
            if e.family == "h=k" {
                (paper.unwrap_or_default().iter())
                    .find(|p| p.0 == e.n)
                    .map_or(f64::NAN, |p| p.1)
            } else {
                f64::NAN
            }
        })
        .collect();
    let t = Table::new()
        .str("scenario", all.iter().map(|(s, _)| s.clone()).collect())
        .str(
            "family",
            all.iter().map(|(_, e)| e.family.to_string()).collect(),
        )
        .u64("n", all.iter().map(|(_, e)| e.n as u64).collect())
        .u64("steps", all.iter().map(|(_, e)| e.steps as u64).collect())
        .f64(
            "h_plus_k",
            all.iter()
                .map(|(_, e)| 1.0 / e.n as f64 + 1.0 / e.steps as f64)
                .collect(),
        )
        .f64(
            "rel_err_T_percent",
            all.iter().map(|(_, e)| 100.0 * e.rel_t).collect(),
        )
        .f64("order_T", order_t)
        .f64(
            "rel_err_max_percent",
            all.iter().map(|(_, e)| 100.0 * e.rel_max).collect(),
        )
        .f64("order_max", order_max);
    let t = if paper.is_some() {
        t.f64("paper_percent", paper_col)
    } else {
        t
    };
    let t = t
        .f64(
            &format!("share_{}", regions.near),
            all.iter().map(|(_, e)| e.regions[0] / total(e)).collect(),
        )
        .f64(
            "share_contact_strip",
            all.iter().map(|(_, e)| e.regions[1] / total(e)).collect(),
        )
        .f64(
            "share_rest",
            all.iter().map(|(_, e)| e.regions[2] / total(e)).collect(),
        );
    Ok((t, params))
}
