use evhi::assembly::Pair;
use evhi::linalg::Cholesky;
use evhi::ordering::Ordering;
use evhi::scenario::Scenario;
use evhi::scheme::Discretisation;
use std::time::Instant;

fn med(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let n: usize = std::env::args().nth(1).map_or(512, |s| s.parse().unwrap());
    let scn = Scenario::load("figure").unwrap();
    let disc = Discretisation::new(&scn, n).unwrap();
    let k = 1.0 / n as f64;
    let kmat = Pair::new(&disc.a, &disc.b).unwrap().lin_comb(1.0, k);
    for (name, ord) in [(
        "nd",
        Ordering::nested_dissection(&disc.mesh, &disc.dofs, &disc.contact_dofs),
    )] {
        let t = Instant::now();
        let mut chol = Cholesky::factor(&kmat, &ord).unwrap();
        let tf = t.elapsed().as_secs_f64();
        for par in [true, false] {
            if !par {
                chol.sequential();
            }
            let (mut f, mut b) = (vec![], vec![]);
            let mut x = vec![];
            for _ in 0..41 {
                let t = Instant::now();
                x = chol.forward(&disc.f);
                f.push(t.elapsed().as_secs_f64());
                let t = Instant::now();
                let u = chol.backward(x.clone());
                b.push(t.elapsed().as_secs_f64());
                std::hint::black_box(u);
            }
            println!(
                "{name} nnz {} factor {:.3} parallel {} forward {:.2} ms backward {:.2} ms",
                chol.nnz_l(),
                tf,
                chol.is_parallel(),
                1e3 * med(f),
                1e3 * med(b)
            );
            std::hint::black_box(&x);
            for r in [2, 4] {
                let bs: Vec<&[f64]> = (0..r).map(|_| disc.f.as_slice()).collect();
                let (mut f, mut b) = (vec![], vec![]);
                for _ in 0..15 {
                    let t = Instant::now();
                    let xs = chol.forward_many(&bs);
                    f.push(t.elapsed().as_secs_f64());
                    let t = Instant::now();
                    std::hint::black_box(chol.backward_many(xs));
                    b.push(t.elapsed().as_secs_f64());
                }
                println!(
                    "    {r} columns: forward {:.2} ms backward {:.2} ms",
                    1e3 * med(f),
                    1e3 * med(b)
                );
            }
        }
    }
}
