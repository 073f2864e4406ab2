//! CSV tables built as polars data frames.

use polars::prelude::*;
use std::path::Path;

/// One column of a table.
pub enum Col {
    F64(Vec<f64>),
    U64(Vec<u64>),
    Str(Vec<String>),
}

/// A table under construction: named columns of equal length.
#[derive(Default)]
pub struct Table {
    cols: Vec<(String, Col)>,
}

impl Table {
    pub fn new() -> Self {
        Self::default()
    }
    pub fn f64(mut self, name: &str, v: Vec<f64>) -> Self {
        self.cols.push((name.to_string(), Col::F64(v)));
        self
    }
    pub fn u64(mut self, name: &str, v: Vec<u64>) -> Self {
        self.cols.push((name.to_string(), Col::U64(v)));
        self
    }
    pub fn str(mut self, name: &str, v: Vec<String>) -> Self {
        self.cols.push((name.to_string(), Col::Str(v)));
        self
    }

    /// The table's first `k` columns.
    pub fn first(mut self, k: usize) -> Self {
        self.cols.truncate(k);
        self
    }

    /// The table as a polars frame.
    pub fn frame(&self) -> PolarsResult<DataFrame> {
        let cols = self
            .cols
            .iter()
            .map(|(n, c)| match c {
                Col::F64(v) => Column::new(n.as_str().into(), v.as_slice()),
                Col::U64(v) => Column::new(n.as_str().into(), v.as_slice()),
                Col::Str(v) => Column::new(n.as_str().into(), v.as_slice()),
            })
            .collect();
        DataFrame::new_infer_height(cols)
    }

    /// CSV text; floats are written in full (round-trip) precision.
    pub fn to_csv(&self) -> PolarsResult<Vec<u8>> {
        let mut df = self.frame()?;
        let mut buf = Vec::new();
        CsvWriter::new(&mut buf).finish(&mut df)?;
        Ok(buf)
    }

    /// Writes the table atomically; `comments` become leading `# ` lines.
    pub fn write(&self, path: &Path, comments: &[String]) -> std::io::Result<()> {
        let mut out = Vec::new();
        for c in comments {
            out.extend_from_slice(format!("# {c}\n").as_bytes());
        }
        out.extend(self.to_csv().map_err(std::io::Error::other)?);
        super::write_atomic(path, &out)
    }
}

/// Reads a CSV written by [`crate::experiments::Ctx::write`] or a run (comment lines
/// skipped).
pub fn read_csv(path: &Path) -> Result<DataFrame, super::FileError> {
    let err = |e: PolarsError| super::FileError::Table {
        path: path.display().to_string(),
        message: e.to_string(),
    };
    CsvReadOptions::default()
        .with_parse_options(CsvParseOptions::default().with_comment_prefix(Some("#")))
        .try_into_reader_with_file_path(Some(path.to_path_buf()))
        .map_err(err)?
        .finish()
        .map_err(err)
}

/// A numeric column as `f64`.
pub fn col_f64(df: &DataFrame, name: &str) -> Result<Vec<f64>, super::FileError> {
    let err = |m: String| super::FileError::Table {
        path: name.to_string(),
        message: m,
    };
    let c = df.column(name).map_err(|e| err(e.to_string()))?;
    let c = c.cast(&DataType::Float64).map_err(|e| err(e.to_string()))?;
    Ok(c.f64()
        .map_err(|e| err(e.to_string()))?
        .into_no_null_iter()
        .collect())
}

/// A column as text.
pub fn col_str(df: &DataFrame, name: &str) -> Result<Vec<String>, super::FileError> {
    let err = |m: String| super::FileError::Table {
        path: name.to_string(),
        message: m,
    };
    // As text whatever the reader inferred (`true`, `false` come back as booleans).
    let c = df.column(name).map_err(|e| err(e.to_string()))?;
    let c = c.cast(&DataType::String).map_err(|e| err(e.to_string()))?;
    let ca = c.str().map_err(|e| err(e.to_string()))?;
    Ok((0..ca.len())
        .map(|i| ca.get(i).unwrap_or("").to_string())
        .collect())
}
