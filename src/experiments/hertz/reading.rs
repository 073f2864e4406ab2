//! How the half-width is read off the nodal pressures, and what the reading adds.
//!
//! The computed half-width $a_h$ comes from the nodal pressures $p_i = F_i / \ell_i$
//! ($F_i$ a node's contact force, $\ell_i$ its share of the $x$ axis): $p^2$ is extended
//! linearly through the last two nodes in contact to zero ([`super::edge`]), since
//! $p^2 \propto a - x$ near any smooth contact's edge. Three measurements of it, each
//! at the nodes of a mesh of `hertz.csv` and Hertz's half-width $a$ at its force:
//!
//! - Hertz's exact pressure sampled at the nodes, $p_i = p(x_i)$, read the same way:
//!   the reading's own error, with no finite elements involved. For
//!   $p^2 = p_0^2 (1 - x^2/a^2)$ the line through $x_{L-1}, x_L$ meets zero at
//!   $x_L + (a - x_L)(a + x_L)/(x_{L-1} + x_L)$, an error of
//!   $(a - x_L)(a - x_{L-1})/(x_{L-1} + x_L) \le h^2/a$: second order.
//! - Hertz's exact pressure as nodal forces, $F_i = \int_0^a p\,\varphi_i\,dx$ with the
//!   hat functions $\varphi_i$ along $x$ (what a load that is exactly Hertz's puts on
//!   the nodes), read the same way: the node just past $a$ then carries a force too,
//!   and the reading errs by a fraction of $h$ that depends on where $a$ falls.
//! - The finite element solution as the edge crosses one element: the press is raised
//!   in [`STEPS`] steps that move $a$ by about one element, and each computed error is
//!   recorded with the place of Hertz's edge between its two nodes.

use super::{Gap, PRESS, R, edge, solve, x_shares};
use crate::experiments::{Ctx, ExpError};

/// The meshes swept (names `hertz_N`).
pub const MESHES: [usize; 4] = [25, 50, 100, 200];
/// Presses per mesh: $d_j = d\,(1 + 4j / (N\,\text{STEPS}))$, $j < $ `STEPS`, which
/// moves $a \approx 0.05R$ by $j/\text{STEPS}$ of the mesh's $h = 0.1R/N$ (with
/// $a^2 \propto P$ and $P$ nearly proportional to the press).
pub const STEPS: usize = 8;

evhi::row! {
    /// One solve of the sweep.
    pub struct ReadingRow {
        mesh: u64 => "mesh",
        press: f64 => "press",
        elements_across: f64 => "elements_across",
        /// Where Hertz's a falls between the two nodes around it: 0 at the inner, 1 at the outer.
        place: f64 => "edge_place",
        /// (last node in the finite element solution's contact - Hertz's a) / h.
        last_in_contact: f64 => "last_in_contact_minus_a_over_h",
        rel_err_a: f64 => "rel_err_a",
        /// The reading applied to Hertz's pressure sampled at the nodes.
        exact_sampled: f64 => "reading_err_sampled",
        /// The reading applied to Hertz's pressure as consistent nodal forces.
        exact_forces: f64 => "reading_err_forces",
        rel_err_p0: f64 => "rel_err_p0",
    }
}

evhi::row! {
    /// One mesh of the sweep: the errors of a over the edge's places.
    pub struct EdgeRow {
        mesh: u64 => "mesh",
        elements_across: f64 => "elements_across",
        fem_mean: f64 => "rel_err_a_mean",
        fem_min: f64 => "rel_err_a_min",
        fem_max: f64 => "rel_err_a_max",
        /// The largest less the least: the sawtooth's width, and that times the elements across a.
        width: f64 => "rel_err_a_width",
        width_h: f64 => "width_over_h_a",
        /// The mean of last_in_contact_minus_a_over_h.
        last_mean: f64 => "last_in_contact_mean",
        sampled_max: f64 => "reading_err_sampled_max",
        forces_mean: f64 => "reading_err_forces_mean",
        /// That times the elements across a.
        forces_h: f64 => "forces_mean_over_h_a",
    }
}

/// The nodal forces that Hertz's pressure of half-width `a` and peak 1 puts on the
/// nodes `x` (increasing from 0): $\int_0^a p\,\varphi_i\,dx$ with the hat functions
/// of the nodes, by 8-point Gauss–Legendre in $u = \sqrt{a - x}$, in which the
/// integrand $2u^2\sqrt{2a - u^2}/a$ times the hat is smooth up to the edge.
pub fn hertz_forces(x: &[f64], a: f64) -> Vec<f64> {
    const GL: [(f64, f64); 4] = [
        (0.183_434_642_495_649_8, 0.362_683_783_378_362),
        (0.525_532_409_916_329, 0.313_706_645_877_887_3),
        (0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
        (0.960_289_856_497_536_3, 0.101_228_536_290_376_3),
    ];
    let mut f = vec![0.0; x.len()];
    for i in 0..x.len().saturating_sub(1) {
        let (l, r) = (x[i], x[i + 1]);
        if l >= a {
            break;
        }
        let (u_lo, u_hi) = ((a - r.min(a)).sqrt(), (a - l).sqrt());
        let (mid, half) = (0.5 * (u_lo + u_hi), 0.5 * (u_hi - u_lo));
        for (xi, wi) in GL {
            for u in [mid - half * xi, mid + half * xi] {
                let t = a - u * u;
                let v = wi * half * 2.0 * u * u * (2.0 * a - u * u).sqrt() / a;
                f[i] += v * (r - t) / (r - l);
                f[i + 1] += v * (t - l) / (r - l);
            }
        }
    }
    f
}

/// The reading's relative error on Hertz's pressure of half-width `a` at the nodes
/// `x`: sampled there, and as nodal forces over the nodes' shares.
pub fn reading_errors(x: &[f64], a: f64) -> (f64, f64) {
    let sampled: Vec<f64> = (x.iter())
        .map(|&t| (1.0 - (t / a).powi(2)).max(0.0).sqrt())
        .collect();
    let shares = x_shares(x);
    let forces: Vec<f64> = (hertz_forces(x, a).iter().zip(&shares))
        .map(|(f, l)| f / l)
        .collect();
    let err = |p: &[f64]| (edge(x, p).0 - a) / a;
    (err(&sampled), err(&forces))
}

/// Runs the sweep and writes its tables; returns the per-mesh summary.
pub fn run(ctx: &Ctx) -> Result<Vec<EdgeRow>, ExpError> {
    ctx.add_units(MESHES.len());
    let (mut rows, mut summary) = (vec![], vec![]);
    for n in MESHES {
        let mut mine = vec![];
        for j in 0..STEPS {
            let press = PRESS * (1.0 + 4.0 * j as f64 / (n * STEPS) as f64);
            let s = solve(&format!("hertz_{n}"), press, Gap::Circle)?;
            let a = s.row.a_hertz;
            let k = s.x.iter().rposition(|&t| t <= a).expect("a node at 0");
            let h = s.x[k + 1] - s.x[k];
            let last = s.p.iter().rposition(|&v| v > 0.0).expect("contact");
            let (sampled, forces) = reading_errors(&s.x, a);
            mine.push(ReadingRow {
                mesh: n as u64,
                press,
                elements_across: s.row.elements_across,
                place: (a - s.x[k]) / h,
                last_in_contact: (s.x[last] - a) / h,
                rel_err_a: s.row.rel_err_a,
                exact_sampled: sampled,
                exact_forces: forces,
                rel_err_p0: s.row.rel_err_p0,
            });
        }
        let mean = |f: &dyn Fn(&ReadingRow) -> f64| mine.iter().map(f).sum::<f64>() / STEPS as f64;
        let fold = |f: &dyn Fn(&ReadingRow) -> f64, lo: bool| {
            let init = if lo { f64::INFINITY } else { f64::NEG_INFINITY };
            (mine.iter().map(f)).fold(init, |m, v| if lo { m.min(v) } else { m.max(v) })
        };
        let across = mean(&|r| r.elements_across);
        let (lo, hi) = (fold(&|r| r.rel_err_a, true), fold(&|r| r.rel_err_a, false));
        let forces = mean(&|r| r.exact_forces);
        summary.push(EdgeRow {
            mesh: n as u64,
            elements_across: across,
            fem_mean: mean(&|r| r.rel_err_a),
            fem_min: lo,
            fem_max: hi,
            width: hi - lo,
            width_h: (hi - lo) * across,
            last_mean: mean(&|r| r.last_in_contact),
            sampled_max: fold(&|r| r.exact_sampled.abs(), false),
            forces_mean: forces,
            forces_h: forces * across,
        });
        ctx.log(&format!("hertz: the edge across one element of mesh {n}"));
        rows.extend(mine);
    }
    let about = format!(
        "the reading of a: meshes hertz_N of hertz.csv, each pressed by {PRESS} (1 + 4 j / (N {STEPS})), j < {STEPS}, which moves a (about 0.05 R = {}) across about one element; edge_place = where Hertz's a falls between the nodes around it (0 inner, 1 outer); rel_err_a as in hertz.csv; reading_err_sampled = the same reading of Hertz's exact pressure sampled at the nodes, reading_err_forces = of its consistent nodal forces (hat functions along x) over the nodes' shares",
        0.05 * R
    );
    ctx.write("hertz_reading.csv", &ReadingRow::table(&rows), &about)?;
    ctx.write(
        "hertz_edge.csv",
        &EdgeRow::table(&summary),
        &format!("hertz_reading.csv per mesh: the mean, least and largest relative error of a over the {STEPS} places of the edge, the largest less the least (width) and that times the elements across a, the mean place of the last node in contact relative to Hertz's a (in elements), the largest error of the reading on Hertz's pressure sampled at the nodes, and the mean on its nodal forces (and that times the elements across a)"),
    )?;
    Ok(summary)
}
