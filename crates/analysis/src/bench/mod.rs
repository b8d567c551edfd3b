//! Benchmarks that measure the solver against itself: quasi-static skip-ahead against full
//! integration, run time against error.

pub mod accuracy;
pub mod skip;
