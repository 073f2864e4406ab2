//! The log–log panel of Fig. 5, and the error split into its h and k parts drawn
//! from a table of [`super::compute`].

use super::*;
#[allow(unused_imports)]
use crate::output::plot::FONT;
use crate::output::plot::{GREY_DARK, okabe_ito as oi};
use crate::output::plot::{LogLogChart, extent, one_two_five};

/// A plotted series: label, points, colour, and whether it is the second
/// (dashed, crosses) series of its scenario.
pub type Series = (String, Vec<(f64, f64)>, RGBColor, bool);

/// One log–log panel of Fig. 5.
pub struct Fig5 {
    /// The panel's caption.
    pub title: String,
    /// The description of the $x$ axis (the $y$ axis is the relative energy error, %).
    pub x_desc: String,
    /// The series drawn.
    pub series: Vec<Series>,
}

/// The error split: the h part and the k part, at t = T and over time.
struct Fig5Split {
    panels: [Fig5; 2],
}

/// Okabe–Ito colours (safe for colour-blind readers), one per scenario in order.
pub const COLOURS: [RGBColor; 3] = [oi::BLUE, oi::VERMILLION, oi::BLUISH_GREEN];

/// The error split of the table at `path` (of [`compute`]) for `scenarios`, into
/// `dir` as `stem`.png and .svg: the h part ($x = 1/n$) and the k part ($x = 1/N$), at
/// T and over time.
pub fn draw_split(
    dir: &std::path::Path,
    stem: &str,
    path: &std::path::Path,
    scenarios: &[String],
    x_desc: &str,
) -> Result<(), ExpError> {
    let df = read_csv(path)?;
    let (sc, fam) = (col_str(&df, "scenario")?, col_str(&df, "family")?);
    let (n, steps) = (col_f64(&df, "n")?, col_f64(&df, "steps")?);
    let (et, em) = (
        col_f64(&df, "rel_err_T_percent")?,
        col_f64(&df, "rel_err_max_percent")?,
    );
    let pick = |s: &str, f: &str, v: &[f64]| -> Vec<(f64, f64)> {
        (0..sc.len())
            .filter(|&i| sc[i] == s && fam[i] == f && v[i].is_finite())
            .map(|i| (if f == "k" { 1.0 / steps[i] } else { 1.0 / n[i] }, v[i]))
            .collect()
    };
    let panel = |title: &str, v: &[f64]| Fig5 {
        title: title.into(),
        x_desc: x_desc.into(),
        series: scenarios
            .iter()
            .zip(COLOURS.iter().cycle())
            .flat_map(|(name, &colour)| {
                [
                    (format!("{name}, h part"), pick(name, "h", v), colour, false),
                    (format!("{name}, k part"), pick(name, "k", v), colour, true),
                ]
            })
            .collect(),
    };
    Ok(both(
        dir,
        stem,
        (1000, 1300),
        &Fig5Split {
            panels: [panel("at t = T", &et), panel("maximum over t", &em)],
        },
    )?)
}

impl Figure for Fig5Split {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        let root = root
            .titled("Error split: the h part and the k part", (FONT, 26))
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
        let ((xmin, xmax), (ymin, ymax)) = extent(&pts);
        // A tick and a label at every level.
        let mut keys: Vec<f64> = pts.iter().map(|p| p.0).collect();
        keys.sort_by(f64::total_cmp);
        keys.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
        // 1, 2 and 5 of each decade over up to three decades; beyond, the decades only
        // (their labels would crowd).
        let yr = (ymin * 0.5, ymax * 2.0);
        let ykeys = if yr.1 / yr.0 <= 1e3 {
            one_two_five(yr, -6..=3)
        } else {
            crate::output::plot::keys_within(yr, (-6..=3).map(|e| 10f64.powi(e)))
        };
        let mut chart = LogLogChart {
            caption: (&self.title, 24),
            label_areas: (55, 80),
            desc: (&self.x_desc, "relative energy error, %"),
            format: (
                Some(&|x| reciprocal_label(*x)),
                Some(&crate::output::plot::plain),
            ),
            fonts: (18, Some(20)),
            ..LogLogChart::default()
        }
        .build(
            root,
            (xmin * 0.8..xmax * 1.25).log_scale().with_key_points(keys),
            (ymin * 0.5..ymax * 2.0).log_scale().with_key_points(ykeys),
        )?;
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
            let grey = GREY_DARK;
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
