//! Markdown renderings of the CSV tables the book shows: numbers to four
//! significant digits, wide tables split into narrower ones that repeat the key
//! columns, each column headed in words with its unit where the table gives a
//! heading for it (`wall_s` as "wall time (s)"; the CSV keeps its name), and the
//! CSV's provenance kept as an HTML comment. The CSV stays the source of truth; the
//! rendering is regenerated whenever it is written.

/// A CSV column's name and the heading the rendering gives it.
pub type Heading = (&'static str, &'static str);

/// Renders `csv` (with its `#` provenance lines) as Markdown, without the columns
/// named in `hide`. The first `keys` columns shown are repeated in every part; each part has at most `max_cols` columns. A
/// column named in `headings` is headed by its words; any other by its CSV name, in
/// code type where the table has no headings at all (a name that is already a word,
/// such as `n` or `solver`, reads as one beside headings in words).
pub fn table(
    csv: &str,
    keys: usize,
    max_cols: usize,
    hide: &[&str],
    headings: &[Heading],
) -> String {
    let mut provenance = vec![];
    let mut rows: Vec<Vec<String>> = vec![];
    for line in csv.lines() {
        if let Some(c) = line.strip_prefix('#') {
            provenance.push(c.trim().replace("--", "- -"));
        } else if !line.trim().is_empty() {
            rows.push(split(line));
        }
    }
    if let Some(header) = rows.first() {
        let keep: Vec<bool> = header.iter().map(|h| !hide.contains(&h.as_str())).collect();
        for r in &mut rows {
            let mut i = 0;
            r.retain(|_| {
                i += 1;
                keep.get(i - 1).copied().unwrap_or(true)
            });
        }
    }
    let mut out = String::new();
    if !provenance.is_empty() {
        out.push_str(&format!("<!-- {} -->\n\n", provenance.join("; ")));
    }
    let Some((header, body)) = rows.split_first() else {
        return out;
    };
    let keys = keys.min(header.len());
    let per = max_cols.saturating_sub(keys).max(1);
    let others: Vec<usize> = (keys..header.len()).collect();
    let chunks: Vec<&[usize]> = if others.is_empty() {
        vec![&[]]
    } else {
        others.chunks(per).collect()
    };
    for (part, chunk) in chunks.iter().enumerate() {
        if part > 0 {
            out.push('\n');
        }
        let cols: Vec<usize> = (0..keys).chain(chunk.iter().copied()).collect();
        let integer: Vec<bool> = cols
            .iter()
            .map(|&c| {
                body.iter().all(|r| {
                    r.get(c).is_none_or(|v| {
                        v.parse::<f64>()
                            .map(|x| !x.is_finite() || (x.fract() == 0.0 && x.abs() < 1e15))
                            .unwrap_or(true)
                    })
                })
            })
            .collect();
        // A key column (parameters such as g = 0.09) reads as given where every value
        // is short, not padded to four digits (0.09000).
        let short_key: Vec<bool> = cols
            .iter()
            .map(|&c| {
                c < keys
                    && body
                        .iter()
                        .all(|r| r.get(c).is_some_and(|v| short(v).is_some()))
            })
            .collect();
        out.push('|');
        for &c in &cols {
            match headings.iter().find(|h| h.0 == header[c]) {
                Some((_, words)) => out.push_str(&format!(" {} |", words.replace('|', "\\|"))),
                None if headings.is_empty() => out.push_str(&format!(" `{}` |", header[c])),
                None => out.push_str(&format!(" {} |", header[c])),
            }
        }
        out.push_str("\n|");
        for _ in &cols {
            out.push_str("---|");
        }
        out.push('\n');
        for r in body {
            out.push('|');
            for (i, &c) in cols.iter().enumerate() {
                let cell = r.get(c).map_or("", |s| s.as_str());
                let text = match short(cell) {
                    Some(v) if short_key[i] => v,
                    _ => number(cell, integer[i]),
                };
                out.push_str(&format!(" {text} |"));
            }
            out.push('\n');
        }
    }
    out
}

/// Splits a CSV line at commas outside double quotes.
fn split(line: &str) -> Vec<String> {
    let mut out = vec![];
    let (mut cur, mut quoted) = (String::new(), false);
    for ch in line.chars() {
        match ch {
            '"' => quoted = !quoted,
            ',' if !quoted => out.push(std::mem::take(&mut cur)),
            _ => cur.push(ch),
        }
    }
    out.push(cur);
    out
}

/// A number whose shortest decimal form has at most four significant digits, in that
/// form (0.09, 2.5, 128); `None` for anything else.
fn short(cell: &str) -> Option<String> {
    let x = cell.trim().parse::<f64>().ok().filter(|x| x.is_finite())?;
    let text = format!("{x}");
    let digits = text.trim_start_matches(['-', '0', '.']).replace('.', "");
    (!text.contains('e') && digits.trim_end_matches('0').len() <= 4 && !text.starts_with("0.0000"))
        .then_some(text)
}

/// A cell: numbers to four significant digits (integers whole, NaN as a dash),
/// anything else as text.
fn number(cell: &str, integer: bool) -> String {
    let Ok(x) = cell.trim().parse::<f64>() else {
        return cell.replace('|', "\\|");
    };
    if x.is_nan() {
        return "–".into();
    }
    if integer {
        return format!("{x:.0}");
    }
    if x == 0.0 {
        return "0".into();
    }
    let mag = x.abs().log10().floor() as i32;
    if (-3..5).contains(&mag) {
        let dec = (3 - mag).max(0) as usize;
        format!("{x:.dec$}")
    } else {
        format!("{x:.3e}")
    }
}

/// A table the book shows, as a Markdown rendering beside its CSV: the file, the key
/// columns repeated in every part, the most columns of one part (so a part fits
/// the page), the CSV's columns the rendering leaves out (an identifier the book
/// names otherwise), and the columns' headings in words.
pub struct BookTable {
    /// The CSV file's name, such as `hypotheses.csv`.
    pub file: &'static str,
    /// How many leading columns are keys, repeated in every part.
    pub keys: usize,
    /// The most columns of one part, keys included.
    pub cols: usize,
    /// CSV columns the rendering leaves out, by name.
    pub hide: &'static [&'static str],
    /// Headings in words, with units, by CSV column name (a column left out is headed
    /// by its name).
    pub headings: &'static [Heading],
}

/// A [`BookTable`] whose columns are headed by their CSV names.
pub const fn book_table(file: &'static str, keys: usize, cols: usize) -> BookTable {
    BookTable {
        file,
        keys,
        cols,
        hide: &[],
        headings: &[],
    }
}

impl BookTable {
    /// The same table without the columns `hide` in its rendering.
    pub const fn hiding(self, hide: &'static [&'static str]) -> BookTable {
        BookTable { hide, ..self }
    }
    /// The table with its columns headed by `headings`.
    pub const fn headed(self, headings: &'static [Heading]) -> BookTable {
        BookTable { headings, ..self }
    }
}

/// The table `file` among `tables`, if it is one.
pub fn layout<'a>(
    mut tables: impl Iterator<Item = &'a BookTable>,
    file: &str,
) -> Option<&'a BookTable> {
    tables.find(|t| t.file == file)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_keep_four_significant_digits() {
        assert_eq!(number("714.2857142857143", false), "714.3");
        assert_eq!(number("0.006250645", false), "0.006251");
        assert_eq!(number("3.3164307570356644e-16", false), "3.316e-16");
        assert_eq!(number("30293238.0", true), "30293238");
        assert_eq!(number("NaN", false), "–");
        assert_eq!(number("newton", false), "newton");
    }

    #[test]
    fn wide_tables_split_and_repeat_their_keys() {
        let csv = "# made by a test\na,b,c,d\nx,1.5,2,3\ny,2.25,3,4\n";
        let md = table(csv, 1, 3, &[], &[]);
        assert!(md.starts_with("<!-- made by a test -->"));
        assert!(md.contains("| `a` | `b` | `c` |"), "{md}");
        assert!(md.contains("| `a` | `d` |"), "{md}");
        assert!(md.contains("| y | 2.250 | 3 |"), "{md}");
    }

    #[test]
    fn short_keys_read_as_given() {
        let md = table("g,limit\n0.1,39\n0.09,47\n", 1, 6, &[], &[]);
        assert!(
            md.contains("| 0.1 | 39 |") && md.contains("| 0.09 | 47 |"),
            "{md}"
        );
        // A value column keeps its four digits; a key column with a long value keeps
        // the rule throughout.
        let md = table("g,err\n0.123456,0.5\n0.5,0.5\n", 1, 6, &[], &[]);
        assert!(
            md.contains("| 0.1235 | 0.5000 |") && md.contains("| 0.5000 |"),
            "{md}"
        );
    }

    #[test]
    fn hidden_columns_are_left_out() {
        let md = table("name,letter,x\nregimes,(b),1.5\n", 1, 6, &["name"], &[]);
        assert!(md.contains("| `letter` | `x` |"), "{md}");
        assert!(
            md.contains("| (b) | 1.500 |") && !md.contains("regimes"),
            "{md}"
        );
    }

    #[test]
    fn headings_in_words_replace_the_names_they_give() {
        let csv = "n,wall_s,x\n4,0.5,1\n";
        let md = table(
            csv,
            1,
            3,
            &[],
            &[("wall_s", "wall time (s)"), ("n", "n = 1/h")],
        );
        assert!(md.contains("| n = 1/h | wall time (s) | x |"), "{md}");
        assert!(!md.contains("wall_s"), "{md}");
    }

    #[test]
    fn quoted_commas_stay_in_their_cell() {
        assert_eq!(split("1,\"a, b\",2"), vec!["1", "a, b", "2"]);
    }
}
