//! Similarity scaling of model events to a prototype fault (docs/model.md §9, the paper's "Similarity
//! analysis").
//!
//! Same material in model and prototype and geometric similarity: one ratio `λ = L_p/L_m`.
//! - time: `t_p = λ·t_m`;
//! - recurrence: `Δt_p = Δt_m·λ·(u̇_m/u̇_p)` (Eq. 14);
//! - seismic moment, **paper convention** (Eq. 15 as printed): `M0 = Δσ·L_p·A_p·λ` with
//!   `A_p = λ²·A_m`. The extra factor λ is not a dimensionally consistent moment scaling; it is
//!   kept because it is what the paper's M = 6.77 rests on;
//! - seismic moment, **consistent convention**: `M0 = Δσ·L_p·A_p`;
//! - Riera magnitude (Eq. 16): `M = 0.6536·(log10 M0[dyne·cm] − 15.51 − 0.483·X)`, X = 0
//!   interplate, 1 intraplate;
//! - moment magnitude (Hanks & Kanamori): `Mw = (2/3)·log10 M0[dyne·cm] − 10.7`.
//!
//! Accelerograms scale with lengths ×λ, times ×λ, velocities ×1, accelerations ÷λ.

/// Seconds in a Julian year.
pub const SECONDS_PER_YEAR: f64 = 365.25 * 86_400.0;
/// 1 N·m in dyne·cm.
pub const DYNE_CM_PER_N_M: f64 = 1e7;

/// Which model area stands for the rupture area in the moment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AreaChoice {
    /// The whole contact area `nx·Lc × ny·Lc` (the paper's choice).
    Contact,
    /// The event's rupture area (peak sliding nodes' share of the contact area).
    Rupture,
}

/// The prototype fault (the pipeline's `[similarity]` section).
#[derive(Clone, Debug, PartialEq)]
pub struct SimilarityParams {
    /// Prototype fault length L_p in metres. Default 1.0e4 (10 km, λ = 10⁴ for the paper block).
    pub prototype_length_m: f64,
    /// Prototype loading rate u̇_p in m/s. Default 3.17e-10 (1 cm/yr).
    pub prototype_rate_m_s: f64,
    /// Model area used for the moment: `"contact"` (default, the paper's) or `"rupture"`.
    pub area: AreaChoice,
}

impl Default for SimilarityParams {
    fn default() -> Self {
        SimilarityParams { prototype_length_m: 1.0e4, prototype_rate_m_s: 3.17e-10, area: AreaChoice::Contact }
    }
}

/// Inputs for one event at model scale.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModelEvent {
    /// Mean stress drop Δσ (Pa).
    pub stress_drop_pa: f64,
    /// Model fault length L_m (m).
    pub model_length_m: f64,
    /// Model rupture area A_m (m²).
    pub model_area_m2: f64,
    /// Event duration (s), if known.
    pub duration_s: Option<f64>,
    /// Recurrence since the previous main shock (s), if known.
    pub recurrence_s: Option<f64>,
    /// Model loading rate u̇_m (m/s).
    pub model_rate_m_s: f64,
}

/// The event at prototype scale.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scaled {
    /// λ = L_p/L_m.
    pub lambda: f64,
    /// Prototype rupture area A_p = λ²·A_m (m²).
    pub prototype_area_m2: f64,
    /// λ·duration (s).
    pub prototype_duration_s: Option<f64>,
    /// Recurrence at prototype scale (s).
    pub prototype_recurrence_s: Option<f64>,
    /// M0 by the paper's Eq. 15 (dyne·cm).
    pub m0_paper_dyne_cm: f64,
    /// M0 = Δσ·L_p·A_p (dyne·cm).
    pub m0_consistent_dyne_cm: f64,
}

/// Riera et al.'s magnitude `0.6536·(log10 M0 − 15.51 − 0.483·X)`, M0 in dyne·cm.
pub fn riera_magnitude(m0_dyne_cm: f64, intraplate: bool) -> f64 {
    let x = if intraplate { 1.0 } else { 0.0 };
    0.6536 * (m0_dyne_cm.log10() - 15.51 - 0.483 * x)
}

/// Hanks & Kanamori's moment magnitude `(2/3)·log10 M0 − 10.7`, M0 in dyne·cm.
pub fn moment_magnitude(m0_dyne_cm: f64) -> f64 {
    2.0 / 3.0 * m0_dyne_cm.log10() - 10.7
}

/// The magnitudes of one scaled event, each from one of its two moments.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Magnitudes {
    /// Riera's magnitude of the paper's moment, interplate (X = 0).
    pub riera_paper_interplate: f64,
    /// Riera's magnitude of the paper's moment, intraplate (X = 1).
    pub riera_paper_intraplate: f64,
    /// Riera's magnitude of the consistent moment, interplate.
    pub riera_consistent_interplate: f64,
    /// Riera's magnitude of the consistent moment, intraplate.
    pub riera_consistent_intraplate: f64,
    /// Moment magnitude of the paper's moment.
    pub mw_paper: f64,
    /// Moment magnitude of the consistent moment.
    pub mw_consistent: f64,
}

impl Scaled {
    /// The event's magnitudes by both conventions.
    pub fn magnitudes(&self) -> Magnitudes {
        let (paper, consistent) = (self.m0_paper_dyne_cm, self.m0_consistent_dyne_cm);
        Magnitudes {
            riera_paper_interplate: riera_magnitude(paper, false),
            riera_paper_intraplate: riera_magnitude(paper, true),
            riera_consistent_interplate: riera_magnitude(consistent, false),
            riera_consistent_intraplate: riera_magnitude(consistent, true),
            mw_paper: moment_magnitude(paper),
            mw_consistent: moment_magnitude(consistent),
        }
    }
}

/// Scales one model event with the prototype of `p`.
pub fn scale(e: &ModelEvent, p: &SimilarityParams) -> Scaled {
    let lambda = p.prototype_length_m / e.model_length_m;
    let area_p = lambda * lambda * e.model_area_m2;
    let m0 = e.stress_drop_pa * p.prototype_length_m * area_p;
    Scaled {
        lambda,
        prototype_area_m2: area_p,
        prototype_duration_s: e.duration_s.map(|d| lambda * d),
        prototype_recurrence_s: e.recurrence_s.map(|r| r * lambda * e.model_rate_m_s / p.prototype_rate_m_s),
        m0_paper_dyne_cm: m0 * lambda * DYNE_CM_PER_N_M,
        m0_consistent_dyne_cm: m0 * DYNE_CM_PER_N_M,
    }
}

/// The similarity rules of a record and of everything computed from it (docs/model.md §9.5),
/// applied to values computed once at model scale: times and periods ×λ, frequencies ÷λ,
/// lengths and displacements ×λ (SD, PGD), velocities ×1 (PSV, PGV, the Fourier amplitude of an
/// acceleration), accelerations ÷λ (PSA, PGA), Arias intensity ÷λ. They hold exactly for the
/// numerics of this crate (the oscillator `ü + 2ξωu̇ + ω²u = −a` is the same equation in scaled
/// time), so the prototype's spectra, RotD, Fourier spectra and intensity measures are derived,
/// not computed again; `tests/similarity.rs` shows each derived value equal, to round-off, to
/// the one computed directly from the record scaled.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RecordScale {
    /// λ (1 at model scale).
    pub lambda: f64,
}

impl RecordScale {
    /// A time, duration, period or sampling interval (s).
    pub fn time(self, t: f64) -> f64 {
        t * self.lambda
    }

    /// A frequency (Hz).
    pub fn frequency(self, f: f64) -> f64 {
        f / self.lambda
    }

    /// A length or displacement (m): positions, SD, PGD.
    pub fn length(self, x: f64) -> f64 {
        x * self.lambda
    }

    /// A velocity (m/s): PSV, PGV, and the Fourier amplitude |X|·Δt of an acceleration.
    pub fn velocity(self, v: f64) -> f64 {
        v
    }

    /// An acceleration (m/s²): samples, PSA, PGA.
    pub fn acceleration(self, a: f64) -> f64 {
        a / self.lambda
    }

    /// Arias intensity `π/(2g)·∫a²dt` (m/s).
    pub fn arias(self, ia: f64) -> f64 {
        ia / self.lambda
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The paper's S2 of seed 200 (docs/model.md §9).
    fn paper_s2() -> Scaled {
        let e = ModelEvent {
            stress_drop_pa: 7600.0,
            model_length_m: 1.0,
            model_area_m2: 0.1,
            duration_s: Some(0.0021),
            recurrence_s: Some(0.0258),
            model_rate_m_s: 1.1e-4,
        };
        scale(&e, &SimilarityParams::default())
    }

    #[test]
    fn paper_convention_gives_the_papers_moment_and_magnitude() {
        let s = paper_s2();
        assert!((s.lambda - 1e4).abs() < 1e-9);
        assert!((s.m0_paper_dyne_cm / 7.6e25 - 1.0).abs() < 1e-12, "{}", s.m0_paper_dyne_cm);
        let m = riera_magnitude(s.m0_paper_dyne_cm, false);
        assert!((m - 6.778).abs() < 0.01, "M = {m}");
        assert!((riera_magnitude(s.m0_paper_dyne_cm, true) - (m - 0.6536 * 0.483)).abs() < 1e-12);
    }

    #[test]
    fn consistent_convention_and_moment_magnitude() {
        let s = paper_s2();
        assert!((s.m0_consistent_dyne_cm / 7.6e21 - 1.0).abs() < 1e-12);
        assert!((riera_magnitude(s.m0_consistent_dyne_cm, false) - 4.16).abs() < 0.01);
        assert!((moment_magnitude(7.6e25) - (2.0 / 3.0 * 7.6e25f64.log10() - 10.7)).abs() < 1e-12);
    }

    #[test]
    fn time_and_recurrence_scale_like_the_paper() {
        let s = paper_s2();
        assert!((s.prototype_duration_s.unwrap() - 21.0).abs() < 1e-9);
        let years = s.prototype_recurrence_s.unwrap() / SECONDS_PER_YEAR;
        assert!((years - 2.83).abs() < 0.02, "recurrence {years} years");
        assert!((s.prototype_area_m2 - 1e7).abs() < 1e-3, "10 km × 1 km");
    }
}
