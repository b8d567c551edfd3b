//! Bars that crack: the bilinear softening law of the LDEM, the share of the crack area each bar
//! stands for, and the random fields on the fracture energy (docs/model.md §11).
//!
//! # The law (Rocha 1989; Riera & Rocha 1991; Kosteski, Barrios D'Ambra & Iturrioz 2012)
//!
//! Every bar of a scene with `[rupture]` follows, in its axial strain `ε`, a bilinear envelope:
//!
//! ```text
//! F(ε) = EA·ε                              0 ≤ ε ≤ εp      (elastic)
//! F(ε) = EA·εp·(εr − ε)/(εr − εp)          εp < ε < εr     (linear softening)
//! F(ε) = 0                                 ε ≥ εr          (broken)
//! εr = Kr·εp,  Kr > 1
//! ```
//!
//! The largest strain reached so far, `κ`, is the bar's only history: below it the bar unloads
//! and reloads along the damaged secant `F = F(κ)/κ · ε` toward the origin, and damage never
//! heals. In compression (`ε ≤ 0`) the bar is elastic with its undamaged stiffness, broken or not
//! (a crack closes and transmits compression). [`BarLaw::force`] is this rule; the step's
//! rupture kernel ([`crate::step::rupture`]) applies it bar by bar and is tested bit for bit
//! against it.
//!
//! **Energy.** The area under the envelope times the bar length is the energy the bar dissipates
//! to complete failure, `½·EA·εp·εr·L`. The LDEM of Riera, Rocha and Kosteski makes it equal to
//! the material's fracture energy `Gf` (J/m²) times the bar's share `A_f` (m²) of the crack area:
//!
//! ```text
//! ½·EA·εp·(Kr·εp)·L = Gf·A_f    ⇒    εp = √(2·Gf·A_f / (Kr·EA·L))
//! ```
//!
//! With secant unloading the energy dissipated once the bar has reached `κ` is linear in `κ`:
//! `D(κ) = Gf·A_f·(κ − εp)/(εr − εp)` between `εp` and `εr` ([`BarLaw::dissipated`]).
//!
//! **Equivalent-area convention (stickslip's).** A crack plane normal to a cube axis cuts, per
//! cell of area `Lc²` inside the block, one edge bar, one centre bar and four diagonals. Their
//! shares of `Lc²` are taken proportional to `EA·L` (the stiffness of a bar times its length,
//! surface reduction of docs/model.md §1.2 included):
//!
//! ```text
//! A_f = Lc² · EA_nom·L / S,     S = Σ_cell EA_nom·L = (2 + 4δ)·α·E·Lc³
//! normal bar  A_f = Lc²/(2 + 4δ)          (× 0.5 or 0.25 on the surface)
//! diagonal    A_f = δ·Lc²/(2 + 4δ)
//! ```
//!
//! so a crack crossing a section of a block normal to an axis dissipates exactly `Gf` times the
//! section's area (the reduced surface edge bars sum to the section's cells), and every bar of a
//! homogeneous lattice has the same critical strain
//! `εp = √(2·Gf / (Kr·(2 + 4δ)·α·E·Lc))` ([`Rupture::peak_strain`]). With random fields the bar's
//! own `E` and `Gf` enter: `εp,b = εp·√(ΦG/ΦE)`; `A_f` stays the geometric share (nominal
//! stiffness). Cracks along other planes cut other bars and dissipate a different energy per unit
//! area: the lattice's fracture energy is anisotropic, as in every LDEM.
//!
//! **Failure factor.** Kosteski et al. write the critical strain from a failure factor `Rf`
//! (1/√m, the inverse square root of an intrinsic flaw size) as `εp = Rf·√(Gf/((1 − ν²)·E))`, and
//! `Kr` then follows from the energy. With the convention above that `Kr` is one number for the
//! whole lattice, `Kr = 2(1 − ν²)/((2 + 4δ)·α·Lc·Rf²)` ([`kr_from_failure_factor`]); a scene gives
//! either `Kr` or `Rf`, and both must make `Kr > 1`.
//!
//! # Random fields (docs/model.md §3, §11)
//!
//! `Gf` may carry its own Weibull field of mean 1 (Eqs. 6–11), one factor `ΦG` per bar in
//! canonical bar order from its own random stream (the scene names it; streams 0 and 1 are E and
//! μ). Optionally it is correlated with the E field through a Gaussian copula: with `UE` the E
//! field's uniform and `U2` the Gf stream's, `zG = ρ·N⁻¹(UE) + √(1 − ρ²)·N⁻¹(U2)` and
//! `ΦG = Weibull⁻¹(N(zG))` — `ρ` is the correlation of the two fields' normal scores.

use rand::SeedableRng;
use rand::distr::{Distribution, Open01};
use rand::rngs::ChaCha8Rng;

use crate::error::SolverError;
use crate::geometry::{Bar, Face, Lattice};
use crate::material::{STREAM_YOUNG, UnitWeibull, truss_constants};

/// The validated `[rupture]` of a scene: the bilinear law's parameters and the fields on `Gf`.
#[derive(Clone, Debug, PartialEq)]
pub struct Rupture {
    /// Mean fracture energy Gf (J/m²).
    pub fracture_energy_j_m2: f64,
    /// `Kr = εr/εp` (> 1): given, or derived from the failure factor.
    pub kr: f64,
    /// The failure factor Rf (1/√m) the scene gave instead of `Kr`, if it did.
    pub failure_factor_per_sqrt_m: Option<f64>,
    /// Coefficient of variation of the Weibull field on Gf (0: uniform).
    pub fracture_energy_cv: f64,
    /// Random stream of the Gf field (when its CV > 0).
    pub fracture_energy_stream: Option<u64>,
    /// Correlation of the normal scores of the E and Gf fields (0: independent).
    pub young_correlation: f64,
    /// Zones whose bars stay elastic: every bar whose midpoint lies within the depth (m) of the
    /// face, e.g. the grips of a tension test or the block around a loading point.
    pub elastic_zones: Vec<(Face, f64)>,
}

impl Rupture {
    /// Whether `bar` lies in an elastic zone (its midpoint within a zone's depth of its face).
    pub fn stays_elastic(&self, lattice: &Lattice, bar: &Bar) -> bool {
        let m = lattice.bar_midpoint(bar);
        let extent = lattice.extent();
        self.elastic_zones.iter().any(|&(face, depth)| {
            let (axis, far) = face.axis();
            let distance = if far { extent[axis] - m[axis] } else { m[axis] };
            distance <= depth + 1e-9 * lattice.lc()
        })
    }

    /// Critical strain of a homogeneous bar of the lattice (any family):
    /// `εp = √(2·Gf / (Kr·(2 + 4δ)·α·E·Lc))`.
    pub fn peak_strain(&self, young_pa: f64, poisson: f64, lc_m: f64) -> f64 {
        (2.0 * self.fracture_energy_j_m2 / (self.kr * cell_stiffness_length(young_pa, poisson, lc_m) / (lc_m * lc_m)))
            .sqrt()
    }
}

/// `S = Σ_cell EA·L = (2 + 4δ)·α·E·Lc³` (N·m): the stiffness-lengths of the bars a crack plane
/// normal to an axis cuts in one interior cell (one edge bar, one centre bar, four diagonals).
pub fn cell_stiffness_length(young_pa: f64, poisson: f64, lc_m: f64) -> f64 {
    let (delta, alpha) = truss_constants(poisson);
    (2.0 + 4.0 * delta) * alpha * young_pa * lc_m.powi(3)
}

/// Crack-area share `A_f = Lc²·EA·L/S` (m²) of a bar of nominal stiffness `ea_n` (N, surface
/// reduction included, no random factor) and length `length_m`.
pub fn crack_area(ea_n: f64, length_m: f64, young_pa: f64, poisson: f64, lc_m: f64) -> f64 {
    lc_m * lc_m * ea_n * length_m / cell_stiffness_length(young_pa, poisson, lc_m)
}

/// `Kr = 2(1 − ν²)/((2 + 4δ)·α·Lc·Rf²)`: the `Kr` that makes Kosteski's
/// `εp = Rf·√(Gf/((1 − ν²)E))` dissipate `Gf·A_f` (see the module doc).
pub fn kr_from_failure_factor(rf_per_sqrt_m: f64, poisson: f64, lc_m: f64) -> f64 {
    let (delta, alpha) = truss_constants(poisson);
    2.0 * (1.0 - poisson * poisson) / ((2.0 + 4.0 * delta) * alpha * lc_m * rf_per_sqrt_m * rf_per_sqrt_m)
}

/// The largest failure factor for which `Kr > 1`: `√(2(1 − ν²)/((2 + 4δ)·α·Lc))` (1/√m).
pub fn max_failure_factor(poisson: f64, lc_m: f64) -> f64 {
    kr_from_failure_factor(1.0, poisson, lc_m).sqrt()
}

/// One bar's bilinear law in elongation units: `k` the undamaged stiffness, `peak` the
/// elongation at the peak force (`εp` times the length), `kr = εr/εp`. Any consistent units do:
/// the step kernel uses its own (for diagonals, √3 times the elongation and a third of the
/// stiffness, see [`crate::step::bars`]), in which `½·k·p²` is still the bar's strain energy.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BarLaw {
    /// Undamaged stiffness.
    pub k: f64,
    /// Elongation at the peak force.
    pub peak: f64,
    /// `εr/εp` (> 1).
    pub kr: f64,
}

/// The history of one bar: its secant stiffness in tension and the largest elongation reached.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BarHistory {
    /// Stiffness in tension now: `k` until the peak, `F(κ)/κ` after it, 0 once broken.
    pub secant: f64,
    /// Largest elongation reached beyond the peak (0 until the bar first passes it).
    pub reach: f64,
}

/// What one evaluation of the law did to a bar.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Transition {
    /// Nothing new.
    None,
    /// It passed its peak for the first time.
    Softened,
    /// It reached `εr`.
    Broke,
    /// Both in one evaluation (a jump past `εr` from the elastic range).
    SoftenedAndBroke,
}

/// The law's rule for one bar with undamaged stiffness `k0`, secant `ks`, reach `reach`, peak
/// elongation `peak`, `kr`, at elongation `p`: `(force, secant after, reach after)`. The force is
/// always `stiffness·p` with the stiffness the bar then has (`k0` in compression), which is what
/// makes the step's energy ledger exact (docs/model.md §11). Shared by [`BarLaw::force`] and the
/// step's rupture kernel, so both give the same bits.
#[inline(always)]
pub fn law_step(k0: f64, ks: f64, reach: f64, peak: f64, kr: f64, p: f64) -> (f64, f64, f64) {
    if !(p > 0.0) {
        return (k0 * p, ks, reach);
    }
    if p <= reach.max(peak) {
        return (ks * p, ks, reach);
    }
    let rupture = kr * peak;
    if p >= rupture {
        return (0.0 * p, 0.0, p);
    }
    let envelope = k0 * peak * (rupture - p) / (rupture - peak);
    let secant = envelope / p;
    (secant * p, secant, p)
}

impl BarLaw {
    /// A bar at rest.
    pub fn fresh(&self) -> BarHistory {
        BarHistory { secant: self.k, reach: 0.0 }
    }

    /// Elongation at which the force is back to zero, `kr·peak`.
    pub fn rupture(&self) -> f64 {
        self.kr * self.peak
    }

    /// The envelope `F(p)` for `p ≥ 0`.
    pub fn envelope(&self, p: f64) -> f64 {
        if p <= self.peak {
            self.k * p
        } else if p < self.rupture() {
            self.k * self.peak * (self.rupture() - p) / (self.rupture() - self.peak)
        } else {
            0.0
        }
    }

    /// Force at elongation `p` for a bar with history `h`, the history after, and what happened.
    pub fn force(&self, h: BarHistory, p: f64) -> (f64, BarHistory, Transition) {
        let (f, secant, reach) = law_step(self.k, h.secant, h.reach, self.peak, self.kr, p);
        let softened = h.secant == self.k && secant != self.k;
        let broke = h.secant != 0.0 && secant == 0.0;
        let t = match (softened, broke) {
            (false, false) => Transition::None,
            (true, false) => Transition::Softened,
            (false, true) => Transition::Broke,
            (true, true) => Transition::SoftenedAndBroke,
        };
        (f, BarHistory { secant, reach }, t)
    }

    /// Energy dissipated to complete failure, `½·k·peak·(kr·peak)` (`Gf·A_f` in real units).
    pub fn fracture_energy(&self) -> f64 {
        0.5 * self.k * self.peak * self.rupture()
    }

    /// Energy dissipated once the largest elongation reached is `reach` (closed form of the
    /// envelope's work minus the energy the secant gives back): 0 up to the peak,
    /// `fracture_energy·(reach − peak)/(rupture − peak)` while softening, all of it once broken.
    pub fn dissipated(&self, reach: f64) -> f64 {
        if reach <= self.peak {
            0.0
        } else if reach < self.rupture() {
            self.fracture_energy() * (reach - self.peak) / (self.rupture() - self.peak)
        } else {
            self.fracture_energy()
        }
    }

    /// Strain energy a bar with history `h` holds at elongation `p` (`½·stiffness·p²`).
    pub fn stored(&self, h: BarHistory, p: f64) -> f64 {
        let k = if p > 0.0 { h.secant } else { self.k };
        0.5 * k * p * p
    }
}

/// The uniform `U` in (0, 1) per bar of stream `stream` of `seed` (ChaCha8, portable).
pub fn uniforms(seed: u64, stream: u64, n: usize) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(stream);
    (0..n).map(|_| Open01.sample(&mut rng)).collect()
}

/// The standard normal distribution function `N(z) = ½·erfc(−z/√2)` (portable `libm`).
pub fn normal_cdf(z: f64) -> f64 {
    0.5 * libm::erfc(-z * std::f64::consts::FRAC_1_SQRT_2)
}

/// The standard normal quantile `N⁻¹(u)` for `u` in (0, 1): Acklam's rational approximation
/// refined by one Halley step on `N(z) − u` (relative error near 1e-15; portable `libm`).
pub fn normal_quantile(u: f64) -> f64 {
    const A: [f64; 6] = [
        -3.969683028665376e+01,
        2.209460984245205e+02,
        -2.759285104469687e+02,
        1.38357751867269e+02,
        -3.066479806614716e+01,
        2.506628277459239e+00,
    ];
    const B: [f64; 5] = [
        -5.447609879822406e+01,
        1.615858368580409e+02,
        -1.556989798598866e+02,
        6.680131188771972e+01,
        -1.328068155288572e+01,
    ];
    const C: [f64; 6] = [
        -7.784894002430293e-03,
        -3.223964580411365e-01,
        -2.400758277161838e+00,
        -2.549732539343734e+00,
        4.374664141464968e+00,
        2.938163982698783e+00,
    ];
    const D: [f64; 4] = [7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00, 3.754408661907416e+00];
    let tail = |q: f64| {
        (((((C[0] * q + C[1]) * q + C[2]) * q + C[3]) * q + C[4]) * q + C[5])
            / ((((D[0] * q + D[1]) * q + D[2]) * q + D[3]) * q + 1.0)
    };
    let z = if u < 0.02425 {
        tail(libm::sqrt(-2.0 * libm::log(u)))
    } else if u > 1.0 - 0.02425 {
        -tail(libm::sqrt(-2.0 * libm::log1p(-u)))
    } else {
        let q = u - 0.5;
        let r = q * q;
        (((((A[0] * r + A[1]) * r + A[2]) * r + A[3]) * r + A[4]) * r + A[5]) * q
            / (((((B[0] * r + B[1]) * r + B[2]) * r + B[3]) * r + B[4]) * r + 1.0)
    };
    // One Halley step: e = N(z) − u, z ← z − t/(1 + z·t/2), t = e·√(2π)·exp(z²/2).
    let e = normal_cdf(z) - u;
    let t = e * (2.0 * std::f64::consts::PI).sqrt() * libm::exp(0.5 * z * z);
    z - t / (1.0 + 0.5 * z * t)
}

/// The factor `ΦG` of the Gf field per bar (canonical order) for `seed`, or `None` when the field
/// is uniform (CV 0).
pub fn fracture_energy_factors(
    r: &Rupture,
    young_cv: f64,
    seed: u64,
    bars: usize,
) -> Result<Option<Vec<f64>>, SolverError> {
    if r.fracture_energy_cv == 0.0 {
        return Ok(None);
    }
    let stream = r.fracture_energy_stream.ok_or_else(|| {
        SolverError::Numerical("a Weibull field on the fracture energy needs its random stream".into())
    })?;
    let dist = UnitWeibull::from_cv(r.fracture_energy_cv)?;
    let own = uniforms(seed, stream, bars);
    if r.young_correlation == 0.0 || young_cv == 0.0 {
        return Ok(Some(own.into_iter().map(|u| dist.factor(u)).collect()));
    }
    let rho = r.young_correlation;
    let spread = (1.0 - rho * rho).sqrt();
    let young = uniforms(seed, STREAM_YOUNG, bars);
    Ok(Some(
        young
            .iter()
            .zip(&own)
            .map(|(&ue, &u2)| {
                let z = rho * normal_quantile(ue) + spread * normal_quantile(u2);
                // Keep U inside (0, 1) where N(z) rounds to an end.
                let u = normal_cdf(z).clamp(f64::MIN_POSITIVE, 1.0 - f64::EPSILON / 2.0);
                dist.factor(u)
            })
            .collect(),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The law's parameters for a normal bar of the paper material with Gf = 100 J/m², Kr = 3.
    fn paper_bar() -> (BarLaw, f64, f64) {
        let (e, nu, lc) = (2.0e10, 0.2, 0.1);
        let r = Rupture {
            fracture_energy_j_m2: 100.0,
            kr: 3.0,
            failure_factor_per_sqrt_m: None,
            fracture_energy_cv: 0.0,
            fracture_energy_stream: None,
            young_correlation: 0.0,
            elastic_zones: Vec::new(),
        };
        let ea = crate::material::axial_stiffness(crate::geometry::BarFamily::Edge, e, nu, lc);
        let eps_p = r.peak_strain(e, nu, lc);
        let area = crack_area(ea, lc, e, nu, lc);
        (BarLaw { k: ea / lc, peak: eps_p * lc, kr: r.kr }, r.fracture_energy_j_m2, area)
    }

    #[test]
    fn one_bar_follows_the_closed_form_through_loading_softening_unloading_reloading_and_compression() {
        let (law, _, _) = paper_bar();
        let (k, pp, pr) = (law.k, law.peak, law.rupture());
        let env = |p: f64| if p <= pp { k * p } else { k * pp * (pr - p) / (pr - pp) };
        // (elongation, closed-form force, reach after): a path through every branch.
        let kappa1 = 1.5 * pp;
        let sec1 = env(kappa1) / kappa1;
        let kappa2 = 2.2 * pp;
        let sec2 = env(kappa2) / kappa2;
        let path: Vec<(f64, f64, f64)> = vec![
            (0.4 * pp, k * 0.4 * pp, 0.0),         // elastic loading
            (pp, k * pp, 0.0),                     // the peak (reach counts beyond it)
            (kappa1, env(kappa1), kappa1),         // softening on the envelope
            (0.5 * pp, sec1 * 0.5 * pp, kappa1),   // unloading along the secant
            (0.0, 0.0, kappa1),                    // at the origin
            (-0.7 * pp, k * -0.7 * pp, kappa1),    // compression: undamaged stiffness
            (1.2 * pp, sec1 * 1.2 * pp, kappa1),   // reloading along the same secant
            (kappa1, env(kappa1), kappa1),         // back on the envelope
            (kappa2, env(kappa2), kappa2),         // softening further
            (0.3 * pp, sec2 * 0.3 * pp, kappa2),   // unloading along a flatter secant
            (pr * 1.01, 0.0, pr * 1.01),           // broken
            (0.5 * pp, 0.0, pr * 1.01),            // no force in tension
            (-0.2 * pp, k * -0.2 * pp, pr * 1.01), // a closed crack carries compression
        ];
        let mut h = law.fresh();
        for (i, &(p, want, reach)) in path.iter().enumerate() {
            let (f, next, _) = law.force(h, p);
            let scale = k * pp;
            assert!((f - want).abs() <= 1e-12 * scale, "step {i}: force {f} against {want}");
            assert_eq!(next.reach, reach, "step {i}: reach");
            h = next;
        }
    }

    #[test]
    fn the_transitions_are_reported_once() {
        let (law, _, _) = paper_bar();
        let mut h = law.fresh();
        let mut seen = Vec::new();
        for p in [0.5, 1.0, 1.2, 0.8, 1.3, 2.9, 3.2, 0.1, 3.5].map(|x| x * law.peak) {
            let (_, next, t) = law.force(h, p);
            if t != Transition::None {
                seen.push((p / law.peak, t));
            }
            h = next;
        }
        assert_eq!(seen, vec![(1.2, Transition::Softened), (3.2, Transition::Broke)]);
        let (_, _, t) = law.force(law.fresh(), 5.0 * law.peak);
        assert_eq!(t, Transition::SoftenedAndBroke);
    }

    #[test]
    fn energy_to_complete_failure_is_gf_times_the_area_share_to_round_off() {
        let (law, gf, area) = paper_bar();
        // The closed form, and the work along a strain path that passes every kink (trapezoids
        // are exact on a piecewise-linear force): load to 1.7 εp, unload to −0.3 εp, reload to
        // failure, come back to zero.
        assert!((law.fracture_energy() - gf * area).abs() <= 1e-14 * gf * area, "{}", law.fracture_energy());
        let pp = law.peak;
        let knots = [0.0, pp, 1.7 * pp, 0.0, -0.3 * pp, 0.0, 1.7 * pp, law.rupture(), 1.2 * law.rupture(), 0.0];
        let (mut h, mut f_prev, mut p_prev, mut work) = (law.fresh(), 0.0, 0.0, 0.0);
        let mut dissipated_halfway = 0.0;
        for (leg, w) in knots.windows(2).enumerate() {
            // Each leg subdivided: the trapezoid rule stays exact, the sum longer.
            for s in 1..=50 {
                let p = if s == 50 { w[1] } else { w[0] + (w[1] - w[0]) * s as f64 / 50.0 };
                let (f, next, _) = law.force(h, p);
                work += 0.5 * (f + f_prev) * (p - p_prev);
                (h, f_prev, p_prev) = (next, f, p);
            }
            if leg == 3 {
                // After the first softening excursion and a compression: work so far minus what
                // the bar holds.
                dissipated_halfway = work - law.stored(h, p_prev);
            }
        }
        let d = law.dissipated(1.7 * pp);
        assert!((dissipated_halfway - d).abs() <= 1e-12 * gf * area, "D(1.7 εp) {d}");
        assert!((d - gf * area * 0.7 / (law.kr - 1.0)).abs() <= 1e-12 * gf * area);
        assert!((work - gf * area).abs() <= 1e-12 * gf * area, "work to failure {work} against Gf·A {}", gf * area);
    }

    #[test]
    fn a_crack_across_a_section_dissipates_gf_per_unit_area() {
        // The bars a plane x = const cuts through a block of ny × nz modules: (ny+1)(nz+1) edge
        // bars along x (reduced on the surface), ny·nz centre bars and 4·ny·nz diagonals.
        use crate::geometry::{BarFamily, Dims, Direction, Lattice};
        let (e, nu, lc) = (2.0e10, 0.2, 0.1);
        for (ny, nz) in [(1, 1), (1, 5), (3, 4)] {
            let lattice = Lattice::new(Dims::new(4, ny, nz), lc);
            let x = |id| lattice.position(id)[0];
            // Plane at x = 1.25·Lc: edge bars [1, 2]·Lc, diagonals of modules i = 1 to their
            // corners at x = Lc, centre bars between modules 0 and 1.
            let cut = 1.25 * lc;
            let mut area = 0.0;
            for bar in lattice.bars() {
                let (a, b) = (x(bar.ends[0]), x(bar.ends[1]));
                if a.min(b) < cut && a.max(b) > cut {
                    let ea = bar.surface_factor * crate::material::axial_stiffness(bar.family, e, nu, lc);
                    area += crack_area(ea, bar.length_factor() * lc, e, nu, lc);
                    assert!(bar.family != BarFamily::Edge || bar.direction == Direction::Axis(0));
                }
            }
            let section = ny as f64 * nz as f64 * lc * lc;
            assert!((area - section).abs() <= 1e-14 * section, "{ny}×{nz}: shares sum to {area}, section {section}");
        }
    }

    #[test]
    fn every_family_shares_one_peak_strain_and_the_failure_factor_gives_its_kr() {
        let (e, nu, lc) = (2.0e10, 0.2, 0.1);
        let r = Rupture {
            fracture_energy_j_m2: 50.0,
            kr: 4.0,
            failure_factor_per_sqrt_m: None,
            fracture_energy_cv: 0.0,
            fracture_energy_stream: None,
            young_correlation: 0.0,
            elastic_zones: Vec::new(),
        };
        for family in [crate::geometry::BarFamily::Edge, crate::geometry::BarFamily::Diagonal] {
            let l = if family == crate::geometry::BarFamily::Diagonal { 3f64.sqrt() / 2.0 * lc } else { lc };
            let ea = crate::material::axial_stiffness(family, e, nu, lc);
            let eps = (2.0 * r.fracture_energy_j_m2 * crack_area(ea, l, e, nu, lc) / (r.kr * ea * l)).sqrt();
            assert!((eps / r.peak_strain(e, nu, lc) - 1.0).abs() < 1e-14, "{family:?}");
        }
        // Kosteski's εp = Rf·√(Gf/((1−ν²)E)) with the derived Kr is the same critical strain.
        let rf = 2.0;
        let kr = kr_from_failure_factor(rf, nu, lc);
        let with_rf = Rupture { kr, ..r.clone() };
        let kosteski = rf * (r.fracture_energy_j_m2 / ((1.0 - nu * nu) * e)).sqrt();
        assert!((with_rf.peak_strain(e, nu, lc) / kosteski - 1.0).abs() < 1e-14);
        assert!((kr_from_failure_factor(max_failure_factor(nu, lc), nu, lc) - 1.0).abs() < 1e-14);
    }

    #[test]
    fn the_normal_quantile_inverts_the_distribution_function() {
        for i in 1..2000 {
            let u = i as f64 / 2000.0;
            let z = normal_quantile(u);
            assert!((normal_cdf(z) - u).abs() < 2e-15, "u = {u}: N(N⁻¹(u)) = {}", normal_cdf(z));
        }
        for u in [1e-200, 1e-12, 1e-6, 1.0 - 1e-10] {
            let z = normal_quantile(u);
            assert!((normal_cdf(z) / u - 1.0).abs() < 1e-9, "u = {u}");
        }
        assert!(normal_quantile(0.5).abs() < 1e-16);
        assert!((normal_quantile(0.975) - 1.959963984540054).abs() < 1e-14);
    }

    #[test]
    fn the_fracture_energy_field_has_its_cv_and_its_correlation_with_e() {
        let n = 100_000;
        let r = Rupture {
            fracture_energy_j_m2: 1.0,
            kr: 3.0,
            failure_factor_per_sqrt_m: None,
            fracture_energy_cv: 0.2,
            fracture_energy_stream: Some(2),
            young_correlation: 0.0,
            elastic_zones: Vec::new(),
        };
        let g = fracture_energy_factors(&r, 0.1, 5, n).unwrap().unwrap();
        let mean = g.iter().sum::<f64>() / n as f64;
        let cv = (g.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt() / mean;
        assert!((mean - 1.0).abs() < 0.005 && (cv - 0.2).abs() < 0.005, "mean {mean}, CV {cv}");
        let ue = uniforms(5, STREAM_YOUNG, n);
        let score = |u: &[f64]| u.iter().map(|&u| normal_quantile(u)).collect::<Vec<f64>>();
        let corr = |a: &[f64], b: &[f64]| {
            let (ma, mb) = (a.iter().sum::<f64>() / n as f64, b.iter().sum::<f64>() / n as f64);
            let cov: f64 = a.iter().zip(b).map(|(x, y)| (x - ma) * (y - mb)).sum();
            let va: f64 = a.iter().map(|x| (x - ma).powi(2)).sum();
            let vb: f64 = b.iter().map(|y| (y - mb).powi(2)).sum();
            cov / (va * vb).sqrt()
        };
        let dist = UnitWeibull::from_cv(0.2).unwrap();
        // Normal scores of the Gf factors: invert the Weibull factor to its uniform first.
        let gf_scores = |g: &[f64]| -> Vec<f64> {
            g.iter()
                .map(|&f| {
                    let u = -libm::expm1(-libm::pow(f * dist.mean_divisor, dist.shape));
                    normal_quantile(u)
                })
                .collect()
        };
        assert!(corr(&score(&ue), &gf_scores(&g)).abs() < 0.01, "independent streams");
        for rho in [0.7, -0.4] {
            let g =
                fracture_energy_factors(&Rupture { young_correlation: rho, ..r.clone() }, 0.1, 5, n).unwrap().unwrap();
            let c = corr(&score(&ue), &gf_scores(&g));
            assert!((c - rho).abs() < 0.01, "ρ = {rho}: measured {c}");
        }
        let none = Rupture { fracture_energy_cv: 0.0, fracture_energy_stream: None, ..r };
        assert!(fracture_energy_factors(&none, 0.1, 5, 10).unwrap().is_none());
    }
}
