//! The work–precision chart: error in energy norm against wall time for the
//! configurations of the convergence study (`evhi bench` times them).

use super::tables::{BenchRow, PaperRow, REFERENCE, WorkPrecisionRow, read_bench};
use evhi::output::csv;
use evhi::output::plot::FONT;
use evhi::output::plot::{
    Figure, LogLogChart, both, circle_legend, e2s, extent, legend, one_two_five,
};
use evhi::output::plot::{GREY_DARK, okabe_ito as oi};
use evhi::output::rows::{Allowed, POSITIVE, column};

/// A relative error in percent that a reference can have: above 0 (the log axis) and at
/// most 100.
const PERCENT: Allowed<f64> = Allowed {
    test: |x| (POSITIVE.test)(x) && *x <= 100.0,
    says: "a percentage > 0 and at most 100",
};
use evhi::study::{Ctx, ExpError};
use plotters::prelude::*;
use std::path::Path;

/// A family of runs: label, points (time, error, "n/N"), colour.
type Family = (String, Vec<(f64, f64, String)>, RGBColor);

/// The work-precision chart, read from its table and ready to draw.
pub struct Chart {
    series: Vec<Family>,
    /// The estimated own error of the $h = 1/512$ mesh (percent), below which the
    /// $k$ family's total error cannot go: its errors are measured against a
    /// reference on its own mesh, so they are time errors only.
    floor: Option<f64>,
}

/// The orthogonal estimate of the 1/512 mesh's own error for `figure`, percent, from
/// `data/table1_reference_error.csv` (written by the forensics), if there; a value
/// there that is not a percentage in (0, 100] is refused (the chart draws it on a log
/// axis, and a mesh whose own error passed 100 % would be no reference).
fn mesh_floor(ctx: &Ctx) -> Result<Option<f64>, ExpError> {
    let path = ctx.data_path("table1_reference_error.csv");
    if !path.exists() {
        return Ok(None);
    }
    let text = csv::Text::read(&path)?;
    let load = column::<String>(&text, "load", &[])?;
    let name = "reference_error_orthogonal_percent";
    let v = column::<f64>(&text, name, &[])?;
    Ok(match load.iter().position(|l| l == "figure") {
        Some(i) if !(PERCENT.test)(&v[i]) => Err(text.bad_cell(i, name, PERCENT.says))?,
        Some(i) => Some(v[i]),
        None => None,
    })
}

impl Chart {
    /// The chart of `data/work_precision.csv` at `path` (checked, see
    /// [`super::tables::read_work_precision`]).
    pub fn read(ctx: &Ctx, path: &Path) -> Result<Chart, ExpError> {
        let rows: Vec<WorkPrecisionRow> = super::tables::read_work_precision(path)?
            .into_iter()
            .map(|(_, r)| r)
            .collect();
        let pick = |f: &str| -> Vec<(f64, f64, String)> {
            (rows.iter().filter(|r| r.family == f))
                .map(|r| {
                    (
                        r.wall_s,
                        r.rel_err_max_percent,
                        format!("{}/{}", r.n, r.steps),
                    )
                })
                .collect()
        };
        Ok(Chart {
            series: vec![
                ("h = k = 1/n".into(), pick("h=k"), oi::BLUE),
                (
                    format!("h = 1/n, k = 1/{REFERENCE}"),
                    pick("h"),
                    oi::VERMILLION,
                ),
                (
                    format!("h = 1/{REFERENCE}, k = 1/N: time error only"),
                    pick("k"),
                    oi::BLUISH_GREEN,
                ),
            ],
            floor: mesh_floor(ctx)?,
        })
    }

    /// Draws `figures/work_precision.{png,svg}`.
    pub fn draw(&self, ctx: &Ctx) -> Result<(), ExpError> {
        Ok(both(&ctx.figures, "work_precision", (1000, 750), self)?)
    }
}

/// Draws `figures/work_precision.{png,svg}` from `data/work_precision.csv`.
pub fn draw(ctx: &Ctx, path: &Path) -> Result<(), ExpError> {
    Chart::read(ctx, path)?.draw(ctx)
}

impl Figure for Chart {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        let pts: Vec<(f64, f64)> = self
            .series
            .iter()
            .flat_map(|s| s.1.iter().map(|p| (p.0, p.1)))
            .collect();
        let ((xmin, xmax), (ymin, ymax)) = extent(&pts);
        let ykeys = one_two_five((ymin * 0.6, ymax * 1.6), -3..=2);
        let mut chart = LogLogChart {
            caption: ("Work against precision, scenario figure (labels: n/N)", 24),
            label_areas: (55, 80),
            desc: (
                "wall time of the whole run [s] (median)",
                "relative error, max over t [%]",
            ),
            format: (
                Some(&evhi::output::plot::plain),
                Some(&evhi::output::plot::plain),
            ),
            fonts: (18, Some(18)),
            ..LogLogChart::default()
        }
        .build(
            root,
            (xmin * 0.7..xmax * 1.5)
                .log_scale()
                .with_key_points(evhi::output::plot::keys_within(
                    (xmin * 0.7, xmax * 1.5),
                    (-6..=6).map(|e| 10f64.powi(e)),
                )),
            (ymin * 0.6..ymax * 1.6).log_scale().with_key_points(ykeys),
        )?;
        let placed = place_labels(
            |x, y| chart.backend_coord(&(x, y)),
            chart.plotting_area().get_pixel_range(),
            &self.series,
            self.floor,
        );
        for (label, s, c) in &self.series {
            let c = *c;
            let line: Vec<(f64, f64)> = s.iter().map(|p| (p.0, p.1)).collect();
            chart
                .draw_series(LineSeries::new(line, c.stroke_width(2)))
                .map_err(e2s)?
                .label(label.clone())
                .legend(move |xy| circle_legend(xy, 12, c.stroke_width(2), 5, c));
            chart
                .draw_series(
                    s.iter()
                        .map(move |p| Circle::new((p.0, p.1), 5, c.filled())),
                )
                .map_err(e2s)?;
        }
        if let Some(f) = self.floor {
            let grey = GREY_DARK.stroke_width(2);
            chart
                .draw_series(DashedLineSeries::new(
                    vec![(xmin * 0.7, f), (xmax * 1.5, f)],
                    8,
                    6,
                    grey,
                ))
                .map_err(e2s)?
                .label(format!(
                    "own error of the h = 1/512 mesh, about {f:.1} % (estimate)"
                ))
                .legend(move |xy| evhi::output::plot::dashed_legend(xy, 8, 6, grey));
        }
        chart
            .draw_series(
                (placed.into_iter())
                    .map(|(text, at)| Text::new(text, at, (FONT, LABEL.0).into_font())),
            )
            .map_err(e2s)?;
        legend(&mut chart, SeriesLabelPosition::UpperRight, 18, 0.9)?;
        Ok(())
    }
}

/// The points' labels: font size, and the width of a character and the height of a
/// line of it (pixels, a little over DejaVu Sans's, so that a box holds its text).
const LABEL: (u32, i32, i32) = (16, 10, 18);

/// Where each point's label goes: beside its point, at the first of twelve
/// positions (right or left; above, level or below; near or farther) whose box, in
/// pixels, lies inside the plotting area `inside` (x and y pixel ranges) and overlaps
/// no earlier label, point, line of a series or the `floor` line.
/// Returns (text, the label's top-left corner in data coordinates).
/// `at` maps a point to pixels; both axes are logarithmic.
fn place_labels(
    at: impl Fn(f64, f64) -> (i32, i32),
    inside: (std::ops::Range<i32>, std::ops::Range<i32>),
    series: &[Family],
    floor: Option<f64>,
) -> Vec<(String, (f64, f64))> {
    // Pixels per decade on each axis, to turn a pixel offset into a data factor.
    let (p0, p1) = (at(1.0, 1.0), at(10.0, 10.0));
    let (dx, dy) = ((p1.0 - p0.0) as f64, (p1.1 - p0.1) as f64);
    let mut points: Vec<(i32, i32)> = (series.iter())
        .flat_map(|(_, s, _)| s.iter().map(|p| at(p.0, p.1)))
        .collect();
    // The lines between points, as points every 4 pixels (the markers' boxes are 10
    // pixels wide, so a box catches the line between two of them).
    let mut lines: Vec<(i32, i32)> = vec![];
    for (_, s, _) in series {
        for w in s.windows(2) {
            let (a, b) = (at(w[0].0, w[0].1), at(w[1].0, w[1].1));
            let len = f64::from((b.0 - a.0).pow(2) + (b.1 - a.1).pow(2)).sqrt();
            let steps = (len / 4.0).ceil() as i32;
            for i in 1..steps {
                let t = f64::from(i) / f64::from(steps);
                lines.push((
                    a.0 + (t * f64::from(b.0 - a.0)) as i32,
                    a.1 + (t * f64::from(b.1 - a.1)) as i32,
                ));
            }
        }
    }
    points.extend(lines);
    let floor_y = floor.map(|f| at(1.0, f).1);
    let overlaps = |a: (i32, i32, i32, i32), b: (i32, i32, i32, i32)| {
        a.0 < b.0 + b.2 && b.0 < a.0 + a.2 && a.1 < b.1 + b.3 && b.1 < a.1 + a.3
    };
    let mut boxes: Vec<(i32, i32, i32, i32)> = vec![];
    let mut out = vec![];
    for (_, s, _) in series {
        for p in s {
            let (px, py) = at(p.0, p.1);
            let (w, h) = (LABEL.1 * p.2.chars().count() as i32, LABEL.2);
            let candidates = [
                (8, -h - 2),
                (8, 4),
                (-8 - w, -h - 2),
                (-8 - w, 4),
                (10, -h / 2),
                (-10 - w, -h / 2),
                (8, -2 * h - 4),
                (8, h + 6),
                (-8 - w, -2 * h - 4),
                (-8 - w, h + 6),
                (24, -h / 2),
                (-24 - w, -h / 2),
            ];
            let free = |b: (i32, i32, i32, i32)| {
                inside.0.start <= b.0
                    && b.0 + b.2 <= inside.0.end
                    && inside.1.start <= b.1
                    && b.1 + b.3 <= inside.1.end
                    && !boxes.iter().any(|&o| overlaps(b, o))
                    && floor_y.is_none_or(|y| !overlaps(b, (b.0, y - 3, b.2, 6)))
                    && !points
                        .iter()
                        .any(|&q| overlaps(b, (q.0 - 5, q.1 - 5, 10, 10)))
            };
            let (ox, oy) = (candidates.iter())
                .copied()
                .find(|&(ox, oy)| free((px + ox, py + oy, w, h)))
                .unwrap_or(candidates[0]);
            boxes.push((px + ox, py + oy, w, h));
            let to_data =
                |v: f64, off: i32, per_decade: f64| v * 10f64.powf(off as f64 / per_decade);
            out.push((p.2.clone(), (to_data(p.0, ox, dx), to_data(p.1, oy, dy))));
        }
    }
    out
}

/// The paper's reported CPU times (§5): (n = steps, its dof count, seconds), on a
/// 2.33 GHz Intel core.
pub const PAPER_TIMES: [(usize, u64, f64); 2] = [(128, 17_028, 665.0), (512, 264_508, 93_878.0)];

/// The rows of `data/bench_vs_paper.csv`: for each of the paper's levels, our rows
/// of `bench` at that level.
pub fn paper_rows(bench: &[BenchRow]) -> Vec<PaperRow> {
    let mut rows = vec![];
    for &(pn, pd, ps) in PAPER_TIMES.iter() {
        for r in bench.iter().filter(|r| r.n == pn as u64) {
            rows.push(PaperRow {
                n_and_steps: pn as u64,
                paper_dofs: pd,
                paper_cpu_s: ps,
                path: r.path.clone(),
                our_dofs: r.dofs,
                our_wall_s: r.wall_s,
                paper_over_ours: ps / r.wall_s,
            });
        }
    }
    rows
}

/// Writes `data/bench_vs_paper.csv` (and its Markdown) from the rows of `data/bench.csv`:
/// our median wall time beside the paper's CPU time at the same $h = k$.
pub fn write_paper_comparison(ctx: &Ctx, bench: &[BenchRow]) -> Result<(), ExpError> {
    ctx.write_as(
        "bench_vs_paper.csv",
        &PaperRow::table(&paper_rows(bench)),
        "bench",
        "paper: CPU seconds of its section 5 (2.33 GHz Intel core, its own dof count); ours: median wall seconds from data/bench.csv (machine named there)",
    )?;
    Ok(())
}

/// Writes `data/bench_vs_paper.csv` from `data/bench.csv` (checked, see
/// [`super::tables::read_bench`]).
pub fn paper_comparison(ctx: &Ctx) -> Result<(), ExpError> {
    let bench: Vec<BenchRow> = read_bench(&ctx.data_path("bench.csv"))?
        .into_iter()
        .map(|(_, r)| r)
        .collect();
    write_paper_comparison(ctx, &bench)
}
