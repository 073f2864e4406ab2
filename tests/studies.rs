//! The studies on scenes of one's own: levels chosen so that every mesh the study
//! builds resolves the scene.

mod common;
use common::{Csv, evhi, ok, scratch, written};

/// A 3 x 1 scene whose supports end at y = 0.4 and 0.6 and whose contact zone starts at
/// 0.375 (issue 41, item 8): the coarsest power-of-two grid that resolves it at one
/// level, n = 16 (5 rows), misses y = 0.4 at 2n = 32 (11 rows), and the study used to
/// refuse it naming an n it does not take. It now starts from the coarsest n0 whose
/// every level resolves the scene (120: 40 rows, then 80).
#[test]
fn a_study_picks_levels_that_all_resolve_the_scene() {
    let dir = scratch("study-levels");
    let scene = written(
        dir.join("k2.toml"),
        "name = \"K2\"\nT = 1.0\ng = 0.05\n[geometry]\nwidth = 3.0\nheight = 1.0\n\
         contact = [0.375, 2.25]\n[geometry.supports]\n\
         left = [{ from = 0.0, to = 0.4, kind = \"rollers\" }, { from = 0.6, to = 1.0, kind = \"clamped\" }]\n\
         bottom = [{ from = 2.25, to = 3.0, kind = \"rollers\" }]\n\
         [material]\nE = 1000.0\nkappa = 0.3\nalpha = 50.0\nbeta = 30.0\n\
         [loads]\nf0 = [0.5, -4.0]\nf2 = [0.0, -20.0]\nhistory = { ramp = 0.3 }\n\
         [law]\nbreakpoints = [0.0, 0.02, 0.04]\nslopes = [0.0, 400.0, -100.0, 300.0]\n",
    );
    let out = dir.join("stab");
    ok(&evhi()
        .args(["study", "stability", "--quick", "--scenario"])
        .arg(&scene)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap());
    let table = Csv::read(out.join("stability.csv"));
    let mut levels: Vec<f64> = table.column_f64("n");
    levels.dedup();
    assert_eq!(levels, vec![120.0, 240.0]);
    assert!(table.column_str("outcome").contains(&"certified"));
}
