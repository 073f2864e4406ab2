//! The factorisation phases of a scene, each alone and timed (medians of 5): the
//! ordering, the analysis and numeric factorisation of the run's $B$, and the smallness
//! check's trace constant. `cargo run --release --example mesh_phases -- SCENE [N]`
use evhi::linalg::Cholesky;
use evhi::ordering::Ordering;
use evhi::scenario::Scenario;
use evhi::simulation::{RunSettings, Simulation};
use std::time::Instant;

fn median<T>(f: impl Fn() -> T) -> f64 {
    let mut v: Vec<f64> = (0..5)
        .map(|_| {
            let t = Instant::now();
            std::hint::black_box(f());
            t.elapsed().as_secs_f64()
        })
        .collect();
    v.sort_by(f64::total_cmp);
    v[2]
}

fn main() {
    let mut args = std::env::args().skip(1);
    let scn = Scenario::load(&args.next().unwrap_or("figure".into())).unwrap();
    let n: usize = args.next().and_then(|s| s.parse().ok()).unwrap_or(512);
    let mut settings = RunSettings::default();
    if scn.body().is_none() {
        settings = settings.with_n(n);
    }
    let sim = Simulation::new(scn.clone(), settings).unwrap();
    let disc = sim.discretisation();
    let (mesh, dofs, c) = (&disc.mesh, &disc.dofs, &disc.contact_dofs);
    let order = || {
        if mesh.pattern.is_grid() {
            Ordering::nested_dissection(mesh, dofs, c)
        } else {
            Ordering::coordinate_dissection(mesh, dofs, c)
        }
    };
    // The first call orders the mesh; a mesh keeps its node order, so later calls
    // only map it to the dofs.
    let clock = Instant::now();
    let o = order();
    let t_first = clock.elapsed().as_secs_f64();
    let t_order = median(order);
    let t_factor = median(|| Cholesky::factor(&disc.b, &o).unwrap());
    let nnz = Cholesky::factor(&disc.b, &o).unwrap().nnz_l();
    let t_trace = median(|| evhi::norms::trace_norm_sq(&scn, n).unwrap());
    println!(
        "{}: dofs {} ordering {t_first:.3} s (then {t_order:.3} s, kept), factor (analysis + numeric) {t_factor:.3} s, nnz(L) {nnz}, trace constant {t_trace:.3} s",
        scn.name(),
        dofs.count
    );
}
