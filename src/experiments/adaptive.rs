//! Meshes that adapt themselves, against the uniform and graded families, on the
//! paper's scene with contact and time.
//!
//! Every mesh is a set of leaves of one newest-vertex bisection forest grown from the
//! structured mesh with $n_0 = 4$ ([`evhi::bisection`]):
//! - `uniform`: every longest edge at most $D_n = 2\sqrt2/n$;
//! - `graded`: at most $D_n\min(1, \max(r, D_n^{1/\mu})^{1-\mu})$, $r$ the distance to the
//!   nearest clamp end or top corner, $\mu = 0.4$ (as the experiment `graded`);
//! - `adaptive`: the levels of [`evhi::adapt`] with its defaults ($\theta = 0.5$, each
//!   triangle's indicator at its maximum over the steps), from $n_0 = 4$ until the next
//!   mesh would pass the budget. It is told nothing of the scene's singular points.
//!
//! All runs take the same $N$ steps as the reference, so the errors are those of the
//! space discretisation alone. The reference is the graded mesh of level $n_{ref}$,
//! refined further wherever an adaptive mesh is finer
//! ([`evhi::bisection::Forest::refine_to_contain`]), so every mesh embeds in it exactly.
//! The error of a level is $\|u_{ref}(t_j) - u(t_j)\|_E / \|u_{ref}(t_j)\|_E$ at $T$
//! (`err_T`) and at its largest over $t_j = jT/N$ (`err_max`); `estimator` is
//! [`evhi::adapt`]'s estimated relative error, and `efficiency` = estimator / err_max.

use super::{Ctx, ExpError};
use evhi::adapt::{AdaptObserver, AdaptSettings, Aggregate, Solved, solve_estimating};
use evhi::bisection::{Forest, Leaves, centroid};
use evhi::geometry::{Geometry, PAPER_SINGULAR};
use evhi::mesh::{Dofs, Mesh};
use evhi::output::csv::{Table, col_f64, col_str, read_csv};
use evhi::output::plot::{Figure, LogLogChart, both, e2s, keys_within, okabe_ito as oi};
use evhi::scenario::Scenario;
use evhi::simulation::{Observer, RunSettings, Simulation};
use plotters::prelude::*;
use std::sync::Arc;

/// The scenes, each adapted on its own.
pub const LOADS: [&str; 2] = ["figure", "literal"];

/// The families, in the table's and the figure's order.
pub const FAMILIES: [&str; 4] = ["uniform", "graded", "adaptive", "adaptive (time mean)"];

/// The figure draws the adaptive mesh of the last level with at most these unknowns.
const DRAWN_DOFS: usize = 3000;

/// The grading exponent of the graded family.
const MU: f64 = 0.4;

pub(super) struct Plan {
    pub(super) steps: usize,
    uniform: Vec<usize>,
    graded: Vec<usize>,
    n_ref: usize,
    pub(super) max_dofs: usize,
}

pub(super) fn plan(quick: bool) -> Plan {
    if quick {
        Plan {
            steps: 8,
            uniform: vec![4, 8, 16],
            graded: vec![4, 8, 16],
            n_ref: 64,
            max_dofs: 1500,
        }
    } else {
        Plan {
            steps: 32,
            uniform: vec![4, 8, 16, 32, 64, 128],
            graded: vec![4, 8, 16, 32, 64],
            n_ref: 256,
            max_dofs: 24000,
        }
    }
}

/// Refines `from` until every longest edge is within level `n`'s bound, graded
/// towards `points` (uniform if none).
pub(super) fn level(
    forest: &mut Forest,
    geo: &Geometry,
    from: &Leaves,
    n: usize,
    points: &[[f64; 2]],
) -> Leaves {
    let slack = 1.0 + 1e-12;
    let d = evhi::bisection::cell_diagonal(geo, n);
    forest.refine(from, |f, t| {
        let bound = if points.is_empty() {
            d
        } else {
            evhi::bisection::graded_size(d, centroid(f, t), points, MU)
        };
        f.diameter(t) > slack * bound
    })
}

/// One solved level of a family for one scene.
pub(super) struct Lev {
    pub(super) family: &'static str,
    pub(super) scene: usize,
    pub(super) level: usize,
    pub(super) leaves: Leaves,
    pub(super) dofs: usize,
    /// Fields at $t_0, \dots, t_N$ (free dofs).
    pub(super) fields: Vec<Vec<f64>>,
    pub(super) estimate: f64,
    pub(super) wall_s: f64,
}

/// A row of `adaptive_convergence.csv`: a level of a family on a scene, its errors
/// against the scene's reference and its wall time.
pub(super) struct Row {
    pub(super) scenario: String,
    pub(super) family: &'static str,
    pub(super) level: usize,
    pub(super) dofs: usize,
    pub(super) steps: usize,
    pub(super) err_t: f64,
    pub(super) err_max: f64,
    pub(super) estimate: f64,
    pub(super) wall_s: f64,
}

/// Keeps every step's field.
pub(super) struct Keep;
impl AdaptObserver for Keep {
    fn keep_fields(&self) -> bool {
        true
    }
}

/// Keeps every adaptive level.
pub(super) struct Collect {
    pub(super) family: &'static str,
    pub(super) scene: usize,
    pub(super) levels: Vec<Lev>,
}
impl AdaptObserver for Collect {
    fn keep_fields(&self) -> bool {
        true
    }
    fn level_done(&mut self, s: &Solved) {
        self.levels.push(Lev {
            family: self.family,
            scene: self.scene,
            level: s.level.level,
            leaves: s.leaves.clone(),
            dofs: s.level.dofs,
            fields: s.fields.to_vec(),
            estimate: s.level.estimate,
            wall_s: s.level.wall_s,
        });
    }
}

/// The reference's fields at every step.
pub(super) struct Fields(pub(super) Vec<Vec<f64>>, pub(super) usize);
impl Observer for Fields {
    fn wants_field(&self, _: usize) -> bool {
        true
    }
    fn step(
        &mut self,
        _n: usize,
        _t: f64,
        u: Option<&[f64]>,
        _c: &[evhi::certificate::ContactState],
    ) {
        if let Some(u) = u {
            self.0.push(u.to_vec());
        }
    }
    fn restart(&mut self) {
        self.0 = vec![vec![0.0; self.1]];
    }
}

/// Runs the paper's scenes and writes the tables and figures, the user scenes' rows
/// (`user`, described by `user_what`) appended to `adaptive_convergence.csv` and its
/// summary.
pub(super) fn run(ctx: &Ctx, user: Vec<Row>, user_what: &str) -> Result<(), ExpError> {
    let plan = plan(ctx.quick);
    let scns = LOADS
        .iter()
        .map(|s| Scenario::load(s))
        .collect::<Result<Vec<_>, _>>()?;
    let geo = scns[0].geometry().clone();
    let settings = RunSettings::default().with_n(4).with_steps(plan.steps);
    ctx.add_units(plan.uniform.len() + plan.graded.len() + 2 * LOADS.len() + 1);
    let (mut forest, root) = Forest::new(4, &geo)?;
    // The uniform and graded families' meshes.
    let mut meshes: Vec<(&'static str, usize, Leaves)> = vec![];
    for (family, levels, points) in [
        (FAMILIES[0], &plan.uniform, &[][..]),
        (FAMILIES[1], &plan.graded, &PAPER_SINGULAR[..]),
    ] {
        let mut prev = root.clone();
        for (i, &n) in levels.iter().enumerate() {
            prev = level(&mut forest, &geo, &prev, n, points);
            meshes.push((family, i, prev.clone()));
        }
    }
    let mut solved: Vec<Lev> = vec![];
    // The adaptive family, scene by scene, in the same forest.
    let adapt = AdaptSettings::default()
        .with_tol(1e-6)
        .with_max_dofs(plan.max_dofs);
    let mut finals = vec![];
    let mut others = vec![];
    // The mesh the figure draws: the default family's last level within a budget that
    // leaves its triangles readable.
    let mut drawn: Vec<(usize, usize, Leaves)> = vec![];
    for (family, aggregate) in [(FAMILIES[2], Aggregate::Max), (FAMILIES[3], Aggregate::Sum)] {
        for (i, scn) in scns.iter().enumerate() {
            let clock = std::time::Instant::now();
            let mut collect = Collect {
                family,
                scene: i,
                levels: vec![],
            };
            let a = evhi::adapt::adapt_from(
                forest,
                root.clone(),
                scn,
                &settings,
                &adapt.clone().with_aggregate(aggregate),
                &mut collect,
            )?;
            forest = a.forest;
            if aggregate == adapt.aggregate {
                let shown = (collect.levels.iter())
                    .rfind(|l| l.dofs <= DRAWN_DOFS)
                    .unwrap_or(&collect.levels[0]);
                drawn.push((shown.level, shown.dofs, shown.leaves.clone()));
                finals.push(a.leaves);
            } else {
                others.push(a.leaves);
            }
            ctx.log(&format!(
                "{} {family}: {} levels to {} dofs ({:.1} s)",
                scn.name(),
                collect.levels.len(),
                collect.levels.last().map_or(0, |l| l.dofs),
                clock.elapsed().as_secs_f64()
            ));
            solved.extend(collect.levels);
        }
    }
    // The uniform and graded levels, each scene on its own (as the adaptive runs are).
    // The indicators of the uniform level of 32 segments (or the finest below) are drawn.
    let shown_n = plan.uniform.iter().copied().filter(|&n| n <= 32).max();
    let mut shown: Vec<super::indicators::Shown> = vec![];
    for (family, l, leaves) in &meshes {
        let clock = std::time::Instant::now();
        let mesh = Arc::new(forest.mesh(leaves, 4));
        let dofs = Dofs::new(&mesh, true).count;
        for (i, scn) in scns.iter().enumerate() {
            let c = std::time::Instant::now();
            let sim = Simulation::on_mesh(scn.clone(), settings.clone(), mesh.clone())?;
            let est = solve_estimating(&sim, adapt.aggregate, &mut Keep)?;
            let total: f64 = est.eta_sq.iter().sum();
            if *family == FAMILIES[0] && Some(plan.uniform[*l]) == shown_n {
                let tris = mesh.triangles.iter().map(|t| t.map(|v| mesh.nodes[v]));
                let eta = est.eta_sq.iter().map(|e| e.sqrt()).collect();
                shown.push((scn.name().to_string(), tris.collect(), eta));
            }
            solved.push(Lev {
                family,
                scene: i,
                level: *l,
                leaves: leaves.clone(),
                dofs,
                fields: est.fields,
                estimate: (total / est.norm_sq).sqrt(),
                wall_s: c.elapsed().as_secs_f64(),
            });
        }
        ctx.log(&format!(
            "{family} level {l}: {dofs} dofs ({:.1} s)",
            clock.elapsed().as_secs_f64()
        ));
    }
    // The reference: the graded family continued to n_ref, refined to hold every
    // adaptive mesh.
    let clock = std::time::Instant::now();
    let mut reference = meshes
        .iter()
        .rfind(|m| m.0 == FAMILIES[1])
        .expect("a graded level")
        .2
        .clone();
    let mut n = *plan.graded.last().expect("levels");
    while n < plan.n_ref {
        n *= 2;
        reference = level(&mut forest, &geo, &reference, n, &PAPER_SINGULAR);
    }
    let graded_ref_dofs = Dofs::new(&forest.mesh(&reference, plan.n_ref), true).count;
    for f in finals.iter().chain(&others) {
        reference = forest.refine_to_contain(&reference, f);
    }
    let ref_mesh = Arc::new(forest.mesh(&reference, plan.n_ref));
    let ref_dofs = Dofs::new(&ref_mesh, true);
    let mut ref_fields = vec![];
    for scn in &scns {
        let sim = Simulation::on_mesh(scn.clone(), settings.clone(), ref_mesh.clone())?;
        let mut keep = Fields(vec![], ref_dofs.count);
        keep.restart();
        sim.solve(&mut keep)?;
        ref_fields.push(
            keep.0
                .iter()
                .map(|u| ref_dofs.expand(u))
                .collect::<Vec<_>>(),
        );
    }
    ctx.log(&format!(
        "reference: {} dofs (graded level {}: {graded_ref_dofs}), {} steps ({:.1} s)",
        ref_dofs.count,
        plan.n_ref,
        plan.steps,
        clock.elapsed().as_secs_f64()
    ));
    // Errors.
    let g = scns[0].elasticity();
    let norm_geo = evhi::norms::NormGeometry::new(&ref_mesh);
    let ref_norms: Vec<Vec<f64>> = ref_fields
        .iter()
        .map(|f| {
            f.iter()
                .map(|u| norm_geo.norms(&ref_mesh, &g, u).energy_sq)
                .collect()
        })
        .collect();
    // Each level's errors at every step, the levels shared between two threads.
    let reference = Reference {
        mesh: &ref_mesh,
        norm_geo: &norm_geo,
        g: &g,
    };
    let error_of = |lev: &Lev| {
        reference.error(
            &forest,
            lev,
            4,
            &ref_fields[lev.scene],
            &ref_norms[lev.scene],
        )
    };
    let errors: Vec<(f64, f64)> = std::thread::scope(|s| {
        let second = s.spawn(|| {
            solved
                .iter()
                .skip(1)
                .step_by(2)
                .map(error_of)
                .collect::<Vec<_>>()
        });
        let first: Vec<_> = solved.iter().step_by(2).map(error_of).collect();
        let second = second.join().expect("the second thread's errors");
        let mut all = vec![];
        for i in 0..solved.len() {
            all.push(if i % 2 == 0 {
                first[i / 2]
            } else {
                second[i / 2]
            });
        }
        all
    });
    let mut rows: Vec<(&Lev, f64, f64)> = (solved.iter())
        .zip(errors)
        .map(|(l, (at_t, max))| (l, at_t, max))
        .collect();
    let family_index = |f: &str| FAMILIES.iter().position(|x| *x == f).unwrap_or(0);
    rows.sort_by_key(|(l, ..)| (l.scene, family_index(l.family), l.level));
    let mut rows: Vec<Row> = (rows.into_iter())
        .map(|(l, err_t, err_max)| Row {
            scenario: scns[l.scene].name().to_string(),
            family: l.family,
            level: l.level,
            dofs: l.dofs,
            steps: plan.steps,
            err_t,
            err_max,
            estimate: l.estimate,
            wall_s: l.wall_s,
        })
        .collect();
    rows.extend(user);
    let walls = recorded_walls(ctx, &rows);
    let t = Table::new()
        .str(
            "scenario",
            rows.iter().map(|r| r.scenario.clone()).collect(),
        )
        .str(
            "family",
            rows.iter().map(|r| r.family.to_string()).collect(),
        )
        .u64("level", rows.iter().map(|r| r.level as u64).collect())
        .u64("dofs", rows.iter().map(|r| r.dofs as u64).collect())
        .u64("steps", rows.iter().map(|r| r.steps as u64).collect())
        .f64("err_T", rows.iter().map(|r| r.err_t).collect())
        .f64("err_max", rows.iter().map(|r| r.err_max).collect())
        .f64("estimator", rows.iter().map(|r| r.estimate).collect())
        .f64(
            "efficiency",
            rows.iter().map(|r| r.estimate / r.err_max).collect(),
        )
        .f64("wall_s", walls.clone());
    let params = format!(
        "every mesh from newest-vertex bisection of the n = 4 mesh; uniform: longest edge <= 2 sqrt2 / n (n = {:?}); graded: <= D min(1, max(r, D^(1/mu))^(1-mu)), D = 2 sqrt2 / n, mu = {MU}, r = distance to the nearest clamp end or top corner (n = {:?}); adaptive: evhi::adapt with theta = {}, indicators at their {} over the steps, from n = 4 until the next mesh would pass {} dofs (told nothing of the corners); adaptive (time mean): the same with each indicator's mean over the steps; N = {} steps on every level and the reference; reference: graded level {} ({graded_ref_dofs} dofs) refined to hold each adaptive family's last mesh ({} dofs); err_T, err_max = relative energy error ||u_ref - u||_E / ||u_ref||_E at T and its maximum over t_j = j T / N (fractions); estimator = the estimated relative error of evhi::adapt (sum of the indicators' per-triangle maximum over the steps, over the maximum of ||sigma||^2, square root); efficiency = estimator / err_max; wall_s = the level's solve with its indicators (adaptive: with the marking), one scene, as measured by the run that last moved another column (a rerun that reproduces every other column bit for bit keeps the recorded times, so that reproduce leaves this table as it was); then {user_what}",
        plan.uniform,
        plan.graded,
        adapt.theta,
        adapt.aggregate.name(),
        plan.max_dofs,
        plan.steps,
        plan.n_ref,
        ref_dofs.count
    );
    let path = ctx.write("adaptive_convergence.csv", &t, &params)?;
    ctx.write(
        "adaptive_summary.csv",
        &summary(&rows, &walls),
        &format!(
            "adaptive_convergence.csv by scene and family: its levels, the last level's unknowns and errors (percent), order_last = -2 d ln(err_T) / d ln(dofs) fitted by least squares over the last {FIT} levels, the efficiency index's smallest and largest value over the levels, and the family's wall time summed over its levels (s)"
        ),
    )?;
    // An adaptive mesh of each scene, triangle by triangle.
    let (mut scene, mut v) = (vec![], vec![vec![]; 6]);
    for (i, (_, _, f)) in drawn.iter().enumerate() {
        for &tri in &f.0 {
            let p = forest.triangle(tri);
            scene.push(scns[i].name().to_string());
            for (c, col) in v.iter_mut().enumerate() {
                col.push(p[c / 2][c % 2]);
            }
        }
    }
    let mut mt = Table::new().str("scenario", scene);
    for (c, col) in v.into_iter().enumerate() {
        mt = mt.f64(&format!("{}{}", ["x", "y"][c % 2], c / 2), col);
    }
    let mesh_path = ctx.write(
        "adaptive_meshes.csv",
        &mt,
        &format!(
            "a mesh of the adaptive family of adaptive_convergence.csv for each scene, its last level with at most {DRAWN_DOFS} dofs ({}): one row a triangle, its vertices (x0, y0), (x1, y1), (x2, y2)",
            (drawn.iter().zip(&scns))
                .map(|((l, d, _), s)| format!("{}: level {l}, {d} dofs", s.name()))
                .collect::<Vec<_>>()
                .join("; ")
        ),
    )?;
    if let Some(n) = shown_n {
        super::indicators::write(ctx, n, plan.steps, &shown)?;
    }
    draw(&ctx.figures, &path, &mesh_path)
}

/// A reference mesh of a bisection forest, with what a level's error against it needs.
pub(super) struct Reference<'a> {
    pub(super) mesh: &'a Mesh,
    pub(super) norm_geo: &'a evhi::norms::NormGeometry,
    pub(super) g: &'a evhi::material::Isotropic,
}

impl Reference<'_> {
    /// The relative energy error $\|u_{ref} - u\|_E / \|u_{ref}\|_E$ of `lev` (a mesh of
    /// `forest`, labelled `n`) at $T$ and its largest over the steps, each step's field
    /// carried to the reference exactly: `ref_fields` the reference's nodal fields at
    /// every step (step 0 first), `ref_norms` their $\|\cdot\|_E^2$.
    pub(super) fn error(
        &self,
        forest: &Forest,
        lev: &Lev,
        n: usize,
        ref_fields: &[Vec<[f64; 2]>],
        ref_norms: &[f64],
    ) -> (f64, f64) {
        let mesh = forest.mesh(&lev.leaves, n);
        let dofs = Dofs::new(&mesh, true);
        let interp = forest.interpolation(&lev.leaves, self.mesh);
        let (mut at_t, mut max) = (f64::NAN, 0.0f64);
        for j in 1..lev.fields.len() {
            let u = interp.apply(&dofs.expand(&lev.fields[j]));
            let diff: Vec<[f64; 2]> = (ref_fields[j].iter().zip(&u))
                .map(|(a, b)| [a[0] - b[0], a[1] - b[1]])
                .collect();
            let e = (self.norm_geo.norms(self.mesh, self.g, &diff).energy_sq / ref_norms[j]).sqrt();
            max = max.max(e);
            at_t = e;
        }
        (at_t, max)
    }
}

/// The levels the summary's order is fitted over.
const FIT: usize = 5;

/// `adaptive_summary.csv`: one row a scene and family.
fn summary(rows: &[Row], walls: &[f64]) -> Table {
    let (mut scn, mut fam, mut levels, mut dofs) = (vec![], vec![], vec![], vec![]);
    let (mut err_t, mut err_max, mut order, mut eff_lo, mut eff_hi, mut wall) =
        (vec![], vec![], vec![], vec![], vec![], vec![]);
    // The scenes in the order of their rows.
    let mut scenes: Vec<&str> = vec![];
    for r in rows {
        if !scenes.contains(&r.scenario.as_str()) {
            scenes.push(&r.scenario);
        }
    }
    for scene in scenes {
        for family in FAMILIES {
            let idx: Vec<usize> = (0..rows.len())
                .filter(|&i| rows[i].scenario == scene && rows[i].family == family)
                .collect();
            let Some(&last) = idx.last() else { continue };
            let fit = &idx[idx.len().saturating_sub(FIT)..];
            let pts: Vec<(f64, f64)> = (fit.iter())
                .map(|&i| ((rows[i].dofs as f64).ln(), rows[i].err_t.ln()))
                .collect();
            let n = pts.len() as f64;
            let (mx, my) = (
                pts.iter().map(|p| p.0).sum::<f64>() / n,
                pts.iter().map(|p| p.1).sum::<f64>() / n,
            );
            let slope = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum::<f64>()
                / pts.iter().map(|p| (p.0 - mx).powi(2)).sum::<f64>();
            let eff: Vec<f64> = idx
                .iter()
                .map(|&i| rows[i].estimate / rows[i].err_max)
                .collect();
            scn.push(scene.to_string());
            fam.push(family.to_string());
            levels.push(idx.len() as u64);
            dofs.push(rows[last].dofs as u64);
            err_t.push(100.0 * rows[last].err_t);
            err_max.push(100.0 * rows[last].err_max);
            order.push(-2.0 * slope);
            eff_lo.push(eff.iter().copied().fold(f64::INFINITY, f64::min));
            eff_hi.push(eff.iter().copied().fold(0.0, f64::max));
            wall.push(idx.iter().map(|&i| walls[i]).sum());
        }
    }
    Table::new()
        .str("scenario", scn)
        .str("family", fam)
        .u64("levels", levels)
        .u64("dofs", dofs)
        .f64("err_T_percent", err_t)
        .f64("err_max_percent", err_max)
        .f64("order_last", order)
        .f64("efficiency_min", eff_lo)
        .f64("efficiency_max", eff_hi)
        .f64("wall_total_s", wall)
}

/// The wall times of `rows`: those of the table already at the output path if it
/// holds the same rows with the same numbers in every other column (a rerun that
/// reproduced them), else the ones just measured.
fn recorded_walls(ctx: &Ctx, rows: &[Row]) -> Vec<f64> {
    let measured: Vec<f64> = rows.iter().map(|r| r.wall_s).collect();
    let Ok(df) = read_csv(&ctx.data.join("adaptive_convergence.csv")) else {
        return measured;
    };
    let cols = |names: &[&str]| -> Option<Vec<Vec<f64>>> {
        names.iter().map(|c| col_f64(&df, c).ok()).collect()
    };
    let (Some(old), Ok(fam), Ok(scn)) = (
        cols(&[
            "level",
            "dofs",
            "steps",
            "err_T",
            "err_max",
            "estimator",
            "wall_s",
        ]),
        col_str(&df, "family"),
        col_str(&df, "scenario"),
    ) else {
        return measured;
    };
    let same = old[0].len() == rows.len()
        && rows.iter().enumerate().all(|(i, r)| {
            fam[i] == r.family
                && scn[i] == r.scenario
                && old[0][i] == r.level as f64
                && old[1][i] == r.dofs as f64
                && old[2][i] == r.steps as f64
                && old[3][i] == r.err_t
                && old[4][i] == r.err_max
                && old[5][i] == r.estimate
        });
    if same { old[6].clone() } else { measured }
}

/// A chart's series: label, (unknowns, error %) points, colour, whether solid (the
/// first load) or dashed.
type Series = (String, Vec<(f64, f64)>, RGBColor, bool);

/// The figure: each scene's last adaptive mesh, and the error at T against the
/// unknowns for every family and scene.
struct Fig {
    meshes: Vec<(String, Vec<[[f64; 2]; 3]>)>,
    series: Vec<Series>,
}

fn draw(
    dir: &std::path::Path,
    path: &std::path::Path,
    mesh_path: &std::path::Path,
) -> Result<(), ExpError> {
    let df = read_csv(path)?;
    let (scn, fam) = (col_str(&df, "scenario")?, col_str(&df, "family")?);
    let (dofs, err) = (col_f64(&df, "dofs")?, col_f64(&df, "err_T")?);
    let colours = [oi::BLACK, oi::BLUE, oi::VERMILLION, oi::BLUISH_GREEN];
    let mut series = vec![];
    for (li, l) in LOADS.iter().enumerate() {
        for (fi, f) in FAMILIES.iter().enumerate() {
            let pts = (0..scn.len())
                .filter(|&i| scn[i] == *l && fam[i] == *f)
                .map(|i| (dofs[i], 100.0 * err[i]))
                .collect();
            series.push((format!("{l}, {f}"), pts, colours[fi], li == 0));
        }
    }
    let mf = read_csv(mesh_path)?;
    let ms = col_str(&mf, "scenario")?;
    let c: Vec<Vec<f64>> = (0..6)
        .map(|k| col_f64(&mf, &format!("{}{}", ["x", "y"][k % 2], k / 2)))
        .collect::<Result<_, _>>()?;
    let meshes = LOADS
        .iter()
        .map(|l| {
            let tris = (0..ms.len())
                .filter(|&i| ms[i] == *l)
                .map(|i| [[c[0][i], c[1][i]], [c[2][i], c[3][i]], [c[4][i], c[5][i]]])
                .collect();
            (l.to_string(), tris)
        })
        .collect();
    both(
        dir,
        "adaptive_meshes",
        (1500, 1500),
        &Fig { meshes, series },
    )?;
    // The same errors against what they cost: a uniform or graded level's own solve
    // (with its indicators), an adaptive level's solve and every level's before it.
    let wall = col_f64(&df, "wall_s")?;
    let mut work = vec![];
    for (li, l) in LOADS.iter().enumerate() {
        for (fi, f) in FAMILIES.iter().enumerate() {
            let climbs = fi >= 2;
            let mut spent = 0.0;
            let pts = (0..scn.len())
                .filter(|&i| scn[i] == *l && fam[i] == *f)
                .map(|i| {
                    spent = if climbs { spent + wall[i] } else { wall[i] };
                    (spent, 100.0 * err[i])
                })
                .collect();
            work.push((format!("{l}, {f}"), pts, colours[fi], li == 0));
        }
    }
    Ok(both(dir, "adaptive_work", (1500, 1000), &Work(work))?)
}

/// The work–precision chart of the study's families.
struct Work(Vec<Series>);

impl Figure for Work {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        families(
            root,
            &self.0,
            "error at T against the wall time that reached it",
            (
                "wall time, s (adaptive: its levels summed)",
                (-4..=2).map(|e| 10f64.powi(e)).collect(),
            ),
            false,
        )
    }
}

impl Figure for Fig {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        let (top, bottom) = root.split_vertically(440);
        let halves = top.split_horizontally(750);
        for (area, (name, tris)) in [halves.0, halves.1].iter().zip(&self.meshes) {
            let caption = format!(
                "({}) {name}: adaptive mesh, {} triangles",
                if name == LOADS[0] { "a" } else { "b" },
                tris.len()
            );
            let mut chart = ChartBuilder::on(area)
                .caption(caption, (evhi::output::plot::FONT, 24))
                .margin(12)
                .build_cartesian_2d(0.0..2.0, 0.0..1.0)
                .map_err(e2s)?;
            chart
                .draw_series(tris.iter().map(|t| {
                    PathElement::new(
                        vec![
                            (t[0][0], t[0][1]),
                            (t[1][0], t[1][1]),
                            (t[2][0], t[2][1]),
                            (t[0][0], t[0][1]),
                        ],
                        BLACK.stroke_width(1),
                    )
                }))
                .map_err(e2s)?;
        }
        families(
            &bottom,
            &self.series,
            "(c) error at T against the graded reference",
            ("unknowns N", (1..=7).map(|e| 10f64.powi(e)).collect()),
            true,
        )
    }
}

/// A log-log chart of every family's error at T (percent) against `x` (its
/// description and key points), each scene's families solid or dashed, with the
/// slope of order 1 in h through the first graded point if `guide`.
fn families<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    series: &[Series],
    caption: &str,
    (x_desc, x_keys): (&str, Vec<f64>),
    guide: bool,
) -> Result<(), String> {
    let pts: Vec<(f64, f64)> = series.iter().flat_map(|s| s.1.clone()).collect();
    let ((xmin, xmax), (ymin, ymax)) = evhi::output::plot::extent(&pts);
    let (xr, yr) = ((xmin / 1.5, xmax * 1.5), (ymin / 1.5, ymax * 1.5));
    let mut chart = LogLogChart {
        caption: (caption, 28),
        label_areas: (76, 104),
        margin: 28,
        desc: (x_desc, "relative energy error at T, %"),
        format: (
            Some(&evhi::output::plot::plain),
            Some(&evhi::output::plot::plain),
        ),
        fonts: (26, Some(26)),
    }
    .build(
        area,
        (xr.0..xr.1)
            .log_scale()
            .with_key_points(keys_within(xr, x_keys)),
        (yr.0..yr.1).log_scale().with_key_points(keys_within(
            yr,
            [0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0],
        )),
    )?;
    for (label, s, c, solid) in series {
        let c = *c;
        let style = c.stroke_width(if *solid { 3 } else { 2 });
        if *solid {
            chart
                .draw_series(LineSeries::new(s.clone(), style))
                .map_err(e2s)?
                .label(label.clone())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 30, y)], c.stroke_width(3))
                });
        } else {
            chart
                .draw_series(DashedLineSeries::new(s.clone(), 10, 6, style))
                .map_err(e2s)?
                .label(label.clone())
                .legend(move |(x, y)| {
                    EmptyElement::at((x, y))
                        + PathElement::new(vec![(0, 0), (10, 0)], c.stroke_width(2))
                        + PathElement::new(vec![(16, 0), (26, 0)], c.stroke_width(2))
                });
        }
        chart
            .draw_series(s.iter().map(|&p| {
                Circle::new(
                    p,
                    6,
                    if *solid {
                        c.filled()
                    } else {
                        c.stroke_width(2)
                    },
                )
            }))
            .map_err(e2s)?;
    }
    // The slope of order 1 in h, N^(-1/2), through the first graded point.
    if let Some(&(x0, y0)) = series.get(1).and_then(|s| s.1.first()).filter(|_| guide) {
        let guide = vec![(x0, y0), (xr.1 / 1.5, y0 * (xr.1 / 1.5 / x0).powf(-0.5))];
        chart
            .draw_series(DashedLineSeries::new(
                guide,
                6,
                6,
                evhi::output::plot::GREY_DARK.stroke_width(2),
            ))
            .map_err(e2s)?
            .label("N^(-1/2): order 1 in h")
            .legend(|(x, y)| {
                let grey = evhi::output::plot::GREY_DARK.stroke_width(2);
                EmptyElement::at((x, y))
                    + PathElement::new(vec![(0, 0), (6, 0)], grey)
                    + PathElement::new(vec![(12, 0), (18, 0)], grey)
                    + PathElement::new(vec![(24, 0), (30, 0)], grey)
            });
    }
    evhi::output::plot::legend(&mut chart, SeriesLabelPosition::LowerLeft, 24, 0.9)
}
