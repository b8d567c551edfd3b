//! A table as text for a terminal: schema, size and the first rows, optionally only some columns
//! or transposed (one line per column) for wide tables.

use std::path::Path;

use polars::prelude::*;

use crate::error::StoreError;
use crate::io::{read_parquet, scan_glob};

/// How to show a table.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct View {
    /// Rows to show.
    pub rows: usize,
    /// Only these columns (all when empty).
    pub columns: Vec<String>,
    /// One line per column, the rows side by side.
    pub transpose: bool,
}

/// Schema, row count and the first rows of a Parquet file or glob, as text.
pub fn describe(path: &Path, view: &View) -> Result<String, StoreError> {
    let is_glob = path.to_string_lossy().contains('*');
    let df = if is_glob {
        scan_glob(path)?.ok_or_else(|| StoreError::NotAnOutput {
            path: path.to_path_buf(),
            what: "no file matches this pattern".into(),
        })?
    } else {
        read_parquet(path)?
    };
    let table = path.display().to_string();
    let df = if view.columns.is_empty() {
        df
    } else {
        let names = df.get_column_names().iter().map(|s| s.to_string()).collect::<Vec<_>>();
        for c in &view.columns {
            if !names.contains(c) {
                return Err(StoreError::Corrupt {
                    path: path.to_path_buf(),
                    what: format!("no column {c:?}; the columns are: {}", names.join(", ")),
                });
            }
        }
        df.select(view.columns.iter().map(|s| s.as_str())).map_err(|e| StoreError::table(&table, e))?
    };
    let schema: Vec<String> = df.schema().iter().map(|(n, t)| format!("  {n}: {t}")).collect();
    let head = df.head(Some(view.rows));
    let body =
        if view.transpose { transposed(&head).map_err(|e| StoreError::table(&table, e))? } else { format!("{head}") };
    Ok(format!("{}: {} rows × {} columns\n{}\n{body}", path.display(), df.height(), df.width(), schema.join("\n")))
}

/// One line per column: its name, then the values of the rows, each row's values in an aligned
/// column.
fn transposed(df: &DataFrame) -> PolarsResult<String> {
    let width = df.get_column_names().iter().map(|n| n.chars().count()).max().unwrap_or(0);
    let cells: Vec<Vec<String>> = df
        .columns()
        .iter()
        .map(|c| {
            (0..df.height())
                .map(|i| c.get(i).map(|v| format!("{v}").trim_matches('"').to_string()).unwrap_or_default())
                .collect()
        })
        .collect();
    let widths: Vec<usize> =
        (0..df.height()).map(|i| cells.iter().map(|r| r[i].chars().count()).max().unwrap_or(0)).collect();
    let mut out = String::new();
    for (c, row) in df.columns().iter().zip(&cells) {
        let mut line = format!("{:<width$}", c.name().as_str());
        for (v, w) in row.iter().zip(&widths) {
            line.push_str(&format!("  {v:<w$}"));
        }
        out.push_str(line.trim_end());
        out.push('\n');
    }
    Ok(out)
}
