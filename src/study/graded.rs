//! Nested families of meshes graded towards singular points, with contact and time:
//! the computation behind the book's experiment `graded` and `evhi study convergence`.
//!
//! Every mesh comes from newest-vertex bisection of one structured mesh
//! ([`crate::bisection`]), so every level is nested in the reference and errors are
//! exact by embedding. A uniform family bisects until every triangle's longest edge is
//! at most $D_n = 2\sqrt2/n$; a graded one until it is at most
//! $D_n \min(1, \max(r, D_n^{1/\mu})^{1-\mu})$, with $r$ the distance of the triangle's
//! centroid to the nearest of its points and $\mu$ = [`MU`]. Level $n$ runs with
//! $k = T/n$; the reference continues the first graded family. Beside the error at $T$
//! against the reference: the reference-free increment of each level to the next of
//! its family, at $T$ and its maximum over the level's time grid, and, with a
//! [`Split`], the error by region and the reference's energy near each group of points.

use super::ExpError;
use crate::bisection::{Forest, Leaves, centroid};
use crate::geometry::Geometry;
use crate::mesh::{Dofs, Mesh};
use crate::output::csv::Table;
use crate::output::csv::{col_f64, col_str, read_csv};
use crate::output::plot::{Figure, LogLogChart, both, e2s, keys_within, slope_guides};
use crate::output::plot::{GREY_DARK, okabe_ito as oi};
use crate::scenario::Scenario;
use plotters::prelude::*;
use std::sync::Arc;

/// The grading exponent $\mu$ (below the smallest corner exponent, $\tfrac12$).
pub const MU: f64 = 0.4;

/// Levels of each family and the reference. A graded level has about five
/// times the unknowns of the uniform one with the same $n$, so the graded family
/// stops a level earlier, four times coarser than its reference.
pub struct Plan {
    /// The levels $n$ of the uniform family.
    pub uniform: Vec<usize>,
    /// The levels $n$ of each graded family.
    pub graded: Vec<usize>,
    /// The level $n$ of the reference.
    pub n_ref: usize,
    /// The step solver of every run (the registry's; `newton` in the book's study).
    pub solver: &'static crate::step::SolverEntry,
}

/// The levels of the study: with `quick`, 4 to 32 in both families and a reference
/// at 128; else uniform 4 to 128, graded 4 to 64 and a reference at 256; the default
/// step solver.
pub fn plan(quick: bool) -> Plan {
    if quick {
        Plan {
            uniform: vec![4, 8, 16, 32],
            graded: vec![4, 8, 16, 32],
            n_ref: 128,
            solver: crate::step::DEFAULT_SOLVER_ENTRY,
        }
    } else {
        Plan {
            uniform: vec![4, 8, 16, 32, 64, 128],
            graded: vec![4, 8, 16, 32, 64],
            n_ref: 256,
            solver: crate::step::DEFAULT_SOLVER_ENTRY,
        }
    }
}

fn diagonal(n: usize) -> f64 {
    2.0 * std::f64::consts::SQRT_2 / n as f64
}

/// The largest longest edge allowed at `x` on the mesh of level `n` graded towards
/// `points` ([`crate::bisection::graded_size`] with $\mu$ = [`MU`]).
pub fn graded_size(n: usize, x: [f64; 2], points: &[[f64; 2]]) -> f64 {
    crate::bisection::graded_size(diagonal(n), x, points, MU)
}

/// Refines `from` to the mesh of level `n` on `geo` graded towards `points` (uniform
/// if none), lengths in units of the shorter side (1 on the paper's scene).
fn level(
    forest: &mut Forest,
    geo: &Geometry,
    from: &Leaves,
    n: usize,
    points: &[[f64; 2]],
) -> Leaves {
    // A hair of slack so that a triangle exactly at the bound is not cut.
    let slack = 1.0 + 1e-12;
    let unit = geo.width.min(geo.height);
    let d = crate::bisection::cell_diagonal(geo, n) / unit;
    if !points.is_empty() {
        let pts: Vec<[f64; 2]> = points.iter().map(|p| [p[0] / unit, p[1] / unit]).collect();
        forest.refine(from, |f, t| {
            let c = centroid(f, t);
            f.diameter(t) / unit
                > slack * crate::bisection::graded_size(d, [c[0] / unit, c[1] / unit], &pts, MU)
        })
    } else {
        forest.refine(from, |f, t| f.diameter(t) / unit > slack * d)
    }
}

/// One level's result.
struct Row {
    family: String,
    load: String,
    n: usize,
    dofs: usize,
    triangles: usize,
    min_edge: f64,
    rel_err: f64,
    /// Increment to the next level of the family at T, its maximum over the level's
    /// time grid and where that maximum is (NaN at a family's last level).
    inc_t: f64,
    inc_max: f64,
    t_inc_max: f64,
    /// With a [`Split`]: the squared error at T by region (each group, then the rest)
    /// over the reference's squared norm, and the level's longest edge at each
    /// group's first point.
    regions: Vec<f64>,
    h_at: Vec<f64>,
}

/// Where [`compute`] measures the error apart: within `radius` of each group of
/// points (a triangle by its centroid, the first group that claims it), and the rest.
/// The reference's own energy within radii `radius`, `radius`/2, ... (`halvings`
/// of them) of each group gives the strength of its singular field.
pub struct Split<'a> {
    /// Each group: its name in the tables, its points, and the exponent $\lambda$ its
    /// singular field $r^\lambda$ is expected to have (the strengths divide by
    /// $\rho^\lambda$).
    pub groups: &'a [(&'a str, &'a [[f64; 2]], f64)],
    /// The radius of each group's region, and the largest radius of the energy table.
    pub radius: f64,
    /// How many times the energy table halves the radius.
    pub halvings: usize,
}

impl Split<'_> {
    fn of(&self, radius: f64) -> impl Fn([f64; 2]) -> usize + '_ {
        move |c: [f64; 2]| {
            (self.groups.iter())
                .position(|(_, pts, _)| {
                    pts.iter()
                        .any(|p| (c[0] - p[0]).hypot(c[1] - p[1]) < radius)
                })
                .unwrap_or(self.groups.len())
        }
    }
}

/// The longest edge of the triangles of `mesh` that have a vertex at `p`.
fn edge_at(mesh: &Mesh, p: [f64; 2]) -> f64 {
    let at = |k: usize| (mesh.nodes[k][0] - p[0]).hypot(mesh.nodes[k][1] - p[1]) < 1e-12;
    (mesh.triangles.iter())
        .filter(|t| t.iter().any(|&k| at(k)))
        .flat_map(|t| {
            (0..3).map(move |i| {
                let (a, b) = (mesh.nodes[t[i]], mesh.nodes[t[(i + 1) % 3]]);
                (a[0] - b[0]).hypot(a[1] - b[1])
            })
        })
        .fold(f64::NAN, f64::max)
}

/// What [`compute`] returns: the table of `graded_convergence.csv`, the reference's
/// unknowns, and with a [`Split`] the error by region (`graded_regions.csv`) and the
/// reference's energy near each group (`graded_corner_energy.csv`).
pub struct Graded {
    /// The table of `graded_convergence.csv`.
    pub table: Table,
    /// The reference's unknowns (degrees of freedom).
    pub ref_dofs: usize,
    /// With a [`Split`]: the tables of `graded_regions.csv` and
    /// `graded_corner_energy.csv`, in this order.
    pub split: Option<(Table, Table)>,
}

/// The steps of level `n`: $k = T/n$, or one step for a steady problem.
fn steps_of(scns: &[Scenario], n: usize) -> usize {
    if scns[0].problem == crate::scenario::Problem::Steady {
        1
    } else {
        n
    }
}

/// The fields (`[load][step]`, step 0 included; empty where `keep(step)` is false)
/// on `mesh` (level `n`) with `steps` steps.
fn solve_steps(
    scns: &[Scenario],
    mesh: &Arc<Mesh>,
    n: usize,
    steps: usize,
    solver: &crate::step::SolverEntry,
    keep: impl Fn(usize) -> bool,
) -> Result<Vec<Vec<Vec<f64>>>, ExpError> {
    let mut fields = vec![vec![vec![]; steps + 1]; scns.len()];
    let Some(first) = scns.first() else {
        return Ok(fields);
    };
    let settings = crate::simulation::RunSettings::general(n, steps);
    let sim = crate::simulation::Simulation::on_mesh(first.clone(), settings, mesh.clone())?;
    super::runs::run_batch_with(&sim, scns, solver, &mut |i, step, _, u| {
        if keep(step) {
            fields[i][step] = u.to_vec();
        }
    })?;
    Ok(fields)
}

/// The fields at $T$ on the reference mesh. With proportional damping by the reduced
/// loop: one factorisation of $B$ serves every load and every step, and the field
/// is formed (and the step certified on the full system) at $T$ only, where the
/// general loop would sweep the factor of $A + kB$ at every step. The two loops agree
/// to rounding (`data/paths.csv`: at most $5\cdot10^{-10}$ relative in the field at
/// $T$ on the paper's scene at $h = k = 1/512$).
pub(super) fn reference_at_t(
    scns: &[Scenario],
    mesh: &Arc<Mesh>,
    n: usize,
    steps: usize,
    solver: &crate::step::SolverEntry,
) -> Result<Vec<Vec<f64>>, ExpError> {
    let settings = crate::simulation::RunSettings::general(n, steps);
    let sim = crate::simulation::Simulation::on_mesh(scns[0].clone(), settings, mesh.clone())?;
    let disc = sim.discretisation();
    if crate::reduced::proportional(&scns[0], &disc).is_none() {
        return Ok(solve_steps(scns, mesh, n, steps, solver, |s| s == steps)?
            .into_iter()
            .map(|mut fields| fields.pop().expect("the last step"))
            .collect());
    }
    let mut timings = crate::scheme::Timings::default();
    let op = sim.reduced_operator(&disc, &mut timings)?;
    let mut out = vec![];
    for scn in scns {
        let load = op.load_of(scn);
        let mut at_t = vec![];
        op.march(
            scn,
            &load,
            steps,
            solver.build().as_mut(),
            crate::scheme::CERTIFICATE_TOL,
            &|s| s == steps,
            &mut timings,
            &mut |s| {
                if let Some(u) = s.field {
                    at_t = u.to_vec();
                }
            },
        )?;
        out.push(at_t);
    }
    Ok(out)
}

/// One level of a family, solved.
struct Level {
    n: usize,
    steps: usize,
    leaves: Leaves,
    mesh: Arc<Mesh>,
    dofs: Dofs,
    fields: Vec<Vec<Vec<f64>>>,
}

/// The relative energy increment from `coarse` to `fine` (the next level of its
/// family) for each load: at T, its maximum over the coarse time grid, and where.
/// The embedding and the norm geometry serve every load.
fn increments(
    forest: &Forest,
    coarse: &Level,
    fine: &Level,
    g: &crate::material::Isotropic,
    t_end: f64,
) -> Vec<(f64, f64, f64)> {
    let interp = forest.interpolation(&coarse.leaves, &fine.mesh);
    let geo = crate::norms::NormGeometry::new(&fine.mesh);
    (0..fine.fields.len())
        .map(|i| increments_of(&interp, &geo, coarse, fine, i, g, t_end))
        .collect()
}

fn increments_of(
    interp: &crate::mesh::Interpolation,
    geo: &crate::norms::NormGeometry,
    coarse: &Level,
    fine: &Level,
    i: usize,
    g: &crate::material::Isotropic,
    t_end: f64,
) -> (f64, f64, f64) {
    let ratio = fine.steps / coarse.steps;
    let (mut at_t, mut max, mut t_max) = (f64::NAN, 0.0, f64::NAN);
    for j in 1..=coarse.steps {
        let uf = fine.dofs.expand(&fine.fields[i][ratio * j]);
        let uc = interp.apply(&coarse.dofs.expand(&coarse.fields[i][j]));
        let diff: Vec<[f64; 2]> = uf
            .iter()
            .zip(&uc)
            .map(|(a, b)| [a[0] - b[0], a[1] - b[1]])
            .collect();
        let rel = (geo.norms(&fine.mesh, g, &diff).energy_sq
            / geo.norms(&fine.mesh, g, &uf).energy_sq)
            .sqrt();
        if rel > max {
            (max, t_max) = (rel, j as f64 * t_end / coarse.steps as f64);
        }
        at_t = rel;
    }
    (at_t, max, t_max)
}

/// The units of progress of [`compute`]: one per level and one for the reference.
pub fn units(plan: &Plan, families: usize) -> usize {
    plan.uniform.len() + (families.saturating_sub(1)) * plan.graded.len() + 1
}

/// The unknowns and the contact nodes of the first two levels, `n0` and `2 n0`, of a
/// family graded towards `points` from the structured mesh of `n0` on `geo`, built as
/// [`compute`] builds them (a family without points is uniform): what `evhi study
/// convergence` carries on to its finer levels to say what a plan will cost before any
/// work.
pub fn first_sizes(
    geo: &Geometry,
    n0: usize,
    points: &[[f64; 2]],
) -> Result<[(usize, usize); 2], ExpError> {
    let (mut forest, root) = Forest::new(n0, geo)?;
    let first = level(&mut forest, geo, &root, n0, points);
    let second = level(&mut forest, geo, &first, 2 * n0, points);
    let sizes = |leaves: &Leaves, n: usize| {
        let mesh = forest.mesh(leaves, n);
        (Dofs::new(&mesh, true).count, mesh.contact.len())
    };
    Ok([sizes(&first, n0), sizes(&second, 2 * n0)])
}

/// The convergence study of the scenarios `scns` (one batch: they share the geometry
/// and the step matrix) on nested families of bisection meshes of their scene: the
/// first family uniform on `plan.uniform`, each other graded towards its points on
/// `plan.graded`, the reference the first graded family's finest level refined on to
/// `plan.n_ref` towards `ref_points`; $k = T/n$ on every level. Returns the table of
/// `graded_convergence.csv` and the reference's unknowns. `log` reports each level
/// (one unit of progress each, [`units`]).
pub fn compute(
    scns: &[Scenario],
    families_in: &[(String, Vec<[f64; 2]>)],
    plan: &Plan,
    ref_points: &[[f64; 2]],
    split: Option<&Split>,
    log: &dyn Fn(&str),
) -> Result<Graded, ExpError> {
    let geo = &scns[0].geometry;
    let t_end = scns[0].t_end;
    let levels_of = |f: usize| if f == 0 { &plan.uniform } else { &plan.graded };
    let (mut forest, root) = Forest::new(plan.uniform[0], geo)?;
    // Meshes first (the forest grows), then the runs.
    let mut families: Vec<(String, Vec<(usize, Leaves)>)> = vec![];
    for (f, (family, points)) in families_in.iter().enumerate() {
        let mut prev = root.clone();
        let mut list = vec![];
        for &n in levels_of(f) {
            prev = level(&mut forest, geo, &prev, n, points);
            list.push((n, prev.clone()));
        }
        families.push((family.clone(), list));
    }
    // The reference continues the first graded family (the uniform one if none).
    let ri = 1.min(families.len() - 1);
    let mut prev = families[ri].1.last().expect("levels").1.clone();
    let mut n = *levels_of(ri).last().expect("levels");
    while n < plan.n_ref {
        n *= 2;
        prev = level(&mut forest, geo, &prev, n, ref_points);
    }
    let ref_leaves = prev;
    let ref_mesh = Arc::new(forest.mesh(&ref_leaves, plan.n_ref));
    let clock = std::time::Instant::now();
    let ref_steps = steps_of(scns, plan.n_ref);
    let reference = reference_at_t(scns, &ref_mesh, plan.n_ref, ref_steps, plan.solver)
        .map_err(|e| e.at(format!("the graded reference, level n = {}", plan.n_ref)))?;
    let ref_dofs = Dofs::new(&ref_mesh, true);
    log(&format!(
        "graded reference: {} dofs, k = 1/{} ({:.1} s)",
        ref_dofs.count,
        plan.n_ref,
        clock.elapsed().as_secs_f64()
    ));
    let g = scns[0].elasticity();
    let ref_geo = crate::norms::NormGeometry::new(&ref_mesh);
    let ref_fields: Vec<Vec<[f64; 2]>> = reference.iter().map(|u| ref_dofs.expand(u)).collect();
    let ref_norms: Vec<f64> = ref_fields
        .iter()
        .map(|u| ref_geo.norms(&ref_mesh, &g, u).energy_sq)
        .collect();
    // Errors at T are relative to the reference there: zero (the loads vanish at T)
    // leaves every one undefined, refused by name rather than written as NaN.
    if let Some(i) = ref_norms.iter().position(|&r| r.is_nan() || r <= 0.0) {
        return Err(crate::error::InputError::field(
            "scenario",
            &scns[i].name,
            "a scene whose solution at t = T is not zero: the reference's energy norm \
             there is 0 (the loads vanish at T), so no relative error at T is defined; \
             take a load history that does not end at zero",
        )
        .into());
    }
    let mut rows = vec![];
    for (family, list) in &families {
        let mut solved: Vec<Level> = vec![];
        for (n, leaves) in list {
            let clock = std::time::Instant::now();
            let mesh = Arc::new(forest.mesh(leaves, *n));
            let dofs = Dofs::new(&mesh, true);
            let steps = steps_of(scns, *n);
            let fields = solve_steps(scns, &mesh, *n, steps, plan.solver, |_| true)
                .map_err(|e| e.at(format!("the {family} family, level n = {n}")))?;
            solved.push(Level {
                n: *n,
                steps,
                leaves: leaves.clone(),
                mesh,
                dofs,
                fields,
            });
            log(&format!(
                "{family} level {n}: {} dofs ({:.1} s)",
                solved.last().expect("pushed").dofs.count,
                clock.elapsed().as_secs_f64()
            ));
        }
        for (l, lev) in solved.iter().enumerate() {
            let interp = forest.interpolation(&lev.leaves, &ref_mesh);
            let min_edge = lev
                .leaves
                .0
                .iter()
                .map(|&t| forest.diameter(t))
                .fold(f64::INFINITY, f64::min);
            let inc = solved
                .get(l + 1)
                .map(|next| increments(&forest, lev, next, &g, t_end));
            for i in 0..scns.len() {
                let pu = interp.apply(&lev.dofs.expand(&lev.fields[i][lev.steps]));
                let diff: Vec<[f64; 2]> = ref_fields[i]
                    .iter()
                    .zip(&pu)
                    .map(|(a, b)| [a[0] - b[0], a[1] - b[1]])
                    .collect();
                let e = ref_geo.norms(&ref_mesh, &g, &diff).energy_sq;
                let (regions, h_at) = match split {
                    Some(sp) => {
                        let mut r = vec![0.0; sp.groups.len() + 1];
                        ref_geo.energy_by_region(&ref_mesh, &g, &diff, sp.of(sp.radius), &mut r);
                        (
                            r.iter().map(|x| x / ref_norms[i]).collect(),
                            (sp.groups.iter())
                                .map(|(_, pts, _)| edge_at(&lev.mesh, pts[0]))
                                .collect(),
                        )
                    }
                    None => (vec![], vec![]),
                };
                let (inc_t, inc_max, t_inc_max) = inc
                    .as_ref()
                    .map_or((f64::NAN, f64::NAN, f64::NAN), |v| v[i]);
                rows.push(Row {
                    family: family.clone(),
                    load: scns[i].name.clone(),
                    n: lev.n,
                    dofs: lev.dofs.count,
                    triangles: lev.mesh.triangles.len(),
                    min_edge,
                    rel_err: (e / ref_norms[i]).sqrt(),
                    inc_t,
                    inc_max,
                    t_inc_max,
                    regions,
                    h_at,
                });
            }
        }
    }
    rows.sort_by(|a, b| {
        (a.load.as_str(), a.family.as_str(), a.n).cmp(&(b.load.as_str(), b.family.as_str(), b.n))
    });
    let order_of = |v: &dyn Fn(&Row) -> f64| -> Vec<f64> {
        rows.iter()
            .enumerate()
            .map(|(i, r)| match i.checked_sub(1).map(|j| &rows[j]) {
                Some(p) if p.load == r.load && p.family == r.family => {
                    -2.0 * (v(r) / v(p)).ln() / (r.dofs as f64 / p.dofs as f64).ln()
                }
                _ => f64::NAN,
            })
            .collect()
    };
    let order = order_of(&|r| r.rel_err);
    let order_inc = order_of(&|r| r.inc_t);
    let order_inc_max = order_of(&|r| r.inc_max);
    let t = Table::new()
        .str("load", rows.iter().map(|r| r.load.clone()).collect())
        .str("family", rows.iter().map(|r| r.family.clone()).collect())
        .u64("n", rows.iter().map(|r| r.n as u64).collect())
        .u64("dofs", rows.iter().map(|r| r.dofs as u64).collect())
        .u64(
            "triangles",
            rows.iter().map(|r| r.triangles as u64).collect(),
        )
        .f64(
            "min_longest_edge",
            rows.iter().map(|r| r.min_edge).collect(),
        )
        .f64(
            "rel_err_T_percent",
            rows.iter().map(|r| 100.0 * r.rel_err).collect(),
        )
        .f64("order_dofs", order)
        .f64(
            "increment_T_percent",
            rows.iter().map(|r| 100.0 * r.inc_t).collect(),
        )
        .f64("order_increment_dofs", order_inc)
        .f64(
            "increment_max_percent",
            rows.iter().map(|r| 100.0 * r.inc_max).collect(),
        )
        .f64("order_increment_max_dofs", order_inc_max)
        .f64(
            "t_of_increment_max",
            rows.iter().map(|r| r.t_inc_max).collect(),
        );
    let split = split.map(|sp| {
        let regions = region_table(&rows, sp);
        let corner = corner_table(sp, scns, &ref_mesh, &ref_geo, &g, &ref_fields, &ref_norms);
        (regions, corner)
    });
    Ok(Graded {
        table: t,
        ref_dofs: ref_dofs.count,
        split,
    })
}

/// `graded_regions.csv`: per load, family and level, the error at T within the
/// split's radius of each group and in the rest (percent of the reference's norm;
/// their squares add up to `rel_err_T_percent`'s), the level's longest edge at the
/// group, the order of each part in that edge (the rest's in $N^{-1/2}$), and the
/// strength: the part over (edge)$^\lambda$ with the group's exponent $\lambda$, and the
/// part's share of the squared error.
fn region_table(rows: &[Row], sp: &Split) -> Table {
    let mut t = Table::new()
        .str("load", rows.iter().map(|r| r.load.clone()).collect())
        .str("family", rows.iter().map(|r| r.family.clone()).collect())
        .u64("n", rows.iter().map(|r| r.n as u64).collect())
        .u64("dofs", rows.iter().map(|r| r.dofs as u64).collect());
    let prev = |i: usize| -> Option<&Row> {
        let p = &rows[i.checked_sub(1)?];
        (p.load == rows[i].load && p.family == rows[i].family).then_some(p)
    };
    let total = |r: &Row| r.regions.iter().sum::<f64>();
    for (gi, (name, _, lambda)) in sp.groups.iter().enumerate() {
        let key = name.replace(' ', "_");
        let err = |r: &Row| r.regions[gi].sqrt();
        t = t
            .f64(
                &format!("h_{key}"),
                rows.iter().map(|r| r.h_at[gi]).collect(),
            )
            .f64(
                &format!("err_{key}_percent"),
                rows.iter().map(|r| 100.0 * err(r)).collect(),
            )
            .f64(
                &format!("order_{key}"),
                (0..rows.len())
                    .map(|i| {
                        prev(i).map_or(f64::NAN, |p| {
                            (err(&rows[i]) / err(p)).ln() / (rows[i].h_at[gi] / p.h_at[gi]).ln()
                        })
                    })
                    .collect(),
            )
            .f64(
                &format!("strength_{key}"),
                rows.iter()
                    .map(|r| err(r) / r.h_at[gi].powf(*lambda))
                    .collect(),
            )
            .f64(
                &format!("share_{key}"),
                rows.iter().map(|r| r.regions[gi] / total(r)).collect(),
            );
    }
    let rest = |r: &Row| r.regions[sp.groups.len()].sqrt();
    t.f64(
        "err_rest_percent",
        rows.iter().map(|r| 100.0 * rest(r)).collect(),
    )
    .f64(
        "order_rest_dofs",
        (0..rows.len())
            .map(|i| {
                prev(i).map_or(f64::NAN, |p| {
                    -2.0 * (rest(&rows[i]) / rest(p)).ln()
                        / (rows[i].dofs as f64 / p.dofs as f64).ln()
                })
            })
            .collect(),
    )
}

/// `graded_corner_energy.csv`: the share of the reference's energy at T within
/// $\rho$ of each group's points, for $\rho$ = radius, radius/2, ...; the local
/// exponent $\ln(E_{2\rho}/E_\rho) / (2\ln 2)$, which tends to $\lambda$ when a field
/// $r^\lambda$ holds the energy there (a smooth field gives 1); and the strength
/// $\sqrt{E_\rho/E}/\rho^\lambda$, constant in that case.
fn corner_table(
    sp: &Split,
    scns: &[Scenario],
    mesh: &Mesh,
    geo: &crate::norms::NormGeometry,
    g: &crate::material::Isotropic,
    fields: &[Vec<[f64; 2]>],
    norms: &[f64],
) -> Table {
    let (mut load, mut group, mut rho, mut share, mut local, mut strength) =
        (vec![], vec![], vec![], vec![], vec![], vec![]);
    for (i, scn) in scns.iter().enumerate() {
        for (name, pts, lambda) in sp.groups {
            let mut last = f64::NAN;
            for h in 0..=sp.halvings {
                let r = sp.radius / f64::powi(2.0, h as i32);
                let mut e = [0.0; 2];
                let inside = |c: [f64; 2]| {
                    usize::from(!pts.iter().any(|p| (c[0] - p[0]).hypot(c[1] - p[1]) < r))
                };
                geo.energy_by_region(mesh, g, &fields[i], inside, &mut e);
                let s = e[0] / norms[i];
                load.push(scn.name.clone());
                group.push(name.to_string());
                rho.push(r);
                share.push(s);
                local.push((last / s).ln() / (2.0 * std::f64::consts::LN_2));
                strength.push(s.sqrt() / r.powf(*lambda));
                last = s;
            }
        }
    }
    Table::new()
        .str("load", load)
        .str("points", group)
        .f64("rho", rho)
        .f64("energy_share", share)
        .f64("local_exponent", local)
        .f64("strength", strength)
}

/// A series: label, (unknowns, value) points, colour, its family's index and its
/// load's.
type Series = (String, Vec<(f64, f64)>, RGBColor, usize, usize);

/// Two panels: the error at T against the reference, and the largest increment
/// over time to the next level (no reference).
struct GradedFig {
    panels: [(String, String, Vec<Series>); 2],
}

/// Draws the table at `path` (of [`compute`]) into `dir` as `stem`.png and .svg: a
/// colour and a marker per family, a line style per load (solid and filled markers
/// for the first of `loads`, dashed and open for the second), one legend under both
/// panels.
pub fn draw(
    dir: &std::path::Path,
    stem: &str,
    path: &std::path::Path,
    loads: &[String],
    families: &[String],
) -> Result<(), ExpError> {
    let df = read_csv(path)?;
    let (load, family) = (col_str(&df, "load")?, col_str(&df, "family")?);
    let dofs = col_f64(&df, "dofs")?;
    // Colour-blind-safe (Okabe–Ito), one per family, which its marker says too.
    let colours = [oi::BLACK, oi::BLUE, oi::VERMILLION, oi::BLUISH_GREEN];
    let panel = |col: &str| -> Result<Vec<Series>, ExpError> {
        let v = col_f64(&df, col)?;
        let mut series = vec![];
        for (li, l) in loads.iter().enumerate() {
            for (fi, f) in families.iter().enumerate() {
                let pts: Vec<(f64, f64)> = (0..load.len())
                    .filter(|&i| load[i] == *l && family[i] == *f && v[i].is_finite())
                    .map(|i| (dofs[i], v[i]))
                    .collect();
                series.push((format!("{l}, {f}"), pts, colours[fi % 4], fi, li));
            }
        }
        Ok(series)
    };
    let fig = GradedFig {
        panels: [
            (
                "(a) error at T against the graded reference".into(),
                "relative energy error at T, %".into(),
                panel("rel_err_T_percent")?,
            ),
            (
                "(b) largest increment to the next level".into(),
                "max over t of ‖u_n − u_2n‖ / ‖u_2n‖, %".into(),
                panel("increment_max_percent")?,
            ),
        ],
    };
    Ok(both(
        dir,
        stem,
        (1500, 760 + key_height(fig.panels[0].2.len())),
        &fig,
    )?)
}

/// The legend's columns and the height of one of its rows, pixels.
const KEY: (usize, u32) = (4, 38);

/// The font sizes (pixels) of the panels' captions, tick labels, axis descriptions and
/// the legend: the figure is 1500 px wide and the book's column about 750, so each
/// reads at half its size there (no less than 13 px).
const FONTS: (u32, u32, u32, u32) = (28, 26, 26, 26);

/// The legend's row and column of entry `i` of `series` series and the two guides:
/// the series row by row ([`KEY`]`.0` a row, one load a row when there are four
/// families), the guides on a row of their own below.
fn key_cell(i: usize, series: usize) -> (usize, usize) {
    if i < series {
        (i / KEY.0, i % KEY.0)
    } else {
        (series.div_ceil(KEY.0), i - series)
    }
}

/// The height of the legend under the panels for `series` series and the two guides.
fn key_height(series: usize) -> u32 {
    (series.div_ceil(KEY.0) as u32 + 1) * KEY.1 + 16
}

/// The outline of family `f`'s marker: square (uniform), octagon (graded towards all
/// four points), triangle (clamp ends), diamond (top corners); 12 to 16 px across.
fn shape(f: usize) -> Vec<(i32, i32)> {
    let outline = match f {
        0 => vec![(-6, -6), (6, -6), (6, 6), (-6, 6)],
        1 => vec![
            (-3, -7),
            (3, -7),
            (7, -3),
            (7, 3),
            (3, 7),
            (-3, 7),
            (-7, 3),
            (-7, -3),
        ],
        2 => vec![(0, -8), (8, 6), (-8, 6)],
        _ => vec![(0, -8), (8, 0), (0, 8), (-8, 0)],
    };
    // Half as large again, to read at the column's half scale.
    outline
        .into_iter()
        .map(|(x, y)| (x * 3 / 2, y * 3 / 2))
        .collect()
}

impl Figure for GradedFig {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        let (w, h) = root.dim_in_pixel();
        let (charts, key) = root.split_vertically(h - key_height(self.panels[0].2.len()));
        let areas = charts.split_horizontally(w / 2);
        let guides = [
            (0.5, "N^(-1/2): order 1 in h".to_string()),
            (0.25, "N^(-1/4): order 1/2 in h".to_string()),
        ];
        for (area, (title, ydesc, series)) in [areas.0, areas.1].iter().zip(&self.panels) {
            let pts: Vec<(f64, f64)> = series.iter().flat_map(|s| s.1.clone()).collect();
            let ((xmin, xmax), (ymin, ymax)) = crate::output::plot::extent(&pts);
            // Room below the data for the whole of each slope guide.
            let guides_low = series
                .get(1)
                .and_then(|s| s.1.first())
                .map_or(f64::INFINITY, |&start| {
                    crate::output::plot::slope_guides_low(&[0.5, 0.25], start, xmax, 0.45)
                });
            let (xr, yr) = (
                (xmin / 1.5, xmax * 1.5),
                ((ymin / 2.0).min(guides_low / 1.3), ymax * 2.0),
            );
            // 1, 2 and 5 of each decade over up to three decades, else the decades.
            let keys = if xr.1 / xr.0 <= 1e3 {
                crate::output::plot::one_two_five(xr, 0..=7)
            } else {
                keys_within(xr, (1..=7).map(|e| 10f64.powi(e)))
            };
            let ykeys = keys_within(yr, [0.2, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0]);
            let mut chart = LogLogChart {
                caption: (title, FONTS.0),
                label_areas: (76, 104),
                margin: 28,
                desc: ("unknowns N", ydesc),
                format: (
                    Some(&crate::output::plot::plain),
                    Some(&crate::output::plot::plain),
                ),
                fonts: (FONTS.1, Some(FONTS.2)),
            }
            .build(
                area,
                (xr.0..xr.1).log_scale().with_key_points(keys),
                (yr.0..yr.1).log_scale().with_key_points(ykeys),
            )?;
            for (_, s, c, f, l) in series {
                let (c, f) = (*c, *f);
                if *l == 0 {
                    chart
                        .draw_series(LineSeries::new(s.clone(), c.stroke_width(3)))
                        .map_err(e2s)?;
                } else {
                    chart
                        .draw_series(DashedLineSeries::new(s.clone(), 10, 6, c.stroke_width(2)))
                        .map_err(e2s)?;
                }
                chart
                    .draw_series(
                        s.iter()
                            .map(|&p| EmptyElement::at(p) + Polygon::new(shape(f), c.filled())),
                    )
                    .map_err(e2s)?;
                if *l > 0 {
                    chart
                        .draw_series(
                            s.iter().map(|&p| {
                                EmptyElement::at(p) + Polygon::new(hole(f), WHITE.filled())
                            }),
                        )
                        .map_err(e2s)?;
                }
            }
            // Slope guides N^(-1/2) (order 1 in h) and N^(-1/4) (order 1/2), from the
            // first graded point of the first load, below the data.
            if let Some(&start) = series.get(1).and_then(|s| s.1.first()) {
                slope_guides(
                    &mut chart,
                    &guides,
                    &crate::output::plot::DISTINCT_DASHES,
                    start,
                    xmax,
                    0.45,
                )?;
            }
        }
        // One legend for both panels, under them.
        let (kw, _) = key.dim_in_pixel();
        let col = kw as i32 / KEY.0 as i32;
        let font = TextStyle::from((crate::output::plot::FONT, FONTS.3).into_font());
        let grey = GREY_DARK;
        let entries = self.panels[0].2.len() + guides.len();
        for i in 0..entries {
            let (row, column) = key_cell(i, self.panels[0].2.len());
            let (x, y) = (20 + col * column as i32, 14 + KEY.1 as i32 * row as i32);
            let label = match self.panels[0].2.get(i) {
                Some((label, _, c, f, l)) => {
                    let (c, f) = (*c, *f);
                    if *l == 0 {
                        key.draw(&PathElement::new(
                            vec![(x, y), (x + 36, y)],
                            c.stroke_width(3),
                        ))
                        .map_err(e2s)?;
                    } else {
                        for a in [0, 16] {
                            key.draw(&PathElement::new(
                                vec![(x + a, y), (x + a + 10, y)],
                                c.stroke_width(2),
                            ))
                            .map_err(e2s)?;
                        }
                    }
                    key.draw(&(EmptyElement::at((x + 18, y)) + Polygon::new(shape(f), c.filled())))
                        .map_err(e2s)?;
                    if *l > 0 {
                        key.draw(
                            &(EmptyElement::at((x + 18, y))
                                + Polygon::new(hole(f), WHITE.filled())),
                        )
                        .map_err(e2s)?;
                    }
                    label.clone()
                }
                None => {
                    let g = i - self.panels[0].2.len();
                    let (dash, gap) = crate::output::plot::DISTINCT_DASHES[g];
                    key.draw(&crate::output::plot::dashed_legend(
                        (x, y),
                        dash,
                        gap,
                        grey.stroke_width(2),
                    ))
                    .map_err(e2s)?;
                    guides[g].1.clone()
                }
            };
            key.draw(&Text::new(
                label,
                (x + 46, y),
                font.clone().pos(plotters::style::text_anchor::Pos::new(
                    plotters::style::text_anchor::HPos::Left,
                    plotters::style::text_anchor::VPos::Center,
                )),
            ))
            .map_err(e2s)?;
        }
        Ok(())
    }
}

/// The white inside of family `f`'s open marker (the second load's): its shape at
/// half size.
fn hole(f: usize) -> Vec<(i32, i32)> {
    shape(f).into_iter().map(|(x, y)| (x / 2, y / 2)).collect()
}
