//! stickslip store: the output folder of a run.
//!
//! Owns: the folder's layout and manifest ([`layout`]); every table declared once — name, scope,
//! sort key, columns and, for a per-seed table, its writer ([`spec`], listed in [`schema`]) —
//! with its typed reader ([`tables`]); writing one seed's analysis: its tables, its record files
//! in every format asked, its fault station files, `runs` last ([`seed`], [`files`]); atomic
//! Parquet and text writes ([`io`]); comparing two folders ([`compare`]); showing a table
//! ([`describe`]). Must not know: how the numbers are computed (the analysis hands it a
//! [`stickslip_analysis::SeedAnalysis`]), how seeds are scheduled, figures.
#![deny(missing_docs)]

pub mod col;
pub mod compare;
pub mod describe;
pub mod error;
pub mod files;
pub mod frame;
pub mod io;
pub mod layout;
pub mod parquet_write;
pub mod schema;
pub mod seed;
pub mod spec;
pub mod tables;

pub use error::StoreError;
pub use layout::{Folder, Manifest};
pub use spec::{Scope, SeedTable, SeedView, TableSpec};
