//! The Saragoni–Hart (1974) window that shapes a stochastic record's envelope, in the form and
//! with the constants of Boore (2003, *Pure Appl. Geophys.* 160, 635–676, eq. 24):
//!
//! ```text
//! w(t) = a·(t/t_η)^b·exp(−c·t/t_η),   b = −ε·ln η/(1 + ε·(ln ε − 1)),   c = b/ε,   a = (e/ε)^b
//! ```
//!
//! It rises from 0, peaks at 1 at `t = ε·t_η` and has fallen to `η` at `t = t_η`, where it is cut.
//! Boore's defaults, which the Broadband Platform's Graves–Pitarka method keeps: ε = 0.2,
//! η = 0.05, and `t_η = f_TW·T_gm` with `f_TW = 2` times the ground-motion duration.

use crate::error::SeismoError;

/// The shape of the Saragoni–Hart window.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SaragoniHart {
    /// Fraction of `t_η` at which the window peaks (0 < ε < 1).
    pub epsilon: f64,
    /// Level of the window at `t_η` (0 < η < 1).
    pub eta: f64,
    /// `t_η` as a multiple of the ground-motion duration (> 0).
    pub duration_factor: f64,
}

impl Default for SaragoniHart {
    /// Boore (2003): ε = 0.2, η = 0.05, `t_η = 2·T_gm`.
    fn default() -> Self {
        SaragoniHart { epsilon: 0.2, eta: 0.05, duration_factor: 2.0 }
    }
}

impl SaragoniHart {
    /// Refuses a shape outside its ranges, naming the field.
    pub fn check(&self, prefix: &str) -> Result<(), SeismoError> {
        let open01 = |name: &str, v: f64| {
            if v > 0.0 && v < 1.0 {
                Ok(())
            } else {
                Err(SeismoError::parameter(format!("{prefix}{name}"), v, "0 < value < 1"))
            }
        };
        open01("window_epsilon", self.epsilon)?;
        open01("window_eta", self.eta)?;
        if !(self.duration_factor.is_finite() && self.duration_factor > 0.0) {
            return Err(SeismoError::parameter(format!("{prefix}window_duration_factor"), self.duration_factor, "> 0"));
        }
        Ok(())
    }

    /// The exponents `(a, b, c)` of the window.
    fn coefficients(&self) -> (f64, f64, f64) {
        let (e, n) = (self.epsilon, self.eta);
        let b = -e * n.ln() / (1.0 + e * (e.ln() - 1.0));
        let c = b / e;
        let a = (std::f64::consts::E / e).powf(b);
        (a, b, c)
    }

    /// The window's samples `w(k·dt)` for `k = 0, 1, …` up to its cut at `t_η = duration_factor ·
    /// duration_s` (the last sample at or before it).
    pub fn samples(&self, duration_s: f64, dt: f64) -> Vec<f64> {
        let n = (self.duration_factor * duration_s / dt).floor() as usize + 1;
        self.envelope(duration_s, dt, n)
    }

    /// The window's first `n` samples `w(k·dt)`, not cut at `t_η` (the Platform lets it decay
    /// over the whole buffer: at `2·t_η` it is 2·10⁻⁴ of its peak with the default shape).
    pub fn envelope(&self, duration_s: f64, dt: f64, n: usize) -> Vec<f64> {
        let t_eta = self.duration_factor * duration_s;
        let (a, b, c) = self.coefficients();
        (0..n)
            .map(|k| {
                let x = k as f64 * dt / t_eta;
                if x == 0.0 { 0.0 } else { a * x.powf(b) * (-c * x).exp() }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_window_peaks_at_one_at_epsilon_and_falls_to_eta_at_its_end() {
        let w = SaragoniHart::default();
        let (a, b, c) = w.coefficients();
        let at = |x: f64| a * x.powf(b) * (-c * x).exp();
        assert!((at(0.2) - 1.0).abs() < 1e-12);
        assert!((at(1.0) - 0.05).abs() < 1e-12);
        // The peak is the maximum: the derivative b/x − c vanishes at x = b/c = ε.
        assert!(at(0.19) < 1.0 && at(0.21) < 1.0);
        // Sampled: 0 at t = 0, the last sample at t_η = 2·T_gm.
        let s = w.samples(5.0, 0.01);
        assert_eq!(s.len(), 1001);
        assert_eq!(s[0], 0.0);
        assert!((s[200] - 1.0).abs() < 1e-12 && (s[1000] - 0.05).abs() < 1e-12);
    }

    #[test]
    fn shapes_outside_their_ranges_are_refused_by_name() {
        for (w, field) in [
            (SaragoniHart { epsilon: 1.0, ..Default::default() }, "bb.window_epsilon"),
            (SaragoniHart { eta: 0.0, ..Default::default() }, "bb.window_eta"),
            (SaragoniHart { duration_factor: f64::NAN, ..Default::default() }, "bb.window_duration_factor"),
        ] {
            let e = w.check("bb.").unwrap_err().to_string();
            assert!(e.starts_with(field), "{e}");
        }
        assert!(SaragoniHart::default().check("").is_ok());
    }
}
