//! Load histories: the factor φ(t), its TOML form, its validation, and the
//! hypotheses H(f), H(0) it decides.

use evhi::history::History;
use evhi::scenario::Scenario;

/// `figure`'s TOML with `extra` added to its `[loads]` table.
fn figure_with(extra: &str) -> String {
    let text = std::fs::read_to_string("data/scenarios/figure.toml").unwrap();
    text.replace("[loads]\n", &format!("[loads]\n{extra}\n"))
}

fn field_of(extra: &str) -> String {
    let err = Scenario::from_toml(&figure_with(extra), "test.toml")
        .expect_err(&format!("`{extra}` must be rejected"));
    let name = err
        .field_name()
        .unwrap_or_else(|| panic!("{err} names no field"));
    assert!(err.to_string().contains(name), "{err}");
    name.to_string()
}

#[test]
fn phi_at_and_between_table_points() {
    let h = History::Table {
        points: vec![(0.0, 0.0), (0.5, 1.0), (1.0, 0.25)],
    };
    assert_eq!(h.phi(0.0), 0.0);
    assert_eq!(h.phi(0.5), 1.0);
    assert_eq!(h.phi(1.0), 0.25);
    assert_eq!(h.phi(0.25), 0.5);
    assert_eq!(h.phi(0.75), 0.625);
    // Outside the points φ keeps its end values.
    assert_eq!(h.phi(2.0), 0.25);
    assert!(h.starts_at_zero());
}

#[test]
fn phi_of_ramp_and_constant() {
    let r = History::Ramp { t_r: 0.25 };
    assert_eq!(r.phi(0.0), 0.0);
    assert_eq!(r.phi(0.125), 0.5);
    assert_eq!(r.phi(0.25), 1.0);
    assert_eq!(r.phi(0.9), 1.0);
    assert_eq!(History::Constant.phi(0.0), 1.0);
    assert!(!History::Constant.starts_at_zero());
}

#[test]
fn toml_forms_parse() {
    let s = Scenario::from_toml(&figure_with("history = { ramp = 0.25 }"), "t").unwrap();
    assert_eq!(s.history().clone(), History::Ramp { t_r: 0.25 });
    let s = Scenario::from_toml(&figure_with("history = \"constant\""), "t").unwrap();
    assert_eq!(s.history().clone(), History::Constant);
    let s = Scenario::from_toml(
        &figure_with("history = { table = [[0.0, 0.0], [0.5, 1.0], [1.0, 1.0]] }"),
        "t",
    )
    .unwrap();
    assert_eq!(
        s.history().clone(),
        History::Table {
            points: vec![(0.0, 0.0), (0.5, 1.0), (1.0, 1.0)]
        }
    );
    // Absent means constant: the shipped scenarios are unchanged.
    assert_eq!(
        Scenario::load("figure").unwrap().history().clone(),
        History::Constant
    );
}

#[test]
fn bad_histories_name_their_field() {
    for (extra, field) in [
        ("history = \"linear\"", "loads.history"),
        ("history = 3", "loads.history"),
        ("history = { ramp = 0.0 }", "loads.history.ramp"),
        ("history = { ramp = -1.0 }", "loads.history.ramp"),
        ("history = { ramp = inf }", "loads.history.ramp"),
        ("history = { ramp = \"fast\" }", "loads.history.ramp"),
        ("history = { ramp = 0.25, table = [] }", "loads.history"),
        ("history = { spline = [] }", "loads.history"),
        ("history = { table = [[0.0, 0.0]] }", "loads.history.table"),
        ("history = { table = 1.0 }", "loads.history.table"),
        (
            "history = { table = [[0.0, 0.0], [1.0]] }",
            "loads.history.table[1]",
        ),
        (
            "history = { table = [[0.0, 0.0], [1.0, 1.0, 2.0]] }",
            "loads.history.table[1]",
        ),
        (
            "history = { table = [[0.0, 0.0], [0.5, nan], [1.0, 1.0]] }",
            "loads.history.table[1]",
        ),
        (
            "history = { table = [[0.0, 0.0], [0.5, 1.0], [0.5, 1.0], [1.0, 1.0]] }",
            "loads.history.table[2]",
        ),
        (
            "history = { table = [[0.0, 0.0], [0.6, 1.0], [0.5, 1.0]] }",
            "loads.history.table[2]",
        ),
        // Must cover [0, T] = [0, 1].
        (
            "history = { table = [[0.1, 0.0], [1.0, 1.0]] }",
            "loads.history.table",
        ),
        (
            "history = { table = [[0.0, 0.0], [0.9, 1.0]] }",
            "loads.history.table",
        ),
    ] {
        assert_eq!(field_of(extra), field, "{extra}");
    }
}

#[test]
fn three_component_loads_are_rejected() {
    let text = std::fs::read_to_string("data/scenarios/figure.toml").unwrap();
    for (from, to, field) in [
        ("f0 = [0.0, -5.0]", "f0 = [1.0, 2.0, 3.0]", "loads.f0"),
        ("f2 = [0.0, -75.0]", "f2 = [1.0, 2.0, 3.0]", "loads.f2"),
        ("f0 = [0.0, -5.0]", "f0 = [1.0]", "loads.f0"),
    ] {
        let err = Scenario::from_toml(&text.replace(from, to), "t").expect_err(to);
        assert_eq!(err.field_name(), Some(field), "{err}");
        assert!(err.to_string().contains("exactly two"), "{err}");
    }
}

#[test]
fn the_ramp_override_is_validated() {
    let s = Scenario::load("figure").unwrap();
    let err = s.clone().with_ramp(0.0).unwrap_err();
    assert_eq!(err.field_name(), Some("ramp"));
    assert_eq!(
        s.with_ramp(0.5).unwrap().history().clone(),
        History::Ramp { t_r: 0.5 }
    );
}

#[test]
fn constant_loads_break_h_f_and_a_ramp_meets_it() {
    for name in ["figure", "literal", "smooth"] {
        let s = Scenario::load(name).unwrap();
        let h = s.time_hypotheses();
        assert!(!h.h_f() && !h.h_0(), "{name}: {h:?}");
        assert!(!h.failures().is_empty());
        let h = s.with_ramp(0.25).unwrap().time_hypotheses();
        assert!(h.h_f() && h.h_0(), "{name} with a ramp: {h:?}");
        assert!(h.failures().is_empty());
    }
    // A volume force that vanishes on the clamp is in V: figure's supports clamp x = 0
    // and x = 2, where 1 - cos(pi x) = 0; with f2 = 0 the constant load is compatible.
    let text = std::fs::read_to_string("data/scenarios/figure.toml")
        .unwrap()
        .replace("f2 = [0.0, -75.0]", "f2 = [0.0, 0.0]\nf0_modulation = -1.0");
    let s = Scenario::from_toml(&text, "t").unwrap();
    let h = s.time_hypotheses();
    assert!(h.f0_in_v && h.f2_zero && h.h_0(), "{h:?}");
    // A law whose Clarke subdifferential at 0 excludes 0 breaks H(0) but not H(f).
    let text = std::fs::read_to_string("data/scenarios/figure.toml")
        .unwrap()
        .replace(
            "slopes = [0.0, 200.0, -100.0, 300.0]",
            "slopes = [0.0, 200.0, -100.0, 300.0]\np_left = 1.0",
        );
    let h = Scenario::from_toml(&text, "t")
        .unwrap()
        .with_ramp(0.25)
        .unwrap()
        .time_hypotheses();
    assert!(h.h_f() && !h.h_0(), "{h:?}");
}
