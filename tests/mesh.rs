//! The mesh patterns, the general P1 interpolation between nested meshes, the
//! nested-dissection ordering of criss-cross meshes and the exact P1 norms.

use evhi::geometry::Geometry;
use evhi::material::Isotropic;
use evhi::mesh::{Interpolation, Mesh, Pattern};
use evhi::norms::field_norms;
use evhi::scenario::Scenario;

mod common;

const PATTERNS: [Pattern; 3] = [
    Pattern::Diagonal,
    Pattern::Antidiagonal,
    Pattern::CrissCross,
];

#[test]
fn every_pattern_tiles_the_domain_counter_clockwise() {
    for p in PATTERNS {
        let m = Mesh::build(8, &Geometry::paper(), p).unwrap();
        let per_cell = if p == Pattern::CrissCross { 4 } else { 2 };
        assert_eq!(m.triangles.len(), per_cell * 8 * 4, "{p:?}");
        let area: f64 = m
            .triangles
            .iter()
            .map(|t| {
                let a = 0.5 * evhi::element::twice_area(t.map(|v| m.nodes[v]));
                assert!(a > 0.0, "{p:?}: triangle {t:?} is not counter-clockwise");
                a
            })
            .sum();
        assert!((area - 2.0).abs() < 1e-12, "{p:?}: area {area}");
        assert_eq!(m.contact.len(), 9);
    }
}

/// Linear fields lie in every P1 space: interpolation reproduces them at every
/// fine node, whatever the two patterns.
#[test]
fn interpolation_reproduces_linear_fields() {
    let lin = |p: [f64; 2]| [1.0 + 2.0 * p[0] - 3.0 * p[1], -0.5 * p[0] + 4.0 * p[1]];
    for pc in PATTERNS {
        for pf in PATTERNS {
            let coarse = Mesh::build(4, &Geometry::paper(), pc).unwrap();
            let fine = Mesh::build(16, &Geometry::paper(), pf).unwrap();
            let vals: Vec<[f64; 2]> = coarse.nodes.iter().map(|&p| lin(p)).collect();
            let out = Interpolation::new(&coarse, &fine).apply(&vals);
            for (p, v) in fine.nodes.iter().zip(&out) {
                let w = lin(*p);
                assert!(
                    (v[0] - w[0]).abs() < 1e-12 && (v[1] - w[1]).abs() < 1e-12,
                    "{pc:?} -> {pf:?} at {p:?}: {v:?} against {w:?}"
                );
            }
        }
    }
}

/// On the paper's pattern the general interpolation equals the closed-form
/// nested one for any (not only linear) field, and the transpose is the adjoint:
/// v·(P u) = (P^T v)·u.
#[test]
fn interpolation_equals_the_structured_prolongation() {
    let coarse = Mesh::structured(8).unwrap();
    let fine = Mesh::structured(32).unwrap();
    let vals: Vec<[f64; 2]> = coarse
        .nodes
        .iter()
        .map(|p| [(3.0 * p[0]).sin(), (p[0] * p[1]).exp()])
        .collect();
    let a = Interpolation::new(&coarse, &fine).apply(&vals);
    let nested = Interpolation::nested(&coarse, &fine).unwrap();
    let b = nested.apply(&vals);
    for (x, y) in a.iter().zip(&b) {
        assert!((x[0] - y[0]).abs() < 1e-14 && (x[1] - y[1]).abs() < 1e-14);
    }
    let v: Vec<[f64; 2]> = fine
        .nodes
        .iter()
        .map(|p| [p[1].cos(), p[0] - p[1]])
        .collect();
    let dot = |x: &[[f64; 2]], y: &[[f64; 2]]| -> f64 {
        x.iter()
            .zip(y)
            .map(|(a, b)| a[0] * b[0] + a[1] * b[1])
            .sum()
    };
    let lhs = dot(&v, &b);
    let rhs = dot(&nested.apply_transpose(&v, coarse.nodes.len()), &vals);
    assert!((lhs - rhs).abs() < 1e-12 * lhs.abs(), "{lhs} against {rhs}");
    // Only nested meshes of the paper's pattern.
    assert!(Interpolation::nested(&fine, &coarse).is_err());
    let cross = Mesh::build(32, &Geometry::paper(), Pattern::CrissCross).unwrap();
    assert!(Interpolation::nested(&coarse, &cross).is_err());
}

/// The exact P1 norms of v = (x, y + 1) on (0,2) x (0,1): ∫|v|² = 8/3 + 14/3,
/// ∫|∇v|² = 4, energy ½∫(a (tr ε)² + b ε:ε) = ½·2·(4a + 2b), max |v| = √8, and
/// v_ν = -(y + 1) = -1 on Γ3, so ‖v_ν‖² = 2. Clamped nodes play no part here.
#[test]
fn field_norms_are_exact_for_linear_fields() {
    let g = Isotropic { a: 3.0, b: 5.0 };
    for p in PATTERNS {
        let m = Mesh::build(8, &Geometry::paper(), p).unwrap();
        let v: Vec<[f64; 2]> = m.nodes.iter().map(|q| [q[0], q[1] + 1.0]).collect();
        let n = field_norms(&m, &g, &v);
        let close = |a: f64, b: f64| (a - b).abs() < 1e-12 * b.abs().max(1.0);
        assert!(
            close(n.l2_sq, 8.0 / 3.0 + 14.0 / 3.0),
            "{p:?} l2 {}",
            n.l2_sq
        );
        assert!(close(n.h1_sq, 4.0), "{p:?} h1 {}", n.h1_sq);
        assert!(
            close(n.energy_sq, 4.0 * 3.0 + 2.0 * 5.0),
            "{p:?} energy {}",
            n.energy_sq
        );
        assert!(close(n.max, 8f64.sqrt()), "{p:?} max {}", n.max);
        assert!(close(n.gamma_sq, 2.0), "{p:?} gamma {}", n.gamma_sq);
    }
}

/// Nested dissection orders the criss-cross centres with their half: the run
/// equals the AMD-ordered one, and no matrix entry couples the halves.
#[test]
fn criss_cross_runs_with_nested_dissection() {
    use evhi::scheme::OrderingKind;
    use evhi::step::newton::Newton;
    let scn = Scenario::load("figure")
        .unwrap()
        .with_pattern(Pattern::CrissCross);
    let mut last = vec![];
    for ordering in [OrderingKind::NestedDissection, OrderingKind::Amd] {
        let settings = common::general(16, 8).with_ordering(ordering);
        let run = common::solve_with(&scn, settings, None, &mut Newton::default(), &mut ());
        last.push(run.unwrap().u);
    }
    let scale = last[1].iter().fold(0.0f64, |a, x| a.max(x.abs()));
    assert!(scale > 0.0);
    for (a, b) in last[0].iter().zip(&last[1]) {
        assert!((a - b).abs() <= 1e-10 * scale, "{a} against {b}");
    }
    let mesh = scn.mesh(16).unwrap();
    let dofs = evhi::mesh::Dofs::new(&mesh, true);
    let cdofs: Vec<usize> = mesh
        .contact
        .iter()
        .map(|&c| dofs.of(c, 1).unwrap())
        .collect();
    let ord = evhi::ordering::Ordering::nested_dissection(&mesh, &dofs, &cdofs);
    let mut seen = ord.fwd.clone();
    seen.sort_unstable();
    assert_eq!(
        seen,
        (0..dofs.count).collect::<Vec<_>>(),
        "not a permutation"
    );
    let (n1, n2) = ord.halves.unwrap();
    let inv = ord.inverse();
    let half = |d: usize| match inv[d] {
        p if p < n1 => Some(0),
        p if p < n1 + n2 => Some(1),
        _ => None,
    };
    for t in &mesh.triangles {
        let dofs = &dofs;
        let ds: Vec<usize> = t
            .iter()
            .flat_map(|&v| (0..2).filter_map(move |c| dofs.of(v, c)))
            .collect();
        let halves: Vec<usize> = ds.iter().filter_map(|&d| half(d)).collect();
        assert!(
            halves.windows(2).all(|w| w[0] == w[1]),
            "triangle {t:?} couples the halves"
        );
    }
}

#[test]
fn a_bad_pattern_is_refused_by_name() {
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data/scenarios/literal.toml"),
    )
    .unwrap();
    let bad = format!("{text}\n[geometry]\npattern = \"hexagons\"\n");
    let err = Scenario::from_toml(&bad, "test").unwrap_err();
    assert_eq!(err.field_name(), Some("geometry.pattern"), "{err}");
    assert!(err.to_string().contains("crisscross"), "{err}");
    let good = format!("{text}\n[geometry]\npattern = \"crisscross\"\n");
    assert_eq!(
        Scenario::from_toml(&good, "test").unwrap().pattern(),
        Pattern::CrissCross
    );
}
