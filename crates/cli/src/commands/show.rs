//! `stickslip show`: a table's schema and first rows.

use std::path::PathBuf;

use anyhow::Result;
use stickslip_store::describe::{View, describe};

/// Arguments of `stickslip show`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// A Parquet file, or a glob such as 'reports/paper/tables/events/*.parquet'.
    pub table: PathBuf,
    /// Rows to print.
    #[arg(long, default_value_t = 10)]
    pub rows: usize,
    /// Only these columns, comma separated.
    #[arg(long, value_delimiter = ',')]
    pub columns: Vec<String>,
    /// One line per column (the rows side by side): readable for wide tables.
    #[arg(long, short)]
    pub transpose: bool,
}

/// `stickslip show`.
pub fn run(a: Args) -> Result<()> {
    // SAFETY: set before any other thread exists (polars reads these when formatting).
    unsafe {
        std::env::set_var("POLARS_FMT_MAX_ROWS", a.rows.to_string());
        std::env::set_var("POLARS_FMT_MAX_COLS", "60");
        std::env::set_var("POLARS_FMT_STR_LEN", "40");
        std::env::set_var("POLARS_TABLE_WIDTH", "400");
    }
    let view = View { rows: a.rows, columns: a.columns, transpose: a.transpose };
    outln!("{}", describe(&a.table, &view)?);
    Ok(())
}
