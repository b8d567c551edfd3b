//! Tables: solver records as polars frames, and atomic Parquet writes.
//!
//! Schemas (units in every column name):
//! - **series** (one row per recorded instant): `seed` u64, `time_s` f64, then one column per
//!   recorded channel ([`stickslip_solver::Channel::name`]), f64 except node counts (u32).
//! - **control** (long: one row per control node, component and instant): `seed` u64,
//!   `node` u32 (LDEM number), `component` str (`x`, `y`, `z`), `time_s` f64, then
//!   `displacement_m`, `velocity_m_s`, `acceleration_m_s2` (f64, null where not recorded).

use std::fs::File;
use std::path::{Path, PathBuf};

use polars::prelude::*;
use stickslip_solver::Records;
use stickslip_solver::scene::{Component, Kinematic};

use crate::error::AnalysisError;

/// The series table of one seed.
pub fn series_frame(seed: u64, records: &Records) -> Result<DataFrame, AnalysisError> {
    let n = records.len();
    let mut cols: Vec<Column> =
        vec![Column::new("seed".into(), vec![seed; n]), Column::new("time_s".into(), records.time_s.clone())];
    for (ch, values) in &records.channels {
        if ch.is_count() {
            cols.push(Column::new(ch.name().into(), values.iter().map(|&v| v as u32).collect::<Vec<u32>>()));
        } else {
            cols.push(Column::new(ch.name().into(), values.clone()));
        }
    }
    DataFrame::new(n, cols).map_err(|e| AnalysisError::table("series", e))
}

/// The control-node table of one seed (empty frame with the schema when nothing was recorded).
pub fn control_frame(seed: u64, records: &Records) -> Result<DataFrame, AnalysisError> {
    let n = records.len();
    let mut pairs: Vec<(u64, Component)> = records.control.iter().map(|(c, _)| (c.node.ldem(), c.component)).collect();
    pairs.sort();
    pairs.dedup();
    let quantities = [Kinematic::Displacement, Kinematic::Velocity, Kinematic::Acceleration];
    let rows = pairs.len() * n;
    let mut seed_col = Vec::with_capacity(rows);
    let mut node_col = Vec::with_capacity(rows);
    let mut comp_col: Vec<&str> = Vec::with_capacity(rows);
    let mut time_col = Vec::with_capacity(rows);
    let mut values: [Vec<Option<f64>>; 3] = [Vec::new(), Vec::new(), Vec::new()];
    for &(node, comp) in &pairs {
        seed_col.extend(std::iter::repeat_n(seed, n));
        node_col.extend(std::iter::repeat_n(node as u32, n));
        comp_col.extend(std::iter::repeat_n(comp.name(), n));
        time_col.extend_from_slice(&records.time_s);
        for (q, out) in quantities.iter().zip(values.iter_mut()) {
            let found =
                records.control.iter().find(|(c, _)| c.node.ldem() == node && c.component == comp && c.quantity == *q);
            match found {
                Some((_, v)) => out.extend(v.iter().map(|&x| Some(x))),
                None => out.extend(std::iter::repeat_n(None, n)),
            }
        }
    }
    let mut cols = vec![
        Column::new("seed".into(), seed_col),
        Column::new("node".into(), node_col),
        Column::new("component".into(), comp_col),
        Column::new("time_s".into(), time_col),
    ];
    for (q, v) in quantities.iter().zip(values) {
        cols.push(Column::new(q.column().into(), v));
    }
    DataFrame::new(rows, cols).map_err(|e| AnalysisError::table("control", e))
}

/// The skip log of one seed (one row per quasi-static jump): `seed` u64, `from_s`, `to_s` f64
/// (shear-stage times), `steps` u64 (not integrated), `next` str (`slide`, `lift`, `land`,
/// `end`: the transition predicted just after `to_s`), `node` u32 (its LDEM number, null for
/// `end`).
pub fn skips_frame(seed: u64, records: &Records) -> Result<DataFrame, AnalysisError> {
    let s = &records.skips;
    let n = s.len();
    let cols = vec![
        Column::new("seed".into(), vec![seed; n]),
        Column::new("from_s".into(), s.iter().map(|k| k.from_s).collect::<Vec<_>>()),
        Column::new("to_s".into(), s.iter().map(|k| k.to_s).collect::<Vec<_>>()),
        Column::new("steps".into(), s.iter().map(|k| k.steps).collect::<Vec<_>>()),
        Column::new("next".into(), s.iter().map(|k| k.next.kind()).collect::<Vec<_>>()),
        Column::new("node".into(), s.iter().map(|k| k.next.node().map(|id| id.ldem() as u32)).collect::<Vec<_>>()),
    ];
    DataFrame::new(n, cols).map_err(|e| AnalysisError::table("skips", e))
}

/// Writes `df` to `path` atomically: a hidden temporary file in the same folder, then a rename,
/// so a reader (or a resumed run) never sees a half-written table.
pub fn write_parquet_atomic(df: &mut DataFrame, path: &Path) -> Result<(), AnalysisError> {
    let dir = path.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir).map_err(|e| AnalysisError::io(dir, e))?;
    let tmp = temp_path(path);
    let result = (|| {
        let file = File::create(&tmp).map_err(|e| AnalysisError::io(&tmp, e))?;
        ParquetWriter::new(file)
            .with_compression(ParquetCompression::Zstd(None))
            .finish(df)
            .map_err(|e| AnalysisError::table(path.display().to_string(), e))?;
        std::fs::rename(&tmp, path).map_err(|e| AnalysisError::io(path, e))
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// Writes `text` to `path` atomically (temporary file, then rename).
pub fn write_text_atomic(path: &Path, text: &str) -> Result<(), AnalysisError> {
    let dir = path.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir).map_err(|e| AnalysisError::io(dir, e))?;
    let tmp = temp_path(path);
    std::fs::write(&tmp, text).map_err(|e| AnalysisError::io(&tmp, e))?;
    std::fs::rename(&tmp, path).map_err(|e| AnalysisError::io(path, e))
}

/// `.<name>.<pid>.tmp` beside `path` (hidden, so globs like `*.parquet` never match it).
fn temp_path(path: &Path) -> PathBuf {
    let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("out");
    path.with_file_name(format!(".{name}.{}.tmp", std::process::id()))
}

/// Reads a Parquet file eagerly.
pub fn read_parquet(path: &Path) -> Result<DataFrame, AnalysisError> {
    let file = File::open(path).map_err(|e| AnalysisError::io(path, e))?;
    ParquetReader::new(file).finish().map_err(|e| AnalysisError::table(path.display().to_string(), e))
}

/// Builds a frame column by column.
pub(crate) struct Frame {
    height: usize,
    cols: Vec<Column>,
}

impl Frame {
    pub(crate) fn new(height: usize) -> Self {
        Frame { height, cols: Vec::new() }
    }

    /// A float column; NaN (a value that does not exist, e.g. the recurrence of a first
    /// event) is written as null, so no table ever holds a NaN.
    pub(crate) fn f64(mut self, name: &str, v: Vec<f64>) -> Self {
        if v.iter().any(|x| x.is_nan()) {
            let v: Vec<Option<f64>> = v.into_iter().map(|x| (!x.is_nan()).then_some(x)).collect();
            self.cols.push(Column::new(name.into(), v));
        } else {
            self.cols.push(Column::new(name.into(), v));
        }
        self
    }

    pub(crate) fn opt_f64(mut self, name: &str, v: Vec<Option<f64>>) -> Self {
        let v: Vec<Option<f64>> = v.into_iter().map(|x| x.filter(|x| !x.is_nan())).collect();
        self.cols.push(Column::new(name.into(), v));
        self
    }

    pub(crate) fn u32(mut self, name: &str, v: Vec<u32>) -> Self {
        self.cols.push(Column::new(name.into(), v));
        self
    }

    pub(crate) fn u64(mut self, name: &str, v: Vec<u64>) -> Self {
        self.cols.push(Column::new(name.into(), v));
        self
    }

    pub(crate) fn str(mut self, name: &str, v: Vec<String>) -> Self {
        self.cols.push(Column::new(name.into(), v));
        self
    }

    pub(crate) fn finish(self, what: &str) -> Result<DataFrame, AnalysisError> {
        DataFrame::new(self.height, self.cols).map_err(|e| AnalysisError::table(what, e))
    }
}

/// Lazily scans every Parquet file matching `glob` (e.g. `dir/*.parquet`) and collects them,
/// or `None` when no file matches.
pub fn scan_glob(glob: &Path) -> Result<Option<DataFrame>, AnalysisError> {
    let pattern = glob.display().to_string();
    let dir = glob.parent().unwrap_or(Path::new("."));
    let any = std::fs::read_dir(dir)
        .map(|mut d| d.any(|e| e.is_ok_and(|e| e.path().extension().is_some_and(|x| x == "parquet"))))
        .unwrap_or(false);
    if !any {
        return Ok(None);
    }
    let lf = LazyFrame::scan_parquet(PlRefPath::new(&pattern), ScanArgsParquet::default())
        .map_err(|e| AnalysisError::table(&pattern, e))?;
    lf.collect().map(Some).map_err(|e| AnalysisError::table(&pattern, e))
}

/// Schema, row count and the first `rows` rows of a Parquet file or glob, as text.
pub fn describe(path: &Path, rows: usize) -> Result<String, AnalysisError> {
    let is_glob = path.to_string_lossy().contains('*');
    let df = if is_glob {
        scan_glob(path)?.ok_or_else(|| AnalysisError::Setup(format!("no file matches {}", path.display())))?
    } else {
        read_parquet(path)?
    };
    let head = df.head(Some(rows));
    let schema: Vec<String> = df.schema().iter().map(|(n, t)| format!("  {n}: {t}")).collect();
    Ok(format!("{}: {} rows × {} columns\n{}\n{head}", path.display(), df.height(), df.width(), schema.join("\n")))
}
