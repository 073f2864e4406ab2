//! A run's output set: written whole or not at all, never mixed, never lost.

mod common;

use common::{evhi, names, scratch};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn solve(n: usize, out: &Path) -> Command {
    solve_steps(n, 8, out)
}

fn solve_steps(n: usize, steps: usize, out: &Path) -> Command {
    let mut c = evhi();
    c.args([
        "solve",
        "--scenario",
        "figure",
        "--n",
        &n.to_string(),
        "--steps",
        &steps.to_string(),
        "--out",
    ])
    .arg(out)
    .stdout(Stdio::null())
    .stderr(Stdio::piped());
    c
}

/// The mesh size of a whole, consistent set in `dir`, or why it is not one.
fn whole_set(dir: &Path) -> Result<usize, String> {
    let read = |f: &str| std::fs::read_to_string(dir.join(f)).map_err(|e| format!("{f}: {e}"));
    let header = |text: &str| text.lines().take(2).collect::<Vec<_>>().join("\n");
    let (contact, steps, summary, vtu) = (
        read("contact.csv")?,
        read("steps.csv")?,
        read("summary.csv")?,
        read("solution.vtu")?,
    );
    if !dir.join(".evhi-run").exists() {
        return Err("no marker".into());
    }
    if header(&contact) != header(&steps) || header(&steps) != header(&summary) {
        return Err("CSV headers of different runs".into());
    }
    let n = contact.lines().filter(|l| !l.starts_with('#')).count() - 2;
    let points = (n + 1) * (n / 2 + 1);
    if !vtu.contains(&format!("NumberOfPoints=\"{points}\"")) {
        return Err(format!("solution.vtu is not of the run with n = {n}"));
    }
    if !summary.contains(&format!("\n{n},8,")) {
        return Err(format!("summary.csv is not of the run with n = {n}"));
    }
    Ok(n)
}

/// Hidden leftovers beside the target (staging directories, lock files): none, once
/// the run has ended (its lock `.NAME.lock` exists only while the run holds it).
fn leftovers(parent: &Path) -> Vec<String> {
    names(parent)
        .into_iter()
        .filter(|n| n.starts_with('.'))
        .collect()
}

#[test]
fn a_second_writer_fails_at_once() {
    let root = scratch("out-busy");
    let out = root.join("run");
    let mut first = solve_steps(64, 64, &out)
        .env("EVHI_WRITE_DELAY_MS", "400")
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(300));
    let t = Instant::now();
    let second = solve(16, &out).output().unwrap();
    let err = String::from_utf8_lossy(&second.stderr);
    assert!(!second.status.success());
    assert!(
        err.contains("another evhi run is writing") && err.contains("run"),
        "{err}"
    );
    assert!(
        t.elapsed() < Duration::from_secs(2),
        "the refusal must not wait"
    );
    assert!(first.wait().unwrap().success());
    assert!(
        std::fs::read_to_string(out.join("summary.csv"))
            .unwrap()
            .contains("\n64,64,")
    );
    assert!(leftovers(&root).is_empty(), "{:?}", leftovers(&root));
}

#[test]
fn bad_out_paths_fail_before_the_solve_naming_the_path() {
    let root = scratch("out-bad");
    let file = root.join("a_file");
    std::fs::write(&file, "x").unwrap();
    let foreign = root.join("mine");
    std::fs::create_dir(&foreign).unwrap();
    std::fs::write(foreign.join("notes.txt"), "keep me").unwrap();
    for (out, needle) in [
        (file.clone(), "is not a directory"),
        (PathBuf::from("/dev/full"), "is not a directory"),
        (foreign.clone(), "not an evhi run directory"),
    ] {
        let t = Instant::now();
        // A mesh that takes over ten seconds to solve: the refusal must come before it.
        let o = solve_steps(512, 512, &out).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success());
        assert!(
            err.contains(&out.display().to_string()) && err.contains(needle),
            "{err}"
        );
        assert!(
            t.elapsed() < Duration::from_secs(3),
            "{err}: not before the solve"
        );
    }
    assert_eq!(
        std::fs::read_to_string(foreign.join("notes.txt")).unwrap(),
        "keep me"
    );
}

/// Kills `solve` at pseudo-random moments of its write phase (slowed by the test hook)
/// with SIGKILL or SIGINT, alternating the mesh so that old and new sets differ. After
/// every kill the target holds one whole set, old or new; the next run clears what the
/// killed one left.
#[test]
fn interrupted_writes_leave_a_whole_set() {
    let root = scratch("out-kill");
    let out = root.join("run");
    assert!(solve(16, &out).status().unwrap().success());
    assert_eq!(whole_set(&out), Ok(16));
    let mut seed: u64 = 0x9e3779b97f4a7c15;
    let (mut old_kept, mut new_whole) = (0, 0);
    for trial in 0..24 {
        let previous = whole_set(&out).unwrap();
        let n = if previous == 16 { 20 } else { 16 };
        let mut child = solve(n, &out)
            .env("EVHI_WRITE_DELAY_MS", "25")
            .spawn()
            .unwrap();
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        // The solve takes a few ms, each of the five files 25 ms more.
        let wait = 5 + (seed >> 33) % 180;
        std::thread::sleep(Duration::from_millis(wait));
        let signal = if trial % 2 == 0 { "-KILL" } else { "-INT" };
        let _ = Command::new("kill")
            .args([signal, &child.id().to_string()])
            .status();
        let _ = child.wait();
        match whole_set(&out) {
            Ok(m) if m == previous => old_kept += 1,
            Ok(m) if m == n => new_whole += 1,
            other => panic!("trial {trial} ({signal} after {wait} ms): {other:?}"),
        }
    }
    // A complete run afterwards cleans every leftover of the killed ones.
    assert!(solve(16, &out).status().unwrap().success());
    assert_eq!(whole_set(&out), Ok(16));
    assert!(leftovers(&root).is_empty(), "{:?}", leftovers(&root));
    eprintln!("24 interrupted writes: {old_kept} kept the old set, {new_whole} the new");
    assert!(old_kept > 0, "no kill landed inside the write phase");
}

/// A file the user puts into `--out` while a run is writing is kept: the check at the
/// start cannot see it, and the old set it lands in is swapped out at publish; it used
/// to be deleted with that set, silently (issue 41, item 2). It is moved into the new
/// set, the run says so, and the next run refuses it by name.
#[test]
fn a_file_added_during_the_run_is_kept() {
    let root = scratch("out-added");
    let out = root.join("run");
    assert!(solve(8, &out).status().unwrap().success());
    let run = solve(8, &out)
        .env("EVHI_WRITE_DELAY_MS", "300")
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(600));
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    let done = run.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&done.stderr);
    assert!(done.status.success(), "{err}");
    assert!(err.contains("`notes.txt`") && err.contains("kept"), "{err}");
    assert_eq!(
        std::fs::read_to_string(out.join("notes.txt")).unwrap(),
        "mine"
    );
    assert_eq!(whole_set(&out), Ok(8));
    let again = solve(8, &out).output().unwrap();
    let err = String::from_utf8_lossy(&again.stderr);
    assert!(
        !again.status.success() && err.contains("`notes.txt`"),
        "{err}"
    );
}

/// A user's file named like a temporary is the user's: `.notes.tmp-1.txt` in a run
/// directory used to count as a run's leftover and be deleted by the next run (issue
/// 41, item 4). Only the temporaries of a run's own files count.
#[test]
fn a_user_file_named_like_a_temporary_is_refused_not_deleted() {
    use evhi::output::rundir::is_run_file;
    assert!(is_run_file(".deformed.tmp-123.png") && is_run_file(".summary.csv.tmp-9"));
    assert!(!is_run_file(".notes.tmp-1.txt") && !is_run_file(".deformed.tmp-x.png"));
    let root = scratch("out-tmpname");
    let out = root.join("run");
    assert!(solve(8, &out).status().unwrap().success());
    std::fs::write(out.join(".notes.tmp-1.txt"), "mine").unwrap();
    let again = solve(8, &out).output().unwrap();
    let err = String::from_utf8_lossy(&again.stderr);
    assert!(
        !again.status.success() && err.contains("`.notes.tmp-1.txt`"),
        "{err}"
    );
    assert!(out.join(".notes.tmp-1.txt").exists());
}

/// The scenario file is read once: moved or edited while the run writes, the run still
/// ends and records the text it solved (it read the file again after solving, so a move
/// failed with `No such file or directory` naming no path and lost the result, and an
/// edit put the new text beside the old results; issue 41, item 3).
#[test]
fn the_scenario_file_is_read_once() {
    let root = scratch("out-readonce");
    let out = root.join("run");
    let file = root.join("s.toml");
    let text = std::fs::read_to_string("data/scenarios/figure.toml").unwrap();
    std::fs::write(&file, format!("# the text solved\n{text}")).unwrap();
    let mut c = evhi();
    c.args(["solve", "--n", "8", "--steps", "4", "--scenario"])
        .arg(&file)
        .arg("--out")
        .arg(&out)
        .env("EVHI_WRITE_DELAY_MS", "300")
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    let run = c.spawn().unwrap();
    std::thread::sleep(Duration::from_millis(600));
    std::fs::rename(&file, root.join("moved.toml")).unwrap();
    let done = run.wait_with_output().unwrap();
    assert!(
        done.status.success(),
        "{}",
        String::from_utf8_lossy(&done.stderr)
    );
    let recorded = std::fs::read_to_string(out.join("scenario.toml")).unwrap();
    assert!(recorded.contains("# the text solved"), "{recorded}");
}

/// The run lock exists only while held, and still excludes: a second taker is refused
/// while it is held, a killed holder's file (unlocked) is taken and removed, and
/// threads that take and release it in a tight loop (each take its own open file, as
/// separate processes would have) never hold it two at a time (issue 41, case 18).
#[test]
fn the_lock_leaves_no_file_and_still_excludes() {
    use std::sync::Arc;
    use std::sync::atomic::{AtomicUsize, Ordering};
    let dir = scratch("held-lock");
    let path = dir.join(".x.lock");
    let held = evhi::output::try_lock_file(&path).unwrap().unwrap();
    assert!(path.exists());
    assert!(evhi::output::try_lock_file(&path).unwrap().is_none());
    drop(held);
    assert!(!path.exists(), "the lock file outlived its holder");
    // A killed holder's file: there, but locked by no one.
    std::fs::write(&path, "").unwrap();
    drop(evhi::output::try_lock_file(&path).unwrap().unwrap());
    assert!(!path.exists());
    let inside = Arc::new(AtomicUsize::new(0));
    let taken = Arc::new(AtomicUsize::new(0));
    let threads: Vec<_> = (0..8)
        .map(|_| {
            let (path, inside, taken) = (path.clone(), inside.clone(), taken.clone());
            std::thread::spawn(move || {
                // Each thread takes the lock 20 times, trying until it gets it: how often
                // a try fails depends on the machine's load, the count taken does not.
                let (mut mine, mut tries) = (0, 0u64);
                while mine < 20 {
                    tries += 1;
                    assert!(tries < 10_000_000, "the lock was never free");
                    if let Some(lock) = evhi::output::try_lock_file(&path).unwrap() {
                        assert_eq!(inside.fetch_add(1, Ordering::SeqCst), 0, "two holders");
                        taken.fetch_add(1, Ordering::SeqCst);
                        std::thread::yield_now();
                        inside.fetch_sub(1, Ordering::SeqCst);
                        drop(lock);
                        mine += 1;
                    } else {
                        std::thread::yield_now();
                    }
                }
            })
        })
        .collect();
    for t in threads {
        t.join().unwrap();
    }
    assert_eq!(taken.load(Ordering::SeqCst), 8 * 20);
    assert!(!path.exists());
}

/// A log axis over a range that is not finite, positive and increasing is refused at
/// once: plotters' key points of a log axis from 0 never moved (a work-precision chart
/// of a time of 0 spun) and to infinity never ended (NaN allocated without bound;
/// issue 47, case 3).
#[test]
fn a_log_axis_over_zero_or_nan_is_refused_not_drawn() {
    use evhi::output::plot::{LogLogChart, init_font};
    use plotters::prelude::*;
    init_font();
    let start = Instant::now();
    for (x, y) in [
        ((0.0, 0.0), (1.0, 10.0)),
        ((0.0, 2.0), (1.0, 10.0)),
        ((f64::INFINITY, 0.0), (1.0, 10.0)),
        ((f64::NAN, 1.0), (1.0, 10.0)),
        ((1.0, 10.0), (-1.0, 10.0)),
        ((1.0, 10.0), (5.0, 5.0)),
        ((1.0, f64::INFINITY), (1.0, 10.0)),
        // Subnormal: plotters stepped up from it for hours (round four's re-run).
        ((1e-310, 1.0), (1.0, 10.0)),
    ] {
        let mut svg = String::new();
        let root = SVGBackend::with_string(&mut svg, (400, 300)).into_drawing_area();
        let chart = LogLogChart {
            desc: ("time [s]", "error [%]"),
            ..LogLogChart::default()
        }
        .build(&root, (x.0..x.1).log_scale(), (y.0..y.1).log_scale());
        let err = chart.err().unwrap_or_else(|| panic!("{x:?} x {y:?} drawn"));
        assert!(err.contains("a log axis spans finite numbers > 0"), "{err}");
    }
    // An axis over more than 30 decades is refused as unreadable.
    let mut svg = String::new();
    let root = SVGBackend::with_string(&mut svg, (400, 300)).into_drawing_area();
    let wide =
        LogLogChart::default().build(&root, (1e-300..1e10).log_scale(), (1.0..10.0).log_scale());
    let err = wide.err().expect("310 decades drawn");
    assert!(
        err.contains("310 decades; a chart shows at most 30"),
        "{err}"
    );
    assert!(start.elapsed() < Duration::from_secs(5));
    let mut svg = String::new();
    let root = SVGBackend::with_string(&mut svg, (400, 300)).into_drawing_area();
    let chart =
        LogLogChart::default().build(&root, (0.5..20.0).log_scale(), (1e-3..1e2).log_scale());
    assert!(chart.is_ok(), "{:?}", chart.err());
}

/// The text reader of every table names the file, line and column of what it refuses,
/// and reads every committed table.
#[test]
fn tables_are_read_as_written_and_refused_by_line_and_column() {
    use evhi::output::csv::Text;
    let t = Text::parse(
        b"# made by a test\na,b\n\"x, \"\"y\"\"\",1\n\n\"\",2\n",
        "t.csv",
    )
    .unwrap();
    assert_eq!(t.header, (2, vec!["a".to_string(), "b".to_string()]));
    assert_eq!(
        t.rows[0],
        (3, vec!["x, \"y\"".to_string(), "1".to_string()])
    );
    assert_eq!(t.rows[1], (5, vec![String::new(), "2".to_string()]));
    // A byte-order mark is not part of the first column's name.
    let bom = Text::parse("\u{feff}a,b\n1,2\n".as_bytes(), "t.csv").unwrap();
    assert_eq!(bom.column("a").unwrap(), 0);
    // A deleted header line, even where the first row repeats a value (which would
    // read as a column named twice), is said to be one.
    for text in [&b"1,2\n3,4\n"[..], b"32,32,general,0.5\n"] {
        let err = Text::parse(text, "t.csv").unwrap_err().to_string();
        assert!(err.contains("t.csv:1:"), "{err}");
        assert!(err.contains("the header line seems to be missing"), "{err}");
    }
    for (text, expect) in [
        (
            &b"a,b\n1,2,3\n"[..],
            "t.csv:2: 3 fields where the header (line 1) has 2: field 3, `3`, has no column",
        ),
        (
            b"a,b\n1\n",
            "t.csv:2: 1 fields where the header (line 1) has 2: column `b` (field 2) has no value",
        ),
        (b"a,b\n1,\"2\n", "t.csv:2: a double quote is not closed"),
        (
            b"a,b\n1,x\x00y\n",
            "t.csv:2: column `b` holds `x\\0y`, with the control or line-breaking character U+0000",
        ),
        // A line separator inside quotes (round four's re-run saw it echoed raw).
        (
            "a,b\n1,\"x\u{2028}y\"\n".as_bytes(),
            "t.csv:2: column `b` holds `x\\u{2028}y`, with the control or line-breaking character U+2028",
        ),
        (b"a,a\n", "t.csv:1: column `a` appears twice in the header"),
        (b"# only\n", "t.csv:1: no header line"),
        (b"a,b\n1,\xff\n", "t.csv:2: not UTF-8 text"),
    ] {
        let err = Text::parse(text, "t.csv").unwrap_err().to_string();
        assert!(err.contains(expect), "{err}");
    }
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("data");
    let tables: Vec<PathBuf> = names(&data)
        .into_iter()
        .filter(|f| f.ends_with(".csv"))
        .map(|f| data.join(f))
        .collect();
    assert!(tables.len() > 40);
    for path in tables {
        Text::read(&path).unwrap_or_else(|e| panic!("{e}"));
    }
}

/// A figure that cannot be written says its I/O error in words (round four's re-run
/// on a full disk got plotters' Debug dump, "backend error … ImageError(IoError(…))").
/// Here the temporary's name is taken by a directory, which no file can replace.
#[test]
fn a_figure_that_cannot_be_written_says_why() {
    use evhi::output::plot::{Figure, both};
    use plotters::prelude::*;
    struct Blank;
    impl Figure for Blank {
        fn draw<DB: DrawingBackend>(
            &self,
            root: &DrawingArea<DB, plotters::coord::Shift>,
        ) -> Result<(), String> {
            root.fill(&WHITE).map_err(|e| e.to_string())
        }
    }
    let dir = scratch("figure-unwritable");
    let pid = std::process::id();
    for ext in ["png", "svg"] {
        std::fs::create_dir_all(dir.join(format!(".blank.tmp-{pid}.{ext}"))).unwrap();
    }
    let err = both(&dir, "blank", (40, 30), &Blank)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("blank.png: could not be written: Is a directory"),
        "{err}"
    );
    assert!(!err.contains("Error("), "{err}");
    assert!(!dir.join("blank.png").exists());
}
