//! One file per subcommand: its arguments and what it does.

pub mod catalogue;
pub mod check;
pub mod compare;
pub mod cycles;
pub mod gmm;
pub mod merge;
pub mod per_seed;
pub mod pipeline;
pub mod run;
pub mod select;
pub mod show;
pub mod similarity;
pub mod spectra;
