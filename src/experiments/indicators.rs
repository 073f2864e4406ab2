//! Where the residual estimator puts the error: each triangle's indicator
//! $\bar\eta_T = (\max_n \eta^2_{T,n})^{1/2}$ on one uniform mesh of the adaptive study,
//! per scene, as a table (`adaptive_indicators.csv`) and a figure
//! (`adaptive_indicators`): the triangles coloured by $\bar\eta_T / \max_T\bar\eta_T$ on a
//! log scale over [`DECADES`] decades, each scene against its own largest.

use super::{Ctx, ExpError};
use evhi::output::csv::{Table, col_f64, col_str, read_csv};
use evhi::output::plot::{FONT, Figure, both, e2s, viridis};
use plotters::prelude::*;

/// The decades of $\bar\eta_T / \max_T\bar\eta_T$ the colours span; smaller ones take the
/// darkest colour.
pub const DECADES: f64 = 3.0;

/// One scene's mesh and indicators: its name, each triangle's vertices, $\bar\eta_T$.
pub type Shown = (String, Vec<[[f64; 2]; 3]>, Vec<f64>);

/// Writes `adaptive_indicators.csv` for `scenes` (the uniform mesh of `n` segments,
/// `steps` steps) and draws its figure from it.
pub fn write(ctx: &Ctx, n: usize, steps: usize, scenes: &[Shown]) -> Result<(), ExpError> {
    let mut name = vec![];
    let mut v: [Vec<f64>; 7] = Default::default();
    for (scn, tris, eta) in scenes {
        for (t, e) in tris.iter().zip(eta) {
            name.push(scn.clone());
            for (c, col) in v.iter_mut().take(6).enumerate() {
                col.push(t[c / 2][c % 2]);
            }
            v[6].push(*e);
        }
    }
    let [x0, y0, x1, y1, x2, y2, eta] = v;
    let table = Table::new()
        .str("scenario", name)
        .f64("x0", x0)
        .f64("y0", y0)
        .f64("x1", x1)
        .f64("y1", y1)
        .f64("x2", x2)
        .f64("y2", y2)
        .f64("eta", eta);
    let path = ctx.write(
        "adaptive_indicators.csv",
        &table,
        &format!(
            "the uniform mesh n = {n} of adaptive_convergence.csv (longest edge <= 2 sqrt2 / n), {steps} steps, per scene: one row a triangle, its vertices (x0, y0), (x1, y1), (x2, y2) and its indicator eta = (max over the steps of eta_T,n^2)^(1/2) (evhi::estimator, absolute)"
        ),
    )?;
    draw(&ctx.figures, &path, n)
}

fn draw(dir: &std::path::Path, path: &std::path::Path, n: usize) -> Result<(), ExpError> {
    let df = read_csv(path)?;
    let scn = col_str(&df, "scenario")?;
    let c: Vec<Vec<f64>> = (0..6)
        .map(|k| col_f64(&df, &format!("{}{}", ["x", "y"][k % 2], k / 2)))
        .collect::<Result<_, _>>()?;
    let eta = col_f64(&df, "eta")?;
    let mut panels: Vec<Shown> = vec![];
    for i in 0..scn.len() {
        if panels.last().is_none_or(|p| p.0 != scn[i]) {
            panels.push((scn[i].clone(), vec![], vec![]));
        }
        let p = panels.last_mut().expect("pushed");
        p.1.push([[c[0][i], c[1][i]], [c[2][i], c[3][i]], [c[4][i], c[5][i]]]);
        p.2.push(eta[i]);
    }
    Ok(both(
        dir,
        "adaptive_indicators",
        (1500, 1700),
        &Fig { panels, n },
    )?)
}

struct Fig {
    panels: Vec<Shown>,
    n: usize,
}

impl Figure for Fig {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        let (maps, bar) = root.split_vertically(1540);
        let areas = maps.split_evenly((self.panels.len().max(1), 1));
        for (k, (area, (name, tris, eta))) in areas.iter().zip(&self.panels).enumerate() {
            let top = eta.iter().copied().fold(0.0, f64::max);
            let caption = format!(
                "({}) {name}: indicators on the uniform mesh n = {}, {} triangles",
                (b'a' + k as u8) as char,
                self.n,
                tris.len()
            );
            let mut chart = ChartBuilder::on(area)
                .caption(caption, (FONT, 26))
                .margin(16)
                .build_cartesian_2d(0.0..2.0, 0.0..1.0)
                .map_err(e2s)?;
            chart
                .draw_series(tris.iter().zip(eta).map(|(t, &e)| {
                    let s = ((e / top).log10() + DECADES) / DECADES;
                    Polygon::new(
                        t.iter().map(|p| (p[0], p[1])).collect::<Vec<_>>(),
                        viridis(s).filled(),
                    )
                }))
                .map_err(e2s)?;
        }
        // The colour bar: log10 of the indicator over the scene's largest.
        let mut chart = ChartBuilder::on(&bar)
            .margin_left(60)
            .margin_right(60)
            .margin_bottom(10)
            .x_label_area_size(70)
            .build_cartesian_2d(-DECADES..0.0, 0.0..1.0)
            .map_err(e2s)?;
        chart
            .configure_mesh()
            .disable_y_axis()
            .disable_mesh()
            .x_labels(DECADES as usize + 1)
            .x_label_formatter(&|x| format!("{x:.0}"))
            .x_desc("log10 of the indicator over its largest in the panel")
            .label_style((FONT, 24))
            .axis_desc_style((FONT, 26))
            .draw()
            .map_err(e2s)?;
        let steps = 200;
        chart
            .draw_series((0..steps).map(|i| {
                let (a, b) = (i as f64 / steps as f64, (i + 1) as f64 / steps as f64);
                Rectangle::new(
                    [(-DECADES * (1.0 - a), 0.0), (-DECADES * (1.0 - b), 1.0)],
                    viridis(a).filled(),
                )
            }))
            .map_err(e2s)?;
        Ok(())
    }
}
