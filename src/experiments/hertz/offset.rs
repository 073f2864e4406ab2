//! The finite body's offset from Hertz, measured directly.
//!
//! Hertz's formula is for a half-space whose surface is the parabola $x^2/(2R)$. The
//! computed cylinder departs from it by its size (the flat face and the rest of the
//! disc are a distance $R$ away) and by its shape (the circle's gap
//! $R - \sqrt{R^2 - x^2} = x^2/(2R) + x^4/(8R^3) + \dots$), each by a relative amount of
//! order $(a/R)^2$; the discretisation's share depends on the elements across $a$.
//! So the errors are measured at $a/R$ = 0.05, 0.1 and 0.2 with the same elements
//! across $a$ ([`SETS`]: `hertz_2M`, `hertz_M` and `hertz_wide_M/2` have equal $h/a$),
//! once with the circle's gaps and once with the parabola's at the same nodes. The
//! error of $a$ at one press depends on where the edge falls between two nodes (a
//! sawtooth of width $O(h)$, `hertz_reading.csv`), so each error here is the mean over
//! [`PLACES`] presses that move the edge across one element. Each quantity's mean
//! errors at one count across $a$ are fitted by
//! $e = e_h + c\,(a/R)^2$: $e_h$ is the discretisation's part, $c\,(a/R)^2$ the finite
//! body's, and the fit's residual says how well the $(a/R)^2$ law holds.

use super::{Gap, HertzRow, R, solve};
use crate::experiments::{Ctx, ExpError};

/// The presses that make $a/R \approx$ 0.05, 0.1 and 0.2 (from first runs).
pub const PRESSES: [(f64, f64); 3] = [(0.05, 0.0050), (0.1, 0.0161), (0.2, 0.0500)];

/// Presses per size, $d\,(1 + 2j/(M\,\text{PLACES}))$ for $j <$ `PLACES` with $M$ the
/// elements across $a$: they move $a$ across about one element ($a^2 \propto P$, nearly
/// proportional to the press $d$), at evenly spaced places.
pub const PLACES: usize = 4;

/// For each count of elements across $a$: the meshes for $a/R$ = 0.05, 0.1, 0.2.
pub const SETS: [(u64, [&str; 3]); 3] = [
    (25, ["hertz_50", "hertz_25", "hertz_wide_12"]),
    (50, ["hertz_100", "hertz_50", "hertz_wide_25"]),
    (100, ["hertz_200", "hertz_100", "hertz_wide_50"]),
];

evhi::row! {
    /// One solve: a gap, a size a/R and a mesh.
    pub struct OffsetRow {
        gap: String => "gap",
        /// The nominal elements across a (the set).
        across: u64 => "across",
        /// The nominal a/R.
        size: f64 => "a_over_R",
        mesh: String => "mesh",
        elements_across: f64 => "elements_across",
        a_hertz: f64 => "a_hertz",
        /// The mean over the edge's places, and the largest less the least.
        rel_err_a: f64 => "rel_err_a",
        range_a: f64 => "rel_err_a_range",
        rel_err_p0: f64 => "rel_err_p0",
        rel_err_p_l2: f64 => "rel_err_p_l2",
    }
}

evhi::row! {
    /// The fit e = e_h + c (a/R)^2 of one quantity at one gap and count across a.
    pub struct FitRow {
        gap: String => "gap",
        quantity: String => "quantity",
        across: u64 => "across",
        /// e_h, the discretisation's part.
        discretisation: f64 => "e_h",
        /// c, the finite body's coefficient.
        coefficient: f64 => "c",
        /// c (0.1)^2: the finite body's part at a/R = 0.1.
        at_01: f64 => "finite_body_at_0.1",
        /// The largest |e - fit| of the three sizes.
        residual: f64 => "fit_residual",
    }
}

/// The least-squares line $e = e_h + c\,s$ through the points $(s_j, e_j)$, with its
/// largest residual.
fn fit(s: &[f64], e: &[f64]) -> (f64, f64, f64) {
    let m = s.len() as f64;
    let (ms, me) = (s.iter().sum::<f64>() / m, e.iter().sum::<f64>() / m);
    let sxx: f64 = s.iter().map(|v| (v - ms).powi(2)).sum();
    let sxy: f64 = s.iter().zip(e).map(|(v, w)| (v - ms) * (w - me)).sum();
    let c = sxy / sxx;
    let e_h = me - c * ms;
    let res = (s.iter().zip(e))
        .map(|(v, w)| (w - e_h - c * v).abs())
        .fold(0.0, f64::max);
    (e_h, c, res)
}

/// Runs the sizes and gaps and writes the tables; returns the fits.
pub fn run(ctx: &Ctx) -> Result<Vec<FitRow>, ExpError> {
    ctx.add_units(2 * SETS.len());
    let (mut rows, mut fits) = (vec![], vec![]);
    for gap in [Gap::Circle, Gap::Parabola] {
        for (across, meshes) in SETS {
            let mut solved: Vec<OffsetRow> = vec![];
            for ((size, press), mesh) in PRESSES.iter().zip(meshes) {
                let mut at: Vec<HertzRow> = vec![];
                for j in 0..PLACES {
                    let d = press * (1.0 + 2.0 * j as f64 / (across as usize * PLACES) as f64);
                    at.push(solve(mesh, d, gap)?.row);
                }
                let mean =
                    |f: &dyn Fn(&HertzRow) -> f64| at.iter().map(f).sum::<f64>() / PLACES as f64;
                let ea: Vec<f64> = at.iter().map(|r| r.rel_err_a).collect();
                solved.push(OffsetRow {
                    gap: gap.name().into(),
                    across,
                    size: *size,
                    mesh: mesh.into(),
                    elements_across: mean(&|r| r.elements_across),
                    a_hertz: mean(&|r| r.a_hertz),
                    rel_err_a: mean(&|r| r.rel_err_a),
                    range_a: ea.iter().fold(f64::NEG_INFINITY, |m, v| m.max(*v))
                        - ea.iter().fold(f64::INFINITY, |m, v| m.min(*v)),
                    rel_err_p0: mean(&|r| r.rel_err_p0),
                    rel_err_p_l2: mean(&|r| r.rel_err_p_l2),
                });
            }
            let s2: Vec<f64> = solved.iter().map(|r| (r.a_hertz / R).powi(2)).collect();
            for q in ["a", "p0"] {
                let e: Vec<f64> = (solved.iter())
                    .map(|r| if q == "a" { r.rel_err_a } else { r.rel_err_p0 })
                    .collect();
                let (e_h, c, residual) = fit(&s2, &e);
                fits.push(FitRow {
                    gap: gap.name().into(),
                    quantity: q.into(),
                    across,
                    discretisation: e_h,
                    coefficient: c,
                    at_01: c * 0.01,
                    residual,
                });
            }
            ctx.log(&format!(
                "hertz: the finite body, {} gap, {across} across a",
                gap.name()
            ));
            rows.extend(solved);
        }
    }
    ctx.write(
        "hertz_offset.csv",
        &OffsetRow::table(&rows),
        &format!("the finite body's offset: Hertz's cylinder (data/scenarios/examples/hertz.toml, R = {R}) pressed to a/R about 0.05, 0.1 and 0.2 (presses d = {:?}) on meshes with about the same elements across a (across; hertz_wide_N keep the fine size out to 0.24 R), with the circle's initial gaps and with Hertz's parabola x^2/(2R) at the same nodes; errors as in hertz.csv, each the mean over {PLACES} presses d (1 + 2 j / (across {PLACES})), j < {PLACES}, which move the edge across one element (rel_err_a_range: the largest less the least of rel_err_a)", PRESSES.map(|p| p.1)),
    )?;
    ctx.write(
        "hertz_offset_fit.csv",
        &FitRow::table(&fits),
        "hertz_offset.csv fitted: for each gap, quantity (a, p0) and count across a, the least-squares e = e_h + c (a_hertz/R)^2 over the three sizes; e_h the discretisation's part, c (0.1)^2 the finite body's at a/R = 0.1, fit_residual the largest misfit",
    )?;
    Ok(fits)
}
