//! The initial gap of the contact nodes (Kikuchi–Oden, `src/body.rs`), the prescribed
//! displacement of a part (a rigid shift of the gaps) and the zero law
//! (`law = "none"`, `src/law/file.rs`), each solved and compared with a scene whose
//! answer must be the same.

use evhi::law::Law;
use evhi::scenario::Scenario;
use evhi::simulation::{Loop, RunSettings, Simulation};
use std::path::Path;

const PAPER_MESH: &str = "data/scenarios/examples/paper_mesh.toml";

fn text() -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(PAPER_MESH)).unwrap()
}

fn scene(text: &str) -> Scenario {
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join(PAPER_MESH);
    Scenario::from_toml(text, &source.display().to_string()).unwrap_or_else(|e| panic!("{e}"))
}

fn solve(scn: Scenario, path: Loop) -> evhi::simulation::Solution {
    let settings = RunSettings::default()
        .with_n(16)
        .with_steps(16)
        .with_path(path);
    Simulation::new(scn, settings)
        .unwrap()
        .solve(&mut ())
        .unwrap()
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

/// Lifting Gamma_3 by delta above the foundation (the line y = -delta) is the flat
/// scene with the law and the limit moved out by delta: p~(s) = p(s - delta), g + delta.
/// The displacements agree and the contact variable is shifted by delta, on both loops.
#[test]
fn a_constant_gap_is_the_flat_scene_with_the_law_shifted() {
    let delta = 0.02;
    let lifted = text().replace(
        "contact = \"bottom\"",
        &format!(
            "contact = \"bottom\"\nfoundation = {{ point = [0.0, {}], normal = [0.0, -1.0] }}",
            -delta
        ),
    );
    let shifted = text()
        .replace("g = 0.1", &format!("g = {}", 0.1 + delta))
        .replace(
            "breakpoints = [0.0, 0.05, 0.075]",
            &format!(
                "breakpoints = [{}, {}, {}]",
                delta,
                0.05 + delta,
                0.075 + delta
            ),
        );
    assert_ne!(lifted, text());
    assert_ne!(shifted, text());
    for path in [Loop::General, Loop::Reduced] {
        let a = solve(scene(&lifted), path);
        let b = solve(scene(&shifted), path);
        let scale = max_abs(&b.run.u);
        let diff: Vec<f64> = a.run.u.iter().zip(&b.run.u).map(|(x, y)| x - y).collect();
        assert!(
            max_abs(&diff) <= 1e-11 * scale,
            "{path:?}: u differs by {:e} of {scale:e}",
            max_abs(&diff)
        );
        for (ca, cb) in a.run.contact.iter().zip(&b.run.contact) {
            assert!((ca.u_nu - (cb.u_nu - delta)).abs() <= 1e-11 * scale);
            assert!((ca.sigma_nu1 - cb.sigma_nu1).abs() <= 1e-9 * 75.0);
            assert!((ca.sigma_nu2 - cb.sigma_nu2).abs() <= 1e-9 * 75.0);
        }
        // The contact acts: some node carries a force (so the shift is tested).
        assert!(
            a.run
                .contact
                .iter()
                .any(|c| c.sigma_nu1 + c.sigma_nu2 < -1.0),
            "{path:?}: no contact force"
        );
        // And the lift changed the answer from the flat scene's.
        let flat = solve(scene(&text()), path);
        let d: Vec<f64> = flat
            .run
            .u
            .iter()
            .zip(&a.run.u)
            .map(|(x, y)| x - y)
            .collect();
        assert!(max_abs(&d) > 1e-3 * scale);
    }
}

/// A foundation farther than the body moves: no contact force at all, and the
/// displacement is the one without contact (the same for two such distances).
#[test]
fn gaps_larger_than_the_motion_give_no_contact_force() {
    let far = |d: f64| {
        text().replace(
            "contact = \"bottom\"",
            &format!(
                "contact = \"bottom\"\nfoundation = {{ point = [0.0, {d}], normal = [0.0, -1.0] }}"
            ),
        )
    };
    let a = solve(scene(&far(-10.0)), Loop::Auto);
    let b = solve(scene(&far(-20.0)), Loop::Auto);
    for c in &a.run.contact {
        assert_eq!(c.sigma_nu1 + c.sigma_nu2, 0.0);
        assert!(c.u_nu < -9.0);
    }
    // The same up to the solver's rounding.
    let scale = max_abs(&b.run.u);
    let diff: Vec<f64> = a.run.u.iter().zip(&b.run.u).map(|(x, y)| x - y).collect();
    assert!(max_abs(&diff) <= 1e-12 * scale, "{:e}", max_abs(&diff));
}

/// A prescribed displacement d of the clamped part is the scene moved rigidly by d: the
/// body's displacement is u + d with u the scene's own where the foundation moves by d
/// too (the gap g0 - d.n_f is the same).
#[test]
fn a_prescribed_displacement_is_a_rigid_shift_of_the_gaps() {
    let (dy, delta) = (-0.3, 0.02);
    let pressed = text().replace(
        "contact = \"bottom\"",
        &format!(
            "contact = \"bottom\"\nfoundation = {{ point = [0.0, {}], normal = [0.0, -1.0] }}\n\
             displacement = {{ on = \"clamped\", u = [0.0, {dy}] }}",
            dy - delta
        ),
    );
    let lifted = text().replace(
        "contact = \"bottom\"",
        &format!(
            "contact = \"bottom\"\nfoundation = {{ point = [0.0, {}], normal = [0.0, -1.0] }}",
            -delta
        ),
    );
    let a = solve(scene(&pressed), Loop::Auto);
    let b = solve(scene(&lifted), Loop::Auto);
    let scale = max_abs(&b.run.u);
    let diff: Vec<f64> = a.run.u.iter().zip(&b.run.u).map(|(x, y)| x - y).collect();
    assert!(max_abs(&diff) <= 1e-11 * scale);
    assert_eq!(a.run.mesh.shift, [0.0, dy]);
    let dofs = evhi::mesh::Dofs::new(&a.run.mesh, true);
    let disp = a.run.mesh.displacement(&dofs, &a.run.u);
    let own = b.run.mesh.displacement(&dofs, &b.run.u);
    for (p, q) in disp.iter().zip(&own) {
        assert!((p[0] - q[0]).abs() <= 1e-11 && (p[1] - (q[1] + dy)).abs() <= 1e-11);
    }
}

/// What the rigid shift cannot carry is refused by name.
#[test]
fn a_displacement_the_shift_cannot_carry_is_refused() {
    let with = |d: &str| {
        text().replace(
            "contact = \"bottom\"",
            &format!("contact = \"bottom\"\ndisplacement = {d}"),
        )
    };
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join(PAPER_MESH);
    let err = |t: &str| {
        Scenario::from_toml(t, &source.display().to_string())
            .unwrap_err()
            .to_string()
    };
    // A part the file lacks.
    let e = err(&with("{ on = \"lid\", u = [0.0, -0.1] }"));
    assert!(
        e.contains("geometry.displacement.on") && e.contains("\"lid\""),
        "{e}"
    );
    // A part that is not held.
    let e = err(&with("{ on = \"top\", u = [0.0, -0.1] }"));
    assert!(
        e.contains("geometry.displacement.u") && e.contains("holds y"),
        "{e}"
    );
    // On the rectangle.
    let e = err(&read_figure_with(
        "[geometry]\ndisplacement = { on = \"top\", u = [0.0, -0.1] }",
    ));
    assert!(
        e.contains("geometry.displacement") && e.contains("nothing on the rectangle"),
        "{e}"
    );
}

fn read_figure_with(geometry: &str) -> String {
    std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("data/scenarios/figure.toml"),
    )
    .unwrap()
    .replace("[loads]", &format!("{geometry}\n[loads]"))
}

/// `law = "none"`: the zero law, the limit alone. Its nodes carry only the limit's
/// reaction, and the answer is that of a piecewise law with zero slopes.
#[test]
fn law_none_is_the_limit_alone() {
    let law_at = text().find("[law]").unwrap();
    let none = text()[..law_at].replace("T = 1.0", "T = 1.0\nlaw = \"none\"");
    let zero = format!(
        "{}[law]\nbreakpoints = [0.0]\nslopes = [0.0, 0.0]\n",
        &text()[..law_at]
    );
    let scn = scene(&none);
    assert!(scn.law().is_none());
    assert_eq!(*scn.law(), Law::none());
    let a = solve(scn, Loop::Auto);
    let b = solve(scene(&zero), Loop::Auto);
    assert_eq!(a.run.u, b.run.u);
    let g = 0.1;
    let mut at_limit = 0;
    for c in &a.run.contact {
        assert_eq!(c.sigma_nu1, 0.0);
        assert!(c.u_nu <= g * (1.0 + 1e-9));
        if c.sigma_nu2 < 0.0 {
            at_limit += 1;
            assert!((c.u_nu - g).abs() <= 1e-9 * g);
        }
    }
    assert!(at_limit > 0, "no node reached the limit");
    // Refused: a name that is no law, and the zero law without a limit.
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join(PAPER_MESH);
    let err = |t: &str| {
        Scenario::from_toml(t, &source.display().to_string())
            .unwrap_err()
            .to_string()
    };
    let e = err(&none.replace("law = \"none\"", "law = \"linear\""));
    assert!(
        e.contains("law") && e.contains("\"linear\"") && e.contains("\"none\""),
        "{e}"
    );
    let e = err(&none.replace("g = 0.1", "g = \"none\""));
    assert!(
        e.contains("g") && e.contains("nothing acts on Gamma_3"),
        "{e}"
    );
    // The library's builder refuses the same scene the same way.
    let b = scene(&none).without_limit().unwrap_err().to_string();
    assert_eq!(b, e.lines().next().unwrap_or(&e).to_string(), "{b}");
    // A [law] table's own errors still name their line.
    let e = err(&format!(
        "{}[law]\nbreakpoints = [0.0]\nslope = [0.0]\n",
        &text()[..law_at]
    ));
    assert!(e.contains("line") && e.contains("slope"), "{e}");
}

/// Gaps given by `Scenario::with_contact_gaps` act as the file's do: the paper's mesh
/// with the gap delta at every node is the scene lifted by delta above its foundation,
/// to the last bit; a count other than the contact nodes', a negative or a non-finite
/// gap and the rectangle are refused by name.
#[test]
fn contact_gaps_of_one_s_own_act_as_the_foundation_s() {
    let delta = 0.02;
    let lifted = text().replace(
        "contact = \"bottom\"",
        &format!(
            "contact = \"bottom\"\nfoundation = {{ point = [0.0, {}], normal = [0.0, -1.0] }}",
            -delta
        ),
    );
    let flat = scene(&text());
    let m = flat.body().unwrap().gamma3.len();
    let given = flat.clone().with_contact_gaps(vec![delta; m]).unwrap();
    let a = solve(given, Loop::General);
    let b = solve(scene(&lifted), Loop::General);
    assert_eq!(a.run.u, b.run.u);
    assert!(
        a.run
            .contact
            .iter()
            .any(|c| c.sigma_nu1 + c.sigma_nu2 < 0.0)
    );
    for (gaps, needle) in [
        (vec![delta; m - 1], "contact gaps"),
        (vec![-delta; m], "contact gaps[0]"),
        (vec![f64::NAN; m], "contact gaps[0]"),
    ] {
        let e = flat.clone().with_contact_gaps(gaps).unwrap_err();
        assert_eq!(e.field_name(), Some(needle), "{e}");
    }
    let e = Scenario::load("figure")
        .unwrap()
        .with_contact_gaps(vec![0.0; 17])
        .unwrap_err();
    assert_eq!(e.field_name(), Some("geometry.mesh"), "{e}");
}
