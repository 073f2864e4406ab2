use evhi::assembly::{Pair, matvec};
use evhi::linalg::Cholesky;
use evhi::ordering::Ordering;
use evhi::scenario::Scenario;
use evhi::scheme::Discretisation;
use faer::linalg::solvers::Solve;

fn main() {
    let name = std::env::args().nth(1).unwrap_or("smooth".into());
    let n: usize = std::env::args().nth(2).map_or(512, |s| s.parse().unwrap());
    let scn = Scenario::load(&name).unwrap();
    let disc = Discretisation::new(&scn, n).unwrap();
    let k = 1.0 / n as f64;
    let kmat = Pair::new(&disc.a, &disc.b).unwrap().lin_comb(1.0, k);
    let b: Vec<f64> = disc.f.iter().map(|f| k * f).collect();
    let inf = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let res = |x: &[f64]| {
        let kx = matvec(&kmat, x);
        let r: Vec<f64> = kx.iter().zip(&b).map(|(a, c)| a - c).collect();
        inf(&r) / inf(&b).max(inf(&kx))
    };
    for (name, ord) in [
        (
            "nd",
            Ordering::nested_dissection(&disc.mesh, &disc.dofs, &disc.contact_dofs),
        ),
        ("amd", Ordering::amd(&kmat, &disc.contact_dofs).unwrap()),
    ] {
        let mut c = Cholesky::factor(&kmat, &ord).unwrap();
        println!("{name} parallel residual {:e}", res(&c.solve(&b)));
        c.sequential();
        println!("{name} sequential residual {:e}", res(&c.solve(&b)));
    }
    let llt = kmat.as_ref().sp_cholesky(faer::Side::Lower).unwrap();
    let x = llt.solve(faer::Mat::from_fn(b.len(), 1, |i, _| b[i]));
    let x: Vec<f64> = (0..b.len()).map(|i| x[(i, 0)]).collect();
    println!("faer default residual {:e}", res(&x));
}
