//! Meshes graded towards the singular points, on the paper's scene with contact and
//! time: if the corners are what holds Table 1's order below 1, refining near them
//! must restore order 1 in $N_{dof}^{-1/2}$.
//!
//! Both families come from newest-vertex bisection of the structured mesh with
//! $n_0 = 4$ ([`crate::bisection`]), so every mesh is nested in the reference and
//! errors are exact by embedding:
//! - `uniform`: bisect until every triangle's longest edge is at most $D_n = 2\sqrt2/n$,
//!   the diagonal of the paper's cell at level $n$;
//! - `graded`: bisect until it is at most $D_n \min(1, \max(r, D_n^{1/\mu})^{1-\mu})$, with $r$
//!   the distance of the triangle's centroid to the nearest singular point (the clamp
//!   ends $(0, \tfrac12)$, $(2, \tfrac12)$ and the top corners $(0, 1)$, $(2, 1)$) and
//!   $\mu = 0.4$, below the clamp end's exponent $\tfrac12$. A function $r^\lambda$ is then
//!   approximated at the rate of a smooth one (Babuška, Kellogg, Pitkäranta 1979).
//!
//! Level $n$ runs with $k = 1/n$; the reference is the graded mesh of level
//! $n_{ref}$ with $k = 1/n_{ref}$. The error is the relative energy norm at $t = T$
//! (where the time part of the error is below 0.3 % at every level of Table 1).

use super::plot::{Figure, both, circle_legend, e2s, legend, slope_guides};
use super::{Ctx, ExpError, col_f64, col_str, read_csv};
use crate::bisection::{Forest, Leaves};
use crate::mesh::{Dofs, Mesh, Supports};
use crate::norms::field_norms;
use crate::output::csv::Table;
use crate::scenario::Scenario;
use crate::scheme::Settings;
use plotters::prelude::*;
use std::sync::Arc;

/// The grading exponent $\mu$ (below the smallest corner exponent, $\tfrac12$).
pub const MU: f64 = 0.4;

/// The singular points of the paper's scene.
pub const SINGULAR: [[f64; 2]; 4] = [[0.0, 0.5], [2.0, 0.5], [0.0, 1.0], [2.0, 1.0]];

/// Levels of each family and the reference. A graded level has about five
/// times the unknowns of the uniform one with the same $n$, so the graded family
/// stops a level earlier, four times coarser than its reference.
pub struct Plan {
    pub uniform: Vec<usize>,
    pub graded: Vec<usize>,
    pub n_ref: usize,
}

pub fn plan(quick: bool) -> Plan {
    if quick {
        Plan {
            uniform: vec![4, 8, 16, 32],
            graded: vec![4, 8, 16, 32],
            n_ref: 128,
        }
    } else {
        Plan {
            uniform: vec![4, 8, 16, 32, 64, 128],
            graded: vec![4, 8, 16, 32, 64],
            n_ref: 256,
        }
    }
}

fn diagonal(n: usize) -> f64 {
    2.0 * std::f64::consts::SQRT_2 / n as f64
}

/// The largest longest edge allowed at `x` on the graded mesh of level `n`.
pub fn graded_size(n: usize, x: [f64; 2]) -> f64 {
    let d = diagonal(n);
    let r = SINGULAR
        .iter()
        .map(|p| (x[0] - p[0]).hypot(x[1] - p[1]))
        .fold(f64::INFINITY, f64::min);
    d * r.max(d.powf(1.0 / MU)).powf(1.0 - MU).min(1.0)
}

fn centroid(f: &Forest, t: usize) -> [f64; 2] {
    let p = f.triangle(t);
    [
        (p[0][0] + p[1][0] + p[2][0]) / 3.0,
        (p[0][1] + p[1][1] + p[2][1]) / 3.0,
    ]
}

/// Refines `from` to the uniform or graded mesh of level `n`.
fn level(forest: &mut Forest, from: &Leaves, n: usize, graded: bool) -> Leaves {
    // A hair of slack so that a triangle exactly at the bound is not cut.
    let slack = 1.0 + 1e-12;
    if graded {
        forest.refine(from, |f, t| {
            f.diameter(t) > slack * graded_size(n, centroid(f, t))
        })
    } else {
        let d = diagonal(n);
        forest.refine(from, |f, t| f.diameter(t) > slack * d)
    }
}

/// One level's result.
struct Row {
    family: &'static str,
    load: String,
    n: usize,
    dofs: usize,
    triangles: usize,
    min_edge: f64,
    rel_err: f64,
}

/// The loads of the study (one batched run per mesh).
pub const LOADS: [&str; 2] = ["literal", "figure"];

fn solve_at_t(scns: &[Scenario], mesh: &Arc<Mesh>, n: usize) -> Result<Vec<Vec<f64>>, ExpError> {
    let mut last = vec![vec![]; scns.len()];
    let opt = Settings {
        mesh: Some(mesh.clone()),
        ..Settings::new(n, n)
    };
    super::run_newton_batch_with(scns, &opt, &mut |i, step, _, u| {
        if step == n {
            last[i] = u.to_vec();
        }
    })?;
    Ok(last)
}

pub fn run(ctx: &Ctx) -> Result<(), ExpError> {
    let plan = plan(ctx.quick);
    let scns = LOADS
        .iter()
        .map(|s| Scenario::load(s))
        .collect::<Result<Vec<_>, _>>()?;
    ctx.add_units(plan.uniform.len() + plan.graded.len() + 1);
    let (mut forest, root) = Forest::new(4, Supports::Paper)?;
    // Meshes first (the forest grows), then the runs.
    let mut families: Vec<(&'static str, Vec<(usize, Leaves)>)> = vec![];
    for (family, graded, levels) in [
        ("uniform", false, &plan.uniform),
        ("graded", true, &plan.graded),
    ] {
        let mut prev = root.clone();
        let mut list = vec![];
        for &n in levels {
            prev = level(&mut forest, &prev, n, graded);
            list.push((n, prev.clone()));
        }
        families.push((family, list));
    }
    let mut prev = families[1].1.last().expect("levels").1.clone();
    let mut n = *plan.graded.last().expect("levels");
    while n < plan.n_ref {
        n *= 2;
        prev = level(&mut forest, &prev, n, true);
    }
    let ref_leaves = prev;
    let ref_mesh = Arc::new(forest.mesh(&ref_leaves, plan.n_ref));
    let clock = std::time::Instant::now();
    let reference = solve_at_t(&scns, &ref_mesh, plan.n_ref)?;
    let ref_dofs = Dofs::new(&ref_mesh, true);
    ctx.log(&format!(
        "graded reference: {} dofs, k = 1/{} ({:.1} s)",
        ref_dofs.count,
        plan.n_ref,
        clock.elapsed().as_secs_f64()
    ));
    let g = scns[0].elasticity();
    let ref_fields: Vec<Vec<[f64; 2]>> = reference.iter().map(|u| ref_dofs.expand(u)).collect();
    let ref_norms: Vec<f64> = ref_fields
        .iter()
        .map(|u| field_norms(&ref_mesh, &g, u).energy_sq)
        .collect();
    let mut rows = vec![];
    for (family, list) in &families {
        for (n, leaves) in list {
            let clock = std::time::Instant::now();
            let mesh = Arc::new(forest.mesh(leaves, *n));
            let dofs = Dofs::new(&mesh, true);
            let fields = solve_at_t(&scns, &mesh, *n)?;
            let interp = forest.interpolation(leaves, &ref_mesh);
            let min_edge = leaves
                .0
                .iter()
                .map(|&t| forest.diameter(t))
                .fold(f64::INFINITY, f64::min);
            for (i, u) in fields.iter().enumerate() {
                let pu = interp.apply(&dofs.expand(u));
                let diff: Vec<[f64; 2]> = ref_fields[i]
                    .iter()
                    .zip(&pu)
                    .map(|(a, b)| [a[0] - b[0], a[1] - b[1]])
                    .collect();
                let e = field_norms(&ref_mesh, &g, &diff).energy_sq;
                rows.push(Row {
                    family,
                    load: scns[i].name.clone(),
                    n: *n,
                    dofs: dofs.count,
                    triangles: mesh.triangles.len(),
                    min_edge,
                    rel_err: (e / ref_norms[i]).sqrt(),
                });
            }
            ctx.log(&format!(
                "{family} level {n}: {} dofs ({:.1} s)",
                dofs.count,
                clock.elapsed().as_secs_f64()
            ));
        }
    }
    rows.sort_by(|a, b| (a.load.as_str(), a.family, a.n).cmp(&(b.load.as_str(), b.family, b.n)));
    let order: Vec<f64> = rows
        .iter()
        .enumerate()
        .map(|(i, r)| match i.checked_sub(1).map(|j| &rows[j]) {
            Some(p) if p.load == r.load && p.family == r.family => {
                -2.0 * (r.rel_err / p.rel_err).ln() / (r.dofs as f64 / p.dofs as f64).ln()
            }
            _ => f64::NAN,
        })
        .collect();
    let t = Table::new()
        .str("load", rows.iter().map(|r| r.load.clone()).collect())
        .str(
            "family",
            rows.iter().map(|r| r.family.to_string()).collect(),
        )
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
        .f64("order_dofs", order);
    let params = format!(
        "newest-vertex bisection of the n = 4 mesh; uniform: longest edge <= 2 sqrt2 / n; graded: <= D min(1, max(r, D^(1/mu))^(1-mu)) with D = 2 sqrt2 / n, mu = {MU}, r = distance of the triangle's centroid to the nearest clamp end or top corner; min_longest_edge = the shortest longest edge of the mesh; k = 1/n; reference: graded level {} ({} dofs), k = 1/{}; error: relative energy norm at t = T; order_dofs = -2 dln(err) / dln(dofs) (1 = order 1 in h for a uniform mesh)",
        plan.n_ref, ref_dofs.count, plan.n_ref
    );
    let path = ctx.write("graded_convergence.csv", &t, "graded", &params)?;
    draw(ctx, &path)
}

/// A series: label, (unknowns, error) points, colour, and whether it is graded.
type Series = (String, Vec<(f64, f64)>, RGBColor, bool);

struct GradedFig {
    series: Vec<Series>,
}

fn draw(ctx: &Ctx, path: &std::path::Path) -> Result<(), ExpError> {
    let df = read_csv(path)?;
    let (load, family) = (col_str(&df, "load")?, col_str(&df, "family")?);
    let (dofs, err) = (col_f64(&df, "dofs")?, col_f64(&df, "rel_err_T_percent")?);
    // Colour-blind-safe (Okabe–Ito): blue and vermillion by load; filled circles
    // for graded, open squares for uniform.
    let colours = [RGBColor(0, 114, 178), RGBColor(213, 94, 0)];
    let mut series = vec![];
    for (li, l) in LOADS.iter().enumerate() {
        for f in ["uniform", "graded"] {
            let pts: Vec<(f64, f64)> = (0..load.len())
                .filter(|&i| load[i] == *l && family[i] == f)
                .map(|i| (dofs[i], err[i]))
                .collect();
            series.push((format!("{l}, {f}"), pts, colours[li], f == "graded"));
        }
    }
    both(
        &ctx.figures,
        "graded_convergence",
        (900, 650),
        &GradedFig { series },
    )
}

impl Figure for GradedFig {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        let pts: Vec<(f64, f64)> = self.series.iter().flat_map(|s| s.1.clone()).collect();
        let (xmin, xmax) = pts.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
            (a.min(p.0), b.max(p.0))
        });
        let (ymin, ymax) = pts.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
            (a.min(p.1), b.max(p.1))
        });
        let keys: Vec<f64> = (1..=7)
            .map(|e| 10f64.powi(e))
            .filter(|x| *x >= xmin / 2.0 && *x <= xmax * 2.0)
            .collect();
        let mut chart = ChartBuilder::on(root)
            .caption(
                "Energy error at the final time, uniform and graded meshes",
                ("sans-serif", 22),
            )
            .margin(15)
            .x_label_area_size(60)
            .y_label_area_size(80)
            .build_cartesian_2d(
                (xmin / 1.5..xmax * 1.5).log_scale().with_key_points(keys),
                (ymin / 2.0..ymax * 2.0)
                    .log_scale()
                    .with_key_points(vec![0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0]),
            )
            .map_err(e2s)?;
        chart
            .configure_mesh()
            .x_desc("unknowns N")
            .y_desc("relative energy error at T, %")
            .x_label_formatter(&|x| format!("{x:.0e}"))
            .y_label_formatter(&|y| format!("{y}"))
            .label_style(("sans-serif", 18))
            .axis_desc_style(("sans-serif", 20))
            .draw()
            .map_err(e2s)?;
        for (label, s, c, graded) in &self.series {
            let (c, graded) = (*c, *graded);
            let style = if graded {
                c.stroke_width(3)
            } else {
                c.mix(0.8).stroke_width(2)
            };
            chart
                .draw_series(LineSeries::new(s.clone(), style))
                .map_err(e2s)?;
            let marks: Vec<_> = s.clone();
            if graded {
                chart
                    .draw_series(marks.iter().map(|&p| Circle::new(p, 6, c.filled())))
                    .map_err(e2s)?
                    .label(label.clone())
                    .legend(move |xy| circle_legend(xy, 12, c.stroke_width(3), 6, c));
            } else {
                chart
                    .draw_series(marks.iter().map(|&p| {
                        EmptyElement::at(p) + Rectangle::new([(-6, -6), (6, 6)], c.stroke_width(2))
                    }))
                    .map_err(e2s)?
                    .label(label.clone())
                    .legend(move |(x, y)| {
                        EmptyElement::at((x + 12, y))
                            + PathElement::new(vec![(-12, 0), (12, 0)], c.stroke_width(2))
                            + Rectangle::new([(-6, -6), (6, 6)], c.stroke_width(2))
                    });
            }
        }
        // Slope guides N^(-1/2) (order 1 in h) and N^(-1/4) (order 1/2), from the
        // first graded point, below the data.
        if let Some(&start) = self.series.get(1).and_then(|s| s.1.first()) {
            let guides = [
                (0.5, "N^(-1/2): order 1 in h".to_string()),
                (0.25, "N^(-1/4): order 1/2 in h".to_string()),
            ];
            slope_guides(&mut chart, &guides, start, xmax, 0.45)?;
        }
        legend(&mut chart, SeriesLabelPosition::LowerLeft, 17, 0.9)?;
        Ok(())
    }
}
