//! The time grids' figure: the largest error over time against the number of steps,
//! one panel per load history, for the uniform levels, the layer grids and the
//! adaptive levels, both scenes.

use super::*;
use evhi::output::plot::{GREY, LogLogChart, keys_within, okabe_ito as oi};

/// One family's colour: uniform, layer, adaptive.
const FAMILIES: [(&str, RGBColor); 3] = [
    ("uniform", oi::BLUE),
    ("into the layer", oi::ORANGE),
    ("adaptive", oi::BLUISH_GREEN),
];

/// A panel's series: family index, whether the scene is `literal` (dashed), points.
type Series = (usize, bool, Vec<(f64, f64)>);

struct Grids {
    /// Per history: its words and its series.
    panels: Vec<(String, Vec<Series>)>,
}

/// Reads the three tables and draws `time_grids`.
pub(super) fn draw_grids(ctx: &Ctx) -> Result<(), ExpError> {
    let files = ["time_study.csv", "time_layer.csv", "time_adaptive.csv"];
    let mut tables = vec![];
    for f in files {
        let df = read_csv(&ctx.data_path(f))?;
        tables.push((
            col_str(&df, "scenario")?,
            col_str(&df, "history")?,
            col_f64(&df, "steps")?,
            col_f64(&df, "rel_err_max_percent")?,
        ));
    }
    let mut panels = vec![];
    for (label, _) in histories() {
        let mut series = vec![];
        for (fam, (sc, hi, steps, err)) in tables.iter().enumerate() {
            for name in SCENARIOS {
                let mut pts: Vec<(f64, f64)> = (0..sc.len())
                    .filter(|&i| sc[i] == name && hi[i] == label && err[i] > 0.0)
                    .map(|i| (steps[i], err[i]))
                    .collect();
                pts.sort_by(|a, b| a.0.total_cmp(&b.0));
                series.push((fam, name == "literal", pts));
            }
        }
        panels.push((in_words(label), series));
    }
    both(&ctx.figures, "time_grids", (2100, 760), &Grids { panels })?;
    Ok(())
}

impl Figure for Grids {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        let pts: Vec<(f64, f64)> = (self.panels.iter())
            .flat_map(|p| p.1.iter().flat_map(|s| s.2.iter().copied()))
            .collect();
        let ((xmin, xmax), (ymin, ymax)) = evhi::output::plot::extent(&pts);
        let (xr, yr) = ((xmin / 1.3, xmax * 1.3), (ymin / 1.5, ymax * 2.5));
        let areas = root.split_evenly((1, self.panels.len()));
        for (p, (area, (words, series))) in areas.iter().zip(&self.panels).enumerate() {
            let caption = format!("({}) {words}", ['a', 'b', 'c'][p % 3]);
            let mut chart = LogLogChart {
                caption: (&caption, 26),
                label_areas: (64, 92),
                margin: 20,
                desc: ("steps", "largest error over time, %"),
                format: (
                    Some(&evhi::output::plot::plain),
                    Some(&evhi::output::plot::plain),
                ),
                fonts: (22, Some(22)),
            }
            .build(
                area,
                (xr.0..xr.1)
                    .log_scale()
                    .with_key_points(keys_within(xr, (0..=12).map(|e| 4.0 * 2f64.powi(e)))),
                (yr.0..yr.1)
                    .log_scale()
                    .with_key_points(keys_within(yr, [0.001, 0.01, 0.1, 1.0, 10.0])),
            )?;
            // The study's targets, 1 % and 0.1 %.
            for target in [1.0, 0.1] {
                chart
                    .draw_series(DashedLineSeries::new(
                        vec![(xr.0, target), (xr.1, target)],
                        4,
                        6,
                        GREY.stroke_width(1),
                    ))
                    .map_err(e2s)?;
            }
            for (fam, dashed, s) in series {
                let (name, c) = FAMILIES[*fam];
                let label = format!(
                    "{name}, {}",
                    if *dashed { SCENARIOS[1] } else { SCENARIOS[0] }
                );
                let style = c.stroke_width(3);
                let drawn = if *dashed {
                    chart.draw_series(DashedLineSeries::new(s.clone(), 10, 6, style))
                } else {
                    chart.draw_series(LineSeries::new(s.clone(), style))
                }
                .map_err(e2s)?;
                if p == 0 {
                    let dashed = *dashed;
                    // A dashed key has a gap in the middle; a solid one has none.
                    let gap = if dashed { (10, 16) } else { (13, 13) };
                    drawn.label(label).legend(move |(x, y)| {
                        EmptyElement::at((x, y))
                            + PathElement::new(vec![(0, 0), (gap.0, 0)], c.stroke_width(3))
                            + PathElement::new(vec![(gap.1, 0), (26, 0)], c.stroke_width(3))
                    });
                }
                chart
                    .draw_series(s.iter().map(|&q| Circle::new(q, 4, c.filled())))
                    .map_err(e2s)?;
            }
            if p == 0 {
                legend(&mut chart, SeriesLabelPosition::LowerLeft, 18, 0.9)?;
            }
        }
        Ok(())
    }
}
