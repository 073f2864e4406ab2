//! The time study's figures: the error against k (maximum over time and at T), and
//! the controls against k/τ.

use super::*;
#[allow(unused_imports)]
use evhi::output::plot::FONT;
use evhi::output::plot::LogLogChart;
use evhi::output::plot::{GREY, GREY_DARK, GREY_LIGHT, okabe_ito as oi};

/// Okabe–Ito colours (safe for colour-blind readers), one per history.
const COLOURS: [RGBColor; 3] = [oi::VERMILLION, oi::BLUE, oi::BLUISH_GREEN];

/// A plotted series: label, points, colour index (the history), marker (0 circle for
/// `figure`, 1 triangle for `literal`) and whether it is the dashed scalar model.
type Series = (String, Vec<(f64, f64)>, usize, usize, bool);

struct TimeFig {
    series: Vec<Series>,
    title: String,
    levels: Vec<f64>,
    /// Room above the data for the legend, as a factor on the largest value.
    headroom: f64,
}

pub(super) fn draw(ctx: &Ctx, path: &std::path::Path) -> Result<(), ExpError> {
    let df = read_csv(path)?;
    let (sc, hi) = (col_str(&df, "scenario")?, col_str(&df, "history")?);
    let k = col_f64(&df, "k")?;
    let mut levels: Vec<f64> = k.clone();
    levels.sort_by(f64::total_cmp);
    levels.dedup();
    for (which, col, model) in [
        ("max", "rel_err_max_percent", "model_max_percent"),
        ("T", "rel_err_T_percent", "model_T_percent"),
    ] {
        let (e, m) = (col_f64(&df, col)?, col_f64(&df, model)?);
        let mut series = vec![];
        for (si, s) in SCENARIOS.iter().enumerate() {
            for (hi_i, (label, _)) in histories().iter().enumerate() {
                let pts: Vec<(f64, f64)> = (0..k.len())
                    .filter(|&i| sc[i] == *s && hi[i] == *label && e[i] > 0.0)
                    .map(|i| (k[i], e[i]))
                    .collect();
                series.push((format!("{s}, {}", in_words(label)), pts, hi_i, si, false));
            }
        }
        for (hi_i, (label, _)) in histories().iter().enumerate() {
            let pts: Vec<(f64, f64)> = (0..k.len())
                .filter(|&i| sc[i] == "literal" && hi[i] == *label && m[i] > 0.0)
                .map(|i| (k[i], m[i]))
                .collect();
            let name = if hi_i == 0 {
                "scalar model (dashed), τ = 0.07".to_string()
            } else {
                String::new()
            };
            series.push((name, pts, hi_i, 9, true));
        }
        let title = if which == "max" {
            "Time error at fixed h: max over t"
        } else {
            "Time error at fixed h: at t = T"
        };
        let fig = TimeFig {
            series,
            title: title.into(),
            levels: levels.clone(),
            headroom: if which == "max" { 40.0 } else { 1000.0 },
        };
        both(
            &ctx.figures,
            &format!("time_study_{which}"),
            (900, 700),
            &fig,
        )?;
    }
    Ok(())
}

impl Figure for TimeFig {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        let ys: Vec<f64> = self
            .series
            .iter()
            .flat_map(|s| s.1.iter().map(|p| p.1))
            .collect();
        let ymin = ys.iter().copied().fold(f64::INFINITY, f64::min);
        let ymax = ys.iter().copied().fold(0.0, f64::max);
        let (xmin, xmax) = (self.levels[0], self.levels[self.levels.len() - 1]);
        let levels = self.levels.clone();
        let mut chart = LogLogChart {
            caption: (&self.title, 28),
            label_areas: (60, 90),
            desc: ("time step k", "relative error in energy norm [%]"),
            format: (
                Some(&|x| format!("1/{}", (1.0 / x).round())),
                Some(&evhi::output::plot::power_of_ten),
            ),
            fonts: (20, Some(22)),
            ..LogLogChart::default()
        }
        .build(
            root,
            (xmin / 1.4..xmax * 1.4).log_scale().with_key_points(levels),
            (ymin / 3.0..ymax * self.headroom).log_scale(),
        )?;
        for (label, pts, ci, marker, dashed) in &self.series {
            if pts.is_empty() {
                continue;
            }
            let c = COLOURS[*ci];
            let width = if *dashed {
                2
            } else if *marker == 0 {
                3
            } else {
                1
            };
            let style = c.stroke_width(width);
            let m = *marker;
            if *dashed {
                let drawn = chart
                    .draw_series(DashedLineSeries::new(pts.clone(), 8, 6, style))
                    .map_err(e2s)?;
                if !label.is_empty() {
                    let grey = GREY_DARK.stroke_width(2);
                    drawn.label(label.clone()).legend(move |(x, y)| {
                        EmptyElement::at((x, y))
                            + PathElement::new(vec![(0, 0), (10, 0)], grey)
                            + PathElement::new(vec![(16, 0), (24, 0)], grey)
                    });
                }
                continue;
            }
            chart
                .draw_series(LineSeries::new(pts.clone(), style))
                .map_err(e2s)?;
            if m == 0 {
                chart
                    .draw_series(pts.iter().map(|&p| Circle::new(p, 6, c.filled())))
                    .map_err(e2s)?
                    .label(label.clone())
                    .legend(move |xy| circle_legend(xy, 12, style, 6, c));
            } else {
                chart
                    .draw_series(
                        pts.iter()
                            .map(|&p| TriangleMarker::new(p, 7, c.stroke_width(2))),
                    )
                    .map_err(e2s)?
                    .label(label.clone())
                    .legend(move |(x, y)| {
                        EmptyElement::at((x + 12, y))
                            + PathElement::new(vec![(-12, 0), (12, 0)], style)
                            + TriangleMarker::new((0, 0), 7, c.stroke_width(2))
                    });
            }
        }
        // The relaxation time: backward Euler follows the layer only for k well below it.
        let tau = 0.07;
        let (y0, y1) = (ymin / 3.0, ymax * self.headroom);
        chart
            .draw_series(DashedLineSeries::new(
                vec![(tau, y0), (tau, y1)],
                4,
                4,
                GREY.stroke_width(1),
            ))
            .map_err(e2s)?;
        chart
            .draw_series(std::iter::once(Text::new(
                "k = τ",
                (tau * 1.05, y0 * 1.6),
                (FONT, 18).into_font().color(&GREY_DARK),
            )))
            .map_err(e2s)?;
        // Slope-1 guide through the last point of the first compatible series.
        if let Some(&(x0, y0)) = self.series.get(1).and_then(|s| s.1.last()) {
            let guide = vec![(x0, y0 / 2.5), (x0 * 16.0, y0 / 2.5 * 16.0)];
            chart
                .draw_series(DashedLineSeries::new(
                    guide,
                    3,
                    5,
                    GREY_DARK.stroke_width(1),
                ))
                .map_err(e2s)?
                .label("slope 1")
                .legend(|xy| dashed_legend(xy, 3, 5, GREY_DARK.stroke_width(1)));
        }
        legend(&mut chart, SeriesLabelPosition::UpperLeft, 18, 0.9)?;
        Ok(())
    }
}

/// The colour of the scalar model's band in the controls' figure.
const MODEL_BAND: RGBColor = GREY_LIGHT;

/// A load history's label (`a_constant`, `b_ramp1`, ...) in words.
pub(super) fn in_words(label: &str) -> String {
    match label.split_once('_').map_or(label, |(_, rest)| rest) {
        "constant" => "constant load".into(),
        other => match other.strip_prefix("ramp") {
            Some(t) => format!("load ramped in over [0, {t}]"),
            None => other.to_string(),
        },
    }
}

/// A series of the controls' figure: label, (k/τ, error) points, colour, marker
/// (0 circle for `figure`, 1 triangle for `literal`), dashed (the scalar model).
type ControlSeries = (String, Vec<(f64, f64)>, RGBColor, usize, bool);

struct ControlFig {
    panels: Vec<(String, Vec<ControlSeries>)>,
}

/// `figures/time_controls.png`: the errors of the controls against k/τ, the maximum
/// over time. If the layer sets the error, the τ curves fall on one another.
pub(super) fn draw_controls(ctx: &Ctx, path: &std::path::Path) -> Result<(), ExpError> {
    let df = read_csv(path)?;
    let (sc, va) = (col_str(&df, "scenario")?, col_str(&df, "variant")?);
    let x = col_f64(&df, "k_over_tau")?;
    let mut variants: Vec<String> = va.clone();
    variants.sort();
    variants.dedup();
    // The constant load only: the ramp's errors are another story (chapter "Time").
    variants.retain(|v| !v.contains("ramp"));
    // Okabe–Ito: the three relaxation times, then the no-landing control.
    let colour = |v: &str, i: usize| {
        if v.starts_with("no landing") {
            oi::BLACK
        } else {
            [oi::BLUE, oi::VERMILLION, oi::BLUISH_GREEN][i % 3]
        }
    };
    let mut panels = vec![];
    // The maximum over time only: at T the short relaxation times leave errors at
    // the reference's rounding, which say nothing of the layer.
    for (title, col, model) in [("max over t", "rel_err_max_percent", "model_max_percent")] {
        let (e, m) = (col_f64(&df, col)?, col_f64(&df, model)?);
        let mut series = vec![];
        for (vi, v) in variants.iter().enumerate() {
            for (si, s) in ["figure", "literal"].iter().enumerate() {
                let pts: Vec<(f64, f64)> = (0..x.len())
                    .filter(|&i| sc[i] == *s && va[i] == *v && e[i] > 0.0)
                    .map(|i| (x[i], e[i]))
                    .collect();
                if !pts.is_empty() {
                    series.push((
                        format!("{s}, {}", v.replace("tau", "τ")),
                        pts,
                        colour(v, vi),
                        si,
                        false,
                    ));
                }
            }
            let pts: Vec<(f64, f64)> = (0..x.len())
                .filter(|&i| sc[i] == "figure" && va[i] == *v && m[i] > 0.0)
                .map(|i| (x[i], m[i]))
                .collect();
            // The model depends on the relaxation time only: one grey dashed line per
            // tau, apart from the measured series it would otherwise hide.
            if !v.starts_with("no landing") {
                series.push((String::new(), pts, GREY, 9, true));
            }
        }
        panels.push((title.to_string(), series));
    }
    Ok(both(
        &ctx.figures,
        "time_controls",
        (900, 700),
        &ControlFig { panels },
    )?)
}

impl Figure for ControlFig {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        for (k, (title, series)) in self.panels.iter().enumerate() {
            let area = root;
            let pts: Vec<(f64, f64)> = series.iter().flat_map(|s| s.1.clone()).collect();
            let ((xmin, xmax), (ymin, ymax)) = evhi::output::plot::extent(&pts);
            let (xr, yr) = ((xmin / 1.5, xmax * 1.5), (ymin / 3.0, ymax * 4.0));
            let keys = evhi::output::plot::keys_within(xr, (-4..=3).map(|e| 10f64.powi(e)));
            let ykeys = evhi::output::plot::keys_within(yr, (-8..=3).map(|e| 10f64.powi(e)));
            let caption = format!("Time error against k/τ: {title}");
            let mut chart = LogLogChart {
                caption: (&caption, 22),
                desc: ("k / τ", "relative error in energy norm, %"),
                format: (
                    Some(&evhi::output::plot::plain),
                    Some(&evhi::output::plot::plain),
                ),
                fonts: (17, Some(19)),
                ..LogLogChart::default()
            }
            .build(
                area,
                (xr.0..xr.1).log_scale().with_key_points(keys),
                (yr.0..yr.1).log_scale().with_key_points(ykeys),
            )?;
            // The scalar model first, as a wide pale band under the measured series
            // that lie on it (a dashed line there was hidden by `literal`'s).
            for (_, pts, _, _, dashed) in series {
                if *dashed {
                    chart
                        .draw_series(LineSeries::new(pts.clone(), MODEL_BAND.stroke_width(11)))
                        .map_err(e2s)?;
                }
            }
            for (label, pts, c, marker, dashed) in series {
                let (c, m) = (*c, *marker);
                if *dashed {
                    continue;
                }
                let style = c.stroke_width(if m == 0 { 3 } else { 1 });
                chart
                    .draw_series(LineSeries::new(pts.clone(), style))
                    .map_err(e2s)?;
                let drawn = if m == 0 {
                    chart
                        .draw_series(pts.iter().map(|&p| Circle::new(p, 6, c.filled())))
                        .map_err(e2s)?
                } else {
                    chart
                        .draw_series(pts.iter().map(|&p| Circle::new(p, 4, c.stroke_width(2))))
                        .map_err(e2s)?
                };
                if k == 0 {
                    let r = if m == 0 { 6 } else { 4 };
                    let st = if m == 0 {
                        c.filled()
                    } else {
                        c.stroke_width(2)
                    };
                    drawn.label(label.clone()).legend(move |(x, y)| {
                        EmptyElement::at((x + 12, y))
                            + PathElement::new(vec![(-12, 0), (12, 0)], style)
                            + Circle::new((0, 0), r, st)
                    });
                }
            }
            if k == 0 {
                let band = MODEL_BAND.stroke_width(11);
                chart
                    .draw_series(std::iter::once(PathElement::new(vec![], band)))
                    .map_err(e2s)?
                    .label("scalar model (wide grey band), one per τ")
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], band));
            }
            legend(&mut chart, SeriesLabelPosition::UpperLeft, 15, 0.9)?;
        }
        Ok(())
    }
}
