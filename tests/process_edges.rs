//! The edges of the process (issue 47): arguments that are not UTF-8, standard
//! streams that are closed or full, output directories that hold a user's files,
//! names with Unicode line breaks, one bound for both forms of a material, TOML
//! errors on long lines, sizes in units that show them, and `plot`'s own words.

mod common;

use common::*;
use std::process::{Command, Stdio};

/// A non-UTF-8 `--out` (a legal Linux path) is solved and written; the provenance line
/// names it lossily instead of panicking after all the steps (case 1).
#[cfg(target_os = "linux")]
#[test]
fn a_non_utf8_out_is_written_and_named_lossily() {
    use std::os::unix::ffi::OsStrExt;
    let dir = scratch("non-utf8-out");
    let out = dir.join(std::ffi::OsStr::from_bytes(b"run-\xff\xfe"));
    let o = evhi_with("solve --scenario figure --n 8 --steps 2 --out")
        .arg(&out)
        .output()
        .unwrap();
    let err = ok(&o);
    assert!(!err.contains("panicked"), "{err}");
    let summary = read(out.join("summary.csv"));
    assert!(
        summary
            .lines()
            .next()
            .unwrap()
            .contains("run-\u{fffd}\u{fffd}"),
        "{summary}"
    );
    // A study's provenance is built the same way.
    let study = dir.join(std::ffi::OsStr::from_bytes(b"study-\xff"));
    let o = evhi_with("study stability --quick --scenario figure --out")
        .arg(&study)
        .output()
        .unwrap();
    ok(&o);
}

/// A `--scenario` path that is not UTF-8 is refused in our words, naming the
/// argument and saying what to do, by every command that reads a scene; nothing is
/// written.
#[test]
fn a_non_utf8_scenario_is_refused_with_what_to_do() {
    use std::os::unix::ffi::OsStrExt;
    let dir = scratch("non-utf8-scenario");
    let scene = dir.join(std::ffi::OsStr::from_bytes(b"scene-\xff.toml"));
    std::fs::write(&scene, "").unwrap();
    let out = dir.join("out");
    for cmd in [
        "solve --out",
        "study time --quick --out",
        "study stability --quick --out",
        "study convergence --quick --out",
    ] {
        let o = evhi_with(cmd)
            .arg(&out)
            .arg("--scenario")
            .arg(&scene)
            .output()
            .unwrap();
        assert!(!o.status.success(), "{cmd}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains("--scenario"), "{cmd}: {err}");
        assert!(err.contains("is not valid UTF-8"), "{cmd}: {err}");
        assert!(err.contains("rename the file"), "{cmd}: {err}");
        assert!(!err.contains("panicked"), "{cmd}: {err}");
        assert!(!out.exists(), "{cmd} wrote {out:?}");
    }
    let o = evhi_with("show").arg(&scene).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("is not valid UTF-8"),
        "{err}"
    );
}

/// `evhi scenarios | head -1` ends quietly: no panic, success, whatever the timing
/// (case 2; it panicked 9 times in 20).
#[test]
fn a_closed_stdout_ends_quietly() {
    for _ in 0..20 {
        let o = Command::new("sh")
            .arg("-c")
            .arg(format!(
                "'{}' scenarios | head -c 1 >/dev/null",
                env!("CARGO_BIN_EXE_evhi")
            ))
            .output()
            .unwrap();
        let err = stderr(&o);
        assert!(!err.contains("panicked"), "{err}");
    }
    // The reader gone before the first byte: the command still succeeds.
    let mut child = evhi()
        .arg("scenarios")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let o = child.wait_with_output().unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!stderr(&o).contains("panicked"), "{}", stderr(&o));
}

/// A full stdout is an error that says so (rc 1), never a panic (rc 101); a full
/// stderr loses only the commentary: the run is written (case 2).
#[cfg(target_os = "linux")]
#[test]
fn a_full_stream_is_no_panic() {
    let full = || {
        std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap()
    };
    let o = evhi_with("show figure").stdout(full()).output().unwrap();
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    refused(&o, &["error:"]);
    let dir = scratch("full-stderr");
    let o = evhi_with("solve --scenario figure --n 8 --steps 2 --timings --out")
        .arg(dir.join("run"))
        .stderr(full())
        .output()
        .unwrap();
    assert!(o.status.success(), "rc {:?}", o.status.code());
    assert!(dir.join("run/summary.csv").exists());
    // A refusal whose message cannot be written still fails, quietly.
    let o = evhi_with("solve --scenario figure --n 7 --out")
        .arg(dir.join("refused"))
        .stderr(full())
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
}

/// `reproduce --data DIR --figures DIR` refuses a directory that holds files evhi did
/// not write (`/`, a user's folder), before any work, instead of overwriting
/// same-named files; an empty or new directory is taken and marked, and a second run
/// into it is allowed. The provenance line names the directories (case 4).
#[test]
fn reproduce_writes_only_where_it_may() {
    let dir = scratch("reproduce-foreign");
    let user = dir.join("mine");
    std::fs::create_dir_all(&user).unwrap();
    written(user.join("fig2_law.csv"), "my own table\n");
    let run = |data: &std::path::Path, figures: &std::path::Path| {
        evhi_with("reproduce fig2 --quick -q --data")
            .arg(data)
            .arg("--figures")
            .arg(figures)
            .output()
            .unwrap()
    };
    for (data, figures, flag) in [
        (user.clone(), dir.join("figs"), "`--data`"),
        (dir.join("data"), user.clone(), "`--figures`"),
        (std::path::PathBuf::from("/"), dir.join("figs"), "`--data`"),
    ] {
        let err = refused(&run(&data, &figures), &[flag, "evhi did not write"]);
        assert!(err.contains(".evhi-outputs"), "{err}");
    }
    assert_eq!(read(user.join("fig2_law.csv")), "my own table\n");
    assert!(!dir.join("figs").exists() && !dir.join("data").exists());
    // A new directory is taken, marked, and taken again.
    let (data, figs) = (dir.join("data"), dir.join("figs"));
    for _ in 0..2 {
        ok(&run(&data, &figs));
    }
    assert!(data.join(".evhi-outputs").exists() && figs.join(".evhi-outputs").exists());
    let head = read(data.join("fig2_law.csv"));
    let first = head.lines().next().unwrap();
    assert!(
        first.contains("--quick --data ") && first.contains(" --figures "),
        "{first}"
    );
    // The committed directories carry the mark, so the main job writes there.
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    for d in ["data", "figures"] {
        assert!(root.join(d).join(".evhi-outputs").exists(), "{d}");
    }
}

/// Every Unicode line break is refused in a name or description, in a file and
/// through the library (case 6: U+2028 split Python's reading of the `#` line).
#[test]
fn unicode_line_breaks_are_refused_in_names() {
    let text = read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/data/scenarios/figure.toml"
    ));
    for sep in [
        '\u{2028}', '\u{2029}', '\u{85}', '\u{b}', '\u{c}', '\n', '\r',
    ] {
        for key in ["name", "description"] {
            let line = text
                .lines()
                .find(|l| l.starts_with(&format!("{key} =")))
                .unwrap();
            let edited = text.replace(line, &format!("{key} = \"a\\U{:08X}b\"", sep as u32));
            let e = evhi::scenario::Scenario::from_toml(&edited, "t").unwrap_err();
            assert_eq!(e.field_name(), Some(key), "{sep:?}: {e}");
        }
        let scn = evhi::scenario::Scenario::load("figure").unwrap();
        let e = scn.clone().with_name(&format!("a{sep}b")).unwrap_err();
        assert_eq!(e.field_name(), Some("name"));
        let e = scn.with_description(&format!("a{sep}b")).unwrap_err();
        assert_eq!(e.field_name(), Some("description"));
    }
}

/// One bound for both forms of the elasticity: lambda = 1.67e14, mu = 3.33e8 is the
/// material E = 1e9, kappa = 0.499999, and both solve certified (case 8).
#[test]
fn both_forms_of_one_material_are_accepted_together() {
    let text = read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/data/scenarios/figure.toml"
    ));
    let (e, kappa) = (1e9, 0.499999);
    let lambda = e * kappa / ((1.0 + kappa) * (1.0 - 2.0 * kappa));
    let mu = e / (2.0 * (1.0 + kappa));
    assert!(lambda > 1e14);
    let young = text
        .replace("E = 1000.0", &format!("E = {e:e}"))
        .replace("kappa = 0.4", &format!("kappa = {kappa}"));
    let lame = text
        .replace("E = 1000.0", &format!("lambda = {lambda:e}"))
        .replace("kappa = 0.4", &format!("mu = {mu:e}"));
    let a = evhi::scenario::Scenario::from_toml(&young, "young").unwrap();
    let b = evhi::scenario::Scenario::from_toml(&lame, "lame").unwrap();
    assert!((a.kappa() - b.kappa()).abs() < 1e-12 && (a.e() - b.e()).abs() < 1e-3 * a.e());
    let settings = evhi::simulation::RunSettings::default()
        .with_n(8)
        .with_steps(2);
    for scn in [a, b] {
        let s = evhi::simulation::Simulation::new(scn, settings.clone())
            .unwrap()
            .solve(&mut ())
            .unwrap();
        assert!(s.max_certificate() <= 1e-10, "{}", s.max_certificate());
    }
    // What the implied Poisson ratio cannot hold is still refused, by name.
    let too = text
        .replace("E = 1000.0", "lambda = 1e300")
        .replace("kappa = 0.4", "mu = 1.0");
    let e = evhi::scenario::Scenario::from_toml(&too, "too").unwrap_err();
    assert_eq!(e.field_name(), Some("material.lambda"), "{e}");
}

/// A TOML error on a long line keeps its reason and its caret: the echoed line is cut
/// around the error, and bare carriage returns are escaped, not echoed (case 9).
#[test]
fn toml_errors_keep_the_reason_and_the_spot() {
    let text = read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/data/scenarios/figure.toml"
    ));
    let long = format!(
        "{text}\n[loads.extra]\nvalues = [{}, oops]\n",
        (0..400)
            .map(|i| i.to_string())
            .collect::<Vec<_>>()
            .join(", ")
    );
    let e = evhi::scenario::Scenario::from_toml(&long, "long")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("oops") && e.contains('^') && e.contains("line "),
        "{e}"
    );
    assert!(e.lines().all(|l| l.chars().count() < 200), "{e}");
    let reason = e.lines().next().unwrap();
    assert!(reason.contains("column"), "{e}");
    let cr = text.replace('\n', "\r");
    let e = evhi::scenario::Scenario::from_toml(&cr, "cr")
        .unwrap_err()
        .to_string();
    assert!(!e.contains('\r') && e.contains("\\r"), "{e:?}");
    assert!(e.lines().all(|l| l.chars().count() < 200), "{e}");
}

/// Sizes are given in the unit that shows them: 17 MB and 1.3 MB, not "0.0 GB" (case
/// 14).
#[test]
fn sizes_are_given_in_a_unit_that_shows_them() {
    use evhi::term::size_text;
    assert_eq!(size_text(17.3e6), "17.3 MB");
    assert_eq!(size_text(1.3e6), "1.30 MB");
    assert_eq!(size_text(512e3), "512 kB");
    assert_eq!(size_text(40.0), "40 B");
    assert_eq!(size_text(2.5e12), "2.50 TB");
}

/// `plot` speaks of the run directory, never of `--out`, which it does not have:
/// for `/` and for a run that a `solve` is writing (case 15).
#[test]
fn plot_speaks_of_its_run_directory() {
    let err = refused(
        &evhi().arg("plot").arg("/").output().unwrap(),
        &["run directory"],
    );
    assert!(!err.contains("--out"), "{err}");
    let dir = scratch("plot-busy");
    let run = dir.join("run");
    ok(&evhi_with("solve --scenario figure --n 8 --steps 2 --out")
        .arg(&run)
        .output()
        .unwrap());
    // Hold the lock a writer holds, as a `solve` into the same directory would.
    let _lock = evhi::output::rundir::lock_run_dir(&run).unwrap();
    let err = refused(
        &evhi().arg("plot").arg(&run).output().unwrap(),
        &["run directory"],
    );
    assert!(!err.contains("--out"), "{err}");
    assert!(err.contains("wait for it"), "{err}");
}
