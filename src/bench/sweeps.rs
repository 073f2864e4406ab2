//! What each ingredient of the triangular sweeps buys (`evhi bench --sweeps`):
//! the step matrix of `figure` at $h = k = 1/n$, one forward and one backward sweep
//! timed for faer's own solve and for ours with the ordering, threads, prefetch and
//! number of columns varied, beside the machine's streaming bandwidth.

use super::tables::SweepRow;
use evhi::assembly::Pair;
use evhi::linalg::Cholesky;
use evhi::ordering::Ordering;
use evhi::scenario::Scenario;
use evhi::scheme::Discretisation;
use evhi::study::{Ctx, ExpError};
use evhi::timing::median;
use faer::linalg::solvers::SolveCore;
use std::time::Instant;

/// Repetitions of each timing; the median is kept.
const REPEAT: usize = 21;

/// One variant as measured (the table's row, [`SweepRow`], adds what follows from it).
struct Row {
    variant: &'static str,
    ordering: &'static str,
    threads: u64,
    prefetch: bool,
    columns: u64,
    nnz_l: f64,
    forward_ms: f64,
    backward_ms: f64,
}

/// $\sum_i v_i$ with eight partial sums: a dependency chain of additions would
/// measure the adder's latency, not the memory.
fn sum(v: &[f64]) -> f64 {
    let mut s = [0.0; 8];
    let chunks = v.chunks_exact(8);
    let rest: f64 = chunks.remainder().iter().sum();
    for c in chunks {
        for l in 0..8 {
            s[l] += c[l];
        }
    }
    s.iter().sum::<f64>() + rest
}

/// Median seconds of a sum over `len` values on `threads` threads: the rate at
/// which this machine streams memory, the bound of a sweep.
fn stream(values: &[f64], threads: usize) -> f64 {
    let times: Vec<f64> = (0..REPEAT)
        .map(|_| {
            let t = Instant::now();
            let parts = values.chunks(values.len().div_ceil(threads));
            let total: f64 = std::thread::scope(|s| {
                let handles: Vec<_> = parts.map(|p| s.spawn(move || sum(p))).collect();
                handles.into_iter().map(|h| h.join().expect("sum")).sum()
            });
            std::hint::black_box(total);
            t.elapsed().as_secs_f64()
        })
        .collect();
    median(times)
}

fn time_ours(chol: &Cholesky, b: &[f64], columns: usize) -> (f64, f64) {
    let bs: Vec<&[f64]> = (0..columns).map(|_| b).collect();
    let (mut f, mut w) = (vec![], vec![]);
    for _ in 0..REPEAT {
        let t = Instant::now();
        let xs = chol.forward_many(&bs);
        f.push(t.elapsed().as_secs_f64());
        let t = Instant::now();
        std::hint::black_box(chol.backward_many(xs));
        w.push(t.elapsed().as_secs_f64());
    }
    (1e3 * median(f), 1e3 * median(w))
}

pub fn run(ctx: &Ctx, n: usize, machine: &str) -> Result<(), ExpError> {
    let scn = Scenario::load("figure")?;
    let disc = Discretisation::new(&scn, n)?;
    let k = scn.t_end() / n as f64;
    let kmat = Pair::new(&disc.a, &disc.b)
        .ok_or_else(|| {
            ExpError::File(evhi::output::FileError::Table {
                path: "bench_sweeps".into(),
                message: "A and B do not share their pattern".into(),
            })
        })?
        .lin_comb(1.0, k);
    let b: Vec<f64> = disc.f.iter().map(|f| k * f).collect();
    let fail = |e: String| {
        ExpError::File(evhi::output::FileError::Table {
            path: "bench_sweeps".into(),
            message: e,
        })
    };
    let mut rows = vec![];

    // faer's own: AMD, supernodal, its solve (forward and backward in one call).
    ctx.log(&format!("sweeps at n = {n}: faer"));
    let llt = kmat
        .as_ref()
        .sp_cholesky(faer::Side::Lower)
        .map_err(|e| fail(format!("{e:?}")))?;
    let mut x = faer::Mat::<f64>::from_fn(b.len(), 1, |i, _| b[i]);
    let t: Vec<f64> = (0..REPEAT)
        .map(|_| {
            let t = Instant::now();
            llt.solve_in_place_with_conj(faer::Conj::No, x.as_mut());
            t.elapsed().as_secs_f64()
        })
        .collect();
    rows.push(Row {
        variant: "faer's solve",
        ordering: "amd",
        threads: 1,
        prefetch: false,
        columns: 1,
        nnz_l: f64::NAN,
        forward_ms: f64::NAN,
        backward_ms: 1e3 * median(t),
    });

    let amd = Ordering::amd(&kmat, &disc.contact_dofs).map_err(|e| fail(e.to_string()))?;
    let nd = Ordering::nested_dissection(&disc.mesh, &disc.dofs, &disc.contact_dofs);
    let mut chol_amd = Cholesky::factor(&kmat, &amd).map_err(|e| fail(e.to_string()))?;
    let mut chol_nd = Cholesky::factor(&kmat, &nd).map_err(|e| fail(e.to_string()))?;
    let plan: [(&str, bool, bool, usize); 7] = [
        ("amd", false, false, 1),
        ("amd", false, true, 1),
        ("nd", false, true, 1),
        ("nd", true, false, 1),
        ("nd", true, true, 1),
        ("nd", true, true, 2),
        ("nd", true, true, 4),
    ];
    for (ordering, parallel, prefetch, columns) in plan {
        ctx.log(&format!(
            "sweeps at n = {n}: ours, {ordering}, {} thread(s), prefetch {prefetch}, {columns} column(s)",
            if parallel { 2 } else { 1 }
        ));
        let chol = if ordering == "amd" {
            &mut chol_amd
        } else {
            // Rebuilt so that `sequential` can be undone.
            chol_nd = Cholesky::factor(&kmat, &nd).map_err(|e| fail(e.to_string()))?;
            &mut chol_nd
        };
        if !parallel {
            chol.sequential();
        }
        chol.set_prefetch(prefetch);
        let (f, w) = time_ours(chol, &b, columns);
        rows.push(Row {
            variant: "ours",
            ordering,
            threads: if chol.is_parallel() { 2 } else { 1 },
            prefetch,
            columns: columns as u64,
            nnz_l: chol.nnz_l() as f64,
            forward_ms: f,
            backward_ms: w,
        });
    }

    // The machine's streaming rate over as many values as the ND factor holds.
    let values = vec![1.0f64; chol_nd.nnz_l()];
    for threads in [1usize, 2] {
        ctx.log(&format!("sweeps: streaming sum, {threads} thread(s)"));
        let s = stream(&values, threads);
        rows.push(Row {
            variant: "streaming sum",
            ordering: "",
            threads: threads as u64,
            prefetch: false,
            columns: 1,
            nnz_l: values.len() as f64,
            // One pass; a solve makes two.
            forward_ms: 1e3 * s,
            backward_ms: 1e3 * s,
        });
    }

    let total = |r: &Row| {
        if r.forward_ms.is_nan() {
            r.backward_ms
        } else {
            r.forward_ms + r.backward_ms
        }
    };
    let t = SweepRow::table(
        &rows
            .iter()
            .map(|r| SweepRow {
                variant: r.variant.to_string(),
                ordering: r.ordering.to_string(),
                threads: r.threads,
                prefetch: r.prefetch.to_string(),
                columns: r.columns,
                nnz_l: r.nnz_l,
                forward_ms: r.forward_ms,
                backward_ms: r.backward_ms,
                total_ms: total(r),
                ms_per_column: total(r) / r.columns as f64,
                // Bytes of values read by the two passes over the time they took.
                gb_per_s: 2.0 * 8.0 * r.nnz_l / (1e-3 * total(r)) / 1e9,
            })
            .collect::<Vec<_>>(),
    );
    ctx.write_as(
        "bench_sweeps.csv",
        &t,
        "bench --sweeps",
        &format!(
            "machine: {machine}; step matrix of `figure` at h = k = 1/{n}; medians of {REPEAT} sweeps; total_ms = forward + backward (faer's solve: both in one call); gb_per_s = 16 bytes x nnz_l / total"
        ),
    )?;
    Ok(())
}
