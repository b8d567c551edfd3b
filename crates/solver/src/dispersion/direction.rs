//! Which wave a question names: its direction of propagation (the pure-mode directions of the
//! cubic lattice), its polarisation and its branch.

use std::f64::consts::PI;
use std::fmt;

/// Direction of propagation: the pure-mode directions of the cubic lattice used here.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum WaveDirection {
    /// Along `x` (slip direction).
    X,
    /// Along `y`.
    Y,
    /// Along `z` (height).
    Z,
    /// Along the body diagonal `(1, 1, 1)/√3`.
    BodyDiagonal,
}

impl WaveDirection {
    /// Unit vector `n` of the direction.
    pub fn unit(self) -> [f64; 3] {
        match self {
            WaveDirection::X => [1.0, 0.0, 0.0],
            WaveDirection::Y => [0.0, 1.0, 0.0],
            WaveDirection::Z => [0.0, 0.0, 1.0],
            WaveDirection::BodyDiagonal => [1.0 / 3f64.sqrt(); 3],
        }
    }

    /// One transverse polarisation (a unit vector `⊥ n`; the other is `n × t`, same branch).
    pub fn transverse(self) -> [f64; 3] {
        match self {
            WaveDirection::X | WaveDirection::Z => [0.0, 1.0, 0.0],
            WaveDirection::Y => [0.0, 0.0, 1.0],
            WaveDirection::BodyDiagonal => [1.0 / 2f64.sqrt(), -1.0 / 2f64.sqrt(), 0.0],
        }
    }

    /// Wavenumber of the Brillouin-zone edge along this direction (rad/m): `π/Lc` on an axis,
    /// `√3·π/Lc` on the body diagonal (where the ray leaves the cube `|k_a| ≤ π/Lc`).
    pub fn zone_edge_rad_m(self, lc_m: f64) -> f64 {
        let n = self.unit();
        PI / (lc_m * n.iter().fold(0.0f64, |m, v| m.max(v.abs())))
    }
}

impl fmt::Display for WaveDirection {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            WaveDirection::X => "x",
            WaveDirection::Y => "y",
            WaveDirection::Z => "z",
            WaveDirection::BodyDiagonal => "[111]",
        })
    }
}

/// Polarisation of a branch.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Polarisation {
    /// Along the wave direction.
    Longitudinal,
    /// Perpendicular to the wave direction.
    Transverse,
}

/// A dispersion branch along a pure-mode direction.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Branch {
    /// Acoustic longitudinal (the P wave).
    P,
    /// Acoustic transverse (the S wave, two equal polarisations).
    S,
    /// Optical longitudinal (the two sub-lattices in antiphase at `k = 0`).
    OpticalP,
    /// Optical transverse.
    OpticalS,
}

impl Branch {
    /// Polarisation of the branch.
    pub fn polarisation(self) -> Polarisation {
        match self {
            Branch::P | Branch::OpticalP => Polarisation::Longitudinal,
            Branch::S | Branch::OpticalS => Polarisation::Transverse,
        }
    }

    /// Whether the branch is optical (non-zero frequency at `k = 0`).
    pub fn is_optical(self) -> bool {
        matches!(self, Branch::OpticalP | Branch::OpticalS)
    }
}

impl fmt::Display for Branch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Branch::P => "P",
            Branch::S => "S",
            Branch::OpticalP => "optical P",
            Branch::OpticalS => "optical S",
        })
    }
}
