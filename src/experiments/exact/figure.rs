//! The exact-solution study's figures, drawn from its CSV tables: the errors of every
//! family against the truth, the Céa terms of (b), and the regimes (b) visits.

use crate::experiments::{Ctx, ExpError, col_f64, col_str, read_csv};
use evhi::manufactured::run::REGIMES;
use evhi::output::plot::FONT;
use evhi::output::plot::okabe_ito as oi;
use evhi::output::plot::{
    Figure, LogLogChart, both, e2s, extent, fit_title, legend, regime_colour, regime_label,
    slope_guides,
};
use evhi::output::plot::{GREY, GREY_DARK, viridis};
use plotters::prelude::*;
use std::path::Path;

/// A labelled, coloured series of points.
type Series = (String, Vec<(f64, f64)>, RGBColor);

/// A log–log chart of several series with slope guides.
struct LogLog {
    title: String,
    x_desc: String,
    y_desc: String,
    series: Vec<Series>,
    /// (slope, label) of each dashed guide, drawn through the first series' start.
    guides: Vec<(f64, String)>,
    /// Where the legend goes.
    legend_at: SeriesLabelPosition,
    /// The top of the y axis over the largest value (room for a legend at the top).
    headroom: f64,
    /// Font sizes: caption, tick labels and axis descriptions, legend.
    fonts: (u32, u32, u32),
    /// The marker of each series ([`shape`]); empty: `first_marker + i` for series `i`.
    markers: Vec<usize>,
    /// Series drawn [`nested`], each narrower than the one before.
    nested: bool,
}

/// The outline of marker `i` in pixels around its centre: circle, triangle, square,
/// diamond, inverted triangle, hexagon; `scale` times the usual size.
fn shape(i: usize, scale: f64) -> Vec<(i32, i32)> {
    let poly = |k: usize, r: f64, phase: f64| -> Vec<(i32, i32)> {
        (0..k)
            .map(|j| {
                let a = phase + std::f64::consts::TAU * j as f64 / k as f64;
                ((r * a.cos()).round() as i32, (-r * a.sin()).round() as i32)
            })
            .collect()
    };
    use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, SQRT_2};
    let s = scale;
    match i % 6 {
        0 => poly(16, 6.0 * s, 0.0),
        1 => poly(3, 8.0 * s, FRAC_PI_2),
        2 => poly(4, 6.0 * SQRT_2 * s, FRAC_PI_4),
        3 => poly(4, 8.0 * s, 0.0),
        4 => poly(3, 8.0 * s, -FRAC_PI_2),
        _ => poly(6, 7.0 * s, 0.0),
    }
}

/// Marker `i` at `at` with a line of `half` pixels each side in the series' colour (0
/// in the plot, 12 in the legend), so the legend shows what the plot draws.
fn marker<C, DB: DrawingBackend>(i: usize, at: C, c: RGBColor, half: i32) -> Marker<C, DB> {
    sized_marker(i, at, c, half, (1.0, 3))
}

/// [`marker`] at `size` = (scale of the shape, width of the line).
fn sized_marker<C, DB: DrawingBackend>(
    i: usize,
    at: C,
    c: RGBColor,
    half: i32,
    (scale, width): (f64, u32),
) -> Marker<C, DB> {
    EmptyElement::at(at)
        + PathElement::new(vec![(-half, 0), (half, 0)], c.stroke_width(width))
        + Polygon::new(shape(i, scale), c.filled())
}

/// The size of series `i` of a panel whose series may coincide (a family with no space
/// error beside one with no time error): the first drawn widest, each later one
/// narrower on top of it, so that every one shows.
fn nested(i: usize, of: usize) -> (f64, u32) {
    if of < 2 {
        return (1.0, 3);
    }
    [(1.7, 7), (1.0, 3), (0.6, 2), (0.6, 2)][i.min(3)]
}

type Marker<C, DB> =
    plotters::element::ComposedElement<C, DB, PathElement<(i32, i32)>, Polygon<(i32, i32)>>;

impl LogLog {
    /// Draws into `area`; series `i` gets the marker [`marker`] of `first_marker + i`.
    fn draw_on<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, plotters::coord::Shift>,
        first_marker: usize,
    ) -> Result<(), String> {
        let pts: Vec<(f64, f64)> = self
            .series
            .iter()
            .flat_map(|s| s.1.iter().copied())
            .collect();
        let ((xmin, xmax), (ymin, ymax)) = extent(&pts);
        let keys: Vec<f64> = (0..=13)
            .map(|e| 2f64.powi(e))
            .filter(|x| *x >= xmin && *x <= xmax)
            .collect();
        let (ylo, yhi) = (ymin / 3.0, ymax * self.headroom);
        // Over a few decades the axis reads 1, 2, 5 in plain numbers; over many, the
        // powers of ten.
        let few = yhi / ylo < 1e4;
        let ykeys: Vec<f64> = if few {
            evhi::output::plot::one_two_five((ylo, yhi), -16..=3)
        } else {
            (-16..=3)
                .map(|e| 10f64.powi(e))
                .filter(|&y| y >= ylo && y <= yhi)
                .collect()
        };
        let plain = |y: &f64| evhi::output::plot::plain(y);
        let power = |y: &f64| evhi::output::plot::power_of_ten(y);
        let (cap, tick, _) = self.fonts;
        let mut chart = LogLogChart {
            caption: (&self.title, cap),
            label_areas: (60, 90),
            desc: (&self.x_desc, &self.y_desc),
            format: (
                Some(&|x| format!("{}", x.round())),
                Some(if few { &plain } else { &power }),
            ),
            fonts: (tick, Some(tick)),
            ..LogLogChart::default()
        }
        .build(
            area,
            (xmin / 1.3..xmax * 1.3).log_scale().with_key_points(keys),
            (ylo..yhi).log_scale().with_key_points(ykeys),
        )?;
        let of = if self.nested { self.series.len() } else { 1 };
        for (i, (label, s, c)) in self.series.iter().enumerate() {
            let m = self.markers.get(i).copied().unwrap_or(first_marker + i);
            let (c, size) = (*c, nested(i, of));
            chart
                .draw_series(LineSeries::new(s.clone(), c.stroke_width(size.1)))
                .map_err(e2s)?;
            chart
                .draw_series(
                    s.iter()
                        .map(|&p| sized_marker::<(f64, f64), DB>(m, p, c, 0, size)),
                )
                .map_err(e2s)?
                .label(label.clone())
                .legend(move |(x, y)| sized_marker::<(i32, i32), DB>(m, (x + 12, y), c, 12, size));
        }
        if let Some(&start) = self.series.first().and_then(|s| s.1.first()) {
            slope_guides(
                &mut chart,
                &self.guides,
                &evhi::output::plot::EXACT_DASHES,
                start,
                xmax,
                0.4,
            )?;
        }
        legend(&mut chart, self.legend_at.clone(), self.fonts.2, 0.9)?;
        Ok(())
    }
}

impl Figure for LogLog {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        self.draw_on(root, 0)
    }
}

/// Small multiples: one log–log chart per solution, in rows of two, and a last panel
/// for the share of $\Gamma_3 \times (0, T)$ at $g$.
struct Panels {
    charts: Vec<LogLog>,
    share: Share,
}

impl Figure for Panels {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        let rows = (self.charts.len() + 2) / 2;
        let cells = root.split_evenly((rows, 2));
        for (area, chart) in cells.iter().zip(&self.charts) {
            chart.draw_on(area, 0)?;
        }
        match cells.get(self.charts.len()) {
            Some(area) => self.share.draw(area),
            None => Ok(()),
        }
    }
}

/// The share of $\Gamma_3 \times (0, T)$ at $g$ against the level, in percent, with the
/// exact share as a dashed line.
struct Share {
    title: String,
    series: Vec<Series>,
    exact: f64,
    fonts: (u32, u32, u32),
}

impl Figure for Share {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        let pts: Vec<(f64, f64)> = self
            .series
            .iter()
            .flat_map(|s| s.1.iter().copied())
            .collect();
        let ((xmin, xmax), _) = extent(&pts);
        let keys: Vec<f64> = (0..=10)
            .map(|e| 2f64.powi(e))
            .filter(|x| *x >= xmin && *x <= xmax)
            .collect();
        let (cap, tick, leg) = self.fonts;
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, (FONT, cap))
            .margin(15)
            .x_label_area_size(60)
            .y_label_area_size(90)
            .build_cartesian_2d(
                (xmin / 1.3..xmax * 1.3).log_scale().with_key_points(keys),
                0.0..1.4 * self.exact,
            )
            .map_err(e2s)?;
        chart
            .configure_mesh()
            .x_desc("mesh n (h = 1/n) or steps N (k = T/N)")
            .y_desc("share of Γ3 × (0, T) at g (%)")
            .x_label_formatter(&|x| format!("{}", x.round()))
            .y_label_formatter(&|y| format!("{y:.0}"))
            .label_style((FONT, tick))
            .axis_desc_style((FONT, tick))
            .draw()
            .map_err(e2s)?;
        let grey = GREY_DARK;
        let (dash, gap) = evhi::output::plot::EXACT_DASHES[0];
        chart
            .draw_series(DashedLineSeries::new(
                vec![(xmin / 1.3, self.exact), (xmax * 1.3, self.exact)],
                dash as u32,
                gap as u32,
                grey.stroke_width(2),
            ))
            .map_err(e2s)?
            .label(format!("exact: {} %", self.exact))
            .legend(move |xy| {
                evhi::output::plot::dashed_legend(xy, dash, gap, grey.stroke_width(2))
            });
        for (i, (label, s, c)) in self.series.iter().enumerate() {
            let c = *c;
            chart
                .draw_series(LineSeries::new(s.clone(), c.stroke_width(3)))
                .map_err(e2s)?;
            chart
                .draw_series(s.iter().map(|&p| marker::<(f64, f64), DB>(i, p, c, 0)))
                .map_err(e2s)?
                .label(label.clone())
                .legend(move |(x, y)| marker::<(i32, i32), DB>(i, (x + 12, y), c, 12));
        }
        legend(&mut chart, SeriesLabelPosition::LowerRight, leg, 0.9)?;
        Ok(())
    }
}

/// Contact nodes per regime against time.
struct Regimes {
    title: String,
    /// (regime, points (t, count)).
    series: Vec<(String, Vec<(f64, f64)>)>,
    /// The top of the y axis.
    top: f64,
}

impl Figure for Regimes {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, (FONT, 24))
            .margin(15)
            .x_label_area_size(55)
            .y_label_area_size(70)
            .build_cartesian_2d(0.0..1.0, 0.0..self.top)
            .map_err(e2s)?;
        chart
            .configure_mesh()
            .x_desc("t")
            .y_desc("contact nodes")
            .light_line_style(TRANSPARENT)
            .y_label_formatter(&|y| format!("{y:.0}"))
            .label_style((FONT, 18))
            .axis_desc_style((FONT, 18))
            .draw()
            .map_err(e2s)?;
        for (regime, pts) in &self.series {
            let c = regime_colour(regime);
            chart
                .draw_series(LineSeries::new(pts.clone(), c.stroke_width(3)))
                .map_err(e2s)?
                .label(regime_label(regime))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 24, y)], c.stroke_width(3))
                });
        }
        legend(&mut chart, SeriesLabelPosition::UpperRight, 15, 0.9)?;
        Ok(())
    }
}

/// The families of a solution in the order its panel lists them, each with its colour
/// and marker, the same in every panel.
const FAMILIES: [(&str, RGBColor, usize); 4] = [
    ("h=k", oi::BLUE, 0),
    ("h", oi::ORANGE, 2),
    ("k", oi::VERMILLION, 1),
    ("k_on_step", oi::BLUISH_GREEN, 3),
];

/// Font sizes of the convergence figure's panels: caption, ticks and axis
/// descriptions, legend (the figure is 1200 pixels wide, shown at about 750).
const PANEL_FONTS: (u32, u32, u32) = (24, 20, 20);

/// The panel of `exact_hold.csv`'s family: (i)'s largest error on the hold, with the
/// exact compliance integral, with the limit and without it, and with the nodal rule.
fn hold_panel(hold: &Path) -> Result<LogLog, ExpError> {
    let df = read_csv(hold)?;
    let (sol, limit, rule, steps, err) = (
        col_str(&df, "solution")?,
        col_str(&df, "limit")?,
        col_str(&df, "rule")?,
        col_f64(&df, "steps")?,
        col_f64(&df, "rel_err_hold_percent")?,
    );
    let n = col_f64(&df, "n")?.first().copied().unwrap_or(0.0);
    let pick = |l: &str, r: &str| -> Vec<(f64, f64)> {
        (0..sol.len())
            .filter(|&i| sol[i] == "hold" && limit[i] == l && rule[i] == r)
            .map(|i| (steps[i], err[i]))
            .collect()
    };
    Ok(LogLog {
        title: format!("{}: on the hold only, n = {n}", label_of("hold")),
        x_desc: "time steps N (k = T/N)".into(),
        y_desc: "largest relative error on the hold (%)".into(),
        series: vec![
            (
                "k, exact integral".into(),
                pick("on", "exact"),
                FAMILIES[2].1,
            ),
            ("k, nodal rule".into(), pick("on", "nodal"), oi::BLUE),
            (
                "k, exact integral, no limit".into(),
                pick("removed", "exact"),
                GREY,
            ),
        ],
        guides: vec![(1.0, "slope −1".into())],
        legend_at: SeriesLabelPosition::LowerLeft,
        headroom: 1.5,
        fonts: PANEL_FONTS,
        markers: vec![1, 0, 4],
        nested: true,
    })
}

fn label_of(sol: &str) -> &'static str {
    evhi::manufactured::SOLUTIONS
        .iter()
        .find(|s| s.name() == sol)
        .map_or("?", |s| s.label())
}

pub fn draw_all(
    ctx: &Ctx,
    conv: &Path,
    cea: &Path,
    regimes: &Path,
    hold: &Path,
) -> Result<(), ExpError> {
    // Errors of every family, one panel per solution.
    let df = read_csv(conv)?;
    let (sol, fam, n, steps, err, share) = (
        col_str(&df, "solution")?,
        col_str(&df, "family")?,
        col_f64(&df, "n")?,
        col_f64(&df, "steps")?,
        col_f64(&df, "rel_err_max_percent")?,
        col_f64(&df, "limit_share_percent")?,
    );
    // The points of family `f` of solution `s`: (n or N, the column `v`), and its legend.
    let family = |s: &str, f: &str, v: &[f64]| -> (String, Vec<(f64, f64)>) {
        let rows: Vec<usize> = (0..sol.len())
            .filter(|&i| sol[i] == s && fam[i] == f)
            .collect();
        let pts = rows
            .iter()
            .map(|&i| (if f.starts_with('k') { steps[i] } else { n[i] }, v[i]))
            .collect();
        let first = rows.first().copied().unwrap_or(0);
        let (n0, s0) = (
            n.get(first).copied().unwrap_or(0.0),
            steps.get(first).copied().unwrap_or(0.0),
        );
        let what = match f {
            "h=k" => "h = k = 1/n".to_string(),
            "h" if s == "steady" => "h = 1/n, static".to_string(),
            "h" => format!("h = 1/n, N = {s0}"),
            "k_on_step" => format!("k = 1/N, N = 5·2^m, n = {n0}"),
            _ => format!("k = 1/N, n = {n0}"),
        };
        (what, pts)
    };
    let mut charts = vec![];
    for s in evhi::manufactured::SOLUTIONS {
        let (mut series, mut markers) = (vec![], vec![]);
        for (f, c, m) in FAMILIES {
            let (label, pts) = family(s.name(), f, &err);
            if !pts.is_empty() {
                series.push((label, pts, c));
                markers.push(m);
            }
        }
        if series.is_empty() {
            continue;
        }
        charts.push(LogLog {
            title: s.label().to_string(),
            x_desc: "mesh n (h = 1/n) or steps N (k = T/N)".into(),
            y_desc: "largest relative energy error (%)".into(),
            series,
            guides: vec![(1.0, "slope −1".into())],
            legend_at: SeriesLabelPosition::LowerLeft,
            headroom: 1.5,
            fonts: PANEL_FONTS,
            markers,
            nested: true,
        });
    }
    charts.push(hold_panel(hold)?);
    // The share at g of the solutions whose exact share is 15 %: (f), (g), (i).
    let mut shares = vec![];
    for (s, f, c) in [
        ("p1limit", "h=k", oi::BLUE),
        ("p1limit", "k", oi::VERMILLION),
        ("landing", "k", oi::BLUISH_GREEN),
    ] {
        let (label, pts) = family(s, f, &share);
        shares.push((
            format!("{} {label}", label_of(s).get(..3).unwrap_or("")),
            pts,
            c,
        ));
    }
    {
        let df = read_csv(hold)?;
        let (sol, limit, rule, steps, share, n) = (
            col_str(&df, "solution")?,
            col_str(&df, "limit")?,
            col_str(&df, "rule")?,
            col_f64(&df, "steps")?,
            col_f64(&df, "limit_share")?,
            col_f64(&df, "n")?,
        );
        for (r, what, c) in [
            ("nodal", "nodal rule", oi::REDDISH_PURPLE),
            ("exact", "exact integral", oi::SKY_BLUE),
        ] {
            let rows: Vec<usize> = (0..sol.len())
                .filter(|&i| sol[i] == "hold" && limit[i] == "on" && rule[i] == r)
                .collect();
            let n0 = rows.first().map_or(0.0, |&i| n[i]);
            shares.push((
                format!("(i) k = 1/N, n = {n0}, {what}"),
                rows.iter().map(|&i| (steps[i], 100.0 * share[i])).collect(),
                c,
            ));
        }
    }
    both(
        &ctx.figures,
        "exact_convergence",
        (1200, 3000),
        &Panels {
            charts,
            share: Share {
                title: "(f), (g), (i): share of Γ3 × (0, T) at g".into(),
                series: shares,
                exact: 15.0,
                fonts: PANEL_FONTS,
            },
        },
    )?;
    // The Céa terms of (b), and R_n of (d).
    let df = read_csv(cea)?;
    let (sol, n) = (col_str(&df, "solution")?, col_f64(&df, "n")?);
    let pick = |s: &str, col: &str| -> Result<Vec<(f64, f64)>, ExpError> {
        let v = col_f64(&df, col)?;
        Ok((0..sol.len())
            .filter(|&i| sol[i] == s && v[i] > 0.0)
            .map(|i| (n[i], v[i]))
            .collect())
    };
    let series = vec![
        (
            "(b) max ||u_n - Πu_n||²_V".to_string(),
            pick("regimes", "interp_max")?,
            oi::BLUE,
        ),
        (
            "(b) k Σ ||δ(u_n - Πu_n)||²_V".into(),
            pick("regimes", "dinterp_sum")?,
            oi::ORANGE,
        ),
        (
            "(b) k Σ ||u_nν - Πu_nν||_L²(Γ3)".into(),
            pick("regimes", "gamma_sum")?,
            oi::BLUISH_GREEN,
        ),
        (
            "(b) k Σ ||δ_n||²_V".into(),
            pick("regimes", "delta_sum")?,
            oi::REDDISH_PURPLE,
        ),
        (
            "(d) k Σ |R_n(Πu_n)| ((b): 0)".into(),
            pick("moving", "r_sum")?,
            oi::SKY_BLUE,
        ),
        (
            "(h) k Σ |R_n(Πu_n)|, ends on no node".into(),
            pick("offnode", "r_sum")?,
            oi::BLACK,
        ),
        (
            "(b) left side of (4.24)".into(),
            pick("regimes", "lhs")?,
            oi::VERMILLION,
        ),
    ];
    both(
        &ctx.figures,
        "exact_cea",
        (1000, 760),
        &LogLog {
            title: "The Céa inequality (4.16) term by term, h = k = 1/n".into(),
            x_desc: "n = 1/h = 1/k".into(),
            y_desc: "value of each term of (4.16)".into(),
            series,
            guides: vec![(2.0, "slope -2 (h², k²)".into())],
            // The terms fall to the right; the lower left is empty.
            legend_at: SeriesLabelPosition::LowerLeft,
            headroom: 30.0,
            fonts: (22, 18, 19),
            markers: vec![],
            nested: false,
        },
    )?;
    // The regimes (b) visits, at the finest level up to 64.
    let df = read_csv(regimes)?;
    let (sol, n, t) = (
        col_str(&df, "solution")?,
        col_f64(&df, "n")?,
        col_f64(&df, "t")?,
    );
    let level = (0..sol.len())
        .filter(|&i| sol[i] == "regimes" && n[i] <= 64.0)
        .map(|i| n[i])
        .fold(0.0, f64::max);
    let series = REGIMES
        .iter()
        .map(|r| -> Result<(String, Vec<(f64, f64)>), ExpError> {
            let c = col_f64(&df, r)?;
            let pts = (0..sol.len())
                .filter(|&i| sol[i] == "regimes" && n[i] == level)
                .map(|i| (t[i], c[i]))
                .collect();
            Ok((r.to_string(), pts))
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(both(
        &ctx.figures,
        "exact_regimes",
        (1000, 600),
        &Regimes {
            title: format!(
                "(b): contact nodes per regime, h = k = 1/{level} ({} nodes)",
                level + 1.0
            ),
            top: 1.5
                * series
                    .iter()
                    .flat_map(|s| s.1.iter().map(|p| p.1))
                    .fold(1.0, f64::max),
            series,
        },
    )?)
}

/// The observed constant of (4.24) over the $(h, k)$ grid: one panel per solution,
/// a cell per $(n, N)$ coloured by $\log_{10}$ of its value (each panel on its own
/// range) and labelled with it.
struct Grid {
    panels: Vec<Panel>,
}

/// A panel of [`Grid`]: its title and its cells $(n, N, \text{value})$.
type Panel = (String, Vec<(f64, f64, f64)>);

/// A sequential colour from light (0) to dark (1): viridis run backwards, readable in
/// grey and by colour-blind readers.
fn sequential(s: f64) -> RGBColor {
    viridis(1.0 - s.clamp(0.0, 1.0))
}

impl Figure for Grid {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        let root = fit_title(
            root,
            "C = L/(h² + k²), L = max ‖e_n‖²_V + k Σ ‖e_n‖²_V (the left side of (4.24)); \
             colour: log C, each panel on its own scale",
            22,
        )?;
        // One panel above the other, so that the figure keeps the book column's width.
        let panels = root.split_evenly((self.panels.len(), 1));
        for (whole, (title, cells)) in panels.iter().zip(&self.panels) {
            // The colour bar at the right of each panel.
            let (wide, _) = whole.dim_in_pixel();
            let (area, bar) = whole.split_horizontally(wide.saturating_sub(110));
            let levels = |pick: fn(&(f64, f64, f64)) -> f64| {
                let mut v: Vec<f64> = cells.iter().map(pick).collect();
                v.sort_by(f64::total_cmp);
                v.dedup();
                v
            };
            let (ns, steps) = (levels(|c| c.0), levels(|c| c.1));
            let mut chart = ChartBuilder::on(&area)
                .caption(title, (FONT, 22))
                .margin(15)
                .x_label_area_size(60)
                .y_label_area_size(80)
                .build_cartesian_2d(0.0..ns.len() as f64, 0.0..steps.len() as f64)
                .map_err(e2s)?;
            let name = |v: &[f64], x: f64| {
                v.get(x.floor() as usize)
                    .filter(|_| (x - x.floor() - 0.5).abs() < 1e-9)
                    .map_or(String::new(), |n| format!("{n}"))
            };
            chart
                .configure_mesh()
                .disable_mesh()
                .x_labels(ns.len() * 2 + 1)
                .y_labels(steps.len() * 2 + 1)
                .x_label_formatter(&|x| name(&ns, *x))
                .y_label_formatter(&|y| name(&steps, *y))
                .x_desc("n = 1/h")
                .y_desc("N = T/k")
                .label_style((FONT, 18))
                .axis_desc_style((FONT, 18))
                .draw()
                .map_err(e2s)?;
            let logs = cells.iter().map(|c| c.2.log10());
            let (lo, hi) = (
                logs.clone().fold(f64::INFINITY, f64::min),
                logs.fold(f64::NEG_INFINITY, f64::max),
            );
            colour_bar(&bar, lo, hi.max(lo + 1e-12))?;
            for &(n, s, v) in cells {
                let (i, j) = (
                    ns.iter().position(|&x| x == n).unwrap_or(0) as f64,
                    steps.iter().position(|&x| x == s).unwrap_or(0) as f64,
                );
                let shade = (v.log10() - lo) / (hi - lo).max(1e-12);
                chart
                    .draw_series(std::iter::once(Rectangle::new(
                        [(i, j), (i + 1.0, j + 1.0)],
                        sequential(shade).filled(),
                    )))
                    .map_err(e2s)?;
                let ink = if shade > 0.55 { WHITE } else { BLACK };
                let style =
                    (FONT, 17)
                        .into_font()
                        .color(&ink)
                        .pos(plotters::style::text_anchor::Pos::new(
                            plotters::style::text_anchor::HPos::Center,
                            plotters::style::text_anchor::VPos::Center,
                        ));
                chart
                    .draw_series(std::iter::once(Text::new(
                        if v >= 0.01 {
                            format!("{v:.3}")
                        } else {
                            format!("{v:.1e}")
                        },
                        (i + 0.5, j + 0.5),
                        style,
                    )))
                    .map_err(e2s)?;
            }
        }
        Ok(())
    }
}

/// A vertical colour bar on `area` for $\log_{10} C$ from `lo` to `hi`: the
/// [`sequential`] scale with the values of $C$ at its ticks.
fn colour_bar<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    lo: f64,
    hi: f64,
) -> Result<(), String> {
    let (a, b) = (10f64.powf(lo), 10f64.powf(hi));
    let keys = evhi::output::plot::one_two_five((a, b), -12..=6);
    let mut chart = ChartBuilder::on(area)
        .margin_top(52)
        .margin_bottom(75)
        .margin_right(8)
        .y_label_area_size(70)
        .build_cartesian_2d(0.0..1.0, (a..b).log_scale().with_key_points(keys))
        .map_err(e2s)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_label_formatter(&|v| evhi::output::plot::plain(v))
        .label_style((FONT, 16))
        .draw()
        .map_err(e2s)?;
    const STEPS: usize = 60;
    let at = |s: f64| 10f64.powf(lo + s * (hi - lo));
    chart
        .draw_series((0..STEPS).map(|i| {
            let (s0, s1) = (i as f64 / STEPS as f64, (i + 1) as f64 / STEPS as f64);
            Rectangle::new(
                [(0.0, at(s0)), (1.0, at(s1))],
                sequential((s0 + s1) / 2.0).filled(),
            )
        }))
        .map_err(e2s)?;
    Ok(())
}

/// The heat map of the $(h, k)$ grid ([`super::grid`]) from `exact_grid.csv`.
pub fn draw_grid(ctx: &Ctx, grid: &Path) -> Result<(), ExpError> {
    let df = read_csv(grid)?;
    let (sol, n, steps, c) = (
        col_str(&df, "solution")?,
        col_f64(&df, "n")?,
        col_f64(&df, "steps")?,
        col_f64(&df, "lhs_over_h2_plus_k2")?,
    );
    let mut names: Vec<&str> = sol.iter().map(String::as_str).collect();
    names.dedup();
    let panels: Vec<Panel> = names
        .iter()
        .map(|&s| {
            let cells = (0..sol.len())
                .filter(|&i| sol[i] == s)
                .map(|i| (n[i], steps[i], c[i]))
                .collect();
            (format!("{}: C, h = 1/n, k = T/N", label_of(s)), cells)
        })
        .collect();
    Ok(both(
        &ctx.figures,
        "exact_grid",
        (1000, 1300),
        &Grid { panels },
    )?)
}

/// One log–log chart per solution, in rows of two.
struct SmallMultiples(Vec<LogLog>);

impl Figure for SmallMultiples {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        let cells = root.split_evenly((self.0.len().div_ceil(2), 2));
        for (area, chart) in cells.iter().zip(&self.0) {
            chart.draw_on(area, 0)?;
        }
        Ok(())
    }
}

/// `exact_adaptive.png`: per solution, the largest error over time against the
/// unknowns, the uniform family and the two adaptive families (marked by the residual
/// and by the equilibrated indicators) of `exact_adaptive.csv`.
pub fn draw_adaptive(ctx: &Ctx, table: &Path) -> Result<(), ExpError> {
    let df = read_csv(table)?;
    let (sol, fam, dofs, err) = (
        col_str(&df, "solution")?,
        col_str(&df, "family")?,
        col_f64(&df, "dofs")?,
        col_f64(&df, "err_max")?,
    );
    let mut names: Vec<&str> = sol.iter().map(String::as_str).collect();
    names.dedup();
    let pick = |s: &str, f: &str| -> Vec<(f64, f64)> {
        (0..sol.len())
            .filter(|&i| sol[i] == s && fam[i] == f)
            .map(|i| (dofs[i], 100.0 * err[i]))
            .collect()
    };
    let families = crate::experiments::adaptive::FAMILIES;
    let charts = names
        .iter()
        .map(|&s| LogLog {
            title: label_of(s).to_string(),
            x_desc: "unknowns".into(),
            y_desc: "largest relative error over time (%)".into(),
            series: vec![
                (families[0].into(), pick(s, families[0]), oi::BLACK),
                (families[2].into(), pick(s, families[2]), oi::VERMILLION),
                (
                    "adaptive, equilibrated".into(),
                    pick(s, "adaptive equilibrated"),
                    oi::BLUE,
                ),
            ],
            guides: vec![(0.5, "slope −1/2: order 1 in h".into())],
            legend_at: SeriesLabelPosition::LowerLeft,
            headroom: 1.5,
            fonts: PANEL_FONTS,
            markers: vec![0, 1, 2],
            nested: false,
        })
        .collect();
    Ok(both(
        &ctx.figures,
        "exact_adaptive",
        (1200, 1500),
        &SmallMultiples(charts),
    )?)
}
