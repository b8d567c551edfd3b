//! Writers (typed values → frames) and readers (frames → typed columns) of every table of
//! [`crate::schema`].

pub mod catalogue;
pub mod cracks;
pub mod events;
pub mod fronts;
pub mod records;
pub mod runs;
pub mod series;
pub mod stats;
