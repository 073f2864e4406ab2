//! CSV tables built as polars data frames.

use polars::prelude::*;
use std::path::Path;

/// One column of a table.
pub enum Col {
    /// Floating-point values, written in full (round-trip) precision.
    F64(Vec<f64>),
    /// Unsigned integers.
    U64(Vec<u64>),
    /// Text.
    Str(Vec<String>),
}

/// A table under construction: named columns of equal length.
#[derive(Default)]
pub struct Table {
    cols: Vec<(String, Col)>,
}

impl Table {
    /// A table with no columns.
    pub fn new() -> Self {
        Self::default()
    }
    /// The table with a column `name` of floats appended.
    pub fn f64(mut self, name: &str, v: Vec<f64>) -> Self {
        self.cols.push((name.to_string(), Col::F64(v)));
        self
    }
    /// The table with a column `name` of unsigned integers appended.
    pub fn u64(mut self, name: &str, v: Vec<u64>) -> Self {
        self.cols.push((name.to_string(), Col::U64(v)));
        self
    }
    /// The table with a column `name` of text appended.
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

/// A table as evhi writes it, read as text: `#` lines skipped, a header line, then rows
/// of as many fields as the header has columns (a field in double quotes may hold
/// commas, and a doubled quote for a quote). Each row keeps its line number in the
/// file, so that an error names the file, the line and the column.
#[derive(Debug, Clone)]
pub struct Text {
    /// The file, as errors name it.
    pub path: String,
    /// The header's line number (from 1) and its column names.
    pub header: (usize, Vec<String>),
    /// Each data row: its line number and its fields.
    pub rows: Vec<(usize, Vec<String>)>,
}

impl Text {
    /// The table at `path`, refused (file and line named) where it is not UTF-8 text,
    /// has no header, names a column twice, leaves a quote open, holds a control
    /// character, or has a row whose fields are not one per column.
    pub fn read(path: &Path) -> Result<Text, super::FileError> {
        let bytes = std::fs::read(path).map_err(|e| super::FileError::Io {
            path: path.display().to_string(),
            source: e,
        })?;
        Text::parse(&bytes, &path.display().to_string())
    }

    /// The table in `bytes`, read from `path` (for the errors); see [`Text::read`].
    pub fn parse(bytes: &[u8], path: &str) -> Result<Text, super::FileError> {
        let at = |line: usize, message: String| super::FileError::Table {
            path: format!("{path}:{line}"),
            message,
        };
        let text = std::str::from_utf8(bytes).map_err(|e| {
            let line = 1 + bytes[..e.valid_up_to()]
                .iter()
                .filter(|&&b| b == b'\n')
                .count();
            at(line, "not UTF-8 text, as a table evhi writes is".into())
        })?;
        // A byte-order mark (some editors save one) is not part of the first name.
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let mut header: Option<(usize, Vec<String>)> = None;
        let mut rows = vec![];
        for (i, line) in text.split('\n').enumerate() {
            let line = line.strip_suffix('\r').unwrap_or(line);
            if line.starts_with('#') || line.is_empty() {
                continue;
            }
            let fields =
                split(line).ok_or_else(|| at(i + 1, "a double quote is not closed".into()))?;
            let names = header.as_ref().map(|h| h.1.as_slice()).unwrap_or(&fields);
            for (k, f) in fields.iter().enumerate() {
                // A line separator breaks the line for other readers (Python's
                // `splitlines`) as a control character does.
                if let Some(c) = f.chars().find(|&c| crate::error::breaks_line(c)) {
                    let column = names.get(k).map_or(format!("field {}", k + 1), |n| {
                        format!("column `{}`", n.escape_debug())
                    });
                    return Err(at(
                        i + 1,
                        format!(
                            "{column} holds `{}`, with the control or line-breaking character \
                             U+{:04X}, not text a table holds",
                            shown(f),
                            c as u32
                        ),
                    ));
                }
            }
            match &header {
                None => {
                    // A deleted header line makes the first row the header: names that
                    // are mostly numbers.
                    let numbers = fields.iter().filter(|f| f.parse::<f64>().is_ok()).count();
                    if numbers > 0 && 2 * numbers >= fields.len() {
                        return Err(at(
                            i + 1,
                            format!(
                                "{numbers} of its {} fields are numbers where the header's \
                                 column names belong: the header line seems to be missing",
                                fields.len()
                            ),
                        ));
                    }
                    if let Some((k, name)) =
                        (fields.iter().enumerate()).find(|(k, name)| fields[..*k].contains(name))
                    {
                        return Err(at(
                            i + 1,
                            format!(
                                "column `{}` appears twice in the header (field {})",
                                shown(name),
                                k + 1
                            ),
                        ));
                    }
                    header = Some((i + 1, fields));
                }
                Some((hl, names)) => {
                    if fields.len() != names.len() {
                        let (n, m) = (fields.len(), names.len());
                        let which = if n > m {
                            format!("field {}, `{}`, has no column", m + 1, shown(&fields[m]))
                        } else {
                            format!("column `{}` (field {}) has no value", names[n], n + 1)
                        };
                        return Err(at(
                            i + 1,
                            format!("{n} fields where the header (line {hl}) has {m}: {which}"),
                        ));
                    }
                    rows.push((i + 1, fields));
                }
            }
        }
        let header = header.ok_or_else(|| at(1, "no header line".into()))?;
        Ok(Text {
            path: path.to_string(),
            header,
            rows,
        })
    }

    /// The index of column `name`; refused (the file and its columns named) if the
    /// header has no such column.
    pub fn column(&self, name: &str) -> Result<usize, super::FileError> {
        let (line, names) = &self.header;
        names
            .iter()
            .position(|c| c == name)
            .ok_or_else(|| no_column(&format!("{}:{line}", self.path), name, names.iter()))
    }

    /// The error of a cell: the file and line of row `row`, the column, the value and
    /// what the column allows.
    pub fn bad_cell(&self, row: usize, column: &str, allowed: &str) -> super::FileError {
        let (line, fields) = &self.rows[row];
        let value = self
            .column(column)
            .ok()
            .and_then(|k| fields.get(k))
            .map_or("", |v| v.as_str());
        super::FileError::Table {
            path: format!("{}:{line}", self.path),
            message: format!("column `{column}` holds `{}`, not {allowed}", shown(value)),
        }
    }
}

/// A cell as an error echoes it: escaped, a number in exponent notation where its
/// decimal form is long, and cut to 60 characters (a cell may hold megabytes).
pub fn shown(cell: &str) -> String {
    let v = match cell.parse::<f64>() {
        Ok(x) if x.is_finite() && cell.len() > 24 => format!("{x:e}"),
        _ => cell.escape_debug().to_string(),
    };
    match v.char_indices().nth(60) {
        None => v,
        Some((i, _)) => format!("{}… ({} characters)", &v[..i], cell.chars().count()),
    }
}

/// The error of a table whose header (at `at`, file and line) lacks column `name`.
fn no_column<'a>(
    at: &str,
    name: &str,
    names: impl Iterator<Item = &'a String>,
) -> super::FileError {
    let names: Vec<&String> = names.collect();
    let names: Vec<String> = names.iter().map(|n| format!("`{}`", shown(n))).collect();
    super::FileError::Table {
        path: at.to_string(),
        message: format!(
            "no column `{name}`; the header has {}",
            if names.is_empty() {
                "none".to_string()
            } else {
                names.join(", ")
            }
        ),
    }
}

/// The fields of a CSV line: split at the commas outside double quotes, the quotes
/// dropped and a doubled quote inside them read as one; `None` if a quote is not closed.
pub fn split(line: &str) -> Option<Vec<String>> {
    let (mut out, mut cell, mut quoted) = (vec![], String::new(), false);
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '"' if quoted && chars.peek() == Some(&'"') => {
                cell.push('"');
                chars.next();
            }
            '"' => quoted = !quoted,
            ',' if !quoted => out.push(std::mem::take(&mut cell)),
            _ => cell.push(c),
        }
    }
    out.push(cell);
    (!quoted).then_some(out)
}

/// A table read by [`read_csv`]: the data frame, and the file it came from, so that
/// an error about a column names the file.
pub struct Frame {
    /// The table's contents.
    pub df: DataFrame,
    /// The file, as errors name it.
    pub path: String,
}

impl std::ops::Deref for Frame {
    type Target = DataFrame;
    fn deref(&self) -> &DataFrame {
        &self.df
    }
}

/// Reads a CSV written by [`crate::study::Ctx::write`] or a run (comment lines
/// skipped). The text is checked first ([`Text::read`]), so that a row of the wrong
/// length is named by its line; what the table library still cannot read is said
/// without its advice, which is for its Python users.
pub fn read_csv(path: &Path) -> Result<Frame, super::FileError> {
    Text::read(path)?;
    let read = |infer: Option<usize>| {
        CsvReadOptions::default()
            .with_infer_schema_length(infer)
            .with_parse_options(CsvParseOptions::default().with_comment_prefix(Some("#")))
            .try_into_reader_with_file_path(Some(path.to_path_buf()))
            .and_then(|r| r.finish())
    };
    // A column of numbers whose later rows hold text: read every row as the column's
    // kind is inferred from all of them, and let the column's reader name the cell.
    let df = read(Some(100))
        .or_else(|_| read(None))
        .map_err(|e| super::FileError::Table {
            path: path.display().to_string(),
            message: format!(
                "not a table evhi can read ({})",
                e.to_string().lines().next().unwrap_or_default()
            ),
        })?;
    Ok(Frame {
        df,
        path: path.display().to_string(),
    })
}

/// The column `name` of `df`; refused, the file and its columns named, if it has none.
fn column<'a>(df: &'a Frame, name: &str) -> Result<&'a Column, super::FileError> {
    df.df.column(name).map_err(|_| {
        let names: Vec<String> = df
            .get_column_names()
            .iter()
            .map(|c| c.to_string())
            .collect();
        no_column(&df.path, name, names.iter())
    })
}

/// A numeric column as `f64`; a cell that is not a number is refused, with its file,
/// line and value.
pub fn col_f64(df: &Frame, name: &str) -> Result<Vec<f64>, super::FileError> {
    let err = |m: String| super::FileError::Table {
        path: df.path.clone(),
        message: format!("column `{name}`: {m}"),
    };
    let c = column(df, name)?;
    let c = c.cast(&DataType::Float64).map_err(|e| err(e.to_string()))?;
    let c = c.f64().map_err(|e| err(e.to_string()))?;
    if let Some(row) = (c.null_count() > 0)
        .then(|| (0..c.len()).find(|&i| c.get(i).is_none()))
        .flatten()
    {
        // Read again, only to name the cell as the file has it.
        return Err(match Text::read(Path::new(&df.path)) {
            Ok(t) if row < t.rows.len() => t.bad_cell(row, name, "a number"),
            _ => err(format!("row {} is not a number", row + 1)),
        });
    }
    Ok(c.into_no_null_iter().collect())
}

/// A column as text.
pub fn col_str(df: &Frame, name: &str) -> Result<Vec<String>, super::FileError> {
    let err = |m: String| super::FileError::Table {
        path: df.path.clone(),
        message: format!("column `{name}`: {m}"),
    };
    // As text whatever the reader inferred (`true`, `false` come back as booleans).
    let c = column(df, name)?;
    let c = c.cast(&DataType::String).map_err(|e| err(e.to_string()))?;
    let ca = c.str().map_err(|e| err(e.to_string()))?;
    Ok((0..ca.len())
        .map(|i| ca.get(i).unwrap_or("").to_string())
        .collect())
}
