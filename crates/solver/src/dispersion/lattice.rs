//! The homogeneous lattice whose dispersion is computed: material and module side, validated, and
//! the truss constants, masses and long-wave speeds that follow from them.

use crate::dispersion::error::{DispersionError, positive, refuse};
use crate::geometry::BarFamily;
use crate::material;

/// The homogeneous lattice: material and module side, validated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LatticeMaterial {
    young_pa: f64,
    poisson: f64,
    density_kg_m3: f64,
    lc_m: f64,
}

impl LatticeMaterial {
    /// Young's modulus `E` (Pa), Poisson's ratio `ν` (`0 < ν < 0.5`), density `ρ` (kg/m³) and
    /// module side `Lc` (m); refuses non-finite or out-of-range values, naming the parameter.
    pub fn new(young_pa: f64, poisson: f64, density_kg_m3: f64, lc_m: f64) -> Result<Self, DispersionError> {
        positive("young_pa", young_pa, "Pa")?;
        if !(poisson > 0.0 && poisson < 0.5) {
            return Err(refuse("poisson", poisson, "0 < poisson < 0.5"));
        }
        positive("density_kg_m3", density_kg_m3, "kg/m³")?;
        positive("lc_m", lc_m, "m")?;
        Ok(LatticeMaterial { young_pa, poisson, density_kg_m3, lc_m })
    }

    /// Young's modulus `E` (Pa).
    pub fn young_pa(&self) -> f64 {
        self.young_pa
    }

    /// Poisson's ratio `ν`.
    pub fn poisson(&self) -> f64 {
        self.poisson
    }

    /// Density `ρ` (kg/m³).
    pub fn density_kg_m3(&self) -> f64 {
        self.density_kg_m3
    }

    /// Module side `Lc` (m).
    pub fn lc_m(&self) -> f64 {
        self.lc_m
    }

    /// The cubic-truss constants `(δ, α)`: `δ = 9ν/(4−8ν)`, `α = (9+8δ)/(18+24δ)`
    /// ([`material::truss_constants`]).
    pub fn truss_constants(&self) -> (f64, f64) {
        material::truss_constants(self.poisson)
    }

    /// Spring constant `k_n = EA_n/Lc = α·E·Lc` (N/m) of an edge or centre bar.
    pub fn normal_bar_stiffness_n_m(&self) -> f64 {
        material::axial_stiffness(BarFamily::Edge, self.young_pa, self.poisson, self.lc_m) / self.lc_m
    }

    /// Spring constant `k_d = EA_d/(Lc·√3/2) = (4δ/3)·α·E·Lc` (N/m) of a diagonal.
    pub fn diagonal_bar_stiffness_n_m(&self) -> f64 {
        material::axial_stiffness(BarFamily::Diagonal, self.young_pa, self.poisson, self.lc_m)
            / (0.5 * 3f64.sqrt() * self.lc_m)
    }

    /// Lumped mass `ρ·Lc³/2` (kg) of either node of the cell (an interior corner or a centre).
    pub fn node_mass_kg(&self) -> f64 {
        0.5 * self.density_kg_m3 * self.lc_m.powi(3)
    }

    /// The elastic constants `(C11, C12, C44)` (Pa) of affine strain: `λ+2μ`, `λ`, `λ`
    /// ([`material::lattice_elastic_constants`]).
    pub fn elastic_constants_pa(&self) -> (f64, f64, f64) {
        material::lattice_elastic_constants(self.young_pa, self.poisson)
    }

    /// Long-wave speeds along a cube axis `(C_p, C_s) = (√(C11/ρ), √(C44/ρ))` (m/s).
    pub fn long_wave_speeds_m_s(&self) -> (f64, f64) {
        let (c11, _, c44) = self.elastic_constants_pa();
        ((c11 / self.density_kg_m3).sqrt(), (c44 / self.density_kg_m3).sqrt())
    }
}
