//! The spring support (`supports = { right = { spring = k_s } }`: $\sigma\nu = -k_s u$ on
//! the part) against its closed form, and its refusals.
//!
//! The bar: $\Omega = (0, 2) \times (0, 1)$ with Poisson ratio 0 ($a = 0$, $b = E$: no
//! lateral coupling), rollers on the left ($u_x = 0$), a spring $k_s$ and a traction
//! $(F, 0)$ on the right, $\Gamma_3$ the whole bottom. The field $u = a(t)\,(x, 0)$ has
//! $\sigma = E a\, e_x \otimes e_x$: free on the top, zero normal stress on the bottom
//! (where $u_\nu = 0$ and $p(0) = 0$), and on the right $E a = F - k_s a W$. With
//! $\mathcal C = c\,\mathcal G$ ($\alpha = 0$, $\beta = cE$) every operator maps $u^* =
//! (x, 0)$ onto multiples of $\ell(v) = \int_{x = W} v_x\,ds$: $B u^* = (E + k_s W)\ell$
//! (the body and the spring), $A u^* = cE\,\ell$ (the spring is in $B$ alone), $f = F\ell$.
//! Backward Euler from $u_0 = 0$ then gives $u_n = a_n u^*$ with
//! $$\big(cE + k(E + k_s W)\big)\, a_n = cE\, a_{n-1} + kF,$$
//! and the elastic problem $a_n = F/(E + k_s W)$. The field is linear, so it lies in
//! the P1 space of every mesh: the discrete solution is exactly it, and what is left
//! is rounding and the step solver's stopping point.

use evhi::mesh::Dofs;
use evhi::prelude::*;

const E: f64 = 1000.0;
const C: f64 = 0.1;
const F: f64 = 50.0;
const W: f64 = 2.0;

fn bar(k_s: f64, problem: &str) -> Scenario {
    let viscosity = if problem == "viscoelastic" {
        format!("alpha = 0.0\nbeta = {}\n", C * E)
    } else {
        String::new()
    };
    let text = format!(
        "name = \"spring-bar\"\nT = 1.0\ng = \"none\"\nproblem = \"{problem}\"\n\
         [geometry]\nwidth = {W}\nheight = 1.0\n\
         supports = {{ left = \"rollers\", right = {{ spring = {k_s:e} }} }}\n\
         [material]\nE = {E}\nkappa = 0.0\n{viscosity}\
         [loads]\nf0 = [0.0, 0.0]\nf2 = [0.0, 0.0]\nhistory = \"constant\"\n\
         [[loads.traction]]\nside = \"right\"\nfrom = 0.0\nto = 1.0\nf = [{F}, 0.0]\n\
         [law]\nbreakpoints = [0.0]\nslopes = [0.0, 100.0]\n"
    );
    Scenario::from_toml(&text, "spring-bar").unwrap()
}

/// The largest nodal distance from $a\,(x, 0)$, relative to $a W$.
fn off(sim: &Simulation, u: &[f64], a: f64) -> f64 {
    let mesh = sim.mesh();
    let nodal = Dofs::new(mesh, true).expand(u);
    (mesh.nodes.iter().zip(&nodal))
        .map(|(p, v)| (v[0] - a * p[0]).abs().max(v[1].abs()))
        .fold(0.0, f64::max)
        / (a * W)
}

/// Every step of the general loop against the recursion, for a soft and a stiff
/// spring (k_s W = E/10 and 10 E), on two meshes and two time steps; and the elastic
/// problem against $F/(E + k_s W)$.
#[test]
fn a_bar_on_a_spring_matches_its_closed_form() {
    let mut worst: f64 = 0.0;
    for k_s in [50.0, 5000.0] {
        for (n, steps) in [(4, 4), (8, 16)] {
            for problem in ["viscoelastic", "elastic"] {
                let sim =
                    Simulation::new(bar(k_s, problem), RunSettings::general(n, steps)).unwrap();
                let k = 1.0 / steps as f64;
                let mut fields = vec![];
                let mut observer = OnStep::new(|_, _, u: Option<&[f64]>, _: &[ContactState]| {
                    fields.push(u.expect("the general loop forms every field").to_vec())
                });
                sim.solve(&mut observer).unwrap();
                assert_eq!(fields.len(), steps);
                let mut a = 0.0;
                for u in &fields {
                    a = if problem == "viscoelastic" {
                        (C * E * a + k * F) / (C * E + k * (E + k_s * W))
                    } else {
                        F / (E + k_s * W)
                    };
                    worst = worst.max(off(&sim, u, a));
                }
            }
        }
    }
    // The field is in the P1 space, so only rounding is left: measured 8.3e-15 (the
    // contact nodes sit at u_nu = 0, where the law is smooth, so the step solver's
    // stopping point adds nothing measurable). 1e-12 leaves rounding room; a spring
    // of the wrong strength or also in A would move a_n by a share of k_s W/E (0.1
    // and 10 here), far beyond it.
    println!("worst relative nodal error: {worst:e}");
    assert!(worst <= 1e-12, "{worst:e}");
}

/// The spring enters B alone, so A = cB fails: the reduced loop is refused by the
/// spring's field, and the automatic choice takes the general loop. Without viscosity
/// A = 0 = 0 (B + B_s) still holds: the automatic choice takes the reduced loop, and it
/// meets the closed form.
#[test]
fn the_reduced_loop_refuses_a_spring() {
    let scn = bar(500.0, "viscoelastic");
    let reduced = RunSettings::general(4, 4).with_path(Loop::Reduced);
    let sim = Simulation::new(scn.clone(), reduced).unwrap();
    let e = sim.solve(&mut ()).unwrap_err().to_string();
    assert!(
        e.contains("geometry.supports.right") && e.contains("A = cB"),
        "{e}"
    );
    let auto = RunSettings::general(4, 4).with_path(Loop::Auto);
    let solution = Simulation::new(scn, auto).unwrap().solve(&mut ()).unwrap();
    assert!(!solution.reduced);
    let k_s = 500.0;
    let sim = Simulation::new(bar(k_s, "elastic"), RunSettings::default().with_n(8)).unwrap();
    let solution = sim.solve(&mut ()).unwrap();
    assert!(solution.reduced);
    let worst = off(&sim, &solution.run.u, F / (E + k_s * W));
    assert!(worst <= 1e-12, "{worst:e}");
}

/// A spring's value is checked by name, its table takes nothing else, and springs alone
/// hold the body (no rigid motion is left free: the term is positive on each).
#[test]
fn a_spring_is_checked_and_holds_the_body() {
    let text = |supports: &str| {
        format!(
            "name = \"s\"\nT = 1.0\ng = 0.05\n[geometry]\nwidth = 2.0\nheight = 1.0\nsupports = {supports}\n\
             [material]\nE = 1000.0\nkappa = 0.3\nalpha = 10.0\nbeta = 20.0\n\
             [loads]\nf0 = [0.0, -5.0]\nf2 = [0.0, -20.0]\n\
             [law]\nbreakpoints = [0.0]\nslopes = [0.0, 100.0]\n"
        )
    };
    for (supports, field) in [
        (
            "{ left = { spring = -1.0 } }",
            "geometry.supports.left.spring",
        ),
        (
            "{ left = { spring = \"stiff\" } }",
            "geometry.supports.left.spring",
        ),
        (
            "{ left = { spring = 1e4, glue = 1 } }",
            "geometry.supports.left.glue",
        ),
        ("{ left = {} }", "geometry.supports.left.spring"),
        (
            "{ left = [{ from = 0.0, to = 0.5, kind = { spring = 0.0 } }] }",
            "geometry.supports.left[0].kind.spring",
        ),
    ] {
        let e = Scenario::from_toml(&text(supports), "s").unwrap_err();
        assert_eq!(e.field_name(), Some(field), "{supports}: {e}");
    }
    let held = Scenario::from_toml(
        &text("{ left = { spring = 1e4 }, right = { spring = 1e4 } }"),
        "s",
    )
    .unwrap();
    let solution = Simulation::new(held, RunSettings::general(8, 4))
        .unwrap()
        .solve(&mut ())
        .unwrap();
    assert!(solution.max_certificate() <= 1e-10);
}

/// `show` does not call a viscoelastic scene with a spring "proportional damping": its
/// C is a multiple of G, but the spring is in B alone. It names the spring's support,
/// and the scene's own answer agrees with the loop `solve` takes. Without viscosity,
/// or without the spring, the damping is proportional.
#[test]
fn show_says_a_spring_breaks_proportional_damping() {
    let (text, _) = evhi::show::report(&bar(500.0, "viscoelastic"), 8, 4);
    assert!(!text.contains("proportional damping"), "{text}");
    assert!(
        text.contains("geometry.supports.right") && text.contains("not proportional"),
        "{text}"
    );
    assert_eq!(bar(500.0, "viscoelastic").proportional_damping(), None);
    assert_eq!(bar(500.0, "elastic").proportional_damping(), Some(0.0));
    let figure = Scenario::load("figure").unwrap();
    assert!(figure.proportional_damping().is_some());
    let (text, _) = evhi::show::report(&figure, 8, 4);
    assert!(text.contains("proportional damping"), "{text}");
}
