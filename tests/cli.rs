//! The command line: outputs, headers, and readable errors.

use std::process::Command;

fn evhi() -> Command {
    Command::new(env!("CARGO_BIN_EXE_evhi"))
}

/// Runs `cmd`, which must succeed (its stderr is shown otherwise).
fn succeed(cmd: &mut Command) {
    let out = cmd.output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn solve_writes_all_outputs() {
    let dir = std::env::temp_dir().join(format!("evhi-cli-{}", std::process::id()));
    succeed(
        evhi()
            .args([
                "solve",
                "--scenario",
                "figure",
                "--n",
                "16",
                "--steps",
                "8",
                "--out",
            ])
            .arg(&dir),
    );
    let contact = std::fs::read_to_string(dir.join("contact.csv")).unwrap();
    assert!(contact.starts_with("x,u_nu,sigma_nu1,sigma_nu2,regime\n"));
    assert_eq!(contact.lines().count(), 1 + 17);
    let summary = std::fs::read_to_string(dir.join("summary.csv")).unwrap();
    assert!(summary.starts_with("n,steps,dofs,energy_norm_T,max_certificate,wall_s,"));
    let steps = std::fs::read_to_string(dir.join("steps.csv")).unwrap();
    assert_eq!(steps.lines().count(), 1 + 8);
    let vtu = std::fs::read_to_string(dir.join("solution.vtu")).unwrap();
    assert!(vtu.contains("NumberOfPoints=\"153\"") && vtu.contains("NumberOfCells=\"256\""));
    // No temporary files are left behind.
    assert!(
        std::fs::read_dir(&dir).unwrap().all(|e| !e
            .unwrap()
            .file_name()
            .to_string_lossy()
            .starts_with('.'))
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_arguments_fail_with_the_field_named() {
    for (args, needle) in [
        (vec!["--n", "10"], "`n`"),
        (vec!["--g", "-0.1"], "`g`"),
        (vec!["--steps", "0"], "`steps`"),
        (vec!["--scenario", "nope"], "`scenario`"),
    ] {
        let out = evhi()
            .args(["solve", "--out", "/tmp/evhi-never"])
            .args(&args)
            .output()
            .unwrap();
        assert!(!out.status.success());
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
    }
    let out = evhi()
        .args(["solve", "--out", "/tmp/x", "--f0", "1,two"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("two"));
}

#[test]
fn bench_sweeps_writes_every_variant() {
    let dir = std::env::temp_dir().join(format!("evhi-sweeps-{}", std::process::id()));
    succeed(
        evhi()
            .args(["bench", "--sweeps", "--sweeps-n", "16", "--data"])
            .arg(&dir),
    );
    let csv = std::fs::read_to_string(dir.join("bench_sweeps.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().filter(|l| !l.starts_with('#')).collect();
    assert!(rows[0].starts_with("variant,ordering,threads,prefetch,columns,nnz_l,"));
    // faer, seven of ours, two streaming rates.
    assert_eq!(rows.len(), 1 + 10, "{csv}");
    for row in &rows[1..] {
        let total: f64 = row.split(',').nth(8).unwrap().parse().unwrap();
        assert!(total > 0.0 && total.is_finite(), "{row}");
    }
    // A level the mesh does not allow is refused with the field named.
    let out = evhi()
        .args(["bench", "--sweeps", "--sweeps-n", "10", "--data"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("`n`"));
    std::fs::remove_dir_all(&dir).ok();
}
