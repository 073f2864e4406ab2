//! The static control of Table 1: the paper's geometry and supports, linear
//! elasticity only (no contact, no time: the steady state $Bu = f$), on the uniform
//! family up to $n = 1/h = 1024$. No reference solution is needed. The spaces are nested
//! and $u_h$ is the $B$-orthogonal projection of $u$, so
//! $$\|u - u_h\|_E^2 = \|u\|_E^2 - \|u_h\|_E^2, \qquad \|u_{h/2} - u_h\|_E^2 = \|u_{h/2}\|_E^2 - \|u_h\|_E^2,$$
//! with $\|u_h\|_E^2 = \tfrac12 u_h^\top B u_h = \tfrac12 f^\top u_h$. The differences give the
//! observed order directly; $\|u\|_E^2$ is extrapolated from the last three levels.
//! (Exactly so for loads that do not depend on the mesh; `smooth`'s body force is
//! sampled at the vertices, so for it the identities hold up to $O(h^2)$.)
//!
//! The observed orders are set against the corner exponents of the Lamé system: near a
//! corner of opening $\omega$ the solution behaves like $r^\lambda$, with $\lambda$ the
//! smallest root with positive real part of the corner's characteristic equation
//! ([`wedge_exponents`]); on uniform meshes the energy error then decays like
//! $h^{\operatorname{Re}\lambda}$ when $\operatorname{Re}\lambda < 1$.

use super::{Ctx, ExpError, col_f64, col_str, read_csv};
use evhi::assembly::stiffness;
use evhi::linalg::Cholesky;
use evhi::mesh::Dofs;
use evhi::ordering::Ordering;
use evhi::output::csv::Table;
use evhi::output::plot::okabe_ito as oi;
use evhi::output::plot::{
    Figure, LogLogChart, both, circle_legend, e2s, extent, legend, one_two_five, slope_guides,
};
use evhi::scenario::Scenario;
pub use evhi::study::corners::{Edge, clamp_end_exponent, wedge_exponents};
use plotters::prelude::*;

/// The scenarios of the control: the paper's supports with both loads, and `smooth`.
pub const SCENARIOS: [&str; 3] = ["literal", "figure", "smooth"];

/// Per scenario and level: $\|u_h\|_E^2$. Scenarios on the same mesh with the same
/// elasticity share each level's factorisation of $B$ (one factor, a solve per
/// load), which is all the work at the finest levels.
fn energies(scns: &[Scenario], levels: &[usize], ctx: &Ctx) -> Result<Vec<Vec<f64>>, ExpError> {
    ctx.add_units(levels.len() * scns.len());
    // Groups of scenarios with one mesh and one elasticity; one factor alive at a time.
    let mut groups: Vec<Vec<usize>> = vec![];
    for (i, scn) in scns.iter().enumerate() {
        let same = |j: &usize| {
            let o = &scns[*j];
            o.geometry() == scn.geometry()
                && o.pattern() == scn.pattern()
                && (o.e(), o.kappa()) == (scn.e(), scn.kappa())
        };
        match groups.iter_mut().find(|g| same(&g[0])) {
            Some(g) => g.push(i),
            None => groups.push(vec![i]),
        }
    }
    let mut out = vec![vec![]; scns.len()];
    for &n in levels {
        evhi::scheme::check_memory(n, n / 2)?;
        for group in &groups {
            let first = &scns[group[0]];
            let mesh = first.mesh(n)?;
            let dofs = Dofs::new(&mesh, true);
            let b = stiffness(&mesh, &dofs, &first.elasticity());
            let cdofs: Vec<usize> = mesh
                .contact
                .iter()
                .map(|&c| dofs.of(c, 1).expect("contact nodes are free"))
                .collect();
            let order = Ordering::nested_dissection(&mesh, &dofs, &cdofs);
            let chol = Cholesky::factor(&b, &order).map_err(|e| {
                ExpError::File(evhi::output::FileError::Table {
                    path: "static_control".into(),
                    message: e.to_string(),
                })
            })?;
            for &i in group {
                ctx.log(&format!("static control: {} n = {n}", scns[i].name()));
                let f = scns[i].load_vector(&mesh, &dofs);
                let u = chol.solve(&f);
                out[i].push(0.5 * f.iter().zip(&u).map(|(a, b)| a * b).sum::<f64>());
            }
        }
    }
    Ok(out)
}

pub fn levels(quick: bool) -> Vec<usize> {
    if quick {
        vec![4, 8, 16, 32, 64, 128]
    } else {
        vec![4, 8, 16, 32, 64, 128, 256, 512, 1024]
    }
}

pub fn run(ctx: &Ctx) -> Result<(), ExpError> {
    let levels = levels(ctx.quick);
    let paper = Scenario::load("literal")?;
    let nu = paper.kappa();
    let kappa_m = 3.0 - 4.0 * nu;
    let (re_end, im_end) = clamp_end_exponent(kappa_m);
    let top = wedge_exponents(
        std::f64::consts::FRAC_PI_2,
        kappa_m,
        [Edge::Clamped, Edge::Free],
    );
    let lambda_top = top.first().copied().unwrap_or(f64::NAN);
    let mut t = Table::new();
    let (mut sc, mut ns, mut es, mut ds, mut od, mut errs, mut oe, mut e512) = (
        vec![],
        vec![],
        vec![],
        vec![],
        vec![],
        vec![],
        vec![],
        vec![],
    );
    let scns = SCENARIOS
        .iter()
        .map(|name| Scenario::load(name))
        .collect::<Result<Vec<_>, _>>()?;
    let all = energies(&scns, &levels, ctx)?;
    for (name, e) in SCENARIOS.iter().zip(all) {
        let l = e.len();
        // Differences to the next finer level: ||u_{h/2} - u_h||_E^2.
        let d: Vec<f64> = (0..l)
            .map(|i| if i + 1 < l { e[i + 1] - e[i] } else { f64::NAN })
            .collect();
        // Aitken's extrapolation of ||u||_E^2 from the last three levels.
        let r = d[l - 2] / d[l - 3];
        let e_inf = e[l - 1] + d[l - 2] * r / (1.0 - r);
        // Table 1's measure: against the n = 512 solution instead of u.
        let at_512 = levels.iter().position(|&n| n == 512).map(|j| e[j]);
        for i in 0..l {
            sc.push(name.to_string());
            ns.push(levels[i] as u64);
            es.push(e[i]);
            ds.push(d[i].sqrt() / e_inf.sqrt());
            od.push(if i >= 1 && i + 1 < l {
                0.5 * (d[i - 1] / d[i]).log2()
            } else {
                f64::NAN
            });
            errs.push(((e_inf - e[i]).max(0.0) / e_inf).sqrt());
            e512.push(match at_512 {
                Some(r) if levels[i] < 512 => ((r - e[i]) / r).sqrt(),
                _ => f64::NAN,
            });
            oe.push(if i >= 1 {
                0.5 * ((e_inf - e[i - 1]) / (e_inf - e[i])).log2()
            } else {
                f64::NAN
            });
        }
    }
    t = t
        .str("scenario", sc)
        .u64("n", ns)
        .f64("energy_sq", es)
        .f64("rel_diff_next", ds)
        .f64("order_diff", od)
        .f64("rel_err_extrapolated", errs)
        .f64("order_err", oe)
        .f64("rel_err_vs_n512", e512);
    let params = format!(
        "steady state B u = f (no contact, no time), P1 on the uniform family n = 1/h; energy_sq = ||u_h||_E^2 = f.u_h/2; \
         rel_diff_next = ||u_(h/2) - u_h||_E / ||u||_E (Galerkin orthogonality, nested spaces; up to O(h^2) for smooth's vertex-sampled load); order_diff = observed order of \
         the differences between successive rows; rel_err_extrapolated = ||u - u_h||_E / ||u||_E with ||u||_E^2 from Aitken's \
         extrapolation of the last three levels; rel_err_vs_n512 = ||u_512 - u_h||_E / ||u_512||_E, Table 1's measure; exponents (plane strain, kappa_M = 3 - 4 kappa = {kappa_m}): clamp end on a straight \
         edge lambda = {re_end} + {im_end:.5} i; clamped top corner (pi/2, clamped-free) lambda = {lambda_top:.5}"
    );
    let path = ctx.write("static_control.csv", &t, &params)?;
    write_markdown(ctx, &path)?;
    draw(ctx, &path, re_end, lambda_top)
}

/// `data/static_control.md`: the differences and their orders, for the book.
fn write_markdown(ctx: &Ctx, path: &std::path::Path) -> Result<(), ExpError> {
    use super::time::sig3;
    let df = read_csv(path)?;
    let (sc, n) = (col_str(&df, "scenario")?, col_f64(&df, "n")?);
    let (d, o, e512) = (
        col_f64(&df, "rel_diff_next")?,
        col_f64(&df, "order_diff")?,
        col_f64(&df, "rel_err_vs_n512")?,
    );
    let mut md = format!(
        "<!-- {} -->\n\n",
        ctx.provenance(ctx.experiment, "").join(" ")
    );
    md += "Relative energy norm of the difference to the next level, \
           ‖u<sub>2n</sub> − u<sub>n</sub>‖<sub>E</sub> / ‖u‖<sub>E</sub> in percent (observed order; \
           from the energies, exact for `literal` and `figure`, up to O(h²) for `smooth`), \
           and `literal` measured as Table 1 measures (against n = 512).\n\n\
           | n | `literal` | `figure` | `smooth` | `literal` against n = 512 |\n|---|---|---|---|---|\n";
    let levels: Vec<f64> = (0..sc.len())
        .filter(|&i| sc[i] == SCENARIOS[0] && d[i].is_finite())
        .map(|i| n[i])
        .collect();
    for &level in &levels {
        let mut row = format!("| {level} |");
        for s in SCENARIOS {
            let i = (0..sc.len())
                .find(|&i| sc[i] == s && n[i] == level)
                .expect("every level");
            row += &if !d[i].is_finite() {
                " – |".to_string()
            } else if o[i].is_finite() {
                format!(" {} ({:.2}) |", sig3(100.0 * d[i]), o[i])
            } else {
                format!(" {} |", sig3(100.0 * d[i]))
            };
        }
        let i = (0..sc.len())
            .find(|&i| sc[i] == SCENARIOS[0] && n[i] == level)
            .expect("level");
        row += &format!(
            " {} |\n",
            if e512[i].is_finite() {
                sig3(100.0 * e512[i])
            } else {
                "–".into()
            }
        );
        md += &row;
    }
    ctx.write_file(&ctx.data_path("static_control.md"), md.as_bytes())
}

/// A plotted series: label, points, colour.
type Series = (String, Vec<(f64, f64)>, RGBColor);

struct StaticFig {
    series: Vec<Series>,
    guides: Vec<(f64, String)>,
}

fn draw(
    ctx: &Ctx,
    path: &std::path::Path,
    lambda_end: f64,
    lambda_top: f64,
) -> Result<(), ExpError> {
    let df = read_csv(path)?;
    let (sc, n, d) = (
        col_str(&df, "scenario")?,
        col_f64(&df, "n")?,
        col_f64(&df, "rel_diff_next")?,
    );
    let colours = [oi::VERMILLION, oi::BLUE, oi::BLUISH_GREEN];
    let series = SCENARIOS
        .iter()
        .zip(colours)
        .map(|(s, c)| {
            let pts = (0..sc.len())
                .filter(|&i| sc[i] == *s && d[i].is_finite() && d[i] > 0.0)
                .map(|i| (n[i], 100.0 * d[i]))
                .collect();
            (format!("{s}: ||u_h/2 - u_h||_E / ||u||_E"), pts, c)
        })
        .collect();
    let fig = StaticFig {
        series,
        guides: vec![
            (lambda_end, format!("slope -{lambda_end} (clamp end)")),
            (lambda_top, format!("slope -{lambda_top:.3} (top corner)")),
            (1.0, "slope -1 (smooth)".into()),
        ],
    };
    Ok(both(&ctx.figures, "static_control", (900, 700), &fig)?)
}

impl Figure for StaticFig {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        let pts: Vec<(f64, f64)> = self
            .series
            .iter()
            .flat_map(|s| s.1.iter().copied())
            .collect();
        let ((_, xmax), (ymin, ymax)) = extent(&pts);
        let keys: Vec<f64> = (2..=12)
            .map(|e| 2f64.powi(e))
            .filter(|x| *x <= xmax)
            .collect();
        let ykeys = one_two_five((ymin / 3.0, ymax * 2.5), -6..=3);
        let mut chart = LogLogChart {
            caption: ("Static control: the paper's supports, no contact", 26),
            label_areas: (60, 90),
            desc: (
                "n = 1/h (the difference to the next level, 2n)",
                "relative energy norm of the difference, %",
            ),
            format: (
                Some(&|x| format!("{}", x.round())),
                Some(&|y| format!("{y}")),
            ),
            ..LogLogChart::default()
        }
        .build(
            root,
            (3.0..xmax * 1.3).log_scale().with_key_points(keys),
            (ymin / 3.0..ymax * 2.5).log_scale().with_key_points(ykeys),
        )?;
        for (label, s, c) in &self.series {
            let c = *c;
            chart
                .draw_series(LineSeries::new(s.clone(), c.stroke_width(3)))
                .map_err(e2s)?;
            chart
                .draw_series(s.iter().map(|&p| Circle::new(p, 6, c.filled())))
                .map_err(e2s)?
                .label(label.clone())
                .legend(move |xy| circle_legend(xy, 12, c.stroke_width(3), 6, c));
        }
        // Slope guides through the first point of the first series, below it.
        if let Some(&start) = self.series.first().and_then(|s| s.1.first()) {
            slope_guides(
                &mut chart,
                &self.guides,
                &evhi::output::plot::DISTINCT_DASHES,
                start,
                xmax,
                0.5,
            )?;
        }
        legend(&mut chart, SeriesLabelPosition::UpperRight, 18, 0.9)?;
        Ok(())
    }
}
