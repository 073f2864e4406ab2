//! Metamorphic relations of the discrete problem, for every registered certified step
//! solver: scaling the loads, the law's breakpoints and jumps and the limit g by s
//! scales the solution by s (the law's slopes unchanged), so each solver must certify
//! the scaled problem and return s times the unscaled contact displacements. This
//! would have caught issue 27's cases 1 (a certificate blind at extreme scales) and 13
//! (the convexification's absolute tolerances).

use evhi::scenario::Scenario;
use evhi::scheme::{Settings, run};

/// `figure` (h = k = 1/16) with loads, g, breakpoints and jumps scaled by `s`.
fn scaled(s: f64) -> Scenario {
    let text = format!(
        "name = \"scaled\"\nT = 1.0\ng = {g:e}\n[material]\nE = 1000.0\nkappa = 0.4\nalpha = 100.0\nbeta = 50.0\n\
         [loads]\nf0 = [0.0, {f0:e}]\nf2 = [0.0, {f2:e}]\n\
         [law]\nbreakpoints = [0.0, {b1:e}, {b2:e}]\nslopes = [0.0, 200.0, -100.0, 300.0]\njumps = [0.0, {j:e}, 0.0]\n",
        g = 0.1 * s,
        f0 = -5.0 * s,
        f2 = -75.0 * s,
        b1 = 0.05 * s,
        b2 = 0.075 * s,
        j = 1.0 * s,
    );
    Scenario::from_toml(&text, "scaled").unwrap()
}

/// The contact normal displacements at T of `scn` with the solver `name`.
fn contact_at_t(scn: &Scenario, name: &str) -> Vec<f64> {
    let entry = evhi::step::solver(name).unwrap();
    let mut solver = entry.build();
    let r = run(
        scn,
        &Settings::new(16, 16),
        solver.as_mut(),
        &mut |_, _, _| {},
    )
    .unwrap_or_else(|e| panic!("{name} at scale of g = {}: {e}", scn.g));
    assert!(
        r.records.iter().all(|rec| rec.certificate.max() <= 1e-10),
        "{name}"
    );
    r.contact.iter().map(|c| c.u_nu).collect()
}

#[test]
fn scaling_loads_g_and_the_law_scales_the_solution() {
    for entry in evhi::step::SOLVERS.iter().filter(|e| e.certified) {
        let base = contact_at_t(&scaled(1.0), entry.name);
        let norm = base.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        for s in [1e-6, 1e-3, 10.0, 1e3] {
            let u = contact_at_t(&scaled(s), entry.name);
            let gap = u
                .iter()
                .zip(&base)
                .fold(0.0f64, |a, (x, y)| a.max((x / s - y).abs()));
            assert!(
                gap <= 1e-7 * norm,
                "{} at s = {s:e}: {gap:e} against {norm:e}",
                entry.name
            );
        }
    }
}
