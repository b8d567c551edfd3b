//! Atomic writes (temporary file, then rename) and reads of Parquet tables and text files.

use std::fs::File;
use std::path::{Path, PathBuf};

use polars::prelude::*;

use crate::error::StoreError;

/// Writes `df` to `path` atomically: a hidden temporary file in the same folder, then a rename,
/// so a reader (or a resumed run) never sees a half-written table.
pub fn write_parquet_atomic(df: &mut DataFrame, path: &Path) -> Result<(), StoreError> {
    let dir = path.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir).map_err(|e| StoreError::io(dir, e))?;
    let tmp = temp_path(path);
    let result = (|| {
        let file = File::create(&tmp).map_err(|e| StoreError::io(&tmp, e))?;
        ParquetWriter::new(file)
            .with_compression(ParquetCompression::Zstd(None))
            .finish(df)
            .map_err(|e| StoreError::table(path.display().to_string(), e))?;
        std::fs::rename(&tmp, path).map_err(|e| StoreError::io(path, e))
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
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

/// Lazily scans every Parquet file matching `glob` (e.g. `dir/*.parquet`) and collects them,
/// or `None` when no file matches.
pub fn scan_glob(glob: &Path) -> Result<Option<DataFrame>, StoreError> {
    let pattern = glob.display().to_string();
    let dir = glob.parent().unwrap_or(Path::new("."));
    let any = std::fs::read_dir(dir)
        .map(|mut d| d.any(|e| e.is_ok_and(|e| e.path().extension().is_some_and(|x| x == "parquet"))))
        .unwrap_or(false);
    if !any {
        return Ok(None);
    }
    let lf = LazyFrame::scan_parquet(PlRefPath::new(&pattern), ScanArgsParquet::default())
        .map_err(|e| StoreError::table(&pattern, e))?;
    lf.collect().map(Some).map_err(|e| StoreError::table(&pattern, e))
}
