//! What the test binaries share (as cargo's own `cargo-test-support`): running the `evhi`
//! binary, a scratch directory per test, the checks of a run that must succeed or be
//! refused, solving a scenario given as text, and one CSV reader for every table a test
//! reads. Each test binary takes it with `mod common;` and uses a part of it.
#![allow(dead_code)]

use std::collections::HashMap;
use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The `evhi` binary of this build.
pub fn evhi() -> Command {
    Command::new(env!("CARGO_BIN_EXE_evhi"))
}

/// `evhi` with the blank-separated words of `words` as its first arguments (no
/// argument given this way holds a blank): `evhi_with("solve --n 8 --out").arg(dir)`.
pub fn evhi_with(words: &str) -> Command {
    let mut cmd = evhi();
    cmd.args(words.split_whitespace());
    cmd
}

/// A fresh, empty scratch directory for one test.
pub fn scratch(name: &str) -> Scratch {
    let dir = std::env::temp_dir().join(format!("evhi-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    Scratch(dir)
}

/// A test's scratch directory, removed when the test ends unless it failed (then it
/// stays for a look): runs no longer leave a directory per test behind.
pub struct Scratch(PathBuf);

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<OsStr> for Scratch {
    fn as_ref(&self) -> &OsStr {
        self.0.as_os_str()
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        if !std::thread::panicking() {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }
}

/// A command's standard error as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A command's standard output as text.
pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Runs `cmd` to its end, or kills it after `secs` seconds and fails the test: for a
/// case whose bug was a hang (it spun, or allocated without bound).
pub fn output_within(cmd: &mut Command, secs: u64) -> Output {
    use std::io::Read;
    let mut child = cmd
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // Read both pipes while waiting, so that a full pipe cannot stall the child.
    let drain = |mut r: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut buf = vec![];
            let _ = r.read_to_end(&mut buf);
            buf
        })
    };
    let out = drain(Box::new(child.stdout.take().unwrap()));
    let err = drain(Box::new(child.stderr.take().unwrap()));
    let start = std::time::Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if start.elapsed().as_secs() >= secs {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{cmd:?} still ran after {secs} s (killed)");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    };
    Output {
        status,
        stdout: out.join().unwrap(),
        stderr: err.join().unwrap(),
    }
}

/// Every file under `dir` (its path relative to `dir`) with its bytes, to show that a
/// refused command wrote or changed nothing.
pub fn snapshot(dir: &Path) -> std::collections::BTreeMap<PathBuf, Vec<u8>> {
    let mut files = std::collections::BTreeMap::new();
    let mut todo = vec![dir.to_path_buf()];
    while let Some(d) = todo.pop() {
        for e in std::fs::read_dir(&d).unwrap_or_else(|e| panic!("{}: {e}", d.display())) {
            let path = e.unwrap().path();
            if path.is_dir() {
                todo.push(path);
            } else {
                let rel = path.strip_prefix(dir).unwrap().to_path_buf();
                files.insert(rel, std::fs::read(&path).unwrap());
            }
        }
    }
    files
}

/// Asserts that a command succeeded (its stderr is shown otherwise); returns the stderr.
pub fn ok(o: &Output) -> String {
    let err = stderr(o);
    assert!(o.status.success(), "{err}");
    err
}

/// Asserts that `text` holds every one of `needles` (the text is shown otherwise).
pub fn assert_contains(text: &str, needles: &[&str]) {
    for n in needles {
        assert!(text.contains(n), "no `{n}` in: {text}");
    }
}

/// Asserts that a command failed (its stderr is shown otherwise); returns the stderr.
pub fn failed(o: &Output) -> String {
    let err = stderr(o);
    assert!(!o.status.success(), "accepted: {err}");
    err
}

/// Asserts that a command failed with `needle` in its stderr; returns the stderr.
pub fn failed_with(o: &Output, needle: &str) -> String {
    let err = stderr(o);
    assert!(!o.status.success() && err.contains(needle), "{err}");
    err
}

/// Runs `cmd`, which must succeed (its stderr is shown otherwise).
pub fn succeed(cmd: &mut Command) -> Output {
    let out = cmd.output().unwrap();
    ok(&out);
    out
}

/// Asserts that a command was refused and that its stderr holds every one of
/// `needles` and no panic; returns the stderr.
pub fn refused(o: &Output, needles: &[&str]) -> String {
    let err = stderr(o);
    assert!(!o.status.success(), "accepted: {err}");
    assert!(!err.contains("panicked"), "{err}");
    assert_contains(&err, needles);
    err
}

/// A file's text; a missing file panics with its path.
pub fn read(path: impl AsRef<Path>) -> String {
    let path = path.as_ref();
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Writes `text` to `path` and returns the path.
pub fn written(path: impl Into<PathBuf>, text: impl AsRef<[u8]>) -> PathBuf {
    let path = path.into();
    std::fs::write(&path, text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    path
}

/// The names of the entries of `dir`.
pub fn names(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect()
}

/// Solves a scenario given as text: writes `text` to `dir/NAME.toml` and runs
/// `evhi solve --scenario dir/NAME.toml EXTRA... --out dir/NAME`, returning the output
/// (succeeded or not) and the run directory.
pub fn solve_text(dir: &Path, name: &str, text: &str, extra: &[&str]) -> (Output, PathBuf) {
    let file = dir.join(format!("{name}.toml"));
    std::fs::write(&file, text).unwrap();
    let out = dir.join(name);
    let o = evhi()
        .arg("solve")
        .arg("--scenario")
        .arg(&file)
        .args(extra)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    (o, out)
}

/// A CSV line's fields: split at the commas outside double quotes (the quotes dropped),
/// so that a label such as "newton, no line search" stays one field.
pub fn fields(line: &str) -> Vec<String> {
    let (mut out, mut cell, mut quoted) = (Vec::new(), String::new(), false);
    for c in line.chars() {
        match c {
            '"' => quoted = !quoted,
            ',' if !quoted => out.push(std::mem::take(&mut cell)),
            _ => cell.push(c),
        }
    }
    out.push(cell);
    out
}

/// A table as evhi writes it: `#` provenance lines (anywhere, skipped but kept), a
/// header, then rows; fields split by [`fields`]. Access by column name panics with the
/// file and the column when either is wrong.
pub struct Csv {
    /// Where the table came from, for messages.
    pub source: String,
    /// The `#` lines, in order.
    pub provenance: Vec<String>,
    pub header: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl Csv {
    /// The table in the file at `path`.
    pub fn read(path: impl AsRef<Path>) -> Csv {
        let path = path.as_ref();
        Csv::parse_from(&read(path), &path.display().to_string())
    }

    /// The table in `text`.
    pub fn parse(text: &str) -> Csv {
        Csv::parse_from(text, "a table's text")
    }

    fn parse_from(text: &str, source: &str) -> Csv {
        let (provenance, lines): (Vec<&str>, Vec<&str>) =
            text.lines().partition(|l| l.starts_with('#'));
        let mut lines = lines.into_iter();
        let header = fields(
            lines
                .next()
                .unwrap_or_else(|| panic!("{source}: no header")),
        );
        Csv {
            source: source.to_string(),
            provenance: provenance.into_iter().map(str::to_string).collect(),
            header,
            rows: lines.map(fields).collect(),
        }
    }

    /// The data rows (the header not among them).
    pub fn rows(&self) -> &[Vec<String>] {
        &self.rows
    }

    /// How many data rows.
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// The index of column `name`.
    pub fn col(&self, name: &str) -> usize {
        self.header
            .iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("{}: no column `{name}` in {:?}", self.source, self.header))
    }

    /// The text in row `row` (0 is the first data row), column `name`.
    pub fn get(&self, row: usize, name: &str) -> &str {
        let at = self.col(name);
        let r = self
            .rows
            .get(row)
            .unwrap_or_else(|| panic!("{}: no row {row} of {}", self.source, self.rows.len()));
        r.get(at)
            .unwrap_or_else(|| panic!("{}: row {row} has no `{name}`: {r:?}", self.source))
    }

    /// The number in row `row`, column `name`.
    pub fn f64(&self, row: usize, name: &str) -> f64 {
        let text = self.get(row, name);
        text.parse()
            .unwrap_or_else(|e| panic!("{}: row {row}, `{name}` = {text:?}: {e}", self.source))
    }

    /// Every row's text in column `name`.
    pub fn column_str(&self, name: &str) -> Vec<&str> {
        (0..self.rows.len()).map(|r| self.get(r, name)).collect()
    }

    /// Every row's number in column `name`.
    pub fn column_f64(&self, name: &str) -> Vec<f64> {
        (0..self.rows.len()).map(|r| self.f64(r, name)).collect()
    }

    /// The rows as maps from column to text (a row shorter than the header has only its
    /// first columns).
    pub fn maps(&self) -> Vec<HashMap<String, String>> {
        self.rows
            .iter()
            .map(|r| self.header.iter().cloned().zip(r.iter().cloned()).collect())
            .collect()
    }
}

/// The one row of a run's `summary.csv`, typed as the run wrote it.
pub fn summary(run: &Path) -> evhi::output::rows::SummaryRow {
    let mut rows = evhi::output::rows::SummaryRow::read(&run.join("summary.csv"))
        .unwrap_or_else(|e| panic!("{}: {e}", run.display()));
    assert_eq!(rows.len(), 1, "{}: one row", run.display());
    rows.remove(0)
}

/// The rows of a run's `steps.csv`, typed.
pub fn steps(run: &Path) -> Vec<evhi::output::rows::StepRow> {
    evhi::output::rows::StepRow::read(&run.join("steps.csv"))
        .unwrap_or_else(|e| panic!("{}: {e}", run.display()))
}

/// The rows of a run's `contact.csv`, typed.
pub fn contact(run: &Path) -> Vec<evhi::output::rows::ContactRow> {
    evhi::output::rows::ContactRow::read(&run.join("contact.csv"))
        .unwrap_or_else(|e| panic!("{}: {e}", run.display()))
}

/// The settings of the general time loop on `n` segments with `steps` steps, the rest
/// as [`evhi::simulation::RunSettings::default`].
pub fn general(n: usize, steps: usize) -> evhi::simulation::RunSettings {
    evhi::simulation::RunSettings::general(n, steps)
}

/// Solves `scn` with `settings` (on `mesh` if given) by the caller's `solver`, telling
/// `observer` every step.
pub fn solve_with(
    scn: &evhi::scenario::Scenario,
    settings: evhi::simulation::RunSettings,
    mesh: Option<std::sync::Arc<evhi::mesh::Mesh>>,
    solver: &mut dyn evhi::step::StepSolver,
    observer: &mut dyn evhi::simulation::Observer,
) -> Result<evhi::scheme::Run, evhi::scheme::RunError> {
    use evhi::simulation::Simulation;
    let sim = match mesh {
        Some(mesh) => Simulation::on_mesh(scn.clone(), settings, mesh)?,
        None => Simulation::new(scn.clone(), settings)?,
    };
    Ok(sim.solve_with(solver, observer)?.run)
}

/// The general time loop with Newton on `n` segments and `steps` steps, no observer
/// (the plain run the tests compare against).
pub fn run_newton(
    scn: &evhi::scenario::Scenario,
    n: usize,
    steps: usize,
) -> Result<evhi::scheme::Run, evhi::scheme::RunError> {
    let newton = &mut evhi::step::newton::Newton::default();
    solve_with(scn, general(n, steps), None, newton, &mut ())
}

/// An observer that asks the reduced loop for the field at every step (and is told
/// nothing).
pub struct EveryField;

impl evhi::simulation::Observer for EveryField {
    fn wants_field(&self, _step: usize) -> bool {
        true
    }
}

/// The settings of the time loop `reduced` or general on `n` segments with `steps` steps.
pub fn on_loop(n: usize, steps: usize, reduced: bool) -> evhi::simulation::RunSettings {
    general(n, steps).with_path(if reduced {
        evhi::simulation::Loop::Reduced
    } else {
        evhi::simulation::Loop::General
    })
}

/// An observer that asks the reduced loop for the field where `wants(step)` and tells
/// `step(n, t_n, u_n, contact_n)` every step.
pub struct Watch<W, F> {
    wants: W,
    step: F,
}

/// The observer [`Watch`] of `wants` and `step`.
pub fn watch<W, F>(wants: W, step: F) -> Watch<W, F>
where
    W: Fn(usize) -> bool,
    F: FnMut(usize, f64, Option<&[f64]>, &[evhi::certificate::ContactState]),
{
    Watch { wants, step }
}

impl<W, F> evhi::simulation::Observer for Watch<W, F>
where
    W: Fn(usize) -> bool,
    F: FnMut(usize, f64, Option<&[f64]>, &[evhi::certificate::ContactState]),
{
    fn wants_field(&self, step: usize) -> bool {
        (self.wants)(step)
    }
    fn step(&mut self, n: usize, t: f64, u: Option<&[f64]>, c: &[evhi::certificate::ContactState]) {
        (self.step)(n, t, u, c)
    }
}
