//! Table 1 and Fig. 5: relative energy-norm errors $\|u_{ref} - u^{hk}\|_E / \|u_{ref}\|_E$
//! against a reference solution ($h = k = 1/512$), for $h = k = 1/4, \dots, 1/128$,
//! for the `literal` and the `figure` scenarios. Beyond the paper: the error split
//! into its $h$ part ($k$ at the reference value) and its $k$ part ($h$ at the
//! reference value), and where in $\Omega$ the error sits.
//!
//! Coarse fields are prolongated exactly onto the reference mesh (the spaces are
//! nested). The paper does not say at which time it measures; we report $t = T$ and
//! the maximum over the time levels shared with the reference,
//! $\max_n \|e_n\|_E / \max_n \|u_{ref,n}\|_E$ (the norm of Corollary 4.1's left side).

use super::plot::{Figure, both, circle_legend, dashed_legend, e2s, legend};
use super::{Ctx, ExpError, col_f64, col_str, read_csv, run_newton_batch_with};
use crate::assembly::stiffness;
use crate::element::strain_matrix;
use crate::mesh::{Dofs, Mesh, prolongate};
use crate::norms::energy_norm;
use crate::output::csv::Table;
use crate::scenario::Scenario;
use crate::scheme::Options;
use plotters::prelude::*;
use std::collections::BTreeMap;

/// The paper's Table 1 (percent), keyed by $n$ with $h = k = 1/n$ ($h + k = 2/n$).
pub const PAPER: [(usize, f64); 6] = [
    (4, 24.099),
    (8, 12.835),
    (16, 6.407),
    (32, 3.153),
    (64, 1.540),
    (128, 0.741),
];

/// Levels and reference of a study.
pub struct Plan {
    pub levels: Vec<usize>,
    pub n_ref: usize,
}

pub fn plan(quick: bool) -> Plan {
    if quick {
        Plan {
            levels: vec![4, 8, 16],
            n_ref: 32,
        }
    } else {
        Plan {
            levels: vec![4, 8, 16, 32, 64, 128],
            n_ref: 512,
        }
    }
}

/// The reference solution at the time levels $t = j/N_{grid}$.
/// The reference solutions of a group of scenarios that share the step matrix
/// (so the mesh and the energy norm too), at the time levels $t = j/N_{grid}$.
struct Reference {
    mesh: Mesh,
    dofs: Dofs,
    b: crate::assembly::SpMat,
    grid: usize,
    /// Per scenario of the group: the fields and their energy norms, by level $j$.
    fields: Vec<BTreeMap<usize, Vec<f64>>>,
    norms: Vec<BTreeMap<usize, f64>>,
    tensor: crate::material::Isotropic,
}

/// Error of one level against the reference.
#[derive(Debug, Clone)]
pub struct LevelError {
    pub family: &'static str,
    pub n: usize,
    pub steps: usize,
    pub rel_t: f64,
    pub rel_max: f64,
    /// Squared error at $t = T$ in three regions: near the clamp ends, near $\Gamma_3$, the rest.
    pub regions: [f64; 3],
}

/// Region of a point: 0 within 1/8 of the ends of $\Gamma_1$ at $(0, 1/2)$, $(2, 1/2)$;
/// 1 within 1/8 of $\Gamma_3$; 2 elsewhere.
pub fn region(x: f64, y: f64) -> usize {
    let d = ((x).hypot(y - 0.5)).min((x - 2.0).hypot(y - 0.5));
    if d < 0.125 {
        0
    } else if y < 0.125 {
        1
    } else {
        2
    }
}

/// The running error measures of one scenario in one level.
#[derive(Default)]
struct Accumulator {
    max_e: f64,
    max_u: f64,
    e_t: f64,
    u_t: f64,
    regions: [f64; 3],
    fail: Option<usize>,
}

impl Reference {
    /// The references of a group of scenarios that share the step matrix, in one
    /// batched run.
    fn compute(
        scns: &[Scenario],
        n_ref: usize,
        grid: usize,
        ctx: &Ctx,
    ) -> Result<Reference, ExpError> {
        let every = n_ref / grid;
        let mut fields = vec![BTreeMap::new(); scns.len()];
        let clock = std::time::Instant::now();
        run_newton_batch_with(scns, &Options::new(n_ref, n_ref), &mut |i, step, _, u| {
            if step % every == 0 {
                fields[i].insert(step / every, u.to_vec());
            }
        })?;
        let names: Vec<&str> = scns.iter().map(|s| s.name.as_str()).collect();
        ctx.log(&format!(
            "{}: reference, h = k = 1/{n_ref} ({:.1} s)",
            names.join(" + "),
            clock.elapsed().as_secs_f64()
        ));
        let mesh = scns[0].mesh(n_ref)?;
        let dofs = Dofs::new(&mesh, true);
        let tensor = scns[0].elasticity();
        let b = stiffness(&mesh, &dofs, &tensor);
        let norms = (fields.iter())
            .map(|f| f.iter().map(|(&j, u)| (j, energy_norm(&b, u))).collect())
            .collect();
        Ok(Reference {
            mesh,
            dofs,
            b,
            grid,
            fields,
            norms,
            tensor,
        })
    }

    /// Errors of the level $(n, N)$ for each scenario of the group, in one batched
    /// run, computed on the fly at the shared time levels.
    fn levels(
        &self,
        scns: &[Scenario],
        family: &'static str,
        n: usize,
        steps: usize,
    ) -> Result<Vec<LevelError>, ExpError> {
        let coarse = scns[0].mesh(n)?;
        let cdofs = Dofs::new(&coarse, true);
        let mut acc: Vec<Accumulator> = scns
            .iter()
            .map(|_| Accumulator {
                u_t: 1.0,
                ..Default::default()
            })
            .collect();
        run_newton_batch_with(
            scns,
            // Two workers already keep both cores busy with levels; a second sweep
            // thread per run only waits for a core. Measured once each: table1 in
            // 70.6 s this way, 77.5 s with two sweep threads for the levels too.
            &Options {
                parallel: false,
                ..Options::new(n, steps)
            },
            &mut |i, step, _, u| {
                let a = &mut acc[i];
                if !(step * self.grid).is_multiple_of(steps) || a.fail.is_some() {
                    return;
                }
                let j = step * self.grid / steps;
                let Some(uref) = self.fields[i].get(&j) else {
                    return;
                };
                let fine = if n == self.mesh.n {
                    u.to_vec()
                } else {
                    self.dofs
                        .gather(&prolongate(&coarse, &cdofs.expand(u), &self.mesh))
                };
                let diff: Vec<f64> = uref.iter().zip(&fine).map(|(a, b)| a - b).collect();
                let e = energy_norm(&self.b, &diff);
                a.max_e = a.max_e.max(e);
                a.max_u = a.max_u.max(self.norms[i][&j]);
                if j == self.grid {
                    a.e_t = e;
                    a.u_t = self.norms[i][&j];
                    a.regions = self.regions(&diff);
                }
                if !e.is_finite() {
                    a.fail = Some(step);
                }
            },
        )?;
        scns.iter()
            .zip(acc)
            .map(|(scn, a)| match a.fail {
                Some(step) => Err(ExpError::Table {
                    path: format!("table1, scenario {}", scn.name),
                    message: format!("non-finite error at h = 1/{n}, {steps} steps, step {step}"),
                }),
                None => Ok(LevelError {
                    family,
                    n,
                    steps,
                    rel_t: a.e_t / a.u_t,
                    rel_max: a.max_e / a.max_u,
                    regions: a.regions,
                }),
            })
            .collect()
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
            out[region(cx, cy)] += dens;
        }
        out
    }
}

/// The scenarios of the study: the paper's data as printed, the loads of Figs. 3-4,
/// and the smooth scene that satisfies the corollary's regularity hypotheses.
pub const SCENARIOS: [&str; 3] = ["literal", "figure", "smooth"];

/// One unit of the study's work: the references of a group of scenarios that
/// share the step matrix, or one level of one family for such a group.
#[derive(Debug, Clone, Copy)]
enum Task {
    Reference(usize),
    Level {
        group: usize,
        /// Index of the level in the plan and of the family in [`FAMILIES`].
        level: usize,
        family: usize,
    },
}

/// The three families: name, and $(n, N)$ from the level's $n$ and the reference's.
const FAMILIES: [&str; 3] = ["h=k", "h", "k"];

fn family_sizes(family: usize, n: usize, n_ref: usize) -> (usize, usize) {
    match family {
        0 => (n, n),
        1 => (n, n_ref),
        _ => (n_ref, n),
    }
}

impl Task {
    /// Rough cost, for running the dearest first: dof-steps of the run plus the
    /// fine-mesh error evaluations at the shared time levels.
    fn cost(&self, plan: &Plan, grid: usize) -> usize {
        match *self {
            Task::Reference(_) => usize::MAX,
            Task::Level { level, family, .. } => {
                let (n, steps) = family_sizes(family, plan.levels[level], plan.n_ref);
                steps * n * n + steps.min(grid) * plan.n_ref * plan.n_ref
            }
        }
    }
}

/// What the workers share: the tasks not yet started, the references done so far,
/// and the first error.
struct Queue {
    pending: Vec<Task>,
    references: Vec<Option<std::sync::Arc<Reference>>>,
    /// (table row, error).
    levels: Vec<(usize, LevelError)>,
    error: Option<ExpError>,
}

/// All three families of all scenarios, on two threads (this machine has two
/// cores). Scenarios that share the step matrix run together (`literal` and
/// `figure`: one factorisation and one sweep over $L$ per step for both).
/// References go first; then the levels, dearest first, each as soon as its
/// reference is there, so neither thread idles while work remains.
fn study(plan: &Plan, grid: usize, ctx: &Ctx) -> Result<Vec<(String, LevelError)>, ExpError> {
    let scenarios = SCENARIOS
        .iter()
        .map(|name| Scenario::load(name))
        .collect::<Result<Vec<_>, _>>()?;
    let mut groups: Vec<Vec<Scenario>> = vec![];
    for scn in &scenarios {
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
    let mut levels = vec![];
    for group in 0..groups.len() {
        for level in 0..nl {
            for family in 0..FAMILIES.len() {
                levels.push(Task::Level {
                    group,
                    level,
                    family,
                });
            }
        }
    }
    levels.sort_by_key(|t| std::cmp::Reverse(t.cost(plan, grid)));
    // One unit per reference and per level run.
    ctx.add_units(pending.len() + levels.len());
    pending.extend(levels);
    let queue = std::sync::Mutex::new(Queue {
        pending,
        references: vec![None; groups.len()],
        levels: vec![],
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
                    Task::Reference(_) => true,
                    Task::Level { group, .. } => q.references[*group].is_some(),
                });
                match runnable {
                    Some(i) => {
                        let task = q.pending.remove(i);
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
            (Task::Reference(g), _) => Reference::compute(&groups[g], plan.n_ref, grid, ctx)
                .map(|r| (Some((g, std::sync::Arc::new(r))), vec![])),
            (
                Task::Level {
                    group,
                    level,
                    family,
                },
                Some(reference),
            ) => {
                let (n, steps) = family_sizes(family, plan.levels[level], plan.n_ref);
                let clock = std::time::Instant::now();
                let errors = reference.levels(&groups[group], FAMILIES[family], n, steps);
                let names: Vec<&str> = groups[group].iter().map(|s| s.name.as_str()).collect();
                ctx.log(&format!(
                    "{}: {} family, h = 1/{n}, k = 1/{steps} ({:.1} s)",
                    names.join(" + "),
                    FAMILIES[family],
                    clock.elapsed().as_secs_f64()
                ));
                errors.map(|errors| {
                    let rows = (groups[group].iter().zip(errors))
                        .map(|(s, e)| (row(&s.name, level, family), e))
                        .collect();
                    (None, rows)
                })
            }
            (Task::Level { .. }, None) => unreachable!("levels wait for their reference"),
        };
        let mut q = queue.lock().expect("study queue");
        match outcome {
            Ok((Some((g, r)), _)) => q.references[g] = Some(r),
            Ok((None, rows)) => {
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

pub fn run(ctx: &Ctx) -> Result<(), ExpError> {
    let plan = plan(ctx.quick);
    let grid = *plan.levels.last().expect("levels");
    let all = study(&plan, grid, ctx)?;
    let params = format!(
        "reference h = k = 1/{}; families: h=k (h = k = 1/n), h (k = 1/{}), k (h = 1/{}); rel_err_T at t = T, rel_err_max = max_n ||e_n||_E / max_n ||u_ref,n||_E over the level's own time steps (all on the grid t = j/{grid}); solver newton",
        plan.n_ref, plan.n_ref, plan.n_ref
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
    let paper: Vec<f64> = all
        .iter()
        .map(|(_, e)| {
            if e.family == "h=k" {
                PAPER.iter().find(|p| p.0 == e.n).map_or(f64::NAN, |p| p.1)
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
        .f64("order_max", order_max)
        .f64("paper_percent", paper)
        .f64(
            "share_clamp_ends",
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
    let path = ctx.write("table1.csv", &t, "table1", &params)?;
    write_markdown(ctx, &path, &params)?;
    draw(ctx, &path)
}

/// The Markdown Table 1, ours beside the paper's, from the CSV.
fn write_markdown(ctx: &Ctx, path: &std::path::Path, params: &str) -> Result<(), ExpError> {
    let df = read_csv(path)?;
    let (sc, fam) = (col_str(&df, "scenario")?, col_str(&df, "family")?);
    let (n, hk) = (col_f64(&df, "n")?, col_f64(&df, "h_plus_k")?);
    let (et, em, ot, om, pp) = (
        col_f64(&df, "rel_err_T_percent")?,
        col_f64(&df, "rel_err_max_percent")?,
        col_f64(&df, "order_T")?,
        col_f64(&df, "order_max")?,
        col_f64(&df, "paper_percent")?,
    );
    let f = |x: f64| {
        if x.is_finite() {
            format!("{x:.3}")
        } else {
            "".into()
        }
    };
    let mut md = format!(
        "<!-- {} -->\n<!-- {} -->\n\n",
        ctx.provenance("table1", "").join(" "),
        params
    );
    let rows: Vec<usize> = (0..sc.len())
        .filter(|&i| fam[i] == "h=k" && sc[i] == SCENARIOS[0])
        .collect();
    // Two narrow tables, at t = T and the maximum over t, each with the paper's column.
    for (title, err, ord) in [
        ("at t = T", &et, &ot),
        (
            "maximum over t (over the time levels shared with the reference)",
            &em,
            &om,
        ),
    ] {
        md += &format!(
            "Relative error in energy norm, h = k, in percent, {title}; order = observed order between successive rows.\n\n| h + k | paper |"
        );
        for name in SCENARIOS {
            md += &format!(" {name} | order |");
        }
        md += "\n|---|---|";
        md += &"---|---|".repeat(SCENARIOS.len());
        md += "\n";
        for &i in &rows {
            md += &format!("| 1/{} | {} |", (1.0 / hk[i]).round(), f(pp[i]));
            for name in SCENARIOS {
                let j = (0..sc.len())
                    .find(|&j| fam[j] == "h=k" && sc[j] == name && n[j] == n[i])
                    .expect("every scenario");
                md += &format!(" {} | {} |", f(err[j]), f(ord[j]));
            }
            md += "\n";
        }
        md += "\n";
    }
    ctx.write_file(&ctx.data_path("table1.md"), md.as_bytes())
}

/// A plotted series: label, points, colour, and whether it is the second
/// (dashed, crosses) series of its scenario.
type Series = (String, Vec<(f64, f64)>, RGBColor, bool);

/// One log–log panel of Fig. 5.
struct Fig5 {
    title: String,
    x_desc: String,
    series: Vec<Series>,
}

/// The error split: the h part and the k part, at t = T and over time.
struct Fig5Split {
    panels: [Fig5; 2],
}

/// Okabe–Ito colours (safe for colour-blind readers), in [`SCENARIOS`] order.
const COLOURS: [RGBColor; 3] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
];

fn draw(ctx: &Ctx, path: &std::path::Path) -> Result<(), ExpError> {
    let df = read_csv(path)?;
    let (sc, fam) = (col_str(&df, "scenario")?, col_str(&df, "family")?);
    let (n, steps) = (col_f64(&df, "n")?, col_f64(&df, "steps")?);
    let (hk, et, em, pp) = (
        col_f64(&df, "h_plus_k")?,
        col_f64(&df, "rel_err_T_percent")?,
        col_f64(&df, "rel_err_max_percent")?,
        col_f64(&df, "paper_percent")?,
    );
    // x: h + k for the h = k family; the varying h = 1/n or k = 1/N for the split.
    let x_of = |i: usize| match fam[i].as_str() {
        "h" => 1.0 / n[i],
        "k" => 1.0 / steps[i],
        _ => hk[i],
    };
    let pick = |s: &str, f: &str, v: &[f64]| -> Vec<(f64, f64)> {
        (0..sc.len())
            .filter(|&i| sc[i] == s && fam[i] == f && v[i].is_finite())
            .map(|i| (x_of(i), v[i]))
            .collect()
    };
    let mut main = vec![(
        "paper, Table 1".to_string(),
        pick("literal", "h=k", &pp),
        BLACK,
        false,
    )];
    for (name, colour) in SCENARIOS.iter().zip(COLOURS) {
        main.push((
            format!("{name}, t = T"),
            pick(name, "h=k", &et),
            colour,
            false,
        ));
        main.push((
            format!("{name}, max over t"),
            pick(name, "h=k", &em),
            colour,
            true,
        ));
    }
    both(
        &ctx.figures,
        "fig5_errors",
        (1000, 750),
        &Fig5 {
            title: "Fig. 5: relative error in energy norm, h = k".into(),
            x_desc: "h + k".into(),
            series: main,
        },
    )?;
    let panel = |title: &str, v: &[f64]| Fig5 {
        title: title.into(),
        x_desc: "h (h part, k as the reference's) or k (k part, h as the reference's)".into(),
        series: SCENARIOS
            .iter()
            .zip(COLOURS)
            .flat_map(|(name, colour)| {
                [
                    (format!("{name}, h part"), pick(name, "h", v), colour, false),
                    (format!("{name}, k part"), pick(name, "k", v), colour, true),
                ]
            })
            .collect(),
    };
    both(
        &ctx.figures,
        "fig5_split",
        (1000, 1300),
        &Fig5Split {
            panels: [panel("at t = T", &et), panel("maximum over t", &em)],
        },
    )
}

impl Figure for Fig5Split {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        let root = root
            .titled("Error split: the h part and the k part", ("sans-serif", 26))
            .map_err(e2s)?;
        let areas = root.split_evenly((2, 1));
        for (area, panel) in areas.iter().zip(&self.panels) {
            panel.draw(area)?;
        }
        Ok(())
    }
}

/// "1/n" for a value close to the reciprocal of an integer, else three decimals.
fn reciprocal_label(x: f64) -> String {
    let r = 1.0 / x;
    if (r - r.round()).abs() < 1e-6 * r {
        format!("1/{}", r.round())
    } else {
        format!("{x:.3}")
    }
}

impl Figure for Fig5 {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        let pts: Vec<(f64, f64)> = self
            .series
            .iter()
            .flat_map(|s| s.1.iter().copied())
            .collect();
        let (xmin, xmax) = pts
            .iter()
            .fold((f64::INFINITY, 0.0f64), |a, p| (a.0.min(p.0), a.1.max(p.0)));
        let (ymin, ymax) = pts
            .iter()
            .fold((f64::INFINITY, 0.0f64), |a, p| (a.0.min(p.1), a.1.max(p.1)));
        // A tick and a label at every level.
        let mut keys: Vec<f64> = pts.iter().map(|p| p.0).collect();
        keys.sort_by(f64::total_cmp);
        keys.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
        let ykeys: Vec<f64> = (-6..=3)
            .flat_map(|e| [1.0, 2.0, 5.0].map(|m| m * 10f64.powi(e)))
            .filter(|&y| y >= ymin * 0.5 && y <= ymax * 2.0)
            .collect();
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, ("sans-serif", 24))
            .margin(15)
            .x_label_area_size(55)
            .y_label_area_size(80)
            .build_cartesian_2d(
                (xmin * 0.8..xmax * 1.25).log_scale().with_key_points(keys),
                (ymin * 0.5..ymax * 2.0).log_scale().with_key_points(ykeys),
            )
            .map_err(e2s)?;
        chart
            .configure_mesh()
            .x_desc(&self.x_desc)
            .x_label_formatter(&|x| reciprocal_label(*x))
            .y_label_formatter(&|y| format!("{y}"))
            .y_desc("relative energy error, %")
            .label_style(("sans-serif", 18))
            .axis_desc_style(("sans-serif", 20))
            .draw()
            .map_err(e2s)?;
        for (label, s, colour, second) in &self.series {
            if s.is_empty() {
                continue;
            }
            let c = *colour;
            if *second {
                // Dashed, with crosses.
                chart
                    .draw_series(DashedLineSeries::new(s.clone(), 10, 6, c.stroke_width(2)))
                    .map_err(e2s)?;
                chart
                    .draw_series(s.iter().map(move |&p| Cross::new(p, 7, c.stroke_width(2))))
                    .map_err(e2s)?
                    .label(label.clone())
                    .legend(move |(x, y)| {
                        EmptyElement::at((x + 14, y))
                            + PathElement::new(vec![(-14, 0), (-4, 0)], c.stroke_width(2))
                            + PathElement::new(vec![(4, 0), (14, 0)], c.stroke_width(2))
                            + Cross::new((0, 0), 6, c.stroke_width(2))
                    });
            } else {
                chart
                    .draw_series(LineSeries::new(s.clone(), c.stroke_width(3)))
                    .map_err(e2s)?;
                chart
                    .draw_series(s.iter().map(move |&p| Circle::new(p, 5, c.filled())))
                    .map_err(e2s)?
                    .label(label.clone())
                    .legend(move |xy| circle_legend(xy, 14, c.stroke_width(3), 5, c));
            }
        }
        // Slope guides below the first series' first point: order 1 long dashes,
        // order 1/2 dots.
        if let Some(&(x0, y0)) = self
            .series
            .iter()
            .find(|s| !s.1.is_empty())
            .and_then(|s| s.1.first())
        {
            let grey = RGBColor(90, 90, 90);
            for (slope, y, label, dash, gap) in [
                (1.0, y0 * 0.45, "slope 1", 12, 6),
                (0.5, y0 * 0.2, "slope 1/2", 2, 5),
            ] {
                let guide = vec![(x0, y), (xmin, y * (xmin / x0).powf(slope))];
                chart
                    .draw_series(DashedLineSeries::new(
                        guide,
                        dash,
                        gap,
                        grey.stroke_width(2),
                    ))
                    .map_err(e2s)?
                    .label(label)
                    .legend(move |xy| dashed_legend(xy, dash, gap, grey.stroke_width(2)));
            }
        }
        legend(&mut chart, SeriesLabelPosition::LowerRight, 16, 0.9)?;
        Ok(())
    }
}
