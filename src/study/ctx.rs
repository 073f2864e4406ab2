//! Where and how an experiment runs: its output directories, mode, progress bar
//! and provenance, and how it writes a table (with its Markdown rendering when the
//! book shows it). The book's experiments and the studies of `evhi study` both run
//! in one; the dispatcher that runs an experiment by name fills in its name and the
//! book's table layouts.

use super::ExpError;
use crate::output::csv::Table;
use std::path::{Path, PathBuf};

/// Where and how an experiment runs.
#[derive(Debug, Clone)]
pub struct Ctx {
    /// Coarse levels for tests.
    pub quick: bool,
    /// Directory of the CSV tables.
    pub data: PathBuf,
    /// Directory of the figures.
    pub figures: PathBuf,
    /// Print progress lines on stderr (when there is no progress bar).
    pub verbose: bool,
    /// The experiment's progress bar: [`Ctx::add_units`] announces work, each
    /// [`Ctx::log`] completes one unit.
    pub progress: Option<indicatif::ProgressBar>,
    /// Table 1's reference level $n$ (`h = k = 1/n`) instead of the paper's 512;
    /// its tables are then written beside the paper's, with the level in their name.
    pub reference: Option<usize>,
    /// The command named in the provenance lines, when it is not `evhi reproduce`
    /// (a study on a user's scenario).
    pub command: Option<String>,
    /// The output flags `evhi reproduce` was given (` --data DIR --figures DIR`, each
    /// only where the user chose it), named in the provenance lines after the mode.
    pub out_flags: String,
    /// The experiment running (set by the dispatcher from the registry): its tables'
    /// provenance names it.
    pub experiment: &'static str,
    /// The Markdown layout of a table the book shows, by file name: the key columns
    /// repeated in every part, the most columns of one part and the columns'
    /// headings; `None` for a table the book does not show (no Markdown written).
    pub book_table: fn(&str) -> Option<&'static crate::output::markdown::BookTable>,
}

/// No table shown by the book: [`Ctx::book_table`] of a study or a test.
pub fn no_book_table(_: &str) -> Option<&'static crate::output::markdown::BookTable> {
    None
}

impl Ctx {
    /// A quiet context writing tables into `root/data` and figures into
    /// `root/figures` (quick or full levels), with no progress bar.
    pub fn under(root: &std::path::Path, quick: bool) -> Ctx {
        Ctx {
            quick,
            data: root.join("data"),
            figures: root.join("figures"),
            verbose: false,
            progress: None,
            reference: None,
            command: None,
            out_flags: String::new(),
            experiment: "",
            book_table: no_book_table,
        }
    }

    /// The provenance lines of a CSV: crate version, experiment, mode and the parameters.
    pub fn provenance(&self, experiment: &str, params: &str) -> Vec<String> {
        vec![
            match experiment {
                _ if self.command.is_some() => format!(
                    "produced by evhi {} `evhi {}`",
                    env!("CARGO_PKG_VERSION"),
                    self.command.as_deref().unwrap_or_default()
                ),
                _ => format!(
                    "produced by evhi {} `evhi reproduce{}{experiment}{}{}`",
                    env!("CARGO_PKG_VERSION"),
                    if experiment.is_empty() { "" } else { " " },
                    if self.quick { " --quick" } else { "" },
                    crate::output::run::one_line(&self.out_flags)
                ),
            },
            params.to_string(),
        ]
    }

    /// The path of the table `file` in the data directory.
    pub fn data_path(&self, file: &str) -> PathBuf {
        self.data.join(file)
    }

    /// The path of the figure `stem.ext` in the figures directory.
    pub fn figure_path(&self, stem: &str, ext: &str) -> PathBuf {
        self.figures.join(format!("{stem}.{ext}"))
    }

    /// Writes a table with its provenance, naming the running experiment (and, for a
    /// table the book shows, its Markdown rendering, see [`Ctx::book_table`]).
    pub fn write(&self, file: &str, table: &Table, params: &str) -> Result<PathBuf, ExpError> {
        self.write_as(file, table, self.experiment, params)
    }

    /// [`Ctx::write`] with the provenance naming `experiment` (a command's variant,
    /// such as `table1 --reference 1024`, or `bench`).
    pub fn write_as(
        &self,
        file: &str,
        table: &Table,
        experiment: &str,
        params: &str,
    ) -> Result<PathBuf, ExpError> {
        let path = self.data_path(file);
        table
            .write(&path, &self.provenance(experiment, params))
            .map_err(|e| {
                ExpError::File(crate::output::FileError::Io {
                    path: path.display().to_string(),
                    source: e,
                })
            })?;
        self.render_book_table(file)?;
        Ok(path)
    }

    /// Writes `data/<stem>.md`, the Markdown rendering of `data/<file>`, if the
    /// book shows that table ([`Ctx::book_table`]).
    pub fn render_book_table(&self, file: &str) -> Result<(), ExpError> {
        let Some(layout) = (self.book_table)(file) else {
            return Ok(());
        };
        let path = self.data_path(file);
        let text = std::fs::read_to_string(&path).map_err(|e| {
            ExpError::File(crate::output::FileError::Io {
                path: path.display().to_string(),
                source: e,
            })
        })?;
        let md = crate::output::markdown::table(
            &text,
            layout.keys,
            layout.cols,
            layout.hide,
            layout.headings,
        );
        self.write_file(&path.with_extension("md"), md.as_bytes())
    }

    /// Writes `bytes` to `path` atomically (a Markdown fragment, a report, a copied
    /// figure); the error names the path.
    pub fn write_file(&self, path: &Path, bytes: &[u8]) -> Result<(), ExpError> {
        crate::output::write_atomic(path, bytes).map_err(|e| {
            ExpError::File(crate::output::FileError::Io {
                path: path.display().to_string(),
                source: e,
            })
        })
    }

    /// Reports one finished unit of work (a run, a level, a cell).
    pub fn log(&self, msg: &str) {
        match &self.progress {
            Some(bar) => {
                bar.set_message(msg.to_string());
                bar.inc(1);
            }
            None if self.verbose => crate::diag!(
                "  [{:7.1} s] {}: {msg}",
                crate::timing::since_start(),
                self.experiment
            ),
            None => {}
        }
    }

    /// Announces `n` more units of work (calls of [`Ctx::log`]) to the progress bar.
    pub fn add_units(&self, n: usize) {
        if let Some(bar) = &self.progress {
            bar.inc_length(n as u64);
        }
    }
}
