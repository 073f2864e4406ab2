//! Meshes graded towards the singular points, on the paper's scene with contact and
//! time: if the corners are what holds Table 1's order below 1, refining near them
//! must restore order 1 in $N_{dof}^{-1/2}$.
//!
//! Both families come from newest-vertex bisection of the structured mesh with
//! $n_0 = 4$ ([`evhi::bisection`]), so every mesh is nested in the reference and
//! errors are exact by embedding:
//! - `uniform`: bisect until every triangle's longest edge is at most $D_n = 2\sqrt2/n$,
//!   the diagonal of the paper's cell at level $n$;
//! - `graded`: bisect until it is at most $D_n \min(1, \max(r, D_n^{1/\mu})^{1-\mu})$, with $r$
//!   the distance of the triangle's centroid to the nearest singular point (the clamp
//!   ends $(0, \tfrac12)$, $(2, \tfrac12)$ and the top corners $(0, 1)$, $(2, 1)$) and
//!   $\mu = 0.4$, below the clamp end's exponent $\tfrac12$. A function $r^\lambda$ is then
//!   approximated at the rate of a smooth one (Babuška, Kellogg, Pitkäranta 1979).
//!
//! Two more graded families refine towards half of the points only, to tell the two
//! kinds of singularity apart: `clamp ends` (the two ends of the clamped sides on
//! the contact line's level, exponent $\tfrac12$) and `top corners` (exponent about
//! 0.65). Grading towards one kind leaves the other's order in place.
//!
//! Level $n$ runs with $k = 1/n$; the reference is the graded mesh of level
//! $n_{ref}$ with $k = 1/n_{ref}$. The reference goes by the reduced loop where the damping is
//! proportional (`reference_at_t`; until the session that moved it there it went
//! by the general loop, and the errors at $T$ moved by at most $4\cdot10^{-10}$
//! relative). The error is the relative energy norm at $t = T$
//! (where the time part of the error is below 0.3 % at every level of Table 1).
//! Beside it, reference-free: the increment of each level to the next of its own
//! family, $\|u_n - u_{2n}\| / \|u_{2n}\|$ in the energy norm, at $T$ and its
//! maximum over the level's time grid $t_j = j/n$, with the time where it occurs.

use super::{Ctx, ExpError};
use evhi::geometry::PAPER_SINGULAR as SINGULAR;
use evhi::scenario::Scenario;
use evhi::study::graded::{Graded, MU, Split, compute, draw, plan, units};

/// The families: name, and the points a graded mesh refines towards (none: uniform).
pub const FAMILIES: [(&str, &[[f64; 2]]); 4] = [
    ("uniform", &[]),
    ("graded", &SINGULAR),
    ("clamp ends", &[SINGULAR[0], SINGULAR[1]]),
    ("top corners", &[SINGULAR[2], SINGULAR[3]]),
];

/// The loads of the study (one batched run per mesh).
pub const LOADS: [&str; 2] = ["literal", "figure"];

pub fn run(ctx: &Ctx) -> Result<(), ExpError> {
    let plan = plan(ctx.quick);
    let scns = LOADS
        .iter()
        .map(|s| Scenario::load(s))
        .collect::<Result<Vec<_>, _>>()?;
    let families: Vec<(String, Vec<[f64; 2]>)> = FAMILIES
        .iter()
        .map(|(f, p)| (f.to_string(), p.to_vec()))
        .collect();
    ctx.add_units(units(&plan, families.len()));
    // The exponents the static control names (`singular`): the top corner's real
    // one, the clamp end's real part.
    use evhi::study::corners::{Edge, clamp_end_exponent, wedge_exponents};
    let kappa_m = 3.0 - 4.0 * scns[0].kappa();
    let top = wedge_exponents(
        std::f64::consts::FRAC_PI_2,
        kappa_m,
        [Edge::Clamped, Edge::Free],
    );
    let groups: [(&str, &[[f64; 2]], f64); 2] = [
        ("top corners", &SINGULAR[2..], top[0]),
        ("clamp ends", &SINGULAR[..2], clamp_end_exponent(kappa_m).0),
    ];
    let split = Split {
        groups: &groups,
        radius: 0.125,
        halvings: 5,
    };
    let Graded {
        table: t,
        ref_dofs,
        split: tables,
    } = compute(&scns, &families, &plan, &SINGULAR, Some(&split), &|m| {
        ctx.log(m)
    })?;
    let params = format!(
        "newest-vertex bisection of the n = 4 mesh; uniform: longest edge <= 2 sqrt2 / n; graded: <= D min(1, max(r, D^(1/mu))^(1-mu)) with D = 2 sqrt2 / n, mu = {MU}, r = distance of the triangle's centroid to the nearest clamp end or top corner (family graded), clamp end only (clamp ends), top corner only (top corners); min_longest_edge = the shortest longest edge of the mesh; k = 1/n; reference: graded level {} ({} dofs), k = 1/{}; error: relative energy norm at t = T; order_dofs = -2 dln(err) / dln(dofs) (1 = order 1 in h for a uniform mesh); increment = ||u_n - u_2n||_E / ||u_2n||_E against the next level of the same family (no reference), at T and its maximum over t_j = j/n, with the t where it occurs; order_increment_dofs and order_increment_max_dofs from increment_T and increment_max",
        plan.n_ref, ref_dofs, plan.n_ref
    );
    let path = ctx.write("graded_convergence.csv", &t, &params)?;
    if let Some((regions, corner)) = tables {
        let exps = format!(
            "exponents: top corners {:.6} (wedge pi/2, clamped-free), clamp ends {} (real part)",
            groups[0].2, groups[1].2
        );
        ctx.write(
            "graded_regions.csv",
            &regions,
            &format!(
                "the error at T of graded_convergence.csv split by where it sits: within {} of the top corners (0,1), (2,1), within {} of the clamp ends (0,1/2), (2,1/2) (a triangle of the reference mesh by its centroid), and the rest; err_*_percent = 100 ||e||_E,region / ||u_ref||_E (their squares add up to rel_err_T_percent's); h_* = the level's longest edge at (0,1) resp. (0,1/2); order_* = dln(err) / dln(h_*); order_rest_dofs = -2 dln(err_rest) / dln(dofs); strength_* = (err_*_percent / 100) / h_*^lambda; share_* = err_*^2 / rel_err_T^2; {exps}",
                split.radius, split.radius
            ),
        )?;
        ctx.write(
            "graded_corner_energy.csv",
            &corner,
            &format!(
                "the reference of graded_convergence.csv (graded level {}, {} dofs) at T: energy_share = the share of its squared energy norm within rho of the two points (a triangle by its centroid); local_exponent = ln(share(2 rho) / share(rho)) / (2 ln 2), lambda where r^lambda holds the energy, 1 for a smooth field; strength = sqrt(share) / rho^lambda; {exps}",
                plan.n_ref, ref_dofs
            ),
        )?;
    }
    let names = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    draw(
        &ctx.figures,
        "graded_convergence",
        &path,
        &names(&LOADS),
        &names(&FAMILIES.map(|f| f.0)),
    )
}
