//! The residual estimator ([`evhi::estimator`]) against the truth: the manufactured
//! solutions' energy error on the h-family (N = n).

use evhi::manufactured::SOLUTIONS;
use evhi::manufactured::run::{ExactRun, run_estimated};
use evhi::scenario::Scenario;

/// The efficiency index at the step of the largest error: eta / ||e_n||_E there.
fn efficiency(r: &ExactRun) -> f64 {
    let row = r.max_row();
    row.eta / row.err_e
}

#[test]
fn efficiency_table() {
    let scn = Scenario::load("literal").unwrap();
    println!("{:?} {:?}", scn.elasticity(), scn.viscosity());
    for sol in SOLUTIONS {
        let mut line = format!("{}", sol.name());
        for n in [8, 16, 32] {
            let r = run_estimated(sol, &scn, n, n).unwrap();
            let row = r.max_row();
            line += &format!(
                "  n={n}: step {} eta {:.3e} err {:.3e} eff {:.3} sig {:.3e} eff_s {:.3}",
                row.step,
                row.eta,
                row.err_e,
                efficiency(&r),
                row.err_sigma,
                row.eta / row.err_sigma
            );
        }
        println!("{line}");
    }
}
