//! The factorisation layer: both orderings are permutations with the contact
//! dofs last, nested dissection's halves are uncoupled, the hand-written
//! triangular solves (one thread or two) solve $Kx = b$, and the shared-pattern
//! products equal faer's.

use evhi::assembly::{Pair, lin_comb, matvec};
use evhi::linalg::Cholesky;
use evhi::ordering::Ordering;
use evhi::scenario::Scenario;
use evhi::scheme::{Discretisation, OrderingKind};
use evhi::simulation::Simulation;
use evhi::step::newton::Newton;

mod common;

fn operators(name: &str, n: usize) -> (Discretisation, evhi::assembly::SpMat) {
    let scn = Scenario::load(name).unwrap();
    let disc = Discretisation::new(&scn, n).unwrap();
    let k = lin_comb(1.0, &disc.a, 1.0 / n as f64, &disc.b);
    (disc, k)
}

fn rel_residual(k: &evhi::assembly::SpMat, x: &[f64], b: &[f64]) -> f64 {
    let kx = matvec(k, x);
    let r: f64 = kx.iter().zip(b).map(|(a, c)| (a - c).powi(2)).sum();
    let nb: f64 = b.iter().map(|c| c * c).sum();
    (r / nb).sqrt()
}

fn is_permutation(fwd: &[usize]) -> bool {
    let mut seen = vec![false; fwd.len()];
    fwd.iter()
        .all(|&d| d < seen.len() && !std::mem::replace(&mut seen[d], true))
}

#[test]
fn orderings_are_permutations_with_the_contact_dofs_last() {
    for name in ["figure", "smooth"] {
        let (disc, k) = operators(name, 32);
        let m = disc.contact_dofs.len();
        for ord in [
            Ordering::nested_dissection(&disc.mesh, &disc.dofs, &disc.contact_dofs),
            Ordering::amd(&k, &disc.contact_dofs).unwrap(),
        ] {
            assert!(is_permutation(&ord.fwd), "{name}: not a permutation");
            assert_eq!(ord.fwd[ord.fwd.len() - m..], disc.contact_dofs[..]);
        }
    }
}

#[test]
fn no_matrix_entry_couples_the_two_halves() {
    for name in ["figure", "smooth"] {
        let (disc, k) = operators(name, 32);
        let ord = Ordering::nested_dissection(&disc.mesh, &disc.dofs, &disc.contact_dofs);
        let (n1, n2) = ord.halves.unwrap();
        assert!(n1 > 0 && n2 > 0 && n1 + n2 < ord.fwd.len());
        let inv = ord.inverse();
        let half = |d: usize| match inv[d] {
            p if p < n1 => 1,
            p if p < n1 + n2 => 2,
            _ => 0,
        };
        let (ptr, idx) = (k.col_ptr(), k.row_idx());
        let mut entries = 0;
        for j in 0..k.ncols() {
            for &i in &idx[ptr[j]..ptr[j + 1]] {
                let (hi, hj) = (half(i), half(j));
                assert!(
                    hi == 0 || hj == 0 || hi == hj,
                    "{name}: K[{i},{j}] couples the halves"
                );
                entries += 1;
            }
        }
        assert!(entries > 0);
    }
}

#[test]
fn parallel_sequential_and_amd_solves_agree() {
    let (disc, k) = operators("figure", 64);
    let b: Vec<f64> = (0..k.nrows())
        .map(|i| ((i * 7919) % 101) as f64 - 50.0)
        .collect();
    let nd = Ordering::nested_dissection(&disc.mesh, &disc.dofs, &disc.contact_dofs);
    let par = Cholesky::factor(&k, &nd).unwrap();
    assert!(
        par.is_parallel(),
        "the halves should give a parallel factor"
    );
    let mut seq = Cholesky::factor(&k, &nd).unwrap();
    seq.sequential();
    assert!(!seq.is_parallel());
    let amd = Cholesky::factor(&k, &Ordering::amd(&k, &disc.contact_dofs).unwrap()).unwrap();
    let xs = [par.solve(&b), seq.solve(&b), amd.solve(&b)];
    for x in &xs {
        let r = rel_residual(&k, x, &b);
        assert!(r < 1e-12, "relative residual {r:e}");
    }
    // The two threads do the same arithmetic as one, except for the order in
    // which the halves' updates of the tail are summed.
    let d: f64 = xs[0]
        .iter()
        .zip(&xs[1])
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    let scale = xs[1].iter().map(|a| a.abs()).fold(0.0, f64::max);
    assert!(
        d <= 1e-12 * scale,
        "parallel and sequential differ by {d:e}"
    );
}

#[test]
fn the_schur_complement_does_not_depend_on_the_ordering() {
    let (disc, k) = operators("figure", 32);
    let s = |ord: &Ordering| {
        let c = Cholesky::factor(&k, ord).unwrap();
        c.l_cc() * c.l_cc().transpose()
    };
    let a = s(&Ordering::nested_dissection(
        &disc.mesh,
        &disc.dofs,
        &disc.contact_dofs,
    ));
    let b = s(&Ordering::amd(&k, &disc.contact_dofs).unwrap());
    let diff = (&a - &b).norm_max();
    assert!(
        diff <= 1e-10 * b.norm_max(),
        "Schur complements differ by {diff:e}"
    );
}

#[test]
fn shared_pattern_products_equal_faers() {
    let (disc, _) = operators("smooth", 32);
    let pair = Pair::new(&disc.a, &disc.b).expect("A and B share their pattern");
    let x: Vec<f64> = (0..disc.a.nrows()).map(|i| (i as f64).sin()).collect();
    let k = 0.25;
    let kmat = lin_comb(1.0, &disc.a, k, &disc.b);
    let abs_norm = {
        let (ptr, idx, val) = (kmat.col_ptr(), kmat.row_idx(), kmat.val());
        let mut y = vec![0.0f64; kmat.nrows()];
        for j in 0..kmat.ncols() {
            for p in ptr[j]..ptr[j + 1] {
                y[idx[p]] += val[p].abs() * x[j].abs();
            }
        }
        y.into_iter().fold(0.0, f64::max)
    };
    for threads in [1, 2] {
        let p = pair.products(&x, k, threads);
        for (mine, faer) in [(p.ax, matvec(&disc.a, &x)), (p.bx, matvec(&disc.b, &x))] {
            let d = mine
                .iter()
                .zip(&faer)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(d < 1e-10, "threads {threads}: products differ by {d:e}");
        }
        assert!(
            (p.abs_norm - abs_norm).abs() <= 1e-12 * abs_norm,
            "threads {threads}: |K||x|"
        );
        assert_eq!(
            p.abs_norm,
            evhi::assembly::abs_matvec_norm(&kmat, &x).max(p.abs_norm)
        );
    }
    let k = pair.lin_comb(1.0, 0.25);
    let reference = lin_comb(1.0, &disc.a, 0.25, &disc.b);
    let d = matvec(&k, &x)
        .iter()
        .zip(&matvec(&reference, &x))
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(d < 1e-10, "combinations differ by {d:e}");
    // A matrix of another mesh has another pattern.
    let other = operators("smooth", 16).0;
    assert!(Pair::new(&disc.a, &other.b).is_none());
}

#[test]
fn both_orderings_give_the_same_run() {
    let scn = Scenario::load("figure").unwrap();
    let mut last = vec![];
    for ordering in [OrderingKind::NestedDissection, OrderingKind::Amd] {
        let settings = common::general(32, 16).with_ordering(ordering);
        let r = common::solve_with(&scn, settings, None, &mut Newton::default(), &mut ()).unwrap();
        last.push(r.u);
    }
    let d = last[0]
        .iter()
        .zip(&last[1])
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(d < 1e-12, "orderings change u_N by {d:e}");
}

#[test]
fn a_batch_run_equals_separate_runs() {
    let scns = [
        Scenario::load("literal").unwrap(),
        Scenario::load("figure").unwrap(),
    ];
    let sim = Simulation::new(scns[0].clone(), common::general(32, 16)).unwrap();
    let mut seen = vec![0usize; 2];
    let (mut a, mut b) = (Newton::default(), Newton::default());
    let batch = sim
        .solve_batch(&scns, &mut [&mut a, &mut b], &mut |i, _, _, _, _| {
            seen[i] += 1
        })
        .unwrap();
    assert_eq!(seen, vec![16, 16]);
    for (scn, r) in scns.iter().zip(&batch) {
        let alone = common::run_newton(scn, 32, 16).unwrap();
        // Column j of a batched sweep does the same arithmetic as a single one.
        assert_eq!(alone.u, r.u, "{}: batch and single runs differ", scn.name());
        assert_eq!(alone.records.len(), r.records.len());
    }
}

#[test]
fn a_batch_refuses_scenarios_with_different_operators() {
    let scns = [
        Scenario::load("figure").unwrap(),
        Scenario::load("smooth").unwrap(),
    ];
    let (mut a, mut b) = (Newton::default(), Newton::default());
    let sim = Simulation::new(scns[0].clone(), common::general(16, 4)).unwrap();
    let err = sim
        .solve_batch(&scns, &mut [&mut a, &mut b], &mut |_, _, _, _, _| {})
        .err()
        .expect("different supports must be refused");
    let msg = err.to_string();
    assert!(msg.contains("scenarios") && msg.contains("smooth"), "{msg}");
}

#[test]
fn many_columns_solve_like_one() {
    let (disc, k) = operators("figure", 32);
    let chol = Cholesky::factor(
        &k,
        &Ordering::nested_dissection(&disc.mesh, &disc.dofs, &disc.contact_dofs),
    )
    .unwrap();
    // Six columns: a group of four and a group of two.
    let bs: Vec<Vec<f64>> = (0..6)
        .map(|j| {
            (0..k.nrows())
                .map(|i| ((i * (j + 3)) % 17) as f64 - 8.0)
                .collect()
        })
        .collect();
    let refs: Vec<&[f64]> = bs.iter().map(Vec::as_slice).collect();
    let xs = chol.backward_many(chol.forward_many(&refs));
    for (x, b) in xs.iter().zip(&bs) {
        assert_eq!(*x, chol.solve(b));
    }
}

/// A forward sweep of right-hand sides that vanish off the contact dofs may start at
/// the first supernode holding a contact column: the same bits as the full sweep (in
/// both orderings, with nested dissection's halves split or not, one to six columns),
/// and the fields solved from it are the same bits as well.
#[test]
fn contact_forward_sweeps_skip_the_interior_bit_for_bit() {
    let (disc, k) = operators("figure", 32);
    let nd = Ordering::nested_dissection(&disc.mesh, &disc.dofs, &disc.contact_dofs);
    let amd = Ordering::amd(&k, &disc.contact_dofs).unwrap();
    let split = Cholesky::factor(&k, &nd).unwrap();
    assert!(split.is_parallel(), "the test wants the split halves");
    let mut seq = Cholesky::factor(&k, &nd).unwrap();
    seq.sequential();
    let amd = Cholesky::factor(&k, &amd).unwrap();
    let bits = |v: &[Vec<f64>]| -> Vec<Vec<u64>> {
        v.iter()
            .map(|x| x.iter().map(|y| y.to_bits()).collect())
            .collect()
    };
    for chol in [&split, &seq, &amd] {
        for cols in 1..=6 {
            let bs: Vec<Vec<f64>> = (0..cols)
                .map(|j| {
                    let mut b = vec![0.0; k.nrows()];
                    for (i, &d) in disc.contact_dofs.iter().enumerate() {
                        b[d] = ((i * (j + 5)) % 13) as f64 - 6.5;
                    }
                    b
                })
                .collect();
            let refs: Vec<&[f64]> = bs.iter().map(Vec::as_slice).collect();
            let full = chol.forward_many(&refs);
            let contact = chol.forward_many_contact(&refs);
            assert_eq!(bits(&contact), bits(&full), "{cols} column(s)");
            assert_eq!(
                bits(&chol.backward_many(contact)),
                bits(&chol.backward_many(full))
            );
        }
    }
}

/// The mesh scenes the coordinate dissection is tried on: the paper's rectangle read
/// from its mesh file, the holed block and the Hertz cylinder.
const MESH_SCENES: [&str; 3] = [
    "data/scenarios/examples/paper_mesh.toml",
    "data/scenarios/examples/holed_block.toml",
    "data/scenarios/examples/hertz.toml",
];

#[test]
fn coordinate_dissection_is_a_permutation_with_uncoupled_halves() {
    for name in MESH_SCENES {
        let (disc, k) = operators(name, 16);
        assert!(!disc.mesh.pattern.is_grid(), "{name}: read as a grid");
        let m = disc.contact_dofs.len();
        let ord = Ordering::coordinate_dissection(&disc.mesh, &disc.dofs, &disc.contact_dofs);
        assert!(is_permutation(&ord.fwd), "{name}: not a permutation");
        assert_eq!(ord.fwd.len(), disc.dofs.count);
        assert_eq!(ord.fwd[ord.fwd.len() - m..], disc.contact_dofs[..]);
        let (n1, n2) = ord.halves.expect("two halves");
        assert!(n1 > 0 && n2 > 0 && n1 + n2 < ord.fwd.len() - m, "{name}");
        let inv = ord.inverse();
        let half = |d: usize| match inv[d] {
            p if p < n1 => 1,
            p if p < n1 + n2 => 2,
            _ => 0,
        };
        let (ptr, idx) = (k.col_ptr(), k.row_idx());
        let mut inside = [0usize; 2];
        for j in 0..k.ncols() {
            for &i in &idx[ptr[j]..ptr[j + 1]] {
                let (hi, hj) = (half(i), half(j));
                assert!(
                    hi == 0 || hj == 0 || hi == hj,
                    "{name}: K[{i},{j}] couples the halves"
                );
                if hi == hj && hi > 0 {
                    inside[hi - 1] += 1;
                }
            }
        }
        assert!(inside[0] > 0 && inside[1] > 0, "{name}: {inside:?}");
    }
}

#[test]
fn coordinate_dissection_solves_as_amd_does_on_mesh_scenes() {
    for name in MESH_SCENES {
        let (disc, k) = operators(name, 16);
        let b: Vec<f64> = (0..k.nrows())
            .map(|i| ((i * 7919) % 101) as f64 - 50.0)
            .collect();
        let cd = Ordering::coordinate_dissection(&disc.mesh, &disc.dofs, &disc.contact_dofs);
        let par = Cholesky::factor(&k, &cd).unwrap();
        assert!(
            par.is_parallel(),
            "{name}: the halves should split the factor"
        );
        let amd = Cholesky::factor(&k, &Ordering::amd(&k, &disc.contact_dofs).unwrap()).unwrap();
        let (x, y) = (par.solve(&b), amd.solve(&b));
        let r = rel_residual(&k, &x, &b);
        assert!(r < 1e-12, "{name}: relative residual {r:e}");
        let d = x
            .iter()
            .zip(&y)
            .map(|(a, c)| (a - c).abs())
            .fold(0.0, f64::max);
        let scale = y.iter().map(|a| a.abs()).fold(0.0, f64::max);
        assert!(d <= 1e-12 * scale, "{name}: the orderings differ by {d:e}");
    }
}
