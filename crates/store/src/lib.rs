//! stickslip store: the output folder of a run.
//!
//! Owns: the folder's layout and manifest ([`layout`]); every table declared once — name, scope,
//! sort key, columns ([`schema`]) — with its writer from typed values and its typed reader
//! ([`tables`]); atomic Parquet and text writes ([`io`]); comparing two folders ([`compare`]);
//! showing a table ([`describe`]). Must not know: how the numbers are computed (the solver and
//! the seismology numerics hand it values), how seeds are scheduled, figures.
#![deny(missing_docs)]

pub mod compare;
pub mod describe;
pub mod error;
pub mod frame;
pub mod io;
pub mod layout;
pub mod schema;
pub mod tables;

pub use error::StoreError;
pub use layout::{Folder, Manifest};
pub use schema::{Scope, TableSpec};
