//! Assembly: symmetry, rigid-motion kernel and patch test of the unclamped elasticity
//! matrix, and the load vector's total force.

use evhi::assembly::{load, matvec, stiffness};
use evhi::geometry::{Side, Traction};
use evhi::material::Isotropic;
use evhi::mesh::{Dofs, Mesh};

fn field(mesh: &Mesh, dofs: &Dofs, f: impl Fn(f64, f64) -> [f64; 2]) -> Vec<f64> {
    let mut u = vec![0.0; dofs.count];
    for (v, p) in mesh.nodes.iter().enumerate() {
        let val = f(p[0], p[1]);
        for (c, x) in val.iter().enumerate() {
            if let Some(d) = dofs.of(v, c) {
                u[d] = *x;
            }
        }
    }
    u
}

#[test]
fn mesh_counts_match_the_paper() {
    let m = Mesh::structured(128).unwrap();
    assert_eq!(m.triangles.len(), 16_384);
    assert_eq!(m.contact.len(), 129);
    assert_eq!(m.triangles.len() + m.contact.len(), 16_513);
    let d = Dofs::new(&m, true);
    // 129 x 65 nodes, 2 x 33 clamped nodes.
    assert_eq!(d.count, 2 * (129 * 65 - 66));
    assert!(Mesh::structured(6).is_err());
    assert_eq!(Mesh::structured(6).unwrap_err().field_name(), Some("n"));
}

#[test]
fn rigid_motions_are_the_kernel_of_unclamped_b() {
    let mesh = Mesh::structured(8).unwrap();
    let dofs = Dofs::new(&mesh, false);
    let b = stiffness(&mesh, &dofs, &Isotropic::elasticity(1000.0, 0.4));
    for rigid in [
        |_: f64, _: f64| [1.0, 0.0],
        |_: f64, _: f64| [0.0, 1.0],
        |x: f64, y: f64| [-y, x],
    ] {
        let u = field(&mesh, &dofs, rigid);
        let r = matvec(&b, &u);
        let max = r.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        assert!(max < 1e-10, "rigid motion gives force {max}");
    }
    // and a stretch does not
    let u = field(&mesh, &dofs, |x, _| [x, 0.0]);
    assert!(matvec(&b, &u).iter().any(|x| x.abs() > 1.0));
}

#[test]
fn patch_test_linear_field_has_no_interior_force() {
    let mesh = Mesh::structured(8).unwrap();
    let dofs = Dofs::new(&mesh, false);
    let t = Isotropic::elasticity(1000.0, 0.4);
    let b = stiffness(&mesh, &dofs, &t);
    // u = (0.1x + 0.3y, -0.2x + 0.05y): constant strain, so Div σ = 0 and only
    // boundary nodes carry force, equal to the traction σν integrated by P1.
    let u = field(&mesh, &dofs, |x, y| {
        [0.1 * x + 0.3 * y, -0.2 * x + 0.05 * y]
    });
    let r = matvec(&b, &u);
    let (eps11, eps22, eps12) = (0.1, 0.05, 0.5 * (0.3 - 0.2));
    let tr = eps11 + eps22;
    let sxx = t.a * tr + t.b * eps11;
    let syy = t.a * tr + t.b * eps22;
    let sxy = t.b * eps12;
    let side = 2.0 / 8.0;
    for (v, p) in mesh.nodes.iter().enumerate() {
        let on_x = p[0] == 0.0 || p[0] == 2.0;
        let on_y = p[1] == 0.0 || p[1] == 1.0;
        let fx = r[dofs.of(v, 0).unwrap()];
        let fy = r[dofs.of(v, 1).unwrap()];
        if !on_x && !on_y {
            assert!(
                fx.abs() < 1e-11 && fy.abs() < 1e-11,
                "interior node {v}: ({fx}, {fy})"
            );
        } else if !on_x && p[1] == 1.0 {
            // top edge, normal (0, 1): traction (sxy, syy) times side
            assert!((fx - sxy * side).abs() < 1e-10 && (fy - syy * side).abs() < 1e-10);
        } else if !on_y && p[0] == 2.0 {
            assert!((fx - sxx * side).abs() < 1e-10 && (fy - sxy * side).abs() < 1e-10);
        }
    }
}

#[test]
fn matrices_are_symmetric() {
    let mesh = Mesh::structured(4).unwrap();
    let dofs = Dofs::new(&mesh, true);
    let b = stiffness(&mesh, &dofs, &Isotropic::viscosity(100.0, 50.0));
    let dense = b.to_dense();
    for i in 0..dofs.count {
        for j in 0..dofs.count {
            assert!((dense[(i, j)] - dense[(j, i)]).abs() < 1e-12);
        }
    }
}

#[test]
fn load_vector_sums_to_the_total_force() {
    let mesh = Mesh::structured(8).unwrap();
    let dofs = Dofs::new(&mesh, false);
    let top = |f: [f64; 2], side: Side, from: f64, to: f64| Traction {
        side,
        from,
        to,
        f,
        field: "test".into(),
    };
    let f = load(
        &mesh,
        &dofs,
        [0.5, -2.0],
        &[top([3.0, -7.0], Side::Top, 0.0, 2.0)],
        0.0,
    );
    let (mut fx, mut fy) = (0.0, 0.0);
    for v in 0..mesh.nodes.len() {
        fx += f[dofs.of(v, 0).unwrap()];
        fy += f[dofs.of(v, 1).unwrap()];
    }
    // area 2, top length 2
    assert!((fx - (0.5 * 2.0 + 3.0 * 2.0)).abs() < 1e-12);
    assert!((fy - (-2.0 * 2.0 - 7.0 * 2.0)).abs() < 1e-12);
    // Tractions on segments of each side: each adds its density times its length,
    // and nothing outside its segment.
    let f = load(
        &mesh,
        &dofs,
        [0.0, 0.0],
        &[
            top([1.0, 0.0], Side::Left, 0.25, 0.75),
            top([0.0, 2.0], Side::Right, 0.0, 0.5),
            top([4.0, 0.0], Side::Top, 1.5, 2.0),
        ],
        0.0,
    );
    let (mut fx, mut fy) = (0.0, 0.0);
    for v in 0..mesh.nodes.len() {
        fx += f[dofs.of(v, 0).unwrap()];
        fy += f[dofs.of(v, 1).unwrap()];
        let p = mesh.nodes[v];
        let on_left = p[0] == 0.0 && (0.25..=0.75).contains(&p[1]);
        let on_top = p[1] == 1.0 && p[0] >= 1.5;
        if !on_left && !on_top {
            assert_eq!(
                f[dofs.of(v, 0).unwrap()],
                0.0,
                "x load off the segments at {p:?}"
            );
        }
    }
    assert!((fx - (1.0 * 0.5 + 4.0 * 0.5)).abs() < 1e-12);
    assert!((fy - 2.0 * 0.5).abs() < 1e-12);
}
