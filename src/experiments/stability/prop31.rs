//! The stability bound of Proposition 3.1: $\max_n \|\delta u_n\|_V^2 + k\sum_n \|\delta u_n\|_V^2 \le c$
//! uniformly in $h$ and $k$, with $\delta u_n = (u_n - u_{n-1})/k$ and
//! $\|v\|_V^2 = (\varepsilon(v), \varepsilon(v))_{\mathcal H}$ (4.8). Measured as $k \to 0$ at fixed $h$.

use crate::experiments::{Ctx, ExpError};
use evhi::assembly::{quad_form, stiffness};
use evhi::material::Isotropic;
use evhi::mesh::{Dofs, Mesh};
use evhi::output::csv::Table;
use evhi::scenario::Scenario;
use evhi::simulation::OnStep;
use evhi::step::newton::Newton;

pub fn run(ctx: &Ctx) -> Result<(), ExpError> {
    let (n, steps): (usize, Vec<usize>) = if ctx.quick {
        (8, vec![4, 8, 16, 32])
    } else {
        (32, vec![4, 8, 16, 32, 64, 128, 256, 512, 1024])
    };
    let mesh = Mesh::structured(n)?; // the paper's supports, as in both scenarios below
    let dofs = Dofs::new(&mesh, true);
    // (u, v)_V = (eps(u), eps(v)): the isotropic tensor with a = 0, b = 1.
    let v_mat = stiffness(&mesh, &dofs, &Isotropic { a: 0.0, b: 1.0 });
    let mut rows = vec![];
    for name in ["literal", "figure"] {
        let scn = Scenario::load(name)?;
        for &nsteps in &steps {
            let k = scn.t_end() / nsteps as f64;
            let mut prev = vec![0.0; dofs.count];
            let (mut max_sq, mut sum_sq) = (0.0f64, 0.0f64);
            let sim = crate::experiments::runs::simulation(&scn, n, nsteps)?;
            let mut observer = OnStep::new(|_, _, u: Option<&[f64]>, _: &[_]| {
                let u = u.expect("the general loop forms every step's field");
                let du: Vec<f64> = u.iter().zip(&prev).map(|(a, b)| (a - b) / k).collect();
                let sq = quad_form(&v_mat, &du);
                max_sq = max_sq.max(sq);
                sum_sq += k * sq;
                prev.copy_from_slice(u);
            });
            sim.solve_with(&mut Newton::default(), &mut observer)?;
            rows.push((name, nsteps, k, max_sq.sqrt(), sum_sq, max_sq + sum_sq));
        }
    }
    let t = Table::new()
        .str("scenario", rows.iter().map(|r| r.0.to_string()).collect())
        .u64("steps", rows.iter().map(|r| r.1 as u64).collect())
        .f64("k", rows.iter().map(|r| r.2).collect())
        .f64("max_norm_du", rows.iter().map(|r| r.3).collect())
        .f64("k_sum_norm_du_sq", rows.iter().map(|r| r.4).collect())
        .f64("prop31_lhs", rows.iter().map(|r| r.5).collect());
    ctx.write(
        "stability_prop31.csv",
        &t,
        &format!(
            "h = 1/{n}, solver newton; du_n = (u_n - u_(n-1))/k, ||v||_V^2 = (eps(v), eps(v))"
        ),
    )?;
    Ok(())
}
