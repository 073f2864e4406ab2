//! Fig. 2: the contact law, $-\sigma_\nu$ against $u_\nu$: the nonmonotone normal
//! compliance (5.1) up to $g$, then the vertical wall of the unilateral limit (5.2),
//! where $-\sigma_\nu = p(g) + \mu$ with any $\mu \ge 0$.

use super::{Ctx, ExpError, col_f64, read_csv};
use evhi::output::csv::Table;
use evhi::output::plot::FONT;
use evhi::output::plot::okabe_ito as oi;
use evhi::output::plot::{Figure, both, e2s, legend};
use evhi::scenario::Scenario;
use plotters::prelude::*;

pub fn run(ctx: &Ctx) -> Result<(), ExpError> {
    let scn = Scenario::load("figure")?;
    let labels = Labels {
        headroom: 1.08,
        title: "Fig. 2: contact law, -σν against uν".into(),
        law: "normal compliance -σν¹ = p(uν), (5.1)".into(),
        points: "branch points 0, u¹ = 0.05, u² = 0.075, g".into(),
        params: format!(
            "law of scenario `figure` (paper (5.1)-(5.2)), g = {}",
            scn.g()
        ),
    };
    draw_in(ctx, &scn, "fig2_law", "fig2_breakpoints", &labels)
}

/// What a drawing of a law says: its title, the law's and the points' legend
/// entries, and the provenance line of its tables.
struct Labels {
    /// Room above the curve for the legend, as a factor on its largest value.
    headroom: f64,
    title: String,
    law: String,
    points: String,
    params: String,
}

/// Any scenario's law drawn as Fig. 2 draws the paper's: tables `STEM.csv` (the
/// curve and the wall) and `STEM_kinks.csv`, figure `STEM`.
pub fn draw_law(ctx: &Ctx, scn: &Scenario, stem: &str) -> Result<(), ExpError> {
    let labels = Labels {
        headroom: 1.5,
        title: format!("The law of scenario {}, -σν against uν", scn.name()),
        law: format!("normal compliance -σν¹ = p(uν) ({} law)", scn.law().kind()),
        points: match scn.law().kinks() {
            [] => "the limit g".into(),
            [k] => format!("kink of p at uν = {k} and the limit g"),
            _ => "kinks of p and the limit g".into(),
        },
        params: format!("law of scenario `{}`, g = {}", scn.name(), scn.g()),
    };
    draw_in(ctx, scn, stem, &format!("{stem}_kinks"), &labels)
}

/// The law of `scn` into the tables `STEM.csv` (curve and wall) and `POINTS.csv`
/// (kinks and g), drawn as figure `STEM`.
fn draw_in(
    ctx: &Ctx,
    scn: &Scenario,
    stem: &str,
    points: &str,
    labels: &Labels,
) -> Result<(), ExpError> {
    let g = scn.g();
    // The law's own polyline: for a piecewise-affine law its vertices (both sides of
    // a jump), for a smooth one samples.
    let lo = -0.025;
    let (mut u, mut sig): (Vec<f64>, Vec<f64>) = scn.law().polyline(lo, g).into_iter().unzip();
    let mut part = vec!["compliance".to_string(); u.len()];
    // The wall at g: -sigma_nu takes every value above p(g).
    let top = 2.0 * scn.law().p(g).max(1.0);
    for v in [scn.law().p(g), top] {
        u.push(g);
        sig.push(v);
        part.push("unilateral".to_string());
    }
    let mut bp_u = scn.law().kinks().to_vec();
    bp_u.push(g);
    let bp_s: Vec<f64> = bp_u.iter().map(|&s| scn.law().p(s)).collect();
    let table = Table::new()
        .f64("u_nu", u)
        .f64("minus_sigma_nu", sig)
        .str("part", part);
    let path = ctx.write(&format!("{stem}.csv"), &table, &labels.params)?;
    let bp = Table::new().f64("u_nu", bp_u).f64("minus_sigma_nu", bp_s);
    let bp_path = ctx.write(&format!("{points}.csv"), &bp, &labels.params)?;
    // Draw from the CSVs.
    let df = read_csv(&path)?;
    let bdf = read_csv(&bp_path)?;
    let fig = Fig2 {
        u: col_f64(&df, "u_nu")?,
        s: col_f64(&df, "minus_sigma_nu")?,
        part: super::col_str(&df, "part")?,
        bu: col_f64(&bdf, "u_nu")?,
        bs: col_f64(&bdf, "minus_sigma_nu")?,
        g,
        headroom: labels.headroom,
        title: labels.title.clone(),
        law_label: labels.law.clone(),
        points_label: labels.points.clone(),
    };
    Ok(both(&ctx.figures, stem, (900, 600), &fig)?)
}

struct Fig2 {
    u: Vec<f64>,
    s: Vec<f64>,
    part: Vec<String>,
    bu: Vec<f64>,
    bs: Vec<f64>,
    g: f64,
    headroom: f64,
    title: String,
    law_label: String,
    points_label: String,
}

impl Figure for Fig2 {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        let ymax = self.s.iter().fold(0.0f64, |a, &b| a.max(b)) * self.headroom;
        let xmin = self.u.iter().fold(0.0f64, |a, &b| a.min(b));
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, (FONT, 26))
            .margin(15)
            .x_label_area_size(50)
            .y_label_area_size(70)
            .build_cartesian_2d(xmin..self.g * 1.12, -1.0..ymax)
            .map_err(e2s)?;
        chart
            .configure_mesh()
            .x_desc("normal displacement uν [m]")
            .y_desc("-σν [N/m]")
            .label_style((FONT, 18))
            .draw()
            .map_err(e2s)?;
        let comp: Vec<(f64, f64)> = self
            .u
            .iter()
            .zip(&self.s)
            .zip(&self.part)
            .filter(|(_, p)| *p == "compliance")
            .map(|((&u, &s), _)| (u, s))
            .collect();
        let wall: Vec<(f64, f64)> = self
            .u
            .iter()
            .zip(&self.s)
            .zip(&self.part)
            .filter(|(_, p)| *p == "unilateral")
            .map(|((&u, &s), _)| (u, s))
            .collect();
        chart
            .draw_series(LineSeries::new(comp, oi::BLUE.stroke_width(3)))
            .map_err(e2s)?
            .label(self.law_label.clone())
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], oi::BLUE.stroke_width(3)));
        chart
            .draw_series(LineSeries::new(wall, oi::VERMILLION.stroke_width(3)))
            .map_err(e2s)?
            .label(format!(
                "unilateral limit uν = g = {} (5.2): -σν² ≥ 0",
                self.g
            ))
            .legend(|(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], oi::VERMILLION.stroke_width(3))
            });
        chart
            .draw_series(
                self.bu
                    .iter()
                    .zip(&self.bs)
                    .map(|(&u, &s)| Circle::new((u, s), 6, BLACK.filled())),
            )
            .map_err(e2s)?
            .label(self.points_label.clone())
            .legend(|(x, y)| Circle::new((x + 10, y), 5, BLACK.filled()));
        legend(&mut chart, SeriesLabelPosition::UpperLeft, 18, 0.9)?;
        Ok(())
    }
}
