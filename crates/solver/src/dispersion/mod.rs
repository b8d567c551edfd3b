//! Bloch (plane-wave) dispersion of the unbounded LDEM cubic-truss lattice and the highest frequency it resolves.
//!
//! # The periodic cell
//!
//! The unbounded lattice is simple cubic with period `Lc` and a two-node basis: the corner node
//! `A` at `0` and the centre node `B` at `(½, ½, ½)·Lc`, each of lumped mass `m = ρ·Lc³/2`. One
//! cell owns 14 bars ([`cell_bars`]):
//! - 3 edge bars `A → A + Lc·e_a` and 3 centre bars `B → B + Lc·e_a`, spring constant
//!   `k_n = EA_n/Lc = α·E·Lc`;
//! - 8 diagonals `B → A + (s_x, s_y, s_z)·Lc/2`, `s = ±1`, spring constant
//!   `k_d = EA_d/(Lc·√3/2) = (4δ/3)·α·E·Lc`,
//!
//! with `δ = 9ν/(4−8ν)` and `α = (9+8δ)/(18+24δ)` ([`crate::material`]).
//!
//! # Dynamical matrix
//!
//! With `u_p(R) = U_p·exp(i(k·(R + r_p) − ωt))` (the phase of the node's own position `R + r_p`),
//! a bar from node `p` to node `q` along `d` (unit vector `e = d/|d|`, spring constant `k_b`)
//! adds `k_b·eeᵀ` to the 3×3 blocks `K_pp` and `K_qq`, and `−k_b·eeᵀ·e^{+ik·d}` to `K_pq`,
//! `−k_b·eeᵀ·e^{−ik·d}` to `K_qp` (small strain: bar force `k_b·e·eᵀ(u_q − u_p)`). Then
//! `ω²·Ũ = D(k)·Ũ` with `D(k) = M^{−1/2}·K(k)·M^{−1/2}` (6×6, Hermitian, positive semi-definite)
//! and `Ũ = M^{1/2}·U`; [`dynamical_matrix`], [`bloch_spectrum`], [`bloch_modes`].
//!
//! # Branches, identified by polarisation
//!
//! Along a cube axis and along the body diagonal ([`WaveDirection`]) every 3×3 block of `D` has
//! the wave direction `n` and every direction `⊥ n` as eigenvectors, so `D` splits exactly into a
//! longitudinal 2×2 block (polarisation `n` on both nodes) and two equal transverse 2×2 blocks.
//! The P and S branches are the lower eigenvalue of the longitudinal and of the transverse block,
//! the optical branches OP and OS the upper ones ([`Branch`]); the two never cross within a block,
//! whereas P may well cross OS, which is why branches are not found by sorting the six ω.
//! Along `x` (and `y`, `z`: cubic symmetry), with `s = sin`, `c = cos`:
//!
//! ```text
//! m·ω²_S,OS = (16/3)·k_d·{s², c²}(q·Lc/4)
//! m·ω²_P,OP = 4·k_n·s²(q·Lc/2) + (8/3)·k_d·(1 ∓ c(q·Lc/2))
//! ```
//!
//! so the phase velocities are `c_S(q) = C_s·sinc(q·Lc/4)` and
//! `c_P(q)² = C_p²·[sinc²(q·Lc/2) + (4δ/9)·sinc²(q·Lc/4)]/(1 + 4δ/9)` (`sinc x = sin x / x`), with
//! the long-wave speeds `ρ·C_p² = C11 = (2k_n + ⅔k_d)/Lc = λ+2μ` and `ρ·C_s² = C44 = ⅔k_d/Lc = λ`.
//! The Brillouin zone edge along an axis is `q = π/Lc` (wavelength `2·Lc`); along the body
//! diagonal `|k| = √3·π/Lc`. At the axis zone edge S meets OS, so the lowest optical frequency
//! along an axis is `f = √2·C_s/(π·Lc) ≈ 0.450·C_s/Lc`, the top of the S branch.
//!
//! # The usable band
//!
//! `f_max(ε)` is the lowest frequency at which the phase velocity `c = ω/q` of P or S, along any
//! of the examined directions (default `x` and `z`), departs from its long-wave value `c₀` by
//! `|c/c₀ − 1| = ε` (default [`DEFAULT_TOLERANCE`] = 5 %), found by bisection on the branch
//! ([`usable_band`]). Along an axis the S branch gives the closed form
//!
//! ```text
//! sinc(x*) = 1 − ε,  x* = q*·Lc/4,  f_S = (2(1−ε)·x*/π)·C_s/Lc,  λ/Lc = π/(2x*)
//! ```
//!
//! independent of ν: for ε = 5 %, `x* = 0.5519`, `f_S = 0.3338·C_s/Lc`, `λ = 2.85·Lc`. The P
//! branch departs at a longer wavelength (`λ = 5.11·Lc` at ν = 0.2, `4.91·Lc` at ν = 0.25) but,
//! for ν < 0.2527, at a higher frequency (`0.1858·C_p/Lc = 0.372·C_s/Lc` at ν = 0.2), so S sets
//! the limit there: `f_max = 0.3338·C_s/Lc`. Above ν = 0.2527 P sets it, with `f_max·Lc/C_s`
//! between 0.292 (ν = 0.4) and 0.334. The body diagonal departs later than the axes. The lowest
//! optical frequency, `0.4502·C_s/Lc`, is also the lowest of the fourth band over the whole zone
//! (sampled, [`lowest_optical_in_zone`]). Prototype scaling at equal E and ρ: lengths and times
//! ×λ_sim, so frequencies ÷λ_sim ([`prototype_frequency_hz`]). Paper lattice (E = 2e10 Pa,
//! ρ = 2400 kg/m³, ν = 0.2, Lc = 0.1 m): `f_max` = 5078 Hz (S), optical from 6849 Hz; at
//! λ_sim = 10⁴, 0.508 Hz and 0.685 Hz.

mod band;
mod branch;
mod cell;
mod direction;
mod error;
mod lattice;
#[cfg(test)]
mod tests;

pub use band::{
    BranchLimit, DEFAULT_TOLERANCE, OpticalOnset, UsableBand, branch_point_at_frequency, departure_limit,
    lowest_optical_in_zone, optical_minimum, prototype_frequency_hz, usable_band, usable_band_along,
};
pub use branch::{BlochMode, BranchPoint, bloch_modes, branch_point, long_wave_speed_m_s};
pub use cell::{CellBar, CellNode, bloch_spectrum, cell_bars, dynamical_matrix};
pub use direction::{Branch, Polarisation, WaveDirection};
pub use error::DispersionError;
pub use lattice::LatticeMaterial;
