//! `evhi reproduce`: the experiments on a pool of workers (one per core by default),
//! the costliest first, one progress bar each. The book's command, so it lives with
//! the experiments rather than with the product's commands in [`crate::cli`].

use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::Args)]
pub struct ReproduceArgs {
    /// Experiments to run (default: all; each listed below). `paper` stands for the
    /// paper's own set: its hypotheses, Figs. 2-4, the search for the `figure` loads and Table 1.
    #[arg(value_parser = clap::builder::PossibleValuesParser::new(super::registry::values()))]
    pub names: Vec<String>,
    /// Coarse levels only (seconds; what the tests snapshot).
    #[arg(long)]
    pub quick: bool,
    /// No progress bars and no summary; errors still go to stderr.
    #[arg(short, long)]
    pub quiet: bool,
    /// Progress as lines on stderr instead of bars: each unit of work as its
    /// experiment reports it (a level, a run, a cell; most report a unit when it is
    /// done), with the seconds since the start and the experiment's name, to see
    /// where the time goes or to keep a log of a run.
    #[arg(long, conflicts_with = "quiet")]
    pub log: bool,
    /// Table 1's reference level n (h = k = 1/n) in place of the paper's 512, e.g.
    /// 1024 (1.05 M unknowns, about 2 GB): writes `table1_ref<n>.csv` and
    /// `table1_reference_shift_ref<n>.csv`, how far each entry of table1.csv moves
    /// (run `reproduce table1` first); the paper's table1.csv is left as it is.
    #[arg(long, value_name = "N")]
    pub reference: Option<usize>,
    /// Record this invocation's wall times in the committed table
    /// `data/reproduce_times.csv` (which the book quotes), replacing that set's rows.
    /// Without it a full run keeps its times in `data/local/reproduce_times.csv`,
    /// which git ignores: the main job then changes no committed file.
    #[arg(long)]
    pub record_times: bool,
    /// Experiments run at once (default: the machine's cores). Each experiment's
    /// numbers are the same whatever the number: the experiments share no state, and
    /// their own threads do not depend on it.
    #[arg(long, short, value_name = "N")]
    pub jobs: Option<usize>,
    /// Directory of the CSV tables [default: data, or data/local/quick with --quick,
    /// so that coarse levels never overwrite the committed tables].
    #[arg(long)]
    pub data: Option<PathBuf>,
    /// Directory of the figures [default: figures, or figures/local/quick with --quick].
    #[arg(long)]
    pub figures: Option<PathBuf>,
}

/// Runs the named experiments (all by default).
pub fn run(args: ReproduceArgs) -> Result<(), Box<dyn std::error::Error>> {
    use super::{Ctx, registry, run};
    let all = registry::names();
    // Everything that can be refused is refused before a directory is made.
    let jobs = match args.jobs {
        Some(0) => {
            return Err(evhi::error::InputError::field("jobs", 0, "at least 1").into());
        }
        Some(n) => n,
        None => std::thread::available_parallelism().map_or(2, |n| n.get()),
    };
    if args.record_times && args.quick {
        return Err(evhi::error::InputError::field(
            "record-times",
            "with --quick",
            "a full run: the committed table records the full set's times, and quick runs \
             record none",
        )
        .into());
    }
    let names: Vec<String> = if args.names.is_empty() {
        all.iter().map(|s| s.to_string()).collect()
    } else {
        let mut names: Vec<String> = vec![];
        for name in args.names {
            let group: Vec<String> = match name.as_str() {
                "paper" => paper_set().iter().map(|s| s.to_string()).collect(),
                _ => vec![name],
            };
            for n in group {
                if !names.contains(&n) {
                    names.push(n);
                }
            }
        }
        names
    };
    if args.reference.is_some() && !names.iter().any(|n| n == registry::WITH_REFERENCE) {
        return Err(evhi::error::InputError::field(
            "reference",
            args.reference.unwrap_or_default(),
            format!(
                "nothing unless {} is run (by name, in paper or in all): only Table 1 has \
                 a reference level",
                registry::WITH_REFERENCE
            ),
        )
        .into());
    }
    // The provenance names the directories where the user chose them.
    let out_flags: String = [("--data", &args.data), ("--figures", &args.figures)]
        .iter()
        .filter_map(|(flag, dir)| {
            dir.as_ref().map(|d| {
                format!(
                    " {flag} {}",
                    evhi::output::run::quote_args([d.to_string_lossy().into_owned()])
                )
            })
        })
        .collect();
    let ctx = Ctx {
        quick: args.quick,
        data: args.data.unwrap_or_else(|| quick_or(args.quick, "data")),
        figures: args
            .figures
            .unwrap_or_else(|| quick_or(args.quick, "figures")),
        verbose: true,
        progress: None,
        reference: args.reference,
        command: None,
        out_flags,
        experiment: "",
        book_table: registry::book_table,
    };
    let _lock = crate::cli::outputs::claim_outputs(&ctx)?;
    let set = if names.len() == all.len() {
        "all".to_string()
    } else if names.iter().eq(paper_set().iter()) {
        "paper".to_string()
    } else {
        names.join("+")
    };
    let total = Instant::now();
    evhi::timing::since_start();
    // One progress bar per experiment (drawn only on a terminal), with its ETA.
    let multi = indicatif::MultiProgress::new();
    if args.quiet || args.log {
        multi.set_draw_target(indicatif::ProgressDrawTarget::hidden());
    }
    let style = ProgressStyle::with_template(
        "{prefix:>10} [{bar:30}] {pos}/{len} {elapsed:>4} eta {eta:>4} {wide_msg}",
    )
    .expect("valid template")
    .progress_chars("=> ");
    let bars: std::collections::HashMap<String, ProgressBar> = names
        .iter()
        .map(|n| {
            let bar = multi.add(
                ProgressBar::new(0)
                    .with_style(style.clone())
                    .with_prefix(n.clone()),
            );
            (n.clone(), bar)
        })
        .collect();
    // The queue, costliest first (registry order among equals): a worker takes the
    // next one as it finishes its last, so that no long experiment starts last.
    let cost = |n: &String| registry::experiment(n).map_or(0.0, |e| e.cost);
    let mut queue = names.clone();
    queue.sort_by(|a, b| cost(b).total_cmp(&cost(a)));
    let queue = std::sync::Mutex::new(std::collections::VecDeque::from(queue));
    let mut results: Vec<(String, f64, Result<(), String>)> = std::thread::scope(|s| {
        let worker = || {
            let mut done = vec![];
            loop {
                let Some(name) = queue.lock().expect("reproduce queue").pop_front() else {
                    return done;
                };
                let t = Instant::now();
                let bar = bars[&name].clone();
                bar.reset();
                let ctx = Ctx {
                    progress: (!args.log).then(|| bar.clone()),
                    ..ctx.clone()
                };
                let r = run(&name, &ctx).map_err(|e| e.to_string());
                let secs = t.elapsed().as_secs_f64();
                match &r {
                    Ok(()) => bar.finish_with_message(format!("done in {secs:.1} s")),
                    Err(_) => bar.abandon_with_message(format!("FAILED after {secs:.1} s")),
                }
                done.push((name, secs, r));
            }
        };
        let handles: Vec<_> = (0..jobs.min(names.len()).max(1))
            .map(|_| s.spawn(worker))
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().expect("experiment thread"))
            .collect()
    });
    // In the order asked, whatever the order they finished in.
    results.sort_by_key(|r| names.iter().position(|n| *n == r.0));
    let mut failed = vec![];
    for (name, secs, r) in &results {
        match r {
            Ok(()) if !args.quiet => evhi::diag!("  {name}: done in {secs:.1} s"),
            Ok(()) => {}
            Err(e) => {
                evhi::diag!("  {name}: FAILED after {secs:.1} s: {e}");
                failed.push(name.clone());
            }
        }
    }
    let wall = total.elapsed().as_secs_f64();
    if !args.quiet {
        evhi::diag!(
            "reproduce: {} experiment(s) in {wall:.1} s wall",
            results.len()
        );
    }
    if failed.is_empty() && !ctx.quick && ctx.reference.is_none() {
        let file = if args.record_times {
            RECORDED_TIMES
        } else {
            LOCAL_TIMES
        };
        record_times(&ctx, file, &set, &results, wall, jobs)?;
    }
    if failed.is_empty() {
        Ok(())
    } else {
        Err(format!("experiments failed: {}", failed.join(", ")).into())
    }
}

/// The default output directory `dir`, or its git-ignored `local/quick/` for a quick
/// run (whose coarse levels must not replace the committed full-level outputs).
fn quick_or(quick: bool, dir: &str) -> PathBuf {
    if quick {
        PathBuf::from(dir).join("local").join("quick")
    } else {
        PathBuf::from(dir)
    }
}

/// The paper's own experiments: its hypotheses, Figs. 2-4 and Table 1 (the registry's
/// `paper` entries).
pub fn paper_set() -> Vec<&'static str> {
    super::registry::EXPERIMENTS
        .iter()
        .filter(|e| e.paper)
        .map(|e| e.name)
        .collect()
}

/// The committed table of wall times the book quotes; only `--record-times` writes it.
pub const RECORDED_TIMES: &str = "reproduce_times.csv";

/// Where a plain full run keeps its times: under the data directory, in `local/`,
/// which `.gitignore` names, so the main job leaves every committed file as it was.
pub const LOCAL_TIMES: &str = "local/reproduce_times.csv";

/// Keeps the wall times of this invocation in `file` (under the data directory),
/// beside those of other sets of experiments (a set's earlier rows are replaced):
/// the set, each experiment's time with the others of its set running beside it
/// (`jobs` at once), and the set's total.
fn record_times(
    ctx: &super::Ctx,
    file: &str,
    set: &str,
    results: &[(String, f64, Result<(), String>)],
    wall: f64,
    jobs: usize,
) -> Result<(), Box<dyn std::error::Error>> {
    use evhi::output::csv::{col_f64, col_str, read_csv};
    let path = ctx.data_path(file);
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    }
    let mut rows: Vec<(String, String, f64)> = vec![];
    if path.exists() {
        let old = read_csv(&path)?;
        let (sets, names, secs) = (
            col_str(&old, "set")?,
            col_str(&old, "experiment")?,
            col_f64(&old, "wall_s")?,
        );
        for i in 0..sets.len() {
            if sets[i] != set {
                rows.push((sets[i].clone(), names[i].clone(), secs[i]));
            }
        }
    }
    for (name, secs, _) in results {
        rows.push((set.to_string(), name.clone(), *secs));
    }
    rows.push((set.to_string(), "(total)".to_string(), wall));
    let t = evhi::output::csv::Table::new()
        .str("set", rows.iter().map(|r| r.0.clone()).collect())
        .str("experiment", rows.iter().map(|r| r.1.clone()).collect())
        .f64("wall_s", rows.iter().map(|r| r.2).collect());
    // The command of this invocation (the file also keeps the other sets' rows).
    let mut command = match set {
        "all" => String::new(),
        other => other.replace('+', " "),
    };
    if file == RECORDED_TIMES {
        command = format!("{command} --record-times").trim().to_string();
    }
    ctx.write_as(
        file,
        &t,
        &command,
        &format!(
            "wall seconds of `evhi reproduce` by set of experiments (all, paper = {}, or the names run); the rows of a set were measured by `evhi reproduce [SET] {}` (SET left out for all); machine: {}; {} worker(s), costliest first, each experiment timed while the others of its set run beside it",
            paper_set().join(" "),
            if file == RECORDED_TIMES { "--record-times" } else { "" },
            evhi::timing::machine(),
            jobs
        ),
    )?;
    Ok(())
}
