//! The output folder of a pipeline run, and its manifest.
//!
//! ```text
//! <out>/manifest.toml                      pipeline name and hash of the results in this folder
//! <out>/pipeline.toml                      the pipeline file as run
//! <out>/tables/<table>/seed-<seed>.parquet one part per seed of each per-seed table
//! <out>/tables/<table>.parquet             gathered tables and statistics across seeds
//! <out>/records/…                          record files (AT2, SAC, CSV), model and prototype scale
//! <out>/set/…                              a set matched to a design spectrum: its records and table
//! <out>/figures/*.png, <out>/index.html    the report
//! <out>/fault_stations/seed<seed>/…        fault station files (SEAS layout)
//! <out>/inputs/<field>/<file>              copies of the files the pipeline read (a friction grid…)
//! <out>/shards/shard-<k>-of-<n>.toml       which shards of a sharded run started here
//! <out>/checkpoints/seed-<seed>[.rank-<r>-of-<n>].ckpt  a seed's checkpoint while it runs
//! ```
//! `<seed>` is written with ten digits (`seed-0000000123.parquet`) so the parts sort by seed.

use std::path::{Path, PathBuf};

use crate::error::StoreError;
use crate::io::write_text_atomic;
use crate::schema::{TableSpec, seed_tables};

/// The name of the manifest file.
pub const MANIFEST: &str = "manifest.toml";

/// An output folder.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Folder {
    root: PathBuf,
}

impl Folder {
    /// The folder at `root` (it need not exist yet).
    pub fn new(root: impl Into<PathBuf>) -> Self {
        Folder { root: root.into() }
    }

    /// Its root.
    pub fn root(&self) -> &Path {
        &self.root
    }

    /// `<out>/tables`.
    pub fn tables(&self) -> PathBuf {
        self.root.join("tables")
    }

    /// Path of a seed's part of `table`.
    pub fn part(&self, table: &TableSpec, seed: u64) -> PathBuf {
        self.tables().join(table.name).join(format!("seed-{seed:010}.parquet"))
    }

    /// Glob of the parts of `table`.
    pub fn part_glob(&self, table: &TableSpec) -> PathBuf {
        self.tables().join(table.name).join("*.parquet")
    }

    /// Path of a gathered table.
    pub fn gathered(&self, table: &TableSpec) -> PathBuf {
        self.tables().join(format!("{}.parquet", table.name))
    }

    /// The manifest.
    pub fn manifest(&self) -> PathBuf {
        self.root.join(MANIFEST)
    }

    /// The copy of the pipeline file.
    pub fn pipeline_copy(&self) -> PathBuf {
        self.root.join("pipeline.toml")
    }

    /// The record files (AT2, SAC, CSV).
    pub fn records_dir(&self) -> PathBuf {
        self.root.join("records")
    }

    /// A running seed's checkpoint (docs/model.md §19): one per seed on one process, one per
    /// rank when the seed is split over `ranks` MPI ranks. Removed once the seed is written.
    pub fn checkpoint(&self, seed: u64, rank: usize, ranks: usize) -> PathBuf {
        let name = if ranks > 1 {
            format!("seed-{seed:010}.rank-{rank}-of-{ranks}.ckpt")
        } else {
            format!("seed-{seed:010}.ckpt")
        };
        self.root.join("checkpoints").join(name)
    }

    /// The fault station files (SEAS layout), one folder per seed.
    pub fn fault_stations_dir(&self, seed: u64) -> PathBuf {
        self.root.join("fault_stations").join(format!("seed{seed}"))
    }

    /// A matched set: its scaled record files, table and figure.
    pub fn set_dir(&self) -> PathBuf {
        self.root.join("set")
    }

    /// Copies of the files the pipeline read, `inputs/<field>/<file>`.
    pub fn inputs_dir(&self) -> PathBuf {
        self.root.join("inputs")
    }

    /// The marks of a sharded run: one file per shard that started here.
    pub fn shards_dir(&self) -> PathBuf {
        self.root.join("shards")
    }

    /// Removes every result of an earlier run — tables, record files, fault stations, the set,
    /// figures, the page, shard marks, input copies, the MiniSEED station records, the inventory
    /// and the QuakeML catalogue — so nothing of it survives or is linked.
    /// The manifest and the pipeline copy are left for the caller to overwrite.
    pub fn discard_results(&self) -> Result<(), StoreError> {
        for dir in [
            self.tables(),
            self.records_dir(),
            self.root.join("fault_stations"),
            self.set_dir(),
            self.figures(),
            self.shards_dir(),
            self.inputs_dir(),
            self.root.join("mseed"),
            self.root.join("checkpoints"),
        ] {
            match std::fs::remove_dir_all(&dir) {
                Ok(()) => {}
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
                Err(e) => return Err(StoreError::io(&dir, e)),
            }
        }
        for file in [self.index(), self.root.join("stations.xml"), self.root.join("catalogue.xml")] {
            crate::io::remove_file_if_present(&file)?;
        }
        Ok(())
    }

    /// The figures.
    pub fn figures(&self) -> PathBuf {
        self.root.join("figures")
    }

    /// The report page.
    pub fn index(&self) -> PathBuf {
        self.root.join("index.html")
    }

    /// Whether `seed` has finished here (its `runs` part, written last, exists).
    pub fn is_finished(&self, seed: u64) -> bool {
        self.part(&crate::schema::RUNS, seed).exists()
    }

    /// The manifest, if the folder has one.
    pub fn read_manifest(&self) -> Result<Option<Manifest>, StoreError> {
        let path = self.manifest();
        if !path.exists() {
            return Ok(None);
        }
        let text = std::fs::read_to_string(&path).map_err(|e| StoreError::io(&path, e))?;
        let table: toml::Table =
            toml::from_str(&text).map_err(|e| StoreError::Corrupt { path: path.clone(), what: e.to_string() })?;
        let get = |k: &str| table.get(k).and_then(|v| v.as_str()).map(str::to_string);
        match (get("name"), get("pipeline_hash")) {
            (Some(name), Some(hash)) => Ok(Some(Manifest { name, pipeline_hash: hash })),
            _ => Err(StoreError::Corrupt { path, what: "expected name and pipeline_hash".into() }),
        }
    }

    /// Writes the manifest.
    pub fn write_manifest(&self, m: &Manifest) -> Result<(), StoreError> {
        let text = format!(
            "# Written by stickslip {}: every table in this folder comes from this pipeline.\nname = {:?}\npipeline_hash = {:?}\n",
            env!("CARGO_PKG_VERSION"),
            m.name,
            m.pipeline_hash
        );
        write_text_atomic(&self.manifest(), &text)
    }

    /// Refuses a folder that is not the output of a pipeline run (no such folder, or no manifest).
    pub fn require_output(&self) -> Result<Manifest, StoreError> {
        if !self.root.is_dir() {
            return Err(StoreError::NotAnOutput { path: self.root.clone(), what: "no such folder".into() });
        }
        self.read_manifest()?.ok_or_else(|| StoreError::NotAnOutput {
            path: self.root.clone(),
            what: format!("no {MANIFEST}: not the output folder of a stickslip pipeline"),
        })
    }

    /// Removes the hidden temporary files a killed writer left for `seeds` (only those: another
    /// process may be writing other seeds into the same folder), in the per-seed tables and the
    /// accelerogram folder.
    pub fn remove_stale_temporaries(&self, seeds: &[u64]) -> Result<(), StoreError> {
        let prefixes: std::collections::HashSet<String> =
            seeds.iter().map(|s| format!(".seed-{s:010}.parquet.")).collect();
        for table in seed_tables() {
            let dir = self.tables().join(table.name);
            let Ok(entries) = std::fs::read_dir(&dir) else { continue };
            for file in entries.flatten() {
                let name = file.file_name().to_string_lossy().into_owned();
                if name.ends_with(".tmp") && name.rfind(".parquet.").is_some_and(|i| prefixes.contains(&name[..i + 9]))
                {
                    std::fs::remove_file(file.path()).map_err(|e| StoreError::io(&file.path(), e))?;
                }
            }
        }
        // Record files: `.<pipeline>_seed<seed>_….<ext>.<pid>.tmp`.
        if let Ok(entries) = std::fs::read_dir(self.records_dir()) {
            let seeds: std::collections::HashSet<u64> = seeds.iter().copied().collect();
            for file in entries.flatten() {
                let name = file.file_name().to_string_lossy().into_owned();
                let seed = name.split("_seed").nth(1).and_then(|r| r.split('_').next()).and_then(|s| s.parse().ok());
                if name.starts_with('.') && name.ends_with(".tmp") && seed.is_some_and(|s| seeds.contains(&s)) {
                    std::fs::remove_file(file.path()).map_err(|e| StoreError::io(&file.path(), e))?;
                }
            }
        }
        Ok(())
    }
}

/// What `manifest.toml` says.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Manifest {
    /// Pipeline name.
    pub name: String,
    /// Hash of the pipeline every table here comes from.
    pub pipeline_hash: String,
}
