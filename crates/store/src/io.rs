//! Atomic writes (temporary file, then rename) and reads of Parquet tables and text files.

use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

use polars::prelude::*;

use crate::error::StoreError;
use crate::parquet_write::write_table;

/// Writes `df` to `path` atomically: a hidden temporary file in the same folder, then a rename,
/// so a reader (or a resumed run) never sees a half-written table.
///
/// Every reader sees plain types: the Arrow schema stored in the file is polars' oldest
/// compatibility level (strings as `large_string`, not the `string_view` some pyarrow compute
/// functions reject), and a float zero is written as +0.0, never −0.0 (τ = −ΣF/A of a free
/// interface would otherwise print as "-0.0").
pub fn write_parquet_atomic(df: &mut DataFrame, path: &Path) -> Result<(), StoreError> {
    let dir = path.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir).map_err(|e| StoreError::io(dir, e))?;
    let tmp = temp_path(path);
    let table = path.display().to_string();
    positive_zeros(df).map_err(|e| StoreError::table(&table, e))?;
    let arrow_schema = polars_parquet::write::schema_to_metadata_key(&df.schema().to_arrow(CompatLevel::oldest()));
    let result = (|| {
        // Buffered: the writer hands over each page and piece of metadata as its own write,
        // thousands of system calls for a table of a few megabytes.
        let file = File::create(&tmp).map_err(|e| StoreError::io(&tmp, e))?;
        let mut out = BufWriter::with_capacity(1 << 20, file);
        write_table(df, &mut out, vec![arrow_schema]).map_err(|e| StoreError::table(path.display().to_string(), e))?;
        out.into_inner().map_err(|e| StoreError::io(&tmp, e.into_error()))?;
        std::fs::rename(&tmp, path).map_err(|e| StoreError::io(path, e))
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// Turns every −0.0 of the float columns into +0.0 (x + 0.0 changes nothing else).
fn positive_zeros(df: &mut DataFrame) -> PolarsResult<()> {
    let names: Vec<(PlSmallStr, DataType)> = df
        .columns()
        .iter()
        .filter(|c| matches!(c.dtype(), DataType::Float64 | DataType::Float32))
        .map(|c| (c.name().clone(), c.dtype().clone()))
        .collect();
    for (name, dtype) in names {
        let col = df.column(&name)?;
        let fixed = if dtype == DataType::Float64 {
            let ca = col.f64()?;
            ca.iter()
                .flatten()
                .any(|v| v == 0.0 && v.is_sign_negative())
                .then(|| ca.apply_values(|v| v + 0.0).into_column())
        } else {
            let ca = col.f32()?;
            ca.iter()
                .flatten()
                .any(|v| v == 0.0 && v.is_sign_negative())
                .then(|| ca.apply_values(|v| v + 0.0).into_column())
        };
        if let Some(fixed) = fixed {
            df.replace(&name, fixed)?;
        }
    }
    Ok(())
}

/// Writes `text` to `path` atomically (temporary file, then rename).
pub fn write_text_atomic(path: &Path, text: &str) -> Result<(), StoreError> {
    write_bytes_atomic(path, text.as_bytes())
}

/// Writes `bytes` to `path` atomically (temporary file, then rename).
pub fn write_bytes_atomic(path: &Path, bytes: &[u8]) -> Result<(), StoreError> {
    let dir = path.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir).map_err(|e| StoreError::io(dir, e))?;
    let tmp = temp_path(path);
    std::fs::write(&tmp, bytes).map_err(|e| StoreError::io(&tmp, e))?;
    std::fs::rename(&tmp, path).map_err(|e| StoreError::io(path, e))
}

/// Removes the file at `path` if there is one (a missing file is not an error).
pub fn remove_file_if_present(path: &Path) -> Result<(), StoreError> {
    match std::fs::remove_file(path) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(StoreError::io(path, e)),
        _ => Ok(()),
    }
}

/// `.<name>.<pid>.tmp` beside `path` (hidden, so globs like `*.parquet` never match it).
pub fn temp_path(path: &Path) -> PathBuf {
    let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("out");
    path.with_file_name(format!(".{name}.{}.tmp", std::process::id()))
}

/// Reads a Parquet file eagerly.
pub fn read_parquet(path: &Path) -> Result<DataFrame, StoreError> {
    let file = File::open(path).map_err(|e| StoreError::io(path, e))?;
    ParquetReader::new(file).finish().map_err(|e| StoreError::table(path.display().to_string(), e))
}

/// Reads a Parquet file if it exists.
pub fn read_parquet_if_present(path: &Path) -> Result<Option<DataFrame>, StoreError> {
    if path.exists() { read_parquet(path).map(Some) } else { Ok(None) }
}

/// Whether any Parquet file is in the folder of `glob` (e.g. `dir/*.parquet`): a look at the
/// folder's names, no file opened.
pub fn any_part(glob: &Path) -> bool {
    let dir = glob.parent().unwrap_or(Path::new("."));
    std::fs::read_dir(dir)
        .map(|mut d| {
            d.any(|e| {
                e.is_ok_and(|e| {
                    !e.file_name().to_string_lossy().starts_with('.')
                        && e.path().extension().is_some_and(|x| x == "parquet")
                })
            })
        })
        .unwrap_or(false)
}

/// Lazily scans every Parquet file matching `glob` (e.g. `dir/*.parquet`) and collects them,
/// or `None` when no file matches.
pub fn scan_glob(glob: &Path) -> Result<Option<DataFrame>, StoreError> {
    scan_columns(glob, &[], None)
}

/// Lazily scans every Parquet file matching `glob`, reading only `columns` (every column when
/// empty) of the rows that pass `filter` (applied while scanning), and collects them; `None`
/// when no file matches. Each file is opened once and only the asked columns are decoded.
pub fn scan_columns(glob: &Path, columns: &[&str], filter: Option<Expr>) -> Result<Option<DataFrame>, StoreError> {
    if !any_part(glob) {
        return Ok(None);
    }
    let pattern = glob.display().to_string();
    let mut lf = LazyFrame::scan_parquet(PlRefPath::new(&pattern), ScanArgsParquet::default())
        .map_err(|e| StoreError::table(&pattern, e))?;
    if let Some(f) = filter {
        lf = lf.filter(f);
    }
    if !columns.is_empty() {
        lf = lf.select(columns.iter().map(|c| col(*c)).collect::<Vec<_>>());
    }
    lf.collect().map(Some).map_err(|e| StoreError::table(&pattern, e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn written_tables_have_plain_strings_and_no_negative_zero() {
        let dir = std::env::temp_dir().join(format!("stickslip-store-io-{}", std::process::id()));
        let path = dir.join("t.parquet");
        let mut df = df!("kind" => ["main", "minor"], "tau_pa" => [-0.0, -1.5]).unwrap();
        write_parquet_atomic(&mut df, &path).unwrap();
        let back = read_parquet(&path).unwrap();
        let tau: Vec<f64> = back.column("tau_pa").unwrap().f64().unwrap().iter().flatten().collect();
        assert_eq!(tau, [0.0, -1.5]);
        assert!(tau[0].is_sign_positive(), "a zero came back as -0.0");
        assert_eq!(back.column("kind").unwrap().dtype(), &DataType::String);
        // The Arrow schema stored in the file (what pyarrow reads; polars maps it back to its own
        // types) is that of the oldest compatibility level: large_string, not string_view.
        let meta = polars_parquet::read::read_metadata(&mut File::open(&path).unwrap()).unwrap();
        let stored = meta.key_value_metadata().as_ref().unwrap().iter().find(|kv| kv.key == "ARROW:schema").cloned();
        let key = |level| polars_parquet::write::schema_to_metadata_key(&back.schema().to_arrow(level));
        assert_eq!(stored, Some(key(CompatLevel::oldest())));
        assert_ne!(stored, Some(key(CompatLevel::newest())), "the levels do not differ for this table");
        assert_eq!(back.schema().to_arrow(CompatLevel::oldest()).get("kind").unwrap().dtype, ArrowDataType::LargeUtf8);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
