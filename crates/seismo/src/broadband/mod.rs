//! Broadband records by the hybrid method of the SCEC Broadband Platform (Graves & Pitarka 2010,
//! 2015): the deterministic rupture's motion below a crossover frequency joined to a stochastic
//! finite-fault synthesis of the same rupture above it, each taken to the station's site.
//!
//! - [`fault`]: the rupture resampled into subfaults (moment, rupture time, local rupture speed);
//! - [`stochastic`]: the stochastic synthesis of each subfault and its sum at a station;
//! - [`synth`]: one realization of a Fourier amplitude spectrum under a window (Boore 2003);
//! - [`window`]: the Saragoni–Hart envelope;
//! - [`params`]: the parameters and their Western-US defaults;
//! - [`site`]: the crust of the stochastic part and the BSSA14 site terms of both parts;
//! - [`merge`]: the matched filters that join the parts;
//! - [`hybrid`]: a station's record: both parts taken to its site and joined.
//!
//! Equations and the choices made for the lattice's homogeneous crust: docs/model.md, section
//! "Broadband records".

pub mod fault;
pub mod hybrid;
pub mod merge;
pub mod params;
pub mod site;
pub mod stochastic;
pub mod synth;
pub mod window;

pub use fault::{FaultNode, FiniteFault, Subfault};
pub use hybrid::{HybridComponent, HybridRecord, HybridSite, hybrid};
pub use merge::{Crossover, Joined, join};
pub use params::{CornerSpeed, Stochastic};
pub use site::{Crust, SiteFactor};
pub use stochastic::{Medium, Synthesis};
