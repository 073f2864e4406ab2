//! The time grid chosen from the solution: the library's search on both loops, a
//! simulation on a grid of its own, and `evhi solve --adapt-time`.

mod common;

use common::*;
use evhi::prelude::*;
use evhi::time_adapt::{Settings, Stop, choose, choose_from};
use evhi::time_grid::TimeGrid;

fn search(reduced: bool) -> evhi::time_adapt::Chosen {
    let sim = Simulation::new(Scenario::load("figure").unwrap(), on_loop(8, 4, reduced)).unwrap();
    let s = Settings {
        tol: 0.05,
        ..Settings::default()
    };
    let mut seen = 0;
    let chosen = choose(&sim, &s, &mut |_| seen += 1).unwrap();
    assert_eq!(seen, chosen.levels.len());
    chosen
}

/// The reduced loop measures the predictor and the reconstruction's residual on its
/// states, the general loop on its fields: the same grids, the same estimates and
/// bounds to rounding.
#[test]
fn both_loops_choose_the_same_grid() {
    let (r, g) = (search(true), search(false));
    assert_eq!(r.stop, Stop::Tolerance);
    assert_eq!(r.levels.len(), g.levels.len());
    assert!(r.levels.len() > 3, "{}", r.levels.len());
    for (a, b) in r.levels.iter().zip(&g.levels) {
        assert_eq!(a.grid, b.grid);
        assert!(
            (a.estimate - b.estimate).abs() <= 1e-8 * a.estimate,
            "{} {}",
            a.estimate,
            b.estimate
        );
    }
    // The reconstruction's bound: on states (A = cB, the contact block of B's factor
    // for the law's part) and on fields (a factor of A) agree to rounding.
    for (a, b) in r.levels.iter().zip(&g.levels) {
        let (a, b) = (a.bound.unwrap(), b.bound.unwrap());
        assert!((a - b).abs() <= 1e-8 * a, "{a} {b}");
    }
    let last = r.levels.last().unwrap();
    // The search stops on the bound, marked on its steps' residuals; the bound falls
    // from level to level, and the layer at t = 0 gets the short steps.
    assert!(last.bound.unwrap() <= 0.05);
    assert!(
        r.levels[..r.levels.len() - 1]
            .iter()
            .all(|l| l.bound.unwrap() > 0.05)
    );
    assert!(r.levels[0].bound.unwrap() > 5.0 * last.bound.unwrap());
    assert!(r.levels.iter().all(|l| l.theta.len() == l.grid.len()));
    assert_eq!(last.grid.k(1), last.grid.k_min());
    assert!(last.grid.k(last.grid.len()) > 8.0 * last.grid.k_min());
}

/// A simulation runs on the grid it is given, and refuses one that does not end at T.
#[test]
fn a_simulation_runs_on_a_grid_of_its_own() {
    let sim = Simulation::new(Scenario::load("figure").unwrap(), on_loop(8, 4, true)).unwrap();
    let grid = TimeGrid::uniform(1.0, 4).bisect(&[0, 2]).unwrap();
    let on = sim.on_time_grid(grid.clone()).unwrap();
    assert_eq!(on.steps(), 6);
    let sol = on.solve(&mut ()).unwrap();
    assert_eq!(sol.run.steps, 6);
    assert!(sol.max_certificate() <= 1e-10);
    let short = TimeGrid::uniform(0.5, 4);
    let e = sim.on_time_grid(short).unwrap_err().to_string();
    assert!(e.contains("time grid") && e.contains("T = 1"), "{e}");
    let layered = Simulation::new(
        Scenario::load("figure").unwrap(),
        on_loop(8, 4, true).with_time_layer(2),
    )
    .unwrap();
    let e = layered.on_time_grid(grid).unwrap_err().to_string();
    assert!(e.contains("time_layer"), "{e}");
}

/// The command line prints a line per level, says why it stopped, runs the chosen
/// grid and writes its levels.
#[test]
fn solve_adapt_time_writes_its_levels() {
    let dir = scratch("adapt-time");
    let run = dir.join("run");
    let o =
        evhi_with("solve --scenario literal --n 8 --adapt-time 0.05 --timings --estimate --out")
            .arg(&run)
            .output()
            .unwrap();
    let err = ok(&o);
    assert_contains(
        &err,
        &[
            "time level: 4 steps, shortest T/4",
            "stopped: the bound (or, without viscosity, the estimate) is within the tolerance",
            "time grid search: ",
        ],
    );
    let rows = table_rows(&run.join("time_adapt.csv"));
    let last = rows.last().unwrap();
    let steps: usize = last[1].parse().unwrap();
    let bound: f64 = last[6].parse().unwrap();
    assert!(bound <= 0.05, "{bound}");
    // The damped estimate never passes the plain sum beside it.
    for row in &rows {
        let (damped, sum): (f64, f64) = (row[4].parse().unwrap(), row[5].parse().unwrap());
        assert!(damped <= sum && damped > 0.0, "{row:?}");
    }
    assert_eq!(steps, steps_of(&run));
    assert_eq!(rows.len(), err.matches("time level: ").count());
}

/// A run's table: its rows past the `#` lines and the header, split into fields.
fn table_rows(path: &std::path::Path) -> Vec<Vec<String>> {
    let text = read(path);
    (text.lines())
        .filter(|l| !l.starts_with('#'))
        .skip(1)
        .map(fields)
        .collect()
}

fn steps_of(run: &std::path::Path) -> usize {
    steps(run).len()
}

/// A tolerance out of range, a budget below the first grid and a layer beside it are
/// refused by their flags.
#[test]
fn solve_adapt_time_refuses_bad_input() {
    let dir = scratch("adapt-time-bad");
    let run = dir.join("run");
    for (words, needles) in [
        (
            "solve --scenario figure --adapt-time 2 --out",
            &["--adapt-time", "[1e-6, 1]"][..],
        ),
        (
            "solve --scenario figure --adapt-time 0.1 --steps 8 --max-steps 4 --out",
            &["--max-steps", "8 steps"][..],
        ),
        (
            "solve --scenario figure --adapt-time 0.1 --time-layer 3 --out",
            &["--time-layer"][..],
        ),
        (
            "solve --scenario figure --max-steps 40 --out",
            &["--adapt-time"][..],
        ),
    ] {
        let o = evhi_with(words).arg(&run).output().unwrap();
        refused(&o, needles);
    }
}

/// The space loop's estimator takes each step's own $k_n$ on a grid of unequal steps
/// (before, it took $T/M$ for every step): recomputed step by step from the fields it
/// saw, bit for bit; with $T/M$ the indicators differ.
#[test]
fn the_space_loop_estimates_each_step_with_its_own_k() {
    use evhi::adapt::{AdaptObserver, Aggregate, solve_estimating};
    use evhi::certificate::ContactState;
    struct Keep(Vec<(usize, f64, Vec<f64>, Vec<ContactState>)>);
    impl AdaptObserver for Keep {
        fn step(&mut self, n: usize, t: f64, u: &[f64], c: &[ContactState]) {
            self.0.push((n, t, u.to_vec(), c.to_vec()));
        }
        fn restart(&mut self) {
            self.0.clear();
        }
    }
    let scn = Scenario::load("figure").unwrap();
    let grid = TimeGrid::uniform(1.0, 4).bisect(&[0, 1]).unwrap();
    let sim = Simulation::new(scn.clone(), on_loop(8, 4, true))
        .unwrap()
        .on_time_grid(grid.clone())
        .unwrap();
    let mut keep = Keep(vec![]);
    let est = solve_estimating(&sim, Aggregate::Max, &mut keep).unwrap();
    assert_eq!(keep.0.len(), 6);
    let mesh = sim.mesh();
    let dofs = evhi::mesh::Dofs::new(mesh, true);
    let again = |k_of: &dyn Fn(usize) -> f64| -> Vec<f64> {
        let mut prev = vec![[0.0; 2]; mesh.nodes.len()];
        let mut eta_sq = vec![0.0f64; mesh.triangles.len()];
        for (n, t, u, c) in &keep.0 {
            let mut un = vec![];
            dofs.expand_into(u, &mut un);
            let e = evhi::estimator::estimate_scene(&scn, mesh, &un, &prev, k_of(*n), *t, c);
            eta_sq
                .iter_mut()
                .zip(&e.eta_sq)
                .for_each(|(a, &b)| *a = a.max(b));
            prev = un;
        }
        eta_sq
    };
    assert_eq!(again(&|n| grid.k(n)), est.eta_sq);
    assert_ne!(again(&|_| 1.0 / 6.0), est.eta_sq);
    // The time mean weighs each step by k_n / T, in step order, bit for bit.
    let mut keep = Keep(vec![]);
    let mean = solve_estimating(&sim, Aggregate::Sum, &mut keep).unwrap();
    let mut prev = vec![[0.0; 2]; mesh.nodes.len()];
    let mut eta_sq = vec![0.0f64; mesh.triangles.len()];
    let mut weights = 0.0;
    for (n, t, u, c) in &keep.0 {
        let mut un = vec![];
        dofs.expand_into(u, &mut un);
        let k = grid.k(*n);
        let e = evhi::estimator::estimate_scene(&scn, mesh, &un, &prev, k, *t, c);
        eta_sq
            .iter_mut()
            .zip(&e.eta_sq)
            .for_each(|(a, &b)| *a += k / 1.0 * b);
        weights += k;
        prev = un;
    }
    assert_eq!(eta_sq, mean.eta_sq);
    assert!((weights - 1.0).abs() < 1e-15);
}

/// `--adapt` with `--adapt-time`: each level's grid is chosen on its own mesh, and each
/// level's line names its steps.
#[test]
fn solve_adapt_with_adapt_time_chooses_each_levels_grid() {
    let dir = scratch("adapt-space-time");
    let run = dir.join("run");
    let o = evhi_with(
        "solve --scenario figure --adapt 0.3 --max-dofs 1500 --adapt-time 0.2 --timings --out",
    )
    .arg(&run)
    .output()
    .unwrap();
    let err = ok(&o);
    assert_contains(&err, &["adapting `figure`", "time grid searches "]);
    assert!(read(run.join("time_adapt.csv")).contains("the last mesh level's mesh"));
    let searched = table_rows(&run.join("time_adapt.csv"));
    let chosen: usize = searched.last().unwrap()[1].parse().unwrap();
    let levels = table_rows(&run.join("adapt.csv"));
    assert!(levels.len() >= 2, "{}", levels.len());
    // Each level's line names the steps its own search chose, and adapt.csv has them.
    for l in &levels {
        let steps: usize = l[3].parse().unwrap();
        let line = format!("time grid of {steps} steps chosen in ");
        let level = format!("level {:>2}: ", l[0]);
        assert!(
            err.lines()
                .any(|x| x.starts_with(&level) && x.contains(&line)),
            "level {}: {steps} steps\n{err}",
            l[0]
        );
    }
    // The run directory is the last level's, on its own grid.
    assert_eq!(steps_of(&run), chosen);
    assert_eq!(levels.last().unwrap()[3].parse::<usize>().unwrap(), chosen);
}

/// On a grid that comes back to lengths it left, the general loop keeps the operators
/// it will need again: one factorisation per distinct length, and the same run as the
/// reduced loop's to rounding.
#[test]
fn the_general_loop_factorises_each_length_once() {
    // 1/8 1/8 1/4 1/8 1/8 1/4: the lengths alternate four times.
    let grid = TimeGrid::from_exponents(1.0, 4, 1, &[0, 0, 1, 0, 0, 1]).unwrap();
    let run = |reduced: bool| {
        Simulation::new(Scenario::load("figure").unwrap(), on_loop(8, 4, reduced))
            .unwrap()
            .on_time_grid(grid.clone())
            .unwrap()
            .solve(&mut ())
            .unwrap()
    };
    let (g, r) = (run(false), run(true));
    assert_eq!(g.run.timings.factorisations, 2);
    // Three lengths, each taken twice: 1/16 1/16 1/8 1/4 1/16 1/16 1/8 1/4.
    let three = TimeGrid::from_exponents(1.0, 4, 2, &[0, 0, 1, 2, 0, 0, 1, 2]).unwrap();
    let sim = Simulation::new(Scenario::load("figure").unwrap(), on_loop(8, 4, false)).unwrap();
    let sol = sim.on_time_grid(three).unwrap().solve(&mut ()).unwrap();
    assert_eq!(sol.run.timings.factorisations, 3);
    assert_eq!(r.run.timings.factorisations, 1);
    let (eg, er) = (g.energy_norm_t(), r.energy_norm_t());
    assert!((eg - er).abs() <= 1e-9 * er, "{eg} {er}");
    assert_eq!(g.run.steps, 6);
}

/// A search from a grid goes on from it: from a level of an earlier search it refines
/// that grid into the same grids the search from N0 went on to, and from the grid that
/// search chose it stops at once; a grid of another N0, or past the budgets, is refused
/// by name.
#[test]
fn a_search_goes_on_from_the_grid_it_is_given() {
    let sim = Simulation::new(Scenario::load("figure").unwrap(), on_loop(8, 4, true)).unwrap();
    let s = Settings {
        tol: 0.05,
        ..Settings::default()
    };
    let cold = choose(&sim, &s, &mut |_| {}).unwrap();
    assert_eq!(cold.stop, Stop::Tolerance);
    assert!(cold.levels.len() > 3, "{}", cold.levels.len());
    let from = choose_from(&sim, &s, cold.levels[2].grid.clone(), &mut |_| {}).unwrap();
    assert_eq!(from.levels.len(), cold.levels.len() - 2);
    for (a, b) in from.levels.iter().zip(&cold.levels[2..]) {
        assert_eq!(a.grid, b.grid);
    }
    let done = choose_from(&sim, &s, cold.grid().clone(), &mut |_| {}).unwrap();
    assert_eq!((done.levels.len(), done.stop), (1, Stop::Tolerance));
    assert_eq!(done.grid(), cold.grid());
    for (bad, field) in [
        (TimeGrid::uniform(1.0, 8), "`start`"),
        (TimeGrid::uniform(1.0, 0), "`start`"),
        (TimeGrid::uniform(2.0, 4), "time grid"),
    ] {
        let e = choose_from(&sim, &s, bad, &mut |_| {})
            .unwrap_err()
            .to_string();
        assert!(e.contains(field), "{e}");
    }
    let small = Settings { max_steps: 5, ..s };
    let e = choose_from(&sim, &small, cold.grid().clone(), &mut |_| {})
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("`start`") && e.contains("at most 5 steps"),
        "{e}"
    );
    // Bad settings are named before the start grid is looked at.
    let no_n0 = Settings { n0: 0, ..s };
    let e = choose_from(&sim, &no_n0, TimeGrid::uniform(1.0, 0), &mut |_| {})
        .unwrap_err()
        .to_string();
    assert!(e.contains("`n0`"), "{e}");
}

/// The adaptive loop with a time search chooses each level's grid on that level's
/// mesh, going on from the grid the level before chose: every level searched and
/// timed, the grids never shorter, the last search returned, its grid the last
/// level's and what a search on the last mesh from the level before's grid chooses;
/// a given grid beside a search is refused by name.
#[test]
fn the_space_loop_chooses_each_levels_time_grid() {
    use evhi::adapt::{AdaptSettings, adapt};
    let scn = Scenario::load("figure").unwrap();
    let search = Settings {
        tol: 0.05,
        ..Settings::default()
    };
    let s = AdaptSettings::default()
        .with_tol(1e-6)
        .with_max_dofs(200)
        .with_time_search(search);
    let a = adapt(&scn, &RunSettings::default().with_steps(4), &s, &mut ()).unwrap();
    assert!(a.levels.len() >= 2, "{}", a.levels.len());
    for l in &a.levels {
        assert!(
            l.time_search_s > 0.0 && l.time_search_s <= l.wall_s,
            "{l:?}"
        );
    }
    for w in a.levels.windows(2) {
        assert!(w[1].steps >= w[0].steps, "{:?}", a.levels);
    }
    // Each level's grid is what a search on its mesh chooses from the grid of the level
    // before: the last one here.
    let chosen = a.time_search.expect("searched");
    let n = a.levels.len();
    assert_eq!(chosen.grid().len(), a.levels[n - 1].steps);
    let start = chosen.levels[0].grid.clone();
    assert_eq!(start.len(), a.levels[n - 2].steps);
    let mesh = a.solution.run.mesh.clone();
    let sim = Simulation::on_mesh(
        a.scenario.clone(),
        RunSettings::default().with_steps(4),
        mesh,
    )
    .unwrap();
    let alone = choose_from(&sim, &search, start, &mut |_| {}).unwrap();
    assert_eq!(alone.grid(), chosen.grid());
    let both = s.with_time_grid(TimeGrid::uniform(1.0, 4));
    let e = both.check().unwrap_err().to_string();
    assert!(e.contains("time_search"), "{e}");
}
