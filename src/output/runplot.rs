//! The figures of one run directory, drawn from its CSVs (`evhi solve` draws them;
//! `evhi plot RUN_DIR` redraws them): `deformed` (the body at $t = T$ and the
//! interface forces, in the style of Fig. 3) and `evolution` (the normal displacement
//! and force at five contact nodes over time, and the number of nodes in each regime).

use super::FileError;
use super::csv::{Text, col_f64, read_csv};
use super::rows::SummaryRow;
use crate::certificate::regime_order;
use crate::output::plot::FONT;
use crate::output::plot::{Figure, both, e2s, fit_title, regime_colour, side_legend};
use crate::output::plot::{GREY, okabe_ito as oi};
use crate::scenario::Scenario;
use plotters::prelude::*;
use std::path::Path;

/// The run's tables the figures read, with the columns that may hold text (every
/// other column must hold finite numbers).
const TABLES: [(&str, &[&str]); 4] = [
    ("contact.csv", &["regime"]),
    ("nodes.csv", &[]),
    ("evolution.csv", &["regime"]),
    ("regimes.csv", &[]),
];

/// The largest magnitude a run's table holds (loads and moduli are bounded by 1e12,
/// displacements and stresses far below this).
const PLAUSIBLE: f64 = 1e100;

/// Refuses a run table the figures would misdraw: missing, without a data row, a
/// row of the wrong length, or a number that is not finite or beyond `PLAUSIBLE` in
/// a numeric column; the error names the file, the line and the column.
pub fn validate_tables(dir: &Path) -> Result<(), FileError> {
    for (file, text_cols) in TABLES {
        let text = Text::read(&dir.join(file))?;
        let (hl, cols) = &text.header;
        if text.rows.is_empty() {
            return Err(FileError::Table {
                path: format!("{}:{hl}", text.path),
                message: "a header and no data row".into(),
            });
        }
        for (i, (_, fields)) in text.rows.iter().enumerate() {
            for (c, f) in cols.iter().zip(fields) {
                if text_cols.contains(&c.as_str()) {
                    continue;
                }
                match f.trim().parse::<f64>() {
                    Ok(x) if x.is_finite() && x.abs() <= PLAUSIBLE => {}
                    _ => {
                        return Err(text.bad_cell(
                            i,
                            c,
                            &format!(
                                "a finite number of magnitude at most {PLAUSIBLE:e} (the table \
                                 was not written by this run)"
                            ),
                        ));
                    }
                }
            }
        }
    }
    Ok(())
}

/// Refuses a summary (its row at `at`) whose n, h or steps, which the figures' titles
/// state, the run's other tables contradict (a summary copied from another run):
/// - n, on a uniform mesh: its contact nodes (`contact.csv`) lie on the bottom's cells
///   of width $W/n$, $W$ the width of `nodes.csv`, so every gap between neighbours is
///   a whole number of cells (more than one where a support holds a node) and the
///   smallest is one. A graded mesh's nodes do not give n (its initial grid is the
///   coarsest that resolves the scene, bisected down to a size that n bounds).
/// - h: $W/(2n)$.
/// - steps: `regimes.csv` has a row per step, the last numbered `steps`.
fn check_claims(dir: &Path, at: &str, summary: &SummaryRow) -> Result<(), FileError> {
    let refuse = |column: &str, value: String, why: String| FileError::Table {
        path: at.to_string(),
        message: format!(
            "column `{column}` holds `{value}`, but {why}; the summary was not written by \
             the run of these tables"
        ),
    };
    let x = col_f64(&read_csv(&dir.join("nodes.csv"))?, "x")?;
    let width = x.iter().copied().fold(f64::NEG_INFINITY, f64::max)
        - x.iter().copied().fold(f64::INFINITY, f64::min);
    let n = summary.n as f64;
    let cell = width / n;
    let uniform = summary.mesh == "uniform";
    if uniform == dir.join("triangles.csv").exists() {
        return Err(refuse(
            "mesh",
            summary.mesh.clone(),
            if uniform {
                "the run directory holds triangles.csv, which only a graded run writes".into()
            } else {
                "the run directory has no triangles.csv, which a graded run writes".into()
            },
        ));
    }
    if uniform {
        let mut xs: Vec<f64> = super::rows::ContactRow::read(&dir.join("contact.csv"))?
            .into_iter()
            .map(|r| r.x)
            .collect();
        xs.sort_by(f64::total_cmp);
        if let Some(w) = xs.windows(2).find(|w| w[0] == w[1]) {
            return Err(FileError::Table {
                path: dir.join("contact.csv").display().to_string(),
                message: format!(
                    "two contact nodes at x = {}; a run writes each node once",
                    crate::error::number(w[0])
                ),
            });
        }
        let gaps: Vec<f64> = xs.windows(2).map(|w| w[1] - w[0]).collect();
        // Gaps in cells, a whole number up to rounding in the coordinates.
        let whole = |gap: f64| ((gap / cell) - (gap / cell).round()).abs() < 1e-6;
        let closest = gaps.iter().copied().fold(f64::INFINITY, f64::min);
        let fits = gaps.iter().all(|&g| whole(g)) && (closest / cell - 1.0).abs() < 1e-6;
        if !gaps.is_empty() && !fits {
            return Err(refuse(
                "n",
                summary.n.to_string(),
                format!(
                    "the contact nodes of contact.csv are {} apart at the closest, on a \
                     body {} wide, which makes n = {}, not cells of {}/{n}",
                    crate::error::number(closest),
                    crate::error::number(width),
                    (width / closest).round(),
                    crate::error::number(width)
                ),
            ));
        }
    }
    if let Some(mu) = summary.mesh.strip_prefix("graded mu = ") {
        check_graded_n(dir, summary, mu, x.len(), &refuse)?;
    }
    let h = width / (2.0 * n);
    if (summary.h - h).abs() > 1e-9 * h {
        return Err(refuse(
            "h",
            summary.h.to_string(),
            format!(
                "the body of nodes.csv is {} wide, so h = W/(2n) = {} for n = {n}",
                crate::error::number(width),
                crate::error::number(h)
            ),
        ));
    }
    check_g(dir, summary, &refuse)?;
    let regimes = read_csv(&dir.join("regimes.csv"))?;
    let step = col_f64(&regimes, "step")?;
    let last = step.last().copied().unwrap_or(0.0);
    if step.len() as u64 != summary.steps || last != summary.steps as f64 {
        return Err(refuse(
            "steps",
            summary.steps.to_string(),
            format!(
                "regimes.csv records {} step(s), the last numbered {last}",
                step.len()
            ),
        ));
    }
    Ok(())
}

/// Refuses a graded run's n that its nodes contradict: the graded mesh is a function of
/// the scene (the run's `scenario.toml`; the command line changes only g and the ramp,
/// which it does not depend on), n and the exponent mu, so the mesh of the summary's n
/// must have as many nodes as `nodes.csv`. (The bottom's cells do not give n here, as
/// they do on a uniform mesh.)
fn check_graded_n(
    dir: &Path,
    summary: &SummaryRow,
    mu: &str,
    nodes: usize,
    refuse: &dyn Fn(&str, String, String) -> FileError,
) -> Result<(), FileError> {
    let Ok(mu) = mu.trim().parse::<f64>() else {
        let why = "a graded run writes `graded mu = ` and its exponent".to_string();
        return Err(refuse("mesh", summary.mesh.clone(), why));
    };
    let path = dir.join("scenario.toml");
    let scene = Scenario::load(&path.display().to_string()).map_err(|e| FileError::Table {
        path: path.display().to_string(),
        message: format!("the scene of this graded run does not read: {e}"),
    })?;
    let n = usize::try_from(summary.n).unwrap_or(usize::MAX);
    let rebuilt = scene.graded_mesh(n, mu).map_err(|e| {
        let why = format!("the scene's graded mesh of that level is refused: {e}");
        refuse("n", summary.n.to_string(), why)
    })?;
    if rebuilt.nodes.len() != nodes {
        return Err(refuse(
            "n",
            summary.n.to_string(),
            format!(
                "the scene's mesh of that level graded with mu = {mu} has {} nodes, and \
                 nodes.csv has {nodes}",
                rebuilt.nodes.len()
            ),
        ));
    }
    Ok(())
}

/// Refuses a summary's g (the limit line the evolution figure draws) that the run
/// contradicts: the g its `contact.csv` states in its `# scenario …; g = …;` line (the
/// scene as run, command-line changes included), a contact node above it beyond the
/// overshoot the summary records (the penalty's), or a node `contact.csv` places at the
/// limit that is not at it.
fn check_g(
    dir: &Path,
    summary: &SummaryRow,
    refuse: &dyn Fn(&str, String, String) -> FileError,
) -> Result<(), FileError> {
    let g = summary.g;
    let contact_path = dir.join("contact.csv");
    let text = std::fs::read_to_string(&contact_path).map_err(|e| FileError::Io {
        path: contact_path.display().to_string(),
        source: e,
    })?;
    let stated = (text.lines().take_while(|l| l.starts_with('#')))
        .find_map(|l| l.split("; g = ").nth(1))
        .and_then(|rest| rest.split(';').next())
        .and_then(|v| v.trim().parse::<f64>().ok());
    if let Some(stated) = stated
        && stated != g
    {
        return Err(refuse(
            "g",
            crate::error::number(g),
            format!(
                "contact.csv, written by the same run, states g = {}",
                crate::error::number(stated)
            ),
        ));
    }
    // The penalty lets u_nu pass g by what the summary records; the others, by what
    // the certificate accepts, far below a millionth of the displacements' scale.
    let rows = super::rows::ContactRow::read(&contact_path)?;
    let scale = rows.iter().fold(g.abs(), |m, r| m.max(r.u_nu.abs()));
    let slack = (g.abs() * summary.max_overshoot_over_g.max(0.0)).max(1e-6 * scale);
    for r in rows {
        let at_limit = r.regime == "limit";
        let off = if at_limit {
            (r.u_nu - g).abs() > slack || !g.is_finite()
        } else {
            r.u_nu > g + slack
        };
        if off {
            return Err(refuse(
                "g",
                crate::error::number(g),
                format!(
                    "contact.csv's node at x = {} has u_nu = {} {}",
                    crate::error::number(r.x),
                    crate::error::number(r.u_nu),
                    if at_limit { "at the limit" } else { "above it" }
                ),
            ));
        }
    }
    Ok(())
}

/// Draws both figures of the run directory `dir` into it.
pub fn draw(dir: &Path) -> Result<(), FileError> {
    draw_scene(dir, None)
}

pub use crate::output::scene::Written;

/// [`draw`] for a run directory, with what its writer still holds (`evhi solve`):
/// the tables were written by this process a moment ago, so they are not checked
/// again (the checks refuse tables from elsewhere, for `evhi plot`), and the scene
/// and the triangles are taken as given.
pub fn draw_scene(dir: &Path, written: Option<Written>) -> Result<(), FileError> {
    let not_a_run = |what: &str| FileError::NotThere {
        message: format!(
            "{what}; `evhi plot` redraws the figures of a run directory that `evhi solve` \
             wrote (it holds summary.csv, contact.csv, nodes.csv, …)"
        ),
    };
    if !dir.is_dir() {
        return Err(not_a_run(if dir.exists() {
            "not a directory"
        } else {
            "no such directory"
        }));
    }
    if !dir.join("summary.csv").is_file() {
        return Err(not_a_run("not a run directory: it has no summary.csv"));
    }
    if written.is_none() {
        validate_tables(dir)?;
    }
    let summary_path = dir.join("summary.csv");
    let (line, summary) = SummaryRow::read_lines(&summary_path)?
        .into_iter()
        .next()
        .ok_or_else(|| FileError::Table {
            path: summary_path.display().to_string(),
            message: "no row".into(),
        })?;
    let summary_at = format!("{}:{line}", summary_path.display());
    let bad = |c: &str, v: f64, allowed: &str| FileError::Table {
        path: summary_at.clone(),
        message: format!(
            "column `{c}` holds `{}`, not {allowed} (the table was not written by this run)",
            crate::error::number(v)
        ),
    };
    let count = |c: &str, v: u64, max: f64| -> Result<usize, FileError> {
        if v >= 1 && v as f64 <= max {
            Ok(v as usize)
        } else {
            Err(bad(c, v as f64, &format!("an integer in [1, {max}]")))
        }
    };
    let (n, steps) = (
        count("n", summary.n, crate::mesh::MAX_N as f64)?,
        count("steps", summary.steps, 1e6)?,
    );
    // g is positive, `inf` for a scene without a limit.
    let g = summary.g;
    if g.is_nan() || g <= 0.0 {
        return Err(bad("g", g, "a positive number (inf for no limit)"));
    }
    let scenario = summary.scenario.clone();
    // A uniform run's nodes are a lattice every few cells (its first row says how
    // many columns); a graded run's are every node, drawn by its triangles.
    let stride = if dir.join("triangles.csv").exists() {
        1
    } else {
        let nodes = read_csv(&dir.join("nodes.csv"))?;
        let y = col_f64(&nodes, "y")?;
        let cols = y.iter().take_while(|&&v| v == y[0]).count();
        let stride = n / cols.saturating_sub(1).max(1);
        // The rows the lattice implies, and the stride a run with this n writes them at.
        let ny = (y.len() / cols.max(1)).saturating_sub(1) * stride;
        let written = crate::output::run::lattice_stride(n, ny.max(1));
        if cols < 2 || !n.is_multiple_of(cols - 1) || stride != written {
            return Err(FileError::Table {
                path: dir.join("nodes.csv").display().to_string(),
                message: format!(
                    "its {} node(s) are not a lattice of rows of {} (the n of summary.csv, \
                     drawn every few cells); the table was not written by this run",
                    y.len(),
                    n / written + 1
                ),
            });
        }
        stride
    };
    if written.is_none() {
        check_claims(dir, &summary_at, &summary)?;
    }
    // h as the summary gives it: 1/n on the paper's rectangle, W/(2n) on another.
    let h = summary.h;
    let h_text = if (h * n as f64 - 1.0).abs() < 1e-12 {
        format!("1/{n}")
    } else {
        crate::output::plot::plain(&h)
    };
    let deformed = || {
        crate::output::scene::draw_run(
            dir,
            g,
            n / stride,
            format!(
                "{scenario} at t = T (true scale), forces on Γ3; h = {h_text}, {steps} steps, {}{}",
                if g.is_finite() {
                    format!("g = {g}")
                } else {
                    "no limit".to_string()
                },
                if stride > 1 {
                    format!(" (mesh drawn every {stride} cells)")
                } else {
                    String::new()
                }
            ),
            written,
        )
    };
    // The two figures at once (each writes its PNG and SVG on two threads).
    std::thread::scope(|s| {
        let deformed = s.spawn(deformed);
        let evolution = draw_evolution(dir, &scenario, (&h_text, steps, g));
        let deformed = deformed.join().unwrap_or_else(|_| {
            Err(FileError::Plot {
                path: dir.join("deformed.png").display().to_string(),
                message: "the drawing failed (panicked); the tables are not as a run writes them"
                    .into(),
            })
        });
        deformed.and(evolution)
    })
}

/// The evolution figure of a run directory: the watched nodes over time and the
/// regime counts.
fn draw_evolution(
    dir: &Path,
    scenario: &str,
    (h_text, steps, g): (&str, usize, f64),
) -> Result<(), FileError> {
    let ev = read_csv(&dir.join("evolution.csv"))?;
    let (t, x, u, s1, s2) = (
        col_f64(&ev, "t")?,
        col_f64(&ev, "x")?,
        col_f64(&ev, "u_nu")?,
        col_f64(&ev, "sigma_nu1")?,
        col_f64(&ev, "sigma_nu2")?,
    );
    let mut xs: Vec<f64> = x.clone();
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    let nodes = xs
        .iter()
        .map(|&x0| {
            let idx: Vec<usize> = (0..x.len()).filter(|&i| x[i] == x0).collect();
            (
                x0,
                idx.iter().map(|&i| (t[i], u[i])).collect(),
                idx.iter().map(|&i| (t[i], -(s1[i] + s2[i]))).collect(),
            )
        })
        .collect();
    let rg = read_csv(&dir.join("regimes.csv"))?;
    let tr = col_f64(&rg, "t")?;
    let names: Vec<String> = rg
        .get_column_names()
        .iter()
        .map(|c| c.to_string())
        .filter(|c| c != "step" && c != "t")
        .collect();
    let ordered = regime_order(&names);
    let counts = ordered
        .iter()
        .map(|r| {
            Ok((
                r.clone(),
                tr.iter().copied().zip(col_f64(&rg, r)?).collect(),
            ))
        })
        .collect::<Result<Vec<_>, FileError>>()?;
    both(
        dir,
        "evolution",
        (1000, 1240),
        &Evolution {
            title: format!("{scenario}: evolution on Γ3, h = {h_text}, {steps} steps"),
            g,
            nodes,
            counts,
        },
    )
}

/// One watched node: x, its (t, u_nu) and its (t, -sigma_nu).
type NodeSeries = (f64, Vec<(f64, f64)>, Vec<(f64, f64)>);

struct Evolution {
    title: String,
    g: f64,
    /// Per node: x, (t, u_nu), (t, -sigma_nu).
    nodes: Vec<NodeSeries>,
    /// Per regime: name, (t, count).
    counts: Vec<(String, Vec<(f64, f64)>)>,
}

impl Figure for Evolution {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        let root = fit_title(root, &self.title, 26)?;
        let panels = root.split_evenly((3, 1));
        let t_max = self
            .nodes
            .iter()
            .flat_map(|n| n.1.iter().map(|p| p.0))
            .fold(0.0, f64::max);
        // Watched nodes right of the middle are dashed: on a symmetric scene they trace
        // their mirror images' curves, which stay visible between the dashes.
        let (x_lo, x_hi) = self
            .nodes
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), n| {
                (a.min(n.0), b.max(n.0))
            });
        let middle = 0.5 * (x_lo + x_hi);
        let dashed = |x: f64| x > middle + 1e-12 * (x_hi - x_lo);
        let series: [(&str, &str, usize); 2] = [
            ("normal displacement u_ν", "u_ν [m]", 1),
            ("interface force -σ_ν", "-σ_ν [N/m]", 2),
        ];
        // Each panel: the chart, and its legend beside it rather than on the data.
        let split = |area: &DrawingArea<DB, plotters::coord::Shift>| {
            let w = area.dim_in_pixel().0;
            area.split_horizontally(w.saturating_sub(LEGEND_WIDTH))
        };
        for (panel, (caption, ylabel, which)) in panels.iter().zip(series) {
            let (plot, key) = split(panel);
            let pick = |n: &NodeSeries| {
                if which == 1 { n.1.clone() } else { n.2.clone() }
            };
            let ys: Vec<f64> = self.nodes.iter().flat_map(pick).map(|p| p.1).collect();
            let mut lo = ys.iter().copied().fold(0.0, f64::min);
            let mut hi = ys.iter().copied().fold(0.0, f64::max);
            // The limit is drawn where there is one (g = "none" has none).
            let limit = which == 1 && self.g.is_finite();
            if limit {
                hi = hi.max(self.g);
            }
            let pad = 0.08 * (hi - lo).max(1e-300);
            (lo, hi) = (lo - pad, hi + pad);
            let mut chart = ChartBuilder::on(&plot)
                .caption(caption, (FONT, 22))
                .margin(12)
                .x_label_area_size(50)
                .y_label_area_size(95)
                .build_cartesian_2d(0.0..t_max, lo..hi)
                .map_err(e2s)?;
            chart
                .configure_mesh()
                .x_desc("t [s]")
                .y_desc(ylabel)
                .x_label_formatter(&crate::output::plot::plain)
                .y_label_formatter(&crate::output::plot::plain)
                .label_style((FONT, 18))
                .axis_desc_style((FONT, 18))
                .draw()
                .map_err(e2s)?;
            let mut entries = vec![];
            if limit {
                let grey = GREY;
                chart
                    .draw_series(DashedLineSeries::new(
                        vec![(0.0, self.g), (t_max, self.g)],
                        6,
                        4,
                        grey.stroke_width(2),
                    ))
                    .map_err(e2s)?;
                entries.push(("the limit g".to_string(), grey, true));
            }
            for (k, node) in self.nodes.iter().enumerate() {
                let c = oi::series(k);
                if dashed(node.0) {
                    chart
                        .draw_series(DashedLineSeries::new(pick(node), 10, 8, c.stroke_width(3)))
                        .map_err(e2s)?;
                } else {
                    chart
                        .draw_series(LineSeries::new(pick(node), c.stroke_width(3)))
                        .map_err(e2s)?;
                }
                entries.push((format!("x = {}", node.0), c, dashed(node.0)));
            }
            side_legend(&key, &entries, 17)?;
        }
        let n_max = self
            .counts
            .iter()
            .flat_map(|c| c.1.iter().map(|p| p.1))
            .fold(1.0, f64::max);
        let (plot, key) = split(&panels[2]);
        let mut chart = ChartBuilder::on(&plot)
            .caption("contact nodes in each regime", (FONT, 22))
            .margin(12)
            .x_label_area_size(50)
            .y_label_area_size(95)
            .build_cartesian_2d(0.0..t_max, 0.0..n_max * 1.08)
            .map_err(e2s)?;
        chart
            .configure_mesh()
            .x_desc("t [s]")
            .y_desc("nodes")
            .x_label_formatter(&crate::output::plot::plain)
            // A count: whole numbers.
            .y_label_formatter(&|y| {
                if y.fract().abs() < 1e-9 {
                    format!("{y:.0}")
                } else {
                    String::new()
                }
            })
            .label_style((FONT, 18))
            .axis_desc_style((FONT, 18))
            .draw()
            .map_err(e2s)?;
        let mut entries = vec![];
        for (name, pts) in &self.counts {
            let c = regime_colour(name);
            chart
                .draw_series(LineSeries::new(pts.clone(), c.stroke_width(3)))
                .map_err(e2s)?;
            entries.push((name.replace('_', " "), c, false));
        }
        side_legend(&key, &entries, 17)?;
        Ok(())
    }
}

/// The width of the legend column beside each panel of the evolution figure.
const LEGEND_WIDTH: u32 = 170;
